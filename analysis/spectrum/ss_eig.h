/* ss_eig.h — eigenstructure of a local subdivision matrix and the eigenvalue
 * condition (DESIGN sections 1 and 5).
 *
 * S = [A 0; B C] (ss_local.h), so its spectrum is that of the one-ring block A
 * together with that of the outer block C.  C is itself reducible: ordered by
 * the strongly connected components of its sparsity graph (Tarjan's algorithm)
 * it is block lower triangular, and its spectrum is the union of its diagonal
 * blocks' spectra.  A is solved by LAPACK dgeevx (balanced; reciprocal
 * condition numbers of eigenvalues and eigenvectors), each outer block of more
 * than one point likewise, 1 x 1 blocks by reading the diagonal.  Condition
 * numbers are those of the block holding the eigenvalue.
 *
 * Multiplicities: eigenvalues within a relative tolerance `tol` of each other
 * (|a - b| <= tol * max(|a|, |b|)) form one group; an imaginary part below
 * tol * |lambda| (a real multiple eigenvalue split by rounding into a
 * conjugate pair) is set to 0.  The default, 1e-6, joins
 * the copies of an exact tie that rounding splits (by about 1e-8 for a Jordan
 * block of size 2) and keeps apart genuine near-ties (relative gaps of 1e-3 are
 * met in practice).  It is printed with every verdict.
 *
 * Rounding floor.  A tolerance finer than the eigenvalues' own rounding error
 * would let rounding decide the verdict (lambda0 computed as 1 + 2e-16 "is not
 * 1" at 1e-16).  Each computed eigenvalue carries the bound of LAPACK's
 * Users' Guide (section 4.8, "error bounds for the nonsymmetric eigenproblem"),
 *   err_i = p(b) eps ||B|| / s_i,
 * where B is its diagonal block as balanced by dgeevx (ABNRM), s_i the
 * reciprocal condition number (RCONDE) and p(b) = 4 b: the block size b for
 * LAPACK's "modestly growing function", times 4 for the rounding already in
 * S's entries, which the rule's arithmetic leaves a few units in the last
 * place from the exact weights (1 x 1 blocks: err = 4 eps |s_jj|).  The bound
 * is approximate, not rigorous (`--certify` is): the test suite checks it
 * against the exact spectra (ss_exact) of every vertex with k <= 9 and edge
 * of valence 3..10 of two schemes, where it holds with a margin of 3.
 * The first-order bound fails for a multiple eigenvalue (its copies'
 * individual s_i are near 0; computed copies of a Jordan block of size 2
 * differ by about sqrt(eps) ||B||, which the default tolerance joins): an
 * eigenvalue whose bound reaches its nearest neighbour is a cluster member,
 * and its bound is capped at sqrt(p(b) eps) ||B||, the spread of a double
 * eigenvalue (ss_eigval.cluster).
 * The floor is the largest relative error any comparison of the verdict can
 * meet: err_0 (lambda0 = 1), (err_0 + err_1) / |lambda0| (simple),
 * err_i / |lambda_i| (real, i = 1..m) and (err_m + err_m+1) / lambda_m (the
 * gap).  The tolerance
 * used is max(requested, floor); when the floor raised it, a verdict that
 * would have passed at the requested tolerance but fails at the raised one is
 * SS_UNDECIDED ("rounding decides"), never a fail.  Both are printed.
 *
 * The subdominant basis (the control net of the characteristic map): the
 * leading m eigenvalues after lambda0 (m = 3 in volume cases, 2 on surfaces).
 * When they are distinct by more than `cluster` (relative), the right
 * eigenvectors of A; otherwise (repeated or clustered) an orthonormal basis of
 * their invariant subspace from the real Schur form (dgees, reordered by
 * dtrsen).  Either is extended from the one-ring to the two-ring by solving
 * B X1 + C X2 = X2 T block by block.  If a leading eigenvalue belongs to the
 * outer block, the basis comes from a Schur form of the whole S. */
#ifndef SS_EIG_H
#define SS_EIG_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_progress.h"
#include "ss_verdict.h"

SS_BEGIN_DECLS

/* One eigenvalue of S. */
typedef struct {
  double re, im;  /* the eigenvalue */
  double rcond;   /* reciprocal condition number in its block (1 for 1 x 1) */
  int block;      /* 0: the one-ring block; b > 0: outer block number b */
  int group;      /* index of its group of equal eigenvalues (0 = leading) */
  int mult;       /* size of that group */
  double err;     /* bound on its rounding error (absolute; see "Rounding floor") */
  double cluster; /* the same for a member of a cluster (see there) */
} ss_eigval;

