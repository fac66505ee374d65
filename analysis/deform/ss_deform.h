/* ss_deform.h — deformations of embedded test patterns (tet/oct paper,
 * section 3 and figures 7-8; MacCracken and Joy's free-form deformations):
 * a point x of the base mesh's volume is named by its cell and parameters
 * there, and the deformation sends it to the limit of the moved control net at
 * the same cell and parameters.
 *
 * Cells and parameters (ss_deform_loc).  Every volume cell has a reference
 * shape and an interpolant from it to space, linear in the cell's corners:
 *   hex  (u, v, w) in [0,1]^3, corner k at its bits (ss_cube_corner_bits);
 *        the trilinear map;
 *   tet  (u, v, w) with u, v, w >= 0, u + v + w <= 1, corner 0 at the origin,
 *        corners 1, 2, 3 at the unit vectors (barycentric (1-u-v-w, u, v, w));
 *        the affine map;
 *   oct  r with |r|_1 <= 1, corners 0..5 at +e1 +e2 +e3 -e1 -e2 -e3 (ss_cx.h's
 *        order); the map affine on each of its four tets about the diagonal
 *        (0,3) (the octant pair sign r2, sign r3).
 * The split of each scheme refines a reference shape exactly into the
 * reference shapes of its children, each an affine image (hex children are
 * octants; tet/oct children are scaled or centrally symmetric pieces), so a
 * point keeps exact parameters from level to level: its child is the one
 * whose affine image holds it, its parameters there that image's inverse.
 * The corners of a child are read from the split's parent lists (a fine
 * vertex is the centroid of its parents), not from a table.
 *
 * Level L of subdivision evaluates a point by the interpolant of its level-L
 * cell over the level-L control net; the limit is the limit of those values
 * as L grows (the schemes converge).  Where the exact evaluator covers the
 * mesh (ss_limit.h: hex meshes under mlca, ccsolid and the averaging
 * family), ss_deform_eval_exact gives the limit itself.
 *
 * Library code: nothing here prints; errors through ss_error. */
#ifndef SS_DEFORM_H
#define SS_DEFORM_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_cx.h"
#include "ss_error.h"
#include "ss_scheme.h"

SS_BEGIN_DECLS

/* Where a point lies: a volume cell and its parameters there. */
typedef struct {
  ss_cell_type type; /* SS_HEX, SS_TET or SS_OCT */
  size_t cell;       /* index among the mesh's cells of that type, 0-based */
  double r[3];       /* parameters in the cell's reference shape (above) */
} ss_deform_loc;

/* Tolerance in parameters for "inside a cell" (relative to the reference
 * shape's size 1): points this close outside a cell's face are taken as in
 * it (and their parameters clamped onto the face). */
#define SS_DEFORM_TOL 1e-9

typedef struct ss_deform_locator ss_deform_locator; /* opaque: cell boxes */

/* A point locator over the volume cells (hex, tet, oct) of mesh (3
 * coordinates; copied).  SS_EINPUT when the mesh has not 3 coordinates or no
 * volume cell; SS_ENOMEM.  O(cells). */
ss_status ss_deform_locator_new(const ss_cx *mesh, ss_deform_locator **out,
                                ss_error *err);
void ss_deform_locator_free(ss_deform_locator *P);

/* The cell holding x and its parameters: *found = 1 and *loc set, or *found
 * = 0 when no cell holds x (within SS_DEFORM_TOL).  The first cell in file
 * order (hexes, then tets, then octahedra) whose reference shape holds the
 * parameters wins.  Hex parameters by Newton's method on the trilinear map
 * (converged to 1e-14 or refused for that cell); tets by solving the affine
 * map; octahedra by their four tets.  Cost: the cells whose bounding box
 * holds x. */
void ss_deform_locate(const ss_deform_locator *P, const double x[3], ss_deform_loc *loc,
                      int *found);

/* The interpolant of loc's cell over the positions of mesh (dim >= 3; the
 * first three coordinates): the point with those parameters.  loc must name
 * a cell of mesh. */
void ss_deform_interp(const ss_cx *mesh, const ss_deform_loc *loc, double x[3]);

/* One level of tracking: the child of loc's cell under the split that made
 * fine from coarse (L, from ss_split_refine or ss_scheme_refine_split with
 * the multilinear or tetoct split) and the parameters there, in *out (may
 * alias loc).  SS_EINPUT when the split made no children of that type here
 * (another split kind) or no child holds the point (a defect, not expected);
 * SS_ENOMEM never. */
ss_status ss_deform_child(const ss_cx *coarse, const ss_cx *fine, const ss_split *L,
                          const ss_deform_loc *loc, ss_deform_loc *out, ss_error *err);

/* The subdivision path: refine `mesh` by scheme s `levels` times (1..8),
 * tracking the n points loc; val[(l * n) + i] (levels + 1 rows of n) receives
 * point i at level l (the interpolant of its level-l cell over the level-l
 * net; row 0 is the base interpolant).  `levels` refinements of the whole
 * mesh: memory and time grow by 8^levels.  SS_EINPUT for a scheme whose split
 * is not multilinear or tetoct, a mesh it refuses, a bad loc; SS_ENOMEM. */
ss_status ss_deform_eval_levels(const ss_scheme *s, const ss_cx *mesh, int levels,
                                const ss_deform_loc *loc, size_t n, double (*val)[3],
                                ss_error *err);

/* The exact path: the limit at each loc (all hexes) by ss_limit_eval on mesh;
 * ok[i] = 1 where it succeeded, 0 where the evaluator refused that point (its
 * value NaN; the first such message in err, status SS_OK).  SS_EINPUT when
 * the evaluator does not cover scheme and mesh (ss_limit_new's reasons: the
 * caller then takes the subdivision path) or a loc is not a hex; SS_ENOMEM. */
ss_status ss_deform_eval_exact(const ss_scheme *s, const ss_cx *mesh,
                               const ss_deform_loc *loc, size_t n, double (*val)[3],
                               unsigned char *ok, ss_error *err);

/* The error estimate of the subdivision path at one point from its values at
 * levels 0..levels (levels >= 1): with the gap g_l = |q_l - q_(l-1)| and the
 * contraction lambda = max(1/2, g_L / g_(L-1)) (1/2 alone when levels = 1),
 * the tail of a geometric series g_L lambda / (1 - lambda), or +infinity when
 * lambda >= 1.  An estimate, not a bound: it assumes the gaps keep shrinking
 * by lambda, as they do once the point's cell is in the stationary regime
 * (the rate is then the largest eigenvalue below 1 whose eigenvector the
 * point's value sees; docs/deform.md).  *rate receives lambda. */
double ss_deform_estimate(const double (*q)[3], size_t stride, int levels, double *rate);

SS_END_DECLS

#endif
