/* ss_scheme_boxspline.c — box-spline solid subdivision (Chang, McDonnell, Qin:
 * "A new solid subdivision scheme based on box splines", sections 3.3–3.6).
 *
 * Over the tet/oct split (tets and octahedra; triangle cells are surface parts,
 * below), every fine vertex is a combination of coarse vertices:
 *   old vertex x, k = |rho(x)|:      9/16 x + 7/(16k) sum rho(x)          (3.7)
 *     (at k = 14 this is the regular rule (3.3): 18/32 x + 1/32 each)
 *   edge point of e = (a, b), k = |rho(e)|:
 *     k = 4:  8/32 (a + b) + 4/32 each                                   (3.5)
 *     else:   5/16 (a + b) + 3/(8k) each                                 (3.8)
 *     (at k = 6 this is the regular rule (3.4): 10/32 and 2/32)
 *   octahedron centre: 4/32 each corner + 4/32 more on each end of the
 *     octahedron's major diagonal                                        (3.6)
 * with rho (Definition 3.3) the neighbours by an edge or by a major diagonal of
 * an octahedron, and rho(e) = rho(a) ∩ rho(b).  Major diagonals live in the
 * vertex order (ss_split.h): an octahedron's is its pair (0, 3), and the split
 * hands every child the diagonal parallel to its parent's (Algorithm 1).
 *
 * Boundary (section 3.6, figure 14) and surface parts (figure 29's hybrid
 * solid): the surface made of the fine faces held by one cell and the fine
 * triangle cells follows Loop's rules (ss_loop_surface, shared with tet/oct's
 * crease surfaces): a vertex with n surface neighbours (1 - n beta) x + beta
 * each, beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n; an edge 3/8 (a + b) +
 * 1/8 of the vertex opposite it in each of its two triangles.  The paper
 * leaves the hybrid's "additional rules" to Chang and Qin 2004; here an edge
 * in three or more surface triangles (where a surface part meets the solid)
 * and the edges of the surface's own boundary are crease curves (Hoppe's
 * 1/8, 3/4, 1/8 and midpoints; corners as ss_crease.h says).  The solid's rules read only
 * the tets' and octahedra's edges, so a point off the surface moves as without triangles.
 *
 * boxspline-avg (Appendix A): the mean of the three schemes whose major
 * diagonals all point one of the lattice's three ways.  It reads no diagonals.
 * On the lattice its rules are the means of (3.3)-(3.6) over the three
 * directions (derived below from their weights, checked against the three
 * box-spline schemes in test_boxspline).  A regular vertex x lies in six
 * octahedra; in each direction two of the six corners opposite x are its
 * diagonal neighbours, so each such corner gets 1/3 of 1/32, and the twelve
 * edge neighbours keep 1/32.  A regular edge lies in two octahedra; in two
 * directions it has six neighbours (3.4: the four apexes of its triangles and
 * one octahedron corner opposite an end), in one direction four (3.5).  An
 * octahedron centre is the mean of its corners.  Away from the lattice the
 * weights go by counts, as (3.7)/(3.8) do: a vertex in some octahedron takes
 * 9/16 x + 3/8 mean(edge neighbours) + 1/16 mean(corners opposite x); an edge
 * in some octahedron takes 7/24 on each end, 1/3 shared by the common edge
 * neighbours and 1/12 by the corners opposite its ends in its octahedra.
 * Vertices and edges in no octahedron (the refined input mesh's own vertices
 * and edge pieces) never see a diagonal and keep (3.7) and (3.5)/(3.8); so do
 * boundary points their Loop rules.  The face-to-face configuration has no
 * lattice counterpart (Appendix A: it "becomes irregular"); the count rules
 * apply there as written. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_scheme_impl.h"

/* Sorted adjacency lists of the coarse vertices. */
typedef struct {
  size_t *ptr; /* nv + 1 */
  ss_idx *nb;  /* neighbours, sorted, distinct within a list */
} adjacency;

static void adj_free(adjacency *A) {
  free(A->ptr);
  free(A->nb);
}

static int cmp_idx(const void *a, const void *b) {
  const ss_idx x = *(const ss_idx *)a, y = *(const ss_idx *)b;
  return (x > y) - (x < y);
}

/* Build lists from the pairs (a[i], b[i]), i < n, both directions; duplicates
 * dropped.  0 or -1 without memory. */
