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

// Written without branches (selects instead): lavapipe runs both arms of
// an if anyway, and the inlined copies compile faster without the blocks.
uvec2 pick(bool c, uvec2 yes, uvec2 no) { return mix(no, yes, bvec2(c)); }

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

// Whether a - b borrows.
bool u64_lt(uvec2 a, uvec2 b)
{
    uint low, high, again;
    usubBorrow(a.x, b.x, low);
    usubBorrow(usubBorrow(a.y, b.y, high), low, again);
    return (high | again) != 0u;
}

// a << n, n in [0, 63]. (GLSL leaves shifts by 32 or more undefined:
// the bits crossing words move by 31 - m after one.)
uvec2 u64_shl(uvec2 a, uint n)
{
    uint m = n & 31u;
    uint lo = a.x << m;
    uint hi = (a.y << m) | ((a.x >> 1) >> (31u - m));
    return pick(n >= 32u, uvec2(0u, lo), uvec2(lo, hi));
}

// a >> n, n in [0, 63].
uvec2 u64_shr(uvec2 a, uint n)
{
    uint m = n & 31u;
    uint hi = a.y >> m;
    uint lo = (a.x >> m) | ((a.y << 1) << (31u - m));
    return pick(n >= 32u, uvec2(hi, 0u), uvec2(lo, hi));
}

// a >> n for any n, with every bit shifted out ORed into bit 0 ("jamming"):
// rounding then still sees whether anything below the last place was lost.
// (Past 63, a >> 63 is 0 for every a here, below 2^63, so 1 if a is not 0.)
uvec2 u64_shr_jam(uvec2 a, uint n)
{
    uint k = min(n, 63u);
    uvec2 kept = u64_shr(a, k);
    bool lost = u64_shl(kept, k) != a;
    return uvec2(kept.x | uint(lost), kept.y);
}

// Leading zeros of a (64 when a is 0).
uint u64_clz(uvec2 a)
{
    uint high = uint(31 - findMSB(a.y)), low = uint(63 - findMSB(a.x));
    return a.y != 0u ? high : low;
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
    return uvec2(w2 | uint((l00 | w1) != 0u), h11 + c2);
}

bool either(bool a, bool b) { return any(bvec2(a, b)); }
bool both(bool a, bool b) { return all(bvec2(a, b)); }

// Fields of a double.
uint sd_sign_of(uvec2 a) { return a.y & SD_SIGN; }
int sd_exponent_of(uvec2 a) { return int((a.y >> 20) & 0x7FFu); }
uvec2 sd_fraction_of(uvec2 a) { return uvec2(a.x, a.y & 0xFFFFFu); }
bool sd_is_special(uvec2 a) { return (a.y & 0x7FF00000u) == 0x7FF00000u; } // NaN or infinite
bool sd_is_nan(uvec2 a) { return both(sd_is_special(a), sd_fraction_of(a) != uvec2(0u)); }
bool sd_is_zero(uvec2 a) { return ((a.y & ~SD_SIGN) | a.x) == 0u; }
uvec2 sd_infinity(uint sign) { return uvec2(0u, sign | 0x7FF00000u); }

// Rounds sign * m * 2^(e + 1 - 1023 - 62) to a double (see the top).
uvec2 sd_round_pack(uint sign, int e, uvec2 m)
{
    m = u64_shr_jam(m, uint(max(-e, 0))); // below the normal range: a subnormal's exponent
    e = max(e, 0);
    uint below = m.x & 0x3FFu;
    m = u64_add(m, uvec2(0x200u, 0u));
    bool overflow = either(e > 0x7FD, both(e == 0x7FD, (m.y & SD_SIGN) != 0u));
    m = u64_shr(m, 10u);
    m.x &= below == 0x200u ? ~1u : ~0u; // a tie: to even
    e = m == uvec2(0u) ? 0 : e;
    uvec2 bits = u64_add(uvec2(0u, uint(min(e, 0x7FD)) << 20), m);
    return pick(overflow, sd_infinity(sign), uvec2(bits.x, bits.y | sign));
}

