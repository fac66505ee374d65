/* ss_psi_inject.c — psi's winding number on the boundary of the star, and
 * with it injectivity (method and theorem: ss_psi_inject.h). */
#include "ss_psi_inject.h"

#include <arb.h>
#include <math.h>
#include <flint/fmpq.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cx.h"
#include "ss_limit.h"

#define PREC 128 /* bits of the balls (inputs are exact doubles) */

/* A square of the boundary grid: its corners' names, outward
 * counter-clockwise, and the direction proven positive on its box's hull. */
typedef struct {
  ss_star_coord key[4];
  size_t vi[4]; /* the corners' indices into the vertex table (phase 2) */
  double d[3];
} square;

/* A value offered for a boundary vertex; the one of highest priority (then
 * the first) is the vertex of T. */
typedef struct {
  ss_star_coord key;
  double v[3];
  int prio; /* 1: psi in doubles from a piece; 0: a tube patch's mean */
  size_t seq;
} offer;

/* A box of the traversal touching the boundary, kept (the grid is built
 * once every box is known, at the finest level it needs). */
typedef struct {
  size_t cell;    /* the cell round p */
  unsigned pbits; /* p's corner in it */
  int depth;      /* the box: side 2^-depth, corner origin */
  double origin[3];
  double shift[3]; /* true point = shift + translated point */
  int tube;        /* 1: a tube's box (its patch), 0: a piece (its net) */
  size_t n;        /* points: 64 or the patch's 4 ncol */
  double *lo, *hi; /* n x 3: their enclosures (translated) */
  double *net;     /* a piece: its 64 double points (translated); else NULL */
  /* a tube's box: its layered structure (ss_limit_tube.h) */
  int axis, across[2]; /* the edge's axis, the two others */
  unsigned corner;     /* the box corner the edge runs through */
  unsigned quad[3];    /* the other quadrants' corner bits across */
  size_t ncol;         /* columns */
  double *w;           /* enclosures of F (ncol^2) then G_0..G_2 (16 ncol
                          each): lo, hi pairs, row-major */
} bbox;

struct ss_psi_inject {
  const ss_local *M;
  int N;    /* the box depth: boxes have side 2^-N at most deep */
  int G;    /* the grid being built: side 2^-G, G >= N */
  bbox *bx; /* the boundary's boxes */
  size_t nbx, capbx;
  square *sq; /* the squares */
  size_t nsq, capsq;
  offer *of; /* the vertex offers */
  size_t nof, capof;
  int stop; /* 1 once the boundary cannot be decided (why) */
  char why[200];
};

ss_psi_inject *ss_psi_inject_new(const ss_local *M, int depth) {
  if (!M || depth < 1 || depth > 8) return NULL;
  ss_psi_inject *b = calloc(1, sizeof *b);
  if (!b) return NULL;
  b->M = M;
  b->N = depth;
  return b;
}

void ss_psi_inject_free(ss_psi_inject *b) {
  if (!b) return;
  for (size_t i = 0; i < b->nbx; i++) {
    free(b->bx[i].lo);
    free(b->bx[i].hi);
    free(b->bx[i].net);
    free(b->bx[i].w);
  }
  free(b->bx);
  free(b->sq);
  free(b->of);
  free(b);
}

static void stop(ss_psi_inject *b, const char *why) {
  if (b->stop) return;
  b->stop = 1;
  snprintf(b->why, sizeof b->why, "%s", why);
}

/* --- exact names of grid points ---------------------------------------- */

/* The corner slot of cell corner bits `bits`. */
static int slot_of(unsigned bits) {
  for (int j = 0; j < 8; j++)
    if (ss_cube_corner_bits(3, j) == bits) return j;
  return -1;
}

/* Sparse vector a*x + c*y (coefficients int64) into a dense list over the
 * union of indices: idx[n], val[n]. */
typedef struct {
  int n;
  int32_t idx[16];
  int64_t val[16];
} acc;

static void acc_add(acc *a, const ss_star_coord *x, int64_t c) {
  for (int i = 0; i < x->n; i++) {
    int k = 0;
    while (k < a->n && a->idx[k] != x->idx[i])
      k++;
    if (k == a->n) {
      a->idx[k] = x->idx[i];
      a->val[k] = 0;
      a->n++;
    }
    a->val[k] += c * (int64_t)x->val[i];
  }
}

/* The accumulated vector as a canonical coordinate; 0 if it does not fit. */
static int acc_coord(const acc *a, ss_star_coord *out) {
  int32_t idx[16], val[16];
  int m = 0;
  for (int i = 0; i < a->n; i++) {
    if (a->val[i] == 0) continue;
    if (a->val[i] > INT32_MAX || a->val[i] < -INT32_MAX || m == SS_STAR_MAXSUPP) return 0;
    idx[m] = a->idx[i];
    val[m++] = (int32_t)a->val[i];
  }
  for (int i = 1; i < m; i++) /* ascending indices */
    for (int j = i; j > 0 && idx[j - 1] > idx[j]; j--) {
      const int32_t ti = idx[j], tv = val[j];
      idx[j] = idx[j - 1], val[j] = val[j - 1];
      idx[j - 1] = ti, val[j - 1] = tv;
    }
  *out = ss_star_coord_make(m, idx, val);
  return 1;
}

