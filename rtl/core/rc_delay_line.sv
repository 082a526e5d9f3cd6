// rc_delay_line: a fixed delay line of Cycles clock cycles, as a shift register (rc_delay) or,
// with Block = 1, as a circular buffer in block RAM (rc_delay_ram with ForceBlock).
//
// Contract
// - Function: data_o = data_i as it was Cycles rising edges earlier, either way (every cycle
//   shifts; no enable, no handshake: it runs beside a valid-only pipeline whose valid bits travel
//   elsewhere). Only where the bits are kept differs: Width x Cycles flip-flops, or block RAM with
//   Width flip-flops behind it (a unit's wide delay lines on the lit board, where flip-flops fill
//   the logic tiles: docs/fpga.md).
// - Latency: Cycles (>= 1; >= 3 with Block).
// - Parameters: Width data bits (>= 1), Cycles, Block (0 or 1).
// - Illegal input: none. Reset: rst_ni (active low, asynchronous) clears rc_delay_ram's write
//   pointer (Block = 1; unused otherwise); before Cycles edges data_o is undefined.
module rc_delay_line #(
  parameter int unsigned Width  = 1,
  parameter int unsigned Cycles = 1,
  parameter bit          Block  = 1'b0
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic [Width-1:0] data_i,
  output logic [Width-1:0] data_o
);

  if (Block) begin : g_block
    rc_delay_ram #(.Width(Width), .Cycles(Cycles), .ForceBlock(1'b1)) u_ram (
      .clk_i, .rst_ni, .data_i, .data_o
    );
  end else begin : g_shift
    rc_delay #(.Width(Width), .Cycles(Cycles)) u_shift (.clk_i, .data_i, .data_o);
    logic unused_rst;
    assign unused_rst = rst_ni;
  end

endmodule
