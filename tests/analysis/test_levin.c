/* test_levin.c — the Levin-Levin sub-patch matrices and reduction against
 * properties that would break if the mathematics were wrong: unit row sums;
 * quadratic precision of the tet/oct face maps checked directly on the
 * support (S_i maps samples of linear functions q at level j to samples of
 * q((. + d_i) / 2) exactly, and of quadratics up to a polynomial of
 * degree <= 1); the eigenvalues 1, 1/2 x3, 1/4 x6 of S_1 on the quadratics; the
 * edge's lambda_1 and 1/2 found again in the spectrum of ss_local's edge
 * matrix (an independent extraction); relabelling invariance of the blocks'
 * norm profile; a mutated weight breaks the invariance and is refused; bad
 * cases are refused with SS_EINPUT. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "ss_eig.h"
#include "ss_jsr.h"
#include "ss_levin.h"
#include "ss_test.h"

static ss_scheme *scheme(const char *name) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  if (ss_scheme_new(name, &s, &err)) fprintf(stderr, "%s\n", err.msg);
  return s;
}

/* Value of monomial k (0: 1, 1..3: x, y, z, 4..9: xx xy xz yy yz zz) at x. */
static double mono(int k, const double *x) {
  static const int a[10] = {-1, 0, 1, 2, 0, 0, 0, 1, 1, 2};
  static const int b[10] = {-1, -1, -1, -1, 0, 1, 2, 1, 2, 2};
  return (a[k] < 0 ? 1 : x[a[k]]) * (b[k] < 0 ? 1 : x[b[k]]);
}

/* Residual of the least-squares fit of y (n values) by the first nb
 * monomials on the points x (n x 3), relative to max(1, max |y|). */
static double fit_residual(size_t n, int nb, const double *x, const double *y) {
  double *A = malloc(n * 10 * sizeof *A), *B = malloc(n * sizeof *B), ymax = 0;
  for (size_t i = 0; i < n; i++) {
    for (int k = 0; k < nb; k++)
      A[i * nb + k] = mono(k, x + 3 * i);
    B[i] = y[i];
    ymax = fmax(ymax, fabs(y[i]));
  }
  double *A0 = malloc(n * 10 * sizeof *A0);
  memcpy(A0, A, n * 10 * sizeof *A);
  LAPACKE_dgels(LAPACK_ROW_MAJOR, 'N', (lapack_int)n, nb, 1, A, nb, B, 1);
  double res = 0;
  for (size_t i = 0; i < n; i++) {
    double f = 0;
    for (int k = 0; k < nb; k++)
      f += A0[i * nb + k] * B[k];
    res = fmax(res, fabs(f - y[i]));
  }
  free(A), free(A0), free(B);
  return res / fmax(1.0, ymax); /* values are O(1..100): positions in grid units */
}

/* The tet/oct face: structure, quadratic precision, eigenvalues. */
static void face_tetoct(void) {
  ss_scheme *s = scheme("tetoct");
  ss_error err = {0};
  ss_case c = {0};
  c.kind = SS_CASE_FACE;
  ss_levin *L = NULL;
  ss_star *star = NULL;
  REQUIRE_OK_VOID(ss_levin_new(s, &c, &L, &err), &err);
  REQUIRE_OK_VOID(ss_case_star(s, &c, &star, &err), &err);
  CHECK(L->m == 4 && L->r == 10 && L->n > 10, "m %zu r %zu n %zu", L->m, L->r, L->n);
  CHECK(!strcmp(L->basis, "quadratics"), "basis %s", L->basis);
  const size_t n = L->n;
  for (size_t i = 0; i < L->m; i++)
    for (size_t a = 0; a < n; a++) {
      double sum = 0;
      for (size_t b = 0; b < n; b++)
        sum += L->S[i][a * n + b];
      CHECK_CLOSE(sum, 1.0, 1e-13, "row %zu of S_%zu", a, i + 1);
    }
  /* sub-patch i = s + 2t has its corner at (s, t) in the face's (u, v) =
   * (x_1, x_2) frame of level j + 1: chart offset (-s-t, s, t, 0, 0) */
  double *y = malloc(n * sizeof *y), *g = malloc(n * sizeof *g);
  for (int i = 0; i < 4; i++) {
    const int32_t si = i & 1, ti = i >> 1, idx[3] = {0, 1, 2},
                  val[3] = {-si - ti, si, ti};
    int32_t ii[3], vv[3], k = 0;
    for (int q = 0; q < 3; q++)
      if (val[q]) ii[k] = idx[q], vv[k++] = val[q];
    const ss_star_coord d = ss_star_coord_make(k, ii, vv);
    double dp[3];
    ss_star_coord_position(star, &d, 1.0, dp);
    for (int mnm = 0; mnm < 10; mnm++) {
      for (size_t a = 0; a < n; a++) {
        double h[3];
        for (int q = 0; q < 3; q++)
          h[q] = (L->pos[3 * a + q] + dp[q]) / 2;
        double t = 0;
        for (size_t b = 0; b < n; b++)
          t += L->S[i][a * n + b] * mono(mnm, L->pos + 3 * b);
        y[a] = t - mono(mnm, h); /* S_i q - q((p + d_i) / 2) */
      }
      if (mnm < 4) { /* constants and linear functions: reproduced exactly */
        double e = 0;
        for (size_t a = 0; a < n; a++)
          e = fmax(e, fabs(y[a]));
        CHECK(e < 1e-12, "S_%d on monomial %d: error %.3g", i + 1, mnm, e);
      } else { /* quadratics: up to a polynomial of degree <= 1 */
        const double res = fit_residual(n, 4, L->pos, y);
        CHECK(res < 1e-10, "S_%d on monomial %d: residual %.3g", i + 1, mnm, res);
      }
    }
  }
  free(y), free(g);
  const double want[10] = {1, .5, .5, .5, .25, .25, .25, .25, .25, .25};
  for (int k = 0; k < 10; k++)
    CHECK_CLOSE(L->theta[k], want[k], 1e-10, "theta %d", k);
  CHECK(L->defect < 1e-12, "defect %.3g", L->defect);
  CHECK(L->threshold == 0.25, "threshold %g", L->threshold);
  ss_star_free(star);
  ss_levin_free(L);
  ss_scheme_free(s);
}

