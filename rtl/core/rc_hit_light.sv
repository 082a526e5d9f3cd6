// rc_hit_light: the lighting of a packet's hits (docs/architecture.md, "Lighting", "Reflection",
// "Refraction"): each hit's geometry (rc_hit_geom) and, for each light of the configuration in
// order, the light's sample at each of the packet's hits (rc_light_term), so that a light's
// samples for one packet (its shadow packet's lanes) leave one after the other: the hits' part of
// rc::lit_work() (tb/golden/trace.hpp).
//
// Contract
// - Input: hits, a packet's hits consecutively (1 to 4 of them, in lane order; the caller gives
//   only the lanes with a hit), last_i on the packet's last one.
// - Function: per hit taken, exactly
//     h = hit_geometry(ray, t_i, dz_i, n_i, eta_enter_i, eta_leave_i, w_i, mirror_i, transmit_i)
//   and per light l = 0 .. light_count_i - 1 and hit,
//     s = light_sample({h.p, h.n, h.v}, light l, kd_i, ks_i, ns_i, w_i),
//     a = ambient_terms(kd_i, w_i)
//   bit for bit, with ray = {org_i, dir_i, inv_len_i} and light l = {light_dir_i[l],
//   light_pos_i[l], light_col_i[l]} (vectors at [(3l + a)*W +: W]). Vector ports hold component
//   or channel a at [a*W +: W] (W = 1 + ExpW + FracW), fixed-point ports channel c at
//   [c*(FixBits+1) +: FixBits+1], as rc_hit_geom and rc_light_term.
// - Outputs: two streams.
//     geo_*: one record per hit, in the order the hits were taken: h.p, h.r (mirror direction),
//            h.t (refraction direction), the children's weights and flags (what the hit's mirror
//            and refraction rays need).
//     lt_*:  light_count_i x (the packet's hits) records per packet, packets in order, and in a
//            packet light by light, each light's hits in order: the hit's tag, the light's index,
//            lt_lane_last_o (the light's last hit of the packet: its shadow packet is complete),
//            lt_light_last_o (the packet's last light), the shadow ray's origin h.p (lt_org_o),
//            s's present, direction lh (meaningful when present), t_hi and term, and a (the same
//            for every light).
//   A packet taken while light_count_i is 0 has its geo records only.
// - Structure: a hit enters rc_hit_geom with last_i, kd_i, ks_i, ns_i and w_i in its tag; its
//   result goes to the geo FIFO and, with lights, into a lane memory (distributed RAM, two banks
//   of four lanes: point, normal, view, material and tag) that a packet fills while the other
//   bank's packet issues its rc_light_term jobs, light by light and lane by lane (the light's
//   configuration chosen by an AND-OR select of the light index). The jobs' tags carry the hit's
//   tag, the light's index, the two last flags and h.p, so lt_* is rc_light_term's output FIFO.
// - Handshake: valid_i/ready_o in (rc_hit_geom's: ready_o is flip-flops only and never depends
//   on valid_i); geo_valid_o/geo_ready_i and lt_valid_o/lt_ready_i out, each with backpressure;
//   no valid depends on its ready. Nothing is dropped or duplicated.
// - Throughput: one hit per Period cycles while light_count_i <= 1 and both outputs are ready;
//   one per Period x light_count_i cycles with more lights (rc_hit_geom and rc_light_term each
//   take one job per Period cycles).
// - Configuration: ambient_i, light_count_i (0 .. MaxLights) and the lights are quasi-static:
//   they may change only while no hit is in the unit. The unit registers them (a change is seen
//   from the next cycle on, before a hit taken after it reaches them).
// - Parameters: ExpW, FracW: the number format; TagW: tag bits (>= 1); MaxLights (>= 1):
//   docs/spec.toml [light] max_lights; FixBits, ExpBits: [light] fixed_bits, exponent_bits;
//   Period: [light] unit_period, the cycles per hit of rc_hit_geom and per job of rc_light_term.
// - Illegal input: light_count_i above MaxLights; a packet of more than 4 hits (assertions catch
//   both).
// - Reset: rst_ni (active low, asynchronous) clears control state only.
module rc_hit_light #(
  parameter int unsigned ExpW      = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW     = rc_pkg::Fp24FracW,
  parameter int unsigned TagW      = 8,
  parameter int unsigned MaxLights = rc_pkg::LightMaxLights,
  parameter int unsigned FixBits   = rc_pkg::LightFixedBits,
  parameter int unsigned ExpBits   = rc_pkg::LightExponentBits,
  parameter int unsigned Period    = rc_pkg::LightUnitPeriod,
  // Derived (do not override).
  parameter int unsigned W         = 1 + ExpW + FracW,
  parameter int unsigned FW        = FixBits + 1,
  parameter int unsigned LightW    = (MaxLights > 1) ? $clog2(MaxLights) : 1,
  parameter int unsigned CountW    = $clog2(MaxLights + 1)
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,

  // Configuration (quasi-static).
  input  logic [W-1:0]             ambient_i,
  input  logic [CountW-1:0]        light_count_i,
  input  logic [MaxLights-1:0]     light_dir_i,   // light l is directional
  input  logic [MaxLights*3*W-1:0] light_pos_i,   // its position, or the vector toward it
  input  logic [MaxLights*3*W-1:0] light_col_i,   // its colour x intensity

  // A hit.
  input  logic                     valid_i,
  output logic                     ready_o,
  input  logic [TagW-1:0]          tag_i,
  input  logic                     last_i,        // the packet's last hit
  input  logic [3*W-1:0]           org_i,
  input  logic [3*W-1:0]           dir_i,
  input  logic [W-1:0]             inv_len_i,
  input  logic [W-1:0]             t_i,
  input  logic [W-1:0]             dz_i,
  input  logic [3*W-1:0]           n_i,           // the triangle's unit normal
  input  logic [W-1:0]             eta_enter_i,
  input  logic [W-1:0]             eta_leave_i,
  input  logic [W-1:0]             w_i,           // the ray's weight
  input  logic [W-1:0]             mirror_i,
  input  logic [W-1:0]             transmit_i,
  input  logic [3*W-1:0]           kd_i,
  input  logic [3*W-1:0]           ks_i,
  input  logic [ExpBits-1:0]       ns_i,          // the material's integer exponent

  // Its geometry.
  output logic                     geo_valid_o,
  input  logic                     geo_ready_i,
  output logic [TagW-1:0]          geo_tag_o,
  output logic [3*W-1:0]           geo_p_o,
  output logic [3*W-1:0]           geo_r_o,
  output logic [3*W-1:0]           geo_refr_o,
  output logic [W-1:0]             geo_w_mirror_o,
  output logic [W-1:0]             geo_w_refract_o,
  output logic                     geo_mirror_o,
  output logic                     geo_refract_o,

  // Its light samples.
  output logic                     lt_valid_o,
  input  logic                     lt_ready_i,
  output logic [TagW-1:0]          lt_tag_o,
  output logic [LightW-1:0]        lt_light_o,
  output logic                     lt_lane_last_o,
  output logic                     lt_light_last_o,
  output logic [3*W-1:0]           lt_org_o,
  output logic                     lt_present_o,
  output logic [3*W-1:0]           lt_dir_o,
  output logic [W-1:0]             lt_t_hi_o,
  output logic [3*FW-1:0]          lt_term_o,
  output logic [3*FW-1:0]          lt_amb_o
);

  if (TagW < 1 || MaxLights < 1) begin : g_param_check
    $error("rc_hit_light: TagW and MaxLights must be at least 1");
  end

  //////////////////
  // The geometry //
  //////////////////

  localparam int unsigned MatW  = 6 * W + ExpBits + W;  // kd, ks, ns, w
  localparam int unsigned GTagW = TagW + 1 + MatW;

  logic              hg_valid, hg_ready, hg_back, hg_mirror, hg_refract;
  logic [GTagW-1:0]  hg_tag;
  logic [3*W-1:0]    hg_p, hg_n, hg_v, hg_r, hg_refr;
  logic [W-1:0]      hg_w_mirror, hg_w_refract;

  rc_hit_geom #(
    .ExpW  (ExpW),
    .FracW (FracW),
    .TagW  (GTagW),
    .Period(Period)
  ) u_geom (
    .clk_i,
    .rst_ni,
    .valid_i,
    .ready_o,
    .tag_i      ({tag_i, last_i, kd_i, ks_i, ns_i, w_i}),
    .org_i,
    .dir_i,
    .inv_len_i,
    .t_i,
    .dz_i,
    .n_i,
    .eta_enter_i,
    .eta_leave_i,
    .w_i,
    .mirror_i,
    .transmit_i,
    .valid_o    (hg_valid),
    .ready_i    (hg_ready),
    .tag_o      (hg_tag),
    .back_o     (hg_back),
    .p_o        (hg_p),
    .n_o        (hg_n),
    .v_o        (hg_v),
    .r_o        (hg_r),
    .refr_o     (hg_refr),
    .w_mirror_o (hg_w_mirror),
    .w_refract_o(hg_w_refract),
    .mirror_o   (hg_mirror),
    .refract_o  (hg_refract)
  );

  logic unused_back;
  assign unused_back = hg_back;  // the facing normal is what the lights need

  /////////////////////////////////////////////////
  // The split: the geo FIFO and the lane memory //
  /////////////////////////////////////////////////

  // A geometry result is taken when the geo FIFO has room and, unless there are no lights, the
  // lane memory's fill bank is free.
  localparam int unsigned GeoW     = TagW + 9 * W + 2 * W + 2;
  localparam int unsigned GeoDepth = 2;
  localparam int unsigned CntFW    = $clog2(GeoDepth + 1);
  localparam int unsigned LaneW    = TagW + 9 * W + MatW;  // tag, p, n, v, kd, ks, ns, w

  logic              no_lights, hg_take, hg_last, fill_bank_full;
  logic [CntFW-1:0]  geo_count;
  logic [TagW-1:0]   hg_tag_hit;
  logic [MatW-1:0]   hg_mat;
  logic [1:0]        full_q;        // bank b holds a packet whose light jobs are not all issued
  logic [1:0]        full_set, full_clr;
  logic              wb_q, rb_q;    // the bank being filled, the bank issuing
  logic [1:0]        wk_q;          // the next lane to fill
  logic [3:0]        lanes_q;       // bank b's last lane at [2b +: 2]

  // The configuration is registered here, loaded in every cycle (cfg_*_q): the register file
  // that holds it is across the die, and its nets ran into the split's and the issue side's
  // control. It is quasi-static, and a hit reaches the split many cycles after it enters
  // rc_hit_geom, so the registers hold the configuration it was taken with.
  logic               cfg_none_q;     // no lights
  logic [CountW-1:0]  cfg_last_q;     // the last light's index, light_count_i - 1
  logic [W-1:0]       cfg_amb_q;
  always_ff @(posedge clk_i) begin
    cfg_none_q <= light_count_i == '0;
    cfg_last_q <= light_count_i - CountW'(1);
    cfg_amb_q  <= ambient_i;
  end

  assign {hg_tag_hit, hg_last, hg_mat} = hg_tag;
  assign no_lights      = cfg_none_q;
  assign fill_bank_full = wb_q ? full_q[1] : full_q[0];
  // The geometry side's ready is a register (hg_ready_q), loaded with the next cycle's room
  // (HgReady_A): it pops rc_hit_geom's output FIFO and writes the lane memory, a thousand
  // enables, which thus start at two flip-flops (the FIFO's valid and this).
  logic             hg_ready_q, hg_ready_d, wb_d;
  logic [1:0]       full_d;
  logic [CntFW-1:0] geo_count_d;
  logic             geo_pop;
  assign geo_pop        = geo_valid_o & geo_ready_i;
  assign hg_ready       = hg_ready_q;
  assign hg_take        = hg_valid & hg_ready;
  assign full_d         = (full_q | full_set) & ~full_clr;
  assign wb_d           = wb_q ^ (fill & hg_last);
  assign geo_count_d    = geo_count + CntFW'(hg_take) - CntFW'(geo_pop);
  assign hg_ready_d     = (geo_count_d != CntFW'(GeoDepth)) &
                          ((light_count_i == '0) | ~(wb_d ? full_d[1] : full_d[0]));
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) hg_ready_q <= 1'b1;  // empty: room, and no bank full
    else hg_ready_q <= hg_ready_d;
  end

  rc_fifo #(
    .Width   (GeoW),
    .Depth   (GeoDepth),
    .MemArray(1'b0)
  ) u_geo_fifo (
    .clk_i,
    .rst_ni,
    .push_i (hg_take),
    .data_i ({hg_tag_hit, hg_p, hg_r, hg_refr, hg_w_mirror, hg_w_refract, hg_mirror, hg_refract}),
    .valid_o(geo_valid_o),
    .ready_i(geo_ready_i),
    .data_o ({geo_tag_o, geo_p_o, geo_r_o, geo_refr_o, geo_w_mirror_o, geo_w_refract_o,
              geo_mirror_o, geo_refract_o}),
    .count_o(geo_count)
  );

  // The lane memory: entry {bank, lane}, written at the fill side, read asynchronously at the
  // issue side (distributed RAM).
  logic [LaneW-1:0] lane_mem_q [8];
  logic             fill;
  assign fill = hg_take & ~no_lights;
  always_ff @(posedge clk_i) begin
    if (fill) lane_mem_q[{wb_q, wk_q}] <= {hg_tag_hit, hg_p, hg_n, hg_v, hg_mat};
  end

  // The issue side: light rl_q of lane rk_q of bank rb_q.
  logic [LightW-1:0]  rl_q;
  logic [1:0]         rk_q;
  logic               iss_valid, lt_take, lt_ready, lane_last, light_last;
  logic [TagW-1:0]    iss_tag;
  logic [3*W-1:0]     iss_p, iss_n, iss_view, iss_kd, iss_ks;
  logic [ExpBits-1:0] iss_ns;
  logic [W-1:0]       iss_w;

  assign iss_valid  = rb_q ? full_q[1] : full_q[0];
  assign {iss_tag, iss_p, iss_n, iss_view, iss_kd, iss_ks, iss_ns, iss_w} =
      lane_mem_q[{rb_q, rk_q}];
  assign lane_last  = rk_q == lanes_q[2*rb_q +: 2];
  assign light_last = CountW'(rl_q) == cfg_last_q;
  assign lt_take    = iss_valid & lt_ready;

  always_comb begin
    full_set = '0;
    full_clr = '0;
    full_set[wb_q] = fill & hg_last;
    full_clr[rb_q] = lt_take & lane_last & light_last;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      full_q  <= '0;
      wb_q    <= 1'b0;
      wk_q    <= '0;
      lanes_q <= '0;
      rb_q    <= 1'b0;
      rk_q    <= '0;
      rl_q    <= '0;
    end else begin
      full_q <= full_d;
      if (fill) begin
        wk_q <= hg_last ? 2'd0 : wk_q + 2'd1;
        wb_q <= wb_d;
        if (hg_last) lanes_q[2*wb_q +: 2] <= wk_q;
      end
      if (lt_take) begin
        rk_q <= lane_last ? 2'd0 : rk_q + 2'd1;
        if (lane_last) begin
          rl_q <= light_last ? '0 : rl_q + LightW'(1);
          rb_q <= rb_q ^ light_last;
        end
      end
    end
  end

  // The light of the issue side's index (an AND-OR select over the configuration), registered
  // (sel_*_q, loaded in every cycle): rl_q changes only at a take, and rc_light_term takes a job
  // at most every other cycle (Period >= 2), so at a take the registers hold rl_q's light
  // (LightSel_A).
  logic             sel_dir, sel_dir_q;
  logic [3*W-1:0]   sel_pos, sel_col, sel_pos_q, sel_col_q;
  always_ff @(posedge clk_i) begin
    sel_dir_q <= sel_dir;
    sel_pos_q <= sel_pos;
    sel_col_q <= sel_col;
  end
  always_comb begin
    sel_dir = 1'b0;
    sel_pos = '0;
    sel_col = '0;
    for (int unsigned l = 0; l < MaxLights; l++) begin
      if (rl_q == LightW'(l)) begin
        sel_dir = sel_dir | light_dir_i[l];
        sel_pos = sel_pos | light_pos_i[l*3*W +: 3*W];
        sel_col = sel_col | light_col_i[l*3*W +: 3*W];
      end
    end
  end

  ////////////////////////
  // The light samples  //
  ////////////////////////

  localparam int unsigned LTagW = TagW + LightW + 2 + 3 * W;

  logic [LTagW-1:0] lt_tag;

  rc_light_term #(
    .ExpW   (ExpW),
    .FracW  (FracW),
    .TagW   (LTagW),
    .FixBits(FixBits),
    .ExpBits(ExpBits),
    .Period (Period)
  ) u_light (
    .clk_i,
    .rst_ni,
    .ambient_i  (cfg_amb_q),
    .valid_i    (iss_valid),
    .ready_o    (lt_ready),
    .tag_i      ({iss_tag, rl_q, lane_last, light_last, iss_p}),
    .p_i        (iss_p),
    .n_i        (iss_n),
    .v_i        (iss_view),
    .dir_light_i(sel_dir_q),
    .lpos_i     (sel_pos_q),
    .lcol_i     (sel_col_q),
    .kd_i       (iss_kd),
    .ks_i       (iss_ks),
    .ns_i       (iss_ns),
    .w_i        (iss_w),
    .valid_o    (lt_valid_o),
    .ready_i    (lt_ready_i),
    .tag_o      (lt_tag),
    .present_o  (lt_present_o),
    .lh_o       (lt_dir_o),
    .t_hi_o     (lt_t_hi_o),
    .term_o     (lt_term_o),
    .amb_o      (lt_amb_o)
  );

  assign {lt_tag_o, lt_light_o, lt_lane_last_o, lt_light_last_o, lt_org_o} = lt_tag;

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
  // The configuration names at most MaxLights lights.
  LightCount_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 light_count_i <= CountW'(MaxLights));
  // The issue side's light index stays below the count while it issues.
  LightIndex_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 iss_valid |-> CountW'(rl_q) < light_count_i);
  // A job is taken with its light's configuration in the select registers.
  LightSel_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               lt_take |-> {sel_dir_q, sel_pos_q, sel_col_q} ==
                                           {sel_dir, sel_pos, sel_col});
  // The registered ready is the room of this cycle.
  HgReady_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              hg_ready_q == ((geo_count != CntFW'(GeoDepth)) &
                                             (no_lights | ~fill_bank_full)));
  // A packet has at most four hits.
  PacketLanes_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  fill && wk_q == 2'd3 |-> hg_last);
`endif

endmodule
