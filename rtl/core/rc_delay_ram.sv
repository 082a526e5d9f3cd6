// rc_delay_ram: a fixed delay line of Cycles clock cycles kept in a memory (a circular buffer),
// for long delays where a shift register's flip-flops would cost too much.
//
// Contract
// - Function: data_o = data_i as it was Cycles rising edges earlier, as rc_delay (every cycle
//   shifts; no enable, no handshake: it runs beside a valid-only pipeline).
// - Structure: a memory of Depth = 2^ceil(log2(Cycles)) words, a circular buffer: each cycle
//   data_i is written at the write pointer and an older word is read. Two mappings:
//     distributed RAM (ram_style "distributed", e.g. ECP5 DPR16X4): the word written Cycles - 1
//       cycles earlier is read into the output register;
//     block RAM (ram_style "block", ECP5 DP16KD) when Depth > 64, or Depth > 16 and Width >= 8:
//       the word written Cycles - 2 cycles earlier is read into the block RAM's own read
//       register, then into an output register in the fabric (a DP16KD's clock-to-out is 5.8 ns
//       on the LFE5U-85F, so the value reaches logic from a flip-flop).
//   A distributed RAM costs six LUT sites per 64 bits and its read multiplexer grows with Depth
//   (Yosys: 923 LUT4 sites for 256 x 24); one DP16KD holds 512 x 36 bits. So every line of 17
//   cycles or more and 8 bits or more is block RAM, and so is every line of more than 64 cycles;
//   a short or narrow one stays in LUTs, unless ForceBlock = 1 puts it in block RAM too (a
//   wide line of a few cycles: its Width x Cycles flip-flops each take a place of their own in
//   the logic tiles, the block RAMs take none; rc_xform_unit's and rc_isect_unit's delay lines on
//   the lit board, docs/fpga.md).
//   The read address is never the one being written (Cycles - 1 < Depth; Cycles - 2 >= 1).
// - Latency: Cycles (>= 2; >= 3 in block RAM).
// - Parameters: Width data bits (>= 1), Cycles (>= 2), ForceBlock (0 or 1: block RAM whatever
//   Width and Cycles; then Cycles >= 3).
// - Illegal input: none. Reset: rst_ni (active low, asynchronous) clears the write pointer only
//   (the memory and the output registers have no reset: before Cycles edges data_o is
//   undefined).
module rc_delay_ram #(
  parameter int unsigned Width  = 1,
  parameter int unsigned Cycles = 2,
  parameter bit          ForceBlock = 1'b0
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic [Width-1:0] data_i,
  output logic [Width-1:0] data_o
);

  if (Width < 1 || Cycles < 2) begin : g_param_check
    $error("rc_delay_ram: Width must be at least 1 and Cycles at least 2");
  end

  localparam int unsigned AddrW = $clog2(Cycles);
  localparam int unsigned Depth = 1 << AddrW;
  // The mapping rule above: block RAM for deep lines, and for lines past one DPR16X4's 16 words
  // that are 8 bits wide or more; or when asked.
  localparam bit          Block = ForceBlock || Depth > 64 || (Depth > 16 && Width >= 8);

  if (Block && Cycles < 3) begin : g_block_check
    $error("rc_delay_ram: a line in block RAM needs Cycles >= 3");
  end

  logic [AddrW-1:0] wp_q;
  logic [Width-1:0] rd_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) wp_q <= '0;
    else wp_q <= wp_q + AddrW'(1);
  end

  // The same memory either way; only where it goes, and the registers behind it, differ.
  if (Block) begin : g_block
    logic [AddrW-1:0] rp;
    logic [Width-1:0] out_q;
    assign rp = wp_q - AddrW'(Cycles - 2);
    (* ram_style = "block" *) logic [Width-1:0] mem_q [Depth];
    always_ff @(posedge clk_i) begin
      mem_q[wp_q] <= data_i;
      rd_q        <= mem_q[rp];
      out_q       <= rd_q;
    end
    assign data_o = out_q;
  end else begin : g_lut
    logic [AddrW-1:0] rp;
    assign rp = wp_q - AddrW'(Cycles - 1);
    (* ram_style = "distributed" *) logic [Width-1:0] mem_q [Depth];
    always_ff @(posedge clk_i) begin
      mem_q[wp_q] <= data_i;
      rd_q        <= mem_q[rp];
    end
    assign data_o = rd_q;
  end

endmodule
