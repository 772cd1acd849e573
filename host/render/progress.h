/* progress.h: a progress bar on stderr for long renders.
 *
 * Drawn only when enabled, stderr is a terminal and the render has run for
 * a second: short renders and logs stay quiet. */
#ifndef TP2_PROGRESS_H
#define TP2_PROGRESS_H

#include <stdbool.h>

struct progress {
    bool enabled, drawn;
    double start;
};

void progress_start(struct progress *p, bool enabled);

/* fraction in [0, 1] of the work done. */
void progress_update(struct progress *p, double fraction);

/* Clears the bar's line if one was drawn. */
void progress_finish(struct progress *p);

#endif
