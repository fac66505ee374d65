/* ss_diag.h — choosing the major diagonals of a tet mesh (box-spline paper,
 * Definition 3.2 and Algorithm 2; DESIGN section 4).
 *
 * A tet's major diagonal is one of its three pairs of opposite edges; the
 * octahedron born from it gets the diagonal joining those edges' midpoints.
 * It lives in the vertex order (ss_split.h): the pair (0,1), (2,3).  Choosing
 * a diagonal therefore reorders a tet's vertices by an even permutation, which
 * keeps its orientation.  Octahedra keep theirs (the pair (0,3)).
 *
 * Choices:
 *   bfs     Algorithm 2 (MAJOR-DIAGONAL-CHOOSE): tets in breadth-first order
 *           over shared faces from the first tet of each connected part; each
 *           takes a pair neither of whose edges is an edge of an
 *           already-visited neighbour's diagonal.  Tie-breaks (the paper leaves
 *           them open): the pairs are tried in the order (01,23), (02,13),
 *           (03,12) of the tet's current vertex order; the first pair with no
 *           edge in the neighbours' set wins; if there is none, the first with
 *           the fewest such edges.  Deterministic for a given mesh.
 *   skew    around the edge (v0, v1): in every tet (v0, v1, c_i, c_i+1) (in
 *           the positive order) the pair v0 c_i, v1 c_i+1 — the same turn all
 *           round (the paper's figure 23, first row);
 *   center  around the edge (v0, v1): the pair v0 v1, c_i c_i+1 (all diagonals
 *           toward the central edge, figure 23, second row).
 *   proper  Algorithm 2's breadth-first search and tie-breaks, but each tet
 *           takes the pair holding the most edges of its visited neighbours'
 *           diagonals (the first such pair), i.e. it makes as many of its face
 *           pairs proper (below) as it can; not an algorithm of the paper.
 * Tets not holding the edge are left alone by skew and center.
 *
 * Properness.  Definition 3.2 states its condition (a)/(b)/(c) for two
 * octahedra sharing an edge; that is the octet-truss lattice's situation,
 * where it holds for parallel diagonals.  Across a face of the input mesh two
 * tets meet (and, once refined, two octahedra and two tets meet face to face,
 * section 4.2), where no choice can meet (a)/(b)/(c) on all three shared
 * edges.  What section 4.2 needs there is that the refined points inside the
 * shared face see the regular neighbour counts (|rho| = 14 at vertices, 4 or 6
 * at edges), so that the regular rules apply; test_boxspline shows by
 * counting that this holds exactly when the two diagonals mark the same part
 * of the face: two tets whose pairs hold the same edge of their common face,
 * two octahedra whose diagonals end at the same corner of it.  A pair of
 * cells is therefore counted as improper if it is
 *   two tets or two octahedra sharing a face whose marks differ, or
 *   two octahedra sharing only an edge that violates (a), (b) and (c).
 * Note: Algorithm 2 as printed keeps a tet's pair away from its visited
 * neighbours' diagonal edges, so it tends to make face pairs improper in this
 * sense, and the "skew" edge star (figure 23's smoother row) is improper on
 * every face around the edge while "center" is proper. */
#ifndef SS_DIAG_H
#define SS_DIAG_H

#include "ss_api.h"
#include "ss_cx.h"

SS_BEGIN_DECLS

typedef enum {
  SS_DIAG_BFS = 0, /* Algorithm 2 (the default) */
  SS_DIAG_SKEW,    /* skew around an edge */
  SS_DIAG_CENTER,  /* toward an edge */
  SS_DIAG_PROPER   /* Algorithm 2's search, matching instead of avoiding */
} ss_diag_mode;

/* Name ("bfs", "skew", "center", "proper") and parse (0, or -1 for an unknown name). */
const char *ss_diag_name(ss_diag_mode m);
int ss_diag_parse(const char *name, ss_diag_mode *out);

/* Reorder the tets of cx so that their vertex order carries the chosen
 * diagonals.  For skew and center, (v0, v1) is the edge; ignored for bfs.
 * SS_ENOMEM; SS_EINPUT if skew/center name a pair that is no edge of a tet. */
ss_status ss_diag_choose(ss_cx *cx, ss_diag_mode m, ss_idx v0, ss_idx v1, ss_error *err);

/* Count the adjacent pairs of cells the diagonals concern (tet-tet and
 * oct-oct across a face, oct-oct across an edge only) and the improper ones
 * among them (see above).  Reads the diagonals from the vertex order.
 * SS_ENOMEM.  Cost O(c log c) in the number of cells. */
ss_status ss_diag_improper(const ss_cx *cx, size_t *pairs, size_t *improper,
                           ss_error *err);

SS_END_DECLS

#endif
