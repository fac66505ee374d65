/* ss_testmesh.c — builders of test complexes (see ss_testmesh.h). */
#include "ss_testmesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "ss_diag.h"

#define PI 3.14159265358979323846

static void die(const char *what) {
  fprintf(stderr, "test mesh builder failed: %s\n", what);
  exit(99);
}

static ss_cx *newcx(int dim) {
  ss_cx *cx;
  ss_error err = {0};
  if (ss_cx_new(dim, &cx, &err)) die(err.msg);
  return cx;
}

static void addv(ss_cx *cx, const double *x) {
  ss_error err = {0};
  if (ss_cx_add_vertex(cx, x, 0, &err)) die(err.msg);
}

static void addc(ss_cx *cx, ss_cell_type t, const ss_idx *v) {
  ss_error err = {0};
  if (ss_cx_add_cell(cx, t, v, 0, &err)) die(err.msg);
}

static void normalize(double *x) {
  double n = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  for (int i = 0; i < 3; i++)
    x[i] /= n;
}

static double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

tm_link *tm_link_named(const char *name) {
  tm_link *l = calloc(1, sizeof *l);
  if (!l) die("link");
  int N = 0;
  if (!strcmp(name, "tetrahedron")) {
    l->k = 4;
  } else if (!strcmp(name, "octahedron")) {
    N = 4;
    l->k = 6;
  } else if (!strcmp(name, "icosahedron")) {
    l->k = 12;
  } else if (sscanf(name, "bipyramid:%d", &N) == 1 && N >= 3) {
    l->k = N + 2;
  } else {
    die(name);
  }
  l->ntri = 2 * l->k - 4;
  l->tri = calloc((size_t)l->ntri, sizeof *l->tri);
  l->x = calloc((size_t)l->k, sizeof *l->x);
  if (!l->tri || !l->x) die("link");
  int t = 0;
  if (l->k == 4) {
    const double s = 1.0 / sqrt(3.0);
    const double p[4][3] = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
    memcpy(l->x, p, sizeof p);
    const int tr[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    memcpy(l->tri, tr, sizeof tr);
  } else if (l->k == 12 && N == 0) {
    /* top 0, upper ring 1..5, lower ring 6..10 (turned by pi/5), bottom 11 */
    const double h = 1.0 / sqrt(5.0), r = 2.0 / sqrt(5.0);
    l->x[0][2] = 1.0;
    l->x[11][2] = -1.0;
    for (int i = 0; i < 5; i++) {
      l->x[1 + i][0] = r * cos(2 * PI * i / 5);
      l->x[1 + i][1] = r * sin(2 * PI * i / 5);
      l->x[1 + i][2] = h;
      l->x[6 + i][0] = r * cos(2 * PI * (i + 0.5) / 5);
      l->x[6 + i][1] = r * sin(2 * PI * (i + 0.5) / 5);
      l->x[6 + i][2] = -h;
    }
    for (int i = 0; i < 5; i++) {
      int u0 = 1 + i, u1 = 1 + (i + 1) % 5, d0 = 6 + i, d1 = 6 + (i + 1) % 5;
      int tr[4][3] = {{0, u0, u1}, {u0, d0, u1}, {u1, d0, d1}, {d0, 11, d1}};
      for (int j = 0; j < 4; j++)
        memcpy(l->tri[t++], tr[j], sizeof tr[j]);
    }
  } else {
    for (int i = 0; i < N; i++) {
      l->x[i][0] = cos(2 * PI * i / N);
      l->x[i][1] = sin(2 * PI * i / N);
    }
    l->x[N][2] = 1.0;
    l->x[N + 1][2] = -1.0;
    for (int i = 0; i < N; i++) {
      int a = i, b = (i + 1) % N;
      int t0[3] = {a, b, N}, t1[3] = {b, a, N + 1};
      memcpy(l->tri[t++], t0, sizeof t0);
      memcpy(l->tri[t++], t1, sizeof t1);
    }
  }
  /* orient every triangle outward (the sphere is star-shaped about 0) */
  for (int i = 0; i < l->ntri; i++) {
    double *a = l->x[l->tri[i][0]], *b = l->x[l->tri[i][1]], *c = l->x[l->tri[i][2]];
    double e1[3], e2[3], n[3];
    for (int j = 0; j < 3; j++) {
      e1[j] = b[j] - a[j];
      e2[j] = c[j] - a[j];
    }
    cross3(e1, e2, n);
    if (dot3(n, a) < 0) {
      int s = l->tri[i][1];
      l->tri[i][1] = l->tri[i][2];
      l->tri[i][2] = s;
    }
  }
  return l;
}

void tm_link_free(tm_link *l) {
  if (!l) return;
  free(l->tri);
  free(l->x);
  free(l);
}

ss_cx *tm_torus(int d, int N) {
  ss_cx *cx = newcx(d);
  int nv = 1;
  for (int i = 0; i < d; i++)
    nv *= N;
  for (int v = 0; v < nv; v++) {
    double x[3] = {(double)(v % N), (double)((v / N) % N), (double)(v / (N * N))};
    addv(cx, x);
  }
  ss_cell_type t = d == 1 ? SS_SEGMENT : d == 2 ? SS_QUAD : SS_HEX;
  for (int c = 0; c < nv; c++) {
    int base[3] = {c % N, (c / N) % N, c / (N * N)};
    ss_idx v[8];
    for (int k = 0; k < (1 << d); k++) {
      unsigned b = ss_cube_corner_bits(d, k);
      int idx = 0, s = 1;
      for (int i = 0; i < d; i++, s *= N)
        idx += ((base[i] + (int)((b >> i) & 1u)) % N) * s;
      v[k] = (ss_idx)idx;
    }
    addc(cx, t, v);
  }
  return cx;
}

ss_cx *tm_torus_triangles(int N) {
  ss_cx *cx = newcx(2);
  for (int v = 0; v < N * N; v++) {
    double x[2] = {(double)(v % N), (double)(v / N)};
    addv(cx, x);
  }
  for (int j = 0; j < N; j++)
    for (int i = 0; i < N; i++) {
      ss_idx a = (ss_idx)(i + N * j), b = (ss_idx)((i + 1) % N + N * j),
             c = (ss_idx)((i + 1) % N + N * ((j + 1) % N)),
             e = (ss_idx)(i + N * ((j + 1) % N));
      ss_idx t0[3] = {a, b, c}, t1[3] = {a, c, e};
      addc(cx, SS_TRIANGLE, t0);
      addc(cx, SS_TRIANGLE, t1);
    }
  return cx;
}

ss_cx *tm_polygon(int n) {
  ss_cx *cx = newcx(2);
  for (int i = 0; i < n; i++) {
    double x[2] = {cos(2 * PI * i / n), sin(2 * PI * i / n)};
    addv(cx, x);
  }
  for (int i = 0; i < n; i++) {
    ss_idx v[2] = {(ss_idx)i, (ss_idx)((i + 1) % n)};
    addc(cx, SS_SEGMENT, v);
  }
  return cx;
}

/* index of the link edge {a,b} in a k x k table, assigned on first use */
static ss_idx edge_vertex(ss_cx *cx, ss_idx *tab, int k, const tm_link *l, int a, int b) {
  ss_idx *e = &tab[a * k + b];
  if (*e == SS_IDX_NONE) {
    double x[3];
    for (int j = 0; j < 3; j++)
      x[j] = l->x[a][j] + l->x[b][j];
    normalize(x);
    *e = tab[b * k + a] = (ss_idx)cx->nv;
    addv(cx, x);
  }
  return *e;
}

ss_cx *tm_hex_star(const tm_link *l) {
  ss_cx *cx = newcx(3);
  const int k = l->k;
  double o[3] = {0, 0, 0};
  addv(cx, o);
  for (int i = 0; i < k; i++)
    addv(cx, l->x[i]);
  ss_idx *tab = malloc((size_t)(k * k) * sizeof *tab);
  if (!tab) die("star");
  for (int i = 0; i < k * k; i++)
    tab[i] = SS_IDX_NONE;
  for (int t = 0; t < l->ntri; t++) {
    int a = l->tri[t][0], b = l->tri[t][1], c = l->tri[t][2];
    ss_idx ab = edge_vertex(cx, tab, k, l, a, b), bc = edge_vertex(cx, tab, k, l, b, c),
           ca = edge_vertex(cx, tab, k, l, c, a);
    double x[3];
    for (int j = 0; j < 3; j++)
      x[j] = l->x[a][j] + l->x[b][j] + l->x[c][j];
    normalize(x);
    ss_idx abc = (ss_idx)cx->nv;
    addv(cx, x);
    /* binary corners: v 000, a 100, ab 110, b 010, c 001, ca 101, abc 111, bc 011 */
    ss_idx h[8] = {0, (ss_idx)(1 + a), ab, (ss_idx)(1 + b), (ss_idx)(1 + c), ca, abc, bc};
    addc(cx, SS_HEX, h);
    if (ss_cx_cell_orientation(cx, SS_HEX, cx->nc[SS_HEX] - 1, NULL) < 0) {
      /* mirror a <-> b (a symmetry of the cube) to make it positive */
      ss_idx *q = ss_cx_cell(cx, SS_HEX, cx->nc[SS_HEX] - 1);
      ss_idx m[8] = {0, (ss_idx)(1 + b), ab, (ss_idx)(1 + a), (ss_idx)(1 + c), bc, abc,
                     ca};
      memcpy(q, m, sizeof m);
    }
  }
  free(tab);
  return cx;
}

/* Append the tet v, its vertices swapped if needed to make it positive. */
static void add_positive_tet(ss_cx *cx, const ss_idx v[4]) {
  addc(cx, SS_TET, v);
  size_t i = cx->nc[SS_TET] - 1;
  if (ss_cx_cell_orientation(cx, SS_TET, i, NULL) < 0) {
    ss_idx *q = ss_cx_cell(cx, SS_TET, i);
    ss_idx s = q[1];
    q[1] = q[2];
    q[2] = s;
  }
}

ss_cx *tm_tet_star(const tm_link *l) {
  ss_cx *cx = newcx(3);
  double o[3] = {0, 0, 0};
  addv(cx, o);
  for (int i = 0; i < l->k; i++)
    addv(cx, l->x[i]);
  for (int t = 0; t < l->ntri; t++) {
    ss_idx v[4] = {0, (ss_idx)(1 + l->tri[t][0]), (ss_idx)(1 + l->tri[t][1]),
                   (ss_idx)(1 + l->tri[t][2])};
    add_positive_tet(cx, v);
  }
  return cx;
}

ss_cx *tm_link_surface(const tm_link *l) {
  ss_cx *cx = newcx(3);
  for (int i = 0; i < l->k; i++)
    addv(cx, l->x[i]);
  for (int t = 0; t < l->ntri; t++) {
    ss_idx v[3] = {(ss_idx)l->tri[t][0], (ss_idx)l->tri[t][1], (ss_idx)l->tri[t][2]};
    addc(cx, SS_TRIANGLE, v);
  }
  return cx;
}

ss_cx *tm_link_quads(const tm_link *l) {
  ss_cx *cx = newcx(3);
  const int k = l->k;
  for (int i = 0; i < k; i++)
    addv(cx, l->x[i]);
  ss_idx *tab = malloc((size_t)(k * k) * sizeof *tab);
  if (!tab) die("quads");
  for (int i = 0; i < k * k; i++)
    tab[i] = SS_IDX_NONE;
  for (int t = 0; t < l->ntri; t++) {
    const int *a = l->tri[t];
    ss_idx m[3];
    for (int j = 0; j < 3; j++)
      m[j] = edge_vertex(cx, tab, k, l, a[j], a[(j + 1) % 3]);
    double x[3];
    for (int j = 0; j < 3; j++)
      x[j] = l->x[a[0]][j] + l->x[a[1]][j] + l->x[a[2]][j];
    normalize(x);
    ss_idx c = (ss_idx)cx->nv;
    addv(cx, x);
    for (int j = 0; j < 3; j++) {
      /* corner a[j], midpoint to the next, centre, midpoint from the previous */
      ss_idx q[4] = {(ss_idx)a[j], m[j], c, m[(j + 2) % 3]};
      addc(cx, SS_QUAD, q);
    }
  }
  free(tab);
  return cx;
}

ss_cx *tm_kuhn(int N) {
  ss_cx *cx = newcx(3);
  const int M = N + 1;
  for (int v = 0; v < M * M * M; v++) {
    double x[3] = {(double)(v % M), (double)((v / M) % M), (double)(v / (M * M))};
    addv(cx, x);
  }
  /* the six monotone paths from corner 000 to 111 */
  static const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                 {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < N; k++)
    for (int j = 0; j < N; j++)
      for (int i = 0; i < N; i++)
        for (int p = 0; p < 6; p++) {
          int pos[3] = {i, j, k};
          ss_idx v[4];
          v[0] = (ss_idx)(i + M * j + M * M * k);
          for (int s = 0; s < 3; s++) {
            pos[perm[p][s]]++;
            v[s + 1] = (ss_idx)(pos[0] + M * pos[1] + M * M * pos[2]);
          }
          add_positive_tet(cx, v);
        }
  return cx;
}

void tm_jitter(ss_cx *cx, double amp, unsigned long seed) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  if (!r) die("rng");
  gsl_rng_set(r, seed);
  for (size_t i = 0; i < cx->nv * (size_t)cx->dim; i++)
    cx->x[i] += amp * (2.0 * gsl_rng_uniform(r) - 1.0);
  gsl_rng_free(r);
}

