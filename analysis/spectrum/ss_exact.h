/* ss_exact.h — the exact eigenstructure of a local subdivision matrix and the
 * certified eigenvalue condition (DESIGN sections 5 and 10, "certified
 * verdicts"; `analyze --certify`).
 *
 * Rational matrix.  The schemes' weights are rationals with small
 * denominators, but ss_local reads S in double precision.  Each entry s is
 * replaced by the rational p/q with q <= maxden nearest to it, accepted only if
 * |s - p/q| <= 2^-40 max(1, |s|): two rationals of denominator <= maxden are
 * at least 1/maxden^2 apart, far more than that, so the rational matrix is
 * the unique one of bounded denominators the computed entries round to (the
 * default maxden = 2^18 keeps 1/maxden^2 = 2^-36 above the acceptance
 * window).  Every row must then sum to exactly 1.  A scheme with irrational
 * weights (Loop's cos(2 pi / n), box-spline boundary rules) fails this with
 * SS_ENUMERIC naming the entry: its verdicts cannot be certified this way.
 * What is certified is therefore a statement about that rational matrix.
 *
 * Spectrum.  S = [A 0; B C] and C is block lower triangular over the strongly
 * connected components of its sparsity graph, so the characteristic
 * polynomial of S is the product of those of A and of C's diagonal blocks
 * (equal blocks are computed once).  Each is computed exactly over Z
 * (multimodular, each row scaled by its own denominator: ss_exact_charpoly.c;
 * rebuilt as the polynomial of the block scaled by the common denominator
 * of its entries) and factored
 * into irreducibles over Q (fmpz_poly_factor); equal factors of different
 * blocks are merged, multiplicities added.  Distinct irreducible factors have
 * no common root and each has simple roots, so the distinct eigenvalues of S
 * are exactly the roots of the merged factors, with the multiplicity of their
 * factor.  Roots are isolated in ball arithmetic (Durand-Kerner and arb's
 * inclusion test, as arb_fmpz_poly_complex_roots on each squarefree factor,
 * but started from A's eigenvalues computed by LAPACK where each factor of
 * A gets its degree of them: ss_exact_isolate.c; the balls are accepted by
 * the same tests whatever the start) and refined until the moduli of all
 * roots that matter to the order are separated, or until maxprec bits.
 *
 * Lazy factoring (ss_exact_opts.lazy, what sweeps and check use): the
 * one-ring block's polynomial is split into its squarefree parts, the simple
 * part's linear factors are found from the block's LAPACK eigenvalues (each
 * candidate rational checked exactly) and divided out, and when the rest has
 * degree >= 12 it is kept whole, not proven irreducible (the degree-68
 * factor of an MLCA k = 14 link: FLINT's proof was 6-12 ms a case); the
 * other parts and blocks are factored as above (ss_exact_squarefree.c).
 * Such an unproven factor must have multiplicity 1 in S and no root in
 * common with any other factor (checked: gcds modulo a prime, exactly where
 * those do not decide), so that the roots stay distinct with their
 * multiplicities; then every step below holds for it (conjugates and
 * reflections are roots of the factors named, its roots are isolated as a
 * squarefree polynomial's), except what reads irreducibility: a root's
 * minimal polynomial (ss_exact_minpoly and ss_exact_root.degree give the
 * unproven factor), the non-defectiveness of a multiple root (none is
 * unproven), and exact moduli or reflections hidden inside it.  So the
 * result stands only when the condition is certified, no root among
 * lambda1..lambdam is an unproven factor's, and a pass has its basis;
 * otherwise ss_exact_new starts again with every factor FLINT's.  The
 * verdicts are those of the full factorisation (tests/analysis/
 * test_exact_lazy.c; certified sweeps before and after agree).
 *
 * Order: distinct roots by decreasing modulus, real before complex, larger
 * real part first, then larger imaginary part (ss_eig's order).  Two distinct
 * roots of equal modulus are tied exactly when that is proven: complex
 * conjugates (the conjugate of an isolated root is the one root of its
 * factor whose ball meets the conjugate ball), r and -r (a root of f and of
 * its reflection f(-x), found the same way), or equal exact |r|^2 (rational
 * for the roots of linear factors, of quadratics with complex roots (c0/c2)
 * and of cyclotomic factors (1)).  Any other pair whose modulus enclosures
 * still overlap at maxprec makes the order, and every verdict depending on
 * it, uncertified (e.g. the three roots of 27 x^3 - 2).  The order is proven
 * as far as the verdict needs it: every root other than 1 below 1, and each
 * of lambda1..lambdam above every later root.  Roots proven below lambda_m
 * are ordered among themselves by the midpoints of their modulus enclosures
 * where those overlap; tied_next is set only where equality is proven.
 *
 * The certified eigenvalue condition (m = 3 in volume cases, 2 on surfaces),
 * on the multiset of eigenvalues ordered as above:
 *   lambda0 = 1 simple: x - 1 is a factor of multiplicity 1 and every other
 *     root has modulus < 1 (proven; a root proven of modulus 1, such as -1
 *     or a root of unity, or of modulus > 1, is a certified fail);
 *   lambda1..lambdam real and positive (their factors' roots are real, proven
 *     by the real-root isolation, and > 0);
 *   lambda_m > |lambda_m+1|: proven by separated enclosures; lambda_m =
 *     lambda_m+1 (the same root, multiplicity > 1, from one factor) is a
 *     certified fail ("exact tie"), as is |lambda_m+1| = lambda_m proven for a
 *     different root (a conjugate pair, -lambda_m, an equal exact modulus);
 *   non-defective lambda1..lambdam: for each of their factors f with
 *     multiplicity e > 1, rank f(T) = |T| - e deg f, computed exactly (as
 *     the rank of the integer matrix D^deg f f(T), D the lcm of T's
 *     denominators), where T is the principal submatrix of S on the diagonal
 *     blocks (one-ring, outer components) lying on a path between blocks
 *     whose polynomial f divides.  Why T suffices: the blocks reachable from
 *     f's blocks span an invariant subspace holding every generalised
 *     eigenvector of f's roots, and its part not leading back to them is
 *     invariant and free of f's roots, so dividing it out keeps their
 *     Jordan structure; hence rank f(T) decides it exactly, including
 *     Jordan chains that couple copies of a root in different blocks
 *     (through the off-diagonal blocks).  When f divides one block only, T is
 *     that block.  A Jordan block is a certified fail ("defective"); a T
 *     larger than max_block leaves the verdict undecided ("not certified:
 *     non-defectiveness ... needs an exact rank on N points").
 * Each verdict carries certified = 1 when it follows from the above, 0 when
 * something could not be decided (then the verdict is SS_UNDECIDED with the
 * reason, e.g. "not certified: moduli of lambda3 and lambda4 not separated
 * at 4096 bits" or "not certified: an outer block of 900 points exceeds the
 * exact path's limit of 400"; in the latter case nothing is factored and
 * ss_exact_roots lists no roots).
 *
 * Basis.  For a certified pass, an enclosure of a real basis X (n x m) of the
 * invariant subspace of lambda1..lambdam: S X = X J exactly with J =
 * diag(lambda1..lambdam) (the pass proves them real and non-defective, so X
 * consists of eigenvectors).  Column j belongs to lambda_j+1.  For each
 * distinct lambda among them, whose factor must divide A's polynomial only
 * (if it also divides an outer block's, the basis is out of reach:
 * SS_ENUMERIC):
 *   - lambda rational: the nullspace of A - lambda over Q, extended to the
 *     outer points by exact block solves (C_cc - lambda) x_c = -B x1 - (the
 *     components before c); each column scaled to max |entry| = 1.  The same
 *     X is returned exactly by ss_exact_basis_rational when all of
 *     lambda1..m are rational;
 *   - lambda irrational: Rump's method on A (acb_mat_eig_enclosure_rump; for
 *     a simple root the same in real balls, ss_exact_rump.c),
 *     started from an approximate eigenspace (SVD of A - lambda in doubles,
 *     two steps of inverse iteration at the working precision) with the e
 *     best-conditioned rows frozen.  It proves A X = X J' with the
 *     eigenvalues of J' in a ball; that ball meeting no other root of A and
 *     the frozen e x e rows having a nonzero determinant make X a basis of
 *     lambda's eigenspace.  Extended by the same block solves in ball
 *     arithmetic (each diagonal block proven invertible); the precision is
 *     doubled up to maxprec if a step cannot be verified.
 * The enclosure is returned as intervals lo <= X <= hi, rounded outward to
 * doubles from balls of relative radius far below 2^-90 at the default
 * precision: each interval is at most 2 ulp wide (or, for an entry that is
 * zero or nearly, 2^-90 of its column's largest entry).
 *
 * Threads: no global state; FLINT's own caches are thread-local.  Call
 * flint_cleanup() per thread only at thread exit (the CLI does not).  FLINT
 * aborts on its own allocation failures; everything else is a status.
 *
 * Cost (bench_pipeline --phases --certify, MLCA vertex k = 12, 0.1 s per
 * case): the subdominant basis enclosure (Rump's method on A) about 0.025 s
 * (0.07 s in complex balls),
 * the characteristic polynomials and factorisation about 0.015 s; isolating
 * the roots of A's degree 50-60 factor 0.1 s from arb's generic start, 4 ms
 * from the eigenvalues. */
