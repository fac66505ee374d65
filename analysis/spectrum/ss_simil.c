/* ss_simil.c — the verified similarity of each diagonal block and its
 * Gershgorin discs (ss_simil.h, "One block"); the pass and the basis are in
 * ss_simil_pass.c. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>
#include <flint/ulong_extras.h>
#include <lapacke.h>

#include "ss_exact.h"
#include "ss_simil_impl.h"

double ss_simil_up(double x) {
  return x * (1.0 + 0x1p-40) + 0x1p-1000;
}

double ss_simil_dn(double x) {
  return x * (1.0 - 0x1p-40) - 0x1p-1000;
}

/* gamma_q = q u / (1 - q u), u = 2^-53, bounded above for q < 2^12. */
static double gamma_of(size_t q) {
  return (double)q * 0x1p-53 * (1.0 + 0x1p-20);
}

static void disc_push(ss_simil *s, double re, double im, double rad, long blk) {
  s->d[s->nd++] = (ss_simil_disc){re, im, rad, blk};
}

/* C = A B for complex k x k matrices in split row-major form (zeroed here):
 * each part of an entry is a sum of 2k rounded products. */
static void cmul(const double *Ar, const double *Ai, const double *Br, const double *Bi,
                 double *Cr, double *Ci, size_t k) {
  memset(Cr, 0, k * k * sizeof *Cr);
  memset(Ci, 0, k * k * sizeof *Ci);
  for (size_t i = 0; i < k; i++)
    for (size_t l = 0; l < k; l++) {
      const double a = Ar[i * k + l], b = Ai[i * k + l];
      const double *br = Br + l * k, *bi = Bi + l * k;
      double *cr = Cr + i * k, *ci = Ci + i * k;
      for (size_t j = 0; j < k; j++) {
        cr[j] += a * br[j] - b * bi[j];
        ci[j] += a * bi[j] + b * br[j];
      }
    }
}

/* Row sums of |Z| (|re| + |im|) into v. */
static void abs_rows(const double *Zr, const double *Zi, size_t k, double *v) {
  for (size_t i = 0; i < k; i++) {
    double t = 0.0;
    for (size_t j = 0; j < k; j++)
      t += fabs(Zr[i * k + j]) + (Zi ? fabs(Zi[i * k + j]) : 0.0);
    v[i] = t;
  }
}

/* X: T's eigenvectors (dgeev), complex, each column scaled by its entry of
 * largest modulus; 0, or 1 when LAPACK fails. */
static int eigvecs(const double *T, size_t k, double *Xr, double *Xi, double *work) {
  double *a = work, *wr = a + k * k, *wi = wr + k, *vr = wi + k;
  memcpy(a, T, k * k * sizeof *a);
  if (LAPACKE_dgeev(LAPACK_ROW_MAJOR, 'N', 'V', (lapack_int)k, a, (lapack_int)k, wr, wi,
                    NULL, 1, vr, (lapack_int)k))
    return 1;
  for (size_t j = 0; j < k; j++) {
    const int pair = wi[j] != 0.0;
    if (pair && j + 1 >= k) return 1;
    size_t p = 0;
    double best = -1.0;
    for (size_t q = 0; q < k; q++) {
      const double re = vr[q * k + j], im = pair ? vr[q * k + j + 1] : 0.0;
      const double md = re * re + im * im;
      if (md > best) best = md, p = q;
    }
    const double complex piv = CMPLX(vr[p * k + j], pair ? vr[p * k + j + 1] : 0.0);
    if (best <= 0.0 || !isfinite(best)) return 1;
    for (size_t q = 0; q < k; q++) {
      double complex z = CMPLX(vr[q * k + j], pair ? vr[q * k + j + 1] : 0.0);
      z = q == p ? 1.0 : z / piv;
      Xr[q * k + j] = creal(z);
      Xi[q * k + j] = pair ? cimag(z) : 0.0;
      if (pair) {
        Xr[q * k + j + 1] = creal(z);
        Xi[q * k + j + 1] = -cimag(z);
      }
    }
    j += (size_t)pair;
  }
  return 0;
}

