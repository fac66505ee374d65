/* ss_report_ref.h — values the papers quote (data/reference/ files, one TSV
 * per paper) and the rule that compares them with computed results (`subspectra
 * reproduce`).
 *
 * A reference file is UTF-8 text, one quoted value per line, ten fields
 * separated by tabs; lines starting with '#' and blank lines are comments:
 *
 *   paper      the name of the paper's text (the texts are not in the
 *              repository; docs/references.bib cites the papers)
 *   location   table, figure, section or equation of the quote
 *   scheme     scheme name (ss_scheme.h): mlca, tetoct, boxspline, ...
 *   case       vertex, edge, face or surface-vertex
 *   range      the cases it speaks of: "A..B" or "A" = the link's vertex count
 *              k (vertex) or the valence n (edge, surface-vertex); "-" (face);
 *              either may end in ":LABEL" (a configuration the paper names,
 *              e.g. "8:8(a)" for its table row 8(a)): then the row speaks only
 *              of a case that a table labels LABEL (`reproduce`, source list)
 *   diagonals  "-" (any, or none read) or bfs, proper, skew, center
 *   quantity   lambdaI (I = 1..15: the real eigenvalue lambda_I after
 *              lambda0 = 1), multI (size of lambda_I's group of equal
 *              eigenvalues), two_ring, one_ring (matrix sizes), verdict (both
 *              conditions), eigen_condition, regularity; links (how many links
 *              with k in the range a table of every link enumerates: compared
 *              once per table); jsr_threshold, jsr_verdict and jsr_rhoI (the
 *              joint spectral radius test's threshold, verdict and rho^[I] =
 *              max ||Y_w||_inf^(1/I) over the words of length I = 1..15:
 *              compared only by the JSR tables, ss_cli_reproduce_jsr)
 *   value      the quoted value as compared: a decimal as printed ("0.4101"),
 *              an exact fraction or integer ("1/2", "2"), a closed form
 *              linear in k or n ("5k-5", "2n+3"), a bound (">1/4") or a
 *              verdict (pass, fail, undecided)
 *   quote      the exact text of the paper that states it
 *   note       how the quote is read (e.g. "closed form, evaluated per k")
 *
 * Match rule: a decimal matches when |computed - quoted| <= half a unit in
 * its last printed digit; exact values (fractions, integers given as
 * fractions or formulas) within SS_REF_EXACT_TOL; a bound when the computed
 * value satisfies it strictly; a verdict when equal. */
#ifndef SS_REPORT_REF_H
#define SS_REPORT_REF_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_local.h"

SS_BEGIN_DECLS

#define SS_REF_EXACT_TOL 1e-9 /* absolute tolerance for exact quoted values */

/* One quoted value (one line of a reference file).  Strings are owned. */
typedef struct {
  char *file;        /* the reference file it was read from */
  long line;         /* its line number there (1-based) */
  char *paper;       /* field 1 */
  char *location;    /* field 2 */
  char *scheme;      /* field 3 */
  ss_case_kind kind; /* field 4 */
  int lo, hi;        /* field 5: k or n range, inclusive (face: 0, 0) */
  char *label;       /* field 5 after ':': the configuration's label, or NULL */
  char *diagonals;   /* field 6: "-" or a diagonal mode name */
  char *quantity;    /* field 7 */
  char *value;       /* field 8, as written */
  char *quote;       /* field 9 */
  char *note;        /* field 10 */
} ss_ref_row;

/* All quoted values read so far. */
typedef struct {
  ss_ref_row *row; /* n rows, in file and line order */
  size_t n;        /* number of rows */
  size_t cap;      /* allocated rows */
} ss_ref;

/* The kind of a quoted value once evaluated. */
typedef enum {
  SS_REF_NUMBER = 0, /* compare |computed - x| <= tol */
  SS_REF_GREATER,    /* compare computed > x */
  SS_REF_VERDICT     /* compare the verdict name */
} ss_ref_kind;

/* A quoted value evaluated for one case. */
typedef struct {
  ss_ref_kind kind; /* see above */
  double x;         /* number or bound */
  double tol;       /* NUMBER: half a unit in the last digit, or SS_REF_EXACT_TOL */
  int exact;        /* 1 for fractions and formulas, 0 for printed decimals */
  char verdict[16]; /* VERDICT: "pass", "fail" or "undecided" */
} ss_ref_value;

/* Read the reference file at path and append its rows to ref (which must be
 * zeroed before the first call).  SS_EIO when it cannot be read, SS_EINPUT
 * for a malformed line (message "FILE:LINE: problem"; ref is left with the
 * rows read before), SS_ENOMEM.  Linear in the file size. */
ss_status ss_report_ref_load(const char *path, ss_ref *ref, ss_error *err);

/* Release every row of ref and zero it.  NULL is a no-op. */
void ss_report_ref_free(ss_ref *ref);

/* Evaluate value text v (field 8) for a case with k (link vertices or
 * valence).  SS_EINPUT with a message when v is malformed. */
ss_status ss_report_ref_eval(const char *v, int k, ss_ref_value *out, ss_error *err);

/* 1 if the computed number c matches the evaluated quote q (NUMBER or
 * GREATER), else 0.  NaN never matches. */
int ss_report_ref_match(const ss_ref_value *q, double c);

/* 1 if the quantity name is one ss_report_ref_load accepts; *index receives
 * I for lambdaI, multI and jsr_rhoI (else 0). */
int ss_report_ref_quantity(const char *name, int *index);

/* 1 if row r speaks of the case (scheme, kind, k or valence, diagonal mode
 * name or NULL when the scheme reads none) of no label: a row with a label
 * speaks of none. */
int ss_report_ref_applies(const ss_ref_row *r, const char *scheme, ss_case_kind kind,
                          int k, const char *diagonals);

/* As ss_report_ref_applies for a case labelled label (or NULL): a row with a
 * label speaks only of a case with the same label, a row without one of
 * every case its other fields name. */
int ss_report_ref_applies_label(const ss_ref_row *r, const char *scheme,
                                ss_case_kind kind, int k, const char *diagonals,
                                const char *label);

SS_END_DECLS

#endif
