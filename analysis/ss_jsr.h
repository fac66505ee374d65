/* ss_jsr.h — joint spectral radius of a finite set of square matrices
 * (Levin-Levin smoothness test, issue 18; DESIGN section 2).
 *
 * For matrices Y_1..Y_m (n x n) the joint spectral radius is
 *   rho(Y) = lim_k max_{|w| = k} ||Y_{w_k} ... Y_{w_1}||^{1/k},
 * independent of the norm.  For every k
 *   max_{|w| = k} rho(Y_w)^{1/k}  <=  rho(Y)  <=  max_{|w| = k} ||Y_w||^{1/k},
 * so products of length <= K give a lower bound (spectral radii) and the
 * k-th norm profile rho_k an upper bound for each k.  A branch and bound over
 * products (Gripenberg 1996) tightens the upper bound without enumerating
 * all m^K words: a word w whose bound max(||Y_w||^{1/|w|}, ...) is already below
 * the current lower bound + gap is not extended.
 *
 * This header is the interface shared by the algorithms (ss_jsr.c) and the
 * Levin-Levin reduction that builds Y_i from a scheme's global rule. */
#ifndef SS_JSR_H
#define SS_JSR_H

#include <stddef.h>

#include "ss_error.h"

typedef enum {
  SS_JSR_NORM_INF = 0, /* maximum absolute row sum (the tet/oct paper's norm) */
  SS_JSR_NORM_2 = 1    /* spectral norm (largest singular value) */
} ss_jsr_norm;

typedef struct {
  int depth;          /* K >= 1: products of length 1..K for rho_k and the lower
                         bound (brute force over m^k words for k <= K) */
  double gap;         /* the branch and bound stops when upper <= lower * (1 +
                         gap) (relative; e.g. 1e-3) */
  ss_jsr_norm norm;   /* the norm of the branch and bound's upper bound */
  size_t max_nodes;   /* most products the branch and bound may form; 0: no
                         limit besides max_seconds */
  double max_seconds; /* wall-clock limit of the branch and bound; <= 0: none */
  int max_depth;      /* longest word the branch and bound forms; 0: no limit
                         besides max_nodes / max_seconds (>= depth to matter) */
} ss_jsr_opts;

/* Defaults: depth 8, gap 1e-3, inf-norm, 10^7 nodes, no time or depth limit. */
ss_jsr_opts ss_jsr_defaults(void);

typedef struct {
  int depth;       /* K, the length of rho_inf and rho_2 */
  double *rho_inf; /* rho_inf[k-1] = max_{|w| = k} ||Y_w||_inf^{1/k}, k = 1..K */
  double *rho_2;   /* the same in the 2-norm */
  double lower;    /* certified lower bound: max over the words of length <= K
                      (and those the branch and bound met) of rho(Y_w)^{1/|w|} */
  int lower_len;   /* length of the word attaining `lower` */
  int *lower_word; /* that word, indices 0..m-1, lower_len of them (first
                      factor applied first) */
  double upper;    /* certified upper bound on rho(Y) */
  int converged;   /* 1 if upper <= lower * (1 + gap) */
  size_t nodes;    /* products formed by the branch and bound */
  int bnb_depth;   /* word length of the last completed branch-and-bound pass
                      (0 if none completed) */
  double seconds;  /* wall-clock time of the computation */
  int certified;   /* 1 if both bounds account for rounding (ball arithmetic
                      or a rigorous floating-point error bound) */
} ss_jsr_result;

/* Bounds on the joint spectral radius of the m matrices Y[0..m-1], each n x n,
 * row-major (Y[i][r * n + c]).  The inputs are not kept.  *out is filled; free
 * its arrays with ss_jsr_result_clear.  SS_EINPUT for m < 1, n < 1 or a
 * non-finite entry; SS_ENOMEM; SS_ENUMERIC if an eigenvalue or singular value
 * computation fails.  Cost: m^K products for rho_k, then the branch and bound
 * within max_nodes / max_seconds (converged = 0 when a limit stops it). */
ss_status ss_jsr_compute(size_t m, size_t n, const double *const *Y, const ss_jsr_opts *o,
                         ss_jsr_result *out, ss_error *err);

/* Free the arrays of r and zero it; NULL-safe. */
void ss_jsr_result_clear(ss_jsr_result *r);

#endif
