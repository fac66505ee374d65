/* ss_psi_bernstein.h — the sign of det Dψ on one tricubic B-spline piece of
 * the characteristic map, proven (issue 34, section 2; DESIGN section 5).
 *
 * On a ring cell whose 4x4x4 control neighbourhood is a regular grid, the
 * characteristic map ψ of MLCA and ccsolid is exactly the tricubic B-spline
 * of those 64 points, so det Dψ is a polynomial of degree (8, 8, 8) with
 * 9 x 9 x 9 = 729 Bernstein coefficients on [0,1]^3.  The net's layout is
 * ss_limit_bspline's (analysis/limit/ss_limit.h): net[i + 4j + 16k] is the
 * control point at grid position (i - 1, j - 1, k - 1), the piece being
 * [0,1]^3 in (u, v, w) = parameters along i, j, k.
 *
 * Method.  Per direction the uniform cubic B-spline's 4 points P0..P3 become
 * the segment's Bezier points b0 = (P0 + 4P1 + P2)/6, b1 = (4P1 + 2P2)/6,
 * b2 = (2P1 + 4P2)/6, b3 = (P1 + 4P2 + P3)/6; the three partial derivatives
 * of the tricubic Bezier net are Bernstein polynomials of degrees (2,3,3),
 * (3,2,3), (3,3,2); det Dψ = ψ_u . (ψ_v x ψ_w) is formed by Bernstein
 * multiplication (coefficients scaled by their binomials, 3D convolution,
 * the product's binomials divided out at the end).  The factors 1/6 per
 * axis and 3 per derivative are kept out of the sums and divided out with
 * the binomials in one division per coefficient, so the double path rounds
 * only its additions, products and that division; the interval path does
 * the same operations in arb's di_t with outward rounding.
 *
 * The decision (as ss_jac's hex test, analysis/charmap/ss_jac.h, one degree
 * up): all 729 coefficients of one strict sign prove that sign on the closed
 * piece; the 8 corner coefficients are exact values of det Dψ (at the
 * corners), so two of opposite strict signs prove a fold; otherwise the
 * coefficient box is split in 8 by de Casteljau's algorithm at 1/2 per axis
 * and the sub-boxes judged the same way (their corner coefficients again
 * exact values), down to maxdepth levels.  A box with an exact corner value
 * of no sign is not split further (its sub-boxes at that corner could never
 * be decided); the other boxes are still searched for a fold.
 *
 * Values with no sign.  Rounding alone never decides.  In the double path a
 * value v is zero to rounding when |v| <= ss_psi_bernstein_flat(net), i.e.
 * SS_PSI_FLAT N_u N_v N_w with N_a the largest Euclidean norm of the
 * Bernstein coefficients of the partial derivative ψ_a: every coefficient of
 * det Dψ is a convex combination of triple products of those, so |v| <= N_u
 * N_v N_w, and the rounding of the computed coefficients is of order
 * 1e-16 (|x| / L) N_u N_v N_w for a piece of size L at distance |x| from the
 * origin: the threshold covers pieces up to about 10^3 of their size away
 * from the origin (as SS_JAC_FLAT does for cells).  In the interval path an
 * enclosure that holds 0 has no sign (no threshold).
 *
 * Cost and memory: about 50,000 multiply-adds for the coefficients (some 14
 * us in doubles, 20 times that in intervals), about 8,700 halvings per
 * sub-box judged (7 us, 40 us), and one 729-coefficient box per subdivision
 * level, held in fixed-size arrays on the C stack (about 65 kB for doubles,
 * 130 kB for intervals, with the coefficients' scratch); no allocation, no
 * global state, nothing printed.  A piece whose det Dψ touches 0 without
 * changing sign away from the sub-box corners is the worst case: every box
 * along the zero set is split down to maxdepth (about 11,000 boxes at depth
 * 6 for a plane of tangential zeros: 80 ms in doubles, 0.5 s in intervals).
 * These functions cannot fail: a non-finite input, or lo > hi, gives
 * SS_JAC_UNDECIDED with NaN measures. */
#ifndef SS_PSI_BERNSTEIN_H
#define SS_PSI_BERNSTEIN_H

#include "ss_api.h"
#include "ss_jac.h"

SS_BEGIN_DECLS

/* The number of Bernstein coefficients of det Dψ on a piece: degree 8 in
 * each of u, v, w, coefficient (a, b, c) at index a + 9b + 81c. */
#define SS_PSI_NCOEF 729

/* Relative size below which a value of det Dψ is zero to rounding in the
 * double path: |v| <= SS_PSI_FLAT N_u N_v N_w (see "Values with no sign"). */
#define SS_PSI_FLAT SS_JAC_FLAT

/* Default depth limit of the subdivision, and the largest depth used (a
 * larger maxdepth is taken as SS_PSI_MAXDEPTH: 8^8 boxes of side 1/256). */
#define SS_PSI_DEPTH    6
#define SS_PSI_MAXDEPTH 8

