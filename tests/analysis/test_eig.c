/* test_eig.c — the eigenstructure of a block lower-triangular S = [A 0; B C]
 * (ss_eig) on matrices whose spectrum is known by construction, with every
 * expectation computed here from the construction, never from ss_eig.
 *
 * Properties:
 *   - block structure: A = Q D Q^T (Q a Householder reflection, D given) and
 *     C block lower triangular after a random relabelling of its nodes, with
 *     diagonal blocks of closed-form spectra (1 x 1 entries, a 2 x 2 block
 *     a +- sqrt(bc), a rotation block a +- ib, c times a 3-cycle: c times the
 *     cube roots of unity): the spectrum of S is D together with the blocks'
 *     (to 1e-12), the eigenvalues of D are found in the one-ring block
 *     (block 0) and the others outside, nblocks and largest_block are the
 *     construction's; one dense dgeev of S (ss_eig_dense) agrees;
 *   - relabelling: permuting the one-ring points among themselves and the
 *     outer points among themselves (a permutation similarity keeping the
 *     form) changes no eigenvalue, group, multiplicity, block count or
 *     verdict;
 *   - similarity: P D P^-1 (P unit lower triangular) has the eigenvalues D;
 *   - the companion matrix of prod (x - r_i) with dyadic roots has the
 *     roots as eigenvalues, each within its rounding bound (ss_eigval.err,
 *     documented as approximate); with a double root it is non-derogatory,
 *     so the double root is a Jordan block: one group of 2, and the Schur
 *     basis is marked defective; with the same roots in a diagonalisable
 *     matrix it is not;
 *   - the cubic B-spline's local matrix (5 points, the one-ring of 3 first)
 *     has 1, 1/2, 1/4, 1/8, 1/8 (1/8 twice, in two outer 1 x 1 blocks: one
 *     group of 2): surface condition (lambda2 = 1/4 > 1/8) passes, volume
 *     condition (lambda3 = 1/8 = |lambda4|) fails; its tensor squares
 *     (bicubic, 25 points) and cubes (tricubic, 125) have the products of
 *     those eigenvalues, and lambda1 = lambda2 = 1/2 (surface), lambda1..3 =
 *     1/2 (volume) pass as one group with a Schur basis that is not
 *     defective;
 *   - every basis returned spans an invariant subspace: S X = X T to
 *     rounding, X of full rank; a leading eigenvalue in the outer block gives
 *     a Schur basis of the whole S with the same property;
 *   - ordering: decreasing modulus; ties real first, the larger real part
 *     first, then the larger imaginary part;
 *   - groups: eigenvalues 1e-8 apart (relative) are one group at tol 1e-6
 *     and 1e-7, two at 1e-9 and 1e-10 (well above the rounding floor of a
 *     symmetric matrix);
 *   - verdicts of constructed failures in the outer block (a negative or
 *     complex leading outer eigenvalue) and of lambda0 != 1;
 *   - refused input: a one-ring row reading an outer column, tolerances out
 *     of range, dim not 2 or 3.
 * Mutations this catches (tried by hand: the report of issue 33):
 *   - an outer 1 x 1 block read at the wrong diagonal entry (S[i][i] with
 *     i = comp instead of n1 + comp): the block spectrum check fails;
 *   - ties sorted with the negative real first: the ordering check;
 *   - groups joined at tol * 100: the tolerance check (1e-8 apart at 1e-9);
 *   - the extension of the eigenvector basis to the outer rows with B's sign
 *     flipped: S X = X T fails on the B-spline matrices. */
#include <complex.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "ss_eig.h"
#include "ss_test.h"

/* ---- small dense helpers (row-major) ---- */

static void matmul(size_t n, const double *a, const double *b, double *c) {
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      double s = 0.0;
      for (size_t k = 0; k < n; k++)
        s += a[i * n + k] * b[k * n + j];
      c[i * n + j] = s;
    }
}

/* Q D Q^T with Q = I - 2 v v^T / (v^T v): symmetric, eigenvalues d. */
static void householder_similar(size_t n, const double *d, const double *v, double *A) {
  double vv = 0.0;
  for (size_t i = 0; i < n; i++)
    vv += v[i] * v[i];
  double *Q = malloc(n * n * sizeof *Q), *T = malloc(n * n * sizeof *T);
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      Q[i * n + j] = (i == j) - 2.0 * v[i] * v[j] / vv;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      T[i * n + j] = Q[i * n + j] * d[j]; /* Q D */
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      double s = 0.0;
      for (size_t k = 0; k < n; k++)
        s += T[i * n + k] * Q[j * n + k];
      A[i * n + j] = s;
    }
  free(Q);
  free(T);
}

