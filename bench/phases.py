#!/usr/bin/env python3
"""phases.py - tp2 builds side by side, every phase of --stats.

    python3 bench/phases.py OLD_TP2,NEW_TP2 SCENE RUNS [tp2 options...]

Renders SCENE at 400 x 300 with each build in turn (the order reversed
every other round), after one untimed round, RUNS times each, and prints
per build the median of the process's wall time and of each phase
--stats reports (parse, device, bvh, upload, pipeline, render, retrace,
readback, write). For the host-side phases of large scenes, where
bench/compare.py gives wall and render only. VK_ICD_FILENAMES is set to
lavapipe when unset. Standard library only."""
import os
import re
import statistics
import subprocess
import sys
import time


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    builds = sys.argv[1].split(',')
    scene, runs, extra = sys.argv[2], int(sys.argv[3]), sys.argv[4:]
    env = dict(os.environ)
    env.setdefault('VK_ICD_FILENAMES', '/usr/share/vulkan/icd.d/lvp_icd.x86_64.json')
    out = '/tmp/tp2-phases-%d.ppm' % os.getpid()
    res = {b: {} for b in builds}
    for i in range(runs + 1):
        for b in (builds if i % 2 else builds[::-1]):
            t0 = time.perf_counter()
            r = subprocess.run([b, '--stats', '--quiet', *extra, scene, out, '400', '300'],
                               capture_output=True, text=True, env=env)
            wall = time.perf_counter() - t0
            if r.returncode != 0:
                sys.exit('%s failed: %s' % (b, r.stderr.strip()))
            if i == 0:
                continue
            d = res[b]
            d.setdefault('wall', []).append(wall)
            for m in re.finditer(r'tp2: (\w+) +([0-9.]+) s', r.stderr):
                d.setdefault(m[1], []).append(float(m[2]))
    if os.path.exists(out):
        os.remove(out)
    for b in builds:
        print(b, ' '.join('%s %.4f' % (k, statistics.median(v)) for k, v in res[b].items()))


if __name__ == '__main__':
    main()
