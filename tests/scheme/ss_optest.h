/* ss_optest.h — helpers for tests of refinement operators. */
#ifndef SS_OPTEST_H
#define SS_OPTEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>

#include "ss_scheme.h"
#include "ss_test.h"

/* Refine once with the operator; aborts the test program on failure. */
static inline ss_cx *op_refine(const char *scheme, const ss_cx *cx, gsl_spmatrix **R) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *fine = NULL;
  if (ss_scheme_new(scheme, &s, &err) || ss_scheme_refine(s, cx, &fine, R, &err)) {
    fprintf(stderr, "refine with %s failed: %s\n", scheme, err.msg);
    exit(1);
  }
  ss_scheme_free(s);
  return fine;
}

/* Every row of R sums to 1 (checked here independently of the library). */
static inline void check_row_sums(const gsl_spmatrix *R, const char *what) {
  double worst = 0;
  size_t bad = 0;
  for (size_t r = 0; r < R->size1; r++) {
    double s = 0;
    for (int q = R->p[r]; q < R->p[r + 1]; q++)
      s += R->data[q];
    if (fabs(s - 1) > worst) worst = fabs(s - 1);
    if (fabs(s - 1) > 1e-14) bad++;
  }
  CHECK(bad == 0, "%s: %zu rows do not sum to 1 (worst deviation %g)", what, bad, worst);
}

/* The positions path (no operator) and the operator path agree. */
static inline void check_paths_agree(const char *scheme, const ss_cx *cx,
                                     const char *what) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *a = NULL, *b = NULL;
  gsl_spmatrix *R = NULL;
  if (ss_scheme_new(scheme, &s, &err) || ss_scheme_refine(s, cx, &a, NULL, &err) ||
      ss_scheme_refine(s, cx, &b, &R, &err)) {
    CHECK(0, "%s: refine failed: %s", what, err.msg);
    return;
  }
  double worst = 0;
  for (size_t i = 0; i < a->nv * (size_t)a->dim; i++)
    if (fabs(a->x[i] - b->x[i]) > worst) worst = fabs(a->x[i] - b->x[i]);
  CHECK(a->nv == b->nv && worst <= 1e-13,
        "%s: positions path and operator path differ by %g", what, worst);
  gsl_spmatrix_free(R);
  ss_cx_free(a);
  ss_cx_free(b);
  ss_scheme_free(s);
}

#endif
