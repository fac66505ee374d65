/* ss_exact_basis.c — the enclosure of the subdominant basis on a certified
 * pass (ss_exact.h, "Basis").
 *
 * On a certified pass every lambda_i (i = 1..m) is real and non-defective,
 * so S X = X J holds with J = diag(lambda1..m) for the eigenvectors X.  For
 * each distinct lambda among them whose factor divides only A's
 * characteristic polynomial (otherwise: SS_ENUMERIC, out of reach):
 *   - lambda rational: the nullspace of A - lambda over Q (exact), extended
 *     to the outer points by exact block solves (C_cc - lambda) x_c = rhs
 *     over the components in order; enclosed by outward rounding;
 *   - lambda irrational: an approximate basis (SVD of A - lambda in doubles,
 *     two steps of inverse iteration at the working precision), then Rump's
 *     method on A (acb_mat_eig_enclosure_rump) with the k best-conditioned
 *     rows frozen (moved last).  It proves A X = X J' with eigenvalues of J'
 *     in a ball; if that ball meets no other root of A, J' has only lambda,
 *     the frozen rows make X of full rank e (a nonzero determinant, in
 *     balls), so X spans the generalised eigenspace of lambda in A, which
 *     (non-defective) is its eigenspace: A X = lambda X.  The true X with
 *     those frozen rows is unique and real (lambda, A real), so the real
 *     parts enclose it.  A simple root (e = 1) runs all of this in real
 *     balls (ss_exact_rump_real: its preconditioner and T = I - R M in
 *     doubles with rigorous radii, the vector refined by Newton's steps at
 *     the working precision instead of inverse iteration; ss_exact_rump.c);
 *     the complex method remains for e > 1 and wherever the real one does
 *     not prove its inclusion.
 *     Extended by the same block solves in ball arithmetic (arb_mat_solve
 *     proves each block invertible).
 * C - lambda is invertible because lambda is no eigenvalue of C. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq_mat.h>
#include <flint/fmpz_mat.h>

#include <lapacke.h>

#include "acb_mat.h"
#include "arb_mat.h"

#include "ss_ball.h"
#include "ss_exact_impl.h"

/* The entry of S at CSR position k as a ball (from the cache when it holds
 * this precision). */
static void entry_ball(const ss_exact *x, size_t k, arb_t b, long prec) {
  if (x->qb && x->qb_prec == prec) {
    arb_set(b, x->qb + k);
    return;
  }
  fmpq_t v;
  fmpq_init(v);
  fmpq_set_si(v, x->q[k].num, (ulong)x->q[k].den);
  arb_set_fmpq(b, v, prec);
  fmpq_clear(v);
}

/* Fill the cache of entry balls at prec (x->qb); 0, or -1 out of memory. */
static int entry_cache(ss_exact *x, long prec) {
  const size_t nnz = x->A.ptr[x->n];
  if (x->qb && x->qb_prec == prec) return 0;
  if (!x->qb && !(x->qb = _arb_vec_init((slong)nnz))) return -1;
  x->qb_prec = 0; /* entry_ball below must not read a stale cache */
  for (size_t k = 0; k < nnz; k++)
    entry_ball(x, k, x->qb + k, prec);
  x->qb_prec = prec;
  return 0;
}

/* ---- exact columns for a rational eigenvalue ---- */

/* Column-major n x e rational matrix. */
typedef struct {
  fmpq *v;
  size_t n, e;
} qcols;

/* The e exact eigenvectors of the rational eigenvalue r into X (n x e),
 * each scaled so that its largest |entry| is 1.  SS_ENOMEM, SS_EINTERNAL. */
