#!/usr/bin/env python3
"""The carry chains of a Yosys ECP5 netlist without nextpnr's feed slices (docs/fpga.md, step 4b).

Usage: carry_outs.py [--no-fold] IN.json OUT.json

nextpnr-ecp5's packer ends every carry chain whose last CCU2C has a net on COUT with a feed-out
CCU2C (a slice: two LUT4 sites, TRELLIS_COMB) that brings the carry to the fabric, whether or not
anything reads that net. Yosys's synth_ecp5 leaves a net on every CCU2C's COUT, so a chain
that only makes a sum (its carry-out read by nothing) still gets one. This pass disconnects
each CCU2C's COUT that no cell input and no module output reads ("x" in the JSON netlist, as
Yosys writes an unconnected bit): the logic is unchanged, and nextpnr makes no feed-out for it.
A COUT that anything reads (the next CCU2C's CIN, a compare's result in a LUT, a port) is kept.
A cell whose port directions the netlist does not give counts every port as a reader.

It also folds constant carry-ins. nextpnr starts every chain whose first CIN has a net (the
constants 0 and 1 included) with a feed-in CCU2C, because in the fabric a chain's carry-in comes
over the fixed carry wire from the slice below. A chain's first CCU2C can make its own carry
instead when its first half's sum S0 is read by nothing (a compare, a subtraction's borrow, the
low bit of a sum whose other operand is the constant carry) and that half's C0 and D0 are
constants: its carry-out cout_0 is then a function of A0 and B0 alone, which the half's LUT2
(INIT0[3:0] on B0, A0) makes when its LUT4 is 0. The fold sets INIT0 to that LUT2 and zeros the
rest, ties C0 and D0 to 1 (so the LUT4 reads entries 12 to 15, all 0, and passes no carry-in),
sets INJECT1_0 to "NO" and disconnects CIN and S0; nextpnr then needs no feed-in, as for its own
feed-in cells, which are built the same way. Every folded cell is checked before it is written:
its S1 and COUT, for every value of A0, B0, A1, B1, C1, D1 and of the now unconnected carry-in,
equal the original cell's with its constant carry-in (the CCU2C of Yosys's ECP5 simulation model,
share/yosys/ecp5/cells_sim.v, transcribed in ccu2c() below; the test proves the fold with
Yosys's own model). --no-fold turns the fold off.

Prints the number of carry-outs cut and of carry-ins folded. Used by fpga_ecp5.py between
synthesis and place and route; tests/fpga/carry_outs_test.py checks it on hand-made netlists.
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


def carry_cells(netlist):
    """Every CCU2C of every module that is not a black box, with its module's readers() (counted
    once per module, before the caller changes any of its cells)."""
    for module in netlist.get("modules", {}).values():
        if module.get("attributes", {}).get("blackbox"):
            continue
        cells = module.get("cells", {})
        if not any(c.get("type") == "CCU2C" for c in cells.values()):
            continue
        read = readers(module)
        for cell in cells.values():
            if cell.get("type") == "CCU2C":
                yield cell, read


def cut_unused_carry_outs(netlist):
    """Disconnect every CCU2C COUT that nothing reads, in every module; returns how many."""
    cut = 0
    for cell, read in carry_cells(netlist):
        cout = cell.get("connections", {}).get("COUT")
        if cout and isinstance(cout[0], int) and read.get(cout[0], 0) == 0:
            cell["connections"]["COUT"] = ["x"]
            cut += 1
    return cut


def lut4(init, a, b, c, d):
    """cells_sim.v's LUT4: INIT bit {D, C, B, A}."""
    return (init >> (d * 8 + c * 4 + b * 2 + a)) & 1


def half(init, inject, cin, a, b, c, d):
    """One half of cells_sim.v's CCU2C: (sum, carry-out). inject: INJECT1_n == "YES"."""
    l4 = lut4(init, a, b, c, d)
    l2 = lut4(init & 0xF, a, b, 0, 0)
    s = l4 ^ (0 if inject else cin)
    cout = ((1 - l4) & (0 if inject else l2)) | (l4 & cin)
    return s, cout


