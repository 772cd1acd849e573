#!/usr/bin/env python3
"""compare.py - two tp2 builds side by side on the same scenes.

    python3 bench/compare.py OLD_TP2 NEW_TP2 [--scenes FILE...] [--sizes 1920x1080]
                             [--runs 5] [--imgcmp build/tests/tp2-imgcmp] [--bailout W]
                             [--old-options "..."] [--new-options "..."]

For each scene and size, the two builds render alternately (the old one
first in even rounds, the new one first in odd ones), after one untimed
warm-up each; whole-process wall time and the render phase (tp2 --stats)
are taken per run, and the table gives their medians, the ratio new / old
of the medians, and how the two images compare (tp2-imgcmp: mean error in
levels and pixels off by more than 8; "same" when identical). Default
scenes: those of bench.py (corpus and scenes/ without texmap) that the
old build can read. --old-options and --new-options pass options to one
build only, so that one build can be compared with itself under two
settings (e.g. --precision float against auto). VK_ICD_FILENAMES is set to
lavapipe when unset.
Standard library only."""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import bench  # noqa: E402  (default scene list, environment)


def run_phases(tp2, scene, out, w, h, env, options=()):
    """(wall seconds, {phase: seconds} as --stats reports them, ok, stderr)
    of one tp2 --stats run."""
    t0 = time.perf_counter()
    r = subprocess.run([tp2, "--stats", "--quiet", *options, scene, out, str(w), str(h)],
                       capture_output=True, env=env)
    wall = time.perf_counter() - t0
    err = r.stderr.decode("utf-8", "replace")
    phases = {m[1]: float(m[2]) for m in re.finditer(r"tp2: (\w+) +([0-9.]+) s", err)}
    return wall, phases, r.returncode == 0 and "warning" not in err, err


def run(tp2, scene, out, w, h, env, options=()):
    """(wall seconds, render seconds, ok) of one tp2 --stats run."""
    wall, phases, ok, _ = run_phases(tp2, scene, out, w, h, env, options)
    return wall, phases.get("render", float("nan")), ok


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--scenes", nargs="+")
    ap.add_argument("--sizes", default="1920x1080")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--imgcmp", default=os.path.join(REPO, "build", "tests", "tp2-imgcmp"))
    ap.add_argument("--corpus", default=bench.DEFAULT_CORPUS)
    ap.add_argument("--bailout", help="tp2 --bailout for both builds (0: equal ray trees)")
    ap.add_argument("--old-options", default="", help="options for the old build only")
    ap.add_argument("--new-options", default="", help="options for the new build only")
    a = ap.parse_args()
    common = ("--bailout", a.bailout) if a.bailout is not None else ()
    options = {"old": (*common, *a.old_options.split()), "new": (*common, *a.new_options.split())}
    env = bench.tp2_env(True)
    scenes = a.scenes or bench.default_scenes(a.new, a.corpus)
    print(f"old: {a.old} {' '.join(options['old'])}\nnew: {a.new} {' '.join(options['new'])}\n"
          f"runs: {a.runs} alternating after a warm-up; "
          f"load at start {os.getloadavg()[0]:.2f}")
    print(f"{'scene':28s} {'size':>10s} {'old wall':>9s} {'new wall':>9s} {'ratio':>6s} "
          f"{'old rend':>9s} {'new rend':>9s} {'ratio':>6s}  image")
    ratios = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            for size in a.sizes.split(","):
                w, h = map(int, size.split("x"))
                outs = {k: os.path.join(tmp, f"{k}.ppm") for k in ("old", "new")}
                times = {"old": [], "new": []}
                ok = True
                for k in ("old", "new"):   # warm-up
                    ok &= run(getattr(a, k), scene, outs[k], w, h, env, options[k])[2]
                if not ok:
                    print(f"{os.path.basename(scene):28s} {size:>10s} (a build failed or warned)")
                    continue
                for i in range(a.runs):
                    for k in (("old", "new") if i % 2 == 0 else ("new", "old")):
                        wall, rend, _ = run(getattr(a, k), scene, outs[k], w, h, env, options[k])
                        times[k].append((wall, rend))
                med = {k: (statistics.median(t[0] for t in v), statistics.median(t[1] for t in v))
                       for k, v in times.items()}
                cmp = subprocess.run([a.imgcmp, outs["old"], outs["new"]], capture_output=True)
                text = cmp.stdout.decode()
                mae = re.search(r"mae=([0-9.]+)", text)
                bad = re.search(r"bad8=(\d+)", text)
                image = "same" if "max=0 " in text else f"mae {mae[1]}, bad8 {bad[1]}"
                ratio = med["new"][0] / med["old"][0]
                ratios.append(ratio)
                print(f"{os.path.basename(scene):28s} {size:>10s} {med['old'][0]:9.3f} "
                      f"{med['new'][0]:9.3f} {ratio:6.3f} {med['old'][1]:9.3f} "
                      f"{med['new'][1]:9.3f} {med['new'][1] / med['old'][1]:6.3f}  {image}")
    if ratios:
        geo = 1.0
        for r in ratios:
            geo *= r
        print(f"geometric mean of wall ratios new/old: {geo ** (1 / len(ratios)):.3f} "
              f"over {len(ratios)} rows; load at end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    sys.exit(main())
