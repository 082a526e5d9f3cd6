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
//   through the ROM into its own response ready. rsp_valid_o comes from a register and never
//   depends on rsp_ready_i. The response holds until taken. rsp_ready_i moves only the output
//   register and a second one-entry skid buffer behind the read: the read stage (the block
//   RAM's read enable and its registers) moves on whenever that buffer is empty, a register,
//   so no path runs from the consumer's ready across the chip into the block RAM.
// - Latency: 2 cycles: the block RAM's registered read, then an output register in the fabric,
//   so that the block RAM's slow clock-to-out (5.8 ns on the LFE5U-85F, speed grade 6) ends at a
//   flip-flop instead of feeding the core's response checks. A request that finds the read
//   stage stalled waits in the request skid buffer and is read one cycle later; a read result
//   that finds the output register held waits in the response skid buffer. Throughput one
//   request per cycle while rsp_ready_i is 1 (both skid buffers then stay empty); up to four
//   requests are held while rsp_ready_i is 0. Responses are in request order.
// - Parameters: Width record bits, Depth records (>= 1), IdxW index bits, TagW tag bits.
// - Illegal input: none (every index is answered; out-of-range ones with an error).
// - Reset: rst_ni (active low, asynchronous) clears rsp_valid_o; contents are not reset.
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

  // The request skid buffer (k) holds a request accepted while the read stage could not take
  // it; req_ready_o is its emptiness, a register. Stage 1 is the block RAM's read register
  // (s1), stage 2 the output register (s2), with the response skid buffer (r) beside it.
  // Stage 1 moves on (adv) whenever r is empty: into s2 if s2 is empty or being taken, else
  // into r. s2 takes r's entry first. Stage 1 takes the request skid buffer's request, or else
  // the port's, whenever it is empty or moving on. So adv, and with it the read enable, comes
  // from registers and req_valid_i only.
  logic             acc, take, in_range, adv, s1_free, s2_free, rd_valid;
  logic [IdxW-1:0]  rd_index;
  logic [TagW-1:0]  rd_tag;
  logic [AddrW-1:0] addr;
  logic             k_valid_q, s1_valid_q, s1_error_q, r_valid_q, r_error_q, s2_valid_q;
  logic             s2_error_q;
  logic [IdxW-1:0]  k_index_q;
  logic [TagW-1:0]  k_tag_q, s1_tag_q, r_tag_q, s2_tag_q;
  logic [Width-1:0] s1_data_q, r_data_q, s2_data_q;

  assign adv         = s1_valid_q & ~r_valid_q;
  assign s1_free     = ~s1_valid_q | adv;
  assign s2_free     = ~s2_valid_q | rsp_ready_i;
  assign req_ready_o = ~k_valid_q;
  assign acc         = req_valid_i & ~k_valid_q;
  assign rd_valid    = k_valid_q | req_valid_i;
  assign rd_index    = k_valid_q ? k_index_q : req_index_i;
  assign rd_tag      = k_valid_q ? k_tag_q : req_tag_i;
  assign take        = rd_valid & s1_free;
  assign in_range    = 64'(rd_index) < 64'(Depth);
  assign addr        = in_range ? AddrW'(rd_index) : '0;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      k_valid_q  <= 1'b0;
      s1_valid_q <= 1'b0;
      r_valid_q  <= 1'b0;
      s2_valid_q <= 1'b0;
    end else begin
      // Full only from an accepted request the read stage could not take; a full buffer is
      // emptied by the read stage before anything else (req_ready_o is 0 meanwhile).
      k_valid_q <= k_valid_q ? ~s1_free : (acc & ~s1_free);
      if (take) begin
        s1_valid_q <= 1'b1;
      end else if (adv) begin
        s1_valid_q <= 1'b0;
      end
      // Full only from a read result the output register could not take; emptied into the
      // output register before anything else (adv is 0 meanwhile).
      r_valid_q <= r_valid_q ? ~s2_free : (adv & ~s2_free);
      if (s2_free) s2_valid_q <= r_valid_q | adv;
    end
  end

  always_ff @(posedge clk_i) begin
    if (acc) begin
      k_index_q <= req_index_i;
      k_tag_q   <= req_tag_i;
    end
    if (take) begin
      s1_tag_q   <= rd_tag;
      s1_error_q <= ~in_range;
    end
    if (adv && !s2_free) begin
      r_tag_q   <= s1_tag_q;
      r_error_q <= s1_error_q;
      r_data_q  <= s1_data_q;
    end
    if (s2_free) begin
      s2_tag_q   <= r_valid_q ? r_tag_q : s1_tag_q;
      s2_error_q <= r_valid_q ? r_error_q : s1_error_q;
      s2_data_q  <= r_valid_q ? r_data_q : s1_data_q;
    end
  end

  // The block RAM read port: registered, enabled by the request handshake.
  always_ff @(posedge clk_i) begin
    if (take) s1_data_q <= mem[addr];
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
  // A request waits in the skid buffer only behind a read stage that cannot move on.
  SkidBehindRead_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    k_valid_q |-> s1_valid_q);
  // A read result waits in the response skid buffer only behind a held output register.
  SkidBehindOutput_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    r_valid_q |-> s2_valid_q);
`endif

endmodule
