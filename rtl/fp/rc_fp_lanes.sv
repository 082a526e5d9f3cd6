// rc_fp_lanes: the lanes of the iterative divider and square root (rc_fp_div_iter,
// rc_fp_sqrt_iter): which lane takes the next operation, and the state of the lane whose
// operation has had its last turn.
//
// Contract
// - Function: operation i (a cycle with valid_i) goes to lane i mod Lanes: take_o[l] is valid_i
//   and the lane pointer at l (a round robin over the operations, not over the cycles). fin_o is
//   state_i's word of the lane that took an operation Iters + 1 cycles ago (its last turn done:
//   the owner's last slot reads it), zero when none did (one lane at a time: the lanes'
//   operations came in different cycles); the lane is busy in the Iters cycles before that.
// - Operations i and i + Lanes must come at least Iters + 1 cycles apart, so that a lane is free
//   when its turn comes (assertion LaneFree_A): the owner's contract.
// - Parameters: Lanes (>= 1), Iters (>= 1); Width: a lane's state (state_i holds lane l's at
//   [l*Width +: Width]). Reset: rst_ni (active low, asynchronous) clears the
//   pointer and the lanes' ages.
module rc_fp_lanes #(
  parameter int unsigned Lanes = 1,
  parameter int unsigned Iters = 1,
  parameter int unsigned Width = 1
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  input  logic                   valid_i,
  output logic [Lanes-1:0]       take_o,
  input  logic [Lanes*Width-1:0] state_i,
  output logic [Width-1:0]       fin_o
);

  if (Lanes < 1 || Iters < 1) begin : g_param_check
    $error("rc_fp_lanes: Lanes and Iters must be at least 1");
  end

  localparam int unsigned LaneW = (Lanes > 1) ? $clog2(Lanes) : 1;

  logic [LaneW-1:0] lane_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lane_q <= '0;
    end else if (valid_i) begin
      lane_q <= (32'(lane_q) == Lanes - 1) ? '0 : lane_q + 1'b1;
    end
  end

  logic [Lanes-1:0] busy, at_fin;
  for (genvar l = 0; l < Lanes; l++) begin : g_lane
    logic [Iters:0] age_q;  // age_q[j]: the lane's operation is at cycle j + 1
    assign take_o[l] = valid_i & (32'(lane_q) == l);
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        age_q <= '0;
      end else begin
        age_q <= {age_q[Iters-1:0], take_o[l]};
      end
    end
    assign at_fin[l] = age_q[Iters];
    assign busy[l] = |age_q[Iters-1:0];
  end

  always_comb begin
    fin_o = '0;
    for (int unsigned l = 0; l < Lanes; l++) begin
      fin_o |= state_i[l*Width +: Width] & {Width{at_fin[l]}};
    end
  end

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // Operations i and i + Lanes at least Iters + 1 cycles apart: the lane is free when its turn
  // comes.
  LaneFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               valid_i |-> !busy[lane_q]);
`else
  logic unused_busy;
  assign unused_busy = ^busy;
`endif

endmodule
