/* test_report.c — tables and plots of a results store: a store made of real
 * cases (MLCA vertex links and edges 3..8, where edge 8 fails the eigenvalue
 * condition and one k = 8 link fails regularity; boxspline with major
 * diagonals; the tetoct face), read back with and without --where; the
 * summary against counts made here from the verdicts; CSV parsed back to the
 * computed doubles bit for bit; Markdown and LaTeX structure and escaping;
 * JSON through json-c; PNG and SVG plots; the errors (bad where, foreign
 * file, CSV with two tables, unknown picture format). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cairo.h>
#include <json-c/json.h>

#include "ss_link.h"
#include "ss_report_plot.h"
#include "ss_report_table.h"
#include "ss_scheme.h"
#include "ss_store.h"
#include "ss_test.h"

#define MAXCASES 32

/* The cases computed here, the reference for everything read back. */
typedef struct {
  ss_result r[MAXCASES];       /* results */
  const char *ident[MAXCASES]; /* their scheme identities */
  size_t n;                    /* results */
} computed;

static char ident_mlca[256], ident_box[256], ident_tetoct[256];

static const char *const k8_fail = "8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb";

/* Compute case c of scheme s, store it under id, keep it in all. */
static void add_case(ss_store *st, int64_t id, const char *ident, const ss_scheme *s,
                     ss_case c, computed *all) {
  ss_error err = {0};
  ss_result_opts o = ss_result_defaults();
  ss_result r;
  REQUIRE_OK_VOID(ss_result_compute(s, &c, &o, &r, &err), &err);
  int added = 0;
  REQUIRE_OK_VOID(ss_store_put(st, id, &r, &added, &err), &err);
  if (!added) { /* the same canonical link again (bipyramid:4 = octahedron) */
    ss_result_clear(&r);
    return;
  }
  all->r[all->n] = r;
  all->ident[all->n++] = ident;
}

static int64_t scheme_id(ss_store *st, const ss_scheme *s, char *ident) {
  ss_error err = {0};
  ss_store_scheme sc = {
      ss_scheme_name(s),   NULL, 0, ss_scheme_reads_diagonals(s), SS_DIAG_BFS,
      ss_result_defaults()};
  ss_store_identity(&sc, ident, 256);
  int64_t id = -1;
  ss_status stt = ss_store_scheme_id(st, &sc, &id, &err);
  CHECK(stt == SS_OK, "%s", err.msg);
  return id;
}

static int make_store(const char *path, computed *all) {
  ss_error err = {0};
  ss_store *st = NULL;
  ss_scheme *mlca = NULL, *box = NULL, *tetoct = NULL;
  REQUIRE_OK(ss_store_open(path, SS_STORE_WRITE, &st, &err), &err);
  REQUIRE_OK(ss_scheme_new("mlca", &mlca, &err), &err);
  REQUIRE_OK(ss_scheme_new("boxspline", &box, &err), &err);
  REQUIRE_OK(ss_scheme_new("tetoct", &tetoct, &err), &err);
  const int64_t im = scheme_id(st, mlca, ident_mlca);
  const int64_t ib = scheme_id(st, box, ident_box);
  const int64_t it = scheme_id(st, tetoct, ident_tetoct);
  static const char *const names[] = {"tetrahedron", "octahedron",  "bipyramid:3",
                                      "bipyramid:4", "bipyramid:5", k8_fail};
  for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
    ss_link *l = NULL;
    if (strchr(names[i], ','))
      REQUIRE_OK(ss_link_parse(names[i], &l, &err), &err);
    else
      REQUIRE_OK(ss_link_named(names[i], &l, &err), &err);
    add_case(st, im, ident_mlca, mlca, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0},
             all);
    if (i < 2)
      add_case(st, ib, ident_box, box, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0},
               all);
    ss_link_free(l);
  }
  for (int n = 3; n <= 8; n++)
    add_case(st, im, ident_mlca, mlca, (ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0},
             all);
  add_case(st, ib, ident_box, box, (ss_case){SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0}, all);
  add_case(st, it, ident_tetoct, tetoct, (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0},
           all);
  add_case(st, it, ident_tetoct, tetoct, (ss_case){SS_CASE_EDGE, NULL, 4, SS_DIAG_BFS, 0},
           all);
  ss_scheme_free(mlca);
  ss_scheme_free(box);
  ss_scheme_free(tetoct);
  ss_store_close(st);
  return 0;
}

/* The computed case with this identity, kind, k and link, or NULL. */
static const ss_result *find(const computed *all, const char *ident, ss_case_kind kind,
                             int k, const char *link) {
  for (size_t i = 0; i < all->n; i++)
    if (!strcmp(all->ident[i], ident) && all->r[i].kind == kind && all->r[i].k == k &&
        !strcmp(all->r[i].link, link))
      return &all->r[i];
  return NULL;
}

/* Own combined verdict: not ss_result_verdict, so the summary is checked
 * against an independent count. */
static int own_verdict(const ss_result *r) {
  const int c = r->v.cond.verdict, g = r->v.reg.verdict;
  if (c == SS_FAIL || g == SS_FAIL) return 1;
  return c == SS_PASS && g == SS_PASS ? 0 : 2;
}

