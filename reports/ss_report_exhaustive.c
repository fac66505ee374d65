/* ss_report_exhaustive.c — per-k counts of vertex one-rings and the list of
 * the links that do not pass (ss_report_exhaustive.h). */
#include "ss_report_exhaustive.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <json-c/json.h>

void ss_report_exh_init(ss_report_exh_k *g, int k) {
  memset(g, 0, sizeof *g);
  g->k = k;
  g->edge_verdict = SS_UNDECIDED;
}

const char *ss_report_exh_class(const ss_result *r) {
  switch (ss_result_verdict(r)) {
  case SS_PASS:
    return "pass";
  case SS_FAIL:
    if (r->v.cond.verdict == SS_FAIL) return "fail: eigenvalue condition";
    if (r->v.reg.verdict == SS_FAIL) return "fail: regularity";
    return "fail: injectivity only";
  default:
    return "undecided";
  }
}

void ss_report_exh_add(ss_report_exh_k *g, const ss_result *r, int psi_asked) {
  if (!ss_result_has_link(r)) return;
  const ss_verdict_kind v = ss_result_verdict(r);
  g->links++;
  if (r->kind == SS_CASE_EDGE_POINT) { /* judged as an edge: not a vertex */
    g->edge_points++;
    g->edge_valence = r->valence;
    g->edge_verdict = v;
    return;
  }
  g->vertices++;
  g->pass += v == SS_PASS;
  g->fail_cond += r->v.cond.verdict == SS_FAIL;
  g->fail_reg += r->v.cond.verdict != SS_FAIL && r->v.reg.verdict == SS_FAIL;
  g->fail_inj +=
      v == SS_FAIL && r->v.cond.verdict != SS_FAIL && r->v.reg.verdict != SS_FAIL;
  g->undecided += v == SS_UNDECIDED;
  g->centre += v == SS_PASS && r->centre_corner_folds > 0;
  g->cert_pass += v == SS_PASS && ss_result_certified(r);
  g->cert_fail += v == SS_FAIL && ss_result_certified(r);
  const int map = r->v.reg.on == SS_ON_NET || r->v.reg.on == SS_ON_PSI;
  if (r->psi.ran || (psi_asked && map)) { /* the regularity verdict on psi */
    const int on = r->v.reg.on == SS_ON_PSI;
    g->psi_pass += on && r->v.reg.verdict == SS_PASS;
    g->psi_fail += on && r->v.reg.verdict == SS_FAIL;
    g->psi_undecided += !on || r->v.reg.verdict == SS_UNDECIDED;
  }
}

int ss_report_exh_has_psi(const ss_report_exh_k *g) {
  return g->psi_pass + g->psi_fail + g->psi_undecided > 0;
}

void ss_report_exh_md_head(int certify, int psi, char *buf, size_t n) {
  snprintf(buf, n,
           "| k | links | pass | fail: eigenvalue condition | fail: regularity | "
           "fail: injectivity only | undecided | passing, with folds around p | "
           "points on an edge (edge verdict) |%s%s\n"
           "|--:|--:|--:|--:|--:|--:|--:|--:|---|%s%s\n",
           certify ? " certified pass | certified fail | not certified |" : "",
           psi ? " on psi: pass | on psi: fail | on psi: undecided |" : "",
           certify ? "--:|--:|--:|" : "", psi ? "--:|--:|--:|" : "");
}

void ss_report_exh_md_row(const ss_report_exh_k *g, int certify, int psi, char *buf,
                          size_t n) {
  char edges[128] = "–";
  buf[0] = '\0';
  if (!g->links) return;
  if (g->edge_points)
    snprintf(edges, sizeof edges, "%zu (valence %d: %s)", g->edge_points, g->edge_valence,
             ss_verdict_name(g->edge_verdict));
  int len = snprintf(buf, n, "| %d | %zu | %zu | %zu | %zu | %zu | %zu | %zu | %s |",
                     g->k, g->links, g->pass, g->fail_cond, g->fail_reg, g->fail_inj,
                     g->undecided, g->centre, edges);
  if (len < 0 || (size_t)len >= n) return;
  if (certify)
    len += snprintf(buf + len, n - (size_t)len, " %zu | %zu | %zu |", g->cert_pass,
                    g->cert_fail, g->vertices - g->cert_pass - g->cert_fail);
  if (len < 0 || (size_t)len >= n) return;
  if (psi && ss_report_exh_has_psi(g))
    len += snprintf(buf + len, n - (size_t)len, " %zu | %zu | %zu |", g->psi_pass,
                    g->psi_fail, g->psi_undecided);
  else if (psi)
    len += snprintf(buf + len, n - (size_t)len, " – | – | – |");
  if (len >= 0 && (size_t)len < n) snprintf(buf + len, n - (size_t)len, "\n");
}

