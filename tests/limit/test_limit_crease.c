/* test_limit_crease.c — limit evaluation of boundary and creased cells
 * (issue 36): corners, segments and quadrilaterals on the hexahedra, refined
 * by the scheme's own crease rules.  Four independent checks, per scheme:
 *   - a crease plane of quadrilaterals is refined by the schemes' surface
 *     rules alone (Catmull-Clark's for ccsolid, MLCA's quad averaging for
 *     mlca: on a regular quad grid both are the bicubic B-spline), so on a
 *     face of the plane whose corners are regular the limit is the bicubic
 *     B-spline of the plane's 4 x 4 net, written here from the basis matrix,
 *     with its two derivatives in the plane; a crease chain of segments is
 *     likewise the cubic B-spline of its points;
 *   - the limit at a mesh vertex and at dyadic points is the limit of the
 *     fine vertex under global subdivision (ss_scheme_refine_levels, the
 *     whole mesh, no patches): |fine - limit| falls like 4^-L;
 *   - both schemes' crease rules reproduce linear functions on a box whose
 *     edges are crease segments, corners vertex cells and faces quads, so an
 *     affine image of the grid is its own limit, with the constant Jacobian,
 *     in every cell and on every face, edge and corner;
 *   - the Jacobian against finite differences of limit values, one-sided on
 *     the boundary and on the crease plane;
 *   - the cached walk against the reference (plain steps, no runs).
 * Bad creases (off the hexahedra) are refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testmesh.h"

/* ---- meshes: an n^3 grid (tm_hex_grid) with creases ---- */

static ss_idx gv(int n, int i, int j, int k) {
  return (ss_idx)(i + (n + 1) * (j + (n + 1) * k));
}

static size_t gcell(int n, int i, int j, int k) {
  return (size_t)(i + n * (j + n * k));
}

static void add(ss_cx *cx, ss_cell_type t, const ss_idx *v) {
  ss_error err = {0};
  if (ss_cx_add_cell(cx, t, v, 0, &err)) abort();
}

/* The point of the grid with coordinate c[a] = t along axis a and the other
 * two (p, q) in cyclic order after a. */
static ss_idx gpt(int n, int a, int t, int p, int q) {
  int c[3];
  c[a] = t;
  c[(a + 1) % 3] = p;
  c[(a + 2) % 3] = q;
  return gv(n, c[0], c[1], c[2]);
}

/* Quadrilaterals on the plane x_a = t. */
static void add_plane(ss_cx *cx, int n, int a, int t) {
  for (int p = 0; p < n; p++)
    for (int q = 0; q < n; q++) {
      ss_idx v[4] = {gpt(n, a, t, p, q), gpt(n, a, t, p + 1, q),
                     gpt(n, a, t, p + 1, q + 1), gpt(n, a, t, p, q + 1)};
      add(cx, SS_QUAD, v);
    }
}

/* Segments along axis a from t0 to t1 at (p, q). */
static void add_chain(ss_cx *cx, int n, int a, int p, int q, int t0, int t1) {
  for (int t = t0; t < t1; t++) {
    ss_idx v[2] = {gpt(n, a, t, p, q), gpt(n, a, t + 1, p, q)};
    add(cx, SS_SEGMENT, v);
  }
}

/* The box made sharp: its 12 edges crease chains, its 8 corners vertex
 * cells, its 6 faces quadrilaterals. */
static void add_sharp_box(ss_cx *cx, int n) {
  for (int a = 0; a < 3; a++)
    for (int s = 0; s < 2; s++) {
      add_plane(cx, n, a, s * n);
      for (int r = 0; r < 2; r++)
        add_chain(cx, n, a, s * n, r * n, 0, n);
    }
  for (unsigned b = 0; b < 8; b++) {
    ss_idx v = gv(n, (b & 1u) * n, ((b >> 1) & 1u) * n, ((b >> 2) & 1u) * n);
    add(cx, SS_VERTEX, &v);
  }
}

/* The test mesh: a jittered n^3 grid (n = 4) with the crease plane z = 2, a
 * crease chain inside the volume along x at y = 1, z = 1 ending at x = 3,
 * and a vertex cell at a boundary vertex. */
