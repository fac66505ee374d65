/* ss_cli_reproduce_jsr.c — the joint-spectral-radius tables of `subspectra
 * reproduce`: per case the Levin-Levin blocks Y_i (ss_levin.h), rho_k in the
 * inf-norm (the tet/oct paper's rho^[k]), certified lower and upper bounds
 * (ss_jsr.h), the threshold and the verdict, beside the paper's statements. */
#include "ss_cli_reproduce_jsr.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_blas.h>

#include "ss_diag.h"
#include "ss_jsr.h"
#include "ss_levin.h"
#include "ss_outfile.h"
#include "ss_scheme.h"

/* One table: the face (when face_depth > 0) then edges lo..hi, each case
 * under one or two diagonal modes. */
typedef struct {
  const char *name;          /* file stem */
  const char *title;         /* Markdown title */
  const char *scheme;        /* scheme name */
  int nface;                 /* face rows: one per face_diag entry */
  ss_diag_mode face_diag[2]; /* their diagonal modes */
  int lo, hi;                /* edge valences */
  int nedge;                 /* edge rows per valence: one per edge_diag entry */
  ss_diag_mode edge_diag[2]; /* their diagonal modes */
  const char *papers;        /* the closing line: what the paper says */
} jsr_table;

/* The budgets.  Word length K of rho_k and of the brute-force lower bound:
 * the face has 4 maps (4 + ... + 4^K products), an edge 2.  The branch and
 * bound forms at most JSR_NODES products and has no time limit, so the
 * tables are the same on every run and machine speed. */
enum { FACE_DEPTH = 6, EDGE_DEPTH = 8, JSR_NODES = 10000 };
static const double JSR_GAP = 1e-3;

static const jsr_table tables[] = {
    {"tetoct-jsr",
     "Tet/oct: the joint spectral radius test (face, edges 3..10)",
     "tetoct",
     1,
     {SS_DIAG_BFS},
     3,
     10,
     1,
     {SS_DIAG_BFS},
     "The paper's ρ^[9] = 0.238 of the face is compared with ours in the same "
     "∞-norm, which depends on the basis of the complement of the quadratics (a "
     "change G of it alters ρ^[k] by at most cond(G)^(1/k)): ours is Y_i = Q_2ᵀ S_i "
     "Q_2, Q_2 the orthonormal complement from the QR factorisation of the "
     "quadratics sampled on the support in the order of `jsr --face`; the paper "
     "does not state its basis.  Its edge statement: valences 4..10 pass; for "
     "n = 3 it \"could not find a k\" (read as undecided)."},
    {"boxspline-jsr",
     "Box-spline solids: the joint spectral radius test (face, edges 4..9)",
     "boxspline",
     2,
     {SS_DIAG_BFS, SS_DIAG_PROPER},
     4,
     9,
     2,
     {SS_DIAG_CENTER, SS_DIAG_SKEW},
     "The box-spline paper runs no joint spectral radius test (it cites the tet/oct "
     "paper's): nothing is quoted."},
};
#define NTABLES (sizeof tables / sizeof tables[0])

size_t ss_reproduce_jsr_count(void) {
  return NTABLES;
}

const char *ss_reproduce_jsr_name(size_t i) {
  return i < NTABLES ? tables[i].name : NULL;
}

/* One computed row. */
typedef struct {
  ss_case c;           /* the case */
  ss_levin *L;         /* the reduction, NULL if it does not apply */
  char reason[512];    /* why not (ss_levin_new's message) */
  ss_jsr_result r;     /* bounds (when L) */
  const char *verdict; /* pass, fail, undecided or n/a */
} jsr_row;

static const char *verdict_of(const jsr_row *w) {
  if (!w->L) return "n/a";
  ss_verdict v;
  ss_levin_verdict(w->L, &w->r, &v);
  return ss_verdict_name(v.verdict);
}

static void label(const jsr_row *w, char *buf, size_t n) {
  if (w->c.kind == SS_CASE_FACE)
    snprintf(buf, n, "face (%s)", ss_diag_name(w->c.diag));
  else
    snprintf(buf, n, "edge %d (%s)", w->c.n, ss_diag_name(w->c.diag));
}

/* Markdown cell text: a bar would end the cell, a newline the row. */
static void cell(FILE *f, const char *s) {
  for (; *s; s++)
    fputs(*s == '|' ? "\\|" : *s == '\n' ? " " : (char[]){*s, 0}, f);
}

