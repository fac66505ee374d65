/* ss_scheme_quasi48.c — quasi 4-8 subdivision surfaces (Velho & Gomes,
 * "Quasi 4-8 subdivision surfaces", sections 3.1-3.2).
 *
 * One level is one pass of the paper's Algorithm 1 (the bisect split,
 * ss_split_bisect.c: longest edges first, one split edge per triangle) followed
 * by the cascade convolution of section 3.2.  On a regular 4-8 mesh one level
 * is one of the two interleaved binary steps (figure 3); two levels make one
 * full 4-8 refinement (a dyadic step).  With the split positions (midpoints)
 * and the coarse points p:
 *   new vertex x    p'(x) = 1/4 sum of its 4 neighbours (figure 5): the two
 *                   ends of its edge and the two opposite corners, all coarse;
 *   old vertex v    p'(v) = 1/2 p(v) + 1/(2n) sum of p'(x) over the n new
 *                   neighbours x of v (the cascade of section 3.2, which for a
 *                   regular valence-8 vertex is the mask of figure 6 and for
 *                   valence n that of figure 7).
 * Choices the paper leaves open (also in docs/schemes.md, "Quasi 4-8 surfaces"):
 *  - boundaries (section 4.3, ss_boundary): "boundary vertices are
 *    constrained to move along the surface normal direction", and figure
 *    15(c)'s untagged "boundary curves are smooth".  The paper gives no curve
 *    rule; here it is the cascade along the boundary (a new boundary vertex
 *    stays at its midpoint, an old one becomes 1/2 itself + 1/(2k) its k new
 *    boundary neighbours: the cubic B-spline where every edge splits), and
 *    by default (SS_BOUNDARY_NORMAL) an old vertex's displacement is then
 *    projected on its surface normal (normal_boundary, after the rows, in
 *    positions: a projection that depends on positions has no operator).  A
 *    planar surface's boundary so stays where it is, section 4.1's "boundary
 *    vertices are not allowed to move".  SS_BOUNDARY_SMOOTH keeps the curve
 *    rule unprojected, SS_BOUNDARY_FIXED the boundary polygon;
 *  - an interior old vertex with no new neighbour (n = 0, possible where the
 *    clusters leave a vertex untouched) keeps its position;
 *  - a new vertex on an interior edge that is adjacent to a boundary new
 *    vertex uses that vertex's (midpoint) value in the cascade as any other;
 *  - tags (section 4.3, "a tagged vertex or edge is not affected by
 *    smoothing"): a vertex cell keeps its vertex where it is, a segment cell
 *    (a tagged edge; the split halves it with its edge) keeps the new vertex
 *    on it at its midpoint — both then enter the cascade as boundary points
 *    do; a boundary vertex that ends a segment cell is kept (figure 15(c):
 *    smooth "except at the vertex shared with the tagged edge");
 *  - adaptive levels (ss_scheme_set_adapt): the split bisects only where a
 *    criterion asks (ss_split_refine_adapt); this rule is unchanged, and an
 *    old vertex with no new neighbour keeps its place, so the mesh away from
 *    the refined triangles stays put. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_scheme_impl.h"
#include "ss_triedge.h"

/* Weight of each of an interior new vertex's four neighbours (figure 5); the
 * cascade of the old vertices reads p'(x) through the same weight. */
static const double new_weight = 0.25;

/* What the rule makes of each fine vertex of the split. */
typedef struct {
  unsigned char *fixed; /* nv: keeps its split position (boundary, tagged) */
  unsigned char *curve; /* nv: an old boundary vertex the curve rule smooths
                           (ss_boundary) */
  ss_idx *bn;           /* 2 nv: a curve vertex's two boundary neighbours */
} roles;

static void roles_free(roles *r) {
  free(r->fixed);
  free(r->curve);
  free(r->bn);
}

/* The roles of the vertices of the split `fine` (te its edges, nc old
 * vertices) under the scheme's boundary rule: fixed are the boundary vertices
 * and the tagged ones (a vertex cell, a new vertex on a segment cell); of the
 * old boundary vertices, those the curve rule smooths (not tagged, not ending
 * a segment cell, on exactly two boundary edges) are curve instead. */