#ifndef SS_EXACT_H
#define SS_EXACT_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_eig.h"
#include "ss_error.h"

SS_BEGIN_DECLS

typedef struct ss_exact ss_exact; /* opaque: FLINT matrices, factors, balls */

/* Thread CPU seconds of the exact path's stages, added to (never reset) when
 * the options carry one (ss_exact_opts.times): where a certified case's time
 * goes, for benchmarks (bench_pipeline --phases --certify).  Timing reads
 * clocks only: no result depends on it. */
typedef struct {
  double rational; /* S reconstructed as rationals, row sums checked, the
                      outer block's components */
  double charpoly; /* the diagonal blocks' characteristic polynomials
                      (scaled to integers, fmpz_mat_charpoly) */
  double factor;   /* their factorisation over Q and the merged factors */
  double isolate;  /* root isolation in ball arithmetic: the first, and every
                      refinement (the order's and the basis's) */
  double decide;   /* the order and the condition without the refinements:
                      classes, comparisons, exact ranks (non-defectiveness) */
  double basis;    /* the subdominant basis enclosure without refinements */
  long cases;      /* exact spectra timed */
  double simil;    /* the verified similarity's pre-pass (ss_simil.h), whether
                      it passed or left the case to the exact path */
  long simil_tried, simil_passed; /* cases it ran on, and proved */
} ss_exact_times;

