/* test_boxspline.c — the box-spline solid scheme (box-spline paper, sections
 * 3.3–3.5) against the trivariate box spline it is built on:
 *  - inside a refined tet (the octet-truss with parallel major diagonals)
 *    every row is one of the regular rules (3.3)–(3.6);
 *  - the composite mask of an interior vertex equals the coefficients of
 *    (1/32)(1+z1)^2(1+z2)^2(1+z3)^2(1+z1 z2 z3)^2 (equation 3.2) under a
 *    unimodular map of Z^3 onto the lattice, and its even part is rule (3.3);
 *  - the extraordinary vertex rule (3.7) at an icosahedral vertex. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_diag.h"
#include "ss_scheme.h"
#include "ss_split.h"
#include "ss_test.h"

/* A tet with corners 0, e1, e2, e3, refined `levels` times by the linear
 * split: vertex positions are exact dyadic lattice points.  dir picks which
 * pair of opposite edges carries the major diagonal (all cells inherit it). */
static ss_cx *lattice_tet_dir(int levels, int dir) {
  static const ss_idx order[3][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}};
  const double x[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  ss_cx *cx = NULL;
  ss_error err = {0};
  ss_cx_new(3, &cx, &err);
  for (int i = 0; i < 4; i++)
    ss_cx_add_vertex(cx, x[i], 0, &err);
  /* an even reordering: the diagonal pair (01),(23) is one of three */
  ss_cx_add_cell(cx, SS_TET, order[dir], 0, &err);
  for (int l = 0; l < levels && cx; l++) {
    ss_cx *f = NULL;
    ss_split *L = NULL;
    if (ss_split_refine(SS_SPLIT_TETOCT, cx, &f, &L, &err)) {
      CHECK(0, "split: %s", err.msg);
      f = NULL;
    }
    ss_split_free(L);
    ss_cx_free(cx);
    cx = f;
  }
  return cx;
}

static ss_cx *lattice_tet(int levels) {
  return lattice_tet_dir(levels, 0);
}

/* Lattice coordinates (units 1/n) of point x; -1 entries if not a lattice
 * point. */
static void lat(const double *x, int n, long *out) {
  for (int r = 0; r < 3; r++) {
    const double s = x[r] * n;
    out[r] = fabs(s - nearbyint(s)) < 1e-9 ? (long)nearbyint(s) : -1;
  }
}

/* Strictly inside the tet a+b+c <= n, all >= 0, at distance >= d. */
static int inside(const long *a, int n, int d) {
  return a[0] >= d && a[1] >= d && a[2] >= d && a[0] + a[1] + a[2] <= n - d;
}

typedef struct {
  ss_cx *coarse, *fine;
  gsl_spmatrix *R;
  double *y; /* fine lattice positions (linear split), fine->nv x 3 */
} level_op;

/* The operator from a tet refined `levels` times to the next level, with the
 * fine vertices' linear positions. */
static int make_op(const ss_scheme *s, int levels, level_op *o) {
  ss_error err = {0};
  ss_split *L = NULL;
  memset(o, 0, sizeof *o);
  o->coarse = lattice_tet(levels);
  if (!o->coarse ||
      ss_scheme_refine_split(s, o->coarse, &o->fine, &o->R, &L, &err) != SS_OK) {
    CHECK(0, "box-spline refinement: %s", err.msg);
    return -1;
  }
  o->y = calloc(o->fine->nv * 3, sizeof *o->y);
  for (size_t f = 0; f < o->fine->nv; f++) {
    const size_t np = ss_split_npar(L, f);
    for (size_t q = L->ptr[f]; q < L->ptr[f + 1]; q++)
      for (int r = 0; r < 3; r++)
        o->y[3 * f + r] += o->coarse->x[3 * L->parent[q] + r] / (double)np;
  }
  ss_split_free(L);
  return 0;
}

static void free_op(level_op *o) {
  free(o->y);
  if (o->R) gsl_spmatrix_free(o->R);
  ss_cx_free(o->fine);
  ss_cx_free(o->coarse);
}

static int near(double a, double b) {
  return fabs(a - b) < 1e-14;
}