/* The cell's corner coordinates c[8] (by slot); 0 unless the cell is the
 * affine image c000 + sum_i bit_i (c_ei - c000) of the cube. */
static int cell_corners(const ss_local *M, size_t cell, const ss_star_coord **c) {
  for (int j = 0; j < 8; j++) {
    const size_t q = M->corner[cell * SS_MAXCELLVERTS + (size_t)j];
    if (q == SIZE_MAX || q >= M->n2) return 0;
    c[j] = &M->label[q];
  }
  const int s0 = slot_of(0);
  for (int j = 0; j < 8; j++) {
    const unsigned bits = ss_cube_corner_bits(3, j);
    acc a = {0};
    acc_add(&a, c[j], 1);
    acc_add(&a, c[s0], -1);
    for (int i = 0; i < 3; i++)
      if (bits & (1u << i)) {
        acc_add(&a, c[slot_of(1u << i)], -1);
        acc_add(&a, c[s0], 1);
      }
    for (int i = 0; i < a.n; i++)
      if (a.val[i]) return 0;
  }
  return 1;
}

/* The name of grid point g (units 2^-N of the cell's parameters). */
static int grid_name(const ss_star_coord *const *c, int N, const int64_t g[3],
                     ss_star_coord *out) {
  const int s0 = slot_of(0);
  acc a = {0};
  acc_add(&a, c[s0], (int64_t)1 << N);
  for (int i = 0; i < 3; i++) {
    acc_add(&a, c[slot_of(1u << i)], g[i]);
    acc_add(&a, c[s0], -g[i]);
  }
  return acc_coord(&a, out);
}

/* --- phase 1: the boxes ------------------------------------------------ */

/* Whether every x in [lo, hi] + shift (n points) has d.x > 0, in balls. */
static int positive_on(const double *lo, const double *hi, size_t n,
                       const double shift[3], const double d[3]) {
  arb_t s, x, t;
  arf_t a, c;
  arb_init(s), arb_init(x), arb_init(t);
  arf_init(a), arf_init(c);
  int ok = 1;
  for (size_t i = 0; i < n && ok; i++) {
    arb_zero(s);
    for (int k = 0; k < 3; k++) {
      arf_set_d(a, lo[3 * i + (size_t)k]);
      arf_set_d(c, hi[3 * i + (size_t)k]);
      arb_set_interval_arf(x, a, c, PREC);
      arb_set_d(t, shift[k]);
      arb_add(x, x, t, PREC);
      arb_set_d(t, d[k]);
      arb_addmul(s, x, t, PREC);
    }
    ok = arb_is_positive(s);
  }
  arb_clear(s), arb_clear(x), arb_clear(t);
  arf_clear(a), arf_clear(c);
  return ok;
}

/* Whether the exact rationals p / q (n of them, rows of ncol) are
 * nonnegative with rows summing to 1. */
static int stochastic(const long long *p, const long long *q, size_t rows, size_t ncol) {
  fmpq_t s, t;
  fmpq_init(s), fmpq_init(t);
  int ok = 1;
  for (size_t i = 0; i < rows && ok; i++) {
    fmpq_zero(s);
    for (size_t j = 0; j < ncol && ok; j++) {
      const size_t k = i * ncol + j;
      if (p[k] < 0 || q[k] <= 0) ok = 0;
      fmpq_set_si(t, (slong)p[k], (ulong)q[k]);
      fmpq_add(s, s, t);
    }
    ok = ok && fmpq_is_one(s);
  }
  fmpq_clear(s), fmpq_clear(t);
  return ok;
}

static int grow(void **p, size_t *cap, size_t need, size_t size) {
  if (need <= *cap) return 1;
  size_t c = *cap ? 2 * *cap : 256;
  while (c < need)
    c *= 2;
  void *q = realloc(*p, c * size);
  if (!q) return 0;
  *p = q;
  *cap = c;
  return 1;
}

/* Cubic B-spline halves: the control points of [0, 1/2] (b = 0) and [1/2, 1]
 * (b = 1) from those of [0, 1], in eighths (nonnegative, rows summing to 8). */
static const int HALF[2][4][4] = {
    {{4, 4, 0, 0}, {1, 6, 1, 0}, {0, 4, 4, 0}, {0, 1, 6, 1}},
    {{1, 6, 1, 0}, {0, 4, 4, 0}, {0, 1, 6, 1}, {0, 0, 4, 4}}};

/* One half step along axis a of an enclosed 64-point net (lo, hi, in place):
 * nonnegative weights, so bounds map to bounds; each sum of at most three
 * exact products is widened by 4e-16 of its magnitude (> gamma_3) and
 * 1e-300, which holds the rounding. */
