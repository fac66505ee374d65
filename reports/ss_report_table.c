/* ss_report_table.c — rows of a results store, their summary and the table
 * writers (ss_report_table.h). */
#include "ss_report_table.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <json-c/json.h>

#define NLAMBDA 4 /* lambda1..lambda4 in the cases table */

/* ---- rows ---- */

ss_status ss_report_rows_append(ss_report_rows *t, const ss_store_row *row,
                                ss_error *err) {
  if (t->n == t->cap) {
    const size_t cap = t->cap ? 2 * t->cap : 64;
    ss_report_row *p = realloc(t->row, cap * sizeof *p);
    if (!p) return ss_error_nomem(err, "report rows");
    t->row = p;
    t->cap = cap;
  }
  ss_report_row *d = &t->row[t->n];
  d->r = row->r;
  d->scheme = strdup(row->scheme ? row->scheme : "");
  d->identity = strdup(row->identity ? row->identity : "");
  d->r.link = strdup(row->r.link ? row->r.link : "");
  if (!d->scheme || !d->identity || !d->r.link) {
    free(d->scheme);
    free(d->identity);
    free(d->r.link);
    return ss_error_nomem(err, "report row");
  }
  t->n++;
  return SS_OK;
}

/* ss_store_each visitor: copy the row; stop on failure. */
typedef struct {
  ss_report_rows *t; /* where rows go */
  ss_error *err;     /* the caller's error */
  ss_status st;      /* first failure */
} load_ctx;

static int load_visit(const ss_store_row *row, void *ctx) {
  load_ctx *c = ctx;
  c->st = ss_report_rows_append(c->t, row, c->err);
  return c->st != SS_OK;
}

/* Order of rows: identity, kind (enum order), k, link. */
static int row_cmp(const void *a, const void *b) {
  const ss_report_row *x = a, *y = b;
  int c = strcmp(x->identity, y->identity);
  if (!c && x->r.kind != y->r.kind) c = x->r.kind < y->r.kind ? -1 : 1;
  if (!c && x->r.k != y->r.k) c = x->r.k < y->r.k ? -1 : 1;
  return c ? c : strcmp(x->r.link, y->r.link);
}

ss_status ss_report_rows_load(ss_store *st, const char *where, ss_report_rows *t,
                              ss_error *err) {
  const size_t n0 = t->n;
  load_ctx c = {t, err, SS_OK};
  ss_status s = ss_store_each(st, where, load_visit, &c, err);
  if (!s) s = c.st;
  if (!s && t->n > n0) qsort(t->row + n0, t->n - n0, sizeof *t->row, row_cmp);
  return s;
}

void ss_report_rows_clear(ss_report_rows *t) {
  if (!t) return;
  for (size_t i = 0; i < t->n; i++) {
    free(t->row[i].scheme);
    free(t->row[i].identity);
    free(t->row[i].r.link);
  }
  free(t->row);
  memset(t, 0, sizeof *t);
}

/* ---- summary ---- */

/* |lambda_i| of a row, NaN when not kept. */
static double modulus(const ss_result *r, int i) {
  return i < r->neig ? hypot(r->eig[i].re, r->eig[i].im) : (double)NAN;
}

/* Order of the group key (identity, kind, k). */
static int key_cmp(const ss_report_row *a, const ss_report_row *b) {
  const int c = strcmp(a->identity, b->identity);
  if (c) return c;
  if (a->r.kind != b->r.kind) return a->r.kind < b->r.kind ? -1 : 1;
  return (a->r.k > b->r.k) - (a->r.k < b->r.k);
}

static int ptr_cmp(const void *a, const void *b) {
  const ss_report_row *x = *(const ss_report_row *const *)a;
  const ss_report_row *y = *(const ss_report_row *const *)b;
  const int c = key_cmp(x, y);
  /* stable: equal keys keep the input order */
  return c ? c : (x > y) - (x < y);
}

static double min_nan(double a, double b) {
  return isnan(a) ? b : isnan(b) ? a : (b < a ? b : a);
}

static double max_nan(double a, double b) {
  return isnan(a) ? b : isnan(b) ? a : (b > a ? b : a);
}

