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
from tp2test import read_pfm, read_ppm, render

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "render")

REL_TOL = 1e-4        # PFM, relative (float geometry, see above)
ABS_TOL = 1e-5        # PFM, absolute floor for values near zero
PPM_MARGIN = 1e-3     # skip a byte whose 255 c is this close to x.5
EDGE = 1e-3           # world units: skip rays this close to a silhouette
JITTER = 5e-5         # image-plane offset probing for a discontinuity
JUMP = 0.02           # a change this big under JITTER is an edge
BACKGROUND = (0.5, 0.5, 0.5)
GRAY_BYTES = (128, 128, 128)  # round(255 * 0.5) = round(127.5), halves up
MAX_DEPTH = 10
NUDGE = 1e-9          # secondary rays start this far off the surface

# ---------------------------------------------------------------- vectors


def add(a, b):
    """a + b."""
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    """a - b."""
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def mul(a, s):
    """a scaled by the number s."""
    return (a[0] * s, a[1] * s, a[2] * s)


def hadamard(a, b):
    """a times b channel by channel (colors)."""
    return (a[0] * b[0], a[1] * b[1], a[2] * b[2])


def dot(a, b):
    """a . b."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    """a x b."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    """|a|."""
    return math.sqrt(dot(a, a))


def unit(a):
    """a / |a|."""
    return mul(a, 1 / norm(a))


def reflect(d, n):
    """d mirrored about the plane of unit normal n."""
    return sub(d, mul(n, 2 * dot(d, n)))


# ---------------------------------------------------------------- scene files

Scene = namedtuple("Scene", "size eye center up fov ambient lights pigments finishes objects")
Light = namedtuple("Light", "pos color att")
Finish = namedtuple("Finish", "ka kd ks n kr kt ior")
Solid = namedtuple("Solid", "color")
Checker = namedtuple("Checker", "color1 color2 side")
Sphere = namedtuple("Sphere", "pigment finish center radius")
Plane = namedtuple("Plane", "pigment finish normal dist")  # unit normal . x + dist = 0

NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


def tokens(path):
    """The file's tokens, numbers split the way strtod reads them (SPEC 2)."""
    out = []
    with open(path) as f:
        for line in f:
            for word in line.split("#", 1)[0].split():
                while word and NUMBER.match(word):
                    m = NUMBER.match(word)
                    out.append(float(m.group()))
                    word = word[m.end():]
                if word:
                    out.append(word)
    return out


class Reader:
    """Takes a scene file's tokens in order."""

    def __init__(self, path):
        self.items = tokens(path)
        self.pos = 0

    def take(self):
        """The next token."""
        self.pos += 1
        return self.items[self.pos - 1]

    def vec(self):
        """The next three numbers."""
        return (self.take(), self.take(), self.take())

    def count(self):
        """The next number as a count."""
        return int(self.take())


def read_pigment(r):
    """One pigment line."""
    kind = r.take()
    if kind == "solid":
        return Solid(r.vec())
    assert kind == "checker", f"pigment {kind} not handled here"
    return Checker(r.vec(), r.vec(), r.take())


def read_object(r):
    """One object line."""
    pigment, finish, kind = r.count(), r.count(), r.take()
    if kind == "sphere":
        return Sphere(pigment, finish, r.vec(), r.take())
    assert kind == "plane", f"object {kind} not handled here"
    n, d = r.vec(), r.take()
    return Plane(pigment, finish, unit(n), d / norm(n))


def load(name):
    """Reads tests/render/NAME.txt (both variants; trailing directives ignored)."""
    r = Reader(os.path.join(SCENES, name + ".txt"))
    size = None
    if isinstance(r.items[0], str):
        r.take()
        size = (r.count(), r.count())
    eye, center, up, fov = r.vec(), r.vec(), r.vec(), r.take()
    lights = [Light(r.vec(), r.vec(), r.vec()) for _ in range(r.count())]
    pigments = [read_pigment(r) for _ in range(r.count())]
    finishes = [Finish(*(r.take() for _ in range(7))) for _ in range(r.count())]
    objects = [read_object(r) for _ in range(r.count())]
    return Scene(size, eye, center, up, fov, lights[0].color, lights[1:], pigments,
                 finishes, objects)


def without(scene, kind):
    """The scene with its objects of type kind removed."""
    return scene._replace(objects=[o for o in scene.objects if not isinstance(o, kind)])


# ---------------------------------------------------------------- geometry

Camera = namedtuple("Camera", "eye u v w x_scale y_scale width height")


def camera(scene, width, height):
    """SPEC 4's camera basis for an image of width x height."""
    w = unit(sub(scene.center, scene.eye))
    u = unit(cross(w, scene.up))
    v = cross(u, w)
    t = math.tan(math.radians(scene.fov) / 2)
    return Camera(scene.eye, u, v, w, t * width / height, t, width, height)


