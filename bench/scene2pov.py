#!/usr/bin/env python3
"""scene2pov.py - convert a tp2 scene file into POV-Ray 3.7 SDL.

Usage:
    python3 bench/scene2pov.py SCENE [W H] [-o OUT.pov] [--tp2 build/tp2]

The scene is read by tp2 itself (tp2 --dump-scene), so it means here
exactly what it means to tp2.

W H is the image size the .pov file is written for (the camera's aspect
ratio depends on it); default: the scene's own size (header variant), else
400 300, exactly as tp2 chooses. Render the result with, e.g.

    povray +IOUT.pov +OOUT.ppm +FP +WW +HH -A -D +WT2 File_Gamma=1.0 \\
           $(sed -n 's|^// povray-options: ||p' OUT.pov)

`File_Gamma=1.0` makes POV-Ray write linear values like tp2 does (SPEC §4:
round(255 c)); without it POV-Ray 3.7 gamma-encodes its output. A line
`// povray-options: ...` in the output names any further options the scene
needs (only `samples N` does: anti-aliasing); bench/bench.py reads it.

The goal is the SPEC.md §4 image, as closely as POV-Ray allows, so that a
timing comparison compares the same work. Every place where POV-Ray cannot
express the model exactly is listed in the comment block written at the top
of each output file (see APPROXIMATIONS below); exact translations:

  camera   The SPEC basis is computed here and given to POV-Ray explicitly:
           location = eye, direction = w, right = u * 2 tan(fov/2) * W/H,
           up = v * 2 tan(fov/2), no look_at. POV-Ray's perspective camera
           shoots direction + x0 right + y0 up with x0 = (i+0.5)/W - 0.5 and
           y0 = 0.5 - (j+0.5)/H (tracepixel.cpp), which is SPEC §4's pixel
           center ray, unnormalised; no cross product is taken, so POV-Ray's
           left-handedness cannot mirror the image (the equivalent look_at
           form would need `right -x*W/H` with sky = up).
  depth    max_trace_level 11: POV-Ray stops a ray whose level (camera ray
           0, +1 per reflection/refraction) is >= 11, SPEC one with k > 10.
  pruning  adc_bailout = tp2's --bailout (default 1/255, the default of
           both programs; --bailout 0: neither drops a ray for low weight).
  gamma    assumed_gamma 1: colours are linear, as in SPEC.
  ambient  ambient_light = light 0's colour; finish ambient ka.
  lights   light_source at each light i >= 1 (point lights are invisible in
           POV-Ray, as in SPEC).
  pigments solid -> rgb; checker -> POV-Ray's 3-D checker (colour 1 where
           floor(x)+floor(y)+floor(z) is even, like SPEC) scaled by s. Checked
           by rendering planes 1e-5 above and below a cube face (y = -1 +-
           1e-5, s = 1) with both programs: same parity, so POV-Ray 3.7 adds
           no visible tolerance before floor() and no translate is needed.
  finish   ambient ka, diffuse kd, phong ks phong_size n (POV-Ray's phong is
           ks (R.V)^n times the light colour, R the mirrored ray, as SPEC),
           reflection kr (constant, no fresnel, not affected by transmit).
  spheres  sphere { c, r }.
  planes   SPEC a x + b y + c z + d = 0 is POV-Ray's plane { <a,b,c>, D } with
           D = -d/|(a,b,c)| (POV-Ray's plane is n.p = D |n|); both take
           (a,b,c) as the outward normal and n.p + d < 0 as the inside.
  box, cylinder, cone (capped), quadric (same coefficient order), triangle,
  mesh (OBJ triangles, fanned), polyhedron (intersection of planes) and
  torus (POV-Ray's y-axis torus, rotated onto the axis by a matrix) are
  exact shape translations.
"""

import argparse
import json
import math
import os
import subprocess
import sys

# ---------------------------------------------------------------------------
# Scenes are read by tp2 itself (tp2 --dump-scene: the grammar lives in one
# place); this turns its JSON into the dictionaries convert() works on.

class SceneError(Exception):
    pass


