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

/* big_alloc(count * size), zeroed; NULL on overflow too. */
void *big_calloc(size_t count, size_t size);

#endif
