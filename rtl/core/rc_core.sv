// rc_core: the ray tracing core. Traces four-ray packets through the kd-tree of a memory image and
// shades their closest hits, exactly by the rules of docs/architecture.md (rc::trace_packet() and
// rc::shade() of tb/golden/trace.hpp), with up to Threads packets in flight. This module is
// wiring: the units are the files named below, each with its contract at its top.
//
// Contract
// - Configuration inputs (bounds_i, *_count_i, root_node_i, ambient_i, diffuse_i, background_i,
//   t_eps_i) are quasi-static: change them only while idle_o is 1 and no packet is offered.
//   bounds_i: the header's root box (lo x, y, z, hi x, y, z); node/list/tri_count_i: the record
//   counts of those sections (the checks of docs/architecture.md, "Errors", use them);
//   root_node_i: node 0's record (every packet's walk starts there; unused when the node section
//   is empty); ambient_i/diffuse_i: the format values of ambient and 1 - ambient; background_i:
//   the miss colour, R [7:0], G [15:8], B [23:16]; t_eps_i: a secondary ray's hits need t_eps < t
//   (docs/architecture.md, "Lighting").
// - Packet input: valid/ready. pkt_mask_i bit r: ray r exists. Per ray r: origin and direction
//   component a at [(3r + a)*W +: W], inv_len at [r*W +: W], pixel id at [r*32 +: 32]. A packet
//   is taken into the set-up unit's input register whenever it is empty (pkt_ready_o is that
//   register's empty flag), and from there when a thread is free and the feeder is idle
//   (rc_setup_unit). pkt_kind_i (rc_pkg::ray_kind_e) says what the packet is: a primary packet
//   (RayPrimary), or one of secondary rays (docs/architecture.md, "Lighting", "Reflection",
//   "Refraction"): ray r's interval ends at its limit pkt_t_hi_i[r*W +: W], which is also its
//   initial best, and a hit needs t_eps_i < t and never its start triangle
//   pkt_start_tri_i[r*32 +: 32]; in a shadow packet (RayShadow) any hit ends the ray, the rays of
//   a mirror (RayBounce) or refraction (RayRefract) packet look for the closest hit (the core
//   treats the two kinds alike). A primary packet's t_hi and start triangles are not read.
// - Framebuffer write port: valid/ready, one write per existing ray of every packet, in no
//   particular order: fb_pixel_o (the ray's pixel id), fb_rgb_o, and the ray's hit record
//   (fb_hit_o, fb_tri_o, fb_t_o, fb_u_o, fb_v_o; zero on a miss) with its d'z (fb_dz_o, what a
//   tree controller needs to light the hit; zero on a miss, and always with Secondary = 0). A
//   packet that met an error writes the background with no hit for every ray. A secondary
//   packet's rays are not shaded: they write their hit records (a shadow ray's hit: it is
//   occluded; none: it reached its limit, the light) and colour 0, or 1 when the packet met an
//   error (no hits then).
// - Memory ports node_, list_, tri_, shd_, mat_: the protocol of docs/architecture.md ("Memory
//   ports"): request (index, tag) and response (tag, data, error) handshakes, responses in any
//   order after any delay. Records: node pair 128 bits (a request for node i answers records i
//   and i + 1: the core asks only for an inner node's two children), list entry 32, triangle
//   12*W, shading record 32 + 4*W, material 96 (the material record's kd field: three 32-bit
//   slots). Tags are CoreTagBits wide; the core never has two requests with the same tag
//   outstanding on a port.
// - Status: idle_o = no packet in flight and no write pending. error_o (sticky until reset):
//   CoreStatus* bits: malformed node, bad address (also any error response), stack overflow,
//   watchdog (work held and no handshake completed for WatchdogCycles cycles; error_o shows it
//   from the edge WatchdogCycles + 2 after the last handshake's).
// - Performance counters: perf_o = counter number perf_sel_i (CorePerf* of rc_pkg)
//   CorePerfReadLatency (2) cycles late: after the edge that follows the one sampling
//   perf_sel_i, perf_o shows that counter's word as it was before the sampling edge
//   (rc_core_status); numbers >= CorePerfCount read 0. The counters count an event one cycle
//   after it (registered increments), and a word is exact when it is sampled
//   CorePerfSettleCycles or more cycles after its counter's last event (before, it is the
//   counter's value of some recent cycle, never ahead of it): from CorePerfSettleCycles cycles
//   after idle_o rises, set perf_sel_i and read perf_o two edges later. Rays, traversal steps
//   and triangle tests are also counted per ray kind, under their packet's pkt_kind_i
//   (rc_kind_perf; with Secondary = 0 the primary ones read the totals and the others 0).
// - Debug: dbg_thread_state_o, every thread's state (rc_pkg::thread_state_e, ThreadStateBits per
//   thread), kept from the units' events in simulation (zero in synthesis); no logic depends on
//   it.
// - Handshakes: valid never depends on ready on any port; a valid with its payload stays until
//   taken. Every memory response asked for is taken eventually.
// - Illegal input: configuration changes while busy; a response with a tag that is not
//   outstanding, or two responses for one request (assertions catch both).
// - Parameters: ExpW/FracW must be the package's format (docs/spec.toml [fp24]: the records of
//   rc_pkg are typed with it); Threads 1 .. CoreMaxThreads; StackDepth a power of two up to
//   KdtreeStackDepth; ListTags >= 2; IsectInterval 1 or 2; SetupUnits 1 to 3; Secondary: 1 =
//   secondary packets as above, 0 = primary packets only (pkt_kind_i, pkt_t_hi_i,
//   pkt_start_tri_i and t_eps_i are not read, and no logic is made for them); Shade: 1 = primary
//   hits shaded as above, 0 = no ray shaded (for a tree controller that lights every hit itself:
//   a primary packet's rays write the background colour with their hit records, the shd_ and
//   mat_ ports make no requests, and no shading unit is built); BlockDelays: the intersection
//   unit's delay lines in block RAM instead of flip-flops (rc_isect_unit; the same cycles).
// - Reset: rst_ni, active low, asynchronous; clears all control state.
module rc_core #(
  parameter int unsigned ExpW           = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW          = rc_pkg::Fp24FracW,
  parameter int unsigned Threads        = rc_pkg::CoreThreads,
  parameter int unsigned StackDepth     = rc_pkg::KdtreeStackDepth,
  parameter int unsigned ListTags       = rc_pkg::CoreListTags,
  parameter int unsigned WatchdogCycles = rc_pkg::CoreWatchdogCycles,
  parameter int unsigned IsectInterval  = rc_pkg::CoreIsectInterval,
  parameter int unsigned SetupUnits     = rc_pkg::CoreSetupUnits,
  parameter bit          Secondary      = 1'b1,
  parameter bit          Shade          = 1'b1,
  parameter bit          BlockDelays    = 1'b0,
  // Derived (do not override).
  parameter int unsigned W              = 1 + ExpW + FracW,
  parameter int unsigned TagW           = rc_pkg::CoreTagBits,
  parameter int unsigned StatusW        = rc_pkg::CoreStatusBits,
  parameter int unsigned NodeRecW       = 8 * rc_pkg::KdNodeBytes,
  parameter int unsigned NodeRspW       = rc_pkg::CoreNodeRspRecords * NodeRecW
) (
  input  logic                clk_i,
  input  logic                rst_ni,

  // Configuration (quasi-static).
  input  logic [6*W-1:0]      bounds_i,
  input  logic [31:0]         node_count_i,
  input  logic [31:0]         list_count_i,
  input  logic [31:0]         tri_count_i,
  input  logic [NodeRecW-1:0] root_node_i,
  input  logic [W-1:0]        ambient_i,
  input  logic [W-1:0]        diffuse_i,
  input  logic [23:0]         background_i,
  input  logic [W-1:0]        t_eps_i,

  // Packet input.
  input  logic                pkt_valid_i,
  output logic                pkt_ready_o,
  input  logic [3:0]          pkt_mask_i,
  input  logic [12*W-1:0]     pkt_org_i,
  input  logic [12*W-1:0]     pkt_dir_i,
  input  logic [4*W-1:0]      pkt_inv_len_i,
  input  logic [127:0]        pkt_pixel_i,
  input  logic [rc_pkg::RayKindBits-1:0] pkt_kind_i,
  input  logic [4*W-1:0]      pkt_t_hi_i,
  input  logic [127:0]        pkt_start_tri_i,

  // Framebuffer write port.
  output logic                fb_valid_o,
  input  logic                fb_ready_i,
  output logic [31:0]         fb_pixel_o,
  output logic [23:0]         fb_rgb_o,
  output logic                fb_hit_o,
  output logic [31:0]         fb_tri_o,
  output logic [W-1:0]        fb_t_o,
  output logic [W-1:0]        fb_u_o,
  output logic [W-1:0]        fb_v_o,
  output logic [W-1:0]        fb_dz_o,

  // Memory port: kd nodes (pairs).
  output logic                node_req_valid_o,
  input  logic                node_req_ready_i,
  output logic [TagW-1:0]     node_req_tag_o,
  output logic [31:0]         node_req_index_o,
  input  logic                node_rsp_valid_i,
  output logic                node_rsp_ready_o,
  input  logic [TagW-1:0]     node_rsp_tag_i,
  input  logic [NodeRspW-1:0] node_rsp_data_i,
  input  logic                node_rsp_error_i,

  // Memory port: leaf lists.
  output logic                list_req_valid_o,
  input  logic                list_req_ready_i,
  output logic [TagW-1:0]     list_req_tag_o,
  output logic [31:0]         list_req_index_o,
  input  logic                list_rsp_valid_i,
  output logic                list_rsp_ready_o,
  input  logic [TagW-1:0]     list_rsp_tag_i,
  input  logic [31:0]         list_rsp_data_i,
  input  logic                list_rsp_error_i,

  // Memory port: triangles (unit-triangle transforms).
  output logic                tri_req_valid_o,
  input  logic                tri_req_ready_i,
  output logic [TagW-1:0]     tri_req_tag_o,
  output logic [31:0]         tri_req_index_o,
  input  logic                tri_rsp_valid_i,
  output logic                tri_rsp_ready_o,
  input  logic [TagW-1:0]     tri_rsp_tag_i,
  input  logic [12*W-1:0]     tri_rsp_data_i,
  input  logic                tri_rsp_error_i,

  // Memory port: shading records.
  output logic                shd_req_valid_o,
  input  logic                shd_req_ready_i,
  output logic [TagW-1:0]     shd_req_tag_o,
  output logic [31:0]         shd_req_index_o,
  input  logic                shd_rsp_valid_i,
  output logic                shd_rsp_ready_o,
  input  logic [TagW-1:0]     shd_rsp_tag_i,
  input  logic [32+4*W-1:0]   shd_rsp_data_i,
  input  logic                shd_rsp_error_i,

  // Memory port: materials (kd).
  output logic                mat_req_valid_o,
  input  logic                mat_req_ready_i,
  output logic [TagW-1:0]     mat_req_tag_o,
  output logic [31:0]         mat_req_index_o,
  input  logic                mat_rsp_valid_i,
  output logic                mat_rsp_ready_o,
  input  logic [TagW-1:0]     mat_rsp_tag_i,
  input  logic [95:0]         mat_rsp_data_i,
  input  logic                mat_rsp_error_i,

  // Status and counters.
  output logic                idle_o,
  output logic [StatusW-1:0]  error_o,
  input  logic [7:0]          perf_sel_i,
  output logic [63:0]         perf_o,

  // Debug.
  output logic [Threads*rc_pkg::ThreadStateBits-1:0] dbg_thread_state_o
);

  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned ThrW  = (Threads > 1) ? $clog2(Threads) : 1;
  localparam int unsigned LtW   = (ListTags > 1) ? $clog2(ListTags) : 1;
  localparam int unsigned SpW   = rc_pkg::CoreSpBits;
  localparam int unsigned NPerf = rc_pkg::CorePerfCount;

  if (ExpW != rc_pkg::Fp24ExpW || FracW != rc_pkg::Fp24FracW || Threads < 1 ||
      Threads > rc_pkg::CoreMaxThreads || ThrW + 2 > TagW || LtW > TagW || ListTags < 2 ||
      NodeRspW != 128 || WatchdogCycles < 2 || IsectInterval < 1 || IsectInterval > 2 ||
      SetupUnits < 1 || SetupUnits > 3) begin : g_param_check
    $error("rc_core: need the package's fp format, 1 <= Threads <= CoreMaxThreads, {thread, ray} and ListTags within the tags, IsectInterval 1 or 2, SetupUnits 1 to 3");
  end

  ///////////////////////////////
  // Ray set-up (packet intake) //
  ///////////////////////////////

  logic               acc_valid, raywr_valid, axwr_valid, invwr_valid, start_valid, start_ready;
  logic [ThrW-1:0]    acc_thr, raywr_thr, axwr_thr, invwr_thr;
  logic [3:0]         acc_vmask;
  logic               acc_anyhit, acc_sec;
  logic [rc_pkg::RayKindBits-1:0] acc_kind;
  logic [Threads-1:0] acc_hot;
  logic [1:0]         raywr_ray, axwr_axis, invwr_axis;
  logic [6*W-1:0]     raywr_orgdir;
  logic [W+31:0]      raywr_lenpix;
  logic [W+32:0]      raywr_lim;
  logic [4*W+3:0]     axwr_data;
  logic [4*W-1:0]     invwr_data;
  rc_pkg::walk_item_t start_item;
  logic               setup_all_free, perf_packet, perf_setup;
  logic [2:0]         perf_rays;
  logic               shd_free_valid, shd_free0_valid;
  logic [ThrW-1:0]    shd_free_thr, shd_free0_thr;

  rc_setup_unit #(
    .Threads   (Threads),
    .SetupUnits(SetupUnits),
    .Secondary (Secondary)
  ) u_setup (
    .clk_i,
    .rst_ni,
    .bounds_i,
    .root_node_i,
    .node_count_i,
    .list_count_i,
    .pkt_valid_i,
    .pkt_ready_o,
    .pkt_mask_i,
    .pkt_org_i,
    .pkt_dir_i,
    .pkt_inv_len_i,
    .pkt_pixel_i,
    .pkt_kind_i,
    .pkt_t_hi_i,
    .pkt_start_tri_i,
    .free_valid_i  (shd_free_valid),
    .free_thr_i    (shd_free_thr),
    .free0_valid_i (shd_free0_valid),
    .free0_thr_i   (shd_free0_thr),
    .acc_valid_o   (acc_valid),
    .acc_thr_o     (acc_thr),
    .acc_hot_o     (acc_hot),
    .acc_vmask_o   (acc_vmask),
    .acc_anyhit_o  (acc_anyhit),
    .acc_sec_o     (acc_sec),
    .acc_kind_o    (acc_kind),
    .raywr_valid_o (raywr_valid),
    .raywr_thr_o   (raywr_thr),
    .raywr_ray_o   (raywr_ray),
    .raywr_orgdir_o(raywr_orgdir),
    .raywr_lenpix_o(raywr_lenpix),
    .raywr_lim_o   (raywr_lim),
    .axwr_valid_o  (axwr_valid),
    .axwr_thr_o    (axwr_thr),
    .axwr_axis_o   (axwr_axis),
    .axwr_data_o   (axwr_data),
    .invwr_valid_o (invwr_valid),
    .invwr_thr_o   (invwr_thr),
    .invwr_axis_o  (invwr_axis),
    .invwr_data_o  (invwr_data),
    .start_valid_o (start_valid),
    .start_ready_i (start_ready),
    .start_item_o  (start_item),
    .all_free_o    (setup_all_free),
    .perf_packet_o (perf_packet),
    .perf_rays_o   (perf_rays),
    .perf_setup_o  (perf_setup)
  );

  ////////////////////////////////
  // Ray store, thread control  //
  ////////////////////////////////

  logic            trav_ax_re, isect_ray_re, shd_ilen_re, shd_pix_re;
  logic [ThrW-1:0] trav_ax_thr, isect_ray_thr, shd_ilen_thr, shd_pix_thr;
  logic [1:0]      trav_ax_axis, isect_ray_ray, shd_ilen_ray, shd_pix_ray;
  logic [4*W-1:0]  rays_ax_org, rays_ax_inv;
  logic [3:0]      rays_ax_sign;
  logic [6*W-1:0]  rays_od;
  logic [W+32:0]   rays_lim;
  logic [W-1:0]    rays_ilen;
  logic [31:0]     rays_pix;

  rc_ray_store #(
    .Threads(Threads),
    .Secondary(Secondary)
  ) u_rays (
    .clk_i,
    .ray_we_i     (raywr_valid),
    .ray_wthr_i   (raywr_thr),
    .ray_wray_i   (raywr_ray),
    .ray_worgdir_i(raywr_orgdir),
    .ray_wlenpix_i(raywr_lenpix),
    .ray_wlim_i   (raywr_lim),
    .ax_we_i      (axwr_valid),
    .ax_wthr_i    (axwr_thr),
    .ax_waxis_i   (axwr_axis),
    .ax_wdata_i   (axwr_data),
    .inv_we_i     (invwr_valid),
    .inv_wthr_i   (invwr_thr),
    .inv_waxis_i  (invwr_axis),
    .inv_wdata_i  (invwr_data),
    .ax_re_i      (trav_ax_re),
    .ax_rthr_i    (trav_ax_thr),
    .ax_raxis_i   (trav_ax_axis),
    .ax_org_o     (rays_ax_org),
    .ax_sign_o    (rays_ax_sign),
    .ax_inv_o     (rays_ax_inv),
    .od_re_i      (isect_ray_re),
    .od_rthr_i    (isect_ray_thr),
    .od_rray_i    (isect_ray_ray),
    .od_o         (rays_od),
    .lim_o        (rays_lim),
    .ilen_re_i    (shd_ilen_re),
    .ilen_rthr_i  (shd_ilen_thr),
    .ilen_rray_i  (shd_ilen_ray),
    .ilen_o       (rays_ilen),
    .pix_re_i     (shd_pix_re),
    .pix_rthr_i   (shd_pix_thr),
    .pix_rray_i   (shd_pix_ray),
    .pix_o        (rays_pix)
  );

  logic                   trav_err_valid, trav_reqnr_valid, stk_err_valid, list_err_valid;
  logic                   isect_err_valid, trav_sp_valid, hits_hit_valid, stk_sp_valid;
  logic [ThrW-1:0]        trav_err_thr, trav_reqnr_thr, stk_err_thr, list_err_thr;
  logic [ThrW-1:0]        isect_err_thr, trav_sp_thr, hits_hit_thr, stk_sp_thr;
  logic [ThrW-1:0]        stk_sp_rd_thr, shd_vm_rd_thr;
  logic [2:0]             trav_err_bits, stk_err_bits, list_err_bits, isect_err_bits;
  logic [SpW-1:0]         trav_sp_sp, stk_sp_sp, thr_sp_rd;
  logic [1:0]             hits_hit_ray;
  logic [Threads-1:0]     thr_err, thr_shadow;
  logic [Threads*4-1:0]   thr_hit;
  logic [3:0]             thr_vm_rd;
  logic                   thr_vm_rd_sec;

  rc_thread_ctrl #(
    .Threads(Threads)
  ) u_thr (
    .clk_i,
    .rst_ni,
    .acc_valid_i   (acc_valid),
    .acc_thr_i     (acc_thr),
    .acc_hot_i     (acc_hot),
    .acc_vmask_i   (acc_vmask),
    .acc_anyhit_i  (acc_anyhit),
    .acc_sec_i     (acc_sec),
    .err0_valid_i  (trav_err_valid),
    .err0_thr_i    (trav_err_thr),
    .err1_valid_i  (trav_reqnr_valid),
    .err1_thr_i    (trav_reqnr_thr),
    .err2_valid_i  (stk_err_valid),
    .err2_thr_i    (stk_err_thr),
    .err3_valid_i  (list_err_valid),
    .err3_thr_i    (list_err_thr),
    .err4_valid_i  (isect_err_valid),
    .err4_thr_i    (isect_err_thr),
    .sp_tr_valid_i (trav_sp_valid),
    .sp_tr_thr_i   (trav_sp_thr),
    .sp_tr_sp_i    (trav_sp_sp),
    .sp_pop_valid_i(stk_sp_valid),
    .sp_pop_thr_i  (stk_sp_thr),
    .sp_pop_sp_i   (stk_sp_sp),
    .hit_valid_i   (hits_hit_valid),
    .hit_thr_i     (hits_hit_thr),
    .hit_ray_i     (hits_hit_ray),
    .err_o         (thr_err),
    .shadow_o      (thr_shadow),
    .hit_o         (thr_hit),
    .sp_rd_thr_i   (stk_sp_rd_thr),
    .sp_rd_o       (thr_sp_rd),
    .vm_rd_thr_i   (shd_vm_rd_thr),
    .vm_rd_o       (thr_vm_rd),
    .vm_rd_sec_o   (thr_vm_rd_sec)
  );

  //////////////////////
  // Traversal unit   //
  //////////////////////

  logic                stk_trav_valid, stk_trav_ready;
  rc_pkg::walk_item_t  stk_trav_item;
  logic                trav_push_valid, trav_leaf_valid, trav_req_valid;
  logic [ThrW-1:0]     trav_push_thr, trav_req_thr;
  logic [SpW-1:0]      trav_push_sp;
  rc_pkg::walk_entry_t trav_push_entry;
  rc_pkg::leaf_item_t  trav_leaf_item;
  logic                trav_issue_valid, trav_step_valid, trav_dec_valid;
  logic [ThrW-1:0]     trav_issue_thr, trav_step_thr, trav_dec_thr;
  logic                perf_node_req, perf_inner, perf_push, perf_tr_leaf, perf_tr_empty;
  logic [2:0]          perf_steps;
  logic [SpW-1:0]      perf_push_depth;

  rc_trav_unit #(
    .Threads   (Threads),
    .StackDepth(StackDepth)
  ) u_trav (
    .clk_i,
    .rst_ni,
    .node_count_i,
    .list_count_i,
    .q_valid_i        (stk_trav_valid),
    .q_ready_o        (stk_trav_ready),
    .q_item_i         (stk_trav_item),
    .node_req_valid_o,
    .node_req_ready_i,
    .node_req_tag_o,
    .node_req_index_o,
    .node_rsp_valid_i,
    .node_rsp_ready_o,
    .node_rsp_tag_i,
    .node_rsp_data_i,
    .node_rsp_error_i,
    .ax_re_o          (trav_ax_re),
    .ax_thr_o         (trav_ax_thr),
    .ax_axis_o        (trav_ax_axis),
    .ax_org_i         (rays_ax_org),
    .ax_sign_i        (rays_ax_sign),
    .ax_inv_i         (rays_ax_inv),
    .push_valid_o     (trav_push_valid),
    .push_thr_o       (trav_push_thr),
    .push_sp_o        (trav_push_sp),
    .push_entry_o     (trav_push_entry),
    .sp_tr_valid_o    (trav_sp_valid),
    .sp_tr_thr_o      (trav_sp_thr),
    .sp_tr_sp_o       (trav_sp_sp),
    .leaf_valid_o     (trav_leaf_valid),
    .leaf_item_o      (trav_leaf_item),
    .req_tr_valid_o   (trav_req_valid),
    .req_tr_thr_o     (trav_req_thr),
    .err_valid_o      (trav_err_valid),
    .err_thr_o        (trav_err_thr),
    .err_bits_o       (trav_err_bits),
    .req_nr_valid_o   (trav_reqnr_valid),
    .req_nr_thr_o     (trav_reqnr_thr),
    .issue_valid_o    (trav_issue_valid),
    .issue_thr_o      (trav_issue_thr),
    .step_valid_o     (trav_step_valid),
    .step_thr_o       (trav_step_thr),
    .dec_valid_o      (trav_dec_valid),
    .dec_thr_o        (trav_dec_thr),
    .perf_node_req_o  (perf_node_req),
    .perf_inner_o     (perf_inner),
    .perf_steps_o     (perf_steps),
    .perf_push_o      (perf_push),
    .perf_push_depth_o(perf_push_depth),
    .perf_leaf_o      (perf_tr_leaf),
    .perf_empty_o     (perf_tr_empty)
  );

  ///////////////////////////
  // Pop unit and stacks   //
  ///////////////////////////

  logic               list_leaf_b_ready, stk_leaf_valid, stk_done_valid;
  rc_pkg::leaf_item_t stk_leaf_item;
  logic [ThrW-1:0]    stk_done_thr;
  logic [Threads-1:0] list_leaf_end, stk_popq;
  logic               stk_bt_re;
  logic [ThrW-1:0]    stk_bt_thr;
  logic [4*W-1:0]     hits_pop_t;
  logic               stk_pick_valid, stk_route_valid;
  logic [ThrW-1:0]    stk_pick_thr, stk_route_thr;
  logic               perf_pop, perf_culled, perf_failed, perf_stk_leaf, perf_stk_empty;

  rc_stack_unit #(
    .Threads   (Threads),
    .StackDepth(StackDepth),
    .Secondary (Secondary)
  ) u_stack (
    .clk_i,
    .rst_ni,
    .push_valid_i  (trav_push_valid),
    .push_thr_i    (trav_push_thr),
    .push_sp_i     (trav_push_sp),
    .push_entry_i  (trav_push_entry),
    .req_tr_valid_i(trav_req_valid),
    .req_tr_thr_i  (trav_req_thr),
    .req_nr_valid_i(trav_reqnr_valid),
    .req_nr_thr_i  (trav_reqnr_thr),
    .req_lf_i      (list_leaf_end),
    .err_i         (thr_err),
    .hit_i         (thr_hit),
    .shadow_i      (thr_shadow),
    .sp_rd_thr_o   (stk_sp_rd_thr),
    .sp_rd_i       (thr_sp_rd),
    .sp_pop_valid_o(stk_sp_valid),
    .sp_pop_thr_o  (stk_sp_thr),
    .sp_pop_sp_o   (stk_sp_sp),
    .err_valid_o   (stk_err_valid),
    .err_thr_o     (stk_err_thr),
    .err_bits_o    (stk_err_bits),
    .bt_re_o       (stk_bt_re),
    .bt_thr_o      (stk_bt_thr),
    .bt_i          (hits_pop_t),
    .start_valid_i (start_valid),
    .start_ready_o (start_ready),
    .start_item_i  (start_item),
    .trav_valid_o  (stk_trav_valid),
    .trav_ready_i  (stk_trav_ready),
    .trav_item_o   (stk_trav_item),
    .leaf_valid_o  (stk_leaf_valid),
    .leaf_ready_i  (list_leaf_b_ready),
    .leaf_item_o   (stk_leaf_item),
    .done_valid_o  (stk_done_valid),
    .done_thr_o    (stk_done_thr),
    .popq_o        (stk_popq),
    .pick_valid_o  (stk_pick_valid),
    .pick_thr_o    (stk_pick_thr),
    .route_valid_o (stk_route_valid),
    .route_thr_o   (stk_route_thr),
    .perf_pop_o    (perf_pop),
    .perf_culled_o (perf_culled),
    .perf_failed_o (perf_failed),
    .perf_leaf_o   (perf_stk_leaf),
    .perf_empty_o  (perf_stk_empty)
  );

  ///////////////
  // List unit //
  ///////////////

  logic [LtW-1:0]  isect_tp_tag, isect_free_tag;
  logic [ThrW-1:0] list_tp_thr, isect_fin_thr, hits_fin_thr, list_take_thr;
  logic [3:0]      list_tp_mask;
  logic [2:0]      list_tp_first;
  logic [31:0]     list_tp_tri;
  logic            isect_free_valid, isect_fin_valid, hits_fin_valid, list_take_valid;
  logic            perf_entry, perf_list_issue, list_wd_req, list_wd_rsp;

  rc_list_unit #(
    .Threads (Threads),
    .ListTags(ListTags)
  ) u_list (
    .clk_i,
    .rst_ni,
    .tri_count_i,
    .leaf_a_valid_i  (trav_leaf_valid),
    .leaf_a_item_i   (trav_leaf_item),
    .leaf_b_valid_i  (stk_leaf_valid),
    .leaf_b_ready_o  (list_leaf_b_ready),
    .leaf_b_item_i   (stk_leaf_item),
    .list_req_valid_o,
    .list_req_ready_i,
    .list_req_tag_o,
    .list_req_index_o,
    .list_rsp_valid_i,
    .list_rsp_ready_o,
    .list_rsp_tag_i,
    .list_rsp_data_i,
    .list_rsp_error_i,
    .tri_req_valid_o,
    .tri_req_ready_i,
    .tri_req_tag_o,
    .tri_req_index_o,
    .tp_tag_i        (isect_tp_tag),
    .tp_thr_o        (list_tp_thr),
    .tp_mask_o       (list_tp_mask),
    .tp_first_o      (list_tp_first),
    .tp_tri_o        (list_tp_tri),
    .free_valid_i    (isect_free_valid),
    .free_tag_i      (isect_free_tag),
    .fin_te_valid_i  (isect_fin_valid),
    .fin_te_thr_i    (isect_fin_thr),
    .fin_io_valid_i  (hits_fin_valid),
    .fin_io_thr_i    (hits_fin_thr),
    .leaf_end_o      (list_leaf_end),
    .err_valid_o     (list_err_valid),
    .err_thr_o       (list_err_thr),
    .err_bits_o      (list_err_bits),
    .take_valid_o    (list_take_valid),
    .take_thr_o      (list_take_thr),
    .perf_entry_o    (perf_entry),
    .perf_issue_o    (perf_list_issue),
    .wd_req_o        (list_wd_req),
    .wd_rsp_o        (list_wd_rsp)
  );

  ////////////////////////////////////
  // Intersection unit and hit store //
  ////////////////////////////////////

  logic               isect_res_valid, isect_load_valid, perf_test, isect_wd_rsp;
  rc_pkg::isect_res_t isect_res;
  logic [ThrW-1:0]    isect_load_thr;
  logic [W+31:0]      hits_isect_best;

  rc_isect_issue #(
    .Threads      (Threads),
    .ListTags     (ListTags),
    .IsectInterval(IsectInterval),
    .Secondary    (Secondary),
    .BlockDelays  (BlockDelays)
  ) u_isect (
    .clk_i,
    .rst_ni,
    .tri_rsp_valid_i,
    .tri_rsp_ready_o,
    .tri_rsp_tag_i,
    .tri_rsp_data_i,
    .tri_rsp_error_i,
    .tp_tag_o      (isect_tp_tag),
    .tp_thr_i      (list_tp_thr),
    .tp_mask_i     (list_tp_mask),
    .tp_first_i    (list_tp_first),
    .tp_tri_i      (list_tp_tri),
    .free_valid_o  (isect_free_valid),
    .free_tag_o    (isect_free_tag),
    .ray_re_o      (isect_ray_re),
    .ray_thr_o     (isect_ray_thr),
    .ray_ray_o     (isect_ray_ray),
    .ray_orgdir_i  (rays_od),
    .ray_lim_i     (rays_lim),
    .t_eps_i,
    .best_i        (hits_isect_best),
    .acc_hot_i     (acc_hot),
    .hitset_valid_i(hits_hit_valid),
    .hitset_thr_i  (hits_hit_thr),
    .hitset_ray_i  (hits_hit_ray),
    .res_valid_o   (isect_res_valid),
    .res_o         (isect_res),
    .err_valid_o   (isect_err_valid),
    .err_thr_o     (isect_err_thr),
    .err_bits_o    (isect_err_bits),
    .fin_te_valid_o(isect_fin_valid),
    .fin_te_thr_o  (isect_fin_thr),
    .load_valid_o  (isect_load_valid),
    .load_thr_o    (isect_load_thr),
    .perf_test_o   (perf_test),
    .wd_rsp_o      (isect_wd_rsp)
  );

  logic             shd_tri_re, shd_rec_re, shd_dz_re, perf_commit;
  logic [ThrW-1:0]  shd_tri_thr, shd_rec_thr, shd_dz_thr;
  logic [1:0]       shd_rec_ray, shd_dz_ray;
  logic [127:0]     hits_shade_tri;
  logic [4*W+31:0]  hits_fb_best;
  logic [W-1:0]     hits_dz;

  rc_hit_store #(
    .Threads(Threads),
    .FbDz   (Secondary)
  ) u_hits (
    .clk_i,
    .rst_ni,
    .res_valid_i  (isect_res_valid),
    .res_i        (isect_res),
    .hit_i        (thr_hit),
    .hit_valid_o  (hits_hit_valid),
    .hit_thr_o    (hits_hit_thr),
    .hit_ray_o    (hits_hit_ray),
    .fin_valid_o  (hits_fin_valid),
    .fin_thr_o    (hits_fin_thr),
    .isect_re_i   (isect_ray_re),
    .isect_thr_i  (isect_ray_thr),
    .isect_ray_i  (isect_ray_ray),
    .isect_best_o (hits_isect_best),
    .pop_re_i     (stk_bt_re),
    .pop_thr_i    (stk_bt_thr),
    .pop_t_o      (hits_pop_t),
    .shade_re_i   (shd_tri_re),
    .shade_thr_i  (shd_tri_thr),
    .shade_tri_o  (hits_shade_tri),
    .fb_re_i      (shd_rec_re),
    .fb_thr_i     (shd_rec_thr),
    .fb_ray_i     (shd_rec_ray),
    .fb_best_o    (hits_fb_best),
    .dz_re_i      (shd_dz_re),
    .dz_thr_i     (shd_dz_thr),
    .dz_ray_i     (shd_dz_ray),
    .dz_o         (hits_dz),
    .perf_commit_o(perf_commit)
  );

  /////////////
  // Shading //
  /////////////

  logic            shd_err_shd, shd_err_mat, shd_pick_valid, perf_shade, perf_fb, shd_wd;
  logic [ThrW-1:0] shd_pick_thr;

  rc_shade_seq #(
    .Threads  (Threads),
    .Secondary(Secondary),
    .Shade    (Shade)
  ) u_shade (
    .clk_i,
    .rst_ni,
    .ambient_i,
    .diffuse_i,
    .background_i,
    .done_valid_i   (stk_done_valid),
    .done_thr_i     (stk_done_thr),
    .vm_rd_thr_o    (shd_vm_rd_thr),
    .vm_rd_i        (thr_vm_rd),
    .vm_rd_sec_i    (thr_vm_rd_sec),
    .hit_i          (thr_hit),
    .err_i          (thr_err),
    .tri_re_o       (shd_tri_re),
    .tri_thr_o      (shd_tri_thr),
    .tri_i          (hits_shade_tri),
    .rec_re_o       (shd_rec_re),
    .rec_thr_o      (shd_rec_thr),
    .rec_ray_o      (shd_rec_ray),
    .rec_i          (hits_fb_best),
    .dz_re_o        (shd_dz_re),
    .dz_thr_o       (shd_dz_thr),
    .dz_ray_o       (shd_dz_ray),
    .dz_i           (hits_dz),
    .ilen_re_o      (shd_ilen_re),
    .ilen_thr_o     (shd_ilen_thr),
    .ilen_ray_o     (shd_ilen_ray),
    .ilen_i         (rays_ilen),
    .pix_re_o       (shd_pix_re),
    .pix_thr_o      (shd_pix_thr),
    .pix_ray_o      (shd_pix_ray),
    .pix_i          (rays_pix),
    .shd_req_valid_o,
    .shd_req_ready_i,
    .shd_req_tag_o,
    .shd_req_index_o,
    .shd_rsp_valid_i,
    .shd_rsp_ready_o,
    .shd_rsp_tag_i,
    .shd_rsp_data_i,
    .shd_rsp_error_i,
    .mat_req_valid_o,
    .mat_req_ready_i,
    .mat_req_tag_o,
    .mat_req_index_o,
    .mat_rsp_valid_i,
    .mat_rsp_ready_o,
    .mat_rsp_tag_i,
    .mat_rsp_data_i,
    .mat_rsp_error_i,
    .fb_valid_o,
    .fb_ready_i,
    .fb_pixel_o,
    .fb_rgb_o,
    .fb_hit_o,
    .fb_tri_o,
    .fb_t_o,
    .fb_u_o,
    .fb_v_o,
    .fb_dz_o,
    .free_valid_o   (shd_free_valid),
    .free_thr_o     (shd_free_thr),
    .free0_valid_o  (shd_free0_valid),
    .free0_thr_o    (shd_free0_thr),
    .err_shd_o      (shd_err_shd),
    .err_mat_o      (shd_err_mat),
    .pick_valid_o   (shd_pick_valid),
    .pick_thr_o     (shd_pick_thr),
    .perf_shade_o   (perf_shade),
    .perf_fb_o      (perf_fb),
    .wd_o           (shd_wd)
  );

  ////////////////////////////
  // Status and counters    //
  ////////////////////////////

  logic              idle;
  logic [2:0]        ev_err;
  logic [3*NPerf-1:0] perf_inc;
  logic [11:0]       wd_ev;

  assign idle = setup_all_free;

  assign ev_err = ({3{trav_err_valid}} & trav_err_bits) |
                  ({3{trav_reqnr_valid}} & (3'd1 << rc_pkg::CoreStatusBadAddress)) |
                  ({3{stk_err_valid}} & stk_err_bits) |
                  ({3{list_err_valid}} & list_err_bits) |
                  ({3{isect_err_valid}} & isect_err_bits) |
                  ({3{shd_err_shd | shd_err_mat}} & (3'd1 << rc_pkg::CoreStatusBadAddress));

  assign wd_ev = {pkt_valid_i & pkt_ready_o, fb_valid_o & fb_ready_i,
                  node_req_valid_o & node_req_ready_i, node_rsp_valid_i & node_rsp_ready_o,
                  list_wd_req, list_wd_rsp, tri_req_valid_o & tri_req_ready_i, isect_wd_rsp,
                  shd_wd, 3'b000};

  logic hs_node_req, hs_tri_req, hs_shd_req, hs_mat_req;
  assign hs_node_req = node_req_valid_o & node_req_ready_i;
  assign hs_tri_req  = tri_req_valid_o & tri_req_ready_i;
  assign hs_shd_req  = shd_req_valid_o & shd_req_ready_i;
  assign hs_mat_req  = mat_req_valid_o & mat_req_ready_i;

  // The per-kind counters (a core with secondary packets only; rc_core_status aliases them
  // otherwise).
  localparam int unsigned KindIncW = 3 * (rc_pkg::CorePerfCount - rc_pkg::CorePerfPrimaryRays);
  logic [KindIncW-1:0] kind_inc;
  if (Secondary) begin : g_kind_perf
    rc_kind_perf #(
      .Threads(Threads)
    ) u_kind_perf (
      .clk_i,
      .rst_ni,
      .acc_valid_i(acc_valid),
      .acc_hot_i  (acc_hot),
      .acc_vmask_i(acc_vmask),
      .acc_kind_i (acc_kind),
      .steps_i    (perf_steps),
      .step_thr_i (trav_step_thr),
      .test_i     (perf_test),
      .test_thr_i (isect_ray_thr),
      .inc_o      (kind_inc)
    );
  end else begin : g_no_kind_perf
    logic unused_kind;
    assign unused_kind = ^acc_kind;  // every packet is a primary one
    assign kind_inc    = '0;
  end

  always_comb begin
    perf_inc = '0;
    perf_inc[3*rc_pkg::CorePerfPrimaryRays +: KindIncW] = kind_inc;
    perf_inc[3*rc_pkg::CorePerfCycles +: 3]           = 3'd1;
    perf_inc[3*rc_pkg::CorePerfBusyCycles +: 3]       = 3'(!idle);
    perf_inc[3*rc_pkg::CorePerfPackets +: 3]          = 3'(perf_packet);
    perf_inc[3*rc_pkg::CorePerfRays +: 3]             = perf_rays;
    perf_inc[3*rc_pkg::CorePerfNodesFetched +: 3]     = 3'(perf_node_req);
    perf_inc[3*rc_pkg::CorePerfInnerVisits +: 3]      = 3'(perf_inner);
    perf_inc[3*rc_pkg::CorePerfTraversalSteps +: 3]   = perf_steps;
    perf_inc[3*rc_pkg::CorePerfLeafVisits +: 3]       = 3'(perf_tr_leaf) + 3'(perf_stk_leaf);
    perf_inc[3*rc_pkg::CorePerfEmptyLeaves +: 3]      = 3'(perf_tr_empty) + 3'(perf_stk_empty);
    perf_inc[3*rc_pkg::CorePerfListEntries +: 3]      = 3'(perf_entry);
    perf_inc[3*rc_pkg::CorePerfTriangleTests +: 3]    = 3'(perf_test);
    perf_inc[3*rc_pkg::CorePerfStackPushes +: 3]      = 3'(perf_push);
    perf_inc[3*rc_pkg::CorePerfStackPops +: 3]        = 3'(perf_pop);
    perf_inc[3*rc_pkg::CorePerfCulledPops +: 3]       = 3'(perf_culled);
    perf_inc[3*rc_pkg::CorePerfFailedPackets +: 3]    = 3'(perf_failed);
    perf_inc[3*rc_pkg::CorePerfSetupBusy +: 3]        = 3'(perf_setup);
    perf_inc[3*rc_pkg::CorePerfTravBusy +: 3]         = 3'(perf_inner);
    perf_inc[3*rc_pkg::CorePerfListBusy +: 3]         = 3'(perf_list_issue);
    perf_inc[3*rc_pkg::CorePerfIsectBusy +: 3]        = 3'(perf_test);
    perf_inc[3*rc_pkg::CorePerfShadeBusy +: 3]        = 3'(perf_shade);
    perf_inc[3*rc_pkg::CorePerfNodeRequests +: 3]     = 3'(hs_node_req);
    perf_inc[3*rc_pkg::CorePerfListRequests +: 3]     = 3'(list_wd_req);
    perf_inc[3*rc_pkg::CorePerfTriRequests +: 3]      = 3'(hs_tri_req);
    perf_inc[3*rc_pkg::CorePerfShadingRequests +: 3]  = 3'(hs_shd_req);
    perf_inc[3*rc_pkg::CorePerfMaterialRequests +: 3] = 3'(hs_mat_req);
    perf_inc[3*rc_pkg::CorePerfFbWrites +: 3]         = 3'(perf_fb);
  end

  rc_core_status #(
    .WatchdogCycles(WatchdogCycles),
    .EvW           (12),
    .KindCounters  (Secondary)
  ) u_status (
    .clk_i,
    .rst_ni,
    .idle_i      (idle),
    .wd_ev_i     (wd_ev),
    .err_i       (ev_err),
    .perf_inc_i  (perf_inc),
    .perf_depth_i(perf_push_depth),
    .perf_sel_i,
    .error_o,
    .perf_o
  );

  assign idle_o = idle;

  logic unused_bits;
  assign unused_bits = ^{perf_commit, stk_popq, isect_load_valid, isect_load_thr, list_take_valid,
                         list_take_thr, trav_issue_valid, trav_issue_thr, trav_step_valid,
                         trav_step_thr, trav_dec_valid, trav_dec_thr, stk_pick_valid,
                         stk_pick_thr, stk_route_valid, stk_route_thr, shd_pick_valid,
                         shd_pick_thr};

  //////////////////////////////////////////////
  // Thread states (debug) and their checks   //
  //////////////////////////////////////////////

`ifdef SYNTHESIS
  assign dbg_thread_state_o = '0;
`else
  // Every thread's state, kept from the units' events (rc_thread_mon). Five of its inputs are
  // registers inside a unit that no port carries: the pop unit's pushes into the fetch and leaf
  // queues and its own-thread pop, the traversal decision's continuation flag, and the shading
  // sequencer's output thread.
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  rc_thread_mon #(
    .Threads(Threads),
    .ThrW   (ThrW)
  ) u_thread_mon (
    .clk_i,
    .rst_ni,
    .acc_valid_i     (acc_valid),
    .acc_thr_i       (acc_thr),
    .tq_valid_i      (u_stack.tq_push_q),
    .tq_thr_i        (ThrW'(u_stack.tq_item_q.thr)),
    .iss_valid_i     (trav_issue_valid),
    .iss_thr_i       (trav_issue_thr),
    .cont_i          (u_trav.cont_v_q),
    .leaf_tr_valid_i (trav_leaf_valid),
    .leaf_tr_thr_i   (ThrW'(trav_leaf_item.thr)),
    .req_tr_valid_i  (trav_req_valid),
    .req_tr_thr_i    (trav_req_thr),
    .req_nr_valid_i  (trav_reqnr_valid),
    .req_nr_thr_i    (trav_reqnr_thr),
    .leaf_stk_valid_i(u_stack.lq_push_q),
    .leaf_stk_thr_i  (ThrW'(u_stack.lq_item_q.thr)),
    .take_valid_i    (list_take_valid),
    .take_thr_i      (list_take_thr),
    .lend_i          (list_leaf_end),
    .own_valid_i     (u_stack.own_v_q),
    .own_thr_i       (u_stack.own_thr_q),
    .pick_valid_i    (stk_pick_valid),
    .pick_thr_i      (stk_pick_thr),
    .done_valid_i    (stk_done_valid),
    .done_thr_i      (stk_done_thr),
    .spick_valid_i   (shd_pick_valid),
    .spick_thr_i     (shd_pick_thr),
    .free_valid_i    (shd_free_valid),
    .free_thr_i      (shd_free_thr),
    .free0_valid_i   (shd_free0_valid),
    .free0_thr_i     (shd_free0_thr),
    .step_valid_i    (trav_step_valid),
    .step_thr_i      (trav_step_thr),
    .load_valid_i    (isect_load_valid),
    .load_thr_i      (isect_load_thr),
    .fin_valid_i     (hits_fin_valid),
    .fin_thr_i       (hits_fin_thr),
    .commit_valid_i  (hits_hit_valid),
    .commit_thr_i    (hits_hit_thr),
    .fb_valid_i      (fb_valid_o),
    .fb_thr_i        (u_shade.oq_thr),
    .state_o         (dbg_thread_state_o)
  );

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
