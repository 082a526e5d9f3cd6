// rc_thread_mon: every thread's state, kept from the units' events, and the checks on them
// (docs/architecture.md, "Thread states"). Simulation only: rc_core instantiates it outside
// synthesis and ties its debug output to zero in synthesis. No logic depends on it.
//
// Contract
// - Events: each *_valid_i with its *_thr_i is one unit's event for that thread in this cycle
//   (lend_i: a bit per thread); each moves the thread to the state of the unit that now holds it:
//     acc -> Setup (the set-up unit took a free thread), tq -> Fetch (a walk or a pop queued for
//     node fetch), iss -> Node (the traversal unit issued the thread's node), leaf_tr, leaf_stk ->
//     Leaf (a leaf queued for the list unit, from the decision or from the pop unit), take ->
//     LeafRun (the list unit took the leaf), req_tr, req_nr, lend, own -> Pop (a pop asked for),
//     pick -> Popping, done -> Done (the walk ended), spick -> Shade, free, free0 -> Free.
//   cont_i: the issue in this cycle is a continuation (the decision's own thread).
// - Checks (assertions, on from the cycle after reset): a thread has at most one event a cycle
//   (EventsExclusive_A); each event applies to a thread in the state it leaves (EventState_A);
//   the units' work belongs to threads in their hands: a node step (step_*), a triangle response
//   (load_*), an intersection result (fin_*) to a thread in LeafRun, a hit commit (commit_*) to
//   one in LeafRun or Pop, a framebuffer write (fb_*) to one in Shade.
// - Output: state_o, thread t's rc_pkg::thread_state_e at [t*ThreadStateBits +: ThreadStateBits],
//   registered; every thread is Free after reset.
// - Parameters: Threads (>= 1); ThrW: thread index bits.
// - Reset: rst_ni (active low, asynchronous) sets every thread Free.
module rc_thread_mon #(
  parameter int unsigned Threads = 1,
  parameter int unsigned ThrW    = 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                acc_valid_i,
  input  logic [ThrW-1:0]     acc_thr_i,
  input  logic                tq_valid_i,
  input  logic [ThrW-1:0]     tq_thr_i,
  input  logic                iss_valid_i,
  input  logic [ThrW-1:0]     iss_thr_i,
  input  logic                cont_i,
  input  logic                leaf_tr_valid_i,
  input  logic [ThrW-1:0]     leaf_tr_thr_i,
  input  logic                req_tr_valid_i,
  input  logic [ThrW-1:0]     req_tr_thr_i,
  input  logic                req_nr_valid_i,
  input  logic [ThrW-1:0]     req_nr_thr_i,
  input  logic                leaf_stk_valid_i,
  input  logic [ThrW-1:0]     leaf_stk_thr_i,
  input  logic                take_valid_i,
  input  logic [ThrW-1:0]     take_thr_i,
  input  logic [Threads-1:0]  lend_i,
  input  logic                own_valid_i,
  input  logic [ThrW-1:0]     own_thr_i,
  input  logic                pick_valid_i,
  input  logic [ThrW-1:0]     pick_thr_i,
  input  logic                done_valid_i,
  input  logic [ThrW-1:0]     done_thr_i,
  input  logic                spick_valid_i,
  input  logic [ThrW-1:0]     spick_thr_i,
  input  logic                free_valid_i,
  input  logic [ThrW-1:0]     free_thr_i,
  input  logic                free0_valid_i,
  input  logic [ThrW-1:0]     free0_thr_i,
  input  logic                step_valid_i,
  input  logic [ThrW-1:0]     step_thr_i,
  input  logic                load_valid_i,
  input  logic [ThrW-1:0]     load_thr_i,
  input  logic                fin_valid_i,
  input  logic [ThrW-1:0]     fin_thr_i,
  input  logic                commit_valid_i,
  input  logic [ThrW-1:0]     commit_thr_i,
  input  logic                fb_valid_i,
  input  logic [ThrW-1:0]     fb_thr_i,
  output logic [Threads*rc_pkg::ThreadStateBits-1:0] state_o
);

  localparam int unsigned SB = rc_pkg::ThreadStateBits;

  rc_pkg::thread_state_e st_q [0:Threads-1];

  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  function automatic logic at(input logic v, input logic [ThrW-1:0] thr,
                              input logic [ThrW-1:0] t);
    at = v && thr == t;
  endfunction

  for (genvar t = 0; t < Threads; t++) begin : g_state
    logic e_acc, e_tq, e_iss, e_cont, e_leaf_tr, e_req_tr, e_req_nr, e_leaf_stk, e_take;
    logic e_lend, e_own, e_pick, e_done, e_spick, e_free;
    assign e_acc      = at(acc_valid_i, acc_thr_i, ThrW'(t));
    assign e_tq       = at(tq_valid_i, tq_thr_i, ThrW'(t));
    assign e_iss      = at(iss_valid_i, iss_thr_i, ThrW'(t));
    assign e_leaf_tr  = at(leaf_tr_valid_i, leaf_tr_thr_i, ThrW'(t));
    assign e_req_tr   = at(req_tr_valid_i, req_tr_thr_i, ThrW'(t));
    assign e_req_nr   = at(req_nr_valid_i, req_nr_thr_i, ThrW'(t));
    assign e_leaf_stk = at(leaf_stk_valid_i, leaf_stk_thr_i, ThrW'(t));
    assign e_take     = at(take_valid_i, take_thr_i, ThrW'(t));
    assign e_lend     = lend_i[t];
    assign e_own      = at(own_valid_i, own_thr_i, ThrW'(t));
    assign e_pick     = at(pick_valid_i, pick_thr_i, ThrW'(t));
    assign e_done     = at(done_valid_i, done_thr_i, ThrW'(t));
    assign e_spick    = at(spick_valid_i, spick_thr_i, ThrW'(t));
    assign e_free     = at(free_valid_i, free_thr_i, ThrW'(t)) |
                        at(free0_valid_i, free0_thr_i, ThrW'(t));
    assign e_cont     = e_iss && cont_i;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        st_q[t] <= rc_pkg::StFree;
      end else begin
        // The decision's leaf and pop outputs come a cycle before their thread could be issued
        // again, and only one of them at a time (the decision routes a thread one way).
        if (e_acc) st_q[t] <= rc_pkg::StSetup;
        if (e_tq) st_q[t] <= rc_pkg::StFetch;
        if (e_iss) st_q[t] <= rc_pkg::StNode;
        if (e_leaf_tr || e_leaf_stk) st_q[t] <= rc_pkg::StLeaf;
        if (e_take) st_q[t] <= rc_pkg::StLeafRun;
        if (e_req_tr || e_req_nr || e_lend || e_own) st_q[t] <= rc_pkg::StPop;
        if (e_pick) st_q[t] <= rc_pkg::StPopping;
        if (e_done) st_q[t] <= rc_pkg::StDone;
        if (e_spick) st_q[t] <= rc_pkg::StShade;
        if (e_free) st_q[t] <= rc_pkg::StFree;
      end
    end
    assign state_o[t*SB +: SB] = st_q[t];

`ifndef SYNTHESIS
    rc_pkg::thread_state_e st;
    assign st = st_q[t];
    EventsExclusive_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                        $onehot0({e_acc, e_tq, e_iss, e_leaf_tr | e_leaf_stk,
                                                  e_take, e_req_tr | e_req_nr | e_lend | e_own,
                                                  e_pick, e_done, e_spick, e_free}));
    EventState_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   (!e_acc || st == rc_pkg::StFree) &&
                                   (!e_tq || st == rc_pkg::StSetup || st == rc_pkg::StPopping) &&
                                   (!e_iss || (e_cont ? st == rc_pkg::StNode :
                                                        st == rc_pkg::StFetch)) &&
                                   (!e_leaf_tr || st == rc_pkg::StNode) &&
                                   (!e_leaf_stk || st == rc_pkg::StSetup ||
                                    st == rc_pkg::StPopping) &&
                                   (!e_take || st == rc_pkg::StLeaf) &&
                                   (!e_req_tr || st == rc_pkg::StNode) &&
                                   (!e_req_nr || st == rc_pkg::StNode) &&
                                   (!e_lend || st == rc_pkg::StLeafRun) &&
                                   (!e_own || st == rc_pkg::StSetup ||
                                    st == rc_pkg::StPopping) &&
                                   (!e_pick || st == rc_pkg::StPop) &&
                                   (!e_done || st == rc_pkg::StPopping) &&
                                   (!e_spick || st == rc_pkg::StDone) &&
                                   (!e_free || st == rc_pkg::StShade));
`endif
  end

`ifndef SYNTHESIS
  // The units' work belongs to threads in their hands.
  rc_pkg::thread_state_e st_step, st_load, st_fin, st_commit, st_fb;
  always_comb begin
    st_step   = st_q[step_thr_i];
    st_load   = st_q[load_thr_i];
    st_fin    = st_q[fin_thr_i];
    st_commit = st_q[commit_thr_i];
    st_fb     = st_q[fb_thr_i];
  end
  StepOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                step_valid_i |-> st_step == rc_pkg::StNode);
  TriRspOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  load_valid_i |-> st_load == rc_pkg::StLeafRun);
  IsectOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 fin_valid_i |-> st_fin == rc_pkg::StLeafRun);
  CommitOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  commit_valid_i |-> st_commit == rc_pkg::StLeafRun ||
                                                     st_commit == rc_pkg::StPop);
  FbOwner_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              fb_valid_i |-> st_fb == rc_pkg::StShade);
`endif

endmodule