/* Whether the multiset of computed (re, im) matches the expected one within
 * tol (absolute): greedy nearest matching; returns the worst distance. */
static double match_spectrum(const double complex *want, size_t n, const double *re,
                             const double *im) {
  unsigned char *used = calloc(n, 1);
  double worst = 0.0;
  for (size_t i = 0; i < n; i++) {
    size_t best = SIZE_MAX;
    double bd = INFINITY;
    for (size_t j = 0; j < n; j++) {
      if (used[j]) continue;
      const double d = cabs(want[i] - CMPLX(re[j], im[j]));
      if (d < bd) bd = d, best = j;
    }
    if (best != SIZE_MAX) used[best] = 1;
    worst = fmax(worst, bd);
  }
  free(used);
  return worst;
}

static ss_eig *eig(const double *S, size_t n, size_t n1, int dim, double tol, int basis,
                   const char *what) {
  ss_eig_opts o = ss_eig_defaults(dim);
  o.tol = tol;
  o.basis = basis;
  ss_eig *e = NULL;
  ss_error err = {0};
  if (ss_eig_new(S, n, n1, &o, &e, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    return NULL;
  }
  return e;
}

static void values(const ss_eig *e, double *re, double *im) {
  for (size_t i = 0; i < e->n; i++)
    re[i] = e->val[i].re, im[i] = e->val[i].im;
}

/* S X = X T and X of full rank, for e's basis (if any). */
static void check_basis(const double *S, const ss_eig *e, const char *what) {
  CHECK(e->basis && e->T, "%s: no basis", what);
  if (!e->basis || !e->T) return;
  const size_t n = e->n, m = (size_t)e->m;
  const double *X = e->basis, *T = e->T;
  double res = 0.0, xmax = 0.0;
  for (size_t j = 0; j < m; j++)
    for (size_t i = 0; i < n; i++) {
      double sx = 0.0, xt = 0.0;
      for (size_t k = 0; k < n; k++)
        sx += S[i * n + k] * X[j * n + k];
      for (size_t l = 0; l < m; l++)
        xt += X[l * n + i] * T[j * m + l];
      res = fmax(res, fabs(sx - xt));
      xmax = fmax(xmax, fabs(X[j * n + i]));
    }
  CHECK(res <= 1e-12 * xmax, "%s: |S X - X T| = %g (|X| %g)", what, res, xmax);
  /* full rank: the Gram matrix of the normalised columns has det > 1e-6 */
  double G[9] = {0}, nrm[3] = {0};
  for (size_t a = 0; a < m; a++)
    for (size_t i = 0; i < n; i++)
      nrm[a] += X[a * n + i] * X[a * n + i];
  for (size_t a = 0; a < m; a++)
    for (size_t b = 0; b < m; b++) {
      for (size_t i = 0; i < n; i++)
        G[a * 3 + b] += X[a * n + i] * X[b * n + i];
      G[a * 3 + b] /= sqrt(nrm[a] * nrm[b]);
    }
  if (m == 2) G[8] = 1.0;
  const double det = G[0] * (G[4] * G[8] - G[5] * G[7]) -
                     G[1] * (G[3] * G[8] - G[5] * G[6]) +
                     G[2] * (G[3] * G[7] - G[4] * G[6]);
  CHECK(det > 1e-6, "%s: basis nearly singular (Gram det %g)", what, det);
}

/* ---- block structure, relabelling, the dense cross-check ---- */

enum { BN1 = 5, BNC = 12, BN = BN1 + BNC };

/* S of the block test: A = Q D Q^T; C's diagonal blocks in construction
 * order [0.15], [[0.1, 0.02], [0.03, 0.1]], [[0.12, -0.05], [0.05, 0.12]],
 * 0.09 x (3-cycle), [-0.13], [0.11], [0.07], [0.05]; lower blocks and B
 * random; then C's nodes relabelled by perm.  want receives the spectrum. */
static void block_matrix(gsl_rng *r, const size_t *perm, double *S,
                         double complex *want) {
  const double d[BN1] = {1.0, 0.5, 0.4, 0.3, 0.2};
  const double v[BN1] = {1.0, -0.5, 0.25, 2.0, 0.75};
  double A[BN1 * BN1], C[BNC * BNC] = {0};
  householder_similar(BN1, d, v, A);
  /* the diagonal blocks: start offsets and sizes */
  const int bs[8] = {0, 1, 3, 5, 8, 9, 10, 11}, bz[8] = {1, 2, 2, 3, 1, 1, 1, 1};
  C[0] = 0.15;
  C[1 * BNC + 1] = 0.1, C[1 * BNC + 2] = 0.02, C[2 * BNC + 1] = 0.03,
              C[2 * BNC + 2] = 0.1;
  C[3 * BNC + 3] = 0.12, C[3 * BNC + 4] = -0.05, C[4 * BNC + 3] = 0.05,
              C[4 * BNC + 4] = 0.12;
  C[5 * BNC + 6] = 0.09, C[6 * BNC + 7] = 0.09, C[7 * BNC + 5] = 0.09;
  C[8 * BNC + 8] = -0.13, C[9 * BNC + 9] = 0.11, C[10 * BNC + 10] = 0.07,
              C[11 * BNC + 11] = 0.05;
  for (int b = 1; b < 8; b++) /* strictly below the diagonal blocks */
    for (int i = bs[b]; i < bs[b] + bz[b]; i++)
      for (int j = 0; j < bs[b]; j++)
        if (gsl_rng_uniform(r) < 0.4) C[i * BNC + j] = 0.1 * gsl_rng_uniform_pos(r);
  memset(S, 0, BN * BN * sizeof *S);
  for (int i = 0; i < BN1; i++)
    for (int j = 0; j < BN1; j++)
      S[i * BN + j] = A[i * BN1 + j];
  for (int i = 0; i < BNC; i++) {
    const size_t pi = BN1 + perm[i];
    for (int j = 0; j < BN1; j++)
      S[pi * BN + (size_t)j] = gsl_rng_uniform(r) < 0.5 ? gsl_rng_uniform(r) : 0.0;
    for (int j = 0; j < BNC; j++)
      S[pi * BN + BN1 + perm[j]] = C[i * BNC + j];
  }
  size_t k = 0;
  for (int i = 0; i < BN1; i++)
    want[k++] = d[i];
  const double s6 = sqrt(0.02 * 0.03);
  const double complex w = CMPLX(-0.5, sqrt(0.75));
  const double complex cw[BNC] = {0.15,
                                  0.1 + s6,
                                  0.1 - s6,
                                  CMPLX(0.12, 0.05),
                                  CMPLX(0.12, -0.05),
                                  0.09,
                                  0.09 * w,
                                  0.09 * conj(w),
                                  -0.13,
                                  0.11,
                                  0.07,
                                  0.05};
  for (int i = 0; i < BNC; i++)
    want[k++] = cw[i];
}

static void test_blocks(void) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 7);
  size_t perm[BNC];
  for (int t = 0; t < 8; t++) {
    for (int i = 0; i < BNC; i++)
      perm[i] = (size_t)i;
    if (t) gsl_ran_shuffle(r, perm, BNC, sizeof *perm);
    double S[BN * BN], re[BN], im[BN];
    double complex want[BN];
    block_matrix(r, perm, S, want);
    char what[64];
    snprintf(what, sizeof what, "blocks, relabelling %d", t);
    ss_eig *e = eig(S, BN, BN1, 3, 1e-6, 1, what);
    if (!e) continue;
    values(e, re, im);
    const double worst = match_spectrum(want, BN, re, im);
    CHECK(worst <= 1e-12, "%s: spectrum off by %g", what, worst);
    CHECK(e->nblocks == 8 && e->largest_block == 3, "%s: %zu blocks, largest %zu", what,
          e->nblocks, e->largest_block);
    /* D's eigenvalues in the one-ring block, the rest outside */
    int misplaced = 0;
    for (size_t i = 0; i < BN; i++) {
      int in_d = 0;
      for (int j = 0; j < BN1; j++)
        in_d |= cabs(want[j] - CMPLX(re[i], im[i])) <= 1e-12;
      misplaced += in_d != (e->val[i].block == 0);
    }
    CHECK(misplaced == 0, "%s: %d eigenvalues in the wrong block", what, misplaced);
    /* lambda1..3 = 0.5, 0.4, 0.3 > |lambda4| = 0.2: pass, eigenvectors */
    CHECK(e->cond.verdict == SS_PASS, "%s: %s (%s)", what,
          ss_verdict_name(e->cond.verdict), e->cond.reason);
    CHECK(e->ngroups == BN, "%s: %d groups of %d distinct eigenvalues", what, e->ngroups,
          BN);
    check_basis(S, e, what);
    CHECK(!strcmp(e->basis_kind, "eigenvectors") && !e->defective, "%s: basis %s", what,
          e->basis_kind);
    /* the dense cross-check: one dgeev of the whole S */
    double dre[BN], dim_[BN];
    ss_error err = {0};
    if (!ss_eig_dense(S, BN, dre, dim_, &err)) {
      const double wd = match_spectrum(want, BN, dre, dim_);
      CHECK(wd <= 1e-12, "%s: dense spectrum off by %g", what, wd);
    } else {
      CHECK(0, "%s: dense: %s", what, err.msg);
    }
    /* relabel the one-ring too: points 1 and 3 swapped (the centre stays
     * first only by convention; any permutation inside the block is a
     * similarity) */
    double T[BN * BN];
    const size_t p1[BN1] = {3, 1, 4, 0, 2};
    for (size_t i = 0; i < BN; i++)
      for (size_t j = 0; j < BN; j++) {
        const size_t a = i < BN1 ? p1[i] : i, b = j < BN1 ? p1[j] : j;
        T[a * BN + b] = S[i * BN + j];
      }
    ss_eig *f = eig(T, BN, BN1, 3, 1e-6, 1, what);
    if (f) {
      int same = f->ngroups == e->ngroups && f->nblocks == e->nblocks &&
                 f->cond.verdict == e->cond.verdict;
      for (size_t i = 0; i < BN; i++)
        same &= fabs(f->val[i].re - e->val[i].re) <= 1e-13 &&
                fabs(f->val[i].im - e->val[i].im) <= 1e-13 &&
                f->val[i].mult == e->val[i].mult && f->val[i].group == e->val[i].group;
      CHECK(same, "%s: the one-ring relabelled changes the eigenstructure", what);
      ss_eig_free(f);
    }
    ss_eig_free(e);
  }
  gsl_rng_free(r);
}

