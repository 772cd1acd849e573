/* spirv_specialize.h: a shader with the code its specialization constants
 * rule out taken away before the driver sees it. */
#ifndef TP2_SPIRV_SPECIALIZE_H
#define TP2_SPIRV_SPECIALIZE_H

#include <stddef.h>
#include <stdint.h>

/* lavapipe turns the whole module into its IR, inlining every call, and
 * only then drops what the specialization constants rule out: most of the
 * time it takes to make a pipeline goes to code that cannot run (docs/decisions.md). This finds, by sparse conditional constant propagation
 * over 32-bit integers and booleans (Wegman and Zadeck), the blocks of
 * each function that cannot run with the constants `values` (indexed by
 * SpecId; ids from `count` on keep the module's defaults), empties them,
 * and removes the functions no longer called and the names and
 * decorations of what went with them. The module stays valid SPIR-V and
 * means the same under those constants (which it still declares, and the
 * pipeline still sets): what is left runs exactly as before.
 *
 * Returns a malloc'd module (*out_words its length), or NULL when `code`
 * is malformed, uses something this does not follow (then the caller
 * keeps the original), or memory runs out. */
uint32_t *spirv_specialize(const uint32_t *code, size_t words, const int32_t *values,
                           size_t count, size_t *out_words);

#endif
