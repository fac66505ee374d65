/* test_psi_certify.c — psi's verdicts proven (ss_psi_certify,
 * ss_limit_pieces_enclosed, ss_psi_apply with certify):
 *   - the enclosed pieces: with the mesh's points as point intervals and the
 *     rule's exact weights, every piece's intervals lie within rounding of
 *     its double net; with weights enclosed 1e-6 too high (a wrong rule) they
 *     do not — the enclosure follows the weights, not the double net;
 *   - the regular MLCA vertex: pass, proven on every piece;
 *   - finding 1 (k = 8) and a k = 9 link the control net leaves undecided: a
 *     proven fold of psi, two witnesses whose enclosures have opposite strict
 *     signs and contain det Dpsi as the limit evaluator computes it
 *     (ss_limit_eval: canonical frames and cached transitions, another path)
 *     on the enclosure's midpoint net;
 *   - on the edge: the same enclosure widened by 1e-12 still proves the
 *     fold; widened until the witnesses' enclosures must hold 0, it does
 *     not (the verdict in doubles unchanged, certified 0);
 *   - the combination rules (ss_psi_apply) with and without certify;
 *   - refusals: enclosures with lo > hi or NaN (SS_EINPUT), weights no
 *     rational of the allowed denominators accepts (SS_ENUMERIC). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "psi_case.h"
#include "ss_exact.h"
#include "ss_limit_pieces.h"
#include "ss_psi.h"
#include "ss_test.h"

static const char *const FINDING1 = "8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb";
/* k = 9: the control net undecided (a fold shrinking under refinement) */
static const char *const K9 = "9 bcdefghi,aic,abied,ace,adcigf,aeg,afeih,agi,ahgecb";

static ss_pipeline *run(const ss_scheme *s, const char *link) {
  return psi_run(s, link, 4, 1);
}

/* What the enclosed traversal found, piece by piece. */
typedef struct {
  size_t pieces;
  double worst; /* largest distance of a double net point from its interval,
                   relative to the piece's largest |point| */
} cover;

static int visit_cover(const ss_limit_piece *pc, void *arg) {
  cover *c = arg;
  if (!pc->net) return 0;
  c->pieces++;
  double scale = 0.0, out = 0.0;
  for (int q = 0; q < 64; q++)
    for (int d = 0; d < 3; d++) {
      scale = fmax(scale, fabs(pc->net[q][d]));
      const double v = pc->net[q][d];
      out = fmax(out, fmax(pc->lo[q][d] - v, v - pc->hi[q][d]));
    }
  c->worst = fmax(c->worst, out / scale);
  return 0;
}

static int weight_exact(double w, void *arg, double *lo, double *hi) {
  return ss_exact_rational_enclose(w, *(const long *)arg, lo, hi) ? 0 : -1;
}

static int weight_high(double w, void *arg, double *lo, double *hi) {
  (void)arg;
  *lo = *hi = w + 1e-6; /* a rule 1e-6 off the one the net was refined with */
  return 0;
}

static int weight_none(double w, void *arg, double *lo, double *hi) {
  (void)w, (void)arg, (void)lo, (void)hi;
  return -1;
}

/* ss_limit_pieces_enclosed on the net of the regular vertex's basis. */
static void enclosed_pieces(const ss_scheme *s) {
  ss_pipeline *p = run(s, "icosahedron");
  ss_limit *L = p && p->ex ? psi_limit(s, p, p->cm->x) : NULL;
  CHECK(L != NULL, "icosahedron: limit evaluator");
  if (!L) goto done;
  const long maxden = ss_exact_defaults(3).maxden;
  ss_limit_enclosure en = {p->cm->x, p->cm->x, weight_exact, (void *)&maxden};
  cover c = {0, 0.0}, h = {0, 0.0};
  ss_error err = {0};
  size_t cell = 0; /* a cell round p */
  while (cell < p->M->ncells && ss_local_centre_corner(p->M, cell) < 0)
    cell++;
  CHECK(!ss_limit_pieces_enclosed(L, cell, 3, &en, NULL, visit_cover, &c, &err),
        "exact weights: %s", err.msg);
  CHECK(c.pieces > 0 && c.worst <= 1e-13,
        "exact weights: %zu pieces, double nets within %.3g of their intervals", c.pieces,
        c.worst);
  en.weight = weight_high;
  CHECK(!ss_limit_pieces_enclosed(L, cell, 3, &en, NULL, visit_cover, &h, &err),
        "wrong weights: %s", err.msg);
  CHECK(h.pieces == c.pieces && h.worst > 1e-8,
        "weights 1e-6 too high: double nets %.3g outside their intervals", h.worst);
  en.weight = weight_none;
  CHECK(ss_limit_pieces_enclosed(L, cell, 3, &en, NULL, visit_cover, &h, &err) ==
            SS_ENUMERIC,
        "a weight without enclosure: SS_ENUMERIC");
  double bad = NAN;
  en = (ss_limit_enclosure){p->cm->x, p->cm->x, weight_exact, (void *)&maxden};
  const double keep = p->cm->x[0];
  p->cm->x[0] = bad;
  CHECK(ss_limit_pieces_enclosed(L, cell, 3, &en, NULL, visit_cover, &h, &err) ==
            SS_EINPUT,
        "a NaN bound: SS_EINPUT");
  p->cm->x[0] = keep;
done:
  ss_limit_free(L);
  ss_pipeline_free(p);
}

