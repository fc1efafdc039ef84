#!/usr/bin/python3
"""Simulation time per frame against guide vertices, from the JSON files of scripts/gpu-perf.sh.

    /usr/bin/python3 scripts/plot-sim-perf.py OUTDIR docs/images/sim-perf.png

Debian's python3-matplotlib. One line per simulation path (the default choice, the one-thread frame kernel, pass per
dispatch, whichever the sweep ran) and step rate (sweep-PATH-GUIDES-RATE.json), log-log; AMD TressFX 4.1's own kernels on an NVIDIA H200 (one step, 3+3 iterations)
as points; and the bandwidth floor: the bytes a frame must move (bytes_per_frame) at the speed of a plain copy kernel
measured in the same run (the fastest copy_gb_per_s of the run; transfer_copy_gb_per_s, vkCmdCopyBuffer's, is not
the floor: a copy engine may move less). The step error of every point is in the JSON file and the tables of docs/simulation.md.
"""
import glob
import json
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TRESSFX_H200 = [(71072, 113.6), (1048576, 418.0), (4194304, 1608.0)]  # guide vertices, us per frame


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    series = {}
    floor = {}
    device = ""
    for path in sorted(glob.glob(os.path.join(sys.argv[1], "sweep-*.json"))):
        m = re.match(r"sweep-(.+)-(\d+)-(\d+)\.json$", os.path.basename(path))
        if not m:
            continue
        with open(path) as f:
            r = json.load(f)
        sim_path, rate = m.group(1), int(m.group(3))
        x = r["guide_vertices"]
        series.setdefault((sim_path, rate), []).append((x, 1e3 * r["gpu_ms_per_frame"], r["step_error_max_rel"]))
        if r.get("copy_gb_per_s", 0) > 0:
            b, c = floor.get(x, (0, 0.0))
            floor[x] = (max(b, r["bytes_per_frame"]), max(c, r["copy_gb_per_s"]))
        device = r.get("device", device)
    if not series:
        sys.exit("no sweep-*.json files in " + sys.argv[1])
    # Above 768 k guide vertices the default is the one-thread kernel, whose rows the sweep runs once (as fused).
    for (sim_path, rate), pts in list(series.items()):
        if sim_path == "fused" and ("default", rate) in series:
            have = {p[0] for p in series[("default", rate)]}
            series[("default", rate)] += [p for p in pts if p[0] > 768 * 1024 and p[0] not in have]
    fig, ax = plt.subplots(figsize=(8, 5.5))
    colours = {60: "tab:green", 120: "tab:orange", 240: "tab:blue"}
    looks = {  # path: (style, alpha, name)
        "default": ("-o", 1.0, "default (run kernel up to 768 k, then one thread per strand)"),
        "fused": ("--s", 0.6, "one thread per strand"),
        "passes": (":d", 0.5, "pass per dispatch"),
    }
    for (sim_path, rate), pts in sorted(series.items()):
        pts.sort()
        worst = max(p[2] for p in pts)
        style, alpha, name = looks.get(sim_path, ("-.", 0.6, sim_path))
        ax.plot([p[0] for p in pts], [p[1] for p in pts], style, color=colours.get(rate, "grey"),
                label=f"{name}, {rate} Hz (step error <= {worst:.1g})", markersize=4, alpha=alpha)
    ax.plot([p[0] for p in TRESSFX_H200], [p[1] for p in TRESSFX_H200], "k^", markersize=8,
            label="AMD TressFX 4.1 kernels, NVIDIA H200 (1 step, 3+3 iterations)")
    if floor:
        # The fastest copy of the run: a copy timed right after idle GPU time reads slow (clocks still low).
        speed = max(c for _, c in floor.values())
        xs = sorted(floor)
        ax.plot(xs, [floor[x][0] / (speed * 1e9) * 1e6 for x in xs], ":", color="black",
                label=f"bandwidth floor (frame bytes at {speed:.0f} GB/s, the run's fastest copy kernel)")
    ax.plot([71072, 1048576, 4194304], [25, 200, 600], "rx", markersize=9, label="issue 11 targets at 240 Hz")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("guide vertices")
    ax.set_ylabel("GPU time per frame (µs, median)")
    ax.set_title(f"TressVK simulation, scene shake, 2 local iterations, 1 length sweep\n{device.split('(')[0].strip()}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
