/* tp2: ray traces a scene file on a Vulkan device (README.TXT, SPEC.md). */
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "image_write.h"
#include "render.h"
#include "scene.h"
#include "scene_parse.h"
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

static int render_to_file(const struct cli *c, const struct scene *s)
{
    struct render_options opt = {
        .device_index = c->device_index,
        .use_double = c->use_double,
        .validate = c->validate,
    };
    image_size(c, s, &opt.width, &opt.height);
    float *rgba = malloc((size_t)opt.width * (size_t)opt.height * 4 * sizeof *rgba);
    if (!rgba) {
        fputs("tp2: out of memory for the image\n", stderr);
        return EXIT_FAILURE;
    }
    int rc = render_scene(s, &opt, rgba);
    if (rc == 0 && vkc_validation_message_count() > 0) {
        fprintf(stderr, "tp2: %u validation message(s); no image written\n",
                vkc_validation_message_count());
        rc = -1;
    }
    if (rc == 0)
        rc = image_write(c->outfile, image_format_of(c->outfile), opt.width,
                         opt.height, rgba);
    free(rgba);
    return rc == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

int main(int argc, char **argv)
{
    struct cli c;
    if (cli_parse(argc, argv, &c) != 0)
        return EXIT_USAGE;
    if (c.help) {
        cli_usage(stdout);
        return EXIT_SUCCESS;
    }
    if (c.list_devices)
        return vkc_list_devices(stdout) == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
    if (image_format_of(c.outfile) == IMAGE_UNKNOWN) {
        fprintf(stderr, "tp2: cannot tell the format of '%s': name it .ppm, "
                        ".png or .pfm\n", c.outfile);
        return EXIT_USAGE;
    }
    struct scene s;
    char err[512];
    if (scene_parse_file(c.infile, &s, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return EXIT_FAILURE;
    }
    int rc = render_to_file(&c, &s);
    scene_free(&s);
    return rc;
}
