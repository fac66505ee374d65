/* ss_charmap.h — the characteristic map on the two-ring and its regularity
 * under multilinear interpolation (DESIGN sections 1 and 5).
 *
 * The characteristic map's control net places two-ring point i at
 * (z1[i], .., zm[i]), the rows of the subdominant basis (ss_eig): eigenvectors
 * of lambda1..lambdam, or an orthonormal basis of their invariant subspace when
 * they repeat or cluster.  Any two bases differ by an invertible linear map,
 * which changes no Jacobian's strictness of sign, only possibly all signs at
 * once, so the verdict does not depend on the basis.  Scaling, which the
 * verdict ignores but the scaled Jacobian and pictures see: eigenvectors each
 * to unit Euclidean norm over the two-ring (each is unique up to scale and
 * sign), a Schur basis by one common factor to mean column norm 1 (another
 * orthonormal basis of the subspace differs by a rotation).  Either way the
 * map of a case is unique up to a similarity, so the minimum scaled Jacobian
 * does not change when a link is relabelled.
 *
 * Regularity: every cell of the two-ring (ss_local's cells) mapped by its
 * natural interpolant (ss_jac) has a Jacobian determinant of one strict sign,
 * and all cells the same sign (the cells are consistently oriented).  Verdict:
 *   fail       a folded cell (which cell, where), or cells of both signs; or,
 *              with no map, complex or defective subdominant eigenvalues;
 *   undecided  a hex still in doubt at the subdivision depth limit; or no map
 *              because the eigenvalue condition fails otherwise (e.g. lambda3
 *              not above |lambda4|: the subdominant subspace is not defined);
 *   pass       otherwise.
 * The minimum scaled Jacobian (ss_jac) over the cells, times the common sign
 * (the sign of most cells), measures the margin: positive on a pass, <= 0 when
 * some cell is inverted or degenerate. */
#ifndef SS_CHARMAP_H
#define SS_CHARMAP_H

#include "ss_eig.h"
#include "ss_jac.h"
#include "ss_local.h"

/* The characteristic map's control net on the two-ring. */
typedef struct {
  int dim;             /* coordinates per point: m = 3 (volume) or 2 (surface) */
  size_t n;            /* points: the two-ring, in the order of the labels */
  size_t n1;           /* the first n1 points are the one-ring */
  double *x;           /* n * dim coordinates, point by point */
  double lambda[3];    /* lambda1..lambdam (real parts) */
  size_t ncells;       /* cells of the two-ring (copied from ss_local) */
  ss_cell_type *ctype; /* ncells cell types */
  size_t *corner;      /* ncells * SS_MAXCELLVERTS corner point indices */
  ss_jac_result *jac;  /* ncells per-cell results (after ss_charmap_regularity) */
} ss_charmap;

/* The regularity verdict. */
typedef struct {
  ss_verdict verdict;         /* pass, fail or undecided, with the reason */
  double min_scaled_jacobian; /* see above; NaN when there is no map */
  int sign;                   /* +1 or -1: the orientation of most cells; 0: none */
  size_t worst_cell;          /* the cell giving the minimum (or the failing one);
                                 SIZE_MAX when there is no map */
  size_t npositive, nnegative, nfolded, nundecided; /* cells by ss_jac verdict */
  int depth; /* the hex subdivision depth limit used */
} ss_regularity;

/* The characteristic map of case M with eigenstructure e (which must carry a
 * subdominant basis).  *out is owned by the caller (ss_charmap_free).
 * SS_EINPUT if e has no basis or sizes disagree; SS_ENOMEM. */
ss_status ss_charmap_new(const ss_local *M, const ss_eig *e, ss_charmap **out,
                         ss_error *err);

void ss_charmap_free(ss_charmap *cm);

/* Judge every cell (filling cm->jac) and summarise into *r, with hex
 * subdivision to maxdepth levels (SS_JAC_DEPTH by default).  Cannot fail. */
void ss_charmap_regularity(ss_charmap *cm, int maxdepth, ss_regularity *r);

/* The whole second half of the verdict for one case: when e allows a map,
 * build it (*cm, caller frees; may be NULL on return) and judge it; otherwise
 * the verdict without a map (fail for complex or defective subdominant
 * eigenvalues, undecided for any other failure of the eigenvalue condition).
 * SS_ENOMEM only. */
ss_status ss_charmap_analyze(const ss_local *M, const ss_eig *e, int maxdepth,
                             ss_charmap **cm, ss_regularity *r, ss_error *err);

#endif