static ss_status exact_columns(const ss_exact *x, const fmpq_t r, int e, qcols *X,
                               ss_error *err) {
  const size_t n = x->n, n1 = x->n1;
  ss_status st = SS_OK;
  size_t *idx = malloc((n1 + 1) * sizeof *idx);
  if (!idx) return ss_error_nomem(err, "exact basis");
  for (size_t i = 0; i < n1; i++)
    idx[i] = i;
  fmpz_mat_t M, Z;
  fmpz_t D, t, one;
  fmpq_t a, b;
  fmpz_init_set_ui(one, 1);
  fmpz_mat_init(M, (slong)n1, (slong)n1);
  fmpz_mat_init(Z, (slong)n1, (slong)n1);
  fmpz_init(D);
  fmpz_init(t);
  fmpq_init(a);
  fmpq_init(b);
  if (ss_exact_principal(x, idx, n1, D, M)) {
    st = ss_error_nomem(err, "exact basis");
    goto done;
  }
  /* q (D A) - p D = q D (A - r), r = p / q */
  fmpz_mat_scalar_mul_fmpz(M, M, fmpq_denref(r));
  fmpz_mul(t, D, fmpq_numref(r));
  for (size_t i = 0; i < n1; i++)
    fmpz_sub(fmpz_mat_entry(M, (slong)i, (slong)i), fmpz_mat_entry(M, (slong)i, (slong)i),
             t);
  if (fmpz_mat_nullspace(Z, M) != e) {
    st =
        ss_error_set(err, SS_EINTERNAL, "nullspace of A - lambda of the wrong dimension");
    goto done;
  }
  for (int j = 0; j < e; j++)
    for (size_t i = 0; i < n1; i++)
      fmpq_set_fmpz_frac(X->v + (size_t)j * n + i, fmpz_mat_entry(Z, (slong)i, j), one);
  /* (C_cc - r) x_c = -B x1 - sum over earlier components */
  for (long c = 0; c < x->K.n && !st; c++) {
    const size_t s = x->K.start[c], sz = x->K.start[c + 1] - s;
    fmpq_mat_t Mc, R, Xc;
    fmpq_mat_init(Mc, (slong)sz, (slong)sz);
    fmpq_mat_init(R, (slong)sz, e);
    fmpq_mat_init(Xc, (slong)sz, e);
    for (size_t u = 0; u < sz; u++) {
      const size_t i = n1 + x->K.comp[s + u];
      for (size_t k = x->A.ptr[i]; k < x->A.ptr[i + 1]; k++) {
        const size_t j = x->A.col[k];
        fmpq_set_si(a, x->q[k].num, (ulong)x->q[k].den);
        if (j >= n1 && x->K.cid[j - n1] == (size_t)c) {
          fmpq_add(fmpq_mat_entry(Mc, u, x->K.pos[j - n1]),
                   fmpq_mat_entry(Mc, u, x->K.pos[j - n1]), a);
          continue;
        }
        for (int q = 0; q < e; q++)
          fmpq_submul(fmpq_mat_entry(R, u, q), a, X->v + (size_t)q * n + j);
      }
      fmpq_sub(fmpq_mat_entry(Mc, u, u), fmpq_mat_entry(Mc, u, u), r);
    }
    if (!fmpq_mat_solve(Xc, Mc, R))
      st = ss_error_set(err, SS_EINTERNAL, "an outer block minus lambda is singular");
    for (size_t u = 0; u < sz && !st; u++)
      for (int q = 0; q < e; q++)
        fmpq_set(X->v + (size_t)q * n + n1 + x->K.comp[s + u], fmpq_mat_entry(Xc, u, q));
    fmpq_mat_clear(Mc);
    fmpq_mat_clear(R);
    fmpq_mat_clear(Xc);
  }
  for (int q = 0; q < e && !st; q++) { /* scale: largest |entry| 1 */
    fmpq *col = X->v + (size_t)q * n;
    fmpq_zero(b);
    for (size_t i = 0; i < n; i++) {
      fmpq_abs(a, col + i);
      if (fmpq_cmp(a, b) > 0) fmpq_set(b, a);
    }
    for (size_t i = 0; i < n; i++)
      fmpq_div(col + i, col + i, b);
  }
done:
  fmpz_mat_clear(M);
  fmpz_mat_clear(Z);
  fmpz_clear(D);
  fmpz_clear(t);
  fmpz_clear(one);
  fmpq_clear(a);
  fmpq_clear(b);
  free(idx);
  return st;
}

