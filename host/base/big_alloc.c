/* big_alloc.c: see big_alloc.h. Page faults are most of what packing a
 * million objects costs on some machines (a paravirtualized guest here:
 * ~15% of all samples under perf); huge pages where the kernel grants them
 * (transparent_hugepage "madvise" or "always") take that away, and
 * elsewhere this is plain malloc. */
#define _DEFAULT_SOURCE /* madvise's MADV_HUGEPAGE */
#include "big_alloc.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#define HUGE_PAGE ((size_t)2 << 20)

void *big_alloc(size_t n)
{
    if (n == 0)
        return NULL;
    if (n < HUGE_PAGE)
        return malloc(n);
    size_t rounded = big_alloc_capacity(n);
    if (rounded == 0)
        return NULL;
    void *p = aligned_alloc(HUGE_PAGE, rounded);
#ifdef MADV_HUGEPAGE
    if (p)
        madvise(p, rounded, MADV_HUGEPAGE); /* advice: failure changes nothing */
#endif
    return p;
}

void *big_realloc(void *p, size_t n)
{
    void *bigger = realloc(p, n);
#ifdef MADV_HUGEPAGE
    if (bigger && n >= HUGE_PAGE) {
        uintptr_t page = (uintptr_t)sysconf(_SC_PAGESIZE);
        uintptr_t begin = (uintptr_t)bigger / page * page;
        uintptr_t end = ((uintptr_t)bigger + n + page - 1) / page * page;
        madvise((void *)begin, end - begin, MADV_HUGEPAGE); /* advice only */
    }
#endif
    return bigger;
}

size_t big_alloc_capacity(size_t n)
{
    if (n < HUGE_PAGE || n > SIZE_MAX - HUGE_PAGE)
        return 0;
    return (n + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
}

void *big_calloc(size_t count, size_t size)
{
    if (size != 0 && count > SIZE_MAX / size)
        return NULL;
    void *p = big_alloc(count * size);
    if (p)
        memset(p, 0, count * size);
    return p;
}

void big_advise(void *p, size_t n)
{
#ifdef MADV_HUGEPAGE
    uintptr_t begin = ((uintptr_t)p + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
    uintptr_t end = ((uintptr_t)p + n) / HUGE_PAGE * HUGE_PAGE;
    if ((uintptr_t)p <= UINTPTR_MAX - n && end > begin)
        madvise((void *)begin, end - begin, MADV_HUGEPAGE);
#else
    (void)p;
    (void)n;
#endif
}