/* Options of the exact path. */
typedef struct {
  long maxden;           /* largest denominator of the rational reconstruction
                            (default 1 << 18) */
  long prec;             /* first working precision of the root balls, bits (128) */
  long maxprec;          /* precision at which separation gives up (4096) */
  int dim;               /* 3: volume condition (lambda1..3); 2: surface */
  size_t max_block;      /* largest diagonal block (one-ring or outer) whose
                            characteristic polynomial is computed (default 400);
                            larger: every verdict undecided, not certified */
  int basis;             /* nonzero: enclose the subdominant basis on a pass */
  int lazy;              /* nonzero: the one-ring block's simple part is not
                            proven irreducible where nothing needs it (below,
                            "Lazy factoring"); 0, the default: every factor
                            is fmpz_poly_factor's */
  ss_exact_times *times; /* NULL (the default), or where to add the stages'
                            thread CPU times (above); borrowed */
} ss_exact_opts;

/* One distinct eigenvalue of S. */
typedef struct {
  double re, im; /* midpoint of its enclosure */
  double rad;    /* radius of the enclosure: |true - (re + i im)| <= rad */
  int mult;      /* algebraic multiplicity in S */
  int degree;    /* degree of its minimal polynomial over Q */
  int factor;    /* index of that polynomial among the merged factors */
  int real;      /* 1 if proven real */
  int tied_next; /* 1 if its modulus is proven equal to the next root's */
} ss_exact_root;

