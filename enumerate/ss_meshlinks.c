/* ss_meshlinks.c — vertex links and edge valences of a tet or hex mesh.
 *
 * One pass over the vertices.  For a vertex v the cells at v give its link
 * triangles (on the mesh vertices adjacent to v); these are renumbered
 * 0..k-1, and for each link vertex w the triangles at w give the wedges of
 * the edge vw (module header).  The wedge graph decides the edge (counted
 * once, from its smaller endpoint) and, through the number of triangles on
 * each link edge, whether the link is closed.  Closed links go through
 * ss_link_from_triangles, then ss_link_canonical and ss_link_format; the
 * canonical texts are counted in a string-keyed hash table. */
#include "ss_meshlinks.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_link.h"

/* ---- distinct links: open addressing on the canonical text ---- */

typedef struct {
  ss_meshlink_class *cls; /* classes in order of first appearance */
  size_t n, cap;          /* classes used / allocated */
  size_t *slot;           /* nslot entries: class index + 1, or 0 if empty */
  size_t nslot;           /* a power of two, at least 2 (n + 1) */
} linkset;

static uint64_t hash_text(const char *s) {
  uint64_t h = 1469598103934665603u; /* FNV-1a */
  for (; *s; s++) {
    h ^= (unsigned char)*s;
    h *= 1099511628211u;
  }
  return h;
}

static void linkset_free(linkset *s) {
  for (size_t i = 0; i < s->n; i++)
    free(s->cls[i].link);
  free(s->cls);
  free(s->slot);
}

/* Count one vertex v with canonical text `text` (taken over: stored or freed,
 * also on failure) and k link vertices.  SS_ENOMEM. */
static ss_status linkset_add(linkset *s, char *text, int k, size_t v, ss_error *err) {
  if (2 * (s->n + 1) > s->nslot) {
    size_t ns = s->nslot ? 2 * s->nslot : 64;
    size_t *slot = calloc(ns, sizeof *slot);
    if (!slot) {
      free(text);
      return ss_error_nomem(err, "link table");
    }
    for (size_t i = 0; i < s->n; i++) {
      size_t j = (size_t)hash_text(s->cls[i].link) & (ns - 1);
      while (slot[j])
        j = (j + 1) & (ns - 1);
      slot[j] = i + 1;
    }
    free(s->slot);
    s->slot = slot;
    s->nslot = ns;
  }
  size_t j = (size_t)hash_text(text) & (s->nslot - 1);
  while (s->slot[j]) {
    ss_meshlink_class *c = &s->cls[s->slot[j] - 1];
    if (!strcmp(c->link, text)) {
      c->count++;
      free(text);
      return SS_OK;
    }
    j = (j + 1) & (s->nslot - 1);
  }
  if (s->n == s->cap) {
    size_t nc = s->cap ? 2 * s->cap : 64;
    ss_meshlink_class *cls = realloc(s->cls, nc * sizeof *cls);
    if (!cls) {
      free(text);
      return ss_error_nomem(err, "link classes");
    }
    s->cls = cls;
    s->cap = nc;
  }
  s->cls[s->n] = (ss_meshlink_class){text, k, 1, v};
  s->slot[j] = ++s->n;
  return SS_OK;
}

static int cmp_class(const void *pa, const void *pb) {
  const ss_meshlink_class *a = pa, *b = pb;
  if (a->count != b->count) return a->count > b->count ? -1 : 1;
  if (a->k != b->k) return a->k < b->k ? -1 : 1;
  return strcmp(a->link, b->link);
}

static int cmp_idx(const void *pa, const void *pb) {
  ss_idx a = *(const ss_idx *)pa, b = *(const ss_idx *)pb;
  return (a > b) - (a < b);
}

/* ---- histograms that grow with their largest value ---- */

/* (*h)[value]++, growing *h (of *len entries) to value + 1 entries. */
static ss_status hist_add(size_t **h, int *len, int value, ss_error *err) {
  if (value >= *len) {
    size_t *g = realloc(*h, (size_t)(value + 1) * sizeof *g);
    if (!g) return ss_error_nomem(err, "valence histogram");
    memset(g + *len, 0, (size_t)(value + 1 - *len) * sizeof *g);
    *h = g;
    *len = value + 1;
  }
  (*h)[value]++;
  return SS_OK;
}

/* ---- per-vertex scratch ---- */

typedef struct {
  ss_idx *gtri; /* 3m link triangle corners as mesh vertex indices */
  ss_idx *loc;  /* the k distinct link vertices (mesh indices), ascending */
  int *tri;     /* 3m link triangle corners renumbered 0..k-1 */
  int *toff;    /* k + 1 offsets into tlist */
  int *tlist;   /* for each link vertex the triangles containing it */
  int *deg;     /* per link vertex: wedge degree (scratch, reset after use) */
  int *uf;      /* per link vertex: union-find parent (scratch) */
} scratch;

