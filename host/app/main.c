/* tp2: ray traces a scene file on a Vulkan device (README.TXT, SPEC.md). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "clock.h"
#include "image_write.h"
#include "lexer.h"
#include "render.h"
#include "scene.h"
#include "scene_json.h"
#include "scene_parse.h"
#include "tempfile.h"
#include "tp2_version.h"
#include "vk_context.h"

enum { EXIT_USAGE = 2 };

/* SPEC 1 and 3: the command line's X Y, else the scene's, else 400 x 300. */
static void image_size(const struct cli *c, const struct scene *s, int *w, int *h)
{
    if (c->width) {
        *w = c->width;
        *h = c->height;
    } else if (s->has_size) {
        *w = s->width;
        *h = s->height;
    } else {
        *w = 400;
        *h = 300;
    }
}

/* Where the scene's largest length was written, and what it is, for
 * messages about float's range (scene.c, scene_length_limit). */
struct range_note {
    char where[64 + 4 * 4096]; /* FILE:LINE:COL, the name escaped */
    char what[192];
};

/* Precision for s (scene_length_limit has the rule): as asked, mixed
 * and auto meaning float with a double retrace (*retrace; render.c may
 * turn auto's into double throughout on a CPU device); double where float
 * cannot carry its lengths and --precision float was not asked for, in
 * which case *note is filled; refused (one message, -1) when the lengths
 * are past even double's bound, or past float's under --precision float. */
static int choose_precision(const struct cli *c, const struct scene *s, bool *use_double,
                            bool *retrace, struct range_note *note, bool *noted)
{
    double fmax_len = scene_length_limit(false), dmax_len = scene_length_limit(true);
    *use_double = c->precision == PRECISION_DOUBLE;
    *retrace = c->precision == PRECISION_AUTO || c->precision == PRECISION_MIXED;
    *noted = false;
    if (s->max_length <= fmax_len)
        return 0;
    char *shown = lexer_escape(c->infile);
    snprintf(note->where, sizeof note->where, "%s:%zu:%zu", shown ? shown : "?",
             s->max_length_line, s->max_length_col);
    free(shown);
    if (s->max_length > dmax_len) {
        fprintf(stderr, "%s: error: a coordinate or size of %.3g (%s) is beyond what "
                        "tp2 can render (lengths up to %.3g, in double precision)\n",
                note->where, s->max_length, s->max_length_what, dmax_len);
        return -1;
    }
    if (c->precision == PRECISION_FLOAT) {
        fprintf(stderr, "%s: error: a coordinate or size of %.3g (%s) is beyond float "
                        "precision's range (lengths up to %.3g); leave out --precision "
                        "float to render it in double\n",
                note->where, s->max_length, s->max_length_what, fmax_len);
        return -1;
    }
    if (*retrace) {
        snprintf(note->what, sizeof note->what, "a coordinate or size of %.3g (%s) is beyond "
                 "float precision's range (lengths up to %.3g)", s->max_length,
                 s->max_length_what, fmax_len);
        *use_double = true;
        *retrace = false;
        *noted = true;
    }
    return 0;
}

/* --stats: where the time went and how many rays it bought. */
static void print_stats(const struct render_stats *st, double parse, double write,
                        int width, int height)
{
    static const char *kinds[TP2_STAT_COUNT] = {"camera", "shadow", "reflected",
                                                "transmitted"};
    uint64_t total = 0;
    fprintf(stderr, "tp2: device     %s\n", st->device_name);
    fprintf(stderr, "tp2: precision  %s\n", st->precision);
    fprintf(stderr, "tp2: parse      %8.3f s\n", parse);
    char waited[80] = ""; /* auto: packing waited for the choice of device */
    if (st->device_choice > 0)
        snprintf(waited, sizeof waited, " once the device was chosen, %.3f s in: auto's "
                 "choice needs it", st->device_choice);
    fprintf(stderr, "tp2: device     %8.3f s (instance and device creation, beside bvh and "
                    "upload%s)\n", st->device, waited);
    fprintf(stderr, "tp2: bvh        %8.3f s (%s %llu bounded primitive%s%s; %llu unbounded, "
                    "tested by every ray)\n", st->bvh,
            st->has_bvh ? "building the BVH over" : "no BVH:", (unsigned long long)st->bounded,
            st->bounded == 1 ? "" : "s", st->has_bvh ? "" : ", in a plain loop",
            (unsigned long long)st->unbounded);
    fprintf(stderr, "tp2: upload     %8.3f s (packing and filling the device's buffers",
            st->upload);
    if (st->in_place)
        fprintf(stderr, "; %.1f MiB of them read in place", (double)st->in_place / (1 << 20));
    fputs(")\n", stderr);
    fprintf(stderr, "tp2: pipeline   %8.3f s", st->pipeline);
    if (st->pipeline_beside > 0)
        fprintf(stderr, " (waited for; made in %.3f s beside bvh and upload)",
                st->pipeline_beside);
    fputc('\n', stderr);
    fprintf(stderr, "tp2: render     %8.3f s (%d band%s of %d rows, less readback and "
                    "write)\n", st->render, st->bands, st->bands == 1 ? "" : "s", st->band_rows);
    if (st->retracing)
        fprintf(stderr, "tp2: retrace    %8.3f s (%llu pixels, %.2f%%, again in %sdouble; in "
                        "render)\n", st->retrace, (unsigned long long)st->retraced,
                100.0 * (double)st->retraced / ((double)width * height),
                st->retrace_soft ? "software " : "");
    fprintf(stderr, "tp2: passes     %8u (walks of at most %d rays each)\n", st->passes,
            st->pass_rays);
    fprintf(stderr, "tp2: readback   %8.3f s (finished bands as the file needs them, "
                    "copied from the device)\n",
            st->readback);
    fprintf(stderr, "tp2: write      %8.3f s (encoding and writing rows while the next "
                    "band renders, then closing the file)\n", write);
    for (int i = 0; i < TP2_STAT_COUNT; i++) {
        fprintf(stderr, "tp2: rays %-11s %14llu\n", kinds[i], (unsigned long long)st->rays[i]);
        total += st->rays[i];
    }
    fprintf(stderr, "tp2: rays total       %14llu (%.2f Mrays/s while rendering)\n",
            (unsigned long long)total, st->render > 0 ? total / st->render * 1e-6 : 0.0);
}