/* ---- similarity and companion matrices ---- */

static void test_similarity(void) {
  enum { N = 7 };
  const double d[N] = {1.0, 0.7, 0.55, -0.45, 0.3, 0.2, -0.05};
  double P[N * N], Pi[N * N], D[N * N] = {0}, T[N * N], S[N * N];
  /* P unit lower triangular with entries 0.5 (i + 2j) / N: inverse by
   * forward substitution */
  for (int i = 0; i < N; i++)
    for (int j = 0; j < N; j++)
      P[i * N + j] = i == j ? 1.0 : j < i ? 0.5 * (i + 2 * j) / N : 0.0;
  for (int j = 0; j < N; j++)
    for (int i = 0; i < N; i++) {
      double s = i == j ? 1.0 : 0.0;
      for (int k = 0; k < i; k++)
        s -= P[i * N + k] * Pi[k * N + j];
      Pi[i * N + j] = s;
    }
  for (int i = 0; i < N; i++)
    D[i * N + i] = d[i];
  matmul(N, P, D, T);
  matmul(N, T, Pi, S);
  ss_eig *e = eig(S, N, N, 3, 1e-6, 1, "P D P^-1");
  if (!e) return;
  double re[N], im[N];
  double complex want[N];
  for (int i = 0; i < N; i++)
    want[i] = d[i];
  values(e, re, im);
  const double worst = match_spectrum(want, N, re, im);
  CHECK(worst <= 1e-12, "P D P^-1: spectrum off by %g", worst);
  /* lambda3 = 0.45 > |lambda4| but lambda3 < 0: fail, "not positive" */
  CHECK(e->cond.verdict == SS_FAIL && strstr(e->cond.reason, "not positive"),
        "P D P^-1: %s (%s)", ss_verdict_name(e->cond.verdict), e->cond.reason);
  ss_eig_free(e);
}

