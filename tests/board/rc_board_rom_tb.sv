// rc_board_rom_tb: test bench top for tests/board/board_rom_test.cpp (not synthesized).
//
// Contract
// - Function: one rc_board_rom (u_rom) with the same parameters and ports, passed straight
//   through, plus three debug outputs that show its read stage's enables, so the test reads
//   them as ports instead of Verilator-internal names: dbg_a0_free_o (u_rom.a0_free, the
//   address stage's enable), dbg_s1_free_o (u_rom.s1_free, the read enable), dbg_adv_o
//   (u_rom.adv, the read stage's move on, also the clock enable of the FIFO entry it writes).
//   The test checks they never follow rsp_ready_i within a cycle. They are hierarchical
//   references, so renaming those signals in rc_board_rom breaks this bench (rc_board_rom's
//   contract names them).
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

  // Debug: the read stage's enables inside u_rom.
  output logic             dbg_a0_free_o,
  output logic             dbg_s1_free_o,
  output logic             dbg_adv_o
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

  assign dbg_a0_free_o = u_rom.a0_free;
  assign dbg_s1_free_o = u_rom.s1_free;
  assign dbg_adv_o     = u_rom.adv;

endmodule
