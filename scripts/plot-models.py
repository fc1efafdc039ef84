#!/usr/bin/python3
"""GPU time per frame against model error for the three simulation models, from scripts/gpu-models.sh.

    /usr/bin/python3 scripts/plot-models.py OUTDIR OUT.png [OUT.md]

Reads OUTDIR/sweep-MODEL-GROOM.csv (`tressvk-bench sweep --csv`). One panel per groom: each setting (step rate /
local iterations) of each model as a point, the worst scene's model error rms (trajectory distance from the converged
reference of the same model / median strand length) on x, the slowest scene's GPU ms per frame on y, each model's
default marked. OUT.md (or stdout) gets the same rows as a table, with the worst stretch and step error.
"""
import csv
import os
import sys

MODELS = [("follow-the-leader", "follow-the-leader (default)", "tab:blue"),
          ("compliant", "compliant", "tab:orange"),
          ("conservative", "conservative local shape", "tab:green")]
GROOMS = ["curly", "straight"]


def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    out = {}
    for r in rows:
        k = (float(r["step_rate_hz"]), int(r["local_iterations"]))
        e = out.setdefault(k, {"ms": 0.0, "err": 0.0, "stretch": 0.0, "step": 0.0, "default": False,
                               "guides": int(r["guides"]), "scenes": {}})
        e["ms"] = max(e["ms"], float(r["gpu_ms_per_frame"]))
        e["err"] = max(e["err"], float(r["model_error_rms"]))
        e["stretch"] = max(e["stretch"], float(r["stretch_max"]))
        e["step"] = max(e["step"], float(r["step_error_max"]))
        e["default"] = e["default"] or r["is_default"] == "1"
        e["scenes"][r["scene"]] = float(r["model_error_rms"])
    return out


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    outdir, png = sys.argv[1], sys.argv[2]
    data = {}
    for g in GROOMS:
        for m, _, _ in MODELS:
            p = os.path.join(outdir, f"sweep-{m}-{g}.csv")
            if os.path.exists(p):
                data[(m, g)] = load(p)
    lines = ["| groom | model | rate / local iterations | ms per frame (slowest scene) | model error rms, worst scene "
             "(settle / shake / run / wind) | worst stretch | worst step error |", "|---|---|---|---|---|---|---|"]
    for g in GROOMS:
        for m, name, _ in MODELS:
            for (rate, it), e in sorted(data.get((m, g), {}).items()):
                sc = " / ".join(f"{e['scenes'].get(s, float('nan')):.3g}" for s in ["settle", "shake", "run", "wind"])
                mark = " (default)" if e["default"] else ""
                lines.append(f"| {g} | {name} | {rate:.0f} Hz / {it}{mark} | {e['ms']:.3f} | {e['err']:.3g} ({sc}) | "
                             f"{e['stretch']:.2g} | {e['step']:.2g} |")
    text = "\n".join(lines) + "\n"
    if len(sys.argv) > 3:
        with open(sys.argv[3], "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(GROOMS), figsize=(6.2 * len(GROOMS), 4.8), squeeze=False)
    for ax, g in zip(axes[0], GROOMS):
        guides = None
        for m, name, color in MODELS:
            pts = data.get((m, g))
            if not pts:
                continue
            for (rate, it), e in sorted(pts.items()):
                guides = e["guides"]
                marker = "o" if it == 1 else "s"
                ax.scatter(e["err"], e["ms"], color=color, marker=marker, s=90 if e["default"] else 36,
                           edgecolors="black" if e["default"] else "none", zorder=3)
                ax.annotate(f"{rate:.0f}/{it}", (e["err"], e["ms"]), textcoords="offset points", xytext=(5, 3),
                            fontsize=7, color=color)
            ax.scatter([], [], color=color, label=name)
        ax.set_xscale("log")
        ax.set_xlabel("model error, rms / median strand length (worst of settle, shake, run, wind)")
        ax.set_ylabel("GPU ms per frame (slowest scene)")
        ax.set_title(f"{g}, {guides} guides x 32 vertices" if guides else g)
        ax.grid(True, which="both", alpha=0.3)
        ax.scatter([], [], color="gray", marker="o", label="1 local iteration (label: Hz / iterations)")
        ax.scatter([], [], color="gray", marker="s", label="2 local iterations")
        ax.scatter([], [], facecolors="none", edgecolors="black", s=90, label="the model's own setting (the sweep's default row)")
        ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main()