def _pigment(p):
    kind = p['kind']
    if kind == 'solid':
        return {'type': 'solid', 'c': p['color']}
    if kind == 'checker':
        return {'type': 'checker', 'c1': p['color1'], 'c2': p['color2'], 's': p['side']}
    if kind == 'gradient':
        return {'type': 'gradient', 'p0': p['p0'], 'p1': p['p1'], 'c0': p['color0'],
                'c1': p['color1']}
    return {'type': 'texmap', 'file': os.path.abspath(p['file']), 's': p['s'], 't': p['t']}


def _object(o):
    v = o['numbers']
    d = {'pig': o['pigment'], 'fin': o['finish'], 'type': o['kind']}
    if o['kind'] == 'sphere':
        d['c'], d['r'] = v[0:3], v[3]
    elif o['kind'] == 'plane':
        d['abcd'] = v
    elif o['kind'] == 'polyhedron':
        d['faces'] = [v[k:k + 4] for k in range(0, len(v), 4)]
    elif o['kind'] == 'mesh':
        d['tris'] = [(v[k:k + 3], v[k + 3:k + 6], v[k + 6:k + 9]) for k in range(0, len(v), 9)]
    else:
        d['v'] = v
    return d


def load_scene(tp2, path):
    """The scene at path as tp2 reads it; SceneError with tp2's message if
    tp2 refuses it."""
    r = subprocess.run([tp2, '--dump-scene', path], capture_output=True)
    if r.returncode != 0:
        raise SceneError(r.stderr.decode('utf-8', 'replace').strip())
    j = json.loads(r.stdout)
    sc = {'file': path, 'size': tuple(j['size']) if j['size'] else None,
          'eye': j['eye'], 'center': j['center'], 'up': j['up'], 'fov': j['fov'],
          'lights': [{'pos': l['pos'], 'color': l['color'], 'att': l['att']}
                     for l in j['lights']],
          'pigments': [_pigment(p) for p in j['pigments']],
          'finishes': j['finishes'],
          'objects': [_object(o) for o in j['objects']],
          'directives': {}}
    d = sc['directives']
    if j['samples'] is not None:
        d['samples'] = j['samples']
    if j['lens'] is not None:
        d['lens'] = j['lens']
    if j['fog'] is not None:
        d['fog'] = j['fog']['color'] + [j['fog']['density']]
    if j['arealight'] is not None:
        a = j['arealight']
        d['arealight'] = (a['light'], a['radius'], a['samples'])
    return sc


# ---------------------------------------------------------------------------
# Vector helpers and number formatting.

def sub(a, b): return [a[i] - b[i] for i in range(3)]
def add(a, b): return [a[i] + b[i] for i in range(3)]
def mul(a, s): return [x * s for x in a]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))
def norm(a): return math.sqrt(dot(a, a))
def unit(a): return mul(a, 1.0 / norm(a))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0]]


def f(x):
    """A float in POV-Ray syntax: shortest repr that round-trips."""
    s = repr(float(x))
    if s in ('-0.0', '0.0'):
        return '0'
    if s.endswith('.0'):
        s = s[:-2]
    return s


def vec(v):
    return '<%s>' % ', '.join(f(x) for x in v)


# ---------------------------------------------------------------------------
# Light attenuation: SPEC 1/(a + b d + c d^2); POV-Ray: 2/(1 + (d/fd)^p).

def _att_spec(a, b, c, d):
    return 1.0 / (a + b * d + c * d * d)


def _att_pov(k, fd, p, d):
    return k * 2.0 / (1.0 + (d / fd) ** p)


def _max_rel_err(a, b, c, k, fd, p, ds):
    return max(abs(_att_pov(k, fd, p, d) / _att_spec(a, b, c, d) - 1.0)
               for d in ds)


