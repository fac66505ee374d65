/* ss_charmap.h — the characteristic map's control net and its regularity,
 * judged on the map's ring (DESIGN sections 1, 5 and 10).
 *
 * The control net places two-ring point i at (z1[i], .., zm[i]), the rows of
 * the subdominant basis (ss_eig): eigenvectors of lambda1..lambdam, or a basis
 * of their invariant subspace when they repeat or cluster.  Any two bases
 * differ by an invertible linear map G, which changes no Jacobian's
 * strictness of sign, only possibly all signs at once, so verdicts do not
 * depend on the basis.  The scaled Jacobian does, so the net is normalised:
 * translated to the centroid of the ring's points (the corners of ring level
 * 0's cells, below) and mapped by C^(-1/2), C their covariance matrix, which
 * makes that point cloud isotropic (covariance I).  For another basis, X G,
 * this gives the same net up to an orthogonal map (C^(1/2) G = U P, polar
 * decomposition: (X - m) G (G^T C G)^(-1/2) = (X - m) C^(-1/2) U), and
 * scaled Jacobians are invariant under orthogonal maps up to their common
 * sign, which the orientation below absorbs: the minimum scaled Jacobian is
 * a property of the case, not of LAPACK's basis.
 *
 * Where regularity is judged.  psi is self-similar, psi(lambda .) = Lambda
 * psi on the cells around p, so psi is regular iff it is regular on its ring
 * (ss_local.h): ring level r = the cells of grid level w + 1 + r inside the
 * cells around p on level w and outside those on level w + 1, their control
 * points pushed from the two-ring by r + 1 applications of the global rule
 * (ring level 0 is the two-ring's cells that do not touch p, as S maps them).
 * The multilinear interpolant of ring level r converges to psi as r grows.
 * The two-ring's cells that touch p are not part of it: their interpolant's
 * Jacobian at the centre corner is not a value of psi's, so a fold there
 * decides nothing; such cells are counted (centre_corner_folds) and do not
 * fail the verdict.
 *
 * Verdict, levels r = 0, 1, .., L - 1 (opts.ring_levels = L):
 *   pass       at the first level whose cells are all of one strict sign;
 *   fail       a fold or cells of both orientations at the last level, which
 *              persists: the fraction of ring cells that fold or are inverted
 *              has not fallen below opts.shrink times the previous level's
 *              (a fold of psi over a region keeps its fraction as the cells
 *              shrink, i.e. its cell count grows about 8x per level; a
 *              Jacobian that vanishes on a curve leaves a chain of bad cells
 *              whose count only doubles: fraction x 1/4); also, with no map,
 *              complex or defective subdominant eigenvalues;
 *   undecided  a fold that shrinks from level to level (the mark of a
 *              Jacobian that vanishes on a curve or surface: neither pass nor
 *              fail by this test), cells still in doubt (hex subdivision
 *              depth) or flat to rounding at the last level, or no map because
 *              the eigenvalue condition fails otherwise.
 * The minimum scaled Jacobian (ss_jac) is over the deciding (else the last)
 * level's ring cells, times their common sign. */
#ifndef SS_CHARMAP_H
#define SS_CHARMAP_H

#include "ss_api.h"
#include "ss_eig.h"
#include "ss_exact.h"
#include "ss_jac.h"
#include "ss_local.h"

SS_BEGIN_DECLS