ss_status ss_report_summarize(const ss_report_row *rows, size_t n,
                              ss_report_summary **out, size_t *nout, ss_error *err) {
  *out = NULL;
  *nout = 0;
  if (n == 0) return SS_OK;
  const ss_report_row **p = malloc(n * sizeof *p);
  ss_report_summary *s = malloc(n * sizeof *s);
  if (!p || !s) {
    free(p);
    free(s);
    return ss_error_nomem(err, "report summary");
  }
  for (size_t i = 0; i < n; i++)
    p[i] = &rows[i];
  qsort(p, n, sizeof *p, ptr_cmp);
  size_t m = 0;
  for (size_t i = 0; i < n; i++) {
    const ss_report_row *r = p[i];
    if (i == 0 || key_cmp(p[i - 1], r) != 0) {
      ss_report_summary *g = &s[m++];
      memset(g, 0, sizeof *g);
      g->identity = r->identity;
      g->scheme = r->scheme;
      g->kind = r->r.kind;
      g->k = r->r.k;
      g->worst_sj = g->l1_min = g->l1_max = (double)NAN;
    }
    ss_report_summary *g = &s[m - 1];
    g->cases++;
    switch (ss_result_verdict(&r->r)) {
    case SS_PASS:
      g->pass++;
      break;
    case SS_FAIL:
      g->fail++;
      break;
    default:
      g->undecided++;
      break;
    }
    if (isnan(r->r.min_sj)) g->no_map++;
    g->certified += (size_t)ss_result_certified(&r->r);
    g->worst_sj = min_nan(g->worst_sj, r->r.min_sj);
    const double l1 = modulus(&r->r, 1);
    g->l1_min = min_nan(g->l1_min, l1);
    g->l1_max = max_nan(g->l1_max, l1);
  }
  free(p);
  ss_report_summary *shrunk = realloc(s, m * sizeof *s);
  *out = shrunk ? shrunk : s;
  *nout = m;
  return SS_OK;
}

void ss_report_tol_range(const ss_report_row *rows, size_t n, double *lo, double *hi) {
  *lo = *hi = (double)NAN;
  for (size_t i = 0; i < n; i++) {
    *lo = min_nan(*lo, rows[i].r.tol);
    *hi = max_nan(*hi, rows[i].r.tol);
  }
}

int ss_report_format_parse(const char *name, ss_report_format *fmt) {
  static const char *const names[] = {"md", "csv", "tex", "json"};
  for (int i = 0; i < 4; i++)
    if (!strcmp(name, names[i])) {
      *fmt = (ss_report_format)i;
      return 0;
    }
  return -1;
}

int ss_report_tables_parse(const char *name, unsigned *tables) {
  if (!strcmp(name, "cases"))
    *tables = SS_REPORT_CASES;
  else if (!strcmp(name, "summary"))
    *tables = SS_REPORT_SUMMARY;
  else if (!strcmp(name, "both"))
    *tables = SS_REPORT_BOTH;
  else
    return -1;
  return 0;
}

/* ---- cell text shared by Markdown and LaTeX ---- */

/* A value of lambda_i with 6 decimals, "a+bi" when complex; "" when not
 * kept.  math: wrap in $...$ (LaTeX). */
static void fmt_lambda(char *buf, size_t n, const ss_result *r, int i, int math) {
  const char *d = math ? "$" : "";
  if (i >= r->neig)
    snprintf(buf, n, "%s", math ? "--" : "–");
  else if (r->eig[i].im == 0.0)
    snprintf(buf, n, "%s%.6f%s", d, r->eig[i].re, d);
  else
    snprintf(buf, n, "%s%.6f%+.6fi%s", d, r->eig[i].re, r->eig[i].im, d);
}

/* Multiplicities of lambda1..4, comma separated. */
static void fmt_mult(char *buf, size_t n, const ss_result *r) {
  size_t len = 0;
  buf[0] = '\0';
  for (int i = 1; i <= NLAMBDA && i < r->neig && len < n; i++)
    len += (size_t)snprintf(buf + len, n - len, "%s%d", i > 1 ? "," : "", r->eig[i].mult);
}

/* A scaled Jacobian or modulus for reading: 4 decimals, or 3 significant
 * digits when tiny (a sign matters near 0); "none" when NaN. */
static void fmt_short(char *buf, size_t n, double v, int math, const char *none) {
  const char *d = math ? "$" : "";
  if (isnan(v))
    snprintf(buf, n, "%s", none);
  else if (v != 0.0 && fabs(v) < 1e-3)
    snprintf(buf, n, "%s%.2e%s", d, v, d);
  else
    snprintf(buf, n, "%s%.4f%s", d, v, d);
}

/* "pass", or "fail: reason". */
static void fmt_verdict(char *buf, size_t n, const ss_verdict *v) {
  snprintf(buf, n, "%s%s%s", ss_verdict_name(v->verdict), v->reason[0] ? ": " : "",
           v->reason);
}

static void fmt_k(char *buf, size_t n, const ss_result *r, const char *none) {
  if (r->kind == SS_CASE_FACE)
    snprintf(buf, n, "%s", none);
  else
    snprintf(buf, n, "%d", r->k);
}

/* Any row with major diagonals?  Then the tables get an improper-pairs
 * column. */
static int any_diag(const ss_report_row *rows, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (rows[i].r.has_diag) return 1;
  return 0;
}

/* The tolerance of the rows as text ("1e-06", or "1e-08 to 1e-06"). */
static void fmt_tol(char *buf, size_t n, const ss_report_row *rows, size_t nr) {
  double lo, hi;
  ss_report_tol_range(rows, nr, &lo, &hi);
  if (isnan(lo))
    snprintf(buf, n, "(no cases)");
  else if (lo == hi)
    snprintf(buf, n, "%g", lo);
  else
    snprintf(buf, n, "%g to %g", lo, hi);
}

