/* ss_exact_rational.c — the rational matrix of an ss_exact: each entry of S
 * reconstructed as the nearest rational of bounded denominator, the rows
 * checked to sum to 1, and the entries and principal submatrices read back
 * (ss_exact_impl.h). */
#include "ss_exact.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_mat.h>
#include <flint/fmpz_poly_factor.h>

#include "arb_fmpz_poly.h"
#include "arf.h"
#include "double_interval.h"

#include "ss_exact_impl.h"

/* Largest |entry| reconstructed (so that numerators fit in 64 bits with room
 * to spare). */
#define MAXABS 1048576.0

/* The rational nearest to v >= 0 among those of denominator <= maxden: v
 * itself if its denominator is small enough, else the last convergent or
 * semiconvergent of v's continued fraction within the bound, whichever is
 * nearer (the best approximation theorem; as Python's limit_denominator). */
static void nearest_rational(fmpq_t r, const fmpq_t v, long maxden) {
  if (fmpz_cmp_si(fmpq_denref(v), maxden) <= 0) {
    fmpq_set(r, v);
    return;
  }
  fmpz_t p0, q0, p1, q1, a, q2, nn, dd, t;
  fmpz_init_set_ui(p0, 0);
  fmpz_init_set_ui(q0, 1);
  fmpz_init_set_ui(p1, 1);
  fmpz_init_set_ui(q1, 0);
  fmpz_init(a);
  fmpz_init(q2);
  fmpz_init_set(nn, fmpq_numref(v));
  fmpz_init_set(dd, fmpq_denref(v));
  fmpz_init(t);
  while (!fmpz_is_zero(dd)) {
    fmpz_fdiv_q(a, nn, dd);
    fmpz_set(q2, q0);
    fmpz_addmul(q2, a, q1);
    if (fmpz_cmp_si(q2, maxden) > 0) break;
    fmpz_set(t, p0); /* (p0, p1) = (p1, p0 + a p1), (q0, q1) = (q1, q2) */
    fmpz_addmul(t, a, p1);
    fmpz_swap(p0, p1);
    fmpz_swap(p1, t);
    fmpz_swap(q0, q1);
    fmpz_swap(q1, q2);
    fmpz_submul(nn, a, dd); /* (nn, dd) = (dd, nn - a dd) */
    fmpz_swap(nn, dd);
  }
  /* the first step always fits (q = 1), so q1 >= 1 here */
  fmpz_set_si(t, maxden);
  fmpz_sub(t, t, q0);
  fmpz_fdiv_q(a, t, q1); /* the largest semiconvergent step */
  fmpq_t b1, d1, d2;
  fmpq_init(b1);
  fmpq_init(d1);
  fmpq_init(d2);
  fmpz_set(fmpq_numref(b1), p0);
  fmpz_addmul(fmpq_numref(b1), a, p1);
  fmpz_set(fmpq_denref(b1), q0);
  fmpz_addmul(fmpq_denref(b1), a, q1);
  fmpq_canonicalise(b1);
  fmpq_set_fmpz_frac(r, p1, q1);
  fmpq_sub(d1, b1, v);
  fmpq_abs(d1, d1);
  fmpq_sub(d2, r, v);
  fmpq_abs(d2, d2);
  if (fmpq_cmp(d2, d1) > 0) fmpq_set(r, b1);
  fmpq_clear(b1);
  fmpq_clear(d1);
  fmpq_clear(d2);
  fmpz_clear(p0);
  fmpz_clear(q0);
  fmpz_clear(p1);
  fmpz_clear(q1);
  fmpz_clear(a);
  fmpz_clear(q2);
  fmpz_clear(nn);
  fmpz_clear(dd);
  fmpz_clear(t);
}

/* s = M 2^e with M odd (or s = 0) in lowest terms when its denominator 2^-e
 * is at most maxden: then s itself is the nearest rational of bounded
 * denominator, at distance 0, and the general path below would return the
 * same p / q.  The rules' weights are such dyadic rationals (1/8, 3/64,
 * ...): the certified path reads each of them many times.  1 with *p, *q,
 * or 0 (not such a rational: the general path decides).  s finite, |s| <=
 * MAXABS. */
