/* ss_schur_tie.c — a root's invariant subspace enclosed (Rump's method), the
 * character norm of the symmetry group on it (Schur's lemma), and the basis
 * completed over the outer rows (method: ss_schur.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_ball.h"
#include "ss_schur_impl.h"

static double mid(const arb_t x) {
  return arf_get_d(arb_midref(x), ARF_RND_NEAR);
}

int ss_schur_subspace(ss_schur *s, size_t r, char *why, size_t len) {
  sc_root *o = s->rt + r;
  if (!o->has_xc) {
    snprintf(why, len, "%s", "its invariant subspace not enclosed (Rump's method)");
    return 1;
  }
  if (o->has_x) return 0;
  const slong n1 = acb_mat_nrows(&o->Xc), c = acb_mat_ncols(&o->Xc);
  arb_mat_init(&o->X, n1, c);
  o->has_x = 1;
  for (slong i = 0; i < n1; i++)
    for (slong j = 0; j < c; j++)
      arb_set(arb_mat_entry(&o->X, i, j), acb_realref(acb_mat_entry(&o->Xc, i, j)));
  return 0;
}

/* c pivot rows I of X (partial pivoting on the midpoints). */
static void pivots(const arb_mat_t X, slong *I) {
  const slong n = arb_mat_nrows(X), c = arb_mat_ncols(X);
  double *W = malloc(((size_t)(n * c) + 1) * sizeof *W);
  unsigned char *used = calloc((size_t)n + 1, 1);
  for (slong i = 0; W && i < n; i++)
    for (slong j = 0; j < c; j++)
      W[i * c + j] = mid(arb_mat_entry(X, i, j));
  for (slong k = 0; k < c; k++) {
    slong p = k < n ? k : 0;
    double best = -1.0;
    for (slong i = 0; W && used && i < n; i++)
      if (!used[i] && fabs(W[i * c + k]) > best) best = fabs(W[i * c + k]), p = i;
    I[k] = p;
    if (!W || !used) continue;
    used[p] = 1;
    for (slong i = 0; i < n; i++) /* eliminate column k with row p */
      if (!used[i] && W[p * c + k] != 0.0) {
        const double f = W[i * c + k] / W[p * c + k];
        for (slong j = k; j < c; j++)
          W[i * c + j] -= f * W[p * c + j];
      }
  }
  free(W);
  free(used);
}

/* M = X_I^-1 X_(g(I)) for element g; 1 when some row of P_g X = X M is not
 * met (g does not map the enclosure of V to itself). */
static int rep_matrix(const arb_mat_t X, const arb_mat_t XIi, const slong *I,
                      const size_t *g, arb_mat_t Y, arb_mat_t M, arb_mat_t row,
                      arb_mat_t prod) {
  const slong n1 = arb_mat_nrows(X), c = arb_mat_ncols(X);
  for (slong a = 0; a < c; a++)
    for (slong b = 0; b < c; b++)
      arb_set(arb_mat_entry(Y, a, b), arb_mat_entry(X, (slong)g[I[a]], b));
  arb_mat_mul(M, XIi, Y, SC_PREC);
  for (slong i = 0; i < n1; i++) { /* row g(i) of X against row i of X M */
    for (slong b = 0; b < c; b++)
      arb_set(arb_mat_entry(row, 0, b), arb_mat_entry(X, i, b));
    arb_mat_mul(prod, row, M, SC_PREC);
    for (slong b = 0; b < c; b++)
      if (!arb_overlaps(arb_mat_entry(prod, 0, b), arb_mat_entry(X, (slong)g[i], b)))
        return 1;
  }
  return 0;
}

/* Whether x is proven in (k - 0.5, k + 0.5). */
static int near_int(const arb_t x, int k) {
  arb_t h;
  arb_init(h);
  arb_set_d(h, k - 0.5);
  int in = arb_gt(x, h);
  arb_set_d(h, k + 0.5);
  in = in && arb_lt(x, h);
  arb_clear(h);
  return in;
}

int ss_schur_character(ss_schur *s, size_t r, const size_t *group, size_t ng, char *why,
                       size_t len) {
  sc_root *o = s->rt + r;
  const arb_mat_struct *X = &o->X;
  const slong c = arb_mat_ncols(X);
  slong I[8];
  if (c > 8) {
    snprintf(why, len, "a cluster of %ld, more than 8", (long)c);
    return 1;
  }
  pivots(X, I);
  arb_mat_t XI, XIi, Y, M, row, prod;
  arb_t acc, chi, ind;
  arb_mat_init(XI, c, c);
  arb_mat_init(XIi, c, c);
  arb_mat_init(Y, c, c);
  arb_mat_init(M, c, c);
  arb_mat_init(row, 1, c);
  arb_mat_init(prod, 1, c);
  arb_init(acc);
  arb_init(chi);
  arb_init(ind);
  int rc = 0;
  for (slong a = 0; a < c; a++)
    for (slong b = 0; b < c; b++)
      arb_set(arb_mat_entry(XI, a, b), arb_mat_entry(X, I[a], b));
  if (!arb_mat_inv(XIi, XI, SC_PREC)) {
    snprintf(why, len, "%s", "no minor of its basis proven invertible");
    rc = 1;
  }
  for (size_t g = 0; g < ng && !rc; g++) {
    if (rep_matrix(X, XIi, I, group + g * s->n, Y, M, row, prod)) {
      snprintf(why, len,
               "symmetry %zu does not map the enclosed invariant subspace to itself", g);
      rc = 1;
    }
    arb_mat_trace(chi, M, SC_PREC);
    arb_addmul(acc, chi, chi, SC_PREC);
    arb_mat_sqr(Y, M, SC_PREC); /* M_(g^2) = M_g^2: chi(g^2) */
    arb_mat_trace(chi, Y, SC_PREC);
    arb_add(ind, ind, chi, SC_PREC);
  }
  if (!rc) {
    arb_div_ui(acc, acc, (ulong)ng, SC_PREC);
    arb_div_ui(ind, ind, (ulong)ng, SC_PREC);
    ss_ball_doubles(acc, &o->nlo, &o->nhi);
    o->scalar = near_int(acc, 1); /* <chi, chi> = 1: irreducible */
    for (int k = 2; k <= 3; k++)  /* sum m_i^2 = k <= 3: every m_i = 1 */
      if (near_int(acc, k) && near_int(ind, k)) o->split = k;
  }
  arb_mat_clear(XI);
  arb_mat_clear(XIi);
  arb_mat_clear(Y);
  arb_mat_clear(M);
  arb_mat_clear(row);
  arb_mat_clear(prod);
  arb_clear(acc);
  arb_clear(chi);
  arb_clear(ind);
  return rc;
}

