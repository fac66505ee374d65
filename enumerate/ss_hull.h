/* ss_hull.h — convex hulls of points in general position on a sphere, the C
 * face of the CGAL shim (ss_hull.cpp).
 *
 * The hull of n >= 4 points in convex position, no four on a plane through a
 * hull facet, is a simplicial polytope whose boundary is a triangulated sphere
 * on all n points: a link (ss_link.h).  Points drawn independently and
 * uniformly on the unit sphere are in that position with probability 1.
 *
 * The hull is CGAL::convex_hull_3 with exact predicates (Exact_predicates_
 * inexact_constructions_kernel), so the combinatorics are exact for the given
 * doubles: no rounding can make a point look inside or outside.  Every C++
 * exception is caught inside the shim and returned as a status; nothing is
 * printed and nothing aborts. */
#ifndef SS_HULL_H
#define SS_HULL_H

#include "ss_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The triangles of the boundary of the convex hull of n points
 * p_i = (xyz[3 i], xyz[3 i + 1], xyz[3 i + 2]), i = 0..n-1.
 *
 * On success *tri (malloc'd, owned by the caller: free() it) holds *ntri =
 * 2n - 4 triangles (*tri)[3 t + 0..2] of 0-based point indices, each oriented
 * outward (counterclockwise seen from outside the hull), rotated to start at
 * its smallest index, and sorted lexicographically, so the output depends only
 * on the points, not on CGAL's internal order.  xyz is read, never kept.
 *
 * SS_EINPUT, with a message naming the point(s), when the hull is not a
 * simplicial polytope with every point a vertex: n < 4, a coordinate not
 * finite, two points equal, all points on a plane, a point not a vertex of the
 * hull (inside it or on its boundary), or four points on one hull facet (the
 * triangulation of that facet would be arbitrary); messages give 0-based point
 * indices.  SS_ENOMEM; SS_EINTERNAL for any other exception from CGAL.  On
 * failure *tri = NULL, *ntri = 0.
 *
 * Cost O(n log n) expected time, O(n) memory. */
ss_status ss_hull_sphere_triangles(int n, const double *xyz, int **tri, int *ntri,
                                   ss_error *err);

#ifdef __cplusplus
}
#endif

#endif
