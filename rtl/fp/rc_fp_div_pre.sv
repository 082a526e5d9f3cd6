// rc_fp_div_pre: the first slot of the raycore dividers (rc_fp_div, rc_fp_div_iter): unpack,
// classify, pre-normalise, and the first quotient bit.
//
// Contract
// - Function (combinational): for a_i / b_i, the state after quotient bit 1 of the radix-2
//   restoring division that rc_fp_div's header describes:
//     hdr_o   = {spec_nan, spec_inf, spec_zero, sign, exp}: the special results (NaN wins over
//               infinity, infinity over zero; an exponent field of 0 reads as zero), the sign
//               (the operands' signs xored) and the quotient's unbounded biased exponent
//               (ExpW + 2 bits, two's complement), for the dividend pre-normalised so that the
//               significands' quotient lies in [1, 2);
//     dvs_o   = the divisor's fraction bits; dvs3_o = 3 times its significand (ManW + 2 bits);
//     rem_o   = the partial remainder after bit 1 (always 1), below the divisor (ManW + 1 bits).
// - Parameters: ExpW (>= 2), FracW (>= 1): the format. Illegal input: none.
// - Timing: bit 1's subtraction is made for both pre-normalisations side by side (a - b, whose
//   borrow says that a's significand is below b's, and 2a - b) and only selected, and so is the
//   exponent (run 34: -1.04 ns in rc_ray_setup's divider with the select in front of it), so
//   the slot's depth is one carry chain and a select.
module rc_fp_div_pre #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW
) (
  input  logic [ExpW+FracW:0] a_i,
  input  logic [ExpW+FracW:0] b_i,
  output logic [ExpW+5:0]     hdr_o,
  output logic [FracW-1:0]    dvs_o,
  output logic [FracW+2:0]    dvs3_o,
  output logic [FracW+1:0]    rem_o
);

  localparam int unsigned W    = 1 + ExpW + FracW;
  localparam int unsigned ManW = FracW + 1;
  localparam int unsigned ExW  = ExpW + 2;
  localparam int unsigned D3W  = ManW + 2;
  localparam int unsigned Bias = (1 << (ExpW - 1)) - 1;

  logic [ExpW-1:0] a_exp, b_exp;
  logic            a_zero, b_zero, a_nan, b_nan, a_inf, b_inf;
  logic            spec_nan, spec_inf, spec_zero;
  logic [ManW-1:0] a_man, b_man;
  logic            a_below;
  logic [ManW:0]   d_lo;
  logic [ManW-1:0] d_hi;
  logic [ExW-1:0]  exp_hi, exp_lo;

  assign a_exp  = a_i[W-2 -: ExpW];
  assign b_exp  = b_i[W-2 -: ExpW];
  assign a_zero = ~|a_exp;
  assign b_zero = ~|b_exp;
  assign a_nan  = (&a_exp) & (|a_i[FracW-1:0]);
  assign b_nan  = (&b_exp) & (|b_i[FracW-1:0]);
  assign a_inf  = (&a_exp) & ~(|a_i[FracW-1:0]);
  assign b_inf  = (&b_exp) & ~(|b_i[FracW-1:0]);

  assign spec_nan  = a_nan | b_nan | (a_zero & b_zero) | (a_inf & b_inf);
  assign spec_inf  = a_inf | b_zero;  // (overridden by spec_nan)
  assign spec_zero = a_zero | b_inf;  // (overridden by spec_nan and spec_inf)

  // The hidden bit is always 1 here: zero, infinity and NaN operands are overridden at the end.
  assign a_man   = {1'b1, a_i[FracW-1:0]};
  assign b_man   = {1'b1, b_i[FracW-1:0]};
  // Dividend in [divisor, 2 * divisor), so the first quotient bit is 1 and q lies in [1, 2).
  assign d_lo    = {1'b0, a_man} - {1'b0, b_man};
  assign d_hi    = {a_man[ManW-2:0], 1'b0} - b_man;  // in [0, b): modulo 2^ManW is exact
  assign a_below = d_lo[ManW];
  assign rem_o   = {1'b0, a_below ? d_hi : d_lo[ManW-1:0]};
  assign exp_hi  = ExW'(a_exp) - ExW'(b_exp) + ExW'(Bias);
  assign exp_lo  = ExW'(a_exp) - ExW'(b_exp) + ExW'(Bias - 1);
  assign hdr_o   = {spec_nan, spec_inf, spec_zero, a_i[W-1] ^ b_i[W-1], a_below ? exp_lo : exp_hi};
  assign dvs_o   = b_i[FracW-1:0];
  assign dvs3_o  = D3W'(b_man) + D3W'({b_man, 1'b0});

endmodule
