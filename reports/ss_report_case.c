/* ss_report_case.c — one case as the JSON object of `analyze --format json`,
 * and the pipeline of `analyze` that makes it (ss_report_case.h). */
#include "ss_report_case.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_diag.h"
#include "ss_exact.h"
#include "ss_link.h"
#include "ss_report_table.h"
#include "ss_star.h"

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

/* The regularity object of DESIGN section 7, with the ring's levels. */
static json_object *regularity_json(const ss_regularity *reg) {
  /* certified: set by ss_charmap_certify under --certify, else 0 */
  json_object *g = ss_report_verdict_json(&reg->verdict, reg->certified);
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

ss_status ss_report_case_json(const ss_report_case *c, json_object **out, ss_error *err) {
  const ss_local *M = c->M;
  const ss_eig *e = c->e;
  json_object *r = json_object_new_object();
  *out = NULL;
  if (!r) {
    json_object_put(c->eigenvectors);
    return ss_error_nomem(err, "JSON object");
  }
  json_object_object_add(r, "scheme", json_object_new_string(c->scheme));
  json_object_object_add(r, "case", json_object_new_string(ss_case_name(c->kind)));
  if (c->kind == SS_CASE_VERTEX || c->kind == SS_CASE_EDGE_POINT) {
    json_object_object_add(r, "link", json_object_new_string(c->link ? c->link : ""));
    json_object_object_add(r, "k", json_object_new_int(c->k));
  }
  if (c->kind == SS_CASE_EDGE || c->kind == SS_CASE_SURFACE_VERTEX ||
      c->kind == SS_CASE_EDGE_POINT)
    json_object_object_add(r, "valence", json_object_new_int(c->n));
  json_object_object_add(r, "two_ring_size", json_object_new_int64((int64_t)M->n2));
  json_object_object_add(r, "one_ring_size", json_object_new_int64((int64_t)M->n1));
  json_object_object_add(r, "level", json_object_new_int(M->level));
  if (c->diag_shown) {
    json_object *d = json_object_new_object();
    json_object_object_add(d, "choice", json_object_new_string(ss_diag_name(c->diag)));
    json_object_object_add(d, "pairs", json_object_new_int64((int64_t)c->diag_pairs));
    json_object_object_add(d, "improper",
                           json_object_new_int64((int64_t)c->diag_improper));
    json_object_object_add(r, "diagonals", d);
  }
  json_object_object_add(r, "outer_blocks", json_object_new_int64((int64_t)e->nblocks));
  json_object_object_add(r, "largest_outer_block",
                         json_object_new_int64((int64_t)e->largest_block));
  json_object *ev = json_object_new_array();
  for (size_t i = 0; i < e->n && i < (size_t)c->neig; i++) {
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
  json_object *cj = ss_report_verdict_json(c->cert ? &c->cert->cond : &e->cond,
                                           c->cert && c->cert->cond_certified);
  json_object_object_add(cj, "tolerance", json_object_new_double(e->tol));
  json_object_object_add(cj, "tolerance_requested",
                         json_object_new_double(e->tol_requested));
  json_object_object_add(cj, "rounding_bound", json_object_new_double(e->rounding));
  if (c->exact) {
    size_t nr = 0;
    const ss_exact_root *x = ss_exact_roots(c->exact, &nr);
    json_object *a = json_object_new_array();
    for (size_t i = 0; i < nr && i < (size_t)c->neig; i++) {
      char poly[256];
      json_object *q = json_object_new_object();
      json_object_object_add(q, "re", json_object_new_double(x[i].re));
      json_object_object_add(q, "im", json_object_new_double(x[i].im));
      json_object_object_add(q, "radius", json_object_new_double(x[i].rad));
      json_object_object_add(q, "multiplicity", json_object_new_int(x[i].mult));
      json_object_object_add(q, "degree", json_object_new_int(x[i].degree));
      json_object_object_add(
          q, "minimal_polynomial",
          json_object_new_string(ss_exact_minpoly(c->exact, i, poly, sizeof poly)));
      json_object_array_add(a, q);
    }
    json_object_object_add(cj, "exact_roots", a);
    json_object_object_add(cj, "exact_seconds",
                           json_object_new_double(c->cert ? c->cert->seconds : 0.0));
  }
  json_object_object_add(r, "eigen_condition", cj);
  json_object_object_add(r, "subdominant_basis", json_object_new_string(e->basis_kind));
  json_object_object_add(r, "regularity", regularity_json(c->reg));
  json_object *in = ss_report_verdict_json(&c->inj->verdict, c->inj->certified);
  json_object_object_add(in, "degree", json_object_new_int(c->inj->degree));
  json_object_object_add(in, "overlaps",
                         json_object_new_int64((int64_t)c->inj->overlaps));
  json_object_object_add(r, "injectivity", in);
  if (c->eigenvectors) json_object_object_add(r, "eigenvectors", c->eigenvectors);
  if (c->cls48) /* quasi48: the 4-8 class analysed */
    json_object_object_add(r, "class", json_object_new_int(c->cls48));
  *out = r;
  return SS_OK;
}

ss_report_analyze_opts ss_report_analyze_defaults(void) {
  const ss_report_analyze_opts o = {1e-6, 16, SS_JAC_DEPTH,
                                    ss_charmap_defaults().ring_levels, 0};
  return o;
}

ss_status ss_report_analyze(const ss_scheme *s, const ss_case *c,
                            const ss_report_analyze_opts *o, char **json, ss_error *err) {
  *json = NULL;
  if (!(o->tol > 0.0 && o->tol < 1.0) || o->neig < 1 || o->depth < 0 ||
      o->ring_levels < 1 || o->ring_levels > SS_LOCAL_MAXRING)
    return ss_error_set(err, SS_EINPUT,
                        "analyze options out of range: tol %g (0..1), eigenvalues %d "
                        "(>= 1), depth %d (>= 0), ring levels %d (1..%d)",
                        o->tol, o->neig, o->depth, o->ring_levels, SS_LOCAL_MAXRING);
  if (c->kind == SS_CASE_VERTEX && !c->link)
    return ss_error_set(err, SS_EINPUT, "a vertex case needs a link");
  ss_status st = SS_OK;
  ss_link *cl = NULL;
  char *canon = NULL;
  ss_local *M = NULL;
  ss_eig *e = NULL;
  ss_charmap *cm = NULL;
  ss_exact *ex = NULL;
  ss_star *star = NULL;
  json_object *r = NULL;
  ss_case cc = *c;
  ss_report_case rc;
  memset(&rc, 0, sizeof rc);
  rc.scheme = ss_scheme_name(s);
  rc.kind = c->kind;
  rc.n = c->n;
  rc.neig = o->neig;
  rc.diag = c->diag;
  if (ss_scheme_split_kind(s) == SS_SPLIT_BISECT && c->kind == SS_CASE_SURFACE_VERTEX)
    rc.cls48 = ss_case_class48(c->n, c->cls);
  if (c->kind == SS_CASE_VERTEX) {
    /* the canonical labelling, as analyze, sweep and reproduce use it */
    if ((st = ss_link_canonical(c->link, &cl, NULL, err)) ||
        (st = ss_link_format(cl, &canon, err)))
      goto done;
    cc.link = cl;
    rc.link = canon;
    rc.k = cl->k;
    const int ep = ss_case_edge_point(s, cl);
    if (ep < 0) {
      st = ss_error_nomem(err, "edge-point test");
      goto done;
    }
    if (ep > 0) { /* a point on an extraordinary edge: the edge case judges it */
      cc = (ss_case){SS_CASE_EDGE, NULL, ep, c->diag, 0};
      rc.kind = SS_CASE_EDGE_POINT;
      rc.n = ep;
    }
  }
  if ((st = ss_local_new(s, &cc, &M, err))) goto done;
  if (ss_scheme_reads_diagonals(s) && M->cell == SS_TET) {
    if ((st = ss_case_star(s, &cc, &star, err)) ||
        (st = ss_diag_improper(star->cx, &rc.diag_pairs, &rc.diag_improper, err)))
      goto done;
    rc.diag_shown = 1;
  }
  ss_eig_opts eo = ss_eig_defaults(M->dim);
  eo.tol = o->tol;
  if ((st = ss_eig_new(M->S, M->n2, M->n1, &eo, &e, err))) goto done;
  ss_charmap_opts co = ss_charmap_defaults();
  co.depth = o->depth;
  co.ring_levels = o->ring_levels;
  ss_regularity reg;
  ss_charmap_inj inj;
  ss_certified cert;
  if ((st = ss_certify_verdicts(s, &cc, M, e, &co, o->certify, &cm, &reg, &inj, &cert,
                                &ex, err)))
    goto done;
  rc.M = M;
  rc.e = e;
  rc.reg = &reg;
  rc.inj = &inj;
  rc.cert = o->certify ? &cert : NULL;
  rc.exact = ex;
  if ((st = ss_report_case_json(&rc, &r, err))) goto done;
  const char *text = json_object_to_json_string_ext(
      r, JSON_C_TO_STRING_PLAIN | JSON_C_TO_STRING_NOSLASHESCAPE);
  if (!text || !(*json = strdup(text))) st = ss_error_nomem(err, "JSON text");
done:
  json_object_put(r);
  ss_star_free(star);
  ss_exact_free(ex);
  ss_charmap_free(cm);
  ss_eig_free(e);
  ss_local_free(M);
  free(canon);
  ss_link_free(cl);
  return st;
}
