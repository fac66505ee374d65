/* ss_cli_analyze.h — what `analyze`, `matrix` and `draw` share inside the
 * command line (private to cli/): their options, and the writers of one
 * analysed case (ss_cli_analyze_print.c: text, TSV, JSON; ss_cli_matrix.c:
 * Matrix Market; ss_cli_draw.c: pictures).  Each case runs through one
 * pipeline (ss_pipeline), so the three commands show the same numbers. */
#ifndef SS_CLI_ANALYZE_H
#define SS_CLI_ANALYZE_H

#include <stddef.h>

#include <json-c/json.h>

#include "ss_pipeline.h"
#include "ss_report_draw.h"

enum { FMT_TEXT = 0, FMT_JSON, FMT_TSV, FMT_MTX };

/* Options of analyze, matrix and draw. */
typedef struct {
  const char *cmd;          /* "analyze", "matrix" or "draw" */
  const char *scheme;       /* --scheme */
  const char *stencil;      /* --stencil FILE (instead of --scheme) */
  ss_case_kind kind;        /* which case option was given */
  int ncase;                /* how many case options were given */
  const char *link;         /* --vertex argument ("-" = standard input) */
  int n;                    /* --edge / --surface-vertex valence */
  double tol;               /* --tol */
  int neig;                 /* --eigenvalues: how many to print */
  int format;               /* FMT_* */
  int ring;                 /* matrix --ring 1|2 */
  const char *out;          /* matrix, draw: -o FILE */
  int depth;                /* --depth: hex subdivision limit of the Jacobian test */
  int ring_levels;          /* --ring-levels: ring levels judged at most */
  int certify;              /* --certify: the exact path too (ss_certify) */
  int psi_depth;            /* --psi-depth: psi judged on its polynomial pieces
                               down to boxes of side 2^-psi_depth (0: not) */
  int psi_tubes;            /* --psi-tubes: with --certify, the spokes' tubes
                               proven too */
  ss_report_draw_opts draw; /* draw: picture options */
  ss_diag_mode diag;        /* --diagonals: major diagonals of tet stars */
  int force;                /* draw --force: a map even when the condition fails */
  double max_memory;        /* --max-memory in bytes, 0: the default budget */
  int progress;             /* --progress: progress lines on stderr */
  int nvec;                 /* --eigenvectors K: export the K leading eigenpairs
                               (analyze: JSON; matrix: Matrix Market); 0: none */
  int left;                 /* matrix --left: the left eigenvectors */
  int nocaption;            /* draw --no-caption */
  int cls;                  /* --class 4|8: 4-8 class of a quasi48 surface
                               vertex; 0: ss_case_class48's default */
} ss_cli_analyze_opts;

/* The case's parameter as printed: the canonical link of a vertex or edge
 * point, "" for the face, else the valence ("N, 4-8 class C" for a quasi48
 * surface vertex, except in TSV, whose column stays a number). */
const char *ss_cli_case_param(const ss_cli_analyze_opts *o, const ss_pipeline *p,
                              char *buf, size_t n);

/* analyze's three formats of one case (p run through its verdicts).  JSON:
 * the object of ss_report_case_json on one line, with eigvec (NULL or the
 * "eigenvectors" value, whose ownership passes); the exit status. */
int ss_cli_print_json(const ss_cli_analyze_opts *o, const ss_pipeline *p,
                      json_object *eigvec);
void ss_cli_print_tsv(const ss_cli_analyze_opts *o, const ss_pipeline *p, int header);
void ss_cli_print_text(const ss_cli_analyze_opts *o, const ss_pipeline *p);

/* matrix: the local matrix (p run through its matrix stage), or with
 * --eigenvectors its K leading eigenpairs, in Matrix Market format to -o
 * FILE or standard output; the exit status. */
int ss_cli_write_mtx(const ss_cli_analyze_opts *o, const ss_pipeline *p);
int ss_cli_write_eigvec_mtx(const ss_cli_analyze_opts *o, const ss_pipeline *p);

/* analyze --eigenvectors K --format json: the "eigenvectors" value into
 * *out; 0, or the exit status after saying why not. */
int ss_cli_eigvec_json_of(const ss_cli_analyze_opts *o, const ss_pipeline *p,
                          const char *where, json_object **out);

/* draw: the picture of p's map (its verdicts stage run; with --force a
 * forced map when there is no characteristic map); the exit status: 0, 1
 * for a forced map or none to draw, 2 when writing fails. */
int ss_cli_draw_case(const ss_cli_analyze_opts *o, const ss_pipeline *p,
                     const char *where);

#endif