/* ---- enclosed columns for an irrational eigenvalue ---- */

/* A - lam I for the one-ring block A in doubles, column-major (n1 x n1, a
 * new array; the one-ring rows read only one-ring columns), or NULL. */
static double *shifted_block(const ss_exact *x, double lam) {
  const size_t n1 = x->n1;
  double *a = calloc(n1 * n1 + 1, sizeof *a);
  if (!a) return NULL;
  for (size_t i = 0; i < n1; i++) {
    for (size_t k = x->A.ptr[i]; k < x->A.ptr[i + 1]; k++)
      a[x->A.col[k] * n1 + i] = x->A.val[k];
    a[i * n1 + i] -= lam;
  }
  return a;
}

/* For e = 1: the approximate eigenvector by two steps of inverse iteration
 * on one LU of A - lam in doubles (LAPACK), from a vector no eigenvector is
 * orthogonal to in practice (1 + i / (2 n1)); a tenth of the SVD's work.
 * Its sign is canonical — the entry of largest modulus (the first of them)
 * is positive — so the enclosed basis's orientation does not depend on
 * LAPACK's conventions (the SVD's vectors have an arbitrary sign).
 * Returns 0, or -1 (singular to working precision, not finite, memory: the
 * caller falls back to the SVD). */
static int approx_vector(const ss_exact *x, double lam, double *xa) {
  const size_t n1 = x->n1;
  double *a = shifted_block(x, lam);
  lapack_int *piv = malloc((n1 + 1) * sizeof *piv);
  int rc = -1;
  if (!a || !piv) goto done;
  for (size_t i = 0; i < n1; i++)
    xa[i] = 1.0 + (double)i / (double)(2 * n1);
  const lapack_int nn = (lapack_int)n1;
  if (LAPACKE_dgetrf(LAPACK_COL_MAJOR, nn, nn, a, nn, piv)) goto done;
  for (int it = 0; it < 2; it++) { /* scaled: the largest |entry| (first) is +1 */
    if (LAPACKE_dgetrs(LAPACK_COL_MAJOR, 'N', nn, 1, a, nn, piv, xa, nn)) goto done;
    double big = 0.0;
    for (size_t i = 0; i < n1; i++)
      if (fabs(xa[i]) > fabs(big)) big = xa[i];
    if (!(big != 0.0) || !isfinite(big)) goto done;
    for (size_t i = 0; i < n1; i++)
      xa[i] /= big;
  }
  rc = 0;
done:
  free(a);
  free(piv);
  return rc;
}

/* Approximate basis (n1 x e, column-major doubles) of the eigenspace of
 * lambda ~ lam in A: for e = 1 by inverse iteration (approx_vector), else
 * (or if that fails) the right singular vectors of A - lam of the e
 * smallest singular values.  Returns 0, or -1 (LAPACK or memory). */
static int approx_basis(const ss_exact *x, double lam, int e, double *xa) {
  const size_t n1 = x->n1;
  if (e == 1 && !approx_vector(x, lam, xa)) return 0;
  double *a = shifted_block(x, lam), *vt = malloc((n1 * n1 + 1) * sizeof *vt),
         *sv = malloc((n1 + 1) * sizeof *sv), *sup = malloc((n1 + 1) * sizeof *sup);
  int rc = -1;
  if (!a || !vt || !sv || !sup) goto done;
  const lapack_int nn = (lapack_int)n1;
  if (LAPACKE_dgesvd(LAPACK_COL_MAJOR, 'N', 'A', nn, nn, a, nn, sv, NULL, 1, vt, nn, sup))
    goto done;
  for (int j = 0; j < e; j++)
    for (size_t i = 0; i < n1; i++)
      xa[(size_t)j * n1 + i] = vt[i * n1 + (n1 - (size_t)e + (size_t)j)];
  rc = 0;
done:
  free(a);
  free(vt);
  free(sv);
  free(sup);
  return rc;
}

