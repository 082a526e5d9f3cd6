// rc_fp_round_flags: the range checks of an fp unit's rounding, for rc_fp_round_kind.
//
// Contract
// - Function (purely combinational, no clock): for the result's biased exponent exp_i before the
//   rounding carry (two's complement, unbounded: it may be <= 0 or >= all ones) and its
//   normalised significand man_i (with the hidden bit man_i[FracW]),
//     man_ones_o = &man_i                          (a rounding increment carries out)
//     uflow_o[0] = exp_i <= 0,     uflow_o[1] = exp_i + 1 <= 0      (flush to zero)
//     oflow_o[0] = exp_i >= ones,  oflow_o[1] = exp_i + 1 >= ones   (overflow to infinity)
//   with ones the all-ones exponent field. Index 1 is the exponent after a rounding carry.
// - Use: every fp unit computes these beside its rounding increment (they do not need it), so
//   the increment only selects between the flags of its two outcomes (rc_fp_round_kind); the
//   adder registers them at its last cut (docs/fp24.md, "Rounding and packing").
// - Parameters: ExpW exponent bits (>= 2), FracW fraction bits (>= 1), ExW width of exp_i
//   (>= ExpW + 2, checked at elaboration).
// - Illegal input: exp_i + 1 must fit in ExW bits as a signed value (no wrap-around). When the
//   result is a number (no special operand) that does not flush, man_i[FracW] must be 1:
//   rc_fp_round_pack drops it.
module rc_fp_round_flags #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW,
  parameter int unsigned ExW   = ExpW + 2
) (
  input  logic [ExW-1:0] exp_i,
  input  logic [FracW:0] man_i,
  output logic           man_ones_o,
  output logic [1:0]     uflow_o,
  output logic [1:0]     oflow_o
);

  if (ExpW < 2 || FracW < 1 || ExW < ExpW + 2) begin : g_width_check
    $error("rc_fp_round_flags: need ExpW >= 2, FracW >= 1 and ExW >= ExpW + 2");
  end

  localparam logic [ExpW-1:0] ExpOnes = {ExpW{1'b1}};

  assign man_ones_o = &man_i;
  assign uflow_o[0] = exp_i[ExW-1] | ~|exp_i;
  assign uflow_o[1] = exp_i[ExW-1];
  assign oflow_o[0] = ~exp_i[ExW-1] & (exp_i >= ExW'(ExpOnes));
  assign oflow_o[1] = ~exp_i[ExW-1] & (exp_i >= ExW'(ExpOnes) - ExW'(1));

endmodule
