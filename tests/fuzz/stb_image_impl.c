/* stb_image_impl.c: stb_image compiled here, for the fuzz build only, so
 * that its code is instrumented (Debian's libstb is not). */
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
