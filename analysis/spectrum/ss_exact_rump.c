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
 * number of steps are acb_mat_eig_enclosure_rump's. */
#include <math.h>
#include <stdlib.h>

#include <lapacke.h>

#include "arb_mat.h"

#include "ss_exact_impl.h"

/* R ~ M^-1 in doubles (LAPACK) as an exact ball matrix; 0, or -1. */
static int approx_inverse(arb_mat_t R, const arb_mat_t A, const arb_t lam,
                          const arb_mat_t Xa) {
  const slong n = arb_mat_nrows(A);
  double *m = malloc(((size_t)(n * n) + 1) * sizeof *m);
  lapack_int *piv = malloc(((size_t)n + 1) * sizeof *piv);
  int rc = -1;
  if (!m || !piv) goto done;
  const double l = arf_get_d(arb_midref(lam), ARF_RND_NEAR);
  for (slong i = 0; i < n; i++) /* row-major */
    for (slong j = 0; j < n; j++)
      m[i * n + j] = j == n - 1
                         ? -arf_get_d(arb_midref(arb_mat_entry(Xa, i, 0)), ARF_RND_NEAR)
                         : arf_get_d(arb_midref(arb_mat_entry(A, i, j)), ARF_RND_NEAR) -
                               (i == j ? l : 0.0);
  if (LAPACKE_dgetrf(LAPACK_ROW_MAJOR, (lapack_int)n, (lapack_int)n, m, (lapack_int)n,
                     piv) ||
      LAPACKE_dgetri(LAPACK_ROW_MAJOR, (lapack_int)n, m, (lapack_int)n, piv))
    goto done;
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < n; j++) {
      if (!isfinite(m[i * n + j])) goto done;
      arb_set_d(arb_mat_entry(R, i, j), m[i * n + j]);
    }
  rc = 0;
done:
  free(m);
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

int ss_exact_rump_real(arb_mat_t X, arb_t lr, const arb_mat_t A, const arb_t lam,
                       const arb_mat_t Xa, slong prec) {
  const slong n = arb_mat_nrows(A);
  arb_mat_t R, T, Y, Y0;
  arb_t l;
  arb_mat_init(R, n, n);
  arb_mat_init(T, n, n);
  arb_mat_init(Y, n, 1);
  arb_mat_init(Y0, n, 1);
  arb_init(l);
  int ok = 0;
  arb_get_mid_arb(l, lam);
  if (n < 2 || approx_inverse(R, A, l, Xa)) goto done;
  arb_mat_set(T, A); /* T = A - lambda~ I */
  for (slong i = 0; i < n; i++)
    arb_sub(arb_mat_entry(T, i, i), arb_mat_entry(T, i, i), l, prec);
  arb_mat_mul(Y0, T, Xa, prec); /* Y0 = -R (A - lambda~ I) x~ */
  arb_mat_mul(Y0, R, Y0, prec);
  arb_mat_neg(Y0, Y0);
  arb_mat_set(Y, Y0);
  for (slong i = 0; i < n; i++) /* T = I - R ((A - lambda~ I) U U^T - x~ V^T) */
    arb_neg(arb_mat_entry(T, i, n - 1), arb_mat_entry(Xa, i, 0));
  arb_mat_mul(T, R, T, prec);
  arb_mat_neg(T, T);
  for (slong i = 0; i < n; i++)
    arb_add_ui(arb_mat_entry(T, i, i), arb_mat_entry(T, i, i), 1, prec);
  if (!contract(Y, Y0, T, R, prec)) goto done;
  arb_set(lr, l); /* lambda = lambda~ + y_v */
  arb_add_error(lr, arb_mat_entry(Y, n - 1, 0));
  for (slong i = 0; i < n; i++) {
    arb_get_mid_arb(arb_mat_entry(X, i, 0), arb_mat_entry(Xa, i, 0));
    if (i < n - 1)
      arb_add(arb_mat_entry(X, i, 0), arb_mat_entry(X, i, 0), arb_mat_entry(Y, i, 0),
              prec);
  }
  ok = 1;
done:
  arb_mat_clear(R);
  arb_mat_clear(T);
  arb_mat_clear(Y);
  arb_mat_clear(Y0);
  arb_clear(l);
  return ok;
}
