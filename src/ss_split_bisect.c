/* ss_split_bisect.c — one pass of the quasi 4-8 refinement (Velho & Gomes,
 * "Quasi 4-8 subdivision surfaces", Algorithm 1): bisect the longest edges,
 * at most one per triangle, and halve every triangle holding a split edge.
 *
 * This split is geometry-sensitive: it reads the coarse positions (coarse->x)
 * to rank edges by length.  The paper leaves open how ties are broken
 * ("sorts edges by decreasing length and radially around each vertex"); here
 * the order is deterministic:
 *  - lengths are compared after rounding the squared length to 2^-36 of the
 *    mesh's largest squared edge length, so that edges equal in exact
 *    arithmetic but not in floating point (a regular polygon's spokes) tie;
 *  - among tied edges the one with the smaller lower endpoint goes first, then
 *    the smaller higher endpoint.  Around a vertex whose neighbours are
 *    numbered in turn this takes every other spoke, the paper's "radial"
 *    choice for a regular n-gon fan (section 3.3).
 * Processing edges in that order, an unmarked edge splits and marks its
 * cluster: itself and every edge of the (at most two) triangles holding it
 * (mark_cluster, figure 4), so no triangle has two split edges.  A triangle
 * (p, a, c) whose edge (a, c) opposite corner p split at m becomes (p, a, m)
 * and (p, m, c), both oriented as the parent; other triangles are
 * copied.  New vertices (midpoints, two parents) are numbered in the order
 * their edges split.
 *
 * Refused (SS_EINPUT): an edge held by more than two triangles (non-manifold:
 * its cluster is undefined), two triangles on an edge with the same third
 * corner (a doubled triangle: the split point would not have the four
 * neighbours of section 3.2) and a zero-length edge (the longest-edge order is
 * undefined among its triangle's edges).  Vertex cells are copied; a segment
 * cell (a tagged edge, quasi 4-8 section 4.3) on a split edge becomes its two
 * halves (a, m), (m, b), any other segment is copied; the split takes no
 * other cells.
 *
 * Adaptive pass (ss_split_refine_adapt): the whole pass's split edges are
 * found as above, then only those of the triangles a criterion wants and of
 * their closure split (restrict_splits); numbering as in the whole pass, so a
 * criterion that wants every triangle gives it bit for bit. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "ss_split_builder.h"
#include "ss_split_impl.h"
#include "ss_split_tri.h"

typedef struct {
  uint64_t key; /* rounded squared length */
  ss_idx lo, hi;
  size_t e; /* edge index */
} ranked;

/* Longest first, then ascending endpoints. */
static int cmp_ranked(const void *a, const void *b) {
  const ranked *x = a, *y = b;
  if (x->key != y->key) return (x->key < y->key) - (x->key > y->key);
  if (x->lo != y->lo) return (x->lo > y->lo) - (x->lo < y->lo);
  return (x->hi > y->hi) - (x->hi < y->hi);
}

/* Squared length of the edge (a, b) with every coordinate difference
 * multiplied by `scale`, a power of two chosen from the whole mesh (see
 * diff_scale): exact rescaling, so the ranking does not depend on the mesh's
 * units, and neither tiny (1e-170) nor huge (1e160) coordinates under- or
 * overflow the square. */
static double len2(const ss_cx *cx, ss_idx a, ss_idx b, double scale) {
  const size_t dim = (size_t)cx->dim;
  double s = 0.0;
  for (size_t r = 0; r < dim; r++) {
    double d = (cx->x[(size_t)a * dim + r] - cx->x[(size_t)b * dim + r]) * scale;
    s += d * d;
  }
  return s;
}

/* Largest |coordinate difference| along the edge (a, b); +inf or NaN if a
 * coordinate or the difference is not finite. */
static double max_diff(const ss_cx *cx, ss_idx a, ss_idx b) {
  const size_t dim = (size_t)cx->dim;
  double m = 0.0;
  for (size_t r = 0; r < dim; r++) {
    double d = fabs(cx->x[(size_t)a * dim + r] - cx->x[(size_t)b * dim + r]);
    if (!(d <= m)) m = d; /* NaN propagates */
  }
  return m;
}

/* The index of the edge (a, b) in te, or SIZE_MAX when no triangle has it. */
static size_t find_edge(const ss_triedge *te, ss_idx a, ss_idx b) {
  const ss_idx lo = a < b ? a : b, hi = a < b ? b : a;
  size_t l = 0, h = te->ne;
  while (l < h) { /* edges sorted by their (lo, hi) ends */
    const size_t m = l + (h - l) / 2;
    const ss_idx *e = te->end + 2 * m;
    if (e[0] < lo || (e[0] == lo && e[1] < hi))
      l = m + 1;
    else
      h = m;
  }
  return l < te->ne && te->end[2 * l] == lo && te->end[2 * l + 1] == hi ? l : SIZE_MAX;
}