/* Orientation-preserving symmetries as maps old local index -> new local index. */
static void random_symmetry(ss_cell_type t, gsl_rng *r, int *map) {
  int n = ss_cell_nverts(t);
  for (int i = 0; i < n; i++)
    map[i] = i;
  int steps = 1 + (int)gsl_rng_uniform_int(r, 6);
  for (int s = 0; s < steps; s++) {
    int g[8];
    int which = (int)gsl_rng_uniform_int(r, 2);
    switch (t) {
    case SS_SEGMENT: /* segments carry no orientation a scheme could see */
      g[0] = 1, g[1] = 0;
      break;
    case SS_TRIANGLE:
      g[0] = 1, g[1] = 2, g[2] = 0;
      break;
    case SS_QUAD:
      g[0] = 1, g[1] = 2, g[2] = 3, g[3] = 0;
      break;
    case SS_TET: /* 3-cycles generate the even permutations */
      if (which)
        g[0] = 1, g[1] = 2, g[2] = 0, g[3] = 3;
      else
        g[0] = 0, g[1] = 2, g[2] = 3, g[3] = 1;
      break;
    case SS_HEX:
      for (int k = 0; k < 8; k++) {
        unsigned b = ss_cube_corner_bits(3, k), x = b & 1u, y = (b >> 1) & 1u,
                 z = (b >> 2) & 1u, nb;
        if (which)
          nb = (1u - y) | (x << 1) | (z << 2); /* quarter turn about z */
        else
          nb = x | ((1u - z) << 1) | (y << 2); /* quarter turn about x */
        g[k] = ss_cube_corner_index(3, nb);
      }
      break;
    case SS_OCT: {
      static const int rz[6] = {1, 3, 2, 4, 0, 5}, rx[6] = {0, 2, 4, 3, 5, 1};
      for (int k = 0; k < 6; k++)
        g[k] = which ? rz[k] : rx[k];
      break;
    }
    default:
      g[0] = 0;
    }
    for (int i = 0; i < n; i++)
      map[i] = g[map[i]];
  }
}

