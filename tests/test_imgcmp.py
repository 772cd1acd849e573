#!/usr/bin/env python3
"""test_imgcmp.py IMGCMP: checks tp2-imgcmp on small images made here.

Identical images (PPM P6, P3 with comments, PFM in both byte orders, rows
bottom to top) give psnr=inf; known changes give the exact counts;
thresholds set the exit status; --diff writes |A - B| x 8; malformed
files, size mismatches and bad usage exit 2 with a `tp2-imgcmp: ` message
and never crash. Prints "N passed, M failed" last."""
import math
import os
import random
import struct
import subprocess
import sys
import tempfile

W, H = 5, 3
passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print(f"FAIL {what}")


def levels():
    """The asymmetric test image: W x H pixels of 3 distinct levels each."""
    return [[[10 + 15 * (y * W + x) + 5 * c for c in range(3)]
             for x in range(W)] for y in range(H)]


def p6(img, maxval=255):
    h, w = len(img), len(img[0])
    data = bytes(v for row in img for px in row for v in px)
    return f"P6\n{w} {h}\n{maxval}\n".encode() + data


def p3(img):
    h, w = len(img), len(img[0])
    lines = ["P3", "# a comment", f"{w} {h} # size", "255"]
    lines += [" ".join(str(v) for px in row for v in px) for row in img]
    return ("\n".join(lines) + "\n").encode()


def pfm(img, little=True, scale_of=lambda v: v / 255.0):
    """PF with rows bottom to top; values scale_of(level)."""
    h, w = len(img), len(img[0])
    fmt = "<" if little else ">"
    out = f"PF\n{w} {h}\n{-1.0 if little else 1.0}\n".encode()
    for row in reversed(img):
        for px in row:
            out += struct.pack(fmt + "3f", *(scale_of(v) for v in px))
    return out


def parse(stdout):
    return dict(kv.split("=", 1) for kv in stdout.split())


class Runner:
    def __init__(self, exe, tmp):
        self.exe, self.tmp, self.n = exe, tmp, 0

    def file(self, data, suffix=".ppm"):
        self.n += 1
        path = os.path.join(self.tmp, f"f{self.n}{suffix}")
        with open(path, "wb") as f:
            f.write(data)
        return path

    def run(self, *args):
        r = subprocess.run([self.exe, *args], capture_output=True, timeout=60)
        return (r.returncode, r.stdout.decode("utf-8", "replace"),
                r.stderr.decode("utf-8", "replace"))


def expect_ok(rn, what, a, b, want, *opts, status=0):
    rc, out, err = rn.run(*opts, a, b)
    check(rc == status, f"{what}: exit {rc}, want {status} (stderr {err!r})")
    got = parse(out) if rc in (0, 1) else {}
    for key, value in want.items():
        check(got.get(key) == value,
              f"{what}: {key}={got.get(key)}, want {value} (line {out!r})")
    return got


def expect_error(rn, what, *args):
    rc, out, err = rn.run(*args)
    check(rc == 2, f"{what}: exit {rc}, want 2 (stderr {err!r})")
    check(err.startswith("tp2-imgcmp: "), f"{what}: stderr {err!r}")
    check(out == "", f"{what}: stdout {out!r}")


