/* ss_cx_orient.c — orientation and signed volume of cells, flat- and
 * inverted-cell checks.
 *
 * A cell is "positive" under the vertex-order conventions of ss_cx.h.  Hexes and
 * quads are judged at every corner (the corner Jacobians of the multilinear map;
 * a cell whose corners disagree is folded), octahedra by the eight tets from
 * their centroid, simplices by their one determinant.
 *
 * Every judgement is scale-free: the cell's coordinates are first taken
 * relative to its vertex 0 and multiplied by a power of two (exact) so that the
 * largest difference lies in [1/2, 1), and each corner determinant is formed
 * from its edges taken to unit length one by one, i.e. divided by the product
 * of their lengths (for a simplex, at the corner where this is largest).  The resulting
 * "scaled Jacobian" lies in [-1, 1]; a value within SS_CX_FLAT_TOL of 0 is zero up to
 * rounding and has no sign.  So a cube of side 1e-300 or 1e300 is judged like the unit
 * cube (unscaled, its determinants under- or overflow), and a flat cell is flat whatever
 * its size. */
#include "ss_cx.h"

#include <math.h>

#include "ss_dense.h"

/* A cell's vertices relative to its vertex 0, scaled by 2^-e. */
typedef struct {
  int n;                                /* vertices */
  int dim;                              /* coordinates per vertex */
  int e;                                /* original difference = p * 2^e */
  double p[SS_MAXCELLVERTS][SS_MAXDIM]; /* scaled differences, |p| < 1 */
} local_cell;

static void localise(const ss_cx *cx, const ss_idx *v, int n, local_cell *c) {
  const int dim = cx->dim;
  const double *x0 = cx->x + (size_t)v[0] * (size_t)dim;
  int half = 0;
  c->n = n;
  c->dim = dim;
  for (int k = 0; k < n; k++)
    for (int r = 0; r < dim; r++) {
      c->p[k][r] = cx->x[(size_t)v[k] * (size_t)dim + (size_t)r] - x0[r];
      if (!isfinite(c->p[k][r])) half = 1;
    }
  if (half) /* coordinates near DBL_MAX of opposite signs: halve first */
    for (int k = 0; k < n; k++)
      for (int r = 0; r < dim; r++)
        c->p[k][r] = 0.5 * cx->x[(size_t)v[k] * (size_t)dim + (size_t)r] - 0.5 * x0[r];
  double h = 0.0;
  for (int k = 0; k < n; k++)
    for (int r = 0; r < dim; r++)
      h = fmax(h, fabs(c->p[k][r]));
  c->e = 0;
  if (h > 0.0 && isfinite(h)) frexp(h, &c->e);
  for (int k = 0; k < n; k++)
    for (int r = 0; r < dim; r++)
      c->p[k][r] = ldexp(c->p[k][r], -c->e);
  c->e += half;
}

static double det2(double a, double b, double c, double d) {
  return a * d - b * c;
}

static double norm(int n, const double *a) {
  double s = 0.0;
  for (int r = 0; r < n; r++)
    s += a[r] * a[r];
  return sqrt(s);
}

/* The k-volume of the parallelotope spanned by the columns c[0..k) in R^n
 * (k <= n): the signed determinant when k == n, otherwise its unsigned size
 * by Cauchy–Binet (the root of the sum of the squared k x k minors, accurate
 * where the Gram determinant would cancel). */
static double spread(int n, int k, const double (*c)[SS_MAXDIM]) {
  if (k == n) {
    if (n == 1) return c[0][0];
    if (n == 2) return det2(c[0][0], c[1][0], c[0][1], c[1][1]);
    if (n == 3) return ss_dense_det3(c[0], c[1], c[2]);
  }
  if (k == 1) return norm(n, c[0]);
  double s = 0.0;
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++) {
      if (k == 2) {
        double m = det2(c[0][i], c[1][i], c[0][j], c[1][j]);
        s += m * m;
        continue;
      }
      for (int l = j + 1; l < n; l++) { /* k == 3 */
        double a[3] = {c[0][i], c[0][j], c[0][l]}, b[3] = {c[1][i], c[1][j], c[1][l]},
               d[3] = {c[2][i], c[2][j], c[2][l]};
        double m = ss_dense_det3(a, b, d);
        s += m * m;
      }
    }
  return sqrt(s);
}

/* Scale column c (n entries) to unit length without under- or overflow;
 * 0 if it vanishes, else 1. */
