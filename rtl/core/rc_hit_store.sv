// rc_hit_store: the rays' best hits (docs/architecture.md, "Hit store"): the write-back of the
// intersection unit's results and the copies of the best hits each reader needs.
//
// Contract
// - Results (res_*, never refused): a result with its hit bit set replaces its ray's best if its
//   (t, triangle) is smaller: t < best.t, or t == best.t and triangle < best.tri (the tie
//   break); compared again here because other tests of the same ray may have finished since this
//   one read its best. Accepted t are positive and finite, so their encodings order like their
//   values. The best of a ray without its hit bit (rc_thread_ctrl hit_i) is t = +inf, triangle -1.
// - Pipeline: the result is registered (iu) and its ray's committed best read from a block RAM
//   (with a fabric register: io1, io2), the hit bit sampled at the read's edge; the best is then
//   registered (wb) with the commits the read missed forwarded, newest first (those of the three
//   cycles from the read's on); the compare (wb) also compares against the decision made in the
//   cycle before, when it was the same ray's, instead of forwarding it; the commit (wc) writes
//   every copy and sets the ray's hit bit (hit_*). So a result's commit is 5 cycles after it
//   arrives.
// - Leaf accounting: fin_valid_o marks the compare of a list entry's last ray's result (the
//   entry is done; its commit, if any, comes in the next cycle).
// - Copies (block RAMs written at every commit, each read by one unit; data 2 cycles after the
//   read):
//     isect: {tri, t} per {thread, ray} (the intersection issue's filter);
//     pop:   t of the four rays per thread (the pop unit's cull);
//     shade: the four rays' triangles per thread (the shading sequencer's requests);
//     dz:    d'z per {thread, ray} (shading);
//     fb:    {dz, tri, v, u, t} per {thread, ray} (the framebuffer write's hit record; dz only
//            with FbDz, zero without).
//   A copy's word for a ray counts only where the ray's hit bit is set; readers gate with it.
// - Parameters: Threads; FbDz: 1 = the fb copy holds d'z (a tree controller lights the hits).
// - Reset: rst_ni (active low, asynchronous) clears the valid bits.
module rc_hit_store #(
  parameter int unsigned Threads = rc_pkg::CoreThreads,
  parameter bit          FbDz    = 1'b1,
  // Derived (do not override).
  parameter int unsigned W       = rc_pkg::CoreFpW,
  parameter int unsigned ThrW    = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,

  // Results of the intersection unit.
  input  logic                  res_valid_i,
  input  rc_pkg::isect_res_t    res_i,
  input  logic [Threads*4-1:0]  hit_i,

  // Commits (to rc_thread_ctrl) and finished entries (to the list unit).
  output logic                  hit_valid_o,
  output logic [ThrW-1:0]       hit_thr_o,
  output logic [1:0]            hit_ray_o,
  output logic                  fin_valid_o,
  output logic [ThrW-1:0]       fin_thr_o,

  // Read ports.
  input  logic                  isect_re_i,
  input  logic [ThrW-1:0]       isect_thr_i,
  input  logic [1:0]            isect_ray_i,
  output logic [W+31:0]         isect_best_o,   // {tri, t}
  input  logic                  pop_re_i,
  input  logic [ThrW-1:0]       pop_thr_i,
  output logic [4*W-1:0]        pop_t_o,        // ray r at [r*W +: W]
  input  logic                  shade_re_i,
  input  logic [ThrW-1:0]       shade_thr_i,
  output logic [127:0]          shade_tri_o,    // ray r at [r*32 +: 32]
  input  logic                  fb_re_i,
  input  logic [ThrW-1:0]       fb_thr_i,
  input  logic [1:0]            fb_ray_i,
  output logic [4*W+31:0]       fb_best_o,      // {dz, tri, v, u, t}
  input  logic                  dz_re_i,
  input  logic [ThrW-1:0]       dz_thr_i,
  input  logic [1:0]            dz_ray_i,
  output logic [W-1:0]          dz_o,

  // Counter events.
  output logic                  perf_commit_o
);

  localparam int unsigned  RidW  = ThrW + 2;

  ////////////////////
  // The write-back //
  ////////////////////

  logic               iu_v_q, io1_v_q, io2_v_q, wb_v_q, wc_we_q, wd_we_q, we_we_q;
  rc_pkg::isect_res_t iu_q, io1_q, io2_q, wb_q;
  logic               io2_hit_q;
  logic [W+31:0]      bw_rd;     // {tri, t}
  logic [RidW-1:0]    iu_rid, io2_rid, wb_rid_q, wc_rid_q, wd_rid_q, we_rid_q;
  logic [W-1:0]       wc_t_q, wd_t_q, we_t_q, wb_bt_q;
  logic [31:0]        wc_tri_q, wd_tri_q, we_tri_q, wb_btri_q;
  logic               wb_pf_q, wb_better, wb_lt_own, wb_lt_prev;
  rc_pkg::hit_commit_t wc_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      iu_v_q  <= 1'b0;
      io1_v_q <= 1'b0;
      io2_v_q <= 1'b0;
      wb_v_q  <= 1'b0;
      wc_we_q <= 1'b0;
      wd_we_q <= 1'b0;
      we_we_q <= 1'b0;
    end else begin
      iu_v_q  <= res_valid_i;
      io1_v_q <= iu_v_q;
      io2_v_q <= io1_v_q;
      wb_v_q  <= io2_v_q;
      wc_we_q <= wb_better;
      wd_we_q <= wc_we_q;
      we_we_q <= wd_we_q;
    end
  end

  assign iu_rid  = {ThrW'(iu_q.thr), iu_q.ray};
  assign io2_rid = {ThrW'(io2_q.thr), io2_q.ray};
  logic [RidW-1:0] io1_rid;
  assign io1_rid = {ThrW'(io1_q.thr), io1_q.ray};

  // The hit bit of the result's ray, sampled at the read's edge (rc_bit_read: the multiplexer by
  // {thread, ray} split by a register, within each group of 16 threads before the edge, between
  // the groups after it), given in io1.
  logic io1_hit;
  rc_bit_read #(
    .N   (Threads * 4),
    .IdxW(RidW),
    .LoW (6)
  ) u_hit_read (
    .clk_i,
    .bits_i(hit_i),
    .idx_i (iu_rid),
    .bit_o (io1_hit)
  );

  always_ff @(posedge clk_i) begin
    iu_q      <= res_i;
    io1_q     <= iu_q;
    io2_q     <= io1_q;
    io2_hit_q <= io1_hit;
  end

  // wb: the result with its ray's best; the commits the read missed (now in wc, wd, we: the
  // commits of this cycle and the two before, the read's cycle among them) are forwarded, newest
  // first. The decision being made now (wb_better, committed next cycle) is not forwarded: wb_pf_q
  // records that it is the same ray's, and the compare in wb compares against it beside the best.
  logic wb_fwd;
  logic [W-1:0]  io2_bt;
  logic [31:0]   io2_btri;
  assign io2_bt   = io2_hit_q ? bw_rd[W-1:0] : rc_pkg::CoreFpPosInf;
  assign io2_btri = io2_hit_q ? bw_rd[W +: 32] : '1;
  assign wb_fwd   = wb_v_q & (wb_rid_q == io2_rid);
  // The three forwarding decisions are registered a cycle ahead, from io1 and the stages that
  // become wc, wd and we at the next edge (wb's decision, wc, wd), so the best's multiplexer in
  // front of wb_bt_q and wb_btri_q starts from flip-flops, not from three {thread, ray} compares.
  logic wc_fwd_q, wd_fwd_q, we_fwd_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wc_fwd_q <= 1'b0;
      wd_fwd_q <= 1'b0;
      we_fwd_q <= 1'b0;
    end else begin
      wc_fwd_q <= wb_better & (wb_rid_q == io1_rid);
      wd_fwd_q <= wc_we_q & (wc_rid_q == io1_rid);
      we_fwd_q <= wd_we_q & (wd_rid_q == io1_rid);
    end
  end

  always_ff @(posedge clk_i) begin
    if (io2_v_q) begin
      wb_q      <= io2_q;
      wb_rid_q  <= io2_rid;
      wb_pf_q   <= wb_fwd;
      wb_bt_q   <= wc_fwd_q ? wc_t_q : wd_fwd_q ? wd_t_q : we_fwd_q ? we_t_q : io2_bt;
      wb_btri_q <= wc_fwd_q ? wc_tri_q : wd_fwd_q ? wd_tri_q : we_fwd_q ? we_tri_q : io2_btri;
    end
    // Loaded every cycle (only wc_we_q says whether they commit).
    wc_rid_q <= wb_rid_q;
    wc_t_q   <= wb_q.t;
    wc_tri_q <= wb_q.tri_idx;
    wc_q.thr <= wb_q.thr;
    wc_q.ray <= wb_q.ray;
    wc_q.tri_idx <= wb_q.tri_idx;
    wc_q.t   <= wb_q.t;
    wc_q.u   <= wb_q.u;
    wc_q.v   <= wb_q.v;
    wc_q.dz  <= wb_q.dz;
    wd_rid_q <= wc_rid_q;
    wd_t_q   <= wc_t_q;
    wd_tri_q <= wc_tri_q;
    we_rid_q <= wd_rid_q;
    we_t_q   <= wd_t_q;
    we_tri_q <= wd_tri_q;
  end

  // wb's two compares are made a cycle ahead, in io2, and registered with wb (run 73 seed 1:
  // wb_q through the (t, tri) compare's carry chains and wb_better into wc_fwd_q, -0.38 ns):
  // against the best wb_bt_q is loaded with (each of the four candidates compared, the
  // forwarding flags selecting the result, as they select the best), and against wb_q, whose
  // (t, tri) wc_t_q and wc_tri_q hold in wb's cycle (they follow wb_q every cycle). wb_bt_q and
  // wb_btri_q stay for the assertions (LtOwn_A, WbBest_A); synthesis drops them.
  function automatic logic lt_hit(input logic [W-1:0] t, input logic [31:0] tri_idx,
                                  input logic [W-1:0] bt, input logic [31:0] btri);
    lt_hit = (t < bt) | ((t == bt) & (tri_idx < btri));
  endfunction
  logic lt_own_q, lt_prev_q;
  always_ff @(posedge clk_i) begin
    if (io2_v_q) begin
      lt_own_q  <= wc_fwd_q ? lt_hit(io2_q.t, io2_q.tri_idx, wc_t_q, wc_tri_q) :
                   wd_fwd_q ? lt_hit(io2_q.t, io2_q.tri_idx, wd_t_q, wd_tri_q) :
                   we_fwd_q ? lt_hit(io2_q.t, io2_q.tri_idx, we_t_q, we_tri_q) :
                              lt_hit(io2_q.t, io2_q.tri_idx, io2_bt, io2_btri);
      lt_prev_q <= lt_hit(io2_q.t, io2_q.tri_idx, wb_q.t, wb_q.tri_idx);
    end
  end
  assign wb_lt_own  = lt_own_q;
  assign wb_lt_prev = lt_prev_q;
  assign wb_better  = wb_v_q & wb_q.hit & ((wb_pf_q & wc_we_q) ? wb_lt_prev : wb_lt_own);

  assign hit_valid_o   = wc_we_q;
  assign hit_thr_o     = ThrW'(wc_q.thr);
  assign hit_ray_o     = wc_q.ray;
  assign fin_valid_o   = wb_v_q & wb_q.last;
  assign fin_thr_o     = ThrW'(wb_q.thr);
  assign perf_commit_o = wc_we_q;

  ////////////
  // Copies //
  ////////////

  logic [ThrW-1:0] wc_thr;
  assign wc_thr = ThrW'(wc_q.thr);

  // The write-back's own copy and the intersection issue's: {tri, t} per {thread, ray}.
  rc_ram #(
    .Width(W + 32), .Depth(4 << ThrW), .OutReg(1'b1)
  ) u_bw (
    .clk_i,
    .we_i   (wc_we_q),
    .waddr_i(wc_rid_q),
    .wdata_i({wc_q.tri_idx, wc_q.t}),
    .re_i   (iu_v_q),
    .raddr_i(iu_rid),
    .rdata_o(bw_rd)
  );
  rc_ram #(
    .Width(W + 32), .Depth(4 << ThrW), .OutReg(1'b1)
  ) u_bi (
    .clk_i,
    .we_i   (wc_we_q),
    .waddr_i(wc_rid_q),
    .wdata_i({wc_q.tri_idx, wc_q.t}),
    .re_i   (isect_re_i),
    .raddr_i({isect_thr_i, isect_ray_i}),
    .rdata_o(isect_best_o)
  );
  // The pop unit's and the shading sequencer's: per thread, one block RAM per ray (lane r is
  // written by ray r's commits).
  for (genvar r = 0; r < 4; r++) begin : g_lanes
    rc_ram #(
      .Width(W), .Depth(1 << ThrW), .OutReg(1'b1)
    ) u_bp (
      .clk_i,
      .we_i   (wc_we_q && wc_q.ray == 2'(r)),
      .waddr_i(wc_thr),
      .wdata_i(wc_q.t),
      .re_i   (pop_re_i),
      .raddr_i(pop_thr_i),
      .rdata_o(pop_t_o[r*W +: W])
    );
    rc_ram #(
      .Width(32), .Depth(1 << ThrW), .OutReg(1'b1)
    ) u_bs (
      .clk_i,
      .we_i   (wc_we_q && wc_q.ray == 2'(r)),
      .waddr_i(wc_thr),
      .wdata_i(wc_q.tri_idx),
      .re_i   (shade_re_i),
      .raddr_i(shade_thr_i),
      .rdata_o(shade_tri_o[r*32 +: 32])
    );
  end
  // Shading's d'z and the framebuffer write's hit record, per {thread, ray}.
  rc_ram #(
    .Width(W), .Depth(4 << ThrW), .OutReg(1'b1)
  ) u_bz (
    .clk_i,
    .we_i   (wc_we_q),
    .waddr_i(wc_rid_q),
    .wdata_i(wc_q.dz),
    .re_i   (dz_re_i),
    .raddr_i({dz_thr_i, dz_ray_i}),
    .rdata_o(dz_o)
  );
  localparam int unsigned FbW = (FbDz ? 4 : 3) * W + 32;
  logic [FbW-1:0] fb_rd;
  logic [FbW-1:0] fb_wd;
  if (FbDz) begin : g_fb_dz
    assign fb_wd     = {wc_q.dz, wc_q.tri_idx, wc_q.v, wc_q.u, wc_q.t};
    assign fb_best_o = fb_rd;
  end else begin : g_fb_no_dz
    assign fb_wd     = {wc_q.tri_idx, wc_q.v, wc_q.u, wc_q.t};
    assign fb_best_o = {{W{1'b0}}, fb_rd};
  end
  rc_ram #(
    .Width(FbW), .Depth(4 << ThrW), .OutReg(1'b1)
  ) u_bf (
    .clk_i,
    .we_i   (wc_we_q),
    .waddr_i(wc_rid_q),
    .wdata_i(fb_wd),
    .re_i   (fb_re_i),
    .raddr_i({fb_thr_i, fb_ray_i}),
    .rdata_o(fb_rd)
  );

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // The forwarding decisions registered a cycle ahead are the ones io2 would compute.
  FwdAhead_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               wc_fwd_q == (wc_we_q & (wc_rid_q == io2_rid)) &&
                               wd_fwd_q == (wd_we_q & (wd_rid_q == io2_rid)) &&
                               we_fwd_q == (we_we_q & (we_rid_q == io2_rid)));
  // A shadow of the committed bests, to check the forwarding: every commit improves its ray's
  // committed best, and the compare sees the ray's best as it will be after this cycle's commit.
  logic [W-1:0]  sh_t   [0:(4 << ThrW)-1];
  logic [31:0]   sh_tri [0:(4 << ThrW)-1];
  always_ff @(posedge clk_i) begin
    if (wc_we_q) begin
      sh_t[wc_rid_q]   <= wc_q.t;
      sh_tri[wc_rid_q] <= wc_q.tri_idx;
    end
  end
  logic [(4 << ThrW)-1:0] hit_all;
  assign hit_all = (4 << ThrW)'(hit_i);
  logic [W-1:0]  wc_old_t, wb_now_t, wb_eff_t;
  logic [31:0]   wc_old_tri, wb_now_tri, wb_eff_tri;
  logic          wb_same_c;
  assign wc_old_t   = hit_all[wc_rid_q] ? sh_t[wc_rid_q] : rc_pkg::CoreFpPosInf;
  assign wc_old_tri = hit_all[wc_rid_q] ? sh_tri[wc_rid_q] : '1;
  WbForward_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                wc_we_q |-> lt_hit(wc_q.t, wc_q.tri_idx, wc_old_t, wc_old_tri));
  assign wb_now_t   = hit_all[wb_rid_q] ? sh_t[wb_rid_q] : rc_pkg::CoreFpPosInf;
  assign wb_now_tri = hit_all[wb_rid_q] ? sh_tri[wb_rid_q] : '1;
  assign wb_same_c  = wc_we_q && wc_rid_q == wb_rid_q;
  assign wb_eff_t   = (wb_pf_q && wc_we_q) ? wc_t_q : wb_bt_q;
  assign wb_eff_tri = (wb_pf_q && wc_we_q) ? wc_tri_q : wb_btri_q;
  // The compares made in io2 are wb's own: against the best and against wc's (t, tri).
  LtOwn_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            wb_v_q |-> wb_lt_own == lt_hit(wb_q.t, wb_q.tri_idx, wb_bt_q,
                                                           wb_btri_q) &&
                                       wb_lt_prev == lt_hit(wb_q.t, wb_q.tri_idx, wc_t_q,
                                                            wc_tri_q));
  WbBest_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             wb_v_q |-> (wb_pf_q && wc_we_q) == wb_same_c &&
                                        wb_eff_t == (wb_same_c ? wc_t_q : wb_now_t) &&
                                        wb_eff_tri == (wb_same_c ? wc_tri_q : wb_now_tri));
`endif

endmodule
