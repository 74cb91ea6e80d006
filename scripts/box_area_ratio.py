#!/usr/bin/env python3
"""How much a mesh would gain from splitting triangles with loose boxes
(early split clipping, Ernst and Greiner 2007; edge volume heuristic,
Dammertz and Keller 2008): per triangle, the surface area of its axis-aligned
box over the triangle's own area (a triangle in an axis plane gives 1 to 2, a
long thin diagonal one hundreds), and the share of the sum of all box areas
that the worst 1, 2 and 5% of triangles hold (by box area). A BVH pays for box
area, so a large share in few triangles is what splitting could win back.

Usage: box_area_ratio.py MESH.obj...
"""
import math
import sys


def load_obj(path):
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                verts.append(tuple(float(x) for x in line.split()[1:4]))
            elif line.startswith("f "):
                idx = []
                for tok in line.split()[1:]:
                    i = int(tok.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                for k in range(1, len(idx) - 1):  # fan, as the loader does
                    tris.append((idx[0], idx[k], idx[k + 1]))
    return verts, tris


def report(path):
    verts, tris = load_obj(path)
    boxes, ratios = [], []
    for a, b, c in tris:
        p, q, r = verts[a], verts[b], verts[c]
        d = [max(p[i], q[i], r[i]) - min(p[i], q[i], r[i]) for i in range(3)]
        box = 2.0 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0])
        e1 = [q[i] - p[i] for i in range(3)]
        e2 = [r[i] - p[i] for i in range(3)]
        n = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
             e1[0] * e2[1] - e1[1] * e2[0])
        area = 0.5 * math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2)
        boxes.append(box)
        # Twice the area: a triangle's box is at least 2 * area (its
        # projection onto one axis plane is at most the box's face).
        ratios.append(box / (2.0 * area) if area > 0 else float("inf"))
    n = len(tris)
    total = sum(boxes)
    ranked = sorted(boxes, reverse=True)
    rs = sorted(ratios)
    share = lambda f: sum(ranked[: max(1, int(f * n))]) / total
    q = lambda f: rs[min(n - 1, int(f * n))]
    print(f"{path.split('/')[-1]:20s} {n:7d} tris  box/(2 area): median {q(0.5):6.2f}"
          f"  p90 {q(0.9):6.2f}  p99 {q(0.99):8.2f}  >4: {sum(r > 4 for r in rs) / n:6.1%}"
          f"  >16: {sum(r > 16 for r in rs) / n:6.2%}"
          f" | box-area share of worst 1% {share(0.01):6.1%}  2% {share(0.02):6.1%}"
          f"  5% {share(0.05):6.1%}  max/mean {ranked[0] / (total / n):7.1f}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.stderr.write(__doc__)
        sys.exit(2)
    for p in sys.argv[1:]:
        report(p)
