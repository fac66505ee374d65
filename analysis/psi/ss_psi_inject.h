/* ss_psi_inject.h — injectivity of the characteristic map psi of a vertex,
 * proven from its regularity and its degree on the boundary of its star
 * (issue 34, section 4).
 *
 * The theorem used.  Let D0 be the star of p (the cells around p, a ball),
 * D1 = D0 / 2 its self-similar copy, psi(x / 2) = Lambda psi(x) with Lambda
 * invertible and |eigenvalues| < 1 (the subdominant eigenvalues), psi(p) = 0,
 * so psi extends to the infinite cone C = union of 2^j D0.  Suppose
 *   (R) det Dpsi has one strict sign s on the ring D0 \ D1 minus the spokes
 *       (edges from p) — hence on C \ (spokes u {p}); psi is C^1 there;
 *   (A) along each spoke psi is a C^1 curve with nonzero derivative;
 *   (W) 0 is not on psi(dD0) and the winding number of psi|dD0 round 0,
 *       dD0 oriented outward, is s.
 * Then psi is injective on C.  Proof sketch: for y off the null set psi(dD_j
 * u spokes), the preimages of y in D_-J = 2^J D0 are regular points, each of
 * local degree s, so their number is s deg(psi, D_-J, y) = s winding(psi(dD_-J),
 * y) = s winding(psi(dD0), Lambda^(J+1) y) (up to the sign of det Lambda^(J+1):
 * take J + 1 even), which is 1 once Lambda^(J+1) y lies in the component of
 * 0.  So such y have one preimage in C.  Two preimages x1 != x2 of any y: if
 * one is regular, its neighbourhood maps onto a neighbourhood of y, which
 * meets the open image of a neighbourhood of the other (psi of the regular
 * points near it): a generic point with two preimages.  If both are on
 * spokes they are isolated preimages (by (A) along the spoke, and regular
 * preimages accumulating at one would be the first case), so the local
 * degree on a small ball round each is defined, constant near y and positive
 * (the ball's regular points map to points arbitrarily near y), and again a
 * generic point near y has two preimages.  And with (R), (W) with winding n s,
 * |n| >= 2, generic y near 0 have |n| preimages in D0: psi is not injective.
 *
 * (R) and (A) are ss_psi's certified pass with the tubes (ss_psi_tube.h: the
 * along-spoke column is one factor of det Dpsi's proven strict sign, to the
 * spoke).  (W) is computed here:
 *   - dD0 is the union of the faces of the cells around p opposite p.  On
 *     the grid of side 2^-N (N = the ring's box depth) each face square lies
 *     in one box of the traversal: a polynomial piece (psi in the convex hull
 *     of its 64 B-spline points) or a tube's box (psi in the hull of its
 *     patch: the rule's weights are nonnegative and sum to 1, checked on the
 *     tube's exact F and G_c).
 *   - T: the closed surface of triangles over that grid with one double
 *     point per grid vertex (psi in doubles where a piece holds it, a tube
 *     patch's mean on a spoke), the vertices named by their exact star
 *     coordinates so that neighbouring cells share them (closedness is
 *     checked: every edge twice, once each way).
 *   - The straight homotopy (1 - t) psi + t T avoids 0 if for each square a
 *     direction d has d.x > 0 on every enclosed point of its box's hull
 *     (arb, from the piece's enclosure) and on its four vertices of T; then
 *     winding(psi|dD0) = winding(T) = (sum of the triangles' signed solid
 *     angles) / 4 pi, enclosed in arb (Van Oosterom-Strackee) and rounded to
 *     the unique integer its ball holds.
 * Nothing else is claimed: a square without such a d, an open surface, a
 * ball holding no unique integer leave injectivity undecided, with why. */
#ifndef SS_PSI_INJECT_H
#define SS_PSI_INJECT_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_limit_pieces.h"
#include "ss_local.h"

SS_BEGIN_DECLS

#define SS_PSI_INJECT_MAXSQ  2000000 /* most boundary squares (memory bound) */
#define SS_PSI_INJECT_REFINE 3       /* grid levels tried below the box depth */

/* The boundary's squares and vertices gathered during a traversal. */
typedef struct ss_psi_inject ss_psi_inject;

/* What the degree on the boundary decided. */
typedef struct {
  int decided;    /* 1: psi injective (proven); -1: psi not injective
                     (proven: degree of absolute value >= 2); 0: not decided */
  int degree;     /* with a unique integer: the winding number of psi|dD0
                     round 0 (outward orientation); else 0 */
  size_t squares; /* boundary squares used */
  double wlo;     /* the winding number's enclosure */
  double whi;
  char why[200]; /* the reason, proven or not */
} ss_psi_inject_result;

/* For the cells of M around p, boundary grid of side 2^-depth (1..8).  NULL
 * when out of memory. */
ss_psi_inject *ss_psi_inject_new(const ss_local *M, int depth);
/* (The grid starts at the box depth and is refined, up to
 * SS_PSI_INJECT_REFINE levels and side 2^-8, while a square's hull is not
 * separated from 0: pieces' nets are refined to the square; a tube's box
 * keeps its patch's hull, its squares' inner vertices its patch's mean.) */
void ss_psi_inject_free(ss_psi_inject *b);

/* One box of ss_limit_pieces_tubes with an enclosure (a piece, or a tube's
 * box at the box depth) in a cell around p, p at its corner pbits: its
 * squares on the faces opposite p, if any.  A box without enclosure or the
 * structure above marks the boundary undecidable (the result says why).
 * SS_ENOMEM only. */
ss_status ss_psi_inject_box(ss_psi_inject *b, const ss_limit_piece *pc, unsigned pbits,
                            ss_error *err);

/* The winding number once every box was given; sign: the proven sign of
 * det Dpsi (+-1).  SS_ENOMEM only; the rest is in *out. */
ss_status ss_psi_inject_degree(ss_psi_inject *b, int sign, ss_psi_inject_result *out,
                               ss_error *err);

SS_END_DECLS

#endif
