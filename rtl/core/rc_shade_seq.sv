// rc_shade_seq: the shading sequencer (docs/architecture.md, "Shading"): for each traced packet,
// every existing ray's shading record and material are read and the ray shaded (rc_shade_unit),
// or given the background colour, and written to the framebuffer with its hit record; the thread
// is freed after its last write.
//
// Contract
// - Traced packets: done_valid_i (the pop unit: the walk ended) makes the thread wait for
//   shading; waiting threads are picked round robin, one packet at a time. At the pick the
//   thread's rays, hit bits and error bits are sampled (rc_thread_ctrl, through the one-hot
//   pick) and its rays' triangles read (the hit store's shade copy); a packet that met an error
//   has no hits (every ray gets the background). A packet without rays is freed at once.
// - The sequencer then takes the packet's rays 0..3 in turn, one per cycle: a ray with a hit
//   sends a shading request {tag = {thread, ray}, index = its triangle} (shd_req_*, from the
//   head register of a two-entry queue), a ray without one goes to the two-entry miss queue; an
//   absent ray is skipped. A ray waits while its queue has no room (a flip-flop).
// - A shading response stores the ray's |n| and whether it failed (per {thread, ray}) and sends
//   the material request {same tag, the record's material index; 0 after an error response}
//   (mat_req_*). A material response (taken while the shading input queue has room for every
//   response in flight: mat_rsp_ready_o, a register) reads the ray's |n|, its hit's d'z (the hit
//   store's fb copy) and its inv_len (rc_ray_store), two cycles, and queues the shading of kd
//   (zero after a failed shading or material read: black) for rc_shade_unit.
// - Framebuffer writes (fb_*, valid/ready from a queue's head register): the shaded rays first,
//   then the misses. A write's pixel id (rc_ray_store) and hit record with its d'z (the hit
//   store's fb copy; zeros for a miss) are read on its way to the queue (two cycles). One write
//   per existing ray; a thread's last write frees it (free_valid_o, two cycles after the write).
// - Secondary packets (shadow and bounce; rc_thread_ctrl's kind bit, read with the rays): no ray
//   is shaded; every ray goes the misses' way and is written with its hit record (zeros when it
//   has none: a shadow ray that reached the light, a bounce ray that left the scene) and colour
//   0, or 1 when the packet met an error (it has no hits then).
// - Errors: a failed shading or material read raises the core's bad-address bit (err_shd_o,
//   err_mat_o: the packet's own error bits are final by then).
// - Parameters: Threads; Secondary: 1 = secondary packets as above, 0 = primary packets only
//   (vm_rd_sec_i not read). Shade: 1 = primary hits shaded as above; 0 = no ray is shaded (a
//   tree controller, rc_tracer, lights the hits itself): every ray goes the misses' way and is
//   written with its hit record, a primary packet's with the background colour; the shading and
//   material ports stay idle (no requests, responses ignored), and rc_shade_unit is not built.
// - Reset: rst_ni (active low, asynchronous) clears control state.
module rc_shade_seq #(
  parameter int unsigned Threads   = rc_pkg::CoreThreads,
  parameter bit          Secondary = 1'b1,
  parameter bit          Shade     = 1'b1,
  // Derived (do not override).
  parameter int unsigned W         = rc_pkg::CoreFpW,
  parameter int unsigned ThrW      = (Threads > 1) ? $clog2(Threads) : 1,
  parameter int unsigned TagW      = rc_pkg::CoreTagBits
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,

  // Configuration (quasi-static).
  input  logic [W-1:0]         ambient_i,
  input  logic [W-1:0]         diffuse_i,
  input  logic [23:0]          background_i,

  // Traced packets.
  input  logic                 done_valid_i,
  input  logic [ThrW-1:0]      done_thr_i,
  output logic [ThrW-1:0]      vm_rd_thr_o,     // the picked thread's rays, read (rc_thread_ctrl)
  input  logic [3:0]           vm_rd_i,
  input  logic                 vm_rd_sec_i,     // the picked thread holds a secondary packet
  input  logic [Threads*4-1:0] hit_i,
  input  logic [Threads-1:0]   err_i,

  // The hit store's copies (2 cycles).
  output logic                 tri_re_o,
  output logic [ThrW-1:0]      tri_thr_o,
  input  logic [127:0]         tri_i,          // ray r's triangle at [r*32 +: 32]
  output logic                 rec_re_o,
  output logic [ThrW-1:0]      rec_thr_o,
  output logic [1:0]           rec_ray_o,
  input  logic [4*W+31:0]      rec_i,          // {dz, tri, v, u, t}
  output logic                 dz_re_o,
  output logic [ThrW-1:0]      dz_thr_o,
  output logic [1:0]           dz_ray_o,
  input  logic [W-1:0]         dz_i,
  // The ray store (2 cycles).
  output logic                 ilen_re_o,
  output logic [ThrW-1:0]      ilen_thr_o,
  output logic [1:0]           ilen_ray_o,
  input  logic [W-1:0]         ilen_i,
  output logic                 pix_re_o,
  output logic [ThrW-1:0]      pix_thr_o,
  output logic [1:0]           pix_ray_o,
  input  logic [31:0]          pix_i,

  // Shading and material ports.
  output logic                 shd_req_valid_o,
  input  logic                 shd_req_ready_i,
  output logic [TagW-1:0]      shd_req_tag_o,
  output logic [31:0]          shd_req_index_o,
  input  logic                 shd_rsp_valid_i,
  output logic                 shd_rsp_ready_o,
  input  logic [TagW-1:0]      shd_rsp_tag_i,
  input  logic [32+4*W-1:0]    shd_rsp_data_i,
  input  logic                 shd_rsp_error_i,
  output logic                 mat_req_valid_o,
  input  logic                 mat_req_ready_i,
  output logic [TagW-1:0]      mat_req_tag_o,
  output logic [31:0]          mat_req_index_o,
  input  logic                 mat_rsp_valid_i,
  output logic                 mat_rsp_ready_o,
  input  logic [TagW-1:0]      mat_rsp_tag_i,
  input  logic [95:0]          mat_rsp_data_i,
  input  logic                 mat_rsp_error_i,

  // Framebuffer write port.
  output logic                 fb_valid_o,
  input  logic                 fb_ready_i,
  output logic [31:0]          fb_pixel_o,
  output logic [23:0]          fb_rgb_o,
  output logic                 fb_hit_o,
  output logic [31:0]          fb_tri_o,
  output logic [W-1:0]         fb_t_o,
  output logic [W-1:0]         fb_u_o,
  output logic [W-1:0]         fb_v_o,
  output logic [W-1:0]         fb_dz_o,

  // Threads freed: by their last write (free_*), or at the pick for a packet without rays
  // (free0_*).
  output logic                 free_valid_o,
  output logic [ThrW-1:0]      free_thr_o,
  output logic                 free0_valid_o,
  output logic [ThrW-1:0]      free0_thr_o,

  // Errors, debug and counter events.
  output logic                 err_shd_o,
  output logic                 err_mat_o,
  output logic                 pick_valid_o,   // a packet chosen (the choice register)
  output logic [ThrW-1:0]      pick_thr_o,
  output logic                 perf_shade_o,   // a ray into rc_shade_unit
  output logic                 perf_fb_o,      // a framebuffer write
  output logic                 wd_o            // a handshake on the shading, material or fb port
);

  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned RidW    = ThrW + 2;
  localparam int unsigned NlenLsb = 8 * rc_pkg::ImageShadingFirstValue +
                                    rc_pkg::ImageShadingNormalLen * W;
  // The two queues: 8 entries each (Yosys maps a distributed-RAM FIFO of 5 or fewer entries into
  // LUTs, several times the cells of 8).
  localparam int unsigned InQD    = 8;   // shading input queue (after the reads)
  localparam int unsigned OutQD   = 8;   // framebuffer output queue

  if (Threads < 1 || RidW > TagW) begin : g_param_check
    $error("rc_shade_seq: need {thread, ray} to fit the port tags");
  end

  ///////////////////////////
  // Traced packets, pick  //
  ///////////////////////////

  logic [Threads-1:0] done_q, g_shp, gshp_q;
  logic               shp_any, shp_room, shp_v_q, st1_v_q, st2_v_q, sh_busy_q;
  logic [ThrW-1:0]    shp_idx, shp_thr_q, st1_thr_q, st2_thr_q, sh_thr_q;
  logic [3:0]         st1_vm_q, st1_hm_q, st2_vm_q, st2_hm_q, sh_vm_q, sh_hm_q;
  logic               st1_sec_q, st2_sec_q, nb_sec_q, sh_sec_q;
  logic               st1_se_q, st2_se_q, nb_se_q, sh_se_q;  // a secondary packet with an error
  logic [Threads-1:0] st1_hot_q;
  logic [1:0]         sh_r_q;
  logic               sh_last_q;
  logic [127:0]       sh_btri_q;

  rc_rr_pick #(
    .N   (Threads),
    .IdxW(ThrW)
  ) u_pick_done (
    .clk_i,
    .rst_ni,
    .req_i  (done_q),
    .take_i (shp_room),
    .valid_o(shp_any),
    .idx_o  (shp_idx),
    .grant_o(g_shp)
  );
  // The choice is registered, one-hot (gshp_q) and as its thread number (shp_thr_q): the reads
  // after it start at flip-flops.

  // A packet is chosen when the stages before the sequencer are free (shp_room, from flip-flops);
  // the choice is registered (shp), the rays and hit bits sampled through the one-hot choice, the
  // triangles read (st1, st2) into the next-packet register (nb), from which the sequencer takes
  // the packet when it is done with the one before: the next packet is read while the sequencer
  // works, five cycles a packet at most.
  logic       nb_v_q, sh_load;
  logic [ThrW-1:0] nb_thr_q;
  logic [3:0] nb_vm_q, nb_hm_q;
  logic [127:0] nb_btri_q;
  assign shp_room = ~shp_v_q & ~st1_v_q & ~st2_v_q & ~nb_v_q;
  assign sh_load  = nb_v_q & (~sh_busy_q | (adv & sh_last_q));

  logic [3:0] shp_vm, shp_hm;
  logic       shp_err;
  for (genvar r = 0; r < 4; r++) begin : g_shp_hm
    logic [Threads-1:0] hit_r;
    for (genvar t = 0; t < Threads; t++) begin : g_t
      assign hit_r[t] = hit_i[t*4 + r];
    end
    assign shp_hm[r] = |(gshp_q & hit_r);   // a reduction OR: balanced, not a chain
  end
  assign shp_err     = |(gshp_q & err_i);
  assign vm_rd_thr_o = shp_thr_q;
  assign shp_vm      = vm_rd_i;

  logic adv, to_shd, to_miss, sreq_free, miss_free, miss_v;
  logic sh_valid_r, sh_hit_r;
  logic [RidW-1:0] miss_rid;
  logic            miss_take, miss_sec, miss_hit, miss_sec_err;

  // The sequencer's two outputs, shading requests and misses, are two-entry queues whose room is
  // a flip-flop (rc_credit_fifo's credit): a ray's step depends on this unit's registers only,
  // never on the shading port's ready or the framebuffer stage. The current ray's bits are
  // bit 0 of the packet's (sh_vm_q, sh_hm_q shift down as the rays advance) and its last ray a
  // flag (sh_last_q), so a step starts at flip-flops, not at a select by the ray counter sh_r_q
  // (run 51 seed 5: sh_r_q through the select and the load into 140 enables, -1.69 ns); sh_r_q
  // only numbers the ray in the queues' data.
  assign sh_valid_r = sh_vm_q[0];
  assign sh_hit_r   = sh_hm_q[0];
  // A secondary packet's rays all go the misses' way (with their hit bit, for the record), and
  // with Shade = 0 every packet's.
  assign to_shd     = sh_busy_q & sh_valid_r & sh_hit_r & ~sh_sec_q & sreq_free;
  assign to_miss    = sh_busy_q & sh_valid_r & (~sh_hit_r | sh_sec_q | ~Shade) & miss_free;
  assign adv        = sh_busy_q & (~sh_valid_r | to_shd | to_miss);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      done_q          <= '0;
      shp_v_q         <= 1'b0;
      gshp_q          <= '0;
      shp_thr_q       <= '0;
      st1_v_q         <= 1'b0;
      st2_v_q         <= 1'b0;
      nb_v_q          <= 1'b0;
      sh_busy_q       <= 1'b0;
      sh_thr_q        <= '0;
      sh_r_q          <= '0;
      sh_last_q       <= 1'b0;
    end else begin
      done_q    <= (done_q & ~gshp_q) | h_done;
      shp_v_q   <= shp_any & shp_room;
      gshp_q    <= (shp_any & shp_room) ? g_shp : '0;
      shp_thr_q <= shp_idx;
      // A packet without rays goes no further than st1 (it is freed there).
      st1_v_q   <= shp_v_q;
      st2_v_q   <= st1_v_q & (st1_vm_q != 4'd0);
      if (st2_v_q) begin
        nb_v_q <= 1'b1;
      end else if (sh_load) begin
        nb_v_q <= 1'b0;
      end
      if (adv) begin
        sh_r_q    <= sh_r_q + 2'd1;
        sh_last_q <= sh_r_q == 2'd2;
        if (sh_last_q) sh_busy_q <= 1'b0;
      end
      if (sh_load) begin
        sh_busy_q <= 1'b1;
        sh_thr_q  <= nb_thr_q;
        sh_r_q    <= '0;
        sh_last_q <= 1'b0;
      end
    end
  end
  always_ff @(posedge clk_i) begin
    st1_thr_q <= shp_thr_q;
    st1_hot_q <= gshp_q;
    st1_vm_q  <= shp_vm;
    st1_hm_q  <= shp_hm & {4{~shp_err}};
    st1_sec_q <= Secondary & vm_rd_sec_i;
    st1_se_q  <= Secondary & vm_rd_sec_i & shp_err;
    st2_sec_q <= st1_sec_q;
    st2_se_q  <= st1_se_q;
    st2_thr_q <= st1_thr_q;
    st2_vm_q  <= st1_vm_q;
    st2_hm_q  <= st1_hm_q;
    if (st2_v_q) begin
      nb_thr_q  <= st2_thr_q;
      nb_vm_q   <= st2_vm_q;
      nb_hm_q   <= st2_hm_q;
      nb_sec_q  <= st2_sec_q;
      nb_se_q   <= st2_se_q;
      nb_btri_q <= tri_i;
    end
    if (sh_load) begin
      sh_vm_q   <= nb_vm_q;
      sh_hm_q   <= nb_hm_q;
      sh_sec_q  <= nb_sec_q;
      sh_se_q   <= nb_se_q;
      sh_btri_q <= nb_btri_q;
    end else if (adv) begin
      sh_vm_q   <= sh_vm_q >> 1;
      sh_hm_q   <= sh_hm_q >> 1;
    end
  end
  assign tri_re_o  = shp_v_q;
  assign tri_thr_o = shp_thr_q;

  rc_credit_fifo #(
    .Width(3 + RidW),
    .Depth(2)
  ) u_miss_q (
    .clk_i,
    .rst_ni,
    .take_i    (to_miss),
    .credit_o  (miss_free),
    .wr_valid_i(to_miss),
    .wr_data_i ({sh_sec_q, (sh_sec_q | ~Shade) & sh_hit_r, sh_se_q, sh_thr_q, sh_r_q}),
    .valid_o   (miss_v),
    .ready_i   (miss_take),
    .data_o    ({miss_sec, miss_hit, miss_sec_err, miss_rid})
  );

  // The shading path: shading requests, the shading and material responses, rc_shade_unit
  // (Shade = 0: none of it; the ports stay idle).
  logic            port_hs;
  logic            sho_v, sho_ready;
  logic [RidW-1:0] sho_rid;
  logic [23:0]     sho_rgb;
  if (Shade) begin : g_shade
    logic [RidW-1:0] shd_req_rid;
    rc_credit_fifo #(
      .Width(RidW + 32),
      .Depth(2)
    ) u_shd_req_q (
      .clk_i,
      .rst_ni,
      .take_i    (to_shd),
      .credit_o  (sreq_free),
      .wr_valid_i(to_shd),
      .wr_data_i ({rc_pkg::lane32(sh_btri_q, sh_r_q), sh_thr_q, sh_r_q}),
      .valid_o   (shd_req_valid_o),
      .ready_i   (shd_req_ready_i),
      .data_o    ({shd_req_index_o, shd_req_rid})
    );
    assign shd_req_tag_o = TagW'(shd_req_rid);

    ////////////////////////////////////
    // Shading record -> material     //
    ////////////////////////////////////

    logic            mat_req_valid_q, sr_take, mreq_free;
    logic [RidW-1:0] mat_req_rid_q, sr_rid;
    logic [31:0]     mat_req_index_q;

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
    assign mat_req_valid_o = mat_req_valid_q;
    assign mat_req_tag_o   = TagW'(mat_req_rid_q);
    assign mat_req_index_o = mat_req_index_q;

    logic            ma_take;
    logic [RidW-1:0] mr_rid;

    // |n| and whether the shading read failed, per {thread, ray}: written at the shading response,
    // read at the material response (which comes after its request, so after the write).
    logic [W:0] nl_rd;
    rc_ram #(
      .Width (W + 1),
      .Depth (4 << ThrW),
      .OutReg(1'b1)
    ) u_nlen (
      .clk_i,
      .we_i   (sr_take),
      .waddr_i(sr_rid),
      .wdata_i({shd_rsp_error_i, shd_rsp_data_i[NlenLsb +: W]}),
      .re_i   (ma_take),
      .raddr_i(mr_rid),
      .rdata_o(nl_rd)
    );

    //////////////////////////////
    // Material -> shading unit //
    //////////////////////////////

    // A material response is taken while the input queue has room for it and every response in
    // the two read stages (m1, m2): ma_room_q, from the queue's count a cycle ago.
    logic            ma_room_q, m1_v_q, m2_v_q, m1_bad_q, m2_bad_q;
    logic [RidW-1:0] m1_rid_q, m2_rid_q;
    logic [3*W-1:0]  m1_kd_q, m2_kd_q;
    logic [$clog2(InQD+1)-1:0] iq_cnt;
    logic            iq_valid, sh_ready;
    logic [RidW+6*W-1:0] iq_data;
    logic [RidW-1:0] iq_rid;
    logic [W-1:0]    iq_dz, iq_nlen, iq_ilen;
    logic [3*W-1:0]  iq_kd;

    assign mr_rid          = mat_rsp_tag_i[RidW-1:0];
    assign mat_rsp_ready_o = ma_room_q;
    assign ma_take         = mat_rsp_valid_i & ma_room_q;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        m1_v_q    <= 1'b0;
        m2_v_q    <= 1'b0;
        ma_room_q <= 1'b1;
      end else begin
        m1_v_q    <= ma_take;
        m2_v_q    <= m1_v_q;
        // Room for a response taken now: the queue's entries, the two read stages and this one.
        ma_room_q <= 32'(iq_cnt) + 32'(m1_v_q) + 32'(m2_v_q) + 32'(ma_take) + 1 <= InQD;
      end
    end
    always_ff @(posedge clk_i) begin
      m1_rid_q <= mr_rid;
      m1_bad_q <= mat_rsp_error_i;
      m1_kd_q  <= {mat_rsp_data_i[64 +: W], mat_rsp_data_i[32 +: W], mat_rsp_data_i[0 +: W]};
      m2_rid_q <= m1_rid_q;
      m2_bad_q <= m1_bad_q;
      m2_kd_q  <= m1_kd_q;
    end
    assign dz_re_o    = ma_take;
    assign dz_thr_o   = mr_rid[RidW-1:2];
    assign dz_ray_o   = mr_rid[1:0];
    assign ilen_re_o  = ma_take;
    assign ilen_thr_o = mr_rid[RidW-1:2];
    assign ilen_ray_o = mr_rid[1:0];

    rc_fifo #(
      .Width(RidW + 6 * W),
      .Depth(InQD)
    ) u_in_q (
      .clk_i,
      .rst_ni,
      .push_i (m2_v_q),
      .data_i ({m2_rid_q, (m2_bad_q | nl_rd[W]) ? {3*W{1'b0}} : m2_kd_q, ilen_i, nl_rd[W-1:0],
                dz_i}),
      .valid_o(iq_valid),
      .ready_i(sh_ready),
      .data_o (iq_data),
      .count_o(iq_cnt)
    );
    assign {iq_rid, iq_kd, iq_ilen, iq_nlen, iq_dz} = iq_data;

    rc_shade_unit #(
      .ExpW (rc_pkg::Fp24ExpW),
      .FracW(rc_pkg::Fp24FracW),
      .TagW (RidW)
    ) u_shade (
      .clk_i,
      .rst_ni,
      .valid_i  (iq_valid),
      .ready_o  (sh_ready),
      .tag_i    (iq_rid),
      .dz_i     (iq_dz),
      .nlen_i   (iq_nlen),
      .inv_len_i(iq_ilen),
      .kd_i     (iq_kd),
      .ambient_i(ambient_i),
      .diffuse_i(diffuse_i),
      .valid_o  (sho_v),
      .ready_i  (sho_ready),
      .tag_o    (sho_rid),
      .rgb_o    (sho_rgb)
    );

    assign err_shd_o    = sr_take & shd_rsp_error_i;
    assign err_mat_o    = ma_take & mat_rsp_error_i;
    assign perf_shade_o = iq_valid & sh_ready;
    assign port_hs      = (shd_req_valid_o & shd_req_ready_i) | sr_take |
                          (mat_req_valid_q & mat_req_ready_i) | ma_take;
  end else begin : g_none
    assign sreq_free       = 1'b0;
    assign shd_req_valid_o = 1'b0;
    assign shd_req_tag_o   = '0;
    assign shd_req_index_o = '0;
    assign shd_rsp_ready_o = 1'b1;
    assign mat_req_valid_o = 1'b0;
    assign mat_req_tag_o   = '0;
    assign mat_req_index_o = '0;
    assign mat_rsp_ready_o = 1'b1;
    assign dz_re_o         = 1'b0;
    assign dz_thr_o        = '0;
    assign dz_ray_o        = '0;
    assign ilen_re_o       = 1'b0;
    assign ilen_thr_o      = '0;
    assign ilen_ray_o      = '0;
    assign sho_v           = 1'b0;
    assign sho_rid         = '0;
    assign sho_rgb         = '0;
    assign err_shd_o       = 1'b0;
    assign err_mat_o       = 1'b0;
    assign perf_shade_o    = 1'b0;
    assign port_hs         = 1'b0;
    logic unused_none;
    assign unused_none = ^{shd_req_ready_i, shd_rsp_valid_i, shd_rsp_error_i, mat_req_ready_i,
                           mat_rsp_valid_i, mat_rsp_error_i, dz_i, ilen_i, sho_ready,
                           ambient_i, diffuse_i, sh_btri_q};
  end

  ////////////////////////
  // Framebuffer writes //
  ////////////////////////

  // A write (a shaded ray first, else a miss) is taken while the output queue has room for it and
  // the two read stages (f1, f2); its pixel id and hit record are read on the way.
  logic            f_take, f_hit, f_room_q, f1_v_q, f2_v_q, f1_hit_q, f2_hit_q;
  logic [RidW-1:0] f_rid, f1_rid_q, f2_rid_q;
  logic [23:0]     f_rgb, f1_rgb_q, f2_rgb_q;
  logic [$clog2(OutQD+1)-1:0] oq_cnt;
  logic [ThrW+32+24+1+32+4*W-1:0] oq_data;
  logic            fb_take;
  logic [W-1:0]    rec_t, rec_u, rec_v, rec_dz;
  logic [31:0]     rec_tri;

  assign f_take    = (sho_v | miss_v) & f_room_q;
  assign f_hit     = sho_v | miss_hit;
  assign f_rid     = sho_v ? sho_rid : miss_rid;
  assign f_rgb     = sho_v ? sho_rgb : (miss_sec ? {23'd0, miss_sec_err} : background_i);
  assign sho_ready = f_room_q;
  assign miss_take = miss_v & f_room_q & ~sho_v;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      f1_v_q   <= 1'b0;
      f2_v_q   <= 1'b0;
      f_room_q <= 1'b1;
    end else begin
      f1_v_q   <= f_take;
      f2_v_q   <= f1_v_q;
      f_room_q <= 32'(oq_cnt) + 32'(f1_v_q) + 32'(f2_v_q) + 32'(f_take) + 1 <= OutQD;
    end
  end
  always_ff @(posedge clk_i) begin
    f1_rid_q <= f_rid;
    f1_hit_q <= f_hit;
    f1_rgb_q <= f_rgb;
    f2_rid_q <= f1_rid_q;
    f2_hit_q <= f1_hit_q;
    f2_rgb_q <= f1_rgb_q;
  end
  assign rec_re_o  = f_take;
  assign rec_thr_o = f_rid[RidW-1:2];
  assign rec_ray_o = f_rid[1:0];
  assign pix_re_o  = f_take;
  assign pix_thr_o = f_rid[RidW-1:2];
  assign pix_ray_o = f_rid[1:0];
  assign {rec_dz, rec_tri, rec_v, rec_u, rec_t} = rec_i;

  logic [ThrW-1:0] oq_thr;
  rc_fifo #(
    .Width(ThrW + 32 + 24 + 1 + 32 + 4 * W),
    .Depth(OutQD)
  ) u_out_q (
    .clk_i,
    .rst_ni,
    .push_i (f2_v_q),
    .data_i ({f2_rid_q[RidW-1:2], pix_i, f2_rgb_q, f2_hit_q, f2_hit_q ? rec_tri : 32'd0,
              f2_hit_q ? rec_t : {W{1'b0}}, f2_hit_q ? rec_u : {W{1'b0}},
              f2_hit_q ? rec_v : {W{1'b0}}, f2_hit_q ? rec_dz : {W{1'b0}}}),
    .valid_o(fb_valid_o),
    .ready_i(fb_ready_i),
    .data_o (oq_data),
    .count_o(oq_cnt)
  );
  assign {oq_thr, fb_pixel_o, fb_rgb_o, fb_hit_o, fb_tri_o, fb_t_o, fb_u_o, fb_v_o, fb_dz_o} =
      oq_data;
  assign fb_take = fb_valid_o & fb_ready_i;

  // Writes still due per thread: set as shading takes the packet (st1), counted down by writes
  // (registered first: fbt_*), the last one frees the thread (a packet without rays is freed at
  // st1). A thread's count is set only after its last write has freed it, so the two never meet.
  logic [Threads*3-1:0] fbw_q;
  logic [Threads-1:0]   h_done, h_fb, fbt_hot_q;
  logic                 fbt_v_q;
  logic [ThrW-1:0]      fbt_thr_q;
  // The write's thread is registered one-hot (fbt_hot_q), so the per-thread counts and their
  // read start at flip-flops.
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_fb (.valid_i(fb_take), .idx_i(oq_thr), .hot_o(h_fb));
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fbt_v_q   <= 1'b0;
      fbt_thr_q <= '0;
      fbt_hot_q <= '0;
    end else begin
      fbt_v_q   <= fb_take;
      fbt_thr_q <= oq_thr;
      fbt_hot_q <= h_fb;
    end
  end
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_done (.valid_i(done_valid_i), .idx_i(done_thr_i),
                                                   .hot_o(h_done));
  logic                 free_v, free0_v;
  logic [ThrW-1:0]      free_thr, free0_thr;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fbw_q <= '0;
    end else begin
      for (int unsigned t = 0; t < Threads; t++) begin
        if (st1_hot_q[t]) begin
          fbw_q[t*3 +: 3] <= rc_pkg::ray_count(st1_vm_q);
        end else if (fbt_hot_q[t]) begin
          fbw_q[t*3 +: 3] <= fbw_q[t*3 +: 3] - 3'd1;
        end
      end
    end
  end
  logic [2:0] fb_cnt;
  for (genvar b = 0; b < 3; b++) begin : g_fb_cnt
    logic [Threads-1:0] fbw_b;
    for (genvar t = 0; t < Threads; t++) begin : g_t
      assign fbw_b[t] = fbw_q[t*3 + b];
    end
    assign fb_cnt[b] = |(fbt_hot_q & fbw_b);
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      free_v    <= 1'b0;
      free_thr  <= '0;
      free0_v   <= 1'b0;
      free0_thr <= '0;
    end else begin
      free_v    <= fbt_v_q && fb_cnt == 3'd1;
      free_thr  <= fbt_thr_q;
      free0_v   <= st1_v_q && st1_vm_q == 4'd0;
      free0_thr <= st1_thr_q;
    end
  end
  assign free_valid_o  = free_v;
  assign free_thr_o    = free_thr;
  assign free0_valid_o = free0_v;
  assign free0_thr_o   = free0_thr;

  assign pick_valid_o = shp_v_q;
  assign pick_thr_o   = shp_thr_q;
  assign perf_fb_o    = fb_take;
  assign wd_o         = port_hs | fb_take;

  logic unused_bits;
  assign unused_bits = ^{shd_rsp_tag_i, shd_rsp_data_i, mat_rsp_tag_i, mat_rsp_data_i,
                         f2_rid_q};

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // A thread waits for shading once.
  DoneOnce_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               done_valid_i |-> !done_q[done_thr_i] || gshp_q[done_thr_i]);
  // The next-packet register is free when a packet's read completes (one packet between the
  // choice and the sequencer).
  NextFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               st2_v_q |-> !nb_v_q);
  // The pick's one-hot grant is its thread.
  ShadeGrant_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 shp_v_q |-> gshp_q == (Threads'(1) << shp_thr_q));
  // The sequencer's last-ray flag is its ray counter at 3 (the step's control reads the flag).
  LastRay_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              sh_busy_q |-> sh_last_q == (sh_r_q == 2'd3));
  // A write belongs to a thread with writes due.
  FbDue_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            fbt_v_q |-> fb_cnt != 3'd0);
`endif

endmodule
