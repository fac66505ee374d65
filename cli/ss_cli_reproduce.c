/* ss_cli_reproduce.c — `subspectra reproduce [--out DIR]`: regenerate every
 * table this project reproduces from the papers, each case beside the values
 * the papers quote (the TSV files of data/reference/, ss_report_ref.h) with the
 * difference and a match / differ / not quoted mark, the raw results as JSON
 * lines (DIR/data/), a TSV of the comparison per table, and the pictures of
 * characteristic maps (DIR/figures/).
 *
 * Every case is judged by ss_result_compute, as `analyze`, `check` and
 * `sweep` judge it. */
#include <errno.h>
#include <getopt.h>
#include <glob.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <gsl/gsl_rng.h>
#include <json-c/json.h>

#include "ss_charmap.h"
#include "ss_cli.h"
#include "ss_cli_reproduce_jsr.h"
#include "ss_diag.h"
#include "ss_eig.h"
#include "ss_enum.h"
#include "ss_link.h"
#include "ss_link_random.h"
#include "ss_local.h"
#include "ss_outfile.h"
#include "ss_report_draw.h"
#include "ss_report_ref.h"
#include "ss_report_table.h"
#include "ss_result.h"
#include "ss_scheme.h"

static const char cmd[] = "reproduce";

/* ---- the tables ---- */

typedef enum {
  SRC_LINKS,    /* every link with lo..hi vertices (ss_enum_links order) */
  SRC_RANDOM,   /* per k = lo..hi the first link of `enumerate random --seed 1` */
  SRC_VALENCES, /* edge or surface vertex of valence lo..hi */
  SRC_FACE,     /* the one face case */
  SRC_QUASI48   /* surface vertices of valence lo..hi of 4-8 class 4, then those
                   of class 8 (even valences 6..hi); schemes without classes
                   run the same valences */
} src_kind;

typedef struct {
  const char *name;    /* file stem: NAME.md, NAME.tsv, data/NAME.jsonl */
  const char *title;   /* Markdown title */
  const char *scheme;  /* scheme name */
  ss_case_kind kind;   /* case kind */
  src_kind src;        /* where the cases come from */
  int lo, hi;          /* k or valence range */
  ss_diag_mode diag;   /* major diagonals (schemes that read them) */
  int neig;            /* > 0: show lambda1..neig; 0: lambda1..m and |lambda_m+1| */
  const char *command; /* the equivalent `analyze` commands */
  const char *note;    /* paragraph under the header, or NULL */
  const char *vs;      /* other schemes run on the same cases and shown side by
                          side (their results are not written separately): one
                          name or several separated by commas, or NULL */
} table_spec;

#define RANDOM_CMD(S, D)                                                                 \
  "for k in $(seq 5 22); do subspectra enumerate random --vertices $k --samples 1 "      \
  "--seed 1 | subspectra analyze --scheme " S " --vertex -" D " --format json; done"

