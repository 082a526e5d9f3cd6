// rc_light_term: one light as seen from one hit (docs/architecture.md, "Lighting"): the shadow
// ray's direction and limit, whether the light is in front of the surface, the light's terms
// and the hit's ambient terms, in the lighting's fixed point.
//
// Contract
// - Function: exactly rc::light_sample() and rc::ambient_terms() (tb/golden/trace.hpp), bit for
//   bit. Vector ports hold component or channel a at [a*W +: W] (W = 1 + ExpW + FracW), the
//   fixed-point ports channel c at [c*(F+1) +: F+1] (F = FixBits).
//     point light (dir_light_i = 0), L = lpos_i - p_i:
//       dist2 = (L.x*L.x + L.y*L.y) + L.z*L.z,  inv = 1 / sqrt(dist2)
//       lh_o[a] = L[a] * inv,  t_hi_o = dist2 * inv
//     directional light: lh_o = lpos_i (the unit vector toward it), t_hi_o = +inf
//     cos = (n.x*lh.x + n.y*lh.y) + n.z*lh.z,  present_o = lt(0, cos)
//     H[a] = lh[a] - v_i[a],  nh = ((n.H sums as for cos)) * (1 / sqrt(H.H))
//     spec = lt(0, nh) ? pow(nh, ns_i) : +0     (square and multiply, low bit first, ExpBits
//                                                 bits: r = 1, b = nh; per bit: r = r * b if
//                                                 set, then b = b * b)
//     term_o[c] = present_o ? fix(((kd_i[c] * cos + ks_i[c] * spec) * lcol_i[c]) * w_i) : 0
//     amb_o[c]  = fix((kd_i[c] * ambient_i) * w_i)
//   with fix() of rc_fp_to_fix. Every operation is the format's (rc_fp_mul, rc_fp_add,
//   rc_fp_sqrt, rc_fp_div), in this order and with these operands.
// - Structure: component-serial, as rc_hit_geom: a taken job waits three cycles in an input
//   register while its x, y and z (or red, green and blue) enter the vector operations one a
//   cycle; every vector value then travels as a stream of three consecutive components, every
//   scalar as one value at a fixed cycle after the job's first (the Time* constants below). A
//   scalar that a vector operation needs (inv, cos, spec) is held for its stream's three cycles by
//   a register loaded in the first. A dot product (dist2, cos, H.H, N.H) takes a stream's
//   products, then x + y as y's leaves, then + z as x + y leaves (z's product La - 1 cycles
//   later; H.H's x + y and cos's + z a cycle later still: WaitXyH, WaitZC below). The power is
//   ExpBits steps of Lm cycles, each taking b * b and then r * b in consecutive cycles (the next
//   b * b as this one leaves). Jobs are taken at phase 0 modulo Period, a multiple of 6
//   (rc_serial_sched, Phased), so operations whose cycles fall at different phases share an
//   operator and no two jobs meet there. Modulo 3: one square root and one divider serve both
//   1 / sqrt(dist2) and 1 / sqrt(H.H) (H.H enters a cycle after its sum): pipelined at Period 6,
//   iterative with two lanes at 12 (rc_fp_sqrt_iter, rc_fp_div_iter; the same results and
//   latencies). Every product (the streams L * L, L * inv, kd * ambient, ka * w, kd * cos,
//   ks * spec, sum * lcol and its * w, N * lh, H * H and N * H; the scalars dist and nh; the
//   power's steps) is a user of one pool of multipliers (rc_fp_pool), which places each on the
//   first multiplier whose users' phases modulo Period it does not meet: 10 multipliers at
//   Period 6, 5 at 12. Every sum (the streams L = lpos - p, H = lh - v and kd cos + ks spec; the
//   dot products' x + y and + z) is a user of one pool of adders: 4 at Period 6, 2 at 12. (The
//   ambient term and the cos and N.H dot products start later than their operands allow, off the
//   path to the output, for those counts: ShiftA, ShiftC, ShiftN, WaitZC below.) Each pool has
//   an input register before every operator (rc_fp_pool InReg), so an operand's select and the
//   operator's first stage are in different cycles: a product takes Lm = [fp_stages] mul + 1
//   cycles, a sum La = add + 1. The fixed-point conversions are rc_fp_to_fix at two stages
//   (Lf = 2: the shift, then the rounding).
//   Values wait for their operations in rc_delay lines (short) and rc_delay_ram memories (long),
//   so a job may follow another after Period cycles or after any gap (rc_serial_sched keeps the
//   slots and the job times). The last stage collects each stream's three components into the
//   output FIFO.
// - Handshake: valid_i/ready_o in, valid_o/ready_i out, with backpressure, as rc_hit_geom (ready_o
//   is the AND of two flip-flops; valid_o never depends on ready_i; results leave in order;
//   tag_i travels with the operation to tag_o).
// - Latency: TimeOut + 2 cycles from the taking cycle to valid_o when the FIFO is empty and
//   ready_i is 1 (187 at the default fp_stages: mul 4, add 6, sqrt 10, div 11, so Lm = 5 and
//   La = 7, and ExpBits 10): input register 1, then the chain L (La), L.L (Lm, 1, 2 La), sqrt
//   (10), 1 / sqrt (11), lh (Lm), H (La), H.H (Lm, 2, 2 La), 1 into the root, sqrt, 1 / sqrt, nh
//   (Lm), the power (ExpBits Lm + 1), ks * spec (Lm), kd cos + ks spec (La), * lcol, * w (2 Lm),
//   fix (Lf) (TimeFix = 183 after slot 0), two cycles for the stream's y and z, the FIFO's output
//   register 1.
// - Throughput: one job per Period cycles while ready_i is 1; ready_o is high only in cycles
//   whose phase modulo Period lets a job start at phase 0, so a job offered after a gap may wait
//   up to Period - 1 cycles. The FIFO holds Latency / Period + 2 entries.
// - Parameters: ExpW, FracW: the number format (default fp24); TagW: tag bits (>= 1); FixBits:
//   the fixed point's fraction bits (docs/spec.toml [light] fixed_bits); ExpBits: the exponent's
//   bits ([light] exponent_bits); Period: the cycles between two jobs, 6 or 12 ([light]
//   unit_period, or [board] lit_light_period on the lit board, as rc_hit_geom's; checked at
//   elaboration: the operators shared modulo 3 and 6 need a multiple of 6, and the schedule is
//   tested at these two).
// - Illegal input: none; every bit pattern of the data inputs is legal.
// - Reset: rst_ni (active low, asynchronous) clears control state only (the slot counter, the
//   stream-start chain, the delay memories' pointers, the FIFO's pointers and credit count).
module rc_light_term #(
  parameter int unsigned ExpW    = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW   = rc_pkg::Fp24FracW,
  parameter int unsigned TagW    = 8,
  parameter int unsigned FixBits = rc_pkg::LightFixedBits,
  parameter int unsigned ExpBits = rc_pkg::LightExponentBits,
  parameter int unsigned Period  = rc_pkg::LightUnitPeriod
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  input  logic [ExpW+FracW:0]         ambient_i,    // ambient as a format value (a constant)
  // Input handshake.
  input  logic                        valid_i,
  output logic                        ready_o,
  input  logic [TagW-1:0]             tag_i,
  input  logic [3*(ExpW+FracW+1)-1:0] p_i,          // the hit point
  input  logic [3*(ExpW+FracW+1)-1:0] n_i,          // the facing unit normal
  input  logic [3*(ExpW+FracW+1)-1:0] v_i,          // the unit view direction
  input  logic                        dir_light_i,  // a directional light
  input  logic [3*(ExpW+FracW+1)-1:0] lpos_i,       // its position, or the vector toward it
  input  logic [3*(ExpW+FracW+1)-1:0] lcol_i,       // its colour x intensity
  input  logic [3*(ExpW+FracW+1)-1:0] kd_i,
  input  logic [3*(ExpW+FracW+1)-1:0] ks_i,
  input  logic [ExpBits-1:0]          ns_i,         // the material's integer exponent
  input  logic [ExpW+FracW:0]         w_i,          // the ray's weight
  // Output handshake.
  output logic                        valid_o,
  input  logic                        ready_i,
  output logic [TagW-1:0]             tag_o,
  output logic                        present_o,
  output logic [3*(ExpW+FracW+1)-1:0] lh_o,
  output logic [ExpW+FracW:0]         t_hi_o,
  output logic [3*(FixBits+1)-1:0]    term_o,
  output logic [3*(FixBits+1)-1:0]    amb_o
);

  localparam int unsigned W  = ExpW + FracW + 1;
  localparam int unsigned FW = FixBits + 1;
  // Every product and sum is an operation of a pool (rc_fp_pool, InReg): the pool's input
  // register, then the operator, so its latency is the operator's ([fp_stages]) plus one.
  localparam int unsigned Lm = rc_pkg::FpStagesMul + 1;
  localparam int unsigned La = rc_pkg::FpStagesAdd + 1;
  localparam int unsigned Ls = rc_pkg::FpStagesSqrt;
  localparam int unsigned Ld = rc_pkg::FpStagesDiv;
  localparam int unsigned Lf = 2;  // rc_fp_to_fix's Stages (its shift, then its rounding)

  // Off the path to the output, three things start later than their operands allow, where the
  // pools need fewer operators: the ambient term's two products ShiftA cycles, the cos dot
  // product's stream ShiftC and the N.H dot product's ShiftN; and cos's + z waits WaitZC cycles
  // after its x + y leaves. On the path, H.H's x + y waits WaitXyH cycles after its y's product
  // leaves (a cycle of latency, which also puts H.H's turn at the shared root at another phase
  // modulo 3 than dist2's). At the default fp stages these take 5 multipliers and 2 adders at
  // Period 12 and 10 and 4 at 6, as a search over them found (as soon as the operands are there:
  // 11 and 4, 19 and 5, with the root's phases clashing; their results then wait).
  localparam int unsigned ShiftA   = 1;
  localparam int unsigned ShiftC   = 2;
  localparam int unsigned ShiftN   = 2;
  localparam int unsigned WaitZC   = 1;
  localparam int unsigned WaitXyH  = 1;
  // The cycle (after slot 0) at which each value, or a stream's x, leaves its operation.
  localparam int unsigned TimeL    = La;                      // L = lpos - p
  localparam int unsigned TimeLl   = TimeL + Lm;              // L * L
  localparam int unsigned TimeD01  = TimeLl + 1 + La;         // L.x^2 + L.y^2
  localparam int unsigned TimeD2   = TimeD01 + La;            // dist2
  localparam int unsigned TimeSq1  = TimeD2 + Ls;             // sqrt(dist2)
  localparam int unsigned TimeInv  = TimeSq1 + Ld;            // 1 / sqrt(dist2)
  localparam int unsigned TimeLh   = TimeInv + Lm;            // lh, dist
  localparam int unsigned TimeH    = TimeLh + La;             // H = lh - v
  // The dot products N.lh (cos), H.H and N.H: their streams of products are issued at TimeDc,
  // TimeDh and TimeDn, their x + y at TimeXy* (y's product leaving, plus a wait) and their + z at
  // TimeZ* (x + y leaving, plus a wait); each sum leaves La cycles after its issue.
  localparam int unsigned TimeDc   = TimeLh + 2 + ShiftC;
  localparam int unsigned TimeDh   = TimeH;
  localparam int unsigned TimeDn   = TimeH + 1 + ShiftN;
  localparam int unsigned TimeXyC  = TimeDc + Lm + 1;
  localparam int unsigned TimeXyH  = TimeDh + Lm + 1 + WaitXyH;
  localparam int unsigned TimeXyN  = TimeDn + Lm + 1;
  localparam int unsigned TimeZC   = TimeXyC + La + WaitZC;
  localparam int unsigned TimeZH   = TimeXyH + La;
  localparam int unsigned TimeZN   = TimeXyN + La;
  localparam int unsigned TimeCos  = TimeZC + La;             // cos = N.lh
  localparam int unsigned TimeHh   = TimeZH + La;             // H.H
  localparam int unsigned TimeNhd  = TimeZN + La;             // N.H
  localparam int unsigned TimeHs   = TimeHh + 1;              // H.H into the shared root
  localparam int unsigned TimeIh   = TimeHs + Ls + Ld;        // 1 / sqrt(H.H)
  localparam int unsigned TimeNh   = TimeIh + Lm;             // nh
  localparam int unsigned PowStep  = Lm;
  localparam int unsigned TimeSpec = TimeNh + ExpBits * PowStep + 1;
  localparam int unsigned TimeSum  = TimeSpec + Lm + La;      // kd cos + ks spec
  localparam int unsigned TimeX    = TimeSum + 2 * Lm;        // (...) * lcol * w
  localparam int unsigned TimeFix  = TimeX + Lf;
  localparam int unsigned TimeKa   = ShiftA;                  // kd * ambient issued
  localparam int unsigned TimeAw   = TimeKa + Lm;             // (kd * ambient) * w issued
  localparam int unsigned TimeOut  = TimeFix + 2;
  localparam int unsigned Latency  = TimeOut + 2;
  localparam int unsigned FifoDepth = Latency / Period + 2;
  localparam int unsigned OutW = TagW + 1 + 3 * W + W + 6 * FW;

  localparam logic [W-1:0] One     = {1'b0, 1'b0, {(ExpW - 1) {1'b1}}, {FracW{1'b0}}};
  localparam logic [W-1:0] PosInf  = {1'b0, {ExpW{1'b1}}, {FracW{1'b0}}};
  localparam logic [W-1:0] PosZero = '0;

  if (TagW < 1 || ExpBits < 1) begin : g_param_check
    $error("rc_light_term: TagW and ExpBits must be at least 1");
  end
  // The periods its schedule is tested at (rc_fp_pool would place the products at any period,
  // but the phases of the operators it shares modulo 3 and 6 are checked for these two only).
  if (Period != 6 && Period != 12) begin : g_period_check
    $error("rc_light_term: Period must be 6 or 12");
  end
  // The shared root's and divider's two users must come at different phases (see "cos = N.lh").
  if (TimeD2 % 3 == TimeHs % 3) begin : g_phase_check
    $error("rc_light_term: the shared operators' users must come at different phases");
  end

  // lt(+0, x): x is positive, not zero (an exponent field of 0 reads as zero) and not NaN.
  function automatic logic pos(input logic [W-1:0] x);
    pos = ~x[W-1] & (|x[W-2 -: ExpW]) & ~((&x[W-2 -: ExpW]) & (|x[FracW-1:0]));
  endfunction

  ////////////////////////////////////////////
  // Input register, slots, stream starts   //
  ////////////////////////////////////////////

  logic [2:0] slot_q;
  logic       in_free_q, take, credit;

  assign ready_o = credit & in_free_q;
  assign take    = valid_i & ready_o;

  // The input register loads in every cycle the unit is ready, taken or not: the job before no
  // longer needs it then (a take would overwrite it too), so the enable is ready_o's two
  // flip-flops, not valid_i's net.
  logic [TagW-1:0]    tag_q;
  logic [3*W-1:0]     p_q, n_q, v_q, lpos_q, lcol_q, kd_q, ks_q;
  logic [ExpBits-1:0] ns_q;
  logic [W-1:0]       w_q;
  logic               dirl_q;

  always_ff @(posedge clk_i) begin
    if (ready_o) begin
      tag_q  <= tag_i;
      p_q    <= p_i;
      n_q    <= n_i;
      v_q    <= v_i;
      lpos_q <= lpos_i;
      lcol_q <= lcol_i;
      kd_q   <= kd_i;
      ks_q   <= ks_i;
      ns_q   <= ns_i;
      w_q    <= w_i;
      dirl_q <= dir_light_i;
    end
  end

  // at[T]: a job is at time T (cycles after its slot 0); strm[T]: a stream issued at T is busy
  // (rc_serial_sched).
  logic [TimeOut:0]   at;
  logic [TimeOut-2:0] strm;
  rc_serial_sched #(.Time(TimeOut), .Phased(1'b1), .Period(Period)) u_sched (
    .clk_i, .rst_ni, .take_i(take), .slot_o(slot_q), .in_free_o(in_free_q), .at_o(at),
    .strm_o(strm)
  );

  // The components (channels) entering in this slot.
  logic [W-1:0] p_s, n_s, v_s, lp_s, lc_s, kd_s, ks_s;
  always_comb begin
    p_s  = p_q[0 +: W];
    n_s  = n_q[0 +: W];
    v_s  = v_q[0 +: W];
    lp_s = lpos_q[0 +: W];
    lc_s = lcol_q[0 +: W];
    kd_s = kd_q[0 +: W];
    ks_s = ks_q[0 +: W];
    for (int unsigned k = 1; k < 3; k++) begin
      if (slot_q[k]) begin
        p_s  = p_q[k*W +: W];
        n_s  = n_q[k*W +: W];
        v_s  = v_q[k*W +: W];
        lp_s = lpos_q[k*W +: W];
        lc_s = lcol_q[k*W +: W];
        kd_s = kd_q[k*W +: W];
        ks_s = ks_q[k*W +: W];
      end
    end
  end

  // Scalars held for their stream's three cycles.
  logic [W-1:0] inv_res, inv_hold_q, inv_b;
  logic [W-1:0] cos_res, cos_hold_q, cos_b;
  logic [W-1:0] spec_v, spec_hold_q, spec_b;
  logic         pres_hold_q, pres_b;

  assign inv_b  = at[TimeInv] ? inv_res : inv_hold_q;
  assign cos_b  = at[TimeCos] ? cos_res : cos_hold_q;
  assign spec_b = at[TimeSpec] ? spec_v : spec_hold_q;
  assign pres_b = at[TimeCos] ? pos(cos_res) : pres_hold_q;

  always_ff @(posedge clk_i) begin
    if (at[TimeInv]) inv_hold_q <= inv_res;
    if (at[TimeCos]) cos_hold_q <= cos_res;
    if (at[TimeSpec]) spec_hold_q <= spec_v;
    if (at[TimeCos]) pres_hold_q <= pos(cos_res);
  end

  //////////////////////////////////////////////////////////
  // Toward the light: L, dist2, inv, lh, dist                //
  //////////////////////////////////////////////////////////

  logic [W-1:0] l_s, dist2, l_at_inv, d2_at_inv, lh_pt, dist_res;
  logic [W-1:0] ll, ll_d1, ll_dz, d01;

  // L = lpos - p: in u_adds (below), as the unit's other sums.
  // dist2 = (L.x L.x + L.y L.y) + L.z L.z, as every dot product: x + y as y's product leaves (at
  // TimeLl + 1), then + z (at TimeD01), both in u_adds.
  // L * L: in u_muls (below), as the unit's other products.
  rc_delay #(.Width(W), .Cycles(1)) u_dly_llx (.clk_i, .data_i(ll), .data_o(ll_d1));
  rc_delay #(.Width(W), .Cycles(La - 1)) u_dly_llz (.clk_i, .data_i(ll), .data_o(ll_dz));
  rc_delay_ram #(.Width(W), .Cycles(TimeInv - TimeL)) u_dly_l (
    .clk_i, .rst_ni, .data_i(l_s), .data_o(l_at_inv)
  );
  // lh = L * inv: in u_muls.
  rc_delay_ram #(.Width(W), .Cycles(TimeInv - TimeD2)) u_dly_d2 (
    .clk_i, .rst_ni, .data_i(dist2), .data_o(d2_at_inv)
  );
  // dist = dist2 * inv: in u_muls (below).

  // A directional light: its vector and +inf instead (the light's kind and vector wait here).
  logic [W-1:0] lp_at_lh, lh_s, thi_s;
  logic         dirl_at_lh;
  rc_delay_ram #(.Width(W + 1), .Cycles(TimeLh)) u_dly_lp (
    .clk_i, .rst_ni, .data_i({dirl_q, lp_s}), .data_o({dirl_at_lh, lp_at_lh})
  );
  assign lh_s  = dirl_at_lh ? lp_at_lh : lh_pt;
  assign thi_s = dirl_at_lh ? PosInf : dist_res;

  //////////////////////////////////////////////////////////
  // cos = N.lh, H = lh - V, N.H, H.H, nh                 //
  //////////////////////////////////////////////////////////

  logic [W-1:0] n_at_lh, v_at_lh, n_at_dn, n_at_lh2, lh_s2;
  rc_delay_ram #(.Width(2 * W), .Cycles(TimeLh)) u_dly_nv (
    .clk_i, .rst_ni, .data_i({n_s, v_s}), .data_o({n_at_lh, v_at_lh})
  );
  rc_delay #(.Width(W), .Cycles(TimeDn - TimeLh)) u_dly_nh (
    .clk_i, .data_i(n_at_lh), .data_o(n_at_dn)
  );
  rc_delay #(.Width(2 * W), .Cycles(TimeDc - TimeLh)) u_dly_nl (
    .clk_i, .data_i({n_at_lh, lh_s}), .data_o({n_at_lh2, lh_s2})
  );

  logic [W-1:0] h_s, h_at_dn, hsum, nhd, ih, nhd_d;
  logic [W-1:0] nh;
  // H = lh - v: in u_adds.
  rc_delay #(.Width(W), .Cycles(TimeDn - TimeH)) u_dly_h1 (
    .clk_i, .data_i(h_s), .data_o(h_at_dn)
  );
  // cos = N.lh, H.H and N.H, each (x + y) + z as every dot product: the stream's products in
  // u_muls, x + y as y's product leaves (x's a cycle later) and + z as x + y leaves (z's product
  // La - 1 cycles later), both in u_adds; H.H's x + y WaitXyH cycles later (x's and y's products
  // wait) and cos's + z WaitZC (x + y and z's product wait). N.lh's stream is issued
  // 2 + ShiftC cycles late (TimeDc), H.H's on time (TimeDh), N.H's 1 + ShiftN late (TimeDn): cos
  // leaves at TimeCos, H.H at TimeHh, N.H at TimeNhd. (The first offsets, 2 and 1, once kept
  // the three sums apart modulo 3 in two adders of their own; the shifts are the pools', above.)
  logic [3*W-1:0] dp, dp_dx, dp_dy, dp_dz, dxy, dxy_d, dz;  // per dot product (cos, H.H, N.H)
  for (genvar k = 0; k < 3; k++) begin : g_dot
    localparam int unsigned WaitXy = (k == 1) ? WaitXyH : 0;
    localparam int unsigned WaitZ  = (k == 0) ? WaitZC : 0;
    rc_delay #(.Width(W), .Cycles(1 + WaitXy)) u_dly_x (
      .clk_i, .data_i(dp[k*W +: W]), .data_o(dp_dx[k*W +: W])
    );
    rc_delay #(.Width(W), .Cycles(WaitXy)) u_dly_y (
      .clk_i, .data_i(dp[k*W +: W]), .data_o(dp_dy[k*W +: W])
    );
    rc_delay #(.Width(W), .Cycles(La - 1 + WaitXy + WaitZ)) u_dly_z (
      .clk_i, .data_i(dp[k*W +: W]), .data_o(dp_dz[k*W +: W])
    );
    rc_delay #(.Width(W), .Cycles(WaitZ)) u_dly_xy (
      .clk_i, .data_i(dxy[k*W +: W]), .data_o(dxy_d[k*W +: W])
    );
  end
  assign cos_res = dz[0 +: W];
  assign hsum    = dz[W +: W];
  assign nhd     = dz[2*W +: W];
  // One square root and one divider make both 1 / sqrt(dist2) (into the root at TimeD2) and
  // 1 / sqrt(H.H) (at TimeHs, a cycle after the sum): the two times differ modulo 3 and every
  // job's slot 0 is at phase 0 (rc_serial_sched, Phased), so no two jobs bring them to the
  // root, or their roots to the divider, in one cycle. Each user reads the shared result at its
  // own time (TimeInv, TimeIh).
  logic [W-1:0] hsum_d1, rt_a, rt, rinv;
  logic         rt_vld, rinv_vld;
  rc_delay #(.Width(W), .Cycles(1)) u_dly_hs (.clk_i, .data_i(hsum), .data_o(hsum_d1));
  assign rt_a = at[TimeD2] ? dist2 : hsum_d1;
  // At a job per 12 cycles the two users bring at most two operations into any 12 cycles (one
  // at each user's phase), so an iterative root and divider with two lanes serve them
  // (rc_fp_sqrt_iter, rc_fp_div_iter: a lane is busy 8 and 9 cycles); at 6 they are pipelined.
  if (Period >= 12) begin : g_iter
    rc_fp_sqrt_iter #(.ExpW(ExpW), .FracW(FracW), .Stages(Ls), .Lanes(2)) u_sqrt (
      .clk_i, .rst_ni, .valid_i(at[TimeD2] | at[TimeHs]), .a_i(rt_a), .valid_o(rt_vld),
      .res_o(rt)
    );
    rc_fp_div_iter #(.ExpW(ExpW), .FracW(FracW), .Stages(Ld), .Lanes(2)) u_div (
      .clk_i, .rst_ni, .valid_i(at[TimeSq1] | at[TimeHs + Ls]), .a_i(One), .b_i(rt),
      .valid_o(rinv_vld), .res_o(rinv)
    );
  end else begin : g_pipe
    rc_fp_sqrt #(.ExpW(ExpW), .FracW(FracW), .Stages(Ls)) u_sqrt (
      .clk_i, .rst_ni, .valid_i(at[TimeD2] | at[TimeHs]), .a_i(rt_a), .valid_o(rt_vld),
      .res_o(rt)
    );
    rc_fp_div #(.ExpW(ExpW), .FracW(FracW), .Stages(Ld)) u_div (
      .clk_i, .rst_ni, .valid_i(at[TimeSq1] | at[TimeHs + Ls]), .a_i(One), .b_i(rt),
      .valid_o(rinv_vld), .res_o(rinv)
    );
  end
  assign inv_res = rinv;
  assign ih      = rinv;
  rc_delay_ram #(.Width(W), .Cycles(TimeIh - TimeNhd)) u_dly_nhd (
    .clk_i, .rst_ni, .data_i(nhd), .data_o(nhd_d)
  );
  // dist = dist2 * inv (at TimeInv) and nh = N.H * (1 / sqrt(H.H)) (at TimeIh): in u_muls.
  logic [W-1:0] dist_p, nh_p;
  assign dist_res = dist_p;
  assign nh       = nh_p;

  //////////////////////////////////////////////////////////
  // spec = lt(0, nh) ? pow(nh, ns) : +0                  //
  //////////////////////////////////////////////////////////

  // Step i at T_i = TimeNh + i * PowStep (PowStep = Lm): b * b at T_i, r * b at T_i + 1 (u_muls'
  // user 10 + i, two cycles). Word i of b_src holds b_i at T_i (b_0 = nh; b_{i+1} = b_i * b_i
  // leaves at T_i + Lm = T_{i+1}), word i of r_src r_i at T_i + 1 (r_0 = 1; r_{i+1} = r_i * b_i
  // where bit i of ns is set, else r_i, at T_{i+1} + 1), flat: Yosys 0.23 reads no
  // multi-dimensional packed arrays. r_src's word ExpBits is the power at TimeSpec.
  logic [ExpBits*W-1:0]     b_src, b_d1_q, step_a, step_b;
  logic [(ExpBits+1)*W-1:0] r_src;
  logic [ExpBits-1:0]       step_issue;
  logic [ExpBits*W-1:0]     pow_prod;
  logic [ExpBits-1:0]       ns_at_nh;

  rc_delay_ram #(.Width(ExpBits), .Cycles(TimeNh)) u_dly_ns (
    .clk_i, .rst_ni, .data_i(ns_q), .data_o(ns_at_nh)
  );

  assign b_src[0 +: W] = nh;
  assign r_src[0 +: W] = One;

  // b_i for r * b, a cycle after its b * b.
  always_ff @(posedge clk_i) begin
    b_d1_q <= b_src;
  end

  for (genvar i = 0; i < ExpBits; i++) begin : g_pow
    logic [W-1:0] prod, r_keep;
    logic         bit_i;
    assign step_issue[i]     = at[TimeNh + i*PowStep] | at[TimeNh + i*PowStep + 1];
    assign step_a[i*W +: W] = at[TimeNh + i*PowStep + 1] ? r_src[i*W +: W] : b_src[i*W +: W];
    assign step_b[i*W +: W] = at[TimeNh + i*PowStep + 1] ? b_d1_q[i*W +: W] : b_src[i*W +: W];
    assign prod = pow_prod[i*W +: W];
    // r_i waits from T_i + 1 to T_{i+1} + 1, where bit i of ns arrives.
    rc_delay #(.Width(W), .Cycles(PowStep)) u_dly_r (
      .clk_i, .data_i(r_src[i*W +: W]), .data_o(r_keep)
    );
    rc_delay #(.Width(1), .Cycles((i + 1) * PowStep + 1)) u_dly_bit (
      .clk_i, .data_i(ns_at_nh[i]), .data_o(bit_i)
    );
    assign r_src[(i+1)*W +: W] = bit_i ? prod : r_keep;
    // b_{i+1}: the product as it leaves (the last step's is not needed).
    if (i + 1 < ExpBits) begin : g_next_b
      assign b_src[(i+1)*W +: W] = prod;
    end
  end

  logic nh_pos_at_spec;
  rc_delay #(.Width(1), .Cycles(ExpBits * PowStep + 1)) u_dly_nhpos (
    .clk_i, .data_i(pos(nh)), .data_o(nh_pos_at_spec)
  );
  assign spec_v = nh_pos_at_spec ? r_src[ExpBits*W +: W] : PosZero;

  //////////////////////////////////////////////////////////
  // Terms: fix(((kd cos + ks spec) * lcol) * w)           //
  //////////////////////////////////////////////////////////

  logic [W-1:0] kd_at_cos, kdcos, kdcos_d, ks_at_spec, ksspec, sum, lc_at_sum, sl, w_at_sl, x_s;
  rc_delay_ram #(.Width(W), .Cycles(TimeCos)) u_dly_kd (
    .clk_i, .rst_ni, .data_i(kd_s), .data_o(kd_at_cos)
  );
  // kd * cos: in u_muls (below).
  rc_delay_ram #(.Width(W), .Cycles(TimeSpec - TimeCos)) u_dly_kdcos (
    .clk_i, .rst_ni, .data_i(kdcos), .data_o(kdcos_d)
  );
  rc_delay_ram #(.Width(W), .Cycles(TimeSpec)) u_dly_ks (
    .clk_i, .rst_ni, .data_i(ks_s), .data_o(ks_at_spec)
  );
  // ks * spec: in u_muls.
  // kd cos + ks spec: in u_adds.
  rc_delay_ram #(.Width(W), .Cycles(TimeSum)) u_dly_lc (
    .clk_i, .rst_ni, .data_i(lc_s), .data_o(lc_at_sum)
  );
  // (...) * lcol: in u_muls.
  // w is the input register's: a delay of T gives it at T, T + 1, T + 2.
  rc_delay_ram #(.Width(W), .Cycles(TimeSum + Lm)) u_dly_w (
    .clk_i, .rst_ni, .data_i(w_q), .data_o(w_at_sl)
  );
  // lh = L * inv (at TimeInv) and (... * lcol) * w (at TimeSum + Lm): in u_muls.
  logic [W-1:0] lhw, xw;
  assign lh_pt = lhw;
  assign x_s   = xw;
  logic [FW-1:0] term_s;
  logic          term_vld;
  rc_fp_to_fix #(.ExpW(ExpW), .FracW(FracW), .FixBits(FixBits), .Stages(Lf)) u_fix_t (
    .clk_i, .rst_ni, .valid_i(strm[TimeX]), .x_i(x_s), .valid_o(term_vld), .out_o(term_s)
  );
  logic pres_at_fix;
  rc_delay_ram #(.Width(1), .Cycles(TimeFix - TimeCos)) u_dly_pres (
    .clk_i, .rst_ni, .data_i(pres_b), .data_o(pres_at_fix)
  );

  //////////////////////////////////////////////////////////
  // Ambient: fix((kd * ambient) * w)                      //
  //////////////////////////////////////////////////////////

  logic [W-1:0]  kd_at_ka, ka, w_at_ka, aw;
  logic [FW-1:0] amb_s, amb_at_fix;
  logic          amb_vld;
  // kd * ambient (at TimeKa) and ka * w (at TimeAw): in u_muls.
  rc_delay #(.Width(W), .Cycles(TimeKa)) u_dly_kda (.clk_i, .data_i(kd_s), .data_o(kd_at_ka));
  rc_delay #(.Width(W), .Cycles(TimeAw)) u_dly_wa (.clk_i, .data_i(w_q), .data_o(w_at_ka));
  rc_fp_to_fix #(.ExpW(ExpW), .FracW(FracW), .FixBits(FixBits), .Stages(Lf)) u_fix_a (
    .clk_i, .rst_ni, .valid_i(strm[TimeAw + Lm]), .x_i(aw), .valid_o(amb_vld), .out_o(amb_s)
  );
  rc_delay_ram #(.Width(FW), .Cycles(TimeFix - (TimeAw + Lm + Lf))) u_dly_amb (
    .clk_i, .rst_ni, .data_i(amb_s), .data_o(amb_at_fix)
  );

  //////////////////////////////////////////////////////////
  // Products                                             //
  //////////////////////////////////////////////////////////

  // Every product of the unit, each a user of one pool of multipliers at its time in the
  // schedule (three cycles for a stream, one for a scalar, two for a power step): rc_fp_pool
  // places the users on as few multipliers as their phases modulo Period allow (11 at Period 6,
  // 5 at 12 with the default fp_stages and ExpBits). Each product is read at its own time.
  localparam int unsigned MulUsers = 13 + ExpBits;

  // User k's issue time at [16k +: 16] and cycles at [2k +: 2].
  function automatic logic [511:0] mul_times();
    mul_times = '0;
    mul_times[16*0 +: 16] = 16'(TimeKa);      // kd * ambient
    mul_times[16*1 +: 16] = 16'(TimeSpec);    // ks * spec
    mul_times[16*2 +: 16] = 16'(TimeAw);      // ka * w
    mul_times[16*3 +: 16] = 16'(TimeCos);     // kd * cos
    mul_times[16*4 +: 16] = 16'(TimeInv);     // lh = L * inv
    mul_times[16*5 +: 16] = 16'(TimeSum + Lm); // (sum * lcol) * w
    mul_times[16*6 +: 16] = 16'(TimeSum);     // sum * lcol
    mul_times[16*7 +: 16] = 16'(TimeL);       // L * L
    mul_times[16*8 +: 16] = 16'(TimeInv);     // dist = dist2 * inv
    mul_times[16*9 +: 16] = 16'(TimeIh);      // nh = N.H * (1 / sqrt(H.H))
    for (int unsigned i = 0; i < ExpBits; i++) begin
      mul_times[16*(10+i) +: 16] = 16'(TimeNh + i * PowStep);  // power step i
    end
    mul_times[16*(10+ExpBits) +: 16] = 16'(TimeDc);  // N * lh
    mul_times[16*(11+ExpBits) +: 16] = 16'(TimeDh);  // H * H
    mul_times[16*(12+ExpBits) +: 16] = 16'(TimeDn);  // N * H
  endfunction
  function automatic logic [63:0] mul_cycles();
    mul_cycles = '0;
    for (int unsigned k = 0; k < 8; k++) mul_cycles[2*k +: 2] = 2'd3;
    mul_cycles[2*8 +: 2] = 2'd1;
    mul_cycles[2*9 +: 2] = 2'd1;
    for (int unsigned i = 0; i < ExpBits; i++) mul_cycles[2*(10+i) +: 2] = 2'd2;
    for (int unsigned k = 10 + ExpBits; k < MulUsers; k++) mul_cycles[2*k +: 2] = 2'd3;
  endfunction

  logic [MulUsers-1:0]   mul_issue, mul_vld;
  logic [MulUsers*W-1:0] mul_a, mul_b, mul_res;
  assign mul_issue = {strm[TimeDn], strm[TimeDh], strm[TimeDc], step_issue, at[TimeIh],
                      at[TimeInv], strm[TimeL], strm[TimeSum], strm[TimeSum + Lm], strm[TimeInv],
                      strm[TimeCos], strm[TimeAw], strm[TimeSpec], strm[TimeKa]};
  assign mul_a     = {n_at_dn, h_s, n_at_lh2, step_a, nhd_d, d2_at_inv, l_s, sum, sl, l_at_inv,
                      kd_at_cos, ka, ks_at_spec, kd_at_ka};
  assign mul_b     = {h_at_dn, h_s, lh_s2, step_b, ih, inv_res, l_s, lc_at_sum, w_at_sl, inv_b,
                      cos_b, w_at_ka, spec_b, ambient_i};
  rc_fp_pool #(
    .ExpW(ExpW), .FracW(FracW), .Users(MulUsers), .Period(Period), .Time(mul_times()),
    .Cycles(mul_cycles()), .InReg(1'b1)
  ) u_muls (
    .clk_i, .rst_ni, .issue_i(mul_issue), .a_i(mul_a), .b_i(mul_b), .valid_o(mul_vld),
    .res_o(mul_res)
  );
  assign {dp[2*W +: W], dp[W +: W], dp[0 +: W], pow_prod, nh_p, dist_p, ll, sl, xw, lhw, kdcos,
          aw, ksspec, ka} = mul_res;

  // Every sum, likewise in one pool of adders (4 at Period 6, 2 at 12): the streams L = lpos - p
  // (at 0), H = lh - v (at TimeLh) and kd cos + ks spec (at TimeSpec + Lm), dist2's scalar sums
  // x + y (at TimeLl + 1) and + z (at TimeD01), then the other dot products' x + y (cos, H.H and
  // N.H, at TimeXy*) and their + z (at TimeZ*).
  localparam logic [511:0] AddTimes  = 512'({16'(TimeZN), 16'(TimeZH), 16'(TimeZC),
                                              16'(TimeXyN), 16'(TimeXyH), 16'(TimeXyC),
                                              16'(TimeD01), 16'(TimeLl + 1), 16'(TimeSpec + Lm),
                                              16'(TimeLh), 16'(0)});
  localparam logic [63:0]  AddCycles = 64'({{8{2'd1}}, 2'd3, 2'd3, 2'd3});
  localparam int unsigned  AddUsers  = 11;
  logic [AddUsers-1:0]   add_issue, add_vld;
  logic [AddUsers*W-1:0] add_a, add_b, add_res;
  assign add_issue = {at[TimeZN], at[TimeZH], at[TimeZC], at[TimeXyN], at[TimeXyH], at[TimeXyC],
                      at[TimeD01], at[TimeLl + 1], strm[TimeSpec + Lm], strm[TimeLh], strm[0]};
  assign add_a     = {dxy_d[2*W +: W], dxy_d[W +: W], dxy_d[0 +: W], dp_dx[2*W +: W],
                      dp_dx[W +: W], dp_dx[0 +: W], d01, ll_d1, kdcos_d, lh_s, lp_s};
  assign add_b     = {dp_dz[2*W +: W], dp_dz[W +: W], dp_dz[0 +: W], dp_dy[2*W +: W],
                      dp_dy[W +: W], dp_dy[0 +: W], ll_dz, ll, ksspec, v_at_lh, p_s};
  rc_fp_pool #(
    .ExpW(ExpW), .FracW(FracW), .Add(1'b1), .Users(AddUsers), .Sub(32'b00011), .Period(Period),
    .Time(AddTimes), .Cycles(AddCycles), .InReg(1'b1)
  ) u_adds (
    .clk_i, .rst_ni, .issue_i(add_issue), .a_i(add_a), .b_i(add_b), .valid_o(add_vld),
    .res_o(add_res)
  );
  assign {dz, dxy, dist2, d01, sum, h_s, l_s} = add_res;

  //////////////////////////////////////
  // Collect the streams at TimeFix   //
  //////////////////////////////////////

  logic [W-1:0]    lh_at_fix, thi_at_fix;
  logic [TagW-1:0] tag_at_out;
  rc_delay_ram #(.Width(2 * W), .Cycles(TimeFix - TimeLh)) u_dly_lh (
    .clk_i, .rst_ni, .data_i({lh_s, thi_s}), .data_o({lh_at_fix, thi_at_fix})
  );
  rc_delay_ram #(.Width(TagW), .Cycles(TimeOut - 2)) u_dly_tag (
    .clk_i, .rst_ni, .data_i(tag_q), .data_o(tag_at_out)
  );

  // Per cycle: lh, the term (0 unless the light is in front), the ambient term, t_hi and present
  // (scalars: meaningful in the x position).
  localparam int unsigned SerW = 2 * W + 2 * FW + 1;
  logic [SerW-1:0] ser, ser_d1_q, ser_d2_q;
  assign ser = {lh_at_fix, pres_at_fix ? term_s : FW'(0), amb_at_fix, thi_at_fix, pres_at_fix};
  always_ff @(posedge clk_i) begin
    ser_d1_q <= ser;
    ser_d2_q <= ser_d1_q;
  end

  logic [3*W-1:0]  lh_v;
  logic [3*FW-1:0] term_v, amb_v;
  assign lh_v   = {ser[SerW-1 -: W], ser_d1_q[SerW-1 -: W], ser_d2_q[SerW-1 -: W]};
  assign term_v = {ser[SerW-W-1 -: FW], ser_d1_q[SerW-W-1 -: FW], ser_d2_q[SerW-W-1 -: FW]};
  assign amb_v  = {ser[SerW-W-FW-1 -: FW], ser_d1_q[SerW-W-FW-1 -: FW],
                   ser_d2_q[SerW-W-FW-1 -: FW]};

  rc_credit_fifo #(
    .Width   (OutW),
    .Depth   (FifoDepth),
    .MemArray(1'b1)
  ) u_fifo (
    .clk_i,
    .rst_ni,
    .take_i    (take),
    .credit_o  (credit),
    .wr_valid_i(at[TimeOut]),
    .wr_data_i ({tag_at_out, ser_d2_q[0], lh_v, ser_d2_q[W:1], term_v, amb_v}),
    .valid_o,
    .ready_i,
    .data_o    ({tag_o, present_o, lh_o, t_hi_o, term_o, amb_o})
  );

  ////////////////
  // Assertions //
  ////////////////

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  // The shared root's and divider's two users never come in one cycle (the phase).
  SharedRoot_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
      !(at[TimeD2] && at[TimeHs]) && !(at[TimeSq1] && at[TimeHs + Ls]));

  // Each operation's result leaves at the time the schedule above gives it: the fp units' valid
  // chains agree with the stream starts, so no value is read at the wrong cycle.
  Schedule_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
      rt_vld == (at[TimeSq1] | at[TimeHs + Ls]) &&
      rinv_vld == (at[TimeInv] | at[TimeIh]) &&
      term_vld == strm[TimeFix] && amb_vld == strm[TimeAw + Lm + Lf]);
  // Every product leaves its multiplier when its user reads it, Lm cycles after its issue (the
  // pool's multipliers' valid chains, which also carry the other users' products).
  logic [MulUsers-1:0] mul_due;
  for (genvar i = 0; i < ExpBits; i++) begin : g_pow_due
    assign mul_due[10 + i] = at[TimeNh + i*PowStep + Lm] | at[TimeNh + i*PowStep + Lm + 1];
  end
  assign mul_due[MulUsers-1 -: 3] = {strm[TimeDn + Lm], strm[TimeDh + Lm], strm[TimeDc + Lm]};
  assign mul_due[9:0] = {at[TimeNh], at[TimeLh], strm[TimeLl], strm[TimeSum + Lm], strm[TimeX],
                         strm[TimeLh], strm[TimeCos + Lm], strm[TimeAw + Lm], strm[TimeSpec + Lm],
                         strm[TimeKa + Lm]};
  Products_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              (mul_due & ~mul_vld) == '0);
  // Likewise every sum of u_adds, La cycles after its issue.
  logic [AddUsers-1:0] add_due;
  assign add_due = {at[TimeNhd], at[TimeHh], at[TimeCos],
                    at[TimeXyN + La], at[TimeXyH + La], at[TimeXyC + La],
                    at[TimeD2], at[TimeD01], strm[TimeSum], strm[TimeH], strm[TimeL]};
  Sums_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                          (add_due & ~add_vld) == '0);
  // ready_o must be known once out of reset (upstream acts on it).
  ReadyKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !$isunknown(ready_o));
`endif

endmodule
