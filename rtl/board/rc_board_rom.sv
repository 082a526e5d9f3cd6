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
//   then rsp_valid_o/rsp_ready_i. req_ready_o is a register: the ROM holds at most Credits = 4
//   requests (accepted and not yet taken), and req_ready_o says that the count, as it will be
//   after this cycle's transfers, is below that. rsp_valid_o and the response come straight
//   from the output register and never depend on rsp_ready_i. The response holds until taken.
// - Pipeline: an address stage and the block RAM's read stage that move on every cycle,
//   whatever the consumer does (they have no enables: the block RAM reads every cycle), then a
//   FIFO of Credits - 1 entries beside the output register. The read stage's result is written
//   into the FIFO's entry at the write pointer whenever it is valid (each entry's enable is a
//   register of its own, decided a cycle ahead); it counts as pushed unless it goes straight on
//   to the output register (FIFO empty, output register free). The credits guarantee the room:
//   a request accepted is in the address stage, the read stage, the FIFO or the output
//   register. rsp_ready_i reaches the output register's enable and, through the next pointers
//   and count, a few control registers (pointers, count, not-empty flag, the entries' enables);
//   never the block RAM's enable, and no wide enable or select in the same cycle, so no path
//   runs from the consumer's ready across the chip into the block RAMs, their address register
//   or the FIFO's entries (run 52: the triangle ROM's control, through its enables, -0.84 ns).
// - Latency: 3 cycles: the address register, the block RAM's registered read, then the output
//   register in the fabric. The address register makes the read's address a flip-flop (a
//   small ROM becomes LUTs, whose decode otherwise began at the request's select: run 24's
//   critical path); the output register ends the block RAM's slow clock-to-out (5.8 ns on the
//   LFE5U-85F, speed grade 6) at a flip-flop instead of the core's response checks.
//   Throughput one request per cycle while rsp_ready_i is 1 (the FIFO then stays empty); four
//   requests are held while rsp_ready_i is 0 (the output register and the FIFO's three
//   entries, once the address and read stages have moved on). Responses are in request order.
// - Parameters: Width record bits, Depth records (>= 1), IdxW index bits, TagW tag bits.
// - Illegal input: none (every index is answered; out-of-range ones with an error).
// - Reset: rst_ni (active low, asynchronous) clears the valid bits, the FIFO's pointers and
//   count and the credit count; contents are not reset.
// - Debug: tests/board/rc_board_rom_tb.sv reads entry_we (the FIFO entries' write enables)
//   hierarchically; renaming it breaks that test bench.
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

  localparam int unsigned Credits = 4;  // the least count that keeps one request a cycle
  localparam int unsigned Entries = Credits - 1;

  // Requests held: accepted and not yet taken (address stage, read stage, FIFO, output
  // register). req_ready_o is the count after this cycle's transfers below Credits, registered.
  logic       acc, take, ready_q;
  logic [2:0] cnt_q, cnt_d;
  assign acc         = req_valid_i & ready_q;
  assign take        = s2_valid_q & rsp_ready_i;
  assign cnt_d       = cnt_q + 3'(acc) - 3'(take);
  assign req_ready_o = ready_q;

  // Address stage and read stage: every cycle. The block RAM is addressed by the index's low
  // bits whether or not it is in range (an out-of-range read returns an error response whose
  // data nobody uses), so the range check's carry chain ends at the error flag's register, not
  // at the block RAM's address pins.
  logic             a0_valid_q, a0_error_q, s1_valid_q, s1_error_q;
  logic [AddrW-1:0] a0_addr_q;
  logic [TagW-1:0]  a0_tag_q, s1_tag_q;
  logic [Width-1:0] s1_data_q;

  function automatic logic [1:0] next_ptr(input logic [1:0] p);
    next_ptr = (p == 2'(Entries - 1)) ? 2'd0 : p + 2'd1;
  endfunction

  // The FIFO: Entries plain registers (not an array, so no tool makes them a RAM), a read
  // pointer, a write pointer and a count. The write pointer is the read pointer plus the count
  // (WritePointer_A), and cnt_q is the sum of the stages' valid bits (Credits_A); both are kept
  // as registers so that req_ready_o starts at a flip-flop. The signals that fan out to a whole
  // record (Width + TagW + 1 flip-flops) are registers of their own, decided a cycle ahead from
  // the next pointer and count: each entry's write enable (o_we_q, the read stage's valid bit
  // and the write pointer's decode) and the FIFO's not-empty flag (o_any_q, the output
  // register's select). Run 58 (seed 2): the decode and the flag were a LUT each in front of
  // those nets, with 4 to 5 ns of routing on both sides (-0.86 and -0.28 ns).
  logic [Entries-1:0]       o_err_q;
  logic [Entries*TagW-1:0]  o_tag_q;   // entry e at [e * TagW +: TagW]
  logic [Entries*Width-1:0] o_data_q;  // entry e at [e * Width +: Width]
  logic [1:0]               o_rp_q, o_wp_q, o_cnt_q, o_wp_d, o_cnt_d;
  logic                     o_any_q, s2_free, push, pop;
  logic [Entries-1:0]       entry_we, o_we_q;
  logic                     s2_valid_q, s2_error_q, s2_valid_d, s2_valid_out, s2_valid_en;
  logic                     s2_free_en;
  logic [TagW-1:0]          s2_tag_q;
  logic [Width-1:0]         s2_data_q;

  // The output register's valid bit, three kept copies (rc_reg_copies): s2_valid_q for the
  // control (pointers, count, the FIFO's flags, its own next value), s2_valid_en for the output
  // register's enable (s2_free_en, Width + TagW + 1 flip-flops) and s2_valid_out for rsp_valid_o,
  // which crosses the chip to the consumer. With one flip-flop for all three, placement pulled it
  // toward the consumer and every control path began with that net (run 72 seed 2: s2_valid_q
  // into o_we_q, o_any_q, s2_tag_q and o_cnt_q, 4.5 ns on its first net, -1.36 ns).
  assign s2_free    = ~s2_valid_q | rsp_ready_i;
  assign s2_free_en = ~s2_valid_en | rsp_ready_i;
  assign s2_valid_d = s2_free ? (o_any_q | s1_valid_q) : s2_valid_q;
  rc_reg_copies #(
    .Width   (1),
    .Copies  (3),
    .HasReset(1'b1)
  ) u_s2_valid (
    .clk_i,
    .rst_ni,
    .d_i(s2_valid_d),
    .q_o({s2_valid_out, s2_valid_en, s2_valid_q})
  );
  // The read stage's result counts in the FIFO unless it goes straight on to s2.
  assign push     = s1_valid_q & (o_any_q | ~s2_free);
  assign pop      = o_any_q & s2_free;
  assign o_wp_d   = push ? next_ptr(o_wp_q) : o_wp_q;
  assign o_cnt_d  = o_cnt_q + 2'(push) - 2'(pop);
  // The read stage's result is written at the write pointer whenever it is valid.
  assign entry_we = o_we_q;

  // The FIFO's head, a plain multiplexer on the read pointer (a part-select at a computed
  // offset would be a shifter).
  logic             head_err;
  logic [TagW-1:0]  head_tag;
  logic [Width-1:0] head_data;
  always_comb begin
    head_err  = o_err_q[0];
    head_tag  = o_tag_q[0 +: TagW];
    head_data = o_data_q[0 +: Width];
    for (int unsigned e = 1; e < Entries; e++) begin
      if (o_rp_q == 2'(e)) begin
        head_err  = o_err_q[e];
        head_tag  = o_tag_q[e*TagW +: TagW];
        head_data = o_data_q[e*Width +: Width];
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ready_q    <= 1'b1;
      cnt_q      <= 3'd0;
      a0_valid_q <= 1'b0;
      s1_valid_q <= 1'b0;
      o_rp_q     <= 2'd0;
      o_wp_q     <= 2'd0;
      o_cnt_q    <= 2'd0;
      o_any_q    <= 1'b0;
      o_we_q     <= '0;
    end else begin
      cnt_q      <= cnt_d;
      ready_q    <= cnt_d < 3'(Credits);
      a0_valid_q <= acc;
      s1_valid_q <= a0_valid_q;
      o_wp_q     <= o_wp_d;
      if (pop) o_rp_q <= next_ptr(o_rp_q);
      o_cnt_q <= o_cnt_d;
      o_any_q <= o_cnt_d != 2'd0;
      for (int unsigned e = 0; e < Entries; e++) begin
        o_we_q[e] <= a0_valid_q & (o_wp_d == 2'(e));
      end
    end
  end

  always_ff @(posedge clk_i) begin
    a0_addr_q  <= AddrW'(req_index_i);
    a0_tag_q   <= req_tag_i;
    a0_error_q <= 64'(req_index_i) >= 64'(Depth);
    s1_tag_q   <= a0_tag_q;
    s1_error_q <= a0_error_q;
    for (int unsigned e = 0; e < Entries; e++) begin
      if (entry_we[e]) begin
        o_tag_q[e*TagW +: TagW]    <= s1_tag_q;
        o_err_q[e]                 <= s1_error_q;
        o_data_q[e*Width +: Width] <= s1_data_q;
      end
    end
    if (s2_free_en) begin
      s2_tag_q   <= o_any_q ? head_tag : s1_tag_q;
      s2_error_q <= o_any_q ? head_err : s1_error_q;
      s2_data_q  <= o_any_q ? head_data : s1_data_q;
    end
  end

  // The block RAM read port: registered, and enabled on every cycle (a read without a request
  // loads data nobody uses: s1_valid_q stays 0).
  always_ff @(posedge clk_i) begin
    s1_data_q <= mem[a0_addr_q];
  end

  assign rsp_valid_o = s2_valid_out;
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
  // The count is what the stages hold: every request accepted is in exactly one of them.
  Credits_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    32'(cnt_q) == 32'(a0_valid_q) + 32'(s1_valid_q) + 32'(o_cnt_q) + 32'(s2_valid_q));
  // The FIFO never overflows (the credits keep its room).
  OutCount_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    32'(o_cnt_q) <= Entries);
  // Results wait in the FIFO only behind a held output register.
  FifoBehindOutput_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    o_any_q |-> s2_valid_q);
  // The registers decided a cycle ahead are what they stand for: the not-empty flag is the
  // count's, and each entry's write enable the read stage's valid bit at the write pointer.
  AnyIsCount_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    o_any_q == (o_cnt_q != 2'd0));
  for (genvar e = 0; e < Entries; e++) begin : g_we_check
    WriteEnable_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
      o_we_q[e] == (s1_valid_q && o_wp_q == 2'(e)));
  end
  // The write pointer is the read pointer plus the count.
  WritePointer_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    32'(o_wp_q) == (32'(o_rp_q) + 32'(o_cnt_q)) % Entries);
`endif

endmodule
