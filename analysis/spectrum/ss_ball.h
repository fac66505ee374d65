/* ss_ball.h — arb balls handed back as doubles: the one rounding the certified
 * paths (ss_exact_basis, ss_fourier, ss_schur) apply to what they enclose; the
 * ball a computed entry of S stands for when S's weights are algebraic; the
 * eigenvalue enclosure of a ball matrix the algebraic routes share; and what
 * those two routes (ss_fourier.h, ss_schur.h) share of the condition: their
 * outcome (ss_ball_outcome.h), the root both hold of an eigenvalue ball, and
 * the steps of the assessment both take (lambda0 = 1 isolated, every other
 * modulus below 1, the rest below the leading roots).
 * Needs arb's headers (not installed, internal to the analysis). */
#ifndef SS_BALL_H
#define SS_BALL_H

#include <stddef.h>

#include "acb_mat.h"
#include "arb.h"

#include "ss_ball_outcome.h"

/* An entry s of S stands for s +- 2^-SS_BALL_WINDOW max(1, |s|): the window
 * ss_exact's rational reconstruction trusts the doubles to (DESIGN section 5). */
enum { SS_BALL_WINDOW = 40 };

/* [*lo, *hi] holding every point of x, its bounds rounded outward to doubles
 * (at 64 bits; +-inf when x is not finite).  Outputs may not alias x. */
void ss_ball_doubles(const arb_t x, double *lo, double *hi);

/* The half-width of s's window, 2^-SS_BALL_WINDOW max(1, |s|). */
double ss_ball_window(double s);

/* b = the ball s stands for: s +- 2^(e - SS_BALL_WINDOW) >= s's window; 0
 * for an entry computed as 0 (no rule reads that point: the exact path's
 * reconstruction takes it for 0 too). */
void ss_ball_entry(arb_t b, double s);

/* The eigenvalue enclosures of B (b x b, at prec bits) into E (b entries),
 * with eigenvectors in R (may be NULL) when the balls isolate them: returns
 * 1 for isolating balls, 0 for common balls of clusters (each eigenvalue in
 * its ball, multiplicities counted: a ball shared by c entries holds c
 * eigenvalues), 2 where even that fails (a Jordan block): every eigenvalue
 * within acb_mat_eig_global_enclosure's eps of an approximation, balls that
 * bound moduli but count nothing, -1 none.  E's order is that of the
 * approximations acb_mat_approx_eig_qr gives, returned in E0 and R0 when not
 * NULL (b entries, b x b: the approximate eigenvalues and vectors). */
int ss_ball_eig(acb_ptr E, acb_mat_t R, const acb_mat_t B, acb_ptr E0, acb_mat_t R0,
                slong prec);

/* Whether S (n x n, row-major) is invariant under the permutation p within
 * the windows: S[p i][p j] = S[i][j] up to the sum of their windows, zero
 * exactly where the other is.  1, or 0 with the first entry (i, j) that is not. */
int ss_ball_invariant(const double *S, size_t n, const size_t *p, size_t *bi, size_t *bj);

/* A ball route's outcome (ss_ball_outcome.h). */
struct ss_ball_outcome {
  ss_verdict cond; /* the condition: cond.certified 1 when proven; judged on
                      the spectrum */
  size_t n;        /* rows of the basis: the size of S */
  int m;           /* its columns: the subdominant eigenvalues, 2 or 3 */
  double *lo, *hi; /* on a certified pass: the basis enclosure, n x m
                      column-major (owned), or NULL */
  char bmsg[256];  /* why there is no basis */
};

/* o for S of size n and m subdominant eigenvalues: undecided ("not
 * certified: not assessed"), no basis ("the condition is not a certified
 * pass").  Owns nothing yet. */
void ss_ball_outcome_init(ss_ball_outcome *o, size_t n, int m);

/* Free o's basis (o itself is its route's). */
void ss_ball_outcome_clear(ss_ball_outcome *o);

/* o's condition: verdict v, certified or not, the reason printf(fmt, ...)
 * (truncated to the reason's size), judged on the spectrum. */
