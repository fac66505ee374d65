/* test_meshlinks.c — vertex links and edge valences of volume meshes, against
 * answers derived by hand:
 *   - hex grids (open N^3 block and periodic): every interior vertex has the
 *     octahedron as link, every interior edge 4 hexes;
 *   - the Kuhn-subdivided cube grid: every interior vertex has 14 edges
 *     (±e_i, ±(e_i + e_j) for i < j, ±(1,1,1)) and the tetrakis hexahedron
 *     as link; axis edges and main diagonals have 6 tets, face diagonals 4;
 *   - tet and hex stars of named links: the centre's link is the named link;
 *   - invariance under relabelling; non-manifold vertices and edges; bad
 *     input (mixed, cell-less, octahedra, dangling indices). */
#include <stdlib.h>
#include <string.h>

#include "ss_link.h"
#include "ss_meshlinks.h"
#include "ss_test.h"
#include "ss_testmesh.h"

/* Canonical plantri text of a link (malloc'd), or NULL after a failed check. */
static char *canonical_text(const ss_link *l) {
  ss_error err = {0};
  ss_link *c = NULL;
  char *text = NULL;
  if (ss_link_canonical(l, &c, NULL, &err) || ss_link_format(c, &text, &err))
    fprintf(stderr, "canonical_text: %s\n", err.msg);
  ss_link_free(c);
  return text;
}

static char *named_canonical(const char *name) {
  ss_error err = {0};
  ss_link *l = NULL;
  if (ss_link_named(name, &l, &err)) {
    fprintf(stderr, "%s: %s\n", name, err.msg);
    return NULL;
  }
  char *t = canonical_text(l);
  ss_link_free(l);
  return t;
}

/* The tetrakis hexahedron: a cube (corners 0..7 by binary coordinates) with a
 * pyramid on every face (apexes 8..13): 8 vertices of degree 6, 6 of degree 4. */
static char *tetrakis_canonical(void) {
  int tri[24 * 3], n = 0;
  static const int cyc[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 3; i++)
    for (int side = 0; side < 2; side++) {
      int j = (i + 1) % 3, k = (i + 2) % 3, c[4];
      for (int q = 0; q < 4; q++)
        c[q] = (side << i) | (cyc[q][0] << j) | (cyc[q][1] << k);
      for (int q = 0; q < 4; q++) {
        tri[n++] = 8 + 2 * i + side;
        tri[n++] = c[q];
        tri[n++] = c[(q + 1) % 4];
      }
    }
  ss_error err = {0};
  ss_link *l = NULL;
  if (ss_link_from_triangles(14, 24, tri, &l, &err)) {
    fprintf(stderr, "tetrakis: %s\n", err.msg);
    return NULL;
  }
  char *t = canonical_text(l);
  ss_link_free(l);
  return t;
}

/* An open grid of N^3 unit hexes on (N+1)^3 vertices. */
static ss_cx *hex_block(int N) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  const int M = N + 1;
  if (ss_cx_new(3, &cx, &err)) return NULL;
  for (int v = 0; v < M * M * M; v++) {
    double x[3] = {v % M, (v / M) % M, v / (M * M)};
    if (ss_cx_add_vertex(cx, x, 0, &err)) goto fail;
  }
  for (int c = 0; c < N * N * N; c++) {
    int base[3] = {c % N, (c / N) % N, c / (N * N)};
    ss_idx h[8];
    for (int q = 0; q < 8; q++) {
      unsigned b = ss_cube_corner_bits(3, q);
      h[q] = (ss_idx)((base[0] + (int)(b & 1u)) + M * (base[1] + (int)((b >> 1) & 1u)) +
                      M * M * (base[2] + (int)((b >> 2) & 1u)));
    }
    if (ss_cx_add_cell(cx, SS_HEX, h, 0, &err)) goto fail;
  }
  return cx;
fail:
  ss_cx_free(cx);
  return NULL;
}

