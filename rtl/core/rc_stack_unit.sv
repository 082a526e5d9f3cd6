// rc_stack_unit: the pop unit and the per-thread traversal stacks (docs/architecture.md, "Pop
// unit"): pops a thread's stack, culls the popped entry's rays against their best hits, and sends
// the thread's new current entry where it goes next; it also routes every packet's first entry.
//
// Contract
// - Stack: thread t's entry at depth k (1 .. StackDepth: the stack depth after its push) is kept
//   in slot {t, k mod StackDepth} of one block RAM (rc_ram). push_* (the traversal decision,
//   from registers) writes it at the clock edge ending its cycle. A thread pops only after its
//   push has been written: a thread's pop request comes at least a cycle after its last push.
// - Pop requests: a thread waits for the pop unit (popq_o[t], a register) from a request until
//   this unit picks it. Requests: req_tr_* (the traversal decision), req_nr_* (the node port's
//   error response), req_lf_i (leaves that have finished, one bit per thread), and the unit's own
//   re-pops (below). Every request is for a thread in no other unit's hands, at most one each.
// - A pop: the waiting threads are picked round robin (rc_rr_pick), one a cycle while the two
//   output queues have room for every pop in flight and no start waits. In the next cycle the
//   thread's error flag (through the one-hot pick) and stack depth (read by its number: sp_rd_*)
//   decide: an error or an empty stack ends its walk (done_valid_o, to shading); otherwise the
//   depth goes down by one (sp_pop_*), the top entry and the thread's best t (bt_*, the hit
//   store's per-thread copy, gated with the hit bits sampled at the same edge) are read, and
//   each ray r of the entry stays active only if le(tmin_r, best_t_r) (the format's compare) and,
//   in a shadow packet (shadow_i, rc_thread_ctrl's kind bits, through the one-hot pick), the ray
//   has no hit: any hit ends a shadow ray. (A shadow ray without a hit has best t = its limit,
//   rc::trace_packet(); set-up ended its interval there, so every entry's tmin is below it and
//   the compare with +inf gives the same.) An entry left with no ray is a culled pop: the thread
//   asks to pop again.
// - Start (valid/ready, from ray set-up): a packet's first entry. It takes the routing stage when
//   no pop result does and the output queues have room (start_ready_o, from registers: the cull
//   compare's valid and the room flag); while one waits, no pop is picked, so it waits at most
//   the pop pipeline's depth once there is room.
// - Routing (walk_route, walk_err of rc_pkg) of a popped or started entry with rays: an inner node
//   goes with its thread and stack depth into the traversal queue (trav_*: valid/ready, from a
//   queue of TravQDepth); a leaf with triangles into the leaf queue (leaf_*, LeafQDepth); an
//   empty leaf to a pop again; a node whose checks fail raises its error bits (err_*) and asks to
//   pop (which then ends the walk).
// - Latency: pick to routing 6 cycles (choice register, its index, block RAM read, fabric
//   register, cull compare, routing register), routing to queue 1.
// - Counters (perf_*): pops, culled pops, failed packets (a walk that ends with an error), leaf
//   visits and empty leaves of the routed entries.
// - Parameters: Threads, StackDepth (a power of two, at most rc_pkg::KdtreeStackDepth);
//   Secondary: 1 = the shadow cull above, 0 = none (shadow_i not read).
// - Reset: rst_ni (active low, asynchronous) clears the requests and the pipeline's valid bits.
module rc_stack_unit #(
  parameter int unsigned Threads     = rc_pkg::CoreThreads,
  parameter int unsigned StackDepth  = rc_pkg::KdtreeStackDepth,
  parameter bit          Secondary   = 1'b1,
  parameter int unsigned TravQDepth  = 16,
  parameter int unsigned LeafQDepth  = 16,
  // Derived (do not override).
  parameter int unsigned W           = rc_pkg::CoreFpW,
  parameter int unsigned ThrW        = (Threads > 1) ? $clog2(Threads) : 1,
  parameter int unsigned SpW         = rc_pkg::CoreSpBits
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,

  // Pushes (the traversal decision).
  input  logic                       push_valid_i,
  input  logic [ThrW-1:0]            push_thr_i,
  input  logic [SpW-1:0]             push_sp_i,      // the depth after the push
  input  rc_pkg::walk_entry_t        push_entry_i,

  // Pop requests.
  input  logic                       req_tr_valid_i,
  input  logic [ThrW-1:0]            req_tr_thr_i,
  input  logic                       req_nr_valid_i,
  input  logic [ThrW-1:0]            req_nr_thr_i,
  input  logic [Threads-1:0]         req_lf_i,

  // The threads' control state (rc_thread_ctrl).
  input  logic [Threads-1:0]         err_i,
  input  logic [Threads*4-1:0]       hit_i,
  input  logic [Threads-1:0]         shadow_i,
  output logic [ThrW-1:0]            sp_rd_thr_o,    // the picked thread's depth, read
  input  logic [SpW-1:0]             sp_rd_i,
  output logic                       sp_pop_valid_o, // a pop: the thread's new depth
  output logic [ThrW-1:0]            sp_pop_thr_o,
  output logic [SpW-1:0]             sp_pop_sp_o,
  output logic                       err_valid_o,
  output logic [ThrW-1:0]            err_thr_o,
  output logic [2:0]                 err_bits_o,

  // The best t of a thread's rays (the hit store's per-thread copy; 2 cycles).
  output logic                       bt_re_o,
  output logic [ThrW-1:0]            bt_thr_o,
  input  logic [4*W-1:0]             bt_i,

  // Start entries.
  input  logic                       start_valid_i,
  output logic                       start_ready_o,
  input  rc_pkg::walk_item_t         start_item_i,

  // Outputs.
  output logic                       trav_valid_o,
  input  logic                       trav_ready_i,
  output rc_pkg::walk_item_t         trav_item_o,
  output logic                       leaf_valid_o,
  input  logic                       leaf_ready_i,
  output rc_pkg::leaf_item_t         leaf_item_o,
  output logic                       done_valid_o,
  output logic [ThrW-1:0]            done_thr_o,

  // Debug and counter events.
  output logic [Threads-1:0]         popq_o,
  output logic                       pick_valid_o,   // a thread picked (the choice register)
  output logic [ThrW-1:0]            pick_thr_o,
  output logic                       route_valid_o,  // an entry routed (the routing register)
  output logic [ThrW-1:0]            route_thr_o,
  output logic                       perf_pop_o,
  output logic                       perf_culled_o,
  output logic                       perf_failed_o,
  output logic                       perf_leaf_o,
  output logic                       perf_empty_o
);

  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned SpIdxW = (StackDepth > 1) ? $clog2(StackDepth) : 1;
  localparam int unsigned StkAW  = ThrW + SpIdxW;
  localparam int unsigned TqCntW = $clog2(TravQDepth + 1);
  localparam int unsigned LqCntW = $clog2(LeafQDepth + 1);
  // Entries that may reach a queue after the count the room flag saw: a pick writes its queue 7
  // cycles later (choice register, its index, block RAM read, fabric register, compare, routing
  // register, queue write) and the count shows a write a cycle after it, and the flag is a cycle
  // older: so the picks of 9 cycles, and a start.
  localparam int unsigned InFlight = 10;

  if (Threads < 1 || StackDepth < 1 || (1 << SpIdxW) != StackDepth ||
      StackDepth > rc_pkg::KdtreeStackDepth || TravQDepth < InFlight + 2 ||
      LeafQDepth < InFlight + 2) begin : g_param_check
    $error("rc_stack_unit: need StackDepth a power of two <= KdtreeStackDepth and queues deeper than the pops in flight");
  end

  ///////////////////
  // Pop requests  //
  ///////////////////

  logic [Threads-1:0] popq_q, g_pp, pk_hot_q, gpp_q, own_req;
  logic               pp_any, pp_take, pk_v_q, pp_v_q, pick_room_q;
  logic [ThrW-1:0]    pp_thr_q, pk_thr_q, pp_idx;

  // The pick's one-hot grant and its thread number are registered (pk): the per-thread reads
  // after the pick start at flip-flops.
  rc_rr_pick #(
    .N   (Threads),
    .IdxW(ThrW)
  ) u_pick_pop (
    .clk_i,
    .rst_ni,
    .req_i  (popq_q & ~pk_hot_q),
    .take_i (pp_take),
    .valid_o(pp_any),
    .idx_o  (pp_idx),
    .grant_o(g_pp)
  );
  // A thread is picked while both queues have room for every pop in flight (their counts as they
  // were a cycle ago: pick_room_q) and no start waits for the routing stage.
  assign pp_take = pp_any & pick_room_q & ~start_valid_i;

  logic [Threads-1:0] h_tr, h_nr;
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_tr (.valid_i(req_tr_valid_i), .idx_i(req_tr_thr_i),
                                                 .hot_o(h_tr));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_nr (.valid_i(req_nr_valid_i), .idx_i(req_nr_thr_i),
                                                 .hot_o(h_nr));
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      popq_q <= '0;
    end else begin
      popq_q <= (popq_q & ~pk_hot_q) | h_tr | h_nr | req_lf_i | own_req;
    end
  end
  assign popq_o = popq_q;

  ////////////////////
  // Pop pipeline   //
  ////////////////////

  logic               pp_end, pop0_v_q, pop1_v_q, pop2_v;
  logic [SpW-1:0]     pp_sp;
  logic               pp_err, pp_sh, pop0_sh_q, pop1_sh_q, pop2_sh_q;
  logic [3:0]         pp_hit;
  logic [ThrW-1:0]    pop0_thr_q, pop1_thr_q, pop2_thr_q;
  logic [SpW-1:0]     pop0_sp_q, pop1_sp_q, pop2_sp_q;
  logic [3:0]         pop0_hit_q, pop1_hit_q, pop2_hit_q, pop2_nn_q;
  rc_pkg::walk_entry_t stk_rd, pop2_entry_q;
  logic [3:0]         pop_le, pop_cmp_v;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pk_v_q   <= 1'b0;
      pk_hot_q <= '0;
      pk_thr_q <= '0;
      pp_v_q   <= 1'b0;
      pp_thr_q <= '0;
      gpp_q    <= '0;
      pop0_v_q <= 1'b0;
      pop1_v_q <= 1'b0;
    end else begin
      pk_v_q   <= pp_take;
      pk_hot_q <= pp_take ? g_pp : '0;
      pk_thr_q <= pp_idx;
      pp_v_q   <= pk_v_q;
      pp_thr_q <= pk_thr_q;
      gpp_q    <= pk_hot_q;
      pop0_v_q <= pp_v_q & ~pp_end;
      pop1_v_q <= pop0_v_q;
    end
  end

  // The picked thread's error flag and hit bits through its one-hot grant, its depth read by its
  // number (rc_thread_ctrl's distributed RAMs); an error or an empty stack ends the walk.
  for (genvar r = 0; r < 4; r++) begin : g_pp_hit
    logic [Threads-1:0] hit_r;
    for (genvar t = 0; t < Threads; t++) begin : g_t
      assign hit_r[t] = hit_i[t*4 + r];
    end
    assign pp_hit[r] = |(gpp_q & hit_r);   // a reduction OR: balanced, not a chain
  end
  // The depth is read a cycle early, by the choice's thread number (pk), and registered: the
  // distributed RAMs' read and the end decision are in different cycles. (A thread's depth was
  // written at least a cycle before its pop request, so before the read.)
  logic [SpW-1:0] pp_sp_q;
  always_ff @(posedge clk_i) pp_sp_q <= sp_rd_i;
  assign pp_err      = |(gpp_q & err_i);
  assign pp_sh       = Secondary & |(gpp_q & shadow_i);
  assign sp_rd_thr_o = pk_thr_q;
  assign pp_sp       = pp_sp_q;
  assign pp_end      = pp_err | (pp_sp == '0);

  // The new depth and an ended walk leave through registers (the thread's next pop, or its shading,
  // comes many cycles later).
  logic            sp_pop_v_q, done_v_q;
  logic [ThrW-1:0] sp_pop_thr_q;
  logic [SpW-1:0]  sp_pop_sp_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sp_pop_v_q <= 1'b0;
      done_v_q   <= 1'b0;
    end else begin
      sp_pop_v_q <= pp_v_q & ~pp_end;
      done_v_q   <= pp_v_q & pp_end;
    end
  end
  always_ff @(posedge clk_i) begin
    sp_pop_thr_q <= pp_thr_q;
    sp_pop_sp_q  <= pp_sp - SpW'(1);
  end
  assign sp_pop_valid_o = sp_pop_v_q;
  assign sp_pop_thr_o   = sp_pop_thr_q;
  assign sp_pop_sp_o    = sp_pop_sp_q;
  assign done_valid_o   = done_v_q;
  assign done_thr_o     = sp_pop_thr_q;

  // The stack and the best t are read at every registered pick (an ended walk leaves its read
  // unused), so the read enables are flip-flops.
  logic [4*W-1:0] bt_rd;
  rc_ram #(
    .Width (262),
    .Depth ((1 << ThrW) * StackDepth),
    .OutReg(1'b1)
  ) u_stack (
    .clk_i,
    .we_i   (push_valid_i),
    .waddr_i(StkAW'({push_thr_i, push_sp_i[SpIdxW-1:0]})),
    .wdata_i(push_entry_i),
    .re_i   (pp_v_q),
    .raddr_i(StkAW'({pp_thr_q, pp_sp[SpIdxW-1:0]})),
    .rdata_o(stk_rd)
  );
  assign bt_re_o  = pp_v_q;
  assign bt_thr_o = pp_thr_q;
  assign bt_rd    = bt_i;

  always_ff @(posedge clk_i) begin
    pop0_thr_q <= pp_thr_q;
    pop0_sp_q  <= pp_sp - SpW'(1);
    pop0_hit_q <= pp_hit;
    pop0_sh_q  <= pp_sh;
    pop1_sh_q  <= pop0_sh_q;
    pop2_sh_q  <= pop1_sh_q;
    pop1_thr_q <= pop0_thr_q;
    pop1_sp_q  <= pop0_sp_q;
    pop1_hit_q <= pop0_hit_q;
    pop2_thr_q <= pop1_thr_q;
    pop2_sp_q  <= pop1_sp_q;
    pop2_entry_q <= stk_rd;
  end

  // Cull: ray r stays only if le(tmin_r, best_t_r), where a ray without a hit has best t = +inf.
  // The compare takes the best t as read, and the hit bit selects after its register: le(tmin,
  // +inf) is "tmin is not NaN" (pop2_nn_q), so no select sits in front of the compare's
  // magnitude compare (run 50 seed 2: pop1_hit_q through that select and the compare, -1.84 ns).
  for (genvar r = 0; r < 4; r++) begin : g_pop_cmp
    logic unused_lt, unused_eq, cmp_le;
    logic [W-1:0] unused_min, unused_max, tmin;
    assign tmin = stk_rd.tmin[r];
    always_ff @(posedge clk_i) begin
      pop2_hit_q[r] <= pop1_hit_q[r];
      pop2_nn_q[r]  <= ~((&tmin[W-2 -: rc_pkg::Fp24ExpW]) & (|tmin[rc_pkg::Fp24FracW-1:0]));
    end
    rc_fp_cmp #(
      .ExpW  (rc_pkg::Fp24ExpW),
      .FracW (rc_pkg::Fp24FracW),
      .Stages(1)
    ) u_cmp (
      .clk_i,
      .rst_ni,
      .valid_i(pop1_v_q),
      .a_i    (tmin),
      .b_i    (bt_rd[r*W +: W]),
      .valid_o(pop_cmp_v[r]),
      .lt_o   (unused_lt),
      .le_o   (cmp_le),
      .eq_o   (unused_eq),
      .min_o  (unused_min),
      .max_o  (unused_max)
    );
    assign pop_le[r] = pop2_hit_q[r] ? (cmp_le & ~pop2_sh_q) : pop2_nn_q[r];
  end
  assign pop2_v = pop_cmp_v[0];
  // A start takes the routing register when no pop result does this cycle and the queues have
  // room for it besides the pops in flight.
  assign start_ready_o = ~pop2_v & pick_room_q;

  /////////////
  // Routing //
  /////////////

  // The routing register takes a pop result (its entry with the culled mask) or a start.
  logic                rt_v_q, rt_culled_q;
  logic [ThrW-1:0]     rt_thr_q;
  logic [SpW-1:0]      rt_sp_q;
  rc_pkg::walk_entry_t rt_entry_q;
  logic                start_take;
  logic [3:0]          pop2_mask;

  assign start_take = start_valid_i & start_ready_o;
  assign pop2_mask  = pop2_entry_q.mask & pop_le;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rt_v_q <= 1'b0;
    end else begin
      rt_v_q <= pop2_v | start_take;
    end
  end
  always_ff @(posedge clk_i) begin
    rt_culled_q <= pop2_v & (pop2_mask == 4'd0);
    if (pop2_v) begin
      rt_thr_q        <= pop2_thr_q;
      rt_sp_q         <= pop2_sp_q;
      rt_entry_q      <= pop2_entry_q;
      rt_entry_q.mask <= pop2_mask;
    end else begin
      rt_thr_q   <= ThrW'(start_item_i.thr);
      rt_sp_q    <= start_item_i.sp;
      rt_entry_q <= start_item_i.entry;
    end
  end

  logic [1:0] rt_route;
  logic [2:0] rt_err;
  logic       rt_leaf_kind;
  assign rt_route     = rc_pkg::walk_route(rt_entry_q.mask, rt_entry_q.node.rec[1:0],
                                           rt_entry_q.node.rec[63:32], rt_entry_q.node.chk);
  assign rt_err       = rc_pkg::walk_err(rt_entry_q.mask, rt_entry_q.node.chk);
  assign rt_leaf_kind = rt_entry_q.node.rec[rc_pkg::KdNodeKindLsb +: 2] ==
                        2'(rc_pkg::KdNodeKindLeaf);

  // The routing outputs are registered: queue writes, the re-pop and the error bits.
  logic                tq_push_q, lq_push_q, own_v_q, err_v_q;
  logic [ThrW-1:0]     own_thr_q;
  logic [2:0]          err_bits_q;
  rc_pkg::walk_item_t  tq_item_q;
  rc_pkg::leaf_item_t  lq_item_q;
  logic                perf_pop_q, perf_culled_q, perf_failed_q, perf_leaf_q, perf_empty_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tq_push_q     <= 1'b0;
      lq_push_q     <= 1'b0;
      own_v_q       <= 1'b0;
      err_v_q       <= 1'b0;
      perf_pop_q    <= 1'b0;
      perf_culled_q <= 1'b0;
      perf_failed_q <= 1'b0;
      perf_leaf_q   <= 1'b0;
      perf_empty_q  <= 1'b0;
    end else begin
      tq_push_q     <= rt_v_q && rt_route == rc_pkg::RouteTrav;
      lq_push_q     <= rt_v_q && rt_route == rc_pkg::RouteLeaf;
      own_v_q       <= rt_v_q && rt_route == rc_pkg::RoutePop;
      err_v_q       <= rt_v_q && rt_err != 3'd0;
      perf_pop_q    <= pp_v_q & ~pp_end;
      perf_culled_q <= rt_v_q & rt_culled_q;
      perf_failed_q <= pp_v_q & pp_end & pp_err;
      perf_leaf_q   <= rt_v_q && rt_entry_q.mask != 4'd0 && rt_leaf_kind;
      perf_empty_q  <= rt_v_q && rt_entry_q.mask != 4'd0 && rt_leaf_kind &&
                       rt_entry_q.node.rec[rc_pkg::KdNodeValueLsb +: 32] == 32'd0;
    end
  end
  always_ff @(posedge clk_i) begin
    own_thr_q       <= rt_thr_q;
    err_bits_q      <= rt_err;
    tq_item_q.thr   <= rc_pkg::CoreThrBits'(rt_thr_q);
    tq_item_q.sp    <= rt_sp_q;
    tq_item_q.entry <= rt_entry_q;
    lq_item_q.thr   <= rc_pkg::CoreThrBits'(rt_thr_q);
    lq_item_q.mask  <= rt_entry_q.mask;
    lq_item_q.first <= rt_entry_q.node.rec[rc_pkg::KdNodeIndexLsb +: 30];
    lq_item_q.count <= rt_entry_q.node.rec[rc_pkg::KdNodeValueLsb +: 32];
  end
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_own (.valid_i(own_v_q), .idx_i(own_thr_q),
                                                  .hot_o(own_req));
  assign err_valid_o = err_v_q;
  assign err_thr_o   = own_thr_q;
  assign err_bits_o  = err_bits_q;

  ////////////
  // Queues //
  ////////////

  logic [TqCntW-1:0] tq_cnt;
  logic [LqCntW-1:0] lq_cnt;
  rc_fifo #(
    .Width(rc_pkg::CoreThrBits + SpW + 262),
    .Depth(TravQDepth)
  ) u_trav_q (
    .clk_i,
    .rst_ni,
    .push_i (tq_push_q),
    .data_i (tq_item_q),
    .valid_o(trav_valid_o),
    .ready_i(trav_ready_i),
    .data_o (trav_item_o),
    .count_o(tq_cnt)
  );
  rc_fifo #(
    .Width(rc_pkg::CoreThrBits + 4 + 30 + 32),
    .Depth(LeafQDepth)
  ) u_leaf_q (
    .clk_i,
    .rst_ni,
    .push_i (lq_push_q),
    .data_i (lq_item_q),
    .valid_o(leaf_valid_o),
    .ready_i(leaf_ready_i),
    .data_o (leaf_item_o),
    .count_o(lq_cnt)
  );
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pick_room_q <= 1'b1;
    end else begin
      pick_room_q <= 32'(tq_cnt) + InFlight + 1 <= TravQDepth &&
                     32'(lq_cnt) + InFlight + 1 <= LeafQDepth;
    end
  end

  assign pick_valid_o  = pk_v_q;
  assign pick_thr_o    = pk_thr_q;
  assign route_valid_o = rt_v_q;
  assign route_thr_o   = rt_thr_q;
  assign perf_pop_o    = perf_pop_q;
  assign perf_culled_o = perf_culled_q;
  assign perf_failed_o = perf_failed_q;
  assign perf_leaf_o   = perf_leaf_q;
  assign perf_empty_o  = perf_empty_q;

  logic unused_bits;
  assign unused_bits = ^{pop_cmp_v[3:1], push_sp_i, start_item_i.thr};

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // A pop request is for a thread not already waiting (each thread is in one unit's hands).
  for (genvar t = 0; t < Threads; t++) begin : g_req_checks
    ReqOnce_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                $onehot0({popq_q[t] & ~gpp_q[t], h_tr[t], h_nr[t], req_lf_i[t],
                                          own_req[t]}));
  end
  // The one-hot grant is the picked thread.
  PopGrant_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               pp_v_q |-> gpp_q == (Threads'(1) << pp_thr_q));
  // A start and a pop result never meet in the routing stage.
  RouteSlot_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                !(pop2_v && start_take) && (pop2_v == $past(pop1_v_q)));
  // No pop reads a slot that is being written (a push comes a cycle or more before its pop).
  PushFirst_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                push_valid_i && pp_v_q |->
                                StkAW'({push_thr_i, push_sp_i[SpIdxW-1:0]}) !=
                                StkAW'({pp_thr_q, pp_sp[SpIdxW-1:0]}));
`endif

endmodule
