// rc_fp_to_u8: a format value to an 8-bit colour channel (docs/architecture.md, "Shading").
//
// Contract
// - Function: exactly rc::to_u8() (tb/golden/trace.hpp), bit for bit:
//     v = max(x_i, +0)                    (format max: canonical NaN if x_i is NaN)
//     if v is NaN: byte_o = 0
//     else: v = min(v, 1.0) * 255.0       (format min and multiply; v is then in [+0, 255])
//           byte_o = v rounded to the nearest integer, ties to even
// - Handshake: valid only, no backpressure. valid_o is valid_i delayed by exactly its latency;
//   byte_o belongs to the input presented that many cycles earlier and is meaningful only while
//   valid_o is 1. A new value may be presented every cycle.
// - Latency: 2 * FpStagesCmp + FpStagesMul + 1 cycles (max · min · multiply · round; 7 at the
//   defaults of docs/spec.toml [fp_stages]).
// - Parameters: ExpW, FracW: the number format (default fp24). FracW >= 7 is required (255.0
//   needs 8 significant bits) and ExpW >= 4 (255.0 must be a normal number); any other
//   parameterisation is illegal and stops elaboration.
// - Illegal input: none; every bit pattern of x_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears only the valid pipeline; data registers have
//   no reset.
module rc_fp_to_u8 #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  input  logic [ExpW+FracW:0] x_i,
  output logic                valid_o,
  output logic [7:0]          byte_o
);

  ////////////////
  // Parameters //
  ////////////////

  if (FracW < 7 || ExpW < 4) begin : g_param_check
    $error("rc_fp_to_u8: need FracW >= 7 and ExpW >= 4 (255.0 must be a normal number)");
  end

  localparam int unsigned W         = 1 + ExpW + FracW;
  localparam int unsigned CmpStages = rc_pkg::FpStagesCmp;
  localparam int unsigned MulStages = rc_pkg::FpStagesMul;
  localparam int unsigned NanDly    = CmpStages + MulStages;  // NaN flag: after max to round
  localparam int unsigned FxW       = FracW + 9;              // 8 integer bits . FracW+1 bits

  localparam int unsigned       BiasInt = (1 << (ExpW - 1)) - 1;
  localparam logic [ExpW-1:0]   Bias    = ExpW'(BiasInt);
  localparam logic [ExpW-1:0]   HalfExp = ExpW'(BiasInt - 1);  // exponent field of [0.5, 1)
  localparam logic [W-1:0]      PosZero = '0;
  localparam logic [W-1:0]      One     = {1'b0, Bias, {FracW{1'b0}}};
  // 255.0 = 1.1111111b x 2^7
  localparam logic [W-1:0]      C255    = {1'b0, ExpW'(BiasInt + 7), FracW'(7'h7f) << (FracW - 7)};

  ////////////////////////////////////////
  // Stage 1: v = max(x, +0), NaN check //
  ////////////////////////////////////////

  logic         max_valid;
  logic [W-1:0] v_max;
  logic         unused_max_lt, unused_max_le, unused_max_eq;
  logic [W-1:0] unused_max_min;

  rc_fp_cmp #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(CmpStages)
  ) u_max (
    .clk_i,
    .rst_ni,
    .valid_i,
    .a_i    (x_i),
    .b_i    (PosZero),
    .valid_o(max_valid),
    .lt_o   (unused_max_lt),
    .le_o   (unused_max_le),
    .eq_o   (unused_max_eq),
    .min_o  (unused_max_min),
    .max_o  (v_max)
  );

  logic v_nan;
  assign v_nan = (&v_max[W-2 -: ExpW]) & (|v_max[FracW-1:0]);

  logic [NanDly-1:0] nan_q;
  always_ff @(posedge clk_i) begin
    nan_q[0] <= v_nan;
    for (int unsigned i = 1; i < NanDly; i++) nan_q[i] <= nan_q[i-1];
  end

  ////////////////////////////////////////
  // Stage 2: v = min(v, 1.0)           //
  ////////////////////////////////////////

  logic         min_valid;
  logic [W-1:0] v_min;
  logic         unused_min_lt, unused_min_le, unused_min_eq;
  logic [W-1:0] unused_min_max;

  rc_fp_cmp #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(CmpStages)
  ) u_min (
    .clk_i,
    .rst_ni,
    .valid_i(max_valid),
    .a_i    (v_max),
    .b_i    (One),
    .valid_o(min_valid),
    .lt_o   (unused_min_lt),
    .le_o   (unused_min_le),
    .eq_o   (unused_min_eq),
    .min_o  (v_min),
    .max_o  (unused_min_max)
  );

  ////////////////////////////////////////
  // Stage 3: v * 255.0                 //
  ////////////////////////////////////////

  logic         mul_valid;
  logic [W-1:0] p;

  rc_fp_mul #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(MulStages)
  ) u_mul (
    .clk_i,
    .rst_ni,
    .valid_i(min_valid),
    .a_i    (v_min),
    .b_i    (C255),
    .valid_o(mul_valid),
    .res_o  (p)
  );

  //////////////////////////////////////////////////////////
  // Stage 4: round to the nearest integer, ties to even  //
  //////////////////////////////////////////////////////////

  // p is +0 or a normal number in [2^-(Bias-1), 255] (never NaN or inf unless v was NaN).
  // p = 2^k x 1.f with k = e - Bias; for k >= -1 the fixed-point value fx = {1, f} << (k + 1)
  // has 8 integer bits and FracW + 1 fraction bits; below 0.5 (k < -1, or zero) the byte is 0.
  logic [ExpW-1:0] p_exp;
  logic [FracW-1:0] p_frac;
  logic [ExpW-1:0] sh_full;
  logic [3:0]      sh;
  logic [FxW-1:0]  fx;
  logic [7:0]      ip;
  logic            half, sticky, round_up, below_half;
  logic [7:0]      ip_inc, rounded;
  logic [7:0]      byte_d;

  assign p_exp      = p[W-2 -: ExpW];
  assign p_frac     = p[FracW-1:0];
  assign below_half = p_exp < HalfExp;  // includes the zero exponent
  assign sh_full    = p_exp - HalfExp;  // k + 1, in 0 .. 8 when not below_half
  assign sh         = sh_full[3:0];
  assign fx         = FxW'({1'b1, p_frac}) << sh;
  assign ip         = fx[FxW-1 -: 8];
  assign half       = fx[FracW];
  assign sticky     = |fx[FracW-1:0];
  assign round_up   = half & (sticky | ip[0]);
  // ip + 1 is made beside the sticky bit and the round decision only selects it, so no carry
  // chain follows the sticky OR (run 61 seeds 1 and 3: u_to_u8 -> byte_q, -0.35 and -0.47 ns).
  // (ip = 255 never rounds up: p <= 255, InRange_A.)
  assign ip_inc     = ip + 8'd1;
  assign rounded    = round_up ? ip_inc : ip;
  assign byte_d     = (nan_q[NanDly-1] | below_half) ? 8'd0 : rounded;

  logic [7:0] byte_q;
  logic       valid_q;
  always_ff @(posedge clk_i) begin
    byte_q <= byte_d;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= 1'b0;
    end else begin
      valid_q <= mul_valid;
    end
  end
  assign valid_o = valid_q;
  assign byte_o  = byte_q;

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

  // min(max(x, 0), 1) * 255 is at most 255, so the shift never exceeds 8 and rounding never
  // carries out of the byte; a NaN can only come from a NaN v.
  InRange_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              mul_valid && !nan_q[NanDly-1] && !below_half |->
                              sh_full <= ExpW'(8) && !(round_up && ip == 8'hff));
  // v >= +0 (max with +0 turns -0 into +0) and the canonical NaN is positive, so p has no sign.
  PositiveProduct_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                      mul_valid |-> !p[W-1]);
  // The output qualifies with valid_o, so it must be known once out of reset.
  ValidKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !$isunknown(valid_o));
  ByteKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                valid_o |-> !$isunknown(byte_o));
`endif

endmodule