static const table_spec tables[] = {
    {"mlca-vertices-k4-8", "MLCA: every vertex one-ring with k ≤ 8 (at most 12 hexes)",
     "mlca", SS_CASE_VERTEX, SRC_LINKS, 4, 8, SS_DIAG_BFS, 0,
     "subspectra enumerate links --vertices 4..8 | subspectra analyze --scheme mlca "
     "--vertex - --format json",
     "Cells = hexes around the vertex (2k − 4). λ1..λ3 and \\|λ4\\| are the leading "
     "eigenvalues of the two-ring matrix after λ0 = 1. The one differing row is "
     "finding 1 of reports/README.md.",
     NULL},
    {"mlca-vertices-k9-10",
     "MLCA: every vertex one-ring with k = 9 and 10 (14 and 16 hexes)", "mlca",
     SS_CASE_VERTEX, SRC_LINKS, 9, 10, SS_DIAG_BFS, 0,
     "subspectra enumerate links --vertices 9..10 | subspectra analyze --scheme mlca "
     "--vertex - --format json",
     "Inside the range the MLCA paper says it analysed exhaustively (val ≤ 12 edges at "
     "the vertex, i.e. k ≤ 12), beyond what earlier versions of this project swept. "
     "Cells = hexes around the vertex (2k − 4). See reports/README.md, finding 5.",
     NULL},
    {"tetoct-vertices-k8-10", "tet/oct: every vertex one-ring with k = 8..10", "tetoct",
     SS_CASE_VERTEX, SRC_LINKS, 8, 10, SS_DIAG_BFS, 0,
     "subspectra enumerate links --vertices 8..10 | subspectra analyze --scheme tetoct "
     "--vertex - --format json",
     "Beyond the paper's tested links. Cells = tets around the vertex (2k − 4).", NULL},
    {"tetoct-vertices-k4-7", "tet/oct: every vertex one-ring with k ≤ 7", "tetoct",
     SS_CASE_VERTEX, SRC_LINKS, 4, 7, SS_DIAG_BFS, 0,
     "subspectra enumerate links --vertices 4..7 | subspectra analyze --scheme tetoct "
     "--vertex - --format json",
     "Cells = tets around the vertex (2k − 4).", NULL},
    {"tetoct-edges-3-10", "tet/oct: points on extraordinary edges, valence 3..10",
     "tetoct", SS_CASE_EDGE, SRC_VALENCES, 3, 10, SS_DIAG_BFS, 0,
     "for n in 3 4 5 6 7 8 9 10; do subspectra analyze --scheme tetoct --edge $n "
     "--format json; done",
     "The paper gives the spectrum the form 1, λ1, λ1, 1/2, … (Appendix A). It holds "
     "in that order from valence 6 on; for valences 3..5 the eigenvalue 1/2 (along the "
     "edge) comes first and the double pair is smaller, so those rows differ.",
     NULL},
    {"tetoct-face", "tet/oct: a point inside the face shared by two tets", "tetoct",
     SS_CASE_FACE, SRC_FACE, 0, 0, SS_DIAG_BFS, 9,
     "subspectra analyze --scheme tetoct --face --format json",
     "The face case of the paper's Appendix A (equation (3)). λ1..λ9 follow λ0 = 1.",
     NULL},
    {"mlca-edges-3-8", "MLCA: points on extraordinary edges, valence 3..8", "mlca",
     SS_CASE_EDGE, SRC_VALENCES, 3, 8, SS_DIAG_BFS, 0,
     "for n in 3 4 5 6 7 8; do subspectra analyze --scheme mlca --edge $n --format "
     "json; done",
     "Along an edge the spectrum is the tensor product of the 2D valence-n spectrum "
     "with the cubic B-spline curve's {1, 1/2, 1/4, 1/8, 1/8}: λ1 = λ2 is the 2D "
     "subdominant eigenvalue, and λ3 is the larger of the curve's 1/2 and the 2D "
     "eigenvalue pair of the second Fourier mode, (5 + cos(4π/n) + "
     "cos(2π/n)·√(2(9 + cos(4π/n))))/16, which is below 1/2 for n < 8, exactly 1/2 at "
     "n = 8 and above it (a double eigenvalue) for n > 8. So the eigenvalue condition "
     "λ3 > \\|λ4\\| holds only up to valence 7 — see reports/README.md, finding 2. The "
     "paper proves C¹ along edges by the tensor-product structure, not by this test, "
     "so nothing here is compared.",
     NULL},
    {"mlca-surface-vertices-3-8", "MLCA surfaces: extraordinary vertices, valence 3..8",
     "mlca", SS_CASE_SURFACE_VERTEX, SRC_VALENCES, 3, 8, SS_DIAG_BFS, 0,
     "for n in 3 4 5 6 7 8; do subspectra analyze --scheme mlca --surface-vertex $n "
     "--format json; done",
     "The 2D scheme of the MLCA paper, section 4.1: λ1, λ2 and \\|λ3\\| after λ0 = 1.",
     NULL},
    {"catmull-clark-surface-vertices-3-8",
     "Catmull–Clark surfaces: extraordinary vertices, valence 3..8", "catmull-clark",
     SS_CASE_SURFACE_VERTEX, SRC_VALENCES, 3, 8, SS_DIAG_BFS, 0,
     "for n in 3 4 5 6 7 8; do subspectra analyze --scheme catmull-clark "
     "--surface-vertex $n --format json; done",
     "The 2D baseline the MLCA paper compares with (section 4.1, after Reif and "
     "Peters).",
     NULL},
    {"boxspline-vertices-5-22",
     "box-spline solids: extraordinary vertices of valence 5..22", "boxspline",
     SS_CASE_VERTEX, SRC_RANDOM, 5, 22, SS_DIAG_BFS, 6, RANDOM_CMD("boxspline", ""),
     "One link per valence k (= \\|ρ\\| of the vertex, the number of its edges): the "
     "first random link with k vertices for seed 1 (the convex hull of k random points "
     "on the sphere). Major diagonals by Algorithm 2 (`--diagonals bfs`). Cells = tets "
     "around the vertex (2k − 4). λ1..λ6 follow λ0 = 1. The paper's Table 2 is "
     "withheld; its matrix sizes are compared.",
     NULL},
    {"boxspline-vertices-5-22-proper",
     "box-spline solids: extraordinary vertices of valence 5..22, proper diagonals",
     "boxspline", SS_CASE_VERTEX, SRC_RANDOM, 5, 22, SS_DIAG_PROPER, 6,
     RANDOM_CMD("boxspline", " --diagonals proper"),
     "The links of boxspline-vertices-5-22.md, with diagonals chosen by `--diagonals "
     "proper` (Algorithm 2's search made to match neighbours instead of avoiding them; "
     "not the paper's algorithm) instead of Algorithm 2: compare the improper-pair "
     "counts and the outer eigenvalues. λ1..λ6 follow λ0 = 1.",
     NULL},
    {"boxspline-edges-4-9-skew",
     "box-spline solids: extraordinary edges of valence 4..9, diagonals 'skew'",
     "boxspline", SS_CASE_EDGE, SRC_VALENCES, 4, 9, SS_DIAG_SKEW, 6,
     "for n in 4 5 6 7 8 9; do subspectra analyze --scheme boxspline --edge $n "
     "--diagonals skew --format json; done",
     "Major diagonals around the edge: skew — in every tet (v0, v1, c_i, c_i+1) the "
     "pair v0 c_i, v1 c_i+1, the same turn all round (the paper's figure 23, first "
     "row). λ1..λ6 follow λ0 = 1. The paper's Table 3 is withheld. Its edge matrix S_e "
     "(4k + 3 points) acts on the once-subdivided star of a finite edge; our two-ring "
     "is the support neighbourhood of a point on an edge in the stationary regime, a "
     "larger set, so the two-ring sizes differ while the one-ring blocks (2k + 3) "
     "agree.",
     NULL},
    {"boxspline-edges-4-9-center",
     "box-spline solids: extraordinary edges of valence 4..9, diagonals 'center'",
     "boxspline", SS_CASE_EDGE, SRC_VALENCES, 4, 9, SS_DIAG_CENTER, 6,
     "for n in 4 5 6 7 8 9; do subspectra analyze --scheme boxspline --edge $n "
     "--diagonals center --format json; done",
     "Major diagonals around the edge: toward the centre — the pair v0 v1, c_i c_i+1 "
     "in every tet (figure 23, second row). λ1..λ6 follow λ0 = 1. The two-ring sizes "
     "differ from the paper's S_e for the reason given in "
     "boxspline-edges-4-9-skew.md.",
     NULL},
    {"boxspline-avg-vertices-5-22",
     "averaged box-spline solids: extraordinary vertices of valence 5..22",
     "boxspline-avg", SS_CASE_VERTEX, SRC_RANDOM, 5, 22, SS_DIAG_BFS, 6,
     RANDOM_CMD("boxspline-avg", ""),
     "The links of boxspline-vertices-5-22.md (the first random link with k vertices "
     "for seed 1). The averaged scheme reads no diagonals. λ1..λ6 follow λ0 = 1. The "
     "paper (Appendix A) states no result for it at extraordinary points.",
     NULL},
    {"boxspline-avg-edges-4-9",
     "averaged box-spline solids: extraordinary edges of valence 4..9", "boxspline-avg",
     SS_CASE_EDGE, SRC_VALENCES, 4, 9, SS_DIAG_BFS, 6,
     "for n in 4 5 6 7 8 9; do subspectra analyze --scheme boxspline-avg --edge $n "
     "--format json; done",
     "No diagonals: one table replaces the two of boxspline. λ1..λ6 follow λ0 = 1.",
     NULL},
    {"ccsolid-vertices-k4-9",
     "Catmull–Clark solids: every vertex one-ring with k ≤ 9, beside MLCA", "ccsolid",
     SS_CASE_VERTEX, SRC_LINKS, 4, 9, SS_DIAG_BFS, 0,
     "subspectra enumerate links --vertices 4..9 | subspectra analyze --scheme ccsolid "
     "--vertex - --format json",
     "The Joy–MacCracken rules (README, \"Catmull–Clark solids\"); no paper tabulates "
     "them. Cells = hexes around the vertex (2k − 4). The second table puts the MLCA "
     "results for the same links beside them.",
     "mlca"},
    {"ccsolid-edges-3-10",
     "Catmull–Clark solids: points on extraordinary edges, valence 3..10, beside MLCA",
     "ccsolid", SS_CASE_EDGE, SRC_VALENCES, 3, 10, SS_DIAG_BFS, 0,
     "for n in 3 4 5 6 7 8 9 10; do subspectra analyze --scheme ccsolid --edge $n "
     "--format json; done",
     "Along an edge the spectrum is not the tensor product of the Catmull–Clark "
     "surface's and the cubic curve's: the modes that turn about the edge (w ≠ 0) are "
     "the tensor product's, the rotation-invariant ones differ for n ≠ 4 (README, "
     "\"Catmull–Clark solids\"). λ1..λ3 are 1/2 and the surface pair, as for MLCA, "
     "so the eigenvalue condition fails from valence 8 on in both.",
     "mlca"},
    {"quasi48-surface-vertices-3-16",
     "quasi 4–8 surfaces: vertices of valence 3..16, both 4–8 classes, beside Loop and "
     "Catmull–Clark",
     "quasi48", SS_CASE_SURFACE_VERTEX, SRC_QUASI48, 3, 16, SS_DIAG_BFS, 0,
     "for n in $(seq 3 16); do subspectra analyze --scheme quasi48 --surface-vertex $n "
     "--class 4 --format json; done; for n in 6 8 10 12 14 16; do subspectra analyze "
     "--scheme quasi48 --surface-vertex $n --class 8 --format json; done",
     "S maps two binary steps (a full 4–8 cycle, a dyadic step) of the topological "
     "4–8 refinement, which longest-edge bisection follows on 4–8 meshes (§2.3; README, "
     "\"Quasi 4–8 surfaces\"). Rows 1..14: vertices of class 4 (valence n, outer edges "
     "split first; n = 4 is regular), rows 15..20: class 8 (spokes alternate; even "
     "n ≥ 6; n = 8 is regular). A class-4 vertex of valence n is a class-8 vertex of "
     "valence 2n after one step, so row n = 3..8 of class 4 equals row 2n of class 8. "
     "The paper has only \"strong indications\" of C¹ and quotes no values: nothing "
     "is compared. Loop and Catmull–Clark run the same valences (the class is "
     "quasi48's only).",
     "loop,catmull-clark"},
};
#define NTABLES (sizeof tables / sizeof tables[0])

/* ---- the figures (those reports/README.md shows) ---- */

typedef struct {
  const char *file;   /* DIR/figures/FILE */
  const char *scheme; /* scheme name */
  ss_case_kind kind;  /* case kind */
  const char *link;   /* vertex: link text or name */
  int n;              /* edge, surface vertex: valence */
  ss_diag_mode diag;  /* major diagonals */
  int force;          /* draw the would-be map when the condition fails */
} figure_spec;

