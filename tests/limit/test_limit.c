/* test_limit.c — limit evaluation (ss_limit): the tricubic B-spline on regular
 * grids (from the basis matrix, independently of the library's basis), the
 * decay of |global subdivision L levels - limit| near extraordinary vertices
 * and edges, partition of unity and affine covariance, derivatives against
 * finite differences, the cached walk against the reference, relabelling,
 * bad input. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit.h"
#include "ss_limit_impl.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testmesh.h"

/* ---- meshes ---- */

/* The hex of tm_hex_grid(nx, ny, nz) at (i, j, k). */
static size_t grid_cell(int nx, int ny, int i, int j, int k) {
  return (size_t)(i + nx * (j + ny * k));
}

static void jitter(ss_cx *cx, double amp, unsigned seed) {
  srand(seed);
  for (size_t i = 0; i < cx->nv * 3; i++)
    cx->x[i] += amp * (2.0 * rand() / RAND_MAX - 1.0);
}

/* ---- independent references ---- */

/* Tricubic B-spline of a 4x4x4 net by the basis matrix of the uniform cubic
 * B-spline, (1/6) [1 4 1 0; -3 0 3 0; 3 -6 3 0; -1 3 -3 1], in power form. */
static void bspline_ref(const double (*net)[3], const double x[3], double p[3]) {
  static const double B[4][4] = {
      {1, 4, 1, 0}, {-3, 0, 3, 0}, {3, -6, 3, 0}, {-1, 3, -3, 1}};
  double b[3][4];
  for (int a = 0; a < 3; a++)
    for (int i = 0; i < 4; i++) {
      double t = 1.0;
      b[a][i] = 0.0;
      for (int e = 0; e < 4; e++, t *= x[a])
        b[a][i] += t * B[e][i] / 6.0;
    }
  p[0] = p[1] = p[2] = 0.0;
  for (int k = 0; k < 4; k++)
    for (int j = 0; j < 4; j++)
      for (int i = 0; i < 4; i++)
        for (int d = 0; d < 3; d++)
          p[d] += b[0][i] * b[1][j] * b[2][k] * net[i + 4 * j + 16 * k][d];
}

/* The vertex of `mesh` refined L times at the corner `corner` (bits) of the
 * level-L sub-cell of cell c holding the dyadic point x (each coordinate a
 * multiple of 2^-L): its position converges to the limit at x. */
static int fine_vertex(const ss_scheme *s, const ss_cx *mesh, size_t c, const double x[3],
                       int L, double out[3]) {
  ss_cx *fine;
  ss_error err = {0};
  if (ss_scheme_refine_levels(s, mesh, L, &fine, &err)) {
    fprintf(stderr, "refine: %s\n", err.msg);
    return 1;
  }
  double y[3] = {x[0], x[1], x[2]};
  unsigned corner = 0;
  for (int l = 0; l < L; l++) {
    unsigned b = 0;
    for (int a = 0; a < 3; a++)
      if (y[a] >= 0.5 && !(l == L - 1 && y[a] == 1.0 && 0)) b |= 1u << a;
    /* keep the point at the child's corner 0 unless it is at 1 */
    for (int a = 0; a < 3; a++)
      y[a] = 2.0 * y[a] - ((b >> a) & 1u);
    c = c * 8 + (size_t)ss_cube_corner_index(3, b);
  }
  for (int a = 0; a < 3; a++)
    if (y[a] != 0.0) corner |= 1u << a;
  ss_idx v = ss_cx_cell(fine, SS_HEX, c)[ss_cube_corner_index(3, corner)];
  memcpy(out, fine->x + 3 * (size_t)v, 3 * sizeof(double));
  ss_cx_free(fine);
  return 0;
}

static double dist(const double a[3], const double b[3]) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

/* ---- tests ---- */

static void test_regular(const ss_scheme *s) {
  ss_error err = {0};
  ss_cx *g = tm_hex_grid(5, 5, 5);
  jitter(g, 0.2, 7);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  const double xs[][3] = {
      {0, 0, 0}, {1, 1, 1}, {0.3, 0.7, 0.1}, {0.5, 0.25, 1}, {0.9, 0.01, 0.6}};
  double worst = 0.0;
  for (int ci = 1; ci <= 3; ci++)
    for (size_t q = 0; q < sizeof xs / sizeof xs[0]; q++) {
      size_t c = grid_cell(5, 5, ci, 2, 3 - (ci == 3));
      double net[64][3];
      int cj = 2, ck = 3 - (ci == 3);
      for (int k = 0; k < 4; k++)
        for (int j = 0; j < 4; j++)
          for (int i = 0; i < 4; i++) {
            int vi = ci - 1 + i, vj = cj - 1 + j, vk = ck - 1 + k;
            memcpy(net[i + 4 * j + 16 * k], g->x + 3 * (size_t)(vi + 6 * (vj + 6 * vk)),
                   sizeof net[0]);
          }
      double want[3];
      bspline_ref((const double(*)[3])net, xs[q], want);
      ss_limit_point p;
      REQUIRE_OK_VOID(ss_limit_eval(L, c, xs[q][0], xs[q][1], xs[q][2], 1, &p, &err),
                      &err);
      double e = dist(p.p, want);
      if (e > worst) worst = e;
      CHECK(e <= 1e-12, "regular cell %zu at (%g %g %g): off by %g", c, xs[q][0],
            xs[q][1], xs[q][2], e);
      CHECK(p.products == 0, "a regular cell took %d products", p.products);
    }
  printf("regular grid: largest |limit - tricubic B-spline| = %.2e\n", worst);
  ss_limit_free(L);
  ss_cx_free(g);
}

