// rc_board_rom_tb: test bench top for tests/board/board_rom_test.cpp (not synthesized).
//
// Contract
// - Function: one rc_board_rom (u_rom) with the same parameters and ports, passed straight
//   through, plus a debug output that shows its FIFO entries' write enables (u_rom.entry_we),
//   so the test reads them as a port instead of Verilator-internal names. The test checks they
//   never follow rsp_ready_i within a cycle. It is a hierarchical reference, so renaming the
//   signal in rc_board_rom breaks this bench (rc_board_rom's contract names it).
// - A test bench wrapper only: never synthesized, not in rtl/rtl_files.f.
// - Parameters, handshake, latency, illegal input, reset: those of rc_board_rom.
module rc_board_rom_tb #(
  parameter int unsigned Width    = 32,
  parameter int unsigned Depth    = 1,
  parameter int unsigned IdxW     = 32,
  parameter int unsigned TagW     = 8,
  parameter              InitFile = "",
  parameter              Name     = "rom"
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             req_valid_i,
  output logic             req_ready_o,
  input  logic [TagW-1:0]  req_tag_i,
  input  logic [IdxW-1:0]  req_index_i,
  output logic             rsp_valid_o,
  input  logic             rsp_ready_i,
  output logic [TagW-1:0]  rsp_tag_o,
  output logic [Width-1:0] rsp_data_o,
  output logic             rsp_error_o,

  // Debug: the FIFO entries' write enables inside u_rom (three entries).
  output logic [2:0]       dbg_entry_we_o
);

  rc_board_rom #(
    .Width   (Width),
    .Depth   (Depth),
    .IdxW    (IdxW),
    .TagW    (TagW),
    .InitFile(InitFile),
    .Name    (Name)
  ) u_rom (
    .clk_i,
    .rst_ni,
    .req_valid_i,
    .req_ready_o,
    .req_tag_i,
    .req_index_i,
    .rsp_valid_o,
    .rsp_ready_i,
    .rsp_tag_o,
    .rsp_data_o,
    .rsp_error_o
  );

  assign dbg_entry_we_o = u_rom.entry_we;

endmodule