static int same_double(double a, double b) {
  return (isnan(a) && isnan(b)) || memcmp(&a, &b, sizeof a) == 0;
}

/* Write the chosen tables into a malloc'd string. */
static char *render(ss_report_format fmt, unsigned tables, const ss_report_rows *t,
                    ss_status *st, ss_error *err) {
  ss_report_summary *sum = NULL;
  size_t ns = 0;
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  *st = ss_report_summarize(t->row, t->n, &sum, &ns, err);
  if (!*st) *st = ss_report_table_write(f, fmt, tables, t->row, t->n, sum, ns, NULL, err);
  fclose(f);
  free(sum);
  return buf;
}

/* ---- the rows and the summary ---- */

static void test_rows(ss_store *st, const computed *all) {
  ss_error err = {0};
  ss_report_rows t = {0};
  REQUIRE_OK_VOID(ss_report_rows_load(st, NULL, &t, &err), &err);
  CHECK(t.n == all->n, "%zu rows read, %zu stored", t.n, all->n);
  CHECK(all->n == 16, "%zu distinct cases computed (expected 16)", all->n);
  for (size_t i = 0; i < t.n; i++) {
    const ss_report_row *w = &t.row[i];
    const ss_result *r = find(all, w->identity, w->r.kind, w->r.k, w->r.link);
    CHECK(r != NULL, "row %zu (%s %d %s) was not stored", i, ss_case_name(w->r.kind),
          w->r.k, w->r.link);
    if (!r) continue;
    CHECK(w->r.neig == r->neig && w->r.cells == r->cells &&
              w->r.two_ring == r->two_ring && w->r.has_diag == r->has_diag &&
              w->r.improper == r->improper && same_double(w->r.min_sj, r->min_sj),
          "row %zu differs from the computed result", i);
    for (int j = 0; j < r->neig; j++)
      CHECK(same_double(w->r.eig[j].re, r->eig[j].re) &&
                same_double(w->r.eig[j].im, r->eig[j].im) &&
                w->r.eig[j].mult == r->eig[j].mult,
            "row %zu eigenvalue %d", i, j);
    if (i > 0) { /* identity, kind (enum order), k, link */
      const ss_report_row *p = &t.row[i - 1];
      int c = strcmp(p->identity, w->identity);
      if (!c) c = (int)p->r.kind - (int)w->r.kind;
      if (!c) c = p->r.k - w->r.k;
      if (!c) c = strcmp(p->r.link, w->r.link);
      CHECK(c < 0, "rows %zu and %zu out of order", i - 1, i);
    }
  }
  /* the summary against counts made here */
  ss_report_summary *sum = NULL;
  size_t ns = 0;
  REQUIRE_OK_VOID(ss_report_summarize(t.row, t.n, &sum, &ns, &err), &err);
  size_t total = 0, groups = 0;
  for (size_t i = 0; i < all->n; i++) {
    int first = 1;
    for (size_t j = 0; j < i; j++)
      first &= !(!strcmp(all->ident[j], all->ident[i]) &&
                 all->r[j].kind == all->r[i].kind && all->r[j].k == all->r[i].k);
    groups += first;
  }
  CHECK(ns == groups, "%zu summary groups, %zu expected", ns, groups);
  for (size_t g = 0; g < ns; g++) {
    size_t cnt[3] = {0, 0, 0}, cases = 0;
    double worst = INFINITY, lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < all->n; i++) {
      const ss_result *r = &all->r[i];
      if (strcmp(all->ident[i], sum[g].identity) || r->kind != sum[g].kind ||
          r->k != sum[g].k)
        continue;
      cases++;
      cnt[own_verdict(r)]++;
      if (!isnan(r->min_sj) && r->min_sj < worst) worst = r->min_sj;
      const double m = hypot(r->eig[1].re, r->eig[1].im);
      lo = fmin(lo, m);
      hi = fmax(hi, m);
    }
    total += sum[g].cases;
    CHECK(sum[g].cases == cases && sum[g].pass == cnt[0] && sum[g].fail == cnt[1] &&
              sum[g].undecided == cnt[2],
          "group %s %s %d: %zu/%zu/%zu/%zu, expected %zu/%zu/%zu/%zu", sum[g].identity,
          ss_case_name(sum[g].kind), sum[g].k, sum[g].cases, sum[g].pass, sum[g].fail,
          sum[g].undecided, cases, cnt[0], cnt[1], cnt[2]);
    CHECK(isinf(worst) ? isnan(sum[g].worst_sj) : sum[g].worst_sj == worst,
          "group %zu worst min SJ %g, expected %g", g, sum[g].worst_sj, worst);
    CHECK(sum[g].l1_min == lo && sum[g].l1_max == hi, "group %zu |lambda1| range", g);
  }
  CHECK(total == t.n, "summary covers %zu of %zu cases", total, t.n);
  /* the known verdicts: MLCA edge 8 fails the eigenvalue condition, the k = 8
   * link fails regularity; MLCA passes elsewhere */
  for (size_t g = 0; g < ns; g++) {
    if (strcmp(sum[g].identity, ident_mlca)) continue;
    const int bad =
        (sum[g].kind == SS_CASE_EDGE || sum[g].kind == SS_CASE_VERTEX) && sum[g].k == 8;
    CHECK(sum[g].fail == (size_t)bad && sum[g].pass == sum[g].cases - (size_t)bad,
          "mlca %s %d: %zu fail", ss_case_name(sum[g].kind), sum[g].k, sum[g].fail);
  }
  const ss_result *e8 = find(all, ident_mlca, SS_CASE_EDGE, 8, "");
  const ss_result *v8 = find(all, ident_mlca, SS_CASE_VERTEX, 8, k8_fail);
  CHECK(e8 && e8->v.cond.verdict == SS_FAIL && isnan(e8->min_sj), "mlca edge 8");
  CHECK(v8 && v8->v.cond.verdict == SS_PASS && v8->v.reg.verdict == SS_FAIL &&
            v8->min_sj < 0.0,
        "mlca k = 8 link");
  free(sum);
  ss_report_rows_clear(&t);
}

