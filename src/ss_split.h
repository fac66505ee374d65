/* ss_split.h — linear (topological) refinement of a complex.
 *
 * A split refines every cell of a complex once and places each new vertex at the
 * centroid of a set of coarse vertices, its *parents*: an edge midpoint has 2, a
 * quad-face centre 4, an octahedron centre 6, a hex centre 8.  The linear
 * refinement operator L (fine x coarse) therefore has row f equal to
 * 1/|parents(f)| on each parent.  Coarse vertex v is fine vertex v (a single
 * parent, itself); new vertices follow in order of first appearance.
 *
 * Splits:
 *  - multilinear (MLCA paper, section 2.1): a d-cube (segment, quad, hex) into 2^d
 *    d-cubes; new vertices are shared by every cell holding the same edge or quad
 *    face (matched by vertex sets, whatever the cell type), so hexes, crease quads
 *    and crease segments stay conforming.  Child k' of a d-cube is the octant with
 *    binary offset ss_cube_corner_bits(d, k'); it holds coarse corner k' at its
 *    own corner k', and every child keeps the parent's orientation.
 *  - tetoct (tet/oct paper, section 2.1): a tet into 4 corner tets + 1 octahedron,
 *    an octahedron into 6 octahedra + 8 tets about its centroid, a triangle into
 *    4, a segment into 2.  Children 0..3 of a tet (of a triangle) sit at corners
 *    0..3 (0..2) with the parent's vertex order; the tet's octahedron is
 *    (m01, m03, m02, m23, m12, m13); the middle triangle is (m12, m20, m01).
 *    Octahedron children: octahedra 0..5 about corners 0..5, then the 8 tets of
 *    the faces (s0,s1,s2), s_k in {k, k+3}, in binary order of the choices.
 *    Major diagonals (box-spline paper, Definition 3.2) live in the vertex
 *    order: an octahedron's is its pair (0,3), a tet's its edge pair (0,1),
 *    (2,3) (the tet's octahedron joins their midpoints); every child's is
 *    parallel to its parent's (corner children are scaled copies, and an
 *    octahedron's tet (c, B, ., .) with B = m(s1,s2) puts first the pair
 *    whose octahedron lies along the parent's axis (0,3)).
 *  - bisect (quasi 4-8 paper, Algorithm 1): one pass of longest-edge
 *    bisection of a triangle surface, at most one split edge per triangle,
 *    which halves the triangles holding it (ss_split_bisect.c).  Unlike the
 *    others this split reads the coarse positions (the complex's x): which
 *    edges split depends on their lengths; ties are broken by vertex index.
 *  - nvb (the same paper, sections 2.2-2.3): newest-vertex bisection, the
 *    topological 4-8 refinement.  Corner 0 of a triangle is its newest vertex
 *    and the edge opposite it is split; (a, b, c) becomes (m, a, b) and
 *    (m, c, a).  Two passes are one full 4-8 cycle.  It reads no positions:
 *    the analysis of quasi48 refines stars with it (ss_split_nvb.c).
 *  - hexify (MLCA paper, section 3.3): non-hexahedral input made hexahedral.
 *    A cell whose vertices all have valence three splits into one cell per
 *    vertex: the vertex, its edges' midpoints, its faces' centres, the
 *    centroid.  Triangles give 3 quads, tets 4 hexes (each in the parent's
 *    orientation), segments, quads and hexes split as by multilinear; shared
 *    edges and faces share their points, so a mixed mesh stays conforming.
 *    Octahedra (valence four) are not taken (ss_split_multilinear.c).
 * Vertex cells are copied.  Every child keeps the parent's reference.
 *
 * Fine cells of coarse cell i of type t occupy a contiguous block, in coarse
 * order (for hexify: a triangle's 3 quads after every quad's 4, a tet's 4
 * hexes after every hex's 8; for the tet/oct split: each coarse cell's tets in the tet
 * array and its octahedra in the octahedron array, coarse tets first). */
#ifndef SS_SPLIT_H
#define SS_SPLIT_H

#include <stddef.h> /* gsl_spmatrix.h uses size_t without including it */

#include <gsl/gsl_spmatrix.h>

#include "ss_api.h"
#include "ss_cx.h"

SS_BEGIN_DECLS

