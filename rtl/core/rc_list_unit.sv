// rc_list_unit: the list unit (docs/architecture.md, "List unit"): for each leaf a packet visits,
// reads the leaf's list entries (triangle indices) and requests each triangle's transform for the
// intersection unit; counts each leaf's entries in flight and ends the leaf (a pop request) when
// the last of them is done.
//
// Contract
// - Leaves: from the traversal decision (leaf_a_*: a push, never refused: the queue holds every
//   thread once) and from the pop unit (leaf_b_*: valid/ready). One leaf at a time issues its
//   entries, one list request per cycle; the two sources take turns.
// - List port (rc_core's list_*): request {tag, index} from a register with a one-entry skid
//   buffer (the port's ready reaches only those registers); the tag is a free pool tag. Responses
//   are registered as they arrive, range-checked against tri_count_i and turned into the
//   triangle request {same tag, the triangle index} (tri_req_*, from a register). A failed entry
//   (error response or index >= tri_count_i) raises bad address for its thread (err_*), frees its
//   tag and is done.
// - Tag pool: ListTags tags; per tag its thread, the leaf's active rays, the mask's first ray and
//   whether it is the only one (so the intersection issue needs no decode), and the triangle
//   index. tp_* is an asynchronous read port of the pool for the intersection issue (by the
//   triangle response's tag). A tag is freed a cycle after free_valid_i (the triangle response
//   entering the issue register) or after its failed list entry; freed tags are offered again a
//   cycle after.
// - Leaf end: per thread the list entries in flight (issued, not finished) are counted; an entry
//   finishes as a failed list entry, a failed triangle read (fin_te_*) or its last ray's test
//   result reaching the best-hit compare (fin_io_*). When a thread's count reaches zero and the
//   unit issues no more for it, leaf_end_o[t] (a register) asks its pop, two cycles after its
//   last entry finished (the best-hit commit of that result is made by then).
// - Counters (perf_*): list entries read, list requests issued (the unit's busy cycles).
// - Parameters: Threads, ListTags (>= 2).
// - Reset: rst_ni (active low, asynchronous) clears the pool, queues and counts.
module rc_list_unit #(
  parameter int unsigned Threads  = rc_pkg::CoreThreads,
  parameter int unsigned ListTags = rc_pkg::CoreListTags,
  // Derived (do not override).
  parameter int unsigned ThrW     = (Threads > 1) ? $clog2(Threads) : 1,
  parameter int unsigned LtW      = (ListTags > 1) ? $clog2(ListTags) : 1,
  parameter int unsigned TagW     = rc_pkg::CoreTagBits
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic [31:0]         tri_count_i,

  // Leaves.
  input  logic                leaf_a_valid_i,
  input  rc_pkg::leaf_item_t  leaf_a_item_i,
  input  logic                leaf_b_valid_i,
  output logic                leaf_b_ready_o,
  input  rc_pkg::leaf_item_t  leaf_b_item_i,

  // List port.
  output logic                list_req_valid_o,
  input  logic                list_req_ready_i,
  output logic [TagW-1:0]     list_req_tag_o,
  output logic [31:0]         list_req_index_o,
  input  logic                list_rsp_valid_i,
  output logic                list_rsp_ready_o,
  input  logic [TagW-1:0]     list_rsp_tag_i,
  input  logic [31:0]         list_rsp_data_i,
  input  logic                list_rsp_error_i,

  // Triangle requests (the responses go to the intersection issue).
  output logic                tri_req_valid_o,
  input  logic                tri_req_ready_i,
  output logic [TagW-1:0]     tri_req_tag_o,
  output logic [31:0]         tri_req_index_o,

  // The tag pool's read port and the tag free (the intersection issue).
  input  logic [LtW-1:0]      tp_tag_i,
  output logic [ThrW-1:0]     tp_thr_o,
  output logic [3:0]          tp_mask_o,
  output logic [2:0]          tp_first_o,    // {one ray only, lowest ray}
  output logic [31:0]         tp_tri_o,
  input  logic                free_valid_i,
  input  logic [LtW-1:0]      free_tag_i,

  // Entries finished elsewhere.
  input  logic                fin_te_valid_i,   // a failed triangle read
  input  logic [ThrW-1:0]     fin_te_thr_i,
  input  logic                fin_io_valid_i,   // an entry's last result at the compare
  input  logic [ThrW-1:0]     fin_io_thr_i,

  // Outputs.
  output logic [Threads-1:0]  leaf_end_o,
  output logic                err_valid_o,
  output logic [ThrW-1:0]     err_thr_o,
  output logic [2:0]          err_bits_o,

  // Debug and counter events.
  output logic                take_valid_o,     // a leaf taken (this cycle)
  output logic [ThrW-1:0]     take_thr_o,
  output logic                perf_entry_o,     // a list response taken
  output logic                perf_issue_o,     // a list request issued
  output logic                wd_req_o,         // list port request handshake
  output logic                wd_rsp_o          // list port response handshake
);

  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned IsectDepth = 2 + (rc_pkg::FpStagesMul + 3 * rc_pkg::FpStagesAdd) +
                                       rc_pkg::FpStagesDiv + rc_pkg::FpStagesMul +
                                       2 * rc_pkg::FpStagesAdd + rc_pkg::FpStagesCmp + 2;
  // Entries in flight per thread: a tag each, then the issue register, the read stages and input
  // queue of the intersection issue, the intersection unit, and the write-back's stages; plus one
  // counted a cycle long.
  localparam int unsigned LfMax = ListTags + 16 + IsectDepth + 8;
  localparam int unsigned LfW   = $clog2(LfMax + 1);
  localparam int unsigned AQD   = (Threads > 1) ? Threads : 2;

  if (Threads < 1 || ListTags < 2 || LtW > TagW || ThrW > rc_pkg::CoreThrBits) begin : g_param_check
    $error("rc_list_unit: need ListTags >= 2 tags of at most TagW bits");
  end

  ///////////////////
  // Leaf sources  //
  ///////////////////

  logic               qa_valid, qa_ready;
  rc_pkg::leaf_item_t qa_item;
  logic [$clog2(AQD+1)-1:0] qa_cnt;
  rc_fifo #(
    .Width(rc_pkg::CoreThrBits + 4 + 30 + 32),
    .Depth(AQD)
  ) u_leaf_a (
    .clk_i,
    .rst_ni,
    .push_i (leaf_a_valid_i),
    .data_i (leaf_a_item_i),
    .valid_o(qa_valid),
    .ready_i(qa_ready),
    .data_o (qa_item),
    .count_o(qa_cnt)
  );

  logic               lu_busy_q, li_take, lp_take, turn_b_q, take_b;
  logic [ThrW-1:0]    lu_thr_q;
  logic [3:0]         lu_mask_q;
  logic [31:0]        lu_idx_q, lu_left_q;
  rc_pkg::leaf_item_t lp_item;

  // A leaf is taken when the unit is idle: from the source whose turn it is, else the other.
  assign take_b         = leaf_b_valid_i & (turn_b_q | ~qa_valid);
  assign lp_take        = ~lu_busy_q & (qa_valid | leaf_b_valid_i);
  assign lp_item        = take_b ? leaf_b_item_i : qa_item;
  assign qa_ready       = ~lu_busy_q & ~take_b;
  assign leaf_b_ready_o = ~lu_busy_q & take_b;

  //////////////
  // Tag pool //
  //////////////

  logic [ListTags-1:0] tf_q, tf_d;
  logic [ThrW-1:0]     tp_thr_m [0:ListTags-1];
  logic [3:0]          tp_mask_m [0:ListTags-1];
  logic [2:0]          tp_first_m [0:ListTags-1];
  logic [31:0]         tp_tri_m [0:ListTags-1];

  // The next tag to take: the lowest set bit of the free set (x & -x), registered one-hot
  // (tag_first_q), computed from the free set without this cycle's take; freed tags are offered a
  // cycle later. The search runs on the free set with and without the registered tag, and the
  // take picks one at the end; the tag's number is encoded from the register (tag_new), so the
  // search's loop has no encoder in it.
  logic [ListTags-1:0] tf_rest, tag_first_all, tag_first_rest, tag_first_q;
  logic [LtW-1:0]      tag_new;
  logic                tag_avail_q, tag_avail_d;
  function automatic logic [LtW-1:0] tag_index(input logic [ListTags-1:0] one_hot);
    tag_index = '0;
    for (int unsigned i = 0; i < ListTags; i++) begin
      if (one_hot[i]) tag_index = tag_index | LtW'(i);
    end
  endfunction
  assign tf_rest        = tf_q & ~tag_first_q;
  assign tag_first_all  = tf_q & (~tf_q + ListTags'(1));
  assign tag_first_rest = tf_rest & (~tf_rest + ListTags'(1));
  assign tag_new        = tag_index(tag_first_q);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tag_avail_q <= 1'b1;
      tag_first_q <= ListTags'(1);
    end else begin
      tag_avail_q <= tag_avail_d;
      tag_first_q <= li_take ? tag_first_rest : tag_first_all;
    end
  end

  ///////////////////
  // List requests //
  ///////////////////

  logic           lreq_free, lout_free;
  logic           list_req_valid_q, lsk_v_q;
  // Not state machines (Yosys's FSM extraction would see constants chosen by tag_first_q's bits
  // and enumerate them).
  (* fsm_encoding = "none" *) logic [LtW-1:0] list_req_tag_q;
  (* fsm_encoding = "none" *) logic [LtW-1:0] lsk_tag_q;
  logic [31:0]    list_req_index_q, lsk_index_q;

  // The request leaves through a register with a one-entry skid buffer (lsk), so the unit issues
  // whenever the buffer is empty (a flip-flop) and the port's ready reaches the request registers
  // only.
  assign lout_free = ~list_req_valid_q | list_req_ready_i;
  assign lreq_free = ~lsk_v_q;

  // The issue of a list entry (lu_busy_q & tag_avail_q & lreq_free) drives some 250 enables and
  // selects in both halves of this unit, so it is registered from the next values, in kept copies
  // (rc_reg_copies): li_take_q for the tag pool (tag_first_q, tf_q, the pool's writes) and
  // li_take_r for the request side (lu_*, the request registers, the in-flight counts). Both
  // equal the expression above (LiTake_A).
  //
  // Whether the unit issues in the next cycle depends on whether it issues in this one (the
  // leaf's count, the skid buffer, the free tags): a one-cycle loop. It does not run through the
  // flags that drive the enables: a flip-flop with hundreds of loads is placed among them, and
  // the loop then crosses the chip twice (run 70 seed 2: the take flag, through lu_left_q's
  // compare with 1, back to the take flag, 10.49 ns routed, -1.96 ns). The loop reads copies of
  // its own instead, read by the next values below only: the issue (li_take_l), the busy flag
  // (lu_busy_l), the skid buffer's valid (lsk_v_l) and the request register's valid (lreq_v_l),
  // each equal to the flag the datapath reads (LoopCopy_A); and lu_last_q, whether the entry to
  // issue is the leaf's last (lu_left_q == 1, LuLast_A), so the loop holds no compare. All of
  // these flags are kept copies: Yosys would merge a plain flip-flop into a kept one with the
  // same input.
  logic lu_busy_d, lsk_v_d, lreq_v_d, li_take_d, li_take_q, li_take_r;
  logic li_take_l, lu_busy_l, lsk_v_l, lreq_v_l, lout_free_l, lu_last_q, lu_last_d;
  assign li_take     = li_take_q;
  assign lout_free_l = ~lreq_v_l | list_req_ready_i;
  always_comb begin
    lu_busy_d = lu_busy_l;
    if (!lu_busy_l && (qa_valid || leaf_b_valid_i)) lu_busy_d = 1'b1;  // lp_take
    if (li_take_l && lu_last_q) lu_busy_d = 1'b0;
  end
  assign lsk_v_d     = lsk_v_l ? ~lout_free_l : (li_take_l & ~lout_free_l);
  assign lreq_v_d    = lout_free_l ? (lsk_v_l | li_take_l) : lreq_v_l;
  assign tag_avail_d = li_take_l ? |tf_rest : |tf_q;
  assign li_take_d   = lu_busy_d & tag_avail_d & ~lsk_v_d;
  rc_reg_copies #(
    .Width   (1),
    .Copies  (3),
    .HasReset(1'b1)
  ) u_li_take (
    .clk_i,
    .rst_ni,
    .d_i   (li_take_d),
    .q_o   ({li_take_l, li_take_r, li_take_q})
  );
  rc_reg_copies #(
    .Width   (3),
    .Copies  (2),
    .HasReset(1'b1)
  ) u_flags (
    .clk_i,
    .rst_ni,
    .d_i   ({lu_busy_d, lsk_v_d, lreq_v_d}),
    .q_o   ({lu_busy_l, lsk_v_l, lreq_v_l, lu_busy_q, lsk_v_q, list_req_valid_q})
  );
  always_comb begin
    lu_last_d = lu_last_q;
    if (lp_take) lu_last_d = lp_item.count == 32'd1;
    if (li_take_r) lu_last_d = lu_left_q == 32'd2;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      turn_b_q         <= 1'b0;
      lu_thr_q         <= '0;
      lu_mask_q        <= '0;
      lu_idx_q         <= '0;
      lu_left_q        <= '0;
      list_req_tag_q   <= '0;
      list_req_index_q <= '0;
      lsk_tag_q        <= '0;
      lsk_index_q      <= '0;
      lu_last_q        <= 1'b0;
    end else begin
      lu_last_q <= lu_last_d;
      if (lp_take) begin
        turn_b_q  <= ~take_b;
        lu_thr_q  <= ThrW'(lp_item.thr);
        lu_mask_q <= lp_item.mask;
        lu_idx_q  <= {2'b00, lp_item.first};
        lu_left_q <= lp_item.count;
      end
      if (lout_free) begin
        list_req_tag_q   <= lsk_v_q ? lsk_tag_q : tag_new;
        list_req_index_q <= lsk_v_q ? lsk_index_q : lu_idx_q;
      end
      if (!lsk_v_q) begin
        lsk_tag_q   <= tag_new;
        lsk_index_q <= lu_idx_q;
      end
      if (li_take_r) begin
        lu_idx_q  <= lu_idx_q + 32'd1;
        lu_left_q <= lu_left_q - 32'd1;
      end
    end
  end

  assign list_req_valid_o = list_req_valid_q;
  assign list_req_tag_o   = TagW'(list_req_tag_q);
  assign list_req_index_o = list_req_index_q;

  ////////////////////
  // List responses //
  ////////////////////

  logic            tbuf_free, lr_take, lr_bad, lb_v_q, lq_v_q, lq_err_q;
  logic [LtW-1:0]  lr_tag, lb_tag_q, lq_tag_q;
  logic [ThrW-1:0] lb_thr_q;
  logic [31:0]     lq_data_q;
  logic            tri_req_valid_q;
  logic [LtW-1:0]  tri_req_tag_q;
  logic [31:0]     tri_req_index_q;

  // The response is registered as it arrives (lq) and range-checked from there; a failed entry is
  // registered with its tag's thread (lb) and retired a cycle later.
  assign tbuf_free        = ~tri_req_valid_q | tri_req_ready_i;
  assign list_rsp_ready_o = ~lq_v_q | tbuf_free;
  assign lr_take          = lq_v_q & tbuf_free;
  assign lr_tag           = lq_tag_q;
  assign lr_bad           = lq_err_q | (lq_data_q >= tri_count_i);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lq_v_q    <= 1'b0;
      lq_err_q  <= 1'b0;
      lq_tag_q  <= '0;
      lq_data_q <= '0;
    end else if (list_rsp_ready_o) begin
      lq_v_q    <= list_rsp_valid_i;
      lq_err_q  <= list_rsp_error_i;
      lq_tag_q  <= list_rsp_tag_i[LtW-1:0];
      lq_data_q <= list_rsp_data_i;
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lb_v_q   <= 1'b0;
      lb_tag_q <= '0;
      lb_thr_q <= '0;
    end else begin
      lb_v_q <= lr_take & lr_bad;
      if (lr_take) begin
        lb_tag_q <= lr_tag;
        lb_thr_q <= tp_thr_m[lr_tag];
      end
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tri_req_valid_q <= 1'b0;
      tri_req_tag_q   <= '0;
      tri_req_index_q <= '0;
    end else begin
      if (tri_req_valid_q && tri_req_ready_i) tri_req_valid_q <= 1'b0;
      if (lr_take) begin
        tri_req_valid_q <= ~lr_bad;
        tri_req_tag_q   <= lr_tag;
        tri_req_index_q <= lq_data_q;
      end
    end
  end
  assign tri_req_valid_o = tri_req_valid_q;
  assign tri_req_tag_o   = TagW'(tri_req_tag_q);
  assign tri_req_index_o = tri_req_index_q;

  always_ff @(posedge clk_i) begin
    if (li_take) begin
      tp_thr_m[tag_new]   <= lu_thr_q;
      tp_mask_m[tag_new]  <= lu_mask_q;
      tp_first_m[tag_new] <= {(lu_mask_q & (lu_mask_q - 4'd1)) == 4'd0,
                                rc_pkg::ray_lowest(lu_mask_q)};
    end
    // Written on every list response, failed ones too (a failed entry's tag sends no triangle
    // request, and the tag's next response writes it again before it is read).
    if (lr_take) tp_tri_m[lr_tag] <= lq_data_q;
  end
  assign tp_thr_o   = tp_thr_m[tp_tag_i];
  assign tp_mask_o  = tp_mask_m[tp_tag_i];
  assign tp_first_o = tp_first_m[tp_tag_i];
  assign tp_tri_o   = tp_tri_m[tp_tag_i];

  // The pool's free set: a take clears its one-hot tag; a registered free (from the intersection
  // issue: tl) or a retired failed entry sets one.
  logic           tl_v_q;
  logic [LtW-1:0] tl_tag_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tl_v_q   <= 1'b0;
      tl_tag_q <= '0;
    end else begin
      tl_v_q   <= free_valid_i;
      tl_tag_q <= free_tag_i;
    end
  end
  always_comb begin
    for (int unsigned i = 0; i < ListTags; i++) begin
      tf_d[i] = (tf_q[i] & ~(li_take & tag_first_q[i])) |
                (lb_v_q & (lb_tag_q == LtW'(i))) |
                (tl_v_q & (tl_tag_q == LtW'(i)));
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tf_q <= '1;
    end else begin
      tf_q <= tf_d;
    end
  end

  ////////////////////////
  // Entries in flight  //
  ////////////////////////

  // Per thread the entries in flight: issues are counted a cycle late (lf_inc_q) and so are the
  // finishing entries (pend_dec_q, up to three a cycle: a failed list entry, a failed triangle
  // read and a last result); whether a count is 1, 2 or 3 is registered with it, so the leaf's end
  // is a compare of flip-flops. A thread with an issue still to count, or the one the unit issues
  // for, is still issuing.
  logic [Threads*LfW-1:0] lf_q, lf_d;
  logic [Threads*3-1:0]   lf_small_q, lf_small_d;
  logic [2*Threads-1:0]   pend_dec_q, pend_dec_d;
  logic [Threads-1:0]     lf_inc_q, lf_inc_d, pend_zero, h_lu, h_lb, h_te, h_io;
  // The events' threads one-hot (rc_onehot).
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_lu (.valid_i(lu_busy_q), .idx_i(lu_thr_q),
                                                 .hot_o(h_lu));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_lb (.valid_i(lb_v_q), .idx_i(lb_thr_q),
                                                 .hot_o(h_lb));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_te (.valid_i(fin_te_valid_i), .idx_i(fin_te_thr_i),
                                                 .hot_o(h_te));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_io (.valid_i(fin_io_valid_i), .idx_i(fin_io_thr_i),
                                                 .hot_o(h_io));
  always_comb begin
    for (int unsigned t = 0; t < Threads; t++) begin
      logic issuing;
      logic [1:0] dec;
      lf_inc_d[t] = li_take_r & h_lu[t];
      issuing = h_lu[t] || lf_inc_q[t];
      pend_dec_d[2*t +: 2] = 2'(h_lb[t]) + 2'(h_te[t]) + 2'(h_io[t]);
      dec = pend_dec_q[2*t +: 2];
      lf_d[t*LfW +: LfW] = lf_q[t*LfW +: LfW] + LfW'(lf_inc_q[t]) - LfW'(dec);
      for (int unsigned k = 1; k <= 3; k++) begin
        lf_small_d[3*t + k - 1] = lf_d[t*LfW +: LfW] == LfW'(k);
      end
      pend_zero[t] = !issuing && ((dec == 2'd1 && lf_small_q[3*t]) ||
                                  (dec == 2'd2 && lf_small_q[3*t + 1]) ||
                                  (dec == 2'd3 && lf_small_q[3*t + 2]));
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lf_q       <= '0;
      lf_small_q <= '0;
      pend_dec_q <= '0;
      lf_inc_q   <= '0;
    end else begin
      lf_q       <= lf_d;
      lf_small_q <= lf_small_d;
      pend_dec_q <= pend_dec_d;
      lf_inc_q   <= lf_inc_d;
    end
  end
  // The leaf ends leave through a register (the pop unit's request bits are across the chip).
  logic [Threads-1:0] leaf_end_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      leaf_end_q <= '0;
    end else begin
      leaf_end_q <= pend_zero;
    end
  end
  assign leaf_end_o = leaf_end_q;

  assign err_valid_o  = lb_v_q;
  assign err_thr_o    = lb_thr_q;
  assign err_bits_o   = 3'd1 << rc_pkg::CoreStatusBadAddress;
  assign take_valid_o = lp_take;
  assign take_thr_o   = ThrW'(lp_item.thr);
  assign perf_entry_o = lr_take;
  assign perf_issue_o = li_take;
  assign wd_req_o     = list_req_valid_q & list_req_ready_i;
  assign wd_rsp_o     = lr_take;

  logic unused_bits;
  assign unused_bits = ^{list_rsp_tag_i, qa_cnt};

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // The leaf queue holds a thread once at most, so it never overflows.
  LeafQRoom_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                leaf_a_valid_i |-> 32'(qa_cnt) < AQD);
  // A leaf has triangles and rays.
  LeafWork_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               lp_take |-> lp_item.count != 32'd0 && lp_item.mask != 4'd0);
  // The registered issue and its inverse are the issue's expression.
  LiTake_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             li_take == (lu_busy_q & tag_avail_q & lreq_free) &&
                             li_take_r == li_take);
  // The issue loop's copies are the flags the datapath reads.
  LoopCopy_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               {li_take_l, lu_busy_l, lsk_v_l, lreq_v_l} ==
                               {li_take, lu_busy_q, lsk_v_q, list_req_valid_q});
  // lu_last_q is the leaf's count's compare with 1 (the count is 0 while idle).
  LuLast_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             lu_last_q == (lu_left_q == 32'd1));
  // A list entry waits in the skid buffer only behind a request the port has not taken.
  ListSkid_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               lsk_v_q |-> list_req_valid_q);
  // Responses carry an outstanding tag; a failed entry keeps its tag until it is retired.
  ListRspTag_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 lq_v_q |-> !tf_q[lr_tag]);
  ListBadRetire_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    lb_v_q |-> !tf_q[lb_tag_q]);
  // The registered next tag is free, one-hot with its index (or none while none was free).
  TagFirst_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               tag_avail_q ? (tf_q[tag_new] &&
                                              tag_first_q == ListTags'(1) << tag_new) :
                                             (tag_first_q == '0));
  // A tag is freed only while in use.
  TagFreeBusy_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  free_valid_i |-> !tf_q[free_tag_i]);
  // The counts stay within their bound and none finishes that was not issued.
  for (genvar t = 0; t < Threads; t++) begin : g_lf_checks
    InFlight_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 32'(lf_q[t*LfW +: LfW]) <= LfMax &&
                                 32'(pend_dec_q[2*t +: 2]) <= 32'(lf_q[t*LfW +: LfW]));
    LfSmall_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                lf_small_q[3*t +: 3] == {lf_q[t*LfW +: LfW] == LfW'(3),
                                                         lf_q[t*LfW +: LfW] == LfW'(2),
                                                         lf_q[t*LfW +: LfW] == LfW'(1)});
  end
`endif

endmodule
