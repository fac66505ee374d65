/* ss_limit.h — the limit volume of a hex mesh: point and Jacobian at parameters
 * (u, v, w) of a cell, for any scheme with the multilinear split whose rule
 * reads only the coarse cells holding a fine vertex's birth element
 * (ss_scheme_reach == 1: mlca, ccsolid and the averaging family) and which
 * is the tricubic B-spline on regular grids (checked by ss_limit_new).
 *
 * Why analysis/: the evaluator reads local subdivision matrices from the
 * scheme's global rule and eigen-decomposes them (LAPACK), like ss_local and
 * ss_eig; it is a consumer of the same machinery, not a new top level.
 *
 * Patches.  The limit on a cell c is determined by the control points of its
 * patch: c and every cell sharing a vertex with c.  Refining the patch once
 * gives, exactly as the whole mesh would, the patch of each of c's eight
 * children (a child's patch reads only the coarse cells at the corner it
 * sits at, all inside c's patch).  A patch is numbered canonically by a
 * breadth-first walk over face neighbours from c, every cell carrying the
 * frame its neighbour hands on across the shared face; its *key* (the framed
 * cells as vertex numbers) names its topology.  A patch is regular when it is
 * the 3x3x3 block of a grid (c's eight corners are interior vertices with
 * the octahedron link): then the limit is the tricubic B-spline of its 64
 * points (written here from the uniform cubic basis, not from the scheme).
 *
 * The walk.  Evaluate at x in c: while the patch is not regular, step into
 * the child holding x (bit a of the child = x_a >= 1/2; x <- 2x - bits), the
 * new patch's points being W times the old ones, W read from the rows of the
 * patch's refinement operator.  Every (key, child) transition is computed
 * once and cached with its W and the canonical frame of the child (the
 * smallest key over the 48 cube symmetries, the inherited frame first).
 * Runs: a transition that maps a key to itself in the inherited frame is
 * stationary (the child at an extraordinary vertex after one step, or the
 * left/right child along an extraordinary edge); a run of m equal steps is
 * W^m = V diag(lambda)^m V^-1, one eigen-solve per such transition (Stam's
 * idea), and m = infinity (a point exactly on the vertex, or an edge point
 * whose remaining digits vanish) is the projection on the eigenvalue 1.
 *
 * Cost per point (the finding, docs/methods.md "Limit evaluation"):
 *   - regular cells: O(1), the B-spline;
 *   - cells at an extraordinary vertex, the point in the cells around it:
 *     O(1) -- one step to level 1, one jump over the run, one step out, the
 *     B-spline (constant independent of the distance to the vertex);
 *   - near an extraordinary edge whose stationary halves factor as
 *     A_b (x) T (checked on the patch; MLCA's do): O(1) by the paper's
 *     eq. (1) -- the net summed along the edge with the cubic B-spline
 *     weights, copied into every layer, has the same limit at the edge's
 *     end, one jump away;
 *   - near any other extraordinary edge (Joy--MacCracken's do not factor:
 *     only the rows of the points on the edge differ): the walk follows the
 *     binary digits of the point; runs of equal digits are jumps, so the
 *     steps are bounded by the number of digit changes, at most about 53 per
 *     coordinate in double precision, each a K x K product (K ~ 100 patch
 *     points).  Bounded, not constant.
 * Boundary cells are walked the same way (the patch holds the boundary rule's
 * cells), and so are creased ones: vertex cells, segments and quads on the
 * hexes are the scheme's creases, and a patch carries (and its key names)
 * those holding a corner of its cell -- the only ones the rules for its
 * children's points read -- so every step applies the crease rules as a
 * global refinement would; a patch with one is never regular.  A point on the boundary
 * surface (or exactly on an extraordinary vertex or edge) never reaches a regular patch:
 * every double is dyadic, so once its binary digits have run out it is a corner of its
 * sub-cell, the fixed point of an infinite run.  Its Jacobian comes from that run's
 * eigenvectors: components with |lambda| < 1/2 have derivative 0 there,
 * those with lambda = 1/2 (real, or a pair 1/2 +- i eps: a double 1/2 split
 * by rounding) are linear along rays (their derivative is read from one more
 * evaluation per axis); any other |lambda| >= 1/2 (besides the constant 1),
 * or a Jordan block at 1/2, makes the parametric Jacobian unbounded or
 * undefined there: SS_ENUMERIC.
 *
 * Precision: patch points are kept relative to a point of the current
 * sub-cell (the rows of W sum to 1, so a shift commutes with every step);
 * their differences, of the size of the sub-cell, keep full relative
 * precision, and the Jacobian after m steps does not lose a factor 2^m.
 * Depth: the walk keeps 2^s times those points and the derivative map
 * divided by 2^s, rescaled by powers of 2 (exact) when the points fall below
 * 2^-256, and a jump forms lambda^m 2^s with the exponent apart, so that
 * nothing under- or overflows down to parameters of 2^-1074; a point or
 * Jacobian that is still not a finite double (it exceeds DBL_MAX) is
 * refused, SS_ENUMERIC.  The Jacobian is accurate normwise (to about 1e-13
 * of its largest entry); where its rows grow at different rates (across and
 * along an extraordinary edge) a small row carries that absolute error --
 * it is that much more sensitive to the mesh's coordinates (README).
 *
 * Defective eigenstructure (a run's W not diagonalisable to working accuracy:
 * condition of V above SS_LIMIT_MAXCOND, as MLCA's icosahedron vertex, where
 * 1/8 has a Jordan block): W^m is then formed from cached powers (at most 12
 * products): the translation from W^(2^i), the points' differences from the
 * powers of the difference map D ((W P)_r - (W P)_0 from P_r - P_0, the
 * eigenvalue 1 removed), stored scaled, so that differences of size
 * |lambda_2|^m keep their relative precision.  A Jacobian at such a run's
 * fixed point takes the eigenvalue-1/2 part by its spectral projector (null
 * spaces of W - I/2, by SVD); refused (SS_ENUMERIC with the reason) when 1/2
 * has a Jordan block or another |lambda| >= 1/2 -- never a silent wrong
 * point.
 *
 * Memory: the transitions of patches that only coarse cells have are kept
 * for the 64 most recent ones (and rebuilt when needed again); first use of
 * an irregular coarse cell costs about a millisecond (its canonical frame and
 * one refinement of its patch per child visited).
 *
 * Fields.  Scalar values stored per control point (density, stiffness: the
 * paper's "scalar properties") are subdivided by the same rules as the
 * coordinates (the schemes are linear and act on every coordinate alike), so
 * the walk carries a net of D = 3 + nf columns, every step, jump and
 * B-spline acting on each column alike: a field's limit value and its
 * derivatives in (u, v, w) come from the same weights as the point's.  A
 * field whose values are an affine function of the coordinates has that
 * function of the limit point as its limit (the rows of every step sum to 1).
 * Without fields asked the net has the 3 coordinates only, exactly as
 * before.  At a fixed point the components of the net are judged negligible
 * per column group (the coordinates together, each field alone: their units
 * differ); a field whose gradient is unbounded there refuses the point with
 * derivatives as the Jacobian does.
 *
 * The evaluator caches what it learns and is therefore not thread-safe: give
 * each thread its own. */
