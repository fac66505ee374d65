/* ss_case.h — one case to analyse: which centre, its star, and the facts
 * about it that every command needs before anything is extracted (DESIGN
 * section 2).
 *
 * A case names a centre p and the star around it:
 *   vertex          a 3D vertex with a given link: the hex star for schemes with
 *                   the multilinear split, the tet star for the tet/oct split;
 *   edge            the midpoint of an edge of valence n (a vertex from level 1
 *                   on), in n hexes or n tets;
 *   face            tet/oct split only: a vertex inside the face shared by two
 *                   tets (from level 2 on, the vertex 1/4 (2, 1, 1) of the face;
 *                   every vertex inside that face sees the same infinite mesh,
 *                   two half tet/oct lattices meeting at a plane);
 *   surface vertex  a 2D vertex of valence n: n quads (multilinear split) or n
 *                   triangles (tet/oct split, which splits triangles like Loop);
 *                   for quasi48 a tagged 4-8 star of class 4 or 8
 *                   (ss_star_tri48_vertex), refined by the scheme's analysis
 *                   step, a full 4-8 cycle of two topological bisection
 *                   passes (ss_scheme_refine_step), so S is the two-pass
 *                   (dyadic) matrix.  A class-4 vertex of valence n is a
 *                   class-8 vertex of valence 2n after one pass, so its S is
 *                   that of class 8, valence 2n.
 * The local subdivision matrix of a case is extracted by ss_local.h. */
#ifndef SS_CASE_H
#define SS_CASE_H

#include "ss_api.h"
#include "ss_diag.h"
#include "ss_error.h"
#include "ss_link.h"
#include "ss_scheme.h"
#include "ss_star.h"

SS_BEGIN_DECLS

typedef enum {
  SS_CASE_VERTEX = 0,     /* a 3D vertex with a link */
  SS_CASE_EDGE,           /* a point on an edge of valence n */
  SS_CASE_FACE,           /* a point inside the face shared by two tets */
  SS_CASE_SURFACE_VERTEX, /* a 2D vertex of valence n */
  SS_CASE_EDGE_POINT      /* results only: a vertex whose link is the bipyramid
                             over n (n != 4) in a hex mesh, which is a point on
                             an edge of valence n and is analysed as the edge
                             case (ss_case_edge_point) */
} ss_case_kind;

#define SS_NCASEKINDS 5 /* case kinds, for tables indexed by kind */

/* One case to analyse.  The link is borrowed, not copied. */
typedef struct {
  ss_case_kind kind;   /* which centre */
  const ss_link *link; /* vertex case: the link; otherwise NULL */
  int n;               /* edge and surface vertex cases: the valence */
  ss_diag_mode diag;   /* tet stars: major diagonals (ss_diag.h; bfs = 0 by
                          default, or proper; skew and center only for the
                          edge case, around the edge) */
  int cls;             /* quasi48 surface vertex: its 4-8 class, 4 or 8, or 0
                          for ss_case_class48's default; 0 for other
                          schemes and cases */
} ss_case;

/* Name of a case kind as in the command line and JSON ("vertex", "edge",
 * "face", "surface-vertex", "edge-point"). */
const char *ss_case_name(ss_case_kind kind);

/* The kind named name (one of ss_case_name's five names) into *out: 0, or
 * -1 for any other name (*out untouched). */
int ss_case_kind_parse(const char *name, ss_case_kind *out);

/* The 4-8 class of a quasi48 surface vertex of valence n when the case leaves
 * it 0: the class that longest-edge refinement gives the centre of a regular
 * n-gon fan (Velho & Gomes section 3.3): 4 (its outer edges split first, its
 * valence doubles) for n < 6 and for odd n (which that refinement cannot keep:
 * odd n > 6 gains one spoke), 8 (alternate spokes split, the valence stays)
 * for even n >= 6.  cls itself when it is 4 or 8. */
int ss_case_class48(int n, int cls);

/* The first refinement level on which the centre of a case of kind `kind`
 * is a vertex of the refined star: 0 for a vertex (3D or surface), 1 for an
 * edge's midpoint, 2 for the face point. */
int ss_case_centre_level(ss_case_kind kind);

/* Points on extraordinary edges (DESIGN section 10).  A vertex of a hex mesh
 * whose link is the bipyramid over an n-gon has two edges of valence n (the
 * poles) and n regular ones: it lies on an edge of valence n, and its hex star
 * is the star of that edge's midpoint once refined, so its local matrix is
 * the edge case's (the same two-ring, relabelled) and the edge analysis, not
 * the vertex condition, decides its smoothness.  Returns n when the scheme
 * splits hexes (multilinear split) and l is such a bipyramid with n != 4 (the
 * octahedron is the regular vertex); 0 otherwise, and -1 when out of memory.
 * For tet stars a bipyramid link is an ordinary vertex: the tet/oct split
 * refines a vertex and an edge midpoint differently. */
int ss_case_edge_point(const ss_scheme *s, const ss_link *l);

/* The cell type of the star of a case of kind `kind` under scheme s: hex or
 * tet for vertices and edges (by the scheme's split), tet for the face, quad
 * or triangle for surface vertices.  SS_EINPUT when the scheme has no such
 * case (the face of a multilinear split, cells the scheme does not take). */
ss_status ss_case_cell(const ss_scheme *s, ss_case_kind kind, ss_cell_type *t,
                       ss_error *err);

/* The star the scheme refines for case c (hex or tet stars by the scheme's
 * split; see above).  *out is owned by the caller.  SS_EINPUT if the scheme
 * does not support the case (it does not take the star's cell type, or the face
 * case with a multilinear split) or the valence is out of range. */
ss_status ss_case_star(const ss_scheme *s, const ss_case *c, ss_star **out,
                       ss_error *err);

SS_END_DECLS

#endif
