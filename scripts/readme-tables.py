#!/usr/bin/env python3
"""The README's "Measured" tables from the JSON files that scripts/gpu-readme.sh writes.

    python3 scripts/readme-tables.py OUTDIR

OUTDIR/sim/models-{ratboy,curly1M,curly4M}-default-{240,60}.json come from `tressvk-bench perf` (scripts/gpu-perf.sh,
MODELS=1 PATHS=default); OUTDIR/render/{ratboy4,100k}-compute-1080p.json from `tressvk-bench render`
(scripts/gpu-render-bench.sh); OUTDIR/host/ratboy-{1,64}[-bones]-r<k>.json (or one ratboy-{1,64}[-bones].json) from
`tressvk-bench perf [--bones]`, whose CPU times are the median of the rounds (a virtual machine's CPU time wanders by
up to 2x between runs). Prints the three tables as the README has them, and the device they ran on. A row whose file
is missing says so instead of a number.
"""
import glob
import json
import os
import statistics
import sys


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def short_e(x):
    """1.9e-06 -> 1.9e-6, as the README writes it."""
    mantissa, exponent = f"{x:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    sim_rows = [("ratboy", "Ratboy mohawk + 2 follows (71 k guide vertices)"),
                ("curly1M", "curly, 1 M guide vertices"),
                ("curly4M", "curly, 4 M guide vertices")]
    devices = set()
    print("| simulation, `shake`, defaults (240 Hz, 2 local iterations) | GPU µs per frame, 240 Hz / 60 Hz "
          "| step error (relative to the median strand length) |")
    print("|---|---|---|")
    for key, label in sim_rows:
        runs = [load(os.path.join(out, "sim", f"models-{key}-default-{rate}.json")) for rate in (240, 60)]
        if any(r is None for r in runs):
            print(f"| {label} | missing | |")
            continue
        devices.update(r["device"] for r in runs)
        times = " / ".join(f"{1e3 * r['gpu_ms_per_frame']:,.1f}" for r in runs)
        errors = " / ".join(short_e(r["step_error_max_rel"]) for r in runs)
        print(f"| {label} | {times} | {errors} |")
    print()
    render_rows = [("ratboy4-compute-1080p", "Ratboy mohawk + 4 follows ({n:,} strands)"),
                   ("100k-compute-1080p", "100,000 strands × 32")]
    print("| rendering, 1920×1080, shadow + shading | GPU ms per frame "
          "| error against a brute-force reference (mean / p99, 1/255) |")
    print("|---|---|---|")
    for key, label in render_rows:
        r = load(os.path.join(out, "render", f"{key}.json"))
        if r is None:
            print(f"| {label} | missing | |")
            continue
        devices.add(r["device"])
        ms = r["gpu_ms_shadow"] + r["gpu_ms_shading"]
        print(f"| {label.format(n=r['strands_drawn'])} | {ms:.2f} | {r['error_mean']:.2f} / {r['error_p99']:.2f} |")
    print()
    host = os.path.join(out, "host")
    rounds = {}
    for n in (1, 64):
        for suffix in ("", "-bones"):
            paths = sorted(glob.glob(os.path.join(host, f"ratboy-{n}{suffix}-r*.json")))
            paths = paths or [os.path.join(host, f"ratboy-{n}{suffix}.json")]
            rounds[(n, suffix)] = [r for r in (load(p) for p in paths) if r is not None]
    count = max((len(v) for v in rounds.values()), default=0)
    median_of = f", median of {count} runs" if count > 1 else ""
    print("| host CPU per frame (set_frame, new_frame, cmd_simulate), Ratboy + 2 follows, 240 Hz, `shake`"
          f"{median_of} | 1 instance: CPU ms (GPU ms) | 64 instances in one call: CPU ms (GPU ms) |")
    print("|---|---|---|")
    for suffix, label in (("", "moved by its transform"), ("-bones", "its 105 bones driven (`--bones`)")):
        cells = []
        for n in (1, 64):
            runs = rounds[(n, suffix)]
            if not runs:
                cells.append("missing")
                continue
            for r in runs:
                devices.add(r["device"])
            cpu = statistics.median(r["host_ms_per_frame"] for r in runs)
            gpu = statistics.median(r["gpu_ms_per_frame"] for r in runs)
            cells.append(f"{cpu:.3f} ({gpu:.3f})")
        print(f"| {label} | {cells[0]} | {cells[1]} |")
    print()
    for d in sorted(devices):
        print(f"device: {d}")


if __name__ == "__main__":
    main()
