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
//   Every operation is the format's (rc_fp_mul, rc_fp_add, and the square root of rc_fp_sqrt,
//   made by rc_fp_sqrt_iter), in exactly this order and with these operands.
// - Structure: component-serial. A taken hit waits in an input register for three cycles
//   (slots 0, 1, 2) while its x, y and z enter the vector operations, one component a cycle;
//   every vector value then travels as a stream of three consecutive components and every scalar
//   as one value at a fixed cycle. A scalar that a vector operation needs (t, inv_len, the
//   mirror term's c + c, the refraction term's g) is held for the three cycles of the stream by
//   a register loaded in the stream's first cycle (c + c's before it). Hits are taken at phase 0
//   modulo Period, a multiple of 6 (rc_serial_sched, Phased), so operations whose cycles fall at
//   different phases share an operator and no two hits meet there: every product (the streams
//   t * d, d * inv_len, N * V, (c + c) * N, g * N and e * V; the two weights; c * c, e * e and
//   e * c in consecutive cycles; e^2 (1 - c^2)) is a user of one pool of multipliers
//   (rc_fp_pool), and every sum (the streams o + t d, V - (c + c) N and e V - g N; N.V's x + y
//   and + z; 1 - c * c, q = 1 - x and g) of one pool of adders, which place each user on the first
//   operator whose users' phases modulo Period it does not meet: 5 multipliers and 4 adders at
//   Period 6, 3 and 3 at 12 (e * V issued ShiftE cycles after V leaves and (c + c) * N ShiftK
//   cycles after c + c, both off the path to the output, and N.V's + z WaitZ cycles after its x +
//   y: the times below). Each pool has an input register before every operator (rc_fp_pool InReg),
//   so an operand's select and the operator's first stage are in different cycles: a product takes
//   Lm = [fp_stages] mul + 1 cycles, a sum La = add + 1. c + c is rc_fp_twice (exact doubling, a
//   cycle). Each value reaches its operation through rc_delay lines (rc_delay_ram memories where
//   they are long) of the lengths these latencies give (the times below, in cycles after slot 0),
//   so a stream's timing never depends on its neighbours: a hit may follow another after Period
//   cycles or after any gap (rc_serial_sched keeps the slots and says which job time is now). The
//   last stage collects each stream's three components into the output FIFO.
// - Handshake: valid_i/ready_o in, valid_o/ready_i out, with backpressure. An operation is taken
//   when valid_i & ready_o. ready_o is the AND of two flip-flops (rc_credit_fifo's credit
//   register and the input register's free flag) and never depends on valid_i or ready_i;
//   valid_o never depends on ready_i. Results leave in order; nothing is dropped or duplicated.
//   tag_i travels with the operation to tag_o.
// - Latency: TimeT + 4 cycles from the taking cycle to valid_o when the FIFO is empty and ready_i
//   is 1 (84 at the default fp_stages: mul 4, add 6, sqrt 10, so Lm = 5, La = 7): input register
//   1, then the chain V (Lm), N.V (Lm, a cycle for y, La for x + y, WaitZ = 2, La for + z: the
//   sum c), c * c (Lm), 1 - c * c (La), e^2 (1 - c^2) (Lm), q (La), sqrt(q) (10), g (La), g * N
//   (Lm), e * V - g * N (La) (TimeT = 80 after slot 0), two cycles for the stream's y and z, the
//   FIFO's output register 1.
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
  // Every product and sum is an operation of a pool (rc_fp_pool, InReg): the pool's input
  // register, then the operator, so its latency is the operator's ([fp_stages]) plus one.
  localparam int unsigned Lm = rc_pkg::FpStagesMul + 1;
  localparam int unsigned La = rc_pkg::FpStagesAdd + 1;
  localparam int unsigned Ls = rc_pkg::FpStagesSqrt;

  // The cycle (after slot 0) at which each value, or a stream's x, leaves its operation.
  localparam int unsigned TimeV   = Lm;                // V = d * inv_len; also t * d
  localparam int unsigned TimeP   = TimeV + La;        // P = o + t * d
  localparam int unsigned TimeNv  = TimeV + Lm;        // N * V, per component
  localparam int unsigned TimeS01 = TimeNv + 1 + La;   // N.x V.x + N.y V.y (issued with y)
  // N.V's + z is issued WaitZ cycles after x + y leaves (on the path to the output: two cycles of
  // latency, for the pools' counts below).
  localparam int unsigned WaitZ   = 2;
  localparam int unsigned TimeC   = TimeS01 + WaitZ + La; // c
  localparam int unsigned TimeK   = TimeC + 1;         // c + c (rc_fp_twice)
  // (c + c) * N is issued ShiftK cycles after c + c leaves, and e * V ShiftE cycles after V
  // leaves (TimeEv): both off the path to the output, placed where the pools need fewer
  // operators (with WaitZ: 3 multipliers and 3 adders at Period 12, 5 and 4 at 6, at the default
  // fp stages, as a search over these three found; all three at 0, 5 and 4, 9 and 6; the results
  // then wait). 1 <= ShiftK and ShiftK + 2 <= 6: the stream reads c + c from the register loaded
  // at TimeK, which the next job's c + c overwrites 6 cycles later at 6.
  localparam int unsigned ShiftK  = 1;
  localparam int unsigned ShiftE  = 3;
  localparam int unsigned TimeEv  = TimeV + ShiftE;    // e * V issued
  localparam int unsigned TimeKi  = TimeK + ShiftK;    // (c + c) * N issued
  localparam int unsigned TimeKn  = TimeKi + Lm;       // (c + c) * N
  localparam int unsigned TimeR   = TimeKn + La;       // R = V - (c + c) N
  localparam int unsigned TimeS   = TimeC + Lm + La;   // 1 - c * c
  localparam int unsigned TimeX   = TimeS + Lm;        // e^2 * (1 - c^2)
  localparam int unsigned TimeQ   = TimeX + La;        // q
  localparam int unsigned TimeSq  = TimeQ + Ls;        // sqrt(q)
  localparam int unsigned TimeG   = TimeSq + La;       // g = e c + sqrt(q)
  localparam int unsigned TimeGn  = TimeG + Lm;        // g * N (e * V waits for it)
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
  // The periods its schedule is tested at (rc_fp_pool would place its users at any period; the
  // unit's timing tests and the lit core run it at these two).
  if (Period != 6 && Period != 12) begin : g_period_check
    $error("rc_hit_geom: Period must be 6 or 12");
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

  // The input register (no reset: slot_q says when it holds a hit) loads in every cycle the
  // unit is ready, taken or not: the hit before no longer needs it then (a take would
  // overwrite it too), so the enable is ready_o's two flip-flops, not valid_i's net.
  logic [TagW-1:0] tag_q;
  logic [3*W-1:0]  org_q, dir_q, n_q;
  logic [W-1:0]    ilen_q, t_q, eta_enter_q, eta_leave_q, w_q, mirror_q, transmit_q;
  logic            back_q;

  always_ff @(posedge clk_i) begin
    if (ready_o) begin
      tag_q       <= tag_i;
      org_q       <= org_i;
      dir_q       <= dir_i;
      n_q         <= n_i;
      ilen_q      <= inv_len_i;
      t_q         <= t_i;
      back_q      <= pos(dz_i);
      eta_enter_q <= eta_enter_i;
      eta_leave_q <= eta_leave_i;
      w_q         <= w_i;
      mirror_q    <= mirror_i;
      transmit_q  <= transmit_i;
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

  // A scalar held for its stream's three cycles: the value in the first, then a register's (c
  // and g); c + c from its register only, its stream starting ShiftK cycles after it leaves.
  logic [W-1:0] k_res, k_hold_q, k_b;
  logic [W-1:0] c_res, c_hold_q, c_b;
  logic [W-1:0] g_res, g_hold_q, g_b;

  assign k_b = k_hold_q;  // read from TimeKi = TimeK + ShiftK on
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

  // t * d and V = d * inv_len: in u_muls (below); o + t d in u_adds (below).
  rc_delay #(.Width(W), .Cycles(TimeV)) u_dly_o (.clk_i, .data_i(o_s), .data_o(o_d));

  // The facing normal's stream, tapped where the operations need it.
  logic [W-1:0] n_at_v, n_at_k, n_at_g, n_at_t;
  rc_delay #(.Width(W), .Cycles(TimeV)) u_dly_n0 (.clk_i, .data_i(nf_s), .data_o(n_at_v));
  rc_delay_ram #(.Width(W), .Cycles(TimeKi - TimeV)) u_dly_n1 (
    .clk_i, .rst_ni, .data_i(n_at_v), .data_o(n_at_k)
  );
  rc_delay_ram #(.Width(W), .Cycles(TimeG - TimeKi)) u_dly_n2 (
    .clk_i, .rst_ni, .data_i(n_at_k), .data_o(n_at_g)
  );
  rc_delay #(.Width(W), .Cycles(TimeT - TimeG)) u_dly_n3 (
    .clk_i, .data_i(n_at_g), .data_o(n_at_t)
  );
  assign n_dv = n_at_v;

  // c = (N.x V.x + N.y V.y) + N.z V.z: N * V in u_muls, x + y as y's product leaves (x's a
  // cycle later), then + z WaitZ cycles after x + y leaves (z's product La - 1 + WaitZ cycles
  // later), both in u_adds.
  logic [W-1:0] nv, nv_d1, nv_dz, s01, s01_d;
  rc_delay #(.Width(W), .Cycles(1)) u_dly_nvx (.clk_i, .data_i(nv), .data_o(nv_d1));
  rc_delay #(.Width(W), .Cycles(La - 1 + WaitZ)) u_dly_nvz (
    .clk_i, .data_i(nv), .data_o(nv_dz)
  );
  rc_delay #(.Width(W), .Cycles(WaitZ)) u_dly_s01 (.clk_i, .data_i(s01), .data_o(s01_d));

  //////////////////////////////////////
  // R = V - (c + c) N                //
  //////////////////////////////////////

  logic [W-1:0] kn, v_at_kn, r_s, v_at_g;
  logic         k_vld;

  // c + c: exact doubling (rc_fp_twice, x + x bit for bit), a cycle.
  rc_fp_twice #(.ExpW(ExpW), .FracW(FracW)) u_twice_k (
    .clk_i, .rst_ni, .valid_i(at[TimeC]), .x_i(c_res), .valid_o(k_vld), .res_o(k_res)
  );

  // (c + c) * N: in u_muls; V - (c + c) N: in u_adds.
  rc_delay_ram #(.Width(W), .Cycles(TimeKn - TimeV)) u_dly_v0 (
    .clk_i, .rst_ni, .data_i(v_s), .data_o(v_at_kn)
  );
  rc_delay_ram #(.Width(W), .Cycles(TimeG - TimeKn)) u_dly_v1 (
    .clk_i, .rst_ni, .data_i(v_at_kn), .data_o(v_at_g)
  );

  ////////////////////////////////////////////////////////////
  // Refraction: q = 1 - e^2 (1 - c^2), T = e V - g N       //
  ////////////////////////////////////////////////////////////

  // e (one of the input register's two ratios, chosen by back_q after the register: the ratios
  // come from across the die, and back_q's compare is not on their way in) as a stream: at slot
  // k the register holds it, so a delay line of T gives it at T, T + 1, T + 2.
  logic [W-1:0] eta, e_at_ev, e_at_c;
  assign eta = back_q ? eta_leave_q : eta_enter_q;
  rc_delay #(.Width(W), .Cycles(TimeEv)) u_dly_e0 (.clk_i, .data_i(eta), .data_o(e_at_ev));
  rc_delay_ram #(.Width(W), .Cycles(TimeC - TimeEv)) u_dly_e1 (
    .clk_i, .rst_ni, .data_i(e_at_ev), .data_o(e_at_c)
  );

  // One user of u_muls: c * c at TimeC, e * e at TimeC + 1, e * c at TimeC + 2.
  logic [W-1:0] m5_a, m5_b, m5, e2_d, ec_d, s_res, x_res, q_res, sq_res;
  logic         sq_vld;
  assign m5_a = at[TimeC] ? c_b : e_at_c;
  assign m5_b = at[TimeC + 1] ? e_at_c : c_b;

  // e^2 (1 - c^2) (at TimeS): in u_muls; 1 - c * c (at TimeC + Lm), 1 - x (at TimeX) and
  // g = e c + sqrt(q) (at TimeSq): in u_adds.
  rc_delay #(.Width(W), .Cycles(TimeS - (TimeC + 1 + Lm))) u_dly_e2 (
    .clk_i, .data_i(m5), .data_o(e2_d)
  );
  // One root a job: an iterative one (rc_fp_sqrt_iter, a lane busy 8 cycles) with one lane at a
  // job per 12 cycles, two at 6 (any two roots then come at least 12 cycles apart).
  rc_fp_sqrt_iter #(
    .ExpW(ExpW), .FracW(FracW), .Stages(Ls), .Lanes((Period >= 12) ? 1 : 2)
  ) u_sqrt (
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

  // g * N (at TimeG) and e * V (at TimeEv, waiting for g * N): in u_muls; e V - g N (at TimeGn):
  // in u_adds.
  logic [W-1:0] gn, ev, ev_d, t_s, v_at_ev;
  rc_delay #(.Width(W), .Cycles(ShiftE)) u_dly_vev (.clk_i, .data_i(v_s), .data_o(v_at_ev));
  rc_delay_ram #(.Width(W), .Cycles(TimeG - TimeEv)) u_dly_ev (
    .clk_i, .rst_ni, .data_i(ev), .data_o(ev_d)
  );

  //////////////////////////////////////
  // Weights                          //
  //////////////////////////////////////

  // w * mirror at slot 0, w * transmit at slot 1; each with lt(0, factor) beside it.
  logic [W-1:0] wf_s, wx, wx_at_t;
  logic         fpos_s, fpos_d, wok, wok_at_t;
  assign wf_s   = slot_q[1] ? transmit_q : mirror_q;
  assign fpos_s = pos(wf_s);
  // The weights (slots 0 and 1): in u_muls.
  rc_delay #(.Width(1), .Cycles(Lm)) u_dly_fpos (.clk_i, .data_i(fpos_s), .data_o(fpos_d));
  assign wok = fpos_d & pos(wx);
  rc_delay_ram #(.Width(W + 1), .Cycles(TimeT - Lm)) u_dly_w (
    .clk_i, .rst_ni, .data_i({wok, wx}), .data_o({wok_at_t, wx_at_t})
  );

  //////////////////////////////////////
  // The operators                    //
  //////////////////////////////////////

  // Every product, a user of one pool of multipliers at its time (three cycles for a stream, two
  // for the weights, one for a scalar), and every sum, a user of one pool of adders; each result
  // is read at its own time.
  localparam int unsigned MulUsers = 9;
  localparam logic [511:0] MulTimes  = 512'({16'(TimeEv), 16'(TimeG), 16'(TimeS), 16'(TimeKi),
                                              16'(TimeC), 16'(TimeV), 16'(0), 16'(0), 16'(0)});
  localparam logic [63:0]  MulCycles = 64'({2'd3, 2'd3, 2'd1, 2'd3, 2'd3, 2'd3, 2'd2, 2'd3,
                                            2'd3});
  logic [MulUsers-1:0]   mul_issue, mul_vld;
  logic [MulUsers*W-1:0] mul_a, mul_b, mul_res;
  // e * V, g * N, e^2 (1 - c^2), (c + c) * N, c * c | e * e | e * c, N * V, the weights,
  // d * inv_len, t * d.
  assign mul_issue = {strm[TimeEv], strm[TimeG], at[TimeS], strm[TimeKi], strm[TimeC],
                      strm[TimeV], slot_q[0] | slot_q[1], strm[0], strm[0]};
  assign mul_a     = {e_at_ev, g_b, e2_d, k_b, m5_a, n_dv, w_q, d_s, t_q};
  assign mul_b     = {v_at_ev, n_at_g, s_res, n_at_k, m5_b, v_s, wf_s, ilen_q, d_s};
  rc_fp_pool #(
    .ExpW(ExpW), .FracW(FracW), .Users(MulUsers), .Period(Period), .Time(MulTimes),
    .Cycles(MulCycles), .InReg(1'b1)
  ) u_muls (
    .clk_i, .rst_ni, .issue_i(mul_issue), .a_i(mul_a), .b_i(mul_b), .valid_o(mul_vld),
    .res_o(mul_res)
  );
  assign {ev, gn, x_res, kn, m5, nv, wx, v_s, td} = mul_res;

  localparam int unsigned AddUsers = 8;
  localparam logic [511:0] AddTimes  = 512'({16'(TimeS01 + WaitZ), 16'(TimeNv + 1), 16'(TimeSq),
                                              16'(TimeX), 16'(TimeC + Lm), 16'(TimeKn),
                                              16'(TimeGn), 16'(TimeV)});
  localparam logic [63:0]  AddCycles = 64'({2'd1, 2'd1, 2'd1, 2'd1, 2'd1, 2'd3, 2'd3, 2'd3});
  logic [AddUsers-1:0]   add_issue, add_vld;
  logic [AddUsers*W-1:0] add_a, add_b, add_res;
  // N.V's + z and x + y, g = e c + sqrt(q), q = 1 - x, 1 - c * c, R = V - (c + c) N,
  // e V - g N, P = o + t d.
  assign add_issue = {at[TimeS01 + WaitZ], at[TimeNv + 1], at[TimeSq], at[TimeX], at[TimeC + Lm],
                      strm[TimeKn], strm[TimeGn], strm[TimeV]};
  assign add_a     = {s01_d, nv_d1, ec_d, One, One, v_at_kn, ev_d, o_d};
  assign add_b     = {nv_dz, nv, sq_res, x_res, m5, kn, gn, td};
  rc_fp_pool #(
    .ExpW(ExpW), .FracW(FracW), .Add(1'b1), .Users(AddUsers), .Sub(32'b00011110),
    .Period(Period), .Time(AddTimes), .Cycles(AddCycles), .InReg(1'b1)
  ) u_adds (
    .clk_i, .rst_ni, .issue_i(add_issue), .a_i(add_a), .b_i(add_b), .valid_o(add_vld),
    .res_o(add_res)
  );
  assign {c_res, s01, g_res, q_res, s_res, r_s, t_s, p_s} = add_res;

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
                               k_vld == at[TimeK] && sq_vld == at[TimeSq]);
  // Every product and sum leaves its operator when its user reads it (the pools' valid chains,
  // which also carry the other users' results on the same operator).
  logic [MulUsers-1:0] mul_due;
  logic [AddUsers-1:0] add_due;
  assign mul_due = {strm[TimeEv + Lm], strm[TimeGn], at[TimeX], strm[TimeKn], strm[TimeC + Lm],
                    strm[TimeNv], at[Lm] | at[Lm + 1], strm[TimeV], strm[TimeV]};
  assign add_due = {at[TimeC], at[TimeS01], at[TimeG], at[TimeQ], at[TimeS], strm[TimeR],
                    strm[TimeT], strm[TimeP]};
  Results_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              (mul_due & ~mul_vld) == '0 && (add_due & ~add_vld) == '0);
  // ready_o must be known once out of reset (upstream acts on it).
  ReadyKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !$isunknown(ready_o));
`endif

endmodule
