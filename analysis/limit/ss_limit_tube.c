/* ss_limit_tube.c — the exact layered structure of a box left uncovered
 * round an extraordinary edge (ss_limit_tube.h). */
#include "ss_limit_tube.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "double_interval.h"
#include "ss_limit_impl.h"

/* exact products of two 64-bit integers (GCC and Clang) */
__extension__ typedef __int128 i128;

/* a rational p / q, q > 0 */
typedef struct {
  long long p, q;
} rat_t;

/* The rational of weight w (0 -> 0/1): 0, or -1 if rat does not know it. */
static int read_w(double w, ss_limit_rational_fn rat, void *arg, rat_t *r) {
  if (w == 0.0) {
    *r = (rat_t){0, 1};
    return 0;
  }
  if (rat(w, arg, &r->p, &r->q) || r->q <= 0) return -1;
  return 0;
}

/* x / (a / 8), a in 1..8 (A_b's entries times 8), in lowest terms: 0, or -1
 * if it does not fit in 64 bits. */
static int div_a(rat_t x, long long a8, rat_t *out) {
  i128 p = (i128)x.p * 8, q = (i128)x.q * a8, u = p < 0 ? -p : p, v = q;
  while (v) {
    const i128 t = u % v;
    u = v;
    v = t;
  }
  if (u == 0) u = 1;
  p /= u;
  q /= u;
  if (p > INT64_MAX || p < -INT64_MAX || q > INT64_MAX) return -1;
  *out = (rat_t){(long long)p, (long long)q};
  return 0;
}

/* Whether x == (a / 8) y exactly. */
static int eq_scaled(rat_t x, long long a8, long long yp, long long yq) {
  return (i128)x.p * 8 * yq == (i128)a8 * yp * x.q;
}

/* What the build owns; the public view is t. */
struct ss_lim_tube {
  ss_limit_tube t;
  double *P, *lo, *hi;
  long long *Fp, *Fq, *Gp[3], *Gq[3];
  ss_lim_tensor T; /* layers and columns of the box's patch */
};

void ss_lim_tube_free(ss_lim_tube *u) {
  if (!u) return;
  free(u->P), free(u->lo), free(u->hi), free(u->Fp), free(u->Fq);
  for (int c = 0; c < 3; c++)
    free(u->Gp[c]), free(u->Gq[c]);
  free(u->T.layer), free(u->T.col), free(u->T.colpt);
  free(u);
}

const ss_limit_tube *ss_lim_tube_view(const ss_lim_tube *u) {
  return u ? &u->t : NULL;
}

/* The 8 children of the box: their patches (inherited frame) and rows. */
typedef struct {
  ss_lim_patch ch[8];
  double *W[8];
  int made[8];
} kids;

static void kids_free(kids *k) {
  for (int i = 0; i < 8; i++) {
    if (k->made[i]) ss_lim_patch_free(&k->ch[i]);
    free(k->W[i]);
  }
}

/* The 8 children; *framed 0 if one comes in a frame other than the box's
 * (not expected: then no tube). */
static ss_status kids_make(const ss_scheme *s, const ss_cx *pcx, kids *k, int *framed,
                           ss_error *err) {
  memset(k, 0, sizeof *k);
  *framed = 1;
  ss_lim_refined r; /* refined once for the 8 */
  ss_status st = ss_lim_refine(s, pcx, 1, &r, err);
  for (int i = 0; i < 8 && *framed && !st; i++) {
    ss_lim_frame g;
    ss_cx *ccx = NULL;
    st = ss_lim_cut(&r, i, 0, &k->ch[i], &g, &ccx, &k->W[i], err);
    ss_cx_free(ccx);
    if (st) break;
    k->made[i] = 1;
    *framed = ss_lim_frame_is_id(&g);
  }
  ss_lim_refined_free(&r);
  return st;
}

/* Rows W (nc x K) factor exactly as A_b (x) X: child point u in layer lu[u]
 * (A_b's row) and cross row ru[u]; X (nr x ncol) read from the rows of layer
 * 1 when first is set, else checked against. */