static const figure_spec figures[] = {
    {"mlca-vertex-k4.png", "mlca", SS_CASE_VERTEX, "tetrahedron", 0, SS_DIAG_BFS, 0},
    {"mlca-vertex-k5.png", "mlca", SS_CASE_VERTEX, "bipyramid:3", 0, SS_DIAG_BFS, 0},
    {"mlca-vertex-regular.png", "mlca", SS_CASE_VERTEX, "octahedron", 0, SS_DIAG_BFS, 0},
    {"mlca-vertex-k7-bipyramid.png", "mlca", SS_CASE_VERTEX, "bipyramid:5", 0,
     SS_DIAG_BFS, 0},
    {"mlca-vertex-k8-finding.png", "mlca", SS_CASE_VERTEX,
     "8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb", 0, SS_DIAG_BFS, 0},
    {"tetoct-vertex-k4.png", "tetoct", SS_CASE_VERTEX, "tetrahedron", 0, SS_DIAG_BFS, 0},
    {"tetoct-edge-3.png", "tetoct", SS_CASE_EDGE, NULL, 3, SS_DIAG_BFS, 0},
    {"catmull-clark-3.png", "catmull-clark", SS_CASE_SURFACE_VERTEX, NULL, 3, SS_DIAG_BFS,
     0},
    {"quasi48-5.png", "quasi48", SS_CASE_SURFACE_VERTEX, NULL, 5, SS_DIAG_BFS, 0},
    {"boxspline-edge-9-skew.png", "boxspline", SS_CASE_EDGE, NULL, 9, SS_DIAG_SKEW, 0},
    /* lambda3 = lambda4: no characteristic map; the would-be map, labelled */
    {"boxspline-edge-9-center-forced.png", "boxspline", SS_CASE_EDGE, NULL, 9,
     SS_DIAG_CENTER, 1},
    {"boxspline-vertex-k5-bipyramid.png", "boxspline", SS_CASE_VERTEX, "bipyramid:3", 0,
     SS_DIAG_BFS, 0},
};
#define NFIGURES (sizeof figures / sizeof figures[0])

/* ---- results of one table ---- */

typedef struct {
  ss_result *r;     /* n results, in case order */
  size_t n;         /* number of results */
  size_t cap;       /* allocated */
  ss_result_opts o; /* how the cases are analysed (--certify) */
} result_list;

static void results_free(result_list *l) {
  for (size_t i = 0; i < l->n; i++)
    ss_result_clear(l->r + i);
  free(l->r);
  memset(l, 0, sizeof *l);
}

/* Analyse one case and append it. */
static ss_status add_case(result_list *l, const ss_scheme *s, const ss_case *c,
                          ss_error *err) {
  if (l->n == l->cap) {
    size_t nc = l->cap ? 2 * l->cap : 32;
    ss_result *nr = realloc(l->r, nc * sizeof *nr);
    if (!nr) return ss_error_nomem(err, "results");
    l->r = nr;
    l->cap = nc;
  }
  ss_status st = ss_result_compute(s, c, &l->o, l->r + l->n, err);
  if (!st) l->n++;
  return st;
}

typedef struct {
  result_list *list;   /* where results go */
  const ss_scheme *s;  /* the scheme */
  const table_spec *t; /* the table */
  ss_status st;        /* first failure */
  ss_error *err;       /* its message */
} enum_ctx;

static int visit_link(const ss_link *l, void *ctx) {
  enum_ctx *e = ctx;
  ss_case c = {e->t->kind, l, 0, e->t->diag, 0};
  e->st = add_case(e->list, e->s, &c, e->err);
  return e->st != SS_OK;
}

/* Compute every case of table t. */
static ss_status compute_table(const table_spec *t, const ss_scheme *s, result_list *out,
                               ss_error *err) {
  ss_status st = SS_OK;
  if (t->src == SRC_LINKS) {
    enum_ctx e = {out, s, t, SS_OK, err};
    ss_enum_opts o = {t->lo, t->hi, 0, 1};
    st = ss_enum_links(&o, visit_link, &e, NULL, err);
    if (!st) st = e.st;
  } else if (t->src == SRC_RANDOM) {
    for (int k = t->lo; k <= t->hi && !st; k++) {
      /* a fresh generator per k, as `enumerate random --vertices k --samples 1
       * --seed 1` starts one */
      gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
      ss_link *l = NULL;
      if (!r) return ss_error_nomem(err, "random generator");
      gsl_rng_set(r, 1UL);
      st = ss_link_random(k, r, &l, err);
      if (!st) {
        ss_case c = {t->kind, l, 0, t->diag, 0};
        st = add_case(out, s, &c, err);
      }
      ss_link_free(l);
      gsl_rng_free(r);
    }
  } else if (t->src == SRC_VALENCES) {
    for (int n = t->lo; n <= t->hi && !st; n++) {
      ss_case c = {t->kind, NULL, n, t->diag, 0};
      st = add_case(out, s, &c, err);
    }
  } else if (t->src == SRC_QUASI48) {
    const int classes = ss_scheme_split_kind(s) == SS_SPLIT_BISECT;
    for (int n = t->lo; n <= t->hi && !st; n++) {
      ss_case c = {t->kind, NULL, n, t->diag, classes ? 4 : 0};
      st = add_case(out, s, &c, err);
    }
    for (int n = t->lo > 6 ? t->lo + t->lo % 2 : 6; n <= t->hi && !st; n += 2) {
      ss_case c = {t->kind, NULL, n, t->diag, classes ? 8 : 0};
      st = add_case(out, s, &c, err);
    }
  } else {
    ss_case c = {SS_CASE_FACE, NULL, 0, t->diag, 0};
    st = add_case(out, s, &c, err);
  }
  return st;
}

/* ---- comparison with the quoted values ---- */

typedef struct {
  size_t row;            /* index of the result */
  const ss_ref_row *ref; /* the quoted value */
  int note;              /* its footnote number (1-based) */
  char quoted[64];       /* as shown: value, "= x" for formulas */
  char computed[64];     /* our value */
  char diff[32];         /* computed - quoted, or "–" */
  char tol[32];          /* the tolerance applied */
  int match;             /* 1 match, 0 differ */
} comparison;

static int is_real(const ss_result_eigval *v) {
  return fabs(v->im) <= 1e-12 * fabs(v->re);
}

static void eig_text(const ss_result_eigval *v, char *buf, size_t n) {
  if (is_real(v))
    snprintf(buf, n, "%.6f", v->re);
  else
    snprintf(buf, n, "%.4f%+.4fi", v->re, v->im);
}

/* Compare result r with quoted value q; fills c (row and note are set by the
 * caller). */
static ss_status compare(const ss_result *r, const ss_ref_row *q, comparison *c,
                         ss_error *err) {
  ss_ref_value v;
  ss_status st = ss_report_ref_eval(q->value, r->k, &v, err);
  if (st) return st;
  int index = 0;
  ss_report_ref_quantity(q->quantity, &index);
  snprintf(c->diff, sizeof c->diff, "–");
  if (v.kind == SS_REF_VERDICT) {
    ss_verdict_kind got = !strcmp(q->quantity, "verdict")           ? ss_result_verdict(r)
                          : !strcmp(q->quantity, "eigen_condition") ? r->cond.verdict
                                                                    : r->reg.verdict;
    snprintf(c->quoted, sizeof c->quoted, "%s", v.verdict);
    snprintf(c->computed, sizeof c->computed, "%s", ss_verdict_name(got));
    snprintf(c->tol, sizeof c->tol, "equal");
    c->match = !strcmp(v.verdict, ss_verdict_name(got));
    return SS_OK;
  }
  double x = NAN;
  int have = 1;
  if (!strncmp(q->quantity, "lambda", 6)) {
    if (index < r->neig && is_real(r->eig + index)) {
      x = r->eig[index].re;
      snprintf(c->computed, sizeof c->computed, "%.9g", x);
    } else if (index < r->neig) {
      eig_text(r->eig + index, c->computed, sizeof c->computed);
      have = 0;
    } else {
      snprintf(c->computed, sizeof c->computed, "none kept");
      have = 0;
    }
  } else {
    x = !strncmp(q->quantity, "mult", 4)
            ? (index < r->neig ? (double)r->eig[index].mult : (double)NAN)
        : !strcmp(q->quantity, "two_ring") ? (double)r->two_ring
                                           : (double)r->one_ring;
    snprintf(c->computed, sizeof c->computed, "%.0f", x);
    have = isfinite(x);
  }
  const int formula = strchr(q->value, 'k') || strchr(q->value, 'n');
  if (formula)
    snprintf(c->quoted, sizeof c->quoted, "%s = %.0f", q->value, v.x);
  else
    snprintf(c->quoted, sizeof c->quoted, "%s", q->value);
  if (v.kind == SS_REF_GREATER) {
    snprintf(c->tol, sizeof c->tol, "strict");
  } else {
    if (v.exact)
      snprintf(c->tol, sizeof c->tol, "%.0e (exact)", v.tol);
    else
      snprintf(c->tol, sizeof c->tol, "±%.1g", v.tol);
    if (have) snprintf(c->diff, sizeof c->diff, "%+.2e", x - v.x);
  }
  c->match = have && ss_report_ref_match(&v, x);
  return SS_OK;
}

