#!/usr/bin/env python3
"""The core's benchmark (`make bench-core`): renders each scene through the verilated core at
several memory latencies and thread counts, and at latency 16 with one and two ray set-up units,
bit for bit against the golden model, and prints one table: cycles, rays per cycle, efficiency
(ideal cycles / cycles), the utilisation of each unit and of the busiest one
(docs/architecture.md, "Counters"), and the simulation's speed. Two more tables light the scenes
with their own lights (--lighting scene, mirror and refraction rays to the default depth): the
frame with its secondary rays made on chip (the tree controller rc_tracer, docs/architecture.md
"The tracer") against the same frame's primary rays alone and against the host's passes
(--secondary host: the core alone traces each level's shadow, mirror and refraction packets after
the primary frame), and each ray kind's figures in the on-chip frame: rays, rays per cycle, its
share of the traversal and intersection units, its efficiency (its ideal cycles over the frame's
cycles). It measures; it judges nothing but the bit-exact check (a run that differs from the
golden model fails it).

Usage: bench_core.py RAYCORE [--models DIR] [--jobs N] [--markdown FILE] [--quick] [--lit-only]
"""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys
import tempfile
import time

# (label, input, size, extra raycore options)
SCENES = [
    ("default", "scenes/default.json", "256x192", []),
    ("conference", "scenes/conference.json", "256x192", []),
    ("sponza", "scenes/sponza.json", "256x192", []),
    ("terrain", "scenes/terrain.json", "256x192", []),
    ("spheres", "scenes/spheres.json", "256x192", []),
    ("bunny", "{models}/bunny/bunny.obj", "512x384", ["--auto-camera"]),
]
# The lit scenes (their own lights, shadow, mirror and refraction rays traced by the core), at
# latency 16.
LIT_SCENES = ["default", "spheres", "sponza", "conference"]
# Lit only: the box with a mirror block, the shared box with a mirror and a glass sphere, and the
# conference room with one light (the target).
LIT_EXTRA = [("cornell-mirror", "scenes/cornell-mirror.json", "256x192", []),
             ("cornell-glass", "scenes/cornell-glass.json", "256x192", []),
             ("conference-one-light", "scenes/conference-one-light.json", "256x192", [])]
LATENCIES = [1, 16, 64]
THREADS = ["16", "64", "default"]
# The cores with fewer ray set-up units than the default (docs/spec.toml [core] setup_units), at
# latency 16 and the default threads: what the set-up units buy.
SETUP_UNITS = ["1", "2"]

# SaarCOR's published figures (docs/architecture.md, "Performance"; ../shared/papers): the share
# of the ideal rate one RTC reached with 16 and 32 threads, in cycle-accurate simulation.
SAARCOR = "SaarCOR (simulated, 64-ray packets): 16 threads 70-80% of the ideal rate, 32 threads 80-90%"


def run(raycore, root, models, scene, latency, threads, setup_units="default", lit=None):
    label, inp, size, extra = scene
    inp = inp.format(models=models)
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "s.json")
        cmd = [raycore, "render", inp, "--engine", "rtl", "--check", "--size", size,
               "--latency", str(latency), "--threads-rtl", threads,
               "--setup-units-rtl", setup_units, "-q",
               "-o", os.path.join(tmp, "i.png"), "--stats", stats] + extra
        if lit:  # where the secondary rays are made: chip or host
            cmd += ["--lighting", "scene", "--secondary", lit]
        if models:
            cmd += ["--models-path", models]
        start = time.monotonic()
        p = subprocess.run(cmd, cwd=root, capture_output=True, text=True)
        wall = time.monotonic() - start
        if p.returncode != 0 or not os.path.exists(stats):
            return {"label": label, "latency": latency, "threads": threads,
                    "setup_units": setup_units, "error":
                    (p.stderr or p.stdout).strip().splitlines()[-1:] or ["failed"], "wall": wall}
        with open(stats) as f:
            d = json.load(f)
    r = d["rtl"]
    return {"label": label, "latency": latency, "threads": r["threads"],
            "setup_units": r["setup_units"], "size": size,
            "cycles": r["cycles"], "rays_per_cycle": r["rays_per_cycle"],
            "efficiency": r["efficiency"], "util": r["utilisation"],
            "busiest": r["busiest_unit"], "pass": d["check"]["pass"],
            "speed": r["simulated_cycles_per_second"], "wall": wall,
            "frame_cycles": r.get("frame_cycles", r["cycles"]), "kinds": r.get("kinds"),
            "shadow": r.get("shadow_pass"), "bounce": r.get("bounce_pass"),
            "refract": r.get("refract_pass")}


