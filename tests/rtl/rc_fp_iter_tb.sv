// rc_fp_iter_tb: verilation wrapper of the iterative divider and square root (rc_fp_div_iter,
// rc_fp_sqrt_iter), each with its own operand stream.
//
// Contract
// - div_valid_i, a_i and b_i go to rc_fp_div_iter (a / b); sqrt_valid_i and s_i to
//   rc_fp_sqrt_iter (sqrt(s)). Valid-only, no backpressure: each *_valid_o is its *_valid_i
//   delayed by the unit's Stages. The bench keeps each unit's operations far enough apart (its
//   contract: operations i and i + Lanes at least Iters + 1 cycles apart), or breaks that on
//   purpose to see the unit's assertion fire.
// - Parameters: ExpW/FracW the format (default fp24), Lanes both units' lane count, DivStages and
//   SqrtStages their latencies (defaults rc_pkg's, those of rc_fp_div and rc_fp_sqrt).
// - Illegal input: none. Reset: rst_ni, active low, asynchronous.
// A test harness top for Verilator (no logic of its own).
module rc_fp_iter_tb #(
  parameter int unsigned ExpW       = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW      = rc_pkg::Fp24FracW,
  parameter int unsigned Lanes      = 1,
  parameter int unsigned DivStages  = rc_pkg::FpStagesDiv,
  parameter int unsigned SqrtStages = rc_pkg::FpStagesSqrt
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                div_valid_i,
  input  logic [ExpW+FracW:0] a_i,
  input  logic [ExpW+FracW:0] b_i,
  output logic                div_valid_o,
  output logic [ExpW+FracW:0] div_res_o,
  input  logic                sqrt_valid_i,
  input  logic [ExpW+FracW:0] s_i,
  output logic                sqrt_valid_o,
  output logic [ExpW+FracW:0] sqrt_res_o
);
  rc_fp_div_iter #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(DivStages),
    .Lanes (Lanes)
  ) u_div (
    .clk_i,
    .rst_ni,
    .valid_i(div_valid_i),
    .a_i,
    .b_i,
    .valid_o(div_valid_o),
    .res_o  (div_res_o)
  );
  rc_fp_sqrt_iter #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(SqrtStages),
    .Lanes (Lanes)
  ) u_sqrt (
    .clk_i,
    .rst_ni,
    .valid_i(sqrt_valid_i),
    .a_i    (s_i),
    .valid_o(sqrt_valid_o),
    .res_o  (sqrt_res_o)
  );
endmodule
