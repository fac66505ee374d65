/* ss_report_case.c — one case as the JSON object of `analyze --format json`,
 * and the pipeline of `analyze` that makes it (ss_report_case.h). */
#include "ss_report_case.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_diag.h"
#include "ss_exact.h"
#include "ss_psi_spoke.h"
#include "ss_report_table.h"

static json_object *level_json(const ss_ring_level *L, int l) {
  json_object *x = json_object_new_object();
  json_object_object_add(x, "level", json_object_new_int(l));
  json_object_object_add(x, "cells", json_object_new_int64((int64_t)L->cells));
  json_object_object_add(x, "positive", json_object_new_int64((int64_t)L->positive));
  json_object_object_add(x, "negative", json_object_new_int64((int64_t)L->negative));
  json_object_object_add(x, "folded", json_object_new_int64((int64_t)L->folded));
  json_object_object_add(x, "inverted", json_object_new_int64((int64_t)L->inverted));
  json_object_object_add(x, "undecided", json_object_new_int64((int64_t)L->undecided));
  json_object_object_add(x, "degenerate", json_object_new_int64((int64_t)L->degenerate));
  json_object_object_add(x, "min_scaled_jacobian",
                         isfinite(L->min_scaled_jacobian)
                             ? json_object_new_double(L->min_scaled_jacobian)
                             : NULL);
  return x;
}

static json_object *psi_point_json(const ss_psi_point *x) {
  json_object *o = json_object_new_object();
  const int cell = x->cell != SIZE_MAX;
  json_object_object_add(o, "cell",
                         cell ? json_object_new_int64((int64_t)x->cell) : NULL);
  json_object *a = cell ? json_object_new_array() : NULL;
  for (int d = 0; d < 3 && cell; d++)
    json_object_array_add(a, json_object_new_double(x->at[d]));
  json_object_object_add(o, "at", a);
  if (x->chart) { /* a regular vertex of the ring (ss_psi_mask.h) */
    json_object *c = json_object_new_object(), *v = json_object_new_array(),
                *y = json_object_new_array();
    for (int d = 0; d < 3; d++) {
      char name[16];
      ss_psi_spoke_name(x->cone[d], name);
      json_object_array_add(v, json_object_new_string(name));
      json_object_array_add(y, json_object_new_double(x->x[d]));
    }
    json_object_object_add(c, "cone", v);
    json_object_object_add(c, "x", y);
    json_object_object_add(o, "chart", c);
  }
  json_object *v = json_object_new_array();
  json_object_array_add(v, json_object_new_double(x->det[0]));
  json_object_array_add(v, json_object_new_double(x->det[1]));
  json_object_object_add(o, "det", v);
  return o;
}

