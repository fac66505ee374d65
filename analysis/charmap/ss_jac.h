/* ss_jac.h — the sign of the Jacobian determinant of one cell's natural
 * interpolant, and its scaled Jacobian (DESIGN section 5).
 *
 * A cell is given by its corner points in the vertex order of ss_cx.h, `dim`
 * coordinates each (3 for hexes, tets and octahedra; 2 for quads and
 * triangles), and mapped by its natural interpolant:
 *   hex       the trilinear map of [0,1]^3 (corner j at the parameter point
 *             ss_cube_corner_bits(3, j), bit i the i-th parameter).  Its
 *             Jacobian determinant is triquadratic; its 27 Bernstein (Bezier)
 *             coefficients on [0,1]^3 bound it, and the 8 corner coefficients
 *             are its exact corner values.  All 27 of one strict sign: that sign
 *             everywhere.  Two exact values (corners of the cell or of a
 *             sub-cube) of opposite signs: folded.  Otherwise the box is split
 *             in 8 by de Casteljau's algorithm, down to `maxdepth` levels;
 *             boxes still in doubt there make the cell undecided.
 *   quad      the bilinear map of [0,1]^2: its Jacobian determinant is affine,
 *             so the four corner values decide exactly (two of opposite signs:
 *             folded).
 *   tet, triangle  the affine map: the determinant of the edge vectors from
 *             vertex 0.
 *   oct       the eight tets (centroid, one vertex of each opposite pair
 *             (0,3), (1,4), (2,5)), each oriented as the octant it fills: all
 *             eight of one strict sign, else folded when two are of opposite
 *             signs.
 *
 * Values with no sign.  Rounding alone never decides a verdict.  In the double
 * path (ss_jac_cell) a value v of det J is zero to rounding, and has no sign,
 * when |v| <= SS_JAC_FLAT L^dim, L the largest distance between two corners of
 * the cell (dim 3 for hexes, tets, octahedra, 2 for quads and triangles); the
 * rounding of the values is of order 1e-16 (|x| / L) L^dim, so the threshold
 * covers cells up to about 10^3 of their size away from the origin.  In the
 * interval path (ss_jac_cell_interval) an enclosure holding 0 has no sign.
 * "Strict sign" above means: a sign.  Then:
 *   - every value that bounds det J without a sign (the 27 coefficients of
 *     the cell, the 4 quad corner values, the simplex determinant, the 8
 *     octant determinants): SS_JAC_DEGENERATE in the double path (flat),
 *     SS_JAC_UNDECIDED in the interval path;
 *   - else two exact values (corner coefficients of the cell or of a sub-box,
 *     quad corner values, octant determinants) with signs, opposite ones:
 *     SS_JAC_FOLDED;
 *   - else an exact value without a sign: SS_JAC_UNDECIDED, `where` at the
 *     first one met.  A hex box with such a corner is not split further (its
 *     sub-boxes at that corner could never be decided, and where det J
 *     vanishes on a face their number would grow as 4^depth); the other boxes
 *     are still searched for a fold.
 * This replaces an earlier rule, "an exact zero means folded": a value that is
 * 0 mathematically comes out as +-1e-17 as often as 0.
 *
 * Scaled Jacobian (a continuous measure, 1 for the ideal cell, invariant
 * under similarities, negative when inverted): min_scaled is the smallest over the
 * cell's corners of det(edge vectors at the corner) / product of their lengths,
 * with edges taken along the parameter directions (hex, quad), times sqrt(2) for
 * tets and 2/sqrt(3) for triangles so that the regular simplex scores 1; for an
 * octahedron the smallest over its eight centroid tets of that value at the
 * centroid (1 for the regular octahedron).  For a cell of one strict sign the
 * smallest |corner value| (its quality) is at most 1; single tet corners reach
 * sqrt(2) in size, so an inverted tet's min_scaled can be below -1 (ss_charmap
 * uses -quality for cells of the opposite sign).
 *
 * These functions cannot fail: cells have at most 8 corners and the
 * subdivision works in a fixed-size stack (about 40 kB for doubles and 70 kB
 * for intervals).  Non-finite corners give SS_JAC_UNDECIDED with NaN
 * measures. */
#ifndef SS_JAC_H
#define SS_JAC_H

#include "ss_api.h"
#include "ss_cx.h"

SS_BEGIN_DECLS

/* The verdict for one cell. */
typedef enum {
  SS_JAC_FOLDED = 0,    /* the determinant vanishes or changes sign in the cell */
  SS_JAC_POSITIVE = 1,  /* > 0 everywhere on the closed cell */
  SS_JAC_NEGATIVE = -1, /* < 0 everywhere on the closed cell */
  SS_JAC_UNDECIDED = 2, /* still in doubt: hex at the depth limit; or a value
                           that decides is zero to rounding (see below); or,
                           for the interval and exact variants, no proof */
  SS_JAC_DEGENERATE = 3 /* double path only: every value that bounds det J is
                           zero to rounding, |v| <= SS_JAC_FLAT L^dim (L the
                           cell's largest corner distance): flat, no sign */
} ss_jac_sign;

