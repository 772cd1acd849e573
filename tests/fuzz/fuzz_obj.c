/* fuzz_obj.c: libFuzzer target for the OBJ reader (obj_read). The input is
 * handed over as a FILE through fmemopen, as mesh_read hands a file.
 * Also built into fuzz_replay_obj (tests/fuzz/replay.c). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "obj_read.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0) /* fmemopen refuses an empty buffer */
        return 0;
    /* A copy: fmemopen wants a writable buffer even to read. */
    char *copy = malloc(size);
    if (!copy)
        return 0;
    memcpy(copy, data, size);
    FILE *f = fmemopen(copy, size, "rb");
    if (!f) {
        free(copy);
        return 0;
    }
    struct obj_mesh m;
    char err[512];
    if (obj_read(f, "fuzz.obj", &m, err, sizeof err) == 0) {
        /* Every corner the reader hands on is a finite number. */
        for (size_t i = 0; i < 9 * m.ntri; i++)
            if (!isfinite(m.tri[i]))
                abort();
        obj_mesh_free(&m);
    } else if (err[0] == '\0' || strchr(err, '\n') || m.tri || m.ntri) {
        abort(); /* one line of error, *out zeroed */
    }
    fclose(f);
    free(copy);
    return 0;
}