static int unitise(int n, double *c) {
  double m = 0.0, s = 0.0;
  for (int r = 0; r < n; r++)
    m = fmax(m, fabs(c[r]));
  if (!(m > 0.0)) return 0;
  for (int r = 0; r < n; r++) {
    c[r] /= m;
    s += c[r] * c[r];
  }
  s = sqrt(s);
  for (int r = 0; r < n; r++)
    c[r] /= s;
  return 1;
}

/* The scaled Jacobian of k unit-length columns: their spread, 0 if one
 * vanishes.  Columns are taken to unit length one by one, so cells of any
 * aspect ratio keep their precision. */
static double scaled(int n, int k, double (*c)[SS_MAXDIM]) {
  for (int i = 0; i < k; i++)
    if (!unitise(n, c[i])) return 0.0;
  return spread(n, k, (const double(*)[SS_MAXDIM])c);
}

/* Scaled measure of the simplex on local points q[0..k]: the scaled Jacobian
 * at the corner where it is largest (corner j's edges q_i - q_j in increasing
 * i carry the sign (-1)^j of corner 0's when signed), so a needle is not flat;
 * *raw receives the unscaled spread at corner 0. */
static double simplex(const local_cell *c, int k, const double *const *q, int same,
                      double *raw) {
  double e[3][SS_MAXDIM], best = 0.0;
  for (int i = 0; i < k; i++)
    for (int r = 0; r < c->dim; r++)
      e[i][r] = q[i + 1][r] - q[0][r];
  *raw = spread(c->dim, k, (const double(*)[SS_MAXDIM])e);
  for (int j = 0; j <= k; j++) {
    int col = 0;
    for (int i = 0; i <= k; i++) {
      if (i == j) continue;
      for (int r = 0; r < c->dim; r++)
        e[col][r] = q[i][r] - q[j][r];
      col++;
    }
    double m = scaled(c->dim, k, e);
    if (same && (j & 1)) m = -m;
    if (fabs(m) > fabs(best)) best = m;
  }
  return best;
}

/* Jacobian columns of the d-linear map of a d-cube (d = 2, 3) at parameter
 * u in [0,1]^d; corners in the ss_cx order. */
static void cube_jac(const local_cell *c, int d, const double *u,
                     double (*J)[SS_MAXDIM]) {
  for (int i = 0; i < d; i++)
    for (int r = 0; r < c->dim; r++)
      J[i][r] = 0.0;
  for (int k = 0; k < (1 << d); k++) {
    unsigned b = ss_cube_corner_bits(d, k);
    for (int i = 0; i < d; i++) {
      double w = 1.0; /* derivative of the tensor Lagrange basis in direction i */
      for (int j = 0; j < d; j++) {
        int bj = (int)((b >> j) & 1u);
        if (j == i)
          w *= bj ? 1.0 : -1.0;
        else
          w *= bj ? u[j] : 1.0 - u[j];
      }
      for (int r = 0; r < c->dim; r++)
        J[i][r] += w * c->p[k][r];
    }
  }
}

/* The scaled corner measures of cell v of type t (see the file comment):
 * m[0..return) — signed when the cell's dimension equals cx->dim, else >= 0 —
 * and its signed volume in *vol (0 unless the dimensions are equal).  Returns
 * 0 for vertex cells and cells of more dimensions than coordinates. */
static int measures(const ss_cx *cx, ss_cell_type t, const ss_idx *v, double *m,
                    double *vol) {
  const int k = ss_cell_dim(t), n = ss_cell_nverts(t);
  *vol = 0.0;
  if (k < 1 || k > cx->dim) return 0;
  local_cell c;
  localise(cx, v, n, &c);
  const int same = k == cx->dim;
  double V = 0.0;
  int nm = 0;
  if (t == SS_SEGMENT || t == SS_TRIANGLE || t == SS_TET) {
    const double *q[4] = {c.p[0], c.p[1], c.p[2], c.p[3]};
    double raw;
    m[nm++] = simplex(&c, k, q, same, &raw);
    V = raw / (k == 3 ? 6.0 : k == 2 ? 2.0 : 1.0);
  } else if (t == SS_QUAD || t == SS_HEX) {
    double J[3][SS_MAXDIM];
    for (int corner = 0; corner < (1 << k); corner++) {
      unsigned b = ss_cube_corner_bits(k, corner);
      double u[3];
      for (int j = 0; j < k; j++)
        u[j] = (double)((b >> j) & 1u);
      cube_jac(&c, k, u, J);
      m[nm++] = scaled(c.dim, k, J);
    }
    if (same) {
      /* exact volume: det J is of degree <= 2 per variable, so the 2-point
       * Gauss rule in each direction integrates it exactly */
      const double g[2] = {0.5 - 0.5 / sqrt(3.0), 0.5 + 0.5 / sqrt(3.0)};
      for (int q = 0; q < (1 << k); q++) {
        double u[3];
        for (int j = 0; j < k; j++)
          u[j] = g[(q >> j) & 1];
        cube_jac(&c, k, u, J);
        V += spread(c.dim, k, (const double(*)[SS_MAXDIM])J) / (double)(1 << k);
      }
    }
  } else if (t == SS_OCT) {
    double ctr[SS_MAXDIM] = {0};
    for (int j = 0; j < 6; j++)
      for (int r = 0; r < c.dim; r++)
        ctr[r] += c.p[j][r] / 6.0;
    for (int f = 0; f < 8; f++) {
      int s0 = (f & 1) ? 3 : 0, s1 = (f & 2) ? 4 : 1, s2 = (f & 4) ? 5 : 2;
      int flips = (f & 1) + ((f >> 1) & 1) + ((f >> 2) & 1);
      const double *q[4] = {ctr, c.p[s0], c.p[s1], c.p[s2]};
      double raw, s = simplex(&c, 3, q, same, &raw);
      if (same && (flips & 1)) {
        s = -s;
        raw = -raw;
      }
      V += raw / 6.0;
      m[nm++] = s;
    }
  }
  *vol = same ? ldexp(V, k * c.e) : 0.0;
  return nm;
}

