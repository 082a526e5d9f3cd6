#!/usr/bin/env python3
"""fpga/sta.py against small SDF files whose answers are worked out by hand.

Each case writes an SDF in nextpnr's form (cell IOPATHs in ps as min:typ:max, INTERCONNECT
delays, SETUPHOLD checks), runs sta.py with --json and checks the worst slack, the number of
failing endpoints, the worst path's pins and the grouping. Exit status 0 when all hold.
"""
import json
import pathlib
import subprocess
import sys
import tempfile

STA = pathlib.Path(__file__).resolve().parents[2] / "fpga" / "sta.py"


def ff(name, clk_q, setup, pin="DI"):
    return f"""  (CELL
    (CELLTYPE "TRELLIS_FF")
    (INSTANCE {name})
    (DELAY
      (ABSOLUTE
        (IOPATH CLK Q ({clk_q - 50}:{clk_q - 20}:{clk_q}) ({clk_q - 50}:{clk_q - 20}:{clk_q}))
      )
    )
    (TIMINGCHECK
      (SETUPHOLD (posedge {pin}) (posedge CLK) ({setup}:{setup}:{setup}) (0:0:0))
      (SETUPHOLD (negedge {pin}) (posedge CLK) ({setup}:{setup}:{setup}) (0:0:0))
    )
  )
"""


def lut(name, arcs):
    body = "".join(f"        (IOPATH {a} F ({d}:{d}:{d}) ({d}:{d}:{d}))\n" for a, d in arcs)
    return f"""  (CELL
    (CELLTYPE "TRELLIS_COMB")
    (INSTANCE {name})
    (DELAY
      (ABSOLUTE
{body}      )
    )
  )
"""


def sdf(cells, nets):
    inter = "".join(f"        (INTERCONNECT {a} {b} ({d - 10}:{d - 5}:{d}) ({d}:{d}:{d}))\n"
                    for a, b, d in nets)
    return f"""(DELAYFILE
  (SDFVERSION "3.0")
  (DESIGN "top")
  (VENDOR "nextpnr")
  (DIVIDER /)
  (TIMESCALE 1ps)
  (CELL
    (CELLTYPE "top")
    (INSTANCE )
    (DELAY
      (ABSOLUTE
{inter}      )
    )
  )
{''.join(cells)})
"""


def run(text, period, tmp):
    f = pathlib.Path(tmp) / "t.sdf"
    f.write_text(text)
    out = pathlib.Path(tmp) / "t.json"
    res = subprocess.run([sys.executable, str(STA), str(f), "--period", str(period), "--json",
                          str(out)], capture_output=True, text=True)
    if res.returncode != 0:
        raise AssertionError(f"sta.py failed: {res.stderr}")
    return json.loads(out.read_text()), res.stdout


def check(cond, what):
    if not cond:
        raise AssertionError(what)


def case_reconvergent(tmp):
    # a_q[0] -> lut1 (A, 300) -> lut2 (B, 200) -> b_q[0]
    # a_q[1] ----------------->  lut2 (A, 250) -> b_q[0]
    # a_q[1] -> c_q[3] directly (one net)
    # Arrivals (ns, max values): a_q.Q 0.5; lut1/A 0.5+0.4=0.9; lut1/F 1.2; lut2/B 1.2+1.0=2.2;
    # lut2/A 0.5+0.3=0.8; lut2/F max(2.2+0.2, 0.8+0.25)=2.4; b_q/DI 2.4+0.1=2.5; setup 0.2:
    # slack at 2.5 ns = 2.5 - 0.2 - 2.5 = -0.2. c_q_TRELLIS_FF_Q_3/DI: 0.5+1.9=2.4, setup 0.2,
    # slack -0.1.
    cells = [ff("a_q_TRELLIS_FF_Q", 500, 200), ff("a_q_TRELLIS_FF_Q_1", 500, 200),
             ff("b_q_TRELLIS_FF_Q", 500, 200), ff("c_q_TRELLIS_FF_Q_3", 500, 200),
             lut("u.lut1_LUT4_Z", [("A", 300)]), lut("u.lut2_LUT4_Z", [("A", 250), ("B", 200)])]
    nets = [("a_q_TRELLIS_FF_Q/Q", "u.lut1_LUT4_Z/A", 400),
            ("u.lut1_LUT4_Z/F", "u.lut2_LUT4_Z/B", 1000),
            ("a_q_TRELLIS_FF_Q_1/Q", "u.lut2_LUT4_Z/A", 300),
            ("u.lut2_LUT4_Z/F", "b_q_TRELLIS_FF_Q/DI", 100),
            ("a_q_TRELLIS_FF_Q_1/Q", "c_q_TRELLIS_FF_Q_3/DI", 1900)]
    rep, text = run(sdf(cells, nets), 2.5, tmp)
    check(abs(rep["worst_slack_ns"] - (-0.2)) < 1e-6, f"worst slack {rep['worst_slack_ns']}")
    check(abs(rep["fmax_mhz"] - 1000.0 / 2.7) < 1e-3, f"fmax {rep['fmax_mhz']}")
    # a_q's inputs are driven by nothing timed: only b_q and c_q are timed endpoints.
    check(rep["endpoints"] == 2 and rep["failing"] == 2,
          f"endpoints {rep['endpoints']} failing {rep['failing']}")
    pins = [p["pin"] for p in rep["paths"][0]["pins"]]
    check(pins == ["a_q_TRELLIS_FF_Q/Q", "u.lut1_LUT4_Z/A", "u.lut1_LUT4_Z/F",
                   "u.lut2_LUT4_Z/B", "u.lut2_LUT4_Z/F", "b_q_TRELLIS_FF_Q/DI"], f"path {pins}")
    ends = {g["name"]: g for g in rep["by_end"]}
    check(set(ends) == {"b_q", "c_q"}, f"end groups {sorted(ends)}")
    check(ends["b_q"]["start"] == "a_q" and ends["c_q"]["count"] == 1, f"groups {ends}")
    check(abs(ends["c_q"]["worst"] - (-0.1)) < 1e-6, f"c_q slack {ends['c_q']['worst']}")
    # At 3 ns nothing fails; the worst slack is then +0.3.
    rep, _ = run(sdf(cells, nets), 3.0, tmp)
    check(rep["failing"] == 0 and abs(rep["worst_slack_ns"] - 0.3) < 1e-6,
          f"at 3 ns: failing {rep['failing']}, worst {rep['worst_slack_ns']}")


