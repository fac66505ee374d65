/* ss_result.c — one case through the whole pipeline (ss_result.h). */
#include "ss_result.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ss_certify.h"
#include "ss_charmap.h"
#include "ss_diag.h"
#include "ss_jac.h"
#include "ss_link.h"

ss_result_opts ss_result_defaults(void) {
  const ss_charmap_opts co = ss_charmap_defaults();
  return (ss_result_opts){1e-6, co.depth, co.ring_levels, 0, 0.0};
}

void ss_result_clear(ss_result *r) {
  if (!r) return;
  free(r->link);
  memset(r, 0, sizeof *r);
}

ss_verdict_kind ss_result_verdict(const ss_result *r) {
  if (r->cond.verdict == SS_FAIL || r->reg.verdict == SS_FAIL ||
      r->inj.verdict == SS_FAIL)
    return SS_FAIL;
  if (r->cond.verdict == SS_PASS && r->reg.verdict == SS_PASS &&
      r->inj.verdict == SS_PASS)
    return SS_PASS;
  return SS_UNDECIDED;
}

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int ss_result_certified(const ss_result *r) {
  switch (ss_result_verdict(r)) {
  case SS_PASS:
    return r->cond_certified && r->reg_certified;
  case SS_FAIL:
    return (r->cond.verdict == SS_FAIL && r->cond_certified) ||
           (r->reg.verdict == SS_FAIL && r->reg_certified) ||
           (r->inj.verdict == SS_FAIL && r->inj_certified);
  default:
    return 0;
  }
}

/* The canonical form of a vertex case's link (*cl, caller frees) and its text
 * (an empty string and no link otherwise).  The canonical labelling is the
 * one analysed, so that isomorphic links give results equal to the last bit
 * (LAPACK's rounding depends on the order of rows). */
static ss_status link_text(const ss_case *c, ss_link **cl, char **out, ss_error *err) {
  *cl = NULL;
  if (c->kind != SS_CASE_VERTEX) {
    *out = calloc(1, 1);
    return *out ? SS_OK : ss_error_nomem(err, "result link");
  }
  if (!c->link) return ss_error_set(err, SS_EINPUT, "vertex case without a link");
  ss_status st = ss_link_canonical(c->link, cl, NULL, err);
  if (!st) st = ss_link_format(*cl, out, err);
  return st;
}

/* Count improper pairs of major diagonals.  ss_local does not keep its star,
 * so the star is built once more; it costs a small fraction of the
 * extraction, which refines it several levels. */
static ss_status diagonals(const ss_scheme *s, const ss_case *c, ss_result *r,
                           ss_error *err) {
  ss_star *star = NULL;
  ss_status st = ss_case_star(s, c, &star, err);
  if (!st) st = ss_diag_improper(star->cx, &r->pairs, &r->improper, err);
  ss_star_free(star);
  r->has_diag = st == SS_OK;
  return st;
}

ss_result_workspace *ss_result_workspace_new(void) {
  ss_result_workspace *w = calloc(1, sizeof *w);
  if (!w) return NULL;
  w->local = ss_local_workspace_new();
  w->eig = ss_eig_workspace_new(0);
  if (!w->local || !w->eig) {
    ss_result_workspace_free(w);
    return NULL;
  }
  return w;
}

void ss_result_workspace_free(ss_result_workspace *w) {
  if (!w) return;
  ss_local_workspace_free(w->local);
  ss_eig_workspace_free(w->eig);
  free(w);
}

ss_status ss_result_compute(const ss_scheme *s, const ss_case *c, const ss_result_opts *o,
                            ss_result *r, ss_error *err) {
  return ss_result_compute_ws(s, c, o, NULL, r, err);
}

