#!/usr/bin/env python3
"""What must follow shaders/kinds.h by hand does (docs/adding-a-kind.md):
shapes.glsl's two dispatch chains test every GPU shape kind inside its
tier's #ifdef, flat_kind names exactly the flat kinds, pigments.glsl
colors every pigment kind but the solid (its default), and the helpers
that know each kind (tests/reference.py, bench/scene2pov.py, the fuzz
dictionary, test_parser.c's keyword lists) name every keyword.

usage: check_kinds.py [ROOT]"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import kinds  # noqa: E402

TIER_OF_IFDEF = {"TP2_FACETED": "FACETED", "TP2_CURVED": "CURVED"}


def function_body(text, name):
    """The lines of GLSL function `name`, from its signature to its closing
    brace at column 0."""
    m = re.search(r"^\w[\w ]* %s\(.*?^}" % name, text, re.M | re.S)
    return m.group(0) if m else ""


def kinds_by_tier(body):
    """{TP2_SHAPE_NAME: tier} of each kind a chain compares with, the tier
    being that of the #ifdef block around the comparison."""
    found, tier = {}, "BASIC"
    for line in body.splitlines():
        m = re.match(r"\s*#ifdef (\w+)", line)
        if m:
            tier = TIER_OF_IFDEF.get(m.group(1), tier)
        elif re.match(r"\s*#endif", line):
            tier = "BASIC"
        for name in re.findall(r"kind == TP2_SHAPE_(\w+)", line):
            found.setdefault(name, tier)
    return found


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else kinds.ROOT
    read = lambda *p: open(os.path.join(root, *p), encoding="utf-8").read()
    shapes, pigments = kinds.shapes(root), kinds.pigments(root)
    gpu = {}
    for s in shapes:  # a mesh is triangles: the first row of an id names it
        gpu.setdefault(s.id, s)
    bad = []

    glsl = read("shaders", "shapes.glsl")
    for fn in ("hit_object", "surface_point"):
        found = kinds_by_tier(function_body(glsl, fn))
        for s in gpu.values():
            if s.name not in found:
                bad.append(f"shapes.glsl's {fn} has no branch for TP2_SHAPE_{s.name}")
            elif found[s.name] != s.tier:
                bad.append(f"shapes.glsl's {fn} tests TP2_SHAPE_{s.name} in the "
                           f"{found[s.name]} builds, kinds.h says {s.tier}")
    flat = set(re.findall(r"TP2_SHAPE_(\w+)", function_body(glsl, "flat_kind")))
    want = {s.name for s in gpu.values() if s.flat}
    if flat != want:
        bad.append(f"shapes.glsl's flat_kind names {sorted(flat)}, "
                   f"kinds.h's flat kinds are {sorted(want)}")
    colors = read("shaders", "pigments.glsl")
    for p in pigments[1:]:
        if f"kind == TP2_PIGMENT_{p.name}" not in colors:
            bad.append(f"pigments.glsl does not color TP2_PIGMENT_{p.name}")

    words = [s.keyword for s in shapes] + [p.keyword for p in pigments]
    for path, quote in ((("tests", "reference.py"), '"'),
                        (("bench", "scene2pov.py"), "'"),
                        (("tests", "fuzz", "scene.dict"), '"')):
        text = read(*path)
        for w in words:
            if f"{quote}{w}{quote}" not in text:
                bad.append(f"{'/'.join(path)} does not name the kind {w!r}")
    # The "expected ..." lists: every keyword, in the list's order (another
    # spelling read the same may follow a keyword).
    parser = read("tests", "test_parser.c")
    for macro, rows in (("SHAPE_WORDS", shapes), ("PIGMENT_WORDS", pigments)):
        m = re.search(r'#define %s "(.*)"' % macro, parser)
        listed = re.findall(r"'(\w+)'", m.group(1)) if m else []
        keywords = [r.keyword for r in rows]
        if [w for w in listed if w in keywords] != keywords:
            bad.append(f"tests/test_parser.c's {macro} lists {listed}, "
                       f"not kinds.h's keywords {keywords} in order")

    for line in bad:
        print(line)
    print(f"{len(shapes)} shape kinds ({len(gpu)} on the GPU), {len(pigments)} "
          f"pigment kinds: {'ok' if not bad else f'{len(bad)} problems'}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