/* The characteristic map's control net on the two-ring. */
typedef struct {
  int dim;             /* coordinates per point: m = 3 (volume) or 2 (surface) */
  size_t n;            /* points: the two-ring, in the order of the labels */
  size_t n1;           /* the first n1 points are the one-ring */
  double *x;           /* n * dim coordinates, point by point, normalised */
  double centre[3];    /* psi(p) in the normalised coordinates: the image of
                          the origin of the basis' coordinates (psi(p) = 0
                          there, since psi(lambda .) = Lambda psi) */
  double lambda[3];    /* lambda1..lambdam (real parts) */
  size_t ncells;       /* cells of the two-ring (copied from ss_local) */
  ss_cell_type *ctype; /* ncells cell types */
  size_t *corner;      /* ncells * SS_MAXCELLVERTS corner point indices */
  ss_jac_result *jac;  /* ncells per-cell results of the two-ring's cells
                          (after ss_charmap_regularity; for pictures) */
  /* The ring level that decided the verdict (the last judged if none did),
   * kept by ss_charmap_regularity so that pictures and files can show the
   * cells the verdict and its minimum scaled Jacobian come from: */
  int ring_level;           /* its number; -1 before a regularity test */
  size_t ring_n;            /* its points */
  double *ring_x;           /* ring_n * dim coordinates, normalised as x */
  size_t ring_ncells;       /* its cells */
  ss_cell_type *ring_ctype; /* ring_ncells cell types */
  size_t *ring_corner;      /* ring_ncells * SS_MAXCELLVERTS corners, indices
                               into ring_x */
  ss_jac_result *ring_jac;  /* ring_ncells per-cell results */
} ss_charmap;

/* Thread CPU seconds of the regularity test's stages, added to (never
 * reset) by ss_charmap_judge and ss_certify_verdicts when the caller hands
 * one in (ss_charmap_opts.times): for benchmarks (bench_pipeline --phases),
 * which read where a case's time goes without a profiler.  Timing reads
 * clocks only: no result depends on it. */
typedef struct {
  double map;       /* ss_charmap_new: the map's net and its normalisation */
  double jacobian;  /* the Jacobian test on the two-ring's cells and the ring
                       levels M already has */
  double deepen;    /* ss_local_ring_deepen: refining the deeper ring levels
                       of a link that folds on the first ones */
  double deep_jac;  /* the Jacobian test on those deeper levels */
  double symmetry;  /* ss_charmap_symmetry */
  double injective; /* ss_charmap_injectivity (ss_certify_verdicts) */
  long deep;        /* cases that needed deeper ring levels */
  /* the exact path (ss_certify), with certify only: */
  double certify;       /* ss_certify whole: the exact spectrum and the proofs */
  ss_exact_times exact; /* the exact spectrum's stages */
  double cert_level[SS_LOCAL_MAXRING]; /* ss_charmap_certify: the interval
                                          net pushed to ring level l and its
                                          cells' Jacobians in intervals */
  double cert_sym;                     /* ss_charmap_certify: psi o sigma = psi proven */
} ss_charmap_times;

/* Options of the regularity test. */
typedef struct {
  int depth;               /* hex subdivision depth limit of ss_jac (SS_JAC_DEPTH) */
  int ring_levels;         /* ring levels judged at most, 1..SS_LOCAL_MAXRING (3) */
  double shrink;           /* a fold shrinks when its fraction of the ring's cells
                              falls below shrink times the previous level's (0.5: a
                              fold over a region keeps its fraction, one along a curve
                              falls 4x per level) */
  ss_charmap_times *times; /* NULL (the default), or where to add the stages'
                              thread CPU times (above); borrowed */
  int exact_lazy;          /* nonzero: the certified path's exact spectrum
                              proves a factor irreducible only where a verdict
                              needs it (ss_exact_opts.lazy; the same verdicts,
                              not always the same printed factors); 0, the
                              default: fmpz_poly_factor's factors */
  int similarity;          /* nonzero, with exact_lazy: a rational S is first
                              tried by the verified similarity (ss_simil.h),
                              which proves passes only; the exact path runs
                              where it decides nothing, and *x (ss_certify) is
                              then NULL on its passes.  0, the default: the
                              exact path alone */
} ss_charmap_opts;

/* One ring level's cells by verdict. */
typedef struct {
  size_t cells;               /* ring cells of the level */
  size_t positive, negative;  /* of one strict sign (ss_jac) */
  size_t folded;              /* whose sign changes inside (or vanishes) */
  size_t undecided;           /* in doubt (hex depth limit, rounding) */
  size_t degenerate;          /* flat to rounding: no sign */
  int sign;                   /* +1 or -1: the orientation of most cells */
  size_t inverted;            /* cells of one strict sign opposite to it */
  double min_scaled_jacobian; /* oriented minimum over the cells (ss_jac) */
  size_t worst_cell;          /* the cell giving it */
  double bad_fraction;        /* (folded + inverted) / cells: what must not
                                 shrink for a fold to persist */
} ss_ring_level;

