#define _POSIX_C_SOURCE 200809L
#include "progress.h"

#include <stdio.h>
#include <unistd.h>

#include "clock.h"

#define TP2_BAR_WIDTH 40

void progress_start(struct progress *p, bool enabled)
{
    p->enabled = enabled && isatty(STDERR_FILENO);
    p->drawn = false;
    p->start = clock_seconds();
}

void progress_update(struct progress *p, double fraction)
{
    if (!p->enabled)
        return;
    double elapsed = clock_seconds() - p->start;
    if (elapsed < 1.0)
        return;
    int filled = (int)(fraction * TP2_BAR_WIDTH + 0.5);
    char bar[TP2_BAR_WIDTH + 1];
    for (int i = 0; i < TP2_BAR_WIDTH; i++)
        bar[i] = i < filled ? '#' : '.';
    bar[TP2_BAR_WIDTH] = '\0';
    double left = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
    fprintf(stderr, "\rtp2: [%s] %3.0f%%  %.0f s left ", bar, fraction * 100, left);
    fflush(stderr);
    p->drawn = true;
}

void progress_finish(struct progress *p)
{
    if (p->drawn)
        fprintf(stderr, "\r%*s\r", TP2_BAR_WIDTH + 32, "");
}
