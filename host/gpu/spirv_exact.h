/* spirv_exact.h: the double build's geometry evaluated as written, on
 * every device. */
#ifndef TP2_SPIRV_EXACT_H
#define TP2_SPIRV_EXACT_H

#include <stddef.h>
#include <stdint.h>

/* The double build is the exact image's model, and the default's retrace
 * settles in it the decisions float cannot (docs/accuracy.md). Where a
 * point lies exactly on a decision's boundary (a checker cell face
 * through a row of pixel centers, as course files with whole-number
 * coordinates have), the last bit of each rounding decides, so a device
 * that fuses a * b + c into one rounding (GPU compilers do, unless told
 * not to) decides such pixels otherwise than lavapipe, which never fuses.
 * This decorates every 64-bit arithmetic result (sum, difference,
 * product, quotient, negation, remainder, dot product, vector and matrix
 * products) NoContraction, SPIR-V's form of GLSL's `precise`, which a
 * device must honor.
 *
 * Returns a malloc'd copy of the SPIR-V module `code` of `words` 32-bit
 * words so decorated (*out_words its length, *sites how many results were
 * decorated, none twice), or NULL when the module is malformed, has no
 * decoration to put them after, or memory runs out. */
uint32_t *spirv_exact(const uint32_t *code, size_t words, size_t *out_words, size_t *sites);

#endif