static void half_along(double *lo, double *hi, int a, int b) {
  const int st = a == 0 ? 1 : a == 1 ? 4 : 16;
  for (int q0 = 0; q0 < 64; q0++) {
    if ((q0 / st) % 4) continue; /* the first point of each line along a */
    double l[4][3], h[4][3];
    for (int i = 0; i < 4; i++)
      for (int k = 0; k < 3; k++) {
        l[i][k] = lo[3 * (q0 + i * st) + k];
        h[i][k] = hi[3 * (q0 + i * st) + k];
      }
    for (int i = 0; i < 4; i++)
      for (int k = 0; k < 3; k++) {
        double sl = 0.0, sh = 0.0, ml = 0.0, mh = 0.0;
        for (int j = 0; j < 4; j++) {
          const double w = HALF[b][i][j] / 8.0;
          sl += w * l[j][k], sh += w * h[j][k];
          ml += fabs(w * l[j][k]), mh += fabs(w * h[j][k]);
        }
        lo[3 * (q0 + i * st) + k] = sl - 4e-16 * ml - 1e-300;
        hi[3 * (q0 + i * st) + k] = sh + 4e-16 * mh + 1e-300;
      }
  }
}

/* The enclosed net of the sub-box of the piece at `levels` deeper, index
 * idx (per axis, 0 .. 2^levels - 1), into lo, hi (64 x 3). */
static void refine64(double *lo, double *hi, int levels, const int64_t idx[3]) {
  for (int l = levels - 1; l >= 0; l--)
    for (int a = 0; a < 3; a++)
      half_along(lo, hi, a, (int)((idx[a] >> l) & 1));
}

static void subnet(const bbox *x, int levels, const int64_t idx[3], double *lo,
                   double *hi) {
  memcpy(lo, x->lo, 64 * 3 * sizeof *lo);
  memcpy(hi, x->hi, 64 * 3 * sizeof *hi);
  refine64(lo, hi, levels, idx);
}

/* A direction d with d.x > 0 on the enclosed points (true positions), found
 * on their midpoints by the perceptron (start: the sum of their unit
 * vectors; while the worst point's cosine is below 1e-3, add its unit
 * vector: finite if a margin exists), then proven on the enclosures (arb).
 * 0 if none is proven. */
static int hull_direction(const double *lo, const double *hi, size_t n,
                          const double shift[3], double d[3]) {
  d[0] = d[1] = d[2] = 0.0;
  for (size_t i = 0; i < n; i++) {
    double x[3], r = 0.0;
    for (int k = 0; k < 3; k++) {
      x[k] = 0.5 * lo[3 * i + (size_t)k] + 0.5 * hi[3 * i + (size_t)k] + shift[k];
      r += x[k] * x[k];
    }
    r = sqrt(r);
    for (int k = 0; k < 3 && r > 0.0; k++)
      d[k] += x[k] / r;
  }
  for (int it = 0; it < 2000; it++) {
    double worst = INFINITY, u[3] = {0.0, 0.0, 0.0};
    const double dn = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (size_t i = 0; i < n; i++) {
      double x[3], r = 0.0, c = 0.0;
      for (int k = 0; k < 3; k++) {
        x[k] = 0.5 * lo[3 * i + (size_t)k] + 0.5 * hi[3 * i + (size_t)k] + shift[k];
        r += x[k] * x[k];
        c += x[k] * d[k];
      }
      r = sqrt(r);
      if (r == 0.0 || dn == 0.0) return 0;
      if (c / (r * dn) < worst) {
        worst = c / (r * dn);
        for (int k = 0; k < 3; k++)
          u[k] = x[k] / r;
      }
    }
    if (worst > 1e-3) break;
    for (int k = 0; k < 3; k++)
      d[k] = d[k] / dn + u[k];
  }
  return positive_on(lo, hi, n, shift, d);
}

/* An enclosure [lo, hi] of the rational p / q >= 0 (q > 0): the division in
 * doubles moved out by three ulps (the conversions and the division round
 * by less than two). */
static void rat_enclose(long long p, long long q, double *lo, double *hi) {
  const double v = (double)p / (double)q;
  *lo = v, *hi = v;
  for (int i = 0; i < 3; i++)
    *lo = nextafter(*lo, -INFINITY), *hi = nextafter(*hi, INFINITY);
  if (*lo < 0.0) *lo = 0.0;
}

/* out[r] = sum_c W[r][c] x[c] over rows r < nr, c < nc, W nonnegative
 * intervals (w: lo, hi pairs), x intervals of 3 coordinates, outward: each
 * product's bound picked by the sign of x, the sums widened by (nc + 2)
 * 1.2e-16 of their magnitude and 1e-300. */
static void wmul(const double *w, size_t nr, size_t nc, const double *xlo,
                 const double *xhi, double *olo, double *ohi) {
  for (size_t r = 0; r < nr; r++)
    for (int k = 0; k < 3; k++) {
      double sl = 0.0, sh = 0.0, ml = 0.0, mh = 0.0;
      for (size_t c = 0; c < nc; c++) {
        const double wl = w[2 * (r * nc + c)], wh = w[2 * (r * nc + c) + 1];
        if (wh == 0.0) continue;
        const double pl = xlo[3 * c + (size_t)k], ph = xhi[3 * c + (size_t)k];
        const double a = pl >= 0.0 ? wl * pl : wh * pl, z = ph >= 0.0 ? wh * ph : wl * ph;
        sl += a, sh += z, ml += fabs(a), mh += fabs(z);
      }
      const double e = (double)(nc + 2) * 1.2e-16;
      olo[3 * r + (size_t)k] = sl - e * ml - 1e-300;
      ohi[3 * r + (size_t)k] = sh + e * mh + 1e-300;
    }
}