def fit_attenuation(a, b, c, dmin, dmax):
    """(colour scale k, fade_distance or None, fade_power, note).

    Exact when at most one of b, c is non-zero and a > 0; with a == 0 the
    fade distance is tiny (error (fd/d)^p); b > 0 and c > 0 together are
    fitted over [dmin, dmax] (the distances from the light to the scene's
    objects), minimising the largest relative error."""
    if b == 0 and c == 0:
        if a == 0:
            return 1.0, None, None, 'no attenuation (a=b=c=0): exact'
        return 1.0 / a, None, None, 'constant 1/a: exact (colour scaled)'
    ds = [dmin * (dmax / dmin) ** (i / 63.0) for i in range(64)]
    if (b == 0) != (c == 0):
        p = 1.0 if c == 0 else 2.0
        coef = b if c == 0 else c
        if a > 0:
            fd = (a / coef) ** (1.0 / p)
            return 1.0 / (2.0 * a), fd, p, (
                '1/(a+%sd%s) = (1/a)/(1+(d/fd)^%d): exact' %
                ('b' if p == 1 else 'c', '' if p == 1 else '^2', p))
        fd = max(1e-4 * dmin, 1e-6)
        k = 1.0 / (2.0 * coef * fd ** p)
        err = _max_rel_err(a, b, c, k, fd, p, ds)
        return k, fd, p, ('1/(%sd%s) ~ k*2/(1+(d/fd)^%d) with tiny fd: '
                          'max relative error %.2g for d in [%.3g, %.3g]' %
                          ('b' if p == 1 else 'c', '' if p == 1 else '^2',
                           p, err, dmin, dmax, ))
    best = None
    for pi in range(0, 101):
        p = 1.0 + pi / 100.0
        for fi in range(0, 241):
            fd = dmin * 1e-3 * (dmax * 1e3 / (dmin * 1e-3)) ** (fi / 240.0)
            r = [math.log(_att_spec(a, b, c, d) / _att_pov(1.0, fd, p, d))
                 for d in ds]
            spread = (max(r) - min(r)) / 2.0
            if best is None or spread < best[0]:
                best = (spread, p, fd, math.exp((max(r) + min(r)) / 2.0))
    spread, p, fd, k = best
    err = _max_rel_err(a, b, c, k, fd, p, ds)
    return k, fd, p, ('1/(a+bd+cd^2) fitted as k*2/(1+(d/fd)^p): max '
                      'relative error %.2g for d in [%.3g, %.3g]' %
                      (err, dmin, dmax))


def _light_range(sc, pos):
    """Distances from pos over which the scene's objects lie (for fits)."""
    near, far = [], []
    eye = sc['eye']
    for o in sc['objects']:
        if o['type'] == 'sphere':
            dc = norm(sub(o['c'], pos))
            near.append(max(dc - o['r'], 0.0))
            far.append(dc + o['r'])
        elif o['type'] == 'plane':
            n = o['abcd'][:3]
            near.append(abs(dot(n, pos) + o['abcd'][3]) / norm(n))
            far.append(4.0 * norm(sub(eye, pos)) + near[-1])
        else:
            far.append(4.0 * norm(sub(eye, pos)))
    far.append(norm(sub(eye, pos)))
    scale = max(far) if far else 1.0
    dmin = max(min(near) if near else 0.0, 1e-3 * scale, 1e-9)
    dmax = max(max(far), 2.0 * dmin)
    return dmin, dmax


# ---------------------------------------------------------------------------
# Converter.

