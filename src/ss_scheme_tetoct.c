/* ss_scheme_tetoct.c — tetrahedral/octahedral subdivision (Schaefer, Hakenberg,
 * Warren, "Smooth subdivision of tetrahedral meshes", section 2 and figure 5).
 *
 * Linear tet/oct split, then each vertex moves to the mean over its cells of the
 * weighted centroids of figure 4/5:
 *   tet:  -1/16 of the vertex itself, 17/48 of each of the three others;
 *   oct:  3/8 of itself, 1/12 of each of its four edge neighbours, 7/24 of the
 *         opposite vertex.
 * These make the smoothing mask on the uniform lattice 1/8 of the linear
 * subdivision mask, so the composite mask is 1/8 of that mask convolved with
 * itself (the paper's appendix).
 *
 * Creases: the paper's crease surfaces are "defined by Loop subdivision"
 * (figure 8, after Hoppe et al.): a vertex whose lowest cells are triangles
 * takes Loop's rows on the triangle cells (ss_loop_surface: Loop's beta(n) at
 * a surface vertex of n surface neighbours, 3/8, 3/8, 1/8, 1/8 at an edge;
 * the surface's boundary and non-manifold edges are crease curves).
 * Segments average with 1/2, 1/2 (the cubic B-spline: 1/8, 3/4, 1/8 and the
 * midpoint), vertex cells interpolate.  The triangle mask below (self 1/4,
 * 3/8 per other vertex: the construction one dimension down, whose regular
 * composite rule is Loop's quartic box spline too) is what the averaging
 * family and `data/stencils/tetoct.ini` use; it differs from Loop at surface
 * vertices of valence other than 6.  Loop's beta is irrational at most
 * valences; no vertex, edge or face case of tet/oct holds a triangle, so the
 * exact path never meets one. */
#include "ss_scheme_impl.h"

ss_status ss_scheme_tetoct_new(ss_scheme **out, ss_error *err) {
  ss_averaging a = {.split = SS_SPLIT_TETOCT};
  a.accepts[SS_VERTEX] = a.accepts[SS_SEGMENT] = a.accepts[SS_TRIANGLE] =
      a.accepts[SS_TET] = a.accepts[SS_OCT] = 1;
  a.mask[SS_VERTEX][0] = 1.0;
  a.mask[SS_SEGMENT][0] = a.mask[SS_SEGMENT][1] = 1.0 / 2.0;
  a.mask[SS_TRIANGLE][0] = 1.0 / 4.0;
  a.mask[SS_TRIANGLE][1] = 3.0 / 8.0;
  a.mask[SS_TET][0] = -1.0 / 16.0;
  a.mask[SS_TET][1] = 17.0 / 48.0;
  a.mask[SS_OCT][0] = 3.0 / 8.0;
  a.mask[SS_OCT][1] = 1.0 / 12.0;
  a.mask[SS_OCT][2] = 7.0 / 24.0;
  ss_status st = ss_scheme_averaging_new("tetoct", &a, out, err);
  if (!st) (*out)->loop_surfaces = 1;
  return st;
}
