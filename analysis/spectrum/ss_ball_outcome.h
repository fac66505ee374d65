/* ss_ball_outcome.h — what a ball route (ss_fourier: Fourier blocks in
 * balls; ss_schur: balls, ties by Schur's lemma) proves of a local matrix S:
 * its certified eigenvalue condition and, on a certified pass, an enclosure
 * of a basis of its subdominant eigenvectors.  Held by its route
 * (ss_fourier_outcome, ss_schur_outcome), valid while the route lives. */
#ifndef SS_BALL_OUTCOME_H
#define SS_BALL_OUTCOME_H

#include "ss_api.h"
#include "ss_error.h"
#include "ss_verdict.h"

SS_BEGIN_DECLS

typedef struct ss_ball_outcome ss_ball_outcome; /* opaque: owned by its route */

/* The certified eigenvalue condition, as ss_exact_condition: *v (judged on
 * the spectrum), *certified 1 when it is proven. */
void ss_ball_outcome_condition(const ss_ball_outcome *o, ss_verdict *v, int *certified);

/* The subdominant basis enclosure (the route's header says how) into lo, hi
 * (n * m each, n x m column-major: n the size of S, m its subdominant
 * eigenvalues): SS_OK, or SS_EINPUT when the condition is not a certified
 * pass, SS_ENUMERIC when it could not be enclosed (the message says why). */
ss_status ss_ball_outcome_basis(const ss_ball_outcome *o, double *lo, double *hi,
                                ss_error *err);

SS_END_DECLS

#endif
