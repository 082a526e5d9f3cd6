// rc_delay_ram: a fixed delay line of Cycles clock cycles kept in a memory (a circular buffer),
// for long delays where a shift register's flip-flops would cost too much.
//
// Contract
// - Function: data_o = data_i as it was Cycles rising edges earlier, as rc_delay (every cycle
//   shifts; no enable, no handshake: it runs beside a valid-only pipeline).
// - Structure: a memory of Depth = 2^ceil(log2(Cycles)) words (ram_style: distributed RAM, e.g.
//   ECP5 DPR16X4, up to 64 words; block RAM beyond): each cycle data_i is written at the write
//   pointer and the word written Cycles - 1 cycles earlier is read into the output register, so
//   data_o is Cycles cycles late.
//   The read address is never the one being written (Cycles - 1 < Depth).
// - Latency: Cycles (>= 2).
// - Parameters: Width data bits (>= 1), Cycles (>= 2).
// - Illegal input: none. Reset: rst_ni (active low, asynchronous) clears the write pointer only
//   (the memory and the output register have no reset: before Cycles edges data_o is undefined).
module rc_delay_ram #(
  parameter int unsigned Width  = 1,
  parameter int unsigned Cycles = 2
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
  // Deeper than this, the memory goes to block RAM (ECP5 DP16KD: 512 x 36), where a LUT RAM's
  // read multiplexer would cost more than its storage (Yosys: 923 LUT4 sites for 256 x 24).
  localparam int unsigned BlockDepth = 64;

  logic [AddrW-1:0] wp_q, rp;
  logic [Width-1:0] rd_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) wp_q <= '0;
    else wp_q <= wp_q + AddrW'(1);
  end

  assign rp = wp_q - AddrW'(Cycles - 1);

  // The same memory either way; only where it goes differs (a read register behind it in both).
  if (Depth > BlockDepth) begin : g_block
    (* ram_style = "block" *) logic [Width-1:0] mem_q [Depth];
    always_ff @(posedge clk_i) begin
      mem_q[wp_q] <= data_i;
      rd_q        <= mem_q[rp];
    end
  end else begin : g_lut
    (* ram_style = "distributed" *) logic [Width-1:0] mem_q [Depth];
    always_ff @(posedge clk_i) begin
      mem_q[wp_q] <= data_i;
      rd_q        <= mem_q[rp];
    end
  end

  assign data_o = rd_q;

endmodule
