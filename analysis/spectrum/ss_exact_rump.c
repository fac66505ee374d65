/* ss_exact_rump.c — Rump's enclosure of a simple real eigenpair in real ball
 * arithmetic (ss_exact_impl.h; S. M. Rump, "Verification methods: rigorous
 * results using floating-point arithmetic", Acta Numerica 19 (2010),
 * section 13.4, as acb_mat_eig_enclosure_rump implements it for complex
 * matrices).
 *
 * A simple real eigenvalue of a real matrix has a real eigenvector, so the
 * whole method runs in arb_mat instead of acb_mat: a quarter of the
 * multiplications.  The preconditioner R, an approximate inverse of
 * M = (A - lambda I) with its frozen column replaced by -x, is computed in
 * doubles by LAPACK: Rump's theorem holds for any R, and the inclusion below
 * proves what it needs (R and M nonsingular, a unique correction in the
 * box); a poorer R only contracts less (T = I - R M is computed in balls at
 * the working precision, so the enclosure's width is still set by the
 * residual of the approximate eigenvector at that precision).  With frozen
 * row v (the last), Y encloses the correction (x - x~ on the other rows,
 * lambda - lambda~ in row v) when
 *   Y0 + T Y + R (U U^T Y) (V^T Y)  lies in the interior of Y,
 *   Y0 = -R (A - lambda~ I) x~.
 * The interior is checked entry by entry (arb_contains_interior), stricter
 * than acb_mat_eig_enclosure_rump's containment; the inflation and the
 * number of steps are acb_mat_eig_enclosure_rump's.
 *
 * Two savings (issue 37; the theorem is unchanged):
 *   - x~ and lambda~ are first refined by Newton's method on the bordered
 *     system: the correction -R (A - lambda~ I) x~ (the residual in balls at
 *     prec, R exact doubles) is added to x~ (rows other than v) and lambda~
 *     (row v) until it is below 2^(8-prec) of x~, at most 6 times.  Each
 *     step costs n^2 ball products, and after it one inclusion round
 *     suffices: before, a dense LU at prec did inverse iteration and the
 *     method ran twice, the second from the first's midpoint.
 *   - T = I - R M is computed in doubles: C = fl(R Md) by BLAS dgemm, Md the
 *     doubles nearest M's midpoints, and the radius bounds every error —
 *     |R M - R Md| <= |R| dM (dM >= |M - Md| entrywise, from the balls) and
 *     |fl(R Md) - R Md| <= gamma_n |R| |Md| (gamma_n = n u / (1 - n u), u =
 *     2^-53: Higham, Accuracy and Stability of Numerical Algorithms, 2nd
 *     ed., (3.13) for every summation order and with fused multiply-adds,
 *     i.e. for any conventional dgemm, not a Strassen-like one) — as
 *     rad = (1 + 4(n + 6) u) fl(|R| (g |Md| + dM)) + 2 u |T~| + n 2^-960,
 *     g = 1.01 (n + 2) u >= gamma_n, the factor covering fl(|R| W)'s own
 *     rounding (it is below the exact |R| W by at most gamma_n of it), 2u|T~|
 *     the rounding of I - C, the last term underflow.  T's radius is then
 *     ~1e-14 instead of ~2^-prec; it only has to make T a contraction (its
 *     norm ~1e-13): the enclosure's width is set by Y0, the residual at
 *     prec, as before.  Before, T was a ball product at prec: n^3 ball
 *     multiplications, most of the basis enclosure's time. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_blas.h>
#include <lapacke.h>

#include "arb_mat.h"

#include "ss_exact_impl.h"

/* r ~ M^-1 in doubles (LAPACK; n x n, row-major), M = A - lambda~ I with its
 * last column replaced by -x~; 0, or -1. */
static int approx_inverse(double *r, const arb_mat_t A, const arb_t lam,
                          const arb_mat_t Xa) {
  const slong n = arb_mat_nrows(A);
  lapack_int *piv = malloc(((size_t)n + 1) * sizeof *piv);
  if (!piv) return -1;
  const double l = arf_get_d(arb_midref(lam), ARF_RND_NEAR);
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < n; j++)
      r[i * n + j] = j == n - 1
                         ? -arf_get_d(arb_midref(arb_mat_entry(Xa, i, 0)), ARF_RND_NEAR)
                         : arf_get_d(arb_midref(arb_mat_entry(A, i, j)), ARF_RND_NEAR) -
                               (i == j ? l : 0.0);
  int rc = LAPACKE_dgetrf(LAPACK_ROW_MAJOR, (lapack_int)n, (lapack_int)n, r,
                          (lapack_int)n, piv) ||
                   LAPACKE_dgetri(LAPACK_ROW_MAJOR, (lapack_int)n, r, (lapack_int)n, piv)
               ? -1
               : 0;
  for (slong i = 0; i < n * n && !rc; i++)
    rc = isfinite(r[i]) ? 0 : -1;
  free(piv);
  return rc;
}

