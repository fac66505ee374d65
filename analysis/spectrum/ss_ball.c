/* ss_ball.c — arb balls as doubles, entries' windows, eigenvalue enclosures,
 * the ball routes' outcome and shared steps (ss_ball.h). */
#include "ss_ball.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* ---- the ball routes' outcome ---- */

void ss_ball_outcome_init(ss_ball_outcome *o, size_t n, int m) {
  memset(o, 0, sizeof *o);
  o->n = n;
  o->m = m;
  snprintf(o->bmsg, sizeof o->bmsg, "%s", "the condition is not a certified pass");
  ss_ball_verdict(o, SS_UNDECIDED, 0, "%s", "not certified: not assessed");
}

void ss_ball_outcome_clear(ss_ball_outcome *o) {
  free(o->lo);
  free(o->hi);
  o->lo = o->hi = NULL;
}

void ss_ball_verdict(ss_ball_outcome *o, ss_verdict_kind v, int certified,
                     const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  o->cond.verdict = v;
  vsnprintf(o->cond.reason, sizeof o->cond.reason, fmt, ap);
  va_end(ap);
  o->cond.certified = certified;
  o->cond.on = SS_ON_SPECTRUM;
}

void ss_ball_outcome_condition(const ss_ball_outcome *o, ss_verdict *v, int *certified) {
  *v = o->cond;
  *certified = o->cond.certified;
}

ss_status ss_ball_outcome_basis(const ss_ball_outcome *o, double *lo, double *hi,
                                ss_error *err) {
  if (o->cond.verdict != SS_PASS || !o->cond.certified)
    return ss_error_set(err, SS_EINPUT, "%s", o->bmsg);
  if (!o->lo) return ss_error_set(err, SS_ENUMERIC, "%s", o->bmsg);
  memcpy(lo, o->lo, (size_t)o->m * o->n * sizeof *lo);
  memcpy(hi, o->hi, (size_t)o->m * o->n * sizeof *hi);
  return SS_OK;
}

/* ---- the ball routes' shared steps ---- */

void ss_ball_mid(const ss_ball_root *r, double *re, double *im, double *rad) {
  *re = arf_get_d(arb_midref(acb_realref(&r->z)), ARF_RND_NEAR);
  *im = arf_get_d(arb_midref(acb_imagref(&r->z)), ARF_RND_NEAR);
  if (rad) {
    mag_t m;
    mag_init(m);
    mag_hypot(m, arb_radref(acb_realref(&r->z)), arb_radref(acb_imagref(&r->z)));
    *rad = mag_get_d(m);
    mag_clear(m);
  }
}

const ss_ball_root *ss_ball_at(const ss_ball_roots *r, size_t i) {
  return (const ss_ball_root *)((const char *)r->at + i * r->size);
}

size_t ss_ball_ones(const ss_ball_roots *r, size_t *one) {
  acb_t u;
  acb_init(u);
  acb_one(u);
  size_t ones = 0;
  for (size_t i = 0; i < r->nrt; i++)
    if (acb_contains(&ss_ball_at(r, i)->z, u)) ones++, *one = i;
  acb_clear(u);
  return ones;
}

int ss_ball_below_one(const ss_ball_roots *r, size_t one, ss_ball_outcome *o) {
  char b1[96];
  arb_t t;
  arb_init(t);
  arb_one(t);
  int open = 0;
  for (size_t i = 0; i < r->nrt && !open; i++) {
    const ss_ball_root *x = ss_ball_at(r, i);
    if (i == one || arb_lt(&x->mod, t)) continue;
    open = 1;
    if (arb_gt(&x->mod, t) && x->counted)
      ss_ball_verdict(o, SS_FAIL, 1, "the eigenvalue %s has modulus > 1 (proven, balls)",
                      r->text(r->route, i, b1, sizeof b1));
    else
      ss_ball_verdict(
          o, SS_UNDECIDED, 0,
          "not certified: the modulus of the eigenvalue %s and 1 not separated",
          r->text(r->route, i, b1, sizeof b1));
  }
  arb_clear(t);
  return open;
}

int ss_ball_rest_below(const ss_ball_roots *r, size_t one, const size_t *lead, int nl,
                       const arb_t x, size_t skip) {
  for (size_t i = 0; i < r->nrt; i++) {
    int led = i == one || i == skip;
    for (int j = 0; j < nl; j++)
      led |= i == lead[j];
    if (!led && !arb_lt(&ss_ball_at(r, i)->mod, x)) return 0;
  }
  return 1;
}

static double mid_mod(const ss_ball_root *r) {
  return arf_get_d(arb_midref(&r->mod), ARF_RND_NEAR);
}

int ss_ball_by_modulus(const void *a, const void *b) {
  const double x = mid_mod(a), y = mid_mod(b);
  return x > y ? -1 : x < y;
}

#if defined(__GNUC__)
__attribute__((noinline))
#endif
void ss_ball_conj(acb_t cz, const acb_t z) {
  acb_conj(cz, z);
}

void ss_ball_solver_make(ss_ball_solver *f, const arb_mat_t M, slong m, long wp) {
  const slong n = arb_mat_nrows(M);
  f->perm = flint_malloc((size_t)(n + 1) * sizeof *f->perm);
  arb_mat_init(f->M, n, n);
  arb_mat_init(f->R, n, n);
  arb_mat_init(f->LU, n, n);
  arb_mat_set(f->M, M);
  if (n <= 4 || (double)wp > 10.0 * (double)n) {
    f->kind = 1;
    f->ok = arb_mat_lu(f->perm, f->LU, M, wp);
  } else if ((double)m < 0.1 * (double)n + 1.0) {
    arb_mat_t Id, RM;
    arb_mat_init(Id, n, n);
    arb_mat_init(RM, n, n);
    arb_mat_one(Id);
    f->kind = 2;
    f->ok = arb_mat_approx_solve(f->R, M, Id, wp);
    if (f->ok) {
      arb_mat_mul(RM, f->R, M, wp);
      f->ok = arb_mat_lu(f->perm, f->LU, RM, wp);
    }
    arb_mat_clear(Id);
    arb_mat_clear(RM);
  } else {
    f->kind = 3;
  }
}

void ss_ball_solver_clear(ss_ball_solver *f) {
  if (!f->kind) return;
  flint_free(f->perm);
  arb_mat_clear(f->M);
  arb_mat_clear(f->R);
  arb_mat_clear(f->LU);
}

int ss_ball_solver_solve(const ss_ball_solver *f, arb_mat_t X, const arb_mat_t M,
                         const arb_mat_t B, long wp) {
  if (f->kind == 3 || !arb_mat_equal(M, f->M)) return arb_mat_solve(X, M, B, wp);
  if (!f->ok) return 0;
  if (f->kind == 1) {
    arb_mat_solve_lu_precomp(X, f->perm, f->LU, B, wp);
    return 1;
  }
  arb_mat_t RB;
  arb_mat_init(RB, arb_mat_nrows(B), arb_mat_ncols(B));
  arb_mat_mul(RB, f->R, B, wp);
  arb_mat_solve_lu_precomp(X, f->perm, f->LU, RB, wp);
  arb_mat_clear(RB);
  return 1;
}