/* psi judged on its polynomial pieces (ss_psi.h), or null when it was not. */
static json_object *psi_json(const ss_psi_result *r) {
  if (!r->ran) return NULL;
  json_object *o = ss_report_verdict_json(&r->verdict);
  json_object_object_add(o, "enclosed", json_object_new_boolean(r->enclosed));
  json_object_object_add(o, "covered", json_object_new_double(r->covered));
  json_object_object_add(o, "opposite", json_object_new_double(r->opposite));
  json_object_object_add(o, "doubtful", json_object_new_double(r->doubtful));
  json_object_object_add(o, "uncovered", json_object_new_double(r->uncovered));
  json_object_object_add(o, "pieces", json_object_new_int64((int64_t)r->pieces));
  json_object_object_add(o, "positive", json_object_new_int64((int64_t)r->npositive));
  json_object_object_add(o, "negative", json_object_new_int64((int64_t)r->nnegative));
  json_object_object_add(o, "folded", json_object_new_int64((int64_t)r->nfolded));
  json_object_object_add(o, "undecided", json_object_new_int64((int64_t)r->nundecided));
  json_object_object_add(o, "uncovered_boxes",
                         json_object_new_int64((int64_t)r->nuncovered));
  json_object_object_add(o, "box_depth", json_object_new_int(r->maxdepth));
  json_object_object_add(o, "piece_depth", json_object_new_int(r->piece_depth));
  if (r->tubes) { /* the tubes proven (ss_psi_tube.h) */
    json_object *t = json_object_new_object();
    json_object_object_add(t, "proven", json_object_new_int64((int64_t)r->ntubes));
    json_object_object_add(t, "boxes", json_object_new_int64((int64_t)r->nuncovered));
    json_object_object_add(t, "layers", json_object_new_int(r->tube_layers));
    json_object_object_add(t, "why", json_object_new_string(r->tube_why));
    json_object_object_add(o, "tubes", t);
  }
  if (r->inject_why[0]) { /* the winding number on the boundary (ss_psi_inject.h) */
    json_object *t = json_object_new_object();
    json_object_object_add(t, "decided",
                           json_object_new_string(r->inject > 0   ? "injective"
                                                  : r->inject < 0 ? "not injective"
                                                                  : "undecided"));
    json_object_object_add(t, "proven", json_object_new_boolean(r->inject != 0));
    json_object_object_add(
        t, "winding", r->degree || r->inject ? json_object_new_int(r->degree) : NULL);
    json_object_object_add(t, "squares",
                           json_object_new_int64((int64_t)r->boundary_squares));
    json_object_object_add(t, "why", json_object_new_string(r->inject_why));
    json_object_object_add(o, "injectivity", t);
  }
  if (r->by_masks) { /* decided at the ring's regular vertices (ss_psi_mask.h) */
    json_object *m = json_object_new_object();
    json_object_object_add(m, "count", json_object_new_int64((int64_t)r->nregular));
    json_object_object_add(m, "positive",
                           json_object_new_int64((int64_t)r->nregular_pos));
    json_object_object_add(m, "negative",
                           json_object_new_int64((int64_t)r->nregular_neg));
    json_object_object_add(o, "regular_vertices", m);
  }
  if (r->spokes || r->spoke_why[0]) { /* the tubes' evidence (ss_psi_spoke.h) */
    json_object *k = json_object_new_object();
    json_object_object_add(k, "classified", json_object_new_boolean(r->spokes));
    json_object_object_add(k, "why", json_object_new_string(r->spoke_why));
    json_object_object_add(k, "count", json_object_new_int64((int64_t)r->nspokes));
    json_object_object_add(k, "one_sign", json_object_new_int64((int64_t)r->nspoke_one));
    json_object_object_add(k, "sign_change",
                           json_object_new_int64((int64_t)r->nspoke_change));
    json_object_object_add(k, "degenerate",
                           json_object_new_int64((int64_t)r->nspoke_deg));
    json_object_object_add(k, "degenerate_verdict",
                           json_object_new_boolean(r->degenerate));
    char name[16]; /* the link vertex's name, as the verdict's reason has it */
    ss_psi_spoke_name(r->spoke_vertex, name);
    json_object_object_add(k, "decided_by",
                           r->spoke_vertex >= 0 ? json_object_new_string(name) : NULL);
    json_object_object_add(o, "spokes", k);
  }
  return o;
}

/* The regularity object of DESIGN section 7, with the ring's levels: the
 * verdict as combined with psi's (a forced map's own), the control net's
 * (net_verdict) and psi's (psi, with covered and witness) beside it. */
static json_object *regularity_json(const ss_pipeline *p) {
  const ss_regularity *reg = &p->reg;
  json_object *g = ss_report_verdict_json(p->forced ? &reg->verdict : &p->v.reg);
  json_object_object_add(g, "net_verdict", ss_report_verdict_json(&reg->verdict));
  json_object_object_add(g, "covered",
                         p->psi.ran ? json_object_new_double(p->psi.covered) : NULL);
  json_object *w = NULL;
  if (p->psi.ran && p->psi.nwitness == 2) {
    w = json_object_new_array();
    for (int i = 0; i < 2; i++)
      json_object_array_add(w, psi_point_json(&p->psi.witness[i]));
  }
  json_object_object_add(g, "witness", w);
  json_object_object_add(g, "psi", psi_json(&p->psi));
  json_object_object_add(g, "min_scaled_jacobian",
                         isfinite(reg->min_scaled_jacobian)
                             ? json_object_new_double(reg->min_scaled_jacobian)
                             : NULL);
  json_object_object_add(
      g, "cells",
      json_object_new_int64((int64_t)(reg->npositive + reg->nnegative + reg->nfolded +
                                      reg->nundecided + reg->ndegenerate)));
  json_object_object_add(g, "orientation", json_object_new_int(reg->sign));
  json_object_object_add(g, "folded_cells", json_object_new_int64((int64_t)reg->nfolded));
  json_object_object_add(g, "inverted_cells",
                         json_object_new_int64((int64_t)reg->ninverted));
  json_object_object_add(g, "undecided_cells",
                         json_object_new_int64((int64_t)reg->nundecided));
  json_object_object_add(g, "degenerate_cells",
                         json_object_new_int64((int64_t)reg->ndegenerate));
  json_object_object_add(g, "centre_corner_folds",
                         json_object_new_int64((int64_t)reg->centre_corner_folds));
  json_object_object_add(g, "ring_level", json_object_new_int(reg->ring_level));
  json_object *lv = json_object_new_array();
  for (int l = 0; l < reg->nlevels; l++)
    json_object_array_add(lv, level_json(reg->level + l, l));
  json_object_object_add(g, "ring_levels", lv);
  json_object_object_add(g, "shrink", json_object_new_double(reg->shrink));
  json_object_object_add(g, "depth", json_object_new_int(reg->depth));
  return g;
}

