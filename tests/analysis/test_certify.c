/* test_certify.c — the certified path of one case (ss_certify,
 * ss_certify_verdicts): the exact spectrum decides the eigenvalue condition,
 * the enclosed basis the regularity, and nothing passes without proof.
 *
 * Properties, on every MLCA vertex link with k = 4..7 (enumerated), MLCA and
 * tet/oct edges of valence 3..8 and 3..6, tet/oct vertices k = 4..6, the
 * tet/oct face, Catmull-Clark surface vertices 3..6 and the Catmull-Clark
 * solid's tetrahedron link, each run with and without certify:
 *   - without certify: the condition is the double path's, nothing is marked
 *     proven, no exact spectrum is returned;
 *   - with it, agreement: a proven condition or regularity verdict is the
 *     double path's wherever that one decided (pass or fail);
 *   - nothing passes without proof: a passing condition or regularity is
 *     certified, a failing condition is certified, a failing regularity is
 *     certified or kept from the double path's spectrum (no map, the
 *     condition failing, proven); every verdict the exact path could not
 *     prove is undecided, "not certified" or "no characteristic map", and
 *     an injectivity pass keeps the double verdict, uncertified; the
 *     exact spectrum is returned for rational weights;
 *   - known answers (reports/): every MLCA link with k <= 7 passes both,
 *     proven; the MLCA edge of valence 8 fails the condition by an exact tie
 *     (1/2 three times), proven, and then has no map to judge; the
 *     Catmull-Clark solid's tetrahedron link fails it with lambda1 < 0,
 *     proven;
 *   - relabelled and mirrored links give the same certified verdicts;
 *   - Loop (irrational weights): no exact spectrum, the condition and the
 *     regularity proven by the Fourier blocks' balls (ss_fourier; its own
 *     test_fourier), injectivity the double path's, uncertified;
 *   - ss_certify without a map from the double path (cm NULL) proves no
 *     regularity even when the exact condition passes;
 *   - with the verified similarity first (ss_simil.h, as sweeps run it): the
 *     same verdicts and certified flags, the similarity deciding passes only
 *     (and some: the route ran).
 * Mutations this catches (tried by hand: the report of issue 33):
 *   - the regularity left as it was when the weights are not rational (the
 *     "no exact spectrum" unproven dropped): an uncertified pass (Loop's,
 *     before the Fourier route proved it);
 *   - a proven condition failure that leaves the regularity's reason alone:
 *     the MLCA edge of valence 8 lacks "(certified)" in it. */
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>

#include "ss_certify.h"
#include "ss_enum.h"
#include "ss_stencil.h"
#include "ss_test.h"
#include "ss_testcase.h"
#include "ss_testlink.h"

/* The certified flags, read in one place (each verdict carries its own,
 * ss_verdict.certified). */
static int cond_certified(const ss_certified *c) {
  return c->cond.certified;
}

static int reg_certified(const ss_regularity *r) {
  return r->verdict.certified;
}

static int inj_certified(const ss_charmap_inj *i) {
  return i->verdict.certified;
}

/* The verdicts of one case. */
typedef struct {
  ss_certified out;   /* the condition (and time) */
  ss_regularity reg;  /* regularity */
  ss_charmap_inj inj; /* injectivity */
  int map;            /* 1 if the double path built a map */
  int exact;          /* 1 if an exact spectrum was returned */
} verdicts;

/* certify: 0 the double path, 1 the exact path, 2 the verified similarity
 * first (ss_charmap_opts.similarity, with lazy factoring). */