static ss_status compute_row(const ss_scheme *s, jsr_row *w, ss_error *err) {
  ss_error e = {0};
  ss_status st = ss_levin_new(s, &w->c, &w->L, &e);
  if (st == SS_EINTERNAL) { /* the reduction does not apply: a row, not an error */
    snprintf(w->reason, sizeof w->reason, "%s", e.msg);
    w->L = NULL;
    w->verdict = verdict_of(w);
    return SS_OK;
  }
  if (st) {
    *err = e;
    return st;
  }
  ss_jsr_opts o = ss_jsr_defaults();
  o.depth = w->c.kind == SS_CASE_FACE ? FACE_DEPTH : EDGE_DEPTH;
  o.gap = JSR_GAP;
  o.norm = SS_JSR_NORM_AUTO;
  o.max_nodes = JSR_NODES;
  o.max_seconds = 0; /* none: the node budget alone, for reproducible output */
  st = ss_jsr_compute(w->L->m, w->L->n - w->L->r, (const double *const *)w->L->Y, &o,
                      &w->r, err);
  if (!st) w->verdict = verdict_of(w);
  return st;
}

/* One level of rho_at: the products of prod (n x n) with every word of the
 * remaining length left, their largest inf-norm into *best; work holds
 * left matrices n x n. */
static void rho_words(const ss_levin *L, size_t n, const double *prod, int left,
                      double *work, double *best) {
  if (!left) {
    for (size_t i = 0; i < n; i++) {
      double row = 0;
      for (size_t j = 0; j < n; j++)
        row += fabs(prod[i * n + j]);
      *best = row > *best ? row : *best;
    }
    return;
  }
  gsl_matrix_const_view P = gsl_matrix_const_view_array(prod, n, n);
  gsl_matrix_view W = gsl_matrix_view_array(work, n, n);
  for (size_t a = 0; a < L->m; a++) { /* work = Y_a prod: the word extended */
    gsl_matrix_const_view Y = gsl_matrix_const_view_array(L->Y[a], n, n);
    gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, &Y.matrix, &P.matrix, 0.0, &W.matrix);
    rho_words(L, n, work, left - 1, work + n * n, best);
  }
}

/* rho^[K] = max over the m^K words of length K of ||Y_w||_inf^(1/K) (floating
 * point, as ss_jsr's rho_inf), for a quoted length beyond the table's depth;
 * NaN when out of memory.  Cost m^K n^3 (the tet/oct face, K = 9: seconds). */
static double rho_at(const ss_levin *L, int K) {
  const size_t n = L->n - L->r;
  double *work = malloc((size_t)(K + 1) * n * n * sizeof *work), best = 0;
  if (!work) return 0.0 / 0.0;
  for (size_t i = 0; i < n * n; i++)
    work[i] = i % (n + 1) == 0; /* the identity: the empty word */
  rho_words(L, n, work, K, work + n * n, &best);
  free(work);
  return pow(best, 1.0 / K);
}

/* Compare quoted jsr_* values with row w: writes the Markdown notes and TSV
 * lines, counts into ty; returns 0 none quoted, 1 all match, 2 some differ. */
static int compare_row(const jsr_table *t, const jsr_row *w, const ss_ref *ref,
                       FILE *notes, FILE *tsv, ss_jsr_tally *ty) {
  int status = 0;
  char lab[64];
  label(w, lab, sizeof lab);
  for (size_t j = 0; j < ref->n; j++) {
    const ss_ref_row *q = ref->row + j;
    if (strncmp(q->quantity, "jsr_", 4) ||
        !ss_report_ref_applies(q, t->scheme, w->c.kind, w->c.n, ss_diag_name(w->c.diag)))
      continue;
    ss_ref_value v;
    ss_error e = {0};
    if (ss_report_ref_eval(q->value, w->c.n, &v, &e)) continue; /* checked on load */
    char got[64];
    int match;
    if (!strcmp(q->quantity, "jsr_verdict")) {
      snprintf(got, sizeof got, "%s", w->verdict);
      match = v.kind == SS_REF_VERDICT && !strcmp(v.verdict, w->verdict);
    } else if (!strcmp(q->quantity, "jsr_threshold")) {
      const double x = w->L ? w->L->threshold : 0.0 / 0.0;
      snprintf(got, sizeof got, "%.17g", x);
      match = ss_report_ref_match(&v, x);
    } else { /* jsr_rhoK: rho^[K] in the inf-norm */
      int K = 0;
      ss_report_ref_quantity(q->quantity, &K);
      const double x = !w->L             ? 0.0 / 0.0
                       : K <= w->r.depth ? w->r.rho_inf[K - 1]
                                         : rho_at(w->L, K);
      snprintf(got, sizeof got, "%.6f", x);
      match = ss_report_ref_match(&v, x);
    }
    ty->quoted++;
    ty->match += (size_t)match;
    status = match && status != 2 ? 1 : 2;
    fprintf(notes, "| %s | %s | %s | %s | %s | ", lab, q->quantity, q->value, got,
            match ? "match" : "differ");
    cell(notes, q->location);
    fputs(": ", notes);
    cell(notes, q->quote);
    fputs(" |\n", notes);
    fprintf(tsv, "%s\t%s\t%s\t%s\t%s\t%s:%ld\n", lab, q->quantity, q->value, got,
            match ? "match" : "differ", q->file, q->line);
  }
  return status;
}

