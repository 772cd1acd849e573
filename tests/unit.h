/* unit.h: pass/fail bookkeeping shared by the C unit tests.
 *
 * Header-only, included once by each test program: expect() records a
 * check, CHECK() one named by its own source text, and unit_report() prints
 * the closing "N passed, M failed" line and gives main's exit status. */
#ifndef TP2_UNIT_H
#define TP2_UNIT_H

#include <stdarg.h>
#include <stdio.h>

static int passed, failed;

/* Records one check; prints "FAIL: " and the message only when it fails. */
static void expect(int ok, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void expect(int ok, const char *fmt, ...)
{
    if (ok) {
        passed++;
        return;
    }
    failed++;
    va_list ap;
    va_start(ap, fmt);
    fputs("FAIL: ", stdout);
    vprintf(fmt, ap);
    fputs("\n", stdout);
    va_end(ap);
}

#define CHECK(cond) expect((cond) != 0, "line %d: %s", __LINE__, #cond)

/* The closing line; 0 when nothing failed, else 1. */
static int unit_report(void)
{
    printf("%d passed, %d failed\n", passed, failed);
    return failed != 0;
}

#endif