void ss_ball_verdict(ss_ball_outcome *o, ss_verdict_kind v, int certified,
                     const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* One eigenvalue ball as both routes hold it: the first member of each
 * route's own root struct, so that the steps below read an array of those
 * through ss_ball_roots. */
typedef struct {
  acb_struct z;   /* the ball */
  arb_struct mod; /* |z| enclosed */
  int counted;    /* 1: the ball holds as many eigenvalues (with multiplicity)
                     as the route counts in it; 0: it only bounds where they
                     are (ss_ball_eig's 2, a Jordan block): nothing fails by it */
} ss_ball_root;

/* A route's roots as the shared steps read them (borrowed, not kept). */
typedef struct {
  const void *at; /* nrt roots of `size` bytes each, each beginning with its
                     ss_ball_root, by decreasing midpoint modulus */
  size_t nrt;     /* how many */
  size_t size;    /* bytes from one root to the next */
  const char *(*text)(const void *route, size_t i, char *buf,
                      size_t len); /* root i as a reason quotes it, in buf */
  const void *route;               /* text's first argument */
} ss_ball_roots;

/* The midpoint re + i im of r's ball (rounded to nearest) and, when rad is
 * not NULL, its radius (an upper bound of |true - midpoint|). */
void ss_ball_mid(const ss_ball_root *r, double *re, double *im, double *rad);

/* Root i of r. */
const ss_ball_root *ss_ball_at(const ss_ball_roots *r, size_t i);

/* How many of r's balls hold 1; *one the last that does (unchanged when
 * none does). */
size_t ss_ball_ones(const ss_ball_roots *r, size_t *one);

/* Every root of r but `one` (lambda0) proven of modulus below 1: 0;
 * otherwise 1 with o's verdict set from the first root (in r's order) that
 * is not: a certified fail when its modulus is proven above 1 and its ball
 * counted, else undecided (not separated from 1). */
int ss_ball_below_one(const ss_ball_roots *r, size_t one, ss_ball_outcome *o);

/* Whether every root of r but `one`, the nl leading ones lead[] and skip
 * (SIZE_MAX: none) is proven of modulus below x. */
int ss_ball_rest_below(const ss_ball_roots *r, size_t one, const size_t *lead, int nl,
                       const arb_t x, size_t skip);

/* qsort's comparison of two roots (each beginning with an ss_ball_root): by
 * decreasing midpoint modulus. */
int ss_ball_by_modulus(const void *a, const void *b);

/* cz = conj(z).  Not inlined: GCC 12 inlining acb_conj on a root's ball
 * warns -Wstringop-overread (a false positive). */
void ss_ball_conj(acb_t cz, const acb_t z);

/* arb_mat_solve(X, M, B, wp) for one outer block minus lambda M (the
 * exact path's and the verified similarity's outer solves), factored
 * once for the later components with the same block (the lattice repeats
 * them: MLCA k = 14 has 74 outer components of which 4-8 distinct blocks are
 * larger than 1 x 1, and the solves were 40 % of the basis enclosure).  The
 * steps are arb_mat_solve's own (arb 2.23): below 5 rows or above 10 bits a
 * row, the LU of M and its triangular solves; else, with fewer right-hand
 * sides than n / 10 + 1, an approximate inverse R of M (arb_mat_approx_solve
 * of M X = I), the LU of R M and the triangular solves of R B; else
 * arb_mat_solve itself each time.  So the balls are the ones arb_mat_solve
 * gives, and a later component reuses the factors only when its M equals the
 * first one's entry for entry. */
typedef struct {
  int kind;     /* 0: not made; 1: LU of M; 2: LU of R M; 3: arb_mat_solve */
  int ok;       /* the factorisation succeeded (arb_mat_solve's result) */
  slong *perm;  /* the LU's row permutation */
  arb_mat_t M;  /* the block minus lambda it was made from */
  arb_mat_t R;  /* kind 2: the approximate inverse of M */
  arb_mat_t LU; /* the LU factors of M (kind 1) or R M (kind 2) */
} ss_ball_solver;

/* Factor M (m right-hand sides to come) at wp into f (zeroed on entry). */
void ss_ball_solver_make(ss_ball_solver *f, const arb_mat_t M, slong m, long wp);

/* Free f's factors (a zeroed f: nothing). */
void ss_ball_solver_clear(ss_ball_solver *f);

/* X = M^-1 B as arb_mat_solve(X, M, B, wp) gives it, with f's factors when
 * M is f's block; 1, or 0 when not proven invertible. */
int ss_ball_solver_solve(const ss_ball_solver *f, arb_mat_t X, const arb_mat_t M,
                         const arb_mat_t B, long wp);

#endif
