/* ss_clock.c — the monotonic wall clock and the thread CPU clock
 * (ss_clock.h). */
#include "ss_clock.h"

#include <time.h>

double ss_clock_wall(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

double ss_clock_cpu(void) {
  struct timespec t;
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t)) return 0.0;
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void ss_clock_lap(double *acc, double *t0) {
  const double t = ss_clock_cpu();
  *acc += t - *t0;
  *t0 = t;
}