/* An affine image of a grid is its own limit (linear precision), in every
 * cell, boundary-touching ones included; a constant net gives the constant. */
static void test_affine(const ss_scheme *s) {
  ss_error err = {0};
  ss_cx *g = tm_hex_grid(4, 4, 4);
  const double A[3][3] = {{1.2, 0.3, -0.1}, {0.2, 0.9, 0.4}, {-0.3, 0.1, 1.1}};
  const double b[3] = {0.5, -2, 3};
  for (size_t v = 0; v < g->nv; v++) {
    double y[3];
    for (int i = 0; i < 3; i++) {
      y[i] = b[i];
      for (int j = 0; j < 3; j++)
        y[i] += A[i][j] * g->x[3 * v + (size_t)j];
    }
    memcpy(g->x + 3 * v, y, sizeof y);
  }
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  const size_t c = grid_cell(4, 4, 1, 2, 1); /* interior, regular */
  const double x[3] = {0.3, 0.6, 0.8};
  ss_limit_point p;
  REQUIRE_OK_VOID(ss_limit_eval(L, c, x[0], x[1], x[2], 1, &p, &err), &err);
  for (int i = 0; i < 3; i++) {
    double want = b[i];
    for (int j = 0; j < 3; j++)
      want += A[i][j] * ((j == 0 ? 1 : j == 1 ? 2 : 1) + x[j]);
    CHECK_CLOSE(p.p[i], want, 1e-12, "affine grid coordinate %d", i);
    for (int j = 0; j < 3; j++)
      CHECK_CLOSE(p.jac[j][i], A[i][j], 1e-12, "affine grid Jacobian (%d, %d)", j, i);
  }
  ss_limit_free(L);
  ss_cx_free(g);
}

/* A fixed point at an interior regular vertex: cell (0, 1, 1) of a grid
 * touches the boundary, so its corner (1, 1, 1) is reached through a run
 * and its Jacobian from the run's eigenvalue-1/2 part; cell (1, 1, 1) is
 * regular and has the same point and Jacobian at its corner 0 by the
 * B-spline. */
static void test_fixed_point_jacobian(const ss_scheme *s) {
  ss_error err = {0};
  ss_cx *g = tm_hex_grid(4, 4, 4);
  jitter(g, 0.15, 21);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  ss_limit_point a, b;
  REQUIRE_OK_VOID(ss_limit_eval(L, grid_cell(4, 4, 0, 1, 1), 1, 0, 0, 1, &a, &err), &err);
  REQUIRE_OK_VOID(ss_limit_eval(L, grid_cell(4, 4, 1, 1, 1), 0, 0, 0, 1, &b, &err), &err);
  CHECK(a.products > 0 && b.products == 0, "paths: %d and %d products", a.products,
        b.products);
  CHECK(dist(a.p, b.p) <= 1e-13, "fixed point vs B-spline: %g", dist(a.p, b.p));
  for (int i = 0; i < 3; i++)
    for (int d = 0; d < 3; d++)
      CHECK_CLOSE(a.jac[i][d], b.jac[i][d], 1e-11, "fixed-point Jacobian (%d,%d)", i, d);
  ss_limit_free(L);
  ss_cx_free(g);
}

/* Limit of a mesh whose every point is the same: that point, everywhere;
 * and of an affine image of the mesh: the affine image of the limit. */
static void test_constant(const ss_scheme *s, const ss_cx *m, size_t c,
                          const char *what) {
  ss_error err = {0};
  ss_cx *k;
  if (ss_cx_copy(m, &k, &err)) abort();
  for (size_t v = 0; v < k->nv; v++) {
    k->x[3 * v] = 1.25;
    k->x[3 * v + 1] = -3.5;
    k->x[3 * v + 2] = 7;
  }
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, k, &L, &err), &err);
  const double xs[][3] = {{0.001, 0.002, 0.003}, {0.3, 1e-9, 1e-9}, {0.6, 0.2, 0.9}};
  /* affine covariance: the limit of A X + b is A (limit of X) + b */
  {
    const double A[3][3] = {{0.8, -0.3, 0.2}, {0.1, 1.3, -0.4}, {0.5, 0.2, 0.9}};
    const double b[3] = {-1, 2.5, 0.25};
    ss_cx *y;
    ss_limit *LX, *LY;
    if (ss_cx_copy(m, &y, &err)) abort();
    for (size_t v = 0; v < y->nv; v++)
      for (int i = 0; i < 3; i++) {
        y->x[3 * v + (size_t)i] = b[i];
        for (int j = 0; j < 3; j++)
          y->x[3 * v + (size_t)i] += A[i][j] * m->x[3 * v + (size_t)j];
      }
    REQUIRE_OK_VOID(ss_limit_new(s, m, &LX, &err), &err);
    REQUIRE_OK_VOID(ss_limit_new(s, y, &LY, &err), &err);
    for (int q = 0; q < 3; q++) {
      ss_limit_point px, py;
      REQUIRE_OK_VOID(ss_limit_eval(LX, c, xs[q][0], xs[q][1], xs[q][2], 1, &px, &err),
                      &err);
      REQUIRE_OK_VOID(ss_limit_eval(LY, c, xs[q][0], xs[q][1], xs[q][2], 1, &py, &err),
                      &err);
      for (int i = 0; i < 3; i++) {
        double want = b[i];
        for (int j = 0; j < 3; j++)
          want += A[i][j] * px.p[j];
        CHECK_CLOSE(py.p[i], want, 1e-12, "%s: affine covariance at point %d", what, q);
        for (int r = 0; r < 3; r++) {
          double wj = 0.0;
          for (int j = 0; j < 3; j++)
            wj += A[i][j] * px.jac[r][j];
          CHECK_CLOSE(py.jac[r][i], wj, 1e-10, "%s: affine covariance of J at point %d",
                      what, q);
        }
      }
    }
    ss_limit_free(LX);
    ss_limit_free(LY);
    ss_cx_free(y);
  }
  for (int q = 0; q < 3; q++) {
    ss_limit_point p;
    REQUIRE_OK_VOID(ss_limit_eval(L, c, xs[q][0], xs[q][1], xs[q][2], 0, &p, &err), &err);
    CHECK(fabs(p.p[0] - 1.25) <= 1e-12 && fabs(p.p[1] + 3.5) <= 1e-12 &&
              fabs(p.p[2] - 7) <= 1e-12,
          "%s: partition of unity at point %d: (%.17g %.17g %.17g)", what, q, p.p[0],
          p.p[1], p.p[2]);
  }
  ss_limit_free(L);
  ss_cx_free(k);
}

