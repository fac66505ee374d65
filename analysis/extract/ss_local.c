/* ss_local.c — local subdivision matrices read from the global refinement
 * operator of a refined star.  The method and the checks are in ss_local.h. */
#include "ss_local.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_gsl.h"

#define MAXLEVELS 8       /* levels of refinement tried at most */
#define MAXCELLS  6000000 /* refuse to refine a patch beyond this many cells */
#define STAT_TOL  1e-12   /* S on consecutive levels must agree to this */

/* One level of the refined star. */
typedef struct {
  ss_cx *cx;             /* the complex of this level */
  ss_split *split;       /* parents of this level's vertices (NULL on level 0) */
  gsl_spmatrix *R;       /* operator to the next level, CSR (NULL on the last) */
  ss_star_coord *abs;    /* chart coordinates, cx->nv */
  ss_star_coord *rel;    /* coordinates relative to p (levels >= lc), cx->nv */
  ss_idx *index;         /* the vertices hashed by rel, for lookup: open
                            addressing, mask + 1 slots, SS_IDX_NONE empty */
  size_t mask;           /* slots - 1 (a power of two minus one) */
  unsigned char *inner;  /* vertex not on the patch boundary */
  unsigned char *rows;   /* the finest level an attempt or a ring reads
                            (add_level's keep): the vertices whose rows into
                            this level were computed, the inner ones inside
                            Omega_w (complete_rows adds the others when
                            needed); NULL: every inner vertex's */
  unsigned char *cinner; /* schemes reaching 2 rings: vertex not on the
                            boundary of the complex refined into the next
                            level (after peeling), else NULL */
} level;

/* Extraction workspace (kept in ss_local.levels when asked). */
typedef struct ss_local_levels {
  const ss_scheme *scheme; /* the scheme */
  ss_star *star;           /* the star (level 0 is its complex) */
  int lc;                  /* first level on which p is a vertex */
  ss_star_coord cp;        /* p's chart coordinates on level lc */
  int nlev;                /* levels built */
  level lev[MAXLEVELS];    /* levels 0 .. nlev-1 */
  const ss_progress *prog; /* progress reports (may be NULL) */
  ss_local_workspace *ws;  /* scratch memory (never NULL while a level is
                              built or an attempt made; NULL in kept levels) */
} work;

ss_local_workspace *ss_local_workspace_new(void) {
  return calloc(1, sizeof(ss_local_workspace));
}

/* Free w's buffers and empty it (w itself stays). */
static void ws_release(ss_local_workspace *w) {
  free(w->dense);
  free(w->colmap);
  free(w->mark);
  free(w->facet);
  free(w->bucket);
  memset(w, 0, sizeof *w);
}

void ss_local_workspace_free(ss_local_workspace *w) {
  if (!w) return;
  ws_release(w);
  free(w);
}

/* A block of at least n elements of size sz in place of p (capacity *cap):
 * p itself when it holds them, else a larger block (p freed: its contents
 * are scratch).  NULL when out of memory (p freed, *cap 0). */
static void *ws_grow(void *p, size_t *cap, size_t n, size_t sz) {
  if (p && n <= *cap) return p;
  free(p);
  p = malloc((n + 1) * sz);
  *cap = p ? n : 0;
  return p;
}

int ss_local_label_norm(const ss_star_coord *c) {
  int m = 0;
  for (int i = 0; i < c->n; i++)
    m = abs(c->val[i]) > m ? abs(c->val[i]) : m;
  return m;
}

/* ---- sparse coordinate arithmetic ---- */

/* sum_i mult[i] * c[i] / div, which must be an integer vector with at most
 * SS_STAR_MAXSUPP nonzeros.  Returns 0 on success, -1 otherwise. */
static int lincomb(int m, const ss_star_coord *const *c, const int *mult, int div,
                   ss_star_coord *out) {
  int32_t idx[8 * SS_STAR_MAXSUPP];
  long val[8 * SS_STAR_MAXSUPP];
  int n = 0;
  for (int i = 0; i < m; i++)
    for (int e = 0; e < c[i]->n; e++) {
      int j = 0;
      while (j < n && idx[j] != c[i]->idx[e])
        j++;
      if (j == n) {
        if (n == 8 * SS_STAR_MAXSUPP) return -1;
        idx[n] = c[i]->idx[e];
        val[n++] = 0;
      }
      val[j] += (long)mult[i] * c[i]->val[e];
    }
  int32_t oi[SS_STAR_MAXSUPP], ov[SS_STAR_MAXSUPP];
  int k = 0;
  for (int j = 0; j < n; j++) {
    if (val[j] == 0) continue;
    if (val[j] % div != 0 || k == SS_STAR_MAXSUPP) return -1;
    oi[k] = idx[j];
    ov[k++] = (int32_t)(val[j] / div);
  }
  *out = ss_star_coord_make(k, oi, ov);
  return 0;
}

/* 2 * (the mean of the np parents' coordinates), which must be an integer
 * vector with at most SS_STAR_MAXSUPP nonzeros: lincomb(np, par, {2, ..},
 * np, out) to the bit, the entries merged in index order as they come (the
 * parents' entries are few and each parent's ascending).  0 or -1. */
static int child_coord(int np, const ss_star_coord *const *par, ss_star_coord *out) {
  if (np == 1) { /* a coarse vertex: its coordinates doubled */
    *out = *par[0];
    for (int e = 0; e < out->n; e++)
      out->val[e] = (int32_t)(2L * par[0]->val[e]);
    return 0;
  }
  int32_t idx[8 * SS_STAR_MAXSUPP];
  long val[8 * SS_STAR_MAXSUPP];
  int n = 0;
  for (int i = 0; i < np; i++)
    for (int e = 0; e < par[i]->n; e++) {
      const int32_t x = par[i]->idx[e];
      int j = n;
      while (j > 0 && idx[j - 1] > x)
        j--;
      if (j > 0 && idx[j - 1] == x) {
        val[j - 1] += 2L * par[i]->val[e];
        continue;
      }
      if (n == 8 * SS_STAR_MAXSUPP) return -1;
      for (int u = n; u > j; u--) { /* a loop: memmove would be a call */
        idx[u] = idx[u - 1];
        val[u] = val[u - 1];
      }
      idx[j] = x;
      val[j] = 2L * par[i]->val[e];
      n++;
    }
  ss_star_coord c;
  c.n = 0;
  for (int j = 0; j < n; j++) {
    if (val[j] == 0) continue;
    if (val[j] % np != 0 || c.n == SS_STAR_MAXSUPP) return -1;
    c.idx[c.n] = idx[j];
    c.val[c.n++] = (int32_t)(val[j] / np);
  }
  for (int i = c.n; i < SS_STAR_MAXSUPP; i++) { /* as ss_star_coord_make leaves them */
    c.idx[i] = -1;
    c.val[i] = 0;
  }
  *out = c;
  return 0;
}

/* ---- the levels ---- */

/* A hash of a coordinate vector (of its nonzero entries: the unused slots
 * of equal vectors agree anyway). */
static size_t coord_hash(const ss_star_coord *c) {
  uint64_t h = (uint64_t)(c->n + 1) * 0x9e3779b97f4a7c15u;
  for (int i = 0; i < c->n; i++) {
    h ^= (uint64_t)(uint32_t)c->idx[i] << 32 | (uint32_t)c->val[i];
    h *= 0xff51afd7ed558ccdu;
    h ^= h >> 29;
  }
  return (size_t)h;
}