static ss_status find_roles(const ss_scheme *s, const ss_cx *fine, const ss_triedge *te,
                            size_t nc, roles *r, ss_error *err) {
  const size_t nv = fine->nv;
  unsigned char *nb = calloc(nv + 1, 1), *tagged = calloc(nv + 1, 1);
  r->fixed = malloc(nv + 1);
  r->curve = calloc(nv + 1, 1);
  r->bn = malloc(2 * nv * sizeof *r->bn + 1);
  if (!nb || !tagged || !r->fixed || !r->curve || !r->bn) {
    free(nb);
    free(tagged);
    roles_free(r);
    return ss_error_nomem(err, "quasi48 tags");
  }
  memcpy(r->fixed, te->vbnd, nv);
  for (size_t i = 0; i < fine->nc[SS_VERTEX]; i++)
    r->fixed[fine->cells[SS_VERTEX][i]] = tagged[fine->cells[SS_VERTEX][i]] = 1;
  for (size_t i = 0; i < 2 * fine->nc[SS_SEGMENT]; i++) {
    const ss_idx v = fine->cells[SS_SEGMENT][i];
    tagged[v] = 1;
    if (v >= nc) r->fixed[v] = 1;
  }
  /* with fewer than three coordinates the surface's normal leaves them: a
   * normal-constrained boundary does not move */
  const int moves = s->boundary == SS_BOUNDARY_SMOOTH ||
                    (s->boundary == SS_BOUNDARY_NORMAL && fine->dim >= 3);
  for (size_t e = 0; moves && e < te->ne; e++) {
    if (te->nface[e] != 1) continue;
    for (int j = 0; j < 2; j++) {
      const ss_idx v = te->end[2 * e + j], w = te->end[2 * e + 1 - j];
      if (nb[v] < 2) r->bn[2 * (size_t)v + nb[v]] = w;
      if (nb[v] < 3) nb[v]++;
    }
  }
  for (size_t v = 0; moves && v < nc; v++)
    r->curve[v] = te->vbnd[v] && nb[v] == 2 && !tagged[v];
  free(nb);
  free(tagged);
  return SS_OK;
}

/* The new boundary neighbours of curve vertex v (k of them, into x). */
static size_t new_boundary_nbrs(const roles *r, size_t v, size_t nc, ss_idx x[2]) {
  size_t k = 0;
  for (int j = 0; j < 2; j++)
    if (r->bn[2 * v + (size_t)j] >= nc) x[k++] = r->bn[2 * v + (size_t)j];
  return k;
}

/* An old vertex v's row: the cascade, or the curve rule on the boundary. */
static void old_row(const ss_triedge *te, const roles *r, size_t nc, size_t v,
                    ss_sink *k) {
  if (r->curve[v]) {
    ss_idx x[2];
    if (!new_boundary_nbrs(
            r, v, nc, x)) { /* no boundary edge of v splits: kept, as an interior n = 0 */
      ss_sink_emit(k, v, v, 1.0);
      return;
    }
    ss_sink_emit(k, v, v, 0.75);
    for (int j = 0; j < 2; j++) { /* the coarse polygon's neighbours */
      ss_idx w = r->bn[2 * v + (size_t)j];
      if (w >= nc) /* a midpoint: its edge's other end */
        w = r->bn[2 * (size_t)w] == v ? r->bn[2 * (size_t)w + 1] : r->bn[2 * (size_t)w];
      ss_sink_emit(k, v, w, 0.125);
    }
    return;
  }
  size_t n = 0;
  for (size_t q = te->vptr[v]; q < te->vptr[v + 1]; q++)
    n += te->vnbr[q] >= nc;
  if (r->fixed[v] || n == 0) {
    ss_sink_emit(k, v, v, 1.0);
    return;
  }
  ss_sink_emit(k, v, v, 0.5);
  const double w = 1.0 / (2.0 * (double)n);
  for (size_t q = te->vptr[v]; q < te->vptr[v + 1]; q++) {
    size_t x = te->vnbr[q];
    if (x < nc) continue;
    if (r->fixed[x]) {
      ss_sink_emit(k, v, x, w);
      continue;
    }
    for (size_t s = te->vptr[x]; s < te->vptr[x + 1]; s++)
      ss_sink_emit(k, v, te->vnbr[s], new_weight * w);
  }
}

/* The normal boundary (SS_BOUNDARY_NORMAL), after the rows: each curve
 * vertex v the curve rule moved (a new boundary neighbour) goes to
 * x + n (n . (y - x)) / |n|^2 in the first three coordinates, x its position,
 * y the rule's (in k's positions), n the sum of the cross products of the
 * coarse triangles at v (area-weighted normal); a zero or non-finite n keeps
 * x.  Building an operator (k's operator mode) it refuses instead: the
 * projection depends on the positions. */
