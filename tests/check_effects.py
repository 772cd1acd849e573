#!/usr/bin/env python3
"""check_effects.py TP2 CASE: sampling, lens, fog, area lights, BVH, cache.

`check_effects.py --list` prints the case names. Expected values come from
SPEC 3-4 worked out here in double precision, never from tp2's output;
float images are compared within 1e-5 unless a case says otherwise."""
import glob
import json
import math
import os
import re
import sys

import tp2test
from tp2test import layer_env, read_pfm, read_ppm, render, run, scene_file

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench"))
import mesh  # noqa: E402  (bench/mesh.py: the OBJ generator)

HERE = os.path.dirname(os.path.abspath(__file__))
TOL = 1e-5

# A camera at the origin looking down -z at a plane z = -5 facing it; the
# vertical fov makes one pixel exactly 1 x 1 unit on the plane at 5 x 4.
FOV_1UNIT = math.degrees(2 * math.atan(0.4))
CAMERA = f"0 0 0\n0 0 -1\n0 1 0\n{FOV_1UNIT!r}\n"
WALL = "plane 0 0 1 5\n"  # z = -5, normal toward the camera
AMBIENT_ONLY = "1\n1 0 0 0 0 0 0\n"  # ka = 1, nothing else


def approx(a, b, tol=TOL):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def pixel_dir(i, j, w, h, fov):
    """SPEC 4's camera ray for the camera above (w = -z, u = x, v = y)."""
    t = math.tan(math.radians(fov) / 2)
    x = (2 * (i + 0.5) / w - 1) * t * w / h
    y = (1 - 2 * (j + 0.5) / h) * t
    n = math.sqrt(x * x + y * y + 1)
    return x / n, y / n, -1 / n


class Case(tp2test.Case):
    def image(self, text, size=(5, 4), options=(), name="s", env=None):
        """Renders scene text to PFM; returns its rows."""
        scene = scene_file(self.tmp, name + ".txt", text)
        out = os.path.join(self.tmp, name + ".pfm")
        render(self.tp2, scene, out, size, options, env)
        return read_pfm(out)[2]


def case_fog_background(c):
    """With fog, a ray that hits nothing returns the fog color."""
    rows = c.image(CAMERA + "1\n0 0 0 1 1 1 0 0 0\n0\n0\n0\nfog 0.2 0.4 0.6 0.3\n")
    for row in rows:
        for p in row:
            c.expect(approx(p, (0.2, 0.4, 0.6)), f"fog miss {p}")


def case_fog_distance(c):
    """A segment of length t keeps exp(-density t) of its color."""
    rows = c.image(CAMERA + "1\n0 0 0 1 1 1 0 0 0\n1\nsolid 0.9 0.5 0.1\n" + AMBIENT_ONLY +
                   "1\n0 0 " + WALL + "fog 0.1 0.2 0.3 0.15\n")
    for j, row in enumerate(rows):
        for i, p in enumerate(row):
            t = 5 / -pixel_dir(i, j, 5, 4, FOV_1UNIT)[2]
            keep = math.exp(-0.15 * t)
            want = [keep * a + (1 - keep) * f for a, f in zip((0.9, 0.5, 0.1), (0.1, 0.2, 0.3))]
            c.expect(approx(p, want), f"fog at ({i},{j}): {p} != {want}")


def stratified_scene(extra=""):
    """Checks of side 1 whose vertical edges run through every pixel's center."""
    return (CAMERA + "1\n0 0 0 1 1 1 0 0 0\n1\nchecker 1 0.5 0  0 0.25 1  1\n" +
            AMBIENT_ONLY + "1\n0 0 " + WALL + extra)


def case_samples_stratified(c):
    """Stratified samples split a pixel cut in half by an edge exactly 8 : 8."""
    rows = c.image(stratified_scene("samples 16\n"))
    want = (0.5, 0.375, 0.5)
    for row in rows:
        for p in row:
            c.expect(approx(p, want), f"half-covered pixel {p} != {want}")


def case_spp_overrides_scene(c):
    """--spp overrides the scene's samples; samples 1 is the pixel center."""
    a = c.image(stratified_scene("samples 16\n"), options=["--spp", "4"], name="a")
    b = c.image(stratified_scene(), options=["--spp", "4"], name="b")
    one = c.image(stratified_scene("samples 1\n"), name="one")
    center = c.image(stratified_scene(), name="center")
    c.expect(a == b, "--spp 4 differs between scenes with and without 'samples 16'")
    c.expect(one == center, "'samples 1' differs from the default pixel-center sample")
    # Three samples cannot split a half-covered pixel evenly.
    three = c.image(stratified_scene("samples 16\n"), options=["--spp", "3"], name="three")
    c.expect(not approx(three[0][0], (0.5, 0.375, 0.5)), "--spp 3 was ignored")


def effects_scene():
    with open(os.path.join(HERE, "render", "effects.txt")) as f:
        return f.read()


def case_deterministic(c):
    """The same command gives the same image, with every random feature on."""
    a = c.image(effects_scene(), (64, 48), name="a")
    b = c.image(effects_scene(), (64, 48), name="b")
    c.expect(a == b, "two runs of the same command differ")


def lens_scene(lens):
    return (CAMERA + "1\n0 0 0 1 1 1 0 0 0\n1\nchecker 1 1 1  0 0 0  0.7\n" + AMBIENT_ONLY +
            "1\n0 0 " + WALL + "samples 16\n" + lens)


def case_lens_focal_plane(c):
    """Everything on the focal plane stays sharp: the lens image equals the
    pinhole image up to samples that land on a check's edge."""
    pinhole = c.image(lens_scene(""), (20, 16), name="pinhole")
    lens = c.image(lens_scene("lens 0.5 5\n"), (20, 16), name="lens")
    diffs = [abs(a[0] - b[0]) for ra, rb in zip(pinhole, lens) for a, b in zip(ra, rb)]
    c.expect(max(diffs) <= 1 / 16 + TOL, f"a focal-plane pixel moved by {max(diffs)}")
    c.expect(sum(d > TOL for d in diffs) <= 4, f"{sum(d > TOL for d in diffs)} pixels changed")


def case_lens_blurs(c):
    """Off the focal plane the lens blurs: a small sphere in front of the wall
    gains many partly covered pixels."""
    text = (CAMERA + "1\n0 0 0 1 1 1 0 0 0\n2\nsolid 1 1 1\nsolid 0 0 0\n" + AMBIENT_ONLY +
            "2\n0 0 sphere 0 0 -2 0.3\n1 0 " + WALL + "samples 64\n")
    def partial(rows):
        return sum(0.05 < p[0] < 0.95 for row in rows for p in row)
    sharp = partial(c.image(text, (40, 32), name="sharp"))
    blurred = partial(c.image(text + "lens 0.2 5\n", (40, 32), name="blurred"))
    c.expect(blurred > 3 * sharp, f"partial pixels: {blurred} with lens, {sharp} without")


def shadow_scene(area):
    """Looking down at a floor beside a sphere lit from above and aside."""
    return ("0 0 10\n0 0 0\n0 1 0\n60\n"
            "2\n0 0 0 0.2 0.2 0.2 0 0 0\n3 0 6 1 1 1 1 0 0\n"
            "1\nsolid 1 1 1\n1\n1 1 0 1 0 0 0\n"
            "2\n0 0 sphere 0 0 2 1\n0 0 plane 0 0 1 0\n" + area)


def case_arealight_soft_shadow(c):
    """An area light shrinks the umbra and adds a penumbra; a tiny one is a
    point light again."""
    point = c.image(shadow_scene(""), (40, 40), name="point")
    area = c.image(shadow_scene("arealight 1 0.8 64\n"), (40, 40), name="area")
    tiny = c.image(shadow_scene("arealight 1 1e-6 16\n"), (40, 40), name="tiny")
    ambient = 0.2
    def umbra(rows):
        return sum(abs(p[0] - ambient) < TOL for row in rows for p in row)
    c.expect(0 < umbra(area) < umbra(point), f"umbra {umbra(area)} vs point {umbra(point)}")
    partial = sum(ambient + 0.01 < a[0] < p[0] - 0.01
                  for ra, rp in zip(area, point) for a, p in zip(ra, rp))
    c.expect(partial >= 20, f"only {partial} penumbra pixels")
    worst = max(abs(a[0] - b[0]) for ra, rb in zip(point, tiny) for a, b in zip(ra, rb))
    c.expect(worst < 1e-4, f"a tiny area light differs from the point light by {worst}")


def occluders_scene():
    """A floor under a 5 x 5 grid of spheres (through the BVH by default)
    and a wide arealight: many points see some of its samples blocked by
    one sphere, some by another, some not at all."""
    spheres = "".join(f"0 0 sphere {x} {y} 1.5 0.45\n"
                      for x in (-2, -1, 0, 1, 2) for y in (-2, -1, 0, 1, 2))
    return ("0 -3 9\n0 0 0\n0 0 1\n60\n"
            "2\n0 0 0 0.2 0.2 0.2 0 0 0\n0.5 0.3 6 1 1 1 1 0 0\n"
            "1\nsolid 1 1 1\n1\n1 1 0 1 0 0 0\n"
            "26\n" + spheres + "0 0 plane 0 0 1 0\narealight 1 2 16\n")


