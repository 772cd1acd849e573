/* cli.h: the command line of SPEC 1. */
#ifndef TP2_CLI_H
#define TP2_CLI_H

#include <stdbool.h>
#include <stdio.h>

struct cli {
    const char *infile, *outfile;
    int width, height; /* 0 when not given */
    int device_index;  /* -1: the best device */
    int samples;       /* --spp: samples per pixel; 0: the scene's */
    int bvh_min;       /* --bvh-min: BVH from this many spheres; 0: default */
    double bailout;    /* --bailout: least weight of a traced ray; 0: all
                        * are traced; default 1/255, 0 with --precision double */
    enum precision { PRECISION_AUTO, PRECISION_MIXED, PRECISION_FLOAT, PRECISION_DOUBLE } precision;
                       /* --precision; under auto (the default) and mixed
                        * main.c may choose double for a scene float cannot
                        * carry */
    bool validate;     /* --validate or TP2_VALIDATE=1 */
    bool stats;        /* --stats: phase times and ray counts on stderr */
    bool quiet;        /* --quiet: no progress bar */
    bool dump_scene;   /* --dump-scene: print the parsed scene as JSON */
    bool help, version, list_devices;
};

/* The default --bailout, POV-Ray's default adc_bailout: a ray this faint
 * adds at most one 8-bit level where radiance is at most 1 (docs/design.md has the
 * proof, docs/accuracy.md the measured error). */
#define TP2_DEFAULT_BAILOUT (1.0 / 255.0)

/* Fills c from argv. Returns 0, or -1 after printing "tp2: ..." and a hint
 * to stderr (a usage error: exit status 2). */
int cli_parse(int argc, char **argv, struct cli *c);

/* The --help text (usage.h). */
void cli_usage(FILE *out);

#endif