/* Defaults for dimension dim (2 or 3). */
ss_exact_opts ss_exact_defaults(int dim);

/* The exact eigenstructure of S (n x n, row-major, leading n1 x n1 block
 * invariant as in ss_eig_new).  *out is owned by the caller (ss_exact_free).
 * Fails with SS_ENUMERIC when an entry is not a rational of bounded
 * denominator or a row does not sum to 1 (the message names the entry),
 * SS_EINPUT for a malformed S or options, SS_ENOMEM.  A block beyond
 * max_block or roots not separated at maxprec are not failures: the verdict
 * says so.  Cost: dominated by the characteristic polynomial of A,
 * O(n1^4) big-integer operations, and its factorisation. */
ss_status ss_exact_new(const double *S, size_t n, size_t n1, const ss_exact_opts *o,
                       ss_exact **out, ss_error *err);

/* Free; NULL is a no-op. */
void ss_exact_free(ss_exact *x);

/* The certified eigenvalue condition: verdict, reason and *certified (1 if the
 * verdict is proven, 0 if it is SS_UNDECIDED for want of proof). */
void ss_exact_condition(const ss_exact *x, ss_verdict *v, int *certified);

/* The distinct eigenvalues in the order above: *nroots of them, valid while x
 * lives. */
const ss_exact_root *ss_exact_roots(const ss_exact *x, size_t *nroots);

/* The minimal polynomial of root r as text ("8*x^2 - 6*x + 1"), into buf of
 * size len (truncated with "..." if longer).  Returns buf. */
char *ss_exact_minpoly(const ss_exact *x, size_t r, char *buf, size_t len);

/* Enclosure of the subdominant basis (see above): lo, hi receive n * m values,
 * column-major (column j = basis vector j, rows in S's order).  SS_EINPUT if
 * the condition is not a certified pass or the basis was not requested;
 * SS_ENUMERIC if a leading eigenvalue is also one of an outer block, or
 * Rump's method or a block solve could not be verified at maxprec (then
 * nothing about regularity can be certified; the message says which). */
ss_status ss_exact_basis(const ss_exact *x, double *lo, double *hi, ss_error *err);

/* When lambda1..m are all rational, the basis is rational too: if every
 * entry of an exact basis (the same X as ss_exact_basis encloses, or another
 * basis of the same subspace) has numerator and denominator fitting in int64,
 * fill num and den (n * m each, column-major, den > 0) and return 1; else
 * (also without a certified basis) return 0 and leave them unspecified.
 * The basis is the one ss_exact_basis encloses: the eigenvectors, each
 * scaled to a largest |entry| of 1. */
int ss_exact_basis_rational(const ss_exact *x, long long *num, long long *den);

/* The reconstructed entry S[i][j] = *p / *q in lowest terms (q > 0; 0/1
 * where S is 0): the rational matrix every certified statement is about.
 * Returns 1, or 0 if i or j is out of range. */
int ss_exact_entry(const ss_exact *x, size_t i, size_t j, long long *p, long long *q);

/* The rational of denominator at most maxden nearest to s, accepted under the
 * rule above (|s - p/q| <= 2^-40 max(1, |s|)): 1 with *p / *q in lowest
 * terms (q > 0), else 0.  The same reconstruction ss_exact_new applies to S,
 * for callers that need other rows of the rule exactly. */
int ss_exact_rational(double s, long maxden, long long *p, long long *q);

/* As ss_exact_rational, the rational p / q as an interval [*lo, *hi] of
 * doubles holding it (outward rounded; a point when p / q is a double):
 * 1, or 0 when s is not accepted (or p or q is not below 2^53). */
int ss_exact_rational_enclose(double s, long maxden, double *lo, double *hi);

SS_END_DECLS

#endif
