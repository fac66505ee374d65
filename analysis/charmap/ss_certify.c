/* ss_certify.c — the certified path of one case (ss_certify.h). */
#include "ss_certify.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"
#include "ss_fourier.h"
#include "ss_schur.h"
#include "ss_simil.h"

/* Regularity and injectivity once the condition cond is settled, the basis
 * from ex (rational S) or else bo (a ball route's: algebraic weights,
 * enclosed in their windows, ss_fourier.h or ss_schur.h, maxden < 0; or the
 * verified similarity's on a rational S, ss_simil.h, maxden > 0). */
static ss_status judge_after(const ss_local *M, const ss_case *c, const ss_charmap *cm,
                             const ss_charmap_opts *o, const ss_verdict *cond,
                             const ss_exact *ex, const ss_ball_outcome *bo, long maxden,
                             ss_regularity *reg, ss_charmap_inj *inj, ss_error *err) {
  ss_status st = SS_OK;
  double *lo = NULL, *hi = NULL;
  if (!cond->certified) { /* undecided already, with its reason */
    ss_verdict_unproven(&reg->verdict, "the eigenvalue condition is not proven");
    ss_verdict_unproven(&inj->verdict, "the eigenvalue condition is not proven");
  } else if (cond->verdict != SS_PASS) {
    /* no characteristic map; keep a failure the double path proved from the
     * spectrum's kind (complex, defective), else there is nothing to judge */
    if (!(cm == NULL && reg->verdict.verdict == SS_FAIL)) {
      reg->verdict.verdict = SS_UNDECIDED;
      reg->verdict.on = SS_ON_NOTHING;
      snprintf(reg->verdict.reason, sizeof reg->verdict.reason,
               "no characteristic map: the eigenvalue condition fails (certified)");
    }
    inj->verdict.verdict = SS_UNDECIDED;
    inj->verdict.on = SS_ON_NOTHING;
    snprintf(inj->verdict.reason, sizeof inj->verdict.reason, "no characteristic map");
  } else if (!cm) {
    ss_verdict_unproven(&reg->verdict,
                        "the double-precision path found no characteristic map");
    ss_verdict_unproven(&inj->verdict,
                        "the double-precision path found no characteristic map");
  } else {
    const size_t n = M->n2 * (size_t)cm->dim;
    lo = malloc((n + 1) * sizeof *lo);
    hi = malloc((n + 1) * sizeof *hi);
    if (!lo || !hi) {
      st = ss_error_nomem(err, "basis enclosure");
      goto done;
    }
    ss_error be = {0};
    const ss_status bs =
        ex ? ss_exact_basis(ex, lo, hi, &be) : ss_ball_outcome_basis(bo, lo, hi, &be);
    if (bs == SS_ENOMEM) {
      st = ss_error_nomem(err, "basis enclosure");
      goto done;
    }
    if (bs) {
      char why[sizeof be.msg + 32];
      snprintf(why, sizeof why, "basis enclosure: %s", be.msg);
      ss_verdict_unproven(&reg->verdict, why);
    } else {
      st = ss_charmap_certify(M, c, lo, hi, cm->dim, maxden, o, reg, inj, err);
    }
  }
done:
  free(lo);
  free(hi);
  return st;
}

/* Whether case c's star turns about its centre (a surface vertex's rays, an
 * edge's faces): the Fourier route's cases. */
static int turns(const ss_case *c) {
  return c->kind == SS_CASE_SURFACE_VERTEX || c->kind == SS_CASE_EDGE;
}

/* A ball route that could not be set up (st from its symmetries or its
 * constructor, pe the message): SS_ENOMEM passed on in *err; otherwise cond
 * undecided with why and the route's words (`no Fourier blocks`, `no
 * symmetry route`) and SS_OK. */
static ss_status route_refused(ss_status st, const ss_error *pe, const char *why,
                               const char *none, ss_verdict *cond, ss_error *err) {
  if (st == SS_ENOMEM) {
    *err = *pe;
    return st;
  }
  char r[sizeof cond->reason];
  snprintf(r, sizeof r, "%.200s; %s: %.200s", why, none, pe->msg);
  ss_verdict_unproven(cond, r);
  return SS_OK;
}

/* The Fourier route's condition for a surface vertex or an edge (*fx: caller frees), or
 * *fx NULL when the star's rotation and reflection do not map the two-ring
 * (then out stays undecided with why). */
