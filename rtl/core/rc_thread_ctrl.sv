// rc_thread_ctrl: the control state that every packet thread of rc_core keeps and several units
// read or change: whether it met an error, its stack depth, which of its rays exist and which
// have a best hit (docs/architecture.md, "Thread control").
//
// Contract
// - err_o[t]: thread t's packet met an error (the error bits themselves go straight to the core's
//   status, rc_core_status); set by any of five units' events (errN_*), cleared when a packet is
//   taken into the thread (acc_*). A flip-flop per thread.
// - hit_o[4t + r]: ray r of thread t has a best hit (the best-hit stores' words count only where
//   this bit is set); set by the write-back's commit (hit_*), cleared at acc_*. Flip-flops.
// - Stack depth: 0 after acc_*; the traversal decision's push writes sp + 1 (sp_tr_*), a pop
//   writes sp - 1 (sp_pop_*). Read port sp_rd_thr_i -> sp_rd_o (asynchronous, from distributed
//   RAM). The depths live in two distributed RAMs, one per writer, and a flip-flop pair per
//   thread says which holds its depth or that it is 0 (a live-value table): two writers without a
//   second write port.
// - Rays that exist and the packet's kind: written at acc_*; read port vm_rd_thr_i -> vm_rd_o,
//   vm_rd_sec_o (a secondary packet: acc_sec_i at its take; asynchronous, from distributed RAM).
//   shadow_o[t]: thread t holds a shadow packet (acc_anyhit_i at its take); a flip-flop per
//   thread.
// - Every event is for a thread in its unit's hands: the two depth writers never meet on one
//   thread, and a new packet's thread has no other event (assertions).
// - Timing: an event changes the state at the clock edge that ends its cycle; reads see it from the
//   next cycle on.
// - Parameters: Threads (>= 1).
// - Reset: rst_ni (active low, asynchronous) clears the flip-flops (all depths read 0); the
//   distributed RAMs have no reset (a depth or ray mask is read only after it is written).
module rc_thread_ctrl #(
  parameter int unsigned Threads = rc_pkg::CoreThreads,
  // Derived (do not override).
  parameter int unsigned ThrW    = (Threads > 1) ? $clog2(Threads) : 1,
  parameter int unsigned SpW     = rc_pkg::CoreSpBits
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,

  // A packet taken into thread acc_thr_i (acc_hot_i: the same, one-hot).
  input  logic                 acc_valid_i,
  input  logic [ThrW-1:0]      acc_thr_i,
  input  logic [Threads-1:0]   acc_hot_i,     // acc_valid_i && acc_thr_i == t (a register)
  input  logic [3:0]           acc_vmask_i,
  input  logic                 acc_anyhit_i,
  input  logic                 acc_sec_i,

  // Errors met, from five units.
  input  logic                 err0_valid_i,    // the traversal decision
  input  logic [ThrW-1:0]      err0_thr_i,
  input  logic                 err1_valid_i,    // the node port's error response
  input  logic [ThrW-1:0]      err1_thr_i,
  input  logic                 err2_valid_i,    // the pop unit's routing
  input  logic [ThrW-1:0]      err2_thr_i,
  input  logic                 err3_valid_i,    // a failed list entry
  input  logic [ThrW-1:0]      err3_thr_i,
  input  logic                 err4_valid_i,    // a failed triangle read
  input  logic [ThrW-1:0]      err4_thr_i,

  // Stack depth writes.
  input  logic                 sp_tr_valid_i,   // the traversal decision (a push)
  input  logic [ThrW-1:0]      sp_tr_thr_i,
  input  logic [SpW-1:0]       sp_tr_sp_i,
  input  logic                 sp_pop_valid_i,  // a pop
  input  logic [ThrW-1:0]      sp_pop_thr_i,
  input  logic [SpW-1:0]       sp_pop_sp_i,

  // A new best hit of ray hit_ray_i of thread hit_thr_i.
  input  logic                 hit_valid_i,
  input  logic [ThrW-1:0]      hit_thr_i,
  input  logic [1:0]           hit_ray_i,

  // The state.
  output logic [Threads-1:0]   err_o,
  output logic [Threads-1:0]   shadow_o,
  output logic [Threads*4-1:0] hit_o,
  input  logic [ThrW-1:0]      sp_rd_thr_i,
  output logic [SpW-1:0]       sp_rd_o,
  input  logic [ThrW-1:0]      vm_rd_thr_i,
  output logic [3:0]           vm_rd_o,
  output logic                 vm_rd_sec_o
);

  if (Threads < 1 || (1 << ThrW) < Threads) begin : g_param_check
    $error("rc_thread_ctrl: need Threads >= 1");
  end

  localparam int unsigned Depth = 1 << ThrW;
  localparam logic [1:0]  SpZero = 2'd0, SpFromTr = 2'd1, SpFromPop = 2'd2;

  // Each event's thread one-hot (rc_onehot: shared predecoders, not a compare per thread).
  logic [Threads-1:0] h_acc, h_e0, h_e1, h_e2, h_e3, h_e4, h_sp, h_pop, h_hit;
  // The take's one-hot comes as a register from rc_setup_unit (its bit t drives thread t's
  // state only, where a decode here made each bit of the thread number drive all of it).
  assign h_acc = acc_hot_i;
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_e0  (.valid_i(err0_valid_i),   .idx_i(err0_thr_i),
                                                  .hot_o(h_e0));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_e1  (.valid_i(err1_valid_i),   .idx_i(err1_thr_i),
                                                  .hot_o(h_e1));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_e2  (.valid_i(err2_valid_i),   .idx_i(err2_thr_i),
                                                  .hot_o(h_e2));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_e3  (.valid_i(err3_valid_i),   .idx_i(err3_thr_i),
                                                  .hot_o(h_e3));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_e4  (.valid_i(err4_valid_i),   .idx_i(err4_thr_i),
                                                  .hot_o(h_e4));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_sp  (.valid_i(sp_tr_valid_i),  .idx_i(sp_tr_thr_i),
                                                  .hot_o(h_sp));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_pop (.valid_i(sp_pop_valid_i), .idx_i(sp_pop_thr_i),
                                                  .hot_o(h_pop));
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_hit (.valid_i(hit_valid_i),    .idx_i(hit_thr_i),
                                                  .hot_o(h_hit));

  ////////////////////////////////
  // Error flags and hit bits   //
  ////////////////////////////////

  logic [Threads-1:0]   err_q, shadow_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      err_q    <= '0;
      shadow_q <= '0;
    end else begin
      err_q    <= (err_q & ~h_acc) | h_e0 | h_e1 | h_e2 | h_e3 | h_e4;
      shadow_q <= (shadow_q & ~h_acc) | (h_acc & {Threads{acc_anyhit_i}});
    end
  end
  assign err_o    = err_q;
  assign shadow_o = shadow_q;

  rc_hit_bits #(
    .Threads(Threads)
  ) u_hits (
    .clk_i,
    .rst_ni,
    .acc_hot_i,
    .hit_valid_i,
    .hit_thr_i,
    .hit_ray_i,
    .hit_o
  );

  /////////////////
  // Stack depth //
  /////////////////

  // Two distributed RAMs (one per writer) and which holds the depth, per thread.
  logic [SpW-1:0]       sp_tr_m  [0:Depth-1];
  logic [SpW-1:0]       sp_pop_m [0:Depth-1];
  logic [2*Threads-1:0] sp_sel_q;
  always_ff @(posedge clk_i) begin
    if (sp_tr_valid_i) sp_tr_m[sp_tr_thr_i] <= sp_tr_sp_i;
    if (sp_pop_valid_i) sp_pop_m[sp_pop_thr_i] <= sp_pop_sp_i;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sp_sel_q <= '0;
    end else begin
      for (int unsigned t = 0; t < Threads; t++) begin
        if (h_acc[t]) begin
          sp_sel_q[2*t +: 2] <= SpZero;
        end else if (h_sp[t]) begin
          sp_sel_q[2*t +: 2] <= SpFromTr;
        end else if (h_pop[t]) begin
          sp_sel_q[2*t +: 2] <= SpFromPop;
        end
      end
    end
  end
  // The thread's selector by its number: bit selects of the two selector bits (balanced
  // multiplexer trees, not a chain of compares).
  logic [1:0]       sp_rd_sel;
  logic [Depth-1:0] sel0, sel1;
  always_comb begin
    sel0 = '0;
    sel1 = '0;
    for (int unsigned t = 0; t < Threads; t++) begin
      sel0[t] = sp_sel_q[2*t];
      sel1[t] = sp_sel_q[2*t + 1];
    end
  end
  assign sp_rd_sel = {sel1[sp_rd_thr_i], sel0[sp_rd_thr_i]};
  assign sp_rd_o = (sp_rd_sel == SpFromTr)  ? sp_tr_m[sp_rd_thr_i] :
                   (sp_rd_sel == SpFromPop) ? sp_pop_m[sp_rd_thr_i] : '0;

  //////////////////////
  // Rays that exist  //
  //////////////////////

  logic [4:0] vm_m [0:Depth-1];
  always_ff @(posedge clk_i) begin
    if (acc_valid_i) vm_m[acc_thr_i] <= {acc_sec_i, acc_vmask_i};
  end
  assign {vm_rd_sec_o, vm_rd_o} = vm_m[vm_rd_thr_i];

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  for (genvar t = 0; t < Threads; t++) begin : g_checks
    SpWriters_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  $onehot0({h_acc[t], h_sp[t], h_pop[t]}));
    AccAlone_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 h_acc[t] |-> !(h_e0[t] | h_e1[t] | h_e2[t] | h_e3[t] | h_e4[t] |
                                                h_hit[t]));
  end
`endif

endmodule
