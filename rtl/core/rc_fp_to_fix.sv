// rc_fp_to_fix: a format value to the lighting's fixed point (docs/architecture.md, "Lighting":
// fix(x) = round_to_nearest_even(min(max(x, 0), 1) * 2^F) as an integer, a NaN gives 0).
//
// Contract
// - Function: exactly rc::light_fixed() (tb/golden/trace.hpp), bit for bit, with F = FixBits:
//   fix_o = 0 for a NaN, a zero (an exponent field of 0) or a negative x_i; 2^F for x_i >= 1
//   (+inf too); otherwise x_i = 1.f x 2^k with k < 0, and fix_o = the integer nearest to
//   1.f x 2^(k + F), ties to even. The golden model's min(max(x, 0), 1) * 2^F is exact in the
//   format (a power of two times a value at most 1, far inside the range), so this is the same
//   number; it is computed here on the significand as an integer shift.
// - Handshake: valid only, no backpressure. valid_o is valid_i one cycle later; fix_o belongs to
//   the input of the cycle before and is meaningful only while valid_o is 1.
// - Latency: 1 (the output register).
// - Parameters: ExpW, FracW: the number format (default fp24); FixBits: F (default
//   docs/spec.toml [light] fixed_bits), at most FracW.
// - Illegal input: none; every bit pattern of x_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears only valid_o.
module rc_fp_to_fix #(
  parameter int unsigned ExpW    = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW   = rc_pkg::Fp24FracW,
  parameter int unsigned FixBits = rc_pkg::LightFixedBits
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                valid_i,
  input  logic [ExpW+FracW:0] x_i,
  output logic                valid_o,
  output logic [FixBits:0]    fix_o
);

  if (FixBits > FracW || FixBits < 1) begin : g_param_check
    $error("rc_fp_to_fix: FixBits must be 1 .. FracW");
  end

  localparam int unsigned W       = 1 + ExpW + FracW;
  localparam int unsigned BiasInt = (1 << (ExpW - 1)) - 1;
  localparam int unsigned MW      = FracW + 1;  // the significand 1.f as an integer
  // The shift right of the significand: FracW - FixBits - k for x = 1.f x 2^k; k <= -1 here, and
  // a shift beyond MW leaves less than a half: 0.
  localparam int unsigned ShW     = $clog2(MW + 2) + 1;

  logic [ExpW-1:0]  e;
  logic [FracW-1:0] f;
  logic             s, is_nan, is_zero, ge_one;
  logic [MW-1:0]    m;
  logic [ExpW:0]    sh_full;   // BiasInt - e + FracW - FixBits, for e < BiasInt
  logic [ShW-1:0]   sh;
  logic             sh_big;
  logic [MW-1:0]    q, rem, half;
  logic             up;
  logic [FixBits:0] fix_d;

  assign s       = x_i[W-1];
  assign e       = x_i[W-2 -: ExpW];
  assign f       = x_i[FracW-1:0];
  assign is_nan  = (&e) && (f != '0);
  assign is_zero = e == '0;
  assign ge_one  = e >= ExpW'(BiasInt);
  assign m       = {1'b1, f};
  assign sh_full = (ExpW + 1)'(BiasInt) - {1'b0, e} + (ExpW + 1)'(FracW - FixBits);
  assign sh_big  = sh_full > (ExpW + 1)'(MW);
  assign sh      = ShW'(sh_full);

  always_comb begin
    q    = '0;
    rem  = '0;
    half = '0;
    up   = 1'b0;
    if (!sh_big) begin
      // sh >= 1 here (e < BiasInt and FixBits <= FracW).
      q    = m >> sh;
      rem  = m & ((MW'(1) << sh) - MW'(1));
      half = MW'(1) << (sh - ShW'(1));
      up   = (rem > half) || ((rem == half) && q[0]);
    end
  end

  always_comb begin
    if (s || is_nan || is_zero) fix_d = '0;
    else if (ge_one) fix_d = (FixBits + 1)'(1) << FixBits;
    else fix_d = (FixBits + 1)'(q) + (FixBits + 1)'(up);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) valid_o <= 1'b0;
    else valid_o <= valid_i;
  end

  always_ff @(posedge clk_i) begin
    fix_o <= fix_d;
  end

endmodule
