// rc_fp_round_pack: the rounding increment, the kind's select and the packing of an fp unit's
// result, shared by the fp units.
//
// Contract
// - Function (purely combinational, no clock): with the rounding carry
//     carry = round_up_i & man_ones_i          (the significand all ones and rounding up)
//   the result's kind is kind_i's entry for that outcome (rc_fp_round_kinds: index 0 no carry,
//   1 carry), and the word {sign, exp[ExpW-1:0], frac[FracW-1:0]} is
//     FpKindNan    -> {sign_i, all ones, 1 then zeros}   (the canonical NaN; sign_i is 0)
//     FpKindInf    -> {sign_i, all ones, 0}              (+-infinity)
//     FpKindZero   -> {sign_i, 0, 0}                     (signed zero)
//     FpKindNormal -> {sign_i, carry ? exp_inc_i : exp_i, frac_i + round_up_i}
//   The fraction's increment wraps to 0 exactly when the rounding carries out, the right
//   fraction then. The carry is the AND of the increment and the all-ones flag, not the end of
//   the increment's carry chain, and it only selects between two kinds decided without it.
// - Parameters: ExpW exponent bits (>= 2), FracW fraction bits (>= 1).
// - Inputs: kind_i and sign_i are rc_fp_round_kinds' outputs, man_ones_i rc_fp_round_flags'
//   all-ones flag, for the same result; exp_i is the low ExpW bits of its exponent before the
//   carry, exp_inc_i the low ExpW bits of that exponent plus one (the caller's: the adder makes
//   it before its cut, beside the exponent), frac_i the significand without the hidden bit,
//   round_up_i the rounding increment.
//   The units register all of them in front of this module (the adder registers the flags and
//   makes the kinds after its cut), so the word's select starts a LUT from flip-flops.
// - Illegal input: none beyond rc_fp_round_flags'; with FpKindNormal, exp_i + carry is the
//   result's exponent field (1 .. all ones - 1).
module rc_fp_round_pack #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW
) (
  input  logic [2*rc_pkg::FpResultKindBits-1:0] kind_i,  // two rc_pkg::fp_kind_e
  input  logic                                  sign_i,
  input  logic                                  man_ones_i,
  input  logic [ExpW-1:0]                       exp_i,
  input  logic [ExpW-1:0]                       exp_inc_i,
  input  logic [FracW-1:0]                      frac_i,
  input  logic                                  round_up_i,
  output logic [ExpW+FracW:0]                   res_o
);

  if (ExpW < 2 || FracW < 1) begin : g_width_check
    $error("rc_fp_round_pack: need ExpW >= 2 and FracW >= 1");
  end

  localparam int unsigned      KW      = rc_pkg::FpResultKindBits;
  localparam logic [ExpW-1:0]  ExpOnes = {ExpW{1'b1}};
  localparam logic [FracW-1:0] NanFrac = FracW'(1) << (FracW - 1);

  logic             carry;
  logic [KW-1:0]    kind;
  logic [FracW-1:0] frac_rounded;
  logic [ExpW-1:0]  exp_field;
  assign carry        = round_up_i & man_ones_i;
  assign kind         = carry ? kind_i[KW +: KW] : kind_i[0 +: KW];
  assign frac_rounded = frac_i + FracW'(round_up_i);
  assign exp_field    = carry ? exp_inc_i : exp_i;

  always_comb begin
    case (kind)
      rc_pkg::FpKindNan:  res_o = {sign_i, ExpOnes, NanFrac};
      rc_pkg::FpKindInf:  res_o = {sign_i, ExpOnes, {FracW{1'b0}}};
      rc_pkg::FpKindZero: res_o = {sign_i, ExpW'(0), {FracW{1'b0}}};
      default:            res_o = {sign_i, exp_field, frac_rounded};
    endcase
  end

endmodule
