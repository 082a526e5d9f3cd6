// MULT18X18D: simulation model of the ECP5 18x18 multiplier, for the netlist tests only.
//
// Contract
// - Yosys 0.23 ships MULT18X18D as a black box only (share/yosys/ecp5/cells_bb.v); its
//   ecp5/cells_sim.v has models of every other cell synth_ecp5 emits. This models the one
//   configuration synth_ecp5 produces (ecp5/dsp_map.v): no input, pipeline or output registers
//   (every REG_*_CLK "NONE", checked at elaboration), C and SOURCEA/SOURCEB tied to 0, so the
//   primitive is the combinational product P = A * B, each operand two's complement when its
//   SIGNEDA/SIGNEDB is 1 and unsigned otherwise.
// - Ports: those dsp_map.v connects, with the vendor's names (a netlist connecting any other port
//   fails to elaborate, which is the intent). Handshake, clock and reset: none.
// - Illegal input: SOURCEA or SOURCEB = 1 (cascade inputs, never used by dsp_map.v): P is X.
module MULT18X18D #(
  parameter REG_INPUTA_CLK   = "NONE",
  parameter REG_INPUTA_CE    = "CE0",
  parameter REG_INPUTA_RST   = "RST0",
  parameter REG_INPUTB_CLK   = "NONE",
  parameter REG_INPUTB_CE    = "CE0",
  parameter REG_INPUTB_RST   = "RST0",
  parameter REG_INPUTC_CLK   = "NONE",
  parameter REG_INPUTC_CE    = "CE0",
  parameter REG_INPUTC_RST   = "RST0",
  parameter REG_PIPELINE_CLK = "NONE",
  parameter REG_PIPELINE_CE  = "CE0",
  parameter REG_PIPELINE_RST = "RST0",
  parameter REG_OUTPUT_CLK   = "NONE",
  parameter REG_OUTPUT_CE    = "CE0",
  parameter REG_OUTPUT_RST   = "RST0",
  parameter CLK0_DIV         = "ENABLED",
  parameter CLK1_DIV         = "ENABLED",
  parameter CLK2_DIV         = "ENABLED",
  parameter CLK3_DIV         = "ENABLED",
  parameter HIGHSPEED_CLK    = "NONE",
  parameter GSR              = "ENABLED",
  parameter CAS_MATCH_REG    = "FALSE",
  parameter SOURCEB_MODE     = "B_SHIFT",
  parameter MULT_BYPASS      = "DISABLED",
  parameter RESETMODE        = "SYNC"
) (
  input  A0, A1, A2, A3, A4, A5, A6, A7, A8, A9, A10, A11, A12, A13, A14, A15, A16, A17,
  input  B0, B1, B2, B3, B4, B5, B6, B7, B8, B9, B10, B11, B12, B13, B14, B15, B16, B17,
  input  C0, C1, C2, C3, C4, C5, C6, C7, C8, C9, C10, C11, C12, C13, C14, C15, C16, C17,
  input  SIGNEDA, SIGNEDB, SOURCEA, SOURCEB,
  output P0, P1, P2, P3, P4, P5, P6, P7, P8, P9, P10, P11, P12, P13, P14, P15, P16, P17,
  output P18, P19, P20, P21, P22, P23, P24, P25, P26, P27, P28, P29, P30, P31, P32, P33, P34, P35
);

  if (REG_INPUTA_CLK != "NONE" || REG_INPUTB_CLK != "NONE" || REG_INPUTC_CLK != "NONE" ||
      REG_PIPELINE_CLK != "NONE" || REG_OUTPUT_CLK != "NONE") begin : g_unsupported
    $error("MULT18X18D sim model: only the unregistered configuration is modelled");
  end

  wire [17:0] a = {A17, A16, A15, A14, A13, A12, A11, A10, A9, A8, A7, A6, A5, A4, A3, A2, A1, A0};
  wire [17:0] b = {B17, B16, B15, B14, B13, B12, B11, B10, B9, B8, B7, B6, B5, B4, B3, B2, B1, B0};
  // The product of the operands extended to 36 bits (sign or zero) is exact modulo 2^36, and
  // every 18x18 product (signed, unsigned or mixed) fits 36 bits.
  wire [35:0] a_ext = {{18{SIGNEDA & a[17]}}, a};
  wire [35:0] b_ext = {{18{SIGNEDB & b[17]}}, b};
  wire [35:0] p = (SOURCEA | SOURCEB) ? {36{1'bx}} : a_ext * b_ext;

  assign {P35, P34, P33, P32, P31, P30, P29, P28, P27, P26, P25, P24, P23, P22, P21, P20, P19,
          P18, P17, P16, P15, P14, P13, P12, P11, P10, P9, P8, P7, P6, P5, P4, P3, P2, P1, P0} = p;

endmodule
