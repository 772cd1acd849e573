#!/usr/bin/env python3
"""check_accuracy.py TP2 IMGCMP SCENE [W H]: the float image meets the bar.

Renders SCENE with the default (float) shader and with --precision double
(the reference image of SPEC 4) as PFM, and asks tp2-imgcmp whether the
float image has at least 99.5% of channel values within +-1 level of the
reference and at most 0.1% of pixels off by more than 8 levels (the default
accuracy bar in README.TXT). Prints imgcmp's figures either way."""
import os
import subprocess
import sys
import tempfile

MIN_WITHIN1 = 0.995
MAX_BAD8_FRACTION = 0.001


def render(tp2, scene, out, size, extra):
    r = subprocess.run([tp2] + extra + [scene, out] + size, capture_output=True, timeout=900)
    if r.returncode != 0 or r.stderr:
        raise SystemExit(f"FAIL {scene} {extra}: exit {r.returncode}, {r.stderr.decode()!r}")


def main():
    tp2, imgcmp, scene = sys.argv[1:4]
    w, h = (int(sys.argv[4]), int(sys.argv[5])) if len(sys.argv) > 5 else (200, 150)
    size = [str(w), str(h)]
    with tempfile.TemporaryDirectory() as tmp:
        fast, ref = os.path.join(tmp, "float.pfm"), os.path.join(tmp, "double.pfm")
        render(tp2, scene, fast, size, [])
        render(tp2, scene, ref, size, ["--precision", "double"])
        max_bad = int(MAX_BAD8_FRACTION * w * h)
        r = subprocess.run([imgcmp, "--min-within1", str(MIN_WITHIN1), "--max-bad8",
                            str(max_bad), fast, ref], capture_output=True, timeout=60)
    print(f"{os.path.basename(scene)}: {r.stdout.decode().strip()} (bar: within1 >= "
          f"{MIN_WITHIN1}, bad8 <= {max_bad})")
    if r.returncode != 0:
        print(f"FAIL {r.stderr.decode().strip()}")
    return r.returncode


if __name__ == "__main__":
    sys.exit(main())