/* Every row of an interior fine vertex is a regular rule. */
static void test_regular_rules(const ss_scheme *s) {
  level_op o;
  if (make_op(s, 3, &o)) return;
  const int n = 16;             /* fine lattice units */
  int counts[4] = {0, 0, 0, 0}; /* vertex, edge 6, edge 4, centre */
  for (size_t f = 0; f < o.fine->nv; f++) {
    long a[3];
    lat(o.y + 3 * f, n, a);
    if (a[0] < 0 || !inside(a, n, 3)) continue;
    const int b = o.R->p[f], e = o.R->p[f + 1], m = e - b;
    double big = 0.0;
    int nbig = 0, nsmall = 0;
    double small = -1.0;
    for (int q = b; q < e; q++)
      big = fmax(big, o.R->data[q]);
    for (int q = b; q < e; q++) {
      if (near(o.R->data[q], big))
        nbig++;
      else if (small < 0 || near(o.R->data[q], small))
        small = o.R->data[q], nsmall++;
    }
    const int even = a[0] % 2 == 0 && a[1] % 2 == 0 && a[2] % 2 == 0;
    if (even) { /* an old vertex: (3.3) */
      CHECK(m == 15 && near(big, 18.0 / 32) && nsmall == 14 && near(small, 1.0 / 32),
            "vertex (%ld %ld %ld): %d entries, %g and %d x %g", a[0], a[1], a[2], m, big,
            nsmall, small);
      counts[0]++;
    } else if (m == 8) { /* (3.4) */
      CHECK(nbig == 2 && near(big, 10.0 / 32) && nsmall == 6 && near(small, 2.0 / 32),
            "edge point (%ld %ld %ld): %d x %g, %d x %g", a[0], a[1], a[2], nbig, big,
            nsmall, small);
      counts[1]++;
    } else if (m == 6 && near(big, 8.0 / 32) && nbig == 2 && near(small, 4.0 / 32)) {
      /* (3.5) has 8/32 on the edge's ends and (3.6) on the diagonal's ends:
       * tell them apart by the parity of the fine point (an octahedron centre
       * has all three coordinates odd) */
      const int allodd = a[0] % 2 && a[1] % 2 && a[2] % 2;
      counts[allodd ? 3 : 2]++;
    } else {
      CHECK(0, "row at (%ld %ld %ld) is no regular rule: %d entries", a[0], a[1], a[2],
            m);
    }
  }
  CHECK(counts[0] > 0 && counts[1] > 0 && counts[2] > 0 && counts[3] > 0,
        "regular rules seen: %d vertex, %d edge (3.4), %d edge (3.5), %d centres (3.6)",
        counts[0], counts[1], counts[2], counts[3]);
  free_op(&o);
}

/* The composite mask of the vertex at lattice point (4,4,4)/16 against the
 * box spline's generating function. */