/* Cached walk against the reference; derivatives against central
 * differences of the limit itself. */
static void test_direct_vs_reference(const ss_scheme *s, const ss_cx *m,
                                     const size_t *cells, int ncells, const char *what) {
  ss_error err = {0};
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, m, &L, &err), &err);
  const double xs[][3] = {{0.01, 0.02, 0.03},   {0.2, 0.1, 0.15},  {0.4, 0.001, 0.0004},
                          {0.7, 0.0001, 0.003}, {0.3, 0.45, 0.05}, {0.125, 0.0625, 0.3},
                          {1e-5, 2e-5, 3e-6},   {0.6, 0.3, 0.2}};
  double worst = 0.0, worst_fd = 0.0;
  for (int ci = 0; ci < ncells; ci++)
    for (size_t q = 0; q < sizeof xs / sizeof xs[0]; q++) {
      ss_limit_point a, r;
      REQUIRE_OK_VOID(
          ss_limit_eval(L, cells[ci], xs[q][0], xs[q][1], xs[q][2], 1, &a, &err), &err);
      REQUIRE_OK_VOID(ss_limit_eval_reference(L, cells[ci], xs[q][0], xs[q][1], xs[q][2],
                                              1, 60, &r, &err),
                      &err);
      double e = dist(a.p, r.p), scale = 1.0;
      if (e > worst) worst = e;
      CHECK(e <= 1e-12 * scale, "%s cell %zu at (%g %g %g): direct - reference = %g",
            what, cells[ci], xs[q][0], xs[q][1], xs[q][2], e);
      for (int i = 0; i < 3; i++)
        for (int d = 0; d < 3; d++) {
          double jr = fabs(r.jac[i][d]) > 1 ? fabs(r.jac[i][d]) : 1;
          CHECK(fabs(a.jac[i][d] - r.jac[i][d]) <= 1e-11 * jr,
                "%s cell %zu: Jacobian (%d,%d) direct %.17g reference %.17g", what,
                cells[ci], i, d, a.jac[i][d], r.jac[i][d]);
        }
      /* central differences with steps well inside the point's sub-cell */
      for (int i = 0; i < 3; i++) {
        double h = 1e-6 * (xs[q][i] > 1e-3 ? 1 : xs[q][i] * 100);
        double xp[3] = {xs[q][0], xs[q][1], xs[q][2]}, xm[3];
        memcpy(xm, xp, sizeof xm);
        xp[i] += h;
        xm[i] -= h;
        ss_limit_point pp, pm;
        REQUIRE_OK_VOID(ss_limit_eval(L, cells[ci], xp[0], xp[1], xp[2], 0, &pp, &err),
                        &err);
        REQUIRE_OK_VOID(ss_limit_eval(L, cells[ci], xm[0], xm[1], xm[2], 0, &pm, &err),
                        &err);
        for (int d = 0; d < 3; d++) {
          double fd = (pp.p[d] - pm.p[d]) / (2 * h);
          double sc = fabs(a.jac[i][d]) > 1 ? fabs(a.jac[i][d]) : 1;
          double e2 = fabs(fd - a.jac[i][d]) / sc;
          if (e2 > worst_fd) worst_fd = e2;
          CHECK(e2 <= 1e-5,
                "%s cell %zu at (%g %g %g): d/dx%d coordinate %d: %.10g vs FD %.10g",
                what, cells[ci], xs[q][0], xs[q][1], xs[q][2], i, d, a.jac[i][d], fd);
        }
      }
    }
  ss_limit_stats st = ss_limit_get_stats(L);
  printf("%s: direct vs reference max %.2e, Jacobian vs central differences max %.2e "
         "(relative); %zu keys, %zu transitions, %zu eigen-solves, %zu factoring edges\n",
         what, worst, worst_fd, st.keys, st.transitions, st.eigs, st.tensor);
  ss_limit_free(L);
}

/* |fine vertex after L global levels - limit| for growing L must fall like
 * C lambda^L; prints the decay. */
