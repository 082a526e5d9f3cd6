// rc_flag_pair: one control flag registered twice, as itself and as its inverse, so that two
// flip-flops share its fan-out.
//
// Contract
// - Function: q_o is d_i registered, qn_o is ~d_i registered: qn_o == ~q_o in every cycle
//   (FlagPair_A). The owner uses q_o on one side of its logic and ~qn_o on the other, so no one
//   flip-flop (and no one net) drives both sides: a flag that enables hundreds of registers across
//   a unit otherwise puts one long net on every path that starts at it (docs/fpga.md, "Rules for
//   the clock", fan-out).
// - Why the inverse: Yosys merges flip-flops with the same input (opt_merge), so two copies of
//   d_i would become one again; the inverse is a different function and stays a flip-flop of its
//   own.
// - Latency: one cycle. No handshake.
// - Parameters: ResetVal, q_o's value in reset (qn_o's is its inverse).
// - Reset: rst_ni (active low, asynchronous).
module rc_flag_pair #(
  parameter bit ResetVal = 1'b0
) (
  input  logic clk_i,
  input  logic rst_ni,
  input  logic d_i,
  output logic q_o,
  output logic qn_o
);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      q_o  <= ResetVal;
      qn_o <= ~ResetVal;
    end else begin
      q_o  <= d_i;
      qn_o <= ~d_i;
    end
  end

`ifndef SYNTHESIS
  // Simulation-only: 1 from the first clock edge after a reset (rc_checks_on).
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // The two flip-flops always hold one value (the owner reads either side as the flag).
  FlagPair_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1) qn_o == !q_o);
`endif

endmodule
