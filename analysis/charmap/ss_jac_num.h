/* ss_jac_num.h — the two number types of the Jacobian tests, as the tiny
 * interface the FLINT-style templates ss_jac_impl.h and
 * analysis/psi/ss_psi_bernstein_impl.h are written over: double (rounding to
 * nearest; a value of no sign is one within the flat threshold thr of 0) and
 * arb's di_t (enclosures with outward rounding; no threshold).  Each
 * operation is named with the type's suffix, _d or _di (see ss_jac_impl.h for
 * the list).  Internal: not installed; included by ss_jac.c and
 * ss_psi_bernstein.c (and by ss_charmap_cert.c for mul_di). */
#ifndef SS_JAC_NUM_H
#define SS_JAC_NUM_H

#include "double_interval.h"

/* ---- the number interface: double ---- */

static inline double add_d(double a, double b) {
  return a + b;
}
static inline double sub_d(double a, double b) {
  return a - b;
}
static inline double mul_d(double a, double b) {
  return a * b;
}
static inline double scale_d(double a, double s) {
  return s * a;
}
static inline double divd_d(double a, double s) {
  return a / s;
}
static inline double minus_d(double a) {
  return -a;
}
static inline double zero_d(void) {
  return 0.0;
}
/* above the flat threshold: a sign that rounding did not decide */
static inline int gt0_d(double v, double thr) {
  return v > thr;
}
static inline int lt0_d(double v, double thr) {
  return v < -thr;
}

/* ---- the number interface: intervals (enclosures, outward rounding) ---- */

static inline di_t add_di(di_t a, di_t b) {
  return di_fast_add(a, b);
}
static inline di_t sub_di(di_t a, di_t b) {
  return di_fast_sub(a, b);
}
/* di_fast_mul's product, inline (the call was a tenth of the interval
 * Jacobian test): by the signs of the ends the two products that bound it,
 * else the least and greatest of all four (an undefined one, 0 times an
 * infinite end: the whole line); then moved outward as di_fast_add moves a
 * sum.  The same bits as arb's di_fast_mul (test_jac compares them). */
static inline di_t mul_di(di_t x, di_t y) {
  double lo, hi;
  if (x.a > 0 && y.a > 0) {
    lo = x.a * y.a;
    hi = x.b * y.b;
  } else if (x.a > 0 && y.b < 0) {
    lo = x.b * y.a;
    hi = x.a * y.b;
  } else if (x.b < 0 && y.a > 0) {
    lo = x.a * y.b;
    hi = x.b * y.a;
  } else if (x.b < 0 && y.b < 0) {
    lo = x.b * y.b;
    hi = x.a * y.a;
  } else {
    const double p = x.a * y.a, q = x.a * y.b, r = x.b * y.a, s = x.b * y.b;
    if (p != p || q != q || r != r || s != s) {
      di_t whole = {-D_INF, D_INF};
      return whole;
    }
    lo = FLINT_MIN(FLINT_MIN(p, q), FLINT_MIN(r, s));
    hi = FLINT_MAX(FLINT_MAX(p, q), FLINT_MAX(r, s));
  }
  di_t res = {_di_below(lo), _di_above(hi)};
  return res;
}
/* s a x as two products rounded to nearest, then moved outward (arb's own
 * helpers of di_fast_add; they also cover underflow): cheaper than
 * di_fast_mul_d's general case, and hex_at scales 1944 times per cell */
static inline di_t scale_di(di_t a, double s) {
  const double p = s * a.a, q = s * a.b;
  di_t r;
  r.a = _di_below(s >= 0.0 ? p : q);
  r.b = _di_above(s >= 0.0 ? q : p);
  return r;
}
static inline di_t divd_di(di_t a, double s) {
  return di_fast_div_d(a, s);
}
static inline di_t minus_di(di_t a) {
  return di_neg(a);
}
static inline di_t zero_di(void) {
  const di_t z = {0.0, 0.0};
  return z;
}
/* the whole enclosure on one side of 0 (no threshold: rounding is enclosed) */
static inline int gt0_di(di_t v, double thr) {
  (void)thr;
  return v.a > 0.0;
}
static inline int lt0_di(di_t v, double thr) {
  (void)thr;
  return v.b < 0.0;
}

#endif