/* Column block col0.. of the basis from root r: X on the one-ring, then
 * (lambda - C_cc) Y_c = B_c X + sum of C's earlier components' Y, component
 * by component, into Z (n x cols of the root, arb).  0, or 1 when a solve
 * fails. */
static int complete_root(const ss_schur *s, const double *S, size_t r, arb_mat_t Z) {
  const size_t n1 = s->n1;
  const sc_root *o = s->rt + r;
  const slong c = o->count;
  arb_t w;
  arb_init(w);
  for (size_t i = 0; i < n1; i++)
    for (slong j = 0; j < c; j++)
      arb_set(arb_mat_entry(Z, (slong)i, j), arb_mat_entry(&o->X, (slong)i, j));
  int rc = 0;
  for (long k = 0; k < s->scc.n && !rc; k++) {
    const size_t *nodes = s->scc.comp + s->scc.start[k];
    const slong b = (slong)(s->scc.start[k + 1] - s->scc.start[k]);
    arb_mat_t D, R, Y;
    arb_mat_init(D, b, b);
    arb_mat_init(R, b, c);
    arb_mat_init(Y, b, c);
    for (slong x = 0; x < b; x++) {
      const size_t row = n1 + nodes[x];
      for (size_t e = s->csr.ptr[row]; e < s->csr.ptr[row + 1]; e++) {
        const size_t col = s->csr.col[e];
        if (col >= n1 && s->scc.cid[col - n1] == (size_t)k) { /* the block */
          ss_ball_entry(w, S[row * s->n + col]);
          arb_neg(arb_mat_entry(D, x, (slong)s->scc.pos[col - n1]), w);
          continue;
        }
        if (col >= n1 && s->scc.cid[col - n1] > (size_t)k) rc = 1; /* not triangular */
        ss_ball_entry(w, S[row * s->n + col]); /* read: one-ring or earlier */
        for (slong j = 0; j < c; j++)
          arb_addmul(arb_mat_entry(R, x, j), w, arb_mat_entry(Z, (slong)col, j), SC_PREC);
      }
      arb_add(arb_mat_entry(D, x, x), arb_mat_entry(D, x, x), acb_realref(&o->ball.z),
              SC_PREC);
    }
    rc = rc || !arb_mat_solve(Y, D, R, SC_PREC);
    for (slong x = 0; x < b && !rc; x++)
      for (slong j = 0; j < c; j++)
        arb_set(arb_mat_entry(Z, (slong)(n1 + nodes[x]), j), arb_mat_entry(Y, x, j));
    arb_mat_clear(D);
    arb_mat_clear(R);
    arb_mat_clear(Y);
  }
  arb_clear(w);
  return rc;
}

int ss_schur_complete(ss_schur *s, const double *S, char *why, size_t len) {
  const size_t n = s->n;
  s->out.lo = malloc(((size_t)s->m * n + 1) * sizeof *s->out.lo);
  s->out.hi = malloc(((size_t)s->m * n + 1) * sizeof *s->out.hi);
  if (!s->out.lo || !s->out.hi) return -1;
  int rc = 0;
  size_t col = 0;
  for (int j = 0; j < s->nlead && !rc; j++) {
    const size_t r = s->lead[j];
    const slong c = s->rt[r].count;
    arb_mat_t Z;
    arb_mat_init(Z, (slong)n, c);
    rc = complete_root(s, S, r, Z);
    for (slong q = 0; q < c && !rc; q++, col++)
      for (size_t i = 0; i < n && !rc; i++) {
        double *lo = s->out.lo + col * n + i, *hi = s->out.hi + col * n + i;
        ss_ball_doubles(arb_mat_entry(Z, (slong)i, q), lo, hi);
        rc = !(isfinite(*lo) && isfinite(*hi));
      }
    arb_mat_clear(Z);
  }
  if (rc) {
    free(s->out.lo);
    free(s->out.hi);
    s->out.lo = s->out.hi = NULL;
    snprintf(
        why, len, "%s",
        "the eigenvectors' outer rows not enclosed ((lambda - C) singular in balls)");
  }
  return rc;
}
