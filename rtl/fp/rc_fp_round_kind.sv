// rc_fp_round_kind: the kind, sign and exponent carry of an fp unit's result, from the special
// operand flags, rc_fp_round_flags' range checks and the rounding increment.
//
// Contract
// - Function (purely combinational, no clock): with the rounding carry
//     carry_o = round_up_i & man_ones_i             (the significand all ones and rounding up)
//   and the flags of the exponent it selects (index 0: exp, index 1: exp + 1), kind_o is, by
//   priority:
//     1. nan_i                                 -> FpKindNan     (the canonical NaN)
//     2. inf_i, or !zero_i and oflow_i[carry]  -> FpKindInf     (+-infinity)
//     3. zero_i, or uflow_i[carry]             -> FpKindZero    (an exact zero, or flushed)
//     4. otherwise                             -> FpKindNormal  (the rounded number)
//   sign_o is the result's sign bit: 0 for a NaN, zero_sign_i for an exact zero (zero_i),
//   sign_i otherwise. The units without a separate sign for exact zeros tie zero_sign_i to
//   sign_i.
// - Inputs: man_ones_i, uflow_i and oflow_i are rc_fp_round_flags of the result's unbounded
//   exponent exp and normalised significand man (whose rules apply); round_up_i is the
//   round-to-nearest-even increment of man.
// - Use: the kind is decided for both values of the carry, and the carry (the late signal) only
//   selects. The divider, the square root and the multiplier decide it before their last cut,
//   beside the increment, and register it, so rc_fp_round_pack's select of the output word
//   starts at flip-flops (docs/fp24.md, "Rounding and packing"); the adder registers the flags
//   and decides the kind after its last cut, where its range checks, two carry chains behind
//   its leading-zero count, leave room. kind_o is an rc_pkg::fp_kind_e on a plain vector port:
//   Debian's Yosys 0.23, which makes the fp units' netlist test, takes no package types on
//   ports.
module rc_fp_round_kind (
  input  logic                                nan_i,
  input  logic                                inf_i,
  input  logic                                zero_i,
  input  logic                                zero_sign_i,
  input  logic                                sign_i,
  input  logic                                man_ones_i,
  input  logic [1:0]                          uflow_i,
  input  logic [1:0]                          oflow_i,
  input  logic                                round_up_i,
  output logic [rc_pkg::FpResultKindBits-1:0] kind_o,  // an rc_pkg::fp_kind_e
  output logic                                carry_o,
  output logic                                sign_o
);

  function automatic rc_pkg::fp_kind_e kind_of(input logic oflow, input logic uflow,
                                               input logic nan, input logic inf,
                                               input logic zero);
    if (nan) begin
      kind_of = rc_pkg::FpKindNan;
    end else if (inf || (oflow && !zero)) begin
      kind_of = rc_pkg::FpKindInf;
    end else if (zero || uflow) begin
      kind_of = rc_pkg::FpKindZero;
    end else begin
      kind_of = rc_pkg::FpKindNormal;
    end
  endfunction

  rc_pkg::fp_kind_e kind_nc, kind_c;
  assign kind_nc = kind_of(oflow_i[0], uflow_i[0], nan_i, inf_i, zero_i);
  assign kind_c  = kind_of(oflow_i[1], uflow_i[1], nan_i, inf_i, zero_i);
  assign carry_o = round_up_i & man_ones_i;
  assign kind_o  = carry_o ? kind_c : kind_nc;
  assign sign_o  = nan_i ? 1'b0 : (zero_i ? zero_sign_i : sign_i);

endmodule
