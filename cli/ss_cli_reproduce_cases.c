/* ss_cli_reproduce_cases.c — the cases of one `reproduce` table, each judged
 * by ss_result_compute as `analyze`, `check` and `sweep` judge it. */
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "ss_cli_reproduce.h"
#include "ss_enum.h"
#include "ss_link.h"
#include "ss_link_random.h"

void ss_reproduce_results_free(ss_reproduce_results *l) {
  for (size_t i = 0; i < l->n; i++)
    ss_result_clear(l->r + i);
  free(l->r);
  memset(l, 0, sizeof *l);
}

/* Analyse one case and append it. */
static ss_status add_case(ss_reproduce_results *l, const ss_scheme *s, const ss_case *c,
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
  ss_reproduce_results *list;  /* where results go */
  const ss_scheme *s;          /* the scheme */
  const ss_reproduce_table *t; /* the table */
  ss_status st;                /* first failure */
  ss_error *err;               /* its message */
} enum_ctx;

static int visit_link(const ss_link *l, void *ctx) {
  enum_ctx *e = ctx;
  ss_case c = {e->t->kind, l, 0, e->t->diag, 0};
  e->st = add_case(e->list, e->s, &c, e->err);
  return e->st != SS_OK;
}

ss_status ss_reproduce_cases(const ss_reproduce_table *t, const ss_scheme *s,
                             ss_reproduce_results *out, ss_error *err) {
  ss_status st = SS_OK;
  if (t->src == SS_REPRODUCE_LINKS) {
    enum_ctx e = {out, s, t, SS_OK, err};
    ss_enum_opts o = {t->lo, t->hi, 0, 1};
    st = ss_enum_links(&o, visit_link, &e, NULL, err);
    if (!st) st = e.st;
  } else if (t->src == SS_REPRODUCE_RANDOM) {
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
  } else if (t->src == SS_REPRODUCE_LIST) {
    for (size_t i = 0; i < t->nlist && !st; i++) {
      const char *label, *text;
      ss_link *l = NULL;
      ss_reproduce_list_item(t, i, &label, &text);
      ss_error e = {0};
      st = ss_link_parse(text, &l, &e);
      if (st)
        ss_error_set(err, st, "%s: link %s: %s", t->name, label, e.msg);
      else {
        ss_case c = {t->kind, l, 0, t->diag, 0};
        st = add_case(out, s, &c, err);
      }
      ss_link_free(l);
    }
  } else if (t->src == SS_REPRODUCE_VALENCES) {
    for (int n = t->lo; n <= t->hi && !st; n++) {
      ss_case c = {t->kind, NULL, n, t->diag, 0};
      st = add_case(out, s, &c, err);
    }
  } else if (t->src == SS_REPRODUCE_QUASI48) {
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
