/* ss_jsr_ws.h — internal to the jsr room: the workspace of the walks over
 * words that ss_jsr_compute (ss_jsr.c) drives.  The products along a word and
 * their rigorous norms live in ss_jsr_products.c; the walks (brute force,
 * branch and bound) and the choice of the norm they bound in
 * (ss_jsr_search.c).  Not installed. */
#ifndef SS_JSR_WS_H
#define SS_JSR_WS_H

#include <float.h>
#include <math.h>
#include <stddef.h>

#include "ss_dense.h"
#include "ss_jsr.h"

/* The depth-first walk over words.  Level k (0-based) of the stacks holds the
 * word's product of length k + 1, Y_{w_{k+1}} ... Y_{w_1}, formed as
 * Y_{w_{k+1}} times level k - 1: one n x n product per node.  All buffers are
 * allocated once (grown by ss_jsr_ws_reserve when the branch and bound deepens). */
typedef struct {
  size_t m, n;            /* number and order of the matrices */
  const double *const *Y; /* the matrices in use: the (normalised) inputs or
                             their weighted copies in zbuf (not owned) */
  int cap;                /* levels the stacks hold */
  int *word;              /* cap: the current word, word[k] in 0..m-1 */
  double *prod;           /* cap * n * n: the computed products, row-major */
  double *err_inf;        /* cap: rigorous bound on ||exact - computed||_inf */
  double *nhat_inf;       /* cap: ||computed product||_inf (floating point) */
  double *nf_up;          /* cap: rigorous bound on ||computed product||_F */
  double *cap2;           /* cap: min(sqrt(||P^||_1 ||P^||_inf), ||P^||_F) >=
                             ||P^||_2 >= rho(P^) (floating point) */
  double *err_2;          /* cap: rigorous bound on ||exact - computed||_2 */
  double *qabs;           /* cap * n * n: products of |Y_i| along the word,
                             for the componentwise error bound (ss_jsr_ws_push) */
  int *qvalid;            /* cap: 1 if that level of qabs is formed */
  double *bnd;            /* cap: the branch and bound's value of the prefix */
  double *a;              /* n * n: scratch copy for LAPACK (destroyed) */
  double *wr, *wi, *sv;   /* n each: eigenvalues and singular values */
  double *sb;             /* n: dgesvd's superdiagonal scratch, column sums */
  double *ynorm;          /* m: rigorous upper bounds of ||Y_i||_inf (of the
                             exact matrices the stored Y_i approximate) */
  double *delta;          /* m: rigorous bound on ||exact - stored Y_i||_inf:
                             0 for the inputs, rounding of the scaled copies */
  double *zbuf;           /* m * n * n: the diagonally scaled copies */
  const double **zptr;    /* m: pointers into zbuf */
  double *d;              /* 2 n: a candidate weighting and the sum of the
                             rotations' candidates (ss_jsr_choose_scaling) */
  double *vl;             /* n * n: dgeev's eigenvectors */
  double *v, *t2;         /* n * n each: the 2-norm certificate's V and A V */
  double *y2, *yf;        /* m each: rigorous ||Y_i + Delta||_2 and ||Y_i||_F */
  double *ebuf;           /* m * n * n: the ellipsoidal copies L^T Y_i L^{-T}
                             (ss_jsr_ellipsoid.h), NULL until fitted */
  const double **eptr;    /* m: pointers into ebuf */
  double *edelta;         /* m: rigorous ||exact - stored||_inf of those */
  int ecw;                /* 1 if their entries are within 3u (componentwise) */
  int cw_ok;              /* 1 if the active copies are within 3u of the exact
                             matrices entrywise (ws_err_componentwise) */
  double gam;             /* gamma_n = n u / (1 - n u), u the unit roundoff */
  double tiny;            /* n^2 times the smallest subnormal: the absolute
                             rounding error of a row sum of a product
                             through underflow */
  double lower;           /* best rho(Y_w)^{1/|w|} found so far (floating point) */
  int lower_len;          /* its word's length */
  int *lower_word;        /* cap: its word */
  size_t nodes;           /* products formed */
  ss_status st;           /* first LAPACK failure, SS_OK if none */
} ss_jsr_ws;

