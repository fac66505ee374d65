/* ss_schur.h — the certified eigenvalue condition of a local matrix whose
 * entries are not rational (a stencil's cos(2 pi / n) in a volume rule),
 * from ball enclosures of its eigenvalues and the case's symmetry group:
 * ties among the leading eigenvalues are proven by Schur's lemma (DESIGN
 * section 5, "certified path"; `analyze --certify` at volume vertices, where
 * the link's automorphism group is not cyclic and ss_fourier does not apply).
 *
 * Entries.  As ss_fourier.h: each computed entry s stands for s +- 2^-40
 * max(1, |s|) (ss_ball_entry), a computed 0 for 0.  What is proven is a
 * statement about every matrix inside those balls that commutes with the
 * group's permutations: the scheme's S when its doubles are that accurate
 * (its rules read the combinatorics only).  The invariance is checked on the
 * doubles (ss_ball_invariant), else nothing is proven.
 *
 * Eigenvalues.  S = [A 0; B C] (A the one-ring's n1 x n1 block) and C block
 * lower triangular over the strongly connected components of its pattern
 * (ss_scc.h), so the spectrum of S is that of A and of C's diagonal blocks.
 * Each is enclosed by arb (ss_ball_eig: isolating balls, or common balls of
 * clusters with their counts, or for a Jordan block a bound on the moduli
 * that counts nothing).  Balls sharing a cluster form one root of `count`
 * eigenvalues.
 *
 * Ties (Schur's lemma).  For a root of count c > 1 in A that meets no other
 * root, its spectral subspace V (dimension c) is enclosed by Rump's method
 * (acb_mat_eig_enclosure_rump: A X = X J, X n1 x c with a c x c minor X_I
 * proven invertible, J's eigenvalues in a ball meeting no other root, so
 * span X = V).  A permutation P_g of the group commutes with A, so P_g V = V
 * and P_g X = X M_g with M_g = X_I^-1 X_(g(I)) enclosed in balls (every
 * other row checked to agree).  g -> M_g is a representation of G (|G| = ng
 * elements, checked to be a group) of character chi(g) = tr M_g, and <chi,
 * chi> = (1 / |G|) sum |chi(g)|^2 is a positive integer (the sum of the
 * squares of the irreducible constituents' multiplicities); enclosed in
 * (0.5, 1.5) it is 1, V is irreducible, and A restricted to V, which
 * commutes with every M_g, is a scalar: one eigenvalue of multiplicity c,
 * not defective.  It is real when the conjugate of its ball meets no other
 * root (S is real: the conjugate eigenvalue is in a root, hence in this one,
 * and V holds one eigenvalue).  <chi, chi> not proven 1 (a reducible V, or
 * balls too wide): the tie is not forced by the symmetry, undecided.
 *
 * Condition (m = 3 in volumes, 2 on surfaces), the roots by decreasing
 * modulus: lambda0 = 1 the one root holding 1, of A, count 1, meeting no
 * other, every other modulus proven below 1 (one proven above: a certified
 * fail); lambda1..lambda_m the next roots until m eigenvalues are counted,
 * each of A, counted, meeting no other root, real, positive, and a tie
 * (count > 1) proven by Schur's lemma; every other root proven below each
 * of them in modulus.  A last root counting past m, a proven tie, with all
 * else placed: lambda_m = lambda_m+1, a certified fail.  Anything else is
 * undecided with the reason (a leading eigenvalue of C, a cluster the
 * enclosures do not count, a reducible V, moduli not separated).
 *
 * Basis on a pass: per leading root X (real parts: V is real) on the
 * one-ring, and on the outer rows Y = (lambda I - C)^-1 B X by block forward
 * substitution over C's components, lambda the root's ball (the true
 * eigenvector's completion lies in the ball solve's result).  Enclosed as
 * doubles lo <= X <= hi, n x m column-major, as ss_exact_basis.
 *
 * Cost: arb's eigenvalue enclosure of A and of C's blocks (cubic in their
 * sizes), the group check O(ng^2 n) and the invariance O(ng n^2).  No global
 * state. */
#ifndef SS_SCHUR_H
#define SS_SCHUR_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_ball_outcome.h"
#include "ss_error.h"
#include "ss_verdict.h"

SS_BEGIN_DECLS

typedef struct ss_schur ss_schur; /* opaque: the enclosures */

/* One root: a ball holding count eigenvalues of S. */
typedef struct {
  double re, im;    /* midpoint */
  double rad;       /* |true - (re + i im)| <= rad for each of them */
  int count;        /* eigenvalues in the ball (with multiplicity); 0: the
                       ball only bounds where they are (a Jordan block) */
  int outer;        /* 0: an eigenvalue of the one-ring block A; 1 + c: of
                       C's component c */
  int lead;         /* 1: lambda0; 2: among lambda1..m (or straddling m);
                       0: the rest */
  double norm_lo;   /* a leading root of count > 1: <chi, chi> >= norm_lo */
  double norm_hi;   /* ... and <= norm_hi (0, 0 when not computed) */
  int constituents; /* a leading root of count > 1: 1 for a tie proven by
                       Schur's lemma, 2 or 3 for distinct real-type
                       constituents (diagonalizable, real eigenvalues); 0
                       not proven */
} ss_schur_root;

/* The analysis of S (n x n, row-major, one-ring the first n1 points: S =
 * [A 0; B C]) under the group G of ng permutations (group[g * n + i] = the
 * image of point i under element g; each must keep the one-ring), for the
 * condition on m = 2 or 3 subdominant eigenvalues.  *out (caller frees,
 * ss_schur_free) holds the condition, undecided with the reason when S is
 * not invariant under an element or something cannot be proven.  SS_EINPUT
 * when an element is not a permutation keeping the one-ring or G is not a
 * group (closed under composition, holding the identity); SS_ENOMEM. */
ss_status ss_schur_new(const double *S, size_t n, size_t n1, const size_t *group,
                       size_t ng, int m, ss_schur **out, ss_error *err);

/* Free; NULL is a no-op. */
void ss_schur_free(ss_schur *s);

/* The certified eigenvalue condition and on a pass the subdominant basis
 * enclosure (above), read by ss_ball_outcome_condition and
 * ss_ball_outcome_basis: valid while s lives. */
const ss_ball_outcome *ss_schur_outcome(const ss_schur *s);

/* The roots, by decreasing modulus (midpoints): *nroots of them, valid while
 * s lives (0 when the enclosures were not computed). */
const ss_schur_root *ss_schur_roots(const ss_schur *s, size_t *nroots);

SS_END_DECLS

#endif
