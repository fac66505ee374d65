/* ss_result.c — one case through the whole pipeline (ss_result.h). */
#include "ss_result.h"

#include <stdlib.h>
#include <string.h>

ss_result_opts ss_result_defaults(void) {
  const ss_charmap_opts co = ss_charmap_defaults();
  return (ss_result_opts){1e-6, co.depth, co.ring_levels, 0, 0, 0, 0.0, 0};
}

void ss_result_clear(ss_result *r) {
  if (!r) return;
  free(r->link);
  memset(r, 0, sizeof *r);
}

ss_verdict_kind ss_result_verdict(const ss_result *r) {
  return ss_verdicts_combined(&r->v);
}

int ss_result_certified(const ss_result *r) {
  return ss_verdicts_certified(&r->v);
}

ss_status ss_result_compute(const ss_scheme *s, const ss_case *c, const ss_result_opts *o,
                            ss_result *r, ss_error *err) {
  return ss_result_compute_ws(s, c, o, NULL, r, err);
}

ss_status ss_result_of_pipeline(const ss_pipeline *p, const ss_result_opts *o,
                                ss_result *r, ss_error *err) {
  memset(r, 0, sizeof *r);
  if (p->done < SS_PIPE_VERDICTS)
    return ss_error_set(err, SS_EINPUT, "the pipeline has not reached its verdicts");
  if (!(r->link = strdup(p->c.text))) return ss_error_nomem(err, "result link");
  r->kind = p->c.kind;
  r->k = p->c.k;
  r->valence = p->c.valence;
  r->cls = p->c.cls;
  r->cells = p->c.cells;
  r->two_ring = p->M->n2;
  r->one_ring = p->M->n1;
  r->neig = p->e->n < SS_RESULT_NEIG ? (int)p->e->n : SS_RESULT_NEIG;
  for (int i = 0; i < r->neig; i++)
    r->eig[i] = (ss_result_eigval){p->e->val[i].re, p->e->val[i].im, p->e->val[i].mult};
  r->v = p->v;
  if (p->psi.ran)
    r->psi = (ss_result_psi){1, p->psi.verdict.verdict, p->psi.covered, p->psi.uncovered,
                             p->psi.pieces};
  r->tol = p->e->tol_requested; /* the identity asked for; the verdict says if
                                   rounding raised it */
  r->inj_degree = p->inj.degree;
  r->min_sj = p->reg.min_scaled_jacobian;
  r->depth = p->reg.depth;
  r->ring_levels = o->ring_levels;
  r->ring_level = p->reg.ring_level;
  r->centre_corner_folds = p->reg.centre_corner_folds;
  r->has_diag = p->has_diag;
  r->pairs = p->pairs;
  r->improper = p->improper;
  r->seconds = p->seconds;
  return SS_OK;
}

ss_status ss_result_compute_ws(const ss_scheme *s, const ss_case *c,
                               const ss_result_opts *o, ss_pipeline_workspace *w,
                               ss_result *r, ss_error *err) {
  memset(r, 0, sizeof *r);
  ss_pipeline_opts po = ss_pipeline_defaults();
  po.tol = o->tol;
  po.depth = o->depth;
  po.ring_levels = o->ring_levels;
  po.certify = o->certify;
  po.exact_lazy = !o->exact_full;
  po.psi_depth = o->psi_depth;
  po.psi_tubes = o->psi_tubes;
  po.max_bytes = o->max_bytes;
  ss_pipeline *p = NULL;
  ss_status st = ss_pipeline_compute(s, c, &po, SS_PIPE_VERDICTS, w, &p, err);
  if (!st) st = ss_result_of_pipeline(p, o, r, err);
  ss_pipeline_free(p);
  return st;
}
