#!/usr/bin/env python3
"""check_install.py CMAKE BUILD_DIR SOURCE_DIR: `cmake --install` into a
fresh prefix puts bin/tp2 and share/man/man1/tp2.1 there; the installed
tp2 runs and says its version and git revision; the man page is the
--help text (every option of --help is in it) and renders without
warnings (`man -l`, where man is installed). Outside a git checkout the
revision is "unknown"."""
import os
import re
import shutil
import subprocess
import sys
import tempfile


def main():
    cmake, build, source = sys.argv[1:4]
    failures = []

    def expect(cond, what):
        if not cond:
            failures.append(what)

    with tempfile.TemporaryDirectory() as prefix:
        r = subprocess.run([cmake, "--install", build, "--prefix", prefix],
                           capture_output=True, text=True, timeout=600)
        expect(r.returncode == 0, f"cmake --install: exit {r.returncode} {r.stderr!r}")
        tp2 = os.path.join(prefix, "bin", "tp2")
        page = os.path.join(prefix, "share", "man", "man1", "tp2.1")
        expect(os.access(tp2, os.X_OK), "no executable bin/tp2")
        expect(os.path.isfile(page), "no share/man/man1/tp2.1")
        if failures:
            return report(failures)

        version = subprocess.run([tp2, "--version"], capture_output=True, text=True, timeout=60)
        m = re.fullmatch(r"tp2 (\d+\.\d+\.\d+) \(git ([0-9a-f]{4,}(-dirty)?|unknown)\)\n",
                         version.stdout)
        expect(version.returncode == 0 and m and version.stderr == "",
               f"--version: exit {version.returncode}, {version.stdout!r} {version.stderr!r}")
        in_checkout = shutil.which("git") and subprocess.run(
            ["git", "-C", source, "rev-parse"], capture_output=True).returncode == 0
        if m and in_checkout:
            expect(m[2] != "unknown", "built from a git checkout, yet the revision is unknown")

        help_text = subprocess.run([tp2, "--help"], capture_output=True, text=True).stdout
        options = re.findall(r"^  (--[a-z-]+)", help_text, re.M)
        expect(len(options) >= 10, f"--help lists {options}")
        with open(page) as f:
            roff = f.read()
        expect(m is None or f'"tp2 {m[1]}"' in roff, "the man page's version differs")
        for opt in options:
            expect(opt.replace("-", "\\-") in roff, f"{opt} missing from the man page")

        if shutil.which("man"):
            env = dict(os.environ, MANWIDTH="80", MANPAGER="cat", LC_ALL="C")
            shown = subprocess.run(["man", "--warnings", "-l", page], capture_output=True,
                                   text=True, env=env, timeout=60)
            text = re.sub(r".\x08", "", shown.stdout)  # overstrike bold
            expect(shown.returncode == 0 and shown.stderr == "",
                   f"man -l: exit {shown.returncode}, {shown.stderr!r}")
            for heading in ("NAME", "SYNOPSIS", "DESCRIPTION", "OPTIONS", "EXIT STATUS"):
                expect(re.search(rf"^{heading}$", text, re.M), f"man -l shows no {heading}")
            for opt in options:
                expect(opt in text, f"man -l shows no {opt}")
        else:
            print("man not installed: the page was checked as text only")
        # Outside a checkout the revision is "unknown".
        outside = os.path.join(prefix, "not-a-checkout")
        os.mkdir(outside)
        header = os.path.join(prefix, "v.h")
        r = subprocess.run([cmake, f"-DSOURCE_DIR={outside}", f"-DOUTPUT={header}",
                            "-DVERSION=1.2.3", "-P",
                            os.path.join(source, "cmake", "GitRevision.cmake")],
                           capture_output=True, text=True, timeout=60,
                           env=dict(os.environ, GIT_CEILING_DIRECTORIES=prefix))
        with open(header) as f:
            text = f.read()
        expect(r.returncode == 0 and '#define TP2_GIT_REVISION "unknown"' in text and
               '#define TP2_VERSION "1.2.3"' in text, f"outside a checkout: {text!r}")
    return report(failures)


def report(failures):
    for f in failures:
        print(f"FAIL install: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
