"""reference.py: SPEC 4's image model in double precision, for the tests.

An independent implementation of what tp2 computes, written for clarity,
not speed: scenes come from `tp2 --dump-scene` (so the format is parsed in
one place), and everything after that is done here from the numbers, with
other methods than the shader's where it matters: every crossing of a ray
with a surface is found (a quartic's roots by Durand-Kerner iteration, not
by isolation), the nearest one past the ray's start wins, and secondary
rays start NUDGE off their surface instead of excluding it. Standard
library only."""
import cmath
import json
import math
import subprocess
from collections import namedtuple

BACKGROUND = (0.5, 0.5, 0.5)
MAX_DEPTH = 10
NUDGE = 1e-9          # secondary rays start this far off the surface, relative

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


# ---------------------------------------------------------------- scenes

Scene = namedtuple("Scene", "size eye center up fov ambient lights pigments finishes objects "
                            "samples lens fog arealight")
Light = namedtuple("Light", "pos color att")
Finish = namedtuple("Finish", "ka kd ks n kr kt ior")
Solid = namedtuple("Solid", "color")
Checker = namedtuple("Checker", "color1 color2 side")
Gradient = namedtuple("Gradient", "p0 p1 color0 color1")
Texmap = namedtuple("Texmap", "width height s t texels")  # texels[y][x] = (r, g, b) in [0, 1]

Sphere = namedtuple("Sphere", "pigment finish center radius")
Plane = namedtuple("Plane", "pigment finish normal dist")          # unit normal . x + dist = 0
Polyhedron = namedtuple("Polyhedron", "pigment finish faces")      # faces: Planes' (normal, dist)
Box = namedtuple("Box", "pigment finish lo hi")
Cylinder = namedtuple("Cylinder", "pigment finish base top radius")
Cone = namedtuple("Cone", "pigment finish base r0 top r1")
Torus = namedtuple("Torus", "pigment finish center axis R r")     # unit axis
Quadric = namedtuple("Quadric", "pigment finish coef")             # A..J
Triangle = namedtuple("Triangle", "pigment finish a b c")


def read_ppm_texels(path):
    """rows[y][x] = (r, g, b) in [0, 1] of a P3 or P6 file (the tests' own)."""
    with open(path, "rb") as f:
        data = f.read()
    words, pos = [], 2
    while len(words) < 3:   # width, height, maxval; '#' comments between
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos)
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        words.append(int(data[pos:end]))
        pos = end
    w, h, maxval = words
    if data[:2] == b"P6":
        size = 2 if maxval > 255 else 1
        raw = data[pos + 1:]
        values = [int.from_bytes(raw[k * size:(k + 1) * size], "big") for k in range(3 * w * h)]
    else:
        values = [int(v) for v in data[pos:].split()[:3 * w * h]]
    texel = [round(255 * v / maxval) / 255 for v in values]  # tp2 keeps 8 bits
    return [[tuple(texel[3 * (y * w + x):3 * (y * w + x) + 3]) for x in range(w)]
            for y in range(h)]


def make_pigment(p):
    """A pigment of --dump-scene's JSON."""
    if p["kind"] == "solid":
        return Solid(tuple(p["color"]))
    if p["kind"] == "checker":
        return Checker(tuple(p["color1"]), tuple(p["color2"]), p["side"])
    if p["kind"] == "gradient":
        return Gradient(tuple(p["p0"]), tuple(p["p1"]), tuple(p["color0"]), tuple(p["color1"]))
    if p["kind"] == "texmap":
        return Texmap(p["width"], p["height"], tuple(p["s"]), tuple(p["t"]),
                      read_ppm_texels(p["file"]))
    raise ValueError(f"reference.py has no model of the pigment kind {p['kind']!r}")


def plane_of(a, b, c, d):
    """(unit normal, distance) of a x + b y + c z + d = 0."""
    n = norm((a, b, c))
    return (unit((a, b, c)), d / n)