static void regular(const ss_scheme *s) {
  ss_pipeline *p = run(s, "octahedron");
  CHECK(p && p->psi.ran && p->psi.enclosed, "regular vertex: psi judged on an enclosure");
  if (p && p->psi.ran)
    CHECK(p->psi.verdict.verdict == SS_PASS && p->psi.verdict.certified &&
              p->v.reg.verdict == SS_PASS && p->v.reg.certified &&
              p->v.reg.on == SS_ON_PSI,
          "regular vertex: %s%s on %s: %s", ss_verdict_name(p->v.reg.verdict),
          p->v.reg.certified ? " (certified)" : "", ss_judged_on_name(p->v.reg.on),
          p->v.reg.reason);
  ss_pipeline_free(p);
}

/* A proven fold: witnesses checked against ss_limit_eval on the midpoints. */
static void proven_fold(const ss_scheme *s, const char *link, int net_certified) {
  ss_pipeline *p = run(s, link);
  CHECK(p && p->psi.ran, "%s: psi judged", link);
  if (!p || !p->psi.ran) {
    ss_pipeline_free(p);
    return;
  }
  const ss_psi_result *r = &p->psi;
  CHECK(p->reg.verdict.certified == net_certified,
        "%s: the control net's own verdict %s%s", link,
        ss_verdict_name(p->reg.verdict.verdict),
        p->reg.verdict.certified ? " (certified)" : "");
  CHECK(r->verdict.verdict == SS_FAIL && r->verdict.certified && r->nwitness == 2 &&
            p->v.reg.verdict == SS_FAIL && p->v.reg.certified &&
            p->v.reg.on == SS_ON_PSI && p->v.inj.verdict == SS_FAIL && p->v.inj.certified,
        "%s: %s%s: %s", link, ss_verdict_name(p->v.reg.verdict),
        p->v.reg.certified ? " (certified)" : "", p->v.reg.reason);
  psi_encl e = {0};
  ss_limit *L = NULL;
  if (r->nwitness == 2 && !psi_encl_get(p, 0.0, NULL, &e)) L = psi_limit(s, p, e.mid);
  for (int i = 0; i < 2 && L; i++) {
    const ss_psi_point *w = &r->witness[i];
    ss_limit_point pt;
    ss_error err = {0};
    CHECK(!ss_limit_eval(L, w->cell, w->at[0], w->at[1], w->at[2], 1, &pt, &err),
          "%s: witness %d evaluated: %s", link, i, err.msg);
    const double d = psi_det3(pt.jac), tol = 1e-9 * fabs(d);
    CHECK(w->det[0] <= w->det[1] && (i == 0 ? w->det[0] > 0.0 : w->det[1] < 0.0),
          "%s: witness %d enclosure [%.17g, %.17g] of sign %+d", link, i, w->det[0],
          w->det[1], i ? -1 : 1);
    CHECK(w->det[0] - tol <= d && d <= w->det[1] + tol && w->det[1] - w->det[0] <= tol,
          "%s: witness %d: [%.17g, %.17g] vs ss_limit_eval %.17g", link, i, w->det[0],
          w->det[1], d);
  }
  ss_limit_free(L);
  psi_encl_free(&e);
  ss_pipeline_free(p);
}

