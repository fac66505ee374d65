/* ss_cx.c — cell type tables and the complex container. */
#include "ss_cx.h"

#include <stdlib.h>
#include <string.h>

static const int nverts_tab[SS_NCELLTYPES] = {1, 2, 3, 4, 4, 8, 6};
static const int dim_tab[SS_NCELLTYPES] = {0, 1, 2, 2, 3, 3, 3};
static const int nroles_tab[SS_NCELLTYPES] = {1, 2, 2, 3, 2, 4, 3};
static const char *const name_tab[SS_NCELLTYPES] = {
    "corner",      "segment",    "triangle",  "quadrilateral",
    "tetrahedron", "hexahedron", "octahedron"};
static const char *const plural_tab[SS_NCELLTYPES] = {
    "corners",    "segments",  "triangles", "quadrilaterals",
    "tetrahedra", "hexahedra", "octahedra"};

static const int seg_edges[][2] = {{0, 1}};
static const int tri_edges[][2] = {{0, 1}, {1, 2}, {2, 0}};
static const int quad_edges[][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
static const int tet_edges[][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
static const int hex_edges[][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                   {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
/* every pair but the opposite ones (0,3), (1,4), (2,5) */
static const int oct_edges[][2] = {{0, 1}, {0, 2}, {0, 4}, {0, 5}, {1, 2}, {1, 3},
                                   {1, 5}, {2, 3}, {2, 4}, {3, 4}, {3, 5}, {4, 5}};
static const int nedges_tab[SS_NCELLTYPES] = {0, 1, 3, 4, 6, 12, 12};
static const int (*const edges_tab[SS_NCELLTYPES])[2] = {
    NULL, seg_edges, tri_edges, quad_edges, tet_edges, hex_edges, oct_edges};

int ss_cell_nverts(ss_cell_type t) {
  return nverts_tab[t];
}
int ss_cell_dim(ss_cell_type t) {
  return dim_tab[t];
}
int ss_cell_nroles(ss_cell_type t) {
  return nroles_tab[t];
}
const char *ss_cell_name(ss_cell_type t) {
  return name_tab[t];
}
const char *ss_cell_plural(ss_cell_type t) {
  return plural_tab[t];
}
int ss_cell_nedges(ss_cell_type t) {
  return nedges_tab[t];
}
void ss_cell_edge(ss_cell_type t, int e, int *a, int *b) {
  *a = edges_tab[t][e][0];
  *b = edges_tab[t][e][1];
}

/* Cyclic quad order 0 1 2 3 visits binary corners 00 10 11 01 (bit 0 = x). */
static const unsigned quad_bits[4] = {0u, 1u, 3u, 2u};
static const int quad_index[4] = {0, 1, 3, 2};

unsigned ss_cube_corner_bits(int d, int k) {
  if (d == 1) return (unsigned)k;
  if (d == 2) return quad_bits[k];
  return quad_bits[k & 3] | (unsigned)(k & 4);
}

int ss_cube_corner_index(int d, unsigned bits) {
  if (d == 1) return (int)bits;
  if (d == 2) return quad_index[bits & 3u];
  return quad_index[bits & 3u] | (int)(bits & 4u);
}

static int popcount3(unsigned v) {
  return (int)((v & 1u) + ((v >> 1) & 1u) + ((v >> 2) & 1u));
}

int ss_cell_role(ss_cell_type t, int i, int j) {
  if (i == j) return 0;
  switch (t) {
  case SS_QUAD:
    return popcount3(ss_cube_corner_bits(2, i) ^ ss_cube_corner_bits(2, j));
  case SS_HEX:
    return popcount3(ss_cube_corner_bits(3, i) ^ ss_cube_corner_bits(3, j));
  case SS_OCT:
    return (i - j == 3 || j - i == 3) ? 2 : 1;
  default:
    return 1;
  }
}

const char *ss_cell_defect(ss_cell_type t, const ss_idx *v, size_t nv) {
  int n = nverts_tab[t];
  for (int i = 0; i < n; i++) {
    if ((size_t)v[i] >= nv) return "vertex index out of range";
    for (int j = 0; j < i; j++)
      if (v[i] == v[j]) return "degenerate (a vertex repeated)";
  }
  return NULL;
}

ss_status ss_cx_new(int dim, ss_cx **out, ss_error *err) {
  *out = NULL;
  if (dim < 1 || dim > SS_MAXDIM)
    return ss_error_set(err, SS_EINPUT, "coordinate dimension %d is not in 1..%d", dim,
                        SS_MAXDIM);
  ss_cx *cx = calloc(1, sizeof *cx);
  if (!cx) return ss_error_nomem(err, "complex");
  cx->dim = dim;
  *out = cx;
  return SS_OK;
}

void ss_cx_free(ss_cx *cx) {
  if (!cx) return;
  free(cx->x);
  free(cx->vref);
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    free(cx->cells[t]);
    free(cx->cref[t]);
  }
  free(cx);
}

ss_status ss_cx_reserve_vertices(ss_cx *cx, size_t n, ss_error *err) {
  if (n <= cx->nv_cap) return SS_OK;
  if (n > (size_t)SS_IDX_NONE)
    return ss_error_set(err, SS_EINPUT, "too many vertices (%zu; at most %u)", n,
                        (unsigned)SS_IDX_NONE);
  double *x = realloc(cx->x, n * (size_t)cx->dim * sizeof *x);
  if (!x) return ss_error_nomem(err, "vertex coordinates");
  cx->x = x;
  int32_t *r = realloc(cx->vref, n * sizeof *r);
  if (!r) return ss_error_nomem(err, "vertex references");
  cx->vref = r;
  cx->nv_cap = n;
  return SS_OK;
}

ss_status ss_cx_reserve_cells(ss_cx *cx, ss_cell_type t, size_t n, ss_error *err) {
  if (n <= cx->nc_cap[t]) return SS_OK;
  ss_idx *c = realloc(cx->cells[t], n * (size_t)nverts_tab[t] * sizeof *c);
  if (!c) return ss_error_nomem(err, "cells");
  cx->cells[t] = c;
  int32_t *r = realloc(cx->cref[t], n * sizeof *r);
  if (!r) return ss_error_nomem(err, "cell references");
  cx->cref[t] = r;
  cx->nc_cap[t] = n;
  return SS_OK;
}

/* Amortised growth: double, starting at 16. */
static size_t grown(size_t cap) {
  return cap < 16 ? 16 : 2 * cap;
}

ss_status ss_cx_add_vertex(ss_cx *cx, const double *x, int32_t ref, ss_error *err) {
  if (cx->nv == cx->nv_cap) {
    size_t want = grown(cx->nv_cap);
    if (want > (size_t)SS_IDX_NONE) want = (size_t)SS_IDX_NONE;
    if (cx->nv >= want)
      return ss_error_set(err, SS_EINPUT, "too many vertices (at most %u)",
                          (unsigned)SS_IDX_NONE);
    ss_status st = ss_cx_reserve_vertices(cx, want, err);
    if (st) return st;
  }
  memcpy(cx->x + cx->nv * (size_t)cx->dim, x, (size_t)cx->dim * sizeof *x);
  cx->vref[cx->nv] = ref;
  cx->nv++;
  return SS_OK;
}

ss_status ss_cx_add_cell(ss_cx *cx, ss_cell_type t, const ss_idx *v, int32_t ref,
                         ss_error *err) {
  if (cx->nc[t] == cx->nc_cap[t]) {
    ss_status st = ss_cx_reserve_cells(cx, t, grown(cx->nc_cap[t]), err);
    if (st) return st;
  }
  memcpy(ss_cx_cell(cx, t, cx->nc[t]), v, (size_t)nverts_tab[t] * sizeof *v);
  cx->cref[t][cx->nc[t]] = ref;
  cx->nc[t]++;
  return SS_OK;
}

size_t ss_cx_ncells(const ss_cx *cx) {
  size_t n = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++)
    n += cx->nc[t];
  return n;
}

int ss_cx_topdim(const ss_cx *cx) {
  int d = -1;
  for (int t = 0; t < SS_NCELLTYPES; t++)
    if (cx->nc[t] && dim_tab[t] > d) d = dim_tab[t];
  return d;
}

ss_status ss_cx_copy(const ss_cx *cx, ss_cx **out, ss_error *err) {
  ss_cx *c = NULL;
  ss_status st = ss_cx_new(cx->dim, &c, err);
  if (st) return st;
  st = ss_cx_reserve_vertices(c, cx->nv, err);
  if (st) goto done;
  if (cx->nv) {
    memcpy(c->x, cx->x, cx->nv * (size_t)cx->dim * sizeof *c->x);
    memcpy(c->vref, cx->vref, cx->nv * sizeof *c->vref);
  }
  c->nv = cx->nv;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    st = ss_cx_reserve_cells(c, (ss_cell_type)t, cx->nc[t], err);
    if (st) goto done;
    if (cx->nc[t]) {
      memcpy(c->cells[t], cx->cells[t],
             cx->nc[t] * (size_t)nverts_tab[t] * sizeof *c->cells[t]);
      memcpy(c->cref[t], cx->cref[t], cx->nc[t] * sizeof *c->cref[t]);
    }
    c->nc[t] = cx->nc[t];
  }
done:
  if (st) {
    ss_cx_free(c);
    c = NULL;
  }
  *out = c;
  return st;
}

ss_status ss_cx_validate(const ss_cx *cx, ss_error *err) {
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (size_t i = 0; i < cx->nc[t]; i++) {
      const char *d =
          ss_cell_defect((ss_cell_type)t, ss_cx_cell(cx, (ss_cell_type)t, i), cx->nv);
      if (d) return ss_error_set(err, SS_EINPUT, "%s %zu: %s", name_tab[t], i + 1, d);
    }
  return SS_OK;
}