/* The child of a tube's patch (lo, hi: 4 layers x ncol) in along half hb:
 * k < 0 the tube child (the box again: 4 x ncol points, (A_hb (x) F) P), else
 * the regular child of quadrant k (64 points in ss_limit_bspline's layout,
 * (A_hb (x) G_k) P).  Returns 0 without memory. */
static int tube_child(const bbox *x, const double *lo, const double *hi, int hb, int k,
                      double *olo, double *ohi) {
  const size_t n = x->ncol, rows = k < 0 ? n : 16;
  const double *w = k < 0 ? x->w : x->w + 2 * n * n + 2 * 16 * n * (size_t)k;
  double *ql = malloc(4 * rows * 3 * sizeof *ql), *qh = malloc(4 * rows * 3 * sizeof *qh);
  if (!ql || !qh) {
    free(ql), free(qh);
    return 0;
  }
  for (size_t l = 0; l < 4; l++) /* across first, layer by layer */
    wmul(w, rows, n, lo + 3 * n * l, hi + 3 * n * l, ql + 3 * rows * l,
         qh + 3 * rows * l);
  for (size_t l2 = 0; l2 < 4; l2++) /* then along: a B-spline half, exact eighths */
    for (size_t r = 0; r < rows; r++) {
      size_t at = l2 * rows + r; /* the tube child's layout */
      if (k >= 0) {              /* the regular child's: along, g0, g1 across */
        size_t id[3];
        id[x->axis] = l2, id[x->across[0]] = r % 4, id[x->across[1]] = r / 4;
        at = id[0] + 4 * id[1] + 16 * id[2];
      }
      for (size_t d = 0; d < 3; d++) {
        double sl = 0.0, sh = 0.0, ml = 0.0, mh = 0.0;
        for (size_t l = 0; l < 4; l++) {
          const double a = HALF[hb][l2][l] / 8.0;
          const size_t from = 3 * (l * rows + r) + d;
          sl += a * ql[from], sh += a * qh[from];
          ml += fabs(a * ql[from]), mh += fabs(a * qh[from]);
        }
        olo[3 * at + d] = sl - 4e-16 * ml - 1e-300;
        ohi[3 * at + d] = sh + 4e-16 * mh + 1e-300;
      }
    }
  free(ql), free(qh);
  return 1;
}

/* The hull of the sub-box idx (levels deeper, relative) of tube box x: down
 * the tube children while the sub-box holds the spoke, then the regular
 * child's net refined to it.  Its direction into d (proven) and, when a net
 * was reached, its midpoints into vnet (*have = 1).  Returns -1 without
 * memory, 0 if 0 is not separated, 1 if it is. */
static int tube_direction(const bbox *x, int levels, const int64_t idx[3], double d[3],
                          double vnet[64][3], int *have) {
  const size_t np = 4 * x->ncol;
  double *lo = malloc(np * 3 * sizeof *lo), *hi = malloc(np * 3 * sizeof *hi),
         *clo = malloc(np * 3 * sizeof *clo), *chi = malloc(np * 3 * sizeof *chi);
  double nlo[64 * 3], nhi[64 * 3];
  int rc = -1;
  *have = 0;
  if (!lo || !hi || !clo || !chi) goto out;
  memcpy(lo, x->lo, np * 3 * sizeof *lo);
  memcpy(hi, x->hi, np * 3 * sizeof *hi);
  const unsigned amask = (1u << x->across[0]) | (1u << x->across[1]);
  for (int l = levels - 1; l >= 0; l--) {
    unsigned q = 0;
    for (int a = 0; a < 3; a++)
      if (a != x->axis && ((idx[a] >> l) & 1)) q |= 1u << a;
    const int hb = (int)((idx[x->axis] >> l) & 1);
    int k = -1;
    for (int j = 0; j < 3 && q != (x->corner & amask); j++)
      if (x->quad[j] == q) k = j;
    if (q != (x->corner & amask) && k < 0) { /* (four quadrants: not met) */
      rc = 0;
      goto out;
    }
    if (k < 0) {
      if (!tube_child(x, lo, hi, hb, -1, clo, chi)) goto out;
      memcpy(lo, clo, np * 3 * sizeof *lo);
      memcpy(hi, chi, np * 3 * sizeof *hi);
      continue;
    }
    if (!tube_child(x, lo, hi, hb, k, nlo, nhi)) goto out;
    refine64(nlo, nhi, l, idx);
    for (int i = 0; i < 64; i++)
      for (int c = 0; c < 3; c++)
        vnet[i][c] = 0.5 * nlo[3 * i + c] + 0.5 * nhi[3 * i + c];
    *have = 1;
    rc = hull_direction(nlo, nhi, 64, x->shift, d);
    goto out;
  }
  rc = hull_direction(lo, hi, np, x->shift, d);
out:
  free(lo), free(hi), free(clo), free(chi);
  return rc;
}

/* The offer of the double point at grid g (level G) of box x, corner o,
 * side squares a side (a piece: psi there; a tube: its patch's mean). */