// The significand of a finite nonzero double with its leading bit at 52,
// and the biased exponent that goes with it (below 1 for a subnormal).
uvec2 sd_normalized(uvec2 a, out int e)
{
    int biased = sd_exponent_of(a);
    uvec2 m = sd_fraction_of(a);
    uint shift = biased != 0 ? 0u : min(u64_clz(m) - 11u, 63u);
    e = biased != 0 ? biased : 1 - int(shift);
    return u64_shl(uvec2(m.x, m.y | (biased != 0 ? SD_IMPLICIT : 0u)), shift);
}

uvec2 sd_neg(uvec2 a) { return uvec2(a.x, a.y ^ SD_SIGN); }
uvec2 sd_abs(uvec2 a) { return uvec2(a.x, a.y & ~SD_SIGN); }

uvec2 sd_add(uvec2 a, uvec2 b)
{
    // a the larger in magnitude (the bits order magnitudes)
    bool swap = u64_lt(sd_abs(a), sd_abs(b));
    uvec2 big = pick(swap, b, a), small = pick(swap, a, b);
    int eb = sd_exponent_of(big), es = sd_exponent_of(small);
    uvec2 mb = u64_shl(sd_fraction_of(big) | uvec2(0u, eb != 0 ? SD_IMPLICIT : 0u), 10u);
    uvec2 ms = u64_shl(sd_fraction_of(small) | uvec2(0u, es != 0 ? SD_IMPLICIT : 0u), 10u);
    eb = max(eb, 1); // a subnormal's exponent
    es = max(es, 1);
    ms = u64_shr_jam(ms, uint(eb - es));
    bool same = sd_sign_of(a) == sd_sign_of(b);
    // Same signs: the sum, one place lower where it carried past bit 62.
    uvec2 sum = u64_add(mb, ms);
    bool carried = (sum.y & SD_SIGN) != 0u;
    sum = pick(carried, u64_shr_jam(sum, 1u), sum);
    // Opposite: the difference, its leading bit moved up to 62 (exact: a
    // shift of more than one means no bits were jammed).
    uvec2 difference = u64_sub(mb, ms);
    uint shift = min(u64_clz(difference), 63u) - 1u;
    int e = same ? eb - 1 + int(carried) : eb - 1 - int(shift);
    uvec2 m = same ? sum : u64_shl(difference, shift);
    uvec2 rounded = sd_round_pack(sd_sign_of(big), e, m);
    rounded = pick(both(!same, difference == uvec2(0u)), uvec2(0u), rounded); // x - x is +0
    // NaN, infinities: the larger, or NaN (infinities of opposite signs)
    bool nan = either(either(sd_is_nan(a), sd_is_nan(b)),
                      both(both(sd_is_special(a), sd_is_special(b)), !same));
    return pick(nan, SD_NAN, pick(sd_is_special(big), big, rounded));
}

uvec2 sd_sub(uvec2 a, uvec2 b) { return sd_add(a, sd_neg(b)); }

uvec2 sd_mul(uvec2 a, uvec2 b)
{
    uint sign = sd_sign_of(a) ^ sd_sign_of(b);
    int ea, eb;
    uvec2 ma = u64_shl(sd_normalized(a, ea), 10u);
    uvec2 mb = u64_shl(sd_normalized(b, eb), 11u);
    uvec2 m = u64_mul_high_jam(ma, mb); // leading bit at 61 or 62
    bool low = (m.y & 0x40000000u) == 0u;
    uvec2 product = sd_round_pack(sign, ea + eb - 0x3FF - int(low), u64_shl(m, uint(low)));
    bool zero = either(sd_is_zero(a), sd_is_zero(b));
    bool infinite = either(sd_is_special(a), sd_is_special(b));
    bool nan = either(either(sd_is_nan(a), sd_is_nan(b)), both(zero, infinite));
    return pick(nan, SD_NAN,
                pick(infinite, sd_infinity(sign), pick(zero, uvec2(0u, sign), product)));
}

