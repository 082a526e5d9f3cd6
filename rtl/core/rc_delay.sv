// rc_delay: a fixed delay line (shift register) of Cycles clock cycles.
//
// Contract
// - Function: data_o = data_i as it was Cycles rising edges earlier. Every cycle shifts; there is
//   no enable and no handshake (it runs beside a valid-only pipeline whose valid bits travel
//   elsewhere).
// - Latency: Cycles (>= 0; 0 is a wire).
// - Parameters: Width data bits (>= 1).
// - Illegal input: none. Reset: none (data only; before Cycles edges data_o is undefined).
module rc_delay #(
  parameter int unsigned Width  = 1,
  parameter int unsigned Cycles = 1
) (
  input  logic             clk_i,
  input  logic [Width-1:0] data_i,
  output logic [Width-1:0] data_o
);

  if (Width < 1) begin : g_param_check
    $error("rc_delay: Width must be >= 1");
  end

  if (Cycles == 0) begin : g_wire
    assign data_o = data_i;
    logic unused_clk;
    assign unused_clk = clk_i;
  end else begin : g_shift
    // Stage i at sr_q[i*Width +: Width]; stage 0 takes data_i.
    logic [Cycles*Width-1:0] sr_q;

    always_ff @(posedge clk_i) begin
      sr_q[0 +: Width] <= data_i;
      for (int unsigned i = 1; i < Cycles; i++) begin
        sr_q[i*Width +: Width] <= sr_q[(i-1)*Width +: Width];
      end
    end

    assign data_o = sr_q[(Cycles-1)*Width +: Width];
  end

endmodule
