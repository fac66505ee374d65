/* ss_ball.h — arb balls handed back as doubles: the one rounding the certified
 * paths (ss_exact_basis, ss_fourier, ss_schur) apply to what they enclose; the
 * ball a computed entry of S stands for when S's weights are algebraic; and
 * the eigenvalue enclosure of a ball matrix the algebraic routes share.
 * Needs arb's headers (not installed, internal to the analysis). */
#ifndef SS_BALL_H
#define SS_BALL_H

#include <stddef.h>

#include "acb_mat.h"
#include "arb.h"

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

#endif
