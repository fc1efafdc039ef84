#!/usr/bin/python3
"""Pareto fronts of GPU time per frame against model error, from `tressvk-bench sweep --json` (scripts/gpu-sweep.sh).

    /usr/bin/python3 scripts/plot-pareto.py SWEEP.json OUT.png [OUT.md]

Debian's python3-matplotlib (optional at test time: only this script needs it). One panel per scene: every
configuration (step rate / local iterations / length iterations / vertices per strand) as a point, model error rms
(trajectory distance from the converged reference / median strand length) on x, GPU ms per frame on y, the front
(configurations no other beats on both) as a line, the default marked. OUT.md (or stdout) gets the table of which
setting to pick for a GPU budget of 0.1 / 0.25 / 0.5 / 1 ms per groom: the lowest worst-scene model error among the
settings whose slowest scene fits the budget.
"""
import json
import sys

BUDGETS_MS = [0.1, 0.25, 0.5, 1.0]


def label(r):
    return f"{r['step_rate_hz']:.0f} Hz / {r['local_iterations']} / {r['length_iterations']} / N {r['vertices_per_strand']}"


def key(r):
    return (r["step_rate_hz"], r["local_iterations"], r["length_iterations"], r["vertices_per_strand"])


def front(rows):
    """Configurations that no other is both faster and more accurate than, fastest first."""
    out, best = [], float("inf")
    for r in sorted(rows, key=lambda r: (r["gpu_ms_per_frame"], r["model_error_rms"])):
        if r["model_error_rms"] < best:
            out.append(r)
            best = r["model_error_rms"]
    return out


def budget_table(doc):
    rows = doc["rows"]
    scenes = sorted({r["scene"] for r in rows})
    by_setting = {}
    for r in rows:
        by_setting.setdefault(key(r), {})[r["scene"]] = r
    settings = [(k, v) for k, v in by_setting.items() if len(v) == len(scenes)]
    lines = [
        f"Budget per groom ({doc['groom']}, {doc['guides']} guides; {doc['device']}): the setting (step rate / local "
        "iterations / length iterations / vertices per strand) with the lowest worst-scene model error rms among those "
        "whose slowest scene fits.",
        "",
        "| budget | setting | slowest scene ms | worst model error rms (scene) | worst model error max | default fits? |",
        "|---|---|---|---|---|---|",
    ]
    default = next((v for k, v in settings if any(r["is_default"] for r in v.values())), None)
    for budget in BUDGETS_MS:
        fits = [(k, v) for k, v in settings if max(r["gpu_ms_per_frame"] for r in v.values()) <= budget]
        if not fits:
            lines.append(f"| {budget} ms | none fits | | | | |")
            continue
        k, v = min(fits, key=lambda kv: max(r["model_error_rms"] for r in kv[1].values()))
        worst = max(v.values(), key=lambda r: r["model_error_rms"])
        slowest = max(r["gpu_ms_per_frame"] for r in v.values())
        default_fits = default is not None and max(r["gpu_ms_per_frame"] for r in default.values()) <= budget
        lines.append(
            f"| {budget} ms | {label(worst)} | {slowest:.3f} | {worst['model_error_rms']:.3g} ({worst['scene']}) | "
            f"{max(r['model_error_max'] for r in v.values()):.3g} | {'yes' if default_fits else 'no'} |")
    on_front = []
    for scene in scenes:
        f = front([r for r in rows if r["scene"] == scene])
        d = [r for r in rows if r["scene"] == scene and r["is_default"]]
        on_front.append(f"{scene}: {'yes' if d and any(key(x) == key(d[0]) for x in f) else 'no'}")
    lines += ["", "Default on the front: " + ", ".join(on_front) + "."]
    return "\n".join(lines) + "\n"


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        doc = json.load(f)
    table = budget_table(doc)
    if len(sys.argv) == 4:
        with open(sys.argv[3], "w") as f:
            f.write(table)
    else:
        sys.stdout.write(table)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = doc["rows"]
    scenes = sorted({r["scene"] for r in rows})
    cols = 2 if len(scenes) > 1 else 1
    nrows = (len(scenes) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(6.5 * cols, 4.8 * nrows), squeeze=False)
    ref = doc["reference"]
    for ax, scene in zip(axes.flat, scenes):
        pts = [r for r in rows if r["scene"] == scene]
        ax.scatter([r["model_error_rms"] for r in pts], [r["gpu_ms_per_frame"] for r in pts], s=14, c="0.6",
                   label="configurations")
        f = front(pts)
        ax.plot([r["model_error_rms"] for r in f], [r["gpu_ms_per_frame"] for r in f], "-o", ms=4, c="tab:blue",
                label="front")
        for r in f:
            ax.annotate(label(r), (r["model_error_rms"], r["gpu_ms_per_frame"]), fontsize=6, xytext=(3, 3),
                        textcoords="offset points")
        for r in pts:
            if r["is_default"]:
                ax.scatter([r["model_error_rms"]], [r["gpu_ms_per_frame"]], marker="*", s=160, c="tab:red",
                           zorder=5, label="default " + label(r))
        for b in BUDGETS_MS:
            ax.axhline(b, lw=0.5, ls=":", c="0.4")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{doc['groom']} {doc['guides']} guides, {scene}", fontsize=9)
        ax.set_xlabel("model error rms (/ median strand length)", fontsize=8)
        ax.set_ylabel("GPU ms per frame", fontsize=8)
        ax.legend(fontsize=6, loc="upper right")
    for ax in list(axes.flat)[len(scenes):]:
        ax.axis("off")
    fig.suptitle(f"{doc['device']}; converged reference {ref['step_rate_hz']:.0f} Hz, {ref['local_iterations']} local / "
                 f"{ref['length_iterations']} length iterations, N {ref['vertices_per_strand']}, {doc['error_guides']} "
                 f"guides, {doc['frames']} frames", fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=130)


if __name__ == "__main__":
    main()