/* The companion matrix of prod (x - r_i) (n <= 8): ones on the
 * subdiagonal, -c_{n-1-i} in the first row. */
static void companion(const double *r, int n, double *S) {
  double c[9] = {1.0}; /* monic: c[0] x^n + c[1] x^(n-1) + ... */
  for (int i = 0; i < n; i++)
    for (int k = i + 1; k >= 1; k--)
      c[k] -= r[i] * c[k - 1];
  memset(S, 0, (size_t)(n * n) * sizeof *S);
  for (int j = 0; j < n; j++)
    S[j] = -c[j + 1];
  for (int i = 1; i < n; i++)
    S[i * n + i - 1] = 1.0;
}

static void test_companion(void) {
  enum { N = 6 };
  const double roots[N] = {1.0, 0.5, 0.25, 0.125, -0.0625, 0.03125};
  double S[N * N], re[N], im[N];
  double complex want[N];
  companion(roots, N, S);
  ss_eig *e = eig(S, N, N, 3, 1e-6, 1, "companion");
  if (e) {
    for (int i = 0; i < N; i++)
      want[i] = roots[i];
    values(e, re, im);
    const double worst = match_spectrum(want, N, re, im);
    CHECK(worst <= 1e-10, "companion: roots off by %g", worst);
    /* sorted as the roots (decreasing modulus), each within its bound */
    for (int i = 0; i < N; i++)
      CHECK(fabs(e->val[i].re - roots[i]) <= fmax(e->val[i].err, 1e-15) &&
                e->val[i].im == 0.0,
            "companion: lambda%d = %.17g, root %g, bound %g", i, e->val[i].re, roots[i],
            e->val[i].err);
    CHECK(e->cond.verdict == SS_PASS && e->ngroups == N, "companion: %s, %d groups",
          ss_verdict_name(e->cond.verdict), e->ngroups);
    ss_eig_free(e);
  }
  /* a double root: a Jordan block (a companion matrix is non-derogatory) */
  const double twice[N] = {1.0, 0.5, 0.25, 0.25, 0.125, 0.0625};
  companion(twice, N, S);
  e = eig(S, N, N, 3, 1e-6, 1, "companion, double root");
  if (e) {
    CHECK(e->val[2].mult == 2 && e->val[3].mult == 2 &&
              e->val[2].group == e->val[3].group,
          "double root: multiplicities %d %d", e->val[2].mult, e->val[3].mult);
    CHECK(fabs(e->val[2].re - 0.25) <= 1e-6 && fabs(e->val[3].re - 0.25) <= 1e-6,
          "double root: %.17g %.17g", e->val[2].re, e->val[3].re);
    /* lambda1 = 1/2, lambda2 = lambda3 = 1/4 > 1/8: the condition holds; the
     * basis is a Schur basis (repeated), and defective */
    CHECK(e->cond.verdict == SS_PASS, "double root: %s (%s)",
          ss_verdict_name(e->cond.verdict), e->cond.reason);
    CHECK(e->basis && !strcmp(e->basis_kind, "schur") && e->defective == 1,
          "double root: basis %s, defective %d", e->basis_kind, e->defective);
    if (e->basis) check_basis(S, e, "companion, double root");
    ss_eig_free(e);
  }
  /* the same roots, diagonalisable (diag plus a coupling that keeps the
   * eigenvectors apart): not defective */
  double Dg[N * N] = {0};
  for (int i = 0; i < N; i++)
    Dg[i * N + i] = twice[i];
  Dg[1 * N + 0] = 0.3, Dg[4 * N + 2] = 0.2, Dg[5 * N + 3] = 0.1;
  e = eig(Dg, N, N, 3, 1e-6, 1, "diagonalisable double root");
  if (e) {
    CHECK(e->cond.verdict == SS_PASS && e->basis && e->defective == 0,
          "diagonalisable double root: %s, defective %d",
          ss_verdict_name(e->cond.verdict), e->defective);
    if (e->basis) check_basis(Dg, e, "diagonalisable double root");
    ss_eig_free(e);
  }
}