static int adj_make(size_t nv, size_t n, const ss_idx *pairs, adjacency *A) {
  A->ptr = calloc(nv + 2, sizeof *A->ptr);
  A->nb = malloc((2 * n + 1) * sizeof *A->nb);
  if (!A->ptr || !A->nb) return -1;
  for (size_t i = 0; i < 2 * n; i++)
    A->ptr[pairs[i] + 2]++;
  for (size_t v = 0; v < nv; v++)
    A->ptr[v + 2] += A->ptr[v + 1];
  for (size_t i = 0; i < n; i++) {
    const ss_idx a = pairs[2 * i], b = pairs[2 * i + 1];
    A->nb[A->ptr[a + 1]++] = b;
    A->nb[A->ptr[b + 1]++] = a;
  }
  /* sort each list and squeeze out repeats, compacting in place */
  size_t out = 0;
  for (size_t v = 0; v < nv; v++) {
    const size_t b = A->ptr[v], e = A->ptr[v + 1];
    qsort(A->nb + b, e - b, sizeof *A->nb, cmp_idx);
    const size_t start = out;
    for (size_t q = b; q < e; q++)
      if (q == b || A->nb[q] != A->nb[q - 1]) A->nb[out++] = A->nb[q];
    A->ptr[v] = start;
  }
  A->ptr[nv] = out;
  return 0;
}

/* Triangular faces of the cells, as sorted triples. */
typedef struct {
  ss_idx v[3]; /* sorted corners */
} face;

static int face_cmp(const void *a, const void *b) {
  return memcmp(a, b, 3 * sizeof(ss_idx));
}

static face make_face(ss_idx a, ss_idx b, ss_idx c) {
  face f = {{a, b, c}};
  for (int i = 1; i < 3; i++)
    for (int j = i; j > 0 && f.v[j - 1] > f.v[j]; j--) {
      ss_idx t = f.v[j];
      f.v[j] = f.v[j - 1];
      f.v[j - 1] = t;
    }
  return f;
}

/* The faces held by exactly one tet or octahedron of coarse (the solid's
 * boundary), sorted, into a new array with room for `extra` more faces;
 * their number into *n.  NULL when out of memory. */
static face *held_once(const ss_cx *coarse, size_t extra, size_t *n) {
  const size_t nt = coarse->nc[SS_TET], no = coarse->nc[SS_OCT];
  face *f = malloc((4 * nt + 8 * no + extra + 1) * sizeof *f);
  if (!f) return NULL;
  size_t all = 0;
  for (size_t t = 0; t < nt; t++) {
    const ss_idx *v = ss_cx_cell(coarse, SS_TET, t);
    for (int i = 0; i < 4; i++)
      f[all++] = make_face(v[(i + 1) % 4], v[(i + 2) % 4], v[(i + 3) % 4]);
  }
  for (size_t o = 0; o < no; o++) {
    const ss_idx *v = ss_cx_cell(coarse, SS_OCT, o);
    for (int q = 0; q < 8; q++)
      f[all++] = make_face(v[q & 1 ? 3 : 0], v[q & 2 ? 4 : 1], v[q & 4 ? 5 : 2]);
  }
  qsort(f, all, sizeof *f, face_cmp);
  size_t m = 0; /* compacted in place, still sorted */
  for (size_t i = 0; i < all;) {
    size_t j = i + 1;
    while (j < all && face_cmp(f + i, f + j) == 0)
      j++;
    if (j - i == 1) f[m++] = f[i];
    i = j;
  }
  *n = m;
  return f;
}

/* The coarse complex's neighbourhoods, shared by both variants. */
typedef struct {
  adjacency nb;    /* boxspline: rho (edges and diagonals); avg: edges; only the
                      edges of tets and octahedra (a triangle cell's edges are
                      Loop's business) */
  adjacency opp;   /* avg: the corners opposite x in the octahedra holding x */
  adjacency inoct; /* avg: the octahedra holding x (as indices) */
  ss_idx *common;  /* scratch for one edge's neighbours */
} topo;

static void topo_free(topo *T) {
  adj_free(&T->nb);
  adj_free(&T->opp);
  adj_free(&T->inoct);
  free(T->common);
}

/* The tet/oct split's fine vertices are edge midpoints (2 parents) or
 * octahedron centres (6); anything else is a split this file cannot read. */
static ss_status check_parents(const ss_split *L, size_t nv, ss_error *err) {
  for (size_t f = nv; f < L->nfine; f++) {
    const size_t npar = ss_split_npar(L, f);
    if (npar != 2 && npar != 6)
      return ss_error_set(err, SS_EINTERNAL, "fine vertex %zu with %zu parents", f, npar);
  }
  return SS_OK;
}

/* Build T; with_diag adds the major diagonals (pair (0, 3) of each
 * octahedron) to the neighbours, as Definition 3.3 does; without, the
 * octahedra's opposite corners and incidences are listed instead.
 * The split's parents are checked first (check_parents). */