uvec2 sd_div(uvec2 a, uvec2 b)
{
    uint sign = sd_sign_of(a) ^ sd_sign_of(b);
    int ea, eb;
    uvec2 ma = sd_normalized(a, ea), mb = sd_normalized(b, eb);
    bool low = u64_lt(ma, mb);
    ma = u64_shl(ma, uint(low));
    // Long division, one bit of quotient a step: 55 bits, the last place
    // and two below it; the remainder says whether more would follow.
    uvec2 q = uvec2(0u), r = ma;
    for (int i = 0; i < 55; ++i) {
        bool fits = !u64_lt(r, mb);
        q = uvec2((q.x << 1) | uint(fits), (q.y << 1) | (q.x >> 31));
        r = u64_shl(pick(fits, u64_sub(r, mb), r), 1u);
    }
    uvec2 m = u64_shl(q, 8u);
    m.x |= uint(r != uvec2(0u));
    uvec2 quotient = sd_round_pack(sign, ea - eb + 0x3FE - int(low), m);
    bool a_inf = sd_is_special(a), b_inf = sd_is_special(b);
    bool a_zero = sd_is_zero(a), b_zero = sd_is_zero(b);
    bool nan = either(either(sd_is_nan(a), sd_is_nan(b)),
                      either(both(a_inf, b_inf), both(a_zero, b_zero)));
    return pick(nan, SD_NAN, pick(either(a_inf, b_zero), sd_infinity(sign),
                                  pick(either(b_inf, a_zero), uvec2(0u, sign), quotient)));
}

uvec2 sd_sqrt(uvec2 a)
{
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
        bool fits = !u64_lt(rem, trial);
        rem = pick(fits, u64_sub(rem, trial), rem);
        root = uvec2((root.x << 1) | uint(fits), (root.y << 1) | (root.x >> 31));
    }
    uvec2 m = u64_shl(root, 8u);
    m.x |= uint(rem != uvec2(0u));
    uvec2 r = sd_round_pack(0u, ((unbiased - odd) >> 1) + 0x3FE, m);
    bool nan = either(sd_is_nan(a), both(sd_sign_of(a) != 0u, !sd_is_zero(a)));
    return pick(nan, SD_NAN, pick(either(sd_is_zero(a), sd_is_special(a)), a, r));
}

// Ordered comparisons: false when either is NaN; -0 equals +0.
bool sd_eq(uvec2 a, uvec2 b)
{
    bool nan = either(sd_is_nan(a), sd_is_nan(b));
    return both(!nan, either(a == b, both(sd_is_zero(a), sd_is_zero(b))));
}

bool sd_lt(uvec2 a, uvec2 b)
{
    bool na = sd_sign_of(a) != 0u, nb = sd_sign_of(b) != 0u;
    uvec2 ma = sd_abs(a), mb = sd_abs(b);
    bool lt = na != nb ? na : na ? u64_lt(mb, ma) : u64_lt(ma, mb);
    bool never = either(either(sd_is_nan(a), sd_is_nan(b)), both(sd_is_zero(a), sd_is_zero(b)));
    return both(!never, lt);
}

bool sd_le(uvec2 a, uvec2 b) { return either(sd_lt(a, b), sd_eq(a, b)); }
bool sd_gt(uvec2 a, uvec2 b) { return sd_lt(b, a); }
bool sd_ge(uvec2 a, uvec2 b) { return sd_le(b, a); }
bool sd_une(uvec2 a, uvec2 b) { return !sd_eq(a, b); } // unordered: true with a NaN

// min and max as lavapipe's doubles give them: a NaN operand yields the
// other; of two zeros, the second.
uvec2 sd_min(uvec2 a, uvec2 b)
{
    return pick(sd_is_nan(a), b, pick(sd_is_nan(b), a, pick(sd_lt(a, b), a, b)));
}

uvec2 sd_max(uvec2 a, uvec2 b)
{
    return pick(sd_is_nan(a), b, pick(sd_is_nan(b), a, pick(sd_lt(b, a), a, b)));
}

