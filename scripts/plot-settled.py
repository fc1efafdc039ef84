#!/usr/bin/env python3
"""Settled grooms side by side (docs/accuracy.md, "The settled look against the settings").

    /usr/bin/python3 scripts/plot-settled.py OUT.png COLUMNS GUIDES N "LABEL=POSE" ...

Each POSE is a file written by `tressvk_rest_probe` with TVK_SAVE_POSE (the settled positions as float64 x, y, z, guide
vertices first), GUIDES x N of them drawn as one line a strand, seen from the side (z across, y up); "-" leaves a
panel empty. Panels fill COLUMNS a row. Needs Debian's python3-matplotlib.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main():
    if len(sys.argv) < 6:
        sys.exit(__doc__)
    out, cols, guides, n = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
    panels = sys.argv[5:]
    rows = (len(panels) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.2 * cols, 3.6 * rows), squeeze=False, sharex=True, sharey=True)
    for k, spec in enumerate(panels):
        ax = axes[k // cols][k % cols]
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        if spec == "-":
            ax.axis("off")
            continue
        label, path = spec.split("=", 1)
        strands = np.fromfile(path, dtype=np.float64).reshape(-1, 3)[: guides * n].reshape(guides, n, 3)
        for s in strands:
            ax.plot(s[:, 2], s[:, 1], color="#6b4a2b", linewidth=0.35, alpha=0.6)
        ax.plot(strands[:, -1, 2], strands[:, -1, 1], ".", color="#c0392b", markersize=1.0)
        ax.set_title(label, fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
