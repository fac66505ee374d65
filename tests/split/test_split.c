/* test_split.c — the topological splits: counts, shared vertices, parents,
 * orientation and volume of children, and L as a matrix. */
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_spblas.h>

#include "ss_split.h"
#include "ss_test.h"
#include "ss_testmesh.h"

static ss_cx *one_cell(ss_cell_type t, const double (*x)[3], int nv) {
  ss_cx *cx = NULL;
  ss_error err = {0};
  ss_cx_new(3, &cx, &err);
  for (int i = 0; i < nv; i++)
    ss_cx_add_vertex(cx, x[i], 0, &err);
  ss_idx v[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  ss_cx_add_cell(cx, t, v, 7, &err);
  return cx;
}

/* Children are positive and their volumes sum to the parent's. */
static void check_children(const ss_cx *coarse, const ss_cx *fine, const char *what) {
  double vc = 0, vf = 0;
  for (int t = SS_TET; t < SS_NCELLTYPES; t++) {
    for (size_t i = 0; i < coarse->nc[t]; i++) {
      double v;
      ss_cx_cell_orientation(coarse, (ss_cell_type)t, i, &v);
      vc += v;
    }
    for (size_t i = 0; i < fine->nc[t]; i++) {
      double v;
      int o = ss_cx_cell_orientation(fine, (ss_cell_type)t, i, &v);
      CHECK(o == 1, "%s: child %s %zu has orientation %d", what,
            ss_cell_name((ss_cell_type)t), i, o);
      CHECK(fine->cref[t][i] == 7, "%s: child lost the parent's reference", what);
      vf += v;
    }
  }
  CHECK_CLOSE(vf, vc, 1e-13, "%s: children's volumes sum to the parent's", what);
}

/* L x_coarse reproduces the split positions. */
static void check_L(const ss_cx *coarse, const ss_cx *fine, const ss_split *L,
                    const char *what) {
  gsl_spmatrix *M = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_split_matrix(L, &M, &err), &err);
  double *y = calloc(fine->nv, sizeof *y);
  double worst = 0;
  for (int r = 0; r < coarse->dim; r++) {
    gsl_vector_const_view x = gsl_vector_const_view_array_with_stride(
        coarse->x + r, (size_t)coarse->dim, coarse->nv);
    gsl_vector_view yv = gsl_vector_view_array(y, fine->nv);
    gsl_spblas_dgemv(CblasNoTrans, 1.0, M, &x.vector, 0.0, &yv.vector);
    for (size_t f = 0; f < fine->nv; f++) {
      double d = fabs(y[f] - fine->x[f * (size_t)fine->dim + (size_t)r]);
      if (d > worst) worst = d;
    }
  }
  CHECK(worst <= 1e-15, "%s: L x differs from the split positions by %g", what, worst);
  for (size_t v = 0; v < L->ncoarse; v++)
    CHECK(ss_split_npar(L, v) == 1 && L->parent[L->ptr[v]] == v,
          "%s: coarse vertex %zu is not its own single parent", what, v);
  free(y);
  gsl_spmatrix_free(M);
}

