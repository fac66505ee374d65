/* test_ccsolid.c — Catmull-Clark solids (Joy-MacCracken rules) against
 * independent derivations:
 *   1. the regular vertex: the two-ring spectrum is the tensor cube of the
 *      cubic curve's, computed here from the curve's own 5 x 5 matrix;
 *   2. regular grids: one step is the tricubic B-spline rule entry by entry,
 *      and L steps converge to the tricubic B-spline volume (evaluated here
 *      from the basis) like 4^-L;
 *   3. a naive implementation of the rules (literal averages over the cells,
 *      faces and edges of the mesh) on meshes with extraordinary vertices and
 *      edges;
 *   4. the boundary: the catmull-clark scheme on the mesh's boundary surface;
 *   5. extraordinary edges: the local matrix against the tensor product of
 *      the Catmull-Clark surface matrix and the cubic curve's (equal off the
 *      edge's own vertices; the rotation-invariant part differs for n != 4);
 *      ccsolid-tensor's equal to it in every row, its spectrum the surface's
 *      times the curve's with Catmull-Clark's lambda_1(n) in closed form;
 *   6. non-manifold and tet input refused. */
#include <lapacke.h>
#include <stdlib.h>
#include <string.h>

#include "ss_local.h"
#include "ss_optest.h"
#include "ss_star.h"
#include "ss_testmesh.h"

/* ---- eigenvalues ---- */

/* Eigenvalues of the n x n row-major matrix A into wr, wi (LAPACK dgeev). */
static void eigvals(const double *A, size_t n, double *wr, double *wi) {
  double *a = malloc(n * n * sizeof *a);
  memcpy(a, A, n * n * sizeof *a);
  lapack_int info = LAPACKE_dgeev(LAPACK_ROW_MAJOR, 'N', 'N', (lapack_int)n, a,
                                  (lapack_int)n, wr, wi, NULL, 1, NULL, 1);
  CHECK(info == 0, "dgeev failed (%d)", (int)info);
  free(a);
}

/* Largest distance, relative to max(1, |a|), between the multisets a and b of
 * n complex numbers when each a is matched greedily to its nearest unused b.
 * Equal multisets up to rounding give a small value; multisets differing in
 * one element give at least that element's distance to the rest. */
static double multiset_dist(size_t n, const double *ar, const double *ai,
                            const double *br, const double *bi) {
  unsigned char *used = calloc(n + 1, 1);
  double worst = 0.0;
  for (size_t i = 0; i < n; i++) {
    size_t best = SIZE_MAX;
    double bd = INFINITY;
    for (size_t j = 0; j < n; j++) {
      if (used[j]) continue;
      double d = hypot(ar[i] - br[j], ai[i] - bi[j]);
      if (d < bd) bd = d, best = j;
    }
    used[best] = 1;
    double s = hypot(ar[i], ai[i]);
    bd /= s > 1.0 ? s : 1.0;
    worst = bd > worst ? bd : worst;
  }
  free(used);
  return worst;
}

/* The cubic B-spline curve's two-ring matrix (points -2..2, fine t from coarse
 * t'), from the mask alone: S[t][t'] = b(t - 2 t'). */
static void curve_matrix(double S[25]) {
  for (int t = -2; t <= 2; t++)
    for (int u = -2; u <= 2; u++)
      S[(t + 2) * 5 + (u + 2)] = op_bspline(t - 2 * u);
}

static ss_scheme *scheme(const char *name) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  if (ss_scheme_new(name, &s, &err)) {
    fprintf(stderr, "%s\n", err.msg);
    exit(1);
  }
  return s;
}

static ss_local *local(const char *name, ss_case c) {
  ss_error err = {0};
  ss_scheme *s = scheme(name);
  ss_local *M = NULL;
  if (ss_local_new(s, &c, &M, &err)) {
    fprintf(stderr, "%s: local matrix: %s\n", name, err.msg);
    exit(1);
  }
  ss_scheme_free(s);
  return M;
}

/* ---- 1. the regular vertex ---- */

static void test_regular_vertex(void) {
  ss_error err = {0};
  ss_link *oct = NULL;
  if (ss_link_named("octahedron", &oct, &err)) {
    CHECK(0, "octahedron: %s", err.msg);
    return;
  }
  ss_local *M = local("ccsolid", (ss_case){SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0});
  CHECK(M->n2 == 125 && M->n1 == 27, "regular vertex: two-ring %zu, one-ring %zu", M->n2,
        M->n1);
  double C[25], cr[5], ci[5];
  curve_matrix(C);
  eigvals(C, 5, cr, ci);
  /* the curve's spectrum itself: 1, 1/2, 1/4, 1/8, 1/8 (closed form) */
  const double cexp[5] = {1.0, 0.5, 0.25, 0.125, 0.125}, z5[5] = {0};
  CHECK(multiset_dist(5, cr, ci, cexp, z5) < 1e-14, "cubic curve spectrum");
  double tr[125], ti[125] = {0}, wr[125], wi[125];
  for (int a = 0; a < 5; a++)
    for (int b = 0; b < 5; b++)
      for (int c = 0; c < 5; c++)
        tr[25 * a + 5 * b + c] = cr[a] * cr[b] * cr[c];
  if (M->n2 == 125) {
    eigvals(M->S, 125, wr, wi);
    double d = multiset_dist(125, wr, wi, tr, ti);
    CHECK(d < 1e-12, "regular vertex: spectrum differs from the tensor cube by %g", d);
    size_t n8 = 0;
    for (int i = 0; i < 125; i++)
      n8 += fabs(wr[i] - 0.125) < 1e-12;
    CHECK(n8 == 13, "regular vertex: 1/8 has multiplicity %zu, not 13", n8);
  }
  ss_local_free(M);
  ss_link_free(oct);
}

