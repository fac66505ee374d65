/* ss_limit.c — the limit evaluator's object: built on a hex mesh (the scheme
 * and mesh checked, the tricubic B-spline rule verified), its options and
 * statistics, freed.  The walk is in ss_limit_walk.c, the cache of patch
 * states in ss_limit_state.c (method in ss_limit.h). */
#include "ss_limit.h"

#include <complex.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit_impl.h"

size_t ss_limit_ncells(const ss_limit *L) {
  return L->mesh->nc[SS_HEX];
}

size_t ss_limit_nfields(const ss_limit *L) {
  return L->nf;
}

ss_limit_stats ss_limit_get_stats(const ss_limit *L) {
  return L->stats;
}

void ss_limit_set_tensor(ss_limit *L, int on) {
  L->tensor = on != 0;
}

void ss_limit_free(ss_limit *L) {
  if (!L) return;
  for (size_t i = 0; i < L->nst; i++)
    ss_lim_state_free(L->st[i]);
  free(L->st);
  free(L->tab);
  if (L->cell)
    for (size_t c = 0; c < L->mesh->nc[SS_HEX]; c++)
      free(L->cell[c].src);
  free(L->cell);
  free(L->loc);
  free(L->fld);
  ss_lim_adj_free(&L->adj);
  ss_cx_free(L->mesh);
  free(L);
}

/* SS_EINPUT naming the first field value that is not finite. */
static ss_status check_fields(size_t nv, size_t nf, const double *fields, ss_error *err) {
  if (nf && !fields)
    return ss_error_set(err, SS_EINPUT, "limit evaluation: %zu fields but no values", nf);
  for (size_t v = 0; v < nv; v++)
    for (size_t i = 0; i < nf; i++)
      if (!isfinite(fields[v * nf + i]))
        return ss_error_set(err, SS_EINPUT,
                            "limit evaluation: field %zu of vertex %zu is %g, not a "
                            "finite number",
                            i + 1, v + 1, fields[v * nf + i]);
  return SS_OK;
}

/* Whether crease cell v (type t) is a face, edge or corner of hex h: its
 * corners' binary coordinates in h agree in 3 - dim(t) bits. */
static int on_hex(const ss_cx *cx, size_t h, ss_cell_type t, const ss_idx *v) {
  const ss_idx *hv = ss_cx_cell(cx, SS_HEX, h);
  unsigned agree = 7u, first = 0;
  for (int j = 0; j < ss_cell_nverts(t); j++) {
    int k = -1;
    for (int i = 0; i < 8; i++)
      if (hv[i] == v[j]) k = i;
    if (k < 0) return 0;
    unsigned b = ss_cube_corner_bits(3, k);
    if (!j) first = b;
    agree &= ~(b ^ first);
  }
  int nagree = (int)(agree & 1u) + (int)((agree >> 1) & 1u) + (int)((agree >> 2) & 1u);
  return nagree == 3 - ss_cell_dim(t);
}

/* Why crease cell v (type t, not on any hex) is not: its vertices on no
 * hexahedron, on no common one, or corners of hexahedron h that span no
 * edge or face of it (a diagonal). */
static void why_off(const ss_lim_adj *a, ss_cell_type t, const ss_idx *v, char *buf,
                    size_t n) {
  const ss_cx *cx = a->cx;
  const int nv = ss_cell_nverts(t);
  for (int j = 0; j < nv; j++)
    if (a->vptr[v[j]] == a->vptr[v[j] + 1]) {
      snprintf(buf, n, "its vertex %lu is on no hexahedron", (unsigned long)v[j] + 1);
      return;
    }
  for (size_t i = a->vptr[v[0]]; i < a->vptr[v[0] + 1]; i++) {
    const size_t h = a->vcell[i];
    const ss_idx *hv = ss_cx_cell(cx, SS_HEX, h);
    int all = 1;
    for (int j = 0; j < nv && all; j++) {
      int in = 0;
      for (int k = 0; k < 8; k++)
        in |= hv[k] == v[j];
      all = in;
    }
    if (all) {
      snprintf(buf, n, "its vertices are corners of hexahedron %zu but %s", h + 1,
               t == SS_SEGMENT ? "not the ends of one of its edges (a diagonal)"
                               : "not one of its faces");
      return;
    }
  }
  snprintf(buf, n, "its vertices are not corners of one hexahedron");
}

/* SS_EINPUT naming the first crease cell (vertex cell, segment, quad) that
 * is no corner, edge or face of a hex, its vertices (the file's numbers) and
 * why: a patch holds the cells on its hexes only, though subdivide refines
 * such a cell as a crease. */