/* The slot of L's index holding the vertex with relative coordinates c, or
 * the empty slot where it would go. */
static size_t slot_of(const level *L, const ss_star_coord *c) {
  size_t h = coord_hash(c) & L->mask;
  while (L->index[h] != SS_IDX_NONE && ss_star_coord_cmp(L->rel + L->index[h], c) != 0)
    h = (h + 1) & L->mask;
  return h;
}

/* Vertex with relative coordinates c on level l, or SIZE_MAX. */
static size_t lookup(const level *L, const ss_star_coord *c) {
  const ss_idx v = L->index[slot_of(L, c)];
  return v == SS_IDX_NONE ? SIZE_MAX : (size_t)v;
}

/* Facets of the top cells, as sorted vertex quadruples (padded with
 * SS_IDX_NONE); a vertex is inner iff it lies in a top cell and no facet
 * holding it occurs once.  (Peeling, below, leaves vertices in no cell; the
 * rule gives them the identity row, which must never be read.) */
static const int hex_facets[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                     {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
static const int tet_facets[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

typedef struct {
  ss_idx v[4];
} facet;

static int facet_eq(const facet *a, const facet *b) {
  return a->v[0] == b->v[0] && a->v[1] == b->v[1] && a->v[2] == b->v[2] &&
         a->v[3] == b->v[3];
}

/* Whether a comes before b on the words after the first (an order; only
 * equality matters). */
static int facet_less_tail(const facet *a, const facet *b) {
  for (int k = 1; k < 4; k++)
    if (a->v[k] != b->v[k]) return a->v[k] < b->v[k];
  return 0;
}

/* The nf facets f grouped so that equal ones are adjacent, into g: a counting
 * sort on the smallest vertex (nv of them), then an insertion sort within each
 * bucket, which holds the few facets a vertex is the smallest of.  Linear,
 * where qsort with a memcmp comparator cost a tenth of an extraction. */
static ss_status facet_group(const facet *f, size_t nf, size_t nv, facet *g,
                             ss_local_workspace *ws, ss_error *err) {
  if (!(ws->bucket = ws_grow(ws->bucket, &ws->nbucket, nv + 2, sizeof *ws->bucket)))
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
        const facet t = g[j];
        g[j] = g[j - 1];
        g[j - 1] = t;
      }
  return SS_OK;
}

static void push_facet(facet *f, size_t *nf, const ss_idx *cell, const int *loc, int m) {
  facet x = {{SS_IDX_NONE, SS_IDX_NONE, SS_IDX_NONE, SS_IDX_NONE}};
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
static ss_status grouped_facets(const ss_cx *cx, ss_local_workspace *ws, facet **g,
                                size_t *nf_out, ss_error *err) {
  size_t cap = 6 * cx->nc[SS_HEX] + 4 * cx->nc[SS_TET] + 8 * cx->nc[SS_OCT] +
               4 * cx->nc[SS_QUAD] + 3 * cx->nc[SS_TRIANGLE] + 1;
  if (!(ws->facet = ws_grow(ws->facet, &ws->nfacet, 2 * cap * sizeof(facet), 1)))
    return ss_error_nomem(err, "patch boundary");
  facet *f = ws->facet; /* the facets, then grouped after them */
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
static ss_status boundary_facets(const ss_cx *cx, ss_local_workspace *ws, facet **b,
                                 size_t *nb, ss_error *err) {
  facet *g = NULL;
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
static ss_status boundary_marks(const ss_cx *cx, const facet *b, size_t nb,
                                unsigned char **out, ss_error *err) {
  unsigned char *inner = *out = malloc(cx->nv + 1);
  if (!inner) return ss_error_nomem(err, "patch boundary");
  top_marks(cx, inner);
  for (size_t i = 0; i < nb; i++)
    for (int k = 0; k < 4 && b[i].v[k] != SS_IDX_NONE; k++)
      inner[b[i].v[k]] = 0;
  return SS_OK;
}

static ss_status inner_marks(const ss_cx *cx, ss_local_workspace *ws, unsigned char **out,
                             ss_error *err) {
  facet *b = NULL;
  size_t nb = 0;
  ss_status st = boundary_facets(cx, ws, &b, &nb, err);
  return st ? st : boundary_marks(cx, b, nb, out, err);
}

/* A hash of a facet's (sorted) vertices. */
static size_t facet_hash(const facet *x) {
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
static void face_put(facet *t, size_t mask, const facet *x) {
  size_t h = facet_hash(x) & mask;
  while (t[h].v[0] != SS_IDX_NONE && !facet_eq(t + h, x))
    h = (h + 1) & mask;
  t[h] = *x;
}

static int face_has(const facet *t, size_t mask, const facet *x) {
  size_t h = facet_hash(x) & mask;
  while (t[h].v[0] != SS_IDX_NONE) {
    if (facet_eq(t + h, x)) return 1;
    h = (h + 1) & mask;
  }
  return 0;
}

/* The boundary marks of F = split(C) (inner_marks(F->cx) to the bit) from
 * the coarse complex C as refined (after peeling), without grouping F's
 * facets, eight times as many as C's.  A fine vertex lies in the relative
 * interior of its carrier, the face of C spanned by its parents (ss_split.h:
 * a corner, an edge, a quad, a cell); the split refines every facet of C
 * into facets that occur as often as it does, so a fine facet occurs once
 * iff its coarse facet does, and f lies on such a fine facet iff its carrier
 * lies in a boundary facet Q of C, i.e. (its parents spanning a face of C)
 * iff its parents are a subset of Q's corners: a corner of Q, two of them
 * (an edge; two opposite corners of a quad span no edge, so no fine vertex
 * has them as parents), or all of Q.  Cells' centres (more parents than a
 * facet has corners) are never on the boundary.  g: C's nb boundary facets
 * (boundary_facets).  inner[f] = f lies in a top cell of F and not on the
 * boundary. */
static ss_status inner_marks_split(const ss_cx *C, const facet *g, size_t nb,
                                   const ss_cx *F, const ss_split *sp,
                                   unsigned char **out, ss_error *err) {
  size_t slots = 16;
  while (slots < 4 * 8 * nb) /* a facet and its at most 6 pairs, load <= 1/4 */
    slots *= 2;
  unsigned char *inner = *out = malloc(F->nv + 1), *bv = calloc(C->nv + 1, 1);
  facet *t = malloc(slots * sizeof *t);
  if (!inner || !bv || !t) {
    free(bv);
    free(t);
    return ss_error_nomem(err, "patch boundary");
  }
  memset(t, 0xff, slots * sizeof *t); /* SS_IDX_NONE */
  for (size_t i = 0; i < nb; i++) {
    const facet *q = g + i;
    int m = 0;
    while (m < 4 && q->v[m] != SS_IDX_NONE)
      bv[q->v[m++]] = 1;
    if (m >= 2) face_put(t, slots - 1, q);
    for (int a = 0; m > 2 && a < m; a++)
      for (int b = a + 1; b < m; b++) {
        const facet e = {{q->v[a], q->v[b], SS_IDX_NONE, SS_IDX_NONE}};
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
      facet x = {{SS_IDX_NONE, SS_IDX_NONE, SS_IDX_NONE, SS_IDX_NONE}};
      for (size_t k = 0; k < np; k++) /* ascending already */
        x.v[k] = p[k];
      inner[f] = !face_has(t, slots - 1, &x);
    }
  }
  free(bv);
  free(t);
  return SS_OK;
}

/* Relative coordinates, lookup order and boundary marks of level l >= lc. */
static ss_status finish_level(work *W, int l, ss_error *err) {
  level *L = W->lev + l;
  const size_t nv = L->cx->nv;
  size_t slots = 4;
  while (slots < 2 * nv)
    slots *= 2;
  L->rel = malloc((nv + 1) * sizeof *L->rel);
  L->index = malloc(slots * sizeof *L->index);
  if (!L->rel || !L->index) return ss_error_nomem(err, "local coordinates");
  L->mask = slots - 1;
  if (W->cp.n == 0) /* p is the chart's origin: relative = absolute */
    memcpy(L->rel, L->abs, nv * sizeof *L->rel);
  else {
    const ss_star_coord *c[2];
    const int mult[2] = {1, -(1 << (l - W->lc))};
    c[1] = &W->cp;
    for (size_t v = 0; v < nv; v++) {
      c[0] = L->abs + v;
      if (lincomb(2, c, mult, 1, L->rel + v))
        return ss_error_set(err, SS_EINTERNAL,
                            "local coordinates of vertex %zu on level %d have too many "
                            "nonzero entries",
                            v, l);
    }
  }
  memset(L->index, 0xff, slots * sizeof *L->index); /* SS_IDX_NONE */
  for (size_t v = 0; v < nv; v++) {
    const size_t h = slot_of(L, L->rel + v);
    if (L->index[h] != SS_IDX_NONE)
      return ss_error_set(err, SS_EINTERNAL, "two vertices of level %d share coordinates",
                          l);
    L->index[h] = (ss_idx)v;
  }
  return L->inner ? SS_OK : inner_marks(L->cx, W->ws, &L->inner, err);
}

/* Peel level l (l > 0, p a vertex) before it is refined: with the distance
 * of a vertex from p counted in steps between vertices that share a cell (the
 * max-norm in grid units on a cube grid, whatever the chart), drop the cells
 * with a vertex at the largest distance r, if r >= PEEL_FROM.  Level l + 1
 * then reaches 2(r - 1) instead of 2r in that direction: the patch still
 * grows from level to level (so a boundary effect cannot repeat itself and
 * pass the stationarity check) but each level costs about ((r - 1) / r)^3 of
 * the unpeeled one (27/64 on level 2 of a vertex star).
 * The inner marks of level l stay as they are: they say which rows of the
 * operator into level l are complete, and that operator was built before the
 * peeling.  The vertices of dropped cells stay, in no cell; their children
 * on level l + 1 are in no cell either, hence not inner.  Too much peeling can
 * only cost room (a deeper level), never a wrong row: every row read belongs
 * to an inner vertex of the complex the operator was built from. */
#define PEEL_FROM 4
/* With `near` (marks of L's vertices) instead: drop every cell with a vertex
 * farther from p than margin plus the farthest marked vertex (the ring's
 * deeper levels need only a neighbourhood of Omega_w). */
static ss_status peel(level *L, const unsigned char *near, int margin, ss_error *err) {
  ss_cx *cx = L->cx;
  const size_t nv = cx->nv;
  const ss_star_coord zero = ss_star_coord_make(0, NULL, NULL);
  const size_t p = lookup(L, &zero);
  if (p == SIZE_MAX) return SS_OK; /* p is no vertex yet: nothing to measure from */
  /* vertex -> cells incidence, cells numbered across types */
  size_t base[SS_NCELLTYPES + 1] = {0};
  for (int t = 0; t < SS_NCELLTYPES; t++)
    base[t + 1] = base[t] + cx->nc[t];
  size_t *ptr = calloc(nv + 2, sizeof *ptr), *inc = NULL, *queue = NULL;
  int *dist = malloc((nv + 1) * sizeof *dist);
  size_t ninc = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++)
    ninc += cx->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t);
  inc = malloc((ninc + 1) * sizeof *inc);
  queue = malloc((nv + 1) * sizeof *queue);
  if (!ptr || !dist || !inc || !queue) {
    free(ptr), free(dist), free(inc), free(queue);
    return ss_error_nomem(err, "peeling");
  }
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (size_t i = 0; i < cx->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t); i++)
      ptr[cx->cells[t][i] + 2]++;
  for (size_t v = 0; v < nv; v++)
    ptr[v + 2] += ptr[v + 1];
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    const int n = ss_cell_nverts((ss_cell_type)t);
    for (size_t i = 0; i < cx->nc[t] * (size_t)n; i++)
      inc[ptr[cx->cells[t][i] + 1]++] = base[t] + i / (size_t)n;
  }
  /* breadth-first distances from p; ptr[v] .. ptr[v + 1] are v's cells */
  for (size_t v = 0; v < nv; v++)
    dist[v] = -1;
  size_t head = 0, tail = 0;
  dist[p] = 0;
  queue[tail++] = p;
  int r = 0;
  while (head < tail) {
    const size_t v = queue[head++];
    r = dist[v] > r ? dist[v] : r;
    for (size_t q = ptr[v]; q < ptr[v + 1]; q++) {
      int t = 0;
      while (inc[q] >= base[t + 1])
        t++;
      const int n = ss_cell_nverts((ss_cell_type)t);
      const ss_idx *c = cx->cells[t] + (inc[q] - base[t]) * (size_t)n;
      for (int j = 0; j < n; j++)
        if (dist[c[j]] < 0) {
          dist[c[j]] = dist[v] + 1;
          queue[tail++] = c[j];
        }
    }
  }
  free(ptr), free(inc), free(queue);
  int cut = r; /* cells reaching dist >= cut go */
  if (near) {
    int rho = 0;
    for (size_t v = 0; v < nv; v++)
      if (near[v] && dist[v] > rho) rho = dist[v];
    cut = rho + margin + 1;
  }
  if (near || r >= PEEL_FROM) {
    for (int t = 0; t < SS_NCELLTYPES; t++) {
      const int n = ss_cell_nverts((ss_cell_type)t);
      size_t kept = 0;
      for (size_t i = 0; i < cx->nc[t]; i++) {
        const ss_idx *v = cx->cells[t] + i * (size_t)n;
        int far = 0;
        for (int j = 0; j < n && !far; j++)
          far = dist[v[j]] < 0 || dist[v[j]] >= cut;
        if (far) continue;
        memmove(cx->cells[t] + kept * (size_t)n, v, (size_t)n * sizeof *v);
        if (cx->cref[t]) cx->cref[t][kept] = cx->cref[t][i];
        kept++;
      }
      cx->nc[t] = kept;
    }
  }
  free(dist);
  return SS_OK;
}

/* Give level l (computed with level.rows) every inner vertex's row into it:
 * the rule once more for the rows left out, merged row by row into the
 * operator from level l - 1 (ss_scheme_step_rows: each row the same bits
 * whichever rows are asked with it).  Before level l - 1 ... l change: C's
 * complex must be the one F was split from (not peeled since). */
static ss_status complete_rows(work *W, int l, ss_error *err) {
  level *C = W->lev + l - 1, *F = W->lev + l;
  if (!F->rows) return SS_OK;
  const size_t nf = F->cx->nv;
  unsigned char *rest = malloc(nf + 1);
  if (!rest) return ss_error_nomem(err, "refinement operator");
  size_t n = 0;
  for (size_t f = 0; f < nf; f++)
    n += rest[f] = (unsigned char)(F->inner[f] && !F->rows[f]);
  gsl_spmatrix *B = NULL, *A = C->R, *M = NULL;
  ss_status st = SS_OK;
  if (n &&
      !(st = ss_scheme_step_rows(W->scheme, C->cx, F->cx, F->split, rest, &B, err))) {
    size_t nnz = 0;
    for (size_t f = 0; f < nf; f++) {
      const gsl_spmatrix *X = rest[f] ? B : A;
      nnz += (size_t)(X->p[f + 1] - X->p[f]);
    }
    if (!(M = ss_gsl_csr_alloc(A->size1, A->size2, nnz)))
      st = ss_error_nomem(err, "refinement operator");
    else {
      size_t q = 0;
      M->p[0] = 0;
      for (size_t f = 0; f < nf; f++) {
        const gsl_spmatrix *X = rest[f] ? B : A;
        for (int e = X->p[f]; e < X->p[f + 1]; e++, q++) {
          M->i[q] = X->i[e];
          M->data[q] = X->data[e];
        }
        M->p[f + 1] = (int)q;
      }
      M->nz = nnz;
      gsl_spmatrix_free(C->R);
      C->R = M;
    }
  }
  if (B) gsl_spmatrix_free(B);
  free(rest);
  if (!st) {
    free(F->rows);
    F->rows = NULL;
  }
  return st;
}

/* Refine the last level once more, peeled first (peel's near and margin).
 * With keep (marks of the last level's vertices in Omega_w), the new level
 * is the finest one an attempt or the ring reads, only inside Omega_w
 * (ss_local.h): the rule runs only for the inner vertices there
 * (level.rows; a vertex of the finer level lies in Omega_w iff all its
 * parents do, as omega_marks says), the other rows are added
 * (complete_rows) when a read needs them or a level is added below. */
static ss_status add_level(work *W, const unsigned char *near, int margin,
                           const unsigned char *keep, ss_error *err) {
  if (W->nlev == MAXLEVELS)
    return ss_error_set(err, SS_EINTERNAL, "no stationary neighbourhood within %d levels",
                        MAXLEVELS);
  level *C = W->lev + W->nlev - 1, *F = W->lev + W->nlev;
  if (W->nlev >= 2) { /* C becomes an inner level: every inner row into it */
    ss_status st = complete_rows(W, W->nlev - 1, err);
    if (st) return st;
  }
  if (W->nlev - 1 > 0 && W->nlev - 1 >= W->lc) {
    ss_status st = peel(C, near, margin, err);
    if (st) return st;
  }
  /* C's boundary facets, once for both of their uses: the marks of C's
   * complex as refined (schemes reaching 2 rings) and F's derived marks */
  const int one_split = ss_scheme_step_is_one_split(W->scheme),
            derive = one_split && W->nlev >= W->lc; /* F will be level >= lc */
  facet *cb = NULL;
  size_t ncb = 0;
  if (ss_scheme_reach(W->scheme) > 1 || derive) {
    ss_status st = boundary_facets(C->cx, W->ws, &cb, &ncb, err);
    if (st) return st;
  }
  if (ss_scheme_reach(W->scheme) > 1) {
    free(C->cinner);
    ss_status st = boundary_marks(C->cx, cb, ncb, &C->cinner, err);
    if (st) return st;
  }
  if (8 * ss_cx_ncells(C->cx) > MAXCELLS)
    return ss_error_set(err, SS_EINTERNAL,
                        "no stationary neighbourhood before the patch exceeds %d cells",
                        MAXCELLS);
  ss_progress_step(W->prog, "refining the star to level", (size_t)W->nlev, 0);
  ss_status st;
  if (one_split) {
    /* split, then the rule only for the rows that can be read: those of
     * inner vertices (row_complete), where a level has its boundary marks */
    st = ss_split_refine(ss_scheme_split_kind(W->scheme), C->cx, &F->cx, &F->split, err);
    if (st) return st;
    W->nlev++;
    if (derive &&
        (st = inner_marks_split(C->cx, cb, ncb, F->cx, F->split, &F->inner, err)))
      return st;
#ifdef SS_CHECK_MARKS
    if (derive) {
      unsigned char *chk = NULL;
      if ((st = inner_marks(F->cx, W->ws, &chk, err))) return st;
      const int same = !memcmp(chk, F->inner, F->cx->nv);
      free(chk);
      if (!same) return ss_error_set(err, SS_EINTERNAL, "derived boundary marks differ");
    }
#endif
    if (keep && F->inner) { /* only the rows inside Omega_w */
      if (!(F->rows = malloc(F->cx->nv + 1))) return ss_error_nomem(err, "ring rows");
      for (size_t f = 0; f < F->cx->nv; f++) {
        int in = F->inner[f];
        for (size_t q = F->split->ptr[f]; in && q < F->split->ptr[f + 1]; q++)
          in = keep[F->split->parent[q]];
        F->rows[f] = (unsigned char)in;
      }
    }
    st = ss_scheme_step_rows(W->scheme, C->cx, F->cx, F->split,
                             F->rows ? F->rows : F->inner, &C->R, err);
    if (st) return st;
  } else {
    st = ss_scheme_refine_step(W->scheme, C->cx, &F->cx, &C->R, &F->split, err);
    if (st) return st;
    W->nlev++;
  }
  const size_t nf = F->cx->nv;
  F->abs = malloc((nf + 1) * sizeof *F->abs);
  if (!F->abs) return ss_error_nomem(err, "local coordinates");
  for (size_t f = 0; f < nf; f++) {
    const ss_star_coord *par[8];
    const size_t np = ss_split_npar(F->split, f);
    if (np > 8) return ss_error_set(err, SS_EINTERNAL, "vertex with %zu parents", np);
    for (size_t i = 0; i < np; i++)
      par[i] = C->abs + F->split->parent[F->split->ptr[f] + i];
    if (child_coord((int)np, par, F->abs + f))
      return ss_error_set(err, SS_EINTERNAL,
                          "fine vertex %zu on level %d has no integer coordinates", f,
                          W->nlev - 1);
  }
  if (W->nlev - 1 >= W->lc) return finish_level(W, W->nlev - 1, err);
  return SS_OK;
}

static ss_status omega_marks(const work *W, int w, size_t p, unsigned char **out,
                             ss_error *err);

/* Add level w + D + 1, the finest an attempt at level w reads (rows of
 * Omega_w's vertices and of the labels, ss_local.h), computing only the rows
 * inside Omega_w (add_level's keep); the labels' rows, if any lies outside,
 * are added before S is read there (attempt). */
static ss_status add_finest(work *W, int w, ss_error *err) {
  const ss_star_coord zero = ss_star_coord_make(0, NULL, NULL);
  const size_t p = w >= W->lc && w < W->nlev ? lookup(W->lev + w, &zero) : SIZE_MAX;
  if (p == SIZE_MAX || !ss_scheme_step_is_one_split(W->scheme))
    return add_level(W, NULL, 0, NULL, err);
  unsigned char *om[MAXLEVELS] = {NULL};
  ss_status st = omega_marks(W, w, p, om, err);
  if (!st) st = add_level(W, NULL, 0, om[W->nlev - 1 - w], err);
  for (int l = 0; l < MAXLEVELS; l++)
    free(om[l]);
  return st;
}

static void free_work(work *W) {
  for (int l = 0; l < W->nlev; l++) {
    level *L = W->lev + l;
    if (l > 0) ss_cx_free(L->cx); /* level 0 belongs to the star */
    ss_split_free(L->split);
    if (L->R) gsl_spmatrix_free(L->R);
    if (l > 0) free(L->abs);
    free(L->rel);
    free(L->index);
    free(L->inner);
    free(L->rows);
    free(L->cinner);
  }
  ss_star_free(W->star);
}

/* ---- sets of coordinates ---- */

/* Why an attempt at level w failed: for lack of room (a deeper level may do)
 * or for good (status set in err). */
enum { OK = 0, ROOM = 1, HARD = 2 };

/* Whether the row of fine vertex f (level F) in C's operator is complete: f
 * is not on the boundary of F; and for schemes whose rule reads the coarse
 * neighbourhoods of the vertices it combines (reach 2, ss_scheme.h), none of
 * the row's coarse vertices is on the boundary of the complex C refined. */
static int row_complete(const level *C, const level *F, size_t f) {
  if (!(F->rows ? F->rows : F->inner)[f]) return 0;
  if (C->cinner)
    for (int q = C->R->p[f]; q < C->R->p[f + 1]; q++)
      if (!C->cinner[C->R->i[q]]) return 0;
  return 1;
}

/* Add to mark_c (level l) every column of the rows of the marked vertices of
 * level l + 1.  A row of a boundary vertex means the patch is too small. */
static int influence(const level *C, const level *F, const unsigned char *mark_f,
                     unsigned char *mark_c) {
  for (size_t f = 0; f < F->cx->nv; f++) {
    if (!mark_f[f]) continue;
    if (!row_complete(C, F, f)) return ROOM;
    for (int q = C->R->p[f]; q < C->R->p[f + 1]; q++)
      mark_c[C->R->i[q]] = 1;
  }
  return OK;
}

/* Vertices of level l lying in Omega_w (the cells around p on level w). */
static ss_status omega_marks(const work *W, int w, size_t p, unsigned char **out,
                             ss_error *err) {
  for (int l = w; l < W->nlev; l++) {
    out[l - w] = calloc(W->lev[l].cx->nv + 1, 1);
    if (!out[l - w]) return ss_error_nomem(err, "two-ring");
  }
  const ss_cx *cx = W->lev[w].cx;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (ss_cell_dim((ss_cell_type)t) != ss_cx_topdim(cx)) continue;
    const int nv = ss_cell_nverts((ss_cell_type)t);
    for (size_t i = 0; i < cx->nc[t]; i++) {
      const ss_idx *v = ss_cx_cell(cx, (ss_cell_type)t, i);
      int has = 0;
      for (int j = 0; j < nv; j++)
        has |= v[j] == p;
      for (int j = 0; has && j < nv; j++)
        out[0][v[j]] = 1;
    }
  }
  for (int l = w + 1; l < W->nlev; l++) {
    const ss_split *sp = W->lev[l].split;
    for (size_t f = 0; f < sp->nfine; f++) {
      int all = 1;
      for (size_t q = sp->ptr[f]; q < sp->ptr[f + 1]; q++)
        all &= out[l - 1 - w][sp->parent[q]];
      out[l - w][f] = (unsigned char)all;
    }
  }
  return SS_OK;
}

static int label_cmp(const void *a, const void *b) {
  const ss_star_coord *x = a, *y = b;
  int nx = ss_local_label_norm(x), ny = ss_local_label_norm(y);
  if (nx != ny) return nx < ny ? -1 : 1;
  return ss_star_coord_cmp(x, y);
}

/* Read S (n2 x n2) between levels l and l + 1 for the labels; ROOM if a label is
 * missing or a row lies on the boundary, HARD (with err) if a row leaves the
 * set. */
static int read_matrix(const work *W, int l, const ss_local *M, double *S, size_t *colmap,
                       ss_error *err) {
  const level *C = W->lev + l, *F = W->lev + l + 1;
  const size_t n = M->n2;
  for (size_t j = 0; j < C->cx->nv; j++)
    colmap[j] = SIZE_MAX;
  for (size_t j = 0; j < n; j++) {
    size_t v = lookup(C, M->label + j);
    if (v == SIZE_MAX) return ROOM;
    colmap[v] = j;
  }
  memset(S, 0, n * n * sizeof *S);
  for (size_t i = 0; i < n; i++) {
    size_t f = lookup(F, M->label + i);
    if (f == SIZE_MAX || !row_complete(C, F, f)) return ROOM;
    for (int q = C->R->p[f]; q < C->R->p[f + 1]; q++) {
      size_t j = colmap[C->R->i[q]];
      if (j == SIZE_MAX) {
        ss_error_set(
            err, SS_EINTERNAL,
            "the two-ring is not invariant: a row of level %d reaches outside it", l + 1);
        return HARD;
      }
      if (i < M->n1 && j >= M->n1) {
        ss_error_set(err, SS_EINTERNAL, "the one-ring is not invariant (level %d)",
                     l + 1);
        return HARD;
      }
      S[i * n + j] += C->R->data[q];
    }
  }
  return OK;
}

/* Make sure the rows of M's labels into level l are computed where they
 * are inner (level.rows leaves out those outside Omega_w): OK or HARD. */
static int label_rows(work *W, int l, const ss_local *M, ss_error *err) {
  const level *F = W->lev + l;
  if (l >= W->nlev || !F->rows) return OK;
  for (size_t i = 0; i < M->n2; i++) {
    const size_t f = lookup(F, M->label + i);
    if (f != SIZE_MAX && F->inner[f] && !F->rows[f])
      return complete_rows(W, l, err) ? HARD : OK;
  }
  return OK;
}

/* Index of the label x among M's labels (sorted within the one-ring and
 * within the rest), or SIZE_MAX. */
size_t ss_local_label_index(const ss_local *M, const ss_star_coord *x) {
  const ss_star_coord *hit = bsearch(x, M->label, M->n1, sizeof *M->label, label_cmp);
  if (!hit)
    hit = bsearch(x, M->label + M->n1, M->n2 - M->n1, sizeof *M->label, label_cmp);
  return hit ? (size_t)(hit - M->label) : SIZE_MAX;
}

/* The top cells of level w (L) with every corner in the two-ring (marks t2),
 * corners as label indices.  OK or HARD (with err). */
static int collect_cells(const level *L, const unsigned char *t2, ss_local *M,
                         ss_error *err) {
  const ss_cx *cx = L->cx;
  const int top = ss_cx_topdim(cx);
  size_t n = 0;
  for (int pass = 0; pass < 2; pass++) {
    for (int t = 0; t < SS_NCELLTYPES; t++) {
      if (ss_cell_dim((ss_cell_type)t) != top) continue;
      const int nv = ss_cell_nverts((ss_cell_type)t);
      for (size_t i = 0; i < cx->nc[t]; i++) {
        const ss_idx *v = ss_cx_cell(cx, (ss_cell_type)t, i);
        int in = 1;
        for (int j = 0; j < nv && in; j++)
          in = t2[v[j]];
        if (!in) continue;
        if (pass == 0) {
          n++;
          continue;
        }
        M->ctype[M->ncells] = (ss_cell_type)t;
        size_t *c = M->corner + M->ncells * SS_MAXCELLVERTS;
        for (int j = 0; j < SS_MAXCELLVERTS; j++) {
          c[j] = SIZE_MAX;
          if (j >= nv) continue;
          c[j] = ss_local_label_index(M, L->rel + v[j]);
          if (c[j] == SIZE_MAX) {
            ss_error_set(err, SS_EINTERNAL, "a two-ring cell corner has no label");
            return HARD;
          }
          M->ncentre += c[j] == 0; /* label 0 is the centre */
        }
        M->ncells++;
      }
    }
    if (pass == 0) {
      M->ctype = malloc((n + 1) * sizeof *M->ctype);
      M->corner = malloc((n * SS_MAXCELLVERTS + 1) * sizeof *M->corner);
      M->ncells = M->ncentre = 0;
      if (!M->ctype || !M->corner) {
        ss_error_nomem(err, "two-ring cells");
        return HARD;
      }
    }
  }
  return OK;
}

/* The two-ring estimate of depth d (ss_local.h): out (marks of level w) =
 * A_w with A_{w+d} = the vertices of level w + d in Omega_w (om[d]) and A_l =
 * (vertices of level l in Omega_w) u N(A_{l+1}).  scratch holds the vertex
 * count of every level w + 1 .. w + d.  OK or ROOM. */
static int ring_depth(const work *W, int w, int d, unsigned char *const *om,
                      unsigned char *const *scratch, unsigned char *out) {
  if (d == 1) {
    memcpy(out, om[0], W->lev[w].cx->nv);
    return influence(W->lev + w, W->lev + w + 1, om[1], out);
  }
  unsigned char *a = scratch[d - 1]; /* A_{w+d-1} */
  memcpy(a, om[d - 1], W->lev[w + d - 1].cx->nv);
  int rc = influence(W->lev + w + d - 1, W->lev + w + d, om[d], a);
  for (int l = w + d - 2; !rc && l >= w; l--) {
    unsigned char *to = l == w ? out : scratch[l - w];
    memcpy(to, om[l - w], W->lev[l].cx->nv);
    rc = influence(W->lev + l, W->lev + l + 1, scratch[l + 1 - w], to);
  }
  return rc;
}

/* One attempt with the two-ring on level w (levels up to w + D + 1 exist, D
 * the scheme's ring depth). */
static int attempt(work *W, int w, ss_local *M, ss_error *err) {
  const level *Lw = W->lev + w;
  const ss_star_coord zero = ss_star_coord_make(0, NULL, NULL);
  size_t p = lookup(Lw, &zero);
  if (p == SIZE_MAX) {
    ss_error_set(err, SS_EINTERNAL, "the centre is not a vertex of level %d", w);
    return HARD;
  }
  int rc = OK;
  const int D = ss_scheme_ring_depth(W->scheme);
  unsigned char *om[MAXLEVELS] = {NULL}, *sc[MAXLEVELS] = {NULL}, *t1 = NULL, *t2 = NULL,
                *one = NULL;
  size_t *colmap = NULL;
  double *S2 = NULL;
  const size_t nw = Lw->cx->nv;
  if (omega_marks(W, w, p, om, err)) {
    rc = HARD;
    goto done;
  }
  for (int d = 1; d <= D; d++)
    if (!(sc[d] = malloc(W->lev[w + d].cx->nv + 1))) {
      ss_error_nomem(err, "two-ring");
      rc = HARD;
      goto done;
    }
  ss_local_workspace *ws = W->ws;
  if (!(ws->mark = ws_grow(ws->mark, &ws->nmark, 3 * nw, 1))) {
    ss_error_nomem(err, "two-ring");
    rc = HARD;
    goto done;
  }
  t1 = ws->mark;
  t2 = t1 + nw;
  one = t2 + nw;
  memset(ws->mark, 0, 3 * nw); /* as fresh memory would be read: never */
  /* depth D and depth D + 1 */
  if ((rc = ring_depth(W, w, D, om, sc, t1))) goto done;
  if ((rc = ring_depth(W, w, D + 1, om, sc, t2))) goto done;
  if (memcmp(t1, t2, nw) != 0) {
    ss_error_set(err, SS_EINTERNAL,
                 "the two-ring grows from depth %d to depth %d: no fixed point reached",
                 D, D + 1);
    rc = HARD;
    goto done;
  }
  /* one-ring: closure of {p}, via coordinates */
  one[p] = 1;
  for (int changed = 1; changed;) {
    changed = 0;
    for (size_t v = 0; v < nw; v++) {
      if (!one[v]) continue;
      size_t f = lookup(W->lev + w + 1, Lw->rel + v);
      if (f == SIZE_MAX || !row_complete(Lw, W->lev + w + 1, f)) {
        rc = ROOM;
        goto done;
      }
      for (int q = Lw->R->p[f]; q < Lw->R->p[f + 1]; q++) {
        size_t u = Lw->R->i[q];
        if (!one[u]) one[u] = 1, changed = 1;
      }
    }
  }
  size_t n2 = 0, n1 = 0;
  for (size_t v = 0; v < nw; v++) {
    n2 += t2[v];
    n1 += one[v];
    if (one[v] && !t2[v]) {
      ss_error_set(err, SS_EINTERNAL, "the one-ring is not inside the two-ring");
      rc = HARD;
      goto done;
    }
  }
  M->n2 = n2;
  M->n1 = n1;
  M->label = malloc((n2 + 1) * sizeof *M->label);
  M->S = malloc((n2 * n2 + 1) * sizeof *M->S);
  if (!M->label || !M->S ||
      !(ws->dense = ws_grow(ws->dense, &ws->ndense, n2 * n2, sizeof *ws->dense)) ||
      !(ws->colmap = ws_grow(ws->colmap, &ws->ncolmap, W->lev[w + 1].cx->nv,
                             sizeof *ws->colmap))) {
    ss_error_nomem(err, "local matrix");
    rc = HARD;
    goto done;
  }
  S2 = ws->dense;
  colmap = ws->colmap;
  size_t i1 = 0, i2 = n1;
  for (size_t v = 0; v < nw; v++)
    if (one[v])
      M->label[i1++] = Lw->rel[v];
    else if (t2[v])
      M->label[i2++] = Lw->rel[v];
  qsort(M->label, n1, sizeof *M->label, label_cmp);
  qsort(M->label + n1, n2 - n1, sizeof *M->label, label_cmp);
  ss_progress_step(W->prog, "reading S, rows", n2, 0);
  if ((rc = label_rows(W, w + 1, M, err)) || (rc = label_rows(W, w + 2, M, err)))
    goto done;
  if ((rc = read_matrix(W, w, M, M->S, colmap, err))) goto done;
  if ((rc = read_matrix(W, w + 1, M, S2, colmap, err))) goto done;
  double diff = 0.0;
  M->nnz = 0;
  for (size_t k = 0; k < n2 * n2; k++) {
    diff = fmax(diff, fabs(M->S[k] - S2[k]));
    M->nnz += M->S[k] != 0.0;
  }
  if (!(diff <= STAT_TOL)) {
    ss_error_set(err, SS_EINTERNAL,
                 "not stationary: the local matrix on level %d differs from level %d by "
                 "%.3g",
                 w, w + 1, diff);
    rc = HARD;
    goto done;
  }
  for (size_t i = 0; i < n2; i++) {
    double sum = 0.0;
    for (size_t j = 0; j < n2; j++)
      sum += M->S[i * n2 + j];
    if (!(fabs(sum - 1.0) <= 1e-12)) {
      ss_error_set(err, SS_EINTERNAL, "row %zu of the local matrix sums to %.17g", i,
                   sum);
      rc = HARD;
      goto done;
    }
  }
  if ((rc = collect_cells(Lw, t2, M, err))) goto done;
  M->level = w;
done:
  for (int i = 0; i < MAXLEVELS; i++) {
    free(om[i]);
    free(sc[i]);
  }
  if (rc) {
    free(M->label);
    free(M->S);
    free(M->ctype);
    free(M->corner);
    M->label = NULL;
    M->S = NULL;
    M->ctype = NULL;
    M->corner = NULL;
    M->ncells = 0;
  }
  return rc;
}

/* ---- the ring ---- */

/* Whether the top cell v (nv corners) of a level has every corner marked. */
static int all_marked(const ss_idx *v, int nv, const unsigned char *mark) {
  for (int j = 0; j < nv; j++)
    if (!mark[v[j]]) return 0;
  return 1;
}

/* Ring level r on grid level l = w + 1 + r (ss_local.h): the top cells of
 * level l inside Omega_w (om marks) and not inside Omega_{w+1} (om1 marks);
 * counts them, or with M->ring[r] allocated, lists them with corners as
 * vertex indices of level l (renumbered by the caller). */
static size_t ring_cells(const level *L, const unsigned char *om,
                         const unsigned char *om1, ss_local_ring *R) {
  const ss_cx *cx = L->cx;
  const int top = ss_cx_topdim(cx);
  size_t n = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (ss_cell_dim((ss_cell_type)t) != top) continue;
    const int nv = ss_cell_nverts((ss_cell_type)t);
    for (size_t i = 0; i < cx->nc[t]; i++) {
      const ss_idx *v = ss_cx_cell(cx, (ss_cell_type)t, i);
      if (!all_marked(v, nv, om) || all_marked(v, nv, om1)) continue;
      if (R) {
        R->ctype[n] = (ss_cell_type)t;
        for (int j = 0; j < SS_MAXCELLVERTS; j++)
          R->corner[n * SS_MAXCELLVERTS + (size_t)j] = j < nv ? v[j] : SIZE_MAX;
      }
      n++;
    }
  }
  return n;
}

