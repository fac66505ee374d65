/* ss_psi.h — the characteristic map judged on itself, not on its control
 * net: its polynomial pieces on the ring (DESIGN section 5, "Eigenstructure
 * and verdicts").
 *
 * For a scheme that is the tricubic B-spline on regular grids and whose rule
 * reads only the cells at a fine vertex's birth element (the limit
 * evaluator's schemes: mlca, ccsolid; ss_limit.h), psi on the cells around
 * the centre p is the limit of the two-ring's cells (a hex mesh) with the
 * characteristic map's net as their points: the two-ring is by definition
 * every point whose basis function reaches those cells, and a reach-1 rule
 * refines a cell's patch from the patch alone.  psi's ring is each cell
 * around p minus its octant [0,1/2]^3 at p (ss_local.h, "the ring").
 *
 * Pieces.  The ring is cut into boxes (the octants of the cells around p,
 * halved again down to depth maxdepth); a box whose patch is the 3x3x3
 * block of a grid carries psi exactly as the tricubic B-spline of its 64
 * points (ss_limit_pieces), and det Dpsi there is a polynomial of degree
 * (8, 8, 8) whose Bernstein coefficients bound it (ss_psi_bernstein): one
 * strict sign proves the sign on the box, two exact values of opposite signs
 * prove a fold.  Boxes along a spoke (an edge from p of valence other than
 * 4) never become regular: at maxdepth they are left uncovered, a tube
 * round each spoke of relative volume about 2^-2 maxdepth per spoke.
 *
 * Verdict on psi (ss_psi_result.verdict, judged on SS_ON_PSI):
 *   fail       det Dpsi takes both strict signs on the ring: a folded piece,
 *              or pieces proven of opposite signs; the two witnesses are
 *              points of cells around p (their parameters) with enclosures
 *              of det Dpsi there.  The ring is connected, so psi is then
 *              neither regular nor injective (a continuous injective map of
 *              a connected open set has one local degree, the sign of det
 *              Dpsi wherever it is not 0);
 *   pass       every box is a piece proven of one and the same strict sign:
 *              psi is regular on the ring, hence everywhere but p (it is
 *              self-similar);
 *   undecided  otherwise (uncovered tubes, pieces still in doubt): covered
 *              says how much of the ring is proven of one sign.
 * The tubes (ss_psi_spoke.h): when boxes are left uncovered and no piece
 * folds, each spoke is classified by the sign of its coefficient det[a' |
 * B] (evidence in double precision at sample points, not a proof), and
 *   a spoke whose s changes sign                  -> fail (psi folds across
 *                                                    it; witnesses: two probe
 *                                                    points near it);
 *   a spoke of one sign opposite to the ring's    -> fail (witnesses: a
 *                                                    proven piece's corner
 *                                                    and a probe point);
 *   a degenerate spoke (s = 0 relatively, no sign -> fail of regularity,
 *   change)                                         "degenerate on spoke a"
 *                                                    (Reif's condition needs
 *                                                    det Dpsi != 0; not a
 *                                                    fold: injectivity is
 *                                                    left to the net);
 *   every spoke of the ring's sign, every piece   -> pass "by evidence in the
 *   proven of it, and det Dpsi by ss_limit_eval      tubes", never proven;
 *   of that sign at every sample
 *   otherwise the verdict stays undecided, the spokes named in the reason.
 *
 * Proof (ss_psi_certify).  Given an enclosure of the true net (the exact
 * path's subdominant basis, ss_exact_basis) the same traversal runs on the
 * enclosure's midpoints in doubles, and then a decided verdict is proven or
 * left unproven (never reversed):
 *   fail   the two witnesses' pieces are reached again with the enclosure
 *          carried through every refinement step (ss_limit_pieces_enclosed:
 *          the rule's weights as the exact path's rationals, interval
 *          arithmetic), and det Dpsi at each witness (a corner coefficient
 *          of its piece's Bernstein form: an exact value) is enclosed; two
 *          enclosures of opposite strict signs prove the fold.  Failing
 *          that, a folded piece's interval test (ss_psi_piece_sign_interval)
 *          proves it if it finds the fold again;
 *   pass   every piece's interval test proves the same strict sign (with no
 *          box left uncovered: in practice the regular vertex only, until
 *          the spokes are decided).
 * The proven verdict has certified = 1 and its witnesses carry the
 * enclosures.  What is proven is a statement about psi of the rule with
 * those rational weights (the matrix every certified statement is about,
 * ss_exact.h), in the basis the enclosure holds (det Dpsi scales by det G
 * under a change of basis G: signs compare, values do not).  Without an
 * enclosure (ss_psi_judge) nothing is proven: the verdict is a statement
 * about psi in double precision (and the Bernstein test's double path
 * decides values only beyond its flat threshold).

 * ss_psi_apply combines it with the control net's verdict (ss_charmap): a
 * psi verdict that decides (with certify: a proven one) replaces it; else
 * the net's stays, but a failure of the net that psi does not show is no
 * longer proven. */
