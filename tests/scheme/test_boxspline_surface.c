/* test_boxspline_surface.c — the box-spline solid's Loop surfaces (box-spline
 * paper, section 3.6 and figure 14; the hybrid solid of figure 29; issue 38).
 *
 * A jittered 2 x 2 x 2 Kuhn cube (48 tets) with a wall of four triangle
 * cells standing on its top face (a surface part joined to the solid along a
 * line, figure 29's "hybrid dimensionality"), refined twice by boxspline,
 * against the surface alone — the cube's boundary triangles and the wall, on
 * the same vertices, no tets — refined twice by the `loop` scheme (a second
 * code path: ss_scheme_loop.c's own rule, which sends its rows in passes):
 *   - every point of the Loop surface is a point of the box-spline solid's
 *     surface (fine faces held by one cell, and its triangle cells), to 1e-13
 *     of the cube's size, and the counts agree; so for boxspline-avg;
 *   - the boundary and the wall refined as two separate Loop surfaces miss
 *     those points by more than 1e-3 (the comparison can fail: the line
 *     where the wall meets the solid is a crease curve of one surface);
 *   - one level: the points off the surface are where the solid without the
 *     wall puts them, bit for bit (the rows of the solid read no triangle);
 *   - triangle cells that are the solid's own boundary faces (TetGen's .face)
 *     change nothing: the same complex and points within 1e-14.
 * And figure 14(b)'s choice of the smooth boundary vertex's weight c at
 * valence k, (1 - k c) x + c each neighbour, against closed forms: with
 * c = 3/(8k) the vertex keeps 5/8 at every k (a tet's corner, k = 3: 5/8
 * and 1/8; an octahedron's, k = 4: 5/8 and 3/32), with Loop's beta 7/16,
 * 3/16 and 33/64, 31/256; at k = 6 both are figure 14(a)'s regular rule,
 * 10/16 and 1/16; the edge rule, 3/8, 3/8, 1/8, 1/8, is the same for both;
 * schemes whose papers fix Loop's beta (tetoct, loop) refuse the choice. */
#include <stdlib.h>
#include <string.h>

#include "ss_diag.h"
#include "ss_scheme.h"
#include "ss_split.h"
#include "ss_test.h"
#include "ss_testmesh.h"

/* The cube with the wall's three new vertices (above the grid line y = 1 of
 * the top face z = N) and, with_wall, its four triangles on the grid edges
 * of that line. */
static ss_cx *hybrid(int N, int with_wall, ss_idx wall[4][3]) {
  ss_error err = {0};
  ss_cx *cx = tm_kuhn(N);
  ss_idx low[3] = {0}, high[3] = {0};
  for (size_t v = 0; v < cx->nv; v++) { /* the grid points (i, 1, N) */
    const double *p = cx->x + 3 * v;
    if (p[1] == 1.0 && p[2] == (double)N) low[(int)p[0]] = (ss_idx)v;
  }
  for (int i = 0; i <= N; i++) {
    const double p[3] = {(double)i, 1.0, (double)N + 1.0};
    high[i] = (ss_idx)cx->nv;
    ss_cx_add_vertex(cx, p, 0, &err);
  }
  for (int i = 0; i < N; i++) {
    const ss_idx t0[3] = {low[i], low[i + 1], high[i + 1]},
                 t1[3] = {low[i], high[i + 1], high[i]};
    memcpy(wall[2 * i], t0, sizeof t0);
    memcpy(wall[2 * i + 1], t1, sizeof t1);
    if (with_wall) {
      ss_cx_add_cell(cx, SS_TRIANGLE, t0, 0, &err);
      ss_cx_add_cell(cx, SS_TRIANGLE, t1, 0, &err);
    }
  }
  tm_jitter(cx, 0.08, 11);
  return cx;
}

static ss_cx *refine(const char *scheme, const ss_cx *cx, int levels) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  if (ss_scheme_new(scheme, &s, &err)) {
    CHECK(0, "%s: %s", scheme, err.msg);
    return NULL;
  }
  ss_cx *a = tm_refined(s, cx, levels, &err);
  CHECK(a, "%s %s", scheme, err.msg);
  ss_scheme_free(s);
  return a;
}