static int offer_at(ss_psi_inject *b, const bbox *x, const int64_t g[3],
                    const int64_t o[3], int64_t side, const ss_star_coord *key) {
  if (!grow((void **)&b->of, &b->capof, b->nof + 1, sizeof *b->of)) return 0;
  offer *f = &b->of[b->nof];
  f->key = *key;
  f->seq = b->nof++;
  if (!x->tube) {
    double p[3], J[3][3];
    ss_limit_bspline((const double(*)[3])x->net, (double)(g[0] - o[0]) / (double)side,
                     (double)(g[1] - o[1]) / (double)side,
                     (double)(g[2] - o[2]) / (double)side, p, J);
    for (int k = 0; k < 3; k++)
      f->v[k] = p[k] + x->shift[k];
    f->prio = 1;
  } else { /* the patch's mean, a point near psi there */
    for (int k = 0; k < 3; k++) {
      double m = 0.0;
      for (size_t i = 0; i < x->n; i++)
        m += 0.5 * x->lo[3 * i + (size_t)k] + 0.5 * x->hi[3 * i + (size_t)k];
      f->v[k] = m / (double)x->n + x->shift[k];
    }
    f->prio = 0;
  }
  return 1;
}

/* Stop with "0 not separated from the hull of" the box or sub-box (corner g
 * at grid level G, side 2^-depth). */
static void not_separated(ss_psi_inject *b, const bbox *x, int depth,
                          const int64_t g[3]) {
  char why[200];
  snprintf(why, sizeof why,
           "0 not separated from the hull of cell %zu's box (%.6g, %.6g, %.6g) of side "
           "2^-%d",
           x->cell + 1, ldexp((double)g[0], -b->G), ldexp((double)g[1], -b->G),
           ldexp((double)g[2], -b->G), depth);
  stop(b, why);
}

/* The direction proven positive on the hull of the square's sub-box of side
 * 2^-G (a piece: its net refined there; a tube's box: its children down to
 * it, vnet then the net reached, if any: *have).  1 if proven; 0 with why
 * set; -1 without memory. */
static int square_direction(ss_psi_inject *b, const bbox *x, const int64_t o[3],
                            const int64_t sub[3], double d[3], double vnet[64][3],
                            int *have) {
  const int64_t idx[3] = {sub[0] - o[0], sub[1] - o[1], sub[2] - o[2]};
  *have = 0;
  int rc;
  if (x->tube) {
    rc = tube_direction(x, b->G - x->depth, idx, d, vnet, have);
  } else {
    double lo[64 * 3], hi[64 * 3];
    subnet(x, b->G - x->depth, idx, lo, hi);
    rc = hull_direction(lo, hi, 64, x->shift, d);
  }
  if (rc == 0) not_separated(b, x, b->G, sub);
  return rc;
}

/* The squares of box x on the face of axis a opposite p (far side f). */
static ss_status face_squares(ss_psi_inject *b, const bbox *x,
                              const ss_star_coord *const *c, int a, int f,
                              const int64_t o[3], int64_t side, ss_error *err) {
  const int e1 = (a + 1) % 3, e2 = (a + 2) % 3;
  static const int ccw[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int64_t s1 = 0; s1 < side; s1++)
    for (int64_t s2 = 0; s2 < side; s2++) {
      if (b->nsq >= SS_PSI_INJECT_MAXSQ) {
        stop(b, "more boundary squares than the bound SS_PSI_INJECT_MAXSQ");
        return SS_OK;
      }
      if (!grow((void **)&b->sq, &b->capsq, b->nsq + 1, sizeof *b->sq))
        return ss_error_nomem(err, "psi boundary squares");
      square *q = &b->sq[b->nsq];
      int64_t sub[3]; /* the square's sub-box, its corner of smallest indices */
      sub[a] = f ? o[a] + side - 1 : o[a];
      sub[e1] = o[e1] + s1;
      sub[e2] = o[e2] + s2;
      double vnet[64][3];
      int have;
      const int rc = square_direction(b, x, o, sub, q->d, vnet, &have);
      if (rc < 0) return ss_error_nomem(err, "psi boundary tubes");
      if (rc == 0) return SS_OK;
      for (int v = 0; v < 4; v++) {
        const int r = f ? v : (4 - v) % 4; /* outward: e1 x e2 = e_a */
        int64_t g[3];
        g[a] = f ? (int64_t)1 << b->G : 0;
        g[e1] = o[e1] + s1 + ccw[r][0];
        g[e2] = o[e2] + s2 + ccw[r][1];
        if (!grid_name(c, b->G, g, &q->key[v])) {
          stop(b, "a boundary point's star coordinates do not fit");
          return SS_OK;
        }
        if (!offer_at(b, x, g, o, side, &q->key[v]))
          return ss_error_nomem(err, "psi boundary vertices");
        if (have) { /* a tube's regular child reached: psi at the corner */
          double t[3], pt[3], J[3][3];
          t[a] = f, t[e1] = ccw[r][0], t[e2] = ccw[r][1];
          ss_limit_bspline((const double(*)[3])vnet, t[0], t[1], t[2], pt, J);
          offer *fo = &b->of[b->nof - 1];
          for (int k = 0; k < 3; k++)
            fo->v[k] = pt[k] + x->shift[k];
          fo->prio = 1;
        }
      }
      b->nsq++;
    }
  return SS_OK;
}

/* Which faces opposite p box x touches at grid level G (touches[a]), its
 * corner o and squares per side; 0 if none. */