/* Build M's ring levels 0 .. nring - 1 from the levels w .. w + nring of W
 * (which must exist).  OK or HARD (with err). */
static int build_ring(const work *W, int w, int nring, ss_local *M, ss_error *err) {
  const ss_star_coord zero = ss_star_coord_make(0, NULL, NULL);
  const size_t p0 = lookup(W->lev + w, &zero), p1 = lookup(W->lev + w + 1, &zero);
  unsigned char *om[MAXLEVELS] = {NULL}, *om1[MAXLEVELS] = {NULL},
                *need[MAXLEVELS] = {NULL};
  size_t *idx[MAXLEVELS] = {NULL};
  int rc = OK;
  if (p0 == SIZE_MAX || p1 == SIZE_MAX || w + nring >= W->nlev) {
    ss_error_set(err, SS_EINTERNAL, "ring: levels %d..%d are missing", w, w + nring);
    rc = HARD;
    goto done;
  }
  if (omega_marks(W, w, p0, om, err) || omega_marks(W, w + 1, p1, om1, err)) {
    rc = HARD;
    goto done;
  }
  for (int l = w; l <= w + nring; l++) {
    need[l] = calloc(W->lev[l].cx->nv + 1, 1);
    idx[l] = malloc((W->lev[l].cx->nv + 1) * sizeof *idx[l]);
    if (!need[l] || !idx[l]) {
      ss_error_nomem(err, "ring");
      rc = HARD;
      goto done;
    }
  }
  /* the cells, then what their corners read, from the finest level down */
  for (int r = 0; r < nring; r++) {
    const int l = w + 1 + r;
    ss_local_ring *R = M->ring + r;
    R->ncells = ring_cells(W->lev + l, om[l - w], om1[l - w - 1], NULL);
    R->ctype = malloc((R->ncells + 1) * sizeof *R->ctype);
    R->corner = malloc((R->ncells * SS_MAXCELLVERTS + 1) * sizeof *R->corner);
    if (!R->ctype || !R->corner) {
      ss_error_nomem(err, "ring cells");
      rc = HARD;
      goto done;
    }
    ring_cells(W->lev + l, om[l - w], om1[l - w - 1], R);
    for (size_t q = 0; q < R->ncells * SS_MAXCELLVERTS; q++)
      if (R->corner[q] != SIZE_MAX) need[l][R->corner[q]] = 1;
  }
  for (int l = w + nring; l > w; l--) {
    const level *C = W->lev + l - 1, *F = W->lev + l;
    for (size_t f = 0; f < F->cx->nv; f++) {
      if (!need[l][f]) continue;
      if (!row_complete(C, F, f)) {
        ss_error_set(err, SS_EINTERNAL,
                     "ring level %d: the row of a point inside Omega_w is incomplete",
                     l - w - 1);
        rc = HARD;
        goto done;
      }
      for (int q = C->R->p[f]; q < C->R->p[f + 1]; q++)
        need[l - 1][C->R->i[q]] = 1;
    }
  }
  /* number the kept points; level w's are the two-ring labels */
  for (size_t v = 0; v < W->lev[w].cx->nv; v++) {
    idx[w][v] = need[w][v] ? ss_local_label_index(M, W->lev[w].rel + v) : SIZE_MAX;
    if (need[w][v] && idx[w][v] == SIZE_MAX) {
      ss_error_set(err, SS_EINTERNAL, "the ring reads a point outside the two-ring");
      rc = HARD;
      goto done;
    }
  }
  for (int r = 0; r < nring; r++) {
    const int l = w + 1 + r;
    const level *C = W->lev + l - 1, *F = W->lev + l;
    ss_local_ring *R = M->ring + r;
    size_t nv = 0, nnz = 0;
    for (size_t f = 0; f < F->cx->nv; f++) {
      idx[l][f] = need[l][f] ? nv++ : SIZE_MAX;
      if (need[l][f]) nnz += (size_t)(C->R->p[f + 1] - C->R->p[f]);
    }
    R->nv = nv;
    R->nprev = r == 0 ? M->n2 : M->ring[r - 1].nv;
    R->ptr = malloc((nv + 1) * sizeof *R->ptr);
    R->col = malloc((nnz + 1) * sizeof *R->col);
    R->w = malloc((nnz + 1) * sizeof *R->w);
    if (!R->ptr || !R->col || !R->w) {
      ss_error_nomem(err, "ring rows");
      rc = HARD;
      goto done;
    }
    size_t q = 0, i = 0;
    for (size_t f = 0; f < F->cx->nv; f++) {
      if (!need[l][f]) continue;
      R->ptr[i++] = q;
      for (int e = C->R->p[f]; e < C->R->p[f + 1]; e++) {
        R->col[q] = idx[l - 1][C->R->i[e]];
        R->w[q++] = C->R->data[e];
      }
    }
    R->ptr[nv] = q;
    for (size_t k = 0; k < R->ncells * SS_MAXCELLVERTS; k++)
      if (R->corner[k] != SIZE_MAX) R->corner[k] = idx[l][R->corner[k]];
    M->nring = r + 1;
  }
done:
  for (int l = 0; l < MAXLEVELS; l++) {
    free(om[l]);
    free(om1[l]);
    free(need[l]);
    free(idx[l]);
  }
  return rc;
}

