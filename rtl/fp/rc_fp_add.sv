// rc_fp_add: pipelined floating-point adder/subtractor for the raycore number format.
//
// Contract
// - Function: res_o = a_i + b_i when sub_i = 0, res_o = a_i - b_i when sub_i = 1, correctly
//   rounded, bit-exact with rc::Fp<ExpW, FracW>::operator+ / operator- (tb/fp/fp.hpp).
// - Handshake: valid only, no backpressure. valid_o is valid_i delayed by exactly Stages cycles;
//   res_o belongs to the inputs presented Stages cycles earlier and is meaningful only while
//   valid_o is 1. A new operation may be presented every cycle.
// - Latency: Stages cycles (Stages >= 1, checked at elaboration).
// - Parameters: ExpW exponent bits (>= 2), FracW fraction bits (>= 1); a word is
//   {sign, exp[ExpW-1:0], frac[FracW-1:0]}. Stages = latency in cycles.
// - Illegal input: none; every bit pattern of a_i, b_i and sub_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears only the valid pipeline; data registers have
//   no reset.
// - Format rules implemented: an exponent field of 0 reads as signed zero whatever the fraction
//   (flush-to-zero inputs); exp all ones with frac 0 is +-inf, with frac != 0 NaN; any NaN input,
//   and inf - inf, give the canonical NaN (sign 0, exp all ones, frac MSB only); rounding is to
//   nearest, ties to even, with an unbounded exponent, and only then a biased exponent <= 0
//   flushes to signed zero and one >= all ones overflows to signed infinity; an exact zero sum is
//   +0 except (-0) + (-0) = -0; a flushed or overflowed result keeps the sign of the exact result.
//
// Pipeline (three combinational segments; the registers sit at the cuts between them):
//   segment 0: unpack, classify, order the operands by magnitude, align the smaller significand
//              (guard, round and sticky bits)
//   segment 1: significand add or subtract, leading-zero count
//   segment 2: normalise, round to nearest even, exponent adjust, flush/overflow, pack
//   Stages = 1: one register at the output. Stages = 2: cut segment 1 | segment 2, plus the output
//   register. Stages >= 3: both cuts, plus Stages - 2 registers at the output.
module rc_fp_add #(
  parameter int unsigned ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW  = rc_pkg::Fp24FracW,
  parameter int unsigned Stages = 3
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  input  logic                sub_i,
  input  logic [ExpW+FracW:0] a_i,
  input  logic [ExpW+FracW:0] b_i,
  output logic                valid_o,
  output logic [ExpW+FracW:0] res_o
);

  ////////////////
  // Parameters //
  ////////////////

  if (Stages < 1) begin : g_stages_check
    $error("rc_fp_add: Stages must be >= 1 (it is the latency in cycles)");
  end
  if (ExpW < 2 || FracW < 1) begin : g_width_check
    $error("rc_fp_add: need ExpW >= 2 and FracW >= 1");
  end

  localparam int unsigned W     = 1 + ExpW + FracW;  // word width
  localparam int unsigned MagW  = ExpW + FracW;      // {exp, frac}
  localparam int unsigned ManW  = FracW + 1;         // significand with the hidden bit
  localparam int unsigned AlnW  = ManW + 3;          // significand, guard, round, sticky
  localparam int unsigned SumW  = AlnW + 1;          // plus the carry out
  localparam int unsigned LzW   = $clog2(SumW + 1);  // leading-zero count 0..SumW
  // Unbounded result exponent, two's complement: holds -(SumW) .. 2^ExpW.
  localparam int unsigned ExW   = ((ExpW > LzW) ? ExpW : LzW) + 2;

  // Cut placement (see the header).
  localparam bit          Cut1    = Stages >= 3;  // between segment 0 and segment 1
  localparam bit          Cut2    = Stages >= 2;  // between segment 1 and segment 2
  localparam int unsigned OutRegs = Stages - 32'(Cut1) - 32'(Cut2);

  ///////////////////////////////
  // Segment 0: order, align   //
  ///////////////////////////////

  logic            a_sign, b_sign;
  logic [ExpW-1:0] a_exp, b_exp;
  logic            a_zero, b_zero, a_nan, b_nan, a_inf, b_inf;
  logic [MagW-1:0] a_mag, b_mag, big_mag, small_mag;
  logic            swap;
  logic            big_sign_s0, eff_sub_s0, zero_sign_s0, spec_nan_s0, spec_inf_s0;
  logic [ExpW-1:0] big_exp_s0, small_exp, exp_diff;
  logic [ManW-1:0] big_man_s0, small_man;
  logic [ManW+1:0] small_ext, small_shifted;
  logic            small_sticky;
  logic [AlnW-1:0] small_aln_s0;

  assign a_sign = a_i[W-1];
  assign b_sign = b_i[W-1] ^ sub_i;  // the effective sign of the second operand
  assign a_exp  = a_i[W-2 -: ExpW];
  assign b_exp  = b_i[W-2 -: ExpW];
  assign a_zero = ~|a_exp;
  assign b_zero = ~|b_exp;
  assign a_nan  = (&a_exp) & (|a_i[FracW-1:0]);
  assign b_nan  = (&b_exp) & (|b_i[FracW-1:0]);
  assign a_inf  = (&a_exp) & ~(|a_i[FracW-1:0]);
  assign b_inf  = (&b_exp) & ~(|b_i[FracW-1:0]);
  // Magnitudes with zero-exponent encodings read as exact zero.
  assign a_mag  = a_zero ? '0 : a_i[MagW-1:0];
  assign b_mag  = b_zero ? '0 : b_i[MagW-1:0];

  assign swap         = b_mag > a_mag;
  assign big_mag      = swap ? b_mag : a_mag;
  assign small_mag    = swap ? a_mag : b_mag;
  assign big_sign_s0  = swap ? b_sign : a_sign;
  assign big_exp_s0   = big_mag[MagW-1 -: ExpW];
  assign small_exp    = small_mag[MagW-1 -: ExpW];
  assign big_man_s0   = {|big_exp_s0, big_mag[FracW-1:0]};
  assign small_man    = {|small_exp, small_mag[FracW-1:0]};
  assign exp_diff     = big_exp_s0 - small_exp;

  // Align: shift the smaller significand right by the exponent difference, keeping two extra
  // bits (guard, round) and ORing everything shifted out beyond them into a sticky bit. A shift
  // of the full width or more yields 0 (and a sticky of |small_man), as the operators define.
  assign small_ext     = {small_man, 2'b00};
  assign small_shifted = small_ext >> exp_diff;
  assign small_sticky  = |(small_ext & ~({(ManW + 2){1'b1}} << exp_diff));
  assign small_aln_s0  = {small_shifted, small_sticky};

  assign eff_sub_s0   = a_sign ^ b_sign;
  assign zero_sign_s0 = a_sign & b_sign;  // sign of an exact zero sum (round to nearest)
  assign spec_nan_s0  = a_nan | b_nan | (a_inf & b_inf & eff_sub_s0);
  assign spec_inf_s0  = a_inf | b_inf;    // an infinity is always the bigger operand

  ////////////////
  // Cut 1      //
  ////////////////

  localparam int unsigned S1W = 5 + ExpW + ManW + AlnW;
  logic [S1W-1:0] s1_d, s1_q;
  logic           spec_nan_s1, spec_inf_s1, big_sign_s1, eff_sub_s1, zero_sign_s1;
  logic [ExpW-1:0] big_exp_s1;
  logic [ManW-1:0] big_man_s1;
  logic [AlnW-1:0] small_aln_s1;

  assign s1_d = {spec_nan_s0, spec_inf_s0, big_sign_s0, eff_sub_s0, zero_sign_s0, big_exp_s0,
                 big_man_s0, small_aln_s0};
  if (Cut1) begin : g_cut1
    always_ff @(posedge clk_i) begin
      s1_q <= s1_d;
    end
  end else begin : g_no_cut1
    assign s1_q = s1_d;
  end
  assign {spec_nan_s1, spec_inf_s1, big_sign_s1, eff_sub_s1, zero_sign_s1, big_exp_s1,
          big_man_s1, small_aln_s1} = s1_q;

  ///////////////////////////////////////////
  // Segment 1: add, leading-zero count    //
  ///////////////////////////////////////////

  logic [SumW-1:0] big_al, small_al, sum_s1;
  logic [LzW-1:0]  lz_s1;

  assign big_al   = {1'b0, big_man_s1, 3'b000};
  assign small_al = {1'b0, small_aln_s1};
  assign sum_s1   = eff_sub_s1 ? (big_al - small_al) : (big_al + small_al);

  // Priority encoder; the highest set bit wins. lz = SumW means the sum is exactly zero.
  always_comb begin
    lz_s1 = LzW'(SumW);
    for (int i = 0; i < SumW; i++) begin
      if (sum_s1[i]) begin
        lz_s1 = LzW'(SumW - 1 - i);
      end
    end
  end

  ////////////////
  // Cut 2      //
  ////////////////

  localparam int unsigned S2W = 4 + ExpW + SumW + LzW;
  logic [S2W-1:0]  s2_d, s2_q;
  logic            spec_nan_s2, spec_inf_s2, big_sign_s2, zero_sign_s2;
  logic [ExpW-1:0] big_exp_s2;
  logic [SumW-1:0] sum_s2;
  logic [LzW-1:0]  lz_s2;

  assign s2_d = {spec_nan_s1, spec_inf_s1, big_sign_s1, zero_sign_s1, big_exp_s1, sum_s1, lz_s1};
  if (Cut2) begin : g_cut2
    always_ff @(posedge clk_i) begin
      s2_q <= s2_d;
    end
  end else begin : g_no_cut2
    assign s2_q = s2_d;
  end
  assign {spec_nan_s2, spec_inf_s2, big_sign_s2, zero_sign_s2, big_exp_s2, sum_s2, lz_s2} = s2_q;

  //////////////////////////////////////////////
  // Segment 2: normalise, round, pack        //
  //////////////////////////////////////////////

  logic [SumW-1:0] norm;
  logic [ManW-1:0] man;
  logic            round_bit, sticky_bit, round_up, sum_zero;
  logic [ExW-1:0]  exp_norm;
  logic [W-1:0]    res_d;

  assign norm       = sum_s2 << lz_s2;  // leading one to the top bit
  assign man        = norm[SumW-1 -: ManW];
  assign round_bit  = norm[3];
  assign sticky_bit = |norm[2:0];
  assign round_up   = round_bit & (sticky_bit | man[0]);
  // The leading one of the sum sits at bit SumW-2 for an unshifted big operand, so the result
  // exponent is big_exp + 1 - lz (rc_fp_round_pack adds one when rounding carries out).
  assign exp_norm   = ExW'(big_exp_s2) + ExW'(1) - ExW'(lz_s2);
  // An exact zero sum has exp_norm <= big_exp - 5 < all ones and no rounding carry, so gating
  // the overflow with zero_i inside rc_fp_round_pack changes nothing here.
  assign sum_zero   = lz_s2 == LzW'(SumW);

  rc_fp_round_pack #(
    .ExpW (ExpW),
    .FracW(FracW),
    .ExW  (ExW)
  ) u_round_pack (
    .nan_i      (spec_nan_s2),
    .inf_i      (spec_inf_s2),
    .zero_i     (sum_zero),
    .zero_sign_i(zero_sign_s2),
    .sign_i     (big_sign_s2),
    .exp_i      (exp_norm),
    .man_i      (man),
    .round_up_i (round_up),
    .res_o      (res_d)
  );

  ///////////////////////////////
  // Output and valid pipeline //
  ///////////////////////////////

  rc_pipe_out #(
    .Width   (W),
    .DataRegs(OutRegs),
    .Stages  (Stages)
  ) u_out (
    .clk_i,
    .rst_ni,
    .valid_i,
    .data_i (res_d),
    .valid_o,
    .data_o (res_o)
  );

endmodule
