/* ss_jsr.h — joint spectral radius of a finite set of square matrices
 * (Levin-Levin smoothness test, issue 18; DESIGN section 2).
 *
 * For matrices Y_1..Y_m (n x n) the joint spectral radius is
 *   rho(Y) = lim_k max_{|w| = k} ||Y_{w_k} ... Y_{w_1}||^{1/k},
 * independent of the norm.  For every k
 *   max_{|w| = k} rho(Y_w)^{1/k}  <=  rho(Y)  <=  max_{|w| = k} ||Y_w||^{1/k}.
 *
 * Method (ss_jsr.c).
 *  - Brute force over the m + m^2 + ... + m^K words of length <= K, one
 *    length at a time (depth first to that length, each product formed from
 *    its prefix's; the prefixes are formed again for each length, about
 *    1 / (m - 1) more products, but a time limit then leaves complete
 *    lengths): the profiles rho_inf, rho_2 and the lower bound.  Eigenvalues are
 *    computed for Lyndon words only (rho(Y_w)^{1/|w|} is invariant under
 *    rotating w and under powers) and only when ||Y_w||_inf could beat the
 *    current lower bound.
 *  - Upper bound: Gripenberg's branch and bound (Linear Algebra Appl. 234,
 *    1996).  A word w gets the bound b(w) = min over its prefixes u of
 *    ||Y_u||^{1/|u|}; words with b(w) <= lower (1 + gap) are not extended,
 *    the others are extended up to length L.  The words not extended form a
 *    complete prefix set (every infinite word has one as a prefix), so every
 *    long product is a product of their prefix-minimising pieces and a
 *    bounded remainder, and submultiplicativity gives
 *      rho(Y) <= max over the unextended words of b(w).
 *    L grows by iterative deepening from K (each pass recomputes its shallow
 *    levels, about m / (m - 1) times the last level's work when the tree is
 *    bushy) until upper <= lower (1 + gap) or a limit stops it; a pass cut
 *    short by a limit is discarded.  With norm AUTO the first pass runs in the
 *    inf-norm (plain and weighted), the 2-norm and the ellipsoidal norm,
 *    and the rest keep the norm with the lowest bound.  In the inf-norm the pass may run
 * in a diagonally weighted inf-norm ||D^{-1} X D||_inf (D from |eigenvectors| of the
 * lower bound's product and its rotations; kept only when its first pass beats the plain
 * one): an exact similarity, so the bound stays valid.
 *  - Ellipsoidal norm (ss_jsr_ellipsoid.h): ||A||_P = ||L^T A L^{-T}||_2
 *    with L fitted by L-BFGS to minimise max_i ||L^T Y_i L^{-T}||_2.  Why:
 *    Gripenberg's bound in a norm ||.|| converges like C^{1/k}, C the
 *    distance of ||.|| from an extremal norm; the inf- and 2-norms are far
 *    from it on the tet/oct face (C^{1/k} ~ 1.3 at k = 8), a fitted
 *    ellipsoid much nearer (on the tet/oct edges it is extremal: upper =
 *    lower at k = 1).  The similar copies are enclosed in ball arithmetic
 *    with the exact double L (no inverse is trusted), and their enclosure
 *    radius enters the rounding bound below like a perturbation of the
 *    inputs, so the bound stays proven for the inputs.
 *  - Invariant polytope (ss_jsr_polytope.h, Guglielmi-Protasov): from the
 *    word of the lower bound, a polytope norm in which every Y_i has norm
 *    <= lower (1 + gap / 2) (up to rounding), proven in ball arithmetic;
 *    exact up to eps when it closes.  Norm POLYTOPE runs it first, then
 *    the branch and bound as AUTO; AUTO never runs it (on the tet/oct face
 *    and edges it does not close, and would take the branch and bound's
 *    time).  A vertex cap (20000) and the time limit stop it; then the
 *    branch and bound's bound stands.
 *
 * Certification.
 *  - Upper bounds (both norms): every product carries a rigorous bound on
 *    its rounding error (|fl(AB) - AB| <= gamma_n |A| |B|, gamma_n =
 *    n u / (1 - n u), propagated along the word, plus an absolute term for
 *    underflow); the inf-norm of a computed product is bounded with the
 *    error of its row sums, the 2-norm by ||P V||_2 / sigma_min(V) from
 *    LAPACK's singular vectors V with Gershgorin and rounding bounds; the
 *    k-th root is rounded up.  So `upper` is a proven upper bound of the
 *    JSR of the exact double inputs.
 *  - Lower bound: the word found in floating point is multiplied in arb
 *    ball arithmetic and its eigenvalues enclosed (Rump's method, simple then
 *    clustered eigenvalues; fallback |trace(P^j)| <= n rho(P)^j), giving a
 *    proven lower bound of rho(Y_w)^{1/|w|}.  If every enclosure fails,
 *    `lower` is the floating-point value and certified = 0.
 *
 * This header is the interface shared by the algorithms (ss_jsr.c) and the
 * Levin-Levin reduction that builds Y_i from a scheme's global rule. */
