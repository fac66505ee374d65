/* ss_levin.h — the Levin-Levin reduction: sub-patch subdivision matrices S_i
 * read from a scheme's global rule, and the blocks Y_i whose joint spectral
 * radius decides smoothness across a face or along an edge (tet/oct paper,
 * appendix A; Levin and Levin 2003; issue 18).
 *
 * Patches.  A patch Q is a piece of the centre on level j; one subdivision
 * step splits it into m scaled, translated copies Q_i on level j + 1:
 *   face (two tets sharing a face, tet/oct split): in the face's affine frame
 *     (u, v) = (x_1, x_2), x_i the barycentric coordinates of the face star in
 *     units of level j, Q is the unit square [a, a+1] x [b, b+1]: the tet/tet
 *     triangle (lower left) and the oct/oct triangle (upper right) of figure
 *     10; Q_i are the four unit squares of level j + 1 with corners
 *     2 (a, b) + (s, t), s, t in {0, 1} (i = s + 2 t);
 *   edge of valence n: the chart's edge coordinate x_n runs from -2^j to 2^j
 *     along the edge, edge vertices at even x_n; Q is the segment [t, t + 2],
 *     Q_1 and Q_2 its halves, corners 2 t and 2 t + 2 on level j + 1.
 * Points are named by exact chart coordinates relative to the patch corner
 * (as ss_local names them relative to the centre), so the point with relative
 * coordinates x near Q on level j and near Q_i on level j + 1 is "the same
 * point" of the support.
 *
 * Support.  P = the level-j points whose basis functions do not vanish on
 * (closed) Q: the smallest set containing Q's corners such that every row of
 * the rule for a point of Q_i's copy of P (i = 1..m) reads only points of P.
 * (The vertices of Q on level j + k are the union of the Q_i's vertices on
 * level j + k, so this closure is the union of the supports N^k(vertices of Q
 * on level j + k), N = the columns of the rows.)  Then
 *   S_i[r][c] = R(point P_r of Q_i on level j + 1, point P_c of Q on level j),
 * square, rows summing to 1 (checked: SS_EINTERNAL otherwise).  Every row
 * read must be far from the boundary of the refined star (the barycentric
 * distance of its point to the star's outer faces, which hold the base edges
 * and vertices, at least 2 (reach + 1) grid steps), and the matrices read on
 * levels (j, j + 1) must equal those read on (j + 1, j + 2) for a patch placed
 * likewise (the stationary regime); j grows until both hold.
 *
 * Reduction.  V (n x r) spans the subspace the smoothness order needs:
 *   face (C^2): the quadratic polynomials in the points' positions (the
 *     star's chart mapped to space, ss_star_coord_position), r = 10: 1, x, y,
 *     z and their 6 products, whose restrictions to level j + 1 are, up to
 *     lower degree, the same polynomials at half scale: S_i's eigenvalues
 *     on span(V) are 1, 1/2 x3, 1/4 x6.  If these are not invariant (the
 *     box-spline rules: the chart's mirror-symmetric embedding of the two
 *     tets need not be the affine structure the rules keep), the paper's
 *     own construction: the eigenvectors of S_1 for 1, 1/2 x3, 1/4 x6
 *     (checked: these must be its 10 dominant eigenvalues);
 *   edge: the eigenvectors of S_1 for its four dominant eigenvalues, which
 *     must be 1, lambda_1, lambda_1, 1/2 (the paper's "1, lambda1, lambda1,
 *     1/2, ..."): constants, the two maps around the edge, the map along it.
 * span(V) must be invariant under EVERY S_i: ||Q_2^T S_i V|| / ||S_i V|| <=
 * tol (SS_EINTERNAL otherwise, naming i and the defect).  With the QR
 * factorisation V = [Q_1 Q_2] [R; 0] take W = [V Q_2]; then W^{-1} has last
 * n - r rows Q_2^T, and
 *   W^{-1} S_i W = [Theta_i  C_i; 0  Y_i],   Y_i = Q_2^T S_i Q_2.
 * Why only the norm depends on the complement: any other complement basis is
 * W' = W [I H; 0 G] (columns of Q_2 G plus combinations of V, G invertible),
 * and then Y'_i = G^{-1} Y_i G with the SAME G for every i, so every product
 * Y'_w = G^{-1} Y_w G: the spectral radii of products, hence the joint
 * spectral radius and the lower bounds, are unchanged, and each norm
 * profile rho_k changes at most by cond(G)^{1/k}, which tends to 1.  A change
 * of V's basis (V -> V B) does not change Y_i at all.  Relabelling the
 * support (a permutation P) maps S_i -> P S_i P^T, V -> P V, and the QR
 * factorisation of P V gives another orthonormal complement: Y_i -> G^T Y_i G
 * with G orthogonal, so the 2-norm profile and the spectral radii are
 * unchanged and the inf-norm profile changes by at most n^{1/k}.
 *
 * The threshold: 1/4 for the face (C^2: the JSR must lie below the sixfold
 * quadratic eigenvalue); for an edge lambda_3, the third subdominant
 * eigenvalue of S_1 = min(lambda_1, 1/2) (the paper: "the joint-spectral
 * radius ... must be less than lambda3"). */