static void scratch_free(scratch *s) {
  free(s->gtri);
  free(s->loc);
  free(s->tri);
  free(s->toff);
  free(s->tlist);
  free(s->deg);
  free(s->uf);
}

/* Scratch for vertices in at most maxm cells (3 maxm link triangle corners). */
static ss_status scratch_alloc(scratch *s, size_t maxm, ss_error *err) {
  const size_t m3 = 3 * maxm + 1;
  s->gtri = malloc(m3 * sizeof *s->gtri);
  s->loc = malloc(m3 * sizeof *s->loc);
  s->tri = malloc(m3 * sizeof *s->tri);
  s->toff = malloc((m3 + 1) * sizeof *s->toff);
  s->tlist = malloc(m3 * sizeof *s->tlist);
  s->deg = malloc(m3 * sizeof *s->deg);
  s->uf = malloc(m3 * sizeof *s->uf);
  if (!s->gtri || !s->loc || !s->tri || !s->toff || !s->tlist || !s->deg || !s->uf)
    return ss_error_nomem(err, "mesh links");
  return SS_OK;
}

static int uf_find(int *uf, int x) {
  while (uf[x] != x) {
    uf[x] = uf[uf[x]];
    x = uf[x];
  }
  return x;
}

/* Kinds of wedge graphs (cells around an edge). */
enum { EDGE_CLOSED, EDGE_OPEN, EDGE_NONMANIFOLD };

/* Classify the cells around the edge to link vertex w: *n receives the number
 * of cells, *has_triple 1 if some link edge at w lies in 3 or more triangles,
 * *has_single 1 if some lies in exactly one.  Returns EDGE_*. */
static int wedge_kind(scratch *s, int w, int *n, int *has_triple, int *has_single) {
  const int *tl = s->tlist + s->toff[w];
  const int nt = s->toff[w + 1] - s->toff[w];
  /* the other two corners of each triangle at w: one wedge each */
  for (int i = 0; i < nt; i++)
    for (int j = 0; j < 3; j++) {
      int x = s->tri[3 * tl[i] + j];
      s->deg[x] = 0;
      s->uf[x] = x;
    }
  for (int i = 0; i < nt; i++) {
    int e[2], ne = 0;
    for (int j = 0; j < 3; j++)
      if (s->tri[3 * tl[i] + j] != w) e[ne++] = s->tri[3 * tl[i] + j];
    s->deg[e[0]]++;
    s->deg[e[1]]++;
    int a = uf_find(s->uf, e[0]), b = uf_find(s->uf, e[1]);
    if (a != b) s->uf[a] = b;
  }
  int maxdeg = 0, n1 = 0, comps = 0;
  for (int i = 0; i < nt; i++)
    for (int j = 0; j < 3; j++) {
      int x = s->tri[3 * tl[i] + j];
      if (x == w || s->deg[x] < 0) continue;
      if (s->deg[x] > maxdeg) maxdeg = s->deg[x];
      if (s->deg[x] == 1) n1++;
      if (uf_find(s->uf, x) == x) comps++;
      s->deg[x] = -1; /* counted */
    }
  *n = nt;
  *has_triple = maxdeg > 2;
  *has_single = n1 > 0;
  if (maxdeg > 2 || comps != 1) return EDGE_NONMANIFOLD;
  if (n1 == 0) return EDGE_CLOSED;
  return n1 == 2 ? EDGE_OPEN : EDGE_NONMANIFOLD;
}

/* ---- the computation ---- */

void ss_meshlinks_free(ss_meshlinks *ml) {
  if (!ml) return;
  for (size_t i = 0; i < ml->nlinks; i++)
    free(ml->links[i].link);
  free(ml->links);
  free(ml->vval_hist);
  free(ml->eval_hist);
  free(ml->nonmanifold);
  free(ml);
}

/* Check the cell types; sets *t to SS_TET or SS_HEX. */
static ss_status pick_cell_type(const ss_cx *cx, ss_cell_type *t, ss_error *err) {
  if (cx->nc[SS_OCT])
    return ss_error_set(err, SS_EINPUT,
                        "the mesh has %zu octahedra: mesh links are computed for "
                        "tetrahedral or hexahedral meshes only",
                        cx->nc[SS_OCT]);
  if (cx->nc[SS_TET] && cx->nc[SS_HEX])
    return ss_error_set(err, SS_EINPUT,
                        "mixed mesh (%zu tetrahedra and %zu hexahedra): mesh links "
                        "are computed for one cell type at a time",
                        cx->nc[SS_TET], cx->nc[SS_HEX]);
  if (!cx->nc[SS_TET] && !cx->nc[SS_HEX])
    return ss_error_set(err, SS_EINPUT,
                        "the mesh has no tetrahedra or hexahedra: mesh links need a "
                        "volume mesh");
  *t = cx->nc[SS_TET] ? SS_TET : SS_HEX;
  return SS_OK;
}

