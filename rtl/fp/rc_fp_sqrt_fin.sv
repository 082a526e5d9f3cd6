// rc_fp_sqrt_fin: the last root bit's extras in the raycore square roots (rc_fp_sqrt,
// rc_fp_sqrt_iter): the sticky bit, the rounding increment and the result's kinds, so that the
// rounding cycle after it only selects.
//
// Contract
// - Function (combinational): with r_bit_i the last root bit (bit N = FracW + 2, the round bit),
//   rem_sh_i the brought-down remainder it was taken from (4 r + the last radicand pair, N + 2
//   bits), root_i the N - 1 root bits before it (the significand, MSB first) and hdr_i
//   rc_fp_sqrt_pre's header,
//     sticky = the final remainder is nonzero: r_bit_i ? rem_sh_i != 4 root_i + 1 : rem_sh_i != 0
//              (two equality compares beside the last subtraction, which only selects);
//     fin_o  = {kinds (rc_fp_round_kinds, both outcomes of the rounding carry), sign,
//              man_ones (rc_fp_round_flags), exponent field, fraction (root_i without its
//              leading 1), round_up = r_bit_i & (sticky | root_i[0])}: round to nearest, ties
//              to even; what rc_fp_round_pack takes.
// - Parameters: ExpW (>= 2), FracW (>= 1): the format. Illegal input: none.
// - Timing: the sticky bit is not an OR over the final remainder behind the last subtraction's
//   carry chain (run 47, -0.44 ns in rc_ray_gen), and the rounding increment is one cell beside
//   its select (run 54, -0.35 ns), so the rounding cycle starts from registered decisions.
module rc_fp_sqrt_fin #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW
) (
  input  logic [ExpW+3:0]                                  hdr_i,
  input  logic                                             r_bit_i,
  input  logic [FracW+3:0]                                 rem_sh_i,
  input  logic [FracW:0]                                   root_i,
  output logic [2*rc_pkg::FpResultKindBits+ExpW+FracW+2:0] fin_o
);

  localparam int unsigned ExW = ExpW + 2;  // rc_fp_round_pack's exponent width

  logic                                  sticky, round_up, man_ones, sign;
  logic [1:0]                            uflow, oflow;
  logic [2*rc_pkg::FpResultKindBits-1:0] kinds;
  logic                                  h_nan, h_inf, h_zero, h_sign;
  logic [ExpW-1:0]                       h_exp;

  assign {h_nan, h_inf, h_zero, h_sign, h_exp} = hdr_i;
  // With the trial subtracted the remainder is zero exactly when the trial equals the
  // brought-down remainder.
  assign sticky   = r_bit_i ? (rem_sh_i != {1'b0, root_i, 2'b01}) : (rem_sh_i != '0);
  assign round_up = r_bit_i & (sticky | root_i[0]);
  rc_fp_round_flags #(
    .ExpW (ExpW),
    .FracW(FracW),
    .ExW  (ExW)
  ) u_round_flags (
    .exp_i     (ExW'(h_exp)),
    .man_i     (root_i),
    .man_ones_o(man_ones),
    .uflow_o   (uflow),
    .oflow_o   (oflow)
  );
  rc_fp_round_kinds u_round_kinds (
    .nan_i      (h_nan),
    .inf_i      (h_inf),
    .zero_i     (h_zero),
    .zero_sign_i(h_sign),  // sqrt(-0) = -0
    .sign_i     (1'b0),    // every other non-NaN result is positive
    .uflow_i    (uflow),
    .oflow_i    (oflow),
    .kind_o     (kinds),
    .sign_o     (sign)
  );
  assign fin_o = {kinds, sign, man_ones, h_exp, root_i[FracW-1:0], round_up};

endmodule
