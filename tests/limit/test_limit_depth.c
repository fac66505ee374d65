/* test_limit_depth.c — limit evaluation (ss_limit) at extreme depth: points
 * 2^-1074 .. 2^-40 from an extraordinary vertex, edge or the boundary
 * (issue 35, items 2-4 and 6).
 *
 * Properties:
 *   - the growth law at MLCA's icosahedron vertex (a defective run: 1/8 has a
 *     Jordan block): with lambda the run's subdominant eigenvalue (found here
 *     by power iteration on the run's own matrix W, not by the library's
 *     eigen-solver), the Jacobian at 2^-(j+1) x0 is 2 lambda times the one at
 *     2^-j x0, to 1e-10, at depths j = 70 .. 1072 -- not at one depth only
 *     (the entries grow like d^(-1 - log2 lambda) = d^-0.331); ccsolid at the
 *     same vertex (not defective) likewise;
 *   - the Jacobian against the reference (repeated local subdivision, no
 *     eigenvalues) at 2^-58 and 2^-40 from the vertex, to 1e-11 of its size;
 *   - near an edge of valence 5 (5 wedges x 3 layers, straight along z, the
 *     point (d, d, 1/2)): the across rows growing by 2 mu per halving (mu the
 *     across eigenvalue, by power iteration); the along row, and every number
 *     finite down to 2^-1074, in test_limit_along.c;
 *   - parameters down to the smallest subnormal on a plain grid: finite, the
 *     Jacobian continuous with the one at 2^-60;
 *   - ccsolid's Jacobian on boundary edges and at boundary corners of grids
 *     (a double eigenvalue 1/2 that LAPACK returns as 0.5 +- 1.7e-16i, or
 *     with nearly parallel eigenvectors): defined and equal to the limit of
 *     the Jacobians at 2^-200 inside (at a corner 0: the components' largest
 *     eigenvalue, 0.41, is below 1/2). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit.h"
#include "ss_limit_impl.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testmesh.h"

static double jnorm(double J[3][3]) {
  double m = 0.0;
  for (int i = 0; i < 3; i++)
    for (int d = 0; d < 3; d++)
      m = fmax(m, fabs(J[i][d]));
  return m;
}

static int all_finite(ss_limit_point *p) {
  for (int d = 0; d < 3; d++) {
    if (!isfinite(p->p[d])) return 0;
    for (int i = 0; i < 3; i++)
      if (!isfinite(p->jac[i][d])) return 0;
  }
  return 1;
}

/* The largest |eigenvalue| other than 1 of the first stationary run the
 * evaluator has met (a transition from a state to itself in the inherited
 * frame), by power iteration on differences (the rows of W sum to 1, so
 * x - x_0 1 carries every eigenvalue but 1); 0 if there is none. */
static double run_subdominant(const ss_limit *L) {
  for (size_t i = 0; i < L->nst; i++)
    for (int k = 0; k < 8; k++) {
      const ss_lim_trans *t = L->st[i]->tr[k];
      if (!t || t->next != i || !ss_lim_frame_is_id(&t->g)) continue;
      const size_t K = L->st[i]->patch.nv;
      double *x = malloc(K * sizeof *x), *y = malloc(K * sizeof *y), lam = 0.0;
      srand(11);
      for (size_t r = 0; r < K; r++)
        x[r] = rand() / (double)RAND_MAX - 0.5;
      for (int it = 0; it < 400; it++) {
        double nx = 0.0, ny = 0.0;
        for (size_t r = 0; r < K; r++) {
          y[r] = 0.0;
          for (size_t c = 0; c < K; c++)
            y[r] += t->W[r * K + c] * x[c];
        }
        for (size_t r = K; r-- > 0;) {
          y[r] -= y[0];
          nx += x[r] * x[r];
        }
        for (size_t r = 0; r < K; r++)
          ny += y[r] * y[r];
        lam = sqrt(ny / nx);
        for (size_t r = 0; r < K; r++)
          x[r] = y[r] / sqrt(ny);
      }
      free(x);
      free(y);
      return lam;
    }
  return 0.0;
}

/* The growth law along the ray x0 2^-j (w scaled too if scale_w, else kept:
 * towards an edge along w): J(2^-(j+1) x0) = 2 lambda J(2^-j x0)
 * asymptotically (the subdominant component dominates after j steps); rows
 * `rows` (bits) are compared. */