/* The rows to freeze in Rump's method: the e pivots of a QR factorisation
 * with column pivoting of X^T (X n1 x e), i.e. a well-conditioned e x e
 * submatrix.  perm[0..n1) receives the other rows, then those.  Returns 0 or
 * -1. */
static int frozen_rows(const double *xa, size_t n1, int e, size_t *perm) {
  double *t = malloc((n1 * (size_t)e + 1) * sizeof *t),
         *tau = malloc(((size_t)e + 1) * sizeof *tau);
  lapack_int *jpvt = calloc(n1 + 1, sizeof *jpvt);
  unsigned char *frozen = calloc(n1 + 1, 1);
  int rc = -1;
  if (!t || !tau || !jpvt || !frozen) goto done;
  for (size_t i = 0; i < n1; i++) /* X^T, e x n1 column-major */
    for (int j = 0; j < e; j++)
      t[i * (size_t)e + (size_t)j] = xa[(size_t)j * n1 + i];
  if (LAPACKE_dgeqp3(LAPACK_COL_MAJOR, e, (lapack_int)n1, t, e, jpvt, tau)) goto done;
  for (int j = 0; j < e; j++)
    frozen[jpvt[j] - 1] = 1;
  size_t k = 0;
  for (size_t i = 0; i < n1; i++)
    if (!frozen[i]) perm[k++] = i;
  for (int j = 0; j < e; j++)
    perm[k++] = (size_t)jpvt[j] - 1;
  rc = 0;
done:
  free(t);
  free(tau);
  free(jpvt);
  free(frozen);
  return rc;
}

/* P A P^T in balls at wp into Ap (zero on entry): row perm[i] of A is row
 * i; inv (n1) receives the inverse permutation. */
static void permuted(const ss_exact *x, const size_t *perm, size_t *inv, arb_mat_t Ap,
                     long wp) {
  const size_t n1 = x->n1;
  for (size_t i = 0; i < n1; i++)
    inv[perm[i]] = i;
  for (size_t i = 0; i < n1; i++)
    for (size_t k = x->A.ptr[perm[i]]; k < x->A.ptr[perm[i] + 1]; k++)
      entry_ball(x, k, arb_mat_entry(Ap, (slong)i, (slong)inv[x->A.col[k]]), wp);
}

/* The eigenvalues of J' are roots of A: whether lr meets root r's ball and
 * no other root's of A. */
static int only_root(const ss_exact *x, size_t r, const acb_t lr) {
  int self = 0;
  for (size_t b = x->bstart[0]; b < x->bstart[1]; b++) {
    const ss_exact_factor *G = x->fac + x->bfac[b];
    for (slong i = 0; i < fmpz_poly_degree(G->f); i++) {
      const size_t s2 = G->root0 + (size_t)i;
      if (!acb_overlaps(lr, &x->rt[s2].z)) continue;
      if (s2 != r) return 0;
      self = 1;
    }
  }
  return self;
}

/* As rump_block for a simple root (e = 1), all in real balls: Rump's method
 * in real arithmetic (ss_exact_rump_real: Newton's steps at wp refine the
 * double-precision vector xa0 first, then one inclusion).  1 proven, 0 not,
 * -1 out of memory. */