static ss_status fourier_condition(const ss_local *M, const ss_case *c, const char *why,
                                   ss_verdict *cond, ss_fourier **fx, ss_error *err) {
  *fx = NULL;
  const size_t n = M->n2;
  size_t *rot = malloc((n + 1) * sizeof *rot), *refl = malloc((n + 1) * sizeof *refl);
  if (!rot || !refl) {
    free(rot);
    free(refl);
    return ss_error_nomem(err, "Fourier blocks");
  }
  /* ss_charmap_symmetry's candidates 0 (rotation by one ray or face about
   * the centre) and rays - 1
   * (reflection by 0) */
  ss_charmap_sym y = {0};
  y.found = 1;
  ss_error pe = {0};
  ss_status st = ss_charmap_sym_perm(M, c, &y, rot, &pe);
  y.index = c->kind == SS_CASE_EDGE ? c->n - 1 : M->ncoord - 1;
  if (!st) st = ss_charmap_sym_perm(M, c, &y, refl, &pe);
  if (st)
    st = route_refused(st, &pe, why, "no Fourier blocks", cond, err);
  else if (!(st = ss_fourier_new(M->S, n, M->n1, rot, refl,
                                 c->kind == SS_CASE_EDGE ? c->n : M->ncoord, M->dim, fx,
                                 err))) {
    int certified = 0;
    ss_ball_outcome_condition(ss_fourier_outcome(*fx), cond, &certified);
  }
  free(rot);
  free(refl);
  return st;
}

/* The Schur route's condition for a volume vertex (*sx: caller frees), or
 * *sx NULL when the link's automorphisms cannot be had (then cond stays
 * undecided with why). */
static ss_status schur_condition(const ss_local *M, const ss_case *c, const char *why,
                                 ss_verdict *cond, ss_schur **sx, ss_error *err) {
  *sx = NULL;
  size_t *G = NULL, ng = 0;
  ss_error pe = {0};
  ss_status st = ss_charmap_sym_group(M, c, &G, &ng, &pe);
  if (!st) st = ss_schur_new(M->S, M->n2, M->n1, G, ng, M->dim, sx, &pe);
  if (st) {
    st = route_refused(st, &pe, why, "no symmetry route", cond, err);
  } else {
    int certified = 0;
    ss_ball_outcome_condition(ss_schur_outcome(*sx), cond, &certified);
  }
  free(G);
  return st;
}

/* An edge the Fourier blocks leave undecided (MLCA-like: a Jordan block in
 * the mode-0 block beside lambda0 = 1, which ss_ball_eig can only bound):
 * the Schur route under the edge's dihedral symmetries and flips, whose
 * clusters Rump's method encloses one by one, defective or not.  When it
 * proves the condition it replaces the Fourier route (*fx freed, *sx set);
 * otherwise cond keeps the Fourier route's reason, the Schur route's
 * appended. */
static ss_status edge_by_schur(const ss_local *M, const ss_case *c, ss_verdict *cond,
                               ss_fourier **fx, ss_schur **sx, ss_error *err) {
  ss_verdict sv = *cond;
  ss_schur *s = NULL;
  ss_status st = schur_condition(M, c, "", &sv, &s, err);
  if (!st && s && sv.certified) {
    ss_fourier_free(*fx);
    *fx = NULL;
    *sx = s;
    *cond = sv;
    return SS_OK;
  }
  if (!st) {
    char r[sizeof cond->reason];
    snprintf(r, sizeof r, "%.200s; by the edge's symmetries: %.200s", cond->reason,
             sv.reason);
    snprintf(cond->reason, sizeof cond->reason, "%s", r);
  }
  ss_schur_free(s);
  return st;
}

/* The verified similarity's pre-pass on a rational S (ss_simil.h): on a
 * proven pass (*passed = 1) the condition and the judgements from its basis,
 * the exact path never run; otherwise nothing is changed and the exact path
 * decides as before. */
