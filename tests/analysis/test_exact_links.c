/* test_exact_links.c — the exact path over every small link and its basis
 * enclosure (split from test_exact.c, which keeps the known spectra, the
 * proofs tolerances cannot give, relabelling and timing):
 *  - the basis enclosure: narrow, S X = X J to rounding, containing the
 *    double-precision basis in its span, exact (rational) where lambda1..m
 *    are rational, and S X = lambda X checked in rationals;
 *  - it agrees with the double path's verdict (a certified pass) on every
 *    MLCA vertex one-ring with k <= 8;
 *  - the double path's rounding error bounds (ss_eig.h, "Rounding floor")
 *    hold against the exact spectrum for every eigenvalue of every MLCA and
 *    tet/oct vertex with k <= 9 and edge of valence 3..10, and a tolerance
 *    below them never turns a certified pass into a fail. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>

#include <flint/flint.h>
#include <flint/fmpq.h>
#include <flint/fmpq_mat.h>

#include "arb.h"

#include "ss_eig.h"
#include "ss_enum.h"
#include "ss_exact.h"
#include "ss_local.h"
#include "ss_test.h"
#include "ss_testcase.h"
#include "ss_testexact.h"

/* ---- the basis ---- */

/* The enclosure of case (M, x) is narrow and an invariant basis; the double
 * basis of ss_eig lies in its span; a rational basis satisfies S X = lambda X
 * exactly. */
