// rc_setup_unit: the core's packet intake and ray set-up (docs/architecture.md, "Ray set-up
// unit"): takes a packet into a free thread, stores its rays, sets each ray up
// (rc::setup_ray(): 1/d and the root-box clip) and hands the packet's walk to the pop unit as its
// first walk entry: the root node with the packet's active rays and intervals.
//
// Contract
// - Threads: a thread is free when it holds no packet. It becomes free with free_valid_i or
//   free0_valid_i (shading: its last framebuffer write, or a packet without rays) and busy when
//   this unit takes a packet into it. All free at reset.
// - Packet input (rc_core's pkt_* ports, valid/ready): a packet enters an input register when it
//   is empty (pkt_ready_o: its empty flag, a flip-flop), and is taken from there into a thread
//   when a thread is free (the free-thread choice, rc_rr_pick) and the feeder is idle.
//   acc_valid_o/acc_thr_o/acc_vmask_o and the kind bits acc_anyhit_o (a shadow packet) and
//   acc_sec_o (a secondary packet), and the packet's kind acc_kind_o (rc_pkg::ray_kind_e;
//   RayPrimary when Secondary = 0) announce the take in the cycle after it, and
//   acc_hot_o the same as a one-hot vector (the free pick's grant registered: each bit drives
//   one thread's state in rc_thread_ctrl and rc_isect_issue, so no unit decodes the thread
//   number).
// - Ray stores: the feeder offers the packet's rays 0..3, one per cycle while the set-up units
//   take them, and writes per ray r, from registers in the cycle after it is taken, the ray
//   store's per-ray words (raywr_*: origin and direction; ilen and pixel id; the ray's kind,
//   start triangle and limit: {secondary, start_tri, tlim}) and, for r = axis
//   a < 3, the per-axis word of the four rays' origins and direction signs on axis a (axwr_*).
//   After the packet's last set-up result it writes the four rays' 1/d on each axis (invwr_*,
//   axes x, y, z in three cycles), then offers the start entry.
// - Secondary packets (pkt_kind_i not RayPrimary): each ray's interval ends at its pkt_t_hi_i
//   (rc_ray_setup's limit, tlim = t_hi; a primary packet's rays get tlim = +inf and their t_hi is
//   not read), and pkt_start_tri_i names the triangle each ray starts on (read by the
//   intersection issue).
// - Set-up: SetupUnits instances of rc_ray_setup (each one ray per 3 cycles) take the rays in
//   rotation, so the unit sets up SetupUnits rays per 3 cycles (3: one ray per cycle, a packet
//   per 4 cycles); results are gathered in the same rotation, so in order.
// - Start (valid/ready to the pop unit): start_item_o = {thread, sp 0, entry} with entry = the root
//   (root_node_i, checked: malformed when the node section is empty), the active rays (a ray is
//   active when it exists and tmin <= tmax) and their intervals. It is offered after the last
//   1/d word is written and held until taken.
// - Status: all_free_o = every thread free and nothing in the input register or the feeder (the
//   core is idle).
// - Parameters: Threads, SetupUnits (1 to 3); Secondary: 1 = secondary packets as above, 0 =
//   primary packets only (pkt_kind_i, pkt_t_hi_i and pkt_start_tri_i not read: every packet is
//   a primary one, and rc_ray_setup has no limit).
// - Reset: rst_ni (active low, asynchronous) frees every thread and clears control state.
module rc_setup_unit #(
  parameter int unsigned Threads    = rc_pkg::CoreThreads,
  parameter int unsigned SetupUnits = 3,
  parameter bit          Secondary  = 1'b1,
  // Derived (do not override).
  parameter int unsigned W          = rc_pkg::CoreFpW,
  parameter int unsigned ThrW       = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,

  // Configuration (quasi-static).
  input  logic [6*W-1:0]        bounds_i,
  input  logic [63:0]           root_node_i,
  input  logic [31:0]           node_count_i,
  input  logic [31:0]           list_count_i,

  // Packet input.
  input  logic                  pkt_valid_i,
  output logic                  pkt_ready_o,
  input  logic [3:0]            pkt_mask_i,
  input  logic [12*W-1:0]       pkt_org_i,
  input  logic [12*W-1:0]       pkt_dir_i,
  input  logic [4*W-1:0]        pkt_inv_len_i,
  input  logic [127:0]          pkt_pixel_i,
  input  logic [rc_pkg::RayKindBits-1:0] pkt_kind_i,
  input  logic [4*W-1:0]        pkt_t_hi_i,
  input  logic [127:0]          pkt_start_tri_i,

  // Threads freed (from shading: by a last write, and a packet without rays).
  input  logic                  free_valid_i,
  input  logic [ThrW-1:0]       free_thr_i,
  input  logic                  free0_valid_i,
  input  logic [ThrW-1:0]       free0_thr_i,

  // A packet taken (a cycle after the take).
  output logic                  acc_valid_o,
  output logic [ThrW-1:0]       acc_thr_o,
  output logic [Threads-1:0]    acc_hot_o,      // acc_valid_o && acc_thr_o == t, a register
  output logic [3:0]            acc_vmask_o,
  output logic                  acc_anyhit_o,   // a shadow packet: any hit ends a ray
  output logic                  acc_sec_o,      // a secondary packet (shadow or bounce)
  output logic [rc_pkg::RayKindBits-1:0] acc_kind_o,

  // Ray store writes.
  output logic                  raywr_valid_o,   // per ray: {thread, ray}
  output logic [ThrW-1:0]       raywr_thr_o,
  output logic [1:0]            raywr_ray_o,
  output logic [6*W-1:0]        raywr_orgdir_o,  // org x, y, z, dir x, y, z
  output logic [W+31:0]         raywr_lenpix_o,  // {pixel id, inv_len}
  output logic [W+32:0]         raywr_lim_o,     // {secondary, start triangle, tlim}
  output logic                  axwr_valid_o,    // per axis: {thread, axis}
  output logic [ThrW-1:0]       axwr_thr_o,
  output logic [1:0]            axwr_axis_o,
  output logic [4*W+3:0]        axwr_data_o,     // {dir sign of rays 3..0, org of rays 3..0}
  output logic                  invwr_valid_o,   // per axis: {thread, axis}
  output logic [ThrW-1:0]       invwr_thr_o,
  output logic [1:0]            invwr_axis_o,
  output logic [4*W-1:0]        invwr_data_o,    // 1/d of rays 3..0

  // The packet's first walk entry, to the pop unit.
  output logic                  start_valid_o,
  input  logic                  start_ready_i,
  output rc_pkg::walk_item_t    start_item_o,

  // Status and counter events.
  output logic                  all_free_o,
  output logic                  perf_packet_o,   // a packet taken (this cycle)
  output logic [2:0]            perf_rays_o,     // its rays
  output logic                  perf_setup_o     // a ray taken by a set-up unit
);

  ////////////////
  // Parameters //
  ////////////////

  localparam int unsigned NU = SetupUnits;
  localparam int unsigned UW = (NU > 1) ? $clog2(NU) : 1;
  localparam int unsigned TagW = 1 + ThrW + 2;  // {ray exists, thread, ray}

  if (Threads < 1 || SetupUnits < 1 || SetupUnits > 3 ||
      ThrW > rc_pkg::CoreThrBits) begin : g_param_check
    $error("rc_setup_unit: need 1 <= Threads <= CoreMaxThreads and SetupUnits 1 to 3");
  end

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
`endif

  function automatic logic [3*W-1:0] lane_3w(input logic [12*W-1:0] v, input logic [1:0] i);
    lane_3w = '0;
    for (int unsigned r = 0; r < 4; r++) if (i == 2'(r)) lane_3w = v[r*3*W +: 3*W];
  endfunction
  function automatic logic [W-1:0] lane_w(input logic [4*W-1:0] v, input logic [1:0] i);
    lane_w = '0;
    for (int unsigned r = 0; r < 4; r++) if (i == 2'(r)) lane_w = v[r*W +: W];
  endfunction

  //////////////////////////
  // Free threads, intake //
  //////////////////////////

  logic [Threads-1:0] free_q, g_acc, gacc_q;
  logic               acc_any, acc_take, acc_take_f, acc_v_q;
  logic               take_ok_q, take_no_q, take_ok_d;  // the take's condition (below)
  logic [ThrW-1:0]    acc_thr;
  logic               feed_busy_q, feed_busy_d;

  // The free-thread choice (from registers at more than 32 threads: rc_rr_pick's candidates) is
  // taken as it is (acc_take: its valid, the feeder idle, a packet waiting). A taken thread leaves
  // the free set a cycle after the take (gacc_q); the feeder stays busy for the packet's four
  // rays meanwhile (and above 32 threads the pick leaves out the requester it took a cycle
  // before).
  // The pick is given the take's condition alone (TakeNeedsChoice: it takes only with a choice),
  // so the choice's valid is not in the path from its candidates back into their loads (run
  // 49 seed 2: the candidates through the valid, the take and back, -2.01 ns, 10 ns routed).
  rc_rr_pick #(
    .N              (Threads),
    .IdxW           (ThrW),
    .TakeNeedsChoice(1'b1),
    .RegValid       (1'b1)
  ) u_pick_free (
    .clk_i,
    .rst_ni,
    .req_i  (free_q),
    .take_i (take_ok_q),
    .valid_o(acc_any),
    .idx_o  (acc_thr),
    .grant_o(g_acc)
  );

  // every_free_q is &free_q without a 128-input AND: busy_cnt_q counts the threads not free (a
  // take clears a bit a cycle later, with acc_v_q; each free event sets one that was clear), and
  // every_free_q registers its next value's compare with 0. (The AND built from free_q's next
  // value instead was folded by Yosys into the free pick's logic, a nanosecond deeper.)
  localparam int unsigned BcW = $clog2(Threads + 1);
  logic [BcW-1:0] busy_cnt_q, busy_cnt_d;
  logic           every_free_q;
  assign busy_cnt_d = busy_cnt_q + BcW'(acc_v_q) - BcW'(free_valid_i) - BcW'(free0_valid_i);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      acc_v_q      <= 1'b0;
      gacc_q       <= '0;
      free_q       <= '1;
      busy_cnt_q   <= '0;
      every_free_q <= 1'b1;
    end else begin
      acc_v_q      <= acc_take;
      gacc_q       <= take_ok_q ? g_acc : '0;  // g_acc is zero without a choice
      free_q       <= (free_q & ~gacc_q) | h_free | h_free0;
      busy_cnt_q   <= busy_cnt_d;
      every_free_q <= busy_cnt_d == '0;
    end
  end
  logic [Threads-1:0] h_free, h_free0;
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_free (.valid_i(free_valid_i), .idx_i(free_thr_i),
                                                   .hot_o(h_free));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_free0 (.valid_i(free0_valid_i), .idx_i(free0_thr_i),
                                                    .hot_o(h_free0));

  // The packet input register: pkt_ready_o is its empty flag (a flip-flop), so neither the
  // free-thread choice nor the feeder reaches the port's ready, and the take (a thread free, the
  // feeder idle, a packet here) is local to this unit. It refills while the feeder works on the
  // packet before, so a packet is still taken every 4 cycles.
  logic            pin_v_q;
  logic [3:0]      pin_mask_q;
  logic [12*W-1:0] pin_org_q, pin_dir_q;
  logic [4*W-1:0]  pin_ilen_q;
  logic [127:0]    pin_pix_q, pin_stri_q;
  logic [4*W-1:0]  pin_tlim_q;
  logic [rc_pkg::RayKindBits-1:0] pin_kind_q, pkt_kind;
  logic            pin_v_d;
  assign pkt_kind = Secondary ? pkt_kind_i : rc_pkg::RayPrimary;
  assign pin_v_d = pin_v_q ? ~acc_take_f : pkt_valid_i;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pin_v_q <= 1'b0;
    end else begin
      pin_v_q <= pin_v_d;
    end
  end
  always_ff @(posedge clk_i) begin
    if (!pin_v_q) begin
      pin_mask_q <= pkt_mask_i;
      pin_org_q  <= pkt_org_i;
      pin_dir_q  <= pkt_dir_i;
      pin_ilen_q <= pkt_inv_len_i;
      pin_pix_q  <= pkt_pixel_i;
      pin_kind_q <= pkt_kind;
      pin_tlim_q <= (pkt_kind != rc_pkg::RayPrimary) ? pkt_t_hi_i : {4{rc_pkg::CoreFpPosInf}};
      pin_stri_q <= pkt_start_tri_i;
    end
  end
  assign pkt_ready_o = ~pin_v_q;

  // The take's condition beside the pick (a packet waiting, the feeder idle) is registered from
  // the next values, twice: take_ok_q makes the take for the pick and the taken thread's
  // registers, and take_no_q, its inverse (rc_flag_pair), makes the feeder's copy for the feeder
  // and the input register. So neither feed_busy_q nor one net drives both sides (run 47:
  // feed_busy_q -> su_v_q, -1.12 ns, and into the pick's candidates, -0.57 ns).
  assign acc_take   = take_ok_q & acc_any;
  assign acc_take_f = ~take_no_q & acc_any;
  assign take_ok_d  = pin_v_d & ~feed_busy_d;
  rc_flag_pair u_take_ok (
    .clk_i,
    .rst_ni,
    .d_i (take_ok_d),
    .q_o (take_ok_q),
    .qn_o(take_no_q)
  );

  ////////////
  // Feeder //
  ////////////

  logic [ThrW-1:0] feed_thr_q;
  logic [1:0]      feed_r_q;
  logic [12*W-1:0] feed_org_q, feed_dir_q;
  logic [4*W-1:0]  feed_ilen_q;
  logic [127:0]    feed_pix_q, feed_stri_q;
  logic [4*W-1:0]  feed_tlim_q;
  logic [rc_pkg::RayKindBits-1:0] feed_kind_q;
  logic            feed_sec, feed_any;  // decodes of the kind: a secondary packet, a shadow packet
  assign feed_sec = feed_kind_q != rc_pkg::RayPrimary;
  assign feed_any = feed_kind_q == rc_pkg::RayShadow;
  logic [3:0]      feed_vmask_q;
  logic [NU-1:0]   su_ready_all, su_valid_all;
  logic [UW-1:0]   out_u_q;
  logic [1:0]      out_r_q;  // the ray number of the result at the head (see "Gather")
  logic            su_take;

  // The feeder's flags, so that no one flip-flop drives everything: feed_busy_q for the take and
  // the step; feed_idle_q, its inverse, enables the feeder's copy of the packet (700
  // flip-flops); each set-up unit selects its next offer from copies of its own of the idle flag
  // and the ray counter (rc_reg_copies, below; runs 59 and 60: u_feed_busy -> st_tag_q and
  // st_dir_q, -0.24 ns on run 59 seed 5, -2.41 on run 60 seed 4, one select shared by the units
  // across the chip); su_v_q[u], set-up unit u's input valid (the feeder busy and the rotation
  // at u), registered from the next values, drives that unit only (its input registers, 450
  // flip-flops each).
  //
  // su_v_q[u]'s next value is the feeder busy with the rotation at u after this cycle's take,
  // written per unit from registers so that a unit's ready (two flip-flops in the unit, across
  // the chip) meets at most two LUTs (run 48: a unit's slot_q -> su_v_q through four, -3.07 ns):
  // the valid moves on from unit u - 1 when it takes a ray that is not the packet's last
  // (last_q: feed_r_q is 3), stays at u while u is not ready, and starts at u when a packet is
  // taken with the rotation at u (arm_q[u]: the take's condition and the rotation at u, both
  // registered from the next values; acc_any, the pick's valid, completes the take).
  //
  // arm_q[u]'s next value, the take's condition and the next rotation at u, is written from the
  // state it can be reached from, so that it reads unit u - 1's ready only, not the take of
  // whichever unit holds the offer (run 71 seed 4: a unit's in_free_q into arm_q across the
  // chip, 9.36 ns of routing, -1.07 ns). A busy feeder offers at the rotation (su_v_q = hot_q,
  // SuValid_A) and cannot take (take_ok_q = 0, TakeOk_A): the condition holds after it hands
  // its last ray to unit u - 1, and the rotation moves on to u. An idle feeder offers nothing
  // (su_v_q = 0): the rotation stays, and the condition holds unless a take now makes it busy.
  logic          feed_idle_q, last_q;
  logic [3*NU-1:0] st_idle_q;
  logic [1:0]      st_r_q [3*NU];
  logic [NU-1:0] su_v_q, hot_q, hot_d, arm_q, arm_d, su_v_d;
  logic [1:0]    feed_r_d;
  assign su_take = |(su_v_q & su_ready_all);
  always_comb begin
    feed_busy_d = feed_busy_q;
    if (acc_take_f) begin
      feed_busy_d = 1'b1;
    end else if (su_take && last_q) begin
      feed_busy_d = 1'b0;
    end
    // The ray counter needs no reset at a take: the feeder is idle then, with the counter at 0
    // and no set-up unit offered a ray (FeedIdle_A, SuValid_A), so the pick's valid stays out of the
    // counter and last_q (run 70 seed 2: any_q to last_q, -0.55 ns).
    feed_r_d = su_take ? feed_r_q + 2'd1 : feed_r_q;
    for (int unsigned u = 0; u < NU; u++) begin
      hot_d[u]  = su_take ? hot_q[(u + NU - 1) % NU] : hot_q[u];
      su_v_d[u] = (su_v_q[(u + NU - 1) % NU] & su_ready_all[(u + NU - 1) % NU] & ~last_q) |
                  (su_v_q[u] & ~su_ready_all[u]) | (arm_q[u] & acc_any);
      // take_ok_d ? hot_d[u] : 0, from the reachable states (above; ArmNext_A checks it).
      arm_d[u]  = pin_v_d & ((su_v_q[(u + NU - 1) % NU] & su_ready_all[(u + NU - 1) % NU] &
                              last_q) | (~feed_busy_q & ~acc_take_f & hot_q[u]));
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      su_v_q      <= '0;
      hot_q       <= NU'(1);
      arm_q       <= '0;
      last_q      <= 1'b0;
      feed_thr_q  <= '0;
    end else begin
      su_v_q      <= su_v_d;
      hot_q       <= hot_d;
      arm_q       <= arm_d;
      last_q      <= feed_r_d == 2'd3;
      if (acc_take_f) feed_thr_q <= acc_thr;
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      feed_busy_q <= 1'b0;
    end else begin
      feed_busy_q <= feed_busy_d;
    end
  end
  // The idle flag (the inverse: a different function, so Yosys keeps it apart from feed_busy_q)
  // and the ray counter, in 3 NU + 1 kept copies: copy 0 for the feeder (feed_idle_q,
  // feed_r_q), copies 3u + 1 .. 3u + 3 for set-up unit u's offer select, one per group of its
  // registers (st_idle_q[3u + k], st_r_q[3u + k]; k = 0: the origin, 1: the direction, 2: the
  // tag and limit), so no one copy's net spans the unit's 170 multiplexers.
  logic [(3*NU+1)*3-1:0] feed_state_q;
  rc_reg_copies #(
    .Width   (3),
    .Copies  (3 * NU + 1),
    .HasReset(1'b1),
    .ResetVal(3'b100)  // idle, ray 0
  ) u_feed_state (
    .clk_i,
    .rst_ni,
    .d_i   ({~feed_busy_d, feed_r_d}),
    .q_o   (feed_state_q)
  );
  assign {feed_idle_q, feed_r_q} = feed_state_q[2:0];
  for (genvar u = 0; u < 3 * NU; u++) begin : g_state_copy
    assign {st_idle_q[u], st_r_q[u]} = feed_state_q[(u+1)*3 +: 3];
  end
  // The feeder's copy of the packet follows the input register while the feeder is idle (so the
  // take is not the enable of its 700 flip-flops): it holds the taken packet from the take on.
  always_ff @(posedge clk_i) begin
    if (feed_idle_q) begin
      feed_org_q   <= pin_org_q;
      feed_dir_q   <= pin_dir_q;
      feed_ilen_q  <= pin_ilen_q;
      feed_pix_q   <= pin_pix_q;
      feed_vmask_q <= pin_mask_q;
      feed_kind_q  <= pin_kind_q;
      feed_tlim_q  <= pin_tlim_q;
      feed_stri_q  <= pin_stri_q;
    end
  end

  assign acc_valid_o  = acc_v_q;
  assign acc_thr_o    = feed_thr_q;
  assign acc_hot_o    = gacc_q;
  assign acc_vmask_o  = feed_vmask_q;
  assign acc_anyhit_o = feed_any;
  assign acc_sec_o    = feed_sec;
  assign acc_kind_o   = feed_kind_q;

  // The ray store's words of the ray being taken.
  logic [3*W-1:0] feed_org_r, feed_dir_r;
  assign feed_org_r      = lane_3w(feed_org_q, feed_r_q);
  assign feed_dir_r      = lane_3w(feed_dir_q, feed_r_q);
  // The ray store's per-ray and per-axis writes leave through registers (a cycle after the ray
  // is taken; the words are read only after the packet's set-up, tens of cycles later).
  logic            rw_v_q, aw_v_q;
  logic [ThrW-1:0] rw_thr_q;
  logic [1:0]      rw_r_q;
  logic [6*W-1:0]  rw_orgdir_q;
  logic [W+31:0]   rw_lenpix_q;
  logic [W+32:0]   rw_lim_q;
  logic [4*W+3:0]  aw_data_q, aw_data;
  always_comb begin
    for (int unsigned r = 0; r < 4; r++) begin
      aw_data[r*W +: W] = '0;
      aw_data[4*W + r]  = 1'b0;
      for (int unsigned a = 0; a < 3; a++) begin
        if (feed_r_q == 2'(a)) begin
          aw_data[r*W +: W] = feed_org_q[(3*r+a)*W +: W];
          aw_data[4*W + r]  = feed_dir_q[(3*r+a)*W + W-1];
        end
      end
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rw_v_q <= 1'b0;
      aw_v_q <= 1'b0;
    end else begin
      rw_v_q <= su_take;
      aw_v_q <= su_take & (feed_r_q != 2'd3);
    end
  end
  always_ff @(posedge clk_i) begin
    rw_thr_q    <= feed_thr_q;
    rw_r_q      <= feed_r_q;
    rw_orgdir_q <= {feed_dir_r, feed_org_r};
    rw_lenpix_q <= {rc_pkg::lane32(feed_pix_q, feed_r_q), lane_w(feed_ilen_q, feed_r_q)};
    rw_lim_q    <= {feed_sec, rc_pkg::lane32(feed_stri_q, feed_r_q),
                    lane_w(feed_tlim_q, feed_r_q)};
    aw_data_q   <= aw_data;
  end
  assign raywr_valid_o  = rw_v_q;
  assign raywr_thr_o    = rw_thr_q;
  assign raywr_ray_o    = rw_r_q;
  assign raywr_orgdir_o = rw_orgdir_q;
  assign raywr_lenpix_o = rw_lenpix_q;
  assign raywr_lim_o    = rw_lim_q;
  assign axwr_valid_o   = aw_v_q;
  assign axwr_thr_o     = rw_thr_q;
  assign axwr_axis_o    = rw_r_q;
  assign axwr_data_o    = aw_data_q;

  ////////////////////
  // Set-up units   //
  ////////////////////

  logic [NU*TagW-1:0] su_tag_all;
  logic [NU*3*W-1:0]  su_inv_all;
  logic [NU*W-1:0]    su_tmin_all, su_tmax_all;
  logic [NU-1:0]      su_act_all;
  logic               out_ready;

  // The ray a unit is offered next, chosen a cycle ahead into a register per unit (st_*_q), so
  // a unit's input starts at flip-flops and not at the feeder's ray counter through the packet
  // copy's lane select (run 53 seed 1: feed_r_q -> a unit's ax_q, -1.63 ns, 5.22 ns on the
  // select's last net). While unit u holds no offer (su_v_q[u] low; with one unit, also while
  // it takes) its register loads the next offer's ray: ray 0 of the input register's packet
  // while the feeder is idle (an offer starts with the take), else ray
  // feed_r_q + 1 of the feeder's copy (an offer moves on to u when u - 1 takes ray feed_r_q).
  // Its enable is the unit's own valid flip-flop, so no unit's ready reaches these registers,
  // and its select is the unit's own copies of the idle flag and the ray counter, one for its
  // origin, one for its direction, one for its tag and limit.
  // The tag's thread is not staged: feed_thr_q holds it for the whole packet (staging it would
  // take it from the free pick's choice while the feeder is idle: run 54, -0.06 and 0.00 ns).
  for (genvar u = 0; u < NU; u++) begin : g_setup
    logic u_ready_i, st_en;
    logic [3*W-1:0]  st_org_q, st_dir_q, nx_org, nx_dir;
    logic [W-1:0]    st_tlim_q, nx_tlim;
    logic [2:0]      st_tag_q, nx_tag;  // {ray exists, ray}
    logic [1:0]      nx_r;
    assign u_ready_i = out_ready && out_u_q == UW'(u);
    assign st_en     = ~su_v_q[u] | ((NU == 1) & su_ready_all[u]);
    logic [1:0] nx_r_o, nx_r_d;  // the next ray by the origin's and the direction's copies
    assign nx_r_o    = st_idle_q[3*u] ? 2'd0 : st_r_q[3*u] + 2'd1;
    assign nx_r_d    = st_idle_q[3*u+1] ? 2'd0 : st_r_q[3*u+1] + 2'd1;
    assign nx_r      = st_idle_q[3*u+2] ? 2'd0 : st_r_q[3*u+2] + 2'd1;
    assign nx_org    = st_idle_q[3*u] ? pin_org_q[0 +: 3*W] : lane_3w(feed_org_q, nx_r_o);
    assign nx_dir    = st_idle_q[3*u+1] ? pin_dir_q[0 +: 3*W] : lane_3w(feed_dir_q, nx_r_d);
    assign nx_tag    = st_idle_q[3*u+2] ? {pin_mask_q[0], 2'd0} : {feed_vmask_q[nx_r], nx_r};
    assign nx_tlim   = st_idle_q[3*u+2] ? pin_tlim_q[0 +: W] : lane_w(feed_tlim_q, nx_r);
    always_ff @(posedge clk_i) begin
      if (st_en) begin
        st_org_q  <= nx_org;
        st_dir_q  <= nx_dir;
        st_tag_q  <= nx_tag;
        st_tlim_q <= nx_tlim;
      end
    end
`ifndef SYNTHESIS
    // The offer's register holds what the feeder's state says it offers.
    StagedRay_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  su_v_q[u] |-> st_org_q == feed_org_r &&
                                                st_dir_q == feed_dir_r &&
                                                st_tag_q == {feed_vmask_q[feed_r_q], feed_r_q} &&
                                                st_tlim_q == lane_w(feed_tlim_q, feed_r_q));
