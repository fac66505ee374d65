/* test_hexify.c — the hexify split (MLCA paper, section 3.3): non-hexahedral
 * input made hexahedral at the cells' corners.
 *
 * Properties, each computed here from the cells' own geometry:
 *   - a tetrahedron gives 4 hexahedra (its 4 vertices, 6 edge midpoints, 4
 *     face centres and the centroid: 15 points), each positive, with planar
 *     faces, whose volumes (divergence theorem over their triangulated faces)
 *     sum to the tet's; the centroid lies in all 4 (the paper's "extraordinary
 *     vertex of valence 4 into the center of every tetrahedron");
 *   - a jittered Kuhn grid (48 tets): V + E + F + T points, with E and F the
 *     distinct edges and faces counted here by sorting, all positions
 *     distinct, volumes summing to the grid's, orientation positive — so
 *     neighbouring tets share their edge midpoints and face centres;
 *   - a closed triangle surface (the icosahedron): 3 quads per triangle,
 *     planar, facing the triangle's way, their areas summing to its area;
 *   - on cubes it is the multilinear split, bit for bit (a hex grid with
 *     boundary quads and segments);
 *   - octahedra are refused (SS_EINPUT). */
#include <stdlib.h>
#include <string.h>

#include "ss_split.h"
#include "ss_test.h"
#include "ss_testmesh.h"

static void sub3(const double *a, const double *b, double *o) {
  for (int i = 0; i < 3; i++)
    o[i] = a[i] - b[i];
}

static void cross(const double *a, const double *b, double *o) {
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}

static double det3(const double *a, const double *b, const double *c) {
  double t[3];
  cross(b, c, t);
  return a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
}

/* Volume of hex h by the divergence theorem over its six faces, outward,
 * each cut into two triangles (exact for planar faces); *planar receives the
 * largest distance of a face's fourth corner from the plane of the other
 * three, relative to the face's size. */
