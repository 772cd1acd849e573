#!/usr/bin/env python3
"""check_accuracy.py TP2 IMGCMP SCENE [W H]: the default image meets the bar.

Renders SCENE with the default settings (--precision auto, pruning at
1/255) and the exact image of SPEC 4 (--precision double --bailout 0) as
PFM, at 400 x 300 unless told, and asks tp2-imgcmp whether the default
image has at least 99.95% of channel values within +-1 level of the exact
one and at most 10 pixels off by more than 8 levels (README.TXT
"Accuracy"). Also renders --precision float and prints its figures
against the same bar, which several scenes fail: what auto's double
retrace buys, shown."""
import os
import subprocess
import sys
import tempfile

MIN_WITHIN1 = 0.9995
MAX_BAD8 = 10


def render(tp2, scene, out, size, extra):
    r = subprocess.run([tp2] + extra + [scene, out] + size, capture_output=True, timeout=900)
    if r.returncode != 0 or r.stderr:
        raise SystemExit(f"FAIL {scene} {extra}: exit {r.returncode}, {r.stderr.decode()!r}")


def compare(imgcmp, image, ref):
    return subprocess.run([imgcmp, "--min-within1", str(MIN_WITHIN1), "--max-bad8",
                           str(MAX_BAD8), image, ref], capture_output=True, timeout=60)


def main():
    tp2, imgcmp, scene = sys.argv[1:4]
    w, h = (int(sys.argv[4]), int(sys.argv[5])) if len(sys.argv) > 5 else (400, 300)
    size = [str(w), str(h)]
    name = os.path.basename(scene)
    with tempfile.TemporaryDirectory() as tmp:
        auto, fast, ref = (os.path.join(tmp, f"{k}.pfm") for k in ("auto", "float", "ref"))
        render(tp2, scene, auto, size, [])
        render(tp2, scene, fast, size, ["--precision", "float"])
        render(tp2, scene, ref, size, ["--precision", "double", "--bailout", "0"])
        r = compare(imgcmp, auto, ref)
        f = compare(imgcmp, fast, ref)
    bar = f"bar: within1 >= {MIN_WITHIN1}, bad8 <= {MAX_BAD8}"
    print(f"{name} default: {r.stdout.decode().strip()} ({bar})")
    print(f"{name} float:   {f.stdout.decode().strip()} ({'meets' if f.returncode == 0 else 'fails'}"
          " the bar; not asserted)")
    if r.returncode != 0:
        print(f"FAIL {r.stderr.decode().strip()}")
    return r.returncode


if __name__ == "__main__":
    sys.exit(main())