static void check_growth(ss_limit *L, size_t cell, const double x0[3], int scale_w,
                         unsigned rows, int jmin, int jmax, const char *what) {
  ss_error err = {0};
  ss_limit_point a, b;
  REQUIRE_OK_VOID(ss_limit_eval(L, cell, ldexp(x0[0], -jmin), ldexp(x0[1], -jmin),
                                scale_w ? ldexp(x0[2], -jmin) : x0[2], 1, &a, &err),
                  &err);
  const double lam = run_subdominant(L);
  CHECK(lam > 0.5 && lam < 1.0, "%s: subdominant eigenvalue %g", what, lam);
  double worst = 0.0;
  int fails = 0;
  for (int j = jmin; j < jmax; j++) {
    double x[3] = {ldexp(x0[0], -j), ldexp(x0[1], -j),
                   scale_w ? ldexp(x0[2], -j) : x0[2]};
    double y[3] = {x[0] / 2, x[1] / 2, scale_w ? x[2] / 2 : x[2]};
    if (ss_limit_eval(L, cell, x[0], x[1], x[2], 1, &a, &err) ||
        ss_limit_eval(L, cell, y[0], y[1], y[2], 1, &b, &err)) {
      CHECK(0, "%s: depth %d: %s", what, j, err.msg);
      return;
    }
    CHECK(all_finite(&a) && all_finite(&b), "%s: depth %d: not finite", what, j);
    double scale = 0.0, off = 0.0;
    for (int i = 0; i < 3; i++) {
      if (!((rows >> i) & 1u)) continue;
      for (int d = 0; d < 3; d++) {
        scale = fmax(scale, fabs(b.jac[i][d]));
        off = fmax(off, fabs(b.jac[i][d] - 2.0 * lam * a.jac[i][d]));
      }
    }
    double rel = off / scale;
    if (rel > worst) worst = rel;
    if (!(rel <= 1e-10) && fails++ < 5)
      CHECK(0, "%s: depth %d: J(d/2) - 2 lambda J(d) = %g of |J|, lambda %.15g", what, j,
            rel, lam);
  }
  CHECK(fails == 0, "%s: the growth law failed at %d depths", what, fails);
  printf("%s: J(d/2) = 2 lambda J(d), lambda = %.12f, depths %d..%d: worst %.2g\n", what,
         lam, jmin, jmax, worst);
}

/* The walk against the reference at x (cell c). */
static void check_reference(ss_limit *L, size_t c, const double x[3], double tol,
                            const char *what) {
  ss_error err = {0};
  ss_limit_point a, b;
  REQUIRE_OK_VOID(ss_limit_eval(L, c, x[0], x[1], x[2], 1, &a, &err), &err);
  REQUIRE_OK_VOID(ss_limit_eval_reference(L, c, x[0], x[1], x[2], 1, 80, &b, &err), &err);
  double off = 0.0;
  for (int i = 0; i < 3; i++)
    for (int d = 0; d < 3; d++)
      off = fmax(off, fabs(a.jac[i][d] - b.jac[i][d]));
  double rel = off / jnorm(b.jac);
  CHECK(rel <= tol,
        "%s at (%g %g %g): Jacobian off the reference by %g of |J| (%.17g vs %.17g)",
        what, x[0], x[1], x[2], rel, a.jac[0][0], b.jac[0][0]);
  printf("%s at (%g %g %g): |J| %.3g, off the reference by %.2g of |J|\n", what, x[0],
         x[1], x[2], jnorm(b.jac), rel);
}

static void test_icosahedron(ss_scheme *s, const char *name) {
  ss_error err = {0};
  tm_link *l = tm_link_named("icosahedron");
  ss_cx *h = tm_hex_star(l);
  tm_jitter(h, 0.05, 5);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, h, &L, &err), &err);
  char what[96];
  snprintf(what, sizeof what, "%s, icosahedron vertex", name);
  const double x0[3] = {0.75, 0.625, 0.5625};
  check_growth(L, 0, x0, 1, 7u, 150, 1069, what);
  const double r1[3] = {0.75 * 0x1p-58, 0.625 * 0x1p-58, 0.5625 * 0x1p-58};
  const double r2[3] = {0.3 * 0x1p-40, 0.7 * 0x1p-40, 0.1 * 0x1p-40};
  check_reference(L, 0, r1, 1e-11, what);
  check_reference(L, 7, r2, 1e-11, what);
  ss_limit_free(L);
  ss_cx_free(h);
  tm_link_free(l);
}

/* (d, d, 1/2) in the middle layer's first wedge of 5 wedges x 3 layers: the
 * growth law of the rows across the edge. */
