/* ss_jac_num.h — the two number types of the Jacobian tests, as the tiny
 * interface the FLINT-style templates ss_jac_impl.h and
 * analysis/psi/ss_psi_bernstein_impl.h are written over: double (rounding to
 * nearest; a value of no sign is one within the flat threshold thr of 0) and
 * arb's di_t (enclosures with outward rounding; no threshold).  Each
 * operation is named with the type's suffix, _d or _di (see ss_jac_impl.h for
 * the list).  Internal: not installed; included by ss_jac.c and
 * ss_psi_bernstein.c. */
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
static inline di_t mul_di(di_t a, di_t b) {
  return di_fast_mul(a, b);
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
