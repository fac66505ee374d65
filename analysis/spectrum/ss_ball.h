/* ss_ball.h — arb balls handed back as doubles: the one rounding the certified
 * paths (ss_exact_basis, ss_fourier) apply to what they enclose.  Needs arb's
 * headers (not installed, internal to the analysis). */
#ifndef SS_BALL_H
#define SS_BALL_H

#include "arb.h"

/* [*lo, *hi] holding every point of x, its bounds rounded outward to doubles
 * (at 64 bits; +-inf when x is not finite).  Outputs may not alias x. */
void ss_ball_doubles(const arb_t x, double *lo, double *hi);

#endif
