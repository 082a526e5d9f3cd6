// rc_fp_mul: pipelined floating-point multiplier for the raycore number format.
//
// Contract
// - Function: res_o = a_i * b_i, correctly rounded, bit-exact with rc::Fp<ExpW, FracW>::operator*
//   (tb/fp/fp.hpp).
// - Handshake: valid only, no backpressure. valid_o is valid_i delayed by exactly Stages cycles;
//   res_o belongs to the inputs presented Stages cycles earlier and is meaningful only while
//   valid_o is 1. A new operation may be presented every cycle.
// - Latency: Stages cycles (Stages >= 1, checked at elaboration).
// - Parameters: ExpW exponent bits (>= 2), FracW fraction bits (>= 1); a word is
//   {sign, exp[ExpW-1:0], frac[FracW-1:0]}. Stages = latency in cycles.
// - Illegal input: none; every bit pattern of a_i and b_i is legal.
// - Reset: rst_ni (active low, asynchronous) clears only the valid pipeline; data registers have
//   no reset.
// - Format rules implemented: an exponent field of 0 reads as signed zero whatever the fraction
//   (flush-to-zero inputs); exp all ones with frac 0 is +-inf, with frac != 0 NaN; any NaN input,
//   and 0 * inf, give the canonical NaN (sign 0, exp all ones, frac MSB only); the sign of every
//   other result (zero and infinity included) is the xor of the operand signs; rounding is to
//   nearest, ties to even, with an unbounded exponent, and only then a biased exponent <= 0
//   flushes to signed zero and one >= all ones overflows to signed infinity.
// - Synthesis: the significand product is a single plain (FracW+1) x (FracW+1) unsigned multiply
//   of two signals (one MULT18X18D on ECP5 at fp24).
//
// Pipeline (segments, and the cuts between them in the order Stages enables them):
//   segment 0: unpack, classify, exponent sum            | cut A (Stages >= 4)
//   segment 1: significand product; beside it the range  | cut B (Stages >= 2)
//              checks and the result's kinds for both carries (rc_fp_round_kinds), for both
//              outcomes of the normalise shift (the product below 2, or from 2 up)
//   segment 2: normalise (one-bit shift), round/sticky,  | cut C (Stages >= 3)
//              the shift's select of the kinds and the exponent
//   segment 3: round increment, the kind's select, pack  | output register(s)
//   The output has Stages minus the enabled internal cuts registers (at least one).
module rc_fp_mul #(
  parameter int unsigned ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW  = rc_pkg::Fp24FracW,
  parameter int unsigned Stages = rc_pkg::FpStagesMul
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
    $error("rc_fp_mul: Stages must be >= 1 (it is the latency in cycles)");
  end
  if (ExpW < 2 || FracW < 1) begin : g_width_check
    $error("rc_fp_mul: need ExpW >= 2 and FracW >= 1");
  end

  localparam int unsigned W     = 1 + ExpW + FracW;
  localparam int unsigned ManW  = FracW + 1;          // significand with the hidden bit
  localparam int unsigned ProdW = 2 * ManW;
  localparam int unsigned ExW   = ExpW + 2;           // unbounded exponent, two's complement
  localparam int unsigned Bias  = (1 << (ExpW - 1)) - 1;

  localparam bit          CutA    = Stages >= 4;
  localparam bit          CutB    = Stages >= 2;
  localparam bit          CutC    = Stages >= 3;
  localparam int unsigned OutRegs = Stages - 32'(CutA) - 32'(CutB) - 32'(CutC);

  // Per-operation flags carried down the pipeline: {spec_nan, spec_inf, spec_zero, sign}.
  localparam int unsigned MetaW = 4;

  ///////////////////////////
  // Segment 0: unpack     //
  ///////////////////////////

  logic [ExpW-1:0]  a_exp, b_exp;
  logic             a_zero, b_zero, a_nan, b_nan, a_inf, b_inf;
  logic             spec_nan, spec_inf, spec_zero;
  logic [MetaW-1:0] meta_s0;
  logic [ExW-1:0]   exp_s0;
  logic [ManW-1:0]  a_man_s0, b_man_s0;

  assign a_exp  = a_i[W-2 -: ExpW];
  assign b_exp  = b_i[W-2 -: ExpW];
  assign a_zero = ~|a_exp;
  assign b_zero = ~|b_exp;
  assign a_nan  = (&a_exp) & (|a_i[FracW-1:0]);
  assign b_nan  = (&b_exp) & (|b_i[FracW-1:0]);
  assign a_inf  = (&a_exp) & ~(|a_i[FracW-1:0]);
  assign b_inf  = (&b_exp) & ~(|b_i[FracW-1:0]);

  assign spec_nan  = a_nan | b_nan | (a_inf & b_zero) | (a_zero & b_inf);
  assign spec_inf  = a_inf | b_inf;
  assign spec_zero = a_zero | b_zero;
  assign meta_s0   = {spec_nan, spec_inf, spec_zero, a_i[W-1] ^ b_i[W-1]};

  // Biased exponent of the product before normalisation (only used for finite nonzero operands).
  assign exp_s0   = ExW'(a_exp) + ExW'(b_exp) - ExW'(Bias);
  // The hidden bit is always 1 here: zero, infinity and NaN operands are overridden later.
  assign a_man_s0 = {1'b1, a_i[FracW-1:0]};
  assign b_man_s0 = {1'b1, b_i[FracW-1:0]};

  ////////////////
  // Cut A      //
  ////////////////

  localparam int unsigned SAW = MetaW + ExW + 2 * ManW;
  logic [SAW-1:0]   sa_d, sa_q;
  logic [MetaW-1:0] meta_s1;
  logic [ExW-1:0]   exp_s1;
  logic [ManW-1:0]  a_man_s1, b_man_s1;

  assign sa_d = {meta_s0, exp_s0, a_man_s0, b_man_s0};
  // Kept: two multipliers with a common operand would otherwise share one merged register
  // (Yosys's opt_merge), which then feeds both MULT18X18D across the chip (runs 60 and 61,
  // seed 1: a transform row's operand register into another row's multiplier).
  if (CutA) begin : g_cut_a
    (* keep *) always_ff @(posedge clk_i) begin
      sa_q <= sa_d;
    end
  end else begin : g_no_cut_a
    assign sa_q = sa_d;
  end
  assign {meta_s1, exp_s1, a_man_s1, b_man_s1} = sa_q;

  ///////////////////////////
  // Segment 1: product    //
  ///////////////////////////

  logic [ProdW-1:0] prod_s1;
  assign prod_s1 = a_man_s1 * b_man_s1;

  // Beside the product (it does not need it): the normalised exponent for both outcomes of the
  // normalise shift (index 0: the product below 2, exponent exp; 1: from 2 up, exp + 1), each
  // one's range checks (rc_fp_round_flags without its all-ones flag, which needs the
  // significand) and the result's kinds for both rounding carries, so segment 2 only selects
  // them by the product's top bit (runs 60 and 61: the checks and the kinds behind the shift
  // made segment 2 the multipliers' longest, 13 to 14 cells).
  // (Plain vectors, entry n at [n*width +: width]: Debian's Yosys 0.23, which makes the fp
  // units' netlist test, takes no packed arrays of vectors.)
  localparam int unsigned KindsW = 2 * rc_pkg::FpResultKindBits;  // two kinds: no carry, carry
  logic [2*ExW-1:0]    exp_nrm_s1;
  logic [3:0]          uflow_s1, oflow_s1;
  logic [2*KindsW-1:0] kinds_s1;
  logic [1:0]          res_sign_s1, unused_ones_s1;
  logic                spec_nan_s1, spec_inf_s1, spec_zero_s1, sign_s1;
  assign {spec_nan_s1, spec_inf_s1, spec_zero_s1, sign_s1} = meta_s1;
  assign exp_nrm_s1 = {exp_s1 + ExW'(1), exp_s1};
  for (genvar n = 0; n < 2; n++) begin : g_shift
    rc_fp_round_flags #(
      .ExpW (ExpW),
      .FracW(FracW),
      .ExW  (ExW)
    ) u_round_flags (
      .exp_i     (exp_nrm_s1[n*ExW +: ExW]),
      .man_i     ('0),
      .man_ones_o(unused_ones_s1[n]),
      .uflow_o   (uflow_s1[2*n +: 2]),
      .oflow_o   (oflow_s1[2*n +: 2])
    );
    rc_fp_round_kinds u_round_kinds (
      .nan_i      (spec_nan_s1),
      .inf_i      (spec_inf_s1),
      .zero_i     (spec_zero_s1),
      .zero_sign_i(sign_s1),
      .sign_i     (sign_s1),
      .uflow_i    (uflow_s1[2*n +: 2]),
      .oflow_i    (oflow_s1[2*n +: 2]),
      .kind_o     (kinds_s1[n*KindsW +: KindsW]),
      .sign_o     (res_sign_s1[n])
    );
  end
  // Unused: the all-ones flag (it needs the significand: segment 2 makes it) and the second sign
  // (the same as the first).
  logic unused_s1;
  assign unused_s1 = ^{unused_ones_s1, res_sign_s1[1]};

  ////////////////
  // Cut B      //
  ////////////////

  localparam int unsigned SBW = 2 * KindsW + 1 + 2 * ExpW + ProdW;
  logic [SBW-1:0]      sb_d, sb_q;
  logic [2*KindsW-1:0] kinds_s2;
  logic                res_sign_s2;
  logic [2*ExpW-1:0]   exp_nrm_s2;
  logic [ProdW-1:0]    prod_s2;

  // The sign does not depend on the range checks: both instances give the same one.
  assign sb_d = {kinds_s1, res_sign_s1[0], exp_nrm_s1[ExW +: ExpW], exp_nrm_s1[0 +: ExpW],
                 prod_s1};
  if (CutB) begin : g_cut_b
    always_ff @(posedge clk_i) begin
      sb_q <= sb_d;
    end
  end else begin : g_no_cut_b
    assign sb_q = sb_d;
  end
  assign {kinds_s2, res_sign_s2, exp_nrm_s2, prod_s2} = sb_q;

  ///////////////////////////////////////
  // Segment 2: normalise, round bits  //
  ///////////////////////////////////////

  // The product of two significands in [1, 2) lies in [1, 4): its top bit says which.
  logic                                  prod_top;
  logic [ProdW-1:0]                      prod_norm;
  logic [ManW-1:0]                       man_s2;
  logic                                  round_up_s2, man_ones_s2;
  logic [ExpW-1:0]                       exp_norm_s2;
  logic [KindsW-1:0]                     kind_sel_s2;

  assign prod_top    = prod_s2[ProdW-1];
  assign prod_norm   = prod_top ? prod_s2 : (prod_s2 << 1);
  assign man_s2      = prod_norm[ProdW-1 -: ManW];
  assign round_up_s2 = prod_norm[ManW-1] & ((|prod_norm[ManW-2:0]) | man_s2[0]);
  // rc_fp_round_flags' all-ones flag (a rounding increment carries out); its range checks were
  // made in segment 1 for both shifts.
  assign man_ones_s2 = &man_s2;
  assign exp_norm_s2 = prod_top ? exp_nrm_s2[ExpW +: ExpW] : exp_nrm_s2[0 +: ExpW];
  assign kind_sel_s2 = prod_top ? kinds_s2[KindsW +: KindsW] : kinds_s2[0 +: KindsW];

  ////////////////
  // Cut C      //
  ////////////////

  localparam int unsigned SCW = KindsW + 2 + ExpW + FracW + 1;
  logic [SCW-1:0]                        sc_d, sc_q;
  logic [KindsW-1:0]                     kinds_s3;
  logic                                  sign_s3, man_ones_s3, round_up_s3;
  logic [ExpW-1:0]                       exp_s3;
  logic [FracW-1:0]                      frac_s3;

  assign sc_d = {kind_sel_s2, res_sign_s2, man_ones_s2, exp_norm_s2, man_s2[FracW-1:0],
                 round_up_s2};
  if (CutC) begin : g_cut_c
    always_ff @(posedge clk_i) begin
      sc_q <= sc_d;
    end
  end else begin : g_no_cut_c
    assign sc_q = sc_d;
  end
  assign {kinds_s3, sign_s3, man_ones_s3, exp_s3, frac_s3, round_up_s3} = sc_q;

  //////////////////////////////////////////////////////
  // Segment 3: round increment, kind's select, pack  //
  //////////////////////////////////////////////////////

  logic [W-1:0] res_d;

  rc_fp_round_pack #(
    .ExpW (ExpW),
    .FracW(FracW)
  ) u_round_pack (
    .kind_i    (kinds_s3),
    .sign_i    (sign_s3),
    .man_ones_i(man_ones_s3),
    .exp_i     (exp_s3),
    .exp_inc_i (exp_s3 + ExpW'(1)),
    .frac_i    (frac_s3),
    .round_up_i(round_up_s3),
    .res_o     (res_d)
  );

  ///////////////////////////////
  // Output and valid pipeline //
  ///////////////////////////////

  rc_pipe_out #(
    .Width   (W),
    .DataRegs(OutRegs),
    .Stages  (Stages)
  ) u_out (
    .clk_i,
    .rst_ni,
    .valid_i,
    .data_i (res_d),
    .valid_o,
    .data_o (res_o)
  );

endmodule