static ss_status check_creases(const ss_lim_adj *a, ss_error *err) {
  const ss_cx *cx = a->cx;
  const ss_cell_type ts[] = {SS_VERTEX, SS_SEGMENT, SS_QUAD};
  for (size_t i = 0; i < sizeof ts / sizeof ts[0]; i++)
    for (size_t c = 0; c < cx->nc[ts[i]]; c++) {
      const ss_idx *v = ss_cx_cell(cx, ts[i], c);
      int found = 0;
      for (size_t j = a->vptr[v[0]]; j < a->vptr[v[0] + 1] && !found; j++)
        found = on_hex(cx, a->vcell[j], ts[i], v);
      if (found) continue;
      char verts[64] = "", why[160];
      for (int j = 0, at = 0; j < ss_cell_nverts(ts[i]) && at < (int)sizeof verts; j++)
        at += snprintf(verts + at, sizeof verts - (size_t)at, "%s%lu", j ? " " : "",
                       (unsigned long)v[j] + 1);
      why_off(a, ts[i], v, why, sizeof why);
      return ss_error_set(err, SS_EINPUT,
                          "limit evaluation: %s %zu (vertices %s) is not %s of any "
                          "hexahedron: %s; subdivide refines it as a crease, but "
                          "the limit is evaluated only with creases on the hexahedra",
                          ss_cell_name(ts[i]), c + 1, verts,
                          ts[i] == SS_QUAD      ? "a face"
                          : ts[i] == SS_SEGMENT ? "an edge"
                                                : "a corner",
                          why);
    }
  return SS_OK;
}

ss_status ss_limit_new(const ss_scheme *s, const ss_cx *mesh, ss_limit **out,
                       ss_error *err) {
  return ss_limit_new_fields(s, mesh, 0, NULL, out, err);
}

ss_status ss_limit_new_fields(const ss_scheme *s, const ss_cx *mesh, size_t nf,
                              const double *fields, ss_limit **out, ss_error *err) {
  ss_status st;
  *out = NULL;
  if (ss_scheme_split_kind(s) != SS_SPLIT_MULTILINEAR || !ss_scheme_accepts(s, SS_HEX) ||
      ss_scheme_reach(s) != 1)
    return ss_error_set(
        err, SS_EINPUT,
        "limit evaluation needs a scheme that splits hexahedra "
        "multilinearly with a one-ring rule (mlca, ccsolid); %s is not one",
        ss_scheme_name(s));
  if (mesh->dim != 3)
    return ss_error_set(err, SS_EINPUT,
                        "limit evaluation needs a mesh with 3 coordinates, not %d",
                        mesh->dim);
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    int crease = t == SS_VERTEX || t == SS_SEGMENT || t == SS_QUAD;
    if (t != SS_HEX && mesh->nc[t] && (!crease || !ss_scheme_accepts(s, (ss_cell_type)t)))
      return ss_error_set(err, SS_EINPUT,
                          "limit evaluation takes meshes of hexahedra only (with "
                          "corners, segments and quadrilaterals as creases where scheme "
                          "%s takes them); this one has %zu %s",
                          ss_scheme_name(s), mesh->nc[t],
                          ss_cell_plural((ss_cell_type)t));
  }
  if (!mesh->nc[SS_HEX])
    return ss_error_set(err, SS_EINPUT, "limit evaluation: the mesh has no hexahedra");
  if ((st = ss_cx_validate(mesh, err)) || (st = check_fields(mesh->nv, nf, fields, err)))
    return st;
  ss_limit *L = calloc(1, sizeof *L);
  if (!L) return ss_error_nomem(err, "limit evaluator");
  L->s = s;
  L->tensor = 1;
  if (nf) {
    if (mesh->nv > SIZE_MAX / sizeof *L->fld / nf ||
        !(L->fld = malloc(mesh->nv * nf * sizeof *L->fld))) {
      st = ss_error_nomem(err, "limit fields");
      goto done;
    }
    memcpy(L->fld, fields, mesh->nv * nf * sizeof *L->fld);
    L->nf = nf;
  }
  if ((st = ss_cx_copy(mesh, &L->mesh, err))) goto done;
  if ((st = ss_lim_adj_build(L->mesh, &L->adj, err)) ||
      (st = check_creases(&L->adj, err)))
    goto done;
  L->loc = malloc((mesh->nv + 1) * sizeof *L->loc);
  L->cell = calloc(mesh->nc[SS_HEX], sizeof *L->cell);
  L->captab = 64;
  L->tab = calloc(L->captab, sizeof *L->tab);
  if (!L->loc || !L->cell || !L->tab) {
    st = ss_error_nomem(err, "limit evaluator");
    goto done;
  }
  for (size_t v = 0; v < mesh->nv; v++)
    L->loc[v] = -1;
  for (size_t c = 0; c < mesh->nc[SS_HEX]; c++)
    L->cell[c].state = SIZE_MAX;
  st = ss_lim_check_bspline(s, err);
done:
  if (st)
    ss_limit_free(L);
  else
    *out = L;
  return st;
}
