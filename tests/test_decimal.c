/* test_decimal.c: decimal_read against strtod, bit for bit and end for
 * end, on the edges of its fast path and on a million random strings in
 * the shapes scene files use (and some they do not). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "decimal.h"
#include "unit.h"

/* 1 if decimal_read and strtod agree on s: same bits, same end. */
static int agrees(const char *s)
{
    char *e1 = NULL, *e2 = NULL;
    double a = decimal_read(s, &e1);
    double b = strtod(s, &e2);
    return memcmp(&a, &b, sizeof a) == 0 && e1 == e2;
}

static uint64_t rng = 88172645463325252u;

static unsigned next(unsigned n)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (unsigned)(rng % n);
}

/* A random string of sign, digits, point, exponent and junk. */
static void random_number(char *out, size_t size)
{
    static const char tail[] = " e-+.x#abc";
    size_t n = 0;
    if (next(3) == 0)
        out[n++] = "+-"[next(2)];
    int digits = (int)next(next(4) == 0 ? 30 : 10);
    for (int i = 0; i < digits && n + 1 < size; i++)
        out[n++] = (char)('0' + (next(4) == 0 ? 0 : next(10)));
    if (next(2) && n + 1 < size) {
        out[n++] = '.';
        int frac = (int)next(next(4) == 0 ? 30 : 12);
        for (int i = 0; i < frac && n + 1 < size; i++)
            out[n++] = (char)('0' + next(10));
    }
    if (next(3) == 0 && n + 6 < size) {
        out[n++] = "eE"[next(2)];
        if (next(2))
            out[n++] = "+-"[next(2)];
        int ed = (int)next(4);
        for (int i = 0; i < ed; i++)
            out[n++] = (char)('0' + next(10));
    }
    if (next(4) == 0 && n + 1 < size)
        out[n++] = tail[next(sizeof tail - 1)];
    out[n] = '\0';
}

int main(void)
{
    static const char *const edges[] = {
        "0", "-0", "+0", "0.0", "-0.0", ".5", "-.5", "5.", "+5.", ".", "-", "+", "",
        "e5", ".e5", "1e", "1e+", "1e-", "1e5x", "1.5.3", "2.5e-3", "1E22", "1e23",
        "1e-22", "1e-23", "9007199254740992", "9007199254740993", "9007199254740991e3",
        "1234567890123456789", "12345678901234567890", "0.1234567890123456789",
        "00000000000000000000000001", "0.00000000000000000000000001", "1e308",
        "1e309", "1e-400", "0e999999999999", "123e-20", "0x1p3", "0X1P-3", "0x",
        "inf", "-Infinity", "nan", "NaN(1)", "1,5", "3.14159265358979323846",
        "0.30000000000000004", "1e0000000000000000000000005", "4.9e-324", "  7",
        "1.7976931348623157e308", "2.2250738585072014e-308", "100000000000000000000000",
    };
    for (size_t i = 0; i < sizeof edges / sizeof edges[0]; i++)
        expect(agrees(edges[i]), "'%s' reads as strtod reads it", edges[i]);

    int bad = 0;
    const int n = 1000000;
    char buf[96];
    for (int i = 0; i < n; i++) {
        random_number(buf, sizeof buf);
        if (!agrees(buf) && bad++ < 10)
            printf("differs from strtod: '%s'\n", buf);
    }
    expect(bad == 0, "%d of %d random strings read differently from strtod", bad, n);
    return unit_report();
}
