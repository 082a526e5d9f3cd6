// rc_credit_fifo: output FIFO with credit accounting, to put a ready/valid handshake around a
// fixed-latency, valid-only pipeline that cannot stall.
//
// Contract
// - Use: the owning unit drives take_i = valid_i & ready_o (an operation enters its pipeline) and
//   uses credit_o as its ready_o. The pipeline's output (wr_valid_i, wr_data_i) is written into
//   the FIFO; the FIFO drives the downstream handshake (valid_o, ready_i, data_o).
// - Credits: cnt_q counts operations in flight in the pipeline plus entries held in the FIFO.
//   credit_o = cnt_q < Depth, itself a register (credit_q, loaded with cnt_d != Depth: the count
//   never exceeds Depth; checked by CreditIsCount_A), so the owner's ready fans out from a
//   flip-flop and no compare sits before it; credit_o never depends on ready_i or valid_i in the
//   same cycle. Since every operation in flight has a FIFO slot reserved, a write always finds
//   room and nothing is dropped, whatever ready_i does.
// - Handshake (downstream): valid_o/ready_i; an entry is popped when valid_o & ready_i. valid_o
//   and data_o are flip-flops (an output register at the head, loaded from the storage or
//   straight from a write) and stay stable until popped (valid_o never depends on ready_i).
// - Latency: a write appears on valid_o/data_o the cycle after wr_valid_i.
// - Throughput: with a pipeline of latency L (take_i to wr_valid_i), an operation is counted in
//   cnt_q for L + 1 cycles when ready_i is 1, and credit_o needs cnt_q < Depth, so Depth >= L + 2
//   sustains one operation per cycle.
// - Parameters: Width data bits (>= 1); Depth entries (>= 1: the head register and Depth - 1
//   behind it; Depth = 1 is the head register alone: with one credit a write always finds the
//   head free); MemArray: 0 = the entries behind the head in a flat register vector with a read
//   multiplexer (flip-flops), 1 = in a memory array written at wr_ptr and read asynchronously at
//   rd_ptr, mapped to distributed RAM (ram_style; e.g. ECP5 DPR16X4, never block RAM): the
//   better choice for deep or wide FIFOs. Same behaviour either way.
// - Illegal input: take_i while credit_o is 0; wr_valid_i for an operation that did not take a
//   credit (more writes than takes). Both are caught by assertions.
// - Reset: rst_ni (active low, asynchronous) clears the pointers and counters; the storage has no
//   reset.
module rc_credit_fifo #(
  parameter int unsigned Width    = 1,
  parameter int unsigned Depth    = 2,
  parameter bit          MemArray = 1'b0
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  // Credit side (upstream of the pipeline).
  input  logic             take_i,
  output logic             credit_o,
  // Pipeline output.
  input  logic             wr_valid_i,
  input  logic [Width-1:0] wr_data_i,
  // Downstream handshake.
  output logic             valid_o,
  input  logic             ready_i,
  output logic [Width-1:0] data_o
);

  ////////////////
  // Parameters //
  ////////////////

  if (Width < 1 || Depth < 1) begin : g_param_check
    $error("rc_credit_fifo: need Width >= 1 and Depth >= 1");
  end

  //////////////
  // Counters //
  //////////////

  // The head of the FIFO is an output register (out_q, out_v_q); the storage behind it holds
  // the entries after the head (RamDepth = Depth - 1 suffice: it is non-empty only while the
  // head is full). A write goes straight into the output register when the storage is empty and
  // the register is free or being popped (the latency stays one cycle), else into the storage;
  // the register reloads from the storage when it is free or popped. So valid_o and data_o are
  // flip-flops, and the storage's read (a distributed-RAM read) ends at the output register
  // instead of running into the consumer's logic.
  localparam int unsigned RamDepth = (Depth > 1) ? Depth - 1 : 1;
  localparam int unsigned CntW     = $clog2(Depth + 1);              // holds 0 .. Depth
  localparam int unsigned PtrW     = (RamDepth > 1) ? $clog2(RamDepth) : 1;
  localparam logic [CntW-1:0] DepthCnt = CntW'(Depth);
  localparam logic [PtrW-1:0] LastPtr  = PtrW'(RamDepth - 1);

  logic             pop, credit_q, credit_d, out_v_q, out_free, ram_any, ram_rd, ram_wr, bypass;
  logic [CntW-1:0]  cnt_d, cnt_q;  // credits in use: in flight + stored (storage + head)
  logic [CntW-1:0]  occ_d, occ_q;  // entries in the storage behind the head
  logic             ram_any_q, ram_any_d;  // occ_q != 0
  logic [PtrW-1:0]  wr_ptr_d, wr_ptr_q, rd_ptr_d, rd_ptr_q;
  logic [Width-1:0] ram_data, out_q;

  assign pop      = out_v_q & ready_i;
  assign out_free = ~out_v_q | ready_i;
  assign ram_any  = (Depth > 1) && ram_any_q;  // Depth 1: no storage behind the head
  assign ram_rd   = out_free & ram_any;
  assign bypass   = out_free & ~ram_any & wr_valid_i;
  assign ram_wr   = wr_valid_i & ~bypass;
  assign credit_o = credit_q;
  assign valid_o  = out_v_q;
  assign data_o   = out_q;

  // The counts move by at most one a cycle: the count one up and one down are made from the
  // registers, beside the handshakes, which only select (no adder behind ready_i). The flags
  // derived from the counts (credit_q: cnt_q != Depth; ram_any_q: occ_q != 0) are registered
  // from the same selection, with their compares against the registers too (run 47: the ray
  // generator's FIFO, occ_q -> occ_q, -1.04 ns, and credit_q, -0.40 ns).
  always_comb begin
    cnt_d    = cnt_q;
    credit_d = credit_q;
    if (take_i && !pop) begin
      cnt_d    = cnt_q + CntW'(1);
      credit_d = cnt_q != DepthCnt - CntW'(1);
    end else if (pop && !take_i) begin
      cnt_d    = cnt_q - CntW'(1);
      credit_d = 1'b1;
    end
    occ_d     = occ_q;
    ram_any_d = ram_any_q;
    if (ram_wr && !ram_rd) begin
      occ_d     = occ_q + CntW'(1);
      ram_any_d = 1'b1;
    end else if (ram_rd && !ram_wr) begin
      occ_d     = occ_q - CntW'(1);
      ram_any_d = occ_q != CntW'(1);
    end
    wr_ptr_d = wr_ptr_q;
    if (ram_wr) wr_ptr_d = (wr_ptr_q == LastPtr) ? '0 : wr_ptr_q + PtrW'(1);
    rd_ptr_d = rd_ptr_q;
    if (ram_rd) rd_ptr_d = (rd_ptr_q == LastPtr) ? '0 : rd_ptr_q + PtrW'(1);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      cnt_q     <= '0;
      credit_q  <= 1'b1;
      occ_q     <= '0;
      ram_any_q <= 1'b0;
      wr_ptr_q <= '0;
      rd_ptr_q <= '0;
      out_v_q  <= 1'b0;
    end else begin
      cnt_q     <= cnt_d;
      credit_q  <= credit_d;
      occ_q     <= occ_d;
      ram_any_q <= ram_any_d;
      wr_ptr_q <= wr_ptr_d;
      rd_ptr_q <= rd_ptr_d;
      if (out_free) out_v_q <= ram_any | wr_valid_i;
    end
  end

  // The head register loads whenever it is free, from the storage if that holds an entry, else
  // from the write port (the entry if there is a write, a value out_v_q marks empty otherwise):
  // its enable is out_free alone and its select a register compare, so neither the write's valid
  // nor the bypass decision reaches the head's Width clock enables.
  // With Depth 1 a write never meets a valid head (one credit: HeadFree1_A), so the head loads
  // only while it is empty, and ready_i reaches no clock enable at all (the tracer's one-packet
  // queues, hundreds of bits wide, popped by the core's take).
  logic head_load;
  assign head_load = (Depth == 1) ? ~out_v_q : out_free;
  always_ff @(posedge clk_i) begin
    if (head_load) begin
      out_q <= ram_any ? ram_data : wr_data_i;
    end
  end

  /////////////
  // Storage //
  /////////////

  // Every write is stored at wr_ptr_q, also one that bypasses the storage into the head register:
  // that happens only with the storage empty, so the slot holds nothing, and the pointer does
  // not move (only ram_wr moves it). So the storage's write enable is wr_valid_i alone, not the
  // bypass decision (the head's state and ready_i), before the write enables of every memory
  // cell (run 33: -0.38 ns).

  if (Depth == 1) begin : g_no_mem
    // The head register alone: with one credit, a write comes only while the head is free.
    assign ram_data = '0;
  end else if (MemArray) begin : g_mem_array
    // Write port at wr_ptr_q, asynchronous read at rd_ptr_q (distributed RAM). ram_style keeps
    // synthesis from making the output register the read port of a block RAM, whose
    // clock-to-out (5.8 ns on the LFE5U-85F) would then start the consumer's paths.
    (* ram_style = "distributed" *) logic [Width-1:0] mem_q [0:RamDepth-1];

    always_ff @(posedge clk_i) begin
      if (wr_valid_i) mem_q[wr_ptr_q] <= wr_data_i;
    end

    assign ram_data = mem_q[rd_ptr_q];
  end else begin : g_mem_flat
    // Entry i at mem_q[i*Width +: Width] (flat vectors: Yosys 0.23 reads no multi-dimensional
    // packed arrays).
    logic [RamDepth*Width-1:0] mem_q;

    always_ff @(posedge clk_i) begin
      for (int unsigned i = 0; i < RamDepth; i++) begin
        if (wr_valid_i && wr_ptr_q == PtrW'(i)) mem_q[i*Width +: Width] <= wr_data_i;
      end
    end

    always_comb begin
      ram_data = '0;
      for (int unsigned i = 0; i < RamDepth; i++) begin
        if (rd_ptr_q == PtrW'(i)) ram_data = mem_q[i*Width +: Width];
      end
    end
  end

  ////////////////
  // Assertions //
  ////////////////

`ifndef SYNTHESIS
  // Simulation-only: 1 from the first clock edge after a reset (rc_checks_on).
  logic checks_on;
  rc_checks_on u_checks_on (
    .clk_i,
    .rst_ni,
    .on_o (checks_on)
  );

  // Depth 1: a write finds the head empty (its one credit was free at the take).
  HeadFree1_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                Depth == 1 && wr_valid_i |-> !out_v_q);
  // An operation may only enter the pipeline with a credit, or its result could find no slot.
  TakeHasCredit_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    take_i |-> credit_o);
  // Every write was reserved by a credit, so the storage is never full when a write goes there
  // (it holds at most Depth - 1 entries: it is non-empty only while the head is full).
  WriteHasRoom_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                   ram_wr |-> Depth > 1 && occ_q < CntW'(RamDepth));
  // Entries wait behind a full head only.
  HeadFirst_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                ram_any |-> out_v_q);
  // The credit register always equals the count's compare (both are loaded from cnt_d).
  CreditIsCount_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                    credit_o == (cnt_q < DepthCnt));
  // Stored entries (storage and head) are a subset of the credits in use (the rest are in
  // flight).
  OccWithinCredits_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                       occ_q + CntW'(out_v_q) <= cnt_q && cnt_q <= DepthCnt);
  // The storage's flag always equals its count's compare (both are loaded from the same case).
  RamAnyIsOcc_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  ram_any_q == (occ_q != '0));
  // Handshake outputs must be known once out of reset.
  HandshakeKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                     !$isunknown({valid_o, credit_o}));
  // A result offered downstream must be fully determined.
  DataKnown_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                valid_o |-> !$isunknown(data_o));
  // The offered entry stays until it is taken (registered FIFO head).
  ValidStable_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                  valid_o && !ready_i |=> valid_o && $stable(data_o));
`endif

endmodule
