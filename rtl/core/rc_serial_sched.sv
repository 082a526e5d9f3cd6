// rc_serial_sched: the schedule of a component-serial unit (rc_hit_geom, rc_light_term): the
// input register's three slots and, for every cycle of a job's fixed schedule, whether a job is
// at that cycle.
//
// Contract
// - Slots: take_i (the owner's valid_i & ready_o) loads the owner's input register; the job is
//   then in slot 0, 1 and 2 (slot_o one-hot, all zero: the register is empty) in the next three
//   cycles, one vector component (x, y, z) entering the owner's operations in each.
// - in_free_o: the register is free (empty, or in its job's last slot), a flip-flop registered
//   from the slot counter's next value, so the owner's ready_o (its credit AND this) comes from
//   two flip-flops and never depends on valid_i; the next job can be taken in slot 2, one job per
//   3 cycles (Phased: one per Period cycles, below).
// - Phased = 1: in_free_o is also low unless the cycle's phase (a counter modulo Period, 0 after
//   reset) is Period - 1, so every job's slot 0 falls at phase 0 and its time T at phase
//   T mod Period, for every job. Scalar operations (one cycle per job) whose times differ modulo
//   3 can then share an operator: no two jobs ever bring them to it in one cycle (Period is a
//   multiple of 3). Jobs follow each other every Period cycles; a job offered at another phase
//   waits at most Period - 1 cycles.
// - at_o[T]: a job is at time T of its schedule in this cycle (T cycles after its slot 0; at_o[0]
//   is slot_o[0]), T = 0 .. Time. strm_o[T] = at_o[T] | at_o[T + 1] | at_o[T + 2]: a vector
//   operation issued at time T (its x, then y and z) is busy in this cycle.
// - Parameters: Time (>= 3), the last time the owner needs; Phased (above); Period (a multiple
//   of 3, 3 .. 15): the cycles between two jobs' slot 0 when Phased (without Phased it must be
//   3: a job may then be taken in any job's slot 2).
// - Reset: rst_ni (active low, asynchronous) empties the slots and the chain.
module rc_serial_sched #(
  parameter int unsigned Time   = 3,
  parameter bit          Phased = 1'b0,
  parameter int unsigned Period = 3
) (
  input  logic          clk_i,
  input  logic          rst_ni,
  input  logic          take_i,
  output logic [2:0]    slot_o,
  output logic          in_free_o,
  output logic [Time:0] at_o,
  output logic [Time-2:0] strm_o
);

  if (Time < 3) begin : g_param_check
    $error("rc_serial_sched: Time must be at least 3");
  end
  if (Period < 3 || Period > 15 || Period % 3 != 0 || (!Phased && Period != 3))
  begin : g_period_check
    $error("rc_serial_sched: Period must be 3, 6, 9, 12 or 15 (3 without Phased)");
  end

  localparam logic [3:0] LastPhase = 4'(Period - 1);

  logic [2:0]      slot_q, slot_d;
  logic            in_free_q;
  logic [Time-1:0] first_q;  // first_q[k]: a job's slot 0 was k + 1 cycles ago
  logic [3:0]      phase_q, phase_d;  // 0 .. Period - 1
  logic            free_d;

  assign slot_d  = take_i ? 3'b001 : slot_q << 1;
  assign phase_d = (phase_q == LastPhase) ? 4'd0 : phase_q + 4'd1;
  assign free_d  = (~|slot_d | slot_d[2]) & (~Phased | (phase_d == LastPhase));

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      slot_q    <= '0;
      in_free_q <= ~Phased;
      first_q   <= '0;
      phase_q   <= '0;
    end else begin
      slot_q    <= slot_d;
      in_free_q <= free_d;
      first_q   <= {first_q[Time-2:0], slot_q[0]};
      phase_q   <= phase_d;
    end
  end

  assign slot_o    = slot_q;
  assign in_free_o = in_free_q;
  assign at_o      = {first_q, slot_q[0]};
  for (genvar t = 0; t <= Time - 2; t++) begin : g_strm
    assign strm_o[t] = at_o[t] | at_o[t+1] | at_o[t+2];
  end

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  // The owner takes a job only while the register is free.
  TakeWhenFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   take_i |-> in_free_q);
  // Job starts are at least three cycles apart, so a scalar the owner holds for a stream's three
  // cycles is never overwritten within them.
  StartsApart_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  slot_q[0] |-> !first_q[0] && !first_q[1]);
  // in_free_q is the register's freedom as the slot counter says (at the last phase when Phased).
  InFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             in_free_q == ((~|slot_q | slot_q[2]) &
                                           (~Phased | phase_q == LastPhase)));
  // Phased: every job's slot 0 is at phase 0.
  SlotPhase_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                Phased & slot_q[0] |-> phase_q == 4'd0);
`endif

endmodule
