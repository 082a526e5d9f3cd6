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
//   caller; man_ones_i, uflow_i and oflow_i are rc_fp_round_flags of exp_i and man_i, which the
//   caller computes a cycle earlier and registers (the override then starts near flip-flops).
//   The rounding carry out of the significand (man_i all ones and rounding up) only selects
//   between the flags of exp_i and of exp_i + 1.
// - Illegal input: exp_i + 1 must fit in ExW bits as a signed value (no wrap-around); when none of
//   nan_i, inf_i, zero_i is set and the result does not flush, man_i[FracW] must be 1 (the hidden
//   bit is dropped, not checked). Otherwise man_i and exp_i are don't-care. man_ones_i, uflow_i
//   and oflow_i must be rc_fp_round_flags of the same exp_i and man_i.
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
  input  logic                man_ones_i,
  input  logic [1:0]          uflow_i,
  input  logic [1:0]          oflow_i,
  output logic [ExpW+FracW:0] res_o
);

  if (ExpW < 2 || FracW < 1 || ExW < ExpW + 2) begin : g_width_check
    $error("rc_fp_round_pack: need ExpW >= 2, FracW >= 1 and ExW >= ExpW + 2");
  end

  localparam int unsigned W = 1 + ExpW + FracW;

  localparam logic [ExpW-1:0] ExpOnes = {ExpW{1'b1}};
  localparam logic [W-1:0]    QNaN    = (W'(ExpOnes) << FracW) | (W'(1) << (FracW - 1));

  // The rounding carry out of the significand is the AND of the increment and the registered
  // all-ones flag, not the end of the increment's carry chain, and the exponent's checks for
  // both outcomes (exp_i and exp_i + 1) come in as flags; the carry only selects. This is the
  // same function as incrementing, adding the carry to the exponent and then checking.
  logic [FracW-1:0] frac_rounded;
  logic             carry;
  logic [ExpW-1:0]  exp_inc, exp_field;

  assign frac_rounded = man_i[FracW-1:0] + FracW'(round_up_i);
  assign carry        = round_up_i & man_ones_i;
  assign exp_inc      = exp_i[ExpW-1:0] + ExpW'(1);
  assign exp_field    = carry ? exp_inc : exp_i[ExpW-1:0];
  // The exponent's high bits and the hidden bit are read only through the flags.
  logic unused_flag_inputs;
  assign unused_flag_inputs = ^{exp_i[ExW-1:ExpW], man_i[FracW]};

  // The priority above decides the result's kind. It is decided for both values of the carry
  // from the flags alone, which every caller registers, so the carry (the late signal) only
  // selects between two kinds (run 52: in the ray generator's square root the carry went
  // through the overflow flag's select and then the priority chain, five cells into its output
  // register's reset, -1.02 ns).
  typedef enum logic [1:0] {
    KindNormal,
    KindZero,
    KindInf,
    KindNan
  } kind_e;
  function automatic kind_e kind_of(input logic nan, input logic inf, input logic zero,
                                    input logic oflow, input logic uflow);
    if (nan) begin
      kind_of = KindNan;
    end else if (inf || (oflow && !zero)) begin
      kind_of = KindInf;
    end else if (zero || uflow) begin
      kind_of = KindZero;
    end else begin
      kind_of = KindNormal;
    end
  endfunction

  kind_e kind_nc, kind_c, kind;
  logic  res_zero_sign;  // an exact zero's sign, or a flushed result's
  assign kind_nc       = kind_of(nan_i, inf_i, zero_i, oflow_i[0], uflow_i[0]);
  assign kind_c        = kind_of(nan_i, inf_i, zero_i, oflow_i[1], uflow_i[1]);
  assign kind          = carry ? kind_c : kind_nc;
  assign res_zero_sign = zero_i ? zero_sign_i : sign_i;

  always_comb begin
    case (kind)
      KindNan:  res_o = QNaN;
      KindInf:  res_o = {sign_i, ExpOnes, {FracW{1'b0}}};
      KindZero: res_o = {res_zero_sign, {(W - 1){1'b0}}};
      // On a carry out the incremented fraction wraps to 0, the right fraction.
      default:  res_o = {sign_i, exp_field, frac_rounded};
    endcase
  end

endmodule
