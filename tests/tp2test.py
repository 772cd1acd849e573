"""tp2test.py: running tp2 and reading its images, for the Python tests."""
import os
import re
import sys
import tempfile
import struct
import subprocess


def run(tp2, args, env=None, timeout=600):
    """Runs tp2 with args; returns (status, stdout, stderr) as text."""
    e = dict(os.environ)
    e.update(env or {})
    r = subprocess.run([tp2] + list(args), capture_output=True, timeout=timeout, env=e)
    return r.returncode, r.stdout.decode("utf-8", "replace"), r.stderr.decode("utf-8", "replace")


def layer_env(layer):
    """The environment that runs tp2 on lavapipe as the device a test layer
    makes of it (tests/layers: "no_fp64" or "fused"), below the validation
    layer, so that validation sees tp2's own calls."""
    folder = os.environ.get("TP2_TEST_LAYERS")
    assert folder, "TP2_TEST_LAYERS is not set: run the tests through ctest"
    return {"XDG_DATA_HOME": os.path.join(folder, layer)}


def render(tp2, scene, out, size=(), options=(), env=None):
    """Renders scene to out; raises AssertionError unless exit 0 and silent."""
    status, _, err = run(tp2, list(options) + [scene, out] + [str(v) for v in size], env)
    assert status == 0 and err == "", f"tp2 {options} {scene}: exit {status}, stderr {err!r}"


def read_pfm(path):
    """(width, height, rows) with rows[y][x] = (r, g, b), y = 0 at the top."""
    with open(path, "rb") as f:
        data = f.read()
    magic, dims, scale, pixels = data.split(b"\n", 3)
    assert magic == b"PF" and float(scale) < 0, "little-endian colour PFM expected"
    w, h = map(int, dims.split())
    values = struct.unpack(f"<{3 * w * h}f", pixels[:12 * w * h])
    rows = [[values[3 * (r * w + x):3 * (r * w + x) + 3] for x in range(w)] for r in range(h)]
    return w, h, rows[::-1]


def read_ppm(path):
    """(width, height, RGB bytes) of a P6 file with maxval 255. One white
    space byte ends the header: the pixels may begin with bytes that look
    like white space themselves."""
    with open(path, "rb") as f:
        data = f.read()
    m = re.match(rb"P6\s+(\d+)\s+(\d+)\s+255\s", data)
    assert m, f"{path}: no P6 header with maxval 255"
    return int(m[1]), int(m[2]), data[m.end():]


def scene_file(folder, name, text):
    """Writes a scene and returns its path."""
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path


class CaseFailed(Exception):
    """A check a case cannot go on without failed."""


class CaseSkipped(Exception):
    """The case cannot run here (its reason is the message): exit 77,
    which ctest counts as skipped."""


class Case:
    """One test case's temporary folder and failures."""

    def __init__(self, tp2, tmp):
        self.tp2, self.tmp, self.failures = tp2, tmp, []

    def expect(self, cond, what):
        """Records a failure unless cond; returns cond."""
        if not cond:
            self.failures.append(what)
        return cond

    def require(self, cond, what):
        """Stops the case unless cond (the case's own premise)."""
        if not cond:
            raise CaseFailed(what)


def run_cases(namespace, case_class=Case):
    """main() of a case script: `SCRIPT --list` prints the names of the
    functions case_NAME in namespace; `SCRIPT TP2 NAME` runs one in a fresh
    folder and prints its failures. Returns the exit status (77: skipped,
    with the reason printed)."""
    cases = {n[5:]: f for n, f in namespace.items() if n.startswith("case_")}
    if sys.argv[1:] == ["--list"]:
        print("\n".join(cases))
        return 0
    if len(sys.argv) != 3 or sys.argv[2] not in cases:
        print(f"usage: {sys.argv[0]} TP2 CASE | --list", file=sys.stderr)
        return 2
    tp2, name = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        c = case_class(tp2, tmp)
        try:
            cases[name](c)
        except (CaseFailed, AssertionError) as e:
            c.failures.append(str(e))
        except CaseSkipped as e:
            print(f"SKIP {name}: {e}")
            return 77
    for f in c.failures[:10]:
        print(f"FAIL {name}: {f}")
    if len(c.failures) > 10:
        print(f"FAIL {name}: ... {len(c.failures) - 10} more")
    return 1 if c.failures else 0