def pixel_ray(cam, i, j, dx=0.0, dy=0.0):
    """(origin, unit direction) through pixel (i, j)'s center, moved by
    (dx, dy) on the image plane."""
    x = (2 * (i + 0.5) / cam.width - 1) * cam.x_scale + dx
    y = (1 - 2 * (j + 0.5) / cam.height) * cam.y_scale + dy
    return cam.eye, unit(add(cam.w, add(mul(cam.u, x), mul(cam.v, y))))


def pixels(cam):
    """Every (i, j) of the image, row by row."""
    return ((i, j) for j in range(cam.height) for i in range(cam.width))


def hit_sphere(o, d, s):
    """Nearest t > 0 where o + t d (d unit) meets sphere s, or None."""
    oc = sub(o, s.center)
    b = dot(oc, d)
    disc = b * b - (dot(oc, oc) - s.radius ** 2)
    if disc < 0:
        return None
    root = math.sqrt(disc)
    return next((t for t in (-b - root, -b + root) if t > 0), None)


def hit_plane(o, d, p):
    """t > 0 where o + t d meets plane p, or None."""
    denom = dot(p.normal, d)
    if denom == 0:
        return None
    t = -(dot(p.normal, o) + p.dist) / denom
    return t if t > 0 else None


def hit(obj, o, d):
    """t > 0 where the ray meets obj, or None."""
    return hit_sphere(o, d, obj) if isinstance(obj, Sphere) else hit_plane(o, d, obj)


def nearest(scene, o, d):
    """(t, object) of the nearest hit, or None."""
    hits = [(t, obj) for obj in scene.objects for t in [hit(obj, o, d)] if t is not None]
    return min(hits, key=lambda h: h[0], default=None)


def normal_at(obj, p):
    """obj's outward unit normal at its surface point p."""
    return unit(sub(p, obj.center)) if isinstance(obj, Sphere) else obj.normal


def sphere_gap(o, d, s):
    """Distance from the ray's line to sphere s's surface: < 0 through it."""
    oc = sub(s.center, o)
    return norm(sub(oc, mul(d, dot(oc, d)))) - s.radius


def segment_gap(a, b, s):
    """Distance from segment a-b to sphere s's surface: < 0 crossing it."""
    ab = sub(b, a)
    t = min(max(dot(sub(s.center, a), ab) / dot(ab, ab), 0.0), 1.0)
    return norm(sub(add(a, mul(ab, t)), s.center)) - s.radius


def the(scene, kind):
    """The scene's first object of type kind."""
    return next(o for o in scene.objects if isinstance(o, kind))


def nudge(p, n):
    """p moved off its surface along n (double precision self-hit guard)."""
    return add(p, mul(n, NUDGE * (1 + norm(p))))


# ---------------------------------------------------------------- SPEC 4


def pigment_at(pig, p):
    """The pigment's color at point p (SPEC 3)."""
    if isinstance(pig, Solid):
        return pig.color
    k = sum(math.floor(x / pig.side) for x in p)
    return pig.color1 if k % 2 == 0 else pig.color2


def attenuation(light, dist):
    """1 / (a + b d + c d^2), or 1 when a = b = c = 0."""
    a, b, c = light.att
    return 1.0 if a == b == c == 0 else 1 / (a + b * dist + c * dist * dist)


def in_shadow(scene, origin, light):
    """True if any object crosses the segment from origin to the light."""
    to_light = sub(light.pos, origin)
    dist = norm(to_light)
    d = mul(to_light, 1 / dist)
    return any(t is not None and t < dist for t in (hit(o, origin, d) for o in scene.objects))


def light_term(scene, fin, pig, p, nf, view, light):
    """att * C * (kd (Nf.L) P + ks max(0, R.V)^n) of one light, 0 if hidden."""
    to_light = sub(light.pos, p)
    dist = norm(to_light)
    l = mul(to_light, 1 / dist)
    ndotl = dot(nf, l)
    if ndotl <= 0 or in_shadow(scene, nudge(p, nf), light):
        return (0.0, 0.0, 0.0)
    spec = fin.ks * max(0.0, dot(reflect(mul(l, -1), nf), view)) ** fin.n
    shade = add(mul(pig, fin.kd * ndotl), (spec, spec, spec))
    return mul(hadamard(light.color, shade), attenuation(light, dist))


def local_color(scene, fin, pig, p, nf, view):
    """ka C0 P plus every visible light's Phong term."""
    color = mul(hadamard(scene.ambient, pig), fin.ka)
    for light in scene.lights:
        color = add(color, light_term(scene, fin, pig, p, nf, view, light))
    return color


def transmitted_ray(d, n, ior, p):
    """(origin, direction, total) of the transmitted ray at p: bent by Snell's
    law, or along the mirror direction under total internal reflection."""
    entering = dot(d, n) < 0
    nf, eta = (n, 1 / ior) if entering else (mul(n, -1), ior)
    cosi = -dot(d, nf)
    k = 1 - eta * eta * (1 - cosi * cosi)
    if k < 0:
        return nudge(p, nf), reflect(d, nf), True
    bent = add(mul(d, eta), mul(nf, eta * cosi - math.sqrt(k)))
    return nudge(p, mul(nf, -1)), unit(bent), False