/* rho_k of the blocks (brute force, depth 3). */
static int profile(size_t m, size_t c, double *const *Y, double *rho) {
  ss_jsr_opts o = ss_jsr_defaults();
  o.depth = 3;
  o.max_nodes = 1000;
  ss_jsr_result r;
  ss_error err = {0};
  if (ss_jsr_compute(m, c, (const double *const *)Y, &o, &r, &err)) {
    fprintf(stderr, "%s\n", err.msg);
    return -1;
  }
  for (int k = 0; k < 3; k++)
    rho[k] = r.rho_2[k], rho[3 + k] = r.rho_inf[k];
  rho[6] = r.lower;
  ss_jsr_result_clear(&r);
  return 0;
}

/* Relabelling the support (a permutation similarity) leaves the 2-norm profile
 * and the lower bound unchanged; a mutated weight breaks the invariance. */
static void relabel_and_mutate(void) {
  ss_scheme *s = scheme("tetoct");
  ss_error err = {0};
  ss_case c = {0};
  c.kind = SS_CASE_FACE;
  ss_levin *L = NULL;
  REQUIRE_OK_VOID(ss_levin_new(s, &c, &L, &err), &err);
  const size_t n = L->n, r = L->r, m = L->m;
  size_t *p = malloc(n * sizeof *p);
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 18);
  for (size_t i = 0; i < n; i++)
    p[i] = i;
  for (size_t i = n - 1; i > 0; i--) {
    const size_t j = gsl_rng_uniform_int(rng, i + 1), t = p[i];
    p[i] = p[j], p[j] = t;
  }
  double *S2[4], *V2 = malloc(n * r * sizeof *V2), *Y2[4];
  for (size_t i = 0; i < m; i++) {
    S2[i] = malloc(n * n * sizeof **S2);
    for (size_t a = 0; a < n; a++)
      for (size_t b = 0; b < n; b++)
        S2[i][p[a] * n + p[b]] = L->S[i][a * n + b];
  }
  for (size_t a = 0; a < n; a++)
    for (size_t k = 0; k < r; k++)
      V2[p[a] * r + k] = L->V[a * r + k];
  double defect;
  REQUIRE_OK_VOID(ss_levin_reduce(m, n, (const double *const *)S2, V2, r, SS_LEVIN_TOL,
                                  Y2, &defect, &err),
                  &err);
  double a1[7], a2[7];
  if (!profile(m, n - r, L->Y, a1) && !profile(m, n - r, Y2, a2))
    for (int k = 0; k < 7; k++) /* the inf-norm entries 3..5 may change (QR of
                                   P V is not P times that of V: Y_i -> G^T Y_i G,
                                   G orthogonal) */
      if (k < 3 || k == 6)
        CHECK_CLOSE(a2[k], a1[k], 1e-12, "relabelled profile entry %d", k);
  /* move 1/100 of a weight to another column in one row of S_2 */
  double *S3[4];
  for (size_t i = 0; i < m; i++) {
    S3[i] = malloc(n * n * sizeof **S3);
    memcpy(S3[i], L->S[i], n * n * sizeof **S3);
  }
  size_t col = 0;
  while (S3[1][5 * n + col] == 0)
    col++;
  S3[1][5 * n + col] -= 0.01;
  S3[1][5 * n + (col + 1) % n] += 0.01;
  double *Y3[4];
  const ss_status st = ss_levin_reduce(m, n, (const double *const *)S3, L->V, r,
                                       SS_LEVIN_TOL, Y3, &defect, &err);
  CHECK(st == SS_EINTERNAL, "a mutated weight must break the invariance (status %d)", st);
  CHECK(strstr(err.msg, "S_2") != NULL, "message names S_2: %s", err.msg);
  for (size_t i = 0; i < m; i++)
    free(S2[i]), free(Y2[i]), free(S3[i]);
  free(V2), free(p);
  gsl_rng_free(rng);
  ss_levin_free(L);
  ss_scheme_free(s);
}

