/* ss_cli_tune_search.c — tune's search with NLopt: a global derivative-free
 * method, then a local one on the epigraph of the smallest margin
 * (ss_cli_tune.h).  Without NLopt (meson option nlopt) tune is refused. */
#include "ss_cli_tune.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if SS_HAVE_NLOPT
#include <nlopt.h>
#endif

int ss_tune_available(void) {
  return SS_HAVE_NLOPT;
}

#if SS_HAVE_NLOPT
/* The global stage's objective: the smallest margin at x. */
static double global_f(unsigned n, const double *x, double *grad, void *ctx) {
  (void)n;
  (void)grad; /* derivative-free methods ask for none */
  return ss_tune_eval(ctx, x);
}

/* The local stage: y = (x, s), maximise s subject to s - margin_i(x) <= 0.
 * NLopt asks for the objective and the constraints at the same y; the
 * margins are computed once per y (the last y is remembered). */
typedef struct {
  ss_tune *t;
  double last[SS_STENCIL_MAXPARAMS]; /* the x of t->margins */
  int have;                          /* last is set */
} epigraph;

static double local_f(unsigned n, const double *y, double *grad, void *ctx) {
  (void)ctx;
  (void)grad;
  return y[n - 1];
}

static void local_c(unsigned m, double *c, unsigned n, const double *y, double *grad,
                    void *ctx) {
  (void)grad;
  epigraph *e = ctx;
  const unsigned k = n - 1;
  if (!e->have || memcmp(e->last, y, k * sizeof *y)) {
    ss_tune_eval(e->t, y);
    memcpy(e->last, y, k * sizeof *y);
    e->have = 1;
  }
  for (unsigned i = 0; i < m; i++)
    c[i] = y[k] - e->t->margins[i];
}

/* The global stage on budget evaluations. */
static int global_stage(ss_tune *t, long budget, char *msg, size_t msgsize) {
  const unsigned n = (unsigned)t->nfree;
  nlopt_opt o = nlopt_create(NLOPT_GN_DIRECT_L, n);
  if (!o) return snprintf(msg, msgsize, "NLopt: out of memory"), -1;
  double x[SS_STENCIL_MAXPARAMS], f = 0.0;
  for (unsigned i = 0; i < n; i++)
    x[i] = 0.5 * (t->lo[i] + t->hi[i]);
  nlopt_set_lower_bounds(o, t->lo);
  nlopt_set_upper_bounds(o, t->hi);
  nlopt_set_max_objective(o, global_f, t);
  nlopt_set_maxeval(o, (int)budget);
  const nlopt_result r = nlopt_optimize(o, x, &f);
  nlopt_destroy(o);
  if (r < 0 && r != NLOPT_ROUNDOFF_LIMITED)
    return snprintf(msg, msgsize, "NLopt's DIRECT_L failed (code %d)", (int)r), -1;
  return 0;
}

/* The local stage from t->bestx on budget evaluations. */
static int local_stage(ss_tune *t, long budget, char *msg, size_t msgsize) {
  const unsigned n = (unsigned)t->nfree + 1, m = (unsigned)t->run->ncases;
  nlopt_opt o = nlopt_create(NLOPT_LN_COBYLA, n);
  double lo[SS_STENCIL_MAXPARAMS + 1], hi[SS_STENCIL_MAXPARAMS + 1];
  double y[SS_STENCIL_MAXPARAMS + 1], step[SS_STENCIL_MAXPARAMS + 1];
  double *tol = calloc(m, sizeof *tol);
  int ok = o && tol;
  for (unsigned i = 0; ok && i + 1 < n; i++) {
    lo[i] = t->lo[i], hi[i] = t->hi[i], y[i] = t->bestx[i];
    step[i] = 0.05 * (hi[i] - lo[i]);
  }
  lo[n - 1] = -11.0, hi[n - 1] = 2.0, y[n - 1] = t->best, step[n - 1] = 0.05;
  epigraph e = {t, {0}, 0};
  double f = 0.0;
  nlopt_result r = NLOPT_SUCCESS;
  if (ok) {
    nlopt_set_lower_bounds(o, lo);
    nlopt_set_upper_bounds(o, hi);
    nlopt_set_max_objective(o, local_f, &e);
    nlopt_add_inequality_mconstraint(o, m, local_c, &e, tol);
    nlopt_set_initial_step(o, step);
    nlopt_set_xtol_rel(o, 1e-7);
    nlopt_set_maxeval(o, (int)budget);
    r = nlopt_optimize(o, y, &f);
  }
  nlopt_destroy(o);
  free(tol);
  if (!ok) return snprintf(msg, msgsize, "NLopt: out of memory"), -1;
  if (r < 0 && r != NLOPT_ROUNDOFF_LIMITED)
    return snprintf(msg, msgsize, "NLopt's COBYLA failed (code %d)", (int)r), -1;
  return 0;
}
#endif

int ss_tune_search(ss_tune *t, long budget, char *msg, size_t msgsize) {
#if !SS_HAVE_NLOPT
  (void)t;
  (void)budget;
  snprintf(msg, msgsize, "this build has no NLopt (meson option nlopt)");
  return -1;
#else
  const long global = budget * 2 / 3;
  t->phase = "global";
  if (global_stage(t, global, msg, msgsize)) return -1;
  t->phase = "local";
  return budget > t->evals ? local_stage(t, budget - t->evals, msg, msgsize) : 0;
#endif
}
