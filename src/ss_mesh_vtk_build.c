/* ss_mesh_vtk_build.c — an unstructured grid read from a VTK file (legacy or
 * XML) as a complex: cells by type, references, and point data as named
 * fields (ss_mesh_vtk_impl.h). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_mesh_vtk_impl.h"

void ss_vtk_grid_done(ss_vtk_grid *g) {
  free(g->pts);
  free(g->offsets);
  free(g->conn);
  free(g->types);
  for (size_t i = 0; i < g->npd; i++)
    free(g->pdata[i].val);
  for (size_t i = 0; i < g->ncd; i++)
    free(g->cdata[i].val);
  free(g->pdata);
  free(g->cdata);
  memset(g, 0, sizeof *g);
}

ss_status ss_vtk_slurp(const char *path, char **buf, size_t *len, ss_error *err) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return ss_error_set(err, SS_EIO, "%s: %s", path, strerror(errno));
  size_t cap = 1 << 16, n = 0;
  char *b = malloc(cap + 64);
  for (size_t r; b && (r = fread(b + n, 1, cap - n, fp)) > 0;) {
    n += r;
    if (n == cap) {
      char *nb = realloc(b, 2 * cap + 64);
      if (!nb) free(b);
      b = nb;
      cap *= 2;
    }
  }
  const int bad = ferror(fp);
  fclose(fp);
  if (!b) return ss_error_nomem(err, "VTU file");
  if (bad) {
    free(b);
    return ss_error_set(err, SS_EIO, "%s: read error", path);
  }
  b[n] = '\0';
  *buf = b;
  *len = n;
  return SS_OK;
}

ss_status ss_vtk_array_add(const char *path, ss_vtk_array **list, size_t *n,
                           const char *name, int ncomp, ss_vtk_array **a, ss_error *err) {
  /* room for a component suffix (_x, _12) within SS_FIELD_NAME_MAX */
  if (strlen(name) > SS_VTK_NAME_MAX)
    return ss_error_set(err, SS_EINPUT,
                        "%s: data array name '%.40s...' is longer than %d characters",
                        path, name, SS_VTK_NAME_MAX);
  ss_vtk_array *l = realloc(*list, (*n + 1) * sizeof *l);
  if (!l) return ss_error_nomem(err, "VTK data arrays");
  *list = l;
  *a = &l[(*n)++];
  memset(*a, 0, sizeof **a);
  snprintf((*a)->name, sizeof(*a)->name, "%s", name);
  (*a)->ncomp = ncomp;
  return SS_OK;
}

/* The complex's cell type of VTK cell type t (pyramids: SS_NCELLTYPES, one
 * half of an octahedron), or -1. */
static int cell_type(int t) {
  static const int vtk[] = {1, 3, 5, 9, 10, 12};
  for (int k = 0; k < 6; k++)
    if (vtk[k] == t) return k; /* SS_VERTEX .. SS_HEX in order */
  return t == 14 ? SS_NCELLTYPES : -1;
}

static const ss_vtk_array *find(const ss_vtk_array *a, size_t n, const char *name) {
  for (size_t i = 0; i < n; i++)
    if (!strcmp(a[i].name, name) && a[i].ncomp == 1) return &a[i];
  return NULL;
}

/* The number of field components of g (every point array but vref). */
static int field_count(const ss_vtk_grid *g, const ss_vtk_array *vref) {
  int nf = 0;
  for (size_t i = 0; i < g->npd; i++)
    if (&g->pdata[i] != vref)
      nf += g->pdata[i].ncomp > SS_MAXDIM ? SS_MAXDIM : g->pdata[i].ncomp;
  return nf;
}

/* Field names: NAME for a scalar, NAME_x/_y/_z for 3 components, else
 * NAME_0, NAME_1, ... */
static void field_names(const ss_vtk_grid *g, const ss_vtk_array *vref,
                        ss_mesh_fields *names) {
  static const char xyz[] = "xyz";
  int k = 0;
  for (size_t i = 0; i < g->npd; i++) {
    const ss_vtk_array *a = &g->pdata[i];
    if (a == vref) continue;
    for (int c = 0; c < a->ncomp; c++, k++) {
      char *s = names->name[k];
      if (a->ncomp == 1)
        snprintf(s, SS_FIELD_NAME_MAX, "%s", a->name);
      else if (a->ncomp == 3)
        snprintf(s, SS_FIELD_NAME_MAX, "%.48s_%c", a->name, xyz[c]);
      else
        snprintf(s, SS_FIELD_NAME_MAX, "%.48s_%d", a->name, c);
    }
  }
  names->n = k;
}

/* The vertices: points, fields, references. */
static ss_status add_vertices(const char *path, const ss_vtk_grid *g,
                              const ss_vtk_array *vref, ss_cx *cx, ss_error *err) {
  ss_status st = ss_cx_reserve_vertices(cx, g->np, err);
  const size_t dim = (size_t)cx->dim;
  for (size_t v = 0; v < g->np && !st; v++) {
    double x[SS_MAXDIM];
    size_t k = 0;
    for (; k < 3 && k < dim; k++)
      x[k] = g->pts[3 * v + k];
    for (size_t i = 0; i < g->npd; i++)
      if (&g->pdata[i] != vref)
        for (int c = 0; c < g->pdata[i].ncomp; c++)
          x[k++] = g->pdata[i].val[v * (size_t)g->pdata[i].ncomp + (size_t)c];
    for (k = 0; k < dim; k++)
      if (!isfinite(x[k]))
        return ss_error_set(err, SS_EINPUT, "%s: point %zu: %s %g is not a finite number",
                            path, v, k < 3 ? "coordinate" : "point data value", x[k]);
    double r = vref ? vref->val[v] : 0.0;
    if (r != floor(r) || r < INT32_MIN || r > INT32_MAX)
      return ss_error_set(err, SS_EINPUT, "%s: point %zu: vref %g is not an integer",
                          path, v, r);
    st = ss_cx_add_vertex(cx, x, (int32_t)r, err);
  }
  return st;
}