def case_ram_launch(tmp):
    # A distributed RAM read: the write clock launches nothing on the read data, the read address
    # (from a register) goes through the RAM's combinational arc, and the write data pin is an
    # endpoint with its own setup check against WCK.
    cells = [ff("addr_q_TRELLIS_FF_Q", 400, 100), ff("out_q_TRELLIS_FF_Q", 400, 100),
             f"""  (CELL
    (CELLTYPE "TRELLIS_COMB")
    (INSTANCE mem_m$DPRAM)
    (DELAY
      (ABSOLUTE
        (IOPATH A F (600:600:600) (600:600:600))
      )
    )
    (TIMINGCHECK
      (SETUPHOLD (posedge WD) (posedge WCK) (300:300:300) (0:0:0))
    )
  )
"""]
    nets = [("addr_q_TRELLIS_FF_Q/Q", "mem_m$DPRAM/A", 500),
            ("mem_m$DPRAM/F", "out_q_TRELLIS_FF_Q/DI", 700),
            ("addr_q_TRELLIS_FF_Q/Q", "mem_m$DPRAM/WD", 2000)]
    # out_q: 0.4 + 0.5 + 0.6 + 0.7 = 2.2, setup 0.1 -> slack at 2 ns: -0.3.
    # mem WD: 0.4 + 2.0 = 2.4, setup 0.3 -> slack -0.7 (the worst).
    rep, _ = run(sdf(cells, nets), 2.0, tmp)
    check(abs(rep["worst_slack_ns"] - (-0.7)) < 1e-6, f"worst {rep['worst_slack_ns']}")
    check(rep["failing"] == 2, f"failing {rep['failing']}")
    check(rep["paths"][0]["endpoint"] == "mem_m$DPRAM/WD", f"endpoint {rep['paths'][0]}")
    names = [g["name"] for g in rep["by_end"]]
    check(names == ["mem_m", "out_q"], f"groups {names}")


def dcca(name):
    return f"""  (CELL
    (CELLTYPE "DCCA")
    (INSTANCE {name})
    (DELAY
      (ABSOLUTE
        (IOPATH CLKI CLKO (0:0:0) (0:0:0))
      )
    )
  )
"""


def case_global_buffer(tmp):
    # The reset's synchroniser -> a global buffer (DCCA) -> a flip-flop's LSR, which has a setup
    # check: the buffer passes the path through (0.5 + 1.7 + 0 + 7.0 = 9.2, setup 0.4: slack at
    # 9 ns -0.6); timed from the buffer's output instead, it would pass (+1.6). The clock's own
    # buffer only reaches clock pins and makes no endpoint.
    cells = [ff("rst_sync_q_TRELLIS_FF_Q", 500, 200), ff("x_q_TRELLIS_FF_Q", 500, 400, "LSR"),
             dcca("u_rst_buf"), dcca("gbuf_clk")]
    nets = [("rst_sync_q_TRELLIS_FF_Q/Q", "u_rst_buf/CLKI", 1700),
            ("u_rst_buf/CLKO", "x_q_TRELLIS_FF_Q/LSR", 7000),
            ("u_pll/CLKOP", "gbuf_clk/CLKI", 150),
            ("gbuf_clk/CLKO", "x_q_TRELLIS_FF_Q/CLK", 0),
            ("gbuf_clk/CLKO", "rst_sync_q_TRELLIS_FF_Q/CLK", 0)]
    rep, _ = run(sdf(cells, nets), 9.0, tmp)
    check(abs(rep["worst_slack_ns"] - (-0.6)) < 1e-6, f"worst {rep['worst_slack_ns']}")
    check(rep["endpoints"] == 1 and rep["failing"] == 1,
          f"endpoints {rep['endpoints']} failing {rep['failing']}")
    pins = [p["pin"] for p in rep["paths"][0]["pins"]]
    check(pins == ["rst_sync_q_TRELLIS_FF_Q/Q", "u_rst_buf/CLKI", "u_rst_buf/CLKO",
                   "x_q_TRELLIS_FF_Q/LSR"], f"path {pins}")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        for case in (case_reconvergent, case_ram_launch, case_global_buffer):
            case(tmp)
            print(f"sta_test: {case.__name__}: ok")
    print("[cases] fpga/sta.py: 4 hand-worked SDF timings, 0 mismatches")


if __name__ == "__main__":
    try:
        main()
    except AssertionError as e:
        print(f"sta_test: FAIL: {e}")
        sys.exit(1)
