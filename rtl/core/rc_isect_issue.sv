// rc_isect_issue: the intersection unit's front (docs/architecture.md, "Intersection unit"): takes
// each triangle read for a leaf and tests it against every active ray of the leaf's packet, one
// ray after the other, in rc_isect_unit.
//
// Contract
// - Triangle port responses (rc_core's tri_rsp_*, tag = the list entry's pool tag): taken through
//   a one-entry skid buffer (tri_rsp_ready_o is the buffer's emptiness, a flip-flop) into the
//   issue register, with the tag's thread, rays and triangle index read from the list unit's tag
//   pool (tp_*, always at the port's tag: a response waiting in the skid buffer keeps what the
//   read gave when it arrived; a tag's entry does not change until the tag is freed); the tag is
//   then freed (free_*). A failed read (error response) raises bad address for its thread
//   (err_*) and finishes its entry (fin_te_*).
// - Tests: from the issue register one ray per IsectInterval cycles (the intersection unit's
//   rate), lowest ray first: the ray's origin and direction (rc_ray_store, per {thread, ray}) and
//   its best hit (t and triangle, the hit store's copy for this unit) are read from block RAMs,
//   and two cycles later the test enters rc_isect_unit, which is then always ready (its results
//   are always taken, and the tests are spaced by its interval). The best counts only if the
//   ray's hit bit (this unit's copy of the hit bits, rc_hit_bits) was set at the read's edge
//   (else +inf and triangle -1: rc_isect_unit's best_valid_i). The bit is read a cycle later,
//   from the index registered with the test (rc_bit_read: the multiplexer split by a register),
//   and a commit to the same ray in the read's cycle, which that later sample sees and the
//   read's edge does not, clears it. So the bit is never newer than the word: it is the bit the
//   read's edge sampled, or 0 where that commit came (the test then goes without a best). A bit
//   and word sampled together are the same commit's, or the word is newer and the bit older;
//   either only lets through a test the write-back rejects (it compares again).
// - Secondary rays (the ray store's limit word {secondary, start_tri, tlim}, read with the ray):
//   the test takes the secondary rules (rc_isect_unit secondary_i: a hit needs t_eps_i < t;
//   excl_i: the triangle the ray starts on is never its hit) and the best {tlim, -1} whatever the
//   hit bit says. The write-back compares again and keeps the smallest (t, tri) of the hits found
//   before tlim, so the ray's record is the one rc::trace_packet() gives (its best starts at
//   {t_hi, -1}): for a shadow ray any hit before the light occludes (the pop culls it once it has
//   a hit); a bounce ray (tlim = +inf) gets its closest hit.
// - Results (res_*): every test's result, one per cycle at most, never refused: {thread, ray, last
//   (its list entry's last ray), triangle, hit, t, u, v, dz}.
// - Counters: perf_test_o, a test issued.
// - Parameters: Threads, IsectInterval (1: two transform units, 2: one used twice); Secondary:
//   1 = secondary rays as above, 0 = primary rays only (ray_lim_i and t_eps_i not read, no logic
//   for them); BlockDelays: the intersection unit's delay lines in block RAM (rc_isect_unit).
// - Reset: rst_ni (active low, asynchronous) clears the valid bits.
module rc_isect_issue #(
  parameter int unsigned Threads       = rc_pkg::CoreThreads,
  parameter int unsigned ListTags      = rc_pkg::CoreListTags,
  parameter int unsigned IsectInterval = rc_pkg::CoreIsectInterval,
  parameter bit          Secondary     = 1'b1,
  parameter bit          BlockDelays   = 1'b0,
  // Derived (do not override).
  parameter int unsigned W             = rc_pkg::CoreFpW,
  parameter int unsigned ThrW          = (Threads > 1) ? $clog2(Threads) : 1,
  parameter int unsigned LtW           = (ListTags > 1) ? $clog2(ListTags) : 1,
  parameter int unsigned TagW          = rc_pkg::CoreTagBits
) (
  input  logic                clk_i,
  input  logic                rst_ni,

  // Triangle port responses.
  input  logic                tri_rsp_valid_i,
  output logic                tri_rsp_ready_o,
  input  logic [TagW-1:0]     tri_rsp_tag_i,
  input  logic [12*W-1:0]     tri_rsp_data_i,
  input  logic                tri_rsp_error_i,

  // The list unit's tag pool.
  output logic [LtW-1:0]      tp_tag_o,
  input  logic [ThrW-1:0]     tp_thr_i,
  input  logic [3:0]          tp_mask_i,
  input  logic [2:0]          tp_first_i,
  input  logic [31:0]         tp_tri_i,
  output logic                free_valid_o,
  output logic [LtW-1:0]      free_tag_o,

  // The rays' origins and directions (rc_ray_store, per {thread, ray}; 2 cycles).
  output logic                ray_re_o,
  output logic [ThrW-1:0]     ray_thr_o,
  output logic [1:0]          ray_ray_o,
  input  logic [6*W-1:0]      ray_orgdir_i,   // org x, y, z, dir x, y, z
  input  logic [W+32:0]       ray_lim_i,      // {secondary, start triangle, tlim}
  // A secondary ray's lower bound of t (a frame's constant).
  input  logic [W-1:0]        t_eps_i,
  // The best hits (the hit store's copy, per {thread, ray}; 2 cycles).
  input  logic [W+31:0]       best_i,         // {tri, t}
  // The events that change the hit bits (rc_thread_ctrl's): this unit keeps its own copy.
  input  logic [Threads-1:0]  acc_hot_i,      // bit t: a packet taken into thread t
  input  logic                hitset_valid_i, // the write-back's commit of a new best hit
  input  logic [ThrW-1:0]     hitset_thr_i,
  input  logic [1:0]          hitset_ray_i,

  // Results.
  output logic                res_valid_o,
  output rc_pkg::isect_res_t  res_o,

  // A failed triangle read.
  output logic                err_valid_o,
  output logic [ThrW-1:0]     err_thr_o,
  output logic [2:0]          err_bits_o,
  output logic                fin_te_valid_o,
  output logic [ThrW-1:0]     fin_te_thr_o,

  // Debug and counter events.
  output logic                load_valid_o,   // a response entered the issue register
  output logic [ThrW-1:0]     load_thr_o,
  output logic                perf_test_o,
  output logic                wd_rsp_o
);

  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned  IuTagW = ThrW + 3;

  if (Threads < 1 || IsectInterval < 1 || IsectInterval > 2 || LtW > TagW) begin : g_param_check
    $error("rc_isect_issue: need IsectInterval 1 or 2");
  end

  ///////////////////////////////
  // Skid buffer and issue reg //
  ///////////////////////////////

  logic            is_take, ti_err_take, ti_free, ti_load, ti_v_q, ti_err_q, ti_last_q;
  logic            pace_ok, pace_ctl, is_take_ctl;  // below, with the pace
  logic            tk_v_q, tk_err_q, src_v, src_err, rsp_take;
  logic [LtW-1:0]  tk_tag_q, src_tag;
  logic [12*W-1:0] tk_data_q, src_data, ti_m_q;
  logic [ThrW-1:0] tk_thr_q, src_thr, ti_thr_q;
  logic [31:0]     tk_tri_q, src_tri, ti_tri_q;
  logic [3:0]      tk_mask_q, src_mask, ti_rem_q, ti_rem_next;
  logic [2:0]      tk_first_q, src_first;
  logic [1:0]      ti_r;

  assign tri_rsp_ready_o = ~tk_v_q;
  assign rsp_take        = tri_rsp_valid_i & ~tk_v_q;
  assign src_v           = tk_v_q | tri_rsp_valid_i;
  assign src_tag         = tk_v_q ? tk_tag_q : tri_rsp_tag_i[LtW-1:0];
  assign src_err         = tk_v_q ? tk_err_q : tri_rsp_error_i;
  assign src_data        = tk_v_q ? tk_data_q : tri_rsp_data_i;
  // The pool is read at the port's tag, not the selected one, so its read does not wait for the
  // skid buffer's select (run 63 seeds 1 and 4: tk_v_q and ti_last_q through the read into ti_r).
  assign tp_tag_o        = tri_rsp_tag_i[LtW-1:0];
  assign src_thr         = tk_v_q ? tk_thr_q : tp_thr_i;
  assign src_mask        = tk_v_q ? tk_mask_q : tp_mask_i;
  assign src_first       = tk_v_q ? tk_first_q : tp_first_i;
  assign src_tri         = tk_v_q ? tk_tri_q : tp_tri_i;
  // The register takes the next response in the cycle its last ray goes (or its error does).
  // Its valid bit is two kept copies (rc_reg_copies): ti_v_q for the test's outputs (is_take),
  // ti_v_ctl for the register's own control (ti_free, ti_load), as the pace below (run 73 seed
  // 3: ti_v_q into ti_r, ti_rem_q, ti_last_q and ti_tri_q's enable, -2.19 ns, 9.4 to 10.5 ns of
  // routing).
  // "The register is free" (ti_free) is itself a register, two kept copies computed from the
  // next cycle's valid, error, pace and last-ray bits (TiFree_A): ti_free for the control,
  // ti_free_dat for the enables of the register's data (ti_m_q, ti_tri_q, ti_thr_q). So no path
  // runs from ti_last_q through the test's take into those enables (the lit board routed at
  // 6799b81, seed 2: ti_last_q into ti_tri_q's enable, -2.28 ns with 11.3 ns of routing, and into
  // ti_r, ti_rem_q and ti_last_q, -1.92 to -1.02 ns).
  logic ti_v_ctl, ti_v_d, ti_free_dat, ti_free_d, ti_err_d, ti_last_d, pace_d;
  assign ti_load         = src_v & ti_free;
  assign ti_v_d          = ti_free ? src_v : ti_v_ctl;
  assign ti_err_d        = ti_free ? src_v & src_err : ti_err_q;
  assign pace_d          = (IsectInterval == 1) | ~is_take_ctl;
  assign ti_free_d       = ~ti_v_d | ti_err_d | (pace_d & ti_last_d);
  rc_reg_copies #(
    .Width   (1),
    .Copies  (2),
    .HasReset(1'b1),
    .ResetVal(1'b1)
  ) u_ti_free (
    .clk_i,
    .rst_ni,
    .d_i(ti_free_d),
    .q_o({ti_free_dat, ti_free})
  );
  rc_reg_copies #(
    .Width   (1),
    .Copies  (2),
    .HasReset(1'b1)
  ) u_ti_v (
    .clk_i,
    .rst_ni,
    .d_i(ti_v_d),
    .q_o({ti_v_ctl, ti_v_q})
  );

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tk_v_q   <= 1'b0;
      ti_err_q <= 1'b0;
    end else begin
      tk_v_q   <= tk_v_q ? ~ti_free : (rsp_take & ~ti_free);
      ti_err_q <= ti_err_d;
    end
  end
  always_ff @(posedge clk_i) begin
    if (rsp_take) begin
      tk_tag_q   <= tri_rsp_tag_i[LtW-1:0];
      tk_err_q   <= tri_rsp_error_i;
      tk_data_q  <= tri_rsp_data_i;
      tk_thr_q   <= tp_thr_i;
      tk_mask_q  <= tp_mask_i;
      tk_first_q <= tp_first_i;
      tk_tri_q   <= tp_tri_i;
    end
    // The triangle's 12 words (ti_m_q, the issue register's widest field), its index and its
    // thread load whenever the register is free, with or without a response: without one ti_v_q
    // goes low and they are not read (is_take's tests and the error's report read them). So
    // their enable is the register ti_free_dat, not ti_load, which also waits for the skid
    // buffer's and the port's valid bits (run 72 seed 2: tk_v_q through ti_load into ti_m_q's
    // enable, -0.67 ns).
    if (ti_free_dat) begin
      ti_thr_q <= src_thr;
      ti_tri_q <= src_tri;
      ti_m_q   <= src_data;
    end
  end

  // The rays still to test (lowest first) and whether the current one is the last are registers,
  // loaded with the triangle (from the pool's {one ray only, lowest ray}) and updated at each
  // test.
  assign ti_rem_next = ti_rem_q & (ti_rem_q - 4'd1);
  assign ti_last_d   = ti_load     ? src_first[2] :
                       is_take_ctl ? (ti_rem_next & (ti_rem_next - 4'd1)) == 4'd0 : ti_last_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ti_rem_q  <= '0;
      ti_last_q <= 1'b0;
      ti_r      <= '0;
    end else begin
      ti_last_q <= ti_last_d;
      if (ti_load) begin
        ti_rem_q  <= src_mask;
        ti_r      <= src_first[1:0];
      end else if (is_take_ctl) begin
        ti_rem_q  <= ti_rem_next;
        ti_r      <= rc_pkg::ray_lowest(ti_rem_next);
      end
    end
  end

  // One test every IsectInterval cycles: the pace register u_pace is 1 when a test may be taken
  // (at interval 2, the cycle after a take is not). Two kept copies (rc_reg_copies): pace_ok for
  // the test's outputs (the ray store's read, i1, the counter) and pace_ctl for the issue
  // register's own control (ti_free, ti_load and the rays left), so the flip-flop those read can
  // sit beside the issue register (run 73 seeds 2 and 4, then with a single pace_q register:
  // pace_q through ti_free and the response's valid into ti_rem_q, ti_last_q and ti_r, -0.33 and
  // -0.18 ns, 8.5 to 8.8 ns of routing in 4 to 5 cells).
  if (IsectInterval == 1) begin : g_pace1
    assign pace_ok  = 1'b1;
    assign pace_ctl = 1'b1;
  end else begin : g_pace2
    rc_reg_copies #(
      .Width   (1),
      .Copies  (2),
      .HasReset(1'b1),
      .ResetVal(1'b1)
    ) u_pace (
      .clk_i,
      .rst_ni,
      .d_i(~is_take),
      .q_o({pace_ctl, pace_ok})
    );
  end
  assign is_take     = ti_v_q & ~ti_err_q & pace_ok;
  assign is_take_ctl = ti_v_ctl & ~ti_err_q & pace_ctl;
  assign ti_err_take = ti_v_q & ti_err_q;

  //////////////////////////////
  // Reads and the unit input //
  //////////////////////////////

  // The ray's words and best hit are read at is_take (block RAMs with a fabric register), the hit
  // bit a cycle later (i1); the test's own values travel beside them (i1, i2).
  logic              i1_v_q, i2_v_q, i2_hit, i1_last_q, i2_last_q, i1_hs_q, i2_hs_q;
  logic [ThrW-1:0]   i1_thr_q, i2_thr_q;
  logic [1:0]        i1_r_q, i2_r_q;
  logic [31:0]       i1_tri_q, i2_tri_q;
  logic [12*W-1:0]   i1_m_q, i2_m_q;

  // The hit bits: this unit's copy of rc_thread_ctrl's (rc_hit_bits, the same events), placed
  // beside the unit, read by {thread, ray} through a multiplexer split by a register
  // (rc_bit_read: within each group of 8 threads before the edge, between the groups after it):
  // sampled at the edge that ends i1, given in i2.
  logic [Threads*4-1:0] hit_bits;
  rc_hit_bits #(
    .Threads(Threads)
  ) u_hit_bits (
    .clk_i,
    .rst_ni,
    .acc_hot_i,
    .hit_valid_i(hitset_valid_i),
    .hit_thr_i  (hitset_thr_i),
    .hit_ray_i  (hitset_ray_i),
    .hit_o      (hit_bits)
  );
  // The read's index {thread, ray}: i1's, one kept copy per group of the read, placed beside
  // its group, loaded from the registers ti_thr_q and ti_r. (ti_r alone drove every group at
  // is_take: run 61 seed 2, ti_r -> u_hit_read.grp_q, -1.44 ns; copies loaded with ti_r's next
  // value fanned the tag pool's read out to every group: run 63 seeds 1 and 4, -1.91 ns.)
  localparam int unsigned HitIdxW   = ThrW + 2;
  localparam int unsigned HitGroups = (HitIdxW > 5) ? (1 << (HitIdxW - 5)) : 1;
  logic [HitGroups*HitIdxW-1:0] hit_idx_q;
  logic                         hit_bit;
  rc_reg_copies #(
    .Width (HitIdxW),
    .Copies(HitGroups)
  ) u_hit_idx (
    .clk_i,
    .rst_ni,
    .d_i ({ti_thr_q, ti_r}),
    .q_o (hit_idx_q)
  );
  rc_bit_read #(
    .N        (Threads * 4),
    .IdxW     (HitIdxW),
    .LoW      (5),
    .IdxCopies(HitGroups)
  ) u_hit_read (
    .clk_i,
    .bits_i(hit_bits),
    .idx_i (hit_idx_q),
    .bit_o (hit_bit)
  );
  // The bit i1's edge sampled also holds the commits of the test's read cycle (is_take's); with
  // a commit to the test's own ray there (i1_hs_q) the word may be older than the bit, so the
  // bit reads 0 (no best: at worst a test the write-back rejects). Nothing clears a bit while
  // its thread has a test in flight (NoClearInFlight_A).
  assign i2_hit = hit_bit & ~i2_hs_q;

  assign ray_re_o  = is_take;
  assign ray_thr_o = ti_thr_q;
  assign ray_ray_o = ti_r;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      i1_v_q <= 1'b0;
      i2_v_q <= 1'b0;
    end else begin
      i1_v_q <= is_take;
      i2_v_q <= i1_v_q;
    end
  end
  always_ff @(posedge clk_i) begin
    i1_thr_q  <= ti_thr_q;
    i1_r_q    <= ti_r;
    i1_last_q <= ti_last_q;
    i1_tri_q  <= ti_tri_q;
    i1_m_q    <= ti_m_q;
    i2_thr_q  <= i1_thr_q;
    i2_r_q    <= i1_r_q;
    i2_last_q <= i1_last_q;
    i2_tri_q  <= i1_tri_q;
    i2_m_q    <= i1_m_q;
    i1_hs_q   <= hitset_valid_i & (hitset_thr_i == ti_thr_q) & (hitset_ray_i == ti_r);
    i2_hs_q   <= i1_hs_q;
  end

  // A secondary ray's test: its limit as the best, its start triangle excluded.
  logic              sec_kind, sec_ray;
  logic [31:0]       sec_start_tri, iu_best_tri;
  logic [W-1:0]      sec_tlim, iu_best_t;
  assign {sec_kind, sec_start_tri, sec_tlim} = ray_lim_i;
  assign sec_ray     = Secondary & sec_kind;
  assign iu_best_t   = sec_ray ? sec_tlim : best_i[W-1:0];
  assign iu_best_tri = sec_ray ? 32'hffff_ffff : best_i[W +: 32];

  logic              iu_ready, ix_v, ix_hit;
  logic [IuTagW-1:0] ix_tag;
  logic [31:0]       ix_tri;
  logic [W-1:0]      ix_t, ix_u, ix_vb, ix_dz;

  rc_isect_unit #(
    .ExpW       (rc_pkg::Fp24ExpW),
    .FracW      (rc_pkg::Fp24FracW),
    .TagW        (IuTagW),
    .SharedXform (IsectInterval == 2),
    .Backpressure(1'b0),  // the write-back takes every result at once
    .Secondary   (Secondary),
    .BlockDelays (BlockDelays)
  ) u_isect (
    .clk_i,
    .rst_ni,
    .valid_i   (i2_v_q),
    .ready_o   (iu_ready),
    .tag_i     ({i2_last_q, i2_r_q, i2_thr_q}),
    .tri_i     (i2_tri_q),
    .m_i       (i2_m_q),
    .org_i     (ray_orgdir_i[0 +: 3*W]),
    .dir_i     (ray_orgdir_i[3*W +: 3*W]),
    .best_t_i    (iu_best_t),
    .best_tri_i  (iu_best_tri),
    .best_valid_i(i2_hit | sec_ray),
    .secondary_i (sec_ray),
    .excl_i      (sec_ray & (i2_tri_q == sec_start_tri)),
    .t_eps_i     (t_eps_i),
    .valid_o   (ix_v),
    .ready_i   (1'b1),
    .tag_o     (ix_tag),
    .tri_o     (ix_tri),
    .hit_o     (ix_hit),
    .t_o       (ix_t),
    .u_o       (ix_u),
    .v_o       (ix_vb),
    .dz_o      (ix_dz)
  );

  assign res_valid_o = ix_v;
  always_comb begin
    res_o         = '0;
    res_o.thr     = rc_pkg::CoreThrBits'(ix_tag[ThrW-1:0]);
    res_o.ray     = ix_tag[ThrW +: 2];
    res_o.last    = ix_tag[ThrW + 2];
    res_o.tri_idx = ix_tri;
    res_o.hit     = ix_hit;
    res_o.t       = ix_t;
    res_o.u       = ix_u;
    res_o.v       = ix_vb;
    res_o.dz      = ix_dz;
  end

  assign free_valid_o   = ti_load;
  assign free_tag_o     = src_tag;
  assign err_valid_o    = ti_err_take;
  assign err_thr_o      = ti_thr_q;
  assign err_bits_o     = 3'd1 << rc_pkg::CoreStatusBadAddress;
  assign fin_te_valid_o = ti_err_take;
  assign fin_te_thr_o   = ti_thr_q;
  assign load_valid_o   = ti_load;
  assign load_thr_o     = src_thr;
  assign perf_test_o    = is_take;
  assign wd_rsp_o       = tri_rsp_valid_i & tri_rsp_ready_o;

  logic unused_bits;
  assign unused_bits = ^{tri_rsp_tag_i};

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // The intersection unit takes every test when it arrives (the tests are spaced by its
  // interval, and its results are always taken).
  IsectReady_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 i2_v_q |-> iu_ready);
  // A triangle has a ray to test.
  TriHasRay_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                ti_v_q && !ti_err_q |-> ti_rem_q != 4'd0);
  // The current ray is the lowest ray left, and the last-ray bit says whether one is left.
  TiRem_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            ti_v_q && !ti_err_q |-> ti_r == rc_pkg::ray_lowest(ti_rem_q) &&
                            ti_last_q == ((ti_rem_q & (ti_rem_q - 4'd1)) == 4'd0));
  // The register's free bit is the function of its valid, error, pace and last-ray bits that it
  // stands for.
  TiFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             ti_free == (~ti_v_ctl | ti_err_q | (is_take_ctl & ti_last_q)));
  // The hit read's index copies hold i1's {thread, ray}.
  HitIdx_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            i1_v_q |-> hit_idx_q[HitIdxW-1:0] == {i1_thr_q, i1_r_q});
  // No packet is taken into a thread with a test being read: its hit bits, which the bit read a
  // cycle after the word relies on, only rise while the test is in flight.
  NoClearInFlight_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                      is_take |-> !acc_hot_i[ti_thr_q]);
`endif

endmodule
