/* ss_psi_tet.h — the spokes of a tet/oct vertex case decided from the edge
 * case's own local matrix (issue 34, section 3; DESIGN section 5, "The
 * spokes").  tet/oct has no limit evaluator (ss_limit.h is hex only), so the
 * spoke coefficient is read from the ring's control points instead.
 *
 * Matching.  Round the spoke p-a of a tet vertex star (ss_star.h: conical
 * coordinates, tet (0, e_a, e_b, e_c) per positive link triangle (a, b, c)),
 * with b_0..b_{n-1} a's link neighbours in their cyclic order (so (a, b_i,
 * b_i+1) are positive link triangles), the affine map sending tet (0, e_a,
 * e_b_i, e_b_i+1) onto the edge star's tet i (-e_n, e_n, e_i, e_i+1) (vertex
 * order to vertex order: both are positive, ss_star_check_positive, so the
 * map keeps orientation) sends an offset dx (level-l grid units) to
 *     dy_n = 2 dx_a + dx_b_i + dx_b_i+1,  dy_i = dx_b_i,  dy_i+1 = dx_b_i+1.
 * Refinement is by midpoints, so it maps each level's lattice onto the
 * other's; tet/oct reads no diagonals, so the refined cells correspond too.
 * An edge-case label y (an offset from the edge's centre, in its level's
 * grid units) therefore names, for a spoke point e = t e_a of ring level r,
 * the point with coordinates
 *     coord(e) + sum_i y_i e_b_i + (y_n - sum_i y_i) / 2 e_a
 * (ss_local_ring.coord).  The edge case's S describes the refinement round e
 * exactly when every such point keeps an e_a coordinate >= 1 (its cells then
 * lie in the n tets round the spoke, away from p's other cones; the far end
 * e_a of level 0 is outside the ring): such a spoke point is usable when all
 * its labels land on points of the ring level; others are skipped and counted.
 *
 * The coefficient.  With the edge case's left eigenvectors l_h (eigenvalue
 * 1/2, along the edge) and l_1, l_2 (the double eigenvalue lambda across;
 * ss_eigvec, biorthonormal to the right ones r_h, r_1, r_2) applied to psi's
 * ring points X at the matched labels, a' = l_h . X and B = (l_1 . X,
 * l_2 . X) are the coefficients of psi's expansion round e in the edge's
 * eigenfunctions, psi = psi(e) + a' phi_h + B chi + (smaller modes), so close
 * to the spoke det Dpsi has the sign of
 *     s(e) = sigma det[a' | l_1 . X | l_2 . X],
 * sigma the orientation of the edge's own characteristic map (r_h, r_1, r_2)
 * on the edge case's cells (the sign of every cell of its last ring level;
 * the edge analysis passes regularity for valences 3..10,
 * reports/tetoct-edges-3-10.md).  rel = |s| / d^3, d the largest distance of
 * a matched point from X(e): s relative to the neighbourhood's size.
 *
 * Classes, per spoke, over its usable points on every ring level of M, as
 * ss_psi_spoke.h: sign change (points of both strict signs), degenerate (a
 * point with rel below SS_PSI_SPOKE_DEGENERATE, no sign change), one sign.
 * A spoke with no usable point is not classified (ss_psi_tet_spoke.cls -1).
 *
 * Proven: nothing.  Evidence in double precision at finitely many points of
 * ring levels 0..nring-1 (x0 = t / 2^(r+1); psi(x / 2) = Lambda psi(x) with
 * Lambda positive, so s at x0 / 2 has the sign of s at x0 and a period
 * [x0, 2 x0) of the spoke decides it): a zero of s between two points is
 * not excluded, and the degenerate threshold cannot tell s = 0 from a tiny
 * s.  Checked (tests/psi/test_psi_spoke_tet.c): the label map against the
 * edge case's S row by row on the ring, and the sign against a second path
 * (the matched points refined by the edge's S alone, the tets at its centre). */
#ifndef SS_PSI_TET_H
#define SS_PSI_TET_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_case.h"
#include "ss_charmap.h"
#include "ss_error.h"
#include "ss_local.h"
#include "ss_psi.h"
#include "ss_psi_spoke.h"
#include "ss_scheme.h"

SS_BEGIN_DECLS

/* The edge case of valence n, what the spokes read from it. */
typedef struct {
  int n;          /* valence */
  ss_local *E;    /* its local matrix (labels, S, ring), owned */
  double lambda;  /* the across eigenvalue (double, real) */
  double next;    /* the largest modulus after 1, 1/2 and lambda, lambda */
  double *l;      /* 3 left eigenvectors, E->n2 entries each (l + j E->n2):
                     1/2, then the two of lambda; biorthonormal to r */
  double *r;      /* the 3 right eigenvectors, the same layout */
  int sigma;      /* +1 or -1: the sign of det of the map (r_h, r_1, r_2) on
                     every cell of E's last ring level */
  size_t emaxneg; /* the largest -dx_a over the labels: a spoke point needs
                     t > emaxneg to be usable */
} ss_psi_tet_edge;