/* The link of one vertex in m cells, whose (cell, corner) incidences are
 * inc[0..m) (flat indices into cells, n corners a cell; nb[corner] the
 * corners opposite it): its triangles on mesh vertices (s->gtri), the mesh
 * vertices sorted (s->loc[0..k)), the triangles renumbered 0..k-1 (s->tri)
 * and the triangles at each link vertex (s->toff, s->tlist).  Returns k. */
static int link_triangles(scratch *s, const ss_idx *cells, int n, int nb[8][3],
                          const size_t *inc, int m) {
  const size_t mm = (size_t)m;
  for (int i = 0; i < m; i++) {
    size_t f = inc[i];
    const ss_idx *c = cells + f - f % (size_t)n;
    int corner = (int)(f % (size_t)n);
    for (int j = 0; j < 3; j++)
      s->gtri[3 * i + j] = c[nb[corner][j]];
  }
  memcpy(s->loc, s->gtri, 3 * mm * sizeof *s->loc);
  qsort(s->loc, 3 * mm, sizeof *s->loc, cmp_idx);
  int k = 0;
  for (int i = 0; i < 3 * m; i++)
    if (k == 0 || s->loc[i] != s->loc[k - 1]) s->loc[k++] = s->loc[i];
  for (int i = 0; i < 3 * m; i++) {
    const ss_idx *p = bsearch(&s->gtri[i], s->loc, (size_t)k, sizeof *s->loc, cmp_idx);
    s->tri[i] = (int)(p - s->loc);
  }
  /* triangles at each link vertex */
  memset(s->toff, 0, (size_t)(k + 1) * sizeof *s->toff);
  for (int i = 0; i < 3 * m; i++)
    s->toff[s->tri[i] + 1]++;
  for (int w = 0; w < k; w++)
    s->toff[w + 1] += s->toff[w];
  for (int i = 0; i < 3 * m; i++)
    s->tlist[s->toff[s->tri[i]]++] = i / 3;
  for (int w = k; w > 0; w--)
    s->toff[w] = s->toff[w - 1];
  s->toff[0] = 0;
  return k;
}

/* The vertex's link as canonical text, added to set when it is a sphere
 * (*interior = 1); a closed link that is no sphere is non-manifold
 * (*interior = 0, SS_OK).  SS_ENOMEM. */
static ss_status vertex_link(const scratch *s, int k, int m, size_t v, linkset *set,
                             int *interior, ss_error *err) {
  ss_error lerr = {0};
  ss_link *l = NULL, *cl = NULL;
  char *text = NULL;
  *interior = 0;
  ss_status st = ss_link_from_triangles(k, m, s->tri, &l, &lerr);
  if (st == SS_OK) {
    *interior = 1;
    st = ss_link_canonical(l, &cl, NULL, err);
    if (st == SS_OK) st = ss_link_format(cl, &text, err);
    if (st == SS_OK) st = linkset_add(set, text, k, v, err);
  } else if (st == SS_EINPUT) {
    st = SS_OK; /* closed but not a sphere: non-manifold */
  } else if (err) {
    *err = lerr;
  }
  ss_link_free(l);
  ss_link_free(cl);
  return st;
}

/* The vertex -> (cell, corner) incidences of the ncorners corners cells
 * (flat indices into cells) of a mesh with nv vertices, grouped by vertex:
 * those of vertex v are inc[off[v] .. off[v+1]-1] (off zeroed by the
 * caller, nv + 1 entries; inc, ncorners).  *maxm = the most cells at one
 * vertex; SS_EINPUT when that is more than a link has triangles. */
static ss_status incidences(const ss_idx *cells, size_t ncorners, size_t nv, size_t *off,
                            size_t *inc, size_t *maxm, ss_error *err) {
  for (size_t i = 0; i < ncorners; i++)
    off[cells[i] + 1]++;
  *maxm = 0;
  for (size_t v = 0; v < nv; v++) {
    if (off[v + 1] > *maxm) *maxm = off[v + 1];
    off[v + 1] += off[v];
  }
  for (size_t i = 0; i < ncorners; i++)
    inc[off[cells[i]]++] = i;
  for (size_t v = nv; v > 0; v--)
    off[v] = off[v - 1];
  off[0] = 0;
  if (*maxm <= 2 * (size_t)SS_LINK_MAXK - 4) return SS_OK;
  size_t v = 0;
  while (off[v + 1] - off[v] != *maxm)
    v++;
  return ss_error_set(err, SS_EINPUT,
                      "vertex %zu is in %zu cells, more than a link has triangles (at "
                      "most %d)",
                      v + 1, *maxm, 2 * SS_LINK_MAXK - 4);
}

