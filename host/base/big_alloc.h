/* big_alloc.h: memory for the arrays that grow with the scene (boxes, BVH
 * nodes, packed objects). */
#ifndef TP2_BIG_ALLOC_H
#define TP2_BIG_ALLOC_H

#include <stddef.h>

/* Like malloc (free it with free), but an array of 2 MiB or more is
 * aligned to 2 MiB and offered to the kernel as transparent huge pages,
 * so that touching it costs a page fault per 2 MiB rather than per 4 KiB.
 * NULL when n is 0 or out of memory. */
void *big_alloc(size_t n);

/* Like realloc, for arrays that grow by doubling as a file is read (not
 * for big_alloc's blocks): once the block is 2 MiB or more, the whole of
 * it is offered as transparent huge pages. Whole, so that its mapping
 * stays one piece and realloc can go on moving it without copying
 * (mremap); its 2 MiB-aligned stretches then fault in a page at a time. */
void *big_realloc(void *p, size_t n);

/* The bytes a block of big_alloc(n) owns when it is aligned to 2 MiB (n
 * rounded up to a multiple of 2 MiB), or 0 when it is plain malloc's. */
size_t big_alloc_capacity(size_t n);

/* big_alloc(count * size), zeroed; NULL on overflow too. */
void *big_calloc(size_t count, size_t size);

/* Offers the 2 MiB-aligned whole pages inside [p, p + n), memory that
 * something else allocated and nothing has touched yet (a CPU device's
 * buffer, which is the host's own memory), as transparent huge pages.
 * Advice only: where the kernel declines, nothing changes. */
void big_advise(void *p, size_t n);

#endif
