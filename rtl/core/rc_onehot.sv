// rc_onehot: a thread number as a one-hot vector (an event's thread, for the per-thread state
// that many units keep: N outputs, each an AND of two predecoded lines).
//
// Contract
// - hot_o[i] = valid_i && idx_i == i, for i < N (combinational).
// - Structure: the index's low 4 bits are predecoded into 16 lines and the rest, with valid_i,
//   into N/16 lines (rounded up); each output is the AND of its two lines: N + N/16 + 16 LUT4
//   for all N threads, where a compare per thread costs about 3N. Synthesis does not keep the
//   structure when it may build wider functions from LUT4s: ABC maps an output of this module
//   alone as one function of all its inputs (N = 64, synth_ecp5: 263 LUT4 and 64 L6MUX21 in
//   Yosys 0.70, 512 and 192 in 0.23; 80 LUT4 with -nowidelut in both).
// - Parameters: N (>= 1) outputs, IdxW index bits (2^IdxW >= N).
module rc_onehot #(
  parameter int unsigned N    = 8,
  parameter int unsigned IdxW = (N > 1) ? $clog2(N) : 1
) (
  input  logic            valid_i,
  input  logic [IdxW-1:0] idx_i,
  output logic [N-1:0]    hot_o
);

  if (N < 1 || (1 << IdxW) < N) begin : g_param_check
    $error("rc_onehot: need N >= 1 and 2^IdxW >= N");
  end

  if (IdxW <= 4) begin : g_small
    for (genvar i = 0; i < N; i++) begin : g_out
      assign hot_o[i] = valid_i && idx_i == IdxW'(i);
    end
  end else begin : g_split
    localparam int unsigned HiW = IdxW - 4;
    localparam int unsigned NHi = (N + 15) / 16;
    logic [15:0]    lo;
    logic [NHi-1:0] hi;
    for (genvar i = 0; i < 16; i++) begin : g_lo
      assign lo[i] = idx_i[3:0] == 4'(i);
    end
    for (genvar i = 0; i < NHi; i++) begin : g_hi
      assign hi[i] = valid_i && idx_i[IdxW-1:4] == HiW'(i);
    end
    // Sixteen outputs at a time: the same ANDs as one assign per output, written so that the
    // verilated model computes a 16-bit AND per line instead of one operation per bit.
    localparam int unsigned NPad = NHi * 16;
    logic [NPad-1:0] hot;
    for (genvar g = 0; g < NHi; g++) begin : g_out
      assign hot[g*16 +: 16] = {16{hi[g]}} & lo;
    end
    assign hot_o = hot[N-1:0];
  end

endmodule
