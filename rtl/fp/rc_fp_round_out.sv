// rc_fp_round_out: the last cycles of the raycore dividers and square roots (rc_fp_div,
// rc_fp_sqrt, rc_fp_div_iter, rc_fp_sqrt_iter): the register in front of the rounding, the
// rounding and packing, and the output registers with the valid chain.
//
// Contract
// - Function: fin_i is the last slot's state (rc_fp_div_fin's or rc_fp_sqrt_fin's: the result's
//   kinds for both outcomes of the rounding carry, sign, man_ones, exponent field, fraction,
//   round_up); with Cut it passes a register (no reset), without it goes straight on; then
//   rc_fp_round_pack makes the result word, which passes DataRegs output registers; valid_o is
//   valid_i (the owning unit's own input valid) delayed by Stages cycles (rc_pipe_out).
// - Parameters: ExpW (>= 2), FracW (>= 1): the format; Cut: the register in front of the rounding;
//   DataRegs (>= 1), Stages (>= DataRegs): as rc_pipe_out's.
// - Handshake: valid only, no backpressure. Reset: rst_ni (active low, asynchronous) clears the
//   valid chain only.
module rc_fp_round_out #(
  parameter int unsigned ExpW     = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW    = rc_pkg::Fp24FracW,
  parameter bit          Cut      = 1'b1,
  parameter int unsigned DataRegs = 1,
  parameter int unsigned Stages   = 1
) (
  input  logic                                             clk_i,
  input  logic                                             rst_ni,
  input  logic                                             valid_i,
  input  logic [2*rc_pkg::FpResultKindBits+ExpW+FracW+2:0] fin_i,
  output logic                                             valid_o,
  output logic [ExpW+FracW:0]                              res_o
);

  localparam int unsigned W    = 1 + ExpW + FracW;
  localparam int unsigned FinW = 2 * rc_pkg::FpResultKindBits + 2 + ExpW + FracW + 1;

  logic [FinW-1:0] fin_q;
  if (Cut) begin : g_cut
    always_ff @(posedge clk_i) begin
      fin_q <= fin_i;
    end
  end else begin : g_no_cut
    assign fin_q = fin_i;
  end

  logic [2*rc_pkg::FpResultKindBits-1:0] kinds;
  logic                                  sign, man_ones, round_up;
  logic [ExpW-1:0]                       exp;
  logic [FracW-1:0]                      frac;
  logic [W-1:0]                          res_d;

  assign {kinds, sign, man_ones, exp, frac, round_up} = fin_q;

  rc_fp_round_pack #(
    .ExpW (ExpW),
    .FracW(FracW)
  ) u_round_pack (
    .kind_i    (kinds),
    .sign_i    (sign),
    .man_ones_i(man_ones),
    .exp_i     (exp),
    .exp_inc_i (exp + ExpW'(1)),
    .frac_i    (frac),
    .round_up_i(round_up),
    .res_o     (res_d)
  );

  rc_pipe_out #(
    .Width   (W),
    .DataRegs(DataRegs),
    .Stages  (Stages)
  ) u_out (
    .clk_i,
    .rst_ni,
    .valid_i,
    .data_i (res_d),
    .valid_o,
    .data_o (res_o)
  );

endmodule
