// rc_xform_unit: the transform unit, a 3x4 matrix times a 3-vector, for the raycore number format.
//
// Contract
// - Function: for each row r = 0..2, with x = v[0], y = v[1], z = v[2] and every operation a
//   correctly rounded format operation (rc_fp_mul / rc_fp_add), exactly
//     r_o[r] = ((m[4r] * x + m[4r+1] * y) + m[4r+2] * z)              when translate = 0
//     r_o[r] = ((m[4r] * x + m[4r+1] * y) + m[4r+2] * z) + m[4r+3]    when translate = 1
//   (docs/architecture.md, "Intersection"; tb/golden/trace.hpp intersect()). With translate = 0
//   there is no final add at all (adding +0 would turn a -0 row result into +0).
// - Packing: a word is {sign, exp[ExpW-1:0], frac[FracW-1:0]}, W = 1 + ExpW + FracW bits.
//   m_i[k*W +: W] = m_k (k = 0..11, row-major), v_i[(3*r+c)*W +: W] = component c (x, y, z)
//   of the vector for row r: one copy per row, so that a caller can place a register beside
//   each row's multipliers (every caller passes the same vector three times; the rows use only
//   their own copy). r_o[r*W +: W] = row r. tag_i is carried unchanged to tag_o.
// - rt_o (Backpressure = 0 only; 0 with Backpressure = 1): the rows' results as if translate
//   were 1, without the row select: equal to r_o whenever valid_o is 1 for a vector with
//   translate = 1 (RtEq_A). A caller that reads only translated results takes them from here,
//   so no select flip-flop is in its path (rc_isect_unit's divider: run 71 seed 3, sel_o_q into
//   the divider's first slot, -1.71 ns).
// - Handshake (Backpressure = 1): valid_i/ready_o at the input, valid_o/ready_i at the output,
//   AXI-style (a transfer happens on a clock edge where valid and ready are both 1). valid_o never
//   depends on ready_i, ready_o depends only on registered state, and once valid_o is 1 it stays
//   1 with r_o/tag_o stable until the transfer. Results leave in input order, none is lost or
//   duplicated. The fp pipelines cannot stall, so the unit uses credits (rc_credit_fifo): an
//   output FIFO of Depth = PipeLat + 2 entries, and ready_o = credits < Depth, where credits =
//   inputs accepted - outputs taken = operations in flight + FIFO occupancy (one registered
//   counter), so the FIFO always has room for everything in flight. PipeLat + 2 is the least
//   depth that sustains one input per cycle (in steady state PipeLat results are in flight and
//   one waits in the FIFO).
//   Backpressure = 0: a bare valid-only pipeline for use inside other units: ready_o is always 1,
//   ready_i is ignored, valid_o is valid_i delayed by exactly PipeLat cycles (no FIFO).
// - Latency: PipeLat = MulStages + 3 * AddStages cycles through the arithmetic (22 at the
//   defaults 4 and 6, the rc_fp_* default latencies). Backpressure = 1 adds the FIFO's output
//   register: valid_o rises PipeLat + 1 cycles (23 at the defaults) after an accepted input when
//   ready_i is high.
// - Throughput: one vector per cycle (with ready_i held high, ready_o stays 1).
// - Parameters: ExpW (>= 2), FracW (>= 1): the format; TagW (>= 1): width of the tag carried
//   alongside; MulStages, AddStages (>= 1): the latencies of the rc_fp_mul / rc_fp_add
//   instances; Backpressure: 1 = valid/ready with the output FIFO, 0 = valid-only pipeline;
//   BlockDelays: 1 = the delay lines (the tag's, m3's, p2's and b's, the three rows' words side
//   by side) in block RAM (rc_delay_line), 0 = shift registers; the same results either way.
// - Illegal input: none; every bit pattern of every input is legal.
// - Reset: rst_ni (active low, asynchronous) clears control state only (valid pipelines, FIFO
//   pointers and counters); data registers have no reset.
//
// Pipeline per row (all three rows in parallel; x = multiply, + = add):
//   cycle 0            : the three products m0*x, m1*y, m2*z start together
//   MulStages          : a = p0 + p1 starts; p2 waits AddStages cycles in a delay line
//   MulStages + A      : b = a + p2 starts; m3 (delayed since cycle 0) waits here
//   MulStages + 2A     : c = b + m3 starts; b waits AddStages cycles in a delay line
//   MulStages + 3A     : r = translate ? c : b   (translate delayed alongside)
module rc_xform_unit #(
  parameter int unsigned ExpW         = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW        = rc_pkg::Fp24FracW,
  parameter int unsigned TagW         = 8,
  parameter int unsigned MulStages    = rc_pkg::FpStagesMul,
  parameter int unsigned AddStages    = rc_pkg::FpStagesAdd,
  parameter bit          Backpressure = 1'b1,
  parameter bit          BlockDelays  = 1'b0
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  // Input
  input  logic                         valid_i,
  output logic                         ready_o,
  input  logic [12*(1+ExpW+FracW)-1:0] m_i,
  input  logic [9*(1+ExpW+FracW)-1:0]  v_i,
  input  logic                         translate_i,
  input  logic [TagW-1:0]              tag_i,
  // Output
  output logic                         valid_o,
  input  logic                         ready_i,
  output logic [3*(1+ExpW+FracW)-1:0]  r_o,
  output logic [3*(1+ExpW+FracW)-1:0]  rt_o,
  output logic [TagW-1:0]              tag_o
);

  ////////////////
  // Parameters //
  ////////////////

  if (ExpW < 2 || FracW < 1 || TagW < 1) begin : g_param_check
    $error("rc_xform_unit: need ExpW >= 2, FracW >= 1, TagW >= 1");
  end
  if (MulStages < 1 || AddStages < 1) begin : g_stages_check
    $error("rc_xform_unit: MulStages and AddStages must be >= 1");
  end

  localparam int unsigned W       = 1 + ExpW + FracW;
  localparam int unsigned PipeLat = MulStages + 3 * AddStages;
  // Delay of m3 and translate from the input to the last add.
  localparam int unsigned M3Dly   = MulStages + 2 * AddStages;

  //////////////////////////////
  // Input side of the credit //
  //////////////////////////////

  logic in_fire;
  assign in_fire = valid_i & ready_o;

  ////////////////
  // Datapath   //
  ////////////////

  logic [2:0]     mul_valid, add_a_valid, add_b_valid, add_c_valid;
  logic [3*W-1:0] res, res_t;

  // Tag and translate flag ride along for the whole pipeline.
  logic [TagW-1:0] pipe_tag;
  rc_delay_line #(.Width(TagW), .Cycles(PipeLat), .Block(BlockDelays)) u_dly_tag (
    .clk_i, .rst_ni, .data_i(tag_i), .data_o(pipe_tag)
  );

  logic [M3Dly-1:0] tr_dly_q;
  always_ff @(posedge clk_i) begin
    tr_dly_q <= (tr_dly_q << 1) | M3Dly'(translate_i);
  end

  // Delays translate a further AddStages cycles, to the row select at the end: one copy per row,
  // each of a different function (row 0 the inverse, row 1 ANDed with the row's valid, row 2
  // ORed with its invalid), equal to translate whenever the row's result is valid. So synthesis
  // keeps three flip-flops, each selecting its own row's W bits, and none of them is the tag line's
  // copy of translate, which a caller may carry in tag_i (rc_isect_unit does): run 49, one
  // flip-flop selecting all 72 bits into the intersection divider, -2.73 ns. tr_end_q is the
  // plain delay the copies are checked against (RowSel_A).
  logic [AddStages-1:0] tr_end_q, sel_n_q, sel_v_q, sel_o_q;
  logic [2:0]           row_sel;
  logic                 tr_b, sel_n_d, sel_v_d, sel_o_d;  // at the third add's input
  assign tr_b    = tr_dly_q[M3Dly-1];
  assign sel_n_d = ~tr_b;
  assign sel_v_d = tr_b & add_b_valid[1];
  assign sel_o_d = tr_b | ~add_b_valid[2];
  always_ff @(posedge clk_i) begin
    tr_end_q <= (tr_end_q << 1) | AddStages'(tr_b);
    sel_n_q  <= (sel_n_q << 1) | AddStages'(sel_n_d);
    sel_v_q  <= (sel_v_q << 1) | AddStages'(sel_v_d);
    sel_o_q  <= (sel_o_q << 1) | AddStages'(sel_o_d);
  end
  assign row_sel = {sel_o_q[AddStages-1], sel_v_q[AddStages-1], ~sel_n_q[AddStages-1]};

  // The rows' delay lines, their three words side by side (the rows run in lockstep): m3 waits
  // from the input until the last add, p2 for the first add, and b alongside the last add.
  logic [3*W-1:0] m3_all, m3_dly, p2_all, p2_dly, b_all, b_dly;
  for (genvar r = 0; r < 3; r++) begin : g_m3
    assign m3_all[r*W +: W] = m_i[(4*r+3)*W +: W];
  end
  rc_delay_line #(.Width(3 * W), .Cycles(M3Dly), .Block(BlockDelays)) u_dly_m3 (
    .clk_i, .rst_ni, .data_i(m3_all), .data_o(m3_dly)
  );
  rc_delay_line #(.Width(3 * W), .Cycles(AddStages), .Block(BlockDelays)) u_dly_p2 (
    .clk_i, .rst_ni, .data_i(p2_all), .data_o(p2_dly)
  );
  rc_delay_line #(.Width(3 * W), .Cycles(AddStages), .Block(BlockDelays)) u_dly_b (
    .clk_i, .rst_ni, .data_i(b_all), .data_o(b_dly)
  );

  for (genvar r = 0; r < 3; r++) begin : g_row
    logic [W-1:0] p0, p1, p2, sum_a, sum_b, sum_c;
    logic         mul1_valid, mul2_valid;
    // The three multiplies of a row run in lockstep; only the first one's valid is used.
    logic         unused_mul_valid;
    assign unused_mul_valid = mul1_valid ^ mul2_valid;

    rc_fp_mul #(.ExpW(ExpW), .FracW(FracW), .Stages(MulStages)) u_mul0 (
      .clk_i, .rst_ni, .valid_i(in_fire), .a_i(m_i[(4*r+0)*W +: W]), .b_i(v_i[(3*r+0)*W +: W]),
      .valid_o(mul_valid[r]), .res_o(p0)
    );
    rc_fp_mul #(.ExpW(ExpW), .FracW(FracW), .Stages(MulStages)) u_mul1 (
      .clk_i, .rst_ni, .valid_i(in_fire), .a_i(m_i[(4*r+1)*W +: W]), .b_i(v_i[(3*r+1)*W +: W]),
      .valid_o(mul1_valid), .res_o(p1)
    );
    rc_fp_mul #(.ExpW(ExpW), .FracW(FracW), .Stages(MulStages)) u_mul2 (
      .clk_i, .rst_ni, .valid_i(in_fire), .a_i(m_i[(4*r+2)*W +: W]), .b_i(v_i[(3*r+2)*W +: W]),
      .valid_o(mul2_valid), .res_o(p2)
    );

    assign p2_all[r*W +: W] = p2;

    rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(AddStages)) u_add_a (
      .clk_i, .rst_ni, .valid_i(mul_valid[r]), .sub_i(1'b0), .a_i(p0), .b_i(p1),
      .valid_o(add_a_valid[r]), .res_o(sum_a)
    );
    rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(AddStages)) u_add_b (
      .clk_i, .rst_ni, .valid_i(add_a_valid[r]), .sub_i(1'b0), .a_i(sum_a),
      .b_i(p2_dly[r*W +: W]), .valid_o(add_b_valid[r]), .res_o(sum_b)
    );
    rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(AddStages)) u_add_c (
      .clk_i, .rst_ni, .valid_i(add_b_valid[r]), .sub_i(1'b0), .a_i(sum_b),
      .b_i(m3_dly[r*W +: W]), .valid_o(add_c_valid[r]), .res_o(sum_c)
    );

    // Without translation the row result is sum_b itself, delayed to line up with sum_c.
    assign b_all[r*W +: W] = sum_b;
    assign res[r*W +: W]   = row_sel[r] ? sum_c : b_dly[r*W +: W];
    assign res_t[r*W +: W] = sum_c;
  end

  logic            pipe_valid;
  assign pipe_valid = add_c_valid[0];

  // Only row 0's valid chain is used; the others are identical (checked below).
  logic unused_valid;
  assign unused_valid = ^{mul_valid[2:1], add_a_valid[2:1], add_b_valid[2:1], add_c_valid[2:1]};

  ///////////////////////////////
  // Output: credit FIFO or not //
  ///////////////////////////////

  if (Backpressure) begin : g_fifo
    // rc_credit_fifo holds the credit counter, the FIFO and their checks; Depth = PipeLat + 2
    // sustains one vector per cycle, storage in distributed RAM (MemArray).
    rc_credit_fifo #(.Width(TagW + 3 * W), .Depth(PipeLat + 2), .MemArray(1'b1)) u_fifo (
      .clk_i, .rst_ni, .take_i(in_fire), .credit_o(ready_o), .wr_valid_i(pipe_valid),
      .wr_data_i({pipe_tag, res}), .valid_o, .ready_i, .data_o({tag_o, r_o})
    );
    assign rt_o = '0;
    logic unused_res_t;
    assign unused_res_t = ^res_t;
  end else begin : g_nofifo
    assign ready_o = 1'b1;
    assign valid_o = pipe_valid;
    assign r_o     = res;
    assign rt_o    = res_t;
    assign tag_o   = pipe_tag;
    logic unused_ready;
    assign unused_ready = ready_i;
  end

  ////////////////
  // Assertions //
  ////////////////