ss_status ss_result_compute_ws(const ss_scheme *s, const ss_case *c,
                               const ss_result_opts *o, ss_result_workspace *w,
                               ss_result *r, ss_error *err) {
  memset(r, 0, sizeof *r);
  if (!(o->tol > 0.0 && o->tol < 0.1) || o->depth < 0 || o->depth > 12 ||
      o->ring_levels < 1 || o->ring_levels > SS_LOCAL_MAXRING)
    return ss_error_set(
        err, SS_EINPUT,
        "analysis options out of range (tol %g, depth %d, ring levels %d)", o->tol,
        o->depth, o->ring_levels);
  const double t0 = now();
  ss_result_times *tm = w ? w->times : NULL;
  double c1 = tm ? ss_charmap_cpu_seconds() : 0.0;
  ss_local *M = NULL;
  ss_eig *e = NULL;
  ss_charmap *cm = NULL;
  ss_regularity reg;
  ss_link *cl = NULL;
  ss_status st = link_text(c, &cl, &r->link, err);
  ss_case cc = *c;
  if (cl) cc.link = cl;
  const int ep = !st && cl ? ss_case_edge_point(s, cl) : 0;
  if (ep < 0) st = ss_error_nomem(err, "edge point");
  if (ep > 0) cc = (ss_case){SS_CASE_EDGE, NULL, ep, c->diag, 0};
  if (tm) ss_charmap_lap(&tm->canon, &c1);
  ss_local_opts lo = ss_local_defaults();
  lo.max_bytes = o->max_bytes;
  /* a link that folds on the first ring levels is judged on a deeper one:
   * keep the levels so that only the deeper level is refined then (on a
   * failing k = 12 MLCA link the extraction again was a quarter of that) */
  lo.keep_levels = o->ring_levels > lo.nring;
  if (!st) st = ss_local_new_ws(s, &cc, &lo, w ? w->local : NULL, &M, err);
  if (tm) ss_charmap_lap(&tm->extract, &c1);
  if (!st && ss_scheme_reads_diagonals(s) && M->cell == SS_TET)
    st = diagonals(s, &cc, r, err);
  if (tm) ss_charmap_lap(&tm->diagonals, &c1);
  if (!st) {
    ss_eig_opts eo = ss_eig_defaults(M->dim);
    eo.tol = o->tol;
    st = ss_eig_new_ws(M->S, M->n2, M->n1, &eo, w ? w->eig : NULL, &e, err);
  }
  if (tm) ss_charmap_lap(&tm->eig, &c1);
  ss_charmap_inj inj;
  ss_certified cert;
  if (!st) {
    ss_charmap_opts co = ss_charmap_defaults();
    co.depth = o->depth;
    co.ring_levels = o->ring_levels;
    co.times = tm ? &tm->charmap : NULL;
    st = ss_certify_verdicts(s, &cc, M, e, &co, o->certify, &cm, &reg, &inj, &cert, NULL,
                             err);
  }
  ss_link_free(cl);
  if (st) {
    ss_charmap_free(cm);
    ss_eig_free(e);
    ss_local_free(M);
    ss_result_clear(r);
    return st;
  }
  r->kind = ep > 0 ? SS_CASE_EDGE_POINT : c->kind;
  r->k = c->kind == SS_CASE_VERTEX ? c->link->k : c->kind == SS_CASE_FACE ? 0 : c->n;
  r->valence = ep > 0                                                         ? ep
               : c->kind == SS_CASE_EDGE || c->kind == SS_CASE_SURFACE_VERTEX ? c->n
                                                                              : 0;
  if (c->kind == SS_CASE_SURFACE_VERTEX && ss_scheme_split_kind(s) == SS_SPLIT_BISECT)
    r->cls = ss_case_class48(c->n, c->cls);
  r->cells = c->kind == SS_CASE_VERTEX ? (size_t)(2 * r->k - 4)
             : c->kind == SS_CASE_FACE ? 2
                                       : (size_t)c->n;
  r->two_ring = M->n2;
  r->one_ring = M->n1;
  r->neig = e->n < SS_RESULT_NEIG ? (int)e->n : SS_RESULT_NEIG;
  for (int i = 0; i < r->neig; i++)
    r->eig[i] = (ss_result_eigval){e->val[i].re, e->val[i].im, e->val[i].mult};
  r->cond = cert.cond;
  r->cond_certified = cert.cond_certified;
  r->reg_certified = reg.certified;
  r->inj_certified = inj.certified;
  r->tol = e->tol_requested; /* the identity asked for; the verdict says if rounding
                                raised it */
  r->reg = reg.verdict;
  r->inj = inj.verdict;
  r->inj_degree = inj.degree;
  r->min_sj = reg.min_scaled_jacobian;
  r->depth = reg.depth;
  r->ring_levels = o->ring_levels;
  r->ring_level = reg.ring_level;
  r->centre_corner_folds = reg.centre_corner_folds;
  ss_charmap_free(cm);
  ss_eig_free(e);
  ss_local_free(M);
  r->seconds = now() - t0;
  if (tm) tm->cases++;
  return SS_OK;
}