def case_occluder_hint_same_image(c):
    """Shadow rays toward the arealight test the last sample's occluder
    first: any occluder decides alike, so the image is the same bytes as
    without the hint (TP2_OCCLUDER_HINT=0), through the BVH and the loop."""
    scene = scene_file(c.tmp, "s.txt", occluders_scene())
    for name, bvh_min in (("bvh", "1"), ("loop", "100000")):
        images = []
        for hint in ("1", "0"):
            out = os.path.join(c.tmp, f"{name}{hint}.ppm")
            status, _, err = run(c.tp2, ["--bvh-min", bvh_min, scene, out, "64", "48"],
                                 {"TP2_OCCLUDER_HINT": hint})
            c.require(status == 0 and "validation" not in err, f"exit {status}: {err!r}")
            images.append(read_ppm(out)[2])
        partial = sum(60 < v < 250 for v in images[0][0::3])
        c.expect(partial >= 200, f"{name}: only {partial} pixels in a penumbra")
        c.expect(images[0] == images[1], f"{name}: the occluder hint changed the image")


def mirror_chain(kr, ambient, bailout, depth=10, background=0.5):
    """SPEC 4 with tp2's pruning for a ray bouncing between two facing
    mirrors of reflectance kr lit only by ambient: ray k has weight kr^k; a
    child of weight w below the bailout is pruned while the pruned weights
    stay within the bailout, adding w * 0.5 instead of what it would see."""
    value, budget = 0.0, bailout
    for k in range(depth + 1):
        value += kr ** k * ambient
        w = kr ** (k + 1)
        if k == depth:
            return value + w * background  # past the depth limit: gray
        if w < bailout and w <= budget:
            return value + w * 0.5
    return value


def case_bailout(c):
    """--bailout W prunes a ray of weight below W only while the sample's
    pruned weights add up to at most W, and a pruned ray adds its weight
    times 0.5: between two mirrors of kr 0.5 the center pixel stops at the
    first weight at most W (W = 0.1: after 4 rays; the default 1/255:
    after 8) instead of 11 rays and the gray tail (W = 0, and the double
    reference); the error is at most W / 2 (no ray here brings more than 1)."""
    mirrors = (CAMERA + "1\n0 0 0 0.2 0.2 0.2 0 0 0\n1\nsolid 1 1 1\n1\n1 0 0 1 0.5 0 0\n"
               "2\n0 0 plane 0 0 1 1\n0 0 plane 0 0 -1 1\n")
    exact = mirror_chain(0.5, 0.2, 0)
    c.expect(abs(exact - (0.2 * sum(0.5 ** k for k in range(11)) + 0.5 ** 11 * 0.5)) < 1e-12,
             "mirror_chain's exact value is not the closed form")
    for options, w in (([], 1 / 255), (["--bailout", "0"], 0),
                       (["--precision", "double"], 0), (["--bailout", "0.1"], 0.1)):
        want = mirror_chain(0.5, 0.2, w)
        center = c.image(mirrors, (5, 5), options, name="b")[2][2]
        c.expect(approx(center, (want,) * 3), f"{options}: center {center}, want {want}")
        c.expect(abs(exact - center[0]) <= w / 2 + TOL, f"{options}: error above the bound")
    c.expect(mirror_chain(0.5, 0.2, 0.1) != exact and mirror_chain(0.5, 0.2, 1 / 255) != exact,
             "the chain prunes nothing: the test would not see pruning")


def bailout_worst_case(lights):
    """The worst case for pruning we could build: the camera inside a glass
    sphere (kr 0.3, kt 0.6, ior 1.3: rays off the center meet total
    internal reflection, so chains of glass rays run to depth 10), with
    glass and mirror spheres inside and a checker floor outside, under
    `lights` dim point lights. Every finish's local color is at most 0.1
    and kr + kt <= 0.9, so no ray returns more than 0.1 / (1 - 0.9) = 1
    (the gray past the depth limit, 0.5, too): the bound applies as stated."""
    c0 = 0.2
    ci = 0.05 / lights  # sum of lights' colors 0.05; kd + ks = 1: at most 0.05
    light_lines = "".join(
        f"{3 * math.cos(k * 2.4):.4f} {2 - 0.3 * k:.4f} {3 * math.sin(k * 2.4):.4f} "
        f"{ci!r} {ci!r} {ci!r} 1 0 0\n" for k in range(lights))
    return (f"0.7 0.4 2.5\n-0.5 -0.3 -4\n0 1 0\n70\n{lights + 1}\n"
            f"0 0 0 {c0} {c0} {c0} 0 0 0\n" + light_lines +
            "3\nsolid 1 1 1\nchecker 1 1 1 0.2 0.3 0.9 1\nsolid 0.9 0.5 0.3\n"
            "3\n0.25 0.5 0.5 30 0.3 0.6 1.3\n"   # glass: local <= 0.05 + 0.05
            "0.25 0.5 0.5 10 0.9 0 1\n"           # mirror
            "0.25 0.5 0.5 5 0.3 0.6 0.8\n"        # glass thinner than air
            "6\n0 0 sphere 0 0 0 4\n1 0 plane 0 1 0 6\n"
            "0 0 sphere -1 -1 -1 1.2\n2 1 sphere 1.2 0.5 -1.5 0.8\n"
            "0 2 sphere 0 1.5 0.5 0.6\n0 1 sphere -1.5 1 1 0.5\n")


def case_bailout_bound(c):
    """Pruning's error is bounded by construction: what it prunes adds up
    to at most the bailout of weight per sample, each pruned ray adding
    half its weight, so where no ray returns more than 1 the default image
    is within half a level of --bailout 0 at every pixel, in the worst
    case we could build (glass around the camera, total internal
    reflection, 1 and 12 lights), while it still prunes (fewer rays than
    --bailout 0)."""
    for lights in (1, 12):
        text = bailout_worst_case(lights)
        exact = c.image(text, (64, 48), ["--bailout", "0"], name=f"exact{lights}")
        pruned = c.image(text, (64, 48), [], name=f"pruned{lights}")
        worst = max(abs(a - b) for ra, rb in zip(exact, pruned)
                    for pa, pb in zip(ra, rb) for a, b in zip(pa, pb))
        c.expect(worst <= 0.5 / 255 + TOL,
                 f"{lights} lights: pruning moved a pixel by {worst * 255:.3f} levels")
        counts = []
        for options in (["--bailout", "0"], []):
            status, _, err = run(c.tp2, ["--stats"] + options +
                                 [os.path.join(c.tmp, f"exact{lights}.txt"),
                                  os.path.join(c.tmp, "count.pfm"), "64", "48"])
            m = re.search(r"rays total +(\d+)", err)
            counts.append(int(m[1]) if m else 0)
        c.expect(0 < counts[1] < counts[0], f"{lights} lights: rays {counts}, pruning pruned nothing")


def slab_value(z, direction, depth, planes=(-3, -1, 1, 3)):
    """SPEC 4 for a ray along z between the planes z = planes, each with ka 1,
    kr = kt = 0.5, ior 1, under ambient 0.2: what the ray returns."""
    ahead = [p for p in planes if (p - z) * direction > 0]
    if not ahead:
        return 0.5
    hit = min(ahead, key=lambda p: abs(p - z))
    if depth + 1 > 10:
        return 0.2 + 1.0 * 0.5
    return (0.2 + 0.5 * slab_value(hit, -direction, depth + 1, planes)
            + 0.5 * slab_value(hit, direction, depth + 1, planes))


def case_many_samples_full_trees(c):
    """Every sample of a pixel traces a full tree of reflections and
    transmissions between four planes: 64 samples must give the value of one
    (lavapipe stops a shader invocation's loops after 65535 iterations in
    all, which 64 such samples in one invocation used to overrun)."""
    slabs = (CAMERA + "1\n0 0 0 0.2 0.2 0.2 0 0 0\n1\nsolid 1 1 1\n1\n1 0 0 1 0.5 0.5 1\n"
             "4\n0 0 plane 0 0 1 1\n0 0 plane 0 0 -1 1\n0 0 plane 0 0 1 3\n"
             "0 0 plane 0 0 -1 3\n")
    want = slab_value(0, -1, 0)
    for spp in ("1", "64"):
        center = c.image(slabs, (5, 5), ["--bailout", "0", "--spp", spp], name="slabs")[2][2]
        c.expect(approx(center, (want,) * 3, 1e-4), f"spp {spp}: center {center}, want {want}")


def deep_scene(c):
    """A scene whose unpruned trees need more loop iterations than lavapipe
    allows one invocation (about 460 rays, each testing 84 objects for
    itself and for 8 lights, in a plain loop: --bvh-min keeps the BVH out)."""
    spheres = "".join(f"0 0 sphere {100 + 3 * i} 0 0 1\n" for i in range(80))
    lights = "".join(f"{x} {y} {z} 0.1 0.1 0.1 1 0 0\n"
                     for x in (-1, 1) for y in (-1, 1) for z in (-0.5, 0.5))
    text = (CAMERA + "9\n0 0 0 0.2 0.2 0.2 0 0 0\n" + lights + "1\nsolid 1 1 1\n"
            "1\n1 0.1 0 1 0.5 0.5 1\n84\n0 0 plane 0 0 1 1\n0 0 plane 0 0 -1 1\n"
            "0 0 plane 0 0 1 3\n0 0 plane 0 0 -1 3\n" + spheres)
    return scene_file(c.tmp, "deep.txt", text)