/* The edge model of valence n (>= 3) under scheme s (a
 * tet/oct split reading no diagonals).  *out is the caller's
 * (ss_psi_tet_edge_free).  SS_EINPUT for another scheme or valence;
 * SS_ENUMERIC when the spectrum is not 1, 1/2 and a real double pair in some
 * order among the four leading, the pairs are not biorthonormal, or the
 * edge's map is not of one strict sign on its ring; SS_ENOMEM; the errors of
 * ss_local_new. */
ss_status ss_psi_tet_edge_new(const ss_scheme *s, int n, ss_psi_tet_edge **out,
                              ss_error *err);

void ss_psi_tet_edge_free(ss_psi_tet_edge *m);

/* The link vertex and the edge-case label y mapped onto the vertex star
 * round spoke point t e_a (above): coordinates into *out (relative to p, the
 * spoke point's level's units).  nb: a's n link neighbours in cyclic order.
 * Returns 0, or -1 when y is not a label of that shape (support not on two
 * consecutive faces and the edge, or (y_n - sum y_i) odd). */
int ss_psi_tet_map_label(int a, const int *nb, int n, int t, const ss_star_coord *y,
                         ss_star_coord *out);

/* The spokes of tet vertex case M (link l, the one M was made from: the
 * case's) with net x on its two-ring (M->n2 x 3, any basis of the
 * subdominant subspace), classified over every ring level M has.  Every link
 * vertex is a spoke (an edge of n tets is never the lattice's, which has two
 * tets and two octahedra round it).  The samples reuse ss_psi_spoke_sample:
 * cell = a two-ring cell round p holding the spoke, at = on = the point's
 * parameters there (corner 0 + u (corner 1 - corner 0) + v (corner 2 -
 * corner 0) + w (corner 3 - corner 0)), axis -1, x0 = t / 2^(r+1), s and rel
 * as above, det_eval = s (there is no second route).  mu = lambda, gap =
 * next / min(1/2, lambda).  *out is the caller's (ss_psi_spokes_free);
 * nskipped receives the spoke points not usable.  SS_EINPUT when M is not a
 * tet vertex case or l does not fit it; the errors of ss_psi_tet_edge_new. */
ss_status ss_psi_tet_spokes_classify(const ss_scheme *s, const ss_local *M,
                                     const ss_link *l, const double *x,
                                     ss_psi_spokes *out, size_t *nskipped, ss_error *err);

/* psi of tet/oct vertex case c (M, its net x = the characteristic map's,
 * e NULL or the exact path's enclosure of that net in its own basis, reg
 * the control net's regularity verdict of x on M's ring) judged at its
 * regular vertices and by its spokes.  Runs (out->ran = 1) unless reg
 * passes; the spokes only for tetoct (boxspline reads major diagonals;
 * boxspline-avg's split is not checked against its edge cases), so for the
 * other tet schemes only a fold at the regular vertices decides.  The case is extracted
 * again with SS_LOCAL_MAXRING whole ring levels (ss_local_opts.whole: the
 * points round the whole spoke, 18 usable points per spoke covering x0 in
 * [3/16, 7/8], a full period of psi's self-similarity at step 1/16).
 * First the regular vertices (ss_psi_mask.h): two of opposite strict signs
 * -> fail on psi, witnesses those two (their chart points; with e only when
 * proven, ss_psi_mask_certify, and then certified).  Then, when reg is
 * undecided with a sign, the bad cells of the deepest ring level (the
 * ring's cells, not of the ring's sign) are located: when each has a corner
 * on a spoke, the spokes decide,
 *   a sign change                      -> fail, witnesses its two points;
 *   one sign opposite to the ring's    -> fail, witnesses its point of least
 *                                         |s| and a point of a spoke of the
 *                                         ring's sign;
 *   degenerate                         -> fail "degenerate on spoke a";
 *   all of the ring's sign             -> pass, by evidence on the spokes;
 * never certified (ss_psi_apply with certify then leaves the net's verdict,
 * the finding in its reason); otherwise undecided with the reason.  The
 * spokes' witnesses' det holds s (the sign of det Dpsi in the tube, not its
 * value); covered and uncovered are 0, by_spokes 1.  SS_ENOMEM; the errors
 * of the extraction and of ss_psi_mask_certify. */
ss_status ss_psi_tet_judge(const ss_scheme *s, const ss_case *c, const ss_local *M,
                           const double *x, const ss_psi_enclosure *e,
                           const ss_regularity *reg, ss_psi_result *out, ss_error *err);

SS_END_DECLS

#endif