static ss_status topo_make(const ss_cx *coarse, const ss_split *L, int with_diag, topo *T,
                           ss_error *err) {
  const size_t nv = coarse->nv, nt = coarse->nc[SS_TET], no = coarse->nc[SS_OCT];
  memset(T, 0, sizeof *T);
  ss_status st = check_parents(L, nv, err);
  if (st) return st;
  ss_idx *pairs = malloc((2 * (6 * nt + 12 * no + 3 * no) + 1) * sizeof *pairs);
  if (!pairs) goto nomem;
  /* the edges of the tets and octahedra (a triangle cell's own edges are no
   * neighbours of rho: the solid's rules stay as without triangles) */
  size_t np = 0;
  const ss_cell_type solid[2] = {SS_TET, SS_OCT};
  for (int t = 0; t < 2; t++) {
    const int ne = ss_cell_nedges(solid[t]);
    for (size_t c = 0; c < coarse->nc[solid[t]]; c++) {
      const ss_idx *v = ss_cx_cell(coarse, solid[t], c);
      for (int e = 0; e < ne; e++) {
        int a, b;
        ss_cell_edge(solid[t], e, &a, &b);
        pairs[2 * np] = v[a];
        pairs[2 * np + 1] = v[b];
        np++;
      }
    }
  }
  if (with_diag)
    for (size_t o = 0; o < no; o++) { /* major diagonals: pair (0, 3) */
      const ss_idx *v = ss_cx_cell(coarse, SS_OCT, o);
      pairs[2 * np] = v[0];
      pairs[2 * np + 1] = v[3];
      np++;
    }
  if (adj_make(nv, np, pairs, &T->nb)) goto nomem;
  if (!with_diag) {
    /* opposite corners (all three pairs), and vertex-octahedron incidence as
     * pairs (vertex, nv + octahedron) folded back below */
    np = 0;
    for (size_t o = 0; o < no; o++) {
      const ss_idx *v = ss_cx_cell(coarse, SS_OCT, o);
      for (int i = 0; i < 3; i++) {
        pairs[2 * np] = v[i];
        pairs[2 * np + 1] = v[i + 3];
        np++;
      }
    }
    if (adj_make(nv, np, pairs, &T->opp)) goto nomem;
    /* incidence: a CSR of octahedra per vertex */
    T->inoct.ptr = calloc(nv + 1, sizeof *T->inoct.ptr);
    T->inoct.nb = malloc((6 * no + 1) * sizeof *T->inoct.nb);
    if (!T->inoct.ptr || !T->inoct.nb) goto nomem;
    for (size_t o = 0; o < no; o++)
      for (int i = 0; i < 6; i++)
        T->inoct.ptr[ss_cx_cell(coarse, SS_OCT, o)[i] + 1]++;
    for (size_t v = 0; v < nv; v++)
      T->inoct.ptr[v + 1] += T->inoct.ptr[v];
    size_t *fill = calloc(nv + 1, sizeof *fill);
    if (!fill) goto nomem;
    for (size_t o = 0; o < no; o++)
      for (int i = 0; i < 6; i++) {
        const ss_idx x = ss_cx_cell(coarse, SS_OCT, o)[i];
        T->inoct.nb[T->inoct.ptr[x] + fill[x]++] = (ss_idx)o;
      }
    free(fill);
  }
  size_t maxdeg = 0;
  for (size_t v = 0; v < nv; v++)
    maxdeg = T->nb.ptr[v + 1] - T->nb.ptr[v] > maxdeg ? T->nb.ptr[v + 1] - T->nb.ptr[v]
                                                      : maxdeg;
  size_t maxoct = 0; /* room for two corners per octahedron of an end */
  if (T->inoct.ptr)
    for (size_t v = 0; v < nv; v++)
      maxoct = T->inoct.ptr[v + 1] - T->inoct.ptr[v] > maxoct
                   ? T->inoct.ptr[v + 1] - T->inoct.ptr[v]
                   : maxoct;
  T->common = malloc((maxdeg + 2 * maxoct + 1) * sizeof *T->common);
  if (!T->common) goto nomem;
  free(pairs);
  return SS_OK;
nomem:
  free(pairs);
  topo_free(T);
  return ss_error_nomem(err, "box-spline neighbours");
}

/* A coarse edge's midpoint in the split: parents a < b, fine vertex m. */
typedef struct {
  ss_idx a, b, m;
} midpoint;

static int mid_cmp(const void *x, const void *y) {
  const midpoint *p = x, *q = y;
  if (p->a != q->a) return (p->a > q->a) - (p->a < q->a);
  return (p->b > q->b) - (p->b < q->b);
}