static void test_where(ss_store *st, const computed *all) {
  ss_error err = {0};
  ss_report_rows t = {0};
  size_t want = 0;
  for (size_t i = 0; i < all->n; i++)
    want += all->r[i].k == 4;
  REQUIRE_OK_VOID(ss_report_rows_load(st, "k = 4", &t, &err), &err);
  CHECK(t.n == want && want == 4, "k = 4: %zu rows, expected %zu", t.n, want);
  for (size_t i = 0; i < t.n; i++)
    CHECK(t.row[i].r.k == 4, "k = 4 let k = %d through", t.row[i].r.k);
  ss_report_rows_clear(&t);
  want = 0;
  for (size_t i = 0; i < all->n; i++)
    want += own_verdict(&all->r[i]) == 1;
  REQUIRE_OK_VOID(ss_report_rows_load(st, "verdict = 'fail'", &t, &err), &err);
  CHECK(t.n == want && want >= 3, "verdict = 'fail': %zu rows, expected %zu", t.n, want);
  for (size_t i = 0; i < t.n; i++)
    CHECK(ss_result_verdict(&t.row[i].r) == SS_FAIL, "a passing row selected");
  ss_report_rows_clear(&t);
  REQUIRE_OK_VOID(ss_report_rows_load(st, "k = 100", &t, &err), &err);
  CHECK(t.n == 0, "k = 100: %zu rows", t.n);
  ss_status s = ss_report_rows_load(st, "k = = 4", &t, &err);
  CHECK(s == SS_EINPUT && strstr(err.msg, "k = = 4"), "bad where: %d %s", s, err.msg);
  s = ss_report_rows_load(st, "no_such_column > 1", &t, &err);
  CHECK(s == SS_EINPUT && strstr(err.msg, "no_such_column"), "bad column: %s", err.msg);
  s = ss_report_rows_load(st, "1); DROP TABLE result; --", &t, &err);
  CHECK(s == SS_EINPUT, "a second statement: %d", s);
  ss_report_rows_clear(&t);
}

/* ---- CSV ---- */

/* Split one CSV record of buf at *pos (RFC 4180) into at most max fields
 * (malloc'd); returns the number of fields, -1 at the end, -2 on a syntax
 * error. */
static int csv_record(const char *buf, size_t *pos, char **field, int max) {
  size_t i = *pos;
  if (!buf[i]) return -1;
  int n = 0;
  for (;;) {
    char *out = malloc(strlen(buf + i) + 1);
    size_t o = 0;
    if (buf[i] == '"') {
      for (i++;; i++) {
        if (!buf[i]) {
          free(out);
          return -2;
        }
        if (buf[i] == '"') {
          if (buf[i + 1] != '"') break;
          i++;
        }
        out[o++] = buf[i];
      }
      i++;
    } else {
      while (buf[i] && buf[i] != ',' && buf[i] != '\r' && buf[i] != '\n')
        out[o++] = buf[i++];
    }
    out[o] = '\0';
    if (n < max)
      field[n++] = out;
    else
      free(out);
    if (buf[i] == ',') {
      i++;
      continue;
    }
    if (buf[i] == '\r' && buf[i + 1] == '\n') {
      *pos = i + 2;
      return n;
    }
    free(field[--n]);
    return -2; /* a record must end with CRLF */
  }
}

static int col(char **hdr, int nh, const char *name) {
  for (int i = 0; i < nh; i++)
    if (!strcmp(hdr[i], name)) return i;
  return -1;
}

static void free_fields(char **f, int n) {
  for (int i = 0; i < n; i++)
    free(f[i]);
}