/* ---- the cubic B-spline and its tensor powers ---- */

/* The cubic B-spline's local matrix on the points -2..2, reordered one-ring
 * (-1, 0, 1) first: order[] maps S's index to the position. */
static const int bs_pos[5] = {-1, 0, 1, -2, 2};

static double bspline_entry(int fine, int coarse) {
  /* fine point f at level +1: f even a vertex (1/8, 6/8, 1/8 around f / 2),
   * f odd an edge point (1/2, 1/2) */
  if (fine % 2 == 0) {
    const int d = abs(coarse - fine / 2);
    return d == 0 ? 0.75 : d == 1 ? 0.125 : 0.0;
  }
  const int lo = (fine - 1) / 2; /* fine - 1 is even: exact */
  return coarse == lo || coarse == lo + 1 ? 0.5 : 0.0;
}

/* S1 (5 x 5) and its d-th tensor power (5^d x 5^d), one-ring (3^d points,
 * every coordinate in -1..1) first. */
static double *bspline_power(int d, size_t *n, size_t *n1) {
  size_t N = 1;
  for (int k = 0; k < d; k++)
    N *= 5;
  size_t *order = malloc(N * sizeof *order), m = 0;
  /* multi-indices: digit k in 0..4 indexes bs_pos; the one-ring first */
  for (int pass = 0; pass < 2; pass++)
    for (size_t i = 0; i < N; i++) {
      int inner = 1;
      for (size_t q = i, k = 0; k < (size_t)d; k++, q /= 5)
        inner &= q % 5 < 3;
      if (inner == !pass) order[m++] = i;
    }
  *n1 = 1;
  for (int k = 0; k < d; k++)
    *n1 *= 3;
  double *S = malloc(N * N * sizeof *S);
  for (size_t a = 0; a < N; a++)
    for (size_t b = 0; b < N; b++) {
      double w = 1.0;
      for (size_t p = order[a], q = order[b], k = 0; k < (size_t)d; k++, p /= 5, q /= 5)
        w *= bspline_entry(bs_pos[p % 5], bs_pos[q % 5]);
      S[a * N + b] = w;
    }
  free(order);
  *n = N;
  return S;
}

