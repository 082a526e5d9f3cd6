// rc_fp_div_fin: the last quotient bit's extras in the raycore dividers (rc_fp_div,
// rc_fp_div_iter): the sticky bit, the rounding increment and the result's kinds, so that the
// rounding cycle after it only selects.
//
// Contract
// - Function (combinational): with q_i the last quotient bit (the round bit), rem_i the partial
//   remainder it was taken from (ManW + 1 bits), dvs_i the divisor's fraction bits, man_i the
//   significand's ManW quotient bits (MSB first) and hdr_i rc_fp_div_pre's header,
//     sticky  = the final remainder is nonzero: q_i ? rem_i != divisor : rem_i != 0 (two
//               equality compares beside the last subtraction, which only selects);
//     fin_o   = {kinds (rc_fp_round_kinds, both outcomes of the rounding carry), sign,
//               man_ones (rc_fp_round_flags), exponent field, fraction (man_i without its
//               hidden bit), round_up = q_i & (sticky | man_i[0])}: round to nearest, ties to
//               even; what rc_fp_round_pack takes.
// - Parameters: ExpW (>= 2), FracW (>= 1): the format. Illegal input: none.
module rc_fp_div_fin #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW
) (
  input  logic [ExpW+5:0]                                     hdr_i,
  input  logic [FracW-1:0]                                    dvs_i,
  input  logic [FracW+1:0]                                    rem_i,
  input  logic                                                q_i,
  input  logic [FracW:0]                                      man_i,
  output logic [2*rc_pkg::FpResultKindBits+ExpW+FracW+2:0]    fin_o
);

  localparam int unsigned ExW = ExpW + 2;

  logic                                  sticky, round_up, man_ones, sign;
  logic [1:0]                            uflow, oflow;
  logic [2*rc_pkg::FpResultKindBits-1:0] kinds;
  logic                                  h_nan, h_inf, h_zero, h_sign;
  logic [ExW-1:0]                        h_exp;

  assign {h_nan, h_inf, h_zero, h_sign, h_exp} = hdr_i;
  assign sticky   = q_i ? (rem_i != {2'b01, dvs_i}) : (rem_i != '0);
  assign round_up = q_i & (sticky | man_i[0]);
  rc_fp_round_flags #(
    .ExpW (ExpW),
    .FracW(FracW),
    .ExW  (ExW)
  ) u_round_flags (
    .exp_i     (h_exp),
    .man_i     (man_i),
    .man_ones_o(man_ones),
    .uflow_o   (uflow),
    .oflow_o   (oflow)
  );
  rc_fp_round_kinds u_round_kinds (
    .nan_i      (h_nan),
    .inf_i      (h_inf),
    .zero_i     (h_zero),
    .zero_sign_i(h_sign),
    .sign_i     (h_sign),
    .uflow_i    (uflow),
    .oflow_i    (oflow),
    .kind_o     (kinds),
    .sign_o     (sign)
  );
  assign fin_o = {kinds, sign, man_ones, h_exp[ExpW-1:0], man_i[FracW-1:0], round_up};

endmodule
