/* test_cx.c — cell tables, orientation conventions, the inverted-cell check,
 * validation and the hash table. */
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>

#include "ss_cx.h"
#include "ss_hash.h"
#include "ss_test.h"

static void test_tables(void) {
  /* roles: a cube's role is the dimension of the smallest face holding both;
   * count vertices per role as the binomial coefficients C(d, r) */
  int hex[4] = {0}, quad[3] = {0}, oct[3] = {0};
  for (int j = 0; j < 8; j++)
    hex[ss_cell_role(SS_HEX, 0, j)]++;
  for (int j = 0; j < 4; j++)
    quad[ss_cell_role(SS_QUAD, 2, j)]++;
  for (int j = 0; j < 6; j++)
    oct[ss_cell_role(SS_OCT, 4, j)]++;
  CHECK(hex[0] == 1 && hex[1] == 3 && hex[2] == 3 && hex[3] == 1, "hex roles");
  CHECK(quad[0] == 1 && quad[1] == 2 && quad[2] == 1, "quad roles");
  CHECK(oct[0] == 1 && oct[1] == 4 && oct[2] == 1, "octahedron roles");
  /* edges are exactly the role-1 pairs */
  for (int t = SS_SEGMENT; t < SS_NCELLTYPES; t++) {
    int n = ss_cell_nverts((ss_cell_type)t), role1 = 0;
    for (int i = 0; i < n; i++)
      for (int j = i + 1; j < n; j++)
        role1 += ss_cell_role((ss_cell_type)t, i, j) == 1;
    CHECK(role1 == ss_cell_nedges((ss_cell_type)t), "%s: %d role-1 pairs, %d edges",
          ss_cell_name((ss_cell_type)t), role1, ss_cell_nedges((ss_cell_type)t));
    for (int e = 0; e < ss_cell_nedges((ss_cell_type)t); e++) {
      int a, b;
      ss_cell_edge((ss_cell_type)t, e, &a, &b);
      CHECK(ss_cell_role((ss_cell_type)t, a, b) == 1, "%s edge %d",
            ss_cell_name((ss_cell_type)t), e);
    }
  }
  for (int d = 1; d <= 3; d++)
    for (int k = 0; k < (1 << d); k++)
      CHECK(ss_cube_corner_index(d, ss_cube_corner_bits(d, k)) == k, "corner bits d=%d",
            d);
}