#ifndef SS_LIMIT_H
#define SS_LIMIT_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_cx.h"
#include "ss_error.h"
#include "ss_scheme.h"

SS_BEGIN_DECLS

typedef struct ss_limit ss_limit; /* opaque: the mesh, its adjacency and the caches */

/* Largest condition number ||V|| ||V^-1|| (1-norms, unit columns) of a run's
 * eigenvector matrix accepted before the run is declared defective. */
#define SS_LIMIT_MAXCOND 1e6
/* Most plain (non-jump) steps of one evaluation before it gives up. */
#define SS_LIMIT_MAXSTEPS 400

/* One evaluated point. */
typedef struct {
  double p[3];      /* the limit point */
  double jac[3][3]; /* with derivatives: rows d/du, d/dv, d/dw of p */
  int steps;        /* subdivision steps walked (a jump counts its run) */
  int products;     /* matrix products done (plain steps + jumps) */
} ss_limit_point;

/* Counters of what the caches hold. */
typedef struct {
  size_t keys;        /* distinct patch topologies met */
  size_t transitions; /* (key, child) transitions computed */
  size_t eigs;        /* eigen-decompositions computed (stationary runs) */
  size_t tensor;      /* extraordinary-edge patches found to factor (eq. (1)) */
  double matrix_s;    /* CPU seconds spent computing transitions: one
                         refinement step of a patch and its matrix W (the
                         direct-limit paper's "subdivision matrix" stage) */
  double eig_s;       /* CPU seconds spent in eigen-decompositions of W (its
                         "eigenstructure" stage) */
} ss_limit_stats;

/* An evaluator for the limit of `mesh` under scheme s.  The scheme is
 * borrowed (it must outlive the evaluator; schemes are immutable); the mesh
 * is copied.  SS_EINPUT when the mesh is not 3D, holds cells other than
 * hexahedra and creases on them (vertex cells, segments, quads the scheme
 * takes, each a corner, edge or face of a hex), has a face shared by more
 * than two cells, or the scheme does not
 * split hexes multilinearly with a reach-1 rule or is not the tricubic
 * B-spline on a regular grid; SS_ENOMEM.  O(cells). */
