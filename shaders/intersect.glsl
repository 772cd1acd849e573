// intersect.glsl: rays against the scene's spheres (through the BVH) and
// planes.

const real NO_HIT = real(3.0e38);

struct Hit {
    real t;
    int object; // -1: none
};

// The surface a ray starts on, which rounding must not let it hit again at
// t ~ 0. A ray leaving it outward never meets it again (spheres are convex,
// planes flat); one going into a sphere meets it only at the far root.
struct Start {
    int skip;     // object never hit, or -1
    int far_only; // sphere counted at its far root only, or -1
};

const Start NOWHERE = Start(-1, -1);

Start leaving(int object, bool is_sphere, bool inward)
{
    return is_sphere && inward ? Start(-1, object) : Start(object, -1);
}

// Nearest t > 0 where the ray meets sphere (center c, radius r), or NO_HIT;
// with far_only, the far root alone. The discriminant is formed from the
// ray's closest approach to the center rather than b^2 - c, which cancels
// catastrophically for far-away spheres; the near root comes from c / q
// (no subtraction of nearly equal numbers).
real hit_sphere(rvec3 o, rvec3 d, rvec4 sphere, bool far_only)
{
    rvec3 oc = o - sphere.xyz;
    real r = sphere.w;
    real b = dot(oc, d);
    rvec3 closest = oc - b * d;
    real disc = r * r - dot(closest, closest);
    if (disc < 0.0)
        return NO_HIT;
    real q = -b - (b < 0.0 ? -sqrt(disc) : sqrt(disc));
    real c = dot(oc, oc) - r * r;
    real t0 = q != 0.0 ? c / q : real(0.0);
    real near_t = min(t0, q);
    real far_t = max(t0, q);
    if (near_t > 0.0 && !far_only)
        return near_t;
    return far_t > 0.0 ? far_t : NO_HIT;
}

// t > 0 where the ray meets the plane n.x + dist = 0, or NO_HIT.
real hit_plane(rvec3 o, rvec3 d, rvec4 plane)
{
    real denom = dot(plane.xyz, d);
    if (denom == 0.0)
        return NO_HIT;
    real t = -(dot(plane.xyz, o) + plane.w) / denom;
    return t > 0.0 ? t : NO_HIT;
}

// Distance at which the ray enters the box, if before tmax; else NO_HIT.
real box_entry(vec3 lo, vec3 hi, rvec3 o, rvec3 inv_d, real tmax)
{
    rvec3 t0 = (rvec3(lo) - o) * inv_d;
    rvec3 t1 = (rvec3(hi) - o) * inv_d;
    rvec3 tn = min(t0, t1);
    rvec3 tf = max(t0, t1);
    real enter = max(max(tn.x, tn.y), max(tn.z, real(0.0)));
    real leave = min(min(tf.x, tf.y), min(tf.z, tmax));
    return enter <= leave ? enter : NO_HIT;
}

// 1 / d with zero components replaced by a tiny positive number, so the
// slab test never computes 0 * inf.
rvec3 safe_inverse(rvec3 d)
{
    const real tiny = real(1e-30);
    return real(1.0) / mix(d, rvec3(tiny), lessThan(abs(d), rvec3(tiny)));
}

// Offers spheres [first, first + count) to the hit.
void hit_spheres(int first, int count, rvec3 o, rvec3 d, Start start, inout Hit h)
{
    for (int i = first; i < first + count; ++i) {
        TP2_STEP();
        if (i == start.skip)
            continue;
        real t = hit_sphere(o, d, objects[i].geom, i == start.far_only);
        if (t < h.t)
            h = Hit(t, i);
    }
}

// The nearest object with 0 < t < tmax, or, if any_hit, any one of them,
// for a ray from o along unit d that starts on `start`. Spheres sit in BVH
// order at the start of objects[], planes after them.
Hit trace_scene(rvec3 o, rvec3 d, Start start, real tmax, bool any_hit)
{
    Hit h = Hit(tmax, -1);
    if (HAS_SPHERES && !USE_BVH) { // few spheres: a plain loop is faster
        hit_spheres(0, frame.geometry.x, o, d, start, h);
        if (any_hit && h.object >= 0)
            return h;
    }
    if (HAS_SPHERES && USE_BVH) {
        rvec3 inv_d = safe_inverse(d);
        int stack_node[TP2_BVH_STACK];
        real stack_t[TP2_BVH_STACK];
        int sp = 0;
        int node = box_entry(nodes[0].lo, nodes[0].hi, o, inv_d, h.t) < NO_HIT ? 0 : -1;
        // Each node is visited at most once: the loop is bounded by their count.
        for (int visit = 0; visit < frame.geometry.z && node >= 0; ++visit) {
            TP2_STEP();
            BvhNode n = nodes[node];
            node = -1;
            if (n.count > 0) {
                hit_spheres(n.first, n.count, o, d, start, h);
                if (any_hit && h.object >= 0)
                    return h;
            } else {
                real tl = box_entry(nodes[n.first].lo, nodes[n.first].hi, o, inv_d, h.t);
                real tr = box_entry(nodes[n.first + 1].lo, nodes[n.first + 1].hi, o, inv_d, h.t);
                bool left_first = tl <= tr;
                real t_near = min(tl, tr);
                real t_far = max(tl, tr);
                if (t_near < NO_HIT)
                    node = left_first ? n.first : n.first + 1;
                if (t_far < NO_HIT && sp < TP2_BVH_STACK) {
                    stack_node[sp] = left_first ? n.first + 1 : n.first;
                    stack_t[sp] = t_far;
                    ++sp;
                }
            }
            // Resume at the nearest pending node still closer than the hit.
            for (; node < 0 && sp > 0; --sp) {
                TP2_STEP();
                if (stack_t[sp - 1] < h.t)
                    node = stack_node[sp - 1];
            }
        }
    }
    if (HAS_PLANES) {
        int end = frame.geometry.x + frame.geometry.y;
        for (int i = frame.geometry.x; i < end; ++i) {
            TP2_STEP();
            real t = i == start.skip ? NO_HIT : hit_plane(o, d, objects[i].geom);
            if (t < h.t) {
                h = Hit(t, i);
                if (any_hit)
                    return h;
            }
        }
    }
    return h;
}
