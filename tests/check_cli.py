#!/usr/bin/env python3
"""check_cli.py TP2 CASE: the command line of SPEC 1, case by case.

`check_cli.py --list` prints the case names. Each case runs tp2 in a fresh
folder and checks exit status, the message, and which files exist after."""
import os
import sys

import tp2test
from tp2test import run

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "render", "cli.txt")
PARSE_ERROR = os.path.join(HERE, "errors", "not-a-number.txt")


def ppm_size(path):
    """(width, height) from a P6 header."""
    with open(path, "rb") as f:
        fields = f.read(64).split()
    assert fields[0] == b"P6", fields[0]
    return int(fields[1]), int(fields[2])


class Check(tp2test.Case):
    def out(self, name="out.ppm"):
        return os.path.join(self.tmp, name)

    def usage_error(self, args, message):
        """Exit 2, stderr starts with message, nothing written."""
        status, _, err = run(self.tp2, args)
        self.expect(status == 2, f"{args}: exit {status}, expected 2")
        self.expect(err.startswith(message), f"{args}: stderr {err!r}, expected {message!r}...")
        self.expect(os.listdir(self.tmp) == [], f"{args}: wrote {os.listdir(self.tmp)}")

    def failure(self, args, message, env=None):
        """Exit 1, message somewhere in stderr, nothing written."""
        status, _, err = run(self.tp2, args, env)
        self.expect(status == 1, f"{args}: exit {status}, expected 1")
        self.expect(message in err, f"{args}: stderr {err!r}, expected {message!r}")
        self.expect(os.listdir(self.tmp) == [], f"{args}: wrote {os.listdir(self.tmp)}")

    def renders(self, args, size, name="out.ppm"):
        """Exit 0, silent, and a PPM of the given size."""
        status, _, err = run(self.tp2, args)
        self.expect(status == 0 and err == "", f"{args}: exit {status}, stderr {err!r}")
        if status == 0:
            self.expect(ppm_size(self.out(name)) == size,
                        f"{args}: size {ppm_size(self.out(name))}, expected {size}")


def case_help(c):
    """--help prints the usage on stdout and exits 0."""
    status, out, _ = run(c.tp2, ["--help"])
    c.expect(status == 0 and out.startswith("usage: tp2"), f"--help: {status} {out[:40]!r}")


def case_usage_errors(c):
    """Wrong argument counts and values exit 2 with a tp2: message."""
    c.usage_error([], "tp2: expected an input and an output file")
    c.usage_error([SCENE], "tp2: expected an input and an output file")
    c.usage_error([SCENE, c.out(), "40"], "tp2: expected both X and Y, or neither")
    c.usage_error([SCENE, c.out(), "0", "30"], "tp2: X must be an integer from 1 to 32768, found '0'")
    c.usage_error([SCENE, c.out(), "40", "3x"], "tp2: Y must be an integer from 1 to 32768, found '3x'")
    c.usage_error([SCENE, c.out(), "40000", "30"], "tp2: X must be an integer")
    c.usage_error([SCENE, c.out(), "4", "3", "2"], "tp2: unexpected argument '2'")
    c.usage_error(["--bogus", SCENE, c.out()], "tp2: unknown option '--bogus'")
    c.usage_error(["--device", SCENE, c.out()], "tp2: --device needs a device index")
    c.usage_error(["--device"], "tp2: --device needs a device index, found 'nothing'")
    c.usage_error(["--precision", "half", SCENE, c.out()], "tp2: --precision needs 'float' or 'double'")
    c.usage_error([SCENE, c.out("out.jpg")], "tp2: cannot tell the format of")
    c.usage_error(["--bailout", "2", SCENE, c.out()], "tp2: --bailout needs a weight from 0 to 1")
    c.usage_error(["--spp", "0", SCENE, c.out()], "tp2: --spp needs a number of samples")
    c.usage_error(["--bvh-min", "x", SCENE, c.out()], "tp2: --bvh-min needs a positive number")


def case_input_missing(c):
    """A missing input file exits 1 naming it."""
    c.failure([os.path.join(c.tmp, "nope.txt"), c.out()], "tp2: cannot read '")


def case_output_dir_missing(c):
    """An output in a missing folder exits 1 and writes nothing."""
    status, _, err = run(c.tp2, [SCENE, os.path.join(c.tmp, "no", "out.ppm"), "8", "6"])
    c.expect(status == 1 and err.startswith("tp2: cannot write"), f"exit {status} {err!r}")
    c.expect(os.listdir(c.tmp) == [], f"wrote {os.listdir(c.tmp)}")


def case_bad_device(c):
    """A device index past the list exits 1."""
    c.failure(["--device", "99", SCENE, c.out()], "tp2: no device 99")


def case_no_vulkan(c):
    """With no Vulkan driver at all, one sentence says what to install."""
    env = {"VK_ICD_FILENAMES": "/nonexistent/icd.json", "VK_DRIVER_FILES": "/nonexistent/icd.json"}
    c.failure([SCENE, c.out()], "tp2: no Vulkan device found; install", env)


