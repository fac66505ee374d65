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
 * multilinear one, not the same map.
 *
 * Degree.  The boundary of the union of the cells (facets that belong to one
 * cell only), mapped PL, is a closed surface (3D) or closed polygon (2D).
 * Its winding number about the image of the centre point is the degree of the
 * map there: computed exactly, by counting signed crossings of a ray with
 * exact orientation predicates (CGAL, exact predicates on the double
 * coordinates; a ray that meets an edge or vertex is replaced by another), so
 * the count is exact for the PL surface as given.  It must be +1 or -1.
 *
 * Overlaps.  Image cells (their PL tets or triangles) that share no vertex of
 * the net must not intersect (CGAL do_intersect, exact predicates, after a box
 * filter).  Cells that share a vertex are neighbours and are not tested.
 *
 * Verdict: pass when |degree| = 1 and no overlap; fail otherwise, with the
 * degree, the number of overlapping pairs and one such pair in the reason;
 * undecided when the centre's image lies on the boundary image.  The
 * predicates are exact on the given doubles, so the verdict is exact for
 * that PL net; it says nothing about rounding in the net itself (certified
 * is never set by this module).
 *
 * Cost: O(F) for the degree (F boundary triangles), O((T + K) log T) for the
 * overlaps with T tets and K box-overlapping pairs. */
#ifndef SS_INJECT_H
#define SS_INJECT_H

#include <stddef.h>

#include "ss_cx.h"
#include "ss_eig.h"
#include "ss_error.h"

/* What the test found. */
typedef struct {
  ss_verdict verdict; /* pass, fail or undecided, with the reason */
  int degree;         /* winding number of the boundary image about the
                         centre's image; 0 if undecided */
  size_t boundary;    /* boundary facets (quads, triangles or segments) */
  size_t overlaps;    /* pairs of non-neighbouring cells whose images meet */
  size_t first[2];    /* one such pair (cell indices), SIZE_MAX if none */
} ss_injectivity;

/* Test the net x (n points of dim = 2 or 3 coordinates, point by point) on
 * ncells cells of types ctype with corners corner[c * SS_MAXCELLVERTS + j]
 * (indices into x, unused slots SIZE_MAX; the vertex orders of ss_cx.h),
 * about the image of point `centre`.  Cells must all be of dimension dim.
 * SS_EINPUT for a corner out of range or a mixed or unsupported cell type,
 * SS_ENOMEM; a non-closed boundary (a facet in more than two cells) is
 * SS_EINPUT too. */
ss_status ss_inject_test(const double *x, int dim, size_t n, const ss_cell_type *ctype,
                         const size_t *corner, size_t ncells, size_t centre,
                         ss_injectivity *out, ss_error *err);

#endif
