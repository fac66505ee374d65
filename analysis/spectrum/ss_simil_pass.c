/* ss_simil_pass.c — the certified pass from the discs of all blocks and its
 * basis (ss_simil.h, "The pass", "Basis on a pass"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arb_mat.h"

#include "ss_simil_impl.h"

enum { PREC = 80 };

/* The entries of S as balls holding the rationals (s->eb); 0, -1 out of
 * memory. */
static int entry_balls(ss_simil *s) {
  const size_t nnz = s->A.ptr[s->n];
  s->eb = _arb_vec_init((slong)nnz + 1);
  arf_t a, c;
  arf_init(a);
  arf_init(c);
  for (size_t k = 0; k < nnz; k++) {
    arf_set_d(a, s->lo[k]);
    arf_set_d(c, s->hi[k]);
    arb_set_interval_arf(s->eb + k, a, c, PREC);
  }
  arf_clear(a);
  arf_clear(c);
  return 0;
}

/* Entry k of S as a double t and a radius r with |S_k - t| <= r. */
static void mid_rad(const ss_simil *s, size_t k, double *t, double *r) {
  *t = 0.5 * (s->lo[k] + s->hi[k]);
  *r = s->lo[k] == s->hi[k] ? 0.0 : ss_simil_up(fmax(s->hi[k] - *t, *t - s->lo[k]));
}

/* The dense diagonal blocks and their discs: 0, 1 a block refused, -1 out of
 * memory. */
static int all_discs(ss_simil *s) {
  const size_t n1 = s->n1;
  double *T = calloc(n1 * n1 + 1, sizeof *T), *Tr = calloc(n1 * n1 + 1, sizeof *Tr);
  int rc = T && Tr ? 0 : -1;
  for (size_t i = 0; i < n1 && !rc; i++)
    for (size_t k = s->A.ptr[i]; k < s->A.mid[i]; k++)
      mid_rad(s, k, T + i * n1 + s->A.col[k], Tr + i * n1 + s->A.col[k]);
  if (!rc) rc = ss_simil_block(s, T, Tr, n1, -1);
  if (!rc && !s->Xa) rc = 1;
  double **seen = calloc((size_t)s->K.n + 1, sizeof *seen); /* distinct blocks */
  if (!seen) rc = -1;
  for (long c = 0; c < s->K.n && !rc; c++) {
    const size_t st = s->K.start[c], sz = s->K.start[c + 1] - st;
    double *B = malloc((2 * sz * sz + 1) * sizeof *B);
    if (!B) {
      rc = -1;
      break;
    }
    memset(B, 0, 2 * sz * sz * sizeof *B);
    for (size_t u = 0; u < sz; u++) {
      const size_t i = n1 + s->K.comp[st + u];
      for (size_t k = s->A.mid[i]; k < s->A.ptr[i + 1]; k++) {
        const size_t j = s->A.col[k] - n1;
        if (s->K.cid[j] != (size_t)c) continue;
        mid_rad(s, k, B + u * sz + s->K.pos[j], B + sz * sz + u * sz + s->K.pos[j]);
      }
    }
    size_t r = (size_t)c;
    for (long d = 0; d < c && r == (size_t)c; d++)
      if (seen[d] && s->K.start[d + 1] - s->K.start[d] == sz &&
          !memcmp(seen[d], B, 2 * sz * sz * sizeof *B))
        r = (size_t)d;
    s->rep[c] = r;
    s->dstart[c] = s->nd;
    if (r != (size_t)c) { /* the same discs as its first occurrence's */
      for (size_t u = 0; u < sz; u++) {
        s->d[s->nd] = s->d[s->dstart[r] + u];
        s->d[s->nd++].block = c;
      }
      free(B);
      continue;
    }
    seen[c] = B;
    rc = ss_simil_block(s, B, B + sz * sz, sz, c);
  }
  for (long c = 0; seen && c < s->K.n; c++)
    free(seen[c]);
  free(seen);
  free(T);
  free(Tr);
  return rc;
}

/* Lower bound on the distance between the centres of discs a and b. */
static double dist(const ss_simil_disc *a, double bre, double bim) {
  return ss_simil_dn(hypot(a->re - bre, a->im - bim));
}