/* The fine vertex the split puts on the coarse edge (a, b), a < b. */
static ss_idx mid_of(const midpoint *mids, size_t n, ss_idx a, ss_idx b) {
  const midpoint key = {a, b, 0};
  const midpoint *hit = bsearch(&key, mids, n, sizeof *mids, mid_cmp);
  return hit ? hit->m : SS_IDX_NONE;
}

/* The surface Loop's rules refine (figure 14; figure 29's hybrid solid): the
 * coarse faces held by one tet or octahedron — the solid's boundary — and the
 * coarse triangle cells, each face once (a triangle cell on the boundary, as
 * TetGen's .face gives them, is that boundary face), each as its four fine
 * triangles (the fine boundary faces are the split's children of the coarse
 * ones), a Loop surface over the split L (ss_loop_surface, shared with
 * tet/oct's crease surfaces; its edges in three or more faces, where a
 * surface meets the solid, and its own boundary are crease curves).  Sorting
 * coarse faces, not fine ones, keeps it cheap.  SS_ENOMEM, SS_EINTERNAL. */
static ss_status loop_surface(const ss_scheme *s, const ss_cx *coarse, const ss_cx *fine,
                              const ss_split *L, ss_loop_surface **out, ss_error *err) {
  *out = NULL;
  const size_t ntri = coarse->nc[SS_TRIANGLE], nc = L->ncoarse;
  size_t m = 0; /* the faces held once, then the triangle cells */
  face *f = held_once(coarse, ntri, &m);
  midpoint *mids = malloc((L->nfine - nc + 1) * sizeof *mids);
  ss_idx *tri = NULL;
  ss_status st = SS_OK;
  if (!f || !mids) goto nomem;
  size_t nm = 0;
  for (size_t t = 0; t < ntri; t++) {
    const ss_idx *v = ss_cx_cell(coarse, SS_TRIANGLE, t);
    f[m++] = make_face(v[0], v[1], v[2]);
  }
  qsort(f, m, sizeof *f, face_cmp);
  for (size_t x = nc; x < L->nfine; x++) /* parents ascending (ss_split.h) */
    if (ss_split_npar(L, x) == 2)
      mids[nm++] = (midpoint){L->parent[L->ptr[x]], L->parent[L->ptr[x] + 1], (ss_idx)x};
  qsort(mids, nm, sizeof *mids, mid_cmp);
  if (!(tri = malloc((12 * m + 1) * sizeof *tri))) goto nomem;
  size_t u = 0;
  for (size_t i = 0; i < m; i++) {
    if (i > 0 && face_cmp(f + i - 1, f + i) == 0) continue;
    const ss_idx *v = f[i].v; /* sorted corners */
    const ss_idx m01 = mid_of(mids, nm, v[0], v[1]), m12 = mid_of(mids, nm, v[1], v[2]),
                 m02 = mid_of(mids, nm, v[0], v[2]);
    if (m01 == SS_IDX_NONE || m12 == SS_IDX_NONE || m02 == SS_IDX_NONE) {
      st =
          ss_error_set(err, SS_EINTERNAL, "box-spline surface: an edge with no midpoint");
      goto done;
    }
    const ss_idx kids[4][3] = {
        {v[0], m01, m02}, {v[1], m12, m01}, {v[2], m02, m12}, {m01, m12, m02}};
    memcpy(tri + 12 * u++, kids, sizeof kids);
  }
  ss_cx surf = {0};
  surf.dim = fine->dim;
  surf.nv = fine->nv;
  surf.nc[SS_TRIANGLE] = 4 * u;
  surf.cells[SS_TRIANGLE] = tri;
  st = ss_loop_surface_new(&surf, L, s->loop_c, out, err);
  goto done;
nomem:
  st = ss_error_nomem(err, "box-spline boundary surface");
done:
  free(f);
  free(mids);
  free(tri);
  return st;
}

/* The sorted intersection of the neighbour lists of a and b into
 * T->common; its length. */
static size_t common_neighbours(const topo *T, ss_idx a, ss_idx b) {
  size_t m = 0, p = T->nb.ptr[a], q = T->nb.ptr[b];
  while (p < T->nb.ptr[a + 1] && q < T->nb.ptr[b + 1]) {
    if (T->nb.nb[p] < T->nb.nb[q])
      p++;
    else if (T->nb.nb[p] > T->nb.nb[q])
      q++;
    else
      T->common[m++] = T->nb.nb[p], p++, q++;
  }
  return m;
}

