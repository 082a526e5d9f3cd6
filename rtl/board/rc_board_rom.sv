// rc_board_rom: one of rc_core's memory ports served from block RAM (a ROM of records).
//
// Contract
// - Function: answers each request (index, tag) with record `index` of the ROM (Depth records of
//   Width bits, the layout of rc::harness::MemoryPort::record_words(): record bit i at data bit
//   i) and the request's tag; an index >= Depth gets an error response (rsp_error_o = 1, data
//   undefined). The ROM is initialised from InitFile ($readmemh, one record per line, most
//   significant digit first); in simulation (SYNTHESIS undefined) the plusarg +<Name>=<file>
//   overrides it, so one verilated model serves any scene.
// - Handshake: the protocol of docs/architecture.md ("Memory ports"). req_valid_i/req_ready_o,
//   then rsp_valid_o/rsp_ready_i. req_ready_o comes from a register (a one-entry skid buffer
//   in front of the read: ready while it is empty), so no combinational path runs from
//   rsp_ready_i or req_valid_i to req_ready_o and the core's request logic does not chain
//   through the ROM into its own response ready. rsp_valid_o and the response come straight
//   from the output register and never depend on rsp_ready_i. The response holds until taken.
//   rsp_ready_i moves only the output register and the pointers and count of a two-entry
//   FIFO beside it, never a clock enable of the FIFO's entries or of the read stage, which
//   follow registers only (the count as it was at the start of the cycle), so no path runs
//   from the consumer's ready across the chip into the block RAM or the wide data registers.
// - Latency: 3 cycles: an address register, the block RAM's registered read, then the output
//   register in the fabric. The address register makes the read's address a flip-flop (a
//   small ROM becomes LUTs, whose decode otherwise began at the skid buffer's select: run
//   24's critical path); the output register ends the block RAM's slow clock-to-out (5.8 ns
//   on the LFE5U-85F, speed grade 6) at a flip-flop instead of the core's response checks.
//   A request that finds the address stage stalled waits in the skid buffer and moves on one
//   cycle later; a read result that finds the output register held waits in the FIFO.
//   Throughput one request per cycle while rsp_ready_i is 1 (the FIFO and the skid buffer
//   then stay empty); up to six requests are held while rsp_ready_i is 0 (the skid buffer,
//   the address stage, the read stage, two FIFO entries, the output register). Responses are
//   in request order.
// - Parameters: Width record bits, Depth records (>= 1), IdxW index bits, TagW tag bits.
// - Illegal input: none (every index is answered; out-of-range ones with an error).
// - Reset: rst_ni (active low, asynchronous) clears rsp_valid_o; contents are not reset.
// - Debug: tests/board/rc_board_rom_tb.sv reads a0_free, s1_free and adv (hierarchically);
//   renaming them breaks that test bench.
module rc_board_rom #(
  parameter int unsigned Width    = 32,
  parameter int unsigned Depth    = 1,
  parameter int unsigned IdxW     = 32,
  parameter int unsigned TagW     = 8,
  parameter              InitFile = "",
  parameter              Name     = "rom"
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             req_valid_i,
  output logic             req_ready_o,
  input  logic [TagW-1:0]  req_tag_i,
  input  logic [IdxW-1:0]  req_index_i,
  output logic             rsp_valid_o,
  input  logic             rsp_ready_i,
  output logic [TagW-1:0]  rsp_tag_o,
  output logic [Width-1:0] rsp_data_o,
  output logic             rsp_error_o
);

  if (Width < 1 || Depth < 1) begin : g_param_check
    $error("rc_board_rom: need Width >= 1 and Depth >= 1");
  end

  localparam int unsigned AddrW = (Depth > 1) ? $clog2(Depth) : 1;

  logic [Width-1:0] mem [0:Depth-1];

  initial begin
`ifndef SYNTHESIS
    string file;
    if ($value$plusargs({Name, "=%s"}, file)) begin
      $readmemh(file, mem);
    end else if (InitFile != "") begin
      $readmemh(InitFile, mem);
    end
`else
    if (InitFile != "") $readmemh(InitFile, mem);
