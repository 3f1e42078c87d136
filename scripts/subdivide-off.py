#!/usr/bin/env python3
"""Splits every triangle of an OFF mesh 1-to-4 at its edge midpoints (shared
midpoints welded), N times: the large meshes the docs measure on, e.g. the
355,712-triangle elephant from Debian's libcgal-demo (scripts/setup.sh --tests
installs it):

    tar -xzf /usr/share/doc/libcgal-dev/data.tar.gz -C /tmp data/meshes/refined_elephant.off
    scripts/subdivide-off.py /tmp/data/meshes/refined_elephant.off 1 elephant-355k.off
"""
import sys


def read_off(path):
    words = []
    with open(path) as f:
        for line in f:
            line = line.split('#', 1)[0]
            words.extend(line.split())
    if not words or not words[0].endswith('OFF'):
        sys.exit(f"{path}: not an OFF file")
    at = 1
    nv, nf = int(words[at]), int(words[at + 1])
    at += 3
    verts = []
    for _ in range(nv):
        verts.append(tuple(float(w) for w in words[at:at + 3]))
        at += 3
    tris = []
    for _ in range(nf):
        n = int(words[at])
        idx = [int(w) for w in words[at + 1:at + 1 + n]]
        at += 1 + n
        for k in range(1, n - 1):  # fan-split polygons
            tris.append((idx[0], idx[k], idx[k + 1]))
    return verts, tris


def subdivide(verts, tris):
    verts = list(verts)
    mid = {}

    def midpoint(a, b):
        key = (a, b) if a < b else (b, a)
        if key not in mid:
            pa, pb = verts[a], verts[b]
            verts.append(tuple((x + y) / 2 for x, y in zip(pa, pb)))
            mid[key] = len(verts) - 1
        return mid[key]

    out = []
    for a, b, c in tris:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return verts, out


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    verts, tris = read_off(sys.argv[1])
    for _ in range(int(sys.argv[2])):
        verts, tris = subdivide(verts, tris)
    with open(sys.argv[3], 'w') as f:
        f.write(f"OFF\n{len(verts)} {len(tris)} 0\n")
        f.writelines(f"{x:.7g} {y:.7g} {z:.7g}\n" for x, y, z in verts)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in tris)
    print(f"{sys.argv[3]}: {len(verts)} vertices, {len(tris)} triangles")


if __name__ == '__main__':
    main()
