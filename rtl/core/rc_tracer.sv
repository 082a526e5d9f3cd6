// rc_tracer: the tree controller around rc_core (docs/architecture.md, "The tracer"): scene
// lighting made on chip. Primary packets go to the core; from each packet's hits the controller
// reads the shading records and materials, lights the hits with rc_hit_light, sends the shadow
// packets it makes back to the core, then the hits' mirror and refraction packets, lights their
// hits in turn, and writes each pixel once, when its whole ray tree is done: rc::lit_work(),
// rc::lit_accumulate() and rc::lit_finish() of tb/golden/trace.hpp, to depth max_bounces_i.
//
// Contract
// - Ports: rc_core's (its configuration, packet input, framebuffer write, five memory ports,
//   status, counters and debug, with the core's meaning; the core is built with Shade = 0, so
//   shd_* and mat_* make no requests and diffuse_i is not read: the lighting reads lshd_* and
//   lmat_*, and ambient_i goes to rc_hit_light), and:
//     light_count_i (1 .. MaxLights), light_dir_i, light_pos_i, light_col_i: the lights, as
//       rc_hit_light's; max_bounces_i (0 .. MaxBounces): the depth of the trees; bg_i: the
//       background colour as format values (channel c = byte c / 255 in double, rounded once),
//       what a mirror or refraction ray that misses sees (all quasi-static, as the core's
//       configuration);
//     lshd_*: shading records for the lighting (the core's shd record: material word, unit
//       normal, |n|), tag FetchW bits;
//     lmat_*: materials for the lighting: bytes [image_material] kd .. eta + 4 of a record
//       (LMatW bits, the field at byte offset o at [(o - kd)*8 +: 32]), tag FetchW bits.
//   Both follow the memory protocol of docs/architecture.md ("Memory ports").
// - Packet input: primary packets only (pkt_kind_i, pkt_t_hi_i and pkt_start_tri_i are not
//   read). A packet with rays takes a slot (Slots of them); pkt_ready_o is low while no slot is
//   free or a packet of the controller's own waits for the core.
// - Framebuffer write port: one write per existing ray of every primary packet, in no particular
//   order, once the pixel's tree is done: the pixel id; fb_rgb_o = light_byte() of the pixel's
//   sums for a hit, the core's write for a ray without a hit (the background); the primary ray's
//   hit record as the core wrote it; fb_lights_o, bit l: light l's shadow ray from the primary
//   hit reached the light (0 for a miss); fb_bounce_tri_o, fb_refract_tri_o: the triangle the
//   pixel's first mirror (refraction) ray hit, -1 when it missed or its packet failed, -2 when
//   there is none.
// - Inside (docs/architecture.md, "The tracer"): a slot holds a primary packet's pixel ids, its
//   hit records, its lanes' sums and one packet of its tree at a time, the current one: its rays,
//   weights, depth and the core's writes. Every non-shadow packet the core gets carries
//   {0, depth 0, depth 1, slot, lane} as its pixel ids, a shadow packet {1, from a primary hit,
//   light, slot, shadow packet, lane} (PixD0 below), so that a write brings what it needs; the
//   core's writes come back here and are always taken. When a packet's writes are all back, its
//   lanes go to the fetch in lane order: a hit to a shading request, then a material request (Ns through
//   rc_fp_to_exp; eta_enter = 1 / ior is the record's eta), put back in order in FetchEntries
//   entries, then to rc_hit_light with the packet's ray and weight; a miss below a mirror or
//   refraction ray (depth > 0) to fix(bg x weight). A sample at light 0 adds the hit's ambient
//   term; a present sample's ray goes into the light's shadow packet, which takes one of
//   ShadowPackets entries (its slot, light and four terms) and goes to the core; a shadow ray's
//   write without a hit and without its packet's error (colour 1) adds its term (two cycles
//   later; the packets' terms are a block RAM). The hits'
//   geometry makes the packet's mirror and refraction packets (depth < max_bounces_i): the
//   mirror packet becomes the slot's current packet, the refraction packet goes onto the slot's
//   stack (MaxBounces entries of a block RAM), popped when a packet has no mirror packet (the
//   popped packet is sent a cycle after the decision); a packet that met an
//   error adds nothing and has no children. The slot is done when no packet of its tree is left
//   and all its terms are added; its lanes are then written, one per cycle, and it is freed.
// - Status: idle_o = the core idle, no slot held and no write pending. error_o: the core's, and
//   CoreStatusBadAddress on an error response of lshd_* or lmat_* (its hit is lit as black).
// - Parameters: the core's (passed on); Slots >= 1 ([tracer] slots); FetchEntries a power of
//   two >= 2 ([tracer] fetch_entries); ShadowPackets >= 1 ([tracer] shadow_packets); MaxLights
//   ([light] max_lights); MaxBounces ([light] bounce_limit); LightPeriod (rc_hit_light's Period,
//   6 or 12: [light] unit_period); BlockDelays (the core's: its intersection unit's delay lines
//   in block RAM; the lit board's [board] lit_block_delays).
// - Illegal input: light_count_i of 0 or above MaxLights; max_bounces_i above MaxBounces; a
//   packet kind other than primary (assertions catch all three).
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
  parameter int unsigned MaxBounces     = rc_pkg::LightBounceLimit,
  parameter int unsigned ShadowPackets  = rc_pkg::TracerShadowPackets,
  parameter int unsigned LightPeriod    = rc_pkg::LightUnitPeriod,
  parameter bit          BlockDelays    = 1'b0,
  // Derived (do not override).
  parameter int unsigned W              = 1 + ExpW + FracW,
  parameter int unsigned TagW           = rc_pkg::CoreTagBits,
  parameter int unsigned StatusW        = rc_pkg::CoreStatusBits,
  parameter int unsigned NodeRecW       = 8 * rc_pkg::KdNodeBytes,
  parameter int unsigned NodeRspW       = rc_pkg::CoreNodeRspRecords * NodeRecW,
  parameter int unsigned FetchW         = (FetchEntries > 1) ? $clog2(FetchEntries) : 1,
  parameter int unsigned CountW         = $clog2(MaxLights + 1),
  parameter int unsigned DepthW         = $clog2(MaxBounces + 1),
  parameter int unsigned LMatW          =
      8 * (rc_pkg::ImageMaterialEta + 4 - rc_pkg::ImageMaterialKd)
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
  input  logic [DepthW-1:0]        max_bounces_i,
  input  logic [3*W-1:0]           bg_i,          // the background as format values

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
  output logic [31:0]              fb_bounce_tri_o,
  output logic [31:0]              fb_refract_tri_o,

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
  localparam int unsigned LaneW  = SlotW + 2;                  // {slot, lane}
  localparam int unsigned LightW = (MaxLights > 1) ? $clog2(MaxLights) : 1;
  localparam int unsigned SpW    = (ShadowPackets > 1) ? $clog2(ShadowPackets) : 1;
  // The pixel ids the core carries for the controller's packets (bit 31: a shadow packet):
  //   a slot's packet: {0, depth 0, depth 1, 0.., slot, lane};
  //   a shadow packet: {1, from a primary hit, 0.., light, slot, shadow packet, lane};
  // so that the core's write brings what the controller needs with it, without a look-up.
  localparam int unsigned PixD0    = 30;  // a slot's packet: its depth is 0 / a shadow packet's
  localparam int unsigned PixD1    = 29;  // hit is a primary one; a slot's packet: depth 1
  localparam int unsigned PixSlot  = 2 + SpW;           // a shadow packet's slot
  localparam int unsigned PixLight = 2 + SpW + SlotW;   // and light
  localparam int unsigned FW     = rc_pkg::LightFixedBits + 1;
  localparam int unsigned ExpB   = rc_pkg::LightExponentBits;
  localparam int unsigned SumW   = 32;
  localparam int unsigned AddQ   = 8;                            // the add queue's entries
  // A slot's work out: its shadow rays in the core (at most 4 per shadow packet), its adds
  // pending (ambient and miss terms, at most two add queues' worth) and its packets in
  // rc_hit_light (at most MaxBounces + 1): one counter, as the slot waits for all three.
  localparam int unsigned WkW    = $clog2(4 * ShadowPackets + 2 * AddQ + MaxBounces + 2);
  // The miss term's latency: the issue's register, the weight's register and three channels,
  // one a cycle (the term leaves with the third), the product, the fixed point (two stages).
  localparam int unsigned MissL  = 4 + rc_pkg::FpStagesMul + 2;
  localparam int unsigned KsLsb  = 8 * (rc_pkg::ImageMaterialKs - rc_pkg::ImageMaterialKd);
  localparam int unsigned NsLsb  = 8 * (rc_pkg::ImageMaterialNs - rc_pkg::ImageMaterialKd);
  localparam int unsigned IorLsb = 8 * (rc_pkg::ImageMaterialIor - rc_pkg::ImageMaterialKd);
  localparam int unsigned MirLsb = 8 * (rc_pkg::ImageMaterialMirror - rc_pkg::ImageMaterialKd);
  localparam int unsigned TrLsb  = 8 * (rc_pkg::ImageMaterialTransmit - rc_pkg::ImageMaterialKd);
  localparam int unsigned EtaLsb = 8 * (rc_pkg::ImageMaterialEta - rc_pkg::ImageMaterialKd);
  localparam int unsigned NrmLsb = 8 * rc_pkg::ImageShadingFirstValue +
                                   W * rc_pkg::ImageShadingNormal;
  localparam int unsigned MatLsb = 8 * rc_pkg::ImageShadingMaterial;
  localparam logic [W-1:0] FpOne = {1'b0, 1'b0, {(ExpW - 1){1'b1}}, {FracW{1'b0}}};
  localparam logic [W-1:0] FpInf = {1'b0, {ExpW{1'b1}}, {FracW{1'b0}}};

  if (Slots < 1 || FetchEntries < 2 || (FetchEntries & (FetchEntries - 1)) != 0 ||
      ShadowPackets < 1 || MaxBounces < 1 || 2 + SlotW > PixD1 ||
      PixLight + LightW > PixD1) begin : g_param_check
    $error("rc_tracer: need Slots, ShadowPackets, MaxBounces >= 1, FetchEntries a power of two >= 2, pixel ids within 32 bits");
  end

  // Three format values at [a*W +: W] from a material field of three 32-bit slots.
  function automatic logic [3*W-1:0] rgb_field(input logic [LMatW-1:0] d,
                                                input int unsigned lsb);
    for (int a = 0; a < 3; a++) rgb_field[a*W +: W] = d[lsb + 32*a +: W];
  endfunction

  // A packet of the tree (a slot's mirror or refraction packet).
  typedef struct packed {
    logic [3:0]        mask;
    logic              mirror;    // a mirror packet (else refraction)
    logic [DepthW-1:0] depth;
    logic [12*W-1:0]   org;
    logic [12*W-1:0]   dir;
    logic [4*W-1:0]    w;
    logic [127:0]      stri;      // the rays' start triangles
  } child_t;

  ///////////////
  // The slots //
  ///////////////

  logic [Slots-1:0]       busy_q;    // held by a primary packet
  logic [Slots-1:0]       td_q;      // its tree has no packet left to trace or light
  logic [Slots-1:0]       fin_q;     // its writes are being made
  logic [Slots-1:0]       cf_q;      // the current packet failed (a secondary packet's colour 1)
  logic [Slots-1:0]       cm_q;      // the current packet is a mirror packet
  logic [Slots*3-1:0]     pend_q;    // the current packet's writes still due, [3s +: 3]
  logic [Slots-1:0]       pend1_q;   // pend_q[3s +: 3] == 1 (Pend1_A)
  logic [Slots*DepthW-1:0] depth_q;  // the current packet's depth
  logic [Slots*WkW-1:0]   wk_q;      // work out: shadow rays, adds pending, packets being lit
  logic [Slots*DepthW-1:0] sp_q;     // the stack's entries
  logic [3:0]             pmask_q  [Slots];   // the primary packet's rays
  logic [3:0]             cmask_q  [Slots];   // the current packet's rays
  logic [Slots*4-1:0]     hit_q;               // its hits, at {slot, lane}
  // The per-lane records are block RAMs (u_lanes, below), the stacks too (u_stack).
  // The adds to the lanes' sums (u_lanes): an add is read in one cycle, its old sum registered
  // in the next and the sum written in the third.
  logic                   ln_add, ln_add_pend, ln_add_pend1;
  logic [LaneW-1:0]       ln_add_ln;
  logic [SlotW-1:0]       ln_add_slot, ln_add_slot1;
  logic [3*FW-1:0]        aq_term_q, aq_term2_q, ln_add_term;
  logic [MaxLights-1:0]   ln_add_lights;

  ///////////////////////////
  // Packets into the core //
  ///////////////////////////

  logic                     core_pkt_valid, core_pkt_ready;
  logic [3:0]               core_pkt_mask;
  logic [12*W-1:0]          core_pkt_org, core_pkt_dir;
  logic [4*W-1:0]           core_pkt_inv_len, core_pkt_t_hi;
  logic [127:0]             core_pkt_pixel, core_pkt_start_tri;
  logic [rc_pkg::RayKindBits-1:0] core_pkt_kind;

  // The shadow packet queue and the tree packet queue (one entry each, below).
  localparam int unsigned ShqW = 4 + 24 * W + 4 * W + 128 + 1 + LightW + SlotW + SpW;
  localparam int unsigned BqW  = 1 + 1 + 4 + 28 * W + 128 + SlotW;
  logic            shq_push, shq_valid, shq_pop;
  logic [ShqW-1:0] shq_wdata, shq_rdata;
  logic            shq_count;
  logic [3:0]      shq_mask;
  logic [12*W-1:0] shq_org, shq_dir;
  logic [4*W-1:0]  shq_t_hi;
  logic [127:0]    shq_tri;
  logic [SpW-1:0]  shq_sp;
  logic            shq_d0;
  logic [LightW-1:0] shq_light;
  logic [SlotW-1:0] shq_slot;
  logic            bq_push, bq_valid, bq_pop;
  logic [BqW-1:0]  bq_wdata, bq_rdata;
  logic            bq_count;
  logic            bq_mirror, bq_d1;
  logic [3:0]      bq_mask;
  logic [12*W-1:0] bq_org, bq_dir;
  logic [4*W-1:0]  bq_w;
  logic [127:0]    bq_tri;
  logic [SlotW-1:0] bq_slot;

  // The shadow packet queue holds one packet: the light samples wait while it is full.
  rc_fifo #(
    .Width   (ShqW),
    .Depth   (1),
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
  assign {shq_mask, shq_org, shq_dir, shq_t_hi, shq_tri, shq_d0, shq_light, shq_slot,
          shq_sp} = shq_rdata;

  // The tree packet queue holds one packet: a decision (which sends at most one) needs it empty
  // and no pop in its second cycle (dec_room).
  rc_fifo #(
    .Width   (BqW),
    .Depth   (1),
    .MemArray(1'b0)
  ) u_tree_q (
    .clk_i,
    .rst_ni,
    .push_i (bq_push),
    .data_i (bq_wdata),
    .valid_o(bq_valid),
    .ready_i(bq_pop),
    .data_o (bq_rdata),
    .count_o(bq_count)
  );
  assign {bq_d1, bq_mirror, bq_mask, bq_org, bq_dir, bq_w, bq_tri, bq_slot} = bq_rdata;

  // A free slot: the lowest and the highest free slots of the cycle before, registered (lo_*,
  // hi_*); the lowest, unless it was taken in the cycle before (one slot is taken per cycle),
  // then the highest when it is another. A slot freed in a cycle is offered from the one after
  // the next.
  logic             free_any, slot_take, lo_any_c, hi_any_c, lo_any_q, hi_any_q;
  logic [SlotW-1:0] free_idx, lo_idx_c, hi_idx_c, lo_idx_q, hi_idx_q;
  logic [Slots-1:0] free_hot, lo_hot_c, hi_hot_c, lo_hot_q, hi_hot_q, busy_rev;
  logic             use_hi, use_hi_st;
  rc_lowest #(
    .N   (Slots),
    .IdxW(SlotW)
  ) u_free (
    .req_i  (~busy_q),
    .valid_o(lo_any_c),
    .idx_o  (lo_idx_c),
    .hot_o  (lo_hot_c)
  );
  always_comb begin
    for (int s = 0; s < Slots; s++) busy_rev[s] = busy_q[Slots - 1 - s];
  end
  logic [SlotW-1:0] hi_ridx;
  logic [Slots-1:0] hi_rhot;
  rc_lowest #(
    .N   (Slots),
    .IdxW(SlotW)
  ) u_free_hi (
    .req_i  (~busy_rev),
    .valid_o(hi_any_c),
    .idx_o  (hi_ridx),
    .hot_o  (hi_rhot)
  );
  always_comb begin
    hi_idx_c = SlotW'(Slots - 1) - hi_ridx;
    for (int s = 0; s < Slots; s++) hi_hot_c[s] = hi_rhot[Slots - 1 - s];
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lo_any_q <= 1'b0;
      hi_any_q <= 1'b0;
    end else begin
      lo_any_q <= lo_any_c;
      // The highest free slot is another than the lowest when two or more are free: the free
      // vector less its lowest bit (one carry chain, not the two picks' indices compared).
      hi_any_q <= (~busy_q & (~busy_q - 1'b1)) != '0;
    end
  end
  always_ff @(posedge clk_i) begin
    lo_idx_q   <= lo_idx_c;
    lo_hot_q   <= lo_hot_c;
    hi_idx_q   <= hi_idx_c;
    hi_hot_q   <= hi_hot_c;
  end
  // "The lowest was taken in the cycle before" (use_hi) is itself a register, two kept copies
  // (UseHi_A): the lowest free slot of this cycle is the one taken. use_hi_st selects the slots'
  // state enables (about 200 flip-flops' enables through free_hot), use_hi the rest. (The lit
  // board routed: at 6799b81, seed 2, the slot taken, which Yosys had merged with the lane
  // store's pr_slot_q beside the block RAMs, through the compare into cf_q, cmask_q, pend_q and
  // depth_q, -1.61 ns; at d6b0aa3, seed 1, with a register of its own, -1.47 ns, 217
  // endpoints.)
  rc_reg_copies #(
    .Width   (1),
    .Copies  (2),
    .HasReset(1'b1)
  ) u_use_hi (
    .clk_i,
    .rst_ni,
    .d_i(slot_take && lo_idx_c == free_idx),
    .q_o({use_hi_st, use_hi})
  );
  assign free_any = use_hi ? hi_any_q : lo_any_q;
  assign free_idx = use_hi ? hi_idx_q : lo_idx_q;
  assign free_hot = use_hi_st ? hi_hot_q : lo_hot_q;

  // The controller's own packets first: shadow packets, then the trees' packets.
  // The queues' valid bits select about a thousand multiplexer bits into the core's set-up unit
  // and the lane records' ray write: each is also five kept copies (rc_reg_copies), loaded from
  // its queue's next valid (a one-entry queue: a push into an empty queue, or a packet held and
  // not popped), so no one flip-flop's net spans them all (ShqSel_A, BqSel_A). Copy 0 makes the
  // handshakes, 1 the origins, 2 the directions and the rest of the rays, 3 the pixel ids and
  // start triangles, 4 the lane records' slot and weights.
  localparam int unsigned SelCopies = 5;
  logic [SelCopies-1:0] shq_sel, bq_sel;
  rc_reg_copies #(
    .Width   (1),
    .Copies  (SelCopies),
    .HasReset(1'b1)
  ) u_shq_sel (
    .clk_i,
    .rst_ni,
    .d_i(shq_push || (shq_valid && !shq_pop)),
    .q_o(shq_sel)
  );
  rc_reg_copies #(
    .Width   (1),
    .Copies  (SelCopies),
    .HasReset(1'b1)
  ) u_bq_sel (
    .clk_i,
    .rst_ni,
    .d_i(bq_push || (bq_valid && !bq_pop)),
    .q_o(bq_sel)
  );

  logic ext_take, slot_offer;
  assign slot_offer     = pkt_valid_i && free_any;
  assign pkt_ready_o    = core_pkt_ready && !shq_sel[0] && !bq_sel[0] && free_any;
  assign ext_take       = pkt_valid_i && pkt_ready_o;
  assign slot_take      = ext_take && pkt_mask_i != 4'd0;
  assign shq_pop        = shq_sel[0] && core_pkt_ready;
  assign bq_pop         = bq_sel[0] && !shq_sel[0] && core_pkt_ready;
  assign core_pkt_valid = shq_sel[0] || bq_sel[0] || (pkt_valid_i && free_any);

  // Each field's select reads its own copy.
  always_comb begin
    core_pkt_org = shq_sel[1] ? shq_org : bq_sel[1] ? bq_org : pkt_org_i;
    if (shq_sel[2]) begin
      core_pkt_mask    = shq_mask;
      core_pkt_dir     = shq_dir;
      core_pkt_inv_len = {4{FpOne}};
      core_pkt_kind    = rc_pkg::RayKindBits'(rc_pkg::RayKindShadow);
      core_pkt_t_hi    = shq_t_hi;
    end else if (bq_sel[2]) begin
      core_pkt_mask    = bq_mask;
      core_pkt_dir     = bq_dir;
      core_pkt_inv_len = {4{FpOne}};
      core_pkt_kind    = rc_pkg::RayKindBits'(bq_mirror ? rc_pkg::RayKindBounce :
                                                           rc_pkg::RayKindRefract);
      core_pkt_t_hi    = {4{FpInf}};
    end else begin
      core_pkt_mask    = pkt_mask_i;
      core_pkt_dir     = pkt_dir_i;
      core_pkt_inv_len = pkt_inv_len_i;
      core_pkt_kind    = rc_pkg::RayKindBits'(rc_pkg::RayKindPrimary);
      core_pkt_t_hi    = '0;
    end
    core_pkt_pixel = '0;
    if (shq_sel[3]) begin
      core_pkt_start_tri = shq_tri;
      for (int r = 0; r < 4; r++) begin
        core_pkt_pixel[r*32 +: 32]   = 32'({shq_light, shq_slot, shq_sp, 2'(r)});
        core_pkt_pixel[r*32 + 31]    = 1'b1;
        core_pkt_pixel[r*32 + PixD0] = shq_d0;
      end
    end else if (bq_sel[3]) begin
      core_pkt_start_tri = bq_tri;
      for (int r = 0; r < 4; r++) begin
        core_pkt_pixel[r*32 +: 32]   = 32'({bq_slot, 2'(r)});
        core_pkt_pixel[r*32 + PixD1] = bq_d1;
      end
    end else begin
      core_pkt_start_tri = '0;
      for (int r = 0; r < 4; r++) begin
        core_pkt_pixel[r*32 +: 32]   = 32'({free_idx, 2'(r)});
        core_pkt_pixel[r*32 + PixD0] = 1'b1;
      end
    end
  end
  logic lane_bq;  // the lane records' ray write is a tree packet's
  assign lane_bq = bq_sel[4] && !shq_sel[4];

  //////////////
  // The core //
  //////////////

  // The core's writes (co_*, its output register in the shading unit) are registered here
  // (core_fb_*, loaded in every cycle) before the controller takes them: the shading unit is
  // across the die from the fetch queue, the shadow packets' counts and the lane records.
  logic            co_valid, co_hit;
  logic [31:0]     co_pixel, co_tri;
  logic [23:0]     co_rgb;
  logic [W-1:0]    co_t, co_u, co_v, co_dz;
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
    .Secondary     (1'b1),
    .Shade         (1'b0),
    .BlockDelays   (BlockDelays)
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
    .fb_valid_o      (co_valid),
    .fb_ready_i      (1'b1),
    .fb_pixel_o      (co_pixel),
    .fb_rgb_o        (co_rgb),
    .fb_hit_o        (co_hit),
    .fb_tri_o        (co_tri),
    .fb_t_o          (co_t),
    .fb_u_o          (co_u),
    .fb_v_o          (co_v),
    .fb_dz_o         (co_dz),
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

  // The valid bit is four kept registers (rc_reg_copies), one per group of the write's users:
  // 0 the fetch queue, 1 the slots' state, 2 the lane records' ports and the add queue, 3 the
  // shadow packets. Kept, too, because the core's watchdog registers the same handshake and
  // synthesis would otherwise merge them into the core's flip-flop.
  logic [3:0] fbv_q;
  rc_reg_copies #(
    .Width   (1),
    .Copies  (4),
    .HasReset(1'b1)
  ) u_fb_valid (
    .clk_i,
    .rst_ni,
    .d_i(co_valid),
    .q_o(fbv_q)
  );
  assign core_fb_valid = fbv_q[0];
  always_ff @(posedge clk_i) begin
    {core_fb_hit, core_fb_pixel, core_fb_tri, core_fb_rgb, core_fb_t, core_fb_u, core_fb_v,
     core_fb_dz} <= {co_hit, co_pixel, co_tri, co_rgb, co_t, co_u, co_v, co_dz};
  end

  // The core's write: a slot's current packet's ray, or a shadow packet's.
  logic              cw_shadow, cw_cur, cw_sh, cw_reached, cw_d0, cw_d1;
  logic              cw_cur_fq, cw_cur_ln, cw_reached_ln;  // cw_cur, cw_reached: other copies
  logic [SlotW-1:0]  cw_slot;     // the current packet's slot
  logic [SpW-1:0]    cw_sp;       // the shadow packet
  logic [1:0]        cw_lane;
  logic [LaneW-1:0]  cw_ln;       // {slot, lane} of the current packet's ray
  assign cw_shadow  = core_fb_pixel[31];
  assign cw_slot    = core_fb_pixel[2 +: SlotW];
  assign cw_sp      = core_fb_pixel[2 +: SpW];
  assign cw_lane    = core_fb_pixel[1:0];
  assign cw_ln      = {cw_slot, cw_lane};
  assign cw_cur     = fbv_q[1] && !cw_shadow;
  assign cw_cur_fq  = fbv_q[0] && !cw_shadow;
  assign cw_cur_ln  = fbv_q[2] && !cw_shadow;
  assign cw_sh      = fbv_q[3] && cw_shadow;
  assign cw_d0      = core_fb_pixel[PixD0];
  assign cw_d1      = core_fb_pixel[PixD1];
  // A shadow ray reached its light: no hit, and its packet met no error (colour 1).
  assign cw_reached = cw_sh && !core_fb_hit && !core_fb_rgb[0];
  assign cw_reached_ln = fbv_q[2] && cw_shadow && !core_fb_hit && !core_fb_rgb[0];

  // The shadow packets in flight: busy and rays out (the four terms are a block RAM, u_terms,
  // below; the slot, light and whether from a primary hit travel in the rays' pixel ids).
  logic [ShadowPackets-1:0] spb_q;
  logic [2:0]               sp_cnt_q   [ShadowPackets];
  logic [SlotW-1:0]         cws_slot;
  assign cws_slot = core_fb_pixel[PixSlot +: SlotW];

  // A free shadow packet: the lowest, registered. It was free in the cycle before. A packet
  // taken at a close becomes busy at its push, the cycle after, and the next close is two
  // cycles later still (lt_ready: none in the push's cycle, nor while the one-entry shadow
  // packet queue is full), so a packet taken is not offered again.
  logic                     sp_free_any, sp_free_any_c;
  logic [SpW-1:0]           sp_free, sp_free_c;
  logic [ShadowPackets-1:0] sp_free_hot, sp_free_hot_c;
  rc_lowest #(
    .N   (ShadowPackets),
    .IdxW(SpW)
  ) u_sp_free (
    .req_i  (~spb_q),
    .valid_o(sp_free_any_c),
    .idx_o  (sp_free_c),
    .hot_o  (sp_free_hot_c)
  );
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) sp_free_any <= 1'b0;
    else sp_free_any <= sp_free_any_c;
  end
  always_ff @(posedge clk_i) begin
    sp_free     <= sp_free_c;
    sp_free_hot <= sp_free_hot_c;
  end

  ///////////////////////////////////////////
  // Fetch: shading record, then material  //
  ///////////////////////////////////////////

  // Slots whose current packet's writes are all back, in order: a FIFO (fr_*), then the head
  // register (fq_*), which holds the head's lanes to fetch, read from the slot's records when it
  // enters (they do not change while the slot waits for its fetch).
  logic             fq_push, fq_valid, fq_pop, fr_valid, fr_pop;
  logic [SlotW-1:0] fq_slot, fr_slot;
  logic [$clog2(Slots + 1)-1:0] fq_count;
  // A slot enters the queue in the cycle after its last write (fq_push, registered with its
  // slot): the write's pixel id selects its slot's flag, which ends at a register instead of at
  // the queue's enables.
  logic             fq_push_q;
  logic [SlotW-1:0] fq_wslot_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) fq_push_q <= 1'b0;
    else fq_push_q <= fq_push;
  end
  always_ff @(posedge clk_i) fq_wslot_q <= cw_slot;
  // Whether the write is its packet's last reads a flag per slot (pend1_q), not the slot's count
  // and a compare (the lit board routed at 6799b81, seed 2: core_fb_pixel through the count's
  // select into fq_push_q, -2.30 ns).
  assign fq_push = cw_cur_fq && pend1_q[cw_slot];

  rc_fifo #(
    .Width   (SlotW),
    .Depth   (Slots),
    .MemArray(1'b1)
  ) u_fetch_q (
    .clk_i,
    .rst_ni,
    .push_i (fq_push_q),
    .data_i (fq_wslot_q),
    .valid_o(fr_valid),
    .ready_i(fr_pop),
    .data_o (fr_slot),
    .count_o(fq_count)
  );

  // The popped packet's lanes: its hits (to the lighting) and, below the primary, its misses (to
  // the miss term); none when it failed.
  logic [3:0] fq_hits, fq_work, fr_hits, fr_miss;
  logic       fr_deep;
  assign fr_deep = depth_q[fr_slot*DepthW +: DepthW] != '0;
  assign fr_hits = cf_q[fr_slot] ? 4'd0 : hit_q[fr_slot*4 +: 4] & cmask_q[fr_slot];
  assign fr_miss = (cf_q[fr_slot] || !fr_deep) ? 4'd0 : ~hit_q[fr_slot*4 +: 4] & cmask_q[fr_slot];
  assign fr_pop  = fr_valid && (!fq_valid || fq_pop);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) fq_valid <= 1'b0;
    else if (fr_pop || fq_pop) fq_valid <= fr_pop;
  end
  always_ff @(posedge clk_i) begin
    if (fr_pop) begin
      fq_slot <= fr_slot;
      fq_hits <= fr_hits;
      fq_work <= fr_hits | fr_miss;
    end
  end

  // The decision on a packet's children: at its geometry's last record (dec_geo); for a packet
  // without hits at its last miss's issue (dec_seq), or at its pop when it has no lane to fetch
  // (a failed packet, a primary packet without hits); the last two wait for a cycle without
  // dec_geo and for room in the tree packet queue.
  logic dec_geo, dec_room;
  logic fs_busy_q;
  logic pop_q;  // a stack pop's read: its packet is sent in this cycle, no decision is made
  logic dq_q;   // a decision's second cycle: it is carried out, no decision is made
  assign dec_room = !bq_count && !pop_q && !dq_q;
  // A decision of the fetch or the sequencer yields to a geometry's last record that waits
  // (geo_end), taken or not: a record of another slot's packet, which the sequencer does not
  // hold up, so it is taken once there is room.
  logic geo_end;
  assign fq_pop   = fq_valid && !fs_busy_q && (fq_work != 4'd0 || (dec_room && !geo_end));

  // The sequencer: the popped packet's lanes, one per two cycles (fs_wait_q, below).
  logic [SlotW-1:0] fs_slot_q;
  logic [3:0]       fs_lanes_q, fs_hits_q;
  logic [1:0]       fs_lane;
  logic             fs_hit, fs_last, fs_step, fs_room_hit, fs_room_miss;
  assign fs_lane = rc_pkg::ray_lowest(fs_lanes_q);
  assign fs_hit  = fs_hits_q[fs_lane];
  assign fs_last = (fs_lanes_q & fs_hits_q & ~(4'd1 << fs_lane)) == 4'd0;  // its last hit

  // The lane's records (u_lanes) are read two cycles ahead (the address registered beside the
  // block RAMs, then their read register): at a pop its first lane, at a step the next one,
  // else the lane again; so seq_* hold fs_lane's from the second cycle after a pop or a step
  // on, and the sequencer waits one cycle after each (fs_wait_q): a lane per two cycles. The
  // ray and its weight (seq_ray, seq_w) come a cycle later still, through a register after the
  // block RAMs: they are fs_lane's in the cycle after a step, and in the one after that, and
  // their users (the entry's copy, the miss term's weight) take them then.
  logic [LaneW-1:0] seq_ln;
  logic [7*W-1:0]   seq_ray;
  logic [W-1:0]     seq_w, seq_t, seq_dz;
  logic [31:0]      seq_tri;

  // The entries: a ring, allocated in lane order, filled in any order, retired in order.
  logic [FetchW-1:0] fe_head_q, fe_tail_q;
  logic [FetchW:0]   fe_count_q;
  logic [FetchEntries-1:0] fe_done_q;
  logic [LaneW-1:0]  fe_ln_q    [FetchEntries];
  logic [DepthW-1:0] fe_depth_q [FetchEntries];  // the slot's depth (FeDepth_A)
  logic              fe_last_q  [FetchEntries];
  logic [3*W-1:0]    fe_n_q     [FetchEntries];
  logic [3*W-1:0]    fe_kd_q    [FetchEntries];
  logic [3*W-1:0]    fe_ks_q    [FetchEntries];
  logic [W-1:0]      fe_ior_q   [FetchEntries];
  logic [W-1:0]      fe_mir_q   [FetchEntries];
  logic [W-1:0]      fe_tr_q    [FetchEntries];
  logic [ExpB-1:0]   fe_ns_q    [FetchEntries];
  logic [W-1:0]      fe_eta_q   [FetchEntries];
  logic [7*W-1:0]    fe_ray_q   [FetchEntries];  // the lane's records, copied at allocation
  logic [W-1:0]      fe_w_q     [FetchEntries];
  logic [31:0]       fe_tri_q   [FetchEntries];
  logic [W-1:0]      fe_t_q     [FetchEntries];
  logic [W-1:0]      fe_dz_q    [FetchEntries];

  logic              lshd_req_valid_q;
  logic [FetchW-1:0] lshd_req_tag_q;
  logic [31:0]       lshd_req_index_q;
  logic              mi_ok;       // room for a miss term
  logic              mi_free;     // the miss term's multiplier takes a miss
  // A hit needs an entry and a free shading request register; the port's ready is not waited
  // for (it comes from across the die), and the sequencer steps a lane per two cycles anyway.
  logic fe_room;  // the ring has room (a register: FeRoom_A)
  assign fs_room_hit  = fe_room && !lshd_req_valid_q;
  assign fs_room_miss = mi_ok && mi_free;
  // A packet without hits is decided at its last miss's issue (dec_seq), after its weights are
  // read.
  logic fs_final, dec_seq;
  assign fs_final     = fs_hits_q == 4'd0 && (fs_lanes_q & ~(4'd1 << fs_lane)) == 4'd0;
  logic fs_wait_q;
  assign fs_step      = fs_busy_q && !fs_wait_q && (fs_hit ? fs_room_hit : fs_room_miss) &&
                        (!fs_final || (dec_room && !geo_end));
  assign dec_seq      = fs_step && fs_final;
  logic fs_alloc, mi_issue;
  assign fs_alloc = fs_step && fs_hit;
  assign mi_issue = fs_step && !fs_hit;
  always_comb begin
    if (fq_pop && fq_work != 4'd0) seq_ln = {fq_slot, rc_pkg::ray_lowest(fq_work)};
    else if (fs_step) seq_ln = {fs_slot_q, rc_pkg::ray_lowest(fs_lanes_q & ~(4'd1 << fs_lane))};
    else seq_ln = {fs_slot_q, fs_lane};
  end

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

  // Ns as the integer exponent (two cycles), the entry beside it; the entry is complete with Ns.
  // eta_enter = 1 / ior is the record's eta (the image holds it rounded once, as the rules
  // compute it); a failed read gives ior 0 and eta +inf, which is 1 / 0.
  logic [W-1:0]      lmat_ns, lmat_ior, lmat_eta;
  logic              ns_valid;
  logic [ExpB-1:0]   ns_val;
  logic [FetchW-1:0] ns_tag1_q, ns_tag_q;
  assign lmat_ns  = lmat_rsp_error_i ? W'(0) : lmat_rsp_data_i[NsLsb +: W];
  assign lmat_ior = lmat_rsp_error_i ? W'(0) : lmat_rsp_data_i[IorLsb +: W];
  assign lmat_eta = lmat_rsp_error_i ? FpInf : lmat_rsp_data_i[EtaLsb +: W];
  rc_fp_to_exp #(
    .ExpW   (ExpW),
    .FracW  (FracW),
    .ExpBits(ExpB),
    .Stages (2)
  ) u_ns (
    .clk_i,
    .rst_ni,
    .valid_i(lmat_take),
    .x_i    (lmat_ns),
    .valid_o(ns_valid),
    .ns_o   (ns_val)
  );

  logic fetch_err;
  assign fetch_err = (lshd_take && lshd_rsp_error_i) || (lmat_take && lmat_rsp_error_i);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fs_busy_q        <= 1'b0;
      fs_wait_q        <= 1'b0;
      fs_slot_q        <= '0;
      fs_lanes_q       <= '0;
      fs_hits_q        <= '0;
      lshd_req_valid_q <= 1'b0;
      lshd_req_tag_q   <= '0;
      lshd_req_index_q <= '0;
      lmat_req_valid_q <= 1'b0;
      lmat_req_tag_q   <= '0;
      lmat_req_index_q <= '0;
      ns_tag1_q        <= '0;
      ns_tag_q         <= '0;
    end else begin
      fs_wait_q <= (fq_pop && fq_work != 4'd0) || fs_step;
      if (fq_pop && fq_work != 4'd0) begin
        fs_busy_q  <= 1'b1;
        fs_slot_q  <= fq_slot;
        fs_lanes_q <= fq_work;
        fs_hits_q  <= fq_hits;
      end else if (fs_step) begin
        fs_lanes_q <= fs_lanes_q & ~(4'd1 << fs_lane);
        if ((fs_lanes_q & ~(4'd1 << fs_lane)) == 4'd0) fs_busy_q <= 1'b0;
      end
      // The request's fields load while the register is free, allocated or not (an allocation
      // needs it free), so the sequencer's step is only the valid bit's enable.
      if (!lshd_req_valid_q) begin
        lshd_req_tag_q   <= fe_tail_q;
        lshd_req_index_q <= seq_tri;
      end
      if (fs_alloc) lshd_req_valid_q <= 1'b1;
      else if (lshd_req_ready_i) lshd_req_valid_q <= 1'b0;
      if (lshd_take) begin
        lmat_req_valid_q <= 1'b1;
        lmat_req_tag_q   <= lshd_rsp_tag_i;
        lmat_req_index_q <= lshd_rsp_error_i ? 32'd0 : lshd_rsp_data_i[MatLsb +: 32];
      end else if (lmat_req_ready_i) begin
        lmat_req_valid_q <= 1'b0;
      end
      ns_tag1_q <= lmat_rsp_tag_i;
      ns_tag_q  <= ns_tag1_q;
    end
  end

  // The entries' payload (no reset: written before it is read). The tail entry is free unless
  // the ring is full, so the lane's copy is written into it in every cycle the ring has room,
  // allocated or not (the enables are the tail's decode, not the sequencer's step); the
  // allocation's cycle writes last. The ray and its weight are written a cycle later, into the
  // tail of the cycle before (fe_rw_*_q): they come from the block RAMs' register a cycle after
  // the rest (the lit board routed at 6799b81, seed 2: the block RAM's read through the lane's
  // select into fe_ray_q and fe_w_q, -2.57 and -2.77 ns). An entry is not read in the cycle
  // after its allocation (FeRwLate_A: it waits for its shading and material reads).
  logic              fe_rw_we_q;
  logic [FetchW-1:0] fe_rw_tail_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) fe_rw_we_q <= 1'b0;
    else fe_rw_we_q <= fe_room;
  end
  always_ff @(posedge clk_i) fe_rw_tail_q <= fe_tail_q;
  always_ff @(posedge clk_i) begin
    if (fe_room) begin
      fe_ln_q[fe_tail_q]    <= {fs_slot_q, fs_lane};
      fe_depth_q[fe_tail_q] <= depth_q[fs_slot_q*DepthW +: DepthW];
      fe_last_q[fe_tail_q] <= fs_last;
      fe_tri_q[fe_tail_q]  <= seq_tri;
      fe_t_q[fe_tail_q]    <= seq_t;
      fe_dz_q[fe_tail_q]   <= seq_dz;
    end
    if (fe_rw_we_q) begin
      fe_ray_q[fe_rw_tail_q] <= seq_ray;
      fe_w_q[fe_rw_tail_q]   <= seq_w;
    end
    if (lshd_take) fe_n_q[lshd_rsp_tag_i] <= lshd_rsp_error_i ? '0 : lshd_rsp_data_i[NrmLsb +: 3*W];
    if (lmat_take) begin
      fe_kd_q[lmat_rsp_tag_i]  <= lmat_rsp_error_i ? '0 : rgb_field(lmat_rsp_data_i, 0);
      fe_ks_q[lmat_rsp_tag_i]  <= lmat_rsp_error_i ? '0 : rgb_field(lmat_rsp_data_i, KsLsb);
      fe_ior_q[lmat_rsp_tag_i] <= lmat_ior;
      fe_mir_q[lmat_rsp_tag_i] <= lmat_rsp_error_i ? '0 : lmat_rsp_data_i[MirLsb +: W];
      fe_tr_q[lmat_rsp_tag_i]  <= lmat_rsp_error_i ? '0 : lmat_rsp_data_i[TrLsb +: W];
      fe_eta_q[lmat_rsp_tag_i] <= lmat_eta;
    end
    if (ns_valid) fe_ns_q[ns_tag_q] <= ns_val;
  end

  ////////////////////////////////
  // Lighting (rc_hit_light)    //
  ////////////////////////////////

  // The tag through rc_hit_light: {start triangle, depth, primary, last, slot, lane} (the
  // slot's depth does not change while its packet is lit).
  localparam int unsigned HlTagW = 32 + DepthW + 1 + 1 + LaneW;
  // The ring's head entry (a distributed-RAM read) goes into a one-entry queue (u_hl_q, hl_*)
  // before rc_hit_light, whose input registers are across the die: the read ends at a register
  // here. The queue takes an entry while it is empty (fe_pop); rc_hit_light takes at most one
  // hit per Period cycles, so the queue's cycle between two entries costs nothing.
  localparam int unsigned HlQW = HlTagW + 1 + 7 * W + 2 * W + 3 * W + 5 * W + 6 * W + ExpB;
  logic              fe_valid, fe_pop;
  logic [LaneW-1:0]  fe_head_ln;
  logic [DepthW-1:0] fe_head_depth;
  logic              hl_valid, hl_ready, hl_last, hq_count;
  logic [HlTagW-1:0] hl_tag;
  logic [7*W-1:0]    hl_ray;
  logic [W-1:0]      hl_t, hl_dz, hl_eta, hl_ior, hl_w, hl_mir, hl_tr;
  logic [3*W-1:0]    hl_n, hl_kd, hl_ks;
  logic [ExpB-1:0]   hl_ns;
  assign fe_valid      = fe_count_q != '0 && fe_done_q[fe_head_q];
  assign fe_pop        = fe_valid && !hq_count;
  assign fe_head_ln    = fe_ln_q[fe_head_q];
  // The entry's depth is copied from its slot's at allocation (it does not change until the
  // slot's next packet is sent, after its lighting), so the head's read is one distributed-RAM
  // read, not that and the slot's select after it (the lit board routed at 6799b81, seed 2:
  // fe_head_q through both into u_hl_q, -1.47 ns).
  assign fe_head_depth = fe_depth_q[fe_head_q];
  rc_fifo #(
    .Width   (HlQW),
    .Depth   (1),
    .MemArray(1'b0)
  ) u_hl_q (
    .clk_i,
    .rst_ni,
    .push_i (fe_pop),
    .data_i ({fe_tri_q[fe_head_q], fe_head_depth, fe_head_depth == '0, fe_last_q[fe_head_q],
              fe_head_ln, fe_last_q[fe_head_q], fe_ray_q[fe_head_q], fe_t_q[fe_head_q],
              fe_dz_q[fe_head_q], fe_eta_q[fe_head_q], fe_ior_q[fe_head_q], fe_w_q[fe_head_q],
              fe_mir_q[fe_head_q], fe_tr_q[fe_head_q], fe_n_q[fe_head_q], fe_kd_q[fe_head_q],
              fe_ks_q[fe_head_q], fe_ns_q[fe_head_q]}),
    .valid_o(hl_valid),
    .ready_i(hl_ready),
    .data_o ({hl_tag, hl_last, hl_ray, hl_t, hl_dz, hl_eta, hl_ior, hl_w, hl_mir, hl_tr, hl_n,
              hl_kd, hl_ks, hl_ns}),
    .count_o(hq_count)
  );

  // The ring's room is a register, loaded with the next count's compare (the lit board routed
  // at 6799b81, seed 2: fe_count_q's compare through the sequencer's step, -1.57 ns).
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fe_head_q  <= '0;
      fe_tail_q  <= '0;
      fe_count_q <= '0;
      fe_done_q  <= '0;
      fe_room    <= 1'b1;
    end else begin
      if (fs_alloc) fe_tail_q <= fe_tail_q + 1'b1;
      if (fe_pop) fe_head_q <= fe_head_q + 1'b1;
      fe_count_q <= fe_count_q + (FetchW + 1)'(fs_alloc) - (FetchW + 1)'(fe_pop);
      fe_room    <= fe_pop ||
                    (fe_count_q != (FetchW + 1)'(FetchEntries) &&
                     !(fs_alloc && fe_count_q == (FetchW + 1)'(FetchEntries - 1)));
      for (int e = 0; e < FetchEntries; e++) begin
        if (ns_valid && ns_tag_q == FetchW'(e)) fe_done_q[e] <= 1'b1;
        else if (fe_pop && fe_head_q == FetchW'(e)) fe_done_q[e] <= 1'b0;
      end
    end
  end

  logic              geo_valid, geo_ready, geo_mirror, geo_refract;
  logic [HlTagW-1:0] geo_tag;
  logic [3*W-1:0]    geo_p, geo_r, geo_refr;
  logic [W-1:0]      geo_w_mirror, geo_w_refract;
  // The light unit's geometry records (hg_*) pass a one-entry queue here (u_geo_q, geo_*): the
  // light unit's geometry FIFO is across the die from the decision and the children's
  // registers. The queue takes a record while it is empty (its count, a register, is the light
  // unit's ready); records come at most one per rc_hit_light period.
  localparam int unsigned GeoQW = HlTagW + 11 * W + 2;
  logic              hg_valid, hg_mirror, hg_refract, gq_count;
  logic [HlTagW-1:0] hg_tag;
  logic [3*W-1:0]    hg_p, hg_r, hg_refr;
  logic [W-1:0]      hg_w_mirror, hg_w_refract;
  rc_fifo #(
    .Width   (GeoQW),
    .Depth   (1),
    .MemArray(1'b0)
  ) u_geo_q (
    .clk_i,
    .rst_ni,
    .push_i (hg_valid && !gq_count),
    .data_i ({hg_tag, hg_p, hg_r, hg_refr, hg_w_mirror, hg_w_refract, hg_mirror, hg_refract}),
    .valid_o(geo_valid),
    .ready_i(geo_ready),
    .data_o ({geo_tag, geo_p, geo_r, geo_refr, geo_w_mirror, geo_w_refract, geo_mirror,
              geo_refract}),
    .count_o(gq_count)
  );
  // The light unit's samples (hk_*) pass a one-entry queue here (u_lt_q, lt_*): the unit's
  // output FIFO is across the die, and its pop would otherwise wait for lt_ready, which is made
  // here. The queue takes a sample while it is empty (its count, a register, is the unit's
  // ready); samples come at most one per Period cycles.
  localparam int unsigned LtQW = HlTagW + LightW + 3 + 7 * W + 6 * FW;
  logic              hk_valid, hk_lane_last, hk_light_last, hk_present, ltq_count;
  logic [HlTagW-1:0] hk_tag;
  logic [LightW-1:0] hk_light;
  logic [3*W-1:0]    hk_org, hk_dir;
  logic [W-1:0]      hk_t_hi;
  logic [3*FW-1:0]   hk_term, hk_amb;
  logic              lt_valid, lt_ready, lt_take;
  logic [HlTagW-1:0] lt_tag;
  logic [LightW-1:0] lt_light;
  logic              lt_lane_last, lt_light_last, lt_present;
  logic [3*W-1:0]    lt_org, lt_dir;
  logic [W-1:0]      lt_t_hi;
  logic [3*FW-1:0]   lt_term, lt_amb;
  rc_fifo #(
    .Width   (LtQW),
    .Depth   (1),
    .MemArray(1'b0)
  ) u_lt_q (
    .clk_i,
    .rst_ni,
    .push_i (hk_valid && !ltq_count),
    .data_i ({hk_tag, hk_light, hk_lane_last, hk_light_last, hk_present, hk_org, hk_dir, hk_t_hi,
              hk_term, hk_amb}),
    .valid_o(lt_valid),
    .ready_i(lt_ready),
    .data_o ({lt_tag, lt_light, lt_lane_last, lt_light_last, lt_present, lt_org, lt_dir, lt_t_hi,
              lt_term, lt_amb}),
    .count_o(ltq_count)
  );

  rc_hit_light #(
    .ExpW     (ExpW),
    .FracW    (FracW),
    .TagW     (HlTagW),
    .MaxLights(MaxLights),
    .Period   (LightPeriod)
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
    .tag_i           (hl_tag),
    .last_i          (hl_last),
    .org_i           (hl_ray[0 +: 3*W]),
    .dir_i           (hl_ray[3*W +: 3*W]),
    .inv_len_i       (hl_ray[6*W +: W]),
    .t_i             (hl_t),
    .dz_i            (hl_dz),
    .n_i             (hl_n),
    .eta_enter_i     (hl_eta),
    .eta_leave_i     (hl_ior),
    .w_i             (hl_w),
    .mirror_i        (hl_mir),
    .transmit_i      (hl_tr),
    .kd_i            (hl_kd),
    .ks_i            (hl_ks),
    .ns_i            (hl_ns),
    .geo_valid_o     (hg_valid),
    .geo_ready_i     (!gq_count),
    .geo_tag_o       (hg_tag),
    .geo_p_o         (hg_p),
    .geo_r_o         (hg_r),
    .geo_refr_o      (hg_refr),
    .geo_w_mirror_o  (hg_w_mirror),
    .geo_w_refract_o (hg_w_refract),
    .geo_mirror_o    (hg_mirror),
    .geo_refract_o   (hg_refract),
    .lt_valid_o      (hk_valid),
    .lt_ready_i      (!ltq_count),
    .lt_tag_o        (hk_tag),
    .lt_light_o      (hk_light),
    .lt_lane_last_o  (hk_lane_last),
    .lt_light_last_o (hk_light_last),
    .lt_org_o        (hk_org),
    .lt_present_o    (hk_present),
    .lt_dir_o        (hk_dir),
    .lt_t_hi_o       (hk_t_hi),
    .lt_term_o       (hk_term),
    .lt_amb_o        (hk_amb)
  );

  ////////////////////////////////////////////
  // Children: mirror and refraction packets //
  ////////////////////////////////////////////

  // A packet's geometry records come in lane order, its last hit's flagged; each makes its
  // lane's mirror and refraction rays while the packet's depth is below max_bounces_i.
  logic              geo_take, geo_last, geo_deeper;
  logic [LaneW-1:0]  geo_ln;
  logic [SlotW-1:0]  geo_slot;
  logic [1:0]        geo_lane;
  logic [31:0]       geo_tri;
  logic [DepthW-1:0] geo_depth;
  child_t            gm_q, gr_q, gm, gr;
  assign {geo_tri, geo_last, geo_ln} = {geo_tag[HlTagW-1 -: 32], geo_tag[LaneW],
                                        geo_tag[LaneW-1:0]};
  assign geo_slot   = geo_ln[LaneW-1:2];
  assign geo_lane   = geo_ln[1:0];
  assign geo_depth  = geo_tag[LaneW + 2 +: DepthW];
  // max_bounces_i registered here (quasi-static): it comes from the board's register file,
  // across the die, into the children's enables.
  logic [DepthW-1:0] max_bounces_q;
  always_ff @(posedge clk_i) max_bounces_q <= max_bounces_i;
  assign geo_deeper = geo_depth < max_bounces_q;
  // The decision waits while the sequencer still issues the packet's misses (it reads the
  // packet's weights, which the decision replaces), and a last record decides from its second
  // cycle in the queue on (gq_old_q: the geometry candidate's registers are its by then).
  logic gq_old_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) gq_old_q <= 1'b0;
    else gq_old_q <= geo_valid && !geo_take;
  end
  assign geo_ready  = !dq_q && (!geo_last || (gq_old_q && dec_room &&
                                              !(fs_busy_q && fs_slot_q == geo_slot)));
  assign geo_take   = geo_valid && geo_ready;
  assign dec_geo    = geo_take && geo_last;
  assign geo_end    = geo_valid && geo_last;

  always_comb begin
    gm = gm_q;
    gr = gr_q;
    gm.mirror = 1'b1;
    gr.mirror = 1'b0;
    gm.depth  = geo_depth + 1'b1;
    gr.depth  = geo_depth + 1'b1;
    // A loop over the lanes with constant part-selects: a select at a computed offset becomes a
    // barrel shifter over the whole record in synthesis. A lane's rays (origin, start triangle,
    // directions and weights) are written whenever its record is offered (geo_valid), whether
    // or not it makes a ray: a lane without its ray is never read, so the two packets' origins
    // and start triangles are the same registers (synthesis merges them), and the wide enables
    // wait neither for geo_ready nor for the depth's compare and the material's flags. The
    // geometry FIFO holds a record until the take, records come in order, and the decision
    // reads the packets before (in dq_q, a cycle in which no record is taken). Only the masks
    // (and with them the mirror flag and depth) wait for the take and the flags.
    for (int r = 0; r < 4; r++) begin
      if (geo_lane == 2'(r) && geo_valid) begin
        gm.org[r*3*W +: 3*W]   = geo_p;
        gm.stri[r*32 +: 32]    = geo_tri;
        gm.dir[r*3*W +: 3*W]   = geo_r;
        gm.w[r*W +: W]         = geo_w_mirror;
        gr.dir[r*3*W +: 3*W]   = geo_refr;
        gr.w[r*W +: W]         = geo_w_refract;
      end
      if (geo_lane == 2'(r) && geo_valid && geo_deeper && geo_mirror) gm.mask[r] = 1'b1;
      if (geo_lane == 2'(r) && geo_valid && geo_deeper && geo_refract) gr.mask[r] = 1'b1;
    end
    gr.org  = gm.org;
    gr.stri = gm.stri;
  end

  // The packets' heads {mask, mirror, depth} and rays {org, dir, w, stri}, as child_t packs them.
  localparam int unsigned HeadW = 5 + DepthW;
  localparam int unsigned RaysW = 24 * W + 4 * W + 128;
  logic [HeadW-1:0] gm_head_q, gr_head_q;
  logic [RaysW-1:0] gm_rays_q, gr_rays_q;
  assign gm_q = {gm_head_q, gm_rays_q};
  assign gr_q = {gr_head_q, gr_rays_q};
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      gm_head_q <= '0;
      gr_head_q <= '0;
    end else if (geo_take) begin
      gm_head_q <= gm[HeadW+RaysW-1 -: HeadW];
      gr_head_q <= gr[HeadW+RaysW-1 -: HeadW];
    end else if (dq_q && dq_geo_q) begin  // the decision took the last record's packets
      gm_head_q[HeadW-1 -: 4] <= 4'd0;
      gr_head_q[HeadW-1 -: 4] <= 4'd0;
    end
  end
  always_ff @(posedge clk_i) begin
    gm_rays_q <= gm[RaysW-1:0];
    gr_rays_q <= gr[RaysW-1:0];
  end

  // The decision: the mirror packet becomes the slot's current packet and the refraction packet
  // goes onto its stack; without a mirror packet the refraction packet is sent, or the stack's
  // top; with neither the tree is done. It takes two cycles: in the first (dec) the slot,
  // whether it has packets, its stack pointer and its stack addresses are registered (dq_*,
  // stk_*); in the second (dq_q) the decision is carried out: a packet is sent or the stack's
  // top read, the stack pointer and the tree's end written (the geometry, held in that cycle,
  // leaves the last record's packets in gm_q and gr_q). A pop sends its packet in the cycle
  // after (pop_q). No decision is made in the second cycle nor in a pop's (dec_room), so the
  // tree packet queue, empty at the decision, has room for the packet.
  localparam int unsigned StkDepth = Slots * MaxBounces;
  localparam int unsigned ChildW   = 4 + 1 + DepthW + 24 * W + 4 * W + 128;  // child_t's bits
  localparam int unsigned StkIdxW  = (StkDepth > 1) ? $clog2(StkDepth) : 1;
  logic              dec, dec_now, dec_push, dec_pop, dec_done, dec_m_any, dec_r_any;
  logic [SlotW-1:0]  dec_slot, pop_slot_q;
  child_t            dec_r, stk_top;
  logic [DepthW-1:0] dq_sp_q;
  assign dec       = dec_geo || dec_seq || (fq_pop && fq_work == 4'd0);
  assign dec_slot  = dec_geo ? geo_slot : dec_seq ? fs_slot_q : fq_slot;
  // Outside dec_geo there are no packets: a packet without rays is neither sent nor pushed.
  assign dec_m_any = dec_geo && gm.mask != 4'd0;
  assign dec_r_any = dec_geo && gr.mask != 4'd0;

  // The slot's stack pointer and its stack addresses are registered in the first cycle too:
  // a pointer is written only in a decision's second cycle, in which none is made, so the
  // registered one is the pointer of the second (DqSp_A). Each candidate slot's are made from
  // registers, the decision's kind chooses among them, and the block RAM's address and read
  // enable come from flip-flops.
  logic               dq_geo_q, dq_now_q, dq_push_q, dq_msel_q, stk_re_q;
  logic [SlotW-1:0]   dq_slot_q;
  logic [DepthW-1:0]  dec_sp;
  logic [StkIdxW-1:0] dec_wa, dec_ra, stk_waddr_q, stk_raddr_q;
  // A slot's candidate {stack pointer, write address (the next entry), read address (the
  // top)}; each candidate slot's is registered, and the decision's kind chooses among them.
  // The addresses slot * MaxBounces + p and that less one are AND-OR tables over the slot and
  // its pointer's value, not a multiplier and two carry chains after the pointer's select (the
  // lit board routed at 6799b81, seed 2: the geometry's and the sequencer's candidates, 10
  // cells, -0.61 and -0.88 ns).
  localparam int unsigned CandW = DepthW + 2 * StkIdxW;
  function automatic logic [CandW-1:0] stk_cand(input logic [SlotW-1:0]        slot,
                                                input logic [Slots*DepthW-1:0] sp);
    logic [DepthW-1:0]  p;
    logic [StkIdxW-1:0] wa, ra;
    p  = '0;
    wa = '0;
    ra = '0;
    for (int s = 0; s < Slots; s++) begin
      p = p | ({DepthW{slot == SlotW'(s)}} & sp[s*DepthW +: DepthW]);
      for (int q = 0; q < (1 << DepthW); q++) begin
        wa = wa | ({StkIdxW{slot == SlotW'(s) && sp[s*DepthW +: DepthW] == DepthW'(q)}} &
                   StkIdxW'(s * MaxBounces + q));
        ra = ra | ({StkIdxW{slot == SlotW'(s) && sp[s*DepthW +: DepthW] == DepthW'(q)}} &
                   StkIdxW'(s * MaxBounces + q - 1));
      end
    end
    stk_cand = {p, wa, ra};
  endfunction
  logic [CandW-1:0] cand_geo_q, cand_seq_q, cand_fq_q;
  always_ff @(posedge clk_i) begin
    // The geometry candidate is loaded in every cycle from the record in the geometry queue: a
    // last record decides from its second cycle there, and no decision changes its slot's
    // pointer while the slot's packet is lit (GeoSp_A).
    cand_geo_q <= stk_cand(geo_slot, sp_q);
    // The sequencer's is the fetch head's, copied at the pop that gives the sequencer its slot:
    // no decision changes that slot's pointer while the sequencer holds it, so at a step the
    // register is the slot's (SeqSp_A).
    if (fq_pop) cand_seq_q <= cand_fq_q;
    // The fetch head's, as the slot enters the head register (from the FIFO's slot): a slot
    // waiting for its fetch has no decision, so its pointer does not change until it leaves
    // the head (FqSp_A).
    if (fr_pop) cand_fq_q <= stk_cand(fr_slot, sp_q);
  end
  assign {dec_sp, dec_wa, dec_ra} = dec_geo ? cand_geo_q : dec_seq ? cand_seq_q : cand_fq_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      dq_q     <= 1'b0;
      stk_re_q <= 1'b0;
    end else begin
      dq_q     <= dec;
      stk_re_q <= dec && !(dec_m_any || dec_r_any) && dec_sp != '0;
    end
  end
  always_ff @(posedge clk_i) begin
    if (dec) begin
      dq_geo_q    <= dec_geo;
      dq_slot_q   <= dec_slot;
      dq_now_q    <= dec_m_any || dec_r_any;
      dq_push_q   <= dec_m_any && dec_r_any;
      dq_msel_q   <= dec_m_any;
      dq_sp_q     <= dec_sp;
      stk_waddr_q <= dec_wa;
      stk_raddr_q <= dec_ra;
    end
  end
  always_comb begin
    dec_r = gr_q;
    if (!dq_geo_q) dec_r.mask = '0;
  end
  assign dec_now   = dq_q && dq_now_q;
  assign dec_push  = dq_q && dq_push_q;
  assign dec_pop   = stk_re_q;  // dq_q && !dq_now_q && dq_sp_q != 0
  assign dec_done  = dq_q && !dq_now_q && dq_sp_q == '0;

  // The stacks: a slot's MaxBounces entries from slot * MaxBounces; a word is never read in the
  // cycle it is written (one decision at a time).
  rc_ram #(
    .Width (ChildW),
    .Depth (StkDepth),
    .OutReg(1'b0)
  ) u_stack (
    .clk_i,
    .we_i   (dec_push),
    .waddr_i(stk_waddr_q),
    .wdata_i(dec_r),
    .re_i   (dec_pop),
    .raddr_i(stk_raddr_q),
    .rdata_o(stk_top)
  );

  // A popped packet's slot takes its mask, mirror flag and depth a cycle after it is sent
  // (pop2_q), from a register behind the block RAM: the slot's next write, fetch or decision
  // is far later, and no decision is carried out in that cycle (the tree packet queue holds
  // the packet).
  // pop_q in two kept copies: copy 0 for the sequencer and the slots (dec_room, snd), copy 1
  // (pop_sel_q) for the sent packet's select, whose 800 multiplexers are across the die from
  // the sequencer.
  logic              pop_sel_q;
  rc_reg_copies #(
    .Width   (1),
    .Copies  (2),
    .HasReset(1'b1)
  ) u_pop_q (
    .clk_i,
    .rst_ni,
    .d_i   (dec_pop),
    .q_o   ({pop_sel_q, pop_q})
  );
  logic              pop2_q, pop2_mirror_q;
  logic [SlotW-1:0]  pop2_slot_q;
  logic [3:0]        pop2_mask_q;
  logic [DepthW-1:0] pop2_depth_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pop_slot_q <= '0;
      pop2_q     <= 1'b0;
    end else begin
      pop2_q <= pop_q;
      if (dec_pop) pop_slot_q <= dq_slot_q;
    end
  end
  always_ff @(posedge clk_i) begin
    if (pop_q) begin
      pop2_slot_q  <= pop_slot_q;
      pop2_mask_q  <= stk_top.mask;
      pop2_mirror_q <= stk_top.mirror;
      pop2_depth_q <= stk_top.depth;
    end
  end

  // A packet of the tree is sent: it becomes its slot's current packet.
  logic             snd;
  logic [SlotW-1:0] snd_slot;
  child_t           snd_pkt;
  // The slot's registers take a sent packet's mask, mirror flag and depth (sw_*): a decision's
  // packet at once, a popped one a cycle after it is sent.
  logic              sw, sw_mirror;
  logic [SlotW-1:0]  sw_slot;
  logic [3:0]        sw_mask;
  logic [DepthW-1:0] sw_depth;
  assign snd      = dec_now || pop_q;
  assign snd_slot = pop_q ? pop_slot_q : dq_slot_q;
  // Which of the decision's packets is sent is registered in its first cycle (dq_msel_q, the
  // mirror packet's: DecSel_A), so the slots' wide writes do not wait for dq_geo_q's masks.
  assign snd_pkt  = pop_sel_q ? stk_top : dq_msel_q ? gm_q : gr_q;
  assign sw      = dec_now || pop2_q;
  assign sw_slot = pop2_q ? pop2_slot_q : dq_slot_q;
  always_comb begin
    if (pop2_q) {sw_mask, sw_mirror, sw_depth} = {pop2_mask_q, pop2_mirror_q, pop2_depth_q};
    else if (dq_msel_q) {sw_mask, sw_mirror, sw_depth} = {gm_q.mask, gm_q.mirror, gm_q.depth};
    else {sw_mask, sw_mirror, sw_depth} = {gr_q.mask, gr_q.mirror, gr_q.depth};
  end
  assign bq_push  = snd;
  assign bq_wdata = {snd_pkt.depth == DepthW'(1), snd_pkt.mirror, snd_pkt.mask, snd_pkt.org,
                     snd_pkt.dir, snd_pkt.w, snd_pkt.stri, snd_slot};

  /////////////////////////////
  // Light samples and terms //
  /////////////////////////////

  // The add queue: ambient terms and miss terms on their way to the sums, applied in a cycle
  // without a reached shadow ray (which adds at once).
  localparam int unsigned AqW = LaneW + 3 * FW;
  logic             aq_push, aq_valid, aq_pop;
  logic [AqW-1:0]   aq_wdata, aq_rdata;
  logic [$clog2(AddQ + 1)-1:0] aq_count;
  logic [$clog2(MissL + 1)-1:0] mi_count_q;
  logic             mo_valid;
  logic [3*FW-1:0]  mo_term;
  logic [LaneW-1:0] mo_ln;
  logic [LaneW-1:0] aq_ln;
  logic [3*FW-1:0]  aq_term;

  rc_fifo #(
    .Width   (AqW),
    .Depth   (AddQ),
    .MemArray(1'b1)
  ) u_add_q (
    .clk_i,
    .rst_ni,
    .push_i (aq_push),
    .data_i (aq_wdata),
    .valid_o(aq_valid),
    .ready_i(aq_pop),
    .data_o (aq_rdata),
    .count_o(aq_count)
  );
  assign {aq_ln, aq_term} = aq_rdata;
  logic rs_q;  // a reached shadow ray's term is read in this cycle (added two cycles later)
  assign aq_pop = aq_valid && !cw_reached_ln && !(cw_cur_ln && cw_d0);  // u_lanes's add port

  // The miss term: fix(bg_c * w) per channel, MissL cycles; issued only while the add queue has
  // room for it beside the ones in flight and an ambient term.
  // pm_q = aq_count + mi_count_q, counted beside them so that the room is a compare of a
  // register with a constant. A miss term's push into the add queue leaves the sum as it is (one
  // in flight less, one queued more), so the count adds the issues and the ambient terms and
  // takes the pops: a sample is not taken while a miss term leaves (lt_ready), and the queue's
  // pushes are exactly those two (the lit board routed at 6799b81, seed 2: sp_free_any through
  // the sample's take and four increments into pm_q, -2.33 ns).
  localparam int unsigned PmW = $clog2(AddQ + MissL + 1);
  logic [PmW-1:0] pm_q;
  assign mi_ok = 32'(pm_q) + 2 <= AddQ;
  // Channel-serial: one multiplier and one conversion take the three channels in consecutive
  // cycles (mi_ph_q 1, 2, 3: red, green, blue), from the second cycle after the issue (the
  // weight, seq_w, comes the cycle after it and is held in mi_w_q); a miss may issue while the
  // second channel enters (mi_free: its first channel then enters after the last one), so one
  // per three cycles. The results leave in the same order, three consecutive ones per miss
  // (mo_ch_q counts them), and the term goes with the third.
  logic [1:0]   mi_ph_q, mo_ch_q;
  logic         mi_issue_q;  // a miss issued in the cycle before: its weight is on seq_w
  logic [W-1:0] mi_w_q;      // the weight, registered off the lane records' register
  logic [W-1:0] mi_bg;
  logic         mm_valid, mf_valid;
  logic [W-1:0] mm_res;
  logic [FW-1:0] mf_out, mo_r_q, mo_g_q;
  assign mi_free = !mi_issue_q && mi_ph_q != 2'd1;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      mi_issue_q <= 1'b0;
      mi_ph_q    <= 2'd0;
      mo_ch_q    <= 2'd0;
    end else begin
      mi_issue_q <= mi_issue;
      if (mi_issue_q) mi_ph_q <= 2'd1;
      else if (mi_ph_q != 2'd0) mi_ph_q <= mi_ph_q + 2'd1;  // 3 wraps to 0
      if (mf_valid) mo_ch_q <= (mo_ch_q == 2'd2) ? 2'd0 : mo_ch_q + 2'd1;
    end
  end
  always_ff @(posedge clk_i) begin
    if (mi_issue_q) mi_w_q <= seq_w;
    if (mf_valid && mo_ch_q == 2'd0) mo_r_q <= mf_out;
    if (mf_valid && mo_ch_q == 2'd1) mo_g_q <= mf_out;
  end
  always_comb begin
    unique case (mi_ph_q)
      2'd2:    mi_bg = bg_i[1*W +: W];
      2'd3:    mi_bg = bg_i[2*W +: W];
      default: mi_bg = bg_i[0*W +: W];
    endcase
  end
  rc_fp_mul #(
    .ExpW (ExpW),
    .FracW(FracW)
  ) u_miss_mul (
    .clk_i,
    .rst_ni,
    .valid_i(mi_ph_q != 2'd0),
    .a_i    (mi_bg),
    .b_i    (mi_w_q),
    .valid_o(mm_valid),
    .res_o  (mm_res)
  );
  rc_fp_to_fix #(
    .ExpW   (ExpW),
    .FracW  (FracW),
    .FixBits(rc_pkg::LightFixedBits),
    .Stages (2)
  ) u_miss_fix (
    .clk_i,
    .rst_ni,
    .valid_i(mm_valid),
    .x_i    (mm_res),
    .valid_o(mf_valid),
    .out_o  (mf_out)
  );
  // A miss's term leaves MissL cycles after its issue: mo_valid is the issue through a shift
  // register (mi_sr_q, with reset), a flip-flop beside the sample take and the add queue's
  // counts instead of the conversion's valid and mo_ch_q's compare (MoValid_A).
  logic [MissL-1:0] mi_sr_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) mi_sr_q <= '0;
    else mi_sr_q <= {mi_sr_q[MissL-2:0], mi_issue};
  end
  assign mo_valid = mi_sr_q[MissL-1];
  assign mo_term  = {mf_out, mo_g_q, mo_r_q};
  rc_delay #(
    .Width (LaneW),
    .Cycles(MissL)
  ) u_miss_tag (
    .clk_i,
    .data_i({fs_slot_q, fs_lane}),
    .data_o(mo_ln)
  );

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) mi_count_q <= '0;
    else mi_count_q <= mi_count_q + $bits(mi_count_q)'(mi_issue) - $bits(mi_count_q)'(mo_valid);
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) pm_q <= '0;
    else pm_q <= pm_q + PmW'(mi_issue) + PmW'(lt_amb_push) - PmW'(aq_pop);
  end

  // A light's samples: the ambient term at light 0 (to the add queue, after a miss term in the
  // same cycle), the light's shadow packet assembled from the present ones.
  logic              shp_q;  // a closed shadow packet is pushed (a cycle after its close)
  logic [LaneW-1:0]  lt_ln;
  logic [SlotW-1:0]  lt_slot;
  logic [1:0]        lt_lane;
  logic [31:0]       lt_tri;
  logic              lt_d0, lt_close, lt_amb_push;
  assign {lt_tri, lt_d0, lt_ln} = {lt_tag[HlTagW-1 -: 32], lt_tag[LaneW + 1], lt_tag[LaneW-1:0]};
  assign lt_slot     = lt_ln[LaneW-1:2];
  assign lt_lane     = lt_ln[1:0];
  assign lt_ready    = !shq_count && !shp_q && sp_free_any && !mo_valid &&
                       32'(pm_q) + 1 <= AddQ;
  assign lt_take     = lt_valid && lt_ready;
  assign lt_close    = lt_take && lt_lane_last;
  assign lt_amb_push = lt_take && lt_light == '0;
  assign aq_push     = mo_valid || lt_amb_push;
  assign aq_wdata    = mo_valid ? {mo_ln, mo_term} : {lt_ln, lt_amb};

  // The packet being assembled. A present sample's fields are loaded into its lane whenever it
  // is offered (lt_valid), not only when taken: the light unit's output holds it until the
  // take, samples come in order, and the packet before was pushed from these registers before
  // (so the wide enables do not wait for lt_ready). Only the mask waits for the take. The
  // closed packet is pushed a cycle after its last sample (shp_q), from the registers: no
  // sample is taken in that cycle (lt_ready), nor in the next (the queue is full).
  logic [3:0]        as_mask_q, as_mask;
  logic [12*W-1:0]   as_org_q, as_dir_q;
  logic [4*W-1:0]    as_t_hi_q;
  logic [127:0]      as_tri_q;
  logic [12*FW-1:0]  as_term_q;
  logic              sh_close;
  logic [3:0]        shp_mask_q;
  logic              shp_d0_q;
  logic [LightW-1:0] shp_light_q;
  logic [SlotW-1:0]  shp_slot_q;
  logic [SpW-1:0]    shp_sp_q;
  logic [ShadowPackets-1:0] shp_hot_q;
  always_comb begin
    as_mask = as_mask_q;
    for (int r = 0; r < 4; r++) begin
      if (lt_lane == 2'(r) && lt_take && lt_present) as_mask[r] = 1'b1;
    end
  end
  assign sh_close  = lt_close && as_mask != 4'd0;
  assign shq_push  = shp_q;
  assign shq_wdata = {shp_mask_q, as_org_q, as_dir_q, as_t_hi_q, as_tri_q, shp_d0_q, shp_light_q,
                      shp_slot_q, shp_sp_q};

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      as_mask_q <= '0;
      shp_q     <= 1'b0;
    end else begin
      if (lt_take) as_mask_q <= lt_lane_last ? 4'd0 : as_mask;
      shp_q <= sh_close;
    end
  end
  always_ff @(posedge clk_i) begin
    for (int r = 0; r < 4; r++) begin  // constant part-selects, as for the tree's packets
      if (lt_lane == 2'(r) && lt_valid && lt_present) begin
        as_org_q[r*3*W +: 3*W]    <= lt_org;
        as_dir_q[r*3*W +: 3*W]    <= lt_dir;
        as_t_hi_q[r*W +: W]       <= lt_t_hi;
        as_tri_q[r*32 +: 32]      <= lt_tri;
        as_term_q[r*3*FW +: 3*FW] <= lt_term;
      end
    end
    // Loaded in every cycle (read only in the cycle after a close, shp_q): the mask as it is
    // at a close, whose sample is taken.
    shp_mask_q  <= as_mask_q | (lt_present ? 4'd1 << lt_lane : 4'd0);
    shp_d0_q    <= lt_d0;
    shp_light_q <= lt_light;
    shp_slot_q  <= lt_slot;
    shp_sp_q    <= sp_free;
    shp_hot_q   <= sp_free_hot;
  end

  // The shadow packets' entries.
  // A packet is freed in the cycle after its last ray's write (cwsf_q, registered with its
  // index): the write's pixel id selects its count, and the compare ends at a register
  // instead of at the busy bits' decode.
  logic                     cws_free, cwsf_q;
  logic [SpW-1:0]           cwsf_sp_q;
  logic [ShadowPackets-1:0] cwsf_hot;
  assign cws_free = cw_sh && sp_cnt_q[cw_sp] == 3'd1;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) cwsf_q <= 1'b0;
    else cwsf_q <= cws_free;
  end
  always_ff @(posedge clk_i) cwsf_sp_q <= cw_sp;
  rc_onehot #(.N(ShadowPackets), .IdxW(SpW)) u_cwsf_hot (.valid_i(cwsf_q), .idx_i(cwsf_sp_q),
                                                         .hot_o(cwsf_hot));
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      spb_q   <= '0;
    end else begin
      for (int k = 0; k < ShadowPackets; k++) begin  // decoded writes
        if (cwsf_hot[k]) spb_q[k] <= 1'b0;
        if (shq_push && shp_hot_q[k]) spb_q[k] <= 1'b1;
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (cw_sh) sp_cnt_q[cw_sp] <= sp_cnt_q[cw_sp] - 1'b1;
    if (shq_push) begin
      sp_cnt_q[shp_sp_q] <= rc_pkg::ray_count(shp_mask_q);
    end
  end

  // The shadow packets' terms, a word of four per packet: written at the packet's push (from
  // the assembly's registers), read at a reached ray's write, its lane's term registered a cycle
  // later (rs_q) and added in the cycle after (rs2_q). The word read belongs to a packet whose
  // rays are out and the word written to one whose rays are not yet, so a word is never read in
  // the cycle it is written.
  logic [12*FW-1:0] term_word;
  rc_ram #(
    .Width (12 * FW),
    .Depth (ShadowPackets),
    .OutReg(1'b0)
  ) u_terms (
    .clk_i,
    .we_i   (shq_push),
    .waddr_i(shp_sp_q),
    .wdata_i(as_term_q),
    .re_i   (cw_reached),
    .raddr_i(cw_sp),
    .rdata_o(term_word)
  );

  // The reached ray's lane, light and whether from a primary hit, for its add.
  logic [1:0]        rs_lane_q;
  logic              rs_d0_q, rs2_q, rs2_d0_q;
  logic [LightW-1:0] rs_light_q, rs2_light_q;
  logic [3*FW-1:0]   rs_term, rs_term_q;
  always_comb begin  // a multiplexer (an indexed part-select would multiply the index)
    unique case (rs_lane_q)
      2'd0:    rs_term = term_word[0*3*FW +: 3*FW];
      2'd1:    rs_term = term_word[1*3*FW +: 3*FW];
      2'd2:    rs_term = term_word[2*3*FW +: 3*FW];
      default: rs_term = term_word[3*3*FW +: 3*FW];
    endcase
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rs_q  <= 1'b0;
      rs2_q <= 1'b0;
    end else begin
      rs_q  <= cw_reached;
      rs2_q <= rs_q;
    end
  end
  always_ff @(posedge clk_i) begin
    if (cw_reached) begin
      rs_lane_q  <= cw_lane;
      rs_d0_q    <= core_fb_pixel[PixD0];
      rs_light_q <= core_fb_pixel[PixLight +: LightW];
    end
    if (rs_q) begin
      rs_term_q   <= rs_term;
      rs2_d0_q    <= rs_d0_q;
      rs2_light_q <= rs_light_q;
    end
  end

  ////////////////////////
  // The pixels' writes //
  ////////////////////////

  // Done slots: the lowest first, one slot's lanes at a time, one lane per cycle.
  logic [Slots-1:0] done_vec, dn_hot, dn_hot_q, fs_hot, lnp_hot, lnp1_hot, ev_hot;
  logic [Slots-1:0] wk_hot_q;  // a work event registered with its change, not yet counted
  logic             dn_any, dn_any_q;
  logic [SlotW-1:0] dn_idx, dn_idx_q;
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_fs_hot  (.valid_i(fs_busy_q),   .idx_i(fs_slot_q),
                                                  .hot_o(fs_hot));
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_lnp_hot (.valid_i(ln_add_pend), .idx_i(ln_add_slot),
                                                  .hot_o(lnp_hot));
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_lnp1_hot (.valid_i(ln_add_pend1),
                                                   .idx_i(ln_add_slot1), .hot_o(lnp1_hot));
  always_comb begin
    for (int s = 0; s < Slots; s++) begin
      // Not while the sequencer still issues the last packet's misses (their adds are counted
      // from the issue), nor while an add's sum is still to be written (ln_add_pend1,
      // ln_add_pend), nor with a work event not yet counted (ev_hot, wk_hot_q).
      done_vec[s] = busy_q[s] && td_q[s] && !fin_q[s] && wk_q[s*WkW +: WkW] == '0 &&
                    !ev_hot[s] && !wk_hot_q[s] && !fs_hot[s] && !lnp_hot[s] && !lnp1_hot[s];
    end
  end
  // Registered: a done slot stays done until its write starts (fin_q), which masks it at once.
  logic [Slots-1:0] done_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) done_q <= '0;
    else done_q <= done_vec;
  end
  rc_lowest #(
    .N   (Slots),
    .IdxW(SlotW)
  ) u_done (
    .req_i  (done_q & ~fin_q),
    .valid_o(dn_any),
    .idx_o  (dn_idx),
    .hot_o  (dn_hot)
  );
  // The pick, registered (dn_*_q): the pick's carry chain and the final write's read address
  // (fin_ln, into the lane records' block RAMs) are a cycle apart. A write lasts four cycles at
  // least, and its slot is masked (fin_q) from the cycle after it starts, so the pick a write
  // starts with is always a done slot not being written (DonePick_A).
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) dn_any_q <= 1'b0;
    else dn_any_q <= dn_any;
  end
  always_ff @(posedge clk_i) begin
    dn_idx_q <= dn_idx;
    dn_hot_q <= dn_hot;
  end

  localparam int unsigned OutW = 32 + 24 + 1 + 32 + 3 * W + MaxLights + 64;
  logic             fw_busy_q, fw_issue, fw_room, fw_free, fw_write;
  logic [SlotW-1:0] fw_slot_q;
  logic [1:0]       fw_lane_q;
  logic [LaneW-1:0] fw_ln;
  // The lane's write in three stages (st_*, st2_*, st3_*), the sums registered before their
  // bytes (rc_light_byte: two cycles).
  logic             st_valid_q, st_hit_q, st2_valid_q, st2_hit_q, st3_valid_q, st3_hit_q;
  logic [OutW-1:0]  st_rec_q, st2_rec_q, st3_rec_q;  // {pixel, rgb, hit, tri, t, u, v, lights,
                                                     //  bounce, refract}
  logic [3*SumW-1:0] st_sum_q;
  logic [2:0]       oq_count;
  logic             oq_valid;
  logic [OutW-1:0]  oq_wdata, oq_rdata;
  logic [2:0]       lb_valid;
  logic [23:0]      lb_rgb;

  assign fw_ln    = {fw_slot_q, fw_lane_q};
  // The room: fw_cnt_q counts the output queue's entries and the writes in its three stages
  // (FwCnt_A), so the room is a compare of a register with a constant.
  logic [2:0] fw_cnt_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) fw_cnt_q <= '0;
    else fw_cnt_q <= fw_cnt_q + 3'(fw_write) - 3'(oq_valid && fb_ready_i);
  end
  assign fw_room  = fw_cnt_q < 3'd4;
  assign fw_issue = fw_busy_q && fw_room;
  assign fw_write = fw_issue && pmask_q[fw_slot_q][fw_lane_q];
  assign fw_free  = fw_issue && fw_lane_q == 2'd3;

  // The lane's records (u_lanes) are read a cycle ahead: lane 0 of the slot chosen, the next
  // lane at an issue, else the lane again; so ln_fin_* always hold fw_ln's.
  logic [LaneW-1:0]     fin_ln;
  logic [31:0]          ln_fin_pixel, ln_fin_tri, ln_fin_btri, ln_fin_rtri;
  logic                 ln_fin_hit;
  logic [W-1:0]         ln_fin_t, ln_fin_u, ln_fin_v;
  logic [23:0]          ln_fin_rgb;
  logic [3*SumW-1:0]    ln_fin_sum;
  logic [MaxLights-1:0] ln_fin_lights;
  always_comb begin
    if (!fw_busy_q && dn_any_q) fin_ln = {dn_idx_q, 2'd0};
    else if (fw_issue) fin_ln = {fw_slot_q, fw_lane_q + 2'd1};
    else fin_ln = fw_ln;
  end

  for (genvar c = 0; c < 3; c++) begin : g_byte
    rc_light_byte #(
      .FixBits(rc_pkg::LightFixedBits),
      .SumW   (SumW)
    ) u_byte (
      .clk_i,
      .rst_ni,
      .valid_i(st_valid_q),
      .sum_i  (st_sum_q[c*SumW +: SumW]),
      .valid_o(lb_valid[c]),
      .byte_o (lb_rgb[c*8 +: 8])
    );
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fw_busy_q  <= 1'b0;
      fw_slot_q  <= '0;
      fw_lane_q  <= '0;
      st_valid_q  <= 1'b0;
      st2_valid_q <= 1'b0;
      st2_hit_q   <= 1'b0;
      st2_rec_q   <= '0;
      st3_valid_q <= 1'b0;
      st3_hit_q   <= 1'b0;
      st3_rec_q   <= '0;
    end else begin
      if (!fw_busy_q && dn_any_q) begin
        fw_busy_q <= 1'b1;
        fw_slot_q <= dn_idx_q;
        fw_lane_q <= '0;
      end else if (fw_issue) begin
        fw_lane_q <= fw_lane_q + 1'b1;
        if (fw_free) fw_busy_q <= 1'b0;
      end
      st_valid_q  <= fw_write;
      st2_valid_q <= st_valid_q;
      st3_valid_q <= st2_valid_q;
      if (st_valid_q) begin
        st2_hit_q <= st_hit_q;
        st2_rec_q <= st_rec_q;
      end
      if (st2_valid_q) begin
        st3_hit_q <= st2_hit_q;
        st3_rec_q <= st2_rec_q;
      end
    end
  end

  // The first stage loads in every cycle, without an enable (fw_write's fan-out): only a
  // write's (st_valid_q) goes on. A hit's colour is its sums' bytes, a miss's the core's write.
  always_ff @(posedge clk_i) begin
    st_hit_q <= ln_fin_hit;
    st_rec_q <= {ln_fin_pixel, ln_fin_rgb, ln_fin_hit, ln_fin_tri, ln_fin_t, ln_fin_u,
                 ln_fin_v, ln_fin_hit ? ln_fin_lights : '0, ln_fin_btri, ln_fin_rtri};
    st_sum_q <= ln_fin_sum;
  end
  always_comb begin
    oq_wdata = st3_rec_q;
    if (st3_hit_q) oq_wdata[OutW-33 -: 24] = lb_rgb;
  end

  rc_fifo #(
    .Width   (OutW),
    .Depth   (4),
    .MemArray(1'b1)
  ) u_out_q (
    .clk_i,
    .rst_ni,
    .push_i (st3_valid_q),
    .data_i (oq_wdata),
    .valid_o(oq_valid),
    .ready_i(fb_ready_i),
    .data_o (oq_rdata),
    .count_o(oq_count)
  );
  assign fb_valid_o = oq_valid;
  assign {fb_pixel_o, fb_rgb_o, fb_hit_o, fb_tri_o, fb_t_o, fb_u_o, fb_v_o, fb_lights_o,
          fb_bounce_tri_o, fb_refract_tri_o} = oq_rdata;

  //////////////////////
  // The slots' state //
  //////////////////////

  // The slots' events, decoded (rc_onehot: two predecoded lines per slot, not a compare each).
  logic [SlotW-1:0] aq_slot;
  logic [Slots-1:0] lt_hot, cws_hot, aq_hot, fq_hot, mi_hot, cw_hot, snd_hot, dec_hot, fwf_hot;
  assign aq_slot = aq_ln[LaneW-1:2];

  // The work's events (wk_q), registered: the counts take them a cycle later, and a slot with
  // an event in the register is not done (ev_hot). Every event of the lighting comes with a
  // sample taken (lt_take).
  logic             ev_lt_q, ev_mi_q, ev_fq_q, ev_cws_q, ev_aq_q, ev_amb_q, ev_lt_end_q;
  logic [2:0]       ev_rays_q;
  logic [SlotW-1:0] ev_lt_slot_q, ev_mi_slot_q, ev_fq_slot_q, ev_cws_slot_q, ev_aq_slot_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ev_lt_q  <= 1'b0;
      ev_mi_q  <= 1'b0;
      ev_fq_q  <= 1'b0;
      ev_cws_q <= 1'b0;
      ev_aq_q  <= 1'b0;
    end else begin
      ev_lt_q  <= lt_take;
      ev_mi_q  <= mi_issue;
      ev_fq_q  <= fq_pop && fq_hits != 4'd0;
      ev_cws_q <= cw_sh;
      ev_aq_q  <= aq_pop;
    end
  end
  always_ff @(posedge clk_i) begin
    ev_rays_q     <= sh_close ? rc_pkg::ray_count(as_mask) : 3'd0;
    ev_amb_q      <= lt_amb_push;
    ev_lt_end_q   <= lt_lane_last && lt_light_last;
    ev_lt_slot_q  <= lt_slot;
    ev_mi_slot_q  <= fs_slot_q;
    ev_fq_slot_q  <= fq_slot;
    ev_cws_slot_q <= cws_slot;
    ev_aq_slot_q  <= aq_slot;
  end
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_lt_hot  (.valid_i(ev_lt_q),  .idx_i(ev_lt_slot_q),
                                                  .hot_o(lt_hot));
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_cws_hot (.valid_i(ev_cws_q), .idx_i(ev_cws_slot_q),
                                                  .hot_o(cws_hot));
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_aq_hot  (.valid_i(ev_aq_q),  .idx_i(ev_aq_slot_q),
                                                  .hot_o(aq_hot));
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_fq_hot  (.valid_i(ev_fq_q),  .idx_i(ev_fq_slot_q),
                                                  .hot_o(fq_hot));
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_mi_hot  (.valid_i(ev_mi_q),  .idx_i(ev_mi_slot_q),
                                                  .hot_o(mi_hot));
  assign ev_hot = lt_hot | cws_hot | aq_hot | fq_hot | mi_hot;
  // The work's change of each slot in this cycle's events, -3 .. 7: a shadow packet's rays, a
  // miss term's issue, an ambient term, a packet into the lighting; less a shadow ray's write,
  // an add, a packet's last sample. The sample's three (wk_lt, -1 .. 5) are summed once for all
  // slots, the four single events per slot, then the two; the change is registered (wk_dq_q,
  // with wk_hot_q: an event in it) and added to the count in the next cycle, so the sums and
  // the counts' adders are a cycle apart (the lit board routed at d6b0aa3, seed 1: ev_rays_q
  // through both into wk_q, -2.32 ns, 228 endpoints; at 6799b81, -1.50 ns in 13 cells).
  logic [4:0]         wk_lt;  // a sample's change of its slot's work (with lt_hot)
  logic [Slots*5-1:0] wk_dq_q;
  assign wk_lt = 5'(ev_rays_q) + 5'(ev_amb_q) - 5'(ev_lt_end_q);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wk_dq_q  <= '0;
      wk_hot_q <= '0;
    end else begin
      for (int s = 0; s < Slots; s++) begin
        wk_dq_q[s*5 +: 5] <= (lt_hot[s] ? wk_lt : 5'd0) + 5'(mi_hot[s]) + 5'(fq_hot[s]) -
                             5'(cws_hot[s]) - 5'(aq_hot[s]);
      end
      wk_hot_q <= ev_hot;
    end
  end
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_cw_hot  (.valid_i(cw_cur), .idx_i(cw_slot),
                                                  .hot_o(cw_hot));
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_snd_hot (.valid_i(sw),     .idx_i(sw_slot),
                                                  .hot_o(snd_hot));
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_dec_hot (.valid_i(dq_q),   .idx_i(dq_slot_q),
                                                  .hot_o(dec_hot));
  rc_onehot #(.N(Slots), .IdxW(SlotW)) u_fwf_hot (.valid_i(fw_free), .idx_i(fw_slot_q),
                                                  .hot_o(fwf_hot));

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      busy_q  <= '0;
      td_q    <= '0;
      fin_q   <= '0;
      cf_q    <= '0;
      cm_q    <= '0;
      pend_q  <= '0;
      pend1_q <= '0;
      depth_q <= '0;
      wk_q    <= '0;
      sp_q    <= '0;
    end else begin
      for (int s = 0; s < Slots; s++) begin
        // The work's change, registered (wk_dq_q) and added a cycle later.
        wk_q[s*WkW +: WkW] <= wk_q[s*WkW +: WkW] +
                              {{(WkW - 5){wk_dq_q[s*5 + 4]}}, wk_dq_q[s*5 +: 5]};
        // The free slot's state is cleared while a primary packet is offered (slot_offer), not
        // only when it is taken: the slot is free (SlotOffer_A), and nothing reads a free
        // slot's state but busy_q, which alone waits for the core's take.
        if (slot_offer && free_hot[s]) begin
          busy_q[s] <= slot_take;
          td_q[s]   <= 1'b0;
          fin_q[s]  <= 1'b0;
          cf_q[s]   <= 1'b0;
          cm_q[s]   <= 1'b0;
          pend_q[s*3 +: 3] <= rc_pkg::ray_count(pkt_mask_i);
          pend1_q[s]       <= rc_pkg::ray_count(pkt_mask_i) == 3'd1;
          depth_q[s*DepthW +: DepthW] <= '0;
          sp_q[s*DepthW +: DepthW] <= '0;
        end else begin
          if (cw_hot[s]) begin
            pend_q[s*3 +: 3] <= pend_q[s*3 +: 3] - 1'b1;
            pend1_q[s]       <= pend_q[s*3 +: 3] == 3'd2;
            if (!cw_d0 && core_fb_rgb[0]) cf_q[s] <= 1'b1;
          end
          if (snd_hot[s]) begin
            pend_q[s*3 +: 3] <= rc_pkg::ray_count(sw_mask);
            pend1_q[s]       <= rc_pkg::ray_count(sw_mask) == 3'd1;
            depth_q[s*DepthW +: DepthW] <= sw_depth;
            cm_q[s] <= sw_mirror;
            cf_q[s] <= 1'b0;
          end
          if (dec_hot[s]) begin
            if (dec_push) sp_q[s*DepthW +: DepthW] <= dq_sp_q + 1'b1;
            if (dec_pop) sp_q[s*DepthW +: DepthW] <= dq_sp_q - 1'b1;
            if (dec_done) td_q[s] <= 1'b1;
          end
          if (!fw_busy_q && dn_any_q && dn_hot_q[s]) fin_q[s] <= 1'b1;
          if (fwf_hot[s]) busy_q[s] <= 1'b0;
        end
      end
    end
  end

  // The slots' payload (no reset: written before it is read).
  always_ff @(posedge clk_i) begin
    if (slot_offer) begin  // the free slot's, as above
      pmask_q[free_idx] <= pkt_mask_i;
      cmask_q[free_idx] <= pkt_mask_i;
    end
    if (sw) cmask_q[sw_slot] <= sw_mask;
    for (int i = 0; i < 4 * Slots; i++) begin  // a decoded write, not a shifted one
      if (cw_hot[i / 4] && cw_lane == 2'(i % 4)) hit_q[i] <= core_fb_hit;
    end
  end

  // The per-lane records. A packet's rays and weights are written when it goes to the core
  // (ext_take or bq_pop: ext_take waits for an empty tree queue, so the core's packet is the
  // one written); by then its slot's sequencer and lighting have read the packet before it.
  // The sums: a reached shadow ray's term (read from u_terms in the ray's cycle) or, in a cycle
  // without one, the add queue's head; the term is added two cycles later (registered twice).
  assign ln_add        = cw_reached_ln || aq_pop;
  assign ln_add_ln     = cw_reached_ln ? {cws_slot, cw_lane} : aq_ln;
  assign ln_add_term   = rs2_q ? rs_term_q : aq_term2_q;
  assign ln_add_lights = (rs2_q && rs2_d0_q) ? MaxLights'(1) << rs2_light_q : '0;
  always_ff @(posedge clk_i) begin
    aq_term_q  <= aq_term;
    aq_term2_q <= aq_term_q;
  end

  rc_lane_store #(
    .ExpW     (ExpW),
    .FracW    (FracW),
    .Slots    (Slots),
    .MaxLights(MaxLights),
    .FW       (FW),
    .SumW     (SumW)
  ) u_lanes (
    .clk_i,
    .rst_ni,
    .prim_i           (ext_take),
    .prim_slot_i      (free_idx),
    .prim_pixel_i     (pkt_pixel_i),
    .ray_i            (ext_take || bq_pop),
    .ray_slot_i       (lane_bq ? bq_slot : free_idx),
    .ray_org_i        (core_pkt_org),
    .ray_dir_i        (core_pkt_dir),
    .ray_inv_len_i    (core_pkt_inv_len),
    .ray_w_i          (lane_bq ? bq_w : {4{FpOne}}),
    .cw_i             (cw_cur_ln),
    .cw_ln_i          (cw_ln),
    .cw_d0_i          (cw_d0),
    .cw_d1_i          (cw_d1),
    .cw_mirror_i      (cm_q[cw_slot]),
    .cw_hit_i         (core_fb_hit),
    .cw_tri_i         (core_fb_tri),
    .cw_t_i           (core_fb_t),
    .cw_u_i           (core_fb_u),
    .cw_v_i           (core_fb_v),
    .cw_dz_i          (core_fb_dz),
    .cw_rgb_i         (core_fb_rgb),
    .seq_ln_i         (seq_ln),
    .seq_ray_o        (seq_ray),
    .seq_w_o          (seq_w),
    .seq_tri_o        (seq_tri),
    .seq_t_o          (seq_t),
    .seq_dz_o         (seq_dz),
    .add_i            (ln_add),
    .add_ln_i         (ln_add_ln),
    .add_term_i       (ln_add_term),
    .add_lights_i     (ln_add_lights),
    .add_pend1_o      (ln_add_pend1),
    .add_pend1_slot_o (ln_add_slot1),
    .add_pend_o       (ln_add_pend),
    .add_pend_slot_o  (ln_add_slot),
    .fin_ln_i         (fin_ln),
    .fin_pixel_o      (ln_fin_pixel),
    .fin_hit_o        (ln_fin_hit),
    .fin_tri_o        (ln_fin_tri),
    .fin_t_o          (ln_fin_t),
    .fin_u_o          (ln_fin_u),
    .fin_v_o          (ln_fin_v),
    .fin_rgb_o        (ln_fin_rgb),
    .fin_sum_o        (ln_fin_sum),
    .fin_lights_o     (ln_fin_lights),
    .fin_bounce_tri_o (ln_fin_btri),
    .fin_refract_tri_o(ln_fin_rtri)
  );

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
  assign idle_o = core_idle && !core_fb_valid && busy_q == '0 && !st_valid_q && !st2_valid_q &&
                  !st3_valid_q && !oq_valid;

  // Not read: the primary packets' kind, limits and start triangles (the controller makes the
  // secondary packets); the fields of the records the lighting does not use; the valid bits of
  // units whose latency is known; the fetch queue's count (it never overflows: one entry per
  // slot); the pixel id bits above the fields; the depth in the lighting's tag (the geometry
  // reads it).
  logic unused;
  assign unused = ^{pkt_t_hi_i, pkt_start_tri_i, lb_valid, lmat_rsp_data_i, lshd_rsp_data_i,
                    fq_count, core_fb_pixel, lt_tag[LaneW + 2 +: DepthW]};

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
  logic cw_expected, fs_held;
  assign cw_expected = cw_shadow ? spb_q[cw_sp] && sp_cnt_q[cw_sp] != '0 :
                                   busy_q[cw_slot] && pend_q[cw_slot*3 +: 3] != '0;
  assign fs_held     = busy_q[fs_slot_q];
  // The controller makes the secondary packets itself.
  PrimaryOnly_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  pkt_valid_i |-> pkt_kind_i ==
                                  rc_pkg::RayKindBits'(rc_pkg::RayKindPrimary));
  // Every hit has at least one light's samples (its ambient term comes with light 0).
  LightCount_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 light_count_i != '0 && light_count_i <= CountW'(MaxLights));
  // The trees fit the stacks.
  Bounces_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              max_bounces_i <= DepthW'(MaxBounces));
  // The select copies are the queues' valid bits (rc_reg_copies keeps the copies equal).
  ShqSel_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             shq_sel[0] == shq_valid);
  BqSel_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            bq_sel[0] == bq_valid);
  // A sequencer step finds its slot's stack pointer in the registered candidate.
  SeqSp_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            fs_step |-> cand_seq_q == stk_cand(fs_slot_q, sp_q));
  // A slot's last-write flag is its count's compare.
  for (genvar gs = 0; gs < Slots; gs++) begin : g_pend1_chk
    Pend1_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              pend1_q[gs] == (pend_q[gs*3 +: 3] == 3'd1));
  end
  // The head entry's depth is its slot's.
  FeDepth_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              fe_valid |-> fe_head_depth ==
                                           depth_q[fe_head_ln[LaneW-1:2]*DepthW +: DepthW]);
  // The ring's room register is the count's compare.
  FeRoom_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             fe_room == (fe_count_q != (FetchW + 1)'(FetchEntries)));
  // An entry whose ray and weight are written in this cycle (a cycle after the rest) is not
  // read: it waits for its shading and material reads.
  FeRwLate_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               fe_rw_we_q && fe_valid |-> fe_head_q != fe_rw_tail_q);
  // The miss term's shift register marks the third channel's result.
  MoValid_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              mo_valid == (mf_valid && mo_ch_q == 2'd2));
  // A geometry decision finds its slot's stack pointer in the registered candidate.
  GeoSp_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            dec_geo |-> cand_geo_q == stk_cand(geo_slot, sp_q));
  // A write starts with a done slot that is not being written.
  DonePick_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               !fw_busy_q && dn_any_q |-> done_q[dn_idx_q] && !fin_q[dn_idx_q]);
  // A write of the core belongs to a packet that expects it.
  CoreWrite_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                core_fb_valid |-> cw_expected);
  // A slot is not freed while the fetch still issues for it.
  FetchSlot_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                fs_busy_q |-> fs_held);
  // A miss issues only when the miss term's multiplier takes it.
  MissIssue_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                mi_issue |-> mi_free);
  // The add queue never overflows (its pushes are counted ahead).
  AddQueue_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               aq_push |-> 32'(aq_count) < AddQ || aq_pop);
  // The room's count is the add queue's and the miss terms' in flight.
  RoomCount_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                32'(pm_q) == 32'(aq_count) + 32'(mi_count_q));
  // A pop's packet is sent alone: no decision beside it (the stack RAM's word and the tree
  // packet queue's room are the pop's).
  PopAlone_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               pop_q |-> !dec);
  // A decision is carried out alone: none is made in its second cycle (it may send a packet).
  DecAlone_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               dq_q |-> !dec);
  // The registered free slot is free: the slot taken in a cycle is not offered in the next.
  SlotFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               slot_take |-> !busy_q[free_idx]);
  // The closed packet's mask is the one its registers were loaded with.
  ShpMask_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              sh_close |-> as_mask == (as_mask_q | (lt_present ? 4'd1 << lt_lane
                                                                               : 4'd0)));
  // The free slot offered to a primary packet is free, taken or not.
  SlotOffer_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                slot_offer |-> !busy_q[free_idx]);
  // The registered free shadow packet is free: closes are at least three cycles apart.
  SpFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             sh_close |-> !spb_q[sp_free]);
  // The final write's count is the output queue's entries and the writes in its two stages.
  FwCnt_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            fw_cnt_q == oq_count + 3'(st_valid_q) + 3'(st2_valid_q) +
                                        3'(st3_valid_q));
  // The pointer registered in a decision's first cycle is its slot's in the second.
  DqSp_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                           dq_q |-> dq_sp_q == sp_q[dq_slot_q*DepthW +: DepthW]);
  // A fetch decision finds its slot's stack pointer in the registered candidate.
  FqSp_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                           dec && !dec_geo && !dec_seq |->
                           cand_fq_q == stk_cand(fq_slot, sp_q));
  // use_hi is "a slot was taken in the cycle before, and it is the lowest free one registered".
  logic             take_q;
  logic [SlotW-1:0] take_idx_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) take_q <= 1'b0;
    else take_q <= slot_take;
  end
  always_ff @(posedge clk_i) take_idx_q <= free_idx;
  UseHi_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            use_hi == (take_q && lo_idx_q == take_idx_q));
  // Two or more free slots: the highest free slot is another than the lowest.
  HiAny_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            hi_any_q == $past(hi_any_c && hi_idx_c != lo_idx_c));
  // The registered choice is the mirror packet whenever it has rays, the refraction one else.
  DecSel_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             dq_q |-> dq_msel_q == (dq_geo_q && gm_q.mask != 4'd0));
  // The registered read enable is the pop's.
  StkRe_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            stk_re_q == (dq_q && !dq_now_q && dq_sp_q != '0));
  // A push has room in its slot's MaxBounces entries (a tree pushes at most once per level).
  PushRoom_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               dec_push |-> 32'(dq_sp_q) < MaxBounces);
`endif

endmodule