static int rump_real_block(ss_exact *x, size_t r, const double *xa0, const size_t *perm,
                           long wp, arb_ptr Xb) {
  const size_t n1 = x->n1;
  const slong m = (slong)n1;
  arb_mat_t Ap, Xa, X;
  arb_t lam, lr;
  acb_t lz;
  size_t *inv = malloc((n1 + 1) * sizeof *inv);
  arb_mat_init(Ap, m, m);
  arb_mat_init(Xa, m, 1);
  arb_mat_init(X, m, 1);
  arb_init(lam);
  arb_init(lr);
  acb_init(lz);
  int ok = 0;
  if (!inv) {
    ok = -1;
    goto done;
  }
  permuted(x, perm, inv, Ap, wp);
  for (size_t i = 0; i < n1; i++)
    arb_set_d(arb_mat_entry(Xa, (slong)i, 0), xa0[perm[i]]);
  arb_get_mid_arb(lam, acb_realref(&x->rt[r].z));
  if (!ss_exact_rump_real(X, lr, Ap, lam, Xa, wp)) goto done;
  acb_set_arb(lz, lr);
  /* only r's root in lr; the frozen row (the last) nonzero: full rank */
  if (!only_root(x, r, lz) || arb_contains_zero(arb_mat_entry(X, m - 1, 0))) goto done;
  for (size_t i = 0; i < n1; i++)
    arb_set(Xb + perm[i], arb_mat_entry(X, (slong)i, 0));
  ok = 1;
done:
  arb_mat_clear(Ap);
  arb_mat_clear(Xa);
  arb_mat_clear(X);
  arb_clear(lam);
  arb_clear(lr);
  acb_clear(lz);
  free(inv);
  return ok;
}

/* Rows < n1 of the ball basis Xb (n x e, column-major) for the root r at
 * precision wp, by Rump's method as above.  Returns 1 when proven, 0 when
 * not (at this precision), -1 when out of memory. */
static int rump_block(ss_exact *x, size_t r, int e, const double *xa0, const size_t *perm,
                      long wp, arb_ptr Xb) {
  const size_t n = x->n, n1 = x->n1;
  const ss_exact_rt *R = x->rt + r;
  acb_mat_t Ap, Xa, X, T;
  arb_mat_t F;
  acb_t lam, lr;
  arb_t det, s;
  acb_mat_init(Ap, (slong)n1, (slong)n1);
  acb_mat_init(Xa, (slong)n1, e);
  acb_mat_init(X, (slong)n1, e);
  acb_mat_init(T, (slong)n1, (slong)n1);
  arb_mat_init(F, e, e);
  acb_init(lam);
  acb_init(lr);
  arb_init(det);
  arb_init(s);
  size_t *inv = malloc((n1 + 1) * sizeof *inv);
  int ok = 0;
  if (!inv) {
    ok = -1;
    goto done;
  }
  arb_mat_t Ar;
  arb_mat_init(Ar, (slong)n1, (slong)n1);
  permuted(x, perm, inv, Ar, wp);
  acb_mat_set_arb_mat(Ap, Ar); /* real parts, zero imaginary parts */
  arb_mat_clear(Ar);
  for (size_t i = 0; i < n1; i++)
    for (int j = 0; j < e; j++)
      acb_set_d(acb_mat_entry(Xa, (slong)i, j), xa0[(size_t)j * n1 + perm[i]]);
  acb_get_mid(lam, &R->z);
  /* two steps of inverse iteration, each column scaled to max |entry| ~ 1 */
  acb_mat_get_mid(T, Ap);
  for (size_t i = 0; i < n1; i++)
    acb_sub(acb_mat_entry(T, (slong)i, (slong)i), acb_mat_entry(T, (slong)i, (slong)i),
            lam, wp);
  for (int it = 0; it < 2; it++) {
    if (!acb_mat_approx_solve(Xa, T, Xa, wp)) break;
    for (int j = 0; j < e; j++) {
      double big = 0.0;
      for (size_t i = 0; i < n1; i++) {
        double v = fabs(arf_get_d(arb_midref(acb_realref(acb_mat_entry(Xa, (slong)i, j))),
                                  ARF_RND_NEAR));
        big = v > big ? v : big;
      }
      if (!(big > 0.0) || !isfinite(big)) goto done;
      arb_set_d(s, 1.0 / big);
      for (size_t i = 0; i < n1; i++) {
        acb_mul_arb(acb_mat_entry(Xa, (slong)i, j), acb_mat_entry(Xa, (slong)i, j), s,
                    wp);
        arb_zero(acb_imagref(acb_mat_entry(Xa, (slong)i, j)));
      }
    }
    acb_mat_get_mid(Xa, Xa);
  }
  /* Rump, twice: the second start is the first result's midpoint */
  for (int round = 0; round < 2; round++) {
    acb_mat_eig_enclosure_rump(lr, NULL, X, Ap, lam, Xa, wp);
    if (!acb_is_finite(lr) || !acb_mat_is_finite(X)) goto done;
    if (round == 0) acb_mat_get_mid(Xa, X);
  }
  /* the eigenvalues of J' are roots of A: only r's ball may meet lr */
  if (!only_root(x, r, lr)) goto done;
  /* full rank: the frozen rows (the last e, fixed at Xa's midpoints) */
  for (int i = 0; i < e; i++)
    for (int j = 0; j < e; j++)
      arb_set(arb_mat_entry(F, i, j),
              acb_realref(acb_mat_entry(X, (slong)(n1 - (size_t)e) + i, j)));
  arb_mat_det(det, F, wp);
  if (arb_contains_zero(det)) goto done;
  for (size_t i = 0; i < n1; i++)
    for (int j = 0; j < e; j++)
      arb_set(Xb + (size_t)j * n + perm[i], acb_realref(acb_mat_entry(X, (slong)i, j)));
  ok = 1;
done:
  acb_mat_clear(Ap);
  acb_mat_clear(Xa);
  acb_mat_clear(X);
  acb_mat_clear(T);
  arb_mat_clear(F);
  acb_clear(lam);
  acb_clear(lr);
  arb_clear(det);
  arb_clear(s);
  free(inv);
  return ok;
}

