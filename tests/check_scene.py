#!/usr/bin/env python3
"""check_scene.py TP2 SCENE W H: SCENE renders cleanly at W x H.

Checks exit status 0, an empty stderr (so no validation message), and a P6
image of the right size whose pixels are not all one value (a scene that
renders to a flat image has gone wrong)."""
import os
import subprocess
import sys
import tempfile


def main():
    tp2, scene, w, h = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.ppm")
        r = subprocess.run([tp2, scene, out, str(w), str(h)], capture_output=True, timeout=600)
        err = r.stderr.decode("utf-8", "replace")
        if r.returncode != 0 or err:
            print(f"FAIL {scene}: exit {r.returncode}, stderr {err!r}")
            return 1
        with open(out, "rb") as f:
            data = f.read()
    header = f"P6\n{w} {h}\n255\n".encode()
    if not data.startswith(header) or len(data) != len(header) + 3 * w * h:
        print(f"FAIL {scene}: bad PPM header or size")
        return 1
    pixels = data[len(header):]
    if len(set(pixels[i:i + 3] for i in range(0, len(pixels), 3))) < 2:
        print(f"FAIL {scene}: every pixel is the same")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
