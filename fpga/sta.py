#!/usr/bin/env python3
"""Static timing analysis of a routed design from nextpnr's SDF: every failing endpoint.

Usage: sta.py DESIGN.sdf [--period NS] [--netlist JSON] [--top N] [--groups N] [--paths N]
              [--to REGEX ...] [--json OUT]

nextpnr reports one critical path per clock; closing timing on a large design needs all of them.
nextpnr writes the routed design's delays with `--sdf FILE` (`fpga_ecp5.py` always does): every
cell's arcs (IOPATH, clock-to-out and combinational), every net's delay from its driver to each
sink (INTERCONNECT) and every setup check (SETUPHOLD). This script builds the timing graph from
them and propagates the latest arrival time from every clock-to-out arc, so each register input
gets its worst path; the slack is the period minus the setup time minus that arrival. One clock
domain is assumed (the board's core clock: the clock nets' delays are 0 in nextpnr's SDF, so no
skew) and the maximum of each min:typ:max triple is used, as nextpnr's own analysis does.

It prints:
- the worst slack and the Fmax it gives (nextpnr's figure for the same run, as a cross-check);
- a histogram of the endpoints' slacks and how many fail the period;
- the failing endpoints grouped by register (cell names with their bit and packing suffixes
  removed: `u_core.wb_bt_q`), with the count, the worst slack and the worst path's start group;
- the same for (start group, end group) pairs, and for start groups;
- the N worst paths in full: every pin with its arrival time and the delay of the cell or net
  that reaches it (nets: routing; cells: logic), and the totals.

--netlist JSON (the Yosys netlist nextpnr read) adds each group's RTL source line (the cells'
`src` attributes, e.g. `rc_core.sv:1012`): Yosys names many cells after a net they happen to
touch, so the source line is the reliable way back to the RTL.
--to REGEX adds the worst path to the endpoints (instance/PIN) that match REGEX.
--json OUT writes the groups and paths for other scripts.
"""

import argparse
import collections
import heapq
import json
import re
import sys

TOKEN = re.compile(r'\(|\)|"[^"]*"|[^\s()]+')


def parse_sdf(path):
    """Yields (kind, instance, a, b, delay_ns) for IOPATH, INTERCONNECT and SETUP checks."""
    with open(path) as f:
        text = f.read()
    toks = TOKEN.findall(text)
    n = len(toks)
    i = 0
    instance = ""

    def triple(tok):
        # "(a:b:c)" arrives as "(", "a:b:c", ")"; take the maximum in ps.
        vals = [float(v) for v in tok.split(":") if v != ""]
        return max(vals) / 1000.0 if vals else 0.0

    while i < n:
        t = toks[i]
        if t == "(" and i + 1 < n:
            kw = toks[i + 1]
            if kw == "INSTANCE":
                if toks[i + 2] == ")":
                    instance = ""
                    i += 3
                else:
                    instance = unescape(toks[i + 2])
                    i += 4
                continue
            if kw == "IOPATH":
                a, b = toks[i + 2], toks[i + 3]
                d = triple(toks[i + 5])
                yield ("iopath", instance, a, b, d)
                i += 4
                continue
            if kw == "INTERCONNECT":
                a, b = unescape(toks[i + 2]), unescape(toks[i + 3])
                d = triple(toks[i + 5])
                yield ("net", instance, a, b, d)
                i += 4
                continue
            if kw == "SETUPHOLD":
                # (SETUPHOLD (posedge D) (posedge CLK) (setup) (hold))
                j = i + 2
                assert toks[j] == "("
                data_pin = toks[j + 2]
                j += 4
                assert toks[j] == "("
                clk_pin = toks[j + 2]
                j += 4
                setup = triple(toks[j + 1])
                yield ("setup", instance, data_pin, clk_pin, setup)
                i = j
                continue
        i += 1


def unescape(s):
    return s.replace("\\", "")


def split_pin(p):
    """'inst/PIN' -> (inst, PIN): the last '/' splits (an instance name holds '/' only escaped)."""
    k = p.rfind("/")
    return p[:k], p[k + 1:]


SUFFIXES = [
    re.compile(r"_TRELLIS_FF_Q(_\d+)?$"),
    re.compile(r"\$.*$"),
    re.compile(r"_(LUT4|CCU2C|PFUMX|L6MUX21|DPR16X4|TRELLIS_RAMW|TRELLIS_COMB|DP16KD|MULT18X18D"
               r"|ALU54B)(_[A-Z0-9]+)*(_\d+)*$"),
    re.compile(r"\[\d+\]$"),
    re.compile(r"(_\d+)+$"),
]


PACK_SUFFIX = re.compile(r"\$(CCU2_COMB\d|DPRAM_COMB\d|RAMW_SLICE|RAMW_BLOCK\d|tr_io)$")


