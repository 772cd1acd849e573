/* decimal.c: Clinger's fast path in front of strtod; see decimal.h.
 *
 * Why it is exact: m <= 2^53 and 10^k for k <= 22 (5^22 < 2^53) are both
 * doubles exactly, so m * 10^k and m / 10^k are single IEEE operations,
 * each correctly rounded to nearest, the result strtod must return. This
 * needs double arithmetic without excess precision (FLT_EVAL_METHOD 0, as
 * on x86-64 and AArch64) and the default rounding mode, which tp2 never
 * changes. Parsing 45 MB of spheres spent a fifth of its time in strtod's
 * general algorithm. */
#include "decimal.h"

#include <float.h>
#include <stdint.h>
#include <stdlib.h>

_Static_assert(FLT_EVAL_METHOD == 0, "the fast path needs plain double arithmetic");

static const double powers_of_ten[23] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

double decimal_read(const char *s, char **end)
{
    const char *p = s;
    int negative = *p == '-';
    if (*p == '+' || *p == '-')
        p++;
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X'))
        return strtod(s, end); /* hexadecimal */
    uint64_t m = 0;
    int digits = 0, significant = 0, scale = 0;
    for (; is_digit(*p); p++, digits++) {
        if (m == 0 && *p == '0')
            continue; /* leading zeros are not significant */
        if (++significant > 19)
            return strtod(s, end);
        m = m * 10 + (uint64_t)(*p - '0');
    }
    if (*p == '.') {
        for (p++; is_digit(*p); p++, digits++) {
            scale--;
            if (m == 0 && *p == '0')
                continue;
            if (++significant > 19)
                return strtod(s, end);
            m = m * 10 + (uint64_t)(*p - '0');
        }
    }
    if (digits == 0)
        return strtod(s, end); /* no number here, or "inf", "nan" */
    if (*p == 'e' || *p == 'E') { /* an exponent only if digits follow */
        const char *q = p + 1;
        int exp_negative = *q == '-';
        if (*q == '+' || *q == '-')
            q++;
        if (is_digit(*q)) {
            int e = 0;
            for (; is_digit(*q); q++) {
                if (e > 10000)
                    return strtod(s, end);
                e = e * 10 + (*q - '0');
            }
            scale += exp_negative ? -e : e;
            p = q;
        }
    }
    if (m > (UINT64_C(1) << 53) || scale > 22 || scale < -22)
        return strtod(s, end);
    double v = (double)m;
    v = scale >= 0 ? v * powers_of_ten[scale] : v / powers_of_ten[-scale];
    if (end)
        *end = (char *)p;
    return negative ? -v : v;
}
