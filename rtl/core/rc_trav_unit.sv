// rc_trav_unit: the traversal unit (docs/architecture.md, "Traversal unit"): one step of a packet
// at an inner node. It reads the node's two children in one request of the node port, runs the
// packet's active rays through four rc_trav_step sub-units, and decides where the packet goes:
// on into its first child (straight back to this unit's issue when that is an inner node), the
// second child pushed when both got rays.
//
// Contract
// - Issue: a thread's current entry (an inner node whose checks passed, with active rays) comes
//   from the pop unit's traversal queue (q_*: valid/ready) or from this unit's own decision (a
//   continuation, which always goes first: q_ready_o = no continuation this cycle). At issue the
//   entry is stored (the waiting store: a block RAM by thread) and the node's children are
//   requested: a node-port request {tag = thread, index = the node's left child}, through a queue
//   of Threads entries (a thread has at most one request outstanding, so it never overflows).
// - Node port (rc_core's node_*): requests from the queue's head register; responses are always
//   taken (node_rsp_ready_o = 1: nothing behind them can stall). A response carries the two
//   children's records (docs/architecture.md, "Memory ports"); an error response ends the packet
//   with bad address (err_nr_*, pop request req_nr_*).
// - Step: three cycles after a response's cycle (its thread's waiting entry and its rays'
//   origins, 1/d and direction signs on the split axis are read from block RAMs in that cycle,
//   addressed by the response's tag: rc_ray_store's per-axis words, ax_*; each word passes a
//   fabric register after the read's two), the children's checks are made (rc_pkg::node_check:
//   node_count_i, list_count_i), and the four sub-units take the step (rc::trav_step() for each
//   active ray; the inactive ones' results are ignored).
// - Decision (docs/architecture.md, "Traversal"): the packet's first child is the lead ray's near
//   child; the rays and intervals of each child follow the step's cases; with rays in both the
//   second is pushed (push_*: depth sp + 1, the stack depth sp_tr_*) unless the stack holds
//   StackDepth entries (stack overflow: err_*, pop request). The packet goes on with the first
//   child that got rays, routed by rc_pkg::walk_route: an inner node back to this unit's issue,
//   a leaf with triangles to the list unit (leaf_*), anything else (an empty leaf, a failed
//   check) to a pop (req_tr_*, with the check's error bits on err_*). All outputs are registers.
// - Latency: issue to request queue 1; response to sub-units 3; sub-units 11 (rc_trav_step);
//   decision 2; so a node visit is the memory's latency plus about 18 cycles.
// - Throughput: one issue, one response and one decision per cycle.
// - Counters (perf_*): node requests, inner visits with their active rays (traversal steps),
//   pushes with the depth, leaf visits and empty leaves of the entries the decision routes.
// - Parameters: Threads, StackDepth.
// - Reset: rst_ni (active low, asynchronous) clears the valid bits and queues.
module rc_trav_unit #(
  parameter int unsigned Threads    = rc_pkg::CoreThreads,
  parameter int unsigned StackDepth = rc_pkg::KdtreeStackDepth,
  // Derived (do not override).
  parameter int unsigned W          = rc_pkg::CoreFpW,
  parameter int unsigned ThrW       = (Threads > 1) ? $clog2(Threads) : 1,
  parameter int unsigned SpW        = rc_pkg::CoreSpBits,
  parameter int unsigned TagW       = rc_pkg::CoreTagBits
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,

  // Configuration (quasi-static).
  input  logic [31:0]           node_count_i,
  input  logic [31:0]           list_count_i,

  // Entries from the pop unit.
  input  logic                  q_valid_i,
  output logic                  q_ready_o,
  input  rc_pkg::walk_item_t    q_item_i,

  // Node port.
  output logic                  node_req_valid_o,
  input  logic                  node_req_ready_i,
  output logic [TagW-1:0]       node_req_tag_o,
  output logic [31:0]           node_req_index_o,
  input  logic                  node_rsp_valid_i,
  output logic                  node_rsp_ready_o,
  input  logic [TagW-1:0]       node_rsp_tag_i,
  input  logic [127:0]          node_rsp_data_i,
  input  logic                  node_rsp_error_i,

  // The rays on the split axis (rc_ray_store; data 2 cycles after the read).
  output logic                  ax_re_o,
  output logic [ThrW-1:0]       ax_thr_o,
  output logic [1:0]            ax_axis_o,
  input  logic [4*W-1:0]        ax_org_i,     // ray r at [r*W +: W]
  input  logic [3:0]            ax_sign_i,    // direction sign bits
  input  logic [4*W-1:0]        ax_inv_i,

  // Decision outputs.
  output logic                  push_valid_o,
  output logic [ThrW-1:0]       push_thr_o,
  output logic [SpW-1:0]        push_sp_o,
  output rc_pkg::walk_entry_t   push_entry_o,
  output logic                  sp_tr_valid_o,
  output logic [ThrW-1:0]       sp_tr_thr_o,
  output logic [SpW-1:0]        sp_tr_sp_o,
  output logic                  leaf_valid_o,
  output rc_pkg::leaf_item_t    leaf_item_o,
  output logic                  req_tr_valid_o,
  output logic [ThrW-1:0]       req_tr_thr_o,
  output logic                  err_valid_o,
  output logic [ThrW-1:0]       err_thr_o,
  output logic [2:0]            err_bits_o,

  // A node response with an error.
  output logic                  req_nr_valid_o,
  output logic [ThrW-1:0]       req_nr_thr_o,

  // Debug and counter events.
  output logic                  issue_valid_o,   // an entry issued (this cycle)
  output logic [ThrW-1:0]       issue_thr_o,
  output logic                  step_valid_o,    // a step entering the sub-units
  output logic [ThrW-1:0]       step_thr_o,
  output logic                  dec_valid_o,     // the decision's outputs (registered)
  output logic [ThrW-1:0]       dec_thr_o,
  output logic                  perf_node_req_o,
  output logic                  perf_inner_o,
  output logic [2:0]            perf_steps_o,
  output logic                  perf_push_o,
  output logic [SpW-1:0]        perf_push_depth_o,
  output logic                  perf_leaf_o,
  output logic                  perf_empty_o
);

  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned NodeW  = rc_pkg::KdNodeIndexBits;
  localparam int unsigned WaitW  = SpW + 262;              // {sp, entry}
  localparam int unsigned ComW   = rc_pkg::CoreThrBits + 4 + 4 + 1 + SpW + 2 * 66;
  localparam int unsigned TrTagW = ComW + 2 * W;
  localparam int unsigned ReqQD  = (Threads > 1) ? Threads : 2;

  if (Threads < 1 || StackDepth < 1 || StackDepth > rc_pkg::KdtreeStackDepth ||
      ThrW > TagW || NodeW != 30) begin : g_param_check
    $error("rc_trav_unit: need 1 <= Threads <= 2^TagW and StackDepth <= KdtreeStackDepth");
  end

  ///////////
  // Issue //
  ///////////

  logic               cont_v_q, iss_v;
  rc_pkg::walk_item_t cont_item_q, iss_item;
  logic [ThrW-1:0]    iss_thr;

  assign q_ready_o = ~cont_v_q;
  assign iss_v     = cont_v_q | q_valid_i;
  assign iss_item  = cont_v_q ? cont_item_q : q_item_i;
  assign iss_thr   = ThrW'(iss_item.thr);

  // The waiting store: the entry and stack depth of each thread that waits for its children.
  // Read in the response's cycle (a response comes at least a cycle after its request, so never
  // in the cycle its entry is written); the word passes a third register (wait_q) in the fabric,
  // so the sub-units' first stages start from flip-flops the placer can put beside them, not
  // from the read's output register next to the block RAM.
  logic [WaitW-1:0] wait_rd, wait_q;
  logic [ThrW-1:0]  nq_thr_q;
  logic             nq_v_q;
  rc_ram #(
    .Width (WaitW),
    .Depth (1 << ThrW),
    .OutReg(1'b1)
  ) u_wait (
    .clk_i,
    .we_i   (iss_v),
    .waddr_i(iss_thr),
    .wdata_i({iss_item.sp, iss_item.entry}),
    .re_i   (node_rsp_valid_i),
    .raddr_i(ThrW'(node_rsp_tag_i)),
    .rdata_o(wait_rd)
  );

  // The split axis of each waiting thread (read as its response arrives, to address the rays).
  logic [1:0] axis_m [0:Threads-1];
  always_ff @(posedge clk_i) begin
    if (iss_v) axis_m[iss_thr] <= iss_item.entry.node.rec[rc_pkg::KdNodeKindLsb +: 2];
  end

  // Node requests, one per issue, in order.
  logic [ThrW+NodeW-1:0] rq_head;
  logic                  rq_valid;
  logic [$clog2(ReqQD+1)-1:0] rq_cnt;
  rc_fifo #(
    .Width(ThrW + NodeW),
    .Depth(ReqQD)
  ) u_req_q (
    .clk_i,
    .rst_ni,
    .push_i (iss_v),
    .data_i ({iss_thr, iss_item.entry.node.rec[rc_pkg::KdNodeIndexLsb +: NodeW]}),
    .valid_o(rq_valid),
    .ready_i(node_req_ready_i),
    .data_o (rq_head),
    .count_o(rq_cnt)
  );
  assign node_req_valid_o = rq_valid;
  assign node_req_tag_o   = TagW'(rq_head[NodeW +: ThrW]);
  assign node_req_index_o = {{(32 - NodeW){1'b0}}, rq_head[NodeW-1:0]};

  //////////////
  // Response //
  //////////////

  // The response is registered (nq) while the thread's waiting entry and its rays on the split
  // axis are read (block RAMs, a fabric register after each read, then wait_q and ax_*_q: three
  // cycles; nq, r1 and r2 hold the response meanwhile).
  logic         nq_err_q, r1_v_q, r1_err_q, r2_v_q, r2_err_q;
  logic [127:0] nq_data_q, r1_data_q, r2_data_q;
  logic [ThrW-1:0] r1_thr_q, r2_thr_q;

  assign node_rsp_ready_o = 1'b1;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      nq_v_q <= 1'b0;
      r1_v_q <= 1'b0;
      r2_v_q <= 1'b0;
    end else begin
      nq_v_q <= node_rsp_valid_i;
      r1_v_q <= nq_v_q;
      r2_v_q <= r1_v_q;
    end
  end
  always_ff @(posedge clk_i) begin
    nq_thr_q  <= ThrW'(node_rsp_tag_i);
    nq_data_q <= node_rsp_data_i;
    nq_err_q  <= node_rsp_error_i;
    r1_thr_q  <= nq_thr_q;
    r1_data_q <= nq_data_q;
    r1_err_q  <= nq_err_q;
    r2_thr_q  <= r1_thr_q;
    r2_data_q <= r1_data_q;
    r2_err_q  <= r1_err_q;
  end

  // The rays are read in the response's cycle too, and their words pass a third register here.
  logic [4*W-1:0] ax_org_q, ax_inv_q;
  logic [3:0]     ax_sign_q;
  assign ax_re_o   = node_rsp_valid_i;
  assign ax_thr_o  = ThrW'(node_rsp_tag_i);
  assign ax_axis_o = axis_m[ThrW'(node_rsp_tag_i)];
  always_ff @(posedge clk_i) begin
    wait_q    <= wait_rd;
    ax_org_q  <= ax_org_i;
    ax_inv_q  <= ax_inv_i;
    ax_sign_q <= ax_sign_i;
  end

  // The step's operands (r2).
  rc_pkg::walk_entry_t w_entry;
  logic [SpW-1:0]      w_sp;
  logic [W-1:0]        w_split;
  logic [1:0]          w_lead;
  logic                w_lsign;
  logic [3:0]          w_same;
  rc_pkg::trav_com_t   w_com;
  logic                step_v;

  assign {w_sp, w_entry} = wait_q;

  // The children's checks are made a cycle early, in r1, where the response and the waiting
  // entry's word (the left child's index) are both at hand, and registered for the step: their
  // 33-bit compares do not sit in front of the sub-units' input registers.
  rc_pkg::walk_entry_t r1_entry;
  logic [NodeW-1:0]    r1_left;
  logic [1:0]          chk_l_q, chk_r_q;
  logic                unused_r1;
  assign r1_entry  = wait_rd[WaitW-SpW-1:0];   // {sp, entry}: the entry
  assign r1_left   = r1_entry.node.rec[rc_pkg::KdNodeIndexLsb +: NodeW];
  assign unused_r1 = ^r1_entry;                // only the left child's index is used here
  always_ff @(posedge clk_i) begin
    chk_l_q <= rc_pkg::node_check(r1_data_q[63:0], r1_left, node_count_i, list_count_i);
    chk_r_q <= rc_pkg::node_check(r1_data_q[127:64], r1_left + NodeW'(1), node_count_i,
                                  list_count_i);
  end
  // The split plane's value feeds the four sub-units' subtracters; each reads a copy of its own
  // (rc_reg_copies, loaded beside wait_q from the same word), so no one flip-flop drives the
  // four first stages (run 59: wait_q -> u_step.u_sub.k1_q within 1 ns of the period on all five
  // seeds, -0.04 ns on seed 4).
  logic [4*W-1:0] split_copy_q;
  rc_reg_copies #(
    .Width (W),
    .Copies(4)
  ) u_split_copies (
    .clk_i,
    .rst_ni,
    .d_i   (r1_entry.node.rec[rc_pkg::KdNodeValueLsb +: W]),
    .q_o   (split_copy_q)
  );
  assign w_split = w_entry.node.rec[rc_pkg::KdNodeValueLsb +: W];
  assign w_lead  = rc_pkg::ray_lowest(w_entry.mask);
  assign w_lsign = ax_sign_q[w_lead];
  assign w_same  = ax_sign_q ^ {4{~w_lsign}};
  assign step_v  = r2_v_q & ~r2_err_q;

  always_comb begin
    w_com           = '0;
    w_com.thr       = rc_pkg::CoreThrBits'(r2_thr_q);
    w_com.mask      = w_entry.mask;
    w_com.same      = w_same;
    w_com.lsign     = w_lsign;
    w_com.sp        = w_sp;
    w_com.kid_l.rec = r2_data_q[63:0];
    w_com.kid_l.chk = chk_l_q;
    w_com.kid_r.rec = r2_data_q[127:64];
    w_com.kid_r.chk = chk_r_q;
  end

  ///////////////
  // Sub-units //
  ///////////////

  logic [3:0]          trav_ready_all, trav_v_all;
  logic [ComW-1:0]     trav_com_out;
  logic [8*W-1:0]      trav_iv;      // {tmax, tmin} of ray r at [r*2W +: 2W]
  logic [4*W-1:0]      trav_t;
  logic [7:0]          trav_case;

  // Sub-unit 0 carries the common part (thread, rays, children, stack depth) beside its ray's
  // interval; the others carry their ray's interval only.
  for (genvar r = 0; r < 4; r++) begin : g_trav
    localparam int unsigned TagR = (r == 0) ? TrTagW : 2 * W;
    logic [TagR-1:0] tag_in, tag_out;
    if (r == 0) begin : g_com
      assign tag_in = {w_entry.tmax[r], w_entry.tmin[r], w_com};
    end else begin : g_iv
      assign tag_in = {w_entry.tmax[r], w_entry.tmin[r]};
    end
    rc_trav_step #(
      .ExpW        (rc_pkg::Fp24ExpW),
      .FracW       (rc_pkg::Fp24FracW),
      .TagW        (TagR),
      .Backpressure(1'b0)   // the decision takes every result at once
    ) u_step (
      .clk_i,
      .rst_ni,
      .valid_i(step_v),
      .ready_o(trav_ready_all[r]),
      .tag_i  (tag_in),
      .split_i(split_copy_q[r*W +: W]),
      .org_i  (ax_org_q[r*W +: W]),
      .inv_i  (ax_inv_q[r*W +: W]),
      .tmin_i (w_entry.tmin[r]),
      .tmax_i (w_entry.tmax[r]),
      .valid_o(trav_v_all[r]),
      .ready_i(1'b1),
      .tag_o  (tag_out),
      .t_o    (trav_t[r*W +: W]),
      .case_o (trav_case[r*2 +: 2])
    );
    if (r == 0) begin : g_com_out
      assign trav_com_out = tag_out[0 +: ComW];
    end
    assign trav_iv[r*2*W +: 2*W] = tag_out[TagR-1 -: 2*W];
  end

  //////////////
  // Decision //
  //////////////

  // The head of the sub-units (hd): which rays go to each child, whether the second child is
  // pushed or the stack overflows; registered with the step's results (tq).
  rc_pkg::trav_com_t hd_com, tq_com_q;
  logic [3:0]        hd_a_mask, hd_b_mask, tq_a_mask_q, tq_b_mask_q;
  logic              hd_v, hd_push, hd_ovf, tq_v_q, tq_push_q, tq_ovf_q;
  logic [8*W-1:0]    tq_iv_q;     // {tmax, tmin} of ray r at [r*2W +: 2W]
  logic [4*W-1:0]    tq_t_q;
  logic [7:0]        tq_case_q;

  assign hd_v   = trav_v_all[0];
  assign hd_com = trav_com_out;
  always_comb begin
    for (int unsigned r = 0; r < 4; r++) begin
      logic [1:0] c;
      c = trav_case[r*2 +: 2];
      // kNearOnly (1) visits only the near child, kFarOnly (2) only the far one.
      hd_a_mask[r] = hd_com.mask[r] & (hd_com.same[r] ? c != 2'd2 : c != 2'd1);
      hd_b_mask[r] = hd_com.mask[r] & (hd_com.same[r] ? c != 2'd1 : c != 2'd2);
    end
  end
  assign hd_push = (|hd_a_mask) & (|hd_b_mask);
  assign hd_ovf  = hd_push & (hd_com.sp == SpW'(StackDepth));

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tq_v_q <= 1'b0;
    end else begin
      tq_v_q <= hd_v;
    end
  end
  always_ff @(posedge clk_i) begin
    tq_com_q <= hd_com;
    tq_iv_q     <= trav_iv;
    tq_t_q      <= trav_t;
    tq_case_q   <= trav_case;
    tq_a_mask_q <= hd_a_mask;
    tq_b_mask_q <= hd_b_mask;
    tq_push_q   <= hd_push;
    tq_ovf_q    <= hd_ovf;
  end

  // The children (tq): the first is the lead ray's near child (the left one when its direction's
  // sign bit is 0), and each ray's interval per child by its case.
  rc_pkg::walk_entry_t ent_a, ent_b, ent_go;
  logic [ThrW-1:0]     tq_thr;
  logic [SpW-1:0]      tq_sp1;
  always_comb begin
    ent_a      = '0;
    ent_b      = '0;
    ent_a.node = tq_com_q.lsign ? tq_com_q.kid_r : tq_com_q.kid_l;
    ent_b.node = tq_com_q.lsign ? tq_com_q.kid_l : tq_com_q.kid_r;
    ent_a.mask = tq_a_mask_q;
    ent_b.mask = tq_b_mask_q;
    for (int unsigned r = 0; r < 4; r++) begin
      logic       same, spl;
      logic [W-1:0] t, lo, hi;
      t    = tq_t_q[r*W +: W];
      lo   = tq_iv_q[r*2*W +: W];
      hi   = tq_iv_q[r*2*W + W +: W];
      same = tq_com_q.same[r];
      spl  = tq_case_q[r*2 +: 2] == 2'd3;  // kBothSplit
      ent_a.tmin[r] = (!same && spl) ? t : lo;
      ent_a.tmax[r] = (same && spl) ? t : hi;
      ent_b.tmin[r] = (same && spl) ? t : lo;
      ent_b.tmax[r] = (!same && spl) ? t : hi;
    end
  end
  // Whether the first child has rays, registered beside the masks twice (rc_flag_pair): tq_go_a_q
  // selects between the two children's routes, computed side by side, a LUT before the outputs'
  // valid registers; tq_go_b_q, its inverse, selects the entry that goes on (some 300 bits). So
  // the select's fan-out is off the valids' path (runs 48 to 50: tq_a_mask_q -> req_v_q through
  // the wide select, -0.07 to -0.84 ns).
  logic tq_go_a_q, tq_go_b_q;
  rc_flag_pair u_go_a (
    .clk_i,
    .rst_ni,
    .d_i (|hd_a_mask),
    .q_o (tq_go_a_q),
    .qn_o(tq_go_b_q)
  );
  assign ent_go = tq_go_b_q ? ent_b : ent_a;
  assign tq_thr = ThrW'(tq_com_q.thr);
  assign tq_sp1 = tq_com_q.sp + SpW'(1);

  // The route, the errors, the leaf kind and the empty leaf of each child, then the select.
  logic [1:0] route_a, route_b, go_route;
  logic [2:0] err_a, err_b, go_err;
  logic       leaf_a, leaf_b, empty_a, empty_b, go_leaf_kind, go_empty, push_ok;
  assign route_a      = rc_pkg::walk_route(ent_a.mask, ent_a.node.rec[1:0],
                                           ent_a.node.rec[63:32], ent_a.node.chk);
  assign route_b      = rc_pkg::walk_route(ent_b.mask, ent_b.node.rec[1:0],
                                           ent_b.node.rec[63:32], ent_b.node.chk);
  assign err_a        = rc_pkg::walk_err(ent_a.mask, ent_a.node.chk);
  assign err_b        = rc_pkg::walk_err(ent_b.mask, ent_b.node.chk);
  assign leaf_a       = ent_a.node.rec[rc_pkg::KdNodeKindLsb +: 2] == 2'(rc_pkg::KdNodeKindLeaf);
  assign leaf_b       = ent_b.node.rec[rc_pkg::KdNodeKindLsb +: 2] == 2'(rc_pkg::KdNodeKindLeaf);
  assign empty_a      = ent_a.node.rec[rc_pkg::KdNodeValueLsb +: 32] == 32'd0;
  assign empty_b      = ent_b.node.rec[rc_pkg::KdNodeValueLsb +: 32] == 32'd0;
  assign go_route     = tq_go_a_q ? route_a : route_b;
  assign go_err       = tq_go_a_q ? err_a : err_b;
  assign go_leaf_kind = tq_go_a_q ? leaf_a : leaf_b;
  assign go_empty     = tq_go_a_q ? empty_a : empty_b;
  assign push_ok      = tq_push_q & ~tq_ovf_q;

  // The decision's outputs, registered.
  logic               dc_v_q, push_v_q, leaf_v_q, req_v_q, err_v_q;
  logic [ThrW-1:0]    dc_thr_q;
  logic [SpW-1:0]     push_sp_q;
  rc_pkg::walk_entry_t push_entry_q;
  rc_pkg::leaf_item_t leaf_item_q;
  logic [2:0]         err_bits_q;
  logic               perf_leaf_q, perf_empty_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      dc_v_q       <= 1'b0;
      cont_v_q     <= 1'b0;
      push_v_q     <= 1'b0;
      leaf_v_q     <= 1'b0;
      req_v_q      <= 1'b0;
      err_v_q      <= 1'b0;
      perf_leaf_q  <= 1'b0;
      perf_empty_q <= 1'b0;
    end else begin
      dc_v_q       <= tq_v_q;
      cont_v_q     <= tq_v_q & ~tq_ovf_q & (go_route == rc_pkg::RouteTrav);
      push_v_q     <= tq_v_q & push_ok;
      leaf_v_q     <= tq_v_q & ~tq_ovf_q & (go_route == rc_pkg::RouteLeaf);
      req_v_q      <= tq_v_q & (tq_ovf_q | (go_route == rc_pkg::RoutePop));
      err_v_q      <= tq_v_q & (tq_ovf_q | (go_err != 3'd0));
      perf_leaf_q  <= tq_v_q & ~tq_ovf_q & go_leaf_kind;
      perf_empty_q <= tq_v_q & ~tq_ovf_q & go_leaf_kind & go_empty;
    end
  end
  always_ff @(posedge clk_i) begin
    dc_thr_q          <= tq_thr;
    cont_item_q.thr   <= tq_com_q.thr;
    cont_item_q.sp    <= push_ok ? tq_sp1 : tq_com_q.sp;
    cont_item_q.entry <= ent_go;
    push_sp_q         <= tq_sp1;
    push_entry_q      <= ent_b;
    leaf_item_q.thr   <= tq_com_q.thr;
    leaf_item_q.mask  <= ent_go.mask;
    leaf_item_q.first <= ent_go.node.rec[rc_pkg::KdNodeIndexLsb +: NodeW];
    leaf_item_q.count <= ent_go.node.rec[rc_pkg::KdNodeValueLsb +: 32];
    err_bits_q        <= tq_ovf_q ? (3'd1 << rc_pkg::CoreStatusStackOverflow) : go_err;
  end

  assign push_valid_o  = push_v_q;
  assign push_thr_o    = dc_thr_q;
  assign push_sp_o     = push_sp_q;
  assign push_entry_o  = push_entry_q;
  assign sp_tr_valid_o = push_v_q;
  assign sp_tr_thr_o   = dc_thr_q;
  assign sp_tr_sp_o    = push_sp_q;
  assign leaf_valid_o  = leaf_v_q;
  assign leaf_item_o   = leaf_item_q;
  assign req_tr_valid_o = req_v_q;
  assign req_tr_thr_o  = dc_thr_q;
  assign err_valid_o   = err_v_q;
  assign err_thr_o     = dc_thr_q;
  assign err_bits_o    = err_bits_q;

  // A node response with an error: bad address, and the packet pops (which ends it).
  assign req_nr_valid_o = r2_v_q & r2_err_q;
  assign req_nr_thr_o   = r2_thr_q;

  assign issue_valid_o     = iss_v;
  assign issue_thr_o       = iss_thr;
  assign step_valid_o      = step_v;
  assign step_thr_o        = r2_thr_q;
  assign dec_valid_o       = dc_v_q;
  assign dec_thr_o         = dc_thr_q;
  assign perf_node_req_o   = node_req_valid_o & node_req_ready_i;
  assign perf_inner_o      = step_v;
  assign perf_steps_o      = step_v ? rc_pkg::ray_count(w_entry.mask) : 3'd0;
  assign perf_push_o       = push_v_q;
  assign perf_push_depth_o = push_sp_q;
  assign perf_leaf_o       = perf_leaf_q;
  assign perf_empty_o      = perf_empty_q;

  logic unused_bits;
  assign unused_bits = ^{trav_v_all[3:1], trav_ready_all, rq_cnt, hd_com.lsign,
                         hd_com.kid_l, hd_com.kid_r, hd_com.thr, node_rsp_tag_i, tq_com_q.mask};

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // The sub-units are never full: their results are always taken, so a step always finds room.
  // The sub-units' copies of the split hold the waiting entry's split (what wait_q would give).
  SplitCopy_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               split_copy_q[0 +: W] == w_split);
  TravReady_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                step_v |-> &trav_ready_all);
  // They take the same operations, so they stay in lock step.
  TravLockStep_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   &trav_v_all || ~|trav_v_all);
  // An issued entry is an inner node whose checks passed, with active rays.
  IssueInner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 iss_v |-> iss_item.entry.mask != 4'd0 &&
                                 iss_item.entry.node.chk == rc_pkg::NodeOk &&
                                 iss_item.entry.node.rec[1:0] != 2'(rc_pkg::KdNodeKindLeaf));
  // The decision's select is the first child's mask being nonzero (registered beside it).
  GoA_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                          tq_v_q |-> tq_go_a_q == (tq_a_mask_q != 4'd0));
  // The request queue holds each thread once at most, so it never overflows.
  ReqRoom_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              iss_v |-> 32'(rq_cnt) < ReqQD);
  // The waiting store is read in the response's cycle: never the word its issue writes then (a
  // thread has one request outstanding, answered at least a cycle after it was taken).
  WaitNoCollide_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    node_rsp_valid_i |->
                                    !(iss_v && iss_thr == ThrW'(node_rsp_tag_i)));
`endif

endmodule