/* Flags of the vertices on the solid's surface: on a face held by one cell,
 * or on a triangle cell. */
static unsigned char *surface_flags(const ss_cx *V) {
  unsigned char *on = calloc(V->nv + 1, 1);
  ss_idx *b = NULL;
  const size_t nb = tm_boundary_faces(V, &b);
  for (size_t i = 0; i < 3 * nb; i++)
    on[b[i]] = 1;
  for (size_t i = 0; i < 3 * V->nc[SS_TRIANGLE]; i++)
    on[V->cells[SS_TRIANGLE][i]] = 1;
  free(b);
  return on;
}

/* The largest distance (max norm) from a point of the triangles of the
 * surfaces S[0..ns) to the nearest flagged point of V; *nS, *nV their
 * counts. */
static double surface_gap(const ss_cx *V, ss_cx *const *S, int ns, size_t *nS,
                          size_t *nV) {
  unsigned char *onV = surface_flags(V);
  *nS = *nV = 0;
  for (size_t v = 0; v < V->nv; v++)
    *nV += onV[v];
  double worst = 0.0;
  for (int i = 0; i < ns; i++) {
    unsigned char *onS = calloc(S[i]->nv + 1, 1);
    for (size_t q = 0; q < 3 * S[i]->nc[SS_TRIANGLE]; q++)
      onS[S[i]->cells[SS_TRIANGLE][q]] = 1;
    for (size_t s = 0; s < S[i]->nv; s++) {
      if (!onS[s]) continue;
      ++*nS;
      double best = INFINITY;
      for (size_t v = 0; v < V->nv; v++) {
        if (!onV[v]) continue;
        double d = 0.0;
        for (int k = 0; k < 3; k++)
          d = fmax(d, fabs(S[i]->x[3 * s + (size_t)k] - V->x[3 * v + (size_t)k]));
        best = fmin(best, d);
      }
      worst = fmax(worst, best);
    }
    free(onS);
  }
  free(onV);
  return worst;
}

/* A surface complex on cx's vertices with the n triangles tri. */
static ss_cx *surface(const ss_cx *cx, const ss_idx *tri, size_t n) {
  ss_error err = {0};
  ss_cx *s = NULL;
  ss_cx_new(3, &s, &err);
  for (size_t v = 0; v < cx->nv; v++)
    ss_cx_add_vertex(s, cx->x + 3 * v, 0, &err);
  for (size_t i = 0; i < n; i++)
    ss_cx_add_cell(s, SS_TRIANGLE, tri + 3 * i, 0, &err);
  return s;
}

static void test_hybrid(const char *scheme) {
  const int N = 2;
  ss_idx wall[4][3];
  ss_cx *vol = hybrid(N, 1, wall);
  ss_idx *bnd = NULL;
  const size_t nb = tm_boundary_faces(vol, &bnd);
  CHECK(nb == 6u * 2u * (size_t)(N * N), "boundary triangles: %zu", nb);
  ss_idx *all = malloc((3 * (nb + 4) + 1) * sizeof *all);
  memcpy(all, bnd, 3 * nb * sizeof *all);
  memcpy(all + 3 * nb, wall, sizeof wall);
  ss_cx *joined = surface(vol, all, nb + 4),
        *alone[2] = {surface(vol, bnd, nb), surface(vol, &wall[0][0], 4)};
  ss_cx *V = refine(scheme, vol, 2), *S = refine("loop", joined, 2);
  ss_cx *A[2] = {refine("loop", alone[0], 2), refine("loop", alone[1], 2)};
  if (V && S && A[0] && A[1]) {
    size_t nS, nV;
    double gap = surface_gap(V, &S, 1, &nS, &nV);
    CHECK(nS == nV && nS > 0, "%s: %zu Loop points, %zu on the solid's surface", scheme,
          nS, nV);
    CHECK(gap <= 1e-13 * N, "%s: a Loop point is %.3g from the solid's surface", scheme,
          gap);
    printf("%s, solid and wall: %zu surface points, largest gap to Loop %.2g\n", scheme,
           nS, gap);
    gap = surface_gap(V, A, 2, &nS, &nV);
    CHECK(gap > 1e-3, "%s: the wall and the boundary apart are within %.3g", scheme, gap);
    printf("%s: the two surfaces refined apart miss by %.3g\n", scheme, gap);
  }
  /* one level: off the surface as without the wall, bit for bit */
  ss_cx *plain = hybrid(N, 0, wall);
  ss_cx *P1 = refine(scheme, plain, 1), *V1 = refine(scheme, vol, 1);
  if (P1 && V1) {
    unsigned char *on = surface_flags(V1);
    size_t off, same; /* the split numbers edges in another order */
    tm_points_in(P1, V1, on, &off, &same);
    CHECK(off > 0 && same == off, "%s: %zu of %zu interior points as without the wall",
          scheme, same, off);
    free(on);
  }
  ss_cx_free(P1);
  ss_cx_free(V1);
  ss_cx_free(plain);
  for (int i = 0; i < 2; i++) {
    ss_cx_free(A[i]);
    ss_cx_free(alone[i]);
  }
  ss_cx_free(V);
  ss_cx_free(S);
  ss_cx_free(joined);
  ss_cx_free(vol);
  free(bnd);
  free(all);
}

