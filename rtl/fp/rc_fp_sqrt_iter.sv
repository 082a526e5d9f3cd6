// rc_fp_sqrt_iter: iterative floating-point square root for the raycore number format:
// rc_fp_sqrt's results and latency from the hardware of one slot pair per lane, for users with
// few operations (the lit board's light units and ray generator).
//
// Contract
// - Function: res_o = sqrt(a_i), bit for bit rc_fp_sqrt's (and sqrt(rc::Fp<ExpW, FracW>),
//   tb/fp/fp.hpp): the same format rules, the same rounding.
// - Handshake: valid only, no backpressure. valid_o is valid_i delayed by exactly Stages cycles;
//   res_o belongs to the input presented Stages cycles earlier and is meaningful only while
//   valid_o is 1, as rc_fp_sqrt.
// - Throughput: operation i goes to lane i mod Lanes, which is busy for Interval = Iters + 1
//   cycles (Iters = (FracW - 2) / 2: 7 at fp24, so 8): operations i and i + Lanes must come at
//   least Interval cycles apart (assertion). A user with at most Lanes operations in any
//   Interval consecutive cycles meets this: the lit board's light units (two users at a job per
//   12 cycles, Lanes 2) and ray generator (one per 6, Lanes 2).
// - Latency: Stages cycles, Stages >= Iters + 3 (10 at fp24: rc_fp_sqrt's default; checked at
//   elaboration).
// - Parameters: ExpW (>= 2), FracW (>= 4, even); Stages; Lanes (>= 1).
// - Illegal input: none; every bit pattern of a_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears the lanes' busy bits, the lane pointer and
//   the valid pipeline; data registers have no reset.
//
// Algorithm: rc_fp_sqrt's digit-by-digit restoring square root, slot for slot (N = FracW + 2
// root bits; slots 0 .. N - 1 take root bits 1 .. N, slot N rounds). Cycle 0: slot 0
// (rc_fp_sqrt_pre) and slot 1 chained behind it, into the lane's state register. Cycles 1 ..
// Iters: the lane's state goes once through slots k and k + 1 (k = 2, 4, .., N - 4) and back:
// slot k subtracts its trial 4 q + 1 from the brought-down remainder, and slot k + 1 subtracts
// from slot k's input state for both of slot k's outcomes (trial 8 q + 1 or 8 t + 1, with t =
// 3 q + 1 carried in the state, as rc_fp_sqrt's slots that share a cycle), so one carry chain
// and a select per cycle; the root bits shift in from the bottom. Cycle Iters + 1: slots N - 2
// and N - 1 the same way on the lane whose operation is there, with the last root bit's extras
// (rc_fp_sqrt_fin), into a register. Cycle Iters + 2: the rounding (rc_fp_round_pack), then
// Stages - Iters - 2 output registers. These are rc_fp_sqrt's cycles at fp24 and its default
// Stages 10 (slots {0, 1} {2, 3} .. {16, 17} {18}), so the paths are rc_fp_sqrt's there, with a
// multiplexer in front of each state register and the lane select in front of the last pair.
module rc_fp_sqrt_iter #(
  parameter int unsigned ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW  = rc_pkg::Fp24FracW,
  parameter int unsigned Stages = rc_pkg::FpStagesSqrt,
  parameter int unsigned Lanes  = 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  input  logic [ExpW+FracW:0] a_i,
  output logic                valid_o,
  output logic [ExpW+FracW:0] res_o
);

  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned N     = FracW + 2;           // root bits: significand + round
  localparam int unsigned HdrW  = 4 + ExpW;            // rc_fp_sqrt_pre's header
  localparam int unsigned Iters = (FracW - 2) / 2;     // slot pairs 2 .. N - 3
  localparam int unsigned FinW  = 2 * rc_pkg::FpResultKindBits + 2 + ExpW + FracW + 1;
  // A lane's state, with the widths of rc_fp_sqrt's state after slot N - 3 (the last one it
  // holds): {header, radicand bits not yet brought down (left aligned, N bits), remainder (N - 1
  // bits), partial root q (N - 2 bits), 3 q + 1 (N bits)}. Earlier states are zero-extended.
  localparam int unsigned StW   = HdrW + N + (N - 1) + (N - 2) + N;

  if (ExpW < 2 || FracW < 4 || FracW % 2 != 0) begin : g_width_check
    $error("rc_fp_sqrt_iter: need ExpW >= 2 and FracW >= 4, even (slot pairs)");
  end
  if (Stages < Iters + 3) begin : g_stages_check
    $error("rc_fp_sqrt_iter: Stages must be at least (FracW - 2) / 2 + 3");
  end
  if (Lanes < 1) begin : g_lanes_check
    $error("rc_fp_sqrt_iter: Lanes must be at least 1");
  end

  ////////////////////////////////////////
  // Cycle 0: slots 0 and 1, lane pick  //
  ////////////////////////////////////////

  logic [HdrW-1:0] hdr0;
  logic [N-1:0]    rad0;
  logic [1:0]      rem1;
  rc_fp_sqrt_pre #(
    .ExpW (ExpW),
    .FracW(FracW)
  ) u_pre (
    .a_i,
    .hdr_o(hdr0),
    .rad_o(rad0),
    .rem_o(rem1)
  );

  // Slot 1 (root bit 2), chained behind slot 0 as in rc_fp_sqrt: the root so far is 1, so the
  // trial is 4 * 1 + 1 = 5, and t = 3 q + 1 becomes 10 (q = 3) or 7 (q = 2).
  logic [3:0]     rem_sh1;
  logic [4:0]     diff1;
  logic           r1;
  logic [2:0]     rem2;
  logic [3:0]     t2;
  logic [StW-1:0] st0;
  assign rem_sh1 = {rem1, rad0[N-1 -: 2]};
  assign diff1   = {1'b0, rem_sh1} - 5'd5;
  assign r1      = ~diff1[4];
  assign rem2    = 3'(r1 ? diff1[3:0] : rem_sh1);
  assign t2      = r1 ? 4'd10 : 4'd7;
  assign st0     = {hdr0, rad0[N-3:0], 2'b00, (N - 1)'(rem2), (N - 2)'({1'b1, r1}), N'(t2)};

  ///////////////////////////////////////////
  // Cycles 1 .. Iters: a slot pair a lane //
  ///////////////////////////////////////////

  // Every pair a lane iterates is made by rc_fp_sqrt's formulas for its slots N - 4 and N - 3
  // (the last pair iterated, so the widest), from the state the lane holds (after slot 1, 3, ..
  // or N - 5) read at the widths of the state after slot N - 5 (remainder N - 3 bits, root
  // N - 4, t N - 2). That is exact: the state after slot j has a remainder below 2^(j+2), a root
  // below 2^(j+1) and t below 2^(j+3), so for j <= N - 5 the values fit those widths, and the
  // bits dropped are zero. rc_fp_sqrt's subtractions at slot j take nonnegative operands and, where
  // their result is used, their exact integer difference lies in [-2^(j+3), 2^(j+3)), so the
  // j + 4 bits it keeps hold that integer and its top bit is the sign; the same operands
  // zero-extended into the pair's wider subtractions give the same integer, and so the same root
  // bit, the same kept remainder and the same t (3 q + 1 +- 1 neither wraps nor overflows).
  // The last pair (slots N - 2 and N - 1, below) reads the state after slot N - 3 at full width.

  // take[l]: lane l takes this cycle's operation; st_f: the state of the lane whose operation
  // is at cycle Iters + 1 (slots 0 .. N - 3 done). Operations i and i + Lanes at least Iters + 1
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
    logic [N-1:0]     rad;
    logic [N-2:0]     rem_w;
    logic [N-3:0]     root_w;
    logic [N-1:0]     t_w;
    // The fields at the widths of the state after slot N - 5.
    logic [N-4:0]     rem;
    logic [N-5:0]     root;
    logic [N-3:0]     t, t_inc, t_dec;
    logic             unused_top;
    // Slot N - 4: bring down a pair, subtract 4 q + 1 if it fits.
    logic [N-2:0]     rem_sh_a;
    logic [N-1:0]     diff_a;
    logic             r_a;
    logic [N-3:0]     rem_next_a;
    // Slot N - 3, from slot N - 4's input state for both of its outcomes.
    logic [N:0]       diff_kept, diff_sub, diff_b;
    logic             r_b;
    logic [N-1:0]     rem_sh_b;
    logic [N-2:0]     rem_next_b, t_inc_b, t_dec_b;

    assign {hdr, rad, rem_w, root_w, t_w} = st_q;
    assign rem        = rem_w[N-4:0];
    assign root       = root_w[N-5:0];
    assign t          = t_w[N-3:0];
    // Zero in every state the pair iterates on (the last pair reads them).
    assign unused_top = ^{rem_w[N-2 -: 2], root_w[N-3 -: 2], t_w[N-1 -: 2]};

    assign rem_sh_a   = {rem, rad[N-1 -: 2]};
    assign diff_a     = {1'b0, rem_sh_a} - {2'b00, root, 2'b01};
    assign r_a        = ~diff_a[N-1];
    assign rem_next_a = (N - 2)'(r_a ? diff_a[N-2:0] : rem_sh_a);
    // Kept 4 R + a: the remainder is 16 R + 4 a + b and the trial 8 q + 1; subtracted: the
    // difference is (16 R + 4 a + b) - (8 t + 1) (rc_fp_sqrt's g_both). Slot N - 3's t + 1 and
    // t - 1 are selected from t and t +- 1.
    assign t_inc      = t + (N - 2)'(1);
    assign t_dec      = t - (N - 2)'(1);
    assign diff_kept  = {rem_sh_a, rad[N-3 -: 2]} - {2'b00, root, 3'b001};
    assign diff_sub   = {rem_sh_a, rad[N-3 -: 2]} - {t, 3'b001};
    assign diff_b     = r_a ? diff_sub : diff_kept;
    assign r_b        = ~diff_b[N];
    assign rem_sh_b   = {rem_next_a, rad[N-3 -: 2]};
    assign rem_next_b = (N - 1)'(r_b ? diff_b[N-1:0] : rem_sh_b);
    assign t_inc_b    = r_a ? {t_inc, 1'b1} : {t, 1'b0};
    assign t_dec_b    = r_a ? {t, 1'b1} : {t_dec, 1'b0};

    // The state: taken in cycle 0, then a pair per cycle (an idle lane's state turns over
    // unread).
    always_ff @(posedge clk_i) begin
      if (take[l]) begin
        st_q <= st0;
      end else begin
        st_q <= {hdr, rad[N-5:0], 4'b0000, rem_next_b, root, r_a, r_b,
                 r_b ? {t_inc_b, 1'b0} : {t_dec_b, 1'b1}};
      end
    end

    assign st_all[l*StW +: StW] = st_q;
  end

  //////////////////////////////////////////////////////////
  // Cycle Iters + 1: slots N - 2 and N - 1, the decision //
  //////////////////////////////////////////////////////////

  logic [HdrW-1:0] hdr_f;
  logic [N-1:0]    rad_f, rem_next_a_f;
  logic [N-2:0]    rem_f;
  logic [N-3:0]    root_f;
  logic [N-1:0]    t_f;
  logic [N:0]      rem_sh_a_f;
  logic [N+1:0]    diff_a_f;
  logic            r_a_f;
  logic [N+2:0]    diff_kept_f, diff_sub_f, diff_b_f;
  logic [FinW-1:0] fin_d;
  logic            unused_f;


  // The pair as above, with rc_fp_sqrt's formulas for slots N - 2 and N - 1 at full width;
  // slot N - 1 is the last (rc_fp_sqrt's g_last): its root bit, its brought-down remainder and
  // the root before it go to rc_fp_sqrt_fin.
  assign {hdr_f, rad_f, rem_f, root_f, t_f} = st_f;
  assign rem_sh_a_f   = {rem_f, rad_f[N-1 -: 2]};
  assign diff_a_f     = {1'b0, rem_sh_a_f} - {2'b00, root_f, 2'b01};
  assign r_a_f        = ~diff_a_f[N+1];
  assign rem_next_a_f = N'(r_a_f ? diff_a_f[N:0] : rem_sh_a_f);
  assign diff_kept_f  = {rem_sh_a_f, rad_f[N-3 -: 2]} - {2'b00, root_f, 3'b001};
  assign diff_sub_f   = {rem_sh_a_f, rad_f[N-3 -: 2]} - {t_f, 3'b001};
  assign diff_b_f     = r_a_f ? diff_sub_f : diff_kept_f;
  // By now every radicand bit has been brought down (the rest are the zeros shifted in).
  assign unused_f     = ^{rad_f[N-5:0], diff_b_f[N+1:0]};

  rc_fp_sqrt_fin #(
    .ExpW (ExpW),
    .FracW(FracW)
  ) u_fin (
    .hdr_i   (hdr_f),
    .r_bit_i (~diff_b_f[N+2]),
    .rem_sh_i({rem_next_a_f, rad_f[N-3 -: 2]}),
    .root_i  ({root_f, r_a_f}),
    .fin_o   (fin_d)
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
