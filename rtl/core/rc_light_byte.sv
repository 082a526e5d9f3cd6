// rc_light_byte: a pixel channel's byte from its lighting sum (docs/architecture.md, "Lighting":
// byte = round_to_nearest_even(min(sum, 2^F) * 255 / 2^F), integers, exact).
//
// Contract
// - Function: exactly rc::light_byte() (tb/golden/trace.hpp), bit for bit, with F = FixBits:
//   x = min(sum_i, 2^F) * 255 (computed as (m << 8) - m), byte_o = x >> F rounded to nearest,
//   ties to even on the F bits shifted out.
// - Handshake: valid only, no backpressure. valid_o is valid_i two cycles later; byte_o belongs to
//   the input of two cycles before and is meaningful only while valid_o is 1.
// - Latency: 2 (x registered, then the output register: the clamp and the product are one carry
//   chain each, the rounding's compare and increment two more; the lit board routed at 6799b81,
//   seed 2, had all four in one cycle, 38 cells, -0.74 ns).
// - Parameters: FixBits: F (default docs/spec.toml [light] fixed_bits, >= 1); SumW: the sum's bits
//   (> FixBits).
// - Illegal input: none; every sum is legal.
// - Reset: rst_ni (active low, asynchronous) clears only the valid bits.
module rc_light_byte #(
  parameter int unsigned FixBits = rc_pkg::LightFixedBits,
  parameter int unsigned SumW    = 32
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic            valid_i,
  input  logic [SumW-1:0] sum_i,
  output logic            valid_o,
  output logic [7:0]      byte_o
);

  if (FixBits < 1 || SumW <= FixBits) begin : g_param_check
    $error("rc_light_byte: need FixBits >= 1 and SumW > FixBits");
  end

  localparam int unsigned XW = FixBits + 9;  // min(sum, 2^F) * 255 < 2^(F + 8)

  logic [FixBits:0]   m;        // min(sum, 2^F)
  logic [XW-1:0]      x, x_q;
  logic               x_v_q;
  logic [8:0]         q;        // x >> F: at most 255, one more bit for the rounding's carry
  logic [FixBits-1:0] rem, half;
  logic               up;
  logic [7:0]         byte_d;

  assign m    = (sum_i >= SumW'(1 << FixBits)) ? (FixBits + 1)'(1 << FixBits)
                                               : (FixBits + 1)'(sum_i);
  assign x    = (XW'(m) << 8) - XW'(m);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) x_v_q <= 1'b0;
    else x_v_q <= valid_i;
  end
  always_ff @(posedge clk_i) x_q <= x;
  assign q    = x_q[XW-1 -: 9];
  assign rem  = x_q[FixBits-1:0];
  assign half = FixBits'(1) << (FixBits - 1);
  assign up   = (rem > half) || ((rem == half) && q[0]);
  // q + up never exceeds 255: q = 255 only at m = 2^F, where rem = 0.
  assign byte_d = 8'(q + 9'(up));

  rc_pipe_out #(
    .Width   (8),
    .DataRegs(1),
    .Stages  (1)
  ) u_out (
    .clk_i,
    .rst_ni,
    .valid_i(x_v_q),
    .data_i (byte_d),
    .valid_o,
    .data_o (byte_o)
  );

endmodule
