/* ss_psi_tube.c — det Dψ's sign proven in a spoke's tube (method:
 * ss_psi_tube.h).  Ball arithmetic (arb) at PREC bits for the change of
 * basis, the tail and the nets; ss_psi_bernstein's interval test for the
 * signs; ss_exact for F's spectrum and eigenspace. */
#include "ss_psi_tube.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <arb.h>
#include <acb_mat.h>
#include <arb_mat.h>

#include "ss_exact.h"
#include "ss_psi_bernstein.h"

#define PREC  128
#define NNORM 224 /* powers of N / mu whose norms are bounded (>= NTAU + QMAX) */
#define QMAX  96  /* the period q of the tail bound is at most this */
#define NTAU  128 /* layers judged directly at most (> QMAX: tail_product) */

/* What the proof holds (method: ss_psi_tube.h). */
typedef struct {
  const ss_limit_tube *t;
  size_t n;            /* columns */
  size_t r;            /* n - 3: the rows of N */
  arb_t mu;            /* the across eigenvalue */
  arb_mat_t X;         /* n x 2: mu's eigenvectors */
  size_t piv[3];       /* T's pivot rows (no unit vector there) */
  size_t *eidx;        /* n: row i of E's unit vector is e_i for beta's row
                          eidx[i]; SIZE_MAX at the pivots */
  arb_mat_t C;         /* 3 x r */
  arb_mat_t N;         /* r x r */
  arb_mat_t beta;      /* r x 12 (layer l, coordinate d at column 3 l + d) */
  arb_mat_t b1;        /* (I - N)^-1 beta */
  arb_mat_t bmu;       /* (mu I - N)^-1 beta */
  arb_mat_t a;         /* 1 x 12: the spoke's curve's points */
  arb_mat_t b;         /* 2 x 12: B's coefficients */
  arb_mat_t G[3];      /* 16 x n: the quadrants' factors */
  double norm[NNORM];  /* upper bounds of ||(N / mu)^m||_inf */
  int depth;           /* the pieces' subdivision depth */
  arb_mat_t T;         /* n x n: [1 | X | E] */
  arb_mat_struct *tau; /* NTAU: (N / mu)^m, m < NTAU (the cache's) */
  int tail_m0;         /* the tail being judged: layers m >= tail_m0 */
  int tail_q;          /* its period (tail_period) */
} tube_ws;

/* One cross-section met: everything that depends on F alone (a whole
 * tube_ws, its points' part unused), kept for the next box of the same F. */
typedef struct {
  long long *Fp, *Fq;  /* the key: F exactly */
  size_t n;            /* its size */
  char why[200];       /* not provable for this F: why (else empty) */
  double mu, ratio;    /* for the result */
  tube_ws w;           /* mu, X, piv, eidx, C, N, norm, T */
  arb_mat_struct *tau; /* NTAU powers */
} tube_spec;

struct ss_psi_tube_cache {
  tube_spec **s; /* the cross-sections met */
  size_t n, cap; /* their number and room */
};

static void ws_clear(tube_ws *w) {
  arb_mat_clear(w->T);
  arb_clear(w->mu);
  arb_mat_clear(w->X);
  arb_mat_clear(w->C);
  arb_mat_clear(w->N);
  free(w->eidx);
}

/* What F alone determines (the points' part and the quadrants' factors G
 * are ss_psi_tube_sign's and gfactor's). */
static void ws_init(tube_ws *w, const ss_limit_tube *t) {
  memset(w, 0, sizeof *w);
  w->t = t;
  w->n = t->ncol;
  w->r = t->ncol - 3;
  arb_init(w->mu);
  arb_mat_init(w->T, (slong)w->n, (slong)w->n);
  arb_mat_init(w->X, (slong)w->n, 2);
  arb_mat_init(w->C, 3, (slong)w->r);
  arb_mat_init(w->N, (slong)w->r, (slong)w->r);
}

/* w->G[c] from the tube's exact G_c (initialised here). */
static void gfactor(tube_ws *w, int c) {
  const size_t n = w->n;
  arb_mat_init(w->G[c], 16, (slong)n);
  for (size_t i = 0; i < 16 * n; i++) {
    arb_ptr e = arb_mat_entry(w->G[c], (slong)(i / n), (slong)(i % n));
    arb_set_si(e, w->t->Gp[c][i]);
    arb_div_si(e, e, w->t->Gq[c][i], PREC);
  }
}

static void spec_free(tube_spec *sp) {
  if (!sp) return;
  ws_clear(&sp->w);
  for (int m = 0; m < NTAU && sp->tau; m++)
    arb_mat_clear(sp->tau + m);
  free(sp->tau);
  free(sp->Fp);
  free(sp->Fq);
  free(sp);
}

/* x <- [lo, hi] */
static void ball_of(arb_t x, double lo, double hi) {
  arf_t a, b;
  arf_init(a);
  arf_init(b);
  arf_set_d(a, lo);
  arf_set_d(b, hi);
  arb_set_interval_arf(x, a, b, PREC);
  arf_clear(a);
  arf_clear(b);
}