static int dyadic(double s, long maxden, long long *p, long long *q) {
  int ex;
  const double m = frexp(s, &ex);               /* s = m 2^ex, 1/2 <= |m| < 1 */
  long long M = (long long)ldexp(m, 53), d = 1; /* s = M 2^(ex - 53), exact */
  int e = ex - 53;
  if (M == 0) {
    *p = 0;
    *q = 1;
    return 1;
  }
  while (M % 2 == 0) {
    M /= 2;
    e++;
  }
  if (e >= 0) { /* an integer: |s| <= MAXABS = 2^20 */
    *p = M * (1LL << e);
    *q = 1;
    return 1;
  }
  if (-e > 31) return 0; /* 2^-e > SS_EXACT_MAXDEN_LIMIT >= maxden */
  d <<= -e;
  if (d > maxden) return 0;
  *p = M;
  *q = d;
  return 1;
}

int ss_exact_rational(double s, long maxden, long long *p, long long *q) {
  return ss_exact_rational_within(s, maxden, ldexp(1.0, -40), p, q);
}

int ss_exact_rational_within(double s, long maxden, double reltol, long long *p,
                             long long *q) {
  if (!isfinite(s) || maxden < 1 || maxden > SS_EXACT_MAXDEN_LIMIT ||
      !(fabs(s) <= MAXABS) || !(reltol > 0.0 && reltol < 1.0))
    return 0;
  if (dyadic(s, maxden, p, q)) return 1;
  arf_t f;
  fmpq_t v, r, d, bound;
  arf_init(f);
  fmpq_init(v);
  fmpq_init(r);
  fmpq_init(d);
  fmpq_init(bound);
  arf_set_d(f, s); /* exact */
  arf_get_fmpq(v, f);
  const int neg = fmpq_sgn(v) < 0;
  fmpq_abs(v, v);
  nearest_rational(r, v, maxden);
  if (fmpq_cmp_ui(v, 1) > 0)
    fmpq_set(bound, v);
  else
    fmpq_one(bound);
  arf_set_d(f, reltol); /* exact: 2^-40 for ss_exact_rational */
  arf_get_fmpq(d, f);
  fmpq_mul(bound, bound, d);
  fmpq_sub(d, r, v);
  fmpq_abs(d, d);
  int ok = fmpq_cmp(d, bound) <= 0 && fmpz_fits_si(fmpq_numref(r)) &&
           fmpz_fits_si(fmpq_denref(r));
  if (ok) {
    if (neg) fmpq_neg(r, r);
    *p = fmpz_get_si(fmpq_numref(r));
    *q = fmpz_get_si(fmpq_denref(r));
  }
  arf_clear(f);
  fmpq_clear(v);
  fmpq_clear(r);
  fmpq_clear(d);
  fmpq_clear(bound);
  return ok;
}

int ss_exact_rational_enclose(double s, long maxden, double *lo, double *hi) {
  long long p, q;
  const long long big = 1LL << 53; /* p and q exact as doubles below this */
  if (!ss_exact_rational(s, maxden, &p, &q) || p >= big || -p >= big || q >= big)
    return 0;
  const di_t r =
      di_fast_div(di_interval((double)p, (double)p), di_interval((double)q, (double)q));
  *lo = r.a;
  *hi = r.b;
  return 1;
}

/* Reconstruct every entry and check the row sums.  SS_ENUMERIC naming the
 * entry or row, SS_ENOMEM. */
ss_status ss_exact_reconstruct(ss_exact *x, const double *S, ss_error *err) {
  const size_t n = x->n;
  if (ss_csr_make(S, n, x->n1, &x->A)) return ss_error_nomem(err, "exact matrix");
  x->q = malloc((x->A.ptr[n] + 1) * sizeof *x->q);
  if (!x->q) return ss_error_nomem(err, "exact matrix");
  ss_status st = SS_OK;
  fmpq_t sum, t;
  fmpq_init(sum);
  fmpq_init(t);
  for (size_t i = 0; i < n && !st; i++) {
    fmpq_zero(sum);
    for (size_t k = x->A.ptr[i]; k < x->A.ptr[i + 1]; k++) {
      const double s = x->A.val[k];
      if (!ss_exact_rational(s, x->o.maxden, &x->q[k].num, &x->q[k].den)) {
        st = ss_error_set(err, SS_ENUMERIC,
                          "S[%zu][%zu] = %.17g is not a rational of denominator at most "
                          "%ld (within 2^-40): the exact path cannot certify this matrix",
                          i, x->A.col[k], s, x->o.maxden);
        break;
      }
      fmpq_set_si(t, x->q[k].num, (ulong)x->q[k].den);
      fmpq_add(sum, sum, t);
    }
    if (!st && !fmpq_is_one(sum)) {
      char *str = fmpq_get_str(NULL, 10, sum);
      st = ss_error_set(err, SS_ENUMERIC,
                        "row %zu of the rational matrix sums to %.60s, not exactly 1", i,
                        str ? str : "?");
      flint_free(str);
    }
  }
  fmpq_clear(sum);
  fmpq_clear(t);
  return st;
}