def case_list_devices(c):
    """--list-devices names lavapipe and marks a default."""
    status, out, _ = run(c.tp2, ["--list-devices"])
    c.expect(status == 0 and "llvmpipe" in out and "[default]" in out, f"{status} {out!r}")


def case_sizes(c):
    """X Y set the size; options may come before the positionals."""
    c.renders(["--device", "0", SCENE, c.out(), "37", "23"], (37, 23))
    c.renders([SCENE, c.out(), "1", "1"], (1, 1))


def case_atomic_overwrite(c):
    """A failed run leaves an existing output untouched; a good one replaces it."""
    path = c.out()
    with open(path, "wb") as f:
        f.write(b"old")
    status, _, _ = run(c.tp2, [PARSE_ERROR, path])
    with open(path, "rb") as f:
        c.expect(status == 1 and f.read() == b"old", "parse error changed the old output")
    c.renders([SCENE, path, "9", "7"], (9, 7))
    c.expect(sorted(os.listdir(c.tmp)) == ["out.ppm"], f"left {os.listdir(c.tmp)}")


def run_on_terminal(tp2, args):
    """Runs tp2 with a pseudo-terminal as stderr; returns (status, what it
    wrote there)."""
    import pty
    import subprocess
    main, side = pty.openpty()
    p = subprocess.Popen([tp2] + args, stderr=side, stdout=subprocess.DEVNULL)
    os.close(side)
    chunks = []
    while True:
        try:
            data = os.read(main, 4096)
        except OSError:  # the terminal closed with the process
            break
        if not data:
            break
        chunks.append(data)
    os.close(main)
    return p.wait(timeout=600), b"".join(chunks).decode("utf-8", "replace")


def case_progress_bar(c):
    """On a terminal a render that takes over a second shows a progress bar
    and clears it; --quiet and a pipe show nothing."""
    heavy = [os.path.join(HERE, "..", "scenes", "refraction.txt"), c.out(), "400", "300",
             "--bailout", "0", "--spp", "8"]
    status, err = run_on_terminal(c.tp2, heavy[:1] + heavy[1:])
    c.expect(status == 0, f"exit {status}: {err!r}")
    c.expect("tp2: [" in err and "%" in err, f"no progress bar on a terminal: {err!r}")
    status, err = run_on_terminal(c.tp2, ["--quiet"] + heavy)
    c.expect(status == 0 and err == "", f"--quiet on a terminal: exit {status}, {err!r}")
    status, _, err = run(c.tp2, heavy)
    c.expect(status == 0 and err == "", f"a pipe: exit {status}, {err!r}")


def case_large_image(c):
    """8192 x 8192 renders on lavapipe (a whole float image, 1 GiB, once had
    to fit its 128 MiB storage-buffer limit) in bounded memory: the rows
    stream to the file band by band, so tp2's peak RSS stays below 300 MiB
    (about 180 measured with validation on; holding even the 8-bit image
    would add 192 MiB). Every pixel of the empty scene is the background."""
    import resource
    scene = tp2test.scene_file(c.tmp, "empty.txt", "0 0 0\n0 0 -1\n0 1 0\n45\n"
                               "1\n0 0 0 1 1 1 0 0 0\n0\n0\n0\n")
    out = c.out()
    status, _, err = run(c.tp2, [scene, out, "8192", "8192"])
    rss_mib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    c.require(status == 0 and err == "", f"exit {status}, stderr {err!r}")
    c.expect(rss_mib < 300, f"peak RSS {rss_mib:.0f} MiB")
    header = b"P6\n8192 8192\n255\n"
    with open(out, "rb") as f:
        c.expect(f.read(len(header)) == header, "header")
        gray = bytes([128]) * (1 << 20)
        total = 0
        while chunk := f.read(1 << 20):
            c.require(chunk == gray[:len(chunk)], f"a pixel other than gray near byte {total}")
            total += len(chunk)
    c.expect(total == 8192 * 8192 * 3, f"{total} bytes of pixels")


def case_extreme_shapes(c):
    """The widest and the tallest images SPEC allows render in full."""
    for name, w, h in (("wide.ppm", 32768, 8), ("tall.ppm", 8, 32768)):
        c.renders([SCENE, c.out(name), str(w), str(h)], (w, h), name)
        want = len(f"P6\n{w} {h}\n255\n") + w * h * 3
        c.expect(os.path.getsize(c.out(name)) == want, f"{name}: {os.path.getsize(c.out(name))} bytes")


def case_formats(c):
    """.png and .pfm outputs are written with their signatures."""
    for name, magic in (("o.png", b"\x89PNG"), ("o.pfm", b"PF\n"), ("o.PPM", b"P6\n")):
        status, _, err = run(c.tp2, [SCENE, c.out(name), "8", "6"])
        with open(c.out(name), "rb") as f:
            c.expect(status == 0 and f.read(len(magic)) == magic, f"{name}: {status} {err!r}")


if __name__ == "__main__":
    sys.exit(tp2test.run_cases(globals(), Check))
