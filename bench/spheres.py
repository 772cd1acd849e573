#!/usr/bin/env python3
"""spheres.py - writes a deterministic scene of N random spheres, a third of
them mirrors and a third glass, on a checker floor (a BVH benchmark).

    python3 bench/spheres.py OUT.txt [--n 300] [--seed 1]

bench/scenes/spheres.txt is its default output, in the benchmark's scene
set (bench.py, compare.py). It is not among scenes/ because the float
path misses the accuracy bar there (docs/accuracy.md: the checker
floor's horizon, seen directly and in a hundred mirrors).

The spheres (radius 0.35 to 0.8) lie on the floor y = 0 in x, z within
[-12, 12] x [-16, 4], not overlapping; three point lights and an ambient
light; the camera at (0, 5, 14) looks at (0, 0.5, -4). Standard library
only; the same arguments write the same file."""
import argparse
import random

COLORS = [(0.9, 0.2, 0.2), (0.2, 0.8, 0.3), (0.2, 0.4, 0.9), (0.9, 0.8, 0.2),
          (0.8, 0.3, 0.8), (0.2, 0.8, 0.8), (0.95, 0.95, 0.95), (0.9, 0.5, 0.1)]


def scene(n, seed):
    rng = random.Random(seed)
    spheres = []
    while len(spheres) < n:
        r = rng.uniform(0.35, 0.8)
        x, z = rng.uniform(-12, 12), rng.uniform(-16, 4)
        if all((x - a) ** 2 + (z - c) ** 2 > (r + b) ** 2 for a, b, c in spheres):
            spheres.append((x, r, z))
    lines = [f"# bench/spheres.py --n {n} --seed {seed}: {n} random spheres, a third",
             "# mirrors and a third glass, on a checker floor (a BVH benchmark)",
             "0 5 14", "0 0.5 -4", "0 1 0", "45",
             "4", "0 0 0  0.2 0.2 0.2  0 0 0",
             "-8 12 8  0.7 0.7 0.7  1 0 0", "10 9 4  0.4 0.4 0.5  1 0 0",
             "0 15 -10  0.3 0.3 0.3  1 0 0",
             str(len(COLORS) + 1)]
    lines += [f"solid {r} {g} {b}" for r, g, b in COLORS]
    lines += ["checker 0.9 0.9 0.9  0.15 0.15 0.2  1",
              "4",
              "0.2 0.7 0.3 20  0 0 1          # matte",
              "0.1 0.2 0.6 80  0.7 0 1        # mirror",
              "0.05 0.1 0.7 120  0.1 0.8 1.5  # glass",
              "0.3 0.7 0 1  0.15 0 1          # floor",
              str(n + 1),
              f"{len(COLORS)} 3 plane 0 1 0 0"]
    for k, (x, r, z) in enumerate(spheres):
        lines.append(f"{k % len(COLORS)} {k % 3} sphere {x:.4f} {r:.4f} {z:.4f} {r:.4f}")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--n", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    with open(a.out, "w") as f:
        f.write(scene(a.n, a.seed))


if __name__ == "__main__":
    main()
