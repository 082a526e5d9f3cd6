// rc_fp_div_iter: iterative floating-point divider for the raycore number format: rc_fp_div's
// results and latency from the hardware of one slot pair per lane, for users with few
// operations (the lit board's light units and ray generator).
//
// Contract
// - Function: res_o = a_i / b_i, bit for bit rc_fp_div's (and rc::Fp<ExpW, FracW>::operator/,
//   tb/fp/fp.hpp): the same format rules, the same rounding.
// - Handshake: valid only, no backpressure. valid_o is valid_i delayed by exactly Stages cycles;
//   res_o belongs to the inputs presented Stages cycles earlier and is meaningful only while
//   valid_o is 1, as rc_fp_div.
// - Throughput: operation i goes to lane i mod Lanes, which is busy for Interval = Iters + 1
//   cycles (Iters = FracW / 2: 8 at fp24, so 9): operations i and i + Lanes must come at least
//   Interval cycles apart (assertion). A user with at most Lanes operations in any Interval
//   consecutive cycles meets this: the lit board's light units (two users at a job per 12
//   cycles, Lanes 2) and ray generator (one per 6, Lanes 2).
// - Latency: Stages cycles, Stages >= Iters + 3 (11 at fp24: rc_fp_div's default; checked at
//   elaboration).
// - Parameters: ExpW (>= 2), FracW (>= 2, even); Stages; Lanes (>= 1).
// - Illegal input: none; every bit pattern of a_i and b_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears the lanes' busy bits, the lane pointer and
//   the valid pipeline; data registers have no reset.
//
// Algorithm: rc_fp_div's radix-2 restoring division, slot for slot (N = FracW + 2 quotient bits;
// slot 0 unpacks and takes bit 1, slots 2 .. N - 1 one bit each, slot N the last bit with the
// rounding decision, slot N + 1 the rounding). Cycle 0: slots 0 and 1 (rc_fp_div_pre) into the
// lane's state register. Cycles 1 .. Iters: the lane's state goes once through slots k and
// k + 1 (k = 2, 4, .., N - 2) and back: slot k subtracts the divisor from the remainder, and
// slot k + 1 subtracts from the same remainder for both of slot k's outcomes (2R - D and 2R -
// 3D, as rc_fp_div's slots that share a cycle), so one carry chain and a select per cycle; the
// quotient bits shift in from the bottom. Cycle Iters + 1: slot N on the lane whose operation is
// there (rc_fp_div_fin) into a register. Cycle Iters + 2: the rounding (rc_fp_round_pack), then
// Stages - Iters - 2 output registers. These are rc_fp_div's cycles at its default Stages 11
// (slots {0, 1} {2, 3} .. {16, 17} {18} {19}), so the paths are the ones that close 100 MHz
// there, with a multiplexer in front of each state register.
module rc_fp_div_iter #(
  parameter int unsigned ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW  = rc_pkg::Fp24FracW,
  parameter int unsigned Stages = rc_pkg::FpStagesDiv,
  parameter int unsigned Lanes  = 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  input  logic [ExpW+FracW:0] a_i,
  input  logic [ExpW+FracW:0] b_i,
  output logic                valid_o,
  output logic [ExpW+FracW:0] res_o
);

  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned ManW  = FracW + 1;           // significand with the hidden bit
  localparam int unsigned RemW  = ManW + 1;            // partial remainder, < 2 * divisor
  localparam int unsigned ExW   = ExpW + 2;            // unbounded exponent, two's complement
  localparam int unsigned HdrW  = 4 + ExW;             // rc_fp_div_pre's header
  localparam int unsigned D3W   = ManW + 2;            // three times the divisor's significand
  localparam int unsigned Iters = FracW / 2;           // slot pairs 2 .. N - 1
  localparam int unsigned FinW  = 2 * rc_pkg::FpResultKindBits + 2 + ExpW + FracW + 1;
  // A lane's state: {header, divisor fraction, 3 x divisor, partial remainder, quotient bits so
  // far (MSB first, bit 1 at the top once all are in)}.
  localparam int unsigned StW   = HdrW + FracW + D3W + RemW + ManW;

  if (ExpW < 2 || FracW < 2 || FracW % 2 != 0) begin : g_width_check
    $error("rc_fp_div_iter: need ExpW >= 2 and FracW >= 2, even (slot pairs)");
  end
  if (Stages < Iters + 3) begin : g_stages_check
    $error("rc_fp_div_iter: Stages must be at least FracW / 2 + 3");
  end
  if (Lanes < 1) begin : g_lanes_check
    $error("rc_fp_div_iter: Lanes must be at least 1");
  end

  ////////////////////////////////////////
  // Cycle 0: slots 0 and 1, lane pick  //
  ////////////////////////////////////////

  logic [HdrW-1:0]  hdr0;
  logic [FracW-1:0] dvs0;
  logic [D3W-1:0]   d30;
  logic [RemW-1:0]  rem0;
  logic [StW-1:0]   st0;
  rc_fp_div_pre #(
    .ExpW (ExpW),
    .FracW(FracW)
  ) u_pre (
    .a_i,
    .b_i,
    .hdr_o (hdr0),
    .dvs_o (dvs0),
    .dvs3_o(d30),
    .rem_o (rem0)
  );
  // Slot 1 (its bit always 1, its subtraction rc_fp_div_pre's) passes its remainder doubled.
  logic unused_rem0;
  assign unused_rem0 = rem0[RemW-1];  // 0: rem0 is below the divisor
  assign st0 = {hdr0, dvs0, d30, rem0[ManW-1:0], 1'b0, ManW'(1)};

  ///////////////////////////////////////////
  // Cycles 1 .. Iters: a slot pair a lane //
  ///////////////////////////////////////////

  // take[l]: lane l takes this cycle's operation; st_f: the state of the lane whose operation
  // is at cycle Iters + 1 (slots 1 .. N - 1 done). Operations i and i + Lanes at least Iters + 1
  // cycles apart (rc_fp_lanes' assertion).
  logic [Lanes-1:0]     take;
  logic [Lanes*StW-1:0] st_all;
  logic [StW-1:0]       st_f;
  rc_fp_lanes #(
    .Lanes(Lanes),
    .Iters(Iters),
    .Width(StW)
  ) u_lanes (
    .clk_i,
    .rst_ni,
    .valid_i,
    .take_o (take),
    .state_i(st_all),
    .fin_o  (st_f)
  );

  for (genvar l = 0; l < Lanes; l++) begin : g_lane
    logic [StW-1:0]   st_q;
    logic [HdrW-1:0]  hdr;
    logic [FracW-1:0] dvs;
    logic [D3W-1:0]   dvs3;
    logic [RemW-1:0]  rem;
    logic [ManW-1:0]  quo;
    // Slot k: the divisor fits or not.
    logic [RemW:0]    diff_a;
    logic             q_a;
    logic [ManW-1:0]  kept_a;
    // Slot k + 1, from slot k's input remainder for both of slot k's outcomes.
    logic [RemW:0]    diff_kept, diff_sub, diff_b;
    logic             q_b;
    logic [RemW-1:0]  rem_b;
    logic [ManW-1:0]  kept_b;
    logic             unused_top;

    assign {hdr, dvs, dvs3, rem, quo} = st_q;
    assign unused_top = ^quo[ManW-1 -: 2];  // the bits shifted out (the last turn's is unread)

    assign diff_a    = {1'b0, rem} - {3'b001, dvs};
    assign q_a       = ~diff_a[RemW];
    assign kept_a    = ManW'(q_a ? diff_a[RemW-1:0] : rem);
    // Kept R: slot k + 1's remainder is 2R; kept R - D: 2R - 2D, so its difference is 2R - 3D
    // (both modulo 2^(RemW + 1), as a chained subtraction; a kept R is below the divisor, so its
    // top bit is 0 and not needed).
    assign diff_kept = {1'b0, rem[ManW-1:0], 1'b0} - {3'b001, dvs};
    assign diff_sub  = {rem, 1'b0} - dvs3;
    assign diff_b    = q_a ? diff_sub : diff_kept;
    assign q_b       = ~diff_b[RemW];
    assign rem_b     = {kept_a, 1'b0};
    assign kept_b    = ManW'(q_b ? diff_b[RemW-1:0] : rem_b);

    // The state: taken in cycle 0, then a pair per cycle (an idle lane's state turns over
    // unread).
    always_ff @(posedge clk_i) begin
      if (take[l]) begin
        st_q <= st0;
      end else begin
        st_q <= {hdr, dvs, dvs3, kept_b, 1'b0, quo[ManW-3:0], q_a, q_b};
      end
    end

    assign st_all[l*StW +: StW] = st_q;
  end

  //////////////////////////////////////////
  // Cycle Iters + 1: slot N, the decision //
  //////////////////////////////////////////

  logic [HdrW-1:0]  hdr_f;
  logic [FracW-1:0] dvs_f;
  logic [D3W-1:0]   dvs3_f;
  logic [RemW-1:0]  rem_f;
  logic [ManW-1:0]  quo_f;
  logic [RemW:0]    diff_f;
  logic [FinW-1:0]  fin_d;
  logic             unused_f;

  assign {hdr_f, dvs_f, dvs3_f, rem_f, quo_f} = st_f;
  assign diff_f   = {1'b0, rem_f} - {3'b001, dvs_f};
  assign unused_f = ^{dvs3_f, diff_f[RemW-1:0]};

  rc_fp_div_fin #(
    .ExpW (ExpW),
    .FracW(FracW)
  ) u_fin (
    .hdr_i(hdr_f),
    .dvs_i(dvs_f),
    .rem_i(rem_f),
    .q_i  (~diff_f[RemW]),
    .man_i(quo_f),
    .fin_o(fin_d)
  );

  // Cycle Iters + 2: the rounding, then the output registers.
  rc_fp_round_out #(
    .ExpW    (ExpW),
    .FracW   (FracW),
    .Cut     (1'b1),
    .DataRegs(Stages - Iters - 2),
    .Stages  (Stages)
  ) u_round (
    .clk_i,
    .rst_ni,
    .valid_i,
    .fin_i  (fin_d),
    .valid_o,
    .res_o
  );

endmodule