def case_walks_go_on(c):
    """Walks too long for one lavapipe invocation go on across passes (one
    ray per pass, a few, or as many as fit) and give the same image to the
    bit, with no warning; --stats shows the extra passes."""
    scene = deep_scene(c)
    images = []
    for rays in ("1", "7", "256"):
        out = os.path.join(c.tmp, f"deep-{rays}.pfm")
        status, _, err = run(c.tp2, ["--stats", "--bvh-min", "1000", "--bailout", "0",
                                     scene, out, "8", "8"], {"TP2_PASS_RAYS": rays})
        c.require(status == 0 and "warning" not in err, f"{rays} rays per pass: {status} {err!r}")
        passes = [int(l.split()[2]) for l in err.splitlines() if l.startswith("tp2: passes")]
        c.expect(passes and passes[0] > 1, f"{rays} rays per pass: passes {passes}")
        images.append(read_pfm(out)[2])
    c.expect(images[0] == images[1] == images[2], "the images depend on the rays per pass")


def case_slabs_agree(c):
    """A dispatch cut into slabs of workgroup rows, one per lavapipe thread
    (render_bands.c, dispatch_slabs), traces every pixel once: with 1, 2, 3 and
    7 slabs the bytes are the same, at sizes whose rows of workgroups (29,
    5) no slab count above 1 divides, in the band pass, in mixed's retrace
    of a list of pixels (a far checkered quadric) and in walks that go on
    across passes (over the list of saved walks)."""
    setups = (("retrace", os.path.join(HERE, "stress", "quadric-far.txt"),
               ["--precision", "mixed"], {},
               ["101", "227"]),
              ("walks", deep_scene(c), ["--bvh-min", "1000", "--bailout", "0"],
               {"TP2_PASS_RAYS": "7"}, ["21", "35"]))
    for name, scene, options, env, size in setups:
        images = []
        for slabs in ("1", "2", "3", "7"):
            out = os.path.join(c.tmp, f"{name}-{slabs}.pfm")
            status, _, err = run(c.tp2, ["--stats", *options, scene, out, *size],
                                 dict(env, TP2_DISPATCH_SLABS=slabs))
            c.require(status == 0 and "warning" not in err, f"{name}, {slabs}: {status} {err!r}")
            if name == "retrace":
                c.expect((auto_stats(err)[1] or 0) > 0, f"{slabs} slabs: nothing traced again")
            else:
                passes = [int(l.split()[2]) for l in err.splitlines()
                          if l.startswith("tp2: passes")]
                c.expect(passes and passes[0] > 1, f"{slabs} slabs: passes {passes}")
            with open(out, "rb") as f:
                images.append(f.read())
        c.expect(all(i == images[0] for i in images), f"{name}: the slabs change the image")


def case_loop_limit_warning(c):
    """A single ray that needs more than lavapipe allows one invocation (it
    meets 20 polyhedra of 4096 faces: 81920 face tests) cannot be split:
    tp2 writes the image and says how many samples are wrong. Mesa 25's
    lavapipe does not cut these rays: there tp2 says nothing and every ray
    reaches the last polyhedron, the only one it hits (red: a cone ahead of the
    camera; the others, cones around it, open where it looks), which a
    cut ray would not."""
    def faces(d):
        return "".join(f"{math.cos(k):.6f} {math.sin(k):.6f} 0.5 {d}\n" for k in range(4096))
    text = (CAMERA + "1\n0 0 0 1 1 1 0 0 0\n2\nsolid 1 1 1\nsolid 1 0 0\n" + AMBIENT_ONLY +
            "20\n" + "".join("0 0 polyhedron 4096\n" + faces(-1) for _ in range(19)) +
            "1 0 polyhedron 4096\n" + faces(0.5))
    scene = scene_file(c.tmp, "faces.txt", text)
    out = os.path.join(c.tmp, "faces.ppm")
    status, _, err = run(c.tp2, [scene, out, "2", "2"])
    c.expect(status == 0 and os.path.exists(out), f"exit {status}: {err!r}")
    if err:
        c.expect(err.startswith("tp2: warning: 4 pixel samples needed more than") and
                 "so they are wrong" in err, f"no loop-limit warning: {err!r}")
    elif status == 0:
        _, _, rgb = read_ppm(out)
        c.expect(all(rgb[k] > 0 and rgb[k + 1] == 0 for k in range(0, 12, 3)),
                 f"no warning, and not every ray met the last polyhedron: {list(rgb[:12])}")


MILLION_SCENE = """0 2.5 6
0 1 0
0 1 0
40
2
0 0 0  0.2 0.2 0.2  0 0 0
-4 6 4  1 1 1  1 0 0.002
3
checker 0.9 0.9 0.9  0.2 0.2 0.2  1
solid 0.85 0.4 0.2
solid 0.9 0.9 0.9
3
0.3 0.7 0 1 0 0 1
0.2 0.7 0.5 40 0 0 1
0.05 0.1 0.6 100 0.8 0 1
3
0 0 plane 0 1 0 0
1 1 {ball}
2 2 box -3 0 -2.6  3 3 -2.4
"""


def case_million_triangles(c):
    """A mesh of over 1,000,000 triangles (a unit sphere, bench/mesh.py)
    over a floor it shadows, before a mirror that shows it, renders as the
    analytic sphere does: everywhere within a few levels (its facets stray
    from the sphere by 1e-5), shadows and reflection included."""
    obj = os.path.join(c.tmp, "ball.obj")
    mesh.write_sphere(obj, 1000, 502, 1.0, (0, 1, 0))
    images = []
    for name, ball in (("mesh", "mesh ball.obj"), ("sphere", "sphere 0 1 0 1")):
        scene = scene_file(c.tmp, name + ".txt", MILLION_SCENE.format(ball=ball))
        out = os.path.join(c.tmp, name + ".ppm")
        status, _, err = run(c.tp2, ["--stats", scene, out, "160", "120"])
        c.require(status == 0 and "warning" not in err, f"{name}: exit {status}, {err!r}")
        images.append(read_ppm(out)[2])
    diffs = [abs(a - b) for a, b in zip(*images)]
    within1 = sum(d <= 1 for d in diffs) / len(diffs)
    c.expect(within1 >= 0.99 and max(diffs) <= 8,
             f"mesh differs from the sphere: {within1:.4f} within one level, max {max(diffs)}")
    c.expect(len(set(images[0])) > 50, "flat image")


def grid_of_spheres(n_side):
    """n_side^2 small spheres in a grid before the camera, lit, over a plane."""
    spheres = [f"0 0 sphere {x * 0.05 - n_side * 0.025:.3f} {y * 0.05 - n_side * 0.025:.3f} -8 0.02"
               for x in range(n_side) for y in range(n_side)]
    return ("0 0 0\n0 0 -1\n0 1 0\n40\n2\n0 0 0 0.3 0.3 0.3 0 0 0\n3 4 2 1 1 1 1 0 0\n"
            "1\nchecker 1 0.5 0  0 0.25 1  0.3\n1\n0.2 0.7 0.3 20 0.2 0 1\n" +
            f"{len(spheres) + 1}\n" + "\n".join(spheres) + "\n0 0 plane 0 0 1 9\n")


def case_scene_read_in_place(c):
    """On a CPU device the scene's big arrays are read where they lie
    (VK_EXT_external_memory_host) instead of copied: --stats says how much,
    the validation layer accepts it, and the image is the copied scene's,
    byte for byte, under float, mixed (whose double twin is read in place
    too) and auto (on lavapipe the double twin alone)."""
    scene = scene_file(c.tmp, "grid.txt", grid_of_spheres(230))  # 52,900 spheres
    for precision in ("float", "mixed", "auto"):
        images, in_place = [], []
        for importing in ("1", "0"):
            out = os.path.join(c.tmp, f"{precision}-{importing}.ppm")
            status, _, err = run(c.tp2, ["--stats", "--quiet", "--precision", precision, scene,
                                         out, "80", "60"], {"TP2_HOST_IMPORT": importing})
            c.require(status == 0 and "validation" not in err, f"exit {status}: {err!r}")
            found = re.search(r"; ([0-9.]+) MiB of them read in place\)", err)
            in_place.append(float(found.group(1)) if found else 0.0)
            images.append(read_ppm(out)[2])
        c.expect(in_place[0] >= 2 and in_place[1] == 0,
                 f"{precision}: MiB read in place {in_place} (imported, copied)")
        c.expect(images[0] == images[1], f"{precision}: read in place, the image differs")
        c.expect(len(set(images[0])) > 20, f"{precision}: flat image")


def case_bvh_nodes_beside(c):
    """A tree of 2^14 nodes or more is packed on a thread beside the
    objects under --precision float (scene_pack.c): its image is the one
    the plain loop over every object gives (--bvh-min above the count),
    which has no tree at all."""
    scene = scene_file(c.tmp, "grid.txt", grid_of_spheres(180))  # 32,400 spheres
    images = []
    for bvh_min in ("16", "100000"):
        out = os.path.join(c.tmp, f"grid-{bvh_min}.ppm")
        status, _, err = run(c.tp2, ["--quiet", "--precision", "float", "--bvh-min", bvh_min,
                                     scene, out, "64", "48"])
        c.require(status == 0 and "validation" not in err, f"exit {status}: {err!r}")
        images.append(read_ppm(out)[2])
    c.expect(images[0] == images[1], "the tree's image differs from the plain loop's")
    c.expect(len(set(images[0])) > 20, "flat image")