/* render_rows_fn: the rows go straight to the file, as 8-bit values
 * quantized on the device unless the file is PFM. */
static int write_rows(void *writer, const void *rows, int first, int count)
{
    (void)first; /* they come in order */
    return image_writer_rows_rgba8(writer, rows, count);
}

static int write_float_rows(void *writer, const void *rows, int first, int count)
{
    (void)first;
    return image_writer_rows(writer, rows, count);
}

/* Opens the output first, so that an unwritable one is reported before
 * the render, then streams the rows into it as bands finish. */
static int render_to_file(const struct cli *c, const struct scene *s, double parse_time)
{
    struct range_note *note = malloc(sizeof *note);
    bool use_double, retrace, noted;
    if (!note) {
        fputs("tp2: out of memory\n", stderr);
        return EXIT_FAILURE;
    }
    if (choose_precision(c, s, &use_double, &retrace, note, &noted) != 0) {
        free(note);
        return EXIT_FAILURE;
    }
    struct render_options opt = {
        .device_index = c->device_index,
        .samples = c->samples,
        .bvh_min = c->bvh_min,
        .bailout = c->bailout,
        .use_double = use_double,
        .retrace = retrace,
        .double_on_cpu = retrace && c->precision == PRECISION_AUTO,
        .double_where = noted ? note->where : NULL,
        .double_what = noted ? note->what : NULL,
        .validate = c->validate,
        .count_rays = c->stats,
        .progress = !c->quiet,
        .quiet = c->quiet,
        .bytes = image_format_of(c->outfile) != IMAGE_PFM,
    };
    struct render_stats stats;
    image_size(c, s, &opt.width, &opt.height);
    struct image_writer *w = image_writer_open(c->outfile, image_format_of(c->outfile),
                                               opt.width, opt.height);
    if (!w) {
        free(note);
        return EXIT_FAILURE;
    }
    int rc = render_scene(s, &opt, opt.bytes ? write_rows : write_float_rows, w, &stats);
    free(note);
    if (rc == 0 && vkc_validation_message_count() > 0) {
        fprintf(stderr, "tp2: %u validation message(s); no image written\n",
                vkc_validation_message_count());
        rc = -1;
    }
    if (rc != 0) {
        image_writer_abort(w);
        return EXIT_FAILURE;
    }
    double t0 = clock_seconds();
    if (image_writer_finish(w) != 0)
        return EXIT_FAILURE;
    if (c->stats)
        print_stats(&stats, parse_time, stats.write + clock_seconds() - t0, opt.width,
                    opt.height);
    return EXIT_SUCCESS;
}

int main(int argc, char **argv)
{
    struct cli c;
    tempfile_install_handlers(); /* before any thread: they inherit it */
    if (cli_parse(argc, argv, &c) != 0)
        return EXIT_USAGE;
    if (c.help) {
        cli_usage(stdout);
        return EXIT_SUCCESS;
    }
    if (c.version) {
        printf("tp2 %s (git %s)\n", TP2_VERSION, TP2_GIT_REVISION);
        return EXIT_SUCCESS;
    }
    if (c.list_devices)
        return vkc_list_devices(stdout) == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
    if (!c.dump_scene && image_format_of(c.outfile) == IMAGE_UNKNOWN) {
        char *shown = lexer_escape(c.outfile);
        fprintf(stderr, "tp2: cannot tell the format of '%s': name it .ppm, "
                        ".png or .pfm\n", shown ? shown : "?");
        free(shown);
        return EXIT_USAGE;
    }
    struct scene s;
    size_t errsize = SCENE_ERROR_SIZE(strlen(c.infile));
    char *err = malloc(errsize);
    if (!err) {
        fputs("tp2: out of memory\n", stderr);
        return EXIT_FAILURE;
    }
    double t0 = clock_seconds();
    int parsed = scene_parse_file(c.infile, &s, err, errsize);
    if (parsed != 0)
        fprintf(stderr, "%s\n", err);
    free(err);
    if (parsed != 0)
        return EXIT_FAILURE;
    int rc;
    if (c.dump_scene)
        rc = scene_write_json(&s, stdout) == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
    else
        rc = render_to_file(&c, &s, clock_seconds() - t0);
    scene_free(&s);
    return rc;
}
