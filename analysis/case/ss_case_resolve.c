/* ss_case_resolve.c — a case as analysed and reported (ss_case_resolve.h). */
#include "ss_case_resolve.h"

#include <stdlib.h>
#include <string.h>

ss_status ss_case_resolve(const ss_scheme *s, const ss_case *c, ss_case_resolved *r,
                          ss_error *err) {
  memset(r, 0, sizeof *r);
  r->asked = *c;
  r->asked.link = NULL;
  r->judged = *c;
  r->kind = c->kind;
  ss_status st = SS_OK;
  if (c->kind == SS_CASE_VERTEX) {
    if (!c->link) return ss_error_set(err, SS_EINPUT, "vertex case without a link");
    if ((st = ss_link_canonical(c->link, &r->canon, NULL, err)) ||
        (st = ss_link_format(r->canon, &r->text, err)))
      goto fail;
    r->judged.link = r->canon;
    r->k = r->canon->k;
    r->cells = (size_t)(2 * r->k - 4);
    const int ep = ss_case_edge_point(s, r->canon);
    if (ep < 0) {
      st = ss_error_nomem(err, "edge point");
      goto fail;
    }
    if (ep > 0) { /* a point on an extraordinary edge: the edge case judges it */
      r->judged = (ss_case){SS_CASE_EDGE, NULL, ep, c->diag, 0};
      r->kind = SS_CASE_EDGE_POINT;
      r->valence = ep;
    }
    return SS_OK;
  }
  if (!(r->text = calloc(1, 1))) {
    st = ss_error_nomem(err, "case text");
    goto fail;
  }
  r->k = c->kind == SS_CASE_FACE ? 0 : c->n;
  r->valence = c->kind == SS_CASE_EDGE || c->kind == SS_CASE_SURFACE_VERTEX ? c->n : 0;
  r->cells = c->kind == SS_CASE_FACE ? 2 : (size_t)c->n;
  if (c->kind == SS_CASE_SURFACE_VERTEX && ss_scheme_split_kind(s) == SS_SPLIT_BISECT)
    r->cls = ss_case_class48(c->n, c->cls);
  return SS_OK;
fail:
  ss_case_resolved_clear(r);
  return st;
}

ss_status ss_case_resolved_star(const ss_scheme *s, ss_case_resolved *r,
                                const ss_star **star, ss_error *err) {
  if (!r->star) {
    ss_status st = ss_case_star(s, &r->judged, &r->star, err);
    if (st) return st;
  }
  *star = r->star;
  return SS_OK;
}

void ss_case_resolved_clear(ss_case_resolved *r) {
  if (!r) return;
  ss_link_free(r->canon);
  free(r->text);
  ss_star_free(r->star);
  memset(r, 0, sizeof *r);
}
