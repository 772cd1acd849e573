/* spirv_soft_double.h: the double build with its 64-bit floats done in
 * software, for devices without shaderFloat64. */
#ifndef TP2_SPIRV_SOFT_DOUBLE_H
#define TP2_SPIRV_SOFT_DOUBLE_H

#include <stddef.h>
#include <stdint.h>

/* The double build carries a library of software doubles over uvec2, the
 * IEEE binary64 bits with .x the low word (packDouble2x32's convention),
 * in functions named sd_* (shaders/soft_double_keep.glsl). This rewrites
 * every other function onto it: a double becomes a uvec2, a dvecN an
 * array of N uvec2 (ArrayStride 8 where a buffer lays it out, so that a
 * dvec4 member keeps its 32 bytes at its offset), and structs, arrays,
 * pointers and function types holding them are rebuilt so; arithmetic,
 * comparisons, conversions and abs, sqrt, floor, fract, min, max become
 * calls (one per component), packDouble2x32 and unpackDouble2x32 copies,
 * 64-bit constants their bits. The sd_* functions are left as they are;
 * when they hold no 64-bit float either (the real library is integers
 * only), the module no longer declares any, nor the Float64 capability.
 *
 * Returns a malloc'd module (*out_words its length, *sites the calls it
 * made), or NULL when `code` is malformed, holds a 64-bit construct this
 * does not lower (a matrix, dot, mod, a 64-bit specialization constant,
 * a library function missing ...), or memory runs out. */
uint32_t *spirv_soft_double(const uint32_t *code, size_t words, size_t *out_words,
                            size_t *sites);

#endif
