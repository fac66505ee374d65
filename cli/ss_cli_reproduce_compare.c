/* ss_cli_reproduce_compare.c — each result of a `reproduce` table beside the
 * values the papers quote for it (the TSV files of data/reference/, ss_report_ref.h):
 * the difference, the tolerance applied and match or differ. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli_reproduce.h"

/* Compare result r with quoted value q; fills c (row and note are set by the
 * caller). */
static ss_status compare(const ss_result *r, const ss_ref_row *q, ss_reproduce_cmp *c,
                         ss_error *err) {
  ss_ref_value v;
  ss_status st = ss_report_ref_eval(q->value, r->k, &v, err);
  if (st) return st;
  int index = 0;
  ss_report_ref_quantity(q->quantity, &index);
  snprintf(c->diff, sizeof c->diff, "–");
  if (v.kind == SS_REF_VERDICT) {
    ss_verdict_kind got = !strcmp(q->quantity, "verdict")           ? ss_result_verdict(r)
                          : !strcmp(q->quantity, "eigen_condition") ? r->v.cond.verdict
                                                                    : r->v.reg.verdict;
    snprintf(c->quoted, sizeof c->quoted, "%s", v.verdict);
    snprintf(c->computed, sizeof c->computed, "%s", ss_verdict_name(got));
    snprintf(c->tol, sizeof c->tol, "equal");
    c->match = !strcmp(v.verdict, ss_verdict_name(got));
    return SS_OK;
  }
  double x = NAN;
  int have = 1;
  if (!strncmp(q->quantity, "lambda", 6)) {
    if (index < r->neig && ss_reproduce_is_real(r->eig + index)) {
      x = r->eig[index].re;
      snprintf(c->computed, sizeof c->computed, "%.9g", x);
    } else if (index < r->neig) {
      ss_reproduce_eig_text(r->eig + index, c->computed, sizeof c->computed);
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

/* A zeroed comparison at the end of out, for row i and quoted value q (its
 * footnote numbered by first use); NULL when out of memory. */
static ss_reproduce_cmp *append(ss_reproduce_cmps *out, size_t i, const ss_ref_row *q) {
  if (out->n == out->cap) {
    size_t nc = out->cap ? 2 * out->cap : 64;
    ss_reproduce_cmp *ncm = realloc(out->c, nc * sizeof *ncm);
    if (!ncm) return NULL;
    out->c = ncm;
    out->cap = nc;
  }
  ss_reproduce_cmp *c = out->c + out->n;
  memset(c, 0, sizeof *c);
  c->row = i;
  c->ref = q;
  size_t u = 0;
  while (u < out->nused && out->used[u] != q)
    u++;
  if (u == out->nused) out->used[out->nused++] = q;
  c->note = (int)u + 1;
  return c;
}

/* The quoted counts of links (quantity links, range A..B inside the table's
 * k range, same scheme and case kind) beside the number of cases of table t
 * (every link with t->lo..t->hi vertices) with A <= k <= B. */
static ss_status count_links(const ss_reproduce_table *t, const ss_reproduce_results *l,
                             const ss_ref *ref, ss_reproduce_cmps *out,
                             ss_reproduce_tally *ty, ss_error *err) {
  for (size_t j = 0; j < ref->n; j++) {
    const ss_ref_row *q = ref->row + j;
    if (strcmp(q->quantity, "links") || strcmp(q->scheme, t->scheme) ||
        q->kind != t->kind || q->label || q->lo < t->lo || q->hi > t->hi)
      continue;
    ss_ref_value v;
    ss_status st = ss_report_ref_eval(q->value, q->lo, &v, err);
    if (st) return st;
    size_t n = 0;
    for (size_t i = 0; i < l->n; i++)
      n += l->r[i].k >= q->lo && l->r[i].k <= q->hi;
    ss_reproduce_cmp *c = append(out, SS_REPRODUCE_TABLE_ROW, q);
    if (!c) return ss_error_nomem(err, "comparisons");
    snprintf(c->what, sizeof c->what, "k = %d..%d", q->lo, q->hi);
    snprintf(c->quoted, sizeof c->quoted, "%s", q->value);
    snprintf(c->computed, sizeof c->computed, "%zu", n);
    snprintf(c->diff, sizeof c->diff, "%+.2e", (double)n - v.x);
    snprintf(c->tol, sizeof c->tol, v.exact ? "%.0e (exact)" : "±%.1g", v.tol);
    c->match = v.kind == SS_REF_NUMBER && ss_report_ref_match(&v, (double)n);
    out->n++;
    ty->quoted++;
    ty->match += (size_t)c->match;
  }
  return SS_OK;
}

ss_status ss_reproduce_compare(const ss_reproduce_table *t, const ss_reproduce_results *l,
                               const ss_ref *ref, ss_reproduce_cmps *out,
                               ss_reproduce_tally *ty, ss_error *err) {
  memset(out, 0, sizeof *out);
  memset(ty, 0, sizeof *ty);
  out->row_status = calloc(l->n ? l->n : 1, sizeof *out->row_status);
  out->used = calloc(ref->n ? ref->n : 1, sizeof *out->used);
  if (!out->row_status || !out->used) return ss_error_nomem(err, "table");
  ty->cases = l->n;
  for (size_t i = 0; i < l->n; i++) {
    const ss_result *r = l->r + i;
    const char *dname = r->has_diag ? ss_diag_name(t->diag) : NULL;
    const char *tag = ss_reproduce_case_tag(t, i);
    if (ss_result_verdict(r) == SS_PASS) ty->pass++;
    ty->certified += (size_t)ss_result_certified(r);
    for (size_t j = 0; j < ref->n; j++) {
      const ss_ref_row *q = ref->row + j;
      if (!strncmp(q->quantity, "jsr_", 4) || /* the JSR tables' (ss_cli_reproduce_jsr) */
          !strcmp(q->quantity, "links") ||    /* the whole table's (below) */
          !ss_report_ref_applies_label(q, t->scheme, r->kind, r->k, dname, tag))
        continue;
      ss_reproduce_cmp *c = append(out, i, q);
      if (!c) return ss_error_nomem(err, "comparisons");
      ss_status st = compare(r, q, c, err);
      if (st) return st;
      if (tag) snprintf(c->what, sizeof c->what, "k = %d, %s", r->k, tag);
      out->n++;
      ty->quoted++;
      ty->match += (size_t)c->match;
      out->row_status[i] = c->match && out->row_status[i] != 2 ? 1 : 2;
    }
    if (!out->row_status[i]) ty->unquoted++;
  }
  return t->src == SS_REPRODUCE_LINKS ? count_links(t, l, ref, out, ty, err) : SS_OK;
}

void ss_reproduce_cmps_free(ss_reproduce_cmps *c) {
  free(c->c);
  free(c->used);
  free(c->row_status);
  memset(c, 0, sizeof *c);
}
