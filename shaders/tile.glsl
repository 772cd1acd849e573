// tile.glsl: the push constants of every dispatch (struct gpu_tile in
// host/pack/gpu_layout.h; unit_layout checks the two agree), shared by
// trace.comp (through layout.glsl) and finish.comp.
//
// What this dispatch covers: a band of pixels (or the listed ones of it),
// which of their samples, and how many rays a walk may trace in it
// (TP2_WALK_START, _CONTINUE). finish.comp reads list_length alone: the
// band's pixels.
layout(push_constant) uniform Tile {
    ivec2 tile_origin;
    int sample_index;
    int pass_rays;       // rays each walk may trace in this pass
    int walk_capacity;   // walks the walk buffers hold
    int accept_cut;      // 1: pass_rays is 1 and still cut: keep what there is
    int tile_rows;       // rows of the band; with signatures, one more is traced
    int list_length;     // pixels in pixel_list (TP2_SPEC_PIXEL_LIST)
};
