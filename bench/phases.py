#!/usr/bin/env python3
"""phases.py - tp2 builds side by side, every phase of --stats.

    python3 bench/phases.py OLD_TP2,NEW_TP2 SCENE RUNS [tp2 options...]

Renders SCENE at 400 x 300 with each build in turn (the order reversed
every other round), after one untimed round, RUNS times each, and prints
per build the median of the process's wall time and of each phase
--stats reports (parse, device, bvh, upload, pipeline, render, retrace,
readback, write). For the host-side phases of large scenes, where
bench/compare.py gives wall and render only (its run_phases does each
run). VK_ICD_FILENAMES is set to lavapipe when unset. Standard library
only."""
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench  # noqa: E402  (environment)
import compare  # noqa: E402  (one timed --stats run)


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    builds = sys.argv[1].split(',')
    scene, runs, extra = sys.argv[2], int(sys.argv[3]), sys.argv[4:]
    env = bench.tp2_env(True)
    out = '/tmp/tp2-phases-%d.ppm' % os.getpid()
    res = {b: {} for b in builds}
    for i in range(runs + 1):
        for b in (builds if i % 2 else builds[::-1]):
            wall, phases, ok, err = compare.run_phases(b, scene, out, 400, 300, env, extra)
            if not ok:
                sys.exit('%s failed: %s' % (b, err.strip()))
            if i == 0:
                continue
            res[b].setdefault('wall', []).append(wall)
            for k, v in phases.items():
                res[b].setdefault(k, []).append(v)
    if os.path.exists(out):
        os.remove(out)
    for b in builds:
        print(b, ' '.join('%s %.4f' % (k, statistics.median(v)) for k, v in res[b].items()))


if __name__ == '__main__':
    main()
