/* test_retrace.c: which pixels --precision auto traces again
 * (retrace_mark): UNSURE pixels; both sides of a boundary between hashes
 * when either side is SENSITIVE, across the band's edges too; nothing
 * where hashes differ but neither side is sensitive; both sides where the
 * camera rays' shadows differ, sensitive or not; a STOPPED pixel's hash
 * taken to differ from every neighbour's; and, on bands wide enough
 * for the quick skip of uniform runs, the same marks as the rule read
 * pixel by pixel. */
#include <stdbool.h>
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
#define SH0 TP2_SIG_SHADOW_LOW        /* light class 0 shadowed */
#define SH1 (TP2_SIG_SHADOW_LOW << 1) /* light class 1 shadowed */

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

/* The rule read pixel by pixel (retrace.h), for bands of any width. */
static bool marked_by_rule(const uint32_t *above, const uint32_t *band, const uint32_t *below,
                           int width, int n, int x, int y)
{
    uint32_t sig = band[(size_t)y * width + x];
    if (sig & RETRACE_UNSURE)
        return true;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int nx = x + dx, ny = y + dy;
            const uint32_t *row = ny < 0 ? above : ny >= n ? below : band + (size_t)ny * width;
            if (!row || nx < 0 || nx >= width || (dx == 0 && dy == 0))
                continue;
            uint32_t other = row[nx];
            bool differ = ((sig ^ other) & RETRACE_HASH) || ((sig | other) & RETRACE_STOPPED);
            if ((differ && ((sig | other) & RETRACE_SENSITIVE)) ||
                ((sig ^ other) & RETRACE_SHADOWS))
                return true;
        }
    return false;
}

/* A band wider than the runs retrace_mark skips whole (64 pixels): one
 * word, with patches of other words and flag bits placed by a fixed
 * pseudo-random stream, from single pixels to runs wider than 64 (a wide
 * run of one UNSURE word is uniform and still marked), some at the runs'
 * ends and the image's edges. retrace_mark must list exactly the pixels
 * the rule marks, in block order. */
static void check_wide_band(unsigned seed, int width, bool rows_around)
{
    enum { WW = 300, NN = 7 };
    static uint32_t rows[NN + 2][WW];
    static uint32_t list[WW * NN];
    unsigned state = seed;
    for (int y = 0; y < NN + 2; y++)
        for (int x = 0; x < width; x++)
            rows[y][x] = 5;
    for (int k = 0; k < (int)(seed / 4 % 8); k++) {
        state = state * 1103515245u + 12345u;
        unsigned r = state >> 8;
        int x = (int)(r % (unsigned)width), y = (int)(r / (unsigned)width % (NN + 2));
        static const uint32_t kinds[] = {6,        5 | S,    5 | U,     5 | STOP,
                                         6 | S,    5 | SH0,  6 | SH1,   5 | STOP | S};
        uint32_t word = kinds[(r >> 12) % 8];
        bool wide = (r >> 16) % 3 == 0;
        int w = wide ? 60 + (int)(r >> 18) % 100 : 1 + (int)(r >> 18) % 3;
        int h = wide ? 1 + (int)(r >> 20) % 4 : w;
        for (int dy = 0; dy < h && y + dy < NN + 2; dy++)
            for (int dx = 0; dx < w && x + dx < width; dx++)
                rows[y + dy][x + dx] = word;
    }
    /* A lone pixel that only one corner of a run (64 pixels by the rows
     * of a block) sees, diagonally: (63, 1) from (64, 2), (128, 3) from
     * (127, 4), (192, 6) from (191, 5); one per seed, or none. */
    static const int lone[3][2] = {{63, 1}, {128, 3}, {192, 6}};
    int which = (int)(seed % 4);
    if (which < 3 && lone[which][0] < width)
        rows[1 + lone[which][1]][lone[which][0]] = 9 | S;
    const uint32_t *above = rows_around ? rows[0] : NULL;
    const uint32_t *below = rows_around ? rows[NN + 1] : NULL;
    static uint32_t band[NN * WW];
    for (int y = 0; y < NN; y++)
        memcpy(band + (size_t)y * width, rows[y + 1], (size_t)width * sizeof *band);
    size_t n = retrace_mark(above, band, below, width, NN, list);
    static bool listed[NN * WW];
    memset(listed, 0, sizeof listed);
    for (size_t i = 0; i < n; i++)
        listed[list[i]] = true;
    size_t want = 0;
    for (int y = 0; y < NN; y++)
        for (int x = 0; x < width; x++) {
            bool rule = marked_by_rule(above, band, below, width, NN, x, y);
            want += rule;
            expect(listed[y * width + x] == rule,
                   "wide band (seed %u, width %d): pixel (%d, %d) listed %d, rule %d", seed,
                   width, x, y, listed[y * width + x], rule);
        }
    expect(n == want, "wide band (seed %u, width %d): %zu listed, %zu marked by the rule", seed,
           width, n, want);
    for (size_t i = 1; i < n; i++) {
        long a = list[i - 1], b = list[i];
        long block_a = a / width / RETRACE_BLOCK_Y * width + a % width / RETRACE_BLOCK_X;
        long block_b = b / width / RETRACE_BLOCK_Y * width + b % width / RETRACE_BLOCK_X;
        expect(block_a < block_b || (block_a == block_b && a < b),
               "wide band (seed %u, width %d): %ld listed after %ld", seed, width, b, a);
    }
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

    /* A shadow edge the camera sees: where the lights the camera rays saw
     * shadowed differ, both sides are marked, sensitive or not, hashes
     * equal or not; where they are the same, a hash boundary with nothing
     * sensitive marks nothing. */
    const uint32_t shadow[N][W] = {{3, 3, 3 | SH0, 3 | SH0, 3 | SH0},
                                   {3, 3, 3, 4 | SH0, 4 | SH0},
                                   {3 | SH1, 3 | SH1, 3 | SH1, 3 | SH1, 3 | SH1},
                                   {3 | SH1, 3 | SH1, 3 | SH1, 3 | SH1, 3 | SH1}};
    const int shadow_want[N][W] = {{0, 1, 1, 1, 0},
                                   {1, 1, 1, 1, 1},
                                   {1, 1, 1, 1, 1},
                                   {0, 0, 0, 0, 0}};
    mark(NULL, shadow, NULL, got);
    expect_grid("shadow edges", got, shadow_want);

    static const int widths[] = {300, 256, 129, 65};
    for (unsigned seed = 0; seed < 256; seed++)
        check_wide_band(seed, widths[seed / 32 % 4], seed % 3 != 0);
    return unit_report();
}
