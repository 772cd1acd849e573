// shade.glsl: the Phong sum of SPEC 4: lights, and the shadow rays that
// decide them (traced by trace.comp's trace_step).

// max(0, x)^n with 0^0 = 1 as SPEC's formula reads (GLSL's pow(0, y) is
// undefined).
float phong_power(float x, float n)
{
    if (n == 0.0)
        return 1.0;
    return x > 0.0 ? pow(x, n) : 0.0;
}

// A surface point being shaded: what its shadow rays need.
struct Shading {
    rvec3 p;      // on the surface
    rvec3 nf;     // unit normal facing the viewer
    rvec3 view;   // unit direction toward the viewer
    rvec3 origin; // where shadow rays start: p lifted on the viewer's side
    Start start;  // ... leaving this surface
    Finish fin;
    vec3 pig;
};

// How many point lights shade a point of finish fin: every light, the
// arealight counting as its samples; none for kd = ks = 0 (a pure mirror or
// glass needs no shadow rays).
int light_samples(Finish fin)
{
    if (fin.phong.y == 0.0 && fin.phong.z == 0.0)
        return 0;
    int n = frame.counts.z;
    return HAS_AREA && frame.sampling.y >= 0 ? n - 1 + frame.sampling.z : n;
}

// Whether light sample j is one of the arealight's, which each pixel
// turns its own way (so its shadows differ between neighbours by design).
bool area_sample(int j)
{
    int a = frame.sampling.y;
    return HAS_AREA && a >= 0 && j >= a && j < a + frame.sampling.z;
}

// Light sample j, in light order: a point light as it is, the arealight
// (light frame.sampling.y) as frame.sampling.z points of color Ci / samples
// spread over its sphere, turned by area_shift.
void light_sample(int j, vec2 area_shift, out rvec3 pos, out vec3 color, out vec4 att)
{
    int light = j;
    int k = -1;
    int m = frame.sampling.z;
    if (HAS_AREA) {
        int a = frame.sampling.y;
        if (j >= a && j < a + m) {
            light = a;
            k = j - a;
        } else if (j >= a + m) {
            light = j - m + 1;
        }
    }
    Light l = load_light(light);
    pos = l.pos.xyz;
    color = l.color.rgb;
    att = l.att;
    if (k >= 0) {
        pos += real(frame.area.x) * rvec3(sphere_point(k, m, area_shift));
        color /= float(m);
    }
}

// What light sample j adds at the point if nothing shadows it (`lit`, of
// which `tint` times the pigment is the diffuse part), and the shadow ray
// that decides it: from sh.origin along dir, dist long. False when it
// adds nothing anyway (the light is behind the surface, or at the point).
bool light_ray(Shading sh, int j, vec2 area_shift, out rvec3 dir, out real dist, out vec3 lit,
               out vec3 tint)
{
    rvec3 pos;
    vec3 color;
    vec4 att;
    light_sample(j, area_shift, pos, color, att);
    dir = sh.nf;
    dist = 0.0;
    lit = tint = vec3(0.0);
    rvec3 to_light = pos - sh.p;
    real d = rlength(to_light);
    if (d == 0.0)
        return false;
    rvec3 l = to_light / d;
    float ndotl = float(rdot(sh.nf, l));
    if (ndotl <= 0.0)
        return false;
    rvec3 lo = pos - sh.origin;
    dist = rlength(lo);
    dir = lo / dist;
    float fd = float(d);
    float a = 1.0 / (att.x + att.y * fd + att.z * fd * fd);
    rvec3 r = 2.0 * rdot(sh.nf, l) * sh.nf - l;
    float spec = phong_power(float(rdot(r, sh.view)), sh.fin.phong.w);
    tint = a * color * sh.fin.phong.y * ndotl;
    lit = tint * sh.pig + a * color * sh.fin.phong.z * spec;
    return true;
}