static ss_status normal_boundary(const ss_scheme *s, const ss_cx *coarse, const roles *r,
                                 ss_sink *k, ss_error *err) {
  if (s->boundary != SS_BOUNDARY_NORMAL || coarse->dim < 3) return SS_OK;
  const size_t nc = coarse->nv, dim = (size_t)coarse->dim;
  size_t moved = 0, first = 0;
  ss_idx x2[2];
  for (size_t v = nc; v-- > 0;)
    if (r->curve[v] && new_boundary_nbrs(r, v, nc, x2)) {
      moved++;
      first = v;
    }
  if (!moved) return SS_OK;
  if (k->M || k->rows)
    return ss_error_set(err, SS_EINPUT,
                        "quasi48's normal-constrained boundary moves boundary vertex %zu "
                        "along its normal, which no refinement operator does: choose the "
                        "smooth or fixed boundary for an operator",
                        first + 1);
  double *nrm = calloc(3 * nc + 1, sizeof *nrm);
  if (!nrm) return ss_error_nomem(err, "quasi48 boundary normals");
  for (size_t t = 0; t < coarse->nc[SS_TRIANGLE]; t++) {
    const ss_idx *c = ss_cx_cell(coarse, SS_TRIANGLE, t);
    if (!r->curve[c[0]] && !r->curve[c[1]] && !r->curve[c[2]]) continue;
    double a[3], b[3];
    for (int i = 0; i < 3; i++) {
      a[i] = coarse->x[c[1] * dim + (size_t)i] - coarse->x[c[0] * dim + (size_t)i];
      b[i] = coarse->x[c[2] * dim + (size_t)i] - coarse->x[c[0] * dim + (size_t)i];
    }
    const double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]};
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3 && r->curve[c[j]]; i++)
        nrm[3 * c[j] + (size_t)i] += n[i];
  }
  for (size_t v = 0; v < nc; v++) {
    if (!r->curve[v] || !new_boundary_nbrs(r, v, nc, x2)) continue;
    const double *n = nrm + 3 * v, *p = coarse->x + v * dim;
    double *q = k->y + v * dim;
    const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const double t = n[0] * (q[0] - p[0]) + n[1] * (q[1] - p[1]) + n[2] * (q[2] - p[2]);
    for (int i = 0; i < 3; i++)
      q[i] = nn > 0.0 && isfinite(t / nn) ? p[i] + n[i] * (t / nn) : p[i];
  }
  free(nrm);
  return SS_OK;
}

static ss_status quasi48_rule(const ss_scheme *s, const ss_cx *coarse, const ss_cx *fine,
                              const ss_split *L, ss_sink *k, ss_error *err) {
  ss_triedge *te = NULL;
  roles r = {NULL, NULL, NULL};
  ss_status st = ss_triedge_new(fine, &te, err);
  if (st || (st = find_roles(s, fine, te, L->ncoarse, &r, err))) {
    ss_triedge_free(te);
    return st;
  }
  const size_t nc = L->ncoarse;
  for (size_t x = nc; x < fine->nv && !st; x++) {
    if (r.fixed[x]) {
      ss_sink_emit(k, x, x, 1.0);
      continue;
    }
    /* an interior bisection point has exactly its edge's two ends and the two
     * opposite corners as neighbours, all old (one split edge per triangle) */
    const size_t val = te->vptr[x + 1] - te->vptr[x];
    if (val != 4) {
      st = ss_error_set(err, SS_EINTERNAL,
                        "quasi48: new vertex %zu has valence %zu, not 4", x + 1, val);
      break;
    }
    for (size_t q = te->vptr[x]; q < te->vptr[x + 1]; q++)
      ss_sink_emit(k, x, te->vnbr[q], new_weight);
  }
  for (size_t v = 0; v < nc && !st; v++)
    old_row(te, &r, nc, v, k);
  if (!st) st = normal_boundary(s, coarse, &r, k, err);
  ss_triedge_free(te);
  roles_free(&r);
  return st;
}

ss_status ss_scheme_quasi48_new(ss_scheme **out, ss_error *err) {
  unsigned accepts = (1u << SS_VERTEX) | (1u << SS_SEGMENT) | (1u << SS_TRIANGLE);
  ss_status st =
      ss_scheme_alloc("quasi48", SS_SPLIT_BISECT, accepts, quasi48_rule, out, err);
  /* an old vertex reads the neighbours of its new neighbours: the coarse
   * 1-rings of the vertices it combines */
  if (!st) (*out)->reach = 2;
  /* the analysis refines stars topologically, a full 4-8 cycle per step
   * (ss_scheme_refine_step): on a 4-8 mesh the longest-edge criterion and the
   * topological one agree (section 2.3) */
  if (!st) {
    (*out)->step_split = SS_SPLIT_NVB;
    (*out)->step_passes = 2;
    (*out)->ring_depth = 3; /* the step's rows reach far (ss_scheme.h) */
  }
  return st;
}
