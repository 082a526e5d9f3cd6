#!/usr/bin/env python3
"""Rank the register-to-register paths of a synthesized ECP5 netlist by estimated delay.

Usage: logic_depth.py NETLIST.json [--top N] [--paths K] [--markdown]

NETLIST.json is a flattened `synth_ecp5` netlist (Yosys `write_json`; `make synth-core` writes
BUILD/synth/rc_core.json). The script walks the combinational cells (LUT4, PFUMX, L6MUX21, CCU2C,
the asynchronous read of TRELLIS_DPR16X4, MULT18X18D) from every start point (flip-flop outputs,
block RAM read data and the module's inputs) to every end point (flip-flop D/M/CE/LSR, distributed-RAM write data,
address and enable) with a fixed delay per cell arc and per routed net (below), and prints the
slowest end points, one line per register or RAM (the worst bit), with the start point and the
named signals the worst path passes through.

This is an estimate for finding deep logic in minutes instead of a place-and-route run: the cell
delays are rough ECP5 (speed grade 6) figures and every general net costs the same NET_NS, while
real routing depends on placement and congestion (nextpnr's routed paths in `make fpga-ecp5` have
been 1.5 to 2.5 times these estimates). The ranking, not the absolute figure, is the point.
"""
import argparse
import collections
import json
import re
import sys

NET_NS = 0.55  # one general routed net
FF_CLK_TO_Q_NS = 0.3
# A block RAM's registered read data (DP16KD DO*): nextpnr's clock-to-out for the LFE5U-85F, speed
# grade 6 (5.83 ns in run 13's routed critical path, docs/history.md), far above a flip-flop's.
# Yosys merges a register behind an asynchronously read memory into the block RAM's read port, so
# a register the RTL places after a memory can start its paths 5.8 ns late.
BRAM_CLK_TO_Q_NS = 5.8
FF_SETUP_NS = 0.1
# Per cell type: (input port pattern, output port pattern, delay in ns). A pattern matches the
# port name with an optional bit number (DPR16X4 and MULT18X18D have one port per bit).
ARCS = {
    "LUT4": [(p, "Z", 0.4) for p in "ABCD"],
    "PFUMX": [("ALUT", "Z", 0.2), ("BLUT", "Z", 0.2), ("C0", "Z", 0.4)],
    "L6MUX21": [("D0", "Z", 0.2), ("D1", "Z", 0.2), ("SD", "Z", 0.4)],
    "CCU2C": ([(p + i, "S" + i, 0.5) for i in "01" for p in "ABCD"] +
              [(p + i, "COUT", 0.45) for i in "01" for p in "ABCD"] +
              [("CIN", "S0", 0.25), ("CIN", "S1", 0.3), ("CIN", "COUT", 0.06)]),
    "TRELLIS_DPR16X4": [("RAD", "DO", 0.6)],
    "MULT18X18D": [("A", "P", 4.0), ("B", "P", 4.0)],
}
# Inputs fed by dedicated wires inside a slice (no general routing).
DEDICATED = {"CIN", "ALUT", "BLUT", "D0", "D1"}
END_PORTS = {
    "TRELLIS_FF": re.compile(r"DI|M|CE|LSR"),
    "TRELLIS_DPR16X4": re.compile(r"(DI|WAD)\d|WRE"),
}


def base(port):
    return re.sub(r"\d+$", "", port)


def load(path):
    data = json.load(open(path))
    mods = data["modules"]
    tops = [m for m in mods.values() if int(m.get("attributes", {}).get("top", 0) or 0)]
    if len(tops) != 1:
        sys.exit(f"logic_depth: {path}: expected one top module, found {len(tops)}")
    return tops[0]