static void test_decay(const ss_scheme *s, const ss_cx *m, size_t c, const double x[3],
                       int Lmax, const char *what) {
  ss_error err = {0};
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, m, &L, &err), &err);
  ss_limit_point p;
  REQUIRE_OK_VOID(ss_limit_eval(L, c, x[0], x[1], x[2], 0, &p, &err), &err);
  double prev = 0.0;
  printf("%s: |level-L vertex - limit| at (%g %g %g):", what, x[0], x[1], x[2]);
  for (int l = 1; l <= Lmax; l++) {
    double f[3];
    if (fine_vertex(s, m, c, x, l, f)) {
      CHECK(0, "refine failed");
      break;
    }
    double e = dist(f, p.p);
    printf(" L=%d %.3e", l, e);
    if (l >= 3)
      CHECK(e <= 0.8 * prev, "%s: no decay from level %d to %d: %g -> %g", what, l - 1, l,
            prev, e);
    prev = e;
  }
  printf("\n");
  CHECK(prev < 0.02, "%s: level %d still %g from the limit", what, Lmax, prev);
  ss_limit_free(L);
}

static void test_bad_input(const ss_scheme *s) {
  ss_error err = {0};
  ss_cx *g = tm_hex_grid(3, 3, 3);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, g, &L, &err), &err);
  ss_limit_point p;
  CHECK(ss_limit_eval(L, 27, 0.5, 0.5, 0.5, 0, &p, &err) == SS_EINPUT, "unknown cell");
  CHECK(strstr(err.msg, "cell 28"), "message names the cell: %s", err.msg);
  CHECK(ss_limit_eval(L, 0, 1.5, 0.5, 0.5, 0, &p, &err) == SS_EINPUT, "u > 1");
  CHECK(ss_limit_eval(L, 0, 0.5, -1e-300, 0.5, 0, &p, &err) == SS_EINPUT, "v < 0");
  CHECK(ss_limit_eval(L, 0, 0.5, 0.5, NAN, 0, &p, &err) == SS_EINPUT, "w NaN");
  /* a point on the boundary surface: every double is dyadic, so after its
   * binary digits the point is a corner of a sub-cell, a fixed point of a run;
   * the value is continuous with the interior's, the Jacobian refused */
  ss_limit_point q;
  CHECK(ss_limit_eval(L, 0, 0.3, 0.7, 0.0, 0, &p, &err) == SS_OK, "boundary point: %s",
        err.msg);
  CHECK(ss_limit_eval(L, 0, 0.3, 0.7, ldexp(1, -40), 0, &q, &err) == SS_OK, "near it: %s",
        err.msg);
  CHECK(dist(p.p, q.p) <= 1e-10, "boundary value not continuous: %g", dist(p.p, q.p));
  /* the Jacobian there from the fixed point's eigenvalue-1/2 part, continuous
   * with the interior's */
  CHECK(ss_limit_eval(L, 0, 0.3, 0.7, 0.0, 1, &p, &err) == SS_OK, "boundary Jacobian: %s",
        err.msg);
  CHECK(ss_limit_eval(L, 0, 0.3, 0.7, ldexp(1, -40), 1, &q, &err) == SS_OK, "near it: %s",
        err.msg);
  for (int i = 0; i < 3; i++)
    for (int d = 0; d < 3; d++)
      CHECK(fabs(p.jac[i][d] - q.jac[i][d]) <= 1e-9,
            "boundary Jacobian (%d,%d): %.17g vs %.17g", i, d, p.jac[i][d], q.jac[i][d]);
  ss_limit_free(L);
  ss_cx_free(g);
  /* an averaging scheme whose hex weights are not the tricubic B-spline's:
   * regular cells would be evaluated wrongly, so it is refused up front */
  ss_averaging av = {.split = SS_SPLIT_MULTILINEAR};
  av.accepts[SS_HEX] = 1;
  av.mask[SS_HEX][0] = 1.0 / 8.0 + 0.01;
  av.mask[SS_HEX][1] = av.mask[SS_HEX][2] = 1.0 / 8.0;
  av.mask[SS_HEX][3] = 1.0 / 8.0 - 0.01;
  ss_scheme *bad;
  REQUIRE_OK_VOID(ss_scheme_averaging_new("mutated", &av, &bad, &err), &err);
  g = tm_hex_grid(3, 3, 3);
  CHECK(ss_limit_new(bad, g, &L, &err) == SS_EINPUT && strstr(err.msg, "tricubic"),
        "a scheme that is no B-spline on grids refused: %s", err.msg);
  ss_cx_free(g);
  ss_scheme_free(bad);
  /* two cubes sharing only a vertex (non-manifold there), and three hexes
   * on one face */
  {
    ss_cx *pin;
    if (ss_cx_new(3, &pin, &err)) abort();
    for (int c = 0; c < 2; c++)
      for (int k = 0; k < 8; k++) {
        unsigned b = ss_cube_corner_bits(3, k);
        double x[3] = {(double)(b & 1u), (double)((b >> 1) & 1u),
                       (double)((b >> 2) & 1u)};
        if (c) x[0] = -x[0], x[1] = -x[1], x[2] = -x[2];
        if (!(c && k == 0) && ss_cx_add_vertex(pin, x, 0, &err)) abort();
      }
    ss_idx h0[8] = {0, 1, 2, 3, 4, 5, 6, 7}, h1[8] = {0, 8, 9, 10, 11, 12, 13, 14};
    ss_cx_add_cell(pin, SS_HEX, h0, 0, &err);
    ss_cx_add_cell(pin, SS_HEX, h1, 0, &err);
    REQUIRE_OK_VOID(ss_limit_new(s, pin, &L, &err), &err);
    CHECK(ss_limit_eval(L, 0, 0.5, 0.5, 0.5, 0, &p, &err) == SS_EINPUT &&
              strstr(err.msg, "not connected through faces"),
          "pinched vertex refused: %s", err.msg);
    ss_limit_free(L);
    ss_idx h2[8] = {0, 1, 2, 3, 11, 12, 13, 14}, h3[8] = {0, 1, 2, 3, 8, 9, 10, 4};
    ss_cx_add_cell(pin, SS_HEX, h2, 0, &err);
    ss_cx_add_cell(pin, SS_HEX, h3, 0, &err);
    CHECK(ss_limit_new(s, pin, &L, &err) == SS_EINPUT && strstr(err.msg, "more than two"),
          "a face in three hexahedra refused: %s", err.msg);
    ss_cx_free(pin);
  }
  /* tetrahedra */
  ss_cx *t = tm_kuhn(1);
  ss_cx *t3;
  if (ss_cx_copy(t, &t3, &err)) abort();
  CHECK(ss_limit_new(s, t3, &L, &err) == SS_EINPUT, "tet mesh refused");
  ss_cx_free(t);
  ss_cx_free(t3);
}

