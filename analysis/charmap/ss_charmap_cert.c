/* ss_charmap_cert.c — the regularity and injectivity verdicts proven, or said
 * to be unproven, with an enclosure of the subdominant basis.  Method:
 * ss_charmap.h. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>

#include "double_interval.h"
#include "ss_ball.h"
#include "ss_charmap.h"
#include "ss_charmap_cert_impl.h"
#include "ss_clock.h"
#include "ss_exact.h"

/* An interval net: lo and hi, point by point (dim coordinates each). */
typedef struct {
  double *lo, *hi;
} inet;

static void inet_free(inet *x) {
  free(x->lo);
  free(x->hi);
  x->lo = x->hi = NULL;
}

static int inet_alloc(inet *x, size_t n, int dim) {
  x->lo = malloc((n * (size_t)dim + 1) * sizeof *x->lo);
  x->hi = malloc((n * (size_t)dim + 1) * sizeof *x->hi);
  return x->lo && x->hi ? 0 : -1;
}

/* The rules' weights are few distinct values (1/8, 3/8, 1/64, ...) read
 * once per row they stand in: their enclosures are remembered by the
 * weight's bits, in a small table direct-mapped by a hash of the bits (a miss
 * computes and replaces; the same bits give the same enclosure either way). */
enum { WCACHE = 64 };
typedef struct {
  uint64_t key[WCACHE]; /* the weight's bits */
  double lo[WCACHE], hi[WCACHE];
  unsigned char used[WCACHE]; /* 1 where key, lo, hi hold a weight */
} wcache;

/* The enclosure of weight w through the cache: 1, or 0 for a weight that is
 * no rational of denominator <= maxden (not remembered).  maxden < 0: the
 * weights are not read as rationals (algebraic, ss_fourier.h): each stands
 * for its window w +- 2^-40 max(1, |w|), outward rounded. */
static int weight_enclose(wcache *c, double w, long maxden, double *lo, double *hi) {
  if (maxden < 0) {
    if (!isfinite(w)) return 0;
    const double d = ldexp(fmax(1.0, fabs(w)), -40);
    *lo = nextafter(w - d, -INFINITY);
    *hi = nextafter(w + d, INFINITY);
    return 1;
  }
  uint64_t b;
  memcpy(&b, &w, sizeof b);
  const size_t h = (size_t)((b * 0x9E3779B97F4A7C15ULL) >> 58); /* 0..63 */
  if (c->used[h] && c->key[h] == b) {
    *lo = c->lo[h];
    *hi = c->hi[h];
    return 1;
  }
  if (!ss_exact_rational_enclose(w, maxden, lo, hi)) return 0;
  c->used[h] = 1;
  c->key[h] = b;
  c->lo[h] = *lo;
  c->hi[h] = *hi;
  return 1;
}

/* The push in midpoint-radius form (ss_charmap.h's enclosure, by another
 * arithmetic than di_t's four products a term).  With u = 2^-53, gamma_n =
 * n u / (1 - n u), inputs p = pm +- pr (pm = the box's midpoint, pr >= its
 * distance to either end) and weights w = wm +- wr (wr = 0 for the
 * dyadic weights of the rules): for every p and w in their boxes,
 *   |sum w p - fl(sum wm pm)| <= sum (|wm| pr + wr (|pm| + pr)) + gamma_n A,
 * A = sum |wm| |pm| (Higham, 3.1: a sum of n products rounded to nearest in
 * any order), n the row's length.  The bound r is formed from nonnegative
 * doubles (its own rounding below (n + 8) u relatively) and taken times
 * 1 + 2^-20, plus 2^-1000 for underflow; the output's ends m -+ r are moved
 * out by 2 u (|m| + r) more, which covers their subtraction's rounding.  An
 * input box that is not finite or not ordered, a result that is not finite,
 * or a row of 2^20 terms or more gives the whole line (-inf, inf): nothing
 * proven there, as a di_t enclosure would be. */
