// soft_double.glsl: IEEE 754 binary64 arithmetic from 32-bit integers, for
// devices without shaderFloat64 (host/gpu/spirv_soft_double.h puts a call
// to these in place of each double operation of the double build).
//
// A double is its bit pattern as uvec2: x the low 32 bits, y the high 32
// (GLSL's packDouble2x32). Every operation rounds to nearest, ties to even,
// subnormals included, as IEEE 754 asks and as lavapipe's doubles do, so a
// retrace through these makes the same decisions bit for bit as native
// double. Only 32-bit integer operations are used (no shaderInt64: many of
// those devices lack it too). NaN results are one quiet NaN; no
// instruction tests a NaN's payload.
//
// Inside, a significand being rounded is a 64-bit integer (uvec2, same
// halves) with its leading bit at 62 and 10 bits below the last place; an
// exponent e passed with it is the biased exponent less one, so that
// packing adds the leading bit into the exponent field (and a carry of
// rounding, past it).

const uvec2 SD_NAN = uvec2(0u, 0x7FF80000u);
const uint SD_SIGN = 0x80000000u;
const uint SD_IMPLICIT = 0x00100000u; // bit 52, in the high word

// 64-bit integers as uvec2.
uvec2 u64_add(uvec2 a, uvec2 b)
{
    uint carry;
    uint lo = uaddCarry(a.x, b.x, carry);
    return uvec2(lo, a.y + b.y + carry);
}

uvec2 u64_sub(uvec2 a, uvec2 b)
{
    uint borrow;
    uint lo = usubBorrow(a.x, b.x, borrow);
    return uvec2(lo, a.y - b.y - borrow);
}

bool u64_lt(uvec2 a, uvec2 b) { return a.y < b.y || (a.y == b.y && a.x < b.x); }

// a << n, n in [0, 63]. (GLSL leaves shifts by 32 or more undefined.)
uvec2 u64_shl(uvec2 a, uint n)
{
    if (n >= 32u)
        return uvec2(0u, a.x << (n - 32u));
    if (n == 0u)
        return a;
    return uvec2(a.x << n, (a.y << n) | (a.x >> (32u - n)));
}

// a >> n, n in [0, 63].
uvec2 u64_shr(uvec2 a, uint n)
{
    if (n >= 32u)
        return uvec2(a.y >> (n - 32u), 0u);
    if (n == 0u)
        return a;
    return uvec2((a.x >> n) | (a.y << (32u - n)), a.y >> n);
}

// a >> n for any n, with every bit shifted out ORed into bit 0 ("jamming"):
// rounding then still sees whether anything below the last place was lost.
uvec2 u64_shr_jam(uvec2 a, uint n)
{
    if (n >= 64u)
        return uvec2(a != uvec2(0u) ? 1u : 0u, 0u);
    uvec2 kept = u64_shr(a, n);
    bool lost = u64_shl(kept, n) != a;
    return uvec2(kept.x | (lost ? 1u : 0u), kept.y);
}

// Leading zeros of a (64 when a is 0).
uint u64_clz(uvec2 a)
{
    if (a.y != 0u)
        return uint(31 - findMSB(a.y));
    return a.x != 0u ? uint(63 - findMSB(a.x)) : 64u;
}

// The high 64 bits of the 128-bit product a * b, with the low 64 jammed
// into bit 0.
uvec2 u64_mul_high_jam(uvec2 a, uvec2 b)
{
    uint h00, l00, h01, l01, h10, l10, h11, l11, c;
    umulExtended(a.x, b.x, h00, l00);
    umulExtended(a.x, b.y, h01, l01);
    umulExtended(a.y, b.x, h10, l10);
    umulExtended(a.y, b.y, h11, l11);
    uint w1 = uaddCarry(h00, l01, c);
    uint c1 = c;
    w1 = uaddCarry(w1, l10, c);
    c1 += c;
    uint w2 = uaddCarry(h01, h10, c);
    uint c2 = c;
    w2 = uaddCarry(w2, l11, c);
    c2 += c;
    w2 = uaddCarry(w2, c1, c);
    c2 += c;
    return uvec2(w2 | ((l00 | w1) != 0u ? 1u : 0u), h11 + c2);
}

