/* ss_cli_reproduce.h — what the files of `subspectra reproduce` share (not
 * installed; the command line's own).  One family per file:
 *   ss_cli_reproduce.c          the command: options, the loop over tables
 *   ss_cli_reproduce_spec.c     the tables and figures to make, read from
 *                               data/reproduce/tables.json
 *   ss_cli_reproduce_cases.c    the cases of a table, analysed
 *   ss_cli_reproduce_compare.c  each result beside the papers' quoted values
 *   ss_cli_reproduce_text.c     growing text buffers and the cells they share
 *   ss_cli_reproduce_md.c       NAME.md
 *   ss_cli_reproduce_tsv.c      NAME.tsv
 *   ss_cli_reproduce_jsonl.c    data/NAME.jsonl
 *   ss_cli_reproduce_figures.c  figures/NAME.png and figures/README.md
 *   ss_cli_reproduce_jsr.c      the joint-spectral-radius tables
 * A new kind of table is a new file of its own, called from
 * ss_cli_reproduce.c. */
#ifndef SS_CLI_REPRODUCE_H
#define SS_CLI_REPRODUCE_H

#include <stddef.h>

#include "ss_diag.h"
#include "ss_error.h"
#include "ss_local.h"
#include "ss_report_ref.h"
#include "ss_result.h"
#include "ss_scheme.h"

/* ---- the tables and figures (ss_cli_reproduce_spec.c) ---- */

/* Where a table's cases come from ("source" in the data file). */
typedef enum {
  SS_REPRODUCE_LINKS,    /* every link with lo..hi vertices (ss_enum_links order) */
  SS_REPRODUCE_RANDOM,   /* per k = lo..hi the first link of `enumerate random
                            --seed 1` */
  SS_REPRODUCE_VALENCES, /* edge or surface vertex of valence lo..hi */
  SS_REPRODUCE_FACE,     /* the one face case */
  SS_REPRODUCE_QUASI48,  /* surface vertices of valence lo..hi of 4-8 class 4,
                            then those of class 8 (even valences 6..hi); schemes
                            without classes run the same valences */
  SS_REPRODUCE_LIST      /* the links of the entry's "links", each labelled
                            (the configurations a paper names) */
} ss_reproduce_source;

/* Other schemes a table shows beside its own, at most. */
#define SS_REPRODUCE_MAXVS 2

/* One table: what `reproduce` computes and how it titles it. */
typedef struct {
  const char *name;        /* file stem: NAME.md, NAME.tsv, data/NAME.jsonl */
  const char *title;       /* Markdown title */
  const char *scheme;      /* scheme name */
  ss_case_kind kind;       /* case kind */
  ss_reproduce_source src; /* where the cases come from */
  int lo, hi;              /* k or valence range (0, 0 for the face) */
  ss_diag_mode diag;       /* major diagonals (schemes that read them) */
  int neig;                /* > 0: show lambda1..neig; 0: lambda1..m and |lambda_m+1| */
  int psi_depth;           /* > 0: psi judged on its polynomial pieces to box
                              depth psi_depth (ss_result_opts; vertex cases of
                              mlca and ccsolid), 0: not */
  const char *command;     /* the equivalent `analyze` commands */
  const char *note;        /* paragraph under the header, or NULL */
  const char *vs[SS_REPRODUCE_MAXVS]; /* other schemes run on the same cases and
                                         shown side by side (their results are
                                         not written separately) */
  int nvs;                            /* how many of vs are set */
  void *list;   /* source list: the "links" array (json_object, owned by the
                   spec's doc); NULL otherwise */
  size_t nlist; /* its number of links */
} ss_reproduce_table;

/* Item i < t->nlist of a table of source list: its label and its link (plantri
 * text or a name), pointing into the spec's doc. */
void ss_reproduce_list_item(const ss_reproduce_table *t, size_t i, const char **label,
                            const char **link);
/* The label of case i of table t (source list), NULL for other sources. */
const char *ss_reproduce_case_tag(const ss_reproduce_table *t, size_t i);