static ss_status by_similarity(const ss_local *M, const ss_case *c, const ss_charmap *cm,
                               const ss_charmap_opts *o, long maxden, ss_regularity *reg,
                               ss_charmap_inj *inj, ss_certified *out, int *passed,
                               ss_error *err) {
  ss_exact_times *tm = o->times ? &o->times->exact : NULL;
  const double c0 = tm ? ss_clock_cpu() : 0.0;
  ss_simil *sm = NULL;
  ss_error se = {0};
  ss_status st = ss_simil_new(M->S, M->n2, M->n1, M->dim, maxden, &sm, &se);
  *passed = !st && ss_simil_passed(sm);
  if (tm) {
    tm->simil += ss_clock_cpu() - c0;
    tm->simil_tried++;
    tm->simil_passed += *passed;
  }
  if (st == SS_ENOMEM) *err = se;
  if (st == SS_ENOMEM || !*passed) {
    ss_simil_free(sm);
    return st == SS_ENOMEM ? st : SS_OK;
  }
  int certified = 0;
  ss_ball_outcome_condition(ss_simil_outcome(sm), &out->cond, &certified);
  out->route = "verified similarity";
  out->cond.on = SS_ON_SPECTRUM;
  st = judge_after(M, c, cm, o, &out->cond, NULL, ss_simil_outcome(sm), maxden, reg, inj,
                   err);
  ss_simil_free(sm);
  return st;
}

/* ss_certify; rational = 0: S is known not to be rational (a stencil's
 * algebraic weight), so only the Fourier route (a surface vertex, an edge) or
 * the Schur route (a volume vertex) may prove anything. */
static ss_status certify_run(const ss_local *M, const ss_case *c, const ss_eig *e,
                             const ss_charmap *cm, const ss_charmap_opts *o,
                             ss_regularity *reg, ss_charmap_inj *inj, ss_certified *out,
                             ss_exact **x, int rational, ss_error *err) {
  const double t0 = ss_clock_wall();
  memset(out, 0, sizeof *out);
  if (x) *x = NULL;
  reg->verdict.certified = inj->verdict.certified = 0;
  ss_exact *ex = NULL;
  ss_fourier *fx = NULL;
  ss_schur *sx = NULL;
  ss_exact_opts eo = ss_exact_defaults(M->dim);
  eo.times = o->times ? &o->times->exact : NULL;
  eo.lazy = o->exact_lazy;
  double c1 = o->times ? ss_clock_cpu() : 0.0;
  ss_error xe = {0};
  if (rational && o->similarity && o->exact_lazy) {
    int passed = 0;
    ss_status st = by_similarity(M, c, cm, o, eo.maxden, reg, inj, out, &passed, err);
    if (st || passed) {
      if (o->times) ss_clock_lap(&o->times->certify, &c1);
      out->seconds = ss_clock_wall() - t0;
      return st;
    }
  }
  ss_status st = rational ? ss_exact_new(M->S, M->n2, M->n1, &eo, &ex, &xe) : SS_ENUMERIC;
  if (!rational)
    snprintf(xe.msg, sizeof xe.msg, "%s",
             "weights not rational (the exact path reads rational matrices only)");
  if (st == SS_ENOMEM || st == SS_EINPUT) {
    *err = xe;
    if (o->times) ss_clock_lap(&o->times->certify, &c1);
    return st;
  }
  out->cond = e->cond;
  /* the route tried so far: the exact path, or nothing */
  out->route = rational ? "exact" : "none tried";
  if (st && turns(c)) { /* algebraic: the balls */
    out->route = "Fourier blocks in balls";
    if ((st = fourier_condition(M, c, xe.msg, &out->cond, &fx, err))) goto done;
    const int both = fx && !out->cond.certified && c->kind == SS_CASE_EDGE;
    if (both && (st = edge_by_schur(M, c, &out->cond, &fx, &sx, err))) goto done;
    if (sx)
      out->route = "balls, ties by Schur's lemma";
    else if (both) /* the edge's symmetries tried too, in vain */
      out->route = "Fourier blocks in balls, then ties by Schur's lemma";
    if (!fx && !sx) {
      ss_verdict_unproven(&reg->verdict, "no exact spectrum");
      ss_verdict_unproven(&inj->verdict, "no exact spectrum");
      goto done;
    }
  } else if (st && !rational && c->kind == SS_CASE_VERTEX) { /* the link's group */
    out->route = "balls, ties by Schur's lemma";
    if ((st = schur_condition(M, c, xe.msg, &out->cond, &sx, err))) goto done;
    if (!sx) {
      ss_verdict_unproven(&reg->verdict, "no exact spectrum");
      ss_verdict_unproven(&inj->verdict, "no exact spectrum");
      goto done;
    }
  } else if (st) { /* not rational, or FLINT could not: nothing is proven */
    ss_verdict_unproven(&out->cond, xe.msg);
    ss_verdict_unproven(&reg->verdict, "no exact spectrum");
    ss_verdict_unproven(&inj->verdict, "no exact spectrum");
    st = SS_OK;
    goto done;
  } else {
    ss_exact_condition(ex, &out->cond, &out->cond.certified);
  }
  out->cond.on = SS_ON_SPECTRUM;
  st = judge_after(M, c, cm, o, &out->cond, ex,
                   fx   ? ss_fourier_outcome(fx)
                   : sx ? ss_schur_outcome(sx)
                        : NULL,
                   ex ? eo.maxden : -eo.maxden, reg, inj, err);
done:
  ss_fourier_free(fx);
  ss_schur_free(sx);
  if (o->times) ss_clock_lap(&o->times->certify, &c1);
  out->seconds = ss_clock_wall() - t0;
  if (x && !st)
    *x = ex;
  else
    ss_exact_free(ex);
  return st;
}

