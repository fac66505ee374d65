/* ss_ball.c — arb balls as doubles, entries' windows, eigenvalue enclosures
 * (ss_ball.h). */
#include "ss_ball.h"

#include <math.h>

void ss_ball_doubles(const arb_t x, double *lo, double *hi) {
  arf_t t;
  arf_init(t);
  arb_get_lbound_arf(t, x, 64);
  *lo = arf_get_d(t, ARF_RND_FLOOR);
  arb_get_ubound_arf(t, x, 64);
  *hi = arf_get_d(t, ARF_RND_CEIL);
  arf_clear(t);
}

double ss_ball_window(double s) {
  return ldexp(fmax(1.0, fabs(s)), -SS_BALL_WINDOW);
}

void ss_ball_entry(arb_t b, double s) {
  int e = 0;
  if (s == 0.0) {
    arb_zero(b);
    return;
  }
  if (fabs(s) > 1.0) (void)frexp(s, &e); /* |s| < 2^e */
  arb_set_d(b, s);
  arb_add_error_2exp_si(b, (slong)e - SS_BALL_WINDOW);
}

int ss_ball_eig(acb_ptr E, acb_mat_t R, const acb_mat_t B, acb_ptr E0p, acb_mat_t R0p,
                slong prec) {
  const slong b = acb_mat_nrows(B);
  acb_ptr E0 = _acb_vec_init(b);
  acb_mat_t R0;
  acb_mat_init(R0, b, b);
  acb_mat_approx_eig_qr(E0, NULL, R0, B, NULL, 0, prec);
  int rc = acb_mat_eig_simple(E, NULL, R, B, E0, R0, prec) ? 1
           : acb_mat_eig_multiple(E, B, E0, R0, prec)      ? 0
                                                           : -1;
  if (rc < 0) {
    mag_t eps;
    mag_init(eps);
    acb_mat_eig_global_enclosure(eps, B, E0, R0, prec);
    for (slong i = 0; mag_is_finite(eps) && i < b; i++) {
      acb_set(E + i, E0 + i);
      acb_add_error_mag(E + i, eps);
      rc = 2;
    }
    mag_clear(eps);
  }
  if (E0p) _acb_vec_set(E0p, E0, b);
  if (R0p) acb_mat_set(R0p, R0);
  acb_mat_clear(R0);
  _acb_vec_clear(E0, b);
  return rc;
}

int ss_ball_invariant(const double *S, size_t n, const size_t *p, size_t *bi,
                      size_t *bj) {
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      const double a = S[i * n + j], b = S[p[i] * n + p[j]];
      if ((a == 0.0) != (b == 0.0) ||
          !(fabs(a - b) <= ss_ball_window(a) + ss_ball_window(b))) {
        *bi = i;
        *bj = j;
        return 0;
      }
    }
  return 1;
}
