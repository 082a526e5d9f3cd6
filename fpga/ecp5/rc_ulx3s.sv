// rc_ulx3s: the board build on the ULX3S (Lattice ECP5 LFE5U-85F, CABGA381); docs/fpga.md.
// Port names are the ULX3S constraint file's (fpga/ecp5/ulx3s.lpf), not _i/_o.
//
// Contract
// - Clock: clk_25mhz (the board's oscillator) -> EHXPLLL -> the core clock, f = 25 MHz *
//   ClkfbDiv / ClkiDiv, VCO = f * ClkopDiv (400 .. 800 MHz), feedback from CLKOP. The flow
//   (fpga/fpga_ecp5.py) computes the dividers for the requested frequency and passes CoreHz = f
//   (the UART's bit timing is derived from it). Everything but the PLL runs on the core clock.
// - Reset: asynchronous assert while the PLL is not locked, synchronous release (two flip-flops)
//   after lock. btn[0] (PWRn, the power button) is not used.
// - Host link: the FTDI serial port at Baud, 8N1: ftdi_txd is the PC's transmit (FPGA receives),
//   ftdi_rxd the PC's receive (FPGA transmits). rc_board_host interprets it (protocol in its
//   contract and in docs/fpga.md): 'W' addr d0..d3, 'R' addr, 'S', 'F'; a command left unfinished
//   for a quarter second is abandoned.
// - Buttons: btn[1] (FIRE1, active high) is synchronised and debounced (it must be stable for
//   10 ms) and its press starts a frame (rc_board start_i), with the camera and frame size in the
//   register file (initially those of RegsHex). btn[6:2] are not used.
// - LEDs: led[0] heartbeat (0.5 .. 1 Hz), led[1] busy, led[2] done, led[3]
//   size_error or config_error (the start was refused), led[7:4] rc_core's error bits (malformed node, bad address, stack overflow,
//   watchdog: rc_pkg::CoreStatus*).
// - Parameters: rc_board's (Threads; LitThreads, LitSlots and LitShadowPackets, the lit board's;
//   Lit, ROM depths and hex files: `raycore board-image` writes them with board.json), the PLL
//   dividers with CoreHz, and Baud.
// - Illegal input: none.
module rc_ulx3s #(
  // EHXPLLL dividers (fpga/fpga_ecp5.py computes them) and the resulting core clock in Hz.
  parameter int unsigned ClkiDiv     = 1,
  parameter int unsigned ClkfbDiv    = 4,
  parameter int unsigned ClkopDiv    = 6,
  parameter int unsigned ClkopCphase = 5,
  parameter int unsigned CoreHz      = 100_000_000,
  parameter int unsigned Baud        = 115_200,
  // rc_board.
  parameter int unsigned Threads   = rc_pkg::BoardThreads,
  parameter int unsigned LitThreads = rc_pkg::BoardLitThreads,
  parameter int unsigned LitSlots  = rc_pkg::BoardLitSlots,
  parameter int unsigned LitShadowPackets = rc_pkg::BoardLitShadowPackets,
  parameter int unsigned NodeDepth = 1,
  parameter int unsigned ListDepth = 1,
  parameter int unsigned TriDepth  = 1,
  parameter int unsigned ShdDepth  = 1,
  parameter int unsigned MatDepth  = 1,
  parameter int unsigned FbPixels  = rc_pkg::BoardFbPixels,
  parameter bit          Lit       = 1'b0,
  parameter int unsigned LShdDepth = 1,
  parameter int unsigned LMatDepth = 1,
  parameter              NodeHex   = "",
  parameter              ListHex   = "",
  parameter              TriHex    = "",
  parameter              ShdHex    = "",
  parameter              MatHex    = "",
  parameter              LShdHex   = "",
  parameter              LMatHex   = "",
  parameter              RegsHex   = ""
) (
  input  logic       clk_25mhz,
  input  logic [6:0] btn,
  output logic [7:0] led,
  output logic       ftdi_rxd,
  input  logic       ftdi_txd
);

  localparam int unsigned AddrW      = rc_pkg::BoardAddrBits;
  localparam int unsigned FbAddrW    = (FbPixels > 1) ? $clog2(FbPixels) : 1;
  localparam int unsigned StatusW    = rc_pkg::CoreStatusBits;
  localparam int unsigned W          = 1 + rc_pkg::Fp24ExpW + rc_pkg::Fp24FracW;
  localparam int unsigned DebounceW  = $clog2(CoreHz / 100 + 1);  // 10 ms
  localparam int unsigned HeartbeatW = $clog2(CoreHz);  // MSB period 2^W / CoreHz: 1 .. 2 s

  if (StatusW > 4) begin : g_led_check
    $error("rc_ulx3s: the LEDs show 4 core error bits");
  end

  /////////
  // PLL //
  /////////

  logic clk, pll_lock;
  logic [5:0] pll_unused;  // outputs of the PLL not used

  // Loop filter settings as Project Trellis's ecppll gives them for these PLL configurations.
  (* ICP_CURRENT = "12", LPF_RESISTOR = "8", MFG_ENABLE_FILTEROPAMP = "1", MFG_GMCREF_SEL = "2" *)
  EHXPLLL #(
    .PLLRST_ENA      ("DISABLED"),
    .INTFB_WAKE      ("DISABLED"),
    .STDBY_ENABLE    ("DISABLED"),
    .DPHASE_SOURCE   ("DISABLED"),
    .OUTDIVIDER_MUXA ("DIVA"),
    .OUTDIVIDER_MUXB ("DIVB"),
    .OUTDIVIDER_MUXC ("DIVC"),
    .OUTDIVIDER_MUXD ("DIVD"),
    .CLKI_DIV        (ClkiDiv),
    .CLKOP_ENABLE    ("ENABLED"),
    .CLKOP_DIV       (ClkopDiv),
    .CLKOP_CPHASE    (ClkopCphase),
    .CLKOP_FPHASE    (0),
    .FEEDBK_PATH     ("CLKOP"),
    .CLKFB_DIV       (ClkfbDiv)
  ) u_pll (
    .RST         (1'b0),
    .STDBY       (1'b0),
    .CLKI        (clk_25mhz),
    .CLKOP       (clk),
    .CLKOS       (pll_unused[0]),
    .CLKOS2      (pll_unused[1]),
    .CLKOS3      (pll_unused[2]),
    .CLKFB       (clk),
    .CLKINTFB    (pll_unused[3]),
    .PHASESEL0   (1'b0),
    .PHASESEL1   (1'b0),
    .PHASEDIR    (1'b1),
    .PHASESTEP   (1'b1),
    .PHASELOADREG(1'b1),
    .PLLWAKESYNC (1'b0),
    .ENCLKOP     (1'b0),
    .ENCLKOS     (1'b0),
    .ENCLKOS2    (1'b0),
    .ENCLKOS3    (1'b0),
    .LOCK        (pll_lock),
    .INTLOCK     (pll_unused[4]),
    .REFCLK      (pll_unused[5])
  );

  ///////////
  // Reset //
  ///////////

  logic [1:0] rst_sync_q;  // active high: 1 while in reset
  logic       rst, rst_n;

  always_ff @(posedge clk or negedge pll_lock) begin
    if (!pll_lock) begin
      rst_sync_q <= 2'b11;
    end else begin
      rst_sync_q <= {rst_sync_q[0], 1'b0};
    end
  end

  // The synchronised reset reaches every flip-flop with an asynchronous reset (tens of thousands
  // of them): on fabric routing its release missed the clock period by over a nanosecond (run
  // 19), so it goes through a global buffer (DCCA) onto a global network, as the clock does.
  // The global carries it active high, the polarity of the ECP5 flip-flops' LSR pins: Yosys
  // makes an active-low reset active high with an inverter LUT, which, after the buffer, sent
  // the whole fan-out over fabric routing again (run 63 seed 5: 7.23 ns from that LUT to a
  // set-up FIFO's LSR). Here the design's rst_n is that inverter's input inverted, so the two
  // cancel and every LSR pin is on the global network.
  DCCA u_rst_buf (
    .CLKI(rst_sync_q[1]),
    .CE  (1'b1),
    .CLKO(rst)
  );
  assign rst_n = ~rst;

  ////////////////////////////////
  // FIRE1: start a frame       //
  ////////////////////////////////

  logic [1:0]           fire_sync_q;
  logic                 fire_q, start;
  logic [DebounceW-1:0] fire_cnt_q;

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      fire_sync_q <= 2'b00;
      fire_q      <= 1'b0;
      fire_cnt_q  <= '0;
    end else begin
      fire_sync_q <= {fire_sync_q[0], btn[1]};
      if (fire_sync_q[1] == fire_q) begin
        fire_cnt_q <= '0;
      end else if (fire_cnt_q == DebounceW'(CoreHz / 100)) begin
        fire_q     <= fire_sync_q[1];
        fire_cnt_q <= '0;
      end else begin
        fire_cnt_q <= fire_cnt_q + 1'b1;
      end
    end
  end

  // The press (debounced rising edge): one cycle, registered (the count's compare ends at a
  // flip-flop instead of at the board's frame control: run 23).
  logic start_q;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      start_q <= 1'b0;
    end else begin
      start_q <= fire_sync_q[1] && !fire_q && fire_cnt_q == DebounceW'(CoreHz / 100);
    end
  end
  assign start = start_q;

  ///////////////
  // Host link //
  ///////////////

  logic             rx_valid, tx_valid, tx_ready, rx_frame_error, host_drop;
  logic [7:0]       rx_data, tx_data;
  logic             reg_we;
  logic [AddrW-1:0] reg_addr;
  logic [31:0]      reg_wdata, reg_rdata;
  logic [FbAddrW-1:0] fb_raddr;
  logic [23:0]      fb_rdata;

  rc_uart_rx #(.ClkHz(CoreHz), .Baud(Baud)) u_uart_rx (
    .clk_i        (clk),
    .rst_ni       (rst_n),
    .rx_i         (ftdi_txd),
    .valid_o      (rx_valid),
    .data_o       (rx_data),
    .frame_error_o(rx_frame_error)
  );

  // The received byte and its strobe are registered once more in front of the host, so the
  // receiver can sit near its pin and the host near the register file: run 57 (seed 1) placed
  // them apart, and the receiver's output register -> the host's command decode -> rd_wait_q
  // failed by 0.88 ns. The byte stream has no backpressure; a cycle's delay changes nothing.
  logic       rx_valid_q;
  logic [7:0] rx_data_q;
  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      rx_valid_q <= 1'b0;
    end else begin
      rx_valid_q <= rx_valid;
    end
  end
  always_ff @(posedge clk) begin
    rx_data_q <= rx_data;
  end

  rc_board_host #(
    .FbPixels     (FbPixels),
    .TimeoutCycles(CoreHz / 4)
  ) u_host (
    .clk_i      (clk),
    .rst_ni     (rst_n),
    .rx_valid_i (rx_valid_q),
    .rx_data_i  (rx_data_q),
    .tx_valid_o (tx_valid),
    .tx_ready_i (tx_ready),
    .tx_data_o  (tx_data),
    .reg_we_o   (reg_we),
    .reg_addr_o (reg_addr),
    .reg_wdata_o(reg_wdata),
    .reg_rdata_i(reg_rdata),
    .fb_raddr_o (fb_raddr),
    .fb_rdata_i (fb_rdata),
    .drop_o     (host_drop)
  );

  rc_uart_tx #(.ClkHz(CoreHz), .Baud(Baud)) u_uart_tx (
    .clk_i  (clk),
    .rst_ni (rst_n),
    .valid_i(tx_valid),
    .ready_o(tx_ready),
    .data_i (tx_data),
    .tx_o   (ftdi_rxd)
  );

  ///////////
  // Board //
  ///////////

  logic               busy, done, size_error, config_error;
  logic [StatusW-1:0] core_error;
  logic               mon_valid, mon_hit;
  logic [31:0]        mon_pixel, mon_tri;
  logic [23:0]        mon_rgb;
  logic [W-1:0]       mon_t, mon_u, mon_v;
  logic [rc_pkg::LightMaxLights-1:0] mon_lights;
  logic [31:0]        mon_bounce_tri, mon_refract_tri;

  rc_board #(
    .Threads  (Threads),
    .LitThreads(LitThreads),
    .LitSlots (LitSlots),
    .LitShadowPackets(LitShadowPackets),
    .NodeDepth(NodeDepth),
    .ListDepth(ListDepth),
    .TriDepth (TriDepth),
    .ShdDepth (ShdDepth),
    .MatDepth (MatDepth),
    .FbPixels (FbPixels),
    .Lit      (Lit),
    .LShdDepth(LShdDepth),
    .LMatDepth(LMatDepth),
    .NodeHex  (NodeHex),
    .ListHex  (ListHex),
    .TriHex   (TriHex),
    .ShdHex   (ShdHex),
    .MatHex   (MatHex),
    .LShdHex  (LShdHex),
    .LMatHex  (LMatHex),
    .RegsHex  (RegsHex)
  ) u_board (
    .clk_i       (clk),
    .rst_ni      (rst_n),
    .reg_we_i    (reg_we),
    .reg_addr_i  (reg_addr),
    .reg_wdata_i (reg_wdata),
    .reg_rdata_o (reg_rdata),
    .start_i     (start),
    .fb_raddr_i  (fb_raddr),
    .fb_rdata_o  (fb_rdata),
    .busy_o      (busy),
    .done_o      (done),
    .size_error_o(size_error),
    .config_error_o(config_error),
    .error_o     (core_error),
    .mon_valid_o (mon_valid),
    .mon_pixel_o (mon_pixel),
    .mon_rgb_o   (mon_rgb),
    .mon_hit_o   (mon_hit),
    .mon_tri_o   (mon_tri),
    .mon_t_o     (mon_t),
    .mon_u_o     (mon_u),
    .mon_v_o     (mon_v),
    .mon_lights_o(mon_lights),
    .mon_bounce_tri_o(mon_bounce_tri),
    .mon_refract_tri_o(mon_refract_tri)
  );

  //////////
  // LEDs //
  //////////

  logic [HeartbeatW-1:0] beat_q;
  logic [7:0]            led_q;

  always_ff @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      beat_q <= '0;
      led_q  <= '0;
    end else begin
      beat_q <= beat_q + 1'b1;
      led_q  <= {4'(core_error), size_error || config_error, done, busy, beat_q[HeartbeatW-1]};
    end
  end

  assign led = led_q;

  // Not used on the board: the monitor (simulation), the other buttons, the receiver's framing
  // errors and the host's dropped bytes (a host that waits for its answers sees neither).
  logic unused;
  assign unused = ^{mon_valid, mon_pixel, mon_rgb, mon_hit, mon_tri, mon_t, mon_u, mon_v,
                    mon_lights, mon_bounce_tri, mon_refract_tri, btn[6:2], btn[0], rx_frame_error, host_drop, pll_unused};

endmodule
