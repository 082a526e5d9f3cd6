// rc_uart_tx: UART transmitter, 8N1 (one start bit, 8 data bits least significant first, no
// parity, one stop bit), for the board build's host link (rc_board_host, docs/fpga.md).
//
// Contract
// - Handshake: valid_i/ready_o. A byte is taken when valid_i & ready_o. ready_o comes from a
//   register (1 while no frame is being sent) and does not depend on valid_i.
// - Line: tx_o idles high. The start bit begins on the cycle after the taking edge; each bit lasts
//   ClksPerBit = round(ClkHz / Baud) cycles, the frame 10 bit times. ready_o is 1 while idle and
//   in the last cycle of the stop bit, so back-to-back bytes are sent without idle time (a frame
//   every 10 * ClksPerBit cycles).
// - Parameters: ClkHz (clock frequency in Hz) and Baud; need ClkHz / Baud >= 2 (the receiver,
//   rc_uart_rx, samples at mid-bit). The bit rate is ClkHz / ClksPerBit: the rounding error must
//   stay within what the receiving end tolerates (about 2 % for 8N1).
// - Illegal input: none (valid_i while ready_o = 0 is not taken and may be held or dropped).
// - Reset: rst_ni (active low, asynchronous) idles the line and drops a byte being sent.
module rc_uart_tx #(
  parameter int unsigned ClkHz = 25_000_000,
  parameter int unsigned Baud  = 115_200,
  // Derived (do not override).
  parameter int unsigned ClksPerBit = (ClkHz + Baud / 2) / Baud,
  parameter int unsigned CntW       = $clog2(ClksPerBit + 1)
) (
  input  logic       clk_i,
  input  logic       rst_ni,
  input  logic       valid_i,
  output logic       ready_o,
  input  logic [7:0] data_i,
  output logic       tx_o
);

  if (Baud < 1 || ClksPerBit < 2) begin : g_param_check
    $error("rc_uart_tx: need Baud >= 1 and ClkHz / Baud >= 2");
  end

  // Frame bits still to send, least significant first: {stop, data[7:0], start}; bits_q counts
  // them. cnt_q counts the cycles left of the current bit.
  logic [9:0]      frame_q;
  logic [3:0]      bits_q;
  logic [CntW-1:0] cnt_q;
  logic            busy, ready;

  assign busy  = bits_q != 4'd0;
  assign ready = !busy || (bits_q == 4'd1 && cnt_q == '0);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      frame_q <= '1;
      bits_q  <= '0;
      cnt_q   <= '0;
    end else if (ready && valid_i) begin
      frame_q <= {1'b1, data_i, 1'b0};
      bits_q  <= 4'd10;
      cnt_q   <= CntW'(ClksPerBit - 1);
    end else if (busy) begin
      if (cnt_q != '0) begin
        cnt_q <= cnt_q - 1'b1;
      end else begin
        frame_q <= {1'b1, frame_q[9:1]};
        bits_q  <= bits_q - 4'd1;
        cnt_q   <= CntW'(ClksPerBit - 1);
      end
    end
  end

  // The line is a flip-flop: frame_q[0] is 1 while idle (reset value and shift-in are 1).
  assign tx_o    = frame_q[0];
  assign ready_o = ready;

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

  // An idle line is high, so the receiver sees each start bit as a falling edge.
  IdleHigh_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    !busy |-> tx_o);
  // A frame has at most 10 bits.
  BitsInRange_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    bits_q <= 4'd10);
`endif

endmodule
