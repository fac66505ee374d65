/* test_jsr_polytope.c — the invariant polytope method (ss_jsr_polytope)
 * against joint spectral radii known in closed form, brute-force lower
 * bounds, and a permutation similarity.
 *
 * Closed forms:
 *  - A = [[1,1],[0,1]], B = [[1,0],[1,1]]: JSR = phi (test_jsr.c: ||A||_2 =
 *    ||B||_2 = phi, rho(AB) = phi^2).  AB is spectrum maximising, so the
 *    polytope from the word AB closes and its bound is phi (1 + eps) up to
 *    the certificate's rounding terms; from the word A (rho = 1 < phi) it
 *    can never close (an invariant body would prove JSR <= 1.001): the
 *    vertex cap stops it.
 *  - Cubic B-spline difference schemes (derived as in test_jsr.c: the k-th
 *    differences of a segment's control points, maps A_L, A_R): every row
 *    nonnegative with sum 2^{-k}, so JSR = rho(A_L) = 2^{-k}; the polytope
 *    from the word L closes at 2^{-k} (1 + eps).
 *  - A scaled rotation R = c R(theta) and a contraction B with ||B||_2 <
 *    c: JSR = c exactly (rho(R) = ||R||_2 = c).  R's leading eigenvalue is
 *    complex: the 2-plane (elliptic) variant must run and close at c (1 +
 *    eps).
 *  - A mirror-symmetric pair with JSR 1 attained by both maps (a tie).
 *  - A near-candidate 0.1 % below the JSR (a spiral): with its own roots
 *    (option near) the hull closes from the roots alone, without them only
 *    after a hundred images; relabelled alike.
 *  - A semisimple double leading eigenvalue gives two roots, a defective
 *    one (Jordan block) one.
 * Bounds: for random nonnegative sets the polytope's bound, when it closes,
 * is at least ss_jsr's certified lower bound (brute force over words of
 * length <= 6) and at most that lower bound times (1 + eps) (1 + 1e-6):
 * the candidate word is the lower bound's.  Relabelling the coordinates
 * (P Y_i P^T, P a permutation) leaves the bound unchanged (to 1e-12: the
 * leading eigenvalue is recomputed in another order).  Through
 * ss_jsr_compute (norm POLYTOPE): the result brackets the known value and
 * meets the gap. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <glpk.h>
#include <gsl/gsl_rng.h>

#include "ss_jsr.h"
#include "ss_jsr_polytope.h"
#include "ss_test.h"

static ss_jsr_polytope_result poly(size_t m, size_t n, const double *const *Y,
                                   const int *w, int len, double eps, size_t cap,
                                   int *ok) {
  ss_jsr_polytope_opts o = ss_jsr_polytope_defaults();
  o.eps = eps;
  o.max_vertices = cap;
  o.max_seconds = 20;
  ss_jsr_polytope_result r;
  ss_error e = {0};
  *ok = ss_jsr_polytope(m, n, Y, w, len, &o, &r, &e) == SS_OK;
  CHECK(*ok, "ss_jsr_polytope failed: %s", e.msg);
  return r;
}

/* The bound of a closed polytope for a set whose JSR is `exact`: at least
 * exact, at most exact (1 + eps) (1 + 1e-9). */
static void check_exact(const char *what, const ss_jsr_polytope_result *r, double exact,
                        double eps) {
  CHECK(r->stop == SS_POLY_CLOSED, "%s: not closed (stop %d, %zu vertices)", what,
        (int)r->stop, r->vertices);
  if (r->stop != SS_POLY_CLOSED) return;
  CHECK(r->upper >= exact, "%s: upper %.17g below the JSR %.17g", what, r->upper, exact);
  CHECK(r->upper <= exact * (1 + eps) * (1 + 1e-9),
        "%s: upper %.17g above %.17g (1 + %g)", what, r->upper, exact, eps);
  CHECK(r->pending == 0, "%s: %zu vertices untested", what, r->pending);
}

