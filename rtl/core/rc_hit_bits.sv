// rc_hit_bits: the per-ray "has a best hit" bits of every packet thread (docs/architecture.md,
// "Thread control"), as flip-flops updated by the two events that change them. rc_thread_ctrl
// keeps the copy the pop unit, the shading sequencer and the hit store read; the intersection
// issue keeps its own (rc_isect_issue), so its read by thread number does not load those.
//
// Contract
// - hit_o[4t + r]: ray r of thread t has a best hit. Set by the write-back's commit (hit_valid_i
//   for ray hit_ray_i of thread hit_thr_i), cleared when a packet is taken into the thread
//   (acc_hot_i[t], the take's thread one-hot: a register in rc_setup_unit, so no thread number
//   is decoded here); a clear wins over a set in the same cycle.
// - Timing: an event changes the bits at the clock edge that ends its cycle.
// - Parameters: Threads (>= 1).
// - Reset: rst_ni (active low, asynchronous) clears every bit.
module rc_hit_bits #(
  parameter int unsigned Threads = rc_pkg::CoreThreads,
  // Derived (do not override).
  parameter int unsigned ThrW    = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic [Threads-1:0]   acc_hot_i,
  input  logic                 hit_valid_i,
  input  logic [ThrW-1:0]      hit_thr_i,
  input  logic [1:0]           hit_ray_i,
  output logic [Threads*4-1:0] hit_o
);

  logic [Threads-1:0]   h_hit;
  logic [Threads*4-1:0] hit_q;
  logic [3:0]           ray_hot;
  rc_onehot #(.N(Threads), .IdxW(ThrW)) u_h_hit (.valid_i(hit_valid_i), .idx_i(hit_thr_i),
                                                  .hot_o(h_hit));
  assign ray_hot = 4'd1 << hit_ray_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hit_q <= '0;
    end else begin
      for (int unsigned t = 0; t < Threads; t++) begin
        hit_q[t*4 +: 4] <= acc_hot_i[t] ? 4'd0 : (hit_q[t*4 +: 4] | ({4{h_hit[t]}} & ray_hot));
      end
    end
  end
  assign hit_o = hit_q;

endmodule
