/* test_simil.c — the verified similarity (ss_simil.h) on matrices of known
 * spectrum: the one-ring block A = V D V^-1 with V unit lower triangular of
 * first column 1 (integer, det 1, so V^-1 is integer and A's rows sum to 1),
 * D block diagonal with dyadic eigenvalues, and an outer block C (a 2 x 2
 * component and two 1 x 1 ones) of known eigenvalues.
 *   - generic (1, 1/2, 3/8, 1/4, 1/8, -1/16): a pass; every eigenvalue of D
 *     and of C lies in a disc of its block, each component of discs holds as
 *     many of them as it has discs, lambda1..3 in the leading discs; the
 *     exact path (ss_exact, a second computation) certifies the pass too, its
 *     roots lie in the discs and its exact rational basis lies in the basis
 *     enclosure up to each column's scale;
 *   - lambda3 = lambda4 = 1/4 exactly (the exact path: a certified fail), a
 *     tie lambda1 = lambda2 = 1/2, a complex leading pair 1/2 +- i/4 and a
 *     Jordan block at 1/2: no pass;
 *   - a block with R = 2 X^-1 (alpha = 1) refused; a poor X (V with 1e-3
 *     added) and R = V^-1, and X = V with a poor R = (1 + 1e-3) V^-1: the
 *     discs still hold D's eigenvalues with their counts — for the poor R
 *     only through delta (mutation: delta = 0 fails that check). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_exact.h"
#include "ss_simil.h"
#include "ss_simil_impl.h"
#include "ss_test.h"

enum { K = 6, N = 10 };

static const double V[K][K] = {{1, 0, 0, 0, 0, 0},  {1, 1, 0, 0, 0, 0},
                               {1, -2, 1, 0, 0, 0}, {1, 1, 3, 1, 0, 0},
                               {1, 0, -1, 2, 1, 0}, {1, 2, 1, -1, 1, 1}};

/* W = V^-1 (exact: forward substitution on integers). */
static void inverse_v(double W[K][K]) {
  for (int c = 0; c < K; c++)
    for (int i = 0; i < K; i++) {
      double t = i == c ? 1.0 : 0.0;
      for (int j = 0; j < i; j++)
        t -= V[i][j] * W[j][c];
      W[i][c] = t;
    }
}

/* S (N x N) = [V D V^-1, 0; B C] with D given (K x K), C's eigenvalues
 * 3/32, 1/32 (a 2 x 2 component), 1/8 and -1/32; rows sum to 1. */
static void build(double D[K][K], double *S) {
  double W[K][K], VD[K][K];
  inverse_v(W);
  memset(S, 0, N * N * sizeof *S);
  for (int i = 0; i < K; i++)
    for (int j = 0; j < K; j++) {
      VD[i][j] = 0.0;
      for (int l = 0; l < K; l++)
        VD[i][j] += V[i][l] * D[l][j];
    }
  for (int i = 0; i < K; i++)
    for (int j = 0; j < K; j++)
      for (int l = 0; l < K; l++)
        S[i * N + j] += VD[i][l] * W[l][j];
  const double C[4][4] = {{1.0 / 16, 1.0 / 32, 0, 0},
                          {1.0 / 32, 1.0 / 16, 0, 0},
                          {0, 0.25, 0.125, 0},
                          {0, 0, 0.5, -1.0 / 32}};
  for (int i = 0; i < 4; i++) {
    double sum = 0.0;
    for (int j = 0; j < 4; j++) {
      S[(K + i) * N + K + j] = C[i][j];
      sum += C[i][j];
    }
    S[(K + i) * N + (i % 3)] = 1.0 - sum; /* B: exact dyadic */
  }
}

static void diag(double D[K][K], const double *d) {
  memset(D, 0, sizeof(double[K][K]));
  for (int i = 0; i < K; i++)
    D[i][i] = d[i];
}

static int in_disc(const ss_simil_disc *d, double re, double im) {
  return hypot(re - d->re, im - d->im) <= d->rad;
}

/* Disc of block b among blk's (-1: A; -2: any outer block). */
static int same(long b, long blk) {
  return blk == -2 ? b >= 0 : b == blk;
}

/* Each connected component of the discs of block blk holds exactly as many
 * of the eigenvalues ev (ne of them, complex split) as it has discs, and
 * every eigenvalue lies in a disc.  Returns the number of violations. */
