#!/usr/bin/env python3
"""Synthesize each arithmetic unit with Yosys synth_ecp5 and print its utilisation.

Usage: synth_units.py --build BUILD_DIR [--units A,B] [--markdown] [--param NAME=VALUE ...] RTL_FILE...

For every unit in UNITS (or --units, e.g. --units rc_core for the whole core) this runs `yosys synth_ecp5 -top <unit>` on the given RTL files (the file
list of rtl/rtl_files.f) at its default parameters (fp24), reads `stat -json`, and prints LUT4s,
flip-flops, 18x18 multipliers, carry cells and block RAMs. Logs and JSON go to BUILD_DIR/synth/.
Exits non-zero when Yosys fails or reports a latch.
"""
import argparse
import json
import pathlib
import subprocess
import sys
import time

UNITS = ["rc_fp_add", "rc_fp_mul", "rc_fp_div", "rc_fp_cmp"]
COLUMNS = [  # (heading, cell types counted)
    ("LUT4", ["LUT4"]),
    ("flip-flops", ["TRELLIS_FF"]),
    ("MULT18X18D", ["MULT18X18D"]),
    ("carry (CCU2C)", ["CCU2C"]),
    ("wide muxes (PFUMX, L6MUX21)", ["PFUMX", "L6MUX21"]),
    ("block RAM (DP16KD)", ["DP16KD"]),
]


def synth(unit, files, out_dir, params):
    log = out_dir / f"{unit}.log"
    stat = out_dir / f"{unit}.stat.json"
    chparams = "".join(f"chparam -set {k} {v} {unit}; " for k, v in params)
    script = (f"read_verilog -sv {' '.join(files)}; {chparams}"
              f"synth_ecp5 -top {unit}; tee -q -o {stat} stat -json")
    start = time.monotonic()
    res = subprocess.run(["yosys", "-l", str(log), "-q", "-p", script],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
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
    # synth_ecp5 flattens the design, so the design-wide totals are the unit's
    return {"cells": data["design"]["num_cells_by_type"], "seconds": seconds}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    ap.add_argument("--param", action="append", default=[], help="NAME=VALUE for every unit")
    ap.add_argument("--units", default=",".join(UNITS), help="comma-separated top modules")
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    params = [p.split("=", 1) for p in args.param]
    out_dir = pathlib.Path(args.build) / "synth"
    out_dir.mkdir(parents=True, exist_ok=True)

    rows = []
    for unit in [u for u in args.units.split(",") if u]:
        result = synth(unit, args.files, out_dir, params)
        if result is None:
            return 1
        counts = [sum(result["cells"].get(c, 0) for c in types) for _, types in COLUMNS]
        rows.append((unit, counts, result["seconds"]))

    heads = ["unit"] + [h for h, _ in COLUMNS] + ["yosys s"]
    table = [[u] + [str(c) for c in counts] + [f"{s:.1f}"] for u, counts, s in rows]
    if args.markdown:
        print("| " + " | ".join(heads) + " |")
        print("|" + "---|" * len(heads))
        for r in table:
            print("| " + " | ".join(r) + " |")
    else:
        widths = [max(len(h), *(len(r[i]) for r in table)) for i, h in enumerate(heads)]
        print("  ".join(h.rjust(w) for h, w in zip(heads, widths)))
        for r in table:
            print("  ".join(c.rjust(w) for c, w in zip(r, widths)))
    # The share of the ECP5 LFE5U-85F (ULX3S): 83,640 LUT4 and flip-flops, 156 MULT18X18D, 208 DP16KD.
    device = {"LUT4": 83640, "flip-flops": 83640, "MULT18X18D": 156, "block RAM (DP16KD)": 208}
    for unit, counts, _ in rows:
        shares = [f"{h} {100.0 * c / device[h]:.1f}%" for (h, _), c in zip(COLUMNS, counts)
                  if h in device]
        print(f"{unit} on the LFE5U-85F: " + ", ".join(shares))
    print(f"(Yosys synth_ecp5, default parameters{', ' if params else ''}"
          f"{', '.join(f'{k}={v}' for k, v in params)}; logs in {out_dir})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
