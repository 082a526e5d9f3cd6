// A stand-in with rc_core's ports, for testing the harness (tb/harness/core_sim_impl.hpp) on its
// own: it takes one packet at a time and, for each existing ray in turn, reads one record from
// each memory port and writes a framebuffer entry made from those records' bits:
//   p = pixel id; node = nodes[p % node_count] (the port's pair: record i at [63:0], record
//   i + 1 at [127:64]); l = lists[p % list_count];
//   tri = triangles[l]; shd = shading[l]; kd = materials[shd.material & 0xffff];
//   fb: hit 1, tri l, t = tri value 11, u = shd value 0 (normal x),
//       v = node[63:40] ^ node[127:104] ^ root_node_i[63:40] (both records and the root),
//       rgb = kd slot 0, 1, 2 low bytes.
// An error response sets error_o bit 1. Hang = 1: it never takes a node response (the harness's
// watchdog test). perf_o: cycles, packets, rays, fb writes, and the rays again as primary rays
// (every packet is counted as a primary one); every other counter 0.
module rc_fake_core #(
  parameter int unsigned ExpW = 7,
  parameter int unsigned FracW = 16,
  parameter int unsigned Hang = 0,
  parameter int unsigned W = 1 + ExpW + FracW,
  parameter int unsigned TagW = rc_pkg::CoreTagBits
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  /* verilator lint_off UNUSEDSIGNAL */
  input  logic [6*W-1:0]    bounds_i,
  input  logic [31:0]       node_count_i,
  input  logic [31:0]       list_count_i,
  input  logic [31:0]       tri_count_i,
  input  logic [63:0]       root_node_i,
  input  logic [W-1:0]      ambient_i,
  input  logic [W-1:0]      diffuse_i,
  input  logic [23:0]       background_i,
  input  logic [W-1:0]      t_eps_i,
  input  logic              pkt_valid_i,
  output logic              pkt_ready_o,
  input  logic [3:0]        pkt_mask_i,
  input  logic [12*W-1:0]   pkt_org_i,
  input  logic [12*W-1:0]   pkt_dir_i,
  input  logic [4*W-1:0]    pkt_inv_len_i,
  input  logic [127:0]      pkt_pixel_i,
  input  logic [1:0]        pkt_kind_i,
  input  logic [4*W-1:0]    pkt_t_hi_i,
  input  logic [127:0]      pkt_start_tri_i,
  output logic              fb_valid_o,
  input  logic              fb_ready_i,
  output logic [31:0]       fb_pixel_o,
  output logic [23:0]       fb_rgb_o,
  output logic              fb_hit_o,
  output logic [31:0]       fb_tri_o,
  output logic [W-1:0]      fb_t_o,
  output logic [W-1:0]      fb_u_o,
  output logic [W-1:0]      fb_v_o,
  output logic              node_req_valid_o,
  input  logic              node_req_ready_i,
  output logic [TagW-1:0]   node_req_tag_o,
  output logic [31:0]       node_req_index_o,
  input  logic              node_rsp_valid_i,
  output logic              node_rsp_ready_o,
  input  logic [TagW-1:0]   node_rsp_tag_i,
  input  logic [127:0]      node_rsp_data_i,
  input  logic              node_rsp_error_i,
  output logic              list_req_valid_o,
  input  logic              list_req_ready_i,
  output logic [TagW-1:0]   list_req_tag_o,
  output logic [31:0]       list_req_index_o,
  input  logic              list_rsp_valid_i,
  output logic              list_rsp_ready_o,
  input  logic [TagW-1:0]   list_rsp_tag_i,
  input  logic [31:0]       list_rsp_data_i,
  input  logic              list_rsp_error_i,
  output logic              tri_req_valid_o,
  input  logic              tri_req_ready_i,
  output logic [TagW-1:0]   tri_req_tag_o,
  output logic [31:0]       tri_req_index_o,
  input  logic              tri_rsp_valid_i,
  output logic              tri_rsp_ready_o,
  input  logic [TagW-1:0]   tri_rsp_tag_i,
  input  logic [12*W-1:0]   tri_rsp_data_i,
  input  logic              tri_rsp_error_i,
  output logic              shd_req_valid_o,
  input  logic              shd_req_ready_i,
  output logic [TagW-1:0]   shd_req_tag_o,
  output logic [31:0]       shd_req_index_o,
  input  logic              shd_rsp_valid_i,
  output logic              shd_rsp_ready_o,
  input  logic [TagW-1:0]   shd_rsp_tag_i,
  input  logic [32+4*W-1:0] shd_rsp_data_i,
  input  logic              shd_rsp_error_i,
  output logic              mat_req_valid_o,
  input  logic              mat_req_ready_i,
  output logic [TagW-1:0]   mat_req_tag_o,
  output logic [31:0]       mat_req_index_o,
  input  logic              mat_rsp_valid_i,
  output logic              mat_rsp_ready_o,
  input  logic [TagW-1:0]   mat_rsp_tag_i,
  input  logic [95:0]       mat_rsp_data_i,
  input  logic              mat_rsp_error_i,
  output logic              idle_o,
  output logic [rc_pkg::CoreStatusBits-1:0] error_o,
  input  logic [7:0]        perf_sel_i,
  output logic [63:0]       perf_o
  /* verilator lint_on UNUSEDSIGNAL */
);
  typedef enum logic [3:0] {
    Idle, Next, NodeReq, NodeRsp, ListReq, ListRsp, TriReq, TriRsp, ShdReq, ShdRsp, MatReq,
    MatRsp, Write
  } state_e;
  state_e state_q;
  logic [3:0] mask_q;
  logic [127:0] pixels_q;
  logic [1:0] ray_q;
  logic [31:0] pix_q, list_q, mat_q;
  logic [W-1:0] t_q, u_q, v_q;
  logic [23:0] rgb_q;
  logic [63:0] cycles_q, packets_q, rays_q, writes_q;
  logic [rc_pkg::CoreStatusBits-1:0] err_q;

  assign pkt_ready_o = state_q == Idle;
  assign idle_o = state_q == Idle;
  assign error_o = err_q;
  assign node_req_valid_o = state_q == NodeReq;
  assign list_req_valid_o = state_q == ListReq;
  assign tri_req_valid_o = state_q == TriReq;
  assign shd_req_valid_o = state_q == ShdReq;
  assign mat_req_valid_o = state_q == MatReq;
  assign node_req_tag_o = '0;
  assign list_req_tag_o = '0;
  assign tri_req_tag_o = '0;
  assign shd_req_tag_o = '0;
  assign mat_req_tag_o = '0;
  assign node_req_index_o = pix_q % node_count_i;
  assign list_req_index_o = pix_q % list_count_i;
  assign tri_req_index_o = list_q;
  assign shd_req_index_o = list_q;
  assign mat_req_index_o = mat_q;
  assign node_rsp_ready_o = state_q == NodeRsp && Hang == 0;
  assign list_rsp_ready_o = state_q == ListRsp;
  assign tri_rsp_ready_o = state_q == TriRsp;
  assign shd_rsp_ready_o = state_q == ShdRsp;
  assign mat_rsp_ready_o = state_q == MatRsp;
  assign fb_valid_o = state_q == Write;
  assign fb_pixel_o = pix_q;
  assign fb_rgb_o = rgb_q;
  assign fb_hit_o = 1'b1;
  assign fb_tri_o = list_q;
  assign fb_t_o = t_q;
  assign fb_u_o = u_q;
  assign fb_v_o = v_q;
  always_comb begin
    unique case (perf_sel_i)
      8'(rc_pkg::CorePerfCycles):      perf_o = cycles_q;
      8'(rc_pkg::CorePerfPackets):     perf_o = packets_q;
      8'(rc_pkg::CorePerfRays):        perf_o = rays_q;
      8'(rc_pkg::CorePerfFbWrites):    perf_o = writes_q;
      8'(rc_pkg::CorePerfPrimaryRays): perf_o = rays_q;
      default:                         perf_o = '0;
    endcase
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= Idle;
      mask_q <= '0;
      pixels_q <= '0;
      ray_q <= '0;
      pix_q <= '0;
      list_q <= '0;
      mat_q <= '0;
      t_q <= '0;
      u_q <= '0;
      v_q <= '0;
      rgb_q <= '0;
      cycles_q <= '0;
      packets_q <= '0;
      rays_q <= '0;
      writes_q <= '0;
      err_q <= '0;
    end else begin
      cycles_q <= cycles_q + 64'd1;
      unique case (state_q)
        Idle: if (pkt_valid_i) begin
          mask_q <= pkt_mask_i;
          pixels_q <= pkt_pixel_i;
          ray_q <= '0;
          packets_q <= packets_q + 64'd1;
          state_q <= Next;
        end
        Next: begin
          if (mask_q == '0) state_q <= Idle;
          else if (mask_q[ray_q]) begin
            pix_q <= pixels_q[32*ray_q +: 32];
            mask_q[ray_q] <= 1'b0;
            rays_q <= rays_q + 64'd1;
            state_q <= NodeReq;
          end else ray_q <= ray_q + 2'd1;
        end
        NodeReq: if (node_req_ready_i) state_q <= NodeRsp;
        NodeRsp: if (node_rsp_valid_i && node_rsp_ready_o) begin
          v_q <= node_rsp_data_i[63:64-W] ^ node_rsp_data_i[127:128-W] ^ root_node_i[63:64-W];
          err_q[1] <= err_q[1] | node_rsp_error_i;
          state_q <= ListReq;
        end
        ListReq: if (list_req_ready_i) state_q <= ListRsp;
        ListRsp: if (list_rsp_valid_i) begin
          list_q <= list_rsp_data_i;
          err_q[1] <= err_q[1] | list_rsp_error_i;
          state_q <= TriReq;
        end
        TriReq: if (tri_req_ready_i) state_q <= TriRsp;
        TriRsp: if (tri_rsp_valid_i) begin
          t_q <= tri_rsp_data_i[11*W +: W];
          err_q[1] <= err_q[1] | tri_rsp_error_i;
          state_q <= ShdReq;
        end
        ShdReq: if (shd_req_ready_i) state_q <= ShdRsp;
        ShdRsp: if (shd_rsp_valid_i) begin
          u_q <= shd_rsp_data_i[32 +: W];
          mat_q <= {16'd0, shd_rsp_data_i[15:0]};
          err_q[1] <= err_q[1] | shd_rsp_error_i;
          state_q <= MatReq;
        end
        MatReq: if (mat_req_ready_i) state_q <= MatRsp;
        MatRsp: if (mat_rsp_valid_i) begin
          rgb_q <= {mat_rsp_data_i[71:64], mat_rsp_data_i[39:32], mat_rsp_data_i[7:0]};
          err_q[1] <= err_q[1] | mat_rsp_error_i;
          state_q <= Write;
        end
        Write: if (fb_ready_i) begin
          writes_q <= writes_q + 64'd1;
          state_q <= Next;
        end
        default: state_q <= Idle;
      endcase
    end
  end
endmodule
