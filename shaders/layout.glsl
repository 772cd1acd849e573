// layout.glsl: the GPU structs as the shader sees them (std430).
// Twin of host/gpu_layout_types.h; keep field order and types identical.
// `real`, `rvec3` and `rvec4` are float or double (see trace.comp).

struct Frame {
    rvec4 eye;
    rvec4 u;
    rvec4 v;
    rvec4 w;
    vec4 ambient;
    vec4 background;
    ivec4 counts; // width, height, point lights, objects
};

struct Light {
    rvec4 pos;
    vec4 color;
    vec4 att;
};

struct Pigment {
    vec4 color1;
    vec4 color2;
    rvec4 params; // x: checker side
    ivec4 kind;
};

struct Finish {
    vec4 phong;  // ka kd ks n
    vec4 optics; // kr kt ior
};

struct Object {
    rvec4 geom; // sphere: center, radius; plane: unit normal, d
    ivec4 ids;  // kind, pigment, finish
};

layout(std430, set = 0, binding = TP2_BINDING_FRAME) readonly buffer FrameBuf { Frame frame; };
layout(std430, set = 0, binding = TP2_BINDING_LIGHTS) readonly buffer LightBuf { Light lights[]; };
layout(std430, set = 0, binding = TP2_BINDING_PIGMENTS) readonly buffer PigmentBuf { Pigment pigments[]; };
layout(std430, set = 0, binding = TP2_BINDING_FINISHES) readonly buffer FinishBuf { Finish finishes[]; };
layout(std430, set = 0, binding = TP2_BINDING_OBJECTS) readonly buffer ObjectBuf { Object objects[]; };
layout(std430, set = 0, binding = TP2_BINDING_IMAGE) writeonly buffer ImageBuf { vec4 pixels[]; };

// The tile this dispatch covers, in pixels.
layout(push_constant) uniform Tile { ivec2 tile_origin; };