ss_cx *tm_permuted(const ss_cx *cx, unsigned long seed) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  if (!r) die("rng");
  gsl_rng_set(r, seed);
  size_t nv = cx->nv;
  size_t *perm = malloc(nv * sizeof *perm); /* old vertex -> new */
  size_t *inv = malloc(nv * sizeof *inv);
  if (!perm || !inv) die("perm");
  for (size_t i = 0; i < nv; i++)
    inv[i] = i;
  for (size_t i = nv; i > 1; i--) {
    size_t j = gsl_rng_uniform_int(r, i), s = inv[i - 1];
    inv[i - 1] = inv[j];
    inv[j] = s;
  }
  for (size_t i = 0; i < nv; i++)
    perm[inv[i]] = i;
  ss_cx *out = newcx(cx->dim);
  for (size_t i = 0; i < nv; i++) {
    ss_error err = {0};
    if (ss_cx_add_vertex(out, cx->x + inv[i] * (size_t)cx->dim, cx->vref[inv[i]], &err))
      die(err.msg);
  }
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    size_t n = cx->nc[t];
    size_t *order = malloc((n + 1) * sizeof *order);
    if (!order) die("perm");
    for (size_t i = 0; i < n; i++)
      order[i] = i;
    for (size_t i = n; i > 1; i--) {
      size_t j = gsl_rng_uniform_int(r, i), s = order[i - 1];
      order[i - 1] = order[j];
      order[j] = s;
    }
    int nvt = ss_cell_nverts((ss_cell_type)t);
    for (size_t i = 0; i < n; i++) {
      const ss_idx *c = ss_cx_cell(cx, (ss_cell_type)t, order[i]);
      int map[8];
      random_symmetry((ss_cell_type)t, r, map);
      ss_idx w[8];
      for (int k = 0; k < nvt; k++)
        w[map[k]] = (ss_idx)perm[c[k]];
      ss_error err = {0};
      if (ss_cx_add_cell(out, (ss_cell_type)t, w, cx->cref[t][order[i]], &err))
        die(err.msg);
    }
    free(order);
  }
  free(perm);
  free(inv);
  gsl_rng_free(r);
  return out;
}

