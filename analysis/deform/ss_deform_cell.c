/* ss_deform_cell.c — the reference shapes of hex, tet and octahedron: their
 * interpolants, their inverses, and a point's child under the split
 * (ss_deform.h). */
#include <math.h>
#include <string.h>

#include "ss_deform.h"
#include "ss_deform_impl.h"

void ss_deform_ref_corner(ss_cell_type t, int k, double p[3]) {
  p[0] = p[1] = p[2] = 0.0;
  if (t == SS_HEX) {
    const unsigned b = ss_cube_corner_bits(3, k);
    for (int a = 0; a < 3; a++)
      p[a] = (double)((b >> a) & 1u);
  } else if (t == SS_TET) {
    if (k > 0) p[k - 1] = 1.0;
  } else { /* oct: +e1 +e2 +e3 -e1 -e2 -e3 */
    p[k % 3] = k < 3 ? 1.0 : -1.0;
  }
}

void ss_deform_weights(ss_cell_type t, const double r[3], double w[8]) {
  memset(w, 0, 8 * sizeof *w);
  if (t == SS_HEX) {
    for (int k = 0; k < 8; k++) {
      const unsigned b = ss_cube_corner_bits(3, k);
      double x = 1.0;
      for (int a = 0; a < 3; a++)
        x *= ((b >> a) & 1u) ? r[a] : 1.0 - r[a];
      w[k] = x;
    }
  } else if (t == SS_TET) {
    w[0] = 1.0 - r[0] - r[1] - r[2];
    w[1] = r[0];
    w[2] = r[1];
    w[3] = r[2];
  } else { /* the tet (0, 3, +-e2, +-e3) holding r, affine there */
    const double s = 1.0 - fabs(r[1]) - fabs(r[2]);
    w[r[1] >= 0 ? 1 : 4] = fabs(r[1]);
    w[r[2] >= 0 ? 2 : 5] = fabs(r[2]);
    w[0] = (s + r[0]) / 2.0;
    w[3] = (s - r[0]) / 2.0;
  }
}

double ss_deform_violation(ss_cell_type t, const double r[3]) {
  if (t == SS_HEX) {
    double m = -INFINITY;
    for (int a = 0; a < 3; a++)
      m = fmax(m, fmax(-r[a], r[a] - 1.0));
    return m;
  }
  if (t == SS_TET) return fmax(fmax(-r[0], -r[1]), fmax(-r[2], r[0] + r[1] + r[2] - 1.0));
  return fabs(r[0]) + fabs(r[1]) + fabs(r[2]) - 1.0;
}

void ss_deform_clamp(ss_cell_type t, double r[3]) {
  if (t == SS_HEX) {
    for (int a = 0; a < 3; a++)
      r[a] = fmin(1.0, fmax(0.0, r[a]));
  } else if (t == SS_TET) {
    for (int a = 0; a < 3; a++)
      r[a] = fmax(0.0, r[a]);
    const double s = r[0] + r[1] + r[2];
    if (s > 1.0)
      for (int a = 0; a < 3; a++)
        r[a] /= s;
  } else {
    const double s = fabs(r[0]) + fabs(r[1]) + fabs(r[2]);
    if (s > 1.0)
      for (int a = 0; a < 3; a++)
        r[a] /= s;
  }
}

void ss_deform_interp(const ss_cx *mesh, const ss_deform_loc *loc, double x[3]) {
  const int nv = ss_cell_nverts(loc->type), dim = mesh->dim;
  const ss_idx *v = ss_cx_cell(mesh, loc->type, loc->cell);
  double w[8];
  ss_deform_weights(loc->type, loc->r, w);
  x[0] = x[1] = x[2] = 0.0;
  for (int k = 0; k < nv; k++)
    for (int a = 0; a < 3; a++)
      x[a] += w[k] * mesh->x[(size_t)v[k] * (size_t)dim + (size_t)a];
}

int ss_deform_solve3(const double m[3][3], const double b[3], double x[3]) {
  /* Cramer's rule on columns m[.][j]; 0 if singular */
  const double d = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                   m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                   m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (d == 0.0 || !isfinite(d)) return 0;
  for (int j = 0; j < 3; j++) {
    double c[3][3];
    memcpy(c, m, sizeof c);
    for (int i = 0; i < 3; i++)
      c[i][j] = b[i];
    x[j] = (c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
            c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0]) +
            c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0])) /
           d;
  }
  return 1;
}

/* The affine frame of a child in its parent's reference space: the origin o
 * and the columns m of r_parent = o + m r_child, from the corners' reference
 * points q (hex: corner 0 and the corners one step along each axis; tet:
 * corner 0 and the others; oct: the centre and corners 0, 1, 2). */
