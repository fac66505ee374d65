/* ss_deform_locate.c — which cell of the base mesh holds a point, and its
 * parameters there (ss_deform.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_deform.h"
#include "ss_deform_impl.h"

/* One volume cell and its bounding box. */
typedef struct {
  ss_cell_type type; /* SS_HEX, SS_TET or SS_OCT */
  size_t cell;       /* index among that type's cells */
  double lo[3];      /* bounding box, widened by the tolerance */
  double hi[3];
} cell_box;

struct ss_deform_locator {
  ss_cx *mesh;   /* copy of the base mesh */
  cell_box *box; /* every volume cell, hexes, tets, octahedra in file order */
  size_t nbox;   /* how many */
};

ss_status ss_deform_locator_new(const ss_cx *mesh, ss_deform_locator **out,
                                ss_error *err) {
  static const ss_cell_type kinds[3] = {SS_HEX, SS_TET, SS_OCT};
  *out = NULL;
  if (mesh->dim != 3)
    return ss_error_set(err, SS_EINPUT, "the base mesh needs 3 coordinates, not %d",
                        mesh->dim);
  const size_t n = mesh->nc[SS_HEX] + mesh->nc[SS_TET] + mesh->nc[SS_OCT];
  if (!n)
    return ss_error_set(err, SS_EINPUT,
                        "the base mesh has no volume cell (hexahedron, tetrahedron "
                        "or octahedron)");
  ss_deform_locator *P = calloc(1, sizeof *P);
  if (!P) return ss_error_nomem(err, "locator");
  ss_status st = ss_cx_copy(mesh, &P->mesh, err);
  if (st) goto fail;
  if (!(P->box = malloc(n * sizeof *P->box))) {
    st = ss_error_nomem(err, "cell boxes");
    goto fail;
  }
  for (int ki = 0; ki < 3; ki++) {
    const ss_cell_type t = kinds[ki];
    const int nv = ss_cell_nverts(t);
    for (size_t c = 0; c < mesh->nc[t]; c++) {
      cell_box *b = &P->box[P->nbox++];
      const ss_idx *v = ss_cx_cell(mesh, t, c);
      b->type = t;
      b->cell = c;
      for (int a = 0; a < 3; a++) {
        b->lo[a] = INFINITY;
        b->hi[a] = -INFINITY;
      }
      for (int k = 0; k < nv; k++)
        for (int a = 0; a < 3; a++) {
          const double x = mesh->x[(size_t)v[k] * 3 + (size_t)a];
          b->lo[a] = fmin(b->lo[a], x);
          b->hi[a] = fmax(b->hi[a], x);
        }
      for (int a = 0; a < 3; a++) {
        const double pad = 1e-6 * (b->hi[a] - b->lo[a]) + 1e-300;
        b->lo[a] -= pad;
        b->hi[a] += pad;
      }
    }
  }
  *out = P;
  return SS_OK;
fail:
  ss_deform_locator_free(P);
  return st;
}

void ss_deform_locator_free(ss_deform_locator *P) {
  if (!P) return;
  ss_cx_free(P->mesh);
  free(P->box);
  free(P);
}

/* Corner k of cell v. */
static const double *corner(const ss_cx *m, const ss_idx *v, int k) {
  return m->x + (size_t)v[k] * 3;
}

/* Hex parameters of x by Newton's method on the trilinear map from the
 * centre; 0 if it does not converge (then the cell is skipped). */
