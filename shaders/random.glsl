// random.glsl: deterministic sample positions (SPEC 3: the same command
// gives the same image).

// A 32-bit integer hash (Wellons' lowbias32): decorrelates pixels.
uint hash_u32(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// Two numbers in [0, 1) for this pixel and stream.
vec2 random2(ivec2 pixel, uint stream)
{
    uint h = hash_u32(uint(pixel.x) * 0x9e3779b9u ^ hash_u32(uint(pixel.y) ^ (stream * 0x85ebca6bu)));
    uint h2 = hash_u32(h ^ 0x68e31da4u);
    return vec2(float(h >> 8), float(h2 >> 8)) * (1.0 / 16777216.0);
}

// Sample k of n on the rank-1 lattice (k/n, k g/n mod 1), shifted by `shift`
// modulo 1: every sample alone in its row and in its column of an n x n grid.
vec2 lattice2(int k, int n, int g, vec2 shift)
{
    vec2 p = vec2(float(k), float((k * g) % n)) / float(n);
    return fract(p + shift);
}

// A uniform point on the unit disk from a point of the unit square.
vec2 square_to_disk(vec2 s)
{
    float r = sqrt(s.x);
    float phi = 6.28318530717958647 * s.y;
    return r * vec2(cos(phi), sin(phi));
}

// Point j of n spread evenly over the unit sphere (a Fibonacci lattice),
// rotated by `shift` so different samples see different points.
vec3 sphere_point(int j, int n, vec2 shift)
{
    float z = 1.0 - 2.0 * fract((float(j) + 0.5) / float(n) + shift.x);
    float phi = 6.28318530717958647 * fract(float(j) * 0.61803398874989485 + shift.y);
    float r = sqrt(max(0.0, 1.0 - z * z));
    return vec3(r * cos(phi), r * sin(phi), z);
}
