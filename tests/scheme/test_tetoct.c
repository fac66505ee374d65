/* test_tetoct.c — the tet/oct scheme against its paper: cell counts per level,
 * composite rules that are convex combinations (section 2.2), and inside a base
 * tet the composite mask equal to 1/8 of the linear-subdivision mask convolved
 * with itself (appendix A, equation 2), checked in exact lattice coordinates. */
#include <string.h>

#include "ss_optest.h"
#include "ss_split.h"
#include "ss_testmesh.h"

/* Distinct edges of a tet/oct complex, counted by sorting vertex pairs. */
static int cmp_u64(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

static size_t count_edges(const ss_cx *cx) {
  size_t n = 0, cap = 6 * cx->nc[SS_TET] + 12 * cx->nc[SS_OCT];
  uint64_t *e = malloc((cap + 1) * sizeof *e);
  const ss_cell_type types[2] = {SS_TET, SS_OCT};
  for (int ti = 0; ti < 2; ti++) {
    ss_cell_type t = types[ti];
    for (size_t c = 0; c < cx->nc[t]; c++) {
      const ss_idx *v = ss_cx_cell(cx, t, c);
      for (int k = 0; k < ss_cell_nedges(t); k++) {
        int a, b;
        ss_cell_edge(t, k, &a, &b);
        uint64_t lo = v[a] < v[b] ? v[a] : v[b], hi = v[a] < v[b] ? v[b] : v[a];
        e[n++] = lo << 32 | hi;
      }
    }
  }
  qsort(e, n, sizeof *e, cmp_u64);
  size_t distinct = 0;
  for (size_t i = 0; i < n; i++)
    distinct += i == 0 || e[i] != e[i - 1];
  free(e);
  return distinct;
}

static void test_counts(void) {
  ss_cx *cx = tm_kuhn(2);
  ss_error err = {0};
  ss_scheme *s = NULL;
  REQUIRE_OK_VOID(ss_scheme_new("tetoct", &s, &err), &err);
  for (int level = 1; level <= 3; level++) {
    ss_cx *f = NULL;
    REQUIRE_OK_VOID(ss_scheme_refine(s, cx, &f, NULL, &err), &err);
    size_t T = cx->nc[SS_TET], O = cx->nc[SS_OCT];
    size_t V = cx->nv + count_edges(cx) + O;
    CHECK(f->nc[SS_TET] == 4 * T + 8 * O, "level %d: %zu tets, expected 4T+8O = %zu",
          level, f->nc[SS_TET], 4 * T + 8 * O);
    CHECK(f->nc[SS_OCT] == T + 6 * O, "level %d: %zu octahedra, expected T+6O = %zu",
          level, f->nc[SS_OCT], T + 6 * O);
    CHECK(f->nv == V, "level %d: %zu vertices, expected V+E+O = %zu", level, f->nv, V);
    ss_cx_free(cx);
    cx = f;
  }
  ss_cx_free(cx);
  ss_scheme_free(s);
}

/* Smallest entry of R and how many entries are below -tol. */
static void check_convex(const ss_cx *cx, const char *what) {
  gsl_spmatrix *R = NULL;
  ss_cx *f = op_refine("tetoct", cx, &R);
  double lo = 1.0;
  size_t neg = 0;
  for (size_t q = 0; q < R->nz; q++) {
    if (R->data[q] < lo) lo = R->data[q];
    if (R->data[q] < -1e-15) neg++;
  }
  CHECK(neg == 0, "%s: %zu negative weights in the composite rules (smallest %.3g)", what,
        neg, lo);
  check_row_sums(R, what);
  gsl_spmatrix_free(R);
  ss_cx_free(f);
}

static void test_convex(void) {
  ss_cx *k = tm_kuhn(3);
  check_convex(k, "Kuhn 3x3x3");
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *k2 = NULL;
  REQUIRE_OK_VOID(ss_scheme_new("tetoct", &s, &err), &err);
  REQUIRE_OK_VOID(ss_scheme_refine_levels(s, k, 1, &k2, &err), &err);
  check_convex(k2, "Kuhn 3x3x3 after one level (tets and octahedra)");
  ss_cx_free(k2);
  ss_cx_free(k);
  ss_scheme_free(s);
  const char *links[] = {"tetrahedron", "bipyramid:3", "octahedron",
                         "bipyramid:5", "bipyramid:8", "icosahedron"};
  for (size_t i = 0; i < sizeof links / sizeof *links; i++) {
    tm_link *l = tm_link_named(links[i]);
    ss_cx *t = tm_tet_star(l);
    char what[64];
    snprintf(what, sizeof what, "tet star of %s", links[i]);
    check_convex(t, what);
    ss_cx_free(t);
    tm_link_free(l);
  }
}

/* ---- the appendix: composite mask = (1/8) m * m on the lattice M_c ---- */

/* Linear-subdivision mask m of the paper's equation (2), by offset (sum 0). */
static double linear_mask(const int *o) {
  int ones = 0, mones = 0, zeros = 0;
  for (int i = 0; i < 4; i++) {
    ones += o[i] == 1;
    mones += o[i] == -1;
    zeros += o[i] == 0;
  }
  if (zeros == 4) return 1.0;
  if (ones == 1 && mones == 1 && zeros == 2) return 0.5; /* delta */
  if (ones == 2 && mones == 2) return 1.0 / 6.0;         /* gamma */
  return 0.0;
}

/* The 19 offsets where m is nonzero. */
static int mask_support(int (*a)[4]) {
  int n = 0;
  for (int i0 = -1; i0 <= 1; i0++)
    for (int i1 = -1; i1 <= 1; i1++)
      for (int i2 = -1; i2 <= 1; i2++)
        for (int i3 = -1; i3 <= 1; i3++) {
          int o[4] = {i0, i1, i2, i3};
          if (i0 + i1 + i2 + i3 == 0 && linear_mask(o) != 0.0)
            memcpy(a[n++], o, sizeof o);
        }
  return n;
}

static double composite_mask(const int *o, int (*sup)[4], int nsup) {
  double c = 0;
  for (int i = 0; i < nsup; i++) {
    int b[4];
    for (int j = 0; j < 4; j++)
      b[j] = o[j] - sup[i][j];
    c += linear_mask(sup[i]) * linear_mask(b);
  }
  return c / 8.0;
}

static int lattice_key(const int *c) {
  return c[0] + 64 * c[1] + 64 * 64 * c[2] + 64 * 64 * 64 * c[3];
}

static void test_convolution(void) {
  ss_error err = {0};
  /* one base tet in barycentric coordinates (dim 4) */
  ss_cx *base = NULL;
  REQUIRE_OK_VOID(ss_cx_new(4, &base, &err), &err);
  for (int i = 0; i < 4; i++) {
    double x[4] = {0, 0, 0, 0};
    x[i] = 1.0;
    ss_cx_add_vertex(base, x, 0, &err);
  }
  ss_idx t[4] = {0, 1, 2, 3};
  ss_cx_add_cell(base, SS_TET, t, 0, &err);
  /* linear subdivision (every mask "self = 1") keeps exact dyadic positions */
  ss_averaging lin = {.split = SS_SPLIT_TETOCT};
  lin.accepts[SS_TET] = lin.accepts[SS_OCT] = 1;
  lin.mask[SS_TET][0] = lin.mask[SS_OCT][0] = 1.0;
  ss_scheme *linear = NULL, *tetoct = NULL;
  REQUIRE_OK_VOID(ss_scheme_averaging_new("linear", &lin, &linear, &err), &err);
  REQUIRE_OK_VOID(ss_scheme_new("tetoct", &tetoct, &err), &err);
  const int levels = 3, S = 1 << levels; /* coarse lattice: coordinates sum to S */
  ss_cx *coarse = NULL, *lfine = NULL, *fine = NULL;
  ss_split *L = NULL;
  gsl_spmatrix *R = NULL;
  REQUIRE_OK_VOID(ss_scheme_refine_levels(linear, base, levels, &coarse, &err), &err);
  REQUIRE_OK_VOID(ss_scheme_refine(tetoct, coarse, &fine, &R, &err), &err);
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_TETOCT, coarse, &lfine, &L, &err), &err);
  /* coarse lattice coordinates, exactly */
  int *key2idx = malloc((size_t)(64 * 64 * 64 * 64) * sizeof *key2idx);
  for (int i = 0; i < 64 * 64 * 64 * 64; i++)
    key2idx[i] = -1;
  size_t nonint = 0;
  for (size_t v = 0; v < coarse->nv; v++) {
    int c[4];
    for (int j = 0; j < 4; j++) {
      double y = coarse->x[4 * v + (size_t)j] * S;
      c[j] = (int)lround(y);
      nonint += fabs(y - c[j]) > 1e-12; /* v/val summed val times rounds */
    }
    key2idx[lattice_key(c)] = (int)v;
  }
  CHECK(nonint == 0, "%zu coarse coordinates are not lattice points", nonint);
  CHECK(coarse->nv == 165, "level-3 tet has %zu vertices, C(11,3) = 165", coarse->nv);
  int sup[19][4];
  int nsup = mask_support(sup);
  CHECK(nsup == 19, "linear mask support has %d points, the paper's 1 + 12 + 6", nsup);
  size_t tested = 0, bad = 0, missing = 0;
  for (size_t f = 0; f < lfine->nv; f++) {
    int q[4], interior = 1;
    for (int j = 0; j < 4; j++) {
      double y = lfine->x[4 * f + (size_t)j] * 2 * S;
      q[j] = (int)lround(y);
      nonint += fabs(y - q[j]) > 1e-12;
      interior &= q[j] >= 1;
    }
    if (!interior) continue;
    tested++;
    /* every coarse vertex: expected weight c(q - 2p) */
    double total = 0;
    for (size_t p = 0; p < coarse->nv; p++) {
      int o[4];
      for (int j = 0; j < 4; j++)
        o[j] = q[j] - (int)lround(coarse->x[4 * p + (size_t)j] * S) * 2;
      double want = composite_mask(o, sup, nsup), got = gsl_spmatrix_get(R, f, p);
      total += want;
      if (fabs(got - want) > 1e-15) {
        if (bad < 5)
          fprintf(stderr,
                  "fine (%d,%d,%d,%d), coarse %zu: R = %.17g, (1/8) m*m = %.17g\n", q[0],
                  q[1], q[2], q[3], p, got, want);
        bad++;
      }
    }
    if (fabs(total - 1.0) > 1e-15) missing++; /* mask reaches outside the base tet */
  }
  CHECK(tested >= 100, "only %zu interior fine vertices tested", tested);
  CHECK(bad == 0, "%zu weights of %zu interior rows differ from (1/8) m * m", bad,
        tested);
  CHECK(missing == 0, "%zu interior rows need coarse vertices outside the base tet",
        missing);
  CHECK(nonint == 0, "fine split positions are not lattice points");
  free(key2idx);
  gsl_spmatrix_free(R);
  ss_split_free(L);
  ss_cx_free(lfine);
  ss_cx_free(fine);
  ss_cx_free(coarse);
  ss_cx_free(base);
  ss_scheme_free(linear);
  ss_scheme_free(tetoct);
}

