/* ss_result.h — the whole analysis of one case, reduced to what a sweep
 * stores and a report prints (DESIGN sections 2, 5 and 7).
 *
 * The pipeline (ss_pipeline: case -> local matrix -> eigenstructure ->
 * verdicts) in one call, shared by `check`, `sweep` and `reproduce` so that
 * they judge a case exactly as `analyze` does.  A result owns no pointer into the
 * intermediate objects: it is a plain value (apart from the link text) that
 * can be written to the store and read back unchanged.
 *
 * Thread safety: no global state is touched; results for different cases may
 * be computed concurrently with one shared, read-only scheme. */
#ifndef SS_RESULT_H
#define SS_RESULT_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_charmap.h"
#include "ss_eig.h"
#include "ss_local.h"
#include "ss_pipeline.h"

SS_BEGIN_DECLS

#define SS_RESULT_NEIG 16 /* leading eigenvalues kept (lambda0 first) */

/* Analysis parameters that change a verdict; part of a result's identity. */
typedef struct {
  double tol;       /* relative tolerance for equal eigenvalues (ss_eig; 1e-6) */
  int depth;        /* hex subdivision depth limit of the Jacobian test (ss_jac) */
  int ring_levels;  /* ring levels regularity is judged on at most (ss_charmap) */
  int certify;      /* nonzero: the exact path too (ss_certify): every verdict
                       proven or undecided */
  int psi_depth;    /* psi judged on its polynomial pieces down to boxes of
                       side 2^-psi_depth, 0..8 (ss_pipeline_opts); 0: not */
  int psi_tubes;    /* nonzero, with certify and psi_depth: the tubes round
                       the spokes proven too (ss_pipeline_opts.psi_tubes) */
  double max_bytes; /* memory budget of one case (ss_local_opts): a case whose
                       estimate exceeds it fails with SS_ENOMEM before anything
                       is built; <= 0: none.  Not part of the identity: it
                       decides whether a case runs, never its verdict */
  int exact_full;   /* nonzero, with certify: every factor of the exact
                       spectrum proven irreducible (fmpz_poly_factor); 0, the
                       default: only where a verdict needs it
                       (ss_pipeline_opts.exact_lazy).  Not part of the
                       identity: the same verdicts (bench_pipeline --phases
                       --certify --exact-full compares the two) */
} ss_result_opts;

/* One eigenvalue as kept in a result. */
typedef struct {
  double re, im; /* the eigenvalue */
  int mult;      /* size of its group of equal eigenvalues (within tol) */
} ss_result_eigval;

/* psi judged on its polynomial pieces (ss_psi_result), as a result keeps it. */
typedef struct {
  int ran;                 /* 1 if psi was judged (psi_depth > 0, a vertex case of
                              a scheme with pieces); 0: not judged, or not
                              recorded (a store of schema 2), the rest zero */
  ss_verdict_kind verdict; /* psi's own verdict: pass, fail or undecided */
  double covered;          /* share of the ring proven of the ring's sign */
  double uncovered;        /* share left without a piece round the spokes */
  size_t pieces;           /* polynomial pieces judged */
} ss_result_psi;

