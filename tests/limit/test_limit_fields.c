/* test_limit_fields.c — fields carried by the limit evaluator
 * (ss_limit_new_fields, ss_limit_eval_fields), for every scheme named on the
 * command line, on a jittered grid (regular cells, boundary faces), around
 * an extraordinary edge of valence 3 and at the icosahedron vertex:
 *   - affine fields f = a.x + b (two of them, of very different sizes)
 *     reproduce themselves: the limit value is a.p + b at the limit point p
 *     (relative 1e-12 of |a| |p| + |b|) and the gradient in (u, v, w) is J a
 *     (1e-10 of |J| |a|) -- the rows of every step sum to 1, so this holds
 *     for the exact limit, and any mixing of the columns would break it;
 *   - fields equal to the three coordinates equal the point's coordinates
 *     and Jacobian, bit for bit or within 1e-15 of the patch's size (the
 *     same operations on equal columns), and the point itself is the one
 *     ss_limit_eval gives without fields;
 *   - the reference evaluator (positions refined, fields by the rows of each
 *     step) agrees with the walk to 1e-12;
 *   - refusals: a non-finite field value, fields missing, SS_EINPUT naming
 *     the vertex. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testmesh.h"

/* The affine fields: f_i = a_i . x + b_i. */
static const double fa[2][3] = {{2.0, -3.0, 0.5}, {1e6, 2.5e5, -7e5}};
static const double fb[2] = {1.0, -3e6};

static double norm3(const double v[3]) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* Fields per vertex of m: mode 0 the two affine fields, mode 1 the three
 * coordinates. */
static double *make_fields(const ss_cx *m, int mode, size_t *nf) {
  *nf = mode == 0 ? 2 : 3;
  double *f = malloc(m->nv * *nf * sizeof *f);
  for (size_t v = 0; v < m->nv; v++) {
    const double *x = m->x + v * 3;
    for (size_t i = 0; i < *nf; i++)
      f[v * *nf + i] =
          mode == 0 ? fa[i][0] * x[0] + fa[i][1] * x[1] + fa[i][2] * x[2] + fb[i] : x[i];
  }
  return f;
}

/* The points tried in a cell: inside, near a corner, on the faces u = 0 and
 * w = 0, the corner itself (a fixed point) -- with and without derivatives. */
static const double pts[][3] = {{0.3, 0.6, 0.2},     {0.5, 0.5, 0.5}, {1e-9, 3e-9, 2e-9},
                                {0.0, 0.45, 0.7},    {0.3, 0.7, 0.0}, {0.0, 0.0, 0.0},
                                {0.125, 0.0625, 0.0}};
#define NPTS (sizeof pts / sizeof pts[0])

/* Largest distance between the limit point and the cell's corners: the
 * patch's size for the tolerances. */
static double cell_size(const ss_cx *m, size_t c, const double p[3]) {
  double s = 0.0;
  const ss_idx *v = ss_cx_cell(m, SS_HEX, c);
  for (int k = 0; k < 8; k++) {
    double d[3];
    for (int a = 0; a < 3; a++)
      d[a] = m->x[v[k] * 3 + (size_t)a] - p[a];
    if (norm3(d) > s) s = norm3(d);
  }
  return s;
}

