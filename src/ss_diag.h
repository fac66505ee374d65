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
 * Tets not holding the edge are left alone by skew and center. */
#ifndef SS_DIAG_H
#define SS_DIAG_H

#include "ss_cx.h"

typedef enum {
  SS_DIAG_BFS = 0, /* Algorithm 2 (the default) */
  SS_DIAG_SKEW,    /* skew around an edge */
  SS_DIAG_CENTER   /* toward an edge */
} ss_diag_mode;

/* Name ("bfs", "skew", "center") and parse (0, or -1 for an unknown name). */
const char *ss_diag_name(ss_diag_mode m);
int ss_diag_parse(const char *name, ss_diag_mode *out);

/* Reorder the tets of cx so that their vertex order carries the chosen
 * diagonals.  For skew and center, (v0, v1) is the edge; ignored for bfs.
 * SS_ENOMEM; SS_EINPUT if skew/center name a pair that is no edge of a tet. */
ss_status ss_diag_choose(ss_cx *cx, ss_diag_mode m, ss_idx v0, ss_idx v1, ss_error *err);

#endif