/* Order by decreasing modulus of the centre (d: the discs). */
static int by_centre_modulus(const void *x, const void *y, const void *d) {
  const ss_simil_disc *D = d;
  const size_t a = *(const size_t *)x, b = *(const size_t *)y;
  const double ma = hypot(D[a].re, D[a].im), mb = hypot(D[b].re, D[b].im);
  return ma > mb ? -1 : ma < mb;
}

/* The pass's tests (header): 1 with s->lead set, 0 with s->why. */
static int decide(ss_simil *s) {
  const ss_simil_disc *D = s->d;
  const size_t nd = s->nd;
  const int m = s->m;
  size_t one = nd, nones = 0;
  for (size_t i = 0; i < nd; i++)
    if (dist(D + i, 1.0, 0.0) <= ss_simil_up(D[i].rad)) one = i, nones++;
  if (nones != 1 || D[one].block != -1) {
    snprintf(s->why, sizeof s->why, "%zu discs contain 1", nones);
    return 0;
  }
  for (size_t i = 0; i < nd; i++)
    if (i != one &&
        dist(D + i, D[one].re, D[one].im) <= ss_simil_up(D[i].rad + D[one].rad)) {
      snprintf(s->why, sizeof s->why, "the disc of 1 meets another");
      return 0;
    }
  /* the m largest centres after it */
  size_t top[3] = {nd, nd, nd};
  for (int q = 0; q < m; q++)
    for (size_t i = 0; i < nd; i++) {
      if (i == one || i == top[0] || i == top[1]) continue;
      if (top[q] == nd || by_centre_modulus(&i, top + q, s->d) < 0) top[q] = i;
    }
  double lowm = INFINITY;
  for (int q = 0; q < m; q++) {
    const size_t i = top[q];
    if (i == nd || D[i].block != -1) {
      snprintf(s->why, sizeof s->why, "lambda%d is not the one-ring block's", q + 1);
      return 0;
    }
    const double r = ss_simil_up(D[i].rad + fabs(D[i].im)), lo = ss_simil_dn(D[i].re - r);
    if (!(lo > 0.0) ||
        !(ss_simil_up(D[i].re + r) < ss_simil_dn(1.0 - 2.0 * D[one].rad))) {
      snprintf(s->why, sizeof s->why, "lambda%d's disc leaves (0, 1)", q + 1);
      return 0;
    }
    if (q > 0) {
      const size_t p = top[q - 1];
      const double rp = ss_simil_up(D[p].rad + fabs(D[p].im));
      if (!(ss_simil_up(D[i].re + r) < ss_simil_dn(D[p].re - rp))) {
        snprintf(s->why, sizeof s->why, "the discs of lambda%d and lambda%d meet", q,
                 q + 1);
        return 0;
      }
    }
    lowm = lo;
  }
  for (size_t i = 0; i < nd; i++) {
    if (i == one || i == top[0] || i == top[1] || (m == 3 && i == top[2])) continue;
    if (!(ss_simil_up(hypot(D[i].re, D[i].im) + D[i].rad) < lowm)) {
      snprintf(s->why, sizeof s->why, "a disc reaches lambda%d's", m);
      return 0;
    }
  }
  s->lead[0] = one;
  for (int q = 0; q < m; q++)
    s->lead[q + 1] = top[q];
  return 1;
}

/* A's rows of lambda's eigenvector (disc i of A, i < n1) into balls y[0..n1):
 * X_i +- sum_{j != i} beta_j |X_j|; 1, or 0 when a bound fails. */
static int one_ring_column(const ss_simil *s, size_t i, arb_ptr y) {
  const size_t k = s->n1;
  const ss_simil_disc *D = s->d; /* A's discs are the first n1 */
  const double *Xr = s->Xa, *Xi = s->Xa + k * k;
  const double ri = ss_simil_up(D[i].rad + fabs(D[i].im));
  double *beta = malloc((k + 1) * sizeof *beta);
  if (!beta) return -1;
  for (size_t j = 0; j < k; j++) { /* |w_j| <= min(1, rho_j / d_j), d_j > rho_j */
    const double d = ss_simil_dn(dist(D + j, D[i].re, 0.0) - ri);
    beta[j] = j == i ? 0.0 : fmin(1.0, ss_simil_up(D[j].rad / d));
    if (j != i && !(d > D[j].rad)) {
      free(beta);
      return 0;
    }
  }
  int ok = 1;
  for (size_t q = 0; q < k; q++) {
    double r = 0.0;
    for (size_t j = 0; j < k; j++)
      r += beta[j] * (fabs(Xr[q * k + j]) + fabs(Xi[q * k + j]));
    r = ss_simil_up(r);
    arb_set_d(y + q, Xr[q * k + i]);
    mag_set_d(arb_radref(y + q), r);
    if (Xr[q * k + i] == 1.0 && !(r < 1.0)) ok = 0; /* may vanish */
  }
  free(beta);
  return ok;
}

