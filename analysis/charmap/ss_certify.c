/* ss_certify.c — the certified path of one case (ss_certify.h). */
#include "ss_certify.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

ss_status ss_certify(const ss_local *M, const ss_case *c, const ss_eig *e,
                     const ss_charmap *cm, const ss_charmap_opts *o, ss_regularity *reg,
                     ss_charmap_inj *inj, ss_certified *out, ss_exact **x,
                     ss_error *err) {
  const double t0 = now();
  memset(out, 0, sizeof *out);
  if (x) *x = NULL;
  reg->certified = inj->certified = 0;
  ss_exact *ex = NULL;
  double *lo = NULL, *hi = NULL;
  ss_exact_opts eo = ss_exact_defaults(M->dim);
  ss_error xe = {0};
  ss_status st = ss_exact_new(M->S, M->n2, M->n1, &eo, &ex, &xe);
  if (st == SS_ENOMEM || st == SS_EINPUT) {
    *err = xe;
    return st;
  }
  if (st) { /* not rational, or FLINT could not: nothing is proven */
    out->cond = e->cond;
    ss_charmap_unproven(&out->cond, xe.msg);
    ss_charmap_unproven(&reg->verdict, "no exact spectrum");
    ss_charmap_unproven(&inj->verdict, "no exact spectrum");
    st = SS_OK;
    goto done;
  }
  ss_exact_condition(ex, &out->cond, &out->cond_certified);
  if (!out->cond_certified) { /* undecided already, with its reason */
    ss_charmap_unproven(&reg->verdict, "the eigenvalue condition is not proven");
    ss_charmap_unproven(&inj->verdict, "the eigenvalue condition is not proven");
  } else if (out->cond.verdict != SS_PASS) {
    /* no characteristic map; keep a failure the double path proved from the
     * spectrum's kind (complex, defective), else there is nothing to judge */
    if (!(cm == NULL && reg->verdict.verdict == SS_FAIL)) {
      reg->verdict.verdict = SS_UNDECIDED;
      snprintf(reg->verdict.reason, sizeof reg->verdict.reason,
               "no characteristic map: the eigenvalue condition fails (certified)");
    }
    inj->verdict.verdict = SS_UNDECIDED;
    snprintf(inj->verdict.reason, sizeof inj->verdict.reason, "no characteristic map");
  } else if (!cm) {
    ss_charmap_unproven(&reg->verdict,
                        "the double-precision path found no characteristic map");
    ss_charmap_unproven(&inj->verdict,
                        "the double-precision path found no characteristic map");
  } else {
    const size_t n = M->n2 * (size_t)cm->dim;
    lo = malloc((n + 1) * sizeof *lo);
    hi = malloc((n + 1) * sizeof *hi);
    if (!lo || !hi) {
      st = ss_error_nomem(err, "basis enclosure");
      goto done;
    }
    ss_error be = {0};
    const ss_status bs = ss_exact_basis(ex, lo, hi, &be);
    if (bs == SS_ENOMEM) {
      st = ss_error_nomem(err, "basis enclosure");
      goto done;
    }
    if (bs) {
      char why[sizeof be.msg + 32];
      snprintf(why, sizeof why, "basis enclosure: %s", be.msg);
      ss_charmap_unproven(&reg->verdict, why);
    } else if ((st = ss_charmap_certify(M, c, lo, hi, cm->dim, eo.maxden, o, reg, inj,
                                        err))) {
      goto done;
    }
  }
done:
  free(lo);
  free(hi);
  out->seconds = now() - t0;
  if (x && !st)
    *x = ex;
  else
    ss_exact_free(ex);
  return st;
}

ss_status ss_certify_verdicts(const ss_scheme *s, const ss_case *c, ss_local *M,
                              const ss_eig *e, const ss_charmap_opts *o, int certify,
                              ss_charmap **cm, ss_regularity *reg, ss_charmap_inj *inj,
                              ss_certified *out, ss_exact **x, ss_error *err) {
  *out = (ss_certified){e->cond, 0, 0.0};
  *inj = (ss_charmap_inj){{SS_UNDECIDED, "no characteristic map"}, 0, 0, 0};
  if (x) *x = NULL;
  ss_status st = ss_charmap_judge(s, c, M, e, o, cm, reg, err);
  if (!st && *cm) {
    double t0 = o->times ? ss_charmap_cpu_seconds() : 0.0;
    st = ss_charmap_injectivity(*cm, reg, inj, err);
    if (o->times) ss_charmap_lap(&o->times->injective, &t0);
  }
  if (!st && certify) st = ss_certify(M, c, e, *cm, o, reg, inj, out, x, err);
  return st;
}
