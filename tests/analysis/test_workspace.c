/* test_workspace.c — workspaces of the extraction and the eigen-solve (issue
 * 22): cases run one after another through one workspace give exactly what
 * fresh calls give.
 *
 * Properties (every comparison exact, bit for bit: a workspace holds scratch
 * only, so nothing it served before may show in a result):
 *   - ss_local_new_ws through one ss_local_workspace = ss_local_new_opts:
 *     sizes, S, labels, cells and every ring level;
 *   - ss_eig_new_ws through one ss_eig_workspace = ss_eig_new: every
 *     eigenvalue with its bounds, groups, verdict, tolerance, basis and T;
 *   - ss_result_compute_ws = ss_result_compute (all but the time);
 *   over random links of sizes going up and down (so the workspaces both grow
 *   and serve cases smaller than they hold), edges and faces, of MLCA and
 *   tet/oct interleaved in one workspace;
 *   - a workspace too small grows (ss_eig_workspace_size) and never shrinks;
 *   - a call that fails on bad input leaves the workspace usable;
 *   - the timing hook (ss_pipeline_workspace.times) changes no result, and its
 *     stage times are >= 0 and fit in the calls' thread CPU time. */
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "ss_clock.h"
#include "ss_eig.h"
#include "ss_link_random.h"
#include "ss_local.h"
#include "ss_result.h"
#include "ss_scheme.h"
#include "ss_test.h"

static ss_scheme *scheme(const char *name) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  if (ss_scheme_new(name, &s, &err)) fprintf(stderr, "%s\n", err.msg);
  return s;
}

/* Equal bytes of n elements (both NULL with n = 0 counts as equal). */
static int same(const void *a, const void *b, size_t bytes) {
  if (bytes == 0) return 1;
  return a && b && memcmp(a, b, bytes) == 0;
}

static void compare_local(const ss_local *a, const ss_local *b, const char *what) {
  CHECK(a->n2 == b->n2 && a->n1 == b->n1, "%s: sizes %zu/%zu vs %zu/%zu", what, a->n2,
        a->n1, b->n2, b->n1);
  if (a->n2 != b->n2) return;
  CHECK(same(a->S, b->S, a->n2 * a->n2 * sizeof *a->S), "%s: S differs", what);
  CHECK(a->nnz == b->nnz && a->level == b->level && a->ncoord == b->ncoord &&
            a->dim == b->dim && a->cell == b->cell,
        "%s: nnz/level/chart differ", what);
  int lab = 1;
  for (size_t i = 0; i < a->n2; i++)
    lab &= ss_star_coord_cmp(a->label + i, b->label + i) == 0;
  CHECK(lab, "%s: labels differ", what);
  CHECK(a->ncells == b->ncells && a->ncentre == b->ncentre, "%s: cells differ", what);
  if (a->ncells == b->ncells) {
    CHECK(same(a->ctype, b->ctype, a->ncells * sizeof *a->ctype) &&
              same(a->corner, b->corner, a->ncells * SS_MAXCELLVERTS * sizeof *a->corner),
          "%s: cell corners differ", what);
  }
  CHECK(a->nring == b->nring, "%s: ring levels %d vs %d", what, a->nring, b->nring);
  for (int r = 0; r < a->nring && r < b->nring; r++) {
    const ss_local_ring *x = a->ring + r, *y = b->ring + r;
    int ok = x->nv == y->nv && x->nprev == y->nprev && x->ncells == y->ncells;
    if (ok) {
      const size_t nnz = x->ptr[x->nv];
      ok = same(x->ptr, y->ptr, (x->nv + 1) * sizeof *x->ptr) &&
           same(x->col, y->col, nnz * sizeof *x->col) &&
           same(x->w, y->w, nnz * sizeof *x->w) &&
           same(x->ctype, y->ctype, x->ncells * sizeof *x->ctype) &&
           same(x->corner, y->corner, x->ncells * SS_MAXCELLVERTS * sizeof *x->corner);
      for (size_t i = 0; ok && i < x->nv; i++)
        ok = ss_star_coord_cmp(x->coord + i, y->coord + i) == 0;
    }
    CHECK(ok, "%s: ring level %d differs", what, r);
  }
}

