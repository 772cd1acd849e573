#!/usr/bin/env python3
"""instructions.py - two tp2 builds compared by the instructions lavapipe
executes in their compiled shaders, a count that does not move when other
work shares the machine (wall time on a loaded 2-core machine moves by
tens of percent).

    python3 bench/instructions.py OLD_TP2 NEW_TP2 [--scenes FILE...]
                                  [--size 320x180] [--options "..."]

Each build renders each scene once natively (so that the pipeline caches
are warm) and once under valgrind's callgrind, one profile per thread; the
count is the sum, over all threads, of the instructions in code with no
object file: the shaders lavapipe compiled (the render and finish passes).
Start-up, parsing, packing, compiling and writing are left out. The table
gives both counts, their ratio new / old and whether the images are the
same bytes. An instruction count is not a time (memory and caches are not
in it): a ratio here says where to look, and bench/compare.py times it.
Needs valgrind (callgrind_annotate); standard library otherwise."""
import argparse
import glob
import hashlib
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import bench  # noqa: E402  (environment: lavapipe)

JIT = re.compile(r"^\s*([\d,]+)\s+\(.*\)\s+\S.*\[\?\?\?\]\s*$")


def shader_instructions(tp2, scene, w, h, options, env):
    """(instructions in compiled shaders, image digest) of one run."""
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "out.ppm")
        args = [tp2, "--quiet", *options, scene, out, str(w), str(h)]
        subprocess.run(args, env=env, capture_output=True, check=True)  # warm the caches
        subprocess.run(["valgrind", "--tool=callgrind", "--separate-threads=yes",
                        "--callgrind-out-file=" + os.path.join(d, "cg.%p"), *args],
                       env=env, capture_output=True, check=True)
        total = 0
        for f in glob.glob(os.path.join(d, "cg.*-*")):  # one per thread
            report = subprocess.run(["callgrind_annotate", "--threshold=100", f],
                                    capture_output=True, text=True, check=True).stdout
            for line in report.splitlines():
                m = JIT.match(line)
                if m:
                    total += int(m.group(1).replace(",", ""))
        with open(out, "rb") as f:
            digest = hashlib.sha256(f.read()).hexdigest()
        return total, digest


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--scenes", nargs="+",
                    help="default: scenes/ and bench/scenes/ (bench.py's, corpus left out)")
    ap.add_argument("--size", default="320x180")
    ap.add_argument("--options", default="", help="tp2 options for both builds")
    a = ap.parse_args()
    scenes = a.scenes or bench.default_scenes(a.new, None)
    w, h = (int(x) for x in a.size.split("x"))
    env = bench.tp2_env(True)
    options = a.options.split()
    print("old: %s %s\nnew: %s %s\nsize: %s; instructions in compiled shaders (callgrind)"
          % (a.old, a.options, a.new, a.options, a.size))
    print("%-28s %15s %15s %7s  image" % ("scene", "old", "new", "ratio"))
    for scene in scenes:
        old, old_digest = shader_instructions(a.old, scene, w, h, options, env)
        new, new_digest = shader_instructions(a.new, scene, w, h, options, env)
        print("%-28s %15d %15d %7.3f  %s" % (os.path.basename(scene), old, new,
                                            new / old if old else float("nan"),
                                            "same" if old_digest == new_digest else "differs"))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