static double hex_volume(const ss_cx *cx, size_t h, double *planar) {
  static const int face[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  const ss_idx *v = ss_cx_cell(cx, SS_HEX, h);
  double vol = 0.0;
  *planar = 0.0;
  for (int f = 0; f < 6; f++) {
    const double *p[4];
    for (int i = 0; i < 4; i++)
      p[i] = cx->x + 3 * v[face[f][i]];
    vol += det3(p[0], p[1], p[2]) + det3(p[0], p[2], p[3]);
    double e1[3], e2[3], e3[3], n[3];
    sub3(p[1], p[0], e1);
    sub3(p[2], p[0], e2);
    sub3(p[3], p[0], e3);
    cross(e1, e2, n);
    const double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double size = sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    *planar = fmax(*planar, fabs(n[0] * e3[0] + n[1] * e3[1] + n[2] * e3[2]) / nn / size);
  }
  return vol / 6.0;
}

static double tet_volume(const ss_cx *cx, size_t t) {
  const ss_idx *v = ss_cx_cell(cx, SS_TET, t);
  double a[3], b[3], c[3];
  sub3(cx->x + 3 * v[1], cx->x + 3 * v[0], a);
  sub3(cx->x + 3 * v[2], cx->x + 3 * v[0], b);
  sub3(cx->x + 3 * v[3], cx->x + 3 * v[0], c);
  return det3(a, b, c) / 6.0;
}

/* Hexify cx; checks volumes and orientation; returns the fine complex. */
static ss_cx *hexify_checked(const ss_cx *cx, const char *what) {
  ss_error err = {0};
  ss_cx *f = NULL;
  ss_split *L = NULL;
  if (ss_split_refine(SS_SPLIT_HEXIFY, cx, &f, &L, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    return NULL;
  }
  ss_split_free(L);
  CHECK(f->nc[SS_HEX] == 4 * cx->nc[SS_TET] + 8 * cx->nc[SS_HEX] && f->nc[SS_TET] == 0,
        "%s: %zu hexes, %zu tets", what, f->nc[SS_HEX], f->nc[SS_TET]);
  double vt = 0.0, vh = 0.0, worst_planar = 0.0, least = INFINITY;
  for (size_t t = 0; t < cx->nc[SS_TET]; t++)
    vt += tet_volume(cx, t);
  for (size_t h = 0; h < f->nc[SS_HEX]; h++) {
    double planar;
    const double v = hex_volume(f, h, &planar);
    vh += v;
    least = fmin(least, v);
    worst_planar = fmax(worst_planar, planar);
  }
  CHECK(least > 0.0, "%s: a hex of volume %g", what, least);
  CHECK(fabs(vh - vt) <= 1e-13 * vt, "%s: hex volumes %.17g, tets %.17g", what, vh, vt);
  CHECK(worst_planar <= 1e-13, "%s: a hex face is off its plane by %.3g", what,
        worst_planar);
  CHECK(ss_cx_check_orientation(f, &err) == SS_OK, "%s: orientation: %s", what, err.msg);
  return f;
}

static void test_tet(void) {
  const double x[4][3] = {
      {0.1, 0.0, -0.2}, {1.3, 0.2, 0.1}, {0.2, 1.1, 0.3}, {0.4, 0.3, 1.2}};
  ss_error err = {0};
  ss_cx *cx = NULL;
  REQUIRE_OK_VOID(ss_cx_new(3, &cx, &err), &err);
  for (int i = 0; i < 4; i++)
    REQUIRE_OK_VOID(ss_cx_add_vertex(cx, x[i], 0, &err), &err);
  const ss_idx t[4] = {0, 1, 2, 3};
  REQUIRE_OK_VOID(ss_cx_add_cell(cx, SS_TET, t, 7, &err), &err);
  CHECK(tet_volume(cx, 0) > 0.0, "the test's tet is negative");
  ss_cx *f = hexify_checked(cx, "one tet");
  if (f) {
    CHECK(f->nv == 15, "one tet: %zu points, expected 15", f->nv);
    /* the centroid: the one point in all four hexes, at the vertices' mean */
    size_t *count = calloc(f->nv, sizeof *count);
    for (size_t i = 0; i < 8 * f->nc[SS_HEX]; i++)
      count[f->cells[SS_HEX][i]]++;
    size_t in4 = 0;
    for (size_t v = 0; v < f->nv; v++)
      if (count[v] == 4) {
        in4++;
        for (int k = 0; k < 3; k++)
          CHECK_CLOSE(f->x[3 * v + (size_t)k],
                      (x[0][k] + x[1][k] + x[2][k] + x[3][k]) / 4.0, 1e-15,
                      "centroid coordinate %d", k);
      }
    CHECK(in4 == 1, "one tet: %zu points in four hexes, expected the centroid", in4);
    for (size_t h = 0; h < f->nc[SS_HEX]; h++)
      CHECK(f->cref[SS_HEX][h] == 7, "hex %zu lost its reference", h);
    free(count);
  }
  ss_cx_free(f);
  ss_cx_free(cx);
}

static int cmp_key(const void *a, const void *b) {
  const uint32_t *x = a, *y = b;
  for (int i = 0; i < 3; i++)
    if (x[i] != y[i]) return (x[i] > y[i]) - (x[i] < y[i]);
  return 0;
}

/* Distinct sorted tuples of k vertices of the tets (k = 2 edges, 3 faces). */
static size_t distinct_subsets(const ss_cx *cx, int k) {
  const size_t nt = cx->nc[SS_TET], per = k == 2 ? 6 : 4;
  uint32_t *key = calloc(3 * per * nt + 3, sizeof *key);
  size_t n = 0;
  for (size_t t = 0; t < nt; t++) {
    const ss_idx *v = ss_cx_cell(cx, SS_TET, t);
    for (int a = 0; a < 4; a++)
      for (int b = a + 1; b < 4; b++) {
        if (k == 2) {
          uint32_t *q = key + 3 * n++;
          q[0] = v[a] < v[b] ? v[a] : v[b];
          q[1] = v[a] < v[b] ? v[b] : v[a];
          continue;
        }
        for (int c = b + 1; c < 4; c++) {
          uint32_t *q = key + 3 * n++, s[3] = {v[a], v[b], v[c]};
          for (int i = 1; i < 3; i++)
            for (int j = i; j > 0 && s[j - 1] > s[j]; j--) {
              uint32_t w = s[j];
              s[j] = s[j - 1];
              s[j - 1] = w;
            }
          memcpy(q, s, sizeof s);
        }
      }
  }
  qsort(key, n, 3 * sizeof *key, cmp_key);
  size_t d = 0;
  for (size_t i = 0; i < n; i++)
    d += i == 0 || cmp_key(key + 3 * i, key + 3 * (i - 1));
  free(key);
  return d;
}

static int cmp_point(const void *a, const void *b) {
  const double *x = a, *y = b;
  for (int i = 0; i < 3; i++)
    if (x[i] != y[i]) return (x[i] > y[i]) - (x[i] < y[i]);
  return 0;
}

static void test_kuhn(void) {
  ss_cx *cx = tm_kuhn(2);
  tm_jitter(cx, 0.1, 5);
  ss_cx *f = hexify_checked(cx, "Kuhn grid");
  if (f) {
    const size_t E = distinct_subsets(cx, 2), F = distinct_subsets(cx, 3);
    const size_t expect = cx->nv + E + F + cx->nc[SS_TET];
    CHECK(f->nv == expect, "Kuhn grid: %zu points, expected V + E + F + T = %zu", f->nv,
          expect);
    double *p = malloc(3 * f->nv * sizeof *p);
    memcpy(p, f->x, 3 * f->nv * sizeof *p);
    qsort(p, f->nv, 3 * sizeof *p, cmp_point);
    size_t dup = 0;
    for (size_t i = 1; i < f->nv; i++)
      dup += !cmp_point(p + 3 * i, p + 3 * (i - 1));
    CHECK(dup == 0, "Kuhn grid: %zu points given twice", dup);
    free(p);
  }
  ss_cx_free(f);
  ss_cx_free(cx);
}

static void test_triangles(void) {
  tm_link *l = tm_link_named("icosahedron");
  ss_cx *cx = tm_link_surface(l);
  ss_error err = {0};
  ss_cx *f = NULL;
  ss_split *L = NULL;
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_HEXIFY, cx, &f, &L, &err), &err);
  CHECK(f->nc[SS_QUAD] == 3 * cx->nc[SS_TRIANGLE] && f->nc[SS_TRIANGLE] == 0,
        "icosahedron: %zu quads", f->nc[SS_QUAD]);
  double at = 0.0, aq = 0.0, worst = 0.0, least = INFINITY;
  for (size_t t = 0; t < cx->nc[SS_TRIANGLE]; t++) {
    const ss_idx *v = ss_cx_cell(cx, SS_TRIANGLE, t);
    double e1[3], e2[3], n[3];
    sub3(cx->x + 3 * v[1], cx->x + 3 * v[0], e1);
    sub3(cx->x + 3 * v[2], cx->x + 3 * v[0], e2);
    cross(e1, e2, n);
    const double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    at += nn / 2.0;
    for (size_t q = 3 * t; q < 3 * t + 3; q++) { /* a triangle's quads */
      const ss_idx *w = ss_cx_cell(f, SS_QUAD, q);
      double d1[3], d2[3], m[3], e3[3];
      sub3(f->x + 3 * w[2], f->x + 3 * w[0], d1);
      sub3(f->x + 3 * w[3], f->x + 3 * w[1], d2);
      cross(d1, d2, m);
      const double along = (m[0] * n[0] + m[1] * n[1] + m[2] * n[2]) / nn;
      aq += along / 2.0;
      least = fmin(least, along);
      for (int i = 0; i < 4; i++) { /* every corner in the triangle's plane */
        sub3(f->x + 3 * w[i], cx->x + 3 * v[0], e3);
        worst = fmax(worst, fabs(e3[0] * n[0] + e3[1] * n[1] + e3[2] * n[2]) / nn);
      }
    }
  }
  CHECK(least > 0.0, "icosahedron: a quad faces away from its triangle (%g)", least);
  CHECK(fabs(aq - at) <= 1e-13 * at, "icosahedron: quad area %.17g, triangles %.17g", aq,
        at);
  CHECK(worst <= 1e-15, "icosahedron: a quad corner %.3g off its triangle's plane",
        worst);
  ss_split_free(L);
  ss_cx_free(f);
  ss_cx_free(cx);
  tm_link_free(l);
}