/* ---- geometric comparison ---- */

static const ss_cx *cmp_cx;
static int cmp_vertex(const void *a, const void *b) {
  const double *x = cmp_cx->x + *(const size_t *)a * (size_t)cmp_cx->dim;
  const double *y = cmp_cx->x + *(const size_t *)b * (size_t)cmp_cx->dim;
  for (int i = 0; i < cmp_cx->dim; i++)
    if (x[i] != y[i]) return x[i] < y[i] ? -1 : 1;
  return 0;
}

static size_t *sorted_vertices(const ss_cx *cx) {
  size_t *o = malloc((cx->nv + 1) * sizeof *o);
  if (!o) die("sort");
  for (size_t i = 0; i < cx->nv; i++)
    o[i] = i;
  cmp_cx = cx;
  qsort(o, cx->nv, sizeof *o, cmp_vertex);
  return o;
}

static int cmp_ids(const void *a, const void *b) {
  ss_idx x = *(const ss_idx *)a, y = *(const ss_idx *)b;
  return (x > y) - (x < y);
}
static int cmp_rows8(const void *a, const void *b) {
  return memcmp(a, b, 8 * sizeof(ss_idx));
}

int tm_same_geometry(const ss_cx *a, const ss_cx *b, double tol) {
  if (a->nv != b->nv || a->dim != b->dim) {
    fprintf(stderr, "complexes differ: %zu vs %zu vertices\n", a->nv, b->nv);
    return 1;
  }
  for (int t = 0; t < SS_NCELLTYPES; t++)
    if (a->nc[t] != b->nc[t]) {
      fprintf(stderr, "complexes differ: %zu vs %zu %s\n", a->nc[t], b->nc[t],
              ss_cell_plural((ss_cell_type)t));
      return 1;
    }
  size_t *oa = sorted_vertices(a), *ob = sorted_vertices(b);
  size_t *bmap = malloc((b->nv + 1) * sizeof *bmap); /* b index -> a index */
  if (!bmap) die("cmp");
  int bad = 0;
  for (size_t i = 0; i < a->nv && !bad; i++) {
    const double *x = a->x + oa[i] * (size_t)a->dim, *y = b->x + ob[i] * (size_t)b->dim;
    for (int r = 0; r < a->dim; r++)
      if (!(fabs(x[r] - y[r]) <= tol * (1.0 + fabs(x[r])))) {
        fprintf(stderr, "vertex %zu in sorted order differs: %.17g vs %.17g\n", i, x[r],
                y[r]);
        bad = 1;
        break;
      }
    bmap[ob[i]] = oa[i];
  }
  for (int t = 0; t < SS_NCELLTYPES && !bad; t++) {
    size_t n = a->nc[t];
    int nvt = ss_cell_nverts((ss_cell_type)t);
    ss_idx *ra = calloc(8 * (n + 1), sizeof *ra), *rb = calloc(8 * (n + 1), sizeof *rb);
    if (!ra || !rb) die("cmp");
    for (size_t i = 0; i < n; i++) {
      const ss_idx *ca = ss_cx_cell(a, (ss_cell_type)t, i),
                   *cb = ss_cx_cell(b, (ss_cell_type)t, i);
      for (int k = 0; k < nvt; k++) {
        ra[8 * i + k] = ca[k];
        rb[8 * i + k] = (ss_idx)bmap[cb[k]];
      }
      qsort(ra + 8 * i, (size_t)nvt, sizeof *ra, cmp_ids);
      qsort(rb + 8 * i, (size_t)nvt, sizeof *rb, cmp_ids);
    }
    qsort(ra, n, 8 * sizeof *ra, cmp_rows8);
    qsort(rb, n, 8 * sizeof *rb, cmp_rows8);
    if (n && memcmp(ra, rb, n * 8 * sizeof *ra)) {
      fprintf(stderr, "the %s differ as vertex sets\n", ss_cell_plural((ss_cell_type)t));
      bad = 1;
    }
    free(ra);
    free(rb);
  }
  free(oa);
  free(ob);
  free(bmap);
  return bad;
}