static int judge(const ss_scheme *s, const ss_case *c, int certify, verdicts *v,
                 const char *what) {
  ss_local *M = NULL;
  ss_eig *e = NULL;
  ss_charmap *cm = NULL;
  ss_exact *x = NULL;
  ss_error err = {0};
  memset(v, 0, sizeof *v);
  int ok = !ss_local_new(s, c, &M, &err);
  if (ok) {
    const ss_eig_opts eo = ss_eig_defaults(M->dim);
    ss_charmap_opts o = ss_charmap_defaults();
    o.exact_lazy = o.similarity = certify == 2; /* as sweeps run it */
    ok = !ss_eig_new(M->S, M->n2, M->n1, &eo, &e, &err) &&
         !ss_certify_verdicts(s, c, M, e, &o, certify, &cm, &v->reg, &v->inj, &v->out, &x,
                              &err);
    if (ok && !certify)
      CHECK(v->out.cond.verdict == e->cond.verdict &&
                !strcmp(v->out.cond.reason, e->cond.reason),
            "%s: without certify the condition is not the double path's", what);
  }
  CHECK(ok, "%s: %s", what, err.msg);
  v->map = cm != NULL;
  v->exact = x != NULL;
  ss_exact_free(x);
  ss_charmap_free(cm);
  ss_eig_free(e);
  ss_local_free(M);
  return ok ? 0 : -1;
}

/* A decided verdict proven must agree with the double one when that one
 * decided. */
static int agrees(const ss_verdict *proven, int certified, const ss_verdict *dbl) {
  return !certified || dbl->verdict == SS_UNDECIDED || proven->verdict == dbl->verdict;
}

static int undecided_why(const ss_verdict *v, const ss_verdict *dbl) {
  return v->verdict != SS_UNDECIDED || !strncmp(v->reason, "not certified", 13) ||
         !strncmp(v->reason, "no characteristic map", 21) ||
         (dbl->verdict == SS_UNDECIDED && !strcmp(v->reason, dbl->reason));
}

/* Cases the verified similarity decided (the route ran; checked in main). */
static int by_similarity;

/* The verified similarity's pre-pass changes no verdict and no certified
 * flag of the exact path's (cv), and it decides passes only. */
static void same_by_similarity(const ss_scheme *s, const ss_case *c, const verdicts *cv,
                               const char *what) {
  verdicts sv;
  if (judge(s, c, 2, &sv, what)) return;
  const int sim = !strcmp(sv.out.route, "verified similarity");
  by_similarity += sim;
  CHECK(sv.out.cond.verdict == cv->out.cond.verdict &&
            sv.out.cond.certified == cv->out.cond.certified &&
            sv.reg.verdict.verdict == cv->reg.verdict.verdict &&
            sv.reg.verdict.certified == cv->reg.verdict.certified &&
            sv.inj.verdict.verdict == cv->inj.verdict.verdict &&
            sv.inj.verdict.certified == cv->inj.verdict.certified,
        "%s: with the similarity %s/%s/%s, exact path %s/%s/%s (route %s)", what,
        ss_verdict_name(sv.out.cond.verdict), ss_verdict_name(sv.reg.verdict.verdict),
        ss_verdict_name(sv.inj.verdict.verdict), ss_verdict_name(cv->out.cond.verdict),
        ss_verdict_name(cv->reg.verdict.verdict),
        ss_verdict_name(cv->inj.verdict.verdict), sv.out.route);
  CHECK(!sim || (sv.out.cond.verdict == SS_PASS && !sv.exact &&
                 strstr(sv.out.cond.reason, "verified similarity")),
        "%s: the similarity decided %s (%s)", what, ss_verdict_name(sv.out.cond.verdict),
        sv.out.cond.reason);
}

/* Both paths on one case, the general properties; *cv receives the
 * certified verdicts.  0 on success. */
