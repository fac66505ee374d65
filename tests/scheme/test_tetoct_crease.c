/* test_tetoct_crease.c — tet/oct's crease surfaces are Loop surfaces (the
 * paper's figure 8: "a crease surface defined by Loop subdivision"; issue 38).
 *
 * A jittered 2 x 2 x 2 Kuhn cube (48 tets) with its boundary triangles as
 * triangle cells, refined twice by tetoct, against the same triangles alone
 * (the volume's vertices, no tets) refined twice by the `loop` scheme — a
 * second code path (ss_scheme_loop.c's own rule, which sends its rows in
 * passes, not ss_loop_surface's row by row):
 *   - every point of the Loop surface is a point of tetoct's triangles, to
 *     1e-13 of the cube's size, and the counts agree (the boundary of the
 *     refined volume is the refined boundary surface);
 *   - the same with a crease curve (the square round the bottom face as
 *     segment cells) and corners (its four corners as vertex cells):
 *     Hoppe's conventions agree with tetoct's segment and vertex rules;
 *   - the averaging triangle mask (the family's, data/stencils/tetoct.ini) is
 *     not Loop: it misses points by more than 1e-3 (so the comparison can
 *     fail);
 *   - one level: the vertices off the surface are where the volume without
 *     triangle cells puts them, bit for bit (the surface rows touch only the
 *     surface). */
#include <stdlib.h>
#include <string.h>

#include "ss_scheme.h"
#include "ss_stencil.h"
#include "ss_test.h"
#include "ss_testmesh.h"

/* Add the triangles, and with creases the square round the bottom face
 * (grid edges with z = 0 and one more coordinate at 0 or N) as segments and
 * its four corners as vertex cells; grid: the unjittered positions.  The top
 * corners and the other cube edges stay smooth, so the surface keeps
 * vertices of valence other than 6 (where the masks differ). */
static void add_surface(ss_cx *cx, const ss_idx *tri, size_t ntri, int creases, int N,
                        const double *grid) {
  ss_error err = {0};
  for (size_t i = 0; i < ntri; i++)
    REQUIRE_OK_VOID(ss_cx_add_cell(cx, SS_TRIANGLE, tri + 3 * i, 0, &err), &err);
  if (!creases) return;
  const size_t nv = (size_t)(N + 1) * (size_t)(N + 1) * (size_t)(N + 1);
  for (size_t a = 0; a < nv; a++) {
    const double *p = grid + 3 * a;
    const int xo = p[0] == 0.0 || p[0] == (double)N,
              yo = p[1] == 0.0 || p[1] == (double)N;
    if (xo && yo && p[2] == 0.0) {
      ss_idx v = (ss_idx)a;
      REQUIRE_OK_VOID(ss_cx_add_cell(cx, SS_VERTEX, &v, 0, &err), &err);
    }
    for (size_t b = a + 1; b < nv; b++) { /* a grid edge of the bottom square */
      const double *q = grid + 3 * b;
      if (p[2] != 0.0 || q[2] != 0.0) continue;
      const int alongx =
          p[1] == q[1] && (p[1] == 0.0 || p[1] == (double)N) && fabs(p[0] - q[0]) == 1.0;
      const int alongy =
          p[0] == q[0] && (p[0] == 0.0 || p[0] == (double)N) && fabs(p[1] - q[1]) == 1.0;
      if (alongx || alongy) {
        ss_idx s[2] = {(ss_idx)a, (ss_idx)b};
        REQUIRE_OK_VOID(ss_cx_add_cell(cx, SS_SEGMENT, s, 0, &err), &err);
      }
    }
  }
}

static ss_cx *refine(const char *scheme, const ss_scheme *own, const ss_cx *cx,
                     int levels) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  if (!own && ss_scheme_new(scheme, &s, &err)) {
    CHECK(0, "%s: %s", scheme, err.msg);
    return NULL;
  }
  ss_cx *a = tm_refined(own ? own : s, cx, levels, &err);
  CHECK(a, "%s %s", scheme, err.msg);
  ss_scheme_free(s);
  return a;
}

/* The largest distance from a point of S's triangles to the nearest point of
 * V's triangles; *nS, *nV their counts. */
