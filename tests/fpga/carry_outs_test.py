#!/usr/bin/env python3
"""fpga/carry_outs.py: which CCU2C carry-outs it cuts, on hand-made Yosys JSON netlists.

Cases: a chain's last COUT that nothing reads (cut), a COUT that feeds the next CCU2C's CIN
(kept), a COUT that a LUT reads (a compare's result, kept), a COUT on a module output (kept), a
COUT read by a cell whose port directions the netlist does not give (kept: every port counts as
a reader), a COUT already unconnected (left alone), a COUT only a net name names (cut), a
second module (its own readers), and the
command line on a good file, an unreadable file and a file that is not a netlist.

The fold of constant carry-ins: the folded INIT0 of an adder's and a subtracter's first cell
with carry-in 0 and 1 against the carries of a + b + c and a + ~b + c worked out by hand; cells
that must not fold (first sum read, C0 a signal, carry-in a signal); and a proof with Yosys's own
ECP5 cell model (share/yosys/ecp5/cells_sim.v): 300 cells of random INIT0, INIT1, INJECT1_0/1,
constant carry-in, C0 and D0, written as Verilog before and after the fold, and `sat -prove`
that every S1 and COUT is the same for every input and every value of the folded cells' free
carry-in. A mutant (one folded cell's INIT0 with a wrong bit) must fail that proof. Needs
Debian's yosys (make deps), not YoWASP.
"""
import copy
import json
import pathlib
import random
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "fpga"))
from carry_outs import cut_unused_carry_outs, fold_constant_carry_ins  # noqa: E402

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

# --- The fold of constant carry-ins. ---
ALL_DIRS = {p: "input" for p in ("CIN", "A0", "B0", "C0", "D0", "A1", "B1", "C1", "D1")}
ALL_DIRS.update({"S0": "output", "S1": "output", "COUT": "output"})


def full_ccu(n, init0, init1, inj0, inj1, cin, c0, d0, s0=None):
    """CCU2C number n: inputs A0..D1 on bits 2..7 (C0, D0 as given), outputs on 100 + 3n..."""
    return {"type": "CCU2C", "port_directions": ALL_DIRS,
            "parameters": {"INIT0": format(init0, "016b"), "INIT1": format(init1, "016b"),
                           "INJECT1_0": inj0, "INJECT1_1": inj1},
            "connections": {"CIN": [cin], "A0": [2], "B0": [3], "C0": [c0], "D0": [d0],
                            "A1": [4], "B1": [5], "C1": [6], "D1": [7],
                            "S0": [s0 if s0 is not None else 100 + 3 * n],
                            "S1": [101 + 3 * n], "COUT": [102 + 3 * n]}}


def one_module(cells, outputs, extra_ports=None):
    ports = {"x": {"direction": "input", "bits": [2, 3, 4, 5, 6, 7, 8]},
             "y": {"direction": "output", "bits": outputs}}
    ports.update(extra_ports or {})
    return {"modules": {"top": {"ports": ports, "cells": cells}}}


def init0_of(n, name):
    return int(n["modules"]["top"]["cells"][name]["parameters"]["INIT0"], 2)


# An adder's first cell (Yosys's ECP5 ALU: INIT0 0x96AA, C0 = BI, D0 = 1): with BI = 0 its LUT4
# is a ^ b, with BI = 1 a ^ ~b, so its carry-out is that of a + b + c or a + ~b + c.
cells = {
    "add0": full_ccu(0, 0x96AA, 0x96AA, "NO", "NO", "0", "0", "1"),   # a & b: 0x8
    "add1": full_ccu(1, 0x96AA, 0x96AA, "NO", "NO", "1", "0", "1"),   # a | b: 0xE
    "sub0": full_ccu(2, 0x96AA, 0x96AA, "NO", "NO", "0", "1", "1"),   # a & ~b: 0x2
    "sub1": full_ccu(3, 0x96AA, 0x96AA, "NO", "NO", "1", "1", "1"),   # a | ~b: 0xB
    # Not folded: S0 read (by the module output), C0 a signal, CIN a signal.
    "read": full_ccu(4, 0x96AA, 0x96AA, "NO", "NO", "0", "0", "1"),
    "c0sig": full_ccu(5, 0x96AA, 0x96AA, "NO", "NO", "0", 8, "1"),
    "cinsig": full_ccu(6, 0x96AA, 0x96AA, "NO", "NO", 8, "0", "1"),
}
n = one_module(cells, [112])  # bit 112: "read"'s S0
folded = fold_constant_carry_ins(n)
check(folded == 4, f"folded {folded} carry-ins, expected 4 (add0, add1, sub0, sub1)")
for name, want in (("add0", 0x8), ("add1", 0xE), ("sub0", 0x2), ("sub1", 0xB)):
    got = init0_of(n, name)
    check(got == want, f"{name}: folded INIT0 {got:#06x}, expected {want:#06x}")
    con = n["modules"]["top"]["cells"][name]["connections"]
    check(con["CIN"] == ["x"] and con["S0"] == ["x"] and con["C0"] == ["1"] and
          con["D0"] == ["1"], f"{name}: CIN and S0 disconnected, C0 and D0 tied to 1: {con}")
