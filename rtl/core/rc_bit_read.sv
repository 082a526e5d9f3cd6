// rc_bit_read: one bit of a wide vector read by its index, the multiplexer split by a register:
// before the clock edge each group of 2^LoW bits gives the bit its low index bits choose (a
// register per group), after it the group's number (registered) chooses among the groups. The
// core reads its hit bits this way by {thread, ray} (rc_isect_issue, rc_hit_store): a single
// 512-way multiplexer over bits spread across the chip was the longest path of the board build.
//
// Contract
// - bit_o, in the cycle after idx_i: bits_i[idx_i] as the clock edge ending idx_i's cycle
//   sampled it (what a register after a single multiplexer would hold). Index values at or
//   above N read 0.
// - Parameters: N bits (>= 1); IdxW index bits (2^IdxW >= N); LoW low index bits chosen before
//   the edge (groups of 2^LoW bits).
// - No reset: a data path (its output is meaningful a cycle after a meaningful index).
module rc_bit_read #(
  parameter int unsigned N    = 8,
  parameter int unsigned IdxW = 3,
  parameter int unsigned LoW  = 6
) (
  input  logic            clk_i,
  input  logic [N-1:0]    bits_i,
  input  logic [IdxW-1:0] idx_i,
  output logic            bit_o
);

  localparam int unsigned GW  = (IdxW > LoW) ? LoW : IdxW;
  localparam int unsigned HiW = IdxW - GW;
  localparam int unsigned NG  = 1 << HiW;

  if (N < 1 || (1 << IdxW) < N || LoW < 1) begin : g_param_check
    $error("rc_bit_read: need N >= 1, 2^IdxW >= N and LoW >= 1");
  end

  logic [(1 << IdxW)-1:0] pad;
  logic [NG-1:0]          grp_q;
  assign pad = (1 << IdxW)'(bits_i);

  for (genvar k = 0; k < NG; k++) begin : g_grp
    logic [(1 << GW)-1:0] grp;
    assign grp = pad[k*(1 << GW) +: (1 << GW)];
    always_ff @(posedge clk_i) begin
      grp_q[k] <= grp[idx_i[GW-1:0]];
    end
  end

  if (HiW > 0) begin : g_hi
    logic [HiW-1:0] hi_q;
    always_ff @(posedge clk_i) begin
      hi_q <= idx_i[IdxW-1:GW];
    end
    assign bit_o = grp_q[hi_q];
  end else begin : g_one
    assign bit_o = grp_q[0];
  end

endmodule
