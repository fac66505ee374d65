/* ss_local_cost.h — what one case will cost, estimated from the scheme and
 * the case alone before anything is built (ss_local_estimate), and the
 * memory budget that refuses a case beyond it (ss_local_opts.max_bytes,
 * ss_local.h).  It needs the case (ss_case.h), nothing of the extraction.
 *
 * Rows.  The two-ring and one-ring of a vertex star are lattice points of the
 * cone over the link: the centre, m_v points on each of the k rays, m_e
 * inside each of the 3k - 6 link edges' sectors, m_t inside each of the
 * 2k - 4 triangles' cones; an edge star is the vertex star of the bipyramid
 * over n (k = n + 2; tet stars: its own counts per face), a surface star
 * n sectors.  Hence (k link vertices; n the valence):
 *   multilinear split (hexes):  vertex n2 = 30k - 55, n1 = 6k - 9
 *                               edge   n2 = 30n + 5,  n1 = 6n + 3
 *                               quads  n2 = 6n + 1,   n1 = 2n + 1
 *   tet/oct split (tets):       vertex n2 = 5k - 5,   n1 = k + 1
 *                               edge   n2 = 15n + 5,  n1 = 3n + 3
 *                               face   n2 = 85,       n1 = 19
 *                               triangles n2 = 3n + 1, n1 = n + 1
 *   quasi48 (two-pass step; r rays: n for class 4, n / 2 for class 8):
 *                               n2 = 19r + 1, n1 = 11r + 1
 *   box-spline rules (they read major diagonals): vertex as tet/oct; edge
 *     bfs n2 = ceil((29n + 9) / 2), n1 = ceil((5n + 5) / 2); skew
 *     n2 = 14n + 5, n1 = 2n + 3; center as tet/oct; face n2 = 81, n1 = 15.
 * Exact for the built-in schemes and stencil files of the same splits
 * (tests/analysis/test_local.c checks them against extracted matrices); a
 * stencil whose masks have zero weights may have a smaller support, and
 * then these are upper bounds.
 *
 * Memory (bytes; peak of the pipeline without --certify):
 *   base + P + max(2 D, D + E), base = 16 MB (the program), D = 8 n2^2 the
 *   dense S (extraction holds S read on two levels), P the refined patch =
 *   beta * (cells of the star), beta = beta0 * 8^lc * (4 if the rule reaches
 *   2 rings), lc = the level the centre is born on (0 vertex or surface, 1
 *   edge, 2 face), beta0 = 0.3 MB (hex), 0.125 MB (tet), 8 KB (quad), 4 KB
 *   (triangle), measured; E = 8 (2 n1^2 + 3 m^2 + 6 m + 2 b^2 + b (n2 - n1))
 *   for the eigen-solves (m = max(n1, b), b the largest outer block,
 *   estimated as 2d + 1 for hex vertices, d the largest link degree, 3k - 6
 *   for tet vertices, 2n + 1 for edges, 3 on surfaces, 5 for the face).
 *   Measured peaks lie within a factor 2 of the estimate (test_local checks
 *   a few cases).
 * Time: flops = 25 (n1^3 + (n2 - n1) b^2) for the dense block solves
 * (dgeevx with vectors and condition numbers) plus 4 n2^2 for reading S;
 * seconds = flops / 2e9 + P / 40 MB/s (refinement).  Rough: a guide for
 * progress reports, not a promise. */
#ifndef SS_LOCAL_COST_H
#define SS_LOCAL_COST_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_case.h"
#include "ss_error.h"
#include "ss_scheme.h"

SS_BEGIN_DECLS

/* The estimate of one case (formulas above). */
typedef struct {
  size_t n2;            /* rows of S (two-ring points) */
  size_t n1;            /* rows of the one-ring block A */
  size_t star_vertices; /* vertices of the star refined */
  size_t star_cells;    /* cells of the star */
  size_t block;         /* estimated largest outer block (<= n2 - n1) */
  double dense_bytes;   /* bytes of one dense copy of S: 8 n2^2 */
  double bytes;         /* estimated peak memory of the analysis, bytes */
  double flops;         /* estimated floating-point operations */
  double seconds;       /* rough wall-clock time on one core */
} ss_local_cost;

/* Estimate the cost of case c for scheme s (formulas above).  O(k) for a
 * vertex case (the link's degrees), O(1) otherwise; builds nothing.  SS_EINPUT
 * for cases the scheme does not support (as ss_case_star) or a vertex case
 * without a link. */
ss_status ss_local_estimate(const ss_scheme *s, const ss_case *c, ss_local_cost *out,
                            ss_error *err);

/* The default memory budget of one analysis, in bytes: half the physical
 * memory (sysconf; the machine is often shared), and at most 3/4 of RLIMIT_AS
 * and of RLIMIT_DATA when those are set (the program's own mappings need the
 * rest).  0 if none of these can be read. */
double ss_local_memory_budget(void);

/* SS_OK if the estimate k fits in budget bytes (budget <= 0: no limit);
 * otherwise SS_ENOMEM with the message "needs about N rows of S and ~X GB of
 * memory (more than the budget of Y GB)". */
ss_status ss_local_check_budget(const ss_local_cost *k, double budget, ss_error *err);

/* Human-readable size: "512 KB", "3.2 MB", "14.6 GB" into buf. */
const char *ss_local_bytes_text(double bytes, char *buf, size_t n);

SS_END_DECLS

#endif