/* R ~ X^-1 in doubles (split); 0, or 1 when singular. */
static int inverse(const double *Xr, const double *Xi, size_t k, double *Rr, double *Ri,
                   double complex *z, lapack_int *piv) {
  for (size_t i = 0; i < k * k; i++)
    z[i] = CMPLX(Xr[i], Xi[i]);
  if (LAPACKE_zgetrf(LAPACK_ROW_MAJOR, (lapack_int)k, (lapack_int)k, z, (lapack_int)k,
                     piv) ||
      LAPACKE_zgetri(LAPACK_ROW_MAJOR, (lapack_int)k, z, (lapack_int)k, piv))
    return 1;
  for (size_t i = 0; i < k * k; i++) {
    Rr[i] = creal(z[i]);
    Ri[i] = cimag(z[i]);
    if (!isfinite(Rr[i]) || !isfinite(Ri[i])) return 1;
  }
  return 0;
}

int ss_simil_block_with(ss_simil *s, const double *T, const double *Trad, size_t k,
                        long blk, const double *Xr, const double *Xi, const double *Rr,
                        const double *Ri) {
  double *w = malloc((6 * k * k + 4 * k + 1) * sizeof *w);
  if (!w) return -1;
  double *Pr = w, *Pi = Pr + k * k, *Er = Pi + k * k, *Ei = Er + k * k, *Br = Ei + k * k,
         *Bi = Br + k * k, *x = Bi + k * k, *p = x + k, *t = p + k, *e = t + k;
  /* P = Tm X: real times complex, sums of k products */
  memset(Pr, 0, k * k * sizeof *Pr);
  memset(Pi, 0, k * k * sizeof *Pi);
  for (size_t i = 0; i < k; i++)
    for (size_t l = 0; l < k; l++) {
      const double a = T[i * k + l];
      if (a == 0.0) continue;
      for (size_t j = 0; j < k; j++) {
        Pr[i * k + j] += a * Xr[l * k + j];
        Pi[i * k + j] += a * Xi[l * k + j];
      }
    }
  cmul(Rr, Ri, Xr, Xi, Er, Ei, k);
  cmul(Rr, Ri, Pr, Pi, Br, Bi, k);
  abs_rows(Xr, Xi, k, x);
  abs_rows(Pr, Pi, k, p);
  const double gk = gamma_of(k), g2k = gamma_of(2 * k);
  for (size_t l = 0; l < k; l++) { /* t = gamma_2k p + (gamma_k |Tm| + Trad) x */
    double v = 0.0;
    for (size_t j = 0; j < k; j++)
      v += (gk * fabs(T[l * k + j]) + Trad[l * k + j]) * x[j];
    t[l] = ss_simil_up(g2k * p[l] + v);
  }
  double alpha = 0.0, bnorm = 0.0;
  for (size_t i = 0; i < k; i++) {
    double ei = 0.0, ax = 0.0, ai = 0.0, ri = 0.0;
    for (size_t l = 0; l < k; l++) {
      const double r = fabs(Rr[i * k + l]) + fabs(Ri[i * k + l]);
      ei += r * t[l];
      ax += r * x[l];
      ai += fabs((i == l ? 1.0 : 0.0) - Er[i * k + l]) + fabs(Ei[i * k + l]);
      if (l != i) ri += fabs(Br[i * k + l]) + fabs(Bi[i * k + l]);
    }
    e[i] = ss_simil_up(ss_simil_up(ei) + ss_simil_up(ri));
    alpha = fmax(alpha, ss_simil_up(ai + g2k * ss_simil_up(ax)));
    bnorm = fmax(bnorm, ss_simil_up(hypot(Br[i * k + i], Bi[i * k + i]) + e[i]));
  }
  if (!(alpha < 0.5)) { /* refused: X nearly singular or worse */
    free(w);
    return 1;
  }
  const double delta = ss_simil_up(ss_simil_up(alpha / ss_simil_dn(1.0 - alpha)) * bnorm);
  for (size_t i = 0; i < k; i++)
    disc_push(s, Br[i * k + i], Bi[i * k + i], ss_simil_up(e[i] + delta), blk);
  free(w);
  return 0;
}