void ss_exact_get(const ss_exact *x, size_t i, size_t j, fmpq_t v) {
  size_t lo = x->A.ptr[i], hi = x->A.ptr[i + 1];
  while (lo < hi) { /* columns increase within a row */
    size_t mid = lo + (hi - lo) / 2;
    if (x->A.col[mid] < j)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo < x->A.ptr[i + 1] && x->A.col[lo] == j)
    fmpq_set_si(v, x->q[lo].num, (ulong)x->q[lo].den);
  else
    fmpq_zero(v);
}

int ss_exact_entry(const ss_exact *x, size_t i, size_t j, long long *p, long long *q) {
  if (!x || i >= x->n || j >= x->n) return 0;
  fmpq_t v;
  fmpq_init(v);
  ss_exact_get(x, i, j, v);
  *p = fmpz_get_si(fmpq_numref(v)); /* entries fit (ss_exact_rational) */
  *q = fmpz_get_si(fmpq_denref(v));
  fmpq_clear(v);
  return 1;
}

/* For every column j of x's matrix its place in idx[0..len) (SIZE_MAX where
 * j is not in idx), malloc'd, or NULL. */
static size_t *places(const ss_exact *x, const size_t *idx, size_t len) {
  size_t *at = malloc((x->n + 1) * sizeof *at);
  if (!at) return NULL;
  for (size_t j = 0; j < x->n; j++)
    at[j] = SIZE_MAX;
  for (size_t c = 0; c < len; c++)
    at[idx[c]] = c;
  return at;
}

int ss_exact_principal(const ss_exact *x, const size_t *idx, size_t len, fmpz_t D,
                       fmpz_mat_t M) {
  size_t *at = places(x, idx, len);
  if (!at) return -1;
  fmpz_one(D);
  for (size_t r = 0; r < len; r++)
    for (size_t k = x->A.ptr[idx[r]]; k < x->A.ptr[idx[r] + 1]; k++)
      if (at[x->A.col[k]] != SIZE_MAX) {
        fmpz_t d;
        fmpz_init_set_si(d, x->q[k].den);
        fmpz_lcm(D, D, d);
        fmpz_clear(d);
      }
  fmpz_mat_zero(M);
  fmpz_t t;
  fmpz_init(t);
  for (size_t r = 0; r < len; r++)
    for (size_t k = x->A.ptr[idx[r]]; k < x->A.ptr[idx[r] + 1]; k++) {
      const size_t c = at[x->A.col[k]];
      if (c == SIZE_MAX) continue;
      fmpz_divexact_si(t, D, x->q[k].den);
      fmpz_mul_si(fmpz_mat_entry(M, (slong)r, (slong)c), t, x->q[k].num);
    }
  fmpz_clear(t);
  free(at);
  return 0;
}

int ss_exact_principal_rows(const ss_exact *x, const size_t *idx, size_t len, fmpz *d,
                            fmpz_mat_t N) {
  size_t *at = places(x, idx, len);
  if (!at) return -1;
  fmpz_mat_zero(N);
  fmpz_t t;
  fmpz_init(t);
  for (size_t r = 0; r < len; r++) {
    fmpz_one(d + r);
    for (size_t k = x->A.ptr[idx[r]]; k < x->A.ptr[idx[r] + 1]; k++)
      if (at[x->A.col[k]] != SIZE_MAX) {
        fmpz_set_si(t, x->q[k].den);
        fmpz_lcm(d + r, d + r, t);
      }
    for (size_t k = x->A.ptr[idx[r]]; k < x->A.ptr[idx[r] + 1]; k++) {
      const size_t c = at[x->A.col[k]];
      if (c == SIZE_MAX) continue;
      fmpz_divexact_si(t, d + r, x->q[k].den);
      fmpz_mul_si(fmpz_mat_entry(N, (slong)r, (slong)c), t, x->q[k].num);
    }
  }
  fmpz_clear(t);
  free(at);
  return 0;
}