/* Two doubles the same bit for bit (NaN equal to itself). */
static int bits(double a, double b) {
  return memcmp(&a, &b, sizeof a) == 0;
}

static void compare_eig(const ss_eig *a, const ss_eig *b, const char *what) {
  CHECK(a->n == b->n, "%s: %zu vs %zu eigenvalues", what, a->n, b->n);
  if (a->n != b->n) return;
  int ok = 1;
  for (size_t i = 0; i < a->n; i++) {
    const ss_eigval *x = a->val + i, *y = b->val + i;
    ok &= bits(x->re, y->re) && bits(x->im, y->im) && bits(x->rcond, y->rcond) &&
          x->block == y->block && x->group == y->group && x->mult == y->mult &&
          bits(x->err, y->err) && bits(x->cluster, y->cluster);
  }
  CHECK(ok, "%s: eigenvalues differ", what);
  CHECK(a->ngroups == b->ngroups && a->nblocks == b->nblocks &&
            a->largest_block == b->largest_block,
        "%s: groups or blocks differ", what);
  CHECK(a->cond.verdict == b->cond.verdict && !strcmp(a->cond.reason, b->cond.reason),
        "%s: verdict %s vs %s", what, ss_verdict_name(a->cond.verdict),
        ss_verdict_name(b->cond.verdict));
  CHECK(bits(a->tol, b->tol) && bits(a->rounding, b->rounding), "%s: tolerance differs",
        what);
  CHECK(!strcmp(a->basis_kind, b->basis_kind) && a->defective == b->defective &&
            !a->basis == !b->basis && !a->T == !b->T,
        "%s: basis kind differs", what);
  const size_t m = (size_t)a->m;
  if (a->basis && b->basis)
    CHECK(same(a->basis, b->basis, a->n * m * sizeof *a->basis) &&
              same(a->T, b->T, m * m * sizeof *a->T),
          "%s: basis differs", what);
}

static void compare_result(const ss_result *a, const ss_result *b, const char *what) {
  int ok = a->kind == b->kind && a->k == b->k && a->valence == b->valence &&
           a->cls == b->cls && !strcmp(a->link, b->link) && a->cells == b->cells &&
           a->two_ring == b->two_ring && a->one_ring == b->one_ring &&
           a->neig == b->neig && a->v.cond.verdict == b->v.cond.verdict &&
           !strcmp(a->v.cond.reason, b->v.cond.reason) && bits(a->tol, b->tol) &&
           a->v.reg.verdict == b->v.reg.verdict &&
           !strcmp(a->v.reg.reason, b->v.reg.reason) &&
           a->v.inj.verdict == b->v.inj.verdict && a->inj_degree == b->inj_degree &&
           bits(a->min_sj, b->min_sj) && a->depth == b->depth &&
           a->ring_levels == b->ring_levels && a->ring_level == b->ring_level &&
           a->centre_corner_folds == b->centre_corner_folds;
  for (int i = 0; ok && i < a->neig; i++)
    ok = bits(a->eig[i].re, b->eig[i].re) && bits(a->eig[i].im, b->eig[i].im) &&
         a->eig[i].mult == b->eig[i].mult;
  CHECK(ok, "%s: results differ", what);
}

/* One case three ways: fresh calls, the shared local and eigen workspaces,
 * and the result pipeline with and without the shared result workspace. */
