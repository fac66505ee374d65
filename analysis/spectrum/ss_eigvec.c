/* ss_eigvec.c — leading eigenvectors and limit masks (ss_eigvec.h). */
#include "ss_eigvec.h"

#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>

#define SINGULAR_RCOND                                                                   \
  1e-10 /* smallest singular value of L^T R, relative to the                             \
          columns' norms, below which a group is defective */

typedef double complex cplx;

/* Eigenvalues for the ordering: modulus first, then the tie order. */
typedef struct {
  double re, im, mod;
  int idx; /* column of dgeev's output */
} ev;

static int by_modulus(const void *a, const void *b) {
  const ev *x = a, *y = b;
  if (x->mod != y->mod) return x->mod > y->mod ? -1 : 1;
  return x->idx - y->idx;
}

/* within a run of equal moduli: real first, larger real part, larger
 * imaginary part (ss_eig's order) */
static int by_tie(const void *a, const void *b) {
  const ev *x = a, *y = b;
  const int cx = x->im != 0.0, cy = y->im != 0.0;
  if (cx != cy) return cx - cy;
  if (x->re != y->re) return x->re > y->re ? -1 : 1;
  if (x->im != y->im) return x->im > y->im ? -1 : 1;
  return x->idx - y->idx;
}

static int close_rel(cplx a, cplx b, double tol) {
  const double m = fmax(cabs(a), cabs(b));
  return cabs(a - b) <= tol * m;
}

void ss_eigvec_free(ss_eigvec *v) {
  if (!v) return;
  free(v->re);
  free(v->im);
  free(v->group);
  free(v->biorth);
  free(v->right_re);
  free(v->right_im);
  free(v->left_re);
  free(v->left_im);
  free(v);
}

/* Right vector of dgeev's eigenvalue p as a complex vector, and the row left
 * vector l with l^T S = lambda l^T (dgeev's u satisfies u^H S = lambda u^H,
 * so l = conj(u)). */
static void vectors_of(size_t n, const double *wi, const double *vl, const double *vr,
                       int p, cplx *r, cplx *l) {
  for (size_t i = 0; i < n; i++) {
    if (wi[p] == 0.0) {
      r[i] = vr[i + (size_t)p * n];
      l[i] = vl[i + (size_t)p * n];
    } else if (wi[p] > 0.0) {
      r[i] = CMPLX(vr[i + (size_t)p * n], vr[i + (size_t)(p + 1) * n]);
      l[i] = CMPLX(vl[i + (size_t)p * n], -vl[i + (size_t)(p + 1) * n]);
    } else {
      r[i] = CMPLX(vr[i + (size_t)(p - 1) * n], -vr[i + (size_t)p * n]);
      l[i] = CMPLX(vl[i + (size_t)(p - 1) * n], vl[i + (size_t)p * n]);
    }
  }
}

/* Scale r to maximum modulus 1, that entry (the first of them) real and
 * positive. */
static void normalise_right(size_t n, cplx *r) {
  size_t at = 0;
  double big = -1.0;
  for (size_t i = 0; i < n; i++)
    if (cabs(r[i]) > big * (1.0 + 1e-12)) {
      big = cabs(r[i]);
      at = i;
    }
  if (!(big > 0.0)) return;
  const cplx s = conj(r[at]) / (big * big);
  for (size_t i = 0; i < n; i++)
    r[i] *= s;
}

/* Make the group's left vectors (columns c0..c0+g-1 of L, n x k) biorthonormal
 * to its right ones, L_new = L G^{-T} with G = L^T R, so that L_new^T R = I.  Returns
 * 1 if done, 0 if R^T L is numerically singular, -1 on no memory. */