static void test_csv(ss_store *st, const computed *all) {
  ss_error err = {0};
  ss_report_rows t = {0};
  ss_status s;
  REQUIRE_OK_VOID(ss_report_rows_load(st, NULL, &t, &err), &err);
  char *text = render(SS_REPORT_CSV, SS_REPORT_CASES, &t, &s, &err);
  CHECK(s == SS_OK, "csv: %s", err.msg);
  char *hdr[64], *f[64];
  size_t pos = 0;
  const int nh = csv_record(text, &pos, hdr, 64);
  CHECK(nh == 39, "csv header has %d fields", nh);
  const int cid = col(hdr, nh, "identity"), ckind = col(hdr, nh, "case"),
            ck = col(hdr, nh, "k"), clink = col(hdr, nh, "link"),
            csj = col(hdr, nh, "min_scaled_jacobian"), cre = col(hdr, nh, "lambda1_re"),
            ctol = col(hdr, nh, "tolerance"), cver = col(hdr, nh, "verdict");
  CHECK(cid >= 0 && ckind >= 0 && ck >= 0 && clink >= 0 && csj >= 0 && cre >= 0 &&
            ctol >= 0 && cver >= 0,
        "csv header lacks a column");
  size_t rows = 0;
  int nf;
  while (cid >= 0 && (nf = csv_record(text, &pos, f, 64)) != -1) {
    CHECK(nf == nh, "csv record %zu has %d fields, the header %d", rows, nf, nh);
    if (nf != nh) break;
    rows++;
    ss_case_kind kind = SS_CASE_VERTEX;
    for (int q = 0; q < SS_NCASEKINDS; q++)
      if (!strcmp(f[ckind], ss_case_name((ss_case_kind)q))) kind = (ss_case_kind)q;
    const ss_result *r = find(all, f[cid], kind, atoi(f[ck]), f[clink]);
    CHECK(r != NULL, "csv record %zu: no such case %s %s %s", rows, f[cid], f[ckind],
          f[clink]);
    if (r) {
      for (int j = 1; j <= 4; j++) {
        const double re = strtod(f[cre + 3 * (j - 1)], NULL);
        const double im = strtod(f[cre + 3 * (j - 1) + 1], NULL);
        const int mult = atoi(f[cre + 3 * (j - 1) + 2]);
        CHECK(same_double(re, r->eig[j].re) && same_double(im, r->eig[j].im) &&
                  mult == r->eig[j].mult,
              "csv lambda%d %s != %.17g", j, f[cre + 3 * (j - 1)], r->eig[j].re);
      }
      const double sj = f[csj][0] ? strtod(f[csj], NULL) : (double)NAN;
      CHECK(same_double(sj, r->min_sj), "csv min SJ '%s' != %.17g", f[csj], r->min_sj);
      CHECK(strtod(f[ctol], NULL) == r->tol, "csv tolerance %s", f[ctol]);
      static const char *const vn[3] = {"pass", "fail", "undecided"};
      CHECK(!strcmp(f[cver], vn[own_verdict(r)]), "csv verdict %s", f[cver]);
    }
    free_fields(f, nf);
  }
  CHECK(rows == all->n, "csv: %zu records, %zu cases", rows, all->n);
  CHECK(strstr(text, "\"8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb\""),
        "csv: a link with commas is not quoted");
  free_fields(hdr, nh > 0 ? nh : 0);
  free(text);
  /* the summary as CSV: one record per group */
  text = render(SS_REPORT_CSV, SS_REPORT_SUMMARY, &t, &s, &err);
  pos = 0;
  size_t nrec = 0;
  while ((nf = csv_record(text, &pos, f, 64)) >= 0) {
    CHECK(nf == 13, "summary csv record with %d fields", nf);
    nrec++;
    free_fields(f, nf);
  }
  CHECK(nf == -1 && nrec == 1 + 16, "summary csv: %zu records (header + 16 groups)",
        nrec);
  free(text);
  /* CSV holds one table */
  text = render(SS_REPORT_CSV, SS_REPORT_BOTH, &t, &s, &err);
  CHECK(s == SS_EINPUT, "csv with both tables: %d", s);
  free(text);
  ss_report_rows_clear(&t);
}

/* ---- Markdown and LaTeX ---- */

/* Count occurrences of c in s not preceded by a backslash. */
static int count_unescaped(const char *s, size_t len, char c) {
  int n = 0;
  for (size_t i = 0; i < len; i++)
    n += s[i] == c && (i == 0 || s[i - 1] != '\\');
  return n;
}

static int count_str(const char *s, const char *w) {
  int n = 0;
  for (const char *p = s; (p = strstr(p, w)); p += strlen(w))
    n++;
  return n;
}

/* A row whose scheme name holds every special character. */
static void special_row(ss_report_rows *t, const ss_report_rows *from) {
  ss_error err = {0};
  ss_store_row sr = {"we|ird_&%#${}~^\\<>\"name, x", "weird|id_1", from->row[0].r};
  REQUIRE_OK_VOID(ss_report_rows_append(t, &sr, &err), &err);
}