int ss_simil_block(ss_simil *s, const double *T, const double *Trad, size_t k, long blk) {
  if (k == 1) {
    disc_push(s, T[0], 0.0, ss_simil_up(Trad[0]), blk);
    return 0;
  }
  if (k >= 4096) return 1;
  double *Xr = malloc((2 * k * k + 1) * sizeof *Xr);
  double *R = malloc((2 * k * k + 1) * sizeof *R);
  double *w = malloc((2 * k * k + 2 * k + 1) * sizeof *w);
  double complex *z = malloc((k * k + 1) * sizeof *z);
  lapack_int *piv = malloc((k + 1) * sizeof *piv);
  int rc = -1;
  if (!Xr || !R || !w || !z || !piv) goto done;
  double *Xi = Xr + k * k, *Rr = R, *Ri = R + k * k;
  rc = eigvecs(T, k, Xr, Xi, w) || inverse(Xr, Xi, k, Rr, Ri, z, piv) ||
       ss_simil_block_with(s, T, Trad, k, blk, Xr, Xi, Rr, Ri);
  if (rc < 0) goto done;
  if (!rc && blk < 0) { /* A's X kept for the basis */
    s->Xa = Xr;
    Xr = NULL;
  }
done:
  free(Xr);
  free(R);
  free(w);
  free(z);
  free(piv);
  return rc;
}

/* ---- the rational matrix ---- */

__extension__ typedef __int128 i128;

/* Whether sum_k p[k] / q[k] (q > 0, |p| < 2^53, q <= 2^31) is exactly 1:
 * in 128-bit integers over the common denominator when that fits below
 * 2^62, else in FLINT's rationals. */
static int sums_to_one(const long long *p, const long long *q, size_t nk) {
  long long D = 1;
  int fits = nk < 1024;
  for (size_t k = 0; k < nk && fits; k++) {
    const long long g = (long long)n_gcd((ulong)D, (ulong)q[k]), f = q[k] / g;
    fits = D <= (1LL << 62) / f;
    if (fits) D *= f;
  }
  if (fits) { /* |p (D / q)| < 2^115, nk of them < 2^125 */
    i128 t = 0;
    for (size_t k = 0; k < nk; k++)
      t += (i128)p[k] * (D / q[k]);
    return t == (i128)D;
  }
  fmpq_t sum, r;
  fmpq_init(sum);
  fmpq_init(r);
  for (size_t k = 0; k < nk; k++) {
    fmpq_set_si(r, (slong)p[k], (ulong)q[k]);
    fmpq_add(sum, sum, r);
  }
  const int one = fmpq_is_one(sum);
  fmpq_clear(sum);
  fmpq_clear(r);
  return one;
}

int ss_simil_rational(ss_simil *s, long maxden) {
  const ss_csr *A = &s->A;
  const size_t nnz = A->ptr[s->n];
  s->lo = malloc((nnz + 1) * sizeof *s->lo);
  s->hi = malloc((nnz + 1) * sizeof *s->hi);
  long long *p = malloc((nnz + 1) * sizeof *p), *q = malloc((nnz + 1) * sizeof *q);
  int ok = s->lo && s->hi && p && q ? 1 : -1;
  for (size_t k = 0; k < nnz && ok == 1; k++) {
    const long long big = 1LL << 53;
    ok = ss_exact_rational(A->val[k], maxden, p + k, q + k) && p[k] < big &&
         -p[k] < big && q[k] <= (1LL << 31);
    if (!ok) break;
    const double v = (double)p[k] / (double)q[k]; /* p, q exact: correctly rounded */
    const int exact = fma(v, (double)q[k], -(double)p[k]) == 0.0;
    s->lo[k] = exact ? v : nextafter(v, -INFINITY);
    s->hi[k] = exact ? v : nextafter(v, INFINITY);
  }
  for (size_t i = 0; i < s->n && ok == 1; i++)
    ok = sums_to_one(p + A->ptr[i], q + A->ptr[i], A->ptr[i + 1] - A->ptr[i]);
  free(p);
  free(q);
  return ok;
}