static void test_bspline(void) {
  const double l1[5] = {1.0, 0.5, 0.25, 0.125, 0.125};
  for (int d = 1; d <= 3; d++) {
    size_t n, n1;
    double *S = bspline_power(d, &n, &n1);
    double complex *want = malloc(n * sizeof *want);
    for (size_t i = 0; i < n; i++) {
      double w = 1.0;
      for (size_t q = i, k = 0; k < (size_t)d; k++, q /= 5)
        w *= l1[q % 5];
      want[i] = w;
    }
    double *re = malloc(n * sizeof *re), *im = malloc(n * sizeof *im);
    for (int dim = 2; dim <= 3; dim++) {
      char what[64];
      snprintf(what, sizeof what, "B-spline^%d, dim %d", d, dim);
      ss_eig *e = eig(S, n, n1, dim, 1e-6, 1, what);
      if (!e) continue;
      values(e, re, im);
      const double worst = match_spectrum(want, n, re, im);
      /* the tensor powers repeat 1/8 up to 3 d times: a multiple eigenvalue
       * of non-trivial Jordan structure is only known to sqrt(eps) */
      CHECK(worst <= 1e-7, "%s: spectrum off by %g", what, worst);
      if (d == 1) {
        CHECK(e->val[3].mult == 2 && e->nblocks == 2 && e->largest_block == 1,
              "%s: 1/8 mult %d, %zu outer blocks", what, e->val[3].mult, e->nblocks);
        CHECK(e->cond.verdict == (dim == 2 ? SS_PASS : SS_FAIL), "%s: %s (%s)", what,
              ss_verdict_name(e->cond.verdict), e->cond.reason);
      } else {
        /* lambda1 = 1/2 with multiplicity d; the next is 1/4 */
        CHECK(e->val[1].mult == d && fabs(e->val[1].re - 0.5) <= 1e-12 &&
                  fabs(e->val[d + 1].re - 0.25) <= 1e-12,
              "%s: lambda1 %.17g mult %d, lambda%d %.17g", what, e->val[1].re,
              e->val[1].mult, d + 1, e->val[d + 1].re);
        /* the condition holds exactly when the dimension is the tensor
         * power's (lambda_dim = 1/2 > 1/4), else lambda_dim = 1/2 or 1/4
         * ties with the next */
        CHECK(e->cond.verdict == (dim == d ? SS_PASS : SS_FAIL), "%s: %s (%s)", what,
              ss_verdict_name(e->cond.verdict), e->cond.reason);
      }
      if (e->cond.verdict == SS_PASS) {
        check_basis(S, e, what);
        CHECK(e->defective == 0 &&
                  !strcmp(e->basis_kind, d == 1 ? "eigenvectors" : "schur"),
              "%s: basis %s, defective %d", what, e->basis_kind, e->defective);
      }
      ss_eig_free(e);
    }
    free(re);
    free(im);
    free(want);
    free(S);
  }
}

