/* ss_cli_reproduce_jsonl.c — data/NAME.jsonl of a `reproduce` table: the raw
 * results, one JSON object per case, with the keys of `analyze --format json`
 * (DESIGN section 7) so that scripts read both alike. */
#include <math.h>
#include <stdint.h>

#include <json-c/json.h>

#include "ss_cli.h"
#include "ss_cli_reproduce.h"
#include "ss_report_table.h"

static json_object *result_json(const ss_reproduce_table *t, const ss_result *r) {
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
  json_object *c = ss_report_verdict_json(&r->v.cond);
  json_object_object_add(c, "tolerance", json_object_new_double(r->tol));
  json_object_object_add(o, "eigen_condition", c);
  json_object *g = ss_report_verdict_json(&r->v.reg);
  if (r->psi.ran) { /* a table with psi_depth: psi's figures (as analyze's) */
    json_object_object_add(g, "covered", json_object_new_double(r->psi.covered));
    json_object_object_add(g, "psi", ss_report_psi_json(&r->psi));
  }
  json_object_object_add(g, "min_scaled_jacobian",
                         isfinite(r->min_sj) ? json_object_new_double(r->min_sj) : NULL);
  json_object_object_add(g, "ring_level", json_object_new_int(r->ring_level));
  json_object_object_add(g, "ring_levels", json_object_new_int(r->ring_levels));
  json_object_object_add(g, "centre_corner_folds",
                         json_object_new_int64((int64_t)r->centre_corner_folds));
  json_object_object_add(g, "depth", json_object_new_int(r->depth));
  json_object_object_add(o, "regularity", g);
  json_object *in = ss_report_verdict_json(&r->v.inj);
  json_object_object_add(in, "degree", json_object_new_int(r->inj_degree));
  json_object_object_add(o, "injectivity", in);
  return o;
}

void ss_reproduce_jsonl(ss_strbuf *js, const ss_reproduce_table *t,
                        const ss_reproduce_results *l) {
  for (size_t i = 0; i < l->n; i++) {
    json_object *o = result_json(t, l->r + i);
    ss_sb_printf(js, "%s\n", json_object_to_json_string_ext(o, SS_CLI_JSON_FLAGS));
    json_object_put(o);
  }
}
