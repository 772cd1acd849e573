#include "cli.h"

#include "test_hooks.h"
#include "lexer.h"
#include "scene.h"
#include "usage.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

void cli_usage(FILE *out)
{
    fputs(TP2_USAGE_TEXT, out);
}

/* Prints "tp2: " fmt (with arg escaped as lexer_escape does: arguments
 * can hold any bytes) and a hint; returns -1. */
static int usage_error(const char *fmt, const char *arg)
{
    char *shown = lexer_escape(arg);
    fputs("tp2: ", stderr);
    fprintf(stderr, fmt, shown ? shown : "?");
    fputs("\ntp2: see 'tp2 --help'\n", stderr);
    free(shown);
    return -1;
}

/* A decimal integer in [lo, hi], the whole string, digits only (no sign
 * or white space, as counts in a scene); -1 if not. */
static int parse_int(const char *s, long lo, long hi, int *out)
{
    char *end;
    if (*s < '0' || *s > '9')
        return -1;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || *end || v < lo || v > hi)
        return -1;
    *out = (int)v;
    return 0;
}

/* A number in [0, 1], the whole string; -1 if not. */
static int parse_weight(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end || !(v >= 0 && v <= 1))
        return -1;
    *out = v;
    return 0;
}

/* Consumes the value of option argv[*i]; NULL if missing. */
static const char *option_value(int argc, char **argv, int *i)
{
    if (*i + 1 >= argc)
        return NULL;
    return argv[++*i];
}

static int parse_option(int argc, char **argv, int *i, struct cli *c)
{
    const char *opt = argv[*i];
    const char *v;
    if (strcmp(opt, "--help") == 0 || strcmp(opt, "-h") == 0) {
        c->help = true;
    } else if (strcmp(opt, "--version") == 0) {
        c->version = true;
    } else if (strcmp(opt, "--list-devices") == 0) {
        c->list_devices = true;
    } else if (strcmp(opt, "--dump-scene") == 0) {
        c->dump_scene = true;
    } else if (strcmp(opt, "--validate") == 0) {
        c->validate = true;
    } else if (strcmp(opt, "--stats") == 0) {
        c->stats = true;
    } else if (strcmp(opt, "--quiet") == 0) {
        c->quiet = true;
    } else if (strcmp(opt, "--bailout") == 0) {
        if (!(v = option_value(argc, argv, i)) || parse_weight(v, &c->bailout) != 0)
            return usage_error("--bailout needs a weight from 0 to 1, found '%s'",
                               v ? v : "nothing");
    } else if (strcmp(opt, "--bvh-min") == 0) {
        if (!(v = option_value(argc, argv, i)) ||
            parse_int(v, 1, INT_MAX, &c->bvh_min) != 0)
            return usage_error("--bvh-min needs a positive number of spheres, found '%s'",
                               v ? v : "nothing");
    } else if (strcmp(opt, "--spp") == 0) {
        if (!(v = option_value(argc, argv, i)) ||
            parse_int(v, 1, TP2_MAX_SAMPLES, &c->samples) != 0)
            return usage_error("--spp needs a number of samples from 1 to 4096, found '%s'",
                               v ? v : "nothing");
    } else if (strcmp(opt, "--device") == 0) {
        if (!(v = option_value(argc, argv, i)) ||
            parse_int(v, 0, INT_MAX, &c->device_index) != 0)
            return usage_error("--device needs a device index, found '%s'",
                               v ? v : "nothing");
    } else if (strcmp(opt, "--precision") == 0) {
        v = option_value(argc, argv, i);
        if (v && strcmp(v, "auto") == 0)
            c->precision = PRECISION_AUTO;
        else if (v && strcmp(v, "mixed") == 0)
            c->precision = PRECISION_MIXED;
        else if (v && strcmp(v, "float") == 0)
            c->precision = PRECISION_FLOAT;
        else if (v && strcmp(v, "double") == 0)
            c->precision = PRECISION_DOUBLE;
        else
            return usage_error("--precision needs 'auto', 'mixed', 'float' or 'double', "
                               "found '%s'",
                               v ? v : "nothing");
    } else {
        return usage_error("unknown option '%s'", opt);
    }
    return 0;
}

int cli_parse(int argc, char **argv, struct cli *c)
{
    memset(c, 0, sizeof *c);
    c->device_index = -1;
    c->bailout = -1; /* not given: set below from the precision */
    c->validate = test_hooks()->validate;
    const char *positional[4];
    int npos = 0;
    bool options_done = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!options_done && strcmp(a, "--") == 0) {
            options_done = true;
        } else if (!options_done && a[0] == '-' && a[1] != '\0' &&
                   !(a[1] >= '0' && a[1] <= '9')) { /* "-1" is a (bad) size */
            if (parse_option(argc, argv, &i, c) != 0)
                return -1;
        } else if (npos == 4) {
            return usage_error("unexpected argument '%s'", a);
        } else {
            positional[npos++] = a;
        }
    }
    if (c->bailout < 0) /* the reference image prunes nothing */
        c->bailout = c->precision == PRECISION_DOUBLE ? 0.0 : TP2_DEFAULT_BAILOUT;
    if (c->help || c->version || c->list_devices)
        return 0;
    if (c->dump_scene) {
        if (npos != 1)
            return usage_error("%s", "--dump-scene takes one scene file, and no output");
        c->infile = positional[0];
        return 0;
    }
    if (npos != 2 && npos != 4)
        return usage_error("%s", npos < 2 ? "expected an input and an output file"
                                          : "expected both X and Y, or neither");
    c->infile = positional[0];
    c->outfile = positional[1];
    if (npos == 4) {
        if (parse_int(positional[2], 1, TP2_MAX_IMAGE_SIDE, &c->width) != 0)
            return usage_error("X must be a positive integer up to 32768, found '%s'",
                               positional[2]);
        if (parse_int(positional[3], 1, TP2_MAX_IMAGE_SIDE, &c->height) != 0)
            return usage_error("Y must be a positive integer up to 32768, found '%s'",
                               positional[3]);
    }
    return 0;
}
