#!/usr/bin/env python3
"""Checks that every signal a GTKWave save file of tb/waves/ names exists in a real trace.

Usage: check_gtkw.py RAYCORE WORK_DIR SAVE_FILE...

Renders a tiny frame of scenes/default.json through the verilated core with an FST trace
(raycore render --engine rtl --trace), lists the trace's signals with fst2vcd (GTKWave's), and
fails naming every signal of the save files that the trace does not have: a save file that went
stale after a change to the RTL or to the default parameters.
"""
import pathlib
import re
import subprocess
import sys


def trace_signals(vcd_text):
    """Full dotted names (with their bit ranges) of every variable in a VCD header."""
    scopes, names = [], set()
    for line in vcd_text.splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "$scope":
            scopes.append(parts[2])
        elif parts[0] == "$upscope":
            scopes.pop()
        elif parts[0] == "$var":
            name = parts[4]
            if len(parts) > 5 and parts[5].startswith("["):
                name += parts[5]
            names.add(".".join(scopes + [name]))
        elif parts[0] == "$enddefinitions":
            break
    return names


def main():
    if len(sys.argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    raycore, work = sys.argv[1], pathlib.Path(sys.argv[2])
    root = pathlib.Path(__file__).resolve().parents[2]
    work.mkdir(parents=True, exist_ok=True)
    fst = work / "gtkw_check.fst"
    subprocess.run([raycore, "render", str(root / "scenes/default.json"), "--engine", "rtl",
                    "--size", "8x6", "-q", "-o", str(work / "gtkw_check.png"), "--trace", str(fst),
                    "--trace-window", "0:20"], check=True)
    vcd = subprocess.run(["fst2vcd", str(fst)], check=True, capture_output=True, text=True).stdout
    have = trace_signals(vcd)
    missing, checked = [], 0
    for save in sys.argv[3:]:
        for line in pathlib.Path(save).read_text().splitlines():
            if re.match(r"^[A-Za-z_]\w*\.", line):
                checked += 1
                if line.strip() not in have:
                    missing.append(f"{save}: {line.strip()}")
    print(f"[cases] GTKWave save files: {checked} signals checked against a trace, "
          f"{len(missing)} missing")
    for m in missing:
        print(f"  not in the trace: {m}")
    return 1 if missing or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
