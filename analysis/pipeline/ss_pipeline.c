/* ss_pipeline.c — one case through the whole analysis (ss_pipeline.h). */
#include "ss_pipeline.h"

#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"
#include "ss_diag.h"
#include "ss_jac.h"
#include "ss_psi.h"
#include "ss_psi_tet.h"

ss_pipeline_opts ss_pipeline_defaults(void) {
  const ss_charmap_opts co = ss_charmap_defaults();
  ss_pipeline_opts o;
  memset(&o, 0, sizeof o);
  o.tol = 1e-6;
  o.depth = co.depth;
  o.ring_levels = co.ring_levels;
  o.psi_depth = 0;
  return o;
}

ss_pipeline_workspace *ss_pipeline_workspace_new(void) {
  ss_pipeline_workspace *w = calloc(1, sizeof *w);
  if (!w) return NULL;
  w->local = ss_local_workspace_new();
  w->eig = ss_eig_workspace_new(0);
  if (!w->local || !w->eig) {
    ss_pipeline_workspace_free(w);
    return NULL;
  }
  return w;
}

void ss_pipeline_workspace_free(ss_pipeline_workspace *w) {
  if (!w) return;
  ss_local_workspace_free(w->local);
  ss_eig_workspace_free(w->eig);
  free(w);
}

void ss_pipeline_free(ss_pipeline *p) {
  if (!p) return;
  ss_local_free(p->M); /* its kept levels read the case's star: first */
  ss_eig_free(p->e);
  ss_charmap_free(p->cm);
  ss_exact_free(p->ex);
  ss_case_resolved_clear(&p->c);
  free(p);
}

ss_status ss_pipeline_new(const ss_scheme *s, const ss_case *c, const ss_pipeline_opts *o,
                          ss_pipeline_workspace *w, ss_pipeline **out, ss_error *err) {
  *out = NULL;
  const ss_pipeline_opts d = ss_pipeline_defaults();
  if (!o) o = &d;
  if (!(o->tol > 0.0 && o->tol < 0.1) || o->depth < 0 || o->depth > 12 ||
      o->ring_levels < 1 || o->ring_levels > SS_LOCAL_MAXRING || o->psi_depth < 0 ||
      o->psi_depth > 8)
    return ss_error_set(
        err, SS_EINPUT,
        "analysis options out of range (tol %g, depth %d, ring levels %d, "
        "psi depth %d: 0..8)",
        o->tol, o->depth, o->ring_levels, o->psi_depth);
  ss_pipeline *p = calloc(1, sizeof *p);
  if (!p) return ss_error_nomem(err, "pipeline");
  p->scheme = s;
  p->opts = *o;
  const double t0 = ss_clock_wall();
  ss_pipeline_times *tm = w ? w->times : NULL;
  double c1 = tm ? ss_clock_cpu() : 0.0;
  const ss_status st = ss_case_resolve(s, c, &p->c, err);
  if (tm) ss_clock_lap(&tm->canon, &c1);
  if (st) {
    ss_pipeline_free(p);
    return st;
  }
  p->done = SS_PIPE_CASE;
  p->seconds = ss_clock_wall() - t0;
  *out = p;
  return SS_OK;
}

/* The local matrix and, for schemes that read major diagonals, the improper
 * pairs of the star's diagonals. */
static ss_status matrix(ss_pipeline *p, ss_pipeline_workspace *w, ss_error *err) {
  ss_pipeline_times *tm = w ? w->times : NULL;
  double c1 = tm ? ss_clock_cpu() : 0.0;
  ss_local_opts lo = ss_local_defaults(); /* the budget is checked below, once */
  lo.progress = p->opts.progress;
  /* a link that folds on the first ring levels is judged on a deeper one:
   * keep the levels so that only the deeper level is refined then (on a
   * failing k = 12 MLCA link the extraction again was a quarter of that) */
  lo.keep_levels = p->opts.ring_levels > lo.nring;
  /* the star, once: the extraction refines it, the diagonals are counted on
   * it; the budget is checked before it is built */
  ss_status st = SS_OK;
  if (p->opts.max_bytes > 0.0) {
    ss_local_cost k;
    st = ss_local_estimate(p->scheme, &p->c.judged, &k, err);
    if (!st) st = ss_local_check_budget(&k, p->opts.max_bytes, err);
  }
  if (!st) st = ss_case_resolved_star(p->scheme, &p->c, &lo.star, err);
  if (!st)
    st = ss_local_new_ws(p->scheme, &p->c.judged, &lo, w ? w->local : NULL, &p->M, err);
  if (tm) ss_clock_lap(&tm->extract, &c1);
  if (!st && ss_scheme_reads_diagonals(p->scheme) && p->M->cell == SS_TET) {
    st = ss_diag_improper(p->c.star->cx, &p->pairs, &p->improper, err);
    p->has_diag = st == SS_OK;
  }
  if (tm) ss_clock_lap(&tm->diagonals, &c1);
  return st;
}