/* ---- writing ---- */

/* Append printf-style text to a growing buffer; 0 or -1 on allocation failure. */
typedef struct {
  char *s;
  size_t n, cap;
} strbuf;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int
sb_printf(strbuf *b, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int need = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (need < 0) return -1;
  if (b->n + (size_t)need + 1 > b->cap) {
    size_t nc = b->cap ? b->cap : 4096;
    while (nc < b->n + (size_t)need + 1)
      nc *= 2;
    char *ns = realloc(b->s, nc);
    if (!ns) return -1;
    b->s = ns;
    b->cap = nc;
  }
  va_start(ap, fmt);
  vsnprintf(b->s + b->n, (size_t)need + 1, fmt, ap);
  va_end(ap);
  b->n += (size_t)need;
  return 0;
}

/* Markdown cell text: a bar would end the cell. */
static void sb_cell(strbuf *b, const char *s) {
  for (; *s; s++)
    sb_printf(b, *s == '|' ? "\\|" : "%c", *s);
}

static void sb_verdict(strbuf *b, const ss_verdict *v, int certified) {
  sb_printf(b, "%s%s", ss_verdict_name(v->verdict), certified ? " ✓" : "");
  if (v->reason[0]) {
    sb_printf(b, " (");
    sb_cell(b, v->reason);
    sb_printf(b, ")");
  }
}

/* b into the file at path, whole or not at all (ss_outfile.h). */
static ss_status write_file(const char *path, const strbuf *b, ss_error *err) {
  ss_outfile *out;
  ss_status st = ss_outfile_open(path, &out, err);
  if (st) return st;
  if (b->n) fwrite(b->s, 1, b->n, ss_outfile_file(out)); /* checked by the commit */
  return ss_outfile_commit(out, err);
}

static const char *case_label(const ss_result *r, char *buf, size_t n) {
  if (ss_result_has_link(r))
    snprintf(buf, n, "k = %d", r->k);
  else if (r->kind == SS_CASE_FACE)
    snprintf(buf, n, "face");
  else if (r->cls)
    snprintf(buf, n, "n = %d, class %d", r->k, r->cls);
  else
    snprintf(buf, n, "n = %d", r->k);
  return buf;
}

static json_object *result_json(const table_spec *t, const ss_result *r) {
  json_object *o = json_object_new_object();
  json_object_object_add(o, "scheme", json_object_new_string(t->scheme));
  json_object_object_add(o, "case", json_object_new_string(ss_case_name(r->kind)));
  if (ss_result_has_link(r)) {
    json_object_object_add(o, "link", json_object_new_string(r->link));
    json_object_object_add(o, "k", json_object_new_int(r->k));
  }
  if (r->valence) json_object_object_add(o, "valence", json_object_new_int(r->valence));
  if (r->cls) json_object_object_add(o, "class", json_object_new_int(r->cls));
  json_object_object_add(o, "two_ring_size", json_object_new_int64((int64_t)r->two_ring));
  json_object_object_add(o, "one_ring_size", json_object_new_int64((int64_t)r->one_ring));
  if (r->has_diag) {
    json_object *d = json_object_new_object();
    json_object_object_add(d, "choice", json_object_new_string(ss_diag_name(t->diag)));
    json_object_object_add(d, "pairs", json_object_new_int64((int64_t)r->pairs));
    json_object_object_add(d, "improper", json_object_new_int64((int64_t)r->improper));
    json_object_object_add(o, "diagonals", d);
  }
  json_object_object_add(o, "eigenvalues", ss_report_eig_json(r));
  json_object *c = ss_report_verdict_json(&r->cond, r->cond_certified);
  json_object_object_add(c, "tolerance", json_object_new_double(r->tol));
  json_object_object_add(o, "eigen_condition", c);
  json_object *g = ss_report_verdict_json(&r->reg, r->reg_certified);
  json_object_object_add(g, "min_scaled_jacobian",
                         isfinite(r->min_sj) ? json_object_new_double(r->min_sj) : NULL);
  json_object_object_add(g, "ring_level", json_object_new_int(r->ring_level));
  json_object_object_add(g, "ring_levels", json_object_new_int(r->ring_levels));
  json_object_object_add(g, "centre_corner_folds",
                         json_object_new_int64((int64_t)r->centre_corner_folds));
  json_object_object_add(g, "depth", json_object_new_int(r->depth));
  json_object_object_add(o, "regularity", g);
  json_object *in = ss_report_verdict_json(&r->inj, r->inj_certified);
  json_object_object_add(in, "degree", json_object_new_int(r->inj_degree));
  json_object_object_add(o, "injectivity", in);
  return o;
}

/* The verdicts of an exhaustive table counted per k: which condition fails,
 * and how many passing maps fold in cells around p (which decide nothing,
 * ss_charmap.h). */
static void per_k(strbuf *md, const result_list *l) {
  sb_printf(md,
            "\n| k | links | pass | fail: eigenvalue condition | fail: regularity | "
            "fail: injectivity only | undecided | passing, with folds around p | "
            "points on an edge (edge verdict) |%s\n"
            "|--:|--:|--:|--:|--:|--:|--:|--:|---|%s\n",
            l->o.certify ? " certified pass | certified fail | not certified |" : "",
            l->o.certify ? "--:|--:|--:|" : "");
  int lo = INT_MAX, hi = 0;
  for (size_t i = 0; i < l->n; i++) {
    lo = l->r[i].k < lo ? l->r[i].k : lo;
    hi = l->r[i].k > hi ? l->r[i].k : hi;
  }
  for (int k = lo; k <= hi; k++) { /* the enumeration interleaves the k */
    size_t n = 0, pass = 0, fcond = 0, freg = 0, finj = 0, und = 0, centre = 0, cpass = 0,
           cfail = 0, nedge = 0;
    char edges[128] = "–";
    for (size_t i = 0; i < l->n; i++) {
      const ss_result *r = l->r + i;
      if (r->k != k) continue;
      const ss_verdict_kind v = ss_result_verdict(r);
      if (r->kind == SS_CASE_EDGE_POINT) { /* judged as an edge: not a vertex */
        snprintf(edges, sizeof edges, "%zu (valence %d: %s)", ++nedge, r->valence,
                 ss_verdict_name(v));
        continue;
      }
      n++;
      pass += v == SS_PASS;
      fcond += r->cond.verdict == SS_FAIL;
      freg += r->cond.verdict != SS_FAIL && r->reg.verdict == SS_FAIL;
      finj += v == SS_FAIL && r->cond.verdict != SS_FAIL && r->reg.verdict != SS_FAIL;
      und += v == SS_UNDECIDED;
      centre += v == SS_PASS && r->centre_corner_folds > 0;
      cpass += v == SS_PASS && ss_result_certified(r);
      cfail += v == SS_FAIL && ss_result_certified(r);
    }
    if (!n && !nedge) continue;
    sb_printf(md, "| %d | %zu | %zu | %zu | %zu | %zu | %zu | %zu | %s |", k, n + nedge,
              pass, fcond, freg, finj, und, centre, edges);
    if (l->o.certify)
      sb_printf(md, " %zu | %zu | %zu |", cpass, cfail, n - cpass - cfail);
    sb_printf(md, "\n");
  }
}

