/* ss_jac.c — Jacobian sign of one cell's natural interpolant (Bernstein test
 * for hexes) and its scaled Jacobian.  Method: ss_jac.h. */
#include "ss_jac.h"

#include <math.h>
#include <string.h>

static double det3(const double *a, const double *b, const double *c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

static double det2(const double *a, const double *b) {
  return a[0] * b[1] - a[1] * b[0];
}

static double norm(const double *a, int d) {
  double s = 0.0;
  for (int i = 0; i < d; i++)
    s = hypot(s, a[i]);
  return s;
}

static void sub(int d, const double *a, const double *b, double *r) {
  for (int i = 0; i < d; i++)
    r[i] = a[i] - b[i];
}

/* det/product of lengths, 0 when an edge has length 0 */
static double scaled3(const double *a, const double *b, const double *c) {
  const double l = norm(a, 3) * norm(b, 3) * norm(c, 3);
  return l > 0.0 ? det3(a, b, c) / l : 0.0;
}

static void see_scaled(ss_jac_result *r, double s) {
  r->min_scaled = fmin(r->min_scaled, s);
  r->max_scaled = fmax(r->max_scaled, s);
}

/* ---- d-cubes: the corner frames ---- */

/* Corner k of a d-cube (d = 2, 3): the edge vectors along increasing
 * parameters, e[i] = x(corner with bit i set) - x(corner with bit i clear). */
static void corner_frame(const double *x, int d, int k, double e[3][3]) {
  const unsigned b = ss_cube_corner_bits(d, k);
  for (int i = 0; i < d; i++) {
    const unsigned b1 = b | (1u << i), b0 = b & ~(1u << i);
    const double *p1 = x + d * ss_cube_corner_index(d, b1);
    const double *p0 = x + d * ss_cube_corner_index(d, b0);
    sub(d, p1, p0, e[i]);
  }
}

double ss_jac_hex_at(const double *x, double u, double v, double w) {
  const double t[3] = {u, v, w};
  double J[3][3] = {{0}}; /* J[i] = d x / d t_i */
  for (int k = 0; k < 8; k++) {
    const unsigned b = ss_cube_corner_bits(3, k);
    for (int i = 0; i < 3; i++) {
      double wt = 1.0;
      for (int j = 0; j < 3; j++) {
        const int bj = (int)((b >> j) & 1u);
        wt *= j == i ? (bj ? 1.0 : -1.0) : (bj ? t[j] : 1.0 - t[j]);
      }
      for (int r = 0; r < 3; r++)
        J[i][r] += wt * x[3 * k + r];
    }
  }
  return det3(J[0], J[1], J[2]);
}

/* ---- hexes: Bernstein coefficients and adaptive subdivision ---- */

/* A box of the parameter cube with the 27 Bernstein coefficients of det J
 * on it, c[i + 3 j + 9 k] for the multi-index (i, j, k) in {0,1,2}^3. */
typedef struct {
  double c[27]; /* coefficients */
  double lo[3]; /* the box's low corner in [0,1]^3 */
  double size;  /* its edge length */
  int depth;    /* subdivision level */
} box;

/* de Casteljau at 1/2 along axis a: the coefficients of the lower and upper
 * halves. */
static void split_axis(const double *c, int a, double *lo, double *hi) {
  const int stride = a == 0 ? 1 : a == 1 ? 3 : 9;
  for (int q = 0; q < 27; q++) {
    const int idx = (q / stride) % 3;
    if (idx != 0) continue;
    const double b0 = c[q], b1 = c[q + stride], b2 = c[q + 2 * stride];
    const double m01 = 0.5 * (b0 + b1), m12 = 0.5 * (b1 + b2), m = 0.5 * (m01 + m12);
    lo[q] = b0, lo[q + stride] = m01, lo[q + 2 * stride] = m;
    hi[q] = m, hi[q + stride] = m12, hi[q + 2 * stride] = b2;
  }
}

enum { STACK = 8 * 16 + 8 }; /* depth-first: at most 7 pending boxes per level */

static void hex_sign(const double *x, int maxdepth, ss_jac_result *r) {
  if (maxdepth > 15) maxdepth = 15;
  box stack[STACK];
  int sp = 0;
  /* Lagrange values on {0, 1/2, 1}^3, converted axis by axis */
  box *b = stack + sp++;
  for (int k = 0; k < 3; k++)
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3; i++)
        b->c[i + 3 * j + 9 * k] = ss_jac_hex_at(x, 0.5 * i, 0.5 * j, 0.5 * k);
  for (int a = 0, stride = 1; a < 3; a++, stride *= 3)
    for (int q = 0; q < 27; q++)
      if ((q / stride) % 3 == 1)
        b->c[q] = 2.0 * b->c[q] - 0.5 * (b->c[q - stride] + b->c[q + stride]);
  b->lo[0] = b->lo[1] = b->lo[2] = 0.0;
  b->size = 1.0;
  b->depth = 0;
  int seen = 0; /* sign of the first exact value met */
  int npos = 0, nneg = 0, doubt = 0;
  r->depth = 0;
  while (sp > 0) {
    box cur = stack[--sp];
    r->depth = cur.depth > r->depth ? cur.depth : r->depth;
    /* exact values: the 8 corner coefficients */
    for (int k = 0; k < 8; k++) {
      const int i = (k & 1) * 2, j = ((k >> 1) & 1) * 2, l = ((k >> 2) & 1) * 2;
      const double v = cur.c[i + 3 * j + 9 * l];
      const int s = v > 0.0 ? 1 : v < 0.0 ? -1 : 0;
      if (s == 0 || (seen && s != seen)) {
        r->sign = SS_JAC_FOLDED;
        r->where[0] = cur.lo[0] + cur.size * 0.5 * i;
        r->where[1] = cur.lo[1] + cur.size * 0.5 * j;
        r->where[2] = cur.lo[2] + cur.size * 0.5 * l;
        return;
      }
      if (!seen) seen = s;
    }
    int pos = 1, neg = 1;
    for (int q = 0; q < 27; q++) {
      pos &= cur.c[q] > 0.0;
      neg &= cur.c[q] < 0.0;
    }
    if (pos) {
      npos++;
      continue;
    }
    if (neg) {
      nneg++;
      continue;
    }
    if (cur.depth >= maxdepth || sp + 8 > STACK) {
      doubt++;
      continue;
    }
    /* split into 8: along x, then y, then z */
    double h[2][27], q4[4][27], q8[8][27];
    split_axis(cur.c, 0, h[0], h[1]);
    for (int a = 0; a < 2; a++)
      split_axis(h[a], 1, q4[2 * a], q4[2 * a + 1]);
    for (int a = 0; a < 4; a++)
      split_axis(q4[a], 2, q8[2 * a], q8[2 * a + 1]);
    for (int a = 0; a < 8; a++) {
      /* q8 index: bit 2 = x half, bit 1 = y half, bit 0 = z half */
      box *nb = stack + sp++;
      memcpy(nb->c, q8[a], sizeof nb->c);
      nb->size = 0.5 * cur.size;
      nb->lo[0] = cur.lo[0] + ((a >> 2) & 1) * nb->size;
      nb->lo[1] = cur.lo[1] + ((a >> 1) & 1) * nb->size;
      nb->lo[2] = cur.lo[2] + (a & 1) * nb->size;
      nb->depth = cur.depth + 1;
    }
  }
  if (npos && nneg) {
    /* cannot happen without exact values of both signs, which return above */
    r->sign = SS_JAC_FOLDED;
    return;
  }
  if (doubt)
    r->sign = SS_JAC_UNDECIDED;
  else
    r->sign = seen > 0 ? SS_JAC_POSITIVE : SS_JAC_NEGATIVE;
}

