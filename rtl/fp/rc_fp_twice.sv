// rc_fp_twice: x + x in the format, without an adder: doubling is exact unless it overflows, so
// it is the exponent plus one.
//
// Contract
// - Function: res_o = x_i + x_i exactly as rc_fp_add gives it (the golden fp24 `x + x`), bit for
//   bit, for every encoding: a zero (an exponent field of 0, any fraction) gives the zero of x's
//   sign; a NaN gives the canonical NaN (sign 0, exponent all ones, fraction MSB 1); x with the
//   largest finite exponent, or an infinity, gives the infinity of x's sign; any other x keeps
//   its sign and fraction with its exponent plus one.
// - Handshake: valid only, no backpressure. valid_o is valid_i one cycle later; res_o belongs to
//   the input of the cycle before and is meaningful only while valid_o is 1.
// - Latency: 1 (the output register).
// - Parameters: ExpW, FracW: the number format (default fp24).
// - Illegal input: none; every bit pattern of x_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears only valid_o (rc_pipe_out).
module rc_fp_twice #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  input  logic [ExpW+FracW:0] x_i,
  output logic                valid_o,
  output logic [ExpW+FracW:0] res_o
);

  localparam int unsigned W = 1 + ExpW + FracW;

  logic             s;
  logic [ExpW-1:0]  e;
  logic [FracW-1:0] f;
  logic             is_nan, is_zero, to_inf;
  logic [W-1:0]     res_d;

  assign s       = x_i[W-1];
  assign e       = x_i[W-2 -: ExpW];
  assign f       = x_i[FracW-1:0];
  assign is_nan  = (&e) && (f != '0);
  assign is_zero = e == '0;
  assign to_inf  = e >= {{(ExpW - 1) {1'b1}}, 1'b0};  // the largest finite exponent, or inf

  always_comb begin
    if (is_nan) res_d = {1'b0, {ExpW{1'b1}}, 1'b1, {(FracW - 1) {1'b0}}};
    else if (is_zero) res_d = {s, {(W - 1) {1'b0}}};
    else if (to_inf) res_d = {s, {ExpW{1'b1}}, {FracW{1'b0}}};
    else res_d = {s, e + ExpW'(1), f};
  end

  rc_pipe_out #(
    .Width   (W),
    .DataRegs(1),
    .Stages  (1)
  ) u_out (
    .clk_i,
    .rst_ni,
    .valid_i,
    .data_i (res_d),
    .valid_o,
    .data_o (res_o)
  );

endmodule
