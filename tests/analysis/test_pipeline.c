/* test_pipeline.c — one case through ss_pipeline: the stages, the case as
 * analysed, what each verdict is judged on, and the pipeline against the
 * results every command reads.
 *
 * Properties (comparisons exact, bit for bit):
 *   - the extraction with the star the pipeline built once (and counted the
 *     diagonals on) gives the S of an extraction that builds its own;
 *   - stages run one at a time (case, matrix, eigen, verdicts, each its own
 *     ss_pipeline_run) give what one ss_pipeline_compute gives: S, every
 *     eigenvalue, every verdict with its reason, certified flag and subject;
 *     a pipeline that recomputed a stage, or kept state between stages that
 *     it should not, fails here;
 *   - relabelled and mirrored links (ss_testlink_scrambled) give the same
 *     bits as the link itself: the case is analysed in canonical form;
 *   - a hex vertex whose link is the bipyramid over 5 is the edge point of
 *     valence 5: its S and verdicts are the edge case's bit for bit, while
 *     the tet/oct split keeps it a vertex (ss_case_edge_point's rule);
 *   - judged on: the condition on the spectrum; a regular link's regularity
 *     and injectivity on the net; psi o sigma = psi (the MLCA link of k = 8
 *     in reports/, README finding 1) on psi itself; no map, no judgement;
 *   - ss_result_of_pipeline = ss_result_compute (the commands' two paths);
 *   - force builds the forced map of a failing condition for pictures and
 *     changes no verdict;
 *   - bad options and cases are refused (SS_EINPUT), a result of a pipeline
 *     that did not reach its verdicts too. */
#include <string.h>

#include "ss_link.h"
#include "ss_pipeline.h"
#include "ss_result.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testlink.h"

static ss_scheme *scheme(const char *name) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  if (ss_scheme_new(name, &s, &err)) fprintf(stderr, "%s\n", err.msg);
  return s;
}

static ss_link *named(const char *name) {
  ss_link *l = NULL;
  ss_error err = {0};
  if (ss_link_named(name, &l, &err) && ss_link_parse(name, &l, &err))
    fprintf(stderr, "%s: %s\n", name, err.msg);
  return l;
}

static int same_verdict(const ss_verdict *a, const ss_verdict *b) {
  return a->verdict == b->verdict && a->certified == b->certified && a->on == b->on &&
         !strcmp(a->reason, b->reason);
}

/* a and b ran through their verdicts: the same matrix, spectrum, verdicts. */
static int same_pipeline(const ss_pipeline *a, const ss_pipeline *b) {
  if (a->M->n2 != b->M->n2 || a->M->n1 != b->M->n1 || a->e->n != b->e->n) return 0;
  if (memcmp(a->M->S, b->M->S, a->M->n2 * a->M->n2 * sizeof *a->M->S)) return 0;
  for (size_t i = 0; i < a->e->n; i++)
    if (memcmp(&a->e->val[i].re, &b->e->val[i].re, sizeof(double)) ||
        memcmp(&a->e->val[i].im, &b->e->val[i].im, sizeof(double)))
      return 0;
  return same_verdict(&a->v.cond, &b->v.cond) && same_verdict(&a->v.reg, &b->v.reg) &&
         same_verdict(&a->v.inj, &b->v.inj) &&
         !memcmp(&a->reg.min_scaled_jacobian, &b->reg.min_scaled_jacobian,
                 sizeof(double));
}

static ss_pipeline *run(const ss_scheme *s, const ss_case *c, const ss_pipeline_opts *o,
                        const char *what) {
  ss_pipeline *p = NULL;
  ss_error err = {0};
  if (ss_pipeline_compute(s, c, o, SS_PIPE_VERDICTS, NULL, &p, &err))
    CHECK(0, "%s: %s", what, err.msg);
  return p;
}

