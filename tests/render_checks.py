#!/usr/bin/env python3
"""render_checks.py TP2 CASE: rendered pixels against SPEC 4's image model.

`render_checks.py --list` prints the case names. Each case renders a scene of
tests/render/ and compares tp2's pixels with values worked out here in double
precision from the scene file's own numbers (camera rays, ray-sphere and
ray-plane hits, the Phong sum, shadows, reflection, refraction), never from
tp2's output.

Tolerances. PFM values: within 1e-4 relative (plus 1e-5 absolute for values
near zero), because tp2 does its geometry and lighting in float (2^-24
relative per operation, a few hundred operations per pixel), which moves hit
points, normals and powers by about 1e-6 relative. PPM bytes: exact, except
where 255 c lies within 1e-3 of a rounding boundary (there float error may
round either way). Pixels whose value the model makes jump within a hair of
the pixel's ray (silhouettes, shadow and checker borders) are skipped: float
error may put them on either side."""
import math
import os
import re
import struct
import sys
import zlib
from collections import namedtuple

import tp2test
from reference import (BACKGROUND, MAX_DEPTH, Plane, Sphere, add, attenuation, camera, dot,
                       hadamard, hit, mul, nearest, norm, normal_at, nudge, pixel_ray, pixels,
                       reflect, sub, the, trace, unit, without)
import reference as model
from tp2test import read_pfm, read_ppm, render

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "render")

REL_TOL = 1e-4        # PFM, relative (float geometry, see above)
ABS_TOL = 1e-5        # PFM, absolute floor for values near zero
PPM_MARGIN = 1e-3     # skip a byte whose 255 c is this close to x.5
EDGE = 1e-3           # world units: skip rays this close to a silhouette
JITTER = 5e-5         # image-plane offset probing for a discontinuity
JUMP = 0.02           # a change this big under JITTER is an edge
GRAY_BYTES = (128, 128, 128)  # round(255 * 0.5) = round(127.5), halves up

# ---------------------------------------------------------------- the model
# SPEC 4's model itself is in reference.py.


def sphere_gap(o, d, s):
    """Distance from the ray's line to sphere s's surface: < 0 through it."""
    oc = sub(s.center, o)
    return norm(sub(oc, mul(d, dot(oc, d)))) - s.radius


def segment_gap(a, b, s):
    """Distance from segment a-b to sphere s's surface: < 0 crossing it."""
    ab = sub(b, a)
    t = min(max(dot(sub(s.center, a), ab) / dot(ab, ab), 0.0), 1.0)
    return norm(sub(add(a, mul(ab, t)), s.center)) - s.radius


def reference(scene, cam, i, j):
    """The model's value of pixel (i, j), or None where it is not smooth
    within JITTER of the pixel's ray (an edge that float error may cross,
    however small the jump: a second difference shows it)."""
    want = trace(scene, *pixel_ray(cam, i, j))
    for dx, dy in ((JITTER, 0), (0, JITTER)):
        ahead = trace(scene, *pixel_ray(cam, i, j, dx, dy))
        behind = trace(scene, *pixel_ray(cam, i, j, -dx, -dy))
        for a, w, b in zip(ahead, want, behind):
            if abs(a - w) > JUMP or abs(b - w) > JUMP or abs(a + b - 2 * w) > tolerance(w):
                return None
    return want


# ---------------------------------------------------------------- images


def tolerance(want, rel=REL_TOL):
    """How far a PFM value may be from want (see the top of this file)."""
    return rel * abs(want) + ABS_TOL


def close(got, want, rel=REL_TOL):
    """True if every channel of got is within tolerance of want."""
    return all(abs(g - w) <= tolerance(w, rel) for g, w in zip(got, want))


def ppm_byte(c):
    """SPEC 4's byte: c clamped to [0, 1], round(255 c) with halves up."""
    return math.floor(255 * min(max(c, 0.0), 1.0) + 0.5)


def ppm_ambiguous(c):
    """True if 255 c is within PPM_MARGIN of a rounding boundary."""
    x = 255 * min(max(c, 0.0), 1.0)
    return abs(x - math.floor(x) - 0.5) < PPM_MARGIN


def ppm_bytes(color):
    """The three bytes of color, or None if any is ambiguous."""
    if any(ppm_ambiguous(c) for c in color):
        return None
    return tuple(ppm_byte(c) for c in color)


def paeth(a, b, c):
    """PNG's Paeth predictor."""
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else (b if pb <= pc else c)