static ss_cx *creased_grid(void) {
  const int n = 4;
  ss_cx *g = tm_hex_grid(n, n, n);
  add_plane(g, n, 2, 2);
  add_chain(g, n, 0, 1, 1, 0, 3);
  ss_idx c = gv(n, 4, 0, 2);
  add(g, SS_VERTEX, &c);
  tm_jitter(g, 0.12, 11);
  return g;
}

/* ---- independent references ---- */

/* The uniform cubic B-spline basis at t for the points -1, 0, 1, 2 and its
 * derivative, from the basis matrix (1/6) [1 4 1 0; -3 0 3 0; 3 -6 3 0;
 * -1 3 -3 1] in power form. */
static void basis(double t, double b[4], double db[4]) {
  static const double B[4][4] = {
      {1, 4, 1, 0}, {-3, 0, 3, 0}, {3, -6, 3, 0}, {-1, 3, -3, 1}};
  for (int i = 0; i < 4; i++) {
    b[i] = (B[0][i] + t * (B[1][i] + t * (B[2][i] + t * B[3][i]))) / 6.0;
    db[i] = (B[1][i] + t * (2.0 * B[2][i] + 3.0 * t * B[3][i])) / 6.0;
  }
}

static double dist3(const double *a, const double *b) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

/* ---- tests ---- */

/* On the crease plane z = 2: the cells below (w = 1) and above (w = 0) the
 * faces with regular corners give the bicubic B-spline of the plane's net
 * and its u, v derivatives. */
static void test_plane(const ss_scheme *s) {
  const int n = 4;
  ss_error err = {0};
  ss_cx *g = creased_grid();
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  const double uv[][2] = {{0, 0}, {0.5, 0.5}, {0.3, 0.8}, {1, 0.25}, {0.71, 0.02}};
  double worst = 0.0, worstj = 0.0;
  for (int ci = 1; ci <= 2; ci++)
    for (int side = 0; side < 2; side++)
      for (size_t q = 0; q < sizeof uv / sizeof uv[0]; q++) {
        size_t c = gcell(n, ci, 2, side ? 2 : 1);
        double bu[4], du[4], bv[4], dv[4], want[3] = {0}, wj[2][3] = {{0}};
        basis(uv[q][0], bu, du);
        basis(uv[q][1], bv, dv);
        for (int j = 0; j < 4; j++)
          for (int i = 0; i < 4; i++) {
            const double *x = g->x + 3 * (size_t)gv(n, ci - 1 + i, 1 + j, 2);
            for (int d = 0; d < 3; d++) {
              want[d] += bu[i] * bv[j] * x[d];
              wj[0][d] += du[i] * bv[j] * x[d];
              wj[1][d] += bu[i] * dv[j] * x[d];
            }
          }
        ss_limit_point p;
        REQUIRE_OK_VOID(
            ss_limit_eval(L, c, uv[q][0], uv[q][1], side ? 0.0 : 1.0, 1, &p, &err), &err);
        double e = dist3(p.p, want);
        worst = fmax(worst, e);
        CHECK(e <= 1e-13, "cell %zu (%g %g): %g from the bicubic B-spline", c + 1,
              uv[q][0], uv[q][1], e);
        for (int a = 0; a < 2; a++) {
          double ej = dist3(p.jac[a], wj[a]) / fmax(1.0, dist3(wj[a], (double[3]){0}));
          worstj = fmax(worstj, ej);
          CHECK(ej <= 1e-12, "cell %zu (%g %g): d/d%c off by %g", c + 1, uv[q][0],
                uv[q][1], "uv"[a], ej);
        }
      }
  printf("%s crease plane: |limit - bicubic B-spline| %.2e, tangents %.2e\n",
         ss_scheme_name(s), worst, worstj);
  ss_limit_free(L);
  ss_cx_free(g);
}

/* On the crease chain along x at y = z = 1: the cubic B-spline of its points
 * where the segment's ends are inner chain points (x = 1..2). */
