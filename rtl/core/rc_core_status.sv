// rc_core_status: rc_core's status bits, hardware watchdog and performance counters
// (docs/architecture.md, "Status and counters").
//
// Contract
// - error_o (sticky until reset): bits 0..2 (rc_pkg::CoreStatus*) are ORed from err_i, the error
//   bits raised in each cycle by any unit; bit CoreStatusWatchdog is set when the core holds work
//   (idle_i low) and no handshake (wd_ev_i, any bit) completes for WatchdogCycles cycles. The
//   events reach the count through two register levels (each event registered on its own, then
//   ORed in four groups), so error_o shows the bit from the edge WatchdogCycles + 2 after the last
//   handshake's.
// - Counters: counter k counts perf_inc_i[3k +: 3] per cycle (registered first: a counter lags
//   its events by a cycle, and its bits 63..PerfLoW (32) by two: the low half's carry is
//   registered, so no 64-bit carry chain ends at a counter); counter CorePerfMaxStack instead
//   keeps the largest perf_depth_i seen with perf_inc_i's CorePerfStackPushes field non-zero.
//   With KindCounters = 0 the per-kind counters (CorePerfPrimaryRays ..
//   CorePerfRefractTriangleTests) are not built: the primary ones read CorePerfRays,
//   CorePerfTraversalSteps and CorePerfTriangleTests, the others 0 (their increments are not
//   read).
//   perf_o = counter perf_sel_i (64 bits, zero for numbers >= CorePerfCount) one cycle late: the
//   number is sampled at a clock edge and perf_o shows, from that edge on, the counter as it was
//   before the edge (a multiplexer level between two register levels, see "The read"). So a
//   reader sets perf_sel_i, lets one edge pass and reads; the value is exact when that edge comes
//   two or more cycles after the last event.
// - Parameters: WatchdogCycles (>= 2), EvW (watchdog events, >= 4), PerfLoW (the counters' low
//   half, 3 .. 61; 32 in the core, small in tests/core/units/core_status_test.cpp so the carry
//   into the high half is exercised); KindCounters: 1 = the per-kind counters (a core with
//   secondary packets), 0 = none, as above.
// - Reset: rst_ni (active low, asynchronous) clears the counters, the count and the status.
module rc_core_status #(
  parameter int unsigned WatchdogCycles = rc_pkg::CoreWatchdogCycles,
  parameter int unsigned EvW            = 16,
  parameter int unsigned PerfLoW        = 32,   // the counters' low half (tests make it small)
  parameter bit          KindCounters   = 1'b1,
  // Derived (do not override).
  parameter int unsigned NPerf          = rc_pkg::CorePerfCount,
  parameter int unsigned StatusW        = rc_pkg::CoreStatusBits,
  parameter int unsigned SpW            = rc_pkg::CoreSpBits
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 idle_i,
  input  logic [EvW-1:0]       wd_ev_i,
  input  logic [2:0]           err_i,
  input  logic [3*NPerf-1:0]   perf_inc_i,
  input  logic [SpW-1:0]       perf_depth_i,
  input  logic [7:0]           perf_sel_i,
  output logic [StatusW-1:0]   error_o,
  output logic [63:0]          perf_o
);

  if (WatchdogCycles < 2 || EvW < 4 || StatusW != 4 || PerfLoW < 3 ||
      PerfLoW > 61) begin : g_param_check
    $error("rc_core_status: need WatchdogCycles >= 2, EvW >= 4, 4 status bits, PerfLoW 3..61");
  end

  if (rc_pkg::CorePerfRefractTriangleTests != rc_pkg::CorePerfPrimaryRays + 11 ||
      rc_pkg::CorePerfPrimaryRays <= rc_pkg::CorePerfTriangleTests) begin : g_kind_check
    $error("rc_core_status: the per-kind counters must be 12 numbers after the totals");
  end

  localparam int unsigned G = (EvW + 3) / 4;   // events per group

  //////////////
  // Watchdog //
  //////////////

  logic [EvW-1:0]     wd_ev_q;
  logic [3:0]         wd_grp_q;
  logic [31:0]        wd_q;
  logic               wd_clr, wd_fire;
  logic [StatusW-1:0] error_q;

  assign wd_clr  = |wd_grp_q;
  assign wd_fire = (wd_q == 32'(WatchdogCycles - 1)) & ~wd_clr;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wd_q     <= '0;
      wd_ev_q  <= EvW'(1);
      wd_grp_q <= 4'd1;
      error_q  <= '0;
    end else begin
      wd_ev_q <= {wd_ev_i[EvW-1:1], wd_ev_i[0] | idle_i};
      for (int unsigned g = 0; g < 4; g++) begin
        logic any;
        any = 1'b0;
        for (int unsigned i = 0; i < G; i++) begin
          if (g * G + i < EvW) any = any | wd_ev_q[g * G + i];
        end
        wd_grp_q[g] <= any;
      end
      if (wd_clr) begin
        wd_q <= '0;
      end else if (!wd_fire) begin
        wd_q <= wd_q + 32'd1;
      end
      error_q[2:0] <= error_q[2:0] | err_i;
      if (wd_fire) error_q[rc_pkg::CoreStatusWatchdog] <= 1'b1;
    end
  end
  assign error_o = error_q;

  //////////////
  // Counters //
  //////////////

  // Each counter as two halves, PerfLoW bits and 64 - PerfLoW: the low half's carry out is
  // registered (perf_cy_q) and added to the high half a cycle later. The largest stack depth has
  // a register of its own.
  localparam int unsigned HiW = 64 - PerfLoW;
  localparam int unsigned Groups = (NPerf + 7) / 8;  // the read's groups of 8 (see below)
  logic [Groups*8*64-1:0]   perf_q;                   // counter k at [64k +: 64], zero padded
  logic [NPerf*PerfLoW-1:0] perf_lo_q;
  logic [NPerf*HiW-1:0]     perf_hi_q;
  logic [NPerf-1:0]         perf_cy_q;
  logic [3*NPerf-1:0]       perf_inc_q;
  logic [SpW-1:0]           depth_q, max_sp_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      perf_inc_q <= '0;
      depth_q    <= '0;
      max_sp_q   <= '0;
      perf_lo_q  <= '0;
      perf_hi_q  <= '0;
      perf_cy_q  <= '0;
    end else begin
      perf_inc_q <= perf_inc_i;
      depth_q    <= perf_depth_i;
      if (perf_inc_q[3*rc_pkg::CorePerfStackPushes +: 3] != 3'd0 && depth_q > max_sp_q) begin
        max_sp_q <= depth_q;
      end
      for (int unsigned k = 0; k < NPerf; k++) begin
        if (k != rc_pkg::CorePerfMaxStack) begin
          {perf_cy_q[k], perf_lo_q[k*PerfLoW +: PerfLoW]} <=
              (PerfLoW + 1)'(perf_lo_q[k*PerfLoW +: PerfLoW]) +
              (PerfLoW + 1)'(perf_inc_q[3*k +: 3]);
          perf_hi_q[k*HiW +: HiW] <= perf_hi_q[k*HiW +: HiW] + HiW'(perf_cy_q[k]);
        end
      end
    end
  end
  // Without per-kind counters, kind counter 3 * kind + e reads the total of event e for the
  // primary kind and 0 for the others (their registers have no reader and are removed).
  localparam int unsigned KindLo = rc_pkg::CorePerfPrimaryRays;
  localparam int unsigned KindHi = rc_pkg::CorePerfRefractTriangleTests;
  always_comb begin
    perf_q = '0;
    for (int unsigned k = 0; k < NPerf; k++) begin
      if (k == rc_pkg::CorePerfMaxStack) begin
        perf_q[k*64 +: 64] = 64'(max_sp_q);
      end else if (!KindCounters && k >= KindLo && k <= KindHi) begin
        if (k < KindLo + 3) begin
          // The primary kind's counter of event k - KindLo: the total of that event.
          int unsigned tot;
          tot = (k == KindLo) ? rc_pkg::CorePerfRays :
                (k == KindLo + 1) ? rc_pkg::CorePerfTraversalSteps : rc_pkg::CorePerfTriangleTests;
          perf_q[k*64 +: 64] = {perf_hi_q[tot*HiW +: HiW], perf_lo_q[tot*PerfLoW +: PerfLoW]};
        end
      end else begin
        perf_q[k*64 +: 64] = {perf_hi_q[k*HiW +: HiW], perf_lo_q[k*PerfLoW +: PerfLoW]};
      end
    end
  end
  // The read in two levels: each group of 8 counters (numbers 8g .. 8g+7) has a register
  // loaded every cycle with the counter the number's low bits pick, beside the counters; the
  // number's high bits, registered with it, then pick the group. The counters' 64-bit
  // multiplexer thus ends at flip-flops near the counters and not at its reader (run 56 seed 2:
  // the board's perf_sel_q -> perf_rd_q in one cycle, -1.25 ns, 9.03 ns of routing).
  // Both levels are AND-OR selects (a variable part select became a shifter in Yosys); group g
  // at [64g +: 64] (flat: Yosys 0.23 assigns no whole unpacked arrays).
  logic [Groups*64-1:0] grp_d, grp_q;
  logic [4:0]           sel_hi_q;
  always_comb begin
    grp_d = '0;
    for (int unsigned g = 0; g < Groups; g++) begin
      for (int unsigned i = 0; i < 8; i++) begin
        grp_d[g*64 +: 64] = grp_d[g*64 +: 64] |
                            ({64{perf_sel_i[2:0] == 3'(i)}} & perf_q[(8*g + i)*64 +: 64]);
      end
    end
  end
  always_ff @(posedge clk_i) begin
    grp_q    <= grp_d;
    sel_hi_q <= perf_sel_i[7:3];
  end
  always_comb begin
    perf_o = '0;
    for (int unsigned g = 0; g < Groups; g++) begin
      perf_o = perf_o | ({64{sel_hi_q == 5'(g)}} & grp_q[g*64 +: 64]);
    end
  end

endmodule