static void test_order_invariance(void) {
  tm_link *l = tm_link_named("bipyramid:5");
  ss_cx *t = tm_tet_star(l);
  tm_link_free(l);
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *t1 = NULL, *a = NULL;
  REQUIRE_OK_VOID(ss_scheme_new("tetoct", &s, &err), &err);
  /* one level first so the input holds octahedra too; then creases */
  REQUIRE_OK_VOID(ss_scheme_refine(s, t, &t1, NULL, &err), &err);
  ss_idx tri[3], seg[2], vc = 2;
  memcpy(tri, ss_cx_cell(t1, SS_TET, 0), 3 * sizeof *tri);
  memcpy(seg, ss_cx_cell(t1, SS_TET, 5), 2 * sizeof *seg);
  ss_cx_add_cell(t1, SS_TRIANGLE, tri, 0, &err);
  ss_cx_add_cell(t1, SS_SEGMENT, seg, 0, &err);
  ss_cx_add_cell(t1, SS_VERTEX, &vc, 0, &err);
  tm_jitter(t1, 0.02, 11);
  REQUIRE_OK_VOID(ss_scheme_refine_levels(s, t1, 2, &a, &err), &err);
  for (unsigned long seed = 1; seed <= 4; seed++) {
    ss_cx *p = tm_permuted(t1, seed), *b = NULL;
    REQUIRE_OK_VOID(ss_scheme_refine_levels(s, p, 2, &b, &err), &err);
    CHECK(tm_same_geometry(a, b, 1e-12) == 0,
          "relabelled input (seed %lu) gives a different refined mesh", seed);
    ss_cx_free(p);
    ss_cx_free(b);
  }
  check_paths_agree("tetoct", t1, "tet/oct star with creases");
  /* a vertex cell is interpolated */
  CHECK(memcmp(a->x + 3 * vc, t1->x + 3 * vc, 3 * sizeof(double)) == 0,
        "crease vertex moved");
  ss_cx_free(a);
  ss_cx_free(t1);
  ss_cx_free(t);
  ss_scheme_free(s);
}

int main(void) {
  gsl_set_error_handler_off();
  test_counts();
  test_convex();
  test_convolution();
  test_order_invariance();
  return ss_test_done("tetoct");
}
