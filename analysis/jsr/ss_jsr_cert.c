/* ss_jsr_cert.c — certified lower bound of the spectral radius of a product.
 *
 * The product of the (exact) double matrices is formed in ball arithmetic, so
 * the ball matrix contains the exact product.  Then
 *  1. eigenvalue enclosures: approximate eigenpairs by QR, made rigorous by
 *     Rump's method for simple eigenvalues (acb_mat_eig_simple_rump) or, if
 *     that fails, for clusters (acb_mat_eig_multiple_rump, which handles
 *     multiple eigenvalues); each enclosure contains eigenvalues of
 *     the exact product, so the largest lower bound of |lambda| over the
 *     enclosures is a lower bound of its spectral radius;
 *  2. if that fails: |trace(P^j)| <= n rho(P)^j for every j, so
 *     rho(P) >= (|trace(P^j)| / n)^{1/j}, tried for j = 1, 2, 4, ..., 2^12
 *     (the factor n^{1/j} tends to 1); weak when the dominant eigenvalues
 *     cancel in the trace, but never wrong.
 * Method 1 is tried at 128 and 256 bits.  Method: ss_jsr_cert.h. */
#include "ss_jsr_cert.h"

#include <acb_mat.h>
#include <arb_mat.h>

/* lower bound of max_j |E[j]| over n enclosures, as an arb (0 if none) */
static void max_abs_lower(arb_t out, acb_srcptr E, slong n, slong prec) {
  arb_t t;
  arf_t lb;
  arb_init(t);
  arf_init(lb);
  arb_zero(out);
  for (slong j = 0; j < n; j++) {
    acb_abs(t, E + j, prec);
    arb_get_lbound_arf(lb, t, prec);
    if (arf_cmp(lb, arb_midref(out)) > 0) arb_set_arf(out, lb);
  }
  arf_clear(lb);
  arb_clear(t);
}

/* rho_lo: a lower bound of rho(P) by Rump's enclosures; 1 on success */
static int by_enclosures(arb_t rho_lo, const arb_mat_t P, slong n, slong prec) {
  acb_mat_t A, R;
  acb_ptr E0 = _acb_vec_init(n), E = _acb_vec_init(n);
  acb_mat_init(A, n, n);
  acb_mat_init(R, n, n);
  acb_mat_set_arb_mat(A, P);
  /* NULL tolerance: arb's default for prec (a zero mag_t would ask for
   * exact convergence and stop unconverged) */
  acb_mat_approx_eig_qr(E0, NULL, R, A, NULL, 0, prec);
  /* simple eigenvalues give tight enclosures; clusters (multiple or close
   * eigenvalues) get one common, wider, enclosure */
  int ok = acb_mat_eig_simple_rump(E, NULL, NULL, A, E0, R, prec);
  if (!ok) ok = acb_mat_eig_multiple_rump(E, A, E0, R, prec);
  if (ok) max_abs_lower(rho_lo, E, n, prec);
  acb_mat_clear(R);
  acb_mat_clear(A);
  _acb_vec_clear(E, n);
  _acb_vec_clear(E0, n);
  return ok && arb_is_positive(rho_lo);
}

/* rho_lo: the trace bound (2. above); 1 if it is positive */
static int by_traces(arb_t rho_lo, const arb_mat_t P, slong n, slong prec) {
  arb_mat_t Q;
  arb_t tr, t;
  arf_t lb;
  arb_mat_init(Q, n, n);
  arb_init(tr);
  arb_init(t);
  arf_init(lb);
  arb_mat_set(Q, P);
  arb_zero(rho_lo);
  for (ulong j = 1; j <= 4096; j *= 2) {
    if (j > 1) arb_mat_sqr(Q, Q, prec);
    arb_mat_trace(tr, Q, prec);
    arb_get_abs_lbound_arf(lb, tr, prec);
    if (arf_sgn(lb) <= 0) continue;
    arb_set_arf(t, lb);
    arb_div_ui(t, t, (ulong)n, prec);
    arb_root_ui(t, t, j, prec);
    arb_get_lbound_arf(lb, t, prec);
    if (arf_cmp(lb, arb_midref(rho_lo)) > 0) arb_set_arf(rho_lo, lb);
  }
  arf_clear(lb);
  arb_clear(t);
  arb_clear(tr);
  arb_mat_clear(Q);
  return arb_is_positive(rho_lo);
}

int ss_jsr_cert_lower(size_t n, const double *const *Y, const int *w, int len,
                      double *lo) {
  const slong N = (slong)n;
  arb_mat_t P, F, T;
  arb_t r;
  arf_t lb;
  int ok = 0;
  *lo = 0;
  arb_mat_init(P, N, N);
  arb_mat_init(F, N, N);
  arb_mat_init(T, N, N);
  arb_init(r);
  arf_init(lb);
  for (slong prec = 128; prec <= 256 && !ok; prec *= 2) {
    for (int k = 0; k < len; k++) {
      const double *y = Y[w[k]];
      for (slong a = 0; a < N; a++)
        for (slong b = 0; b < N; b++)
          arb_set_d(arb_mat_entry(F, a, b), y[a * N + b]);
      if (k == 0) {
        arb_mat_set(P, F);
      } else {
        arb_mat_mul(T, F, P, prec);
        arb_mat_swap(T, P);
      }
    }
    ok = by_enclosures(r, P, N, prec);
    if (!ok && prec == 256) ok = by_traces(r, P, N, prec);
  }
  if (ok) {
    arb_root_ui(r, r, (ulong)len, 256);
    arb_get_lbound_arf(lb, r, 256);
    *lo = arf_get_d(lb, ARF_RND_FLOOR);
    ok = *lo > 0;
    if (!ok) *lo = 0;
  }
  arf_clear(lb);
  arb_clear(r);
  arb_mat_clear(T);
  arb_mat_clear(F);
  arb_mat_clear(P);
  return ok;
}