/* Cell i of g (VTK numbering from 0) as cell type *t with vertices v; j is
 * moved past a pyramid pair.  SS_EINPUT naming the cell. */
static ss_status take_cell(const char *path, const ss_vtk_grid *g,
                           const ss_vtk_array *kind, size_t *i, int *t, ss_idx *v,
                           ss_error *err) {
  const size_t c = *i;
  const int64_t b = c ? g->offsets[c - 1] : 0, e = g->offsets[c];
  *t = cell_type(g->types[c]);
  const int oct = *t == SS_NCELLTYPES && kind && kind->val[c] == SS_OCT &&
                  c + 1 < g->nc && g->types[c + 1] == 14 && kind->val[c + 1] == SS_OCT;
  if (*t < 0 || (*t == SS_NCELLTYPES && !oct))
    return ss_error_set(
        err, SS_EINPUT,
        "%s: cell %zu has VTK cell type %d, which is not supported (read: "
        "vertex 1, line 3, triangle 5, quad 9, tetra 10, hexahedron 12, "
        "and octahedra this program wrote as two pyramids 14)",
        path, c, g->types[c]);
  if (oct) *t = SS_OCT;
  const int want = oct ? 5 : ss_cell_nverts((ss_cell_type)*t);
  const int64_t e2 = oct ? g->offsets[c + 1] : e;
  if (e - b != want || (oct && e2 - e != 5))
    return ss_error_set(err, SS_EINPUT, "%s: cell %zu (%s) has %lld points, not %d", path,
                        c, ss_cell_name((ss_cell_type)*t), (long long)(e - b), want);
  int64_t p[10];
  for (int64_t k = b; k < e2; k++) {
    p[k - b] = g->conn[k];
    if (p[k - b] < 0 || (uint64_t)p[k - b] >= g->np)
      return ss_error_set(err, SS_EINPUT,
                          "%s: cell %zu: point index %lld is out of range 0..%zu", path,
                          c, (long long)p[k - b], g->np - 1);
  }
  if (oct) {
    /* ss_mesh_vtk.c's pyramids {1 2 4 5 0} and {1 5 4 2 3} */
    if (p[5] != p[0] || p[6] != p[3] || p[7] != p[2] || p[8] != p[1])
      return ss_error_set(err, SS_EINPUT,
                          "%s: cells %zu and %zu (kind 6) are not the two halves of an "
                          "octahedron",
                          path, c, c + 1);
    const int64_t o[6] = {p[4], p[0], p[1], p[9], p[2], p[3]};
    for (int k = 0; k < 6; k++)
      v[k] = (ss_idx)o[k];
    *i = c + 1;
  } else {
    for (int k = 0; k < want; k++)
      v[k] = (ss_idx)p[k];
  }
  const char *bad = ss_cell_defect((ss_cell_type)*t, v, g->np);
  if (bad) return ss_error_set(err, SS_EINPUT, "%s: cell %zu: %s", path, c, bad);
  return SS_OK;
}

ss_status ss_vtk_build(const char *path, const ss_vtk_grid *g, ss_cx **out,
                       ss_mesh_fields *names, ss_error *err) {
  *out = NULL;
  const ss_vtk_array *vref = find(g->pdata, g->npd, "vref");
  const ss_vtk_array *cref = find(g->cdata, g->ncd, "ref");
  const ss_vtk_array *kind = find(g->cdata, g->ncd, "kind");
  if (vref && !vref->integer) vref = NULL; /* a field that happens to be named so */
  if (cref && !cref->integer) cref = NULL;
  if (kind && !kind->integer) kind = NULL;
  const int nf = field_count(g, vref);
  if (nf > SS_MAXDIM - 3)
    return ss_error_set(
        err, SS_EINPUT,
        "%s: the point data have %d components; a mesh carries at most %d "
        "fields",
        path, nf, SS_MAXDIM - 3);
  if (g->np == 0)
    return ss_error_set(err, SS_EINPUT, "%s: no points: an empty mesh", path);
  int dim = 3 + nf;
  if (!nf) {
    int flat = 1;
    for (size_t i = 0; i < g->nc && flat; i++)
      if (g->types[i] == 10 || g->types[i] == 12 || g->types[i] == 14) flat = 0;
    for (size_t v = 0; v < g->np && flat; v++)
      if (g->pts[3 * v + 2] != 0.0) flat = 0;
    if (flat) dim = 2;
  }
  ss_cx *cx = NULL;
  ss_status st = ss_cx_new(dim, &cx, err);
  if (!st) st = add_vertices(path, g, vref, cx, err);
  for (size_t i = 0; i < g->nc && !st; i++) {
    const size_t first = i;
    int t;
    ss_idx v[SS_MAXCELLVERTS];
    if ((st = take_cell(path, g, kind, &i, &t, v, err))) break;
    const double r = cref ? cref->val[first] : 0.0;
    if (r != floor(r) || r < INT32_MIN || r > INT32_MAX)
      st = ss_error_set(err, SS_EINPUT, "%s: cell %zu: ref %g is not an integer", path,
                        first, r);
    else
      st = ss_cx_add_cell(cx, (ss_cell_type)t, v, (int32_t)r, err);
  }
  if (st) {
    ss_cx_free(cx);
    return st;
  }
  if (names) field_names(g, vref, names);
  *out = cx;
  return SS_OK;
}
