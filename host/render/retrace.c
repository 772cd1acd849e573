#include "retrace.h"

#include <stdbool.h>
#include <string.h>

/* Row y of the band, -1 and n being the rows either side of it. */
static const uint32_t *row_at(const uint32_t *above, const uint32_t *rows,
                              const uint32_t *below, int width, int n, int y)
{
    if (y < 0)
        return above;
    if (y >= n)
        return below;
    return rows + (size_t)y * width;
}

/* Whether a boundary between pixels of signatures a and b needs a double
 * trace: their hashes differ (or one is partial, RETRACE_STOPPED) and one
 * of them says its boundaries may move (RETRACE_SENSITIVE); or their
 * camera rays' shadows differ (RETRACE_SHADOWS, recorded only where the
 * edge may move by a fiftieth of what SENSITIVE needs). */
static bool boundary(uint32_t a, uint32_t b)
{
    bool differ = ((a ^ b) & RETRACE_HASH) != 0 || ((a | b) & RETRACE_STOPPED) != 0;
    return (differ && ((a | b) & RETRACE_SENSITIVE) != 0) || ((a ^ b) & RETRACE_SHADOWS) != 0;
}

/* Whether sig has such a boundary with one of the three pixels of row r
 * around x (r NULL: no row there). */
static bool near_boundary(const uint32_t *r, int width, int x, uint32_t sig)
{
    if (!r)
        return false;
    for (int dx = -1; dx <= 1; dx++)
        if (x + dx >= 0 && x + dx < width && boundary(sig, r[x + dx]))
            return true;
    return false;
}

/* Whether pixel x of row y (here), not quiet (below), is to be traced
 * again. */
static bool marked(const uint32_t *up, const uint32_t *here, const uint32_t *down, int width,
                   int x)
{
    uint32_t sig = here[x];
    return (sig & RETRACE_UNSURE) || near_boundary(up, width, x, sig) ||
           near_boundary(here, width, x, sig) || near_boundary(down, width, x, sig);
}

/* Which of the 64 pixels of row here from x0 are uniform (and not at the
 * image's edges): quiet[i] for pixel x0 + i, 1 when its 3 x 3 pixels are
 * all one word, not UNSURE; such a pixel is not marked. Most are. Returns
 * whether all 64 are. Branch-free, so that the compiler tests several
 * pixels at once: the test by pixel, with early exits, took about 1 ms of
 * each 1920-pixel band of 136 rows, time in which the device waits. */
static bool quiet_run(const uint32_t *up, const uint32_t *here, const uint32_t *down,
                      int width, int x0, uint8_t quiet[64])
{
    memset(quiet, 0, 64);
    if (!up || !down)
        return false;
    int from = x0 > 0 ? 0 : 1, to = width - 1 - x0 < 64 ? width - 1 - x0 : 64;
    const uint32_t *u = up + x0, *h = here + x0, *d = down + x0;
    unsigned all = from == 0 && to == 64;
    for (int i = from; i < to; i++) {
        uint32_t s = h[i];
        quiet[i] = (uint8_t)(((s & RETRACE_UNSURE) == 0) & (u[i - 1] == s) & (u[i] == s) &
                             (u[i + 1] == s) & (h[i - 1] == s) & (h[i + 1] == s) &
                             (d[i - 1] == s) & (d[i] == s) & (d[i + 1] == s));
        all &= quiet[i];
    }
    return all != 0;
}

size_t retrace_mark(const uint32_t *above, const uint32_t *rows, const uint32_t *below,
                    int width, int n, uint32_t *list)
{
    _Static_assert(64 % RETRACE_BLOCK_X == 0, "runs of 64 pixels are whole blocks");
    size_t count = 0;
    uint8_t quiet[RETRACE_BLOCK_Y][64];
    for (int y0 = 0; y0 < n; y0 += RETRACE_BLOCK_Y)
        for (int run = 0; run < width; run += 64) {
            bool all = true;
            for (int y = y0; y < y0 + RETRACE_BLOCK_Y && y < n; y++)
                all &= quiet_run(row_at(above, rows, below, width, n, y - 1),
                                 rows + (size_t)y * width,
                                 row_at(above, rows, below, width, n, y + 1), width, run,
                                 quiet[y - y0]);
            for (int x0 = run; x0 < run + 64 && x0 < width && !all; x0 += RETRACE_BLOCK_X)
                for (int y = y0; y < y0 + RETRACE_BLOCK_Y && y < n; y++) {
                    const uint32_t *up = row_at(above, rows, below, width, n, y - 1);
                    const uint32_t *here = rows + (size_t)y * width;
                    const uint32_t *down = row_at(above, rows, below, width, n, y + 1);
                    for (int x = x0; x < x0 + RETRACE_BLOCK_X && x < width; x++)
                        if (!quiet[y - y0][x - run] && marked(up, here, down, width, x))
                            list[count++] = (uint32_t)((size_t)y * width + x);
                }
        }
    return count;
}