/* ---- the cell types ---- */

void ss_jac_cell(ss_cell_type t, const double *x, int dim, int maxdepth,
                 ss_jac_result *r) {
  memset(r, 0, sizeof *r);
  r->min_scaled = INFINITY;
  r->max_scaled = -INFINITY;
  if (t == SS_HEX && dim == 3) {
    for (int k = 0; k < 8; k++) {
      double e[3][3];
      corner_frame(x, 3, k, e);
      see_scaled(r, scaled3(e[0], e[1], e[2]));
    }
    hex_sign(x, maxdepth < 0 ? 0 : maxdepth, r);
  } else if (t == SS_QUAD && dim == 2) {
    /* det J is affine on the quad: its corner values decide */
    int first = 0, bad = -1;
    for (int k = 0; k < 4; k++) {
      double e[3][3];
      corner_frame(x, 2, k, e);
      const double d = det2(e[0], e[1]), l = norm(e[0], 2) * norm(e[1], 2);
      see_scaled(r, l > 0.0 ? d / l : 0.0);
      const int sg = d > 0.0 ? 1 : d < 0.0 ? -1 : 0;
      if (k == 0) first = sg;
      if (bad < 0 && (sg == 0 || sg != first)) bad = k;
    }
    if (bad >= 0) {
      const unsigned b = ss_cube_corner_bits(2, bad);
      r->where[0] = (double)(b & 1u);
      r->where[1] = (double)((b >> 1) & 1u);
      r->sign = SS_JAC_FOLDED;
    } else {
      r->sign = first > 0 ? SS_JAC_POSITIVE : SS_JAC_NEGATIVE;
    }
  } else if (t == SS_TET && dim == 3) {
    double e[3][3];
    for (int i = 0; i < 3; i++)
      sub(3, x + 3 * (i + 1), x, e[i]);
    const double d = det3(e[0], e[1], e[2]);
    /* the same determinant at every corner; normalised by that corner's edges */
    for (int c = 0; c < 4; c++) {
      double l = 1.0;
      for (int j = 0; j < 4; j++) {
        if (j == c) continue;
        double a[3];
        sub(3, x + 3 * j, x + 3 * c, a);
        l *= norm(a, 3);
      }
      see_scaled(r, l > 0.0 ? sqrt(2.0) * d / l : 0.0);
    }
    r->sign = d > 0.0 ? SS_JAC_POSITIVE : d < 0.0 ? SS_JAC_NEGATIVE : SS_JAC_FOLDED;
  } else if (t == SS_TRIANGLE && dim == 2) {
    double a[2], b[2];
    sub(2, x + 2, x, a);
    sub(2, x + 4, x, b);
    const double d = det2(a, b);
    for (int c = 0; c < 3; c++) {
      double l = 1.0;
      for (int j = 0; j < 3; j++) {
        if (j == c) continue;
        double e[2];
        sub(2, x + 2 * j, x + 2 * c, e);
        l *= norm(e, 2);
      }
      see_scaled(r, l > 0.0 ? 2.0 / sqrt(3.0) * d / l : 0.0);
    }
    r->sign = d > 0.0 ? SS_JAC_POSITIVE : d < 0.0 ? SS_JAC_NEGATIVE : SS_JAC_FOLDED;
  } else if (t == SS_OCT && dim == 3) {
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 6; k++)
      for (int i = 0; i < 3; i++)
        c[i] += x[3 * k + i] / 6.0;
    int pos = 0, neg = 0, zero = 0;
    for (int f = 0; f < 8; f++) {
      /* octant f: one vertex of each opposite pair; an odd number of
       * reflections reverses the orientation (as in ss_cx_orient.c) */
      const int s0 = (f & 1) ? 3 : 0, s1 = (f & 2) ? 4 : 1, s2 = (f & 4) ? 5 : 2;
      const int flips = (f & 1) + ((f >> 1) & 1) + ((f >> 2) & 1);
      double a[3], b[3], e[3];
      sub(3, x + 3 * s0, c, a);
      sub(3, x + 3 * s1, c, b);
      sub(3, x + 3 * s2, c, e);
      double s = scaled3(a, b, e), d = det3(a, b, e);
      if (flips & 1) s = -s, d = -d;
      see_scaled(r, s);
      pos += d > 0.0;
      neg += d < 0.0;
      zero += !(d > 0.0 || d < 0.0);
    }
    r->sign = zero || (pos && neg) ? SS_JAC_FOLDED
              : pos                ? SS_JAC_POSITIVE
                                   : SS_JAC_NEGATIVE;
  } else {
    r->sign = SS_JAC_UNDECIDED;
    r->min_scaled = r->max_scaled = NAN;
  }
}
