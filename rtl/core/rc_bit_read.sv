// rc_bit_read: one bit of a wide vector read by its index, the multiplexer split by a register:
// before the clock edge each group of 2^LoW bits gives the bit its low index bits choose (a
// register per group), after it the group's number (registered) chooses among the groups. The
// core reads its hit bits this way by {thread, ray} (rc_isect_issue, rc_hit_store): a single
// 512-way multiplexer over bits spread across the chip was the longest path of the board build.
// With IdxCopies = the number of groups, each group reads the index from a register of its own
// (the owner's rc_reg_copies), so no single index register drives every group across the chip.
//
// Contract
// - bit_o, in the cycle after idx_i: bits_i[idx_i] as the clock edge ending idx_i's cycle
//   sampled it (what a register after a single multiplexer would hold). Index values at or
//   above N read 0.
// - idx_i holds IdxCopies copies of the index, all equal (the owner's kept register copies):
//   group k reads copy k (IdxCopies = groups) or copy 0 (IdxCopies = 1); the group number after
//   the edge comes from copy 0.
// - Parameters: N bits (>= 1); IdxW index bits (2^IdxW >= N); LoW low index bits chosen before
//   the edge (groups of 2^LoW bits); IdxCopies 1 or the number of groups, 2^(IdxW - LoW) (1 when
//   IdxW <= LoW).
// - No reset: a data path (its output is meaningful a cycle after a meaningful index).
module rc_bit_read #(
  parameter int unsigned N    = 8,
  parameter int unsigned IdxW = 3,
  parameter int unsigned LoW       = 6,
  parameter int unsigned IdxCopies = 1
) (
  input  logic                      clk_i,
  input  logic [N-1:0]              bits_i,
  input  logic [IdxCopies*IdxW-1:0] idx_i,
  output logic                      bit_o
);

  localparam int unsigned GW  = (IdxW > LoW) ? LoW : IdxW;
  localparam int unsigned HiW = IdxW - GW;
  localparam int unsigned NG  = 1 << HiW;

  if (N < 1 || (1 << IdxW) < N || LoW < 1 || (IdxCopies != 1 && IdxCopies != NG))
  begin : g_param_check
    $error("rc_bit_read: need N >= 1, 2^IdxW >= N, LoW >= 1 and IdxCopies 1 or the groups");
  end

  logic [(1 << IdxW)-1:0] pad;
  logic [NG-1:0]          grp_q;
  assign pad = (1 << IdxW)'(bits_i);

  for (genvar k = 0; k < NG; k++) begin : g_grp
    logic [(1 << GW)-1:0] grp;
    logic [GW-1:0]        idx;
    assign grp = pad[k*(1 << GW) +: (1 << GW)];
    assign idx = idx_i[((IdxCopies == 1) ? 0 : k)*IdxW +: GW];
    always_ff @(posedge clk_i) begin
      grp_q[k] <= grp[idx];
    end
  end

  // The other copies' group bits are not read (each group reads only its low bits).
  logic unused_idx;
  assign unused_idx = ^idx_i;

  if (HiW > 0) begin : g_hi
    logic [HiW-1:0] hi_q;
    always_ff @(posedge clk_i) begin
      hi_q <= idx_i[IdxW-1:GW];  // copy 0
    end
    assign bit_o = grp_q[hi_q];
  end else begin : g_one
    assign bit_o = grp_q[0];
  end

endmodule
