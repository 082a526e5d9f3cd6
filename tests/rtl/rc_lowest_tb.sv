// rc_lowest_tb: verilation wrapper of rc_lowest (combinational) for lowest_test.cpp.
//
// Contract
// - req_i, valid_o, idx_o and hot_o are rc_lowest's; clk_i is not read (the harness's
//   VerilatedTb drives a clock on every model).
// - Parameters: N as rc_lowest's (its index width derived).
// A test harness top for Verilator (no logic of its own).
module rc_lowest_tb #(
  parameter int unsigned N    = 8,
  // Derived (do not override).
  parameter int unsigned IdxW = (N > 1) ? $clog2(N) : 1
) (
  input  logic            clk_i,
  input  logic [N-1:0]    req_i,
  output logic            valid_o,
  output logic [IdxW-1:0] idx_o,
  output logic [N-1:0]    hot_o
);

  rc_lowest #(
    .N   (N),
    .IdxW(IdxW)
  ) u_lowest (
    .req_i,
    .valid_o,
    .idx_o,
    .hot_o
  );

  logic unused;
  assign unused = clk_i;

endmodule
