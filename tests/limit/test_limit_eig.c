/* test_limit_eig.c — the eigen-decomposition of a stationary run's matrix and
 * its powers (ss_lim_eig, ss_limit_eig.c), against constructions and repeated
 * multiplication done here.
 *
 * Properties:
 *   - W = T D T^-1 with D real block diagonal (1, a rotation block of
 *     modulus 0.6, 0.5, -0.45, 0.3, 0.2, -0.1): the eigenvalues are D's, the
 *     real eigenvector matrix reconstructs W (W x = lambda x for real
 *     eigenvalues, W [x y] = [x y] [a b; -b a] for a pair a + ib), V V^-1 =
 *     I, the eigenvalue 1 is found (`one`) and `second` = 0.6;
 *     ss_lim_eig_coef solves V C = P;
 *   - powers: W^m P by ss_lim_eig_power equals m repeated products (m = 0, 1,
 *     2, 7, 40) and, with the shift split off, P' + shift row by row; the
 *     limit (m < 0) equals W^(2^16) P formed here by squaring;
 *   - averaging matrices (positive, rows summing to 1, as the evaluator's
 *     runs are): the limit gives every point the same position, pi^T P with
 *     pi the left eigenvector of 1 (power iteration on W^T, here);
 *   - a Jordan block (defective W): the decomposition is refused for the
 *     powers W^(2^i) (pw set, why says so), which give W^m P for m up to
 *     4095 equal to repeated products and the limit; m = 4096 is refused;
 *   - no limit when 1 is not simple (two closed classes) or another
 *     eigenvalue has modulus 1 (a 2-cycle: -1): one = SIZE_MAX and
 *     ss_lim_eig_power(m < 0) is SS_ENUMERIC, finite powers still exact.
 *   - bit for bit (issue 37): the products with three columns, kept four
 *     rows at a time in registers, equal the plain loops of the definition
 *     (V^-1 P, the powers, the limit's single component, a plain step).
 * Mutations this catches (tried by hand: the report of issue 33):
 *   - the rotation of a complex pair's coefficients with the sign of sin
 *     flipped in the second row: W^m P differs from repeated products;
 *   - the limit keeping every component instead of only the eigenvalue-1
 *     one: the limit differs from W^(2^16) P;
 *   - the shift's mean of the eigenvector without the division by K: P' +
 *     shift differs from W^m P. */
#include <complex.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "ss_limit.h"
#include "ss_limit_impl.h"
#include "ss_test.h"

enum { KMAX = 12 };

/* c = a b, K x K row-major (c may alias neither). */
static void matmul(size_t K, const double *a, const double *b, double *c) {
  for (size_t i = 0; i < K; i++)
    for (size_t j = 0; j < K; j++) {
      double s = 0.0;
      for (size_t k = 0; k < K; k++)
        s += a[i * K + k] * b[k * K + j];
      c[i * K + j] = s;
    }
}

/* P <- W P (K x 3), m times. */
static void repeat(const double *W, size_t K, long m, double *P) {
  double Q[KMAX * 3];
  for (long s = 0; s < m; s++) {
    for (size_t i = 0; i < K; i++)
      for (int d = 0; d < 3; d++) {
        double v = 0.0;
        for (size_t j = 0; j < K; j++)
          v += W[i * K + j] * P[j * 3 + (size_t)d];
        Q[i * 3 + (size_t)d] = v;
      }
    memcpy(P, Q, K * 3 * sizeof *P);
  }
}

/* P <- W^(2^16) P by squaring W: the limit of a convergent run whose other
 * eigenvalues are below 0.99 in modulus (0.99^65536 < 1e-280), while the
 * rounding of the eigenvalue 1 grows only to about 65536 eps. */
static void limit_by_squaring(const double *W, size_t K, double *P) {
  double A[KMAX * KMAX], B[KMAX * KMAX];
  memcpy(A, W, K * K * sizeof *A);
  for (int s = 0; s < 16; s++) {
    matmul(K, A, A, B);
    memcpy(A, B, K * K * sizeof *A);
  }
  repeat(A, K, 1, P);
}

static double maxdiff(const double *a, const double *b, size_t n) {
  double m = 0.0;
  for (size_t i = 0; i < n; i++)
    m = fmax(m, fabs(a[i] - b[i]));
  return m;
}

static void points(gsl_rng *r, size_t K, double *P) {
  for (size_t i = 0; i < K * 3; i++)
    P[i] = 2.0 * gsl_rng_uniform(r) - 1.0;
}