int ss_charmap_push_interval(const ss_local_ring *R, const double *plo, const double *phi,
                             int dim, long maxden, double *olo, double *ohi) {
  if (dim < 1 || dim > 3) return -1;
  const double u = 0x1p-53;
  wcache wc;
  memset(wc.used, 0, sizeof wc.used);
  const size_t np = R->nprev * (size_t)dim;
  double *pm = malloc((2 * np + 1) * sizeof *pm);
  if (!pm) return -1;
  double *pr = pm + np;
  for (size_t k = 0; k < np; k++) {
    const int ok = plo[k] <= phi[k] && isfinite(plo[k]) && isfinite(phi[k]);
    pm[k] = ok ? 0.5 * plo[k] + 0.5 * phi[k] : 0.0;
    pr[k] = ok ? FLINT_MAX(phi[k] - pm[k], pm[k] - plo[k]) : (double)INFINITY;
  }
  for (size_t i = 0; i < R->nv; i++) {
    const size_t len = R->ptr[i + 1] - R->ptr[i];
    double m[3] = {0.0, 0.0, 0.0}, r[3] = {0.0, 0.0, 0.0}, A[3] = {0.0, 0.0, 0.0};
    for (size_t q = R->ptr[i]; q < R->ptr[i + 1]; q++) {
      double lo, hi;
      if (!weight_enclose(&wc, R->w[q], maxden, &lo, &hi)) {
        free(pm);
        return -1;
      }
      const double wm = lo == hi ? lo : 0.5 * lo + 0.5 * hi,
                   wr = lo == hi ? 0.0 : FLINT_MAX(hi - wm, wm - lo), wa = fabs(wm);
      const size_t k0 = R->col[q] * (size_t)dim;
      for (int d = 0; d < dim; d++) {
        const double a = pm[k0 + (size_t)d], b = pr[k0 + (size_t)d];
        m[d] += wm * a;
        A[d] += wa * fabs(a);
        r[d] += wa * b + wr * (fabs(a) + b);
      }
    }
    const double g = (double)len * u / (1.0 - (double)len * u);
    for (int d = 0; d < dim; d++) {
      double e = (r[d] + g * A[d]) * (1.0 + 0x1p-20) + 0x1p-1000;
      e += 2.0 * u * (fabs(m[d]) + e);
      const int ok = isfinite(m[d]) && isfinite(e) && len < (1u << 20);
      olo[i * (size_t)dim + (size_t)d] = ok ? m[d] - e : -(double)INFINITY;
      ohi[i * (size_t)dim + (size_t)d] = ok ? m[d] + e : (double)INFINITY;
    }
  }
  free(pm);
  return 0;
}

/* Push the interval net prev through ring level R into out (allocated):
 * 0, -1 out of memory, -2 a weight that is not a rational of bounded
 * denominator. */
static int push(const ss_local_ring *R, const inet *prev, int dim, long maxden,
                inet *out) {
  if (inet_alloc(out, R->nv, dim)) return -1;
  return ss_charmap_push_interval(R, prev->lo, prev->hi, dim, maxden, out->lo, out->hi)
             ? -2
             : 0;
}

typedef ss_charmap_proven proven;

static void judge(const ss_local_ring *R, const inet *x, int dim, int depth, proven *p) {
  memset(p, 0, sizeof *p);
  p->cells = R->ncells;
  for (size_t c = 0; c < R->ncells; c++) {
    double lo[SS_MAXCELLVERTS * 3], hi[SS_MAXCELLVERTS * 3];
    const int nv = ss_cell_nverts(R->ctype[c]);
    for (int j = 0; j < nv; j++)
      for (int d = 0; d < dim; d++) {
        const size_t k =
            R->corner[c * SS_MAXCELLVERTS + (size_t)j] * (size_t)dim + (size_t)d;
        lo[j * dim + d] = x->lo[k];
        hi[j * dim + d] = x->hi[k];
      }
    ss_jac_result res;
    ss_jac_cell_interval_sign(R->ctype[c], lo, hi, dim, depth, &res);
    p->pos += res.sign == SS_JAC_POSITIVE;
    p->neg += res.sign == SS_JAC_NEGATIVE;
    p->folded += res.sign == SS_JAC_FOLDED;
    p->unknown += res.sign != SS_JAC_POSITIVE && res.sign != SS_JAC_NEGATIVE &&
                  res.sign != SS_JAC_FOLDED;
  }
}

