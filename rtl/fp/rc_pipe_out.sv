// rc_pipe_out: the output end of a valid-only pipeline, shared by the arithmetic units.
//
// Contract
// - Function: data_o is data_i delayed by DataRegs clock cycles (registers without reset);
//   valid_o is valid_i delayed by Stages cycles (a chain with asynchronous active-low reset).
//   The owning unit feeds data_i from its last combinational segment and valid_i straight from its
//   own valid_i, so Stages is the unit's latency and DataRegs the registers left after the cuts
//   inside the unit (DataRegs <= Stages).
// - Handshake: valid only, no backpressure; one item per cycle.
// - Parameters: Width (>= 1), DataRegs (>= 1), Stages (>= DataRegs).
// - Illegal input: none.
// - Checks (simulation): once out of reset, valid_o is never X, and data_o is never X while
//   valid_o is 1.
module rc_pipe_out #(
  parameter int unsigned Width    = 1,
  parameter int unsigned DataRegs = 1,
  parameter int unsigned Stages   = 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             valid_i,
  input  logic [Width-1:0] data_i,
  output logic             valid_o,
  output logic [Width-1:0] data_o
);

  if (DataRegs < 1 || Stages < DataRegs) begin : g_bad_params
    $error("rc_pipe_out: need 1 <= DataRegs <= Stages");
  end

  logic [DataRegs*Width-1:0] data_q;
  always_ff @(posedge clk_i) begin
    data_q <= (data_q << Width) | (DataRegs * Width)'(data_i);
  end
  assign data_o = data_q[DataRegs*Width-1 -: Width];

  logic [Stages-1:0] valid_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
    end else begin
      valid_q <= (valid_q << 1) | Stages'(valid_i);
    end
  end
  assign valid_o = valid_q[Stages-1];

`ifndef SYNTHESIS
  // Simulation-only: 1 from the first clock edge after a reset (rc_checks_on).
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  // The consumer qualifies data_o with valid_o, so valid_o must be known once out of reset.
  ValidKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 !$isunknown(valid_o));
  // A valid result must be fully determined by inputs that were known when they were valid.
  DataKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                valid_o |-> !$isunknown(data_o));
`endif

endmodule
