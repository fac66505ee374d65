/* test_mlca.c — MLCA against closed forms: the cubic B-spline on closed
 * polygons, the tensor-product B-spline rules on periodic grids (d = 1, 2, 3),
 * the composite vertex rule of equation (2) of the MLCA paper at extraordinary
 * quad and hex vertices, creases (section 3.2), and invariance under
 * relabelling. */
#include <string.h>

#include "ss_optest.h"
#include "ss_testmesh.h"

static void test_polygon(void) {
  for (int n = 3; n <= 9; n++) {
    ss_cx *cx = tm_polygon(n);
    gsl_spmatrix *R = NULL;
    ss_cx *f = op_refine("mlca", cx, &R);
    CHECK(f->nv == 2 * (size_t)n, "polygon %d: %zu fine vertices", n, f->nv);
    for (int v = 0; v < n; v++) {
      int prev = (v + n - 1) % n, next = (v + 1) % n;
      CHECK_CLOSE(gsl_spmatrix_get(R, (size_t)v, (size_t)v), 0.75, 1e-15, "n=%d v=%d", n,
                  v);
      CHECK_CLOSE(gsl_spmatrix_get(R, (size_t)v, (size_t)prev), 0.125, 1e-15, "n=%d", n);
      CHECK_CLOSE(gsl_spmatrix_get(R, (size_t)v, (size_t)next), 0.125, 1e-15, "n=%d", n);
      CHECK(R->p[v + 1] - R->p[v] == 3, "vertex row has %d entries",
            R->p[v + 1] - R->p[v]);
    }
    for (size_t e = (size_t)n; e < f->nv; e++) {
      CHECK(R->p[e + 1] - R->p[e] == 2, "edge row has %d entries", R->p[e + 1] - R->p[e]);
      for (int q = R->p[e]; q < R->p[e + 1]; q++)
        CHECK_CLOSE(R->data[q], 0.5, 1e-15, "edge point weight");
    }
    check_row_sums(R, "polygon");
    gsl_spmatrix_free(R);
    ss_cx_free(f);
    ss_cx_free(cx);
  }
}

/* Equation (2): for a vertex v of a complex of d-cubes without creases, the
 * weight of u in v's new position is sum over cells C holding u and v of
 * 3^(d - dim_C[u,v]) / (4^d val[v]). */
static void check_equation2(const ss_cx *cx, int d, const char *what) {
  gsl_spmatrix *R = NULL;
  ss_cx *fine = op_refine("mlca", cx, &R);
  ss_cell_type t = d == 2 ? SS_QUAD : SS_HEX;
  const int n = 1 << d;
  double *expect = calloc(cx->nv, sizeof *expect);
  size_t *val = calloc(cx->nv, sizeof *val);
  for (size_t c = 0; c < cx->nc[t] * (size_t)n; c++)
    val[cx->cells[t][c]]++;
  size_t bad = 0, tested = 0;
  for (size_t v = 0; v < cx->nv; v++) {
    if (!val[v]) continue;
    memset(expect, 0, cx->nv * sizeof *expect);
    for (size_t c = 0; c < cx->nc[t]; c++) {
      const ss_idx *cv = ss_cx_cell(cx, t, c);
      for (int i = 0; i < n; i++) {
        if (cv[i] != v) continue;
        for (int j = 0; j < n; j++) {
          int dimuv = ss_cell_role(t, i, j);
          expect[cv[j]] += pow(3.0, d - dimuv) / (pow(4.0, d) * (double)val[v]);
        }
      }
    }
    /* the weight of v itself is always (3/4)^d (the paper's remark) */
    CHECK_CLOSE(expect[v], pow(0.75, d), 1e-15, "%s: eq. (2) self weight", what);
    for (size_t u = 0; u < cx->nv; u++) {
      double got = gsl_spmatrix_get(R, v, u);
      if (fabs(got - expect[u]) > 1e-15) {
        if (bad < 5)
          fprintf(stderr,
                  "%s: vertex %zu (val %zu), weight of %zu: %.17g, eq. (2) %.17g\n", what,
                  v, val[v], u, got, expect[u]);
        bad++;
      }
    }
    tested++;
  }
  CHECK(bad == 0 && tested == cx->nv,
        "%s: %zu weights differ from equation (2) (%zu of %zu "
        "vertices tested)",
        what, bad, tested, cx->nv);
  check_row_sums(R, what);
  free(expect);
  free(val);
  gsl_spmatrix_free(R);
  ss_cx_free(fine);
}