/* Powers, shift and limit of e against repeated products of W. */
static void check_powers(const ss_lim_eig *e, const double *W, size_t K, gsl_rng *r,
                         long mmax, int limit, const char *what) {
  const long ms[6] = {0, 1, 2, 7, 40, 4095};
  ss_error err = {0};
  for (int t = 0; t < 6 && ms[t] <= mmax; t++) {
    double P[KMAX * 3], Q[KMAX * 3], R[KMAX * 3], shift[3];
    points(r, K, P);
    memcpy(Q, P, sizeof Q);
    memcpy(R, P, sizeof R);
    repeat(W, K, ms[t], Q);
    REQUIRE_OK_VOID(ss_lim_eig_power(e, ms[t], 3, P, NULL, NULL, &err), &err);
    CHECK(maxdiff(P, Q, K * 3) <= 1e-12, "%s: W^%ld P off by %g", what, ms[t],
          maxdiff(P, Q, K * 3));
    REQUIRE_OK_VOID(ss_lim_eig_power(e, ms[t], 3, R, shift, NULL, &err), &err);
    for (size_t i = 0; i < K; i++)
      for (int d = 0; d < 3; d++)
        R[i * 3 + (size_t)d] += shift[d];
    CHECK(maxdiff(R, Q, K * 3) <= 1e-12, "%s: W^%ld P = P' + shift off by %g", what,
          ms[t], maxdiff(R, Q, K * 3));
  }
  if (!limit) return;
  double P[KMAX * 3], Q[KMAX * 3];
  points(r, K, P);
  memcpy(Q, P, sizeof Q);
  limit_by_squaring(W, K, Q);
  REQUIRE_OK_VOID(ss_lim_eig_power(e, -1, 3, P, NULL, NULL, &err), &err);
  CHECK(maxdiff(P, Q, K * 3) <= 1e-10, "%s: limit off by %g", what, maxdiff(P, Q, K * 3));
}

/* W = T D T^-1, D (K x K) with its eigenvalue 1 at (0, 0) and e_0 its
 * eigenvector; T unit lower triangular with a first column of ones (T e_0 =
 * 1), so W 1 = 1: rows summing to 1, as a run's matrix's. */
static void similar(size_t K, const double *D, double *W) {
  double T[KMAX * KMAX], Ti[KMAX * KMAX], A[KMAX * KMAX];
  for (size_t i = 0; i < K; i++)
    for (size_t j = 0; j < K; j++)
      T[i * K + j] = i == j || j == 0 ? 1.0
                     : j < i          ? 0.25 * (double)((i + 3 * j) % 5) - 0.4
                                      : 0.0;
  for (size_t j = 0; j < K; j++) /* T^-1 by forward substitution */
    for (size_t i = 0; i < K; i++) {
      double v = i == j ? 1.0 : 0.0;
      for (size_t q = 0; q < i; q++)
        v -= T[i * K + q] * Ti[q * K + j];
      Ti[i * K + j] = v;
    }
  matmul(K, T, D, A);
  matmul(K, A, Ti, W);
}