static void test_generating_function(const ss_scheme *s) {
  level_op o;
  if (make_op(s, 4, &o)) return;
  const int nc = 16, nf = 32;
  size_t x = SIZE_MAX;
  for (size_t v = 0; v < o.coarse->nv; v++) {
    long a[3];
    lat(o.coarse->x + 3 * v, nc, a);
    if (a[0] == 4 && a[1] == 4 && a[2] == 4) x = v;
  }
  CHECK(x != SIZE_MAX, "no coarse vertex at (4,4,4)/16");
  if (x == SIZE_MAX) {
    free_op(&o);
    return;
  }
  /* the column: offsets j = fine lattice point - 2 * (4,4,4) */
  long off[512][3];
  double val[512];
  int m = 0;
  double sum = 0.0;
  for (size_t f = 0; f < o.fine->nv; f++)
    for (int q = o.R->p[f]; q < o.R->p[f + 1]; q++) {
      if ((size_t)o.R->i[q] != x || o.R->data[q] == 0.0) continue;
      long a[3];
      lat(o.y + 3 * f, nf, a);
      CHECK(a[0] >= 0 && inside(a, nf, 1), "mask entry near the tet's boundary");
      if (m < 512) {
        for (int r = 0; r < 3; r++)
          off[m][r] = a[r] - 8;
        val[m++] = o.R->data[q];
      }
      sum += o.R->data[q];
    }
  CHECK_CLOSE(sum, 8.0, 1e-13, "the composite mask sums to 2^3");
  /* coefficients of f, indices 0..4 per variable, centred at 2 */
  double c[5][5][5] = {{{0}}};
  const int binom[3] = {1, 2, 1};
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      for (int d = 0; d < 3; d++)
        for (int e = 0; e < 3; e++)
          c[a + e][b + e][d + e] += binom[a] * binom[b] * binom[d] * binom[e] / 32.0;
  int nz = 0;
  for (int i = 0; i < 125; i++)
    nz += c[i / 25][(i / 5) % 5][i % 5] != 0.0;
  CHECK(m == nz, "mask has %d entries, the generating function %d", m, nz);
  /* the even part is the vertex rule (3.3): 18/32 and fourteen 1/32 */
  int even = 0;
  for (int i = 0; i < 125; i++) {
    const int i0 = i / 25, i1 = (i / 5) % 5, i2 = i % 5;
    if (i0 % 2 == 0 && i1 % 2 == 0 && i2 % 2 == 0 && c[i0][i1][i2] != 0.0) {
      even++;
      CHECK(near(c[i0][i1][i2], i0 == 2 && i1 == 2 && i2 == 2 ? 18.0 / 32 : 1.0 / 32),
            "even coefficient (%d %d %d) = %g", i0, i1, i2, c[i0][i1][i2]);
    }
  }
  CHECK(even == 15, "even part: %d entries", even);
  /* a unimodular U (columns among the mask's offsets of size one step, i.e.
   * the 14 lattice neighbours) with mask(U (i - 2)) = c[i] for all i */
  long nb[64][3];
  int nn = 0;
  for (int k = 0; k < m && nn < 64; k++) {
    int even_k = off[k][0] % 2 == 0 && off[k][1] % 2 == 0 && off[k][2] % 2 == 0;
    if (!even_k || (off[k][0] == 0 && off[k][1] == 0 && off[k][2] == 0)) continue;
    if (near(val[k], 1.0 / 32)) { /* a neighbour of the vertex rule, 2 fine steps */
      for (int r = 0; r < 3; r++)
        nb[nn][r] = off[k][r] / 2;
      nn++;
    }
  }
  CHECK(nn == 14, "the vertex rule has %d neighbours", nn);
  int matches = 0;
  for (int p = 0; p < nn; p++)
    for (int q = 0; q < nn; q++)
      for (int r = 0; r < nn; r++) {
        const long *u1 = nb[p], *u2 = nb[q], *u3 = nb[r];
        const long det = u1[0] * (u2[1] * u3[2] - u2[2] * u3[1]) -
                         u1[1] * (u2[0] * u3[2] - u2[2] * u3[0]) +
                         u1[2] * (u2[0] * u3[1] - u2[1] * u3[0]);
        if (det != 1 && det != -1) continue;
        int ok = 1;
        for (int i = 0; i < 125 && ok; i++) {
          const int i0 = i / 25 - 2, i1 = (i / 5) % 5 - 2, i2 = i % 5 - 2;
          const double want = c[i / 25][(i / 5) % 5][i % 5];
          long t[3];
          for (int d = 0; d < 3; d++)
            t[d] = u1[d] * i0 + u2[d] * i1 + u3[d] * i2;
          double got = 0.0;
          for (int k = 0; k < m; k++)
            if (off[k][0] == t[0] && off[k][1] == t[1] && off[k][2] == t[2]) got = val[k];
          ok = near(got, want);
        }
        matches += ok;
      }
  CHECK(matches > 0, "no unimodular map takes the generating function onto the mask");
  free_op(&o);
}

/* (3.7) at a vertex whose 12 neighbours are all edges (the icosahedral star,
 * before any octahedron exists). */