static void test_equation2(void) {
  /* quad surfaces whose link vertices keep their degree as valence: the
   * bipyramid poles give valences 3, 5, 6; the other vertices 3 and 4 */
  const char *surfaces[] = {"bipyramid:3", "bipyramid:5", "bipyramid:6", "icosahedron",
                            "tetrahedron"};
  for (size_t i = 0; i < sizeof surfaces / sizeof *surfaces; i++) {
    tm_link *l = tm_link_named(surfaces[i]);
    ss_cx *q = tm_link_quads(l);
    char what[64];
    snprintf(what, sizeof what, "quad surface of %s", surfaces[i]);
    check_equation2(q, 2, what);
    ss_cx_free(q);
    tm_link_free(l);
  }
  /* hex stars: the centre has the link as its one-ring topology */
  const char *links[] = {"tetrahedron", "bipyramid:3", "octahedron",
                         "bipyramid:5", "bipyramid:7", "icosahedron"};
  for (size_t i = 0; i < sizeof links / sizeof *links; i++) {
    tm_link *l = tm_link_named(links[i]);
    ss_cx *h = tm_hex_star(l);
    CHECK(h->nv == (size_t)(6 * l->k - 9), "hex star of %s: %zu vertices, 6k-9 = %d",
          links[i], h->nv, 6 * l->k - 9);
    char what[64];
    snprintf(what, sizeof what, "hex star of %s", links[i]);
    check_equation2(h, 3, what);
    ss_cx_free(h);
    tm_link_free(l);
  }
}

static ss_cx *patch3x3(int with_creases) {
  ss_cx *cx = NULL;
  ss_error err = {0};
  ss_cx_new(2, &cx, &err);
  for (int v = 0; v < 9; v++) {
    double x[2] = {(double)(v % 3), (double)(2 - v / 3)};
    x[0] += 0.1 * (v == 4); /* a little asymmetry so nothing holds by accident */
    ss_cx_add_vertex(cx, x, 0, &err);
  }
  /* the paper's numbering 1..9 row by row */
  const ss_idx quads[4][4] = {{1, 2, 5, 4}, {4, 5, 8, 7}, {2, 3, 6, 5}, {5, 6, 9, 8}};
  const ss_idx segs[8][2] = {{1, 4}, {4, 7}, {1, 2}, {2, 3},
                             {3, 6}, {6, 9}, {7, 8}, {8, 9}};
  const ss_idx corners[4] = {1, 3, 7, 9};
  if (with_creases != 2)
    for (int i = 0; i < 4; i++) {
      ss_idx q[4] = {quads[i][0] - 1, quads[i][1] - 1, quads[i][2] - 1, quads[i][3] - 1};
      ss_cx_add_cell(cx, SS_QUAD, q, 0, &err);
    }
  if (with_creases) {
    for (int i = 0; i < 8; i++) {
      ss_idx s[2] = {segs[i][0] - 1, segs[i][1] - 1};
      ss_cx_add_cell(cx, SS_SEGMENT, s, 0, &err);
    }
    for (int i = 0; i < 4; i++) {
      ss_idx c = corners[i] - 1;
      ss_cx_add_cell(cx, SS_VERTEX, &c, 0, &err);
    }
  }
  return cx;
}

/* Find a vertex of b at the position of vertex i of a. */
static int has_position(const ss_cx *b, const double *x, double tol) {
  for (size_t j = 0; j < b->nv; j++) {
    const double *y = b->x + j * (size_t)b->dim;
    int same = 1;
    for (int r = 0; r < b->dim; r++)
      same &= fabs(x[r] - y[r]) <= tol;
    if (same) return 1;
  }
  return 0;
}