def case_retrace_pipeline_eager(c):
    """Mixed's retrace pipeline made at the start, beside the band pass's
    and the first bands' float passes (on a second thread: the validation
    layer watches both; waited for at the first band that marks a pixel),
    gives the image of the one made when a band first marks a pixel, in
    one band or in five; --stats counts neither in the retrace's time."""
    scene = scene_file(c.tmp, "s.txt", effects_scene())
    images = []
    for when, band_bytes in (("0", None), ("1e30", None), ("0", str(48 * 8 * 16))):
        out = os.path.join(c.tmp, f"o{len(images)}.ppm")
        env = {"TP2_EAGER_RETRACE": when}
        if band_bytes:
            env["TP2_BAND_BYTES"] = band_bytes
        status, _, err = run(c.tp2, ["--stats", "--quiet", "--precision", "mixed", scene, out,
                                     "48", "36"], env)
        c.require(status == 0 and "validation" not in err, f"exit {status}: {err!r}")
        retraced = re.search(r"tp2: retrace +([0-9.]+) s \((\d+) pixels", err)
        c.require(retraced and int(retraced.group(2)) > 0, f"no pixel traced again: {err!r}")
        # The retrace is part of the render, which leaves out pipelines
        # made on the way, the retrace's own (made here when first needed)
        # included.
        render = re.search(r"tp2: render +([0-9.]+) s", err)
        c.expect(render and float(retraced.group(1)) <= float(render.group(1)),
                 f"TP2_EAGER_RETRACE={when}: retrace longer than render: {err!r}")
        images.append(read_ppm(out)[2])
        if band_bytes:
            c.require("5 bands of 8 rows" in err, f"not in 5 bands: {err!r}")
    c.expect(images[0] == images[1] == images[2],
             "the eagerly made retrace pipeline changed the image")


def case_pipelines_before_buffers(c):
    """The pipelines made beside packing, before the scene's buffers (a
    large scene's way, TP2_EARLY_PIPELINES=1 forcing it on a small one;
    --stats says so), the retrace's made eagerly or not, give the image of
    those made after the buffers, with no validation message."""
    scene = scene_file(c.tmp, "s.txt", effects_scene())
    images = []
    for early, eager in (("0", "1e30"), ("1", "1e30"), ("1", "0")):
        out = os.path.join(c.tmp, f"o{len(images)}.ppm")
        env = {"TP2_EARLY_PIPELINES": early, "TP2_EAGER_RETRACE": eager}
        status, _, err = run(c.tp2, ["--stats", "--quiet", "--precision", "mixed", scene, out,
                                     "48", "36"], env)
        c.require(status == 0 and "validation" not in err, f"exit {status}: {err!r}")
        retraced = re.search(r"tp2: retrace +[0-9.]+ s \((\d+) pixels", err)
        c.require(retraced and int(retraced.group(1)) > 0, f"no pixel traced again: {err!r}")
        beside = re.search(r"tp2: pipeline +[0-9.]+ s \(waited for; made in [0-9.]+ s beside",
                           err)
        c.expect(bool(beside) == (early == "1"), f"early {early}: --stats {err!r}")
        images.append(read_ppm(out)[2])
    c.expect(images[0] == images[1] == images[2],
             "pipelines made before the buffers changed the image")


def shifted_spheres(dx, dy):
    """tests/render/many-spheres.txt moved by (dx, dy, 0): the camera, the
    lights and the spheres (the floor z = 0 and its 2-unit checker stay,
    for even shifts)."""
    with open(os.path.join(HERE, "render", "many-spheres.txt")) as f:
        lines = f.read().split("\n")

    def moved(words, at):
        words[at] = repr(float(words[at]) + dx)
        words[at + 1] = repr(float(words[at + 1]) + dy)
        return " ".join(words)

    for i, line in enumerate(lines):
        words = line.split()
        if i in (1, 2) or (6 <= i <= 8):  # eye, center, the lights
            lines[i] = moved(words, 0)
        elif len(words) == 7 and words[2] == "sphere":
            lines[i] = moved(words, 3)
    return "\n".join(lines)


def case_bvh_matches_loop(c):
    """Spheres through the BVH give exactly the image of the plain loop,
    under mixed and in double (whose box tests are float's, widened for the
    ray's rounding to float: shaders/intersect.glsl), and so they do with
    the scene moved 4e4 away from the origin, where that rounding is
    largest."""
    near = os.path.join(HERE, "render", "many-spheres.txt")
    far = scene_file(c.tmp, "far.txt", shifted_spheres(20000.0, 40000.0))
    for scene, precision in ((near, "mixed"), (near, "double"), (far, "double")):
        outs = []
        for name, n in (("bvh", "1"), ("loop", "100000")):
            out = os.path.join(c.tmp, name + ".pfm")
            render(c.tp2, scene, out, (96, 72), ["--bvh-min", n, "--precision", precision])
            outs.append(read_pfm(out)[2])
        c.expect(outs[0] == outs[1], f"{scene} {precision}: BVH and loop images differ")
        lit = sum(1 for row in outs[0] for px in row if px != outs[0][0][0])
        c.expect(lit > 1000, f"{scene} {precision}: only {lit} pixels differ from the corner")


def far_glass_grid():
    """100 small glass spheres seen from 1e6 away under a 0.0003 degree
    field of view: float's rounding there is a share of every pixel, so
    mixed traces every pixel again in double."""
    spheres = [f"0 0 sphere {x * 0.5 - 2.25:.3f} {y * 0.5 - 2.25:.3f} -8 0.2"
               for x in range(10) for y in range(10)]
    return ("0 0 1e6\n0 0 -8\n0 1 0\n0.0003\n3\n0 0 0 0.3 0.3 0.3 0 0 0\n"
            "3 4 2 1 1 1 1 0 0\n-3 2 5 0.5 0.5 0.5 1 0 0\n"
            "1\nchecker 1 0.5 0  0 0.25 1  0.3\n1\n0.2 0.7 0.3 20 0.3 0.5 1.5\n" +
            f"{len(spheres) + 1}\n" + "\n".join(spheres) + "\n0 0 plane 0 0 1 9\n")


def case_retrace_tests_boxes_as_built(c):
    """Mixed's float pass tests the BVH's boxes grown for its edge test
    (TP2_EDGE_REACH of the scene's scale); its retrace in double tests
    them as built, as the double build does. Seen from 1e6 away the growth
    is about 1000 units around spheres of 0.2: grown in the tree itself
    (before), every box held every sphere, the retrace tested each one for
    every ray and lavapipe cut its walks (15 passes where 2 do). Every
    pixel is traced again, and the image is double's with the same
    pruning, byte for byte."""
    scene = scene_file(c.tmp, "far.txt", far_glass_grid())
    out, exact = (os.path.join(c.tmp, name) for name in ("mixed.ppm", "double.ppm"))
    status, _, err = run(c.tp2, ["--stats", "--quiet", "--precision", "mixed", scene, out,
                                 "40", "30"])
    c.require(status == 0 and "validation" not in err, f"exit {status}: {err!r}")
    c.require("(building the BVH over 100 bounded primitives" in err, f"no BVH: {err!r}")
    c.expect("(1200 pixels, 100.00%, again in double" in err, f"not all traced again: {err!r}")
    passes = re.search(r"tp2: passes +(\d+)", err)
    c.expect(passes and int(passes.group(1)) == 2,
             f"float pass and retrace not one pass each: {err!r}")
    render(c.tp2, scene, exact, (40, 30), ["--precision", "double",
                                           "--bailout", "0.00392156862745098"])
    c.expect(read_ppm(out)[2] == read_ppm(exact)[2], "mixed's image is not double's")


def case_grown_boxes_mark_as_loop(c):
    """Mixed's float pass tests the BVH's boxes grown by its edge test's
    reach (intersect.glsl, box_ray), so that a ray passing an edge just
    outside a box is tested, and marked, as in a plain loop: on stress
    scenes with edges along rows of pixel centers, forced through the BVH
    (--bvh-min 1), the same pixels are traced again (--stats' count) and
    the image is the loop's, byte for byte. (Without the growth,
    faces-crossing-on-row marked 2662 pixels where the loop marks 2845.)"""
    for name in ("faces-crossing-on-row", "edges-through-glass", "edges-on-pixel-rows",
                 "triangle-corners-on-floor"):
        scene = os.path.join(HERE, "stress", name + ".txt")
        renders = bvh_and_loop(c, scene, (400, 300), "mixed")
        counts = []
        for how, err, _ in renders:
            retraced = re.search(r"tp2: retrace +[0-9.]+ s \((\d+) pixels", err)
            c.require(retraced is not None, f"{name} {how}: no retrace line: {err!r}")
            counts.append(int(retraced.group(1)))
        c.expect(counts[0] == counts[1] and counts[0] > 0,
                 f"{name}: traced again through the BVH {counts[0]}, in a loop {counts[1]}")
        c.expect(renders[0][2] == renders[1][2],
                 f"{name}: the BVH's image differs from the loop's")


def far_off(a, b):
    """Pixels of a and b (PPM bytes) more than 8 levels apart in some channel."""
    return sum(1 for i in range(0, len(a), 3)
               if max(abs(a[i + k] - b[i + k]) for k in range(3)) > 8)


def mixed_catches(c, name, float_least, lost):
    """On tests/stress/name at 400 x 300, float alone has more than
    float_least pixels off by more than 8 levels from double (else the
    scene has `lost` what makes it hard), and mixed none."""
    scene = os.path.join(HERE, "stress", name)
    images = {}
    for precision in ("mixed", "double", "float"):
        out = os.path.join(c.tmp, precision + ".ppm")
        render(c.tp2, scene, out, (400, 300), ["--quiet", "--precision", precision])
        images[precision] = read_ppm(out)[2]
    off_float = far_off(images["float"], images["double"])
    c.expect(off_float > float_least, f"float alone only {off_float} pixels off: {lost}")
    off_mixed = far_off(images["mixed"], images["double"])
    c.expect(off_mixed == 0, f"mixed: {off_mixed} pixels off by more than 8 levels from double")