/* ---- over a store's rows ---- */

/* Whether a scheme identity (ss_store_identity) is that of a certified sweep:
 * it carries the word "certified". */
static int identity_certified(const char *id) {
  for (const char *p = strstr(id, " certified"); p; p = strstr(p + 1, " certified"))
    if (p[10] == ' ' || p[10] == '\0') return 1;
  return 0;
}

/* Whether identity id was swept with --psi-depth N > 0 (ss_store_identity
 * appends " psi-depth=N" only then). */
static int identity_psi(const char *id) {
  const char *p = strstr(id, " psi-depth=");
  return p && atoi(p + 11) > 0;
}

/* The per-k counts of the vertex and edge-point rows rows[a..b) (one
 * identity): *out[0..*nk) for k = 0..*nk-1 (entries with links = 0 count
 * nothing).  SS_ENOMEM. */
static ss_status count_group(const ss_report_row *rows, size_t a, size_t b,
                             ss_report_exh_k **out, int *nk, ss_error *err) {
  int kmax = -1;
  for (size_t i = a; i < b; i++)
    if (ss_result_has_link(&rows[i].r) && rows[i].r.k > kmax) kmax = rows[i].r.k;
  *out = NULL;
  *nk = kmax + 1;
  if (kmax < 0) return SS_OK;
  ss_report_exh_k *g = malloc((size_t)(kmax + 1) * sizeof *g);
  if (!g) return ss_error_nomem(err, "exhaustive table");
  for (int k = 0; k <= kmax; k++)
    ss_report_exh_init(&g[k], k);
  for (size_t i = a; i < b; i++)
    if (ss_result_has_link(&rows[i].r))
      ss_report_exh_add(&g[rows[i].r.k], &rows[i].r, identity_psi(rows[i].identity));
  *out = g;
  return SS_OK;
}

static json_object *jsize(size_t v) {
  return json_object_new_int64((int64_t)v);
}

static const char legend[] =
    "links: every vertex link with k vertices, each once (up to isomorphism and "
    "mirroring); pass: the eigenvalue condition, the regularity of the "
    "characteristic map (judged on its ring) and its injectivity all hold; the "
    "failures are counted by the first condition that fails, in that order "
    "(injectivity only: the other two do not fail); undecided: none fails and "
    "not all pass; passing, with folds around p: passes whose control net folds "
    "only in cells around the centre, which decide nothing; points on an edge: "
    "bipyramid links under a hex scheme, judged as the edge of that valence and "
    "kept out of the other columns.  Certified (sweeps with --certify): a pass "
    "whose eigenvalue condition and regularity are proven, a failure whose "
    "failing condition is proven; injectivity is decided by exact predicates on "
    "the double-precision net, not proven.\n";

static const char legend_psi[] =
    "On psi (sweeps with --psi-depth): the vertex cases with a characteristic map, "
    "by their regularity verdict when it is a statement about psi itself (mlca and "
    "ccsolid: psi judged on its polynomial pieces; tetoct and boxspline: by exact "
    "tangent masks at the ring's regular vertices, tetoct also on its spokes, "
    "where the net does not pass) — pass: det Dpsi of one sign on its whole ring, "
    "fail: of both signs, or psi o sigma = psi; with --certify both proven; else "
    "undecided (psi neither proven regular nor folded: a net pass of tetoct or "
    "boxspline, whose psi is not proven regular, or a net fold psi does not show "
    "where it was looked for); – where no case of that k has a map.\n";

/* One CSV row of the counts e of identity id, scheme sc; psi: the table has
 * the columns on psi. */
static void csv_count_row(FILE *f, const char *id, const char *sc,
                          const ss_report_exh_k *e, int cert, int psi) {
  ss_report_csv_put(f, id);
  fputc(',', f);
  ss_report_csv_put(f, sc);
  fprintf(f, ",%d,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,", e->k, e->links, e->vertices,
          e->pass, e->fail_cond, e->fail_reg, e->fail_inj, e->undecided, e->centre,
          e->edge_points);
  if (e->edge_points)
    fprintf(f, "%d,%s,", e->edge_valence, ss_verdict_name(e->edge_verdict));
  else
    fputs(",,", f);
  if (cert)
    fprintf(f, "%zu,%zu,%zu", e->cert_pass, e->cert_fail,
            e->vertices - e->cert_pass - e->cert_fail);
  else
    fputs(",,", f);
  if (psi && ss_report_exh_has_psi(e))
    fprintf(f, ",%zu,%zu,%zu", e->psi_pass, e->psi_fail, e->psi_undecided);
  else if (psi)
    fputs(",,,", f);
  fputs("\r\n", f);
}