static void test_md(ss_store *st, const computed *all) {
  ss_error err = {0};
  ss_report_rows t = {0};
  ss_status s;
  REQUIRE_OK_VOID(ss_report_rows_load(st, NULL, &t, &err), &err);
  char *text = render(SS_REPORT_MD, SS_REPORT_BOTH, &t, &s, &err);
  CHECK(s == SS_OK, "md: %s", err.msg);
  /* table lines: per table a header, the rule and one line per row; every
   * line of a table has the same number of unescaped '|' */
  int lines = 0, ncases = 0, nsum = 0, pipes_cases = -1, pipes_sum = -1, table = 0;
  for (char *p = text, *e; *p; p = e + 1) {
    e = strchr(p, '\n');
    if (!e) break;
    if (!strncmp(p, "## Cases", 8)) table = 1;
    if (!strncmp(p, "## Summary", 10)) table = 2;
    if (*p != '|') continue;
    lines++;
    const int np = count_unescaped(p, (size_t)(e - p), '|');
    int *want = table == 1 ? &pipes_cases : &pipes_sum;
    if (*want < 0) *want = np;
    CHECK(np == *want, "md line with %d cells separators, not %d: %.60s", np, *want, p);
    ++*(table == 1 ? &ncases : &nsum);
  }
  CHECK(ncases == (int)all->n + 2, "md cases table has %d lines", ncases);
  CHECK(nsum == 16 + 2, "md summary table has %d lines", nsum);
  CHECK(pipes_cases == 15, "md cases: %d separators (14 columns with diagonals)",
        pipes_cases);
  CHECK(strstr(text, "\\|lambda4\\|"), "md: '|' in a reason is not escaped");
  CHECK(strstr(text, "relative tolerance of 1e-06"), "md: no tolerance note");
  /* The MLCA edge of valence 4 is the regular grid: the tricubic B-spline's
   * leading eigenvalues 1/2 (x3, the linear modes) and 1/4; located by its
   * scheme, kind and valence so another scheme's row cannot stand in for it. */
  const char *e4 = strstr(text, "| mlca | edge | 4 |");
  CHECK(e4 && !strstr(e4 + 1, "| mlca | edge | 4 |"), "md: one MLCA edge 4 row");
  if (e4) {
    char want[160];
    snprintf(want, sizeof want, "| %.6f | %.6f | %.6f | %.6f | ", 0.5, 0.5, 0.5, 0.25);
    const char *end = strchr(e4, '\n'), *hit = strstr(e4, want);
    CHECK(hit && hit < end,
          "md: the MLCA edge 4 row lacks the B-spline eigenvalues %s: %.*s", want,
          (int)(end - e4), e4);
    CHECK(strstr(e4, "| pass | pass |") && strstr(e4, "| pass | pass |") < end,
          "md: the regular MLCA edge 4 row is not pass/pass");
  }
  free(text);
  special_row(&t, &t);
  text = render(SS_REPORT_MD, SS_REPORT_CASES, &t, &s, &err);
  CHECK(strstr(text, "| we\\|ird_&%#${}~^\\<>\"name, x |"), "md: special name");
  free(text);
  ss_report_rows_clear(&t);
}

static void test_tex(ss_store *st, const computed *all) {
  ss_error err = {0};
  ss_report_rows t = {0};
  ss_status s;
  REQUIRE_OK_VOID(ss_report_rows_load(st, NULL, &t, &err), &err);
  special_row(&t, &t);
  char *text = render(SS_REPORT_TEX, SS_REPORT_BOTH, &t, &s, &err);
  CHECK(s == SS_OK, "tex: %s", err.msg);
  /* two longtables, each with its first head and its repeated head */
  CHECK(count_str(text, "\\toprule") == 4 && count_str(text, "\\midrule") == 4 &&
            count_str(text, "\\bottomrule") == 2 && count_str(text, "\\endhead") == 2 &&
            count_str(text, "\\endfirsthead") == 2 && count_str(text, "(continued)") == 2,
        "tex: booktabs rules and repeated heads");
  CHECK(count_str(text, "\\begin{longtable}") == 2 &&
            count_str(text, "\\end{longtable}") == 2,
        "tex: two longtables");
  CHECK(strstr(text, "\\label{tab:subspectra-cases}") &&
            strstr(text, "\\label{tab:subspectra-summary}"),
        "tex: labels");
  CHECK(!strstr(text, "\\hline"), "tex: \\hline with booktabs");
  /* body rows: lines between \endfoot and \end{longtable}; a case row has one
   * '&' fewer than columns (13 with two schemes and the diagonals column: the
   * scheme column is there), a detail line below it spans the table */
  int rows[2] = {0, 0}, amp[2] = {13 - 1, 9 - 1}, table = -1, inbody = 0, detail = 0,
      after_row = 0;
  for (char *p = text, *e; *p; p = e + 1) {
    e = strchr(p, '\n');
    if (!e) break;
    if (!strncmp(p, "\\begin{longtable}", 17)) table++;
    if (!strncmp(p, "\\endfoot", 8)) {
      inbody = 1;
      continue;
    }
    if (!strncmp(p, "\\end{longtable}", 15)) inbody = 0;
    if (!inbody) continue;
    if (!strncmp(p, "\\multicolumn{", 13)) {
      CHECK(table == 0 && after_row, "tex: a detail line not below a case row");
      CHECK(!strncmp(p, "\\multicolumn{13}", 16), "tex: detail line spans %.20s", p);
      CHECK(e - p > 9 && !strncmp(e - 9, "} \\\\[2pt]", 9), "tex detail line end");
      detail++;
      after_row = 0;
      continue;
    }
    rows[table]++;
    after_row = 1;
    const int na = count_unescaped(p, (size_t)(e - p), '&');
    CHECK(na == amp[table], "tex row with %d '&', not %d: %.70s", na, amp[table], p);
    CHECK(e - p > 3 && !strncmp(e - 3, " \\\\", 3), "tex row does not end in \\\\");
  }
  CHECK(rows[0] == (int)all->n + 1 && rows[1] == 16 + 1, "tex: %d and %d rows", rows[0],
        rows[1]);
  CHECK(detail > 0 && detail <= rows[0], "tex: %d detail lines", detail);
  CHECK(strstr(text, "we\\textbar{}ird\\_\\&\\%\\#\\$\\{\\}\\textasciitilde{}"
                     "\\textasciicircum{}\\textbackslash{}\\textless{}\\textgreater{}"),
        "tex: specials not escaped");
  CHECK(strstr(text, "weird\\textbar{}id\\_1"), "tex: identity not escaped");
  CHECK(strstr(text, "$\\lambda_1$") && strstr(text, "$0.500000$"), "tex: math");
  CHECK(strstr(text, "relative tolerance of $10^{-6}$"), "tex: tolerance caption");
  free(text);
  ss_report_rows_clear(&t);
}