static int box_faces(const ss_psi_inject *b, const bbox *x, int touches[3], int64_t o[3],
                     int64_t *side) {
  *side = (int64_t)1 << (b->G - x->depth);
  const int64_t one = (int64_t)1 << b->G;
  int any = 0;
  for (int a = 0; a < 3; a++) {
    o[a] = (int64_t)ldexp(x->origin[a], b->G);
    touches[a] = !((x->pbits >> a) & 1u) ? o[a] + *side == one : o[a] == 0;
    any |= touches[a];
  }
  return any;
}

/* The squares of every kept box at grid level b->G. */
static ss_status build_grid(ss_psi_inject *b, ss_error *err) {
  b->nsq = b->nof = 0;
  for (size_t i = 0; i < b->nbx && !b->stop; i++) {
    const bbox *x = &b->bx[i];
    int touches[3];
    int64_t o[3], side;
    if (!box_faces(b, x, touches, o, &side)) continue;
    const ss_star_coord *c[8];
    if (!cell_corners(b->M, x->cell, c)) {
      stop(b, "a cell round p that is not an affine cube of the star's chart");
      break;
    }
    for (int a = 0; a < 3 && !b->stop; a++) {
      if (!touches[a]) continue;
      const ss_status st =
          face_squares(b, x, c, a, !((x->pbits >> a) & 1u), o, side, err);
      if (st) return st;
    }
  }
  return SS_OK;
}

/* A copy of box pc into b->bx. */
static ss_status keep(ss_psi_inject *b, const ss_limit_piece *pc, unsigned pbits,
                      ss_error *err) {
  if (!grow((void **)&b->bx, &b->capbx, b->nbx + 1, sizeof *b->bx))
    return ss_error_nomem(err, "psi boundary boxes");
  bbox *x = &b->bx[b->nbx];
  memset(x, 0, sizeof *x);
  x->cell = pc->cell, x->pbits = pbits, x->depth = pc->depth;
  memcpy(x->origin, pc->origin, sizeof x->origin);
  memcpy(x->shift, pc->shift, sizeof x->shift);
  x->tube = !pc->net;
  x->n = pc->net ? 64 : 4 * pc->tube->ncol;
  const double *lo = pc->net ? &pc->lo[0][0] : pc->tube->lo,
               *hi = pc->net ? &pc->hi[0][0] : pc->tube->hi;
  x->lo = malloc(3 * x->n * sizeof *x->lo);
  x->hi = malloc(3 * x->n * sizeof *x->hi);
  if (pc->net) x->net = malloc(64 * 3 * sizeof *x->net);
  if (!x->lo || !x->hi || (pc->net && !x->net)) {
    free(x->lo), free(x->hi), free(x->net);
    return ss_error_nomem(err, "psi boundary boxes");
  }
  memcpy(x->lo, lo, 3 * x->n * sizeof *x->lo);
  memcpy(x->hi, hi, 3 * x->n * sizeof *x->hi);
  if (pc->net) memcpy(x->net, &pc->net[0][0], 64 * 3 * sizeof *x->net);
  b->nbx++;
  if (pc->net) return SS_OK;
  const ss_limit_tube *u = pc->tube;
  const size_t n = u->ncol;
  x->axis = u->axis, x->across[0] = u->across[0], x->across[1] = u->across[1];
  x->corner = u->corner, x->ncol = n;
  memcpy(x->quad, u->quad, sizeof x->quad);
  if (!(x->w = malloc(2 * (n * n + 3 * 16 * n) * sizeof *x->w)))
    return ss_error_nomem(err, "psi boundary tubes");
  for (size_t i = 0; i < n * n; i++)
    rat_enclose(u->Fp[i], u->Fq[i], &x->w[2 * i], &x->w[2 * i + 1]);
  for (size_t k = 0; k < 3; k++)
    for (size_t i = 0; i < 16 * n; i++) {
      const size_t at = n * n + k * 16 * n + i;
      rat_enclose(u->Gp[k][i], u->Gq[k][i], &x->w[2 * at], &x->w[2 * at + 1]);
    }
  return SS_OK;
}

ss_status ss_psi_inject_box(ss_psi_inject *b, const ss_limit_piece *pc, unsigned pbits,
                            ss_error *err) {
  if (b->stop) return SS_OK;
  if (pc->depth > b->N) {
    stop(b, "a box deeper than the boundary grid");
    return SS_OK;
  }
  bbox probe;
  memset(&probe, 0, sizeof probe);
  probe.cell = pc->cell, probe.pbits = pbits, probe.depth = pc->depth;
  memcpy(probe.origin, pc->origin, sizeof probe.origin);
  int touches[3];
  int64_t o[3], side;
  b->G = b->N;
  if (!box_faces(b, &probe, touches, o, &side)) return SS_OK;
  if (pc->net
          ? !pc->lo || !pc->hi
          : !pc->tube || !pc->tube->lo || !pc->tube->hi ||
                !stochastic(pc->tube->Fp, pc->tube->Fq, pc->tube->ncol, pc->tube->ncol)) {
    stop(b, pc->net ? "a piece without enclosure on the boundary"
                    : "a boundary box without a tube of nonnegative weights");
    return SS_OK;
  }
  if (!pc->net)
    for (int k = 0; k < 3; k++)
      if (!stochastic(pc->tube->Gp[k], pc->tube->Gq[k], 16, pc->tube->ncol)) {
        stop(b, "a boundary tube whose quadrant rows are not nonnegative");
        return SS_OK;
      }
  return keep(b, pc, pbits, err);
}

