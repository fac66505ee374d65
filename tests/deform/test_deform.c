/* test_deform.c — deformations of embedded points (analysis/deform):
 *   - round trip: a point made from a random cell and random parameters of a
 *     jittered hex grid, a jittered Kuhn tet mesh and that mesh split once
 *     into tets and octahedra is located again, and the interpolant at the
 *     found cell and parameters gives the point back (1e-12);
 *   - affine reproduction: on a regular grid (hex for mlca and ccsolid, the
 *     tet/oct lattice for tetoct) with the control points moved by an affine
 *     map M x + c, every deformed point is M p' + c where p' is the
 *     undeformed image (affine invariance: the rows of every step sum to 1),
 *     and p' is the point x itself in the interior (the schemes reproduce
 *     linear functions on their regular lattice: the tricubic B-spline and
 *     the tet/oct scheme's symmetric averages), to 1e-12 relative; on the
 *     levels path at every level;
 *   - mlca's levels path against the exact limit: the gap to the exact point
 *     is within the printed estimate once the rate has settled, and shrinks
 *     by 1/4 per level at a regular interior point (the largest eigenvalue
 *     of the regular tricubic B-spline whose eigenfunctions the trilinear
 *     interpolant of the control net does not reproduce: the quadratics).
 * Every expected value is computed here from the mathematics (the point
 * itself, the affine map), never from the program's output. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_deform.h"
#include "ss_link.h"
#include "ss_limit.h"
#include "ss_scheme.h"
#include "ss_split.h"
#include "ss_test.h"
#include "ss_testcase.h"
#include "ss_testmesh.h"

static double urand(unsigned long *s) {
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

static double dist3(const double a[3], const double b[3]) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

/* Random parameters inside the reference shape of type t. */
static void random_params(ss_cell_type t, unsigned long *seed, double r[3]) {
  for (;;) {
    for (int a = 0; a < 3; a++)
      r[a] = t == SS_OCT ? 2.0 * urand(seed) - 1.0 : urand(seed);
    const double s1 = fabs(r[0]) + fabs(r[1]) + fabs(r[2]);
    if (t == SS_HEX || s1 <= 1.0) return;
  }
}

static void test_round_trip(const ss_cx *m, const char *what) {
  ss_deform_locator *P = NULL;
  ss_error err = {0};
  CHECK(ss_deform_locator_new(m, &P, &err) == SS_OK, "%s: %s", what, err.msg);
  if (!P) return;
  unsigned long seed = 17;
  int tried = 0, same_cell = 0;
  static const ss_cell_type kinds[3] = {SS_HEX, SS_TET, SS_OCT};
  for (int ki = 0; ki < 3; ki++)
    for (size_t c = 0; c < m->nc[kinds[ki]]; c += 1 + m->nc[kinds[ki]] / 40) {
      ss_deform_loc in = {kinds[ki], c, {0, 0, 0}}, out;
      double x[3], y[3];
      int found;
      random_params(in.type, &seed, in.r);
      ss_deform_interp(m, &in, x);
      ss_deform_locate(P, x, &out, &found);
      CHECK(found, "%s: %s %zu: the point is found in no cell", what,
            ss_cell_name(in.type), c + 1);
      if (!found) continue;
      ss_deform_interp(m, &out, y);
      CHECK(dist3(x, y) <= 1e-12 * (1.0 + fabs(x[0]) + fabs(x[1]) + fabs(x[2])),
            "%s: %s %zu: rebuilt %g %g %g from %g %g %g", what, ss_cell_name(in.type),
            c + 1, y[0], y[1], y[2], x[0], x[1], x[2]);
      if (out.type == in.type && out.cell == in.cell) {
        same_cell++;
        CHECK(dist3(out.r, in.r) <= 1e-10, "%s: parameters %g %g %g, not %g %g %g", what,
              out.r[0], out.r[1], out.r[2], in.r[0], in.r[1], in.r[2]);
      }
      tried++;
    }
  const double far[3] = {1e3, -1e3, 1e3};
  ss_deform_loc out;
  int found = 1;
  ss_deform_locate(P, far, &out, &found);
  CHECK(!found, "%s: a point far outside was found", what);
  printf("%s: %d round trips, %d in the same cell\n", what, tried, same_cell);
  CHECK(tried >= 10 && same_cell >= tried / 2, "%s: %d / %d", what, same_cell, tried);
  ss_deform_locator_free(P);
}

