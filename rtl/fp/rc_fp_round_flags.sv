// rc_fp_round_flags: the range checks of rc_fp_round_pack, made a cycle ahead of it.
//
// Contract
// - Function (purely combinational, no clock): for the exponent exp_i and significand man_i that
//   the caller will hand to rc_fp_round_pack,
//     man_ones_o = &man_i                          (a rounding increment carries out)
//     uflow_o[0] = exp_i <= 0,     uflow_o[1] = exp_i + 1 <= 0      (flush to zero)
//     oflow_o[0] = exp_i >= ones,  oflow_o[1] = exp_i + 1 >= ones   (overflow to infinity)
//   with exp_i read as a two's complement number and ones the all-ones exponent field. Index 1
//   is the exponent after a rounding carry.
// - Use: each fp unit computes these beside its last cut (they do not need the rounding bit) and
//   registers them with the rest of the rounding cycle's input, so the special-case override of
//   the output register starts two LUTs from flip-flops instead of after the significand's wide
//   AND and the exponent's compares (docs/fpga.md, "What is left"). The multiplier makes the
//   range checks a cycle earlier still, beside its product, for both outcomes of its one-bit
//   normalise (exp and exp + 1, man_i tied to 0 and man_ones_o unused), and its all-ones flag
//   after the shift, where the significand is known.
// - Parameters: ExpW exponent bits (>= 2), FracW fraction bits (>= 1), ExW width of exp_i
//   (>= ExpW + 2), as rc_fp_round_pack's.
// - Illegal input: exp_i + 1 must fit in ExW bits as a signed value (rc_fp_round_pack's rule).
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