static void test_affine(const ss_scheme *s, const ss_cx *m, const size_t *cells, int nc,
                        const char *what) {
  ss_error err = {0};
  size_t nf;
  double *f = make_fields(m, 0, &nf);
  ss_limit *L = NULL;
  REQUIRE_OK_VOID(ss_limit_new_fields(s, m, nf, f, &L, &err), &err);
  CHECK(ss_limit_nfields(L) == 2, "%s: %zu fields", what, ss_limit_nfields(L));
  int done = 0, refused = 0;
  double worst_v = 0.0, worst_g = 0.0, worst_r = 0.0;
  for (int ci = 0; ci < nc; ci++)
    for (size_t q = 0; q < NPTS; q++)
      for (int der = 0; der < 2; der++) {
        ss_limit_point p, p0, pr;
        double v[2], g[2][3], vr[2], gr[2][3];
        const double *x = pts[q];
        ss_status s0 = ss_limit_eval(L, cells[ci], x[0], x[1], x[2], der, &p0, &err);
        ss_status st =
            ss_limit_eval_fields(L, cells[ci], x[0], x[1], x[2], der, &p, v, g, &err);
        if (s0) {
          /* refused without fields (a Jacobian at an extraordinary vertex):
           * refused with them too */
          CHECK(st == s0,
                "%s: cell %zu (%g, %g, %g) d%d: refused without fields (%d), "
                "not with (%d)",
                what, cells[ci], x[0], x[1], x[2], der, (int)s0, (int)st);
          refused++;
          continue;
        }
        CHECK(st == SS_OK, "%s: cell %zu (%g, %g, %g) d%d: %s", what, cells[ci], x[0],
              x[1], x[2], der, err.msg);
        if (st) continue;
        done++;
        for (int i = 0; i < 2; i++) {
          const double want =
              fa[i][0] * p.p[0] + fa[i][1] * p.p[1] + fa[i][2] * p.p[2] + fb[i];
          const double rel =
              fabs(v[i] - want) / (norm3(fa[i]) * norm3(p.p) + fabs(fb[i]));
          if (rel > worst_v) worst_v = rel;
          CHECK(rel <= 1e-12,
                "%s: cell %zu (%g, %g, %g): field %d = %.17g, a.p + b = %.17g", what,
                cells[ci], x[0], x[1], x[2], i, v[i], want);
          if (!der) continue;
          double jn = 0.0;
          for (int a = 0; a < 3; a++)
            jn = fmax(jn, norm3(p.jac[a]));
          for (int a = 0; a < 3; a++) {
            const double gw =
                p.jac[a][0] * fa[i][0] + p.jac[a][1] * fa[i][1] + p.jac[a][2] * fa[i][2];
            /* J = 0 at a boundary corner: then exactly 0 */
            const double e = fabs(g[i][a] - gw) / fmax(jn * norm3(fa[i]), 1e-300);
            if (e > worst_g) worst_g = e;
            CHECK(e <= 1e-10,
                  "%s: cell %zu (%g, %g, %g): d field %d / dx_%d = %.17g, J a = "
                  "%.17g",
                  what, cells[ci], x[0], x[1], x[2], i, a, g[i][a], gw);
          }
        }
        /* the reference: off the extraordinary vertex and edge only (it
         * never reaches a regular sub-cell there) */
        if (ss_limit_eval_reference_fields(L, cells[ci], x[0], x[1], x[2], der, 60, &pr,
                                           vr, gr, &err))
          continue;
        for (int i = 0; i < 2; i++) {
          const double sc = norm3(fa[i]) * norm3(p.p) + fabs(fb[i]);
          const double e = fabs(vr[i] - v[i]) / sc;
          if (e > worst_r) worst_r = e;
          CHECK(e <= 1e-12,
                "%s: cell %zu (%g, %g, %g): reference field %d %.17g, walk %.17g", what,
                cells[ci], x[0], x[1], x[2], i, vr[i], v[i]);
        }
      }
  printf("%s: affine fields at %d evaluations (%d refused alike): worst value %.2e, "
         "gradient %.2e, reference %.2e\n",
         what, done, refused, worst_v, worst_g, worst_r);
  CHECK(done >= 10, "%s: only %d evaluations", what, done);
  ss_limit_free(L);
  free(f);
}

static void test_coordinates(const ss_scheme *s, const ss_cx *m, const size_t *cells,
                             int nc, const char *what) {
  ss_error err = {0};
  size_t nf;
  double *f = make_fields(m, 1, &nf);
  ss_limit *L = NULL, *L0 = NULL;
  REQUIRE_OK_VOID(ss_limit_new_fields(s, m, nf, f, &L, &err), &err);
  REQUIRE_OK_VOID(ss_limit_new(s, m, &L0, &err), &err);
  int done = 0, exact = 0;
  double worst = 0.0;
  for (int ci = 0; ci < nc; ci++)
    for (size_t q = 0; q < NPTS; q++)
      for (int der = 0; der < 2; der++) {
        ss_limit_point p, p0;
        double v[3], g[3][3];
        const double *x = pts[q];
        if (ss_limit_eval(L0, cells[ci], x[0], x[1], x[2], der, &p0, &err)) continue;
        ss_status st =
            ss_limit_eval_fields(L, cells[ci], x[0], x[1], x[2], der, &p, v, g, &err);
        CHECK(st == SS_OK, "%s: cell %zu (%g, %g, %g) d%d: %s", what, cells[ci], x[0],
              x[1], x[2], der, err.msg);
        if (st) continue;
        done++;
        const double size = cell_size(m, cells[ci], p.p);
        int same = 1;
        for (int d = 0; d < 3; d++) {
          /* the field x_d against the point's x_d; the point against the
           * evaluator without fields */
          double e = fmax(fabs(v[d] - p.p[d]), fabs(p.p[d] - p0.p[d]));
          same &= v[d] == p.p[d] && p.p[d] == p0.p[d];
          for (int a = 0; a < 3 && der; a++) {
            e = fmax(e,
                     fmax(fabs(g[d][a] - p.jac[a][d]), fabs(p.jac[a][d] - p0.jac[a][d])));
            same &= g[d][a] == p.jac[a][d] && p.jac[a][d] == p0.jac[a][d];
          }
          e /= size;
          if (e > worst) worst = e;
          CHECK(e <= 1e-15,
                "%s: cell %zu (%g, %g, %g) d%d: field x%d off by %.3g of the "
                "cell's size",
                what, cells[ci], x[0], x[1], x[2], der, d, e);
        }
        exact += same;
      }
  printf("%s: coordinate fields at %d evaluations, %d bit for bit, worst %.2e\n", what,
         done, exact, worst);
  CHECK(done >= 10, "%s: only %d evaluations", what, done);
  ss_limit_free(L);
  ss_limit_free(L0);
  free(f);
}

