/* ss_jsr_polytope.h — the invariant polytope method for an upper bound of the
 * joint spectral radius (Guglielmi and Protasov, "Exact computation of joint
 * spectral characteristics of linear operators", Found. Comput. Math. 13,
 * 2013; issue 18).  Used by ss_jsr.c for norm SS_JSR_NORM_POLYTOPE and by
 * AUTO; callable alone.
 *
 * Idea.  Let Pi = Y_{w_len} ... Y_{w_1} be a candidate spectrum-maximising
 * product, lambda = rho(Pi)^{1/len} and s = lambda (1 + eps).  If a bounded,
 * absolutely convex body P with nonempty interior satisfies Y_i P within s P
 * for every i, then its gauge ||x||_P is a norm with ||Y_i||_P <= s, so
 * rho(Y) <= s.  The method builds P as the absolutely convex hull of vertices:
 * the leading eigenvector v of Pi (every one, if the leading eigenvalue is
 * a semisimple multiple one) and its cyclic images
 * A_{w_t} ... A_{w_1} v (A_i = Y_i / s), the same for every short product
 * tied with Pi up to rounding, or within a relative `near` of it (found by
 * a bounded search; a tie, e.g. two maps of equal spectral radius, would
 * otherwise need about 1 / eps steps to be absorbed), then repeatedly the
 * images A_i x of
 * every new vertex x, keeping those not already inside the current hull
 * (membership: the linear programme min sum |c_k| s.t. sum c_k v_k = x, by
 * GLPK's dual simplex, warm started).  If no new vertex appears the body is
 * invariant ("closed").  When Pi is spectrum maximising and its leading
 * eigenvalue is simple and strictly dominant among the normalised products
 * (up to the slack eps), the hull closes after finitely many steps; when a
 * product beats lambda (1 + eps) it never closes.
 *
 * A complex leading eigenvalue mu = |mu| e^{i phi}, eigenvector a + i b: the
 * orbit of a under the normalised Pi turns in the real plane span(a, b) on
 * an ellipse, which no finite set of its points contains.  The real 2-plane
 * variant: the N points Re(e^{i pi k / N} (a + i b)), k = 0..N-1, of that
 * ellipse (their absolutely convex hull is a 2N-gon inscribed in it, and
 * contains the ellipse scaled by cos(pi / 2N)) with N the least integer with
 * cos(pi / 2N) >= (1 + eps)^{-len}, so that the normalised Pi maps the
 * polygon into itself (a near-candidate u: cos(pi / 2N) >= rho(Y_u) / s^|u|,
 * fewer points).
 *
 * Certification.  The n vertices delta e_l (delta > 0, the canonical basis)
 * are added first, so P contains the l1 ball of radius delta and
 * ||r||_P <= ||r||_1 / delta; they keep every membership LP feasible.  For
 * every vertex v_j and map i the LP's coefficients c (stored when the image
 * was tested; an image that became a vertex v_k has c = e_k) give, with the
 * residual r = Y_i v_j - s sum_k c_k v_k enclosed in ball arithmetic (arb,
 * 128 bits, from the exact double data),
 *   ||Y_i v_j||_P <= s sum |c_k| + ||r||_1 / delta,
 * and the maximum U over (i, j), rounded up, bounds ||Y_i||_P (gauge of a
 * convex hull: a point x = sum c_j v_j, sum |c_j| = ||x||_P, has
 * ||Y_i x||_P <= max_j ||Y_i v_j||_P ||x||_P), hence the joint spectral
 * radius.  The floating-point LPs decide only which vertices to keep; the
 * bound is a proof for the exact double inputs whatever the LP did.
 *
 * Limits: a vertex cap and a wall-clock limit; when either stops the method
 * the result says "not closed" with how far it got. */
#ifndef SS_JSR_POLYTOPE_H
#define SS_JSR_POLYTOPE_H

#include <stddef.h>

#include "ss_error.h"