/* [lo, hi] holding x, outward rounded to doubles */
static void bounds_of(const arb_t x, double *lo, double *hi) {
  arf_t u;
  arf_init(u);
  arb_get_lbound_arf(u, x, PREC);
  *lo = arf_get_d(u, ARF_RND_FLOOR);
  arb_get_ubound_arf(u, x, PREC);
  *hi = arf_get_d(u, ARF_RND_CEIL);
  arf_clear(u);
}

/* mu and X enclosed at PREC bits (ss_exact exports them as doubles, and
 * the powers of N would widen their ulps by |N|^m): Rump's method on F
 * (acb_mat_eig_enclosure_rump, as ss_exact_basis uses it) from X's
 * midpoints, the two rows of largest |det| moved last (frozen).  It proves F
 * X' = X' J with J's eigenvalues in a ball; that ball meeting no root of F
 * but mu (rt: F's roots, enclosed) makes X' a basis of mu's eigenspace (mu
 * non-defective), real (the frozen rows real).  0, 1 not proven, -1 out of
 * memory. */
static int refine(tube_ws *w, const ss_exact_root *rt, size_t nr) {
  const slong n = (slong)w->n;
  slong *perm = malloc(((size_t)n + 1) * sizeof *perm);
  if (!perm) return -1;
  /* the frozen rows: the pair (i, j) of largest |det X[{i,j}]| (midpoints) */
  slong bi = 0, bj = 1;
  double best = -1.0;
  for (slong i = 0; i < n; i++)
    for (slong j = i + 1; j < n; j++) {
      const double a = arf_get_d(arb_midref(arb_mat_entry(w->X, i, 0)), ARF_RND_NEAR),
                   b = arf_get_d(arb_midref(arb_mat_entry(w->X, i, 1)), ARF_RND_NEAR),
                   c = arf_get_d(arb_midref(arb_mat_entry(w->X, j, 0)), ARF_RND_NEAR),
                   d = arf_get_d(arb_midref(arb_mat_entry(w->X, j, 1)), ARF_RND_NEAR);
      if (fabs(a * d - b * c) > best) best = fabs(a * d - b * c), bi = i, bj = j;
    }
  for (slong i = 0, k = 0; i < n; i++)
    if (i != bi && i != bj) perm[k++] = i;
  perm[n - 2] = bi, perm[n - 1] = bj;
  acb_mat_t A, Xa, X;
  acb_t lam, lr;
  acb_mat_init(A, n, n), acb_mat_init(Xa, n, 2), acb_mat_init(X, n, 2);
  acb_init(lam), acb_init(lr);
  for (slong i = 0; i < n; i++) {
    for (slong j = 0; j < n; j++) {
      arb_ptr e = acb_realref(acb_mat_entry(A, i, j));
      arb_set_si(e, w->t->Fp[perm[i] * n + perm[j]]);
      arb_div_si(e, e, w->t->Fq[perm[i] * n + perm[j]], PREC);
    }
    for (slong j = 0; j < 2; j++)
      arf_set(arb_midref(acb_realref(acb_mat_entry(Xa, i, j))),
              arb_midref(arb_mat_entry(w->X, perm[i], j)));
  }
  arf_set(arb_midref(acb_realref(lam)), arb_midref(w->mu));
  int out = 1;
  for (int round = 0; round < 2; round++) {
    acb_mat_eig_enclosure_rump(lr, NULL, X, A, lam, Xa, PREC);
    if (!acb_is_finite(lr) || !acb_mat_is_finite(X)) goto done;
    if (round == 0) acb_mat_get_mid(Xa, X);
  }
  for (size_t k = 0; k < nr; k++) { /* only mu's ball may meet lr */
    acb_t z;
    acb_init(z);
    acb_set_d_d(z, rt[k].re, rt[k].im);
    mag_set_d(arb_radref(acb_realref(z)), rt[k].rad);
    mag_set_d(arb_radref(acb_imagref(z)), rt[k].rad);
    const int meets = acb_overlaps(lr, z);
    acb_clear(z);
    if (meets != (k == 1)) goto done;
  }
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < 2; j++)
      arb_set(arb_mat_entry(w->X, perm[i], j), acb_realref(acb_mat_entry(X, i, j)));
  arb_set(w->mu, acb_realref(lr));
  out = 0;
done:
  acb_mat_clear(A), acb_mat_clear(Xa), acb_mat_clear(X);
  acb_clear(lam), acb_clear(lr);
  free(perm);
  return out;
}