static const double Maff[3][3] = {{1.2, 0.3, -0.1}, {-0.2, 0.9, 0.4}, {0.15, -0.25, 1.1}};
static const double caff[3] = {0.7, -1.3, 2.1};

static void affine(const double x[3], double y[3]) {
  for (int a = 0; a < 3; a++)
    y[a] = caff[a] + Maff[a][0] * x[0] + Maff[a][1] * x[1] + Maff[a][2] * x[2];
}

static ss_cx *moved(const ss_cx *m) {
  ss_cx *c = NULL;
  ss_error err = {0};
  if (ss_cx_copy(m, &c, &err)) return NULL;
  for (size_t v = 0; v < m->nv; v++)
    affine(m->x + 3 * v, c->x + 3 * v);
  return c;
}

/* Points inside the box [lo, hi]^3 located in m; returns how many. */
static size_t interior_points(const ss_cx *m, double lo, double hi, ss_deform_loc *loc,
                              double (*x)[3], size_t want) {
  ss_deform_locator *P = NULL;
  ss_error err = {0};
  if (ss_deform_locator_new(m, &P, &err)) return 0;
  unsigned long seed = 5;
  size_t n = 0;
  for (size_t i = 0; i < 4 * want && n < want; i++) {
    int found;
    for (int a = 0; a < 3; a++)
      x[n][a] = lo + (hi - lo) * urand(&seed);
    ss_deform_locate(P, x[n], &loc[n], &found);
    n += found != 0;
  }
  ss_deform_locator_free(P);
  return n;
}

/* Affine reproduction on base m (points in [lo, hi]^3): exact path (if
 * exact) and levels path (levels). */
static void test_affine(const ss_scheme *s, const ss_cx *m, double lo, double hi,
                        int exact, int levels, const char *what) {
  enum { N = 40 };
  ss_deform_loc loc[N];
  double x[N][3], vb[9 * N][3], vm[9 * N][3];
  unsigned char okb[N], okm[N];
  ss_error err = {0};
  ss_cx *mv = moved(m);
  const size_t n = interior_points(m, lo, hi, loc, x, N);
  CHECK(n == N, "%s: %zu interior points", what, n);
  double worst_lin = 0.0, worst_aff = 0.0;
  if (exact) {
    CHECK(ss_deform_eval_exact(s, m, loc, n, vb, okb, &err) == SS_OK, "%s: %s", what,
          err.msg);
    CHECK(ss_deform_eval_exact(s, mv, loc, n, vm, okm, &err) == SS_OK, "%s: %s", what,
          err.msg);
  } else {
    CHECK(ss_deform_eval_levels(s, m, levels, loc, n, vb, &err) == SS_OK, "%s: %s", what,
          err.msg);
    CHECK(ss_deform_eval_levels(s, mv, levels, loc, n, vm, &err) == SS_OK, "%s: %s", what,
          err.msg);
  }
  const size_t rows = exact ? 1 : (size_t)levels + 1;
  for (size_t l = 0; l < rows; l++)
    for (size_t i = 0; i < n; i++) {
      double y[3];
      const double *pb = vb[l * n + i], *pm = vm[l * n + i];
      affine(pb, y);
      const double scale = 1.0 + fabs(x[i][0]) + fabs(x[i][1]) + fabs(x[i][2]);
      worst_aff =
          fmax(worst_aff, dist3(pm, y) / (scale + fabs(y[0]) + fabs(y[1]) + fabs(y[2])));
      worst_lin = fmax(worst_lin, dist3(pb, x[i]) / scale);
    }
  printf("%s: %zu points, %s: affine image %.2e, linear precision %.2e\n", what, n,
         exact ? "exact" : "levels", worst_aff, worst_lin);
  CHECK(worst_aff <= 1e-12, "%s: deformed point is not M p' + c: %.3e", what, worst_aff);
  CHECK(worst_lin <= 1e-12, "%s: undeformed image is not the point: %.3e", what,
        worst_lin);
  ss_cx_free(mv);
}

/* The tet/oct lattice: one tet split `k` times by the linear tet/oct split
 * (every piece is a cell of the lattice's affine image). */
