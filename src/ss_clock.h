/* ss_clock.h — the one clock of the library and the tool: monotonic wall
 * seconds (for time limits, deadlines and reported durations), this thread's
 * CPU seconds (for per-stage timings), and the lap that adds a stage's CPU
 * time to an accumulator. */
#ifndef SS_CLOCK_H
#define SS_CLOCK_H

#include "ss_api.h"

SS_BEGIN_DECLS

/* Seconds on CLOCK_MONOTONIC: only differences mean anything; never goes
 * back. */
double ss_clock_wall(void);

/* This thread's CPU time in seconds (CLOCK_THREAD_CPUTIME_ID); 0 where the
 * clock is unavailable. */
double ss_clock_cpu(void);

/* Add the CPU time since *t0 (from ss_clock_cpu) to *acc and restart the
 * clock at now. */
void ss_clock_lap(double *acc, double *t0);

SS_END_DECLS

#endif
