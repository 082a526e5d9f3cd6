// rc_fp_div: pipelined floating-point divider for the raycore number format.
//
// Contract
// - Function: res_o = a_i / b_i, correctly rounded, bit-exact with rc::Fp<ExpW, FracW>::operator/
//   (tb/fp/fp.hpp). A reciprocal 1/x is this unit with a_i = 1.0.
// - Handshake: valid only, no backpressure. valid_o is valid_i delayed by exactly Stages cycles;
//   res_o belongs to the inputs presented Stages cycles earlier and is meaningful only while
//   valid_o is 1. A new operation may be presented every cycle (fully pipelined).
// - Latency: Stages cycles (Stages >= 1, checked at elaboration).
// - Parameters: ExpW exponent bits (>= 2), FracW fraction bits (>= 1); a word is
//   {sign, exp[ExpW-1:0], frac[FracW-1:0]}. Stages = latency in cycles.
// - Illegal input: none; every bit pattern of a_i and b_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears only the valid pipeline; data registers have
//   no reset.
// - Format rules implemented: an exponent field of 0 reads as signed zero whatever the fraction
//   (flush-to-zero inputs, so x / subnormal-encoding = +-inf); exp all ones with frac 0 is +-inf,
//   with frac != 0 NaN; any NaN input, 0/0 and inf/inf give the canonical NaN (sign 0, exp all
//   ones, frac MSB only); x/0 = +-inf for finite nonzero x, inf/x = +-inf, x/inf = +-0, 0/x = +-0;
//   the sign of every non-NaN result is the xor of the operand signs; rounding is to nearest,
//   ties to even, with an unbounded exponent, and only then a biased exponent <= 0 flushes to
//   signed zero and one >= all ones overflows to signed infinity.
//
// Algorithm: radix-2 restoring division of the significands. Slot 0 unpacks, classifies and
// pre-normalises the dividend (doubled when its significand is below the divisor's, so the
// quotient lies in [1, 2)); slots 1..N (N = FracW + 2) each produce one quotient bit (FracW + 1
// significand bits and a round bit). Slot 1's bit is always 1, so its subtraction is made in
// slot 0, for both pre-normalisations side by side (slots 0 and 1: rc_fp_div_pre). Slot N also
// decides the rounding increment (round to nearest even, with the sticky bit of a nonzero final
// remainder: rc_fp_div_fin); slot N + 1 adds it, adjusts the exponent and packs
// (rc_fp_round_out). rc_fp_div_iter is the same division with one slot pair's hardware iterated,
// for users with few operations.
//
// Slots in one cycle do not chain their subtractions: a slot k >= 3 in the same cycle as slot
// k - 1 subtracts from slot k - 1's input remainder R for both of slot k - 1's outcomes side by
// side, 2R - D (slot k - 1 kept R) and 2R - 3D (it kept R - D), with D the divisor and 3D made
// once in slot 0 and carried in the state, and slot k - 1's quotient bit only selects. The
// selected difference is bit for bit the one a chained subtraction gives, so only the depth
// changes: one carry chain per cycle and a select per further slot (run 47: the two chained
// subtractions of a cycle failed 100 MHz by up to 0.65 ns in the set-up and intersection units).
//
// Pipeline: the N + 2 slots are spread evenly over Se = min(Stages, N + 2) cycles, the longer
// cycles first: with Base = (N + 2) / Se and Rem = (N + 2) % Se, the first Rem cycles take
// Base + 1 consecutive slots and the others Base; a register sits in front of every slot that
// starts a cycle, and the remaining Stages - Se + 1 registers (at least one) sit at the output.
// At fp24 (N = 18, 20 slots) the default Stages = 11 gives slots {0, 1} {2, 3} ... {16, 17}
// {18} {19 = round}: at most two subtract-and-select carry chains per cycle (slot 0's two run
// side by side), the last quotient bit alone with the rounding decision, and the rounding
// alone. That closes 100 MHz on an ECP5 LFE5U-85F (docs/fp24.md); spreading the same 11
// cycles evenly ({17, 18} before the rounding) reached only 84 to 88 MHz inside rc_ray_setup.
module rc_fp_div #(
  parameter int unsigned ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW  = rc_pkg::Fp24FracW,
  parameter int unsigned Stages = rc_pkg::FpStagesDiv
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

  if (Stages < 1) begin : g_stages_check
    $error("rc_fp_div: Stages must be >= 1 (it is the latency in cycles)");
  end
  if (ExpW < 2 || FracW < 1) begin : g_width_check
    $error("rc_fp_div: need ExpW >= 2 and FracW >= 1");
  end

  localparam int unsigned ManW  = FracW + 1;          // significand with the hidden bit
  localparam int unsigned RemW  = ManW + 1;           // partial remainder, < 2 * divisor
  localparam int unsigned N     = ManW + 1;           // quotient bits: significand + round
  localparam int unsigned Slots = N + 2;
  localparam int unsigned Se    = (Stages < Slots) ? Stages : Slots;
  localparam int unsigned ExW   = ExpW + 2;           // unbounded exponent, two's complement
  localparam int unsigned Base  = Slots / Se;           // slots per cycle (the short cycles)
  localparam int unsigned Rem   = Slots % Se;           // cycles with Base + 1 slots, first
  // The cycle (0 .. Se - 1) in which slot k runs.
  function automatic int unsigned cycle_of(input int unsigned k);
    cycle_of = ($signed(k) < $signed(Rem * (Base + 1))) ? k / (Base + 1) : (k - Rem) / Base;
  endfunction
  localparam int unsigned OutRegs = Stages - cycle_of(Slots - 1);

  // Per-operation flags carried down the pipeline: {spec_nan, spec_inf, spec_zero, sign}.
  localparam int unsigned MetaW = 4;
  localparam int unsigned HdrW  = MetaW + ExW;
  localparam int unsigned D3W   = ManW + 2;           // three times the divisor's significand
  // Iteration state: {hdr, divisor fraction, 3 x divisor, partial remainder, quotient bits so
  // far}.
  localparam int unsigned StW   = HdrW + FracW + D3W + RemW + N;
  // State after the last iteration, what rc_fp_round_pack takes: the result's kinds for both
  // outcomes of the rounding carry and its sign (rc_fp_round_kinds), the all-ones flag, the
  // exponent field, the quotient's fraction bits and the rounding increment.
  localparam int unsigned FinW  = 2 * rc_pkg::FpResultKindBits + 2 + ExpW + FracW + 1;

  ///////////////////////////////////////
  // Slot 0: unpack, pre-normalise     //
  ///////////////////////////////////////

  // Slot 1's bit is always 1, so its subtraction is made here (rc_fp_div_pre): rem0 is the
  // remainder after it.
  logic [HdrW-1:0]  hdr0;
  logic [FracW-1:0] dvs0;
  logic [D3W-1:0]   d3;
  logic [RemW-1:0]  rem0;
  rc_fp_div_pre #(
    .ExpW (ExpW),
    .FracW(FracW)
  ) u_pre (
    .a_i,
    .b_i,
    .hdr_o (hdr0),
    .dvs_o (dvs0),
    .dvs3_o(d3),
    .rem_o (rem0)
  );

  ///////////////////////////////////////////
  // Slots 1..N: one quotient bit each     //
  ///////////////////////////////////////////

  // st_out[k] is the state after slot k (k = 0..N-1), st_in[k-1] the state entering slot k
  // (k = 1..N). split_var lets Verilator schedule the chain element by element.
  logic [N*StW-1:0] st_out /* verilator split_var */;
  logic [N*StW-1:0] st_in /* verilator split_var */;
  logic [FinW-1:0]  fin_d;
  // Each slot's quotient bit, for the slot after it (read only where the two share a cycle).
  logic [N:1]       q_s /* verilator split_var */;
  logic             unused_q_s;
  assign unused_q_s = ^q_s;

  assign st_out[StW-1:0] = {hdr0, dvs0, d3, rem0, {N{1'b0}}};

  for (genvar k = 1; k <= N; k++) begin : g_iter
    // The register (or wire) in front of slot k.
    if (cycle_of(k) != cycle_of(k - 1)) begin : g_cut
      always_ff @(posedge clk_i) begin
        st_in[(k-1)*StW +: StW] <= st_out[(k-1)*StW +: StW];
      end
    end else begin : g_no_cut
      always_comb begin
        st_in[(k-1)*StW +: StW] = st_out[(k-1)*StW +: StW];
      end
    end

    logic [HdrW-1:0]  hdr;
    logic [FracW-1:0] dvs_frac;
    logic [D3W-1:0]   dvs3;
    logic [RemW-1:0]  rem;
    logic [N-1:0]     quo, quo_next;
    logic             q_bit;
    logic [ManW-1:0]  rem_kept;  // the kept remainder: below the divisor, so ManW bits

    assign {hdr, dvs_frac, dvs3, rem, quo} = st_in[(k-1)*StW +: StW];
    if (k == 1) begin : g_first
      // Slot 1's bit is always 1 and its subtraction was made in slot 0 (rem0).
      logic unused_top;
      assign unused_top = rem[RemW-1];  // 0: rem0 is below the divisor
      assign q_bit      = 1'b1;
      assign rem_kept   = rem[ManW-1:0];
    end else begin : g_next
      // Restoring step: subtract the divisor if it fits (the bit dropped by the cast is 0).
      logic [RemW:0] diff;
      if (k >= 3 && cycle_of(k) == cycle_of(k - 1)) begin : g_both
        // Slot k - 1 runs in this cycle: subtract from its input remainder R for both of its
        // outcomes, and let its quotient bit select. Kept R: this slot's remainder is 2R;
        // kept R - D: it is 2R - 2D, so the difference is 2R - 3D (both modulo 2^(RemW+1),
        // like the chained subtraction).
        // (When R is kept it is below the divisor, so its top bit is 0 and not needed.)
        logic [RemW-1:0] rem_prev;
        logic [RemW:0]   diff_kept, diff_sub;
        assign rem_prev  = st_in[(k-2)*StW + N +: RemW];
        assign diff_kept = {1'b0, rem_prev[ManW-1:0], 1'b0} - {3'b001, dvs_frac};
        assign diff_sub  = {rem_prev, 1'b0} - dvs3;
        assign diff      = q_s[k-1] ? diff_sub : diff_kept;
      end else begin : g_chain
        logic unused_dvs3;
        assign unused_dvs3 = ^dvs3;
        assign diff        = {1'b0, rem} - {3'b001, dvs_frac};
      end
      assign q_bit    = ~diff[RemW];
      assign rem_kept = ManW'(q_bit ? diff[RemW-1:0] : rem);
    end
    assign q_s[k] = q_bit;
    // Quotient bits are placed MSB first, bit N - k in slot k.
    always_comb begin
      quo_next          = quo;
      quo_next[N-k] = q_bit;
    end

    if (k < N) begin : g_mid
      // The next slot's partial remainder is the kept one doubled.
      assign st_out[k*StW +: StW] = {hdr, dvs_frac, dvs3, rem_kept, 1'b0, quo_next};
    end else begin : g_last
      // The rounding increment, the result's kinds and range checks are decided here, before
      // the register, so the rounding cycle starts from them (rc_fp_div_fin; rem_kept is not
      // needed).
      logic unused_kept;
      assign unused_kept = ^{rem_kept, quo_next};  // (q_bit is in fin_d)
      rc_fp_div_fin #(
        .ExpW (ExpW),
        .FracW(FracW)
      ) u_fin (
        .hdr_i(hdr),
        .dvs_i(dvs_frac),
        .rem_i(rem),
        .q_i  (q_bit),
        .man_i(quo[N-1:1]),
        .fin_o(fin_d)
      );
    end
  end

  // Slot N + 1: the register (or wire) in front of it, the rounding and packing, the output
  // registers.
  rc_fp_round_out #(
    .ExpW    (ExpW),
    .FracW   (FracW),
    .Cut     (cycle_of(N + 1) != cycle_of(N)),
    .DataRegs(OutRegs),
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