static int counts_hold(const ss_simil_disc *d, size_t nd, long blk, const double *er,
                       const double *ei, int ne) {
  int comp[N], bad = 0;
  for (size_t i = 0; i < nd; i++)
    comp[i] = (int)i;
  for (int pass = 0; pass < N; pass++) /* label propagation */
    for (size_t i = 0; i < nd; i++)
      for (size_t j = 0; j < nd; j++)
        if (same(d[i].block, blk) && same(d[j].block, blk) &&
            hypot(d[i].re - d[j].re, d[i].im - d[j].im) <= d[i].rad + d[j].rad &&
            comp[j] < comp[i])
          comp[i] = comp[j];
  for (size_t c = 0; c < nd; c++) {
    if (!same(d[c].block, blk) || comp[c] != (int)c) continue;
    int discs = 0, held = 0;
    for (size_t i = 0; i < nd; i++)
      discs += same(d[i].block, blk) && comp[i] == (int)c;
    for (int e = 0; e < ne; e++) {
      int in = 0;
      for (size_t i = 0; i < nd && !in; i++)
        in = same(d[i].block, blk) && comp[i] == (int)c && in_disc(d + i, er[e], ei[e]);
      held += in;
    }
    bad += held != discs;
  }
  for (int e = 0; e < ne; e++) {
    int in = 0;
    for (size_t i = 0; i < nd; i++)
      in |= same(d[i].block, blk) && in_disc(d + i, er[e], ei[e]);
    bad += !in;
  }
  return bad;
}

static ss_simil *run(double D[K][K], double *S) {
  build(D, S);
  ss_simil *s = NULL;
  ss_error err = {0};
  const ss_status st = ss_simil_new(S, N, K, 3, 1L << 18, &s, &err);
  CHECK(!st, "ss_simil_new: %s", err.msg);
  return s;
}

/* The exact path's roots in the discs, its pass and its rational basis in
 * the enclosure (each column scaled at the entry where ours is 1). */
static void against_exact(const ss_simil *s, const double *S) {
  ss_exact *x = NULL;
  ss_error err = {0};
  ss_exact_opts o = ss_exact_defaults(3);
  const ss_status st = ss_exact_new(S, N, K, &o, &x, &err);
  CHECK(!st, "exact path: %s", err.msg);
  if (st) return;
  ss_verdict v;
  int cert = 0;
  ss_exact_condition(x, &v, &cert);
  CHECK(v.verdict == SS_PASS && cert, "exact path passes: %s", v.reason);
  size_t nr = 0, nd = 0, lead[4];
  const ss_exact_root *r = ss_exact_roots(x, &nr);
  const ss_simil_disc *d = ss_simil_discs(s, &nd);
  CHECK(ss_simil_lead(s, lead), "leading discs");
  for (size_t i = 0; i < nr; i++) {
    int in = 0;
    for (size_t j = 0; j < nd; j++)
      in |= in_disc(d + j, r[i].re, r[i].im);
    CHECK(in, "exact root %zu (%g) in a disc", i, r[i].re);
  }
  for (int q = 0; q <= 3 && nr > 3; q++)
    CHECK(in_disc(d + lead[q], r[q].re, r[q].im), "root %d in its leading disc", q);
  long long num[N * 3], den[N * 3];
  double lo[N * 3], hi[N * 3];
  CHECK(ss_exact_basis_rational(x, num, den), "exact rational basis");
  CHECK(!ss_ball_outcome_basis(ss_simil_outcome(s), lo, hi, &err), "basis: %s", err.msg);
  for (int q = 0; q < 3; q++) {
    int p = -1;
    for (int i = 0; i < N; i++)
      if (lo[q * N + i] <= 1.0 && hi[q * N + i] >= 1.0 &&
          hi[q * N + i] - lo[q * N + i] < 1e-6)
        p = i;
    CHECK(p >= 0 && num[q * N + (p < 0 ? 0 : p)] != 0, "column %d has its unit entry", q);
    if (p < 0 || num[q * N + p] == 0) continue;
    const double sc = (double)den[q * N + p] / (double)num[q * N + p];
    for (int i = 0; i < N; i++) {
      const double t = (double)num[q * N + i] / (double)den[q * N + i] * sc;
      const double slack = 4e-16 * fabs(t);
      CHECK(lo[q * N + i] - slack <= t && t <= hi[q * N + i] + slack,
            "basis column %d entry %d: %.17g in [%.17g, %.17g]", q, i, t, lo[q * N + i],
            hi[q * N + i]);
      CHECK(hi[q * N + i] - lo[q * N + i] < 1e-9, "column %d entry %d tight", q, i);
    }
  }
  ss_exact_free(x);
}

static void generic(void) {
  const double d[K] = {1, 0.5, 0.375, 0.25, 0.125, -0.0625};
  const double cr[4] = {3.0 / 32, 1.0 / 32, 0.125, -1.0 / 32}, ci[4] = {0};
  double D[K][K], S[N * N], zi[K] = {0};
  diag(D, d);
  ss_simil *s = run(D, S);
  if (!s) return;
  CHECK(ss_simil_passed(s), "generic: a pass (%s)", ss_simil_why(s));
  size_t nd = 0;
  const ss_simil_disc *dd = ss_simil_discs(s, &nd);
  CHECK(nd == N, "one disc per row: %zu", nd);
  CHECK(!counts_hold(dd, nd, -1, d, zi, K), "A's discs hold D's eigenvalues");
  /* C's discs together: each component of their union holds as many of its
   * eigenvalues as discs (summed over the blocks) */
  CHECK(!counts_hold(dd, nd, -2, cr, ci, 4), "outer discs hold C's eigenvalues");
  const ss_ball_outcome *o = ss_simil_outcome(s);
  ss_verdict v;
  int cert = 0;
  ss_ball_outcome_condition(o, &v, &cert);
  CHECK(v.verdict == SS_PASS && cert && strstr(v.reason, "verified similarity"),
        "verdict: %s", v.reason);
  against_exact(s, S);
  ss_simil_free(s);
}