static ss_status eigen(ss_pipeline *p, ss_pipeline_workspace *w, ss_error *err) {
  ss_pipeline_times *tm = w ? w->times : NULL;
  double c1 = tm ? ss_clock_cpu() : 0.0;
  ss_eig_opts eo = ss_eig_defaults(p->M->dim);
  eo.tol = p->opts.tol;
  eo.force = p->opts.force;
  eo.progress = p->opts.progress;
  const ss_status st =
      ss_eig_new_ws(p->M->S, p->M->n2, p->M->n1, &eo, w ? w->eig : NULL, &p->e, err);
  if (tm) ss_clock_lap(&tm->eig, &c1);
  if (!st) p->v.cond = p->e->cond;
  return st;
}

/* The exact path's enclosure of psi's net (ss_exact_basis, transposed to
 * rows) into lo, hi (allocated here, n2 x 3); 0, or -1 when there is none
 * (*lo, *hi NULL: no exact path, or its basis could not be enclosed). */
static int psi_enclosure(const ss_pipeline *p, double **lo, double **hi, ss_error *err,
                         ss_status *st) {
  const size_t n = p->M->n2, m = (size_t)p->cm->dim;
  *lo = *hi = NULL;
  if (!p->ex || m != 3) return -1;
  double *bl = malloc((3 * n + 1) * sizeof *bl), *bh = malloc((3 * n + 1) * sizeof *bh);
  *lo = malloc((3 * n + 1) * sizeof **lo);
  *hi = malloc((3 * n + 1) * sizeof **hi);
  ss_error be = {0};
  if (!bl || !bh || !*lo || !*hi)
    *st = ss_error_nomem(err, "psi: basis enclosure");
  else if (ss_exact_basis(p->ex, bl, bh, &be) == SS_OK)
    for (size_t i = 0; i < n; i++)
      for (size_t d = 0; d < 3; d++) {
        (*lo)[3 * i + d] = bl[d * n + i]; /* column-major to rows */
        (*hi)[3 * i + d] = bh[d * n + i];
      }
  else {
    free(*lo);
    free(*hi);
    *lo = *hi = NULL;
  }
  free(bl);
  free(bh);
  return *lo ? 0 : -1;
}

/* psi judged on its pieces (ss_psi) when the case has a characteristic map
 * and is a vertex, on the map's double net — with certify on the exact
 * path's enclosure of the basis, proving what it can (ss_psi_certify) — its
 * verdict then combined into the net's (ss_psi_apply; with certify only a
 * proven verdict on psi decides). */
static ss_status psi(ss_pipeline *p, ss_pipeline_times *tm, ss_error *err) {
  p->psi.ran = 0;
  if (!p->opts.psi_depth || !p->cm || p->c.judged.kind != SS_CASE_VERTEX ||
      p->v.cond.verdict != SS_PASS)
    return SS_OK;
  ss_psi_opts o = ss_psi_defaults();
  o.maxdepth = p->opts.psi_depth;
  o.tubes = p->opts.psi_tubes;
  double c1 = tm ? ss_clock_cpu() : 0.0;
  ss_status st = SS_OK;
  if (p->M->cell == SS_TET) { /* no pieces: regular vertices and spokes */
    ss_progress_step(&p->opts.progress, "psi at its regular vertices and spokes", 0, 0);
    double *lo = NULL, *hi = NULL;
    ss_psi_enclosure e = {NULL, NULL, ss_exact_defaults(p->M->dim).maxden};
    if (p->opts.certify && !psi_enclosure(p, &lo, &hi, err, &st)) {
      e.lo = lo;
      e.hi = hi;
    }
    if (!st)
      st = ss_psi_tet_judge(p->scheme, &p->c.judged, p->M, p->cm->x, e.lo ? &e : NULL,
                            &p->reg, &p->psi, err);
    free(lo);
    free(hi);
    if (!st) ss_psi_apply(&p->psi, p->opts.certify, &p->v.reg, &p->v.inj);
    if (tm) ss_clock_lap(&tm->psi, &c1);
    return st;
  }
  ss_progress_step(&p->opts.progress, "psi on its polynomial pieces", 0, 0);
  double *lo = NULL, *hi = NULL;
  if (p->opts.certify && !psi_enclosure(p, &lo, &hi, err, &st)) {
    const ss_psi_enclosure e = {lo, hi, ss_exact_defaults(p->M->dim).maxden};
    st = ss_psi_certify(p->scheme, p->M, &e, &o, &p->psi, err);
  } else if (!st) {
    st = ss_psi_judge(p->scheme, p->M, p->cm->x, &o, &p->psi, err);
  }
  free(lo);
  free(hi);
  if (!st) ss_psi_apply(&p->psi, p->opts.certify, &p->v.reg, &p->v.inj);
  if (tm) {
    ss_clock_lap(&tm->psi, &c1);
    tm->psi_prove += p->psi.prove_seconds;
    tm->psi_spokes += p->psi.spoke_seconds;
  }
  return st;
}

