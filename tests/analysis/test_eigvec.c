/* test_eigvec.c — leading eigenvectors and limit masks (ss_eigvec, issue 21).
 *
 * Checked: the eigen-equations S r = lambda r and l^T S = lambda l^T, the
 * biorthonormality L^T R = I within each group, r_0 = 1; the limit of
 * repeated subdivision of random control points: the centre of S^m x tends
 * to l_0^T x and (S^m x - (l_0^T x) 1) / lambda_1^m to R_1 L_1^T x; the
 * limit-position masks of Loop and Catmull-Clark against their closed forms
 * (written here from the literature, not from the scheme files); bad
 * arguments. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "ss_eigvec.h"
#include "ss_link.h"
#include "ss_local.h"
#include "ss_scheme.h"
#include "ss_test.h"

#define TOL 1e-6 /* grouping tolerance (the analyses' default) */

static ss_scheme *scheme(const char *name) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  if (ss_scheme_new(name, &s, &err)) fprintf(stderr, "%s\n", err.msg);
  return s;
}

/* |S x| in the infinity norm, for residual scales */
static double inf_norm(const double *S, size_t n) {
  double m = 0.0;
  for (size_t i = 0; i < n; i++) {
    double r = 0.0;
    for (size_t j = 0; j < n; j++)
      r += fabs(S[i * n + j]);
    m = fmax(m, r);
  }
  return m;
}