int ss_charmap_cert_sym_margin(double dx2, double e2, double mu0, double gap) {
  const double smin = sqrt(fmax(mu0, 0.0)), en = sqrt(e2);
  return sqrt(dx2) + 2.0 * en < 0.5 * (smin - en) * gap;
}

/* psi o sigma = psi proven: P commutes with the exact S (entries compared as
 * the rationals they stand for; for algebraic weights, maxden < 0, S is
 * invariant within the entries' windows, the premise under which the ball
 * routes enclosed the basis: DESIGN section 5) and, with X the enclosed basis (midpoint
 * Xm, radius E), ||P Xm - Xm||_F + 2 ||E||_F < (s_min(Xm) - ||E||_F) gap / 2: if M_sigma
 * != I then ||P X - X|| = ||X (M_sigma - I)|| >= s_min(X) gap.  The few norms are
 * computed in double with a margin of a factor 2.  Returns 1 proven, 0 not, -1 out of
 * memory. */
static int sym_proven(const ss_local *M, const ss_case *c, const ss_charmap_sym *y,
                      const double *lo, const double *hi, int m, long maxden,
                      ss_error *err) {
  const size_t n = M->n2;
  size_t *P = malloc((n + 1) * sizeof *P);
  if (!P) return -1;
  int ok = ss_charmap_sym_perm(M, c, y, P, err) == SS_OK;
  size_t bi, bj;
  if (ok && maxden < 0) /* algebraic: invariant within the windows, the premise
                         * under which the basis was enclosed (DESIGN 5) */
    ok = ss_ball_invariant(M->S, n, P, &bi, &bj);
  for (size_t i = 0; ok && maxden >= 0 && i < n; i++)
    for (size_t j = 0; ok && j < n; j++) {
      const double a = M->S[i * n + j], b = M->S[P[i] * n + P[j]];
      long long pa = 0, qa = 1, pb = 0, qb = 1;
      if (a == 0.0 && b == 0.0) continue;
      ok = ss_exact_rational(a, maxden, &pa, &qa) &&
           ss_exact_rational(b, maxden, &pb, &qb) && pa == pb && qa == qb;
    }
  double dx = 0.0, e = 0.0, G[9] = {0};
  for (int a = 0; ok && a < m; a++)
    for (size_t i = 0; i < n; i++) {
      const double xa = 0.5 * (lo[(size_t)a * n + i] + hi[(size_t)a * n + i]);
      const double xp = 0.5 * (lo[(size_t)a * n + P[i]] + hi[(size_t)a * n + P[i]]);
      const double r = 0.5 * (hi[(size_t)a * n + i] - lo[(size_t)a * n + i]);
      dx += (xp - xa) * (xp - xa);
      e += r * r;
      for (int b = 0; b < m; b++)
        G[a * m + b] += xa * 0.5 * (lo[(size_t)b * n + i] + hi[(size_t)b * n + i]);
    }
  double mu[3];
  if (ok && LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'N', 'U', m, G, m, mu)) ok = 0;
  if (ok) ok = ss_charmap_cert_sym_margin(dx, e, mu[0], y->gap);
  free(P);
  return ok;
}

int ss_charmap_cert_persists(const proven *Q, const proven *L, double shrink) {
  /* at least the proven bad cells now, at most the proven and unknown ones
   * before */
  const int plus = L->pos > L->neg + L->unknown, minus = L->neg > L->pos + L->unknown;
  const int qplus = Q->pos > Q->neg + Q->unknown, qminus = Q->neg > Q->pos + Q->unknown;
  if (!(plus || minus) || !(qplus || qminus)) return 0;
  const double now = (double)(L->folded + (plus ? L->neg : L->pos)) / (double)L->cells;
  const double before =
      (double)(Q->folded + Q->unknown + (qplus ? Q->neg : Q->pos)) / (double)Q->cells;
  return now > 0.0 && now >= shrink * before;
}

