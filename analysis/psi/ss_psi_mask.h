/* ss_psi_mask.h — det Dψ at the regular vertices of ψ's ring, read exactly
 * from the refined net with the regular neighbourhood's tangent masks (issue
 * 34, section 1; DESIGN section 5, "Tangent masks").
 *
 * Where a vertex q of ring level r (ss_local.h) lies inside one cell cone of
 * the star (its chart coordinates supported on exactly dim link vertices,
 * all positive) together with its whole one-ring O(q) — the smallest set of
 * offsets o with q + o closed under the rule: the rows of the level-(r+1)
 * points 2q + o read only level-r points q + o' — the scheme there is the
 * regular lattice's, and the limit's derivatives at q are linear functionals
 * of the net on q + O:
 *   A[i][j] = weight of q + o_j in the row of 2q + o_i      (|O| x |O|),
 *   X[i]    = o_i, the offsets' chart coordinates             (|O| x dim),
 * A X = X / 2 when the rule reproduces linear functions (checked), and if
 * 1/2 is a semisimple eigenvalue of A with eigenspace spanned by X (the
 * regular vertex's subdominant triple), the tangent masks L (dim x |O|) are
 * the unique solution of L (A - I/2) = 0, L X = I: then D_d ψ(q) = sum_i
 * L[d][i] ψ(q + o_i) is the derivative along chart axis d (the limit of the
 * net X is the linear chart map, so its dual basis reads derivatives).  The
 * masks are solved by least squares (LAPACK dgelsd) and kept only when the
 * system has full rank and is solved to SS_PSI_MASK_TOL relative residual;
 * (O, A) pairs are shared by every q with the same neighbourhood (one solve
 * per distinct pair).
 *
 * Stationarity: the masks are read from one level pair, and hold for q
 * only if the same (O, A) governs every finer level round q.  Inside a cell
 * cone every cell is a child of one base cell and the split's rules read
 * only cell types round a vertex, so an interior neighbourhood of the
 * regular lattice stays one (true of every split here); this is checked
 * where the ring has the levels for it — (O, A) read again at q's own
 * point one level down must agree (a neighbourhood seen to differ is not
 * used) — and otherwise assumed, such vertices counted as unchecked (the
 * deepest ring level's; all of tet/oct's, whose one-ring of 19 points
 * fits inside a cone only from ring level 2 on).  The masks are also used
 * only when A's spectrum is a smooth regular vertex's: 1 simple, 1/2 dim
 * times, everything else below 1/2 in modulus (LAPACK, to
 * SS_PSI_MASK_TOL).
 *
 * Orientation: every chart is linear on a cone (positions = sum of
 * coordinates times axes, ss_star.h), and each cone's orientation is read
 * from the ring's cells inside it (positive in space, ss_local.h): the sign
 * of their edge vectors' determinant in chart coordinates.  det Dψ(q) is
 * reported in the cone's chart times that sign, i.e. with the sign of det
 * Dψ against positively oriented space coordinates, and in units of level
 * w's grid (derivatives along level-w chart axes).
 *
 * Verdict: two regular vertices with det Dψ of strict, opposite signs are
 * witnesses that ψ is not regular: the ring is connected, and a local
 * homeomorphism has one local degree on it, which at a point of
 * differentiability with det Dψ != 0 is the sign of det Dψ (so this holds
 * even across a spoke, where ψ need not be C^1).  A value is flat (no sign)
 * when |det| <= SS_JAC_FLAT times the product of the derivatives' norms.
 * Double
 * precision: witnesses of a few rounding errors' size are not proofs.
 *
 * Proof (ss_psi_mask_certify), given an enclosure of ψ's true net (the
 * exact path's subdominant basis, as for ss_psi_certify): the witnesses are
 * found on its midpoints as above, then at each witness q
 *   - A is read exactly (every weight the rational of bounded denominator
 *     it stands for, ss_exact_rational), A X = X / 2 checked in rationals,
 *     the left nullspace N of A - I/2 computed over Q (FLINT) and required
 *     of dimension dim, and L = (N^T X)^-1 N^T exactly;
 *   - A's eigenvalue condition proven by the exact path (ss_exact: 1
 *     simple, then dim real non-defective eigenvalues separated from the
 *     rest) with 1/2 its second root, of multiplicity dim: so 1/2 is the
 *     subdominant eigenvalue, semisimple, with eigenspace spanned by X,
 *     and L P is the derivative (given that the regular scheme is C^1, and
 *     the stationarity above);
 *   - the net on q + O enclosed by pushing the enclosure through the ring
 *     levels in interval arithmetic with the rational weights
 *     (ss_charmap_push_interval), and det(L P) enclosed in interval
 *     arithmetic.
 * Two witnesses whose enclosures have opposite strict signs prove that ψ
 * (of the rule with those rational weights, in the enclosure's basis) is
 * not regular.  Stationarity stays the assumption named above. */
