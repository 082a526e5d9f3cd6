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
// - Counters: counter k counts perf_inc_i[3k +: 3] per cycle (registered first: a counter counts
//   its events a cycle late); counter CorePerfMaxStack instead keeps the largest perf_depth_i
//   seen with perf_inc_i's CorePerfStackPushes field non-zero. With KindCounters = 0 the
//   per-kind counters (CorePerfPrimaryRays .. CorePerfRefractTriangleTests) are not built: the
//   primary ones read CorePerfRays, CorePerfTraversalSteps and CorePerfTriangleTests, the others
//   0 (their increments are not read).
//   perf_o = counter perf_sel_i (64 bits, zero for numbers >= CorePerfCount) ReadLatency (2)
//   edges late: the number is sampled at a clock edge k and perf_o shows, after edge k + 1, the
//   counter's word as it was before edge k. A word lags its counter (see "Counters" below): it
//   holds the counter's value at some edge of the last PerfSettle, and it is exact when the
//   number is sampled PerfSettle or more edges after the counter's last event (sampled at an
//   edge, as perf_inc_i is). A word never exceeds its counter's value; a number sampled at one
//   of the first NPerf + 2 edges after reset reads 0 (the words are written in the sweep's first
//   round).
// - Parameters: WatchdogCycles (>= 2), EvW (watchdog events, >= 4); KindCounters: 1 = the
//   per-kind counters (a core with secondary packets), 0 = none, as above; PerfSettle and
//   ReadLatency are docs/spec.toml's core.perf_settle_cycles and core.perf_read_latency
//   (checked at elaboration).
// - Reset: rst_ni (active low, asynchronous) clears the fronts, the sweep, the largest depth, the
//   watchdog's count and the status; the words (block RAM, no reset) are written from 0 in the
//   sweep's first round.
module rc_core_status #(
  parameter int unsigned WatchdogCycles = rc_pkg::CoreWatchdogCycles,
  parameter int unsigned EvW            = 16,
  parameter bit          KindCounters   = 1'b1,
  // Derived (do not override).
  parameter int unsigned NPerf          = rc_pkg::CorePerfCount,
  parameter int unsigned StatusW        = rc_pkg::CoreStatusBits,
  parameter int unsigned SpW            = rc_pkg::CoreSpBits,
  parameter int unsigned PerfSettle     = rc_pkg::CorePerfSettleCycles,
  parameter int unsigned ReadLatency    = rc_pkg::CorePerfReadLatency
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

  if (WatchdogCycles < 2 || EvW < 4 || StatusW != 4) begin : g_param_check
    $error("rc_core_status: need WatchdogCycles >= 2, EvW >= 4, 4 status bits");
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

  // Each counter (but the largest stack depth) is a 64-bit word in block RAM (rc_ram, Depth
  // NPerf) and a front counter of FrontW bits in flip-flops. The increments are registered
  // (perf_inc_q) and added to the fronts; a sweep visits one counter per cycle (sw_q = 0 ..
  // NPerf - 1, round and round): at its edge the front's value is taken out (the front restarts
  // from that edge's increment) and, two edges later, added to the word read at the same edge.
  // So a counter's value is its word plus its front plus what is on its way between them, and
  // the word alone is exact PerfSettle edges after the last event. A front gathers at most NPerf
  // edges' increments of at most 7 each between two visits: FrontW bits hold them.
  localparam int unsigned FrontW = $clog2(7 * NPerf + 1);
  localparam int unsigned AW     = $clog2(NPerf);
  localparam int unsigned KindLo = rc_pkg::CorePerfPrimaryRays;
  localparam int unsigned KindHi = rc_pkg::CorePerfRefractTriangleTests;

  // The per-kind increments come a cycle later than the others (rc_kind_perf registers them).
  if (PerfSettle < NPerf + 5 || ReadLatency != 2) begin : g_settle_check
    $error("rc_core_status: need perf_settle_cycles >= core_perf.count + 5, perf_read_latency 2");
  end

  // Whether counter k has a front of its own (not the largest depth; the per-kind counters only
  // with KindCounters).
  function automatic logic counted(input int unsigned k);
    counted = k != rc_pkg::CorePerfMaxStack && (KindCounters || k < KindLo || k > KindHi);
  endfunction

  logic [3*NPerf-1:0]      perf_inc_q;
  logic [SpW-1:0]          depth_q, max_sp_q;
  logic [NPerf*FrontW-1:0] front_q;
  logic [AW-1:0]           sw_q, sw1_q, sw2_q;      // the sweep: its counter, one and two edges on
  logic [NPerf-1:0]        sw_oh_q;                 // sw_q one-hot (the fronts' selects)
  logic                    sw_v1_q, sw_v2_q;        // a visit one and two edges on
  logic                    init_q, init1_q, init2_q; // the first round after reset: words from 0
  logic [FrontW-1:0]       take_d, take1_q, take2_q; // the visited front's value, on its way
  logic [63:0]             word_rd, word_wr;
  // The visited front: an AND-OR over the one-hot sweep (one level of selects, no chain).
  always_comb begin
    take_d = '0;
    for (int unsigned k = 0; k < NPerf; k++) begin
      if (counted(k)) take_d = take_d | ({FrontW{sw_oh_q[k]}} & front_q[k*FrontW +: FrontW]);
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      perf_inc_q <= '0;
      depth_q    <= '0;
      max_sp_q   <= '0;
      front_q    <= '0;
      sw_q       <= '0;
      sw_oh_q    <= NPerf'(1);
      sw1_q      <= '0;
      sw2_q      <= '0;
      sw_v1_q    <= 1'b0;
      sw_v2_q    <= 1'b0;
      init_q     <= 1'b1;
      init1_q    <= 1'b1;
      init2_q    <= 1'b1;
    end else begin
      perf_inc_q <= perf_inc_i;
      depth_q    <= perf_depth_i;
      if (perf_inc_q[3*rc_pkg::CorePerfStackPushes +: 3] != 3'd0 && depth_q > max_sp_q) begin
        max_sp_q <= depth_q;
      end
      for (int unsigned k = 0; k < NPerf; k++) begin
        if (counted(k)) begin
          front_q[k*FrontW +: FrontW] <=
              (sw_oh_q[k] ? FrontW'(0) : front_q[k*FrontW +: FrontW]) +
              FrontW'(perf_inc_q[3*k +: 3]);
        end
      end
      sw_q    <= (sw_q == AW'(NPerf - 1)) ? '0 : sw_q + AW'(1);
      sw_oh_q <= {sw_oh_q[NPerf-2:0], sw_oh_q[NPerf-1]};
      sw1_q   <= sw_q;
      sw2_q   <= sw1_q;
      sw_v1_q <= 1'b1;
      sw_v2_q <= sw_v1_q;
      if (sw_q == AW'(NPerf - 1)) init_q <= 1'b0;
      init1_q <= init_q;
      init2_q <= init1_q;
    end
  end
  always_ff @(posedge clk_i) begin
    take1_q <= take_d;
    take2_q <= take1_q;
  end
  // The word two edges after its read (the block RAM's register and one in the fabric), plus
  // the front's value taken at the read's edge; 0 in the first round (the RAM is not reset).
  assign word_wr = (init2_q ? 64'd0 : word_rd) + 64'(take2_q);

  // The words, twice: one copy for the sweep's read, one for perf_sel_i's (each a block RAM
  // with one write and one read port; both written alike).
  rc_ram #(
    .Width (64),
    .Depth (NPerf),
    .OutReg(1'b1)
  ) u_words_sweep (
    .clk_i,
    .we_i   (sw_v2_q),
    .waddr_i(sw2_q),
    .wdata_i(word_wr),
    .re_i   (1'b1),
    .raddr_i(sw_q),
    .rdata_o(word_rd)
  );

  // The read: the number is mapped to its word (without per-kind counters the primary kind's
  // read the totals) and to what overrides the word (the largest depth; 0 for numbers without
  // a counter, and in the first round after reset, when the words are not yet written). A read
  // at the edge that writes the same word gets the word written (the block RAM's read is
  // unspecified then).
  logic [AW-1:0]  rd_addr;
  logic           rd_zero, rd_max;
  always_comb begin
    rd_addr = AW'(perf_sel_i);
    rd_zero = perf_sel_i >= 8'(NPerf) || init2_q;
    rd_max  = perf_sel_i == 8'(rc_pkg::CorePerfMaxStack);
    if (!KindCounters && perf_sel_i >= 8'(KindLo) && perf_sel_i <= 8'(KindHi)) begin
      rd_zero = perf_sel_i > 8'(KindLo + 2) || init2_q;
      rd_addr = (perf_sel_i == 8'(KindLo)) ? AW'(rc_pkg::CorePerfRays) :
                (perf_sel_i == 8'(KindLo + 1)) ? AW'(rc_pkg::CorePerfTraversalSteps) :
                                                 AW'(rc_pkg::CorePerfTriangleTests);
    end
  end
  logic [63:0]    rd_word, fwd_q, fwd1_q;
  logic [SpW-1:0] max1_q, max2_q;
  logic [1:0]     zero_q, mx_q, coll_q;
  always_ff @(posedge clk_i) begin
    zero_q <= {zero_q[0], rd_zero};
    mx_q   <= {mx_q[0], rd_max};
    coll_q <= {coll_q[0], sw_v2_q && sw2_q == rd_addr};
    fwd_q  <= word_wr;
    fwd1_q <= fwd_q;
    max1_q <= max_sp_q;
    max2_q <= max1_q;
  end
  rc_ram #(
    .Width (64),
    .Depth (NPerf),
    .OutReg(1'b1)
  ) u_words_read (
    .clk_i,
    .we_i   (sw_v2_q),
    .waddr_i(sw2_q),
    .wdata_i(word_wr),
    .re_i   (1'b1),
    .raddr_i(rd_addr),
    .rdata_o(rd_word)
  );
`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // The one-hot sweep and the sweep's number name the same counter (the fronts' selects and the
  // words' addresses agree).
  SweepOneHot_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  sw_oh_q == (NPerf'(1) << sw_q));
`endif
  assign perf_o = zero_q[1] ? 64'd0 : mx_q[1] ? 64'(max2_q) : coll_q[1] ? fwd1_q : rd_word;

endmodule