/* Refuse doubled triangles and zero-length or non-finite edges; else rank
 * the edges into order[0..ne) (longest first, ties by endpoints). */
static ss_status rank_edges(const ss_cx *coarse, const ss_triedge *te, ranked *order,
                            ss_error *err) {
  const size_t ne = te->ne;
  /* two triangles on one edge with the same third corner (a doubled triangle)
   * would give the split point 3 neighbours, not the 4 of section 3.2 */
  for (size_t e = 0; e < ne; e++) {
    if (te->nface[e] != 2) continue;
    ss_idx opp[2];
    for (int j = 0; j < 2; j++) {
      size_t t = te->face[2 * e + (size_t)j];
      int k = 0;
      while (k < 2 && te->tedge[3 * t + (size_t)k] != e)
        k++;
      opp[j] = ss_cx_cell(coarse, SS_TRIANGLE, t)[k];
    }
    if (opp[0] == opp[1])
      return ss_error_set(err, SS_EINPUT,
                          "doubled triangle: both triangles on the edge between vertices "
                          "%lu and %lu have the third corner %lu",
                          (unsigned long)te->end[2 * e] + 1,
                          (unsigned long)te->end[2 * e + 1] + 1,
                          (unsigned long)opp[0] + 1);
  }
  double big = 0.0, dmax = 0.0;
  for (size_t e = 0; e < ne; e++) {
    double l = max_diff(coarse, te->end[2 * e], te->end[2 * e + 1]);
    if (!(l > 0.0))
      return ss_error_set(err, SS_EINPUT,
                          "degenerate edge: vertices %lu and %lu coincide (zero-length "
                          "edge), so the longest edge of its triangles is undefined",
                          (unsigned long)te->end[2 * e] + 1,
                          (unsigned long)te->end[2 * e + 1] + 1);
    if (!isfinite(l))
      return ss_error_set(err, SS_EINPUT,
                          "the edge between vertices %lu and %lu has no finite length "
                          "(coordinates too large or not finite)",
                          (unsigned long)te->end[2 * e] + 1,
                          (unsigned long)te->end[2 * e + 1] + 1);
    if (l > dmax) dmax = l;
  }
  /* 2^-k with dmax * 2^-k in [1/2, 1): the scaled squares neither overflow
   * nor (for the longest edges) underflow; a power of two keeps every
   * ranking key bit for bit what it is unscaled when nothing overflows */
  int ex;
  (void)frexp(dmax, &ex);
  const double scale = ldexp(1.0, ex < -1020 ? 1020 : -ex); /* 2^1020: finite */
  for (size_t e = 0; e < ne; e++) {
    double l = len2(coarse, te->end[2 * e], te->end[2 * e + 1], scale);
    if (l > big) big = l;
  }
  for (size_t e = 0; e < ne; e++) {
    double q = len2(coarse, te->end[2 * e], te->end[2 * e + 1], scale) / big;
    order[e] =
        (ranked){(uint64_t)llround(ldexp(q, 36)), te->end[2 * e], te->end[2 * e + 1], e};
  }
  qsort(order, ne, sizeof *order, cmp_ranked);
  return SS_OK;
}

/* The unnormalized normal of triangle t (the cross product of two edges, in
 * the first three coordinates) into n. */
static void tri_normal(const ss_cx *cx, size_t t, double n[3]) {
  const ss_idx *v = ss_cx_cell(cx, SS_TRIANGLE, t);
  const size_t dim = (size_t)cx->dim;
  double a[3], b[3];
  for (size_t r = 0; r < 3; r++) {
    a[r] = cx->x[(size_t)v[1] * dim + r] - cx->x[(size_t)v[0] * dim + r];
    b[r] = cx->x[(size_t)v[2] * dim + r] - cx->x[(size_t)v[0] * dim + r];
  }
  n[0] = a[1] * b[2] - a[2] * b[1];
  n[1] = a[2] * b[0] - a[0] * b[2];
  n[2] = a[0] * b[1] - a[1] * b[0];
}

/* The angle in radians between the normals of the two triangles on edge e
 * (0..pi; 0 for a boundary edge and with fewer than three coordinates, where
 * the surface is flat). */
