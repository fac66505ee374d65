/* ss_report_table.h — tables of a results store (DESIGN sections 2 and 7):
 * the rows read from a store, the summary per (scheme identity, case kind, k),
 * and writers for GitHub Markdown, CSV (RFC 4180), LaTeX (booktabs) and JSON.
 *
 * Two tables:
 *   cases    one row per case: scheme, case kind, k (link vertices) or the
 *            valence n, cells around the centre, the canonical link (vertex
 *            cases), lambda1..lambda4 of the two-ring matrix (complex values
 *            as a+bi) with their multiplicities, the eigenvalue condition and
 *            the regularity of the characteristic map, each with its reason,
 *            the minimum scaled Jacobian, and the improper pairs of major
 *            diagonals when the scheme reads diagonals;
 *   summary  one row per (identity, kind, k): cases, pass, fail, undecided
 *            (the combined verdict, ss_result_verdict), the worst (smallest)
 *            minimum scaled Jacobian and the range of |lambda1|.
 * Markdown and LaTeX print eigenvalues with 6 decimals and state the relative
 * tolerance of the rows in a caption; CSV and JSON print every number with 17
 * significant digits, so that doubles read back bit for bit.
 *
 * Library code: the writers print to the FILE the caller passes and nothing
 * else; failures come back as ss_status with a message. */
#ifndef SS_REPORT_TABLE_H
#define SS_REPORT_TABLE_H

#include <stdio.h>

#include <json-c/json.h>

#include "ss_api.h"
#include "ss_store.h"

SS_BEGIN_DECLS

/* One case, copied out of the store. */
typedef struct {
  char *scheme;   /* scheme name (owned) */
  char *identity; /* scheme identity, ss_store_identity (owned) */
  ss_result r;    /* the result; r.link is owned */
} ss_report_row;

/* A growing array of rows.  Zero-initialise ({0}) for an empty set; release
 * with ss_report_rows_clear. */
typedef struct {
  ss_report_row *row; /* n rows, in the order they were added */
  size_t n;           /* rows in use */
  size_t cap;         /* rows allocated */
} ss_report_rows;

/* The summary of the cases of one (identity, kind, k). */
typedef struct {
  const char *identity;  /* scheme identity (borrowed from the rows) */
  const char *scheme;    /* scheme name (borrowed from the rows) */
  ss_case_kind kind;     /* case kind */
  int k;                 /* link vertices, valence, or 0 (face) */
  size_t cases;          /* cases in the group */
  size_t pass;           /* of which pass all three verdicts (ss_result_verdict) */
  size_t fail;           /* of which fail one */
  size_t undecided;      /* the rest */
  size_t certified;      /* cases whose combined verdict is proven
                            (ss_result_certified; --certify) */
  size_t no_map;         /* cases without a characteristic map (NaN) */
  double worst_sj;       /* smallest minimum scaled Jacobian; NaN if none */
  double l1_min, l1_max; /* range of |lambda1| over the group; NaN if none */
} ss_report_summary;

/* Output formats. */
typedef enum {
  SS_REPORT_MD = 0, /* GitHub Markdown */
  SS_REPORT_CSV,    /* RFC 4180: CRLF line ends, quoted when needed */
  SS_REPORT_TEX,    /* LaTeX with booktabs rules: a longtable and a float */
  SS_REPORT_JSON    /* {"cases": [...], "summary": [...]} */
} ss_report_format;

/* Which tables to write (a bit set). */
enum {
  SS_REPORT_CASES = 1,   /* the per-case table */
  SS_REPORT_SUMMARY = 2, /* the per-(identity, kind, k) summary */
  SS_REPORT_BOTH = 3     /* both */
};

/* Copy row (all strings duplicated) to the end of t.  SS_ENOMEM (t is left
 * as it was). */
ss_status ss_report_rows_append(ss_report_rows *t, const ss_store_row *row,
                                ss_error *err);

/* Append every row of st that satisfies where (an SQL expression over the view
 * `cases`, or NULL for all) to t, ordered by identity, kind (vertex, edge,
 * face, surface-vertex, as the summary), k and link.  Errors as ss_store_each (SS_EINPUT
 * for a bad expression, SS_EIO, SS_ENOMEM); on failure t holds the rows read before it.
 */
ss_status ss_report_rows_load(ss_store *st, const char *where, ss_report_rows *t,
                              ss_error *err);

/* Free every row and zero t.  NULL is a no-op. */
void ss_report_rows_clear(ss_report_rows *t);

/* The summary of rows[0..n): one entry per distinct (identity, kind, k),
 * sorted by identity, kind (vertex, edge, face, surface-vertex) and k.
 * *out (malloc'd, free with free(); NULL when n = 0) borrows its strings from
 * rows, so rows must outlive it.  O(n log n).  SS_ENOMEM. */
ss_status ss_report_summarize(const ss_report_row *rows, size_t n,
                              ss_report_summary **out, size_t *nout, ss_error *err);

/* The smallest and largest tolerance of rows[0..n) (both NaN when n = 0). */
void ss_report_tol_range(const ss_report_row *rows, size_t n, double *lo, double *hi);

/* Parse a format name ("md", "csv", "tex", "json"); -1 if unknown, else 0. */
int ss_report_format_parse(const char *name, ss_report_format *fmt);

/* Parse a table choice ("cases", "summary", "both") into a bit set of
 * SS_REPORT_CASES and SS_REPORT_SUMMARY; -1 if unknown, else 0. */
int ss_report_tables_parse(const char *name, unsigned *tables);

/* Write the tables chosen by `tables` (SS_REPORT_CASES, SS_REPORT_SUMMARY or
 * both) of rows[0..n) and their summary sum[0..ns) (ss_report_summarize) to f
 * in format fmt.  LaTeX: the cases table is a longtable (needs the packages
 * longtable and array besides booktabs), the summary a table float; they are
 * labelled tab:LABEL-cases and tab:LABEL-summary (label NULL: "subspectra";
 * only letters, digits, '-', '_', ':' and '.' keep it a valid label, which the
 * caller checks).  Empty inputs give empty tables (headers only; JSON empty
 * arrays).  CSV holds one table: SS_EINPUT when both are asked for.  SS_EIO
 * when writing to f fails; SS_ENOMEM. */
ss_status ss_report_table_write(FILE *f, ss_report_format fmt, unsigned tables,
                                const ss_report_row *rows, size_t n,
                                const ss_report_summary *sum, size_t ns,
                                const char *label, ss_error *err);

/* Write s to f as one CSV field (RFC 4180): quoted, with its quotes doubled,
 * when it holds a comma, quote or line break; as it is otherwise. */
void ss_report_csv_put(FILE *f, const char *s);

/* The kept eigenvalues of r as a JSON array of {"re", "im", "multiplicity"}
 * (the key names of `analyze --format json`); the caller owns it
 * (json_object_put). */
json_object *ss_report_eig_json(const ss_result *r);

/* A verdict as the JSON object {"verdict", "certified", "reason"} of
 * `analyze --format json` (DESIGN section 7).  The caller owns it and may
 * add keys. */
json_object *ss_report_verdict_json(const ss_verdict *v);

/* psi judged on its pieces as a result keeps it: {"verdict", "judged_on",
 * "covered", "uncovered", "pieces"} (the keys of analyze's regularity.psi
 * that a result keeps), or NULL (JSON null) when psi was not judged.  The
 * caller owns it. */
json_object *ss_report_psi_json(const ss_result_psi *p);

SS_END_DECLS

#endif
