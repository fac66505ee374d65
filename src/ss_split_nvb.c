/* ss_split_nvb.c — newest-vertex bisection, the topological 4-8 refinement
 * (Velho & Gomes, "Quasi 4-8 subdivision surfaces", sections 2.2-2.3).
 *
 * A triangle carries its tag in its vertex order: corner 0 is its newest
 * vertex (on a regular 4-8 mesh the right-angle corner, the valence-4 vertex
 * of the face) and the edge opposite it, (v1, v2), is its refinement edge
 * (the hypotenuse, the edge joining the two valence-8 vertices).  One pass
 * splits every triangle's refinement edge at its midpoint m and halves the
 * triangle: (a, b, c) becomes (m, a, b) and (m, c, a), both oriented as the
 * parent and both tagged with m, their newest vertex, first, so that their
 * refinement edges are the parent's legs.  This is the interleaved binary step
 * of section 2.2 with the topological criterion ("split only edges connecting
 * valence 8 vertices"); two passes make the quaternary step of figure 2 (every
 * coarse edge split, every face into four similar faces), a full 4-8 cycle.
 * On a uniform 4-8 mesh longest-edge bisection (ss_split_bisect.c) makes the
 * same choice (section 2.3), without reading positions: this split reads only
 * the topology, so a star refined alone is refined as it would be inside the
 * mesh, which is what local subdivision matrices need.
 *
 * Conformity: an interior edge must be the refinement edge of both triangles
 * holding it or of neither (SS_EINPUT otherwise: the tags do not form a 4-8
 * hierarchy and the split point would hang on one side); on a regular 4-8
 * mesh every hypotenuse is shared by two triangles whose right angles face
 * each other, and the two passes preserve that.  An edge held by more than two
 * triangles is refused.  Vertex cells are copied; no other cells are taken. */
#include <stdint.h>
#include <stdlib.h>

#include "ss_split_builder.h"
#include "ss_split_impl.h"
#include "ss_split_tri.h"

ss_status ss_split_nvb(const ss_cx *coarse, ss_cx **fine_out, ss_split **L_out,
                       ss_error *err) {
  ss_split_builder b = {0};
  ss_cx *fine = NULL;
  ss_triedge *te = NULL;
  ss_idx *mid = NULL;
  unsigned char *refine = NULL;
  const size_t nt = coarse->nc[SS_TRIANGLE];
  ss_status st = ss_split_tri_edges(coarse, &te, err);
  if (st) goto done;
  const size_t ne = te->ne;
  mid = malloc((ne + 1) * sizeof *mid);
  refine = calloc(ne + 1, 1); /* how many triangles refine the edge */
  if (!mid || !refine) {
    st = ss_error_nomem(err, "newest-vertex bisection");
    goto done;
  }
  for (size_t e = 0; e < ne; e++)
    mid[e] = SS_IDX_NONE;
  for (size_t t = 0; t < nt; t++)
    refine[te->tedge[3 * t]]++;
  for (size_t e = 0; e < ne; e++)
    if (refine[e] && refine[e] != te->nface[e]) {
      st = ss_error_set(err, SS_EINPUT,
                        "non-conforming 4-8 tags: the edge between vertices %lu and "
                        "%lu is the refinement edge (opposite the first corner) of "
                        "one of its triangles but not of the other",
                        (unsigned long)te->end[2 * e] + 1,
                        (unsigned long)te->end[2 * e + 1] + 1);
      goto done;
    }
  if ((st = ss_split_builder_init(&b, coarse->nv, nt, err))) goto done;
  if ((st = ss_split_tri_fine(coarse, &fine, err))) goto done;
  for (size_t t = 0; t < nt; t++) {
    const ss_idx *v = ss_cx_cell(coarse, SS_TRIANGLE, t);
    const size_t e = te->tedge[3 * t];
    if (mid[e] == SS_IDX_NONE) {
      const ss_idx par[2] = {v[1], v[2]};
      if ((st = ss_split_builder_add(&b, par, 2, &mid[e], err))) goto done;
    }
    const ss_idx m = mid[e], c0[3] = {m, v[0], v[1]}, c1[3] = {m, v[2], v[0]};
    const int32_t ref = coarse->cref[SS_TRIANGLE][t];
    if ((st = ss_cx_add_cell(fine, SS_TRIANGLE, c0, ref, err)) ||
        (st = ss_cx_add_cell(fine, SS_TRIANGLE, c1, ref, err)))
      goto done;
  }
  st = ss_split_builder_finish(&b, coarse, fine, err);
done:
  ss_triedge_free(te);
  free(mid);
  free(refine);
  return ss_split_builder_hand_over(&b, st, fine, fine_out, L_out);
}