def make_objects(o):
    """The objects (a mesh: its triangles) of one --dump-scene object."""
    pg, fi, v = o["pigment"], o["finish"], o["numbers"]
    kind = o["kind"]
    if kind == "sphere":
        return [Sphere(pg, fi, tuple(v[:3]), v[3])]
    if kind == "plane":
        return [Plane(pg, fi, *plane_of(*v))]
    if kind == "polyhedron":
        return [Polyhedron(pg, fi, [plane_of(*v[k:k + 4]) for k in range(0, len(v), 4)])]
    if kind == "box":
        return [Box(pg, fi, tuple(min(v[k], v[k + 3]) for k in range(3)),
                    tuple(max(v[k], v[k + 3]) for k in range(3)))]
    if kind == "cylinder":
        return [Cylinder(pg, fi, tuple(v[:3]), tuple(v[3:6]), v[6])]
    if kind == "cone":
        return [Cone(pg, fi, tuple(v[:3]), v[3], tuple(v[4:7]), v[7])]
    if kind == "torus":
        return [Torus(pg, fi, tuple(v[:3]), unit(tuple(v[3:6])), v[6], v[7])]
    if kind == "quadric":
        return [Quadric(pg, fi, tuple(v))]
    if kind in ("triangle", "mesh"):  # 9 numbers per triangle
        return [Triangle(pg, fi, tuple(v[k:k + 3]), tuple(v[k + 3:k + 6]),
                         tuple(v[k + 6:k + 9])) for k in range(0, len(v), 9)]
    raise ValueError(f"reference.py has no model of the shape kind {kind!r}")


def load(tp2, path):
    """The scene at path as tp2 reads it (tp2 --dump-scene)."""
    out = subprocess.run([tp2, "--dump-scene", path], capture_output=True, check=True).stdout
    j = json.loads(out)
    lights = [Light(tuple(l["pos"]), tuple(l["color"]), tuple(l["att"])) for l in j["lights"]]
    return Scene(tuple(j["size"]) if j["size"] else None, tuple(j["eye"]), tuple(j["center"]),
                 tuple(j["up"]), j["fov"], lights[0].color if lights else (0, 0, 0), lights[1:],
                 [make_pigment(p) for p in j["pigments"]],
                 [Finish(**f) for f in j["finishes"]],
                 [obj for o in j["objects"] for obj in make_objects(o)],
                 j["samples"], j["lens"], j["fog"], j["arealight"])


def without(scene, kind):
    """The scene with its objects of type kind removed."""
    return scene._replace(objects=[o for o in scene.objects if not isinstance(o, kind)])


def the(scene, kind):
    """The scene's first object of type kind."""
    return next(o for o in scene.objects if isinstance(o, kind))


# ---------------------------------------------------------------- camera

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


# ---------------------------------------------------------------- shapes
# crossings(obj, o, d): every t where the line o + t d (d unit) crosses the
# object's surface, ascending. normal_at(obj, p): the outward unit normal at
# surface point p.


def quadratic(a, b, c):
    """Real roots of a t^2 + b t + c, ascending."""
    if a == 0:
        return [] if b == 0 else [-c / b]
    disc = b * b - 4 * a * c
    if disc < 0:
        return []
    q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
    roots = [q / a, c / q] if q != 0 else [0.0, 0.0]
    return sorted(roots)


def convex_span(o, d, faces):
    """(t_in, t_out) of the line inside the half-spaces n.x + dist <= 0."""
    t_in, t_out = -math.inf, math.inf
    for n, dist in faces:
        denom, side = dot(n, d), dot(n, o) + dist
        if denom == 0:
            if side > 0:
                return None
        elif denom < 0:
            t_in = max(t_in, -side / denom)
        else:
            t_out = min(t_out, -side / denom)
    return (t_in, t_out) if t_in <= t_out else None


def span_crossings(span):
    """The finite ends of a span."""
    return [] if span is None else [t for t in span if math.isfinite(t)]


def box_faces(b):
    """A box as six half-spaces."""
    faces = []
    for k in range(3):
        e = tuple(1.0 if a == k else 0.0 for a in range(3))
        faces += [(mul(e, -1), b.lo[k]), (e, -b.hi[k])]
    return faces


def axis_frame(base, top):
    """(unit axis, length) from base to top."""
    a = sub(top, base)
    return unit(a), norm(a)


def tapered_crossings(o, d, base, r0, top, r1):
    """Crossings of a capped cone (r0 = r1: a cylinder): the side's
    quadratic |x_perp|^2 = (r0 + k z)^2 where r0 + k z >= 0, and the caps."""
    axis, h = axis_frame(base, top)
    k = (r1 - r0) / h
    oc = sub(o, base)
    oz, dz = dot(oc, axis), dot(d, axis)
    op, dp = sub(oc, mul(axis, oz)), sub(d, mul(axis, dz))
    rho = r0 + k * oz
    ts = []
    for t in quadratic(dot(dp, dp) - (k * dz) ** 2, 2 * (dot(op, dp) - rho * k * dz),
                       dot(op, op) - rho * rho):
        z = oz + t * dz
        if 0 <= z <= h and r0 + k * z >= 0:
            ts.append(t)
    if dz != 0:
        for z0, rad in ((0.0, r0), (h, r1)):
            t = (z0 - oz) / dz
            if norm(sub(add(oc, mul(d, t)), mul(axis, z0))) <= rad:
                ts.append(t)
    return sorted(ts)