/* Result for one cell. */
typedef struct {
  ss_jac_sign sign;  /* the verdict */
  double min_scaled; /* smallest scaled Jacobian of the cell (see above) */
  double max_scaled; /* largest corner value of the same measure, so that a
                        caller whose cells are all negative can report
                        -max_scaled as its margin */
  int depth;         /* hex: deepest subdivision level used (0 = none) */
  double where[3];   /* FOLDED: a parameter point of the cell where the sign
                        differs from the sign seen first; UNDECIDED because
                        an exact value has no sign: that value's point (hex,
                        quad: in [0,1]^d; tet, triangle, oct, other
                        verdicts: unused, zero) */
} ss_jac_result;

/* Relative size below which a value of det J is zero to rounding in the
 * double path: |v| <= SS_JAC_FLAT * L^dim (see "Values with no sign"). */
#define SS_JAC_FLAT 1e-12

/* Default depth limit of the hex subdivision. */
#define SS_JAC_DEPTH 6

/* Decide the sign of the Jacobian determinant of cell type t with corners x
 * (ss_cell_nverts(t) points of dim coordinates, row by row) and compute its
 * scaled Jacobian.  dim must be 3 for hexes, tets and octahedra and 2 for quads
 * and triangles; other types or dims give SS_JAC_UNDECIDED with NaN measures.
 * maxdepth bounds the hex subdivision (0: the 27 coefficients only). */
void ss_jac_cell(ss_cell_type t, const double *x, int dim, int maxdepth,
                 ss_jac_result *r);

/* As ss_jac_cell for corners known only within boxes, lo[i] <= x[i] <= hi[i]
 * (same layout as x): every quantity is computed in interval arithmetic with
 * outward rounding (arb's di_t), so POSITIVE / NEGATIVE / FOLDED hold for
 * every net in the boxes (the true one among them): POSITIVE when every
 * bounding value is certainly > 0 (after subdivision, for hexes), FOLDED when
 * two exact values (corner coefficients of the cell or of a sub-box, corner
 * values of a quad, octant determinants) are certainly of opposite signs;
 * otherwise UNDECIDED, with `where` as in ss_jac_cell.  Never DEGENERATE.
 * min_scaled and max_scaled are those of the midpoints (a measure, not a
 * proof).  A non-finite bound or lo[i] > hi[i] gives UNDECIDED with NaN
 * measures.  The same traversal as ss_jac_cell, at 10 to 15 times its cost. */
void ss_jac_cell_interval(ss_cell_type t, const double *lo, const double *hi, int dim,
                          int maxdepth, ss_jac_result *r);

/* The verdict of ss_jac_cell_interval without the measures (min_scaled and
 * max_scaled NaN), the certified path's cell test: for a hex in dim 3, first
 * ss_jac_hex_midrad (one evaluation at the midpoints, an a-priori bound),
 * then the 27 Bernstein coefficients enclosed in di_t from its 12 edge
 * vectors (each derivative of the trilinear map at a Lagrange point is an
 * edge or a half sum of edges: about a third of the operations), either
 * proving one sign giving that sign at depth 0; otherwise, and for the
 * other cell types, exactly ss_jac_cell_interval's traversal.  All three
 * enclosures are proofs, so the verdict is ss_jac_cell_interval's wherever
 * that one is POSITIVE, NEGATIVE or FOLDED, and may be POSITIVE or NEGATIVE
 * where that one is UNDECIDED (the enclosures differ in their last bits and
 * widths). */
void ss_jac_cell_interval_sign(ss_cell_type t, const double *lo, const double *hi,
                               int dim, int maxdepth, ss_jac_result *r);

/* The 27 Bernstein coefficients of det J of a hex (dim 3) whose corners are
 * known within boxes lo[i] <= x[i] <= hi[i], from one evaluation in doubles
 * at the boxes' midpoints: c[q] the value there, E[q] an a-priori bound on
 * how far the true coefficient of any hex in the boxes lies from it (the
 * boxes' widths and every rounding; the derivation is at the definition).
 * Returns +1 or -1 when every c[q] is beyond E[q] on that side of 0 (det J
 * has that sign on the whole cell, for every hex in the boxes), 0 otherwise,
 * also for a bound that is not finite, lo[i] > hi[i], or entries outside
 * [2^-300, 2^100] in size (c and E then unspecified).  A third of the
 * interval test's cost: ss_jac_cell_interval_sign tries it first. */
int ss_jac_hex_midrad(const double *lo, const double *hi, double *c, double *E);

/* Jacobian determinant of the trilinear map of the hex with corners x (8 x 3)
 * at the parameter point (u, v, w) in [0,1]^3: the reference value the
 * Bernstein test bounds (for tests and pictures). */
double ss_jac_hex_at(const double *x, double u, double v, double w);

SS_END_DECLS

#endif