typedef enum {
  SS_SPLIT_MULTILINEAR = 0, /* vertices, segments, quads, hexes */
  SS_SPLIT_TETOCT,          /* vertices, segments, triangles, tets, octahedra */
  SS_SPLIT_BISECT,          /* vertices, segments, triangles: longest-edge
                               bisection (segments: tagged edges, halved with
                               their edge) */
  SS_SPLIT_NVB,             /* vertices, triangles: newest-vertex bisection */
  SS_SPLIT_HEXIFY           /* vertices, segments, triangles, quads, tets, hexes:
                               every cell split at its corners (MLCA paper,
                               section 3.3): triangles into 3 quads, tets into
                               4 hexes, the cubes as by the multilinear split;
                               a step that makes such input hexahedral */
} ss_split_kind;

/* The linear refinement operator L in parent-list form. */
typedef struct {
  size_t ncoarse; /* coarse vertices; fine vertex v < ncoarse is coarse vertex v */
  size_t nfine;   /* fine vertices */
  size_t *ptr;    /* nfine+1 offsets into parent */
  ss_idx *parent; /* parents of fine f: parent[ptr[f] .. ptr[f+1]), ascending */
} ss_split;

/* Number of parents of fine vertex f. */
static inline size_t ss_split_npar(const ss_split *L, size_t f) {
  return L->ptr[f + 1] - L->ptr[f];
}

/* Whether a split accepts cells of type t. */
int ss_split_accepts(ss_split_kind kind, ss_cell_type t);
/* Name of a split ("multilinear", "tetoct", "bisect", "nvb", "hexify"). */
const char *ss_split_name(ss_split_kind kind);

/* Refine `coarse` once: *fine receives the refined complex with new vertices at
 * their linear (centroid) positions, *L the operator.  Both are owned by the
 * caller.  SS_EINPUT if the complex holds a cell type the split does not accept
 * or a malformed cell, for the bisect split a non-manifold or zero-length
 * edge, for the nvb split a non-manifold edge or non-conforming tags;
 * SS_ENOMEM.  Cost: linear in the size of the complex. */
ss_status ss_split_refine(ss_split_kind kind, const ss_cx *coarse, ss_cx **fine,
                          ss_split **L, ss_error *err);

/* Where an adaptive pass of the bisect split refines (quasi 4-8 adaptivity):
 * a triangle is wanted when every criterion set holds. */
typedef struct {
  int use_box;      /* 1: wanted only if its bounding box meets `box` */
  double box[6];    /* x0, y0, z0, x1, y1, z1 (the first min(dim, 3) pairs read) */
  double max_edge;  /* > 0: wanted only if an edge is longer than this; 0: not set */
  int use_angle;    /* 1: wanted only if the angle between its normal and a
                       neighbour's across one of its edges exceeds max_angle
                       (a discrete curvature, the dihedral angle's deviation
                       from flat; first three coordinates, fewer: flat) */
  double max_angle; /* that angle in radians, 0..pi (pi: nothing is wanted) */
} ss_adapt;

/* ss_split_refine with an adaptive bisect pass (kind SS_SPLIT_BISECT; adapt
 * NULL: the whole pass, bit for bit ss_split_refine's).  Of the edges the
 * whole pass would split (Algorithm 1: longest first, one per triangle),
 * only those of a wanted triangle split, and of its closure: a wanted
 * triangle none of whose edges splits (its neighbours' clusters marked them)
 * has the neighbours that halve around it refined too, so that its longest
 * edge can split in a later pass.  Every split edge halves both its
 * triangles, so the result is conforming (no hanging vertex).  Errors as
 * ss_split_refine, and SS_EINPUT for adapt with another split. */
ss_status ss_split_refine_adapt(ss_split_kind kind, const ss_cx *coarse,
                                const ss_adapt *adapt, ss_cx **fine, ss_split **L,
                                ss_error *err);

/* Free; NULL is a no-op. */
void ss_split_free(ss_split *L);

/* L as a new nfine x ncoarse CSR matrix (caller frees with gsl_spmatrix_free).
 * SS_ENOMEM. */
ss_status ss_split_matrix(const ss_split *L, gsl_spmatrix **out, ss_error *err);

SS_END_DECLS

#endif