static void test_diagonalisable(gsl_rng *r) {
  enum { K = 8 };
  const double rho = 0.6, th = 0.7;
  double D[K * K] = {0}, W[K * K];
  const double reals[K] = {1.0, 0, 0, 0.5, -0.45, 0.3, 0.2, -0.1};
  for (int i = 0; i < K; i++)
    D[i * K + i] = reals[i];
  D[1 * K + 1] = D[2 * K + 2] = rho * cos(th);
  D[1 * K + 2] = rho * sin(th), D[2 * K + 1] = -rho * sin(th);
  similar(K, D, W);
  ss_lim_eig *e = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_lim_eig_new(W, K, &e, &err), &err);
  CHECK(e->ok && !e->pw && e->cond <= SS_LIMIT_MAXCOND, "diagonalisable: pw %p, cond %g",
        (void *)e->pw, e->cond);
  /* the eigenvalues: D's */
  const double complex want[K] = {1.0,
                                  CMPLX(rho * cos(th), rho * sin(th)),
                                  CMPLX(rho * cos(th), -rho * sin(th)),
                                  0.5,
                                  -0.45,
                                  0.3,
                                  0.2,
                                  -0.1};
  unsigned char used[K] = {0};
  double worst = 0.0;
  for (int i = 0; i < K; i++) {
    int best = -1;
    double bd = INFINITY;
    for (int j = 0; j < K; j++)
      if (!used[j] && cabs(e->lam[j] - want[i]) < bd)
        bd = cabs(e->lam[j] - want[i]), best = j;
    used[best] = 1;
    worst = fmax(worst, bd);
  }
  CHECK(worst <= 1e-12, "diagonalisable: eigenvalues off by %g", worst);
  CHECK(e->one < K && cabs(e->lam[e->one] - 1.0) <= 1e-12 &&
            fabs(e->second - rho) <= 1e-12,
        "diagonalisable: one %zu, second %.17g", e->one, e->second);
  /* W V = V Lambda in the real block form, and V V^-1 = I */
  double res = 0.0, inv = 0.0;
  int pairs = 0;
  for (size_t j = 0; j < K; j++) {
    const double *x = e->V + j * K, *y = e->V + (j + 1) * K;
    const double a = creal(e->lam[j]), b = cimag(e->lam[j]);
    for (size_t i = 0; i < K; i++) {
      double wx = 0.0, wy = 0.0;
      for (size_t q = 0; q < K; q++) {
        wx += W[i * K + q] * x[q];
        if (e->pair[j] == 1) wy += W[i * K + q] * y[q];
      }
      if (e->pair[j] == 1) {
        res = fmax(res, fabs(wx - (a * x[i] - b * y[i])));
        res = fmax(res, fabs(wy - (b * x[i] + a * y[i])));
      } else if (e->pair[j] == 0) {
        res = fmax(res, fabs(wx - a * x[i]));
      }
    }
    pairs += e->pair[j] == 1;
    CHECK(e->pair[j] != 1 || (j + 1 < K && e->pair[j + 1] == 2 &&
                              cabs(e->lam[j + 1] - conj(e->lam[j])) <= 1e-14),
          "diagonalisable: pair %zu not followed by its conjugate", j);
    for (size_t i = 0; i < K; i++) {
      double s = 0.0;
      for (size_t q = 0; q < K; q++)
        s += e->V[q * K + i] * e->Vinv[j * K + q]; /* (V V^-1)[i][j] */
      inv = fmax(inv, fabs(s - (i == j)));
    }
  }
  CHECK(pairs == 1 && res <= 1e-12, "diagonalisable: %d pairs, |W V - V Lambda| = %g",
        pairs, res);
  CHECK(inv <= 1e-12 * e->cond, "diagonalisable: |V V^-1 - I| = %g", inv);
  /* coefficients: V C = P */
  double P[K * 3], C[K * 3], VC[K * 3] = {0};
  points(r, K, P);
  ss_lim_eig_coef(e, 3, P, C);
  for (size_t i = 0; i < K; i++)
    for (size_t j = 0; j < K; j++)
      for (int d = 0; d < 3; d++)
        VC[i * 3 + (size_t)d] += e->V[j * K + i] * C[j * 3 + (size_t)d];
  CHECK(maxdiff(VC, P, K * 3) <= 1e-12, "diagonalisable: V C - P = %g",
        maxdiff(VC, P, K * 3));
  check_powers(e, W, K, r, 40, 1, "diagonalisable");
  ss_lim_eig_free(e);
}

static void test_averaging(gsl_rng *r) {
  enum { K = 10 };
  double W[K * K];
  for (int t = 0; t < 5; t++) {
    for (int i = 0; i < K; i++) {
      double s = 0.0;
      for (int j = 0; j < K; j++)
        s += W[i * K + j] = gsl_rng_uniform_pos(r) * (gsl_rng_uniform(r) < 0.6);
      W[i * K + i] += 0.1, s += 0.1; /* aperiodic, and no zero row */
      for (int j = 0; j < K; j++)
        W[i * K + j] /= s;
    }
    /* the left eigenvector of 1: power iteration on W^T */
    double pi[K], q[K];
    for (int i = 0; i < K; i++)
      pi[i] = 1.0 / K;
    for (int s = 0; s < 2000; s++) {
      for (int j = 0; j < K; j++) {
        q[j] = 0.0;
        for (int i = 0; i < K; i++)
          q[j] += pi[i] * W[i * K + j];
      }
      memcpy(pi, q, sizeof pi);
    }
    ss_lim_eig *e = NULL;
    ss_error err = {0};
    REQUIRE_OK_VOID(ss_lim_eig_new(W, K, &e, &err), &err);
    CHECK(e->one != SIZE_MAX && e->second < 1.0, "averaging %d: one %zu, second %g", t,
          e->one, e->second);
    double P[K * 3], want[3] = {0, 0, 0};
    points(r, K, P);
    for (int i = 0; i < K; i++)
      for (int d = 0; d < 3; d++)
        want[d] += pi[i] * P[i * 3 + d];
    REQUIRE_OK_VOID(ss_lim_eig_power(e, -1, 3, P, NULL, NULL, &err), &err);
    double off = 0.0;
    for (int i = 0; i < K; i++)
      for (int d = 0; d < 3; d++)
        off = fmax(off, fabs(P[i * 3 + d] - want[d]));
    CHECK(off <= 1e-12, "averaging %d: limit points differ from pi^T P by %g", t, off);
    check_powers(e, W, K, r, 40, 1, "averaging");
    ss_lim_eig_free(e);
  }
}

