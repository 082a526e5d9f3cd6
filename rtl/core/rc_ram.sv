// rc_ram: a memory with one write port and one registered read port, the shape of an FPGA block
// RAM (ECP5 DP16KD) used as a simple dual-port RAM: the core's per-thread and per-ray stores.
//
// Contract
// - Write: when we_i, word waddr_i becomes wdata_i at the clock edge.
// - Read: when re_i, word raddr_i appears on rdata_o after the edge (OutReg = 0: one cycle, the
//   block RAM's own read register), or one cycle later through a register in the fabric
//   (OutReg = 1: two cycles; a DP16KD's clock-to-out is 5.8 ns on the LFE5U-85F, so the word
//   reaches logic from a flip-flop). rdata_o holds its word until the next read (the read
//   register keeps it while re_i is 0; the fabric register follows the read register).
// - A read of the word written at the same edge: the model returns the old word; the hardware's
//   is unspecified (no_rw_check: no collision logic around the block RAM). Users never read a
//   word in the cycle it is written (each says why in its own contract).
// - Mapping: a memory of Width * Depth >= BlockBits (1024) bits asks for block RAM (ram_style
//   "block"): a shallow wide store (e.g. 16 threads' records) would otherwise become distributed
//   RAM, on the ECP5 six LUT sites per 64 bits, where one DP16KD holds 18 kbits; smaller ones
//   are left to synthesis.
// - Parameters: Width bits per word (>= 1), Depth words (>= 1), OutReg (0 or 1).
// - Reset: none (contents and read registers are undefined until written and read).
module rc_ram #(
  parameter int unsigned Width  = 8,
  parameter int unsigned Depth  = 16,
  parameter bit          OutReg = 1'b1,
  // Derived (do not override).
  parameter int unsigned AddrW  = (Depth > 1) ? $clog2(Depth) : 1
) (
  input  logic             clk_i,
  input  logic             we_i,
  input  logic [AddrW-1:0] waddr_i,
  input  logic [Width-1:0] wdata_i,
  input  logic             re_i,
  input  logic [AddrW-1:0] raddr_i,
  output logic [Width-1:0] rdata_o
);

  if (Width < 1 || Depth < 1) begin : g_param_check
    $error("rc_ram: need Width >= 1 and Depth >= 1");
  end

  localparam int unsigned BlockBits = 1024;  // from this size on, block RAM (see Mapping)
  logic [Width-1:0] rd_q;

  // The same memory twice: Yosys takes ram_style from the declaration only.
  if (Width * Depth >= BlockBits) begin : g_block
    (* no_rw_check, ram_style = "block" *)
    logic [Width-1:0] mem [0:Depth-1];
    always_ff @(posedge clk_i) begin
      if (we_i) mem[waddr_i] <= wdata_i;
      if (re_i) rd_q <= mem[raddr_i];
    end
  end else begin : g_auto
    (* no_rw_check *)
    logic [Width-1:0] mem [0:Depth-1];
    always_ff @(posedge clk_i) begin
      if (we_i) mem[waddr_i] <= wdata_i;
      if (re_i) rd_q <= mem[raddr_i];
    end
  end

  if (OutReg) begin : g_out_reg
    logic [Width-1:0] out_q;
    always_ff @(posedge clk_i) out_q <= rd_q;
    assign rdata_o = out_q;
  end else begin : g_no_out_reg
    assign rdata_o = rd_q;
  end

endmodule