static int biorthonormalise(size_t n, int g, int c0, cplx *R, cplx *L) {
  cplx *G = calloc((size_t)g * g, sizeof *G), *X = calloc((size_t)g * g, sizeof *X),
       *tmp = calloc((size_t)g, sizeof *tmp);
  lapack_int *piv = calloc((size_t)g, sizeof *piv);
  int ok = -1;
  if (!G || !X || !tmp || !piv) goto done;
  /* G = L^T R, column-major for LAPACK; the scale is the largest product of
   * column norms, so that a tiny G of nearly parallel vectors counts as
   * singular (for one eigenvalue, |l^T r| / (|l| |r|) is the reciprocal of
   * its condition number) */
  double lnorm = 0.0, rnorm = 0.0;
  for (int a = 0; a < g; a++) {
    double sl = 0.0, sr = 0.0;
    for (size_t i = 0; i < n; i++) {
      sl += creal(L[i + (size_t)(c0 + a) * n] * conj(L[i + (size_t)(c0 + a) * n]));
      sr += creal(R[i + (size_t)(c0 + a) * n] * conj(R[i + (size_t)(c0 + a) * n]));
    }
    lnorm = fmax(lnorm, sqrt(sl));
    rnorm = fmax(rnorm, sqrt(sr));
  }
  for (int b = 0; b < g; b++)
    for (int a = 0; a < g; a++) {
      cplx s = 0.0;
      for (size_t i = 0; i < n; i++)
        s += L[i + (size_t)(c0 + a) * n] * R[i + (size_t)(c0 + b) * n];
      G[a + (size_t)b * g] = s;
    }
  for (int a = 0; a < g; a++)
    X[a + (size_t)a * g] = 1.0;
  lapack_int info = LAPACKE_zgesv(LAPACK_COL_MAJOR, g, g, (lapack_complex_double *)G, g,
                                  piv, (lapack_complex_double *)X, g);
  ok = 0;
  if (info != 0) goto done;
  double inorm = 0.0;
  for (int b = 0; b < g; b++) {
    double col = 0.0;
    for (int a = 0; a < g; a++)
      col += cabs(X[a + (size_t)b * g]);
    inorm = fmax(inorm, col);
  }
  if (!(1.0 / inorm >= SINGULAR_RCOND * g * lnorm * rnorm)) goto done;
  /* L_new[i][a] = sum_b L[i][b] Ginv[a][b] */
  for (size_t i = 0; i < n; i++) {
    for (int a = 0; a < g; a++) {
      cplx s = 0.0;
      for (int b = 0; b < g; b++)
        s += L[i + (size_t)(c0 + b) * n] * X[a + (size_t)b * g];
      tmp[a] = s;
    }
    for (int a = 0; a < g; a++)
      L[i + (size_t)(c0 + a) * n] = tmp[a];
  }
  ok = 1;
done:
  free(G);
  free(X);
  free(tmp);
  free(piv);
  return ok;
}

