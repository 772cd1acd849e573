"""The kinds of shaders/kinds.h, for the Python tests and bench scripts:
the one list of shape and pigment kinds (name, keyword, GPU id, tier,
flat)."""
import collections
import os
import re

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
Shape = collections.namedtuple("Shape", "name keyword id tier flat")
Pigment = collections.namedtuple("Pigment", "name keyword id")


def _rows(macro, path):
    """The rows X(...) of the list macro, as lists of fields."""
    text = open(path, encoding="utf-8").read().replace("\\\n", " ")
    line = re.search(r"^#define %s\(X\)(.*)$" % macro, text, re.M).group(1)
    return [[f.strip() for f in m.split(",")] for m in re.findall(r"X\(([^)]*)\)", line)]


def shapes(root=ROOT):
    path = os.path.join(root, "shaders", "kinds.h")
    return [Shape(n, k, int(i), t, f == "1") for n, k, i, t, f in _rows("TP2_SHAPES", path)]


def pigments(root=ROOT):
    path = os.path.join(root, "shaders", "kinds.h")
    return [Pigment(n, k, int(i)) for n, k, i in _rows("TP2_PIGMENTS", path)]