/* No pass for D (name for messages); the exact path's verdict on it is
 * expected_exact (certified). */
static void refused(const char *name, double D[K][K], ss_verdict_kind expected_exact) {
  double S[N * N];
  ss_simil *s = run(D, S);
  if (!s) return;
  CHECK(!ss_simil_passed(s), "%s: not passed by the similarity", name);
  size_t lead[4];
  CHECK(!ss_simil_lead(s, lead), "%s: no leading discs", name);
  ss_exact *x = NULL;
  ss_error err = {0};
  ss_exact_opts o = ss_exact_defaults(3);
  const ss_status st = ss_exact_new(S, N, K, &o, &x, &err);
  CHECK(!st, "%s: exact: %s", name, err.msg);
  if (!st) {
    ss_verdict v;
    int cert = 0;
    ss_exact_condition(x, &v, &cert);
    CHECK(v.verdict == expected_exact && cert, "%s: exact verdict %s", name, v.reason);
  }
  ss_exact_free(x);
  ss_simil_free(s);
}

static void ties_and_pairs(void) {
  double D[K][K];
  const double tie3[K] = {1, 0.5, 0.375, 0.25, 0.25, -0.0625};
  diag(D, tie3);
  refused("lambda3 = lambda4", D, SS_FAIL);
  double S[N * N];
  ss_simil *s = run(D, S);
  if (s) { /* the tied discs: one component of two discs holding both */
    size_t nd = 0;
    const double zi[K] = {0};
    const ss_simil_disc *dd = ss_simil_discs(s, &nd);
    CHECK(!counts_hold(dd, nd, -1, tie3, zi, K), "tie: counts (%zu discs: %s)", nd,
          ss_simil_why(s));
    ss_simil_free(s);
  }
  const double tie1[K] = {1, 0.5, 0.5, 0.25, 0.125, -0.0625};
  diag(D, tie1);
  refused("lambda1 = lambda2", D, SS_PASS); /* the exact path passes it */
  const double cx[K] = {1, 0.5, 0.5, 0.25, 0.125, -0.0625};
  diag(D, cx);
  D[1][2] = 0.25;
  D[2][1] = -0.25;
  refused("complex pair", D, SS_FAIL);
  diag(D, tie1);
  D[1][2] = 1.0;
  refused("Jordan block", D, SS_FAIL);
}

/* A block given X and R directly (ss_simil_block_with). */
static void given_x(void) {
  double W[K][K], D[K][K], S[N * N], T[K * K], Tr[K * K] = {0};
  const double d[K] = {1, 0.5, 0.375, 0.25, 0.125, -0.0625}, zi[K] = {0};
  diag(D, d);
  build(D, S);
  inverse_v(W);
  for (int i = 0; i < K; i++)
    for (int j = 0; j < K; j++)
      T[i * K + j] = S[i * N + j];
  double Xr[K * K], Xi[K * K] = {0}, Rr[K * K], Ri[K * K] = {0};
  ss_simil_disc disc[K];
  struct ss_simil s = {0};
  s.d = disc;
  for (int i = 0; i < K * K; i++) {
    Xr[i] = V[i / K][i % K];
    Rr[i] = 2.0 * W[i / K][i % K];
  }
  CHECK(ss_simil_block_with(&s, T, Tr, K, -1, Xr, Xi, Rr, Ri) == 1, "alpha = 1 refused");
  CHECK(s.nd == 0, "no discs from a refused block");
  for (int i = 0; i < K * K; i++) {
    Xr[i] = V[i / K][i % K] + (i % 5 == 1 ? 1e-3 : 0.0);
    Rr[i] = W[i / K][i % K];
  }
  CHECK(ss_simil_block_with(&s, T, Tr, K, -1, Xr, Xi, Rr, Ri) == 0, "poor X accepted");
  CHECK(!counts_hold(disc, s.nd, -1, d, zi, K), "poor X: discs hold D's eigenvalues");
  /* R = (1 + 1e-3) V^-1: B = R T X = (1 + 1e-3) D has no off-diagonal part,
   * so only delta (alpha = 1e-3) brings D's eigenvalues into the discs */
  s.nd = 0;
  for (int i = 0; i < K * K; i++) {
    Xr[i] = V[i / K][i % K];
    Rr[i] = (1.0 + 1e-3) * W[i / K][i % K];
  }
  CHECK(ss_simil_block_with(&s, T, Tr, K, -1, Xr, Xi, Rr, Ri) == 0, "poor R accepted");
  CHECK(!counts_hold(disc, s.nd, -1, d, zi, K), "poor R: discs hold D's eigenvalues");
}

int main(void) {
  generic();
  ties_and_pairs();
  given_x();
  return ss_test_done("simil");
}