/* The iteration: 1 when Y (holding Y0 on entry) ends strictly inside its
 * inflated self. */
static int contract(arb_mat_t Y, const arb_mat_t Y0, const arb_mat_t T, const arb_mat_t R,
                    slong prec) {
  const slong n = arb_mat_nrows(Y);
  arb_mat_t Yeps, UY;
  arb_t yv;
  mag_t eps, t;
  arb_mat_init(Yeps, n, 1);
  arb_mat_init(UY, n, 1);
  arb_init(yv);
  mag_init(eps);
  mag_init(t);
  int ok = 0;
  const slong maxiter = 5 + FLINT_BIT_COUNT(prec);
  for (slong iter = 0; iter < maxiter && !ok; iter++) {
    mag_zero(eps);
    for (slong i = 0; i < n; i++) {
      arb_get_mag(t, arb_mat_entry(Y, i, 0));
      mag_max(eps, eps, t);
    }
    if (mag_is_zero(eps)) mag_set_ui_2exp_si(eps, 1, -20 * prec);
    mag_mul_2exp_si(eps, eps, -3 + 2 * iter);
    arb_mat_add_error_mag(Y, eps);
    arb_mat_set(Yeps, Y);
    /* Y = Y0 + T Y + R ((U U^T Y) y_v) */
    arb_set(yv, arb_mat_entry(Y, n - 1, 0));
    arb_mat_set(UY, Y);
    arb_zero(arb_mat_entry(UY, n - 1, 0));
    arb_mat_scalar_mul_arb(UY, UY, yv, prec);
    arb_mat_mul(UY, R, UY, prec);
    arb_mat_mul(Y, T, Y, prec);
    arb_mat_add(Y, Y, UY, prec);
    arb_mat_add(Y, Y, Y0, prec);
    ok = 1;
    for (slong i = 0; i < n && ok; i++)
      ok = arb_contains_interior(arb_mat_entry(Yeps, i, 0), arb_mat_entry(Y, i, 0));
  }
  arb_mat_clear(Yeps);
  arb_mat_clear(UY);
  arb_clear(yv);
  mag_clear(eps);
  mag_clear(t);
  return ok;
}

/* Newton's method on the bordered system at prec: Xa (the approximation,
 * its last row frozen) and l (lambda~, exact) refined in place by the
 * correction -R (A - l I) Xa, until it is below 2^(8-prec) of Xa (at most 6
 * steps; each n^2 ball products). */
static void newton(arb_mat_t Xa, arb_t l, const arb_mat_t A, const arb_mat_t R,
                   slong prec) {
  const slong n = arb_mat_nrows(A);
  arb_mat_t res, cor;
  arb_t t;
  arb_mat_init(res, n, 1);
  arb_mat_init(cor, n, 1);
  arb_init(t);
  for (int step = 0; step < 6; step++) {
    arb_mat_mul(res, A, Xa, prec);
    double big = 0.0, top = 0.0;
    for (slong i = 0; i < n; i++) {
      arb_submul(arb_mat_entry(res, i, 0), l, arb_mat_entry(Xa, i, 0), prec);
      big = fmax(big, fabs(arf_get_d(arb_midref(arb_mat_entry(Xa, i, 0)), ARF_RND_NEAR)));
    }
    arb_mat_mul(cor, R, res, prec);
    for (slong i = 0; i < n; i++) { /* [dx; dlambda] = -cor (M's row v: dlambda) */
      arb_get_mid_arb(t, arb_mat_entry(cor, i, 0));
      top = fmax(top, fabs(arf_get_d(arb_midref(t), ARF_RND_NEAR)));
      if (i < n - 1)
        arb_sub(arb_mat_entry(Xa, i, 0), arb_mat_entry(Xa, i, 0), t, prec);
      else
        arb_sub(l, l, t, prec);
    }
    arb_mat_get_mid(Xa, Xa);
    arb_get_mid_arb(l, l);
    if (!(top > ldexp(big, (int)(8 - prec)))) break;
  }
  arb_mat_clear(res);
  arb_mat_clear(cor);
  arb_clear(t);
}

