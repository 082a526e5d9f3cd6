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
//   3 cycles.
// - Phased = 1: in_free_o is also low unless the cycle's phase (a counter modulo 3, 0 after reset)
//   is 2, so every job's slot 0 falls at phase 0 and its time T at phase T mod 3, for every job.
//   Scalar operations (one cycle per job) whose times differ modulo 3 can then share an operator:
//   no two jobs ever bring them to it in one cycle. Jobs still follow each other every 3 cycles;
//   a job offered at another phase waits at most 2 cycles.
// - at_o[T]: a job is at time T of its schedule in this cycle (T cycles after its slot 0; at_o[0]
//   is slot_o[0]), T = 0 .. Time. strm_o[T] = at_o[T] | at_o[T + 1] | at_o[T + 2]: a vector
//   operation issued at time T (its x, then y and z) is busy in this cycle.
// - Parameters: Time (>= 3), the last time the owner needs; Phased (above).
// - Reset: rst_ni (active low, asynchronous) empties the slots and the chain.
module rc_serial_sched #(
  parameter int unsigned Time   = 3,
  parameter bit          Phased = 1'b0
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

  logic [2:0]      slot_q, slot_d;
  logic            in_free_q;
  logic [Time-1:0] first_q;  // first_q[k]: a job's slot 0 was k + 1 cycles ago
  logic [1:0]      phase_q, phase_d;
  logic            free_d;

  assign slot_d  = take_i ? 3'b001 : slot_q << 1;
  assign phase_d = (phase_q == 2'd2) ? 2'd0 : phase_q + 2'd1;
  assign free_d  = (~|slot_d | slot_d[2]) & (~Phased | (phase_d == 2'd2));

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
  // in_free_q is the register's freedom as the slot counter says (at phase 2 when Phased).
  InFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                             in_free_q == ((~|slot_q | slot_q[2]) & (~Phased | phase_q == 2'd2)));
  // Phased: every job's slot 0 is at phase 0.
  SlotPhase_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                Phased & slot_q[0] |-> phase_q == 2'd0);
`endif

endmodule