/* Rows >= n1 of Xb (n x e): (C_cc - lambda) x_c = -B x1 - (earlier
 * components), lambda the ball lam, component by component; 1 when every
 * block is proven invertible, 0 when not, -1 out of memory. */
static int ball_extend(const ss_exact *x, const arb_t lam, int e, long wp, arb_ptr Xb) {
  const size_t n = x->n, n1 = x->n1;
  ss_ball_solver *fs = calloc((size_t)x->K.n + 1, sizeof *fs);
  if (!fs) return -1;
  arb_t a;
  arb_init(a);
  int ok = 1;
  for (long c = 0; c < x->K.n && ok; c++) {
    const size_t s = x->K.start[c], sz = x->K.start[c + 1] - s;
    arb_mat_t Mc, R, Xc;
    arb_mat_init(Mc, (slong)sz, (slong)sz);
    arb_mat_init(R, (slong)sz, e);
    arb_mat_init(Xc, (slong)sz, e);
    for (size_t u = 0; u < sz; u++) {
      const size_t i = n1 + x->K.comp[s + u];
      for (size_t k = x->A.ptr[i]; k < x->A.ptr[i + 1]; k++) {
        const size_t j = x->A.col[k];
        entry_ball(x, k, a, wp);
        if (j >= n1 && x->K.cid[j - n1] == (size_t)c) {
          arb_add(arb_mat_entry(Mc, u, x->K.pos[j - n1]),
                  arb_mat_entry(Mc, u, x->K.pos[j - n1]), a, wp);
          continue;
        }
        for (int q = 0; q < e; q++)
          arb_submul(arb_mat_entry(R, u, q), a, Xb + (size_t)q * n + j, wp);
      }
      arb_sub(arb_mat_entry(Mc, u, u), arb_mat_entry(Mc, u, u), lam, wp);
    }
    const size_t rep = x->brep[c + 1] - 1; /* the first component with this block */
    if (sz > 1 && !fs[rep].kind) ss_ball_solver_make(fs + rep, Mc, e, wp);
    ok = sz > 1 ? ss_ball_solver_solve(fs + rep, Xc, Mc, R, wp)
                : arb_mat_solve(Xc, Mc, R, wp);
    for (size_t u = 0; u < sz && ok; u++)
      for (int q = 0; q < e; q++)
        arb_set(Xb + (size_t)q * n + n1 + x->K.comp[s + u], arb_mat_entry(Xc, u, q));
    arb_mat_clear(Mc);
    arb_mat_clear(R);
    arb_mat_clear(Xc);
  }
  for (long c = 0; c < x->K.n; c++)
    ss_ball_solver_clear(fs + c);
  free(fs);
  arb_clear(a);
  return ok;
}