/* The analysis of one case. */
typedef struct {
  ss_case_kind kind; /* vertex, edge, face, surface-vertex, or edge-point for
                        a vertex case whose link makes it a point on an edge
                        (ss_case_edge_point), judged as that edge */
  int k;             /* vertex and edge-point: vertices of the link; edge and
                        surface vertex: the valence n; face: 0 */
  int valence;       /* edge, surface vertex, edge-point: the valence n;
                        otherwise 0 */
  int cls;           /* quasi48 surface vertex: its 4-8 class (4 or 8, the
                        default filled in, ss_case_class48); otherwise 0 */
  char *link;        /* vertex: the canonical link in plantri ASCII; else an
                        empty string.  Owned (ss_result_clear) */
  size_t cells;      /* cells around the centre: 2k - 4 for a vertex, n for
                        an edge or surface vertex, 2 for a face */
  size_t two_ring;   /* rows of the local matrix S */
  size_t one_ring;   /* rows of its invariant block A */
  int neig;          /* eigenvalues kept: min(SS_RESULT_NEIG, two_ring) */
  ss_result_eigval eig[SS_RESULT_NEIG]; /* leading eigenvalues of S, by
                                           decreasing modulus (ss_eig order) */
  ss_verdicts v;                        /* the eigenvalue condition, regularity
                                           and injectivity of the characteristic
                                           map (ss_charmap_inj), each with its
                                           certified flag and what it was judged
                                           on (SS_ON_NOTHING: not judged, or not
                                           recorded by a store of schema 2) */
  ss_result_psi psi;                    /* psi on its pieces (psi.ran = 0: not) */
  double tol;                           /* the tolerance the condition used */
  int inj_degree;                       /* its degree about psi(p); 0 when not computed */
  double min_sj;              /* minimum scaled Jacobian (ss_charmap); NaN: no map */
  int depth;                  /* the hex depth limit used */
  int ring_levels;            /* the ring levels allowed (ss_charmap_opts) */
  int ring_level;             /* the ring level that decided the regularity verdict (the
                                 last judged if none did); -1 without a map */
  size_t centre_corner_folds; /* cells around p not of the ring's sign */
  int has_diag;               /* 1 if the scheme reads major diagonals (tet stars) */
  size_t pairs;               /* with has_diag: adjacent cell pairs they concern */
  size_t improper;            /* with has_diag: of which improper (ss_diag_improper) */
  double seconds;             /* wall-clock time the analysis took */
} ss_result;

/* Defaults: tol 1e-6, depth SS_JAC_DEPTH, 3 ring levels, no certification, psi
 * not judged (psi_depth 0), no memory budget. */
ss_result_opts ss_result_defaults(void);

/* Analyse case c of scheme s into *r (which need not be initialised; on
 * failure it is left cleared).  For a vertex case the link is put in canonical
 * form first, so isomorphic or mirrored links give equal results; a link that
 * makes the vertex a point on an edge of valence n (ss_case_edge_point) is
 * analysed as the edge case n and reported as kind edge-point.  Free the
 * link text with ss_result_clear.  SS_EINPUT when the scheme does not support
 * the case or an option is out of range; SS_EINTERNAL, SS_ENUMERIC when
 * extraction or LAPACK fail (a defect to report, not a verdict); SS_ENOMEM. */
ss_status ss_result_compute(const ss_scheme *s, const ss_case *c, const ss_result_opts *o,
                            ss_result *r, ss_error *err);

/* ss_result_compute with the scratch memory of the extraction and the
 * eigen-solve taken from w (NULL: allocated per case), and the stages timed
 * into w->times when set.  The result is the same bit for bit (only
 * r->seconds, a time, differs). */
ss_status ss_result_compute_ws(const ss_scheme *s, const ss_case *c,
                               const ss_result_opts *o, ss_pipeline_workspace *w,
                               ss_result *r, ss_error *err);

/* The result of a pipeline that ran its verdicts stage (ss_pipeline), with
 * o the options it ran with (their identity is kept in r), into *r (which
 * need not be initialised).  SS_EINPUT when p has not run that far;
 * SS_ENOMEM. */
ss_status ss_result_of_pipeline(const ss_pipeline *p, const ss_result_opts *o,
                                ss_result *r, ss_error *err);

/* Whether r is a vertex case, judged as a vertex or as an edge point: it
 * carries a link. */
static inline int ss_result_has_link(const ss_result *r) {
  return r->kind == SS_CASE_VERTEX || r->kind == SS_CASE_EDGE_POINT;
}

/* The verdicts combined: ss_verdicts_combined(&r->v). */
ss_verdict_kind ss_result_verdict(const ss_result *r);

/* Whether the combined verdict is proven (only with certify):
 * ss_verdicts_certified(&r->v). */
int ss_result_certified(const ss_result *r);

/* Release r's link text and zero r.  NULL is a no-op. */
void ss_result_clear(ss_result *r);

SS_END_DECLS

#endif