/* ---- JSON ---- */

static void test_json(ss_store *st, const computed *all) {
  ss_error err = {0};
  ss_report_rows t = {0};
  ss_status s;
  REQUIRE_OK_VOID(ss_report_rows_load(st, NULL, &t, &err), &err);
  char *text = render(SS_REPORT_JSON, SS_REPORT_BOTH, &t, &s, &err);
  CHECK(s == SS_OK, "json: %s", err.msg);
  json_object *o = json_tokener_parse(text);
  CHECK(o && json_object_is_type(o, json_type_object), "json does not parse");
  json_object *cases = NULL, *sum = NULL;
  json_object_object_get_ex(o, "cases", &cases);
  json_object_object_get_ex(o, "summary", &sum);
  CHECK(cases && json_object_array_length(cases) == all->n, "json cases");
  CHECK(sum && json_object_array_length(sum) == 16, "json summary");
  for (size_t i = 0; cases && i < json_object_array_length(cases); i++) {
    json_object *c = json_object_array_get_idx(cases, i), *x;
    const char *ident =
        json_object_object_get_ex(c, "identity", &x) ? json_object_get_string(x) : "";
    const char *kind =
        json_object_object_get_ex(c, "case", &x) ? json_object_get_string(x) : "";
    const int k = json_object_object_get_ex(c, "k", &x) ? json_object_get_int(x) : -1;
    const char *link =
        json_object_object_get_ex(c, "link", &x) ? json_object_get_string(x) : "";
    ss_case_kind kd = SS_CASE_VERTEX;
    for (int q = 0; q < SS_NCASEKINDS; q++)
      if (!strcmp(kind, ss_case_name((ss_case_kind)q))) kd = (ss_case_kind)q;
    const ss_result *r = find(all, ident, kd, k, link);
    CHECK(r != NULL, "json case %zu unknown", i);
    if (!r) continue;
    json_object *ev = NULL, *reg = NULL, *sj = NULL;
    json_object_object_get_ex(c, "eigenvalues", &ev);
    CHECK(ev && (int)json_object_array_length(ev) == r->neig, "json eigenvalues");
    for (int j = 0; ev && j < r->neig; j++) {
      json_object *e = json_object_array_get_idx(ev, (size_t)j), *re;
      json_object_object_get_ex(e, "re", &re);
      CHECK(json_object_is_type(re, json_type_double) &&
                same_double(json_object_get_double(re), r->eig[j].re),
            "json eigenvalue %d of case %zu", j, i);
    }
    json_object_object_get_ex(c, "regularity", &reg);
    json_object_object_get_ex(reg, "min_scaled_jacobian", &sj);
    CHECK(isnan(r->min_sj) ? sj == NULL
                           : (json_object_is_type(sj, json_type_double) &&
                              same_double(json_object_get_double(sj), r->min_sj)),
          "json min SJ of case %zu", i);
    CHECK(json_object_object_get_ex(c, "diagonals", &x) == r->has_diag,
          "json diagonals of case %zu", i);
  }
  size_t total = 0;
  for (size_t g = 0; sum && g < json_object_array_length(sum); g++) {
    json_object *x;
    json_object_object_get_ex(json_object_array_get_idx(sum, g), "cases", &x);
    CHECK(json_object_is_type(x, json_type_int), "json: cases is a number");
    total += (size_t)json_object_get_int(x);
  }
  CHECK(total == all->n, "json summary counts %zu cases", total);
  json_object_put(o);
  free(text);
  /* --table summary: no cases key */
  text = render(SS_REPORT_JSON, SS_REPORT_SUMMARY, &t, &s, &err);
  o = json_tokener_parse(text);
  CHECK(o && !json_object_object_get_ex(o, "cases", NULL) &&
            json_object_object_get_ex(o, "summary", NULL),
        "json summary only");
  json_object_put(o);
  free(text);
  ss_report_rows_clear(&t);
}