static void test_golden(void) {
  const double A[4] = {1, 1, 0, 1}, B[4] = {1, 0, 1, 1};
  const double *Y[2] = {A, B};
  const double phi = (1 + sqrt(5.0)) / 2;
  int ok;
  const int ab[2] = {0, 1}, a[1] = {0};
  for (double eps = 1e-2; eps >= 1e-8; eps /= 100) {
    ss_jsr_polytope_result r = poly(2, 2, Y, ab, 2, eps, 1000, &ok);
    if (!ok) continue;
    CHECK(!r.complex_leading, "rho(AB) = phi^2 is real");
    CHECK_CLOSE(r.lambda, phi, 1e-14, "lambda of AB");
    check_exact("golden AB", &r, phi, eps);
  }
  /* the candidate A (rho 1) is not spectrum maximising: never closes */
  ss_jsr_polytope_result r = poly(2, 2, Y, a, 1, 1e-3, 200, &ok);
  if (ok) {
    CHECK(r.stop == SS_POLY_CAP, "golden from A: stop %d, want the vertex cap",
          (int)r.stop);
    CHECK(isinf(r.upper), "golden from A: no bound, got %g", r.upper);
    CHECK(r.vertices == 200 && r.pending > 0, "golden from A: %zu vertices, %zu pending",
          r.vertices, r.pending);
    CHECK(r.max_out > 1 + 1e-3, "golden from A: images outside (max %g)", r.max_out);
  }
  /* a time limit stops it likewise */
  ss_jsr_polytope_opts o = ss_jsr_polytope_defaults();
  o.max_vertices = 1 << 20;
  o.max_seconds = 0.2;
  ss_error e = {0};
  if (ss_jsr_polytope(2, 2, Y, a, 1, &o, &r, &e) == SS_OK)
    CHECK(r.stop == SS_POLY_TIME || r.stop == SS_POLY_CAP,
          "golden from A, 0.2 s: stop %d", (int)r.stop);
}

/* The k-th difference maps of cubic B-spline subdivision (point mask
 * (1 + z)^4 / 8).  The k-th differences refine with the symbol b(z) =
 * (1 + z)^{4-k} / 8 ((1 - z)^k a(z) = b(z) (1 - z^2)^k), coefficients
 * b_0..b_d, d = 4 - k: q_r = sum_j b_{r - 2j} p_j.  A segment carries d
 * differences p_0..p_{d-1}; its left half the d values q_{d-1+i}, its right
 * half q_{d+i} (i = 0..d-1), which read only p_0..p_{d-1}:
 * A_L[i][j] = b_{d-1+i-2j}, A_R[i][j] = b_{d+i-2j}. */
static void bspline_diff(int k, double *AL, double *AR) {
  const int d = 4 - k;
  double b[5] = {1, 0, 0, 0, 0};
  for (int t = 0; t < d; t++)
    for (int j = 4; j > 0; j--)
      b[j] += b[j - 1];
  for (int j = 0; j <= d; j++)
    b[j] /= 8;
  for (int i = 0; i < d; i++)
    for (int j = 0; j < d; j++) {
      const int rl = d - 1 + i - 2 * j, rr = rl + 1;
      AL[i * d + j] = rl >= 0 && rl <= d ? b[rl] : 0;
      AR[i * d + j] = rr >= 0 && rr <= d ? b[rr] : 0;
    }
}

static void test_bspline(void) {
  for (int k = 1; k <= 3; k++) {
    const int d = 4 - k;
    double AL[16], AR[16];
    bspline_diff(k, AL, AR);
    /* the closed form needs every row nonnegative with sum 2^{-k}: check */
    int rows_ok = 1;
    for (int i = 0; i < d; i++) {
      double sl = 0, sr = 0;
      for (int j = 0; j < d; j++) {
        sl += AL[i * d + j], sr += AR[i * d + j];
        rows_ok &= AL[i * d + j] >= 0 && AR[i * d + j] >= 0;
      }
      rows_ok &= sl == ldexp(1.0, -k) && sr == ldexp(1.0, -k);
    }
    CHECK(rows_ok, "k = %d: difference maps not nonnegative with row sums 2^-k", k);
    const double *Y[2] = {AL, AR};
    const int w[1] = {0};
    int ok;
    ss_jsr_polytope_result r = poly(2, (size_t)d, Y, w, 1, 1e-6, 2000, &ok);
    if (!ok) continue;
    check_exact("B-spline differences", &r, ldexp(1.0, -k), 1e-6);
  }
}