def rotation_y_to(axis):
    """3x3 rows of a rotation taking +y onto unit(axis) (for POV matrix)."""
    a = unit(axis)
    y = [0.0, 1.0, 0.0]
    c = dot(y, a)
    if c > 1 - 1e-12:
        return [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    if c < -1 + 1e-12:
        return [[1, 0, 0], [0, -1, 0], [0, 0, -1]]
    k = unit(cross(y, a))
    s = math.sqrt(max(0.0, 1 - c * c))
    # Rodrigues: R = I cos + (1-cos) k k^T + sin [k]x ; columns map basis.
    K = [[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]]
    R = [[(1 if i == j else 0) * c + (1 - c) * k[i] * k[j] + s * K[i][j]
          for j in range(3)] for i in range(3)]
    return R


def pov_matrix(R, t):
    """POV-Ray matrix for p' = R p + t (POV uses row vectors: p' = p M)."""
    vals = [R[0][0], R[1][0], R[2][0], R[0][1], R[1][1], R[2][1],
            R[0][2], R[1][2], R[2][2], t[0], t[1], t[2]]
    return 'matrix <%s>' % ', '.join(f(x) for x in vals)


def bmp_to_ppm(src, dst):
    """Copies a 24-bit BMP (bottom-up or top-down) to a binary PPM: POV-Ray
    3.7 cannot read top-down BMPs (negative height), which SPEC allows."""
    import struct
    with open(src, 'rb') as fh:
        data = fh.read()
    off = struct.unpack_from('<I', data, 10)[0]
    w, h, _, bpp = struct.unpack_from('<iiHH', data, 18)
    if bpp != 24:
        raise ValueError('%s: only 24-bit BMP is supported' % src)
    rows = abs(h)
    stride = (3 * w + 3) & ~3
    out = bytearray()
    for r in range(rows):
        src_row = r if h < 0 else rows - 1 - r      # r counts from the top
        line = data[off + src_row * stride: off + src_row * stride + 3 * w]
        for i in range(0, 3 * w, 3):
            out += bytes((line[i + 2], line[i + 1], line[i]))
    tmp = dst + '.tmp'
    with open(tmp, 'wb') as fh:
        fh.write(b'P6\n%d %d\n255\n' % (w, rows))
        fh.write(bytes(out))
    os.replace(tmp, dst)


def pigment_sdl(p, kt, image_dir='.'):
    """POV pigment for SPEC pigment p with transmit kt."""
    def col(c):
        if kt > 0:
            return 'rgbt <%s, %s, %s, %s>' % (f(c[0]), f(c[1]), f(c[2]), f(kt))
        return 'rgb <%s, %s, %s>' % (f(c[0]), f(c[1]), f(c[2]))
    t = p['type']
    if t == 'solid':
        return 'pigment { %s }' % col(p['c'])
    if t == 'checker':
        return ('pigment { checker color %s color %s '
                'scale %s }' % (col(p['c1']), col(p['c2']), f(p['s'])))
    if t == 'gradient':
        d = sub(p['p1'], p['p0'])
        L2 = dot(d, d)
        if L2 == 0:
            return 'pigment { %s }' % col(p['c0'])
        fn = ('min(1, max(0, ((x - %s)*%s + (y - %s)*%s + (z - %s)*%s)))' %
              (f(p['p0'][0]), f(d[0] / L2), f(p['p0'][1]), f(d[1] / L2),
               f(p['p0'][2]), f(d[2] / L2)))
        return ('pigment { function { %s } color_map { [0 %s] [1 %s] } }' %
                (fn, col(p['c0']), col(p['c1'])))
    if t == 'texmap':
        # Pattern space (s, 1 - t, z'): POV's image_map covers x, y in
        # [0,1] with the image's top row at y = 1.
        s, tt = p['s'], p['t']
        # pattern = M world + off. POV-Ray needs M invertible; a row that is
        # zero or depends on the rows before it (e.g. t constant, as in the
        # corpus's test-texmap.txt) gets 1e-9 times a unit vector orthogonal
        # to them: a texture-coordinate change of 1e-9 per world unit.
        M = []
        for row in (list(s[:3]), [-x for x in tt[:3]], [0.0, 0.0, 0.0]):
            basis = []
            for r in M:
                q = list(r)
                for b in basis:
                    q = sub(q, mul(b, dot(q, b)))
                if norm(q) > 0:
                    basis.append(unit(q))
            q = list(row)
            for b in basis:
                q = sub(q, mul(b, dot(q, b)))
            if norm(q) <= 1e-12 * max(norm(row), 1e-300):
                for cand in ([1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]):
                    e = list(cand)
                    for b in basis:
                        e = sub(e, mul(b, dot(e, b)))
                    if norm(e) > 0.5:
                        row = add(row, mul(unit(e), 1e-9))
                        break
            M.append(row)
        off = [s[3], 1.0 - tt[3], 0.0]
        det = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
               - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
               + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]))
        if abs(det) < 1e-300:
            return 'pigment { rgb 0 }'
        inv = [[(M[(j + 1) % 3][(i + 1) % 3] * M[(j + 2) % 3][(i + 2) % 3]
                 - M[(j + 1) % 3][(i + 2) % 3] * M[(j + 2) % 3][(i + 1) % 3])
                / det for j in range(3)] for i in range(3)]
        tr = [-sum(inv[i][j] * off[j] for j in range(3)) for i in range(3)]
        path = p['file']
        ext = os.path.splitext(path)[1].lower().lstrip('.')
        if ext == 'bmp':
            ppm = os.path.join(image_dir, os.path.splitext(
                os.path.basename(path))[0] + '.scene2pov.ppm')
            bmp_to_ppm(path, ppm)
            path, ext = os.path.abspath(ppm), 'ppm'
        kind = {'png': 'png', 'ppm': 'ppm'}.get(ext, ext)
        tm = (' transmit all %s' % f(kt)) if kt > 0 else ''
        return ('pigment { image_map { %s "%s" interpolate 2%s } %s }' %
                (kind, path, tm, pov_matrix(inv, tr)))
    raise ValueError(t)


