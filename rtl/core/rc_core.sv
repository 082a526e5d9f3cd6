// rc_core: the ray tracing core. Traces four-ray packets through the kd-tree of a memory image and
// shades their closest hits, exactly by the rules of docs/architecture.md (rc::trace_packet() and
// rc::shade() of tb/golden/trace.hpp), with up to Threads packets in flight.
//
// Contract
// - Configuration inputs (bounds_i, *_count_i, root_node_i, ambient_i, diffuse_i, background_i)
//   are quasi-static: change them only while idle_o is 1 and no packet is offered.
//   bounds_i: the header's root box (lo x, y, z, hi x, y, z); node/list/tri_count_i: the record
//   counts of those sections (the core's malformed-node and bad-address checks use them);
//   root_node_i: node 0's record (zero when the node section is empty; this core fetches node 0
//   through the node port and does not use it); ambient_i/diffuse_i: the format values of
//   ambient and 1 - ambient; background_i: the miss colour, R [7:0], G [15:8], B [23:16].
// - Packet input: valid/ready. pkt_mask_i bit r: ray r exists. Per ray r: origin and direction
//   component a at [(3r + a)*W +: W], inv_len at [r*W +: W], pixel id at [r*32 +: 32]. A packet
//   is taken when a thread is free and the ray set-up feeder is idle; its rays then pass ray
//   set-up one per 3 cycles, in order 0..3 (absent rays too; their results are masked).
// - Framebuffer write port: valid/ready, one write per existing ray of every packet, in no
//   particular order: fb_pixel_o (the ray's pixel id), fb_rgb_o, and the ray's hit record
//   (fb_hit_o, fb_tri_o, fb_t_o, fb_u_o, fb_v_o; zero on a miss). A packet that met an error
//   writes the background with no hit for every ray.
// - Memory ports node_, list_, tri_, shd_, mat_: the protocol of docs/architecture.md ("Memory
//   ports"): request (index, tag) and response (tag, data, error) handshakes, responses in any
//   order after any delay. Records: node NodeRspW (128) bits, a pair: a request for node i
//   answers record i at [63:0] and record i + 1 at [127:64] (zero when i is the last node;
//   rc_pkg::CoreNodeRspRecords records of 64 bits), rsp_error only when i itself is outside the
//   section; this core uses record i only. List entry 32, triangle 12*W, shading record
//   32 + 4*W, material 96 (the material record's kd field: three 32-bit slots). Tags are
//   CoreTagBits wide; the core never has two requests with the same tag outstanding on a port.
// - Debug: dbg_thread_state_o, every thread's state (rc_pkg::thread_state_e, 4 bits per thread).
// - Status: idle_o = no packet in flight and no write pending. error_o (sticky until reset):
//   CoreStatus* bits: malformed node, bad address (also any error response), stack overflow,
//   watchdog (work held and no handshake completed for WatchdogCycles cycles; error_o shows it
//   from the edge WatchdogCycles + 2 after the last handshake's: the handshakes reach the count
//   through two register levels).
// - Performance counters: perf_o = counter number perf_sel_i (CoreStatus/CorePerf* of rc_pkg),
//   combinational from registers; numbers >= CorePerfCount read 0. The counters count an event
//   one cycle after it (registered increments): read them from the cycle after idle_o rises on.
// - Handshakes: valid never depends on ready on any port; a valid with its payload stays until
//   taken.
// - Latency and throughput: not fixed; a packet takes as long as its walk through the tree (ray
//   set-up, then per node a memory round trip plus a traversal step, per leaf its list and
//   triangle reads and tests, then shading). Packets are taken at least 11 cycles apart, one
//   per 12 cycles at most while they follow back to back (ray set-up takes one ray per 3 cycles,
//   and the next packet is taken once ray 3 of the one before has entered it); Threads packets
//   are in flight; the intersection unit tests one ray-triangle pair every IsectInterval cycles
//   (2, the default: one transform unit used twice; 1: two transform units, more area);
//   framebuffer writes leave at up to one per cycle. Every memory response asked
//   for is taken eventually (rsp_ready may be low for a while, never for ever).
// - Illegal input: configuration changes while busy; a response with a tag that is not
//   outstanding, or two responses for one request (assertions catch both).
// - Reset: rst_ni, active low, asynchronous; clears all control state.
module rc_core #(
  parameter int unsigned ExpW           = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW          = rc_pkg::Fp24FracW,
  parameter int unsigned Threads        = rc_pkg::CoreThreads,
  parameter int unsigned StackDepth     = rc_pkg::KdtreeStackDepth,
  parameter int unsigned ListTags       = rc_pkg::CoreListTags,
  parameter int unsigned WatchdogCycles = rc_pkg::CoreWatchdogCycles,
  parameter int unsigned IsectInterval  = rc_pkg::CoreIsectInterval,
  // Derived (do not override).
  parameter int unsigned W              = 1 + ExpW + FracW,
  parameter int unsigned TagW           = rc_pkg::CoreTagBits,
  parameter int unsigned StatusW        = rc_pkg::CoreStatusBits,
  parameter int unsigned NodeRecW       = 8 * rc_pkg::KdNodeBytes,  // one node record
  parameter int unsigned NodeRspW       = rc_pkg::CoreNodeRspRecords * NodeRecW  // node response
) (
  input  logic              clk_i,
  input  logic              rst_ni,

  // Configuration (quasi-static).
  input  logic [6*W-1:0]    bounds_i,
  input  logic [31:0]       node_count_i,
  input  logic [31:0]       list_count_i,
  input  logic [31:0]       tri_count_i,
  input  logic [NodeRecW-1:0] root_node_i,
  input  logic [W-1:0]      ambient_i,
  input  logic [W-1:0]      diffuse_i,
  input  logic [23:0]       background_i,

  // Packet input.
  input  logic              pkt_valid_i,
  output logic              pkt_ready_o,
  input  logic [3:0]        pkt_mask_i,
  input  logic [12*W-1:0]   pkt_org_i,
  input  logic [12*W-1:0]   pkt_dir_i,
  input  logic [4*W-1:0]    pkt_inv_len_i,
  input  logic [127:0]      pkt_pixel_i,

  // Framebuffer write port.
  output logic              fb_valid_o,
  input  logic              fb_ready_i,
  output logic [31:0]       fb_pixel_o,
  output logic [23:0]       fb_rgb_o,
  output logic              fb_hit_o,
  output logic [31:0]       fb_tri_o,
  output logic [W-1:0]      fb_t_o,
  output logic [W-1:0]      fb_u_o,
  output logic [W-1:0]      fb_v_o,

  // Memory port: kd nodes.
  output logic              node_req_valid_o,
  input  logic              node_req_ready_i,
  output logic [TagW-1:0]   node_req_tag_o,
  output logic [31:0]       node_req_index_o,
  input  logic              node_rsp_valid_i,
  output logic              node_rsp_ready_o,
  input  logic [TagW-1:0]   node_rsp_tag_i,
  input  logic [NodeRspW-1:0] node_rsp_data_i,
  input  logic              node_rsp_error_i,

  // Memory port: leaf lists.
  output logic              list_req_valid_o,
  input  logic              list_req_ready_i,
  output logic [TagW-1:0]   list_req_tag_o,
  output logic [31:0]       list_req_index_o,
  input  logic              list_rsp_valid_i,
  output logic              list_rsp_ready_o,
  input  logic [TagW-1:0]   list_rsp_tag_i,
  input  logic [31:0]       list_rsp_data_i,
  input  logic              list_rsp_error_i,

  // Memory port: triangles (unit-triangle transforms).
  output logic              tri_req_valid_o,
  input  logic              tri_req_ready_i,
  output logic [TagW-1:0]   tri_req_tag_o,
  output logic [31:0]       tri_req_index_o,
  input  logic              tri_rsp_valid_i,
  output logic              tri_rsp_ready_o,
  input  logic [TagW-1:0]   tri_rsp_tag_i,
  input  logic [12*W-1:0]   tri_rsp_data_i,
  input  logic              tri_rsp_error_i,

  // Memory port: shading records.
  output logic              shd_req_valid_o,
  input  logic              shd_req_ready_i,
  output logic [TagW-1:0]   shd_req_tag_o,
  output logic [31:0]       shd_req_index_o,
  input  logic              shd_rsp_valid_i,
  output logic              shd_rsp_ready_o,
  input  logic [TagW-1:0]   shd_rsp_tag_i,
  input  logic [32+4*W-1:0] shd_rsp_data_i,
  input  logic              shd_rsp_error_i,

  // Memory port: materials (kd).
  output logic              mat_req_valid_o,
  input  logic              mat_req_ready_i,
  output logic [TagW-1:0]   mat_req_tag_o,
  output logic [31:0]       mat_req_index_o,
  input  logic              mat_rsp_valid_i,
  output logic              mat_rsp_ready_o,
  input  logic [TagW-1:0]   mat_rsp_tag_i,
  input  logic [95:0]       mat_rsp_data_i,
  input  logic              mat_rsp_error_i,

  // Status and counters.
  output logic              idle_o,
  output logic [StatusW-1:0] error_o,
  input  logic [7:0]        perf_sel_i,
  output logic [63:0]       perf_o,

  // Debug: every thread's state (thread t at [4t +: 4], rc_pkg::thread_state_e), for the
  // harness's hang reports and waveforms; no logic depends on it.
  output logic [Threads*rc_pkg::ThreadStateBits-1:0] dbg_thread_state_o
);


  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned ThrW    = (Threads > 1) ? $clog2(Threads) : 1;
  localparam int unsigned RidW    = ThrW + 2;                    // ray id {thread, ray}
  localparam int unsigned NodeW   = rc_pkg::KdNodeIndexBits;
  localparam int unsigned SpW     = $clog2(StackDepth + 1);      // holds 0 .. StackDepth
  localparam int unsigned SpIdxW  = (StackDepth > 1) ? $clog2(StackDepth) : 1;
  localparam int unsigned StkAW   = $clog2(Threads * StackDepth);  // stack RAM address
  localparam int unsigned EntryW  = NodeW + 4 + 8 * W;           // stack entry
  localparam int unsigned LtW     = (ListTags > 1) ? $clog2(ListTags) : 1;
  localparam int unsigned NPerf   = rc_pkg::CorePerfCount;

  if (Threads < 1 || Threads > rc_pkg::CoreMaxThreads || RidW > TagW || LtW > TagW ||
      ThrW + 3 > 16 || StackDepth < 1 || (1 << SpIdxW) != StackDepth || ListTags < 2 ||
      W > 32 || FracW < 7 || WatchdogCycles < 2 || IsectInterval < 1 ||
      IsectInterval > 2) begin : g_param_check
    $error("rc_core: need 1 <= Threads <= CoreMaxThreads, StackDepth a power of two, ListTags >= 2 and at most 2^TagW, an fp format of at most 32 bits with FracW >= 7, IsectInterval 1 or 2");
  end

  // Thread states (one per thread; exactly one unit owns a thread at a time): the enum
  // rc_pkg::thread_state_e, generated from docs/spec.toml [thread_state].
  localparam logic [3:0] StFree    = rc_pkg::StFree;     // no packet
  localparam logic [3:0] StSetup   = rc_pkg::StSetup;    // rays in ray set-up
  localparam logic [3:0] StFetch   = rc_pkg::StFetch;    // waiting to fetch its current node
  localparam logic [3:0] StNode    = rc_pkg::StNode;     // node requested, or in the sub-units
  localparam logic [3:0] StLeaf    = rc_pkg::StLeaf;     // leaf waiting for the list unit
  localparam logic [3:0] StLeafRun = rc_pkg::StLeafRun;  // leaf triangles in the list/isect units
  localparam logic [3:0] StPop     = rc_pkg::StPop;      // waiting to pop
  localparam logic [3:0] StPopping = rc_pkg::StPopping;  // chosen to pop: stack read, entry culled
  localparam logic [3:0] StDone    = rc_pkg::StDone;     // traced, waiting for shading
  localparam logic [3:0] StShade   = rc_pkg::StShade;    // rays in shading / framebuffer writes

  localparam logic [W-1:0] FpInf = {1'b0, {ExpW{1'b1}}, {FracW{1'b0}}};
  localparam int unsigned  ErrMalformed = rc_pkg::CoreStatusMalformedNode;
  localparam int unsigned  ErrBadAddr   = rc_pkg::CoreStatusBadAddress;
  localparam int unsigned  ErrOverflow  = rc_pkg::CoreStatusStackOverflow;
  localparam int unsigned  ErrWatchdog  = rc_pkg::CoreStatusWatchdog;

  //////////////////////////
  // Per-thread state     //
  //////////////////////////

  // Control state with reset, as flat vectors (thread t at [t*X +: X]).
  // st_q is also the debug port dbg_thread_state_o (the harness's hang reports print it).
  logic [Threads*4-1:0]   st_q;
  logic [Threads*4-1:0]   st_d;
  logic [Threads*4-1:0]   mask_q, mask_d;      // active rays of the current entry
  logic [Threads*4-1:0]   vmask_q, vmask_d;    // rays that exist
  logic [Threads*4-1:0]   bhit_q, bhit_d;      // ray has a hit
  logic [Threads*SpW-1:0] sp_q, sp_d;          // stack entries
  logic [Threads*3-1:0]   err_q, err_d;        // error bits 0..2
  logic [Threads*3-1:0]   fbw_q, fbw_d;        // framebuffer writes still due
  logic [Threads*4-1:0]   serr_q, serr_d;      // shading-side memory error per ray

  // Data arrays (no reset; RAM-friendly: whole-word writes, one word per thread).
  logic [12*W-1:0]   org_m  [0:Threads-1];     // ray r component a at [(3r+a)*W +: W]
  logic [12*W-1:0]   dir_m  [0:Threads-1];
  logic [12*W-1:0]   inv_m  [0:Threads-1];
  logic [4*W-1:0]    ilen_m [0:Threads-1];
  logic [127:0]      pix_m  [0:Threads-1];
  logic [NodeW-1:0]  node_m [0:Threads-1];     // current node
  logic [4*W-1:0]    tmin_m [0:Threads-1];     // current intervals
  logic [4*W-1:0]    tmax_m [0:Threads-1];
  logic [11:0]       dsign_m [0:Threads-1];    // sign bits of dir_m (ray r axis a at 3r + a)
  logic [31:0]       loff_m [0:Threads-1];     // leaf list offset and count
  logic [31:0]       lcnt_m [0:Threads-1];
  logic [4*W-1:0]    bt_m   [0:Threads-1];     // best hits
  logic [4*W-1:0]    bu_m   [0:Threads-1];
  logic [4*W-1:0]    bv_m   [0:Threads-1];
  logic [4*W-1:0]    bdz_m  [0:Threads-1];
  logic [127:0]      btri_m [0:Threads-1];
  logic [W-1:0]      nlen_m [0:Threads*4-1];   // |n| of the hit triangle, per ray id
  // The stack: thread t's entry at depth k (1 .. StackDepth, the stack pointer after its push)
  // in slot {t, k mod StackDepth}, so a pop reads at the pointer itself (no subtraction). A
  // thread never pushes and pops in one cycle, so a read never meets a write to its slot
  // (no_rw_check: no collision logic around the block RAM).
  (* no_rw_check *)
  logic [EntryW-1:0] stack_m [0:Threads*StackDepth-1];

  // The state vectors of the schedulers.
  logic [Threads-1:0] free_vec, fetch_vec, leaf_vec, pop_vec, done_vec;
  // The schedulers' choices act on the thread states a cycle after they are made, from their
  // registered one-hot grants (below, "Thread state").
  logic [Threads-1:0] h_acc, h_fe, h_lp, h_pe, h_sx;
  always_comb begin
    for (int unsigned t = 0; t < Threads; t++) begin
      free_vec[t]  = st_q[t*4 +: 4] == StFree;
      fetch_vec[t] = st_q[t*4 +: 4] == StFetch;
      leaf_vec[t]  = st_q[t*4 +: 4] == StLeaf;
      pop_vec[t]   = st_q[t*4 +: 4] == StPop;
      done_vec[t]  = st_q[t*4 +: 4] == StDone;
    end
  end

  // Fields of the flat per-thread control vectors (thread t at [t*X +: X]), read through loops
  // over the threads: a decoder and one 2:1 multiplexer per bit (they are written per thread, in
  // the thread state update below). A variable part-select (v[i*X +: X]) is the same function,
  // but Yosys 0.23 builds it as a shifter of the whole vector by i*X, data and mask, which cost
  // this module tens of thousands of LUT4s.
  function automatic logic [3:0] get4(input logic [Threads*4-1:0] v, input logic [ThrW-1:0] i);
    get4 = '0;
    for (int unsigned t = 0; t < Threads; t++) if (i == ThrW'(t)) get4 = v[t*4 +: 4];
  endfunction
  // The same through a one-hot thread vector (a registered grant): an AND-OR over the threads.
  function automatic logic [3:0] sel4(input logic [Threads*4-1:0] v,
                                      input logic [Threads-1:0] onehot);
    sel4 = '0;
    for (int unsigned t = 0; t < Threads; t++) sel4 = sel4 | ({4{onehot[t]}} & v[t*4 +: 4]);
  endfunction
  function automatic logic [2:0] get3(input logic [Threads*3-1:0] v, input logic [ThrW-1:0] i);
    get3 = '0;
    for (int unsigned t = 0; t < Threads; t++) if (i == ThrW'(t)) get3 = v[t*3 +: 3];
  endfunction
  function automatic logic [SpW-1:0] getsp(input logic [Threads*SpW-1:0] v,
                                           input logic [ThrW-1:0] i);
    getsp = '0;
    for (int unsigned t = 0; t < Threads; t++) if (i == ThrW'(t)) getsp = v[t*SpW +: SpW];
  endfunction

  // Lane i (a ray, 0..3) of a four-ray vector: selected and replaced through loops, a 4:1
  // multiplexer per bit (a variable part-select v[i*X +: X] becomes a shifter in Yosys 0.23).
  function automatic logic [W-1:0] lane_w(input logic [4*W-1:0] v, input logic [1:0] i);
    lane_w = '0;
    for (int unsigned r = 0; r < 4; r++) if (i == 2'(r)) lane_w = v[r*W +: W];
  endfunction
  function automatic logic [4*W-1:0] put_lane_w(input logic [4*W-1:0] v, input logic [1:0] i,
                                                input logic [W-1:0] x);
    put_lane_w = v;
    for (int unsigned r = 0; r < 4; r++) if (i == 2'(r)) put_lane_w[r*W +: W] = x;
  endfunction
  function automatic logic [3*W-1:0] lane_3w(input logic [12*W-1:0] v, input logic [1:0] i);
    lane_3w = '0;
    for (int unsigned r = 0; r < 4; r++) if (i == 2'(r)) lane_3w = v[r*3*W +: 3*W];
  endfunction
  function automatic logic [12*W-1:0] put_lane_3w(input logic [12*W-1:0] v, input logic [1:0] i,
                                                  input logic [3*W-1:0] x);
    put_lane_3w = v;
    for (int unsigned r = 0; r < 4; r++) if (i == 2'(r)) put_lane_3w[r*3*W +: 3*W] = x;
  endfunction
  function automatic logic [31:0] lane_32(input logic [127:0] v, input logic [1:0] i);
    lane_32 = '0;
    for (int unsigned r = 0; r < 4; r++) if (i == 2'(r)) lane_32 = v[r*32 +: 32];
  endfunction
  function automatic logic [127:0] put_lane_32(input logic [127:0] v, input logic [1:0] i,
                                               input logic [31:0] x);
    put_lane_32 = v;
    for (int unsigned r = 0; r < 4; r++) if (i == 2'(r)) put_lane_32[r*32 +: 32] = x;
  endfunction
  // Component a (an axis, 0..2) of ray r of a four-ray 3-vector [(3r + a)*W +: W]; a = 3 gives
  // 0 (never used: inner nodes have a < 3). The loop stops at the last axis, so no part-select
  // past the vector is elaborated.
  function automatic logic [W-1:0] axis_w(input logic [12*W-1:0] v, input int unsigned r,
                                          input logic [1:0] a);
    axis_w = '0;
    for (int unsigned k = 0; k < 3; k++) begin
      if (a == 2'(k)) axis_w = v[(3*r+k)*W +: W];
    end
  endfunction

  // The sign bits of a four-ray 3-vector, component (3r + a) at bit 3r + a.
  function automatic logic [11:0] dir_signs(input logic [12*W-1:0] v);
    for (int unsigned k = 0; k < 12; k++) dir_signs[k] = v[k*W+W-1];
  endfunction

  function automatic logic [2:0] popcount4(input logic [3:0] m);
    popcount4 = 3'(m[0]) + 3'(m[1]) + 3'(m[2]) + 3'(m[3]);
  endfunction

  // Lowest set bit of a 4-bit mask (0 for an empty mask).
  function automatic logic [1:0] lowest4(input logic [3:0] m);
    if (m[0]) begin
      lowest4 = 2'd0;
    end else if (m[1]) begin
      lowest4 = 2'd1;
    end else if (m[2]) begin
      lowest4 = 2'd2;
    end else begin
      lowest4 = m[3] ? 2'd3 : 2'd0;
    end
  endfunction

  // A ray without a hit has best t = +inf and best triangle = all ones (-1); the best-hit arrays
  // are not reset per packet, their words are valid only where the ray's bhit_q bit is set.
  function automatic logic [4*W-1:0] gate_t(input logic [4*W-1:0] t, input logic [3:0] hit);
    for (int unsigned r = 0; r < 4; r++) gate_t[r*W +: W] = hit[r] ? t[r*W +: W] : FpInf;
  endfunction
  function automatic logic [127:0] gate_tri(input logic [127:0] tri_idx, input logic [3:0] hit);
    for (int unsigned r = 0; r < 4; r++) gate_tri[r*32 +: 32] = hit[r] ? tri_idx[r*32 +: 32] : '1;
  endfunction

  //////////////////
  // Packet input //
  //////////////////

  logic            acc_any, acc_take, acc_v_q;
  logic [ThrW-1:0] acc_thr;
  logic [Threads-1:0] g_acc, gacc_q;
  logic            feed_busy_q;
  logic [ThrW-1:0] feed_thr_q;
  logic [1:0]      feed_r_q;
  logic [12*W-1:0] feed_org_q, feed_dir_q;
  logic [4*W-1:0]  feed_ilen_q;
  logic [127:0]    feed_pix_q;

  rc_rr_pick #(
    .N   (Threads),
    .IdxW(ThrW)
  ) u_pick_free (
    .clk_i,
    .rst_ni,
    .req_i  (free_vec),
    .take_i (acc_take),
    .valid_o(acc_any),
    .idx_o  (acc_thr),
    .grant_o(g_acc)
  );

  // The free-thread choice is registered (acc_any_q, acc_thr_q, gacc_c_q), so ready is a gate of
  // two flip-flops: the choice over the thread states no longer reaches the packet source (the
  // board's ray generator) and the feeder's wide clock enables in its own cycle. A registered
  // choice is still free when it is used: only a take makes a free thread busy, the choice is
  // withdrawn in the cycle after a take, and the feeder stays busy for the packet's four rays
  // (over 11 cycles) while the thread's state catches up. A thread that becomes free is offered
  // a cycle later than the choice sees it.
  logic            acc_any_q;
  logic [ThrW-1:0] acc_thr_q;
  logic [Threads-1:0] gacc_c_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      acc_any_q <= 1'b0;
      acc_thr_q <= '0;
      gacc_c_q  <= '0;
    end else begin
      acc_any_q <= acc_any & ~acc_take;
      acc_thr_q <= acc_thr;
      gacc_c_q  <= g_acc;
    end
  end
  assign pkt_ready_o = acc_any_q & ~feed_busy_q;
  assign acc_take    = pkt_valid_i & pkt_ready_o;

  /////////////////////////////////////////
  // Ray set-up: one ray per 3 cycles    //
  /////////////////////////////////////////

  // The feeder offers the packet's rays 0..3 in turn and rc_ray_setup takes one every 3 cycles.
  // pkt_ready_o returns in the cycle after ray 3 is taken, and ray set-up takes its next ray no
  // earlier than 3 cycles after that take, so a packet waiting at the input loses no set-up
  // cycle (and nothing here assumes the set-up's rate or latency: the handshake paces it).

  logic            su_ready, su_take, su_v, su_active, su_valid, su_out_ready;
  logic            pop2_v;     // a pop result this cycle (the pop section below)
  logic            pop1_v_q;   // a pop result next cycle (the pop section below)
  logic            tq_v_q;     // a traversal result this cycle (the traversal section below)
  logic [3:0]      trav_v_all; // the traversal sub-units' results (the traversal section below)
  logic [RidW:0]   su_tag;      // {ray exists, thread, ray}
  logic [3*W-1:0]  su_org, su_dir, su_inv;
  logic [W-1:0]    su_tmin, su_tmax;
  logic            s0_valid, s0_ready, s0_active;
  logic [RidW:0]   s0_tag;
  logic [3*W-1:0]  s0_inv;
  logic [W-1:0]    s0_tmin, s0_tmax;
  logic [ThrW-1:0] su_thr;
  logic [1:0]      su_r;
  logic [3:0]      su_mask_new, su_mask_base, su_gmask_q, feed_vmask_q;
  logic            su_last;

  // The taken packet is registered here (feed_*_q) and written to the per-thread arrays from
  // these registers in the next cycle (acc_v_q, thread feed_thr_q): the scheduler's choice,
  // acc_thr, then drives no write port of the wide arrays (a fan-out of hundreds of
  // distributed-RAM cells, run 4's critical net). The feeder reads its rays from the same
  // registers; nothing reads the thread's array words before its rays leave ray set-up.
  assign su_org  = lane_3w(feed_org_q, feed_r_q);
  assign su_dir  = lane_3w(feed_dir_q, feed_r_q);
  assign su_take = feed_busy_q & su_ready;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      acc_v_q     <= 1'b0;
      gacc_q      <= '0;
      feed_busy_q <= 1'b0;
      feed_thr_q  <= '0;
      feed_r_q    <= '0;
    end else begin
      acc_v_q <= acc_take;
      gacc_q  <= gacc_c_q;
      if (acc_take) begin
        feed_busy_q <= 1'b1;
        feed_thr_q  <= acc_thr_q;
        feed_r_q    <= '0;
      end else if (su_take) begin
        feed_r_q <= feed_r_q + 2'd1;
        if (feed_r_q == 2'd3) feed_busy_q <= 1'b0;
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (acc_take) begin
      feed_org_q  <= pkt_org_i;
      feed_dir_q  <= pkt_dir_i;
      feed_ilen_q <= pkt_inv_len_i;
      feed_pix_q  <= pkt_pixel_i;
      feed_vmask_q <= pkt_mask_i;
    end
  end

  rc_ray_setup #(
    .ExpW (ExpW),
    .FracW(FracW),
    .TagW (RidW + 1)
  ) u_setup (
    .clk_i,
    .rst_ni,
    .valid_i (feed_busy_q),
    .ready_o (su_ready),
    .tag_i   ({feed_vmask_q[feed_r_q], feed_thr_q, feed_r_q}),
    .org_i   (su_org),
    .dir_i   (su_dir),
    .bounds_i(bounds_i),
    .valid_o (s0_valid),
    .ready_i (s0_ready),
    .tag_o   (s0_tag),
    .inv_o   (s0_inv),
    .tmin_o  (s0_tmin),
    .tmax_o  (s0_tmax),
    .active_o(s0_active)
  );

  // Set-up results are registered (sq_*_q) before they reach the thread states and the
  // current-entry write port, so the set-up unit's output FIFO (a distributed-RAM read) feeds
  // only this register. One cycle of latency per ray, none per packet in steady state; the
  // register takes the next result in the cycle its result goes.
  logic            sq_valid_q, sq_active_q;
  logic [RidW:0]   sq_tag_q;
  logic [3*W-1:0]  sq_inv_q;
  logic [W-1:0]    sq_tmin_q, sq_tmax_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sq_valid_q <= 1'b0;
    end else if (s0_ready) begin
      sq_valid_q <= s0_valid;
    end
  end
  always_ff @(posedge clk_i) begin
    if (s0_valid && s0_ready) begin
      sq_tag_q    <= s0_tag;
      sq_inv_q    <= s0_inv;
      sq_tmin_q   <= s0_tmin;
      sq_tmax_q   <= s0_tmax;
      sq_active_q <= s0_active;
    end
  end
  assign su_valid  = sq_valid_q;
  assign su_tag    = sq_tag_q;
  assign su_inv    = sq_inv_q;
  assign su_tmin   = sq_tmin_q;
  assign su_tmax   = sq_tmax_q;
  assign su_active = sq_active_q;
  assign s0_ready = ~su_valid | su_out_ready;

  // The current-entry arrays have one write port: pop results first, then traversal results,
  // then set-up results (the other two wait; their units hold them in their output FIFOs).
  // The port's state next cycle is known a cycle ahead (a pop result then is pop1_v_q now, a
  // traversal result then is one leaving the sub-units now), so set-up's slot is a flip-flop.
  logic su_slot_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      su_slot_q <= 1'b1;
    end else begin
      su_slot_q <= ~pop1_v_q & ~trav_v_all[0];
    end
  end
  assign su_out_ready = su_slot_q;
  assign su_v    = su_valid & su_out_ready;
  assign su_thr  = su_tag[RidW-1:2];
  assign su_r    = su_tag[1:0];
  assign su_last = su_v & (su_r == 2'd3);
  // The packet's active rays gather in su_gmask_q as its rays leave set-up (in order 0..3, one
  // packet at a time; SetupMask_A), and whether a ray exists travels with it in the tag: no
  // per-thread read on the way from a set-up result to the thread's state.
  assign su_mask_base = (su_r == 2'd0) ? 4'd0 : su_gmask_q;
  always_comb begin
    // A mux per bit (an indexed write would synthesise as a shifter with carry chains).
    for (int unsigned r = 0; r < 4; r++) begin
      su_mask_new[r] = (su_r == 2'(r)) ? su_active & su_tag[RidW] : su_mask_base[r];
    end
  end
  always_ff @(posedge clk_i) begin
    if (su_v) su_gmask_q <= su_mask_new;
  end

  ////////////////////////////////////////
  // Node fetch                         //
  ////////////////////////////////////////

  logic             fe_any, fe_take, fe_bad;
  logic [ThrW-1:0]  fe_thr;
  logic [Threads-1:0] g_fe;
  logic             nreq_free, fq_free, fq_v_q, fe_took_q;
  logic [ThrW-1:0]  fq_thr_q;
  logic [Threads-1:0] gfe_q;
  logic             node_req_valid_q;
  logic [ThrW-1:0]  node_req_thr_q;
  logic [NodeW-1:0] node_req_node_q;

  rc_rr_pick #(
    .N   (Threads),
    .IdxW(ThrW)
  ) u_pick_fetch (
    .clk_i,
    .rst_ni,
    .req_i  (fetch_vec & ~h_fe),
    .take_i (fq_free),
    .valid_o(fe_any),
    .idx_o  (fe_thr),
    .grant_o(g_fe)
  );

  // The choice is registered (fq_*_q) and the node index read from node_m in the next cycle,
  // so the scheduler's choice addresses no distributed RAM in its own cycle (one cycle of
  // latency per fetch). The thread stays StFetch, then StNode, from its choice on: nothing
  // writes its node_m meanwhile. The choice's registers load whenever the register is free
  // (fq_free), with or without a request (the choice is then zero: no grant, fq_v_q low), so
  // the OR over the requests (fe_any) reaches only fq_v_q's input and no register's enable.
  assign nreq_free = ~node_req_valid_q | node_req_ready_i;
  assign fq_free   = ~fq_v_q | nreq_free;
  assign fe_take   = fe_any & fq_free;
  // Whether the thread's current node is outside the node section. Only a packet's root (node
  // 0) can be: a traversal's two children are checked against the node count with their parent
  // (nr_malformed), and a popped entry is such a child (CurNodeInRange_A). So a fetch fails
  // exactly when the node section is empty, registered (the configuration is quasi-static).
  logic node_empty_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      node_empty_q <= 1'b0;
    end else begin
      node_empty_q <= node_count_i == 32'd0;
    end
  end
  assign fe_bad = node_empty_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fq_v_q           <= 1'b0;
      fq_thr_q         <= '0;
      fe_took_q        <= 1'b0;
      gfe_q            <= '0;
      node_req_valid_q <= 1'b0;
      node_req_thr_q   <= '0;
      node_req_node_q  <= '0;
    end else begin
      fe_took_q <= fe_take;
      if (fq_free) begin
        gfe_q    <= g_fe;
        fq_v_q   <= fe_any & ~fe_bad;
        fq_thr_q <= fe_thr;
      end else begin
        gfe_q    <= '0;
      end
      if (node_req_valid_q && node_req_ready_i) node_req_valid_q <= 1'b0;
      if (fq_v_q && nreq_free) begin
        node_req_valid_q <= 1'b1;
        node_req_thr_q   <= fq_thr_q;
        node_req_node_q  <= node_m[fq_thr_q];
      end
    end
  end

  assign node_req_valid_o = node_req_valid_q;
  assign node_req_tag_o   = TagW'(node_req_thr_q);
  assign node_req_index_o = {{(32 - NodeW){1'b0}}, node_req_node_q};

  ////////////////////////////////////////
  // Node response and decode           //
  ////////////////////////////////////////

  // The node response is registered (nq_*_q) together with its checks, computed from the
  // response as it arrives: the node memory's output (on the board, a block RAM's) feeds only
  // the checks' carry chains and a register, and the decode that drives the sub-units, the
  // thread states and the leaf registers starts from flip-flops. One cycle of latency per node
  // visit; the register takes the next response in the cycle its response goes (ready depends
  // on the sub-units' credit, never the reverse).
  logic             trav_ready, nr_take, nr_leaf, nr_err, nr_malformed, nr_leaf_bad, nr_inner_ok;
  logic             nr_empty;
  logic [ThrW-1:0]  nr_thr;
  logic [NodeW-1:0] nr_idx;
  logic [31:0]      nr_upper;
  logic [3:0]       nr_mask;
  logic [12*W-1:0]  n0_org_all, n0_inv_all;
  logic [4*W-1:0]   nr_org, nr_inv;

  logic             n0_take, n0_leaf, n0_split_wide, n0_split_special, n0_malformed;
  logic             n0_leaf_bad;
  logic [ThrW-1:0]  n0_thr;
  logic [1:0]       n0_kind, n0_axis;
  logic [NodeW-1:0] n0_idx;
  logic [31:0]      n0_upper;
  logic             nq_v_q;

  assign node_rsp_ready_o = ~nq_v_q | trav_ready;
  assign n0_take  = node_rsp_valid_i & node_rsp_ready_o;
  assign n0_thr   = node_rsp_tag_i[ThrW-1:0];
  assign n0_kind  = node_rsp_data_i[rc_pkg::KdNodeKindLsb +: 2];
  assign n0_idx   = node_rsp_data_i[rc_pkg::KdNodeIndexLsb +: NodeW];
  assign n0_upper = node_rsp_data_i[rc_pkg::KdNodeValueLsb +: 32];
  assign n0_leaf  = n0_kind == 2'(rc_pkg::KdNodeKindLeaf);
  assign n0_axis  = n0_leaf ? 2'd0 : n0_kind;  // the split axis (0 for a leaf: unused)

  // The golden model's checks (trace_packet): a split wider than the format, NaN or infinite;
  // children not after the parent, or the right child outside the node section; a leaf's list
  // beyond the list section.
  if (W < 32) begin : g_split_wide
    assign n0_split_wide = |n0_upper[31:W];
  end else begin : g_split_fits
    assign n0_split_wide = 1'b0;
  end
  assign n0_split_special = &n0_upper[W-2 -: ExpW];
  assign n0_malformed = n0_split_wide | n0_split_special |
                        (n0_idx <= node_m[n0_thr]) |
                        ({{(33 - NodeW){1'b0}}, n0_idx} + 33'd1 >= {1'b0, node_count_i});
  assign n0_leaf_bad  = {{(33 - NodeW){1'b0}}, n0_idx} + {1'b0, n0_upper} >
                        {1'b0, list_count_i};

  logic             nq_err_q, nq_leaf_q, nq_malformed_q, nq_leaf_bad_q, nq_empty_q, nq_inner_q;
  logic [ThrW-1:0]  nq_thr_q;
  logic [NodeW-1:0] nq_idx_q;
  logic [31:0]      nq_upper_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      nq_v_q <= 1'b0;
    end else if (node_rsp_ready_o) begin
      nq_v_q <= node_rsp_valid_i;
    end
  end
  always_ff @(posedge clk_i) begin
    if (n0_take) begin
      nq_err_q       <= node_rsp_error_i;
      nq_leaf_q      <= n0_leaf;
      nq_malformed_q <= n0_malformed;
      nq_leaf_bad_q  <= n0_leaf_bad;
      nq_empty_q     <= n0_upper == 32'd0;
      nq_inner_q     <= ~node_rsp_error_i & ~n0_leaf & ~n0_malformed;
      nq_thr_q       <= n0_thr;
      nq_idx_q       <= n0_idx;
      nq_upper_q     <= n0_upper;
    end
  end

  assign nr_take      = nq_v_q & trav_ready;
  assign nr_err       = nq_err_q;
  assign nr_thr       = nq_thr_q;
  assign nr_idx       = nq_idx_q;
  assign nr_upper     = nq_upper_q;
  assign nr_leaf      = nq_leaf_q;
  assign nr_empty     = nq_empty_q;
  assign nr_malformed = nq_malformed_q;
  assign nr_leaf_bad  = nq_leaf_bad_q;
  assign nr_inner_ok  = nq_v_q & nq_inner_q;

  // The rays' origins and inverse directions on the split axis are read as the response
  // arrives and registered with it (the thread's org_m and inv_m do not change while StNode),
  // so the sub-units' first stage starts from flip-flops.
  logic [4*W-1:0] n0_org, n0_inv, nq_org_q, nq_inv_q;
  assign n0_org_all = org_m[n0_thr];
  assign n0_inv_all = inv_m[n0_thr];
  always_comb begin
    for (int unsigned r = 0; r < 4; r++) begin
      n0_org[r*W +: W] = axis_w(n0_org_all, r, n0_axis);
      n0_inv[r*W +: W] = axis_w(n0_inv_all, r, n0_axis);
    end
  end
  // So are the rest of what the traversal needs of the thread: its active rays, stack pointer,
  // intervals and its rays' direction signs on the split axis (none of them changes while the
  // thread waits for its node: TravPayload_A checks them at the result; CurWriteFirst_A that no
  // current-entry write is still due). The sub-units' inputs and the operation's payload then
  // start from flip-flops, not from reads addressed by the registered thread.
  logic [3:0]     n0_sign, nq_mask_q, nq_sign_q;
  logic [11:0]    n0_dsign;
  logic [SpW-1:0] nq_sp_q;
  logic [4*W-1:0] nq_tmin_q, nq_tmax_q;
  assign n0_dsign = dsign_m[n0_thr];
  always_comb begin
    for (int unsigned r = 0; r < 4; r++) begin
      n0_sign[r] = 1'b0;
      for (int unsigned a = 0; a < 3; a++) begin
        if (n0_axis == 2'(a)) n0_sign[r] = n0_dsign[3*r+a];
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (n0_take) begin
      nq_org_q  <= n0_org;
      nq_inv_q  <= n0_inv;
      nq_mask_q <= get4(mask_q, n0_thr);
      nq_sp_q   <= getsp(sp_q, n0_thr);
      nq_tmin_q <= tmin_m[n0_thr];
      nq_tmax_q <= tmax_m[n0_thr];
      nq_sign_q <= n0_sign;
    end
  end
  assign nr_org  = nq_org_q;
  assign nr_inv  = nq_inv_q;
  assign nr_mask = nq_mask_q;

  ////////////////////////////////////////
  // Traversal: four sub-units          //
  ////////////////////////////////////////

  // What the traversal result needs of its thread besides the sub-units' t and case is read
  // when the node response is taken and travels with the operation as the sub-units' tags, so
  // the result reads no per-thread array or state vector: the thread, its active rays, per ray
  // whether its direction's sign on the split axis is the lead ray's (the lowest active ray),
  // the lead's sign, the node's index, the stack pointer and whether the stack is full (common
  // part, used from sub-unit 0), and the ray's interval (sub-unit r). A thread in the sub-units
  // (StNode) changes none of these until its result (TravPayload_A).
  localparam int unsigned TrComW = ThrW + 4 + 4 + 1 + NodeW + SpW + 1;
  localparam int unsigned TrTagW = TrComW + 2 * W;

  logic [3:0]        trav_ready_all;
  logic              tr_ready;      // the sub-units' next result goes to tq (below)
  logic [4*TrTagW-1:0] trav_tag_all;
  logic [4*W-1:0]    trav_t;
  logic [7:0]        trav_case;
  logic [4*W-1:0]    nr_tmin, nr_tmax;
  logic [3:0]        nr_sign, nr_same;
  logic [1:0]        nr_lead;
  logic              nr_lsign;
  logic [SpW-1:0]    nr_sp;
  logic [TrComW-1:0] nr_com;

  assign nr_tmin  = nq_tmin_q;
  assign nr_tmax  = nq_tmax_q;
  assign nr_sp    = nq_sp_q;
  assign nr_lead  = lowest4(nr_mask);
  assign nr_sign  = nq_sign_q;
  assign nr_lsign = nr_sign[nr_lead];
  assign nr_same  = nr_sign ^ {4{~nr_lsign}};
  assign nr_com   = {nr_sp == SpW'(StackDepth), nr_sp, nr_idx, nr_lsign, nr_same, nr_mask,
                     nr_thr};

  for (genvar r = 0; r < 4; r++) begin : g_trav
    rc_trav_step #(
      .ExpW (ExpW),
      .FracW(FracW),
      .TagW (TrTagW)
    ) u_step (
      .clk_i,
      .rst_ni,
      .valid_i(nr_inner_ok),
      .ready_o(trav_ready_all[r]),
      .tag_i  ({nr_tmax[r*W +: W], nr_tmin[r*W +: W], nr_com}),
      .split_i(nr_upper[W-1:0]),
      .org_i  (nr_org[r*W +: W]),
      .inv_i  (nr_inv[r*W +: W]),
      .tmin_i (nr_tmin[r*W +: W]),
      .tmax_i (nr_tmax[r*W +: W]),
      .valid_o(trav_v_all[r]),
      .ready_i(tr_ready),
      .tag_o  (trav_tag_all[r*TrTagW +: TrTagW]),
      .t_o    (trav_t[r*W +: W]),
      .case_o (trav_case[r*2 +: 2])
    );
  end
  // The four sub-units take the same operations, so their credits agree (asserted below).
  assign trav_ready = trav_ready_all[0];

  // Traversal result: the packet's two children.
  logic             tr_v, tr_push, tr_overflow, tr_push_ok, tr_full, tr_lsign;
  logic [ThrW-1:0]  tr_thr;
  logic [NodeW-1:0] tr_idx, tr_first, tr_second;
  logic [3:0]       tr_mask, tr_same, tr_a_mask, tr_b_mask;
  logic [4*W-1:0]   tr_lo, tr_hi, tr_a_tmin, tr_a_tmax, tr_b_tmin, tr_b_tmax;
  logic [SpW-1:0]   tr_sp;

  // The sub-units' results pass a register (tq_*_q) before they act: the four sub-units' output
  // FIFOs sit apart on the chip, and their heads went straight into the thread states, masks
  // and stack pointers (run 28: -2.07 ns, 95 state inputs). The register has no enable and no
  // backpressure: a result acts in the cycle after it leaves the sub-units, always. The pop's
  // result, which goes first on the current-entry port, is known a cycle ahead (pop1_v_q is
  // pop2_v one cycle on: the cull compare has one stage and no stall), so a result leaves the
  // sub-units only when the next cycle has no pop result (tr_ready = ~pop1_v_q, a flip-flop;
  // TravSlot_A). Without a take the register loads the unchanged head with tq_v_q low.
  // What the thread-state update needs is decided before the register, from the head: which
  // rays go to each child, whether the far child is pushed or the stack overflows, the new
  // stack pointer and the thread one-hot (run 29: -0.44 ns, 97 state inputs from tq_case_q and
  // tq_v_q through that logic and the thread decode).
  logic [TrComW-1:0]  tq_com_q;
  logic [8*W-1:0]     tq_iv_q;     // {tmax, tmin} of ray r at [r*2W +: 2W]
  logic [4*W-1:0]     tq_t_q;
  logic [7:0]         tq_case_q;
  logic               hd_v, hd_full, hd_lsign, hd_push, hd_ovf;
  logic [ThrW-1:0]    hd_thr;
  logic [NodeW-1:0]   hd_idx;
  logic [3:0]         hd_mask, hd_same, hd_a_mask, hd_b_mask;
  logic [SpW-1:0]     hd_sp;
  logic [3:0]         tq_a_mask_q, tq_b_mask_q, tq_next_mask_q;
  logic               tq_a_any_q, tq_push_q, tq_ovf_q, tq_push_ok_q;
  logic [SpW-1:0]     tq_sp1_q;
  logic [Threads-1:0] tq_hot_q;
  assign tr_ready = ~pop1_v_q;
  assign hd_v     = trav_v_all[0] & tr_ready;
  assign {hd_full, hd_sp, hd_idx, hd_lsign, hd_same, hd_mask, hd_thr} =
         trav_tag_all[0 +: TrComW];
  always_comb begin
    for (int unsigned r = 0; r < 4; r++) begin
      logic [1:0] c;
      c = trav_case[r*2 +: 2];
      // kNearOnly (1) visits only the near child, kFarOnly (2) only the far one.
      hd_a_mask[r] = hd_mask[r] & (hd_same[r] ? c != 2'd2 : c != 2'd1);
      hd_b_mask[r] = hd_mask[r] & (hd_same[r] ? c != 2'd1 : c != 2'd2);
    end
  end
  assign hd_push = (|hd_a_mask) & (|hd_b_mask);
  assign hd_ovf  = hd_push & hd_full;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tq_v_q       <= 1'b0;
      tq_push_ok_q <= 1'b0;
      tq_hot_q     <= '0;
    end else begin
      tq_v_q       <= hd_v;
      tq_push_ok_q <= hd_v & hd_push & ~hd_ovf;
      for (int unsigned t = 0; t < Threads; t++) tq_hot_q[t] <= hd_v && hd_thr == ThrW'(t);
    end
  end
  always_ff @(posedge clk_i) begin
    tq_com_q <= trav_tag_all[0 +: TrComW];
    for (int unsigned r = 0; r < 4; r++) begin
      tq_iv_q[r*2*W +: 2*W] <= trav_tag_all[r*TrTagW + TrComW +: 2*W];
    end
    tq_t_q         <= trav_t;
    tq_case_q      <= trav_case;
    tq_a_mask_q    <= hd_a_mask;
    tq_b_mask_q    <= hd_b_mask;
    tq_a_any_q     <= |hd_a_mask;
    tq_next_mask_q <= (|hd_a_mask) ? hd_a_mask : hd_b_mask;
    tq_push_q      <= hd_push;
    tq_ovf_q       <= hd_ovf;
    tq_sp1_q       <= hd_sp + SpW'(1);
  end
  assign tr_v = tq_v_q;
  assign {tr_full, tr_sp, tr_idx, tr_lsign, tr_same, tr_mask, tr_thr} = tq_com_q;
  for (genvar r = 0; r < 4; r++) begin : g_tr_iv
    assign tr_lo[r*W +: W] = tq_iv_q[r*2*W +: W];
    assign tr_hi[r*W +: W] = tq_iv_q[r*2*W + W +: W];
  end

  // The lead ray's near child first (left child when its direction sign bit is 0).
  assign tr_first  = tr_lsign ? tr_idx + NodeW'(1) : tr_idx;
  assign tr_second = tr_lsign ? tr_idx : tr_idx + NodeW'(1);

  always_comb begin
    for (int unsigned r = 0; r < 4; r++) begin
      logic       same, spl;
      logic [1:0] c;
      logic [W-1:0] t, lo, hi;
      c       = tq_case_q[r*2 +: 2];
      t       = tq_t_q[r*W +: W];
      lo      = tr_lo[r*W +: W];
      hi      = tr_hi[r*W +: W];
      same    = tr_same[r];
      spl     = c == 2'd3;   // kBothSplit
      tr_a_tmin[r*W +: W]  = (!same && spl) ? t : lo;
      tr_a_tmax[r*W +: W]  = (same && spl) ? t : hi;
      tr_b_tmin[r*W +: W]  = (same && spl) ? t : lo;
      tr_b_tmax[r*W +: W]  = (!same && spl) ? t : hi;
    end
  end
  assign tr_a_mask   = tq_a_mask_q;
  assign tr_b_mask   = tq_b_mask_q;
  assign tr_push     = tq_push_q;
  assign tr_overflow = tq_ovf_q;
  assign tr_push_ok  = tq_push_ok_q;  // the second child goes on the stack

  ////////////////////////////////////////
  // Pop: stack read, cull, continue    //
  ////////////////////////////////////////

  logic             pp_any, pp_v_q, pp_end;
  logic [ThrW-1:0]  pp_thr, pp_thr_q;
  logic [Threads-1:0] g_pp, gpp_q, pop_end_t;
  logic [Threads-1:0] gpop0_q, gpop1_q, gpop2_q;
  logic [SpW-1:0]   pp_sp;
  logic             pop0_v_q;
  logic [ThrW-1:0]  pop0_thr_q, pop1_thr_q, pop2_thr_q;
  logic [EntryW-1:0] pop0_entry_q, pop1_entry_q, pop2_entry_q;
  logic [3:0]       pop_le, pop2_mask;
  logic [4*W-1:0]   pop0_best_t, pop1_best_t;

  rc_rr_pick #(
    .N   (Threads),
    .IdxW(ThrW)
  ) u_pick_pop (
    .clk_i,
    .rst_ni,
    .req_i  (pop_vec & ~h_pe),
    .take_i (pp_any),
    .valid_o(pp_any),
    .idx_o  (pp_thr),
    .grant_o(g_pp)
  );

  // The pop in five cycles: the choice is registered (pp_v_q, pp_thr_q, gpp_q); in the next
  // cycle the thread's stack pointer and error bits decide: an empty stack or an error ends the
  // packet's walk (StDone), otherwise the thread goes to StPopping, the top entry is read and the
  // pointer decremented; the entry read (pop0_entry_q, the block RAM's read register) is copied
  // into a fabric register (pop1_entry_q) with the thread's best hits, since the block RAM's
  // clock-to-out (5.8 ns on the LFE5U-85F) leaves no time for the compare behind it; then the
  // entry is culled against the best hits, and then it becomes the current entry. The choice
  // thus never meets the stack pointer's read in one cycle. Whether the walk ends is decided
  // per thread (pop_end_t, from the thread's own registers) and picked with the one-hot grant,
  // so no thread-indexed read sits before it; the block RAM reads the slot whenever a choice is
  // registered (its enable is pp_v_q), and an ended walk just leaves its read unused.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pp_v_q   <= 1'b0;
      pp_thr_q <= '0;
      gpp_q    <= '0;
      pop0_v_q <= 1'b0;
      pop1_v_q <= 1'b0;
      gpop0_q  <= '0;
      gpop1_q  <= '0;
      gpop2_q  <= '0;
    end else begin
      pp_v_q   <= pp_any;
      pp_thr_q <= pp_thr;
      gpp_q    <= g_pp;
      pop0_v_q <= pp_v_q & ~pp_end;
      pop1_v_q <= pop0_v_q;
      gpop0_q  <= pp_end ? '0 : gpp_q;
      gpop1_q  <= gpop0_q;
      gpop2_q  <= gpop1_q;
    end
  end

  for (genvar t = 0; t < Threads; t++) begin : g_pop_end
    assign pop_end_t[t] = (|err_q[t*3 +: 3]) | (sp_q[t*SpW +: SpW] == '0);
  end
  // The chosen thread's stack pointer through its one-hot grant (an AND-OR over the threads).
  always_comb begin
    pp_sp = '0;
    for (int unsigned t = 0; t < Threads; t++) begin
      pp_sp = pp_sp | ({SpW{gpp_q[t]}} & sp_q[t*SpW +: SpW]);
    end
  end
  assign pp_end = |(gpp_q & pop_end_t);

  // Stack entry: {node, mask, tmin[4], tmax[4]}.
  always_ff @(posedge clk_i) begin
    if (pp_v_q) begin
      pop0_entry_q <= stack_m[StkAW'({pp_thr_q, pp_sp[SpIdxW-1:0]})];
    end
    // The best hits are read with the stack entry, from the registered choice: a popping
    // thread's best hits do not change (only a thread in its leaf gets intersection results,
    // and its leaf's last commit comes before its pop is chosen; PopBest_A).
    if (pp_v_q) pop0_best_t <= gate_t(bt_m[pp_thr_q], sel4(bhit_q, gpp_q));
    if (pop0_v_q) begin
      pop1_entry_q <= pop0_entry_q;
      pop1_best_t  <= pop0_best_t;
    end
    pop0_thr_q   <= pp_thr_q;
    pop1_thr_q   <= pop0_thr_q;
    pop2_thr_q   <= pop1_thr_q;
    pop2_entry_q <= pop1_entry_q;
  end

  // Cull: ray r stays only if le(tmin_r, best_t_r), by the format's comparison.
  logic [3:0] pop_cmp_v;
  for (genvar r = 0; r < 4; r++) begin : g_pop_cmp
    logic unused_lt, unused_eq;
    logic [W-1:0] unused_min, unused_max;
    rc_fp_cmp #(
      .ExpW  (ExpW),
      .FracW (FracW),
      .Stages(1)
    ) u_cmp (
      .clk_i,
      .rst_ni,
      .valid_i(pop1_v_q),
      .a_i    (pop1_entry_q[4*W + r*W +: W]),
      .b_i    (pop1_best_t[r*W +: W]),
      .valid_o(pop_cmp_v[r]),
      .lt_o   (unused_lt),
      .le_o   (pop_le[r]),
      .eq_o   (unused_eq),
      .min_o  (unused_min),
      .max_o  (unused_max)
    );
  end
  assign pop2_v    = pop_cmp_v[0];
  // The popping thread one-hot beside the pipeline (gpop0_q .. gpop2_q, zero without a pop), so
  // the thread-state update takes the result's thread from flip-flops rather than decoding
  // pop2_thr_q with the compare's valid (run 27: 44 state inputs behind that decode).
  assign pop2_mask = pop2_entry_q[8*W +: 4] & pop_le;

  ////////////////////////////////////////
  // List unit and the tag pool         //
  ////////////////////////////////////////

  // Tags of outstanding list entries: a list request takes a tag; the same tag then names the
  // entry's triangle request; the tag is free again when the triangle response is taken (or the
  // entry fails). tp_thr_m / tp_tri_m hold each tag's thread and triangle index, tp_mask_m the
  // thread's active rays (which do not change while the thread has list entries outstanding:
  // it stays StLeaf, StLeafRun until its pending count is zero).
  logic [ListTags-1:0] tf_q, tf_d;             // free tags
  logic [ThrW-1:0]     tp_thr_m [0:ListTags-1];
  logic [3:0]          tp_mask_m [0:ListTags-1];
  logic [2:0]          tp_first_m [0:ListTags-1];  // {one ray only, lowest ray} of the mask
  logic [31:0]         tp_tri_m [0:ListTags-1];
  logic                tag_avail;
  logic [LtW-1:0]      tag_new;

  // The next tag to take: the lowest set bit of the free set (x & -x, a carry chain), its index
  // as an OR of the one-hot bits (no chain through the tags), computed from the free set as it
  // will be without this cycle's frees (tf_q less the tag taken now) and registered, so the list
  // request, the tag pool's write address and the take start at flip-flops, and no response
  // (a freed tag) reaches the chain: a freed tag is offered a cycle later. The registered tag is
  // free when it is taken, since only a take makes a free tag busy (TagFirst_A).
  // The search runs twice side by side, on the free set with and without the registered tag,
  // both from flip-flops, and the issue (li_take) picks one at the end: it reaches the three
  // registers through a mux, not through the carry chain (run 27: 15 cells from lu_busy_q).
  logic [ListTags-1:0] tag_first, tf_rest, tag_first_all, tag_first_rest;
  logic [LtW-1:0]      tag_new_all, tag_new_rest;
  logic                tag_avail_q;
  logic [ListTags-1:0] tag_first_q;
  logic [LtW-1:0]      tag_new_q;
  function automatic logic [LtW-1:0] tag_index(input logic [ListTags-1:0] one_hot);
    tag_index = '0;
    for (int unsigned i = 0; i < ListTags; i++) begin
      if (one_hot[i]) tag_index = tag_index | LtW'(i);
    end
  endfunction
  assign tf_rest        = tf_q & ~tag_first_q;
  assign tag_first_all  = tf_q & (~tf_q + ListTags'(1));
  assign tag_first_rest = tf_rest & (~tf_rest + ListTags'(1));
  assign tag_new_all    = tag_index(tag_first_all);
  assign tag_new_rest   = tag_index(tag_first_rest);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tag_avail_q <= 1'b1;
      tag_first_q <= ListTags'(1);
      tag_new_q   <= '0;
    end else begin
      tag_avail_q <= li_take ? |tf_rest : |tf_q;
      tag_first_q <= li_take ? tag_first_rest : tag_first_all;
      tag_new_q   <= li_take ? tag_new_rest : tag_new_all;
    end
  end
  assign tag_avail = tag_avail_q;
  assign tag_first = tag_first_q;
  assign tag_new   = tag_new_q;

  logic            lp_any, lp_take;
  logic [ThrW-1:0] lp_thr;
  logic [Threads-1:0] g_lp, glp_q;
  logic            lu_busy_q, lu_load_q;
  logic [ThrW-1:0] lu_thr_q;
  logic [3:0]      lu_mask_q;
  logic [31:0]     lu_idx_q, lu_left_q;
  logic            lreq_free, lout_free, li_take;
  logic            list_req_valid_q, lsk_v_q;
  logic [LtW-1:0]  list_req_tag_q, lsk_tag_q;
  logic [31:0]     list_req_index_q, lsk_index_q;

  rc_rr_pick #(
    .N   (Threads),
    .IdxW(ThrW)
  ) u_pick_leaf (
    .clk_i,
    .rst_ni,
    .req_i  (leaf_vec),
    .take_i (lp_take),
    .valid_o(lp_any),
    .idx_o  (lp_thr),
    .grant_o(g_lp)
  );

  // The choice is registered (lu_thr_q) and the leaf's list offset and count read in the next
  // cycle (lu_load_q), so the scheduler's choice addresses no distributed RAM in its own cycle
  // (one cycle of latency per leaf). The thread's active rays are registered in the same cycle
  // (lu_mask_q) and go into the tag pool with each entry's tag. The thread stays StLeaf, then
  // StLeafRun, from its choice on: nothing writes its loff_m, lcnt_m and mask meanwhile.
  assign lp_take   = lp_any & ~lu_busy_q;
  // The list request leaves through a register with a one-entry skid buffer (lsk_*_q) beside
  // it, so the list unit issues whenever the buffer is empty (lreq_free, a flip-flop): the
  // list port's ready, which comes from the list memory across the chip, reaches the request
  // registers only, not the issue (li_take) and with it the tag search, the tag pool and the
  // threads' entry counts (run 23's critical path). An entry waits in the buffer only behind a
  // request the port has not taken.
  assign lout_free = ~list_req_valid_q | list_req_ready_i;
  assign lreq_free = ~lsk_v_q;
  assign li_take   = lu_busy_q & ~lu_load_q & tag_avail & lreq_free;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lu_busy_q        <= 1'b0;
      lu_load_q        <= 1'b0;
      glp_q            <= '0;
      lu_thr_q         <= '0;
      lu_mask_q        <= '0;
      lu_idx_q         <= '0;
      lu_left_q        <= '0;
      list_req_valid_q <= 1'b0;
      list_req_tag_q   <= '0;
      list_req_index_q <= '0;
      lsk_v_q          <= 1'b0;
      lsk_tag_q        <= '0;
      lsk_index_q      <= '0;
    end else begin
      if (lp_take) begin
        lu_busy_q <= 1'b1;
        lu_load_q <= 1'b1;
        glp_q     <= g_lp;
        lu_thr_q  <= lp_thr;
      end
      if (lu_load_q) begin
        lu_load_q <= 1'b0;
        lu_idx_q  <= loff_m[lu_thr_q];
        lu_left_q <= lcnt_m[lu_thr_q];
        lu_mask_q <= get4(mask_q, lu_thr_q);
      end
      // The request register takes the skid buffer's entry first, else a new one; a new entry
      // the register cannot take goes into the skid buffer.
      if (lout_free) begin
        list_req_valid_q <= lsk_v_q | li_take;
        list_req_tag_q   <= lsk_v_q ? lsk_tag_q : tag_new;
        list_req_index_q <= lsk_v_q ? lsk_index_q : lu_idx_q;
      end
      lsk_v_q <= lsk_v_q ? ~lout_free : (li_take & ~lout_free);
      if (!lsk_v_q) begin
        lsk_tag_q   <= tag_new;
        lsk_index_q <= lu_idx_q;
      end
      if (li_take) begin
        lu_idx_q         <= lu_idx_q + 32'd1;
        lu_left_q        <= lu_left_q - 32'd1;
        if (lu_left_q == 32'd1) lu_busy_q <= 1'b0;
      end
    end
  end

  assign list_req_valid_o = list_req_valid_q;
  assign list_req_tag_o   = TagW'(list_req_tag_q);
  assign list_req_index_o = list_req_index_q;

  // List response: the entry's triangle request, or a bad address.
  logic            tbuf_free, lr_take, lr_bad, lb_v_q;
  logic [LtW-1:0]  lr_tag, lb_tag_q;
  logic [ThrW-1:0] lr_thr, lb_thr_q;
  logic            tri_req_valid_q;
  logic [LtW-1:0]  tri_req_tag_q;
  logic [31:0]     tri_req_index_q;

  // The response is registered as it arrives (lq_*_q) and checked from there: the list
  // memory's output (on the board, a block RAM's register across the chip) reaches plain
  // flip-flops only, and the range check's carry chain starts at this register (run 28:
  // -1.40 ns, 5.8 ns of it the route from the ROM). One cycle of latency per list entry; the
  // register takes the next response in the cycle its response goes.
  logic            lq_v_q, lq_err_q;
  logic [LtW-1:0]  lq_tag_q;
  logic [31:0]     lq_data_q;
  assign tbuf_free        = ~tri_req_valid_q | tri_req_ready_i;
  assign list_rsp_ready_o = ~lq_v_q | tbuf_free;
  assign lr_take          = lq_v_q & tbuf_free;
  assign lr_tag           = lq_tag_q;
  assign lr_bad           = lq_err_q | (lq_data_q >= tri_count_i);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lq_v_q    <= 1'b0;
      lq_err_q  <= 1'b0;
      lq_tag_q  <= '0;
      lq_data_q <= '0;
    end else if (list_rsp_ready_o) begin
      lq_v_q    <= list_rsp_valid_i;
      lq_err_q  <= list_rsp_error_i;
      lq_tag_q  <= list_rsp_tag_i[LtW-1:0];
      lq_data_q <= list_rsp_data_i;
    end
  end
  // A failed entry is registered (lb_*_q, with its tag's thread) and retired in the next cycle
  // (its thread's pending count, its tag): the check's carry chain and the tag pool's read end
  // at flip-flops, not at the thread's leaf count.
  assign lr_thr           = lb_thr_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lb_v_q   <= 1'b0;
      lb_tag_q <= '0;
      lb_thr_q <= '0;
    end else begin
      lb_v_q <= lr_take & lr_bad;
      if (lr_take) begin
        lb_tag_q <= lr_tag;
        lb_thr_q <= tp_thr_m[lr_tag];
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tri_req_valid_q <= 1'b0;
      tri_req_tag_q   <= '0;
      tri_req_index_q <= '0;
    end else begin
      // The request's payload is loaded on every taken response (the buffer is free then), so
      // only its valid bit waits for the range check: one flip-flop behind the carry chain
      // instead of the payload's clock enables.
      if (tri_req_valid_q && tri_req_ready_i) tri_req_valid_q <= 1'b0;
      if (lr_take) begin
        tri_req_valid_q <= ~lr_bad;
        tri_req_tag_q   <= lr_tag;
        tri_req_index_q <= lq_data_q;
      end
    end
  end

  assign tri_req_valid_o = tri_req_valid_q;
  assign tri_req_tag_o   = TagW'(tri_req_tag_q);
  assign tri_req_index_o = tri_req_index_q;

  always_ff @(posedge clk_i) begin
    if (li_take) begin
      tp_thr_m[tag_new]  <= lu_thr_q;
      tp_mask_m[tag_new] <= lu_mask_q;
      tp_first_m[tag_new] <= {(lu_mask_q & (lu_mask_q - 4'd1)) == 4'd0, lowest4(lu_mask_q)};
    end
    // Written on every list response, failed ones too, so the range check's carry chain does
    // not reach the pool's write enable: a failed entry's tag sends no triangle request and is
    // retired, and the tag's next list response writes the entry again before it is read.
    if (lr_take) tp_tri_m[lr_tag] <= lq_data_q;
  end

  ////////////////////////////////////////
  // Intersection: each triangle        //
  // against the active rays in turn    //
  ////////////////////////////////////////

  // The triangle response is taken into an issue register (ti_*_q) with its tag's thread and
  // triangle index and the thread's active rays, read from the tag pool here; from the
  // register, the triangle goes to the intersection unit once per active ray (lowest ray
  // first). So the tag pool's read and the reads of the thread's rays and best hits (wide
  // distributed RAMs addressed by the thread) are in different cycles, and the register's
  // ready (ti_free, the triangle port's response ready) decodes no thread. A failed triangle
  // read passes the register too and leaves it in one cycle. The register takes the next
  // response in the cycle its last ray goes (ready depends on the intersection unit's ready,
  // never the reverse). In front of it, a one-entry skid buffer (tk_*_q) takes a response the
  // register cannot, so the port's ready is the buffer's emptiness, a flip-flop: the ready no
  // longer crosses the chip from the issue register's state to the triangle memory (run 20's
  // critical path). The register loads from the buffer when it holds a response, else from the
  // port; a tag is freed when its response enters the register (the tag pool is read then).
  logic            is_ready, is_valid, is_take, ti_err_take, ti_last, ti_free, ti_load;
  logic            ti_v_q, ti_err_q;
  logic            tk_v_q, tk_err_q, src_v, src_err, rsp_take;
  logic [LtW-1:0]  tk_tag_q, src_tag;
  logic [12*W-1:0] tk_data_q, src_data;
  logic [LtW-1:0]  ti_tag;
  logic [ThrW-1:0] ti_thr, ti_thr_q;
  logic [31:0]     ti_tri_q;
  logic [12*W-1:0] ti_m_q;
  logic [3:0]      ti_mask_q, ti_mask_new, ti_rem_q, ti_rem_next;
  logic [2:0]      ti_first_new;
  logic            ti_last_q;
  logic [1:0]      ti_r;
  logic [12*W-1:0] ti_org_all, ti_dir_all;
  logic [4*W-1:0]  ti_bt;
  logic [127:0]    ti_btri;

  assign tri_rsp_ready_o = ~tk_v_q;
  assign rsp_take        = tri_rsp_valid_i & ~tk_v_q;
  assign src_v           = tk_v_q | tri_rsp_valid_i;
  assign src_tag         = tk_v_q ? tk_tag_q : tri_rsp_tag_i[LtW-1:0];
  assign src_err         = tk_v_q ? tk_err_q : tri_rsp_error_i;
  assign src_data        = tk_v_q ? tk_data_q : tri_rsp_data_i;
  assign ti_tag          = src_tag;
  assign ti_thr          = tp_thr_m[ti_tag];
  assign ti_free         = ~ti_v_q | ti_err_q | (is_ready & ti_last_q);
  assign ti_load         = src_v & ti_free;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tk_v_q   <= 1'b0;
      ti_v_q   <= 1'b0;
      ti_err_q <= 1'b0;
    end else begin
      // Full when a taken response cannot enter the register; emptied into the register.
      tk_v_q <= tk_v_q ? ~ti_free : (rsp_take & ~ti_free);
      if (ti_free) begin
        ti_v_q   <= src_v;
        ti_err_q <= src_v & src_err;
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (rsp_take) begin
      tk_tag_q  <= tri_rsp_tag_i[LtW-1:0];
      tk_err_q  <= tri_rsp_error_i;
      tk_data_q <= tri_rsp_data_i;
    end
    if (ti_load) begin
      ti_thr_q  <= ti_thr;
      ti_mask_q <= ti_mask_new;
      ti_tri_q  <= tp_tri_m[ti_tag];
      ti_m_q    <= src_data;
    end
  end

  // The rays still to test (ti_rem_q, lowest first) and whether the current one is the last
  // (ti_last_q) are registers, loaded with the triangle and updated at each test, so the
  // register's ready (ti_free, the triangle port's response ready, which crosses the chip to the
  // triangle memory) is two gates of flip-flops.
  assign ti_mask_new  = tp_mask_m[ti_tag];
  assign ti_first_new = tp_first_m[ti_tag];
  assign ti_rem_next = ti_rem_q & (ti_rem_q - 4'd1);  // the lowest ray done
  assign ti_r        = lowest4(ti_rem_q);
  assign ti_last     = ti_last_q;

  assign is_valid    = ti_v_q & ~ti_err_q;
  assign is_take     = is_valid & is_ready;
  assign ti_err_take = ti_v_q & ti_err_q;

  // The current ray's lane, registered with ti_rem_q, in one copy per group of lane
  // multiplexers, so no select net fans out to all of the slice's 600 multiplexed bits across
  // the chip. The copies have a process of their own marked keep: Yosys merges identical
  // flip-flops unless their cells are kept, and a keep on the signals alone does not reach the
  // cells (runs 33 and 34 had a single copy, ti_r_org_q driving all four groups).
  logic [1:0] ti_r_org_q, ti_r_dir_q, ti_r_bt_q, ti_r_btri_q, ti_r_next;
  assign ti_r_next = ti_load ? ti_first_new[1:0] : lowest4(ti_rem_next);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ti_rem_q    <= '0;
      ti_last_q   <= 1'b0;
    end else if (ti_load) begin
      // The mask's first ray and whether it is the only one come with it from the tag pool
      // (computed when the leaf's mask was registered), so the load reads them straight into
      // the registers.
      ti_rem_q    <= ti_mask_new;
      ti_last_q   <= ti_first_new[2];
    end else if (is_take) begin
      ti_rem_q    <= ti_rem_next;
      ti_last_q   <= (ti_rem_next & (ti_rem_next - 4'd1)) == 4'd0;
    end
  end
  (* keep *)
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ti_r_org_q  <= '0;
      ti_r_dir_q  <= '0;
      ti_r_bt_q   <= '0;
      ti_r_btri_q <= '0;
    end else if (ti_load || is_take) begin
      ti_r_org_q  <= ti_r_next;
      ti_r_dir_q  <= ti_r_next;
      ti_r_bt_q   <= ti_r_next;
      ti_r_btri_q <= ti_r_next;
    end
  end

  // The best hits are gated with the thread's hit bits as they were a cycle before (ti_hit_q;
  // none in the cycle after a load), so no thread-indexed read of bhit_q sits between ti_thr_q
  // and the slice: the filter then sees +inf where a hit is a cycle new, which only lets a test
  // through that the write-back rejects (a hit bit, once set, stays set for the packet, and the
  // word it gates is then the ray's current best).
  logic [3:0] ti_hit_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ti_hit_q <= '0;
    end else begin
      ti_hit_q <= ti_load ? 4'd0 : get4(bhit_q, ti_thr_q);
    end
  end
  assign ti_org_all = org_m[ti_thr_q];
  assign ti_dir_all = dir_m[ti_thr_q];
  assign ti_bt      = gate_t(bt_m[ti_thr_q], ti_hit_q);
  assign ti_btri    = gate_tri(btri_m[ti_thr_q], ti_hit_q);

  // The unit's inputs are registered (ia_*_q, a register slice that takes a test whenever it
  // is empty or the unit takes its test), so the reads of the thread's rays and best hits above
  // end at flip-flops and the unit's input muxes start at them: the two are far apart on the
  // chip. The best hit a test is filtered against is then read a cycle earlier, which changes
  // no result: the write-back compares again with the ray's best at its own time.
  logic              ia_v_q, iu_ready;
  logic [ThrW+2:0]   ia_tag_q;
  logic [31:0]       ia_tri_q, ia_btri_q;
  logic [12*W-1:0]   ia_m_q;
  logic [3*W-1:0]    ia_org_q, ia_dir_q;
  logic [W-1:0]      ia_bt_q;

  assign is_ready = ~ia_v_q | iu_ready;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ia_v_q <= 1'b0;
    end else if (is_ready) begin
      ia_v_q <= is_valid;
    end
  end
  always_ff @(posedge clk_i) begin
    if (is_take) begin
      ia_tag_q  <= {ti_last, ti_r, ti_thr_q};
      ia_tri_q  <= ti_tri_q;
      ia_m_q    <= ti_m_q;
      ia_org_q  <= lane_3w(ti_org_all, ti_r_org_q);
      ia_dir_q  <= lane_3w(ti_dir_all, ti_r_dir_q);
      ia_bt_q   <= lane_w(ti_bt, ti_r_bt_q);
      ia_btri_q <= lane_32(ti_btri, ti_r_btri_q);
    end
  end

  logic              ix_v, ix_hit;
  logic [ThrW+2:0]   ix_tag;
  logic [31:0]       ix_tri;
  logic [W-1:0]      ix_t, ix_u, ix_v_bits, ix_dz;

  rc_isect_unit #(
    .ExpW       (ExpW),
    .FracW      (FracW),
    .TagW       (ThrW + 3),
    .SharedXform(IsectInterval == 2)
  ) u_isect (
    .clk_i,
    .rst_ni,
    .valid_i   (ia_v_q),
    .ready_o   (iu_ready),
    .tag_i     (ia_tag_q),
    .tri_i     (ia_tri_q),
    .m_i       (ia_m_q),
    .org_i     (ia_org_q),
    .dir_i     (ia_dir_q),
    .best_t_i  (ia_bt_q),
    .best_tri_i(ia_btri_q),
    .valid_o   (ix_v),
    .ready_i   (1'b1),
    .tag_o     (ix_tag),
    .tri_o     (ix_tri),
    .hit_o     (ix_hit),
    .t_o       (ix_t),
    .u_o       (ix_u),
    .v_o       (ix_v_bits),
    .dz_o      (ix_dz)
  );

  // The unit's results pass a register slice (iu_*_q) first: the unit's output register sits
  // in the unit beside its FIFO, and the result's thread addresses the best-hit arrays' reads
  // below, across the chip (run 23's path into io_bt); from the slice the read starts at
  // flip-flops placed near the arrays. A result is a cycle later, so its leaf ends a cycle later.
  // Then the results are registered again (io_*) before the write-back, so the unit's output
  // FIFO read and the best-hit read, compare and write are in different cycles. Both stages
  // hold the whole result {tag, tri, hit, t, u, v, dz} as one word.
  localparam int unsigned IuW    = ThrW + 3 + 32 + 1 + 4 * W;
  localparam int unsigned IuTagL = IuW - (ThrW + 3);  // the tag's lowest bit in the word
  logic              iu_v_q, io_v_q, io_hit_q;
  logic [IuW-1:0]    iu_res_q, io_res_q;
  logic [ThrW+2:0]   io_tag_q;
  logic [31:0]       io_tri_q;
  logic [W-1:0]      io_t_q, io_u_q, io_v_bits_q, io_dz_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      iu_v_q <= 1'b0;
      io_v_q <= 1'b0;
    end else begin
      iu_v_q <= ix_v;
      io_v_q <= iu_v_q;
    end
  end
  always_ff @(posedge clk_i) begin
    if (ix_v) iu_res_q <= {ix_tag, ix_tri, ix_hit, ix_t, ix_u, ix_v_bits, ix_dz};
    if (iu_v_q) io_res_q <= iu_res_q;
  end
  assign {io_tag_q, io_tri_q, io_hit_q, io_t_q, io_u_q, io_v_bits_q, io_dz_q} = io_res_q;

  // Write-back: the hit replaces the ray's best if (t, tri) is smaller, compared again here
  // because other tests of the same ray may have finished since this one read its best. Accepted
  // t are positive and finite, so their encodings order like their values. Three cycles after the
  // io register (whose load reads the ray's best hit): the best, forwarded where newer, into
  // wb_*_q; then the compare (wb_better, WbBest_A); then the commit (wc_*_q): the ray's words
  // are read, its lane replaced and written back, and its hit bit set, all from registers, so the
  // compare's carry chains end at a flip-flop instead of the write enables of hundreds of
  // distributed-RAM cells. The read for the io stage misses the bests of the results ahead of it
  // (decided and not yet committed, or committed after the read): those are forwarded when they
  // are the same ray's, the newest first (WbForward_A), or compared against (the one decided as
  // the result enters wb). The leaf's triangle count goes down at the compare; its pop reads the
  // best hits at least three cycles later, after the commit.
  logic            wb_v_q, wb_last_q, wb_hit_q, wb_better, wb_fwd, wc_fwd, wb_pf_q;
  logic            wb_lt_own, wb_lt_prev;
  logic [1:0]      wb_r_q, io_r;
  logic [ThrW-1:0] wb_thr_q, io_thr;
  logic [W-1:0]    io_bt, io_bt_q, wb_bt_q, wb_t_q, wb_u_q, wb_vb_q, wb_dz_q;
  logic [31:0]     io_btri, io_btri_q, wb_btri_q, wb_tri_q;
  logic            io_bhit_q;
  logic [3:0]      iu_hits;
  logic            wc_we_q, wd_we_q, wd_fwd;
  logic [1:0]      wc_r_q, wd_r_q, iu_r;
  logic [ThrW-1:0] wc_thr_q, wd_thr_q, iu_thr;
  logic [W-1:0]    wc_t_q, wc_u_q, wc_vb_q, wc_dz_q, wd_t_q;
  logic [31:0]     wc_tri_q, wd_tri_q;

  // The ray's best hit is read as the result enters the io register (io_bt, io_btri: from the
  // slice's registers), so the read addressed by the result's thread ends at flip-flops; the
  // io stage then only forwards the one committed at the end of this cycle (wc) and the one
  // committed at the end of the last (wd), which the read missed. The best decided this cycle
  // (wb) is only noted (wb_fwd into wb_pf_q) and compared against in the next (below).
  assign iu_thr  = iu_res_q[IuTagL +: ThrW];
  assign iu_r    = iu_res_q[IuTagL + ThrW +: 2];
  assign io_r    = io_tag_q[ThrW +: 2];
  assign io_thr  = io_tag_q[ThrW-1:0];
  assign wb_fwd  = wb_v_q & (wb_thr_q == io_thr) & (wb_r_q == io_r);
  assign wc_fwd  = wc_we_q & (wc_thr_q == io_thr) & (wc_r_q == io_r);
  assign wd_fwd  = wd_we_q & (wd_thr_q == io_thr) & (wd_r_q == io_r);
  assign iu_hits = get4(bhit_q, iu_thr);
  assign io_bt   = io_bhit_q ? io_bt_q : FpInf;
  assign io_btri = io_bhit_q ? io_btri_q : '1;

  // The ray's hit bit is read beside its best hit and applied after the register (io_bt,
  // io_btri: +inf and all ones without a hit), so the hit bits' thread multiplexer and the
  // distributed-RAM read run side by side instead of in series (runs 31 and 32: -2.47 ns).
  always_ff @(posedge clk_i) begin
    if (iu_v_q) begin
      io_bt_q   <= lane_w(bt_m[iu_thr], iu_r);
      io_btri_q <= lane_32(btri_m[iu_thr], iu_r);
      io_bhit_q <= iu_hits[iu_r];
    end
    wd_thr_q <= wc_thr_q;
    wd_r_q   <= wc_r_q;
    wd_t_q   <= wc_t_q;
    wd_tri_q <= wc_tri_q;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wb_v_q  <= 1'b0;
      wc_we_q <= 1'b0;
      wd_we_q <= 1'b0;
    end else begin
      wb_v_q  <= io_v_q;
      wc_we_q <= wb_better;
      wd_we_q <= wc_we_q;
    end
  end
  always_ff @(posedge clk_i) begin
    if (io_v_q) begin
      wb_last_q <= io_tag_q[ThrW+2];
      wb_r_q      <= io_r;
      wb_thr_q    <= io_thr;
      wb_hit_q  <= io_hit_q;
      wb_t_q    <= io_t_q;
      wb_tri_q  <= io_tri_q;
      wb_u_q    <= io_u_q;
      wb_vb_q   <= io_v_bits_q;
      wb_dz_q   <= io_dz_q;
      wb_pf_q   <= wb_fwd;
      wb_bt_q   <= wc_fwd ? wc_t_q : wd_fwd ? wd_t_q : io_bt;
      wb_btri_q <= wc_fwd ? wc_tri_q : wd_fwd ? wd_tri_q : io_btri;
    end
    // Loaded every cycle (only wc_we_q says whether they commit), so the compare reaches one
    // flip-flop and the forwarding muxes, no clock enables.
    wc_r_q   <= wb_r_q;
    wc_thr_q <= wb_thr_q;
    wc_t_q   <= wb_t_q;
    wc_u_q   <= wb_u_q;
    wc_vb_q  <= wb_vb_q;
    wc_dz_q  <= wb_dz_q;
    wc_tri_q <= wb_tri_q;
  end

  // The best decided in the cycle the result entered wb (the wb stage's then, now wc's) is not
  // forwarded into wb_bt_q: its decision (wb_better) would sit between wb_bt_q and itself (run
  // 33: -0.52 ns). wb_pf_q records that it was the same ray's, and the compare against it runs
  // beside the compare against wb_bt_q; the commit's enable (wc_we_q) picks between the two.
  assign wb_lt_own   = (wb_t_q < wb_bt_q) | ((wb_t_q == wb_bt_q) & (wb_tri_q < wb_btri_q));
  assign wb_lt_prev  = (wb_t_q < wc_t_q) | ((wb_t_q == wc_t_q) & (wb_tri_q < wc_tri_q));
  assign wb_better   = wb_v_q & wb_hit_q & ((wb_pf_q & wc_we_q) ? wb_lt_prev : wb_lt_own);

  ////////////////////////////////////////
  // Shading and framebuffer writes     //
  ////////////////////////////////////////

  logic            shp_any, shp_room, shp_none, shp_v_q;
  logic [ThrW-1:0] shp_thr, shp_thr_q;
  logic [Threads-1:0] g_shp, gshp_q;
  logic            sh_busy_q;
  logic [ThrW-1:0] sh_thr_q;
  logic [1:0]      sh_r_q;
  logic            sh_valid_r, sh_hit_r, sh_adv, sh_to_shd, sh_to_miss;
  logic            sreq_free, mreq_free, miss_free, miss_take;
  logic            shd_req_valid_q, mat_req_valid_q, miss_v_q;
  logic [RidW-1:0] shd_req_rid_q, mat_req_rid_q, miss_rid_q;
  logic [31:0]     shd_req_index_q, mat_req_index_q;
  logic [127:0]    sh_btri;

  // The threads in StDone, kept in a register of their own beside st_q (set as a walk ends,
  // cleared as shading takes the packet: the only ways in and out of StDone, DoneMirror_A), so
  // the shading choice starts from flip-flops instead of a decode of the thread states.
  logic [Threads-1:0] done_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      done_q <= '0;
    end else begin
      done_q <= (done_q | (h_pe & pop_end_t)) & ~h_sx;
    end
  end

  rc_rr_pick #(
    .N   (Threads),
    .IdxW(ThrW)
  ) u_pick_done (
    .clk_i,
    .rst_ni,
    .req_i  (done_q),
    .take_i (shp_room),
    .valid_o(shp_any),
    .idx_o  (shp_thr),
    .grant_o(g_shp)
  );

  // A traced packet is chosen and the choice registered (shp_v_q, shp_thr_q, gshp_q); in the
  // next cycle it goes to StShade and its rays start to pass shading one by one (sh_busy_q), or
  // a packet without rays is freed. So the choice never meets the thread's ray mask and the
  // shading sequencer in one cycle. The choice's registers load whenever there is room
  // (shp_room, from flip-flops), with or without a request: the OR over the requests reaches
  // only shp_v_q.
  assign shp_room = ~sh_busy_q & ~shp_v_q;
  // Whether the chosen packet has no rays, through the one-hot choice (an AND-OR over the
  // threads' own any-ray bits, no thread multiplexer of the masks).
  logic [Threads-1:0] vm_any;
  always_comb begin
    for (int unsigned t = 0; t < Threads; t++) vm_any[t] = |vmask_q[t*4 +: 4];
  end
  assign shp_none = ~|(gshp_q & vm_any);

  // The packet's rays, their hits (none after an error) and their triangles are taken into
  // registers as its shading starts (a thread in shading changes none of them: ShadeSnap_A), so
  // the sequencer's requests come from flip-flops, not from reads by its thread.
  logic [3:0]   sh_vm_q, sh_hm_q;
  logic [127:0] sh_btri_q;
  always_ff @(posedge clk_i) begin
    if (shp_v_q) begin
      sh_vm_q   <= get4(vmask_q, shp_thr_q);
      sh_hm_q   <= get4(bhit_q, shp_thr_q) & {4{~(|get3(err_q, shp_thr_q))}};
      sh_btri_q <= btri_m[shp_thr_q];
    end
  end
  assign sh_valid_r = sh_vm_q[sh_r_q];
  assign sh_hit_r   = sh_hm_q[sh_r_q];
  assign sreq_free  = ~shd_req_valid_q | shd_req_ready_i;
  assign sh_to_shd  = sh_busy_q & sh_valid_r & sh_hit_r & sreq_free;
  assign sh_to_miss = sh_busy_q & sh_valid_r & ~sh_hit_r & miss_free;
  assign sh_adv     = sh_busy_q & (~sh_valid_r | sh_to_shd | sh_to_miss);
  assign sh_btri    = sh_btri_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      shp_v_q         <= 1'b0;
      shp_thr_q       <= '0;
      gshp_q          <= '0;
      sh_busy_q       <= 1'b0;
      sh_thr_q        <= '0;
      sh_r_q          <= '0;
      shd_req_valid_q <= 1'b0;
      shd_req_rid_q   <= '0;
      shd_req_index_q <= '0;
      miss_v_q        <= 1'b0;
      miss_rid_q      <= '0;
    end else begin
      shp_v_q   <= shp_any & shp_room;
      shp_thr_q <= shp_thr;
      gshp_q    <= g_shp;
      if (shp_v_q && !shp_none) begin
        sh_busy_q <= 1'b1;
        sh_thr_q  <= shp_thr_q;
        sh_r_q    <= '0;
      end
      if (sh_adv) begin
        sh_r_q <= sh_r_q + 2'd1;
        if (sh_r_q == 2'd3) sh_busy_q <= 1'b0;
      end
      if (shd_req_valid_q && shd_req_ready_i) shd_req_valid_q <= 1'b0;
      if (sh_to_shd) begin
        shd_req_valid_q <= 1'b1;
        shd_req_rid_q   <= {sh_thr_q, sh_r_q};
        shd_req_index_q <= lane_32(sh_btri, sh_r_q);
      end
      if (miss_take) miss_v_q <= 1'b0;
      if (sh_to_miss) begin
        miss_v_q   <= 1'b1;
        miss_rid_q <= {sh_thr_q, sh_r_q};
      end
    end
  end

  assign shd_req_valid_o = shd_req_valid_q;
  assign shd_req_tag_o   = TagW'(shd_req_rid_q);
  assign shd_req_index_o = shd_req_index_q;

  // Shading record -> material request (an error response shades with kd = 0: black).
  logic            sr_take;
  logic [RidW-1:0] sr_rid;
  localparam int unsigned NlenLsb = 8 * rc_pkg::ImageShadingFirstValue +
                                    rc_pkg::ImageShadingNormalLen * W;

  assign mreq_free       = ~mat_req_valid_q | mat_req_ready_i;
  assign shd_rsp_ready_o = mreq_free;
  assign sr_take         = shd_rsp_valid_i & mreq_free;
  assign sr_rid          = shd_rsp_tag_i[RidW-1:0];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      mat_req_valid_q <= 1'b0;
      mat_req_rid_q   <= '0;
      mat_req_index_q <= '0;
    end else begin
      if (mat_req_valid_q && mat_req_ready_i) mat_req_valid_q <= 1'b0;
      if (sr_take) begin
        mat_req_valid_q <= 1'b1;
        mat_req_rid_q   <= sr_rid;
        mat_req_index_q <= shd_rsp_error_i ? 32'd0 :
                           shd_rsp_data_i[8 * rc_pkg::ImageShadingMaterial +: 32];
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (sr_take) nlen_m[32'(sr_rid)] <= shd_rsp_data_i[NlenLsb +: W];
  end

  assign mat_req_valid_o = mat_req_valid_q;
  assign mat_req_tag_o   = TagW'(mat_req_rid_q);
  assign mat_req_index_o = mat_req_index_q;

  // Material -> shading unit. The material response and the ray's values read by its tag
  // (|n|, the hit's dz and the ray's inverse length, distributed RAMs addressed by the tag) go
  // into a register slice (ma_*_q) that takes a response whenever it is empty or the shading
  // unit takes its entry: the reads end at flip-flops and the shading unit's first multipliers
  // start at them. The slice adds a cycle of latency and no bubble.
  logic            sh_ready, sh_in_take, mr_bad, sho_v, fbb_free, ma_free, ma_load, ma_v_q;
  logic [RidW-1:0] mr_rid, sho_rid, ma_rid_q;
  logic [ThrW-1:0] mr_thr;
  logic [1:0]      mr_r;
  logic [3*W-1:0]  mr_kd, ma_kd_q;
  logic [4*W-1:0]  mr_dz_all, mr_ilen_all;
  logic [W-1:0]    ma_dz_q, ma_nlen_q, ma_ilen_q;
  logic [23:0]     sho_rgb;

  assign mr_rid          = mat_rsp_tag_i[RidW-1:0];
  assign mr_thr          = mr_rid[RidW-1:2];
  assign mr_r            = mr_rid[1:0];
  assign mr_bad          = mat_rsp_error_i | serr_q[32'(mr_rid)];
  assign ma_free         = ~ma_v_q | sh_ready;
  assign mat_rsp_ready_o = ma_free;
  assign ma_load         = mat_rsp_valid_i & ma_free;
  assign sh_in_take      = ma_v_q & sh_ready;
  assign mr_dz_all       = bdz_m[mr_thr];
  assign mr_ilen_all     = ilen_m[mr_thr];
  assign mr_kd = mr_bad ? '0 : {mat_rsp_data_i[64 +: W], mat_rsp_data_i[32 +: W],
                                mat_rsp_data_i[0 +: W]};

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ma_v_q <= 1'b0;
    end else if (ma_free) begin
      ma_v_q <= mat_rsp_valid_i;
    end
  end
  always_ff @(posedge clk_i) begin
    if (ma_load) begin
      ma_rid_q  <= mr_rid;
      ma_dz_q   <= lane_w(mr_dz_all, mr_r);
      ma_nlen_q <= nlen_m[32'(mr_rid)];
      ma_ilen_q <= lane_w(mr_ilen_all, mr_r);
      ma_kd_q   <= mr_kd;
    end
  end

  rc_shade_unit #(
    .ExpW (ExpW),
    .FracW(FracW),
    .TagW (RidW)
  ) u_shade (
    .clk_i,
    .rst_ni,
    .valid_i  (ma_v_q),
    .ready_o  (sh_ready),
    .tag_i    (ma_rid_q),
    .dz_i     (ma_dz_q),
    .nlen_i   (ma_nlen_q),
    .inv_len_i(ma_ilen_q),
    .kd_i     (ma_kd_q),
    .ambient_i(ambient_i),
    .diffuse_i(diffuse_i),
    .valid_o  (sho_v),
    .ready_i  (fbb_free),
    .tag_o    (sho_rid),
    .rgb_o    (sho_rgb)
  );

  // Framebuffer write register: shaded rays first, then misses.
  logic            fb_valid_q, fb_hit_q, fb_take;
  logic [RidW-1:0] fb_rid_q;
  logic [23:0]     fb_rgb_q;
  logic [ThrW-1:0] fb_thr;
  logic [1:0]      fb_r;
  logic [127:0]    fb_pix_all, fb_btri_all;
  logic [4*W-1:0]  fb_bt_all, fb_bu_all, fb_bv_all;

  assign fbb_free  = ~fb_valid_q | fb_ready_i;
  assign miss_take = miss_v_q & fbb_free & ~sho_v;
  assign miss_free = ~miss_v_q | miss_take;
  assign fb_take   = fb_valid_q & fb_ready_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fb_valid_q <= 1'b0;
      fb_hit_q   <= 1'b0;
      fb_rid_q   <= '0;
      fb_rgb_q   <= '0;
    end else if (fbb_free) begin
      fb_valid_q <= sho_v | miss_v_q;
      if (sho_v) begin
        fb_hit_q <= 1'b1;
        fb_rid_q <= sho_rid;
        fb_rgb_q <= sho_rgb;
      end else if (miss_v_q) begin
        fb_hit_q <= 1'b0;
        fb_rid_q <= miss_rid_q;
        fb_rgb_q <= background_i;
      end
    end
  end

  assign fb_thr      = fb_rid_q[RidW-1:2];
  assign fb_r        = fb_rid_q[1:0];
  assign fb_pix_all  = pix_m[fb_thr];
  assign fb_btri_all = btri_m[fb_thr];
  assign fb_bt_all   = bt_m[fb_thr];
  assign fb_bu_all   = bu_m[fb_thr];
  assign fb_bv_all   = bv_m[fb_thr];

  assign fb_valid_o = fb_valid_q;
  assign fb_pixel_o = lane_32(fb_pix_all, fb_r);
  assign fb_rgb_o   = fb_rgb_q;
  assign fb_hit_o   = fb_hit_q;
  assign fb_tri_o   = fb_hit_q ? lane_32(fb_btri_all, fb_r) : 32'd0;
  assign fb_t_o     = fb_hit_q ? lane_w(fb_bt_all, fb_r) : '0;
  assign fb_u_o     = fb_hit_q ? lane_w(fb_bu_all, fb_r) : '0;
  assign fb_v_o     = fb_hit_q ? lane_w(fb_bv_all, fb_r) : '0;

  ////////////////////////////////////////
  // Thread state updates               //
  ////////////////////////////////////////

  logic            lr_dec, te_dec, io_dec;
  logic [2:0]      ev_err;                    // error bits raised this cycle (any thread)
  logic [Threads-1:0] pend_zero;

  assign lr_dec = lb_v_q;
  assign te_dec = ti_err_take;
  assign io_dec = wb_v_q & wb_last_q;

  // The thread state update, per thread as a flat AND-OR of its events: each event (a take of a
  // scheduler or unit with its thread number) is decoded to a one-hot thread vector, and every
  // event that writes a field applies only to threads in one state (a packet is taken by a free
  // thread, a fetch by a StFetch thread, ...), so at most one event writes each field of a thread
  // in a cycle (assertions below). No priority chain runs through the events: the depth from a
  // scheduler's choice to the state registers is a decoder and an OR tree.
  function automatic logic [Threads-1:0] hot(input logic en, input logic [ThrW-1:0] i);
    for (int unsigned t = 0; t < Threads; t++) hot[t] = en && (i == ThrW'(t));
  endfunction

  logic [Threads-1:0] h_su, h_nr, h_tr, h_lr, h_te, h_p2, h_wb, h_fb;
  // The schedulers' choices come one-hot from rc_rr_pick (grant_o) and are registered; the state
  // update acts on the registered grant in the next cycle, so a choice and the state it changes
  // are never in one cycle (and there is no index decode between them). Each choice already
  // had that cycle: the packet's arrays are written from the feeder registers (acc_v_q), the
  // node index and the leaf's list are read from the registered choice (fq, lu_load_q), the
  // pop and shading choices decide in the next cycle (pp_v_q, shp_v_q). A chosen thread still
  // shows its old state for that cycle: the fetch and pop choices, which can choose again at
  // once, mask it out of their requests; the others cannot choose in that cycle (the feeder,
  // the list unit and the shading choice are busy).
  assign h_acc = {Threads{acc_v_q}} & gacc_q;
  assign h_su  = hot(su_v, su_thr);
  assign h_fe  = gfe_q;
  assign h_nr  = hot(nr_take, nr_thr);
  assign h_tr  = tq_hot_q;
  assign h_lp  = {Threads{lu_load_q}} & glp_q;
  assign h_lr  = hot(lr_dec, lr_thr);
  assign h_te  = hot(te_dec, ti_thr_q);
  assign h_pe  = gpp_q;  // zero without a pop choice (pp_v_q), as the grant is
  assign h_p2  = gpop2_q;
  assign h_wb  = hot(wc_we_q, wc_thr_q);
  assign h_sx  = {Threads{shp_v_q}} & gshp_q;
  assign h_fb  = hot(fb_take, fb_thr);

  // The thread-independent parts of each event's new values.
  logic [3:0] su_st, nr_st, tr_st, p2_st;
  logic       nr_st_we, nr_bad_addr, nr_malf, tr_mask_we;
  logic [3:0] tr_next_mask;
  assign su_st       = (|su_mask_new) ? StFetch : StPop;
  assign nr_bad_addr = nr_err | (nr_leaf & nr_leaf_bad);
  assign nr_malf     = ~nr_err & ~nr_leaf & nr_malformed;
  assign nr_st_we    = nr_err | nr_leaf | nr_malformed;
  assign nr_st       = (nr_err || !nr_leaf || nr_leaf_bad || nr_empty) ?
                       StPop : StLeaf;
  assign tr_st       = tr_overflow ? StPop : StFetch;
  assign tr_mask_we  = ~tr_overflow;
  assign tr_next_mask = tq_next_mask_q;
  assign p2_st       = (|pop2_mask) ? StFetch : StPop;

  always_comb begin
    serr_d = serr_q;
    ev_err = '0;
    for (int unsigned t = 0; t < Threads; t++) begin
      logic [12:0] we;
      logic [3:0]  st_or, mask_or;
      logic [2:0]  err_or;
      logic        fb_last;
      fb_last = fbw_q[t*3 +: 3] == 3'd1;
      we = {h_acc[t], h_su[t] & su_last, h_fe[t], h_nr[t] & nr_st_we, h_tr[t], h_lp[t],
            pend_zero[t], h_pe[t] & ~pop_end_t[t], h_pe[t] & pop_end_t[t], h_p2[t],
            h_sx[t] & vm_any[t],   // the thread's own rays: h_sx is one-hot, so this is
            h_sx[t] & ~vm_any[t],  // shp_none without the choice's AND-OR
            h_fb[t] & fb_last};
      st_or = ({4{we[12]}} & StSetup) | ({4{we[11]}} & su_st) |
              ({4{we[10]}} & (node_empty_q ? StPop : StNode)) | ({4{we[9]}} & nr_st) |
              ({4{we[8]}} & tr_st) | ({4{we[7]}} & StLeafRun) | ({4{we[6]}} & StPop) |
              ({4{we[5]}} & StPopping) | ({4{we[4]}} & StDone) | ({4{we[3]}} & p2_st) |
              ({4{we[2]}} & StShade) | ({4{we[1]}} & StFree) | ({4{we[0]}} & StFree);
      st_d[t*4 +: 4] = (|we) ? st_or : st_q[t*4 +: 4];

      // Active rays: set-up results, the traversal's continuing child, a popped entry.
      mask_or = ({4{h_su[t]}} & su_mask_new) | ({4{h_tr[t] & tr_mask_we}} & tr_next_mask) |
                ({4{h_p2[t]}} & pop2_mask);
      mask_d[t*4 +: 4] = h_acc[t] ? 4'd0 :
                         (h_su[t] | (h_tr[t] & tr_mask_we) | (h_p2[t] & (|pop2_mask))) ?
                         mask_or : mask_q[t*4 +: 4];
      vmask_d[t*4 +: 4] = h_acc[t] ? feed_vmask_q : vmask_q[t*4 +: 4];
      bhit_d[t*4 +: 4] = h_acc[t] ? 4'd0 :
                         bhit_q[t*4 +: 4] | ({4{h_wb[t]}} & (4'd1 << wc_r_q));
      sp_d[t*SpW +: SpW] = h_acc[t] ? '0 :
                           (h_tr[t] & tr_push_ok) ? tq_sp1_q :
                           (h_pe[t] & ~pop_end_t[t]) ? sp_q[t*SpW +: SpW] - SpW'(1) :
                           sp_q[t*SpW +: SpW];

      // Error bits (sticky for the packet): the events' bits ORed in.
      err_or = '0;
      err_or[ErrMalformed] = (h_fe[t] & node_empty_q) | (h_nr[t] & nr_malf);
      err_or[ErrBadAddr]   = (h_nr[t] & nr_bad_addr) | h_lr[t] | h_te[t];
      err_or[ErrOverflow]  = h_tr[t] & tr_overflow;
      err_d[t*3 +: 3] = h_acc[t] ? 3'd0 : err_q[t*3 +: 3] | err_or;

      // Framebuffer writes still due: set when shading takes the packet, counted down by writes.
      fbw_d[t*3 +: 3] = h_sx[t] ? popcount4(vmask_q[t*4 +: 4]) :
                        h_fb[t] ? fbw_q[t*3 +: 3] - 3'd1 : fbw_q[t*3 +: 3];
    end

    // The sticky status bits of the whole core.
    if (fe_took_q && node_empty_q) ev_err[ErrMalformed] = 1'b1;
    if (nr_take && nr_malf) ev_err[ErrMalformed] = 1'b1;
    if (nr_take && nr_bad_addr) ev_err[ErrBadAddr] = 1'b1;
    if (tr_v && tr_overflow) ev_err[ErrOverflow] = 1'b1;
    if (lr_dec || te_dec) ev_err[ErrBadAddr] = 1'b1;
    if (sr_take) begin
      for (int unsigned k = 0; k < Threads * 4; k++) begin
        if (sr_rid == RidW'(k)) serr_d[k] = shd_rsp_error_i;
      end
      if (shd_rsp_error_i) ev_err[ErrBadAddr] = 1'b1;
    end
    if (ma_load && mat_rsp_error_i) ev_err[ErrBadAddr] = 1'b1;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st_q    <= {Threads{StFree}};
      mask_q  <= '0;
      vmask_q <= '0;
      bhit_q  <= '0;
      sp_q    <= '0;
      err_q   <= '0;
      fbw_q   <= '0;
      serr_q  <= '0;
    end else begin
      st_q    <= st_d;
      mask_q  <= mask_d;
      vmask_q <= vmask_d;
      bhit_q  <= bhit_d;
      sp_q    <= sp_d;
      err_q   <= err_d;
      fbw_q   <= fbw_d;
      serr_q  <= serr_d;
    end
  end

  // A leaf's triangles outstanding, per thread, as the list entries in flight (issued by the list
  // unit and not yet finished) while the list unit no longer issues for the thread: a counter of
  // a few bits instead of the leaf's 32-bit triangle count counted down, so the leaf's end
  // (pend_zero) is a small compare. An entry in flight holds a tag (at most ListTags) until its
  // triangle enters the issue register, and after that sits in the issue register, the input
  // slice, the intersection unit (at most its FIFO depth of tests: the latency of its fp
  // pipeline, rc_isect_unit's contract, plus 2) or the iu, io and wb registers: LfMax bounds
  // them.
  // Up to three entries finish in one cycle (a failed list entry, a failed triangle read and an
  // intersection result); the last one finishes after the list unit has issued it, so the leaf
  // ends when it has finished (a cycle later, below).
  localparam int unsigned IsectDepth = 2 + (rc_pkg::FpStagesMul + 3 * rc_pkg::FpStagesAdd) +
                                       rc_pkg::FpStagesDiv + rc_pkg::FpStagesMul +
                                       2 * rc_pkg::FpStagesAdd + rc_pkg::FpStagesCmp + 2;
  // The finishing entries are counted per thread and registered (pend_dec, from the three
  // events' thread numbers), so the events, which come from across the chip, end at flip-flops
  // next to their thread's counter: the counter and the leaf's end see them a cycle late. A
  // finished entry is then counted one cycle longer, so the bound is one more than the entries
  // in flight; the leaf still ends only after its last entry is done and the list unit has let
  // the thread go (the list unit takes a StLeaf thread, and the thread is StLeafRun until it
  // ends), and the commit of its last hit (the cycle after its io_dec) is then already made.
  localparam int unsigned LfMax = ListTags + 2 + IsectDepth + 4;
  localparam int unsigned LfW   = $clog2(LfMax + 1);
  logic [2*Threads-1:0] pend_dec, pend_dec_d;    // thread t at [2t +: 2]
  // Whether a thread's count is 1, 2 or 3 is registered with the count (lf_small_q, from the
  // next count), so the leaf's end is the finishing entries' count against three flip-flops.
  logic [Threads*LfW-1:0] lf_q, lf_d;           // entries in flight, thread t at [t*LfW +: LfW]
  logic [Threads*3-1:0]   lf_small_q, lf_small_d;  // count == 1, 2, 3 at [3t], [3t+1], [3t+2]
  // The list unit's issues are counted a cycle late too (lf_inc_q, per thread), so the issue,
  // which waits on the tag search's flip-flops, ends at one flip-flop per thread instead of
  // the counter and its small-count compares (run 30: -1.70 ns, 48 inputs). A thread with an
  // issue still to count is still issuing.
  logic [Threads-1:0]     lf_inc_q, lf_inc_d;
  always_comb begin
    for (int unsigned t = 0; t < Threads; t++) begin
      logic issuing;
      logic [1:0] dec;
      lf_inc_d[t] = li_take && lu_thr_q == ThrW'(t);
      issuing = (lu_busy_q && lu_thr_q == ThrW'(t)) || lf_inc_q[t];
      pend_dec_d[2*t +: 2] = 2'(lr_dec && lr_thr == ThrW'(t)) +
                             2'(te_dec && ti_thr_q == ThrW'(t)) +
                             2'(io_dec && wb_thr_q == ThrW'(t));
      dec = pend_dec[2*t +: 2];
      lf_d[t*LfW +: LfW] = lf_q[t*LfW +: LfW] + LfW'(lf_inc_q[t]) - LfW'(dec);
      for (int unsigned k = 1; k <= 3; k++) begin
        lf_small_d[3*t + k - 1] = lf_d[t*LfW +: LfW] == LfW'(k);
      end
      pend_zero[t] = !issuing && ((dec == 2'd1 && lf_small_q[3*t]) ||
                                  (dec == 2'd2 && lf_small_q[3*t + 1]) ||
                                  (dec == 2'd3 && lf_small_q[3*t + 2]));
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lf_q       <= '0;
      lf_small_q <= '0;
      pend_dec   <= '0;
      lf_inc_q   <= '0;
    end else begin
      lf_q       <= lf_d;
      lf_small_q <= lf_small_d;
      pend_dec   <= pend_dec_d;
      lf_inc_q   <= lf_inc_d;
    end
  end

  // Set-up results of the packet in set-up gather here (its rays leave set-up in order 0..3) and
  // go to the arrays as whole words with the fourth ray. Best-hit words: one ray's slot replaced.
  logic [12*W-1:0] su_inv_q, su_inv_new;
  logic [4*W-1:0]  su_tmin_q, su_tmax_q, su_tmin_new, su_tmax_new;
  logic [4*W-1:0]  wc_bt_new, wc_bu_new, wc_bv_new, wc_bdz_new;
  logic [127:0]    wc_btri_new;
  always_ff @(posedge clk_i) begin
    if (su_v) begin
      su_inv_q  <= su_inv_new;
      su_tmin_q <= su_tmin_new;
      su_tmax_q <= su_tmax_new;
    end
  end
  always_comb begin
    su_inv_new  = su_inv_q;
    su_tmin_new = su_tmin_q;
    su_tmax_new = su_tmax_q;
    su_inv_new  = put_lane_3w(su_inv_new, su_r, su_inv);
    su_tmin_new = put_lane_w(su_tmin_new, su_r, su_tmin);
    su_tmax_new = put_lane_w(su_tmax_new, su_r, su_tmax);
    // The commit's words: the thread's words with the ray's lane replaced (the other lanes as
    // they are; a lane without its hit bit is never read ungated).
    wc_bt_new   = put_lane_w(bt_m[wc_thr_q], wc_r_q, wc_t_q);
    wc_bu_new   = put_lane_w(bu_m[wc_thr_q], wc_r_q, wc_u_q);
    wc_bv_new   = put_lane_w(bv_m[wc_thr_q], wc_r_q, wc_vb_q);
    wc_bdz_new  = put_lane_w(bdz_m[wc_thr_q], wc_r_q, wc_dz_q);
    wc_btri_new = put_lane_32(btri_m[wc_thr_q], wc_r_q, wc_tri_q);
  end

  logic              push_v_q;
  logic [StkAW-1:0]  push_addr_q;
  logic [EntryW-1:0] push_data_q;

  // The current entry's write is registered (cur_*_q) and done in the next cycle, so the
  // choice among pop, traversal and set-up (the cull's and the traversal's masks) ends at
  // flip-flops instead of at the write enables of node_m, tmin_m and tmax_m. No read misses
  // it: the thread's next fetch reads node_m two cycles after the event at the earliest (the
  // state changes, then the registered fetch choice reads), and the interval is read when the
  // node's response arrives (CurWriteFirst_A).
  logic             cur_we, cur_we_q;
  logic [ThrW-1:0]  cur_thr, cur_thr_q;
  logic [NodeW-1:0] cur_node, cur_node_q;
  logic [4*W-1:0]   cur_tmin, cur_tmax, cur_tmin_q, cur_tmax_q;
  always_comb begin
    cur_we   = 1'b0;
    cur_thr  = su_thr;
    cur_node = '0;
    cur_tmin = su_tmin_new;
    cur_tmax = su_tmax_new;
    if (pop2_v) begin
      cur_we   = |pop2_mask;
      cur_thr  = pop2_thr_q;
      cur_node = pop2_entry_q[8*W+4 +: NodeW];
      cur_tmin = pop2_entry_q[4*W +: 4*W];
      cur_tmax = pop2_entry_q[0 +: 4*W];
    end else if (tr_v) begin
      cur_we   = ~tr_overflow;
      cur_thr  = tr_thr;
      cur_node = tq_a_any_q ? tr_first : tr_second;
      cur_tmin = tq_a_any_q ? tr_a_tmin : tr_b_tmin;
      cur_tmax = tq_a_any_q ? tr_a_tmax : tr_b_tmax;
    end else if (su_last) begin
      cur_we   = 1'b1;
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      cur_we_q <= 1'b0;
      push_v_q <= 1'b0;
    end else begin
      cur_we_q <= cur_we;
      push_v_q <= tr_push_ok;
    end
  end

  always_ff @(posedge clk_i) begin
    if (acc_v_q) begin
      org_m[feed_thr_q]  <= feed_org_q;
      dir_m[feed_thr_q]  <= feed_dir_q;
      dsign_m[feed_thr_q] <= dir_signs(feed_dir_q);
      ilen_m[feed_thr_q] <= feed_ilen_q;
      pix_m[feed_thr_q]  <= feed_pix_q;
    end
    if (su_last) inv_m[su_thr] <= su_inv_new;
    // The current entry: one write port (at most one of pop, traversal, set-up per cycle),
    // a cycle after the event.
    cur_thr_q  <= cur_thr;
    cur_node_q <= cur_node;
    cur_tmin_q <= cur_tmin;
    cur_tmax_q <= cur_tmax;
    if (cur_we_q) begin
      node_m[cur_thr_q] <= cur_node_q;
      tmin_m[cur_thr_q] <= cur_tmin_q;
      tmax_m[cur_thr_q] <= cur_tmax_q;
    end
    if (nr_take && !nr_err && nr_leaf) begin
      loff_m[nr_thr] <= {{(32 - NodeW){1'b0}}, nr_idx};
      lcnt_m[nr_thr] <= nr_upper;
    end
    // The push is registered (push_*_q) and written a cycle later, so the traversal result's
    // logic ends at flip-flops instead of at the stack's block RAM across the chip. The pushing
    // thread pops no sooner than after its next node's response (PushFirst_A).
    push_addr_q <= StkAW'({tr_thr, tr_sp[SpIdxW-1:0] + SpIdxW'(1)});
    push_data_q <= {tr_second, tr_b_mask, tr_b_tmin, tr_b_tmax};
    if (push_v_q) stack_m[push_addr_q] <= push_data_q;
    if (wc_we_q) begin
      bt_m[wc_thr_q]   <= wc_bt_new;
      bu_m[wc_thr_q]   <= wc_bu_new;
      bv_m[wc_thr_q]   <= wc_bv_new;
      bdz_m[wc_thr_q]  <= wc_bdz_new;
      btri_m[wc_thr_q] <= wc_btri_new;
    end
  end

  // Tag pool, per tag as a flat AND-OR: the taken tag is the one-hot lowest free tag itself
  // (tag_first, not its index decoded again), and a tag is freed only while it is in use
  // (ListRspTag_A, TriRspTag_A), so taking and freeing never meet on one tag. The free of a
  // triangle's tag as it enters the issue register is registered (tl_*_q) and made a cycle
  // later, so the issue register's load, which waits on the intersection unit's ready across
  // the chip, ends at two flip-flops instead of at every tag's free bit (run 22's critical
  // path); the tag pool was read at the load, and the tag is offered again a cycle later.
  logic           tl_v_q;
  logic [LtW-1:0] tl_tag_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tl_v_q <= 1'b0;
    end else begin
      tl_v_q <= ti_load;
    end
  end
  always_ff @(posedge clk_i) begin
    tl_tag_q <= ti_tag;
  end
  always_comb begin
    for (int unsigned i = 0; i < ListTags; i++) begin
      tf_d[i] = (tf_q[i] & ~(li_take & tag_first[i])) |
                (lr_dec & (lb_tag_q == LtW'(i))) |
                (tl_v_q & (tl_tag_q == LtW'(i)));
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tf_q <= '1;
    end else begin
      tf_q <= tf_d;
    end
  end

  ////////////////////////////////////////
  // Status                             //
  ////////////////////////////////////////

  logic            idle, wd_fire, wd_clr;
  logic [14:0]     wd_ev_d, wd_ev_q;
  logic [31:0]     wd_q;
  logic [StatusW-1:0] error_q;

  assign idle    = (&free_vec) & ~feed_busy_q;
  assign wd_ev_d = {idle, acc_take, fb_take,
                    node_req_valid_q & node_req_ready_i, n0_take, nr_take,
                    list_req_valid_q & list_req_ready_i, lr_take,
                    tri_req_valid_q & tri_req_ready_i, tri_rsp_valid_i & tri_rsp_ready_o,
                    shd_req_valid_q & shd_req_ready_i, sr_take,
                    mat_req_valid_q & mat_req_ready_i, ma_load, sh_in_take};
  // Whether the core was idle or completed a handshake is registered, each event on its own
  // (wd_ev_q: the handshakes come from every port across the chip, so each ends at a flip-flop
  // near its port), then ORed in four groups into registers (wd_grp_q), whose OR clears the
  // count: no net runs from all of the ports to the count's 32 bits in one cycle (run 26's
  // critical path). The count sees the events two cycles late; it fires at WatchdogCycles - 1
  // and never in the cycle a clear arrives, so it counts WatchdogCycles cycles without a
  // handshake and the bit shows a cycle after the undelayed count would (the contract's + 2).
  logic [3:0] wd_grp_q;
  assign wd_clr  = |wd_grp_q;
  assign wd_fire = (wd_q == 32'(WatchdogCycles - 1)) & ~wd_clr;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wd_q     <= '0;
      wd_ev_q  <= 15'd1;
      wd_grp_q <= 4'd1;
      error_q  <= '0;
    end else begin
      wd_ev_q  <= wd_ev_d;
      wd_grp_q <= {|wd_ev_q[14:12], |wd_ev_q[11:8], |wd_ev_q[7:4], |wd_ev_q[3:0]};
      if (wd_clr) begin
        wd_q <= '0;
      end else if (!wd_fire) begin
        wd_q <= wd_q + 32'd1;
      end
      error_q[2:0] <= error_q[2:0] | ev_err;
      if (wd_fire) error_q[ErrWatchdog] <= 1'b1;
    end
  end

  assign idle_o  = idle;
  assign error_o = error_q;
  assign dbg_thread_state_o = st_q;

  ////////////////////////////////////////
  // Performance counters               //
  ////////////////////////////////////////

  logic [NPerf*64-1:0] perf_q;
  logic [3*NPerf-1:0]  perf_inc;                 // counter k at [3k +: 3]

  always_comb begin
    perf_inc = '0;
    perf_inc[3*rc_pkg::CorePerfCycles +: 3]           = 3'd1;
    perf_inc[3*rc_pkg::CorePerfBusyCycles +: 3]       = 3'(!idle);
    perf_inc[3*rc_pkg::CorePerfPackets +: 3]          = 3'(acc_take);
    perf_inc[3*rc_pkg::CorePerfRays +: 3]             = acc_take ? popcount4(pkt_mask_i) : 3'd0;
    perf_inc[3*rc_pkg::CorePerfNodesFetched +: 3]     = 3'(fe_took_q && !node_empty_q);
    perf_inc[3*rc_pkg::CorePerfInnerVisits +: 3]      = 3'(nr_take && nr_inner_ok);
    perf_inc[3*rc_pkg::CorePerfTraversalSteps +: 3]   = (nr_take && nr_inner_ok) ? popcount4(nr_mask) : 3'd0;
    perf_inc[3*rc_pkg::CorePerfLeafVisits +: 3]       = 3'(nr_take && !nr_err && nr_leaf);
    perf_inc[3*rc_pkg::CorePerfEmptyLeaves +: 3]      = 3'(nr_take && !nr_err && nr_leaf &&
                                                    nr_empty);
    perf_inc[3*rc_pkg::CorePerfListEntries +: 3]      = 3'(lr_take);
    perf_inc[3*rc_pkg::CorePerfTriangleTests +: 3]    = 3'(is_take);
    perf_inc[3*rc_pkg::CorePerfStackPushes +: 3]      = 3'(tr_push_ok);
    perf_inc[3*rc_pkg::CorePerfStackPops +: 3]        = 3'(pp_v_q && !pp_end);
    perf_inc[3*rc_pkg::CorePerfCulledPops +: 3]       = 3'(pop2_v && pop2_mask == 4'd0);
    perf_inc[3*rc_pkg::CorePerfFailedPackets +: 3]    = 3'(pp_v_q && (|get3(err_q, pp_thr_q)));
    perf_inc[3*rc_pkg::CorePerfSetupBusy +: 3]        = 3'(su_take);
    perf_inc[3*rc_pkg::CorePerfTravBusy +: 3]         = 3'(nr_take && nr_inner_ok);
    perf_inc[3*rc_pkg::CorePerfListBusy +: 3]         = 3'(li_take);
    perf_inc[3*rc_pkg::CorePerfIsectBusy +: 3]        = 3'(is_take);
    perf_inc[3*rc_pkg::CorePerfShadeBusy +: 3]        = 3'(sh_in_take);
    perf_inc[3*rc_pkg::CorePerfNodeRequests +: 3]     = 3'(node_req_valid_q && node_req_ready_i);
    perf_inc[3*rc_pkg::CorePerfListRequests +: 3]     = 3'(list_req_valid_q && list_req_ready_i);
    perf_inc[3*rc_pkg::CorePerfTriRequests +: 3]      = 3'(tri_req_valid_q && tri_req_ready_i);
    perf_inc[3*rc_pkg::CorePerfShadingRequests +: 3]  = 3'(shd_req_valid_q && shd_req_ready_i);
    perf_inc[3*rc_pkg::CorePerfMaterialRequests +: 3] = 3'(mat_req_valid_q && mat_req_ready_i);
    perf_inc[3*rc_pkg::CorePerfFbWrites +: 3]         = 3'(fb_take);
  end

  // The increments are registered first (perf_inc_q, and the stack depth after a push in
  // push_depth_q, valid with the registered push count), so that no event logic shares a cycle
  // with the 64-bit adders: the counters lag the events by one cycle.
  logic [3*NPerf-1:0] perf_inc_q;
  logic [SpW:0]       push_depth_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      perf_inc_q   <= '0;
      push_depth_q <= '0;
      perf_q       <= '0;
    end else begin
      perf_inc_q   <= perf_inc;
      push_depth_q <= (SpW + 1)'(tr_sp) + (SpW + 1)'(1);
      for (int unsigned k = 0; k < NPerf; k++) begin
        if (k == rc_pkg::CorePerfMaxStack) begin
          if (perf_inc_q[3*rc_pkg::CorePerfStackPushes] &&
              64'(push_depth_q) > perf_q[k*64 +: 64]) begin
            perf_q[k*64 +: 64] <= 64'(push_depth_q);
          end
        end else begin
          perf_q[k*64 +: 64] <= perf_q[k*64 +: 64] + 64'(perf_inc_q[3*k +: 3]);
        end
      end
    end
  end

  assign perf_o = (32'(perf_sel_i) < NPerf) ? perf_q[32'(perf_sel_i)*64 +: 64] : 64'd0;

  // Bits the core does not use: tag bits above its own tags, the node response's second record
  // (record i + 1) and the root record (this core fetches node 0 through the node port), the
  // shading record's unit normal, the upper byte of each kd slot, the lock-step copies of the
  // traversal tags and valids.
  logic unused_bits;
  assign unused_bits = ^{node_rsp_tag_i, node_rsp_data_i[NodeRspW-1:NodeRecW], root_node_i,
                         list_rsp_tag_i, tri_rsp_tag_i, shd_rsp_tag_i,
                         shd_rsp_data_i, mat_rsp_tag_i, mat_rsp_data_i, trav_tag_all, pop_cmp_v,
                         hd_lsign, hd_idx};  // the head's fields used after tq only

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
  logic [LfW-1:0] wb_pend;
  assign wb_pend = lf_q[32'(wb_thr_q)*LfW +: LfW];

  // The flat thread state update relies on these: at most one event per thread and cycle among
  // those that write its state, mask or stack pointer, each for a thread in the state it leaves.
  for (genvar t = 0; t < Threads; t++) begin : g_event_checks
    logic [3:0] st_t;
    assign st_t = st_q[t*4 +: 4];
    EventsExclusive_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                        $onehot0({h_acc[t], h_su[t], h_fe[t], h_nr[t], h_tr[t],
                                                  h_lp[t], pend_zero[t], h_pe[t], h_p2[t],
                                                  h_sx[t], h_fb[t]}));
    EventState_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   (!h_acc[t] || st_t == StFree) &&
                                   (!h_fe[t] || st_t == StFetch) &&
                                   (!h_lp[t] || st_t == StLeaf) &&
                                   (!(pend_zero[t] || h_lr[t] || h_te[t]) ||
                                    st_t == StLeafRun) &&
                                   // the commit of a leaf's last result comes as its walk pops
                                   (!h_wb[t] || st_t == StLeafRun || st_t == StPop) &&
                                   (!h_pe[t] || st_t == StPop) &&
                                   (!h_p2[t] || st_t == StPopping) &&
                                   (!h_sx[t] || st_t == StDone) &&
                                   (!h_fb[t] || st_t == StShade));
  end
  // The shading choice's request register mirrors the thread states.
  DoneMirror_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 done_q == done_vec);
  // The shading choice's one-hot grant is its thread (shp_none and the events read the grant).
  ShadeGrant_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 shp_v_q |-> gshp_q == hot(1'b1, shp_thr_q));
  // The registered free-thread choice is a free thread when the packet input offers it.
  AccChoiceFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    pkt_ready_o |-> st_q[acc_thr_q*4 +: 4] == StFree &&
                                                    gacc_c_q == hot(1'b1, acc_thr_q));
  // The issue register's registered hit bits are a subset of its thread's hit bits now (so the
  // best hits it gates are the rays' current ones, or +inf).
  TiHitSubset_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  ti_v_q |-> (ti_hit_q & ~get4(bhit_q, ti_thr_q)) == 4'd0);
  // The four traversal sub-units take the same operations, so they stay in lock step.
  TravLockStep_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   (&trav_ready_all || ~|trav_ready_all) &&
                                   (&trav_v_all || ~|trav_v_all));
  // A node response answers the node request of a thread that waits for it.
  NodeRspOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   nr_take |-> st_q[nr_thr*4 +: 4] == StNode);
  // ... also when it arrives: its checks read the thread's node_m then (stable while StNode).
  NodeRspEarly_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   n0_take |-> st_q[n0_thr*4 +: 4] == StNode);
  // The payload carried through the traversal sub-units is still the thread's state.
  logic [4*W-1:0] tr_lo_now, tr_hi_now;
  logic [3:0]     tr_mask_now;
  logic [SpW-1:0] tr_sp_now;
  assign tr_lo_now   = tmin_m[tr_thr];
  assign tr_hi_now   = tmax_m[tr_thr];
  assign tr_mask_now = get4(mask_q, tr_thr);
  assign tr_sp_now   = getsp(sp_q, tr_thr);
  TravPayload_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  tr_v |-> tr_mask == tr_mask_now && tr_sp == tr_sp_now &&
                                  tr_lo == tr_lo_now && tr_hi == tr_hi_now);
  // Traversal results belong to threads in the traversal sub-units.
  TravOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                tr_v |-> st_q[tr_thr*4 +: 4] == StNode);
  // A traversal result never meets a pop result on the current-entry port (tr_ready looked
  // ahead with pop1_v_q).
  TravSlot_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               !(tr_v && pop2_v) && (pop2_v == $past(pop1_v_q)));
  // Set-up's slot on the port is free exactly when neither a pop nor a traversal result acts.
  SetupSlot_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                su_out_ready == (~pop2_v & ~tr_v));
  // Only a root (from set-up) can be outside the node section; every other current node is a
  // child checked with its parent (fe_bad relies on this).
  CurNodeInRange_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                     cur_we && !su_last |->
                                     {{(32 - NodeW){1'b0}}, cur_node} < node_count_i);
  // No pop reads a thread's stack while its registered push is still due.
  PushFirst_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                push_v_q |-> !(pp_v_q &&
                                               StkAW'({pp_thr_q, pp_sp[SpIdxW-1:0]}) ==
                                               push_addr_q));
  // No read of a thread's current entry comes while its registered write is still due.
  CurWriteFirst_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    cur_we_q |-> !(fq_v_q && nreq_free && fq_thr_q == cur_thr_q) &&
                                                 !(n0_take && n0_thr == cur_thr_q) &&
                                                 !(nr_take && nr_thr == cur_thr_q));
  // The node count does not change under a fetch (quasi-static configuration).
  NodeEmptyStable_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                      fe_take |-> node_empty_q == (node_count_i == 32'd0));
  // The gathered mask is the thread's mask so far (set to 0 when the packet was taken).
  logic [3:0] su_mask_now;
  logic       su_vbit_now;
  assign su_mask_now = get4(mask_q, su_thr);
  assign su_vbit_now = vmask_q[32'(su_thr)*4 + 32'(su_r)];
  SetupMask_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                su_v |-> su_mask_base == su_mask_now &&
                                su_tag[RidW] == su_vbit_now);
  // Ray set-up results belong to threads in set-up.
  SetupOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 su_v |-> st_q[su_thr*4 +: 4] == StSetup);
  // A list entry waits in the skid buffer only behind a request the port has not taken.
  ListSkid_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               lsk_v_q |-> list_req_valid_q);
  // List and triangle responses carry an outstanding tag of a thread in its leaf.
  logic [ThrW-1:0] lr_owner;
  assign lr_owner = tp_thr_m[lr_tag];
  ListRspTag_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 lq_v_q |-> !tf_q[lr_tag] &&
                                 st_q[lr_owner*4 +: 4] == StLeafRun);
  // A failed entry is retired a cycle later, its tag and thread still held.
  ListBadRetire_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    lb_v_q |-> !tf_q[lb_tag_q] &&
                                    st_q[lr_thr*4 +: 4] == StLeafRun);
  logic [LtW-1:0]  tr_port_tag;
  logic [ThrW-1:0] tr_port_owner;
  assign tr_port_tag   = tri_rsp_tag_i[LtW-1:0];
  assign tr_port_owner = tp_thr_m[tr_port_tag];
  TriRspTag_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                tri_rsp_valid_i |-> !tf_q[tr_port_tag] &&
                                st_q[tr_port_owner*4 +: 4] == StLeafRun);
  // ... and so does the response the skid buffer holds (its tag is freed only as it leaves).
  TriSkidTag_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 tk_v_q |-> !tf_q[tk_tag_q] && st_q[ti_thr*4 +: 4] == StLeafRun);
  // The rays a triangle is tested against (from the tag pool) are its thread's active rays now.
  TriMask_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              ti_v_q |-> ti_mask_q == get4(mask_q, ti_thr_q));
  // A leaf's packet has at least one active ray, so every triangle is tested at least once.
  TriHasRay_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                is_valid |-> ti_rem_q != 4'd0);
  // The registered next tag is free, one-hot with its index (or none while none was free).
  TagFirst_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               tag_avail_q ? (tf_q[tag_new_q] &&
                                              tag_first_q == ListTags'(1) << tag_new_q) :
                                             (tag_first_q == '0));
  // The lane copies are the lowest ray left.
  TiLane_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             ti_v_q && !ti_err_q |-> ti_r_org_q == ti_r && ti_r_dir_q == ti_r &&
                                                     ti_r_bt_q == ti_r && ti_r_btri_q == ti_r);
  // The rays left are the triangle's rays not yet sent, and the last-ray bit says one is left.
  TiRem_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            ti_v_q && !ti_err_q |-> (ti_rem_q & ~ti_mask_q) == 4'd0 &&
                            ti_last_q == ((ti_rem_q & (ti_rem_q - 4'd1)) == 4'd0));
  // Intersection results belong to threads in their leaf, with triangles still outstanding.
  IsectOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 wb_v_q |-> st_q[wb_thr_q*4 +: 4] == StLeafRun && wb_pend != '0);
  // The registered small-count flags are the count's.
  for (genvar t = 0; t < Threads; t++) begin : g_lf_small_checks
    LfSmall_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                lf_small_q[3*t +: 3] == {lf_q[t*LfW +: LfW] == LfW'(3),
                                                         lf_q[t*LfW +: LfW] == LfW'(2),
                                                         lf_q[t*LfW +: LfW] == LfW'(1)});
  end
  // The entries in flight stay within their bound (so the counter cannot wrap) and none
  // finishes that was not issued.
  for (genvar t = 0; t < Threads; t++) begin : g_lf_checks
    InFlight_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 32'(lf_q[t*LfW +: LfW]) <= LfMax &&
                                 32'(pend_dec[2*t +: 2]) <= 32'(lf_q[t*LfW +: LfW]));
  end
  // A commit improves the ray's committed best: with a stale best forwarded to the compare, a
  // worse hit could overwrite a better one.
  logic [W-1:0]  wc_old_t;
  logic [31:0]   wc_old_tri;
  assign wc_old_t   = lane_w(gate_t(bt_m[wc_thr_q], get4(bhit_q, wc_thr_q)), wc_r_q);
  assign wc_old_tri = lane_32(gate_tri(btri_m[wc_thr_q], get4(bhit_q, wc_thr_q)), wc_r_q);
  WbForward_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                wc_we_q |-> (wc_t_q < wc_old_t) ||
                                            (wc_t_q == wc_old_t && wc_tri_q < wc_old_tri));
  // The compare sees the ray's best as it will be after this cycle's commit: the committed one,
  // or the commit's own when it is the same ray's (then the two are compared, not forwarded).
  logic [W-1:0]  wb_now_t, wb_eff_t;
  logic [31:0]   wb_now_tri, wb_eff_tri;
  logic          wb_same_c;
  assign wb_now_t   = lane_w(gate_t(bt_m[wb_thr_q], get4(bhit_q, wb_thr_q)), wb_r_q);
  assign wb_now_tri = lane_32(gate_tri(btri_m[wb_thr_q], get4(bhit_q, wb_thr_q)), wb_r_q);
  assign wb_same_c  = wc_we_q && wc_thr_q == wb_thr_q && wc_r_q == wb_r_q;
  assign wb_eff_t   = (wb_pf_q && wc_we_q) ? wc_t_q : wb_bt_q;
  assign wb_eff_tri = (wb_pf_q && wc_we_q) ? wc_tri_q : wb_btri_q;
  WbBest_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             wb_v_q |-> (wb_pf_q && wc_we_q) == wb_same_c &&
                                        wb_eff_t == (wb_same_c ? wc_t_q : wb_now_t) &&
                                        wb_eff_tri == (wb_same_c ? wc_tri_q : wb_now_tri));
  // The best hits read with the stack entry are still the thread's (the cull uses them).
  logic [4*W-1:0] pop1_best_now;
  assign pop1_best_now = gate_t(bt_m[pop1_thr_q], get4(bhit_q, pop1_thr_q));
  PopBest_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              pop1_v_q |-> pop1_best_t == pop1_best_now);
  // The end bit picked by the pop's one-hot grant is the chosen thread's own (error or empty
  // stack), so the grant and the index agree.
  PopEnd_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             pp_v_q |-> gpp_q == hot(1'b1, pp_thr_q) &&
                                        pp_end == ((|get3(err_q, pp_thr_q)) || pp_sp == '0));
  // Without a pop choice the grant is zero (h_pe is the grant alone).
  PopNoGrant_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !pp_v_q |-> gpp_q == '0);
  // The traversal result's decisions made before its register agree with the result.
  TravEarly_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                tq_hot_q == hot(tr_v, tr_thr) && tq_sp1_q == tr_sp + SpW'(1) &&
                                tq_push_ok_q == (tr_v & tr_push & ~tr_overflow) &&
                                tr_overflow == (tr_push & tr_full) &&
                                tq_a_any_q == (|tr_a_mask) &&
                                tq_next_mask_q == (tq_a_any_q ? tr_a_mask : tr_b_mask));
  // A pop result belongs to a thread that is popping.
  PopOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               pop2_v |-> st_q[pop2_thr_q*4 +: 4] == StPopping);
  // The one-hot popping thread beside the pipeline is the result's thread, and only with one.
  PopHot_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             gpop2_q == hot(pop2_v, pop2_thr_q));
  // The shading sequencer's copies of its packet's rays, hits and triangles are still the
  // thread's.
  logic [127:0] sh_btri_now;
  assign sh_btri_now = btri_m[sh_thr_q];
  ShadeSnap_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                sh_busy_q |-> sh_vm_q == get4(vmask_q, sh_thr_q) &&
                                sh_hm_q == (get4(bhit_q, sh_thr_q) &
                                            {4{~(|get3(err_q, sh_thr_q))}}) &&
                                sh_btri_q == sh_btri_now);
  // Shading responses and framebuffer writes belong to threads being shaded.
  ShdRspOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  shd_rsp_valid_i |-> st_q[sr_rid[RidW-1:2]*4 +: 4] == StShade);
  MatRspOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  mat_rsp_valid_i |-> st_q[mr_thr*4 +: 4] == StShade);
  MatSliceOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    ma_v_q |-> st_q[ma_rid_q[RidW-1:2]*4 +: 4] == StShade);
  FbOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              fb_valid_q |-> st_q[fb_thr*4 +: 4] == StShade &&
                              fbw_q[fb_thr*3 +: 3] != 3'd0);
  // Requests and writes hold their payload until taken (the memory-port protocol).
  NodeReqStable_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    node_req_valid_o && !node_req_ready_i |=>
                                    node_req_valid_o && $stable(node_req_index_o));
  TriReqStable_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   tri_req_valid_o && !tri_req_ready_i |=>
                                   tri_req_valid_o && $stable(tri_req_index_o));
  FbStable_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               fb_valid_o && !fb_ready_i |=>
                               fb_valid_o && $stable({fb_pixel_o, fb_rgb_o, fb_t_o}));
  // Outputs that others act on are known after reset.
  OutputsKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   !$isunknown({pkt_ready_o, fb_valid_o, node_req_valid_o,
                                                list_req_valid_o, tri_req_valid_o,
                                                shd_req_valid_o, mat_req_valid_o, idle_o}));
`endif

endmodule