static void test_cubes_and_rejects(void) {
  ss_cx *cx = tm_hex_grid(2, 1, 1);
  ss_error err = {0};
  const ss_idx quad[4] = {0, 1, 4, 3}, seg[2] = {0, 1}, corner = 2;
  REQUIRE_OK_VOID(ss_cx_add_cell(cx, SS_QUAD, quad, 0, &err), &err);
  REQUIRE_OK_VOID(ss_cx_add_cell(cx, SS_SEGMENT, seg, 0, &err), &err);
  REQUIRE_OK_VOID(ss_cx_add_cell(cx, SS_VERTEX, &corner, 0, &err), &err);
  ss_cx *a = NULL, *b = NULL;
  ss_split *La = NULL, *Lb = NULL;
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_HEXIFY, cx, &a, &La, &err), &err);
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_MULTILINEAR, cx, &b, &Lb, &err), &err);
  int same = a->nv == b->nv && !memcmp(a->x, b->x, 3 * a->nv * sizeof *a->x);
  for (int t = 0; t < SS_NCELLTYPES && same; t++)
    same = a->nc[t] == b->nc[t] &&
           !memcmp(a->cells[t], b->cells[t],
                   a->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t) * sizeof(ss_idx));
  CHECK(same, "on cubes hexify is not the multilinear split");
  ss_split_free(La);
  ss_split_free(Lb);
  ss_cx_free(a);
  ss_cx_free(b);
  ss_cx_free(cx);

  ss_cx *oc = NULL;
  REQUIRE_OK_VOID(ss_cx_new(3, &oc, &err), &err);
  const double x[6][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},
                          {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  for (int i = 0; i < 6; i++)
    REQUIRE_OK_VOID(ss_cx_add_vertex(oc, x[i], 0, &err), &err);
  const ss_idx o[6] = {0, 1, 2, 3, 4, 5};
  REQUIRE_OK_VOID(ss_cx_add_cell(oc, SS_OCT, o, 0, &err), &err);
  ss_status st = ss_split_refine(SS_SPLIT_HEXIFY, oc, &a, &La, &err);
  CHECK(st == SS_EINPUT && a == NULL && strstr(err.msg, "octahedra"),
        "an octahedron: status %d, '%s'", (int)st, err.msg);
  ss_cx_free(oc);
}

int main(void) {
  test_tet();
  test_kuhn();
  test_triangles();
  test_cubes_and_rejects();
  return ss_test_done("hexify");
}