def convert(sc, width, height, source_name, image_dir='.', bailout=1 / 255):
    out = []
    notes = []           # deliberate approximations, written at the top
    w = unit(sub(sc['center'], sc['eye']))
    u = unit(cross(w, sc['up']))
    v = cross(u, w)
    h = 2.0 * math.tan(math.radians(sc['fov']) / 2.0)
    right = mul(u, h * width / height)
    upv = mul(v, h)
    d = sc['directives']
    options = []

    notes.append('Depth limit: a ray cut at level 11 returns black in '
                 'POV-Ray (trace.cpp), gray 0.5 in SPEC.')
    notes.append('Lights: a light is used when N.L >= EPSILON (tiny) in '
                  'POV-Ray, N.L > 0 in SPEC; shadow rays ignore hits closer '
                  'than 1e-3 to either end (SHADOW_TOLERANCE) and POV-Ray '
                  'skips intersections closer than its MIN_ISECT_DEPTH; tp2 '
                  'uses its own epsilons.')
    notes.append('Phong: POV-Ray drops a highlight term when phong_size >= 60 '
                 'and (R.V) <= 0.0008 (below 0.0008^60 ~ 1e-186: invisible).')
    notes.append('Checker: a surface lying exactly on a cube face gets its '
                 'parity from rounding in either program (hit points are '
                 'not exact); both agreed on the corpus scenes with such '
                 'planes.')
    notes.append('Output: POV-Ray clips each channel to [0,1] and quantises '
                 'it to 8 bits itself; SPEC: round(255 c). Differences of '
                 '1/255 are expected.')

    if any(F['n'] == 0 and F['ks'] != 0 for F in sc['finishes']):
        notes.append('Phong exponent 0: SPEC\'s max(0, R.V)^0 is 1 even where '
                     'R.V <= 0 (tp2 takes 0^0 = 1); POV-Ray adds no highlight '
                     'there.')

    # Transmission: SPEC local + kt * T; POV-Ray (1-kt) (ambient+diffuse)
    # + phong + kt * T with transmit kt. ambient and diffuse are divided by
    # (1 - kt) to compensate.
    has_kt = any(fi['kt'] > 0 for fi in sc['finishes'])
    if has_kt:
        notes.append('Transmission kt: POV-Ray scales the ambient and diffuse '
                     'terms of a transmit-kt surface by (1 - kt); this file '
                     'divides ka and kd by (1 - kt) so they come out as in '
                     'SPEC (exact). kt >= 1 cannot be expressed: it is '
                     'clamped to 0.999.')
        notes.append('Transmission shadows: in POV-Ray light passes through '
                     'transparent objects (scaled by transmit), in SPEC any '
                     'object blocks it. Each transparent object is therefore '
                     'no_shadow, and an opaque copy marked no_image '
                     'no_reflection (invisible to every camera-derived ray, '
                     'seen only by shadow rays) casts its shadow. POV-Ray '
                     'tests these copies too: a little extra work for it.')
        notes.append('Total internal reflection: POV-Ray adds the internally '
                     'reflected ray with weight 1 and drops the surface\'s own '
                     'kr reflection at that point; SPEC weights it by kt and '
                     'keeps kr.')
        notes.append('Refraction with ior 1: POV-Ray continues the ray '
                     'without counting a level; SPEC counts it (matters only '
                     'at the depth limit). POV-Ray decides entering/leaving '
                     'from the list of objects the ray is inside; SPEC from '
                     'the sign of dir.N: the same for separate closed '
                     'objects, different for overlapping transparent ones.')

    # Lights.
    light_lines = []
    area = d.get('arealight')
    for i, L in enumerate(sc['lights'][1:], start=1):
        a, b, c = L['att']
        dmin, dmax = _light_range(sc, L['pos'])
        k, fd, p, why = fit_attenuation(a, b, c, dmin, dmax)
        col = mul(L['color'], k)
        s = 'light_source { %s color rgb %s' % (vec(L['pos']), vec(col))
        if fd is not None:
            s += ' fade_distance %s fade_power %s' % (f(fd), f(p))
        if area and area[0] == i:
            n = max(2, int(round(math.sqrt(area[2]))))
            r = area[1]
            s += ('\n    area_light <%s, 0, 0>, <0, 0, %s>, %d, %d circular '
                  'orient area_illumination on jitter' %
                  (f(2 * r), f(2 * r), n, n))
            notes.append('arealight %d: SPEC samples a uniformly bright '
                         'sphere of radius %s with %d points; POV-Ray gets a '
                         'circular %dx%d jittered area_light of that radius '
                         'oriented toward each hit point (the sphere\'s '
                         'silhouette), area_illumination on.' %
                         (i, f(r), area[2], n, n))
        s += ' }  // attenuation (%s, %s, %s): %s' % (f(a), f(b), f(c), why)
        if 'exact' not in why:
            notes.append('Light %d attenuation: %s.' % (i, why))
        light_lines.append(s)
    # Directives.
    if 'samples' in d:
        n = d['samples']
        r = max(1, int(round(math.sqrt(n))))
        options += ['+A0.0', '+AM1', '+R%d' % r]
        notes.append('samples %d: SPEC averages %d stratified rays per pixel; '
                     'POV-Ray renders with +A0.0 +AM1 +R%d (adaptive '
                     'supersampling with threshold 0, (%d x %d)-ray grids, '
                     'pixel corners shared): approximate.' % (n, n, r, r, r))
    cam_extra = ''
    if 'lens' in d:
        ap, fdist = d['lens']
        fp = add(sc['eye'], mul(w, fdist))
        bs = max(d.get('samples', 1), 4)
        cam_extra = ('\n  aperture %s focal_point %s blur_samples %d' %
                     (f(2 * ap), vec(fp), bs))
        notes.append('lens: POV-Ray focal blur (aperture %s = lens diameter, '
                     'focal_point on the axis at the focal distance, %d '
                     'random samples) instead of SPEC\'s stratified thin '
                     'lens: approximate.' % (f(2 * ap), bs))
    fog_sdl = ''
    if 'fog' in d:
        r, g, b, dens = d['fog']
        if dens > 0:
            fog_sdl = ('fog { fog_type 1 distance %s color rgb %s }\n' %
                       (f(1.0 / dens), vec([r, g, b])))
            notes.append('fog: POV-Ray constant fog with distance 1/density '
                         '(same exp(-density t) law); a ray cut by the depth '
                         'limit returns fogged black there, plain gray in '
                         'SPEC.')

    # Textures per (pigment, finish) pair actually used.
    used = []
    for o in sc['objects']:
        key = (o['pig'], o['fin'])
        if key not in used:
            used.append(key)
    tex_lines = []
    for (pi, fi) in used:
        F = sc['finishes'][fi]
        kt = min(F['kt'], 0.999) if F['kt'] > 0 else 0.0
        scale = 1.0 / (1.0 - kt)
        fin = 'finish { ambient %s diffuse %s' % (f(F['ka'] * scale),
                                                   f(F['kd'] * scale))
        if F['ks'] != 0:
            fin += ' phong %s phong_size %s' % (f(F['ks']), f(F['n']))
        if F['kr'] != 0:
            fin += ' reflection %s' % f(F['kr'])
        fin += ' }'
        tex_lines.append('#declare T_%d_%d = texture { %s %s }' %
                         (pi, fi, pigment_sdl(sc['pigments'][pi], kt, image_dir), fin))
        if sc['pigments'][pi]['type'] == 'texmap':
            notes.append('texmap pigment %d: POV-Ray image_map with bilinear '
                         'interpolation (interpolate 2) under an affine '
                         'matrix; its texel centres and edge handling are '
                         'POV-Ray\'s, close to but not exactly SPEC\'s. A BMP '
                         'is copied to a PPM beside this file (POV-Ray 3.7 '
                         'cannot read top-down BMPs).' % pi)
    for fi, F in enumerate(sc['finishes']):
        if F['kt'] > 0:
            tex_lines.append('#declare I_%d = interior { ior %s }' %
                             (fi, f(F['ior'] if F['ior'] > 0 else 1.0)))

    # Objects.
    obj_lines = []
    tri_kt = False
    for o in sc['objects']:
        F = sc['finishes'][o['fin']]
        t = o['type']
        if t == 'sphere':
            shape = 'sphere { %s, %s' % (vec(o['c']), f(o['r']))
        elif t == 'plane':
            n = o['abcd'][:3]
            shape = 'plane { %s, %s' % (vec(n), f(-o['abcd'][3] / norm(n)))
        elif t == 'polyhedron':
            shape = 'intersection { %s' % ' '.join(
                'plane { %s, %s }' % (vec(fc[:3]), f(-fc[3] / norm(fc[:3])))
                for fc in o['faces'])
        elif t == 'box':
            vv = o['v']
            shape = 'box { %s, %s' % (vec(vv[0:3]), vec(vv[3:6]))
        elif t == 'cylinder':
            vv = o['v']
            shape = 'cylinder { %s, %s, %s' % (vec(vv[0:3]), vec(vv[3:6]),
                                               f(vv[6]))
        elif t == 'cone':
            vv = o['v']
            shape = 'cone { %s, %s, %s, %s' % (vec(vv[0:3]), f(vv[3]),
                                               vec(vv[4:7]), f(vv[7]))
        elif t == 'torus':
            vv = o['v']
            shape = 'torus { %s, %s %s' % (
                f(vv[6]), f(vv[7]), pov_matrix(rotation_y_to(vv[3:6]), vv[0:3]))
        elif t == 'quadric':
            vv = o['v']
            shape = 'quadric { %s, %s, %s, %s' % (
                vec(vv[0:3]), vec(vv[3:6]), vec(vv[6:9]), f(vv[9]))
        elif t == 'triangle':
            vv = o['v']
            shape = 'triangle { %s, %s, %s' % (vec(vv[0:3]), vec(vv[3:6]),
                                               vec(vv[6:9]))
        elif t == 'mesh':
            tris = o['tris']
            shape = 'mesh { ' + ' '.join(
                'triangle { %s, %s, %s }' % (vec(a), vec(b), vec(c))
                for a, b, c in tris)
        else:
            raise ValueError(t)
        tex = 'texture { T_%d_%d }' % (o['pig'], o['fin'])
        if F['kt'] > 0:
            if t in ('triangle', 'mesh'):
                tri_kt = True
                interior = 'interior { ior 1 }'
            else:
                interior = 'interior { I_%d }' % o['fin']
            obj_lines.append('%s %s %s no_shadow }' % (shape, tex, interior))
            obj_lines.append('%s pigment { rgb 0 } no_image no_reflection }'
                             % shape)
        else:
            obj_lines.append('%s %s }' % (shape, tex))
    if tri_kt:
        notes.append('Transparent triangles/meshes get interior { ior 1 } so '
                     'the ray continues unbent, as in SPEC.')

    c0 = sc['lights'][0]['color'] if sc['lights'] else [0.0, 0.0, 0.0]
    hdr = ['// Generated by bench/scene2pov.py from %s for a %dx%d image.' %
           (source_name, width, height),
           '// Target: the image of tp2 SPEC.md section 4, in POV-Ray 3.7.',
           ('// Render with: povray +I<this> +O<out>.ppm +FP +W%d +H%d %s -D '
            'File_Gamma=1.0' % (width, height, ' '.join(options) or '-A')),
           '//',
           '// Deliberate approximations (everything else is exact, see the '
           'header of bench/scene2pov.py):']
    for n in notes:
        words = n.split()
        line = '//  -'
        for wd in words:
            if len(line) + 1 + len(wd) > 78:
                hdr.append(line)
                line = '//   '
            line += ' ' + wd
        hdr.append(line)
    hdr.append('// povray-options: %s' % ' '.join(options))
    out += hdr
    out.append('#version 3.7;')
    out.append('global_settings {')
    out.append('  assumed_gamma 1.0')
    out.append('  max_trace_level 11  // rays of depth 0..10 are traced, '
               'as SPEC k <= 10')
    out.append('  adc_bailout %s  // as tp2 --bailout' % f(bailout))
    out.append('  ambient_light rgb %s  // light 0' % vec(c0))
    out.append('}')
    out.append('background { color rgb 0.5 }')
    out.append('// SPEC camera basis, explicit (no look_at): eye %s, center '
               '%s, up %s, vertical fov %s deg' %
               (vec(sc['eye']), vec(sc['center']), vec(sc['up']),
                f(sc['fov'])))
    out.append('camera {\n  perspective\n  location %s\n  direction %s\n'
               '  right %s\n  up %s%s\n}' %
               (vec(sc['eye']), vec(w), vec(right), vec(upv), cam_extra))
    if fog_sdl:
        out.append(fog_sdl.rstrip())
    out += light_lines
    out += tex_lines
    out += obj_lines
    return '\n'.join(out) + '\n', options


