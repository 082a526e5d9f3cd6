// rc_rr_pick_flat: the round-robin choice of rc_rr_pick over up to 32 requesters, one pointer
// over all of them (rc_rr_pick's contract; rc_rr_pick builds larger choices from it).
module rc_rr_pick_flat #(
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

  // hi_q bit i: requester i is at or after the pointer. After a take of requester k it holds the
  // bits above k; all zeros (after a take of N-1, or a take without a request) works as all
  // ones, the pointer at 0, because the choice falls back to all requests when none at or after
  // the pointer asks.
  logic [N-1:0]    hi_q, hi_d;
  logic [N-1:0]    upper, first_up, first_all, above_up, above_all;
  logic [IdxW-1:0] idx_up, idx_all;
  logic            any_up;

  // The lowest set bit of x is x & -x, and the bits above it are ~(x ^ (x - 1)): carry chains,
  // for the requests at or after the pointer and for all requests side by side; the index of a
  // one-hot vector is an OR of its bits' numbers (log depth, no chain through the requesters).
  function automatic logic [IdxW-1:0] index_of(input logic [N-1:0] one_hot);
    index_of = '0;
    for (int unsigned i = 0; i < N; i++) begin
      if (one_hot[i]) index_of = index_of | IdxW'(i);
    end
  endfunction

  assign upper     = req_i & hi_q;
  assign any_up    = |upper;
  assign first_up  = upper & (~upper + N'(1));
  assign first_all = req_i & (~req_i + N'(1));
  assign above_up  = ~(upper ^ (upper - N'(1)));
  assign above_all = ~(req_i ^ (req_i - N'(1)));
  assign idx_up    = index_of(first_up);
  assign idx_all   = index_of(first_all);
  assign idx_o     = any_up ? idx_up : idx_all;
  assign grant_o   = any_up ? first_up : first_all;
  assign hi_d      = any_up ? above_up : above_all;
  assign valid_o   = |req_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hi_q <= '1;
    end else if (take_i) begin
      hi_q <= hi_d;
    end
  end

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // The pointer mask is all requesters from some number up: a set bit has its upper neighbour set.
  PtrMask_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              ((hi_q << 1) & ~hi_q) == '0);
  // The new mask is the bits above the choice, or none (the pointer at 0) without a request.
  PtrMove_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                              take_i |-> hi_d == (valid_o ? ~((N'(2) << idx_o) - N'(1)) : '0));
`endif

endmodule
