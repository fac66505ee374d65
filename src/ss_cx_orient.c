/* ss_cx_orient.c — orientation and signed volume of cells, inverted-cell check.
 *
 * A cell is "positive" under the vertex-order conventions of ss_cx.h.  Hexes and
 * quads are judged at every corner (the corner Jacobians of the multilinear map;
 * a cell whose corners disagree is folded), octahedra by the eight tets from
 * their centroid. */
#include "ss_cx.h"

#include <math.h>

static double det3(const double *a, const double *b, const double *c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

static void sub(int n, const double *a, const double *b, double *r) {
  for (int i = 0; i < n; i++)
    r[i] = a[i] - b[i];
}

/* Sign accumulator: returns +1/-1 if all seen values share that strict sign. */
typedef struct {
  int pos, neg, zero;
} signs;

static void see(signs *s, double v) {
  if (v > 0)
    s->pos++;
  else if (v < 0)
    s->neg++;
  else
    s->zero++;
}

static int verdict(const signs *s) {
  if (s->zero || (s->pos && s->neg)) return 0;
  return s->pos ? 1 : -1;
}

/* Jacobian determinant of the d-linear map of a d-cube (d = 2, 3) at parameter
 * u in [0,1]^d; corners in the ss_cx order. */
static double cube_jac(const ss_cx *cx, const ss_idx *v, int d, const double *u) {
  double J[3][3] = {{0}};
  for (int k = 0; k < (1 << d); k++) {
    unsigned b = ss_cube_corner_bits(d, k);
    const double *x = cx->x + (size_t)v[k] * (size_t)cx->dim;
    for (int i = 0; i < d; i++) {
      double w = 1.0; /* derivative of the tensor Lagrange basis in direction i */
      for (int j = 0; j < d; j++) {
        int bj = (int)((b >> j) & 1u);
        if (j == i)
          w *= bj ? 1.0 : -1.0;
        else
          w *= bj ? u[j] : 1.0 - u[j];
      }
      for (int r = 0; r < d; r++)
        J[r][i] += w * x[r];
    }
  }
  if (d == 2) return J[0][0] * J[1][1] - J[0][1] * J[1][0];
  double c0[3] = {J[0][0], J[1][0], J[2][0]}, c1[3] = {J[0][1], J[1][1], J[2][1]},
         c2[3] = {J[0][2], J[1][2], J[2][2]};
  return det3(c0, c1, c2);
}

int ss_cx_cell_orientation(const ss_cx *cx, ss_cell_type t, size_t i, double *vol) {
  const ss_idx *v = ss_cx_cell(cx, t, i);
  const int dim = cx->dim;
  signs s = {0, 0, 0};
  double V = 0.0;
#define X(k) (cx->x + (size_t)v[k] * (size_t)dim)
  if (dim == 3 && t == SS_TET) {
    double a[3], b[3], c[3];
    sub(3, X(1), X(0), a);
    sub(3, X(2), X(0), b);
    sub(3, X(3), X(0), c);
    V = det3(a, b, c) / 6.0;
    see(&s, V);
  } else if (dim == 2 && t == SS_TRIANGLE) {
    double a[2], b[2];
    sub(2, X(1), X(0), a);
    sub(2, X(2), X(0), b);
    V = (a[0] * b[1] - a[1] * b[0]) / 2.0;
    see(&s, V);
  } else if ((dim == 3 && t == SS_HEX) || (dim == 2 && t == SS_QUAD)) {
    int d = dim;
    for (int k = 0; k < (1 << d); k++) {
      unsigned b = ss_cube_corner_bits(d, k);
      double u[3];
      for (int j = 0; j < d; j++)
        u[j] = (double)((b >> j) & 1u);
      see(&s, cube_jac(cx, v, d, u));
    }
    /* exact volume: det J is of degree <= 2 per variable, so the 2-point Gauss
     * rule in each direction integrates it exactly */
    const double g[2] = {0.5 - 0.5 / sqrt(3.0), 0.5 + 0.5 / sqrt(3.0)};
    for (int k = 0; k < (1 << d); k++) {
      double u[3];
      for (int j = 0; j < d; j++)
        u[j] = g[(k >> j) & 1];
      V += cube_jac(cx, v, d, u) / (double)(1 << d);
    }
  } else if (dim == 3 && t == SS_OCT) {
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 6; k++)
      for (int r = 0; r < 3; r++)
        c[r] += X(k)[r] / 6.0;
    for (int f = 0; f < 8; f++) {
      int s0 = (f & 1) ? 3 : 0, s1 = (f & 2) ? 4 : 1, s2 = (f & 4) ? 5 : 2;
      int flips = (f & 1) + ((f >> 1) & 1) + ((f >> 2) & 1);
      double a[3], b[3], e[3];
      sub(3, X(s0), c, a);
      sub(3, X(s1), c, b);
      sub(3, X(s2), c, e);
      double det = det3(a, b, e) / 6.0;
      if (flips & 1) det = -det;
      V += det;
      see(&s, det);
    }
  } else {
    if (vol) *vol = 0.0;
    return 1;
  }
#undef X
  if (vol) *vol = V;
  return verdict(&s);
}

ss_status ss_cx_check_orientation(const ss_cx *cx, ss_error *err) {
  int top = ss_cx_topdim(cx);
  if (top < 2 || top != cx->dim) return SS_OK;
  size_t npos = 0, nneg = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (ss_cell_dim((ss_cell_type)t) != top) continue;
    for (size_t i = 0; i < cx->nc[t]; i++) {
      double vol;
      int o = ss_cx_cell_orientation(cx, (ss_cell_type)t, i, &vol);
      if (o == 0)
        return ss_error_set(err, SS_EINPUT,
                            "%s %zu is flat or folded (corner Jacobians of mixed sign or "
                            "zero; signed volume %g)",
                            ss_cell_name((ss_cell_type)t), i + 1, vol);
      if (o > 0)
        npos++;
      else
        nneg++;
    }
  }
  if (npos && nneg) {
    int minority = npos >= nneg ? -1 : 1;
    for (int t = 0; t < SS_NCELLTYPES; t++) {
      if (ss_cell_dim((ss_cell_type)t) != top) continue;
      for (size_t i = 0; i < cx->nc[t]; i++)
        if (ss_cx_cell_orientation(cx, (ss_cell_type)t, i, NULL) == minority)
          return ss_error_set(err, SS_EINPUT,
                              "%s %zu is inverted (%zu cells are oriented like it, %zu "
                              "the other way)",
                              ss_cell_name((ss_cell_type)t), i + 1,
                              minority < 0 ? nneg : npos, minority < 0 ? npos : nneg);
    }
  }
  return SS_OK;
}