// Fields of a double.
uint sd_sign_of(uvec2 a) { return a.y & SD_SIGN; }
int sd_exponent_of(uvec2 a) { return int((a.y >> 20) & 0x7FFu); }
uvec2 sd_fraction_of(uvec2 a) { return uvec2(a.x, a.y & 0xFFFFFu); }
bool sd_is_nan(uvec2 a) { return sd_exponent_of(a) == 0x7FF && sd_fraction_of(a) != uvec2(0u); }
bool sd_is_zero(uvec2 a) { return (a.y & ~SD_SIGN) == 0u && a.x == 0u; }
uvec2 sd_infinity(uint sign) { return uvec2(0u, sign | 0x7FF00000u); }

// Rounds sign * m * 2^(e + 1 - 1023 - 62) to a double (see the top).
uvec2 sd_round_pack(uint sign, int e, uvec2 m)
{
    if (e < 0) { // below the normal range: a subnormal's fixed exponent
        m = u64_shr_jam(m, uint(-e));
        e = 0;
    }
    uint below = m.x & 0x3FFu;
    m = u64_add(m, uvec2(0x200u, 0u));
    if (e > 0x7FD || (e == 0x7FD && (m.y & SD_SIGN) != 0u))
        return sd_infinity(sign);
    m = u64_shr(m, 10u);
    if (below == 0x200u) // a tie: to even
        m.x &= ~1u;
    if (m == uvec2(0u))
        e = 0;
    uvec2 bits = u64_add(uvec2(0u, uint(e) << 20), m);
    return uvec2(bits.x, bits.y | sign);
}

// The significand of a finite nonzero double with its leading bit at 52,
// and the biased exponent that goes with it (below 1 for a subnormal).
uvec2 sd_normalized(uvec2 a, out int e)
{
    e = sd_exponent_of(a);
    uvec2 m = sd_fraction_of(a);
    if (e != 0)
        return uvec2(m.x, m.y | SD_IMPLICIT);
    uint shift = u64_clz(m) - 11u;
    e = 1 - int(shift);
    return u64_shl(m, shift);
}

uvec2 sd_neg(uvec2 a) { return uvec2(a.x, a.y ^ SD_SIGN); }
uvec2 sd_abs(uvec2 a) { return uvec2(a.x, a.y & ~SD_SIGN); }

uvec2 sd_add(uvec2 a, uvec2 b)
{
    int ea = sd_exponent_of(a), eb = sd_exponent_of(b);
    if (ea == 0x7FF || eb == 0x7FF) {
        if (sd_is_nan(a) || sd_is_nan(b) || (ea == eb && sd_sign_of(a) != sd_sign_of(b)))
            return SD_NAN;
        return ea == 0x7FF ? a : b;
    }
    uvec2 ma = u64_shl(sd_fraction_of(a) | uvec2(0u, ea != 0 ? SD_IMPLICIT : 0u), 10u);
    uvec2 mb = u64_shl(sd_fraction_of(b) | uvec2(0u, eb != 0 ? SD_IMPLICIT : 0u), 10u);
    ea = max(ea, 1); // a subnormal's exponent
    eb = max(eb, 1);
    uint sign = sd_sign_of(a);
    bool same = sign == sd_sign_of(b);
    if (eb > ea || (eb == ea && u64_lt(ma, mb))) { // a the larger in magnitude
        sign = sd_sign_of(b);
        uvec2 m = ma;
        ma = mb;
        mb = m;
        int e = ea;
        ea = eb;
        eb = e;
    }
    mb = u64_shr_jam(mb, uint(ea - eb));
    int e = ea - 1;
    if (same) {
        uvec2 m = u64_add(ma, mb);
        if ((m.y & SD_SIGN) != 0u) {
            m = u64_shr_jam(m, 1u);
            e += 1;
        }
        return sd_round_pack(sign, e, m);
    }
    uvec2 m = u64_sub(ma, mb);
    if (m == uvec2(0u))
        return uvec2(0u); // x - x is +0
    uint shift = u64_clz(m) - 1u; // exact: a large shift means no bits were jammed
    return sd_round_pack(sign, e - int(shift), u64_shl(m, shift));
}

uvec2 sd_sub(uvec2 a, uvec2 b) { return sd_add(a, sd_neg(b)); }

uvec2 sd_mul(uvec2 a, uvec2 b)
{
    uint sign = sd_sign_of(a) ^ sd_sign_of(b);
    if (sd_is_nan(a) || sd_is_nan(b))
        return SD_NAN;
    if (sd_exponent_of(a) == 0x7FF || sd_exponent_of(b) == 0x7FF)
        return sd_is_zero(a) || sd_is_zero(b) ? SD_NAN : sd_infinity(sign);
    if (sd_is_zero(a) || sd_is_zero(b))
        return uvec2(0u, sign);
    int ea, eb;
    uvec2 ma = u64_shl(sd_normalized(a, ea), 10u);
    uvec2 mb = u64_shl(sd_normalized(b, eb), 11u);
    int e = ea + eb - 0x3FF;
    uvec2 m = u64_mul_high_jam(ma, mb); // leading bit at 61 or 62
    if ((m.y & 0x40000000u) == 0u) {
        m = u64_shl(m, 1u);
        e -= 1;
    }
    return sd_round_pack(sign, e, m);
}

