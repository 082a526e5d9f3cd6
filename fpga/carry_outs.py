#!/usr/bin/env python3
"""Cut the unused carry-outs of a Yosys ECP5 netlist's carry chains (docs/fpga.md, step 4b).

Usage: carry_outs.py IN.json OUT.json

nextpnr-ecp5's packer ends every carry chain whose last CCU2C has a net on COUT with a feed-out
CCU2C (a slice: two LUT4 sites, TRELLIS_COMB) that brings the carry to the fabric, whether or not
anything reads that net. Yosys's synth_ecp5 leaves a net on every CCU2C's COUT, so a chain
that only makes a sum (its carry-out read by nothing) still gets one. This pass disconnects
each CCU2C's COUT that no cell input and no module output reads ("x" in the JSON netlist, as
Yosys writes an unconnected bit): the logic is unchanged, and nextpnr makes no feed-out for it.
A COUT that anything reads (the next CCU2C's CIN, a compare's result in a LUT, a port) is kept.
A cell whose port directions the netlist does not give counts every port as a reader.

Prints the number of carry-outs cut. Used by fpga_ecp5.py between synthesis and place and
route; tests/fpga/carry_outs_test.py checks it on hand-made netlists.
"""
import json
import sys


def readers(module):
    """Bit number -> how many cell inputs and module outputs read it."""
    count = {}
    for cell in module.get("cells", {}).values():
        dirs = cell.get("port_directions", {})
        for port, bits in cell.get("connections", {}).items():
            if dirs.get(port) == "output":
                continue
            for b in bits:
                if isinstance(b, int):
                    count[b] = count.get(b, 0) + 1
    for port in module.get("ports", {}).values():
        if port.get("direction") != "input":
            for b in port.get("bits", []):
                if isinstance(b, int):
                    count[b] = count.get(b, 0) + 1
    return count


def cut_unused_carry_outs(netlist):
    """Disconnect every CCU2C COUT that nothing reads, in every module; returns how many."""
    cut = 0
    for module in netlist.get("modules", {}).values():
        if module.get("attributes", {}).get("blackbox"):
            continue
        cells = module.get("cells", {})
        if not any(c.get("type") == "CCU2C" for c in cells.values()):
            continue
        read = readers(module)
        for cell in cells.values():
            if cell.get("type") != "CCU2C":
                continue
            cout = cell.get("connections", {}).get("COUT")
            if cout and isinstance(cout[0], int) and read.get(cout[0], 0) == 0:
                cell["connections"]["COUT"] = ["x"]
                cut += 1
    return cut


def main(argv):
    if len(argv) != 3:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    try:
        with open(argv[1]) as f:
            netlist = json.load(f)
    except (OSError, ValueError) as e:
        print(f"carry_outs: cannot read {argv[1]}: {e}", file=sys.stderr)
        return 1
    if not isinstance(netlist, dict) or not isinstance(netlist.get("modules"), dict):
        print(f"carry_outs: {argv[1]}: not a Yosys JSON netlist (no modules)", file=sys.stderr)
        return 1
    cut = cut_unused_carry_outs(netlist)
    with open(argv[2], "w") as f:
        json.dump(netlist, f)
    print(f"carry_outs: {cut} unused carry-outs cut")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
