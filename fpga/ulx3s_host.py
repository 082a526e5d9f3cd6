#!/usr/bin/env python3
"""Render a frame on the board build over its UART (docs/fpga.md, "The UART protocol").

Usage: ulx3s_host.py [--port /dev/ttyUSB0] [--baud 115200] [--image DIR] [--all-regs]
                     [--no-start] [--timeout S] [--mhz F] [-o frame.ppm]

With --image DIR (a `raycore board-image` directory, e.g. BUILD/fpga/ecp5/image) it first writes
the camera and frame size registers (BoardRegEye .. BoardRegHeight; --all-regs: the whole
register file) from DIR/regs.hex, and checks them by reading them back. Then it starts a frame
('S'), polls the status register until done (or size or config error), prints the status and the frame's
cycle count (and time, with --mhz), and fetches the framebuffer ('F') into a binary PPM (P6).
Without --image the board renders with the registers it has (after configuration: the regs.hex
the bitstream was built with).

Register numbers come from docs/spec.toml ([board_reg], [board_status]), the file the RTL's
rc_pkg is generated from. Uses pyserial when it is installed, else the POSIX termios module.
Exits non-zero on a timeout, a read-back mismatch, a size error or core error bits.
"""
import argparse
import os
import pathlib
import sys
import time

try:
    import tomllib
except ImportError:  # Python < 3.11
    tomllib = None

ROOT = pathlib.Path(__file__).resolve().parent.parent


def load_spec():
    text = (ROOT / "docs" / "spec.toml").read_text()
    if tomllib is not None:
        return tomllib.loads(text)
    # Minimal reader for the sections used here: "[section]" and "name = integer" lines.
    spec, section = {}, None
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if line.startswith("[") and line.endswith("]"):
            section = spec.setdefault(line[1:-1], {})
        elif "=" in line and section is not None:
            k, v = (s.strip() for s in line.split("=", 1))
            try:
                section[k] = int(v, 0)
            except ValueError:
                pass
    return spec


class PosixSerial:
    """The part of pyserial's Serial used here, on termios (raw 8N1, no flow control)."""

    def __init__(self, port, baud, timeout):
        import termios
        self.termios = termios
        self.timeout = timeout
        self.fd = os.open(port, os.O_RDWR | os.O_NOCTTY)
        rate = getattr(termios, f"B{baud}", None)
        if rate is None:
            raise SystemExit(f"ulx3s_host: baud rate {baud} not supported by termios "
                             f"(install pyserial)")
        attrs = termios.tcgetattr(self.fd)
        attrs[0] = 0                                   # iflag: raw
        attrs[1] = 0                                   # oflag
        attrs[2] = termios.CS8 | termios.CREAD | termios.CLOCAL
        attrs[3] = 0                                   # lflag: no echo, non-canonical
        attrs[4] = attrs[5] = rate
        attrs[6][termios.VMIN] = 0
        attrs[6][termios.VTIME] = 1                    # reads return after 0.1 s
        termios.tcsetattr(self.fd, termios.TCSANOW, attrs)
        termios.tcflush(self.fd, termios.TCIOFLUSH)

    def write(self, data):
        view = memoryview(bytes(data))
        while view:
            n = os.write(self.fd, view)
            view = view[n:]

    def read(self, n):
        out = bytearray()
        deadline = time.monotonic() + self.timeout
        while len(out) < n and time.monotonic() < deadline:
            out += os.read(self.fd, n - len(out))
        return bytes(out)

    def reset_input_buffer(self):
        self.termios.tcflush(self.fd, self.termios.TCIFLUSH)

    def close(self):
        os.close(self.fd)


def open_port(port, baud, timeout):
    try:
        import serial
    except ImportError:
        return PosixSerial(port, baud, timeout)
    return serial.Serial(port, baud, bytesize=8, parity="N", stopbits=1, timeout=timeout)