/* The proof on its edge: widened enclosures of finding 1's basis. */
static void widened(const ss_scheme *s) {
  ss_pipeline *p = run(s, FINDING1);
  if (!p || !p->ex) {
    CHECK(0, "finding 1: no exact path");
    ss_pipeline_free(p);
    return;
  }
  const ss_psi_opts o = ss_psi_defaults();
  const long maxden = ss_exact_defaults(3).maxden;
  double width[2] = {0, 0};
  const double delta[3] = {1e-12, 1e-9, 1e-2};
  for (int k = 0; k < 3; k++) {
    psi_encl e = {0};
    if (psi_encl_get(p, delta[k], NULL, &e)) break;
    const ss_psi_enclosure pe = {e.lo, e.hi, maxden};
    ss_psi_result q;
    ss_error err = {0};
    CHECK(!ss_psi_certify(s, p->M, &pe, &o, &q, &err), "delta %g: %s", delta[k], err.msg);
    CHECK(q.verdict.verdict == SS_FAIL, "delta %g: the double verdict stays (%s)",
          delta[k], ss_verdict_name(q.verdict.verdict));
    if (k < 2) {
      CHECK(q.verdict.certified, "delta %g: still proven", delta[k]);
      width[k] = q.witness[0].det[1] - q.witness[0].det[0];
    } else {
      /* the witnesses' |det Dpsi| ~ 0.05 while 64 points each off by 1e-2
       * make its enclosure far wider than that: the proof must refuse */
      CHECK(!q.verdict.certified && q.enclosed, "delta %g: not proven", delta[k]);
    }
    psi_encl_free(&e);
  }
  CHECK(width[1] > 100.0 * width[0], "enclosures widen with delta: %.3g then %.3g",
        width[0], width[1]);
  /* refusals */
  psi_encl e = {0};
  if (!psi_encl_get(p, 0.0, NULL, &e)) {
    ss_psi_result q;
    ss_error err = {0};
    ss_psi_enclosure pe = {e.lo, e.hi, maxden};
    e.lo[5] = e.hi[5] + 1.0;
    CHECK(ss_psi_certify(s, p->M, &pe, &o, &q, &err) == SS_EINPUT, "lo > hi refused");
    e.lo[5] = NAN;
    CHECK(ss_psi_certify(s, p->M, &pe, &o, &q, &err) == SS_EINPUT, "NaN refused");
    e.lo[5] = e.hi[5];
    pe.maxden = 1; /* MLCA's weights (1/8, 1/64, ...) are no integers */
    CHECK(ss_psi_certify(s, p->M, &pe, &o, &q, &err) == SS_ENUMERIC,
          "weights beyond maxden: SS_ENUMERIC (%s)", err.msg);
    CHECK(ss_psi_certify(s, p->M, NULL, &o, &q, &err) == SS_EINPUT, "no enclosure");
  }
  psi_encl_free(&e);
  ss_pipeline_free(p);
}

/* ss_psi_apply's rules on made-up results. */
static void apply_rules(void) {
  ss_psi_result r;
  memset(&r, 0, sizeof r);
  r.ran = 1;
  r.verdict = (ss_verdict){SS_UNDECIDED, "", 0, SS_ON_PSI};
  const ss_verdict netfail = {SS_FAIL, "a fold of the net", 1, SS_ON_NET};
  const ss_verdict netpass = {SS_PASS, "", 1, SS_ON_NET};
  ss_verdict reg = netfail, inj = netpass;
  ss_psi_apply(&r, 0, &reg, &inj);
  CHECK(reg.verdict == SS_FAIL && !reg.certified && reg.on == SS_ON_NET,
        "psi undecided, no certify: the net's fold stays, unproven");
  reg = netfail;
  ss_psi_apply(&r, 1, &reg, &inj);
  CHECK(reg.verdict == SS_UNDECIDED && !reg.certified,
        "psi undecided, certify: the net's fold is no longer a verdict (%s)", reg.reason);
  /* an unproven fold of psi decides without certify only */
  r.verdict = (ss_verdict){SS_FAIL, "psi folds", 0, SS_ON_PSI};
  r.nwitness = 2;
  reg = netpass, inj = netpass;
  ss_psi_apply(&r, 0, &reg, &inj);
  CHECK(reg.verdict == SS_FAIL && reg.on == SS_ON_PSI && inj.verdict == SS_FAIL,
        "psi folds in doubles, no certify: fail");
  reg = netpass, inj = netpass;
  ss_psi_apply(&r, 1, &reg, &inj);
  CHECK(reg.verdict == SS_PASS && reg.certified && inj.verdict == SS_PASS,
        "psi folds in doubles, certify: the net's proven pass stays");
  r.verdict.certified = 1;
  ss_psi_apply(&r, 1, &reg, &inj);
  CHECK(reg.verdict == SS_FAIL && reg.certified && reg.on == SS_ON_PSI &&
            inj.verdict == SS_FAIL && inj.certified,
        "a proven fold of psi, certify: fail, certified, on psi");
  /* a pass on psi replaces the net's undecided */
  r.verdict = (ss_verdict){SS_PASS, "", 1, SS_ON_PSI};
  reg = (ss_verdict){SS_UNDECIDED, "spoke fold", 0, SS_ON_NET};
  ss_psi_apply(&r, 1, &reg, &inj);
  CHECK(reg.verdict == SS_PASS && reg.certified && reg.on == SS_ON_PSI,
        "a proven pass of psi decides");
  r.ran = 0;
  reg = netfail;
  ss_psi_apply(&r, 1, &reg, &inj);
  CHECK(reg.verdict == SS_FAIL && reg.certified, "psi not run: nothing changes");
}

int main(void) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  REQUIRE_OK(ss_scheme_new("mlca", &s, &err), &err);
  enclosed_pieces(s);
  regular(s);
  proven_fold(s, FINDING1, 1);
  proven_fold(s, K9, 0);
  widened(s);
  apply_rules();
  ss_scheme_free(s);
  return ss_test_done("psi_certify");
}