def case_corners_on_the_hit_floor(c):
    """Triangles' corners resting on a floor, each on a pixel center's ray
    (tests/stress/triangle-corners-on-floor.txt): double finds the
    triangle a hair nearer than the floor, float may put its corner a
    hair behind. Mixed's edge test counts an edge as far as the hit,
    within the hit distance's doubt (signature.glsl, edges_seen), so no
    pixel of its image is off by more than 8 levels from double's, where
    float alone has hundreds (and mixed had 24 when it counted only
    edges nearer than the hit)."""
    mixed_catches(c, "triangle-corners-on-floor.txt", 100, "the scene lost its corners")


def case_needle_shadows_in_mirror(c):
    """Shadows thinner than float's error, seen in a mirror floor that is a
    sphere of radius 1000 (tests/stress/needle-shadows-mirrored.txt): a
    pixel in such a shadow that float lit has lit neighbours, so only the
    shadow ray's edge test can mark it, with its origin's doubt known to
    be float's error (signature.glsl, shadow_origin_doubt). No pixel of
    mixed's image is then off by more than 8 levels from double's, where
    float alone has more than 10 (and mixed had 2 when a deeper ray's
    shadow ray counted only its origin's fresh rounding)."""
    mixed_catches(c, "needle-shadows-mirrored.txt", 10, "the shadows lost their flips")


def ellipsoid_grid(n_side):
    """n_side^2 tilted ellipsoids written as quadrics (x^2 + 4 y^2 + 2 z^2
    + x z about each center, some glass), over a plane and under an
    unbounded hyperboloid's sheet."""
    rows = []
    for i in range(n_side):
        for j in range(n_side):
            cx, cy, cz = (i - n_side / 2) * 0.8, (j - n_side / 2) * 0.8, -6.0
            q = [1, 4, 2, 0, 1, 0, -2 * cx - cz, -8 * cy, -4 * cz - cx,
                 cx * cx + 4 * cy * cy + 2 * cz * cz + cx * cz - 0.09]
            rows.append(f"0 {(i + j) % 2} quadric " + " ".join(f"{v:.6g}" for v in q))
    rows.append("1 0 plane 0 0 1 8")
    rows.append("1 0 quadric 1 1 -1 0 0 0 0 0 0 -30")  # a hyperboloid of one sheet
    return ("0 0 0\n0 0 -1\n0 1 0\n50\n2\n0 0 0 0.3 0.3 0.3 0 0 0\n3 4 2 1 1 1 1 0 0\n"
            "2\nsolid 0.9 0.5 0.2\nchecker 1 1 1  0.1 0.2 0.6  0.5\n"
            "2\n0.2 0.7 0.3 20 0.2 0 1\n0.05 0.1 0.5 40 0.1 0.8 1.4\n" +
            f"{len(rows)}\n" + "\n".join(rows) + "\n")


def bvh_and_loop(c, scene, size, precision):
    """scene rendered with --stats under `precision` through the BVH
    (--bvh-min 1) and in a plain loop (--bvh-min 100000): a list of
    (name, stderr, pixels) for the two."""
    renders = []
    for name, n in (("bvh", "1"), ("loop", "100000")):
        out = os.path.join(c.tmp, name + ".pfm")
        status, _, err = run(c.tp2, ["--stats", "--quiet", "--bvh-min", n, "--precision",
                                     precision, scene, out, str(size[0]), str(size[1])])
        c.require(status == 0 and "validation" not in err, f"exit {status}: {err!r}")
        renders.append((name, err, read_pfm(out)[2]))
    return renders


def expect_in_bvh(c, scene, bounded, size, min_colors):
    """--stats says the scene's `bounded` primitives go into the BVH and 2
    unbounded ones are tested by every ray, and the image through the BVH
    is the plain loop's (--bvh-min 100000), byte for byte, under mixed and
    in double."""
    for precision in ("mixed", "double"):
        renders = bvh_and_loop(c, scene, size, precision)
        for name, err, _ in renders:
            said = (f"building the BVH over {bounded} bounded primitives" if name == "bvh" else
                    f"no BVH: {bounded} bounded primitives, in a plain loop")
            c.expect(f"({said}; 2 unbounded, tested by every ray)" in err,
                     f"{precision} {name}: {err!r}")
        c.expect(renders[0][2] == renders[1][2], f"{precision}: BVH and loop images differ")
        colors = {px for row in renders[0][2] for px in row}
        c.expect(len(colors) > min_colors, f"{precision}: only {len(colors)} colors")


def case_ellipsoids_in_bvh(c):
    """An ellipsoid written as a quadric has a box (host/scene/shapes.c,
    quadric_bounds), so a grid of them goes into the BVH while a
    hyperboloid and a plane stay unbounded; the image is the loop's."""
    expect_in_bvh(c, scene_file(c.tmp, "ellipsoids.txt", ellipsoid_grid(6)), 36, (96, 72), 500)


def case_triangle_edges_in_bvh(c):
    """The triangles' edge test marks the same pixels through the BVH
    (whose boxes grow under mixed) as in a plain loop: the triangles of
    tests/stress/triangle-edges-on-pixel-rows, edges along rows of pixel
    centers (so at 400 x 300), one light in the plane of a triangle seen
    edge-on (a shadow ray in its plane meets nothing, in the loop too).
    (Exact ties between triangles are tests/stress/shared-edge-ties'.)"""
    scene = os.path.join(HERE, "stress", "triangle-edges-on-pixel-rows.txt")
    expect_in_bvh(c, scene, 32, (400, 300), 1000)


def geodesic_grid(n_side, faces):
    """n_side^2 polyhedra of `faces` faces each (the tangent planes of a
    sphere of radius 0.3 at spread directions: nearly round), some glass,
    over a plane and a floor written as a one-face polyhedron."""
    golden = math.pi * (3 - math.sqrt(5))
    rows = []
    for i in range(n_side):
        for j in range(n_side):
            cx, cy, cz = (i - n_side / 2) * 0.8, (j - n_side / 2) * 0.8, -6.0
            planes = []
            for k in range(faces):
                z = 1 - (2 * k + 1) / faces
                ring = math.sqrt(1 - z * z)
                u = (ring * math.cos(golden * k), ring * math.sin(golden * k), z)
                d = -(u[0] * cx + u[1] * cy + u[2] * cz + 0.3)
                planes.append(" ".join(f"{v:.9g}" for v in (*u, d)))
            rows.append(f"0 {(i + j) % 2} polyhedron {faces}\n" + "\n".join(planes))
    rows.append("1 0 plane 0 0 1 8")
    rows.append("1 0 polyhedron 1\n-1 0 0 3")  # a wall, x >= 3: a half-space
    return ("0 0 0\n0 0 -1\n0 1 0\n50\n2\n0 0 0 0.3 0.3 0.3 0 0 0\n3 4 2 1 1 1 1 0 0\n"
            "2\nsolid 0.9 0.5 0.2\nchecker 1 1 1  0.1 0.2 0.6  0.5\n"
            "2\n0.2 0.7 0.3 20 0.2 0 1\n0.05 0.1 0.5 40 0.1 0.8 1.4\n" +
            f"{len(rows)}\n" + "\n".join(rows) + "\n")


def case_many_faced_polyhedra_in_bvh(c):
    """A bounded polyhedron of any face count has a box (host/scene/convex.c's
    linear programs), so 16 polyhedra of 160 faces (past the 128 of the
    method before) go into the BVH while a half-space and a plane stay
    unbounded; the image is the loop's."""
    scene = scene_file(c.tmp, "geodesics.txt", geodesic_grid(4, 160))
    expect_in_bvh(c, scene, 16, (64, 48), 300)


def case_one_kind_loop(c):
    """Without a BVH, bounded and unbounded objects all of one kind are
    tested in one loop (shaders/intersect.glsl, trace_plain; spheres and a
    plane are case_bvh_matches_loop's two loops): 16 closed polyhedra and
    a half-space written as a one-face polyhedron give the BVH walk's image
    byte for byte, under mixed and in double."""
    rows = geodesic_grid(4, 12).splitlines()
    rows = [r for r in rows if "plane" not in r]
    rows[rows.index("18")] = "17"  # the object count, the plane left out
    scene = scene_file(c.tmp, "polyhedra.txt", "\n".join(rows) + "\n")
    for precision in ("mixed", "double"):
        renders = bvh_and_loop(c, scene, (64, 48), precision)
        c.expect("(no BVH: 16 bounded primitives, in a plain loop; 1 unbounded" in renders[1][1],
                 f"{precision}: {renders[1][1]!r}")
        c.expect(renders[0][2] == renders[1][2], f"{precision}: BVH and loop images differ")
        colors = {px for row in renders[0][2] for px in row}
        c.expect(len(colors) > 100, f"{precision}: only {len(colors)} colors")


def case_pipeline_cache(c):
    """The cache is written, reused, and survives corrupt or foreign files."""
    env = {"XDG_CACHE_HOME": os.path.join(c.tmp, "cache")}
    first = c.image(effects_scene(), (16, 12), name="first", env=env)
    files = glob.glob(os.path.join(c.tmp, "cache", "tp2", "pipelines-*.bin"))
    c.expect(len(files) == 1, f"cache files: {files}")
    c.expect(c.image(effects_scene(), (16, 12), name="warm", env=env) == first, "warm run differs")
    for junk in (os.urandom(3000), b"", files[0:1] and open(files[0], "rb").read()[:20],
                 b"\x20\0\0\0\x01\0\0\0" + os.urandom(100)):
        with open(files[0], "wb") as f:
            f.write(junk)
        again = c.image(effects_scene(), (16, 12), name="again", env=env)
        c.expect(again == first, f"a corrupt cache ({len(junk)} bytes) changed the image")
    # (Mesa's own shader cache would complain about the bogus folder.)
    nowhere = {"XDG_CACHE_HOME": "/proc/no/such/folder", "HOME": "/proc/no/such/home",
               "MESA_SHADER_CACHE_DIR": os.path.join(c.tmp, "mesa")}
    c.expect(c.image(effects_scene(), (16, 12), name="nocache", env=nowhere) == first,
             "an unwritable cache folder changed the image")