static void child_frame(ss_cell_type t, const double (*q)[3], double o[3],
                        double m[3][3]) {
  for (int a = 0; a < 3; a++) {
    if (t == SS_OCT)
      o[a] = (q[0][a] + q[3][a]) / 2.0;
    else
      o[a] = q[0][a];
  }
  for (int j = 0; j < 3; j++) {
    const int k = t == SS_HEX   ? ss_cube_corner_index(3, 1u << j)
                  : t == SS_TET ? j + 1
                                : j;
    for (int a = 0; a < 3; a++)
      m[a][j] = q[k][a] - o[a];
  }
}

/* The reference point in coarse cell cv (type t) of fine vertex f: the mean
 * of its parents' reference corners.  0, or -1 if a parent is no corner. */
static int fine_ref(ss_cell_type t, const ss_idx *cv, const ss_split *L, size_t f,
                    double q[3]) {
  const int nv = ss_cell_nverts(t);
  const size_t np = ss_split_npar(L, f);
  q[0] = q[1] = q[2] = 0.0;
  for (size_t i = 0; i < np; i++) {
    const ss_idx p = L->parent[L->ptr[f] + i];
    int k = 0;
    while (k < nv && cv[k] != p)
      k++;
    if (k == nv) return -1;
    double c[3];
    ss_deform_ref_corner(t, k, c);
    for (int a = 0; a < 3; a++)
      q[a] += c[a] / (double)np;
  }
  return 0;
}

/* The children of coarse cell (t, c): for each child type u, fine cells
 * [first[u], first[u] + count[u]).  -1 if fine is not that split of coarse. */
static int children(const ss_cx *coarse, const ss_cx *fine, ss_cell_type t, size_t c,
                    size_t first[SS_NCELLTYPES], size_t count[SS_NCELLTYPES]) {
  const size_t nh = coarse->nc[SS_HEX], nt = coarse->nc[SS_TET], no = coarse->nc[SS_OCT];
  memset(count, 0, SS_NCELLTYPES * sizeof *count);
  memset(first, 0, SS_NCELLTYPES * sizeof *first);
  if (t == SS_HEX) {
    if (fine->nc[SS_HEX] != 8 * nh) return -1;
    first[SS_HEX] = 8 * c;
    count[SS_HEX] = 8;
    return 0;
  }
  if (fine->nc[SS_TET] != 4 * nt + 8 * no || fine->nc[SS_OCT] != nt + 6 * no) return -1;
  if (t == SS_TET) {
    first[SS_TET] = 4 * c;
    count[SS_TET] = 4;
    first[SS_OCT] = c;
    count[SS_OCT] = 1;
  } else {
    first[SS_TET] = 4 * nt + 8 * c;
    count[SS_TET] = 8;
    first[SS_OCT] = nt + 6 * c;
    count[SS_OCT] = 6;
  }
  return 0;
}

ss_status ss_deform_child(const ss_cx *coarse, const ss_cx *fine, const ss_split *L,
                          const ss_deform_loc *loc, ss_deform_loc *out, ss_error *err) {
  size_t first[SS_NCELLTYPES], count[SS_NCELLTYPES];
  const ss_cell_type t = loc->type;
  if (children(coarse, fine, t, loc->cell, first, count))
    return ss_error_set(err, SS_EINPUT, "the refined mesh is not the %s split of %s",
                        t == SS_HEX ? "multilinear" : "tet/oct", ss_cell_plural(t));
  const ss_idx *cv = ss_cx_cell(coarse, t, loc->cell);
  ss_deform_loc best = {SS_HEX, 0, {0, 0, 0}};
  double best_viol = INFINITY;
  static const ss_cell_type kinds[3] = {SS_HEX, SS_TET, SS_OCT};
  for (int ki = 0; ki < 3; ki++) {
    const ss_cell_type u = kinds[ki];
    for (size_t c = first[u]; c < first[u] + count[u]; c++) {
      const ss_idx *fv = ss_cx_cell(fine, u, c);
      double q[8][3], o[3], m[3][3], b[3], r[3];
      for (int k = 0; k < ss_cell_nverts(u); k++)
        if (fine_ref(t, cv, L, fv[k], q[k]))
          return ss_error_set(err, SS_EINPUT,
                              "fine vertex %zu does not derive from its coarse cell",
                              (size_t)fv[k] + 1);
      child_frame(u, (const double(*)[3])q, o, m);
      for (int a = 0; a < 3; a++)
        b[a] = loc->r[a] - o[a];
      if (!ss_deform_solve3((const double(*)[3])m, b, r)) continue;
      const double viol = ss_deform_violation(u, r);
      if (viol < best_viol) {
        best_viol = viol;
        best.type = u;
        best.cell = c;
        memcpy(best.r, r, sizeof r);
      }
    }
  }
  if (!(best_viol <= 1e3 * SS_DEFORM_TOL))
    return ss_error_set(err, SS_EINPUT, "no child of %s %zu holds the point",
                        ss_cell_name(t), loc->cell + 1);
  ss_deform_clamp(best.type, best.r);
  *out = best;
  return SS_OK;
}
