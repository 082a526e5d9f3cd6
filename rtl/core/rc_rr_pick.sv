// rc_rr_pick: round-robin choice of one request among N (the core's thread schedulers).
//
// Contract
// - req_i bit i: requester i wants service. valid_o = |req_i; idx_o = the first requester at or
//   after the rotating pointer (wrapping around), combinational from req_i and the pointer
//   register (log depth in N: a mask, a lowest-set-bit carry chain and an OR tree).
// - take_i: the choice is used this cycle (only with valid_o); the pointer then moves to idx_o + 1
//   so that every requester is served within N takes of asking (no starvation).
// - Latency: 0 (combinational choice); the pointer updates at the clock edge.
// - Parameters: N >= 1 requesters; IdxW index bits (>= 1, 2^IdxW >= N).
// - Illegal input: take_i without valid_o (caught by an assertion).
// - Reset: rst_ni (active low, asynchronous) sets the pointer to 0.
module rc_rr_pick #(
  parameter int unsigned N    = 8,
  parameter int unsigned IdxW = (N > 1) ? $clog2(N) : 1
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic [N-1:0]    req_i,
  input  logic            take_i,
  output logic            valid_o,
  output logic [IdxW-1:0] idx_o
);

  if (N < 1 || IdxW < 1 || (1 << IdxW) < N) begin : g_param_check
    $error("rc_rr_pick: need N >= 1 and 2^IdxW >= N");
  end

  logic [IdxW-1:0] ptr_q;
  logic [N-1:0]    at_or_after, upper, sel, first;

  // The first set bit at or after ptr_q, wrapping around: the requests at or above the pointer
  // if there are any, else all of them; the lowest set bit of that (x & -x, a carry chain), then
  // its index as an OR of the one-hot bits (log depth; no chain through the N requesters).
  always_comb begin
    for (int unsigned i = 0; i < N; i++) at_or_after[i] = IdxW'(i) >= ptr_q;
  end
  assign upper = req_i & at_or_after;
  assign sel   = (|upper) ? upper : req_i;
  assign first = sel & (~sel + N'(1));
  always_comb begin
    idx_o = '0;
    for (int unsigned i = 0; i < N; i++) begin
      if (first[i]) idx_o = idx_o | IdxW'(i);
    end
  end
  assign valid_o = |req_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ptr_q <= '0;
    end else if (take_i) begin
      ptr_q <= ({1'b0, idx_o} + (IdxW + 1)'(1) >= (IdxW + 1)'(N)) ? '0 : idx_o + IdxW'(1);
    end
  end

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  // A take uses the current choice, which only exists while someone requests.
  TakeHasChoice_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    take_i |-> valid_o);
  // The pointer stays a valid requester number.
  PtrInRange_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                 {1'b0, ptr_q} < (IdxW + 1)'(N));
`endif

endmodule