/* Append vertex v to ml's non-manifold vertices (*cap allocated). */
static ss_status add_nonmanifold(ss_meshlinks *ml, size_t *cap, size_t v, ss_error *err) {
  if (ml->nv_nonmanifold == *cap) {
    size_t ncap = *cap ? 2 * *cap : 16;
    size_t *g = realloc(ml->nonmanifold, ncap * sizeof *g);
    if (!g) return ss_error_nomem(err, "non-manifold vertices");
    ml->nonmanifold = g;
    *cap = ncap;
  }
  ml->nonmanifold[ml->nv_nonmanifold++] = v;
  return SS_OK;
}

ss_status ss_meshlinks_compute(const ss_cx *cx, ss_meshlinks **out, ss_error *err) {
  *out = NULL;
  ss_cell_type t = SS_TET;
  ss_status st = ss_cx_validate(cx, err);
  if (st || (st = pick_cell_type(cx, &t, err))) return st;

  const int n = ss_cell_nverts(t);
  const size_t nc = cx->nc[t], nv = cx->nv;
  /* nb[i]: the corners whose triangle is the link of corner i in one cell */
  int nb[8][3];
  for (int i = 0; i < n; i++)
    for (int j = 0; j < 3; j++)
      nb[i][j] = t == SS_TET
                     ? (i + 1 + j) % 4
                     : ss_cube_corner_index(3, ss_cube_corner_bits(3, i) ^ (1u << j));

  ss_meshlinks *ml = calloc(1, sizeof *ml);
  size_t *off = calloc(nv + 1, sizeof *off), *inc = NULL, nm_cap = 0;
  int vlen = 1, elen = 1;
  linkset set = {0};
  scratch s = {0};
  if (!ml || !off) {
    st = ss_error_nomem(err, "mesh links");
    goto done;
  }
  ml->cell_type = t;
  ml->nv = nv;
  ml->nc = nc;
  ml->vval_hist = calloc(1, sizeof *ml->vval_hist);
  ml->eval_hist = calloc(1, sizeof *ml->eval_hist);
  inc = malloc((nc * (size_t)n + 1) * sizeof *inc);
  if (!ml->vval_hist || !ml->eval_hist || !inc) {
    st = ss_error_nomem(err, "mesh links");
    goto done;
  }

  const ss_idx *cells = cx->cells[t];
  size_t maxm = 0;
  if ((st = incidences(cells, nc * (size_t)n, nv, off, inc, &maxm, err))) goto done;

  if ((st = scratch_alloc(&s, maxm, err))) goto done;

  double vsum = 0, esum = 0;
  for (size_t v = 0; v < nv; v++) {
    const size_t mm = off[v + 1] - off[v];
    const int m = (int)mm;
    if (mm == 0) {
      ml->nv_unused++;
      continue;
    }
    const int k = link_triangles(&s, cells, n, nb, inc + off[v], m);

    /* edges at v: classify each; count those to larger vertices */
    int any_triple = 0, any_single = 0;
    for (int w = 0; w < k; w++) {
      int cnt, triple, single;
      int kind = wedge_kind(&s, w, &cnt, &triple, &single);
      any_triple |= triple;
      any_single |= single;
      if (s.loc[w] < v) continue;
      ml->ne++;
      if (kind == EDGE_CLOSED) {
        ml->ne_interior++;
        esum += cnt;
        if ((st = hist_add(&ml->eval_hist, &elen, cnt, err))) goto done;
      } else if (kind == EDGE_OPEN) {
        ml->ne_boundary++;
      } else {
        ml->ne_nonmanifold++;
      }
    }

    /* the vertex */
    int interior = 0;
    if (!any_triple && !any_single &&
        (st = vertex_link(&s, k, m, v, &set, &interior, err)))
      goto done;
    if (interior) {
      ml->nv_interior++;
      vsum += k;
      if ((st = hist_add(&ml->vval_hist, &vlen, k, err))) goto done;
    } else if (any_triple || !any_single) {
      if ((st = add_nonmanifold(ml, &nm_cap, v, err))) goto done;
    } else {
      ml->nv_boundary++;
    }
  }

  ml->vval_max = vlen - 1;
  ml->eval_max = elen - 1;
  ml->vval_mean = ml->nv_interior ? vsum / (double)ml->nv_interior : 0.0;
  ml->eval_mean = ml->ne_interior ? esum / (double)ml->ne_interior : 0.0;
  if (set.n) qsort(set.cls, set.n, sizeof *set.cls, cmp_class);
  ml->links = set.cls;
  ml->nlinks = set.n;
  set.cls = NULL;
  set.n = 0;
  *out = ml;
  ml = NULL;
done:
  ss_meshlinks_free(ml);
  linkset_free(&set);
  scratch_free(&s);
  free(off);
  free(inc);
  return st;
}