static void test_defective(gsl_rng *r) {
  enum { K = 6 };
  double D[K * K] = {0}, W[K * K];
  const double d[K] = {1.0, 0.5, 0.5, 0.3, -0.2, 0.1};
  for (int i = 0; i < K; i++)
    D[i * K + i] = d[i];
  D[1 * K + 2] = 1.0; /* a Jordan block of 1/2 */
  similar(K, D, W);
  ss_lim_eig *e = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_lim_eig_new(W, K, &e, &err), &err);
  CHECK(e->ok && e->pw && strstr(e->why, "defective") && !(e->cond <= SS_LIMIT_MAXCOND),
        "Jordan block: pw %p, cond %g (%s)", (void *)e->pw, e->cond, e->why);
  CHECK(e->one != SIZE_MAX, "Jordan block: 1 is simple");
  check_powers(e, W, K, r, 4095, 1, "Jordan block");
  double P[K * 3];
  points(r, K, P);
  CHECK(ss_lim_eig_power(e, 4096, 3, P, NULL, NULL, &err) != SS_OK,
        "Jordan block: W^4096 accepted");
  ss_lim_eig_free(e);
}

static void test_no_limit(gsl_rng *r) {
  enum { K = 5 };
  /* two closed classes {0, 1} and {2, 3}, point 4 averaging both: 1 twice */
  const double two[K * K] = {0.5, 0.5, 0, 0, 0,   0.25, 0.75, 0,   0,   0,   0,   0,  0.4,
                             0.6, 0,   0, 0, 0.3, 0.7,  0,    0.2, 0.2, 0.2, 0.2, 0.2};
  /* a 2-cycle {0, 1} (eigenvalue -1) read by the others */
  const double cyc[K * K] = {0, 1, 0,   0,   0,   1,   0, 0,   0,   0,   0.2, 0.2, 0.6,
                             0, 0, 0.1, 0.1, 0.2, 0.6, 0, 0.1, 0.1, 0.1, 0.1, 0.6};
  const double *Ws[2] = {two, cyc};
  const char *names[2] = {"two closed classes", "a 2-cycle"};
  for (int t = 0; t < 2; t++) {
    ss_lim_eig *e = NULL;
    ss_error err = {0};
    REQUIRE_OK_VOID(ss_lim_eig_new(Ws[t], K, &e, &err), &err);
    CHECK(e->one == SIZE_MAX, "%s: eigenvalue 1 called simple", names[t]);
    double P[K * 3];
    points(r, K, P);
    CHECK(ss_lim_eig_power(e, -1, 3, P, NULL, NULL, &err) == SS_ENUMERIC,
          "%s: a limit that does not exist was given", names[t]);
    check_powers(e, Ws[t], K, r, 40, 0, names[t]);
    ss_lim_eig_free(e);
  }
}

/* The eigenvalue-1/2 part of a defective run (ss_lim_eig_half_part): W = T D
 * T^-1 with a Jordan block at 0.1 (so the run is declared defective) and 1/2
 * double and semisimple: Q satisfies W Q = Q / 2 and P - Q is annihilated by
 * (W - 1)(W - 0.3)(W - 0.1)^2 (it has no 1/2 part); no 1/2 at all (1, 0.45,
 * 0.3, 0.2, 0.1, 0.1): Q = 0;
 * a Jordan block at 1/2, or an eigenvalue 0.6, is refused with the reason. */