/* ---- Markdown ---- */

/* Cell text: '|' escaped, line breaks as spaces. */
static void md_put(FILE *f, const char *s) {
  for (; *s; s++) {
    if (*s == '|')
      fputs("\\|", f);
    else if (*s == '\n' || *s == '\r')
      fputc(' ', f);
    else
      fputc(*s, f);
  }
}

static void md_cell(FILE *f, const char *s) {
  fputs(" ", f);
  md_put(f, s);
  fputs(" |", f);
}

static void md_cases(FILE *f, const ss_report_row *rows, size_t n) {
  const int diag = any_diag(rows, n);
  fprintf(f, "## Cases (%zu)\n\n", n);
  fputs("| scheme | case | k | cells | link | λ1 | λ2 | λ3 | λ4 | mult. λ1..4 "
        "| eigenvalue condition | regularity | min SJ |",
        f);
  fputs(diag ? " improper pairs |\n" : "\n", f);
  fputs("|---|---|--:|--:|---|--:|--:|--:|--:|---|---|---|--:|", f);
  fputs(diag ? "--:|\n" : "\n", f);
  char buf[600];
  for (size_t i = 0; i < n; i++) {
    const ss_result *r = &rows[i].r;
    fputs("|", f);
    md_cell(f, rows[i].scheme);
    md_cell(f, ss_case_name(r->kind));
    fmt_k(buf, sizeof buf, r, "–");
    md_cell(f, buf);
    snprintf(buf, sizeof buf, "%zu", r->cells);
    md_cell(f, buf);
    if (r->link[0]) {
      fputs(" `", f);
      md_put(f, r->link);
      fputs("` |", f);
    } else {
      md_cell(f, "");
    }
    for (int j = 1; j <= NLAMBDA; j++) {
      fmt_lambda(buf, sizeof buf, r, j, 0);
      md_cell(f, buf);
    }
    fmt_mult(buf, sizeof buf, r);
    md_cell(f, buf);
    fmt_verdict(buf, sizeof buf, &r->v.cond);
    md_cell(f, buf);
    fmt_verdict(buf, sizeof buf, &r->v.reg);
    md_cell(f, buf);
    fmt_short(buf, sizeof buf, r->min_sj, 0, "–");
    md_cell(f, buf);
    if (diag) {
      if (r->has_diag)
        snprintf(buf, sizeof buf, "%zu of %zu", r->improper, r->pairs);
      else
        snprintf(buf, sizeof buf, "–");
      md_cell(f, buf);
    }
    fputc('\n', f);
  }
  fputc('\n', f);
}

static void md_summary(FILE *f, const ss_report_summary *s, size_t ns) {
  fprintf(f, "## Summary (%zu groups)\n\n", ns);
  fputs("| scheme identity | case | k | cases | pass | fail | undecided | certified "
        "| worst min SJ | \\|λ1\\| range |\n"
        "|---|---|--:|--:|--:|--:|--:|--:|--:|---|\n",
        f);
  char buf[128], a[40], b[40];
  for (size_t i = 0; i < ns; i++) {
    const ss_report_summary *g = &s[i];
    fputs("|", f);
    md_cell(f, g->identity);
    md_cell(f, ss_case_name(g->kind));
    if (g->kind == SS_CASE_FACE)
      snprintf(buf, sizeof buf, "–");
    else
      snprintf(buf, sizeof buf, "%d", g->k);
    md_cell(f, buf);
    fprintf(f, " %zu | %zu | %zu | %zu | %zu |", g->cases, g->pass, g->fail, g->undecided,
            g->certified);
    fmt_short(buf, sizeof buf, g->worst_sj, 0, "–");
    md_cell(f, buf);
    if (isnan(g->l1_min)) {
      md_cell(f, "–");
    } else {
      snprintf(a, sizeof a, "%.6f", g->l1_min);
      snprintf(b, sizeof b, "%.6f", g->l1_max);
      if (!strcmp(a, b))
        md_cell(f, a);
      else {
        snprintf(buf, sizeof buf, "%s – %s", a, b);
        md_cell(f, buf);
      }
    }
    fputc('\n', f);
  }
  fputc('\n', f);
}

/* ---- LaTeX ---- */

/* Text with LaTeX's special characters escaped (and those the default OT1
 * font encoding would turn into other glyphs: | < >). */