/* The boundary faces given again as triangle cells change nothing. */
static void test_faces_given(const char *scheme) {
  ss_error err = {0};
  ss_cx *vol = tm_kuhn(2), *faced = NULL;
  tm_jitter(vol, 0.08, 5);
  ss_idx *bnd = NULL;
  const size_t nb = tm_boundary_faces(vol, &bnd);
  REQUIRE_OK_VOID(ss_cx_copy(vol, &faced, &err), &err);
  for (size_t i = 0; i < nb; i++)
    REQUIRE_OK_VOID(ss_cx_add_cell(faced, SS_TRIANGLE, bnd + 3 * i, 0, &err), &err);
  ss_cx *P = refine(scheme, vol, 2), *F = refine(scheme, faced, 2);
  if (P && F) {
    CHECK(F->nc[SS_TRIANGLE] == 16 * nb, "%s: %zu triangles", scheme, F->nc[SS_TRIANGLE]);
    F->nc[SS_TRIANGLE] = 0;
    CHECK(!tm_same_geometry(P, F, 1e-14), "%s: the boundary faces as triangles moved it",
          scheme);
  }
  ss_cx_free(P);
  ss_cx_free(F);
  ss_cx_free(faced);
  ss_cx_free(vol);
  free(bnd);
}

/* R(r, c), 0 if absent. */
static double entry(const gsl_spmatrix *R, size_t r, size_t c) {
  for (int q = R->p[r]; q < R->p[r + 1]; q++)
    if ((size_t)R->i[q] == c) return R->data[q];
  return 0.0;
}

/* The operator of one refinement of cx by scheme with c chosen. */
static gsl_spmatrix *operator_of(const char *scheme, ss_loop_c c, const ss_cx *cx,
                                 ss_split **L) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *fine = NULL;
  gsl_spmatrix *R = NULL;
  if (ss_scheme_new(scheme, &s, &err) || ss_scheme_set_loop_c(s, c, &err) ||
      ss_scheme_refine_split(s, cx, &fine, &R, L, &err))
    CHECK(0, "%s: %s", scheme, err.msg);
  ss_cx_free(fine);
  ss_scheme_free(s);
  return R;
}

/* Row r of R is w_self at r and w_nb at each of the n others it holds. */
static void check_vertex_row(const gsl_spmatrix *R, size_t r, size_t n, double w_self,
                             double w_nb, const char *what) {
  CHECK_CLOSE(entry(R, r, r), w_self, 1e-15, "%s: self", what);
  size_t m = 0;
  for (int q = R->p[r]; q < R->p[r + 1]; q++) {
    if ((size_t)R->i[q] == r) continue;
    m++;
    CHECK_CLOSE(R->data[q], w_nb, 1e-15, "%s: neighbour %d", what, R->i[q]);
  }
  CHECK(m == n, "%s: %zu neighbours, not %zu", what, m, n);
}

