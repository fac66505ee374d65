/* ss_local_marks.c — the patch boundary: the facets of a level's top cells,
 * those that occur once, and the marks of the vertices not on them, computed
 * from a level's own facets or derived from the coarser level's through the
 * split (ss_local_inner_marks_split). */
#include <stdlib.h>
#include <string.h>

#include "ss_local_impl.h"

/* Facets of the top cells, as sorted vertex quadruples (padded with
 * SS_IDX_NONE); a vertex is inner iff it lies in a top cell and no facet
 * holding it occurs once.  (Peeling, ss_local_level.c, leaves vertices in
 * no cell; the rule gives them the identity row, which must never be
 * read.) */
static const int hex_facets[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                     {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
static const int tet_facets[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

static int facet_eq(const ss_local_facet *a, const ss_local_facet *b) {
  return a->v[0] == b->v[0] && a->v[1] == b->v[1] && a->v[2] == b->v[2] &&
         a->v[3] == b->v[3];
}

/* Whether a comes before b on the words after the first (an order; only
 * equality matters). */
static int facet_less_tail(const ss_local_facet *a, const ss_local_facet *b) {
  for (int k = 1; k < 4; k++)
    if (a->v[k] != b->v[k]) return a->v[k] < b->v[k];
  return 0;
}

/* The nf facets f grouped so that equal ones are adjacent, into g: a counting
 * sort on the smallest vertex (nv of them), then an insertion sort within each
 * bucket, which holds the few facets a vertex is the smallest of.  Linear,
 * where qsort with a memcmp comparator cost a tenth of an extraction. */
static ss_status facet_group(const ss_local_facet *f, size_t nf, size_t nv,
                             ss_local_facet *g, ss_local_workspace *ws, ss_error *err) {
  if (!(ws->bucket =
            ss_local_ws_grow(ws->bucket, &ws->nbucket, nv + 2, sizeof *ws->bucket)))
    return ss_error_nomem(err, "patch boundary");
  size_t *ptr = ws->bucket;
  memset(ptr, 0, (nv + 2) * sizeof *ptr);
  for (size_t i = 0; i < nf; i++)
    ptr[f[i].v[0] + 2]++;
  for (size_t v = 0; v < nv; v++)
    ptr[v + 2] += ptr[v + 1];
  for (size_t i = 0; i < nf; i++)
    g[ptr[f[i].v[0] + 1]++] = f[i];
  for (size_t v = 0; v < nv; v++) /* ptr[v + 1] now ends bucket v */
    for (size_t i = ptr[v] + 1; i < ptr[v + 1]; i++)
      for (size_t j = i; j > ptr[v] && facet_less_tail(g + j, g + j - 1); j--) {
        const ss_local_facet t = g[j];
        g[j] = g[j - 1];
        g[j - 1] = t;
      }
  return SS_OK;
}

static void push_facet(ss_local_facet *f, size_t *nf, const ss_idx *cell, const int *loc,
                       int m) {
  ss_local_facet x = {{SS_IDX_NONE, SS_IDX_NONE, SS_IDX_NONE, SS_IDX_NONE}};
  for (int i = 0; i < m; i++)
    x.v[i] = cell[loc[i]];
  for (int i = 1; i < m; i++) /* insertion sort */
    for (int j = i; j > 0 && x.v[j - 1] > x.v[j]; j--) {
      ss_idx t = x.v[j];
      x.v[j] = x.v[j - 1];
      x.v[j - 1] = t;
    }
  f[(*nf)++] = x;
}

/* The facets of cx's top cells grouped so that equal ones are adjacent, in
 * the workspace: *g and *nf (scratch until the workspace's next use). */
static ss_status grouped_facets(const ss_cx *cx, ss_local_workspace *ws,
                                ss_local_facet **g, size_t *nf_out, ss_error *err) {
  size_t cap = 6 * cx->nc[SS_HEX] + 4 * cx->nc[SS_TET] + 8 * cx->nc[SS_OCT] +
               4 * cx->nc[SS_QUAD] + 3 * cx->nc[SS_TRIANGLE] + 1;
  if (!(ws->facet = ss_local_ws_grow(ws->facet, &ws->nfacet,
                                     2 * cap * sizeof(ss_local_facet), 1)))
    return ss_error_nomem(err, "patch boundary");
  ss_local_facet *f = ws->facet; /* the facets, then grouped after them */
  size_t nf = 0;
  const int topdim = ss_cx_topdim(cx);
  for (size_t i = 0; topdim == 3 && i < cx->nc[SS_HEX]; i++)
    for (int k = 0; k < 6; k++)
      push_facet(f, &nf, ss_cx_cell(cx, SS_HEX, i), hex_facets[k], 4);
  for (size_t i = 0; topdim == 3 && i < cx->nc[SS_TET]; i++)
    for (int k = 0; k < 4; k++)
      push_facet(f, &nf, ss_cx_cell(cx, SS_TET, i), tet_facets[k], 3);
  for (size_t i = 0; topdim == 3 && i < cx->nc[SS_OCT]; i++)
    for (int k = 0; k < 8; k++) {
      const int loc[3] = {k & 1 ? 3 : 0, k & 2 ? 4 : 1, k & 4 ? 5 : 2};
      push_facet(f, &nf, ss_cx_cell(cx, SS_OCT, i), loc, 3);
    }
  for (size_t i = 0; topdim == 2 && i < cx->nc[SS_QUAD]; i++)
    for (int k = 0; k < 4; k++) {
      const int loc[2] = {k, (k + 1) % 4};
      push_facet(f, &nf, ss_cx_cell(cx, SS_QUAD, i), loc, 2);
    }
  for (size_t i = 0; topdim == 2 && i < cx->nc[SS_TRIANGLE]; i++)
    for (int k = 0; k < 3; k++) {
      const int loc[2] = {k, (k + 1) % 3};
      push_facet(f, &nf, ss_cx_cell(cx, SS_TRIANGLE, i), loc, 2);
    }
  *g = f + cap;
  *nf_out = nf;
  return facet_group(f, nf, cx->nv, *g, ws, err);
}

/* The boundary facets of cx (the facets of its top cells that occur once),
 * in the workspace: *b and *nb (scratch until the workspace's next use). */
ss_status ss_local_boundary_facets(const ss_cx *cx, ss_local_workspace *ws,
                                   ss_local_facet **b, size_t *nb, ss_error *err) {
  ss_local_facet *g = NULL;
  size_t nf = 0, n = 0;
  ss_status st = grouped_facets(cx, ws, &g, &nf, err);
  if (st) return st;
  for (size_t i = 0; i < nf;) {
    size_t j = i + 1;
    while (j < nf && facet_eq(g + i, g + j))
      j++;
    if (j - i == 1) g[n++] = g[i];
    i = j;
  }
  *b = g;
  *nb = n;
  return SS_OK;
}

/* mark[v] = 1 for the vertices of cx's top cells, 0 for the others (nv + 1
 * bytes). */
static void top_marks(const ss_cx *cx, unsigned char *mark) {
  memset(mark, 0, cx->nv + 1);
  const int topdim = ss_cx_topdim(cx);
  for (int ty = 0; ty < SS_NCELLTYPES; ty++) {
    if (ss_cell_dim((ss_cell_type)ty) != topdim) continue;
    const size_t n = cx->nc[ty] * (size_t)ss_cell_nverts((ss_cell_type)ty);
    for (size_t i = 0; i < n; i++)
      mark[cx->cells[ty][i]] = 1;
  }
}

/* inner[v] = v lies in a top cell of cx and on none of its nb boundary
 * facets b. */
ss_status ss_local_boundary_marks(const ss_cx *cx, const ss_local_facet *b, size_t nb,
                                  unsigned char **out, ss_error *err) {
  unsigned char *inner = *out = malloc(cx->nv + 1);
  if (!inner) return ss_error_nomem(err, "patch boundary");
  top_marks(cx, inner);
  for (size_t i = 0; i < nb; i++)
    for (int k = 0; k < 4 && b[i].v[k] != SS_IDX_NONE; k++)
      inner[b[i].v[k]] = 0;
  return SS_OK;
}

ss_status ss_local_inner_marks(const ss_cx *cx, ss_local_workspace *ws,
                               unsigned char **out, ss_error *err) {
  ss_local_facet *b = NULL;
  size_t nb = 0;
  ss_status st = ss_local_boundary_facets(cx, ws, &b, &nb, err);
  return st ? st : ss_local_boundary_marks(cx, b, nb, out, err);
}

/* A hash of a facet's (sorted) vertices. */
static size_t facet_hash(const ss_local_facet *x) {
  uint64_t h = 0x9e3779b97f4a7c15u;
  for (int k = 0; k < 4; k++) {
    h ^= x->v[k];
    h *= 0xff51afd7ed558ccdu;
    h ^= h >> 29;
  }
  return (size_t)h;
}

/* Put x into the open-addressing set t (mask + 1 slots, empty slots all
 * SS_IDX_NONE), unless it is there. */
static void face_put(ss_local_facet *t, size_t mask, const ss_local_facet *x) {
  size_t h = facet_hash(x) & mask;
  while (t[h].v[0] != SS_IDX_NONE && !facet_eq(t + h, x))
    h = (h + 1) & mask;
  t[h] = *x;
}

static int face_has(const ss_local_facet *t, size_t mask, const ss_local_facet *x) {
  size_t h = facet_hash(x) & mask;
  while (t[h].v[0] != SS_IDX_NONE) {
    if (facet_eq(t + h, x)) return 1;
    h = (h + 1) & mask;
  }
  return 0;
}

/* The boundary marks of F = split(C) (ss_local_inner_marks(F->cx) to the
 * bit) from the coarse complex C as refined (after peeling), without
 * grouping F's facets, eight times as many as C's.  A fine vertex lies in the relative
 * interior of its carrier, the face of C spanned by its parents (ss_split.h:
 * a corner, an edge, a quad, a cell); the split refines every facet of C
 * into facets that occur as often as it does, so a fine facet occurs once
 * iff its coarse facet does, and f lies on such a fine facet iff its carrier
 * lies in a boundary facet Q of C, i.e. (its parents spanning a face of C)
 * iff its parents are a subset of Q's corners: a corner of Q, two of them
 * (an edge; two opposite corners of a quad span no edge, so no fine vertex
 * has them as parents), or all of Q.  Cells' centres (more parents than a
 * facet has corners) are never on the boundary.  g: C's nb boundary facets
 * (ss_local_boundary_facets).  inner[f] = f lies in a top cell of F and not
 * on the boundary. */
ss_status ss_local_inner_marks_split(const ss_cx *C, const ss_local_facet *g, size_t nb,
                                     const ss_cx *F, const ss_split *sp,
                                     unsigned char **out, ss_error *err) {
  size_t slots = 16;
  while (slots < 4 * 8 * nb) /* a facet and its at most 6 pairs, load <= 1/4 */
    slots *= 2;
  unsigned char *inner = *out = malloc(F->nv + 1), *bv = calloc(C->nv + 1, 1);
  ss_local_facet *t = malloc(slots * sizeof *t);
  if (!inner || !bv || !t) {
    free(bv);
    free(t);
    return ss_error_nomem(err, "patch boundary");
  }
  memset(t, 0xff, slots * sizeof *t); /* SS_IDX_NONE */
  for (size_t i = 0; i < nb; i++) {
    const ss_local_facet *q = g + i;
    int m = 0;
    while (m < 4 && q->v[m] != SS_IDX_NONE)
      bv[q->v[m++]] = 1;
    if (m >= 2) face_put(t, slots - 1, q);
    for (int a = 0; m > 2 && a < m; a++)
      for (int b = a + 1; b < m; b++) {
        const ss_local_facet e = {{q->v[a], q->v[b], SS_IDX_NONE, SS_IDX_NONE}};
        face_put(t, slots - 1, &e);
      }
  }
  top_marks(F, inner);
  for (size_t f = 0; f < F->nv; f++) {
    if (!inner[f]) continue;
    const size_t np = ss_split_npar(sp, f);
    const ss_idx *p = sp->parent + sp->ptr[f];
    if (np == 1)
      inner[f] = !bv[p[0]];
    else if (np <= 4) {
      ss_local_facet x = {{SS_IDX_NONE, SS_IDX_NONE, SS_IDX_NONE, SS_IDX_NONE}};
      for (size_t k = 0; k < np; k++) /* ascending already */
        x.v[k] = p[k];
      inner[f] = !face_has(t, slots - 1, &x);
    }
  }
  free(bv);
  free(t);
  return SS_OK;
}