typedef struct {
  double eps;          /* slack: the maps are Y_i / (lambda (1 + eps)); > 0 */
  size_t max_vertices; /* most vertices (the n ball vertices included) */
  double max_seconds;  /* wall-clock limit; <= 0: none */
  double delta;        /* radius of the l1 ball inside P (roots have unit
                          2-norm); > 0 */
  double near;         /* other candidates: the Lyndon words u searched with
                          rho(Y_u)^{1/|u|} >= lambda (1 - near) start roots
                          too (at most 32 words); in [0, 1) */
} ss_jsr_polytope_opts;

/* Defaults: eps 5e-4, 20000 vertices, 60 s, delta 1e-4, near 1e-9 (ties up
 * to rounding only). */
ss_jsr_polytope_opts ss_jsr_polytope_defaults(void);

typedef enum {
  SS_POLY_CLOSED = 0, /* invariant: upper is proven */
  SS_POLY_CAP = 1,    /* the vertex cap was reached */
  SS_POLY_TIME = 2,   /* the time limit was reached */
  SS_POLY_LP = 3,     /* an LP failed (GLPK did not report an optimum) */
  SS_POLY_ZERO = 4    /* rho(Pi) = 0: no candidate */
} ss_jsr_polytope_stop;

typedef struct {
  ss_jsr_polytope_stop stop; /* why it ended */
  double upper;              /* CLOSED: proven upper bound U of the joint
                                spectral radius (>= s); otherwise +inf */
  double lambda;             /* rho(Pi)^{1/len} (floating point) */
  double s;                  /* lambda (1 + eps), the normalisation */
  int complex_leading;       /* 1 if Pi's leading eigenvalue is not real
                                (the 2-plane variant ran) */
  size_t roots;              /* starting vertices (eigenvector points and
                                their cyclic images, not the ball) */
  int ties;                  /* other candidate words whose roots joined:
                                Lyndon words u of length <= T (all m + ...
                                + m^T <= min(2^16, 2e9 / n^3) words
                                searched) with
                                rho(Y_u)^{1/|u|} >= lambda (1 - near) */
  size_t vertices;           /* vertices at the end, ball included */
  size_t pending;            /* vertices whose images were not yet tested
                                when it stopped (0 when closed) */
  size_t lps;                /* membership LPs solved */
  int depth;                 /* generations: the longest product of the A_i
                                that made a vertex from a root (the word
                                length the method explored) */
  double max_out;            /* largest ||A_i x||_P met for an image outside
                                (1 < ...; 0 if none): above 1 + eps per step
                                hints that a product beats lambda */
  double seconds;            /* wall-clock time */
} ss_jsr_polytope_result;

/* Run the method for the m matrices Y[0..m-1] (n x n, row-major) from the
 * candidate word w[0..len-1] (indices 0..m-1, w[0] applied first); o = NULL
 * means the defaults.  *out is filled.  SS_EINPUT (message naming the
 * problem) for m or n < 1, n > 4096, len < 1, an index out of range, eps or
 * delta not positive and finite, max_vertices below n + 1 or above 2^25
 * (GLPK's column limit is 10^8); SS_ENUMERIC if LAPACK's eigenvalue
 * computation fails; SS_ENOMEM.  A limit is not an error: out->stop says
 * which.  Cost: an LP of n rows and 2 N columns per image (N the vertices so
 * far), m per vertex; then O(m N n^2) ball operations for the certificate;
 * memory O(N n + m N n).  GLPK has no error return for running out of
 * memory inside an LP: its error hook is set for the call and jumps out, so
 * that is SS_ENOMEM too, not an abort (the thread's GLPK environment is then
 * freed: glp_free_env).  GLPK prints nothing (its output is caught). */
ss_status ss_jsr_polytope(size_t m, size_t n, const double *const *Y, const int *w,
                          int len, const ss_jsr_polytope_opts *o,
                          ss_jsr_polytope_result *out, ss_error *err);

#endif