/* The JSON object of the counts e of identity id, scheme sc. */
static json_object *json_count_row(const char *id, const char *sc,
                                   const ss_report_exh_k *e, int cert) {
  json_object *o = json_object_new_object();
  json_object_object_add(o, "identity", json_object_new_string(id));
  json_object_object_add(o, "scheme", json_object_new_string(sc));
  json_object_object_add(o, "k", json_object_new_int(e->k));
  json_object_object_add(o, "links", jsize(e->links));
  json_object_object_add(o, "vertices", jsize(e->vertices));
  json_object_object_add(o, "pass", jsize(e->pass));
  json_object_object_add(o, "fail_eigen_condition", jsize(e->fail_cond));
  json_object_object_add(o, "fail_regularity", jsize(e->fail_reg));
  json_object_object_add(o, "fail_injectivity_only", jsize(e->fail_inj));
  json_object_object_add(o, "undecided", jsize(e->undecided));
  json_object_object_add(o, "pass_with_centre_folds", jsize(e->centre));
  json_object_object_add(o, "edge_points", jsize(e->edge_points));
  if (e->edge_points) {
    json_object_object_add(o, "edge_point_valence", json_object_new_int(e->edge_valence));
    json_object_object_add(o, "edge_point_verdict",
                           json_object_new_string(ss_verdict_name(e->edge_verdict)));
  }
  if (cert) {
    json_object_object_add(o, "certified_pass", jsize(e->cert_pass));
    json_object_object_add(o, "certified_fail", jsize(e->cert_fail));
    json_object_object_add(o, "not_certified",
                           jsize(e->vertices - e->cert_pass - e->cert_fail));
  }
  if (ss_report_exh_has_psi(e)) {
    json_object_object_add(o, "psi_pass", jsize(e->psi_pass));
    json_object_object_add(o, "psi_fail", jsize(e->psi_fail));
    json_object_object_add(o, "psi_undecided", jsize(e->psi_undecided));
  }
  return o;
}

/* Whether psi was judged, or asked for, for some vertex case of rows[a..b). */
static int rows_have_psi(const ss_report_row *rows, size_t a, size_t b) {
  for (size_t i = a; i < b; i++)
    if (rows[i].r.kind == SS_CASE_VERTEX &&
        (rows[i].r.psi.ran || identity_psi(rows[i].identity)))
      return 1;
  return 0;
}

/* One table over the identity groups of rows (sorted by identity). */
static void write_counts(FILE *f, ss_report_format fmt, const ss_report_row *rows,
                         size_t n, json_object *arr, ss_status *st, ss_error *err) {
  char buf[SS_REPORT_EXH_LINE];
  const int any_psi = rows_have_psi(rows, 0, n);
  if (fmt == SS_REPORT_CSV)
    fprintf(f,
            "identity,scheme,k,links,vertices,pass,fail_eigen_condition,"
            "fail_regularity,fail_injectivity_only,undecided,pass_with_centre_folds,"
            "edge_points,edge_point_valence,edge_point_verdict,certified_pass,"
            "certified_fail,not_certified%s\r\n",
            any_psi ? ",psi_pass,psi_fail,psi_undecided" : "");
  for (size_t a = 0, b; a < n && !*st; a = b) {
    for (b = a + 1; b < n && !strcmp(rows[b].identity, rows[a].identity); b++)
      ;
    ss_report_exh_k *g = NULL;
    int nk = 0;
    if ((*st = count_group(rows, a, b, &g, &nk, err))) break;
    if (!g) continue; /* no vertex cases under this identity */
    const int cert = identity_certified(rows[a].identity);
    const int psi = rows_have_psi(rows, a, b);
    if (fmt == SS_REPORT_MD) {
      ss_report_exh_md_head(cert, psi, buf, sizeof buf);
      fprintf(f, "## %s\n\n%s", rows[a].identity, buf);
    }
    for (int k = 0; k < nk; k++) {
      const ss_report_exh_k *e = &g[k];
      if (!e->links) continue;
      if (fmt == SS_REPORT_MD) {
        ss_report_exh_md_row(e, cert, psi, buf, sizeof buf);
        fputs(buf, f);
      } else if (fmt == SS_REPORT_CSV)
        csv_count_row(f, rows[a].identity, rows[a].scheme, e, cert, any_psi);
      else
        json_object_array_add(arr,
                              json_count_row(rows[a].identity, rows[a].scheme, e, cert));
    }
    if (fmt == SS_REPORT_MD) fputc('\n', f);
    free(g);
  }
  if (fmt == SS_REPORT_MD) fputs(legend, f);
  if (fmt == SS_REPORT_MD && any_psi) fputs(legend_psi, f);
}

