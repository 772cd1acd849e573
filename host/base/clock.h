/* clock.h: a monotonic wall clock for --stats and the progress bar. */
#ifndef TP2_CLOCK_H
#define TP2_CLOCK_H

/* Seconds since an arbitrary fixed point; only differences mean anything. */
double clock_seconds(void);

#endif
