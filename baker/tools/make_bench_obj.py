#!/usr/bin/env python3
"""Writes a synthetic OBJ groom for the baker speed figures in docs/baker.md (nothing big is committed).

usage: make_bench_obj.py OUT.obj [--strands 100000] [--vertices 32] [--style edges|records]
  edges:   Blender style, `v` records then one 2-index `l` edge per segment (the larger, harder form)
  records: Maya/Houdini style, one `l` record per strand
Strands grow from a sphere of radius 0.1 m with a gentle wave; the output is deterministic.
"""
import argparse
import math
import random


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--strands", type=int, default=100000)
    ap.add_argument("--vertices", type=int, default=32)
    ap.add_argument("--style", choices=["edges", "records"], default="edges")
    args = ap.parse_args()
    rng = random.Random(12345)
    n = args.vertices
    with open(args.out, "w", newline="\n") as f:
        f.write("# synthetic groom: %d strands x %d vertices\no hair\n" % (args.strands, n))
        golden = math.pi * (3 - math.sqrt(5))
        for s in range(args.strands):
            y = 1 - (s + 0.5) / args.strands
            r = math.sqrt(max(0.0, 1 - y * y))
            phi = golden * s
            nx, ny, nz = r * math.cos(phi), y, r * math.sin(phi)
            length = 0.15 + 0.1 * rng.random()
            lines = []
            for v in range(n):
                t = v / (n - 1)
                d = 0.1 + length * t
                w = 0.01 * math.sin(6 * t + s)
                lines.append("v %.6f %.6f %.6f\n" % (nx * d + w, ny * d - 0.05 * t * t, nz * d + w))
            f.write("".join(lines))
            base = s * n + 1
            if args.style == "edges":
                f.write("".join("l %d %d\n" % (base + v, base + v + 1) for v in range(n - 1)))
            else:
                f.write("l " + " ".join(str(base + v) for v in range(n)) + "\n")


if __name__ == "__main__":
    main()