/* F's spectrum proven as the method needs, mu and X enclosed. */
static ss_status spectrum(tube_ws *w, long maxden, ss_psi_tube_result *r, ss_error *err) {
  const ss_limit_tube *t = w->t;
  const size_t n = w->n;
  double *F = malloc((n * n + 1) * sizeof *F), *lo = malloc((2 * n + 1) * sizeof *lo),
         *hi = malloc((2 * n + 1) * sizeof *hi);
  ss_exact *x = NULL;
  ss_status st = SS_OK;
  if (!F || !lo || !hi) {
    st = ss_error_nomem(err, "psi tube");
    goto done;
  }
  for (size_t i = 0; i < n * n; i++)
    F[i] = (double)t->Fp[i] / (double)t->Fq[i];
  ss_exact_opts o = ss_exact_defaults(2);
  o.maxden = maxden;
  o.basis = 1;
  ss_error xe = {0};
  if (ss_exact_new(F, n, n, &o, &x, &xe)) {
    snprintf(r->why, sizeof r->why, "the cross-section's matrix: %.150s", xe.msg);
    goto done;
  }
  for (size_t i = 0; i < n * n; i++) {
    long long p, q;
    if (!ss_exact_entry(x, i / n, i % n, &p, &q) || p != t->Fp[i] || q != t->Fq[i]) {
      snprintf(r->why, sizeof r->why,
               "the cross-section's entry (%zu, %zu) is not read back exactly", i / n + 1,
               i % n + 1);
      goto done;
    }
  }
  ss_verdict v;
  int cert = 0;
  ss_exact_condition(x, &v, &cert);
  size_t nr = 0;
  const ss_exact_root *rt = ss_exact_roots(x, &nr);
  if (v.verdict != SS_PASS || !cert || nr < 2 || rt[1].mult != 2 || !rt[1].real) {
    snprintf(r->why, sizeof r->why,
             "the cross-section's spectrum is not 1, mu, mu, smaller (proven): %.120s",
             v.reason);
    goto done;
  }
  r->mu = rt[1].re;
  r->ratio = nr > 2 ? hypot(rt[2].re, rt[2].im) / rt[1].re : 0.0;
  arb_set_d(w->mu, rt[1].re);
  mag_set_d(arb_radref(w->mu), rt[1].rad); /* an upper bound of rad */
  if (ss_exact_basis(x, lo, hi, &xe)) {
    snprintf(r->why, sizeof r->why, "mu's eigenvectors: %.150s", xe.msg);
    goto done;
  }
  for (size_t j = 0; j < 2; j++)
    for (size_t i = 0; i < n; i++)
      ball_of(arb_mat_entry(w->X, (slong)i, (slong)j), lo[j * n + i], hi[j * n + i]);
  const int rf = refine(w, rt, nr);
  if (rf < 0)
    st = ss_error_nomem(err, "psi tube");
  else if (rf > 0)
    snprintf(r->why, sizeof r->why, "mu's eigenvectors not enclosed at %d bits", PREC);
done:
  ss_exact_free(x);
  free(F), free(lo), free(hi);
  return st;
}

/* Three pivot rows of [1 X] (midpoints, partial pivoting). */
static int pivots(tube_ws *w) {
  const size_t n = w->n;
  double *A = malloc((3 * n + 1) * sizeof *A);
  if (!A) return -1;
  for (size_t i = 0; i < n; i++) {
    A[3 * i] = 1.0;
    for (int j = 0; j < 2; j++)
      A[3 * i + 1 + (size_t)j] =
          arf_get_d(arb_midref(arb_mat_entry(w->X, (slong)i, j)), ARF_RND_NEAR);
  }
  unsigned char *used = calloc(n + 1, 1);
  int ok = used != NULL;
  for (int j = 0; j < 3 && ok; j++) {
    size_t best = SIZE_MAX;
    for (size_t i = 0; i < n; i++)
      if (!used[i] && (best == SIZE_MAX || fabs(A[3 * i + j]) > fabs(A[3 * best + j])))
        best = i;
    ok = best != SIZE_MAX && A[3 * best + j] != 0.0;
    if (!ok) break;
    used[best] = 1;
    w->piv[j] = best;
    for (size_t i = 0; i < n; i++)
      if (!used[i]) {
        const double f = A[3 * i + j] / A[3 * best + (size_t)j];
        for (int k = j; k < 3; k++)
          A[3 * i + (size_t)k] -= f * A[3 * best + (size_t)k];
      }
  }
  free(A);
  free(used);
  return ok ? 0 : 1;
}

/* T = [1 | X | E], M = T^-1 F T: C and N (F alone).  0, 1 with why set,
 * -1 out of memory. */
static int basis_change(tube_ws *w, char *why, size_t len) {
  const ss_limit_tube *t = w->t;
  const slong n = (slong)w->n, r = (slong)w->r;
  w->eidx = malloc(((size_t)n + 1) * sizeof *w->eidx);
  if (!w->eidx) return -1;
  arb_mat_t F, FT, M;
  arb_mat_init(F, n, n), arb_mat_init(FT, n, n), arb_mat_init(M, n, n);
  int out = 1;
  slong k = 3;
  for (slong i = 0; i < n; i++) {
    const int pv =
        (size_t)i == w->piv[0] || (size_t)i == w->piv[1] || (size_t)i == w->piv[2];
    w->eidx[i] = pv ? SIZE_MAX : (size_t)(k - 3);
    arb_one(arb_mat_entry(w->T, i, 0));
    arb_set(arb_mat_entry(w->T, i, 1), arb_mat_entry(w->X, i, 0));
    arb_set(arb_mat_entry(w->T, i, 2), arb_mat_entry(w->X, i, 1));
    if (!pv) arb_one(arb_mat_entry(w->T, i, k++));
    for (slong j = 0; j < n; j++) {
      arb_set_si(arb_mat_entry(F, i, j), t->Fp[i * n + j]);
      arb_div_si(arb_mat_entry(F, i, j), arb_mat_entry(F, i, j), t->Fq[i * n + j], PREC);
    }
  }
  arb_mat_mul(FT, F, w->T, PREC);
  if (!arb_mat_solve(M, w->T, FT, PREC)) {
    snprintf(why, len, "the change of basis [1 | X | E] is not proven invertible");
    goto done;
  }
  for (slong i = 3; i < n; i++) /* the invariant columns: exactly 0 below */
    for (slong j = 0; j < 3; j++)
      if (!arb_contains_zero(arb_mat_entry(M, i, j))) {
        snprintf(why, len, "[1 | X] is not invariant under F");
        goto done;
      }
  for (slong i = 0; i < 3; i++)
    for (slong j = 0; j < r; j++)
      arb_set(arb_mat_entry(w->C, i, j), arb_mat_entry(M, i, 3 + j));
  for (slong i = 0; i < r; i++)
    for (slong j = 0; j < r; j++)
      arb_set(arb_mat_entry(w->N, i, j), arb_mat_entry(M, 3 + i, 3 + j));
  out = 0;
done:
  arb_mat_clear(F), arb_mat_clear(FT), arb_mat_clear(M);
  return out;
}

