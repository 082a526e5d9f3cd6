// rc_fp_sqrt: pipelined floating-point square root for the raycore number format.
//
// Contract
// - Function: res_o = sqrt(a_i), correctly rounded, bit-exact with sqrt(rc::Fp<ExpW, FracW>)
//   (tb/fp/fp.hpp).
// - Handshake: valid only, no backpressure. valid_o is valid_i delayed by exactly Stages cycles;
//   res_o belongs to the input presented Stages cycles earlier and is meaningful only while
//   valid_o is 1. A new operation may be presented every cycle (fully pipelined).
// - Latency: Stages cycles (Stages >= 1, checked at elaboration).
// - Parameters: ExpW exponent bits (>= 2), FracW fraction bits (>= 1); a word is
//   {sign, exp[ExpW-1:0], frac[FracW-1:0]}. Stages = latency in cycles.
// - Illegal input: none; every bit pattern of a_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears only the valid pipeline; data registers have
//   no reset.
// - Format rules implemented: an exponent field of 0 reads as signed zero whatever the fraction,
//   and sqrt(+-0) = +-0 (fraction cleared); sqrt(+inf) = +inf; a NaN input and every negative
//   nonzero input (-inf included) give the canonical NaN (sign 0, exp all ones, frac MSB only);
//   any other result is positive and rounded to nearest, ties to even, with an unbounded
//   exponent, then flushed or overflowed by the same rule as the other units (the square root of
//   a normal number is always normal, so neither happens, and a tie cannot occur either; the
//   general rounding is kept so the unit needs no such argument to be right).
//
// Algorithm: digit-by-digit (restoring) square root of the significand, one root bit per slot.
// With e the biased exponent and m = 1.frac, the unbiased exponent e - Bias is made even by
// doubling m when it is odd, so the radicand M = m or 2m lies in [1, 4), its root in [1, 2), and
// the result's biased exponent is floor((e + Bias) / 2) (Bias is odd, so e - Bias is odd exactly
// when e + Bias is). The root is computed on integers: X = M * 2^(2 N - 2) has 2 N bits
// (N = FracW + 2: FracW + 1 significand bits and a round bit), consumed two at a time from the
// top; after root bit j the partial root q_j = floor(sqrt(top 2 j bits of X)) has j bits and the
// remainder r_j = (top 2 j bits) - q_j^2 <= 2 q_j fits in j + 1 bits. Step j: bring down the next
// two bits, r' = 4 r_{j-1} + pair, subtract the trial 4 q_{j-1} + 1 if it fits (root bit 1) and
// keep r' otherwise (root bit 0). Each step is only as wide as its operands (j + 3 bits), so the
// early steps are short. Slot 0 unpacks, classifies, forms the radicand and takes root bit 1
// (always 1: the top pair is 1, 2 or 3; rc_fp_sqrt_pre); slots 1 .. N - 1 take root bits 2 .. N,
// and slot N - 1 also reduces the final remainder to the sticky bit (nonzero = inexact) and
// decides the rounding increment (round to nearest even; rc_fp_sqrt_fin); slot N rounds and
// packs (rc_fp_round_out). rc_fp_sqrt_iter is the same square root with one slot pair's
// hardware iterated, for users with few operations.
//
// Slots in one cycle do not chain their subtractions (as in rc_fp_div): a slot k >= 2 in the
// same cycle as slot k - 1 subtracts from slot k - 1's input state for both of its outcomes,
// with trial 8 p + 1 (slot k - 1 kept its remainder) or 8 t + 1 (it subtracted), where p is
// slot k - 1's partial root and t = 3 p + 1 is carried in the state (each slot derives the next
// t from t + 1 and t - 1, made beside its subtraction), and slot k - 1's root bit only selects.
// One carry chain per cycle, bit for bit the chained result (run 48: the ray generator's square
// root, two chained subtractions a cycle, -0.64 to -2.45 ns).
//
// Pipeline: the N + 1 slots are spread evenly over Se = min(Stages, N + 1) cycles, the longer
// cycles first, as in rc_fp_div: with Base = (N + 1) / Se and Rem = (N + 1) % Se, the first Rem
// cycles take Base + 1 consecutive slots and the others Base; a register sits in front of every
// slot that starts a cycle, and the remaining Stages - Se + 1 registers (at least one) sit at the
// output. At fp24 (N = 18, 19 slots) the default Stages = 10 gives slots {0, 1} {2, 3} ...
// {16, 17} {18 = round}: two root bits per cycle on one carry chain, the last with the sticky
// compares, and the rounding alone. That reaches 121 to 124 MHz alone on an ECP5
// LFE5U-85F; Stages = 9 (three slots in the unpack cycle, the rounding with the last root bit)
// 112 to 117 MHz (docs/fp24.md).
module rc_fp_sqrt #(
  parameter int unsigned ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW  = rc_pkg::Fp24FracW,
  parameter int unsigned Stages = rc_pkg::FpStagesSqrt
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

  if (Stages < 1) begin : g_stages_check
    $error("rc_fp_sqrt: Stages must be >= 1 (it is the latency in cycles)");
  end
  if (ExpW < 2 || FracW < 1) begin : g_width_check
    $error("rc_fp_sqrt: need ExpW >= 2 and FracW >= 1");
  end

  localparam int unsigned ManW  = FracW + 1;          // significand with the hidden bit
  localparam int unsigned N     = ManW + 1;           // root bits: significand + round
  localparam int unsigned Slots = N + 1;
  localparam int unsigned Se    = (Stages < Slots) ? Stages : Slots;
  localparam int unsigned Base  = Slots / Se;           // slots per cycle (the short cycles)
  localparam int unsigned Rem   = Slots % Se;           // cycles with Base + 1 slots, first
  // The cycle (0 .. Se - 1) in which slot k runs.
  function automatic int unsigned cycle_of(input int unsigned k);
    cycle_of = ($signed(k) < $signed(Rem * (Base + 1))) ? k / (Base + 1) : (k - Rem) / Base;
  endfunction
  localparam int unsigned OutRegs = Stages - cycle_of(Slots - 1);

  // Per-operation flags carried down the pipeline: {spec_nan, spec_inf, spec_zero, sign}, then
  // the result's exponent field.
  localparam int unsigned MetaW = 4;
  localparam int unsigned HdrW  = MetaW + ExpW;
  // The state after slot k (k = 0 .. N - 2): {hdr, radicand bits not yet brought down (left
  // aligned, N bits), remainder (k + 2 bits), partial root q (k + 1 bits), 3 q + 1 (k + 3
  // bits)}. The widths grow by three bits a slot, so the states sit one after the other in one
  // vector at offsets st_off(k).
  function automatic int unsigned st_w(input int unsigned k);
    st_w = HdrW + N + 3 * k + 6;
  endfunction
  function automatic int unsigned st_off(input int unsigned k);
    st_off = k * (HdrW + N + 6) + 3 * k * (k - 1) / 2;  // the sum of st_w(0 .. k - 1)
  endfunction
  localparam int unsigned ChainW = st_off(N - 1);
  // State after the last root bit, what rc_fp_round_pack takes: the result's kinds for both
  // outcomes of the rounding carry and its sign (rc_fp_round_kinds), the all-ones flag, the
  // exponent field, the root's fraction bits and the rounding increment (decided from the round
  // bit, the sticky bit and the root's last bit).
  localparam int unsigned FinW   = 2 * rc_pkg::FpResultKindBits + 2 + ExpW + FracW + 1;

  //////////////////////////////////////////////////
  // Slot 0: unpack, classify, radicand, bit 1    //
  //////////////////////////////////////////////////

  // rad0: the radicand bits not yet brought down; rem1: the remainder after root bit 1 (always
  // 1, so the root is 1 and t = 4).
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

  ///////////////////////////////////////////
  // Slots 1 .. N - 1: one root bit each    //
  ///////////////////////////////////////////

  // st_out holds the state after slot k (k = 0 .. N - 2), st_in the same states after the register
  // (or wire) in front of slot k + 1. split_var lets Verilator schedule the chain piece by piece.
  logic [ChainW-1:0] st_out /* verilator split_var */;
  logic [ChainW-1:0] st_in /* verilator split_var */;
  logic [FinW-1:0]   fin_d;

  // Each slot's root bit, for the slot after it (read only where the two share a cycle).
  logic [N-2:1] r_s /* verilator split_var */;
  logic         unused_r_s;
  assign unused_r_s = ^r_s;

  assign st_out[0 +: st_w(0)] = {hdr0, rad0, rem1, 1'b1, 3'd4};

  for (genvar k = 1; k < N; k++) begin : g_step
    // Where the state entering slot k (the state after slot k - 1) sits in st_out and st_in.
    localparam int unsigned InOff  = st_off(k - 1);
    localparam int unsigned InW    = st_w(k - 1);
    localparam int unsigned OutOff = st_off(k);
    localparam int unsigned OutW   = st_w(k);

    // The register (or wire) in front of slot k.
    if (cycle_of(k) != cycle_of(k - 1)) begin : g_cut
      always_ff @(posedge clk_i) begin
        st_in[InOff +: InW] <= st_out[InOff +: InW];
      end
    end else begin : g_no_cut
      always_comb begin
        st_in[InOff +: InW] = st_out[InOff +: InW];
      end
    end

    // Slot k takes root bit j = k + 1 from the state after bit k: remainder k + 1 bits, root q
    // k bits, t = 3 q + 1 k + 2 bits.
    logic [HdrW-1:0] hdr;
    logic [N-1:0]    rad;
    logic [k:0]      rem;
    logic [k-1:0]    root;
    logic [k+1:0]    t, t_inc, t_dec;
    logic [k+2:0]    rem_sh;
    logic [k+3:0]    diff;
    logic            r_bit;
    logic [k+1:0]    rem_next;

    assign {hdr, rad, rem, root, t} = st_in[InOff +: InW];
    // Bring down the next two radicand bits, and subtract the trial 4 q + 1 if it fits. The kept
    // remainder is <= 2 * (the new root), so it fits in k + 2 bits (the bit dropped is 0).
    assign rem_sh = {rem, rad[N-1 -: 2]};
    if (k >= 2 && cycle_of(k) == cycle_of(k - 1)) begin : g_both
      // Slot k - 1 runs in this cycle: subtract from its input state (remainder R, root p,
      // t_p = 3 p + 1, pairs a then b) for both of its outcomes, and let its root bit select.
      // It kept 4 R + a: this slot's remainder is 16 R + 4 a + b and the trial 8 p + 1; it
      // subtracted 4 p + 1: the remainder is 16 R + 4 a + b - 16 p - 4 and the trial 8 p + 5,
      // so the difference is (16 R + 4 a + b) - (8 t_p + 1). Both modulo 2^(k+4), like the
      // chained subtraction, so the bits are the same (a kept 4 R + a has a top bit of 0).
      // t = 3 q + 1 with q = 2 p + r: t_p - 1 shifted with a 1, or t_p + 1 shifted with a 0, so
      // t + 1 and t - 1 are selected from t_p and t_p +- 1 as well (no chain behind slot
      // k - 1's subtraction).
      // Slot k - 1's input state, from the bottom: t_p (k + 1 bits), p (k - 1), R (k), the
      // radicand (N, its top pair a).
      localparam int unsigned PrevOff = st_off(k - 2);
      logic [k+1:0] sh_prev;  // 4 R + a
      logic [k-2:0] root_prev;
      logic [k:0]   t_prev, t_prev_inc, t_prev_dec;
      logic [k+3:0] diff_kept, diff_sub;
      logic         unused_t;
      assign unused_t   = ^t;  // the same as t_p's selection, made from t_p here
      assign sh_prev    = {st_in[PrevOff + 2 * k +: k], st_in[PrevOff + 3 * k + N - 2 +: 2]};
      assign root_prev  = st_in[PrevOff + k + 1 +: k - 1];
      assign t_prev     = st_in[PrevOff +: k + 1];
      assign t_prev_inc = t_prev + (k + 1)'(1);
      assign t_prev_dec = t_prev - (k + 1)'(1);
      assign diff_kept  = {sh_prev, rad[N-1 -: 2]} - {2'b00, root_prev, 3'b001};
      assign diff_sub   = {sh_prev, rad[N-1 -: 2]} - {t_prev, 3'b001};
      assign diff       = r_s[k-1] ? diff_sub : diff_kept;
      assign t_inc      = r_s[k-1] ? {t_prev_inc, 1'b1} : {t_prev, 1'b0};
      assign t_dec      = r_s[k-1] ? {t_prev, 1'b1} : {t_prev_dec, 1'b0};
    end else begin : g_chain
      assign diff  = {1'b0, rem_sh} - {2'b00, root, 2'b01};
      assign t_inc = t + (k + 2)'(1);
      assign t_dec = t - (k + 2)'(1);
    end
    assign r_bit    = ~diff[k+3];
    assign rem_next = (k + 2)'(r_bit ? diff[k+2:0] : rem_sh);
    if (k < N - 1) begin : g_r_s
      assign r_s[k] = r_bit;
    end

    if (k < N - 1) begin : g_mid
      // The new root 2 q + r: t becomes 6 q + 3 r + 1, 2 (t + 1) or 2 (t - 1) + 1.
      assign st_out[OutOff +: OutW] = {hdr, rad[N-3:0], 2'b00, rem_next, root, r_bit,
                                       r_bit ? {t_inc, 1'b0} : {t_dec, 1'b1}};
    end else begin : g_last
      // The sticky bit, the rounding increment and the result's kinds for both outcomes of the
      // rounding carry are made here, before the register, so the rounding cycle starts from
      // them (rc_fp_sqrt_fin: the sticky bit is two equality compares beside the subtraction,
      // which only selects, not an OR over rem_next behind its carry chain).
      logic unused_next;
      assign unused_next = ^{rem_next, t_inc, t_dec};
      rc_fp_sqrt_fin #(
        .ExpW (ExpW),
        .FracW(FracW)
      ) u_fin (
        .hdr_i   (hdr),
        .r_bit_i (r_bit),
        .rem_sh_i(rem_sh),
        .root_i  (root),
        .fin_o   (fin_d)
      );
      // By now every radicand bit has been brought down (the rest are the zeros shifted in).
      logic unused_rad;
      assign unused_rad = ^rad[N-3:0];
    end
  end

  // Slot N: the register (or wire) in front of it, the rounding and packing, the output
  // registers.
  rc_fp_round_out #(
    .ExpW    (ExpW),
    .FracW   (FracW),
    .Cut     (cycle_of(N) != cycle_of(N - 1)),
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