def analyse(mod):
    cells = mod["cells"]
    names = {}
    for name, net in mod["netnames"].items():
        for b in net["bits"]:
            if isinstance(b, int) and (b not in names or len(name) < len(names[b])):
                names[b] = name
    driver = {}
    edges = collections.defaultdict(list)  # bit -> [(bit, delay)]
    for cn, c in cells.items():
        dirs = c.get("port_directions", {})
        conns = c["connections"]
        for p, bits in conns.items():
            if dirs.get(p) == "output":
                for b in bits:
                    if isinstance(b, int):
                        driver[b] = cn
        for ip, op, dl in ARCS.get(c["type"], []):
            ins = [p for p in conns if ip in (p, base(p))]
            outs = [p for p in conns if op in (p, base(p))]
            for i in ins:
                route = 0.0 if ip in DEDICATED else NET_NS
                for ib in conns[i]:
                    if not isinstance(ib, int):
                        continue
                    for o in outs:
                        for ob in conns[o]:
                            if isinstance(ob, int):
                                edges[ib].append((ob, dl + route))
    indeg = collections.Counter(ob for es in edges.values() for ob, _ in es)
    arrival, prev = {}, {}
    queue = collections.deque()
    for b in set(edges) | set(driver):
        if indeg[b] == 0:
            t = cells[driver[b]]["type"] if b in driver else None
            arrival[b] = {"TRELLIS_FF": FF_CLK_TO_Q_NS, "DP16KD": BRAM_CLK_TO_Q_NS}.get(t, 0.0)
            queue.append(b)
    while queue:
        b = queue.popleft()
        for ob, dl in edges.get(b, []):
            t = arrival[b] + dl
            if t > arrival.get(ob, -1.0):
                arrival[ob], prev[ob] = t, b
            indeg[ob] -= 1
            if indeg[ob] == 0:
                queue.append(ob)
    if any(n > 0 for n in indeg.values()):
        sys.stderr.write("logic_depth: combinational loop; the bits on it are not ranked\n")
    ends = {}
    for cn, c in cells.items():
        pat = END_PORTS.get(c["type"])
        if not pat:
            continue
        key = re.sub(r"_TRELLIS_FF_Q(_\d+)?$", "", cn)
        if c["type"] == "TRELLIS_DPR16X4":
            key = re.sub(r"(\.\d+)*(_TRELLIS_DPR16X4.*)?$", "", cn) + " (distributed RAM)"
        for p, bits in c["connections"].items():
            if not pat.fullmatch(p):
                continue
            for b in bits:
                if isinstance(b, int) and b in arrival:
                    t = arrival[b] + NET_NS + FF_SETUP_NS
                    if key not in ends or t > ends[key][0]:
                        ends[key] = (t, base(p), b)
    return ends, arrival, prev, driver, names


def describe(b, prev, driver, names):
    """The start point and the distinct named signals along the worst path into bit b."""
    path = []
    while b in prev:
        path.append(b)
        b = prev[b]
    start = driver.get(b) or names.get(b, "?")
    start = re.sub(r"_TRELLIS_FF_Q(_\d+)?$", "", start)
    signals = []
    for x in reversed(path):
        n = re.sub(r"_(LUT4|PFUMX|L6MUX21|CCU2C|TRELLIS|DPR|MULT)\w*", "", names.get(x, "?"))
        n = re.sub(r"\$.*", "", n)
        if n and (not signals or signals[-1] != n):
            signals.append(n)
    return start, len(path), signals


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("netlist")
    ap.add_argument("--top", type=int, default=20, help="end points to list")
    ap.add_argument("--paths", type=int, default=5, help="end points to show with their signals")
    ap.add_argument("--markdown", action="store_true")
    args = ap.parse_args()
    ends, _, prev, driver, names = analyse(load(args.netlist))
    ranked = sorted(ends.items(), key=lambda kv: -kv[1][0])[:args.top]
    if args.markdown:
        print("| estimate | end point | from | arcs | through |")
        print("|---|---|---|---|---|")
    for i, (key, (t, port, b)) in enumerate(ranked):
        start, hops, signals = describe(b, prev, driver, names)
        through = " > ".join(signals[:12]) + (" > ..." if len(signals) > 12 else "")
        if args.markdown:
            print(f"| {t:.1f} ns | `{key}` .{port} | `{start}` | {hops} | "
                  f"{through if i < args.paths else ''} |")
        else:
            print(f"{t:6.1f} ns  {key} .{port}  <- {start}  ({hops} arcs)")
            if i < args.paths:
                print(f"           through {through}")


if __name__ == "__main__":
    main()