/* ---- the outer block leading, ordering, groups, verdicts, input ---- */

static void test_outer_leading(void) {
  /* A = [[1, 0], [0.5, 0.3]] (eigenvalues 1, 0.3); C lower triangular with
   * 0.6 and 0.5 on the diagonal; B couples them: lambda1 = 0.6, lambda2 =
   * 0.5 lie in the outer block, the surface condition holds (0.5 > 0.3) and
   * the basis is a Schur basis of the whole S */
  enum { N = 4 };
  double S[N * N] = {1.0, 0, 0, 0, 0.5, 0.3, 0, 0, 0.2, 0.1, 0.6, 0, 0.1, 0.3, 0.25, 0.5};
  ss_eig *e = eig(S, N, 2, 2, 1e-6, 1, "outer leading");
  if (e) {
    CHECK(e->cond.verdict == SS_PASS && e->val[1].block > 0 && e->val[2].block > 0,
          "outer leading: %s, blocks %d %d (%s)", ss_verdict_name(e->cond.verdict),
          e->val[1].block, e->val[2].block, e->cond.reason);
    CHECK(fabs(e->val[1].re - 0.6) <= 1e-14 && fabs(e->val[2].re - 0.5) <= 1e-14,
          "outer leading: %.17g %.17g", e->val[1].re, e->val[2].re);
    CHECK(!strcmp(e->basis_kind, "schur"), "outer leading: basis %s", e->basis_kind);
    check_basis(S, e, "outer leading");
    ss_eig_free(e);
  }
  /* the leading outer eigenvalue negative: fail */
  S[10] = -0.6;
  e = eig(S, N, 2, 2, 1e-6, 1, "outer negative");
  if (e) {
    CHECK(e->cond.verdict == SS_FAIL && strstr(e->cond.reason, "lambda1") &&
              strstr(e->cond.reason, "not positive"),
          "outer negative: %s (%s)", ss_verdict_name(e->cond.verdict), e->cond.reason);
    CHECK(!e->basis, "outer negative: a basis without the condition");
    ss_eig_free(e);
  }
  /* a rotation block leading in the outer part: complex, fail */
  double R[5 * 5] = {1.0,  0, 0,   0,   0,   0.5, 0.2, 0,   0,   0,   0.1, 0.1, 0.3,
                     -0.4, 0, 0.1, 0.1, 0.4, 0.3, 0,   0.2, 0.2, 0.1, 0.1, 0.1};
  e = eig(R, 5, 2, 2, 1e-6, 1, "outer complex");
  if (e) {
    CHECK(e->cond.verdict == SS_FAIL && strstr(e->cond.reason, "complex") &&
              fabs(hypot(e->val[1].re, e->val[1].im) - 0.5) <= 1e-14,
          "outer complex: %s (%s)", ss_verdict_name(e->cond.verdict), e->cond.reason);
    ss_eig_free(e);
  }
  /* lambda0 = 0.9: not 1 */
  double L[16] = {0.9, 0, 0, 0, 0.1, 0.5, 0, 0, 0.1, 0.1, 0.2, 0, 0.1, 0.1, 0.1, 0.1};
  e = eig(L, 4, 4, 2, 1e-6, 0, "lambda0 0.9");
  if (e) {
    CHECK(e->cond.verdict == SS_FAIL && strstr(e->cond.reason, "is not 1"),
          "lambda0 0.9: %s (%s)", ss_verdict_name(e->cond.verdict), e->cond.reason);
    ss_eig_free(e);
  }
}