/* The enclosed columns lo, hi (n x e, column-major) of the irrational root r,
 * raising the precision from prec to maxprec.  Returns 1, 0 (not proven:
 * x->bmsg set), -1 (out of memory). */
static int ball_columns(ss_exact *x, size_t r, int e, int pos, double *lo, double *hi) {
  const size_t n = x->n, n1 = x->n1;
  const size_t k = x->rt[r].factor;
  double *xa = malloc((n1 * (size_t)e + 1) * sizeof *xa);
  size_t *perm = malloc((n1 + 1) * sizeof *perm);
  arb_ptr Xb = _arb_vec_init((slong)(n * (size_t)e));
  int ok = -1;
  long wp = x->o.prec;
  if (!xa || !perm) goto done;
  const double lam = arf_get_d(arb_midref(acb_realref(&x->rt[r].z)), ARF_RND_NEAR);
  if (approx_basis(x, lam, e, xa) || frozen_rows(xa, n1, e, perm)) goto done;
  for (ok = 0; !ok; wp *= 2) {
    if (x->fac[k].prec < wp) ss_exact_isolate(x, k, wp);
    if (entry_cache(x, wp)) {
      ok = -1;
      goto done;
    }
    ok = e == 1 ? rump_real_block(x, r, xa, perm, wp, Xb) : 0;
    if (!ok) ok = rump_block(x, r, e, xa, perm, wp, Xb); /* complex, as before */
    if (ok < 0) goto done;
    if (ok) ok = ball_extend(x, acb_realref(&x->rt[r].z), e, wp, Xb);
    if (ok < 0) goto done;
    if (!ok && 2 * wp > x->o.maxprec) {
      snprintf(x->bmsg, sizeof x->bmsg,
               "the eigenvectors of lambda%d (an irrational root of multiplicity %d) "
               "could not be enclosed at %ld bits (Rump's method or an outer block "
               "solve not verified)",
               pos, e, wp);
      goto done;
    }
  }
  for (size_t i = 0; i < n * (size_t)e; i++)
    ss_ball_doubles(Xb + i, lo + i, hi + i);
done:
  free(xa);
  free(perm);
  _arb_vec_clear(Xb, (slong)(n * (size_t)e));
  return ok;
}

/* ---- the basis ---- */