static int hex_params(const ss_cx *m, const ss_idx *v, const double x[3], double r[3]) {
  r[0] = r[1] = r[2] = 0.5;
  for (int it = 0; it < 60; it++) {
    double f[3] = {-x[0], -x[1], -x[2]}, J[3][3] = {{0}}, dr[3];
    for (int k = 0; k < 8; k++) {
      const unsigned b = ss_cube_corner_bits(3, k);
      const double *p = corner(m, v, k);
      double w = 1.0, dw[3];
      for (int a = 0; a < 3; a++)
        w *= ((b >> a) & 1u) ? r[a] : 1.0 - r[a];
      for (int j = 0; j < 3; j++) {
        dw[j] = ((b >> j) & 1u) ? 1.0 : -1.0;
        for (int a = 0; a < 3; a++)
          if (a != j) dw[j] *= ((b >> a) & 1u) ? r[a] : 1.0 - r[a];
      }
      for (int a = 0; a < 3; a++) {
        f[a] += w * p[a];
        for (int j = 0; j < 3; j++)
          J[a][j] += dw[j] * p[a];
      }
    }
    if (!ss_deform_solve3((const double(*)[3])J, f, dr)) return 0;
    double step = 0.0;
    for (int a = 0; a < 3; a++) {
      r[a] -= dr[a];
      step = fmax(step, fabs(dr[a]));
      if (!(fabs(r[a]) < 1e3)) return 0; /* diverging: far outside */
    }
    if (step < 1e-15) return 1;
  }
  return 0;
}

/* Parameters of x in the tet with corners (a, b, c, d) (barycentric weights
 * of b, c, d); 0 if flat. */
static int tet_params(const double *a, const double *b, const double *c, const double *d,
                      const double x[3], double r[3]) {
  double m[3][3], rhs[3];
  for (int i = 0; i < 3; i++) {
    m[i][0] = b[i] - a[i];
    m[i][1] = c[i] - a[i];
    m[i][2] = d[i] - a[i];
    rhs[i] = x[i] - a[i];
  }
  return ss_deform_solve3((const double(*)[3])m, rhs, r);
}

/* Parameters of x in cell (t, v) and how far outside it lies. */
static double params(const ss_cx *m, ss_cell_type t, const ss_idx *v, const double x[3],
                     double r[3]) {
  if (t == SS_HEX) {
    if (!hex_params(m, v, x, r)) return INFINITY;
    return ss_deform_violation(t, r);
  }
  if (t == SS_TET) {
    if (!tet_params(corner(m, v, 0), corner(m, v, 1), corner(m, v, 2), corner(m, v, 3), x,
                    r))
      return INFINITY;
    return ss_deform_violation(t, r);
  }
  /* octahedron: its four tets (0, 3, e2-side, e3-side) */
  double best = INFINITY;
  for (int q = 0; q < 4; q++) {
    const int ia = (q & 1) ? 4 : 1, ib = (q & 2) ? 5 : 2;
    double w[3], rr[3];
    if (!tet_params(corner(m, v, 0), corner(m, v, 3), corner(m, v, ia), corner(m, v, ib),
                    x, w))
      continue;
    const double w0 = 1.0 - w[0] - w[1] - w[2];
    const double viol = fmax(fmax(-w0, -w[0]), fmax(-w[1], -w[2]));
    rr[0] = w0 - w[0];
    rr[1] = (q & 1) ? -w[1] : w[1];
    rr[2] = (q & 2) ? -w[2] : w[2];
    if (viol < best) {
      best = viol;
      memcpy(r, rr, sizeof rr);
    }
  }
  return best;
}

void ss_deform_locate(const ss_deform_locator *P, const double x[3], ss_deform_loc *loc,
                      int *found) {
  *found = 0;
  for (size_t i = 0; i < P->nbox; i++) {
    const cell_box *b = &P->box[i];
    if (x[0] < b->lo[0] || x[0] > b->hi[0] || x[1] < b->lo[1] || x[1] > b->hi[1] ||
        x[2] < b->lo[2] || x[2] > b->hi[2])
      continue;
    double r[3];
    const double viol =
        params(P->mesh, b->type, ss_cx_cell(P->mesh, b->type, b->cell), x, r);
    if (viol <= SS_DEFORM_TOL) {
      ss_deform_clamp(b->type, r);
      loc->type = b->type;
      loc->cell = b->cell;
      memcpy(loc->r, r, sizeof r);
      *found = 1;
      return;
    }
  }
}
