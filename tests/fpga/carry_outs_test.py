#!/usr/bin/env python3
"""fpga/carry_outs.py: which CCU2C carry-outs it cuts, on hand-made Yosys JSON netlists.

Cases: a chain's last COUT that nothing reads (cut), a COUT that feeds the next CCU2C's CIN
(kept), a COUT that a LUT reads (a compare's result, kept), a COUT on a module output (kept), a
COUT read by a cell whose port directions the netlist does not give (kept: every port counts as
a reader), a COUT already unconnected (left alone), a COUT only a net name names (cut), a
second module (its own readers), and the
command line on a good file, an unreadable file and a file that is not a netlist. No YoWASP
needed.
"""
import json
import pathlib
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "fpga"))
from carry_outs import cut_unused_carry_outs  # noqa: E402

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "fpga" / "carry_outs.py"
CCU_DIRS = {"CIN": "input", "A0": "input", "B0": "input", "A1": "input", "B1": "input",
            "S0": "output", "S1": "output", "COUT": "output"}
LUT_DIRS = {"A": "input", "B": "input", "C": "input", "D": "input", "Z": "output"}

failures = []
count = 0


def check(cond, what):
    global count
    count += 1
    if not cond:
        failures.append(what)
        print(f"carry_outs_test: FAIL: {what}")


def ccu(cin, cout, s0, s1):
    return {"type": "CCU2C", "port_directions": CCU_DIRS,
            "connections": {"CIN": [cin], "A0": [2], "B0": [3], "A1": [4], "B1": [5],
                            "S0": [s0], "S1": [s1], "COUT": [cout]}}


def lut(a, z):
    return {"type": "LUT4", "port_directions": LUT_DIRS,
            "connections": {"A": [a], "B": ["0"], "C": ["0"], "D": ["0"], "Z": [z]}}


def netlist():
    # Bits 2..5 are inputs; 10.. are internal.
    top = {
        "ports": {"a": {"direction": "input", "bits": [2, 3, 4, 5]},
                  "y": {"direction": "output", "bits": [40, 41, 52]}},
        "cells": {
            # A two-cell sum chain: c0's COUT feeds c1's CIN (kept); c1's COUT is read by
            # nothing (cut).
            "c0": ccu("0", 20, 40, 41),
            "c1": ccu(20, 21, 42, 43),
            # A compare: c2's COUT is read by a LUT (kept).
            "c2": ccu("1", 30, 44, 45),
            "l0": lut(30, 46),
            # A COUT on the module's output port (kept).
            "c3": ccu("1", 52, 47, 48),
            # A COUT read by a cell of unknown directions (kept).
            "c4": ccu("0", 60, 49, 50),
            "u0": {"type": "MYSTERY", "connections": {"P": [60]}},
            # Already unconnected (left as it is).
            "c5": ccu("0", "x", 51, 53),
            # A COUT that only a net name names: names do not read (cut).
            "c6": ccu("0", 70, 54, 55),
        },
        "netnames": {"unused_cout": {"bits": [21]}, "named_cout": {"bits": [70]}},
    }
    other = {
        "ports": {},
        "cells": {"d0": ccu("0", 20, 10, 11), "l2": lut(20, 12)},
    }
    return {"modules": {"top": top, "other": other,
                        "CCU2C": {"attributes": {"blackbox": 1}, "ports": {}, "cells": {}}}}


def cout(n, module, cell):
    return n["modules"][module]["cells"][cell]["connections"]["COUT"]


n = netlist()
cut = cut_unused_carry_outs(n)
check(cut == 2, f"cut {cut} carry-outs, expected 2 (c1 and c6)")
check(cout(n, "top", "c1") == ["x"], "c1's unused COUT is cut")
check(cout(n, "top", "c6") == ["x"], "c6's unused COUT is cut")
check(cout(n, "top", "c0") == [20], "c0's COUT feeds c1's CIN and is kept")
check(cout(n, "top", "c2") == [30], "c2's COUT read by a LUT is kept")
check(cout(n, "top", "c3") == [52], "c3's COUT on a module output is kept")
check(cout(n, "top", "c4") == [60], "c4's COUT read by a cell of unknown directions is kept")
check(cout(n, "top", "c5") == ["x"], "c5's unconnected COUT stays unconnected")
check(cout(n, "other", "d0") == [20], "bit 20 is read in module other (bits are per module)")
check(n["modules"]["top"]["cells"]["c1"]["connections"]["S1"] == [43],
      "the other ports of a cut cell are untouched")
again = cut_unused_carry_outs(n)
check(again == 0, f"a second pass cuts {again}, expected 0")

with tempfile.TemporaryDirectory() as d:
    src = pathlib.Path(d) / "in.json"
    dst = pathlib.Path(d) / "out.json"
    src.write_text(json.dumps(netlist()))
    r = subprocess.run([sys.executable, str(SCRIPT), str(src), str(dst)], capture_output=True,
                       text=True)
    check(r.returncode == 0 and "2 unused carry-outs cut" in r.stdout,
          f"command line: exit {r.returncode}, output {r.stdout!r} {r.stderr!r}")
    check(json.loads(src.read_text()) == netlist(), "the input file is not changed")
    out = json.loads(dst.read_text()) if dst.exists() else {}
    check(out.get("modules", {}).get("top", {}).get("cells", {}).get("c1", {})
          .get("connections", {}).get("COUT") == ["x"], "the output file has c1's COUT cut")
    r = subprocess.run([sys.executable, str(SCRIPT), str(pathlib.Path(d) / "missing.json"),
                        str(dst)], capture_output=True, text=True)
    check(r.returncode == 1 and "cannot read" in r.stderr,
          f"a missing file: exit {r.returncode}, {r.stderr!r}")
    bad = pathlib.Path(d) / "bad.json"
    bad.write_text('{"creator": "not a netlist"}')
    r = subprocess.run([sys.executable, str(SCRIPT), str(bad), str(dst)], capture_output=True,
                       text=True)
    check(r.returncode == 1 and "not a Yosys JSON netlist" in r.stderr,
          f"a file that is not a netlist: exit {r.returncode}, {r.stderr!r}")
    bad.write_text('{"modules": ')
    r = subprocess.run([sys.executable, str(SCRIPT), str(bad), str(dst)], capture_output=True,
                       text=True)
    check(r.returncode == 1 and "cannot read" in r.stderr,
          f"a truncated file: exit {r.returncode}, {r.stderr!r}")

print(f"carry_outs_test: {count - len(failures)} of {count} checks passed")
sys.exit(1 if failures else 0)