/* The points' coordinates T^-1 P = [alpha; beta], b1, bmu and the limits a,
 * b.  0, 1 with why set. */
static int coordinates(tube_ws *w, ss_psi_tube_result *res) {
  const ss_limit_tube *t = w->t;
  const slong n = (slong)w->n, r = (slong)w->r;
  arb_mat_t P, Y, I;
  arb_mat_init(P, n, 12), arb_mat_init(Y, n, 12), arb_mat_init(I, r, r);
  int out = 1;
  for (slong i = 0; i < n; i++)
    for (int l = 0; l < 4; l++)
      for (int d = 0; d < 3; d++) {
        const size_t q = 3 * ((size_t)l * w->n + (size_t)i) + (size_t)d;
        ball_of(arb_mat_entry(P, i, 3 * l + d), t->lo[q], t->hi[q]);
      }
  if (!arb_mat_solve(Y, w->T, P, PREC)) {
    snprintf(res->why, sizeof res->why,
             "the points' coordinates: T not proven invertible");
    goto done;
  }
  for (slong i = 0; i < r; i++)
    for (slong j = 0; j < 12; j++)
      arb_set(arb_mat_entry(w->beta, i, j), arb_mat_entry(Y, 3 + i, j));
  /* b1 = (I - N)^-1 beta, bmu = (mu I - N)^-1 beta */
  arb_mat_neg(I, w->N);
  for (slong i = 0; i < r; i++)
    arb_add_si(arb_mat_entry(I, i, i), arb_mat_entry(I, i, i), 1, PREC);
  int ok = arb_mat_solve(w->b1, I, w->beta, PREC);
  arb_mat_neg(I, w->N);
  for (slong i = 0; i < r; i++)
    arb_add(arb_mat_entry(I, i, i), arb_mat_entry(I, i, i), w->mu, PREC);
  ok = ok && arb_mat_solve(w->bmu, I, w->beta, PREC);
  if (!ok) {
    snprintf(res->why, sizeof res->why, "I - N or mu I - N not proven invertible");
    goto done;
  }
  /* a = alpha_1 + C_1 b1, b = alpha_mu + C_mu bmu */
  for (slong j = 0; j < 12; j++) {
    arb_set(arb_mat_entry(w->a, 0, j), arb_mat_entry(Y, 0, j));
    arb_set(arb_mat_entry(w->b, 0, j), arb_mat_entry(Y, 1, j));
    arb_set(arb_mat_entry(w->b, 1, j), arb_mat_entry(Y, 2, j));
    for (slong i = 0; i < r; i++) {
      arb_addmul(arb_mat_entry(w->a, 0, j), arb_mat_entry(w->C, 0, i),
                 arb_mat_entry(w->b1, i, j), PREC);
      for (slong e = 0; e < 2; e++)
        arb_addmul(arb_mat_entry(w->b, e, j), arb_mat_entry(w->C, 1 + e, i),
                   arb_mat_entry(w->bmu, i, j), PREC);
    }
  }
  out = 0;
done:
  arb_mat_clear(P), arb_mat_clear(Y), arb_mat_clear(I);
  return out;
}

/* Upper bounds of ||(N / mu)^m||_inf, m < NNORM, and the powers m < NTAU
 * into tau (built there in place; 0, it cannot fail).  Each power is a
 * product of two earlier ones, P_m = P_h P_(m-h) with h the largest power of
 * two below m (P_2h = P_h P_h): a chain of at most log2 m products behind
 * every P_m.  Multiplying by N / mu one step at a time instead lets the
 * balls' radii grow like rho(|N / mu|)^m, which exceeds 1 for a non-normal N
 * although rho(N / mu) < 1 (the powers near m = 75 were wider than their
 * midpoints that way).  Beyond tau only P_NTAU is a factor again (m <= 2 NTAU:
 * h = NTAU, m - h < NTAU); the others there are needed for their norms. */