KINDS = (("primary", "primary"), ("shadow", "shadow"), ("bounce", "mirror"),
         ("refract", "refraction"))


def failed(x):
    return "error" in x or not x["pass"]


def lit_frame_table(lit):
    """Per scene: the primary frame alone, the lit frame on chip, and with the host's passes."""
    head = ("| scene | size | primary only | on chip | on chip / primary | host passes "
            "| host / primary | on chip: rays/cycle | efficiency | busiest unit | bit-exact |")
    lines = [head, "|" + "---|" * 11]
    for p, c, h in lit:
        runs = [x for x in (p, c, h) if x is not None]
        if any(failed(x) for x in runs):
            why = " ".join((x.get("error") or ["not bit-exact"])[0] for x in runs if failed(x))
            lines.append(f"| {c['label']} | | failed: {why} |" + " |" * 8)
            continue
        host = (f"{h['frame_cycles']:,} | {h['frame_cycles'] / p['cycles']:.2f}" if h else
                "not run | ")
        lines.append(
            f"| {c['label']} | {c['size']} | {p['cycles']:,} | {c['cycles']:,} | "
            f"{c['cycles'] / p['cycles']:.2f} | {host} | {c['rays_per_cycle']:.3f} | "
            f"{c['efficiency']:.3f} | {c['busiest']['unit']} {c['busiest']['utilisation']:.3f} "
            f"| yes |")
    return "\n".join(lines)


def lit_kind_table(lit):
    """Per scene and ray kind, in the on-chip frame (every kind in the core together)."""
    head = ("| scene | kind | rays | traversal steps | triangle tests | rays/cycle "
            "| trav share | isect share | efficiency |")
    lines = [head, "|" + "---|" * 9]
    for _, c, _ in lit:
        if failed(c):
            continue
        for key, name in KINDS:
            k = c["kinds"][key]
            if key != "primary" and key != "shadow" and k["rays"] == 0:
                continue
            lines.append(
                f"| {c['label']} | {name} | {k['rays']:,} | {k['traversal_steps']:,} | "
                f"{k['triangle_tests']:,} | {k['rays_per_cycle']:.4f} | "
                f"{k['trav_utilisation']:.3f} | {k['isect_utilisation']:.3f} | "
                f"{k['efficiency']:.3f} |")
    return "\n".join(lines)


