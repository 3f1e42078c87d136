#!/usr/bin/env python3
"""Writes scenes/meshes/sphere-and-box.obj: a UV sphere beside a box, both
closed and wound counter-clockwise seen from outside, on the plane y = 0;
the shadow scene of docs/shadows.md. Usage: make-sphere-box.py OUT.obj"""
import math
import sys

verts, index, faces = [], {}, []


def vertex(p):
    key = tuple(round(c, 6) for c in p)
    if key not in index:
        index[key] = len(verts) + 1
        verts.append(key)
    return index[key]


def quad(a, b, c, d):
    faces.append((a, b, c))
    faces.append((a, c, d))


def sphere(center, r, slices=40, stacks=20):
    def at(i, j):
        th, ph = 2 * math.pi * i / slices, math.pi * j / stacks
        return vertex((center[0] + r * math.sin(ph) * math.cos(th), center[1] + r * math.cos(ph),
                       center[2] - r * math.sin(ph) * math.sin(th)))
    for j in range(stacks):
        for i in range(slices):
            a, b, c, d = at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)
            if j == 0:
                faces.append((a, b, c))
            elif j == stacks - 1:
                faces.append((a, b, d))
            else:
                quad(a, b, c, d)


def box(lo, hi, n=8):
    # Each face from its corner o along u and v, u x v pointing outwards.
    size = [hi[k] - lo[k] for k in range(3)]
    def face(o, u, v):
        for j in range(n):
            for i in range(n):
                def p(a, b):
                    return vertex(tuple(o[k] + u[k] * a / n + v[k] * b / n for k in range(3)))
                quad(p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1))
    x, y, z = size
    face(lo, (0, 0, z), (0, y, 0))                     # -x
    face((hi[0], lo[1], lo[2]), (0, y, 0), (0, 0, z))  # +x
    face(lo, (x, 0, 0), (0, 0, z))                     # -y
    face((lo[0], hi[1], lo[2]), (0, 0, z), (x, 0, 0))  # +y
    face(lo, (0, y, 0), (x, 0, 0))                     # -z
    face((lo[0], lo[1], hi[2]), (x, 0, 0), (0, y, 0))  # +z


sphere((-0.75, 0.6, 0.9), 0.6)
box((0.15, 0.0, -0.5), (1.15, 1.0, 0.5))
with open(sys.argv[1], "w") as f:
    f.write("# pelt: a sphere beside a box (scripts/make-sphere-box.py)\n")
    for v in verts:
        f.write("v %g %g %g\n" % v)
    for t in faces:
        f.write("f %d %d %d\n" % t)
