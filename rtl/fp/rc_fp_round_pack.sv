// rc_fp_round_pack: the rounding increment and the packing of an fp unit's result, shared by the
// fp units.
//
// Contract
// - Function (purely combinational, no clock): packs a word {sign, exp[ExpW-1:0],
//   frac[FracW-1:0]} of the kind kind_i that rc_fp_round_kind decided:
//     FpKindNan    -> {sign_i, all ones, 1 then zeros}    (the canonical NaN; sign_i is 0)
//     FpKindInf    -> {sign_i, all ones, 0}               (+-infinity)
//     FpKindZero   -> {sign_i, 0, 0}                      (signed zero)
//     FpKindNormal -> {sign_i, exp_i + carry_i, frac_i + round_up_i}
//   The fraction's increment wraps to 0 exactly when the rounding carries out (carry_i), the
//   right fraction then.
// - Parameters: ExpW exponent bits (>= 2), FracW fraction bits (>= 1).
// - Inputs: kind_i, carry_i and sign_i are rc_fp_round_kind's outputs for the same result;
//   exp_i is the low ExpW bits of its exponent before the carry, frac_i the significand without
//   the hidden bit, round_up_i the rounding increment. The divider, the square root and the
//   multiplier register all of them in front of this module, so the output word's select
//   starts at flip-flops; the adder decides the kind in front of it (docs/fp24.md, "Rounding and
//   packing").
// - Illegal input: none beyond rc_fp_round_kind's; with FpKindNormal, exp_i + carry_i is the
//   result's exponent field (1 .. all ones - 1).
module rc_fp_round_pack #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW
) (
  input  logic [rc_pkg::FpResultKindBits-1:0] kind_i,  // an rc_pkg::fp_kind_e
  input  logic                                carry_i,
  input  logic                                sign_i,
  input  logic [ExpW-1:0]                     exp_i,
  input  logic [FracW-1:0]                    frac_i,
  input  logic                                round_up_i,
  output logic [ExpW+FracW:0]                 res_o
);

  if (ExpW < 2 || FracW < 1) begin : g_width_check
    $error("rc_fp_round_pack: need ExpW >= 2 and FracW >= 1");
  end

  localparam logic [ExpW-1:0]  ExpOnes = {ExpW{1'b1}};
  localparam logic [FracW-1:0] NanFrac = FracW'(1) << (FracW - 1);

  logic [FracW-1:0] frac_rounded;
  logic [ExpW-1:0]  exp_field;
  assign frac_rounded = frac_i + FracW'(round_up_i);
  assign exp_field    = carry_i ? exp_i + ExpW'(1) : exp_i;

  always_comb begin
    case (kind_i)
      rc_pkg::FpKindNan:  res_o = {sign_i, ExpOnes, NanFrac};
      rc_pkg::FpKindInf:  res_o = {sign_i, ExpOnes, {FracW{1'b0}}};
      rc_pkg::FpKindZero: res_o = {sign_i, ExpW'(0), {FracW{1'b0}}};
      default:            res_o = {sign_i, exp_field, frac_rounded};
    endcase
  end

endmodule