static void test_half_part(gsl_rng *r) {
  enum { K = 6 };
  const double diag[4][K] = {{1.0, 0.5, 0.5, 0.3, 0.1, 0.1},
                             {1.0, 0.45, 0.2, 0.3, 0.1, 0.1},
                             {1.0, 0.5, 0.5, 0.3, 0.1, 0.1},
                             {1.0, 0.6, 0.5, 0.3, 0.1, 0.1}};
  const char *what[4] = {"1/2 semisimple", "no 1/2", "a Jordan block at 1/2", "0.6"};
  for (int t = 0; t < 4; t++) {
    double D[K * K] = {0}, W[K * K], P[K * 3], Q[K * 3], R[K * 3];
    for (int i = 0; i < K; i++)
      D[i * K + i] = diag[t][i];
    D[4 * K + 5] = 1.0;             /* a Jordan block at 0.1 */
    if (t == 2) D[1 * K + 2] = 1.0; /* and one at 1/2 */
    similar(K, D, W);
    ss_lim_eig *e = NULL;
    ss_error err = {0};
    REQUIRE_OK_VOID(ss_lim_eig_new(W, K, &e, &err), &err);
    CHECK(e->pw != NULL, "%s: not declared defective (cond %g)", what[t], e->cond);
    points(r, K, P);
    ss_status st = ss_lim_eig_half_part(e, W, 3, P, Q, &err);
    if (t >= 2) {
      CHECK(st == SS_ENUMERIC && strstr(err.msg, t == 2 ? "Jordan block" : "modulus 0.6"),
            "%s: not refused: %d %s", what[t], (int)st, err.msg);
      ss_lim_eig_free(e);
      continue;
    }
    CHECK(st == SS_OK, "%s: %s", what[t], err.msg);
    /* W Q = Q / 2 */
    memcpy(R, Q, sizeof R);
    repeat(W, K, 1, R);
    for (size_t i = 0; i < K * 3; i++)
      R[i] -= 0.5 * Q[i];
    CHECK(maxdiff(R, (double[K * 3]){0}, K * 3) <= 1e-12, "%s: W Q - Q/2 = %g", what[t],
          maxdiff(R, (double[K * 3]){0}, K * 3));
    /* (W - 1)(W - 0.3)(W - 0.1)^2 (P - Q) = 0 */
    for (size_t i = 0; i < K * 3; i++)
      R[i] = P[i] - Q[i];
    for (int q = 0; q < K; q++) { /* the roots: D's diagonal but 1/2 */
      if (diag[t][q] == 0.5) continue;
      double S[K * 3];
      memcpy(S, R, sizeof S);
      repeat(W, K, 1, S);
      for (size_t i = 0; i < K * 3; i++)
        R[i] = S[i] - diag[t][q] * R[i];
    }
    double zero[K * 3] = {0}, qn = maxdiff(Q, zero, K * 3);
    CHECK(maxdiff(R, zero, K * 3) <= 1e-12, "%s: P - Q has a 1/2 part: %g", what[t],
          maxdiff(R, zero, K * 3));
    CHECK(t == 0 ? qn > 1e-3 : qn == 0.0, "%s: |Q| = %g", what[t], qn);
    ss_lim_eig_free(e);
  }
}

/* P (K x 4) from the K x 3 Q, a fourth column of other values: the plain
 * loops (D != 3) act on each column alike, so their first three columns are
 * the sums of the definition, in its order. */
static void widen(const double *Q, size_t K, gsl_rng *r, double *P) {
  for (size_t i = 0; i < K; i++) {
    memcpy(P + i * 4, Q + i * 3, 3 * sizeof *P);
    P[i * 4 + 3] = gsl_rng_uniform(r);
  }
}

/* Whether the K x 3 a equals the first three columns of the K x 4 b, bit
 * for bit. */
static int same3(const double *a, const double *b, size_t K) {
  for (size_t i = 0; i < K; i++)
    if (memcmp(a + i * 3, b + i * 4, 3 * sizeof *a)) return 0;
  return 1;
}

/* The products with three columns (four rows' sums kept in registers, the
 * evaluator's common case) against the plain loops of the definition, bit
 * for bit: each entry is a sum from +0 in the order of the points (V^-1 P),
 * of the components (V C, over those of nonzero coefficients) or of a row's
 * nonzeros (a plain step), so any other order -- the sums split, reversed or
 * fused -- changes last bits, and the spokes' evidence with them (issue 37).
 * K = 11, not a multiple of 4 (the last rows alone); the first point 0, as
 * the walk's recentred nets have it; the limit (m < 0) forms only the
 * eigenvalue-1 coefficients: against the whole C with the others zeroed. */