def unfilter(kind, line, prev, bpp=3):
    """One PNG scanline with its filter undone."""
    out = bytearray(line)
    for x in range(len(out)):
        a = out[x - bpp] if x >= bpp else 0
        b = prev[x]
        c = prev[x - bpp] if x >= bpp else 0
        pred = (0, a, b, (a + b) // 2, paeth(a, b, c))[kind]
        out[x] = (out[x] + pred) & 0xFF
    return out


def read_png(path):
    """(width, height, RGB bytes) of an 8-bit RGB non-interlaced PNG."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        header = body if kind == b"IHDR" else header
        idat += body if kind == b"IDAT" else b""
        pos += 12 + length
    w, h, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", header)
    assert (depth, color, interlace) == (8, 2, 0), "8-bit RGB non-interlaced expected"
    raw, stride, prev, rows = zlib.decompress(idat), 3 * w, bytearray(3 * w), []
    for y in range(h):
        line = raw[y * (stride + 1):(y + 1) * (stride + 1)]
        prev = unfilter(line[0], line[1:], prev)
        rows.append(bytes(prev))
    return w, h, b"".join(rows)


def byte_rows(w, h, data):
    """rows[j][i] = (r, g, b) of packed RGB bytes."""
    assert len(data) == 3 * w * h, f"{len(data)} pixel bytes for {w} x {h}"
    return [[tuple(data[3 * (j * w + i):3 * (j * w + i) + 3]) for i in range(w)]
            for j in range(h)]


Image = namedtuple("Image", "width height rows")  # rows[j][i] = (r, g, b), j = 0 at top


def read_image(path):
    """A .pfm, .ppm or .png file as an Image."""
    if path.endswith(".pfm"):
        return Image(*read_pfm(path))
    w, h, data = (read_png if path.endswith(".png") else read_ppm)(path)
    return Image(w, h, byte_rows(w, h, data))


# ---------------------------------------------------------------- cases


class Case(tp2test.Case):
    """A case with renders of tests/render/ scenes and pixel checks."""

    def load(self, name):
        """tests/render/NAME.txt as tp2 reads it (tp2 --dump-scene)."""
        return model.load(self.tp2, os.path.join(SCENES, name + ".txt"))

    def render(self, name, ext="pfm", size=(), options=()):
        """Renders tests/render/NAME.txt to a file of type ext; its Image.
        --bailout 0: these cases check the exact model, unpruned (the
        accuracy_* tests measure the default pruning)."""
        out = os.path.join(self.tmp, f"{name}-{len(os.listdir(self.tmp))}.{ext}")
        render(self.tp2, os.path.join(SCENES, name + ".txt"), out, size,
               ["--bailout", "0"] + list(options))
        return read_image(out)

    def expect_pixel(self, img, i, j, want, what, rel=REL_TOL):
        """tp2's PFM pixel (i, j) is want."""
        got = img.rows[j][i]
        return self.expect(close(got, want, rel),
                           f"{what} ({i},{j}): got {fmt(got)}, want {fmt(want)}")

    def expect_bytes(self, img, i, j, want, what):
        """tp2's PPM pixel (i, j) is the bytes want (None: not checked)."""
        got = img.rows[j][i]
        return want is None or self.expect(got == want, f"{what} ({i},{j}): got {got}, want {want}")

    def expect_model(self, scene, img, rel=REL_TOL):
        """Every pixel off any edge is the model's value; returns how many."""
        cam = camera(scene, img.width, img.height)
        checked = 0
        for i, j in pixels(cam):
            want = reference(scene, cam, i, j)
            if want is not None:
                self.expect_pixel(img, i, j, want, "pixel", rel)
                checked += 1
        return checked

    def expect_most(self, checked, img, fraction, what):
        """At least fraction of the image was checked (the case is not vacuous)."""
        total = img.width * img.height
        self.expect(checked >= fraction * total,
                    f"{what}: only {checked} of {total} pixels checked")


def fmt(color):
    """A color, printed compactly."""
    return "(" + ", ".join(f"{c:.6g}" for c in color) + ")"


def ambient(scene, obj):
    """ka C0 P of an object with a solid pigment."""
    fin = scene.finishes[obj.finish]
    return mul(hadamard(scene.ambient, scene.pigments[obj.pigment].color), fin.ka)


def center_pixel(img):
    """(i, j) of the pixel whose ray is the view axis (odd sizes only)."""
    assert img.width % 2 == 1 and img.height % 2 == 1
    return img.width // 2, img.height // 2


def front_lit(scene, sphere, light):
    """The closed-form light term at the sphere point facing the eye on the
    view axis (eye at the origin looking down -z): N = V = +z."""
    assert scene.eye == (0, 0, 0) and sphere.center[:2] == (0, 0), "sphere not on the axis"
    fin = scene.finishes[sphere.finish]
    p = add(sphere.center, (0.0, 0.0, sphere.radius))
    to_light = sub(light.pos, p)
    dist = norm(to_light)
    ndotl = to_light[2] / dist                  # N . L with N = (0, 0, 1)
    rdotv = ndotl                               # R = (-Lx, -Ly, Lz), V = (0, 0, 1)
    att = attenuation(light, dist)
    pig = scene.pigments[sphere.pigment].color
    diffuse = mul(pig, fin.kd * ndotl)
    spec = fin.ks * rdotv ** fin.n
    return mul(hadamard(light.color, add(diffuse, (spec, spec, spec))), att)


def case_ambient_sphere(c):
    """Ambient only: a hit pixel is exactly round(255 ka C0 P), a miss is 128."""
    scene = c.load("ambient_sphere")
    img = c.render("ambient_sphere", "ppm", (40, 30))
    sphere = scene.objects[0]
    want = ppm_bytes(ambient(scene, sphere))
    c.require(want is not None, "scene's ambient color is near a rounding boundary")
    cam = camera(scene, img.width, img.height)
    seen = {True: 0, False: 0}
    for i, j in pixels(cam):
        gap = sphere_gap(*pixel_ray(cam, i, j), sphere)
        if abs(gap) > EDGE:
            seen[gap < 0] += 1
            c.expect_bytes(img, i, j, want if gap < 0 else GRAY_BYTES, "hit" if gap < 0 else "miss")
    c.expect(min(seen.values()) > 50, f"too few hits or misses checked: {seen}")


def expect_all_gray(c, img):
    """Every PPM pixel is 128 (SPEC's round(255 * 0.5), halves up)."""
    bad = [(i, j, p) for j, row in enumerate(img.rows) for i, p in enumerate(row)
           if p != GRAY_BYTES]
    c.expect(not bad, f"{len(bad)} pixels not {GRAY_BYTES}, first {bad[:3]}")


def case_background(c):
    """No objects: every pixel is the background gray 0.5 (PPM 128)."""
    expect_all_gray(c, c.render("background", "ppm", (24, 18)))
    img = c.render("background", "pfm", (24, 18))
    bad = [p for row in img.rows for p in row if p != BACKGROUND]
    c.expect(not bad, f"{len(bad)} PFM pixels not exactly 0.5, first {bad[:3]}")


def case_diffuse(c):
    """One attenuated light, kd only: att C kd (N.L) P, at the axis and everywhere."""
    scene = c.load("diffuse")
    img = c.render("diffuse", "pfm", (41, 31))
    sphere, light = scene.objects[0], scene.lights[0]
    want = front_lit(scene, sphere, light)
    c.expect_pixel(img, *center_pixel(img), want, "axis pixel, closed form")
    c.expect_most(c.expect_model(scene, img), img, 0.9, "diffuse")


def case_specular(c):
    """ks, exponent n: att C ks (R.V)^n where R.V = cos(light angle), and everywhere."""
    scene = c.load("specular")
    img = c.render("specular", "pfm", (41, 31))
    sphere, light = scene.objects[0], scene.lights[0]
    want = front_lit(scene, sphere, light)
    c.expect_pixel(img, *center_pixel(img), want, "axis pixel, closed form")
    c.expect_most(c.expect_model(scene, img), img, 0.9, "specular")
    peak = max(max(p) for row in img.rows for p in row)
    c.expect(peak > 0.5 * light.color[0] * scene.finishes[0].ks, f"no highlight seen (max {peak})")


def floor_pixels(scene, cam):
    """(i, j, hit point) of the pixels whose ray meets the plane first."""
    for i, j in pixels(cam):
        o, d = pixel_ray(cam, i, j)
        found = nearest(scene, o, d)
        if found and isinstance(found[1], Plane):
            yield i, j, add(o, mul(d, found[0]))


def check_shadow(c, name):
    """Floor pixels in the sphere's shadow are ambient only; lit ones add the
    diffuse term att C kd (N.L) P."""
    scene = c.load(name)
    img = c.render(name, "pfm", (48, 36))
    floor, ball = the(scene, Plane), the(scene, Sphere)
    light, fin = scene.lights[0], scene.finishes[floor.finish]
    c.require(fin.ks == fin.kr == fin.kt == 0, "scene premise: floor without ks, kr, kt")
    pig = scene.pigments[floor.pigment].color
    base = ambient(scene, floor)
    counts = {"shadow": 0, "lit": 0}
    for i, j, p in floor_pixels(scene, camera(scene, img.width, img.height)):
        gap = segment_gap(p, light.pos, ball)
        if abs(gap) < 0.05:
            continue
        to_light = sub(light.pos, p)
        dist = norm(to_light)
        diffuse = mul(hadamard(light.color, pig), fin.kd * dot(floor.normal, to_light) / dist
                      * attenuation(light, dist))
        kind = "shadow" if gap < 0 else "lit"
        counts[kind] += 1
        c.expect_pixel(img, i, j, base if gap < 0 else add(base, diffuse), kind)
    c.expect(min(counts.values()) >= 10, f"too few pixels checked: {counts}")


def case_shadow(c):
    """An opaque sphere shadows the floor: ambient only inside, plus diffuse outside."""
    check_shadow(c, "shadow")


def case_transparent_shadow(c):
    """A kt = 1 sphere still casts a full shadow (SPEC: transparent objects do)."""
    check_shadow(c, "transparent_shadow")


def cell_margin(p, side):
    """How far p is from the nearest cube face of the checker, in units of side."""
    return min(abs(x / side - round(x / side)) for x in p)


# Checker hits farther than this many cell sides are skipped: float error in
# the hit point grows with distance (and more at grazing angles).
FAR_CELLS = 15


def case_checker_parity(c):
    """Checker cells: color1 where floor(x/s)+floor(y/s)+floor(z/s) is even,
    color2 where odd, on both sides of 0 on every axis (floor, not truncation)."""
    scene = c.load("checker_parity")
    pfm = c.render("checker_parity", "pfm", (48, 36))
    ppm = c.render("checker_parity", "ppm", (48, 36))
    pig = scene.pigments[0]
    cam = camera(scene, pfm.width, pfm.height)
    cells = set()
    for i, j in pixels(cam):
        o, d = pixel_ray(cam, i, j)
        found = nearest(scene, o, d)
        if not found or abs(sphere_gap(o, d, the(scene, Sphere))) < EDGE:
            continue
        p = add(o, mul(d, found[0]))
        if found[0] > FAR_CELLS * pig.side or cell_margin(p, pig.side) < 1e-3:
            continue
        cell = tuple(math.floor(x / pig.side) for x in p)
        cells.add(cell)
        want = pig.color1 if sum(cell) % 2 == 0 else pig.color2
        c.expect_pixel(pfm, i, j, want, f"cell {cell}")
        c.expect_bytes(ppm, i, j, ppm_bytes(want), f"cell {cell}")
    for axis in range(3):
        signs = {cell[axis] < 0 for cell in cells}
        c.expect(signs == {True, False}, f"axis {axis}: cells on one side of 0 only")
    c.expect({sum(cell) % 2 for cell in cells} == {0, 1}, "one parity only")


def mirror_value(a, kr, limit):
    """Ray value between two facing mirrors of ambient color a and reflectance
    kr when rays deeper than limit return gray."""
    return sum(kr ** k * a for k in range(limit + 1)) + kr ** (limit + 1) * BACKGROUND[0]


def case_depth_limit(c):
    """Facing mirrors: sum_{k<=10} kr^k ka C0 P + kr^11 * 0.5, told apart from 9 and 11."""
    scene = c.load("depth_limit")
    img = c.render("depth_limit", "pfm", (9, 7))
    a_mirror, b_mirror = scene.objects
    c.require(a_mirror[:2] == b_mirror[:2], "both mirrors must share pigment and finish")
    c.require(not scene.lights, "scene premise: ambient light only")
    kr = scene.finishes[a_mirror.finish].kr
    amb = ambient(scene, a_mirror)
    want = tuple(mirror_value(a, kr, MAX_DEPTH) for a in amb)
    for other in (MAX_DEPTH - 1, MAX_DEPTH + 1):
        alt = tuple(mirror_value(a, kr, other) for a in amb)
        c.require(not close(alt, want, 100 * REL_TOL),
                  f"limit {other} indistinguishable: {fmt(alt)}")
    for i, j in pixels(camera(scene, img.width, img.height)):
        if not c.expect_pixel(img, i, j, want, "bounced"):
            got = img.rows[j][i]
            limit = min(range(30), key=lambda n: abs(mirror_value(amb[0], kr, n) - got[0]))
            c.failures.append(f"  (red channel matches a depth limit of {limit})")
            break


def case_refraction_straight(c):
    """A kt = 1, ior = 1 sphere is invisible: the wall is seen straight through it."""
    scene = c.load("refraction_straight")
    img = c.render("refraction_straight", "pfm", (40, 30))
    wall_only = without(scene, Sphere)
    cam = camera(scene, img.width, img.height)
    sphere = the(scene, Sphere)
    through = 0
    for i, j in pixels(cam):
        want = reference(wall_only, cam, i, j)
        if want is not None:
            through += sphere_gap(*pixel_ray(cam, i, j), sphere) < 0
            c.expect_pixel(img, i, j, want, "seen past the sphere")
    c.expect(through > 100, f"only {through} pixels checked through the sphere")


def incidence_sine(o, d, sphere):
    """sin of the angle between the ray and the sphere's normal where it enters."""
    p = add(o, mul(d, hit(sphere, o, d)))
    cosi = dot(d, normal_at(sphere, p))
    return math.sqrt(max(0.0, 1 - cosi * cosi)), p


def case_total_internal_reflection(c):
    """ior < 1: past the critical angle the transmitted ray follows the mirror
    direction (weighted by kt), seeing other things than a straight ray would."""
    scene = c.load("total_internal_reflection")
    img = c.render("total_internal_reflection", "pfm", (41, 31))
    cam = camera(scene, img.width, img.height)
    sphere = the(scene, Sphere)
    fin, no_sphere = scene.finishes[sphere.finish], without(scene, Sphere)
    mirrored = 0
    for i, j in pixels(cam):
        o, d = pixel_ray(cam, i, j)
        if sphere_gap(o, d, sphere) > -EDGE or reference(scene, cam, i, j) is None:
            continue
        sine, p = incidence_sine(o, d, sphere)
        if sine < fin.ior + 0.01:
            continue
        n = normal_at(sphere, p)
        want = mul(trace(scene, nudge(p, n), reflect(d, n), 1), fin.kt)
        straight = trace(no_sphere, o, d)
        if max(abs(a - b) for a, b in zip(want, straight)) > 0.1:
            mirrored += 1
            c.expect_pixel(img, i, j, want, f"mirrored (straight would be {fmt(straight)})")
    c.expect(mirrored >= 20, f"only {mirrored} totally reflected pixels checked")
    c.expect_most(c.expect_model(scene, img), img, 0.8, "whole image")


def case_reflection(c):
    """A kr mirror floor shows kr times the sphere's color where the reflected
    ray meets the sphere, kr times gray where it does not."""
    scene = c.load("reflection")
    img = c.render("reflection", "pfm", (40, 30))
    mirror, ball = the(scene, Plane), the(scene, Sphere)
    kr = scene.finishes[mirror.finish].kr
    c.require(not scene.lights and scene.finishes[mirror.finish][:3] == (0, 0, 0),
              "scene premise: ambient light only, mirror with kr only")
    seen = {True: 0, False: 0}
    for i, j, p in floor_pixels(scene, camera(scene, img.width, img.height)):
        d = reflect(unit(sub(p, scene.eye)), mirror.normal)
        gap = sphere_gap(p, d, ball)
        if abs(gap) > EDGE:
            seen[gap < 0] += 1
            want = mul(ambient(scene, ball) if gap < 0 else BACKGROUND, kr)
            c.expect_pixel(img, i, j, want, "sphere in mirror" if gap < 0 else "sky in mirror")
    c.expect(min(seen.values()) >= 20, f"too few mirror pixels checked: {seen}")
    c.expect_most(c.expect_model(scene, img), img, 0.9, "whole image")


def case_header_variant(c):
    """A file with a name and W H first renders at W x H, or at the command line's X Y."""
    scene = c.load("header_variant")
    img = c.render("header_variant", "ppm")
    c.expect((img.width, img.height) == scene.size,
             f"size {img.width}x{img.height}, want {scene.size}")
    img = c.render("header_variant", "ppm", (20, 10))
    c.expect((img.width, img.height) == (20, 10), f"size {img.width}x{img.height}, want 20x10")
    c.expect(img.rows[0][0] == GRAY_BYTES, f"corner {img.rows[0][0]} not background")


def case_default_size(c):
    """A plain file and no X Y: 400 x 300."""
    img = c.render("background", "ppm")
    c.require((img.width, img.height) == (400, 300), f"size {img.width}x{img.height}, want 400x300")
    expect_all_gray(c, img)


def project(cam, p):
    """Image coordinates (i, j), fractional, of point p ahead of the camera."""
    rel = sub(p, cam.eye)
    x, y = dot(rel, cam.u) / dot(rel, cam.w), dot(rel, cam.v) / dot(rel, cam.w)
    return ((x / cam.x_scale + 1) * cam.width / 2 - 0.5,
            (1 - y / cam.y_scale) * cam.height / 2 - 0.5)


def expect_sphere_colors(c, scene, cam, pfm, ppm):
    """Each pixel off every silhouette shows its sphere's ambient color or gray."""
    spheres = scene.objects
    for i, j in pixels(cam):
        o, d = pixel_ray(cam, i, j)
        if min(abs(sphere_gap(o, d, s)) for s in spheres) < EDGE:
            continue
        found = nearest(scene, o, d)
        want = ambient(scene, found[1]) if found else BACKGROUND
        c.expect_pixel(pfm, i, j, want, "pixel")
        c.expect_bytes(ppm, i, j, ppm_bytes(want) if found else GRAY_BYTES, "pixel")


def case_camera_orientation(c):
    """No flip, mirror or R/B swap; aspect and vertical fov: a sphere of angular
    radius atan(tan(fov/2)/2) on the axis spans the middle half of the rows."""
    scene = c.load("camera_orientation")
    size = (64, 32)
    pfm = c.render("camera_orientation", "pfm", size)
    ppm = c.render("camera_orientation", "ppm", size)
    cam = camera(scene, *size)
    red, green, blue = scene.objects
    half = math.tan(math.radians(scene.fov) / 2) / 2
    c.require(abs(green.radius / norm(green.center) - half / math.hypot(1, half)) < 1e-12,
              "green sphere's angular radius is not atan(tan(fov/2)/2)")
    expect_sphere_colors(c, scene, cam, pfm, ppm)
    column = [j for j in range(size[1]) if close(pfm.rows[j][size[0] // 2], ambient(scene, green))]
    c.expect(column == list(range(size[1] // 4, 3 * size[1] // 4)), f"green rows {column}")
    i, j = project(cam, red.center)
    c.require(i < size[0] / 2 and j < size[1] / 2, "scene premise: red sphere at the upper left")
    c.expect_pixel(pfm, round(i), round(j), ambient(scene, red), "red sphere's center")
    i, j = project(cam, blue.center)
    c.require(i > size[0] / 2, "scene premise: blue sphere at the right")
    c.expect_pixel(pfm, round(i), round(j), ambient(scene, blue), "blue sphere's center")


def case_light_attenuation_none(c):
    """a = b = c = 0: attenuation 1, so a far light still gives C kd (N.L) P."""
    scene = c.load("light_attenuation_none")
    img = c.render("light_attenuation_none", "pfm", (41, 31))
    sphere, light = scene.objects[0], scene.lights[0]
    want = front_lit(scene, sphere, light)
    c.expect(attenuation(light, 1.0) == 1.0, "scene premise: a = b = c = 0")
    c.expect_pixel(img, *center_pixel(img), want, "axis pixel, closed form")
    c.expect_most(c.expect_model(scene, img), img, 0.4, "lit side")


def case_clamp(c):
    """Values above 1 stay in the PFM and clamp to 255 in the PPM."""
    scene = c.load("clamp")
    size = (40, 30)
    pfm, ppm = c.render("clamp", "pfm", size), c.render("clamp", "ppm", size)
    want = ambient(scene, scene.objects[0])
    c.require(max(want) > 1 and ppm_bytes(want) is not None, "scene premise: one channel above 1")
    expect_sphere_colors(c, scene, camera(scene, *size), pfm, ppm)


def case_glass_sphere(c):
    """Every term at once (ambient, diffuse, specular, shadow, reflection,
    refraction with ior 1.5, checker) matches the model everywhere."""
    scene = c.load("glass_sphere")
    img = c.render("glass_sphere", "pfm", (48, 36))
    c.expect_most(c.expect_model(scene, img), img, 0.8, "glass sphere")


def case_glass_sphere_double(c):
    """--precision double: the same scene within 1e-5 of the model."""
    scene = c.load("glass_sphere")
    img = c.render("glass_sphere", "pfm", (48, 36), ("--precision", "double"))
    c.expect_most(c.expect_model(scene, img, rel=1e-5), img, 0.8, "glass sphere, double")


def case_two_lights(c):
    """Two colored lights with different attenuations add up."""
    scene = c.load("two_lights")
    img = c.render("two_lights", "pfm", (40, 30))
    c.expect_most(c.expect_model(scene, img), img, 0.3, "two lights")


def case_png_matches_ppm(c):
    """The PNG output holds the same bytes as the PPM output."""
    size = (64, 32)
    png, ppm = c.render("glass_sphere", "png", size), c.render("glass_sphere", "ppm", size)
    c.expect((png.width, png.height) == size, f"PNG size {png.width}x{png.height}")
    c.expect(png.rows == ppm.rows, "PNG pixels differ from PPM pixels")


# ---------------------------------------------------------------- more kinds


def lit_closed_form(scene, obj, p, n):
    """ka C0 P + att C (kd N.L P + ks (R.V)^n) at point p, normal n facing
    the eye, pigment solid, one light, nothing in between: written out here,
    not taken from the model."""
    fin, light = scene.finishes[obj.finish], scene.lights[0]
    pig = scene.pigments[obj.pigment].color
    view = unit(sub(scene.eye, p))
    to_light = sub(light.pos, p)
    dist = norm(to_light)
    l = mul(to_light, 1 / dist)
    ndotl = dot(n, l)
    r = sub(mul(n, 2 * ndotl), l)
    spec = fin.ks * max(0.0, dot(r, view)) ** fin.n
    a, b, cc = light.att
    att = 1 / (a + b * dist + cc * dist * dist)
    return tuple(fin.ka * scene.ambient[k] * pig[k] +
                 att * light.color[k] * (fin.kd * ndotl * pig[k] + spec) for k in range(3))


def case_box_face(c):
    """A box face's diffuse and specular terms (N = +z on the axis), and the
    whole image against the model."""
    scene = c.load("box_face")
    img = c.render("box_face", "pfm", (41, 31))
    box = the(scene, model.Box)
    want = lit_closed_form(scene, box, (0.0, 0.0, -5.0), (0.0, 0.0, 1.0))
    c.expect_pixel(img, *center_pixel(img), want, "box face on the axis, closed form")
    c.expect_most(c.expect_model(scene, img), img, 0.9, "box")


def case_box_glass(c):
    """A glass box: refraction through flat faces, inside reflections."""
    scene = c.load("box_glass")
    img = c.render("box_glass", "pfm", (48, 36))
    c.expect_most(c.expect_model(scene, img), img, 0.7, "glass box")


def case_polyhedron(c):
    """A closed octahedron (mirror finish), an open wedge, a one-face floor."""
    scene = c.load("polyhedron")
    img = c.render("polyhedron", "pfm", (48, 36))
    c.expect_most(c.expect_model(scene, img), img, 0.8, "polyhedra")


def case_cylinder_cap(c):
    """A cylinder's top cap on the axis (N = +z, closed form); a tilted glass
    cylinder; everything against the model."""
    scene = c.load("cylinder_cap")
    img = c.render("cylinder_cap", "pfm", (41, 31))
    cyl = the(scene, model.Cylinder)
    want = lit_closed_form(scene, cyl, (0.0, 0.0, -5.0), (0.0, 0.0, 1.0))
    c.expect_pixel(img, *center_pixel(img), want, "cap on the axis, closed form")
    c.expect_most(c.expect_model(scene, img), img, 0.85, "cylinders")


def case_cone_apex(c):
    """A cone's side up to its apex and its base cap, a frustum; the model
    everywhere, the apex's neighborhood included."""
    scene = c.load("cone_apex")
    img = c.render("cone_apex", "pfm", (48, 36))
    cam = camera(scene, img.width, img.height)
    cone = the(scene, model.Cone)
    ai, aj = project(cam, cone.top)
    near = 0
    for i, j in pixels(cam):
        want = reference(scene, cam, i, j)
        if want is None:
            continue
        c.expect_pixel(img, i, j, want, "pixel")
        near += abs(i - ai) <= 3 and abs(j - aj) <= 3
    c.expect(near >= 10, f"only {near} pixels checked within 3 of the apex")


def case_standing_on_floor(c):
    """A frustum and a cylinder whose second end lies in the floor (packing
    turns them over, radii and all), and a box, standing on a floor plane
    and casting shadows on it: the model everywhere."""
    scene = c.load("standing")
    img = c.render("standing", "pfm", (48, 36))
    c.expect_most(c.expect_model(scene, img), img, 0.9, "standing solids")


def case_torus_hole(c):
    """The ray on the axis passes through the torus's hole to the wall; the
    ring around it is the torus; the model everywhere."""
    scene = c.load("torus_hole")
    img = c.render("torus_hole", "pfm", (41, 31))
    cam = camera(scene, img.width, img.height)
    ring = the(scene, model.Torus)
    i, j = center_pixel(img)
    found = nearest(scene, *pixel_ray(cam, i, j))
    c.require(isinstance(found[1], Plane), "scene premise: the axis ray meets the wall")
    c.expect_pixel(img, i, j, trace(scene, *pixel_ray(cam, i, j)), "through the hole")
    ri, rj = project(cam, (ring.R, 0.0, -6.0))
    ring_pixel = img.rows[round(rj)][round(ri)]
    c.expect(not close(ring_pixel, img.rows[j][i]), "the ring looks like the hole")
    c.expect_most(c.expect_model(scene, img), img, 0.85, "tori")


def case_quadric_inside(c):
    """The camera inside an ellipsoid quadric: its far end on the axis is
    lit from inside (outward normal -z, facing the eye +z), closed form."""
    scene = c.load("quadric_inside")
    img = c.render("quadric_inside", "pfm", (41, 31))
    shell = the(scene, model.Quadric)
    want = lit_closed_form(scene, shell, (0.0, 0.0, -6.0), (0.0, 0.0, 1.0))
    c.expect_pixel(img, *center_pixel(img), want, "far end on the axis, closed form")
    c.expect_most(c.expect_model(scene, img), img, 0.9, "inside")


def case_quadric_shapes(c):
    """A hyperboloid, a glass ellipsoid and a paraboloid against the model."""
    scene = c.load("quadric_shapes")
    img = c.render("quadric_shapes", "pfm", (48, 36))
    c.expect_most(c.expect_model(scene, img), img, 0.8, "quadrics")


def case_triangle_winding(c):
    """A triangle facing the camera: N.L with the normal facing the eye
    (closed form), whichever way it is wound (the clockwise copy renders the
    same image); a glass triangle lets light through unbent."""
    scene = c.load("triangle_winding")
    img = c.render("triangle_winding", "pfm", (41, 31))
    cw = c.render("triangle_winding_cw", "pfm", (41, 31))
    tri = the(scene, model.Triangle)
    want = lit_closed_form(scene, tri, (0.0, 0.0, -5.0), (0.0, 0.0, 1.0))
    c.expect_pixel(img, *center_pixel(img), want, "triangle on the axis, closed form")
    c.expect(img.rows == cw.rows, "winding the triangle the other way changed the image")
    c.expect_most(c.expect_model(scene, img), img, 0.85, "triangles")


def case_mesh(c):
    """mesh.obj (quads, negative indices, v/t/n parts) renders exactly as its
    triangles written one by one, and matches the model."""
    scene = c.load("mesh")
    img = c.render("mesh", "pfm", (48, 36))
    one_by_one = c.render("mesh_triangles", "pfm", (48, 36))
    c.expect(img.rows == one_by_one.rows, "mesh and its triangles differ")
    c.expect(len(scene.objects) == 8, f"{len(scene.objects)} objects, want floor, 6 triangles, sphere")
    c.expect_most(c.expect_model(scene, img), img, 0.85, "mesh")


def case_gradient_midpoint(c):
    """Ambient light 1 and ka 1 show the pigment itself: the gradient's
    midpoint x = 0 is (c0 + c1) / 2, its ends' colors hold beyond them."""
    scene = c.load("gradient")
    img = c.render("gradient", "pfm", (41, 31))
    cam = camera(scene, img.width, img.height)
    i, j = center_pixel(img)
    c.expect_pixel(img, i, j, (0.5, 0.0, 0.5), "midpoint x = 0")
    for col, want in ((0, (1.0, 0.0, 0.0)), (img.width - 1, (0.0, 0.0, 1.0))):
        o, d = pixel_ray(cam, col, 0)
        c.require(abs(o[0] + d[0] * 5 / -d[2]) > 1, "scene premise: the image's sides lie beyond x = 1")
        c.expect_pixel(img, col, 0, want, "clamped beyond the end")
    c.expect_most(c.expect_model(scene, img), img, 0.9, "gradients")


def case_texmap_texels(c):
    """Texels looked up at s = x / 4 + 0.5 with t = 0 exactly: the first and
    last rows blend half and half (SPEC 3), bilinear across columns,
    worked out here from texels.ppm's numbers; t = -y / 3 below."""
    scene = c.load("texmap")
    size = (40, 30)
    img = c.render("texmap", "pfm", size)
    ppm = c.render("texmap", "ppm", size)
    cam = camera(scene, *size)
    texels = [[(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 0)],
              [(0, 255, 255), (255, 0, 255), (128, 128, 128), (64, 32, 16)],
              [(16, 32, 64), (200, 100, 50), (50, 100, 200), (10, 240, 10)]]
    checked = 0
    for i, j in pixels(cam):
        o, d = pixel_ray(cam, i, j)
        p = add(o, mul(d, -5 / d[2]))
        if p[1] < 1e-3:
            continue  # the lower wall: the model checks it below
        x = ((p[0] / 4 + 0.5) % 1) * 4 - 0.5   # texel coordinate, centers at k + 0.5 - 0.5
        k0 = math.floor(x)
        f = x - k0
        def column(row):
            a, b = texels[row][k0 % 4], texels[row][(k0 + 1) % 4]
            return [(1 - f) * a[ch] + f * b[ch] for ch in range(3)]
        top, bottom = column(0), column(2)
        want = tuple((0.5 * top[ch] + 0.5 * bottom[ch]) / 255 for ch in range(3))
        c.expect_pixel(img, i, j, want, f"texel blend at x = {p[0]:.3f}")
        c.expect_bytes(ppm, i, j, ppm_bytes(want), "texel blend")
        checked += 1
    c.expect(checked >= 400, f"only {checked} top-wall pixels checked")
    c.expect_most(c.expect_model(scene, img), img, 0.9, "texmap")


CASES = {name[5:]: f for name, f in sorted(globals().items()) if name.startswith("case_")}


if __name__ == "__main__":
    sys.exit(tp2test.run_cases(globals(), Case))