/* Options of an analysis. */
typedef struct {
  double tol;           /* relative tolerance for equal eigenvalues (default 1e-6) */
  double cluster;       /* relative gap below which the subdominant eigenvalues are
                           treated as a cluster (default 1e-2) */
  int dim;              /* 3: volume condition (lambda1..3); 2: surface (lambda1..2) */
  int basis;            /* nonzero: compute the subdominant basis */
  int force;            /* nonzero: compute it even when the eigenvalue condition
                           fails, as long as lambda1..m are real and positive (for
                           pictures of what is not a characteristic map; a tie
                           lambda_m = lambda_m+1 is cut arbitrarily) */
  ss_progress progress; /* steps "eigen-solve, block" i of the blocks (the
                           one-ring block first); default silent */
} ss_eig_opts;

/* Eigenstructure of one local matrix. */
typedef struct {
  size_t n;               /* eigenvalues (= rows of S) */
  ss_eigval *val;         /* all n, by decreasing modulus; ties: real first, then
                             larger real part first, then larger imaginary part */
  int ngroups;            /* groups of equal eigenvalues */
  size_t nblocks;         /* diagonal blocks of the outer part */
  size_t largest_block;   /* size of the largest of them */
  ss_verdict cond;        /* the eigenvalue condition */
  double tol;             /* the tolerance used: max(tol_requested, rounding) */
  double tol_requested;   /* the tolerance asked for (ss_eig_opts.tol) */
  double rounding;        /* the rounding floor of the verdict's comparisons */
  int m;                  /* subdominant eigenvalues (3 or 2) */
  double *basis;          /* NULL, or n x m column-major: the subdominant basis */
  const char *basis_kind; /* "eigenvectors", "schur" or "" */
  double *T;              /* with the basis: m x m column-major, S basis = basis T
                             (diagonal for eigenvectors, upper quasi-triangular
                             for a Schur basis); else NULL */
  int defective;          /* with the basis: 1 if a repeated subdominant
                             eigenvalue has fewer eigenvectors than copies (a
                             Jordan block in T, judged with tol), else 0 */
} ss_eig;

/* Default options for dimension dim (2 or 3). */
ss_eig_opts ss_eig_defaults(int dim);

/* Analyse S (n x n, row-major) whose leading n1 x n1 block A is invariant
 * (S[i][j] = 0 for i < n1 <= j).  *out is owned by the caller (ss_eig_free).
 * SS_EINPUT if S is not of that form or opts are out of range; SS_ENUMERIC if
 * LAPACK fails; SS_ENOMEM.  Allocates a workspace for this S and frees it
 * again: ss_eig_new_ws with a fresh ss_eig_workspace_new(0). */
ss_status ss_eig_new(const double *S, size_t n, size_t n1, const ss_eig_opts *opts,
                     ss_eig **out, ss_error *err);

/* Scratch memory of ss_eig_new_ws (GSL's _alloc discipline): the dense
 * block solves' LAPACK workspace (dgeevx's work arrays, eigenvectors,
 * balancing), the one-ring block's copy and eigenvectors, the per-eigenvalue
 * scratch and the memo of distinct outer blocks, kept between calls so that
 * a sweep's thread analyses case after case in the same memory.  One
 * workspace serves one call at a time (one per thread).  Its sizes are
 * capacities: n rows of S and b, the largest dense block (the one-ring block
 * or an outer block).  A matrix beyond them makes the workspace grow (to the
 * largest n and b seen; it never shrinks), so any workspace serves any S and
 * the results do not depend on its history: bit for bit ss_eig_new's.  Not
 * held here: the result (ss_eig), the sparse copy of S with its strongly
 * connected components, and the Schur solves of the subdominant basis (only
 * when the leading eigenvalues cluster).  Opaque: its fields (ss_eig.c) hold
 * LAPACK's integer type, which this header does not expose. */
typedef struct ss_eig_workspace ss_eig_workspace;

/* A workspace for matrices of up to nmax rows (any block structure), or an
 * empty one (nmax = 0) that grows at its first use.  NULL when out of
 * memory.  Free with ss_eig_workspace_free. */
ss_eig_workspace *ss_eig_workspace_new(size_t nmax);

/* Free; NULL is a no-op. */
void ss_eig_workspace_free(ss_eig_workspace *w);

/* The capacities of w: rows of S (*n) and largest dense block (*b) that it
 * serves without growing. */
void ss_eig_workspace_size(const ss_eig_workspace *w, size_t *n, size_t *b);

/* ss_eig_new with the scratch memory taken from w (grown when S needs more;
 * SS_ENOMEM if it cannot grow, w then still valid and usable).  The result
 * is the same as ss_eig_new's bit for bit, whatever w served before.  w
 * NULL: as ss_eig_new. */
ss_status ss_eig_new_ws(const double *S, size_t n, size_t n1, const ss_eig_opts *opts,
                        ss_eig_workspace *w, ss_eig **out, ss_error *err);

void ss_eig_free(ss_eig *e);

/* Eigenvalues of a dense n x n matrix (row-major) by one LAPACK dgeev call,
 * with right eigenvectors: the reference the benchmark compares against.
 * re, im receive n values each (unsorted).  SS_ENUMERIC, SS_ENOMEM. */
ss_status ss_eig_dense(const double *S, size_t n, double *re, double *im, ss_error *err);

SS_END_DECLS

#endif