/* Eigen-equations, biorthonormality and the limits of repeated subdivision. */
static void check_case(const char *sname, ss_case c, const char *what, gsl_rng *rng) {
  ss_scheme *s = scheme(sname);
  ss_local *M = NULL;
  ss_eigvec *v = NULL;
  ss_error err = {0};
  double *x = NULL, *y = NULL, *t = NULL;
  CHECK(s != NULL, "scheme %s", sname);
  if (!s) return;
  if (ss_local_new(s, &c, &M, &err)) {
    CHECK(0, "%s %s: %s", sname, what, err.msg);
    goto done;
  }
  const size_t n = M->n2;
  const int m = M->dim;
  REQUIRE_OK_VOID(ss_eigvec_new(M->S, n, m + 2, TOL, &v, &err), &err);
  if (!v) goto done;
  const double sn = inf_norm(M->S, n);
  CHECK(v->k >= m + 2, "%s %s: k %d", sname, what, v->k);
  /* eigen-equations, residuals relative to ||S|| */
  for (int j = 0; j < v->k; j++) {
    double rr = 0.0, rl = 0.0, rmax = 0.0, lmax = 0.0;
    for (size_t i = 0; i < n; i++) {
      double sr = 0.0, si = 0.0, lr = 0.0, li = 0.0;
      for (size_t q = 0; q < n; q++) {
        sr += M->S[i * n + q] * v->right_re[q + j * n];
        si += M->S[i * n + q] * v->right_im[q + j * n];
        lr += v->left_re[q + j * n] * M->S[q * n + i];
        li += v->left_im[q + j * n] * M->S[q * n + i];
      }
      /* minus lambda times the vector (complex product) */
      sr -= v->re[j] * v->right_re[i + j * n] - v->im[j] * v->right_im[i + j * n];
      si -= v->re[j] * v->right_im[i + j * n] + v->im[j] * v->right_re[i + j * n];
      lr -= v->re[j] * v->left_re[i + j * n] - v->im[j] * v->left_im[i + j * n];
      li -= v->re[j] * v->left_im[i + j * n] + v->im[j] * v->left_re[i + j * n];
      rr = fmax(rr, hypot(sr, si));
      rl = fmax(rl, hypot(lr, li));
      rmax = fmax(rmax, hypot(v->right_re[i + j * n], v->right_im[i + j * n]));
      lmax = fmax(lmax, hypot(v->left_re[i + j * n], v->left_im[i + j * n]));
    }
    CHECK(fabs(rmax - 1.0) < 1e-13, "%s %s: right %d max modulus %.17g", sname, what, j,
          rmax);
    CHECK(rr <= 1e-12 * sn, "%s %s: |S r - lambda r| = %.3g (j = %d)", sname, what, rr,
          j);
    CHECK(rl <= 1e-12 * sn * lmax, "%s %s: |l S - lambda l| = %.3g (j = %d)", sname, what,
          rl, j);
  }
  /* L^T R = I within each biorthonormal group, 0 across groups (distinct
   * eigenvalues: left and right eigenvectors are orthogonal) */
  for (int a = 0; a < v->k; a++)
    for (int b = 0; b < v->k; b++) {
      double gr = 0.0, gi = 0.0, scale = 0.0;
      for (size_t i = 0; i < n; i++) {
        const double lr = v->left_re[i + a * n], li = v->left_im[i + a * n],
                     rr = v->right_re[i + b * n], ri = v->right_im[i + b * n];
        gr += lr * rr - li * ri;
        gi += lr * ri + li * rr;
        scale += hypot(lr, li) * hypot(rr, ri);
      }
      if (v->group[a] == v->group[b] && !v->biorth[a]) continue;
      const double want = a == b ? 1.0 : 0.0;
      CHECK(hypot(gr - want, gi) <= 1e-11 * fmax(1.0, scale),
            "%s %s: (L^T R)[%d][%d] = %.3g%+.3gi, want %g", sname, what, a, b, gr, gi,
            want);
    }
  CHECK(ss_eigvec_has_limit(v, TOL), "%s %s: limit masks defined", sname, what);
  /* repeated subdivision of random control points */
  x = malloc(n * sizeof *x);
  y = malloc(n * sizeof *y);
  t = malloc(n * sizeof *t);
  if (!x || !y || !t) {
    CHECK(0, "out of memory");
    goto done;
  }
  for (size_t i = 0; i < n; i++)
    x[i] = y[i] = gsl_rng_uniform(rng) - 0.5;
  /* the subdominant eigenvalues 1..m (real, as the cases below have them);
   * the next modulus decides the rate of convergence */
  const double l1 = v->re[1], next = hypot(v->re[m + 1], v->im[m + 1]);
  const double rate = next / fabs(v->re[m]);
  int real = 1;
  for (int j = 0; j <= m; j++)
    real &= v->im[j] == 0.0 && v->biorth[j];
  CHECK(real, "%s %s: lambda_0..%d real and biorthonormal", sname, what, m);
  double l0x = 0.0;
  for (size_t i = 0; i < n; i++)
    l0x += v->left_re[i] * x[i];
  /* limit position: the centre of S^m x, m with lambda_1^m < 1e-14 */
  const int steps0 = (int)ceil(log(1e-14) / log(fabs(l1)));
  for (int st = 0; st < steps0; st++) {
    for (size_t i = 0; i < n; i++) {
      double a = 0.0;
      for (size_t q = 0; q < n; q++)
        a += M->S[i * n + q] * y[q];
      t[i] = a;
    }
    memcpy(y, t, n * sizeof *y);
  }
  CHECK_CLOSE(y[0], l0x, 1e-12, "%s %s: centre after %d steps vs l_0^T x", sname, what,
              steps0);
  /* tangents: z_m = S^m (x - (l_0^T x) 1) / lambda_1^m, kept free of the
   * constant (rounding brings it back), tends to sum_j (lambda_j /
   * lambda_1)^m r_j l_j^T x over j = 1..dim */
  if (rate > 0.95) {
    printf("%s %s: |lambda_%d / lambda_%d| = %.4f, too slow for the tangent limit\n",
           sname, what, m + 1, m, rate);
    goto done;
  }
  const int steps = (int)ceil(log(1e-10) / log(rate));
  for (size_t i = 0; i < n; i++)
    y[i] = x[i] - l0x;
  for (int st = 0; st < steps; st++) {
    double cst = 0.0;
    for (size_t i = 0; i < n; i++) {
      double a = 0.0;
      for (size_t q = 0; q < n; q++)
        a += M->S[i * n + q] * y[q];
      t[i] = a / l1;
      cst += v->left_re[i] * t[i];
    }
    for (size_t i = 0; i < n; i++)
      y[i] = t[i] - cst;
  }
  double worst = 0.0, size = 0.0;
  for (size_t i = 0; i < n; i++) {
    double p = 0.0;
    for (int j = 1; j <= m; j++) {
      double lx = 0.0;
      for (size_t q = 0; q < n; q++)
        lx += v->left_re[q + j * n] * x[q];
      p += pow(v->re[j] / l1, steps) * v->right_re[i + j * n] * lx;
    }
    worst = fmax(worst, fabs(y[i] - p));
    size = fmax(size, fabs(p));
  }
  CHECK(worst <= 1e-8 * size,
        "%s %s: S^m (x - l0x) / lambda1^m vs the tangent masks' sum: %.3g (of %.3g, m "
        "= %d)",
        sname, what, worst, size, steps);
done:
  free(x);
  free(y);
  free(t);
  ss_eigvec_free(v);
  ss_local_free(M);
  ss_scheme_free(s);
}

