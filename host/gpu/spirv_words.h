/* spirv_words.h: walking a SPIR-V module word by word, shared by the
 * passes that rewrite tp2's shaders (spirv_specialize.c here; the fused test
 * layer's tests/layers/spirv_fused.c). */
#ifndef TP2_SPIRV_WORDS_H
#define TP2_SPIRV_WORDS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Words before the first instruction (magic, version, generator, id
 * bound, schema), and the largest id bound accepted (tp2's shaders use
 * some 50,000 ids). */
enum { SPIRV_HEADER_WORDS = 5, SPIRV_MAX_BOUND = 1u << 22 };

/* The word count and the opcode of the instruction starting at `at`. */
static inline uint32_t spirv_count(const uint32_t *code, size_t at) { return code[at] >> 16; }
static inline uint32_t spirv_op(const uint32_t *code, size_t at) { return code[at] & 0xffffu; }

/* Whether `code` is a module's header and a run of instructions, each of
 * a word count that fits what is left: what the passes need to walk it. */
static inline bool spirv_well_formed(const uint32_t *code, size_t words)
{
    if (words < SPIRV_HEADER_WORDS || code[0] != 0x07230203u || code[3] == 0 ||
        code[3] > SPIRV_MAX_BOUND)
        return false;
    for (size_t at = SPIRV_HEADER_WORDS; at < words;) {
        uint32_t count = spirv_count(code, at);
        if (count == 0 || count > words - at)
            return false;
        at += count;
    }
    return true;
}

#endif