/* Checks shared by every result: classes and histograms add up. */
static void check_consistent(const ss_meshlinks *ml, const char *what) {
  CHECK(ml->nv_interior + ml->nv_boundary + ml->nv_nonmanifold + ml->nv_unused == ml->nv,
        "%s: vertex classes sum to %zu", what, ml->nv);
  CHECK(ml->ne_interior + ml->ne_boundary + ml->ne_nonmanifold == ml->ne,
        "%s: edge classes sum to %zu", what, ml->ne);
  size_t nl = 0, nh = 0, ne = 0;
  double vs = 0, es = 0;
  for (size_t i = 0; i < ml->nlinks; i++) {
    nl += ml->links[i].count;
    if (i) CHECK(ml->links[i].count <= ml->links[i - 1].count, "%s: links sorted", what);
  }
  for (int k = 0; k <= ml->vval_max; k++)
    nh += ml->vval_hist[k], vs += (double)k * (double)ml->vval_hist[k];
  for (int k = 0; k <= ml->eval_max; k++)
    ne += ml->eval_hist[k], es += (double)k * (double)ml->eval_hist[k];
  CHECK(nl == ml->nv_interior, "%s: link multiplicities sum to %zu, not %zu", what, nl,
        ml->nv_interior);
  CHECK(nh == ml->nv_interior, "%s: vertex histogram", what);
  CHECK(ne == ml->ne_interior, "%s: edge histogram", what);
  if (ml->nv_interior) CHECK_CLOSE(ml->vval_mean, vs / (double)nh, 1e-12, "%s", what);
  if (ml->ne_interior) CHECK_CLOSE(ml->eval_mean, es / (double)ne, 1e-12, "%s", what);
}

static void test_hex_grids(void) {
  ss_error err = {0};
  char *oct = named_canonical("octahedron");
  const int N = 4;
  ss_cx *cx = hex_block(N);
  ss_meshlinks *ml = NULL;
  CHECK(cx != NULL, "hex block");
  if (!cx) return;
  REQUIRE_OK_VOID(ss_meshlinks_compute(cx, &ml, &err), &err);
  check_consistent(ml, "hex block");
  CHECK(ml->cell_type == SS_HEX, "cell type");
  CHECK(ml->nv == 125 && ml->nc == 64, "nv %zu nc %zu", ml->nv, ml->nc);
  CHECK(ml->nv_interior == 27 && ml->nv_boundary == 98, "interior %zu boundary %zu",
        ml->nv_interior, ml->nv_boundary);
  CHECK(ml->nv_nonmanifold == 0 && ml->nv_unused == 0, "no odd vertices");
  /* edges: 3 N (N+1)^2, interior ones have both transverse coordinates inside */
  CHECK(ml->ne == 300, "edges %zu", ml->ne);
  CHECK(ml->ne_interior == (size_t)(3 * N * (N - 1) * (N - 1)), "interior edges %zu",
        ml->ne_interior);
  CHECK(ml->ne_boundary == 300 - 108 && ml->ne_nonmanifold == 0, "boundary edges %zu",
        ml->ne_boundary);
  CHECK(ml->eval_max == 4 && ml->eval_hist[4] == 108, "edge valence max %d",
        ml->eval_max);
  CHECK(ml->vval_max == 6 && ml->vval_mean == 6.0, "vertex valence %g", ml->vval_mean);
  CHECK(ml->nlinks == 1, "one distinct link, not %zu", ml->nlinks);
  if (ml->nlinks == 1 && oct) {
    CHECK(!strcmp(ml->links[0].link, oct), "octahedron: %s", ml->links[0].link);
    CHECK(ml->links[0].count == 27 && ml->links[0].k == 6, "count %zu",
          ml->links[0].count);
    /* the first interior vertex is (1,1,1) */
    CHECK(ml->links[0].first_vertex == 1 + 5 + 25, "first vertex %zu",
          ml->links[0].first_vertex);
  }
  ss_meshlinks_free(ml);
  ml = NULL;
  ss_cx_free(cx);

  /* periodic: no boundary at all */
  cx = tm_torus(3, 3);
  REQUIRE_OK_VOID(ss_meshlinks_compute(cx, &ml, &err), &err);
  check_consistent(ml, "hex torus");
  CHECK(ml->nv_interior == 27 && ml->ne == 81 && ml->ne_interior == 81,
        "torus: %zu interior vertices, %zu/%zu interior edges", ml->nv_interior,
        ml->ne_interior, ml->ne);
  CHECK(ml->eval_mean == 4.0 && ml->nlinks == 1, "torus edge valence %g", ml->eval_mean);
  if (ml->nlinks == 1 && oct) CHECK(!strcmp(ml->links[0].link, oct), "torus link");
  ss_meshlinks_free(ml);
  ss_cx_free(cx);
  free(oct);
}

