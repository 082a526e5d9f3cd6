// rc_fifo: a first-in first-out queue whose writer never waits: it knows the queue has room (the
// core's queues of threads, each of which holds a thread at most once, or a writer that checks
// count_o before it commits to writing).
//
// Contract
// - Write: push_i with data_i stores an entry at the clock edge. A push into a full queue is
//   illegal (an assertion catches it).
// - Read (valid/ready): valid_o/data_o show the oldest entry from a register (rc_credit_fifo's
//   head register), stable until taken; an entry pushed into an empty queue shows the next cycle.
// - count_o: the entries held (0 .. Depth), a register; a push or a pop changes it from the next
//   cycle on.
// - Parameters: Width (>= 1), Depth (>= 1) entries; MemArray as rc_credit_fifo's (1: the entries
//   behind the head in distributed RAM).
// - Reset: rst_ni (active low, asynchronous) empties the queue.
module rc_fifo #(
  parameter int unsigned Width    = 8,
  parameter int unsigned Depth    = 4,
  parameter bit          MemArray = 1'b1,
  // Derived (do not override).
  parameter int unsigned CntW     = $clog2(Depth + 1)
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             push_i,
  input  logic [Width-1:0] data_i,
  output logic             valid_o,
  input  logic             ready_i,
  output logic [Width-1:0] data_o,
  output logic [CntW-1:0]  count_o
);

  logic            credit, pop;
  logic [CntW-1:0] cnt_q;

  // A push takes its credit and writes in the same cycle: the credit FIFO's count is then the
  // number of entries held.
  rc_credit_fifo #(
    .Width   (Width),
    .Depth   (Depth),
    .MemArray(MemArray)
  ) u_fifo (
    .clk_i,
    .rst_ni,
    .take_i    (push_i),
    .credit_o  (credit),
    .wr_valid_i(push_i),
    .wr_data_i (data_i),
    .valid_o,
    .ready_i,
    .data_o
  );

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      cnt_q <= '0;
    end else begin
      cnt_q <= cnt_q + CntW'(push_i) - CntW'(pop);
    end
  end
  assign count_o = cnt_q;
  assign pop     = valid_o & ready_i;

`ifndef SYNTHESIS
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );
  // The writer knows there is room.
  PushRoom_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                               push_i |-> credit && cnt_q < CntW'(Depth));
`endif

endmodule
