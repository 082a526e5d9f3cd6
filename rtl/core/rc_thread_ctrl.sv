// rc_thread_ctrl: the control state that every packet thread of rc_core keeps in flip-flops and
// several units read or change: its error bits, its stack depth, which of its rays exist and
// which have a hit (docs/architecture.md, "Thread control").
//
// Contract
// - State per thread t: err_o[3t +: 3] (rc_pkg::CoreStatus* bits 0..2, sticky for the packet),
//   sp_o[CoreSpBits t +: CoreSpBits] (stack entries), vmask_o[4t +: 4] (rays that exist),
//   hit_o[4t +: 4] (rays with a best hit: the best-hit stores' words count only where this bit
//   is set), pop_end_o[t] = (err != 0 || sp == 0): a pop of the thread ends its walk. All are
//   flip-flops, read by the units through their own selects.
// - Events (each names its thread; every event is for a thread in the unit's hands, so two events
//   that write the same field of one thread never come in one cycle, which assertions check):
//     intake (acc_*): a new packet: err, sp, hit cleared, vmask = acc_vmask_i;
//     error bits (errN_*): ORed into err (the traversal decision, the node port's error response,
//       the pop unit's routing, a failed list entry, a failed triangle read);
//     stack depth (sp_*): the traversal decision's push writes sp + 1 (sp_tr_*), a pop writes
//       sp - 1 (sp_pop_*, through the pop's one-hot grant);
//     hit (hit_*): the best-hit write-back's commit sets the ray's bit.
// - Timing: every event changes the state at the clock edge that ends its cycle; reads see it from
//   the next cycle on.
// - Parameters: Threads (>= 1).
// - Reset: rst_ni (active low, asynchronous) clears every field.
module rc_thread_ctrl #(
  parameter int unsigned Threads = rc_pkg::CoreThreads,
  // Derived (do not override).
  parameter int unsigned ThrW    = (Threads > 1) ? $clog2(Threads) : 1,
  parameter int unsigned SpW     = rc_pkg::CoreSpBits
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,

  // A packet taken into thread acc_thr_i.
  input  logic                 acc_valid_i,
  input  logic [ThrW-1:0]      acc_thr_i,
  input  logic [3:0]           acc_vmask_i,

  // Error bits raised, from five units.
  input  logic                 err0_valid_i,    // the traversal decision
  input  logic [ThrW-1:0]      err0_thr_i,
  input  logic [2:0]           err0_bits_i,
  input  logic                 err1_valid_i,    // the node port's error response
  input  logic [ThrW-1:0]      err1_thr_i,
  input  logic [2:0]           err1_bits_i,
  input  logic                 err2_valid_i,    // the pop unit's routing
  input  logic [ThrW-1:0]      err2_thr_i,
  input  logic [2:0]           err2_bits_i,
  input  logic                 err3_valid_i,    // a failed list entry
  input  logic [ThrW-1:0]      err3_thr_i,
  input  logic [2:0]           err3_bits_i,
  input  logic                 err4_valid_i,    // a failed triangle read
  input  logic [ThrW-1:0]      err4_thr_i,
  input  logic [2:0]           err4_bits_i,

  // Stack depth writes.
  input  logic                 sp_tr_valid_i,   // the traversal decision (a push)
  input  logic [ThrW-1:0]      sp_tr_thr_i,
  input  logic [SpW-1:0]       sp_tr_sp_i,
  input  logic [Threads-1:0]   sp_pop_hot_i,    // a pop: one-hot thread (zero: none)
  input  logic [SpW-1:0]       sp_pop_sp_i,

  // A new best hit of ray hit_ray_i of thread hit_thr_i.
  input  logic                 hit_valid_i,
  input  logic [ThrW-1:0]      hit_thr_i,
  input  logic [1:0]           hit_ray_i,

  // The state.
  output logic [Threads*3-1:0]   err_o,
  output logic [Threads*SpW-1:0] sp_o,
  output logic [Threads*4-1:0]   vmask_o,
  output logic [Threads*4-1:0]   hit_o,
  output logic [Threads-1:0]     pop_end_o
);

  if (Threads < 1 || (1 << ThrW) < Threads) begin : g_param_check
    $error("rc_thread_ctrl: need Threads >= 1");
  end

  logic [Threads*3-1:0]   err_q;
  logic [Threads*SpW-1:0] sp_q;
  logic [Threads*4-1:0]   vmask_q, hit_q;

  // Each event's thread one-hot (rc_onehot: shared predecoders, not a compare per thread).
  logic [Threads-1:0] h_acc, h_e0, h_e1, h_e2, h_e3, h_e4, h_sp, h_hit;
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_acc (.valid_i(acc_valid_i),   .idx_i(acc_thr_i),
                                                  .hot_o(h_acc));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_e0  (.valid_i(err0_valid_i),  .idx_i(err0_thr_i),
                                                  .hot_o(h_e0));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_e1  (.valid_i(err1_valid_i),  .idx_i(err1_thr_i),
                                                  .hot_o(h_e1));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_e2  (.valid_i(err2_valid_i),  .idx_i(err2_thr_i),
                                                  .hot_o(h_e2));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_e3  (.valid_i(err3_valid_i),  .idx_i(err3_thr_i),
                                                  .hot_o(h_e3));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_e4  (.valid_i(err4_valid_i),  .idx_i(err4_thr_i),
                                                  .hot_o(h_e4));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_sp  (.valid_i(sp_tr_valid_i), .idx_i(sp_tr_thr_i),
                                                  .hot_o(h_sp));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_hit (.valid_i(hit_valid_i),   .idx_i(hit_thr_i),
                                                  .hot_o(h_hit));

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      err_q   <= '0;
      sp_q    <= '0;
      vmask_q <= '0;
      hit_q   <= '0;
    end else begin
      for (int unsigned t = 0; t < Threads; t++) begin
        logic [2:0] err_or;
        err_or = ({3{h_e0[t]}} & err0_bits_i) | ({3{h_e1[t]}} & err1_bits_i) |
                 ({3{h_e2[t]}} & err2_bits_i) | ({3{h_e3[t]}} & err3_bits_i) |
                 ({3{h_e4[t]}} & err4_bits_i);
        err_q[t*3 +: 3] <= h_acc[t] ? 3'd0 : (err_q[t*3 +: 3] | err_or);
        if (h_acc[t]) begin
          sp_q[t*SpW +: SpW] <= '0;
        end else if (h_sp[t]) begin
          sp_q[t*SpW +: SpW] <= sp_tr_sp_i;
        end else if (sp_pop_hot_i[t]) begin
          sp_q[t*SpW +: SpW] <= sp_pop_sp_i;
        end
        if (h_acc[t]) vmask_q[t*4 +: 4] <= acc_vmask_i;
        for (int unsigned r = 0; r < 4; r++) begin
          if (h_acc[t]) begin
            hit_q[t*4 + r] <= 1'b0;
          end else if (h_hit[t] && hit_ray_i == 2'(r)) begin
            hit_q[t*4 + r] <= 1'b1;
          end
        end
      end
    end
  end

  assign err_o   = err_q;
  assign sp_o    = sp_q;
  assign vmask_o = vmask_q;
  assign hit_o   = hit_q;
  for (genvar t = 0; t < Threads; t++) begin : g_pop_end
    assign pop_end_o[t] = (|err_q[t*3 +: 3]) | (sp_q[t*SpW +: SpW] == '0);
  end

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // The two stack-depth writers never meet on one thread (a thread is in the traversal unit or in
  // the pop unit, never both), and a new packet's thread has no other event.
  for (genvar t = 0; t < Threads; t++) begin : g_checks
    SpWriters_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  $onehot0({h_acc[t], h_sp[t], sp_pop_hot_i[t]}));
    AccAlone_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 h_acc[t] |-> !(h_e0[t] | h_e1[t] | h_e2[t] | h_e3[t] | h_e4[t] |
                                                h_hit[t]));
  end
`endif

endmodule
