#!/usr/bin/python3
"""Speed against error of the hair renderer, from the JSON files of scripts/gpu-render-bench.sh.

    /usr/bin/python3 scripts/plot-render-bench.py OUTDIR docs/images/render_speed_error.png

Debian's python3-matplotlib (installed for /usr/bin/python3). One point per compute-path row: GPU time of the
hair (shadow + shading, median) against the mean error versus the sorted reference, labelled with the row name;
the 99th percentile is drawn as the upper end of each point's bar.
"""
import glob
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = []
    for path in sorted(glob.glob(os.path.join(sys.argv[1], "*.json"))):
        with open(path) as f:
            r = json.load(f)
        if r.get("path") != "compute" or r.get("error_mean") is None:
            continue
        if r.get("shading") == "per fragment":  # compared with a per-vertex-shaded reference: not the raster error
            continue
        rows.append((os.path.basename(path)[:-5], r))
    if not rows:
        sys.exit("no compute rows with an error in " + sys.argv[1])
    fig, ax = plt.subplots(figsize=(8, 5), dpi=110)
    # Named in a legend, in order of time (labels beside the points overprint where rows cost about the same).
    rows.sort(key=lambda row: row[1]["gpu_ms_shadow"] + row[1]["gpu_ms_shading"])
    for name, r in rows:
        ms = r["gpu_ms_shadow"] + r["gpu_ms_shading"]
        ax.errorbar(ms, r["error_mean"], yerr=[[0], [r["error_p99"] - r["error_mean"]]], fmt="o", capsize=3,
                    label=f"{name}: {ms:.2f} ms, {r['error_mean']:.2f} / {r['error_p99']:.2f}")
    ax.legend(fontsize=7, loc="upper left", title="row: hair ms, error mean / p99", title_fontsize=7)
    ax.axhline(1.0, color="grey", linestyle="--", linewidth=0.8)
    ax.text(ax.get_xlim()[1], 1.0, " mean target 1/255", va="bottom", ha="right", fontsize=7, color="grey")
    ax.set_xscale("log")
    ax.set_xlabel("GPU ms per frame, hair shadow + shading (median)")
    ax.set_ylabel("error vs sorted reference, 1/255 (dot: mean, bar: to p99)")
    ax.set_title("Compute strand rasterizer: speed against error (" + rows[0][1]["device"].split(" (")[0] + ")")
    ax.grid(True, which="both", linewidth=0.3)
    fig.tight_layout()
    fig.savefig(sys.argv[2])


if __name__ == "__main__":
    main()