static int norms(tube_ws *w, arb_mat_struct *tau) {
  _Static_assert(NNORM <= 2 * NTAU && (NTAU & (NTAU - 1)) == 0,
                 "powers beyond tau have the factor P_NTAU and one in tau");
  const slong r = (slong)w->r;
  arb_mat_t top, other; /* P_NTAU; the P_m with m > NTAU, one at a time */
  arb_mat_init(top, r, r);
  arb_mat_init(other, r, r);
  arb_mat_one(tau);
  arb_mat_scalar_div_arb(tau + 1, w->N, w->mu, PREC);
  mag_t b;
  mag_init(b);
  for (int m = 0; m < NNORM; m++) {
    arb_mat_struct *P = m < NTAU ? tau + m : m == NTAU ? top : other;
    if (m >= 2) {
      int h = 1;
      while (2 * h < m)
        h *= 2;
      arb_mat_mul(P, h < NTAU ? tau + h : top, tau + (m - h), PREC);
    }
    arb_mat_bound_inf_norm(b, P);
    w->norm[m] = mag_get_d(b);
  }
  mag_clear(b);
  arb_mat_clear(top);
  arb_mat_clear(other);
  return 0;
}

/* The period q of the tail bound: the first q with ||tau_q||_inf <= 1 (0 if
 * none in reach); *eps = max ||tau_r||_inf over r in [m0, m0 + q) (reported:
 * the matrices' bound; the tail uses the vectors', tail_product). */
static int tail_period(const tube_ws *w, int m0, double *eps) {
  int q = 0;
  for (int k = 1; k <= QMAX && !q; k++)
    if (w->norm[k] <= 1.0) q = k;
  if (!q || m0 + q > NNORM || m0 >= NTAU || q >= NTAU) return 0;
  *eps = 0.0;
  for (int m = m0; m < m0 + q; m++)
    *eps = fmax(*eps, w->norm[m]);
  return q;
}

/* Y <- a matrix holding tau_m B for every m >= m0 (w->tail_m0, period q =
 * w->tail_q with ||tau_q||_inf <= 1): m = r + k q with r in [m0, m0 + q), so
 * tau_m B = tau_q^k (tau_r B) and every column of it is bounded in |.|_inf by
 * that column's max over r of |tau_r B|_inf: column j's entries in [-e_j,
 * e_j].  tau_r B = tau_m0 (tau_(r - m0) B), both powers from w->tau (q <=
 * QMAX < NTAU), not by q steps of N / mu (whose balls would grow). */
static void tail_product(arb_mat_t Y, const arb_mat_t B, const tube_ws *w) {
  const slong r = (slong)w->r;
  arb_mat_t V, U;
  arb_mat_init(V, r, 12), arb_mat_init(U, r, 12);
  mag_t m[12], e;
  mag_init(e);
  for (int j = 0; j < 12; j++)
    mag_init(m[j]);
  for (int k = 0; k < w->tail_q; k++) {
    arb_mat_mul(U, w->tau + k, B, PREC);
    arb_mat_mul(V, w->tau + w->tail_m0, U, PREC);
    for (slong j = 0; j < 12; j++)
      for (slong i = 0; i < r; i++) {
        arb_get_mag(e, arb_mat_entry(V, i, j));
        mag_max(m[j], m[j], e);
      }
  }
  for (slong j = 0; j < 12; j++)
    for (slong i = 0; i < r; i++) {
      arb_zero(arb_mat_entry(Y, i, j));
      mag_set(arb_radref(arb_mat_entry(Y, i, j)), m[j]);
    }
  for (int j = 0; j < 12; j++)
    mag_clear(m[j]);
  mag_clear(e);
  arb_mat_clear(V), arb_mat_clear(U);
}

/* tau beta, tau bmu, tau b1: by products (tau given) or bounded (eps >= 0) */
/* Y <- a matrix holding tau_m B for every m in [m1, m2): their hull, entry by
 * entry (tau_m computed, w->tau). */
static void window_product(arb_mat_t Y, const arb_mat_t B, const tube_ws *w, int m1,
                           int m2) {
  arb_mat_mul(Y, w->tau + m1, B, PREC);
  if (m2 <= m1 + 1) return;
  arb_mat_t Z;
  arb_mat_init(Z, arb_mat_nrows(Y), arb_mat_ncols(Y));
  for (int m = m1 + 1; m < m2; m++) {
    arb_mat_mul(Z, w->tau + m, B, PREC);
    for (slong i = 0; i < arb_mat_nrows(Y); i++)
      for (slong j = 0; j < arb_mat_ncols(Y); j++)
        arb_union(arb_mat_entry(Y, i, j), arb_mat_entry(Y, i, j), arb_mat_entry(Z, i, j),
                  PREC);
  }
  arb_mat_clear(Z);
}

/* tau beta, tau bmu, tau b1: over the layers [m1, m2) (their hull), or for
 * every layer from w->tail_m0 on (eps >= 0: the tail, bounded) */
static void products(const tube_ws *w, int m1, int m2, double eps, arb_mat_t TB,
                     arb_mat_t TM, arb_mat_t T1) {
  if (eps >= 0.0) {
    tail_product(TB, w->beta, w);
    tail_product(TM, w->bmu, w);
    tail_product(T1, w->b1, w);
    return;
  }
  window_product(TB, w->beta, w, m1, m2);
  window_product(TM, w->bmu, w, m1, m2);
  window_product(T1, w->b1, w, m1, m2);
}