static void test_order_groups(void) {
  /* symmetric (perfectly conditioned) with eigenvalues 1, 0.5, -0.5, 0.3 (1
   * + 1e-8), 0.3, 0.1, plus a rotation block 0.3 +- 0.4 i (modulus 0.5) */
  enum { N = 8 };
  const double d[6] = {1.0, 0.5, -0.5, 0.3 * (1 + 1e-8), 0.3, 0.1};
  const double v[6] = {0.3, 1.0, -0.7, 0.2, 0.5, -1.1};
  double A[36], S[N * N] = {0};
  householder_similar(6, d, v, A);
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < 6; j++)
      S[i * N + j] = A[i * 6 + j];
  S[6 * N + 6] = S[7 * N + 7] = 0.3;
  S[6 * N + 7] = 0.4, S[7 * N + 6] = -0.4;
  S[6 * N + 1] = S[7 * N + 2] = 0.25;
  const double tols[4] = {1e-6, 1e-7, 1e-9, 1e-10};
  for (int q = 0; q < 4; q++) {
    const double tol = tols[q];
    const int t = q >= 2; /* 1: the two are apart */
    ss_eig *e = eig(S, N, 6, 2, tol, 0, "ordering");
    if (!e) continue;
    /* 1; then the modulus-0.5 tie: 0.5, -0.5 (real first, larger real part
     * first), 0.3 + 0.4i, 0.3 - 0.4i; then the pair near 0.3; 0.1 */
    const double re[N] = {1, 0.5, -0.5, 0.3, 0.3, 0.3, 0.3, 0.1};
    const double im[N] = {0, 0, 0, 0.4, -0.4, 0, 0, 0};
    int order = 1;
    for (int i = 0; i < N; i++)
      order &= fabs(e->val[i].re - re[i]) <= 1e-7 && fabs(e->val[i].im - im[i]) <= 1e-12;
    CHECK(order, "ordering (tol %g): %g%+gi, %g%+gi, %g%+gi, %g%+gi, %g%+gi", tol,
          e->val[1].re, e->val[1].im, e->val[2].re, e->val[2].im, e->val[3].re,
          e->val[3].im, e->val[4].re, e->val[4].im, e->val[5].re, e->val[5].im);
    /* 0.3 (1 + 1e-8) and 0.3: one group at 1e-6 and 1e-7, two at 1e-9 and
     * 1e-10 */
    const int joined = e->val[5].group == e->val[6].group;
    CHECK(joined == !t && e->val[5].mult == (t ? 1 : 2) && e->ngroups == (t ? 8 : 7),
          "tol %g: 1e-8 apart joined %d, mult %d, %d groups (tol used %g)", tol, joined,
          e->val[5].mult, e->ngroups, e->tol);
    /* groups are numbered in order, the leading one 0 */
    int numbered = e->val[0].group == 0;
    for (int i = 1; i < N; i++)
      numbered &= e->val[i].group == e->val[i - 1].group ||
                  e->val[i].group == e->val[i - 1].group + 1;
    CHECK(numbered, "tol %g: groups not numbered in order", tol);
    /* lambda1 = 0.5 = |lambda2|: the surface condition fails */
    CHECK(e->cond.verdict == SS_FAIL, "ordering: %s", ss_verdict_name(e->cond.verdict));
    ss_eig_free(e);
  }
}

static void test_input(void) {
  double S[9] = {1, 0, 0.5, 0.5, 0.5, 0, 0, 0, 0.25}; /* row 0 reads column 2 */
  ss_eig_opts o = ss_eig_defaults(2);
  ss_eig *e = NULL;
  ss_error err = {0};
  CHECK(ss_eig_new(S, 3, 2, &o, &e, &err) == SS_EINPUT && !e,
        "a one-ring row reading an outer column accepted");
  S[2] = 0.0;
  o.tol = 0.0;
  CHECK(ss_eig_new(S, 3, 2, &o, &e, &err) == SS_EINPUT && !e, "tol 0 accepted");
  o.tol = 0.2;
  CHECK(ss_eig_new(S, 3, 2, &o, &e, &err) == SS_EINPUT && !e, "tol 0.2 accepted");
  o = ss_eig_defaults(2);
  o.dim = 4;
  CHECK(ss_eig_new(S, 3, 2, &o, &e, &err) == SS_EINPUT && !e, "dim 4 accepted");
  o = ss_eig_defaults(2);
  CHECK(ss_eig_new(S, 3, 2, &o, &e, &err) == SS_OK && e, "a good matrix refused: %s",
        err.msg);
  /* 3 eigenvalues are too few for the surface condition (lambda0..2 and a
   * next one): undecided, not pass */
  CHECK(e && e->cond.verdict == SS_UNDECIDED, "3 x 3, dim 2: %s",
        e ? ss_verdict_name(e->cond.verdict) : "-");
  ss_eig_free(e);
}

int main(void) {
  test_blocks();
  test_similarity();
  test_companion();
  test_bspline();
  test_outer_leading();
  test_order_groups();
  test_input();
  return ss_test_done("eig");
}