def cache_file(c, env):
    """Renders once with env's cache folder; returns (image, the cache file's path)."""
    first = c.image(effects_scene(), (16, 12), name="first", env=env)
    files = glob.glob(os.path.join(env["XDG_CACHE_HOME"], "tp2", "pipelines-*.bin"))
    c.require(len(files) == 1, f"cache files: {files}")
    return first, files[0]


def cache_leftovers(folder):
    return [n for n in os.listdir(folder) if not n.startswith("pipelines-")]


def case_cache_planted_link(c):
    """Links planted at the cache file's path and at the temporary name tp2
    once used (PATH.PID, planted by the child itself before exec, so the
    PID is right) are replaced or ignored, never followed: the file they
    point to stays as it was."""
    import subprocess
    env = {"XDG_CACHE_HOME": os.path.join(c.tmp, "cache")}
    first, path = cache_file(c, env)
    victim = os.path.join(c.tmp, "victim")
    with open(victim, "wb") as f:
        f.write(b"victim")
    os.unlink(path)
    os.symlink(victim, path)
    scene = scene_file(c.tmp, "s.txt", effects_scene())
    out = os.path.join(c.tmp, "again.pfm")
    r = subprocess.run([c.tp2, scene, out, "16", "12"], capture_output=True, timeout=600,
                       env=dict(os.environ, **env),
                       preexec_fn=lambda: os.symlink(victim, f"{path}.{os.getpid()}"))
    c.require(r.returncode == 0 and r.stderr == b"", f"exit {r.returncode}, {r.stderr!r}")
    c.expect(read_pfm(out)[2] == first, "image")
    with open(victim, "rb") as f:
        c.expect(f.read() == b"victim", "a link's target was written")
    c.expect(not os.path.islink(path) and os.path.isfile(path), "the link is still there")
    for name in cache_leftovers(os.path.dirname(path)):
        c.expect(os.path.islink(os.path.join(os.path.dirname(path), name)) and
                 name.startswith(os.path.basename(path) + "."), f"left {name}")


def case_cache_folder_not_ours(c):
    """A cache folder that is a link, or that everyone may write to, is not
    used: nothing is read or written there."""
    elsewhere = os.path.join(c.tmp, "elsewhere")
    os.mkdir(elsewhere)
    env = {"XDG_CACHE_HOME": os.path.join(c.tmp, "cache")}
    first, path = cache_file(c, env)
    name = os.path.basename(path)
    with open(os.path.join(elsewhere, name), "wb") as f:
        f.write(b"victim")
    linked = os.path.join(c.tmp, "linked")
    os.mkdir(linked)
    os.symlink(elsewhere, os.path.join(linked, "tp2"))
    image = c.image(effects_scene(), (16, 12), name="linked", env={"XDG_CACHE_HOME": linked})
    c.expect(image == first, "image through a linked folder")
    with open(os.path.join(elsewhere, name), "rb") as f:
        c.expect(f.read() == b"victim", "a file in the linked folder was written")
    c.expect(os.listdir(elsewhere) == [name], f"linked folder holds {os.listdir(elsewhere)}")
    os.unlink(path)
    os.chmod(os.path.dirname(path), 0o777)
    c.expect(c.image(effects_scene(), (16, 12), name="open", env=env) == first, "image")
    c.expect(os.listdir(os.path.dirname(path)) == [], "a world-writable folder was used")


def case_cache_fifo(c):
    """A FIFO at the cache file's path is skipped without blocking (run's
    time limit only catches a hang), and the cache is saved over it."""
    env = {"XDG_CACHE_HOME": os.path.join(c.tmp, "cache")}
    first, path = cache_file(c, env)
    os.unlink(path)
    os.mkfifo(path)
    scene = scene_file(c.tmp, "s.txt", effects_scene())
    out = os.path.join(c.tmp, "fifo.pfm")
    status, _, err = run(c.tp2, [scene, out, "16", "12"], env, timeout=120)
    c.require(status == 0 and err == "", f"exit {status}, {err!r}")
    c.expect(read_pfm(out)[2] == first, "image")
    c.expect(os.path.isfile(path), "no cache file saved over the FIFO")
    c.expect(cache_leftovers(os.path.dirname(path)) == [], f"left {os.listdir(os.path.dirname(path))}")


def case_cache_directory(c):
    """A directory at the cache file's path is neither read nor replaced,
    and no temporary file is left beside it."""
    env = {"XDG_CACHE_HOME": os.path.join(c.tmp, "cache")}
    first, path = cache_file(c, env)
    os.unlink(path)
    os.mkdir(path)
    c.expect(c.image(effects_scene(), (16, 12), name="again", env=env) == first, "image")
    c.expect(os.path.isdir(path) and os.listdir(path) == [], "the directory changed")
    c.expect(cache_leftovers(os.path.dirname(path)) == [], f"left {os.listdir(os.path.dirname(path))}")


def case_bands_agree(c):
    """Bands of 8 rows (TP2_BAND_BYTES=1: 27 bands) give the very bytes of
    the default bands (two of 200 rows here), in every format, with several
    samples per pixel: rows land where they belong and every band gets all
    its samples."""
    scene = scene_file(c.tmp, "s.txt", effects_scene())
    for ext in ("pfm", "png", "ppm"):
        outs = []
        for name, env in (("one", {}), ("many", {"TP2_BAND_BYTES": "1"})):
            out = os.path.join(c.tmp, f"{name}.{ext}")
            status, _, err = run(c.tp2, ["--stats", "--spp", "3", scene, out, "333", "211"], env)
            c.require(status == 0, f"{name}.{ext}: exit {status}: {err}")
            if name == "many":
                c.expect("27 bands of 8 rows" in err, f"many.{ext}: {err!r}")
            with open(out, "rb") as f:
                outs.append(f.read())
        c.expect(outs[0] == outs[1], f".{ext}: 27 bands and 1 band differ")


def case_device_quantize(c):
    """PPM and PNG rows are quantized to 8 bits on the device (finish.comp,
    float arithmetic only); every value equals the host's quantization of
    the same render's floats (PFM), floor(255 c + 0.5) clamped to [0, 255]
    in double, on a render of every sampled feature (8 samples: most
    values land between levels) with a light bright enough to pass 1.
    This catches packing, channel order and rounding mistakes; exactness
    at the rounding boundaries, too rare to meet here, is unit_quantize's."""
    scene = scene_file(c.tmp, "s.txt", effects_scene().replace("0.8 0.8 0.8", "2.5 2.5 2.5"))
    outs = {}
    for ext in ("pfm", "ppm"):
        outs[ext] = os.path.join(c.tmp, "q." + ext)
        status, _, err = run(c.tp2, [scene, outs[ext], "160", "120"])
        c.require(status == 0, f".{ext}: exit {status}: {err}")
    _, _, rows = read_pfm(outs["pfm"])
    want = bytes(0 if not v > 0 else 255 if v >= 1 else math.floor(v * 255 + 0.5)
                 for row in rows for p in row for v in p)
    got = read_ppm(outs["ppm"])[2]
    c.require(len(got) == len(want), f"{len(got)} bytes, want {len(want)}")
    wrong = sum(a != b for a, b in zip(got, want))
    c.expect(wrong == 0, f"{wrong} of {len(want)} values quantized otherwise than the host")
    levels = len(set(want))
    c.expect(levels > 200 and 255 in want and 0 < sum(v >= 1 for row in rows for p in row
                                                       for v in p),
             f"too few values to show anything: {levels} levels")


def auto_stats(err):
    """(precision line, pixels traced again or None) from tp2 --stats."""
    precision = re.search(r"tp2: precision  (.*)", err)
    again = re.search(r"tp2: retrace +[0-9.]+ s \((\d+) pixels", err)
    return precision[1] if precision else None, int(again[1]) if again else None


BAILOUT = repr(1 / 255)  # the default, spelled out for --precision double


def translated_scene(dx, dy, dz):
    """A scene with a mirror, glass and a shadow of every bounded kind but
    the quadric (whose center is solved for, not moved), a gradient and a
    texture (tex.ppm, repeating every 4 units) on the floor, moved by dx
    dy dz. Every number is a short binary fraction, so the move is exact."""
    def p(x, y, z):
        return f"{x + dx!r} {y + dy!r} {z + dz!r}"
    return (f"{p(0.5, 3, 9)}\n{p(0, 0.5, 0)}\n0 1 0\n40\n"
            f"3\n0 0 0 0.2 0.2 0.2 0 0 0\n{p(4, 8, 6)} 0.8 0.7 0.6 1 0 0\n"
            f"{p(-5, 6, 2)} 0.5 0.6 0.8 1 0 0\n"
            f"4\nsolid 0.9 0.4 0.3\ngradient {p(-4, 0, 0)} {p(4, 0, 0)} 0.3 0.8 0.9 0.9 0.2 0.6\n"
            "solid 0.9 0.9 0.8\ntexmap tex.ppm 0.25 0 0 0.5 0 0 0.25 0\n"
            "3\n0.1 0.7 0.4 50 0 0 1\n0.05 0.2 0.5 100 0.75 0 1\n"
            "0.02 0.1 0.5 100 0.1 0.85 1.5\n"
            "9\n"
            f"0 0 box {p(1.5, 1.25, -1)} {p(2.5, 2.25, 0)}\n"
            f"1 1 sphere {p(-1.5, 1, -0.5)} 1\n"
            f"1 2 sphere {p(0.25, 0.75, 2)} 0.75\n"
            f"0 0 cylinder {p(-3, 0, -2)} {p(-2.5, 2, -2.5)} 0.5\n"
            f"1 0 cone {p(3, 0, 1.5)} 0.75 {p(3, 1.5, 1.5)} 0\n"
            f"0 1 torus {p(-0.5, 0.5, -3)} 0 1 0.5 1 0.25\n"
            f"1 0 triangle {p(-4, 0, 0)} {p(-3, 0, 1)} {p(-3.5, 2, 0.5)}\n"
            f"0 0 polyhedron 3\n1 0 0 {-(4.5 + dx)!r}\n0 0 1 {-(-4 + dz)!r}\n"
            f"0 -1 0 {dy!r}\n"
            f"3 0 plane 0 1 0 {-dy!r}\n")