static void test_rotation(void) {
  const double c = 0.75, th = 2 * 3.14159265358979323846 * 0.1234567;
  const double R[4] = {c * cos(th), -c * sin(th), c * sin(th), c * cos(th)};
  /* ||B||_2 <= ||B||_F = sqrt(0.09 + 0.04 + 0.01 + 0.16) = 0.548 < c */
  const double B[4] = {0.3, 0.2, -0.1, 0.4};
  const double *Y[2] = {R, B};
  const int w[1] = {0};
  int ok;
  for (double eps = 1e-2; eps >= 1e-4; eps /= 10) {
    ss_jsr_polytope_result r = poly(2, 2, Y, w, 1, eps, 5000, &ok);
    if (!ok) continue;
    CHECK(r.complex_leading, "rotation: the leading eigenvalue is complex");
    /* N points with cos(pi / 2N) >= 1 / (1 + eps) */
    const double npts = ceil(3.14159265358979323846 / (2 * acos(1 / (1 + eps))));
    CHECK(r.roots >= (size_t)npts - 1 && r.roots <= (size_t)npts + 1,
          "rotation: %zu ellipse points, want about %g", r.roots, npts);
    check_exact("scaled rotation", &r, c, eps);
  }
}

/* Y_0 = [[1, 0.3], [0, 0.2]] and its mirror Y_1 = J Y_0 J (J swaps the
 * coordinates): both have spectral radius 1 and induced l1 norm (largest
 * column sum) 1, so JSR = 1, attained by Y_0 and by Y_1: a tie the search
 * must find (ties = 1), and the hull closes at 1 (1 + eps). */
static void test_tie(void) {
  const double A[4] = {1, 0.3, 0, 0.2}, B[4] = {0.2, 0, 0.3, 1};
  const double *Y[2] = {A, B};
  const int w[1] = {0};
  int ok;
  ss_jsr_polytope_result r = poly(2, 2, Y, w, 1, 1e-5, 1000, &ok);
  if (!ok) return;
  CHECK(r.ties == 1, "mirror pair: %d ties, want 1 (the word B)", r.ties);
  check_exact("mirror pair", &r, 1.0, 1e-5);
}

/* A near-candidate (Mejstrik 2020), order 3: Y_0 = diag(1, 0, 0) (the
 * candidate, rho 1) and Y_1 = [[0, 0, 0], [1, qc, -qs], [0, qs, qc]],
 * c, s = cos, sin theta, q = 1 - 1e-3, theta = 0.01: Y_1 sends e_1 into
 * the plane span(e_2, e_3) and turns that plane by theta, shrinking it by
 * q.  The plane is invariant under both and Y_0 kills it; on the quotient
 * Y_0 is 1 and Y_1 is 0, so JSR = max(rho(q R(theta)), 1) = 1, attained by
 * Y_0 alone; Y_1 is 0.1 % below it, and every word with both letters has a
 * rotation containing Y_0 Y_1 = 0 (rho 0): Y_1 is the only near-candidate.
 * With eps = 1e-5 the orbit of e_1 spirals inward by about 0.999 per step
 * through 0.01 rad: from Y_0's root alone the hull needs over a hundred
 * images.  With near = 2e-3 the word Y_1 joins (ties = 1): its complex pair
 * gives N circle points with cos(pi / 2N) >= q / s, N = 35; the rotated and
 * shrunk 70-gon lies inside the 70-gon, and the hull closes at 1 (1 + eps)
 * with a few vertices besides the roots.  Relabelling the coordinates
 * (P Y_i P^T, P the reversal) changes nothing. */