/* What ss_charmap_symmetry found. */
typedef struct {
  int tested;      /* symmetries of the case that commute with S */
  int found;       /* 1 if one of them, sigma, has psi o sigma = psi */
  int order;       /* with found: the order N of sigma */
  size_t moved;    /* with found: two-ring points sigma moves */
  double distance; /* with found: ||M_sigma - I||_F, against the gap below */
  double gap;      /* 2 sin(pi / N): the least ||M - I|| of a matrix M != I
                      with M^N = I, half of which separates the two cases */
  int reverses;    /* with found: 1 if sigma reverses orientation; then
                      det Dpsi(sigma x) = -det Dpsi(x), so psi is not regular
                      either (its Jacobian changes sign or vanishes) */
  int index;       /* with found: sigma's number among the case's symmetries
                      (ss_charmap_sym_perm rebuilds it) */
  char what[160];  /* with found: sigma, in words */
} ss_charmap_sym;

/* The regularity verdict. */
typedef struct {
  ss_verdict verdict;         /* pass, fail or undecided, with the reason;
                                 certified when ss_charmap_certify proves it;
                                 judged on the net */
  double min_scaled_jacobian; /* see above; NaN when there is no map */
  int sign;                   /* +1 or -1: the orientation of the ring; 0: none */
  size_t worst_cell;          /* in the deciding level's ring cells; SIZE_MAX when
                                 there is no map */
  size_t npositive, nnegative, nfolded, nundecided; /* the deciding (else the
                                                       last) level's ring cells */
  size_t ndegenerate;                               /* of those, flat to rounding */
  size_t ninverted;           /* of those, of one strict sign opposite to most */
  size_t centre_corner_folds; /* two-ring cells around p not of the ring's
                                 sign (folded, inverted, in doubt or flat):
                                 reported, never a failure */
  int ring_level;             /* the level that decided; the last judged if none
                                 did; -1 without a map */
  int nlevels;                /* ring levels judged */
  ss_ring_level level[SS_LOCAL_MAXRING]; /* each judged level */
  int depth;                             /* the hex subdivision depth limit used */
  double shrink;                         /* the shrink ratio used */
  ss_charmap_sym sym; /* the symmetry test (ss_charmap_judge): when it finds
                         psi o sigma = psi the verdict is fail */
  int want_levels;    /* > nlevels when the verdict would be judged on
                         deeper ring levels than M has (ss_charmap_judge
                         builds them) */
} ss_regularity;

/* A cell's scaled-Jacobian measure in the map's orientation sign (+1 or
 * -1, ss_regularity.sign): for a cell of that sign its smallest corner value
 * times sign (its quality, in (0, 1]); for a cell of one strict sign opposite
 * to it, minus its quality; for a folded or undecided cell the smallest
 * oriented corner value; NaN for a degenerate cell (no sign).  The minimum
 * scaled Jacobian of a verdict is the minimum of this over the level's
 * cells, so a picture or file that shows it per cell agrees with analyze. */
double ss_charmap_cell_measure(const ss_jac_result *j, int sign);

/* Defaults: depth SS_JAC_DEPTH, 3 ring levels, shrink 0.5, no timing. */
ss_charmap_opts ss_charmap_defaults(void);

/* The characteristic map of case M with eigenstructure e (which must carry a
 * subdominant basis), normalised as above.  *out is owned by the caller
 * (ss_charmap_free).  SS_EINPUT if e has no basis or sizes disagree;
 * SS_ENUMERIC if the basis is degenerate on the ring; SS_ENOMEM. */
ss_status ss_charmap_new(const ss_local *M, const ss_eig *e, ss_charmap **out,
                         ss_error *err);

void ss_charmap_free(ss_charmap *cm);