static void test_chain(const ss_scheme *s) {
  const int n = 4;
  ss_error err = {0};
  ss_cx *g = creased_grid();
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  const double us[] = {0, 0.25, 0.6, 1};
  double worst = 0.0;
  for (size_t q = 0; q < sizeof us / sizeof us[0]; q++) {
    double b[4], db[4], want[3] = {0};
    basis(us[q], b, db);
    for (int i = 0; i < 4; i++)
      for (int d = 0; d < 3; d++)
        want[d] += b[i] * g->x[3 * (size_t)gv(n, i, 1, 1) + (size_t)d];
    /* the four cells around the chain's segment x in [1, 2] */
    for (int k = 0; k < 2; k++)
      for (int j = 0; j < 2; j++) {
        ss_limit_point p;
        size_t c = gcell(n, 1, j, k);
        REQUIRE_OK_VOID(ss_limit_eval(L, c, us[q], 1.0 - j, 1.0 - k, 0, &p, &err), &err);
        double e = dist3(p.p, want);
        worst = fmax(worst, e);
        CHECK(e <= 1e-13, "cell %zu u = %g: %g from the cubic B-spline", c + 1, us[q], e);
      }
  }
  printf("%s crease chain: |limit - cubic B-spline| %.2e\n", ss_scheme_name(s), worst);
  ss_limit_free(L);
  ss_cx_free(g);
}

/* The fine vertex of fine (g refined lv times) at the dyadic point x of cell
 * c (multiples of 2^-lv): the hex of level lv holding it is c's descendant
 * c 8^lv + ..., the split numbering children by their corner. */
static const double *fine_at(const ss_cx *fine, size_t c, const double x[3], int lv) {
  double y[3] = {x[0], x[1], x[2]};
  for (int l = 0; l < lv; l++) {
    unsigned b = 0;
    for (int a = 0; a < 3; a++)
      if (y[a] > 0.5 || (y[a] == 0.5 && l < lv - 1)) b |= 1u << a;
    for (int a = 0; a < 3; a++)
      y[a] = 2.0 * y[a] - (double)((b >> a) & 1u);
    c = c * 8 + (size_t)ss_cube_corner_index(3, b);
  }
  unsigned corner = 0;
  for (int a = 0; a < 3; a++)
    corner |= (y[a] == 1.0 ? 1u : 0u) << a;
  return fine->x +
         3 * (size_t)ss_cx_cell(fine, SS_HEX, c)[ss_cube_corner_index(3, corner)];
}

/* The limit at every corner of the cells around the creases and at dyadic
 * points against global subdivision: |fine - limit| falls by 1/4 per level
 * (at least by 0.4) and is small at level 4. */
#define LV 4 /* the finest level */
static void test_global(const ss_scheme *s) {
  const int n = 4;
  ss_error err = {0};
  ss_cx *g = creased_grid();
  ss_cx *fine[LV + 1] = {0};
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  for (int l = 2; l <= LV; l++)
    REQUIRE_OK_VOID(ss_scheme_refine_levels(s, g, l, &fine[l], &err), &err);
  const double xs[][3] = {{0, 0, 0},   {1, 1, 1},       {0.5, 0, 1},     {0.25, 0.75, 1},
                          {1, 0.5, 0}, {0.5, 0.5, 0.5}, {0.75, 1, 0.25}, {0, 0.25, 1}};
  double worst[LV + 1] = {0};
  for (int k = 0; k < n; k++)
    for (int j = 0; j < n; j += 3)
      for (int i = 0; i < n; i += 3) {
        size_t c = gcell(n, i, j, k);
        for (size_t q = 0; q < sizeof xs / sizeof xs[0]; q++) {
          ss_limit_point p;
          REQUIRE_OK_VOID(ss_limit_eval(L, c, xs[q][0], xs[q][1], xs[q][2], 0, &p, &err),
                          &err);
          double e[LV + 1];
          for (int l = 2; l <= LV; l++) {
            e[l] = dist3(fine_at(fine[l], c, xs[q], l), p.p);
            worst[l] = fmax(worst[l], e[l]);
          }
          CHECK(e[LV] <= 0.4 * e[LV - 1] + 1e-14 && e[LV - 1] <= 0.4 * e[LV - 2] + 1e-14,
                "cell %zu at (%g %g %g): |fine - limit| %g, %g, %g at levels 2..4", c + 1,
                xs[q][0], xs[q][1], xs[q][2], e[2], e[3], e[4]);
          CHECK(e[LV] <= 4e-3, "cell %zu at (%g %g %g): level %d still %g off", c + 1,
                xs[q][0], xs[q][1], xs[q][2], LV, e[LV]);
        }
      }
  printf("%s creased grid against global subdivision: worst |fine - limit| %.2e, %.2e, "
         "%.2e at levels 2, 3, 4\n",
         ss_scheme_name(s), worst[2], worst[3], worst[4]);
  for (int l = 2; l <= LV; l++)
    ss_cx_free(fine[l]);
  ss_limit_free(L);
  ss_cx_free(g);
}

