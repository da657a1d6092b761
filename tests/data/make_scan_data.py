#!/usr/bin/env python3
"""Writes the small scan test meshes of tst_scan_import (run in tests/data).

dome.{stl,obj,ply}: a closed half-ellipsoid dome, base radius 5 cm, height 4 cm, base disc
on z = 0 (16 segments, 6 rings). dome-side.stl: the same tipped on its side (base normal
+y). open-dome.stl: without the base (16 open edges). nonmanifold-dome.obj: one extra
triangle on a rim edge. empty.stl: 0 bytes. garbage.stl/.ply: random bytes. no-faces.obj:
vertices only."""
import math, random

def dome(a=0.05, h=0.04, drop_base=False, extra=False, side=False):
    nr, nu = 6, 16
    v = [(0.0, 0.0, h)]
    for i in range(1, nr + 1):
        th = 0.5 * math.pi * i / nr
        for j in range(nu):
            ph = 2 * math.pi * j / nu
            v.append((a * math.sin(th) * math.cos(ph), a * math.sin(th) * math.sin(ph), h * math.cos(th)))
    ring = lambda i, j: 1 + (i - 1) * nu + (j % nu)
    t = [(0, ring(1, j), ring(1, j + 1)) for j in range(nu)]
    for i in range(1, nr):
        for j in range(nu):
            t.append((ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)))
            t.append((ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)))
    if not drop_base:
        c = len(v)
        v.append((0.0, 0.0, 0.0))
        t += [(c, ring(nr, j + 1), ring(nr, j)) for j in range(nu)]
    if extra:
        v.append((0.0, 0.0, -0.01))
        t.append((ring(nr, 0), ring(nr, 1), len(v) - 1))
    if side:
        v = [(x, -z, y) for (x, y, z) in v]
    return v, t

def stl(path, v, t):
    with open(path, "w") as f:
        f.write("solid dome\n")
        for tri in t:
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for k in tri:
                f.write("   vertex %.9g %.9g %.9g\n" % v[k])
            f.write("  endloop\n endfacet\n")
        f.write("endsolid dome\n")

def obj(path, v, t):
    with open(path, "w") as f:
        for p in v:
            f.write("v %.9g %.9g %.9g\n" % p)
        for tri in t:
            f.write("f %d %d %d\n" % tuple(k + 1 for k in tri))

def ply(path, v, t):
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
                "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (len(v), len(t)))
        for p in v:
            f.write("%.9g %.9g %.9g\n" % p)
        for tri in t:
            f.write("3 %d %d %d\n" % tri)

v, t = dome()
stl("dome.stl", v, t)
obj("dome.obj", v, t)
ply("dome.ply", v, t)
stl("dome-side.stl", *dome(side=True))
stl("open-dome.stl", *dome(drop_base=True))
obj("nonmanifold-dome.obj", *dome(extra=True))
open("empty.stl", "w").close()
rnd = random.Random(6)
for name in ("garbage.stl", "garbage.ply"):
    with open(name, "wb") as f:
        f.write(bytes(rnd.randrange(256) for _ in range(1001)))
with open("no-faces.obj", "w") as f:
    for p in v[:10]:
        f.write("v %.9g %.9g %.9g\n" % p)
