/* ss_fourier.h — the certified eigenvalue condition of a local matrix whose
 * entries are not rational (Loop's cos(2 pi / n), a stencil's algebraic
 * weights) and whose star turns about the centre (a surface vertex, a volume
 * edge), from its Fourier blocks in ball arithmetic (DESIGN section 5,
 * "certified path"; `analyze --certify` where ss_exact cannot read S as
 * rationals).
 *
 * Entries.  Each computed entry s of S stands for the ball s +- 2^-40 max(1,
 * |s|): the window ss_exact's rational reconstruction also trusts the doubles
 * to (its acceptance test); an entry computed as 0 stands for 0 (no rule
 * reads that point; the reconstruction takes it for 0 as well).  What is proven is a
 * statement about every matrix with entries in those balls that commutes with the
 * rotation and the reflection of the vertex's star (rot, refl below) and whose rows sum
 * to 1: the scheme's S is one when its doubles are that accurate, since the rules depend
 * on the combinatorics only (so S commutes with the star's symmetries) and are affine.
 * The invariance is checked on the doubles (each pair of entries a symmetry maps onto
 * each other within the sum of their windows), else nothing is proven.
 *
 * Blocks.  With P the rotation (order n: the valence) and omega = exp(2 pi i
 * / n), V_k = {x : x[P j] = omega^k x[j]} (k = 0..n-1) is invariant under S
 * and C^N is their direct sum, so the spectrum of S (multiplicities and
 * Jordan structure) is the union of those of S restricted to V_k: the matrix
 * S_k over the orbits O of P whose size m_O has omega^(k m_O) = 1, S_k[O][O']
 * = sum_t S[r_O][P^t r_O'] omega^(k t) (r_O a representative).  S real gives
 * S_(n-k) = conj(S_k); the reflection R (S R = R S, R P R = P^-1) maps V_k
 * onto V_(-k), so S_k and S_(n-k) have the same spectrum and it is closed
 * under conjugation.  Hence only k = 0..n/2 are computed; the eigenvalues of
 * S_k for 0 < k < n/2 count twice.  Each S_k (size: the orbits, 4 for Loop's
 * two-ring) is enclosed in complex balls and its eigenvalues by
 * acb_mat_eig_simple (isolating balls, one eigenvalue each, with
 * eigenvectors); when they cluster (Loop's 1/16 twice at n = 3), S_k =
 * [A_k 0; B_k C_k] over the one-ring's and the outer orbits gives A_k's
 * and C_k's apart (acb_mat_eig_multiple for clusters within one: common
 * balls, no eigenvectors), a ball isolated when it isolates in its
 * sub-block and meets none of the other's.
 * An isolated eigenvalue of S_k whose conjugate ball meets no other of S_k's
 * balls is real (its conjugate is an eigenvalue of S_k too, and lies in no
 * other ball); one whose ball misses its conjugate ball is not real.
 *
 * Condition (m = 2 on surfaces, 3 in volumes), on this multiset, balls in
 * decreasing order of their moduli' midpoints:
 *   lambda0 = 1 simple: exactly one ball contains 1, isolated in S_0 (1 is an
 *     eigenvalue since rows sum to 1, so it is that ball's), every other
 *     modulus proven below 1 (one proven above 1: a certified fail);
 *   lambda1..lambda_m: the next balls until m copies are counted, an
 *     eigenvalue of S_k with 0 < k < n/2 counting twice (an exact tie,
 *     proven by the symmetry: the same eigenvalue in V_k and V_(n-k), simple
 *     in each, so not defective); each isolated, real and positive, and
 *     every other modulus proven below each of them.  Proven fails: a
 *     leading eigenvalue not real or not positive, or a pair straddling
 *     lambda_m (lambda_m = lambda_m+1 exactly).  Anything else is undecided.
 * Basis on a pass: the eigenvector a of S_k lifted to x[P^t r_O] = a_O
 * omega^(k t) (0 elsewhere); for a pair, Re x and Im x (independent since x
 * and conj(x) lie in V_k and V_(n-k)), else x (real).  Enclosed as doubles
 * lo <= X <= hi, n x m column-major, as ss_exact_basis.
 *
 * Cost: n / 2 + 1 blocks of the orbits' size, microseconds each; the
 * invariance check reads S twice (O(N^2)).  No global state. */
#ifndef SS_FOURIER_H
#define SS_FOURIER_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_ball_outcome.h"
#include "ss_error.h"
#include "ss_verdict.h"

SS_BEGIN_DECLS

typedef struct ss_fourier ss_fourier; /* opaque: the blocks' enclosures */

/* One eigenvalue enclosure of S. */
typedef struct {
  double re, im; /* midpoint */
  double rad;    /* |true - (re + i im)| <= rad */
  int mult;      /* copies in S: 2 for a block 0 < k < n / 2, else 1 */
  int mode;      /* k of its block, 0 <= k <= n / 2 */
  int isolated;  /* 1 if its ball holds one eigenvalue of S_k (0: a cluster's
                    common ball) */
  int real;      /* 1 proven real, -1 proven not real, 0 unknown */
} ss_fourier_root;

/* The Fourier analysis of S (n x n, row-major, its one-ring the first n1
 * points, which read no other: S = [A 0; B C]) under the rotation rot (a
 * permutation of 0..n-1, rot[i] the image of i, of order `order` >= 3) and the
 * reflection refl (refl rot refl = rot^-1), both keeping the one-ring, for
 * the condition on m = 2 (surface) or 3 (volume) subdominant eigenvalues.
 * *out (caller frees, ss_fourier_free) holds the condition, undecided with
 * the reason when S is not invariant or something cannot be proven.
 * SS_EINPUT for permutations that are not, SS_ENOMEM. */
ss_status ss_fourier_new(const double *S, size_t n, size_t n1, const size_t *rot,
                         const size_t *refl, int order, int m, ss_fourier **out,
                         ss_error *err);

/* Free; NULL is a no-op. */
void ss_fourier_free(ss_fourier *f);

/* The certified eigenvalue condition and on a pass the subdominant basis
 * enclosure (above), read by ss_ball_outcome_condition and
 * ss_ball_outcome_basis: valid while f lives. */
const ss_ball_outcome *ss_fourier_outcome(const ss_fourier *f);

/* The eigenvalue enclosures, by decreasing modulus (midpoints), each once
 * (see mult): *nroots of them, valid while f lives. */
const ss_fourier_root *ss_fourier_roots(const ss_fourier *f, size_t *nroots);

SS_END_DECLS

#endif