uvec2 sd_div(uvec2 a, uvec2 b)
{
    uint sign = sd_sign_of(a) ^ sd_sign_of(b);
    if (sd_is_nan(a) || sd_is_nan(b))
        return SD_NAN;
    bool a_inf = sd_exponent_of(a) == 0x7FF, b_inf = sd_exponent_of(b) == 0x7FF;
    if (a_inf)
        return b_inf ? SD_NAN : sd_infinity(sign);
    if (b_inf)
        return uvec2(0u, sign);
    if (sd_is_zero(b))
        return sd_is_zero(a) ? SD_NAN : sd_infinity(sign);
    if (sd_is_zero(a))
        return uvec2(0u, sign);
    int ea, eb;
    uvec2 ma = sd_normalized(a, ea), mb = sd_normalized(b, eb);
    int e = ea - eb + 0x3FE;
    if (u64_lt(ma, mb)) {
        ma = u64_shl(ma, 1u);
        e -= 1;
    }
    // Long division, one bit of quotient a step: 55 bits, the last place
    // and two below it; the remainder says whether more would follow.
    uvec2 q = uvec2(0u), r = ma;
    for (int i = 0; i < 55; ++i) {
        q = u64_shl(q, 1u);
        if (!u64_lt(r, mb)) {
            r = u64_sub(r, mb);
            q.x |= 1u;
        }
        r = u64_shl(r, 1u);
    }
    uvec2 m = u64_shl(q, 8u);
    m.x |= r != uvec2(0u) ? 1u : 0u;
    return sd_round_pack(sign, e, m);
}

uvec2 sd_sqrt(uvec2 a)
{
    if (sd_is_nan(a) || (sd_sign_of(a) != 0u && !sd_is_zero(a)))
        return SD_NAN;
    if (sd_is_zero(a) || sd_exponent_of(a) == 0x7FF)
        return a;
    int ea;
    uvec2 ma = sd_normalized(a, ea);
    int unbiased = ea - 0x3FF;
    int odd = unbiased & 1;
    // The root of ma * 2^(56 + odd), 110 bits read two at a time from the
    // top (t holds its top 64; the rest are zeros), digit by digit: 55 bits.
    uvec2 t = u64_shl(ma, uint(10 + odd));
    uvec2 root = uvec2(0u), rem = uvec2(0u);
    for (int i = 0; i < 55; ++i) {
        rem = u64_shl(rem, 2u);
        rem.x |= t.y >> 30;
        t = u64_shl(t, 2u);
        uvec2 trial = u64_shl(root, 2u);
        trial.x |= 1u;
        root = u64_shl(root, 1u);
        if (!u64_lt(rem, trial)) {
            rem = u64_sub(rem, trial);
            root.x |= 1u;
        }
    }
    uvec2 m = u64_shl(root, 8u);
    m.x |= rem != uvec2(0u) ? 1u : 0u;
    return sd_round_pack(0u, ((unbiased - odd) >> 1) + 0x3FE, m);
}

// Ordered comparisons: false when either is NaN; -0 equals +0.
bool sd_eq(uvec2 a, uvec2 b)
{
    return !sd_is_nan(a) && !sd_is_nan(b) && (a == b || (sd_is_zero(a) && sd_is_zero(b)));
}

bool sd_lt(uvec2 a, uvec2 b)
{
    if (sd_is_nan(a) || sd_is_nan(b) || (sd_is_zero(a) && sd_is_zero(b)))
        return false;
    bool na = sd_sign_of(a) != 0u, nb = sd_sign_of(b) != 0u;
    if (na != nb)
        return na;
    uvec2 ma = uvec2(a.x, a.y & ~SD_SIGN), mb = uvec2(b.x, b.y & ~SD_SIGN);
    return na ? u64_lt(mb, ma) : u64_lt(ma, mb);
}

bool sd_le(uvec2 a, uvec2 b) { return sd_lt(a, b) || sd_eq(a, b); }
bool sd_gt(uvec2 a, uvec2 b) { return sd_lt(b, a); }
bool sd_ge(uvec2 a, uvec2 b) { return sd_le(b, a); }
bool sd_une(uvec2 a, uvec2 b) { return !sd_eq(a, b); } // unordered: true with a NaN