def case_translation_invariant(c):
    """A scene moved 4e3-8e3 away from the origin, the camera with it,
    renders the same bytes as at the origin, under float, mixed, auto and
    double:
    positions reach the GPU from the eye's float (scene_pack.c), so float
    rounds them as it would near the origin."""
    near, far = translated_scene(0, 0, 0), translated_scene(4096, -8192, 2048)
    with open(os.path.join(c.tmp, "tex.ppm"), "w") as f:
        f.write("P3 4 4 255\n" + " ".join(f"{(37 * i) % 256} {(91 * i) % 256} {(13 * i) % 256}"
                                           for i in range(16)) + "\n")
    for options in (["--precision", "float"], ["--precision", "mixed"], [],
                    ["--precision", "double"]):
        a = c.image(near, (96, 72), options, name="near")
        b = c.image(far, (96, 72), options, name="far")
        c.expect(a == b, f"{options or 'auto'}: moved scene renders differently")
        c.expect(len({px for row in a for px in row}) > 50, f"{options}: a flat image")


def case_mixed_is_float_or_double(c):
    """--precision mixed: every pixel is the float image's or, where it was
    traced again, the double image's (same pruning), bit for bit; some are
    the double one's where float's differ (a far checkered sphere, where
    float flips cells), and no more differ from float than --stats says
    were traced again. With bands of 8 rows the image is the same."""
    scene = os.path.join(HERE, "stress", "quadric-far.txt")
    size = ("160", "120")
    images = {}
    for name, options, env in (("float", ["--precision", "float"], {}),
                               ("double", ["--precision", "double", "--bailout", BAILOUT], {}),
                               ("mixed", ["--precision", "mixed"], {}),
                               ("bands", ["--precision", "mixed"], {"TP2_BAND_BYTES": "1"})):
        out = os.path.join(c.tmp, name + ".pfm")
        status, _, err = run(c.tp2, ["--stats", "--quiet", *options, scene, out, *size], env)
        c.require(status == 0, f"{name}: exit {status}: {err}")
        images[name] = read_pfm(out)[2]
        if name == "mixed":
            precision, again = auto_stats(err)
            c.expect(precision and precision.startswith("mixed (") and again is not None,
                     f"mixed --stats: {err!r}")
    same_float = same_double = other = 0
    for rf, rd, ra in zip(images["float"], images["double"], images["mixed"]):
        for f, d, a in zip(rf, rd, ra):
            if a == f:
                same_float += 1
            elif a == d:
                same_double += 1
            else:
                other += 1
    c.expect(other == 0, f"{other} pixels neither float's nor double's")
    c.expect(same_double > 0, "no pixel took the double image's value")
    c.expect(again is not None and same_double <= again,
             f"{same_double} pixels from double, {again} traced again")
    c.expect(images["bands"] == images["mixed"], "8-row bands and one band differ")


def case_auto_double_on_cpu(c):
    """On a CPU device (lavapipe) --precision auto renders the whole image
    in double from the double twin, with the default's pruning: the very
    bytes of --precision double --bailout 1/255 (the device is chosen
    first, then the double scene alone packed: render.c, auto_on_device), on
    scenes with a BVH and without, with no retrace and --stats saying
    why; mixed differs from it (float's pixels where no decision was in
    doubt)."""
    grid = scene_file(c.tmp, "ellipsoids.txt", ellipsoid_grid(6))
    for scene in (os.path.join(HERE, "stress", "quadric-far.txt"), grid,
                  os.path.join(HERE, "..", "scenes", "mesh.txt")):
        images = {}
        for name, options in (("auto", []), ("mixed", ["--precision", "mixed"]),
                              ("double", ["--precision", "double", "--bailout", BAILOUT])):
            out = os.path.join(c.tmp, name + ".pfm")
            status, _, err = run(c.tp2, ["--stats", "--quiet", *options, scene, out, "96", "72"])
            c.require(status == 0 and "validation" not in err, f"{name}: exit {status}: {err!r}")
            with open(out, "rb") as f:
                images[name] = f.read()
            if name == "auto":
                precision, again = auto_stats(err)
                c.expect(precision == "double (auto: a CPU device, where double costs no more "
                         "than mixed)" and again is None, f"auto --stats: {err!r}")
            # Only auto waits for the choice of device before packing.
            c.expect(("upload once the device was chosen" in err) == (name == "auto"),
                     f"{name} --stats device line: {err!r}")
        base = os.path.basename(scene)
        c.expect(images["auto"] == images["double"], f"{base}: auto is not double's bytes")
        c.expect(images["mixed"] != images["double"], f"{base}: mixed is double's bytes too")


def expect_validation_above(c, err, layer):
    """That err, from a run under layer_env(layer) with
    VK_LOADER_DEBUG=layer, shows the validation layer above the device layer
    for the instance and the device (the loader's own account of the
    stack): validation sees tp2's calls, not the layer's."""
    for call in ("vkCreateInstance", "vkCreateDevice"):
        stack = err.split(f"{call} layer callstack setup to:", 1)
        if not c.expect(len(stack) == 2, f"{layer}: no {call} layer stack in {err[-2000:]!r}"):
            continue
        top_down = stack[1].split("<Drivers>")[0].split("<Device>")[0]
        names = re.findall(r"\b(VK_LAYER_\w+)\s*$", top_down, re.M)
        ours = f"VK_LAYER_TP2_{layer}"
        c.expect("VK_LAYER_KHRONOS_validation" in names and ours in names and
                 names.index("VK_LAYER_KHRONOS_validation") < names.index(ours),
                 f"{layer} {call}: layers top to bottom {names}")


def expect_auto_is_float(c, env, why):
    """Under env, auto and mixed render float alone (the very bytes of
    --precision float) and --stats says why. Returns the scene and auto's
    stderr."""
    scene = scene_file(c.tmp, "s.txt", effects_scene())
    outs, errs = {}, {}
    for name, options in (("auto", []), ("mixed", ["--precision", "mixed"]),
                          ("float", ["--precision", "float"])):
        outs[name] = os.path.join(c.tmp, name + ".pfm")
        status, _, err = run(c.tp2, ["--stats", *options, scene, outs[name], "40", "30"], env)
        c.require(status == 0, f"{name}: exit {status}: {err}")
        errs[name] = err
        if name != "float":
            precision, again = auto_stats(err)
            c.expect(precision == f"float ({name}: {why})" and again is None,
                     f"{name} --stats: {err!r}")
    for name in ("auto", "mixed"):
        with open(outs[name], "rb") as a, open(outs["float"], "rb") as f:
            c.expect(a.read() == f.read(), f"{name} ({why}) differs from float")
    return scene, errs["auto"]


def case_auto_without_float64(c):
    """On a device without shaderFloat64 (VK_LAYER_TP2_no_fp64 hides it from
    lavapipe, and refuses a device or a shader module that would use it)
    auto and mixed retrace in software double (shaders/soft_double.glsl),
    --stats says so and how many pixels it took, and the image is the very
    bytes of mixed's where the device has double; --precision double is
    refused, exit 1, nothing written. The validation layer is above the
    device layer (checked from the loader's account, VK_LOADER_DEBUG)."""
    env = layer_env("no_fp64")
    scene = scene_file(c.tmp, "s.txt", effects_scene())
    native = os.path.join(c.tmp, "native.pfm")
    status, _, err = run(c.tp2, ["--stats", "--precision", "mixed", scene, native, "40", "30"])
    c.require(status == 0, f"mixed with double: exit {status}: {err}")
    native_again = auto_stats(err)[1]
    auto_err = ""
    for name, options, extra in (("auto", [], {"VK_LOADER_DEBUG": "layer"}),
                                 ("mixed", ["--precision", "mixed"], {})):
        out = os.path.join(c.tmp, name + ".pfm")
        status, _, err = run(c.tp2, ["--stats", *options, scene, out, "40", "30"],
                             {**env, **extra})
        c.require(status == 0, f"{name}: exit {status}: {err}")
        auto_err = err if name == "auto" else auto_err
        precision, again = auto_stats(err)
        c.expect(precision == f"{name} (float, then pixels on decision boundaries again in "
                              "software double)" and "again in software double" in err and
                 again == native_again and again > 0, f"{name} --stats: {err[-1500:]!r}")
        with open(out, "rb") as a, open(native, "rb") as b:
            c.expect(a.read() == b.read(), f"{name} without double differs from mixed with it")
    expect_validation_above(c, auto_err, "no_fp64")
    out = os.path.join(c.tmp, "d.pfm")
    status, _, err = run(c.tp2, ["--precision", "double", scene, out, "40", "30"], env)
    c.expect(status == 1 and "has no shaderFloat64" in err and not os.path.exists(out),
             f"--precision double: exit {status}, {err!r}")


