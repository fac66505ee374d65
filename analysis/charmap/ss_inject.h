/* ss_inject.h — injectivity of a control net's piecewise-linear image: the
 * test the papers leave to "visual inspection" (DESIGN section 10; issue 15).
 *
 * A regular map (Jacobian of one strict sign) is a local homeomorphism, not
 * yet one-to-one: it may wrap around the centre twice, or two distant parts
 * of the two-ring may land on each other.  Both are tested on the
 * piecewise-linear (PL) image of the cells:
 *   hex      its 6 faces, each split into 4 triangles at the face's centre
 *            point (the mean of its 4 corners, a point of the bilinear face),
 *            and for the volume the 24 tets from those triangles to the cell's
 *            centre (the mean of its 8 corners);
 *   tet      itself; octahedron: its 8 tets from the centroid (as ss_jac);
 *   quad     4 triangles at its centre point; triangle: itself.
 * This PL image is what is tested; it is a close surrogate of the
 * multilinear one, not the same map.  The centre points are means rounded to
 * doubles, summed in increasing point order, so two hexes sharing a face
 * split it at the same point.
 *
 * Boundary.  Facets (hex faces, tet and octahedron triangles, edges of quads
 * and triangles) are matched by their corner points.  A facet of one cell is
 * a boundary facet; a facet of two cells must be run through in opposite
 * directions by them (the cells are consistently ordered, whatever the signs
 * of their images); a facet of three or more cells, or of two that run the
 * same way, is SS_EINPUT.  The boundary facets, mapped PL, then form a
 * closed surface (3D) or closed polygon (2D) as a chain: every edge cancels.
 *
 * Degree.  The winding number of that boundary image about the image p of
 * the centre point, i.e. the number of preimages of p counted with the sign
 * of the map there: +1 or -1 for an injective map (-1 when the cells are all
 * negative).  Computed exactly: the signed crossings of the segment from p to
 * a point q beyond the boundary's largest first coordinate (where the
 * winding number is 0), by CGAL's exact orientation predicates
 * (Exact_predicates_inexact_constructions_kernel) on the doubles; q is
 * drawn again (a fixed seed, at most 64 times) while the segment meets an
 * edge or vertex of a facet or lies in a facet's plane.  Facets of zero area
 * (length) are exact too: they add nothing and are only tested for holding p.
 * The degree counts signed crossings, so a folded net (cells of both signs)
 * can have degree 1 and still overlap itself: the overlap test is what finds
 * that.
 *
 * Overlaps.  Image cells (their closed PL tets or triangles) that share no
 * vertex of the net must not meet, touching included: such cells are
 * disjoint in the domain (CGAL do_intersect, exact on the doubles, after a
 * box filter with CGAL::box_intersection_d; a flat tet or triangle is tested
 * as the convex hull of its points).  Cells that share a vertex are
 * neighbours and are not tested: their images always meet, and a contact
 * alone says nothing.  So an overlap between neighbours is missed here — one
 * cell folded over the next across a common face, or the cells around a
 * common edge or vertex wrapping more than once.  The first is a local fold,
 * which regularity (ss_charmap: every cell's Jacobian of one strict sign,
 * all cells the same sign) excludes; the second, with every cell positive, is
 * a branch point, which raises the degree when it lies in the interior (in
 * the centre's component of the complement of the boundary image), but which
 * neither test sees at the boundary of the net.
 *
 * Verdict: fail when |degree| != 1 or some overlap is found (an overlap
 * fails even when the degree is undecided), with the degree, the number of
 * overlapping pairs and the smallest such pair in the reason; otherwise
 * undecided when p lies on the boundary image, or when 64 segments all met an
 * edge or vertex (not seen in practice); otherwise pass.  The predicates are
 * exact on the given doubles, so the verdict is exact for that PL net (with
 * its rounded centre points); it says nothing about rounding in the net
 * itself (certified is never set by this module).
 *
 * Cost: O(F) per segment tried for the degree (F boundary triangles), and a
 * box filter over the C cells (O(C log^d C + K)) followed by the pieces of
 * the K box-overlapping pairs of non-neighbours (up to 24 x 24 tet tests for
 * two hexes, each behind its own box test, most decided by a few orientation
 * predicates before CGAL's do_intersect).  About 1.5 ms for the 160 hexes of
 * the MLCA icosahedron (k = 12) map; a folded map, with many box-overlapping
 * pairs, costs more (ss_charmap_injectivity asks only for the parts it
 * reads: ss_inject_test_parts).  No global state; CGAL's exceptions
 * are caught in the shim. */
