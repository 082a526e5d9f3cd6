// rc_onehot_idx: the index of a one-hot vector (a scheduler's registered grant as a thread
// number): the OR of the set bits' numbers, log depth in N, no chain through the bits.
//
// Contract
// - idx_o = i when hot_i has exactly bit i set; 0 when hot_i is zero; with several bits set, the
//   OR of their numbers (callers give one-hot vectors; rc_core's schedulers' grants are).
// - Parameters: N (>= 1) bits, IdxW index bits (2^IdxW >= N).
module rc_onehot_idx #(
  parameter int unsigned N    = 8,
  parameter int unsigned IdxW = (N > 1) ? $clog2(N) : 1
) (
  input  logic [N-1:0]    hot_i,
  output logic [IdxW-1:0] idx_o
);

  if (N < 1 || (1 << IdxW) < N) begin : g_param_check
    $error("rc_onehot_idx: need N >= 1 and 2^IdxW >= N");
  end

  // Bit k of the index: a reduction OR over the bits whose numbers have bit k set (one balanced OR
  // per index bit, not a chain through the N bits).
  for (genvar k = 0; k < IdxW; k++) begin : g_bit
    logic [N-1:0] has_k;
    for (genvar i = 0; i < N; i++) begin : g_i
      assign has_k[i] = ((i >> k) & 1) != 0;
    end
    assign idx_o[k] = |(hot_i & has_k);
  end

endmodule