def case_auto_double_too_large(c):
    """Where the double scene would not fit the device (objects take twice
    the texels in double: TP2_TEXEL_ELEMENTS between the two) auto and
    mixed render float alone, and --stats says so, whether its pipelines were made
    before the scene was packed or after."""
    status, out, err = run(c.tp2, ["--dump-scene", scene_file(c.tmp, "e.txt", effects_scene())])
    c.require(status == 0, f"--dump-scene: exit {status}: {err}")
    n = {k: len(json.loads(out)[k]) for k in ("lights", "pigments", "finishes", "objects")}
    # The float scene's texels (tp2_shared.h: TP2_*_TEXELS_F) all fit;
    # its objects in double (TP2_OBJECT_TEXELS_D, 8 each) do not.
    limit = max(3 * n["lights"], 5 * n["pigments"], 2 * n["finishes"], 4 * n["objects"])
    c.require(8 * n["objects"] > limit, f"the scene's double objects fit {limit} texels")
    # Pipelines made before the scene is packed (a large scene's, forced
    # here) are planned as if the double scene fits, then made again.
    for early in ("0", "1"):
        env = {"TP2_TEXEL_ELEMENTS": str(limit), "TP2_EARLY_PIPELINES": early}
        expect_auto_is_float(c, env, "the double scene does not fit the device")


def ppm_differences(a, b):
    """(share of channel values within one level, pixels off by more than
    8 in some channel) between two P6 images of one size."""
    (w, h, x), (w2, h2, y) = read_ppm(a), read_ppm(b)
    assert (w, h) == (w2, h2), f"{a} is {w}x{h}, {b} {w2}x{h2}"
    within1 = sum(abs(p - q) <= 1 for p, q in zip(x, y)) / len(x)
    return within1, far_off(x, y)


def case_mixed_same_when_fused(c):
    """The same image on a device that rounds otherwise (issue 9 item 3):
    VK_LAYER_TP2_fused makes the shaders round as a GPU compiler that fuses
    multiply-adds and dot products would (tests/layers/spirv_fused.h). On scenes
    built to make float fail, that flips float's decisions (pixels off by
    more than 8 levels between the two devices), while mixed's two images
    stay within one level of each other almost everywhere, with none off
    by more than 8, and both meet the accuracy bar (docs/accuracy.md) against the exact
    image (within one level for >= 99.95% of values, no pixel off by more
    than 8). quadric-far at this size has two pixels on the curve where
    its quadrics cross, 1e-7 of their distance apart, which float cannot
    order: the default's check of which crossing is nearer
    (signature.glsl) must catch them. The validation layer is above the
    fused layer (checked from the loader's account, VK_LOADER_DEBUG)."""
    size = ("200", "150")
    float_flips = 0
    for name in ("glass-far-checker", "tir-chain", "refraction", "quadric-far"):
        folder = "scenes" if name == "refraction" else os.path.join("tests", "stress")
        scene = os.path.join(HERE, "..", folder, name + ".txt")
        out = {}
        for label, options, env in (
                ("exact", ["--precision", "double", "--bailout", "0"], {}),
                ("float", ["--precision", "float"], {}),
                ("float fused", ["--precision", "float"],
                 {**layer_env("fused"), "VK_LOADER_DEBUG": "layer"}),
                ("mixed", ["--precision", "mixed"], {}),
                ("mixed fused", ["--precision", "mixed"], layer_env("fused"))):
            out[label] = os.path.join(c.tmp, f"{name}-{label.replace(' ', '-')}.ppm")
            status, _, err = run(c.tp2, ["--quiet", *options, scene, out[label], *size], env)
            c.require(status == 0, f"{name} {label}: exit {status}: {err}")
            fused = [int(n) for n in re.findall(
                r"VK_LAYER_TP2_fused: (\d+) operations fused in a module", err)]
            c.expect((len(fused) > 0) == ("fused" in label) and max(fused, default=1) > 0,
                     f"{name} {label}: {err[-2000:]!r}")
            if label == "float fused":
                expect_validation_above(c, err, "fused")
        float_flips += ppm_differences(out["float"], out["float fused"])[1]
        within1, bad8 = ppm_differences(out["mixed"], out["mixed fused"])
        c.expect(within1 >= 0.9995 and bad8 == 0,
                 f"{name}: mixed against mixed fused: within1 {within1:.6f}, {bad8} off by > 8")
        for label in ("mixed", "mixed fused"):
            within1, bad8 = ppm_differences(out[label], out["exact"])
            c.expect(within1 >= 0.9995 and bad8 == 0,
                     f"{name}: {label} against exact: within1 {within1:.6f}, {bad8} off by > 8")
    c.expect(float_flips > 0, "fusing changed no float decision: the check would prove nothing")


def case_specialized_same_image(c):
    """Each pipeline's shader has the code its specialization constants
    rule out taken away before lavapipe sees it (host/gpu/spirv_specialize.h):
    the image is the same bytes as from the whole module
    (TP2_SPECIALIZE=0), under mixed (float pass and double retrace), auto
    (on lavapipe double, from the double twin), float and double, on every tier of kinds (spheres and planes; meshes; the
    curved kinds), with pigments, textures, fog, lens, arealights and
    samples, and with walks that go on across passes (one ray a pass);
    the validation layer sees every specialized module."""
    def path(name):
        return os.path.join(HERE, "..", "scenes", name + ".txt")
    effects = scene_file(c.tmp, "effects.txt", effects_scene())
    tir = os.path.join(HERE, "stress", "tir-chain.txt")
    one_ray = {"TP2_PASS_RAYS": "1"}
    runs = [(path("demo"), "mixed", {}), (path("demo"), "float", {}),
            (path("demo"), "auto", {}),
            (path("mesh"), "mixed", {}), (path("mesh"), "double", {}),
            (path("torus"), "mixed", {}), (path("torus"), "mixed", one_ray),
            (path("texmap"), "float", {}), (path("checker"), "mixed", {}),
            (effects, "mixed", {}), (effects, "double", one_ray), (tir, "mixed", {})]
    retraced = 0
    for scene, precision, env in runs:
        images = []
        for specialize in ("1", "0"):
            out = os.path.join(c.tmp, f"s{specialize}.ppm")
            status, _, err = run(c.tp2, ["--stats", "--quiet", "--precision", precision,
                                         scene, out, "40", "30"],
                                 dict(env, TP2_SPECIALIZE=specialize))
            c.require(status == 0 and "validation" not in err,
                      f"{scene} {precision} {env}: exit {status}: {err!r}")
            found = re.search(r"tp2: retrace +[0-9.]+ s \((\d+) pixels", err)
            retraced += int(found.group(1)) if found else 0
            images.append(read_ppm(out)[2])
        c.expect(images[0] == images[1],
                 f"{os.path.basename(scene)} {precision} {env}: specializing changed the image")
    c.require(retraced > 0, "no pixel traced again: the double retrace went untested")


def case_stats(c):
    """--stats names every phase and counts W x H x spp camera rays under
    --precision float and under auto (on lavapipe, double); under mixed
    also the row after each band but the
    last (traced for its signatures) and the pixels traced again, which it
    reports, less the samples the float pass skips: after a pixel's first
    sample, one with an UNSURE decision is left to the double pass
    (signature.glsl, STOPPED)."""
    scene = scene_file(c.tmp, "s.txt", effects_scene())
    for precision in ("float", "auto", "mixed"):
        status, _, err = run(c.tp2, ["--stats", "--spp", "3", "--precision", precision, scene,
                                     os.path.join(c.tmp, "o.ppm"), "10", "20"],
                             dict(os.environ, TP2_BAND_BYTES="1"))
        c.expect(status == 0, f"exit {status}: {err}")
        for phase in ("parse", "device", "bvh", "upload", "pipeline", "render", "readback",
                      "write"):
            c.expect(f"tp2: {phase} " in err, f"no {phase} line in {err!r}")
        counts = {}
        for line in err.splitlines():
            words = line.split()
            if len(words) >= 4 and words[1] == "rays":
                counts[words[2]] = int(words[3])
        retraced = re.search(r"tp2: retrace +[0-9.]+ s \((\d+) pixels", err)
        bands = re.search(r"tp2: render .*\((\d+) bands? of 8 rows", err)
        c.expect(bands and int(bands.group(1)) == 3, f"20 rows in 8-row bands: {err!r}")
        c.expect((retraced is not None) == (precision == "mixed"), f"retrace line: {err!r}")
        again = int(retraced.group(1)) if retraced else 0
        after = 2 * 10 if precision == "mixed" else 0
        most = (10 * 20 + after + again) * 3
        if precision != "mixed":
            c.expect(counts.get("camera") == most,
                     f"{precision}: camera rays {counts.get('camera')}")
        else:  # this scene has UNSURE pixels: some samples are skipped
            least = (10 * 20 + after) + again * 3
            c.expect(least <= counts.get("camera", 0) < most,
                     f"mixed: camera rays {counts.get('camera')}, {again} traced again")
        c.expect(counts.get("shadow", 0) > 0 and counts.get("reflected", 0) > 0, f"{counts}")
        c.expect(counts.get("total") == sum(v for k, v in counts.items() if k != "total"),
                 f"{counts}")


if __name__ == "__main__":
    sys.exit(tp2test.run_cases(globals(), Case))
