// rc_fp_sqrt_pre: the first slot of the raycore square roots (rc_fp_sqrt, rc_fp_sqrt_iter):
// unpack, classify, form the radicand, and the first root bit.
//
// Contract
// - Function (combinational): for sqrt(a_i), the state after root bit 1 of the digit-by-digit
//   restoring square root that rc_fp_sqrt's header describes:
//     hdr_o = {spec_nan, spec_inf, spec_zero, sign, exp}: the special results (a NaN input and
//             every negative nonzero input give NaN, +inf gives +inf, an exponent field of 0
//             reads as zero; NaN wins), a_i's sign (the sign of a zero result) and the result's
//             exponent field floor((e + Bias) / 2) (ExpW bits);
//     rad_o = the radicand bits not yet brought down, left aligned (N = FracW + 2 bits, the two
//             low bits 0): the radicand M = 1.frac, doubled when e - Bias is odd, has N bits
//             (its top pair is 1, 2 or 3), and bit 1 takes the top pair;
//     rem_o = the remainder after bit 1 (the top pair minus 1, 2 bits).
//   Bit 1 is always 1, so the partial root after it is 1 and its 3 q + 1 is 4: the caller
//   appends those constants.
// - Parameters: ExpW (>= 2), FracW (>= 1): the format. Illegal input: none.
module rc_fp_sqrt_pre #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW
) (
  input  logic [ExpW+FracW:0] a_i,
  output logic [ExpW+3:0]     hdr_o,
  output logic [FracW+1:0]    rad_o,
  output logic [1:0]          rem_o
);

  localparam int unsigned W    = 1 + ExpW + FracW;
  localparam int unsigned N    = FracW + 2;           // root bits: significand + round
  localparam int unsigned Bias = (1 << (ExpW - 1)) - 1;

  logic             a_sign, a_zero, a_nan, a_inf;
  logic [ExpW-1:0]  a_exp;
  logic [FracW-1:0] a_frac;
  logic             spec_nan, spec_inf, spec_zero;
  logic [ExpW:0]    exp_sum;
  logic [N-1:0]     rad0;

  assign a_sign = a_i[W-1];
  assign a_exp  = a_i[W-2 -: ExpW];
  assign a_frac = a_i[FracW-1:0];
  assign a_zero = ~|a_exp;
  assign a_nan  = (&a_exp) & (|a_frac);
  assign a_inf  = (&a_exp) & ~(|a_frac);

  assign spec_nan  = a_nan | (a_sign & ~a_zero);  // NaN, or negative and nonzero (-inf too)
  assign spec_inf  = a_inf;                       // +inf here (-inf is spec_nan, which wins)
  assign spec_zero = a_zero;                      // +-0 (overridden by nothing: it is not NaN)

  // Result exponent field floor((e + Bias) / 2); its low bit says that e - Bias is odd, and then
  // the significand is doubled. The hidden bit is always 1 here: zero, infinity and NaN inputs are
  // overridden at the end.
  assign exp_sum = (ExpW + 1)'(a_exp) + (ExpW + 1)'(Bias);
  assign rad0    = exp_sum[0] ? {1'b1, a_frac, 1'b0} : {1'b0, 1'b1, a_frac};
  // Root bit 1: the top pair of the radicand is 1, 2 or 3, so the bit is 1 and the remainder is
  // the pair minus 1.
  assign rem_o   = rad0[N-1 -: 2] - 2'd1;
  assign rad_o   = {rad0[N-3:0], 2'b00};
  assign hdr_o   = {spec_nan, spec_inf, spec_zero, a_sign, exp_sum[ExpW:1]};

endmodule
