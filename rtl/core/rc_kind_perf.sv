// rc_kind_perf: rc_core's counters per ray kind (docs/architecture.md, "Status and counters";
// docs/spec.toml [core_perf] primary_rays ..): every ray taken, traversal step and ray-triangle
// test counted again under the kind of its packet (primary, shadow, bounce, refract).
//
// Contract
// - Kinds: thread t's packet kind (rc_pkg::ray_kind_e) is written at its take (acc_hot_i bit t,
//   the set-up unit's registered one-hot, with acc_kind_i) and kept until the next take into t.
//   A flip-flop pair per thread.
// - inc_o: the increments of the events of the cycle before (registered here: the thread's kind
//   is looked up beside the kinds, and the increments cross the die from a register; rc_core_status
//   registers them again, so a per-kind counter counts its event two cycles after it), by kind k
//   (the [ray_kind] value) and event e at [3*(3k + e) +: 3]:
//     e = 0, rays:     ray_count(acc_vmask_i) when acc_valid_i, under acc_kind_i;
//     e = 1, steps:    steps_i (0..4, the traversal step's active rays) under the kind of thread
//                      step_thr_i;
//     e = 2, tests:    1 when test_i, under the kind of thread test_thr_i.
//   Every field of another kind is 0, so the kinds' fields of one event sum to the core's own
//   count of it (rc_core feeds the same events to the totals).
// - Every step and test is for a thread whose packet was taken (its kind written) at least a
//   cycle before: no event reads a kind in the cycle it is written.
// - Parameters: Threads (>= 1).
// - Reset: rst_ni (active low, asynchronous) sets every thread's kind to RayPrimary and the
//   increments to 0.
module rc_kind_perf #(
  parameter int unsigned Threads = rc_pkg::CoreThreads,
  // Derived (do not override).
  parameter int unsigned ThrW    = (Threads > 1) ? $clog2(Threads) : 1,
  parameter int unsigned KindW   = rc_pkg::RayKindBits,
  parameter int unsigned Kinds   = 1 << KindW,
  parameter int unsigned IncW    = 3 * 3 * Kinds  // three events a kind, 3 bits each
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,

  // A packet taken (the set-up unit's acc_*).
  input  logic                 acc_valid_i,
  input  logic [Threads-1:0]   acc_hot_i,
  input  logic [3:0]           acc_vmask_i,
  input  logic [KindW-1:0]     acc_kind_i,

  // A traversal step and a ray-triangle test.
  input  logic [2:0]           steps_i,
  input  logic [ThrW-1:0]      step_thr_i,
  input  logic                 test_i,
  input  logic [ThrW-1:0]      test_thr_i,

  output logic [IncW-1:0]      inc_o
);

  if (Threads < 1 || (1 << ThrW) < Threads || KindW != 2) begin : g_param_check
    $error("rc_kind_perf: need Threads >= 1 and four ray kinds");
  end

  logic [Threads*KindW-1:0] kind_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      kind_q <= '0;
    end else begin
      for (int unsigned t = 0; t < Threads; t++) begin
        if (acc_hot_i[t]) kind_q[t*KindW +: KindW] <= acc_kind_i;
      end
    end
  end

  // The kinds of the step's and the test's threads (AND-OR selects).
  logic [KindW-1:0] step_kind, test_kind;
  always_comb begin
    step_kind = '0;
    test_kind = '0;
    for (int unsigned t = 0; t < Threads; t++) begin
      step_kind = step_kind | ({KindW{step_thr_i == ThrW'(t)}} & kind_q[t*KindW +: KindW]);
      test_kind = test_kind | ({KindW{test_thr_i == ThrW'(t)}} & kind_q[t*KindW +: KindW]);
    end
  end

  logic [2:0] rays;
  assign rays = acc_valid_i ? rc_pkg::ray_count(acc_vmask_i) : 3'd0;

  // The increments end at a register: the step's and the test's threads come from the traversal
  // and intersection units, and the counters' fronts are across the die (the lit board routed at
  // 6799b81, seed 2: ti_thr_q through the kind's select into rc_core_status's perf_inc_q, -4.69 ns
  // with 12.3 ns of routing).
  logic [IncW-1:0] inc_d, inc_q;
  always_comb begin
    inc_d = '0;
    for (int unsigned k = 0; k < Kinds; k++) begin
      inc_d[3*(3*k + 0) +: 3] = (acc_kind_i == KindW'(k)) ? rays : 3'd0;
      inc_d[3*(3*k + 1) +: 3] = (step_kind == KindW'(k)) ? steps_i : 3'd0;
      inc_d[3*(3*k + 2) +: 3] = 3'(test_i && test_kind == KindW'(k));
    end
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) inc_q <= '0;
    else inc_q <= inc_d;
  end
  assign inc_o = inc_q;

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // A thread's steps and tests come cycles after its take, so they read its new kind.
  StepAfterTake_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    steps_i != 3'd0 |-> !acc_hot_i[step_thr_i]);
  TestAfterTake_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    test_i |-> !acc_hot_i[test_thr_i]);
`endif

endmodule