static ss_cx *cell(ss_cell_type t, int dim, const double *x, int nv) {
  ss_cx *cx = NULL;
  ss_error err = {0};
  ss_cx_new(dim, &cx, &err);
  for (int i = 0; i < nv; i++)
    ss_cx_add_vertex(cx, x + dim * i, 0, &err);
  ss_idx v[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  ss_cx_add_cell(cx, t, v, 0, &err);
  return cx;
}

static void test_orientation(void) {
  const double tet[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double hex[] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0,
                        0, 0, 3, 2, 0, 3, 2, 1, 3, 0, 1, 3};
  const double oct[] = {1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
  double v;
  ss_cx *c = cell(SS_TET, 3, tet, 4);
  CHECK(ss_cx_cell_orientation(c, SS_TET, 0, &v) == 1, "unit tet");
  CHECK_CLOSE(v, 1.0 / 6, 1e-15, "unit tet volume");
  ss_cx_free(c);
  c = cell(SS_HEX, 3, hex, 8);
  CHECK(ss_cx_cell_orientation(c, SS_HEX, 0, &v) == 1, "box hex");
  CHECK_CLOSE(v, 6.0, 1e-14, "2x1x3 box volume");
  /* swapping bottom and top inverts it */
  ss_idx *h = ss_cx_cell(c, SS_HEX, 0);
  ss_idx sw[8] = {4, 5, 6, 7, 0, 1, 2, 3};
  memcpy(h, sw, sizeof sw);
  CHECK(ss_cx_cell_orientation(c, SS_HEX, 0, &v) == -1 && v < 0, "inverted hex");
  ss_cx_free(c);
  c = cell(SS_OCT, 3, oct, 6);
  CHECK(ss_cx_cell_orientation(c, SS_OCT, 0, &v) == 1, "canonical octahedron");
  CHECK_CLOSE(v, 4.0 / 3, 1e-15, "octahedron volume");
  ss_cx_free(c);
  /* a hex folded through itself: one corner pushed past the opposite face */
  double folded[24];
  memcpy(folded, hex, sizeof folded);
  folded[3 * 6 + 2] = -1.0; /* corner 6 below the bottom face */
  c = cell(SS_HEX, 3, folded, 8);
  CHECK(ss_cx_cell_orientation(c, SS_HEX, 0, NULL) == 0, "folded hex has mixed corners");
  ss_error err = {0};
  CHECK(ss_cx_check_orientation(c, &err) == SS_EINPUT && strstr(err.msg, "folded"),
        "folded hex rejected: %s", err.msg);
  ss_cx_free(c);
}

static void test_inverted(void) {
  /* two tets sharing a face, the second listed with the wrong orientation */
  ss_cx *c = NULL;
  ss_error err = {0};
  ss_cx_new(3, &c, &err);
  const double x[5][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 5; i++)
    ss_cx_add_vertex(c, x[i], 0, &err);
  ss_idx a[4] = {0, 1, 2, 3}, b[4] = {0, 1, 2, 4}, b2[4] = {0, 2, 1, 4};
  ss_cx_add_cell(c, SS_TET, a, 0, &err);
  ss_cx_add_cell(c, SS_TET, b, 0, &err);
  ss_cx_add_cell(c, SS_TET, b2, 0, &err);
  CHECK(ss_cx_check_orientation(c, &err) == SS_EINPUT &&
            strstr(err.msg, "tetrahedron 2") && strstr(err.msg, "inverted"),
        "inverted tet named: %s", err.msg);
  ss_cx_free(c);
}

static void test_validate(void) {
  ss_cx *c = NULL;
  ss_error err = {0};
  ss_cx_new(2, &c, &err);
  const double x[2] = {0, 0};
  for (int i = 0; i < 3; i++)
    ss_cx_add_vertex(c, x, 0, &err);
  ss_idx t[3] = {0, 1, 5};
  ss_cx_add_cell(c, SS_TRIANGLE, t, 0, &err);
  CHECK(ss_cx_validate(c, &err) == SS_EINPUT && strstr(err.msg, "out of range"),
        "index out of range: %s", err.msg);
  ss_cx_free(c);
  CHECK(ss_cx_new(SS_MAXDIM + 1, &c, &err) == SS_EINPUT && c == NULL,
        "dimension SS_MAXDIM + 1 rejected");
  CHECK(ss_cx_new(0, &c, &err) == SS_EINPUT && c == NULL, "dimension 0 rejected");
  CHECK(ss_cx_new(SS_MAXDIM, &c, &err) == SS_OK && c && c->dim == SS_MAXDIM,
        "dimension SS_MAXDIM (3 + 13 fields) taken");
  ss_cx_free(c);
}

static void test_hash(void) {
  ss_hash *h = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_hash_new(3, 4, &h, &err), &err); /* grows many times */
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 5);
  enum { N = 50000 };
  static uint32_t keys[N][3];
  size_t inserted = 0;
  for (int i = 0; i < N; i++) {
    for (int j = 0; j < 3; j++)
      keys[i][j] = (uint32_t)gsl_rng_uniform_int(r, 40);
    uint32_t got;
    int ins;
    REQUIRE_OK_VOID(ss_hash_insert(h, keys[i], (uint32_t)i, &got, &ins, &err), &err);
    inserted += (size_t)ins;
  }
  /* 40^3 = 64000 possible keys: count distinct ones independently */
  static unsigned char seen[40 * 40 * 40];
  size_t distinct = 0, wrong = 0;
  for (int i = 0; i < N; i++) {
    size_t k = keys[i][0] + 40u * keys[i][1] + 1600u * keys[i][2];
    if (!seen[k]) {
      seen[k] = 1;
      distinct++;
      wrong += ss_hash_find(h, keys[i]) != (uint32_t)i; /* first insertion wins */
    }
  }
  CHECK(inserted == distinct && ss_hash_size(h) == distinct,
        "hash: %zu inserted, %zu distinct keys", inserted, distinct);
  CHECK(wrong == 0, "hash: %zu keys map to the wrong value", wrong);
  uint32_t absent[3] = {99, 99, 99};
  CHECK(ss_hash_find(h, absent) == UINT32_MAX, "absent key found");
  gsl_rng_free(r);
  ss_hash_free(h);
}

int main(void) {
  gsl_set_error_handler_off();
  test_tables();
  test_orientation();
  test_inverted();
  test_validate();
  test_hash();
  return ss_test_done("cx");
}