#ifndef SS_LEVIN_H
#define SS_LEVIN_H

#include "ss_api.h"
#include "ss_jsr.h"
#include "ss_local.h"
#include "ss_verdict.h"

SS_BEGIN_DECLS

#define SS_LEVIN_MAXMAPS 4 /* sub-patches at most (the face) */

/* The sub-patch matrices of one case and their reduction. */
typedef struct {
  ss_case_kind kind;           /* SS_CASE_FACE or SS_CASE_EDGE */
  int level;                   /* j: S_i map level j to level j + 1 */
  size_t m;                    /* sub-patches: 4 (face) or 2 (edge) */
  size_t n;                    /* support points: rows and columns of S_i */
  double *S[SS_LEVIN_MAXMAPS]; /* m matrices n x n, row-major */
  ss_star_coord *label;        /* n chart coordinates relative to the patch
                                  corner (level units), the order of S_i */
  double *pos;                 /* n x 3 positions of the labels in space
                                  (relative to the corner, level units) */
  size_t r;                    /* dimension of the invariant subspace (10 or 4) */
  double *V;                   /* n x r, row-major: its basis */
  double *Y[SS_LEVIN_MAXMAPS]; /* m blocks (n - r) x (n - r), row-major */
  double defect;               /* max_i ||Q_2^T S_i V||_max / ||S_i V||_max */
  double theta[16];            /* the r eigenvalues of S_1 on span(V),
                                  descending (real parts) */
  double threshold;            /* 1/4 (face) or lambda_3 (edge) */
  double lambda1;              /* edge: lambda_1 (double eigenvalue); face: 1/2 */
  const char *basis;           /* how V was formed: "quadratics" or
                                  "eigenvectors" (static string) */
} ss_levin;

/* Relative tolerance of the invariance check. */
#define SS_LEVIN_TOL 1e-9

/* Build the sub-patch matrices of case c (kind SS_CASE_FACE or SS_CASE_EDGE,
 * c->n the valence, c->diag the major diagonals) for scheme s, and reduce them
 * (method above).  *out is owned by the caller (ss_levin_free).  SS_EINPUT if
 * the scheme has no such case (ss_case_star) or another kind is asked for;
 * SS_EINTERNAL if a matrix is not square with unit row sums, no stationary
 * level is found, the edge spectrum is not 1, lambda, lambda, 1/2, or the
 * subspace is not invariant under every S_i; SS_ENUMERIC if LAPACK fails;
 * SS_ENOMEM.  Cost: refining the star about j + 2 times (O(8^(j+2)) cells). */
ss_status ss_levin_new(const ss_scheme *s, const ss_case *c, ss_levin **out,
                       ss_error *err);

/* The reduction alone: Y_i = Q_2^T S_i Q_2 for the m matrices S[i] (n x n)
 * and the subspace spanned by V (n x r, row-major, full column rank), with
 * Q_2 an orthonormal basis of range(V)'s complement.  Y[i] receive new arrays
 * (n - r)^2 each (caller frees).  *defect receives max_i ||Q_2^T S_i V||_max /
 * ||S_i V||_max.  SS_EINPUT if r >= n or r = 0; SS_EINTERNAL if V is rank
 * deficient (|R_kk| <= 1e-10 max |R_ll|) or *defect > tol; SS_ENUMERIC if
 * LAPACK fails; SS_ENOMEM.  Cost O(m n^3). */
ss_status ss_levin_reduce(size_t m, size_t n, const double *const *S, const double *V,
                          size_t r, double tol, double **Y, double *defect,
                          ss_error *err);

/* The joint spectral radius test of L with the bounds r of its Y_i
 * (ss_jsr_compute): pass when r->upper < L->threshold, fail when r->lower >=
 * L->threshold, else undecided; judged on the JSR bounds (SS_ON_JSR), and
 * certified when decided with r->certified bounds.  What is proven is the
 * comparison with L->threshold as computed: 1/4 for the face, and for an
 * edge min(lambda_1, 1/2) with lambda_1 from LAPACK in double precision. */
void ss_levin_verdict(const ss_levin *L, const ss_jsr_result *r, ss_verdict *v);

/* Free; NULL is a no-op. */
void ss_levin_free(ss_levin *L);

SS_END_DECLS

#endif
