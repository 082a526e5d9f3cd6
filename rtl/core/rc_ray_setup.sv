// rc_ray_setup: ray set-up of one ray (docs/architecture.md, "Ray set-up"): the reciprocal
// direction and the ray's interval clipped to the root box.
//
// Contract
// - Function: exactly rc::setup_ray() (tb/golden/trace.hpp), bit for bit. Axis index a: 0 = x,
//   1 = y, 2 = z. Vector ports hold element i at [i*W +: W] (W = 1 + ExpW + FracW; the layout
//   of a packed [N][W] array, kept flat because Yosys 0.23 reads no multi-dimensional packed
//   arrays): org_i[a], dir_i[a], inv_o[a]; bounds_i[a] = lo[a], bounds_i[a + 3] = hi[a].
//     inv_o[a] = 1.0 / dir_i[a]                                       (format division)
//     tmin = +0, tmax = +inf
//     for a = x, y, z in that order:
//       t0 = (lo[a] - org_i[a]) * inv[a],  t1 = (hi[a] - org_i[a]) * inv[a]
//       if t0 or t1 is NaN: the axis is skipped
//       else: tmin = max(tmin, min(t0, t1)),  tmax = min(tmax, max(t0, t1))   (format min/max)
//     tmax = min(tmax, tlim_i)                (Limit = 1: a shadow ray's limit; +inf otherwise)
//     tmin_o = tmin, tmax_o = tmax, active_o = le(tmin, tmax)
//   The max/min chain is evaluated in exactly this order and with these operands. (The start
//   value +0 matters for the bits: max(-0, x) would give -0 for x <= -0. The axis order does
//   not: the format's min/max are the infimum/supremum of a total order with -0 below +0, and a
//   NaN t0/t1 skips the axis, so any order gives the same bits; tests/core/units checked this.)
// - Structure: one arithmetic slice, time-multiplexed over the three axes: a taken ray waits in
//   an input register and its axes enter the slice (one divider, two subtracters, two
//   multipliers, the min/max compare, the chain's max and min compares) x first, then y, then z,
//   one axis every CmpStages cycles (1, which the chain needs); the chain step of an axis takes
//   the interval straight from the step registers' results for the axis before it, and the step
//   of x selects max(+0, b) and min(+inf, b) behind the compares instead. The chain's compares
//   are made a cycle ahead, with the next axis' t0 and t1 against both intervals the next step
//   may find, so its loop is a select. A skipped axis is selected
//   behind the compares too: its step keeps the interval (or restarts it at [+0, +inf] for x),
//   so the chain's bits are those above.
// - Handshake: valid_i/ready_o in, valid_o/ready_i out, with backpressure. An operation is taken
//   when valid_i & ready_o. ready_o is the AND of two flip-flops (rc_credit_fifo's
//   credit register and the input register's free flag) and never depends on valid_i or
//   ready_i; valid_o never depends on ready_i. Results leave in order; nothing is dropped or
//   duplicated. tag_i travels with the operation to tag_o.
// - Latency: 22 cycles at the defaults from the taking edge to valid_o (input register 1 · z
//   enters the slice 2 x 1 after x · divide 11, with the subtracts in parallel (an operand
//   register, then rc_fp_add with 10 stages) · multiply 4 ·
//   min/max of t0, t1: 1 · the chain step of z: 1 (those of x and y overlap the later axes) ·
//   le: 1 · output FIFO 1), when the FIFO is empty and ready_i is 1.
// - Throughput: one ray per 3 x CmpStages cycles (3 at the defaults) while ready_i is 1: ready_o
//   rises again in the ray's last cycle in the input register (at the defaults the cycle its z
//   enters the slice), so the next ray is taken then and its x follows at once. The FIFO holds
//   Latency / (3 x CmpStages) + 1 entries (8 at the defaults), enough credits for every
//   operation in flight at that rate.
// - Limit: the chain gives tmax without tlim_i; beside the final le(tmin, tmax) two compares give
//   min(tmax, tlim_i) and le(tmin, tlim_i), and active_o = le(tmin, tmax) && le(tmin, tlim_i),
//   which is le(tmin, min(tmax, tlim_i)) for every tlim_i (tmin and the chain's tmax are never
//   NaN; a NaN tlim_i makes tmax NaN and the ray inactive either way). So the limit costs no
//   cycle. tlim_i travels with the tag.
// - Parameters: ExpW, FracW: the number format (default fp24); TagW: tag bits (>= 1); Limit: 1 =
//   tlim_i as above, 0 = no limit (tlim_i ignored, as if +inf: no logic for it).
// - Illegal input: none; every bit pattern of the data inputs is legal.
// - Reset: rst_ni (active low, asynchronous) clears control state only (the slot counter, valid
//   chains and axis flags, FIFO pointers and credit count); data registers have no reset.
module rc_ray_setup #(
  parameter int unsigned ExpW  = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW = rc_pkg::Fp24FracW,
  parameter int unsigned TagW  = 8,
  parameter bit          Limit = 1'b1
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  // Input handshake.
  input  logic                     valid_i,
  output logic                     ready_o,
  input  logic [TagW-1:0]          tag_i,
  input  logic [3*(ExpW+FracW+1)-1:0] org_i,     // x, y, z
  input  logic [3*(ExpW+FracW+1)-1:0] dir_i,     // x, y, z
  input  logic [6*(ExpW+FracW+1)-1:0] bounds_i,  // lo x, y, z, hi x, y, z
  input  logic [ExpW+FracW:0]      tlim_i,        // tmax's limit (Limit = 1)
  // Output handshake.
  output logic                     valid_o,
  input  logic                     ready_i,
  output logic [TagW-1:0]          tag_o,
  output logic [3*(ExpW+FracW+1)-1:0] inv_o,     // x, y, z
  output logic [ExpW+FracW:0]      tmin_o,
  output logic [ExpW+FracW:0]      tmax_o,
  output logic                     active_o
);

  ////////////////
  // Parameters //
  ////////////////

  if (TagW < 1 || ExpW < 2 || FracW < 1) begin : g_param_check
    $error("rc_ray_setup: need TagW >= 1, ExpW >= 2 and FracW >= 1");
  end

  localparam int unsigned W         = 1 + ExpW + FracW;
  // Latencies of the fp units: the rc_fp_* defaults, both from docs/spec.toml [fp_stages].
  localparam int unsigned DivStages = rc_pkg::FpStagesDiv;
  localparam int unsigned SubStages = DivStages;  // the subtracts run beside the divide
  if (SubStages < 2) begin : g_sub_check
    $error("rc_ray_setup: the subtracts' operand register needs DivStages >= 2");
  end
  localparam int unsigned MulStages = rc_pkg::FpStagesMul;
  localparam int unsigned CmpStages = rc_pkg::FpStagesCmp;
  // The chain makes its compares a cycle ahead, from the next axis at u_mm's input: one axis a
  // cycle, one step register.
  if (CmpStages != 1) begin : g_cmp_check
    $error("rc_ray_setup: the chain needs CmpStages = 1 (docs/spec.toml [fp_stages])");
  end
  // One axis enters the slice every AxisGap cycles: an axis' chain step needs the result of the
  // previous axis' step, which the compares give CmpStages cycles after their inputs.
  localparam int unsigned AxisGap   = CmpStages;
  localparam int unsigned Interval  = 3 * AxisGap;  // cycles per ray
  if (Interval != rc_pkg::CoreSetupInterval) begin : g_interval_check
    $error("rc_ray_setup: 3 * fp_stages.cmp must be docs/spec.toml [core] setup_interval");
  end
  // An axis entering the slice -> its min/max(t0, t1) at the chain: divide, multiply, compare.
  localparam int unsigned ChainDly  = DivStages + MulStages + CmpStages;
  // take -> FIFO write: input register, z enters 2 gaps after x, z's chain step, le.
  localparam int unsigned PipeLat   = 1 + 2 * AxisGap + ChainDly + 2 * CmpStages;
  localparam int unsigned Latency   = PipeLat + 1;  // the FIFO adds one cycle
  // Credits: a ray holds one from its take until it leaves, Latency cycles at the earliest, and
  // rays are taken Interval cycles apart, so Latency / Interval earlier rays hold one when the
  // next is taken.
  localparam int unsigned FifoDepth = Latency / Interval + 1;
  // The divider's result of axis a -> FIFO write: (2 - a) gaps, multiply, three compares.
  localparam int unsigned InvDly    = 2 * AxisGap + MulStages + 3 * CmpStages;
  localparam int unsigned AxW       = 4 * W;  // {org, dir, lo, hi} of one axis
  localparam int unsigned OutW      = TagW + 3 * W + 2 * W + 1;
  // The tag as it travels inside: {tlim, tag} with Limit.
  localparam int unsigned XTagW     = TagW + (Limit ? W : 0);

  localparam logic [ExpW-1:0] Bias   = ExpW'((1 << (ExpW - 1)) - 1);
  localparam logic [W-1:0]    One    = {1'b0, Bias, {FracW{1'b0}}};
  localparam logic [W-1:0]    PosInf = {1'b0, {ExpW{1'b1}}, {FracW{1'b0}}};

  // NaN test on the magnitude bits {exp, frac} (the sign does not matter).
  function automatic logic is_nan(logic [W-2:0] mag);
    is_nan = (&mag[W-2 -: ExpW]) & (|mag[FracW-1:0]);
  endfunction

  ////////////////////////////////////////////////
  // Input register and the axis sequence       //
  ////////////////////////////////////////////////

  // slot_q: one-hot, bit k = cycle k of the ray held in the input register (all zero: empty).
  // Axis a enters the slice in cycle a x AxisGap. The register takes the next ray in the last
  // cycle (the ray's z has then entered, or enters in that very cycle when AxisGap = 1).
  // in_free_q: the register is free (empty, or in its ray's last cycle), registered from slot_q's
  // next value, so ready_o is the AND of two flip-flops (the credit and this) and the feeder,
  // across the chip, folds it into its own first LUT (run 48: slot_q -> su_v_q, -3.07 ns).
  logic [Interval-1:0] slot_q, slot_d;
  logic                in_free_q;
  logic                credit, take, issue, first, last;

  assign ready_o = credit & in_free_q;
  assign take    = valid_i & ready_o;
  assign first   = slot_q[0];
  assign last    = slot_q[2*AxisGap];
  assign issue   = slot_q[0] | slot_q[AxisGap] | slot_q[2*AxisGap];
  assign slot_d  = take ? Interval'(1) : slot_q << 1;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      slot_q    <= '0;
      in_free_q <= 1'b1;
    end else begin
      slot_q    <= slot_d;
      in_free_q <= ~|slot_d | slot_d[Interval-1];
    end
  end

  // The ray's axes as {org, dir, lo, hi}; ax_q[0 +: AxW] is the next axis to enter the slice,
  // the rest move down one place whenever one enters (no read multiplexer in front of the
  // arithmetic). The register loads whenever it is free (empty, or in its ray's last cycle),
  // taken or not: its enables come from slot_q, this unit's own flip-flops, and valid_i reaches
  // only slot_q and the credits (the feeder's valid comes from across the chip). A load without a
  // take is never used: the ray's axes and tag are read only in its three cycles.
  logic [3*AxW-1:0] ax_in, ax_q;
  logic [XTagW-1:0] tag_q, xtag_in;
  if (Limit) begin : g_xtag_lim
    assign xtag_in = {tlim_i, tag_i};
  end else begin : g_xtag
    assign xtag_in = tag_i;
    logic unused_tlim;
    assign unused_tlim = ^tlim_i;
  end
  for (genvar a = 0; a < 3; a++) begin : g_ax_in
    assign ax_in[a*AxW +: AxW] = {org_i[a*W +: W], dir_i[a*W +: W], bounds_i[a*W +: W],
                                  bounds_i[(a+3)*W +: W]};
  end

  always_ff @(posedge clk_i) begin
    if (in_free_q) begin
      ax_q  <= ax_in;
      tag_q <= xtag_in;
    end else if (issue) begin
      ax_q[0 +: 2*AxW] <= ax_q[AxW +: 2*AxW];
    end
  end

  logic [W-1:0] ax_org, ax_dir, ax_lo, ax_hi;
  assign {ax_org, ax_dir, ax_lo, ax_hi} = ax_q[0 +: AxW];

  // The divider's operand (the next axis' dir) from a kept register of its own, with ax_q's
  // next value, so the divider's first slot starts beside it instead of at ax_q, which the
  // feeder's data, the shift and the subtracters' operands also pull (run 61 seed 4: ax_q ->
  // u_div.st_in, -0.75 ns).
  logic [W-1:0] div_dir_d, div_dir_q;
  assign div_dir_d = in_free_q ? ax_in[2*W +: W] : issue ? ax_q[AxW + 2*W +: W] : ax_dir;
  rc_reg_copies #(
    .Width (W),
    .Copies(1)
  ) u_div_dir (
    .clk_i,
    .rst_ni,
    .d_i (div_dir_d),
    .q_o (div_dir_q)
  );

  //////////////////////////////////////////////////
  // Slice 1: inv = 1 / dir, lo - org, hi - org   //
  //////////////////////////////////////////////////

  logic         div_valid, sub_lo_valid, sub_hi_valid;
  logic [W-1:0] inv, dlo, dhi;

  rc_fp_div #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(DivStages)
  ) u_div (
    .clk_i,
    .rst_ni,
    .valid_i(issue),
    .a_i    (One),
    .b_i    (div_dir_q),
    .valid_o(div_valid),
    .res_o  (inv)
  );

  // The subtracts need fewer cycles than the divide they run beside, so the first of their
  // SubStages is a register of their operands (sub_in_q, no enable): their first segment (unpack,
  // magnitude compare, operand order) starts at a register beside them instead of at ax_q, which
  // the feeder's data also pull (runs 49 and 51: ax_q -> the subtracters' cut K1, up to -1.44 ns).
  logic [3*W-1:0] sub_in_q;
  logic           sub_issue_q;
  logic [W-1:0]   sub_lo_a, sub_hi_a, sub_org_b;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sub_issue_q <= 1'b0;
    end else begin
      sub_issue_q <= issue;
    end
  end
  always_ff @(posedge clk_i) begin
    sub_in_q <= {ax_lo, ax_hi, ax_org};
  end
  assign {sub_lo_a, sub_hi_a, sub_org_b} = sub_in_q;

  rc_fp_add #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(SubStages - 1)
  ) u_sub_lo (
    .clk_i,
    .rst_ni,
    .valid_i(sub_issue_q),
    .sub_i  (1'b1),
    .a_i    (sub_lo_a),
    .b_i    (sub_org_b),
    .valid_o(sub_lo_valid),
    .res_o  (dlo)
  );

  rc_fp_add #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(SubStages - 1)
  ) u_sub_hi (
    .clk_i,
    .rst_ni,
    .valid_i(sub_issue_q),
    .sub_i  (1'b1),
    .a_i    (sub_hi_a),
    .b_i    (sub_org_b),
    .valid_o(sub_hi_valid),
    .res_o  (dhi)
  );

  // Beside the slice to the chain: the axis flags (control: reset) and the ray's tag.
  logic [ChainDly*3-1:0]    flag_q;  // {valid, first, last} per cycle
  logic [ChainDly*XTagW-1:0] side_tag_q;
  logic                      ch_valid_side, ch_first, ch_last;
  logic [XTagW-1:0]          ch_tag;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      flag_q <= '0;
    end else begin
      flag_q <= (flag_q << 3) | (ChainDly*3)'({issue, first, last});
    end
  end
  always_ff @(posedge clk_i) begin
    side_tag_q <= (side_tag_q << XTagW) | (ChainDly*XTagW)'(tag_q);
  end
  assign {ch_valid_side, ch_first, ch_last} = flag_q[ChainDly*3-1 -: 3];
  assign ch_tag = side_tag_q[ChainDly*XTagW-1 -: XTagW];

  // The divider's results, one per cycle, for the FIFO: inv_q[k*W +: W] is the result of k + 1
  // cycles ago.
  logic [InvDly*W-1:0] inv_q;
  always_ff @(posedge clk_i) begin
    inv_q <= (inv_q << W) | (InvDly*W)'(inv);
  end

  ///////////////////////////////////////////////
  // Slice 2: t0 = dlo * inv, t1 = dhi * inv   //
  ///////////////////////////////////////////////

  logic         mul_valid, mul_hi_valid, skip_m;
  logic [W-1:0] t0, t1;

  rc_fp_mul #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(MulStages)
  ) u_mul_lo (
    .clk_i,
    .rst_ni,
    .valid_i(div_valid),
    .a_i    (dlo),
    .b_i    (inv),
    .valid_o(mul_valid),
    .res_o  (t0)
  );

  rc_fp_mul #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(MulStages)
  ) u_mul_hi (
    .clk_i,
    .rst_ni,
    .valid_i(div_valid),
    .a_i    (dhi),
    .b_i    (inv),
    .valid_o(mul_hi_valid),
    .res_o  (t1)
  );

  // t0 or t1 is NaN: the axis does not restrict the ray.
  assign skip_m = is_nan(t0[W-2:0]) | is_nan(t1[W-2:0]);

  /////////////////////////////////////////
  // Slice 3: min(t0, t1), max(t0, t1)   //
  /////////////////////////////////////////

  logic         mm_valid;
  logic [W-1:0] mn, mx;
  logic         unused_mm_lt, unused_mm_le, unused_mm_eq;

  rc_fp_cmp #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(CmpStages)
  ) u_mm (
    .clk_i,
    .rst_ni,
    .valid_i(mul_valid),
    .a_i    (t0),
    .b_i    (t1),
    .valid_o(mm_valid),
    .lt_o   (unused_mm_lt),
    .le_o   (unused_mm_le),
    .eq_o   (unused_mm_eq),
    .min_o  (mn),
    .max_o  (mx)
  );

  // The skip flag beside the min/max compare.
  logic [CmpStages-1:0] skip_mm_q;
  logic                 skip;
  always_ff @(posedge clk_i) begin
    skip_mm_q <= (skip_mm_q << 1) | CmpStages'(skip_m);
  end
  assign skip = skip_mm_q[CmpStages-1];

  ///////////////////////////////////////////////////////////////////
  // The chain: one step per axis, x then y then z, fed back       //
  ///////////////////////////////////////////////////////////////////

  // The step of an axis: tmin = max(tmin, min(t0, t1)), tmax = min(tmax, max(t0, t1)), where the
  // interval entering it is the previous axis' result, which leaves the step's registers in this
  // very cycle, or [+0, +inf] for x. The loop is a two-way select per bit behind a choice made
  // from registered compares (below); the compares are written here (no rc_fp_cmp: its min/max
  // canonicalise, handle NaN and select behind the compare, which on this loop Yosys merged with
  // the restart and the skip into two L6MUX levels per bit: run 57 seed 2, u_mm -> u_step_out,
  // -3.24 ns), and everything else, the
  // restart (x: max(+0, b), min(+inf, b)) and the skip flag (t0 or t1 NaN: the axis does not
  // restrict the ray; y and z keep the interval, x takes [+0, +inf]), is folded beside the loop
  // into the other operand and the select's condition. Neither flag sits in front of the
  // compares' carry chains (run 54 seed 1: the restart flag, -0.13 ns; run 56 seed 2: the skip
  // flag, -0.23 ns). The operands are canonical and never NaN when they count: the interval is
  // built from such words and constants, and min(t0, t1), max(t0, t1) are rc_fp_cmp results,
  // canonical, and NaN only when t0 or t1 is, i.e. when the axis is skipped (FirstOperand_A). So
  // rc_fp_cmp's min/max are the compare below and its select, max(+0, b) is +0 for a b with the
  // sign set (-0, a negative value, -inf) and b otherwise, and min(+inf, b) is b.
  localparam int unsigned KeepW = 1 + XTagW;  // {last, tag}
  logic [W-1:0]  b_max, b_min, max_d, min_d, max_res, min_res;
  logic          take_max, take_min, pick_max, pick_min;
  logic          chain_valid, last_keep;
  logic [XTagW-1:0] tag_keep;

  // The chain's order: rc_fp_cmp's order for min/max, on words that are canonical and not NaN
  // (the step registers' interval, and min(t0, t1), max(t0, t1) of an axis that is not skipped):
  // a below b, with -0 below +0.
  function automatic logic below(logic [W-1:0] a, logic [W-1:0] b);
    if (a[W-1] != b[W-1]) begin
      below = a[W-1];
    end else if (a[W-1]) begin
      below = b[W-2:0] < a[W-2:0];
    end else begin
      below = a[W-2:0] < b[W-2:0];
    end
  endfunction

  // Each step register takes either its own value (a) or the other operand (b): b is formed from
  // registers beside the loop, so behind the choice each bit is a two-way select.
  //   tmin: max(tmin, mn) takes mn when tmin is below it; x takes max(+0, mn), a skipped x +0,
  //         a skipped y or z keeps tmin.
  //   tmax: min(tmax, mx) takes mx unless tmax is below it; x takes mx, a skipped x +inf, a
  //         skipped y or z keeps tmax.
  // The compares are made a cycle ahead, off the loop (run 64 seeds 1 and 2: the loop's compare
  // and select, u_step_out -> u_step_out, -0.71 ns): in the step of axis k, the next axis' t0
  // and t1 are at u_mm's input, and the interval the next step will find is one of two values
  // known now, this step's b (if it picks) or the step registers' value (if it keeps). On the
  // chain's operands (canonical, never NaN when they count: FirstOperand_A, MulOperand_A)
  // min(t0, t1) is above a exactly when t0 and t1 both are, and max(t0, t1) is not above a
  // exactly when neither is. So both candidates are compared with t0 and t1 here, registered,
  // and the next step's choice selects by this step's pick: the loop is a select of registered
  // flags and the data select. A step whose axis is x, or skipped, does not read them.
  logic nx_max_b, nx_max_a, nx_min_b, nx_min_a;  // the next step's takes, this step picking b / a
  logic nx_max_b_q, nx_max_a_q, nx_min_b_q, nx_min_a_q, pick_max_q, pick_min_q;
  // b_max and b_min are a restart's constant or mn / mx: the compares are made with both and the
  // flags select after them, so the chain's first flag is not in front of the compares' carry
  // chains (run 71 seed 2: flag_q -> nx_min_b_q, 19 cells, -0.33 ns).
  logic b_max_zero, b_min_inf;
  assign b_max_zero = ch_first & (skip | mn[W-1]);
  assign b_min_inf  = ch_first & skip;
  assign nx_max_b = b_max_zero ? below('0, t0) & below('0, t1) : below(mn, t0) & below(mn, t1);
  assign nx_max_a = below(max_res, t0) & below(max_res, t1);
  assign nx_min_b = b_min_inf ? ~below(PosInf, t0) & ~below(PosInf, t1) :
                                ~below(mx, t0) & ~below(mx, t1);
  assign nx_min_a = ~below(min_res, t0) & ~below(min_res, t1);
  always_ff @(posedge clk_i) begin
    nx_max_b_q <= nx_max_b;
    nx_max_a_q <= nx_max_a;
    nx_min_b_q <= nx_min_b;
    nx_min_a_q <= nx_min_a;
    pick_max_q <= pick_max;
    pick_min_q <= pick_min;
  end
  assign take_max = pick_max_q ? nx_max_b_q : nx_max_a_q;
  assign take_min = pick_min_q ? nx_min_b_q : nx_min_a_q;
  assign pick_max = ch_first | (~skip & take_max);
  assign pick_min = ch_first | (~skip & take_min);
  assign b_max    = {W{~b_max_zero}} & mn;  // +0 is all zeros
  assign b_min    = ({W{~b_min_inf}} & mx) | ({W{b_min_inf}} & PosInf);
  assign max_d    = ({W{pick_max}} & b_max) | ({W{~pick_max}} & max_res);
  assign min_d    = ({W{pick_min}} & b_min) | ({W{~pick_min}} & min_res);

  // The step's registers: CmpStages, as the compares' own would be.
  rc_pipe_out #(
    .Width   (2 * W),
    .DataRegs(CmpStages),
    .Stages  (CmpStages)
  ) u_step_out (
    .clk_i,
    .rst_ni,
    .valid_i(mm_valid),
    .data_i ({max_d, min_d}),
    .valid_o(chain_valid),
    .data_o ({max_res, min_res})
  );

  // The last-axis flag and the tag beside the compares.
  logic [CmpStages*KeepW-1:0] keep_q;
  always_ff @(posedge clk_i) begin
    keep_q <= (keep_q << KeepW) | (CmpStages*KeepW)'({ch_last, ch_tag});
  end
  assign {last_keep, tag_keep} = keep_q[CmpStages*KeepW-1 -: KeepW];

  //////////////////////////////////////////////////////
  // active = le(tmin, tmax), after the step of z     //
  //////////////////////////////////////////////////////

  logic         le_valid, active;
  logic         unused_le_lt, unused_le_eq;
  logic [W-1:0] unused_le_min, unused_le_max;

  rc_fp_cmp #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Stages(CmpStages)
  ) u_le (
    .clk_i,
    .rst_ni,
    .valid_i(chain_valid & last_keep),
    .a_i    (max_res),
    .b_i    (min_res),
    .valid_o(le_valid),
    .lt_o   (unused_le_lt),
    .le_o   (active),
    .eq_o   (unused_le_eq),
    .min_o  (unused_le_min),
    .max_o  (unused_le_max)
  );

  localparam int unsigned FinW = 2 * W + TagW;  // {tmin, tmax, tag}
  logic [CmpStages*FinW-1:0] fin_q;
  logic [W-1:0]              tmin_f, tmax_f, tmax_out;
  logic [TagW-1:0]           tag_f;
  logic                      active_out;
  always_ff @(posedge clk_i) begin
    fin_q <= (fin_q << FinW) | (CmpStages*FinW)'({max_res, min_res, tag_keep[TagW-1:0]});
  end
  assign {tmin_f, tmax_f, tag_f} = fin_q[CmpStages*FinW-1 -: FinW];

  // The limit: min(tmax, tlim) and le(tmin, tlim), beside le(tmin, tmax).
  if (Limit) begin : g_limit
    logic [W-1:0] tlim_keep, unused_lim_min, unused_lim_max, unused_clip_max;
    logic         lim_le, unused_lim_lt, unused_lim_eq, unused_clip_lt, unused_clip_le;
    logic         unused_clip_eq, unused_lim_valid, unused_clip_valid;
    assign tlim_keep = tag_keep[TagW +: W];
    rc_fp_cmp #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(CmpStages)
    ) u_lim_le (
      .clk_i,
      .rst_ni,
      .valid_i(chain_valid & last_keep),
      .a_i    (max_res),
      .b_i    (tlim_keep),
      .valid_o(unused_lim_valid),
      .lt_o   (unused_lim_lt),
      .le_o   (lim_le),
      .eq_o   (unused_lim_eq),
      .min_o  (unused_lim_min),
      .max_o  (unused_lim_max)
    );
    rc_fp_cmp #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(CmpStages)
    ) u_clip (
      .clk_i,
      .rst_ni,
      .valid_i(chain_valid & last_keep),
      .a_i    (min_res),
      .b_i    (tlim_keep),
      .valid_o(unused_clip_valid),
      .lt_o   (unused_clip_lt),
      .le_o   (unused_clip_le),
      .eq_o   (unused_clip_eq),
      .min_o  (tmax_out),
      .max_o  (unused_clip_max)
    );
    assign active_out = active & lim_le;
    logic unused_tmax_f;  // the chain's tmax before the limit: only its assertion reads it
    assign unused_tmax_f = ^tmax_f;
  end else begin : g_no_limit
    assign tmax_out   = tmax_f;
    assign active_out = active;
  end

  // inv of x, y, z: the divider's results of InvDly, InvDly - AxisGap and InvDly - 2 AxisGap
  // cycles before the FIFO write.
  logic [3*W-1:0] inv_f;
  for (genvar a = 0; a < 3; a++) begin : g_inv_f
    assign inv_f[a*W +: W] = inv_q[(InvDly-a*AxisGap)*W-1 -: W];
  end

  /////////////////////////////
  // Output FIFO and credits //
  /////////////////////////////

  rc_credit_fifo #(
    .Width   (OutW),
    .Depth   (FifoDepth),
    .MemArray(1'b1)
  ) u_fifo (
    .clk_i,
    .rst_ni,
    .take_i    (take),
    .credit_o  (credit),
    .wr_valid_i(le_valid),
    .wr_data_i ({tag_f, inv_f, tmin_f, tmax_out, active_out}),
    .valid_o,
    .ready_i,
    .data_o    ({tag_o, inv_o, tmin_o, tmax_o, active_o})
  );

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

  // The divider's operand register holds the next axis' dir whenever an axis enters.
  DivDir_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             issue |-> div_dir_q == ax_dir);
  // The divider and the subtracts are aligned (same Stages), so their results meet.
  SubDivAligned_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    div_valid == sub_lo_valid && div_valid == sub_hi_valid);
  // Both multipliers, and the flags beside the slice, run in lock step with the axis stream.
  SliceLockStep_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    mul_valid == mul_hi_valid && mm_valid == ch_valid_side);
  // A ray's axes reach the chain AxisGap cycles apart, x first: an axis other than x finds the
  // previous axis of its own ray just out of the step registers, and x finds none in flight.
  ChainOrder_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 mm_valid |-> (ch_first ? !(chain_valid && !last_keep)
                                                        : chain_valid && !last_keep));
  // An axis that is not skipped gives the chain operands that are never NaN and canonical (a
  // zero exponent with a zero fraction), so the restart's max(+0, b) and min(+inf, b) are the
  // selects above.
  FirstOperand_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   mm_valid && !skip |-> !is_nan(mn[W-2:0]) &&
                                                         !is_nan(mx[W-2:0]) &&
                                                         (|mn[W-2 -: ExpW] || ~|mn[FracW-1:0]) &&
                                                         (|mx[W-2 -: ExpW] || ~|mx[FracW-1:0]));
  // The multipliers' results are canonical when not NaN, so the compares made a cycle ahead on t0
  // and t1 order them as u_mm does.
  MulOperand_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 mul_valid && !skip_m |-> (|t0[W-2 -: ExpW] || ~|t0[FracW-1:0]) &&
                                                          (|t1[W-2 -: ExpW] || ~|t1[FracW-1:0]));
  // The takes made a cycle ahead are the compares of the step registers with min(t0, t1) and
  // max(t0, t1) wherever a step reads them (an axis other than x, not skipped).
  TakeAhead_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                mm_valid && !ch_first && !skip |->
                                    take_max == below(max_res, mn) &&
                                    take_min == !below(min_res, mx));
  // tmin starts at +0 and only grows through non-NaN values, so it is never NaN.
  TminNotNan_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 le_valid |-> !is_nan(tmin_f[W-2:0]) && !is_nan(tmax_f[W-2:0]));
  // in_free_q is the input register's freedom as its slot counter says.
  InFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             in_free_q == (~|slot_q | slot_q[Interval-1]));
  // ready_o must be known once out of reset (upstream acts on it).
  ReadyKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !$isunknown(ready_o));
`endif

endmodule