def table(rows):
    head = ("| scene | size | latency | threads | set-up units | cycles | rays/cycle | efficiency "
            "| busiest unit | setup | trav | list | isect | shade | bit-exact | sim cycles/s |")
    lines = [head, "|" + "---|" * 16]
    for x in rows:
        if "error" in x:
            lines.append(f"| {x['label']} | | {x['latency']} | {x['threads']} | "
                         f"{x['setup_units']} | failed: {' '.join(x['error'])} |" + " |" * 10)
            continue
        u = x["util"]
        lines.append(
            f"| {x['label']} | {x['size']} | {x['latency']} | {x['threads']} | "
            f"{x['setup_units']} | {x['cycles']:,} | "
            f"{x['rays_per_cycle']:.3f} | {x['efficiency']:.3f} | {x['busiest']['unit']} "
            f"{x['busiest']['utilisation']:.3f} | {u['setup']:.2f} | {u['trav']:.2f} | "
            f"{u['list']:.2f} | {u['isect']:.2f} | {u['shade']:.2f} | "
            f"{'yes' if x['pass'] else 'NO'} | {x['speed']:,.0f} |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("raycore")
    ap.add_argument("--models", default="", help="the shared test models' directory")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--markdown", help="also write the table to this file")
    ap.add_argument("--quick", action="store_true",
                    help="latency 16, the default threads and set-up units only")
    ap.add_argument("--lit-only", action="store_true", help="the lit tables only")
    ap.add_argument("--scenes", help="only these scenes (labels, comma-separated)")
    ap.add_argument("--no-host", action="store_true",
                    help="lit scenes: no run with the host's passes (--secondary host)")
    a = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    models = os.path.abspath(a.models) if a.models else ""
    scenes = [s for s in SCENES if models or "{models}" not in s[1]]
    if len(scenes) < len(SCENES):
        print("bench-core: no shared models directory: bunny left out", file=sys.stderr)
    lit_extra = LIT_EXTRA
    if a.scenes:
        only = a.scenes.split(",")
        known = {s[0] for s in SCENES + LIT_EXTRA}
        unknown = [x for x in only if x not in known]
        if unknown:
            ap.error(f"unknown scene {', '.join(unknown)} (known: {', '.join(sorted(known))})")
        scenes = [s for s in scenes if s[0] in only]
        lit_extra = [s for s in LIT_EXTRA if s[0] in only]
    lats = [16] if a.quick else LATENCIES
    thrs = ["default"] if a.quick else THREADS
    jobs = [] if a.lit_only else [(s, l, t) for s in scenes for t in thrs for l in lats]
    if not a.quick and not a.lit_only:
        jobs += [(s, 16, "default", n) for s in scenes for n in SETUP_UNITS]
    lit_scenes = [s for s in scenes if s[0] in LIT_SCENES] + lit_extra
    # Per lit scene three runs: its primary rays alone (headlight), on chip, host passes.
    lit_modes = (None, "chip") if a.no_host else (None, "chip", "host")
    lit_jobs = [(s, lit) for s in lit_scenes for lit in lit_modes]
    start = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        rows = list(ex.map(lambda j: run(a.raycore, root, models, *j), jobs))
        lit_runs = list(ex.map(lambda j: run(a.raycore, root, models, j[0], 16, "default",
                                             lit=j[1]), lit_jobs))
    n = len(lit_modes)
    lit = [tuple(lit_runs[i:i + n]) + (None,) * (3 - n) for i in range(0, len(lit_runs), n)]
    lit_rows = lit_runs
    text = table(rows) if rows else ""
    text += ("\n\nLit by the scenes' own lights (--lighting scene, mirror and refraction rays to "
             "the default depth), latency 16, the default threads: cycles of the primary rays "
             "alone (the headlight), of the lit frame with its secondary rays made on chip "
             "(rc_tracer) and with the host's passes (--secondary host: the primary frame, then "
             "each level's shadow, mirror and refraction packets, summed)\n\n" +
             lit_frame_table(lit) +
             "\n\nPer ray kind in the on-chip frame: rays/cycle, each unit's share and the "
             "efficiency are over the whole frame's cycles (the kinds share the core)\n\n" +
             lit_kind_table(lit))
    print(text)
    print()
    print(SAARCOR)
    print(f"{len(rows) + len(lit_rows)} runs in {time.monotonic() - start:.0f} s")
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write(text + "\n\n" + SAARCOR + "\n")
    bad = [x for x in rows + lit_rows if "error" in x or not x["pass"]]
    for x in bad:
        print(f"bench-core: {x['label']} latency {x['latency']} threads {x['threads']} "
              f"set-up units {x['setup_units']}: "
              f"{' '.join(x.get('error', ['not bit-exact']))}", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