static int both(const ss_scheme *s, const ss_case *c, verdicts *cv, const char *what) {
  verdicts dv;
  if (judge(s, c, 0, &dv, what) || judge(s, c, 1, cv, what)) return -1;
  CHECK(!cond_certified(&dv.out) && !reg_certified(&dv.reg) && !inj_certified(&dv.inj) &&
            !dv.exact,
        "%s: the double path marks something proven", what);
  CHECK(agrees(&cv->out.cond, cond_certified(&cv->out), &dv.out.cond) &&
            agrees(&cv->reg.verdict, reg_certified(&cv->reg), &dv.reg.verdict),
        "%s: proven %s / %s against double %s / %s", what,
        ss_verdict_name(cv->out.cond.verdict), ss_verdict_name(cv->reg.verdict.verdict),
        ss_verdict_name(dv.out.cond.verdict), ss_verdict_name(dv.reg.verdict.verdict));
  const ss_verdict_kind cond = cv->out.cond.verdict, reg = cv->reg.verdict.verdict;
  CHECK((cond == SS_UNDECIDED || cond_certified(&cv->out)) &&
            (reg != SS_PASS || reg_certified(&cv->reg)) &&
            (reg != SS_FAIL || reg_certified(&cv->reg) ||
             (!cv->map && cond == SS_FAIL && cond_certified(&cv->out) &&
              dv.reg.verdict.verdict == SS_FAIL)),
        "%s: passes without proof: condition %s (certified %d), regularity %s "
        "(certified %d)",
        what, ss_verdict_name(cond), cond_certified(&cv->out), ss_verdict_name(reg),
        reg_certified(&cv->reg));
  CHECK(undecided_why(&cv->out.cond, &dv.out.cond) &&
            undecided_why(&cv->reg.verdict, &dv.reg.verdict) &&
            undecided_why(&cv->inj.verdict, &dv.inj.verdict),
        "%s: undecided without saying why: %s / %s / %s", what, cv->out.cond.reason,
        cv->reg.verdict.reason, cv->inj.verdict.reason);
  CHECK(cv->inj.verdict.verdict != SS_PASS ||
            (dv.inj.verdict.verdict == SS_PASS && !inj_certified(&cv->inj)),
        "%s: injectivity pass certified %d", what, inj_certified(&cv->inj));
  CHECK(cv->exact && cv->out.seconds >= 0.0, "%s: no exact spectrum for rational weights",
        what);
  CHECK(!strcmp(dv.out.route, "none tried") && !strcmp(cv->out.route, "exact"),
        "%s: route without certify '%s', with it '%s'", what, dv.out.route,
        cv->out.route);
  same_by_similarity(s, c, cv, what);
  return 0;
}

/* ---- every small MLCA link ---- */

typedef struct {
  const ss_scheme *s;
  int count;
} links_ctx;

