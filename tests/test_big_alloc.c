/* test_big_alloc.c: big_alloc's blocks (2 MiB-aligned from 2 MiB on, and
 * how much each owns) and big_realloc growing an array by doubling past
 * 2 MiB, as the parser does, with every byte kept. */
#include <stdint.h>
#include <stdlib.h>

#include "big_alloc.h"
#include "unit.h"

#define MIB ((size_t)1 << 20)

static void check_alloc(void)
{
    CHECK(big_alloc(0) == NULL);
    CHECK(big_alloc_capacity(2 * MIB - 1) == 0);
    CHECK(big_alloc_capacity(2 * MIB) == 2 * MIB);
    CHECK(big_alloc_capacity(2 * MIB + 1) == 4 * MIB);
    CHECK(big_alloc_capacity(SIZE_MAX) == 0);
    CHECK(big_alloc(SIZE_MAX) == NULL);
    CHECK(big_calloc(SIZE_MAX / 2, 4) == NULL); /* count * size overflows */
    unsigned char *p = big_alloc(3 * MIB);
    CHECK(p != NULL && (uintptr_t)p % (2 * MIB) == 0);
    free(p);
    unsigned char *z = big_calloc(5 * MIB, 1);
    size_t nonzero = 0;
    for (size_t i = 0; z && i < 5 * MIB; i++)
        nonzero += z[i] != 0;
    CHECK(z != NULL && nonzero == 0);
    free(z);
}

/* Doubling from 1 KiB to 64 MiB: each step keeps what the steps before
 * wrote, through the moves realloc makes and the advice past 2 MiB. */
static void check_realloc(void)
{
    uint32_t *a = NULL;
    size_t n = 0, wrong = 0;
    for (size_t cap = 256; cap <= 16 * MIB; cap *= 2) {
        uint32_t *bigger = big_realloc(a, cap * sizeof *a);
        CHECK(bigger != NULL);
        if (!bigger)
            break;
        a = bigger;
        for (size_t i = 0; i < n; i++)
            wrong += a[i] != (uint32_t)(i * 2654435761u);
        for (; n < cap; n++)
            a[n] = (uint32_t)(n * 2654435761u);
    }
    expect(wrong == 0, "big_realloc kept every word while doubling (%zu wrong)", wrong);
    free(a);
}

int main(void)
{
    check_alloc();
    check_realloc();
    return unit_report();
}