`ifndef SYNTHESIS
  logic chk_on_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      chk_on_q <= 1'b0;
    end else begin
      chk_on_q <= 1'b1;
    end
  end
  // The three rows run in lockstep; diverging valids would mean misaligned delay lines.
  RowsLockstep_A: assert property (@(posedge clk_i) disable iff (chk_on_q !== 1'b1)
                                   (&add_c_valid || ~|add_c_valid) && (&mul_valid || ~|mul_valid));
  // Each row's select is translate whenever the row's result is valid.
  RowSel_A: assert property (@(posedge clk_i) disable iff (chk_on_q !== 1'b1)
                             add_c_valid[0] |-> row_sel == {3{tr_end_q[AddStages-1]}});
  // rt_o is r_o for a translated vector (Backpressure = 0; the FIFO build ties it to 0).
  RtEq_A: assert property (@(posedge clk_i) disable iff (chk_on_q !== 1'b1)
                           !Backpressure && valid_o && tr_end_q[AddStages-1] |-> rt_o == r_o);
  // The consumer qualifies everything with valid_o, so it must be known once out of reset.
  ValidKnown_A: assert property (@(posedge clk_i) disable iff (chk_on_q !== 1'b1)
                                 !$isunknown({valid_o, ready_o}));
  // A valid result is fully determined by known inputs.
  ResKnown_A: assert property (@(posedge clk_i) disable iff (chk_on_q !== 1'b1)
                               valid_o |-> !$isunknown(r_o));
`endif

endmodule