static void tex_put(FILE *f, const char *s) {
  for (; *s; s++) {
    switch (*s) {
    case '_':
    case '&':
    case '%':
    case '#':
    case '$':
    case '{':
    case '}':
      fputc('\\', f);
      fputc(*s, f);
      break;
    case '~':
      fputs("\\textasciitilde{}", f);
      break;
    case '^':
      fputs("\\textasciicircum{}", f);
      break;
    case '\\':
      fputs("\\textbackslash{}", f);
      break;
    case '|':
      fputs("\\textbar{}", f);
      break;
    case '<':
      fputs("\\textless{}", f);
      break;
    case '>':
      fputs("\\textgreater{}", f);
      break;
    case '\n':
    case '\r':
      fputc(' ', f);
      break;
    default:
      fputc(*s, f);
    }
  }
}

/* A tolerance in math: $10^{-6}$ or $2.5\times10^{-7}$. */
static void tex_tol(FILE *f, double t) {
  if (!(t > 0.0) || !isfinite(t)) {
    fprintf(f, "%g", t);
    return;
  }
  int e = (int)floor(log10(t));
  double m = t / pow(10.0, e);
  if (m >= 10.0 - 1e-9) { /* log10 rounded down a power of ten */
    m /= 10.0;
    e++;
  }
  if (fabs(m - 1.0) < 1e-9)
    fprintf(f, "$10^{%d}$", e);
  else
    fprintf(f, "$%.4g\\times10^{%d}$", m, e);
}

static void tex_caption_tol(FILE *f, const ss_report_row *rows, size_t n) {
  double lo, hi;
  ss_report_tol_range(rows, n, &lo, &hi);
  if (isnan(lo)) {
    fputs("no cases selected", f);
    return;
  }
  fputs("eigenvalues equal within a relative tolerance of ", f);
  tex_tol(f, lo);
  if (hi != lo) {
    fputs(" to ", f);
    tex_tol(f, hi);
  }
}

/* A link in \texttt, breakable after each comma (a k = 9 link is 60
 * characters: it has to wrap in its column). */
static void tex_link(FILE *f, const char *link) {
  fputs("\\texttt{", f);
  char one[2] = {0, 0};
  for (const char *p = link; *p; p++) {
    one[0] = *p;
    tex_put(f, one);
    if (*p == ',') fputs("\\allowbreak{}", f);
  }
  fputs("}", f);
}

/* The cases table as a longtable (it runs over pages; the header repeats),
 * \\scriptsize with narrow column gaps.  Each case is one line of numbers
 * and verdicts, followed by a full-width line with what is long — the link
 * and the verdicts' reasons — so that the table fits \\linewidth of a
 * one-column article (checked with pdflatex in
 * tests/reports/test_report_tex.sh). */
/* A verdict in a narrow column: "undecided" is shortened (the caption says so). */
static const char *tex_verdict(ss_verdict_kind v) {
  return v == SS_UNDECIDED ? "undec." : ss_verdict_name(v);
}

static void tex_cases(FILE *f, const ss_report_row *rows, size_t n, const char *label) {
  /* one scheme: named in the caption instead of a column */
  int one = n > 0;
  for (size_t i = 1; i < n && one; i++)
    one = !strcmp(rows[i].scheme, rows[0].scheme);
  const int diag = any_diag(rows, n), ncol = 11 + diag + !one;
  const char *head = "case & $k$ & cells & $\\lambda_1$ & $\\lambda_2$ & "
                     "$\\lambda_3$ & $\\lambda_4$ & mult. & eig.\\ cond. & "
                     "regularity & min.\\ SJ";
  fputs("{\\scriptsize\n\\setlength{\\tabcolsep}{2pt}\n", f);
  fprintf(f, "\\begin{longtable}{@{}%slrrrrrrlllr%s@{}}\n", one ? "" : "l",
          diag ? "r" : "");
  fputs("\\caption{", f);
  if (one) {
    fputs("Scheme \\texttt{", f);
    tex_put(f, rows[0].scheme);
    fputs("}.  ", f);
  }
  fputs("Cases: leading eigenvalues "
        "$\\lambda_1,\\dots,\\lambda_4$ of the local subdivision matrix on the "
        "two-ring, by decreasing modulus, with multiplicities (",
        f);
  tex_caption_tol(f, rows, n);
  fputs("); verdicts of the eigenvalue condition and of the regularity of the "
        "characteristic map; minimum scaled Jacobian (--: no map)",
        f);
  fputs(diag ? "; improper pairs of major diagonals among adjacent cell pairs (impr.)"
             : "",
        f);
  fputs(".  Below each case: its link (vertex cases) and the reasons of verdicts "
        "that do not pass (undec.: undecided).}",
        f);
  fprintf(f,
          "\\label{tab:%s-cases}\\\\\n\\toprule\n%s%s%s\\\\\n\\midrule\n"
          "\\endfirsthead\n",
          label, one ? "" : "scheme & ", head, diag ? " & impr." : "");
  fprintf(f,
          "\\multicolumn{%d}{@{}l}{\\tablename~\\thetable{} (continued)}\\\\\n"
          "\\toprule\n%s%s%s\\\\\n\\midrule\n\\endhead\n\\bottomrule\n\\endfoot\n",
          ncol, one ? "" : "scheme & ", head, diag ? " & impr." : "");
  char buf[600];
  for (size_t i = 0; i < n; i++) {
    const ss_result *r = &rows[i].r;
    if (!one) {
      tex_put(f, rows[i].scheme);
      fputs(" & ", f);
    }
    fprintf(f, "%s & ", ss_case_name(r->kind));
    fmt_k(buf, sizeof buf, r, "--");
    fprintf(f, "%s & %zu", buf, r->cells);
    for (int j = 1; j <= NLAMBDA; j++) {
      fmt_lambda(buf, sizeof buf, r, j, 1);
      fprintf(f, " & %s", buf);
    }
    fmt_mult(buf, sizeof buf, r);
    fprintf(f, " & %s & %s & %s", buf, tex_verdict(r->v.cond.verdict),
            tex_verdict(r->v.reg.verdict));
    fmt_short(buf, sizeof buf, r->min_sj, 1, "--");
    fprintf(f, " & %s", buf);
    if (diag) {
      if (r->has_diag)
        fprintf(f, " & %zu/%zu", r->improper, r->pairs);
      else
        fputs(" & --", f);
    }
    fputs(" \\\\\n", f);
    if (!r->link[0] && !r->v.cond.reason[0] && !r->v.reg.reason[0]) continue;
    fprintf(f, "\\multicolumn{%d}{@{\\quad}p{\\dimexpr\\linewidth-1em\\relax}@{}}{",
            ncol);
    const char *sep = "";
    if (r->link[0]) {
      fputs("link ", f);
      tex_link(f, r->link);
      sep = "; ";
    }
    if (r->v.cond.reason[0]) {
      fprintf(f, "%seigenvalue condition: ", sep);
      tex_put(f, r->v.cond.reason);
      sep = "; ";
    }
    if (r->v.reg.reason[0]) {
      fprintf(f, "%sregularity: ", sep);
      tex_put(f, r->v.reg.reason);
    }
    fputs("} \\\\[2pt]\n", f);
  }
  fputs("\\end{longtable}\n}\n", f);
}

