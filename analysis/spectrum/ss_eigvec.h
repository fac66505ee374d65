/* ss_eigvec.h — the leading right and left eigenvectors of a local
 * subdivision matrix, and the limit masks they give (issue 21).
 *
 * For S (n x n) with S r = lambda r and l^T S = lambda l^T: repeated
 * subdivision of control points x gives S^m x = sum_j lambda_j^m r_j (l_j^T x)
 * when S is diagonalisable and the pairs are biorthonormal (L^T R = I).  With
 * lambda_0 = 1 simple and r_0 = 1 (rows sum to 1), the limit of the centre is
 * l_0^T x: l_0 is the limit-position mask.  The left eigenvectors of the
 * subdominant eigenvalues lambda_1..lambda_m (m = 3 in volume cases, 2 on
 * surfaces) are the tangent (derivative) masks: (S^m x - (l_0^T x) 1) /
 * lambda_1^m tends to the projection onto their eigenspace.
 *
 * Method.  One LAPACK dgeev of the whole S with left and right eigenvectors
 * (O(n^3); meant for export, not for sweeps: ss_eig solves only blocks).
 * Order: by decreasing modulus; moduli equal within the relative tolerance
 * tol form a run, ordered real first, then larger real part, then larger
 * imaginary part (the order of ss_eig).  The k leading are kept; a conjugate
 * pair or a group of equal eigenvalues (below) cut by k is kept whole, so
 * v->k may exceed the k asked for.
 *
 * Normalisation.  Every right vector is scaled to maximum modulus 1 with
 * that entry real and positive (the first such entry), so r_0 = 1 exactly
 * for a partition of unity.  Eigenvalues within tol of each other (relative,
 * complex distance) form a group; a group's left vectors L are replaced by
 * L (R^T L)^{-1}, so that L^T R = I (biorthonormal; for a single eigenvalue,
 * l / (l^T r)).  A tied group's right basis is LAPACK's, as arbitrary as any
 * basis of the eigenspace; only the product R L^T (the projection) is
 * intrinsic.  A group whose L^T R is numerically singular (1 / |G^{-1}|_1
 * below 1e-10 g |L| |R|, column 2-norms: a Jordan block, where left and right
 * eigenvectors are orthogonal) is left as LAPACK gives it and flagged.
 *
 * Complex eigenvalues: the vectors are stored as real and imaginary parts;
 * l is the row vector with l^T S = lambda l^T (no conjugation). */
#ifndef SS_EIGVEC_H
#define SS_EIGVEC_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_error.h"

SS_BEGIN_DECLS

/* The k leading eigenpairs of S. */
typedef struct {
  size_t n;         /* rows of S (points) */
  int k;            /* eigenvalues kept */
  double *re, *im;  /* k eigenvalues, in the order above */
  int *group;       /* k: group of equal eigenvalues (0 = the leading one) */
  int *biorth;      /* k: 1 if its group was made biorthonormal (L^T R = I),
                       0 if the group is defective (see above) */
  double *right_re; /* n x k column-major: right eigenvectors (real parts) */
  double *right_im; /* n x k column-major: imaginary parts (0 for real ones) */
  double *left_re;  /* n x k column-major: left eigenvectors (real parts) */
  double *left_im;  /* n x k column-major: imaginary parts */
  int complex_any;  /* 1 if a kept eigenvalue is not real */
} ss_eigvec;

/* The k leading eigenpairs of S (n x n, row-major), 1 <= k <= n, with
 * eigenvalues equal within the relative tolerance tol (0 < tol < 0.1) grouped
 * and normalised as above.  *out is owned by the caller (ss_eigvec_free).
 * SS_EINPUT for bad arguments, SS_ENUMERIC if LAPACK fails, SS_ENOMEM. */
ss_status ss_eigvec_new(const double *S, size_t n, int k, double tol, ss_eigvec **out,
                        ss_error *err);

void ss_eigvec_free(ss_eigvec *v);

/* Whether the limit masks are defined: lambda_0 = 1 (within tol), simple,
 * real, and its right vector constant (r_0 = 1 within tol); then column 0 of
 * left_re is the limit-position mask. */
int ss_eigvec_has_limit(const ss_eigvec *v, double tol);

SS_END_DECLS

#endif
