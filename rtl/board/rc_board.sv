// rc_board: the core for standalone use on an FPGA board (docs/fpga.md, "The board build"): the
// memory image of a scene in block RAM, a framebuffer in block RAM, on-chip ray generation from
// camera registers (rc_ray_gen), and a register port for a host.
//
// Contract
// - Lit = 0: the core alone (rc_core, primary rays, the headlight). Lit = 1: the tree controller
//   rc_tracer around the core (docs/architecture.md, "The tracer"): the scene's lights with
//   shadow, mirror and refraction rays, from the light registers.
// - Memory: five ROMs (rc_board_rom), one per rc_core memory port, of NodeDepth, ListDepth,
//   TriDepth, ShdDepth and MatDepth lines, initialised from NodeHex .. MatHex (written by
//   `raycore board-image` from the memory image the scene compiler writes; in simulation the
//   plusargs +nodes= +lists= +tris= +shading= +materials= override them); with Lit two more for
//   rc_tracer's lighting ports, LShdDepth lines of the shading records (LShdHex, +lshading=) and
//   LMatDepth lines of the materials' lighting fields (LMatHex, +lmaterials=). A line is what the
//   core's port answers for its index: one record, except for the node ROM, whose line i is the
//   pair {record i + 1 (zero for the last node), record i} (rc_pkg::CoreNodeRspRecords records
//   of 64 bits; NodeDepth = the node count). An index beyond a ROM gets an error response (the
//   core's bad-address bit).
// - Register port: reg_we_i writes reg_wdata_i to register reg_addr_i at the clock edge; reg_rdata_o
//   is register reg_addr_i as it was BoardReadLatency (2) cycles before: the value is sampled in
//   the cycle the address is given and passes two register levels (a four-way preselection of
//   the register file and the control registers' multiplexer, then the final choice). A new
//   address can be given every cycle. Register numbers are
//   rc_pkg's BoardReg* (docs/spec.toml [board_reg]). Registers 0 .. Regs-1 are the register
//   file (camera, frame size, background, root box, record counts, shading constants, the root
//   node's record: rc_core root_node_i = {BoardRegRoot + 1, BoardRegRoot}; with Lit the light
//   registers: count, depth, directional lights, t_eps, the background as format values, each
//   light's position and colour), Regs = BoardRegs, or BoardLitRegs with Lit, initialised from
//   RegsHex (plusarg +regs=); writes to it are ignored while busy_o. Writing bit 0 of
//   BoardRegControl (or a start_i pulse, a cycle later) starts a frame when busy_o is 0: three
//   cycles later the frame size is checked (width * height <= FbPixels, else status bit
//   size_error and no frame), with Lit also the light count (1 .. LightMaxLights) and the depth
//   (at most LightBounceLimit; else status bit config_error and no frame), and the ray
//   generation unit starts. BoardRegPerfLo/Hi show the
//   core's counter BoardRegPerfSel through three register levels (rc_core's perf_o is
//   CorePerfReadLatency (2) cycles late, then perf_rd_q, loaded every cycle): a read shows the
//   counter selected four cycles before its address is given, so after writing PerfSel wait
//   three cycles before reading PerfLo/Hi. The counters are exact CorePerfSettleCycles cycles
//   after the core's last event (rc_core's contract), so read them that long after done_o.
// - Frame: the core renders every pixel into the framebuffer (pixel id y * width + x, 24-bit
//   RGB). done_o rises two cycles after the first cycle in which the last packet has been
//   generated and the core is idle; it stays until the next start. BoardRegCycles holds the
//   frame's cycle count.
// - Framebuffer read port: fb_rdata_o is pixel fb_raddr_i of rc_pkg::BoardFbReadLatency (3)
//   cycles before (the block RAM's read register, a register after each bank of block RAMs, then
//   one after the multiplexer that joins the banks); reading while a frame runs is legal and
//   shows the frame in progress. An address at or beyond FbPixels reads an undefined value.
// - Monitor: mon_valid_o and mon_* show each framebuffer write of the core (of the tracer: with
//   the lights that reach the primary hit and the first mirror and refraction rays' triangles;
//   0, -2, -2 without Lit) with its hit record (simulation checks them; a board top leaves them
//   open).
// - Status: busy_o (a frame is starting or running), done_o, error_o = rc_core's (rc_tracer's)
//   error_o (sticky until reset), size_error_o, config_error_o.
// - Parameters: the fp format (ExpW, FracW); Threads, the core's packet threads (default
//   rc_pkg::BoardThreads, docs/spec.toml [board] threads: fewer than the core alone, chosen for
//   the ROMs' short latency); LitSetupUnits, the lit core's ray set-up units (default
//   rc_pkg::BoardLitSetupUnits, [board] lit_setup_units; the board without Lit keeps the core's
//   default); with Lit, LitThreads (the lit core's packet threads, instead of Threads), LitSlots
//   and LitShadowPackets (rc_tracer's Slots and ShadowPackets; defaults [board] lit_threads,
//   lit_slots, lit_shadow_packets: fewer than the chip's, for area, docs/fpga.md "Status") and
//   LitRaygenPeriod (rc_ray_gen's Period with Lit, [board] lit_raygen_period; without Lit it is
//   [board] raygen_period); LitLightPeriod (rc_tracer's LightPeriod, [board] lit_light_period);
//   LitBlockDelays (rc_tracer's BlockDelays and rc_ray_gen's with Lit: wide delay lines in block
//   RAM, [board] lit_block_delays); the ROM depths and hex files; FbPixels. CoreThreads is
//   derived: the threads of the core built (LitThreads with Lit, else Threads).
// - Illegal input: none on the register port (writes while busy are ignored); reading registers
//   that do not exist returns 0.
// - Reset: rst_ni (active low, asynchronous) clears control state; the register file, ROMs and
//   framebuffer keep their contents.
module rc_board #(
  parameter int unsigned ExpW      = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW     = rc_pkg::Fp24FracW,
  parameter int unsigned Threads   = rc_pkg::BoardThreads,
  parameter int unsigned LitSetupUnits = rc_pkg::BoardLitSetupUnits,
  parameter int unsigned LitThreads = rc_pkg::BoardLitThreads,
  parameter int unsigned LitSlots  = rc_pkg::BoardLitSlots,
  parameter int unsigned LitShadowPackets = rc_pkg::BoardLitShadowPackets,
  parameter int unsigned LitRaygenPeriod = rc_pkg::BoardLitRaygenPeriod,
  parameter int unsigned LitLightPeriod = rc_pkg::BoardLitLightPeriod,
  parameter bit          LitBlockDelays = rc_pkg::BoardLitBlockDelays != 0,
  parameter int unsigned NodeDepth = 1,
  parameter int unsigned ListDepth = 1,
  parameter int unsigned TriDepth  = 1,
  parameter int unsigned ShdDepth  = 1,
  parameter int unsigned MatDepth  = 1,
  parameter int unsigned FbPixels  = rc_pkg::BoardFbPixels,
  parameter bit          Lit       = 1'b0,
  parameter int unsigned LShdDepth = 1,
  parameter int unsigned LMatDepth = 1,
  parameter              NodeHex = "",
  parameter              ListHex = "",
  parameter              TriHex = "",
  parameter              ShdHex = "",
  parameter              MatHex = "",
  parameter              LShdHex = "",
  parameter              LMatHex = "",
  parameter              RegsHex = "",
  // Derived (do not override).
  parameter int unsigned W         = 1 + ExpW + FracW,
  parameter int unsigned MaxLights = rc_pkg::LightMaxLights,
  parameter int unsigned AddrW     = rc_pkg::BoardAddrBits,
  parameter int unsigned FbAddrW   = (FbPixels > 1) ? $clog2(FbPixels) : 1,
  parameter int unsigned StatusW   = rc_pkg::CoreStatusBits,
  parameter int unsigned CoreThreads = Lit ? LitThreads : Threads
) (
  input  logic               clk_i,
  input  logic               rst_ni,

  // Register port.
  input  logic               reg_we_i,
  input  logic [AddrW-1:0]   reg_addr_i,
  input  logic [31:0]        reg_wdata_i,
  output logic [31:0]        reg_rdata_o,
  input  logic               start_i,

  // Framebuffer read port.
  input  logic [FbAddrW-1:0] fb_raddr_i,
  output logic [23:0]        fb_rdata_o,

  // Status.
  output logic               busy_o,
  output logic               done_o,
  output logic               size_error_o,
  output logic               config_error_o,
  output logic [StatusW-1:0] error_o,

  // Monitor of the core's framebuffer writes.
  output logic               mon_valid_o,
  output logic [31:0]        mon_pixel_o,
  output logic [23:0]        mon_rgb_o,
  output logic               mon_hit_o,
  output logic [31:0]        mon_tri_o,
  output logic [W-1:0]       mon_t_o,
  output logic [W-1:0]       mon_u_o,
  output logic [W-1:0]       mon_v_o,
  output logic [MaxLights-1:0] mon_lights_o,
  output logic [31:0]        mon_bounce_tri_o,
  output logic [31:0]        mon_refract_tri_o
);

  localparam int unsigned Regs   = Lit ? rc_pkg::BoardLitRegs : rc_pkg::BoardRegs;
  localparam int unsigned CoordW = rc_pkg::BoardCoordBits;
  localparam int unsigned TagW   = rc_pkg::CoreTagBits;
  // The node port answers a pair of 64-bit records (rc_core NodeRspW).
  localparam int unsigned NodeRspW = rc_pkg::CoreNodeRspRecords * 8 * rc_pkg::KdNodeBytes;
  // The lit board's registers (index 0 without Lit: never read there).
  localparam int unsigned LightCountReg = Lit ? rc_pkg::BoardRegLightCount : 0;
  localparam int unsigned MaxBouncesReg = Lit ? rc_pkg::BoardRegMaxBounces : 0;

  if (Regs < rc_pkg::BoardRegDiffuse + 1 || Regs < rc_pkg::BoardRegRoot + 2 ||
      Regs > rc_pkg::BoardRegControl ||
      (Lit && Regs < rc_pkg::BoardRegLights + 6 * MaxLights)) begin : g_regs_check
    $error("rc_board: the register file must hold registers 0 .. BoardRegDiffuse and %s",
           "BoardRegRoot + 1 (with Lit the lights' too), below control");
  end

  ///////////////////
  // Register file //
  ///////////////////

  // Flip-flops, never a memory (mem2reg): every register is read at a fixed address by its user,
  // and Yosys 0.23's memory_libmap, given the lit board's 64 registers as one memory with 147
  // read ports, grew past 24 GB.
  (* mem2reg *) logic [31:0] regs_q [0:Regs-1];

  initial begin