/* The head of table t: in m (Markdown) the title, how to regenerate it, the
 * test and its budget, the column header; in v (TSV) its header lines. */
static void write_head(const jsr_table *t, FILE *m, FILE *v) {
  fprintf(m, "# %s\n\n", t->title);
  fprintf(m,
          "Regenerate: `subspectra reproduce` (each case: `subspectra jsr --scheme %s "
          "--face|--edge N --diagonals D --format json`, which uses a time limit "
          "instead of a node budget; raw results in `data/%s.jsonl`, the comparison "
          "in `%s.tsv`).\n\n",
          t->scheme, t->name, t->name);
  fprintf(m,
          "The Levin–Levin test (tet/oct paper, appendix A): the sub-patch maps S_i of "
          "the patch (face: 4, an edge: 2), reduced to the blocks Y_i on the complement "
          "of the subspace the smoothness order needs (face: the quadratics, 10; edge: "
          "1, λ1, λ1, ½, 4).  ρ_k = max over words of length k of ‖Y_w‖∞^(1/k), k = 1..K "
          "(the paper's ρ^[k]; K = %d for the face, %d for edges: every word).  "
          "*lower*: the largest ρ(Y_w)^(1/|w|) found, enclosed in ball arithmetic; "
          "*upper*: Gripenberg's branch and bound in the norm with the lower first "
          "pass (inf-norm, weighted inf-norm, 2-norm or an ellipsoidal norm fitted "
          "to the Y_i, whose similar copies are enclosed in ball arithmetic; `norm` "
          "in the JSON lines), every product's rounding bounded — both bounds are proven "
          "for the computed Y_i (*certified*), not for "
          "the rounding in forming Y_i.  Budget: at most %d products in the branch and "
          "bound, relative gap %g, no time limit (so the table is the same on every "
          "run).  Threshold: ¼ for the face (C² across it), λ3 = min(λ1, ½) for an "
          "edge.  Verdict: pass if upper < threshold, fail if lower ≥ threshold, else "
          "undecided; n/a if the reduction does not apply (the reason is given).\n\n",
          FACE_DEPTH, EDGE_DEPTH, JSR_NODES, JSR_GAP);
  fprintf(m,
          "| case | S_i | Y_i | ρ_k (inf-norm), k = 1..K | lower | upper | threshold "
          "| verdict | certified | paper |\n|---|---|---|---|---|---|---|---|---|---|\n");
  fprintf(v, "# %s: the joint spectral radius test (subspectra reproduce)\n", t->name);
  fprintf(v, "case\tmaps\tS_size\tY_size\trho_k_inf\tlower\tupper\tthreshold\tverdict\t"
             "certified\tconverged\tnodes\tpaper\n");
}

/* Row w in m (Markdown), v (TSV) and j (JSON lines), with its comparison
 * with the papers (paper: "not quoted", "match" or "differ"). */