/* One picture of a characteristic map (those reports/README.md shows). */
typedef struct {
  const char *file;   /* DIR/figures/FILE */
  const char *scheme; /* scheme name */
  ss_case_kind kind;  /* case kind */
  const char *link;   /* vertex: link text or name; NULL otherwise */
  int n;              /* edge, surface vertex: valence */
  ss_diag_mode diag;  /* major diagonals */
  int force;          /* draw the would-be map when the condition fails */
} ss_reproduce_figure;

/* Every table and figure, in the order of the data file.  The strings point
 * into doc, which the spec owns. */
typedef struct {
  ss_reproduce_table *table;   /* ntables tables */
  size_t ntables;              /* their number */
  ss_reproduce_figure *figure; /* nfigures figures */
  size_t nfigures;             /* their number */
  void *doc;                   /* the parsed file (json_object), owner of the text */
} ss_reproduce_spec;

/* Read the tables and figures of `reproduce` from the JSON file at path
 * (format: data/reproduce/README.md) into *spec, which the caller frees with
 * ss_reproduce_spec_free.  SS_EIO when it cannot be read, SS_EINPUT naming
 * the file, the entry and the problem when it is not a valid spec (unknown
 * key, source, case kind, diagonal mode or scheme name left to the run),
 * SS_ENOMEM. */
ss_status ss_reproduce_spec_load(const char *path, ss_reproduce_spec *spec,
                                 ss_error *err);
/* Free what ss_reproduce_spec_load allocated; zeroes *spec. */
void ss_reproduce_spec_free(ss_reproduce_spec *spec);

/* ---- the cases of a table (ss_cli_reproduce_cases.c) ---- */

/* The results of one table, in case order. */
typedef struct {
  ss_result *r;     /* n results */
  size_t n;         /* number of results */
  size_t cap;       /* allocated */
  ss_result_opts o; /* how the cases are analysed (--certify) */
} ss_reproduce_results;

/* Analyse every case of table t under scheme s (which may be t's scheme or
 * one of t->vs) as ss_result_compute does, appending to out (whose o is set
 * by the caller).  Errors: those of ss_result_compute, SS_ENOMEM. */
ss_status ss_reproduce_cases(const ss_reproduce_table *t, const ss_scheme *s,
                             ss_reproduce_results *out, ss_error *err);
/* Clear every result and free the list; zeroes *l (o too). */
void ss_reproduce_results_free(ss_reproduce_results *l);

/* ---- comparison with the quoted values (ss_cli_reproduce_compare.c) ---- */

/* One quoted value beside the computed one. */
typedef struct {
  size_t row;            /* index of the result; SS_REPRODUCE_TABLE_ROW for a
                            value about the whole table (quantity links) */
  const ss_ref_row *ref; /* the quoted value */
  int note;              /* its footnote number (1-based) */
  char quoted[64];       /* as shown: value, "= x" for formulas */
  char computed[64];     /* our value */
  char diff[32];         /* computed - quoted, or "–" */
  char tol[32];          /* the tolerance applied */
  char what[48];         /* the case in words when it is not row's label: a
                            labelled case ("k = 8, 8(a)"), a count ("k = 4..7"),
                            else empty */
  int match;             /* 1 match, 0 differ */
} ss_reproduce_cmp;

/* The row of a comparison about the whole table. */
#define SS_REPRODUCE_TABLE_ROW ((size_t)-1)

/* Counts for the summary line. */
typedef struct {
  size_t cases, pass;   /* cases, of which pass both conditions */
  size_t quoted, match; /* quoted values compared, of which match */
  size_t unquoted;      /* cases with no quoted value */
  size_t certified;     /* cases whose verdict is proven (ss_result_certified) */
} ss_reproduce_tally;

/* Every comparison of one table. */
typedef struct {
  ss_reproduce_cmp *c;     /* n comparisons, by row then reference order */
  size_t n;                /* their number */
  size_t cap;              /* allocated */
  const ss_ref_row **used; /* nused footnotes (into the ss_ref), in order of
                              first use */
  size_t nused;            /* their number */
  int *row_status;         /* per result: 0 not quoted, 1 all match, 2 a differ */
} ss_reproduce_cmps;