static void layer_nets(const tube_ws *w, int m1, int m2, double eps, const arb_t s,
                       arb_mat_t Vx, arb_mat_t Vy) {
  const slong n = (slong)w->n, r = (slong)w->r;
  arb_mat_t TB, TM, T1, cf;
  arb_mat_init(TB, r, 12), arb_mat_init(TM, r, 12), arb_mat_init(T1, r, 12);
  arb_mat_init(cf, 3, 12);
  products(w, m1, m2, eps, TB, TM, T1);
  arb_t v;
  arb_init(v);
  for (slong j = 0; j < 12; j++) {
    /* cf row 0: C_1 tau b1; rows 1, 2: b - C_mu tau bmu */
    arb_zero(arb_mat_entry(cf, 0, j));
    for (slong e = 0; e < 2; e++)
      arb_set(arb_mat_entry(cf, 1 + e, j), arb_mat_entry(w->b, e, j));
    for (slong i = 0; i < r; i++) {
      arb_addmul(arb_mat_entry(cf, 0, j), arb_mat_entry(w->C, 0, i),
                 arb_mat_entry(T1, i, j), PREC);
      for (slong e = 0; e < 2; e++)
        arb_submul(arb_mat_entry(cf, 1 + e, j), arb_mat_entry(w->C, 1 + e, i),
                   arb_mat_entry(TM, i, j), PREC);
    }
  }
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < 12; j++) {
      arb_ptr y = arb_mat_entry(Vy, i, j);
      arb_mul(y, arb_mat_entry(w->X, i, 0), arb_mat_entry(cf, 1, j), PREC);
      arb_addmul(y, arb_mat_entry(w->X, i, 1), arb_mat_entry(cf, 2, j), PREC);
      if (w->eidx[i] != SIZE_MAX)
        arb_add(y, y, arb_mat_entry(TB, (slong)w->eidx[i], j), PREC);
      arb_sub(v, y, arb_mat_entry(cf, 0, j), PREC);
      arb_mul(v, v, s, PREC);
      arb_add(arb_mat_entry(Vx, i, j), v, arb_mat_entry(w->a, 0, j), PREC);
    }
  arb_clear(v);
  arb_mat_clear(TB), arb_mat_clear(TM), arb_mat_clear(T1), arb_mat_clear(cf);
}

/* The sign of det Dψ on quadrant c of a layer with nets Vx, Vy: +1, -1, or 0
 * (folded or undecided: pr->sign says which, pr the piece's result). */
static int judge_quadrant(const tube_ws *w, int c, const arb_mat_t Vx, const arb_mat_t Vy,
                          ss_psi_piece_result *pr) {
  const ss_limit_tube *t = w->t;
  double lo[2][64][3], hi[2][64][3];
  arb_t x;
  arb_init(x);
  for (int g0 = 0; g0 < 4; g0++)
    for (int g1 = 0; g1 < 4; g1++)
      for (int l = 0; l < 4; l++) {
        int ix[3];
        ix[t->axis] = l, ix[t->across[0]] = g0, ix[t->across[1]] = g1;
        const int q = ix[0] + 4 * ix[1] + 16 * ix[2];
        for (int d = 0; d < 3; d++)
          for (int k = 0; k < 2; k++) {
            const arb_mat_struct *V = k ? Vy : Vx;
            arb_zero(x);
            for (slong j = 0; j < (slong)w->n; j++)
              arb_addmul(x, arb_mat_entry(w->G[c], g0 + 4 * g1, j),
                         arb_mat_entry(V, j, 3 * l + d), PREC);
            bounds_of(x, &lo[k][q][d], &hi[k][q][d]);
          }
      }
  arb_clear(x);
  const double(*l3[3])[3], (*h3[3])[3];
  for (int a = 0; a < 3; a++) {
    const int k = a == t->axis ? 0 : 1;
    l3[a] = (const double(*)[3])lo[k];
    h3[a] = (const double(*)[3])hi[k];
  }
  ss_psi_piece_sign_interval3(l3, h3, w->depth, pr);
  if (pr->sign == SS_JAC_UNDECIDED && w->depth < SS_PSI_MAXDEPTH) /* near a zero of the
                                                                     leading term */
    ss_psi_piece_sign_interval3(l3, h3, SS_PSI_MAXDEPTH, pr);
  return pr->sign == SS_JAC_POSITIVE ? 1 : pr->sign == SS_JAC_NEGATIVE ? -1 : 0;
}

/* A fold proven on quadrant c of the single layer m (pr FOLDED): its two
 * points and det Dψ enclosures into r in the box's parameters (ss_psi_tube.h,
 * "A fold"). */