#ifndef SS_PSI_MASK_H
#define SS_PSI_MASK_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_local.h"
#include "ss_psi.h"

SS_BEGIN_DECLS

/* Relative residual below which a tangent-mask solve is accepted; also the
 * tolerance of the linear-reproduction check A X = X / 2. */
#define SS_PSI_MASK_TOL 1e-10
/* Two neighbourhoods with the same offsets are the same when their weights
 * agree to this (absolute; weights are at most 1): rounding of the rule's
 * rational weights, summed in different orders, is of order 1e-16. */
#define SS_PSI_MASK_SAME 1e-13
/* Largest one-ring (offsets) a regular vertex may have. */
#define SS_PSI_MASK_MAXO 256

/* One regular vertex where det Dψ was read. */
typedef struct {
  int level;     /* ring level r of q */
  size_t point;  /* q's index among ring level r's points */
  int cone[3];   /* the link vertices (chart coordinate indices) of q's
                    cone, ascending; unused: -1 */
  double x[3];   /* q's chart coordinates on those, in level-w grid units */
  double det;    /* det Dψ(q) (see above) */
  double lo, hi; /* with ss_psi_mask_certify, for the two witnesses: an
                    enclosure of det Dψ(q) of the exact rule on the enclosed
                    net (else lo = hi = det) */
} ss_psi_mask_point;

/* det Dψ over the ring's regular vertices. */
typedef struct {
  size_t interior;        /* ring points inside a cone (support of size dim) */
  size_t judged;          /* of these, regular vertices where det Dψ was read */
  size_t unchecked;       /* of these, read with a neighbourhood not seen on
                             two consecutive levels (the deepest ones) */
  size_t positive;        /* of these, det of strict sign + */
  size_t negative;        /* ... of strict sign - */
  size_t flat;            /* ... with no sign (flat to rounding) */
  ss_psi_mask_point wpos; /* witness of the largest positive det (level -1
                             if none) */
  ss_psi_mask_point wneg; /* of the most negative det (level -1 if none) */
  size_t nmasks;          /* distinct (O, A) pairs whose masks were solved */
  size_t maxo;            /* the largest one-ring met */
  int enclosed;           /* 1 if ss_psi_mask_certify ran its proof */
  int proven;             /* 1 if the witnesses' enclosures have opposite
                             strict signs: psi's fold proven */
} ss_psi_mask_result;

/* det Dψ at the regular vertices of M's ring levels 0 .. M->nring - 2,
 * for the net x on the two-ring (M->n2 points, dim = M->dim coordinates
 * each, in the order of M's labels; e.g. the characteristic map's control
 * net, ss_charmap.h), pushed through the ring's rows.  M's rings must carry
 * coordinates (ss_local_ring.coord) and be of a vertex case (conical charts).
 * SS_EINPUT for a net of another size or a case that is not a vertex case,
 * SS_EINTERNAL if two cells of one cone disagree on its orientation,
 * SS_ENOMEM.  Nothing is printed. */
ss_status ss_psi_mask_judge(const ss_local *M, const double *x, size_t n,
                            ss_psi_mask_result *out, ss_error *err);

/* Called for each regular vertex read, with its sign (+1, -1; 0 flat). */
typedef void (*ss_psi_mask_fn)(const ss_psi_mask_point *pt, int sign, void *arg);

/* As ss_psi_mask_judge, calling fn(pt, sign, arg) for every vertex read. */
ss_status ss_psi_mask_each(const ss_local *M, const double *x, size_t n,
                           ss_psi_mask_fn fn, void *arg, ss_psi_mask_result *out,
                           ss_error *err);

/* Witness pt as a point of psi's domain (ss_psi.h): its chart, and the
 * two-ring tet holding it (barycentric coordinates, det along the tet's
 * edges from corner 0: |det E| times the chart's, E the edge vectors in
 * the chart, a small integer, so the product is exact) when there is one;
 * else cell SIZE_MAX, det along the chart's axes. */
ss_psi_point ss_psi_mask_point_of(const ss_local *M, const ss_psi_mask_point *pt);

/* As ss_psi_mask_judge on the midpoints of enclosure e of ψ's net (as for
 * ss_psi_certify), then the two witnesses proven ("Proof" above):
 * out->proven = 1 when their enclosures of det Dψ have opposite strict
 * signs.  SS_EINPUT for an enclosure that is not of finite intervals. */
ss_status ss_psi_mask_certify(const ss_local *M, const ss_psi_enclosure *e,
                              ss_psi_mask_result *out, ss_error *err);

SS_END_DECLS

#endif