ss_status ss_report_case_json(const ss_pipeline *p, int neig, json_object *eigenvectors,
                              json_object **out, ss_error *err) {
  *out = NULL;
  if (p->done < SS_PIPE_VERDICTS) {
    json_object_put(eigenvectors);
    return ss_error_set(err, SS_EINPUT, "the pipeline has not reached its verdicts");
  }
  const ss_local *M = p->M;
  const ss_eig *e = p->e;
  const ss_case_resolved *c = &p->c;
  json_object *r = json_object_new_object();
  if (!r) {
    json_object_put(eigenvectors);
    return ss_error_nomem(err, "JSON object");
  }
  json_object_object_add(r, "scheme", json_object_new_string(ss_scheme_name(p->scheme)));
  json_object_object_add(r, "case", json_object_new_string(ss_case_name(c->kind)));
  if (c->kind == SS_CASE_VERTEX || c->kind == SS_CASE_EDGE_POINT) {
    json_object_object_add(r, "link", json_object_new_string(c->text));
    json_object_object_add(r, "k", json_object_new_int(c->k));
  }
  if (c->kind == SS_CASE_EDGE || c->kind == SS_CASE_SURFACE_VERTEX ||
      c->kind == SS_CASE_EDGE_POINT)
    json_object_object_add(r, "valence", json_object_new_int(c->valence));
  json_object_object_add(r, "two_ring_size", json_object_new_int64((int64_t)M->n2));
  json_object_object_add(r, "one_ring_size", json_object_new_int64((int64_t)M->n1));
  json_object_object_add(r, "level", json_object_new_int(M->level));
  if (p->has_diag) {
    json_object *d = json_object_new_object();
    json_object_object_add(d, "choice",
                           json_object_new_string(ss_diag_name(c->asked.diag)));
    json_object_object_add(d, "pairs", json_object_new_int64((int64_t)p->pairs));
    json_object_object_add(d, "improper", json_object_new_int64((int64_t)p->improper));
    json_object_object_add(r, "diagonals", d);
  }
  json_object_object_add(r, "outer_blocks", json_object_new_int64((int64_t)e->nblocks));
  json_object_object_add(r, "largest_outer_block",
                         json_object_new_int64((int64_t)e->largest_block));
  json_object *ev = json_object_new_array();
  for (size_t i = 0; i < e->n && i < (size_t)neig; i++) {
    json_object *x = json_object_new_object();
    json_object_object_add(x, "re", json_object_new_double(e->val[i].re));
    json_object_object_add(x, "im", json_object_new_double(e->val[i].im));
    json_object_object_add(x, "multiplicity", json_object_new_int(e->val[i].mult));
    json_object_object_add(x, "rcond", json_object_new_double(e->val[i].rcond));
    json_object_object_add(
        x, "block", json_object_new_string(e->val[i].block ? "outer" : "one-ring"));
    json_object_array_add(ev, x);
  }
  json_object_object_add(r, "eigenvalues", ev);
  /* the condition as judged: the exact path's with certify, else LAPACK's */
  json_object *cj = ss_report_verdict_json(&p->v.cond);
  json_object_object_add(cj, "tolerance", json_object_new_double(e->tol));
  json_object_object_add(cj, "tolerance_requested",
                         json_object_new_double(e->tol_requested));
  json_object_object_add(cj, "rounding_bound", json_object_new_double(e->rounding));
  if (p->ex) {
    size_t nr = 0;
    const ss_exact_root *x = ss_exact_roots(p->ex, &nr);
    json_object *a = json_object_new_array();
    for (size_t i = 0; i < nr && i < (size_t)neig; i++) {
      char poly[256];
      json_object *q = json_object_new_object();
      json_object_object_add(q, "re", json_object_new_double(x[i].re));
      json_object_object_add(q, "im", json_object_new_double(x[i].im));
      json_object_object_add(q, "radius", json_object_new_double(x[i].rad));
      json_object_object_add(q, "multiplicity", json_object_new_int(x[i].mult));
      json_object_object_add(q, "degree", json_object_new_int(x[i].degree));
      json_object_object_add(
          q, "minimal_polynomial",
          json_object_new_string(ss_exact_minpoly(p->ex, i, poly, sizeof poly)));
      json_object_array_add(a, q);
    }
    json_object_object_add(cj, "exact_roots", a);
    json_object_object_add(cj, "exact_seconds", json_object_new_double(p->exact_seconds));
  }
  json_object_object_add(r, "eigen_condition", cj);
  json_object_object_add(r, "subdominant_basis", json_object_new_string(e->basis_kind));
  json_object_object_add(r, "regularity", regularity_json(p));
  json_object *in = ss_report_verdict_json(&p->v.inj);
  json_object_object_add(in, "degree", json_object_new_int(p->inj.degree));
  json_object_object_add(in, "overlaps", json_object_new_int64((int64_t)p->inj.overlaps));
  json_object_object_add(r, "injectivity", in);
  if (eigenvectors) json_object_object_add(r, "eigenvectors", eigenvectors);
  if (c->cls) /* quasi48: the 4-8 class analysed */
    json_object_object_add(r, "class", json_object_new_int(c->cls));
  *out = r;
  return SS_OK;
}

