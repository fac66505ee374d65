/* ss_simil.h — a certified pass of the eigenvalue condition from one
 * verified approximate diagonalisation per diagonal block (issue 37: the
 * lazy exact path's pre-pass; `sweep`/`check --certify`).
 *
 * Matrix.  S is read as ss_exact.h says: every entry the rational of
 * denominator <= maxden it rounds to (ss_exact_rational's reconstruction,
 * enclosed in the doubles p/q rounds to: a point where p/q is a double, else
 * its two neighbours), every row summing to exactly 1 (checked in
 * rationals).  Everything below is about that rational matrix.  S = [A 0; B C]
 * and C is block lower triangular over the strongly connected components of
 * its pattern (ss_scc.h), so the spectrum of S (with multiplicities) is the
 * union of those of A and of C's diagonal blocks T.
 *
 * One block T (k x k, T = Tm + dT, Tm the doubles, |dT| <= Trad entrywise).
 * X: T's eigenvectors from LAPACK (dgeev), complex: a real eigenvalue keeps
 * its real vector, a conjugate pair gets v and conj(v); each column scaled by
 * its largest entry (a real column then has a largest entry of exactly 1).
 * Complex X rather than the real form (Re v, Im v) because the discs below
 * must be tight about complex eigenvalues too: a real 2 x 2 block [a b; -b a]
 * would give a disc of radius |b| about a, whose modulus bound |a| + |b|
 * exceeds |a + ib| by up to sqrt 2 and would mask the separation from
 * lambda_m.  R ~ X^-1 (LAPACK zgetrf/zgetri).  In doubles: P = fl(Tm X),
 * E = fl(R X), Bt = fl(R P).  Error bounds (Higham, Accuracy and Stability,
 * 3.5; any order of summation, FMA included): a computed sum of q products
 * has error at most gamma_q times the sum of their moduli, gamma_q =
 * q u / (1 - q u), u = 2^-53; a complex entry's error is bounded by
 * |re| + |im| of its parts' errors.  With |Z| the entrywise |re| + |im|
 * (>= the modulus), x = |X| 1 and p = |P| 1:
 *   B := R T X (exact) = R (P - dP) - dB with |fl(Tm X) - Tm X| <= gamma_k
 *   |Tm| |X| and dT X, so the row sums satisfy
 *   sum_j |B_ij - Bt_ij| <= e_i := (|R| (gamma_2k p + (gamma_k |Tm| + Trad)
 *   x))_i;
 *   alpha := max_i sum_j |(I - E)_ij| + gamma_2k (|R| x)_i >= ||I - R X||_inf.
 * alpha < 1 proves R X invertible (Neumann), hence X and R, and
 *   X^-1 T X = (R X)^-1 R T X = B + F,  F = ((R X)^-1 - I) B,
 *   ||F||_inf <= alpha / (1 - alpha) ||B||_inf =: delta,
 *   ||B||_inf <= max_i (|Bt_ii| + r_i + e_i), r_i = sum_{j != i} |Bt_ij|.
 * Gershgorin on M = B + F (similar to T): disc i = D(Bt_ii, rho_i),
 * rho_i = r_i + e_i + delta, contains M's own disc i (centre M_ii within
 * |B_ii - Bt_ii| + |F_ii| of Bt_ii, radius the rest of row i's error and F's
 * row sum).  Every eigenvalue of T lies in the union, and a union of discs
 * disjoint from all others holds as many eigenvalues as discs (M's own discs
 * of those rows lie in it and those of the others outside, which is the
 * hypothesis of Gershgorin's count theorem, continuity in t for
 * diag(M) + t offdiag(M)).  alpha >= 1/2 (X far from invertible), or LAPACK failing: the
 * block is refused and S goes to the exact path.  A 1 x 1 block is its own disc. Every
 * computed bound (sums of non-negative doubles, at most 4k + 8 roundings deep, k < 2^12)
 * is inflated by 2^-40 relatively and 2^-1000 absolutely (rounding and underflow), every
 * computed distance deflated alike.
 *
 * The pass (m = 3 in volumes, 2 on surfaces).  Over the discs of all blocks:
 *   - exactly one disc contains 1, it is A's and meets no other disc: it
 *     holds exactly one eigenvalue, and 1 is one (the rows sum to 1, A's
 *     rows too as S[i][j] = 0 for i < n1 <= j), so lambda0 = 1 is simple;
 *   - the m discs of largest centre modulus after it, each A's, enlarged to
 *     D(Re c, rho + |Im c|) (symmetric about the real axis), meet no other
 *     disc: each holds exactly one eigenvalue mu, conj(mu) is an eigenvalue
 *     (S real) in the same symmetric disc, so mu is real; these discs lie in
 *     (0, 1) (mu positive, below 1); their real intervals are disjoint,
 *     which orders lambda1 > ... > lambda_m;
 *   - every other disc lies in |z| < lambda_m's lower end (and so below 1
 *     and apart from the m + 1 discs above, which lie in Re z >= that end).
 * Then lambda0 = 1 is simple, every other eigenvalue has modulus < 1,
 * lambda1..m are real, positive, simple (hence non-defective) and lambda_m >
 * |lambda_m+1|: the certified pass of ss_exact.h.  Anything else (a disc
 * holding a tie or meeting another, complex leading eigenvalues, a leading
 * eigenvalue of C, alpha >= 1, a failure) decides nothing here: the exact path
 * runs as before.  Only passes are decided, so no verdict other than a pass
 * can come from this route.
 *
 * Basis on a pass. For lambda = mu in A's disc i (enlarged as above, radius
 * rho'_i about Re c_i), let w be the eigenvector of M = X^-1 A X scaled so that
 * its largest entry in modulus is 1, at index p. Row p of (M - mu) w = 0 gives
 * |M_pp - mu| <= sum_{k != p} |M_pk|: mu is in M's disc p, so p = i (mu is in
 * no other disc), and w_i = 1, |w_j| <= 1. Row j != i: |w_j| |M_jj - mu| <=
 * sum_{k != j} |M_jk| |w_k|, and with s + t <= rho_j (s the off-diagonal row
 * sum, t = |M_jj - Bt_jj|) and d_j = |Bt_jj - Re c_i| - rho'_i <= |Bt_jj - mu|
 * and d_j > rho_j (the discs are disjoint), |w_j| <= s / (d_j - t) <= rho_j /
 * d_j, so |w_j| <= min(1, rho_j / d_j) =: beta_j (s / (d - t) with s = rho - t
 * decreases in t when rho < d). A's eigenvector X w has Re(X w) = X_i +
 * Re(sum_{j != i} w_j X_j): real (X_i is dgeev's real vector), an eigenvector
 * for the real lambda unless zero, and enclosed entrywise by X_qi +- sum_{j !=
 * i} beta_j |X_qj|; its largest entry (exactly 1) stays away from 0, so it is
 * not zero. Outer rows: for each component c in order, (C_cc - lambda) y_c =
 * -(S's rows c on A and the earlier components) y, solved in arb with lambda
 * the disc's real interval (arb_mat_solve proves C_cc - lambda invertible for
 * every lambda in it; lambda is no eigenvalue of C, whose discs lie below
 * lambda_m). Returned as an ss_ball_outcome (ss_ball.h): lo <= X <= hi, n x m
 * column-major, column j for lambda_j+1, as ss_exact_basis; the widths are
 * those of the bounds above (about 1e-13 relative where X is well conditioned)
 * rather than the exact path's 2 ulp. A basis that cannot be proven (an outer
 * solve not verified, a column that may vanish) refuses the pass.
 *
 * Cost: per block k^3 for dgeev and three complex products in doubles (A of
 * MLCA k = 14: ~70 x 70), the discs O(k^2), the pass O(n d) for d discs, the
 * basis O(n1^2 m) and the outer solves in arb.  No global state. */
