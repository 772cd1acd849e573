#!/usr/bin/env python3
"""gallery.py - renders every scene of scenes/ and of the corpus to PNG.

    python3 bench/gallery.py [--tp2 build/tp2] [--size 400x300] [--out docs/gallery]

Writes OUT/NAME.png for each scenes/*.txt and each ../shared/corpus/*.txt
and *.in (the files other courses wrote; not the refused dialects), at the
given size, with tp2's defaults, and OUT/index.md listing them with what
tp2 --stats says each took. Renders run on whatever device tp2 picks
(VK_ICD_FILENAMES is set to lavapipe when unset and it exists, as in the
benchmarks). Standard library only.
"""
import argparse
import glob
import os
import re
import subprocess
import sys

import lavapipe  # bench/lavapipe.py, beside this script

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
LVP_ICD = lavapipe.ICD


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tp2", default=os.path.join(REPO, "build", "tp2"))
    ap.add_argument("--size", default="400x300")
    ap.add_argument("--out", default=os.path.join(REPO, "docs", "gallery"))
    ap.add_argument("--corpus", default=os.path.join(REPO, "..", "shared", "corpus"))
    a = ap.parse_args()
    w, h = a.size.split("x")
    env = dict(os.environ)
    if "VK_ICD_FILENAMES" not in env and os.path.exists(LVP_ICD):
        env["VK_ICD_FILENAMES"] = LVP_ICD
    scenes = sorted(glob.glob(os.path.join(REPO, "scenes", "*.txt")))
    corpus = sorted(glob.glob(os.path.join(a.corpus, "*.txt")) +
                    glob.glob(os.path.join(a.corpus, "*.in")))
    os.makedirs(a.out, exist_ok=True)
    rows, failed = [], 0
    for group, paths in (("scenes/", scenes), ("corpus/", corpus)):
        for path in paths:
            name = os.path.splitext(os.path.basename(path))[0]
            png = os.path.join(a.out, name + ".png")
            r = subprocess.run([a.tp2, "--quiet", "--stats", path, png, w, h],
                               capture_output=True, env=env)
            err = r.stderr.decode("utf-8", "replace")
            total = sum(float(m) for m in re.findall(r"tp2: \w+ +([0-9.]+) s", err))
            if r.returncode != 0:
                failed += 1
                print(f"FAIL {path}: {err.strip()}", file=sys.stderr)
                continue
            rows.append(f"| {group}{os.path.basename(path)} | ![{name}]({name}.png) | "
                        f"{total:.2f} s |")
            print(f"{name}.png  {total:.2f} s")
    with open(os.path.join(a.out, "index.md"), "w") as f:
        f.write("# tp2 gallery\n\nEvery scene of `scenes/` and every corpus file, "
                f"{w} x {h}, tp2's defaults; time: the phases tp2 --stats reports "
                "(parse to write). Regenerate with `python3 bench/gallery.py`.\n\n"
                "| scene | image | time |\n|---|---|---|\n" + "\n".join(rows) + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