/* The summary, a longtable as well (a sweep over many k is longer than a
 * page); the scheme identity (with its options) wraps in its column. */
static void tex_summary(FILE *f, const ss_report_summary *s, size_t ns,
                        const ss_report_row *rows, size_t n, const char *label) {
  const char *head = "scheme identity & case & $k$ & cases & pass & fail & undec. & "
                     "min.\\ SJ & $|\\lambda_1|$ \\\\\n\\midrule\n";
  fputs("{\\footnotesize\n\\setlength{\\tabcolsep}{3pt}\n"
        "\\begin{longtable}{@{}>{\\raggedright\\arraybackslash}p{0.22\\linewidth}"
        "lrrrrrrl@{}}\n"
        "\\caption{Summary per scheme, case and $k$ "
        "(vertex: link vertices; edge: valence): cases that pass both the eigenvalue "
        "condition and regularity, that fail either, or are undecided (undec.); the "
        "worst minimum scaled Jacobian (min.\\ SJ) and the range of $|\\lambda_1|$ (",
        f);
  tex_caption_tol(f, rows, n);
  fprintf(f, ").}\\label{tab:%s-summary}\\\\\n\\toprule\n%s\\endfirsthead\n", label,
          head);
  fprintf(f,
          "\\multicolumn{9}{@{}l}{\\tablename~\\thetable{} (continued)}\\\\\n"
          "\\toprule\n%s\\endhead\n\\bottomrule\n\\endfoot\n",
          head);
  char buf[128];
  for (size_t i = 0; i < ns; i++) {
    const ss_report_summary *g = &s[i];
    tex_put(f, g->identity);
    fprintf(f, " & %s & ", ss_case_name(g->kind));
    if (g->kind == SS_CASE_FACE)
      fputs("--", f);
    else
      fprintf(f, "%d", g->k);
    fprintf(f, " & %zu & %zu & %zu & %zu & ", g->cases, g->pass, g->fail, g->undecided);
    fmt_short(buf, sizeof buf, g->worst_sj, 1, "--");
    fputs(buf, f);
    if (isnan(g->l1_min))
      fputs(" & --", f);
    else {
      char a[40], b[40];
      snprintf(a, sizeof a, "%.6f", g->l1_min);
      snprintf(b, sizeof b, "%.6f", g->l1_max);
      if (!strcmp(a, b))
        fprintf(f, " & $%s$", a);
      else
        fprintf(f, " & $%s$--$%s$", a, b);
    }
    fputs(" \\\\\n", f);
  }
  fputs("\\end{longtable}\n}\n", f);
}

/* ---- CSV ----
 * Written by hand, and kept so: the only Debian C library for the format,
 * libcsv (libcsv-dev), writes a field with csv_fwrite, which quotes every
 * field; RFC 4180 allows that, but the form `report --format csv` has always
 * written — a field quoted only when it holds a comma, quote or line break,
 * which spreadsheets, pandas and Python's csv module read alike — is the
 * dozen lines of ss_report_csv_put, less than the dependency (issue 40). */