static double edge_angle(const ss_cx *cx, const ss_triedge *te, size_t e) {
  if (te->nface[e] != 2 || cx->dim < 3) return 0.0;
  double n[3], m[3];
  tri_normal(cx, te->face[2 * e], n);
  tri_normal(cx, te->face[2 * e + 1], m);
  const double c[3] = {n[1] * m[2] - n[2] * m[1], n[2] * m[0] - n[0] * m[2],
                       n[0] * m[1] - n[1] * m[0]};
  return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
               n[0] * m[0] + n[1] * m[1] + n[2] * m[2]);
}

/* Whether triangle t (corners v, edges in te) is one the criterion a asks to
 * refine: its bounding box meets a's box (in the first min(dim, 3)
 * coordinates), its longest edge is longer than a->max_edge, and the angle
 * between its normal and a neighbour's across one of its edges exceeds
 * a->max_angle; a criterion not set holds. */
static int wanted(const ss_cx *cx, const ss_triedge *te, size_t t, const ss_idx *v,
                  const ss_adapt *a) {
  const size_t dim = (size_t)cx->dim, nb = dim < 3 ? dim : 3;
  if (a->use_angle) {
    int bent = 0;
    for (int k = 0; k < 3 && !bent; k++)
      bent = edge_angle(cx, te, te->tedge[3 * t + (size_t)k]) > a->max_angle;
    if (!bent) return 0;
  }
  if (a->use_box)
    for (size_t r = 0; r < nb; r++) {
      double lo = INFINITY, hi = -INFINITY;
      for (int i = 0; i < 3; i++) {
        const double x = cx->x[(size_t)v[i] * dim + r];
        lo = fmin(lo, x);
        hi = fmax(hi, x);
      }
      if (hi < a->box[r] || lo > a->box[3 + r]) return 0;
    }
  if (a->max_edge > 0.0) {
    double l2 = 0.0;
    for (int i = 0; i < 3; i++) {
      double s = 0.0;
      for (size_t r = 0; r < dim; r++) {
        const double d =
            cx->x[(size_t)v[i] * dim + r] - cx->x[(size_t)v[(i + 1) % 3] * dim + r];
        s += d * d;
      }
      l2 = fmax(l2, s);
    }
    if (!(sqrt(l2) > a->max_edge)) return 0;
  }
  return 1;
}

/* Adaptive pass: of the edges the whole pass splits (split[e]), keep those of
 * a triangle the criterion wants or of its closure, clearing the others.  A
 * wanted triangle with no split edge (its edges marked by its neighbours'
 * clusters) cannot halve in this pass; the neighbours whose splits marked it
 * are refined instead (forced refinement, as a 4-8 hierarchy refines a
 * diamond's coarser neighbour first), so that its longest edge can split in
 * a later pass.  Any subset of the pass's split edges leaves the mesh
 * conforming: a split edge halves both its triangles. */
static ss_status restrict_splits(const ss_cx *coarse, const ss_triedge *te,
                                 const ss_adapt *a, unsigned char *split, ss_error *err) {
  const size_t nt = coarse->nc[SS_TRIANGLE];
  unsigned char *want = calloc(nt + 1, 1), *keep = calloc(nt + 1, 1);
  if (!want || !keep) {
    free(want);
    free(keep);
    return ss_error_nomem(err, "adaptive bisection");
  }
  for (size_t t = 0; t < nt; t++)
    want[t] = keep[t] =
        (unsigned char)wanted(coarse, te, t, ss_cx_cell(coarse, SS_TRIANGLE, t), a);
  for (size_t t = 0; t < nt; t++) {
    const size_t *ed = te->tedge + 3 * t;
    if (!want[t] || split[ed[0]] || split[ed[1]] || split[ed[2]]) continue;
    for (int k = 0; k < 3; k++) /* the neighbours across t's edges that halve */
      for (size_t j = 0; j < te->nface[ed[k]] && j < 2; j++) {
        const size_t n = te->face[2 * ed[k] + j];
        const size_t *en = te->tedge + 3 * n;
        if (split[en[0]] || split[en[1]] || split[en[2]]) keep[n] = 1;
      }
  }
  for (size_t e = 0; e < te->ne; e++) {
    if (!split[e]) continue;
    int k = 0;
    for (size_t j = 0; j < te->nface[e] && j < 2; j++)
      k |= keep[te->face[2 * e + j]];
    split[e] = (unsigned char)k;
  }
  free(want);
  free(keep);
  return SS_OK;
}

/* The fine cells: a triangle with a split edge (mid[e] set) halves, a
 * segment on one halves, everything else is copied. */