#ifndef SS_PSI_H
#define SS_PSI_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_local.h"
#include "ss_psi_spoke.h"
#include "ss_scheme.h"
#include "ss_verdict.h"

SS_BEGIN_DECLS

#define SS_PSI_BOX_DEPTH   4 /* default: boxes of the ring down to side 1/16 */
#define SS_PSI_PIECE_DEPTH 4 /* default Bernstein subdivision depth of a piece */

/* Options of the test on psi. */
typedef struct {
  int maxdepth;    /* boxes of the ring down to side 2^-maxdepth of a cell
                      around p, 1..8 (SS_PSI_BOX_DEPTH) */
  int piece_depth; /* subdivision depth of one piece's Bernstein test, 0..8
                      (SS_PSI_PIECE_DEPTH) */
  int tubes;       /* nonzero: with the enclosure (ss_psi_certify), prove the
                      tubes round the spokes too (ss_psi_tube.h): a ring of
                      one sign on its pieces becomes a proven pass; a few
                      seconds per case (default 0) */
} ss_psi_opts;

/* A point of psi's domain with det Dpsi there. */
typedef struct {
  size_t cell;   /* the two-ring cell holding it (an index into M's cells,
                    one of the cells around p); SIZE_MAX: none given (a
                    chart point inside an octahedron) */
  double at[3];  /* its parameters in the cell's vertex order: hexes (u, v,
                    w) (ss_cx.h: u along corner 0 -> 1, v along 0 -> 3, w
                    along 0 -> 4); tets the barycentric coordinates of
                    corners 1, 2, 3 */
  double det[2]; /* an enclosure [lo, hi] of det Dpsi there, derivatives in
                    those parameters (without a cell: along the chart's
                    axes, level-w grid units, oriented as space); double
                    path: lo = hi = the value */
  int chart;     /* 1 if cone and x are given (tangent-mask witnesses,
                    ss_psi_mask.h), else 0 */
  int cone[3];   /* the link vertices (0-based) of its chart cone */
  double x[3];   /* its conical coordinates on them, level-w grid units */
} ss_psi_point;

/* What the test on psi found. */
typedef struct {
  int ran;                 /* 1 if psi was judged on its pieces; 0 if this case
                              has none (why says so): the scheme is not a
                              limit evaluator's, or the case is not a vertex */
  char why[160];           /* with ran = 0: the reason */
  ss_verdict verdict;      /* pass, fail, undecided, judged on psi */
  double covered;          /* share of the ring's parameter volume in pieces
                              proven of the ring's sign */
  double opposite;         /* share in pieces proven of the other sign */
  double doubtful;         /* share in pieces folded or in doubt */
  double uncovered;        /* share in boxes left without a piece at maxdepth */
  size_t pieces;           /* pieces judged */
  size_t npositive;        /* of these, proven det > 0 (in the cells' parameters) */
  size_t nnegative;        /* proven det < 0 */
  size_t nfolded;          /* two exact values of opposite signs inside */
  size_t nundecided;       /* no proof either way at piece_depth */
  size_t nuncovered;       /* boxes left without a piece at maxdepth */
  int enclosed;            /* 1 if the proof passes ran (ss_psi_certify) */
  int spokes;              /* 1 if the spokes were classified (ss_psi_spoke.h:
                              boxes left uncovered and no fold on the pieces) */
  size_t nspokes;          /* spokes (edges from p of valence other than 4) */
  size_t nspoke_one;       /* of these, s of one sign */
  size_t nspoke_change;    /* s changes sign */
  size_t nspoke_deg;       /* s = 0 (relatively) somewhere */
  int spoke_vertex;        /* the link vertex (0-based) of the spoke that
                              decided a failure, else -1 */
  int degenerate;          /* 1 if psi fails by a degenerate spoke (not a fold:
                              injectivity is not decided by it) */
  char spoke_why[200];     /* spokes not classified: why (else empty) */
  int by_spokes;           /* 1 if judged by the spokes alone (a tet/oct vertex,
                              ss_psi_tet.h: no pieces, the ring's sign from the
                              net's verdict) */
  int by_masks;            /* 1 if decided at the ring's regular vertices by
                              tangent masks (a tet/oct vertex, ss_psi_mask.h) */
  size_t nregular;         /* regular vertices read by tangent masks */
  size_t nregular_pos;     /* of these, det Dpsi > 0 */
  size_t nregular_neg;     /* det Dpsi < 0 */
  int sign;                /* the ring's sign: of the larger proven volume (+1
                              positive first when equal); 0 when none is proven */
  int nwitness;            /* 2 when failing, else 0 */
  ss_psi_point witness[2]; /* with fail: det Dpsi of opposite strict signs */
  int maxdepth;            /* the options used */
  int piece_depth;
  double seconds;          /* thread CPU time of the test */
  double prove_seconds;    /* of which the proof passes (ss_psi_certify) */
  double spoke_seconds;    /* of which the spokes' classification */
  int tubes;               /* 1 if the tubes' proofs ran (ss_psi_opts.tubes, the
                              enclosure, a ring of one sign on its pieces) */
  size_t ntubes;           /* uncovered boxes whose tube round a spoke was
                              proven of the ring's sign (ss_psi_tube.h; with
                              the enclosure only) */
  int tube_layers;         /* the most layers one of them judged directly
                              before its tail bound */
  char tube_why[240];      /* the first tube not proven: where and why (else
                              empty) */
  int tube_fold_layer;     /* a fail proven in a tube (the witnesses both in
                              one layer of it, ss_psi_tube.h "A fold"): that
                              layer; else -1 */
  int inject;              /* with a proven pass: 1 psi injective, -1 psi not
                              injective (both proven, ss_psi_inject.h: the
                              winding number on the star's boundary), 0 not
                              decided or not run */
  int degree;              /* that winding number (0 when not computed) */
  size_t boundary_squares; /* boundary squares it was computed on */
  char inject_why[200];    /* the reason, decided or not (empty: not run) */
} ss_psi_result;

