/* test_crease.c — the crease classification of a split surface complex
 * (ss_crease), against the rule of ss_crease.h applied here to the coarse
 * complex directly (its edges, their faces and segments), without the split.
 *
 * Properties:
 *   - known answers: a closed torus is smooth everywhere (every vertex on 4
 *     quad edges, 6 triangle edges, no sharp midpoint); a single quad or
 *     triangle has crease corners (two boundary edges each) and sharp
 *     midpoints on every edge; a closed loop of segments on the torus makes
 *     its vertices crease and leaves the rest smooth; a segment path's inner
 *     vertices are crease and its ends darts (smooth); three or four
 *     segment lines meeting make a corner; a vertex cell makes a corner; a
 *     vertex in no edge (a lone vertex cell) is a corner; a fin (a third
 *     face on an edge) makes its ends crease (the non-manifold edge and the
 *     fin's boundary edge); a dangling segment (an edge in no face) makes
 *     both its ends corners (one crease edge, not in two faces);
 *   - seeded random complexes (torus grids of quads and of triangles with
 *     faces removed, segments and vertex cells added, fins making
 *     non-manifold edges): every coarse vertex's kind and edge count, every
 *     fine vertex's face count and sharp flag agree with the rule computed
 *     here; ss_crease_other names the other end of each edge;
 *   - a relabelled copy (vertices and cells permuted, tm_permuted) gives
 *     the same kinds, vertex by vertex through the relabelling.
 * Mutations this catches (tried by hand: the report of issue 33):
 *   - a corner only from four crease edges (ncrease >= 4): the three-line
 *     meeting and the random complexes;
 *   - children_at_edge ignored (4 fine faces expected at every midpoint, a
 *     quad's count): every interior triangle edge turns sharp, the triangle
 *     complexes' kinds and sharp flags differ from the rule. */
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "ss_crease.h"
#include "ss_split.h"
#include "ss_test.h"
#include "ss_testmesh.h"

/* ---- the rule, applied to the coarse complex ---- */

typedef struct {
  ss_idx a, b; /* a < b */
  int nfaces;  /* face incidences */
  int segment; /* 1 if a segment cell lies on it */
} edge;

typedef struct {
  size_t n, cap;
  edge *e;
} edges;

static edge *edge_at(edges *E, ss_idx a, ss_idx b) {
  if (a > b) {
    const ss_idx t = a;
    a = b;
    b = t;
  }
  for (size_t i = 0; i < E->n; i++)
    if (E->e[i].a == a && E->e[i].b == b) return E->e + i;
  if (E->n == E->cap) {
    E->cap = E->cap ? 2 * E->cap : 64;
    E->e = realloc(E->e, E->cap * sizeof *E->e);
  }
  E->e[E->n] = (edge){a, b, 0, 0};
  return E->e + E->n++;
}

/* The edges of cx's faces (of type face) and segments, with their face
 * counts and segment marks. */
static edges edge_table(const ss_cx *cx, ss_cell_type face) {
  edges E = {0, 0, NULL};
  const int fn = ss_cell_nverts(face);
  for (size_t c = 0; c < cx->nc[face]; c++) {
    const ss_idx *v = ss_cx_cell(cx, face, c);
    for (int k = 0; k < fn; k++)
      edge_at(&E, v[k], v[(k + 1) % fn])->nfaces++;
  }
  for (size_t c = 0; c < cx->nc[SS_SEGMENT]; c++) {
    const ss_idx *v = ss_cx_cell(cx, SS_SEGMENT, c);
    edge_at(&E, v[0], v[1])->segment = 1;
  }
  return E;
}

/* Kinds (SS_SMOOTH, SS_CREASE, SS_CORNER) and edge counts of the coarse
 * vertices of cx (faces of type face), by ss_crease.h's rule. */
static void rule(const ss_cx *cx, ss_cell_type face, unsigned char *kind,
                 unsigned *nedge) {
  edges E = edge_table(cx, face);
  unsigned *ncrease = calloc(cx->nv, sizeof *ncrease),
           *nodd = calloc(cx->nv, sizeof *nodd);
  memset(nedge, 0, cx->nv * sizeof *nedge);
  for (size_t i = 0; i < E.n; i++) {
    const edge *e = E.e + i;
    const int odd = e->nfaces != 2, crease = e->segment || odd;
    const ss_idx ends[2] = {e->a, e->b};
    for (int k = 0; k < 2; k++) {
      nedge[ends[k]]++;
      ncrease[ends[k]] += (unsigned)crease;
      nodd[ends[k]] += (unsigned)odd;
    }
  }
  for (size_t v = 0; v < cx->nv; v++)
    kind[v] = nedge[v] == 0 || ncrease[v] >= 3 || (ncrease[v] == 1 && nodd[v]) ? SS_CORNER
              : ncrease[v] == 2                                                ? SS_CREASE
                                : SS_SMOOTH;
  for (size_t c = 0; c < cx->nc[SS_VERTEX]; c++)
    kind[ss_cx_cell(cx, SS_VERTEX, c)[0]] = SS_CORNER;
  free(ncrease);
  free(nodd);
  free(E.e);
}