/* Edges: the eigenvalues 1, lambda_1, lambda_1, 1/2 of S_1 on the subspace,
 * and lambda_1 again in the spectrum of ss_local's edge matrix. */
static void edge_tetoct(int nv) {
  ss_scheme *s = scheme("tetoct");
  ss_error err = {0};
  ss_case c = {0};
  c.kind = SS_CASE_EDGE;
  c.n = nv;
  ss_levin *L = NULL;
  ss_local *M = NULL;
  REQUIRE_OK_VOID(ss_levin_new(s, &c, &L, &err), &err);
  REQUIRE_OK_VOID(ss_local_new(s, &c, &M, &err), &err);
  CHECK(L->m == 2 && L->r == 4, "m %zu r %zu", L->m, L->r);
  double *re = malloc(M->n2 * sizeof *re), *im = malloc(M->n2 * sizeof *im);
  REQUIRE_OK_VOID(ss_eig_dense(M->S, M->n2, re, im, &err), &err);
  int found_l = 0, found_h = 0;
  for (size_t k = 0; k < M->n2; k++) {
    found_l += fabs(re[k] - L->lambda1) < 1e-9 && fabs(im[k]) < 1e-9;
    found_h += fabs(re[k] - 0.5) < 1e-9 && fabs(im[k]) < 1e-9;
  }
  CHECK(found_l >= 2, "valence %d: lambda1 %.12g twice in the edge matrix (%d)", nv,
        L->lambda1, found_l);
  CHECK(found_h >= 1, "valence %d: 1/2 in the edge matrix", nv);
  CHECK_CLOSE(L->threshold, fmin(L->lambda1, 0.5), 0, "valence %d threshold", nv);
  /* the two maps are conjugate by the reflection of the edge, so their
   * spectra agree: the same lambda1 from S_2 */
  double *re2 = malloc(L->n * sizeof *re2), *im2 = malloc(L->n * sizeof *im2);
  REQUIRE_OK_VOID(ss_eig_dense(L->S[1], L->n, re2, im2, &err), &err);
  int found2 = 0;
  for (size_t k = 0; k < L->n; k++)
    found2 += fabs(re2[k] - L->lambda1) < 1e-9 && fabs(im2[k]) < 1e-9;
  CHECK(found2 >= 2, "valence %d: lambda1 twice in S_2 (%d)", nv, found2);
  free(re), free(im), free(re2), free(im2);
  ss_local_free(M);
  ss_levin_free(L);
  ss_scheme_free(s);
}

/* S_1 fixes the patch's corner, a vertex inside the face: its eigenvalues of
 * modulus >= 1/8 are eigenvalues of ss_local's face matrix (an independent
 * extraction around that vertex). */
