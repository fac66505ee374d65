/* ss_pipeline.h — one case through the whole analysis, once (DESIGN sections
 * 2, 5 and 10).
 *
 * The pipeline every command runs, in stages:
 *   case      the case as analysed (ss_case_resolve): a vertex link in
 *             canonical form (isomorphic or mirrored links then give results
 *             equal to the last bit: LAPACK's rounding depends on the order
 *             of rows), a link that makes the vertex a point on an edge of
 *             valence n (ss_case_edge_point) judged as that edge case, a
 *             quasi48 surface vertex's 4-8 class filled in;
 *   matrix    the local subdivision matrix (ss_local), and for schemes that
 *             read major diagonals the star's improper pairs (ss_diag);
 *   eigen     its eigenstructure and the eigenvalue condition (ss_eig);
 *   verdicts  the characteristic map, its regularity on the ring and its
 *             injectivity (ss_certify_verdicts), with certify the exact path
 *             too; with force and no map (the eigenvalue condition fails),
 *             the would-be map of the leading eigenvectors built and judged
 *             for a picture (forced = 1; it is NOT a characteristic map and
 *             changes no verdict); then, for a vertex with a map and a
 *             scheme with polynomial pieces (mlca, ccsolid), psi itself
 *             judged on them (ss_psi; with certify on the exact path's
 *             enclosure of its net, ss_psi_certify) and combined into the
 *             regularity and injectivity verdicts (ss_psi_apply; with
 *             certify only a proven verdict on psi decides).
 * `analyze`, `matrix`, `draw`, `reproduce` (tables and figures), `sweep`,
 * `check` (through ss_result) and the Python package (through
 * ss_report_analyze) all run it, so a case is judged the same way whatever
 * asks.  Hooks: progress (ss_progress), the memory budget (max_bytes: a case
 * whose estimate exceeds it fails with SS_ENOMEM before anything is built),
 * timing (ss_pipeline_times) and a workspace reused from case to case.
 *
 * Thread safety: no global state; pipelines of different cases may run
 * concurrently with one shared, read-only scheme (one workspace per thread). */
#ifndef SS_PIPELINE_H
#define SS_PIPELINE_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_case_resolve.h"
#include "ss_certify.h"
#include "ss_charmap.h"
#include "ss_eig.h"
#include "ss_exact.h"
#include "ss_local.h"
#include "ss_psi.h"
#include "ss_verdict.h"

SS_BEGIN_DECLS

/* How far a pipeline has run, or is to run. */
typedef enum {
  SS_PIPE_CASE = 0, /* the case as analysed */
  SS_PIPE_MATRIX,   /* + the local matrix and the diagonals */
  SS_PIPE_EIGEN,    /* + the eigenstructure and the eigenvalue condition */
  SS_PIPE_VERDICTS  /* + the characteristic map and the three verdicts */
} ss_pipeline_stage;

/* Thread CPU seconds of the stages, added to (never reset) when the
 * workspace carries one: where a case's time goes, for benchmarks (bench_pipeline
 * --phases).  Timing reads clocks only: no result depends on it. */
typedef struct {
  double canon;             /* the case: the link's canonical form and text */
  double extract;           /* the local matrix from the global rule, with the
                               first ring levels */
  double diagonals;         /* schemes reading major diagonals: their count */
  double eig;               /* LAPACK and the condition */
  ss_charmap_times charmap; /* the regularity and injectivity tests */
  double psi;               /* psi judged on its polynomial pieces (ss_psi),
                               with certify its enclosure from the exact
                               path's basis */
  double psi_prove;         /* of psi: the proof passes (ss_psi_certify) */
  double psi_spokes;        /* of psi: the spokes' classification */
  long cases;               /* cases timed */
} ss_pipeline_times;

/* Options of a pipeline. */
typedef struct {
  double tol;           /* relative tolerance for equal eigenvalues, in
                           (0, 0.1) (ss_eig; 1e-6) */
  int depth;            /* hex subdivision depth limit of the Jacobian
                           test, 0..12 (SS_JAC_DEPTH) */
  int ring_levels;      /* ring levels judged at most,
                           1..SS_LOCAL_MAXRING (ss_charmap_opts) */
  int certify;          /* nonzero: the exact path too (ss_certify) */
  int exact_lazy;       /* nonzero, with certify: factors proven irreducible
                           only where a verdict needs it
                           (ss_charmap_opts.exact_lazy: sweeps and check,
                           which store verdicts; analyze prints the factors
                           as minimal polynomials and keeps 0) */
  int force;            /* nonzero: the eigenvectors' basis even when the
                           eigenvalue condition fails (ss_eig_opts.force),
                           and a forced map built and judged for a
                           picture when there is no characteristic map */
  int psi_depth;        /* psi judged on its polynomial pieces down to boxes
                           of side 2^-psi_depth, 0..8 (SS_PSI_BOX_DEPTH for
                           analyze); 0, the default: not at all (the verdicts
                           are the control net's) */
  int psi_tubes;        /* nonzero, with certify and psi_depth: the tubes round
                           the spokes proven too (ss_psi_opts.tubes) */
  double max_bytes;     /* memory budget of the case (ss_local_opts);
                           <= 0: none */
  ss_progress progress; /* steps of the stages (default silent) */
} ss_pipeline_opts;

