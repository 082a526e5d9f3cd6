// rc_ray_store: the rays of every packet thread (docs/architecture.md, "Ray store"), kept once per
// reader in the layout each reader needs, in block RAMs (rc_ram, data two cycles after a read).
//
// Contract
// - Per axis, addressed {thread, axis} (written by ray set-up; read by the traversal unit, which
//   needs the four rays on one split axis at once): the rays' origins and direction sign bits
//   (ax_*: written per axis as the packet's rays are taken) and their 1/d (inv_*: written per
//   axis after the packet's set-up).
// - Per ray, addressed {thread, ray} (written as each ray is taken): origin and direction, and
//   the ray's kind, start triangle and limit {secondary, start_tri, tlim} (read together by the
//   intersection issue), inv_len (read by shading), the pixel id (read by the framebuffer
//   write).
// - A thread's words are written before any unit reads them (a packet's reads follow its start,
//   which follows the writes) and not written while any unit may still read them (a thread is
//   taken again only after its last framebuffer write).
// - Parameters: Threads; Secondary: 1 = the limit words as above, 0 = none (ray_wlim_i not
//   read, lim_o = 0: every ray a primary one).
// - Reset: none.
module rc_ray_store #(
  parameter int unsigned Threads   = rc_pkg::CoreThreads,
  parameter bit          Secondary = 1'b1,
  // Derived (do not override).
  parameter int unsigned W         = rc_pkg::CoreFpW,
  parameter int unsigned ThrW      = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic            clk_i,

  // Writes (ray set-up).
  input  logic            ray_we_i,
  input  logic [ThrW-1:0] ray_wthr_i,
  input  logic [1:0]      ray_wray_i,
  input  logic [6*W-1:0]  ray_worgdir_i,
  input  logic [W+31:0]   ray_wlenpix_i,   // {pixel id, inv_len}
  input  logic [W+32:0]   ray_wlim_i,      // {secondary, start triangle, tlim}
  input  logic            ax_we_i,
  input  logic [ThrW-1:0] ax_wthr_i,
  input  logic [1:0]      ax_waxis_i,
  input  logic [4*W+3:0]  ax_wdata_i,      // {sign bits, org of rays 3..0}
  input  logic            inv_we_i,
  input  logic [ThrW-1:0] inv_wthr_i,
  input  logic [1:0]      inv_waxis_i,
  input  logic [4*W-1:0]  inv_wdata_i,

  // The traversal unit: the rays on one axis.
  input  logic            ax_re_i,
  input  logic [ThrW-1:0] ax_rthr_i,
  input  logic [1:0]      ax_raxis_i,
  output logic [4*W-1:0]  ax_org_o,
  output logic [3:0]      ax_sign_o,
  output logic [4*W-1:0]  ax_inv_o,

  // The intersection issue: one ray's origin and direction, and its limit word.
  input  logic            od_re_i,
  input  logic [ThrW-1:0] od_rthr_i,
  input  logic [1:0]      od_rray_i,
  output logic [6*W-1:0]  od_o,
  output logic [W+32:0]   lim_o,

  // Shading: one ray's inv_len; the framebuffer write: its pixel id.
  input  logic            ilen_re_i,
  input  logic [ThrW-1:0] ilen_rthr_i,
  input  logic [1:0]      ilen_rray_i,
  output logic [W-1:0]    ilen_o,
  input  logic            pix_re_i,
  input  logic [ThrW-1:0] pix_rthr_i,
  input  logic [1:0]      pix_rray_i,
  output logic [31:0]     pix_o
);

  localparam int unsigned Depth4 = 4 << ThrW;  // {thread, ray} addresses

  rc_ram #(.Width(4 * W + 4), .Depth(Depth4), .OutReg(1'b1)) u_ax (
    .clk_i,
    .we_i   (ax_we_i),
    .waddr_i({ax_wthr_i, ax_waxis_i}),
    .wdata_i(ax_wdata_i),
    .re_i   (ax_re_i),
    .raddr_i({ax_rthr_i, ax_raxis_i}),
    .rdata_o({ax_sign_o, ax_org_o})
  );
  rc_ram #(.Width(4 * W), .Depth(Depth4), .OutReg(1'b1)) u_inv (
    .clk_i,
    .we_i   (inv_we_i),
    .waddr_i({inv_wthr_i, inv_waxis_i}),
    .wdata_i(inv_wdata_i),
    .re_i   (ax_re_i),
    .raddr_i({ax_rthr_i, ax_raxis_i}),
    .rdata_o(ax_inv_o)
  );
  // The per-ray word: {limit word, origin and direction}, or the latter alone without Secondary.
  localparam int unsigned OdW = 6 * W + (Secondary ? W + 33 : 0);
  logic [OdW-1:0] od_wdata, od_rdata;
  if (Secondary) begin : g_od_lim
    assign od_wdata       = {ray_wlim_i, ray_worgdir_i};
    assign {lim_o, od_o}  = od_rdata;
  end else begin : g_od
    assign od_wdata = ray_worgdir_i;
    assign od_o     = od_rdata;
    assign lim_o    = '0;
    logic unused_lim;
    assign unused_lim = ^ray_wlim_i;
  end
  rc_ram #(.Width(OdW), .Depth(Depth4), .OutReg(1'b1)) u_od (
    .clk_i,
    .we_i   (ray_we_i),
    .waddr_i({ray_wthr_i, ray_wray_i}),
    .wdata_i(od_wdata),
    .re_i   (od_re_i),
    .raddr_i({od_rthr_i, od_rray_i}),
    .rdata_o(od_rdata)
  );
  rc_ram #(.Width(W), .Depth(Depth4), .OutReg(1'b1)) u_ilen (
    .clk_i,
    .we_i   (ray_we_i),
    .waddr_i({ray_wthr_i, ray_wray_i}),
    .wdata_i(ray_wlenpix_i[W-1:0]),
    .re_i   (ilen_re_i),
    .raddr_i({ilen_rthr_i, ilen_rray_i}),
    .rdata_o(ilen_o)
  );
  rc_ram #(.Width(32), .Depth(Depth4), .OutReg(1'b1)) u_pix (
    .clk_i,
    .we_i   (ray_we_i),
    .waddr_i({ray_wthr_i, ray_wray_i}),
    .wdata_i(ray_wlenpix_i[W +: 32]),
    .re_i   (pix_re_i),
    .raddr_i({pix_rthr_i, pix_rray_i}),
    .rdata_o(pix_o)
  );

endmodule