/* --- phase 2: the surface T and its winding number --------------------- */

static int offer_cmp(const void *x, const void *y) {
  const offer *a = x, *b = y;
  const int c = ss_star_coord_cmp(&a->key, &b->key);
  if (c) return c;
  if (a->prio != b->prio) return b->prio - a->prio;
  return (a->seq > b->seq) - (a->seq < b->seq);
}

/* The index of key among the n unique offers u (sorted), or SIZE_MAX. */
static size_t find(const offer *u, size_t n, const ss_star_coord *key) {
  size_t lo = 0, hi = n;
  while (lo < hi) {
    const size_t m = lo + (hi - lo) / 2;
    const int c = ss_star_coord_cmp(&u[m].key, key);
    if (c == 0) return m;
    if (c < 0)
      lo = m + 1;
    else
      hi = m;
  }
  return SIZE_MAX;
}

typedef struct {
  size_t a, b;
} edge;

static int edge_cmp(const void *x, const void *y) {
  const edge *p = x, *q = y;
  if (p->a != q->a) return (p->a > q->a) - (p->a < q->a);
  return (p->b > q->b) - (p->b < q->b);
}

/* Unique vertices (the first offer of each name), the squares' corners
 * indexed into them; 0 and why if a name has no vertex. */
static size_t unify(ss_psi_inject *b) {
  qsort(b->of, b->nof, sizeof *b->of, offer_cmp);
  size_t n = 0;
  for (size_t i = 0; i < b->nof; i++)
    if (n == 0 || ss_star_coord_cmp(&b->of[n - 1].key, &b->of[i].key) != 0)
      b->of[n++] = b->of[i];
  for (size_t s = 0; s < b->nsq; s++)
    for (int v = 0; v < 4; v++)
      b->sq[s].vi[v] = find(b->of, n, &b->sq[s].key[v]);
  return n;
}

/* Every edge of T once in each direction (a closed oriented surface). */
static int closed(const ss_psi_inject *b, ss_error *err, int *ok) {
  edge *e = malloc(4 * b->nsq * sizeof *e);
  if (!e) return ss_error_nomem(err, "psi boundary edges");
  for (size_t s = 0; s < b->nsq; s++)
    for (int v = 0; v < 4; v++)
      e[4 * s + (size_t)v] = (edge){b->sq[s].vi[v], b->sq[s].vi[(v + 1) % 4]};
  const size_t m = 4 * b->nsq;
  qsort(e, m, sizeof *e, edge_cmp);
  *ok = 1;
  for (size_t i = 0; i < m && *ok; i++) {
    if (i + 1 < m && edge_cmp(&e[i], &e[i + 1]) == 0) *ok = 0; /* twice one way */
    const edge r = {e[i].b, e[i].a};
    if (!bsearch(&r, e, m, sizeof *e, edge_cmp)) *ok = 0;
  }
  free(e);
  return SS_OK;
}

/* s += the signed solid angle of triangle (x, y, z) seen from 0 (Van
 * Oosterom and Strackee): 2 atan2(x.(y x z), |x||y||z| + (x.y)|z| + (x.z)|y|
 * + (y.z)|x|), exact inputs. */
static void add_solid_angle(arb_t s, const double *x, const double *y, const double *z) {
  arb_t p[3][3], num, den, nx, ny, nz, t;
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) {
      arb_init(p[i][k]);
      arb_set_d(p[i][k], (i == 0 ? x : i == 1 ? y : z)[k]);
    }
  arb_init(num), arb_init(den), arb_init(nx), arb_init(ny), arb_init(nz), arb_init(t);
  /* x . (y x z) */
  arb_zero(num);
  for (int k = 0; k < 3; k++) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    arb_mul(t, p[1][k1], p[2][k2], PREC);
    arb_submul(t, p[1][k2], p[2][k1], PREC);
    arb_addmul(num, p[0][k], t, PREC);
  }
  arb_t *n3[3] = {&nx, &ny, &nz};
  for (int i = 0; i < 3; i++) {
    arb_zero(*n3[i]);
    for (int k = 0; k < 3; k++)
      arb_addmul(*n3[i], p[i][k], p[i][k], PREC);
    arb_sqrt(*n3[i], *n3[i], PREC);
  }
  arb_mul(den, nx, ny, PREC);
  arb_mul(den, den, nz, PREC);
  static const int pr[3][3] = {{0, 1, 2}, {0, 2, 1}, {1, 2, 0}}; /* (i.j)|k| */
  for (int q = 0; q < 3; q++) {
    arb_zero(t);
    for (int k = 0; k < 3; k++)
      arb_addmul(t, p[pr[q][0]][k], p[pr[q][1]][k], PREC);
    arb_addmul(den, t, *n3[pr[q][2]], PREC);
  }
  arb_atan2(t, num, den, PREC);
  arb_mul_2exp_si(t, t, 1);
  arb_add(s, s, t, PREC);
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++)
      arb_clear(p[i][k]);
  arb_clear(num), arb_clear(den), arb_clear(nx), arb_clear(ny), arb_clear(nz),
      arb_clear(t);
}

