/* spirv_test.h: checks shared by the tests of tp2's SPIR-V passes
 * (spirv_exact, spirv_fused, spirv_specialize). Header-only, included once
 * by each test program after unit.h; spirv_valid needs SPIRV-Tools linked
 * in (tests/CMakeLists.txt) where it is called. */
#ifndef TP2_SPIRV_TEST_H
#define TP2_SPIRV_TEST_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <spirv-tools/libspirv.h>

enum { SPIRV_TEST_HEADER = 5 };

/* Whether SPIRV-Tools' validator accepts the module for Vulkan 1.1 (its
 * message printed, prefixed by `what`, when not). */
static inline bool spirv_valid(const char *what, const uint32_t *code, size_t words)
{
    spv_context context = spvContextCreate(SPV_ENV_VULKAN_1_1);
    spv_diagnostic diagnostic = NULL;
    spv_result_t r = spvValidateBinary(context, code, words, &diagnostic);
    if (r != SPV_SUCCESS)
        printf("%s: %s\n", what, diagnostic ? diagnostic->error : "invalid");
    spvDiagnosticDestroy(diagnostic);
    spvContextDestroy(context);
    return r == SPV_SUCCESS;
}

/* A pass of spirv_exact's and spirv_fused's form. */
typedef uint32_t *spirv_pass(const uint32_t *code, size_t words, size_t *out_words,
                             size_t *sites);

/* That `pass` refuses (NULL) a copy of the module `code` (`bytes` long)
 * made malformed: shorter than its header, a wrong magic number, an
 * instruction of 0 words, an instruction cut by the module's end. */
static inline void spirv_check_refused(spirv_pass *pass, const uint32_t *code, size_t bytes)
{
    size_t words = bytes / 4, n, sites;
    uint32_t *copy = malloc(bytes);
    memcpy(copy, code, bytes);
    expect(pass(copy, 4, &n, &sites) == NULL, "a module shorter than its header");
    copy[0] ^= 1;
    expect(pass(copy, words, &n, &sites) == NULL, "a wrong magic number");
    copy[0] ^= 1;
    uint32_t first = copy[SPIRV_TEST_HEADER];
    copy[SPIRV_TEST_HEADER] &= 0xffffu; /* a word count of 0 */
    expect(pass(copy, words, &n, &sites) == NULL, "an instruction of 0 words");
    copy[SPIRV_TEST_HEADER] = first;
    expect(copy[SPIRV_TEST_HEADER] >> 16 == 2 &&
               pass(copy, SPIRV_TEST_HEADER + 1, &n, &sites) == NULL,
           "an instruction cut by the module's end");
    free(copy);
}

#endif