for name in ("read", "c0sig", "cinsig"):
    check(init0_of(n, name) == 0x96AA and
          n["modules"]["top"]["cells"][name]["connections"]["CIN"] != ["x"],
          f"{name} is not folded")


def verilog(netlist, name):
    """The module's CCU2C cells as Verilog over x[6:0] and a free carry-in k; y: S1, COUT."""
    cells = netlist["modules"]["top"]["cells"]
    lines = [f"module {name}(input [6:0] x, input k, output [{2 * len(cells) - 1}:0] y);"]
    for i, (cname, c) in enumerate(sorted(cells.items())):
        p, con = c["parameters"], c["connections"]

        def sig(port):
            b = con[port][0]
            if b in ("0", "1"):
                return f"1'b{b}"
            if b == "x":
                return "k"
            return f"x[{b - 2}]"
        ins = ", ".join(f".{q}({sig(q)})" for q in
                        ("CIN", "A0", "B0", "C0", "D0", "A1", "B1", "C1", "D1"))
        lines.append(f"  CCU2C #(.INIT0(16'b{p['INIT0']}), .INIT1(16'b{p['INIT1']}), "
                     f".INJECT1_0(\"{p['INJECT1_0']}\"), .INJECT1_1(\"{p['INJECT1_1']}\")) "
                     f"u_{i}({ins}, .S0(), .S1(y[{2 * i}]), .COUT(y[{2 * i + 1}]));")
    lines.append("endmodule")
    return "\n".join(lines) + "\n"


def prove(gold, gate, d, tag):
    """Yosys: gold's and gate's outputs equal for every x and k; True when proven."""
    src = pathlib.Path(d) / f"{tag}.v"
    width = 2 * len(gold["modules"]["top"]["cells"])
    src.write_text(verilog(gold, "gold") + verilog(gate, "gate") +
                   "module m(input [6:0] x, input k, output ok);\n"
                   f"  wire [{width - 1}:0] a, b;\n  gold g(.x(x), .k(1'b0), .y(a));\n"
                   "  gate n(.x(x), .k(k), .y(b));\n  assign ok = a == b;\nendmodule\n")
    r = subprocess.run(["yosys", "-q", "-l", str(pathlib.Path(d) / f"{tag}.log"), "-p",
                        f"read_verilog -D NO_INCLUDES +/ecp5/cells_sim.v; read_verilog {src}; "
                        "hierarchy -top m; proc; flatten; opt_clean; sat -prove ok 1 -verify"],
                       capture_output=True, text=True)
    return r.returncode == 0


rng = random.Random(26)
gold = one_module({f"r{i:03d}": full_ccu(i, rng.getrandbits(16), rng.getrandbits(16),
                                         rng.choice(("YES", "NO")), rng.choice(("YES", "NO")),
                                         rng.choice("01"), rng.choice("01"), rng.choice("01"))
                   for i in range(300)}, [])
gate = copy.deepcopy(gold)
folded = fold_constant_carry_ins(gate)
check(folded == 300, f"folded {folded} of the 300 random cells (all have unread S0)")
with tempfile.TemporaryDirectory() as d:
    check(prove(gold, gate, d, "fold"), "Yosys proves the 300 folded cells equal to the originals "
          "(S1, COUT for every input and free carry-in)")
    # The mutant: the first cell whose folded carry matters (the second half passes it on:
    # INJECT1_1 "NO" and a LUT4 that is 1 somewhere) with one INIT0 bit flipped.
    bad = copy.deepcopy(gate)
    for name, c in sorted(bad["modules"]["top"]["cells"].items()):
        if c["parameters"]["INJECT1_1"] == "NO" and int(c["parameters"]["INIT1"], 2) != 0:
            c["parameters"]["INIT0"] = format(int(c["parameters"]["INIT0"], 2) ^ 1, "016b")
            break
    check(not prove(gold, bad, d, "mutant"), "Yosys refutes a folded cell with a wrong INIT0 bit")

print(f"carry_outs_test: {count - len(failures)} of {count} checks passed")
sys.exit(1 if failures else 0)
