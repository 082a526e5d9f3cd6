// rc_reg_copies: one register written as several identical copies, each kept by synthesis, so
// that groups of consumers far apart each read a flip-flop of their own.
//
// Contract
// - Function: q_o[c*Width +: Width] is d_i registered, for every copy c (Copies_A): all copies
//   hold one value in every cycle.
// - Why: a register that feeds several units across the chip puts one long net on every path that
//   starts at it (docs/fpga.md, "What is left"). Yosys merges flip-flops with the same input
//   (opt_merge) unless the cell carries `keep`; the attribute on the always_ff reaches the $dff
//   cell (on the variable it does not), and the copies stay separate TRELLIS_FF through
//   synth_ecp5.
// - Latency: one cycle. No handshake.
// - Parameters: Width bits per copy (>= 1), Copies (>= 1), HasReset (1: asynchronous reset to
//   ResetVal; 0: a data register without reset).
// - Reset: rst_ni (active low, asynchronous) when HasReset; otherwise unused.
module rc_reg_copies #(
  parameter int unsigned      Width    = 1,
  parameter int unsigned      Copies   = 2,
  parameter bit               HasReset = 1'b0,
  parameter logic [Width-1:0] ResetVal = '0
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic [Width-1:0]         d_i,
  output logic [Copies*Width-1:0]  q_o
);

  if (Width < 1 || Copies < 1) begin : g_param_check
    $error("rc_reg_copies: need Width >= 1 and Copies >= 1");
  end

  for (genvar c = 0; c < Copies; c++) begin : g_copy
    if (HasReset) begin : g_rst
      (* keep *) always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) begin
          q_o[c*Width +: Width] <= ResetVal;
        end else begin
          q_o[c*Width +: Width] <= d_i;
        end
      end
    end else begin : g_plain
      (* keep *) always_ff @(posedge clk_i) begin
        q_o[c*Width +: Width] <= d_i;
      end
    end
  end

  logic unused_rst;
  assign unused_rst = HasReset ? 1'b0 : rst_ni;

`ifndef SYNTHESIS
  // Simulation-only: 1 from the first clock edge after a reset (rc_checks_on).
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // Every copy holds copy 0's value (the owner reads any copy as the register).
  Copies_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                            q_o == {Copies{q_o[0 +: Width]}});
`endif

endmodule
