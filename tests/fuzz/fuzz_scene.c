/* fuzz_scene.c: libFuzzer target for the scene parser (scene_parse_text)
 * and for what follows it in tp2 before any Vulkan: --dump-scene's JSON
 * and packing into the shader's buffers, where sizes are computed.
 *
 * The scene is named TP2_FUZZ_FILES/fuzz.txt, so the files it names
 * (texmap, mesh) are looked up in tests/fuzz/files/, which holds small
 * images and meshes under the names the seed scenes use. An input that
 * could name a device or a kernel file (any "dev/", "proc/" or "sys/")
 * is skipped: /dev/zero or /dev/stdin as a texture would only measure the
 * machine. Also built into fuzz_replay_scene (tests/fuzz/replay.c). */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_json.h"
#include "scene_pack.h"
#include "scene_parse.h"

#ifndef TP2_FUZZ_FILES
#error "TP2_FUZZ_FILES: the folder of tests/fuzz/files"
#endif
#define FUZZ_SCENE_NAME TP2_FUZZ_FILES "/fuzz.txt"

static int contains(const uint8_t *data, size_t size, const char *word)
{
    size_t n = strlen(word);
    for (size_t i = 0; i + n <= size; i++)
        if (memcmp(data + i, word, n) == 0)
            return 1;
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (contains(data, size, "dev/") || contains(data, size, "proc/") ||
        contains(data, size, "sys/"))
        return 0;
    struct scene s;
    char err[SCENE_ERROR_SIZE(sizeof FUZZ_SCENE_NAME)];
    if (scene_parse_text(FUZZ_SCENE_NAME, (const char *)data, size, &s, err,
                         sizeof err) != 0) {
        /* The contract: one line, never empty, and *out zeroed. */
        if (err[0] == '\0' || strchr(err, '\n') || s.nobjects || s.objects)
            abort();
        return 0;
    }
    static FILE *null_out;
    if (!null_out)
        null_out = fopen("/dev/null", "w");
    if (null_out)
        scene_write_json(&s, null_out);
    /* Both precisions, the BVH forced on or left to its threshold, a
     * double twin (--precision auto: near twins searched) or none: which
     * is picked from the input's length, so each input replays alike. */
    struct pack_options opt = {
        .width = s.has_size ? s.width : 400,
        .height = s.has_size ? s.height : 300,
        .use_double = size & 1,
        .bvh_min = size & 2 ? 1 : 0,
        .bailout = 1.0 / 255,
    };
    struct packed_scene p, twin;
    bool with_twin = size & 4 && !opt.use_double;
    if (scene_pack(&s, &opt, &p, with_twin ? &twin : NULL) == 0) {
        for (int b = 0; b < TP2_INPUT_BUFFERS; b++)
            if (!p.data[b] || p.size[b] == 0)
                abort(); /* every buffer holds at least one element */
        packed_scene_free(&p);
        if (with_twin)
            packed_scene_free(&twin);
    }
    scene_free(&s);
    return 0;
}
