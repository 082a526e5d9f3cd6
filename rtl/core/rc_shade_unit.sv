// rc_shade_unit: headlight shading of one hit (docs/architecture.md, "Shading").
//
// Contract
// - Function: exactly rc::shade() (tb/golden/trace.hpp), bit for bit, with the triangle's
//   normal length, the material's diffuse colour and the ray's inv_len given as inputs:
//     c    = min(abs((dz_i * nlen_i) * inv_len_i), 1.0)      (abs: clear the sign bit)
//     f    = ambient_i + diffuse_i * c
//     rgb_o[8k +: 8] = to_u8(kd_i[k*W +: W] * f)  for k = 0, 1, 2 (R, G, B)  (rc_fp_to_u8)
//   (W = 1 + ExpW + FracW; vector ports are flat, element k at [k*W +: W], the layout of a packed
//   [3][W] array: Yosys 0.23 reads no multi-dimensional packed arrays.)
//   ambient_i and diffuse_i are the format values of ambient and 1 - ambient (rc::shade() rounds
//   both from double once; the harness or the core's configuration supplies those bits).
// - Handshake: valid_i/ready_o in, valid_o/ready_i out, with backpressure. An operation is taken
//   when valid_i & ready_o. ready_o comes from a register (credits, see rc_credit_fifo) and never
//   depends on valid_i or ready_i; valid_o never depends on ready_i. Results leave in order;
//   nothing is dropped or duplicated. tag_i travels with the operation to tag_o.
// - Latency: 4 * mul + cmp + add + to_u8 (2 * cmp + mul + 1) + 1 cycles from the taking edge to
//   valid_o, 31 at the defaults of docs/spec.toml [fp_stages] (multiply 4 · multiply 4 · min 1 ·
//   multiply 4 · add 6 · multiply 4 · to_u8 7 · output FIFO 1), when the FIFO is empty and
//   ready_i is 1.
// - Throughput: one hit per cycle while ready_i is 1 (the FIFO holds Latency + 1 entries, enough
//   credits for every operation in flight).
// - Parameters: ExpW, FracW: the number format (default fp24); TagW: tag bits (>= 1).
//   FracW >= 7 and ExpW >= 4 are required (255.0 in rc_fp_to_u8); anything else is illegal and
//   stops elaboration.
// - Quasi-static inputs: ambient_i and diffuse_i are registered beside their users and read
//   there, not at the taking edge; they may change only while no operation is in flight (checked
//   by an assertion).
// - Illegal input: none for the data inputs; every bit pattern is legal.
// - Reset: rst_ni (active low, asynchronous) clears control state only (valid chains, FIFO
//   pointers and credit count); data registers have no reset.
module rc_shade_unit #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW,
  parameter int unsigned TagW  = 8
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  // Input handshake.
  input  logic                     valid_i,
  output logic                     ready_o,
  input  logic [TagW-1:0]          tag_i,
  input  logic [ExpW+FracW:0]      dz_i,
  input  logic [ExpW+FracW:0]      nlen_i,
  input  logic [ExpW+FracW:0]      inv_len_i,
  input  logic [3*(ExpW+FracW+1)-1:0] kd_i,  // R, G, B
  // Quasi-static shading constants.
  input  logic [ExpW+FracW:0]      ambient_i,
  input  logic [ExpW+FracW:0]      diffuse_i,
  // Output handshake.
  output logic                     valid_o,
  input  logic                     ready_i,
  output logic [TagW-1:0]          tag_o,
  output logic [23:0]              rgb_o   // R [7:0], G [15:8], B [23:16]
);

  ////////////////
  // Parameters //
  ////////////////

  if (TagW < 1 || FracW < 7 || ExpW < 4) begin : g_param_check
    $error("rc_shade_unit: need TagW >= 1, FracW >= 7 and ExpW >= 4 (255.0 must be a normal)");
  end

  localparam int unsigned W         = 1 + ExpW + FracW;
  // Latencies of the fp units: the rc_fp_* defaults, both from docs/spec.toml [fp_stages].
  localparam int unsigned MulStages = rc_pkg::FpStagesMul;
  localparam int unsigned AddStages = rc_pkg::FpStagesAdd;
  localparam int unsigned CmpStages = rc_pkg::FpStagesCmp;
  localparam int unsigned U8Stages  = 2 * CmpStages + MulStages + 1;  // rc_fp_to_u8's latency
  // take -> FIFO write: three multiplies to c, min, multiply, add, kd multiply, to_u8.
  localparam int unsigned PipeLat   = 4 * MulStages + CmpStages + AddStages + U8Stages;
  localparam int unsigned FifoDepth = PipeLat + 2;  // full throughput
  localparam int unsigned KdDly     = 3 * MulStages + CmpStages + AddStages;  // take to kd * f
  localparam int unsigned OutW      = TagW + 24;

  localparam logic [ExpW-1:0] Bias = ExpW'((1 << (ExpW - 1)) - 1);
  localparam logic [W-1:0]    One  = {1'b0, Bias, {FracW{1'b0}}};

  logic take;
  assign take = valid_i & ready_o;

  // The tag travels the whole pipeline; kd waits for f.
  logic [PipeLat*TagW-1:0] tag_q;
  logic [KdDly*3*W-1:0]    kd_q;
  logic [3*W-1:0]          kd_f;  // kd beside f
  always_ff @(posedge clk_i) begin
    tag_q <= (tag_q << TagW) | (PipeLat*TagW)'(tag_i);
    kd_q  <= (kd_q << (3*W)) | (KdDly*3*W)'(kd_i);
  end
  assign kd_f = kd_q[KdDly*3*W-1 -: 3*W];

  //////////////////////////////////////
  // p1 = dz * nlen, p2 = p1 * inv_len //
  //////////////////////////////////////

  logic         p1_valid, p2_valid;
  logic [W-1:0] p1, p2;

  rc_fp_mul #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(MulStages)
  ) u_mul_nlen (
    .clk_i,
    .rst_ni,
    .valid_i(take),
    .a_i    (dz_i),
    .b_i    (nlen_i),
    .valid_o(p1_valid),
    .res_o  (p1)
  );

  logic [MulStages*W-1:0] inv_len_q;
  always_ff @(posedge clk_i) begin
    inv_len_q <= (inv_len_q << W) | (MulStages*W)'(inv_len_i);
  end

  rc_fp_mul #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(MulStages)
  ) u_mul_inv_len (
    .clk_i,
    .rst_ni,
    .valid_i(p1_valid),
    .a_i    (p1),
    .b_i    (inv_len_q[MulStages*W-1 -: W]),
    .valid_o(p2_valid),
    .res_o  (p2)
  );

  //////////////////////////////
  // c = min(abs(p2), 1.0)    //
  //////////////////////////////

  logic         c_valid;
  logic [W-1:0] p2_abs, c;
  logic         unused_c_lt, unused_c_le, unused_c_eq;
  logic [W-1:0] unused_c_max;

  logic unused_p2_sign;  // abs clears the sign bit
  assign p2_abs         = {1'b0, p2[W-2:0]};
  assign unused_p2_sign = p2[W-1];

  rc_fp_cmp #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(CmpStages)
  ) u_min_c (
    .clk_i,
    .rst_ni,
    .valid_i(p2_valid),
    .a_i    (p2_abs),
    .b_i    (One),
    .valid_o(c_valid),
    .lt_o   (unused_c_lt),
    .le_o   (unused_c_le),
    .eq_o   (unused_c_eq),
    .min_o  (c),
    .max_o  (unused_c_max)
  );

  ////////////////////////////////////
  // f = ambient + diffuse * c      //
  ////////////////////////////////////

  logic         dc_valid, f_valid;
  logic [W-1:0] dc, f;

  // The constants registered beside their users: they come from the board's register file or the
  // core's ports, across the chip (run 65 seed 1: regs_q -> u_add_ambient.k1_q, -0.49 ns). They
  // change only with nothing in flight (ConstantsQuasiStatic_A), and a hit taken in the cycle of
  // a change reaches them many cycles later, so a cycle's delay changes no result.
  logic [W-1:0] ambient_q, diffuse_q;
  always_ff @(posedge clk_i) begin
    ambient_q <= ambient_i;
    diffuse_q <= diffuse_i;
  end

  rc_fp_mul #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(MulStages)
  ) u_mul_diffuse (
    .clk_i,
    .rst_ni,
    .valid_i(c_valid),
    .a_i    (diffuse_q),
    .b_i    (c),
    .valid_o(dc_valid),
    .res_o  (dc)
  );

  rc_fp_add #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(AddStages)
  ) u_add_ambient (
    .clk_i,
    .rst_ni,
    .valid_i(dc_valid),
    .sub_i  (1'b0),
    .a_i    (ambient_q),
    .b_i    (dc),
    .valid_o(f_valid),
    .res_o  (f)
  );

  //////////////////////////////////////////////
  // channel = kd * f, byte = to_u8(channel)  //
  //////////////////////////////////////////////

  logic [2:0]     ch_valid, u8_valid;
  logic [3*W-1:0] ch;
  logic [23:0]    rgb;

  for (genvar k = 0; k < 3; k++) begin : g_channel
    rc_fp_mul #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(MulStages)
    ) u_mul_kd (
      .clk_i,
      .rst_ni,
      .valid_i(f_valid),
      .a_i    (kd_f[k*W +: W]),
      .b_i    (f),
      .valid_o(ch_valid[k]),
      .res_o  (ch[k*W +: W])
    );

    rc_fp_to_u8 #(
      .ExpW (ExpW),
      .FracW(FracW)
    ) u_to_u8 (
      .clk_i,
      .rst_ni,
      .valid_i(ch_valid[k]),
      .x_i    (ch[k*W +: W]),
      .valid_o(u8_valid[k]),
      .byte_o (rgb[k*8 +: 8])
    );
  end

  /////////////////////////////
  // Output FIFO and credits //
  /////////////////////////////

  rc_credit_fifo #(
    .Width   (OutW),
    .Depth   (FifoDepth),
    .MemArray(1'b1)   // distributed RAM: a flat register file of this depth costs ~3,000 LUT4s
  ) u_fifo (
    .clk_i,
    .rst_ni,
    .take_i    (take),
    .credit_o  (ready_o),
    .wr_valid_i(u8_valid[0]),
    .wr_data_i ({tag_q[PipeLat*TagW-1 -: TagW], rgb}),
    .valid_o,
    .ready_i,
    .data_o    ({tag_o, rgb_o})
  );

  ////////////////
  // Assertions //
  ////////////////

`ifndef SYNTHESIS
  // Simulation-only: 1 from the first clock edge after a reset (rc_checks_on).
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  // Operations between the taking edge and the FIFO write (simulation-only bookkeeping).
  logic [$clog2(PipeLat + 2)-1:0] inflight_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      inflight_q <= '0;
    end else begin
      inflight_q <= inflight_q + $bits(inflight_q)'(take) - $bits(inflight_q)'(u8_valid[0]);
    end
  end

  // ambient_i and diffuse_i are sampled mid-pipeline: changing them with operations in flight
  // would shade those operations with a mix of old and new constants.
  ConstantsQuasiStatic_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                           !$stable({ambient_i, diffuse_i}) |-> inflight_q == '0);
  // The three channels run in lock step.
  ChannelsLockStep_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                       (&ch_valid == |ch_valid) && (&u8_valid == |u8_valid));
  // ready_o must be known once out of reset (upstream acts on it).
  ReadyKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !$isunknown(ready_o));
`endif

endmodule
