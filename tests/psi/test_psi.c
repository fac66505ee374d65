/* test_psi.c — psi judged on its polynomial pieces (ss_psi, ss_limit_pieces):
 *   - the regular MLCA vertex: psi is the tricubic B-spline everywhere round
 *     p, one piece per cell, every one of one sign: pass judged on psi,
 *     covered share 1, nothing uncovered;
 *   - the icosahedral link (12 spokes of valence 5): every piece of one sign,
 *     the tubes round the spokes left uncovered, decided by the spokes'
 *     evidence (ss_psi_spoke: all 12 of the ring's sign): a pass on psi,
 *     not proven; the covered share grows with the box depth and the uncovered one falls
 * about 4x per level (a tube round a curve);
 *   - finding 1's link (k = 8, psi o sigma = psi by a reflection): a fold of
 *     psi, fail judged on psi, two witnesses of opposite signs, each checked
 *     against the limit evaluator's own walk (ss_limit_eval with derivatives:
 *     canonical frames and cached transitions, another code path than the
 *     pieces' inherited frames) at the same point;
 *   - basis invariance: the net times an invertible G gives the same verdict,
 *     pieces and uncovered boxes, and the same witnesses with det Dpsi times
 *     det G (exchanged when det G < 0);
 *   - a scheme without pieces (tet/oct) is not judged (ran = 0), not an error;
 *     options out of range are refused. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "psi_case.h"
#include "ss_psi.h"
#include "ss_test.h"

static const char *const FINDING1 = "8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb";

static ss_pipeline *run(const ss_scheme *s, const char *link, int psi_depth) {
  return psi_run(s, link, psi_depth, 0);
}

/* det Dpsi at a witness by the limit evaluator on the two-ring mesh. */
static int eval_det(const ss_scheme *s, const ss_pipeline *p, const ss_psi_point *w,
                    double *det) {
  ss_error err = {0};
  ss_limit *L = psi_limit(s, p, p->cm->x);
  ss_limit_point pt;
  const int rc =
      L && !ss_limit_eval(L, w->cell, w->at[0], w->at[1], w->at[2], 1, &pt, &err) ? 0
                                                                                  : -1;
  if (!rc) *det = psi_det3(pt.jac);
  if (L && rc) fprintf(stderr, "eval_det: %s\n", err.msg);
  ss_limit_free(L);
  return rc;
}

static void regular(const ss_scheme *s) {
  ss_pipeline *p = run(s, "octahedron", 4);
  CHECK(p && p->psi.ran, "regular vertex: psi judged");
  if (!p || !p->psi.ran) {
    ss_pipeline_free(p);
    return;
  }
  const ss_psi_result *r = &p->psi;
  CHECK(r->verdict.verdict == SS_PASS && p->v.reg.verdict == SS_PASS &&
            p->v.reg.on == SS_ON_PSI,
        "regular vertex: %s on %s", ss_verdict_name(p->v.reg.verdict),
        ss_judged_on_name(p->v.reg.on));
  CHECK(r->covered == 1.0 && r->uncovered == 0.0 && r->nuncovered == 0 &&
            r->pieces == p->M->ncentre && (r->npositive == 0 || r->nnegative == 0),
        "regular vertex: covered %g, %zu pieces (+%zu -%zu) for %zu cells round p",
        r->covered, r->pieces, r->npositive, r->nnegative, p->M->ncentre);
  ss_pipeline_free(p);
}

static void spokes(const ss_scheme *s) {
  double cov[3], unc[3];
  for (int d = 2; d <= 4; d++) {
    ss_pipeline *p = run(s, "icosahedron", d);
    CHECK(p && p->psi.ran, "icosahedron: judged at depth %d", d);
    if (!p || !p->psi.ran) {
      ss_pipeline_free(p);
      return;
    }
    const ss_psi_result *r = &p->psi;
    cov[d - 2] = r->covered;
    unc[d - 2] = r->uncovered;
    CHECK(r->opposite == 0.0 && r->nfolded == 0 && r->nuncovered > 0 &&
              fabs(r->covered + r->uncovered + r->doubtful - 1.0) < 1e-12,
          "icosahedron depth %d: %s, covered %g, uncovered %g, doubtful %g", d,
          ss_verdict_name(r->verdict.verdict), r->covered, r->uncovered, r->doubtful);
    /* the tubes are left to the spokes' evidence (ss_psi_spoke): 12 spokes
     * of the ring's sign, so psi passes, not proven, judged on psi */
    CHECK(r->verdict.verdict == SS_PASS && !r->verdict.certified && r->spokes &&
              r->nspokes == 12 && r->nspoke_one == 12 &&
              strstr(r->verdict.reason, "by evidence") &&
              strstr(r->verdict.reason, "not proven") && p->v.reg.verdict == SS_PASS &&
              p->v.reg.on == SS_ON_PSI && !p->v.reg.certified,
          "icosahedron depth %d: psi %s (%s), %zu spokes of one sign", d,
          ss_verdict_name(r->verdict.verdict), r->verdict.reason, r->nspoke_one);
    ss_pipeline_free(p);
  }
  for (int i = 1; i < 3; i++) {
    CHECK(cov[i] > cov[i - 1], "covered grows: %g then %g", cov[i - 1], cov[i]);
    /* a tube round a curve: its volume falls 4x per level (about) */
    CHECK(unc[i] < 0.3 * unc[i - 1] && unc[i] > 0.2 * unc[i - 1],
          "uncovered falls ~4x per level: %g then %g", unc[i - 1], unc[i]);
  }
}

