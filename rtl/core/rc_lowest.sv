// rc_lowest: the lowest set bit of a vector (a free entry, a done slot), in logarithmic depth.
//
// Contract
// - valid_o = |req_i; idx_o = the lowest i with req_i[i] (0 when none); hot_o = the one-hot
//   vector of that bit (all zeros when none). Combinational.
// - Structure: groups of 16 bits; in each, the lowest bit is x & -x (a carry chain of 16) and
//   its number an OR of the set bit's numbers; the lowest group with a bit is chosen the same way
//   over the groups' any-bits. A priority loop over the bits becomes a chain of N multiplexers
//   of IdxW bits in synthesis (N stages deep); this is about 4 LUT4 per bit and a few levels
//   (N = 128, Yosys 0.23 synth_ecp5: 475 LUT4 and 68 CCU2C).
// - Parameters: N (>= 1) bits, IdxW index bits (2^IdxW >= N).
module rc_lowest #(
  parameter int unsigned N    = 8,
  parameter int unsigned IdxW = (N > 1) ? $clog2(N) : 1
) (
  input  logic [N-1:0]    req_i,
  output logic            valid_o,
  output logic [IdxW-1:0] idx_o,
  output logic [N-1:0]    hot_o
);

  localparam int unsigned G  = 16;
  localparam int unsigned NG = (N + G - 1) / G;
  localparam int unsigned GW = (NG > 1) ? $clog2(NG) : 1;

  if (N < 1 || (1 << IdxW) < N) begin : g_param_check
    $error("rc_lowest: need N >= 1 and 2^IdxW >= N");
  end

  logic [NG*G-1:0] x, first;
  logic [NG-1:0]   gany, gfirst;
  logic [3:0]      gidx [NG];
  assign x = (NG * G)'(req_i);

  for (genvar g = 0; g < NG; g++) begin : g_group
    logic [G-1:0] xg;
    assign xg                 = x[g*G +: G];
    assign gany[g]            = xg != '0;
    assign first[g*G +: G]    = xg & (~xg + G'(1));
    always_comb begin
      gidx[g] = '0;
      for (int unsigned i = 0; i < G; i++) begin
        if (first[g*G + i]) gidx[g] = gidx[g] | 4'(i);
      end
    end
  end

  assign gfirst = gany & (~gany + NG'(1));

  always_comb begin
    logic [GW-1:0] gsel;
    logic [3:0]    isel;
    gsel = '0;
    isel = '0;
    for (int unsigned g = 0; g < NG; g++) begin
      if (gfirst[g]) begin
        gsel = gsel | GW'(g);
        isel = isel | gidx[g];
      end
    end
    idx_o = (NG > 1) ? IdxW'({gsel, isel}) : IdxW'(isel);
    for (int unsigned i = 0; i < N; i++) hot_o[i] = gfirst[i / G] & first[i];
  end
  assign valid_o = gany != '0;

`ifndef SYNTHESIS
  // The reference: the lowest set bit by a loop over the bits.
  logic [IdxW-1:0] ref_idx;
  always_comb begin
    ref_idx = '0;
    for (int i = N - 1; i >= 0; i--) if (req_i[i]) ref_idx = IdxW'(i);
  end
  always_comb begin
    // The fast structure finds the bit the loop finds.
    if (req_i != '0) Lowest_A: assert (idx_o == ref_idx && hot_o == N'(1) << ref_idx);
  end
`endif

endmodule
