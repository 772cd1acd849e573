#!/usr/bin/env python3
"""no_fp64.py: what a device without shaderFloat64 pays for the default.

For each scene, tp2 --precision float and the default (mixed, its retrace
in software double) under the no_fp64 test layer, which hides
shaderFloat64 from lavapipe (tests/layers), alternately, whole-process
wall time, median of --runs; the ratio per scene and its geometric mean,
with the default's pipeline and retrace seconds and the share of pixels
retraced (--stats). A table on stdout, CSV in docs/no_fp64.csv.

    python3 bench/no_fp64.py [--runs 1] [--size 1920x1080] [--tp2 build/tp2]
                             [--scenes FILE...]
"""
import argparse
import csv
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench  # noqa: E402  (environment: lavapipe)

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = ["bench/scenes/spheres.txt", "scenes/assignment.txt", "scenes/demo.txt",
          "scenes/checker.txt", "scenes/triangle.txt", "scenes/mesh.txt", "scenes/box.txt",
          "scenes/cylinder.txt", "scenes/torus.txt"]


def timed(cmd, env):
    t0 = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, env=env, timeout=3600)
    if r.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)}: exit {r.returncode}: {r.stderr.decode()[-500:]}")
    return time.monotonic() - t0, r.stderr.decode()


def stat(pattern, err):
    m = re.search(pattern, err)
    return float(m[1]) if m else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--tp2", default=os.path.join(REPO, "build", "tp2"))
    ap.add_argument("--scenes", nargs="*", default=[os.path.join(REPO, s) for s in SCENES])
    ap.add_argument("--csv", default=os.path.join(REPO, "docs", "no_fp64.csv"))
    args = ap.parse_args()
    w, h = args.size.split("x")
    layers = os.path.join(os.path.dirname(args.tp2), "tests", "layers", "no_fp64")
    env = bench.tp2_env(True)
    rows = []
    print(f"{'scene':16} {'float s':>8} {'no fp64 s':>9} {'ratio':>6} {'pipeline':>9} "
          f"{'retrace':>8} {'retraced':>8}")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.ppm")
        for scene in args.scenes:
            fast, soft = [], []
            for _ in range(args.runs):
                fast.append(timed([args.tp2, "--precision", "float", scene, out, w, h], env)[0])
                t, err = timed([args.tp2, "--stats", scene, out, w, h],
                               {**env, "XDG_DATA_HOME": layers})
                soft.append(t)
            assert "software double" in err, err
            row = {"scene": os.path.basename(scene), "float_s": statistics.median(fast),
                   "no_fp64_s": statistics.median(soft),
                   "pipeline_s": stat(r"tp2: pipeline +([0-9.]+)", err),
                   "retrace_s": stat(r"tp2: retrace +([0-9.]+)", err),
                   "retraced_pct": stat(r"tp2: retrace .*pixels, ([0-9.]+)%", err)}
            row["ratio"] = row["no_fp64_s"] / row["float_s"]
            rows.append(row)
            print(f"{row['scene']:16} {row['float_s']:8.2f} {row['no_fp64_s']:9.2f} "
                  f"{row['ratio']:6.2f} {row['pipeline_s']:9.2f} {row['retrace_s']:8.2f} "
                  f"{row['retraced_pct']:7.2f}%", flush=True)
    mean = math.exp(statistics.mean(math.log(r["ratio"]) for r in rows))
    print(f"geometric mean of the ratios: {mean:.2f} ({args.size}, median of {args.runs})")
    with open(args.csv, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


if __name__ == "__main__":
    main()