static ss_status fine_cells(const ss_cx *coarse, const ss_triedge *te, const ss_idx *mid,
                            ss_cx *fine, ss_error *err) {
  ss_status st = SS_OK;
  for (size_t t = 0; t < coarse->nc[SS_TRIANGLE]; t++) {
    const ss_idx *v = ss_cx_cell(coarse, SS_TRIANGLE, t);
    const int32_t ref = coarse->cref[SS_TRIANGLE][t];
    int k = 0;
    while (k < 3 && mid[te->tedge[3 * t + (size_t)k]] == SS_IDX_NONE)
      k++;
    if (k == 3) {
      if ((st = ss_cx_add_cell(fine, SS_TRIANGLE, v, ref, err))) return st;
      continue;
    }
    /* the split edge is opposite corner k: (v[k+1], v[k+2]) */
    ss_idx m = mid[te->tedge[3 * t + (size_t)k]];
    ss_idx a = v[(k + 1) % 3], c = v[(k + 2) % 3], apex = v[k];
    const ss_idx c0[3] = {apex, a, m}, c1[3] = {apex, m, c};
    if ((st = ss_cx_add_cell(fine, SS_TRIANGLE, c0, ref, err)) ||
        (st = ss_cx_add_cell(fine, SS_TRIANGLE, c1, ref, err)))
      return st;
  }
  for (size_t c = 0; c < coarse->nc[SS_SEGMENT]; c++) {
    const ss_idx *v = ss_cx_cell(coarse, SS_SEGMENT, c);
    const int32_t ref = coarse->cref[SS_SEGMENT][c];
    const size_t e = find_edge(te, v[0], v[1]);
    const ss_idx m = e == SIZE_MAX ? SS_IDX_NONE : mid[e];
    const ss_idx h0[2] = {v[0], m}, h1[2] = {m, v[1]};
    if ((m == SS_IDX_NONE && (st = ss_cx_add_cell(fine, SS_SEGMENT, v, ref, err))) ||
        (m != SS_IDX_NONE && ((st = ss_cx_add_cell(fine, SS_SEGMENT, h0, ref, err)) ||
                              (st = ss_cx_add_cell(fine, SS_SEGMENT, h1, ref, err)))))
      return st;
  }
  return SS_OK;
}

ss_status ss_split_bisect_adapt(const ss_cx *coarse, const ss_adapt *adapt,
                                ss_cx **fine_out, ss_split **L_out, ss_error *err) {
  ss_split_builder b = {0};
  ss_cx *fine = NULL;
  ss_triedge *te = NULL;
  ranked *order = NULL;
  unsigned char *marked = NULL, *split = NULL;
  ss_idx *mid = NULL;
  ss_status st = ss_split_tri_edges(coarse, &te, err);
  if (st) goto done;
  const size_t ne = te->ne;
  order = malloc((ne + 1) * sizeof *order);
  marked = calloc(ne + 1, 1);
  split = calloc(ne + 1, 1);
  mid = malloc((ne + 1) * sizeof *mid);
  if (!order || !marked || !split || !mid) {
    st = ss_error_nomem(err, "bisection split");
    goto done;
  }
  if ((st = rank_edges(coarse, te, order, err))) goto done;
  /* Algorithm 1: in that order an unmarked edge splits and marks its cluster */
  for (size_t i = 0; i < ne; i++) {
    const size_t e = order[i].e;
    mid[e] = SS_IDX_NONE;
    if (marked[e]) continue;
    split[e] = marked[e] = 1;
    for (size_t j = 0; j < te->nface[e]; j++)
      for (int k = 0; k < 3; k++)
        marked[te->tedge[3 * te->face[2 * e + j] + (size_t)k]] = 1;
  }
  if (adapt && (st = restrict_splits(coarse, te, adapt, split, err))) goto done;
  if ((st = ss_split_builder_init(&b, coarse->nv, ne / 3 + 1, err))) goto done;
  for (size_t i = 0; i < ne; i++) { /* new vertices numbered in that order */
    const size_t e = order[i].e;
    const ss_idx par[2] = {te->end[2 * e], te->end[2 * e + 1]};
    if (split[e] && (st = ss_split_builder_add(&b, par, 2, &mid[e], err))) goto done;
  }
  if ((st = ss_split_tri_fine(coarse, &fine, err)) ||
      (st = fine_cells(coarse, te, mid, fine, err)))
    goto done;
  st = ss_split_builder_finish(&b, coarse, fine, err);
done:
  ss_triedge_free(te);
  free(order);
  free(marked);
  free(split);
  free(mid);
  return ss_split_builder_hand_over(&b, st, fine, fine_out, L_out);
}

ss_status ss_split_bisect(const ss_cx *coarse, ss_cx **fine, ss_split **L,
                          ss_error *err) {
  return ss_split_bisect_adapt(coarse, NULL, fine, L, err);
}