/* The same mesh with vertices and cells renumbered: the same limit. */
static void test_relabel(const ss_scheme *s, const ss_cx *m, size_t c) {
  ss_error err = {0};
  ss_cx *r;
  if (ss_cx_new(3, &r, &err)) abort();
  size_t nv = m->nv, nh = m->nc[SS_HEX];
  size_t *pv = malloc(nv * sizeof *pv), *pc = malloc(nh * sizeof *pc);
  for (size_t i = 0; i < nv; i++)
    pv[i] = (i * 37 + 11) % nv;
  for (size_t i = 0; i < nh; i++)
    pc[i] = (i * 13 + 5) % nh;
  /* pv, pc are bijections when gcd(37, nv) = gcd(13, nh) = 1 */
  double *x = malloc(nv * 3 * sizeof *x);
  for (size_t i = 0; i < nv; i++)
    memcpy(x + 3 * pv[i], m->x + 3 * i, 3 * sizeof *x);
  for (size_t i = 0; i < nv; i++)
    ss_cx_add_vertex(r, x + 3 * i, 0, &err);
  ss_idx *cells = malloc(nh * 8 * sizeof *cells);
  for (size_t i = 0; i < nh; i++)
    for (int j = 0; j < 8; j++)
      cells[pc[i] * 8 + (size_t)j] = (ss_idx)pv[ss_cx_cell(m, SS_HEX, i)[j]];
  for (size_t i = 0; i < nh; i++)
    ss_cx_add_cell(r, SS_HEX, cells + 8 * i, 0, &err);
  ss_limit *A, *B;
  REQUIRE_OK_VOID(ss_limit_new(s, m, &A, &err), &err);
  REQUIRE_OK_VOID(ss_limit_new(s, r, &B, &err), &err);
  const double xs[][3] = {{0.01, 0.02, 0.03}, {0.4, 0.001, 0.0004}, {0.3, 0.45, 0.05}};
  for (int q = 0; q < 3; q++) {
    ss_limit_point a, b;
    REQUIRE_OK_VOID(ss_limit_eval(A, c, xs[q][0], xs[q][1], xs[q][2], 0, &a, &err), &err);
    REQUIRE_OK_VOID(ss_limit_eval(B, pc[c], xs[q][0], xs[q][1], xs[q][2], 0, &b, &err),
                    &err);
    CHECK(dist(a.p, b.p) <= 1e-13, "relabelled mesh: point %d differs by %g", q,
          dist(a.p, b.p));
  }
  ss_limit_free(A);
  ss_limit_free(B);
  ss_cx_free(r);
  free(pv);
  free(pc);
  free(x);
  free(cells);
}

/* The same mesh with vertices and cells permuted and every cell's vertex list
 * turned by a random orientation-preserving symmetry (tm_permuted): the same
 * limit at the corresponding parameters, and Jacobian rows permuted and
 * signed accordingly.  Exercises the canonical frames of coarse cells. */