/* Counts for the summary line. */
typedef struct {
  size_t cases, pass;   /* cases, of which pass both conditions */
  size_t quoted, match; /* quoted values compared, of which match */
  size_t unquoted;      /* cases with no quoted value */
  size_t certified;     /* cases whose verdict is proven (ss_result_certified) */
} tally;

/* The verdict of r in a few words: "pass", or the first condition that does
 * not pass and how. */
static const char *verdict_words(const ss_result *r) {
  const ss_verdict_kind v = ss_result_verdict(r);
  if (v == SS_PASS) return "pass";
  const int und = v == SS_UNDECIDED;
  if (r->cond.verdict != SS_PASS)
    return und ? "undecided: eigenvalue condition" : "fail: eigenvalue condition";
  if (r->reg.verdict != SS_PASS)
    return und ? "undecided: regularity" : "fail: regularity";
  return und ? "undecided: injectivity" : "fail: injectivity";
}

/* lambda1..lambda3 and |lambda4| of r as Markdown cells. */
static void sb_leading(strbuf *md, const ss_result *r) {
  char buf[64];
  for (int e = 1; e <= 3; e++) {
    if (e < r->neig) {
      eig_text(r->eig + e, buf, sizeof buf);
      sb_printf(md, " %s |", buf);
    } else
      sb_printf(md, " |");
  }
  if (4 < r->neig)
    sb_printf(md, " %.6f |", hypot(r->eig[4].re, r->eig[4].im));
  else
    sb_printf(md, " |");
}

/* The section of table t that shows the results l of t's scheme beside the
 * results v of scheme t->vs on the same cases (same order). */
static void side_by_side(strbuf *md, const table_spec *t, const char *vs,
                         const result_list *l, const result_list *v) {
  size_t both = 0, only_a = 0, only_b = 0;
  sb_printf(md,
            "\n## Beside %s\n\nThe same cases with `--scheme %s`: λ1..λ3 and \\|λ4\\| "
            "after λ0 = 1 and the verdict of each.\n\n| # | case | %s λ1 | λ2 | λ3 | "
            "\\|λ4\\| | %s verdict | %s λ1 | λ2 | λ3 | \\|λ4\\| | %s verdict |\n"
            "|--:|---|--:|--:|--:|--:|---|--:|--:|--:|--:|---|\n",
            vs, vs, t->scheme, t->scheme, vs, vs);
  for (size_t i = 0; i < l->n && i < v->n; i++) {
    const ss_result *a = l->r + i, *b = v->r + i;
    char buf[64];
    if (ss_result_has_link(a))
      sb_printf(md, "| %zu | `%s`%s |", i + 1, a->link,
                a->kind == SS_CASE_EDGE_POINT ? " (edge point)" : "");
    else
      sb_printf(md, "| %zu | %s |", i + 1, case_label(a, buf, sizeof buf));
    sb_leading(md, a);
    sb_printf(md, " %s |", verdict_words(a));
    sb_leading(md, b);
    sb_printf(md, " %s |\n", verdict_words(b));
    const int pa = ss_result_verdict(a) == SS_PASS, pb = ss_result_verdict(b) == SS_PASS;
    both += (size_t)(pa && pb);
    only_a += (size_t)(pa && !pb);
    only_b += (size_t)(!pa && pb);
  }
  sb_printf(md,
            "\n**Side by side:** of %zu cases %zu pass under both schemes, %zu under %s "
            "only, %zu under %s only.\n",
            l->n, both, only_a, t->scheme, only_b, vs);
}

#define MAXVS 2 /* schemes beside a table's, at most */

/* The names in t->vs (comma-separated) into names; their count. */
static int vs_names(const table_spec *t, char names[MAXVS][32]) {
  int n = 0;
  for (const char *p = t->vs; p && *p && n < MAXVS;) {
    const size_t len = strcspn(p, ",");
    snprintf(names[n++], 32, "%.*s", (int)len, p);
    p += len + (p[len] == ',');
  }
  return n;
}

/* Write NAME.md, NAME.tsv and data/NAME.jsonl for table t; vs (NULL unless
 * t->vs) holds the other schemes' results on the same cases, in t->vs's
 * order. */