static void test_hex(void) {
  const double x[8][3] = {{0, 0, 0},   {1, 0, 0.1},   {1.1, 1, 0}, {0, 1, 0.2},
                          {0.1, 0, 1}, {1, 0.1, 1.2}, {1, 1, 1},   {0, 1.2, 1}};
  ss_cx *h = one_cell(SS_HEX, x, 8), *f = NULL;
  ss_split *L = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_MULTILINEAR, h, &f, &L, &err), &err);
  CHECK(f->nv == 27 && f->nc[SS_HEX] == 8, "hex: %zu vertices, %zu hexes", f->nv,
        f->nc[SS_HEX]);
  size_t npar[9] = {0};
  for (size_t v = 0; v < f->nv; v++)
    npar[ss_split_npar(L, v)]++;
  CHECK(npar[1] == 8 && npar[2] == 12 && npar[4] == 6 && npar[8] == 1,
        "hex: parents per fine vertex 1:%zu 2:%zu 4:%zu 8:%zu", npar[1], npar[2], npar[4],
        npar[8]);
  check_children(h, f, "hex");
  check_L(h, f, L, "hex");
  /* child k holds coarse corner k at its own corner k */
  for (int k = 0; k < 8; k++)
    CHECK(ss_cx_cell(f, SS_HEX, (size_t)k)[k] == (ss_idx)k, "child %d corner", k);
  ss_split_free(L);
  ss_cx_free(f);

  /* crease cells on the hex's faces, edges and corners share its new vertices,
   * also when a face is listed in the reverse cyclic order */
  static const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                  {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (int i = 0; i < 6; i++) {
    ss_idx q[4] = {(ss_idx)faces[i][0], (ss_idx)faces[i][1], (ss_idx)faces[i][2],
                   (ss_idx)faces[i][3]};
    ss_cx_add_cell(h, SS_QUAD, q, 7, &err);
  }
  for (int e = 0; e < 12; e++) {
    int a, b;
    ss_cell_edge(SS_HEX, e, &a, &b);
    ss_idx s[2] = {(ss_idx)b, (ss_idx)a};
    ss_cx_add_cell(h, SS_SEGMENT, s, 7, &err);
  }
  for (ss_idx v = 0; v < 8; v++)
    ss_cx_add_cell(h, SS_VERTEX, &v, 7, &err);
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_MULTILINEAR, h, &f, &L, &err), &err);
  CHECK(f->nv == 27, "hex with crease cells: %zu fine vertices, expected 27", f->nv);
  CHECK(f->nc[SS_QUAD] == 24 && f->nc[SS_SEGMENT] == 24 && f->nc[SS_VERTEX] == 8,
        "crease cells split into %zu quads, %zu segments, %zu vertices", f->nc[SS_QUAD],
        f->nc[SS_SEGMENT], f->nc[SS_VERTEX]);
  ss_split_free(L);
  ss_cx_free(f);
  ss_cx_free(h);

  /* two hexes sharing a face: a 2x1x1 block refines to a 5x3x3 grid */
  ss_cx *t = tm_torus(3, 4); /* reuse its vertex layout: take two adjacent cells */
  ss_cx *two = NULL;
  ss_cx_new(3, &two, &err);
  for (size_t v = 0; v < t->nv; v++)
    ss_cx_add_vertex(two, t->x + 3 * v, 0, &err);
  ss_cx_add_cell(two, SS_HEX, ss_cx_cell(t, SS_HEX, 0), 0, &err);
  ss_cx_add_cell(two, SS_HEX, ss_cx_cell(t, SS_HEX, 1), 0, &err);
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_MULTILINEAR, two, &f, &L, &err), &err);
  CHECK(f->nv == t->nv - 12 + 45, "two hexes: %zu new vertices, expected 33",
        f->nv - t->nv);
  ss_split_free(L);
  ss_cx_free(f);
  ss_cx_free(two);
  ss_cx_free(t);
}

static void test_tet_oct(void) {
  const double xt[4][3] = {{0, 0, 0}, {1, 0.1, 0}, {0.2, 1, 0.1}, {0.1, 0.2, 1}};
  ss_cx *t = one_cell(SS_TET, xt, 4), *f = NULL;
  ss_split *L = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_TETOCT, t, &f, &L, &err), &err);
  CHECK(f->nv == 10 && f->nc[SS_TET] == 4 && f->nc[SS_OCT] == 1,
        "tet: %zu vertices, %zu tets, %zu octahedra", f->nv, f->nc[SS_TET],
        f->nc[SS_OCT]);
  check_children(t, f, "tet");
  check_L(t, f, L, "tet");
  /* the child octahedron's opposite pairs are opposite edges of the tet */
  const ss_idx *o = ss_cx_cell(f, SS_OCT, 0);
  for (int i = 0; i < 3; i++) {
    ss_idx a = o[i], b = o[i + 3];
    ss_idx pa[2] = {L->parent[L->ptr[a]], L->parent[L->ptr[a] + 1]};
    ss_idx pb[2] = {L->parent[L->ptr[b]], L->parent[L->ptr[b] + 1]};
    int disjoint = pa[0] != pb[0] && pa[0] != pb[1] && pa[1] != pb[0] && pa[1] != pb[1];
    CHECK(disjoint, "octahedron pair %d is not a pair of opposite tet edges", i);
  }
  ss_split_free(L);
  ss_cx_free(f);
  ss_cx_free(t);

  /* an affine image of the regular octahedron: children partition it */
  const double A[3][3] = {{1, 0.2, 0.1}, {0.1, 1.1, -0.2}, {0, 0.3, 0.9}};
  const double ref[6][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},
                            {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  double xo[6][3];
  for (int i = 0; i < 6; i++)
    for (int r = 0; r < 3; r++)
      xo[i][r] = A[r][0] * ref[i][0] + A[r][1] * ref[i][1] + A[r][2] * ref[i][2] + 0.5;
  ss_cx *oc = one_cell(SS_OCT, (const double(*)[3])xo, 6);
  double vol;
  CHECK(ss_cx_cell_orientation(oc, SS_OCT, 0, &vol) == 1, "test octahedron is positive");
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_TETOCT, oc, &f, &L, &err), &err);
  CHECK(f->nv == 19 && f->nc[SS_OCT] == 6 && f->nc[SS_TET] == 8,
        "octahedron: %zu vertices, %zu octahedra, %zu tets", f->nv, f->nc[SS_OCT],
        f->nc[SS_TET]);
  size_t six = 0;
  for (size_t v = 0; v < f->nv; v++)
    six += ss_split_npar(L, v) == 6;
  CHECK(six == 1, "octahedron: %zu fine vertices with 6 parents, expected its centroid",
        six);
  check_children(oc, f, "octahedron");
  check_L(oc, f, L, "octahedron");
  ss_split_free(L);
  ss_cx_free(f);
  ss_cx_free(oc);
}

