// rc_uart_rx: UART receiver, 8N1 (one start bit, 8 data bits least significant first, no parity,
// one stop bit), for the board build's host link (rc_board_host, docs/fpga.md).
//
// Contract
// - Line: rx_i is asynchronous to clk_i (a pin); it passes a two-flip-flop synchroniser first.
//   Idle is high. A falling edge starts a frame; the start bit is checked at its middle (a line
//   back high by then was a glitch and is ignored), then each data bit and the stop bit are
//   sampled once, at the middle of the bit: ClksPerBit = round(ClkHz / Baud) cycles apart.
// - Output: valid_o is a one-cycle pulse with the byte on data_o (held until the next byte) when
//   the stop bit was 1; a stop bit of 0 gives a one-cycle frame_error_o pulse instead and the byte
//   is dropped. There is no backpressure: the consumer takes each byte in the cycle of valid_o.
// - Latency: valid_o rises 2 (synchroniser) + about 9.5 bit times after the start bit's falling
//   edge, i.e. at the middle of the stop bit; the receiver is then ready for the next start bit,
//   so back-to-back frames and a sender a few per cent fast or slow are received.
// - Parameters: ClkHz (clock frequency in Hz) and Baud; need ClkHz / Baud >= 2.
// - Illegal input: none (noise gives glitches ignored or framing errors, never a hang).
// - Reset: rst_ni (active low, asynchronous) returns to idle.
module rc_uart_rx #(
  parameter int unsigned ClkHz = 25_000_000,
  parameter int unsigned Baud  = 115_200,
  // Derived (do not override).
  parameter int unsigned ClksPerBit = (ClkHz + Baud / 2) / Baud,
  parameter int unsigned CntW       = $clog2(ClksPerBit + 1)
) (
  input  logic       clk_i,
  input  logic       rst_ni,
  input  logic       rx_i,
  output logic       valid_o,
  output logic [7:0] data_o,
  output logic       frame_error_o
);

  if (Baud < 1 || ClksPerBit < 2) begin : g_param_check
    $error("rc_uart_rx: need Baud >= 1 and ClkHz / Baud >= 2");
  end

  localparam int unsigned HalfBit = ClksPerBit / 2;

  // Two-flip-flop synchroniser (reset to the idle level).
  logic [1:0] sync_q;
  logic       rx;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sync_q <= 2'b11;
    end else begin
      sync_q <= {sync_q[0], rx_i};
    end
  end

  assign rx = sync_q[1];

  typedef enum logic [1:0] {
    StIdle,
    StStart,
    StData,
    StStop
  } state_e;

  state_e          state_q;
  logic [CntW-1:0] cnt_q;    // cycles to the next sample
  // cnt_q == 0, decided a cycle ahead: the sample's decision (the shift register's enable, the
  // state's and the output's updates) then starts at a flip-flop, not at a CntW-bit compare
  // (run 57, seed 1: cnt_q -> shift_q -0.85 ns).
  logic            cnt_zero_q;
  logic [2:0]      bit_q;    // data bit being received
  logic [7:0]      shift_q;  // data bits so far, shifted in from the top
  logic            valid_q, frame_error_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q       <= StIdle;
      cnt_q         <= '0;
      cnt_zero_q    <= 1'b1;
      bit_q         <= '0;
      shift_q       <= '0;
      valid_q       <= 1'b0;
      frame_error_q <= 1'b0;
    end else begin
      valid_q       <= 1'b0;
      frame_error_q <= 1'b0;
      unique case (state_q)
        StIdle: begin
          if (!rx) begin
            state_q    <= StStart;
            cnt_q      <= CntW'(HalfBit - 1);
            cnt_zero_q <= HalfBit == 1;
          end
        end
        StStart: begin
          if (!cnt_zero_q) begin
            cnt_q      <= cnt_q - 1'b1;
            cnt_zero_q <= cnt_q == CntW'(1);
          end else if (rx) begin
            state_q <= StIdle;  // a glitch, not a start bit
          end else begin
            state_q    <= StData;
            cnt_q      <= CntW'(ClksPerBit - 1);
            cnt_zero_q <= 1'b0;  // ClksPerBit >= 2
            bit_q      <= '0;
          end
        end
        StData: begin
          if (!cnt_zero_q) begin
            cnt_q      <= cnt_q - 1'b1;
            cnt_zero_q <= cnt_q == CntW'(1);
          end else begin
            shift_q    <= {rx, shift_q[7:1]};
            cnt_q      <= CntW'(ClksPerBit - 1);
            cnt_zero_q <= 1'b0;
            bit_q      <= bit_q + 3'd1;
            if (bit_q == 3'd7) state_q <= StStop;
          end
        end
        StStop: begin
          if (!cnt_zero_q) begin
            cnt_q      <= cnt_q - 1'b1;
            cnt_zero_q <= cnt_q == CntW'(1);
          end else begin
            state_q       <= StIdle;
            valid_q       <= rx;
            frame_error_q <= !rx;
          end
        end
        default: state_q <= StIdle;
      endcase
    end
  end

  assign valid_o       = valid_q;
  assign data_o        = shift_q;
  assign frame_error_o = frame_error_q;

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

  // A frame ends in exactly one of a byte or a framing error.
  OneOutcome_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    !(valid_o && frame_error_o));
  // A byte is a one-cycle pulse (frames are at least 10 bit times apart).
  ValidPulse_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    valid_o |=> !valid_o);
  // The flag decided a cycle ahead is the count's.
  CntZero_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    cnt_zero_q == (cnt_q == '0));
`endif

endmodule
