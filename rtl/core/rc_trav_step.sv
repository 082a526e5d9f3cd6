// rc_trav_step: one kd-tree traversal step of one ray at one inner node (docs/architecture.md,
// "Traversal").
//
// Contract
// - Function: exactly rc::trav_step() (tb/golden/trace.hpp), bit for bit:
//     t = (split_i - org_i) * inv_i             (format subtract, then multiply)
//     case_o = 0 (kBothWhole) if t is NaN
//              1 (kNearOnly)  elif lt(tmax_i, t)
//              2 (kFarOnly)   elif lt(t, tmin_i)
//              3 (kBothSplit) otherwise
//   t_o = t (whatever the case). The encoding of case_o is the order of rc::StepCase.
// - Handshake: valid_i/ready_o in, valid_o/ready_i out, with backpressure. An operation is taken
//   when valid_i & ready_o. ready_o comes from a register (credits, see rc_credit_fifo) and never
//   depends on valid_i or ready_i; valid_o never depends on ready_i. Results leave in order;
//   nothing is dropped or duplicated. tag_i travels with the operation to tag_o.
// - Latency: add + mul + cmp + 1 cycles from the taking edge to valid_o, 12 at the defaults of
//   docs/spec.toml [fp_stages] (subtract 6 + multiply 4 + compare 1 + output FIFO 1), when the
//   FIFO is empty and ready_i is 1.
// - Throughput: one operation per cycle while ready_i is 1 (the FIFO holds Latency + 1 entries,
//   enough credits for every operation in flight). With ready_i low the unit accepts until the
//   credits run out, then holds ready_o low.
// - Parameters: ExpW, FracW: the number format (default fp24); TagW: tag bits (>= 1);
//   Backpressure (below): 0 for a consumer that takes every result at once (no FIFO).
// - Illegal input: none; every bit pattern of the data inputs is legal.
// - Reset: rst_ni (active low, asynchronous) clears control state only (valid chains, FIFO
//   pointers and credit count); data registers have no reset.
module rc_trav_step #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW,
  parameter int unsigned TagW  = 8,
  // 1: the output FIFO and credits above; 0: ready_i must always be 1 (rc_core's traversal unit
  // takes every result at once): one output register instead of the FIFO, the same latency,
  // ready_o always 1.
  parameter bit          Backpressure = 1'b1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  // Input handshake.
  input  logic                valid_i,
  output logic                ready_o,
  input  logic [TagW-1:0]     tag_i,
  input  logic [ExpW+FracW:0] split_i,
  input  logic [ExpW+FracW:0] org_i,
  input  logic [ExpW+FracW:0] inv_i,
  input  logic [ExpW+FracW:0] tmin_i,
  input  logic [ExpW+FracW:0] tmax_i,
  // Output handshake.
  output logic                valid_o,
  input  logic                ready_i,
  output logic [TagW-1:0]     tag_o,
  output logic [ExpW+FracW:0] t_o,
  output logic [1:0]          case_o
);

  ////////////////
  // Parameters //
  ////////////////

  if (TagW < 1 || ExpW < 2 || FracW < 1) begin : g_param_check
    $error("rc_trav_step: need TagW >= 1, ExpW >= 2 and FracW >= 1");
  end

  localparam int unsigned W         = 1 + ExpW + FracW;
  // Latencies of the fp units: the rc_fp_* defaults, both from docs/spec.toml [fp_stages].
  localparam int unsigned AddStages = rc_pkg::FpStagesAdd;
  localparam int unsigned MulStages = rc_pkg::FpStagesMul;
  localparam int unsigned CmpStages = rc_pkg::FpStagesCmp;
  localparam int unsigned PipeLat   = AddStages + MulStages + CmpStages;  // take to FIFO write
  localparam int unsigned FifoDepth = PipeLat + 2;                        // full throughput
  localparam int unsigned OutW      = TagW + W + 2;

  localparam logic [1:0] CaseBothWhole = 2'd0;
  localparam logic [1:0] CaseNearOnly  = 2'd1;
  localparam logic [1:0] CaseFarOnly   = 2'd2;
  localparam logic [1:0] CaseBothSplit = 2'd3;

  logic take;
  assign take = valid_i & ready_o;

  //////////////////////////////////////
  // Stage A: d = split - org (3 cyc) //
  //////////////////////////////////////

  logic         sub_valid;
  logic [W-1:0] diff;

  rc_fp_add #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(AddStages)
  ) u_sub (
    .clk_i,
    .rst_ni,
    .valid_i(take),
    .sub_i  (1'b1),
    .a_i    (split_i),
    .b_i    (org_i),
    .valid_o(sub_valid),
    .res_o  (diff)
  );

  // Side data during the subtract: {tag, inv, tmin, tmax}.
  localparam int unsigned SideAW = TagW + 3 * W;
  logic [AddStages*SideAW-1:0] side_a_q;
  always_ff @(posedge clk_i) begin
    side_a_q <= (side_a_q << SideAW) | (AddStages*SideAW)'({tag_i, inv_i, tmin_i, tmax_i});
  end

  logic [TagW-1:0] tag_a;
  logic [W-1:0]    inv_a, tmin_a, tmax_a;
  assign {tag_a, inv_a, tmin_a, tmax_a} = side_a_q[AddStages*SideAW-1 -: SideAW];

  ////////////////////////////////////
  // Stage B: t = d * inv (2 cyc)   //
  ////////////////////////////////////

  logic         mul_valid;
  logic [W-1:0] t_b;

  rc_fp_mul #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(MulStages)
  ) u_mul (
    .clk_i,
    .rst_ni,
    .valid_i(sub_valid),
    .a_i    (diff),
    .b_i    (inv_a),
    .valid_o(mul_valid),
    .res_o  (t_b)
  );

  // Side data during the multiply: {tag, tmin, tmax}.
  localparam int unsigned SideBW = TagW + 2 * W;
  logic [MulStages*SideBW-1:0] side_b_q;
  always_ff @(posedge clk_i) begin
    side_b_q <= (side_b_q << SideBW) | (MulStages*SideBW)'({tag_a, tmin_a, tmax_a});
  end

  logic [TagW-1:0] tag_b;
  logic [W-1:0]    tmin_b, tmax_b;
  assign {tag_b, tmin_b, tmax_b} = side_b_q[MulStages*SideBW-1 -: SideBW];

  ////////////////////////////////////////////////////////
  // Stage C: lt(tmax, t) and lt(t, tmin) (1 cyc), case //
  ////////////////////////////////////////////////////////

  logic         cmp_valid, beyond, behind;
  logic         unused_hi_valid, unused_hi_le, unused_hi_eq, unused_lo_le, unused_lo_eq;
  logic [W-1:0] unused_hi_min, unused_hi_max, unused_lo_min, unused_lo_max;

  // lt(tmax, t): the plane is beyond the interval.
  rc_fp_cmp #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(CmpStages)
  ) u_cmp_hi (
    .clk_i,
    .rst_ni,
    .valid_i(mul_valid),
    .a_i    (tmax_b),
    .b_i    (t_b),
    .valid_o(unused_hi_valid),
    .lt_o   (beyond),
    .le_o   (unused_hi_le),
    .eq_o   (unused_hi_eq),
    .min_o  (unused_hi_min),
    .max_o  (unused_hi_max)
  );

  // lt(t, tmin): the plane is behind the interval.
  rc_fp_cmp #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(CmpStages)
  ) u_cmp_lo (
    .clk_i,
    .rst_ni,
    .valid_i(mul_valid),
    .a_i    (t_b),
    .b_i    (tmin_b),
    .valid_o(cmp_valid),
    .lt_o   (behind),
    .le_o   (unused_lo_le),
    .eq_o   (unused_lo_eq),
    .min_o  (unused_lo_min),
    .max_o  (unused_lo_max)
  );

  // Side data during the compare: {tag, t}.
  localparam int unsigned SideCW = TagW + W;
  logic [CmpStages*SideCW-1:0] side_c_q;
  always_ff @(posedge clk_i) begin
    side_c_q <= (side_c_q << SideCW) | (CmpStages*SideCW)'({tag_b, t_b});
  end

  logic [TagW-1:0] tag_c;
  logic [W-1:0]    t_c;
  logic            t_nan;
  logic [1:0]      case_c;
  assign {tag_c, t_c} = side_c_q[CmpStages*SideCW-1 -: SideCW];
  assign t_nan = (&t_c[W-2 -: ExpW]) & (|t_c[FracW-1:0]);

  // The order of the tests is trav_step()'s: NaN first, then beyond, then behind.
  always_comb begin
    if (t_nan) begin
      case_c = CaseBothWhole;
    end else if (beyond) begin
      case_c = CaseNearOnly;
    end else if (behind) begin
      case_c = CaseFarOnly;
    end else begin
      case_c = CaseBothSplit;
    end
  end

  /////////////////////////////
  // Output FIFO and credits //
  /////////////////////////////

  if (Backpressure) begin : g_fifo
    // Storage as a memory array (distributed RAM): the core's tags make the entries wide.
    rc_credit_fifo #(
      .Width   (OutW),
      .Depth   (FifoDepth),
      .MemArray(1'b1)
    ) u_fifo (
      .clk_i,
      .rst_ni,
      .take_i    (take),
      .credit_o  (ready_o),
      .wr_valid_i(cmp_valid),
      .wr_data_i ({tag_c, t_c, case_c}),
      .valid_o,
      .ready_i,
      .data_o    ({tag_o, t_o, case_o})
    );
  end else begin : g_out_reg
    // Every result is taken as it appears (ready_i is 1), so one output register replaces the
    // FIFO: the same latency, no credits.
    rc_pipe_out #(
      .Width   (OutW),
      .DataRegs(1),
      .Stages  (1)
    ) u_out (
      .clk_i,
      .rst_ni,
      .valid_i(cmp_valid),
      .data_i ({tag_c, t_c, case_c}),
      .valid_o,
      .data_o ({tag_o, t_o, case_o})
    );
    assign ready_o = 1'b1;
    logic unused_ready;   // ready_i must be 1 (NoBackpressure_A)
    assign unused_ready = ready_i;
  end

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

  // The two compare units run in lock step, so their valid chains must agree.
  CmpLockStep_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  cmp_valid == unused_hi_valid);
  // A NaN t compares false both ways; beyond and behind at once would mean tmin > tmax, which is
  // legal input, so only the NaN implication is checked.
  NanComparesFalse_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                       cmp_valid && t_nan |-> !beyond && !behind);
  // Without backpressure the consumer takes every result as it appears.
  NoBackpressure_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                     !Backpressure && valid_o |-> ready_i);
  // ready_o must be known once out of reset (upstream acts on it).
  ReadyKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !$isunknown(ready_o));
`endif

endmodule