/* Outer rows of the column y (n balls, A's rows set) for lambda in lam:
 * (C_cc - lam) y_c = -(rows c on earlier columns) y, a block's factors shared
 * by the later components with the same block; 1, 0 not verified, -1 out of
 * memory. */
static int outer_rows(const ss_simil *s, const arb_t lam, arb_ptr y) {
  const size_t n1 = s->n1;
  ss_ball_solver *fs = calloc((size_t)s->K.n + 1, sizeof *fs);
  if (!fs) return -1;
  int ok = 1;
  for (long c = 0; c < s->K.n && ok; c++) {
    const size_t st = s->K.start[c], sz = s->K.start[c + 1] - st;
    arb_mat_t M, R, Y;
    arb_mat_init(M, (slong)sz, (slong)sz);
    arb_mat_init(R, (slong)sz, 1);
    arb_mat_init(Y, (slong)sz, 1);
    for (size_t u = 0; u < sz; u++) {
      const size_t i = n1 + s->K.comp[st + u];
      for (size_t k = s->A.ptr[i]; k < s->A.ptr[i + 1]; k++) {
        const size_t j = s->A.col[k];
        if (j >= n1 && s->K.cid[j - n1] == (size_t)c)
          arb_add(arb_mat_entry(M, u, s->K.pos[j - n1]),
                  arb_mat_entry(M, u, s->K.pos[j - n1]), s->eb + k, PREC);
        else
          arb_submul(arb_mat_entry(R, u, 0), s->eb + k, y + j, PREC);
      }
      arb_sub(arb_mat_entry(M, u, u), arb_mat_entry(M, u, u), lam, PREC);
    }
    const size_t r = s->rep[c];
    if (sz > 1 && !fs[r].kind) ss_ball_solver_make(fs + r, M, 1, PREC);
    ok = sz > 1 ? ss_ball_solver_solve(fs + r, Y, M, R, PREC)
                : arb_mat_solve(Y, M, R, PREC);
    for (size_t u = 0; u < sz && ok; u++)
      arb_set(y + n1 + s->K.comp[st + u], arb_mat_entry(Y, u, 0));
    arb_mat_clear(M);
    arb_mat_clear(R);
    arb_mat_clear(Y);
  }
  for (long c = 0; c < s->K.n; c++)
    ss_ball_solver_clear(fs + c);
  free(fs);
  return ok;
}

/* The basis into s->out: 1, 0 not proven (s->why), -1 out of memory. */
static int basis(ss_simil *s) {
  const size_t n = s->n;
  const int m = s->m;
  double *lo = malloc((n * (size_t)m + 1) * sizeof *lo);
  double *hi = malloc((n * (size_t)m + 1) * sizeof *hi);
  arb_ptr y = _arb_vec_init((slong)n);
  arb_t lam;
  arb_init(lam);
  int ok = lo && hi && !entry_balls(s) ? 1 : -1;
  for (int q = 0; q < m && ok == 1; q++) {
    const ss_simil_disc *d = s->d + s->lead[q + 1];
    ok = one_ring_column(s, s->lead[q + 1], y);
    arb_set_d(lam, d->re);
    mag_set_d(arb_radref(lam), ss_simil_up(d->rad + fabs(d->im)));
    if (ok == 1) ok = outer_rows(s, lam, y);
    if (!ok)
      snprintf(s->why, sizeof s->why, "lambda%d's eigenvector not enclosed", q + 1);
    for (size_t i = 0; i < n && ok == 1; i++)
      ss_ball_doubles(y + i, lo + (size_t)q * n + i, hi + (size_t)q * n + i);
  }
  if (ok == 1) {
    s->out.lo = lo;
    s->out.hi = hi;
  } else {
    free(lo);
    free(hi);
  }
  _arb_vec_clear(y, (slong)n);
  arb_clear(lam);
  return ok;
}