`ifndef SYNTHESIS
    string file;
    if ($value$plusargs("regs=%s", file)) begin
      $readmemh(file, regs_q);
    end else if (RegsHex != "") begin
      $readmemh(RegsHex, regs_q);
    end
`else
    if (RegsHex != "") $readmemh(RegsHex, regs_q);
`endif
  end

  logic running_q, done_q, size_error_q, config_error_q, fin_q;
  logic [1:0] pend_q;  // start requested: cycles until the size check
  logic busy;

  assign busy = running_q | (pend_q != 2'd0);

  // The register file's lock, registered from the next busy (wr_ok_q == !busy, RegLock_A), so
  // that running_q's and pend_q's nets end at one flip-flop, not at the file's enables.
  logic busy_d, wr_ok_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) wr_ok_q <= 1'b1;
    else wr_ok_q <= !busy_d;
  end
  always_ff @(posedge clk_i) begin
    if (reg_we_i && wr_ok_q && {1'b0, reg_addr_i} < (AddrW+1)'(Regs)) begin
      regs_q[reg_addr_i[$clog2(Regs)-1:0]] <= reg_wdata_i;
    end
  end

  function automatic logic [3*W-1:0] vec3(int unsigned base);
    vec3 = {regs_q[base+2][W-1:0], regs_q[base+1][W-1:0], regs_q[base][W-1:0]};
  endfunction

  logic [3*W-1:0]    eye, c0, cx, cy;
  logic [6*W-1:0]    bounds;
  logic [CoordW-1:0] width, height;

  assign eye    = vec3(rc_pkg::BoardRegEye);
  assign c0     = vec3(rc_pkg::BoardRegC0);
  assign cx     = vec3(rc_pkg::BoardRegCx);
  assign cy     = vec3(rc_pkg::BoardRegCy);
  assign bounds = {vec3(rc_pkg::BoardRegBounds + 3), vec3(rc_pkg::BoardRegBounds)};
  assign width  = regs_q[rc_pkg::BoardRegWidth][CoordW-1:0];
  assign height = regs_q[rc_pkg::BoardRegHeight][CoordW-1:0];

  /////////////////////
  // Frame control   //
  /////////////////////

  logic        start_req, gen_start, gen_busy, core_idle, size_ok, cfg_ok;
  logic        pkt_held;  // with Lit, a packet waits in the register between generator and core
  logic [31:0] pixels_q, cycles_q;
  logic        size_ok_q, cfg_ok_q;

  // The start pulse is registered first (it comes from the board top's button logic, placed
  // anywhere on the chip), so its one net ends at a flip-flop beside the frame control.
  logic start_in_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      start_in_q <= 1'b0;
    end else begin
      start_in_q <= start_i;
    end
  end
  assign start_req = !busy && (start_in_q || (reg_we_i && {1'b0, reg_addr_i} ==
                     (AddrW+1)'(rc_pkg::BoardRegControl) && reg_wdata_i[0]));
  assign size_ok   = size_ok_q;
  assign cfg_ok    = cfg_ok_q;
  assign gen_start = (pend_q == 2'd1) && size_ok && cfg_ok;
  // busy in the next cycle: a start, the start's count, a frame that starts, or one not ending.
  assign busy_d    = start_req || pend_q > 2'd1 || gen_start || (running_q && !fin_q);

  // The frame size, its product and its check are registers in a row (the register file is
  // locked from the start request on, and a register written in the request's own cycle is in
  // the check two cycles later), so the check's carry chain ends at a flip-flop and not at the
  // ray generator's start.
  // With Lit, the light count and the depth are checked beside the size (the tracer's range).
  always_ff @(posedge clk_i) begin
    pixels_q  <= 32'(width) * 32'(height);
    size_ok_q <= pixels_q <= 32'(FbPixels);
    cfg_ok_q  <= !Lit || (regs_q[LightCountReg] != '0 &&
                          regs_q[LightCountReg] <= 32'(MaxLights) &&
                          regs_q[MaxBouncesReg] <= 32'(rc_pkg::LightBounceLimit));
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pend_q         <= 2'd0;
      fin_q          <= 1'b0;
      running_q      <= 1'b0;
      done_q         <= 1'b0;
      size_error_q   <= 1'b0;
      config_error_q <= 1'b0;
      cycles_q       <= '0;
    end else begin
      if (start_req) begin
        pend_q         <= 2'd3;
        done_q         <= 1'b0;
        size_error_q   <= 1'b0;
        config_error_q <= 1'b0;
        cycles_q       <= '0;
      end else if (pend_q != 2'd0) begin
        pend_q <= pend_q - 2'd1;
        if (pend_q == 2'd1) begin
          running_q      <= size_ok && cfg_ok;
          size_error_q   <= !size_ok;
          config_error_q <= !cfg_ok;
        end
      end
      // The generator is busy from the cycle after its start until its last packet is taken;
      // the core is not idle from the cycle after it took a packet until its last write. The
      // end of the frame is registered (fin_q: the core's idle, an AND over its thread states,
      // ends at one flip-flop instead of at the frame control) and acted on a cycle later.
      fin_q <= running_q && !gen_busy && !pkt_held && core_idle;
      if (running_q) begin
        cycles_q <= cycles_q + 32'd1;
        if (fin_q) begin
          running_q <= 1'b0;
          done_q    <= 1'b1;
        end
      end
    end
  end

  ////////////////////
  // Ray generation //
  ////////////////////

  logic              pkt_valid, pkt_ready;
  logic [3:0]        pkt_mask;
  logic [12*W-1:0]   pkt_org, pkt_dir;
  logic [4*W-1:0]    pkt_inv_len;
  logic [127:0]      pkt_pixel;

  rc_ray_gen #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .Period(Lit ? LitRaygenPeriod : rc_pkg::BoardRaygenPeriod),
    .BlockDelays(Lit && LitBlockDelays)
  ) u_ray_gen (
    .clk_i,
    .rst_ni,
    .eye_i        (eye),
    .c0_i         (c0),
    .cx_i         (cx),
    .cy_i         (cy),
    .width_i      (width),
    .height_i     (height),
    .start_i      (gen_start),
    .busy_o       (gen_busy),
    .pkt_valid_o  (pkt_valid),
    .pkt_ready_i  (pkt_ready),
    .pkt_mask_o   (pkt_mask),
    .pkt_org_o    (pkt_org),
    .pkt_dir_o    (pkt_dir),
    .pkt_inv_len_o(pkt_inv_len),
    .pkt_pixel_o  (pkt_pixel)
  );

  //////////////////////////
  // Memory ports (ROMs)  //
  //////////////////////////

  logic            node_req_valid, node_req_ready, node_rsp_valid, node_rsp_ready, node_rsp_error;
  logic [TagW-1:0] node_req_tag, node_rsp_tag;
  logic [31:0]     node_req_index;
  logic [NodeRspW-1:0] node_rsp_data;
  logic            list_req_valid, list_req_ready, list_rsp_valid, list_rsp_ready, list_rsp_error;
  logic [TagW-1:0] list_req_tag, list_rsp_tag;
  logic [31:0]     list_req_index;
  logic [31:0]     list_rsp_data;
  logic            tri_req_valid, tri_req_ready, tri_rsp_valid, tri_rsp_ready, tri_rsp_error;
  logic [TagW-1:0] tri_req_tag, tri_rsp_tag;
  logic [31:0]     tri_req_index;
  logic [12*W-1:0] tri_rsp_data;
  logic            shd_req_valid, shd_req_ready, shd_rsp_valid, shd_rsp_ready, shd_rsp_error;
  logic [TagW-1:0] shd_req_tag, shd_rsp_tag;
  logic [31:0]     shd_req_index;
  logic [32+4*W-1:0] shd_rsp_data;
  logic            mat_req_valid, mat_req_ready, mat_rsp_valid, mat_rsp_ready, mat_rsp_error;
  logic [TagW-1:0] mat_req_tag, mat_rsp_tag;
  logic [31:0]     mat_req_index;
  logic [95:0]     mat_rsp_data;

  rc_board_rom #(.Width(NodeRspW), .Depth(NodeDepth), .TagW(TagW), .InitFile(NodeHex),
                 .Name("nodes"))
  u_rom_nodes (
    .clk_i, .rst_ni,
    .req_valid_i(node_req_valid), .req_ready_o(node_req_ready), .req_tag_i(node_req_tag),
    .req_index_i(node_req_index), .rsp_valid_o(node_rsp_valid), .rsp_ready_i(node_rsp_ready),
    .rsp_tag_o(node_rsp_tag), .rsp_data_o(node_rsp_data), .rsp_error_o(node_rsp_error)
  );
  rc_board_rom #(.Width(32), .Depth(ListDepth), .TagW(TagW), .InitFile(ListHex), .Name("lists"))
  u_rom_lists (
    .clk_i, .rst_ni,
    .req_valid_i(list_req_valid), .req_ready_o(list_req_ready), .req_tag_i(list_req_tag),
    .req_index_i(list_req_index), .rsp_valid_o(list_rsp_valid), .rsp_ready_i(list_rsp_ready),
    .rsp_tag_o(list_rsp_tag), .rsp_data_o(list_rsp_data), .rsp_error_o(list_rsp_error)
  );
  rc_board_rom #(.Width(12*W), .Depth(TriDepth), .TagW(TagW), .InitFile(TriHex), .Name("tris"))
  u_rom_tris (
    .clk_i, .rst_ni,
    .req_valid_i(tri_req_valid), .req_ready_o(tri_req_ready), .req_tag_i(tri_req_tag),
    .req_index_i(tri_req_index), .rsp_valid_o(tri_rsp_valid), .rsp_ready_i(tri_rsp_ready),
    .rsp_tag_o(tri_rsp_tag), .rsp_data_o(tri_rsp_data), .rsp_error_o(tri_rsp_error)
  );
  rc_board_rom #(.Width(32+4*W), .Depth(ShdDepth), .TagW(TagW), .InitFile(ShdHex),
                 .Name("shading"))
  u_rom_shading (
    .clk_i, .rst_ni,
    .req_valid_i(shd_req_valid), .req_ready_o(shd_req_ready), .req_tag_i(shd_req_tag),
    .req_index_i(shd_req_index), .rsp_valid_o(shd_rsp_valid), .rsp_ready_i(shd_rsp_ready),
    .rsp_tag_o(shd_rsp_tag), .rsp_data_o(shd_rsp_data), .rsp_error_o(shd_rsp_error)
  );
  rc_board_rom #(.Width(96), .Depth(MatDepth), .TagW(TagW), .InitFile(MatHex),
                 .Name("materials"))
  u_rom_materials (
    .clk_i, .rst_ni,
    .req_valid_i(mat_req_valid), .req_ready_o(mat_req_ready), .req_tag_i(mat_req_tag),
    .req_index_i(mat_req_index), .rsp_valid_o(mat_rsp_valid), .rsp_ready_i(mat_rsp_ready),
    .rsp_tag_o(mat_rsp_tag), .rsp_data_o(mat_rsp_data), .rsp_error_o(mat_rsp_error)
  );

  //////////////
  // The core //
  //////////////

  logic              fb_valid;
  logic [31:0]       fb_pixel, fb_tri;
  logic [23:0]       fb_rgb;
  logic              fb_hit;
  logic [W-1:0]      fb_t, fb_u, fb_v;
  logic [7:0]        perf_sel_q;
  logic [63:0]       perf, perf_rd_q;
  logic [StatusW-1:0] core_error;

  logic [CoreThreads*rc_pkg::ThreadStateBits-1:0] core_dbg_states;
  logic [MaxLights-1:0] fb_lights;
  logic [31:0]  fb_bounce_tri, fb_refract_tri;
  if (Lit) begin : g_lit
    // The tree controller around the core, its configuration from the light registers and its
    // lighting ports from two more ROMs (the shading records again, the materials' lighting
    // fields).
    localparam int unsigned FetchW = (rc_pkg::TracerFetchEntries > 1) ?
                                     $clog2(rc_pkg::TracerFetchEntries) : 1;
    localparam int unsigned CountW = $clog2(MaxLights + 1);
    localparam int unsigned DepthW = $clog2(rc_pkg::LightBounceLimit + 1);
    localparam int unsigned LMatW  =
        8 * (rc_pkg::ImageMaterialEta + 4 - rc_pkg::ImageMaterialKd);
    // The generator's packets reach the tree controller through a register (a one-entry queue:
    // one packet per two cycles, where the lit frame takes one per 24 or more): the core's
    // take and the generator's advance, placed apart, no longer meet in a cycle.
    localparam int unsigned PktW = 4 + 28 * W + 128;
    logic            pq_valid, pq_ready, pq_count;
    logic [PktW-1:0] pq_rdata;
    logic [3:0]      pq_mask;
    logic [12*W-1:0] pq_org, pq_dir;
    logic [4*W-1:0]  pq_inv_len;
    logic [127:0]    pq_pixel;
    rc_fifo #(
      .Width   (PktW),
      .Depth   (1),
      .MemArray(1'b0)
    ) u_pkt_q (
      .clk_i,
      .rst_ni,
      .push_i (pkt_valid && !pq_count),
      .data_i ({pkt_mask, pkt_org, pkt_dir, pkt_inv_len, pkt_pixel}),
      .valid_o(pq_valid),
      .ready_i(pq_ready),
      .data_o (pq_rdata),
      .count_o(pq_count)
    );
    assign {pq_mask, pq_org, pq_dir, pq_inv_len, pq_pixel} = pq_rdata;
    assign pkt_ready = !pq_count;
    assign pkt_held  = pq_count;

    logic [CountW-1:0]        light_count;
    logic [MaxLights-1:0]     light_dir;
    logic [MaxLights*3*W-1:0] light_pos, light_col;
    logic [DepthW-1:0]        max_bounces;
    logic [3*W-1:0]           light_bg;
    assign light_count = regs_q[rc_pkg::BoardRegLightCount][CountW-1:0];
    assign light_dir   = regs_q[rc_pkg::BoardRegLightDir][MaxLights-1:0];
    assign max_bounces = regs_q[rc_pkg::BoardRegMaxBounces][DepthW-1:0];
    assign light_bg    = vec3(rc_pkg::BoardRegLightBg);
    for (genvar l = 0; l < MaxLights; l++) begin : g_light
      assign light_pos[l*3*W +: 3*W] = vec3(rc_pkg::BoardRegLights + 6 * l);
      assign light_col[l*3*W +: 3*W] = vec3(rc_pkg::BoardRegLights + 6 * l + 3);
    end

    logic              lshd_req_valid, lshd_req_ready, lshd_rsp_valid, lshd_rsp_ready;
    logic              lshd_rsp_error;
    logic [FetchW-1:0] lshd_req_tag, lshd_rsp_tag;
    logic [31:0]       lshd_req_index;
    logic [32+4*W-1:0] lshd_rsp_data;
    logic              lmat_req_valid, lmat_req_ready, lmat_rsp_valid, lmat_rsp_ready;
    logic              lmat_rsp_error;
    logic [FetchW-1:0] lmat_req_tag, lmat_rsp_tag;
    logic [31:0]       lmat_req_index;
    logic [LMatW-1:0]  lmat_rsp_data;
    rc_board_rom #(.Width(32+4*W), .Depth(LShdDepth), .TagW(FetchW), .InitFile(LShdHex),
                   .Name("lshading"))
    u_rom_lshading (
      .clk_i, .rst_ni,
      .req_valid_i(lshd_req_valid), .req_ready_o(lshd_req_ready), .req_tag_i(lshd_req_tag),
      .req_index_i(lshd_req_index), .rsp_valid_o(lshd_rsp_valid), .rsp_ready_i(lshd_rsp_ready),
      .rsp_tag_o(lshd_rsp_tag), .rsp_data_o(lshd_rsp_data), .rsp_error_o(lshd_rsp_error)
    );
    rc_board_rom #(.Width(LMatW), .Depth(LMatDepth), .TagW(FetchW), .InitFile(LMatHex),
                   .Name("lmaterials"))
    u_rom_lmaterials (
      .clk_i, .rst_ni,
      .req_valid_i(lmat_req_valid), .req_ready_o(lmat_req_ready), .req_tag_i(lmat_req_tag),
      .req_index_i(lmat_req_index), .rsp_valid_o(lmat_rsp_valid), .rsp_ready_i(lmat_rsp_ready),
      .rsp_tag_o(lmat_rsp_tag), .rsp_data_o(lmat_rsp_data), .rsp_error_o(lmat_rsp_error)
    );

    rc_tracer #(
      .ExpW      (ExpW),
      .FracW     (FracW),
      .Threads   (LitThreads),
      .SetupUnits(LitSetupUnits),
      .Slots     (LitSlots),
      .ShadowPackets(LitShadowPackets),
      .LightPeriod(LitLightPeriod),
      .BlockDelays(LitBlockDelays)
    ) u_tracer (
    .clk_i,
    .rst_ni,
    .bounds_i        (bounds),
    .node_count_i    (regs_q[rc_pkg::BoardRegNodeCount]),
    .list_count_i    (regs_q[rc_pkg::BoardRegListCount]),
    .tri_count_i     (regs_q[rc_pkg::BoardRegTriCount]),
    .root_node_i     ({regs_q[rc_pkg::BoardRegRoot + 1], regs_q[rc_pkg::BoardRegRoot]}),
    .ambient_i       (regs_q[rc_pkg::BoardRegAmbient][W-1:0]),
    .diffuse_i       (regs_q[rc_pkg::BoardRegDiffuse][W-1:0]),
    .background_i    (regs_q[rc_pkg::BoardRegBackground][23:0]),
    .light_count_i   (light_count),
    .light_dir_i     (light_dir),
    .light_pos_i     (light_pos),
    .light_col_i     (light_col),
    .max_bounces_i   (max_bounces),
    .bg_i            (light_bg),
    .t_eps_i         (regs_q[rc_pkg::BoardRegTEps][W-1:0]),
    .pkt_valid_i     (pq_valid),
    .pkt_ready_o     (pq_ready),
    .pkt_mask_i      (pq_mask),
    .pkt_org_i       (pq_org),
    .pkt_dir_i       (pq_dir),
    .pkt_inv_len_i   (pq_inv_len),
    .pkt_pixel_i     (pq_pixel),
    .pkt_kind_i      (rc_pkg::RayPrimary),
    .pkt_t_hi_i      ('0),
    .pkt_start_tri_i ('0),
    .fb_valid_o      (fb_valid),
    .fb_ready_i      (1'b1),
    .fb_pixel_o      (fb_pixel),
    .fb_rgb_o        (fb_rgb),
    .fb_hit_o        (fb_hit),
    .fb_tri_o        (fb_tri),
    .fb_t_o          (fb_t),
    .fb_u_o          (fb_u),
    .fb_v_o          (fb_v),
    .fb_lights_o     (fb_lights),
    .fb_bounce_tri_o (fb_bounce_tri),
    .fb_refract_tri_o(fb_refract_tri),
    .node_req_valid_o(node_req_valid),
    .node_req_ready_i(node_req_ready),
    .node_req_tag_o  (node_req_tag),
    .node_req_index_o(node_req_index),
    .node_rsp_valid_i(node_rsp_valid),
    .node_rsp_ready_o(node_rsp_ready),
    .node_rsp_tag_i  (node_rsp_tag),
    .node_rsp_data_i (node_rsp_data),
    .node_rsp_error_i(node_rsp_error),
    .list_req_valid_o(list_req_valid),
    .list_req_ready_i(list_req_ready),
    .list_req_tag_o  (list_req_tag),
    .list_req_index_o(list_req_index),
    .list_rsp_valid_i(list_rsp_valid),
    .list_rsp_ready_o(list_rsp_ready),
    .list_rsp_tag_i  (list_rsp_tag),
    .list_rsp_data_i (list_rsp_data),
    .list_rsp_error_i(list_rsp_error),
    .tri_req_valid_o (tri_req_valid),
    .tri_req_ready_i (tri_req_ready),
    .tri_req_tag_o   (tri_req_tag),
    .tri_req_index_o (tri_req_index),
    .tri_rsp_valid_i (tri_rsp_valid),
    .tri_rsp_ready_o (tri_rsp_ready),
    .tri_rsp_tag_i   (tri_rsp_tag),
    .tri_rsp_data_i  (tri_rsp_data),
    .tri_rsp_error_i (tri_rsp_error),
    .shd_req_valid_o (shd_req_valid),
    .shd_req_ready_i (shd_req_ready),
    .shd_req_tag_o   (shd_req_tag),
    .shd_req_index_o (shd_req_index),
    .shd_rsp_valid_i (shd_rsp_valid),
    .shd_rsp_ready_o (shd_rsp_ready),
    .shd_rsp_tag_i   (shd_rsp_tag),
    .shd_rsp_data_i  (shd_rsp_data),
    .shd_rsp_error_i (shd_rsp_error),
    .mat_req_valid_o (mat_req_valid),
    .mat_req_ready_i (mat_req_ready),
    .mat_req_tag_o   (mat_req_tag),
    .mat_req_index_o (mat_req_index),
    .mat_rsp_valid_i (mat_rsp_valid),
    .mat_rsp_ready_o (mat_rsp_ready),
    .mat_rsp_tag_i   (mat_rsp_tag),
    .mat_rsp_data_i  (mat_rsp_data),
    .mat_rsp_error_i (mat_rsp_error),
    .idle_o          (core_idle),
    .error_o         (core_error),
    .perf_sel_i      (perf_sel_q),
    .perf_o          (perf),
    .dbg_thread_state_o(core_dbg_states),
    .lshd_req_valid_o(lshd_req_valid),
    .lshd_req_ready_i(lshd_req_ready),
    .lshd_req_tag_o  (lshd_req_tag),
    .lshd_req_index_o(lshd_req_index),
    .lshd_rsp_valid_i(lshd_rsp_valid),
    .lshd_rsp_ready_o(lshd_rsp_ready),
    .lshd_rsp_tag_i  (lshd_rsp_tag),
    .lshd_rsp_data_i (lshd_rsp_data),
    .lshd_rsp_error_i(lshd_rsp_error),
    .lmat_req_valid_o(lmat_req_valid),
    .lmat_req_ready_i(lmat_req_ready),
    .lmat_req_tag_o  (lmat_req_tag),
    .lmat_req_index_o(lmat_req_index),
    .lmat_rsp_valid_i(lmat_rsp_valid),
    .lmat_rsp_ready_o(lmat_rsp_ready),
    .lmat_rsp_tag_i  (lmat_rsp_tag),
    .lmat_rsp_data_i (lmat_rsp_data),
    .lmat_rsp_error_i(lmat_rsp_error)
    );
  end else begin : g_core
    logic [W-1:0] core_fb_dz;
    assign pkt_held = 1'b0;  // the generator's packets go to the core directly
    rc_core #(
      .ExpW   (ExpW),
      .FracW  (FracW),
      .Threads(Threads),
      .Secondary(1'b0)  // primary rays only: the headlight
    ) u_core (
      .clk_i,
      .rst_ni,
      .bounds_i        (bounds),
      .node_count_i    (regs_q[rc_pkg::BoardRegNodeCount]),
      .list_count_i    (regs_q[rc_pkg::BoardRegListCount]),
      .tri_count_i     (regs_q[rc_pkg::BoardRegTriCount]),
      .root_node_i     ({regs_q[rc_pkg::BoardRegRoot + 1], regs_q[rc_pkg::BoardRegRoot]}),
      .ambient_i       (regs_q[rc_pkg::BoardRegAmbient][W-1:0]),
      .diffuse_i       (regs_q[rc_pkg::BoardRegDiffuse][W-1:0]),
      .background_i    (regs_q[rc_pkg::BoardRegBackground][23:0]),
      .t_eps_i         ('0),
      .pkt_valid_i     (pkt_valid),
      .pkt_ready_o     (pkt_ready),
      .pkt_mask_i      (pkt_mask),
      .pkt_org_i       (pkt_org),
      .pkt_dir_i       (pkt_dir),
      .pkt_inv_len_i   (pkt_inv_len),
      .pkt_pixel_i     (pkt_pixel),
      .pkt_kind_i      (rc_pkg::RayPrimary),
      .pkt_t_hi_i      ('0),
      .pkt_start_tri_i ('0),
      .fb_valid_o      (fb_valid),
      .fb_ready_i      (1'b1),
      .fb_pixel_o      (fb_pixel),
      .fb_rgb_o        (fb_rgb),
      .fb_hit_o        (fb_hit),
      .fb_tri_o        (fb_tri),
      .fb_t_o          (fb_t),
      .fb_u_o          (fb_u),
      .fb_v_o          (fb_v),
      .fb_dz_o         (core_fb_dz),
      .node_req_valid_o(node_req_valid),
      .node_req_ready_i(node_req_ready),
      .node_req_tag_o  (node_req_tag),
      .node_req_index_o(node_req_index),
      .node_rsp_valid_i(node_rsp_valid),
      .node_rsp_ready_o(node_rsp_ready),
      .node_rsp_tag_i  (node_rsp_tag),
      .node_rsp_data_i (node_rsp_data),
      .node_rsp_error_i(node_rsp_error),
      .list_req_valid_o(list_req_valid),
      .list_req_ready_i(list_req_ready),
      .list_req_tag_o  (list_req_tag),
      .list_req_index_o(list_req_index),
      .list_rsp_valid_i(list_rsp_valid),
      .list_rsp_ready_o(list_rsp_ready),
      .list_rsp_tag_i  (list_rsp_tag),
      .list_rsp_data_i (list_rsp_data),
      .list_rsp_error_i(list_rsp_error),
      .tri_req_valid_o (tri_req_valid),
      .tri_req_ready_i (tri_req_ready),
      .tri_req_tag_o   (tri_req_tag),
      .tri_req_index_o (tri_req_index),
      .tri_rsp_valid_i (tri_rsp_valid),
      .tri_rsp_ready_o (tri_rsp_ready),
      .tri_rsp_tag_i   (tri_rsp_tag),
      .tri_rsp_data_i  (tri_rsp_data),
      .tri_rsp_error_i (tri_rsp_error),
      .shd_req_valid_o (shd_req_valid),
      .shd_req_ready_i (shd_req_ready),
      .shd_req_tag_o   (shd_req_tag),
      .shd_req_index_o (shd_req_index),
      .shd_rsp_valid_i (shd_rsp_valid),
      .shd_rsp_ready_o (shd_rsp_ready),
      .shd_rsp_tag_i   (shd_rsp_tag),
      .shd_rsp_data_i  (shd_rsp_data),
      .shd_rsp_error_i (shd_rsp_error),
      .mat_req_valid_o (mat_req_valid),
      .mat_req_ready_i (mat_req_ready),
      .mat_req_tag_o   (mat_req_tag),
      .mat_req_index_o (mat_req_index),
      .mat_rsp_valid_i (mat_rsp_valid),
      .mat_rsp_ready_o (mat_rsp_ready),
      .mat_rsp_tag_i   (mat_rsp_tag),
      .mat_rsp_data_i  (mat_rsp_data),
      .mat_rsp_error_i (mat_rsp_error),
      .idle_o          (core_idle),
      .error_o         (core_error),
      .perf_sel_i      (perf_sel_q),
      .perf_o          (perf),
      .dbg_thread_state_o(core_dbg_states)
    );
    // d'z is a tree controller's (zero at Secondary = 0).
    logic unused_dz;
    assign unused_dz = ^core_fb_dz;
    assign fb_lights      = '0;
    assign fb_bounce_tri  = -32'sd2;
    assign fb_refract_tri = -32'sd2;
  end
  // The core's debug port feeds nothing on the board (the harness reads it on a core alone).
  logic unused_core_dbg;
  assign unused_core_dbg = ^core_dbg_states;

  /////////////////
  // Framebuffer //
  /////////////////

  // The framebuffer is FbBanks banks of FbBankPx pixels: a bank is six DP16KD of 4096 x 4 bits
  // (Yosys's mapping of a 24-bit memory of that depth), the last bank holds what is left. A read
  // passes three registers: the bank's read register (in the block RAMs), a register after each
  // bank (fb_bank_q), then one after the multiplexer that joins the banks (fb_out_q). The block
  // RAM's 5.8 ns clock-to-out thus meets only routing (run 52: through the multiplexer into
  // fb_out_q, -0.57 ns; run 49: into the host's register across two LUTs).
  localparam int unsigned FbBankPx = (FbPixels < 4096) ? FbPixels : 4096;
  localparam int unsigned FbBanks  = (FbPixels + FbBankPx - 1) / FbBankPx;
  localparam int unsigned FbBankAW = (FbBankPx > 1) ? $clog2(FbBankPx) : 1;
  localparam int unsigned FbSelW   = (FbBanks > 1) ? $clog2(FbBanks) : 1;
  if (FbBanks > 1 && FbBankPx != (1 << FbBankAW)) begin : g_fb_bank_check
    $error("rc_board: a framebuffer bank must hold a power of two pixels");
  end

  // A write is registered first (fbw_*_q) and made a cycle later: the core's pixel id comes
  // from a distributed-RAM read, and its range check's carry chain ended at the block RAM's
  // write enable (run 24). The write lands before done_o rises (two cycles after the core is
  // idle).
  logic               fbw_q;
  logic [FbAddrW-1:0] fbw_addr_q;
  logic [23:0]        fbw_rgb_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fbw_q <= 1'b0;
    end else begin
      fbw_q <= fb_valid && fb_pixel < 32'(FbPixels);
    end
  end
  always_ff @(posedge clk_i) begin
    fbw_addr_q <= FbAddrW'(fb_pixel);
    fbw_rgb_q  <= fb_rgb;
  end

  // The bank a pixel address selects (0 with one bank).
  function automatic logic [FbSelW-1:0] fb_bank_of(input logic [FbAddrW-1:0] addr);
    fb_bank_of = (FbBanks > 1) ? FbSelW'(addr >> FbBankAW) : '0;
  endfunction

  logic [FbBanks*24-1:0] fb_bank_q;  // bank b's pixel at [b * 24 +: 24]
  for (genvar b = 0; b < FbBanks; b++) begin : g_fb_bank
    localparam int unsigned Depth = (b == FbBanks - 1) ? FbPixels - b * FbBankPx : FbBankPx;
    localparam int unsigned AW    = (Depth > 1) ? $clog2(Depth) : 1;
    logic [23:0] mem [0:Depth-1];
    logic [23:0] rdata_q;  // the block RAMs' read register (Yosys maps it into the RAMs)
    always_ff @(posedge clk_i) begin
      if (fbw_q && fb_bank_of(fbw_addr_q) == FbSelW'(b)) begin
        mem[AW'(fbw_addr_q)] <= fbw_rgb_q;
      end
    end
    always_ff @(posedge clk_i) begin
      rdata_q      <= mem[AW'(fb_raddr_i)];
      fb_bank_q[b*24 +: 24] <= rdata_q;
    end
  end

  // The bank of each read, beside the two registers in front of the multiplexer (a plain
  // multiplexer on the bank: a part-select at a computed offset would be a shifter).
  logic [FbSelW-1:0] fb_sel0_q, fb_sel1_q;
  logic [23:0]       fb_out_d, fb_out_q;
  always_comb begin
    fb_out_d = '0;
    for (int unsigned b = 0; b < FbBanks; b++) begin
      if (fb_sel1_q == FbSelW'(b)) fb_out_d = fb_bank_q[b*24 +: 24];
    end
  end
  always_ff @(posedge clk_i) begin
    fb_sel0_q <= fb_bank_of(fb_raddr_i);
    fb_sel1_q <= fb_sel0_q;
    fb_out_q  <= fb_out_d;
  end
  if (rc_pkg::BoardFbReadLatency != 3) begin : g_fb_read_check
    $error("rc_board: the framebuffer read has three registers: needs BoardFbReadLatency 3");
  end

  ////////////////////
  // Register reads //
  ////////////////////

  logic [31:0] status, rdata_d, rdata_q;
  // The read in two register levels: the register file's four-way preselection by the address's
  // low bits (rd_grp_q, Regs/4 words) with the control registers' value (rd_ctl_q), then the
  // choice among them. The host's address register fans out to the first level only.
  localparam int unsigned RdGroups = (Regs + 3) / 4;
  localparam int unsigned RdGrpW   = (RdGroups > 1) ? $clog2(RdGroups) : 1;
  logic [31:0]       rd_grp_q [0:RdGroups-1];
  logic [31:0]       rd_ctl_q;
  logic              rd_file_q;
  logic [RdGrpW-1:0] rd_sel_q;

  if (rc_pkg::BoardReadLatency != 2 || Regs % 4 != 0) begin : g_read_check
    $error("rc_board: two-level register read: needs BoardReadLatency 2, Regs a multiple of 4");
  end

  always_comb begin
    status = '0;
    status[rc_pkg::BoardStatusBusy]      = busy;
    status[rc_pkg::BoardStatusDone]      = done_q;
    status[rc_pkg::BoardStatusSizeError] = size_error_q;
    status[rc_pkg::BoardStatusConfigError] = config_error_q;
    status[rc_pkg::BoardStatusCoreErrorLsb +: StatusW] = core_error;
  end

  always_comb begin
    rdata_d = '0;
    unique case (32'(reg_addr_i))
      rc_pkg::BoardRegStatus:  rdata_d = status;
      rc_pkg::BoardRegCycles:  rdata_d = cycles_q;
      rc_pkg::BoardRegPerfSel: rdata_d = 32'(perf_sel_q);
      rc_pkg::BoardRegPerfLo:  rdata_d = perf_rd_q[31:0];
      rc_pkg::BoardRegPerfHi:  rdata_d = perf_rd_q[63:32];
      default:                 rdata_d = '0;
    endcase
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      perf_sel_q <= '0;
    end else if (reg_we_i && 32'(reg_addr_i) == rc_pkg::BoardRegPerfSel) begin
      perf_sel_q <= reg_wdata_i[7:0];
    end
  end

  always_ff @(posedge clk_i) begin
    perf_rd_q <= perf;
    for (int unsigned g = 0; g < RdGroups; g++) begin
      rd_grp_q[g] <= regs_q[4*g + 32'(reg_addr_i[1:0])];
    end
    rd_ctl_q  <= rdata_d;
    rd_file_q <= {1'b0, reg_addr_i} < (AddrW+1)'(Regs);
    rd_sel_q  <= reg_addr_i[2 +: RdGrpW];
    rdata_q   <= rd_file_q ? rd_grp_q[rd_sel_q] : rd_ctl_q;
  end

  assign reg_rdata_o  = rdata_q;
  assign fb_rdata_o   = fb_out_q;
  assign busy_o       = busy;
  assign done_o       = done_q;
  assign size_error_o = size_error_q;
  assign config_error_o = config_error_q;
  assign error_o      = core_error;

  assign mon_valid_o = fb_valid;
  assign mon_pixel_o = fb_pixel;
  assign mon_rgb_o   = fb_rgb;
  assign mon_hit_o   = fb_hit;
  assign mon_tri_o   = fb_tri;
  assign mon_t_o     = fb_t;
  assign mon_u_o     = fb_u;
  assign mon_v_o     = fb_v;
  assign mon_lights_o      = fb_lights;
  assign mon_bounce_tri_o  = fb_bounce_tri;
  assign mon_refract_tri_o = fb_refract_tri;

  ////////////////
  // Assertions //
  ////////////////

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o(checks_on)
  );

  // The size check keeps every pixel inside the framebuffer.
  FbInRange_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    fb_valid |-> fb_pixel < 32'(FbPixels));
  // The generator runs only inside a frame.
  GenInFrame_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    gen_busy |-> running_q);
  // The register file's lock is the frame control's busy.
  RegLock_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    wr_ok_q == !busy);
`endif

endmodule