static void one_case(const ss_scheme *s, const ss_case *c, ss_local_workspace *lw,
                     ss_eig_workspace *ew, ss_pipeline_workspace *rw, const char *what) {
  ss_error err = {0};
  ss_local *M0 = NULL, *M1 = NULL;
  ss_eig *e0 = NULL, *e1 = NULL;
  const ss_local_opts lo = ss_local_defaults();
  if (ss_local_new_opts(s, c, &lo, &M0, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    return;
  }
  if (ss_local_new_ws(s, c, &lo, lw, &M1, &err)) {
    CHECK(0, "%s (workspace): %s", what, err.msg);
    ss_local_free(M0);
    return;
  }
  compare_local(M0, M1, what);
  ss_eig_opts eo = ss_eig_defaults(M0->dim);
  if (ss_eig_new(M0->S, M0->n2, M0->n1, &eo, &e0, &err) == SS_OK &&
      ss_eig_new_ws(M1->S, M1->n2, M1->n1, &eo, ew, &e1, &err) == SS_OK) {
    compare_eig(e0, e1, what);
    size_t n, b;
    ss_eig_workspace_size(ew, &n, &b);
    CHECK(n >= M1->n2 && b >= M1->n1 && b >= e1->largest_block,
          "%s: workspace holds %zu rows, blocks of %zu after a %zu x %zu case", what, n,
          b, M1->n2, M1->n2);
  } else
    CHECK(0, "%s: eig: %s", what, err.msg);
  ss_eig_free(e0);
  ss_eig_free(e1);
  ss_local_free(M0);
  ss_local_free(M1);

  ss_result_opts ro = ss_result_defaults();
  ss_result r0, r1;
  const ss_status s0 = ss_result_compute(s, c, &ro, &r0, &err);
  const ss_status s1 = ss_result_compute_ws(s, c, &ro, rw, &r1, &err);
  CHECK(s0 == SS_OK && s1 == SS_OK, "%s: result: %s", what, err.msg);
  if (s0 == SS_OK && s1 == SS_OK) compare_result(&r0, &r1, what);
  ss_result_clear(&r0);
  ss_result_clear(&r1);
}

int main(void) {
  ss_scheme *mlca = scheme("mlca"), *tetoct = scheme("tetoct");
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  ss_local_workspace *lw = ss_local_workspace_new();
  /* deliberately too small: the first case must make it grow */
  ss_eig_workspace *ew = ss_eig_workspace_new(8);
  ss_pipeline_workspace *rw = ss_pipeline_workspace_new();
  if (!mlca || !tetoct || !rng || !lw || !ew || !rw) {
    fprintf(stderr, "setup failed\n");
    return 1;
  }
  gsl_rng_set(rng, 22);
  size_t n0, b0;
  ss_eig_workspace_size(ew, &n0, &b0);
  CHECK(n0 == 8 && b0 == 8, "a new workspace for 8 rows holds %zu, %zu", n0, b0);

  /* sizes up and down: each case is smaller or larger than the last */
  static const int ks[] = {9, 4, 11, 5, 7, 12, 6, 4, 10, 8};
  const int nk = (int)(sizeof ks / sizeof *ks);
  size_t nmax = 0;
  for (int i = 0; i < nk; i++) {
    ss_link *l = NULL;
    ss_error err = {0};
    if (ss_link_random(ks[i], rng, &l, &err)) {
      CHECK(0, "random link k = %d: %s", ks[i], err.msg);
      continue;
    }
    char what[96];
    /* the two schemes interleaved through the same workspaces */
    const ss_scheme *ss[2] = {i % 2 ? tetoct : mlca, i % 2 ? mlca : tetoct};
    for (int j = 0; j < 2; j++) {
      const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
      snprintf(what, sizeof what, "%s vertex k = %d (case %d)", ss_scheme_name(ss[j]),
               ks[i], i);
      one_case(ss[j], &c, lw, ew, rw, what);
    }
    size_t n, b;
    ss_eig_workspace_size(ew, &n, &b);
    CHECK(n >= nmax, "the workspace shrank from %zu to %zu rows", nmax, n);
    nmax = n;
    ss_link_free(l);
  }
  static const int ns[] = {6, 3, 8, 4};
  for (int i = 0; i < 4; i++) {
    char what[96];
    const ss_case c = {SS_CASE_EDGE, NULL, ns[i], SS_DIAG_BFS, 0};
    snprintf(what, sizeof what, "mlca edge %d", ns[i]);
    one_case(mlca, &c, lw, ew, rw, what);
    snprintf(what, sizeof what, "tetoct edge %d", ns[i]);
    one_case(tetoct, &c, lw, ew, rw, what);
  }
  const ss_case face = {SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0};
  one_case(tetoct, &face, lw, ew, rw, "tetoct face");

  /* bad input leaves the workspace usable: S not block lower triangular */
  {
    double S[9] = {0.5, 0.5, 0.0, 0.25, 0.75, 0.0, 0.0, 0.5, 0.5};
    ss_eig *e = NULL;
    ss_error err = {0};
    ss_eig_opts eo = ss_eig_defaults(3);
    CHECK(ss_eig_new_ws(S, 3, 1, &eo, ew, &e, &err) == SS_EINPUT && !e,
          "a non-triangular S is SS_EINPUT");
    const ss_case c = {SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0};
    one_case(mlca, &c, lw, ew, rw, "mlca edge 5 after a failed call");
  }

  /* the timing hook (ss_pipeline_workspace.times, for bench_pipeline --phases)
   * reads clocks only: the same results bit for bit; every stage's time is
   * >= 0 and together they fit in the thread CPU time around the calls; the
   * cases are counted, and the deeper ring level (ss_charmap_times.deep) at
   * most once per case.  MLCA links k = 10..12 until one needed the deeper
   * level (about 4 in 10 at k = 12 do), at most 12 links. */
  {
    ss_pipeline_times tm;
    memset(&tm, 0, sizeof tm);
    rw->times = &tm;
    long n = 0;
    double cpu = 0.0;
    for (int i = 0; i < 12 && !tm.charmap.deep; i++) {
      ss_link *l = NULL;
      ss_error err = {0};
      if (ss_link_random(10 + i % 3, rng, &l, &err)) continue;
      const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
      ss_result_opts ro = ss_result_defaults();
      ss_result r0, r1;
      const ss_status s0 = ss_result_compute(mlca, &c, &ro, &r0, &err);
      const double t0 = ss_clock_cpu();
      const ss_status s1 = ss_result_compute_ws(mlca, &c, &ro, rw, &r1, &err);
      cpu += ss_clock_cpu() - t0;
      n++;
      CHECK(s0 == SS_OK && s1 == SS_OK, "timed case %d: %s", i, err.msg);
      if (s0 == SS_OK && s1 == SS_OK) compare_result(&r0, &r1, "timed case");
      if (s0 == SS_OK) ss_result_clear(&r0);
      if (s1 == SS_OK) ss_result_clear(&r1);
      ss_link_free(l);
    }
    const ss_charmap_times *ct = &tm.charmap;
    const double st[] = {tm.canon,     tm.extract,   tm.diagonals, tm.eig,
                         ct->map,      ct->jacobian, ct->deepen,   ct->deep_jac,
                         ct->symmetry, ct->injective};
    double sum = 0.0;
    int nonneg = 1;
    for (size_t i = 0; i < sizeof st / sizeof *st; i++) {
      nonneg &= st[i] >= 0.0;
      sum += st[i];
    }
    CHECK(tm.cases == n && ct->deep >= 1 && ct->deep <= n,
          "timed %ld of %ld cases, %ld with the deeper ring level (want >= 1)", tm.cases,
          n, ct->deep);
    CHECK(nonneg && sum <= cpu * (1.0 + 1e-9) + 1e-6 && tm.extract > 0.0 && tm.eig > 0.0,
          "stage times %g s in all, the calls took %g s of thread CPU", sum, cpu);
    rw->times = NULL;
  }

  /* NULL workspaces are the plain calls */
  {
    ss_local *M = NULL;
    ss_error err = {0};
    const ss_case c = {SS_CASE_EDGE, NULL, 3, SS_DIAG_BFS, 0};
    const ss_local_opts lo = ss_local_defaults();
    CHECK(ss_local_new_ws(mlca, &c, &lo, NULL, &M, &err) == SS_OK && M && M->n2 == 95,
          "mlca edge 3 without a workspace: n2 = 30n + 5 = 95");
    ss_local_free(M);
  }

  ss_local_workspace_free(lw);
  ss_eig_workspace_free(ew);
  ss_pipeline_workspace_free(rw);
  gsl_rng_free(rng);
  ss_scheme_free(mlca);
  ss_scheme_free(tetoct);
  return ss_test_done("workspace");
}
