// rc_fp_cmp: pipelined floating-point compare / min / max for the raycore number format.
//
// Contract
// - Function: lt_o = a < b, le_o = a <= b, eq_o = a == b, min_o = min(a, b), max_o = max(a, b),
//   bit-exact with rc::lt / le / eq / min / max on rc::Fp<ExpW, FracW> (tb/fp/fp.hpp).
// - Handshake: valid only, no backpressure. valid_o is valid_i delayed by exactly Stages cycles;
//   the outputs belong to the inputs presented Stages cycles earlier and are meaningful only
//   while valid_o is 1. A new operation may be presented every cycle.
// - Latency: Stages cycles (Stages >= 1, checked at elaboration).
// - Parameters: ExpW exponent bits (>= 2), FracW fraction bits (>= 1); a word is
//   {sign, exp[ExpW-1:0], frac[FracW-1:0]}. Stages = latency in cycles.
// - Illegal input: none; every bit pattern of a_i and b_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears only the valid pipeline; data registers have
//   no reset.
// - Format rules implemented: an exponent field of 0 reads as signed zero whatever the fraction;
//   exp all ones with frac != 0 is NaN. lt/le/eq are the IEEE 754 predicates: false when either
//   operand is NaN, -0 == +0. min/max give the canonical NaN (sign 0, exp all ones, frac MSB
//   only) when either operand is NaN; otherwise the smaller/larger value with -0 ordered below
//   +0, output canonical (a zero-exponent operand comes out as signed zero with frac 0).
//
// Pipeline: a single combinational segment (magnitude compare and selects); all Stages registers
// sit at the output.
module rc_fp_cmp #(
  parameter int unsigned ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW  = rc_pkg::Fp24FracW,
  parameter int unsigned Stages = rc_pkg::FpStagesCmp
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  input  logic [ExpW+FracW:0] a_i,
  input  logic [ExpW+FracW:0] b_i,
  output logic                valid_o,
  output logic                lt_o,
  output logic                le_o,
  output logic                eq_o,
  output logic [ExpW+FracW:0] min_o,
  output logic [ExpW+FracW:0] max_o
);

  ////////////////
  // Parameters //
  ////////////////

  if (Stages < 1) begin : g_stages_check
    $error("rc_fp_cmp: Stages must be >= 1 (it is the latency in cycles)");
  end
  if (ExpW < 2 || FracW < 1) begin : g_width_check
    $error("rc_fp_cmp: need ExpW >= 2 and FracW >= 1");
  end

  localparam int unsigned W    = 1 + ExpW + FracW;
  localparam int unsigned MagW = ExpW + FracW;
  localparam int unsigned OutW = 3 + 2 * W;  // {lt, le, eq, min, max}

  localparam logic [ExpW-1:0] ExpOnes = {ExpW{1'b1}};
  localparam logic [W-1:0]    QNaN    = (W'(ExpOnes) << FracW) | (W'(1) << (FracW - 1));

  /////////////
  // Compare //
  /////////////

  logic            a_sign, b_sign, a_zero, b_zero, a_nan, b_nan, any_nan;
  logic [MagW-1:0] a_mag, b_mag;
  logic [W-1:0]    a_canon, b_canon;
  logic            mag_lt, mag_gt, mag_eq, ord_lt, val_eq, val_lt;
  logic            lt_d, le_d, eq_d;
  logic [W-1:0]    min_d, max_d;

  assign a_sign  = a_i[W-1];
  assign b_sign  = b_i[W-1];
  assign a_zero  = ~|a_i[W-2 -: ExpW];
  assign b_zero  = ~|b_i[W-2 -: ExpW];
  assign a_nan   = (&a_i[W-2 -: ExpW]) & (|a_i[FracW-1:0]);
  assign b_nan   = (&b_i[W-2 -: ExpW]) & (|b_i[FracW-1:0]);
  assign any_nan = a_nan | b_nan;
  // Canonical encodings: a zero-exponent word becomes signed zero with frac 0.
  assign a_mag   = a_zero ? '0 : a_i[MagW-1:0];
  assign b_mag   = b_zero ? '0 : b_i[MagW-1:0];
  assign a_canon = {a_sign, a_mag};
  assign b_canon = {b_sign, b_mag};

  // Non-NaN words order like sign-magnitude integers of {exp, frac}. The comparisons use the raw
  // magnitudes, so the zeroing runs beside them instead of in front: the raw order equals the
  // order of the canonical magnitudes unless both exponent fields are 0, and then both words are
  // zeros: equal in value (both_zero below), and with equal signs their canonical words are
  // equal, so whichever min/max picks is the same word; with different signs ord_lt goes by sign.
  assign mag_lt = a_i[MagW-1:0] < b_i[MagW-1:0];
  assign mag_gt = b_i[MagW-1:0] < a_i[MagW-1:0];
  assign mag_eq = a_i[MagW-1:0] == b_i[MagW-1:0];
  // Total order with -0 below +0 (for min/max): a before b.
  always_comb begin
    unique case ({a_sign, b_sign})
      2'b10:   ord_lt = 1'b1;
      2'b01:   ord_lt = 1'b0;
      2'b00:   ord_lt = mag_lt;
      default: ord_lt = mag_gt;  // both negative: the larger magnitude is the smaller value
    endcase
  end
  // IEEE value order: +0 and -0 are equal, and so are all zero-exponent encodings.
  assign val_eq = (mag_eq & (a_sign == b_sign)) | (a_zero & b_zero);
  assign val_lt = ord_lt & ~val_eq;

  assign lt_d  = ~any_nan & val_lt;
  assign le_d  = ~any_nan & (val_lt | val_eq);
  assign eq_d  = ~any_nan & val_eq;
  // The NaN override is written as AND-OR masks, not as a mux with a constant input: Yosys would
  // turn the latter into flip-flops with a synchronous set/reset, which on ECP5 costs about three
  // times the LUTs of this unit (measured with synth_ecp5).
  assign min_d = ({W{~any_nan}} & (ord_lt ? a_canon : b_canon)) | ({W{any_nan}} & QNaN);
  assign max_d = ({W{~any_nan}} & (ord_lt ? b_canon : a_canon)) | ({W{any_nan}} & QNaN);

  ///////////////////////////////
  // Output and valid pipeline //
  ///////////////////////////////

  logic [OutW-1:0] out_d;
  assign out_d = {lt_d, le_d, eq_d, min_d, max_d};

  rc_pipe_out #(
    .Width   (OutW),
    .DataRegs(Stages),
    .Stages  (Stages)
  ) u_out (
    .clk_i,
    .rst_ni,
    .valid_i,
    .data_i (out_d),
    .valid_o,
    .data_o ({lt_o, le_o, eq_o, min_o, max_o})
  );

`ifndef SYNTHESIS
  // le is lt or eq, and lt excludes eq: a cheap internal consistency check (checked once u_out's
  // own checks are on, i.e. after the first reset).
  LeConsistent_A: assert property (@(posedge clk_i) disable iff (u_out.checks_on !== 1'b1)
                                   valid_o |-> (le_o == (lt_o | eq_o)) && !(lt_o && eq_o));
`endif

endmodule