/* Major diagonals (box-spline paper, Definition 3.2, Algorithm 1; DESIGN
 * section 4) live in the vertex order: an octahedron's is its pair (0, 3), a
 * tet's the edge pair (0,1), (2,3).  Every child inherits the diagonal
 * parallel to its parent's, so after any number of splits of one tet every
 * octahedron's x3 - x0 is parallel to (x2 + x3 - x0 - x1) of the base tet,
 * and every tet's pair gives the octahedron of that direction. */
static void test_diagonals(void) {
  const double xt[4][3] = {{0, 0, 0}, {1, 0.1, 0}, {0.2, 1, 0.1}, {0.1, 0.2, 1}};
  double d[3];
  for (int r = 0; r < 3; r++)
    d[r] = xt[2][r] + xt[3][r] - xt[0][r] - xt[1][r];
  ss_cx *cx = one_cell(SS_TET, xt, 4);
  ss_error err = {0};
  for (int level = 1; level <= 3 && cx; level++) {
    ss_cx *f = NULL;
    ss_split *L = NULL;
    REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_TETOCT, cx, &f, &L, &err), &err);
    ss_split_free(L);
    ss_cx_free(cx);
    cx = f;
    size_t bad = 0;
    for (int t = SS_TET; t <= SS_OCT; t += SS_OCT - SS_TET) {
      for (size_t i = 0; i < cx->nc[t]; i++) {
        const ss_idx *v = ss_cx_cell(cx, (ss_cell_type)t, i);
        double e[3], c[3];
        for (int r = 0; r < 3; r++) {
          const double *x = cx->x;
          e[r] = t == SS_OCT ? x[3 * v[3] + r] - x[3 * v[0] + r]
                             : x[3 * v[2] + r] + x[3 * v[3] + r] - x[3 * v[0] + r] -
                                   x[3 * v[1] + r];
        }
        c[0] = e[1] * d[2] - e[2] * d[1];
        c[1] = e[2] * d[0] - e[0] * d[2];
        c[2] = e[0] * d[1] - e[1] * d[0];
        const double ne = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]),
                     nd = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        bad += !(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) <= 1e-12 * ne * nd);
      }
    }
    CHECK(bad == 0,
          "level %d: %zu of %zu cells have a diagonal not parallel to the "
          "base tet's",
          level, bad, cx->nc[SS_TET] + cx->nc[SS_OCT]);
  }
  ss_cx_free(cx);
}

static void test_triangle_and_rejects(void) {
  ss_cx *cx = NULL, *f = NULL;
  ss_split *L = NULL;
  ss_error err = {0};
  ss_cx_new(2, &cx, &err);
  const double x[3][2] = {{0, 0}, {1, 0.2}, {0.3, 1}};
  for (int i = 0; i < 3; i++)
    ss_cx_add_vertex(cx, x[i], 0, &err);
  ss_idx t[3] = {0, 1, 2};
  ss_cx_add_cell(cx, SS_TRIANGLE, t, 0, &err);
  double area;
  ss_cx_cell_orientation(cx, SS_TRIANGLE, 0, &area);
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_TETOCT, cx, &f, &L, &err), &err);
  double sum = 0;
  for (size_t i = 0; i < f->nc[SS_TRIANGLE]; i++) {
    double a;
    CHECK(ss_cx_cell_orientation(f, SS_TRIANGLE, i, &a) == 1, "child triangle %zu", i);
    sum += a;
  }
  CHECK(f->nc[SS_TRIANGLE] == 4 && f->nv == 6, "triangle split");
  CHECK_CLOSE(sum, area, 1e-15, "child triangles' areas");
  ss_split_free(L);
  ss_cx_free(f);
  /* a split refuses cells it does not know, and malformed cells */
  ss_status st = ss_split_refine(SS_SPLIT_MULTILINEAR, cx, &f, &L, &err);
  CHECK(st == SS_EINPUT && strstr(err.msg, "triangles"),
        "multilinear split took a "
        "triangle: %s",
        err.msg);
  ss_idx bad[3] = {0, 1, 1};
  ss_cx_add_cell(cx, SS_TRIANGLE, bad, 0, &err);
  st = ss_split_refine(SS_SPLIT_TETOCT, cx, &f, &L, &err);
  CHECK(st == SS_EINPUT && strstr(err.msg, "degenerate"), "degenerate cell: %s", err.msg);
  ss_cx_free(cx);
}

int main(void) {
  test_diagonals();
  gsl_set_error_handler_off();
  test_hex();
  test_tet_oct();
  test_triangle_and_rejects();
  return ss_test_done("split");
}
