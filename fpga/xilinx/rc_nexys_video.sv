// rc_nexys_video: the board build (rc_board) with its UART host link (rc_board_host, rc_uart_rx,
// rc_uart_tx) on the Digilent Nexys Video, an Artix-7 XC7A200T-1SBG484C. Built by Vivado with
// fpga/xilinx/build.tcl and the pin constraints of fpga/xilinx/nexys_video.xdc (docs/fpga.md).
//
// Contract
// - Pins (sites and I/O standards in nexys_video.xdc, taken from Digilent's Nexys Video master XDC
//   and reference manual; the signal names there in brackets):
//     clk_i       R4   the 100 MHz oscillator [sysclk]
//     cpu_rst_ni  G4   the CPU RESET button [cpu_resetn], low while pressed
//     btnc_i      B22  the centre button [btnc], high while pressed: starts a frame
//     led_o[7:0]  T14 T15 T16 U16 V15 W16 W15 Y13 [led[0] .. led[7]], high = lit
//     uart_rx_i   V18  bytes from the host [uart_tx_in: the USB-UART bridge's transmit line]
//     uart_tx_o   AA19 bytes to the host [uart_rx_out: the bridge's receive line]
// - Clock: everything runs on the 100 MHz board clock directly (ClkHz, which sets the UART bit
//   time and the button and LED timings). To run slower (if Vivado's timing summary shows a
//   negative slack at 100 MHz), put an MMCME2_BASE between clk_i and the logic (CLKIN1_PERIOD
//   10.0, CLKFBOUT_MULT_F 10.0 for a 1000 MHz VCO, CLKOUT0_DIVIDE_F = 1000 / MHz, CLKFBOUT fed
//   back to CLKFBIN, CLKOUT0 through a BUFG as the logic's clock, LOCKED anded into the reset
//   below) and set ClkHz to the new frequency; Vivado derives the generated clock's constraint
//   from the create_clock on clk_i in the XDC.
// - Reset: CPU RESET asserts rst_ni of every module at once (asynchronously); the release is
//   synchronised to the clock by two flip-flops. The FPGA configuration leaves those flip-flops
//   at 0, so every module also starts in reset and leaves it two cycles after configuration.
//   The register file, the ROMs and the framebuffer keep their contents through a reset
//   (rc_board).
// - Start: BTNC, synchronised and sampled every DebounceCycles cycles (10 ms: longer than the
//   button's bounce); a sample of 1 after a sample of 0 is one start_i pulse of rc_board, which
//   starts a frame unless one is running.
// - Host link: UART 8N1 at Baud on uart_rx_i/uart_tx_o with rc_board_host's protocol ('W' write
//   register, 'R' read register, 'S' start, 'F' read the frame; docs/fpga.md), the same as the
//   ULX3S build's (fpga/ecp5/rc_ulx3s.sv), so fpga/ulx3s_host.py drives either board. A command
//   whose bytes stop coming for HostTimeoutCycles (a quarter second) is abandoned (rc_board_host
//   TimeoutCycles).
// - LEDs (as on the ULX3S build): 0 heartbeat (toggles every 2^(clog2(ClkHz) - 1) cycles: 0.67 s
//   at 100 MHz; shows the clock runs and reset is released), 1 busy (a frame is starting or
//   running), 2 done, 3 size error (the frame was larger than the framebuffer), 4 .. 7 rc_core's
//   error bits (malformed node, bad address, stack overflow, watchdog; sticky until reset).
// - Parameters: Threads, the ROM depths and hex files (NodeDepth/NodeHex .. MatDepth/MatHex,
//   RegsHex) and FbPixels go to rc_board unchanged; build.tcl sets them from the board.json
//   that `raycore board-image` writes.
module rc_nexys_video #(
  parameter int unsigned ClkHz             = 100_000_000,
  parameter int unsigned Baud              = 115_200,
  parameter int unsigned DebounceCycles    = ClkHz / 100,
  parameter int unsigned HostTimeoutCycles = ClkHz / 4,
  parameter int unsigned Threads           = rc_pkg::BoardThreads,
  parameter int unsigned NodeDepth         = 1,
  parameter int unsigned ListDepth         = 1,
  parameter int unsigned TriDepth          = 1,
  parameter int unsigned ShdDepth          = 1,
  parameter int unsigned MatDepth          = 1,
  parameter int unsigned FbPixels          = rc_pkg::BoardFbPixels,
  parameter              NodeHex           = "",
  parameter              ListHex           = "",
  parameter              TriHex            = "",
  parameter              ShdHex            = "",
  parameter              MatHex            = "",
  parameter              RegsHex           = ""
) (
  input  logic       clk_i,
  input  logic       cpu_rst_ni,
  input  logic       btnc_i,
  output logic [7:0] led_o,
  input  logic       uart_rx_i,
  output logic       uart_tx_o
);

  localparam int unsigned W       = 1 + rc_pkg::Fp24ExpW + rc_pkg::Fp24FracW;
  localparam int unsigned AddrW   = rc_pkg::BoardAddrBits;
  localparam int unsigned FbAddrW = (FbPixels > 1) ? $clog2(FbPixels) : 1;
  localparam int unsigned StatusW = rc_pkg::CoreStatusBits;
  localparam int unsigned DbW     = $clog2(DebounceCycles + 1);
  localparam int unsigned BeatW   = $clog2(ClkHz);

  if (StatusW != 4 || DebounceCycles < 2 || ClkHz < 4) begin : g_param_check
    $error("rc_nexys_video: the LEDs show four core error bits; need DebounceCycles >= 2");
  end

  ///////////
  // Reset //
  ///////////

  // Asynchronous assertion, synchronous release.
  (* ASYNC_REG = "TRUE" *) logic [1:0] rst_sync_q;
  logic rst_n;

  always_ff @(posedge clk_i or negedge cpu_rst_ni) begin
    if (!cpu_rst_ni) begin
      rst_sync_q <= 2'b00;
    end else begin
      rst_sync_q <= {rst_sync_q[0], 1'b1};
    end
  end

  assign rst_n = rst_sync_q[1];

  //////////////////
  // Start button //
  //////////////////

  (* ASYNC_REG = "TRUE" *) logic [1:0] btn_sync_q;
  logic [DbW-1:0] db_cnt_q;
  logic           btn_q, start_q;

  always_ff @(posedge clk_i or negedge rst_n) begin
    if (!rst_n) begin
      btn_sync_q <= 2'b00;
      db_cnt_q   <= '0;
      btn_q      <= 1'b0;
      start_q    <= 1'b0;
    end else begin
      btn_sync_q <= {btn_sync_q[0], btnc_i};
      start_q    <= 1'b0;
      if (db_cnt_q == DbW'(DebounceCycles - 1)) begin
        db_cnt_q <= '0;
        btn_q    <= btn_sync_q[1];
        start_q  <= btn_sync_q[1] && !btn_q;
      end else begin
        db_cnt_q <= db_cnt_q + 1'b1;
      end
    end
  end

  ///////////////
  // Host link //
  ///////////////

  logic               rx_valid, rx_frame_error;
  logic [7:0]         rx_data;
  logic               tx_valid, tx_ready;
  logic [7:0]         tx_data;
  logic               host_drop;
  logic               reg_we;
  logic [AddrW-1:0]   reg_addr;
  logic [31:0]        reg_wdata, reg_rdata;
  logic [FbAddrW-1:0] fb_raddr;
  logic [23:0]        fb_rdata;

  rc_uart_rx #(
    .ClkHz(ClkHz),
    .Baud (Baud)
  ) u_uart_rx (
    .clk_i,
    .rst_ni       (rst_n),
    .rx_i         (uart_rx_i),
    .valid_o      (rx_valid),
    .data_o       (rx_data),
    .frame_error_o(rx_frame_error)
  );

  rc_uart_tx #(
    .ClkHz(ClkHz),
    .Baud (Baud)
  ) u_uart_tx (
    .clk_i,
    .rst_ni (rst_n),
    .valid_i(tx_valid),
    .ready_o(tx_ready),
    .data_i (tx_data),
    .tx_o   (uart_tx_o)
  );

  rc_board_host #(
    .FbPixels     (FbPixels),
    .TimeoutCycles(HostTimeoutCycles)
  ) u_host (
    .clk_i,
    .rst_ni     (rst_n),
    .rx_valid_i (rx_valid),
    .rx_data_i  (rx_data),
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

  ///////////
  // Board //
  ///////////

  logic               busy, done, size_error;
  logic [StatusW-1:0] core_error;
  logic               mon_valid, mon_hit;
  logic [31:0]        mon_pixel, mon_tri;
  logic [23:0]        mon_rgb;
  logic [W-1:0]       mon_t, mon_u, mon_v;

  rc_board #(
    .Threads  (Threads),
    .NodeDepth(NodeDepth),
    .ListDepth(ListDepth),
    .TriDepth (TriDepth),
    .ShdDepth (ShdDepth),
    .MatDepth (MatDepth),
    .FbPixels (FbPixels),
    .NodeHex  (NodeHex),
    .ListHex  (ListHex),
    .TriHex   (TriHex),
    .ShdHex   (ShdHex),
    .MatHex   (MatHex),
    .RegsHex  (RegsHex)
  ) u_board (
    .clk_i,
    .rst_ni      (rst_n),
    .reg_we_i    (reg_we),
    .reg_addr_i  (reg_addr),
    .reg_wdata_i (reg_wdata),
    .reg_rdata_o (reg_rdata),
    .start_i     (start_q),
    .fb_raddr_i  (fb_raddr),
    .fb_rdata_o  (fb_rdata),
    .busy_o      (busy),
    .done_o      (done),
    .size_error_o(size_error),
    .error_o     (core_error),
    .mon_valid_o (mon_valid),
    .mon_pixel_o (mon_pixel),
    .mon_rgb_o   (mon_rgb),
    .mon_hit_o   (mon_hit),
    .mon_tri_o   (mon_tri),
    .mon_t_o     (mon_t),
    .mon_u_o     (mon_u),
    .mon_v_o     (mon_v)
  );

  // The monitor is for simulation; the UART's framing errors and the host's dropped bytes have no
  // LED (a host sees them as missing answers).
  logic unused_sigs;
  assign unused_sigs = ^{mon_valid, mon_pixel, mon_rgb, mon_hit, mon_tri, mon_t, mon_u, mon_v,
                         rx_frame_error, host_drop};

  //////////
  // LEDs //
  //////////

  logic [BeatW-1:0] beat_q;
  logic [7:0]       led_q;

  always_ff @(posedge clk_i or negedge rst_n) begin
    if (!rst_n) begin
      beat_q <= '0;
      led_q  <= '0;
    end else begin
      beat_q <= beat_q + 1'b1;
      led_q  <= {core_error, size_error, done, busy, beat_q[BeatW-1]};
    end
  end

  assign led_o = led_q;

endmodule