static void stages(const ss_scheme *s, const ss_case *c, int certify, const char *what) {
  ss_pipeline_opts o = ss_pipeline_defaults();
  o.certify = certify;
  ss_pipeline *whole = run(s, c, &o, what), *p = NULL;
  ss_error err = {0};
  ss_pipeline_workspace *w = ss_pipeline_workspace_new();
  int ok = !ss_pipeline_new(s, c, &o, w, &p, &err);
  CHECK(ok && p->done == SS_PIPE_CASE && !p->M, "%s: the case stage alone", what);
  const ss_pipeline_stage next[3] = {SS_PIPE_MATRIX, SS_PIPE_EIGEN, SS_PIPE_VERDICTS};
  for (int i = 0; ok && i < 3; i++) {
    ok = !ss_pipeline_run(p, next[i], w, &err) && p->done == next[i];
    CHECK(ok, "%s: stage %d: %s", what, (int)next[i], err.msg);
    CHECK(!ss_pipeline_run(p, next[i], w, &err) && p->done == next[i],
          "%s: running a stage again is a no-op", what);
  }
  if (ok && whole) CHECK(same_pipeline(p, whole), "%s: staged run differs", what);
  if (ok) { /* the pipeline lends its star to the extraction: the same S as one
               extraction that builds its own */
    ss_local *M = NULL;
    const ss_local_opts lo = ss_local_defaults();
    CHECK(!ss_local_new_opts(s, &p->c.judged, &lo, &M, &err) && M->n2 == p->M->n2 &&
              !memcmp(M->S, p->M->S, M->n2 * M->n2 * sizeof *M->S),
          "%s: S with the pipeline's star differs from S with its own", what);
    ss_local_free(M);
  }
  if (ok && whole) {
    ss_result r0, r1;
    ss_result_opts ro = ss_result_defaults();
    ro.certify = certify;
    const int a = !ss_result_of_pipeline(whole, &ro, &r0, &err);
    const int b = !ss_result_compute(s, c, &ro, &r1, &err);
    CHECK(a && b, "%s: results: %s", what, err.msg);
    if (a && b)
      CHECK(!strcmp(r0.link, r1.link) && r0.kind == r1.kind && r0.k == r1.k &&
                r0.valence == r1.valence && r0.cells == r1.cells &&
                same_verdict(&r0.v.reg, &r1.v.reg) &&
                same_verdict(&r0.v.cond, &r1.v.cond) &&
                same_verdict(&r0.v.inj, &r1.v.inj) &&
                !memcmp(&r0.min_sj, &r1.min_sj, sizeof(double)) &&
                !memcmp(r0.eig, r1.eig, sizeof r0.eig),
            "%s: ss_result_of_pipeline differs from ss_result_compute", what);
    if (a) ss_result_clear(&r0);
    if (b) ss_result_clear(&r1);
  }
  ss_pipeline_free(p);
  ss_pipeline_free(whole);
  ss_pipeline_workspace_free(w);
}

static void relabelled(const ss_scheme *s, const char *link, const char *what) {
  ss_link *l = named(link);
  if (!l) return;
  const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  ss_pipeline *p = run(s, &c, NULL, what);
  for (unsigned seed = 1; p && seed <= 4; seed++) {
    ss_link *m = ss_testlink_scrambled(l, seed, (int)(seed & 1));
    const ss_case cm = {SS_CASE_VERTEX, m, 0, SS_DIAG_BFS, 0};
    ss_pipeline *q = run(s, &cm, NULL, what);
    CHECK(q && same_pipeline(p, q) && !strcmp(p->c.text, q->c.text),
          "%s: relabelling %u%s changes the result", what, seed,
          seed & 1 ? " (mirror)" : "");
    ss_pipeline_free(q);
    ss_link_free(m);
  }
  ss_pipeline_free(p);
  ss_link_free(l);
}

static void edge_point(const ss_scheme *mlca, const ss_scheme *tetoct) {
  ss_link *l = named("bipyramid:5");
  const ss_case v = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  const ss_case e = {SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0};
  ss_pipeline *pv = run(mlca, &v, NULL, "mlca bipyramid:5"),
              *pe = run(mlca, &e, NULL, "mlca edge 5");
  if (pv && pe) {
    CHECK(pv->c.kind == SS_CASE_EDGE_POINT && pv->c.valence == 5 && pv->c.k == 7 &&
              pv->c.cells == 10 && pv->c.judged.kind == SS_CASE_EDGE,
          "the bipyramid over 5 is an edge point of valence 5 (kind %d, n %d, k %d)",
          (int)pv->c.kind, pv->c.valence, pv->c.k);
    CHECK(same_pipeline(pv, pe), "the edge point is not judged as the edge case");
  }
  ss_pipeline *pt = run(tetoct, &v, NULL, "tetoct bipyramid:5");
  CHECK(pt && pt->c.kind == SS_CASE_VERTEX && pt->c.judged.kind == SS_CASE_VERTEX,
        "tet/oct keeps the bipyramid a vertex");
  ss_pipeline_free(pv);
  ss_pipeline_free(pe);
  ss_pipeline_free(pt);
  ss_link_free(l);
}

