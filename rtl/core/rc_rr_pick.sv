// rc_rr_pick: round-robin choice of one request among N (the core's thread schedulers).
//
// Contract
// - req_i bit i: requester i wants service. take_i: the choice (valid_o, idx_o, grant_o) is used
//   this cycle if there is one. take_i without a choice (valid_o low) is legal: a user can take
//   whenever it has room, so valid_o need not reach its registers' enables. What such a take
//   does is TakeNeedsChoice's: 0, it returns the pointers to 0 (below); 1, it changes nothing,
//   as if take_i were low, so a user whose take is (condition & valid_o) may give the condition
//   alone and keep valid_o out of the take's path (the candidates' loads above 32 requesters use
//   take_i only with a group's choice, which implies valid_o).
// - grant_o: the choice as a one-hot vector (bit idx_o set; zero when valid_o is low), for users
//   that decode the choice per requester.
// - Up to 32 requesters (one pointer over all of them, rc_rr_pick_flat): valid_o = |req_i; idx_o
//   = the first requester at or after the rotating pointer (wrapping around), combinational from
//   req_i and the pointer register. A take moves the pointer to idx_o + 1, so every requester is
//   served within N takes of asking; a take without a request returns the pointer to 0. The
//   pointer is kept as a mask (the requesters at or after it), so neither the choice nor the
//   update compares indices. Latency 0: a request can be chosen in the cycle it rises.
// - More than 32 requesters: groups of 16 (the last one padded with requesters that never ask),
//   each holding a candidate in registers: one of its requesters, chosen round robin
//   (rc_rr_pick_flat) among its requests without the candidate it replaces and without the
//   requester taken in the cycle before. A group with no candidate chooses one every cycle; a
//   group whose candidate is taken chooses its next one in the same cycle. The choice is a
//   round-robin pick (rc_rr_pick_flat) over the groups holding a candidate, and that group's
//   candidate: it comes from registers, so no path runs from req_i to the outputs, and the
//   choice's loop (a take, the candidate's replacement) passes one 16-way pick and the group
//   pick instead of a pick over all N; valid_o is the OR of the candidates' valid bits, or with
//   RegValid a flip-flop holding it (registered from the candidates' next values: a user whose
//   logic after valid_o is long gets it from one register, a user whose take is long keeps the
//   take out of valid_o's path). Rules for the user:
//   - a request stays up until the requester is taken (candidates are not withdrawn; checked by
//     ReqHeld_A), and drops at the clock edge that ends the take's cycle or at the next one;
//   - a request is chosen at the earliest in the cycle after it rises (latency 1);
//   - a group whose candidate is taken offers its next one in the next cycle, so one group can
//     be served every cycle.
//   Every requester is served within G (16 + 1) takes of asking (G groups: 136 at N = 128): it
//   becomes its group's candidate within 16 of the group's takes, each within G takes, and is
//   then taken within G takes.
// - Parameters: N >= 1 requesters; IdxW index bits (>= 1, 2^IdxW >= N); TakeNeedsChoice and
//   RegValid (above; RegValid matters only above 32 requesters).
// - Illegal input: a request dropped before it is taken (more than 32 requesters).
// - Reset: rst_ni (active low, asynchronous) sets the pointers to 0 and, above 32 requesters,
//   clears the candidates.
module rc_rr_pick #(
  parameter int unsigned N               = 8,
  parameter int unsigned IdxW            = (N > 1) ? $clog2(N) : 1,
  parameter bit          TakeNeedsChoice = 1'b0,
  parameter bit          RegValid        = 1'b0
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic [N-1:0]    req_i,
  input  logic            take_i,
  output logic            valid_o,
  output logic [IdxW-1:0] idx_o,
  output logic [N-1:0]    grant_o
);

  if (N < 1 || IdxW < 1 || (1 << IdxW) < N) begin : g_param_check
    $error("rc_rr_pick: need N >= 1 and 2^IdxW >= N");
  end

  // The take as the pointers see it.
  logic take_ptr;
  assign take_ptr = TakeNeedsChoice ? take_i & valid_o : take_i;

  if (N <= 32) begin : g_flat
    rc_rr_pick_flat #(
      .N   (N),
      .IdxW(IdxW)
    ) u_flat (
      .clk_i,
      .rst_ni,
      .req_i,
      .take_i (take_ptr),
      .valid_o,
      .idx_o,
      .grant_o
    );
  end else begin : g_tree
    localparam int unsigned GS  = 16;
    localparam int unsigned G   = (N + GS - 1) / GS;
    localparam int unsigned GW  = (G > 1) ? $clog2(G) : 1;
    localparam int unsigned GIW = 4;
    logic [G*GS-1:0]  req_all, grant_all, cand_all, taken_q;
    logic [G-1:0]     cand_v, cand_v_d, g_grant, load;
    logic             any_q, g_valid;
    logic [GW-1:0]    g_idx;
    logic [G*GIW-1:0] cand_idx;
    logic [GIW-1:0]   idx_in;
    assign req_all = (G * GS)'(req_i);
    for (genvar g = 0; g < G; g++) begin : g_group
      logic [GS-1:0]  cand_q, new_hot;
      logic [GIW-1:0] cand_idx_q, new_idx;
      logic           cand_v_q, new_v;
      // A new candidate when the group has none or its candidate is taken, never the candidate
      // it replaces or last cycle's taken requester (whose request may still be up).
      assign load[g] = ~cand_v_q | (take_i & g_grant[g]);
      rc_rr_pick_flat #(
        .N   (GS),
        .IdxW(GIW)
      ) u_in (
        .clk_i,
        .rst_ni,
        .req_i  (req_all[g*GS +: GS] & ~cand_q & ~taken_q[g*GS +: GS]),
        .take_i (load[g]),
        .valid_o(new_v),
        .idx_o  (new_idx),
        .grant_o(new_hot)
      );
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) begin
          cand_v_q   <= 1'b0;
          cand_q     <= '0;
          cand_idx_q <= '0;
        end else if (load[g]) begin
          cand_v_q   <= new_v;
          cand_q     <= new_hot;
          cand_idx_q <= new_idx;
        end
      end
      assign cand_v[g]                = cand_v_q;
      assign cand_v_d[g]              = load[g] ? new_v : cand_v_q;
      assign cand_idx[g*GIW +: GIW]   = cand_idx_q;
      assign cand_all[g*GS +: GS]  = cand_q;
      assign grant_all[g*GS +: GS] = {GS{g_grant[g]}} & cand_q;
    end
    rc_rr_pick_flat #(
      .N   (G),
      .IdxW(GW)
    ) u_groups (
      .clk_i,
      .rst_ni,
      .req_i  (cand_v),
      .take_i (take_ptr),
      .valid_o(g_valid),
      .idx_o  (g_idx),
      .grant_o(g_grant)
    );
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        taken_q <= '0;
      end else begin
        taken_q <= take_i ? grant_all : '0;
      end
    end
    // The choice's valid (some group holds a candidate). With RegValid it is a flip-flop,
    // registered from the candidates' next values, so a user's logic after valid_o starts at one
    // register instead of an OR over the groups' registers across the chip (run 50: the free
    // pick's valid through the set-up unit's feeder, -2.14 ns). Without, the take does not reach
    // valid_o's register (run 51: the pop pick's take into any_q, -0.68 ns).
    if (RegValid) begin : g_any_reg
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) begin
          any_q <= 1'b0;
        end else begin
          any_q <= |cand_v_d;
        end
      end
    end else begin : g_any_comb
      assign any_q = g_valid;
      logic unused_cand_v_d;
      assign unused_cand_v_d = ^cand_v_d;
    end
    assign valid_o = any_q;
    always_comb begin
      idx_in = '0;
      for (int unsigned g = 0; g < G; g++) begin
        idx_in = idx_in | ({GIW{g_grant[g]}} & cand_idx[g*GIW +: GIW]);
      end
    end
    assign idx_o   = IdxW'({g_idx, idx_in});
    assign grant_o = grant_all[N-1:0];
    logic unused_pad;
    assign unused_pad = ^grant_all;

`ifndef SYNTHESIS
    logic tree_checks_on;
    rc_checks_on u_tree_checks_on (
      .clk_i,
      .rst_ni,
      .on_o (tree_checks_on)
    );
    // The valid (registered or not) is the OR of the candidates' valid bits.
    AnyReg_A: assert property (@(posedge clk_i) disable iff (tree_checks_on !== 1'b1)
                               valid_o == g_valid);
    // A candidate is a requester that still asks (requests are held until taken).
    ReqHeld_A: assert property (@(posedge clk_i) disable iff (tree_checks_on !== 1'b1)
                                (cand_all & ~req_all) == '0);
    // A candidate register holds one requester, and its valid bit says whether it holds one.
    for (genvar g = 0; g < G; g++) begin : g_cand_chk
      CandOneHot_A: assert property (@(posedge clk_i) disable iff (tree_checks_on !== 1'b1)
                                     $onehot0(cand_all[g*GS +: GS]) &&
                                     (cand_v[g] == |cand_all[g*GS +: GS]));
    end
`endif
  end

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  // The one-hot choice and the index agree.
  GrantIsIdx_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 grant_o == (valid_o ? N'(1) << idx_o : '0));
`endif

endmodule
