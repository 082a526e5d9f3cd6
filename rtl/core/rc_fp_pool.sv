// rc_fp_pool: the fp multipliers (or adders) of a component-serial unit (rc_light_term,
// rc_hit_geom; one operator in rc_fp_shared), as few as its schedule allows at its Period: every
// user is placed on an operator at elaboration, the first whose phases it does not meet.
//
// Contract
// - Function: in a cycle with issue_i[k] set, user k's operands a_i[k], b_i[k] enter the operator
//   the user is placed on (Add: a - b where Sub[k] is set, a + b elsewhere); res_o[k] and
//   valid_o[k] are that operator's result and valid, Latency = Stages + InReg cycles later
//   (rc_fp_mul or rc_fp_add, bit for bit; Stages the package's [fp_stages]). Users placed on one
//   operator see each other's results too: each reads res_o[k] at its own time, Latency cycles
//   after its issue.
// - InReg = 1: a register (operands, subtract bit and valid) between each operator's select and
//   the operator, so the select (and whatever the owner puts before it) is all the logic of its
//   cycle and the operator's first stage starts from flip-flops; the latency is one more.
// - Placement: the owner takes its jobs at phase 0 modulo Period (rc_serial_sched, Phased), so
//   user k issues at phase Time[k] mod Period and the next Cycles[k] - 1 phases. Users are placed
//   by decreasing Cycles, then by increasing first phase, then by index, each on the lowest
//   operator none of whose placed users shares one of its phases (first fit); Ops is the number
//   of operators that takes. (In index order, rc_light_term's products took 8 multipliers at
//   Period 12 where 7 suffice; this order reaches the least for rc_light_term and rc_hit_geom at
//   6 and 12, as a search over orders showed.) The same users therefore take
//   fewer operators at a longer Period (at 6 a vector operation's three cycles fill half an
//   operator, at 12 a quarter), and the owner's schedule alone decides the sharing.
// - Select: on each operator, its first user's operands unless another of its users issues (a
//   chain of two-way selects), so an idle cycle's operands mean nothing (with InReg, the input
//   register takes them every cycle).
// - issue_i must never set two users of one operator in a cycle (assertion): their phases are
//   disjoint, so only an owner that breaks its own schedule can.
// - Parameters: ExpW, FracW (the format); Add (0: rc_fp_mul, 1: rc_fp_add); Users (1 to 32); Sub
//   (Add only: bit k, user k subtracts); Period (the owner's cycles per job, 3 to 16); Time: user
//   k's issue time (after the job's slot 0) in bits [16k +: 16]; Cycles: bits [2k +: 2], the
//   consecutive cycles user k issues in (1 to 3); InReg (0 or 1, default 0: rc_fp_shared's; the
//   light units take 1). The stages are the package's ([fp_stages]).
// - Reset: rst_ni (active low, asynchronous) clears the operators' valid pipelines (and the input
//   registers' valid bits; their data registers have no reset).
module rc_fp_pool #(
  parameter int unsigned  ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned  FracW  = rc_pkg::Fp24FracW,
  parameter bit           Add    = 1'b0,
  parameter int unsigned  Users  = 2,
  parameter logic [31:0]  Sub    = '0,
  parameter int unsigned  Period = 6,
  parameter logic [511:0] Time   = '0,
  parameter logic [63:0]  Cycles = {32{2'd1}},
  parameter bit           InReg  = 1'b0,
  // Derived (do not override).
  parameter int unsigned  W      = 1 + ExpW + FracW
) (
  input  logic               clk_i,
  input  logic               rst_ni,
  input  logic [Users-1:0]   issue_i,
  input  logic [Users*W-1:0] a_i,
  input  logic [Users*W-1:0] b_i,
  output logic [Users-1:0]   valid_o,
  output logic [Users*W-1:0] res_o
);

  localparam int unsigned MaxOps = 32;

  // The phases (modulo Period) user k occupies.
  function automatic logic [15:0] occupied(input int unsigned k);
    occupied = '0;
    for (int unsigned j = 0; j < 3; j++) begin
      if (j < 32'(Cycles[2*k +: 2])) occupied[(32'(Time[16*k +: 16]) + j) % Period] = 1'b1;
    end
  endfunction

  // Each user's operator, user k's at [5k +: 5]: first fit, the users taken by decreasing
  // Cycles, then by increasing phase (Time mod Period), then by index.
  function automatic logic [5*32-1:0] placement();
    logic [16*MaxOps-1:0] taken;  // operator j's occupied phases at [16j +: 16]
    logic                 placed;
    taken     = '0;
    placement = '0;
    for (int unsigned c = 3; c >= 1; c--) begin
      for (int unsigned ph = 0; ph < Period; ph++) begin
        for (int unsigned k = 0; k < Users; k++) begin
          if (32'(Cycles[2*k +: 2]) == c && 32'(Time[16*k +: 16]) % Period == ph) begin
            placed = 1'b0;
            for (int unsigned j = 0; j < MaxOps; j++) begin
              if (!placed && (taken[16*j +: 16] & occupied(k)) == '0) begin
                taken[16*j +: 16]  = taken[16*j +: 16] | occupied(k);
                placement[5*k +: 5] = 5'(j);
                placed             = 1'b1;
              end
            end
          end
        end
      end
    end
  endfunction

  localparam logic [5*32-1:0] Place = placement();

  // The operators the placement takes.
  function automatic int unsigned ops_needed();
    ops_needed = 1;
    for (int unsigned k = 0; k < Users; k++) begin
      if (32'(Place[5*k +: 5]) + 1 > ops_needed) ops_needed = 32'(Place[5*k +: 5]) + 1;
    end
  endfunction

  // Bit k: user k is on operator j.
  function automatic logic [Users-1:0] users_of(input int unsigned j);
    for (int unsigned k = 0; k < Users; k++) users_of[k] = (32'(Place[5*k +: 5]) == j);
  endfunction

  // The lowest user on operator j.
  function automatic int unsigned first_of(input int unsigned j);
    first_of = 0;
    for (int unsigned k = Users; k > 0; k--) begin
      if (32'(Place[5*(k-1) +: 5]) == j) first_of = k - 1;
    end
  endfunction

  // Every user issues in 1 to 3 cycles.
  function automatic bit cycles_ok();
    cycles_ok = 1'b1;
    for (int unsigned k = 0; k < Users; k++) begin
      if (Cycles[2*k +: 2] == 2'd0) cycles_ok = 1'b0;
    end
  endfunction

  localparam int unsigned Ops = ops_needed();

  if (Users < 1 || Users > 32 || Period < 3 || Period > 16 || !cycles_ok()) begin : g_param_check
    $error("rc_fp_pool: Users must be 1 to 32, Period 3 to 16 and every user's Cycles 1 to 3");
  end

  logic [Ops-1:0]   op_valid;
  logic [Ops*W-1:0] op_res;

  for (genvar j = 0; j < Ops; j++) begin : g_op
    localparam logic [Users-1:0] Mine = users_of(j);
    logic [W-1:0] a, b;
    logic         sub, issue;
    assign issue = |(issue_i & Mine);
    localparam int unsigned First = first_of(j);
    always_comb begin
      a   = a_i[First*W +: W];
      b   = b_i[First*W +: W];
      sub = Sub[First];
      for (int unsigned k = First + 1; k < Users; k++) begin
        if (Mine[k] && issue_i[k]) begin
          a   = a_i[k*W +: W];
          b   = b_i[k*W +: W];
          sub = Sub[k];
        end
      end
    end

    // The operator's inputs: the select's, or (InReg) the input register's.
    logic [W-1:0] op_a, op_b;
    logic         op_sub, op_issue;
    if (InReg) begin : g_in_reg
      logic [W-1:0] a_q, b_q;
      logic         sub_q, issue_q;
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) issue_q <= 1'b0;
        else issue_q <= issue;
      end
      always_ff @(posedge clk_i) begin
        a_q   <= a;
        b_q   <= b;
        sub_q <= sub;
      end
      assign {op_a, op_b, op_sub, op_issue} = {a_q, b_q, sub_q, issue_q};
    end else begin : g_no_in_reg
      assign {op_a, op_b, op_sub, op_issue} = {a, b, sub, issue};
    end

    if (Add) begin : g_add
      rc_fp_add #(.ExpW(ExpW), .FracW(FracW), .Stages(rc_pkg::FpStagesAdd)) u_add (
        .clk_i, .rst_ni, .valid_i(op_issue), .sub_i(op_sub), .a_i(op_a), .b_i(op_b),
        .valid_o(op_valid[j]), .res_o(op_res[j*W +: W])
      );
    end else begin : g_mul
      logic unused_sub;
      assign unused_sub = op_sub;
      rc_fp_mul #(.ExpW(ExpW), .FracW(FracW), .Stages(rc_pkg::FpStagesMul)) u_mul (
        .clk_i, .rst_ni, .valid_i(op_issue), .a_i(op_a), .b_i(op_b), .valid_o(op_valid[j]),
        .res_o(op_res[j*W +: W])
      );
    end

`ifndef SYNTHESIS
    logic checks_on;
    rc_checks_on u_checks_on (
      .clk_i,
      .rst_ni,
      .on_o (checks_on)
    );
    // One user of an operator at a time: the placement gave them disjoint phases.
    OneUser_A: assert property (@(posedge clk_i) disable iff (checks_on !== 1'b1)
                                $onehot0(issue_i & Mine));
`endif
  end

  for (genvar k = 0; k < Users; k++) begin : g_user
    localparam int unsigned Op = 32'(Place[5*k +: 5]);
    assign valid_o[k]      = op_valid[Op];
    assign res_o[k*W +: W] = op_res[Op*W +: W];
  end

endmodule
