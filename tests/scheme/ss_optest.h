/* ss_optest.h — helpers for tests of refinement operators. */
#ifndef SS_OPTEST_H
#define SS_OPTEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>

#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testmesh.h"

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

/* Cubic B-spline subdivision mask by fine-minus-twice-coarse offset. */
static inline double op_bspline(int off) {
  switch (off < 0 ? -off : off) {
  case 0:
    return 3.0 / 4.0;
  case 1:
    return 1.0 / 2.0;
  case 2:
    return 1.0 / 8.0;
  default:
    return 0.0;
  }
}

/* Check that R on the periodic d-grid is the tensor-product B-spline rule:
 * R(f, p) = prod_i b(q_i - 2 p_i) with offsets taken modulo 2N. */
static inline void op_check_tensor_rule(const char *scheme, int d, int N) {
  ss_cx *cx = tm_torus(d, N);
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *fine = NULL;
  ss_cx *lin = NULL;
  ss_split *L = NULL;
  gsl_spmatrix *R = NULL;
  if (ss_scheme_new(scheme, &s, &err) || ss_scheme_refine(s, cx, &fine, &R, &err) ||
      ss_split_refine(ss_scheme_split_kind(s), cx, &lin, &L, &err)) {
    CHECK(0, "refine failed: %s", err.msg);
    return;
  }
  const int P = 2 * N; /* fine period */
  size_t bad = 0, nnz_expected = 0;
  for (size_t f = 0; f < fine->nv; f++) {
    /* fine lattice point: sum of parents' coordinates, unwrapped, times 2/n */
    int q[3] = {0, 0, 0};
    size_t np = ss_split_npar(L, f);
    int first[3] = {0, 0, 0};
    for (size_t k = L->ptr[f]; k < L->ptr[f + 1]; k++) {
      size_t p = L->parent[k];
      int c[3] = {(int)(p % (size_t)N), (int)((p / (size_t)N) % (size_t)N),
                  (int)(p / (size_t)(N * N))};
      for (int i = 0; i < d; i++) {
        if (k == L->ptr[f]) first[i] = c[i];
        int dc = c[i] - first[i];
        if (dc > N / 2) dc -= N;
        if (dc < -N / 2) dc += N;
        q[i] += 2 * (first[i] + dc);
      }
    }
    for (int i = 0; i < d; i++)
      q[i] = (int)(q[i] / (int)np);
    size_t nexp = 0;
    for (size_t p = 0; p < cx->nv; p++) {
      int c[3] = {(int)(p % (size_t)N), (int)((p / (size_t)N) % (size_t)N),
                  (int)(p / (size_t)(N * N))};
      double w = 1.0;
      for (int i = 0; i < d; i++) {
        int off = ((q[i] - 2 * c[i]) % P + P) % P;
        if (off > P / 2) off -= P;
        w *= op_bspline(off);
      }
      if (w != 0.0) nexp++;
      double got = gsl_spmatrix_get(R, f, p);
      if (fabs(got - w) > 1e-15) {
        if (bad < 5)
          fprintf(stderr, "%s d=%d: R(%zu,%zu) = %.17g, tensor rule %.17g\n", scheme, d,
                  f, p, got, w);
        bad++;
      }
    }
    nnz_expected += nexp;
  }
  CHECK(bad == 0,
        "%s on the periodic %d-grid: %zu entries differ from the tensor-product "
        "cubic B-spline rule",
        scheme, d, bad);
  CHECK(R->nz == nnz_expected, "%s d=%d: %zu nonzeros, tensor rule has %zu", scheme, d,
        R->nz, nnz_expected);
  check_row_sums(R, scheme);
  gsl_spmatrix_free(R);
  ss_split_free(L);
  ss_cx_free(lin);
  ss_cx_free(fine);
  ss_cx_free(cx);
  ss_scheme_free(s);
}

#endif
