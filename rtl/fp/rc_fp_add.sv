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
// Pipeline (six combinational segments; a register may sit at each of the five cuts between
// them):
//   segment 0: unpack, classify, compare the magnitudes, order the operands, exponent difference
//              (saturated to the shifter's width)                                   | cut K1
//   segment 1: align the smaller significand (guard, round and sticky bits)          | cut K2
//   segment 2: significand add or subtract                                            | cut K3
//   segment 3: leading-zero count                                                     | cut K4
//   segment 4: normalise, round/sticky bits, round-to-nearest-even decision, exponent
//              and exponent + 1                                                       | cut K5
//   segment 5: the result's kinds (rc_fp_round_kinds), the fraction's round increment,
//              pack (rc_fp_round_pack)                                                | output
//   Stages - 1 cuts (at most five) are enabled in the order K3, K1, K5, K4, K2: Stages = 1 is one
//   combinational segment with a register at the output, Stages = 2 cuts after the add,
//   Stages = 3 also before the align shifter, Stages = 4 also before the rounding increment,
//   Stages = 5 also between the leading-zero count and the normalise shifter, Stages = 6 also
//   between the align shifter and the add. Stages > 6 appends Stages - 6 more registers at the
//   output (they only help a retiming tool). The default 6 closes 100 MHz on an ECP5 LFE5U-85F
//   with margin (docs/fp24.md); at 5 the align shift and the add share a cycle, about 100 MHz.
module rc_fp_add #(
  parameter int unsigned ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW  = rc_pkg::Fp24FracW,
  parameter int unsigned Stages = rc_pkg::FpStagesAdd
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
  // Alignment shift amount: wide enough for a shift of ManW + 2 or more (which yields zero), so
  // larger exponent differences saturate to all ones.
  localparam int unsigned ShW   = (ExpW < $clog2(ManW + 3)) ? ExpW : $clog2(ManW + 3);

  // Cut placement (see the header): cut Kn is on when Stages - 1 >= its rank.
  localparam int unsigned NCuts   = (Stages - 1 < 5) ? Stages - 1 : 5;
  localparam bit          CutK1   = NCuts >= 2;
  localparam bit          CutK2   = NCuts >= 5;
  localparam bit          CutK3   = NCuts >= 1;
  localparam bit          CutK4   = NCuts >= 4;
  localparam bit          CutK5   = NCuts >= 3;
  localparam int unsigned OutRegs = Stages - NCuts;

  ///////////////////////////////////////////
  // Segment 0: classify, order, exp diff  //
  ///////////////////////////////////////////

  logic            a_sign, b_sign;
  logic [ExpW-1:0] a_exp, b_exp;
  logic            a_zero, b_zero, a_nan, b_nan, a_inf, b_inf;
  logic [MagW-1:0] a_mag, b_mag, big_mag;
  logic [FracW-1:0] small_frac;
  logic            swap;
  logic [ExpW-1:0] diff_ab, diff_ba;
  logic [ShW-1:0]  shift_ab, shift_ba, shift_s0;
  logic            big_sign_s0, eff_sub_s0, zero_sign_s0, spec_nan_s0, spec_inf_s0;
  logic [ExpW-1:0] big_exp_s0;
  logic [ManW-1:0] big_man_s0, small_man_s0;

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

  // The order compares the raw magnitudes: it differs from the order of the zeroed ones only
  // when both exponent fields are 0, where both operands are zero, both orders give the same
  // zeroed big and small operands, and the sum is an exact zero whose sign is zero_sign (the
  // big operand's sign is not used). The zeroing then runs beside the comparison.
  assign swap         = b_i[MagW-1:0] > a_i[MagW-1:0];
  assign big_mag      = swap ? b_mag : a_mag;
  assign small_frac   = swap ? a_mag[FracW-1:0] : b_mag[FracW-1:0];
  assign big_sign_s0  = swap ? b_sign : a_sign;
  assign big_exp_s0   = big_mag[MagW-1 -: ExpW];
  // The hidden bits (a nonzero exponent field) are selected from the operands' own flags, so
  // the comparison's result only selects (not an OR over the selected exponent behind it).
  assign big_man_s0   = {swap ? ~b_zero : ~a_zero, big_mag[FracW-1:0]};
  assign small_man_s0 = {swap ? ~a_zero : ~b_zero, small_frac};
  // Both differences (saturated to the shifter's width) in parallel with the comparison; the
  // ordered one is big - small >= 0.
  assign diff_ab      = a_exp - b_exp;
  assign diff_ba      = b_exp - a_exp;
  if (ExpW > ShW) begin : g_shift_sat
    assign shift_ab = (|diff_ab[ExpW-1:ShW]) ? {ShW{1'b1}} : diff_ab[ShW-1:0];
    assign shift_ba = (|diff_ba[ExpW-1:ShW]) ? {ShW{1'b1}} : diff_ba[ShW-1:0];
  end else begin : g_shift_plain
    assign shift_ab = diff_ab;
    assign shift_ba = diff_ba;
  end
  assign shift_s0     = swap ? shift_ba : shift_ab;

  assign eff_sub_s0   = a_sign ^ b_sign;
  assign zero_sign_s0 = a_sign & b_sign;  // sign of an exact zero sum (round to nearest)
  assign spec_nan_s0  = a_nan | b_nan | (a_inf & b_inf & eff_sub_s0);
  assign spec_inf_s0  = a_inf | b_inf;    // an infinity is always the bigger operand

  // The flags every later segment carries: {spec_nan, spec_inf, big_sign, zero_sign}.
  localparam int unsigned FlW = 4;
  logic [FlW-1:0] fl_s0;
  assign fl_s0 = {spec_nan_s0, spec_inf_s0, big_sign_s0, zero_sign_s0};

  ////////////////
  // Cut K1     //
  ////////////////

  localparam int unsigned K1W = FlW + 1 + ExpW + 2 * ManW + ShW;
  logic [K1W-1:0]  k1_d, k1_q;
  logic [FlW-1:0]  fl_s1;
  logic            eff_sub_s1;
  logic [ExpW-1:0] big_exp_s1;
  logic [ManW-1:0] big_man_s1, small_man_s1;
  logic [ShW-1:0]  shift_s1;

  assign k1_d = {fl_s0, eff_sub_s0, big_exp_s0, big_man_s0, small_man_s0, shift_s0};
  if (CutK1) begin : g_cut_k1
    always_ff @(posedge clk_i) begin
      k1_q <= k1_d;
    end
  end else begin : g_no_cut_k1
    assign k1_q = k1_d;
  end
  assign {fl_s1, eff_sub_s1, big_exp_s1, big_man_s1, small_man_s1, shift_s1} = k1_q;

  ///////////////////////////////
  // Segment 1: align          //
  ///////////////////////////////

  // Shift the smaller significand right by the exponent difference, keeping two extra bits
  // (guard, round) and ORing everything shifted out beyond them into a sticky bit. A shift of the
  // full width or more yields 0 (and a sticky of |small_man), as the operators define.
  logic [ManW+1:0] small_ext, small_shifted;
  logic            small_sticky;
  logic [AlnW-1:0] small_aln_s1;

  assign small_ext     = {small_man_s1, 2'b00};
  assign small_shifted = small_ext >> shift_s1;
  assign small_sticky  = |(small_ext & ~({(ManW + 2){1'b1}} << shift_s1));
  assign small_aln_s1  = {small_shifted, small_sticky};

  ////////////////
  // Cut K2     //
  ////////////////

  localparam int unsigned K2W = FlW + 1 + ExpW + ManW + AlnW;
  logic [K2W-1:0]  k2_d, k2_q;
  logic [FlW-1:0]  fl_s2;
  logic            eff_sub_s2;
  logic [ExpW-1:0] big_exp_s2;
  logic [ManW-1:0] big_man_s2;
  logic [AlnW-1:0] small_aln_s2;

  assign k2_d = {fl_s1, eff_sub_s1, big_exp_s1, big_man_s1, small_aln_s1};
  if (CutK2) begin : g_cut_k2
    always_ff @(posedge clk_i) begin
      k2_q <= k2_d;
    end
  end else begin : g_no_cut_k2
    assign k2_q = k2_d;
  end
  assign {fl_s2, eff_sub_s2, big_exp_s2, big_man_s2, small_aln_s2} = k2_q;

  ///////////////////////////////
  // Segment 2: add            //
  ///////////////////////////////

  logic [SumW-1:0] big_al, small_al, sum_s2;

  assign big_al   = {1'b0, big_man_s2, 3'b000};
  assign small_al = {1'b0, small_aln_s2};
  // One carry chain for both: a - b = a + ~b + 1 (the inversion sits in the chain's LUTs). The
  // select between a sum and a difference took a second chain and a multiplexer (Yosys
  // synth_ecp5 of the adder alone: 9 CCU2C and 22 LUT4 more).
  assign sum_s2   = big_al + (small_al ^ {SumW{eff_sub_s2}}) + SumW'(eff_sub_s2);

  ////////////////
  // Cut K3     //
  ////////////////

  localparam int unsigned K3W = FlW + ExpW + SumW;
  logic [K3W-1:0]  k3_d, k3_q;
  logic [FlW-1:0]  fl_s3;
  logic [ExpW-1:0] big_exp_s3;
  logic [SumW-1:0] sum_s3;

  assign k3_d = {fl_s2, big_exp_s2, sum_s2};
  if (CutK3) begin : g_cut_k3
    always_ff @(posedge clk_i) begin
      k3_q <= k3_d;
    end
  end else begin : g_no_cut_k3
    assign k3_q = k3_d;
  end
  assign {fl_s3, big_exp_s3, sum_s3} = k3_q;

  ///////////////////////////////////////
  // Segment 3: leading-zero count     //
  ///////////////////////////////////////

  // Priority encoder; the highest set bit wins. lz = SumW means the sum is exactly zero.
  logic [LzW-1:0] lz_s3;
  always_comb begin
    lz_s3 = LzW'(SumW);
    for (int i = 0; i < SumW; i++) begin
      if (sum_s3[i]) begin
        lz_s3 = LzW'(SumW - 1 - i);
      end
    end
  end

  ////////////////
  // Cut K4     //
  ////////////////

  localparam int unsigned K4W = FlW + ExpW + SumW + LzW;
  logic [K4W-1:0]  k4_d, k4_q;
  logic [FlW-1:0]  fl_s4;
  logic [ExpW-1:0] big_exp_s4;
  logic [SumW-1:0] sum_s4;
  logic [LzW-1:0]  lz_s4;

  assign k4_d = {fl_s3, big_exp_s3, sum_s3, lz_s3};
  if (CutK4) begin : g_cut_k4
    always_ff @(posedge clk_i) begin
      k4_q <= k4_d;
    end
  end else begin : g_no_cut_k4
    assign k4_q = k4_d;
  end
  assign {fl_s4, big_exp_s4, sum_s4, lz_s4} = k4_q;

  //////////////////////////////////////////////
  // Segment 4: normalise, rounding decision  //
  //////////////////////////////////////////////

  logic [SumW-1:0] norm;
  logic [ManW-1:0] man_s4;
  logic            round_bit, sticky_bit, round_up_s4, sum_zero_s4;
  logic [ExW-1:0]  exp_norm_s4;

  assign norm        = sum_s4 << lz_s4;  // leading one to the top bit
  assign man_s4      = norm[SumW-1 -: ManW];
  assign round_bit   = norm[3];
  assign sticky_bit  = |norm[2:0];
  assign round_up_s4 = round_bit & (sticky_bit | man_s4[0]);
  // The leading one of the sum sits at bit SumW-2 for an unshifted big operand, so the result
  // exponent is big_exp + 1 - lz (rc_fp_round_pack adds one when rounding carries out).
  assign exp_norm_s4 = ExW'(big_exp_s4) + ExW'(1) - ExW'(lz_s4);
  // The exponent if the rounding carries out, made here beside exp_norm (the same operands), so
  // the rounding cycle only selects it (run 63 seeds 1 and 3: a traversal subtracter's last
  // segment, the increment and the kinds behind the carry, -0.80 ns).
  logic [ExpW-1:0] exp_inc_s4;
  assign exp_inc_s4  = ExpW'(ExW'(big_exp_s4) + ExW'(2) - ExW'(lz_s4));
  // An exact zero sum has exp_norm <= big_exp - 5 < all ones and no rounding carry, so gating
  // the overflow with zero_i inside rc_fp_round_pack changes nothing here.
  assign sum_zero_s4 = lz_s4 == LzW'(SumW);

  // The rounding cycle's range checks, made here so its override starts near flip-flops.
  logic       man_ones_s4;
  logic [1:0] uflow_s4, oflow_s4;
  rc_fp_round_flags #(
    .ExpW (ExpW),
    .FracW(FracW),
    .ExW  (ExW)
  ) u_round_flags (
    .exp_i     (exp_norm_s4),
    .man_i     (man_s4),
    .man_ones_o(man_ones_s4),
    .uflow_o   (uflow_s4),
    .oflow_o   (oflow_s4)
  );

  ////////////////
  // Cut K5     //
  ////////////////

  localparam int unsigned K5W = FlW + 1 + 2 * ExpW + FracW + 1 + 5;
  logic [K5W-1:0]   k5_d, k5_q;
  logic             spec_nan_s5, spec_inf_s5, big_sign_s5, zero_sign_s5, sum_zero_s5;
  logic [ExpW-1:0]  exp_s5, exp_inc_s5;
  logic [FracW-1:0] frac_s5;
  logic             round_up_s5, man_ones_s5;
  logic [1:0]       uflow_s5, oflow_s5;
  logic [W-1:0]     res_d;

  assign k5_d = {fl_s4, sum_zero_s4, exp_norm_s4[ExpW-1:0], exp_inc_s4, man_s4[FracW-1:0],
                 round_up_s4, man_ones_s4, uflow_s4, oflow_s4};
  if (CutK5) begin : g_cut_k5
    always_ff @(posedge clk_i) begin
      k5_q <= k5_d;
    end
  end else begin : g_no_cut_k5
    assign k5_q = k5_d;
  end
  assign {spec_nan_s5, spec_inf_s5, big_sign_s5, zero_sign_s5, sum_zero_s5, exp_s5, exp_inc_s5,
          frac_s5, round_up_s5, man_ones_s5, uflow_s5, oflow_s5} = k5_q;

  //////////////////////////////////////////////////////
  // Segment 5: kinds, round increment, pack          //
  //////////////////////////////////////////////////////

  // The kinds are made after the cut here: the range checks come two carry chains behind the
  // leading-zero count, and a LUT more behind them lengthened segment 4 (run 60's trial: the
  // whole kind before the cut made it the adder's longest alone, 8.96 ns).
  logic [2*rc_pkg::FpResultKindBits-1:0] kinds_s5;
  logic                                  res_sign_s5;
  rc_fp_round_kinds u_round_kinds (
    .nan_i      (spec_nan_s5),
    .inf_i      (spec_inf_s5),
    .zero_i     (sum_zero_s5),
    .zero_sign_i(zero_sign_s5),
    .sign_i     (big_sign_s5),
    .uflow_i    (uflow_s5),
    .oflow_i    (oflow_s5),
    .kind_o     (kinds_s5),
    .sign_o     (res_sign_s5)
  );

  rc_fp_round_pack #(
    .ExpW (ExpW),
    .FracW(FracW)
  ) u_round_pack (
    .kind_i    (kinds_s5),
    .sign_i    (res_sign_s5),
    .man_ones_i(man_ones_s5),
    .exp_i     (exp_s5),
    .exp_inc_i (exp_inc_s5),
    .frac_i    (frac_s5),
    .round_up_i(round_up_s5),
    .res_o     (res_d)
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