static void test_edge(ss_scheme *s, const char *name) {
  ss_error err = {0};
  ss_cx *e = tm_edge_ring(5, 1, 3);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, e, &L, &err), &err);
  char what[96];
  snprintf(what, sizeof what, "%s, edge of valence 5", name);
  const double x0[3] = {0.75, 0.75, 0.5};
  check_growth(L, 5, x0, 0, 3u, 300, 1071, what);
  ss_limit_free(L);
  ss_cx_free(e);
}

/* Subnormal parameters on a plain grid, near the boundary and a corner. */
static void test_subnormal(ss_scheme *s, const char *name) {
  ss_error err = {0};
  ss_cx *g = tm_hex_grid(3, 3, 3);
  tm_jitter(g, 0.1, 17);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  const double tiny[] = {0x1p-60, 0x1p-500, 0x1p-1022, 1e-310, 0x1p-1074};
  for (int q = 0; q < 2; q++) {
    ss_limit_point ref, p;
    double y = q ? 0x1p-60 : 0.3;
    REQUIRE_OK_VOID(ss_limit_eval(L, 0, tiny[0], y, 0.6, 1, &ref, &err), &err);
    for (size_t t = 1; t < sizeof tiny / sizeof tiny[0]; t++) {
      double v = q ? tiny[t] : y;
      if (ss_limit_eval(L, 0, tiny[t], v, 0.6, 1, &p, &err)) {
        CHECK(0, "%s: u = %g: %s", name, tiny[t], err.msg);
        continue;
      }
      CHECK(all_finite(&p), "%s: u = %g: not finite", name, tiny[t]);
      double off = 0.0;
      for (int i = 0; i < 3; i++)
        for (int d = 0; d < 3; d++)
          off = fmax(off, fabs(p.jac[i][d] - ref.jac[i][d]));
      CHECK(off <= 1e-9 * fmax(1.0, jnorm(ref.jac)),
            "%s: u = %g, v = %g: Jacobian off the one at 2^-60 by %g", name, tiny[t], v,
            off);
    }
  }
  ss_limit_free(L);
  ss_cx_free(g);
}

/* The Jacobian on boundary edges and at boundary corners of an n^3 grid:
 * defined, and the limit of the ones just inside. */
static void test_boundary(ss_scheme *s, const char *name, int n) {
  ss_error err = {0};
  ss_cx *g = tm_hex_grid(n, n, n);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  const double xs[][3] = {{0.5, 0, 0}, {0, 0.5, 1}, {0.5, 1, 0},  {0, 0, 0.5},
                          {0, 0, 0},   {1, 1, 1},   {0.25, 0, 1}, {0, 0.5, 0.5}};
  for (size_t q = 0; q < sizeof xs / sizeof xs[0]; q++) {
    ss_limit_point p, in;
    double y[3];
    for (int a = 0; a < 3; a++)
      y[a] = xs[q][a] == 0 ? 0x1p-200 : xs[q][a];
    if (ss_limit_eval(L, 0, xs[q][0], xs[q][1], xs[q][2], 1, &p, &err)) {
      CHECK(0, "%s grid %d at (%g %g %g): %s", name, n, xs[q][0], xs[q][1], xs[q][2],
            err.msg);
      continue;
    }
    CHECK(all_finite(&p), "%s grid %d at (%g %g %g): not finite", name, n, xs[q][0],
          xs[q][1], xs[q][2]);
    if (xs[q][0] == 1 || xs[q][1] == 1 || xs[q][2] == 1)
      continue; /* 1 - 2^-53: too near */
    REQUIRE_OK_VOID(ss_limit_eval(L, 0, y[0], y[1], y[2], 1, &in, &err), &err);
    double off = 0.0;
    for (int i = 0; i < 3; i++)
      for (int d = 0; d < 3; d++)
        off = fmax(off, fabs(p.jac[i][d] - in.jac[i][d]));
    CHECK(all_finite(&p) && off <= 1e-9,
          "%s grid %d at (%g %g %g): Jacobian off the one "
          "2^-200 inside by %g",
          name, n, xs[q][0], xs[q][1], xs[q][2], off);
  }
  ss_limit_free(L);
  ss_cx_free(g);
}

int main(void) {
  const char *names[2] = {"mlca", "ccsolid"};
  for (int i = 0; i < 2; i++) {
    ss_error err = {0};
    ss_scheme *s;
    REQUIRE_OK(ss_scheme_new(names[i], &s, &err), &err);
    test_icosahedron(s, names[i]);
    test_edge(s, names[i]);
    test_subnormal(s, names[i]);
    for (int n = 1; n <= 3; n++)
      test_boundary(s, names[i], n);
    ss_scheme_free(s);
  }
  return ss_test_done("limit_depth");
}