/* nx x ny x nz unit hexes; vertex (i, j, k) at (i, j, k). */
ss_cx *tm_hex_grid(int nx, int ny, int nz) {
  ss_cx *cx;
  ss_error err = {0};
  if (ss_cx_new(3, &cx, &err)) abort();
  for (int k = 0; k <= nz; k++)
    for (int j = 0; j <= ny; j++)
      for (int i = 0; i <= nx; i++) {
        double x[3] = {i, j, k};
        if (ss_cx_add_vertex(cx, x, 0, &err)) abort();
      }
#define GV(i, j, k) (ss_idx)((i) + (nx + 1) * ((j) + (ny + 1) * (k)))
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        ss_idx v[8] = {GV(i, j, k),
                       GV(i + 1, j, k),
                       GV(i + 1, j + 1, k),
                       GV(i, j + 1, k),
                       GV(i, j, k + 1),
                       GV(i + 1, j, k + 1),
                       GV(i + 1, j + 1, k + 1),
                       GV(i, j + 1, k + 1)};
        if (ss_cx_add_cell(cx, SS_HEX, v, 0, &err)) abort();
      }
#undef GV
  return cx;
}

/* n sectors of R x R quads around the z axis (sector s between the unit rays
 * at angles 2 pi s / n and 2 pi (s + 1) / n; its point (i, j) at i e_s +
 * j e_s+1), extruded into nz layers: the z axis is an edge of valence n.
 * Cell (s, i, j, k) (i, j < R) is cell ((k * n + s) * R + j) * R + i. */