static ss_cx *tetoct_lattice(int k, double size) {
  ss_cx *c = NULL, *f = NULL;
  ss_split *L = NULL;
  ss_error err = {0};
  const double x[4][3] = {{0, 0, 0}, {size, 0, 0}, {0, size, 0}, {0, 0, size}};
  const ss_idx v[4] = {0, 1, 2, 3};
  if (ss_cx_new(3, &c, &err)) return NULL;
  for (int i = 0; i < 4; i++)
    ss_cx_add_vertex(c, x[i], 0, &err);
  ss_cx_add_cell(c, SS_TET, v, 0, &err);
  for (int i = 0; i < k; i++) {
    if (ss_split_refine(SS_SPLIT_TETOCT, c, &f, &L, &err)) break;
    ss_cx_free(c);
    ss_split_free(L);
    c = f;
  }
  return c;
}

/* mlca's levels path against the exact limit at points of mesh m: per level
 * whether the gap |q_L - exact| is within the estimate (from level 3 on);
 * the ratios of successive gaps of point i into ratio[i] (levels - 1). */
static void levels_vs_exact(const ss_scheme *s, const ss_cx *m, const ss_deform_loc *loc,
                            size_t n, int levels, double (*ratio)[8], const char *what) {
  double(*q)[3] = malloc((size_t)(levels + 1) * n * sizeof *q), ex[64][3];
  unsigned char ok[64];
  ss_error err = {0};
  CHECK(n <= 64 && q, "%s: setup", what);
  if (n > 64 || !q) return;
  CHECK(ss_deform_eval_exact(s, m, loc, n, ex, ok, &err) == SS_OK, "%s: %s", what,
        err.msg);
  CHECK(ss_deform_eval_levels(s, m, levels, loc, n, q, &err) == SS_OK, "%s: %s", what,
        err.msg);
  for (size_t i = 0; i < n; i++) {
    double prev = NAN;
    for (int l = 1; l <= levels; l++) {
      const double gap = dist3(q[(size_t)l * n + i], ex[i]);
      double rate;
      const double est = ss_deform_estimate((const double(*)[3])q + i, n, l, &rate);
      if (l >= 3)
        CHECK(gap <= est, "%s: point %zu level %d: gap %.3e beyond the estimate %.3e",
              what, i, l, gap, est);
      if (l >= 2) ratio[i][l - 2] = gap / prev;
      printf("%s: point %zu level %d gap %.3e estimate %.3e rate %.3f ratio %.4f\n", what,
             i, l, gap, est, rate, gap / prev);
      prev = gap;
    }
  }
  free(q);
}

static void test_levels_exact(const ss_scheme *s) {
  /* a grid vertex (parameters 0: the corner stays the corner at every level,
   * so the gap is the control point's distance to its limit, which shrinks
   * by 1/4 per level on the regular tricubic B-spline, the next eigenvalue
   * 1/8 moving the ratio by a relative 2^-L) and two
   * generic interior points (their parameters in the level-L cell change
   * with L, and so does the interpolation error's factor: the gap shrinks by
   * 1/16 every two levels) of a jittered grid */
  ss_cx *g = tm_hex_grid(5, 5, 5);
  tm_jitter(g, 0.15, 11);
  ss_deform_loc loc[3] = {{SS_HEX, 2 + 5 * (2 + 5 * 2), {0.0, 0.0, 0.0}},
                          {SS_HEX, 2 + 5 * (2 + 5 * 2), {0.3, 0.6, 0.45}},
                          {SS_HEX, 1 + 5 * (2 + 5 * 3), {0.7, 0.2, 0.9}}};
  double ratio[3][8];
  levels_vs_exact(s, g, loc, 3, 4, ratio, "mlca jittered grid");
  for (int l = 2; l <= 4; l++)
    CHECK(fabs(ratio[0][l - 2] - 0.25) <= 0.25 * ldexp(1.0, -l), /* next: 1/8 */
          "grid vertex: gap ratio at level %d %.4f, not 1/4", l, ratio[0][l - 2]);
  for (int i = 1; i < 3; i++) {
    const double two = ratio[i][1] * ratio[i][2]; /* gap_4 / gap_2 */
    CHECK(fabs(sqrt(two) - 0.25) <= 0.02,
          "point %d: gap ratio over levels 2..4 %.4f, not "
          "1/16",
          i, two);
  }
  ss_cx_free(g);
}

