/* ss_inject_cgal.h — private to the analysis library: the exact geometry of
 * the injectivity test (ss_inject.h), the C face of the CGAL shim
 * ss_inject_cgal.cpp.
 *
 * Points are given as doubles, dim = 2 or 3 coordinates each, point by point;
 * every predicate is CGAL's (Exact_predicates_inexact_constructions_kernel),
 * so each answer is exact for those doubles.  Nothing is kept, printed or
 * thrown: every C++ exception becomes a status (SS_ENOMEM, or SS_EINTERNAL
 * with CGAL's message).  Inputs are trusted: ss_inject.c has checked every
 * index and that every coordinate is finite. */
#ifndef SS_INJECT_CGAL_H
#define SS_INJECT_CGAL_H

#include <stddef.h>

#include "ss_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How the winding number came out. */
typedef enum {
  SS_WIND_OK = 0,      /* *winding holds it */
  SS_WIND_ON_BOUNDARY, /* the point lies on the (closed) boundary image */
  SS_WIND_NO_RAY       /* every ray tried met an edge or a vertex */
} ss_wind_kind;

/* Winding number about point p = x[centre] of the closed oriented chain of
 * nfacet facets facet[dim * f + 0..dim-1]: triangles (dim 3, counter-
 * clockwise seen from outside a positive cell) or segments (dim 2, the
 * interior of a positive cell on their left).  The chain must be a cycle
 * (every edge of the triangles, every end of the segments, cancels).
 * Counted as the signed crossings of a segment from p to a point q beyond
 * every facet (x > the largest facet x), q re-chosen at random (a fixed
 * seed) while the segment meets a facet's edge or vertex or lies in its
 * plane; zero-area facets add nothing and are only tested for holding p.
 * Cost O(nfacet) per try, at most 64 tries. */
ss_status ss_inject_cgal_winding(int dim, const double *x, size_t nfacet,
                                 const size_t *facet, size_t centre, ss_wind_kind *kind,
                                 int *winding, ss_error *err);

/* Count the pairs of cells that share no corner and whose images meet.  Cell
 * c (c < ncells) has corners corner[c * maxcorner + j] (unused slots
 * SIZE_MAX) and image the union of the closed simplices (tets in 3D,
 * triangles in 2D) piece[(dim + 1) * s + 0..dim], s in
 * [first_piece[c], first_piece[c + 1]), whose vertices index x.  A simplex
 * that is flat counts as the convex hull of its points.  *noverlaps gets the
 * count and pair[0] < pair[1] the smallest such pair (lexicographically), or
 * SIZE_MAX twice when there is none.  Cost: a box filter over the cells
 * (CGAL::box_self_intersection_d), then the simplices of each candidate pair
 * with their boxes overlapping. */
ss_status ss_inject_cgal_overlaps(int dim, const double *x, size_t ncells,
                                  const size_t *corner, int maxcorner,
                                  const size_t *first_piece, const size_t *piece,
                                  size_t *noverlaps, size_t pair[2], ss_error *err);

/* For the tests: whether the closed simplices a and b (dim + 1 points each,
 * dim = 2 or 3, point by point) meet, by CGAL's do_intersect (*exact, 0 or
 * 1), and what the cheap test that ss_inject_cgal_overlaps asks first
 * answered (*quick: 0 apart, 1 they meet, -1 not decided; -2 when a simplex
 * is flat, where it is not asked).  The overlap count is right only while
 * *quick is -1 or equals *exact. */
ss_status ss_inject_cgal_meet(int dim, const double *a, const double *b, int *quick,
                              int *exact, ss_error *err);

#ifdef __cplusplus
}
#endif

#endif