static void test_rotated(const ss_scheme *s, const ss_cx *m, const char *what) {
  ss_error err = {0};
  ss_cx *r = tm_permuted(m, 4242);
  size_t nv = m->nv, nh = m->nc[SS_HEX];
  size_t *old_of = malloc(nv * sizeof *old_of);
  for (size_t i = 0; i < nv; i++) {
    old_of[i] = SIZE_MAX;
    for (size_t j = 0; j < nv && old_of[i] == SIZE_MAX; j++)
      if (!memcmp(r->x + 3 * i, m->x + 3 * j, 3 * sizeof(double))) old_of[i] = j;
  }
  ss_limit *A, *B;
  REQUIRE_OK_VOID(ss_limit_new(s, m, &A, &err), &err);
  REQUIRE_OK_VOID(ss_limit_new(s, r, &B, &err), &err);
  const double xs[][3] = {{0.01, 0.02, 0.03}, {0.4, 0.001, 0.0004}, {0.3, 0.45, 0.95}};
  double worst = 0.0;
  for (size_t cn = 0; cn < nh; cn += 7) {
    const ss_idx *w = ss_cx_cell(r, SS_HEX, cn);
    size_t co = SIZE_MAX;
    int sigma[8];
    for (size_t c = 0; c < nh && co == SIZE_MAX; c++) {
      const ss_idx *v = ss_cx_cell(m, SS_HEX, c);
      int hits = 0;
      for (int i = 0; i < 8; i++)
        for (int k = 0; k < 8; k++)
          if (v[k] == old_of[w[i]]) {
            sigma[i] = k;
            hits++;
          }
      if (hits == 8) co = c;
    }
    CHECK(co != SIZE_MAX, "%s: permuted cell %zu not found", what, cn);
    if (co == SIZE_MAX) continue;
    unsigned b0 = ss_cube_corner_bits(3, sigma[0]);
    int axis[3];
    for (int a = 0; a < 3; a++) {
      unsigned d = ss_cube_corner_bits(3, sigma[ss_cube_corner_index(3, 1u << a)]) ^ b0;
      axis[a] = d == 1u ? 0 : d == 2u ? 1 : 2;
    }
    for (int q = 0; q < 3; q++) {
      double xo[3];
      for (int a = 0; a < 3; a++)
        xo[axis[a]] = (b0 >> axis[a]) & 1u ? 1.0 - xs[q][a] : xs[q][a];
      ss_limit_point pn, po;
      REQUIRE_OK_VOID(ss_limit_eval(B, cn, xs[q][0], xs[q][1], xs[q][2], 1, &pn, &err),
                      &err);
      REQUIRE_OK_VOID(ss_limit_eval(A, co, xo[0], xo[1], xo[2], 1, &po, &err), &err);
      double e = dist(pn.p, po.p);
      if (e > worst) worst = e;
      CHECK(e <= 1e-13, "%s: turned cell %zu (cell %zu) point %d differs by %g", what, cn,
            co, q, e);
      for (int a = 0; a < 3; a++)
        for (int d = 0; d < 3; d++) {
          double sgn = (b0 >> axis[a]) & 1u ? -1.0 : 1.0;
          CHECK_CLOSE(pn.jac[a][d], sgn * po.jac[axis[a]][d], 1e-10,
                      "%s: turned cell %zu Jacobian (%d,%d)", what, cn, a, d);
        }
    }
  }
  printf("%s: turned and renumbered cells: largest difference %.2e\n", what, worst);
  ss_limit_free(A);
  ss_limit_free(B);
  ss_cx_free(r);
  free(old_of);
}

/* More irregular coarse patches than the evaluator keeps transitions for
 * (the disjoint union of edge rings of valence 3..32, each cell at its
 * edge, so every valence has patches of its own): a second pass over
 * every cell, after their transitions were evicted and rebuilt, gives the
 * same points. */
static void test_eviction(const ss_scheme *s) {
  ss_error err = {0};
  ss_cx *u;
  if (ss_cx_new(3, &u, &err)) abort();
  for (int n = 3; n <= 32; n++) {
    ss_cx *e = tm_edge_ring(n, 1, 3);
    jitter(e, 0.05, (unsigned)n);
    ss_idx off = (ss_idx)u->nv;
    for (size_t v = 0; v < e->nv; v++) {
      double x[3] = {e->x[3 * v] + 10.0 * n, e->x[3 * v + 1], e->x[3 * v + 2]};
      if (ss_cx_add_vertex(u, x, 0, &err)) abort();
    }
    for (size_t c = 0; c < e->nc[SS_HEX]; c++) {
      ss_idx w[8];
      for (int i = 0; i < 8; i++)
        w[i] = ss_cx_cell(e, SS_HEX, c)[i] + off;
      if (ss_cx_add_cell(u, SS_HEX, w, 0, &err)) abort();
    }
    ss_cx_free(e);
  }
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, u, &L, &err), &err);
  size_t nc = ss_limit_ncells(L);
  double(*first)[3] = malloc(nc * sizeof *first);
  int same = 1;
  for (int pass = 0; pass < 2; pass++)
    for (size_t c = 0; c < nc; c++) {
      ss_limit_point p;
      REQUIRE_OK_VOID(ss_limit_eval(L, c, 0.3, 0.01, 0.6, 0, &p, &err), &err);
      if (pass == 0)
        memcpy(first[c], p.p, sizeof p.p);
      else if (dist(first[c], p.p) > 0.0)
        same = 0;
    }
  ss_limit_stats st = ss_limit_get_stats(L);
  CHECK(st.keys > 80, "only %zu patch topologies: the ring of 64 is not exercised",
        st.keys);
  CHECK(same, "a second pass after eviction differs");
  printf("eviction: %zu cells, %zu patch topologies, %zu transitions computed over two "
         "passes\n",
         nc, st.keys, st.transitions);
  free(first);
  ss_limit_free(L);
  ss_cx_free(u);
}

/* Neighbouring cells agree on their common face: around the edge of valence
 * n of tm_edge_ring(n, R, nz), cell (s, 0, 0, k) at (0, t, w) is cell
 * (s + 1, 0, 0, k) at (t, 0, w), and at (u, v, 1) cell (s, 0, 0, k + 1) at
 * (u, v, 0). */
static void test_faces(const ss_scheme *s, int n) {
  ss_error err = {0};
  const int R = 3, nz = 6;
  ss_cx *e = tm_edge_ring(n, R, nz);
  jitter(e, 0.05, 17);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, e, &L, &err), &err);
