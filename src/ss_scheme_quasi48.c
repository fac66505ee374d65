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
 *  - boundaries: section 4.1 keeps boundary vertices fixed; here an old vertex
 *    on a boundary edge (an edge held by one triangle) keeps its position and a
 *    new vertex on a boundary edge stays at its midpoint, so the boundary
 *    polygon is refined linearly and never moves;
 *  - an interior old vertex with no new neighbour (n = 0, possible where the
 *    clusters leave a vertex untouched) keeps its position;
 *  - a new vertex on an interior edge that is adjacent to a boundary new
 *    vertex uses that vertex's (midpoint) value in the cascade as any other;
 *  - tags (section 4.3, "a tagged vertex or edge is not affected by
 *    smoothing"): a vertex cell keeps its vertex where it is, a segment cell
 *    (a tagged edge; the split halves it with its edge) keeps the new vertex
 *    on it at its midpoint — both then enter the cascade as boundary points
 *    do.  The paper's other boundary rule, "boundary vertices are constrained
 *    to move along the surface normal", depends on the positions, not only
 *    on the mesh, and is not a linear rule: boundaries stay fixed here, as in
 *    section 4.1, which is figure 15(b)'s "all boundary edges and vertices
 *    tagged";
 *  - adaptive levels (ss_scheme_set_adapt): the split bisects only where a
 *    criterion asks (ss_split_refine_adapt); this rule is unchanged, and an
 *    old vertex with no new neighbour keeps its place, so the mesh away from
 *    the refined triangles stays put. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_scheme_impl.h"
#include "ss_triedge.h"

/* Weight of each of an interior new vertex's four neighbours (figure 5); the
 * cascade of the old vertices reads p'(x) through the same weight. */
static const double new_weight = 0.25;

static ss_status quasi48_rule(const ss_scheme *s, const ss_cx *coarse, const ss_cx *fine,
                              const ss_split *L, ss_sink *k, ss_error *err) {
  (void)s;
  (void)coarse; /* the split complex and L say all this rule needs */
  ss_triedge *te = NULL;
  ss_status st = ss_triedge_new(fine, &te, err);
  if (st) return st;
  const size_t nc = L->ncoarse;
  /* fixed: on the boundary, or tagged (a vertex cell, a new vertex on a
   * segment cell) */
  unsigned char *fixed = malloc(fine->nv + 1);
  if (!fixed) {
    ss_triedge_free(te);
    return ss_error_nomem(err, "quasi48 tags");
  }
  memcpy(fixed, te->vbnd, fine->nv);
  for (size_t i = 0; i < fine->nc[SS_VERTEX]; i++)
    fixed[fine->cells[SS_VERTEX][i]] = 1;
  for (size_t i = 0; i < 2 * fine->nc[SS_SEGMENT]; i++)
    if (fine->cells[SS_SEGMENT][i] >= nc) fixed[fine->cells[SS_SEGMENT][i]] = 1;
  for (size_t x = nc; x < fine->nv; x++) {
    if (fixed[x]) {
      ss_sink_emit(k, x, x, 1.0);
      continue;
    }
    /* an interior bisection point has exactly its edge's two ends and the two
     * opposite corners as neighbours, all old (one split edge per triangle) */
    const size_t val = te->vptr[x + 1] - te->vptr[x];
    if (val != 4) {
      ss_triedge_free(te);
      free(fixed);
      return ss_error_set(err, SS_EINTERNAL,
                          "quasi48: new vertex %zu has valence %zu, not 4", x + 1, val);
    }
    for (size_t q = te->vptr[x]; q < te->vptr[x + 1]; q++)
      ss_sink_emit(k, x, te->vnbr[q], new_weight);
  }
  for (size_t v = 0; v < nc; v++) {
    size_t n = 0;
    for (size_t q = te->vptr[v]; q < te->vptr[v + 1]; q++)
      n += te->vnbr[q] >= nc;
    if (fixed[v] || n == 0) {
      ss_sink_emit(k, v, v, 1.0);
      continue;
    }
    ss_sink_emit(k, v, v, 0.5);
    const double w = 1.0 / (2.0 * (double)n);
    for (size_t q = te->vptr[v]; q < te->vptr[v + 1]; q++) {
      size_t x = te->vnbr[q];
      if (x < nc) continue;
      if (fixed[x]) {
        ss_sink_emit(k, v, x, w);
        continue;
      }
      for (size_t r = te->vptr[x]; r < te->vptr[x + 1]; r++)
        ss_sink_emit(k, v, te->vnbr[r], new_weight * w);
    }
  }
  ss_triedge_free(te);
  free(fixed);
  return SS_OK;
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