/* (3.7) over the neighbour list of x (or keep x if it has none). */
static void vertex_rule(const topo *T, size_t x, ss_sink *k) {
  const size_t n = T->nb.ptr[x + 1] - T->nb.ptr[x];
  if (n == 0) { /* a vertex in no cell keeps its place */
    ss_sink_emit(k, x, x, 1.0);
    return;
  }
  ss_sink_emit(k, x, x, 9.0 / 16.0);
  for (size_t q = T->nb.ptr[x]; q < T->nb.ptr[x + 1]; q++)
    ss_sink_emit(k, x, T->nb.nb[q], 7.0 / (16.0 * (double)n));
}

/* (3.5) or (3.8) by the number m of neighbours in T->common. */
static void edge_rule(const topo *T, size_t f, ss_idx a, ss_idx b, size_t m, ss_sink *k) {
  if (m == 0) {
    ss_sink_emit(k, f, a, 0.5);
    ss_sink_emit(k, f, b, 0.5);
  } else if (m == 4) {
    ss_sink_emit(k, f, a, 8.0 / 32.0);
    ss_sink_emit(k, f, b, 8.0 / 32.0);
    for (size_t i = 0; i < m; i++)
      ss_sink_emit(k, f, T->common[i], 4.0 / 32.0);
  } else {
    ss_sink_emit(k, f, a, 5.0 / 16.0);
    ss_sink_emit(k, f, b, 5.0 / 16.0);
    for (size_t i = 0; i < m; i++)
      ss_sink_emit(k, f, T->common[i], 3.0 / (8.0 * (double)m));
  }
}

/* The octahedron centres: the split adds one per coarse octahedron, in order,
 * after the edge midpoints it creates; find each by its six parents and give
 * it weight w_end on the diagonal's ends and w_corner on the other corners. */
static ss_status centres(const ss_cx *coarse, const ss_split *L, double w_end,
                         double w_corner, ss_sink *k, ss_error *err) {
  const size_t nv = coarse->nv, no = coarse->nc[SS_OCT];
  size_t oc = 0;
  for (size_t f = nv; f < L->nfine && oc < no; f++) {
    if (ss_split_npar(L, f) != 6) continue;
    const ss_idx *v = ss_cx_cell(coarse, SS_OCT, oc);
    ss_idx sorted[6];
    memcpy(sorted, v, sizeof sorted);
    qsort(sorted, 6, sizeof *sorted, cmp_idx);
    if (memcmp(sorted, L->parent + L->ptr[f], sizeof sorted) != 0)
      return ss_error_set(err, SS_EINTERNAL,
                          "octahedron %zu: its centre is not where the split put it", oc);
    for (int i = 0; i < 6; i++)
      ss_sink_emit(k, f, v[i], i == 0 || i == 3 ? w_end : w_corner);
    oc++;
  }
  if (oc != no) return ss_error_set(err, SS_EINTERNAL, "octahedron centres missing");
  return SS_OK;
}

static ss_status boxspline_rule(const ss_scheme *s, const ss_cx *coarse,
                                const ss_cx *fine, const ss_split *L, ss_sink *k,
                                ss_error *err) {
  const size_t nv = coarse->nv;
  topo T;
  ss_loop_surface *S = NULL;
  ss_status st = topo_make(coarse, L, 1, &T, err);
  if (st) return st;
  if ((st = loop_surface(s, coarse, fine, L, &S, err))) goto done;
  for (size_t x = 0; x < nv; x++)
    if (!ss_loop_surface_emit(S, L, x, k)) /* on the surface: Loop's row */
      vertex_rule(&T, x, k);               /* rho(x): (3.7), i.e. (3.3) at 14 */
  for (size_t f = nv; f < L->nfine; f++) {
    if (ss_split_npar(L, f) != 2 || ss_loop_surface_emit(S, L, f, k)) continue;
    const ss_idx a = L->parent[L->ptr[f]], b = L->parent[L->ptr[f] + 1];
    /* rho(e) = rho(a) ∩ rho(b): (3.4) at 6 is (3.8) */
    edge_rule(&T, f, a, b, common_neighbours(&T, a, b), k);
  }
  st = centres(coarse, L, 8.0 / 32.0, 4.0 / 32.0, k, err); /* (3.6) */
done:
  ss_loop_surface_free(S);
  topo_free(&T);
  return st;
}

/* Appendix A's averaged weights, as means over the three directions of the
 * regular rules' weights (see the file comment). */