/* Whether d.v > 0 exactly (double inputs, in balls). */
static int dot_positive(const double d[3], const double v[3]) {
  arb_t s, x, y;
  arb_init(s), arb_init(x), arb_init(y);
  arb_zero(s);
  for (int k = 0; k < 3; k++) {
    arb_set_d(x, d[k]);
    arb_set_d(y, v[k]);
    arb_addmul(s, x, y, PREC);
  }
  const int ok = arb_is_positive(s);
  arb_clear(s), arb_clear(x), arb_clear(y);
  return ok;
}

/* The winding number of T: its enclosure into out->wlo, whi and, if unique,
 * out->degree; 0 if not unique. */
static int winding(const ss_psi_inject *b, ss_psi_inject_result *out) {
  arb_t s, pi;
  arb_init(s), arb_init(pi);
  arb_zero(s);
  for (size_t q = 0; q < b->nsq; q++) {
    const size_t *vi = b->sq[q].vi;
    add_solid_angle(s, b->of[vi[0]].v, b->of[vi[1]].v, b->of[vi[2]].v);
    add_solid_angle(s, b->of[vi[0]].v, b->of[vi[2]].v, b->of[vi[3]].v);
  }
  arb_const_pi(pi, PREC);
  arb_mul_2exp_si(pi, pi, 2);
  arb_div(s, s, pi, PREC);
  out->wlo = arf_get_d(arb_midref(s), ARF_RND_FLOOR) - mag_get_d(arb_radref(s));
  out->whi = arf_get_d(arb_midref(s), ARF_RND_CEIL) + mag_get_d(arb_radref(s));
  fmpz_t z;
  fmpz_init(z);
  const int unique = arb_get_unique_fmpz(z, s) && fmpz_abs_fits_ui(z);
  if (unique) out->degree = (int)fmpz_get_si(z);
  fmpz_clear(z);
  arb_clear(s), arb_clear(pi);
  return unique;
}

ss_status ss_psi_inject_degree(ss_psi_inject *b, int sign, ss_psi_inject_result *out,
                               ss_error *err) {
  memset(out, 0, sizeof *out);
  if (b->stop) {
    snprintf(out->why, sizeof out->why, "injectivity of psi not decided: %.150s", b->why);
    return SS_OK;
  }
  /* the grid at the box depth, finer while 0 is not separated (up to
   * SS_PSI_INJECT_REFINE levels more, and 8) */
  size_t nv = 0;
  for (b->G = b->N; b->G <= b->N + SS_PSI_INJECT_REFINE && b->G <= 8; b->G++) {
    b->stop = 0;
    ss_status st = build_grid(b, err);
    if (st) return st;
    if (!b->stop && b->nsq == 0) stop(b, "no square of the star's boundary was met");
    if (!b->stop) {
      nv = unify(b);
      for (size_t q = 0; q < b->nsq && !b->stop; q++)
        for (int v = 0; v < 4 && !b->stop; v++) {
          const size_t i = b->sq[q].vi[v];
          if (i == SIZE_MAX || !dot_positive(b->sq[q].d, b->of[i].v))
            stop(b, "0 not separated from a boundary square of T");
        }
    }
    if (!b->stop || strncmp(b->why, "0 not separated", 15) != 0) break;
  }
  if (b->G > b->N + SS_PSI_INJECT_REFINE || b->G > 8) b->G--;
  out->squares = b->nsq;
  if (b->stop) {
    snprintf(out->why, sizeof out->why, "injectivity of psi not decided: %.150s", b->why);
    return SS_OK;
  }
  int ok = 0;
  ss_status st = b->stop ? SS_OK : closed(b, err, &ok);
  if (st) return st;
  if (!b->stop && !ok) stop(b, "the boundary surface is not closed");
  if (b->stop) {
    snprintf(out->why, sizeof out->why, "injectivity of psi not decided: %.150s", b->why);
    return SS_OK;
  }
  if (!winding(b, out)) {
    snprintf(out->why, sizeof out->why,
             "injectivity of psi not decided: its winding number on the star's boundary "
             "is in [%.6g, %.6g] (%zu squares, %zu vertices)",
             out->wlo, out->whi, b->nsq, nv);
    return SS_OK;
  }
  const int n = out->degree;
  if (n == sign) {
    out->decided = 1;
    snprintf(out->why, sizeof out->why,
             "psi injective: regular (det Dpsi of sign %+d) with winding number %+d on "
             "the star's boundary (%zu squares; proven)",
             sign, n, b->nsq);
  } else if (n * sign >= 2) {
    out->decided = -1;
    snprintf(out->why, sizeof out->why,
             "psi not injective: regular with winding number %+d on the star's boundary: "
             "points near 0 have %d preimages (%zu squares; proven)",
             n, n * sign, b->nsq);
  } else {
    snprintf(out->why, sizeof out->why,
             "injectivity of psi not decided: winding number %+d on the star's boundary "
             "against det Dpsi's sign %+d (%zu squares)",
             n, sign, b->nsq);
  }
  return SS_OK;
}
