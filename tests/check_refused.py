#!/usr/bin/env python3
"""check_refused.py TP2 SCENE: tp2 refuses SCENE, a file of another course's
dialect (SPEC 3), with a positioned error.

Runs `tp2 SCENE out.ppm` from SCENE's folder (so the files it names are
found, as for a user) and checks: exit status 1, stderr is one line
`SCENE:LINE:COL: error: ...` naming a line and column inside SCENE, and no
file appeared."""
import os
import re
import subprocess
import sys
import tempfile


def main():
    tp2, scene = os.path.abspath(sys.argv[1]), sys.argv[2]
    name = os.path.basename(scene)
    with open(scene, "rb") as f:
        lines = f.read().split(b"\n")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.ppm")
        r = subprocess.run([tp2, name, out], capture_output=True, timeout=60,
                           cwd=os.path.dirname(os.path.abspath(scene)))
        left = os.listdir(tmp)
    err = r.stderr.decode("utf-8", "replace")
    m = re.fullmatch(re.escape(name) + r":(\d+):(\d+): error: [^\n]+\n", err)
    failures = []
    if r.returncode != 1:
        failures.append(f"exit status {r.returncode}, expected 1")
    if not m:
        failures.append(f"stderr is not one positioned error: {err!r}")
    elif not (1 <= int(m[1]) <= len(lines) and 1 <= int(m[2]) <= len(lines[int(m[1]) - 1]) + 1):
        failures.append(f"position {m[1]}:{m[2]} is outside the file")
    if left:
        failures.append(f"files were written: {left}")
    for f in failures:
        print(f"FAIL {scene}: {f}")
    if not failures:
        print(err.strip())
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