/* Judge the map on M's ring levels (at most o->ring_levels of them; M is the
 * case cm was made from, read during the call only) and the two-ring's cells
 * (filling cm->jac), summarised into *r.  SS_ENOMEM only. */
ss_status ss_charmap_regularity(ss_charmap *cm, const ss_local *M,
                                const ss_charmap_opts *o, ss_regularity *r,
                                ss_error *err);

/* The whole second half of the verdict for one case: when e allows a map,
 * build it (*cm, caller frees; may be NULL on return) and judge it; otherwise
 * the verdict without a map (fail for complex or defective subdominant
 * eigenvalues, undecided for any other failure of the eigenvalue condition).
 * SS_ENOMEM only. */
ss_status ss_charmap_analyze(const ss_local *M, const ss_eig *e, const ss_charmap_opts *o,
                             ss_charmap **cm, ss_regularity *r, ss_error *err);

/* As ss_charmap_analyze, and when the verdict wants deeper ring levels than M
 * has, rebuild M's ring deeper (ss_local_ring_deepen, for scheme s and case c
 * that M was made from) and judge again; then test the symmetries of the case
 * (ss_charmap_symmetry): psi o sigma = psi fails the verdict, whatever the
 * ring showed (kept in the levels).  Errors: those of the calls. */
ss_status ss_charmap_judge(const ss_scheme *s, const ss_case *c, ss_local *M,
                           const ss_eig *e, const ss_charmap_opts *o, ss_charmap **cm,
                           ss_regularity *r, ss_error *err);

/* ---- symmetries the map does not see (ss_charmap_sym.c) ---- */

/* Whether the characteristic map identifies points that a symmetry of the
 * case exchanges.  A symmetry sigma (a link automorphism for a vertex, the
 * dihedral symmetries and the flip of the edge for an edge point, the rays'
 * dihedral group on a surface, the swaps fixing the centre of a face) acts on
 * the two-ring by a permutation P of its labels; if P S = S P, it maps the
 * subdominant invariant subspace to itself, P X = X M_sigma, with M_sigma of
 * finite order N.  psi o sigma = psi exactly when M_sigma = I; otherwise
 * ||M_sigma - I|| >= max over its eigenvalues w != 1 of |w - 1| >= 2 sin(pi/N),
 * so comparing with half that gap is decided by no tolerance of rounding
 * size.  Found: psi is not injective (two distinct points, i and sigma(i), have
 * one image), and not regular: if sigma reverses orientation, det Dpsi(sigma x)
 * = -det Dpsi(x) changes sign on the connected ring; if it keeps it, it is a
 * rotation of the link sphere (a periodic homeomorphism of S^2 keeping its
 * orientation fixes two points), its fixed rays cross the ring, and there
 * Dpsi (Dsigma - I) = 0 with Dsigma != I makes Dpsi singular (psi is C^1 on
 * the ring).  Reflections are preferred when both kinds are found.  c is the case M was
 * made from (for a vertex: the same link, in the labelling M used).  SS_ENOMEM; SS_EINPUT
 * for a malformed case. */
ss_status ss_charmap_symmetry(const ss_charmap *cm, const ss_local *M, const ss_case *c,
                              ss_charmap_sym *out, ss_error *err);

/* The permutation P of the two-ring (P[i] = the label index of sigma(label
 * i)) of the symmetry y found by ss_charmap_symmetry for the same M and c.
 * P receives M->n2 entries.  SS_EINPUT if y found none or does not fit. */
ss_status ss_charmap_sym_perm(const ss_local *M, const ss_case *c,
                              const ss_charmap_sym *y, size_t *P, ss_error *err);

/* The case's symmetry group on the two-ring: *ng permutations (*perms, ng *
 * M->n2 entries, caller frees; (*perms)[g * n2 + i] the label index of
 * sigma_g(label i)), the identity first, then every candidate of
 * ss_charmap_symmetry that maps the two-ring (a vertex: all the link's
 * automorphisms; an edge: its dihedral symmetries and flips).  Whether they
 * commute with S is not checked here.  SS_ENOMEM; SS_EINPUT for a malformed
 * case. */
