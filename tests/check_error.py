#!/usr/bin/env python3
"""check_error.py TP2 SCENE: tp2 must reject SCENE exactly as its first line says.

SCENE's first line is `# expect: LINE:COL: error: MESSAGE`, or
`# expect: FILE:LINE:COL: error: MESSAGE` for an error in another file
(a mesh's OBJ) named relative to SCENE's folder. The test runs
`tp2 SCENE out.ppm` in a fresh folder and checks: exit status 1, stderr is
exactly one line `SCENE:LINE:COL: error: MESSAGE` (or FILE's path), and no
file appeared (neither out.ppm nor a temporary one)."""
import os
import subprocess
import sys
import tempfile


def main():
    tp2, scene = sys.argv[1], sys.argv[2]
    with open(scene, "rb") as f:
        first = f.readline().decode("utf-8", "replace").rstrip("\r\n")
    first = first.removeprefix("\ufeff")  # a byte-order mark, itself under test
    prefix = "# expect: "
    if not first.startswith(prefix):
        print(f"{scene}: first line must start with '{prefix}'")
        return 1
    rest = first[len(prefix):]
    where = scene
    if not rest[:1].isdigit():
        other, rest = rest.split(":", 1)
        where = os.path.join(os.path.dirname(scene), other)
    expected = f"{where}:{rest}"
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.ppm")
        r = subprocess.run([tp2, scene, out], capture_output=True, timeout=60)
        stderr = r.stderr.decode("utf-8", "replace")
        left = os.listdir(tmp)
    failures = []
    if r.returncode != 1:
        failures.append(f"exit status {r.returncode}, expected 1")
    if stderr != expected + "\n":
        failures.append(f"stderr:\n  got      {stderr!r}\n  expected {expected + chr(10)!r}")
    if left:
        failures.append(f"files were written: {left}")
    for f in failures:
        print(f"FAIL {scene}: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