static void test_creases(void) {
  /* one level: exact rows on the boundary of the 3x3 patch */
  ss_cx *p = patch3x3(1);
  gsl_spmatrix *R = NULL;
  ss_cx *f = op_refine("mlca", p, &R);
  const int corner[4] = {0, 2, 6, 8};
  for (int i = 0; i < 4; i++) {
    size_t v = (size_t)corner[i];
    CHECK(R->p[v + 1] - R->p[v] == 1 && gsl_spmatrix_get(R, v, v) == 1.0,
          "corner %zu is not interpolated", v + 1);
  }
  /* boundary vertex 2 between corners 1 and 3 */
  CHECK(R->p[2] - R->p[1] == 3, "crease vertex row has %d entries", R->p[2] - R->p[1]);
  CHECK_CLOSE(gsl_spmatrix_get(R, 1, 1), 0.75, 1e-15, "crease vertex");
  CHECK_CLOSE(gsl_spmatrix_get(R, 1, 0), 0.125, 1e-15, "crease vertex");
  CHECK_CLOSE(gsl_spmatrix_get(R, 1, 2), 0.125, 1e-15, "crease vertex");
  /* the interior vertex 5 gets the regular bicubic rule: 9/16, 3/32, 1/64 */
  CHECK_CLOSE(gsl_spmatrix_get(R, 4, 4), 9.0 / 16.0, 1e-15, "interior vertex");
  CHECK_CLOSE(gsl_spmatrix_get(R, 4, 1), 3.0 / 32.0, 1e-15, "interior vertex");
  CHECK_CLOSE(gsl_spmatrix_get(R, 4, 0), 1.0 / 64.0, 1e-15, "interior vertex");
  check_row_sums(R, "3x3 patch");
  gsl_spmatrix_free(R);
  ss_cx_free(f);

  /* three levels: the boundary of the patch is the cubic B-spline curve of its
   * boundary polygon (same subdivision of the curve alone), corners fixed */
  ss_scheme *s = NULL;
  ss_error err = {0};
  ss_cx *surf = NULL, *curve = NULL, *c0 = patch3x3(2);
  REQUIRE_OK_VOID(ss_scheme_new("mlca", &s, &err), &err);
  REQUIRE_OK_VOID(ss_scheme_refine_levels(s, p, 3, &surf, &err), &err);
  REQUIRE_OK_VOID(ss_scheme_refine_levels(s, c0, 3, &curve, &err), &err);
  size_t missing = 0, checked = 0;
  for (size_t i = 0; i < curve->nc[SS_SEGMENT] * 2; i++) {
    ss_idx v = curve->cells[SS_SEGMENT][i];
    checked++;
    if (!has_position(surf, curve->x + 2 * (size_t)v, 1e-14)) missing++;
  }
  CHECK(missing == 0 && checked > 0,
        "%zu of %zu boundary vertices differ from the B-spline curve of the boundary",
        missing, checked);
  for (int i = 0; i < 4; i++) {
    const double *x0 = p->x + 2 * (size_t)corner[i],
                 *x3 = surf->x + 2 * (size_t)corner[i];
    CHECK(x0[0] == x3[0] && x0[1] == x3[1], "corner %d moved", corner[i] + 1);
  }
  ss_cx_free(surf);
  ss_cx_free(curve);
  ss_cx_free(c0);
  ss_cx_free(p);

  /* a cube with crease quads on its six faces: its boundary is the MLCA
   * (= Catmull-Clark-like) surface of the six quads (paper, figure 3 and 7) */
  tm_link *oct = tm_link_named("octahedron");
  ss_cx *star = tm_hex_star(oct); /* 8 hexes: a 2x2x2 block of cubes */
  tm_link_free(oct);
  ss_cx *vol = NULL, *sur = NULL;
  ss_cx_new(3, &sur, &err);
  /* boundary quads of the block: faces used by exactly one hex */
  for (size_t h = 0; h < star->nc[SS_HEX]; h++) {
    const ss_idx *c = ss_cx_cell(star, SS_HEX, h);
    static const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                    {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (int fc = 0; fc < 6; fc++) {
      size_t uses = 0;
      for (size_t g = 0; g < star->nc[SS_HEX]; g++) {
        const ss_idx *e = ss_cx_cell(star, SS_HEX, g);
        int shared = 0;
        for (int k = 0; k < 4; k++)
          for (int m = 0; m < 8; m++)
            shared += e[m] == c[faces[fc][k]];
        uses += shared == 4;
      }
      if (uses == 1) {
        ss_idx q[4] = {c[faces[fc][0]], c[faces[fc][1]], c[faces[fc][2]],
                       c[faces[fc][3]]};
        ss_cx_add_cell(star, SS_QUAD, q, 0, &err);
      }
    }
  }
  CHECK(star->nc[SS_QUAD] == 24, "2x2x2 block has %zu boundary quads", star->nc[SS_QUAD]);
  /* the same vertex numbering: copy all vertices */
  for (size_t v = 0; v < star->nv; v++)
    ss_cx_add_vertex(sur, star->x + 3 * v, 0, &err);
  for (size_t q = 0; q < star->nc[SS_QUAD]; q++)
    ss_cx_add_cell(sur, SS_QUAD, ss_cx_cell(star, SS_QUAD, q), 0, &err);
  ss_cx *vf = NULL, *sf = NULL;
  REQUIRE_OK_VOID(ss_scheme_refine_levels(s, star, 2, &vf, &err), &err);
  REQUIRE_OK_VOID(ss_scheme_refine_levels(s, sur, 2, &sf, &err), &err);
  missing = checked = 0;
  for (size_t i = 0; i < sf->nc[SS_QUAD] * 4; i++) {
    checked++;
    if (!has_position(vf, sf->x + 3 * (size_t)sf->cells[SS_QUAD][i], 1e-14)) missing++;
  }
  CHECK(
      missing == 0 && checked > 0,
      "%zu of %zu surface vertices of the creased volume differ from the surface scheme",
      missing, checked);
  ss_cx_free(vf);
  ss_cx_free(sf);
  ss_cx_free(vol);
  ss_cx_free(sur);
  ss_cx_free(star);
  ss_scheme_free(s);
}

static void test_order_invariance(void) {
  tm_link *l = tm_link_named("bipyramid:5");
  ss_cx *h = tm_hex_star(l);
  tm_link_free(l);
  ss_error err = {0};
  /* creases of every dimension: a quad, a segment, a vertex */
  ss_idx q[4], sgm[2], vc = 3;
  memcpy(q, ss_cx_cell(h, SS_HEX, 0), 4 * sizeof *q);
  sgm[0] = ss_cx_cell(h, SS_HEX, 1)[4];
  sgm[1] = ss_cx_cell(h, SS_HEX, 1)[5];
  ss_cx_add_cell(h, SS_QUAD, q, 0, &err);
  ss_cx_add_cell(h, SS_SEGMENT, sgm, 0, &err);
  ss_cx_add_cell(h, SS_VERTEX, &vc, 0, &err);
  tm_jitter(h, 0.05, 7);
  ss_scheme *s = NULL;
  ss_cx *a = NULL;
  REQUIRE_OK_VOID(ss_scheme_new("mlca", &s, &err), &err);
  REQUIRE_OK_VOID(ss_scheme_refine_levels(s, h, 2, &a, &err), &err);
  for (unsigned long seed = 1; seed <= 4; seed++) {
    ss_cx *p = tm_permuted(h, seed), *b = NULL;
    REQUIRE_OK_VOID(ss_scheme_refine_levels(s, p, 2, &b, &err), &err);
    CHECK(tm_same_geometry(a, b, 1e-12) == 0,
          "relabelled input (seed %lu) gives a different refined mesh", seed);
    ss_cx_free(p);
    ss_cx_free(b);
  }
  check_paths_agree("mlca", h, "hex star with creases");
  ss_cx_free(a);
  ss_cx_free(h);
  ss_scheme_free(s);
}

int main(void) {
  gsl_set_error_handler_off();
  test_polygon();
  for (int d = 1; d <= 3; d++)
    op_check_tensor_rule("mlca", d, 4);
  op_check_tensor_rule("mlca", 2, 5);
  test_equation2();
  test_creases();
  test_order_invariance();
  return ss_test_done("mlca");
}