static void test_kuhn(void) {
  ss_error err = {0};
  char *tk = tetrakis_canonical();
  CHECK(tk != NULL, "tetrakis hexahedron builds");
  for (int N = 2; N <= 4; N++) {
    ss_cx *cx = tm_kuhn(N);
    ss_meshlinks *ml = NULL;
    REQUIRE_OK_VOID(ss_meshlinks_compute(cx, &ml, &err), &err);
    check_consistent(ml, "kuhn");
    const size_t M = (size_t)N + 1, n = (size_t)N;
    CHECK(ml->cell_type == SS_TET && ml->nc == 6 * n * n * n, "kuhn(%d): %zu tets", N,
          ml->nc);
    CHECK(ml->nv == M * M * M, "kuhn(%d): nv", N);
    CHECK(ml->nv_interior == (n - 1) * (n - 1) * (n - 1), "kuhn(%d): %zu interior", N,
          ml->nv_interior);
    CHECK(ml->nv_nonmanifold == 0 && ml->nv_unused == 0, "kuhn(%d)", N);
    /* edges: axis 3N(N+1)^2, face diagonals 3N^2(N+1), main diagonals N^3 */
    size_t axis = 3 * n * M * M, face = 3 * n * n * M, body = n * n * n;
    CHECK(ml->ne == axis + face + body, "kuhn(%d): %zu edges", N, ml->ne);
    /* interior: axis edges off the boundary planes, face diagonals off the
     * boundary planes parallel to them, every main diagonal */
    size_t v6 = 3 * n * (n - 1) * (n - 1) + body, v4 = 3 * n * n * (n - 1);
    CHECK(ml->ne_interior == v4 + v6, "kuhn(%d): %zu interior edges", N, ml->ne_interior);
    CHECK(ml->eval_max == 6, "kuhn(%d): max edge valence %d", N, ml->eval_max);
    if (ml->eval_max == 6) {
      CHECK(ml->eval_hist[6] == v6 && ml->eval_hist[4] == v4,
            "kuhn(%d): %zu edges of valence 6, %zu of valence 4", N, ml->eval_hist[6],
            ml->eval_hist[4]);
      CHECK(ml->eval_hist[3] == 0 && ml->eval_hist[5] == 0, "kuhn(%d)", N);
    }
    CHECK_CLOSE(ml->eval_mean, (6.0 * (double)v6 + 4.0 * (double)v4) / (double)(v4 + v6),
                1e-12, "kuhn(%d)", N);
    CHECK(ml->vval_max == 14 && ml->vval_mean == 14.0, "kuhn(%d): vertex valence %g", N,
          ml->vval_mean);
    CHECK(ml->nlinks == 1, "kuhn(%d): %zu distinct links", N, ml->nlinks);
    if (ml->nlinks == 1) {
      ss_link *l = NULL;
      REQUIRE_OK_VOID(ss_link_parse(ml->links[0].link, &l, &err), &err);
      int d4 = 0, d6 = 0;
      for (int v = 0; v < l->k; v++)
        d4 += ss_link_deg(l, v) == 4, d6 += ss_link_deg(l, v) == 6;
      CHECK(l->k == 14 && d4 == 6 && d6 == 8, "kuhn link degrees: %d x4, %d x6", d4, d6);
      ss_link_free(l);
      if (tk)
        CHECK(!strcmp(ml->links[0].link, tk), "kuhn link is the tetrakis hexahedron: %s",
              ml->links[0].link);
    }
    /* relabelling changes nothing */
    ss_cx *p = tm_permuted(cx, 1000u + (unsigned long)N);
    ss_meshlinks *mp = NULL;
    REQUIRE_OK_VOID(ss_meshlinks_compute(p, &mp, &err), &err);
    CHECK(mp->nv_interior == ml->nv_interior && mp->ne_interior == ml->ne_interior &&
              mp->ne == ml->ne && mp->nlinks == ml->nlinks &&
              mp->eval_mean == ml->eval_mean,
          "kuhn(%d) relabelled", N);
    for (size_t i = 0; i < mp->nlinks && i < ml->nlinks; i++)
      CHECK(!strcmp(mp->links[i].link, ml->links[i].link) &&
                mp->links[i].count == ml->links[i].count,
            "kuhn(%d) relabelled: link %zu", N, i);
    ss_meshlinks_free(mp);
    ss_cx_free(p);
    ss_meshlinks_free(ml);
    ss_cx_free(cx);
  }
  free(tk);
}

