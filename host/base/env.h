/* env.h: reading the TP2_* environment variables with which tests switch
 * tp2 onto one path or another (README.TXT names each where it is used). */
#ifndef TP2_ENV_H
#define TP2_ENV_H

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

/* Whether environment variable name is set to exactly value. */
static inline bool env_is(const char *name, const char *value)
{
    const char *env = getenv(name);
    return env && strcmp(env, value) == 0;
}

/* The whole number environment variable name holds, or `otherwise` where
 * it is unset, empty or not a number. */
static inline long env_number(const char *name, long otherwise)
{
    const char *env = getenv(name);
    char *end;
    long n = env && *env ? strtol(env, &end, 10) : 0;
    return env && *env && *end == '\0' ? n : otherwise;
}

#endif