static int factor_rows(const double *W, size_t nc, const int *lu, const size_t *ru,
                       const ss_lim_tensor *T, int b, int first, long long *Xp,
                       long long *Xq, ss_limit_rational_fn rat, void *arg) {
  const size_t n = T->ncol, K = 4 * n;
  const long long a11 = (long long)(8.0 * ss_lim_bspline_half[b][1][1]);
  if (first) {
    for (size_t u = 0; u < nc; u++) {
      if (lu[u] != 1) continue;
      for (size_t q = 0; q < n; q++) {
        rat_t w, x;
        if (read_w(W[u * K + T->colpt[q][1]], rat, arg, &w) || div_a(w, a11, &x))
          return 0;
        Xp[ru[u] * n + q] = x.p;
        Xq[ru[u] * n + q] = x.q;
      }
    }
  }
  for (size_t u = 0; u < nc; u++)
    for (size_t w = 0; w < K; w++) {
      rat_t x;
      if (read_w(W[u * K + w], rat, arg, &x)) return 0;
      const long long a = (long long)(8.0 * ss_lim_bspline_half[b][lu[u]][T->layer[w]]);
      const size_t i = ru[u] * n + T->col[w];
      if (!eq_scaled(x, a, Xp[i], Xq[i])) return 0;
    }
  return 1;
}

/* The runs: the two children at the corner are the box again; both factor
 * with one F. */
static int runs_factor(ss_lim_tube *u, const ss_lim_patch *p, const kids *k,
                       ss_limit_rational_fn rat, void *arg) {
  const ss_lim_tensor *T = &u->T;
  int ok = 1;
  for (int b = 0; b < 2 && ok; b++) {
    const int kk = ss_cube_corner_index(3, u->t.corner | ((unsigned)b << u->t.axis));
    ok = factor_rows(k->W[kk], p->nv, T->layer, T->col, T, b, b == 0, u->Fp, u->Fq, rat,
                     arg);
  }
  return ok;
}

/* Quadrant c's two children: regular, their nets factoring with one G_c. */
static int quad_factor(ss_lim_tube *u, int c, const kids *k, ss_limit_rational_fn rat,
                       void *arg) {
  const int ax = u->t.axis, o0 = u->t.across[0], o1 = u->t.across[1];
  for (int b = 0; b < 2; b++) {
    const int kk = ss_cube_corner_index(3, u->t.quad[c] | ((unsigned)b << ax));
    const ss_lim_patch *cp = &k->ch[kk];
    if (!cp->regular || cp->nv != 64) return 0;
    int lu[64];
    size_t ru[64];
    for (int g = 0; g < 64; g++) {
      const int ix[3] = {g % 4, (g / 4) % 4, g / 16};
      lu[cp->net[g]] = ix[ax];
      ru[cp->net[g]] = (size_t)(ix[o0] + 4 * ix[o1]);
    }
    if (!factor_rows(k->W[kk], 64, lu, ru, &u->T, b, b == 0, u->Gp[c], u->Gq[c], rat,
                     arg))
      return 0;
  }
  return 1;
}

/* The edge's axis and corner: exactly two children are the box again, and
 * they differ in one bit.  0 if not. */
static int find_axis(const ss_lim_patch *p, const kids *k, ss_limit_tube *t) {
  int runs[8], n = 0;
  for (int i = 0; i < 8; i++)
    if (ss_lim_patch_same(p, &k->ch[i])) runs[n++] = i;
  if (n != 2) return 0;
  const unsigned d = ss_cube_corner_bits(3, runs[0]) ^ ss_cube_corner_bits(3, runs[1]);
  int a = -1;
  for (int x = 0; x < 3; x++)
    if (d == (1u << x)) a = x;
  if (a < 0) return 0;
  t->axis = a;
  t->across[0] = a == 0 ? 1 : 0;
  t->across[1] = a == 2 ? 1 : 2;
  t->corner = ss_cube_corner_bits(3, runs[0]) & ~(1u << a);
  int c = 0;
  for (unsigned q = 0; q < 8; q++)
    if (!((q >> a) & 1u) && q != t->corner) t->quad[c++] = q;
  return 1;
}