static void test_near(void) {
  const double q = 1 - 1e-3, th = 0.01, eps = 1e-5;
  const double qc = q * cos(th), qs = q * sin(th);
  const double A[9] = {1, 0, 0, 0, 0, 0, 0, 0, 0};
  const double B[9] = {0, 0, 0, 1, qc, -qs, 0, qs, qc};
  double PA[9], PB[9]; /* (P X P^T)[a][b] = X[2 - a][2 - b] */
  for (int e = 0; e < 9; e++)
    PA[e] = A[8 - e], PB[e] = B[8 - e];
  const double *Y[2] = {A, B}, *PY[2] = {PA, PB};
  const int w[1] = {0};
  ss_jsr_polytope_opts o = ss_jsr_polytope_defaults();
  o.eps = eps;
  o.max_vertices = 2000;
  o.max_seconds = 20;
  ss_jsr_polytope_result r;
  ss_error e = {0};
  if (ss_jsr_polytope(2, 3, Y, w, 1, &o, &r, &e) != SS_OK) {
    CHECK(0, "near: %s", e.msg);
    return;
  }
  CHECK(r.ties == 0 && r.roots == 1, "near 1e-9: %d ties, %zu roots, want 0 and 1",
        r.ties, r.roots);
  check_exact("spiral from Y_0's root alone", &r, 1.0, eps);
  CHECK(r.vertices > r.roots + 3 + 100, "near 1e-9: only %zu vertices (%zu roots)",
        r.vertices, r.roots);
  o.near = 2e-3;
  const double npts = ceil(3.14159265358979323846 / (2 * acos(q / (1 + eps))));
  CHECK(npts == 35, "near: N = %g ellipse points, want 35 (cos(pi / 70) >= q / s)", npts);
  for (int relabel = 0; relabel < 2; relabel++) {
    if (ss_jsr_polytope(2, 3, relabel ? PY : Y, w, 1, &o, &r, &e) != SS_OK) {
      CHECK(0, "near 2e-3: %s", e.msg);
      continue;
    }
    CHECK(r.ties == 1 && r.roots == 1 + (size_t)npts,
          "near 2e-3 (relabelled %d): %d ties, %zu roots, want 1 and 1 + %g", relabel,
          r.ties, r.roots, npts);
    check_exact("near-candidate spiral", &r, 1.0, eps);
    CHECK(r.vertices <= r.roots + 3 + 10,
          "near 2e-3: %zu vertices for %zu roots: the roots should nearly close it",
          r.vertices, r.roots);
  }
  o.near = 1;
  CHECK(ss_jsr_polytope(2, 3, Y, w, 1, &o, &r, &e) == SS_EINPUT && strstr(e.msg, "near"),
        "near 1: %s", e.msg);
}

/* A multiple leading eigenvalue.  Semisimple: Y_0 = Q diag(1, 1, 1/2) Q^T
 * (Q a rotation; ||Y_0||_2 = 1) has an eigenplane: both eigenvectors are
 * roots (roots = 2).  Defective: the Jordan block [[1, 1], [0, 1]] plus 1/2
 * has one eigenvector, and LAPACK's second, parallel up to rounding, must
 * not make a second root (roots = 1; alone, so that no tie adds roots).  With Y_1 = 0.3 Q
 * (||Y_1||_2 = 0.3) the semisimple set has JSR 1: the hull closes at 1 (1 + eps). */
static void test_multiple(void) {
  const double c = cos(0.7), s = sin(0.7);
  const double Q[9] = {c, -s, 0, s * 0.6, c * 0.6, -0.8, s * 0.8, c * 0.8, 0.6};
  const double d[3] = {1, 1, 0.5};
  double S[9], B[9];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      S[a * 3 + b] = 0;
      for (int k = 0; k < 3; k++)
        S[a * 3 + b] += Q[a * 3 + k] * d[k] * Q[b * 3 + k];
      B[a * 3 + b] = 0.3 * Q[a * 3 + b];
    }
  const double J[9] = {1, 1, 0, 0, 1, 0, 0, 0, 0.5};
  const double *Y[2] = {S, B}, *JY[1] = {J};
  const int w[1] = {0};
  int ok;
  ss_jsr_polytope_result r = poly(2, 3, Y, w, 1, 1e-4, 2000, &ok);
  if (ok) {
    CHECK(r.roots == 2, "eigenplane: %zu roots, want 2", r.roots);
    check_exact("eigenplane", &r, 1.0, 1e-4);
  }
  r = poly(1, 3, JY, w, 1, 1e-4, 50, &ok);
  if (ok) CHECK(r.roots == 1, "Jordan block: %zu roots, want 1", r.roots);
}