static ss_status write_table(const char *dir, const table_spec *t, const result_list *l,
                             const result_list *vs, const ss_ref *ref, tally *ty,
                             ss_error *err) {
  ss_status st = SS_OK;
  strbuf md = {0}, tsv = {0}, js = {0};
  comparison *cmp = NULL;
  size_t ncmp = 0, cap = 0;
  const ss_ref_row **used = NULL; /* footnotes, in order of first use */
  size_t nused = 0;
  char *path = NULL;
  int *row_status =
      calloc(l->n ? l->n : 1, sizeof *row_status); /* 0 none, 1 ok, 2 differ */
  used = calloc(ref->n ? ref->n : 1, sizeof *used);
  if (!row_status || !used) {
    st = ss_error_nomem(err, "table");
    goto done;
  }
  memset(ty, 0, sizeof *ty);
  ty->cases = l->n;
  /* compare every result with every quoted value that speaks of it */
  for (size_t i = 0; i < l->n; i++) {
    const ss_result *r = l->r + i;
    const char *dname = r->has_diag ? ss_diag_name(t->diag) : NULL;
    if (ss_result_verdict(r) == SS_PASS) ty->pass++;
    ty->certified += (size_t)ss_result_certified(r);
    for (size_t j = 0; j < ref->n; j++) {
      const ss_ref_row *q = ref->row + j;
      if (!strncmp(q->quantity, "jsr_", 4) || /* the JSR tables' (ss_cli_reproduce_jsr) */
          !ss_report_ref_applies(q, t->scheme, r->kind, r->k, dname))
        continue;
      if (ncmp == cap) {
        size_t nc = cap ? 2 * cap : 64;
        comparison *ncm = realloc(cmp, nc * sizeof *ncm);
        if (!ncm) {
          st = ss_error_nomem(err, "comparisons");
          goto done;
        }
        cmp = ncm;
        cap = nc;
      }
      comparison *c = cmp + ncmp;
      memset(c, 0, sizeof *c);
      c->row = i;
      c->ref = q;
      size_t u = 0;
      while (u < nused && used[u] != q)
        u++;
      if (u == nused) used[nused++] = q;
      c->note = (int)u + 1;
      if ((st = compare(r, q, c, err))) goto done;
      ncmp++;
      ty->quoted++;
      ty->match += (size_t)c->match;
      row_status[i] = c->match && row_status[i] != 2 ? 1 : 2;
    }
    if (!row_status[i]) ty->unquoted++;
  }

  const double tol = l->n ? l->r[0].tol : ss_result_defaults().tol;
  const int depth = l->n ? l->r[0].depth : ss_result_defaults().depth;
  /* ---- Markdown ---- */
  sb_printf(&md, "# %s\n\n", t->title);
  sb_printf(&md,
            "Regenerate: `subspectra reproduce` (the cases: `%s`; raw results in "
            "`data/%s.jsonl`, the comparison with the papers in `%s.tsv`).\n\n",
            t->command, t->name, t->name);
  if (t->note) sb_printf(&md, "%s\n\n", t->note);
  sb_printf(&md,
            "Verdicts: eigenvalues equal within relative tolerance %g; hex Jacobian test "
            "to subdivision depth %d. Quoted values (data/reference/*.tsv): a decimal "
            "matches when \\|computed − quoted\\| ≤ half a unit in its last digit, an "
            "exact value (fraction, integer formula) within %g, a verdict when equal; "
            "the column *paper* says whether every value quoted for the row matches.\n\n",
            tol, depth, SS_REF_EXACT_TOL);
  sb_printf(
      &md,
      "Regularity is judged on the characteristic map's ring (ring levels up to "
      "%d, a fold persisting when its share of the cells does not halve); "
      "injectivity by the degree about ψ(p) and the overlaps of the ring's "
      "piecewise-linear image (exact predicates on the double-precision net).%s\n\n",
      l->o.ring_levels,
      l->o.certify
          ? " ✓ marks a proven verdict: the exact spectrum of the rational matrix "
            "(FLINT), the subdominant basis enclosed in ball arithmetic (arb) and "
            "the ring's Jacobians in interval arithmetic; a verdict that could not "
            "be proven is undecided, \"not certified\", with the double-precision "
            "verdict in its reason."
          : " Verdicts are double precision (`reproduce --certify` proves them).");
  const int m = t->kind == SS_CASE_SURFACE_VERTEX ? 2 : 3;
  int has_diag = 0;
  for (size_t i = 0; i < l->n; i++)
    has_diag |= l->r[i].has_diag;
  if (t->kind == SS_CASE_VERTEX)
    sb_printf(&md, "| # | link | k | cells |");
  else if (t->kind == SS_CASE_FACE)
    sb_printf(&md, "| case |");
  else
    sb_printf(&md, "| valence |");
  if (has_diag) sb_printf(&md, " improper pairs |");
  sb_printf(&md, " two-ring | one-ring |");
  if (t->neig)
    for (int i = 1; i <= t->neig; i++)
      sb_printf(&md, " λ%d |", i);
  else {
    for (int i = 1; i <= m; i++)
      sb_printf(&md, " λ%d |", i);
    sb_printf(&md, " \\|λ%d\\| |", m + 1);
  }
  sb_printf(&md, " eigenvalue condition | regularity | injectivity | min scaled Jacobian "
                 "| paper |\n|");
  const int ncol = (t->kind == SS_CASE_VERTEX ? 4 : 1) + has_diag + 2 +
                   (t->neig ? t->neig : m + 1) + 5;
  for (int i = 0; i < ncol; i++)
    sb_printf(&md, "---|");
  sb_printf(&md, "\n");
  for (size_t i = 0; i < l->n; i++) {
    const ss_result *r = l->r + i;
    char buf[64];
    if (ss_result_has_link(r))
      sb_printf(&md, "| %zu | `%s`%s | %d | %zu |", i + 1, r->link,
                r->kind == SS_CASE_EDGE_POINT ? " (edge point)" : "", r->k, r->cells);
    else if (r->kind == SS_CASE_FACE)
      sb_printf(&md, "| face |");
    else
      sb_printf(&md, "| %d |", r->k);
    if (has_diag) {
      if (r->has_diag)
        sb_printf(&md, " %zu of %zu |", r->improper, r->pairs);
      else
        sb_printf(&md, " – |");
    }
    sb_printf(&md, " %zu | %zu |", r->two_ring, r->one_ring);
    const int shown = t->neig ? t->neig : m;
    for (int e = 1; e <= shown; e++) {
      if (e < r->neig) {
        eig_text(r->eig + e, buf, sizeof buf);
        sb_printf(&md, " %s |", buf);
      } else
        sb_printf(&md, " |");
    }
    if (!t->neig) {
      if (m + 1 < r->neig)
        sb_printf(&md, " %.6f |", hypot(r->eig[m + 1].re, r->eig[m + 1].im));
      else
        sb_printf(&md, " |");
    }
    sb_printf(&md, " ");
    sb_verdict(&md, &r->cond, r->cond_certified);
    sb_printf(&md, " | ");
    sb_verdict(&md, &r->reg, r->reg_certified);
    sb_printf(&md, " | ");
    if (r->inj.verdict == SS_PASS)
      sb_printf(&md, "pass (degree %d)", r->inj_degree);
    else
      sb_verdict(&md, &r->inj, r->inj_certified);
    if (isfinite(r->min_sj))
      sb_printf(&md, " | %.4f |", r->min_sj);
    else
      sb_printf(&md, " | – |");
    sb_printf(&md, " %s |\n",
              row_status[i] == 0   ? "not quoted"
              : row_status[i] == 1 ? "match"
                                   : "**differ**");
  }
  sb_printf(
      &md,
      "\n**Summary:** %zu of %zu cases pass both conditions; %zu quoted values: "
      "%zu match, %zu differ; %zu of %zu rows not quoted (relative tolerance %g).\n",
      ty->pass, ty->cases, ty->quoted, ty->match, ty->quoted - ty->match, ty->unquoted,
      ty->cases, tol);
  if (t->src == SRC_LINKS) per_k(&md, l);
  if (vs) {
    char names[MAXVS][32];
    const int nvs = vs_names(t, names);
    for (int k = 0; k < nvs; k++)
      side_by_side(&md, t, names[k], l, vs + k);
  }
  if (ncmp) {
    sb_printf(&md, "\n## Quoted values\n\n| # | case | quantity | quoted | computed | "
                   "computed − quoted | tolerance | status | source |\n"
                   "|---|---|---|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < ncmp; i++) {
      const comparison *c = cmp + i;
      char buf[32];
      sb_printf(&md, "| %zu | %s | %s | %s | %s | %s | %s | %s | [%d] |\n", c->row + 1,
                case_label(l->r + c->row, buf, sizeof buf), c->ref->quantity, c->quoted,
                c->computed, c->diff, c->tol, c->match ? "match" : "**differ**", c->note);
    }
    sb_printf(&md, "\nSources:\n\n");
    for (size_t u = 0; u < nused; u++) {
      const ss_ref_row *q = used[u];
      sb_printf(&md, "%zu. %s, %s: “", u + 1, q->paper, q->location);
      sb_cell(&md, q->quote);
      sb_printf(&md, "” — ");
      sb_cell(&md, q->note);
      sb_printf(&md, " (`%s:%ld`)\n", q->file, q->line);
    }
  } else {
    sb_printf(&md, "\nNo value in this table is quoted by the papers "
                   "(data/reference/*.tsv).\n");
  }
  /* ---- TSV ---- */
  sb_printf(&tsv,
            "# %s\n# produced by: subspectra reproduce (the cases: %s)\n"
            "# verdicts: relative tolerance %g, hex Jacobian depth %d; match rule: "
            "decimals within half a unit in the last digit, exact values within %g, "
            "verdicts equal\n"
            "# summary: %zu of %zu cases pass both conditions; %zu quoted values: %zu "
            "match, %zu differ; %zu rows not quoted\n"
            "table\trow\tcase\tlink\tquantity\tquoted\tcomputed\tdifference\ttolerance\t"
            "status\tpaper\tlocation\treference\n",
            t->title, t->command, tol, depth, SS_REF_EXACT_TOL, ty->pass, ty->cases,
            ty->quoted, ty->match, ty->quoted - ty->match, ty->unquoted);
  for (size_t i = 0, j = 0; i < l->n; i++) {
    char buf[32];
    const ss_result *r = l->r + i;
    if (!row_status[i])
      sb_printf(&tsv, "%s\t%zu\t%s\t%s\t-\t-\t-\t-\t-\tnot quoted\t-\t-\t-\n", t->name,
                i + 1, case_label(r, buf, sizeof buf), r->link[0] ? r->link : "-");
    for (; j < ncmp && cmp[j].row == i; j++) {
      const comparison *c = cmp + j;
      sb_printf(&tsv, "%s\t%zu\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s:%ld\n",
                t->name, i + 1, case_label(r, buf, sizeof buf),
                r->link[0] ? r->link : "-", c->ref->quantity, c->quoted, c->computed,
                c->diff, c->tol, c->match ? "match" : "differ", c->ref->paper,
                c->ref->location, c->ref->file, c->ref->line);
    }
  }
  /* ---- JSON lines ---- */
  for (size_t i = 0; i < l->n; i++) {
    json_object *o = result_json(t, l->r + i);
    sb_printf(&js, "%s\n",
              json_object_to_json_string_ext(o, JSON_C_TO_STRING_PLAIN |
                                                    JSON_C_TO_STRING_NOSLASHESCAPE));
    json_object_put(o);
  }
  if (!md.s || !tsv.s || !js.s) {
    st = ss_error_nomem(err, "table text");
    goto done;
  }
  path = malloc(strlen(dir) + strlen(t->name) + 32);
  if (!path) {
    st = ss_error_nomem(err, "path");
    goto done;
  }
  sprintf(path, "%s/%s.md", dir, t->name);
  if ((st = write_file(path, &md, err))) goto done;
  sprintf(path, "%s/%s.tsv", dir, t->name);
  if ((st = write_file(path, &tsv, err))) goto done;
  sprintf(path, "%s/data/%s.jsonl", dir, t->name);
  st = write_file(path, &js, err);
done:
  free(path);
  free(md.s);
  free(tsv.s);
  free(js.s);
  free(cmp);
  free(used);
  free(row_status);
  return st;
}