/* Compare every result of l (table t) with every quoted value of ref that
 * speaks of it (ss_report_ref_applies; the JSR rows are the JSR tables'),
 * into *out, and count them in *ty (both overwritten; free out with
 * ss_reproduce_cmps_free, even on failure).  The pointers into ref stay
 * valid while ref does.  Errors: SS_EINPUT for a quoted value that does not
 * evaluate, SS_ENOMEM. */
ss_status ss_reproduce_compare(const ss_reproduce_table *t, const ss_reproduce_results *l,
                               const ss_ref *ref, ss_reproduce_cmps *out,
                               ss_reproduce_tally *ty, ss_error *err);
void ss_reproduce_cmps_free(ss_reproduce_cmps *c);

/* ---- text (ss_cli_reproduce_text.c) ---- */

/* A growing buffer of text. */
typedef struct {
  char *s;    /* the text, NUL-terminated once anything was written */
  size_t n;   /* its length */
  size_t cap; /* allocated bytes */
} ss_strbuf;

/* Append printf-style text; 0, or -1 on allocation failure (the text written
 * so far is kept). */
int ss_sb_printf(ss_strbuf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Markdown cell text: a bar would end the cell, so it is escaped. */
void ss_sb_cell(ss_strbuf *b, const char *s);
/* A verdict as a Markdown cell: name, ✓ when certified, (reason). */
void ss_sb_verdict(ss_strbuf *b, const ss_verdict *v, int certified);
/* b into the file at path, whole or not at all (ss_outfile.h). */
ss_status ss_sb_write_file(const char *path, const ss_strbuf *b, ss_error *err);
/* Whether eigenvalue v is real (|im| <= 1e-12 |re|). */
int ss_reproduce_is_real(const ss_result_eigval *v);
/* v as text: "%.6f" when real, else "%.4f%+.4fi". */
void ss_reproduce_eig_text(const ss_result_eigval *v, char *buf, size_t n);
/* The case of r in words ("k = 5", "face", "n = 6, class 8", "n = 3"), in
 * buf; returns buf. */
const char *ss_reproduce_case_label(const ss_result *r, char *buf, size_t n);

/* ---- the writers (ss_cli_reproduce_md.c, _tsv.c, _jsonl.c) ---- */

/* NAME.md of table t: header, one row per result of l, the counts per k for
 * exhaustive tables, the other schemes' results vs (t->nvs lists, in t->vs's
 * order; NULL when none) side by side, the quoted values and their sources.
 * The writers append to their buffer; the caller checks its s (NULL when
 * nothing could be allocated). */
void ss_reproduce_md(ss_strbuf *md, const ss_reproduce_table *t,
                     const ss_reproduce_results *l, const ss_reproduce_results *vs,
                     const ss_reproduce_cmps *cmp, const ss_reproduce_tally *ty);
/* NAME.tsv of table t: a commented header with the summary, then one line per
 * comparison and per row with none. */
void ss_reproduce_tsv(ss_strbuf *tsv, const ss_reproduce_table *t,
                      const ss_reproduce_results *l, const ss_reproduce_cmps *cmp,
                      const ss_reproduce_tally *ty);
/* data/NAME.jsonl of table t: one JSON object per result (keys as `analyze
 * --format json`). */
void ss_reproduce_jsonl(ss_strbuf *js, const ss_reproduce_table *t,
                        const ss_reproduce_results *l);

/* ---- the figures (ss_cli_reproduce_figures.c) ---- */

/* Draw every figure of spec into DIR/figures/ (as `subspectra draw
 * --no-caption`) and write their captions to DIR/figures/README.md.
 * Errors: those of the analysis and of drawing, SS_EIO, SS_ENOMEM; the
 * message names the file. */
ss_status ss_reproduce_figures(const ss_reproduce_spec *spec, const char *dir,
                               ss_error *err);

#endif