/* M's ring of nring levels from the levels of W, S mapping from level w:
 * level w + 1 + r for ring level r; levels W lacks are added, each beyond
 * w + 2 refining a neighbourhood of Omega_w only (the rows read reach a few
 * cells out, the margin covers schemes of reach 2).  ss_local_ring_deepen
 * calls it again on kept levels: the levels added then are those an
 * extraction with the deeper ring from the start adds, in the same order. */
static ss_status ring(work *W, int w, int nring, ss_local *M, ss_error *err) {
  ss_status st = SS_OK;
  while (!st && W->nlev < w + nring + 1) {
    const ss_star_coord zero = ss_star_coord_make(0, NULL, NULL);
    unsigned char *om[MAXLEVELS] = {NULL};
    const size_t p = lookup(W->lev + w, &zero);
    st = p == SIZE_MAX ? ss_error_set(err, SS_EINTERNAL, "the centre is lost")
                       : omega_marks(W, w, p, om, err);
    if (!st)
      st = add_level(W, om[W->nlev - 1 - w], ss_scheme_reach(W->scheme),
                     W->nlev + 1 == w + nring + 1 ? om[W->nlev - 1 - w] : NULL, err);
    for (int l = 0; l < MAXLEVELS; l++)
      free(om[l]);
  }
  if (!st && build_ring(W, w, nring, M, err) == HARD)
    st = err && err->status ? err->status : SS_EINTERNAL;
  return st;
}