/* Empty selections give empty tables. */
static void test_empty(void) {
  ss_error err = {0};
  ss_report_rows t = {0};
  ss_status s;
  char *text = render(SS_REPORT_JSON, SS_REPORT_BOTH, &t, &s, &err);
  CHECK(s == SS_OK && text && !strcmp(text, "{\"cases\":[],\"summary\":[]}\n"),
        "empty json: %s", text);
  free(text);
  text = render(SS_REPORT_MD, SS_REPORT_BOTH, &t, &s, &err);
  CHECK(s == SS_OK && strstr(text, "## Cases (0)") && strstr(text, "|---|"), "empty md");
  free(text);
  text = render(SS_REPORT_TEX, SS_REPORT_BOTH, &t, &s, &err);
  CHECK(s == SS_OK && count_str(text, "\\bottomrule") == 2, "empty tex");
  free(text);
  text = render(SS_REPORT_CSV, SS_REPORT_CASES, &t, &s, &err);
  CHECK(s == SS_OK && count_str(text, "\r\n") == 1, "empty csv: the header only");
  free(text);
}

/* ---- plots ---- */

/* Pixels of the plot's failure red (217, 13, 13 drawn at 85% on white) in
 * the panels: below the title and legend band (y >= 64). */
static long red_pixels(const char *png, int *w, int *h) {
  cairo_surface_t *s = cairo_image_surface_create_from_png(png);
  if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(s);
    return -1;
  }
  *w = cairo_image_surface_get_width(s);
  *h = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char *d = cairo_image_surface_get_data(s);
  long n = 0;
  for (int y = 64; y < *h; y++)
    for (int x = 0; x < *w; x++) {
      uint32_t p;
      memcpy(&p, d + y * stride + 4 * x, sizeof p);
      const int R = (int)((p >> 16) & 255), G = (int)((p >> 8) & 255), B = (int)(p & 255);
      n += R > 200 && G < 70 && B < 70;
    }
  cairo_surface_destroy(s);
  return n;
}

static long file_size(const char *path, char *head, size_t nhead) {
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  memset(head, 0, nhead);
  if (fread(head, 1, nhead, f)) { /* the first bytes */
  }
  fseek(f, 0, SEEK_END);
  const long n = ftell(f);
  fclose(f);
  return n;
}