#define CELL(sec, k) ((size_t)((((k)*n + (sec)) * R + 0) * R + 0))
  const double ts[] = {0.3, 1e-7, 0.75, 0.5};
  double worst = 0.0;
  for (int q = 0; q < 4; q++)
    for (int sec = 0; sec < n; sec++) {
      ss_limit_point a, b;
      double w = ts[(q + 1) % 4];
      REQUIRE_OK_VOID(ss_limit_eval(L, CELL(sec, 2), 0, ts[q], w, 0, &a, &err), &err);
      REQUIRE_OK_VOID(ss_limit_eval(L, CELL((sec + 1) % n, 2), ts[q], 0, w, 0, &b, &err),
                      &err);
      double d = dist(a.p, b.p);
      if (d > worst) worst = d;
      CHECK(d <= 1e-13, "valence %d: sectors %d|%d disagree by %g at t = %g", n, sec,
            (sec + 1) % n, d, ts[q]);
      REQUIRE_OK_VOID(ss_limit_eval(L, CELL(sec, 2), ts[q], w, 1, 0, &a, &err), &err);
      REQUIRE_OK_VOID(ss_limit_eval(L, CELL(sec, 3), ts[q], w, 0, 0, &b, &err), &err);
      d = dist(a.p, b.p);
      if (d > worst) worst = d;
      CHECK(d <= 1e-13, "valence %d: layers 2|3 disagree by %g", n, d);
    }
#undef CELL
  printf("edge of valence %d: common faces of neighbouring cells agree to %.1e\n", n,
         worst);
  ss_limit_free(L);
  ss_cx_free(e);
}

/* W^m by the eigen-decomposition against repeated products, for a matrix
 * with a complex pair (0.6 e^(+-0.7i)), the eigenvalue 1 and real ones:
 * the real 2x2 blocks of the pairs must rotate by m theta. */
static void test_eig_power(void) {
  ss_error err = {0};
  enum { K = 5 };
  const double r = 0.6, th = 0.7;
  const double D[K][K] = {{r * cos(th), r * sin(th), 0, 0, 0},
                          {-r * sin(th), r * cos(th), 0, 0, 0},
                          {0, 0, 1, 0, 0},
                          {0, 0, 0, 0.3, 0},
                          {0, 0, 0, 0, -0.2}};
  double T[K][K], Ti[K][K], W[K * K];
  /* T unit lower triangular plus a little: its inverse by substitution */
  for (int i = 0; i < K; i++)
    for (int j = 0; j < K; j++)
      T[i][j] = i == j ? 1.0 : j < i ? 0.3 * (i + 2 * j + 1) / K : 0.0;
  for (int j = 0; j < K; j++)
    for (int i = 0; i < K; i++) {
      double v = i == j ? 1.0 : 0.0;
      for (int q = 0; q < i; q++)
        v -= T[i][q] * Ti[q][j];
      Ti[i][j] = v;
    }
  for (int i = 0; i < K; i++)
    for (int j = 0; j < K; j++) {
      double v = 0.0;
      for (int a = 0; a < K; a++)
        for (int b = 0; b < K; b++)
          v += T[i][a] * D[a][b] * Ti[b][j];
      W[i * K + j] = v;
    }
  ss_lim_eig *e;
  REQUIRE_OK_VOID(ss_lim_eig_new(W, K, &e, &err), &err);
  CHECK(e->ok && !e->pw, "a diagonalisable matrix: %s", e->why);
  int pairs = 0;
  for (int i = 0; i < K; i++)
    pairs += e->pair[i] == 1;
  CHECK(pairs == 1, "one complex pair found, not %d", pairs);
  for (long m = 0; m <= 9; m += 3) {
    double P[K * 3], Q[K * 3];
    for (int i = 0; i < K * 3; i++)
      P[i] = Q[i] = sin(1.0 + i);
    REQUIRE_OK_VOID(ss_lim_eig_power(e, m, 3, P, NULL, NULL, &err), &err);
    for (long step = 0; step < m; step++) {
      double N[K * 3] = {0};
      for (int i = 0; i < K; i++)
        for (int j = 0; j < K; j++)
          for (int d = 0; d < 3; d++)
            N[i * 3 + d] += W[i * K + j] * Q[j * 3 + d];
      memcpy(Q, N, sizeof N);
    }
    for (int i = 0; i < K * 3; i++)
      CHECK_CLOSE(P[i], Q[i], 1e-13, "W^%ld P entry %d", m, i);
  }
  ss_lim_eig_free(e);
}

/* Near and on an extraordinary edge: the paper's eq. (1) (where the edge's
 * halves factor) and the generic digit walk give the same points and
 * Jacobians; MLCA's edges factor (O(1)), Joy--MacCracken's do not (the
 * ccsolid finding: only the rows of points on the edge differ). */