void ss_report_csv_put(FILE *f, const char *s) {
  if (!strpbrk(s, ",\"\r\n")) {
    fputs(s, f);
    return;
  }
  fputc('"', f);
  for (; *s; s++) {
    if (*s == '"') fputc('"', f);
    fputc(*s, f);
  }
  fputc('"', f);
}

/* A double with 17 significant digits (reads back bit for bit); empty when
 * NaN. */
static void csv_num(FILE *f, double v) {
  if (!isnan(v)) fprintf(f, "%.17g", v);
}

/* Whether psi was judged on its pieces for some row (sweep --psi-depth). */
static int any_psi(const ss_report_row *rows, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (rows[i].r.psi.ran) return 1;
  return 0;
}

/* What v was judged on, as a CSV field (empty: not judged, or not
 * recorded). */
static const char *csv_on(const ss_verdict *v) {
  return v->on == SS_ON_NOTHING ? "" : ss_judged_on_name(v->on);
}

static void csv_cases(FILE *f, const ss_report_row *rows, size_t n) {
  /* the columns of psi only when some row has it: the table of a store
   * without psi is what it was before they existed */
  const int psi = any_psi(rows, n);
  fputs("scheme,identity,case,k,link,cells,two_ring,one_ring", f);
  for (int j = 1; j <= NLAMBDA; j++)
    fprintf(f, ",lambda%d_re,lambda%d_im,lambda%d_mult", j, j, j);
  fputs(",eigen_condition,eigen_reason,tolerance,regularity,regularity_reason,"
        "verdict,min_scaled_jacobian,depth,improper_pairs,adjacent_pairs,seconds,"
        "eigen_certified,regularity_certified,ring_level,centre_corner_folds,"
        "injectivity,injectivity_reason,degree,injectivity_certified",
        f);
  fputs(psi ? ",eigen_on,regularity_on,injectivity_on,psi_verdict,psi_covered,"
              "psi_uncovered,psi_pieces\r\n"
            : "\r\n",
        f);
  for (size_t i = 0; i < n; i++) {
    const ss_result *r = &rows[i].r;
    ss_report_csv_put(f, rows[i].scheme);
    fputc(',', f);
    ss_report_csv_put(f, rows[i].identity);
    fprintf(f, ",%s,%d,", ss_case_name(r->kind), r->k);
    ss_report_csv_put(f, r->link);
    fprintf(f, ",%zu,%zu,%zu", r->cells, r->two_ring, r->one_ring);
    for (int j = 1; j <= NLAMBDA; j++) {
      if (j < r->neig)
        fprintf(f, ",%.17g,%.17g,%d", r->eig[j].re, r->eig[j].im, r->eig[j].mult);
      else
        fputs(",,,", f);
    }
    fprintf(f, ",%s,", ss_verdict_name(r->v.cond.verdict));
    ss_report_csv_put(f, r->v.cond.reason);
    fprintf(f, ",%.17g,%s,", r->tol, ss_verdict_name(r->v.reg.verdict));
    ss_report_csv_put(f, r->v.reg.reason);
    fprintf(f, ",%s,", ss_verdict_name(ss_result_verdict(r)));
    csv_num(f, r->min_sj);
    fprintf(f, ",%d,", r->depth);
    if (r->has_diag)
      fprintf(f, "%zu,%zu", r->improper, r->pairs);
    else
      fputc(',', f);
    fprintf(f, ",%.17g,%d,%d,%d,%zu,%s,", r->seconds, r->v.cond.certified,
            r->v.reg.certified, r->ring_level, r->centre_corner_folds,
            ss_verdict_name(r->v.inj.verdict));
    ss_report_csv_put(f, r->v.inj.reason);
    fprintf(f, ",%d,%d", r->inj_degree, r->v.inj.certified);
    if (psi) {
      fprintf(f, ",%s,%s,%s,", csv_on(&r->v.cond), csv_on(&r->v.reg), csv_on(&r->v.inj));
      if (r->psi.ran) {
        fprintf(f, "%s,", ss_verdict_name(r->psi.verdict));
        csv_num(f, r->psi.covered);
        fputc(',', f);
        csv_num(f, r->psi.uncovered);
        fprintf(f, ",%zu", r->psi.pieces);
      } else
        fputs(",,,", f);
    }
    fputs("\r\n", f);
  }
}