static void test_refusals(const ss_scheme *s) {
  ss_cx *g = tm_hex_grid(3, 3, 3);
  ss_error err = {0};
  ss_limit *L = NULL;
  size_t nf;
  double *f = make_fields(g, 0, &nf);
  f[5 * nf + 1] = NAN;
  CHECK(ss_limit_new_fields(s, g, nf, f, &L, &err) == SS_EINPUT && !L &&
            strstr(err.msg, "field 2 of vertex 6 is nan, not a finite number"),
        "NaN field: %s", err.msg);
  f[5 * nf + 1] = INFINITY;
  CHECK(ss_limit_new_fields(s, g, nf, f, &L, &err) == SS_EINPUT && !L &&
            strstr(err.msg, "not a finite number"),
        "infinite field: %s", err.msg);
  CHECK(ss_limit_new_fields(s, g, 2, NULL, &L, &err) == SS_EINPUT && !L &&
            strstr(err.msg, "no values"),
        "fields missing: %s", err.msg);
  /* no fields: ss_limit_eval_fields with f NULL is ss_limit_eval */
  REQUIRE_OK_VOID(ss_limit_new_fields(s, g, 0, NULL, &L, &err), &err);
  CHECK(ss_limit_nfields(L) == 0, "no fields: %zu", ss_limit_nfields(L));
  ss_limit_point a, b;
  REQUIRE_OK_VOID(ss_limit_eval_fields(L, 13, 0.3, 0.2, 0.9, 1, &a, NULL, NULL, &err),
                  &err);
  REQUIRE_OK_VOID(ss_limit_eval(L, 13, 0.3, 0.2, 0.9, 1, &b, &err), &err);
  CHECK(!memcmp(a.p, b.p, sizeof a.p) && !memcmp(a.jac, b.jac, sizeof a.jac),
        "f NULL differs from ss_limit_eval");
  ss_limit_free(L);
  free(f);
  ss_cx_free(g);
}

static void test_scheme(const ss_scheme *s) {
  test_refusals(s);
  {
    ss_cx *g = tm_hex_grid(4, 4, 4);
    tm_jitter(g, 0.1, 9);
    const size_t cells[2] = {0, 1 + 4 * (2 + 4 * 1)};
    test_affine(s, g, cells, 2, "jittered grid");
    test_coordinates(s, g, cells, 2, "jittered grid");
    ss_cx_free(g);
  }
  {
    const int n = 3;
    ss_cx *e = tm_edge_ring(n, 3, 6);
    tm_jitter(e, 0.05, 3);
    const size_t cells[2] = {(size_t)((3 * n + 0) * 3 + 0) * 3 + 0,
                             (size_t)((2 * n + 1) * 3 + 0) * 3 + 0};
    test_affine(s, e, cells, 2, "edge of valence 3");
    test_coordinates(s, e, cells, 2, "edge of valence 3");
    ss_cx_free(e);
  }
  {
    tm_link *l = tm_link_named("icosahedron");
    ss_cx *h = tm_hex_star(l);
    tm_jitter(h, 0.05, 5);
    const size_t cells[2] = {0, 7};
    test_affine(s, h, cells, 2, "icosahedron vertex");
    test_coordinates(s, h, cells, 2, "icosahedron vertex");
    ss_cx_free(h);
    tm_link_free(l);
  }
}

int main(int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    ss_error err = {0};
    ss_scheme *s;
    REQUIRE_OK(ss_scheme_new(argv[i], &s, &err), &err);
    printf("scheme %s\n", argv[i]);
    test_scheme(s);
    ss_scheme_free(s);
  }
  return ss_test_done("limit_fields");
}
