#!/usr/bin/env python3
"""Writes the skinned test meshes of tests/data/skin (glTF 2.0, buffers inline):

  tube.gltf           a capped tube along +Y from 0 to 2, radius 0.25, two bones:
                      "root" at the origin, "upper" at y = 1 (its child). Vertices
                      below y = 0.8 follow root, above 1.2 follow upper, in between
                      both, linearly. Animation "bend": upper turns about +Z by 0
                      at t = 0, 90 degrees at t = 1, 0 again at t = 2 (linear keys).
  tube_bad_weights.gltf   the same with every weight 0 on one vertex.
  tube_bad_key.gltf       the same with a NaN in a rotation key.
  tube_bad_joint.gltf     the same with a vertex weighed by joint 7 of 2.

Usage: make-skinned-tube.py OUTDIR"""
import base64
import json
import math
import os
import struct
import sys

SEG, RINGS, R, H = 16, 16, 0.25, 2.0


def tube():
    pos, wts, jnts, idx = [], [], [], []
    for j in range(RINGS + 1):
        y = H * j / RINGS
        w_up = min(max((y - 0.8) / 0.4, 0.0), 1.0)
        for i in range(SEG):
            a = 2 * math.pi * i / SEG
            pos.append((R * math.cos(a), y, -R * math.sin(a)))
            jnts.append((0, 1, 0, 0))
            wts.append((1.0 - w_up, w_up, 0.0, 0.0))
    for j in range(RINGS):
        for i in range(SEG):
            a, b = j * SEG + i, j * SEG + (i + 1) % SEG
            c, d = a + SEG, b + SEG
            idx += [a, b, d, a, d, c]
    # caps: a centre vertex each
    for y, ring, flip in ((0.0, 0, True), (H, RINGS, False)):
        centre = len(pos)
        w_up = 0.0 if y < 1 else 1.0
        pos.append((0.0, y, 0.0))
        jnts.append((0, 1, 0, 0))
        wts.append((1.0 - w_up, w_up, 0.0, 0.0))
        for i in range(SEG):
            a, b = ring * SEG + i, ring * SEG + (i + 1) % SEG
            idx += [centre, b, a] if flip else [centre, a, b]
    return pos, wts, jnts, idx


def write(path, bad_weights=False, bad_key=False, bad_joint=False):
    pos, wts, jnts, idx = tube()
    if bad_weights:
        wts[5] = (0.0, 0.0, 0.0, 0.0)
    if bad_joint:
        jnts[9] = (7, 1, 0, 0)
        wts[9] = (1.0, 0.0, 0.0, 0.0)
    half = math.sqrt(0.5)
    times = [0.0, 1.0, 2.0]
    rots = [(0, 0, 0, 1), (0, 0, half, half), (0, 0, 0, 1)]
    if bad_key:
        rots[1] = (0, 0, float("nan"), half)
    blobs, views, accessors = [], [], []

    def add(data, fmt, count, ctype, atype, target=None, minmax=None):
        raw = b"".join(struct.pack("<" + fmt, *d) if isinstance(d, tuple) else struct.pack("<" + fmt, d) for d in data)
        while len(raw) % 4:
            raw += b"\0"
        offset = sum(len(b) for b in blobs)
        blobs.append(raw)
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(raw)}
        if target:
            view["target"] = target
        views.append(view)
        acc = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": atype}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    p = add(pos, "3f", len(pos), 5126, "VEC3", 34962,
            ([min(v[k] for v in pos) for k in range(3)], [max(v[k] for v in pos) for k in range(3)]))
    j = add(jnts, "4H", len(jnts), 5123, "VEC4", 34962)
    w = add(wts, "4f", len(wts), 5126, "VEC4", 34962)
    i = add(idx, "I", len(idx), 5125, "SCALAR", 34963)
    ibm = add([(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1), (1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1)],
              "16f", 2, 5126, "MAT4")
    t = add(times, "f", 3, 5126, "SCALAR", None, ([0.0], [2.0]))
    r = add(rots, "4f", 3, 5126, "VEC4")
    buf = b"".join(blobs)
    doc = {
        "asset": {"version": "2.0", "generator": "pelt tests/data/skin/make-skinned-tube.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [
            {"name": "tube", "mesh": 0, "skin": 0},
            {"name": "root", "children": [2]},
            {"name": "upper", "translation": [0, 1, 0]},
        ],
        "meshes": [{"name": "tube", "primitives": [{"attributes": {"POSITION": p, "JOINTS_0": j, "WEIGHTS_0": w},
                                                    "indices": i}]}],
        "skins": [{"joints": [1, 2], "inverseBindMatrices": ibm, "skeleton": 1}],
        "animations": [{"name": "bend",
                        "samplers": [{"input": t, "output": r, "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
    }
    with open(path, "w") as f:
        json.dump(doc, f, indent=1, allow_nan=True)
        f.write("\n")


out = sys.argv[1]
write(os.path.join(out, "tube.gltf"))
write(os.path.join(out, "tube_bad_weights.gltf"), bad_weights=True)
write(os.path.join(out, "tube_bad_key.gltf"), bad_key=True)
write(os.path.join(out, "tube_bad_joint.gltf"), bad_joint=True)