/* If a spoke of sk is degenerate (ss_psi_spoke.h), r fails regularity by
 * the first one: "degenerate on spoke a (valence n): ..." with its counts
 * of `points` (the word for what was sampled) and `source` (how they were
 * read, a phrase ending in ", ", or ""); r->spoke_vertex and r->degenerate
 * set.  Returns 1 then, else 0 (r untouched). */
int ss_psi_fail_degenerate(ss_psi_result *r, const ss_psi_spokes *sk, const char *points,
                           const char *source);

/* What the exact path knows of psi's net (ss_psi_certify). */
typedef struct {
  const double *lo; /* M->n2 x 3, row by row: lo <= the true net */
  const double *hi; /* the true net <= hi */
  long maxden;      /* the rule's weights are the rationals of denominator
                       <= maxden nearest to its doubles (ss_exact_rational;
                       ss_exact_opts.maxden) */
} ss_psi_enclosure;

/* maxdepth SS_PSI_BOX_DEPTH, piece_depth SS_PSI_PIECE_DEPTH. */
ss_psi_opts ss_psi_defaults(void);

/* Judge psi of vertex case M under scheme s (M from ss_local for s) with the
 * net x (M->n2 points, 3 coordinates each, row by row: the characteristic
 * map's, in any basis of the subdominant subspace).  A case without pieces
 * is not an error: out->ran = 0.  SS_EINPUT for options out of range or no
 * net; SS_ENOMEM; the errors of a refinement step. */
ss_status ss_psi_judge(const ss_scheme *s, const ss_local *M, const double *x,
                       const ss_psi_opts *o, ss_psi_result *out, ss_error *err);

/* As ss_psi_judge on the net of enclosure e's midpoints, then the proof
 * passes (above): out->verdict.certified = 1 for a proven verdict.
 * SS_EINPUT also for an enclosure with a bound that is not finite or lo >
 * hi; SS_ENUMERIC when a weight of the rule is not a rational the exact path
 * accepts (ss_exact_rational). */
ss_status ss_psi_certify(const ss_scheme *s, const ss_local *M, const ss_psi_enclosure *e,
                         const ss_psi_opts *o, ss_psi_result *out, ss_error *err);

/* Combine the verdict on psi r (ran) into the regularity and injectivity
 * verdicts of the control net, reg and inj.  A verdict on psi that decides —
 * any pass or fail without certify; with certify (nonzero) only a proven one
 * — replaces the net's: psi fails by a degenerate spoke -> regularity fails,
 * judged on psi (injectivity is left); psi folds -> both fail, judged on psi, the
 * witnesses in the reason (a regularity failure already about psi, psi o
 * sigma = psi, is kept with the witnesses added, and proven if psi's is);
 * psi passes -> regularity passes judged on psi, and injectivity is
 * psi's where its winding number on the star's boundary decided it (r->inject,
 * proven: ss_psi_inject.h), else left to the net (a regular psi may still
 * overlap itself).  Otherwise the net's verdicts stay
 * with psi's finding added to their reason, and a regularity failure of the
 * net (not one already judged on psi) is no longer proven: without certify
 * it loses certified, with certify it becomes undecided
 * (ss_verdict_unproven). */
void ss_psi_apply(const ss_psi_result *r, int certify, ss_verdict *reg, ss_verdict *inj);

SS_END_DECLS

#endif
