#include "test_hooks.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

static struct test_hooks hooks;
static pthread_once_t read_once = PTHREAD_ONCE_INIT;

static bool is(const char *name, const char *value)
{
    const char *env = getenv(name);
    return env && strcmp(env, value) == 0;
}

/* Set where the variable is an unsigned decimal number, nothing else. */
static struct hook_limit limit_of(const char *name)
{
    const char *env = getenv(name);
    char *end;
    if (!env || *env < '0' || *env > '9')
        return (struct hook_limit){false, 0};
    unsigned long long v = strtoull(env, &end, 10);
    return (struct hook_limit){*end == '\0', v};
}

static void read_hooks(void)
{
    hooks.validate = is("TP2_VALIDATE", "1");
    hooks.band_bytes = limit_of("TP2_BAND_BYTES");
    hooks.storage_range = limit_of("TP2_STORAGE_RANGE");
    hooks.texel_elements = limit_of("TP2_TEXEL_ELEMENTS");
    const char *env = getenv("TP2_EAGER_RETRACE");
    hooks.eager_retrace_set = env && *env;
    hooks.eager_retrace = hooks.eager_retrace_set ? atof(env) : 0;
    hooks.early_pipelines = is("TP2_EARLY_PIPELINES", "1");
    /* a positive whole number, no sign, no leading zero */
    env = getenv("TP2_PASS_RAYS");
    char *end;
    long rays = env && *env >= '1' && *env <= '9' ? strtol(env, &end, 10) : 0;
    hooks.pass_rays = rays > 0 && *end == '\0' ? rays : 0;
    env = getenv("TP2_DISPATCH_SLABS");
    long slabs = env && *env ? strtol(env, &end, 10) : 0;
    hooks.dispatch_slabs_set = env && *env && *end == '\0';
    hooks.dispatch_slabs = hooks.dispatch_slabs_set ? slabs : 0;
    hooks.no_occluder_hint = is("TP2_OCCLUDER_HINT", "0");
    hooks.no_specialize = is("TP2_SPECIALIZE", "0");
    hooks.no_host_import = is("TP2_HOST_IMPORT", "0");
}

const struct test_hooks *test_hooks(void)
{
    pthread_once(&read_once, read_hooks);
    return &hooks;
}

struct test_hooks *test_hooks_edit(void)
{
    pthread_once(&read_once, read_hooks);
    return &hooks;
}

unsigned long long hook_lowered(struct hook_limit hook, unsigned long long limit)
{
    return hook.set && hook.at_most < limit ? hook.at_most : limit;
}