int ss_cx_cell_flat(const ss_cx *cx, ss_cell_type t, const ss_idx *v) {
  double m[8], vol;
  int nm = measures(cx, t, v, m, &vol);
  for (int j = 0; j < nm; j++)
    if (!(fabs(m[j]) > SS_CX_FLAT_TOL)) return 1;
  return 0;
}

int ss_cx_cell_orientation(const ss_cx *cx, ss_cell_type t, size_t i, double *vol) {
  double m[8], V = 0.0;
  int nm = 0, pos = 0, neg = 0, zero = 0;
  if (ss_cell_dim(t) == cx->dim && ss_cell_dim(t) >= 2)
    nm = measures(cx, t, ss_cx_cell(cx, t, i), m, &V);
  if (vol) *vol = V;
  if (nm == 0) return 1;
  for (int j = 0; j < nm; j++) {
    if (m[j] > SS_CX_FLAT_TOL)
      pos++;
    else if (m[j] < -SS_CX_FLAT_TOL)
      neg++;
    else
      zero++;
  }
  if (zero || (pos && neg)) return 0;
  return pos ? 1 : -1;
}

ss_status ss_cx_check_orientation(const ss_cx *cx, ss_error *err) {
  int top = ss_cx_topdim(cx);
  if (top < 2) return SS_OK;
  if (top > cx->dim) {
    for (int t = SS_NCELLTYPES - 1; t >= 0; t--)
      if (cx->nc[t] && ss_cell_dim((ss_cell_type)t) == top)
        return ss_error_set(err, SS_EINPUT,
                            "the mesh has %d coordinate%s per vertex but %zu %s "
                            "(%d-dimensional cells): with fewer coordinates than "
                            "dimensions every cell is flat",
                            cx->dim, cx->dim == 1 ? "" : "s", cx->nc[t],
                            cx->nc[t] == 1 ? ss_cell_name((ss_cell_type)t)
                                           : ss_cell_plural((ss_cell_type)t),
                            top);
  }
  if (top < cx->dim) {
    /* no orientation without a normal: judge flatness only */
    for (int t = 0; t < SS_NCELLTYPES; t++) {
      if (ss_cell_dim((ss_cell_type)t) != top) continue;
      for (size_t i = 0; i < cx->nc[t]; i++)
        if (ss_cx_cell_flat(cx, (ss_cell_type)t, ss_cx_cell(cx, (ss_cell_type)t, i)))
          return ss_error_set(err, SS_EINPUT,
                              "%s %zu is flat (zero %s at a corner, relative to its "
                              "edges)",
                              ss_cell_name((ss_cell_type)t), i + 1,
                              top == 2 ? "area" : "volume");
    }
    return SS_OK;
  }
  size_t npos = 0, nneg = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (ss_cell_dim((ss_cell_type)t) != top) continue;
    for (size_t i = 0; i < cx->nc[t]; i++) {
      double vol;
      int o = ss_cx_cell_orientation(cx, (ss_cell_type)t, i, &vol);
      if (o == 0)
        return ss_error_set(err, SS_EINPUT,
                            "%s %zu is flat or folded (corner Jacobians of mixed sign or "
                            "zero relative to its edges; signed volume %g)",
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