static void test_tensor(const ss_scheme *s, const ss_cx *m, size_t c, const char *what) {
  ss_error err = {0};
  ss_limit *A, *B;
  REQUIRE_OK_VOID(ss_limit_new(s, m, &A, &err), &err);
  REQUIRE_OK_VOID(ss_limit_new(s, m, &B, &err), &err);
  ss_limit_set_tensor(B, 0);
  const double xs[][3] = {{1e-3, 2e-3, 0.3},    {1e-9, 3e-9, 0.7131}, {0.01, 0.02, 0.03},
                          {2e-13, 1e-13, 0.49}, {0.3, 0.2, 0.6},      {0, 0, 0.3}};
  int maxprod = 0;
  for (int q = 0; q < 6; q++) {
    ss_limit_point a, b;
    ss_status sa = ss_limit_eval(A, c, xs[q][0], xs[q][1], xs[q][2], 1, &a, &err);
    ss_status sb = ss_limit_eval(B, c, xs[q][0], xs[q][1], xs[q][2], 1, &b, &err);
    CHECK(sa == sb, "%s: point %d: status %d with eq. (1), %d without", what, q, sa, sb);
    if (sa || sb) {
      REQUIRE_OK_VOID(ss_limit_eval(A, c, xs[q][0], xs[q][1], xs[q][2], 0, &a, &err),
                      &err);
      REQUIRE_OK_VOID(ss_limit_eval(B, c, xs[q][0], xs[q][1], xs[q][2], 0, &b, &err),
                      &err);
    }
    CHECK(dist(a.p, b.p) <= 1e-13, "%s: point %d: eq. (1) and the walk differ by %g",
          what, q, dist(a.p, b.p));
    if (!sa && !sb)
      for (int i = 0; i < 3; i++)
        for (int d = 0; d < 3; d++)
          CHECK_CLOSE(a.jac[i][d], b.jac[i][d], 1e-10, "%s: point %d Jacobian (%d,%d)",
                      what, q, i, d);
    if (a.products > maxprod) maxprod = a.products;
  }
  ss_limit_stats st = ss_limit_get_stats(A);
  if (!strcmp(ss_scheme_name(s), "mlca"))
    CHECK(st.tensor >= 1 && maxprod <= 8,
          "%s: MLCA's edge should factor (eq. (1), constant products): %zu, %d products",
          what, st.tensor, maxprod);
  if (!strcmp(ss_scheme_name(s), "ccsolid"))
    CHECK(st.tensor == 0, "%s: a Joy-MacCracken edge factored", what);
  printf("%s: eq. (1) %s, at most %d products per point\n", what,
         st.tensor ? "applies (the halves factor)"
                   : "does not apply (no factoring halves)",
         maxprod);
  ss_limit_free(A);
  ss_limit_free(B);
}

static void test_scheme(ss_scheme *s) {
  test_regular(s);
  test_eviction(s);
  test_fixed_point_jacobian(s);
  test_affine(s);
  test_bad_input(s);

  /* an edge of valence 3 and 5, interior cells along it */
  for (int n = 3; n <= 5; n += 2) {
    ss_cx *e = tm_edge_ring(n, 3, 6);
    jitter(e, 0.05, 3);
    size_t cells[2] = {(size_t)((3 * n + 0) * 3 + 0) * 3 + 0,
                       (size_t)((2 * n + 1) * 3 + 0) * 3 + 0};
    char what[64];
    snprintf(what, sizeof what, "edge of valence %d", n);
    test_direct_vs_reference(s, e, cells, 2, what);
    test_constant(s, e, cells[0], what);
    const double x[3] = {0.25, 0.125, 0.5}, on[3] = {0, 0, 0.5};
    {
      /* global subdivision to level 4 on a smaller ring: its cell at the
       * edge in layer 2 of 4 */
      ss_cx *e2 = tm_edge_ring(n, 2, 4);
      jitter(e2, 0.05, 3);
      size_t c2 = (size_t)((2 * n + 0) * 2 + 0) * 2 + 0;
      test_decay(s, e2, c2, x, 4, what);
      test_decay(s, e2, c2, on, 4, what); /* on the edge: a fixed point */
      ss_cx_free(e2);
    }
    if (n == 5) test_relabel(s, e, cells[0]);
    if (n == 3) test_rotated(s, e, what);
    test_faces(s, n);
    test_tensor(s, e, cells[0], what);
    ss_cx_free(e);
  }
  /* the vertex with the icosahedron link (every edge at it of valence 5) */
  {
    tm_link *l = tm_link_named("icosahedron");
    ss_cx *h = tm_hex_star(l);
    jitter(h, 0.05, 5); /* no symmetry to make the centre's limit trivially 0 */
    size_t cells[2] = {0, 7};
    test_direct_vs_reference(s, h, cells, 2, "icosahedron vertex");
    test_constant(s, h, 3, "icosahedron vertex");
    const double x[3] = {0.125, 0.0625, 0.1875}, o[3] = {0, 0, 0};
    test_decay(s, h, 0, x, 4, "icosahedron vertex");
    test_decay(s, h, 0, o, 4, "icosahedron vertex"); /* the vertex itself */
    test_relabel(s, h, 0);
    test_rotated(s, h, "icosahedron vertex");
    ss_cx_free(h);
    tm_link_free(l);
  }
  /* boundary cells: a corner cell and a face cell of a grid (the reference
   * reaches regular sub-cells for points off the boundary) */
  {
    ss_cx *g = tm_hex_grid(4, 4, 4);
    jitter(g, 0.1, 9);
    size_t cells[2] = {0, grid_cell(4, 4, 1, 2, 0)};
    test_direct_vs_reference(s, g, cells, 2, "boundary cells of a grid");
    ss_cx_free(g);
  }
}

/* Every scheme named on the command line; a name ending in '?' is skipped
 * when it is not built in (ccsolid, before it lands). */
int main(int argc, char **argv) {
  test_eig_power();
  for (int i = 1; i < argc; i++) {
    char name[64];
    snprintf(name, sizeof name, "%s", argv[i]);
    size_t len = strlen(name);
    int optional = len > 0 && name[len - 1] == '?';
    if (optional) name[len - 1] = '\0';
    ss_error err = {0};
    ss_scheme *s;
    if (ss_scheme_new(name, &s, &err)) {
      if (optional) {
        printf("scheme %s is not built in: skipped\n", name);
        continue;
      }
      REQUIRE_OK(ss_scheme_new(name, &s, &err), &err);
    }
    printf("scheme %s\n", name);
    test_scheme(s);
    ss_scheme_free(s);
  }
  return ss_test_done("limit");
}
