// soft_double_native.glsl: the software double library's interface
// (shaders/soft_double.glsl) done with the device's own doubles, for
// tests: with it, the double build lowered by host/gpu/spirv_soft_double.c
// must render byte for byte what the unlowered one does, which checks the
// pass apart from the library. A double is its IEEE binary64 bits, .x the
// low word (packDouble2x32's convention). Every body keeps to double
// scalars (no double locals, constants or vectors): the pass leaves these
// functions as they are and keeps only that much of Float64 for them.

uvec2 sd_add(uvec2 a, uvec2 b) { return unpackDouble2x32(packDouble2x32(a) + packDouble2x32(b)); }
uvec2 sd_sub(uvec2 a, uvec2 b) { return unpackDouble2x32(packDouble2x32(a) - packDouble2x32(b)); }
uvec2 sd_mul(uvec2 a, uvec2 b) { return unpackDouble2x32(packDouble2x32(a) * packDouble2x32(b)); }
uvec2 sd_div(uvec2 a, uvec2 b) { return unpackDouble2x32(packDouble2x32(a) / packDouble2x32(b)); }
uvec2 sd_neg(uvec2 a) { return unpackDouble2x32(-packDouble2x32(a)); }
uvec2 sd_abs(uvec2 a) { return unpackDouble2x32(abs(packDouble2x32(a))); }
uvec2 sd_sqrt(uvec2 a) { return unpackDouble2x32(sqrt(packDouble2x32(a))); }
uvec2 sd_floor(uvec2 a) { return unpackDouble2x32(floor(packDouble2x32(a))); }
uvec2 sd_fract(uvec2 a) { return unpackDouble2x32(fract(packDouble2x32(a))); }
uvec2 sd_min(uvec2 a, uvec2 b) { return unpackDouble2x32(min(packDouble2x32(a), packDouble2x32(b))); }
uvec2 sd_max(uvec2 a, uvec2 b) { return unpackDouble2x32(max(packDouble2x32(a), packDouble2x32(b))); }
bool sd_lt(uvec2 a, uvec2 b) { return packDouble2x32(a) < packDouble2x32(b); }
bool sd_le(uvec2 a, uvec2 b) { return packDouble2x32(a) <= packDouble2x32(b); }
bool sd_gt(uvec2 a, uvec2 b) { return packDouble2x32(a) > packDouble2x32(b); }
bool sd_ge(uvec2 a, uvec2 b) { return packDouble2x32(a) >= packDouble2x32(b); }
bool sd_eq(uvec2 a, uvec2 b) { return packDouble2x32(a) == packDouble2x32(b); }
bool sd_une(uvec2 a, uvec2 b) { return !(packDouble2x32(a) == packDouble2x32(b)); }
uvec2 sd_from_float(float f) { return unpackDouble2x32(double(f)); }
float sd_to_float(uvec2 a) { return float(packDouble2x32(a)); }
uvec2 sd_from_int(int i) { return unpackDouble2x32(double(i)); }
int sd_to_int(uvec2 a) { return int(packDouble2x32(a)); }