/* tol 1e-6, depth SS_JAC_DEPTH, the charmap's ring levels, psi not
 * judged (psi_depth 0), no certification, no force, no budget, silent. */
ss_pipeline_opts ss_pipeline_defaults(void);

/* The workspaces of one case's extraction and eigen-solve, reused from case
 * to case by one thread (a sweep holds one per thread), and where that
 * thread's stage times go.  Either workspace may be NULL (that step then
 * allocates per case). */
typedef struct {
  ss_local_workspace *local; /* ss_local_new_ws's scratch */
  ss_eig_workspace *eig;     /* ss_eig_new_ws's scratch */
  ss_pipeline_times *times;  /* NULL (ss_pipeline_workspace_new), or where to
                                add the stages' CPU times; borrowed */
} ss_pipeline_workspace;

/* Both workspaces, empty (they grow at first use), untimed; NULL when out of
 * memory.  Free with ss_pipeline_workspace_free (NULL is a no-op there). */
ss_pipeline_workspace *ss_pipeline_workspace_new(void);
void ss_pipeline_workspace_free(ss_pipeline_workspace *w);

/* One case and what the pipeline has computed of it.  Every pointer is
 * owned by the pipeline (ss_pipeline_free) and NULL until its stage ran. */
typedef struct {
  const ss_scheme *scheme; /* the scheme (borrowed) */
  ss_pipeline_opts opts;   /* the options (copied) */
  ss_pipeline_stage done;  /* the last stage run */
  ss_case_resolved c;      /* the case as asked, as analysed, as reported */
  ss_local *M;             /* matrix: the local subdivision matrix */
  int has_diag;            /* matrix: 1 if the scheme reads major diagonals
                              (tet stars) and they were counted */
  size_t pairs;            /* with has_diag: adjacent cell pairs concerned */
  size_t improper;         /* with has_diag: of which improper */
  ss_eig *e;               /* eigen: the eigenstructure */
  ss_charmap *cm;          /* verdicts: the characteristic map, or the forced
                              map (forced), or NULL without a map */
  ss_regularity reg;       /* verdicts: the regularity test (its verdict is
                              v.reg, unless forced: then the forced map's) */
  ss_charmap_inj inj;      /* verdicts: the injectivity test (its verdict is
                              v.inj's before psi's is combined in) */
  ss_psi_result psi;       /* verdicts: psi judged on its pieces (ran = 0 when
                              it was not: no map, not a vertex, no pieces,
                              psi_depth 0) */
  ss_exact *ex;            /* verdicts with certify: the exact spectrum, or
                              NULL when it could not be built */
  double exact_seconds;    /* verdicts with certify: the exact path's wall
                              clock */
  const char *route;       /* verdicts with certify: the route that decided
                              the condition (ss_certified.route), or NULL */
  int forced;              /* verdicts with force: 1 if cm is a forced map */
  ss_verdicts v;           /* verdicts: the eigenvalue condition (eigen: the
                              double-precision one), regularity, injectivity */
  double seconds;          /* wall clock of the stages run */
} ss_pipeline;

/* A pipeline for case c of scheme s (c's link is borrowed until the call
 * returns: the pipeline keeps its own canonical copy) with options o (NULL:
 * the defaults), run through the case stage (timed into w->times when w and
 * its times are given).  SS_EINPUT when an option is
 * out of range or the case is malformed (a vertex case without a link);
 * SS_ENOMEM.  Free with ss_pipeline_free. */
ss_status ss_pipeline_new(const ss_scheme *s, const ss_case *c, const ss_pipeline_opts *o,
                          ss_pipeline_workspace *w, ss_pipeline **out, ss_error *err);

/* Run the stages after p->done up to `until` (none when already there),
 * with scratch memory from w (NULL: allocated per case).  The results do not
 * depend on w, nor on whether the stages run in one call or several.  On
 * failure p keeps the stages that completed.  SS_EINPUT when the scheme does
 * not support the case; SS_ENOMEM (also a case beyond the memory budget);
 * SS_EINTERNAL, SS_ENUMERIC when extraction or LAPACK fail (a defect to
 * report, not a verdict). */
ss_status ss_pipeline_run(ss_pipeline *p, ss_pipeline_stage until,
                          ss_pipeline_workspace *w, ss_error *err);

/* ss_pipeline_new and ss_pipeline_run to `until` in one call; on failure
 * *out is NULL. */
ss_status ss_pipeline_compute(const ss_scheme *s, const ss_case *c,
                              const ss_pipeline_opts *o, ss_pipeline_stage until,
                              ss_pipeline_workspace *w, ss_pipeline **out, ss_error *err);

/* Free; NULL is a no-op. */
void ss_pipeline_free(ss_pipeline *p);

SS_END_DECLS

#endif
