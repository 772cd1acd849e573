#!/usr/bin/env python3
"""mesh.py - writes a trefoil-knot tube or a sphere as a Wavefront OBJ
(tp2's `mesh`).

    python3 bench/mesh.py OUT.obj [--along U] [--around V] [--radius R]
    python3 bench/mesh.py OUT.obj --sphere [--along U] [--around V] [--radius R]

--sphere: a latitude-longitude sphere of U segments around and V from pole
to pole, centered at --center (its pole quads have a corner twice, so
tp2 drops one of their two triangles as degenerate: 2 U V - 2 U triangles);
--along 1000 --around 502 gives 1,002,000 triangles.

The tube follows the trefoil knot (sin t + 2 sin 2t, cos t - 2 cos 2t,
-sin 3t), scaled by --scale, with U segments along the knot and V around
the tube: U x V quads, written as `f` lines of four corners (tp2 fans them
into 2 U V triangles), counter-clockwise seen from outside. Faces use
negative (relative) indices every other row, to exercise both forms.
--along 1000 --around 500 gives 1,000,000 triangles (about 50 MB).
Standard library only; deterministic."""
import argparse
import math


def knot(t, scale):
    """A point of the trefoil knot."""
    return (scale * (math.sin(t) + 2 * math.sin(2 * t)),
            scale * (math.cos(t) - 2 * math.cos(2 * t)),
            scale * -math.sin(3 * t))


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(a):
    n = math.sqrt(a[0] ** 2 + a[1] ** 2 + a[2] ** 2)
    return (a[0] / n, a[1] / n, a[2] / n)


def write(path, along, around, radius, scale, center):
    h = 1e-4
    with open(path, "w") as f:
        f.write(f"# trefoil knot tube: {along} x {around} quads, {2 * along * around} "
                f"triangles (bench/mesh.py)\n")
        for i in range(along):
            t = 2 * math.pi * i / along
            p = knot(t, scale)
            tangent = unit(sub(knot(t + h, scale), knot(t - h, scale)))
            bend = sub(sub(knot(t + h, scale), p), sub(p, knot(t - h, scale)))
            normal = unit(cross(cross(tangent, bend), tangent))
            binormal = cross(tangent, normal)
            for j in range(around):
                a = 2 * math.pi * j / around
                c, s = math.cos(a), math.sin(a)
                v = [p[k] + center[k] + radius * (c * normal[k] + s * binormal[k]) for k in range(3)]
                f.write(f"v {v[0]:.6f} {v[1]:.6f} {v[2]:.6f}\n")
        nv = along * around
        for i in range(along):
            for j in range(around):
                i1, j1 = (i + 1) % along, (j + 1) % around
                quad = [i * around + j, i * around + j1, i1 * around + j1, i1 * around + j]
                if i % 2:   # relative indices: -1 is the last vertex
                    f.write("f " + " ".join(str(q - nv) for q in quad) + "\n")
                else:
                    f.write("f " + " ".join(f"{q + 1}//" for q in quad) + "\n")


def write_sphere(path, around, rows, radius, center):
    with open(path, "w") as f:
        f.write(f"# sphere: {around} x {rows} quads (bench/mesh.py --sphere)\n")
        for j in range(rows + 1):
            th = math.pi * j / rows
            for i in range(around):
                ph = 2 * math.pi * i / around
                v = (center[0] + radius * math.sin(th) * math.cos(ph),
                     center[1] + radius * math.cos(th),
                     center[2] + radius * math.sin(th) * math.sin(ph))
                f.write(f"v {v[0]:.7f} {v[1]:.7f} {v[2]:.7f}\n")
        for j in range(rows):
            for i in range(around):
                i1 = (i + 1) % around
                a, b = j * around + i + 1, j * around + i1 + 1
                c, d = (j + 1) * around + i1 + 1, (j + 1) * around + i + 1
                f.write(f"f {a} {b} {c} {d}\n")   # counter-clockwise from outside


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--along", type=int, default=120, help="segments along the knot")
    ap.add_argument("--around", type=int, default=16, help="segments around the tube")
    ap.add_argument("--radius", type=float, default=0.35, help="tube radius")
    ap.add_argument("--scale", type=float, default=0.6, help="knot scale")
    ap.add_argument("--center", type=float, nargs=3, default=(0, 2.2, 0))
    ap.add_argument("--sphere", action="store_true", help="a sphere instead of the knot")
    a = ap.parse_args()
    if a.sphere:
        write_sphere(a.out, a.along, a.around, a.radius, a.center)
    else:
        write(a.out, a.along, a.around, a.radius, a.scale, a.center)


if __name__ == "__main__":
    main()
