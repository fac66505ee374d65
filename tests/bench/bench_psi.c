/* bench_psi.c — the price of judging psi on its polynomial pieces (issue 34):
 * for MLCA vertex cases with k = 8, 10 and 12 (seeded random links, as
 * bench_certify: `enumerate random --seed 1`), the time per case of the
 * double-precision pipeline without psi, with psi (box depth SS_PSI_BOX_DEPTH),
 * with the exact path (certify, no psi) and with both (certify and psi: the
 * pieces proven where psi decides, ss_psi_certify), and with the spokes'
 * tubes proven too (certify, psi at box depth 2, psi_tubes: ss_psi_tube),
 * measured side by side in one run, best of three each; prints the times, the
 * ratios to the double path, psi's verdicts (certified ones: proven), its mean
 * covered share and how many the tubes make proven passes.
 * One core.
 * `bench_psi [SAMPLES]` (default 4 links per k). */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <flint/flint.h>
#include <gsl/gsl_rng.h>

#include "ss_link_random.h"
#include "ss_pipeline.h"
#include "ss_scheme.h"

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Best of three wall times of one case; the last pipeline kept in *keep. */
static double best(const ss_scheme *s, const ss_case *c, int psi, int certify, int tubes,
                   ss_pipeline **keep) {
  ss_pipeline_opts o = ss_pipeline_defaults();
  o.psi_depth = psi;
  o.certify = certify;
  o.psi_tubes = tubes;
  double t = 1e300;
  for (int rep = 0; rep < 3; rep++) {
    ss_error err = {0};
    ss_pipeline *p = NULL;
    const double t0 = now();
    if (ss_pipeline_compute(s, c, &o, SS_PIPE_VERDICTS, NULL, &p, &err)) {
      fprintf(stderr, "bench_psi: %s\n", err.msg);
      exit(1);
    }
    const double dt = now() - t0;
    t = dt < t ? dt : t;
    if (rep == 2 && keep)
      *keep = p;
    else
      ss_pipeline_free(p);
  }
  return t;
}

int main(int argc, char **argv) {
  const int samples = argc > 1 ? atoi(argv[1]) : 4;
  if (samples < 1) {
    fprintf(stderr, "usage: bench_psi [SAMPLES]\n");
    return 2;
  }
  ss_scheme *s = NULL;
  ss_error err = {0};
  if (ss_scheme_new("mlca", &s, &err)) {
    fprintf(stderr, "bench_psi: %s\n", err.msg);
    return 1;
  }
  printf("psi on its pieces vs the double and certified paths, MLCA vertex cases, %d "
         "random links per k (seed 1), best of 3 each, one core\n\n"
         " k  double s/case  +psi s/case  ratio  certify s/case  ratio  certify+psi "
         "s/case  ratio  psi pass/fail/undecided (proven)  mean covered  tubes s/case  "
         "ratio  proven pass/fail\n",
         samples);
  for (int k = 8; k <= 12; k += 2) {
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(g, 1UL);
    double td = 0.0, tp = 0.0, tc = 0.0, tcp = 0.0, tt = 0.0, cov = 0.0;
    int n[3] = {0, 0, 0}, ran = 0, proven = 0, tpass = 0, tfail = 0;
    for (int i = 0; i < samples; i++) {
      ss_link *l = NULL;
      if (ss_link_random(k, g, &l, &err)) {
        fprintf(stderr, "bench_psi: %s\n", err.msg);
        return 1;
      }
      const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
      ss_pipeline *p = NULL;
      td += best(s, &c, 0, 0, 0, NULL);
      tp += best(s, &c, SS_PSI_BOX_DEPTH, 0, 0, &p);
      tc += best(s, &c, 0, 1, 0, NULL);
      ss_pipeline *q = NULL, *u = NULL;
      tcp += best(s, &c, SS_PSI_BOX_DEPTH, 1, 0, &q);
      tt += best(s, &c, 2, 1, 1, &u);
      if (u->psi.ran && u->psi.verdict.certified) {
        tpass += u->psi.verdict.verdict == SS_PASS;
        tfail += u->psi.verdict.verdict == SS_FAIL;
      }
      ss_pipeline_free(u);
      if (p->psi.ran) {
        ran++;
        n[p->psi.verdict.verdict]++;
        cov += p->psi.covered;
      }
      proven += q->psi.ran && q->psi.verdict.certified;
      ss_pipeline_free(q);
      ss_pipeline_free(p);
      ss_link_free(l);
    }
    gsl_rng_free(g);
    printf(
        "%2d  %13.4f  %11.4f  %5.1f  %14.4f  %5.1f  %18.4f  %5.1f  %d/%d/%d of %d (%d)  "
        "%12.4f  %12.4f  %5.1f  %d/%d\n",
        k, td / samples, tp / samples, tp / td, tc / samples, tc / td, tcp / samples,
        tcp / td, n[SS_PASS], n[SS_FAIL], n[SS_UNDECIDED], samples, proven,
        ran ? cov / ran : 0.0, tt / samples, tt / td, tpass, tfail);
    fflush(stdout);
  }
  ss_scheme_free(s);
  flint_cleanup_master();
  return 0;
}
