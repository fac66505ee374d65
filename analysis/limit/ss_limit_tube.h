/* ss_limit_tube.h — the layered structure of a box of ss_limit_pieces left
 * uncovered round an extraordinary edge, read exactly: what a proof of the
 * limit's sign in the box's tube needs (analysis/psi/ss_psi_tube.h).
 *
 * A box whose patch never becomes regular because an extraordinary edge runs
 * along one of its edges (axis a, through the box corner with bits `corner`
 * across) refines into 8 children: the two at that corner (the halves along
 * a) are the box again — the same patch, numbered alike — and the six others
 * are regular.  When the structure is the edge's (the paper's eq. (1), as
 * ss_limit_tensor finds it for the evaluator's states), the patch's points
 * stand in 4 layers along a (B-spline positions -1..2) and ncol columns
 * across, and the refinement rows factor exactly as
 *     run b:               W_b = A_b (x) F        (F: ncol x ncol)
 *     quadrant c, half b:  W   = A_b (x) G_c      (G_c: 16 x ncol)
 * A_b the cubic B-spline's half matrices.  Then the limit on the box minus
 * the edge is the union over m >= 0 of the tricubics with nets
 *     (I_4 (x) G_c F^m) P
 * on [the box's range along a] x [quadrant c of the m-th cross-section
 * layer]: the halves b of a quadrant's children are the two halves of one
 * cubic along a, and every step towards the edge multiplies by F.
 *
 * Exactness.  Each weight of the rows is read by the caller's rational
 * function (as the exact path reads the rule), and the factorisation is
 * checked in rationals entry by entry; F and G_c are given as exact
 * rationals.  A box whose rows do not factor exactly, whose children at the
 * corner are not the box again, or whose other children are not regular has
 * no tube (NULL): nothing is claimed there. */
#ifndef SS_LIMIT_TUBE_H
#define SS_LIMIT_TUBE_H

#include <stddef.h>

#include "ss_api.h"

SS_BEGIN_DECLS

/* The exact rational p / q (q > 0) a weight w of the rule stands for: 0, or
 * nonzero if w is not known exactly. */
typedef int (*ss_limit_rational_fn)(double w, void *arg, long long *p, long long *q);

/* The layered structure of one uncovered box (valid during the callback of
 * ss_limit_pieces_tubes). */
typedef struct {
  int axis;               /* the edge's axis in the box's parameters */
  int across[2];          /* the two other axes, increasing */
  unsigned corner;        /* the box corner the edge runs through, as bits (bit
                             axis 0) */
  size_t ncol;            /* columns across the edge */
  const double *P;        /* 4 ncol x 3: the point of column c in layer l at row
                             l ncol + c (layer l at position l - 1 along axis),
                             translated by a common vector (which changes no
                             derivative) */
  const double *lo;       /* its enclosure likewise, or NULL without one */
  const double *hi;       /* (lo <= true point - that vector <= hi) */
  const long long *Fp;    /* ncol x ncol row-major: F = Fp / Fq exactly */
  const long long *Fq;    /* (Fq > 0, lowest terms) */
  unsigned quad[3];       /* the three quadrants besides the edge's: their
                             corner bits across (bit axis 0) */
  const long long *Gp[3]; /* 16 x ncol each: G_c = Gp / Gq exactly, row
                             g0 + 4 g1 the child's net point at grid
                             positions g0 - 1 along across[0] and g1 - 1 along
                             across[1] (the child's own units) */
  const long long *Gq[3];
} ss_limit_tube;

SS_END_DECLS

#endif