ss_status ss_certify(const ss_local *M, const ss_case *c, const ss_eig *e,
                     const ss_charmap *cm, const ss_charmap_opts *o, ss_regularity *reg,
                     ss_charmap_inj *inj, ss_certified *out, ss_exact **x,
                     ss_error *err) {
  return certify_run(M, c, e, cm, o, reg, inj, out, x, 1, err);
}

/* What the double path's verdicts are statements about: the condition about
 * the spectrum; a symmetry sigma with psi o sigma = psi about psi itself
 * (psi is the net's combination of basis functions that sigma permutes, so
 * the net's invariance is psi's); every other verdict of a map about its
 * control net; a regularity failure without a map (complex or defective
 * subdominant eigenvalues) about the spectrum; no map, no judgement. */
static void judged_on(const ss_charmap *cm, ss_verdict *cond, ss_regularity *reg,
                      ss_charmap_inj *inj) {
  cond->on = SS_ON_SPECTRUM;
  if (cm && reg->sym.found)
    reg->verdict.on = inj->verdict.on = SS_ON_PSI;
  else if (cm)
    reg->verdict.on = inj->verdict.on = SS_ON_NET;
  else {
    reg->verdict.on = reg->verdict.verdict == SS_FAIL ? SS_ON_SPECTRUM : SS_ON_NOTHING;
    inj->verdict.on = SS_ON_NOTHING;
  }
}

ss_status ss_certify_verdicts(const ss_scheme *s, const ss_case *c, ss_local *M,
                              const ss_eig *e, const ss_charmap_opts *o, int certify,
                              ss_charmap **cm, ss_regularity *reg, ss_charmap_inj *inj,
                              ss_certified *out, ss_exact **x, ss_error *err) {
  *out = (ss_certified){e->cond, 0.0, "none tried"};
  *inj =
      (ss_charmap_inj){{SS_UNDECIDED, "no characteristic map", 0, SS_ON_NOTHING}, 0, 0};
  if (x) *x = NULL;
  ss_status st = ss_charmap_judge(s, c, M, e, o, cm, reg, err);
  if (!st && *cm) {
    double t0 = o->times ? ss_clock_cpu() : 0.0;
    st = ss_charmap_injectivity(*cm, reg, inj, err);
    if (o->times) ss_clock_lap(&o->times->injective, &t0);
  }
  if (!st) judged_on(*cm, &out->cond, reg, inj);
  const int volume = c->kind != SS_CASE_SURFACE_VERTEX;
  const int rational =
      volume ? ss_scheme_volume_weights_rational(s) : ss_scheme_weights_rational(s);
  if (!st && certify && !rational && (turns(c) || c->kind == SS_CASE_VERTEX))
    /* algebraic weights: the balls (Fourier blocks, or the link's group) */
    return certify_run(M, c, e, *cm, o, reg, inj, out, x, 0, err);
  if (!st && certify && !rational) {
    /* a weight known not to be rational (a stencil's cos(2 pi / n)) among
     * those S reads (a volume case reads no surface rule): the rational
     * reconstruction of S would stand for another matrix */
    ss_verdict_unproven(&out->cond, "weights not rational (the exact path reads rational "
                                    "matrices only)");
    ss_verdict_unproven(&reg->verdict, "weights not rational");
    ss_verdict_unproven(&inj->verdict, "weights not rational");
    return st;
  }
  if (!st && certify) st = ss_certify(M, c, e, *cm, o, reg, inj, out, x, err);
  return st;
}
