/* test_case.c — cases (analysis/case/ss_case.h): names, the 4-8 class, the
 * centre's level, the star's cell type and the star itself.
 *
 * Properties: every kind has its own name (the store and the tables key on
 * it); the 4-8 class follows Velho & Gomes's rule (4 below valence 6 and for
 * odd valences, 8 for even valences from 6 on) and keeps an explicit class;
 * the centre is born on level 0 (vertices), 1 (edge midpoints) or 2 (the face
 * point); each split gives its own cell type and refuses the cases it has
 * none of; and the stars have the sizes their combinatorics give: a vertex
 * with a k-vertex link has 2k - 4 cells (one per link triangle), 6k - 9 hex
 * vertices (centre, k rays, 3k - 6 edge sectors, 2k - 4 far corners) or
 * k + 1 tet vertices; n cells around an edge, 4n + 2 hex or n + 2 tet
 * vertices; two tets and five vertices at the face; n quads and 2n + 1
 * vertices or n triangles and n + 1 vertices at a surface vertex. */
#include <string.h>

#include "ss_case.h"
#include "ss_link.h"
#include "ss_test.h"

static void test_names(void) {
  for (int a = 0; a < SS_NCASEKINDS; a++) {
    const char *na = ss_case_name((ss_case_kind)a);
    CHECK(strcmp(na, "?") != 0, "kind %d has no name", a);
    for (int b = 0; b < a; b++)
      CHECK(strcmp(na, ss_case_name((ss_case_kind)b)) != 0, "kinds %d and %d: %s", a, b,
            na);
  }
  CHECK(!strcmp(ss_case_name(SS_CASE_SURFACE_VERTEX), "surface-vertex"), "%s",
        ss_case_name(SS_CASE_SURFACE_VERTEX));
  CHECK(!strcmp(ss_case_name((ss_case_kind)SS_NCASEKINDS), "?"), "an unknown kind");
  /* parsing: the command line's and the store's names, each back to its kind;
   * anything else refused, *out untouched */
  const char *names[] = {"vertex", "edge", "face", "surface-vertex", "edge-point"};
  const ss_case_kind kinds[] = {SS_CASE_VERTEX, SS_CASE_EDGE, SS_CASE_FACE,
                                SS_CASE_SURFACE_VERTEX, SS_CASE_EDGE_POINT};
  for (int i = 0; i < 5; i++) {
    ss_case_kind k = (ss_case_kind)-1;
    CHECK(!ss_case_kind_parse(names[i], &k) && k == kinds[i], "parse %s: %d", names[i],
          (int)k);
  }
  const char *bad[] = {"", "Vertex", "surface vertex", "edge ", "?", "edges"};
  for (int i = 0; i < 6; i++) {
    ss_case_kind k = SS_CASE_FACE;
    CHECK(ss_case_kind_parse(bad[i], &k) == -1 && k == SS_CASE_FACE, "'%s' accepted",
          bad[i]);
  }
}

static void test_class48(void) {
  for (int n = 3; n <= 20; n++) {
    const int want = n >= 6 && n % 2 == 0 ? 8 : 4;
    CHECK(ss_case_class48(n, 0) == want, "valence %d: class %d", n,
          ss_case_class48(n, 0));
    CHECK(ss_case_class48(n, 4) == 4 && ss_case_class48(n, 8) == 8, "valence %d", n);
  }
  CHECK(ss_case_centre_level(SS_CASE_VERTEX) == 0 &&
            ss_case_centre_level(SS_CASE_SURFACE_VERTEX) == 0 &&
            ss_case_centre_level(SS_CASE_EDGE) == 1 &&
            ss_case_centre_level(SS_CASE_FACE) == 2,
        "centre levels");
}

/* The cell type of kind under scheme name: want, or -1 for SS_EINPUT. */
static void check_cell(const char *name, ss_case_kind kind, int want) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_scheme_new(name, &s, &err), &err);
  ss_cell_type t = SS_NCELLTYPES;
  const ss_status st = ss_case_cell(s, kind, &t, &err);
  if (want < 0)
    CHECK(st == SS_EINPUT, "%s %s: status %d", name, ss_case_name(kind), (int)st);
  else
    CHECK(st == SS_OK && (int)t == want, "%s %s: status %d, cell %d", name,
          ss_case_name(kind), (int)st, (int)t);
  ss_scheme_free(s);
}

static void test_cells(void) {
  check_cell("mlca", SS_CASE_VERTEX, SS_HEX);
  check_cell("mlca", SS_CASE_EDGE, SS_HEX);
  check_cell("mlca", SS_CASE_FACE, -1);
  check_cell("tetoct", SS_CASE_VERTEX, SS_TET);
  check_cell("tetoct", SS_CASE_EDGE, SS_TET);
  check_cell("tetoct", SS_CASE_FACE, SS_TET);
  check_cell("tetoct", SS_CASE_SURFACE_VERTEX, SS_TRIANGLE);
  check_cell("catmull-clark", SS_CASE_SURFACE_VERTEX, SS_QUAD);
  check_cell("catmull-clark", SS_CASE_VERTEX, -1);
  check_cell("loop", SS_CASE_SURFACE_VERTEX, SS_TRIANGLE);
  check_cell("loop", SS_CASE_EDGE, -1);
  check_cell("mlca", SS_CASE_EDGE_POINT, -1);
}