`endif
    rc_ray_setup #(
      .ExpW (rc_pkg::Fp24ExpW),
      .FracW(rc_pkg::Fp24FracW),
      .TagW (TagW),
      .Limit(Secondary)
    ) u_setup (
      .clk_i,
      .rst_ni,
      .valid_i (su_v_q[u]),
      .ready_o (su_ready_all[u]),
      .tag_i   ({st_tag_q[2], feed_thr_q, st_tag_q[1:0]}),
      .org_i   (st_org_q),
      .dir_i   (st_dir_q),
      .bounds_i(bounds_i),
      .tlim_i  (st_tlim_q),
      .valid_o (su_valid_all[u]),
      .ready_i (u_ready_i),
      .tag_o   (su_tag_all[u*TagW +: TagW]),
      .inv_o   (su_inv_all[u*3*W +: 3*W]),
      .tmin_o  (su_tmin_all[u*W +: W]),
      .tmax_o  (su_tmax_all[u*W +: W]),
      .active_o(su_act_all[u])
    );
  end

  // The result at the head of the rotation.
  logic            out_valid, out_take, out_active, out_exists;
  logic [TagW-1:0] out_tag;
  logic [3*W-1:0]  out_inv;
  logic [W-1:0]    out_tmin, out_tmax;
  logic [ThrW-1:0] out_thr;
  logic [1:0]      out_r;
  always_comb begin
    out_valid  = 1'b0;
    out_tag    = '0;
    out_inv    = '0;
    out_tmin   = '0;
    out_tmax   = '0;
    out_active = 1'b0;
    for (int unsigned u = 0; u < NU; u++) begin
      if (out_u_q == UW'(u)) begin
        out_valid  = su_valid_all[u];
        out_tag    = su_tag_all[u*TagW +: TagW];
        out_inv    = su_inv_all[u*3*W +: 3*W];
        out_tmin   = su_tmin_all[u*W +: W];
        out_tmax   = su_tmax_all[u*W +: W];
        out_active = su_act_all[u];
      end
    end
  end
  assign {out_exists, out_thr, out_r} = out_tag;

  ////////////
  // Gather //
  ////////////

  // A packet's results gather here in ray order (ga_*_q); with its ray 3 they move to the
  // write-out registers (wo_*_q), which write the three 1/d words and then offer the start entry.
  // Ray 3 of the next packet waits while the write-out is busy. Every packet sends all four rays
  // through the units (a ray that does not exist with its flag clear), and results come back in
  // the order fed, so the ray number at the head is a count of the results taken, out_r_q: the
  // gather's enables do not wait for the head's tag through the units' multiplexer (run 56 seed
  // 1: out_u_q -> ga_tmin_q, -0.33 ns). SetupOrder_A checks it against the tag.
  logic            wo_busy_q, wo_start_q;
  logic [1:0]      wo_a_q;
  logic [ThrW-1:0] wo_thr_q;
  logic [3:0]      wo_mask_q, ga_mask_q, ga_mask_new;
  logic [12*W-1:0] wo_inv_q;
  logic [9*W-1:0]  ga_inv_q;                 // rays 0..2 (ray 3 goes straight to wo)
  logic [4*W-1:0]  wo_tmin_q, wo_tmax_q;
  logic [3*W-1:0]  ga_tmin_q, ga_tmax_q;
  logic            start_take;

  assign out_ready = ~((out_r_q == 2'd3) & wo_busy_q);
  assign out_take  = out_valid & out_ready;
  assign start_take = start_valid_o & start_ready_i;

  always_comb begin
    for (int unsigned r = 0; r < 4; r++) begin
      ga_mask_new[r] = (out_r_q == 2'(r)) ? (out_active & out_exists) :
                       ((out_r_q == 2'd0) ? 1'b0 : ga_mask_q[r]);
    end
  end

  always_ff @(posedge clk_i) begin
    if (out_take) begin
      ga_mask_q <= ga_mask_new;
      for (int unsigned r = 0; r < 3; r++) begin
        if (out_r_q == 2'(r)) begin
          ga_inv_q[r*3*W +: 3*W] <= out_inv;
          ga_tmin_q[r*W +: W]    <= out_tmin;
          ga_tmax_q[r*W +: W]    <= out_tmax;
        end
      end
    end
    if (out_take && out_r_q == 2'd3) begin
      wo_thr_q  <= out_thr;
      wo_mask_q <= ga_mask_new;
      wo_inv_q  <= {out_inv, ga_inv_q};
      wo_tmin_q <= {out_tmin, ga_tmin_q};
      wo_tmax_q <= {out_tmax, ga_tmax_q};
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      out_u_q    <= '0;
      out_r_q    <= '0;
      wo_busy_q  <= 1'b0;
      wo_start_q <= 1'b0;
      wo_a_q     <= '0;
    end else begin
      if (out_take) out_u_q <= (out_u_q == UW'(NU - 1)) ? '0 : out_u_q + UW'(1);
      if (out_take) out_r_q <= out_r_q + 2'd1;
      if (out_take && out_r_q == 2'd3) begin
        wo_busy_q  <= 1'b1;
        wo_start_q <= 1'b0;
        wo_a_q     <= '0;
      end else if (wo_busy_q && !wo_start_q) begin
        wo_a_q <= wo_a_q + 2'd1;
        if (wo_a_q == 2'd2) wo_start_q <= 1'b1;
      end else if (start_take) begin
        wo_busy_q  <= 1'b0;
        wo_start_q <= 1'b0;
      end
    end
  end

  assign invwr_valid_o = wo_busy_q & ~wo_start_q;
  assign invwr_thr_o   = wo_thr_q;
  assign invwr_axis_o  = wo_a_q;
  always_comb begin
    for (int unsigned r = 0; r < 4; r++) begin
      invwr_data_o[r*W +: W] = '0;
      for (int unsigned a = 0; a < 3; a++) begin
        if (wo_a_q == 2'(a)) invwr_data_o[r*W +: W] = wo_inv_q[(3*r+a)*W +: W];
      end
    end
  end

  ///////////
  // Start //
  ///////////

  // The root's checks, from the quasi-static configuration through three registers (its inputs,
  // the record's sums, then the checks): a packet's start leaves the set-up pipeline tens of
  // cycles after the packet is offered, long after a configuration change has reached
  // root_chk_q. An empty node section makes the root malformed (rc::trace_packet: the root index
  // is outside the section). (Run 47: the checks in one cycle, -0.30 ns.)
  logic [1:0]                     root_chk_q;
  logic [63:0]                    root_cfg_q;
  logic [rc_pkg::NodeSumsW-1:0]   root_sums_q;
  logic [31:0]                    node_count_q, list_count_q;
  always_ff @(posedge clk_i) begin
    root_cfg_q   <= root_node_i;
    node_count_q <= node_count_i;
    list_count_q <= list_count_i;
    root_sums_q  <= rc_pkg::node_sums(root_cfg_q);
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      root_chk_q <= rc_pkg::NodeOk;
    end else begin
      root_chk_q <= (node_count_q == 32'd0) ? rc_pkg::NodeMalformed :
                    rc_pkg::node_decide(root_sums_q, 30'd0, node_count_q, list_count_q);
    end
  end

  assign start_valid_o = wo_start_q;
  always_comb begin
    start_item_o                = '0;
    start_item_o.thr            = rc_pkg::CoreThrBits'(wo_thr_q);
    start_item_o.sp             = '0;
    start_item_o.entry.node.rec = root_cfg_q;
    start_item_o.entry.node.chk = root_chk_q;
    start_item_o.entry.mask     = wo_mask_q;
    for (int unsigned r = 0; r < 4; r++) begin
      start_item_o.entry.tmin[r] = wo_tmin_q[r*W +: W];
      start_item_o.entry.tmax[r] = wo_tmax_q[r*W +: W];
    end
  end

  ////////////
  // Status //
  ////////////

  assign all_free_o    = every_free_q & ~feed_busy_q & ~pin_v_q;
  assign perf_packet_o = acc_take;
  assign perf_rays_o   = acc_take ? rc_pkg::ray_count(pin_mask_q) : 3'd0;
  assign perf_setup_o  = su_take;

`ifndef SYNTHESIS
  // acc_hot_o is the announced take's thread, one-hot.
  AccHot_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            acc_hot_o == (acc_valid_o ? Threads'(1) << acc_thr_o : '0));
  // every_free_q is the AND of the free bits.
  EveryFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                every_free_q == (&free_q));
  // The feeder's idle flag is its busy flag's inverse (both copies agree: rc_reg_copies), and
  // the idle feeder's ray counter is 0 (so a take need not reset it; SuValid_A: no unit offered).
  FeedIdle_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               feed_idle_q == !feed_busy_q && (feed_busy_q || feed_r_q == 2'd0));
  // The take's condition is its expression's value (the pair's halves agree: rc_flag_pair).
  TakeOk_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            take_ok_q == (pin_v_q & ~feed_busy_q));
  // The valids are the feeder's state: busy, at the rotation's unit; the registered parts of their
  // next values agree with the state they stand for.
  SuValid_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              $onehot(hot_q) && su_v_q == (feed_busy_q ? hot_q : '0) &&
                              arm_q == (take_ok_q ? hot_q : '0) && last_q == (feed_r_q == 2'd3));
  // arm_q's next value, written from the reachable states, is the take's condition and the
  // next rotation.
  ArmNext_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              arm_d == (take_ok_d ? hot_d : '0));
  // A packet is taken into a free thread.
  AccChoiceFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    acc_take |-> free_q[acc_thr] && gacc_q[acc_thr] == 1'b0);
  // Results come back in the rotation's order: ray r of a packet after ray r - 1 of the same one,
  // and the head's ray number is the count out_r_q.
  logic [ThrW-1:0] last_thr_q;
  logic [1:0]      last_r_q;
  always_ff @(posedge clk_i) if (out_take) {last_thr_q, last_r_q} <= {out_thr, out_r};
  SetupOrder_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 out_valid |-> out_r == out_r_q &&
                                 (out_r == 2'd0 || (out_thr == last_thr_q &&
                                                    out_r == last_r_q + 2'd1)));
  // A thread is freed only while busy.
  FreeBusy_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               (!free_valid_i || !free_q[free_thr_i]) &&
                               (!free0_valid_i || !free_q[free0_thr_i]) &&
                               !(free_valid_i && free0_valid_i && free_thr_i == free0_thr_i));
`endif

endmodule