static void test_extraordinary(const ss_scheme *s) {
  /* a vertex at the origin and 12 around it on a sphere: the 20 tets of the
   * icosahedron */
  const double g = (1.0 + sqrt(5.0)) / 2.0;
  const double ico[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                             {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                             {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  const int tri[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                          {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                          {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                          {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  ss_cx *cx = NULL, *f = NULL;
  ss_error err = {0};
  ss_cx_new(3, &cx, &err);
  const double o[3] = {0, 0, 0};
  ss_cx_add_vertex(cx, o, 0, &err);
  for (int i = 0; i < 12; i++)
    ss_cx_add_vertex(cx, ico[i], 0, &err);
  for (int t = 0; t < 20; t++) {
    const ss_idx v[4] = {0, (ss_idx)tri[t][0] + 1, (ss_idx)tri[t][2] + 1,
                         (ss_idx)tri[t][1] + 1};
    ss_cx_add_cell(cx, SS_TET, v, 0, &err);
  }
  gsl_spmatrix *R = NULL;
  if (ss_scheme_refine(s, cx, &f, &R, &err)) {
    CHECK(0, "icosahedral star: %s", err.msg);
    ss_cx_free(cx);
    return;
  }
  CHECK(R->p[1] - R->p[0] == 13, "centre row has %d entries", R->p[1] - R->p[0]);
  for (int q = R->p[0]; q < R->p[1]; q++)
    CHECK(near(R->data[q], R->i[q] == 0 ? 9.0 / 16 : 7.0 / (16 * 12)),
          "centre row: %g at column %d", R->data[q], R->i[q]);
  for (size_t r = 0; r < f->nv; r++) {
    double sum = 0.0;
    for (int q = R->p[r]; q < R->p[r + 1]; q++)
      sum += R->data[q];
    CHECK(fabs(sum - 1.0) < 1e-14, "row %zu sums to %.17g", r, sum);
  }
  gsl_spmatrix_free(R);
  ss_cx_free(f);
  ss_cx_free(cx);
}

/* Major-diagonal choices on an edge star of n tets (0, 1, c_i, c_i+1). */
static ss_cx *edge_star(int n) {
  ss_cx *cx = NULL;
  ss_error err = {0};
  ss_cx_new(3, &cx, &err);
  const double a[3] = {0, 0, -1}, b[3] = {0, 0, 1};
  ss_cx_add_vertex(cx, a, 0, &err);
  ss_cx_add_vertex(cx, b, 0, &err);
  for (int i = 0; i < n; i++) {
    const double x[3] = {cos(2 * M_PI * i / n), sin(2 * M_PI * i / n), 0};
    ss_cx_add_vertex(cx, x, 0, &err);
  }
  for (int i = 0; i < n; i++) {
    const ss_idx v[4] = {0, 1, (ss_idx)(2 + i), (ss_idx)(2 + (i + 1) % n)};
    ss_cx_add_cell(cx, SS_TET, v, 0, &err);
  }
  return cx;
}

static int same_pair(ss_idx a, ss_idx b, ss_idx c, ss_idx d) {
  return (a == c && b == d) || (a == d && b == c);
}

static void test_diagonals(void) {
  ss_error err = {0};
  for (int n = 3; n <= 9; n++) {
    for (int m = 0; m < 3; m++) {
      ss_cx *cx = edge_star(n);
      int positive = 0;
      for (size_t t = 0; t < cx->nc[SS_TET]; t++)
        positive += ss_cx_cell_orientation(cx, SS_TET, t, NULL) == 1;
      CHECK(positive == n, "edge star %d: %d positive tets before", n, positive);
      CHECK(ss_diag_choose(cx, (ss_diag_mode)m, 0, 1, &err) == SS_OK, "%s", err.msg);
      positive = 0;
      int as_asked = 0;
      for (size_t t = 0; t < cx->nc[SS_TET]; t++) {
        const ss_idx *v = ss_cx_cell(cx, SS_TET, t);
        positive += ss_cx_cell_orientation(cx, SS_TET, t, NULL) == 1;
        const ss_idx ci = (ss_idx)(2 + t), cj = (ss_idx)(2 + (t + 1) % (size_t)n);
        if (m == SS_DIAG_CENTER)
          as_asked += same_pair(v[0], v[1], 0, 1) && same_pair(v[2], v[3], ci, cj);
        else if (m == SS_DIAG_SKEW)
          as_asked += (same_pair(v[0], v[1], 0, ci) && same_pair(v[2], v[3], cj, 1)) ||
                      (same_pair(v[2], v[3], 0, ci) && same_pair(v[0], v[1], cj, 1));
        else
          as_asked++;
      }
      CHECK(positive == n && as_asked == n, "edge star %d, %s: %d positive, %d as asked",
            n, ss_diag_name((ss_diag_mode)m), positive, as_asked);
      if (m == SS_DIAG_BFS) {
        /* Algorithm 2: neighbours (sharing the face (0, 1, c_i+1)) avoid each
         * other's diagonal edges where they can; around the edge only the last
         * tet may be forced */
        int clash = 0;
        for (int t = 0; t < n; t++) {
          const ss_idx *v = ss_cx_cell(cx, SS_TET, (size_t)t),
                       *w = ss_cx_cell(cx, SS_TET, (size_t)((t + 1) % n));
          for (int e = 0; e < 2; e++)
            for (int f = 0; f < 2; f++)
              clash += same_pair(v[2 * e], v[2 * e + 1], w[2 * f], w[2 * f + 1]);
        }
        CHECK(clash <= 1, "edge star %d, bfs: %d neighbours share a diagonal edge", n,
              clash);
      }
      ss_cx_free(cx);
    }
  }
  ss_cx *cx = edge_star(4);
  CHECK(ss_diag_choose(cx, SS_DIAG_SKEW, 2, 4, &err) == SS_EINPUT, "a non-edge");
  ss_diag_mode dm;
  CHECK(ss_diag_parse("center", &dm) == 0 && dm == SS_DIAG_CENTER &&
            ss_diag_parse("diagonal", &dm) == -1 && ss_diag_parse("proper", &dm) == 0 &&
            dm == SS_DIAG_PROPER && !strcmp(ss_diag_name(SS_DIAG_PROPER), "proper"),
        "parse");
  ss_cx_free(cx);
}

/* The face-to-face case (section 4.2): two tets sharing the face (0, 1, 2),
 * every combination of their diagonals.  After three levels of the split,
 * count rho (Definition 3.3: cell edges and octahedron diagonals) at the
 * points strictly inside the shared face: vertices must have 14, and edges 4
 * or 6 exactly when ss_diag_improper calls the pair proper; the count of
 * improper pairs must stay zero on every level of a proper mesh. */
static void test_face_to_face(void) {
  static const int perm[3][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}};
  const double X[5][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {.3, .3, 1}, {.3, .3, -1}};
  const ss_idx A[4] = {0, 1, 2, 3}, B[4] = {0, 2, 1, 4};
  ss_error err = {0};
  int nproper = 0;
  for (int p = 0; p < 3; p++)
    for (int q = 0; q < 3; q++) {
      ss_cx *cx = NULL;
      ss_cx_new(3, &cx, &err);
      for (int i = 0; i < 5; i++)
        ss_cx_add_vertex(cx, X[i], 0, &err);
      ss_idx a[4], b[4];
      for (int i = 0; i < 4; i++)
        a[i] = A[perm[p][i]], b[i] = B[perm[q][i]];
      ss_cx_add_cell(cx, SS_TET, a, 0, &err);
      ss_cx_add_cell(cx, SS_TET, b, 0, &err);
      /* both pairs hold the same edge of the face (0, 1, 2)? */
      int same = 0;
      for (int e = 0; e < 2; e++)
        for (int f = 0; f < 2; f++)
          same += same_pair(a[2 * e], a[2 * e + 1], b[2 * f], b[2 * f + 1]);
      size_t np = 0, nbad = 0;
      CHECK(ss_diag_improper(cx, &np, &nbad, &err) == SS_OK && np == 1 &&
                nbad == (size_t)!same,
            "pairs %d %d: %zu pairs, %zu improper, same edge %d", p, q, np, nbad, same);
      nproper += same;
      const int proper = nbad == 0;
      for (int l = 1; l <= 3; l++) {
        ss_cx *f = NULL;
        ss_split *L = NULL;
        if (ss_split_refine(SS_SPLIT_TETOCT, cx, &f, &L, &err)) {
          CHECK(0, "split: %s", err.msg);
          break;
        }
        ss_split_free(L);
        ss_cx_free(cx);
        cx = f;
        CHECK(ss_diag_improper(cx, &np, &nbad, &err) == SS_OK && np > 0 &&
                  (proper ? nbad == 0 : nbad > 0),
              "pairs %d %d, level %d: %zu of %zu improper", p, q, l, nbad, np);
      }
      const size_t n = cx->nv;
      unsigned char *E = calloc(n * n, 1); /* bit 1: cell edge, bit 2: diagonal */
      for (size_t t = 0; t < cx->nc[SS_TET]; t++) {
        const ss_idx *v = ss_cx_cell(cx, SS_TET, t);
        for (int i = 0; i < 4; i++)
          for (int j = 0; j < 4; j++)
            if (i != j) E[v[i] * n + v[j]] |= 1;
      }
      for (size_t t = 0; t < cx->nc[SS_OCT]; t++) {
        const ss_idx *v = ss_cx_cell(cx, SS_OCT, t);
        for (int i = 0; i < 6; i++)
          for (int j = 0; j < 6; j++)
            if (i != j) E[v[i] * n + v[j]] |= i % 3 != j % 3 ? 1 : i % 3 == 0 ? 2 : 0;
      }
      const double eps = 1e-9;
#define FACE_INSIDE(x)                                                                   \
  (fabs((x)[2]) < eps && (x)[0] > eps && (x)[1] > eps && (x)[0] + (x)[1] < 1 - eps)
      int nv = 0, badv = 0, ne = 0, bade = 0;
      for (size_t u = 0; u < n; u++) {
        if (!FACE_INSIDE(cx->x + 3 * u)) continue;
        int rho = 0;
        for (size_t w = 0; w < n; w++)
          rho += E[u * n + w] != 0;
        nv++;
        badv += rho != 14;
        for (size_t w = u + 1; w < n; w++) {
          if (!(E[u * n + w] & 1) || !FACE_INSIDE(cx->x + 3 * w)) continue;
          int re = 0;
          for (size_t z = 0; z < n; z++)
            re += E[u * n + z] && E[w * n + z];
          ne++;
          bade += re != 4 && re != 6;
        }
      }
#undef FACE_INSIDE
      CHECK(nv > 0 && ne > 0 && badv == 0 && (proper ? bade == 0 : bade > 0),
            "pairs %d %d (%s): %d of %d face vertices, %d of %d face edges irregular", p,
            q, proper ? "proper" : "improper", badv, nv, bade, ne);
      free(E);
      ss_cx_free(cx);
    }
  CHECK(nproper == 3, "%d of 9 combinations share an edge", nproper);
}

/* Inside one refined tet all diagonals are parallel: the lattice is proper;
 * around an edge, "center" is proper and "skew" improper on every face. */
static void test_proper_counts(void) {
  ss_error err = {0};
  size_t np = 0, nbad = 0;
  ss_cx *cx = lattice_tet(3);
  CHECK(cx && ss_diag_improper(cx, &np, &nbad, &err) == SS_OK && np > 0 && nbad == 0,
        "lattice: %zu of %zu improper", nbad, np);
  ss_cx_free(cx);
  for (int n = 3; n <= 9; n++) {
    /* Algorithm 2 avoids its neighbours' edges, so around an edge every face
     * but at most one is improper; the matching search makes none improper */
    size_t nb[2];
    for (int m = 0; m < 2; m++) {
      cx = edge_star(n);
      ss_diag_choose(cx, m ? SS_DIAG_PROPER : SS_DIAG_BFS, 0, 1, &err);
      CHECK(ss_diag_improper(cx, &np, &nb[m], &err) == SS_OK && np == (size_t)n,
            "edge star %d: %zu pairs", n, np);
      ss_cx_free(cx);
    }
    CHECK(nb[0] + 1 >= (size_t)n && nb[1] == 0,
          "edge star %d: bfs %zu, proper %zu improper", n, nb[0], nb[1]);
  }
  for (int n = 3; n <= 9; n++)
    for (int m = SS_DIAG_SKEW; m <= SS_DIAG_CENTER; m++) {
      cx = edge_star(n);
      ss_diag_choose(cx, (ss_diag_mode)m, 0, 1, &err);
      CHECK(ss_diag_improper(cx, &np, &nbad, &err) == SS_OK && np == (size_t)n &&
                nbad == (m == SS_DIAG_SKEW ? (size_t)n : 0),
            "edge star %d %s: %zu of %zu improper", n, ss_diag_name((ss_diag_mode)m),
            nbad, np);
      ss_cx_free(cx);
    }
}

/* Rows of the refinement from a tet refined `levels` times (lattice units
 * 1/2^levels), for the fine points at least 3 fine units inside: rows[i] is
 * dense over the coarse lattice ((2^levels + 1)^3 points), keyed[i] the fine
 * point's lattice index.  Returns the number of rows (0 on failure). */
static int lattice_rows(const ss_scheme *s, int levels, int dir, double **rows,
                        long **keyed) {
  ss_error err = {0};
  ss_split *L = NULL;
  ss_cx *coarse = lattice_tet_dir(levels, dir), *fine = NULL;
  gsl_spmatrix *R = NULL;
  const int nc = 1 << levels, nf = 2 * nc, side = nc + 1;
  *rows = NULL;
  *keyed = NULL;
  if (!coarse || ss_scheme_refine_split(s, coarse, &fine, &R, &L, &err)) {
    CHECK(0, "%s: %s", ss_scheme_name(s), err.msg);
    ss_cx_free(coarse);
    return 0;
  }
  double *W = calloc(fine->nv * (size_t)(side * side * side), sizeof *W);
  long *K = calloc(fine->nv, sizeof *K);
  int n = 0;
  for (size_t f = 0; f < fine->nv; f++) {
    double y[3] = {0, 0, 0};
    const size_t np = ss_split_npar(L, f);
    for (size_t q = L->ptr[f]; q < L->ptr[f + 1]; q++)
      for (int r = 0; r < 3; r++)
        y[r] += coarse->x[3 * L->parent[q] + r] / (double)np;
    long a[3];
    lat(y, nf, a);
    if (a[0] < 0 || !inside(a, nf, 3)) continue;
    K[n] = (a[0] * (nf + 1) + a[1]) * (nf + 1) + a[2];
    for (int q = R->p[f]; q < R->p[f + 1]; q++) {
      long c[3];
      lat(coarse->x + 3 * R->i[q], nc, c);
      W[(size_t)n * (size_t)(side * side * side) +
        (size_t)((c[0] * side + c[1]) * side + c[2])] = R->data[q];
    }
    n++;
  }
  ss_split_free(L);
  gsl_spmatrix_free(R);
  ss_cx_free(fine);
  ss_cx_free(coarse);
  *rows = W;
  *keyed = K;
  return n;
}

/* Appendix A: on the lattice, boxspline-avg is the mean of the three
 * box-spline schemes whose diagonals point the lattice's three ways. */
static void test_avg_lattice(const ss_scheme *bs, const ss_scheme *avg) {
  const int levels = 3, side = (1 << levels) + 1, ncol = side * side * side;
  double *Wd[3], *Wa;
  long *Kd[3], *Ka;
  int nd[3];
  for (int d = 0; d < 3; d++)
    nd[d] = lattice_rows(bs, levels, d, &Wd[d], &Kd[d]);
  const int na = lattice_rows(avg, levels, 0, &Wa, &Ka);
  CHECK(na >= 30 && nd[0] == na && nd[1] == na && nd[2] == na, "rows: %d %d %d %d", na,
        nd[0], nd[1], nd[2]);
  int bad = 0, differ = 0, shapes[4] = {0, 0, 0, 0};
  for (int i = 0; i < na && nd[0] == na && nd[1] == na && nd[2] == na; i++) {
    int j[3];
    for (int d = 0; d < 3; d++) /* the same fine point in each */
      for (j[d] = 0; j[d] < na && Kd[d][j[d]] != Ka[i]; j[d]++)
        ;
    if (j[0] == na || j[1] == na || j[2] == na) {
      bad++;
      continue;
    }
    int nz = 0;
    for (int c = 0; c < ncol; c++) {
      const double *r0 = Wd[0] + (size_t)j[0] * ncol, *r1 = Wd[1] + (size_t)j[1] * ncol,
                   *r2 = Wd[2] + (size_t)j[2] * ncol;
      const double mean = (r0[c] + r1[c] + r2[c]) / 3.0;
      bad += fabs(Wa[(size_t)i * ncol + c] - mean) > 1e-15;
      differ += fabs(r0[c] - r1[c]) > 1e-15;
      nz += Wa[(size_t)i * ncol + c] != 0.0;
    }
    /* vertex 1 + 12 + 6, edge 2 + 4 + 4, centre 6 */
    shapes[nz == 19 ? 0 : nz == 10 ? 1 : nz == 6 ? 2 : 3]++;
  }
  CHECK(bad == 0, "%d averaged weights differ from the mean of the three directions",
        bad);
  CHECK(differ > 0,
        "the three directions give the same rules: the test would be vacuous");
  CHECK(shapes[0] > 0 && shapes[1] > 0 && shapes[2] > 0 && shapes[3] == 0,
        "averaged row shapes: %d vertex, %d edge, %d centre, %d other", shapes[0],
        shapes[1], shapes[2], shapes[3]);
  for (int d = 0; d < 3; d++) {
    free(Wd[d]);
    free(Kd[d]);
  }
  free(Wa);
  free(Ka);
}

/* The points of cx refined `levels` times by s (caller frees); *n their
 * number. */
static double *refined_points(const ss_scheme *s, const ss_cx *cx, int levels,
                              size_t *n) {
  ss_error err = {0};
  ss_cx *f = NULL;
  *n = 0;
  if (ss_scheme_refine_levels(s, cx, levels, &f, &err)) {
    CHECK(0, "%s: %s", ss_scheme_name(s), err.msg);
    return NULL;
  }
  double *x = malloc(3 * f->nv * sizeof *x);
  memcpy(x, f->x, 3 * f->nv * sizeof *x);
  *n = f->nv;
  ss_cx_free(f);
  return x;
}

/* Hausdorff distance of two point sets (max-norm), INFINITY if the counts
 * differ. */
static double point_set_distance(const double *a, size_t na, const double *b, size_t nb) {
  if (na != nb || !a || !b) return (double)INFINITY;
  double h = 0.0;
  for (int side = 0; side < 2; side++) {
    const double *p = side ? b : a, *q = side ? a : b;
    for (size_t i = 0; i < na; i++) {
      double best = (double)INFINITY;
      for (size_t j = 0; j < nb; j++) {
        double d = 0.0;
        for (int r = 0; r < 3; r++)
          d = fmax(d, fabs(p[3 * i + r] - q[3 * j + r]));
        best = fmin(best, d);
      }
      h = fmax(h, best);
    }
  }
  return h;
}

/* An edge star of valence 7 with a bump, a random-ish but fixed geometry. */
static ss_cx *bumpy_star(int n) {
  ss_cx *cx = edge_star(n);
  for (size_t v = 0; v < cx->nv; v++)
    for (int r = 0; r < 3; r++)
      cx->x[3 * v + r] += 0.05 * sin(1.7 * (double)(v + 1) * (r + 1));
  return cx;
}

/* boxspline-avg ignores the diagonals (bfs, skew, center give the same fine
 * points), while boxspline does not; boxspline is invariant under relabelling
 * the vertices when the diagonal pairs are carried along (a random even
 * reordering of each tet that keeps its pair). */
static void test_diagonal_invariance(const ss_scheme *bs, const ss_scheme *avg) {
  ss_error err = {0};
  /* the first level of a tet mesh reads no diagonal (there is no octahedron
   * yet): compare after two */
  for (int n = 4; n <= 8; n++) {
    double *P[2][3];
    size_t np[2][3];
    for (int m = 0; m < 3; m++) {
      ss_cx *cx = bumpy_star(n);
      ss_diag_choose(cx, (ss_diag_mode)m, 0, 1, &err);
      P[0][m] = refined_points(bs, cx, 2, &np[0][m]);
      P[1][m] = refined_points(avg, cx, 2, &np[1][m]);
      ss_cx_free(cx);
    }
    for (int m = 1; m < 3; m++) {
      const double d = point_set_distance(P[1][m], np[1][m], P[1][0], np[1][0]);
      CHECK(d < 1e-14, "edge star %d: boxspline-avg moves by %g between %s and bfs", n, d,
            ss_diag_name((ss_diag_mode)m));
    }
    const double d = point_set_distance(P[0][1], np[0][1], P[0][2], np[0][2]);
    CHECK(d > 1e-3 && isfinite(d),
          "edge star %d: boxspline skew and center differ by only %g (the test would be "
          "vacuous)",
          n, d);
    for (int i = 0; i < 2; i++)
      for (int m = 0; m < 3; m++)
        free(P[i][m]);
  }
  /* relabelling with the diagonals carried along */
  static const int keep[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
  unsigned seed = 7;
  for (int trial = 0; trial < 6; trial++) {
    ss_cx *cx = bumpy_star(5 + trial % 4);
    ss_diag_choose(cx, trial % 2 ? SS_DIAG_SKEW : SS_DIAG_BFS, 0, 1, &err);
    const size_t nv = cx->nv;
    ss_idx *map = malloc(nv * sizeof *map), *inv = malloc(nv * sizeof *inv);
    for (size_t v = 0; v < nv; v++)
      map[v] = (ss_idx)v;
    for (size_t v = nv - 1; v > 0; v--) { /* Fisher-Yates */
      seed = seed * 1103515245u + 12345u;
      const size_t j = (seed >> 8) % (v + 1);
      const ss_idx t = map[v];
      map[v] = map[j];
      map[j] = t;
    }
    for (size_t v = 0; v < nv; v++)
      inv[map[v]] = (ss_idx)v;
    ss_cx *rl = NULL;
    ss_cx_new(3, &rl, &err);
    for (size_t w = 0; w < nv; w++)
      ss_cx_add_vertex(rl, cx->x + 3 * inv[w], 0, &err);
    for (size_t t = 0; t < cx->nc[SS_TET]; t++) {
      const ss_idx *v = ss_cx_cell(cx, SS_TET, t);
      seed = seed * 1103515245u + 12345u;
      const int *k = keep[(seed >> 8) % 4];
      const ss_idx w[4] = {map[v[k[0]]], map[v[k[1]]], map[v[k[2]]], map[v[k[3]]]};
      ss_cx_add_cell(rl, SS_TET, w, 0, &err);
    }
    size_t n1 = 0, n2 = 0;
    double *A = refined_points(bs, cx, 2, &n1), *B = refined_points(bs, rl, 2, &n2);
    const double d = point_set_distance(A, n1, B, n2);
    CHECK(n1 > 0 && d < 1e-14, "trial %d: relabelled box-spline refinement moves by %g",
          trial, d);
    size_t p1, b1, p2, b2;
    CHECK(!ss_diag_improper(cx, &p1, &b1, &err) &&
              !ss_diag_improper(rl, &p2, &b2, &err) && p1 == p2 && b1 == b2,
          "trial %d: improper pairs change under relabelling", trial);
    free(A);
    free(B);
    free(map);
    free(inv);
    ss_cx_free(rl);
    ss_cx_free(cx);
  }
}

int main(void) {
  test_diagonals();
  test_face_to_face();
  test_proper_counts();
  ss_scheme *s = NULL;
  ss_error err = {0};
  if (ss_scheme_new("boxspline", &s, &err)) {
    fprintf(stderr, "%s\n", err.msg);
    return 1;
  }
  test_regular_rules(s);
  test_generating_function(s);
  test_extraordinary(s);
  ss_scheme *avg = NULL;
  if (ss_scheme_new("boxspline-avg", &avg, &err)) {
    fprintf(stderr, "%s\n", err.msg);
    return 1;
  }
  test_avg_lattice(s, avg);
  test_diagonal_invariance(s, avg);
  ss_scheme_free(avg);
  ss_scheme_free(s);
  return ss_test_done("boxspline");
}
