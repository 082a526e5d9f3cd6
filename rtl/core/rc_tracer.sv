// rc_tracer: the tree controller around rc_core (docs/architecture.md, "The tracer"): scene
// lighting made on chip. Primary packets go to the core; from their hits the controller reads each
// hit's shading record and material, lights it with rc_hit_light, sends the shadow packets it
// makes back to the core, adds the terms of the shadow rays that reach their light, and writes
// each pixel once, when its tree is done: rc::lit_work() and rc::lit_accumulate() of
// tb/golden/trace.hpp at max_bounces 0 (local shading and shadows; no mirror or refraction rays).
//
// Contract
// - Ports: rc_core's (its configuration, packet input, framebuffer write, five memory ports,
//   status, counters and debug, with the core's meaning), and:
//     light_count_i (1 .. MaxLights), light_dir_i, light_pos_i, light_col_i: the lights, as
//       rc_hit_light's (quasi-static, as the core's configuration);
//     lshd_*: shading records for the lighting (the core's shd record: material word, unit
//       normal, |n|), tag FetchW bits;
//     lmat_*: materials for the lighting: bytes [image_material] kd .. transmit + 4 of a record
//       (LMatW bits, the field at byte offset o at [(o - kd)*8 +: 32]), tag FetchW bits.
//   Both follow the memory protocol of docs/architecture.md ("Memory ports"): responses in any
//   order after any delay; no two requests with one tag outstanding.
// - Packet input: primary packets only (pkt_kind_i, pkt_t_hi_i and pkt_start_tri_i are not
//   read; the controller makes the secondary packets). A packet with rays takes a slot (Slots of
//   them); pkt_ready_o is low while no slot is free or a shadow packet waits for the core.
// - Framebuffer write port: one write per existing ray of every primary packet, in no particular
//   order, once the pixel's tree is done: the pixel id, fb_rgb_o = light_byte() of the pixel's
//   sums for a hit (the ambient term and the terms of the lights whose shadow ray reached the
//   light), the core's write for a ray without a hit (the background), and the primary ray's hit
//   record as the core wrote it; fb_lights_o, bit l: light l's shadow ray reached it (0 for a
//   miss).
// - Inside: every packet the core gets carries {shadow, slot, light, lane} as its pixel ids
//   (bit 31 set for a shadow packet), so the core's writes come back here and are always taken.
//   A primary write stores the ray's hit record; when a packet's writes are all back, its hits go
//   to the fetch in lane order: a shading request, then a material request (Ns through
//   rc_fp_to_exp), put back in order in FetchEntries entries, then to rc_hit_light with weight 1.
//   Its light samples come light by light, in a light the packet's hits in lane order: each sets
//   the lane's sum to the ambient term at light 0, stores the lane's term, and a present sample
//   adds its ray (origin P, direction lh, limit t_hi, start triangle the hit's) to the light's
//   shadow packet, which goes to a two-entry queue at the light's last hit when it has a ray.
//   Shadow packets go to the core before primary ones. A shadow ray's write without a hit (and
//   without its packet's error, colour 1) adds the lane's term to its sum. A slot is done when
//   its samples are all made and its shadow rays all back; its lanes are then written, one per
//   cycle, and the slot is freed.
// - Status: idle_o = the core idle, no slot held and no write pending. error_o: the core's, and
//   CoreStatusBadAddress on an error response of lshd_* or lmat_* (its hit is lit as black).
// - Parameters: the core's (passed on); Slots >= 1 ([tracer] slots); FetchEntries a power of
//   two >= 2 ([tracer] fetch_entries); MaxLights ([light] max_lights).
// - Illegal input: light_count_i of 0 or above MaxLights; a packet kind other than primary
//   (assertions catch both).
// - Reset: rst_ni (active low, asynchronous) clears control state.
module rc_tracer #(
  parameter int unsigned ExpW           = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW          = rc_pkg::Fp24FracW,
  parameter int unsigned Threads        = rc_pkg::CoreThreads,
  parameter int unsigned StackDepth     = rc_pkg::KdtreeStackDepth,
  parameter int unsigned ListTags       = rc_pkg::CoreListTags,
  parameter int unsigned WatchdogCycles = rc_pkg::CoreWatchdogCycles,
  parameter int unsigned IsectInterval  = rc_pkg::CoreIsectInterval,
  parameter int unsigned SetupUnits     = rc_pkg::CoreSetupUnits,
  parameter int unsigned Slots          = rc_pkg::TracerSlots,
  parameter int unsigned FetchEntries   = rc_pkg::TracerFetchEntries,
  parameter int unsigned MaxLights      = rc_pkg::LightMaxLights,
  // Derived (do not override).
  parameter int unsigned W              = 1 + ExpW + FracW,
  parameter int unsigned TagW           = rc_pkg::CoreTagBits,
  parameter int unsigned StatusW        = rc_pkg::CoreStatusBits,
  parameter int unsigned NodeRecW       = 8 * rc_pkg::KdNodeBytes,
  parameter int unsigned NodeRspW       = rc_pkg::CoreNodeRspRecords * NodeRecW,
  parameter int unsigned FetchW         = (FetchEntries > 1) ? $clog2(FetchEntries) : 1,
  parameter int unsigned CountW         = $clog2(MaxLights + 1),
  parameter int unsigned LMatW          =
      8 * (rc_pkg::ImageMaterialTransmit + 4 - rc_pkg::ImageMaterialKd)
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,

  // Configuration (quasi-static).
  input  logic [6*W-1:0]           bounds_i,
  input  logic [31:0]              node_count_i,
  input  logic [31:0]              list_count_i,
  input  logic [31:0]              tri_count_i,
  input  logic [NodeRecW-1:0]      root_node_i,
  input  logic [W-1:0]             ambient_i,
  input  logic [W-1:0]             diffuse_i,
  input  logic [23:0]              background_i,
  input  logic [W-1:0]             t_eps_i,
  input  logic [CountW-1:0]        light_count_i,
  input  logic [MaxLights-1:0]     light_dir_i,
  input  logic [MaxLights*3*W-1:0] light_pos_i,
  input  logic [MaxLights*3*W-1:0] light_col_i,

  // Packet input (primary packets).
  input  logic                     pkt_valid_i,
  output logic                     pkt_ready_o,
  input  logic [3:0]               pkt_mask_i,
  input  logic [12*W-1:0]          pkt_org_i,
  input  logic [12*W-1:0]          pkt_dir_i,
  input  logic [4*W-1:0]           pkt_inv_len_i,
  input  logic [127:0]             pkt_pixel_i,
  input  logic [rc_pkg::RayKindBits-1:0] pkt_kind_i,
  input  logic [4*W-1:0]           pkt_t_hi_i,
  input  logic [127:0]             pkt_start_tri_i,

  // Framebuffer write port.
  output logic                     fb_valid_o,
  input  logic                     fb_ready_i,
  output logic [31:0]              fb_pixel_o,
  output logic [23:0]              fb_rgb_o,
  output logic                     fb_hit_o,
  output logic [31:0]              fb_tri_o,
  output logic [W-1:0]             fb_t_o,
  output logic [W-1:0]             fb_u_o,
  output logic [W-1:0]             fb_v_o,
  output logic [MaxLights-1:0]     fb_lights_o,   // bit l: light l reaches the hit

  // The core's memory ports.
  output logic                     node_req_valid_o,
  input  logic                     node_req_ready_i,
  output logic [TagW-1:0]          node_req_tag_o,
  output logic [31:0]              node_req_index_o,
  input  logic                     node_rsp_valid_i,
  output logic                     node_rsp_ready_o,
  input  logic [TagW-1:0]          node_rsp_tag_i,
  input  logic [NodeRspW-1:0]      node_rsp_data_i,
  input  logic                     node_rsp_error_i,
  output logic                     list_req_valid_o,
  input  logic                     list_req_ready_i,
  output logic [TagW-1:0]          list_req_tag_o,
  output logic [31:0]              list_req_index_o,
  input  logic                     list_rsp_valid_i,
  output logic                     list_rsp_ready_o,
  input  logic [TagW-1:0]          list_rsp_tag_i,
  input  logic [31:0]              list_rsp_data_i,
  input  logic                     list_rsp_error_i,
  output logic                     tri_req_valid_o,
  input  logic                     tri_req_ready_i,
  output logic [TagW-1:0]          tri_req_tag_o,
  output logic [31:0]              tri_req_index_o,
  input  logic                     tri_rsp_valid_i,
  output logic                     tri_rsp_ready_o,
  input  logic [TagW-1:0]          tri_rsp_tag_i,
  input  logic [12*W-1:0]          tri_rsp_data_i,
  input  logic                     tri_rsp_error_i,
  output logic                     shd_req_valid_o,
  input  logic                     shd_req_ready_i,
  output logic [TagW-1:0]          shd_req_tag_o,
  output logic [31:0]              shd_req_index_o,
  input  logic                     shd_rsp_valid_i,
  output logic                     shd_rsp_ready_o,
  input  logic [TagW-1:0]          shd_rsp_tag_i,
  input  logic [32+4*W-1:0]        shd_rsp_data_i,
  input  logic                     shd_rsp_error_i,
  output logic                     mat_req_valid_o,
  input  logic                     mat_req_ready_i,
  output logic [TagW-1:0]          mat_req_tag_o,
  output logic [31:0]              mat_req_index_o,
  input  logic                     mat_rsp_valid_i,
  output logic                     mat_rsp_ready_o,
  input  logic [TagW-1:0]          mat_rsp_tag_i,
  input  logic [95:0]              mat_rsp_data_i,
  input  logic                     mat_rsp_error_i,

  // The lighting's memory ports: shading records and materials.
  output logic                     lshd_req_valid_o,
  input  logic                     lshd_req_ready_i,
  output logic [FetchW-1:0]        lshd_req_tag_o,
  output logic [31:0]              lshd_req_index_o,
  input  logic                     lshd_rsp_valid_i,
  output logic                     lshd_rsp_ready_o,
  input  logic [FetchW-1:0]        lshd_rsp_tag_i,
  input  logic [32+4*W-1:0]        lshd_rsp_data_i,
  input  logic                     lshd_rsp_error_i,
  output logic                     lmat_req_valid_o,
  input  logic                     lmat_req_ready_i,
  output logic [FetchW-1:0]        lmat_req_tag_o,
  output logic [31:0]              lmat_req_index_o,
  input  logic                     lmat_rsp_valid_i,
  output logic                     lmat_rsp_ready_o,
  input  logic [FetchW-1:0]        lmat_rsp_tag_i,
  input  logic [LMatW-1:0]         lmat_rsp_data_i,
  input  logic                     lmat_rsp_error_i,

  // Status and counters (the core's, error_o with the lighting's bad address).
  output logic                     idle_o,
  output logic [StatusW-1:0]       error_o,
  input  logic [7:0]               perf_sel_i,
  output logic [63:0]              perf_o,

  // Debug.
  output logic [Threads*rc_pkg::ThreadStateBits-1:0] dbg_thread_state_o
);

  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned SlotW  = (Slots > 1) ? $clog2(Slots) : 1;
  localparam int unsigned LightW = (MaxLights > 1) ? $clog2(MaxLights) : 1;
  localparam int unsigned FW     = rc_pkg::LightFixedBits + 1;
  localparam int unsigned ExpB   = rc_pkg::LightExponentBits;
  localparam int unsigned SumW   = 32;
  localparam int unsigned ShW    = $clog2(4 * MaxLights + 1);  // a slot's shadow rays out
  localparam int unsigned HlTagW = SlotW + 2;                  // {slot, lane}
  localparam int unsigned KdLsb  = 0;
  localparam int unsigned KsLsb  = 8 * (rc_pkg::ImageMaterialKs - rc_pkg::ImageMaterialKd);
  localparam int unsigned NsLsb  = 8 * (rc_pkg::ImageMaterialNs - rc_pkg::ImageMaterialKd);
  localparam int unsigned NrmLsb = 8 * rc_pkg::ImageShadingFirstValue +
                                   W * rc_pkg::ImageShadingNormal;
  localparam int unsigned MatLsb = 8 * rc_pkg::ImageShadingMaterial;
  localparam logic [W-1:0] FpOne = {1'b0, 1'b0, {(ExpW - 1){1'b1}}, {FracW{1'b0}}};

  if (Slots < 1 || FetchEntries < 2 || (FetchEntries & (FetchEntries - 1)) != 0 ||
      1 + SlotW + LightW + 2 > 32) begin : g_param_check
    $error("rc_tracer: need Slots >= 1, FetchEntries a power of two >= 2, and the pixel id's fields within 32 bits");
  end

  // A field of 3 format values at [a*W +: W] from a 32-bit-slot material field.
  function automatic logic [3*W-1:0] rgb_field(input logic [LMatW-1:0] d,
                                                input int unsigned lsb);
    for (int a = 0; a < 3; a++) rgb_field[a*W +: W] = d[lsb + 32*a +: W];
  endfunction

  // The pixel id of a packet's ray to the core.
  function automatic logic [31:0] core_pixel(input logic shadow, input logic [SlotW-1:0] slot,
                                            input logic [LightW-1:0] light,
                                            input logic [1:0] lane);
    core_pixel = '0;
    core_pixel[31] = shadow;
    core_pixel[2 + LightW +: SlotW] = slot;
    core_pixel[2 +: LightW] = light;
    core_pixel[1:0] = lane;
  endfunction

  //////////////////
  // The slots    //
  //////////////////

  logic [Slots-1:0]      busy_q;                 // held by a primary packet
  logic [Slots-1:0]      lit_q;                  // its light samples are all made
  logic [Slots-1:0]      fin_q;                  // its writes are being made
  logic [Slots*3-1:0]    pend_q;                 // primary writes still due, slot s at [3s +: 3]
  logic [Slots*ShW-1:0]  sh_q;                   // shadow rays out, slot s at [s*ShW +: ShW]
  logic [3:0]            mask_q   [Slots];
  // Per lane, at {slot, lane}; the terms at {slot, light, lane}.
  logic [31:0]           pix_q    [Slots*4];
  logic [7*W-1:0]        ray_q    [Slots*4];     // {inv_len, dir, org}
  logic [Slots*4-1:0]    hit_q;                  // the primary hit records
  logic [31:0]           tri_q    [Slots*4];
  logic [W-1:0]          t_q      [Slots*4];
  logic [W-1:0]          u_q      [Slots*4];
  logic [W-1:0]          v_q      [Slots*4];
  logic [W-1:0]          dz_q     [Slots*4];
  logic [23:0]           rgb_q    [Slots*4];
  logic [3*SumW-1:0]     sum_q    [Slots*4];
  logic [MaxLights-1:0]  lm_q     [Slots*4];     // the lights that reach the hit
  logic [3*FW-1:0]       term_q   [Slots*(1<<LightW)*4];

  ///////////////////////////////
  // Packets into the core     //
  ///////////////////////////////

  logic                     core_pkt_valid, core_pkt_ready;
  logic [3:0]               core_pkt_mask;
  logic [12*W-1:0]          core_pkt_org, core_pkt_dir;
  logic [4*W-1:0]           core_pkt_inv_len, core_pkt_t_hi;
  logic [127:0]             core_pkt_pixel, core_pkt_start_tri;
  logic [rc_pkg::RayKindBits-1:0] core_pkt_kind;

  // The shadow packet queue (two entries).
  localparam int unsigned ShqW = 4 + 24 * W + 4 * W + 128 + SlotW + LightW;
  logic            shq_push, shq_valid, shq_pop;
  logic [ShqW-1:0] shq_wdata, shq_rdata;
  logic [1:0]      shq_count;
  logic [3:0]      shq_mask;
  logic [12*W-1:0] shq_org, shq_dir;
  logic [4*W-1:0]  shq_t_hi;
  logic [127:0]    shq_tri;
  logic [SlotW-1:0]  shq_slot;
  logic [LightW-1:0] shq_light;

  rc_fifo #(
    .Width   (ShqW),
    .Depth   (2),
    .MemArray(1'b0)
  ) u_shadow_q (
    .clk_i,
    .rst_ni,
    .push_i (shq_push),
    .data_i (shq_wdata),
    .valid_o(shq_valid),
    .ready_i(shq_pop),
    .data_o (shq_rdata),
    .count_o(shq_count)
  );
  assign {shq_mask, shq_org, shq_dir, shq_t_hi, shq_tri, shq_slot, shq_light} = shq_rdata;

  // A free slot: the lowest.
  logic             free_any;
  logic [SlotW-1:0] free_idx;
  always_comb begin
    free_any = 1'b0;
    free_idx = '0;
    for (int s = Slots - 1; s >= 0; s--) begin
      if (!busy_q[s]) begin
        free_any = 1'b1;
        free_idx = SlotW'(s);
      end
    end
  end

  logic ext_take;
  assign pkt_ready_o    = core_pkt_ready && !shq_valid && free_any;
  assign ext_take       = pkt_valid_i && pkt_ready_o;
  assign shq_pop        = shq_valid && core_pkt_ready;
  assign core_pkt_valid = shq_valid || (pkt_valid_i && free_any);

  always_comb begin
    core_pkt_mask      = pkt_mask_i;
    core_pkt_org       = pkt_org_i;
    core_pkt_dir       = pkt_dir_i;
    core_pkt_kind      = rc_pkg::RayKindBits'(rc_pkg::RayKindPrimary);
    core_pkt_t_hi      = '0;
    core_pkt_start_tri = '0;
    for (int r = 0; r < 4; r++) begin
      core_pkt_inv_len[r*W +: W] = pkt_inv_len_i[r*W +: W];
      core_pkt_pixel[r*32 +: 32] = core_pixel(1'b0, free_idx, '0, 2'(r));
    end
    if (shq_valid) begin
      core_pkt_mask      = shq_mask;
      core_pkt_org       = shq_org;
      core_pkt_dir       = shq_dir;
      core_pkt_kind      = rc_pkg::RayKindBits'(rc_pkg::RayKindShadow);
      core_pkt_t_hi      = shq_t_hi;
      core_pkt_start_tri = shq_tri;
      for (int r = 0; r < 4; r++) begin
        core_pkt_inv_len[r*W +: W] = FpOne;
        core_pkt_pixel[r*32 +: 32] = core_pixel(1'b1, shq_slot, shq_light, 2'(r));
      end
    end
  end

  //////////////
  // The core //
  //////////////

  logic            core_fb_valid, core_fb_hit;
  logic [31:0]     core_fb_pixel, core_fb_tri;
  logic [23:0]     core_fb_rgb;
  logic [W-1:0]    core_fb_t, core_fb_u, core_fb_v, core_fb_dz;
  logic            core_idle;
  logic [StatusW-1:0] core_error;

  rc_core #(
    .ExpW          (ExpW),
    .FracW         (FracW),
    .Threads       (Threads),
    .StackDepth    (StackDepth),
    .ListTags      (ListTags),
    .WatchdogCycles(WatchdogCycles),
    .IsectInterval (IsectInterval),
    .SetupUnits    (SetupUnits),
    .Secondary     (1'b1)
  ) u_core (
    .clk_i,
    .rst_ni,
    .bounds_i,
    .node_count_i,
    .list_count_i,
    .tri_count_i,
    .root_node_i,
    .ambient_i,
    .diffuse_i,
    .background_i,
    .t_eps_i,
    .pkt_valid_i     (core_pkt_valid),
    .pkt_ready_o     (core_pkt_ready),
    .pkt_mask_i      (core_pkt_mask),
    .pkt_org_i       (core_pkt_org),
    .pkt_dir_i       (core_pkt_dir),
    .pkt_inv_len_i   (core_pkt_inv_len),
    .pkt_pixel_i     (core_pkt_pixel),
    .pkt_kind_i      (core_pkt_kind),
    .pkt_t_hi_i      (core_pkt_t_hi),
    .pkt_start_tri_i (core_pkt_start_tri),
    .fb_valid_o      (core_fb_valid),
    .fb_ready_i      (1'b1),
    .fb_pixel_o      (core_fb_pixel),
    .fb_rgb_o        (core_fb_rgb),
    .fb_hit_o        (core_fb_hit),
    .fb_tri_o        (core_fb_tri),
    .fb_t_o          (core_fb_t),
    .fb_u_o          (core_fb_u),
    .fb_v_o          (core_fb_v),
    .fb_dz_o         (core_fb_dz),
    .node_req_valid_o,
    .node_req_ready_i,
    .node_req_tag_o,
    .node_req_index_o,
    .node_rsp_valid_i,
    .node_rsp_ready_o,
    .node_rsp_tag_i,
    .node_rsp_data_i,
    .node_rsp_error_i,
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
    .tri_rsp_valid_i,
    .tri_rsp_ready_o,
    .tri_rsp_tag_i,
    .tri_rsp_data_i,
    .tri_rsp_error_i,
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
    .idle_o          (core_idle),
    .error_o         (core_error),
    .perf_sel_i,
    .perf_o,
    .dbg_thread_state_o
  );

  // The core's write: which packet's ray it is.
  logic              cw_shadow, cw_prim, cw_sh, cw_reached;
  logic [SlotW-1:0]  cw_slot;
  logic [LightW-1:0] cw_light;
  logic [1:0]        cw_lane;
  assign cw_shadow  = core_fb_pixel[31];
  assign cw_slot    = core_fb_pixel[2 + LightW +: SlotW];
  assign cw_light   = core_fb_pixel[2 +: LightW];
  assign cw_lane    = core_fb_pixel[1:0];
  assign cw_prim    = core_fb_valid && !cw_shadow;
  assign cw_sh      = core_fb_valid && cw_shadow;
  // A shadow ray reached its light: no hit, and its packet met no error (colour 1).
  assign cw_reached = cw_sh && !core_fb_hit && !core_fb_rgb[0];

  ///////////////////////////////////////////
  // Fetch: shading record, then material  //
  ///////////////////////////////////////////

  // Slots whose primary writes are all back, in order.
  logic             fq_push, fq_valid, fq_pop;
  logic [SlotW-1:0] fq_slot;
  logic [$clog2(Slots + 1)-1:0] fq_count;
  assign fq_push = cw_prim && pend_q[cw_slot*3 +: 3] == 3'd1;

  rc_fifo #(
    .Width   (SlotW),
    .Depth   (Slots),
    .MemArray(1'b1)
  ) u_fetch_q (
    .clk_i,
    .rst_ni,
    .push_i (fq_push),
    .data_i (cw_slot),
    .valid_o(fq_valid),
    .ready_i(fq_pop),
    .data_o (fq_slot),
    .count_o(fq_count)
  );

  // The issue: the popped slot's hit lanes, one entry each.
  logic             fs_busy_q;
  logic [SlotW-1:0] fs_slot_q;
  logic [3:0]       fs_lanes_q;
  logic             fs_nohit;      // the popped slot has no hit: its samples are all made
  assign fq_pop   = fq_valid && !fs_busy_q;
  assign fs_nohit = fq_pop && hit_q[fq_slot*4 +: 4] == 4'd0;

  // The entries: a ring, allocated in lane order, filled in any order, retired in order.
  logic [FetchW-1:0] fe_head_q, fe_tail_q;
  logic [FetchW:0]   fe_count_q;
  logic [FetchEntries-1:0] fe_done_q;
  logic [SlotW-1:0]  fe_slot_q  [FetchEntries];
  logic [1:0]        fe_lane_q  [FetchEntries];
  logic              fe_last_q  [FetchEntries];
  logic [3*W-1:0]    fe_n_q     [FetchEntries];
  logic [3*W-1:0]    fe_kd_q    [FetchEntries];
  logic [3*W-1:0]    fe_ks_q    [FetchEntries];
  logic [ExpB-1:0]   fe_ns_q    [FetchEntries];

  logic        fs_lane_ok, fs_alloc;
  logic [1:0]  fs_lane;
  logic        fs_last;
  logic        lshd_req_valid_q;
  logic [FetchW-1:0] lshd_req_tag_q;
  logic [31:0] lshd_req_index_q;
  always_comb begin
    fs_lane = 2'd0;
    for (int r = 3; r >= 0; r--) if (fs_lanes_q[r]) fs_lane = 2'(r);
  end
  assign fs_last    = (fs_lanes_q & ~(4'd1 << fs_lane)) == 4'd0;
  assign fs_lane_ok = fe_count_q != (FetchW + 1)'(FetchEntries);
  assign fs_alloc   = fs_busy_q && fs_lane_ok && (!lshd_req_valid_q || lshd_req_ready_i);

  assign lshd_req_valid_o = lshd_req_valid_q;
  assign lshd_req_tag_o   = lshd_req_tag_q;
  assign lshd_req_index_o = lshd_req_index_q;

  // A shading response sends the material request (a one-entry register).
  logic              lmat_req_valid_q;
  logic [FetchW-1:0] lmat_req_tag_q;
  logic [31:0]       lmat_req_index_q;
  logic              lshd_take, lmat_take;
  assign lshd_rsp_ready_o = !lmat_req_valid_q || lmat_req_ready_i;
  assign lshd_take        = lshd_rsp_valid_i && lshd_rsp_ready_o;
  assign lmat_req_valid_o = lmat_req_valid_q;
  assign lmat_req_tag_o   = lmat_req_tag_q;
  assign lmat_req_index_o = lmat_req_index_q;
  assign lmat_rsp_ready_o = 1'b1;
  assign lmat_take        = lmat_rsp_valid_i;

  // Ns as the integer exponent (one cycle), its entry beside it.
  logic              ns_valid;
  logic [ExpB-1:0]   ns_val;
  logic [FetchW-1:0] ns_tag_q;
  rc_fp_to_exp #(
    .ExpW   (ExpW),
    .FracW  (FracW),
    .ExpBits(ExpB)
  ) u_ns (
    .clk_i,
    .rst_ni,
    .valid_i(lmat_take),
    .x_i    (lmat_rsp_error_i ? W'(0) : lmat_rsp_data_i[NsLsb +: W]),
    .valid_o(ns_valid),
    .ns_o   (ns_val)
  );

  logic fetch_err;
  assign fetch_err = (lshd_take && lshd_rsp_error_i) || (lmat_take && lmat_rsp_error_i);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fs_busy_q        <= 1'b0;
      fs_slot_q        <= '0;
      fs_lanes_q       <= '0;
      lshd_req_valid_q <= 1'b0;
      lshd_req_tag_q   <= '0;
      lshd_req_index_q <= '0;
      lmat_req_valid_q <= 1'b0;
      lmat_req_tag_q   <= '0;
      lmat_req_index_q <= '0;
      ns_tag_q         <= '0;
    end else begin
      if (fq_pop && !fs_nohit) begin
        fs_busy_q  <= 1'b1;
        fs_slot_q  <= fq_slot;
        fs_lanes_q <= hit_q[fq_slot*4 +: 4];
      end else if (fs_alloc) begin
        fs_lanes_q <= fs_lanes_q & ~(4'd1 << fs_lane);
        if (fs_last) fs_busy_q <= 1'b0;
      end
      if (fs_alloc) begin
        lshd_req_valid_q <= 1'b1;
        lshd_req_tag_q   <= fe_tail_q;
        lshd_req_index_q <= tri_q[{fs_slot_q, fs_lane}];
      end else if (lshd_req_ready_i) begin
        lshd_req_valid_q <= 1'b0;
      end
      if (lshd_take) begin
        lmat_req_valid_q <= 1'b1;
        lmat_req_tag_q   <= lshd_rsp_tag_i;
        lmat_req_index_q <= lshd_rsp_error_i ? 32'd0 : lshd_rsp_data_i[MatLsb +: 32];
      end else if (lmat_req_ready_i) begin
        lmat_req_valid_q <= 1'b0;
      end
      if (lmat_take) ns_tag_q <= lmat_rsp_tag_i;
    end
  end

  // The entries' payload (no reset: written before it is read).
  always_ff @(posedge clk_i) begin
    if (fs_alloc) begin
      fe_slot_q[fe_tail_q] <= fs_slot_q;
      fe_lane_q[fe_tail_q] <= fs_lane;
      fe_last_q[fe_tail_q] <= fs_last;
    end
    if (lshd_take) fe_n_q[lshd_rsp_tag_i] <= lshd_rsp_error_i ? '0 : lshd_rsp_data_i[NrmLsb +: 3*W];
    if (lmat_take) begin
      fe_kd_q[lmat_rsp_tag_i] <= lmat_rsp_error_i ? '0 : rgb_field(lmat_rsp_data_i, KdLsb);
      fe_ks_q[lmat_rsp_tag_i] <= lmat_rsp_error_i ? '0 : rgb_field(lmat_rsp_data_i, KsLsb);
    end
    if (ns_valid) fe_ns_q[ns_tag_q] <= ns_val;
  end

  ////////////////////////////////
  // Lighting (rc_hit_light)    //
  ////////////////////////////////

  logic              hl_valid, hl_ready, hl_take;
  logic [SlotW-1:0]  hl_slot;
  logic [1:0]        hl_lane;
  logic [7*W-1:0]    hl_ray;
  assign hl_valid = fe_count_q != '0 && fe_done_q[fe_head_q];
  assign hl_take  = hl_valid && hl_ready;
  assign hl_slot  = fe_slot_q[fe_head_q];
  assign hl_lane  = fe_lane_q[fe_head_q];
  assign hl_ray   = ray_q[{hl_slot, hl_lane}];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fe_head_q  <= '0;
      fe_tail_q  <= '0;
      fe_count_q <= '0;
      fe_done_q  <= '0;
    end else begin
      if (fs_alloc) fe_tail_q <= fe_tail_q + 1'b1;
      if (hl_take) fe_head_q <= fe_head_q + 1'b1;
      fe_count_q <= fe_count_q + (FetchW + 1)'(fs_alloc) - (FetchW + 1)'(hl_take);
      for (int e = 0; e < FetchEntries; e++) begin
        if (ns_valid && ns_tag_q == FetchW'(e)) fe_done_q[e] <= 1'b1;
        else if (hl_take && fe_head_q == FetchW'(e)) fe_done_q[e] <= 1'b0;
      end
    end
  end

  logic              lt_valid, lt_ready, lt_take;
  logic [HlTagW-1:0] lt_tag;
  logic [LightW-1:0] lt_light;
  logic              lt_lane_last, lt_light_last, lt_present;
  logic [3*W-1:0]    lt_org, lt_dir;
  logic [W-1:0]      lt_t_hi;
  logic [3*FW-1:0]   lt_term, lt_amb;

  logic              geo_valid, geo_mirror, geo_refract;
  logic [HlTagW-1:0] geo_tag;
  logic [3*W-1:0]    geo_p, geo_r, geo_refr;
  logic [W-1:0]      geo_w_mirror, geo_w_refract;

  rc_hit_light #(
    .ExpW     (ExpW),
    .FracW    (FracW),
    .TagW     (HlTagW),
    .MaxLights(MaxLights)
  ) u_hit_light (
    .clk_i,
    .rst_ni,
    .ambient_i,
    .light_count_i,
    .light_dir_i,
    .light_pos_i,
    .light_col_i,
    .valid_i         (hl_valid),
    .ready_o         (hl_ready),
    .tag_i           ({hl_slot, hl_lane}),
    .last_i          (fe_last_q[fe_head_q]),
    .org_i           (hl_ray[0 +: 3*W]),
    .dir_i           (hl_ray[3*W +: 3*W]),
    .inv_len_i       (hl_ray[6*W +: W]),
    .t_i             (t_q[{hl_slot, hl_lane}]),
    .dz_i            (dz_q[{hl_slot, hl_lane}]),
    .n_i             (fe_n_q[fe_head_q]),
    .eta_enter_i     (W'(0)),  // no refraction rays at max_bounces 0
    .eta_leave_i     (W'(0)),
    .w_i             (FpOne),  // a primary ray's weight
    .mirror_i        (W'(0)),
    .transmit_i      (W'(0)),
    .kd_i            (fe_kd_q[fe_head_q]),
    .ks_i            (fe_ks_q[fe_head_q]),
    .ns_i            (fe_ns_q[fe_head_q]),
    .geo_valid_o     (geo_valid),
    .geo_ready_i     (1'b1),   // the children's geometry is not used at max_bounces 0
    .geo_tag_o       (geo_tag),
    .geo_p_o         (geo_p),
    .geo_r_o         (geo_r),
    .geo_refr_o      (geo_refr),
    .geo_w_mirror_o  (geo_w_mirror),
    .geo_w_refract_o (geo_w_refract),
    .geo_mirror_o    (geo_mirror),
    .geo_refract_o   (geo_refract),
    .lt_valid_o      (lt_valid),
    .lt_ready_i      (lt_ready),
    .lt_tag_o        (lt_tag),
    .lt_light_o      (lt_light),
    .lt_lane_last_o  (lt_lane_last),
    .lt_light_last_o (lt_light_last),
    .lt_org_o        (lt_org),
    .lt_present_o    (lt_present),
    .lt_dir_o        (lt_dir),
    .lt_t_hi_o       (lt_t_hi),
    .lt_term_o       (lt_term),
    .lt_amb_o        (lt_amb)
  );

  // A light's shadow packet, assembled from its samples.
  logic [SlotW-1:0]  lt_slot;
  logic [1:0]        lt_lane;
  logic [3:0]        as_mask_q, as_mask;
  logic [12*W-1:0]   as_org_q, as_dir_q, as_org, as_dir;
  logic [4*W-1:0]    as_t_hi_q, as_t_hi;
  logic [127:0]      as_tri_q, as_tri;
  logic              lt_close;   // the light's last sample of the packet
  logic [ShW-1:0]    sh_inc;
  assign lt_slot  = lt_tag[2 +: SlotW];
  assign lt_lane  = lt_tag[1:0];
  assign lt_ready = shq_count != 2'd2;
  assign lt_take  = lt_valid && lt_ready;
  assign lt_close = lt_take && lt_lane_last;

  always_comb begin
    as_mask = as_mask_q;
    as_org  = as_org_q;
    as_dir  = as_dir_q;
    as_t_hi = as_t_hi_q;
    as_tri  = as_tri_q;
    if (lt_take && lt_present) begin
      as_mask[lt_lane]           = 1'b1;
      as_org[lt_lane*3*W +: 3*W] = lt_org;
      as_dir[lt_lane*3*W +: 3*W] = lt_dir;
      as_t_hi[lt_lane*W +: W]    = lt_t_hi;
      as_tri[lt_lane*32 +: 32]   = tri_q[{lt_slot, lt_lane}];
    end
    sh_inc = '0;
    for (int r = 0; r < 4; r++) sh_inc = sh_inc + ShW'(as_mask[r]);
  end
  assign shq_push  = lt_close && as_mask != 4'd0;
  assign shq_wdata = {as_mask, as_org, as_dir, as_t_hi, as_tri, lt_slot, lt_light};

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      as_mask_q <= '0;
    end else if (lt_take) begin
      as_mask_q <= lt_lane_last ? 4'd0 : as_mask;
    end
  end
  always_ff @(posedge clk_i) begin
    if (lt_take) begin
      as_org_q  <= as_org;
      as_dir_q  <= as_dir;
      as_t_hi_q <= as_t_hi;
      as_tri_q  <= as_tri;
    end
  end

  ////////////////////////
  // The pixels' writes //
  ////////////////////////

  // Done slots: the lowest first, one slot's lanes at a time, one lane per cycle.
  logic [Slots-1:0] done_vec;
  logic             dn_any;
  logic [SlotW-1:0] dn_idx;
  always_comb begin
    dn_any = 1'b0;
    dn_idx = '0;
    for (int s = Slots - 1; s >= 0; s--) begin
      done_vec[s] = busy_q[s] && lit_q[s] && sh_q[s*ShW +: ShW] == '0 && !fin_q[s];
      if (done_vec[s]) begin
        dn_any = 1'b1;
        dn_idx = SlotW'(s);
      end
    end
  end

  localparam int unsigned OutW = 32 + 24 + 1 + 32 + 3 * W + MaxLights;
  logic             fw_busy_q, fw_issue, fw_room, fw_free, fw_write;
  logic [SlotW-1:0] fw_slot_q;
  logic [1:0]       fw_lane_q;
  logic             st_valid_q, st_hit_q;
  logic [OutW-1:0]  st_rec_q;    // {pixel, rgb, hit, tri, t, u, v, lights}
  logic [2:0]       oq_count;
  logic             oq_valid;
  logic [OutW-1:0]  oq_wdata, oq_rdata;
  logic [2:0]       lb_valid;
  logic [23:0]      lb_rgb;

  assign fw_room  = oq_count + 3'(st_valid_q) < 3'd4;
  assign fw_issue = fw_busy_q && fw_room;
  assign fw_write = fw_issue && mask_q[fw_slot_q][fw_lane_q];
  assign fw_free  = fw_issue && fw_lane_q == 2'd3;

  for (genvar c = 0; c < 3; c++) begin : g_byte
    rc_light_byte #(
      .FixBits(rc_pkg::LightFixedBits),
      .SumW   (SumW)
    ) u_byte (
      .clk_i,
      .rst_ni,
      .valid_i(fw_write),
      .sum_i  (sum_q[{fw_slot_q, fw_lane_q}][c*SumW +: SumW]),
      .valid_o(lb_valid[c]),
      .byte_o (lb_rgb[c*8 +: 8])
    );
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fw_busy_q  <= 1'b0;
      fw_slot_q  <= '0;
      fw_lane_q  <= '0;
      st_valid_q <= 1'b0;
      st_hit_q   <= 1'b0;
      st_rec_q   <= '0;
    end else begin
      if (!fw_busy_q && dn_any) begin
        fw_busy_q <= 1'b1;
        fw_slot_q <= dn_idx;
        fw_lane_q <= '0;
      end else if (fw_issue) begin
        fw_lane_q <= fw_lane_q + 1'b1;
        if (fw_free) fw_busy_q <= 1'b0;
      end
      st_valid_q <= fw_write;
      if (fw_write) begin
        st_hit_q <= hit_q[{fw_slot_q, fw_lane_q}];
        st_rec_q <= {pix_q[{fw_slot_q, fw_lane_q}], rgb_q[{fw_slot_q, fw_lane_q}],
                     hit_q[{fw_slot_q, fw_lane_q}], tri_q[{fw_slot_q, fw_lane_q}],
                     t_q[{fw_slot_q, fw_lane_q}], u_q[{fw_slot_q, fw_lane_q}],
                     v_q[{fw_slot_q, fw_lane_q}],
                     hit_q[{fw_slot_q, fw_lane_q}] ? lm_q[{fw_slot_q, fw_lane_q}] : '0};
      end
    end
  end

  // A hit's colour is its sums' bytes, a miss's the core's write.
  always_comb begin
    oq_wdata = st_rec_q;
    if (st_hit_q) oq_wdata[OutW-33 -: 24] = lb_rgb;
  end

  rc_fifo #(
    .Width   (OutW),
    .Depth   (4),
    .MemArray(1'b1)
  ) u_out_q (
    .clk_i,
    .rst_ni,
    .push_i (st_valid_q),
    .data_i (oq_wdata),
    .valid_o(oq_valid),
    .ready_i(fb_ready_i),
    .data_o (oq_rdata),
    .count_o(oq_count)
  );
  assign fb_valid_o = oq_valid;
  assign {fb_pixel_o, fb_rgb_o, fb_hit_o, fb_tri_o, fb_t_o, fb_u_o, fb_v_o, fb_lights_o} = oq_rdata;

  //////////////////////////
  // The slots' state     //
  //////////////////////////

  logic [SlotW-1:0] fs_done_slot;
  assign fs_done_slot = fq_slot;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      busy_q <= '0;
      lit_q  <= '0;
      fin_q  <= '0;
      pend_q <= '0;
      sh_q   <= '0;
    end else begin
      for (int s = 0; s < Slots; s++) begin
        logic [ShW-1:0] sh_d;
        sh_d = sh_q[s*ShW +: ShW];
        if (shq_push && lt_slot == SlotW'(s)) sh_d = sh_d + sh_inc;
        if (cw_sh && cw_slot == SlotW'(s)) sh_d = sh_d - 1'b1;
        sh_q[s*ShW +: ShW] <= sh_d;
        if (ext_take && pkt_mask_i != 4'd0 && free_idx == SlotW'(s)) begin
          busy_q[s] <= 1'b1;
          lit_q[s]  <= 1'b0;
          fin_q[s]  <= 1'b0;
          pend_q[s*3 +: 3] <= 3'(pkt_mask_i[0]) + 3'(pkt_mask_i[1]) + 3'(pkt_mask_i[2]) +
                       3'(pkt_mask_i[3]);
        end else begin
          if (cw_prim && cw_slot == SlotW'(s)) pend_q[s*3 +: 3] <= pend_q[s*3 +: 3] - 1'b1;
          if ((fs_nohit && fs_done_slot == SlotW'(s)) ||
              (lt_take && lt_lane_last && lt_light_last && lt_slot == SlotW'(s)))
            lit_q[s] <= 1'b1;
          if (!fw_busy_q && dn_any && dn_idx == SlotW'(s)) fin_q[s] <= 1'b1;
          if (fw_free && fw_slot_q == SlotW'(s)) busy_q[s] <= 1'b0;
        end
      end
    end
  end

  // The slots' payload (no reset: written before it is read).
  always_ff @(posedge clk_i) begin
    if (ext_take) begin
      mask_q[free_idx] <= pkt_mask_i;
      for (int r = 0; r < 4; r++) begin
        pix_q[(SlotW + 2)'(4 * free_idx + r)] <= pkt_pixel_i[r*32 +: 32];
        ray_q[(SlotW + 2)'(4 * free_idx + r)] <= {pkt_inv_len_i[r*W +: W], pkt_dir_i[r*3*W +: 3*W],
                                               pkt_org_i[r*3*W +: 3*W]};
      end
    end
    if (cw_prim) begin
      hit_q[{cw_slot, cw_lane}] <= core_fb_hit;
      tri_q[{cw_slot, cw_lane}] <= core_fb_tri;
      t_q[{cw_slot, cw_lane}]   <= core_fb_t;
      u_q[{cw_slot, cw_lane}]   <= core_fb_u;
      v_q[{cw_slot, cw_lane}]   <= core_fb_v;
      dz_q[{cw_slot, cw_lane}]  <= core_fb_dz;
      rgb_q[{cw_slot, cw_lane}] <= core_fb_rgb;
    end
    // The lane's sums: the ambient term at light 0, a reached shadow ray's term (never the same
    // lane in one cycle: a light's shadow packet leaves after its samples).
    if (lt_take && lt_light == '0) begin
      for (int c = 0; c < 3; c++)
        sum_q[{lt_slot, lt_lane}][c*SumW +: SumW] <= SumW'(lt_amb[c*FW +: FW]);
      lm_q[{lt_slot, lt_lane}] <= '0;
    end
    if (cw_reached) begin
      lm_q[{cw_slot, cw_lane}][cw_light] <= 1'b1;
      for (int c = 0; c < 3; c++)
        sum_q[{cw_slot, cw_lane}][c*SumW +: SumW] <= sum_q[{cw_slot, cw_lane}][c*SumW +: SumW] +
            SumW'(term_q[{cw_slot, cw_light, cw_lane}][c*FW +: FW]);
    end
    if (lt_take && lt_present) term_q[{lt_slot, lt_light, lt_lane}] <= lt_term;
  end

  ////////////
  // Status //
  ////////////

  logic bad_addr_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) bad_addr_q <= 1'b0;
    else if (fetch_err) bad_addr_q <= 1'b1;
  end

  always_comb begin
    error_o = core_error;
    error_o[rc_pkg::CoreStatusBadAddress] = core_error[rc_pkg::CoreStatusBadAddress] || bad_addr_q;
  end
  assign idle_o = core_idle && busy_q == '0 && !st_valid_q && !oq_valid;

  // Not read: the controller makes the secondary packets.
  // Not read: the geometry of the children (none at max_bounces 0); the fields of the records the
  // lighting does not use; the pixel id bits above the controller's fields; counts only there for
  // the FIFO contract.
  logic unused;
  assign unused = ^{pkt_t_hi_i, pkt_start_tri_i, lb_valid, lmat_rsp_data_i, lshd_rsp_data_i,
                    geo_valid, geo_mirror, geo_refract, geo_tag, geo_p, geo_r, geo_refr,
                    geo_w_mirror, geo_w_refract, core_fb_pixel, fq_count};

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
  // The controller makes the secondary packets itself.
  PrimaryOnly_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  pkt_valid_i |-> pkt_kind_i ==
                                  rc_pkg::RayKindBits'(rc_pkg::RayKindPrimary));
  // Every lit hit has at least one light's samples (its sums start at light 0).
  LightCount_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 light_count_i != '0 && light_count_i <= CountW'(MaxLights));
  logic cw_expected, fs_held;
  assign cw_expected = busy_q[cw_slot] &&
                       (cw_shadow ? sh_q[cw_slot*ShW +: ShW] != '0 : pend_q[cw_slot*3 +: 3] != '0);
  assign fs_held     = busy_q[fs_slot_q];
  // A write of the core belongs to a held slot that expects it.
  CoreWrite_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                core_fb_valid |-> cw_expected);
  // A slot is not freed while the fetch still issues for it.
  FetchSlot_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                fs_busy_q |-> fs_held);
`endif

endmodule
