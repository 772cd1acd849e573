/* usage.h: the text of tp2 --help, and the one source of the man page
 * (tools/gen_man.c turns it into tp2.1 at build time).
 *
 * Its shape is what the generator reads: the first line "usage: ...",
 * then a paragraph; "heading:" lines start sections; in a section, a line
 * indented two spaces starts an item (term, two or more spaces, text) and
 * lines indented further continue it. */
#ifndef TP2_USAGE_H
#define TP2_USAGE_H

#define TP2_USAGE_TEXT                                                        \
    "usage: tp2 [options] infile.txt outfile.{ppm,png,pfm} [X Y]\n"           \
    "       tp2 --dump-scene infile.txt\n"                                    \
    "\n"                                                                      \
    "Ray traces a scene file (see README.TXT) into an image of X by Y\n"      \
    "pixels (default: the scene's own size, else 400 300). The image is\n"    \
    "written to a temporary file beside the output and renamed over it.\n"    \
    "\n"                                                                      \
    "options:\n"                                                              \
    "  --device N           render on device N of --list-devices\n"           \
    "                       (default: discrete GPU, then integrated,\n"       \
    "                       then virtual, then CPU)\n"                        \
    "  --list-devices       list the Vulkan devices and exit\n"               \
    "  --dump-scene         print the scene as tp2 read it, as JSON, to\n"    \
    "                       stdout and exit (no output file, no device)\n"    \
    "  --precision P        auto (default), mixed, float or double.\n"        \
    "                       double: double-precision geometry, the\n"         \
    "                       reference image; mixed: float, then the\n"        \
    "                       pixels where rounding can flip a decision\n"      \
    "                       (which object, shadow, checker cell) again\n"     \
    "                       in double (in software where the device\n"        \
    "                       has none); auto: double on a CPU device\n"        \
    "                       that has it (lavapipe), else mixed\n"             \
    "  --spp N              samples per pixel (overrides the scene's\n"       \
    "                       'samples'; default 1, the pixel center)\n"        \
    "  --stats              print phase times and rays traced to stderr\n"    \
    "  --bailout W          do not trace reflected or transmitted rays\n"     \
    "                       whose weight (product of kr, kt, fog) is\n"       \
    "                       below W, like POV-Ray's adc_bailout (default\n"   \
    "                       1/255; 0 with --precision double: the exact\n"    \
    "                       model)\n"                                         \
    "  --bvh-min N          trace bounded objects through the BVH when\n"     \
    "                       there are at least N (default 16; a knob)\n"      \
    "  --quiet              no progress bar\n"                                \
    "  --validate           enable the Khronos validation layer; any\n"       \
    "                       message fails the run (also TP2_VALIDATE=1)\n"    \
    "  --version            print the version and the git revision it\n"      \
    "                       was built from, and exit\n"                       \
    "  --help               show this text and exit\n"                        \
    "\n"                                                                      \
    "exit status:\n"                                                          \
    "  0                    the image was written\n"                          \
    "  1                    failure: a bad scene, no device, an output\n"     \
    "                       that cannot be written (nothing is written)\n"    \
    "  2                    usage error\n"                                    \
    "\n"                                                                      \
    "environment:\n"                                                          \
    "  TP2_VALIDATE=1       as --validate\n"                                  \
    "  XDG_CACHE_HOME       compiled pipelines are cached in\n"               \
    "                       $XDG_CACHE_HOME/tp2 (else ~/.cache/tp2)\n"        \
    "  VK_DRIVER_FILES      Vulkan driver files to use instead of the\n"      \
    "                       installed ones (also VK_ICD_FILENAMES)\n"

#endif