// min and max as lavapipe's doubles give them: a NaN operand yields the
// other; of two zeros, the second.
uvec2 sd_min(uvec2 a, uvec2 b)
{
    if (sd_is_nan(a))
        return b;
    if (sd_is_nan(b))
        return a;
    return sd_lt(a, b) ? a : b;
}

uvec2 sd_max(uvec2 a, uvec2 b)
{
    if (sd_is_nan(a))
        return b;
    if (sd_is_nan(b))
        return a;
    return sd_lt(b, a) ? a : b;
}

uvec2 sd_floor(uvec2 a)
{
    int e = sd_exponent_of(a) - 0x3FF;
    if (e >= 52 || sd_is_zero(a)) // whole already (or NaN, infinite)
        return a;
    bool negative = sd_sign_of(a) != 0u;
    if (e < 0) // |a| < 1
        return negative ? uvec2(0u, 0xBFF00000u) : uvec2(0u);
    uvec2 fraction = u64_sub(u64_shl(uvec2(1u, 0u), uint(52 - e)), uvec2(1u, 0u));
    if ((a & fraction) == uvec2(0u))
        return a;
    uvec2 whole = a & ~fraction; // toward zero
    return negative ? sd_sub(whole, uvec2(0u, 0x3FF00000u)) : whole;
}

uvec2 sd_fract(uvec2 a) { return sd_sub(a, sd_floor(a)); }

uvec2 sd_from_float(float f)
{
    uint bits = floatBitsToUint(f);
    uint sign = bits & SD_SIGN;
    int e = int((bits >> 23) & 0xFFu);
    uint m = bits & 0x7FFFFFu;
    if (e == 0xFF)
        return m != 0u ? SD_NAN : sd_infinity(sign);
    if (e == 0) {
        if (m == 0u)
            return uvec2(0u, sign);
        int top = findMSB(m); // a subnormal float: normal as a double
        e = top - 22;
        m = (m << uint(23 - top)) & 0x7FFFFFu;
    }
    return uvec2(m << 29, sign | (uint(e - 127 + 0x3FF) << 20) | (m >> 3));
}

// Rounded to nearest, ties to even, as a float.
float sd_to_float(uvec2 a)
{
    uint sign = sd_sign_of(a);
    int e = sd_exponent_of(a);
    if (e == 0x7FF)
        return uintBitsToFloat(sd_is_nan(a) ? 0x7FC00000u : sign | 0x7F800000u);
    if (e == 0) // below 2^-1022: far under a float's least subnormal
        return uintBitsToFloat(sign);
    uvec2 m = sd_fraction_of(a) | uvec2(0u, SD_IMPLICIT);
    int ef = e - 0x3FF + 127; // the float's biased exponent
    uint shift = 29u + uint(max(1 - ef, 0)); // past a float's place
    uvec2 kept = u64_shr_jam(m, min(shift - 2u, 63u)); // with 2 bits below it
    uint v = kept.x >> 2, below = kept.x & 3u;
    v += (below > 2u || (below == 2u && (v & 1u) != 0u)) ? 1u : 0u;
    uint field = uint(max(ef - 1, 0));
    if (ef > 254 || field + (v >> 23) >= 255u)
        return uintBitsToFloat(sign | 0x7F800000u);
    return uintBitsToFloat(sign | ((field << 23) + v));
}

uvec2 sd_from_int(int i)
{
    if (i == 0)
        return uvec2(0u);
    uint sign = i < 0 ? SD_SIGN : 0u;
    uint u = i < 0 ? uint(-(i + 1)) + 1u : uint(i);
    int top = findMSB(u);
    uvec2 m = u64_shl(uvec2(u ^ (1u << uint(top)), 0u), uint(52 - top));
    return uvec2(m.x, sign | (uint(top + 0x3FF) << 20) | m.y);
}

// Toward zero; out of int's range, INT_MIN (what x86 gives).
int sd_to_int(uvec2 a)
{
    int e = sd_exponent_of(a) - 0x3FF;
    if (e < 0)
        return 0;
    if (e > 30)
        return int(0x80000000u);
    uvec2 m = sd_fraction_of(a) | uvec2(0u, SD_IMPLICIT);
    int u = int(u64_shr(m, uint(52 - e)).x);
    return sd_sign_of(a) != 0u ? -u : u;
}
