#define _POSIX_C_SOURCE 200809L
#include "tempfile.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Temporary files that can exist at once: the output and the cache. */
#define TEMPFILE_SLOTS 4

/* A slot's path is complete before `used` is set (release) and read by
 * the handler only after seeing it set (acquire). */
static struct {
    atomic_int used;
    char path[PATH_MAX];
} slots[TEMPFILE_SLOTS];

static const int guarded_signals[] = {SIGINT, SIGTERM, SIGHUP};
#define NSIGNALS (sizeof guarded_signals / sizeof guarded_signals[0])

/* Async-signal-safe: atomic loads, unlink and raise only. SA_RESETHAND
 * has restored the default action, and the signal stays blocked until the
 * handler returns, so the raise ends the process right after. */
static void on_signal(int sig)
{
    int saved = errno;
    for (int i = 0; i < TEMPFILE_SLOTS; i++)
        if (atomic_load_explicit(&slots[i].used, memory_order_acquire))
            unlink(slots[i].path);
    errno = saved;
    raise(sig);
}

static void signal_set(sigset_t *set)
{
    sigemptyset(set);
    for (size_t i = 0; i < NSIGNALS; i++)
        sigaddset(set, guarded_signals[i]);
}

void tempfile_install_handlers(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sa.sa_flags = SA_RESETHAND;
    signal_set(&sa.sa_mask); /* one handler at a time */
    for (size_t i = 0; i < NSIGNALS; i++) {
        struct sigaction old;
        if (sigaction(guarded_signals[i], NULL, &old) == 0 && old.sa_handler != SIG_IGN)
            sigaction(guarded_signals[i], &sa, NULL);
    }
}

int tempfile_create(char *path)
{
    if (strlen(path) >= PATH_MAX) {
        errno = ENAMETOOLONG;
        return -1;
    }
    sigset_t block, old;
    signal_set(&block);
    pthread_sigmask(SIG_BLOCK, &block, &old);
    int slot = 0;
    while (slot < TEMPFILE_SLOTS && atomic_load(&slots[slot].used))
        slot++;
    int fd = -1;
    if (slot == TEMPFILE_SLOTS) {
        errno = EMFILE;
    } else if ((fd = mkstemp(path)) >= 0) {
        fcntl(fd, F_SETFD, FD_CLOEXEC);
        strcpy(slots[slot].path, path);
        atomic_store_explicit(&slots[slot].used, 1, memory_order_release);
    }
    int saved = errno;
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    errno = saved;
    return fd;
}

void tempfile_forget(const char *path)
{
    for (int i = 0; i < TEMPFILE_SLOTS; i++)
        if (atomic_load(&slots[i].used) && strcmp(slots[i].path, path) == 0)
            atomic_store(&slots[i].used, 0);
}