#ifndef SS_JSR_H
#define SS_JSR_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_progress.h"

SS_BEGIN_DECLS

typedef enum {
  SS_JSR_NORM_INF = 0,       /* maximum absolute row sum (the tet/oct paper's norm) */
  SS_JSR_NORM_2 = 1,         /* spectral norm (largest singular value) */
  SS_JSR_NORM_AUTO = 2,      /* branch and bound: the first pass runs in each
                                candidate (inf-norm, weighted inf-norm, 2-norm,
                                ellipsoidal norm for orders <= 64), the rest in
                                the one with the lowest bound */
  SS_JSR_NORM_ELLIPSOID = 3, /* ||x||_P = sqrt(x^T P x), P = L L^T fitted to
                               the Y_i (ss_jsr_ellipsoid.h): the 2-norm of
                               the similar L^T Y_i L^{-T}, enclosed */
  SS_JSR_NORM_POLYTOPE = 4   /* the invariant polytope (ss_jsr_polytope.h)
                               from the lower bound's word, eps = gap / 2,
                               within half the time limit; if it does not
                               close, the branch and bound as AUTO */
} ss_jsr_norm;

typedef struct {
  int depth;            /* K in 1..64: products of length 1..K for rho_k and the lower
                           bound (brute force over m^k words for k <= K) */
  double gap;           /* the branch and bound stops when upper <= lower * (1 +
                           gap) (relative; e.g. 1e-3) */
  ss_jsr_norm norm;     /* the norm of the branch and bound (AUTO: chosen by
                           its first pass; see ss_jsr_norm) */
  size_t max_nodes;     /* most products the branch and bound may form; 0: no
                           limit besides max_seconds */
  double max_seconds;   /* wall-clock limit of the whole call (<= 0: none): the
                           brute force from length 2 on (a length it cuts short
                           is left out of rho_inf, rho_2 and the upper bound:
                           see depth, cut_len), the ellipsoid's fit (its first
                           quarter), the polytope (half of what is left) and
                           the branch and bound */
  int max_depth;        /* longest word the branch and bound forms; 0: no limit
                           besides max_nodes / max_seconds (>= depth to matter) */
  int weighted;         /* 1: the inf-norm branch and bound may switch to a
                           diagonally weighted inf-norm (default); 0: never */
  int fit_words;        /* K in 1..5 (m^K <= 4096): the ellipsoidal norm is
                           fitted to the m^K products of length K instead of
                           the m maps (ss_jsr_ellipsoid_fit_words); 1 (default)
                           the maps.  The bound stays proven for any K */
  ss_progress progress; /* steps: "products for rho_k" (done of depth), "fitting
                           the norms", "branch and bound, word length" (done =
                           the length); {NULL, NULL}: none (default) */
} ss_jsr_opts;

/* Defaults: depth 8, gap 1e-3, norm AUTO, 10^7 nodes, no time or depth limit,
 * weighting allowed, the ellipsoid fitted to the maps (fit_words 1), no
 * progress callback. */
ss_jsr_opts ss_jsr_defaults(void);