static int visit(const ss_link *l, void *vctx) {
  links_ctx *ctx = vctx;
  verdicts cv;
  char what[96];
  snprintf(what, sizeof what, "mlca link %d of k = %d", ++ctx->count, l->k);
  if (both(ctx->s, &(ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, &cv, what)) return 0;
  CHECK(cv.out.cond.verdict == SS_PASS && cond_certified(&cv.out) &&
            cv.reg.verdict.verdict == SS_PASS && reg_certified(&cv.reg),
        "%s: %s / %s (%s)", what, ss_verdict_name(cv.out.cond.verdict),
        ss_verdict_name(cv.reg.verdict.verdict), cv.reg.verdict.reason);
  /* relabelled and mirrored: the same certified verdicts */
  for (int q = 0; q < 2; q++) {
    ss_link *m = ss_testlink_scrambled(l, (unsigned)(ctx->count * 7 + q), q);
    verdicts mv;
    if (m &&
        !judge(ctx->s, &(ss_case){SS_CASE_VERTEX, m, 0, SS_DIAG_BFS, 0}, 1, &mv, what))
      CHECK(mv.out.cond.verdict == cv.out.cond.verdict &&
                cond_certified(&mv.out) == cond_certified(&cv.out) &&
                mv.reg.verdict.verdict == cv.reg.verdict.verdict &&
                reg_certified(&mv.reg) == reg_certified(&cv.reg),
            "%s, %s copy: verdicts change", what, q ? "mirrored" : "relabelled");
    ss_link_free(m);
  }
  return 0;
}

static void test_links(void) {
  links_ctx ctx = {ss_testcase_scheme("mlca"), 0};
  ss_enum_opts o = {4, 7, 0, 1};
  ss_error err = {0};
  CHECK(ss_enum_links(&o, visit, &ctx, NULL, &err) == SS_OK, "%s", err.msg);
  CHECK(ctx.count == 9, "%d links with k = 4..7, expected 1 + 1 + 2 + 5", ctx.count);
  ss_scheme_free((ss_scheme *)ctx.s);
}

/* ---- other cases ---- */

static void test_cases(void) {
  ss_scheme *mlca = ss_testcase_scheme("mlca"), *tetoct = ss_testcase_scheme("tetoct"),
            *cc = ss_testcase_scheme("catmull-clark"),
            *ccsolid = ss_testcase_scheme("ccsolid");
  verdicts cv;
  char what[64];
  for (int n = 3; n <= 8; n++) {
    snprintf(what, sizeof what, "mlca edge %d", n);
    if (both(mlca, &(ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0}, &cv, what))
      continue;
    if (n == 8)
      CHECK(cv.out.cond.verdict == SS_FAIL && cond_certified(&cv.out) &&
                strstr(cv.out.cond.reason, "exact tie") &&
                cv.reg.verdict.verdict == SS_UNDECIDED &&
                strstr(cv.reg.verdict.reason, "(certified)") &&
                cv.inj.verdict.verdict == SS_UNDECIDED,
            "%s: %s (%s) / %s (%s)", what, ss_verdict_name(cv.out.cond.verdict),
            cv.out.cond.reason, ss_verdict_name(cv.reg.verdict.verdict),
            cv.reg.verdict.reason);
  }
  for (int n = 3; n <= 6; n++) {
    snprintf(what, sizeof what, "tetoct edge %d", n);
    both(tetoct, &(ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0}, &cv, what);
    snprintf(what, sizeof what, "catmull-clark vertex %d", n);
    both(cc, &(ss_case){SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0}, &cv, what);
  }
  const char *links[3] = {"tetrahedron", "bipyramid:3", "octahedron"};
  ss_error err = {0};
  for (int i = 0; i < 3; i++) {
    ss_link *l = NULL;
    REQUIRE_OK_VOID(ss_link_named(links[i], &l, &err), &err);
    snprintf(what, sizeof what, "tetoct vertex %s", links[i]);
    both(tetoct, &(ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, &cv, what);
    if (i == 0) {
      snprintf(what, sizeof what, "ccsolid vertex %s", links[i]);
      if (!both(ccsolid, &(ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, &cv, what))
        CHECK(cv.out.cond.verdict == SS_FAIL && cond_certified(&cv.out) &&
                  strstr(cv.out.cond.reason, "not positive"),
              "%s: %s (%s)", what, ss_verdict_name(cv.out.cond.verdict),
              cv.out.cond.reason);
    }
    ss_link_free(l);
  }
  both(tetoct, &(ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, &cv, "tetoct face");
  ss_scheme_free(mlca);
  ss_scheme_free(tetoct);
  ss_scheme_free(cc);
  ss_scheme_free(ccsolid);
}

/* ---- nothing to prove with ---- */

/* The route each case names (ss_certified.route) is the one tried: on
 * data/stencils/tetoct.ini with the tet's self weight written with a cos
 * (value unchanged, so the weights read as not rational), the face has no
 * ball route and names none; the edge the Fourier blocks, the vertex the
 * Schur route (never "exact", which cannot read these weights). */
static void routes(void) {
  const char *text = "[scheme]\nname = tetoct-cos\nfamily = averaging\nsplit = tetoct\n"
                     "[mask.segment]\nself = 1/2\nother = 1/2\n"
                     "[mask.triangle]\nself = 1/4\nedge = 3/8\n"
                     "[mask.tet]\nself = -1/16 + (cos(2*pi/7) - cos(2*pi/7))/64\n"
                     "edge = 17/48\n"
                     "[mask.oct]\nself = 3/8\nedge = 1/12\nopposite = 7/24\n";
  ss_scheme *s = NULL;
  ss_link *oct = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_stencil_parse(text, "tetoct-cos", &s, &err), &err);
  CHECK(!ss_scheme_volume_weights_rational(s), "tetoct-cos: read as rational");
  REQUIRE_OK_VOID(ss_link_named("octahedron", &oct, &err), &err);
  const struct {
    ss_case c;
    const char *route, *what;
  } cases[3] = {
      {{SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, "none tried", "face"},
      {{SS_CASE_EDGE, NULL, 4, SS_DIAG_BFS, 0}, "Fourier blocks in balls", "edge 4"},
      {{SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0},
       "balls, ties by Schur's lemma",
       "octahedron"}};
  for (int i = 0; i < 3; i++) {
    verdicts cv;
    if (judge(s, &cases[i].c, 1, &cv, cases[i].what)) continue;
    CHECK(!strcmp(cv.out.route, cases[i].route) && !cv.exact,
          "tetoct-cos %s: route '%s', want '%s' (%s: %s)", cases[i].what, cv.out.route,
          cases[i].route, ss_verdict_name(cv.out.cond.verdict), cv.out.cond.reason);
    if (i == 0)
      CHECK(cv.out.cond.verdict == SS_UNDECIDED &&
                strstr(cv.out.cond.reason, "not rational"),
            "tetoct-cos face: %s (%s)", ss_verdict_name(cv.out.cond.verdict),
            cv.out.cond.reason);
  }
  ss_link_free(oct);
  ss_scheme_free(s);
}

static void test_unprovable(void) {
  ss_scheme *loop = ss_testcase_scheme("loop");
  verdicts dv, cv;
  const ss_case c = {SS_CASE_SURFACE_VERTEX, NULL, 5, SS_DIAG_BFS, 0};
  if (!judge(loop, &c, 0, &dv, "loop 5") && !judge(loop, &c, 1, &cv, "loop 5"))
    CHECK(dv.out.cond.verdict == SS_PASS && dv.reg.verdict.verdict == SS_PASS &&
              !cv.exact && cv.out.cond.verdict == SS_PASS && cond_certified(&cv.out) &&
              cv.reg.verdict.verdict == SS_PASS && reg_certified(&cv.reg) &&
              cv.inj.verdict.verdict == SS_PASS && !inj_certified(&cv.inj),
          "loop 5: %s (%s) / %s (%s) / %s", ss_verdict_name(cv.out.cond.verdict),
          cv.out.cond.reason, ss_verdict_name(cv.reg.verdict.verdict),
          cv.reg.verdict.reason, ss_verdict_name(cv.inj.verdict.verdict));
  CHECK(!strcmp(cv.out.route, "Fourier blocks in balls"), "loop 5: route '%s'",
        cv.out.route);
  ss_scheme_free(loop);
  routes();
  /* the exact condition passes but the double path handed no map: the
   * regularity it claims is not proven */
  ss_link *oct = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_link_named("octahedron", &oct, &err), &err);
  const ss_case v = {SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0};
  ss_testcase t;
  if (!ss_testcase_run("mlca", v, &t)) {
    ss_regularity reg = t.r;
    ss_charmap_inj inj = {{SS_PASS, "", 0, SS_ON_NET}, 1, 0};
    ss_certified out;
    const ss_charmap_opts o = ss_charmap_defaults();
    REQUIRE_OK_VOID(ss_certify(t.M, &v, t.e, NULL, &o, &reg, &inj, &out, NULL, &err),
                    &err);
    CHECK(out.cond.verdict == SS_PASS && cond_certified(&out) &&
              reg.verdict.verdict == SS_UNDECIDED && !reg_certified(&reg) &&
              strstr(reg.verdict.reason, "found no characteristic map") &&
              inj.verdict.verdict == SS_UNDECIDED,
          "no map: %s / %s (%s)", ss_verdict_name(out.cond.verdict),
          ss_verdict_name(reg.verdict.verdict), reg.verdict.reason);
    ss_testcase_free(&t);
  }
  ss_link_free(oct);
}

int main(void) {
  test_links();
  test_cases();
  test_unprovable();
  CHECK(by_similarity > 0, "the verified similarity decided none of the cases");
  flint_cleanup(); /* FLINT's caches, for the leak checker */
  return ss_test_done("certify");
}
