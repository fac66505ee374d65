/* ss_jsr_ellipsoid.h — an ellipsoidal norm for the joint spectral radius
 * branch and bound (ss_jsr.c, norm SS_JSR_NORM_ELLIPSOID).  Internal to
 * analysis/.
 *
 * For an invertible L the norm ||x||_P = sqrt(x^T P x), P = L L^T, has the
 * induced norm ||A||_P = ||L^T A L^{-T}||_2, so the branch and bound in the
 * 2-norm of the similar matrices Z_i = L^T Y_i L^{-T} is the branch and bound
 * in the norm ||.||_P of the Y_i; a similarity leaves the joint spectral
 * radius unchanged.  L is fitted to make max_i ||Z_i||_2 small (a nearly
 * extremal norm makes the bound converge fast: an extremal norm gives the
 * joint spectral radius at word length 1). */
#ifndef SS_JSR_ELLIPSOID_H
#define SS_JSR_ELLIPSOID_H

#include <stddef.h>

#include "ss_error.h"

/* Fit L (n x n, row-major, written) to minimise max_i ||L^T Y_i L^{-T}||_2
 * over the m matrices Y[i] (n x n, row-major).  The maximum of the squared
 * singular values sigma^2 = the generalised eigenvalues of
 * (Y_i^T P Y_i, P) is smoothed to (c / t) log sum exp(t sigma^2 / c) (all
 * singular values of all Y_i; c the maximum at the start of a stage) and
 * minimised over L by L-BFGS for t = 20, 100, 500, 2000, 10000 (at most 150
 * iterations each); the gradient of a generalised eigenvalue lambda with
 * P-unit eigenvector u is (Y u)(Y u)^T - lambda u u^T in P, times 2 L in L.
 * Starts from L = I (warm = 0) or from the L given (warm = 1); returns the
 * best L met (by the true maximum), so never worse than the start.  Stops early at the
 * wall-clock time `deadline` (ss_clock_wall seconds; <= 0: none).  Deterministic
 * without a deadline. SS_ENOMEM; SS_ENUMERIC if LAPACK fails at the start (later failures
 * end the fit with the best L so far).  Cost O(m n^3) per step. */
ss_status ss_jsr_ellipsoid_fit(size_t m, size_t n, const double *const *Y,
                               double deadline, int warm, double *L);

/* Fit L to the products of length K (1..5) instead of the maps: minimise
 * max_{|w| = K} ||L^T Y_w L^{-T}||_2 (the K-th root of which bounds the
 * joint spectral radius) over the m^K products Y_w = Y_{w_K} ... Y_{w_1}.
 * Why: one quadratic norm cannot be near extremal for every single map when
 * the growth is in how they combine (the tet/oct face: K = 1 leaves 5 %, the
 * optimal ellipsoid on products of length 4 about 2.4 %); the norm that is
 * best for the products is what the branch and bound needs at long words.
 * K = 1 is ss_jsr_ellipsoid_fit from L = I, bit for bit.  K > 1: the fit on
 * the maps first (until the first quarter of the time to `deadline`, if
 * any), then on the products from that L (warm start: the single-map norm
 * is a good start, and a product step costs m^{K-1} times a map step).
 * Whatever L comes out, the bound it gives stays proven: the branch and
 * bound encloses the similar maps L^T Y_i L^{-T} (ss_jsr_ellipsoid_similar).
 * SS_ENOMEM; SS_ENUMERIC as ss_jsr_ellipsoid_fit.  Memory (m^K + 3) n^2
 * more than that fit; cost O(m^K n^3) per step. */
ss_status ss_jsr_ellipsoid_fit_words(size_t m, size_t n, const double *const *Y, int K,
                                     double deadline, double *L);

/* The similar matrices Z_i = L^T Y_i L^{-T} for the exact double L, enclosed
 * in ball arithmetic (128 bits; L^{-T} by arb's verified solve) and rounded
 * to doubles: Z (m n^2, row-major, Z + i n^2 the i-th), delta[i] (m) a
 * rigorous upper bound of ||exact Z_i - stored Z_i||_inf, and *cw = 1 if
 * moreover every entry is within 3u |stored entry| (u the unit roundoff; the
 * componentwise rounding bound of ss_jsr.c then holds), else 0.  Returns 1,
 * or 0 if the solve could not prove L invertible (or memory ran out). */
int ss_jsr_ellipsoid_similar(size_t m, size_t n, const double *const *Y, const double *L,
                             double *Z, double *delta, int *cw);

#endif