/* ---- figures ---- */

/* Draw figure f into path, as `subspectra draw --no-caption` does, and append
 * its caption (the case, lambda1..m, the regularity verdict) to cap, the
 * Markdown of figures/README.md: the report captions the pictures, they carry
 * no text of their own besides axes and legend. */
static ss_status draw_figure(const figure_spec *f, const char *path, strbuf *cap,
                             ss_error *err) {
  ss_scheme *s = NULL;
  ss_link *l = NULL, *cl = NULL;
  char *canon = NULL;
  ss_local *M = NULL;
  ss_eig *e = NULL;
  ss_charmap *cm = NULL;
  ss_star *star = NULL;
  ss_status st = ss_scheme_new(f->scheme, &s, err);
  if (!st && f->kind == SS_CASE_VERTEX) {
    st = ss_link_parse(f->link, &l, err);
    if (!st) st = ss_link_canonical(l, &cl, NULL, err);
    if (!st) st = ss_link_format(cl, &canon, err);
  }
  ss_case c = {f->kind, l, f->n, f->diag, 0};
  if (!st) st = ss_local_new(s, &c, &M, err);
  size_t pairs = 0, improper = 0;
  const int diag = !st && ss_scheme_reads_diagonals(s) && M->cell == SS_TET;
  if (diag) {
    st = ss_local_star(s, &c, &star, err);
    if (!st) st = ss_diag_improper(star->cx, &pairs, &improper, err);
  }
  if (!st) {
    ss_eig_opts eo = ss_eig_defaults(M->dim);
    eo.tol = ss_result_defaults().tol;
    eo.force = f->force;
    st = ss_eig_new(M->S, M->n2, M->n1, &eo, &e, err);
  }
  ss_regularity reg;
  const ss_charmap_opts co = ss_charmap_defaults();
  if (!st) st = ss_charmap_judge(s, &c, M, e, &co, &cm, &reg, err);
  int forced = 0;
  if (!st && !cm && f->force && e->basis) {
    st = ss_charmap_new(M, e, &cm, err);
    if (!st) st = ss_charmap_regularity(cm, M, &co, &reg, err);
    forced = 1;
  }
  if (!st && !cm)
    st = ss_error_set(err, SS_EINTERNAL, "%s: no characteristic map to draw: %s", path,
                      reg.verdict.reason);
  if (!st) {
    char caption[600], param[32] = "", dtext[128] = "";
    if (f->kind == SS_CASE_EDGE || f->kind == SS_CASE_SURFACE_VERTEX)
      snprintf(param, sizeof param, "%d", f->n);
    if (diag)
      snprintf(dtext, sizeof dtext, ", diagonals %s (%zu of %zu pairs improper)",
               ss_diag_name(f->diag), improper, pairs);
    snprintf(caption, sizeof caption, "%s, %s %s%s%s", f->scheme, ss_case_name(f->kind),
             canon ? canon : param, dtext,
             forced
                 ? "; forced: NOT a characteristic map (the eigenvalue condition fails)"
                 : "");
    const ss_report_draw_opts o = ss_report_draw_defaults(); /* no caption */
    st = ss_report_draw(cm, &reg, &o, path, err);
    int bad = sb_printf(cap, "## %s\n\n![%s](%s)\n\n", f->file, f->file, f->file);
    sb_cell(cap, caption);
    bad |= sb_printf(cap, ".  λ1..%d =", cm->dim);
    for (int i = 0; i < cm->dim; i++)
      bad |= sb_printf(cap, " %.6f", cm->lambda[i]);
    bad |= sb_printf(cap, "; regularity: %s, minimum scaled Jacobian %.4f%s",
                     ss_verdict_name(reg.verdict.verdict), reg.min_scaled_jacobian,
                     reg.verdict.reason[0] ? ": " : "");
    sb_cell(cap, reg.verdict.reason);
    bad |= sb_printf(cap, ".\n\n");
    if (!st && bad) st = ss_error_nomem(err, "figure captions");
  }
  ss_star_free(star);
  ss_charmap_free(cm);
  ss_eig_free(e);
  ss_local_free(M);
  free(canon);
  ss_link_free(cl);
  ss_link_free(l);
  ss_scheme_free(s);
  return st;
}

/* ---- the command ---- */

static const char usage[] =
    "usage: subspectra reproduce [--out DIR] [--reference DIR] [--certify]\n\n"
    "Regenerate every table this project reproduces from the papers, each case\n"
    "beside the values the papers quote, and the pictures of characteristic maps:\n"
    "  DIR/NAME.md          the table: cases, eigenvalues, both verdicts, and per\n"
    "                       row match / differ / not quoted; then every quoted\n"
    "                       value with the computed one, the difference, the\n"
    "                       tolerance and the source (paper, location, quote)\n"
    "  DIR/NAME.tsv         the comparison, machine-readable\n"
    "  DIR/data/NAME.jsonl  the results, one JSON object per case (keys as in\n"
    "                       `analyze --format json`)\n"
    "  DIR/figures/*.png    pictures (as `subspectra draw --no-caption`), their\n"
    "                       captions in DIR/figures/README.md\n"
    "Quoted values are read from the reference files (one TSV per paper; the\n"
    "columns are documented in their header).  A decimal matches when it is\n"
    "within half a unit in its last printed digit, an exact value (fraction,\n"
    "formula in k or n) within 1e-9, a verdict when equal.  One progress line\n"
    "per table on standard error.\n\n"
    "  -o, --out DIR        output folder, created if missing (default reports)\n"
    "  -r, --reference DIR  reference files DIR/*.tsv; default:\n"
    "                       $SUBSPECTRA_DATADIR/reference when that is set, else\n"
    "                       data/reference when run from the source tree, else\n"
    "                       the installed data beside the program, or\n"
    "                       " SS_DATADIR "/reference\n"
    "  --certify            prove every verdict (as `analyze --certify`): a proven\n"
    "                       verdict is marked ✓, one that cannot be proven becomes\n"
    "                       undecided; the exhaustive tables count both per k\n"
    "  -h, --help           this text\n\n"
    "Exit status: 0 when it ran, whatever the verdicts and comparisons; 1 when an\n"
    "analysis failed internally; 2 for bad usage, a malformed reference file or\n"
    "an output that cannot be written.\n";

/* mkdir -p; 0 or -1 with errno set. */
static int make_dirs(const char *path) {
  char *p = strdup(path);
  if (!p) return -1;
  int rc = 0;
  for (char *s = p + 1;; s++) {
    const char save = *s;
    if (save != '/' && save != '\0') continue;
    *s = '\0';
    struct stat sb;
    if (mkdir(p, 0777) != 0 &&
        !(errno == EEXIST && stat(p, &sb) == 0 && S_ISDIR(sb.st_mode))) {
      if (errno == EEXIST) errno = ENOTDIR;
      rc = -1;
      break;
    }
    *s = save;
    if (save == '\0') break;
  }
  free(p);
  return rc;
}