#define AVG3(a, b, c) (((a) + (b) + (c)) / 3.0)
static const double avg_edge_end = AVG3(10.0 / 32, 10.0 / 32, 8.0 / 32);    /* 7/24 */
static const double avg_edge_apex = 4 * AVG3(2.0 / 32, 2.0 / 32, 4.0 / 32); /* 1/3 */
static const double avg_edge_opp = 4 * AVG3(2.0 / 32, 0.0, 0.0);            /* 1/12 */
static const double avg_vertex_edge = 12 * (1.0 / 32);                      /* 3/8 */
static const double avg_vertex_opp = 6 * AVG3(1.0 / 32, 0.0, 0.0);          /* 1/16 */

static ss_status boxspline_avg_rule(const ss_scheme *s, const ss_cx *coarse,
                                    const ss_cx *fine, const ss_split *L, ss_sink *k,
                                    ss_error *err) {
  const size_t nv = coarse->nv;
  topo T;
  ss_loop_surface *S = NULL;
  ss_status st = topo_make(coarse, L, 0, &T, err);
  if (st) return st;
  if ((st = loop_surface(s, coarse, fine, L, &S, err))) goto done;
  for (size_t x = 0; x < nv; x++) {
    const size_t ne = T.nb.ptr[x + 1] - T.nb.ptr[x], no = T.opp.ptr[x + 1] - T.opp.ptr[x];
    if (ss_loop_surface_emit(S, L, x, k)) {
      continue; /* on the surface: Loop's row */
    } else if (no == 0 || ne == 0) {
      vertex_rule(&T, x, k); /* no octahedron, no diagonal: (3.7) */
    } else {
      ss_sink_emit(k, x, x, 9.0 / 16.0);
      for (size_t q = T.nb.ptr[x]; q < T.nb.ptr[x + 1]; q++)
        ss_sink_emit(k, x, T.nb.nb[q], avg_vertex_edge / (double)ne);
      for (size_t q = T.opp.ptr[x]; q < T.opp.ptr[x + 1]; q++)
        ss_sink_emit(k, x, T.opp.nb[q], avg_vertex_opp / (double)no);
    }
  }
  for (size_t f = nv; f < L->nfine; f++) {
    if (ss_split_npar(L, f) != 2 || ss_loop_surface_emit(S, L, f, k)) continue;
    const ss_idx a = L->parent[L->ptr[f]], b = L->parent[L->ptr[f] + 1];
    const size_t m = common_neighbours(&T, a, b);
    /* the corners opposite a and b in the octahedra holding both */
    size_t q = 0;
    for (size_t i = T.inoct.ptr[a]; i < T.inoct.ptr[a + 1]; i++) {
      const ss_idx *v = ss_cx_cell(coarse, SS_OCT, T.inoct.nb[i]);
      int ia = -1, ib = -1;
      for (int j = 0; j < 6; j++)
        ia = v[j] == a ? j : ia, ib = v[j] == b ? j : ib;
      if (ib < 0) continue;
      T.common[m + q++] = v[(ia + 3) % 6];
      T.common[m + q++] = v[(ib + 3) % 6];
    }
    if (q == 0 || m == 0) {
      edge_rule(&T, f, a, b, m, k); /* no octahedron: (3.5)/(3.8) */
      continue;
    }
    ss_sink_emit(k, f, a, avg_edge_end);
    ss_sink_emit(k, f, b, avg_edge_end);
    for (size_t i = 0; i < m; i++)
      ss_sink_emit(k, f, T.common[i], avg_edge_apex / (double)m);
    for (size_t i = 0; i < q; i++)
      ss_sink_emit(k, f, T.common[m + i], avg_edge_opp / (double)q);
  }
  /* (3.6) averaged: every corner is a diagonal end in one direction of three */
  const double c = AVG3(8.0 / 32, 4.0 / 32, 4.0 / 32);
  st = centres(coarse, L, c, c, k, err);
done:
  ss_loop_surface_free(S);
  topo_free(&T);
  return st;
}

ss_status ss_scheme_boxspline_new(ss_scheme **out, ss_error *err) {
  const unsigned accepts = (1u << SS_TRIANGLE) | (1u << SS_TET) | (1u << SS_OCT);
  ss_status st =
      ss_scheme_alloc("boxspline", SS_SPLIT_TETOCT, accepts, boxspline_rule, out, err);
  if (!st) {
    (*out)->reach = 2; /* rho(e) reads both ends' neighbourhoods */
    (*out)->diagonals = 1;
    (*out)->loop_c_choice = 1; /* figure 14(b)'s c */
  }
  return st;
}