/* At the extraordinary vertex of the icosahedron hex star (its centre, the
 * corner 0 of cell 0 at parameters 0, which stays the corner at every
 * level): from level 2 on the two-ring of the centre holds no boundary
 * vertex, so the centre's control point moves by the centre's local
 * subdivision matrix S, and the gap to the exact limit shrinks by the
 * largest |eigenvalue| of S below 1 whose eigenvector is not 0 at the centre.
 * The observed ratio must settle and be the modulus of an eigenvalue of S
 * (computed here by the analysis pipeline, independently of both paths).
 * Here it is 1/4, not lambda1 = 0.629 (x3) or 0.445 (x5): the centre is fixed
 * by the star's icosahedral symmetry, so only eigenvectors invariant under it
 * can be non-zero there, and the first of those has eigenvalue 1/4. */
static void test_levels_extraordinary(const ss_scheme *s) {
  tm_link *l = tm_link_named("icosahedron");
  ss_cx *h = tm_hex_star(l);
  tm_jitter(h, 0.05, 5);
  ss_deform_loc loc[1] = {{SS_HEX, 0, {0.0, 0.0, 0.0}}};
  double ratio[1][8];
  levels_vs_exact(s, h, loc, 1, 5, ratio, "mlca icosahedron vertex");
  ss_link *ico = NULL;
  ss_error err = {0};
  ss_testcase t;
  CHECK(ss_link_parse("icosahedron", &ico, &err) == SS_OK, "%s", err.msg);
  if (ico &&
      !ss_testcase_run("mlca", (ss_case){SS_CASE_VERTEX, ico, 0, SS_DIAG_BFS, 0}, &t)) {
    const double r = ratio[0][3]; /* gap_5 / gap_4 */
    double best = INFINITY, lam = NAN;
    for (size_t i = 1; i < t.e->n; i++) {
      const double m = hypot(t.e->val[i].re, t.e->val[i].im);
      if (fabs(m - r) < best) {
        best = fabs(m - r);
        lam = m;
      }
    }
    printf("icosahedron vertex: ratio %.5f, nearest eigenvalue modulus %.5f\n", r, lam);
    CHECK(fabs(ratio[0][3] - ratio[0][2]) <= 0.02 * r,
          "the ratio has not settled: %.5f %.5f", ratio[0][2], ratio[0][3]);
    CHECK(best <= 0.02 * r, "ratio %.5f is no eigenvalue of S (nearest %.5f)", r, lam);
    ss_testcase_free(&t);
  }
  ss_link_free(ico);
  ss_cx_free(h);
  tm_link_free(l);
}

int main(int argc, char **argv) {
  (void)argc;
  (void)argv;
  ss_error err = {0};
  {
    ss_cx *g = tm_hex_grid(4, 4, 4);
    tm_jitter(g, 0.2, 3);
    test_round_trip(g, "jittered hex grid");
    ss_cx_free(g);
    ss_cx *k = tm_kuhn(3);
    tm_jitter(k, 0.1, 4);
    test_round_trip(k, "jittered Kuhn tets");
    ss_cx *f = NULL;
    ss_split *L = NULL;
    CHECK(ss_split_refine(SS_SPLIT_TETOCT, k, &f, &L, &err) == SS_OK, "%s", err.msg);
    tm_jitter(f, 0.03, 5);
    test_round_trip(f, "jittered tets and octahedra");
    ss_cx_free(f);
    ss_split_free(L);
    ss_cx_free(k);
  }
  static const char *const hexschemes[2] = {"mlca", "ccsolid"};
  for (int i = 0; i < 2; i++) {
    ss_scheme *s = NULL;
    CHECK(ss_scheme_new(hexschemes[i], &s, &err) == SS_OK, "%s", err.msg);
    ss_cx *g = tm_hex_grid(6, 6, 6);
    char what[64];
    snprintf(what, sizeof what, "%s regular grid", hexschemes[i]);
    test_affine(s, g, 2.5, 3.5, 1, 0, what);
    test_affine(s, g, 2.5, 3.5, 0, 3, what);
    if (i == 0) test_levels_exact(s);
    if (i == 0) test_levels_extraordinary(s);
    ss_cx_free(g);
    ss_scheme_free(s);
  }
  {
    ss_scheme *s = NULL;
    CHECK(ss_scheme_new("tetoct", &s, &err) == SS_OK, "%s", err.msg);
    ss_cx *t = tetoct_lattice(4, 16.0);
    test_affine(s, t, 3.5, 4.5, 0, 2, "tetoct lattice");
    ss_cx_free(t);
    ss_scheme_free(s);
  }
  return ss_test_done("deform");
}
