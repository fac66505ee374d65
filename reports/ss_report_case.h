/* ss_report_case.h — one case's analysis as the JSON object of `analyze
 * --format json` (DESIGN section 7), for the command line and for programs
 * that use the library (the Python package reads it).
 *
 * Two levels: ss_report_case_json writes the object of a pipeline that ran
 * (ss_pipeline: the command line runs it itself, to show progress and check
 * memory budgets); ss_report_analyze runs the pipeline of `analyze` for one
 * case and returns the JSON text, so that a caller gets the same dictionary
 * as the command line without it. */
#ifndef SS_REPORT_CASE_H
#define SS_REPORT_CASE_H

#include <stddef.h>

#include <json-c/json.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_local.h"
#include "ss_pipeline.h"

SS_BEGIN_DECLS

/* The JSON object of `analyze --format json` for the case of pipeline p
 * (run through its verdicts stage), listing neig eigenvalues (and exact
 * roots), with eigenvectors (NULL, or the "eigenvectors" value, whose
 * ownership passes to the result) into *out (the caller's: json_object_put).
 * The regularity object is p->reg's: a forced map's (ss_pipeline.forced)
 * when there is one.  SS_EINPUT when p has not run that far; SS_ENOMEM. */
ss_status ss_report_case_json(const ss_pipeline *p, int neig, json_object *eigenvectors,
                              json_object **out, ss_error *err);

/* Options of ss_report_analyze: those of `analyze` that change its output. */
typedef struct {
  double tol;      /* relative tolerance for equal eigenvalues (--tol; 1e-6) */
  int neig;        /* eigenvalues listed (--eigenvalues; 16) */
  int depth;       /* hex subdivision depth limit (--depth; SS_JAC_DEPTH) */
  int ring_levels; /* ring levels judged at most (--ring-levels) */
  int certify;     /* nonzero: the exact path too (--certify) */
  int psi_depth;   /* psi itself judged on its pieces down to boxes of side
                      2^-psi_depth, 0..8; 0: the control net's verdicts only
                      (--psi-depth; SS_PSI_BOX_DEPTH) */
  int psi_tubes;   /* nonzero, with certify and psi_depth: the tubes round
                      the spokes proven too (--psi-tubes; 0) */
} ss_report_analyze_opts;

/* The defaults of `analyze`: psi judged (psi_depth SS_PSI_BOX_DEPTH), as the
 * command does unless told --psi-depth 0. */
ss_report_analyze_opts ss_report_analyze_defaults(void);

/* Analyse case c of scheme s as `subspectra analyze --format json` does: a
 * vertex link put in canonical form (a bipyramid link that makes the vertex a
 * point on an edge judged as that edge, ss_case_edge_point), the local
 * matrix, its eigenstructure, the three verdicts (ss_pipeline, proven with
 * o->certify), and the object of ss_report_case_json, written as plain
 * JSON text into *json (NUL-terminated, malloc'd, the caller frees it with
 * free).  c->link is not modified.  SS_EINPUT for a case the scheme does not
 * support or options out of range (psi_tubes without certify and psi_depth,
 * which the command refuses too); the errors of the pipeline otherwise. */
ss_status ss_report_analyze(const ss_scheme *s, const ss_case *c,
                            const ss_report_analyze_opts *o, char **json, ss_error *err);

SS_END_DECLS

#endif