`endif
  end

  // The skid buffer (k) holds a request accepted while the address stage (a0) could not take
  // it; req_ready_o is its emptiness, a register. The address stage moves on whenever stage 1
  // is free. Stage 1 is the block RAM's read register (s1);
  // it moves on (adv) whenever the FIFO is not full (o_cnt_q < 2 as the cycle began: a
  // response taken in that cycle makes room only from the next one), and its result is then
  // always written into the FIFO's entry at the write pointer. The output register (s2) takes
  // the FIFO's oldest entry when there is one, else stage 1's result directly (then the entry
  // just written is not counted: the write pointer stays), whenever it is empty or being taken.
  // The address stage takes the skid buffer's request, or else the port's, whenever it is
  // empty or moving on (its valid bit from req_valid_i; its enable from registers only); stage
  // 1 reads at the address stage's registered address whenever it is free. So adv, and with it
  // the read enable and every entry's clock enable, comes from registers only; rsp_ready_i
  // reaches s2, the pointers and the count.
  logic             acc, in_range, adv, s1_free, a0_free, rd_valid, s2_free, o_any, push, pop;
  logic             o_wp;
  logic [IdxW-1:0]  rd_index;
  logic [TagW-1:0]  rd_tag;
  logic [AddrW-1:0] addr;
  logic             k_valid_q, a0_valid_q, a0_error_q, s1_valid_q, s1_error_q, o_rp_q;
  logic [AddrW-1:0] a0_addr_q;
  logic [1:0]       o_cnt_q;
  logic             o0_error_q, o1_error_q, s2_valid_q, s2_error_q;
  logic [IdxW-1:0]  k_index_q;
  logic [TagW-1:0]  k_tag_q, a0_tag_q, s1_tag_q, o0_tag_q, o1_tag_q, s2_tag_q;
  logic [Width-1:0] s1_data_q, o0_data_q, o1_data_q, s2_data_q;

  assign adv         = s1_valid_q & ~o_cnt_q[1];
  assign s1_free     = ~s1_valid_q | adv;
  assign a0_free     = ~a0_valid_q | s1_free;
  assign s2_free     = ~s2_valid_q | rsp_ready_i;
  assign o_any       = o_cnt_q != 2'd0;
  // The entry written this cycle counts unless it goes straight on to s2 (FIFO empty, s2 free).
  assign push        = adv & (o_any | ~s2_free);
  assign pop         = o_any & s2_free;
  // The write pointer is the read pointer plus the count (mod 2), not a register of its own.
  assign o_wp        = o_rp_q ^ o_cnt_q[0];
  assign req_ready_o = ~k_valid_q;
  assign acc         = req_valid_i & ~k_valid_q;
  assign rd_valid    = k_valid_q | req_valid_i;
  assign rd_index    = k_valid_q ? k_index_q : req_index_i;
  assign rd_tag      = k_valid_q ? k_tag_q : req_tag_i;
  // The block RAM is addressed by the index's low bits whether or not it is in range (an
  // out-of-range read returns an error response whose data nobody uses), so the range check's
  // carry chain ends at the error flag's register, not at the block RAM's address pins.
  assign in_range    = 64'(rd_index) < 64'(Depth);
  assign addr        = AddrW'(rd_index);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      k_valid_q  <= 1'b0;
      a0_valid_q <= 1'b0;
      s1_valid_q <= 1'b0;
      o_rp_q     <= 1'b0;
      o_cnt_q    <= 2'd0;
      s2_valid_q <= 1'b0;
    end else begin
      // Full only from an accepted request the address stage could not take; a full buffer is
      // emptied by the address stage before anything else (req_ready_o is 0 meanwhile).
      k_valid_q <= k_valid_q ? ~a0_free : (acc & ~a0_free);
      if (a0_free) a0_valid_q <= rd_valid;
      if (s1_free) s1_valid_q <= a0_valid_q;
      if (pop) o_rp_q <= ~o_rp_q;
      o_cnt_q <= o_cnt_q + 2'(push) - 2'(pop);
      if (s2_free) s2_valid_q <= o_any | adv;
    end
  end

  always_ff @(posedge clk_i) begin
    if (acc) begin
      k_index_q <= req_index_i;
      k_tag_q   <= req_tag_i;
    end
    if (a0_free) begin
      a0_addr_q  <= addr;
      a0_tag_q   <= rd_tag;
      a0_error_q <= ~in_range;
    end
    if (s1_free) begin
      s1_tag_q   <= a0_tag_q;
      s1_error_q <= a0_error_q;
    end
    // The two entries are plain registers (not an array), so no tool makes them a RAM.
    if (adv && !o_wp) begin
      o0_tag_q   <= s1_tag_q;
      o0_error_q <= s1_error_q;
      o0_data_q  <= s1_data_q;
    end
    if (adv && o_wp) begin
      o1_tag_q   <= s1_tag_q;
      o1_error_q <= s1_error_q;
      o1_data_q  <= s1_data_q;
    end
    if (s2_free) begin
      s2_tag_q   <= !o_any ? s1_tag_q : o_rp_q ? o1_tag_q : o0_tag_q;
      s2_error_q <= !o_any ? s1_error_q : o_rp_q ? o1_error_q : o0_error_q;
      s2_data_q  <= !o_any ? s1_data_q : o_rp_q ? o1_data_q : o0_data_q;
    end
  end

  // The block RAM read port: registered, enabled whenever the read stage is free (so the
  // enable comes from this module's registers, not from the core's request valid across the
  // chip: run 22's path into the read's enable). A read without a request loads data nobody
  // uses (s1_valid_q stays 0).
  always_ff @(posedge clk_i) begin
    if (s1_free) s1_data_q <= mem[a0_addr_q];
  end

  assign rsp_valid_o = s2_valid_q;
  assign rsp_tag_o   = s2_tag_q;
  assign rsp_data_o  = s2_data_q;
  assign rsp_error_o = s2_error_q;

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o(checks_on)
  );

  // The memory-port protocol: a response holds, unchanged, until it is taken.
  RspHold_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    rsp_valid_o && !rsp_ready_i |=> rsp_valid_o && $stable(rsp_tag_o) &&
    $stable(rsp_data_o) && $stable(rsp_error_o));
  // A request waits in the skid buffer only behind an address stage that cannot move on.
  SkidBehindRead_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    k_valid_q |-> a0_valid_q);
  // The FIFO holds two entries at most (adv waits while it is full).
  OutCount_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    o_cnt_q <= 2'd2);
  // Results wait in the FIFO only behind a held output register.
  FifoBehindOutput_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    o_any |-> s2_valid_q);
`endif

endmodule