int ss_exact_rump_tmat(arb_mat_t T, const double *r, const arb_mat_t A, const arb_t l,
                       const arb_mat_t Xa, slong prec) {
  const slong n = arb_mat_nrows(A);
  const size_t nn = (size_t)(n * n);
  double *md = malloc((nn + 1) * sizeof *md), *w = malloc((nn + 1) * sizeof *w),
         *ra = malloc((nn + 1) * sizeof *ra), *c = malloc((nn + 1) * sizeof *c),
         *b = malloc((nn + 1) * sizeof *b);
  arb_t z, d;
  mag_t m;
  arb_init(z);
  arb_init(d);
  mag_init(m);
  int rc = -1;
  if (!md || !w || !ra || !c || !b) goto done;
  const double u = ldexp(1.0, -53), g = 1.01 * (double)(n + 2) * u;
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < n; j++) {
      if (j == n - 1)
        arb_neg(z, arb_mat_entry(Xa, i, 0));
      else if (i == j)
        arb_sub(z, arb_mat_entry(A, i, j), l, prec);
      else
        arb_set(z, arb_mat_entry(A, i, j));
      const size_t k = (size_t)(i * n + j);
      md[k] = arf_get_d(arb_midref(z), ARF_RND_NEAR);
      arb_set_d(d, md[k]); /* dM >= |M - Md| over the ball */
      arb_sub(d, z, d, prec);
      arb_get_mag(m, d);
      w[k] = g * fabs(md[k]) + mag_get_d(m);
      ra[k] = fabs(r[k]);
      if (!isfinite(md[k]) || !isfinite(w[k])) goto done;
    }
  gsl_matrix_const_view R = gsl_matrix_const_view_array(r, (size_t)n, (size_t)n),
                        Md = gsl_matrix_const_view_array(md, (size_t)n, (size_t)n),
                        Ra = gsl_matrix_const_view_array(ra, (size_t)n, (size_t)n),
                        W = gsl_matrix_const_view_array(w, (size_t)n, (size_t)n);
  gsl_matrix_view C = gsl_matrix_view_array(c, (size_t)n, (size_t)n),
                  B = gsl_matrix_view_array(b, (size_t)n, (size_t)n);
  gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, &R.matrix, &Md.matrix, 0.0, &C.matrix);
  gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, &Ra.matrix, &W.matrix, 0.0, &B.matrix);
  const double grow = 1.0 + 4.0 * (double)(n + 6) * u,
               tiny = (double)n * ldexp(1.0, -960);
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < n; j++) {
      const size_t k = (size_t)(i * n + j);
      const double t = (i == j ? 1.0 : 0.0) - c[k];
      const double rad = b[k] * grow + 2.0 * u * fabs(t) + tiny;
      if (!isfinite(t) || !isfinite(rad)) goto done;
      arb_set_d(arb_mat_entry(T, i, j), t);
      mag_set_d(m, rad);
      arb_add_error_mag(arb_mat_entry(T, i, j), m);
    }
  rc = 0;
done:
  free(md), free(w), free(ra), free(c), free(b);
  arb_clear(z);
  arb_clear(d);
  mag_clear(m);
  return rc;
}

int ss_exact_rump_real(arb_mat_t X, arb_t lr, const arb_mat_t A, const arb_t lam,
                       const arb_mat_t Xa, slong prec) {
  const slong n = arb_mat_nrows(A);
  arb_mat_t R, T, Y, Y0, Xr;
  arb_t l;
  double *r = malloc(((size_t)(n * n) + 1) * sizeof *r);
  arb_mat_init(R, n, n);
  arb_mat_init(T, n, n);
  arb_mat_init(Y, n, 1);
  arb_mat_init(Y0, n, 1);
  arb_mat_init(Xr, n, 1);
  arb_init(l);
  int ok = 0;
  arb_get_mid_arb(l, lam);
  arb_mat_get_mid(Xr, Xa);
  if (!r || n < 2 || approx_inverse(r, A, l, Xr)) goto done;
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < n; j++)
      arb_set_d(arb_mat_entry(R, i, j), r[i * n + j]);
  newton(Xr, l, A, R, prec);
  arb_mat_set(T, A); /* Y0 = -R (A - lambda~ I) x~, at prec */
  for (slong i = 0; i < n; i++)
    arb_sub(arb_mat_entry(T, i, i), arb_mat_entry(T, i, i), l, prec);
  arb_mat_mul(Y0, T, Xr, prec);
  arb_mat_mul(Y0, R, Y0, prec);
  arb_mat_neg(Y0, Y0);
  arb_mat_set(Y, Y0);
  /* T = I - R ((A - lambda~ I) U U^T - x~ V^T), in doubles */
  if (ss_exact_rump_tmat(T, r, A, l, Xr, prec)) goto done;
  if (!contract(Y, Y0, T, R, prec)) goto done;
  arb_set(lr, l); /* lambda = lambda~ + y_v */
  arb_add_error(lr, arb_mat_entry(Y, n - 1, 0));
  for (slong i = 0; i < n; i++) {
    arb_set(arb_mat_entry(X, i, 0), arb_mat_entry(Xr, i, 0));
    if (i < n - 1)
      arb_add(arb_mat_entry(X, i, 0), arb_mat_entry(X, i, 0), arb_mat_entry(Y, i, 0),
              prec);
  }
  ok = 1;
done:
  free(r);
  arb_mat_clear(R);
  arb_mat_clear(T);
  arb_mat_clear(Y);
  arb_mat_clear(Y0);
  arb_mat_clear(Xr);
  arb_clear(l);
  return ok;
}