/* The sharp box's affine image: limit = A x + b, Jacobian rows = A's
 * columns, at every sample of every cell. */
static void test_affine_box(const ss_scheme *s) {
  const int n = 3, N = 5;
  static const double A[3][3] = {{1.1, 0.3, -0.2}, {0.2, 0.9, 0.1}, {-0.3, 0.25, 1.3}};
  static const double b[3] = {0.5, -0.4, 0.3};
  ss_error err = {0};
  ss_cx *g = tm_hex_grid(n, n, n);
  add_sharp_box(g, n);
  for (size_t v = 0; v < g->nv; v++) {
    double y[3], *x = g->x + 3 * v;
    for (int r = 0; r < 3; r++)
      y[r] = A[r][0] * x[0] + A[r][1] * x[1] + A[r][2] * x[2] + b[r];
    memcpy(x, y, sizeof y);
  }
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  double worst = 0.0, worstj = 0.0;
  for (int k = 0; k < n; k++)
    for (int j = 0; j < n; j++)
      for (int i = 0; i < n; i++)
        for (int q = 0; q < N * N * N; q++) {
          double x[3] = {(double)(q % N) / (N - 1), (double)((q / N) % N) / (N - 1),
                         (double)(q / (N * N)) / (N - 1)};
          double X[3] = {i + x[0], j + x[1], k + x[2]}, want[3];
          for (int r = 0; r < 3; r++)
            want[r] = A[r][0] * X[0] + A[r][1] * X[1] + A[r][2] * X[2] + b[r];
          ss_limit_point p;
          size_t c = gcell(n, i, j, k);
          REQUIRE_OK_VOID(ss_limit_eval(L, c, x[0], x[1], x[2], 1, &p, &err), &err);
          double e = dist3(p.p, want), ej = 0.0;
          for (int a = 0; a < 3; a++)
            for (int d = 0; d < 3; d++)
              ej = fmax(ej, fabs(p.jac[a][d] - A[d][a]));
          worst = fmax(worst, e);
          worstj = fmax(worstj, ej);
          CHECK(e <= 1e-13 && ej <= 1e-12,
                "cell %zu at (%g %g %g): point off by %g, Jacobian by %g", c + 1, x[0],
                x[1], x[2], e, ej);
        }
  printf("%s sharp box, affine: point %.2e, Jacobian %.2e\n", ss_scheme_name(s), worst,
         worstj);
  ss_limit_free(L);
  ss_cx_free(g);
}

/* The Jacobian against differences of limit values: central inside the
 * cell, one-sided (second order) on its faces, for cells on the boundary and
 * on both sides of the crease plane. */
static void test_differences(const ss_scheme *s) {
  const int n = 4;
  const double h = 1e-4;
  ss_error err = {0};
  ss_cx *g = creased_grid();
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  const size_t cells[] = {gcell(n, 1, 2, 1), gcell(n, 2, 1, 2), gcell(n, 0, 0, 0),
                          gcell(n, 3, 2, 3), gcell(n, 2, 0, 1)};
  const double xs[][3] = {
      {0.3, 0.6, 1}, {0.7, 0.2, 0}, {0.4, 0.45, 0.55}, {0, 0.35, 0.8}};
  double worst = 0.0;
  for (size_t ci = 0; ci < sizeof cells / sizeof cells[0]; ci++)
    for (size_t q = 0; q < sizeof xs / sizeof xs[0]; q++) {
      ss_limit_point p;
      REQUIRE_OK_VOID(
          ss_limit_eval(L, cells[ci], xs[q][0], xs[q][1], xs[q][2], 1, &p, &err), &err);
      for (int a = 0; a < 3; a++) {
        double fd[3], y[3][3];
        int sgn = xs[q][a] == 1.0 ? -1 : 1, central = xs[q][a] > 0 && xs[q][a] < 1;
        for (int m = 0; m < 3; m++) {
          double x[3] = {xs[q][0], xs[q][1], xs[q][2]};
          x[a] += central ? (m - 1) * h : sgn * m * h;
          ss_limit_point r;
          REQUIRE_OK_VOID(ss_limit_eval(L, cells[ci], x[0], x[1], x[2], 0, &r, &err),
                          &err);
          memcpy(y[m], r.p, sizeof y[m]);
        }
        for (int d = 0; d < 3; d++)
          fd[d] = central ? (y[2][d] - y[0][d]) / (2 * h)
                          : sgn * (-3 * y[0][d] + 4 * y[1][d] - y[2][d]) / (2 * h);
        double e = dist3(fd, p.jac[a]) / fmax(1.0, dist3(p.jac[a], (double[3]){0}));
        worst = fmax(worst, e);
        CHECK(e <= 1e-6, "cell %zu at (%g %g %g): d/dx%d %g from the differences",
              cells[ci] + 1, xs[q][0], xs[q][1], xs[q][2], a, e);
      }
    }
  printf("%s creased grid: Jacobian against differences %.2e\n", ss_scheme_name(s),
         worst);
  ss_limit_free(L);
  ss_cx_free(g);
}

