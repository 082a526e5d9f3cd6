// rc_isect_unit: the intersection unit, one ray against one triangle every two cycles (one
// transform unit used twice) or, with SharedXform = 0, every cycle (two transform units).
//
// Contract
// - Function: exactly rc::intersect() (tb/golden/trace.hpp; docs/architecture.md, "Intersection
//   (one ray, one triangle)"), every operation a correctly rounded format operation:
//     o' = M (org, 1)  (rc_xform_unit, translate = 1)    d' = M dir  (rc_xform_unit, translate = 0)
//     t  = (-o'z) / d'z          (negate = flip the sign bit)
//     u  = o'x + t * d'x         v = o'y + t * d'y
//     hit_o = lt(t_lo, t) && le(0, u) && le(0, v) && le(u + v, 1.0) && !excl_i
//             && (lt(t, best_t) || (eq(t, best_t) && $signed(tri) < $signed(best_tri)))
//   with (best_t, best_tri) = (best_t_i, best_tri_i) when best_valid_i is 1, and (+inf, -1), no
//   hit yet, when it is 0 (best_t_i and best_tri_i are then not read); t_lo = t_eps_i for a
//   secondary ray's pair (secondary_i: a shadow or bounce ray) and 0 otherwise; excl_i marks the
//   triangle a secondary ray starts on (the caller's compare), which is never its hit.
//   t_o, u_o, v_o, dz_o (= d'z) are the computed values whether or not the hit is accepted;
//   intersect() records them only for an accepted hit. tri_o and tag_o are tri_i and tag_i.
// - Packing: a word is {sign, exp[ExpW-1:0], frac[FracW-1:0]}, W = 1 + ExpW + FracW bits.
//   m_i[k*W +: W] = m_k (k = 0..11, row-major 3x4), org_i/dir_i[c*W +: W] = component c (x, y, z).
//   tri_i and best_tri_i are 32-bit two's complement. best_valid_i, secondary_i and excl_i travel
//   with the pair and are used only at the far end (beside the compares), so a caller may derive
//   them late. t_eps_i is not carried: it is read when the pair's t reaches the compares, so it
//   must hold its value while any secondary pair is in flight (a frame's constant).
// - Handshake: valid_i/ready_o at the input, valid_o/ready_i at the output, AXI-style (a transfer
//   happens on a clock edge where valid and ready are both 1). valid_o never depends on ready_i,
//   ready_o depends only on registered state, and once valid_o is 1 it stays 1 with all outputs
//   stable until the transfer. Results leave in input order, none is lost or duplicated. The fp
//   pipelines cannot stall, so the unit uses credits (rc_credit_fifo): an output FIFO of
//   Depth = PipeLat + 2 entries, and ready_o = credits < Depth, where credits = inputs accepted -
//   outputs taken = operations in flight + FIFO occupancy (one registered counter), so the FIFO
//   always has room for everything in flight. PipeLat + 2 is the least depth that sustains one
//   input per cycle (in steady state PipeLat results are in flight and one waits in the FIFO).
//   With SharedXform = 1, ready_o is also 0 in the cycle after an accepted input (the transform
//   unit's first pass; a register, so ready_o still depends only on registered state).
// - Latency: PipeLat = IssueLat + (MulStages + 3 * AddStages) + DivStages + MulStages +
//   2 * AddStages + CmpStages cycles, IssueLat = 2 with SharedXform (input register, second
//   pass) and 0 without (2 + 22 + 11 + 4 + 12 + 1 = 52 at the defaults mul 4, add 6, div 11,
//   cmp 1: the rc_fp_* default latencies), plus the FIFO's output register: valid_o rises
//   PipeLat + 1 = 53 cycles (51 with SharedXform = 0) after an accepted input when ready_i is
//   high and the FIFO is empty.
// - Throughput: SharedXform = 1: one ray-triangle pair every two cycles (with ready_i held high,
//   ready_o is 1 every other cycle); SharedXform = 0: one pair per cycle (ready_o stays 1).
// - Parameters: ExpW (>= 2), FracW (>= 1): the format; TagW (>= 1): width of the tag carried
//   alongside; MulStages, AddStages, DivStages, CmpStages (>= 1): latencies of the rc_fp_*
//   instances; SharedXform: 1 (default) = one transform unit for d' then o' (9 multipliers and
//   9 adders fewer, about 7,000 ECP5 LUT4 sites: docs/history.md), 0 = two transform units;
//   Backpressure: 1 (default) = the output FIFO and credits above, 0 = ready_i is always 1 (a
//   consumer that takes every result at once): one output register, the same latency;
//   Secondary: 1 (default) = secondary_i, excl_i and t_eps_i as above, 0 = primary rays only
//   (those inputs ignored, as if 0: no logic for them); BlockDelays: 1 = the delay lines that
//   carry the operands and side band past the divider, multipliers, adders and compare (and the
//   transform unit's) in block RAM, 0 (default) = shift registers, the same results either way.
// - Illegal input: none; every bit pattern of every input is legal.
// - Reset: rst_ni (active low, asynchronous) clears control state only (valid pipelines, FIFO
//   pointers and counters); data registers have no reset.
//
// Pipeline (cycle numbers at the defaults with SharedXform = 0, counted from the accepted input;
// SharedXform = 1 registers the input at cycle 0, starts d' at 1 and o' at 2, and keeps d' one
// cycle in xd_q, so everything below happens 2 cycles later):
//   0   o' and d' transforms start (two rc_xform_unit, valid-only)
//   22  t = -o'z / d'z starts; o'x, o'y, d'x, d'y, d'z and the side band wait DivStages
//   33  t*d'x, t*d'y start
//   34  lt(t_lo,t), lt(t,best_t), eq(t,best_t) start (t from a register beside the compares)
//   35  flag a = lt(t_lo,t) && !excl && (lt(t,best_t) || (eq(t,best_t) && tri < best_tri))
//   37  u = o'x + t*d'x, v = o'y + t*d'y start
//   43  u + v starts; le(0,u), le(0,v) start
//   44  flag b = flag a && le(0,u) && le(0,v)
//   49  le(u+v, 1.0) starts
//   50  hit = flag b && le(u+v, 1.0); the result enters the output FIFO
//   51  valid_o
module rc_isect_unit #(
  parameter int unsigned ExpW        = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW       = rc_pkg::Fp24FracW,
  parameter int unsigned TagW        = 8,
  parameter int unsigned MulStages   = rc_pkg::FpStagesMul,
  parameter int unsigned AddStages   = rc_pkg::FpStagesAdd,
  parameter int unsigned DivStages   = rc_pkg::FpStagesDiv,
  parameter int unsigned CmpStages   = rc_pkg::FpStagesCmp,
  parameter bit          SharedXform = 1'b1,
  // 1: the output FIFO and credits above; 0: ready_i must always be 1 (a consumer that takes every
  // result at once, as rc_core's write-back does): the FIFO is one output register, the same
  // latency, and ready_o follows only the shared transform's pass.
  parameter bit          Backpressure = 1'b1,
  // 1: a secondary ray's rules (secondary_i, excl_i, t_eps_i); 0: primary rays only, those
  // inputs are ignored and no logic is made for them (the compare with 0 keeps its constant
  // operand).
  parameter bit          Secondary    = 1'b1,
  // 1: the delay lines beside the divider, multipliers, adders and compare (and the transform
  // unit's) in block RAM (rc_delay_line), 0: shift registers; the same results and cycles.
  parameter bit          BlockDelays  = 1'b0
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  // Input
  input  logic                         valid_i,
  output logic                         ready_o,
  input  logic [TagW-1:0]              tag_i,
  input  logic [31:0]                  tri_i,
  input  logic [12*(1+ExpW+FracW)-1:0] m_i,
  input  logic [3*(1+ExpW+FracW)-1:0]  org_i,
  input  logic [3*(1+ExpW+FracW)-1:0]  dir_i,
  input  logic [ExpW+FracW:0]          best_t_i,
  input  logic [31:0]                  best_tri_i,
  input  logic                         best_valid_i,
  input  logic                         secondary_i,
  input  logic                         excl_i,
  input  logic [ExpW+FracW:0]          t_eps_i,
  // Output
  output logic                         valid_o,
  input  logic                         ready_i,
  output logic [TagW-1:0]              tag_o,
  output logic [31:0]                  tri_o,
  output logic                         hit_o,
  output logic [ExpW+FracW:0]          t_o,
  output logic [ExpW+FracW:0]          u_o,
  output logic [ExpW+FracW:0]          v_o,
  output logic [ExpW+FracW:0]          dz_o
);

  ////////////////
  // Parameters //
  ////////////////

  if (ExpW < 2 || FracW < 1 || TagW < 1) begin : g_param_check
    $error("rc_isect_unit: need ExpW >= 2, FracW >= 1, TagW >= 1");
  end
  if (MulStages < 1 || AddStages < 1 || DivStages < 1 || CmpStages < 1) begin : g_stages_check
    $error("rc_isect_unit: every Stages parameter must be >= 1");
  end

  localparam int unsigned W        = 1 + ExpW + FracW;
  localparam int unsigned XformLat = MulStages + 3 * AddStages;
  localparam int unsigned IssueLat = SharedXform ? 2 : 0;
  localparam int unsigned PipeLat  = IssueLat + XformLat + DivStages + MulStages + 2 * AddStages +
                                     CmpStages;

  localparam logic [W-1:0] Zero = '0;
  localparam logic [W-1:0] Inf  = {1'b0, {ExpW{1'b1}}, {FracW{1'b0}}};
  // 1.0: sign 0, exponent field = bias, fraction 0.
  localparam logic [W-1:0] One  = {1'b0, ExpW'((1 << (ExpW - 1)) - 1), {FracW{1'b0}}};

  logic in_fire;
  assign in_fire = valid_i & ready_o;

`ifndef SYNTHESIS
  // Assertions are checked only once out of reset.
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
`endif

  ///////////////////////////////
  // Transforms: o' and d'     //
  ///////////////////////////////

  // Side band carried through the o' transform's tag: {tag, tri, best_t, best_tri, best_valid}
  // and, with Secondary, {secondary, excl}. The best's select and the triangle order (tri <
  // best_tri, a 32-bit compare) are taken at the far end, between two registers, so neither is
  // on the path from the core's best-hit read into the unit.
  localparam int unsigned SbBaseW = TagW + 32 + W + 32 + 1;
  localparam int unsigned SbW     = SbBaseW + (Secondary ? 2 : 0);
  logic [SbW-1:0] sb_in, sb_x;
  if (Secondary) begin : g_sb_secondary
    assign sb_in = {tag_i, tri_i, best_t_i, best_tri_i, best_valid_i, secondary_i, excl_i};
  end else begin : g_sb_primary
    assign sb_in = {tag_i, tri_i, best_t_i, best_tri_i, best_valid_i};
  end
  logic           xo_valid;
  logic [3*W-1:0] xo, xd;
  logic [W-1:0]   oz;  // o'z for the divider
  logic           issue_busy;  // the input side cannot take a pair this cycle

  if (SharedXform) begin : g_shared_xform
    // One transform unit, used twice per pair. The accepted pair is registered (m_q, sb_q,
    // org_q; v_q starts with dir); the cycle after (pass 1) the unit transforms d' = M dir, and
    // the cycle after that (pass 2) o' = M (org, 1), with v_q reloaded from org_q. m_q and the
    // operand vector come straight from registers into the multipliers. A pair can be accepted
    // in pass 2's cycle (the registers are only overwritten at its end), so one pair every two
    // cycles. d' leaves the transform unit a cycle before o' and waits in xd_q.
    logic [12*W-1:0] m_q;
    logic [3*W-1:0]  org_q;
    logic [9*W-1:0]  v_q;  // one copy per row of the transform unit
    logic [SbW-1:0]  sb_q;
    logic            pass1_q, pass2_q;
    logic [4:0]      hold_q;
    logic            xf_valid, xf_ready, xf_pass2;
    logic [3*W-1:0]  xf_r, xf_rt;
    logic [SbW-1:0]  xf_sb;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        pass1_q <= 1'b0;
        pass2_q <= 1'b0;
      end else begin
        pass1_q <= in_fire;
        pass2_q <= pass1_q;
      end
    end
    // The input registers load at the end of every cycle but pass 1's. Passes 1 and 2 read what
    // the accepted pair's edge loaded, and pass 1's end, the only edge between, keeps it; no
    // pair is accepted in pass 1 (ready_o is 0), and what the other edges load is never read.
    // So the enables come from kept copies of pass1_q, each placed beside its group (hold_q:
    // m_q's rows and v_q's copies 0-2, org_q 3, sb_q 4), not from in_fire, one net to all of
    // them (run 61 seed 3: i2_v_q -> sb_q, 56 enables).
    rc_reg_copies #(
      .Width   (1),
      .Copies  (5),
      .HasReset(1'b1)
    ) u_hold (
      .clk_i,
      .rst_ni,
      .d_i (in_fire),
      .q_o (hold_q)
    );
    always_ff @(posedge clk_i) begin
      for (int r = 0; r < 3; r++) begin
        if (!hold_q[r]) begin
          m_q[4*W*r +: 4*W] <= m_i[4*W*r +: 4*W];
        end
        // The operand vector, one copy beside each row's three multipliers (a single register
        // drove all nine with their classification logic shared: run 47, v_q -> sb_q, -1.23
        // ns): dir at the accepted pair's edge, org at pass 1's. The copies' selects are
        // separate registers, so synthesis does not merge them.
        v_q[3*W*r +: 3*W] <= hold_q[r] ? org_q : dir_i;
      end
      if (!hold_q[3]) begin
        org_q <= org_i;
      end
      if (!hold_q[4]) begin
        sb_q <= sb_in;
      end
    end
    assign issue_busy = pass1_q;
`ifndef SYNTHESIS
    // The enables' copies are pass1_q (the same input, registered with the same reset).
    HoldCopy_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 hold_q[0] == pass1_q);
    // The rows' copies of the operand vector agree whenever the transform unit uses them.
    VCopies_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                pass1_q || pass2_q |-> v_q[3*W +: 3*W] == v_q[0 +: 3*W] &&
                                                       v_q[6*W +: 3*W] == v_q[0 +: 3*W]);
`endif

    rc_xform_unit #(
      .ExpW(ExpW), .FracW(FracW), .TagW(SbW + 1), .MulStages(MulStages), .AddStages(AddStages),
      .Backpressure(1'b0),
      .BlockDelays (BlockDelays)
    ) u_xform (
      .clk_i, .rst_ni,
      .valid_i(pass1_q | pass2_q), .ready_o(xf_ready), .m_i(m_q), .v_i(v_q),
      .translate_i(pass2_q), .tag_i({sb_q, pass2_q}),
      .valid_o(xf_valid), .ready_i(1'b1), .r_o(xf_r), .rt_o(xf_rt), .tag_o({xf_sb, xf_pass2})
    );

    // d' is read one cycle after it leaves, with o' (PassOrder_A), so the register loads at
    // every edge, without an enable (run 61 seed 1 at 9 ns: the transform's output valid into
    // xd_q's 72 enables, -0.90 ns).
    logic [3*W-1:0] xd_q;
    always_ff @(posedge clk_i) begin
      xd_q <= xf_r;
    end
    assign xo_valid = xf_valid & xf_pass2;
    assign xo       = xf_r;
    // The divider reads o'z from the unselected rows (rt_o; o' is a pass-2 result, translated),
    // so the transform's row select is not in its path (run 71 seed 3: sel_o_q into u_div_t's
    // first slot, 10 cells, -1.71 ns). The delay line beside the divider keeps xf_r's o'x and o'y:
    // d' is xf_r a cycle earlier, so they are the flip-flops of the line's d'x and d'y one stage
    // back (and of xd_q), which synthesis shares.
    assign oz       = xf_rt[2*W +: W];
    assign xd       = xd_q;
    assign sb_x     = xf_sb;

    logic unused_xf;
    assign unused_xf = ^{xf_ready, xf_rt[2*W-1:0], xo[3*W-1:2*W]};  // o'z: oz

`ifndef SYNTHESIS
    // Passes alternate d', o': a pass-2 result always follows a pass-1 result by one cycle.
    // (Checked on registered flags: Verilator 5.006 miscompiles the sampling of the tag delay
    // line that an assertion on xf_pass2 itself would need.)
    logic d_prev_q, order_bad_q;
    always_ff @(posedge clk_i) begin
      d_prev_q    <= xf_valid & ~xf_pass2;
      order_bad_q <= xo_valid & ~d_prev_q;
    end
    PassOrder_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  !order_bad_q);
`endif
  end else begin : g_two_xforms
    // Two transform units side by side, one pair per cycle.
    logic           xo_ready, xd_ready, xd_valid, xd_tag;
    logic [3*W-1:0] xo_t, xd_t;  // the translated rows: o' is r_o itself (translate_i = 1)

    rc_xform_unit #(
      .ExpW(ExpW), .FracW(FracW), .TagW(SbW), .MulStages(MulStages), .AddStages(AddStages),
      .Backpressure(1'b0),
      .BlockDelays (BlockDelays)
    ) u_xform_org (
      .clk_i, .rst_ni,
      .valid_i(in_fire), .ready_o(xo_ready), .m_i, .v_i({3{org_i}}), .translate_i(1'b1),
      .tag_i(sb_in),
      .valid_o(xo_valid), .ready_i(1'b1), .r_o(xo), .rt_o(xo_t), .tag_o(sb_x)
    );
    assign oz = xo[2*W +: W];

    rc_xform_unit #(
      .ExpW(ExpW), .FracW(FracW), .TagW(1), .MulStages(MulStages), .AddStages(AddStages),
      .Backpressure(1'b0),
      .BlockDelays (BlockDelays)
    ) u_xform_dir (
      .clk_i, .rst_ni,
      .valid_i(in_fire), .ready_o(xd_ready), .m_i, .v_i({3{dir_i}}), .translate_i(1'b0),
      .tag_i(1'b0),
      .valid_o(xd_valid), .ready_i(1'b1), .r_o(xd), .rt_o(xd_t), .tag_o(xd_tag)
    );

    assign issue_busy = 1'b0;

    logic unused_x2;
    assign unused_x2 = ^{xo_ready, xd_ready, xd_tag, xo_t, xd_t};

`ifndef SYNTHESIS
    // The two transforms run in lockstep; diverging valids would mean misaligned delay lines.
    XformLockstep_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                      xo_valid == xd_valid);
`endif
  end

  ///////////////////////////////
  // t = -o'z / d'z            //
  ///////////////////////////////

  logic [W-1:0] neg_oz, t;
  logic         t_valid;
  assign neg_oz = {~oz[W-1], oz[W-2:0]};

  rc_fp_div #(.ExpW(ExpW), .FracW(FracW), .Stages(DivStages)) u_div_t (
    .clk_i, .rst_ni, .valid_i(xo_valid), .a_i(neg_oz), .b_i(xd[2*W +: W]),
    .valid_o(t_valid), .res_o(t)
  );

  // Waiting for t: {side band, d'z, d'y, d'x, o'y, o'x}.
  localparam int unsigned D1W = SbW + 5 * W;
  logic [D1W-1:0] d1;
  rc_delay_line #(.Width(D1W), .Cycles(DivStages), .Block(BlockDelays)) u_dly_1 (
    .clk_i, .rst_ni, .data_i({sb_x, xd, xo[2*W-1:0]}), .data_o(d1)
  );

  logic [W-1:0]    ox1, oy1, dx1, dy1, dz1, best_t1, best_t1_in;
  logic [TagW-1:0] tag1;
  logic [31:0]     tri_s1;
  logic [31:0]     best_tri1, best_tri1_in;
  logic            best_v1, tri_lt1;
  logic [SbW-1:0]  sb1;
  assign {sb1, dz1, dy1, dx1, oy1, ox1} = d1;
  assign {tag1, tri_s1, best_t1_in, best_tri1_in, best_v1} = sb1[SbW-1 -: SbBaseW];
  // The best: the given one, or +inf and -1 (no hit yet).
  assign best_t1   = best_v1 ? best_t1_in : Inf;
  assign best_tri1 = best_v1 ? best_tri1_in : 32'hffff_ffff;
  assign tri_lt1   = $signed(tri_s1) < $signed(best_tri1);

  ///////////////////////////////////////////////
  // t*d'x, t*d'y and the comparisons on t     //
  ///////////////////////////////////////////////

  logic [W-1:0] tdx, tdy;
  logic         tdx_valid, tdy_valid;

  rc_fp_mul #(.ExpW(ExpW), .FracW(FracW), .Stages(MulStages)) u_mul_tdx (
    .clk_i, .rst_ni, .valid_i(t_valid), .a_i(t), .b_i(dx1), .valid_o(tdx_valid), .res_o(tdx)
  );
  rc_fp_mul #(.ExpW(ExpW), .FracW(FracW), .Stages(MulStages)) u_mul_tdy (
    .clk_i, .rst_ni, .valid_i(t_valid), .a_i(t), .b_i(dy1), .valid_o(tdy_valid), .res_o(tdy)
  );

  logic         c0t_valid, c0t_lt, c0t_le, c0t_eq;
  logic         ctb_valid, ctb_lt, ctb_le, ctb_eq;
  logic [W-1:0] c0t_min, c0t_max, ctb_min, ctb_max;

  // The compares on t take it a cycle after the divider, from a register beside them (t_cq,
  // with best_t1 and the index test): flag a waits for u and v's compares anyway, so it waits a
  // cycle less below (run 52: the divider's output register, which also feeds the two
  // multipliers, through the compare with the best t, -0.89 and -1.12 ns).
  logic [W-1:0] t_cq, best_t_cq, t_lo;
  logic         t_cvalid_q, tri_lt_cq, keep;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      t_cvalid_q <= 1'b0;
    end else begin
      t_cvalid_q <= t_valid;
    end
  end
  always_ff @(posedge clk_i) begin
    t_cq      <= t;
    best_t_cq <= best_t1;
    tri_lt_cq <= tri_lt1;
  end
  // A secondary pair's t_lo (registered beside t_cq) and its exclusion (which waits for the
  // comparator outputs, as tri < best_tri does: 1 + CmpStages cycles).
  if (Secondary) begin : g_secondary
    logic               secondary1, excl1, keep1;
    logic [W-1:0]       t_lo_cq;
    logic [CmpStages:0] keep_q;
    assign {secondary1, excl1} = sb1[1:0];
    assign keep1 = ~excl1;
    always_ff @(posedge clk_i) begin
      t_lo_cq <= secondary1 ? t_eps_i : Zero;
      keep_q  <= (keep_q << 1) | (CmpStages + 1)'(keep1);
    end
    assign t_lo = t_lo_cq;
    assign keep = keep_q[CmpStages];
  end else begin : g_no_secondary
    assign t_lo = Zero;
    assign keep = 1'b1;
    logic unused_secondary;
    assign unused_secondary = ^{secondary_i, excl_i, t_eps_i};
  end

  rc_fp_cmp #(.ExpW(ExpW), .FracW(FracW), .Stages(CmpStages)) u_cmp_0_t (
    .clk_i, .rst_ni, .valid_i(t_cvalid_q), .a_i(t_lo), .b_i(t_cq), .valid_o(c0t_valid),
    .lt_o(c0t_lt), .le_o(c0t_le), .eq_o(c0t_eq), .min_o(c0t_min), .max_o(c0t_max)
  );
  rc_fp_cmp #(.ExpW(ExpW), .FracW(FracW), .Stages(CmpStages)) u_cmp_t_best (
    .clk_i, .rst_ni, .valid_i(t_cvalid_q), .a_i(t_cq), .b_i(best_t_cq), .valid_o(ctb_valid),
    .lt_o(ctb_lt), .le_o(ctb_le), .eq_o(ctb_eq), .min_o(ctb_min), .max_o(ctb_max)
  );

  // tri < best_tri waits for the comparator outputs.
  logic [CmpStages-1:0] tri_lt_q;
  always_ff @(posedge clk_i) begin
    tri_lt_q <= (tri_lt_q << 1) | CmpStages'(tri_lt_cq);
  end

  // Flag a: beyond t_lo, not the excluded triangle, and closer than the best hit (with the index
  // tie break).
  logic flag_a;
  assign flag_a = c0t_lt & keep & (ctb_lt | (ctb_eq & tri_lt_q[CmpStages-1]));

  // Waiting for the products: {tag, tri, d'z, t, o'y, o'x}.
  localparam int unsigned D2W = TagW + 32 + 4 * W;
  logic [D2W-1:0] d2;
  rc_delay_line #(.Width(D2W), .Cycles(MulStages), .Block(BlockDelays)) u_dly_2 (
    .clk_i, .rst_ni, .data_i({tag1, tri_s1, dz1, t, oy1, ox1}), .data_o(d2)
  );

  logic [W-1:0]    ox2, oy2, t2, dz2;
  logic [TagW-1:0] tag2;
  logic [31:0]     tri_s2;
  assign {tag2, tri_s2, dz2, t2, oy2, ox2} = d2;

  ///////////////////////////////
  // u = o'x + t*d'x, v         //
  ///////////////////////////////

  logic [W-1:0] u, v;
  logic         u_valid, v_valid;

  rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(AddStages)) u_add_u (
    .clk_i, .rst_ni, .valid_i(tdx_valid), .sub_i(1'b0), .a_i(ox2), .b_i(tdx),
    .valid_o(u_valid), .res_o(u)
  );
  rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(AddStages)) u_add_v (
    .clk_i, .rst_ni, .valid_i(tdy_valid), .sub_i(1'b0), .a_i(oy2), .b_i(tdy),
    .valid_o(v_valid), .res_o(v)
  );

  // Waiting for u and v: {tag, tri, d'z, t}.
  localparam int unsigned D3W = TagW + 32 + 2 * W;
  logic [D3W-1:0] d3;
  rc_delay_line #(.Width(D3W), .Cycles(AddStages), .Block(BlockDelays)) u_dly_3 (
    .clk_i, .rst_ni, .data_i({tag2, tri_s2, dz2, t2}), .data_o(d3)
  );

  logic [W-1:0]    t3, dz3;
  logic [TagW-1:0] tag3;
  logic [31:0]     tri_s3;
  assign {tag3, tri_s3, dz3, t3} = d3;

  // Flag a (ready 1 + CmpStages after t) waits until u and v's comparisons are done.
  localparam int unsigned FaDly = MulStages + AddStages - 1;
  logic [FaDly-1:0] flag_a_q;
  always_ff @(posedge clk_i) begin
    flag_a_q <= (flag_a_q << 1) | FaDly'(flag_a);
  end

  ///////////////////////////////////////////
  // u + v, le(0, u), le(0, v)             //
  ///////////////////////////////////////////

  logic [W-1:0] uv;
  logic         uv_valid;

  rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(AddStages)) u_add_uv (
    .clk_i, .rst_ni, .valid_i(u_valid), .sub_i(1'b0), .a_i(u), .b_i(v),
    .valid_o(uv_valid), .res_o(uv)
  );

  logic         c0u_valid, c0u_lt, c0u_le, c0u_eq;
  logic         c0v_valid, c0v_lt, c0v_le, c0v_eq;
  logic [W-1:0] c0u_min, c0u_max, c0v_min, c0v_max;

  rc_fp_cmp #(.ExpW(ExpW), .FracW(FracW), .Stages(CmpStages)) u_cmp_0_u (
    .clk_i, .rst_ni, .valid_i(u_valid), .a_i(Zero), .b_i(u), .valid_o(c0u_valid),
    .lt_o(c0u_lt), .le_o(c0u_le), .eq_o(c0u_eq), .min_o(c0u_min), .max_o(c0u_max)
  );
  rc_fp_cmp #(.ExpW(ExpW), .FracW(FracW), .Stages(CmpStages)) u_cmp_0_v (
    .clk_i, .rst_ni, .valid_i(u_valid), .a_i(Zero), .b_i(v), .valid_o(c0v_valid),
    .lt_o(c0v_lt), .le_o(c0v_le), .eq_o(c0v_eq), .min_o(c0v_min), .max_o(c0v_max)
  );

  // Flag b: flag a and both barycentrics non-negative.
  logic flag_b;
  assign flag_b = flag_a_q[FaDly-1] & c0u_le & c0v_le;

  logic [AddStages-1:0] flag_b_q;
  always_ff @(posedge clk_i) begin
    flag_b_q <= (flag_b_q << 1) | AddStages'(flag_b);
  end

  // Waiting for the last comparison: {tag, tri, d'z, t, v, u}.
  localparam int unsigned D4Dly = AddStages + CmpStages;
  localparam int unsigned D4W   = TagW + 32 + 4 * W;
  logic [D4W-1:0] d4;
  rc_delay_line #(.Width(D4W), .Cycles(D4Dly), .Block(BlockDelays)) u_dly_4 (
    .clk_i, .rst_ni, .data_i({tag3, tri_s3, dz3, t3, v, u}), .data_o(d4)
  );

  ///////////////////////////////
  // le(u + v, 1.0) and the hit //
  ///////////////////////////////

  logic         c1_valid, c1_lt, c1_le, c1_eq;
  logic [W-1:0] c1_min, c1_max;

  rc_fp_cmp #(.ExpW(ExpW), .FracW(FracW), .Stages(CmpStages)) u_cmp_uv_1 (
    .clk_i, .rst_ni, .valid_i(uv_valid), .a_i(uv), .b_i(One), .valid_o(c1_valid),
    .lt_o(c1_lt), .le_o(c1_le), .eq_o(c1_eq), .min_o(c1_min), .max_o(c1_max)
  );

  logic            pipe_valid, pipe_hit;
  logic [W-1:0]    pipe_t, pipe_u, pipe_v, pipe_dz;
  logic [TagW-1:0] pipe_tag;
  logic [31:0]     pipe_tri;

  assign pipe_valid = c1_valid;
  assign pipe_hit   = flag_b_q[AddStages-1] & c1_le;
  assign {pipe_tag, pipe_tri, pipe_dz, pipe_t, pipe_v, pipe_u} = d4;

  // Unused outputs of the shared building blocks (min/max, redundant valids and predicates).
  logic unused_outputs;
  assign unused_outputs = ^{v_valid,
                            c0t_valid, c0t_le, c0t_eq, c0t_min, c0t_max,
                            ctb_valid, ctb_le, ctb_min, ctb_max,
                            c0u_valid, c0u_lt, c0u_eq, c0u_min, c0u_max,
                            c0v_valid, c0v_lt, c0v_eq, c0v_min, c0v_max,
                            c1_lt, c1_eq, c1_min, c1_max};

  ////////////////////////////////////////
  // Output FIFO with credit flow control //
  ////////////////////////////////////////

  // The credit counter, FIFO pointers and their checks (credit bound, room for every write,
  // stable output until taken) live in rc_credit_fifo. Depth = PipeLat + 2 sustains one
  // ray-triangle pair per cycle (more than the shared transform's one per two cycles needs, but
  // a shallower one saves nothing: the deep, wide FIFO, 54 x 137 bits at the defaults, is a
  // memory array (MemArray) that synthesis maps to RAM).
  if (Backpressure) begin : g_fifo
    logic credit;
    assign ready_o = credit & ~issue_busy;
    rc_credit_fifo #(.Width(TagW + 32 + 1 + 4 * W), .Depth(PipeLat + 2), .MemArray(1'b1)) u_fifo (
      .clk_i, .rst_ni, .take_i(in_fire), .credit_o(credit), .wr_valid_i(pipe_valid),
      .wr_data_i({pipe_tag, pipe_tri, pipe_hit, pipe_dz, pipe_t, pipe_v, pipe_u}),
      .valid_o, .ready_i, .data_o({tag_o, tri_o, hit_o, dz_o, t_o, v_o, u_o})
    );
  end else begin : g_out_reg
    // Every result is taken as it appears (ready_i is 1), so one output register replaces the
    // FIFO: the same latency, no credits.
    rc_pipe_out #(
      .Width   (TagW + 32 + 1 + 4 * W),
      .DataRegs(1),
      .Stages  (1)
    ) u_out (
      .clk_i,
      .rst_ni,
      .valid_i(pipe_valid),
      .data_i ({pipe_tag, pipe_tri, pipe_hit, pipe_dz, pipe_t, pipe_v, pipe_u}),
      .valid_o,
      .data_o ({tag_o, tri_o, hit_o, dz_o, t_o, v_o, u_o})
    );
    assign ready_o = ~issue_busy;
`ifndef SYNTHESIS
    NoBackpressure_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                       valid_o |-> ready_i);
`endif
  end

  ////////////////
  // Assertions //
  ////////////////

`ifndef SYNTHESIS
  // The parallel pipelines run in lockstep; diverging valids would mean misaligned delay lines.
  Lockstep_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               (tdx_valid == tdy_valid) &&
                               (u_valid == v_valid) && (c0t_valid == ctb_valid) &&
                               (c0u_valid == c0v_valid));
  // The consumer qualifies everything with valid_o, so it must be known once out of reset.
  ValidKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !$isunknown({valid_o, ready_o}));
  // A valid result is fully determined by known inputs.
  ResKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               valid_o |-> !$isunknown({hit_o, t_o, u_o, v_o, dz_o}));
`endif

endmodule