static ss_status run(ss_simil *s, const double *S, long maxden, ss_error *err) {
  if (ss_csr_make(S, s->n, s->n1, &s->A) || ss_scc_make(&s->A, s->n, s->n1, &s->K))
    return ss_error_nomem(err, "verified similarity");
  int rc = ss_simil_rational(s, maxden);
  if (rc == 0)
    snprintf(s->why, sizeof s->why, "S is not a rational matrix of row sums 1");
  if (rc == 1) {
    s->d = malloc((s->n + 1) * sizeof *s->d);
    s->rep = malloc(((size_t)s->K.n + 1) * sizeof *s->rep);
    s->dstart = malloc(((size_t)s->K.n + 1) * sizeof *s->dstart);
    rc = s->d && s->rep && s->dstart ? all_discs(s) : -1;
    if (rc == 1) snprintf(s->why, sizeof s->why, "a block's similarity not verified");
    rc = rc == 0 ? 1 : rc == 1 ? 0 : -1;
  }
  if (rc == 1) rc = decide(s);
  if (rc == 1) rc = basis(s);
  if (rc < 0) return ss_error_nomem(err, "verified similarity");
  if (rc == 1) {
    const ss_simil_disc *D = s->d;
    s->passed = 1;
    const ss_simil_disc *last = D + s->lead[s->m];
    char vals[64];
    int len = 0;
    for (int q = 1; q <= s->m; q++)
      len += snprintf(vals + len, sizeof vals - (size_t)len, "%s%.6g", q > 1 ? ", " : "",
                      D[s->lead[q]].re);
    snprintf(
        s->why, sizeof s->why,
        "certified by a verified similarity: 1 simple, lambda1..%d = %s real, simple "
        "and isolated in Gershgorin discs, all others in |z| < %.6g",
        s->m, vals, ss_simil_dn(last->re - ss_simil_up(last->rad + fabs(last->im))));
    ss_ball_verdict(&s->out, SS_PASS, 1, "%s", s->why);
  }
  return SS_OK;
}

ss_status ss_simil_new(const double *S, size_t n, size_t n1, int m, long maxden,
                       ss_simil **out, ss_error *err) {
  *out = NULL;
  if (n1 < 1 || n1 > n || (m != 2 && m != 3) || maxden < 1)
    return ss_error_set(err, SS_EINPUT, "verified similarity: n1 %zu of %zu, m %d", n1, n,
                        m);
  ss_status st = ss_scc_check_form(S, n, n1, err);
  if (st) return st;
  ss_simil *s = calloc(1, sizeof *s);
  if (!s) return ss_error_nomem(err, "verified similarity");
  s->n = n;
  s->n1 = n1;
  s->m = m;
  ss_ball_outcome_init(&s->out, n, m);
  if ((st = run(s, S, maxden, err))) {
    ss_simil_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}

void ss_simil_free(ss_simil *s) {
  if (!s) return;
  if (s->eb) _arb_vec_clear(s->eb, (slong)s->A.ptr[s->n] + 1);
  ss_csr_free(&s->A);
  ss_scc_free(&s->K);
  free(s->lo);
  free(s->hi);
  free(s->d);
  free(s->rep);
  free(s->dstart);
  free(s->Xa);
  ss_ball_outcome_clear(&s->out);
  free(s);
}

int ss_simil_passed(const ss_simil *s) {
  return s->passed;
}

const char *ss_simil_why(const ss_simil *s) {
  return s->why;
}

const ss_ball_outcome *ss_simil_outcome(const ss_simil *s) {
  return &s->out;
}

const ss_simil_disc *ss_simil_discs(const ss_simil *s, size_t *nd) {
  *nd = s->nd;
  return s->d;
}

int ss_simil_lead(const ss_simil *s, size_t lead[4]) {
  if (!s->passed) return 0;
  memcpy(lead, s->lead, sizeof s->lead);
  return 1;
}
