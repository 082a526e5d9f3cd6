// rc_serial_dot3: a component-serial dot product (rc_hit_geom, rc_light_term): the vectors a and
// b arrive as streams of three consecutive components (x, y, z) and
//   res_o = (a.x * b.x + a.y * b.y) + a.z * b.z
// in the format's arithmetic, in exactly this order (rc_fp_mul, then two rc_fp_add).
//
// Contract
// - Timing, in cycles after the x components enter (time 0, strm_i's first cycle): the products
//   leave the multiplier at Lm, Lm + 1 and Lm + 2 (prod_valid_o); x + y is issued at Lm + 1,
//   when y's product leaves (xy_i), and leaves at Lm + 1 + La (xy_valid_o); z's
//   product, delayed La - 1 cycles, is added to it then (z_i), and the sum leaves at
//   Lm + 1 + 2 La (valid_o, res_o).
// - strm_i is the operands' stream valid (high for their three cycles); xy_i and z_i are the
//   owner's job times Lm + 1 and Lm + 1 + La (rc_serial_sched at_o). Every valid thus comes from
//   the owner's schedule, and the owner's assertions check the outputs' valids against it.
// - Parameters: ExpW, FracW (the format). Lm and La are the multiplier's and the adder's stages,
//   the package's (docs/spec.toml [fp_stages]), as in the owners.
// - Reset: rst_ni (active low, asynchronous) clears the operators' valid pipelines; data
//   registers have no reset.
module rc_serial_dot3 #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW,
  // Derived (do not override).
  parameter int unsigned W     = 1 + ExpW + FracW
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         strm_i,
  input  logic         xy_i,
  input  logic         z_i,
  input  logic [W-1:0] a_i,
  input  logic [W-1:0] b_i,
  output logic         prod_valid_o,
  output logic         xy_valid_o,
  output logic         valid_o,
  output logic [W-1:0] res_o
);

  localparam int unsigned Lm = rc_pkg::FpStagesMul;
  localparam int unsigned La = rc_pkg::FpStagesAdd;

  if (La < 2) begin : g_param_check
    $error("rc_serial_dot3: the adder needs at least 2 stages");
  end

  logic [W-1:0] prod, p_d1, p_dz, xy;

  rc_fp_mul #(.ExpW(ExpW), .FracW(FracW), .Stages(Lm)) u_mul (
    .clk_i, .rst_ni, .valid_i(strm_i), .a_i, .b_i, .valid_o(prod_valid_o), .res_o(prod)
  );
  // x's product waits a cycle for y's; z's waits for x + y.
  rc_delay #(.Width(W), .Cycles(1)) u_dly_x (.clk_i, .data_i(prod), .data_o(p_d1));
  rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(La)) u_add_xy (
    .clk_i, .rst_ni, .valid_i(xy_i), .sub_i(1'b0), .a_i(p_d1), .b_i(prod),
    .valid_o(xy_valid_o), .res_o(xy)
  );
  rc_delay #(.Width(W), .Cycles(La - 1)) u_dly_z (.clk_i, .data_i(prod), .data_o(p_dz));
  rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(La)) u_add_z (
    .clk_i, .rst_ni, .valid_i(z_i), .sub_i(1'b0), .a_i(xy), .b_i(p_dz), .valid_o,
    .res_o
  );

endmodule
