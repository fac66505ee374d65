/* ss_simil_impl.h — the verified similarity's state, shared by its files
 * (ss_simil.c: blocks and discs; ss_simil_pass.c: the pass and the basis). */
#ifndef SS_SIMIL_IMPL_H
#define SS_SIMIL_IMPL_H

#include "ss_ball.h"
#include "ss_scc.h"
#include "ss_simil.h"

struct ss_simil {
  size_t n, n1;        /* size of S, of its one-ring block A */
  int m;               /* subdominant eigenvalues: 3 or 2 */
  ss_csr A;            /* S's nonzeros */
  ss_scc K;            /* the outer block's components */
  double *lo, *hi;     /* per nonzero of A: an interval of doubles holding the
                          rational entry */
  arb_ptr eb;          /* per nonzero of A: the entry as a ball (the basis) */
  size_t *rep;         /* per component: the first with an equal block */
  size_t *dstart;      /* per component: its first disc */
  ss_simil_disc *d;    /* discs, n at most */
  size_t nd;           /* discs so far */
  double *Xa;          /* A's X (n1 x n1 row-major, real parts then
                          imaginary parts), or NULL */
  size_t lead[4];      /* on a pass: the disc of 1, then of lambda1..m */
  int passed;          /* 1: pass proven with its basis */
  char why[256];       /* why nothing was decided, or the pass's reason */
  ss_ball_outcome out; /* the condition and basis as the ball routes' */
};

/* x inflated (deflated) by 2^-40 relatively and 2^-1000 absolutely: a
 * bound on a computed non-negative sum (a distance) safe against its
 * rounding. */
double ss_simil_up(double x);
double ss_simil_dn(double x);

/* The discs of block T (k x k row-major doubles, entry radii Trad) pushed
 * onto s->d with block blk (-1: A, whose X is kept in s->Xa); 0, 1 refused
 * (LAPACK failed, alpha >= 1/2), -1 out of memory. */
int ss_simil_block(ss_simil *s, const double *T, const double *Trad, size_t k, long blk);

/* As ss_simil_block with X (its eigenvectors, complex split, k x k
 * row-major) and R ~ X^-1 given (a test's way to a poor X or R; any X, R give
 * valid discs when alpha < 1/2, only wider ones). */
int ss_simil_block_with(ss_simil *s, const double *T, const double *Trad, size_t k,
                        long blk, const double *Xr, const double *Xi, const double *Rr,
                        const double *Ri);

/* S's entries as rationals of denominator <= maxden (s->lo, s->hi), every
 * row summing to exactly 1: 1, 0 when not, -1 out of memory. */
int ss_simil_rational(ss_simil *s, long maxden);

#endif
