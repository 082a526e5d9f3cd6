// rc_ray_setup: ray set-up of one ray (docs/architecture.md, "Ray set-up"): the reciprocal
// direction and the ray's interval clipped to the root box.
//
// Contract
// - Function: exactly rc::setup_ray() (tb/golden/trace.hpp), bit for bit. Axis index a: 0 = x,
//   1 = y, 2 = z. Vector ports hold element i at [i*W +: W] (W = 1 + ExpW + FracW; the layout
//   of a packed [N][W] array, kept flat because Yosys 0.23 reads no multi-dimensional packed
//   arrays): org_i[a], dir_i[a], inv_o[a]; bounds_i[a] = lo[a], bounds_i[a + 3] = hi[a].
//     inv_o[a] = 1.0 / dir_i[a]                                       (format division)
//     tmin = +0, tmax = +inf
//     for a = x, y, z in that order:
//       t0 = (lo[a] - org_i[a]) * inv[a],  t1 = (hi[a] - org_i[a]) * inv[a]
//       if t0 or t1 is NaN: the axis is skipped
//       else: tmin = max(tmin, min(t0, t1)),  tmax = min(tmax, max(t0, t1))   (format min/max)
//     tmin_o = tmin, tmax_o = tmax, active_o = le(tmin, tmax)
//   The max/min chain is evaluated in exactly this order and with these operands. (The start
//   value +0 matters for the bits: max(-0, x) would give -0 for x <= -0. The axis order does
//   not: the format's min/max are the infimum/supremum of a total order with -0 below +0, and a
//   NaN t0/t1 skips the axis, so any order gives the same bits; tests/core/units checked this.)
// - Handshake: valid_i/ready_o in, valid_o/ready_i out, with backpressure. An operation is taken
//   when valid_i & ready_o. ready_o comes from a register (credits, see rc_credit_fifo) and never
//   depends on valid_i or ready_i; valid_o never depends on ready_i. Results leave in order;
//   nothing is dropped or duplicated. tag_i travels with the operation to tag_o.
// - Latency: 19 cycles from the taking edge to valid_o (divide 11, with the subtracts in parallel
//   · multiply 2 · min/max of t0, t1: 1 · x, y, z max/min chain: 3 x 1 · le: 1 · output FIFO 1),
//   when the FIFO is empty and ready_i is 1.
// - Throughput: one ray per cycle while ready_i is 1 (the FIFO holds Latency + 1 entries, enough
//   credits for every operation in flight).
// - Parameters: ExpW, FracW: the number format (default fp24); TagW: tag bits (>= 1).
// - Illegal input: none; every bit pattern of the data inputs is legal.
// - Reset: rst_ni (active low, asynchronous) clears control state only (valid chains, FIFO
//   pointers and credit count); data registers have no reset.
module rc_ray_setup #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW,
  parameter int unsigned TagW  = 8
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  // Input handshake.
  input  logic                     valid_i,
  output logic                     ready_o,
  input  logic [TagW-1:0]          tag_i,
  input  logic [3*(ExpW+FracW+1)-1:0] org_i,     // x, y, z
  input  logic [3*(ExpW+FracW+1)-1:0] dir_i,     // x, y, z
  input  logic [6*(ExpW+FracW+1)-1:0] bounds_i,  // lo x, y, z, hi x, y, z
  // Output handshake.
  output logic                     valid_o,
  input  logic                     ready_i,
  output logic [TagW-1:0]          tag_o,
  output logic [3*(ExpW+FracW+1)-1:0] inv_o,     // x, y, z
  output logic [ExpW+FracW:0]      tmin_o,
  output logic [ExpW+FracW:0]      tmax_o,
  output logic                     active_o
);

  ////////////////
  // Parameters //
  ////////////////

  if (TagW < 1 || ExpW < 2 || FracW < 1) begin : g_param_check
    $error("rc_ray_setup: need TagW >= 1, ExpW >= 2 and FracW >= 1");
  end

  localparam int unsigned W         = 1 + ExpW + FracW;
  // Latencies of the fp units: the rc_fp_* defaults, both from docs/spec.toml [fp_stages].
  localparam int unsigned DivStages = rc_pkg::FpStagesDiv;
  localparam int unsigned SubStages = DivStages;  // the subtracts run beside the divides
  localparam int unsigned MulStages = rc_pkg::FpStagesMul;
  localparam int unsigned CmpStages = rc_pkg::FpStagesCmp;
  // take -> FIFO write: divide, multiply, min/max(t0, t1), three chain steps, le.
  localparam int unsigned PipeLat   = DivStages + MulStages + 5 * CmpStages;
  localparam int unsigned FifoDepth = PipeLat + 2;  // full throughput
  localparam int unsigned InvDly    = PipeLat - DivStages;  // inv from the divider to the FIFO
  localparam int unsigned OutW      = TagW + 3 * W + 2 * W + 1;

  localparam logic [ExpW-1:0] Bias    = ExpW'((1 << (ExpW - 1)) - 1);
  localparam logic [W-1:0]    One     = {1'b0, Bias, {FracW{1'b0}}};
  localparam logic [W-1:0]    PosZero = '0;
  localparam logic [W-1:0]    PosInf  = {1'b0, {ExpW{1'b1}}, {FracW{1'b0}}};

  // NaN test on the magnitude bits {exp, frac} (the sign does not matter).
  function automatic logic is_nan(logic [W-2:0] mag);
    is_nan = (&mag[W-2 -: ExpW]) & (|mag[FracW-1:0]);
  endfunction

  logic take;
  assign take = valid_i & ready_o;

  /////////////////////////////////////////////////////
  // Stage 1: inv = 1 / dir, lo - org, hi - org      //
  /////////////////////////////////////////////////////

  logic [2:0]     div_valid;
  logic [3*W-1:0] inv, dlo, dhi;
  logic [2:0]        unused_sub_lo_valid, unused_sub_hi_valid;

  for (genvar a = 0; a < 3; a++) begin : g_axis_in
    rc_fp_div #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(DivStages)
    ) u_div (
      .clk_i,
      .rst_ni,
      .valid_i(take),
      .a_i    (One),
      .b_i    (dir_i[a*W +: W]),
      .valid_o(div_valid[a]),
      .res_o  (inv[a*W +: W])
    );

    rc_fp_add #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(SubStages)
    ) u_sub_lo (
      .clk_i,
      .rst_ni,
      .valid_i(take),
      .sub_i  (1'b1),
      .a_i    (bounds_i[a*W +: W]),
      .b_i    (org_i[a*W +: W]),
      .valid_o(unused_sub_lo_valid[a]),
      .res_o  (dlo[a*W +: W])
    );

    rc_fp_add #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(SubStages)
    ) u_sub_hi (
      .clk_i,
      .rst_ni,
      .valid_i(take),
      .sub_i  (1'b1),
      .a_i    (bounds_i[(a+3)*W +: W]),
      .b_i    (org_i[a*W +: W]),
      .valid_o(unused_sub_hi_valid[a]),
      .res_o  (dhi[a*W +: W])
    );
  end

  // The tag travels the whole pipeline.
  logic [PipeLat*TagW-1:0] tag_q;
  always_ff @(posedge clk_i) begin
    tag_q <= (tag_q << TagW) | (PipeLat*TagW)'(tag_i);
  end

  // inv from the divider output to the FIFO.
  logic [InvDly*3*W-1:0] inv_q;
  always_ff @(posedge clk_i) begin
    inv_q <= (inv_q << (3*W)) | (InvDly*3*W)'(inv);
  end

  ///////////////////////////////////////////////
  // Stage 2: t0 = dlo * inv, t1 = dhi * inv   //
  ///////////////////////////////////////////////

  logic [2:0]     mul_valid, unused_mul_hi_valid;
  logic [3*W-1:0] t0, t1;
  logic [2:0]     skip_m;  // t0 or t1 is NaN: the axis does not restrict the ray

  for (genvar a = 0; a < 3; a++) begin : g_axis_mul
    rc_fp_mul #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(MulStages)
    ) u_mul_lo (
      .clk_i,
      .rst_ni,
      .valid_i(div_valid[a]),
      .a_i    (dlo[a*W +: W]),
      .b_i    (inv[a*W +: W]),
      .valid_o(mul_valid[a]),
      .res_o  (t0[a*W +: W])
    );

    rc_fp_mul #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(MulStages)
    ) u_mul_hi (
      .clk_i,
      .rst_ni,
      .valid_i(div_valid[a]),
      .a_i    (dhi[a*W +: W]),
      .b_i    (inv[a*W +: W]),
      .valid_o(unused_mul_hi_valid[a]),
      .res_o  (t1[a*W +: W])
    );

    assign skip_m[a] = is_nan(t0[a*W +: W-1]) | is_nan(t1[a*W +: W-1]);
  end

  //////////////////////////////////////////////////
  // Stage 3: min(t0, t1), max(t0, t1) per axis   //
  //////////////////////////////////////////////////

  logic [2:0]     mm_valid;
  logic [3*W-1:0] mn, mx;
  logic [2:0]        unused_mm_lt, unused_mm_le, unused_mm_eq;

  for (genvar a = 0; a < 3; a++) begin : g_axis_mm
    rc_fp_cmp #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(CmpStages)
    ) u_mm (
      .clk_i,
      .rst_ni,
      .valid_i(mul_valid[a]),
      .a_i    (t0[a*W +: W]),
      .b_i    (t1[a*W +: W]),
      .valid_o(mm_valid[a]),
      .lt_o   (unused_mm_lt[a]),
      .le_o   (unused_mm_le[a]),
      .eq_o   (unused_mm_eq[a]),
      .min_o  (mn[a*W +: W]),
      .max_o  (mx[a*W +: W])
    );
  end

  // The skip flags beside the min/max compare.
  logic [CmpStages*3-1:0] skip_mm_q;
  logic [2:0]             skip_mm;
  always_ff @(posedge clk_i) begin
    skip_mm_q <= (skip_mm_q << 3) | (CmpStages*3)'(skip_m);
  end
  assign skip_mm = skip_mm_q[CmpStages*3-1 -: 3];

  /////////////////////////////////////////////////////////////
  // Stage 4: the chain, x then y then z (one step per axis) //
  /////////////////////////////////////////////////////////////

  // lo_c/hi_c[a*W +: W]: the interval entering step a; [3*W +: W]: the final interval.
  localparam int unsigned AxW = 2 * W + 1;  // {mn, mx, skip} of one axis
  logic [4*W-1:0] lo_c, hi_c;
  logic [3:0]     step_valid;
  assign lo_c[0 +: W]  = PosZero;
  assign hi_c[0 +: W]  = PosInf;
  assign step_valid[0] = mm_valid[0];

  for (genvar a = 0; a < 3; a++) begin : g_chain
    logic [W-1:0] mn_a, mx_a, max_res, min_res;
    logic         skip_a;
    logic         unused_max_valid, unused_max_lt, unused_max_le, unused_max_eq;
    logic         unused_min_lt, unused_min_le, unused_min_eq;
    logic [W-1:0] unused_max_min, unused_min_max;

    // Axis a's {mn, mx, skip} wait a x CmpStages cycles for their chain step.
    logic [AxW-1:0] ax_d, ax_a;
    assign ax_d = {mn[a*W +: W], mx[a*W +: W], skip_mm[a]};
    if (a == 0) begin : g_no_wait
      assign ax_a = ax_d;
    end else begin : g_wait
      localparam int unsigned Dly = a * CmpStages;
      logic [Dly*AxW-1:0] ax_q;
      always_ff @(posedge clk_i) begin
        ax_q <= (ax_q << AxW) | (Dly*AxW)'(ax_d);
      end
      assign ax_a = ax_q[Dly*AxW-1 -: AxW];
    end
    assign {mn_a, mx_a, skip_a} = ax_a;

    // tmin = max(tmin, min(t0, t1))
    rc_fp_cmp #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(CmpStages)
    ) u_max (
      .clk_i,
      .rst_ni,
      .valid_i(step_valid[a]),
      .a_i    (lo_c[a*W +: W]),
      .b_i    (mn_a),
      .valid_o(unused_max_valid),
      .lt_o   (unused_max_lt),
      .le_o   (unused_max_le),
      .eq_o   (unused_max_eq),
      .min_o  (unused_max_min),
      .max_o  (max_res)
    );

    // tmax = min(tmax, max(t0, t1))
    rc_fp_cmp #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(CmpStages)
    ) u_min (
      .clk_i,
      .rst_ni,
      .valid_i(step_valid[a]),
      .a_i    (hi_c[a*W +: W]),
      .b_i    (mx_a),
      .valid_o(step_valid[a + 1]),
      .lt_o   (unused_min_lt),
      .le_o   (unused_min_le),
      .eq_o   (unused_min_eq),
      .min_o  (min_res),
      .max_o  (unused_min_max)
    );

    // The incoming interval and the skip flag beside the compares.
    logic [CmpStages*AxW-1:0] keep_q;
    logic [W-1:0]             lo_keep, hi_keep;
    logic                     skip_keep;
    always_ff @(posedge clk_i) begin
      keep_q <= (keep_q << AxW) | (CmpStages*AxW)'({lo_c[a*W +: W], hi_c[a*W +: W], skip_a});
    end
    assign {lo_keep, hi_keep, skip_keep} = keep_q[CmpStages*AxW-1 -: AxW];

    assign lo_c[(a+1)*W +: W] = skip_keep ? lo_keep : max_res;
    assign hi_c[(a+1)*W +: W] = skip_keep ? hi_keep : min_res;
  end

  ///////////////////////////////////
  // Stage 5: active = le(tmin, tmax) //
  ///////////////////////////////////

  logic         le_valid, active;
  logic         unused_le_lt, unused_le_eq;
  logic [W-1:0] unused_le_min, unused_le_max;

  rc_fp_cmp #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(CmpStages)
  ) u_le (
    .clk_i,
    .rst_ni,
    .valid_i(step_valid[3]),
    .a_i    (lo_c[3*W +: W]),
    .b_i    (hi_c[3*W +: W]),
    .valid_o(le_valid),
    .lt_o   (unused_le_lt),
    .le_o   (active),
    .eq_o   (unused_le_eq),
    .min_o  (unused_le_min),
    .max_o  (unused_le_max)
  );

  logic [CmpStages*2*W-1:0] fin_q;
  logic [W-1:0]             tmin_f, tmax_f;
  always_ff @(posedge clk_i) begin
    fin_q <= (fin_q << (2*W)) | (CmpStages*2*W)'({lo_c[3*W +: W], hi_c[3*W +: W]});
  end
  assign {tmin_f, tmax_f} = fin_q[CmpStages*2*W-1 -: 2*W];

  /////////////////////////////
  // Output FIFO and credits //
  /////////////////////////////

  rc_credit_fifo #(
    .Width(OutW),
    .Depth(FifoDepth)
  ) u_fifo (
    .clk_i,
    .rst_ni,
    .take_i    (take),
    .credit_o  (ready_o),
    .wr_valid_i(le_valid),
    .wr_data_i ({tag_q[PipeLat*TagW-1 -: TagW], inv_q[InvDly*3*W-1 -: 3*W], tmin_f, tmax_f,
                 active}),
    .valid_o,
    .ready_i,
    .data_o    ({tag_o, inv_o, tmin_o, tmax_o, active_o})
  );

  ////////////////
  // Assertions //
  ////////////////

`ifndef SYNTHESIS
  // Simulation-only: 1 from the first clock edge after a reset (rc_checks_on).
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  // The three axes' units run in lock step; their valid chains must agree.
  AxesLockStep_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   (&div_valid == |div_valid) && (&mm_valid == |mm_valid));
  // The divider and the subtracts are aligned (same Stages), so their results meet.
  SubDivAligned_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    div_valid == unused_sub_lo_valid &&
                                    div_valid == unused_sub_hi_valid);
  // tmin starts at +0 and only grows through non-NaN values, so it is never NaN.
  TminNotNan_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 le_valid |-> !is_nan(tmin_f[W-2:0]) && !is_nan(tmax_f[W-2:0]));
  // ready_o must be known once out of reset (upstream acts on it).
  ReadyKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !$isunknown(ready_o));
`endif

endmodule
