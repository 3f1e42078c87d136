#!/usr/bin/env python3
"""Splits every triangle of an OFF mesh 1-to-4 at its edge midpoints (shared
midpoints welded), N times: the large meshes the docs measure on, e.g. the
355,712-triangle elephant from Debian's libcgal-demo (scripts/setup.sh --tests
installs it):

    tar -xzf /usr/share/doc/libcgal-dev/data.tar.gz -C /tmp data/meshes/refined_elephant.off
    scripts/subdivide-off.py /tmp/data/meshes/refined_elephant.off 1 elephant-355k.off

With --open-below F it then drops every triangle that reaches into the lowest
fraction F of the mesh's height (along +Y): an open mesh, such as a bunny with
no bottom (N may be 0):

    scripts/subdivide-off.py /tmp/data/meshes/bunny00.off 0 open-bunny.off --open-below 0.04
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


def open_below(verts, tris, fraction):
    ys = [v[1] for v in verts]
    cut = min(ys) + fraction * (max(ys) - min(ys))
    return [t for t in tris if min(verts[i][1] for i in t) > cut]


def main():
    args = sys.argv[1:]
    fraction = None
    if len(args) == 5 and args[3] == '--open-below':
        fraction = float(args[4])
        args = args[:3]
    if len(args) != 3:
        sys.exit(__doc__)
    verts, tris = read_off(args[0])
    for _ in range(int(args[1])):
        verts, tris = subdivide(verts, tris)
    if fraction is not None:
        tris = open_below(verts, tris, fraction)
    with open(args[2], 'w') as f:
        f.write(f"OFF\n{len(verts)} {len(tris)} 0\n")
        f.writelines(f"{x:.7g} {y:.7g} {z:.7g}\n" for x, y, z in verts)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in tris)
    print(f"{args[2]}: {len(verts)} vertices, {len(tris)} triangles")


if __name__ == '__main__':
    main()