static void keep_fold(const tube_ws *w, int m, int c, const ss_psi_piece_result *pr,
                      ss_psi_tube_result *r) {
  const ss_limit_tube *t = w->t;
  const double h = ldexp(1.0, -(m + 1));
  for (int i = 0; i < 2; i++) {
    r->where[i][t->axis] = pr->where[i][t->axis];
    for (int k = 0; k < 2; k++) {
      const int a = t->across[k];
      const double low = ((t->corner >> a) & 1u) ? 1.0 - 2.0 * h : 0.0;
      r->where[i][a] = low + h * (((t->quad[c] >> a) & 1u) + pr->where[i][a]);
    }
  }
  arb_t f, d;
  arb_init(f), arb_init(d);
  arb_pow_ui(f, w->mu, 2 * (ulong)m, PREC);
  arb_mul_2exp_si(f, f, 2 * (m + 1));
  for (int i = 0; i < 2; i++) {
    ball_of(d, pr->det[i][0], pr->det[i][1]);
    arb_mul(d, d, f, PREC);
    bounds_of(d, &r->det[i][0], &r->det[i][1]);
  }
  arb_clear(f), arb_clear(d);
  r->fold = 1;
  r->fold_layer = m;
}

/* One layer (tau or eps as layer_nets, s): the three quadrants' common strict sign, or 0
 * with why (a fold of a single layer m1 = m2 - 1 kept, keep_fold). */
static int judge_layer(const tube_ws *w, int m1, int m2, double eps, const arb_t s,
                       const char *what, ss_psi_tube_result *r) {
  arb_mat_t Vx, Vy;
  arb_mat_init(Vx, (slong)w->n, 12), arb_mat_init(Vy, (slong)w->n, 12);
  layer_nets(w, m1, m2, eps, s, Vx, Vy);
  int sign = 0;
  for (int c = 0; c < 3; c++) {
    ss_psi_piece_result pr;
    const int sc = judge_quadrant(w, c, Vx, Vy, &pr);
    if (sc == 0 || (c && sc != sign)) {
      const int fold = pr.sign == SS_JAC_FOLDED;
      snprintf(r->why, sizeof r->why, "%s, quadrant %d: %s", what, c + 1,
               fold ? "det Dpsi takes both signs (proven)"
               : sc ? "the other sign"
                    : "no sign proven");
      if (fold && eps < 0.0 && m2 == m1 + 1) keep_fold(w, m1, c, &pr, r);
      sign = 0;
      break;
    }
    sign = sc;
  }
  arb_mat_clear(Vx), arb_mat_clear(Vy);
  return sign;
}

/* The layers [m1, m2) at once (tau_m's and mu^m's hulls), halved where that
 * does not settle them, down to single layers: 1 if all have the strict sign
 * *sign (set by the first), else 0 with why. */
static int judge_window(const tube_ws *w, int m1, int m2, int *sign,
                        ss_psi_tube_result *r) {
  arb_t s, t;
  arb_init(s), arb_init(t);
  arb_pow_ui(s, w->mu, (ulong)m1, PREC);
  arb_pow_ui(t, w->mu, (ulong)(m2 - 1), PREC);
  arb_union(s, s, t, PREC);
  char what[64];
  if (m2 == m1 + 1)
    snprintf(what, sizeof what, "layer %d", m1);
  else
    snprintf(what, sizeof what, "layers %d..%d", m1, m2 - 1);
  const int sl = judge_layer(w, m1, m2, -1.0, s, what, r);
  arb_clear(s), arb_clear(t);
  if (sl && (!*sign || sl == *sign)) {
    *sign = sl;
    r->why[0] = '\0';
    return 1;
  }
  if (m2 == m1 + 1) {
    if (sl) snprintf(r->why, sizeof r->why, "layer %d has the other sign", m1);
    return 0;
  }
  const int mid = (m1 + m2) / 2;
  return judge_window(w, m1, mid, sign, r) && judge_window(w, mid, m2, sign, r);
}

/* The layers in windows [0, 1), [1, 2), [2, 4), [4, 8), [8, 16), then of 16
 * (the tail is tried after each, from its end on: a tail that fails from one
 * start may hold from another, so the starts must not grow too sparse) */
static void layers(tube_ws *w, ss_psi_tube_result *r) {
  arb_t s, st;
  arb_init(s), arb_init(st);
  int sign = 0;
  char what[64], tail_why[sizeof r->why] = "";
  for (int m = 0, width = 1; m < NTAU - 1; width = width < 16 ? 2 * width : 16) {
    const int m2 = m + width < NTAU - 1 ? m + width : NTAU - 1;
    if (!judge_window(w, m, m2, &sign, r)) goto done;
    m = m2;
    double eps = NAN;
    w->tail_q = tail_period(w, m, &eps);
    w->tail_m0 = m;
    if (!w->tail_q) continue;
    double slo, shi;
    arb_pow_ui(s, w->mu, (ulong)m, PREC);
    bounds_of(s, &slo, &shi);
    ball_of(st, 0.0, shi);
    snprintf(what, sizeof what, "the layers from %d on (tail bound %.3g)", m, eps);
    if (judge_layer(w, 0, 0, eps, st, what, r) == sign) {
      r->sign = sign;
      r->layers = m;
      r->eps = eps;
      r->why[0] = '\0';
      goto done;
    }
    memcpy(tail_why, r->why, sizeof tail_why);
    r->why[0] = '\0';
    w->tail_q = 0; /* back to the windows */
  }
  snprintf(r->why, sizeof r->why, "%.190s", tail_why[0] ? tail_why : "no tail bound");
done:
  arb_clear(s), arb_clear(st);
}

