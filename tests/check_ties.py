#!/usr/bin/env python3
"""check_ties.py TP2 [W H]: SPEC 4's Ties, checked against the geometry.

Objects stand on a floor at y = -0.7 (a plane, or a one-face polyhedron);
the camera looks up at them from under the floor, so that each camera ray
meets the floor and, inside a footprint, an object's base at one distance
(a box's face, a cylinder's cap either way up, a cone's base, a frustum's
top, a triangle lying in the floor). Every finish is ambient only, so a
pixel's color says which object its ray hit. The hit is computed here from the camera and
the footprints, away from their edges (margin below): the object listed
first in the file, the floor when it comes first, else the object. Each
precision (float, mixed, the default, double) must show exactly that at
every such pixel: float decides the ties as double does."""
import math
import os
import subprocess
import sys
import tempfile

MARGIN = 0.05  # world units kept from each footprint's edge
FLOOR_Y = -0.7
EYE, CENTER, UP, FOV = (0.2, -5.0, 3.5), (0.0, -0.7, 0.3), (0.0, 1.0, 0.0), 70.0
# name, color, object line (after "pigment finish"), footprint test
OBJECTS = [
    ("box", (0.2, 0.8, 0.2), "box -2 -0.7 -1  -0.8 0.5 0.2",
     lambda x, z: min(x + 2, -0.8 - x, z + 1, 0.2 - z)),
    ("cylinder up", (0.2, 0.2, 0.8), "cylinder 1.2 -0.7 -0.3  1.2 0.6 -0.3  0.6",
     lambda x, z: 0.6 - math.hypot(x - 1.2, z + 0.3)),
    ("cylinder down", (0.8, 0.8, 0.2), "cylinder 0 0.8 1.3  0 -0.7 1.3  0.45",
     lambda x, z: 0.45 - math.hypot(x, z - 1.3)),
    ("cone", (0.2, 0.8, 0.8), "cone -1.4 -0.7 1.4 0.55  -1.4 0.9 1.4 0",
     lambda x, z: 0.55 - math.hypot(x + 1.4, z - 1.4)),
    ("cone top down", (0.5, 0.5, 0.5), "cone -0.1 0.6 -0.4 0.1  -0.1 -0.7 -0.4 0.45",
     lambda x, z: 0.45 - math.hypot(x + 0.1, z + 0.4)),
    ("triangle", (0.8, 0.2, 0.8), "triangle 1.5 -0.7 1  2.6 -0.7 1  2 -0.7 2.2", None),
]
FLOOR_COLOR = (0.8, 0.2, 0.2)
FLOORS = {"plane": "plane 0 2 0 1.4", "polyhedron": "polyhedron 1\n  0 1 0 0.7"}
TRIANGLE = [(1.5, 1.0), (2.6, 1.0), (2.0, 2.2)]


def triangle_inside(x, z):
    """Distance from (x, z) to the triangle's nearest edge, negative outside."""
    best = math.inf
    for k in range(3):
        (ax, az), (bx, bz) = TRIANGLE[k], TRIANGLE[(k + 1) % 3]
        ex, ez = bx - ax, bz - az
        # counterclockwise in (x, z): inside is to the left
        best = min(best, (ex * (z - az) - ez * (x - ax)) / math.hypot(ex, ez))
    return best


def scene_text(floor, floor_first):
    objs = [f"{i + 1} 0 {line}" for i, (_, _, line, _) in enumerate(OBJECTS)]
    floor_line = f"0 0 {FLOORS[floor]}"
    objs = [floor_line] + objs if floor_first else objs + [floor_line]
    pig = [FLOOR_COLOR] + [c for _, c, _, _ in OBJECTS]
    lines = [" ".join(map(str, EYE)), " ".join(map(str, CENTER)), " ".join(map(str, UP)),
             str(FOV), "1", "0 0 0  1 1 1  0 0 0", str(len(pig))]
    lines += [f"solid {r} {g} {b}" for r, g, b in pig]
    lines += ["1", "1 0 0 1 0 0 1", str(len(objs))] + objs
    return "\n".join(lines) + "\n"


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(a):
    n = math.sqrt(sum(x * x for x in a))
    return tuple(x / n for x in a)


def expected(w, h, floor_first):
    """{(px, py): (object name, rgb)} for the pixels whose hit is sure."""
    wv = unit(sub(CENTER, EYE))
    u = unit(cross(wv, UP))
    v = cross(u, wv)
    half_h = math.tan(math.radians(FOV) / 2)
    half_w = half_h * w / h
    out = {}
    for py in range(h):
        for px in range(w):
            x = (2 * (px + 0.5) / w - 1) * half_w
            y = (1 - 2 * (py + 0.5) / h) * half_h
            d = tuple(wv[k] + x * u[k] + y * v[k] for k in range(3))
            if d[1] <= 0:
                continue
            t = (FLOOR_Y - EYE[1]) / d[1]
            hx, hz = EYE[0] + t * d[0], EYE[2] + t * d[2]
            inside = [(name, color) for name, color, _, f in OBJECTS
                      if (f(hx, hz) if f else triangle_inside(hx, hz)) > MARGIN]
            near = [name for name, color, _, f in OBJECTS
                    if abs(f(hx, hz) if f else triangle_inside(hx, hz)) <= MARGIN]
            if near or len(inside) > 1:
                continue
            if not inside:
                out[(px, py)] = ("floor", FLOOR_COLOR)
            elif floor_first:
                out[(px, py)] = ("floor over " + inside[0][0], FLOOR_COLOR)
            else:
                out[(px, py)] = inside[0]
    return out


def read_ppm(path):
    data = open(path, "rb").read()
    head = data.split(maxsplit=4)
    assert head[0] == b"P6", path
    return int(head[1]), int(head[2]), head[4]


def main():
    tp2 = sys.argv[1]
    w, h = (int(sys.argv[2]), int(sys.argv[3])) if len(sys.argv) > 3 else (160, 120)
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for floor in FLOORS:
            for floor_first in (True, False):
                want = expected(w, h, floor_first)
                counts = {}
                for name, _ in want.values():
                    counts[name] = counts.get(name, 0) + 1
                scene = os.path.join(tmp, "ties.txt")
                with open(scene, "w") as f:
                    f.write(scene_text(floor, floor_first))
                label = f"{floor} floor {'first' if floor_first else 'last'}"
                for name, _, _, _ in OBJECTS + [("floor", 0, 0, 0)]:
                    key = name if name == "floor" or not floor_first else "floor over " + name
                    if counts.get(key, 0) < 50:
                        print(f"FAIL {label}: only {counts.get(key, 0)} sure pixels of {key}")
                        failed += 1
                for precision in ("float", "mixed", "auto", "double"):
                    image = os.path.join(tmp, f"{precision}.ppm")
                    r = subprocess.run([tp2, "--precision", precision, scene, image, str(w),
                                        str(h)], capture_output=True, timeout=300)
                    if r.returncode != 0 or r.stderr:
                        print(f"FAIL {label} {precision}: exit {r.returncode} {r.stderr!r}")
                        failed += 1
                        continue
                    _, _, px = read_ppm(image)
                    wrong = 0
                    for (x, y), (name, rgb) in want.items():
                        got = px[3 * (y * w + x):3 * (y * w + x) + 3]
                        if any(abs(g - round(255 * c)) > 1 for g, c in zip(got, rgb)):
                            wrong += 1
                    print(f"{label} {precision}: {len(want)} pixels checked "
                          f"({', '.join(f'{k} {n}' for k, n in sorted(counts.items()))}), "
                          f"{wrong} wrong")
                    failed += wrong > 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