/* The verdict on one piece. */
typedef struct {
  ss_jac_sign sign;   /* SS_JAC_POSITIVE / SS_JAC_NEGATIVE: det Dψ proven of
                         that strict sign on the closed piece [0,1]^3;
                         SS_JAC_FOLDED: two exact values of det Dψ (corner
                         coefficients of the piece or of a sub-box) of
                         opposite strict signs, at where[0] and where[1];
                         SS_JAC_UNDECIDED: depth limit reached with boxes in
                         doubt, or an exact value of no sign (zero to
                         rounding in the double path, an enclosure holding
                         0 in the interval path), or non-finite input;
                         SS_JAC_DEGENERATE (double path only): all 729
                         coefficients zero to rounding, det Dψ flat */
  double where[2][3]; /* FOLDED: the two parameter points in [0,1]^3 (corners
                         of the piece or of sub-boxes), where[0] the one of
                         the sign met first; UNDECIDED because an exact value
                         has no sign: where[0] is the first such point met
                         and where[1] is unused; otherwise zero */
  double det[2][2];   /* det[i] = {lo, hi}: an enclosure of det Dψ at
                         where[i] (the double path: lo = hi = the computed
                         value), for the points where[] holds; else zero */
  double min_coef;    /* the smallest of the piece's 729 coefficients (the
                         interval path: of their midpoints): a measure of
                         how far from failing, not a proof; NaN on bad input */
  double max_coef;    /* the largest, likewise */
  double flat;        /* the zero-to-rounding threshold used (the double
                         path: ss_psi_bernstein_flat(net); intervals: 0) */
  int depth;          /* the deepest subdivision level used (0: none) */
  long boxes;         /* the number of boxes judged (1 without subdivision) */
} ss_psi_piece_result;

/* The 729 Bernstein coefficients of det Dψ on [0,1]^3 of the tricubic
 * B-spline of net (64 points, layout above), coef[a + 9b + 81c] for degree
 * indices a (in u), b (in v), c (in w); in doubles (rounded; a net that is
 * not finite gives coefficients that are not finite). */
void ss_psi_bernstein_det(const double (*net)[3], double coef[SS_PSI_NCOEF]);

/* As ss_psi_bernstein_det for a net known within boxes, lo[q][r] <= net[q][r]
 * <= hi[q][r]: [clo[i], chi[i]] encloses coefficient i for every net in the
 * boxes (interval arithmetic, outward rounding).  Bad input (non-finite, lo >
 * hi): every enclosure is [-inf, inf]. */
void ss_psi_bernstein_det_interval(const double (*lo)[3], const double (*hi)[3],
                                   double clo[SS_PSI_NCOEF], double chi[SS_PSI_NCOEF]);

/* The value at (u, v, w) in [0,1]^3 of the polynomial with Bernstein
 * coefficients coef (degree 8 each, layout above), by de Casteljau's
 * algorithm. */
double ss_psi_bernstein_eval(const double coef[SS_PSI_NCOEF], double u, double v,
                             double w);

/* The double path's zero-to-rounding threshold of the piece of net:
 * SS_PSI_FLAT N_u N_v N_w (see "Values with no sign"); NaN for a net that is
 * not finite. */
double ss_psi_bernstein_flat(const double (*net)[3]);

/* Decide the sign of det Dψ on the piece of net in doubles (method above),
 * subdividing down to maxdepth levels (0: the 729 coefficients only;
 * negative taken as 0, above SS_PSI_MAXDEPTH as SS_PSI_MAXDEPTH). */
void ss_psi_piece_sign(const double (*net)[3], int maxdepth, ss_psi_piece_result *r);

/* As ss_psi_piece_sign for a net known within boxes lo <= net <= hi, in
 * interval arithmetic with outward rounding: POSITIVE / NEGATIVE / FOLDED
 * hold for every net in the boxes (the true one among them); never
 * DEGENERATE (a piece with every enclosure holding 0 is UNDECIDED).  The same
 * traversal as ss_psi_piece_sign. */
void ss_psi_piece_sign_interval(const double (*lo)[3], const double (*hi)[3],
                                int maxdepth, ss_psi_piece_result *r);

/* As ss_psi_piece_sign_interval for the polynomial det[∂_u ψ0 | ∂_v ψ1 |
 * ∂_w ψ2] of three tricubics, net a known within lo[a] <= net a <= hi[a]:
 * column a of the Jacobian from net a.  With three equal nets it is det Dψ;
 * the spoke tubes (ss_psi_tube.h) take the column along a spoke from one net
 * and the columns across it from another, scaled apart (det changes by a
 * positive factor only).  The same coefficients, traversal and verdicts. */
void ss_psi_piece_sign_interval3(const double (*const lo[3])[3],
                                 const double (*const hi[3])[3], int maxdepth,
                                 ss_psi_piece_result *r);

SS_END_DECLS

#endif
