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
//   (EventsExclusive_A); each event applies to a thread in the state it leaves (EventState_A,
//   LendState_A for lend_i); the units' work belongs to threads in their hands: a node step
//   (step_*) to a thread in Node, a triangle response (load_*) and an intersection result (fin_*)
//   to one in LeafRun, a hit commit (commit_*) to one in LeafRun or Pop, a framebuffer write
//   (fb_*) to one in Shade.
// - Output: state_o, thread t's rc_pkg::thread_state_e at [t*ThreadStateBits +: ThreadStateBits],
//   registered; every thread is Free after reset.
// - Structure: each event writes and checks its own thread's state by index, so the verilated
//   model does work per event rather than per thread and event (with one comparator per thread
//   and event it was an eighth of a default core model's C++).
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

  // Thread t's state at [t*SB +: SB] (the layout of state_o).
  logic [Threads*SB-1:0] st_q, st_d;

  function automatic logic [SB-1:0] st_of(input logic [Threads*SB-1:0] v,
                                           input logic [ThrW-1:0] t);
    st_of = v[32'(t)*SB +: SB];
  endfunction

  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  // The events that name one thread each, and the group of each: a thread has at most one
  // group's event a cycle (lend_i, a bit per thread, is in group GPop with req_tr, req_nr, own).
  localparam int unsigned NEv = 14;
  localparam int unsigned GPop = 5;
  function automatic int unsigned ev_group(input int unsigned e);
    case (e)
      0, 1, 2:       ev_group = e;     // acc, tq, iss
      3, 4:          ev_group = 3;     // leaf_tr, leaf_stk
      5:             ev_group = 4;     // take
      6, 7, 8:       ev_group = GPop;  // req_tr, req_nr, own
      9, 10, 11:     ev_group = e - 3; // pick, done, spick
      default:       ev_group = 9;     // free, free0
    endcase
  endfunction
  function automatic logic [SB-1:0] ev_next(input int unsigned e);
    case (e)
      0:             ev_next = rc_pkg::StSetup;
      1:             ev_next = rc_pkg::StFetch;
      2:             ev_next = rc_pkg::StNode;
      3, 4:          ev_next = rc_pkg::StLeaf;
      5:             ev_next = rc_pkg::StLeafRun;
      6, 7, 8:       ev_next = rc_pkg::StPop;
      9:             ev_next = rc_pkg::StPopping;
      10:            ev_next = rc_pkg::StDone;
      11:            ev_next = rc_pkg::StShade;
      default:       ev_next = rc_pkg::StFree;
    endcase
  endfunction
  // Bit e of ev_v and field e of ev_thr (ThrW bits each) are event e, in this order: acc, tq,
  // iss, leaf_tr, leaf_stk, take, req_tr, req_nr, own, pick, done, spick, free, free0
  // (ev_group() and ev_next() follow it; the concatenations list them from the last down).
  logic [NEv-1:0]           ev_v;
  logic [NEv*ThrW-1:0]      ev_thr;
  assign ev_v   = {free0_valid_i, free_valid_i, spick_valid_i, done_valid_i, pick_valid_i,
                   own_valid_i, req_nr_valid_i, req_tr_valid_i, take_valid_i, leaf_stk_valid_i,
                   leaf_tr_valid_i, iss_valid_i, tq_valid_i, acc_valid_i};
  assign ev_thr = {free0_thr_i, free_thr_i, spick_thr_i, done_thr_i, pick_thr_i, own_thr_i,
                   req_nr_thr_i, req_tr_thr_i, take_thr_i, leaf_stk_thr_i, leaf_tr_thr_i,
                   iss_thr_i, tq_thr_i, acc_thr_i};

  // An event applies to its thread when the thread exists (a thread number at or above Threads
  // names none). The events write in the order of the list, lend_i between req_nr and own; the
  // checks below make the order irrelevant (one group's event per thread and cycle).
  always_comb begin
    st_d = st_q;
    for (int unsigned e = 0; e < NEv; e++) begin
      if (e == 8) begin
        for (int unsigned t = 0; t < Threads; t++)
          if (lend_i[t]) st_d[t*SB +: SB] = rc_pkg::StPop;
      end
      if (ev_v[e] && 32'(ev_thr[e*ThrW +: ThrW]) < Threads)
        st_d[32'(ev_thr[e*ThrW +: ThrW])*SB +: SB] = ev_next(e);
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) st_q <= {Threads{rc_pkg::StFree}};
    else         st_q <= st_d;
  end
  assign state_o = st_q;

`ifndef SYNTHESIS
  // Each thread's state under a name of its own (g_state[t].st, for the waveform), and the check
  // of lend_i, the one event given as a bit per thread: a thread lent to the pop unit is in
  // LeafRun (LendState_A; the other events' checks are EventState_A below).
  for (genvar t = 0; t < Threads; t++) begin : g_state
    rc_pkg::thread_state_e st;
    assign st = rc_pkg::thread_state_e'(st_q[t*SB +: SB]);
    LendState_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  lend_i[t] |-> st == rc_pkg::StLeafRun);
  end
`endif

`ifndef SYNTHESIS
  // The checks, with the first offending thread for the message: two groups' events for one
  // thread in a cycle (excl_bad), an event for a thread not in the state it leaves (state_bad).
  logic            excl_bad, state_bad;
  logic [ThrW-1:0] excl_thr, state_thr;
  always_comb begin
    excl_bad  = 1'b0;
    state_bad = 1'b0;
    excl_thr  = '0;
    state_thr = '0;
    for (int unsigned e = 0; e < NEv; e++) begin
      logic [ThrW-1:0] thr;
      thr = ev_thr[e*ThrW +: ThrW];
      if (ev_v[e] && 32'(thr) < Threads) begin
        logic [SB-1:0] st;
        logic ok;
        st = st_of(st_q, thr);
        for (int unsigned f = e + 1; f < NEv; f++) begin
          if (ev_group(f) != ev_group(e) && ev_v[f] && ev_thr[f*ThrW +: ThrW] == thr &&
              !excl_bad) begin
            excl_bad = 1'b1;
            excl_thr = thr;
          end
        end
        if (ev_group(e) != GPop && lend_i[thr] && !excl_bad) begin
          excl_bad = 1'b1;
          excl_thr = thr;
        end
        case (e)
          0:          ok = st == rc_pkg::StFree;                                // acc
          1, 4, 8:    ok = st == rc_pkg::StSetup || st == rc_pkg::StPopping; // tq, leaf_stk, own
          2:          ok = cont_i ? st == rc_pkg::StNode : st == rc_pkg::StFetch; // iss
          3, 6, 7:    ok = st == rc_pkg::StNode;                                // leaf_tr, req_*
          5:          ok = st == rc_pkg::StLeaf;                                // take
          9:          ok = st == rc_pkg::StPop;                                 // pick
          10:         ok = st == rc_pkg::StPopping;                             // done
          11:         ok = st == rc_pkg::StDone;                                // spick
          default:    ok = st == rc_pkg::StShade;                               // free, free0
        endcase
        if (!ok && !state_bad) begin
          state_bad = 1'b1;
          state_thr = thr;
        end
      end
    end
  end
  EventsExclusive_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1) !excl_bad)
    else $error("rc_thread_mon: thread %0d has events of two units in one cycle", excl_thr);
  EventState_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1) !state_bad)
    else $error("rc_thread_mon: an event for thread %0d in a state it does not leave (%0d)",
                state_thr, st_of(st_q, state_thr));
`endif

`ifndef SYNTHESIS
  // The units' work belongs to threads in their hands.
  logic [SB-1:0] st_step, st_load, st_fin, st_commit, st_fb;
  always_comb begin
    st_step   = st_of(st_q, step_thr_i);
    st_load   = st_of(st_q, load_thr_i);
    st_fin    = st_of(st_q, fin_thr_i);
    st_commit = st_of(st_q, commit_thr_i);
    st_fb     = st_of(st_q, fb_thr_i);
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