uvec2 sd_floor(uvec2 a)
{
    int e = sd_exponent_of(a) - 0x3FF;
    // the fraction's bits (all of them below 1; none from 2^52 up)
    uvec2 fraction = u64_sub(u64_shl(uvec2(1u, 0u), uint(clamp(52 - e, 0, 63))), uvec2(1u, 0u));
    fraction = e < 0 ? uvec2(0xFFFFFFFFu, 0x7FFFFFFFu) : fraction;
    bool negative = sd_sign_of(a) != 0u;
    uvec2 whole = a & ~fraction; // toward zero (a signed zero below 1)
    bool cut = both(!sd_is_zero(a), (a & fraction) != uvec2(0u));
    uvec2 down = e < 0 ? uvec2(0u, 0xBFF00000u) : sd_sub(whole, uvec2(0u, 0x3FF00000u));
    return pick(both(cut, e < 52), pick(negative, down, whole), a);
}

uvec2 sd_fract(uvec2 a) { return sd_sub(a, sd_floor(a)); }

uvec2 sd_from_float(float f)
{
    uint bits = floatBitsToUint(f);
    uint sign = bits & SD_SIGN;
    int e = int((bits >> 23) & 0xFFu);
    uint raw = bits & 0x7FFFFFu;
    int top = findMSB(raw); // a subnormal float: normal as a double
    bool subnormal = e == 0;
    uint m = subnormal ? (raw << uint(max(23 - top, 0))) & 0x7FFFFFu : raw;
    int ed = subnormal ? top - 22 : e;
    uvec2 finite = uvec2(m << 29, sign | (uint(ed - 127 + 0x3FF) << 20) | (m >> 3));
    uvec2 special = raw != 0u ? SD_NAN : sd_infinity(sign);
    return pick(e == 0xFF, special, pick(both(subnormal, raw == 0u), uvec2(0u, sign), finite));
}

// Rounded to nearest, ties to even, as a float.
float sd_to_float(uvec2 a)
{
    uint sign = sd_sign_of(a);
    int e = sd_exponent_of(a);
    uvec2 m = sd_fraction_of(a) | uvec2(0u, SD_IMPLICIT);
    int ef = e - 0x3FF + 127; // the float's biased exponent
    uint shift = 29u + uint(clamp(1 - ef, 0, 40)); // past a float's place
    uvec2 kept = u64_shr_jam(m, shift - 2u); // with 2 bits below it
    uint v = kept.x >> 2, below = kept.x & 3u;
    v += uint(either(below > 2u, both(below == 2u, (v & 1u) != 0u)));
    uint field = uint(clamp(ef - 1, 0, 255));
    bool overflow = either(ef > 254, field + (v >> 23) >= 255u);
    uint finite = overflow ? sign | 0x7F800000u : sign | ((field << 23) + v);
    uint special = sd_is_nan(a) ? 0x7FC00000u : sign | 0x7F800000u;
    // below 2^-1022: far under a float's least subnormal
    return uintBitsToFloat(e == 0x7FF ? special : e == 0 ? sign : finite);
}

uvec2 sd_from_int(int i)
{
    uint sign = i < 0 ? SD_SIGN : 0u;
    uint u = i < 0 ? uint(-(i + 1)) + 1u : uint(i);
    int top = max(findMSB(u), 0);
    uvec2 m = u64_shl(uvec2(u ^ (1u << uint(top)), 0u), uint(52 - top));
    uvec2 d = uvec2(m.x, sign | (uint(top + 0x3FF) << 20) | m.y);
    return pick(i == 0, uvec2(0u), d);
}

// Toward zero; out of int's range, INT_MIN (what x86 gives).
int sd_to_int(uvec2 a)
{
    int e = sd_exponent_of(a) - 0x3FF;
    uvec2 m = sd_fraction_of(a) | uvec2(0u, SD_IMPLICIT);
    int u = int(u64_shr(m, uint(clamp(52 - e, 0, 63))).x);
    int whole = sd_sign_of(a) != 0u ? -u : u;
    return e < 0 ? 0 : e > 30 ? int(0x80000000u) : whole;
}