#ifndef SS_SIMIL_H
#define SS_SIMIL_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_ball_outcome.h"
#include "ss_error.h"

SS_BEGIN_DECLS

typedef struct ss_simil ss_simil; /* opaque: the discs and the outcome */

/* One Gershgorin disc of X^-1 T X for a diagonal block T (above). */
typedef struct {
  double re, im; /* centre Bt_ii */
  double rad;    /* radius rho_i: the discs hold T's eigenvalues (above) */
  long block;    /* -1: the one-ring block A; c >= 0: outer component c */
} ss_simil_disc;

/* Try the verified similarity on S (n x n row-major, leading n1 x n1 block
 * invariant as in ss_exact_new), m = 3 (volume) or 2 (surface), entries
 * rationals of denominator <= maxden.  *out (ss_simil_free) always set on
 * SS_OK; ss_simil_passed says whether it proved the pass.  SS_ENOMEM,
 * SS_EINPUT for malformed arguments; a matrix the route cannot decide is
 * not an error (ss_simil_why says why). */
ss_status ss_simil_new(const double *S, size_t n, size_t n1, int m, long maxden,
                       ss_simil **out, ss_error *err);

/* Free; NULL is a no-op. */
void ss_simil_free(ss_simil *s);

/* 1 when the pass is proven (condition and basis), else 0. */
int ss_simil_passed(const ss_simil *s);

/* Why the route decided nothing (or the pass's reason). */
const char *ss_simil_why(const ss_simil *s);

/* The condition (certified pass) and basis, as the ball routes give them:
 * valid while s lives, meaningful when ss_simil_passed. */
const ss_ball_outcome *ss_simil_outcome(const ss_simil *s);

/* All discs computed (blocks refused have none; empty when the route stopped
 * before), *nd of them; valid while s lives. */
const ss_simil_disc *ss_simil_discs(const ss_simil *s, size_t *nd);

/* The leading discs on a pass: lead[0] the disc of 1, lead[1..m] those of
 * lambda1..m (indices into ss_simil_discs); 0 when not passed. */
int ss_simil_lead(const ss_simil *s, size_t lead[4]);

SS_END_DECLS

#endif