/* The cached walk (stationary runs as eigen-decompositions) against the
 * reference (plain steps of the actual patch), at points near the creases
 * and the boundary: the walk's runs and caches handle crease keys as the
 * plain refinement does. */
static void test_reference(const ss_scheme *s) {
  const int n = 4;
  ss_error err = {0};
  ss_cx *g = creased_grid();
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  const size_t cells[] = {gcell(n, 1, 2, 1), gcell(n, 2, 1, 2), gcell(n, 1, 0, 0),
                          gcell(n, 3, 0, 1)};
  const double xs[][3] = {
      {0.3, 0.6, 0.999}, {0.7, 0.2, 0.001}, {0.01, 0.99, 0.98}, {0.999, 0.003, 0.6}};
  double worst = 0.0;
  for (size_t ci = 0; ci < sizeof cells / sizeof cells[0]; ci++)
    for (size_t q = 0; q < sizeof xs / sizeof xs[0]; q++) {
      ss_limit_point a, b;
      REQUIRE_OK_VOID(
          ss_limit_eval(L, cells[ci], xs[q][0], xs[q][1], xs[q][2], 1, &a, &err), &err);
      REQUIRE_OK_VOID(ss_limit_eval_reference(L, cells[ci], xs[q][0], xs[q][1], xs[q][2],
                                              1, 60, &b, &err),
                      &err);
      double e = dist3(a.p, b.p);
      for (int r = 0; r < 3; r++)
        e = fmax(e,
                 dist3(a.jac[r], b.jac[r]) / fmax(1.0, dist3(b.jac[r], (double[3]){0})));
      worst = fmax(worst, e);
      CHECK(e <= 1e-11, "cell %zu at (%g %g %g): walk and reference differ by %g",
            cells[ci] + 1, xs[q][0], xs[q][1], xs[q][2], e);
    }
  printf("%s creased grid: walk against reference %.2e\n", ss_scheme_name(s), worst);
  ss_limit_free(L);
  ss_cx_free(g);
}

/* A segment across a face (no edge of a hex) and a quad that is no face are
 * refused. */
static void test_refused(const ss_scheme *s) {
  ss_error err = {0};
  ss_limit *L = NULL;
  ss_cx *g = tm_hex_grid(2, 2, 2);
  ss_idx diag[2] = {gv(2, 0, 0, 0), gv(2, 1, 1, 0)};
  add(g, SS_SEGMENT, diag);
  CHECK(ss_limit_new(s, g, &L, &err) == SS_EINPUT && strstr(err.msg, "segment 1"),
        "a diagonal segment: %s", err.msg);
  ss_limit_free(L);
  ss_cx_free(g);
  g = tm_hex_grid(2, 2, 2);
  ss_idx skew[4] = {gv(2, 0, 0, 0), gv(2, 1, 0, 0), gv(2, 1, 1, 1), gv(2, 0, 1, 1)};
  add(g, SS_QUAD, skew);
  L = NULL;
  CHECK(ss_limit_new(s, g, &L, &err) == SS_EINPUT && strstr(err.msg, "quadrilateral 1"),
        "a quad through a hexahedron: %s", err.msg);
  ss_limit_free(L);
  ss_cx_free(g);
}

int main(int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    ss_error err = {0};
    ss_scheme *s;
    REQUIRE_OK(ss_scheme_new(argv[i], &s, &err), &err);
    test_plane(s);
    test_chain(s);
    test_global(s);
    test_affine_box(s);
    test_differences(s);
    test_reference(s);
    test_refused(s);
    ss_scheme_free(s);
  }
  return ss_test_done("limit_crease");
}