def main(argv=None):
    ap = argparse.ArgumentParser(
        description='Convert a tp2 scene file to POV-Ray 3.7 SDL.')
    ap.add_argument('scene')
    ap.add_argument('size', nargs='*', type=int, metavar='W H',
                    help='image size (default: the scene\'s, else 400 300)')
    ap.add_argument('-o', '--output', help='output .pov (default: stdout)')
    ap.add_argument('--bailout', type=float, default=1 / 255,
                    help="adc_bailout, as tp2's --bailout (default 1/255)")
    ap.add_argument('--tp2', default=os.path.join(os.path.dirname(os.path.dirname(
                        os.path.abspath(__file__))), 'build', 'tp2'),
                    help='the tp2 that reads the scene (default build/tp2)')
    args = ap.parse_args(argv)
    if len(args.size) not in (0, 2):
        ap.error('give both W and H or neither')
    try:
        sc = load_scene(args.tp2, args.scene)
    except SceneError as e:
        print(str(e), file=sys.stderr)
        return 1
    except OSError as e:
        print('scene2pov: %s' % e, file=sys.stderr)
        return 1
    if args.size:
        W, H = args.size
    elif sc['size']:
        W, H = sc['size']
    else:
        W, H = 400, 300
    if W < 1 or H < 1:
        ap.error('W and H must be positive')
    image_dir = os.path.dirname(os.path.abspath(args.output)) if args.output \
        else os.getcwd()
    try:
        sdl, _ = convert(sc, W, H, os.path.basename(args.scene), image_dir,
                         args.bailout)
    except (OSError, ValueError) as e:
        print('scene2pov: %s' % e, file=sys.stderr)
        return 1
    if args.output:
        tmp = args.output + '.tmp'
        with open(tmp, 'w') as fh:
            fh.write(sdl)
        os.replace(tmp, args.output)
    else:
        sys.stdout.write(sdl)
    return 0


if __name__ == '__main__':
    sys.exit(main())