#ifndef SS_INJECT_H
#define SS_INJECT_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_cx.h"
#include "ss_eig.h"
#include "ss_error.h"

SS_BEGIN_DECLS

/* What the test found. */
typedef struct {
  ss_verdict verdict; /* pass, fail or undecided, with the reason */
  int degree;         /* winding number of the boundary image about the
                         centre's image; 0 when it is undecided */
  size_t boundary;    /* boundary facets (quads, triangles or segments) */
  size_t overlaps;    /* pairs of non-neighbouring cells whose images meet */
  size_t first[2];    /* the smallest such pair (cell indices, first[0] <
                         first[1], lexicographic order), SIZE_MAX if none */
} ss_injectivity;

/* Test the net x (n points of dim = 2 or 3 coordinates, point by point) on
 * ncells cells of types ctype with corners corner[c * SS_MAXCELLVERTS + j]
 * (indices into x, unused slots SIZE_MAX; the vertex orders of ss_cx.h),
 * about the image of point `centre`.  Cells must all be of dimension dim:
 * hexes, or tets and octahedra, in 3D (hexes do not mix with the others:
 * their quad faces cannot match triangles); quads and triangles in 2D.
 * The inputs are read, never kept; *out is written (it aliases nothing).
 * SS_EINPUT, with a message naming the cell or point, for: dim not 2 or 3,
 * no points or cells, centre or a corner out of range, a corner repeated in
 * a cell, a cell type of another dimension (mixed 2D/3D cells) or hexes
 * mixed with tets or octahedra, a coordinate that is not finite (of a corner
 * or the centre), a facet of three or more cells or of two cells that run
 * through it the same way.  SS_ENOMEM; SS_EINTERNAL for an unexpected
 * exception from CGAL.  On failure *out is zeroed, with first = SIZE_MAX
 * and the verdict undecided. */
ss_status ss_inject_test(const double *x, int dim, size_t n, const ss_cell_type *ctype,
                         const size_t *corner, size_t ncells, size_t centre,
                         ss_injectivity *out, ss_error *err);

/* Which parts ss_inject_test_parts computes: the degree, the overlaps, or
 * both (ss_inject_test). */
enum {
  SS_INJECT_DEGREE = 1,  /* the winding number about the centre's image */
  SS_INJECT_OVERLAPS = 2 /* the pairs of non-neighbouring cells that meet */
};

/* ss_inject_test restricted to the parts named in `parts` (a non-zero set of
 * SS_INJECT_DEGREE and SS_INJECT_OVERLAPS): a caller that reads only the
 * degree of one net and only the overlaps of another (ss_charmap_injectivity)
 * pays for nothing else; the overlaps cost nearly all of the time (the degree
 * is one pass over the boundary).  A part not computed reads as not found:
 * degree 0 (the winding counted as undecided) or no overlap; the verdict is
 * judged from what was computed, so it means the whole test's verdict only
 * when both parts are.  The checks of the input, errors and ownership are
 * ss_inject_test's (SS_EINPUT also for an empty `parts`). */
ss_status ss_inject_test_parts(const double *x, int dim, size_t n,
                               const ss_cell_type *ctype, const size_t *corner,
                               size_t ncells, size_t centre, int parts,
                               ss_injectivity *out, ss_error *err);

SS_END_DECLS

#endif