static void face_against_local(const char *name, ss_diag_mode diag) {
  ss_scheme *s = scheme(name);
  ss_error err = {0};
  ss_case c = {0};
  c.kind = SS_CASE_FACE;
  c.diag = diag;
  ss_levin *L = NULL;
  ss_local *M = NULL;
  REQUIRE_OK_VOID(ss_levin_new(s, &c, &L, &err), &err);
  REQUIRE_OK_VOID(ss_local_new(s, &c, &M, &err), &err);
  double *re = malloc(M->n2 * sizeof *re), *im = malloc(M->n2 * sizeof *im);
  double *r1 = malloc(L->n * sizeof *r1), *i1 = malloc(L->n * sizeof *i1);
  REQUIRE_OK_VOID(ss_eig_dense(M->S, M->n2, re, im, &err), &err);
  REQUIRE_OK_VOID(ss_eig_dense(L->S[0], L->n, r1, i1, &err), &err);
  int big = 0;
  for (size_t k = 0; k < L->n; k++) {
    if (hypot(r1[k], i1[k]) < 0.125 + 1e-9) continue;
    big++;
    double best = INFINITY;
    for (size_t q = 0; q < M->n2; q++)
      best = fmin(best, hypot(re[q] - r1[k], im[q] - i1[k]));
    CHECK(best < 1e-7, "%s face: eigenvalue %.12g of S_1 not in the face matrix (%.3g)",
          name, r1[k], best);
  }
  CHECK(big >= 10, "%s face: %d eigenvalues >= 1/8", name, big);
  const double want[10] = {1, .5, .5, .5, .25, .25, .25, .25, .25, .25};
  for (int k = 0; k < 10; k++)
    CHECK_CLOSE(L->theta[k], want[k], 1e-10, "%s face theta %d", name, k);
  free(re), free(im), free(r1), free(i1);
  ss_local_free(M);
  ss_levin_free(L);
  ss_scheme_free(s);
}

/* The box-spline edge of valence 4 with proper diagonals lies in the uniform
 * lattice: linear precision gives 1, 1/2, 1/2, 1/2 on the subspace, and the
 * quadratics left in Y_1 give it the eigenvalue 1/4, so the lower bound is at
 * least 1/4, exactly 1/4 from words of length 1. */
static void regular_edge(void) {
  ss_scheme *s = scheme("boxspline");
  ss_error err = {0};
  ss_case c = {0};
  c.kind = SS_CASE_EDGE;
  c.n = 4;
  c.diag = SS_DIAG_PROPER;
  ss_levin *L = NULL;
  REQUIRE_OK_VOID(ss_levin_new(s, &c, &L, &err), &err);
  const double want[4] = {1, .5, .5, .5};
  for (int k = 0; k < 4; k++)
    CHECK_CLOSE(L->theta[k], want[k], 1e-10, "regular edge theta %d", k);
  CHECK_CLOSE(L->threshold, 0.5, 1e-10, "regular edge threshold");
  double *Yd = malloc((L->n - 4) * (L->n - 4) * sizeof *Yd);
  double *re = malloc((L->n - 4) * sizeof *re), *im = malloc((L->n - 4) * sizeof *im);
  memcpy(Yd, L->Y[0], (L->n - 4) * (L->n - 4) * sizeof *Yd);
  REQUIRE_OK_VOID(ss_eig_dense(Yd, L->n - 4, re, im, &err), &err);
  double rho = 0;
  for (size_t k = 0; k < L->n - 4; k++)
    rho = fmax(rho, hypot(re[k], im[k]));
  CHECK_CLOSE(rho, 0.25, 1e-10, "spectral radius of Y_1 at the regular edge");
  free(Yd), free(re), free(im);
  ss_levin_free(L);
  ss_scheme_free(s);
}

static void bad_input(void) {
  ss_error err = {0};
  ss_scheme *s = scheme("mlca");
  ss_case c = {0};
  c.kind = SS_CASE_FACE;
  ss_levin *L = NULL;
  CHECK(ss_levin_new(s, &c, &L, &err) == SS_EINPUT && !L, "mlca has no face case");
  ss_scheme_free(s);
  s = scheme("tetoct");
  c.kind = SS_CASE_SURFACE_VERTEX;
  c.n = 5;
  CHECK(ss_levin_new(s, &c, &L, &err) == SS_EINPUT && !L, "surface vertex refused");
  c.kind = SS_CASE_EDGE;
  c.n = 2;
  CHECK(ss_levin_new(s, &c, &L, &err) == SS_EINPUT && !L, "valence 2 refused");
  double S[4] = {1, 0, 0, 1}, V[2] = {1, 1}, *Y[1];
  const double *Sp[1] = {S};
  double d;
  CHECK(ss_levin_reduce(1, 2, Sp, V, 2, 1e-9, Y, &d, &err) == SS_EINPUT, "r = n");
  ss_scheme_free(s);
}

int main(void) {
  face_tetoct();
  relabel_and_mutate();
  edge_tetoct(3);
  edge_tetoct(5);
  face_against_local("tetoct", SS_DIAG_BFS);
  face_against_local("boxspline", SS_DIAG_PROPER);
  regular_edge();
  bad_input();
  return ss_test_done("test_levin");
}