ss_status ss_scheme_boxspline_avg_new(ss_scheme **out, ss_error *err) {
  const unsigned accepts = (1u << SS_TRIANGLE) | (1u << SS_TET) | (1u << SS_OCT);
  ss_status st = ss_scheme_alloc("boxspline-avg", SS_SPLIT_TETOCT, accepts,
                                 boxspline_avg_rule, out, err);
  if (!st) {
    (*out)->reach = 2; /* common neighbours of both ends */
    (*out)->loop_c_choice = 1;
  }
  return st;
}

/* The solid's boundary for the neighbours family, whose boundary rule is its
 * own (weights per valence) where the built-in schemes refine the boundary
 * as a Loop surface (loop_surface above): the faces held by one tet or
 * octahedron, sorted; their edges as an adjacency; the vertices on them. */
typedef struct {
  face *faces;        /* the boundary faces, sorted */
  size_t n;           /* their number */
  adjacency bnd;      /* the boundary edges */
  unsigned char *onb; /* nv flags: on the boundary */
} nb_boundary;

static void nb_boundary_free(nb_boundary *B) {
  free(B->faces);
  adj_free(&B->bnd);
  free(B->onb);
}

static ss_status nb_boundary_make(const ss_cx *coarse, nb_boundary *B, ss_error *err) {
  const size_t nv = coarse->nv;
  memset(B, 0, sizeof *B);
  B->faces = held_once(coarse, 0, &B->n);
  B->onb = calloc(nv + 1, 1);
  ss_idx *pairs = B->faces ? malloc((6 * B->n + 1) * sizeof *pairs) : NULL;
  if (!B->faces || !B->onb || !pairs) goto nomem;
  for (size_t i = 0; i < B->n; i++) {
    const ss_idx *v = B->faces[i].v;
    for (int e = 0; e < 3; e++) {
      pairs[6 * i + 2 * (size_t)e] = v[e];
      pairs[6 * i + 2 * (size_t)e + 1] = v[(e + 1) % 3];
      B->onb[v[e]] = 1;
    }
  }
  if (adj_make(nv, 3 * B->n, pairs, &B->bnd)) goto nomem;
  free(pairs);
  return SS_OK;
nomem:
  free(pairs);
  nb_boundary_free(B);
  return ss_error_nomem(err, "box-spline neighbours family: boundary");
}

/* The vertices opposite the edge (a, b) in boundary faces, into T->common;
 * their number (0 when an end is off the boundary or the edge is in no
 * boundary face). */
static size_t boundary_opposite(const nb_boundary *B, const topo *T, ss_idx a, ss_idx b) {
  if (!B->onb[a] || !B->onb[b]) return 0;
  size_t m = 0;
  for (size_t q = B->bnd.ptr[a]; q < B->bnd.ptr[a + 1]; q++) {
    const ss_idx c = B->bnd.nb[q];
    if (c == b) continue;
    const face t = make_face(a, b, c);
    if (bsearch(&t, B->faces, B->n, sizeof *B->faces, face_cmp)) T->common[m++] = c;
  }
  return m;
}

/* ---- the neighbours family: these rules with weights per valence ---- */

/* Weight key of rule r at valence n (SS_AVG_NMAX at most: the caller checks). */
static double nbw(const ss_scheme *s, int r, int key, size_t n) {
  return s->ptab[(size_t)(r * 2 + key) * (SS_AVG_NMAX + 1) + n];
}

/* The valence n of a rule beyond the tables: SS_EINPUT naming the vertex. */
static ss_status beyond(const ss_scheme *s, size_t x, size_t n, ss_error *err) {
  return ss_error_set(err, SS_EINPUT,
                      "scheme %s: fine vertex %zu has %zu neighbours in its rule, beyond "
                      "the valences its weights are given for (1..%d)",
                      s->name, x + 1, n, SS_AVG_NMAX);
}

/* Fine vertex f: self weight ws on x (or ws / 2 on each of x and y when y is
 * given), wn / n on each of the n vertices nb. */
static void emit_shared(ss_sink *k, size_t f, ss_idx x, ss_idx y, double ws, double wn,
                        const ss_idx *nb, size_t n) {
  if (y == SS_IDX_NONE) {
    ss_sink_emit(k, f, x, ws);
  } else {
    ss_sink_emit(k, f, x, ws / 2.0);
    ss_sink_emit(k, f, y, ws / 2.0);
  }
  for (size_t i = 0; i < n; i++)
    ss_sink_emit(k, f, nb[i], wn / (double)n);
}

/* The boundary edge point f of (a, b) by the family's weights if both ends
 * are on the boundary and the edge is in a boundary triangle; 1 if
 * emitted, -1 beyond the tables. */
