// rc_ray_gen: the ray generation unit. Makes the four-ray packets of a whole frame from camera
// registers, in the format's arithmetic, for rc_core's packet port.
//
// Contract
// - Function: exactly rc::raygen_ray() and rc::PacketSource (tb/golden/render.hpp) with
//   RaySource::kRayGen, bit for bit (docs/architecture.md, "Two ray sources"). For pixel (x, y),
//   with X = x and Y = y converted to the format exactly:
//     dir[a]  = (c0_i[a] + X * cx_i[a]) + Y * cy_i[a]                   (a = x, y, z)
//     inv_len = 1 / sqrt((dir[x] * dir[x] + dir[y] * dir[y]) + dir[z] * dir[z])
//     org[a]  = eye_i[a]
//   Vector ports hold component a at [a*W +: W] (W = 1 + ExpW + FracW).
// - Frame: a start_i pulse while busy_o is 0 generates the packets (px, py) of a width_i x
//   height_i frame in row-major packet order (px fastest), packet (px, py) holding ray r
//   (0..3) for pixel (2px + (r & 1), 2py + (r >> 1)) with pixel id y * width_i + x; a ray
//   whose pixel lies outside the frame is absent (pkt_mask_o bit r = 0, its data is defined but
//   meaningless). busy_o is 1 from the cycle after start_i until the frame's last packet has
//   been taken. A frame with width_i or height_i 0 has no packets (busy_o drops at once).
// - Handshake: pkt_valid_o/pkt_ready_i, the layout of rc_core's packet port (ray r's component a
//   of origin and direction at [(3r + a)*W +: W], inv_len at [r*W +: W], pixel id at
//   [r*32 +: 32]). pkt_valid_o and the packet come from registers, never depend on pkt_ready_i,
//   and hold until taken.
// - Latency: Latency cycles (the localparam: 2 + 2 * MulStages + 4 * AddStages + SqrtStages +
//   DivStages of rc_pkg's [fp_stages], 4 more with Period 6) from a ray being taken to its FIFO
//   entry; then 4 cycles to collect a packet.
// - Throughput: one ray every Period cycles while the ray FIFO has credits (RayFifoDepth rays in
//   flight or stored). The arithmetic is one component lane: x, y, z of a ray pass on
//   consecutive cycles through the multipliers and adders of the direction, then the length's
//   two sums, the square root and the divider see one operation per ray.
//   Period 3: three multipliers (X * cx, Y * cy, dir * dir) and four adders (c0 + X cx, + Y cy,
//   the length's two sums), a ray every 3 cycles: a packet every 12 cycles at best, the rate of
//   one rc_ray_setup.
//   Period 6 (the lit board, [board] lit_raygen_period): a ray is taken only at phase 0 of a
//   free-running count modulo 6, and operators whose uses fall at different phases share
//   (rc_fp_shared): X * cx and Y * cy one multiplier (Y * cy three cycles later), c0 + X cx and
//   + Y cy one adder (the second three cycles later than at Period 3), the length's two sums one
//   adder (the second a cycle later): two multipliers and two adders; and the square root and
//   the divider are iterative with two lanes (rc_fp_sqrt_iter, rc_fp_div_iter: two rays' come at
//   least 12 cycles apart). Bit for bit the same results in the same cycles.
// - Parameters: ExpW, FracW: the format; CoordW: bits of width_i/height_i (CoordW <= FracW + 1,
//   so every coordinate converts exactly); RayFifoDepth: rays buffered (>= 4); Period: 3 or 6;
//   BlockDelays: 1 = the direction's delay line in block RAM (rc_delay_line), 0 = a shift
//   register; the same rays in the same cycles.
// - Illegal input: start_i while busy_o; camera or size inputs changing while busy_o or in the
//   cycle before start_i (the last packet column and row are registered from the size).
//   Assertions catch the first and a width/height change.
// - Reset: rst_ni (active low, asynchronous) clears the control state; data registers have no
//   reset.
module rc_ray_gen #(
  parameter int unsigned ExpW         = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW        = rc_pkg::Fp24FracW,
  parameter int unsigned CoordW       = rc_pkg::BoardCoordBits,
  parameter int unsigned RayFifoDepth = rc_pkg::BoardRayFifo,
  parameter int unsigned Period       = rc_pkg::BoardRaygenPeriod,
  parameter bit          BlockDelays  = 1'b0,
  // Derived (do not override).
  parameter int unsigned W            = 1 + ExpW + FracW
) (
  input  logic              clk_i,
  input  logic              rst_ni,

  // Camera registers (quasi-static while busy_o).
  input  logic [3*W-1:0]    eye_i,
  input  logic [3*W-1:0]    c0_i,
  input  logic [3*W-1:0]    cx_i,
  input  logic [3*W-1:0]    cy_i,
  input  logic [CoordW-1:0] width_i,
  input  logic [CoordW-1:0] height_i,

  // Frame control.
  input  logic              start_i,
  output logic              busy_o,

  // Packet output (rc_core's packet port).
  output logic              pkt_valid_o,
  input  logic              pkt_ready_i,
  output logic [3:0]        pkt_mask_o,
  output logic [12*W-1:0]   pkt_org_o,
  output logic [12*W-1:0]   pkt_dir_o,
  output logic [4*W-1:0]    pkt_inv_len_o,
  output logic [127:0]      pkt_pixel_o
);

  ////////////////
  // Parameters //
  ////////////////

  if (CoordW > FracW + 1 || CoordW < 2 || CoordW > 31) begin : g_coord_check
    $error("rc_ray_gen: need 2 <= CoordW <= FracW + 1 (exact coordinates) and CoordW <= 31");
  end
  if (RayFifoDepth < 4) begin : g_fifo_check
    $error("rc_ray_gen: RayFifoDepth must be >= 4 (one packet)");
  end
  if (Period != 3 && Period != 6) begin : g_period_check
    $error("rc_ray_gen: Period must be 3 or 6");
  end

  localparam int unsigned MulStages  = rc_pkg::FpStagesMul;
  localparam int unsigned AddStages  = rc_pkg::FpStagesAdd;
  localparam int unsigned SqrtStages = rc_pkg::FpStagesSqrt;
  localparam int unsigned DivStages  = rc_pkg::FpStagesDiv;
  localparam bit          Shared     = Period == 6;
  // Period 6: + Y cy starts ShiftCy cycles later than at Period 3, the length's second sum
  // ShiftL2 cycles later (so that each shares an operator at a phase of its own).
  localparam int unsigned ShiftCy    = Shared ? 3 : 0;
  localparam int unsigned ShiftL2    = Shared ? 1 : 0;
  // Slot 0 (x) of a ray taken in cycle T is registered at T + 1; its square at
  // T + 1 + 2M + 2A + ShiftCy; y's square a cycle later starts the sum; the ray enters the FIFO at
  // T + Latency.
  localparam int unsigned Latency    = 2 + 2 * MulStages + 4 * AddStages + SqrtStages + DivStages +
                                       ShiftCy + ShiftL2;
  // The direction is complete (z in dir_sr_q) at T + 4 + M + 2A + ShiftCy and then waits for
  // inv_len.
  localparam int unsigned DirWait    = Latency - (4 + MulStages + 2 * AddStages + ShiftCy);
  localparam int unsigned Bias       = (1 << (ExpW - 1)) - 1;
  localparam logic [W-1:0] One       = W'(Bias) << FracW;

  // An unsigned coordinate (< 2^(FracW+1)) as a format value, exactly.
  function automatic logic [W-1:0] coord_to_fp(logic [CoordW-1:0] v);
    coord_to_fp = '0;
    for (int unsigned i = 0; i < CoordW; i++) begin
      if (v[i]) begin
        // The highest set bit wins (later iterations overwrite).
        coord_to_fp[FracW +: ExpW] = ExpW'(Bias + i);
        coord_to_fp[FracW-1:0]     = FracW'({v, FracW'(0)} >> i);
      end
    end
  endfunction

  ///////////////////////
  // Issue: pixel walk //
  ///////////////////////

  logic              credit, take;
  logic              issuing_q, out_busy_q;
  logic [CoordW-1:0] ipx_q, ipy_q;   // packet being issued
  logic [1:0]        ir_q;           // its ray
  logic [CoordW-1:0] pw_last_q, ph_last_q;  // packets per row and packet rows (ceil(size / 2)),
                                            // minus one
  logic              frame_empty_q;
  logic              ix_last_q, iy_last_q, ox_last_q, oy_last_q;  // the walks at their ends
  logic [CoordW-1:0] opx_q, opy_q;   // packet being assembled / offered (below)

  // The frame's last packet column and row and whether it has no packets come from registers
  // (the size is quasi-static and stable in the cycle before a start: SizeBeforeStart_A), so the
  // walks' end compares start at flip-flops instead of behind the size's arithmetic. The
  // compares themselves are registered too (the *_last_q flags, loaded every cycle): a walk's
  // position changes at most every 3 cycles (the issue side: a ray's three slots; the output
  // side: a packet's four FIFO reads), and its end is only looked at a whole packet later
  // (LastFlags_A).
  always_ff @(posedge clk_i) begin
    pw_last_q     <= CoordW'(({1'b0, width_i} + (CoordW+1)'(1)) >> 1) - CoordW'(1);
    ph_last_q     <= CoordW'(({1'b0, height_i} + (CoordW+1)'(1)) >> 1) - CoordW'(1);
    frame_empty_q <= (width_i == '0) || (height_i == '0);
    ix_last_q     <= ipx_q == pw_last_q;
    iy_last_q     <= ipy_q == ph_last_q;
    ox_last_q     <= opx_q == pw_last_q;
    oy_last_q     <= opy_q == ph_last_q;
  end
  // A ray takes three consecutive slot cycles (its x, y, z components); a new ray may start
  // only when the previous one's slots are done.
  logic [1:0] rem_q;  // slots of the current ray still to come
  logic       phase0;  // a ray may start (Period 6: phase 0 of the count modulo 6)
  assign take        = issuing_q & credit & (rem_q == 2'd0) & phase0;
  if (Shared) begin : g_phase
    logic [2:0] phase_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        phase_q <= '0;
      end else begin
        phase_q <= (phase_q == 3'd5) ? 3'd0 : phase_q + 3'd1;
      end
    end
    assign phase0 = phase_q == 3'd0;
  end else begin : g_no_phase
    assign phase0 = 1'b1;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      issuing_q <= 1'b0;
      ipx_q     <= '0;
      ipy_q     <= '0;
      ir_q      <= '0;
    end else if (start_i && !busy_o) begin
      issuing_q <= !frame_empty_q;
      ipx_q     <= '0;
      ipy_q     <= '0;
      ir_q      <= '0;
    end else if (take) begin
      ir_q <= ir_q + 2'd1;
      if (ir_q == 2'd3) begin
        if (ix_last_q) begin
          ipx_q <= '0;
          ipy_q <= ipy_q + CoordW'(1);
          if (iy_last_q) issuing_q <= 1'b0;
        end else begin
          ipx_q <= ipx_q + CoordW'(1);
        end
      end
    end
  end

  // Stage 0, one component slot per cycle: the coordinates as format values (taken with the ray)
  // and the component's camera registers.
  logic         slot, s0_valid_q, s0_first_q;
  logic [1:0]   slot_a;
  logic [W-1:0] fx_q, fy_q, c0s_q, cxs_q, cys_q;

  assign slot   = take | (rem_q != 2'd0);
  assign slot_a = take ? 2'd0 : 2'd3 - rem_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rem_q      <= '0;
      s0_valid_q <= 1'b0;
      s0_first_q <= 1'b0;
    end else begin
      rem_q      <= take ? 2'd2 : (rem_q != 2'd0 ? rem_q - 2'd1 : 2'd0);
      s0_valid_q <= slot;
      s0_first_q <= take;
    end
  end

  always_ff @(posedge clk_i) begin
    if (take) begin
      fx_q <= coord_to_fp({ipx_q[CoordW-2:0], ir_q[0]});
      fy_q <= coord_to_fp({ipy_q[CoordW-2:0], ir_q[1]});
    end
    if (slot) begin
      c0s_q <= c0_i[slot_a*W +: W];
      cxs_q <= cx_i[slot_a*W +: W];
      cys_q <= cy_i[slot_a*W +: W];
    end
  end

  ////////////////
  // Arithmetic //
  ////////////////

  // The components stream through one lane, x, y, z on consecutive cycles; `first` marks x.
  logic         d_valid, q_valid, l2_valid, sq_valid, inv_valid;
  logic [W-1:0] d, q, q_prev, l2, sq, inv;
  logic         d_first, q_first;

  rc_delay #(.Width(1), .Cycles(MulStages + 2 * AddStages + ShiftCy)) u_delay_first_d (
    .clk_i,
    .data_i(s0_first_q),
    .data_o(d_first)
  );
  // dir[a] * dir[a].
  rc_fp_mul #(.ExpW(ExpW), .FracW(FracW)) u_mul_sq (
    .clk_i, .rst_ni,
    .valid_i(d_valid),
    .a_i    (d),
    .b_i    (d),
    .valid_o(q_valid),
    .res_o  (q)
  );
  rc_delay #(.Width(1), .Cycles(2 * MulStages + 2 * AddStages + ShiftCy)) u_delay_first_q (
    .clk_i,
    .data_i(s0_first_q),
    .data_o(q_first)
  );
  // x's square and y's (the cycle after) start the length's first sum.
  logic q_first_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      q_first_q <= 1'b0;
    end else begin
      q_first_q <= q_valid & q_first;
    end
  end
  always_ff @(posedge clk_i) begin
    q_prev <= q;
  end
  // c0[a] waits for X * cx[a]; dir z^2 for the length's first sum (ShiftL2 cycles more at
  // Period 6).
  logic [W-1:0] c0_d, q_z;
  rc_delay #(.Width(W), .Cycles(MulStages)) u_delay_c0 (
    .clk_i,
    .data_i(c0s_q),
    .data_o(c0_d)
  );
  rc_delay #(.Width(W), .Cycles(AddStages - 1 + ShiftL2)) u_delay_qz (
    .clk_i,
    .data_i(q),
    .data_o(q_z)
  );

  if (!Shared) begin : g_plain
    logic         mx_valid, my_valid, s1_valid, s01_valid;
    logic [W-1:0] mx, my, my_d, s1, s01;
    // X * cx[a] and Y * cy[a].
    rc_fp_mul #(.ExpW(ExpW), .FracW(FracW)) u_mul_x (
      .clk_i, .rst_ni,
      .valid_i(s0_valid_q),
      .a_i    (fx_q),
      .b_i    (cxs_q),
      .valid_o(mx_valid),
      .res_o  (mx)
    );
    rc_fp_mul #(.ExpW(ExpW), .FracW(FracW)) u_mul_y (
      .clk_i, .rst_ni,
      .valid_i(s0_valid_q),
      .a_i    (fy_q),
      .b_i    (cys_q),
      .valid_o(my_valid),
      .res_o  (my)
    );
    // c0[a] + X * cx[a], while Y * cy[a] waits.
    rc_fp_add #(.ExpW(ExpW), .FracW(FracW)) u_add_c0 (
      .clk_i, .rst_ni,
      .valid_i(mx_valid),
      .sub_i  (1'b0),
      .a_i    (c0_d),
      .b_i    (mx),
      .valid_o(s1_valid),
      .res_o  (s1)
    );
    rc_delay #(.Width(W), .Cycles(AddStages)) u_delay_my (
      .clk_i,
      .data_i(my),
      .data_o(my_d)
    );
    // dir[a] = (c0[a] + X * cx[a]) + Y * cy[a].
    rc_fp_add #(.ExpW(ExpW), .FracW(FracW)) u_add_cy (
      .clk_i, .rst_ni,
      .valid_i(s1_valid),
      .sub_i  (1'b0),
      .a_i    (s1),
      .b_i    (my_d),
      .valid_o(d_valid),
      .res_o  (d)
    );
    // (dir x^2 + dir y^2) when y's square arrives, the cycle after x's; then + dir z^2, which
    // arrives the cycle after y's and waits AddStages - 1 cycles for the sum.
    rc_fp_add #(.ExpW(ExpW), .FracW(FracW)) u_add_q01 (
      .clk_i, .rst_ni,
      .valid_i(q_first_q),
      .sub_i  (1'b0),
      .a_i    (q_prev),
      .b_i    (q),
      .valid_o(s01_valid),
      .res_o  (s01)
    );
    rc_fp_add #(.ExpW(ExpW), .FracW(FracW)) u_add_l2 (
      .clk_i, .rst_ni,
      .valid_i(s01_valid),
      .sub_i  (1'b0),
      .a_i    (s01),
      .b_i    (q_z),
      .valid_o(l2_valid),
      .res_o  (l2)
    );
    // u_mul_y runs in lock step with u_mul_x, whose valid drives the next step.
    logic unused_valid;
    assign unused_valid = my_valid;
  end else begin : g_shared
    // Rays start at phase 0 modulo 6. Times after a ray's take (T): X * cx issues at T + 1 ..
    // T + 3 (s0_valid_q), Y * cy TimeY later on the same multiplier; c0 + X cx at
    // T + 1 + MulStages, + Y cy TimeCy after X * cx on the same adder (its operands waited: s1
    // ShiftCy cycles, Y * cy AddStages, so Y * cy is ShiftCy later than X * cx); dir leaves
    // HistW cycles after X * cx.
    localparam int unsigned TimeY  = ShiftCy;
    localparam int unsigned TimeCy = TimeY + MulStages + AddStages;
    localparam int unsigned HistW  = TimeCy + AddStages;
    // The length's sums: x^2 + y^2 at TimeL0 after the take (q_first_q), + z^2 AddStages +
    // ShiftL2 later on the same adder (the sum waited ShiftL2 cycles, z^2 AddStages).
    localparam int unsigned TimeL0 = 2 + 2 * MulStages + 2 * AddStages + ShiftCy;

    // vh_q[k]: s0_valid_q k cycles ago; lh_q[k]: q_first_q k cycles ago.
    logic [HistW:1]         vh_q;
    logic [2*AddStages+ShiftL2:1] lh_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        vh_q <= '0;
        lh_q <= '0;
      end else begin
        vh_q <= {vh_q[HistW-1:1], s0_valid_q};
        lh_q <= {lh_q[2*AddStages+ShiftL2-1:1], q_first_q};
      end
    end

    logic         mxy_valid, dsum_valid, lsum_valid;
    logic [W-1:0] cys_d, mxy, dsum, s1_d, my_d, lsum, s01_d;
    // X * cx[a], then Y * cy[a] TimeY cycles later (fy_q holds its ray until the next take, at
    // least 6 cycles after this one).
    rc_delay #(.Width(W), .Cycles(TimeY)) u_delay_cy (
      .clk_i,
      .data_i(cys_q),
      .data_o(cys_d)
    );
    rc_fp_shared #(
      .ExpW(ExpW), .FracW(FracW), .Users(2), .Period(Period),
      .Time(128'({16'(1 + TimeY), 16'(1)})), .Cycles(16'h000f)
    ) u_mul_xy (
      .clk_i, .rst_ni,
      .issue_i({vh_q[TimeY], s0_valid_q}),
      .a_i    ({fy_q, fx_q}),
      .b_i    ({cys_d, cxs_q}),
      .valid_o(mxy_valid),
      .res_o  (mxy)
    );
    rc_delay #(.Width(W), .Cycles(ShiftCy)) u_delay_s1 (
      .clk_i,
      .data_i(dsum),
      .data_o(s1_d)
    );
    rc_delay #(.Width(W), .Cycles(AddStages)) u_delay_my (
      .clk_i,
      .data_i(mxy),
      .data_o(my_d)
    );
    // c0[a] + X * cx[a], then dir[a] = (c0[a] + X * cx[a]) + Y * cy[a].
    rc_fp_shared #(
      .ExpW(ExpW), .FracW(FracW), .Add(1'b1), .Users(2), .Period(Period),
      .Time(128'({16'(1 + TimeCy), 16'(1 + MulStages)})), .Cycles(16'h000f)
    ) u_add_dir (
      .clk_i, .rst_ni,
      .issue_i({vh_q[TimeCy], vh_q[MulStages]}),
      .a_i    ({s1_d, c0_d}),
      .b_i    ({my_d, mxy}),
      .valid_o(dsum_valid),
      .res_o  (dsum)
    );
    assign d       = dsum;
    assign d_valid = vh_q[HistW];

    // dir x^2 + dir y^2, then + dir z^2.
    rc_delay #(.Width(W), .Cycles(ShiftL2)) u_delay_s01 (
      .clk_i,
      .data_i(lsum),
      .data_o(s01_d)
    );
    rc_fp_shared #(
      .ExpW(ExpW), .FracW(FracW), .Add(1'b1), .Users(2), .Period(Period),
      .Time(128'({16'(TimeL0 + AddStages + ShiftL2), 16'(TimeL0)})), .Cycles(16'h0005)
    ) u_add_len (
      .clk_i, .rst_ni,
      .issue_i({lh_q[AddStages+ShiftL2], q_first_q}),
      .a_i    ({s01_d, q_prev}),
      .b_i    ({q_z, q}),
      .valid_o(lsum_valid),
      .res_o  (lsum)
    );
    assign l2       = lsum;
    assign l2_valid = lh_q[2*AddStages+ShiftL2];

    // The shared operators' valids are both users' results; each user's own comes from vh_q or
    // lh_q.
    logic unused_valid;
    assign unused_valid = ^{mxy_valid, dsum_valid, lsum_valid};
  end

  // 1 / sqrt(|dir|^2). At Period 6 two rays' roots (and divisions) come at least 12 cycles
  // apart, so the iterative units with two lanes serve them (rc_fp_sqrt_iter, rc_fp_div_iter: a
  // lane is busy 8 and 9 cycles); at Period 3 they are pipelined.
  if (Shared) begin : g_iter
    rc_fp_sqrt_iter #(.ExpW(ExpW), .FracW(FracW), .Lanes(2)) u_sqrt (
      .clk_i, .rst_ni,
      .valid_i(l2_valid),
      .a_i    (l2),
      .valid_o(sq_valid),
      .res_o  (sq)
    );
    rc_fp_div_iter #(.ExpW(ExpW), .FracW(FracW), .Lanes(2)) u_div (
      .clk_i, .rst_ni,
      .valid_i(sq_valid),
      .a_i    (One),
      .b_i    (sq),
      .valid_o(inv_valid),
      .res_o  (inv)
    );
  end else begin : g_pipe
    rc_fp_sqrt #(.ExpW(ExpW), .FracW(FracW)) u_sqrt (
      .clk_i, .rst_ni,
      .valid_i(l2_valid),
      .a_i    (l2),
      .valid_o(sq_valid),
      .res_o  (sq)
    );
    rc_fp_div #(.ExpW(ExpW), .FracW(FracW)) u_div (
      .clk_i, .rst_ni,
      .valid_i(sq_valid),
      .a_i    (One),
      .b_i    (sq),
      .valid_o(inv_valid),
      .res_o  (inv)
    );
  end

  // The direction, collected from the stream (complete when z arrives, two cycles after x), waits
  // for its inv_len.
  logic [3*W-1:0] dir_sr_q, dir_d;
  always_ff @(posedge clk_i) begin
    dir_sr_q <= {d, dir_sr_q[3*W-1:W]};
  end
  rc_delay_line #(.Width(3*W), .Cycles(DirWait), .Block(BlockDelays)) u_delay_dir (
    .clk_i,
    .rst_ni,
    .data_i(dir_sr_q),
    .data_o(dir_d)
  );

  ////////////////////////////////
  // Ray FIFO and packet output //
  ////////////////////////////////

  logic           fifo_valid, fifo_pop;
  logic [4*W-1:0] fifo_data;  // {inv_len, dir z, y, x}

  rc_credit_fifo #(
    .Width   (4*W),
    .Depth   (RayFifoDepth),
    .MemArray(1'b1)
  ) u_fifo (
    .clk_i,
    .rst_ni,
    .take_i    (take),
    .credit_o  (credit),
    .wr_valid_i(inv_valid),
    .wr_data_i ({inv, dir_d}),
    .valid_o   (fifo_valid),
    .ready_i   (fifo_pop),
    .data_o    (fifo_data)
  );

  // Packet assembly: rays in order r = 0..3 into the lanes of the packet register.
  logic              pkt_valid_q;
  logic [1:0]        olane_q;
  logic [31:0]       row_base_q;     // 2 * opy * width
  logic [12*W-1:0]   pkt_dir_q;
  logic [4*W-1:0]    pkt_inv_q;
  logic              pkt_take, last_packet;

  assign fifo_pop    = fifo_valid & ~pkt_valid_q;
  assign pkt_take    = pkt_valid_q & pkt_ready_i;
  assign last_packet = ox_last_q & oy_last_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      out_busy_q  <= 1'b0;
      pkt_valid_q <= 1'b0;
      olane_q     <= '0;
      opx_q       <= '0;
      opy_q       <= '0;
      row_base_q  <= '0;
    end else if (start_i && !busy_o) begin
      out_busy_q  <= !frame_empty_q;
      pkt_valid_q <= 1'b0;
      olane_q     <= '0;
      opx_q       <= '0;
      opy_q       <= '0;
      row_base_q  <= '0;
    end else begin
      if (fifo_pop) begin
        olane_q <= olane_q + 2'd1;
        if (olane_q == 2'd3) pkt_valid_q <= 1'b1;
      end
      if (pkt_take) begin
        pkt_valid_q <= 1'b0;
        if (last_packet) out_busy_q <= 1'b0;
        if (ox_last_q) begin
          opx_q      <= '0;
          opy_q      <= opy_q + CoordW'(1);
          row_base_q <= row_base_q + 32'({width_i, 1'b0});
        end else begin
          opx_q <= opx_q + CoordW'(1);
        end
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (fifo_pop) begin
      for (int unsigned r = 0; r < 4; r++) begin
        if (olane_q == 2'(r)) begin
          pkt_dir_q[3*r*W +: 3*W] <= fifo_data[0 +: 3*W];
          pkt_inv_q[r*W +: W]     <= fifo_data[3*W +: W];
        end
      end
    end
  end

  // Mask and pixel ids of packet (opx, opy): x0 = 2 opx < width and y0 = 2 opy < height always.
  logic [CoordW:0] x1, y1;
  logic            has_x1, has_y1;
  logic [31:0]     pix0, pix2;

  assign x1     = {opx_q, 1'b1};
  assign y1     = {opy_q, 1'b1};
  assign has_x1 = x1 < {1'b0, width_i};
  assign has_y1 = y1 < {1'b0, height_i};
  assign pix0   = row_base_q + 32'({opx_q, 1'b0});
  assign pix2   = pix0 + 32'(width_i);

  assign busy_o        = issuing_q | out_busy_q;
  assign pkt_valid_o   = pkt_valid_q;
  assign pkt_mask_o    = {has_x1 & has_y1, has_y1, has_x1, 1'b1};
  assign pkt_org_o     = {4{eye_i}};
  assign pkt_dir_o     = pkt_dir_q;
  assign pkt_inv_len_o = pkt_inv_q;
  assign pkt_pixel_o   = {pix2 + 32'd1, pix2, pix0 + 32'd1, pix0};

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

  // A new frame must wait for the previous one.
  StartWhenIdle_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    start_i |-> !busy_o);
  // The size is stable in the cycle before a start, so the registered last column and row are
  // the frame's.
  SizeBeforeStart_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    start_i |-> $stable(width_i) && $stable(height_i));
  // The registered end flags are the walks' own where they are used.
  LastFlags_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    (!(take && ir_q == 2'd3) ||
     (ix_last_q == (ipx_q == pw_last_q) && iy_last_q == (ipy_q == ph_last_q))) &&
    (!pkt_take || (ox_last_q == (opx_q == pw_last_q) && oy_last_q == (opy_q == ph_last_q))));
  // The frame size must not change under a running frame (the walks would disagree).
  SizeStable_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    busy_o && $past(busy_o) |-> $stable(width_i) && $stable(height_i));
  // The stream's slot structure: x (first) is followed by y and z on the next two cycles.
  FirstThenTwo_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    (d_valid && d_first) |=> d_valid && !d_first);
  // The direction register holds a whole ray when its z arrives (inv_len alignment relies on it).
  StreamKeepsRays_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    (q_valid && q_first) |=> q_valid);
  // Rays enter the FIFO exactly Latency cycles after they are taken (take_hist_q: takes of the
  // last Latency cycles, newest in bit 0).
  logic [Latency-1:0] take_hist_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      take_hist_q <= '0;
    end else begin
      take_hist_q <= {take_hist_q[Latency-2:0], take};
    end
  end
  LatencyMatches_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    inv_valid == take_hist_q[Latency-1]);
  // A packet is offered only while the frame is running.
  PacketInFrame_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    pkt_valid_q |-> out_busy_q);
`endif

endmodule