def ccu2c(init0, init1, inject0, inject1, cin, a0, b0, c0, d0, a1, b1, c1, d1):
    """cells_sim.v's CCU2C: (S0, S1, COUT)."""
    s0, cout_0 = half(init0, inject0, cin, a0, b0, c0, d0)
    s1, cout = half(init1, inject1, cout_0, a1, b1, c1, d1)
    return s0, s1, cout


def const_bit(bits):
    """0 or 1 for a connection to a constant, else None."""
    if isinstance(bits, list) and len(bits) == 1 and bits[0] in ("0", "1"):
        return int(bits[0])
    return None


def param_int(value):
    """A Yosys JSON bit-string parameter (most significant bit first) as an int, else None."""
    if isinstance(value, int):
        return value
    if isinstance(value, str) and value and set(value) <= {"0", "1"}:
        return int(value, 2)
    return None


def fold_one(cell, read):
    """The folded parameters and connections of one CCU2C, or None when it does not qualify."""
    con = cell.get("connections", {})
    par = cell.get("parameters", {})
    cin, c0, d0 = const_bit(con.get("CIN")), const_bit(con.get("C0")), const_bit(con.get("D0"))
    if cin is None or c0 is None or d0 is None:
        return None
    s0 = con.get("S0", ["x"])
    if not isinstance(s0, list) or len(s0) != 1:
        return None
    if isinstance(s0[0], int) and read.get(s0[0], 0) != 0:
        return None
    init0, init1 = param_int(par.get("INIT0", 0)), param_int(par.get("INIT1", 0))
    inj0, inj1 = par.get("INJECT1_0", "YES"), par.get("INJECT1_1", "YES")
    if init0 is None or init1 is None or inj0 not in ("YES", "NO") or inj1 not in ("YES", "NO"):
        return None
    inj0, inj1 = inj0 == "YES", inj1 == "YES"
    # The first half's carry-out for each (A0, B0), by the model with the constant carry-in.
    new_init0 = 0
    for b in (0, 1):
        for a in (0, 1):
            new_init0 |= half(init0, inj0, cin, a, b, c0, d0)[1] << (b * 2 + a)
    # The check: the folded cell's S1 and COUT, whatever its (unconnected) carry-in, equal the
    # original's for every input.
    for x in range(64):
        a0, b0, a1, b1, c1, d1 = ((x >> i) & 1 for i in range(6))
        _, s1, cout = ccu2c(init0, init1, inj0, inj1, cin, a0, b0, c0, d0, a1, b1, c1, d1)
        for free_cin in (0, 1):
            _, s1n, coutn = ccu2c(new_init0, init1, False, inj1, free_cin, a0, b0, 1, 1, a1, b1,
                                  c1, d1)
            if (s1n, coutn) != (s1, cout):
                raise AssertionError(f"carry_outs: the fold of a CCU2C (INIT0 {init0:#06x}) "
                                     "changes its outputs")
    return {"INIT0": format(new_init0, "016b"), "INJECT1_0": "NO"}


def fold_constant_carry_ins(netlist):
    """Fold every qualifying chain start's constant carry-in (module docstring); returns the
    number folded."""
    folded = 0
    for cell, read in carry_cells(netlist):
        params = fold_one(cell, read)
        if params is None:
            continue
        cell.setdefault("parameters", {}).update(params)
        con = cell["connections"]
        con["C0"], con["D0"], con["CIN"], con["S0"] = ["1"], ["1"], ["x"], ["x"]
        folded += 1
    return folded


def main(argv):
    args = argv[1:]
    fold = True
    if args and args[0] == "--no-fold":
        fold = False
        args = args[1:]
    if len(args) != 2:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    try:
        with open(args[0]) as f:
            netlist = json.load(f)
    except (OSError, ValueError) as e:
        print(f"carry_outs: cannot read {args[0]}: {e}", file=sys.stderr)
        return 1
    if not isinstance(netlist, dict) or not isinstance(netlist.get("modules"), dict):
        print(f"carry_outs: {args[0]}: not a Yosys JSON netlist (no modules)", file=sys.stderr)
        return 1
    cut = cut_unused_carry_outs(netlist)
    folded = fold_constant_carry_ins(netlist) if fold else 0
    with open(args[1], "w") as f:
        json.dump(netlist, f)
    print(f"carry_outs: {cut} unused carry-outs cut")
    print(f"carry_outs: {folded} constant carry-ins folded")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