static void check_basis(const ss_local *M, const ss_exact *x, const char *what) {
  const size_t n = M->n2;
  const int m = M->dim;
  double *lo = malloc(n * (size_t)m * sizeof *lo),
         *hi = malloc(n * (size_t)m * sizeof *hi),
         *mid = malloc(n * (size_t)m * sizeof *mid);
  ss_error err = {0};
  if (ss_exact_basis(x, lo, hi, &err)) {
    CHECK(0, "%s: basis: %s", what, err.msg);
    goto done;
  }
  /* the enclosures' radii are below 2^-90 of a column's largest entry, so
   * rounded outward to doubles an entry is at most 2 ulp wide, or (an entry
   * that is 0 or nearly) at most 2^-90 of its column */
  double width = 0.0, res = 0.0, tiny = 0.0;
  int ordered = 1;
  for (int j = 0; j < m; j++) {
    double col = 0.0;
    for (size_t i = 0; i < n; i++)
      col = fmax(col, fmax(fabs(lo[j * n + i]), fabs(hi[j * n + i])));
    for (size_t i = j * n; i < (j + 1) * n; i++) {
      ordered &= lo[i] <= hi[i];
      mid[i] = 0.5 * (lo[i] + hi[i]);
      const double a = fmax(fabs(lo[i]), fabs(hi[i]));
      if (a < 0x1p-80 * col) {
        tiny = fmax(tiny, (hi[i] - lo[i]) / col);
        continue;
      }
      width = fmax(width, (hi[i] - lo[i]) / (nextafter(a, INFINITY) - a));
    }
  }
  CHECK(ordered && width <= 2.0 && tiny <= 0x1p-90,
        "%s: intervals up to %g ulp wide, near-zero entries up to %g of their column",
        what, width, tiny);
  for (int j = 0; j < m; j++) {
    const double lj = ss_testexact_lambda(x, j + 1)->re;
    double col = 0.0;
    for (size_t i = 0; i < n; i++)
      col = fmax(col, fabs(mid[j * n + i]));
    for (size_t i = 0; i < n; i++) {
      double s = -lj * mid[j * n + i];
      for (size_t k = 0; k < n; k++)
        s += M->S[i * n + k] * mid[j * n + k];
      res = fmax(res, fabs(s) / col);
    }
  }
  CHECK(res < 1e-13, "%s: |S X - X J| = %g (relative)", what, res);
  /* the double path's basis in the span of the enclosure */
  ss_eig *e = NULL;
  ss_eig_opts eo = ss_eig_defaults(m);
  if (!ss_eig_new(M->S, n, M->n1, &eo, &e, &err) && e->basis) {
    double *a = malloc(n * (size_t)m * sizeof *a), *b = malloc(n * (size_t)m * sizeof *b);
    memcpy(a, mid, n * (size_t)m * sizeof *a);
    memcpy(b, e->basis, n * (size_t)m * sizeof *b);
    double worst = 0.0;
    if (!LAPACKE_dgels(LAPACK_COL_MAJOR, 'N', (lapack_int)n, m, m, a, (lapack_int)n, b,
                       (lapack_int)n)) {
      for (int j = 0; j < m; j++) {
        double r = 0.0, nb = 0.0;
        for (size_t i = (size_t)m; i < n; i++)
          r += b[j * n + i] * b[j * n + i];
        for (size_t i = 0; i < n; i++)
          nb += e->basis[j * n + i] * e->basis[j * n + i];
        worst = fmax(worst, sqrt(r / nb));
      }
    } else {
      worst = INFINITY;
    }
    CHECK(worst < 1e-10, "%s: ss_eig's basis is %g away from the enclosure's span", what,
          worst);
    free(a);
    free(b);
  } else {
    CHECK(0, "%s: ss_eig: %s", what, err.msg);
  }
  ss_eig_free(e);
  /* exact: S X = lambda X in rationals, and the enclosure holds X */
  long long *num = malloc(n * (size_t)m * sizeof *num),
            *den = malloc(n * (size_t)m * sizeof *den);
  int rational = 1;
  for (int j = 1; j <= m; j++)
    rational &= ss_testexact_lambda(x, j)->degree == 1;
  const int got = ss_exact_basis_rational(x, num, den);
  CHECK(!got || rational, "%s: a rational basis for irrational eigenvalues", what);
  if (got) {
    fmpq_t s, t, lam;
    fmpq_init(s);
    fmpq_init(t);
    fmpq_init(lam);
    fmpq_mat_t X;
    fmpq_mat_init(X, (slong)n, m);
    int exact = 1, inside = 1;
    for (int j = 0; j < m; j++)
      for (size_t i = 0; i < n; i++) {
        fmpq_set_si(fmpq_mat_entry(X, i, j), num[j * n + i], (ulong)den[j * n + i]);
        arb_t b;
        arb_init(b);
        arb_set_fmpq(b, fmpq_mat_entry(X, i, j), 128);
        arf_t l, h;
        arf_init(l);
        arf_init(h);
        arf_set_d(l, lo[j * n + i]);
        arf_set_d(h, hi[j * n + i]);
        inside &= arf_cmp(l, arb_midref(b)) <= 0 && arf_cmp(arb_midref(b), h) <= 0;
        arf_clear(l);
        arf_clear(h);
        arb_clear(b);
      }
    for (int j = 0; j < m; j++) {
      long long p, q;
      ss_exact_rational(ss_testexact_lambda(x, j + 1)->re, 1L << 18, &p, &q);
      fmpq_set_si(lam, p, (ulong)q);
      for (size_t i = 0; i < n; i++) {
        fmpq_mul(s, lam, fmpq_mat_entry(X, i, j));
        fmpq_neg(s, s);
        for (size_t k = 0; k < n; k++) {
          long long a, c;
          ss_exact_entry(x, i, k, &a, &c);
          if (!a) continue;
          fmpq_set_si(t, a, (ulong)c);
          fmpq_addmul(s, t, fmpq_mat_entry(X, k, j));
        }
        exact &= fmpq_is_zero(s);
      }
    }
    fmpq_mat_t E;
    fmpq_mat_init(E, (slong)n, m);
    const slong rank = fmpq_mat_rref(E, X);
    CHECK(exact && inside && rank == m,
          "%s: rational basis: S X = X J %s, inside the enclosure %s, rank %ld", what,
          exact ? "exactly" : "fails", inside ? "yes" : "no", (long)rank);
    fmpq_mat_clear(E);
    fmpq_mat_clear(X);
    fmpq_clear(s);
    fmpq_clear(t);
    fmpq_clear(lam);
  }
  free(num);
  free(den);
done:
  free(lo);
  free(hi);
  free(mid);
}

typedef struct {
  ss_scheme *s;
  int count, pass, basis;
} links_ctx;

