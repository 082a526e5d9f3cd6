// rc_fp_round_kinds: the kind of an fp unit's result for both outcomes of the rounding carry, and
// its sign, from the special-operand flags and rc_fp_round_flags' range checks.
//
// Contract
// - Function (purely combinational, no clock): for each outcome c of the rounding carry (index
//   0: no carry, exponent exp; index 1: carry, exp + 1), kind_o[c] is, by priority:
//     1. nan_i                                 -> FpKindNan     (the canonical NaN)
//     2. inf_i, or !zero_i and oflow_i[c]      -> FpKindInf     (+-infinity)
//     3. zero_i, or uflow_i[c]                 -> FpKindZero    (an exact zero, or flushed)
//     4. otherwise                             -> FpKindNormal  (the rounded number)
//   at kind_o[c*FpResultKindBits +: FpResultKindBits] (an rc_pkg::fp_kind_e on a plain vector:
//   Debian's Yosys 0.23, which makes the fp units' netlist test, takes no package types on
//   ports). sign_o is the result's sign bit: 0 for a NaN, zero_sign_i for an exact zero
//   (zero_i), sign_i otherwise. The units without a separate sign for exact zeros tie
//   zero_sign_i to sign_i.
// - Use: the kinds do not wait for the rounding increment, so the divider, the square root and
//   the multiplier make them before their last cut and register them; rc_fp_round_pack's
//   carry then selects one, a LUT in front of the word's select (docs/fpga.md, "What is left":
//   deciding the whole kind before the cut lengthened the segments there, run 60). The adder
//   makes them after its cut, where its range checks (two carry chains late) leave room.
module rc_fp_round_kinds (
  input  logic                                  nan_i,
  input  logic                                  inf_i,
  input  logic                                  zero_i,
  input  logic                                  zero_sign_i,
  input  logic                                  sign_i,
  input  logic [1:0]                            uflow_i,
  input  logic [1:0]                            oflow_i,
  output logic [2*rc_pkg::FpResultKindBits-1:0] kind_o,
  output logic                                  sign_o
);

  localparam int unsigned KW = rc_pkg::FpResultKindBits;

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

  for (genvar c = 0; c < 2; c++) begin : g_outcome
    assign kind_o[c*KW +: KW] = kind_of(oflow_i[c], uflow_i[c], nan_i, inf_i, zero_i);
  end
  assign sign_o = nan_i ? 1'b0 : (zero_i ? zero_sign_i : sign_i);

endmodule