/* Loop: limit position = (1 - n chi) centre + chi each neighbour, chi =
 * 1 / (3 / (8 beta) + n), beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n
 * (Loop 1987; Hoppe et al. 1994).  Catmull-Clark: n / (n + 5) centre,
 * 4 / (n (n + 5)) each edge neighbour, 1 / (n (n + 5)) each face neighbour
 * (Halstead, Kass, DeRose 1993). */
static void check_masks(const char *sname, int n) {
  ss_scheme *s = scheme(sname);
  ss_local *M = NULL;
  ss_eigvec *v = NULL;
  ss_error err = {0};
  const ss_case c = {SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0};
  if (!s || ss_local_new(s, &c, &M, &err)) {
    CHECK(0, "%s %d: %s", sname, n, err.msg);
    goto done;
  }
  REQUIRE_OK_VOID(ss_eigvec_new(M->S, M->n2, 1, TOL, &v, &err), &err);
  if (!v) goto done;
  CHECK(v->k == 1 && ss_eigvec_has_limit(v, TOL), "%s %d: one leading eigenvalue 1",
        sname, n);
  const double pi = acos(-1.0), cs = cos(2 * pi / n);
  const double beta = (5.0 / 8 - (3.0 / 8 + cs / 4) * (3.0 / 8 + cs / 4)) / n;
  const double chi = 1.0 / (3.0 / (8 * beta) + n);
  int nedge = 0, nface = 0;
  for (size_t i = 0; i < M->n2; i++) {
    const ss_star_coord *L = M->label + i;
    const int one = L->n == 1 && L->val[0] == 1;
    const int two = L->n == 2 && L->val[0] == 1 && L->val[1] == 1;
    double want = 0.0;
    if (!strcmp(sname, "loop"))
      want = L->n == 0 ? 1.0 - n * chi : one ? chi : 0.0;
    else
      want = L->n == 0 ? (double)n / (n + 5)
             : one     ? 4.0 / (n * (n + 5.0))
             : two     ? 1.0 / (n * (n + 5.0))
                       : 0.0;
    nedge += one;
    nface += two;
    CHECK(fabs(v->left_re[i] - want) <= 1e-14,
          "%s %d: mask at point %zu: %.17g, want %.17g", sname, n, i, v->left_re[i],
          want);
  }
  CHECK(nedge == n && (nface == n || !strcmp(sname, "loop")),
        "%s %d: %d edge and %d face neighbours", sname, n, nedge, nface);
done:
  ss_eigvec_free(v);
  ss_local_free(M);
  ss_scheme_free(s);
}

int main(void) {
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 21);
  char what[64];
  for (int n = 3; n <= 9; n++) {
    check_masks("loop", n);
    check_masks("catmull-clark", n);
    snprintf(what, sizeof what, "surface vertex %d", n);
    check_case("loop", (ss_case){SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0}, what,
               rng);
    check_case("catmull-clark",
               (ss_case){SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0}, what, rng);
  }
  for (int n = 3; n <= 6; n++) {
    snprintf(what, sizeof what, "edge %d", n);
    check_case("mlca", (ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0}, what, rng);
    check_case("tetoct", (ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0}, what, rng);
  }
  check_case("tetoct", (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, "face", rng);
  const char *links[] = {"octahedron", "icosahedron"};
  for (int i = 0; i < 2; i++) {
    ss_link *l = NULL;
    ss_error err = {0};
    REQUIRE_OK(ss_link_parse(links[i], &l, &err), &err);
    check_case("mlca", (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, links[i], rng);
    ss_link_free(l);
  }
  /* bad arguments */
  {
    const double S[4] = {1, 0, 0.5, 0.5};
    ss_eigvec *v = NULL;
    ss_error err = {0};
    CHECK(ss_eigvec_new(S, 2, 0, TOL, &v, &err) == SS_EINPUT && !v, "k = 0 refused");
    CHECK(ss_eigvec_new(S, 2, 3, TOL, &v, &err) == SS_EINPUT && !v, "k > n refused");
    CHECK(ss_eigvec_new(S, 2, 1, 0.0, &v, &err) == SS_EINPUT && !v, "tol 0 refused");
    /* a Jordan block: [[1/2, 1], [0, 1/2]] plus the eigenvalue 1 */
    const double J[9] = {1, 0, 0, 0.25, 0.5, 1, 0.25, 0, 0.5};
    REQUIRE_OK(ss_eigvec_new(J, 3, 2, TOL, &v, &err), &err);
    CHECK(v->k == 3 && v->biorth[0] && !v->biorth[1] && !v->biorth[2],
          "a Jordan block is flagged, not normalised (k %d)", v->k);
    ss_eigvec_free(v);
  }
  gsl_rng_free(rng);
  return ss_test_done("eigvec");
}