/* Every vertex row of rows that does not pass. */
static void write_links(FILE *f, ss_report_format fmt, const ss_report_row *rows,
                        size_t n, json_object *arr) {
  if (fmt == SS_REPORT_CSV)
    fputs("identity,scheme,k,case,link,class,certified,min_scaled_jacobian,"
          "eigen_condition,eigen_reason,regularity,regularity_reason,injectivity,"
          "injectivity_reason\r\n",
          f);
  for (size_t i = 0; i < n; i++) {
    const ss_result *r = &rows[i].r;
    if (!ss_result_has_link(r) || ss_result_verdict(r) == SS_PASS) continue;
    if (fmt == SS_REPORT_CSV) {
      ss_report_csv_put(f, rows[i].identity);
      fputc(',', f);
      ss_report_csv_put(f, rows[i].scheme);
      fprintf(f, ",%d,%s,", r->k, ss_case_name(r->kind));
      ss_report_csv_put(f, r->link);
      fprintf(f, ",%s,%d,", ss_report_exh_class(r), ss_result_certified(r));
      if (isfinite(r->min_sj)) fprintf(f, "%.17g", r->min_sj);
      fprintf(f, ",%s,", ss_verdict_name(r->v.cond.verdict));
      ss_report_csv_put(f, r->v.cond.reason);
      fprintf(f, ",%s,", ss_verdict_name(r->v.reg.verdict));
      ss_report_csv_put(f, r->v.reg.reason);
      fprintf(f, ",%s,", ss_verdict_name(r->v.inj.verdict));
      ss_report_csv_put(f, r->v.inj.reason);
      fputs("\r\n", f);
    } else {
      json_object *o = json_object_new_object();
      json_object_object_add(o, "identity", json_object_new_string(rows[i].identity));
      json_object_object_add(o, "scheme", json_object_new_string(rows[i].scheme));
      json_object_object_add(o, "k", json_object_new_int(r->k));
      json_object_object_add(o, "case", json_object_new_string(ss_case_name(r->kind)));
      json_object_object_add(o, "link", json_object_new_string(r->link));
      json_object_object_add(o, "class", json_object_new_string(ss_report_exh_class(r)));
      json_object_object_add(o, "certified",
                             json_object_new_boolean(ss_result_certified(r)));
      json_object_object_add(o, "min_scaled_jacobian",
                             isfinite(r->min_sj) ? json_object_new_double(r->min_sj)
                                                 : NULL);
      json_object_object_add(o, "eigen_condition", ss_report_verdict_json(&r->v.cond));
      json_object_object_add(o, "regularity", ss_report_verdict_json(&r->v.reg));
      json_object_object_add(o, "injectivity", ss_report_verdict_json(&r->v.inj));
      json_object_array_add(arr, o);
    }
  }
}

ss_status ss_report_exh_write(FILE *f, ss_report_format fmt, ss_report_exh_table which,
                              const ss_report_row *rows, size_t n, ss_error *err) {
  if (fmt == SS_REPORT_TEX || (which == SS_REPORT_EXH_LINKS && fmt == SS_REPORT_MD))
    return ss_error_set(err, SS_EINPUT,
                        which == SS_REPORT_EXH_LINKS
                            ? "report: the links that do not pass are written as csv or "
                              "json"
                            : "report: the exhaustive table is written as md, csv or "
                              "json");
  ss_status st = SS_OK;
  json_object *arr = fmt == SS_REPORT_JSON ? json_object_new_array() : NULL;
  if (fmt == SS_REPORT_JSON && !arr) return ss_error_nomem(err, "exhaustive table");
  if (which == SS_REPORT_EXH_COUNTS)
    write_counts(f, fmt, rows, n, arr, &st, err);
  else
    write_links(f, fmt, rows, n, arr);
  if (!st && arr) {
    json_object *o = json_object_new_object();
    json_object_object_add(
        o, which == SS_REPORT_EXH_COUNTS ? "exhaustive" : "not_passing", arr);
    arr = NULL;
    fprintf(f, "%s\n",
            json_object_to_json_string_ext(o, JSON_C_TO_STRING_PRETTY |
                                                  JSON_C_TO_STRING_NOSLASHESCAPE));
    json_object_put(o);
  }
  json_object_put(arr);
  if (!st && (fflush(f) != 0 || ferror(f)))
    st = ss_error_set(err, SS_EIO, "report: writing the table failed");
  return st;
}