static void write_row(const jsr_table *t, const jsr_row *w, const char *paper, FILE *m,
                      FILE *v, FILE *j) {
  char lab[64];
  label(w, lab, sizeof lab);
  fprintf(j, "{\"scheme\":\"%s\",\"case\":\"%s\",", t->scheme, ss_case_name(w->c.kind));
  if (w->c.kind == SS_CASE_EDGE) fprintf(j, "\"n\":%d,", w->c.n);
  fprintf(j, "\"diagonals\":\"%s\",", ss_diag_name(w->c.diag));
  if (!w->L) {
    fprintf(m, "| %s | — | — | — | — | — | — | n/a (", lab);
    cell(m, w->reason);
    fprintf(m, ") | — | %s |\n", paper);
    fprintf(v, "%s\t-\t-\t-\t-\t-\t-\t-\tn/a\t-\t-\t-\t%s\n", lab, paper);
    fprintf(j, "\"verdict\":\"n/a\",\"reason\":\"");
    for (const char *s = w->reason; *s; s++)
      fprintf(j, *s == '"' || *s == '\\' ? "\\%c" : "%c", *s);
    fprintf(j, "\"}\n");
    return;
  }
  const ss_levin *L = w->L;
  const ss_jsr_result *r = &w->r;
  const size_t ny = L->n - L->r;
  fprintf(m, "| %s | %zu × %zu² | %zu² | ", lab, L->m, L->n, ny);
  fprintf(v, "%s\t%zu\t%zu\t%zu\t", lab, L->m, L->n, ny);
  fprintf(j, "\"maps\":%zu,\"support\":%zu,\"subspace\":%zu,\"rho_k\":[", L->m, L->n,
          L->r);
  for (int k = 0; k < r->depth; k++) {
    fprintf(m, "%s%.4f", k ? ", " : "", r->rho_inf[k]);
    fprintf(v, "%s%.6g", k ? "," : "", r->rho_inf[k]);
    fprintf(j, "%s%.17g", k ? "," : "", r->rho_inf[k]);
  }
  fprintf(m, " | %.6f | %.6f | %.6g | %s | %s | %s |\n", r->lower, r->upper, L->threshold,
          w->verdict, r->certified ? "yes" : "no", paper);
  fprintf(v, "\t%.9g\t%.9g\t%.17g\t%s\t%d\t%d\t%zu\t%s\n", r->lower, r->upper,
          L->threshold, w->verdict, r->certified, r->converged, r->nodes, paper);
  fprintf(j,
          "],\"lower\":%.17g,\"upper\":%.17g,\"threshold\":%.17g,\"verdict\":\"%s\","
          "\"certified\":%s,\"converged\":%s,\"nodes\":%zu,\"bnb_depth\":%d,"
          "\"norm\":\"%s\"}\n",
          r->lower, r->upper, L->threshold, w->verdict, r->certified ? "true" : "false",
          r->converged ? "true" : "false", r->nodes, r->bnb_depth,
          r->norm == SS_JSR_NORM_ELLIPSOID ? "ellipsoid"
          : r->norm == SS_JSR_NORM_2       ? "2"
          : r->weighted                    ? "weighted inf"
                                           : "inf");
}

/* The end of the table: the summary *ty in m and v, then the quoted values
 * compared (nbuf, nlen bytes of Markdown rows; tbuf, tlen of TSV lines). */
static void write_tail(const jsr_table *t, FILE *m, FILE *v, const ss_jsr_tally *ty,
                       const char *nbuf, size_t nlen, const char *tbuf, size_t tlen) {
  fprintf(
      m,
      "\n**Summary:** %zu of %zu cases pass; the reduction applies to %zu; %zu quoted "
      "values: %zu match, %zu differ.\n",
      ty->pass, ty->cases, ty->reduced, ty->quoted, ty->match, ty->quoted - ty->match);
  fprintf(v,
          "# summary: %zu of %zu cases pass; %zu quoted values: %zu match, %zu differ\n",
          ty->pass, ty->cases, ty->quoted, ty->match, ty->quoted - ty->match);
  if (nlen) {
    fprintf(m, "\n## Quoted by the papers (data/reference/*.tsv)\n\n| case | quantity | "
               "quoted | computed | | source: quote |\n|---|---|---|---|---|---|\n");
    fwrite(nbuf, 1, nlen, m);
  }
  fprintf(m, "\n%s\n", t->papers);
  if (tlen) {
    fprintf(v, "# quoted\ncase\tquantity\tquoted\tcomputed\tmatch\tsource\n");
    fwrite(tbuf, 1, tlen, v);
  }
}

/* Write DIR/NAME.md, DIR/NAME.tsv and DIR/data/NAME.jsonl of table t from
 * its n computed rows, each compared with the quoted values of ref (counted
 * in *ty); each file whole or not at all. */