/* The unit roundoff. */
static const double U = DBL_EPSILON / 2;

/* x rounded away from 0 by a few units: covers the rounding of the handful of
 * floating-point operations on nonnegative numbers that produced x. */
static inline double ss_jsr_up(double x) {
  return x * (1 + 8 * U);
}

/* A rigorous upper bound of x^{1/k} for x >= 0 from pow: glibc's pow is
 * within one ulp, and 1/k rounded perturbs the exponent by at most u/k, which
 * moves the result by the factor exp(u |ln x| / k). */
static inline double ss_jsr_root_up(double x, int k) {
  if (x <= 0) return 0;
  double r = pow(x, 1.0 / k);
  return r * (1 + (8 + fabs(log(x))) * 2 * U);
}

/* --- ss_jsr_products.c: the products along the word and their norms --- */

/* Free the workspace's buffers (not w itself). */
void ss_jsr_ws_free(ss_jsr_ws *w);
/* Make the stacks hold `levels` levels, keeping their contents; 0 if memory
 * ran out. */
int ss_jsr_ws_reserve(ss_jsr_ws *w, int levels);
/* Form the product at level k: Y_i, or Y_i times level k - 1, with its
 * rigorous error bounds. */
void ss_jsr_ws_push(ss_jsr_ws *w, int k, size_t i);
/* A rigorous upper bound of ||exact product at level k||_inf. */
double ss_jsr_ws_norm_inf_up(const ss_jsr_ws *w, int k);
/* A rigorous upper bound of ||exact product at level k||_2 (INFINITY if
 * LAPACK fails). */
double ss_jsr_ws_norm_2_up(ss_jsr_ws *w, int k);
/* Largest singular value of the product at level k (floating point). */
double ss_jsr_ws_norm_2(ss_jsr_ws *w, int k);
/* Spectral radius of the product at level k (floating point). */
double ss_jsr_ws_specrad(ss_jsr_ws *w, int k);
/* Use the exact similarity D^{-1} Y_i D, D = diag(d), for the words formed
 * from now on (d = NULL: Y itself; Y = w->eptr: the ellipsoidal copies). */
void ss_jsr_ws_scale(ss_jsr_ws *w, const double *const *Y, const double *d);

/* --- ss_jsr_search.c: the walks over words and the choice of the norm --- */

/* Brute force over the m^k words of length k = 1..K, one length at a time:
 * rho_inf, rho_2 (floating point), the rigorous inf-norm profile rho_cert,
 * and the lower bound.  From length 2 on, the wall-clock deadline (> 0) is
 * read before every product.  Returns the number of complete lengths (K, or
 * fewer if the deadline stopped it; then *cut_words words of the next length
 * were judged, else 0). */
int ss_jsr_brute_force(ss_jsr_ws *w, int K, double deadline, double *rho_inf,
                       double *rho_2, double *rho_cert, size_t *cut_words);
/* Choose the diagonal weighting of the inf-norm for the branch and bound
 * (*have = 1 and best_d if one beats the identity) and leave it active. */
void ss_jsr_choose_scaling(ss_jsr_ws *w, const double *const *Y, int K, double *best_d,
                           int *have);
/* Make candidate c of the branch and bound active (0 the inputs, 1 the
 * weighted copies, 2 the inputs for the 2-norm, 3 the ellipsoidal copies). */
void ss_jsr_ws_select(ss_jsr_ws *w, const double *const *Y, int c, const double *best_d);
/* Fit the ellipsoidal norm and enclose the similar copies; 1 if they are
 * ready, 0 if not (*st = SS_ENOMEM if memory ran out). */
int ss_jsr_ws_ellipsoid(ss_jsr_ws *w, const double *const *Y, int words, double deadline,
                        ss_status *st);
/* One pass of the branch and bound to depth L in the given norm; 1 and
 * *upper if it completed, 0 if max_nodes or the deadline stopped it. */
int ss_jsr_bnb_pass(ss_jsr_ws *w, int L, ss_jsr_norm norm, double gap, size_t max_nodes,
                    double deadline, double *upper);

#endif