static void test_plot(ss_store *st, const char *dir) {
  ss_error err = {0};
  ss_report_rows t = {0};
  char png[512], svg[512], bad[512], head[16];
  snprintf(png, sizeof png, "%s/plot.png", dir);
  snprintf(svg, sizeof svg, "%s/plot.svg", dir);
  snprintf(bad, sizeof bad, "%s/plot.gif", dir);
  REQUIRE_OK_VOID(ss_report_rows_load(st, NULL, &t, &err), &err);
  ss_report_plot_opts o = ss_report_plot_defaults();
  o.identity = ident_mlca;
  o.width = 1000;
  o.height = 640;
  size_t plotted = 0;
  ss_status s = ss_report_plot(t.row, t.n, &o, png, &plotted, &err);
  CHECK(s == SS_OK && plotted == 11, "plot: %d %s, %zu plotted", s, err.msg, plotted);
  CHECK(file_size(png, head, 8) > 1000 && !memcmp(head, "\x89PNG\r\n\x1a\n", 8),
        "plot: not a PNG");
  int w = 0, h = 0;
  const long red = red_pixels(png, &w, &h);
  CHECK(w == 1000 && h == 640, "plot: %dx%d", w, h);
  CHECK(red > 20, "plot: %ld red pixels, failing cases must show", red);
  /* only passing cases: no red */
  ss_report_rows_clear(&t);
  REQUIRE_OK_VOID(ss_report_rows_load(st, "verdict = 'pass'", &t, &err), &err);
  o.identity = NULL;
  s = ss_report_plot(t.row, t.n, &o, png, &plotted, &err);
  CHECK(s == SS_OK && plotted > 0 && !strcmp(t.row[0].identity, ident_box),
        "plot of passing cases");
  CHECK(red_pixels(png, &w, &h) == 0, "plot: red without a failing case");
  s = ss_report_plot(t.row, t.n, &o, svg, &plotted, &err);
  CHECK(s == SS_OK, "svg: %s", err.msg);
  CHECK(file_size(svg, head, 16) > 1000 &&
            (strstr(head, "<?xml") || strstr(head, "<svg")),
        "svg: not SVG (%.16s)", head);
  /* default size: one column per case kind */
  o.width = o.height = 0;
  o.identity = ident_tetoct;
  s = ss_report_plot(t.row, t.n, &o, png, &plotted, &err);
  CHECK(s == SS_OK && plotted == 2 && red_pixels(png, &w, &h) == 0 && w == 20 + 2 * 560 &&
            h == 720,
        "tetoct plot: %zu cases, %dx%d", plotted, w, h);
  /* an edge point (a vertex whose link is the bipyramid over n, stored with
   * k = n + 2) is analysed as the edge of valence n: its panel's abscissa is
   * that n, found here as the edge with the same leading eigenvalues */
  size_t epoints = 0;
  for (size_t i = 0; i < t.n; i++) {
    const ss_result *p = &t.row[i].r;
    if (p->kind != SS_CASE_EDGE_POINT) continue;
    epoints++;
    int same = 0;
    for (size_t j = 0; j < t.n; j++) {
      const ss_result *e = &t.row[j].r;
      if (e->kind != SS_CASE_EDGE || strcmp(t.row[j].identity, t.row[i].identity) ||
          e->neig < 3 || p->neig < 3)
        continue;
      int eq = 1;
      for (int q = 0; q < 3; q++)
        eq &= fabs(e->eig[q].re - p->eig[q].re) <= 1e-9 * fabs(e->eig[q].re) + 1e-12;
      if (eq && ss_report_plot_x(e) == ss_report_plot_x(p)) same++;
    }
    CHECK(same == 1, "edge point k = %d at x = %d: %d edges with its spectrum there",
          p->k, ss_report_plot_x(p), same);
  }
  CHECK(epoints == 2, "%zu edge points (bipyramid:3 and :5) in the store", epoints);
  /* each column's axis label names what is plotted: "k" where the abscissa is
   * the link's vertex count, "valence n" where it is the valence (issue 40: the
   * edge-point column once said "valence n" but plotted k = n + 2) */
  for (size_t i = 0; i < t.n; i++) {
    const ss_result *p = &t.row[i].r;
    const char *xl = ss_report_plot_xlabel(p->kind);
    const int x = ss_report_plot_x(p);
    if (!strncmp(xl, "valence n", 9))
      CHECK(x == p->valence && p->valence > 0, "%s: label '%s', x = %d, valence %d",
            ss_case_name(p->kind), xl, x, p->valence);
    else if (!strncmp(xl, "k (vertices", 11))
      CHECK(p->kind == SS_CASE_VERTEX && x == p->k, "%s: label '%s', x = %d, k %d",
            ss_case_name(p->kind), xl, x, p->k);
    else
      CHECK(p->kind == SS_CASE_FACE && x == 0 && !*xl, "%s: label '%s', x = %d",
            ss_case_name(p->kind), xl, x);
  }
  /* vertex, edge and edge point: three columns */
  o.identity = ident_mlca;
  s = ss_report_plot(t.row, t.n, &o, png, &plotted, &err);
  CHECK(s == SS_OK && red_pixels(png, &w, &h) >= 0 && w == 20 + 3 * 560,
        "mlca plot: %d, %dx%d", s, w, h);
  /* empty: a figure that says so */
  s = ss_report_plot(t.row, 0, &o, png, &plotted, &err);
  CHECK(s == SS_OK && plotted == 0 && file_size(png, head, 8) > 0, "empty plot");
  s = ss_report_plot(t.row, t.n, &o, bad, &plotted, &err);
  CHECK(s == SS_EINPUT && access(bad, F_OK) != 0, "plot.gif: %d", s);
  s = ss_report_plot(t.row, t.n, &o, "/nonexistent/dir/p.png", &plotted, &err);
  CHECK(s == SS_EIO && strstr(err.msg, "/nonexistent/dir/p.png"), "unwritable: %s",
        err.msg);
  remove(png);
  remove(svg);
  ss_report_rows_clear(&t);
}

/* Files that are not stores. */
static void test_bad_files(const char *dir) {
  char path[512];
  ss_error err = {0};
  ss_store *st = NULL;
  snprintf(path, sizeof path, "%s/not-a-store.txt", dir);
  FILE *f = fopen(path, "w");
  fputs("scheme,case\nmlca,vertex\n", f);
  fclose(f);
  ss_status s = ss_store_open(path, SS_STORE_READ, &st, &err);
  CHECK(s == SS_EINPUT && !st, "a text file opens: %d %s", s, err.msg);
  s = ss_store_open("/nonexistent/x.db", SS_STORE_READ, &st, &err);
  CHECK(s != SS_OK && !st, "a missing file opens");
  remove(path);
}

int main(void) {
  char dir[] = "/tmp/ss_test_report_XXXXXX";
  if (!mkdtemp(dir)) {
    perror("mkdtemp");
    return 1;
  }
  char db[600];
  snprintf(db, sizeof db, "%s/store.db", dir);
  static computed all;
  if (make_store(db, &all)) return 1;
  ss_error err = {0};
  ss_store *st = NULL;
  REQUIRE_OK(ss_store_open(db, SS_STORE_READ, &st, &err), &err);
  test_rows(st, &all);
  test_where(st, &all);
  test_csv(st, &all);
  test_md(st, &all);
  test_tex(st, &all);
  test_json(st, &all);
  test_empty();
  test_plot(st, dir);
  test_bad_files(dir);
  ss_store_close(st);
  for (size_t i = 0; i < all.n; i++)
    ss_result_clear(&all.r[i]);
  char p[700];
  static const char *const files[] = {"store.db", "store.db-wal", "store.db-shm"};
  for (int i = 0; i < 3; i++) {
    snprintf(p, sizeof p, "%s/%s", dir, files[i]);
    remove(p);
  }
  rmdir(dir);
  return ss_test_done("report");
}