def torus_quartic(o, d, t):
    """Coefficients (c4..c0) of the torus equation along the line."""
    x = sub(o, t.center)
    R, r = t.R, t.r
    alpha, xx = dot(x, d), dot(x, x)
    beta = xx + R * R - r * r
    dz, xz = dot(d, t.axis), dot(x, t.axis)
    return (1.0, 4 * alpha, 4 * alpha * alpha + 2 * beta - 4 * R * R * (1 - dz * dz),
            4 * alpha * beta - 8 * R * R * (alpha - xz * dz), beta * beta - 4 * R * R * (xx - xz * xz))


def poly_roots(coef):
    """Real roots of a monic polynomial (Durand-Kerner, then Newton)."""
    n = len(coef) - 1
    f = lambda z: sum(c * z ** (n - i) for i, c in enumerate(coef))
    df = lambda z: sum(c * (n - i) * z ** (n - i - 1) for i, c in enumerate(coef[:-1]))
    bound = 1 + max(abs(c) for c in coef[1:])
    z = [bound * cmath.exp(2j * math.pi * (k + 0.25) / n) for k in range(n)]
    for _ in range(500):
        new = []
        for k in range(n):
            den = 1
            for m in range(n):
                if m != k:
                    den *= z[k] - z[m]
            new.append(z[k] - f(z[k]) / den if den != 0 else z[k] + 1e-9)
        done = max(abs(a - b) for a, b in zip(new, z)) <= 1e-15 * bound
        z = new
        if done:
            break
    roots = []
    for w in z:
        if abs(w.imag) > 1e-6 * bound:
            continue
        x = w.real
        for _ in range(5):   # polish
            s = df(x)
            if s == 0:
                break
            x -= f(x) / s
        roots.append(x)
    return sorted(roots)


def quadric_value(q, p):
    """Q(p) and its gradient."""
    A, B, C, D, E, F, G, H, I, J = q.coef
    x, y, z = p
    val = A * x * x + B * y * y + C * z * z + D * x * y + E * x * z + F * y * z + G * x + H * y + I * z + J
    grad = (2 * A * x + D * y + E * z + G, 2 * B * y + D * x + F * z + H, 2 * C * z + E * x + F * y + I)
    return val, grad


def crossings(obj, o, d):
    """Every t where the line o + t d crosses obj's surface, ascending."""
    if isinstance(obj, Sphere):
        oc = sub(o, obj.center)
        return quadratic(1.0, 2 * dot(oc, d), dot(oc, oc) - obj.radius ** 2)
    if isinstance(obj, Plane):
        denom = dot(obj.normal, d)
        return [] if denom == 0 else [-(dot(obj.normal, o) + obj.dist) / denom]
    if isinstance(obj, Polyhedron):
        return span_crossings(convex_span(o, d, obj.faces))
    if isinstance(obj, Box):
        return span_crossings(convex_span(o, d, box_faces(obj)))
    if isinstance(obj, Cylinder):
        return tapered_crossings(o, d, obj.base, obj.radius, obj.top, obj.radius)
    if isinstance(obj, Cone):
        return tapered_crossings(o, d, obj.base, obj.r0, obj.top, obj.r1)
    if isinstance(obj, Torus):
        return [t for t in poly_roots(torus_quartic(o, d, obj))
                if abs(torus_tube(obj, add(o, mul(d, t)))) < 1e-6 * (obj.R + obj.r) ** 2]
    if isinstance(obj, Quadric):
        A, B, C, D, E, F, G, H, I, J = obj.coef
        q0, g0 = quadric_value(obj, o)
        qa = (A * d[0] ** 2 + B * d[1] ** 2 + C * d[2] ** 2 + D * d[0] * d[1] + E * d[0] * d[2]
              + F * d[1] * d[2])
        return quadratic(qa, dot(g0, d), q0)
    # triangle: the plane's crossing, inside all three edges
    n = cross(sub(obj.b, obj.a), sub(obj.c, obj.a))
    denom = dot(n, d)
    if denom == 0:
        return []
    t = dot(n, sub(obj.a, o)) / denom
    p = add(o, mul(d, t))
    inside = all(dot(cross(sub(q1, q0), sub(p, q0)), n) >= 0
                 for q0, q1 in ((obj.a, obj.b), (obj.b, obj.c), (obj.c, obj.a)))
    return [t] if inside else []