ss_status ss_eigvec_new(const double *S, size_t n, int k, double tol, ss_eigvec **out,
                        ss_error *err) {
  *out = NULL;
  if (!S || n == 0 || k < 1 || (size_t)k > n || !(tol > 0.0 && tol < 0.1))
    return ss_error_set(err, SS_EINPUT,
                        "eigenvectors: need 1 <= k <= n (k = %d, n = %zu) and a "
                        "tolerance in (0, 0.1)",
                        k, n);
  ss_status st = SS_ENOMEM;
  ss_eigvec *v = NULL;
  double *A = malloc(n * n * sizeof *A), *wr = malloc(n * sizeof *wr),
         *wi = malloc(n * sizeof *wi), *vl = malloc(n * n * sizeof *vl),
         *vr = malloc(n * n * sizeof *vr);
  ev *e = malloc(n * sizeof *e);
  cplx *R = NULL, *L = NULL;
  if (!A || !wr || !wi || !vl || !vr || !e) goto nomem;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      A[i + j * n] = S[i * n + j];
  lapack_int info =
      LAPACKE_dgeev(LAPACK_COL_MAJOR, 'V', 'V', (lapack_int)n, A, (lapack_int)n, wr, wi,
                    vl, (lapack_int)n, vr, (lapack_int)n);
  if (info != 0) {
    st = ss_error_set(err, info < 0 ? SS_EINTERNAL : SS_ENUMERIC,
                      "eigenvectors: LAPACK dgeev failed (info %d)", (int)info);
    goto done;
  }
  for (size_t i = 0; i < n; i++)
    e[i] = (ev){wr[i], wi[i], hypot(wr[i], wi[i]), (int)i};
  qsort(e, n, sizeof *e, by_modulus);
  for (size_t a = 0; a < n;) {
    size_t b = a + 1;
    while (b < n && e[a].mod - e[b].mod <= tol * e[a].mod)
      b++;
    qsort(e + a, b - a, sizeof *e, by_tie);
    a = b;
  }
  /* a conjugate pair or a group of equal eigenvalues cut by k is kept whole */
  while ((size_t)k < n &&
         ((e[k - 1].im > 0.0 && e[k].im == -e[k - 1].im && e[k].re == e[k - 1].re) ||
          close_rel(CMPLX(e[k - 1].re, e[k - 1].im), CMPLX(e[k].re, e[k].im), tol)))
    k++;
  if (!(v = calloc(1, sizeof *v))) goto nomem;
  v->n = n;
  v->k = k;
  const size_t nk = n * (size_t)k;
  v->re = malloc((size_t)k * sizeof *v->re);
  v->im = malloc((size_t)k * sizeof *v->im);
  v->group = malloc((size_t)k * sizeof *v->group);
  v->biorth = malloc((size_t)k * sizeof *v->biorth);
  v->right_re = malloc(nk * sizeof *v->right_re);
  v->right_im = malloc(nk * sizeof *v->right_im);
  v->left_re = malloc(nk * sizeof *v->left_re);
  v->left_im = malloc(nk * sizeof *v->left_im);
  R = malloc(nk * sizeof *R);
  L = malloc(nk * sizeof *L);
  if (!v->re || !v->im || !v->group || !v->biorth || !v->right_re || !v->right_im ||
      !v->left_re || !v->left_im || !R || !L)
    goto nomem;
  for (int j = 0; j < k; j++) {
    v->re[j] = e[j].re;
    v->im[j] = e[j].im;
    v->complex_any |= e[j].im != 0.0;
    vectors_of(n, wi, vl, vr, e[j].idx, R + (size_t)j * n, L + (size_t)j * n);
    normalise_right(n, R + (size_t)j * n);
  }
  for (int j0 = 0, grp = 0; j0 < k; grp++) {
    const cplx l0 = CMPLX(v->re[j0], v->im[j0]);
    int j1 = j0 + 1;
    while (j1 < k && close_rel(l0, CMPLX(v->re[j1], v->im[j1]), tol))
      j1++;
    const int done_ = biorthonormalise(n, j1 - j0, j0, R, L);
    if (done_ < 0) goto nomem;
    for (int j = j0; j < j1; j++) {
      v->group[j] = grp;
      v->biorth[j] = done_;
    }
    j0 = j1;
  }
  for (size_t i = 0; i < nk; i++) {
    v->right_re[i] = creal(R[i]);
    v->right_im[i] = cimag(R[i]);
    v->left_re[i] = creal(L[i]);
    v->left_im[i] = cimag(L[i]);
  }
  *out = v;
  v = NULL;
  st = SS_OK;
  goto done;
nomem:
  st = ss_error_set(err, SS_ENOMEM, "eigenvectors: out of memory (n = %zu)", n);
done:
  ss_eigvec_free(v);
  free(A);
  free(wr);
  free(wi);
  free(vl);
  free(vr);
  free(e);
  free(R);
  free(L);
  return st;
}

int ss_eigvec_has_limit(const ss_eigvec *v, double tol) {
  if (!v || v->k < 1 || v->im[0] != 0.0 || !(fabs(v->re[0] - 1.0) <= tol)) return 0;
  if (v->k > 1 && v->group[1] == v->group[0]) return 0;
  if (!v->biorth[0]) return 0;
  for (size_t i = 0; i < v->n; i++)
    if (!(fabs(v->right_re[i] - 1.0) <= tol) || v->right_im[i] != 0.0) return 0;
  return 1;
}