ss_cx *tm_edge_ring(int n, int R, int nz) {
  ss_cx *cx;
  ss_error err = {0};
  if (ss_cx_new(3, &cx, &err)) abort();
  /* 2D points: centre, n rays of R points, n sectors of R x R interior points */
  int np = 1 + n * R + n * R * R;
  for (int k = 0; k <= nz; k++)
    for (int p = 0; p < np; p++) {
      double x[3] = {0, 0, k};
      if (p > 0 && p <= n * R) {
        int s = (p - 1) / R, i = (p - 1) % R + 1;
        x[0] = i * cos(2 * PI * s / n);
        x[1] = i * sin(2 * PI * s / n);
      } else if (p > n * R) {
        int q = p - 1 - n * R, s = q / (R * R), i = q % R + 1, j = (q / R) % R + 1;
        x[0] = i * cos(2 * PI * s / n) + j * cos(2 * PI * (s + 1) / n);
        x[1] = i * sin(2 * PI * s / n) + j * sin(2 * PI * (s + 1) / n);
      }
      if (ss_cx_add_vertex(cx, x, 0, &err)) abort();
    }
  for (int k = 0; k < nz; k++)
    for (int s = 0; s < n; s++)
      for (int j = 0; j < R; j++)
        for (int i = 0; i < R; i++) {
          int q[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          ss_idx v[8];
          for (int c = 0; c < 4; c++) {
            int a = q[c][0], b = q[c][1], id;
            if (a == 0 && b == 0)
              id = 0;
            else if (b == 0)
              id = 1 + s * R + (a - 1);
            else if (a == 0)
              id = 1 + ((s + 1) % n) * R + (b - 1);
            else
              id = 1 + n * R + s * R * R + (b - 1) * R + (a - 1);
            v[c] = (ss_idx)(id + k * np);
            v[c + 4] = (ss_idx)(id + (k + 1) * np);
          }
          if (ss_cx_add_cell(cx, SS_HEX, v, 0, &err)) abort();
        }
  return cx;
}

static int tm_cmp_face(const void *a, const void *b) {
  const ss_idx *x = a, *y = b;
  for (int i = 0; i < 3; i++)
    if (x[i] != y[i]) return (x[i] > y[i]) - (x[i] < y[i]);
  return 0;
}

static void tm_sort3(ss_idx *t) {
  for (int i = 0; i < 3; i++)
    for (int j = i + 1; j < 3; j++)
      if (t[j] < t[i]) {
        ss_idx x = t[i];
        t[i] = t[j];
        t[j] = x;
      }
}

size_t tm_boundary_faces(const ss_cx *cx, ss_idx **out) {
  const size_t nt = cx->nc[SS_TET], no = cx->nc[SS_OCT], n = 4 * nt + 8 * no;
  ss_idx *f = malloc((3 * n + 1) * sizeof *f), *b = malloc((3 * n + 1) * sizeof *b);
  size_t m = 0;
  for (size_t t = 0; t < nt; t++) {
    const ss_idx *v = ss_cx_cell(cx, SS_TET, t);
    for (int skip = 0; skip < 4; skip++, m++)
      for (int j = 0, q = 0; j < 4; j++)
        if (j != skip) f[3 * m + (size_t)q++] = v[j];
  }
  for (size_t o = 0; o < no; o++) {
    const ss_idx *v = ss_cx_cell(cx, SS_OCT, o);
    for (int s = 0; s < 8; s++, m++)
      for (int j = 0; j < 3; j++)
        f[3 * m + (size_t)j] = v[(s >> j & 1) ? j + 3 : j];
  }
  for (size_t i = 0; i < n; i++)
    tm_sort3(f + 3 * i);
  qsort(f, n, 3 * sizeof *f, tm_cmp_face);
  size_t k = 0;
  for (size_t i = 0; i < n;) {
    size_t j = i + 1;
    while (j < n && !tm_cmp_face(f + 3 * i, f + 3 * j))
      j++;
    if (j - i == 1) memcpy(b + 3 * k++, f + 3 * i, 3 * sizeof *b);
    i = j;
  }
  free(f);
  *out = b;
  return k;
}

void tm_points_in(const ss_cx *a, const ss_cx *b, const unsigned char *skip,
                  size_t *total, size_t *found) {
  *total = *found = 0;
  for (size_t v = 0; v < b->nv; v++) {
    if (skip[v]) continue;
    ++*total;
    for (size_t u = 0; u < a->nv; u++)
      if (!memcmp(a->x + 3 * u, b->x + 3 * v, 3 * sizeof(double))) {
        ++*found;
        break;
      }
  }
}

ss_cx *tm_refined(const ss_scheme *s, const ss_cx *cx, int levels, ss_error *err) {
  ss_cx *a = NULL, *b = NULL;
  if (ss_cx_copy(cx, &a, err)) return NULL;
  if (ss_scheme_reads_diagonals(s) && ss_diag_choose(a, SS_DIAG_BFS, 0, 0, err)) {
    ss_cx_free(a);
    return NULL;
  }
  for (int l = 0; l < levels; l++) {
    if (ss_scheme_refine(s, a, &b, NULL, err)) {
      char m[sizeof err->msg];
      snprintf(m, sizeof m, "level %d: %.400s", l + 1, err->msg);
      snprintf(err->msg, sizeof err->msg, "%s", m);
      ss_cx_free(a);
      return NULL;
    }
    ss_cx_free(a);
    a = b;
  }
  return a;
}