typedef struct {
  int depth;            /* the length of rho_inf and rho_2: the complete word
                           lengths of the brute force, o->depth unless the time
                           limit stopped it (cut_len) */
  int cut_len;          /* 0, or the word length whose products the time limit
                           cut short (then depth = cut_len - 1 < o->depth) */
  size_t cut_words;     /* words of length cut_len judged before the limit (of
                           m^cut_len; 0 if cut_len is 0); they count for the
                           lower bound only */
  double *rho_inf;      /* rho_inf[k-1] = max_{|w| = k} ||Y_w||_inf^{1/k},
                           k = 1..depth (floating point, the plain inf-norm of
                           the inputs); o->depth entries allocated */
  double *rho_2;        /* the same in the 2-norm (LAPACK's singular values) */
  double lower;         /* lower bound: max over the words of length <= K (and the
                           Lyndon words the branch and bound met) of
                           rho(Y_w)^{1/|w|}, certified by ball arithmetic (see
                           certified) */
  int lower_len;        /* length of the word attaining `lower` */
  int *lower_word;      /* that word, indices 0..m-1, lower_len of them (first
                           factor applied first) */
  double upper;         /* proven upper bound on rho(Y): min of the rigorous
                           inf-norm profile (complete lengths) and the branch
                           and bound in o->norm */
  int converged;        /* 1 if upper <= lower * (1 + gap) */
  size_t nodes;         /* products formed by the branch and bound (including
                           ranking the weightings), not by the brute force */
  int bnb_depth;        /* word length of the last completed branch-and-bound pass
                           (0 if none completed) */
  int weighted;         /* 1 if that branch and bound used a diagonally weighted
                           inf-norm (ss_jsr.c: choose_scaling) */
  ss_jsr_norm norm;     /* the norm of the bound `upper` (INF, 2, ELLIPSOID or
                           POLYTOPE; AUTO resolved) */
  int polytope;         /* the invariant polytope: -1 not run, else its stop
                           code (ss_jsr_polytope_stop: 0 closed, 1 vertex cap,
                           2 time limit, 3 LP failed, 4 rho = 0) */
  size_t poly_vertices; /* its vertices at the end (0 if not run) */
  double poly_upper;    /* its proven bound when closed, else +inf */
  double seconds;       /* wall-clock time of the computation */
  int certified;        /* 1 if both bounds account for rounding: upper always
                           does; 0 only if the ball enclosure of the lower bound's
                           eigenvalue failed */
} ss_jsr_result;

/* Bounds on the joint spectral radius of the m matrices Y[0..m-1], each n x n,
 * row-major (Y[i][r * n + c]); o = NULL means ss_jsr_defaults().  The inputs
 * are not kept.  *out is filled; free its arrays with ss_jsr_result_clear (on
 * failure it is left cleared).  SS_EINPUT (message naming the problem) for
 * m < 1, n < 1, Y or a Y[i] NULL, a non-finite entry (matrix and entry
 * named), depth outside 1..64, gap negative or not finite, an unknown norm,
 * max_depth < 0, max_seconds NaN, more than 10^10 brute-force words
 * (m + ... + m^K), fit_words outside 1..5 or m^fit_words > 4096; SS_ENOMEM; SS_ENUMERIC
 * if LAPACK's eigenvalue or singular value computation fails, or if norm ELLIPSOID was
 * asked for and the fitted L could not be proven invertible (AUTO then just
 * skips that norm).  Cost: about m / (m - 1) times (m^{K+1} - m) / (m - 1)
 * products, a norm each for the (m^{K+1} - m) / (m - 1) words (an SVD for
 * rho_2), for the profiles (within max_seconds after length 1); the ellipsoid's fit, at
 * most 750 L-BFGS steps of O(m n^3) (within a quarter of max_seconds; with fit_words K >
 * 1 as many more of O(m^K n^3) on the products), and its enclosure, O(m n^3) in 128-bit
 * balls; then the branch and bound within max_nodes / max_seconds / max_depth (converged
 * = 0 when a limit stops it); memory O((K + L) n^2 + m n^2), about (26 + 2 m) n^2 more
 * for the fit. */
ss_status ss_jsr_compute(size_t m, size_t n, const double *const *Y, const ss_jsr_opts *o,
                         ss_jsr_result *out, ss_error *err);

/* Free the arrays of r and zero it; NULL-safe. */
void ss_jsr_result_clear(ss_jsr_result *r);

SS_END_DECLS

#endif
