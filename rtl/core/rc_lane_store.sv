// rc_lane_store: the tracer's per-lane records (docs/architecture.md, "The tracer"), in block
// RAMs: for each slot's four lanes, the current packet's rays and weights, the core's writes of
// it, the primary ray's hit record and pixel id, the pixel's sums and lights, and the triangles
// its first mirror and refraction rays hit.
//
// Contract
// - Lanes are addressed {slot, lane} (LaneW = SlotW + 2 bits). Vector ports hold lane r at
//   [r*k*W +: k*W] as rc_tracer's packet ports.
// - Writes (each at the clock edge of its cycle):
//     prim_i:  a primary packet takes slot prim_slot_i: its four lanes' pixel ids.
//     ray_i:   a packet goes to the core as slot ray_slot_i's current packet (the primary one,
//              or one of its tree): its four lanes' rays {inv_len, dir, org} and weights (the
//              lanes without a ray are written with what the ports hold: never read).
//   These two are registered and reach their memories at the next edge: a lane they write is
//   not read in the cycle after either.
//     cw_i:    the core's write of lane cw_ln_i of its slot's current packet: its triangle, t and
//              d'z; at depth 0 (cw_d0_i) also the primary hit record {hit, tri, t, u, v, rgb},
//              and the lane's first mirror and refraction triangles become -2 (none) and its
//              sums and lights 0; at depth 1 (cw_d1_i) the first mirror (cw_mirror_i) or
//              refraction triangle: the hit's triangle, or -1 for a miss. A lane's primary write
//              comes before every other write and add of its tree.
//     add_i:   an add to lane add_ln_i's sums in this cycle (never with a depth-0 cw_i): the
//              sum is read in this cycle, registered in the next (add_pend1_o, the lane's slot
//              on add_pend1_slot_o) and added and written in the one after (add_pend_o,
//              add_pend_slot_o), in which its term (add_term_i, three channels of FW bits,
//              zero-extended) and the lights to set (add_lights_i, ORed into the lane's) come.
//   The sums' memory has one write port: the depth-0 write's zero takes the adds' pipeline (a
//   read that is not used, then the write), which adds never enter in its cycle. One add or
//   zero per cycle; the sums of the two before it are forwarded to it when they are to its
//   lane, so any sequence of them is exact.
// - Reads (registered: the lane given in a cycle is on the outputs in the next one; seq_ln_i's
//   two cycles later, its address registered before the block RAMs, and seq_ray_o and seq_w_o
//   three cycles later, through a register after their block RAMs):
//     seq_ln_i -> seq_*: the current packet's ray, weight, triangle, t and d'z (the sequencer);
//     fin_ln_i -> fin_*: the primary record, pixel id, sums, lights and the two triangles (the
//              final write).
//   A lane is never read in the cycle it is written, and its record is not written between the
//   read and the use of the data (the users say why: rc_tracer's sequencer reads a slot whose
//   writes are all back and whose next packet is not yet sent; the final write reads a done
//   slot, which no add, write or packet reaches).
// - Memories (rc_ram, one write and one read port each): ray and weight (Slots words of four
//   lanes), the core's writes (Slots x 4 words), the primary records, the first triangles (two),
//   the pixel ids (Slots words), and the sums twice (the adds read one, the final write the
//   other; both written by every add).
// - Parameters: ExpW, FracW (the format); Slots; MaxLights; FW (the lighting's fixed-point term
//   bits); SumW (a sum's bits).
// - Reset: rst_ni (active low, asynchronous) clears the add pipeline's valid bits and the
//   registered writes' enables; the memories are written before they are read.
module rc_lane_store #(
  parameter int unsigned ExpW      = rc_pkg::Fp24ExpW,
  parameter int unsigned FracW     = rc_pkg::Fp24FracW,
  parameter int unsigned Slots     = rc_pkg::TracerSlots,
  parameter int unsigned MaxLights = rc_pkg::LightMaxLights,
  parameter int unsigned FW        = rc_pkg::LightFixedBits + 1,
  parameter int unsigned SumW      = 32,
  // Derived (do not override).
  parameter int unsigned W         = 1 + ExpW + FracW,
  parameter int unsigned SlotW     = (Slots > 1) ? $clog2(Slots) : 1,
  parameter int unsigned LaneW     = SlotW + 2
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,

  // A primary packet takes a slot.
  input  logic                     prim_i,
  input  logic [SlotW-1:0]         prim_slot_i,
  input  logic [127:0]             prim_pixel_i,

  // A slot's packet goes to the core.
  input  logic                     ray_i,
  input  logic [SlotW-1:0]         ray_slot_i,
  input  logic [12*W-1:0]          ray_org_i,
  input  logic [12*W-1:0]          ray_dir_i,
  input  logic [4*W-1:0]           ray_inv_len_i,
  input  logic [4*W-1:0]           ray_w_i,

  // The core's write of a current packet's ray.
  input  logic                     cw_i,
  input  logic [LaneW-1:0]         cw_ln_i,
  input  logic                     cw_d0_i,
  input  logic                     cw_d1_i,
  input  logic                     cw_mirror_i,
  input  logic                     cw_hit_i,
  input  logic [31:0]              cw_tri_i,
  input  logic [W-1:0]             cw_t_i,
  input  logic [W-1:0]             cw_u_i,
  input  logic [W-1:0]             cw_v_i,
  input  logic [W-1:0]             cw_dz_i,
  input  logic [23:0]              cw_rgb_i,

  // The sequencer's read.
  input  logic [LaneW-1:0]         seq_ln_i,
  output logic [7*W-1:0]           seq_ray_o,     // {inv_len, dir, org}
  output logic [W-1:0]             seq_w_o,
  output logic [31:0]              seq_tri_o,
  output logic [W-1:0]             seq_t_o,
  output logic [W-1:0]             seq_dz_o,

  // The adds.
  input  logic                     add_i,
  input  logic [LaneW-1:0]         add_ln_i,
  input  logic [3*FW-1:0]          add_term_i,    // two cycles after add_i
  input  logic [MaxLights-1:0]     add_lights_i,  // two cycles after add_i
  output logic                     add_pend1_o,
  output logic [SlotW-1:0]         add_pend1_slot_o,
  output logic                     add_pend_o,
  output logic [SlotW-1:0]         add_pend_slot_o,

  // The final write's read.
  input  logic [LaneW-1:0]         fin_ln_i,
  output logic [31:0]              fin_pixel_o,
  output logic                     fin_hit_o,
  output logic [31:0]              fin_tri_o,
  output logic [W-1:0]             fin_t_o,
  output logic [W-1:0]             fin_u_o,
  output logic [W-1:0]             fin_v_o,
  output logic [23:0]              fin_rgb_o,
  output logic [3*SumW-1:0]        fin_sum_o,
  output logic [MaxLights-1:0]     fin_lights_o,
  output logic [31:0]              fin_bounce_tri_o,
  output logic [31:0]              fin_refract_tri_o
);

  localparam int unsigned Lanes = Slots * 4;
  localparam int unsigned RwW   = 8 * W;                   // {w, inv_len, dir, org}
  localparam int unsigned CwW   = 32 + 2 * W;              // {tri, t, dz}
  localparam int unsigned PrW   = 1 + 32 + 3 * W + 24;     // {hit, tri, t, u, v, rgb}
  localparam int unsigned SmW   = 3 * SumW + MaxLights;    // {lights, sums}

  if (Slots < 1 || FW > SumW) begin : g_param_check
    $error("rc_lane_store: need Slots >= 1 and FW <= SumW");
  end

  /////////////////////////
  // Rays and weights    //
  /////////////////////////

  // The packet's write and the primary pixel ids' are registered (rw_*_q, pr_*_q) and written a
  // cycle later: the core's take, which enables them, and their data come from across the die,
  // and the records are read only after the core's writes of the packet.
  logic [4*RwW-1:0]   rw_wdata_q, rw_rdata;
  logic               rw_we_q, pr_we_q;
  logic [SlotW-1:0]   rw_slot_q, pr_slot_q;
  logic [127:0]       pr_pixel_q;
  logic [1:0]         seq_lane_q, seq_rw_lane_q;
  logic [LaneW-1:0]   seq_ln_q;  // the sequencer's lane, registered beside the block RAMs
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rw_we_q <= 1'b0;
      pr_we_q <= 1'b0;
    end else begin
      rw_we_q <= ray_i;
      pr_we_q <= prim_i;
    end
  end
  // The addresses and data load in every cycle, without an enable (the take's fan-out): only
  // a write's are used, in the cycle after it.
  always_ff @(posedge clk_i) begin
    rw_slot_q <= ray_slot_i;
    for (int r = 0; r < 4; r++) begin
      rw_wdata_q[r*RwW +: RwW] <= {ray_w_i[r*W +: W], ray_inv_len_i[r*W +: W],
                                   ray_dir_i[r*3*W +: 3*W], ray_org_i[r*3*W +: 3*W]};
    end
    pr_slot_q  <= prim_slot_i;
    pr_pixel_q <= prim_pixel_i;
  end
  // The rays and weights are read through a register after the block RAMs (OutReg): a DP16KD's
  // read reaches the fabric 5.8 ns after the edge, and the lane's select and the fetch ring's
  // distributed RAM are across the die (the lit board routed at 6799b81, seed 2: -2.77 ns).
  rc_ram #(
    .Width (4 * RwW),
    .Depth (Slots),
    .OutReg(1'b1)
  ) u_rw (
    .clk_i,
    .we_i   (rw_we_q),
    .waddr_i(rw_slot_q),
    .wdata_i(rw_wdata_q),
    .re_i   (1'b1),
    .raddr_i(seq_ln_q[LaneW-1:2]),
    .rdata_o(rw_rdata)
  );
  // The lane: a multiplexer (an indexed part-select of the word would be a shifter).
  always_comb begin
    unique case (seq_rw_lane_q)
      2'd0:    {seq_w_o, seq_ray_o} = rw_rdata[0*RwW +: RwW];
      2'd1:    {seq_w_o, seq_ray_o} = rw_rdata[1*RwW +: RwW];
      2'd2:    {seq_w_o, seq_ray_o} = rw_rdata[2*RwW +: RwW];
      default: {seq_w_o, seq_ray_o} = rw_rdata[3*RwW +: RwW];
    endcase
  end

  ///////////////////////////
  // The core's writes     //
  ///////////////////////////

  rc_ram #(
    .Width (CwW),
    .Depth (Lanes),
    .OutReg(1'b0)
  ) u_cw (
    .clk_i,
    .we_i   (cw_i),
    .waddr_i(cw_ln_i),
    .wdata_i({cw_tri_i, cw_t_i, cw_dz_i}),
    .re_i   (1'b1),
    .raddr_i(seq_ln_q),
    .rdata_o({seq_tri_o, seq_t_o, seq_dz_o})
  );

  /////////////////////////////////////////////
  // The primary records and first triangles //
  /////////////////////////////////////////////

  logic [127:0]     pix_rdata;
  logic [31:0]      btri_rdata, rtri_rdata;
  logic [1:0]       fin_lane_q;

  rc_ram #(
    .Width (PrW),
    .Depth (Lanes),
    .OutReg(1'b0)
  ) u_prim (
    .clk_i,
    .we_i   (cw_i && cw_d0_i),
    .waddr_i(cw_ln_i),
    .wdata_i({cw_hit_i, cw_tri_i, cw_t_i, cw_u_i, cw_v_i, cw_rgb_i}),
    .re_i   (1'b1),
    .raddr_i(fin_ln_i),
    .rdata_o({fin_hit_o, fin_tri_o, fin_t_o, fin_u_o, fin_v_o, fin_rgb_o})
  );
  rc_ram #(
    .Width (128),
    .Depth (Slots),
    .OutReg(1'b0)
  ) u_pix (
    .clk_i,
    .we_i   (pr_we_q),
    .waddr_i(pr_slot_q),
    .wdata_i(pr_pixel_q),
    .re_i   (1'b1),
    .raddr_i(fin_ln_i[LaneW-1:2]),
    .rdata_o(pix_rdata)
  );
  always_comb begin
    unique case (fin_lane_q)
      2'd0:    fin_pixel_o = pix_rdata[0*32 +: 32];
      2'd1:    fin_pixel_o = pix_rdata[1*32 +: 32];
      2'd2:    fin_pixel_o = pix_rdata[2*32 +: 32];
      default: fin_pixel_o = pix_rdata[3*32 +: 32];
    endcase
  end

  // The first mirror or refraction ray's triangle, -2 at the primary write.
  logic [31:0] cw_first;
  assign cw_first = cw_d0_i ? -32'sd2 : cw_hit_i ? cw_tri_i : -32'sd1;
  rc_ram #(
    .Width (32),
    .Depth (Lanes),
    .OutReg(1'b0)
  ) u_btri (
    .clk_i,
    .we_i   (cw_i && (cw_d0_i || (cw_d1_i && cw_mirror_i))),
    .waddr_i(cw_ln_i),
    .wdata_i(cw_first),
    .re_i   (1'b1),
    .raddr_i(fin_ln_i),
    .rdata_o(btri_rdata)
  );
  rc_ram #(
    .Width (32),
    .Depth (Lanes),
    .OutReg(1'b0)
  ) u_rtri (
    .clk_i,
    .we_i   (cw_i && (cw_d0_i || (cw_d1_i && !cw_mirror_i))),
    .waddr_i(cw_ln_i),
    .wdata_i(cw_first),
    .re_i   (1'b1),
    .raddr_i(fin_ln_i),
    .rdata_o(rtri_rdata)
  );
  assign fin_bounce_tri_o  = btri_rdata;
  assign fin_refract_tri_o = rtri_rdata;

  //////////////
  // The sums //
  //////////////

  // The add's read (cycle N: add_i, or the zero of a depth-0 write), the old sum registered
  // (N + 1: l_q), its add and write (N + 2: a_q). The word read in N misses the writes of the
  // adds in their N + 1 (a_new, forwarded into the register) and N (fwd_data_q) when they are
  // to the same lane.
  logic             r_valid, r_zero, l_q, l_zero_q, a_q, a_zero_q, fwd_q;
  logic [LaneW-1:0] r_ln, l_ln_q, a_ln_q;
  logic [SmW-1:0]   sm_rdata, sm_fin, l_old, l_old_q, a_new, fwd_data_q;
  assign r_zero  = cw_i && cw_d0_i;
  assign r_valid = add_i || r_zero;
  assign r_ln    = r_zero ? cw_ln_i : add_ln_i;
  rc_ram #(
    .Width (SmW),
    .Depth (Lanes),
    .OutReg(1'b0)
  ) u_sum (
    .clk_i,
    .we_i   (a_q),
    .waddr_i(a_ln_q),
    .wdata_i(a_new),
    .re_i   (r_valid),
    .raddr_i(r_ln),
    .rdata_o(sm_rdata)
  );
  rc_ram #(
    .Width (SmW),
    .Depth (Lanes),
    .OutReg(1'b0)
  ) u_sum_fin (
    .clk_i,
    .we_i   (a_q),
    .waddr_i(a_ln_q),
    .wdata_i(a_new),
    .re_i   (1'b1),
    .raddr_i(fin_ln_i),
    .rdata_o(sm_fin)
  );
  always_comb begin
    if (a_q && a_ln_q == l_ln_q) l_old = a_new;
    else if (fwd_q) l_old = fwd_data_q;
    else l_old = sm_rdata;
  end
  always_comb begin
    a_new[3*SumW +: MaxLights] = l_old_q[3*SumW +: MaxLights] | add_lights_i;
    for (int c = 0; c < 3; c++)
      a_new[c*SumW +: SumW] = l_old_q[c*SumW +: SumW] + SumW'(add_term_i[c*FW +: FW]);
    if (a_zero_q) a_new = '0;
  end
  assign add_pend1_o      = l_q;
  assign add_pend1_slot_o = l_ln_q[LaneW-1:2];
  assign add_pend_o       = a_q;
  assign add_pend_slot_o  = a_ln_q[LaneW-1:2];
  assign {fin_lights_o, fin_sum_o} = sm_fin;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      l_q   <= 1'b0;
      a_q   <= 1'b0;
      fwd_q <= 1'b0;
    end else begin
      l_q   <= r_valid;
      a_q   <= l_q;
      fwd_q <= r_valid && a_q && a_ln_q == r_ln;
    end
  end
  always_ff @(posedge clk_i) begin
    if (r_valid) begin
      l_ln_q   <= r_ln;
      l_zero_q <= r_zero;
    end
    if (l_q) begin
      l_old_q  <= l_old;
      a_ln_q   <= l_ln_q;
      a_zero_q <= l_zero_q;
    end
    if (a_q) fwd_data_q <= a_new;
    seq_ln_q      <= seq_ln_i;
    seq_lane_q    <= seq_ln_q[1:0];
    seq_rw_lane_q <= seq_lane_q;
    fin_lane_q    <= fin_ln_i[1:0];
  end

  ////////////////
  // Assertions //
  ////////////////

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // A primary packet takes a slot no add reaches.
  PrimFree_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               prim_i && a_q |-> a_ln_q[LaneW-1:2] != prim_slot_i);
  PrimFree1_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                prim_i && l_q |-> l_ln_q[LaneW-1:2] != prim_slot_i);
  // The adds leave the pipeline to a depth-0 write's zero.
  ZeroAlone_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                !(add_i && cw_i && cw_d0_i));
`endif

endmodule