ss_status ss_charmap_sym_group(const ss_local *M, const ss_case *c, size_t **perms,
                               size_t *ng, ss_error *err);

/* ---- injectivity (ss_charmap_inj.c) ---- */

/* The injectivity verdict. */
typedef struct {
  ss_verdict verdict; /* pass, fail or undecided, with the reason; certified
                         when proven (ss_charmap_certify: only a failure by
                         psi o sigma = psi is); judged on the net */
  int degree;         /* winding number of the two-ring's boundary image about
                         psi(p) (ss_inject); 0 when not computed */
  size_t overlaps;    /* pairs of ring cells (the two-ring's cells that do not
                         touch p) sharing no vertex whose images meet */
} ss_charmap_inj;

/* Whether the map is one-to-one, beyond regular: fail when the symmetry test
 * of reg found psi o sigma = psi; otherwise the PL test of ss_inject.h: the
 * degree of the image of the two-ring's boundary about psi(p) must be +-1 and
 * no two ring cells that share no vertex may have meeting images (the cells
 * around p are left out: their folds at the centre corner decide nothing).
 * Undecided when psi(p) lies on the boundary image.  SS_ENOMEM; SS_EINPUT
 * when ss_inject refuses the cells (a defect, reported). */
ss_status ss_charmap_injectivity(const ss_charmap *cm, const ss_regularity *reg,
                                 ss_charmap_inj *out, ss_error *err);

/* ---- certified verdicts (ss_charmap_cert.c) ---- */

/* Push an interval net (plo <= net <= phi, R->nprev points of dim
 * coordinates) through ring level R into olo, ohi (R->nv points), each
 * weight replaced by the enclosure of the rational of denominator at most
 * maxden it stands for (ss_exact_rational_enclose), in midpoint-radius
 * arithmetic with an a-priori rounding bound (ss_charmap_cert.c): the result
 * holds the exact rule's net for every net inside the input.  maxden < 0
 * (algebraic weights, ss_fourier.h): each weight w stands for
 * w +- 2^-40 max(1, |w|) instead.  An input box that is not finite gives the
 * whole line in the rows that read it.  0, or -1 for a weight that is no
 * such rational (or dim outside 1..3). */
int ss_charmap_push_interval(const ss_local_ring *R, const double *plo, const double *phi,
                             int dim, long maxden, double *olo, double *ohi);

/* Prove the verdicts r (from ss_charmap_judge) and inj (ss_charmap_injectivity)
 * of case c, or mark them unproven, with an enclosure lo <= X <= hi (n2 x m,
 * column-major, the rows in S's order) of a basis of the subdominant
 * invariant subspace (ss_exact_basis): the basis may differ from the one the
 * double path used, which changes no sign.  The ring's nets are pushed from
 * X by ss_charmap_push_interval (enclosures: midpoint and radius with an
 * a-priori rounding bound), every weight of the rule the rational of
 * denominator <= maxden it rounds to (ss_exact_rational; maxden < 0: its
 * window, and no symmetry proven), and each ring cell is judged by
 * ss_jac_cell_interval_sign (ss_jac_hex_midrad first, then arb's di_t):
 *   pass       proven when every cell of the deciding level is proven of one
 *              strict sign (the same for all);
 *   fail       proven when psi o sigma = psi is (P S = S P exactly, and the
 *              enclosure excludes M_sigma != I by the gap of ss_charmap_sym),
 *              or when the persistence rule holds for the proven counts: the
 *              proven bad cells of the last level against all cells of the
 *              level before that are bad or unproven;
 *   otherwise  the verdict becomes undecided, "not certified: why (double
 *              precision: the verdict)".
 * Injectivity is proven only in the symmetry case (the PL test is exact on
 * the double net, not on X).  Sets r->certified and inj->certified.
 * SS_ENOMEM only. */
ss_status ss_charmap_certify(const ss_local *M, const ss_case *c, const double *lo,
                             const double *hi, int m, long maxden,
                             const ss_charmap_opts *o, ss_regularity *r,
                             ss_charmap_inj *inj, ss_error *err);

SS_END_DECLS

#endif