ss_report_analyze_opts ss_report_analyze_defaults(void) {
  const ss_report_analyze_opts o = {
      1e-6, 16, SS_JAC_DEPTH, ss_charmap_defaults().ring_levels, 0, SS_PSI_BOX_DEPTH, 0};
  return o;
}

ss_status ss_report_analyze(const ss_scheme *s, const ss_case *c,
                            const ss_report_analyze_opts *o, char **json, ss_error *err) {
  *json = NULL;
  if (!(o->tol > 0.0 && o->tol < 1.0) || o->neig < 1 || o->depth < 0 ||
      o->ring_levels < 1 || o->ring_levels > SS_LOCAL_MAXRING || o->psi_depth < 0 ||
      o->psi_depth > 8)
    return ss_error_set(err, SS_EINPUT,
                        "analyze options out of range: tol %g (0..1), eigenvalues %d "
                        "(>= 1), depth %d (>= 0), ring levels %d (1..%d), psi depth %d "
                        "(0..8)",
                        o->tol, o->neig, o->depth, o->ring_levels, SS_LOCAL_MAXRING,
                        o->psi_depth);
  if (o->psi_tubes && (!o->certify || !o->psi_depth))
    return ss_error_set(err, SS_EINPUT,
                        "psi tubes need certify and a psi depth above 0, as "
                        "`analyze --psi-tubes` needs --certify and --psi-depth");
  if (c->kind == SS_CASE_VERTEX && !c->link)
    return ss_error_set(err, SS_EINPUT, "a vertex case needs a link");
  ss_pipeline_opts po = ss_pipeline_defaults();
  po.tol = o->tol;
  po.depth = o->depth;
  po.ring_levels = o->ring_levels;
  po.certify = o->certify;
  po.psi_depth = o->psi_depth;
  po.psi_tubes = o->psi_tubes;
  ss_pipeline *p = NULL;
  json_object *r = NULL;
  ss_status st = ss_pipeline_compute(s, c, &po, SS_PIPE_VERDICTS, NULL, &p, err);
  if (!st) st = ss_report_case_json(p, o->neig, NULL, &r, err);
  if (!st) {
    const char *text = json_object_to_json_string_ext(
        r, JSON_C_TO_STRING_PLAIN | JSON_C_TO_STRING_NOSLASHESCAPE);
    if (!text || !(*json = strdup(text))) st = ss_error_nomem(err, "JSON text");
  }
  json_object_put(r);
  ss_pipeline_free(p);
  return st;
}
