# tp2's host sources, one list per stage, in the order a render runs
# through them: a stage never includes a later stage's header nor calls
# its functions, and no files call each other round a circle (the test
# host_layers, tests/check_layers.py, whose list of stages is this one).
#   base    allocation, clocks, temporary files, small maths, test hooks
#           (no tp2 types)
#   scene   scene text -> struct scene: lexer, reader, parser, kind tables
#   pack    struct scene -> the GPU's buffers: records, BVH, twins
#   gpu     the Vulkan device: context, buffers, pipeline cache, SPIR-V
#   render  the passes over the device: pipelines, bands, retrace, progress
#   write   the image file
#   app     main, the command line and its help text
# base, scene and pack need no Vulkan (the fuzz build uses them alone).
set(TP2_HOST ${CMAKE_CURRENT_LIST_DIR})
set(TP2_BASE_SOURCES
  ${TP2_HOST}/base/big_alloc.c
  ${TP2_HOST}/base/clock.c
  ${TP2_HOST}/base/tempfile.c
  ${TP2_HOST}/base/test_hooks.c)
set(TP2_SCENE_SOURCES
  ${TP2_HOST}/scene/convex.c
  ${TP2_HOST}/scene/decimal.c
  ${TP2_HOST}/scene/json_write.c
  ${TP2_HOST}/scene/lexer.c
  ${TP2_HOST}/scene/obj_read.c
  ${TP2_HOST}/scene/pigments.c
  ${TP2_HOST}/scene/scene.c
  ${TP2_HOST}/scene/scene_json.c
  ${TP2_HOST}/scene/scene_parse.c
  ${TP2_HOST}/scene/scene_reader.c
  ${TP2_HOST}/scene/shapes.c
  ${TP2_HOST}/scene/texture.c)
set(TP2_PACK_SOURCES
  ${TP2_HOST}/pack/bvh.c
  ${TP2_HOST}/pack/scene_pack.c
  ${TP2_HOST}/pack/ties.c
  ${TP2_HOST}/pack/twins.c)
set(TP2_GPU_SOURCES
  ${TP2_HOST}/gpu/pipeline_cache.c
  ${TP2_HOST}/gpu/spirv_exact.c
  ${TP2_HOST}/gpu/spirv_soft_body.c
  ${TP2_HOST}/gpu/spirv_soft_double.c
  ${TP2_HOST}/gpu/spirv_soft_types.c
  ${TP2_HOST}/gpu/spirv_specialize.c
  ${TP2_HOST}/gpu/vk_buffer.c
  ${TP2_HOST}/gpu/vk_check.c
  ${TP2_HOST}/gpu/vk_context.c)
set(TP2_RENDER_SOURCES
  ${TP2_HOST}/render/progress.c
  ${TP2_HOST}/render/render.c
  ${TP2_HOST}/render/render_bands.c
  ${TP2_HOST}/render/render_pipelines.c
  ${TP2_HOST}/render/retrace.c)
set(TP2_WRITE_SOURCES
  ${TP2_HOST}/write/image_write.c)
set(TP2_APP_SOURCES
  ${TP2_HOST}/app/cli.c)
set(TP2_MAIN_SOURCE ${TP2_HOST}/app/main.c)
# Headers are included by name ("scene.h"): every stage's folder is on the
# include path.
set(TP2_HOST_INCLUDE_DIRS
  ${TP2_HOST}/base ${TP2_HOST}/scene ${TP2_HOST}/pack ${TP2_HOST}/gpu
  ${TP2_HOST}/render ${TP2_HOST}/write ${TP2_HOST}/app)
