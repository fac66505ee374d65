/* ss_charmap_cert_impl.h — internal to the charmap room: the two acceptance
 * rules of ss_charmap_cert.c, taken out of their callers so that a test can
 * sit on their edges with hand-made numbers (tests/analysis/test_edges.c).
 * Not installed; ss_charmap_cert.c is their only caller. */
#ifndef SS_CHARMAP_CERT_IMPL_H
#define SS_CHARMAP_CERT_IMPL_H

#include <stddef.h>

/* Proven verdicts of the cells of one ring level. */
typedef struct {
  size_t cells;   /* cells of the level */
  size_t pos;     /* proven det J > 0 on the whole cell */
  size_t neg;     /* proven det J < 0 on the whole cell */
  size_t folded;  /* proven to change sign inside the cell */
  size_t unknown; /* none of these proven */
} ss_charmap_proven;

/* The symmetry proof's margin: with dx2 = ||P Xm - Xm||_F^2, e2 = ||E||_F^2
 * and mu0 the least eigenvalue of Xm^T Xm (so s_min(Xm) = sqrt(mu0)), 1 when
 * sqrt(dx2) + 2 ||E|| < (s_min(Xm) - ||E||) gap / 2, i.e. psi o sigma = psi is
 * proven; 0 if not. */
int ss_charmap_cert_sym_margin(double dx2, double e2, double mu0, double gap);

/* The fold-persistence rule on proven counts: 1 when both levels have a
 * proven majority sign (over the other sign and the unknown cells together)
 * and the proven bad share now (folded and minority cells of `now`) is
 * positive and at least shrink times the largest possible bad share before
 * (folded, unknown and minority cells of `before`); 0 if not. */
int ss_charmap_cert_persists(const ss_charmap_proven *before,
                             const ss_charmap_proven *now, double shrink);

#endif
