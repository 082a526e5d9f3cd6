// rc_fp_to_fix: a format value to an unsigned fixed-point integer with FixBits fraction bits,
// clamped to [0, Max]: the lighting's fixed point (docs/architecture.md, "Lighting": fix(x) =
// round_to_nearest_even(min(max(x, 0), 1) * 2^F), a NaN gives 0; Max = 2^F) and, with no fraction
// bits and Max = 2^exponent_bits - 1, a material's integer exponent (rc_fp_to_exp).
//
// Contract
// - Function: out_o = min(round_to_nearest_even(x_i * 2^FixBits), Max) for x_i > 0, 0 for a NaN,
//   a zero (an exponent field of 0) or a negative x_i; Max for +inf. Bit for bit
//   rc::light_fixed() at the defaults and rc::light_exponent() at FixBits = 0, Max = 2^10 - 1
//   (tb/golden/trace.hpp). x_i * 2^FixBits is exact in the format for every value below the
//   clamp, so this is computed on the significand as an integer shift: x_i = 1.f x 2^k with
//   2^k * 2^FixBits at most Max (else out_o = Max), out_o the integer nearest to
//   1.f x 2^(k + FixBits), ties to even, then the clamp (which only a Max that is not a power of
//   two needs: a value just below 2^TopK rounds up to it).
// - Structure: Stages = 1: one combinational segment into the output register (the shift by a
//   subtracted exponent, the remainder compared with the half). Stages = 2: the shift selected by
//   the exponent field itself, the rounding from the shifted-out bits' guard (the highest) and
//   sticky OR (up = guard & (sticky | lsb)), a register (the kept bits, the round-up bit, the zero
//   and saturate flags), then the increment and the clamp into the output register.
// - Handshake: valid only, no backpressure. valid_o is valid_i Stages cycles later; out_o belongs
//   to the input of Stages cycles before and is meaningful only while valid_o is 1.
// - Latency: Stages (1 or 2).
// - Parameters: ExpW, FracW: the number format (default fp24); FixBits: the fraction bits (default
//   docs/spec.toml [light] fixed_bits), at most FracW; Max: the clamp (>= 1; default 2^FixBits),
//   with Max / 2^FixBits < 2^(FracW - FixBits) so that every value below it shifts right;
//   Stages: 1 or 2 (default 1; rc_light_term's 2).
// - Illegal input: none; every bit pattern of x_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears only the valid chain (rc_pipe_out).
module rc_fp_to_fix #(
  parameter int unsigned ExpW    = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW   = rc_pkg::Fp24FracW,
  parameter int unsigned FixBits = rc_pkg::LightFixedBits,
  parameter int unsigned Max     = 1 << FixBits,
  parameter int unsigned Stages  = 1,
  // Derived (do not override).
  parameter int unsigned OutW    = $clog2(Max + 1)
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  input  logic [ExpW+FracW:0] x_i,
  output logic                valid_o,
  output logic [OutW-1:0]     out_o
);

  // TopK: values from 2^TopK / 2^FixBits on give Max; below, k + FixBits < TopK.
  localparam int unsigned MaxLog = $clog2(Max + 1) - 1;                 // floor(log2(Max))
  localparam bit          MaxPow = (1 << MaxLog) == Max;
  localparam int unsigned TopK   = MaxLog + (MaxPow ? 0 : 1);

  if (FixBits > FracW || Max < 1 || TopK > FracW) begin : g_param_check
    $error("rc_fp_to_fix: need FixBits <= FracW, Max >= 1 and Max below 2^FracW");
  end
  if (Stages < 1 || Stages > 2) begin : g_stages_check
    $error("rc_fp_to_fix: Stages must be 1 or 2");
  end

  localparam int unsigned W       = 1 + ExpW + FracW;
  localparam int unsigned BiasInt = (1 << (ExpW - 1)) - 1;
  localparam int unsigned MW      = FracW + 1;  // the significand 1.f as an integer

  logic [ExpW-1:0]  e;
  logic [FracW-1:0] f;
  logic             s, is_nan, is_zero, ge_top;
  logic [MW-1:0]    m;
  logic [MW-1:0]    q;
  // The first segment's results: the kept bits (below 2^TopK the shift leaves at most OutW + 1
  // bits), the round-up bit, out_o = 0 (zero_s) and out_o = Max (sat_s).
  logic [OutW:0]    q_s;
  logic             up_s, zero_s, sat_s;
  logic [OutW:0]    rounded;   // at most 2^TopK
  logic [OutW-1:0]  out_d;

  assign s       = x_i[W-1];
  assign e       = x_i[W-2 -: ExpW];
  assign f       = x_i[FracW-1:0];
  assign is_nan  = (&e) && (f != '0);
  assign is_zero = e == '0;
  // x >= 2^TopK / 2^FixBits: e - BiasInt + FixBits >= TopK.
  assign ge_top  = {1'b0, e} + (ExpW + 1)'(FixBits) >= (ExpW + 1)'(BiasInt + TopK);
  assign m       = {1'b1, f};

  // The shift right of m is sh = BiasInt + FracW - FixBits - e: for x = 1.f x 2^k with
  // k + FixBits < TopK at least FracW - TopK + 1 >= 1; a shift beyond MW leaves less than a half:
  // 0, so sh is only used up to MW.
  if (Stages == 1) begin : g_shift_sub
    // sh from a subtraction; the remainder (the bits shifted out) against the half.
    localparam int unsigned ShW = $clog2(MW + 2) + 1;
    logic [ExpW:0]  sh_full;  // BiasInt - e + FracW - FixBits, for e < BiasInt + TopK - FixBits
    logic [ShW-1:0] sh;
    logic           sh_big;
    logic [MW-1:0]  rem, half;
    assign sh_full = (ExpW + 1)'(BiasInt) - {1'b0, e} + (ExpW + 1)'(FracW - FixBits);
    assign sh_big  = sh_full > (ExpW + 1)'(MW);
    assign sh      = ShW'(sh_full);
    always_comb begin
      q    = '0;
      rem  = '0;
      half = '0;
      up_s = 1'b0;
      if (!sh_big) begin
        // sh >= 1 here (below 2^TopK, see above).
        q    = m >> sh;
        rem  = m & ((MW'(1) << sh) - MW'(1));
        half = MW'(1) << (sh - ShW'(1));
        up_s = (rem > half) || ((rem == half) && q[0]);
      end
    end
  end else begin : g_shift_sel
    // Each shift 1 .. MW is one exponent field, so the kept bits, the guard (bit sh - 1) and the
    // sticky OR below it are selected by e itself (a comparison with a constant per shift, no
    // subtraction: shallower, for the register after it). The remainder is above half when guard
    // and sticky are set, exactly half when guard is set alone.
    localparam int ShBase = BiasInt + FracW - FixBits;  // sh = ShBase - e
    logic guard, sticky;
    always_comb begin
      q      = '0;
      guard  = 1'b0;
      sticky = 1'b0;
      for (int k = 1; k <= MW; k++) begin
        if (ShBase - k >= 0 && ShBase - k < (1 << ExpW) && 32'(e) == 32'(ShBase - k)) begin
          q      = m >> k;
          guard  = m[k-1];
          sticky = |(m & ((MW'(1) << (k - 1)) - MW'(1)));
        end
      end
    end
    assign up_s = guard & (sticky | q[0]);
  end

  assign q_s    = (OutW + 1)'(q);
  assign zero_s = s || is_nan || is_zero;
  assign sat_s  = ge_top;
  if (MW > OutW + 1) begin : g_q_hi
    logic unused_q_hi;
    assign unused_q_hi = ^q[MW-1:OutW+1];  // 0: below 2^TopK the shift leaves at most OutW bits
  end

  // Stages = 2: the register between the two segments (its valid bit is rc_pipe_out's chain).
  logic [OutW:0] q_r;
  logic          up_r, zero_r, sat_r;
  if (Stages == 2) begin : g_mid
    logic [OutW:0] q_q;
    logic          up_q, zero_q, sat_q;
    always_ff @(posedge clk_i) begin
      q_q    <= q_s;
      up_q   <= up_s;
      zero_q <= zero_s;
      sat_q  <= sat_s;
    end
    assign {q_r, up_r, zero_r, sat_r} = {q_q, up_q, zero_q, sat_q};
  end else begin : g_no_mid
    assign {q_r, up_r, zero_r, sat_r} = {q_s, up_s, zero_s, sat_s};
  end

  assign rounded = q_r + (OutW + 1)'(up_r);

  always_comb begin
    if (zero_r) out_d = '0;
    else if (sat_r || (!MaxPow && rounded > (OutW + 1)'(Max))) out_d = OutW'(Max);
    else out_d = OutW'(rounded);
  end

  rc_pipe_out #(
    .Width   (OutW),
    .DataRegs(1),
    .Stages  (Stages)
  ) u_out (
    .clk_i,
    .rst_ni,
    .valid_i,
    .data_i (out_d),
    .valid_o,
    .data_o (out_o)
  );

endmodule
