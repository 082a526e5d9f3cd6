// rc_fp_units_tb: verilation wrapper feeding one operand stream to all five fp units in parallel.
//
// Contract
// - a_i, b_i and valid_i go to rc_fp_add (with sub_i: 1 = a - b), rc_fp_mul (a * b),
//   rc_fp_div (a / b), rc_fp_sqrt (sqrt(a), b unused) and rc_fp_cmp (lt, le, eq, min, max) at
//   once. Each unit has its own latency (its Stages parameter), so each has its own valid output;
//   valid-only, no backpressure, and each *_valid_o is valid_i delayed by that unit's Stages.
// - Parameters: ExpW/FracW select the format (default fp24); *Stages are the units' latencies
//   (defaults = the units' defaults from rc_pkg: add 6, mul 2, div 11, sqrt 10, cmp 1).
// - Illegal input: none; every bit pattern is legal.
// - Reset: rst_ni, active low, asynchronous; it clears the valid pipelines only.
// A test harness top for Verilator (no logic of its own); tests/CMakeLists.txt also synthesizes it
// with Yosys synth_ecp5 at its defaults and verilates the netlist (the netlist tests).
module rc_fp_units_tb #(
  parameter int unsigned ExpW       = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW      = rc_pkg::Fp24FracW,
  parameter int unsigned AddStages  = rc_pkg::FpStagesAdd,
  parameter int unsigned MulStages  = rc_pkg::FpStagesMul,
  parameter int unsigned DivStages  = rc_pkg::FpStagesDiv,
  parameter int unsigned SqrtStages = rc_pkg::FpStagesSqrt,
  parameter int unsigned CmpStages  = rc_pkg::FpStagesCmp
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  input  logic                sub_i,
  input  logic [ExpW+FracW:0] a_i,
  input  logic [ExpW+FracW:0] b_i,
  output logic                add_valid_o,
  output logic [ExpW+FracW:0] add_res_o,
  output logic                mul_valid_o,
  output logic [ExpW+FracW:0] mul_res_o,
  output logic                div_valid_o,
  output logic [ExpW+FracW:0] div_res_o,
  output logic                sqrt_valid_o,
  output logic [ExpW+FracW:0] sqrt_res_o,
  output logic                cmp_valid_o,
  output logic                lt_o,
  output logic                le_o,
  output logic                eq_o,
  output logic [ExpW+FracW:0] min_o,
  output logic [ExpW+FracW:0] max_o
);

  rc_fp_add #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(AddStages)
  ) u_add (
    .clk_i,
    .rst_ni,
    .valid_i,
    .sub_i,
    .a_i,
    .b_i,
    .valid_o(add_valid_o),
    .res_o  (add_res_o)
  );

  rc_fp_mul #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(MulStages)
  ) u_mul (
    .clk_i,
    .rst_ni,
    .valid_i,
    .a_i,
    .b_i,
    .valid_o(mul_valid_o),
    .res_o  (mul_res_o)
  );

  rc_fp_div #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(DivStages)
  ) u_div (
    .clk_i,
    .rst_ni,
    .valid_i,
    .a_i,
    .b_i,
    .valid_o(div_valid_o),
    .res_o  (div_res_o)
  );

  rc_fp_sqrt #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(SqrtStages)
  ) u_sqrt (
    .clk_i,
    .rst_ni,
    .valid_i,
    .a_i,
    .valid_o(sqrt_valid_o),
    .res_o  (sqrt_res_o)
  );

  rc_fp_cmp #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(CmpStages)
  ) u_cmp (
    .clk_i,
    .rst_ni,
    .valid_i,
    .a_i,
    .b_i,
    .valid_o(cmp_valid_o),
    .lt_o,
    .le_o,
    .eq_o,
    .min_o,
    .max_o
  );

endmodule
