/* bench_certify.c — the price of certified verdicts (issue 15): for MLCA and
 * tet/oct vertex cases with k = 8, 10 and 12 (the same seeded random links
 * for both paths: `enumerate random --seed 1`), the time per case of the
 * whole double-precision pipeline (ss_result_compute) and of the same with
 * the exact path (certify), measured side by side in one run, best of three
 * repetitions per case; prints both, their ratio, and how many verdicts were
 * proven.  One core.  `bench_certify [SAMPLES]` (default 6 links per k).
 * `bench_certify loop`: the same for Loop's surface vertices of valence 3..50
 * (most proven by the Fourier blocks in balls, ss_fourier.h; 3, 4 and 6
 * exactly). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <flint/flint.h>
#include <gsl/gsl_rng.h>

#include "ss_link_random.h"
#include "ss_result.h"
#include "ss_scheme.h"

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Best of three wall times of one case; its result (certify) into *r. */
static double best(const ss_scheme *s, const ss_case *c, int certify, ss_result *r) {
  ss_result_opts o = ss_result_defaults();
  o.certify = certify;
  double t = 1e300;
  for (int rep = 0; rep < 3; rep++) {
    ss_error err = {0};
    ss_result x;
    const double t0 = now();
    if (ss_result_compute(s, c, &o, &x, &err)) {
      fprintf(stderr, "bench_certify: %s\n", err.msg);
      exit(1);
    }
    const double dt = now() - t0;
    t = dt < t ? dt : t;
    if (rep == 2)
      *r = x;
    else
      ss_result_clear(&x);
  }
  return t;
}

/* Loop's surface vertices, one line per valence. */
static int bench_loop(void) {
  static const int valences[] = {3, 4, 5, 6, 7, 10, 15, 20, 30, 40, 50};
  ss_scheme *s = NULL;
  ss_error err = {0};
  if (ss_scheme_new("loop", &s, &err)) {
    fprintf(stderr, "bench_certify: %s\n", err.msg);
    return 1;
  }
  printf("certified vs double-precision verdicts, Loop's surface vertices, best of 3 "
         "each, one core\n\n"
         "  n  double s/case  certified s/case  ratio  proven\n");
  for (size_t i = 0; i < sizeof valences / sizeof *valences; i++) {
    const ss_case c = {SS_CASE_SURFACE_VERTEX, NULL, valences[i], SS_DIAG_BFS, 0};
    ss_result rd, rc;
    const double td = best(s, &c, 0, &rd), tc = best(s, &c, 1, &rc);
    printf("%3d  %13.4f  %16.4f  %5.1f  %s\n", valences[i], td, tc, tc / td,
           ss_result_certified(&rc) ? "yes" : "no");
    fflush(stdout);
    ss_result_clear(&rd);
    ss_result_clear(&rc);
  }
  ss_scheme_free(s);
  flint_cleanup_master();
  return 0;
}

int main(int argc, char **argv) {
  if (argc > 1 && !strcmp(argv[1], "loop")) return bench_loop();
  const int samples = argc > 1 ? atoi(argv[1]) : 6;
  if (samples < 1) {
    fprintf(stderr, "usage: bench_certify [SAMPLES]\n");
    return 2;
  }
  const char *schemes[2] = {"mlca", "tetoct"};
  printf("certified vs double-precision verdicts, vertex cases, %d random links per k "
         "(seed 1), best of 3 each, one core\n\n"
         "scheme  k   double s/case  certified s/case  ratio  proven verdicts\n",
         samples);
  for (int q = 0; q < 2; q++) {
    ss_scheme *s = NULL;
    ss_error err = {0};
    if (ss_scheme_new(schemes[q], &s, &err)) {
      fprintf(stderr, "bench_certify: %s\n", err.msg);
      return 1;
    }
    for (int k = 8; k <= 12; k += 2) {
      gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
      gsl_rng_set(g, 1UL);
      double td = 0.0, tc = 0.0;
      int proven = 0;
      for (int i = 0; i < samples; i++) {
        ss_link *l = NULL;
        if (ss_link_random(k, g, &l, &err)) {
          fprintf(stderr, "bench_certify: %s\n", err.msg);
          return 1;
        }
        const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
        ss_result rd, rc;
        td += best(s, &c, 0, &rd);
        tc += best(s, &c, 1, &rc);
        proven += ss_result_certified(&rc);
        ss_result_clear(&rd);
        ss_result_clear(&rc);
        ss_link_free(l);
      }
      gsl_rng_free(g);
      printf("%-7s %2d  %13.4f  %16.4f  %5.1f  %d of %d\n", schemes[q], k, td / samples,
             tc / samples, tc / td, proven, samples);
      fflush(stdout);
    }
    ss_scheme_free(s);
  }
  flint_cleanup_master();
  return 0;
}