/* Every MLCA vertex one-ring with k <= 8: certified pass (the double path's
 * verdict too) and the basis checks on the links with k >= 5. */
static int visit(const ss_link *l, void *vctx) {
  links_ctx *ctx = vctx;
  ss_local *M;
  ss_exact *x;
  if (ss_testexact_run(ctx->s, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, &M, &x))
    return 0;
  char what[64];
  snprintf(what, sizeof what, "MLCA vertex k = %d (link %d)", l->k, ctx->count);
  ctx->count++;
  ctx->pass += ss_testexact_verdict_is(x, SS_PASS, 1);
  CHECK(ss_testexact_verdict_is(x, SS_PASS, 1), "%s: %s", what, ss_testexact_reason(x).s);
  if (l->k >= 5) {
    check_basis(M, x, what);
    ctx->basis++;
  }
  ss_exact_free(x);
  ss_local_free(M);
  return 0;
}

static void test_basis(void) {
  links_ctx ctx = {ss_testcase_scheme("mlca"), 0, 0, 0};
  ss_enum_opts eo = {4, 8, 0, 1};
  ss_error err = {0};
  CHECK(ss_enum_links(&eo, visit, &ctx, NULL, &err) == SS_OK, "%s", err.msg);
  CHECK(ctx.count == 23 && ctx.pass == 23 && ctx.basis == 22,
        "MLCA k <= 8: %d of %d certified passes, %d bases", ctx.pass, ctx.count,
        ctx.basis);
  ss_scheme *to = ss_testcase_scheme("tetoct"), *cc = ss_testcase_scheme("catmull-clark");
  ss_link *oct = NULL;
  REQUIRE_OK_VOID(ss_link_named("octahedron", &oct, &err), &err);
  struct {
    ss_scheme *s;
    ss_case c;
    const char *what;
  } cases[5] = {
      {to, {SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0}, "tet/oct vertex (octahedron)"},
      {to, {SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, "tet/oct face"},
      {ctx.s, {SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0}, "MLCA edge 5"},
      {ctx.s, {SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0}, "regular MLCA vertex"},
      {cc, {SS_CASE_SURFACE_VERTEX, NULL, 5, SS_DIAG_BFS, 0}, "Catmull-Clark 5"}};
  for (int i = 0; i < 5; i++) {
    ss_local *M;
    ss_exact *x;
    if (ss_testexact_run(cases[i].s, cases[i].c, &M, &x)) continue;
    check_basis(M, x, cases[i].what);
    long long *num = malloc(M->n2 * 3 * sizeof *num),
              *den = malloc(M->n2 * 3 * sizeof *den);
    int rational = ss_exact_basis_rational(x, num, den);
    CHECK(rational == (i == 0 || i == 1 || i == 3), "%s: rational basis %d",
          cases[i].what, rational);
    free(num);
    free(den);
    ss_exact_free(x);
    ss_local_free(M);
  }
  ss_link_free(oct);
  ss_scheme_free(to);
  ss_scheme_free(cc);
  ss_scheme_free(ctx.s);
}

/* ---- the double path's rounding error bounds ---- */

typedef struct {
  ss_scheme *s;
  int cases, flips, raised;
  size_t checked;
  double worst; /* largest |computed - exact| / bound */
} bound_ctx;

/* One case: every computed eigenvalue lies within its bound of an exact root
 * (the nearest; the root's own enclosure radius is added), and at the
 * tolerances 1e-15 and 1e-16 (below the floor) the verdict is the exact one
 * or undecided, with the tolerance raised to the floor and printed as such. */
static void bound_case(bound_ctx *ctx, ss_case c, const char *what) {
  ss_local *M;
  ss_exact *x;
  if (ss_testexact_run(ctx->s, c, &M, &x)) return;
  ss_error err = {0};
  ss_eig_opts eo = ss_eig_defaults(M->dim);
  eo.basis = 0;
  ss_eig *e = NULL;
  if (ss_eig_new(M->S, M->n2, M->n1, &eo, &e, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    goto done;
  }
  size_t nr;
  const ss_exact_root *r = ss_exact_roots(x, &nr);
  for (size_t i = 0; i < e->n && nr > 0; i++) {
    double best = INFINITY;
    for (size_t k = 0; k < nr; k++)
      best = fmin(best, hypot(e->val[i].re - r[k].re, e->val[i].im - r[k].im) - r[k].rad);
    const double ratio = best / e->val[i].err;
    if (ratio > ctx->worst) ctx->worst = ratio;
    CHECK(best <= e->val[i].err,
          "%s: eigenvalue %zu = %.17g%+.3gi is %.3g from the exact "
          "spectrum, beyond its bound %.3g (rcond %.3g)",
          what, i, e->val[i].re, e->val[i].im, best, e->val[i].err, e->val[i].rcond);
    ctx->checked++;
  }
  CHECK(e->rounding > 0.0 && e->rounding < 1e-9 && e->tol == eo.tol,
        "%s: rounding floor %.3g, tolerance %.3g (the default should stand)", what,
        e->rounding, e->tol);
  ss_verdict exact;
  int cert;
  ss_exact_condition(x, &exact, &cert);
  for (int t = 15; t <= 16; t++) {
    ss_eig *f = NULL;
    eo.tol = pow(10.0, -t);
    if (ss_eig_new(M->S, M->n2, M->n1, &eo, &f, &err)) {
      CHECK(0, "%s, tol 1e-%d: %s", what, t, err.msg);
      continue;
    }
    ctx->raised += f->tol > eo.tol;
    CHECK(f->tol_requested == eo.tol && f->tol == fmax(eo.tol, f->rounding) &&
              f->rounding == e->rounding,
          "%s, tol 1e-%d: requested %.3g, used %.3g, floor %.3g (at 1e-6: %.3g)", what, t,
          f->tol_requested, f->tol, f->rounding, e->rounding);
    const int flip =
        f->cond.verdict != SS_UNDECIDED && cert && f->cond.verdict != exact.verdict;
    ctx->flips += flip;
    CHECK(!flip, "%s, tol 1e-%d: %s (%s), exact: %s", what, t,
          ss_verdict_name(f->cond.verdict), f->cond.reason,
          ss_verdict_name(exact.verdict));
    ss_eig_free(f);
  }
  ctx->cases++;
done:
  ss_eig_free(e);
  ss_exact_free(x);
  ss_local_free(M);
}

static int bound_visit(const ss_link *l, void *vctx) {
  bound_ctx *ctx = vctx;
  char what[96];
  snprintf(what, sizeof what, "%s vertex k = %d (link %d)", ss_scheme_name(ctx->s), l->k,
           ctx->cases);
  bound_case(ctx, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, what);
  return 0;
}

static void test_rounding_bound(void) {
  const char *names[2] = {"mlca", "tetoct"};
  for (int j = 0; j < 2; j++) {
    bound_ctx ctx = {ss_testcase_scheme(names[j]), 0, 0, 0, 0, 0.0};
    ss_enum_opts eo = {4, 9, 0, 1};
    ss_error err = {0};
    CHECK(ss_enum_links(&eo, bound_visit, &ctx, NULL, &err) == SS_OK, "%s", err.msg);
    for (int n = 3; n <= 10; n++) {
      char what[64];
      snprintf(what, sizeof what, "%s edge %d", names[j], n);
      bound_case(&ctx, (ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0}, what);
    }
    /* 1 + 1 + 2 + 5 + 14 + 50 links with k = 4..9, 8 edges */
    CHECK(ctx.cases == 81 && ctx.raised == 2 * 81 && ctx.flips == 0,
          "%s: %d cases, %d raised tolerances, %d flips", names[j], ctx.cases, ctx.raised,
          ctx.flips);
    printf("rounding bounds: %s, %d cases, %zu eigenvalues: largest error / bound %.3f\n",
           names[j], ctx.cases, ctx.checked, ctx.worst);
    ss_scheme_free(ctx.s);
  }
}

int main(void) {
  test_basis();
  test_rounding_bound();
  flint_cleanup();
  return ss_test_done("exact_links");
}
