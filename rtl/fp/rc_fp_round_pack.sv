// rc_fp_round_pack: final rounding increment, flush/overflow and packing shared by the fp units.
//
// Contract
// - Function (purely combinational, no clock): adds round_up_i to the significand man_i, carries
//   a significand overflow into the exponent, then packs a word {sign, exp[ExpW-1:0],
//   frac[FracW-1:0]} with this priority:
//     1. nan_i                                    -> canonical NaN (sign 0, exp ones, frac MSB)
//     2. inf_i, or !zero_i and rounded exp >= ones -> {sign_i, all ones, 0}   (+-infinity)
//     3. zero_i                                   -> {zero_sign_i, 0, 0}      (exact zero)
//     4. rounded exp <= 0                         -> {sign_i, 0, 0}           (flush to zero)
//     5. otherwise                                -> {sign_i, rounded exp[ExpW-1:0], rounded frac}
//   The units without a separate sign for exact zeros tie zero_sign_i to sign_i.
// - Parameters: ExpW exponent bits (>= 2), FracW fraction bits (>= 1), ExW width of the unbounded
//   exponent exp_i (>= ExpW + 2, checked at elaboration).
// - Inputs: exp_i is the biased result exponent before the rounding carry, two's complement and
//   unbounded (it may be <= 0 or >= all ones); man_i is the normalised significand including the
//   hidden bit (man_i[FracW]); round_up_i is the round-to-nearest-even increment decided by the
//   caller.
// - Illegal input: exp_i + 1 must fit in ExW bits as a signed value (no wrap-around); when none of
//   nan_i, inf_i, zero_i is set and the result does not flush, man_i[FracW] must be 1 (the hidden
//   bit is dropped, not checked). Otherwise man_i and exp_i are don't-care.
module rc_fp_round_pack #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW,
  parameter int unsigned ExW   = ExpW + 2
) (
  input  logic                nan_i,
  input  logic                inf_i,
  input  logic                zero_i,
  input  logic                zero_sign_i,
  input  logic                sign_i,
  input  logic [ExW-1:0]      exp_i,
  input  logic [FracW:0]      man_i,
  input  logic                round_up_i,
  output logic [ExpW+FracW:0] res_o
);

  if (ExpW < 2 || FracW < 1 || ExW < ExpW + 2) begin : g_width_check
    $error("rc_fp_round_pack: need ExpW >= 2, FracW >= 1 and ExW >= ExpW + 2");
  end

  localparam int unsigned W = 1 + ExpW + FracW;

  localparam logic [ExpW-1:0] ExpOnes = {ExpW{1'b1}};
  localparam logic [W-1:0]    QNaN    = (W'(ExpOnes) << FracW) | (W'(1) << (FracW - 1));

  // The rounding carry out of the significand (man_i all ones and rounding up) is a wide AND,
  // not the end of the increment's carry chain, and the exponent checks are made for both
  // outcomes (exp_i and exp_i + 1) in parallel with the increment; the carry only selects. This
  // is the same function as incrementing, adding the carry to the exponent and then checking.
  logic [FracW-1:0] frac_rounded;
  logic             carry;
  logic [ExpW-1:0]  exp_inc, exp_field;
  logic             uflow0, uflow1, oflow0, oflow1, exp_uflow, exp_oflow;

  assign frac_rounded = man_i[FracW-1:0] + FracW'(round_up_i);
  assign carry        = round_up_i & (&man_i);
  assign exp_inc      = exp_i[ExpW-1:0] + ExpW'(1);
  // exp_i <= 0 and exp_i + 1 <= 0 (exp_i negative); exp_i >= ones and exp_i + 1 >= ones.
  assign uflow0       = exp_i[ExW-1] | ~|exp_i;
  assign uflow1       = exp_i[ExW-1];
  assign oflow0       = ~exp_i[ExW-1] & (exp_i >= ExW'(ExpOnes));
  assign oflow1       = ~exp_i[ExW-1] & (exp_i >= ExW'(ExpOnes) - ExW'(1));
  assign exp_uflow    = carry ? uflow1 : uflow0;
  assign exp_oflow    = carry ? oflow1 : oflow0;
  assign exp_field    = carry ? exp_inc : exp_i[ExpW-1:0];

  always_comb begin
    if (nan_i) begin
      res_o = QNaN;
    end else if (inf_i || (exp_oflow && !zero_i)) begin
      res_o = {sign_i, ExpOnes, {FracW{1'b0}}};
    end else if (zero_i) begin
      res_o = {zero_sign_i, {(W - 1){1'b0}}};
    end else if (exp_uflow) begin
      res_o = {sign_i, {(W - 1){1'b0}}};
    end else begin
      // On a carry out the incremented fraction wraps to 0, the right fraction.
      res_o = {sign_i, exp_field, frac_rounded};
    end
  end

endmodule