static void test_stars(void) {
  static const char *const names[] = {"tetrahedron", "octahedron",  "icosahedron",
                                      "bipyramid:3", "bipyramid:5", "bipyramid:9"};
  ss_error err = {0};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
    tm_link *tl = tm_link_named(names[i]);
    char *want = named_canonical(names[i]);
    ss_link *l = NULL;
    REQUIRE_OK_VOID(ss_link_named(names[i], &l, &err), &err);
    for (int hex = 0; hex < 2; hex++) {
      ss_cx *cx = hex ? tm_hex_star(tl) : tm_tet_star(tl);
      ss_meshlinks *ml = NULL;
      REQUIRE_OK_VOID(ss_meshlinks_compute(cx, &ml, &err), &err);
      const char *what = hex ? "hex star" : "tet star";
      check_consistent(ml, what);
      CHECK(ml->nv_interior == 1 && ml->nlinks == 1, "%s of %s: %zu interior", what,
            names[i], ml->nv_interior);
      CHECK(ml->nv_boundary == ml->nv - 1, "%s of %s: boundary", what, names[i]);
      if (ml->nlinks == 1 && want) {
        CHECK(!strcmp(ml->links[0].link, want), "%s of %s: %s", what, names[i],
              ml->links[0].link);
        CHECK(ml->links[0].first_vertex == 0 && ml->links[0].k == tl->k, "%s of %s", what,
              names[i]);
      }
      /* interior edges: the k edges at the centre, valence = link degree */
      CHECK(ml->ne_interior == (size_t)tl->k, "%s of %s: %zu interior edges", what,
            names[i], ml->ne_interior);
      for (int d = 0; d <= ml->eval_max; d++) {
        size_t want_d = 0;
        for (int v = 0; v < l->k; v++)
          want_d += ss_link_deg(l, v) == d;
        CHECK(ml->eval_hist[d] == want_d, "%s of %s: %zu edges of valence %d", what,
              names[i], ml->eval_hist[d], d);
      }
      ss_meshlinks_free(ml);
      ss_cx_free(cx);
    }
    ss_link_free(l);
    free(want);
    tm_link_free(tl);
  }
}

static ss_cx *tets(int nv, int ntet, const ss_idx *t) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  if (ss_cx_new(3, &cx, &err)) return NULL;
  for (int v = 0; v < nv; v++) {
    double x[3] = {v, v * v, v * v * v};
    ss_cx_add_vertex(cx, x, 0, &err);
  }
  for (int i = 0; i < ntet; i++)
    ss_cx_add_cell(cx, SS_TET, t + 4 * i, 0, &err);
  return cx;
}