static void csv_summary(FILE *f, const ss_report_summary *s, size_t ns) {
  fputs("identity,scheme,case,k,cases,pass,fail,undecided,no_map,"
        "worst_min_scaled_jacobian,lambda1_min,lambda1_max,certified\r\n",
        f);
  for (size_t i = 0; i < ns; i++) {
    const ss_report_summary *g = &s[i];
    ss_report_csv_put(f, g->identity);
    fputc(',', f);
    ss_report_csv_put(f, g->scheme);
    fprintf(f, ",%s,%d,%zu,%zu,%zu,%zu,%zu,", ss_case_name(g->kind), g->k, g->cases,
            g->pass, g->fail, g->undecided, g->no_map);
    csv_num(f, g->worst_sj);
    fputc(',', f);
    csv_num(f, g->l1_min);
    fputc(',', f);
    csv_num(f, g->l1_max);
    fprintf(f, ",%zu\r\n", g->certified);
  }
}

/* ---- JSON ---- */

/* A number, or null for NaN (JSON has no NaN). */
static json_object *jnum(double v) {
  return isfinite(v) ? json_object_new_double(v) : NULL;
}

static json_object *jsize(size_t v) {
  return json_object_new_int64((int64_t)v);
}

json_object *ss_report_verdict_json(const ss_verdict *v) {
  json_object *o = json_object_new_object();
  json_object_object_add(o, "verdict",
                         json_object_new_string(ss_verdict_name(v->verdict)));
  json_object_object_add(o, "certified", json_object_new_boolean(v->certified));
  json_object_object_add(o, "reason", json_object_new_string(v->reason));
  json_object_object_add(
      o, "judged_on",
      v->on == SS_ON_NOTHING ? NULL : json_object_new_string(ss_judged_on_name(v->on)));
  return o;
}

json_object *ss_report_psi_json(const ss_result_psi *p) {
  if (!p->ran) return NULL;
  json_object *o = json_object_new_object();
  json_object_object_add(o, "verdict",
                         json_object_new_string(ss_verdict_name(p->verdict)));
  json_object_object_add(o, "judged_on",
                         json_object_new_string(ss_judged_on_name(SS_ON_PSI)));
  json_object_object_add(o, "covered", jnum(p->covered));
  json_object_object_add(o, "uncovered", jnum(p->uncovered));
  json_object_object_add(o, "pieces", jsize(p->pieces));
  return o;
}

static json_object *json_case(const ss_report_row *row) {
  const ss_result *r = &row->r;
  json_object *o = json_object_new_object();
  json_object_object_add(o, "scheme", json_object_new_string(row->scheme));
  json_object_object_add(o, "identity", json_object_new_string(row->identity));
  json_object_object_add(o, "case", json_object_new_string(ss_case_name(r->kind)));
  json_object_object_add(o, "k", json_object_new_int(r->k));
  if (r->valence) json_object_object_add(o, "valence", json_object_new_int(r->valence));
  if (ss_result_has_link(r))
    json_object_object_add(o, "link", json_object_new_string(r->link));
  json_object_object_add(o, "cells", jsize(r->cells));
  json_object_object_add(o, "two_ring_size", jsize(r->two_ring));
  json_object_object_add(o, "one_ring_size", jsize(r->one_ring));
  json_object_object_add(o, "eigenvalues", ss_report_eig_json(r));
  json_object *c = ss_report_verdict_json(&r->v.cond);
  json_object_object_add(c, "tolerance", json_object_new_double(r->tol));
  json_object_object_add(o, "eigen_condition", c);
  json_object *g = ss_report_verdict_json(&r->v.reg);
  json_object_object_add(g, "covered", r->psi.ran ? jnum(r->psi.covered) : NULL);
  json_object_object_add(g, "psi", ss_report_psi_json(&r->psi));
  json_object_object_add(g, "min_scaled_jacobian", jnum(r->min_sj));
  json_object_object_add(g, "depth", json_object_new_int(r->depth));
  json_object_object_add(g, "ring_level", json_object_new_int(r->ring_level));
  json_object_object_add(g, "centre_corner_folds", jsize(r->centre_corner_folds));
  json_object_object_add(o, "regularity", g);
  json_object *in = ss_report_verdict_json(&r->v.inj);
  json_object_object_add(in, "degree", json_object_new_int(r->inj_degree));
  json_object_object_add(o, "injectivity", in);
  json_object_object_add(o, "verdict",
                         json_object_new_string(ss_verdict_name(ss_result_verdict(r))));
  if (r->has_diag) {
    json_object *d = json_object_new_object();
    json_object_object_add(d, "pairs", jsize(r->pairs));
    json_object_object_add(d, "improper", jsize(r->improper));
    json_object_object_add(o, "diagonals", d);
  }
  json_object_object_add(o, "seconds", json_object_new_double(r->seconds));
  return o;
}