static void judged_on(const ss_scheme *mlca, const ss_scheme *box) {
  ss_link *reg = named("octahedron");
  /* README finding 1: psi o sigma = psi for a reflection of this link */
  ss_link *sym = named("8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb");
  const ss_case cr = {SS_CASE_VERTEX, reg, 0, SS_DIAG_BFS, 0};
  const ss_case cs = {SS_CASE_VERTEX, sym, 0, SS_DIAG_BFS, 0};
  ss_pipeline_opts cert = ss_pipeline_defaults();
  cert.certify = 1;
  ss_pipeline *p = run(mlca, &cr, &cert, "mlca octahedron");
  if (p)
    CHECK(p->v.cond.on == SS_ON_SPECTRUM && p->v.reg.on == SS_ON_NET &&
              p->v.inj.on == SS_ON_NET && ss_verdicts_combined(&p->v) == SS_PASS &&
              p->v.cond.certified && p->v.reg.certified && !p->v.inj.certified,
          "regular vertex: judged on %s/%s/%s, certified %d%d%d",
          ss_judged_on_name(p->v.cond.on), ss_judged_on_name(p->v.reg.on),
          ss_judged_on_name(p->v.inj.on), p->v.cond.certified, p->v.reg.certified,
          p->v.inj.certified);
  ss_pipeline_free(p);
  p = run(mlca, &cs, NULL, "mlca k = 8 finding");
  if (p)
    CHECK(p->reg.sym.found && p->v.reg.verdict == SS_FAIL && p->v.reg.on == SS_ON_PSI &&
              p->v.inj.on == SS_ON_PSI && !p->v.reg.certified,
          "psi o sigma = psi: a statement about psi (regularity %s on %s)",
          ss_verdict_name(p->v.reg.verdict), ss_judged_on_name(p->v.reg.on));
  ss_pipeline_free(p);
  /* box-spline's octahedral vertex: the eigenvalue condition fails, no map */
  const ss_case cb = {SS_CASE_VERTEX, reg, 0, SS_DIAG_BFS, 0};
  p = run(box, &cb, NULL, "boxspline octahedron");
  ss_pipeline_opts force = ss_pipeline_defaults();
  force.force = 1;
  ss_pipeline *f = run(box, &cb, &force, "boxspline octahedron forced");
  if (p && f) {
    CHECK(p->v.cond.verdict != SS_PASS && !p->cm && p->v.reg.on != SS_ON_NET &&
              p->v.inj.on == SS_ON_NOTHING && p->v.reg.verdict != SS_PASS,
          "no map: regularity %s on %s", ss_verdict_name(p->v.reg.verdict),
          ss_judged_on_name(p->v.reg.on));
    CHECK(f->forced && f->cm && same_verdict(&f->v.reg, &p->v.reg) &&
              same_verdict(&f->v.cond, &p->v.cond),
          "force: a forced map (%d) and the same verdicts", f->forced);
  }
  ss_pipeline_free(p);
  ss_pipeline_free(f);
  ss_link_free(reg);
  ss_link_free(sym);
}

static void refusals(const ss_scheme *s) {
  ss_error err = {0};
  ss_pipeline *p = NULL;
  ss_pipeline_opts o = ss_pipeline_defaults();
  const ss_case e = {SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0};
  o.tol = 0.5;
  CHECK(ss_pipeline_new(s, &e, &o, NULL, &p, &err) == SS_EINPUT && !p, "tol 0.5");
  o = ss_pipeline_defaults();
  o.ring_levels = SS_LOCAL_MAXRING + 1;
  CHECK(ss_pipeline_new(s, &e, &o, NULL, &p, &err) == SS_EINPUT && !p, "ring levels");
  const ss_case v = {SS_CASE_VERTEX, NULL, 0, SS_DIAG_BFS, 0};
  CHECK(ss_pipeline_new(s, &v, NULL, NULL, &p, &err) == SS_EINPUT && !p,
        "a vertex without a link");
  const ss_case f = {SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}; /* MLCA has no face */
  CHECK(ss_pipeline_compute(s, &f, NULL, SS_PIPE_MATRIX, NULL, &p, &err) == SS_EINPUT &&
            !p,
        "the face of a hex scheme");
  if (!ss_pipeline_compute(s, &e, NULL, SS_PIPE_MATRIX, NULL, &p, &err)) {
    ss_result r;
    const ss_result_opts ro = ss_result_defaults();
    CHECK(ss_result_of_pipeline(p, &ro, &r, &err) == SS_EINPUT,
          "a result of a pipeline without verdicts");
    ss_pipeline_free(p);
  }
}

int main(void) {
  ss_scheme *mlca = scheme("mlca"), *tetoct = scheme("tetoct"),
            *box = scheme("boxspline"), *q48 = scheme("quasi48");
  if (!mlca || !tetoct || !box || !q48) return 1;
  const char *links[] = {"tetrahedron", "octahedron", "bipyramid:5", "icosahedron"};
  for (size_t i = 0; i < 4; i++) {
    ss_link *l = named(links[i]);
    const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
    stages(mlca, &c, i == 0, links[i]);
    stages(tetoct, &c, 0, links[i]);
    ss_link_free(l);
  }
  const ss_case edge = {SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0};
  const ss_case face = {SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0};
  const ss_case surf = {SS_CASE_SURFACE_VERTEX, NULL, 5, SS_DIAG_BFS, 0};
  stages(mlca, &edge, 1, "mlca edge 5");
  stages(tetoct, &face, 0, "tetoct face");
  stages(q48, &surf, 0, "quasi48 surface vertex 5");
  relabelled(mlca, "icosahedron", "mlca icosahedron");
  relabelled(tetoct, "5 bcde,aec,abed,ace,adcb", "tetoct k = 5");
  edge_point(mlca, tetoct);
  judged_on(mlca, box);
  refusals(mlca);
  ss_scheme_free(mlca);
  ss_scheme_free(tetoct);
  ss_scheme_free(box);
  ss_scheme_free(q48);
  return ss_test_done("pipeline");
}