def torus_tube(t, p):
    """(distance from the core circle)^2 - r^2: zero on the surface."""
    y = sub(p, t.center)
    z = dot(y, t.axis)
    rho = norm(sub(y, mul(t.axis, z)))
    return (rho - t.R) ** 2 + z * z - t.r * t.r


def nearest_face(faces, p):
    """The normal of the face p lies on (the nearest)."""
    return min(faces, key=lambda f: abs(dot(f[0], p) + f[1]))[0]


def normal_at(obj, p):
    """obj's outward unit normal at its surface point p."""
    if isinstance(obj, Sphere):
        return unit(sub(p, obj.center))
    if isinstance(obj, Plane):
        return obj.normal
    if isinstance(obj, Polyhedron):
        return nearest_face(obj.faces, p)
    if isinstance(obj, Box):
        return nearest_face(box_faces(obj), p)
    if isinstance(obj, (Cylinder, Cone)):
        base, top = obj.base, obj.top
        r0, r1 = (obj.radius, obj.radius) if isinstance(obj, Cylinder) else (obj.r0, obj.r1)
        axis, h = axis_frame(base, top)
        z = dot(sub(p, base), axis)
        radial = sub(sub(p, base), mul(axis, z))
        k = (r1 - r0) / h
        side = abs(norm(radial) - (r0 + k * z))
        if min(abs(z), abs(z - h)) < side:
            return mul(axis, -1) if abs(z) < abs(z - h) else axis
        return unit(sub(unit(radial), mul(axis, k)))
    if isinstance(obj, Torus):
        y = sub(p, obj.center)
        radial = sub(y, mul(obj.axis, dot(y, obj.axis)))
        return unit(sub(y, mul(unit(radial), obj.R)))
    if isinstance(obj, Quadric):
        return unit(quadric_value(obj, p)[1])
    return unit(cross(sub(obj.b, obj.a), sub(obj.c, obj.a)))


def hit(obj, o, d):
    """Nearest t > 0 where the ray meets obj, or None."""
    return next((t for t in crossings(obj, o, d) if t > 0), None)


def nearest(scene, o, d):
    """(t, object) of the nearest hit, or None."""
    hits = [(t, obj) for obj in scene.objects for t in [hit(obj, o, d)] if t is not None]
    return min(hits, key=lambda h: h[0], default=None)


def has_inside(obj):
    """A triangle has none: light passes it unbent."""
    return not isinstance(obj, Triangle)


def nudge(p, n):
    """p moved off its surface along n (double precision self-hit guard)."""
    return add(p, mul(n, NUDGE * (1 + norm(p))))


# ---------------------------------------------------------------- SPEC 4


def pigment_at(pig, p):
    """The pigment's color at point p (SPEC 3)."""
    if isinstance(pig, Solid):
        return pig.color
    if isinstance(pig, Checker):
        k = sum(math.floor(x / pig.side) for x in p)
        return pig.color1 if k % 2 == 0 else pig.color2
    if isinstance(pig, Gradient):
        seg = sub(pig.p1, pig.p0)
        f = min(max(dot(sub(p, pig.p0), seg) / dot(seg, seg), 0.0), 1.0)
        return add(mul(pig.color0, 1 - f), mul(pig.color1, f))
    return texel_lookup(pig, dot(pig.s[:3], p) + pig.s[3], dot(pig.t[:3], p) + pig.t[3])


def texel_lookup(pig, s, t):
    """Bilinear lookup at (s, t), repeating: texel centers at (i + 0.5) / size."""
    def cells(u, size):
        x = (u - math.floor(u)) * size - 0.5
        c = math.floor(x)
        return c % size, (c + 1) % size, x - c
    x0, x1, fx = cells(s, pig.width)
    y0, y1, fy = cells(t, pig.height)
    rows = pig.texels
    top = add(mul(rows[y0][x0], 1 - fx), mul(rows[y0][x1], fx))
    bottom = add(mul(rows[y1][x0], 1 - fx), mul(rows[y1][x1], fx))
    return add(mul(top, 1 - fy), mul(bottom, fy))


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


def transmitted_ray(d, n, ior, p, inside=True):
    """(origin, direction, total) of the transmitted ray at p: bent by Snell's
    law, or along the mirror direction under total internal reflection; a
    surface without an inside lets it through unbent."""
    entering = dot(d, n) < 0
    nf, eta = (n, 1 / ior) if entering else (mul(n, -1), ior)
    if not inside:
        return nudge(p, mul(nf, -1)), d, False
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
        origin, direction, _ = transmitted_ray(d, n, fin.ior, p, has_inside(obj))
        color = add(color, mul(trace(scene, origin, direction, depth + 1), fin.kt))
    return color