static void test_bitwise(gsl_rng *r) {
  enum { K = 11 };
  double D[K * K] = {0}, W[K * K];
  const double reals[K] = {1.0, 0, 0, 0.5, -0.45, 0.3, 0.2, -0.1, 0.05, 0.4, -0.25};
  for (int i = 0; i < K; i++)
    D[i * K + i] = reals[i];
  D[1 * K + 1] = D[2 * K + 2] = 0.6 * cos(0.7);
  D[1 * K + 2] = 0.6 * sin(0.7), D[2 * K + 1] = -0.6 * sin(0.7);
  similar(K, D, W);
  ss_lim_eig *e = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_lim_eig_new(W, K, &e, &err), &err);
  double P[K * 3], C[K * 3], P4[K * 4], C4[K * 4], sh[3], sh4[4];
  points(r, K, P);
  P[0] = P[1] = P[2] = 0.0;
  widen(P, K, r, P4);
  ss_lim_eig_coef(e, 3, P, C);
  ss_lim_eig_coef(e, 4, P4, C4);
  CHECK(same3(C, C4, K), "bitwise: V^-1 P with 3 columns differs from the plain loop");
  const long ms[3] = {1, 7, 40};
  for (int t = 0; t < 3; t++) {
    double Q[K * 3], Q4[K * 4];
    memcpy(Q, P, sizeof Q);
    memcpy(Q4, P4, sizeof Q4);
    int s3 = 0, s4 = 0;
    REQUIRE_OK_VOID(ss_lim_eig_power(e, ms[t], 3, Q, sh, &s3, &err), &err);
    REQUIRE_OK_VOID(ss_lim_eig_power(e, ms[t], 4, Q4, sh4, &s4, &err), &err);
    CHECK(same3(Q, Q4, K) && !memcmp(sh, sh4, sizeof sh) && s3 == s4,
          "bitwise: W^%ld P with 3 columns differs from the plain loops", ms[t]);
  }
  /* the limit: V (C with only the eigenvalue-1 row) in the definition's
   * order, from the whole C of the plain loop */
  double L[K * 3], want[K * 3] = {0};
  memcpy(L, P, sizeof L);
  REQUIRE_OK_VOID(ss_lim_eig_power(e, -1, 3, L, NULL, NULL, &err), &err);
  for (size_t i = 0; i < K; i++)
    for (int d = 0; d < 3; d++)
      want[i * 3 + (size_t)d] += e->V[e->one * K + i] * C4[e->one * 4 + (size_t)d];
  CHECK(!memcmp(L, want, sizeof L), "bitwise: the limit differs from V C's one term");
  /* a plain step over W's nonzeros (a third of them zeroed) */
  size_t rp[K + 1], ci[K * K], nz = 0;
  for (size_t i = 0; i < K * K; i++)
    if (gsl_rng_uniform(r) < 0.33) W[i] = 0.0;
  for (size_t i = 0; i < K; i++) {
    rp[i] = nz;
    for (size_t j = 0; j < K; j++)
      if (W[i * K + j] != 0.0) ci[nz++] = j;
  }
  rp[K] = nz;
  ss_lim_trans tr = {0};
  tr.W = W, tr.rp = rp, tr.ci = ci;
  double *X = malloc(sizeof P), *X4 = malloc(sizeof P4);
  if (!X || !X4) {
    CHECK(0, "bitwise: memory");
    free(X), free(X4), ss_lim_eig_free(e);
    return;
  }
  memcpy(X, P, sizeof P);
  memcpy(X4, P4, sizeof P4);
  REQUIRE_OK_VOID(ss_lim_trans_apply(&tr, K, K, 3, &X, &err), &err);
  REQUIRE_OK_VOID(ss_lim_trans_apply(&tr, K, K, 4, &X4, &err), &err);
  CHECK(same3(X, X4, K), "bitwise: a plain step with 3 columns differs from the loop");
  free(X);
  free(X4);
  ss_lim_eig_free(e);
}

int main(void) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 1033);
  test_diagonalisable(r);
  test_averaging(r);
  test_defective(r);
  test_no_limit(r);
  test_half_part(r);
  test_bitwise(r);
  gsl_rng_free(r);
  return ss_test_done("limit_eig");
}
