// rc_rr_pick: round-robin choice of one request among N (the core's thread schedulers).
//
// Contract
// - req_i bit i: requester i wants service. valid_o = |req_i; idx_o = the first requester at or
//   after the rotating pointer (wrapping around), combinational from req_i and the pointer
//   register (log depth in N: an AND with the pointer mask, lowest-set-bit carry chains and OR
//   trees).
// - take_i: the choice is used this cycle if there is one; the pointer then moves to idx_o + 1
//   so that every requester is served within N takes of asking (no starvation; for N > 32 see
//   Structure: within N rounded up to a multiple of 16). take_i without a request (valid_o low)
//   is legal and returns the pointer to 0: a user can take whenever it has room, so valid_o (an
//   OR over all requests) need not reach its registers' enables. A requester that waits keeps
//   valid_o high, so the return to 0 never delays it.
// - The pointer is kept as a mask (hi_q: the requesters at or after it), so neither the choice
//   nor the pointer's update compares indices: the update is the bits above the chosen one.
// - grant_o: the choice as a one-hot vector (bit idx_o set; zero without a request), for users
//   that decode the choice per requester (no index encoding and decoding on their path).
// - Structure: up to 32 requesters, one pointer over all of them (above). More are split into
//   groups of 16, each with its own round-robin pick and pointer, and a round-robin pick over the
//   groups that have a request: the grant is the chosen group's grant (an AND per requester),
//   and only the chosen group's pointer moves at a take. Every requester is then served within
//   16 G takes of asking (its group within G takes, it within 16 of its group's turns; N rounded
//   up to a multiple of 16), and no carry chain is longer than 16 bits or the group count (the
//   128-thread core's schedulers).
// - Latency: 0 (combinational choice); the pointers update at the clock edge.
// - Parameters: N >= 1 requesters; IdxW index bits (>= 1, 2^IdxW >= N).
// - Illegal input: none.
// - Reset: rst_ni (active low, asynchronous) sets the pointer to 0 (hi_q all ones).
module rc_rr_pick #(
  parameter int unsigned N    = 8,
  parameter int unsigned IdxW = (N > 1) ? $clog2(N) : 1
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

  if (N <= 32) begin : g_flat
    rc_rr_pick_flat #(
      .N   (N),
      .IdxW(IdxW)
    ) u_flat (
      .clk_i,
      .rst_ni,
      .req_i,
      .take_i,
      .valid_o,
      .idx_o,
      .grant_o
    );
  end else begin : g_tree
    // Groups of GS requesters (the last one padded with requesters that never ask).
    localparam int unsigned GS  = 16;
    localparam int unsigned G   = (N + GS - 1) / GS;
    localparam int unsigned GW  = (G > 1) ? $clog2(G) : 1;
    localparam int unsigned GIW = 4;
    logic [G*GS-1:0]  req_all, grant_all;
    logic [G-1:0]     g_any, g_grant;
    logic [GW-1:0]    g_idx;
    logic [G*GIW-1:0] in_idx;
    logic [GIW-1:0]   idx_in;
    assign req_all = (G * GS)'(req_i);
    for (genvar g = 0; g < G; g++) begin : g_group
      logic [GS-1:0] in_grant;
      rc_rr_pick_flat #(
        .N   (GS),
        .IdxW(GIW)
      ) u_in (
        .clk_i,
        .rst_ni,
        .req_i  (req_all[g*GS +: GS]),
        .take_i (take_i & g_grant[g]),
        .valid_o(g_any[g]),
        .idx_o  (in_idx[g*GIW +: GIW]),
        .grant_o(in_grant)
      );
      assign grant_all[g*GS +: GS] = {GS{g_grant[g]}} & in_grant;
    end
    rc_rr_pick_flat #(
      .N   (G),
      .IdxW(GW)
    ) u_groups (
      .clk_i,
      .rst_ni,
      .req_i  (g_any),
      .take_i (take_i),
      .valid_o(valid_o),
      .idx_o  (g_idx),
      .grant_o(g_grant)
    );
    always_comb begin
      idx_in = '0;
      for (int unsigned g = 0; g < G; g++) begin
        idx_in = idx_in | ({GIW{g_grant[g]}} & in_idx[g*GIW +: GIW]);
      end
    end
    assign idx_o   = IdxW'({g_idx, idx_in});
    assign grant_o = grant_all[N-1:0];
    logic unused_pad;
    assign unused_pad = ^grant_all;
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
