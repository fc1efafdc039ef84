#!/usr/bin/python3
"""GPU time per character against the size of a crowd, from the JSON files of `CROWD=1 scripts/gpu-perf.sh`.

    /usr/bin/python3 scripts/plot-crowd.py OUTDIR docs/images/sim-crowd.png

Debian's python3-matplotlib. Reads OUTDIR/crowd-K-PATH-RATE.json (K instances of one groom in one
tressvk_cmd_simulate, the kernel PATH forced: runs4, runs8 or fused, at RATE Hz) and draws, per step rate, the
microseconds per instance (the crowd's frame time over K) against K for each kernel, log-log. The step error of every
point is in its JSON file and in the table of docs/simulation.md ("A crowd"); the dotted line is the 25 us target for
one Ratboy at 240 Hz.
"""
import glob
import json
import os
import re
import sys

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "runs4": "runs of 4 (this groom alone)",
    "runs8": "runs of 8",
    "fused": "one thread per strand (a crowd of 400 k guide vertices)",
}
TARGET_240HZ_US = 25.0  # the speed issue's target for Ratboy + 2 follows at 240 Hz
STYLES = {"runs4": "o-", "runs8": "s--", "fused": "^-."}


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    series = {}  # (rate, path) -> [(instances, us per instance)]
    device = groom = ""
    for path in glob.glob(os.path.join(sys.argv[1], "crowd-*.json")):
        m = re.match(r"crowd-(\d+)-(\w+)-(\d+)\.json$", os.path.basename(path))
        if not m:
            continue
        with open(path) as f:
            d = json.load(f)
        k, kernel, rate = int(m.group(1)), m.group(2), int(m.group(3))
        series.setdefault((rate, kernel), []).append((k, 1e3 * d["gpu_ms_per_frame"] / k))
        device, groom = d.get("device", device), d.get("groom", groom)
    if not series:
        sys.exit("plot-crowd.py: no crowd-*.json in " + sys.argv[1])
    rates = sorted({r for r, _ in series}, reverse=True)
    fig, axes = plt.subplots(1, len(rates), figsize=(5.2 * len(rates), 4.2), sharey=True, squeeze=False)
    for ax, rate in zip(axes[0], rates):
        for kernel in ("runs4", "runs8", "fused"):
            pts = sorted(series.get((rate, kernel), []))
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], STYLES[kernel], label=LABELS[kernel])
        if rate == 240:
            ax.axhline(TARGET_240HZ_US, color="grey", linestyle=":", label="target for one groom at 240 Hz")
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xticks([k for k in (1, 2, 4, 8, 16, 32, 64, 128, 256) if any(k == p[0] for v in series.values() for p in v)])
        ax.set_yticks([10, 20, 50, 100, 200, 500])
        ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        ax.yaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_xlabel("instances in one tressvk_cmd_simulate")
        ax.set_title(f"{rate} Hz")
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("GPU µs per instance per frame")
    axes[0][0].legend(fontsize=8)
    fig.suptitle(f"{groom}: a crowd, {device}", fontsize=10)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