/* Classify cx with the module; compare with the rule; returns the module's
 * kinds (caller frees) or NULL. */
static unsigned char *compare(const ss_cx *cx, ss_cell_type face, const char *what) {
  const ss_split_kind sk = face == SS_QUAD ? SS_SPLIT_MULTILINEAR : SS_SPLIT_TETOCT;
  ss_cx *fine = NULL;
  ss_split *L = NULL;
  ss_crease *c = NULL;
  ss_error err = {0};
  unsigned char *out = NULL;
  if (ss_split_refine(sk, cx, &fine, &L, &err) ||
      ss_crease_classify(fine, L, face, face == SS_QUAD ? 2 : 3, &c, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    goto done;
  }
  const size_t nv = cx->nv;
  unsigned char *kind = malloc(nv);
  unsigned *nedge = malloc(nv * sizeof *nedge);
  rule(cx, face, kind, nedge);
  size_t bad_kind = 0, bad_edges = 0, first = SIZE_MAX;
  for (size_t v = 0; v < nv; v++) {
    if (c->kind[v] != kind[v] && first == SIZE_MAX) first = v;
    bad_kind += c->kind[v] != kind[v];
    bad_edges += c->nedge[v] != nedge[v];
  }
  CHECK(bad_kind == 0, "%s: %zu vertices of the wrong kind (first %zu: %d, rule %d)",
        what, bad_kind, first, first < nv ? c->kind[first] : -1,
        first < nv ? kind[first] : -1);
  CHECK(bad_edges == 0, "%s: %zu vertices with the wrong edge count", what, bad_edges);
  /* fine vertices: face counts (each coarse face puts one child at its
   * corners, children_at_edge at its edge midpoints) and sharp midpoints */
  edges E = edge_table(cx, face);
  const int fn = ss_cell_nverts(face);
  unsigned *faces_at = calloc(nv, sizeof *faces_at);
  for (size_t f = 0; f < cx->nc[face]; f++)
    for (int k = 0; k < fn; k++)
      faces_at[ss_cx_cell(cx, face, f)[k]]++;
  size_t bad_nface = 0, bad_sharp = 0, bad_other = 0;
  for (size_t x = 0; x < fine->nv; x++) {
    const size_t np = ss_split_npar(L, x);
    if (x < nv) {
      bad_nface += c->nface[x] != faces_at[x];
      bad_sharp += c->sharp[x] != 0;
    } else if (np == 2) {
      const ss_idx a = L->parent[L->ptr[x]], b = L->parent[L->ptr[x] + 1];
      const edge *e = edge_at(&E, a, b);
      bad_nface += c->nface[x] != (unsigned)(e->nfaces * (face == SS_QUAD ? 2 : 3));
      bad_sharp += c->sharp[x] != (e->segment || e->nfaces != 2);
      bad_other += ss_crease_other(L, x, a) != b || ss_crease_other(L, x, b) != a;
    } else {
      bad_sharp += c->sharp[x] != 0; /* face centres are never sharp */
    }
  }
  CHECK(bad_nface == 0, "%s: %zu fine vertices with the wrong face count", what,
        bad_nface);
  CHECK(bad_sharp == 0, "%s: %zu fine vertices with the wrong sharp flag", what,
        bad_sharp);
  CHECK(bad_other == 0, "%s: %zu midpoints whose other end is wrong", what, bad_other);
  free(faces_at);
  free(E.e);
  free(nedge);
  out = malloc(nv);
  memcpy(out, c->kind, nv);
  free(kind);
done:
  ss_crease_free(c);
  ss_split_free(L);
  ss_cx_free(fine);
  return out;
}

/* ---- complexes ---- */

static ss_cx *empty_like(const ss_cx *src) {
  ss_cx *cx = NULL;
  ss_error err = {0};
  ss_cx_new(src->dim, &cx, &err);
  for (size_t v = 0; v < src->nv; v++)
    ss_cx_add_vertex(cx, src->x + v * (size_t)src->dim, 0, &err);
  return cx;
}

static void add(ss_cx *cx, ss_cell_type t, const ss_idx *v) {
  ss_error err = {0};
  ss_cx_add_cell(cx, t, v, 0, &err);
}

static ss_cx *torus(ss_cell_type face, int N) {
  return face == SS_QUAD ? tm_torus(2, N) : tm_torus_triangles(N);
}

/* Segments along the grid line j = row from i = i0 to i1 (indices mod N). */
static void row_segments(ss_cx *cx, int N, int row, int i0, int i1) {
  for (int i = i0; i < i1; i++) {
    const ss_idx s[2] = {(ss_idx)((i % N) + N * row), (ss_idx)(((i + 1) % N) + N * row)};
    add(cx, SS_SEGMENT, s);
  }
}

static void col_segments(ss_cx *cx, int N, int col, int j0, int j1) {
  for (int j = j0; j < j1; j++) {
    const ss_idx s[2] = {(ss_idx)(col + N * (j % N)), (ss_idx)(col + N * ((j + 1) % N))};
    add(cx, SS_SEGMENT, s);
  }
}

static void test_known(ss_cell_type face) {
  enum { N = 8 };
  const char *fname = face == SS_QUAD ? "quads" : "triangles";
  char what[96];
  unsigned char *k;
  /* a closed torus: smooth */
  ss_cx *cx = torus(face, N);
  snprintf(what, sizeof what, "closed torus of %s", fname);
  if ((k = compare(cx, face, what))) {
    int smooth = 1;
    for (size_t v = 0; v < cx->nv; v++)
      smooth &= k[v] == SS_SMOOTH;
    CHECK(smooth, "%s: not smooth everywhere", what);
    free(k);
  }
  /* vertex (i, j) is i + N j: a closed loop of segments on row 2; a path of 3
   * edges on row 5 (i = 1..4); three lines meeting at (3, 0) (row 0 from
   * i = 1 to 5, column 3 from j = 0 to 1); a cross at (6, 6); a vertex cell
   * at (7, 3) */
  row_segments(cx, N, 2, 0, N);
  row_segments(cx, N, 5, 1, 4);
  row_segments(cx, N, 0, 1, 5);
  col_segments(cx, N, 3, 0, 1);
  row_segments(cx, N, 6, 5, 7);
  col_segments(cx, N, 6, 5, 7);
  const ss_idx corner[1] = {7 + N * 3};
  add(cx, SS_VERTEX, corner);
  snprintf(what, sizeof what, "torus of %s with segments", fname);
  if ((k = compare(cx, face, what))) {
    for (int i = 0; i < N; i++)
      CHECK(k[i + N * 2] == SS_CREASE, "%s: loop vertex %d is %d", what, i, k[i + N * 2]);
    CHECK(k[1 + N * 5] == SS_SMOOTH && k[4 + N * 5] == SS_SMOOTH,
          "%s: path ends (darts) %d %d", what, k[1 + N * 5], k[4 + N * 5]);
    CHECK(k[2 + N * 5] == SS_CREASE && k[3 + N * 5] == SS_CREASE, "%s: path inside",
          what);
    CHECK(k[3] == SS_CORNER && k[6 + N * 6] == SS_CORNER,
          "%s: three lines %d, four lines %d", what, k[3], k[6 + N * 6]);
    CHECK(k[7 + N * 3] == SS_CORNER, "%s: vertex cell %d", what, k[7 + N * 3]);
    CHECK(k[1 + N * 3] == SS_SMOOTH, "%s: untouched vertex %d", what, k[1 + N * 3]);
    free(k);
  }
  ss_cx_free(cx);
  /* a single face: crease corners; plus a lone vertex cell (no edges) */
  cx = NULL;
  ss_error err = {0};
  ss_cx_new(2, &cx, &err);
  const double x[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {3, 3}};
  for (int i = 0; i < 5; i++)
    ss_cx_add_vertex(cx, x[i], 0, &err);
  const ss_idx f[4] = {0, 1, 2, 3}, lone[1] = {4};
  add(cx, face, f);
  add(cx, SS_VERTEX, lone);
  snprintf(what, sizeof what, "single %s", face == SS_QUAD ? "quad" : "triangle");
  if ((k = compare(cx, face, what))) {
    const int nc = face == SS_QUAD ? 4 : 3;
    for (int i = 0; i < nc; i++)
      CHECK(k[i] == SS_CREASE, "%s: corner %d is %d", what, i, k[i]);
    CHECK(k[4] == SS_CORNER, "%s: lone vertex is %d", what, k[4]);
    free(k);
  }
  ss_cx_free(cx);
  /* a fin: a third face on the torus edge (0, 1): a non-manifold edge; with
   * the fin's boundary edge, 0 and 1 have two crease edges -> crease; a
   * segment sticking out of the torus at vertex 9 (an edge in no face): the
   * only crease edge at 9, not in two faces -> corner, and corner at its
   * free end */
  cx = torus(face, N);
  const ss_idx nv = (ss_idx)cx->nv;
  const double far0[2] = {9, 9}, far1[2] = {9, 10}, far2[2] = {9, 11};
  ss_cx_add_vertex(cx, far0, 0, &err);
  ss_cx_add_vertex(cx, far1, 0, &err);
  ss_cx_add_vertex(cx, far2, 0, &err);
  const ss_idx fin[4] = {0, 1, nv, nv + 1}, stick[2] = {9, nv + 2};
  add(cx, face, fin);
  add(cx, SS_SEGMENT, stick);
  snprintf(what, sizeof what, "torus of %s with a fin", fname);
  if ((k = compare(cx, face, what))) {
    CHECK(k[0] == SS_CREASE && k[1] == SS_CREASE, "%s: fin's ends %d %d", what, k[0],
          k[1]);
    CHECK(k[9] == SS_CORNER && k[nv + 2] == SS_CORNER, "%s: dangling segment %d %d", what,
          k[9], k[nv + 2]);
    free(k);
  }
  ss_cx_free(cx);
}

static void test_random(ss_cell_type face, gsl_rng *r) {
  enum { N = 7 };
  for (int t = 0; t < 12; t++) {
    ss_cx *base = torus(face, N), *cx = empty_like(base);
    const int fn = ss_cell_nverts(face);
    for (size_t c = 0; c < base->nc[face]; c++)
      if (gsl_rng_uniform(r) < 0.8) add(cx, face, ss_cx_cell(base, face, c));
    /* segments on random edges of the base faces */
    for (size_t c = 0; c < base->nc[face]; c++)
      for (int k = 0; k < fn; k++)
        if (gsl_rng_uniform(r) < 0.08) {
          const ss_idx *v = ss_cx_cell(base, face, c);
          const ss_idx s[2] = {v[k], v[(k + 1) % fn]};
          add(cx, SS_SEGMENT, s);
        }
    for (size_t v = 0; v < base->nv; v++)
      if (gsl_rng_uniform(r) < 0.04) {
        const ss_idx one[1] = {(ss_idx)v};
        add(cx, SS_VERTEX, one);
      }
    /* fins on a few random edges */
    ss_error err = {0};
    for (int q = 0; q < 2; q++) {
      const ss_idx *v = ss_cx_cell(base, face, gsl_rng_uniform_int(r, base->nc[face]));
      const ss_idx nv = (ss_idx)cx->nv;
      const double far0[2] = {20.0 + q, 20.0}, far1[2] = {20.0 + q, 21.0};
      ss_cx_add_vertex(cx, far0, 0, &err);
      ss_cx_add_vertex(cx, far1, 0, &err);
      const ss_idx fin[4] = {v[0], v[1], nv, nv + 1};
      add(cx, face, fin);
    }
    char what[64];
    snprintf(what, sizeof what, "random %s %d", face == SS_QUAD ? "quads" : "triangles",
             t);
    unsigned char *k = compare(cx, face, what);
    /* relabelled: the same kinds through the vertex permutation (matched by
     * position: every vertex of the torus has its own grid position, the fin
     * vertices their own far positions) */
    ss_cx *p = tm_permuted(cx, (unsigned long)(t + 1));
    strcat(what, " relabelled");
    unsigned char *kp = p ? compare(p, face, what) : NULL;
    if (k && kp) {
      size_t differ = 0;
      for (size_t a = 0; a < p->nv; a++)
        for (size_t b = 0; b < cx->nv; b++)
          if (p->x[2 * a] == cx->x[2 * b] && p->x[2 * a + 1] == cx->x[2 * b + 1])
            differ += kp[a] != k[b];
      CHECK(differ == 0, "%s: %zu vertices change kind", what, differ);
    }
    free(k);
    free(kp);
    ss_cx_free(p);
    ss_cx_free(cx);
    ss_cx_free(base);
  }
}

int main(void) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 8);
  test_known(SS_QUAD);
  test_known(SS_TRIANGLE);
  test_random(SS_QUAD, r);
  test_random(SS_TRIANGLE, r);
  gsl_rng_free(r);
  return ss_test_done("crease");
}