static void fold(const ss_scheme *s) {
  ss_pipeline *p = run(s, FINDING1, 4);
  CHECK(p && p->psi.ran, "finding 1: psi judged");
  if (!p || !p->psi.ran) {
    ss_pipeline_free(p);
    return;
  }
  const ss_psi_result *r = &p->psi;
  CHECK(r->verdict.verdict == SS_FAIL && r->nwitness == 2 && p->v.reg.on == SS_ON_PSI &&
            p->v.reg.verdict == SS_FAIL && p->v.inj.verdict == SS_FAIL &&
            !p->v.reg.certified,
        "finding 1: %s: %s", ss_verdict_name(p->v.reg.verdict), p->v.reg.reason);
  /* the reason names the witnesses (their cells), not another branch's text */
  char cell[40];
  snprintf(cell, sizeof cell, "at cell %zu (", r->witness[0].cell);
  CHECK(!strncmp(r->verdict.reason, "psi folds: det Dpsi in [", 24) &&
            strstr(r->verdict.reason, cell) && !strstr(r->verdict.reason, "tube"),
        "finding 1: psi's reason names its witnesses: %s", r->verdict.reason);
  if (r->nwitness == 2) {
    const double a = r->witness[0].det[0], b = r->witness[1].det[0];
    CHECK(a * b < 0.0, "witnesses of opposite signs: %g, %g", a, b);
    for (int i = 0; i < 2; i++) {
      double d = NAN;
      CHECK(!eval_det(s, p, &r->witness[i], &d), "witness %d evaluated", i);
      CHECK(fabs(d - r->witness[i].det[0]) <= 1e-9 * fabs(r->witness[i].det[0]),
            "witness %d: det %.17g by the pieces, %.17g by ss_limit_eval", i,
            r->witness[i].det[0], d);
    }
  }
  /* basis invariance: X G for a G with det < 0, and one with det > 0 */
  const double G[2][3][3] = {{{0.3, 1.1, -0.2}, {0.9, -0.4, 0.5}, {0.2, 0.7, 1.3}},
                             {{2.0, 0.1, 0.0}, {0.3, 1.0, 0.2}, {-0.1, 0.4, 1.5}}};
  for (int g = 0; g < 2; g++) {
    const size_t n = p->M->n2;
    double *y = malloc(3 * n * sizeof *y);
    for (size_t i = 0; i < n; i++)
      for (int c = 0; c < 3; c++) {
        y[3 * i + (size_t)c] = 0.0;
        for (int k = 0; k < 3; k++)
          y[3 * i + (size_t)c] += p->cm->x[3 * i + (size_t)k] * G[g][k][c];
      }
    ss_psi_result q;
    ss_error err = {0};
    ss_psi_opts o = ss_psi_defaults();
    o.maxdepth = 4;
    CHECK(!ss_psi_judge(s, p->M, y, &o, &q, &err), "basis %d: %s", g, err.msg);
    double Gg[3][3];
    memcpy(Gg, G[g], sizeof Gg);
    const int flip = psi_det3(Gg) < 0.0;
    /* the verdict, the pieces and the uncovered boxes do not depend on the
     * basis, and the witnesses (each sign's largest |det|, far from 0) are
     * the same points with det times det G.  The counts of proven and folded
     * pieces may differ: det Dpsi vanishes on the mirror plane of sigma, and
     * next to it the double path's flat threshold, relative to the piece's
     * scale per axis, decides (what the interval path is for). */
    CHECK(q.verdict.verdict == r->verdict.verdict && q.pieces == r->pieces &&
              q.nuncovered == r->nuncovered && q.nwitness == 2,
          "basis %d: %s, %zu pieces, %zu uncovered", g,
          ss_verdict_name(q.verdict.verdict), q.pieces, q.nuncovered);
    const double dg = psi_det3(Gg);
    for (int i = 0; i < 2 && q.nwitness == 2; i++) {
      const ss_psi_point *a = &r->witness[i], *b = &q.witness[flip ? 1 - i : i];
      CHECK(a->cell == b->cell && !memcmp(a->at, b->at, sizeof a->at) &&
                fabs(b->det[0] - dg * a->det[0]) <= 1e-9 * fabs(dg * a->det[0]),
            "basis %d, witness %d: cell %zu/%zu, det %.17g vs %.17g x det G %.6g", g, i,
            a->cell, b->cell, b->det[0], a->det[0], dg);
    }
    free(y);
  }
  ss_pipeline_free(p);
}

static void refusals(void) {
  ss_scheme *t = NULL;
  ss_error err = {0};
  if (ss_scheme_new("tetoct", &t, &err)) {
    CHECK(0, "tetoct: %s", err.msg);
    return;
  }
  ss_pipeline *p = run(t, "octahedron", 4);
  CHECK(p && !p->psi.ran && p->psi.why[0], "tet/oct: not judged on pieces (%s)",
        p ? p->psi.why : "no pipeline");
  if (p) {
    ss_psi_result q;
    ss_psi_opts o = ss_psi_defaults();
    o.maxdepth = 0;
    CHECK(ss_psi_judge(t, p->M, p->cm ? p->cm->x : NULL, &o, &q, &err) == SS_EINPUT,
          "depth 0 refused");
    o = ss_psi_defaults();
    CHECK(ss_psi_judge(t, p->M, NULL, &o, &q, &err) == SS_EINPUT, "no net refused");
  }
  ss_pipeline_free(p);
  ss_scheme_free(t);
}

int main(void) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  REQUIRE_OK(ss_scheme_new("mlca", &s, &err), &err);
  regular(s);
  spokes(s);
  fold(s);
  refusals();
  ss_scheme_free(s);
  return ss_test_done("psi");
}
