#!/usr/bin/env python3
"""Writes the fuzz seed corpora: small valid inputs cut from the real data (shared/data) and the tests' own
inputs, so every target starts from files that get through its parser. Nothing large is committed; scripts/fuzz.sh
runs this into build/fuzz/corpus/<target>/ before fuzzing.

  make_seeds.py OUT_DIR DATA_DIR [TRESSVK_BAKE]

Without TRESSVK_BAKE (the baker executable) the .tvkhair seeds are skipped. Each seed stays under 4 KB (the
fuzzers' -max_len) so that libFuzzer never truncates one into an invalid file."""
import os
import struct
import subprocess
import sys
import tempfile

MAX = 4000
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def write(out, target, name, data):
    d = os.path.join(out, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def small_obj(text, budget=MAX):
    """The first vertices of an OBJ and the `l`/`f` records that use only them, within `budget` bytes."""
    verts, others = [], []
    for line in text.splitlines():
        if line.startswith("v "):
            verts.append(line)
    # Take as many vertices as leave room for their records.
    for m in (64, 40, 24, 12):
        chosen = verts[:m]
        recs = []
        for line in text.splitlines():
            if line.startswith(("l ", "f ")):
                idx = [int(t.split("/")[0]) for t in line.split()[1:]]
                if idx and all(0 < i <= m for i in idx):
                    recs.append(line)
            elif line.startswith(("o ", "g ")) and len(recs) < 2:
                recs.append(line)
        body = "\n".join(chosen + recs) + "\n"
        if len(body) <= budget and any(r.startswith("l ") for r in recs):
            return body.encode()
    return None


def small_tfx(b, budget=MAX):
    version, strands, n = struct.unpack_from("<fII", b, 0)
    if 3.0 <= version < 4.0:
        header, stride = 296, 12
        pos = struct.unpack_from("<I", b, 144)[0] or 296
        uv = 0
    else:
        header, stride = 160, 16
        pos, uv = struct.unpack_from("<II", b, 12)
        pos = pos or 160
    keep = max(1, min(strands, (budget - header) // (n * stride + (8 if uv else 0))))
    if (budget - header) < n * stride:
        return None
    out = bytearray(b[:header])
    struct.pack_into("<I", out, 4, keep)
    positions = b[pos:pos + keep * n * stride]
    if header == 296:
        struct.pack_into("<I", out, 144, 296)
        out += positions
    else:
        struct.pack_into("<I", out, 12, 160)
        if uv:
            struct.pack_into("<I", out, 16, 160 + len(positions))
            out += positions + b[uv:uv + 8 * keep]
        else:
            out += positions
    return bytes(out)


def small_tfxbone(b, keep=24):
    """The bone table and the records of the first `keep` strands, prefixed with the fuzz target's strand count."""
    at = 0
    bones = struct.unpack_from("<i", b, at)[0]
    at += 4
    for _ in range(bones):
        _, length = struct.unpack_from("<ii", b, at)
        at += 8 + length
    table = b[:at]
    strands = struct.unpack_from("<i", b, at)[0]
    at += 4
    rest = b[at:]
    if len(rest) != 36 * strands:
        return None  # only the fixed 4.x layout is cut here; the 5.x seed below is hand-made
    keep = min(keep, strands)
    records = [rest[i * 36:(i + 1) * 36] for i in range(strands)]
    chosen = [r for r in records if struct.unpack_from("<i", r, 0)[0] < keep]
    if len(chosen) != keep:
        return None
    return struct.pack("<H", keep - 1) + table + struct.pack("<i", keep) + b"".join(chosen)


def tfxbone_5x():
    b = struct.pack("<i", 2)
    for i in range(2):
        b += struct.pack("<ii", i, 3) + b"b%d\0" % i
    b += struct.pack("<i", 3)
    for s in range(3):
        b += struct.pack("<iiifif", s, 2, 0, 0.7, 1, 0.3)
    return struct.pack("<H", 2) + b


def tfx_v4_with_uv():
    strands, n = 3, 4
    b = bytearray(160)
    struct.pack_into("<fIIII", b, 0, 4.0, strands, n, 160, 160 + strands * n * 16)
    for s in range(strands):
        for v in range(n):
            b += struct.pack("<ffff", 0.1 * s, 0.05 * v, 0.01 * v * v, 0.0 if v < 2 else 1.0)
    for s in range(strands):
        b += struct.pack("<ff", 0.5, 0.25 * s)
    return bytes(b)


def main():
    out, data = sys.argv[1], sys.argv[2]
    bake_exe = sys.argv[3] if len(sys.argv) > 3 else None
    objs, tfxs = {}, {}
    with open(os.path.join(ROOT, "tests/baker/data/tiny_groom.obj"), "rb") as f:
        objs["tiny_groom"] = f.read()
    objs["mixed_records"] = (b"# groom\r\no hair\nv 0 0 0\nv 0 0.1 0.001\nv 0 0.2 0.003\nv 0 0.3 0.006\nl 1 2\n"
                             b"l 2 3\nl 3 4\ng two\nv 1 0 0\nv 1 0.1 0\nv 1 0.2 0\nl -3 -2 -1\nvn 0 1 0\n"
                             b"vt 0.5 0.5\nf 1 2 5\nv 2 0 0\nv 2 0.1 0\nv 2 0.2 0\nv 2 0.3 0\nl 8/1 9/1 10/1 11/1\n")
    tfxs["v4_uv"] = tfx_v4_with_uv()
    for rel in ("unity/Cube_Hair.obj", "sintel/sintel.obj"):
        p = os.path.join(data, rel)
        if os.path.exists(p):
            with open(p, encoding="utf-8", errors="replace") as f:
                s = small_obj(f.read())
            if s:
                objs[os.path.basename(rel)[:-4]] = s
    for dirpath, _, files in os.walk(data):
        for name in sorted(files):
            if name.endswith(".tfx"):
                with open(os.path.join(dirpath, name), "rb") as f:
                    s = small_tfx(f.read())
                if s:
                    tfxs[name[:-4]] = s
            if name.endswith(".tfxbone"):
                with open(os.path.join(dirpath, name), "rb") as f:
                    s = small_tfxbone(f.read())
                if s:
                    write(out, "tfxbone", name[:-8], s)
    write(out, "tfxbone", "layout5x", tfxbone_5x())
    for k, v in objs.items():
        write(out, "obj", k, v)
        # bake: OBJ, N 8, one follow, 2 pinned; and N 4, Z up, faces for roots, skip invalid
        write(out, "bake", "obj_" + k, bytes([0, 4, 1, 2]) + v)
        write(out, "bake", "obj_z_" + k, bytes([2 | 64 | 128, 0, 0, 2]) + v)
    for k, v in tfxs.items():
        write(out, "tfx", k, v)
        write(out, "bake", "tfx_" + k, bytes([1, 12, 2, 2]) + v)
    if bake_exe:
        with tempfile.TemporaryDirectory() as tmp:
            for k, v in list(objs.items()) + list(tfxs.items()):
                src = os.path.join(tmp, k + (".tfx" if k in tfxs else ".obj"))
                with open(src, "wb") as f:
                    f.write(v)
                for n, follow in ((4, 1), (6, 0)):
                    dst = os.path.join(tmp, "%s_%d.tvkhair" % (k, n))
                    r = subprocess.run([bake_exe, src, "-o", dst, "--vertices", str(n), "--follow", str(follow),
                                        "-q"], capture_output=True)
                    if r.returncode == 0 and os.path.getsize(dst) <= 64 * 1024:
                        with open(dst, "rb") as f:
                            b = f.read()
                        write(out, "tvkhair", "%s_%d" % (k, n), b)
                        write(out, "plugin_load", "%s_%d" % (k, n), b)
    for t in sorted(os.listdir(out)):
        print("seeds: %-12s %d file(s)" % (t, len(os.listdir(os.path.join(out, t)))))


if __name__ == "__main__":
    main()