static int nb_boundary_edge(const ss_scheme *s, const nb_boundary *B, const topo *T,
                            size_t f, ss_idx a, ss_idx b, ss_sink *k) {
  const size_t m = boundary_opposite(B, T, a, b);
  if (m == 0) return 0;
  if (m > SS_AVG_NMAX) return -1;
  emit_shared(k, f, a, b, nbw(s, SS_NB_BEDGE, 0, m), nbw(s, SS_NB_BEDGE, 1, m), T->common,
              m);
  return 1;
}

static ss_status neighbours_rule(const ss_scheme *s, const ss_cx *coarse,
                                 const ss_cx *fine, const ss_split *L, ss_sink *k,
                                 ss_error *err) {
  (void)fine;
  const size_t nv = coarse->nv;
  topo T;
  nb_boundary B;
  ss_status st = topo_make(coarse, L, 1, &T, err);
  if (st) return st;
  if ((st = nb_boundary_make(coarse, &B, err))) {
    topo_free(&T);
    return st;
  }
  for (size_t x = 0; x < nv && !st; x++) {
    const adjacency *A = B.onb[x] ? &B.bnd : &T.nb;
    const int r = B.onb[x] ? SS_NB_BVERTEX : SS_NB_VERTEX;
    const size_t n = A->ptr[x + 1] - A->ptr[x];
    if (n > SS_AVG_NMAX)
      st = beyond(s, x, n, err);
    else if (n == 0) /* a vertex in no cell keeps its place */
      ss_sink_emit(k, x, x, 1.0);
    else
      emit_shared(k, x, (ss_idx)x, SS_IDX_NONE, nbw(s, r, 0, n), nbw(s, r, 1, n),
                  A->nb + A->ptr[x], n);
  }
  for (size_t f = nv; f < L->nfine && !st; f++) {
    if (ss_split_npar(L, f) != 2) continue;
    const ss_idx a = L->parent[L->ptr[f]], b = L->parent[L->ptr[f] + 1];
    const int bd = nb_boundary_edge(s, &B, &T, f, a, b, k);
    if (bd) {
      if (bd < 0) st = beyond(s, f, SS_AVG_NMAX + 1, err);
      continue;
    }
    const size_t m = common_neighbours(&T, a, b);
    if (m > SS_AVG_NMAX)
      st = beyond(s, f, m, err);
    else if (m == 0) /* no common neighbour: the midpoint */
      emit_shared(k, f, a, b, 1.0, 0.0, NULL, 0);
    else
      emit_shared(k, f, a, b, nbw(s, SS_NB_EDGE, 0, m), nbw(s, SS_NB_EDGE, 1, m),
                  T.common, m);
  }
  if (!st)
    st = centres(coarse, L, nbw(s, SS_NB_CENTRE, 0, 6) / 2.0,
                 nbw(s, SS_NB_CENTRE, 1, 6) / 4.0, k, err);
  topo_free(&T);
  nb_boundary_free(&B);
  return st;
}

ss_status ss_scheme_neighbours_new(const char *name, const ss_neighbours *nb,
                                   ss_scheme **out, ss_error *err) {
  *out = NULL;
  const size_t NN = SS_AVG_NMAX + 1;
  double *tab = calloc(SS_NB_RULES * 2 * NN, sizeof *tab);
  if (!tab) return ss_error_nomem(err, "neighbours weights");
  static const char *const rules[SS_NB_RULES] = {"vertex", "edge", "centre",
                                                 "boundary vertex", "boundary edge"};
  for (int r = 0; r < SS_NB_RULES; r++)
    for (size_t n = 1; n < NN; n++) {
      double sum = 0.0;
      for (int key = 0; key < 2; key++) {
        const double v = nb->w[r][key] ? nb->w[r][key][n] : 0.0;
        tab[(size_t)(r * 2 + key) * NN + n] = v;
        sum += v;
      }
      if (!(fabs(sum - 1.0) <= 1e-12)) {
        free(tab);
        return ss_error_set(err, SS_EINPUT,
                            "scheme %s: the %s weights sum to %.17g at n = %zu, not 1",
                            name, rules[r], sum, n);
      }
    }
  const unsigned accepts = (1u << SS_TET) | (1u << SS_OCT);
  ss_status st =
      ss_scheme_alloc(name, SS_SPLIT_TETOCT, accepts, neighbours_rule, out, err);
  if (st) {
    free(tab);
    return st;
  }
  (*out)->ptab = tab;
  (*out)->irrational = !nb->rational;
  (*out)->irrational_volume = !nb->rational_volume;
  (*out)->reach = 2; /* rho(e) reads both ends' neighbourhoods */
  (*out)->diagonals = 1;
  return SS_OK;
}