/* random nonnegative m sets of order n (entries uniform / n) */
static void random_set(gsl_rng *rng, size_t m, size_t n, double *buf, const double **Y) {
  for (size_t i = 0; i < m; i++) {
    for (size_t e = 0; e < n * n; e++)
      buf[i * n * n + e] = gsl_rng_uniform(rng) / (double)n;
    Y[i] = buf + i * n * n;
  }
}

static void test_random(gsl_rng *rng) {
  enum { M = 2, N = 4 };
  static double buf[M * N * N], pbuf[M * N * N];
  const double *Y[M], *PY[M];
  int closed = 0;
  for (int trial = 0; trial < 8; trial++) {
    random_set(rng, M, N, buf, Y);
    ss_jsr_opts o = ss_jsr_defaults();
    o.depth = 6;
    o.gap = 1e300; /* brute force only: the lower bound and its word */
    ss_jsr_result lr;
    ss_error e = {0};
    if (ss_jsr_compute(M, N, Y, &o, &lr, &e) != SS_OK) {
      CHECK(0, "ss_jsr_compute: %s", e.msg);
      continue;
    }
    int ok;
    const double eps = 1e-4;
    ss_jsr_polytope_result r = poly(M, N, Y, lr.lower_word, lr.lower_len, eps, 3000, &ok);
    if (ok && r.stop == SS_POLY_CLOSED) {
      closed++;
      CHECK(r.upper >= lr.lower, "trial %d: upper %.17g below the lower bound %.17g",
            trial, r.upper, lr.lower);
      CHECK(r.upper <= lr.lower * (1 + eps) * (1 + 1e-6),
            "trial %d: upper %.17g far above lower %.17g", trial, r.upper, lr.lower);
      /* relabel: P Y_i P^T with P the reversal composed with a shift */
      int perm[N];
      for (int a = 0; a < N; a++)
        perm[a] = (N - 1 - a + trial) % N;
      for (int i = 0; i < M; i++) {
        for (int a = 0; a < N; a++)
          for (int b = 0; b < N; b++)
            pbuf[i * N * N + perm[a] * N + perm[b]] = Y[i][a * N + b];
        PY[i] = pbuf + i * N * N;
      }
      ss_jsr_polytope_result pr =
          poly(M, N, PY, lr.lower_word, lr.lower_len, eps, 3000, &ok);
      if (ok) {
        CHECK(pr.stop == SS_POLY_CLOSED, "trial %d: relabelled set did not close", trial);
        if (pr.stop == SS_POLY_CLOSED)
          CHECK_CLOSE(pr.upper, r.upper, 1e-12, "trial %d: relabelled upper", trial);
      }
    } else if (ok) {
      /* not closing is allowed (a tie, or the cap), but never a bound */
      CHECK(isinf(r.upper), "trial %d: bound without closing", trial);
    }
    ss_jsr_result_clear(&lr);
  }
  CHECK(closed >= 4, "only %d of 8 random nonnegative sets closed", closed);
}