def load_sources(path):
    """Yosys cell name -> its first RTL source location (file:line), from the netlist's `src`
    attributes (techmap library files skipped)."""
    with open(path) as f:
        design = json.load(f)
    out = {}
    for mod in design["modules"].values():
        for name, cell in mod.get("cells", {}).items():
            src = cell.get("attributes", {}).get("src", "")
            for part in src.split("|"):
                file_part = part.rsplit(":", 1)[0]
                if not part or "/share/" in file_part or "techmap" in file_part:
                    continue
                line = part.rsplit(":", 1)[-1].split(".")[0]
                out[name] = f"{file_part.rsplit('/', 1)[-1]}:{line}"
                break
    return out


def source_of(inst, sources):
    return sources.get(PACK_SUFFIX.sub("", inst), "") if sources else ""


def group_of(inst):
    """A register's or cell's RTL-ish name: bit indices and packing suffixes removed."""
    g = inst
    for _ in range(3):
        for rx in SUFFIXES:
            g = rx.sub("", g)
    g = re.sub(r"\[\d+\]", "[*]", g)
    g = re.sub(r"\.\d+(\.\d+)*$", "", g)
    return g or inst


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("sdf")
    ap.add_argument("--period", type=float, default=10.0, help="clock period in ns (10)")
    ap.add_argument("--top", type=int, default=40, help="endpoint groups to list (40)")
    ap.add_argument("--groups", type=int, default=25, help="start/end pairs to list (25)")
    ap.add_argument("--paths", type=int, default=5, help="worst paths in full (5)")
    ap.add_argument("--netlist", help="the Yosys JSON netlist, for RTL source lines")
    ap.add_argument("--to", action="append", default=[], metavar="REGEX",
                    help="also print the worst path to the endpoints matching REGEX (repeatable)")
    ap.add_argument("--json", help="write groups and paths as JSON")
    args = ap.parse_args()

    sources = load_sources(args.netlist) if args.netlist else {}
    fanout = collections.defaultdict(list)   # node -> [(node, delay, kind)]
    indeg = collections.Counter()
    launch = {}                               # node -> clock-to-out
    setup = {}                                # endpoint node -> setup time
    clock_pins = collections.defaultdict(set)
    iopaths = []
    n_nets = 0
    for kind, inst, a, b, d in parse_sdf(args.sdf):
        if kind == "setup":
            setup[inst + "/" + a] = max(setup.get(inst + "/" + a, 0.0), d)
            clock_pins[inst].add(b)
        elif kind == "iopath":
            iopaths.append((inst, a, b, d))
        else:
            n_nets += 1
            fanout[a].append((b, d, "net"))
            indeg[b] += 1

    clockish = re.compile(r"^(CLK|WCK|CLKA|CLKB|CLK\d|CLKI|CLKOP)$")
    for inst, a, b, d in iopaths:
        # A global buffer (DCCA, CLKI -> CLKO) passes its input through: the clock's buffer then
        # only leads to clock pins, and the reset's carries a timed path from the synchroniser's
        # flip-flop to every LSR pin (run 63 seed 5, which nextpnr failed and this script missed).
        through = (a, b) == ("CLKI", "CLKO")
        if not through and (a in clock_pins.get(inst, ()) or clockish.match(a)):
            src = inst + "/" + b
            launch[src] = max(launch.get(src, 0.0), d)
        else:
            u, v = inst + "/" + a, inst + "/" + b
            fanout[u].append((v, d, "cell"))
            indeg[v] += 1

    # Arrival times: longest path from any launch, Kahn's order over all nodes.
    arrival = {}
    pred = {}
    nodes = set(fanout)
    for u in list(fanout):
        for v, _, _ in fanout[u]:
            nodes.add(v)
    nodes.update(launch)
    for s, d in launch.items():
        arrival[s] = d
        pred[s] = None
    queue = collections.deque(v for v in nodes if indeg[v] == 0)
    seen = 0
    while queue:
        u = queue.popleft()
        seen += 1
        au = arrival.get(u)
        for v, d, k in fanout.get(u, ()):
            if au is not None:
                t = au + d
                if t > arrival.get(v, -1.0):
                    arrival[v] = t
                    pred[v] = (u, d, k)
            indeg[v] -= 1
            if indeg[v] == 0:
                queue.append(v)
    if seen < len(nodes):
        print(f"sta: {len(nodes) - seen} pins lie on combinational loops and were not timed",
              file=sys.stderr)

    ends = []
    for e, su in setup.items():
        if e in arrival:
            req = args.period - su
            ends.append((req - arrival[e], e, arrival[e], su))
    if not ends:
        sys.exit("sta: no timed endpoint (is this an SDF written by nextpnr after routing?)")
    ends.sort()

    def path_of(e):
        pins = []
        v = e
        while v is not None:
            p = pred.get(v)
            pins.append((v, arrival[v], p[1] if p else arrival[v], p[2] if p else "launch"))
            v = p[0] if p else None
        return list(reversed(pins))

    worst = ends[0]
    wpath = path_of(worst[1])
    fmax = 1000.0 / (args.period - worst[0]) if args.period - worst[0] > 0 else float("inf")
    failing = [x for x in ends if x[0] < 0]
    print(f"sta: {len(ends)} timed endpoints, {len(launch)} launch pins, {n_nets} net arcs; "
          f"period {args.period:.2f} ns")
    print(f"sta: worst slack {worst[0]:.2f} ns -> Fmax {fmax:.2f} MHz; "
          f"{len(failing)} endpoints fail ({100.0 * len(failing) / len(ends):.1f}%), total "
          f"negative slack {sum(x[0] for x in failing):.0f} ns")

    # Histogram of the failing endpoints' slack.
    if failing:
        lo = failing[0][0]
        step = max(0.5, round(-lo / 10.0 * 2) / 2)
        bins = collections.Counter(int(-x[0] // step) for x in failing)
        print("\nfailing endpoints by slack:")
        for b in sorted(bins, reverse=True):
            print(f"  {-(b + 1) * step:7.2f} .. {-b * step:6.2f} ns  {bins[b]:6d}")

    # Groups.
    by_end = {}
    by_pair = {}
    by_start = {}
    for slack, e, arr, su in failing:
        p = path_of(e)
        start_inst, _ = split_pin(p[0][0])
        end_inst, end_pin = split_pin(e)
        sg, eg = group_of(start_inst), group_of(end_inst)
        routing = sum(d for pin, _, d, k in p if k == "net")
        for table, key in ((by_end, eg), (by_pair, (sg, eg)), (by_start, sg)):
            if key not in table:
                table[key] = {"count": 0, "worst": slack, "start": sg, "end": eg,
                              "routing": routing, "cells": sum(1 for x in p if x[3] == "cell"),
                              "endpoint": e, "start_src": source_of(start_inst, sources),
                              "end_src": source_of(end_inst, sources)}
            table[key]["count"] += 1

    def show(title, table, n, keyfmt):
        rows = sorted(table.items(), key=lambda kv: kv[1]["worst"])[:n]
        print(f"\n{title} ({len(table)} in all; worst first):")
        print(f"  {'worst':>7} {'count':>6} {'route':>6} {'cells':>5}  name")
        for k, r in rows:
            print(f"  {r['worst']:7.2f} {r['count']:6d} {r['routing']:6.2f} {r['cells']:5d}  "
                  f"{keyfmt(k, r)}")

    def src(x):
        return f" [{x}]" if x else ""

    if failing:
        show("failing endpoints by register", by_end, args.top,
             lambda k, r: f"{k}{src(r['end_src'])}   <- {r['start']}{src(r['start_src'])}")
        show("failing (start, end) pairs", by_pair, args.groups,
             lambda k, r: f"{k[0]}{src(r['start_src'])} -> {k[1]}{src(r['end_src'])}")
        show("failing paths by start register", by_start, args.groups,
             lambda k, r: f"{k}{src(r['start_src'])}")

    paths = []
    shown = set()
    for rx in args.to:
        hits = [x for x in ends if re.search(rx, x[1])]
        if not hits:
            print(f"\nno timed endpoint matches --to {rx}")
            continue
        slack, e, arr, su = hits[0]
        shown.add(group_of(split_pin(e)[0]))
        paths.append((slack, e, su, path_of(e)))
    for slack, e, arr, su in ends:
        if len(paths) >= args.paths + len(args.to):
            break
        eg = group_of(split_pin(e)[0])
        if eg in shown:
            continue
        shown.add(eg)
        p = path_of(e)
        paths.append((slack, e, su, p))
    for slack, e, su, p in paths:
        logic = sum(d for _, _, d, k in p if k in ("cell", "launch"))
        route = sum(d for _, _, d, k in p if k == "net")
        print(f"\npath to {e}: slack {slack:.2f} ns, arrival {p[-1][1]:.2f} + setup {su:.2f}; "
              f"logic {logic:.2f}, routing {route:.2f}")
        for pin, t, d, k in p:
            print(f"  {t:7.2f} {d:6.2f} {k:6s} {pin}{src(source_of(split_pin(pin)[0], sources))}")

    if args.json:
        out = {
            "period_ns": args.period,
            "worst_slack_ns": worst[0],
            "fmax_mhz": fmax,
            "endpoints": len(ends),
            "failing": len(failing),
            "by_end": [dict(name=k, **v) for k, v in sorted(by_end.items(),
                                                           key=lambda kv: kv[1]["worst"])],
            "by_pair": [dict(name=list(k), **v) for k, v in sorted(by_pair.items(),
                                                                  key=lambda kv: kv[1]["worst"])],
            "paths": [{"slack": s, "endpoint": e, "setup": su,
                       "pins": [{"pin": a, "t": t, "d": d, "kind": k} for a, t, d, k in p]}
                      for s, e, su, p in paths],
        }
        with open(args.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
