#include "retrace.h"

#include <stdbool.h>

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
 * of them says its boundaries may move (RETRACE_SENSITIVE). */
static bool boundary(uint32_t a, uint32_t b)
{
    bool differ = ((a ^ b) & RETRACE_HASH) != 0 || ((a | b) & RETRACE_STOPPED) != 0;
    return differ && ((a | b) & RETRACE_SENSITIVE) != 0;
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

/* Whether the 3 x 3 pixels around x (not at an edge) all have the word
 * sig, which is not UNSURE: then x is not marked. */
static bool uniform(const uint32_t *up, const uint32_t *here, const uint32_t *down, int x,
                    uint32_t sig)
{
    return !(sig & RETRACE_UNSURE) && up[x - 1] == sig && up[x] == sig && up[x + 1] == sig &&
           here[x - 1] == sig && here[x + 1] == sig && down[x - 1] == sig &&
           down[x] == sig && down[x + 1] == sig;
}

/* Whether pixel x of row y (here) is to be traced again. */
static bool marked(const uint32_t *up, const uint32_t *here, const uint32_t *down, int width,
                   int x)
{
    uint32_t sig = here[x];
    if (x > 0 && x + 1 < width && up && down && uniform(up, here, down, x, sig))
        return false; /* most pixels: the quick answer */
    return (sig & RETRACE_UNSURE) || near_boundary(up, width, x, sig) ||
           near_boundary(here, width, x, sig) || near_boundary(down, width, x, sig);
}

size_t retrace_mark(const uint32_t *above, const uint32_t *rows, const uint32_t *below,
                    int width, int n, uint32_t *list)
{
    size_t count = 0;
    for (int y0 = 0; y0 < n; y0 += RETRACE_BLOCK_Y)
        for (int x0 = 0; x0 < width; x0 += RETRACE_BLOCK_X)
            for (int y = y0; y < y0 + RETRACE_BLOCK_Y && y < n; y++) {
                const uint32_t *up = row_at(above, rows, below, width, n, y - 1);
                const uint32_t *here = rows + (size_t)y * width;
                const uint32_t *down = row_at(above, rows, below, width, n, y + 1);
                for (int x = x0; x < x0 + RETRACE_BLOCK_X && x < width; x++)
                    if (marked(up, here, down, width, x))
                        list[count++] = (uint32_t)((size_t)y * width + x);
            }
    return count;
}