static ss_status write_all(const jsr_table *t, const char *dir, const jsr_row *rows,
                           size_t n, const ss_ref *ref, ss_jsr_tally *ty, ss_error *err) {
  ss_status st = SS_OK;
  char *path = malloc(strlen(dir) + strlen(t->name) + 32);
  char *nbuf = NULL, *tbuf = NULL;
  size_t nlen = 0, tlen = 0;
  FILE *notes = NULL, *tsvb = NULL;
  ss_outfile *md = NULL, *tsv = NULL, *js = NULL;
  if (!path || !(notes = open_memstream(&nbuf, &nlen)) ||
      !(tsvb = open_memstream(&tbuf, &tlen))) {
    st = ss_error_nomem(err, "jsr table");
    goto done;
  }
  sprintf(path, "%s/%s.md", dir, t->name);
  if ((st = ss_outfile_open(path, &md, err))) goto done;
  sprintf(path, "%s/%s.tsv", dir, t->name);
  if ((st = ss_outfile_open(path, &tsv, err))) goto done;
  sprintf(path, "%s/data/%s.jsonl", dir, t->name);
  if ((st = ss_outfile_open(path, &js, err))) goto done;
  FILE *m = ss_outfile_file(md), *v = ss_outfile_file(tsv), *j = ss_outfile_file(js);
  int *status = calloc(n ? n : 1, sizeof *status);
  if (!status) {
    st = ss_error_nomem(err, "jsr table");
    goto done;
  }
  for (size_t i = 0; i < n; i++) {
    status[i] = compare_row(t, rows + i, ref, notes, tsvb, ty);
    ty->pass += !strcmp(rows[i].verdict, "pass");
    ty->reduced += rows[i].L != NULL;
  }
  ty->cases = n;
  fflush(notes);
  fflush(tsvb);

  write_head(t, m, v);
  for (size_t i = 0; i < n; i++)
    write_row(t, rows + i,
              status[i] == 0   ? "not quoted"
              : status[i] == 1 ? "match"
                               : "differ",
              m, v, j);
  free(status);
  write_tail(t, m, v, ty, nbuf, nlen, tbuf, tlen);
  st = ss_outfile_commit(md, err);
  md = NULL;
  if (!st) st = ss_outfile_commit(tsv, err);
  tsv = NULL;
  if (!st) st = ss_outfile_commit(js, err);
  js = NULL;
done:
  if (md) ss_outfile_abort(md);
  if (tsv) ss_outfile_abort(tsv);
  if (js) ss_outfile_abort(js);
  if (notes) fclose(notes);
  if (tsvb) fclose(tsvb);
  free(nbuf);
  free(tbuf);
  free(path);
  return st;
}

ss_status ss_reproduce_jsr_table(size_t i, const char *dir, const ss_ref *ref,
                                 ss_jsr_tally *ty, ss_error *err) {
  if (i >= NTABLES) return ss_error_set(err, SS_EINPUT, "no JSR table %zu", i);
  const jsr_table *t = tables + i;
  memset(ty, 0, sizeof *ty);
  const size_t n = (size_t)t->nface + (size_t)(t->hi - t->lo + 1) * (size_t)t->nedge;
  jsr_row *rows = calloc(n, sizeof *rows);
  ss_scheme *s = NULL;
  ss_status st = rows ? ss_scheme_new(t->scheme, &s, err) : ss_error_nomem(err, "rows");
  size_t k = 0;
  for (int f = 0; !st && f < t->nface; f++, k++) {
    rows[k].c.kind = SS_CASE_FACE;
    rows[k].c.diag = t->face_diag[f];
    st = compute_row(s, rows + k, err);
  }
  for (int e = t->lo; !st && e <= t->hi; e++)
    for (int d = 0; !st && d < t->nedge; d++, k++) {
      rows[k].c.kind = SS_CASE_EDGE;
      rows[k].c.n = e;
      rows[k].c.diag = t->edge_diag[d];
      st = compute_row(s, rows + k, err);
    }
  if (!st) st = write_all(t, dir, rows, n, ref, ty, err);
  for (size_t r = 0; rows && r < n; r++) {
    ss_levin_free(rows[r].L);
    ss_jsr_result_clear(&rows[r].r);
  }
  free(rows);
  ss_scheme_free(s);
  return st;
}
