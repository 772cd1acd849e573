/* spirv_fused.h: a shader rewritten to round as a device that fuses float
 * arithmetic would (the rewrite of VK_LAYER_TP2_fused, fused.c). */
#ifndef TP2_SPIRV_FUSED_H
#define TP2_SPIRV_FUSED_H

#include <stddef.h>
#include <stdint.h>

/* GPU compilers contract a * b + c into one fused multiply-add (one
 * rounding instead of two) and compute dot products in fused chains,
 * where the shader does not forbid it (NoContraction, GLSL `precise`);
 * lavapipe never does (gallivm lowers even an explicit fma to a multiply
 * and an add). To render here as such a device would, every 32-bit float
 * sum or difference of a product (OpFAdd or OpFSub with an OpFMul or
 * OpVectorTimesScalar of its type as an operand), and every 32-bit OpDot,
 * neither decorated NoContraction, is computed in double and rounded to
 * float once: a product of floats is exact in double, so this is a fused
 * multiply-add (up to a rare double rounding), and a dot product with one
 * rounding.
 *
 * Returns a malloc'd copy of the SPIR-V module `code` of `words` 32-bit
 * words so rewritten (*out_words its length, *sites how many operations
 * were rewritten); it needs the device's shaderFloat64. NULL when the
 * module is malformed or memory runs out. */
uint32_t *spirv_fused(const uint32_t *code, size_t words, size_t *out_words, size_t *sites);

#endif