/* The three verdicts; with force and no map, the forced map judged for a
 * picture (the verdicts keep what the case has: no characteristic map). */
static ss_status verdicts(ss_pipeline *p, ss_pipeline_times *tm, ss_error *err) {
  ss_charmap_opts co = ss_charmap_defaults();
  co.depth = p->opts.depth;
  co.ring_levels = p->opts.ring_levels;
  co.times = tm ? &tm->charmap : NULL;
  co.exact_lazy = p->opts.exact_lazy;
  co.similarity = p->opts.exact_lazy && !p->opts.psi_depth; /* psi reads p->ex */
  ss_certified cert;
  ss_progress_step(&p->opts.progress,
                   p->opts.certify ? "regularity, injectivity, exact path"
                                   : "regularity and injectivity",
                   0, 0);
  ss_status st =
      ss_certify_verdicts(p->scheme, &p->c.judged, p->M, p->e, &co, p->opts.certify,
                          &p->cm, &p->reg, &p->inj, &cert, &p->ex, err);
  if (st) return st;
  p->v = (ss_verdicts){cert.cond, p->reg.verdict, p->inj.verdict};
  p->exact_seconds = cert.seconds;
  p->route = cert.route;
  if (p->cm && (st = psi(p, tm, err))) return st;
  if (!p->cm && p->opts.force && p->e->basis) {
    if ((st = ss_charmap_new(p->M, p->e, &p->cm, err)) ||
        (st = ss_charmap_regularity(p->cm, p->M, &co, &p->reg, err)))
      return st;
    p->forced = 1;
  }
  return SS_OK;
}

ss_status ss_pipeline_run(ss_pipeline *p, ss_pipeline_stage until,
                          ss_pipeline_workspace *w, ss_error *err) {
  const double t0 = ss_clock_wall();
  ss_status st = SS_OK;
  if (p->done < SS_PIPE_MATRIX && until >= SS_PIPE_MATRIX) {
    if (!(st = matrix(p, w, err))) p->done = SS_PIPE_MATRIX;
  }
  if (!st && p->done < SS_PIPE_EIGEN && until >= SS_PIPE_EIGEN) {
    if (!(st = eigen(p, w, err))) p->done = SS_PIPE_EIGEN;
  }
  if (!st && p->done < SS_PIPE_VERDICTS && until >= SS_PIPE_VERDICTS) {
    ss_pipeline_times *tm = w ? w->times : NULL;
    if (!(st = verdicts(p, tm, err))) {
      p->done = SS_PIPE_VERDICTS;
      if (tm) tm->cases++;
    }
  }
  p->seconds += ss_clock_wall() - t0;
  return st;
}

ss_status ss_pipeline_compute(const ss_scheme *s, const ss_case *c,
                              const ss_pipeline_opts *o, ss_pipeline_stage until,
                              ss_pipeline_workspace *w, ss_pipeline **out,
                              ss_error *err) {
  ss_status st = ss_pipeline_new(s, c, o, w, out, err);
  if (!st && (st = ss_pipeline_run(*out, until, w, err))) {
    ss_pipeline_free(*out);
    *out = NULL;
  }
  return st;
}