ss_status ss_limit_new(const ss_scheme *s, const ss_cx *mesh, ss_limit **out,
                       ss_error *err);

/* As ss_limit_new, with nf fields per vertex: fields[v * nf + i] is field i
 * at mesh vertex v (mesh->nv * nf values, copied; NULL when nf = 0).
 * SS_EINPUT besides ss_limit_new's reasons when a value is not finite (NaN
 * or infinite: its limit would spread it to every point of the patches
 * around) or fields is NULL with nf > 0.  The mesh has 3 coordinates; to
 * evaluate extra coordinates (a Medit 4th coordinate) as fields, pass them
 * here (the CLI does). */
ss_status ss_limit_new_fields(const ss_scheme *s, const ss_cx *mesh, size_t nf,
                              const double *fields, ss_limit **out, ss_error *err);

/* Free; NULL is a no-op. */
void ss_limit_free(ss_limit *L);

/* Number of fields per vertex (0 unless made by ss_limit_new_fields). */
size_t ss_limit_nfields(const ss_limit *L);

/* Number of cells (hexahedra) of the mesh. */
size_t ss_limit_ncells(const ss_limit *L);

/* What the caches hold. */
ss_limit_stats ss_limit_get_stats(const ss_limit *L);

/* Whether to evaluate near extraordinary edges whose stationary halves factor
 * as A_b (x) T (MLCA's do, Joy--MacCracken's do not) by the paper's eq. (1),
 * in constant time (on, the default), or by the generic digit walk (off: for
 * comparison; both give the same point). */
void ss_limit_set_tensor(ss_limit *L, int on);

/* The limit point of cell `cell` (0-based) at (u, v, w) in [0,1]^3 (u along
 * corner 0 -> 1, v along 0 -> 3, w along 0 -> 4; ss_cx.h), and with
 * `derivatives` the Jacobian, by the walk above.  SS_EINPUT for an unknown
 * cell, a parameter outside [0,1] or not finite, a walk that does not end
 * within SS_LIMIT_MAXSTEPS plain steps; SS_ENUMERIC for a fixed point whose
 * limit is not defined (eigenvalue 1 not simple), derivatives asked at a
 * fixed point where the parametric Jacobian is unbounded or undefined (see
 * above), or a result beyond the range of doubles; SS_ENOMEM.  The mesh's
 * cells are not checked for orientation (flat and folded ones are evaluated
 * as they are; the CLI refuses them). */
ss_status ss_limit_eval(ss_limit *L, size_t cell, double u, double v, double w,
                        int derivatives, ss_limit_point *out, ss_error *err);

/* As ss_limit_eval, and the fields' limits: f (ss_limit_nfields(L)
 * entries) receives their values and, with derivatives, df (as many rows;
 * may be NULL without derivatives) their derivatives d/du, d/dv, d/dw in the
 * cell's parameters, by the same walk (the fields go through the same
 * weights).  f NULL: no fields, exactly ss_limit_eval.  Errors as
 * ss_limit_eval (SS_ENUMERIC also when a field's derivatives are unbounded at
 * a fixed point). */
ss_status ss_limit_eval_fields(ss_limit *L, size_t cell, double u, double v, double w,
                               int derivatives, ss_limit_point *out, double *f,
                               double (*df)[3], ss_error *err);

/* The reference: the same point by repeated local subdivision of the actual
 * patch (refine, keep the child's patch, until it is regular; nothing cached,
 * no eigenvalues), at most max_depth steps (SS_ENUMERIC beyond: the point
 * lies on or within 2^-max_depth of an extraordinary vertex or edge).  This is
 * the paper's alternative [BHU10] and the benchmark's baseline.  Errors
 * otherwise as ss_limit_eval. */
ss_status ss_limit_eval_reference(ss_limit *L, size_t cell, double u, double v, double w,
                                  int derivatives, int max_depth, ss_limit_point *out,
                                  ss_error *err);
/* The reference with fields (f, df as ss_limit_eval_fields): the positions by
 * refining the patch as above, the fields by the rows of each step. */
ss_status ss_limit_eval_reference_fields(ss_limit *L, size_t cell, double u, double v,
                                         double w, int derivatives, int max_depth,
                                         ss_limit_point *out, double *f, double (*df)[3],
                                         ss_error *err);

/* The tricubic B-spline of a 4x4x4 net at (u, v, w) in [0,1]^3: net[i + 4j +
 * 16k] is the control point at grid position (i - 1, j - 1, k - 1), the cell
 * being [0,1]^3.  jac (may be NULL) receives rows d/du, d/dv, d/dw. */
void ss_limit_bspline(const double (*net)[3], double u, double v, double w, double p[3],
                      double jac[3][3]);

SS_END_DECLS

#endif