/* Free ring levels 0 .. SS_LOCAL_MAXRING - 1 of M and mark none built. */
static void free_rings(ss_local *M) {
  for (int r = 0; r < SS_LOCAL_MAXRING; r++) {
    free(M->ring[r].ptr);
    free(M->ring[r].col);
    free(M->ring[r].w);
    free(M->ring[r].ctype);
    free(M->ring[r].corner);
    memset(M->ring + r, 0, sizeof M->ring[r]);
  }
  M->nring = 0;
}

ss_status ss_local_new(const ss_scheme *s, const ss_case *c, ss_local **out,
                       ss_error *err) {
  return ss_local_new_ring(s, c, SS_LOCAL_RING, out, err);
}

ss_status ss_local_new_ring(const ss_scheme *s, const ss_case *c, int nring,
                            ss_local **out, ss_error *err) {
  ss_local_opts o = ss_local_defaults();
  o.nring = nring;
  return ss_local_new_opts(s, c, &o, out, err);
}

ss_status ss_local_new_opts(const ss_scheme *s, const ss_case *c, const ss_local_opts *o,
                            ss_local **out, ss_error *err) {
  return ss_local_new_ws(s, c, o, NULL, out, err);
}

ss_status ss_local_new_ws(const ss_scheme *s, const ss_case *c, const ss_local_opts *o,
                          ss_local_workspace *wsp, ss_local **out, ss_error *err) {
  *out = NULL;
  const int nring = o->nring;
  if (nring < 1 || nring > SS_LOCAL_MAXRING)
    return ss_error_set(err, SS_EINPUT, "ring levels must be in 1..%d, not %d",
                        SS_LOCAL_MAXRING, nring);
  if (o->max_bytes > 0.0) { /* refuse what cannot fit before building anything */
    ss_local_cost k;
    ss_status st = ss_local_estimate(s, c, &k, err);
    if (!st) st = ss_local_check_budget(&k, o->max_bytes, err);
    if (st) return st;
  }
  work W;
  memset(&W, 0, sizeof W);
  /* without a caller's workspace, one for this case alone */
  ss_local_workspace own;
  memset(&own, 0, sizeof own);
  W.ws = wsp ? wsp : &own;
  W.scheme = s;
  W.prog = &o->progress;
  ss_progress_step(W.prog, "building the star", 0, 0);
  ss_status st = ss_case_star(s, c, &W.star, err);
  if (st) return st;
  ss_local *M = calloc(1, sizeof *M);
  if (!M) {
    ss_star_free(W.star);
    return ss_error_nomem(err, "local matrix");
  }
  M->ncoord = W.star->ncoord;
  M->dim = c->kind == SS_CASE_SURFACE_VERTEX ? 2 : 3;
  M->cell = W.star->cell_type;
  /* p's chart coordinates on level lc: the origin, or (2, 1, 1) for the face
   * point */
  const int32_t idx[3] = {0, 1, 2}, val[3] = {2, 1, 1};
  W.lc = ss_case_centre_level(c->kind);
  W.cp = c->kind == SS_CASE_FACE ? ss_star_coord_make(3, idx, val)
                                 : ss_star_coord_make(0, NULL, NULL);
  W.lev[0].cx = W.star->cx;
  W.lev[0].abs = W.star->coord;
  W.nlev = 1;
  if (W.lc == 0) st = finish_level(&W, 0, err);
  int w = W.lc + 1, rc = ROOM;
  const int D = ss_scheme_ring_depth(s);
  while (!st && rc == ROOM) {
    while (!st && W.nlev < w + D + 2)
      st = W.nlev + 1 == w + D + 2 ? add_finest(&W, w, err)
                                   : add_level(&W, NULL, 0, NULL, err);
    if (st) break;
    rc = attempt(&W, w, M, err);
    if (rc == HARD) st = err && err->status ? err->status : SS_EINTERNAL;
    w++;
  }
  w--;
  if (!st) st = ring(&W, w, nring, M, err);
  ws_release(&own);
  W.ws = NULL; /* the caller's workspace is not the kept levels' */
  if (!st && o->keep_levels) {
    M->levels = malloc(sizeof *M->levels);
    if (M->levels) {
      *M->levels = W;         /* the levels move into M: freed by ss_local_free */
      M->levels->prog = NULL; /* the caller's options do not outlive the call */
    } else
      st = ss_error_nomem(err, "kept levels");
  }
  if (!M->levels) free_work(&W);
  if (st) {
    ss_local_free(M);
    return st;
  }
  *out = M;
  return SS_OK;
}

