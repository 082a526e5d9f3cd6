// rc_board_host_tb: test bench top for tests/board/board_host_test.cpp (not synthesized).
//
// Contract
// - Loopback: lb_valid_i/lb_ready_o/lb_data_i feed an rc_uart_tx whose line (lb_line_o) drives
//   an rc_uart_rx (lb_rx_valid_o, lb_rx_data_o, lb_rx_frame_error_o): bytes in, bytes out.
// - Host: the serial line rx_i (driven bit by bit by the test) -> rc_uart_rx -> rc_board_host ->
//   rc_uart_tx -> the serial line tx_o (decoded by the test). The host's register port goes to a
//   fake register file: 256 registers of 32 bits, register a initialised to RegInit(a), written
//   by reg_we, read with rc_board's latency (rc_pkg::BoardReadLatency cycles, the value sampled
//   in the address's cycle, so a host that takes it early gets an older read); its framebuffer
//   port goes to a fake framebuffer of FbPixels 24-bit pixels with rc_board's latency
//   (rc_pkg::BoardFbReadLatency cycles: a host that takes the pixel early gets an older one),
//   which the test fills through fb_we_i/fb_waddr_i/fb_wdata_i. No core: it verilates and runs
//   in seconds.
// - Monitor: mon_we_o/mon_addr_o/mon_wdata_o show each register write of the host, drop_o its
//   dropped-byte pulses, rx_frame_error_o the host receiver's framing errors.
// - Parameters: ClkHz and Baud of all UARTs (a small ratio keeps the test fast), FbPixels,
//   TimeoutCycles of the host.
// - Illegal input: none. Reset: rst_ni (active low, asynchronous) for all units.
module rc_board_host_tb #(
  parameter int unsigned ClkHz         = 8,
  parameter int unsigned Baud          = 1,
  parameter int unsigned FbPixels      = 64,
  parameter int unsigned TimeoutCycles = 400,
  // Derived (do not override).
  parameter int unsigned AddrW   = rc_pkg::BoardAddrBits,
  parameter int unsigned FbAddrW = (FbPixels > 1) ? $clog2(FbPixels) : 1
) (
  input  logic               clk_i,
  input  logic               rst_ni,

  // Loopback.
  input  logic               lb_valid_i,
  output logic               lb_ready_o,
  input  logic [7:0]         lb_data_i,
  output logic               lb_line_o,
  output logic               lb_rx_valid_o,
  output logic [7:0]         lb_rx_data_o,
  output logic               lb_rx_frame_error_o,

  // Host serial lines.
  input  logic               rx_i,
  output logic               tx_o,

  // Fake framebuffer fill.
  input  logic               fb_we_i,
  input  logic [FbAddrW-1:0] fb_waddr_i,
  input  logic [23:0]        fb_wdata_i,

  // Monitor.
  output logic               mon_we_o,
  output logic [AddrW-1:0]   mon_addr_o,
  output logic [31:0]        mon_wdata_o,
  output logic               drop_o,
  output logic               rx_frame_error_o
);

  //////////////
  // Loopback //
  //////////////

  rc_uart_tx #(.ClkHz(ClkHz), .Baud(Baud)) u_lb_tx (
    .clk_i,
    .rst_ni,
    .valid_i(lb_valid_i),
    .ready_o(lb_ready_o),
    .data_i (lb_data_i),
    .tx_o   (lb_line_o)
  );

  rc_uart_rx #(.ClkHz(ClkHz), .Baud(Baud)) u_lb_rx (
    .clk_i,
    .rst_ni,
    .rx_i         (lb_line_o),
    .valid_o      (lb_rx_valid_o),
    .data_o       (lb_rx_data_o),
    .frame_error_o(lb_rx_frame_error_o)
  );

  //////////
  // Host //
  //////////

  logic             rx_valid, tx_valid, tx_ready;
  logic [7:0]       rx_data, tx_data;
  logic             reg_we;
  logic [AddrW-1:0] reg_addr;
  logic [31:0]      reg_wdata, reg_rdata_q;
  logic [FbAddrW-1:0] fb_raddr;
  logic [23:0]      fb_rdata;

  rc_uart_rx #(.ClkHz(ClkHz), .Baud(Baud)) u_rx (
    .clk_i,
    .rst_ni,
    .rx_i,
    .valid_o      (rx_valid),
    .data_o       (rx_data),
    .frame_error_o(rx_frame_error_o)
  );

  rc_board_host #(.FbPixels(FbPixels), .TimeoutCycles(TimeoutCycles)) u_host (
    .clk_i,
    .rst_ni,
    .rx_valid_i (rx_valid),
    .rx_data_i  (rx_data),
    .tx_valid_o (tx_valid),
    .tx_ready_i (tx_ready),
    .tx_data_o  (tx_data),
    .reg_we_o   (reg_we),
    .reg_addr_o (reg_addr),
    .reg_wdata_o(reg_wdata),
    .reg_rdata_i(reg_rdata_q),
    .fb_raddr_o (fb_raddr),
    .fb_rdata_i (fb_rdata),
    .drop_o
  );

  rc_uart_tx #(.ClkHz(ClkHz), .Baud(Baud)) u_tx (
    .clk_i,
    .rst_ni,
    .valid_i(tx_valid),
    .ready_o(tx_ready),
    .data_i (tx_data),
    .tx_o
  );

  ////////////////////////
  // Fake register file //
  ////////////////////////

  localparam int unsigned Regs = 1 << AddrW;

  function automatic logic [31:0] reg_init(int unsigned a);
    reg_init = (32'(a) * 32'h0101_0101) ^ 32'hA5C3_0F96;
  endfunction

  logic [31:0] regs_q [0:Regs-1];

  initial begin
    for (int unsigned a = 0; a < Regs; a++) regs_q[a] = reg_init(a);
  end

  localparam int unsigned RdLat = rc_pkg::BoardReadLatency;
  logic [31:0] rd_pipe_q [0:RdLat-1];

  always_ff @(posedge clk_i) begin
    if (reg_we) regs_q[reg_addr] <= reg_wdata;
    rd_pipe_q[0] <= regs_q[reg_addr];
    for (int unsigned k = 1; k < RdLat; k++) rd_pipe_q[k] <= rd_pipe_q[k-1];
  end
  assign reg_rdata_q = rd_pipe_q[RdLat-1];

  //////////////////////
  // Fake framebuffer //
  //////////////////////

  localparam int unsigned FbLat = rc_pkg::BoardFbReadLatency;
  logic [23:0] fb_q [0:FbPixels-1];
  logic [23:0] fb_pipe_q [0:FbLat-1];

  always_ff @(posedge clk_i) begin
    if (fb_we_i) fb_q[fb_waddr_i] <= fb_wdata_i;
    fb_pipe_q[0] <= fb_q[fb_raddr];
    for (int unsigned k = 1; k < FbLat; k++) fb_pipe_q[k] <= fb_pipe_q[k-1];
  end
  assign fb_rdata = fb_pipe_q[FbLat-1];

  assign mon_we_o    = reg_we;
  assign mon_addr_o  = reg_addr;
  assign mon_wdata_o = reg_wdata;

endmodule