def main():
    exe = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        rn = Runner(exe, tmp)
        img = levels()
        a = rn.file(p6(img))
        same = {"psnr": "inf", "mae": "0.000000", "max": "0",
                "within1": "1.000000", "bad8": "0", "pixels": "15"}

        # Identical, across formats; PFM rows are bottom to top.
        expect_ok(rn, "identical P6", a, rn.file(p6(img)), same)
        expect_ok(rn, "P6 vs P3", a, rn.file(p3(img)), same)
        got = expect_ok(rn, "P6 vs PFM", a, rn.file(pfm(img), ".pfm"), same)
        check("fmax" not in got, "fmax only when both are PFM")
        la, be = rn.file(pfm(img), ".pfm"), rn.file(pfm(img, little=False), ".pfm")
        expect_ok(rn, "PFM LE vs BE", la, be, dict(same, fmax="0"))
        expect_ok(rn, "P6 maxval 65535",
                  a, rn.file(b"P6\n5 3\n65535\n" + b"".join(
                      struct.pack(">H", v * 257) for row in img for px in row
                      for v in px)), same)
        flipped = rn.file(p6(img[::-1]))
        got = expect_ok(rn, "flipped differs", a, flipped, {"pixels": "15"})
        check(got.get("psnr") != "inf", "a vertical flip is noticed")

        # PFM quantised as tp2 does: clamp, round(255 c), NaN 0.
        odd = [[[0, 0, 0] for _ in range(W)] for _ in range(H)]
        odd[0][0] = [-1, 256, 127.5]  # scaled by 1/255 below
        q = rn.file(pfm(odd, scale_of=lambda v: v / 255.0), ".pfm")
        ref = [[[0, 0, 0] for _ in range(W)] for _ in range(H)]
        ref[0][0] = [0, 255, 128]
        expect_ok(rn, "PFM quantised", rn.file(p6(ref)), q, same)
        nan = rn.file(pfm(odd, scale_of=lambda v: math.nan if v == 256 else 0.0), ".pfm")
        zero = [[[0, 0, 0] for _ in range(W)] for _ in range(H)]
        expect_ok(rn, "PFM NaN is 0", rn.file(p6(zero)), nan, same)
        got = expect_ok(rn, "PFM NaN vs 0 fmax", rn.file(pfm(zero), ".pfm"), nan,
                        {"fmax": "inf"})
        got = expect_ok(rn, "PFM raw fmax", la,
                        rn.file(pfm(img, scale_of=lambda v: v / 255.0 + 0.25), ".pfm"),
                        {"fmax": "0.25"})

        # One channel of one pixel off by 1: within tolerance everywhere.
        one = levels()
        one[1][3][2] += 1
        expect_ok(rn, "off by 1", a, rn.file(p6(one)),
                  {"max": "1", "within1": "1.000000", "bad8": "0",
                   "mae": f"{1 / 45:.6f}",
                   "psnr": f"{10 * math.log10(255 ** 2 / (1 / 45)):.4f}"})

        # One channel of one pixel off by 20, another pixel's channel by 5.
        bad = levels()
        bad[2][4][0] -= 20
        bad[0][1][1] += 5
        b = rn.file(p6(bad))
        counts = {"max": "20", "bad8": "1", "within1": f"{43 / 45:.6f}",
                  "mae": f"{25 / 45:.6f}", "pixels": "15",
                  "psnr": f"{10 * math.log10(255 ** 2 / (425 / 45)):.4f}"}
        expect_ok(rn, "one bad pixel", a, b, counts)

        # Thresholds.
        expect_ok(rn, "--max-bad8 0", a, b, counts, "--max-bad8", "0", status=1)
        expect_ok(rn, "--max-bad8 1", a, b, counts, "--max-bad8", "1")
        expect_ok(rn, "--min-within1 0.96", a, b, counts, "--min-within1", "0.96",
                  status=1)
        expect_ok(rn, "--min-within1 0.95", a, b, counts, "--min-within1", "0.95")
        expect_ok(rn, "both met", a, b, counts, "--min-within1", "0.9",
                  "--max-bad8", "3")
        expect_ok(rn, "identical, strict", a, a, same, "--min-within1", "1",
                  "--max-bad8", "0")
        rc, _, err = rn.run("--max-bad8", "0", a, b)
        check(err.startswith("tp2-imgcmp: "), f"threshold message {err!r}")

        # --diff: |A - B| x 8, clamped.
        d = os.path.join(tmp, "diff.ppm")
        expect_ok(rn, "--diff", a, b, counts, "--diff", d)
        with open(d, "rb") as f:
            data = f.read()
        want = [[[0, 0, 0] for _ in range(W)] for _ in range(H)]
        want[2][4][0] = 160
        want[0][1][1] = 40
        check(data == p6(want), "--diff image")
        big = levels()
        big[1][1][1] += 40
        expect_ok(rn, "--diff clamps", a, rn.file(p6(big)), {"max": "40"},
                  "--diff", d)
        with open(d, "rb") as f:
            data = f.read()
        check(len(data) == 11 + 45 and data[11 + (1 * W + 1) * 3 + 1] == 255,
              "--diff clamps at 255")
        expect_error(rn, "--diff into a missing folder", "--diff",
                     os.path.join(tmp, "no", "d.ppm"), a, b)

        # Usage errors.
        expect_error(rn, "no arguments")
        expect_error(rn, "one file", a)
        expect_error(rn, "three files", a, a, a)
        expect_error(rn, "unknown option", "--nope", a, a)
        expect_error(rn, "missing value", a, a, "--max-bad8")
        expect_error(rn, "bad fraction", "--min-within1", "1.5", a, a)
        expect_error(rn, "bad fraction text", "--min-within1", "x", a, a)
        expect_error(rn, "negative count", "--max-bad8", "-1", a, a)
        expect_error(rn, "fractional count", "--max-bad8", "1.5", a, a)
        rc, out, _ = rn.run("--help")
        check(rc == 0 and out.startswith("usage: tp2-imgcmp"), "--help")

        # Input errors.
        expect_error(rn, "missing file", a, os.path.join(tmp, "none.ppm"))
        expect_error(rn, "size mismatch", a, rn.file(p6([row[:4] for row in img])))
        good = p6(img)
        malformed = {
            "empty": b"",
            "one byte": b"P",
            "bad magic": b"P5\n5 3\n255\n" + good[11:],
            "truncated P6": good[:-1],
            "header only": b"P6\n5 3\n255\n",
            "no size": b"P6\n",
            "zero width": b"P6\n0 3\n255\n",
            "negative width": b"P6\n-5 3\n255\n" + good[11:],
            "huge": b"P6\n32768 32768\n255\n" + good[11:],
            "too wide": b"P6\n99999999999999999999 1\n255\n",
            "maxval 0": b"P6\n5 3\n0\n" + good[11:],
            "maxval 70000": b"P6\n5 3\n70000\n" + good[11:],
            "junk in size": b"P6\n5x 3\n255\n" + good[11:],
            "no space after maxval": b"P6\n5 3\n255" + good[11:],
            "sample above maxval": b"P6\n5 3\n15\n" + good[11:],
            "P3 short": b"P3\n5 3\n255\n1 2 3\n",
            "P3 word": b"P3\n5 3\n255\n" + b"1 " * 44 + b"x\n",
            "P3 above maxval": b"P3\n1 1\n255\n1 2 256\n",
            "PFM truncated": pfm(img)[:-1],
            "PFM scale 0": b"PF\n5 3\n0\n" + pfm(img)[12:],
            "PFM scale nan": b"PF\n5 3\nnan\n" + pfm(img)[12:],
            "PFM scale junk": b"PF\n5 3\n-1.0x\n" + pfm(img)[12:],
            "PFM long scale": b"PF\n5 3\n" + b"1" * 200 + b"\n",
        }
        for what, data in malformed.items():
            expect_error(rn, what, a, rn.file(data))
        expect_error(rn, "a folder", a, tmp)

        # Random damage to valid files: a result or a clean error, never a
        # crash (negative status) or a threshold failure (none given).
        rng = random.Random(1)
        seeds = [good, p3(img), pfm(img), pfm(img, little=False)]
        crashes = 0
        for i in range(300):
            data = bytearray(rng.choice(seeds))
            for _ in range(rng.randint(1, 4)):
                op = rng.randrange(3)
                k = rng.randrange(len(data) + 1)
                if op == 0 and data:
                    data[min(k, len(data) - 1)] = rng.randrange(256)
                elif op == 1:
                    del data[k:]
                else:
                    data[k:k] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 8)))
            rc, out, err = rn.run(a, rn.file(bytes(data)))
            ok = rc == 0 or (rc == 2 and err.startswith("tp2-imgcmp: ")
                             and "Sanitizer" not in err)
            if not ok:
                crashes += 1
                if crashes <= 3:
                    print(f"  mutant {i}: exit {rc}, stderr {err[:300]!r}")
        check(crashes == 0, f"{crashes} of 300 damaged files mishandled")

    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