ss_status ss_local_ring_deepen(const ss_scheme *s, const ss_case *c, int nring,
                               ss_local *M, ss_error *err) {
  if (M->levels) {
    if (nring < 1 || nring > SS_LOCAL_MAXRING)
      return ss_error_set(err, SS_EINPUT, "ring levels must be in 1..%d, not %d",
                          SS_LOCAL_MAXRING, nring);
    free_rings(M);
    ss_local_workspace own; /* the levels kept their refinement, not a workspace */
    memset(&own, 0, sizeof own);
    M->levels->ws = &own;
    const ss_status st = ring(M->levels, M->level, nring, M, err);
    M->levels->ws = NULL;
    ws_release(&own);
    return st;
  }
  ss_local *D = NULL;
  ss_status st = ss_local_new_ring(s, c, nring, &D, err);
  if (st) return st;
  if (D->n2 != M->n2 || D->n1 != M->n1 ||
      memcmp(D->S, M->S, M->n2 * M->n2 * sizeof *M->S) ||
      memcmp(D->label, M->label, M->n2 * sizeof *M->label)) {
    ss_local_free(D);
    return ss_error_set(err, SS_EINTERNAL,
                        "the deeper extraction gave another local matrix");
  }
  for (int r = 0; r < SS_LOCAL_MAXRING; r++) { /* swap the rings */
    const ss_local_ring t = M->ring[r];
    M->ring[r] = D->ring[r];
    D->ring[r] = t;
  }
  const int n = M->nring;
  M->nring = D->nring;
  D->nring = n;
  ss_local_free(D);
  return SS_OK;
}

void ss_local_free(ss_local *L) {
  if (!L) return;
  free_rings(L);
  if (L->levels) {
    free_work(L->levels);
    free(L->levels);
  }
  free(L->S);
  free(L->label);
  free(L->ctype);
  free(L->corner);
  free(L);
}