class Board:
    def __init__(self, ser, baud):
        self.ser = ser
        self.baud = baud

    def write_reg(self, addr, value):
        self.ser.write(bytes([ord("W"), addr]) + (value & 0xffffffff).to_bytes(4, "little"))

    def read_reg(self, addr):
        self.ser.write(bytes([ord("R"), addr]))
        data = self.ser.read(4)
        if len(data) != 4:
            raise SystemExit(f"ulx3s_host: no answer to 'R' {addr} (got {len(data)} of 4 bytes)")
        return int.from_bytes(data, "little")

    def start(self):
        self.ser.write(b"S")

    def frame(self, width, height):
        n = width * height * 3
        self.ser.timeout = 2.0 + 1.5 * n * 10 / self.baud  # the whole read
        self.ser.write(b"F")
        data = self.ser.read(n)
        self.ser.timeout = 2.0
        if len(data) != n:
            raise SystemExit(f"ulx3s_host: frame: got {len(data)} of {n} bytes")
        return data


def read_hex_words(path):
    return [int(line.split("//", 1)[0], 16) for line in path.read_text().splitlines()
            if line.split("//", 1)[0].strip()]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--port", default="/dev/ttyUSB0")
    ap.add_argument("--baud", type=int, default=115200, help="the bitstream's UART bit rate")
    ap.add_argument("--image", help="board image directory (its regs.hex is used)")
    ap.add_argument("--all-regs", action="store_true", help="write the whole register file")
    ap.add_argument("--no-start", action="store_true", help="fetch the framebuffer only")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds to wait for the frame")
    ap.add_argument("--mhz", type=float, help="core clock, to print the frame time")
    ap.add_argument("-o", "--output", default="frame.ppm")
    args = ap.parse_args()

    spec = load_spec()
    reg, st = spec["board_reg"], spec["board_status"]
    ser = open_port(args.port, args.baud, timeout=2.0)
    board = Board(ser, args.baud)
    # Let a half-received command time out on the board (rc_board_host abandons it), then flush.
    time.sleep(0.5)
    ser.reset_input_buffer()

    if args.image:
        regs = read_hex_words(pathlib.Path(args.image) / "regs.hex")
        # The lit board's image holds board.lit_regs registers (its light registers too).
        nregs = len(regs)
        addrs = range(nregs) if args.all_regs else range(reg["eye"], reg["height"] + 1)
        for a in addrs:
            board.write_reg(a, regs[a])
        bad = [a for a in addrs if board.read_reg(a) != regs[a]]
        if bad:
            raise SystemExit(f"ulx3s_host: register read-back differs at {bad} (is a frame "
                             f"running? writes are ignored while busy)")
        print(f"ulx3s_host: wrote registers {addrs.start} .. {addrs.stop - 1}")

    width = board.read_reg(reg["width"]) & 0xffff
    height = board.read_reg(reg["height"]) & 0xffff
    status = board.read_reg(reg["status"])
    if not args.no_start:
        t0 = time.monotonic()
        board.start()
        while True:
            status = board.read_reg(reg["status"])
            if not status >> st["busy"] & 1:
                break
            if time.monotonic() - t0 > args.timeout:
                raise SystemExit(f"ulx3s_host: frame not done after {args.timeout} s "
                                 f"(status 0x{status:x})")
            time.sleep(0.01)
    cycles = board.read_reg(reg["cycles"])
    errors = status >> st["core_error_lsb"]
    print(f"ulx3s_host: {width}x{height}, status 0x{status:x} (done "
          f"{status >> st['done'] & 1}, size error {status >> st['size_error'] & 1}, config "
          f"error {status >> st['config_error'] & 1}, core errors 0x{errors:x}), {cycles} cycles"
          + (f" = {cycles / (args.mhz * 1e3):.3f} ms at {args.mhz:g} MHz" if args.mhz else ""))
    data = board.frame(width, height)
    with open(args.output, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (width, height) + data)
    print(f"ulx3s_host: wrote {args.output}")
    ser.close()
    failed = (status >> st["size_error"] & 1) or (status >> st["config_error"] & 1) or errors or (
        not args.no_start and not status >> st["done"] & 1)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