/* ---- 2. regular grids ---- */

/* Uniform cubic B-spline basis b_j(t), j = 0..3, on one knot interval. */
static void bspline_basis(double t, double b[4]) {
  const double s = 1.0 - t;
  b[0] = s * s * s / 6.0;
  b[1] = (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0;
  b[2] = (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0;
  b[3] = t * t * t / 6.0;
}

/* An N^3 grid of vertices (i, j, k), N - 1 hexes a side, not periodic. */
static ss_cx *grid(int N) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  if (ss_cx_new(3, &cx, &err)) exit(1);
  for (int v = 0; v < N * N * N; v++) {
    double x[3] = {(double)(v % N), (double)((v / N) % N), (double)(v / (N * N))};
    if (ss_cx_add_vertex(cx, x, 0, &err)) exit(1);
  }
  for (int k = 0; k + 1 < N; k++)
    for (int j = 0; j + 1 < N; j++)
      for (int i = 0; i + 1 < N; i++) {
        ss_idx h[8];
        for (int c = 0; c < 8; c++) {
          unsigned b = ss_cube_corner_bits(3, c);
          h[c] = (ss_idx)((i + (int)(b & 1u)) + N * (j + (int)(b >> 1 & 1u)) +
                          N * N * (k + (int)(b >> 2 & 1u)));
        }
        if (ss_cx_add_cell(cx, SS_HEX, h, 0, &err)) exit(1);
      }
  return cx;
}

/* A 4^3 grid (the only cell whose 4 x 4 x 4 net is interior is [1,2]^3),
 * perturbed at random, refined L = 1..5 times: the refined points over
 * [1,2]^3 against the tricubic B-spline of the coarse points at their
 * parameters.  The parameters come from the same refinement of the unperturbed
 * grid (x = (i, j, k)), which the rules reproduce exactly over [1,2]^3: every
 * refined point there derives from the interior by the regular rules. */
static void test_grid_convergence(void) {
  const int N = 4, LMAX = 5;
  ss_cx *par = grid(N), *pos = grid(N);
  tm_jitter(pos, 0.3, 17);
  ss_scheme *s = scheme("ccsolid");
  double err_l[6] = {0};
  for (int L = 1; L <= LMAX; L++) {
    ss_error err = {0};
    ss_cx *fp = NULL, *fx = NULL;
    if (ss_scheme_refine_levels(s, par, L, &fp, &err) ||
        ss_scheme_refine_levels(s, pos, L, &fx, &err)) {
      CHECK(0, "grid L=%d: %s", L, err.msg);
      break;
    }
    size_t tested = 0;
    double worst = 0.0;
    for (size_t v = 0; v < fp->nv; v++) {
      const double *u = fp->x + 3 * v;
      if (u[0] < 1.0 || u[0] > 2.0 || u[1] < 1.0 || u[1] > 2.0 || u[2] < 1.0 ||
          u[2] > 2.0)
        continue;
      double b[3][4], y[3] = {0, 0, 0};
      for (int d = 0; d < 3; d++)
        bspline_basis(u[d] - 1.0, b[d]);
      for (int k = 0; k < 4; k++)
        for (int j = 0; j < 4; j++)
          for (int i = 0; i < 4; i++) {
            const double w = b[0][i] * b[1][j] * b[2][k];
            const double *p = pos->x + 3 * (size_t)(i + N * j + N * N * k);
            for (int d = 0; d < 3; d++)
              y[d] += w * p[d];
          }
      for (int d = 0; d < 3; d++)
        worst = fmax(worst, fabs(fx->x[3 * v + (size_t)d] - y[d]));
      tested++;
    }
    const size_t side = ((size_t)1 << L) + 1;
    CHECK(tested == side * side * side, "grid L=%d: %zu points over [1,2]^3, not %zu", L,
          tested, side * side * side);
    err_l[L] = worst;
    printf("grid L=%d: %zu points, max distance to the B-spline %.3e%s", L, tested, worst,
           L > 1 ? "" : "\n");
    if (L > 1) printf(", ratio %.3f\n", err_l[L - 1] / worst);
    ss_cx_free(fp);
    ss_cx_free(fx);
  }
  /* control points converge to the limit at O(h^2): ratios tend to 4 (the
   * first, from the coarsest net, is 4.46) */
  for (int L = 3; L <= LMAX; L++)
    CHECK(err_l[L - 1] / err_l[L] > 3.9 && err_l[L - 1] / err_l[L] < 4.2,
          "grid: error ratio %g between levels %d and %d, not ~4",
          err_l[L - 1] / err_l[L], L - 1, L);
  CHECK(err_l[LMAX] < 2e-3, "grid: error %g after %d levels", err_l[LMAX], LMAX);
  ss_scheme_free(s);
  ss_cx_free(par);
  ss_cx_free(pos);
}

/* ---- 3. a naive implementation of the rules ---- */

static const int hex_faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                    {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

/* Elements of a hex mesh as sorted vertex sets, with their incidences. */
typedef struct {
  size_t n;          /* elements */
  int m;             /* vertices per element (2 edges, 4 faces) */
  ss_idx (*v)[4];    /* sorted vertices */
  ss_idx (*cyc)[4];  /* faces: vertices in cyclic order */
  size_t *nhex;      /* hexes holding each */
  size_t (*hex)[16]; /* those hexes (up to 16) */
} elems;

static int cmp_idx(const void *a, const void *b) {
  ss_idx x = *(const ss_idx *)a, y = *(const ss_idx *)b;
  return (x > y) - (x < y);
}

static size_t find_or_add(elems *E, const ss_idx *v, int m, const ss_idx *cyc) {
  ss_idx key[4] = {0, 0, 0, 0};
  memcpy(key, v, (size_t)m * sizeof *v);
  qsort(key, (size_t)m, sizeof *key, cmp_idx);
  for (size_t i = 0; i < E->n; i++)
    if (memcmp(E->v[i], key, sizeof key) == 0) return i;
  memcpy(E->v[E->n], key, sizeof key);
  if (cyc) memcpy(E->cyc[E->n], cyc, 4 * sizeof *cyc);
  E->nhex[E->n] = 0;
  return E->n++;
}

static void elems_init(elems *E, size_t cap, int m) {
  E->n = 0;
  E->m = m;
  E->v = calloc(cap, sizeof *E->v);
  E->cyc = calloc(cap, sizeof *E->cyc);
  E->nhex = calloc(cap, sizeof *E->nhex);
  E->hex = calloc(cap, sizeof *E->hex);
}

static void elems_free(elems *E) {
  free(E->v);
  free(E->cyc);
  free(E->nhex);
  free(E->hex);
}

static void centroid(const ss_cx *cx, const ss_idx *v, int m, double *out) {
  for (int d = 0; d < 3; d++) {
    out[d] = 0.0;
    for (int j = 0; j < m; j++)
      out[d] += cx->x[3 * v[j] + (size_t)d] / m;
  }
}

/* Whether face f (cyclic vertices) has the edge {a, b}. */
static int face_has_edge(const ss_idx *f, ss_idx a, ss_idx b) {
  for (int i = 0; i < 4; i++) {
    ss_idx p = f[i], q = f[(i + 1) % 4];
    if ((p == a && q == b) || (p == b && q == a)) return 1;
  }
  return 0;
}

/* The fine vertex of split L whose parents are the sorted set v[0..m), or
 * SIZE_MAX. */
static size_t fine_of(const ss_split *L, const ss_idx *v, int m) {
  for (size_t f = 0; f < L->nfine; f++)
    if (ss_split_npar(L, f) == (size_t)m &&
        memcmp(L->parent + L->ptr[f], v, (size_t)m * sizeof *v) == 0)
      return f;
  return SIZE_MAX;
}

/* The rules of Joy and MacCracken written out literally, for the interior
 * elements of cx (hexes only), against the scheme's refinement. */
static void check_naive(const ss_cx *cx, const char *what) {
  ss_error err = {0};
  ss_scheme *s = scheme("ccsolid");
  ss_cx *fine = NULL;
  ss_split *L = NULL;
  gsl_spmatrix *R = NULL;
  if (ss_scheme_refine_split(s, cx, &fine, &R, &L, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    ss_scheme_free(s);
    return;
  }
  const size_t nh = cx->nc[SS_HEX];
  elems F, E;
  elems_init(&F, 6 * nh, 4);
  elems_init(&E, 12 * nh, 2);
  for (size_t h = 0; h < nh; h++) {
    const ss_idx *v = ss_cx_cell(cx, SS_HEX, h);
    for (int f = 0; f < 6; f++) {
      ss_idx q[4];
      for (int j = 0; j < 4; j++)
        q[j] = v[hex_faces[f][j]];
      size_t i = find_or_add(&F, q, 4, q);
      F.hex[i][F.nhex[i]++] = h;
    }
    for (int e = 0; e < ss_cell_nedges(SS_HEX); e++) {
      int a, b;
      ss_cell_edge(SS_HEX, e, &a, &b);
      ss_idx q[2] = {v[a], v[b]};
      size_t i = find_or_add(&E, q, 2, NULL);
      E.hex[i][E.nhex[i]++] = h;
    }
  }
  double(*cellpt)[3] = calloc(nh, sizeof *cellpt),
  (*facec)[3] = calloc(F.n, sizeof *facec);
  for (size_t h = 0; h < nh; h++)
    centroid(cx, ss_cx_cell(cx, SS_HEX, h), 8, cellpt[h]);
  for (size_t f = 0; f < F.n; f++)
    centroid(cx, F.cyc[f], 4, facec[f]);
  size_t tested = 0;
  double worst = 0.0;
  /* compare the naive point y with fine vertex of parents v[0..m) */
#define COMPARE(vv, m, y)                                                                \
  do {                                                                                   \
    size_t fv_ = fine_of(L, (vv), (m));                                                  \
    CHECK(fv_ != SIZE_MAX, "%s: no fine vertex for an element", what);                   \
    if (fv_ != SIZE_MAX) {                                                               \
      for (int d_ = 0; d_ < 3; d_++)                                                     \
        worst = fmax(worst, fabs(fine->x[3 * fv_ + (size_t)d_] - (y)[d_]));              \
      tested++;                                                                          \
    }                                                                                    \
  } while (0)
  /* cell points */
  for (size_t h = 0; h < nh; h++) {
    ss_idx v[8];
    memcpy(v, ss_cx_cell(cx, SS_HEX, h), sizeof v);
    qsort(v, 8, sizeof *v, cmp_idx);
    COMPARE(v, 8, cellpt[h]);
  }
  /* face points of interior faces: (C0 + 2 A + C1) / 4 */
  unsigned char *fint = calloc(F.n, 1);
  for (size_t f = 0; f < F.n; f++) {
    fint[f] = F.nhex[f] == 2;
    if (!fint[f]) continue;
    double y[3];
    for (int d = 0; d < 3; d++)
      y[d] = (cellpt[F.hex[f][0]][d] + 2.0 * facec[f][d] + cellpt[F.hex[f][1]][d]) / 4.0;
    COMPARE(F.v[f], 4, y);
  }
  /* edge points of interior edges: (C + 2 A + (n - 3) M) / n */
  unsigned char *eint = calloc(E.n, 1);
  for (size_t e = 0; e < E.n; e++) {
    const ss_idx a = E.v[e][0], b = E.v[e][1];
    double A[3] = {0, 0, 0}, C[3] = {0, 0, 0};
    size_t nf = 0;
    int interior = 1;
    for (size_t f = 0; f < F.n; f++) {
      if (!face_has_edge(F.cyc[f], a, b)) continue;
      interior &= fint[f];
      for (int d = 0; d < 3; d++)
        A[d] += facec[f][d];
      nf++;
    }
    eint[e] = (unsigned char)interior;
    if (!interior) continue;
    for (size_t i = 0; i < E.nhex[e]; i++)
      for (int d = 0; d < 3; d++)
        C[d] += cellpt[E.hex[e][i]][d];
    const double n = (double)nf;
    double y[3];
    for (int d = 0; d < 3; d++) {
      const double M = (cx->x[3 * a + (size_t)d] + cx->x[3 * b + (size_t)d]) / 2.0;
      y[d] = (C[d] / (double)E.nhex[e] + 2.0 * A[d] / n + (n - 3.0) * M) / n;
    }
    COMPARE(E.v[e], 2, y);
  }
  /* vertex points of interior vertices: (C + 3 A + 3 E + (n - 7) P) / n */
  size_t nvert = 0;
  for (size_t p = 0; p < cx->nv; p++) {
    double A[3] = {0, 0, 0}, C[3] = {0, 0, 0}, Ed[3] = {0, 0, 0};
    size_t nc = 0, nf = 0, ne = 0;
    int interior = 1;
    for (size_t h = 0; h < nh; h++) {
      const ss_idx *v = ss_cx_cell(cx, SS_HEX, h);
      int has = 0;
      for (int j = 0; j < 8; j++)
        has |= v[j] == p;
      if (!has) continue;
      for (int d = 0; d < 3; d++)
        C[d] += cellpt[h][d];
      nc++;
    }
    for (size_t f = 0; f < F.n; f++) {
      int has = 0;
      for (int j = 0; j < 4; j++)
        has |= F.v[f][j] == p;
      if (!has) continue;
      interior &= fint[f];
      for (int d = 0; d < 3; d++)
        A[d] += facec[f][d];
      nf++;
    }
    for (size_t e = 0; e < E.n; e++) {
      if (E.v[e][0] != p && E.v[e][1] != p) continue;
      for (int d = 0; d < 3; d++)
        Ed[d] +=
            (cx->x[3 * E.v[e][0] + (size_t)d] + cx->x[3 * E.v[e][1] + (size_t)d]) / 2.0;
      ne++;
    }
    if (!interior || nc == 0) continue;
    const double n = (double)nc;
    double y[3];
    for (int d = 0; d < 3; d++)
      y[d] = (C[d] / n + 3.0 * A[d] / (double)nf + 3.0 * Ed[d] / (double)ne +
              (n - 7.0) * cx->x[3 * p + (size_t)d]) /
             n;
    ss_idx pv = (ss_idx)p;
    COMPARE(&pv, 1, y);
    nvert++;
  }
#undef COMPARE
  double scale = 0.0;
  for (size_t i = 0; i < 3 * cx->nv; i++)
    scale = fmax(scale, fabs(cx->x[i]));
  CHECK(nvert > 0 && tested > nh, "%s: only %zu points (%zu interior vertices) compared",
        what, tested, nvert);
  CHECK(worst <= 1e-13 * scale, "%s: the scheme differs from the naive rules by %g", what,
        worst);
  printf("%s: %zu points (%zu interior vertices) agree with the naive rules to %.1e\n",
         what, tested, nvert, worst);
  free(fint);
  free(eint);
  free(cellpt);
  free(facec);
  elems_free(&F);
  elems_free(&E);
  gsl_spmatrix_free(R);
  ss_split_free(L);
  ss_cx_free(fine);
  ss_scheme_free(s);
}

/* A star split once (more interior: the centre, the edge midpoints around
 * it) and jittered. */
static ss_cx *split_jittered(const ss_cx *cx, unsigned long seed) {
  ss_error err = {0};
  ss_cx *fine = NULL;
  ss_split *L = NULL;
  if (ss_split_refine(SS_SPLIT_MULTILINEAR, cx, &fine, &L, &err)) {
    fprintf(stderr, "split: %s\n", err.msg);
    exit(1);
  }
  ss_split_free(L);
  tm_jitter(fine, 0.05, seed);
  return fine;
}

static ss_cx *edge_ring(int n) {
  ss_error err = {0};
  ss_star *st = NULL;
  ss_cx *cx = NULL;
  if (ss_star_hex_edge(n, &st, &err) || ss_cx_copy(st->cx, &cx, &err)) {
    fprintf(stderr, "edge star: %s\n", err.msg);
    exit(1);
  }
  ss_star_free(st);
  return cx;
}

static void test_naive(void) {
  tm_link *ico = tm_link_named("icosahedron");
  ss_cx *star = tm_hex_star(ico);
  ss_cx *m = split_jittered(star, 3);
  check_naive(m, "hexstar icosahedron, split once, jittered");
  ss_cx_free(m);
  ss_cx_free(star);
  tm_link_free(ico);
  const int ns[2] = {3, 5};
  for (int i = 0; i < 2; i++) {
    ss_cx *ring = edge_ring(ns[i]);
    ss_cx *r1 = split_jittered(ring, 5 + (unsigned long)i);
    char what[64];
    snprintf(what, sizeof what, "ring of %d hexes, split once, jittered", ns[i]);
    check_naive(r1, what);
    ss_cx_free(r1);
    ss_cx_free(ring);
  }
}

/* ---- 4. the boundary ---- */

/* The boundary quads of a hex mesh (faces in one hex), with its explicit
 * quads (not repeated), segments and vertex cells, over the same vertices. */
static ss_cx *boundary_surface(const ss_cx *cx) {
  ss_error err = {0};
  ss_cx *s = NULL;
  if (ss_cx_new(3, &s, &err)) exit(1);
  for (size_t v = 0; v < cx->nv; v++)
    if (ss_cx_add_vertex(s, cx->x + 3 * v, 0, &err)) exit(1);
  const size_t nh = cx->nc[SS_HEX];
  elems F;
  elems_init(&F, 6 * nh + cx->nc[SS_QUAD], 4);
  for (size_t h = 0; h < nh; h++) {
    const ss_idx *v = ss_cx_cell(cx, SS_HEX, h);
    for (int f = 0; f < 6; f++) {
      ss_idx q[4];
      for (int j = 0; j < 4; j++)
        q[j] = v[hex_faces[f][j]];
      size_t i = find_or_add(&F, q, 4, q);
      F.nhex[i]++;
    }
  }
  for (size_t q = 0; q < cx->nc[SS_QUAD]; q++) {
    size_t i = find_or_add(&F, ss_cx_cell(cx, SS_QUAD, q), 4, ss_cx_cell(cx, SS_QUAD, q));
    F.nhex[i] = 1; /* an explicit quad is a surface quad */
  }
  for (size_t f = 0; f < F.n; f++)
    if (F.nhex[f] == 1 && ss_cx_add_cell(s, SS_QUAD, F.cyc[f], 0, &err)) exit(1);
  for (size_t i = 0; i < cx->nc[SS_SEGMENT]; i++)
    if (ss_cx_add_cell(s, SS_SEGMENT, ss_cx_cell(cx, SS_SEGMENT, i), 0, &err)) exit(1);
  for (size_t i = 0; i < cx->nc[SS_VERTEX]; i++)
    if (ss_cx_add_cell(s, SS_VERTEX, ss_cx_cell(cx, SS_VERTEX, i), 0, &err)) exit(1);
  elems_free(&F);
  return s;
}

static void check_boundary(const ss_cx *cx, const char *what) {
  ss_error err = {0};
  ss_scheme *cs = scheme("ccsolid"), *cc = scheme("catmull-clark");
  ss_cx *surf = boundary_surface(cx);
  ss_cx *fs = NULL, *fc = NULL;
  ss_split *Ls = NULL, *Lc = NULL;
  gsl_spmatrix *R1 = NULL, *R2 = NULL;
  if (ss_scheme_refine_split(cs, cx, &fs, &R1, &Ls, &err) ||
      ss_scheme_refine_split(cc, surf, &fc, &R2, &Lc, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    return;
  }
  /* the surface's vertices: those in a fine surface quad */
  unsigned char *in = calloc(fc->nv + 1, 1);
  for (size_t i = 0; i < fc->nc[SS_QUAD] * 4; i++)
    in[fc->cells[SS_QUAD][i]] = 1;
  size_t tested = 0;
  double worst = 0.0, scale = 0.0;
  for (size_t i = 0; i < 3 * cx->nv; i++)
    scale = fmax(scale, fabs(cx->x[i]));
  for (size_t f = 0; f < fc->nv; f++) {
    if (!in[f]) continue;
    size_t g = fine_of(Ls, Lc->parent + Lc->ptr[f], (int)ss_split_npar(Lc, f));
    CHECK(g != SIZE_MAX, "%s: surface vertex %zu not in the solid's refinement", what, f);
    if (g == SIZE_MAX) continue;
    for (int d = 0; d < 3; d++)
      worst = fmax(worst, fabs(fs->x[3 * g + (size_t)d] - fc->x[3 * f + (size_t)d]));
    tested++;
  }
  CHECK(tested > 0 && worst <= 1e-13 * scale,
        "%s: boundary differs from Catmull-Clark by %g (%zu points)", what, worst,
        tested);
  printf("%s: %zu boundary points equal Catmull-Clark's to %.1e\n", what, tested, worst);
  check_paths_agree("ccsolid", cx, what);
  free(in);
  gsl_spmatrix_free(R1);
  gsl_spmatrix_free(R2);
  ss_split_free(Ls);
  ss_split_free(Lc);
  ss_cx_free(fs);
  ss_cx_free(fc);
  ss_cx_free(surf);
  ss_scheme_free(cs);
  ss_scheme_free(cc);
}

static void test_boundary(void) {
  tm_link *ico = tm_link_named("icosahedron");
  ss_cx *star = tm_hex_star(ico);
  ss_cx *m = split_jittered(star, 11);
  check_boundary(m, "hexstar icosahedron, split, jittered");
  /* with creases: a segment across the boundary and a corner */
  ss_error err = {0};
  ss_idx seg[2] = {0, 0}, corner = 0;
  {
    /* a boundary edge of the first hex (both ends on the boundary) */
    const ss_idx *h = ss_cx_cell(m, SS_HEX, m->nc[SS_HEX] - 1);
    seg[0] = h[6];
    seg[1] = h[7];
    corner = h[5];
  }
  if (ss_cx_add_cell(m, SS_SEGMENT, seg, 0, &err) ||
      ss_cx_add_cell(m, SS_VERTEX, &corner, 0, &err))
    exit(1);
  check_boundary(m, "hexstar icosahedron with a crease segment and a corner");
  ss_cx_free(m);
  ss_cx_free(star);
  tm_link_free(ico);
  ss_cx *ring = edge_ring(5);
  ss_cx *r1 = split_jittered(ring, 13);
  check_boundary(r1, "ring of 5 hexes, split, jittered");
  ss_cx_free(r1);
  ss_cx_free(ring);
  /* a 3^3 grid with explicit crease quads on its outer faces: the same
   * surface (quads not counted twice) */
  ss_cx *g = grid(4);
  tm_jitter(g, 0.2, 19);
  ss_cx *gs = boundary_surface(g);
  for (size_t q = 0; q < gs->nc[SS_QUAD]; q++)
    if (ss_cx_add_cell(g, SS_QUAD, ss_cx_cell(gs, SS_QUAD, q), 0, &err)) exit(1);
  check_boundary(g, "4^3 grid with its boundary quads given");
  ss_cx_free(gs);
  ss_cx_free(g);
}

/* ---- 5. extraordinary edges ---- */

/* The Z_n rotation of an edge or surface chart (coordinate i -> i + 1 mod n
 * for i < n) as a permutation of M's labels; -1 if a label leaves the set. */
static int rotation(const ss_local *M, int n, size_t *rot) {
  for (size_t i = 0; i < M->n2; i++) {
    const ss_star_coord *c = M->label + i;
    int32_t idx[SS_STAR_MAXSUPP], val[SS_STAR_MAXSUPP];
    for (int e = 0; e < c->n; e++) {
      idx[e] = c->idx[e] < n ? (c->idx[e] + 1) % n : c->idx[e];
      val[e] = c->val[e];
    }
    ss_star_coord r = ss_star_coord_make(c->n, idx, val);
    rot[i] = ss_local_label_index(M, &r);
    if (rot[i] == SIZE_MAX) return -1;
  }
  return 0;
}

/* The rotation-invariant (Fourier mode 0) block of S (n2 x n2, commuting with
 * the permutation rot): B[a][b] = sum over the orbit b of S[rep a][j].
 * Returns the number of orbits m; B is m x m. */
static size_t invariant_block(const double *S, size_t n2, const size_t *rot, double *B) {
  size_t *orb = malloc(n2 * sizeof *orb), *rep = malloc(n2 * sizeof *rep), m = 0;
  for (size_t i = 0; i < n2; i++)
    orb[i] = SIZE_MAX;
  for (size_t i = 0; i < n2; i++) {
    if (orb[i] != SIZE_MAX) continue;
    rep[m] = i;
    for (size_t j = i; orb[j] == SIZE_MAX; j = rot[j])
      orb[j] = m;
    m++;
  }
  for (size_t a = 0; a < m; a++)
    for (size_t b = 0; b < m; b++) {
      double sum = 0.0;
      for (size_t j = 0; j < n2; j++)
        if (orb[j] == b) sum += S[rep[a] * n2 + j];
      B[a * m + b] = sum;
    }
  free(orb);
  free(rep);
  return m;
}

/* The largest four of the m eigenvalues (wr, wi) below 1 in modulus. */
static void print_leading(size_t m, const double *wr, const double *wi,
                          const char *what) {
  double last = 1.0 - 1e-9;
  printf(" %s", what);
  for (int k = 0; k < 4; k++) {
    double best = -1.0;
    for (size_t i = 0; i < m; i++) {
      double a = hypot(wr[i], wi[i]);
      if (a < last && a > best) best = a;
    }
    if (best < 0) break;
    printf(" %.6f", best);
    last = best - 1e-9;
  }
}

/* How many of the m eigenvalues (wr, wi) are within 1e-12 (relative) of x. */
static int count_near(size_t m, const double *wr, const double *wi, double x) {
  int c = 0;
  for (size_t i = 0; i < m; i++)
    c += hypot(wr[i] - x, wi[i]) <= 1e-12 * fmax(1.0, fabs(x));
  return c;
}

/* The edge of valence n: the scheme's matrix S (ccsolid or ccsolid-tensor)
 * against the separable operator T = S_cc (x) S_curve, built here label by
 * label from the Catmull-Clark surface matrix of valence n and the curve's
 * mask (an edge label is a surface label plus an axis coordinate t in
 * -2..2).  Derivation (README): for ccsolid only the rows of the points on
 * the edge itself (surface label 0, t even) differ, by rotation-invariant
 * rows, so S and T agree on every Fourier mode w != 0 and differ (n != 4) on
 * w = 0.  Checked: the rows, and the spectra as spec S + spec T_0 = spec T +
 * spec S_0 (the _0 blocks are mode 0).  For ccsolid-tensor no row differs:
 * S = T entry for entry, and spec S is spec S_cc times the curve's. */
static void check_edge(const char *name, int n) {
  const int tensor = !strcmp(name, "ccsolid-tensor");
  ss_local *S = local(name, (ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0});
  ss_local *Q =
      local("catmull-clark", (ss_case){SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0});
  const size_t n2 = S->n2, q2 = Q->n2;
  CHECK(n2 == 5 * q2, "edge %d: two-ring %zu, surface two-ring %zu", n, n2, q2);
  if (n2 != 5 * q2) goto done;
  double *T = calloc(n2 * n2, sizeof *T);
  size_t *ci = malloc(n2 * sizeof *ci);
  int *ti = malloc(n2 * sizeof *ti);
  for (size_t i = 0; i < n2; i++) {
    const ss_star_coord *c = S->label + i;
    int32_t idx[SS_STAR_MAXSUPP], val[SS_STAR_MAXSUPP];
    int m = 0;
    ti[i] = 0;
    for (int e = 0; e < c->n; e++) {
      if (c->idx[e] == n) { /* the axis chart counts 2 per cell (ss_star.h) */
        ti[i] = c->val[e] % 2 ? 99 : c->val[e] / 2;
      } else {
        idx[m] = c->idx[e];
        val[m++] = c->val[e];
      }
    }
    ss_star_coord y = ss_star_coord_make(m, idx, val);
    ci[i] = ss_local_label_index(Q, &y);
    CHECK(ci[i] != SIZE_MAX && ti[i] >= -2 && ti[i] <= 2,
          "edge %d: label %zu is no surface label times -2..2", n, i);
    if (ci[i] == SIZE_MAX) ci[i] = 0;
  }
  for (size_t i = 0; i < n2; i++)
    for (size_t j = 0; j < n2; j++)
      T[i * n2 + j] = Q->S[ci[i] * q2 + ci[j]] * op_bspline(ti[i] - 2 * ti[j]);
  size_t *rot = malloc(n2 * sizeof *rot);
  CHECK(rotation(S, n, rot) == 0, "edge %d: labels not closed under rotation", n);
  /* the rows: equal off the edge's own vertices */
  double off = 0.0, on_vertex = 0.0, on_edge = 0.0, asym = 0.0;
  for (size_t i = 0; i < n2; i++) {
    const int axis = Q->label[ci[i]].n == 0;
    for (size_t j = 0; j < n2; j++) {
      const double d = fabs(S->S[i * n2 + j] - T[i * n2 + j]);
      if (!axis)
        off = fmax(off, d);
      else if (ti[i] % 2 == 0)
        on_vertex = fmax(on_vertex, d);
      else
        on_edge = fmax(on_edge, d);
      if (axis) /* the difference row is rotation-invariant */
        asym = fmax(asym, fabs((S->S[i * n2 + j] - T[i * n2 + j]) -
                               (S->S[i * n2 + rot[j]] - T[i * n2 + rot[j]])));
    }
  }
  CHECK(off <= 1e-15, "edge %d: rows off the edge differ from the tensor rule by %g", n,
        off);
  CHECK(on_edge <= 1e-15, "edge %d: edge-point rows differ from the tensor rule by %g", n,
        on_edge);
  CHECK(asym <= 1e-15, "edge %d: the difference is not rotation-invariant (%g)", n, asym);
  if (n == 4 || tensor) /* entries <= 1 summed in other orders: a few ulps */
    CHECK(on_vertex <= 4e-15, "%s edge %d: vertex rows differ by %g", name, n, on_vertex);
  else
    CHECK(on_vertex > 1e-3, "edge %d: vertex rows equal the tensor rule (%g)", n,
          on_vertex);
  /* the vertex weight on itself: 1 - 37/(16 n) against 3/4 (1 - 7/(4 n)) */
  {
    /* fine label +2 on the axis is the vertex point of coarse label +1 */
    int32_t ai = n, av = 4;
    ss_star_coord a = ss_star_coord_make(1, &ai, &av);
    size_t i = ss_local_label_index(S, &a);
    int32_t bi = n, bv = 2;
    ss_star_coord b = ss_star_coord_make(1, &bi, &bv);
    size_t j = ss_local_label_index(S, &b);
    CHECK(i != SIZE_MAX && j != SIZE_MAX, "edge %d: axis labels missing", n);
    if (i != SIZE_MAX && j != SIZE_MAX) {
      CHECK_CLOSE(S->S[i * n2 + j],
                  tensor ? 0.75 * (1.0 - 7.0 / (4.0 * n)) : 1.0 - 37.0 / (16.0 * n),
                  1e-14, "%s edge %d: vertex weight on itself", name, n);
      CHECK_CLOSE(T[i * n2 + j], 0.75 * (1.0 - 7.0 / (4.0 * n)), 1e-14,
                  "edge %d: tensor vertex weight on itself", n);
    }
  }
  /* spectra: T's is the tensor product of the surface's and the curve's */
  double *sr = malloc(2 * n2 * sizeof *sr), *si = malloc(2 * n2 * sizeof *si);
  double *tr = malloc(2 * n2 * sizeof *tr), *tt = malloc(2 * n2 * sizeof *tt);
  double *qr = malloc(q2 * sizeof *qr), *qi = malloc(q2 * sizeof *qi);
  double *pr = malloc(n2 * sizeof *pr), *pi = malloc(n2 * sizeof *pi);
  double C[25], cr[5], cim[5];
  curve_matrix(C);
  eigvals(C, 5, cr, cim);
  eigvals(Q->S, q2, qr, qi);
  for (size_t a = 0; a < q2; a++)
    for (int b = 0; b < 5; b++) {
      pr[a * 5 + (size_t)b] = qr[a] * cr[b];
      pi[a * 5 + (size_t)b] = qi[a] * cr[b];
    }
  eigvals(S->S, n2, sr, si);
  eigvals(T, n2, tr, tt);
  const double dT = multiset_dist(n2, tr, tt, pr, pi);
  CHECK(dT < 1e-12, "edge %d: spec T differs from spec S_cc x curve by %g", n, dT);
  /* mode 0 blocks */
  double *B = malloc(n2 * n2 * sizeof *B);
  size_t m = invariant_block(S->S, n2, rot, B);
  eigvals(B, m, sr + n2, si + n2);
  size_t m2 = invariant_block(T, n2, rot, B);
  eigvals(B, m2, tr + n2, tt + n2);
  CHECK(m == m2, "edge %d: orbit counts", n);
  /* spec S + spec T_0 = spec T + spec S_0: swap the mode-0 parts */
  double *xr = malloc(2 * n2 * sizeof *xr), *xi = malloc(2 * n2 * sizeof *xi);
  memcpy(xr, tr, n2 * sizeof *xr);
  memcpy(xi, tt, n2 * sizeof *xi);
  memcpy(xr + n2, sr + n2, m * sizeof *xr);
  memcpy(xi + n2, si + n2, m * sizeof *xi);
  memcpy(sr + n2, tr + n2, m * sizeof *sr);
  memcpy(si + n2, tt + n2, m * sizeof *si);
  const double dswap = multiset_dist(n2 + m, sr, si, xr, xi);
  CHECK(dswap < 1e-12, "edge %d: spec S + spec T_0 != spec T + spec S_0 (%g)", n, dswap);
  const double d0 = multiset_dist(m, xr + n2, xi + n2, sr + n2, si + n2);
  const double dall = multiset_dist(n2, sr, si, tr, tt);
  if (n == 4 || tensor)
    CHECK(dall < 1e-12 && d0 < 1e-12,
          "%s edge %d: spectrum differs from the tensor product (%g, mode 0 %g)", name, n,
          dall, d0);
  else
    CHECK(d0 > 1e-3 && dall > 1e-3,
          "edge %d: the mode-0 spectrum equals the tensor product's (%g, %g)", n, d0,
          dall);
  if (tensor) { /* Catmull-Clark's subdominant pair (closed form) times 1 and 1/2 */
    const double c = cos(2.0 * M_PI / n);
    const double l1 = (5.0 + c + cos(M_PI / n) * sqrt(2.0 * (9.0 + c))) / 16.0;
    const int a = count_near(n2, sr, si, l1), b = count_near(n2, sr, si, l1 / 2.0);
    CHECK(a >= 2 && b >= 2 && count_near(n2, sr, si, 0.25) >= 1,
          "%s edge %d: lambda_1(n) = %.15g x {1, 1/2} not double in spec S (%d, %d)",
          name, n, l1, a, b);
  }
  /* the leading mode-0 eigenvalues after 1 (distinct values), for docs/schemes.md */
  printf("%s edge %2d: rows off the edge equal (%.0e); modes w != 0 equal (%.0e); mode 0 "
         "differs by %.3g:",
         name, n, off, dswap, d0);
  print_leading(m, xr + n2, xi + n2, name);
  print_leading(m, sr + n2, si + n2, "tensor");
  printf("\n");
  free(xr);
  free(xi);
  free(B);
  free(sr);
  free(si);
  free(tr);
  free(tt);
  free(qr);
  free(qi);
  free(pr);
  free(pi);
  free(rot);
  free(T);
  free(ci);
  free(ti);
done:
  ss_local_free(S);
  ss_local_free(Q);
}

static void test_edges(void) {
  for (int n = 3; n <= 10; n++) {
    check_edge("ccsolid", n);
    check_edge("ccsolid-tensor", n);
  }
}

/* ---- 6. bad input ---- */

static void expect_refused(const ss_cx *cx, const char *phrase, const char *what) {
  ss_error err = {0};
  ss_scheme *s = scheme("ccsolid");
  ss_cx *fine = NULL;
  ss_status st = ss_scheme_refine(s, cx, &fine, NULL, &err);
  CHECK(st == SS_EINPUT && strstr(err.msg, phrase),
        "%s: status %d, message '%s' (expected '%s')", what, (int)st, err.msg, phrase);
  ss_cx_free(fine);
  ss_scheme_free(s);
}

/* Unit cube hexes at integer offsets, sharing vertices by position. */
static ss_cx *cubes(int n, const int (*off)[3]) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  if (ss_cx_new(3, &cx, &err)) exit(1);
  for (int c = 0; c < n; c++) {
    ss_idx h[8];
    for (int k = 0; k < 8; k++) {
      unsigned b = ss_cube_corner_bits(3, k);
      double x[3] = {off[c][0] + (double)(b & 1u), off[c][1] + (double)(b >> 1 & 1u),
                     off[c][2] + (double)(b >> 2 & 1u)};
      size_t v = 0;
      while (v < cx->nv && memcmp(cx->x + 3 * v, x, sizeof x) != 0)
        v++;
      if (v == cx->nv && ss_cx_add_vertex(cx, x, 0, &err)) exit(1);
      h[k] = (ss_idx)v;
    }
    if (ss_cx_add_cell(cx, SS_HEX, h, 0, &err)) exit(1);
  }
  return cx;
}

static void test_bad_input(void) {
  const int vtx[2][3] = {{0, 0, 0}, {1, 1, 1}};
  ss_cx *a = cubes(2, vtx);
  expect_refused(a, "non-manifold", "two cubes sharing a vertex");
  ss_cx_free(a);
  const int edge[2][3] = {{0, 0, 0}, {1, 1, 0}};
  ss_cx *b = cubes(2, edge);
  expect_refused(b, "non-manifold", "two cubes sharing an edge");
  ss_cx_free(b);
  /* three hexes on one face: the third copies the second's vertices */
  const int two[2][3] = {{0, 0, 0}, {0, 0, 1}};
  ss_cx *c = cubes(2, two);
  ss_error err = {0};
  ss_idx h[8];
  memcpy(h, ss_cx_cell(c, SS_HEX, 1), sizeof h);
  for (int k = 4; k < 8; k++) { /* a new top face */
    double x[3];
    memcpy(x, c->x + 3 * h[k], sizeof x);
    x[0] += 0.1;
    if (ss_cx_add_vertex(c, x, 0, &err)) exit(1);
    h[k] = (ss_idx)(c->nv - 1);
  }
  if (ss_cx_add_cell(c, SS_HEX, h, 0, &err)) exit(1);
  expect_refused(c, "lies in 3 hexahedra", "a face in three hexes");
  ss_cx_free(c);
  /* the 2 x 2 x 2 block about the origin without two opposite cubes: the six
   * left are joined through faces at the origin, but their link there is an
   * annulus (the octahedron without two opposite triangles, chi = 0) */
  const int ann[6][3] = {{-1, 0, 0},  {0, -1, 0},  {0, 0, -1},
                         {-1, -1, 0}, {-1, 0, -1}, {0, -1, -1}};
  ss_cx *e = cubes(6, ann);
  expect_refused(e, "Euler characteristic 0", "six cubes with an annulus link");
  ss_cx_free(e);
  ss_cx *k = tm_kuhn(1);
  expect_refused(k, "does not take tetrahedra", "tets");
  ss_cx_free(k);
}

int main(void) {
  test_regular_vertex();
  test_grid_convergence();
  op_check_tensor_rule("ccsolid", 3, 4);
  op_check_tensor_rule("ccsolid-tensor", 3, 4);
  test_naive();
  test_boundary();
  test_edges();
  test_bad_input();
  return ss_test_done("ccsolid");
}