/* The cross-section of F (t's) into *out, from the cache or made (and kept
 * there if c): a spec with why set when F is not provable. */
static ss_status spec_of(const ss_limit_tube *t, long maxden, ss_psi_tube_cache *c,
                         tube_spec **out, ss_error *err) {
  const size_t n = t->ncol;
  ss_status st = SS_OK;
  for (size_t i = 0; c && i < c->n; i++) {
    tube_spec *sp = c->s[i];
    if (sp->n == n && !memcmp(sp->Fp, t->Fp, n * n * sizeof *t->Fp) &&
        !memcmp(sp->Fq, t->Fq, n * n * sizeof *t->Fq))
      return *out = sp, SS_OK;
  }
  tube_spec *sp = calloc(1, sizeof *sp);
  if (!sp) return ss_error_nomem(err, "psi tube");
  sp->n = n;
  sp->Fp = malloc((n * n + 1) * sizeof *sp->Fp);
  sp->Fq = malloc((n * n + 1) * sizeof *sp->Fq);
  sp->tau = malloc(NTAU * sizeof *sp->tau);
  ws_init(&sp->w, t);
  for (int m = 0; m < NTAU && sp->tau; m++)
    arb_mat_init(sp->tau + m, (slong)sp->w.r, (slong)sp->w.r);
  if (!sp->Fp || !sp->Fq || !sp->tau) goto nomem;
  memcpy(sp->Fp, t->Fp, n * n * sizeof *t->Fp);
  memcpy(sp->Fq, t->Fq, n * n * sizeof *t->Fq);
  ss_psi_tube_result r;
  memset(&r, 0, sizeof r);
  if ((st = spectrum(&sp->w, maxden, &r, err))) goto fail;
  int pv = r.why[0] ? 0 : pivots(&sp->w);
  if (pv > 0) snprintf(r.why, sizeof r.why, "no three independent rows of [1 | X]");
  if (!pv && !r.why[0]) pv = basis_change(&sp->w, r.why, sizeof r.why);
  if (pv < 0) goto nomem;
  if (!r.why[0] && norms(&sp->w, sp->tau)) goto nomem;
  memcpy(sp->why, r.why, sizeof sp->why);
  sp->mu = r.mu, sp->ratio = r.ratio;
  *out = sp;
  if (!c) return SS_OK;
  if (c->n == c->cap) {
    const size_t cap = c->cap ? 2 * c->cap : 8;
    tube_spec **q = realloc(c->s, cap * sizeof *q);
    if (!q) goto nomem;
    c->s = q, c->cap = cap;
  }
  c->s[c->n++] = sp;
  return SS_OK;
nomem:
  st = ss_error_nomem(err, "psi tube");
fail:
  spec_free(sp);
  *out = NULL;
  return st;
}

ss_psi_tube_cache *ss_psi_tube_cache_new(void) {
  return calloc(1, sizeof(ss_psi_tube_cache));
}

void ss_psi_tube_cache_free(ss_psi_tube_cache *c) {
  if (!c) return;
  for (size_t i = 0; i < c->n; i++)
    spec_free(c->s[i]);
  free(c->s);
  free(c);
}

ss_status ss_psi_tube_sign(const ss_limit_tube *t, long maxden, int piece_depth,
                           ss_psi_tube_cache *cache, ss_psi_tube_result *r,
                           ss_error *err) {
  memset(r, 0, sizeof *r);
  r->eps = NAN;
  if (!t || !t->lo || !t->hi)
    return ss_error_set(err, SS_EINPUT, "psi tube: no enclosure of its points");
  if (t->ncol < 4) {
    snprintf(r->why, sizeof r->why, "%zu columns across the spoke", t->ncol);
    return SS_OK;
  }
  tube_spec *sp = NULL;
  ss_status st = spec_of(t, maxden, cache, &sp, err);
  if (st) return st;
  r->mu = sp->mu, r->ratio = sp->ratio;
  if (sp->why[0]) {
    memcpy(r->why, sp->why, sizeof r->why);
    goto done;
  }
  /* the points' part in a workspace of their own, the rest shared */
  tube_ws w = sp->w;
  w.t = t;
  w.depth = piece_depth;
  w.tau = sp->tau;
  arb_mat_init(w.beta, (slong)w.r, 12), arb_mat_init(w.b1, (slong)w.r, 12);
  arb_mat_init(w.bmu, (slong)w.r, 12), arb_mat_init(w.a, 1, 12), arb_mat_init(w.b, 2, 12);
  for (int c = 0; c < 3; c++)
    gfactor(&w, c);
  if (!coordinates(&w, r)) layers(&w, r);
  arb_mat_clear(w.beta), arb_mat_clear(w.b1), arb_mat_clear(w.bmu);
  arb_mat_clear(w.a), arb_mat_clear(w.b);
  for (int c = 0; c < 3; c++)
    arb_mat_clear(w.G[c]);
done:
  if (!cache) spec_free(sp);
  return st;
}