/* ss_jsr_compute with norm POLYTOPE: the golden pair to the gap 1e-6 */
static void test_compute(void) {
  const double A[4] = {1, 1, 0, 1}, B[4] = {1, 0, 1, 1};
  const double *Y[2] = {A, B};
  const double phi = (1 + sqrt(5.0)) / 2;
  ss_jsr_opts o = ss_jsr_defaults();
  o.norm = SS_JSR_NORM_POLYTOPE;
  o.depth = 4;
  o.gap = 1e-6;
  o.max_seconds = 20;
  ss_jsr_result r;
  ss_error e = {0};
  if (ss_jsr_compute(2, 2, Y, &o, &r, &e) != SS_OK) {
    CHECK(0, "ss_jsr_compute: %s", e.msg);
    return;
  }
  CHECK(r.lower <= phi && phi <= r.upper, "[%.17g, %.17g]", r.lower, r.upper);
  CHECK(r.converged, "gap 1e-6 not reached: [%.17g, %.17g]", r.lower, r.upper);
  CHECK(r.polytope == SS_POLY_CLOSED, "polytope stop %d", r.polytope);
  CHECK(r.norm == SS_JSR_NORM_POLYTOPE || r.upper < r.poly_upper,
        "norm %d: the bound comes from the polytope or a better one", (int)r.norm);
  CHECK(r.poly_upper >= phi && r.poly_upper <= phi * (1 + 5e-7) * (1 + 1e-9),
        "polytope upper %.17g", r.poly_upper);
  ss_jsr_result_clear(&r);
}

static void test_bad_input(void) {
  const double A[4] = {1, 1, 0, 1};
  const double *Y[1] = {A};
  ss_jsr_polytope_result r;
  ss_error e = {0};
  const int bad[1] = {1}, good[1] = {0};
  CHECK(ss_jsr_polytope(1, 2, Y, bad, 1, NULL, &r, &e) == SS_EINPUT &&
            strstr(e.msg, "letter"),
        "letter out of range: %s", e.msg);
  ss_jsr_polytope_opts o = ss_jsr_polytope_defaults();
  o.eps = 0;
  CHECK(ss_jsr_polytope(1, 2, Y, good, 1, &o, &r, &e) == SS_EINPUT &&
            strstr(e.msg, "eps"),
        "eps 0: %s", e.msg);
  o = ss_jsr_polytope_defaults();
  o.max_vertices = 2;
  CHECK(ss_jsr_polytope(1, 2, Y, good, 1, &o, &r, &e) == SS_EINPUT &&
            strstr(e.msg, "cap"),
        "cap 2: %s", e.msg);
  CHECK(ss_jsr_polytope(1, 2, Y, good, 0, NULL, &r, &e) == SS_EINPUT, "empty word");
}

/* GLPK has no error return for running out of memory; under a GLPK memory
 * limit of 1 MB the golden pair from the word A (which never closes) must
 * come back as SS_ENOMEM with a message, not abort the process, and GLPK
 * must work again afterwards (the limit went with the freed environment). */
static void test_glpk_memory(void) {
  const double A[4] = {1, 1, 0, 1}, B[4] = {1, 0, 1, 1};
  const double *Y[2] = {A, B};
  const int a[1] = {0}, ab[2] = {0, 1};
  ss_jsr_polytope_opts o = ss_jsr_polytope_defaults();
  o.eps = 1e-3;
  o.max_vertices = (size_t)1 << 22;
  o.max_seconds = 60;
  ss_jsr_polytope_result r;
  ss_error e = {0};
  glp_mem_limit(1);
  const ss_status st = ss_jsr_polytope(2, 2, Y, a, 1, &o, &r, &e);
  CHECK(
      st == SS_ENOMEM && strstr(e.msg, "GLPK") && strstr(e.msg, "glp_alloc"),
      "GLPK memory limit: status %d (%s), %zu vertices, want SS_ENOMEM naming glp_alloc",
      (int)st, e.msg, r.vertices);
  int ok;
  r = poly(2, 2, Y, ab, 2, 1e-3, 1000, &ok);
  if (ok) check_exact("golden AB after GLPK's failure", &r, (1 + sqrt(5.0)) / 2, 1e-3);
}

int main(void) {
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 29);
  test_golden();
  test_bspline();
  test_rotation();
  test_tie();
  test_near();
  test_multiple();
  test_random(rng);
  test_compute();
  test_bad_input();
  test_glpk_memory();
  gsl_rng_free(rng);
  return ss_test_done("test_jsr_polytope");
}