static ss_status alloc_all(ss_lim_tube *u, size_t K, int enc, ss_error *err) {
  u->T.layer = malloc((K + 1) * sizeof *u->T.layer);
  u->T.col = malloc((K + 1) * sizeof *u->T.col);
  u->T.colpt = malloc((K + 1) * sizeof *u->T.colpt);
  u->P = malloc((3 * K + 1) * sizeof *u->P);
  u->Fp = malloc((K * K + 1) * sizeof *u->Fp);
  u->Fq = malloc((K * K + 1) * sizeof *u->Fq);
  int ok = u->T.layer && u->T.col && u->T.colpt && u->P && u->Fp && u->Fq;
  for (int c = 0; c < 3; c++) {
    u->Gp[c] = malloc((16 * K + 1) * sizeof *u->Gp[c]);
    u->Gq[c] = malloc((16 * K + 1) * sizeof *u->Gq[c]);
    ok = ok && u->Gp[c] && u->Gq[c];
  }
  if (enc) {
    u->lo = malloc((3 * K + 1) * sizeof *u->lo);
    u->hi = malloc((3 * K + 1) * sizeof *u->hi);
    ok = ok && u->lo && u->hi;
  }
  return ok ? SS_OK : ss_error_nomem(err, "limit tube");
}

/* The points by (layer, column), translated by -x0 (any common vector: no derivative
 * changes); the enclosure outward. */
static void points(ss_lim_tube *u, const ss_cx *pcx, const double *elo, const double *ehi,
                   const double x0[3]) {
  const size_t n = u->T.ncol;
  for (size_t l = 0; l < 4; l++)
    for (size_t c = 0; c < n; c++) {
      const size_t v = u->T.colpt[c][l], r = l * n + c;
      for (int d = 0; d < 3; d++) {
        u->P[3 * r + (size_t)d] = pcx->x[3 * v + (size_t)d] - x0[d];
        if (!elo) continue;
        const di_t y = di_fast_sub_d(
            di_interval(elo[3 * v + (size_t)d], ehi[3 * v + (size_t)d]), x0[d]);
        u->lo[3 * r + (size_t)d] = y.a;
        u->hi[3 * r + (size_t)d] = y.b;
      }
    }
}

ss_status ss_lim_tube_build(const ss_scheme *s, const ss_lim_patch *p, const ss_cx *pcx,
                            const double *elo, const double *ehi, const double x0[3],
                            ss_limit_rational_fn rat, void *arg, ss_lim_tube **out,
                            ss_error *err) {
  *out = NULL;
  kids k;
  int framed = 0;
  ss_status st = kids_make(s, pcx, &k, &framed, err);
  ss_lim_tube *u = NULL;
  size_t *uf = NULL;
  if (st || !framed) goto done;
  u = calloc(1, sizeof *u);
  if (!u) {
    st = ss_error_nomem(err, "limit tube");
    goto done;
  }
  const size_t K = p->nv;
  uf = malloc((K + 1) * sizeof *uf);
  if (!uf || (st = alloc_all(u, K, elo != NULL, err))) {
    if (!st) st = ss_error_nomem(err, "limit tube");
    goto done;
  }
  int ok = find_axis(p, &k, &u->t);
  u->T.axis = u->t.axis;
  ok = ok && ss_lim_tensor_columns(p, &u->T, uf);
  ok = ok && runs_factor(u, p, &k, rat, arg);
  for (int c = 0; c < 3 && ok; c++)
    ok = quad_factor(u, c, &k, rat, arg);
  if (st || !ok) goto done;
  points(u, pcx, elo, ehi, x0);
  u->t.ncol = u->T.ncol;
  u->t.P = u->P;
  u->t.lo = u->lo;
  u->t.hi = u->hi;
  u->t.Fp = u->Fp;
  u->t.Fq = u->Fq;
  for (int c = 0; c < 3; c++)
    u->t.Gp[c] = u->Gp[c], u->t.Gq[c] = u->Gq[c];
  *out = u;
  u = NULL;
done:
  free(uf);
  ss_lim_tube_free(u);
  kids_free(&k);
  return st;
}