ss_status ss_exact_basis_make(ss_exact *x, ss_error *err) {
  const size_t n = x->n;
  const int m = x->m;
  ss_status st = SS_OK;
  int all_rational = 1, pos = 1;
  for (size_t l = 0; l < x->nlead; l++) {
    const size_t k = x->rt[x->lead[l]].factor;
    all_rational &= fmpz_poly_degree(x->fac[k].f) == 1;
    for (size_t j = x->bstart[1]; j < x->bstart[x->nblk]; j++)
      if (x->bfac[j] == k) {
        x->bstatus = SS_ENUMERIC;
        snprintf(x->bmsg, sizeof x->bmsg,
                 "lambda%d is an eigenvalue of an outer block: a certified basis of the "
                 "subdominant subspace is out of reach of the exact path",
                 pos);
        return SS_OK;
      }
    pos += x->fac[k].mult;
  }
  x->lo = malloc((n * (size_t)m + 1) * sizeof *x->lo);
  x->hi = malloc((n * (size_t)m + 1) * sizeof *x->hi);
  qcols X = {NULL, n, (size_t)m};
  if (!x->lo || !x->hi) return ss_error_nomem(err, "basis");
  X.v = _fmpq_vec_init((slong)(n * (size_t)m));
  fmpq_t r;
  arb_t b;
  fmpq_init(r);
  arb_init(b);
  size_t col = 0;
  pos = 1;
  x->bstatus = SS_OK;
  for (size_t l = 0; l < x->nlead && !st && x->bstatus == SS_OK; l++) {
    const size_t root = x->lead[l], k = x->rt[root].factor;
    const int e = x->fac[k].mult;
    if (fmpz_poly_degree(x->fac[k].f) == 1) {
      const fmpz *c = x->fac[k].f->coeffs; /* c1 x + c0 */
      fmpz_neg(fmpq_numref(r), c);
      fmpz_set(fmpq_denref(r), c + 1);
      fmpq_canonicalise(r);
      qcols Xl = {X.v + col * n, n, (size_t)e};
      st = exact_columns(x, r, e, &Xl, err);
      for (size_t i = 0; i < n * (size_t)e && !st; i++) {
        arb_set_fmpq(b, Xl.v + i, 128);
        ss_ball_doubles(b, x->lo + col * n + i, x->hi + col * n + i);
      }
    } else {
      int ok = ball_columns(x, root, e, pos, x->lo + col * n, x->hi + col * n);
      if (ok < 0) st = ss_error_nomem(err, "basis");
      if (ok == 0) x->bstatus = SS_ENUMERIC;
    }
    col += (size_t)e;
    pos += e;
  }
  if (!st && x->bstatus == SS_OK && all_rational) {
    int fits = 1;
    for (size_t i = 0; i < n * (size_t)m; i++)
      fits &= fmpz_fits_si(fmpq_numref(X.v + i)) && fmpz_fits_si(fmpq_denref(X.v + i));
    x->bnum = fits ? malloc((n * (size_t)m + 1) * sizeof *x->bnum) : NULL;
    x->bden = fits ? malloc((n * (size_t)m + 1) * sizeof *x->bden) : NULL;
    if (fits && (!x->bnum || !x->bden)) st = ss_error_nomem(err, "basis");
    for (size_t i = 0; fits && !st && i < n * (size_t)m; i++) {
      x->bnum[i] = fmpz_get_si(fmpq_numref(X.v + i));
      x->bden[i] = fmpz_get_si(fmpq_denref(X.v + i));
    }
  }
  if (x->bstatus != SS_OK || st) {
    free(x->lo);
    free(x->hi);
    x->lo = x->hi = NULL;
  }
  _fmpq_vec_clear(X.v, (slong)(n * (size_t)m));
  fmpq_clear(r);
  arb_clear(b);
  return st;
}

ss_status ss_exact_basis(const ss_exact *x, double *lo, double *hi, ss_error *err) {
  if (x->cond.verdict != SS_PASS || !x->certified)
    return ss_error_set(err, SS_EINPUT,
                        "no certified basis: the eigenvalue condition is not a certified "
                        "pass (%s: %.200s)",
                        ss_verdict_name(x->cond.verdict), x->cond.reason);
  if (x->bstatus != SS_OK) return ss_error_set(err, x->bstatus, "%s", x->bmsg);
  memcpy(lo, x->lo, x->n * (size_t)x->m * sizeof *lo);
  memcpy(hi, x->hi, x->n * (size_t)x->m * sizeof *hi);
  return SS_OK;
}

int ss_exact_basis_rational(const ss_exact *x, long long *num, long long *den) {
  if (!x->bnum || x->bstatus != SS_OK) return 0;
  memcpy(num, x->bnum, x->n * (size_t)x->m * sizeof *num);
  memcpy(den, x->bden, x->n * (size_t)x->m * sizeof *den);
  return 1;
}
