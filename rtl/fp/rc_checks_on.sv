// rc_checks_on: simulation-only enable for assertions.
//
// Contract
// - on_o is 0 until the first clock edge after a reset has been seen, then 1 until the next
//   reset. Assertions use it (disable iff (on !== 1'b1)) instead of sampling rst_ni
//   synchronously, so rst_ni stays a purely asynchronous reset, and they stay quiet before the
//   first reset while pipelines still hold X.
// - Synthesis (SYNTHESIS defined): on_o is constant 0 and nothing is built; only assertions,
//   which synthesis ignores, read it.
// - Handshake: none. Illegal input: none.
module rc_checks_on (
  input  logic clk_i,
  input  logic rst_ni,
  output logic on_o
);

`ifndef SYNTHESIS
  logic on_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      on_q <= 1'b0;
    end else begin
      on_q <= 1'b1;
    end
  end
  assign on_o = on_q;
`else
  assign on_o = 1'b0;
  logic unused_clk_rst;
  assign unused_clk_rst = clk_i ^ rst_ni;
`endif

endmodule
