// rc_fp_to_exp: a material's Blinn-Phong exponent from its Ns (docs/architecture.md, "Lighting":
// ns = round_to_nearest_even(Ns) clamped to [0, 2^exponent_bits - 1], a NaN gives 0), the
// integer that rc_light_term's ns_i takes.
//
// Contract
// - Function: exactly rc::light_exponent() (tb/golden/trace.hpp), bit for bit: rc_fp_to_fix with
//   no fraction bits and Max = 2^ExpBits - 1.
// - Handshake, latency, reset: rc_fp_to_fix's (valid only; latency Stages).
// - Parameters: ExpW, FracW: the number format (default fp24); ExpBits: the exponent's bits
//   (docs/spec.toml [light] exponent_bits), below FracW; Stages: rc_fp_to_fix's, 1 or 2
//   (default 1; rc_tracer's 2).
// - Illegal input: none; every bit pattern of x_i is legal.
module rc_fp_to_exp #(
  parameter int unsigned ExpW    = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW   = rc_pkg::Fp24FracW,
  parameter int unsigned ExpBits = rc_pkg::LightExponentBits,
  parameter int unsigned Stages  = 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  input  logic [ExpW+FracW:0] x_i,
  output logic                valid_o,
  output logic [ExpBits-1:0]  ns_o
);

  rc_fp_to_fix #(
    .ExpW   (ExpW),
    .FracW  (FracW),
    .FixBits(0),
    .Max    ((1 << ExpBits) - 1),
    .Stages (Stages)
  ) u_fix (
    .clk_i,
    .rst_ni,
    .valid_i,
    .x_i,
    .valid_o,
    .out_o  (ns_o)
  );

endmodule