static void test_nonmanifold(void) {
  ss_error err = {0};
  ss_meshlinks *ml = NULL;
  /* two tetrahedron stars pinched at their common centre 0 */
  static const ss_idx pinch[] = {0, 1, 2, 3, 0, 1, 2, 4, 0, 1, 3, 4, 0, 2, 3, 4,
                                 0, 5, 6, 7, 0, 5, 6, 8, 0, 5, 7, 8, 0, 6, 7, 8};
  ss_cx *cx = tets(10, 8, pinch);
  REQUIRE_OK_VOID(ss_meshlinks_compute(cx, &ml, &err), &err);
  check_consistent(ml, "pinch");
  CHECK(ml->nv_nonmanifold == 1 && ml->nonmanifold[0] == 0 && ml->nv_interior == 0,
        "pinch: %zu non-manifold", ml->nv_nonmanifold);
  CHECK(ml->nv_unused == 1 && ml->nv_boundary == 8, "pinch: %zu unused, %zu boundary",
        ml->nv_unused, ml->nv_boundary);
  CHECK(ml->ne_interior == 8 && ml->ne_nonmanifold == 0, "pinch: edges at the centre");
  ss_meshlinks_free(ml);
  ss_cx_free(cx);

  /* three tets on one triangle: a book with three pages */
  static const ss_idx book[] = {0, 1, 2, 3, 0, 1, 2, 4, 0, 1, 2, 5};
  cx = tets(6, 3, book);
  REQUIRE_OK_VOID(ss_meshlinks_compute(cx, &ml, &err), &err);
  check_consistent(ml, "book");
  CHECK(ml->nv_nonmanifold == 3 && ml->nv_boundary == 3, "book: %zu non-manifold",
        ml->nv_nonmanifold);
  CHECK(ml->ne_nonmanifold == 3 && ml->ne_boundary == 9 && ml->ne_interior == 0,
        "book: %zu non-manifold edges, %zu boundary", ml->ne_nonmanifold,
        ml->ne_boundary);
  ss_meshlinks_free(ml);
  ss_cx_free(cx);
}

static void test_bad_input(void) {
  ss_error err = {0};
  ss_meshlinks *ml = NULL;
  /* mixed */
  ss_cx *cx = hex_block(1);
  ss_idx t[4] = {0, 1, 2, 4}, o[6] = {0, 1, 2, 3, 4, 5};
  ss_cx_add_cell(cx, SS_TET, t, 0, &err);
  CHECK(ss_meshlinks_compute(cx, &ml, &err) == SS_EINPUT && ml == NULL &&
            strstr(err.msg, "mixed"),
        "mixed mesh: %s", err.msg);
  ss_cx_free(cx);
  /* octahedra */
  cx = hex_block(1);
  ss_cx_add_cell(cx, SS_OCT, o, 0, &err);
  err = (ss_error){0};
  CHECK(ss_meshlinks_compute(cx, &ml, &err) == SS_EINPUT && strstr(err.msg, "octahedra"),
        "octahedra: %s", err.msg);
  ss_cx_free(cx);
  /* no volume cells */
  tm_link *tl = tm_link_named("icosahedron");
  cx = tm_link_surface(tl);
  err = (ss_error){0};
  CHECK(ss_meshlinks_compute(cx, &ml, &err) == SS_EINPUT && err.msg[0], "surface: %s",
        err.msg);
  ss_cx_free(cx);
  tm_link_free(tl);
  /* a dangling vertex index */
  static const ss_idx dangling[] = {0, 1, 2, 7};
  cx = tets(4, 1, dangling);
  err = (ss_error){0};
  CHECK(ss_meshlinks_compute(cx, &ml, &err) == SS_EINPUT && err.msg[0], "dangling: %s",
        err.msg);
  ss_cx_free(cx);
  ss_meshlinks_free(NULL);
}

int main(void) {
  test_hex_grids();
  test_kuhn();
  test_stars();
  test_nonmanifold();
  test_bad_input();
  return ss_test_done("meshlinks");
}