def trace(scene, o, d, depth=0):
    """The color of ray o + t d at depth `depth` (SPEC 4)."""
    found = nearest(scene, o, d) if depth <= MAX_DEPTH else None
    if found is None:
        return BACKGROUND
    t, obj = found
    p = add(o, mul(d, t))
    n = normal_at(obj, p)
    nf = n if dot(d, n) < 0 else mul(n, -1)
    fin = scene.finishes[obj.finish]
    pig = pigment_at(scene.pigments[obj.pigment], p)
    color = local_color(scene, fin, pig, p, nf, mul(d, -1))
    if fin.kr > 0:
        color = add(color, mul(trace(scene, nudge(p, nf), reflect(d, nf), depth + 1), fin.kr))
    if fin.kt > 0:
        origin, direction, _ = transmitted_ray(d, n, fin.ior, p)
        color = add(color, mul(trace(scene, origin, direction, depth + 1), fin.kt))
    return color


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
    scene = load("ambient_sphere")
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
    scene = load("diffuse")
    img = c.render("diffuse", "pfm", (41, 31))
    sphere, light = scene.objects[0], scene.lights[0]
    want = front_lit(scene, sphere, light)
    c.expect_pixel(img, *center_pixel(img), want, "axis pixel, closed form")
    c.expect_most(c.expect_model(scene, img), img, 0.9, "diffuse")


def case_specular(c):
    """ks, exponent n: att C ks (R.V)^n where R.V = cos(light angle), and everywhere."""
    scene = load("specular")
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
    scene = load(name)
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
    scene = load("checker_parity")
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
    scene = load("depth_limit")
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
    scene = load("refraction_straight")
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
    p = add(o, mul(d, hit_sphere(o, d, sphere)))
    cosi = dot(d, normal_at(sphere, p))
    return math.sqrt(max(0.0, 1 - cosi * cosi)), p


def case_total_internal_reflection(c):
    """ior < 1: past the critical angle the transmitted ray follows the mirror
    direction (weighted by kt), seeing other things than a straight ray would."""
    scene = load("total_internal_reflection")
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
    scene = load("reflection")
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
    scene = load("header_variant")
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
    scene = load("camera_orientation")
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
    scene = load("light_attenuation_none")
    img = c.render("light_attenuation_none", "pfm", (41, 31))
    sphere, light = scene.objects[0], scene.lights[0]
    want = front_lit(scene, sphere, light)
    c.expect(attenuation(light, 1.0) == 1.0, "scene premise: a = b = c = 0")
    c.expect_pixel(img, *center_pixel(img), want, "axis pixel, closed form")
    c.expect_most(c.expect_model(scene, img), img, 0.4, "lit side")


def case_clamp(c):
    """Values above 1 stay in the PFM and clamp to 255 in the PPM."""
    scene = load("clamp")
    size = (40, 30)
    pfm, ppm = c.render("clamp", "pfm", size), c.render("clamp", "ppm", size)
    want = ambient(scene, scene.objects[0])
    c.require(max(want) > 1 and ppm_bytes(want) is not None, "scene premise: one channel above 1")
    expect_sphere_colors(c, scene, camera(scene, *size), pfm, ppm)


def case_glass_sphere(c):
    """Every term at once (ambient, diffuse, specular, shadow, reflection,
    refraction with ior 1.5, checker) matches the model everywhere."""
    scene = load("glass_sphere")
    img = c.render("glass_sphere", "pfm", (48, 36))
    c.expect_most(c.expect_model(scene, img), img, 0.8, "glass sphere")


def case_glass_sphere_double(c):
    """--precision double: the same scene within 1e-5 of the model."""
    scene = load("glass_sphere")
    img = c.render("glass_sphere", "pfm", (48, 36), ("--precision", "double"))
    c.expect_most(c.expect_model(scene, img, rel=1e-5), img, 0.8, "glass sphere, double")


def case_two_lights(c):
    """Two colored lights with different attenuations add up."""
    scene = load("two_lights")
    img = c.render("two_lights", "pfm", (40, 30))
    c.expect_most(c.expect_model(scene, img), img, 0.3, "two lights")


def case_png_matches_ppm(c):
    """The PNG output holds the same bytes as the PPM output."""
    size = (64, 32)
    png, ppm = c.render("glass_sphere", "png", size), c.render("glass_sphere", "ppm", size)
    c.expect((png.width, png.height) == size, f"PNG size {png.width}x{png.height}")
    c.expect(png.rows == ppm.rows, "PNG pixels differ from PPM pixels")


CASES = {name[5:]: f for name, f in sorted(globals().items()) if name.startswith("case_")}


if __name__ == "__main__":
    sys.exit(tp2test.run_cases(globals(), Case))
