#!/usr/bin/env python3
"""mixed_split.py - where --precision mixed's time goes, against float.

    python3 bench/mixed_split.py [--tp2 build/tp2] [--runs 3] [--size 1920x1080]
                                 [--scenes FILE...]

For each scene, float and mixed render alternately (one untimed warm-up
each, then --runs timed runs each); the table gives the medians of their
render phases (tp2 --stats) and splits mixed's into its retrace (marking
and tracing the marked pixels again in double, "retrace" in --stats) and
the rest ("pass": mixed's median less the retrace's), its float pass with
signatures. Ratios are to float's render:
the retrace's ratio is what mixed costs over float even were its float
pass free, so where it exceeds a target no cheaper bookkeeping meets it.
Default scenes: bench/compare.py's 20-row set (scenes/ but showpiece,
spheres.txt, test01, test04, hay-refraction). VK_ICD_FILENAMES is set to
lavapipe when unset. Standard library only."""
import argparse
import glob
import os
import re
import statistics
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import bench  # noqa: E402  (environment, corpus location)
from compare import run_phases  # noqa: E402


def default_scenes():
    scenes = sorted(p for p in glob.glob(os.path.join(REPO, "scenes", "*.txt"))
                    if not p.endswith("showpiece.txt"))
    corpus = bench.DEFAULT_CORPUS
    return scenes + [os.path.join(HERE, "scenes", "spheres.txt")] + [
        os.path.join(corpus, f) for f in ("test01.txt", "test04.txt", "hay-refraction.in")]


def retraced(err):
    """(seconds, percent of pixels) of mixed's retrace in --stats, (0, 0)
    when no pixel was marked."""
    m = re.search(r"tp2: retrace +([0-9.]+) s \((\d+) pixels, ([0-9.]+)%", err)
    return (float(m[1]), float(m[3])) if m else (0.0, 0.0)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tp2", default=os.path.join(REPO, "build", "tp2"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--scenes", nargs="+")
    a = ap.parse_args()
    w, h = map(int, a.size.split("x"))
    env = bench.tp2_env(True)
    settings = {"float": ("--precision", "float"), "mixed": ("--precision", "mixed")}
    print(f"tp2: {a.tp2}; {a.size}; median of {a.runs} alternating runs after a warm-up; "
          f"load at start {os.getloadavg()[0]:.2f}")
    print(f"{'scene':22s} {'float':>7s} {'mixed':>7s} {'pass':>7s} {'retrace':>7s} "
          f"{'marked':>7s} {'mixed/f':>7s} {'pass/f':>7s} {'retr/f':>7s}")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.ppm")
        for scene in a.scenes or default_scenes():
            runs = {k: [] for k in settings}
            for k, opts in settings.items():  # warm-up
                run_phases(a.tp2, scene, out, w, h, env, opts)
            for i in range(a.runs):
                for k in (("float", "mixed") if i % 2 == 0 else ("mixed", "float")):
                    _, phases, ok, err = run_phases(a.tp2, scene, out, w, h, env, settings[k])
                    if not ok:
                        sys.exit(f"{scene}: {k} failed: {err}")
                    runs[k].append((phases["render"], *retraced(err)))
            f = statistics.median(r[0] for r in runs["float"])
            m = statistics.median(r[0] for r in runs["mixed"])
            t = statistics.median(r[1] for r in runs["mixed"])
            share = runs["mixed"][0][2]
            print(f"{os.path.basename(scene):22s} {f:7.3f} {m:7.3f} {m - t:7.3f} {t:7.3f} "
                  f"{share:6.2f}% {m / f:7.3f} {(m - t) / f:7.3f} {t / f:7.3f}", flush=True)


if __name__ == "__main__":
    main()
