#!/usr/bin/env python3
"""cylinder.py -- tetrahedral meshes for `subspectra deform`'s examples
(docs/deform.md), written as Medit .mesh files; nothing is committed but this
script.

A disk of R rings (ring r holds m*r points at radius r/R; the centre has m
triangles around it) extruded into L layers of height H/L; each triangular
prism is cut into 3 tets by the global-index rule (the diagonal of a side
face leaves its lowest-numbered vertex), so neighbouring prisms agree.

  cylinder.py --out base.mesh [--target moved.mesh] [--sectors m] [--rings R]
              [--layers L] [--height H] [--crease] [--move twist|push]

--crease  (the tet/oct paper's figure 8) adds the boundary as crease cells:
          its triangles (Loop-like crease surface) and the two rims as
          segments (crease curves), with --sectors 6.
--sectors m with m = 3 or 4: the axis of the cylinder is an interior edge
          of valence m in every inner layer (m tets around it: one per prism
          at the centre).
--move    the target mesh: twist (the top layer turned by 40 degrees, the
          layers between in proportion) or push (the axis vertices of the
          middle layer moved sideways by a third of the radius).
"""
import argparse
import math


def disk(m, R):
    """Points (x, y) and triangles of the disk."""
    pts = [(0.0, 0.0)]
    rings = [[0]]
    for r in range(1, R + 1):
        n = m * r
        ring = []
        for k in range(n):
            a = 2 * math.pi * k / n
            ring.append(len(pts))
            pts.append((r / R * math.cos(a), r / R * math.sin(a)))
        rings.append(ring)
    tris = []
    for r in range(1, R + 1):
        inner, outer = rings[r - 1], rings[r]
        if len(inner) == 1:
            c = inner[0]
            for k in range(len(outer)):
                tris.append((c, outer[k], outer[(k + 1) % len(outer)]))
            continue
        # merge the two rings by angle
        ni, no = len(inner), len(outer)
        i = j = 0
        while i < ni or j < no:
            ai = (i + 1) / ni
            ao = (j + 1) / no
            if j < no and (i >= ni or ao <= ai):
                tris.append((inner[i % ni], outer[j % no], outer[(j + 1) % no]))
                j += 1
            else:
                tris.append((inner[i % ni], outer[j % no], inner[(i + 1) % ni]))
                i += 1
    return pts, tris, rings[R]


def orient(x, t):
    a, b, c, d = (x[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    w = [d[k] - a[k] for k in range(3)]
    det = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]))
    return t if det > 0 else (t[1], t[0], t[2], t[3])


def build(m, R, L, H, crease):
    pts, tris, rim = disk(m, R)
    n = len(pts)
    x = [(p[0], p[1], H * l / L) for l in range(L + 1) for p in pts]
    tets, faces, segs = [], [], []
    for l in range(L):
        off, up = l * n, (l + 1) * n
        for t in tris:
            a, b, c = sorted(v + off for v in t)
            A, B, C = a - off + up, b - off + up, c - off + up
            for q in ((a, b, c, C), (a, b, B, C), (a, A, B, C)):
                tets.append(orient(x, q))
    if crease:
        for t in tris:
            faces.append(t)
            faces.append(tuple(v + L * n for v in t))
        for l in range(L):
            off, up = l * n, (l + 1) * n
            for k in range(len(rim)):
                a, b = rim[k] + off, rim[(k + 1) % len(rim)] + off
                lo, hi = min(a, b), max(a, b)
                LO, HI = lo - off + up, hi - off + up
                faces.append((lo, hi, HI))  # the diagonal leaves lo, as in the tets
                faces.append((lo, HI, LO))
        for k in range(len(rim)):
            for l in (0, L):
                segs.append((rim[k] + l * n, rim[(k + 1) % len(rim)] + l * n))
    return x, n, tets, faces, segs


def write(path, x, tets, faces, segs):
    with open(path, "w") as f:
        f.write("# written by data/deform/cylinder.py\nMeshVersionFormatted 2\n\nDimension 3\n\n")
        f.write("Vertices\n%d\n" % len(x))
        for p in x:
            f.write("%.17g %.17g %.17g 0\n" % p)
        if segs:
            f.write("\nEdges\n%d\n" % len(segs))
            for s in segs:
                f.write("%d %d 0\n" % (s[0] + 1, s[1] + 1))
        if faces:
            f.write("\nTriangles\n%d\n" % len(faces))
            for t in faces:
                f.write("%d %d %d 0\n" % tuple(v + 1 for v in t))
        f.write("\nTetrahedra\n%d\n" % len(tets))
        for t in tets:
            f.write("%d %d %d %d 0\n" % tuple(v + 1 for v in t))
        f.write("\nEnd\n")


def move(x, n, L, H, how):
    y = list(x)
    for i, p in enumerate(x):
        l = i // n
        if how == "twist":
            a = math.radians(40.0) * l / L
            y[i] = (p[0] * math.cos(a) - p[1] * math.sin(a),
                    p[0] * math.sin(a) + p[1] * math.cos(a), p[2])
        elif how == "push" and i % n == 0 and l == L // 2:
            y[i] = (p[0] + 1.0 / 3.0, p[1], p[2])
    return y


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--target")
    ap.add_argument("--sectors", type=int, default=6)
    ap.add_argument("--rings", type=int, default=3)
    ap.add_argument("--layers", type=int, default=4)
    ap.add_argument("--height", type=float, default=2.0)
    ap.add_argument("--crease", action="store_true")
    ap.add_argument("--move", choices=["twist", "push"], default="twist")
    a = ap.parse_args()
    x, n, tets, faces, segs = build(a.sectors, a.rings, a.layers, a.height, a.crease)
    write(a.out, x, tets, faces, segs)
    if a.target:
        write(a.target, move(x, n, a.layers, a.height, a.move), tets, faces, segs)


if __name__ == "__main__":
    main()
