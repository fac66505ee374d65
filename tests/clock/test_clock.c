/* test_clock.c — the one clock (ss_clock.h).
 *
 * Properties: the wall clock never goes back and agrees with CLOCK_MONOTONIC
 * read directly between two of its readings; the CPU clock is non-negative
 * and never goes back; a busy loop advances both, the CPU clock by no more
 * than the wall clock (one thread); a sleep advances the wall clock by the
 * time slept and the CPU clock by almost nothing (so it is not the wall clock
 * under another name); the lap adds exactly the CPU time between its two
 * readings and restarts at the second. */
#include <time.h>

#include "ss_clock.h"
#include "ss_test.h"

static double direct_monotonic(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Spin until the CPU clock has advanced by `sec` (or 10 s of wall time). */
static double busy(double sec) {
  volatile double x = 1;
  const double c0 = ss_clock_cpu(), w0 = ss_clock_wall();
  while (ss_clock_cpu() - c0 < sec && ss_clock_wall() - w0 < 10)
    for (int i = 0; i < 10000; i++)
      x = x * 1.0000001 + 1e-9;
  return x;
}

int main(void) {
  /* monotone, and the same clock as CLOCK_MONOTONIC */
  double w = ss_clock_wall(), c = ss_clock_cpu();
  CHECK(c >= 0, "cpu clock %g < 0", c);
  int back_w = 0, back_c = 0, outside = 0;
  for (int i = 0; i < 100000; i++) {
    const double w1 = ss_clock_wall(), d = direct_monotonic(), w2 = ss_clock_wall();
    const double c1 = ss_clock_cpu();
    back_w += w1 < w || w2 < w1;
    back_c += c1 < c;
    outside += d < w1 || d > w2;
    w = w2, c = c1;
  }
  CHECK(back_w == 0, "the wall clock went back %d times", back_w);
  CHECK(back_c == 0, "the cpu clock went back %d times", back_c);
  CHECK(outside == 0, "CLOCK_MONOTONIC outside its neighbours %d times", outside);

  /* a busy loop advances both, CPU <= wall (one thread) */
  const double w0 = ss_clock_wall(), c0 = ss_clock_cpu();
  CHECK(busy(0.05) > 0, "busy loop");
  const double dw = ss_clock_wall() - w0, dc = ss_clock_cpu() - c0;
  CHECK(dc >= 0.05, "cpu advanced %g s in a 0.05 s busy loop", dc);
  CHECK(dw >= 0.05, "wall advanced %g s in a 0.05 s busy loop", dw);
  CHECK(dc <= dw + 0.005, "cpu %g s > wall %g s for one thread", dc, dw);

  /* a sleep advances the wall clock, not the CPU clock */
  const double w3 = ss_clock_wall(), c3 = ss_clock_cpu();
  nanosleep(&(struct timespec){0, 100000000}, NULL);
  const double sw = ss_clock_wall() - w3, sc = ss_clock_cpu() - c3;
  CHECK(sw >= 0.099, "wall advanced %g s in a 0.1 s sleep", sw);
  CHECK(sc < 0.05, "cpu advanced %g s in a 0.1 s sleep", sc);

  /* the lap: acc gains exactly the time between the readings, t0 restarts */
  double acc = 0.25, t0 = ss_clock_cpu();
  const double t_old = t0;
  busy(0.01);
  ss_clock_lap(&acc, &t0);
  CHECK(t0 >= t_old + 0.01, "lap restarted at %g, %g s after the start", t0, t0 - t_old);
  CHECK(acc == 0.25 + (t0 - t_old), "lap added %.17g, the readings differ by %.17g",
        acc - 0.25, t0 - t_old);
  const double acc1 = acc, t1 = t0;
  ss_clock_lap(&acc, &t0);
  CHECK(acc >= acc1 && t0 >= t1, "a second lap went back");
  return ss_test_done("clock");
}
