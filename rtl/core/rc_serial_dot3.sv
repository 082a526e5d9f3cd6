// rc_serial_dot3: component-serial dot products (rc_hit_geom, rc_light_term): for each of Users
// users k, the vectors a and b arrive as streams of three consecutive components (x, y, z) and
//   res_o = (a.x * b.x + a.y * b.y) + a.z * b.z
// in the format's arithmetic, in exactly this order (a multiplier per user, then two rc_fp_add
// that every user shares).
//
// Contract
// - Timing, per user k, in cycles after its x components enter (its time 0, strm_i[k]'s first
//   cycle): its products leave its multiplier at Lm, Lm + 1 and Lm + 2 (prod_valid_o[k]); x + y
//   is issued at Lm + 1, when y's product leaves (xy_i[k]), and leaves at Lm + 1 + La
//   (xy_valid_o); z's product, delayed La - 1 cycles, is added to it then (z_i[k]), and the sum
//   leaves at Lm + 1 + 2 La on res_o (valid_o).
// - strm_i[k] is user k's operand stream valid (high for its three cycles); xy_i[k] and z_i[k]
//   are the owner's job times Lm + 1 and Lm + 1 + La of user k (rc_serial_sched at_o). Every
//   valid thus comes from the owner's schedule, and the owner's assertions check the outputs'
//   valids against it; each user reads res_o at its own time.
// - Sharing: the two adders serve every user, so no two users may issue to one adder in a cycle
//   (xy_i and z_i one-hot or zero; assertions): with Users > 1 the owner takes jobs at a fixed
//   phase modulo 3 (rc_serial_sched, Phased) and gives its users times that differ modulo 3.
// - Parameters: ExpW, FracW (the format); Users (1 to 3). Lm and La are the multiplier's and the
//   adder's stages, the package's (docs/spec.toml [fp_stages]), as in the owners.
// - Reset: rst_ni (active low, asynchronous) clears the operators' valid pipelines; data
//   registers have no reset.
module rc_serial_dot3 #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW,
  parameter int unsigned Users = 1,
  // Derived (do not override).
  parameter int unsigned W     = 1 + ExpW + FracW
) (
  input  logic               clk_i,
  input  logic               rst_ni,
  input  logic [Users-1:0]   strm_i,
  input  logic [Users-1:0]   xy_i,
  input  logic [Users-1:0]   z_i,
  input  logic [Users*W-1:0] a_i,
  input  logic [Users*W-1:0] b_i,
  output logic [Users-1:0]   prod_valid_o,
  output logic               xy_valid_o,
  output logic               valid_o,
  output logic [W-1:0]       res_o
);

  localparam int unsigned Lm = rc_pkg::FpStagesMul;
  localparam int unsigned La = rc_pkg::FpStagesAdd;

  if (La < 2 || Users < 1 || Users > 3) begin : g_param_check
    $error("rc_serial_dot3: the adder needs at least 2 stages, and Users must be 1 to 3");
  end

  // Per user: its products; x's product a cycle later (for x + y), z's La - 1 cycles later (for
  // the sum).
  logic [Users*W-1:0] prod, p_d1, p_dz;
  for (genvar k = 0; k < Users; k++) begin : g_user
    rc_fp_mul #(.ExpW(ExpW), .FracW(FracW), .Stages(Lm)) u_mul (
      .clk_i, .rst_ni, .valid_i(strm_i[k]), .a_i(a_i[k*W +: W]), .b_i(b_i[k*W +: W]),
      .valid_o(prod_valid_o[k]), .res_o(prod[k*W +: W])
    );
    rc_delay #(.Width(W), .Cycles(1)) u_dly_x (
      .clk_i, .data_i(prod[k*W +: W]), .data_o(p_d1[k*W +: W])
    );
    rc_delay #(.Width(W), .Cycles(La - 1)) u_dly_z (
      .clk_i, .data_i(prod[k*W +: W]), .data_o(p_dz[k*W +: W])
    );
  end

  // The adders' operands: the issuing user's (AND-OR selects by the one-hot issue times; a
  // single user's go straight in).
  logic [W-1:0] xy_a, xy_b, z_b, xy;
  if (Users == 1) begin : g_one
    assign xy_a = p_d1;
    assign xy_b = prod;
    assign z_b  = p_dz;
  end else begin : g_shared
    always_comb begin
      xy_a = '0;
      xy_b = '0;
      z_b  = '0;
      for (int unsigned k = 0; k < Users; k++) begin
        xy_a = xy_a | ({W{xy_i[k]}} & p_d1[k*W +: W]);
        xy_b = xy_b | ({W{xy_i[k]}} & prod[k*W +: W]);
        z_b  = z_b | ({W{z_i[k]}} & p_dz[k*W +: W]);
      end
    end
  end

  rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(La)) u_add_xy (
    .clk_i, .rst_ni, .valid_i(|xy_i), .sub_i(1'b0), .a_i(xy_a), .b_i(xy_b),
    .valid_o(xy_valid_o), .res_o(xy)
  );
  rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(La)) u_add_z (
    .clk_i, .rst_ni, .valid_i(|z_i), .sub_i(1'b0), .a_i(xy), .b_i(z_b), .valid_o, .res_o
  );

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // One user at a time in each shared adder (the owner's times differ modulo 3).
  OneUser_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              $onehot0(xy_i) && $onehot0(z_i));
`endif

endmodule