static void test_boundary_c(const char *scheme) {
  ss_error err = {0};
  const double tx[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const double ox[6][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},
                           {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  const ss_idx tv[4] = {0, 1, 2, 3}, ov[6] = {0, 1, 2, 3, 4, 5};
  ss_cx *tet = NULL, *oct = NULL, *tet1 = NULL;
  REQUIRE_OK_VOID(ss_cx_new(3, &tet, &err), &err);
  REQUIRE_OK_VOID(ss_cx_new(3, &oct, &err), &err);
  for (int i = 0; i < 4; i++)
    ss_cx_add_vertex(tet, tx[i], 0, &err);
  for (int i = 0; i < 6; i++)
    ss_cx_add_vertex(oct, ox[i], 0, &err);
  ss_cx_add_cell(tet, SS_TET, tv, 0, &err);
  ss_cx_add_cell(oct, SS_OCT, ov, 0, &err);
  ss_split *L = NULL;
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_TETOCT, tet, &tet1, &L, &err), &err);
  ss_split_free(L);
  for (int mode = 0; mode < 2; mode++) {
    const ss_loop_c c = mode ? SS_LOOP_C_3_8K : SS_LOOP_C_BETA;
    char what[96];
    gsl_spmatrix *R = operator_of(scheme, c, tet, &L);
    if (R) {
      snprintf(what, sizeof what, "%s %s, tet corner", scheme, mode ? "3/8k" : "beta");
      check_vertex_row(R, 0, 3, mode ? 5.0 / 8 : 7.0 / 16, mode ? 1.0 / 8 : 3.0 / 16,
                       what);
      /* an edge point: 3/8 each end, 1/8 each opposite vertex */
      const ss_idx a = L->parent[L->ptr[4]], b = L->parent[L->ptr[4] + 1];
      for (ss_idx v = 0; v < 4; v++)
        CHECK_CLOSE(entry(R, 4, v), v == a || v == b ? 3.0 / 8 : 1.0 / 8, 1e-15,
                    "%s: edge point's weight of %u", what, v);
      gsl_spmatrix_free(R);
    }
    ss_split_free(L);
    if ((R = operator_of(scheme, c, oct, &L))) {
      snprintf(what, sizeof what, "%s %s, octahedron corner", scheme,
               mode ? "3/8k" : "beta");
      check_vertex_row(R, 0, 4, mode ? 5.0 / 8 : 33.0 / 64, mode ? 3.0 / 32 : 31.0 / 256,
                       what);
      gsl_spmatrix_free(R);
    }
    ss_split_free(L);
    /* the refined tet's edge midpoints have six surface neighbours */
    if ((R = operator_of(scheme, c, tet1, &L))) {
      snprintf(what, sizeof what, "%s %s, valence 6", scheme, mode ? "3/8k" : "beta");
      check_vertex_row(R, 4, 6, 10.0 / 16, 1.0 / 16, what);
      gsl_spmatrix_free(R);
    }
    ss_split_free(L);
  }
  ss_cx_free(tet);
  ss_cx_free(tet1);
  ss_cx_free(oct);
}

/* Schemes whose papers fix Loop's beta refuse the choice. */
static void test_refused(void) {
  const char *const names[] = {"tetoct", "loop", "mlca"};
  for (int i = 0; i < 3; i++) {
    ss_error err = {0};
    ss_scheme *s = NULL;
    REQUIRE_OK_VOID(ss_scheme_new(names[i], &s, &err), &err);
    CHECK(ss_scheme_set_loop_c(s, SS_LOOP_C_3_8K, &err) == SS_EINPUT &&
              strstr(err.msg, names[i]),
          "%s took the choice of c: %s", names[i], err.msg);
    ss_scheme_free(s);
  }
}

int main(void) {
  test_hybrid("boxspline");
  test_hybrid("boxspline-avg");
  test_faces_given("boxspline");
  test_faces_given("boxspline-avg");
  test_boundary_c("boxspline");
  test_boundary_c("boxspline-avg");
  test_refused();
  return ss_test_done("boxspline_surface");
}