static double surface_gap(const ss_cx *V, const ss_cx *S, size_t *nS, size_t *nV) {
  unsigned char *onV = calloc(V->nv + 1, 1), *onS = calloc(S->nv + 1, 1);
  for (size_t i = 0; i < 3 * V->nc[SS_TRIANGLE]; i++)
    onV[V->cells[SS_TRIANGLE][i]] = 1;
  for (size_t i = 0; i < 3 * S->nc[SS_TRIANGLE]; i++)
    onS[S->cells[SS_TRIANGLE][i]] = 1;
  *nS = *nV = 0;
  for (size_t v = 0; v < V->nv; v++)
    *nV += onV[v];
  double worst = 0.0;
  for (size_t s = 0; s < S->nv; s++) {
    if (!onS[s]) continue;
    ++*nS;
    double best = INFINITY;
    for (size_t v = 0; v < V->nv; v++) {
      if (!onV[v]) continue;
      double d = 0.0;
      for (int k = 0; k < 3; k++)
        d = fmax(d, fabs(S->x[3 * s + (size_t)k] - V->x[3 * v + (size_t)k]));
      best = fmin(best, d);
    }
    worst = fmax(worst, best);
  }
  free(onV);
  free(onS);
  return worst;
}

static void test_loop_surface(const char *stencils, int creases) {
  const int N = 2;
  ss_error err = {0};
  ss_cx *vol = tm_kuhn(N);
  double *grid = malloc(3 * vol->nv * sizeof *grid);
  memcpy(grid, vol->x, 3 * vol->nv * sizeof *grid);
  tm_jitter(vol, 0.08, 11);
  ss_idx *tri = NULL;
  const size_t ntri = tm_boundary_faces(vol, &tri);
  CHECK(ntri == 6u * 2u * (size_t)(N * N), "boundary triangles: %zu", ntri);
  ss_cx *surf = NULL;
  REQUIRE_OK_VOID(ss_cx_new(3, &surf, &err), &err);
  for (size_t v = 0; v < vol->nv; v++)
    REQUIRE_OK_VOID(ss_cx_add_vertex(surf, vol->x + 3 * v, 0, &err), &err);
  add_surface(surf, tri, ntri, creases, N, grid);
  add_surface(vol, tri, ntri, creases, N, grid);
  const char *what = creases ? "with a crease curve and corners" : "closed";

  ss_cx *V = refine("tetoct", NULL, vol, 2), *S = refine("loop", NULL, surf, 2);
  if (V && S) {
    size_t nS, nV;
    const double gap = surface_gap(V, S, &nS, &nV);
    CHECK(nS == nV && nS > 0, "%s: %zu Loop points, %zu on tetoct's triangles", what, nS,
          nV);
    CHECK(gap <= 1e-13 * N, "%s: a Loop point is %.3g from tetoct's surface", what, gap);
    printf("%s: %zu surface points, largest gap to Loop %.2g\n", what, nS, gap);
  }
  /* the averaging triangle mask (data/stencils/tetoct.ini) is not Loop's */
  char path[4096];
  snprintf(path, sizeof path, "%s/tetoct.ini", stencils);
  ss_scheme *avg = NULL;
  uint64_t id = 0;
  REQUIRE_OK_VOID(ss_stencil_load(path, &avg, &id, &err), &err);
  ss_cx *A = refine("tetoct.ini", avg, vol, 2);
  if (A && S) {
    size_t nS, nA;
    const double gap = surface_gap(A, S, &nS, &nA);
    CHECK(gap > 1e-3, "%s: the averaging mask is within %.3g of Loop", what, gap);
    printf("%s: the averaging triangle mask misses Loop by %.3g\n", what, gap);
  }
  /* one level: off the surface, as without triangles */
  if (!creases) {
    ss_cx *plain = tm_kuhn(N);
    memcpy(plain->x, vol->x, 3 * vol->nv * sizeof *plain->x);
    ss_cx *P1 = refine("tetoct", NULL, plain, 1), *V1 = refine("tetoct", NULL, vol, 1);
    if (P1 && V1 && P1->nv == V1->nv) {
      unsigned char *on = calloc(V1->nv + 1, 1);
      for (size_t i = 0; i < 3 * V1->nc[SS_TRIANGLE]; i++)
        on[V1->cells[SS_TRIANGLE][i]] = 1;
      size_t off, same; /* the split numbers edges in another order */
      tm_points_in(P1, V1, on, &off, &same);
      CHECK(off > 0 && same == off, "%zu of %zu interior points as without triangles",
            same, off);
      free(on);
    } else {
      CHECK(0, "one level: %zu and %zu vertices", P1 ? P1->nv : 0, V1 ? V1->nv : 0);
    }
    ss_cx_free(P1);
    ss_cx_free(V1);
    ss_cx_free(plain);
  }
  ss_cx_free(A);
  ss_scheme_free(avg);
  ss_cx_free(V);
  ss_cx_free(S);
  ss_cx_free(surf);
  ss_cx_free(vol);
  free(tri);
  free(grid);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_tetoct_crease DATA/STENCILS\n");
    return 2;
  }
  test_loop_surface(argv[1], 0);
  test_loop_surface(argv[1], 1);
  return ss_test_done("tetoct_crease");
}