static json_object *json_group(const ss_report_summary *g) {
  json_object *o = json_object_new_object();
  json_object_object_add(o, "identity", json_object_new_string(g->identity));
  json_object_object_add(o, "scheme", json_object_new_string(g->scheme));
  json_object_object_add(o, "case", json_object_new_string(ss_case_name(g->kind)));
  json_object_object_add(o, "k", json_object_new_int(g->k));
  json_object_object_add(o, "cases", jsize(g->cases));
  json_object_object_add(o, "pass", jsize(g->pass));
  json_object_object_add(o, "fail", jsize(g->fail));
  json_object_object_add(o, "undecided", jsize(g->undecided));
  json_object_object_add(o, "no_map", jsize(g->no_map));
  json_object_object_add(o, "certified", jsize(g->certified));
  json_object_object_add(o, "worst_min_scaled_jacobian", jnum(g->worst_sj));
  json_object_object_add(o, "lambda1_min", jnum(g->l1_min));
  json_object_object_add(o, "lambda1_max", jnum(g->l1_max));
  return o;
}

/* The JSON object {"cases": [...], "summary": [...]} (the keys asked for). */
static ss_status write_json(FILE *f, unsigned tables, const ss_report_row *rows, size_t n,
                            const ss_report_summary *sum, size_t ns, ss_error *err) {
  json_object *o = json_object_new_object();
  if (!o) return ss_error_nomem(err, "JSON report");
  if (tables & SS_REPORT_CASES) {
    json_object *a = json_object_new_array_ext((int)(n < 16 ? 16 : n));
    for (size_t i = 0; a && i < n; i++)
      json_object_array_add(a, json_case(&rows[i]));
    json_object_object_add(o, "cases", a);
  }
  if (tables & SS_REPORT_SUMMARY) {
    json_object *a = json_object_new_array();
    for (size_t i = 0; a && i < ns; i++)
      json_object_array_add(a, json_group(&sum[i]));
    json_object_object_add(o, "summary", a);
  }
  const char *text = json_object_to_json_string_ext(
      o, JSON_C_TO_STRING_PLAIN | JSON_C_TO_STRING_NOSLASHESCAPE);
  ss_status s = SS_OK;
  if (!text)
    s = ss_error_nomem(err, "JSON report");
  else {
    fputs(text, f);
    fputc('\n', f);
  }
  json_object_put(o);
  return s;
}

/* ---- dispatch ---- */

ss_status ss_report_table_write(FILE *f, ss_report_format fmt, unsigned tables,
                                const ss_report_row *rows, size_t n,
                                const ss_report_summary *sum, size_t ns,
                                const char *label, ss_error *err) {
  tables &= SS_REPORT_BOTH;
  if (!tables) return ss_error_set(err, SS_EINPUT, "report: no table chosen");
  if (fmt == SS_REPORT_CSV && tables == SS_REPORT_BOTH)
    return ss_error_set(err, SS_EINPUT,
                        "report: CSV holds one table: choose cases or summary");
  ss_status s = SS_OK;
  char tol[80];
  switch (fmt) {
  case SS_REPORT_MD:
    if (tables & SS_REPORT_CASES) md_cases(f, rows, n);
    if (tables & SS_REPORT_SUMMARY) md_summary(f, sum, ns);
    fmt_tol(tol, sizeof tol, rows, n);
    fprintf(f,
            "λ1..λ4: leading eigenvalues of the local subdivision matrix on the "
            "two-ring, by decreasing modulus; %s%s%s. Verdicts: eigenvalue condition, "
            "regularity of the characteristic map (judged on its ring) and its "
            "injectivity; min SJ: minimum scaled Jacobian (–: no characteristic map). "
            "Summary: pass = all three hold, fail = one fails, else undecided; "
            "certified = verdicts proven (--certify).\n",
            n ? "eigenvalues equal within a relative tolerance of "
              : "equal ones grouped",
            n ? tol : "", n ? " are grouped (mult.)" : " (mult.)");
    break;
  case SS_REPORT_TEX:
    if (!label) label = "subspectra";
    fputs("% subspectra report: needs \\usepackage{booktabs,longtable,array}\n", f);
    if (tables & SS_REPORT_CASES) tex_cases(f, rows, n, label);
    if (tables & SS_REPORT_SUMMARY) tex_summary(f, sum, ns, rows, n, label);
    break;
  case SS_REPORT_CSV:
    if (tables & SS_REPORT_CASES)
      csv_cases(f, rows, n);
    else
      csv_summary(f, sum, ns);
    break;
  case SS_REPORT_JSON:
    s = write_json(f, tables, rows, n, sum, ns, err);
    break;
  default:
    return ss_error_set(err, SS_EINPUT, "report: unknown format %d", (int)fmt);
  }
  if (!s && (fflush(f) != 0 || ferror(f)))
    s = ss_error_set(err, SS_EIO, "report: cannot write the table");
  return s;
}

json_object *ss_report_eig_json(const ss_result *r) {
  json_object *ev = json_object_new_array();
  for (int i = 0; i < r->neig; i++) {
    json_object *x = json_object_new_object();
    json_object_object_add(x, "re", json_object_new_double(r->eig[i].re));
    json_object_object_add(x, "im", json_object_new_double(r->eig[i].im));
    json_object_object_add(x, "multiplicity", json_object_new_int(r->eig[i].mult));
    json_object_array_add(ev, x);
  }
  return ev;
}
