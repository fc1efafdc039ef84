#!/usr/bin/env python3
"""The fine pass's timeline (docs/rendering.md, "The fine pass's timeline"): per workgroup of the compute
rasterizer's fine pass, when it started and ended, on which SM, and its tile's entries, loads and chunks.

A development measurement, not a product feature: the instrumentation reads the device clock in the shader
(VK_KHR_shader_clock, GL_EXT_shader_realtime_clock) and the SM id (VK_NV_shader_sm_builtins), so it lives in a patch
that is applied to a throw-away tree, built, run and reverted:

    git apply scripts/dev/fine-timeline.patch
    cmake --preset portable && cmake --build --preset portable --target tressvk-bench
    TVK_PROFILE_DUMP=ratboy.bin build/portable/engine/tressvk-bench render --asset RATBOY4.tvkhair \
        --width 1920 --height 1080 --frames 20 --warmup 30 --animate shake --no-pass-timestamps --json ratboy.json
    git apply -R scripts/dev/fine-timeline.patch
    scripts/dev/fine-timeline.py ratboy.bin 1920 1080

The patched build also prints each compute pipeline's registers and shared memory (PIPESTATS lines on stderr,
VK_KHR_pipeline_executable_properties). Its captured frame is not an image (the dump replaces the layer; the error
keys of the JSON mean nothing). The dump holds the records of every tile a frame of the run listed, the last one
written per tile; this script keeps the last full frame (records closer than 0.5 ms apart).
"""
import heapq
import sys

import numpy as np


def load(path, width, height):
    tiles = ((width + 7) // 8) * ((height + 7) // 8)
    r = np.fromfile(path, dtype=np.uint32)[: tiles * 8].reshape(tiles, 8)
    t0 = r[:, 0].astype(np.uint64) | (r[:, 1].astype(np.uint64) << np.uint64(32))
    t1 = r[:, 2].astype(np.uint64) | (r[:, 3].astype(np.uint64) << np.uint64(32))
    count, sm, loads, chunks = r[:, 4].astype(np.int64), r[:, 5], r[:, 6], r[:, 7]
    ok = (t0 > 0) & (count > 0) & (count < 10**7) & (t1 >= t0) & (t1 - t0 < 10**8)
    idx = np.where(ok)[0]
    idx = idx[np.argsort(t1[idx])]
    ends = t1[idx].astype(np.int64)
    cuts = [0] + list(np.where(np.diff(ends) > 500_000)[0] + 1) + [len(ends)]
    # The largest of the last three clusters: the last frame may be one the bench captured with few tiles.
    size, a, b = max((cuts[i + 1] - cuts[i], cuts[i], cuts[i + 1]) for i in range(max(0, len(cuts) - 4), len(cuts) - 1))
    sel = np.sort(idx[a:b])
    start = t0[sel].astype(np.int64)
    origin = start.min()
    s = (start - origin) / 1000.0
    e = (t1[sel].astype(np.int64) - origin) / 1000.0
    return s, e, count[sel], sm[sel], loads[sel], chunks[sel]


def replay(durations, order, slots):
    free = [0.0] * slots
    end = 0.0
    for i in order:
        t = heapq.heappop(free) + durations[i]
        end = max(end, t)
        heapq.heappush(free, t)
    return end


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    s, e, count, sm, loads, chunks = load(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
    d = e - s
    print(f"{len(d)} workgroups, span {e.max():.1f} us, {len(np.unique(sm))} SMs")
    print("| tile entries | tiles | mean us per workgroup | longest | mean chunks | mean loads |")
    print("|---|---|---|---|---|---|")
    for lo, hi in [(1, 64), (65, 256), (257, 1024), (1025, 2048), (2049, 8192), (8193, 1 << 40)]:
        m = (count >= lo) & (count <= hi)
        if m.any():
            print(f"| {lo}-{hi if hi < 1 << 40 else ''} | {m.sum()} | {d[m].mean():.0f} | {d[m].max():.0f} | "
                  f"{chunks[m].mean():.1f} | {loads[m].mean():.1f} |")
    probes = np.linspace(0.0, e.max(), 12)[1:-1]
    running = [int(((s <= t) & (e > t)).sum()) for t in probes]
    print("workgroups running at tenths of the span:", running)
    slots = max(running)
    ids = np.arange(len(d))
    print(f"replayed through {slots} slots: in the measured start order {replay(d, np.argsort(s), slots):.0f} us, "
          f"heaviest first {replay(d, np.argsort(-count, kind='stable'), slots):.0f} us, "
          f"longest first (no order can beat it) {replay(d, np.argsort(-d, kind='stable'), slots):.0f} us")
    slow = np.argsort(-d)[:5]
    rank = np.argsort(np.argsort(-count))
    for i in slow:
        print(f"  slow: {d[i]:.0f} us, {count[i]} entries (rank {rank[i]} by entries), started at {s[i]:.0f} us")


if __name__ == "__main__":
    main()