/* The star of case c under scheme name has ncells cells of type t and nv
 * vertices. */
static void check_star(const char *name, const ss_case *c, ss_cell_type t, size_t ncells,
                       size_t nv) {
  ss_scheme *s = NULL;
  ss_star *star = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_scheme_new(name, &s, &err), &err);
  if (ss_case_star(s, c, &star, &err)) {
    CHECK(0, "%s %s %d: %s", name, ss_case_name(c->kind), c->n, err.msg);
  } else {
    CHECK(star->cx->nc[t] == ncells && ss_cx_ncells(star->cx) == ncells &&
              star->cx->nv == nv,
          "%s %s %d: %zu cells, %zu vertices; want %zu and %zu", name,
          ss_case_name(c->kind), c->n, ss_cx_ncells(star->cx), star->cx->nv, ncells, nv);
  }
  ss_star_free(star);
  ss_scheme_free(s);
}

static void test_stars(void) {
  static const char *const links[] = {"octahedron", "bipyramid:5", "icosahedron"};
  for (int i = 0; i < 3; i++) {
    ss_link *l = NULL;
    ss_error err = {0};
    REQUIRE_OK_VOID(ss_link_named(links[i], &l, &err), &err);
    const size_t k = (size_t)l->k;
    const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
    check_star("mlca", &c, SS_HEX, 2 * k - 4, 6 * k - 9);
    check_star("tetoct", &c, SS_TET, 2 * k - 4, k + 1);
    ss_link_free(l);
  }
  for (size_t n = 3; n <= 7; n++) {
    const ss_case e = {SS_CASE_EDGE, NULL, (int)n, SS_DIAG_BFS, 0};
    check_star("mlca", &e, SS_HEX, n, 4 * n + 2);
    check_star("tetoct", &e, SS_TET, n, n + 2);
    const ss_case v = {SS_CASE_SURFACE_VERTEX, NULL, (int)n, SS_DIAG_BFS, 0};
    check_star("catmull-clark", &v, SS_QUAD, n, 2 * n + 1);
    check_star("loop", &v, SS_TRIANGLE, n, n + 1);
  }
  const ss_case f = {SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0};
  check_star("tetoct", &f, SS_TET, 2, 5);
  /* what a case cannot be: a vertex without a link, skew diagonals away from
   * an edge, a 4-8 class outside quasi48 */
  ss_scheme *s = NULL;
  ss_star *star = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_scheme_new("boxspline", &s, &err), &err);
  const ss_case bad[] = {{SS_CASE_VERTEX, NULL, 0, SS_DIAG_BFS, 0},
                         {SS_CASE_FACE, NULL, 0, SS_DIAG_SKEW, 0}};
  for (int i = 0; i < 2; i++) {
    CHECK(ss_case_star(s, bad + i, &star, &err) == SS_EINPUT && !star, "bad case %d", i);
    ss_star_free(star);
    star = NULL;
  }
  const ss_case skew = {SS_CASE_EDGE, NULL, 5, SS_DIAG_SKEW, 0};
  CHECK(ss_case_star(s, &skew, &star, &err) == SS_OK, "skew edge: %s", err.msg);
  ss_star_free(star);
  star = NULL;
  ss_scheme_free(s);
  /* tet/oct's rule reads no diagonals: a choice would only relabel its star
   * (issue 35), so anything but the default is refused */
  REQUIRE_OK_VOID(ss_scheme_new("tetoct", &s, &err), &err);
  const ss_case tskew = {SS_CASE_EDGE, NULL, 5, SS_DIAG_SKEW, 0},
                tproper = {SS_CASE_VERTEX, NULL, 0, SS_DIAG_PROPER, 0};
  ss_link *oct = NULL;
  REQUIRE_OK_VOID(ss_link_named("octahedron", &oct, &err), &err);
  ss_case tp = tproper;
  tp.link = oct;
  CHECK(ss_case_star(s, &tskew, &star, &err) == SS_EINPUT && !star &&
            strstr(err.msg, "does not read major diagonals"),
        "tetoct edge with skew diagonals refused: %s", err.msg);
  CHECK(ss_case_star(s, &tp, &star, &err) == SS_EINPUT && !star,
        "tetoct vertex with proper diagonals refused");
  ss_link_free(oct);
  ss_scheme_free(s);
  REQUIRE_OK_VOID(ss_scheme_new("loop", &s, &err), &err);
  const ss_case cls = {SS_CASE_SURFACE_VERTEX, NULL, 6, SS_DIAG_BFS, 8};
  CHECK(ss_case_star(s, &cls, &star, &err) == SS_EINPUT && !star,
        "a class outside quasi48");
  ss_star_free(star);
  ss_scheme_free(s);
}

int main(void) {
  test_names();
  test_class48();
  test_cells();
  test_stars();
  return ss_test_done("case");
}
