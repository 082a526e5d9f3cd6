// rc_hit_geom: the geometry of one hit for the lighting (docs/architecture.md, "Lighting",
// "Reflection", "Refraction"): the hit point, the facing normal, the view direction, the mirror
// and refraction directions, and the children's weights.
//
// Contract
// - Function: exactly rc::hit_geometry() (tb/golden/trace.hpp), bit for bit. Vector ports hold
//   component a (0 = x, 1 = y, 2 = z) at [a*W +: W] (W = 1 + ExpW + FracW), flat as in
//   rc_ray_setup (Yosys reads no multi-dimensional packed arrays).
//     back_o   = lt(0, dz_i)                          (the ray leaves through the triangle's back)
//     p_o[a]   = org_i[a] + t_i * dir_i[a]
//     n_o[a]   = back_o ? -n_i[a] : n_i[a]           (a sign flip)
//     v_o[a]   = dir_i[a] * inv_len_i
//     c        = (n_o[0]*v_o[0] + n_o[1]*v_o[1]) + n_o[2]*v_o[2]
//     r_o[a]   = v_o[a] - (c + c) * n_o[a]
//     e        = back_o ? eta_leave_i : eta_enter_i
//     q        = 1 - (e * e) * (1 - c * c)
//     refr_o[a] = lt(0, q) ? e * v_o[a] - (e * c + sqrt(q)) * n_o[a] : r_o[a]
//     w_mirror_o  = w_i * mirror_i,    mirror_o  = lt(0, mirror_i) && lt(0, w_mirror_o)
//     w_refract_o = w_i * transmit_i,  refract_o = lt(0, transmit_i) && lt(0, w_refract_o)
//   Every operation is the format's (rc_fp_mul, rc_fp_add, rc_fp_sqrt), in exactly this order
//   and with these operands.
// - Structure: component-serial. A taken hit waits in an input register for three cycles
//   (slots 0, 1, 2) while its x, y and z enter the vector operations, one component a cycle;
//   every vector value then travels as a stream of three consecutive components and every scalar
//   as one value at a fixed cycle. A scalar that a vector operation needs (t, inv_len, the
//   mirror term's c + c, the refraction term's g) is held for the three cycles of the stream by
//   a register loaded in the stream's first cycle. Hits are taken at phase 0 modulo Period, a
//   multiple of 6 (rc_serial_sched, Phased), so operations whose cycles fall at different phases
//   share an operator and no two hits meet there: the three scalar sums 1 - c * c, q = 1 - x and
//   g (times that differ modulo 3) share one adder; modulo 6 (rc_fp_shared, which checks the
//   phases at elaboration), one multiplier takes the two weights and then c * c, e * e and e * c
//   in consecutive cycles, one t * d and g * N, one d * inv_len and e * V, one (c + c) * N and
//   e^2 (1 - c^2), and one adder o + t d and e V - g N; c + c is rc_fp_twice (exact doubling, a
//   cycle). Each value reaches its operation through rc_delay lines (rc_delay_ram memories where
//   they are long) of the lengths the fp units' latencies give (the times below, in cycles after
//   slot 0), so a stream's timing never depends on its neighbours: a hit may follow another after
//   Period cycles or after any gap (rc_serial_sched keeps the slots and says which job time is
//   now). The last stage collects each stream's three components into the output FIFO.
// - Handshake: valid_i/ready_o in, valid_o/ready_i out, with backpressure. An operation is taken
//   when valid_i & ready_o. ready_o is the AND of two flip-flops (rc_credit_fifo's credit
//   register and the input register's free flag) and never depends on valid_i or ready_i;
//   valid_o never depends on ready_i. Results leave in order; nothing is dropped or duplicated.
//   tag_i travels with the operation to tag_o.
// - Latency: TimeT + 4 cycles from the taking cycle to valid_o when the FIFO is empty and ready_i
//   is 1 (71 at the default fp_stages: mul 4, add 6, sqrt 10): input register 1, then the chain
//   V, N.V, the sum c, c * c, 1 - c * c, e^2 (1 - c^2), q, sqrt(q), g, g * N, e * V - g * N
//   (TimeT = 67 after slot 0), two cycles for the stream's y and z, the FIFO's output register 1.
// - Throughput: one hit per Period cycles while ready_i is 1; ready_o is high only in cycles
//   whose phase modulo Period lets a hit start at phase 0, so a hit offered after a gap may wait
//   up to Period - 1 cycles. The FIFO holds Latency / Period + 2 entries, enough credits for
//   every operation in flight at that rate.
// - Parameters: ExpW, FracW: the number format (default fp24); TagW: tag bits (>= 1); Period:
//   the cycles between two hits, 6 or 12 (docs/spec.toml [light] unit_period: the light units
//   need not keep up with the core, a lower rate needs a shallower FIFO, and the shared
//   operators need a multiple of 6).
// - Illegal input: none; every bit pattern of the data inputs is legal.
// - Reset: rst_ni (active low, asynchronous) clears control state only (the slot counter, the
//   stream-start chain, the delay memories' pointers, the FIFO's pointers and credit count); data
//   registers have no reset.
module rc_hit_geom #(
  parameter int unsigned ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW  = rc_pkg::Fp24FracW,
  parameter int unsigned TagW   = 8,
  parameter int unsigned Period = rc_pkg::LightUnitPeriod
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  // Input handshake.
  input  logic                        valid_i,
  output logic                        ready_o,
  input  logic [TagW-1:0]             tag_i,
  input  logic [3*(ExpW+FracW+1)-1:0] org_i,        // x, y, z
  input  logic [3*(ExpW+FracW+1)-1:0] dir_i,        // x, y, z
  input  logic [ExpW+FracW:0]         inv_len_i,
  input  logic [ExpW+FracW:0]         t_i,          // the hit's distance
  input  logic [ExpW+FracW:0]         dz_i,         // the hit's d'z
  input  logic [3*(ExpW+FracW+1)-1:0] n_i,          // the triangle's unit normal
  input  logic [ExpW+FracW:0]         eta_enter_i,  // the material's 1 / ior
  input  logic [ExpW+FracW:0]         eta_leave_i,  // the material's ior
  input  logic [ExpW+FracW:0]         w_i,          // the ray's weight
  input  logic [ExpW+FracW:0]         mirror_i,     // the material's mirror weight
  input  logic [ExpW+FracW:0]         transmit_i,   // the material's refraction weight
  // Output handshake.
  output logic                        valid_o,
  input  logic                        ready_i,
  output logic [TagW-1:0]             tag_o,
  output logic                        back_o,
  output logic [3*(ExpW+FracW+1)-1:0] p_o,
  output logic [3*(ExpW+FracW+1)-1:0] n_o,
  output logic [3*(ExpW+FracW+1)-1:0] v_o,
  output logic [3*(ExpW+FracW+1)-1:0] r_o,
  output logic [3*(ExpW+FracW+1)-1:0] refr_o,
  output logic [ExpW+FracW:0]         w_mirror_o,
  output logic [ExpW+FracW:0]         w_refract_o,
  output logic                        mirror_o,
  output logic                        refract_o
);

  localparam int unsigned W  = ExpW + FracW + 1;
  localparam int unsigned Lm = rc_pkg::FpStagesMul;
  localparam int unsigned La = rc_pkg::FpStagesAdd;
  localparam int unsigned Ls = rc_pkg::FpStagesSqrt;

  // The cycle (after slot 0) at which each value, or a stream's x, leaves its operation.
  localparam int unsigned TimeV   = Lm;                // V = d * inv_len; also t * d
  localparam int unsigned TimeP   = TimeV + La;        // P = o + t * d
  localparam int unsigned TimeNv  = TimeV + Lm;        // N * V, per component
  localparam int unsigned TimeS01 = TimeNv + 1 + La;   // N.x V.x + N.y V.y (issued with y)
  localparam int unsigned TimeC   = TimeS01 + La;      // c
  localparam int unsigned TimeK   = TimeC + 1;         // c + c (rc_fp_twice)
  localparam int unsigned TimeKn  = TimeK + Lm;        // (c + c) * N
  localparam int unsigned TimeR   = TimeKn + La;       // R = V - (c + c) N
  localparam int unsigned TimeS   = TimeC + Lm + La;   // 1 - c * c
  localparam int unsigned TimeX   = TimeS + Lm;        // e^2 * (1 - c^2)
  localparam int unsigned TimeQ   = TimeX + La;        // q
  localparam int unsigned TimeSq  = TimeQ + Ls;        // sqrt(q)
  localparam int unsigned TimeG   = TimeSq + La;       // g = e c + sqrt(q)
  localparam int unsigned TimeGn  = TimeG + Lm;        // g * N and e * V
  localparam int unsigned TimeT   = TimeGn + La;       // e V - g N
  localparam int unsigned TimeOut = TimeT + 2;         // z of the last streams: the FIFO write
  localparam int unsigned Latency = TimeT + 4;
  localparam int unsigned FifoDepth = Latency / Period + 2;
  localparam int unsigned OutW = TagW + 1 + 15 * W + 2 * W + 2;

  localparam logic [W-1:0] One = {1'b0, 1'b0, {(ExpW - 1) {1'b1}}, {FracW{1'b0}}};
  localparam logic [W-1:0] SignBit = {1'b1, {(W - 1) {1'b0}}};

  if (TagW < 1) begin : g_param_check
    $error("rc_hit_geom: TagW must be at least 1");
  end
  // The shared adder's three users must come at different phases.
  if (TimeSq % 3 == (TimeC + Lm) % 3 || TimeSq % 3 == TimeX % 3 ||
      (TimeC + Lm) % 3 == TimeX % 3) begin : g_phase_check
    $error("rc_hit_geom: the shared adder's users must come at different phases");
  end

  // lt(+0, x): x is positive, not zero (an exponent field of 0 reads as zero) and not NaN.
  function automatic logic pos(input logic [W-1:0] x);
    pos = ~x[W-1] & (|x[W-2 -: ExpW]) & ~((&x[W-2 -: ExpW]) & (|x[FracW-1:0]));
  endfunction

  ////////////////////////////////////////////
  // Input register, slots, stream starts   //
  ////////////////////////////////////////////

  // slot_q: one-hot, bit k = cycle k of the hit held in the input register (all zero: empty);
  // in_free_q: the register is free, a flip-flop, so ready_o is the AND of two (rc_serial_sched).
  logic [2:0] slot_q;
  logic       in_free_q, take, credit;

  assign ready_o = credit & in_free_q;
  assign take    = valid_i & ready_o;

  // The input register (loaded when taken; no reset: slot_q says when it holds a hit).
  logic [TagW-1:0] tag_q;
  logic [3*W-1:0]  org_q, dir_q, n_q;
  logic [W-1:0]    ilen_q, t_q, eta_q, w_q, mirror_q, transmit_q;
  logic            back_q;

  always_ff @(posedge clk_i) begin
    if (take) begin
      tag_q      <= tag_i;
      org_q      <= org_i;
      dir_q      <= dir_i;
      n_q        <= n_i;
      ilen_q     <= inv_len_i;
      t_q        <= t_i;
      back_q     <= pos(dz_i);
      eta_q      <= pos(dz_i) ? eta_leave_i : eta_enter_i;
      w_q        <= w_i;
      mirror_q   <= mirror_i;
      transmit_q <= transmit_i;
    end
  end

  // at[T]: a hit is at time T (cycles after its slot 0) in this cycle; strm[T]: a vector
  // operation issued at time T (its x; y and z follow) is busy (rc_serial_sched).
  logic [TimeOut:0]   at;
  logic [TimeOut-2:0] strm;
  rc_serial_sched #(.Time(TimeOut), .Phased(1'b1), .Period(Period)) u_sched (
    .clk_i, .rst_ni, .take_i(take), .slot_o(slot_q), .in_free_o(in_free_q), .at_o(at),
    .strm_o(strm)
  );

  // The components entering in this slot (slot 0: x, 1: y, 2: z).
  logic [W-1:0] o_s, d_s, nf_s;
  always_comb begin
    o_s  = org_q[0 +: W];
    d_s  = dir_q[0 +: W];
    nf_s = n_q[0 +: W];
    if (slot_q[1]) begin
      o_s  = org_q[W +: W];
      d_s  = dir_q[W +: W];
      nf_s = n_q[W +: W];
    end else if (slot_q[2]) begin
      o_s  = org_q[2*W +: W];
      d_s  = dir_q[2*W +: W];
      nf_s = n_q[2*W +: W];
    end
    if (back_q) nf_s = nf_s ^ SignBit;
  end

  // A scalar held for its stream's three cycles: the value in the first, then a register's.
  // (Three instances below: c + c, c and g.)
  logic [W-1:0] k_res, k_hold_q, k_b;
  logic [W-1:0] c_res, c_hold_q, c_b;
  logic [W-1:0] g_res, g_hold_q, g_b;

  assign k_b = at[TimeK] ? k_res : k_hold_q;
  assign c_b = at[TimeC] ? c_res : c_hold_q;
  assign g_b = at[TimeG] ? g_res : g_hold_q;

  always_ff @(posedge clk_i) begin
    if (at[TimeK]) k_hold_q <= k_res;
    if (at[TimeC]) c_hold_q <= c_res;
    if (at[TimeG]) g_hold_q <= g_res;
  end

  //////////////////////////////////////////////////
  // P = o + t d, V = d inv_len, c = N.V           //
  //////////////////////////////////////////////////

  logic [W-1:0] td, v_s, p_s, o_d, n_dv;
  logic         nv_vld, s01_vld, c_vld;

  // t * d and V = d * inv_len: in u_mul_tdgn and u_mul_vev (below, with g * N and e * V); o + t d
  // in u_add_pt (with e V - g N).
  rc_delay #(.Width(W), .Cycles(TimeV)) u_dly_o (.clk_i, .data_i(o_s), .data_o(o_d));

  // The facing normal's stream, tapped where the operations need it.
  logic [W-1:0] n_at_v, n_at_k, n_at_g, n_at_t;
  rc_delay #(.Width(W), .Cycles(TimeV)) u_dly_n0 (.clk_i, .data_i(nf_s), .data_o(n_at_v));
  rc_delay_ram #(.Width(W), .Cycles(TimeK - TimeV)) u_dly_n1 (
    .clk_i, .rst_ni, .data_i(n_at_v), .data_o(n_at_k)
  );
  rc_delay_ram #(.Width(W), .Cycles(TimeG - TimeK)) u_dly_n2 (
    .clk_i, .rst_ni, .data_i(n_at_k), .data_o(n_at_g)
  );
  rc_delay #(.Width(W), .Cycles(TimeT - TimeG)) u_dly_n3 (
    .clk_i, .data_i(n_at_g), .data_o(n_at_t)
  );
  assign n_dv = n_at_v;

  // c = (N.x V.x + N.y V.y) + N.z V.z: x + y as y's product leaves, then + z.
  rc_serial_dot3 #(.ExpW(ExpW), .FracW(FracW)) u_dot_c (
    .clk_i, .rst_ni, .strm_i(strm[TimeV]), .xy_i(at[TimeNv + 1]), .z_i(at[TimeS01]), .a_i(n_dv),
    .b_i(v_s), .prod_valid_o(nv_vld), .xy_valid_o(s01_vld), .valid_o(c_vld), .res_o(c_res)
  );

  //////////////////////////////////////
  // R = V - (c + c) N                //
  //////////////////////////////////////

  logic [W-1:0] kn, v_at_kn, r_s, v_at_g;
  logic         k_vld, r_vld;

  // c + c: exact doubling (rc_fp_twice, x + x bit for bit), a cycle.
  rc_fp_twice #(.ExpW(ExpW), .FracW(FracW)) u_twice_k (
    .clk_i, .rst_ni, .valid_i(at[TimeC]), .x_i(c_res), .valid_o(k_vld), .res_o(k_res)
  );

  // (c + c) * N: in u_mul_knx (below, with e^2 * (1 - c^2)).
  rc_delay_ram #(.Width(W), .Cycles(TimeKn - TimeV)) u_dly_v0 (
    .clk_i, .rst_ni, .data_i(v_s), .data_o(v_at_kn)
  );
  rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(La)) u_add_r (
    .clk_i, .rst_ni, .valid_i(strm[TimeKn]), .sub_i(1'b1), .a_i(v_at_kn), .b_i(kn),
    .valid_o(r_vld), .res_o(r_s)
  );
  rc_delay_ram #(.Width(W), .Cycles(TimeG - TimeKn)) u_dly_v1 (
    .clk_i, .rst_ni, .data_i(v_at_kn), .data_o(v_at_g)
  );

  ////////////////////////////////////////////////////////////
  // Refraction: q = 1 - e^2 (1 - c^2), T = e V - g N       //
  ////////////////////////////////////////////////////////////

  // e (the input register's, one of the two ratios) as a stream: at slot k the register holds it,
  // so a delay line of T gives it at T, T + 1, T + 2.
  logic [W-1:0] e_at_c, e_at_g;
  rc_delay_ram #(.Width(W), .Cycles(TimeC)) u_dly_e0 (
    .clk_i, .rst_ni, .data_i(eta_q), .data_o(e_at_c));
  rc_delay_ram #(.Width(W), .Cycles(TimeG - TimeC)) u_dly_e1 (
    .clk_i, .rst_ni, .data_i(e_at_c), .data_o(e_at_g)
  );

  // One multiplier: c * c at TimeC, e * e at TimeC + 1, e * c at TimeC + 2.
  logic [W-1:0] m5_a, m5_b, m5, e2_d, ec_d, s_res, x_res, q_res, sq_res;
  logic         knx_vld, sq_vld;
  assign m5_a = at[TimeC] ? c_b : e_at_c;
  assign m5_b = at[TimeC + 1] ? e_at_c : c_b;

  // c * c, e * e, e * c: in u_mul_wm5 (below, with the weights).
  rc_delay #(.Width(W), .Cycles(TimeS - (TimeC + 1 + Lm))) u_dly_e2 (
    .clk_i, .data_i(m5), .data_o(e2_d)
  );
  // One multiplier for the stream (c + c) * N (at TimeK) and the scalar e^2 * (1 - c^2) (at
  // TimeS): their cycles fall at different phases modulo Period.
  logic [W-1:0] knx;
  rc_fp_shared #(
    .ExpW(ExpW), .FracW(FracW), .Users(2), .Period(Period),
    .Time(128'({16'(TimeS), 16'(TimeK)})), .Cycles(16'h0007)
  ) u_mul_knx (
    .clk_i, .rst_ni, .issue_i({at[TimeS], strm[TimeK]}), .a_i({e2_d, k_b}), .b_i({s_res, n_at_k}),
    .valid_o(knx_vld), .res_o(knx)
  );
  assign kn    = knx;
  assign x_res = knx;
  // One adder for the three scalar sums, issued at different phases (jobs start at phase 0,
  // rc_serial_sched Phased): 1 - c * c at TimeC + Lm, 1 - x at TimeX, g = e c + sqrt(q) at
  // TimeSq. Each user reads the result La cycles after its issue (TimeS, TimeQ, TimeG).
  logic [W-1:0] sa_a, sa_b, sa_res;
  logic         sa_sub, sa_valid, sa_vld;
  assign sa_valid = at[TimeC + Lm] | at[TimeX] | at[TimeSq];
  assign sa_sub   = at[TimeC + Lm] | at[TimeX];
  assign sa_a     = ({W{sa_sub}} & One) | ({W{at[TimeSq]}} & ec_d);
  assign sa_b     = ({W{at[TimeC + Lm]}} & m5) | ({W{at[TimeX]}} & x_res) |
                    ({W{at[TimeSq]}} & sq_res);
  rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(La)) u_add_shared (
    .clk_i, .rst_ni, .valid_i(sa_valid), .sub_i(sa_sub), .a_i(sa_a), .b_i(sa_b),
    .valid_o(sa_vld), .res_o(sa_res)
  );
  assign s_res = sa_res;
  assign q_res = sa_res;
  assign g_res = sa_res;
  rc_fp_sqrt #(.ExpW(ExpW), .FracW(FracW), .Stages(Ls)) u_sqrt (
    .clk_i, .rst_ni, .valid_i(at[TimeQ]), .a_i(q_res), .valid_o(sq_vld), .res_o(sq_res)
  );
  rc_delay_ram #(.Width(W), .Cycles(TimeSq - (TimeC + 2 + Lm))) u_dly_ec (
    .clk_i, .rst_ni, .data_i(m5), .data_o(ec_d)
  );

  // Total internal reflection (not lt(0, q), NaN too), held for the stream and carried to T.
  logic tir_hold_q, tir_b, tir_at_t;
  assign tir_b = at[TimeQ] ? !pos(q_res) : tir_hold_q;
  always_ff @(posedge clk_i) begin
    if (at[TimeQ]) tir_hold_q <= !pos(q_res);
  end
  rc_delay_ram #(.Width(1), .Cycles(TimeT - TimeQ)) u_dly_tir (
    .clk_i, .rst_ni, .data_i(tir_b), .data_o(tir_at_t)
  );

  // Two multipliers and an adder, each for two streams at different phases modulo Period:
  // t * d (at 0) with g * N (at TimeG), d * inv_len (at 0) with e * V (at TimeG), and o + t d (at
  // TimeV) with e V - g N (at TimeGn).
  logic [W-1:0] gn, ev, t_s, tdgn, vev, pt;
  logic         tdgn_vld, vev_vld, pt_vld;
  rc_fp_shared #(
    .ExpW(ExpW), .FracW(FracW), .Users(2), .Period(Period),
    .Time(128'({16'(TimeG), 16'(0)})), .Cycles(16'h000f)
  ) u_mul_tdgn (
    .clk_i, .rst_ni, .issue_i({strm[TimeG], strm[0]}), .a_i({g_b, t_q}), .b_i({n_at_g, d_s}),
    .valid_o(tdgn_vld), .res_o(tdgn)
  );
  rc_fp_shared #(
    .ExpW(ExpW), .FracW(FracW), .Users(2), .Period(Period),
    .Time(128'({16'(TimeG), 16'(0)})), .Cycles(16'h000f)
  ) u_mul_vev (
    .clk_i, .rst_ni, .issue_i({strm[TimeG], strm[0]}), .a_i({e_at_g, d_s}),
    .b_i({v_at_g, ilen_q}), .valid_o(vev_vld), .res_o(vev)
  );
  rc_fp_shared #(
    .ExpW(ExpW), .FracW(FracW), .Add(1'b1), .Users(2), .Sub(8'b10), .Period(Period),
    .Time(128'({16'(TimeGn), 16'(TimeV)})), .Cycles(16'h000f)
  ) u_add_pt (
    .clk_i, .rst_ni, .issue_i({strm[TimeGn], strm[TimeV]}), .a_i({ev, o_d}), .b_i({gn, td}),
    .valid_o(pt_vld), .res_o(pt)
  );
  assign td  = tdgn;
  assign gn  = tdgn;
  assign v_s = vev;
  assign ev  = vev;
  assign p_s = pt;
  assign t_s = pt;

  //////////////////////////////////////
  // Weights                          //
  //////////////////////////////////////

  // w * mirror at slot 0, w * transmit at slot 1; each with lt(0, factor) beside it.
  logic [W-1:0] wf_s, wx, wx_at_t;
  logic         fpos_s, fpos_d, wok, wok_at_t, wm5_vld;
  assign wf_s   = slot_q[1] ? transmit_q : mirror_q;
  assign fpos_s = pos(wf_s);
  // One multiplier for the weights (slots 0 and 1) and the stream c * c, e * e, e * c (at
  // TimeC): their cycles fall at different phases modulo Period.
  logic [W-1:0] wm5;
  rc_fp_shared #(
    .ExpW(ExpW), .FracW(FracW), .Users(2), .Period(Period),
    .Time(128'({16'(TimeC), 16'(0)})), .Cycles(16'h000e)
  ) u_mul_wm5 (
    .clk_i, .rst_ni, .issue_i({strm[TimeC], slot_q[0] | slot_q[1]}), .a_i({m5_a, w_q}),
    .b_i({m5_b, wf_s}), .valid_o(wm5_vld), .res_o(wm5)
  );
  assign wx = wm5;
  assign m5 = wm5;
  rc_delay #(.Width(1), .Cycles(Lm)) u_dly_fpos (.clk_i, .data_i(fpos_s), .data_o(fpos_d));
  assign wok = fpos_d & pos(wx);
  rc_delay_ram #(.Width(W + 1), .Cycles(TimeT - Lm)) u_dly_w (
    .clk_i, .rst_ni, .data_i({wok, wx}), .data_o({wok_at_t, wx_at_t})
  );

  //////////////////////////////////////
  // Collect the streams at TimeT     //
  //////////////////////////////////////

  logic [W-1:0] p_at_t, v_at_t, r_at_t, refr_s;
  rc_delay_ram #(.Width(W), .Cycles(TimeT - TimeP)) u_dly_p (
    .clk_i, .rst_ni, .data_i(p_s), .data_o(p_at_t)
  );
  rc_delay #(.Width(W), .Cycles(TimeT - TimeG)) u_dly_v2 (
    .clk_i, .data_i(v_at_g), .data_o(v_at_t)
  );
  rc_delay_ram #(.Width(W), .Cycles(TimeT - TimeR)) u_dly_r (
    .clk_i, .rst_ni, .data_i(r_s), .data_o(r_at_t)
  );
  assign refr_s = tir_at_t ? r_at_t : t_s;

  // The tag and back travel from the input register (held for slots 0..2: the delay to TimeOut
  // gives slot 2's copy).
  logic [TagW-1:0] tag_at_out;
  logic            back_at_out;
  rc_delay_ram #(.Width(TagW + 1), .Cycles(TimeOut - 2)) u_dly_tag (
    .clk_i, .rst_ni, .data_i({tag_q, back_q}), .data_o({tag_at_out, back_at_out})
  );

  // Two cycles of each stream: x two cycles back, y one, z now.
  localparam int unsigned SerW = 5 * W + W + 1;
  logic [SerW-1:0] ser, ser_d1_q, ser_d2_q;
  assign ser = {p_at_t, n_at_t, v_at_t, r_at_t, refr_s, wx_at_t, wok_at_t};
  always_ff @(posedge clk_i) begin
    ser_d1_q <= ser;
    ser_d2_q <= ser_d1_q;
  end

  // Each stream's three components (x two cycles back) in a vector port's layout, k = 0 .. 4: p,
  // n, v, r, refr.
  logic [5*3*W-1:0] vecs;
  for (genvar k = 0; k < 5; k++) begin : g_vec
    assign vecs[(4-k)*3*W +: 3*W] = {ser[SerW-1-k*W -: W], ser_d1_q[SerW-1-k*W -: W],
                                     ser_d2_q[SerW-1-k*W -: W]};
  end

  logic [OutW-1:0] out_d;
  assign out_d = {tag_at_out, back_at_out, vecs, ser_d2_q[W:1], ser_d1_q[W:1], ser_d2_q[0],
                  ser_d1_q[0]};

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
    .wr_data_i (out_d),
    .valid_o,
    .ready_i,
    .data_o    ({tag_o, back_o, p_o, n_o, v_o, r_o, refr_o, w_mirror_o, w_refract_o, mirror_o,
                 refract_o})
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

  // Each operation's result leaves at the time the schedule above gives it: the valid chains of
  // the fp units agree with the stream starts, so no value is read at the wrong cycle.
  Schedule_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               tdgn_vld == (strm[TimeV] | strm[TimeGn]) &&
                               vev_vld == (strm[TimeV] | strm[TimeGn]) &&
                               pt_vld == (strm[TimeP] | strm[TimeT]) && nv_vld == strm[TimeNv] &&
                               s01_vld == at[TimeS01] && c_vld == at[TimeC] &&
                               k_vld == at[TimeK] &&
                               sa_vld == (at[TimeS] | at[TimeQ] | at[TimeG]) &&
                               knx_vld == (strm[TimeKn] | at[TimeX]) &&
                               r_vld == strm[TimeR] &&
                               wm5_vld == (at[Lm] | at[Lm + 1] | strm[TimeC + Lm]) &&
                               sq_vld == at[TimeSq]);
  // At most one user of the shared adder in a cycle (the phases keep them apart).
  OneUser_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              $onehot0({at[TimeC + Lm], at[TimeX], at[TimeSq]}));
  // ready_o must be known once out of reset (upstream acts on it).
  ReadyKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !$isunknown(ready_o));
`endif

endmodule