ss_status ss_charmap_certify(const ss_local *M, const ss_case *c, const double *lo,
                             const double *hi, int m, long maxden,
                             const ss_charmap_opts *o, ss_regularity *r,
                             ss_charmap_inj *inj, ss_error *err) {
  r->verdict.certified = 0;
  inj->verdict.certified = 0;
  ss_verdict *v = &r->verdict;
  char why[200] = "";
  ss_status st = SS_OK;
  const size_t n = M->n2;
  for (size_t i = 0; i < n * (size_t)m; i++)
    if (!(lo[i] <= hi[i]) || !isfinite(lo[i]) || !isfinite(hi[i])) {
      snprintf(why, sizeof why, "the basis enclosure is not finite");
      goto uncertified;
    }
  ss_charmap_times *tm = o->times;
  double c1 = tm ? ss_clock_cpu() : 0.0;
  if (r->sym.found) {
    const int p = sym_proven(M, c, &r->sym, lo, hi, m, maxden, err);
    if (tm) ss_clock_lap(&tm->cert_sym, &c1);
    if (p < 0) return ss_error_nomem(err, "certification");
    if (p) {
      r->verdict.certified = inj->verdict.certified = 1;
      return SS_OK;
    }
    snprintf(why, sizeof why, "psi o sigma = psi is not proven by the enclosure");
    goto uncertified;
  }
  /* the ring levels the double-precision verdict judged, in intervals: the
   * net pushed through all of them (a weight that is not a rational of
   * bounded denominator, on any level, leaves the verdict unproven), but
   * only the levels the rules below read judged (a pass: the deciding level;
   * a fail: it and the one before; anything else is not certified whatever
   * the counts) */
  proven pr[SS_LOCAL_MAXRING];
  memset(pr, 0, sizeof pr);
  inet prev = {NULL, NULL}, cur = {NULL, NULL};
  if (inet_alloc(&prev, n, m)) return ss_error_nomem(err, "certification");
  for (size_t i = 0; i < n; i++)
    for (int d = 0; d < m; d++) {
      prev.lo[i * (size_t)m + (size_t)d] = lo[(size_t)d * n + i];
      prev.hi[i * (size_t)m + (size_t)d] = hi[(size_t)d * n + i];
    }
  const int nl = r->nlevels < M->nring ? r->nlevels : M->nring;
  const int last = r->ring_level >= 0 && r->ring_level < nl ? r->ring_level : nl - 1;
  const int first = v->verdict == SS_PASS ? last : v->verdict == SS_FAIL ? last - 1 : nl;
  for (int l = 0; l < nl; l++) {
    const int rc = push(M->ring + l, &prev, m, maxden, &cur);
    inet_free(&prev);
    prev = cur;
    cur.lo = cur.hi = NULL;
    if (rc == -1) {
      inet_free(&prev);
      return ss_error_nomem(err, "certification");
    }
    if (rc == -2) {
      snprintf(why, sizeof why,
               "a weight of the rule is not a rational of bounded "
               "denominator");
      inet_free(&prev);
      goto uncertified;
    }
    if (l >= first && l <= last) judge(M->ring + l, &prev, m, o->depth, pr + l);
    if (tm) ss_clock_lap(&tm->cert_level[l], &c1);
  }
  inet_free(&prev);
  if (nl < 1) {
    snprintf(why, sizeof why, "no ring level was judged");
    goto uncertified;
  }
  const proven *L = pr + last;
  if (v->verdict == SS_PASS) {
    if (L->pos == L->cells || L->neg == L->cells) {
      r->verdict.certified = 1;
      return SS_OK;
    }
    snprintf(why, sizeof why,
             "ring level %d: %zu of %zu cells not proven of one sign in interval "
             "arithmetic",
             last, L->cells - (L->pos > L->neg ? L->pos : L->neg), L->cells);
    goto uncertified;
  }
  if (v->verdict == SS_FAIL && last >= 1) {
    /* the rule of the verdict with proven counts */
    const proven *Q = pr + last - 1;
    if (ss_charmap_cert_persists(Q, L, r->shrink)) {
      r->verdict.certified = 1;
      return SS_OK;
    }
    snprintf(why, sizeof why,
             "ring levels %d and %d: the folds are not proven to persist in interval "
             "arithmetic (%zu and %zu cells unproven)",
             last - 1, last, Q->unknown, L->unknown);
    goto uncertified;
  }
  if (v->verdict == SS_FAIL)
    snprintf(why, sizeof why, "a fold on one ring level only is not certified");
  else
    snprintf(why, sizeof why, "undecided in double precision");
uncertified:
  ss_verdict_unproven(v, why);
  return st;
}
