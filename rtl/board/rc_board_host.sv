// rc_board_host: command interpreter between a host's UART byte stream and rc_board's register
// port and framebuffer read port (docs/fpga.md, "The UART protocol").
//
// Contract
// - Protocol (bytes from the host on rx_*, answers to the host on tx_*; values little-endian):
//     'W' (0x57) addr d0 d1 d2 d3   write register addr with {d3, d2, d1, d0}; no answer
//     'R' (0x52) addr               answer the 4 bytes of register addr
//     'S' (0x53)                    start a frame: write 1 to BoardRegControl; no answer
//     'F' (0x46)                    answer width * height * 3 bytes: R, G, B of each pixel in
//                                   pixel-id order (y * width + x), width and height being the
//                                   BoardRegWidth/BoardRegHeight registers when 'F' arrives
//   addr is a register number (rc_pkg::BoardReg*, docs/spec.toml [board_reg]). Any other byte in
//   place of a command is ignored, so a host can send filler (e.g. 0x00) harmlessly. A pixel id
//   >= FbPixels (a frame larger than the framebuffer, which rc_board refuses) is sent as 0, 0, 0.
//   The register port has no side effects on reads, so an 'F' during a frame is legal (it shows
//   the frame in progress).
// - Flow control: the host waits for a command's answer before sending the next command. A byte
//   that arrives while an answer is being fetched or sent is dropped (drop_o pulses). If
//   TimeoutCycles > 0, a command whose remaining bytes (addr, d0 .. d3) do not arrive within
//   TimeoutCycles cycles of the previous byte is abandoned (nothing written), which resynchronises
//   the stream after a lost byte.
// - Byte streams: rx_valid_i is a one-cycle strobe with rx_data_i (rc_uart_rx: no backpressure).
//   tx_valid_o/tx_ready_i/tx_data_o is a valid/ready handshake (rc_uart_tx); tx_valid_o comes from
//   a register, never depends on tx_ready_i, and tx_valid_o/tx_data_o hold until taken.
// - Register port: reg_we_o/reg_addr_o/reg_wdata_o come from registers; a write is a single cycle
//   of reg_we_o. reg_rdata_i is the register at reg_addr_o of rc_pkg::BoardReadLatency cycles
//   before (rc_board's read latency). Framebuffer: fb_rdata_i is the pixel at fb_raddr_o of
//   rc_pkg::BoardFbReadLatency cycles before.
// - Latency: a 'W' or 'S' writes 1 cycle after its last byte's strobe; an 'R' answer's first byte
//   is offered BoardReadLatency + 2 cycles after the addr strobe; each pixel of an 'F' is fetched
//   in BoardFbReadLatency + 3 cycles after its predecessor's last byte was taken (the UART, 30
//   bit times per pixel, is the bottleneck). fb_rdata_i goes straight into a register.
// - Illegal input: none (every byte sequence is handled as above).
// - Reset: rst_ni (active low, asynchronous) abandons any command and answer.
module rc_board_host #(
  parameter int unsigned FbPixels      = rc_pkg::BoardFbPixels,
  parameter int unsigned TimeoutCycles = 0,
  // Derived (do not override).
  parameter int unsigned AddrW   = rc_pkg::BoardAddrBits,
  parameter int unsigned FbAddrW = (FbPixels > 1) ? $clog2(FbPixels) : 1,
  parameter int unsigned TimeW   = (TimeoutCycles > 0) ? $clog2(TimeoutCycles + 1) : 1
) (
  input  logic               clk_i,
  input  logic               rst_ni,

  // Bytes from the host (rc_uart_rx).
  input  logic               rx_valid_i,
  input  logic [7:0]         rx_data_i,

  // Bytes to the host (rc_uart_tx).
  output logic               tx_valid_o,
  input  logic               tx_ready_i,
  output logic [7:0]         tx_data_o,

  // rc_board's register port.
  output logic               reg_we_o,
  output logic [AddrW-1:0]   reg_addr_o,
  output logic [31:0]        reg_wdata_o,
  input  logic [31:0]        reg_rdata_i,

  // rc_board's framebuffer read port.
  output logic [FbAddrW-1:0] fb_raddr_o,
  input  logic [23:0]        fb_rdata_i,

  // A byte was dropped (it arrived while an answer was being fetched or sent).
  output logic               drop_o
);

  localparam int unsigned CoordW = rc_pkg::BoardCoordBits;

  if (AddrW < 8 || FbPixels < 1) begin : g_param_check
    $error("rc_board_host: need AddrW >= 8 (the protocol's address is a byte) and FbPixels >= 1");
  end

  localparam logic [7:0] CmdWrite = 8'h57;  // 'W'
  localparam logic [7:0] CmdRead  = 8'h52;  // 'R'
  localparam logic [7:0] CmdStart = 8'h53;  // 'S'
  localparam logic [7:0] CmdFrame = 8'h46;  // 'F'

  typedef enum logic [3:0] {
    StIdle,        // waiting for a command byte
    StAddr,        // 'W' or 'R': waiting for the address byte
    StData,        // 'W': waiting for data bytes d0 .. d3
    StRegWait,     // 'R': the board reads the register
    StRegTake,     // 'R': reg_rdata_i holds it
    StWidthWait,   // 'F': the board reads the width register
    StWidthTake,
    StHeightWait,  // 'F': the board reads the height register
    StHeightTake,
    StPixel,       // 'F': next pixel, or the end of the frame
    StPixWait,     // 'F': the board reads the framebuffer
    StPixTake,     // 'F': fb_rdata_i holds the pixel
    StPixLoad,     // 'F': the pixel's bytes go to out_q
    StSend         // sending out_q's low bytes
  } state_e;

  state_e              state_q;
  logic                cmd_write_q;  // StAddr: the command is 'W' (else 'R')
  logic [1:0]          nbytes_q;     // StData: data bytes received
  logic                we_q;
  logic [AddrW-1:0]    raddr_q;
  logic [31:0]         wdata_q;
  logic [31:0]         out_q;        // answer bytes, the next one at [7:0]
  logic [2:0]          left_q;       // answer bytes left in out_q
  logic                frame_q;      // the answer is an 'F' (StSend returns to StPixel)
  logic [CoordW-1:0]   width_q, height_q, x_q, y_q;
  logic [31:0]         pix_q;        // pixel id y * width + x
  logic                pix_ok_q;     // pix_q < FbPixels when the read was issued
  logic [23:0]         pix_data_q;   // the pixel as read (a register straight after the RAM)
  logic [FbAddrW-1:0]  fb_raddr_q;
  logic                drop_q;
  logic [TimeW-1:0]    idle_q;       // cycles since the last byte (saturating)
  logic                timeout;
  logic                timeout_q;    // idle_q >= TimeoutCycles, registered from the next count
  // A read's wait: the register reads' *Wait states last BoardReadLatency cycles, StPixWait
  // BoardFbReadLatency cycles (rd_wait_q counts the cycles left after this one; loaded with
  // every new read address).
  localparam int unsigned RdLat   = rc_pkg::BoardReadLatency;
  localparam int unsigned FbLat   = rc_pkg::BoardFbReadLatency;
  localparam int unsigned MaxLat  = (RdLat > FbLat) ? RdLat : FbLat;
  localparam int unsigned RdWaitW = (MaxLat > 1) ? $clog2(MaxLat) : 1;
  logic [RdWaitW-1:0]  rd_wait_q;
  logic                rd_ready;
  assign rd_ready = rd_wait_q == '0;
  if (RdLat < 1 || FbLat < 1) begin : g_lat_check
    $error("rc_board_host: BoardReadLatency and BoardFbReadLatency must be at least 1");
  end

  // The count's compare is registered (from the count as it will be: no byte now and the count
  // one short, or at its saturated top), so the command state starts at a flip-flop instead
  // of at the compare's carry chain.
  localparam int unsigned TimeLim = (TimeoutCycles > 0) ? TimeoutCycles : 1;
  assign timeout = (TimeoutCycles != 0) && timeout_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q     <= StIdle;
      cmd_write_q <= 1'b0;
      nbytes_q    <= '0;
      we_q        <= 1'b0;
      raddr_q     <= '0;
      wdata_q     <= '0;
      out_q       <= '0;
      left_q      <= '0;
      frame_q     <= 1'b0;
      width_q     <= '0;
      height_q    <= '0;
      x_q         <= '0;
      y_q         <= '0;
      pix_q       <= '0;
      pix_ok_q    <= 1'b0;
      pix_data_q  <= '0;
      fb_raddr_q  <= '0;
      drop_q      <= 1'b0;
      idle_q      <= '0;
      timeout_q   <= 1'b0;
      rd_wait_q   <= '0;
    end else begin
      if (!rd_ready) rd_wait_q <= rd_wait_q - 1'b1;
      we_q   <= 1'b0;
      drop_q <= 1'b0;
      timeout_q <= !rx_valid_i && (32'(idle_q) + 32'd1 >= TimeLim);
      if (rx_valid_i) begin
        idle_q <= '0;
      end else if (idle_q != '1) begin
        idle_q <= idle_q + 1'b1;
      end

      unique case (state_q)
        StIdle: begin
          if (rx_valid_i) begin
            unique case (rx_data_i)
              CmdWrite: begin
                cmd_write_q <= 1'b1;
                state_q     <= StAddr;
              end
              CmdRead: begin
                cmd_write_q <= 1'b0;
                state_q     <= StAddr;
              end
              CmdStart: begin
                raddr_q <= AddrW'(rc_pkg::BoardRegControl);
                wdata_q <= 32'd1;
                we_q    <= 1'b1;
              end
              CmdFrame: begin
                raddr_q   <= AddrW'(rc_pkg::BoardRegWidth);
                rd_wait_q <= RdWaitW'(RdLat - 1);
                state_q   <= StWidthWait;
              end
              default: begin end  // not a command: ignored
            endcase
          end
        end
        StAddr: begin
          if (rx_valid_i) begin
            raddr_q   <= AddrW'(rx_data_i);
            nbytes_q  <= '0;
            rd_wait_q <= RdWaitW'(RdLat - 1);
            state_q   <= cmd_write_q ? StData : StRegWait;
          end else if (timeout) begin
            state_q <= StIdle;
          end
        end
        StData: begin
          if (rx_valid_i) begin
            wdata_q  <= {rx_data_i, wdata_q[31:8]};
            nbytes_q <= nbytes_q + 2'd1;
            if (nbytes_q == 2'd3) begin
              we_q    <= 1'b1;
              state_q <= StIdle;
            end
          end else if (timeout) begin
            state_q <= StIdle;
          end
        end
        StRegWait: if (rd_ready) state_q <= StRegTake;
        StRegTake: begin
          out_q   <= reg_rdata_i;
          left_q  <= 3'd4;
          frame_q <= 1'b0;
          state_q <= StSend;
        end
        StWidthWait: if (rd_ready) state_q <= StWidthTake;
        StWidthTake: begin
          width_q   <= reg_rdata_i[CoordW-1:0];
          raddr_q   <= AddrW'(rc_pkg::BoardRegHeight);
          rd_wait_q <= RdWaitW'(RdLat - 1);
          state_q   <= StHeightWait;
        end
        StHeightWait: if (rd_ready) state_q <= StHeightTake;
        StHeightTake: begin
          height_q <= reg_rdata_i[CoordW-1:0];
          x_q      <= '0;
          y_q      <= '0;
          pix_q    <= '0;
          state_q  <= StPixel;
        end
        StPixel: begin
          if (width_q == '0 || y_q == height_q) begin
            state_q <= StIdle;
          end else begin
            fb_raddr_q <= FbAddrW'(pix_q);
            pix_ok_q   <= pix_q < 32'(FbPixels);
            rd_wait_q  <= RdWaitW'(FbLat - 1);
            state_q    <= StPixWait;
          end
        end
        StPixWait: if (rd_ready) state_q <= StPixTake;
        // The framebuffer's read data goes to a plain register first.
        StPixTake: begin
          pix_data_q <= fb_rdata_i;
          state_q    <= StPixLoad;
        end
        StPixLoad: begin
          out_q   <= pix_ok_q ? {8'd0, pix_data_q} : 32'd0;
          left_q  <= 3'd3;
          frame_q <= 1'b1;
          pix_q   <= pix_q + 32'd1;
          if (x_q == width_q - 1'b1) begin
            x_q <= '0;
            y_q <= y_q + 1'b1;
          end else begin
            x_q <= x_q + 1'b1;
          end
          state_q <= StSend;
        end
        StSend: begin
          if (tx_ready_i) begin
            out_q  <= {8'd0, out_q[31:8]};
            left_q <= left_q - 3'd1;
            if (left_q == 3'd1) state_q <= frame_q ? StPixel : StIdle;
          end
        end
        default: state_q <= StIdle;
      endcase

      // Bytes are taken only while waiting for a command or its arguments.
      if (rx_valid_i && state_q != StIdle && state_q != StAddr && state_q != StData) begin
        drop_q <= 1'b1;
      end
    end
  end

  assign tx_valid_o  = state_q == StSend;
  assign tx_data_o   = out_q[7:0];
  assign reg_we_o    = we_q;
  assign reg_addr_o  = raddr_q;
  assign reg_wdata_o = wdata_q;
  assign fb_raddr_o  = fb_raddr_q;
  assign drop_o      = drop_q;

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

  // An offered byte stays offered and unchanged until taken (valid/ready protocol).
  TxHold_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    tx_valid_o && !tx_ready_i |=> tx_valid_o && $stable(tx_data_o));
  // StSend always has a byte to send.
  SendNonEmpty_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    state_q == StSend |-> left_q != 3'd0 && left_q <= 3'd4);
  // The pixel counters stay inside the frame.
  PixInFrame_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
    state_q == StPixel && width_q != '0 |-> x_q < width_q && y_q <= height_q);
`endif

endmodule
