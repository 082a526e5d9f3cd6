// rc_fp_shared: one rc_fp_mul (or rc_fp_add) that several users of a component-serial unit
// (rc_hit_geom, rc_ray_gen) take turns on, each at its own fixed times of the owner's job
// schedule: an rc_fp_pool whose users are checked at elaboration to need only one operator.
//
// Contract
// - Function: in a cycle with issue_i[k] set, user k's operands a_i[k], b_i[k] enter the operator
//   (Add: a - b where Sub[k] is set, a + b elsewhere); res_o and valid_o are the operator's, Stages
//   cycles later (rc_fp_mul or rc_fp_add, bit for bit). No user is told which result is its own:
//   each reads res_o at its own time, Stages cycles after its issue.
// - Sharing: the owner takes its jobs at phase 0 modulo Period (rc_serial_sched, Phased), so user
//   k issues at phase Time[k] mod Period and the next Cycles[k] - 1 phases (3 for a vector's x, y
//   and z in consecutive cycles). The users' phases must be disjoint: checked at
//   elaboration (an $error naming the clash), and issue_i must be one-hot or zero in every cycle
//   (rc_fp_pool's assertion).
// - Select: user 0's operands unless another user issues (a chain of two-way selects), so an idle
//   cycle's operands are user 0's and mean nothing.
// - Parameters: ExpW, FracW (the format); Add (0: rc_fp_mul, 1: rc_fp_add); Users (2 to 8); Sub
//   (Add only: bit k, user k subtracts); Period (the owner's cycles per job, 3 to 16); Time: user
//   k's issue time (after the job's slot 0) in bits [16k +: 16]; Cycles: bits [2k +: 2], the
//   consecutive cycles user k issues in (1 to 3). The stages are the package's ([fp_stages]), as
//   in the owners.
// - Reset: rst_ni (active low, asynchronous) clears the operator's valid pipeline.
module rc_fp_shared #(
  parameter int unsigned  ExpW   = rc_pkg::Fp24ExpW,
  parameter int unsigned  FracW  = rc_pkg::Fp24FracW,
  parameter bit           Add    = 1'b0,
  parameter int unsigned  Users  = 2,
  parameter logic [7:0]   Sub    = '0,
  parameter int unsigned  Period = 6,
  parameter logic [127:0] Time   = 128'h1_0000,
  parameter logic [15:0]  Cycles = 16'h5555,
  // Derived (do not override).
  parameter int unsigned  W      = 1 + ExpW + FracW
) (
  input  logic               clk_i,
  input  logic               rst_ni,
  input  logic [Users-1:0]   issue_i,
  input  logic [Users*W-1:0] a_i,
  input  logic [Users*W-1:0] b_i,
  output logic               valid_o,
  output logic [W-1:0]       res_o
);

  // The phases (modulo Period) user k occupies.
  function automatic logic [15:0] occupied(input int unsigned k);
    occupied = '0;
    for (int unsigned j = 0; j < 3; j++) begin
      if (j < 32'(Cycles[2*k +: 2])) occupied[(32'(Time[16*k +: 16]) + j) % Period] = 1'b1;
    end
  endfunction

  // The first user whose phases meet an earlier user's (Users when none does).
  function automatic int unsigned first_clash();
    logic [15:0] seen;
    seen        = '0;
    first_clash = Users;
    for (int unsigned k = 0; k < Users; k++) begin
      if (first_clash == Users && (seen & occupied(k)) != '0) first_clash = k;
      seen = seen | occupied(k);
    end
  endfunction

  // Every user issues in 1 to 3 cycles.
  function automatic bit cycles_ok();
    cycles_ok = 1'b1;
    for (int unsigned k = 0; k < Users; k++) begin
      if (Cycles[2*k +: 2] == 2'd0) cycles_ok = 1'b0;
    end
  endfunction

  if (Users < 2 || Users > 8 || Period < 3 || Period > 16 || !cycles_ok()) begin : g_param_check
    $error("rc_fp_shared: Users must be 2 to 8, Period 3 to 16 and every user's Cycles 1 to 3");
  end
  if (first_clash() != Users) begin : g_phase_check
    $error("rc_fp_shared: user %0d issues at a phase modulo %0d that an earlier user takes",
           first_clash(), Period);
  end

  // The operator: an rc_fp_pool whose users the check above has shown to fit on one, so its
  // placement takes exactly one (every user's result is that operator's).
  logic [Users-1:0]   pool_valid;
  logic [Users*W-1:0] pool_res;
  logic               unused_pool;  // the other users' copies of the one result
  rc_fp_pool #(
    .ExpW(ExpW), .FracW(FracW), .Add(Add), .Users(Users), .Sub(32'(Sub)), .Period(Period),
    .Time(512'(Time)), .Cycles(64'(Cycles))
  ) u_pool (
    .clk_i, .rst_ni, .issue_i, .a_i, .b_i, .valid_o(pool_valid), .res_o(pool_res)
  );
  assign valid_o = pool_valid[0];
  assign res_o   = pool_res[0 +: W];
  assign unused_pool = ^{pool_valid[Users-1:1], pool_res[Users*W-1:W]};

endmodule
