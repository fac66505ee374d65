/* ss_report_case.h — one case's analysis as the JSON object of `analyze
 * --format json` (DESIGN section 7), for the command line and for programs
 * that use the library (the Python package reads it).
 *
 * Two levels: ss_report_case_json writes the object from the pieces an
 * analysis computed (the command line, which runs the pipeline itself to show
 * progress and check memory budgets); ss_report_analyze runs the pipeline of
 * `analyze` for one case and returns the JSON text, so that a caller gets the
 * same dictionary as the command line without it. */
#ifndef SS_REPORT_CASE_H
#define SS_REPORT_CASE_H

#include <stddef.h>

#include <json-c/json.h>

#include "ss_api.h"
#include "ss_certify.h"
#include "ss_charmap.h"
#include "ss_eig.h"
#include "ss_error.h"
#include "ss_local.h"

SS_BEGIN_DECLS

/* What one case's analysis produced, as analyze reports it.  Every pointer is
 * borrowed. */
typedef struct {
  const char *scheme;        /* the scheme's name */
  ss_case_kind kind;         /* the case as reported (edge-point for a vertex
                                judged as an edge) */
  const char *link;          /* vertex and edge-point: the canonical link in
                                plantri ASCII; else ignored */
  int k;                     /* vertex and edge-point: vertices of the link */
  int n;                     /* edge, surface vertex, edge-point: the valence */
  int neig;                  /* eigenvalues (and exact roots) listed at most */
  const ss_local *M;         /* the local matrix */
  const ss_eig *e;           /* its eigenstructure */
  const ss_regularity *reg;  /* the regularity verdict */
  const ss_charmap_inj *inj; /* the injectivity verdict */
  int diag_shown;            /* 1 if the scheme reads major diagonals (tet stars) */
  ss_diag_mode diag;         /* with diag_shown: the choice */
  size_t diag_pairs;         /* with diag_shown: adjacent cell pairs concerned */
  size_t diag_improper;      /* with diag_shown: of which improper */
  const ss_certified *cert;  /* the exact path's condition (certify), or NULL */
  const ss_exact *exact;     /* the exact spectrum, or NULL */
  json_object *eigenvectors; /* the "eigenvectors" value, or NULL; ownership
                                passes to the result */
  int cls48;                 /* quasi48 surface vertex: the 4-8 class analysed
                                (ss_local_class48), written as "class"; else 0 */
} ss_report_case;

/* The JSON object of `analyze --format json` for case c, into *out (the
 * caller's: json_object_put).  SS_ENOMEM. */
ss_status ss_report_case_json(const ss_report_case *c, json_object **out, ss_error *err);

/* Options of ss_report_analyze: those of `analyze` that change its output. */
typedef struct {
  double tol;      /* relative tolerance for equal eigenvalues (--tol; 1e-6) */
  int neig;        /* eigenvalues listed (--eigenvalues; 16) */
  int depth;       /* hex subdivision depth limit (--depth; SS_JAC_DEPTH) */
  int ring_levels; /* ring levels judged at most (--ring-levels) */
  int certify;     /* nonzero: the exact path too (--certify) */
} ss_report_analyze_opts;

/* The defaults of `analyze`. */
ss_report_analyze_opts ss_report_analyze_defaults(void);

/* Analyse case c of scheme s as `subspectra analyze --format json` does: a
 * vertex link put in canonical form (a bipyramid link that makes the vertex a
 * point on an edge judged as that edge, ss_local_edge_point), the local
 * matrix, its eigenstructure, the three verdicts (ss_certify_verdicts, proven
 * with o->certify), and the object of ss_report_case_json, written as plain
 * JSON text into *json (NUL-terminated, malloc'd, the caller frees it with
 * free).  c->link is not modified.  SS_EINPUT for a case the scheme does not
 * support or options out of range; the errors of the pipeline otherwise. */
ss_status ss_report_analyze(const ss_scheme *s, const ss_case *c,
                            const ss_report_analyze_opts *o, char **json, ss_error *err);

SS_END_DECLS

#endif