static int exit_for(const ss_error *err) {
  return ss_cli_exit_status(err->status); /* out of memory: 2, never 1 */
}

int ss_cli_reproduce(int argc, char **argv) {
  static const struct option opts[] = {{"out", required_argument, NULL, 'o'},
                                       {"reference", required_argument, NULL, 'r'},
                                       {"certify", no_argument, NULL, 'c'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  const char *out = "reports", *refdir = NULL;
  char refbuf[4096];
  ss_result_opts ro = ss_result_defaults();
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":o:r:h", opts, NULL)) != -1) {
    switch (c) {
    case 'o':
      out = optarg;
      break;
    case 'r':
      refdir = optarg;
      break;
    case 'c':
      ro.certify = 1;
      break;
    case 'h':
      fputs(usage, stdout);
      return SS_EXIT_OK;
    default:
      return ss_cli_option_error(cmd, c, argv);
    }
  }
  if (optind < argc)
    return ss_cli_usage_error(cmd, "unexpected argument '%s'", argv[optind]);
  if (!*out) return ss_cli_usage_error(cmd, "--out: empty folder name");

  if (!refdir && !(refdir = ss_cli_refdir(refbuf, sizeof refbuf)))
    return ss_cli_usage_error(cmd, "SUBSPECTRA_DATADIR: path too long");
  ss_error err = {0};
  ss_ref ref = {0};
  int rc = SS_EXIT_OK;
  char *path = NULL;
  glob_t g;
  memset(&g, 0, sizeof g);
  /* the reference files */
  path = malloc(strlen(refdir) + strlen(out) + 64);
  if (!path) {
    ss_error_nomem(&err, "path");
    rc = ss_cli_fail(&err);
    goto done;
  }
  sprintf(path, "%s/*.tsv", refdir);
  if (glob(path, 0, NULL, &g) != 0 || g.gl_pathc == 0) {
    fprintf(stderr,
            "subspectra %s: %s: no reference files (*.tsv); run from the source tree, "
            "set SUBSPECTRA_DATADIR or give --reference DIR\n",
            cmd, refdir);
    rc = SS_EXIT_USAGE;
    goto done;
  }
  for (size_t i = 0; i < g.gl_pathc; i++)
    if (ss_report_ref_load(g.gl_pathv[i], &ref, &err)) {
      fprintf(stderr, "subspectra %s: %s\n", cmd, err.msg);
      rc = SS_EXIT_USAGE; /* a bad reference file, or out of memory */
      goto done;
    }
  /* the output folders */
  const char *sub[] = {"", "/data", "/figures"};
  for (int i = 0; i < 3; i++) {
    sprintf(path, "%s%s", out, sub[i]);
    if (make_dirs(path)) {
      fprintf(stderr, "subspectra %s: --out %s: cannot create %s: %s\n", cmd, out, path,
              strerror(errno));
      rc = SS_EXIT_USAGE;
      goto done;
    }
  }
  const double t0 = ss_cli_now();
  size_t tquoted = 0, tmatch = 0;
  for (size_t i = 0; i < NTABLES && rc == SS_EXIT_OK; i++) {
    const table_spec *t = tables + i;
    const double t1 = ss_cli_now();
    ss_scheme *s = NULL, *sv[MAXVS] = {NULL};
    result_list l = {0}, lv[MAXVS] = {{0}};
    char names[MAXVS][32];
    const int nvs = vs_names(t, names);
    l.o = ro;
    for (int k = 0; k < MAXVS; k++)
      lv[k].o = ro;
    tally ty;
    int bad = ss_scheme_new(t->scheme, &s, &err) || compute_table(t, s, &l, &err);
    for (int k = 0; k < nvs && !bad; k++)
      bad =
          ss_scheme_new(names[k], &sv[k], &err) || compute_table(t, sv[k], &lv[k], &err);
    if (bad || write_table(out, t, &l, nvs ? lv : NULL, &ref, &ty, &err)) {
      fprintf(stderr, "subspectra %s: %s: %s\n", cmd, t->name, err.msg);
      rc = exit_for(&err);
    } else {
      char cbuf[64] = "";
      if (ro.certify)
        snprintf(cbuf, sizeof cbuf, " (%zu verdicts certified)", ty.certified);
      fprintf(stderr,
              "reproduce: %s: %zu of %zu cases pass%s; %zu quoted values: %zu match, "
              "%zu differ; %zu rows not quoted (%.1f s)\n",
              t->name, ty.pass, ty.cases, cbuf, ty.quoted, ty.match, ty.quoted - ty.match,
              ty.unquoted, ss_cli_now() - t1);
      tquoted += ty.quoted;
      tmatch += ty.match;
    }
    results_free(&l);
    ss_scheme_free(s);
    for (int k = 0; k < MAXVS; k++) {
      results_free(&lv[k]);
      ss_scheme_free(sv[k]);
    }
  }
  for (size_t i = 0; i < ss_reproduce_jsr_count() && rc == SS_EXIT_OK; i++) {
    const double t1 = ss_cli_now();
    ss_jsr_tally ty;
    if (ss_reproduce_jsr_table(i, out, &ref, &ty, &err)) {
      fprintf(stderr, "subspectra %s: %s: %s\n", cmd, ss_reproduce_jsr_name(i), err.msg);
      rc = exit_for(&err);
    } else {
      fprintf(stderr,
              "reproduce: %s: %zu of %zu cases pass the joint spectral radius test (the "
              "reduction applies to %zu); %zu quoted values: %zu match, %zu differ (%.1f "
              "s)\n",
              ss_reproduce_jsr_name(i), ty.pass, ty.cases, ty.reduced, ty.quoted,
              ty.match, ty.quoted - ty.match, ss_cli_now() - t1);
      tquoted += ty.quoted;
      tmatch += ty.match;
    }
  }
  if (rc != SS_EXIT_OK) goto done;
  const double t2 = ss_cli_now();
  strbuf cap = {0};
  if (sb_printf(&cap,
                "# Figures\n\nWritten by `subspectra reproduce` (as `subspectra draw "
                "--no-caption`); the captions are here, not in the pictures.  Each "
                "picture: the characteristic map's control net on the two-ring in 3D "
                "beside its cross-section z3 = 0 through psi(p) (surfaces: the planar "
                "map), in the frame fixed by the case (psi(p) at the origin, z1 toward "
                "the first two-ring point; see `subspectra draw --help`).\n\n")) {
    ss_error_nomem(&err, "figure captions");
    rc = ss_cli_fail(&err);
  }
  for (size_t i = 0; i < NFIGURES && rc == SS_EXIT_OK; i++) {
    sprintf(path, "%s/figures/", out);
    char *full = malloc(strlen(path) + strlen(figures[i].file) + 1);
    if (!full) {
      ss_error_nomem(&err, "path");
      rc = ss_cli_fail(&err);
      break;
    }
    sprintf(full, "%s%s", path, figures[i].file);
    if (draw_figure(figures + i, full, &cap, &err)) {
      fprintf(stderr, "subspectra %s: %s\n", cmd, err.msg);
      rc = exit_for(&err);
    }
    free(full);
  }
  if (rc == SS_EXIT_OK) {
    sprintf(path, "%s/figures/README.md", out);
    if (write_file(path, &cap, &err)) rc = ss_cli_fail(&err);
  }
  free(cap.s);
  if (rc == SS_EXIT_OK)
    fprintf(stderr,
            "reproduce: figures: %zu pictures in %s/figures (%.1f s)\n"
            "reproduce: wrote %zu tables to %s (%zu quoted values: %zu match, %zu "
            "differ; %.1f s in all)\n",
            NFIGURES, out, ss_cli_now() - t2, NTABLES + ss_reproduce_jsr_count(), out,
            tquoted, tmatch, tquoted - tmatch, ss_cli_now() - t0);
done:
  globfree(&g);
  free(path);
  ss_report_ref_free(&ref);
  return rc;
}
