/* test_retrace.c: which pixels --precision auto traces again
 * (retrace_mark): UNSURE pixels; both sides of a boundary between hashes
 * when either side is SENSITIVE, across the band's edges too; nothing
 * where hashes differ but neither side is sensitive; a STOPPED pixel's
 * hash taken to differ from every neighbour's. */
#include <stdint.h>
#include <string.h>

#include "retrace.h"
#include "unit.h"

enum { W = 5, N = 4 };

/* Where pixel `at` of the band comes in the list's order: by blocks of
 * RETRACE_BLOCK_X x RETRACE_BLOCK_Y, row order within each. */
static long block_order(uint32_t at)
{
    long x = at % W, y = at / W;
    long block = y / RETRACE_BLOCK_Y * W + x / RETRACE_BLOCK_X;
    return block * RETRACE_BLOCK_X * RETRACE_BLOCK_Y + y % RETRACE_BLOCK_Y * RETRACE_BLOCK_X +
           x % RETRACE_BLOCK_X;
}

#define S RETRACE_SENSITIVE
#define U RETRACE_UNSURE
#define STOP (RETRACE_UNSURE | RETRACE_STOPPED)

/* Marks band (N rows of W) with optional rows around it; the marks as a
 * W x N grid of 0/1 in out. Returns the count. */
static size_t mark(const uint32_t *above, const uint32_t band[N][W], const uint32_t *below,
                   int out[N][W])
{
    uint32_t list[W * N];
    size_t n = retrace_mark(above, &band[0][0], below, W, N, list);
    memset(out, 0, sizeof(int) * W * N);
    for (size_t i = 0; i < n; i++) {
        out[list[i] / W][list[i] % W] = 1;
        expect(i == 0 || block_order(list[i]) > block_order(list[i - 1]),
               "list in block order: %u after %u", (unsigned)list[i],
               (unsigned)list[i > 0 ? i - 1 : 0]);
    }
    return n;
}

static void expect_grid(const char *what, int got[N][W], const int want[N][W])
{
    for (int y = 0; y < N; y++)
        for (int x = 0; x < W; x++)
            expect(got[y][x] == want[y][x], "%s: pixel (%d, %d) marked %d, want %d", what, x,
                   y, got[y][x], want[y][x]);
}

int main(void)
{
    int got[N][W];

    /* One hash everywhere, sensitive or not: nothing. */
    const uint32_t flat[N][W] = {{7 | S, 7, 7, 7, 7}, {7, 7, 7 | S, 7, 7},
                                 {7, 7, 7, 7, 7}, {7, 7, 7, 7, 7 | S}};
    CHECK(mark(NULL, flat, NULL, got) == 0);

    /* UNSURE alone marks its pixel only. */
    const uint32_t unsure[N][W] = {{7, 7, 7, 7, 7}, {7, 7, 7 | U, 7, 7},
                                   {7, 7, 7, 7, 7}, {7, 7, 7, 7, 7}};
    const int unsure_want[N][W] = {{0}, {0, 0, 1, 0, 0}};
    mark(NULL, unsure, NULL, got);
    expect_grid("unsure", got, unsure_want);

    /* A vertical boundary between hashes 1 and 2: a pair across it is
     * marked, both sides, where one of the two is sensitive: the
     * sensitive pixel (1, 1) and the three across from it, no other. */
    const uint32_t edge[N][W] = {{1, 1, 2, 2, 2}, {1, 1 | S, 2, 2, 2},
                                 {1, 1, 2, 2, 2}, {1, 1, 2, 2, 2}};
    const int edge_want[N][W] = {{0, 0, 1, 0, 0}, {0, 1, 1, 0, 0},
                                 {0, 0, 1, 0, 0}, {0, 0, 0, 0, 0}};
    mark(NULL, edge, NULL, got);
    expect_grid("edge", got, edge_want);

    /* The same hashes, nothing sensitive: rounding cannot move the
     * boundary across a pixel center, so nothing. */
    const uint32_t calm[N][W] = {{1, 1, 2, 2, 2}, {1, 1, 2, 2, 2},
                                 {1, 1, 2, 2, 2}, {1, 1, 2, 2, 2}};
    CHECK(mark(NULL, calm, NULL, got) == 0);

    /* Boundaries with the rows either side of the band: the row above
     * (the previous band's last) and the row after (traced for its
     * signatures) mark the band's first and last rows. */
    const uint32_t above[W] = {9 | S, 3, 3, 3, 3};
    const uint32_t below[W] = {3, 3, 3, 3, 5 | S};
    const uint32_t plain[N][W] = {{3, 3, 3, 3, 3}, {3, 3, 3, 3, 3},
                                  {3, 3, 3, 3, 3}, {3, 3, 3, 3, 3}};
    const int rows_want[N][W] = {{1, 1, 0, 0, 0}, {0}, {0}, {0, 0, 0, 1, 1}};
    mark(above, plain, below, got);
    expect_grid("rows around the band", got, rows_want);
    CHECK(mark(NULL, plain, NULL, got) == 0);

    /* Flag bits are not part of the hash: equal hashes, one unsure and
     * one sensitive, mark the unsure one only. */
    const uint32_t bits[N][W] = {{4 | U, 4 | S, 4, 4, 4}, {4, 4, 4, 4, 4},
                                 {4, 4, 4, 4, 4}, {4, 4, 4, 4, 4}};
    const int bits_want[N][W] = {{1, 0, 0, 0, 0}};
    mark(NULL, bits, NULL, got);
    expect_grid("flag bits", got, bits_want);

    /* A stopped pixel's hash covers part of its rays: even where it equals
     * a neighbour's, it counts as a boundary with each neighbour, marked
     * where one of the two is sensitive (the stopped one itself always). */
    const uint32_t stopped[N][W] = {{8, 8, 8, 8, 8 | S}, {8, 8 | STOP, 8 | S, 8, 8},
                                    {8, 8, 8, 8, 8}, {8, 8, 8, 8 | STOP | S, 8}};
    const int stopped_want[N][W] = {{0, 0, 0, 0, 0}, {0, 1, 1, 0, 0},
                                    {0, 0, 1, 1, 1}, {0, 0, 1, 1, 1}};
    mark(NULL, stopped, NULL, got);
    expect_grid("stopped", got, stopped_want);
    return unit_report();
}
