/* test_quasi48_adapt.c — adaptive quasi 4-8 refinement (issue 38; the
 * paper's motivation, "the 4-8 structure is a multiresolution structure"):
 * ss_scheme_set_adapt makes each level refine only the triangles a criterion
 * wants and their closure.  On the icosahedron after two Loop levels (a
 * closed surface of 320 triangles):
 *   - a box holding the whole surface, or an edge length below every edge,
 *     gives plain subdivision bit for bit (points, cells, numbering), six
 *     levels;
 *   - with a box round a cap, each of six levels is conforming (every edge
 *     in exactly two triangles, V - E + F = 2, no hanging vertex: no fine
 *     edge joins the two parents of a new vertex), every new vertex lies on
 *     an edge of a wanted triangle or of one sharing an edge with it (the
 *     wanted set computed here, independently), every coarse vertex off
 *     those triangles and the ones across their edges (which a split edge
 *     halves too) stays where it was, bit for bit, and the level refines
 *     something but less than the whole; its split edges are exactly those
 *     of the whole pass (ss_split_refine on the same mesh) in a wanted
 *     triangle or, for a wanted triangle with no split edge, in the
 *     neighbours across its edges (the closure; it occurs on every level);
 *     and no triangle wanted on two levels running is left unrefined;
 *   - with an edge length h alone, refinement stops with every edge at most
 *     h (no wanted triangle is left behind: the closure refines the
 *     neighbours that block one). */
#include <stdlib.h>
#include <string.h>

#include "ss_mesh.h"
#include "ss_scheme.h"
#include "ss_split.h"
#include "ss_test.h"
#include "ss_triedge.h"

static ss_cx *refine_with(const char *name, const ss_adapt *a, const ss_cx *cx,
                          int levels) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *cur = NULL, *next = NULL;
  if (ss_scheme_new(name, &s, &err) || (a && ss_scheme_set_adapt(s, a, &err)) ||
      ss_cx_copy(cx, &cur, &err)) {
    CHECK(0, "%s: %s", name, err.msg);
    ss_scheme_free(s);
    return NULL;
  }
  for (int l = 0; l < levels && cur; l++) {
    if (ss_scheme_refine(s, cur, &next, NULL, &err)) {
      CHECK(0, "%s level %d: %s", name, l + 1, err.msg);
      next = NULL;
    }
    ss_cx_free(cur);
    cur = next;
  }
  ss_scheme_free(s);
  return cur;
}

static int same_complex(const ss_cx *a, const ss_cx *b) {
  if (a->nv != b->nv || memcmp(a->x, b->x, a->nv * (size_t)a->dim * sizeof *a->x))
    return 0;
  for (int t = 0; t < SS_NCELLTYPES; t++)
    if (a->nc[t] != b->nc[t] ||
        (a->nc[t] &&
         memcmp(a->cells[t], b->cells[t],
                a->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t) * sizeof(ss_idx))))
      return 0;
  return 1;
}

static void test_uniform(const ss_cx *cx) {
  ss_cx *plain = refine_with("quasi48", NULL, cx, 6);
  const ss_adapt all = {1, {-10, -10, -10, 10, 10, 10}, 0.0, 0, 0.0};
  const ss_adapt fine = {0, {0}, 1e-9, 0, 0.0};
  const ss_adapt both = {1, {-10, -10, -10, 10, 10, 10}, 1e-9, 0, 0.0};
  const ss_adapt *a[3] = {&all, &fine, &both};
  const char *what[3] = {"a box holding it", "an edge length below all", "both"};
  for (int i = 0; i < 3; i++) {
    ss_cx *r = refine_with("quasi48", a[i], cx, 6);
    CHECK(plain && r && same_complex(plain, r), "%s: not plain subdivision", what[i]);
    ss_cx_free(r);
  }
  if (plain)
    printf("uniform: %zu triangles after 6 levels, as plain\n", plain->nc[SS_TRIANGLE]);
  ss_cx_free(plain);
}

/* The test's own reading of the box criterion: the triangle's bounding box
 * meets the box. */
static int in_box(const ss_cx *cx, const ss_idx *v, const double *box) {
  for (int r = 0; r < 3; r++) {
    double lo = cx->x[3 * v[0] + (size_t)r], hi = lo;
    for (int i = 1; i < 3; i++) {
      lo = fmin(lo, cx->x[3 * v[i] + (size_t)r]);
      hi = fmax(hi, cx->x[3 * v[i] + (size_t)r]);
    }
    if (hi < box[r] || lo > box[r + 3]) return 0;
  }
  return 1;
}

static int has_edge(const ss_triedge *te, ss_idx a, ss_idx b) {
  const ss_idx lo = a < b ? a : b, hi = a < b ? b : a;
  for (size_t e = 0; e < te->ne; e++)
    if (te->end[2 * e] == lo && te->end[2 * e + 1] == hi) return 1;
  return 0;
}

static int cmp_pair(const void *a, const void *b) {
  return memcmp(a, b, 2 * sizeof(ss_idx));
}

/* The new vertices' parent pairs of L, sorted; *n their count. */
static ss_idx *split_pairs(const ss_split *L, size_t *n) {
  *n = L->nfine - L->ncoarse;
  ss_idx *p = malloc((2 * *n + 1) * sizeof *p);
  for (size_t x = L->ncoarse; x < L->nfine; x++)
    memcpy(p + 2 * (x - L->ncoarse), L->parent + L->ptr[x], 2 * sizeof *p);
  qsort(p, *n, 2 * sizeof *p, cmp_pair);
  return p;
}

/* The adaptive pass's edges against their specification, from the whole
 * pass (ss_split_refine, the same coarse mesh): the whole pass's split edges
 * S that lie in a wanted triangle, or in a triangle across an edge of a
 * wanted triangle none of whose edges is in S (the closure). */
static void check_spec(const ss_cx *c, const ss_triedge *tc, const unsigned char *want,
                       const ss_split *L, int level) {
  ss_error err = {0};
  ss_cx *fu = NULL;
  ss_split *Lu = NULL;
  REQUIRE_OK_VOID(ss_split_refine(SS_SPLIT_BISECT, c, &fu, &Lu, &err), &err);
  size_t ns = 0, na = 0;
  ss_idx *S = split_pairs(Lu, &ns), *A = split_pairs(L, &na);
  const size_t nt = c->nc[SS_TRIANGLE];
  unsigned char *inS = calloc(tc->ne + 1, 1), *keep = calloc(nt + 1, 1);
  for (size_t e = 0; e < tc->ne; e++)
    inS[e] = bsearch(tc->end + 2 * e, S, ns, 2 * sizeof *S, cmp_pair) != NULL;
  size_t closure = 0;
  for (size_t t = 0; t < nt; t++) {
    const size_t *ed = tc->tedge + 3 * t;
    keep[t] |= want[t];
    if (!want[t] || inS[ed[0]] || inS[ed[1]] || inS[ed[2]]) continue;
    closure++;
    for (int k = 0; k < 3; k++)
      for (size_t j = 0; j < tc->nface[ed[k]]; j++) {
        const size_t n = tc->face[2 * ed[k] + j];
        const size_t *en = tc->tedge + 3 * n;
        keep[n] |= inS[en[0]] || inS[en[1]] || inS[en[2]];
      }
  }
  size_t expect = 0, found = 0;
  for (size_t e = 0; e < tc->ne; e++) {
    int k = 0;
    for (size_t j = 0; j < tc->nface[e]; j++)
      k |= keep[tc->face[2 * e + j]];
    if (!inS[e] || !k) continue;
    expect++;
    found += bsearch(tc->end + 2 * e, A, na, 2 * sizeof *A, cmp_pair) != NULL;
  }
  CHECK(expect == na && found == na, "level %d: %zu split edges, %zu specified, %zu both",
        level, na, expect, found);
  printf("level %d: %zu wanted triangles with no split edge of their own (closure)\n",
         level, closure);
  free(inS);
  free(keep);
  free(S);
  free(A);
  ss_cx_free(fu);
  ss_split_free(Lu);
}

/* One adaptive level from c to f (split L): conforming, confined, fixed away. */
static void check_level(const ss_cx *c, const ss_cx *f, const ss_split *L,
                        const unsigned char *want_in, int level) {
  ss_error err = {0};
  ss_triedge *tc = NULL, *tf = NULL;
  REQUIRE_OK_VOID(ss_triedge_new(c, &tc, &err), &err);
  REQUIRE_OK_VOID(ss_triedge_new(f, &tf, &err), &err);
  size_t two = 0;
  for (size_t e = 0; e < tf->ne; e++)
    two += tf->nface[e] == 2;
  CHECK(two == tf->ne, "level %d: %zu of %zu edges in two triangles", level, two, tf->ne);
  CHECK((long)f->nv - (long)tf->ne + (long)f->nc[SS_TRIANGLE] == 2,
        "level %d: V - E + F = %ld", level,
        (long)f->nv - (long)tf->ne + (long)f->nc[SS_TRIANGLE]);
  /* wanted triangles and the ones sharing an edge with them */
  const size_t nt = c->nc[SS_TRIANGLE];
  unsigned char *near = calloc(nt + 1, 1), *touched = calloc(c->nv + 1, 1);
  const unsigned char *want = want_in;
  size_t nwant = 0;
  for (size_t t = 0; t < nt; t++)
    nwant += want[t];
  for (size_t t = 0; t < nt; t++) {
    near[t] |= want[t];
    for (int k = 0; want[t] && k < 3; k++) {
      const size_t e = tc->tedge[3 * t + (size_t)k];
      for (size_t j = 0; j < tc->nface[e]; j++)
        near[tc->face[2 * e + j]] = 1;
    }
  }
  check_spec(c, tc, want, L, level);
  ss_triedge *tn = NULL; /* the edges of the near triangles */
  ss_cx sub = *c;
  ss_idx *tri = malloc((3 * nt + 1) * sizeof *tri);
  size_t m = 0;
  for (size_t t = 0; t < nt; t++) {
    if (!near[t]) continue;
    memcpy(tri + 3 * m++, ss_cx_cell(c, SS_TRIANGLE, t), 3 * sizeof *tri);
    /* a split edge of a near triangle halves the triangle across it too, and
     * its corners may move: the near triangles and those sharing an edge */
    for (int k = 0; k < 3; k++) {
      const size_t e = tc->tedge[3 * t + (size_t)k];
      for (size_t j = 0; j < tc->nface[e]; j++)
        for (int i = 0; i < 3; i++)
          touched[ss_cx_cell(c, SS_TRIANGLE, tc->face[2 * e + j])[i]] = 1;
    }
  }
  sub.nc[SS_TRIANGLE] = m;
  sub.cells[SS_TRIANGLE] = tri;
  REQUIRE_OK_VOID(ss_triedge_new(&sub, &tn, &err), &err);
  size_t born = 0, confined = 0, hanging = 0, still = 0, away = 0;
  for (size_t x = c->nv; x < f->nv; x++) {
    const ss_idx a = L->parent[L->ptr[x]], b = L->parent[L->ptr[x] + 1];
    born++;
    confined += has_edge(tn, a, b);
    hanging += has_edge(tf, a, b);
  }
  for (size_t v = 0; v < c->nv; v++)
    if (!touched[v]) {
      away++;
      still += !memcmp(c->x + 3 * v, f->x + 3 * v, 3 * sizeof *c->x);
    }
  CHECK(born > 0 && born < tc->ne / 3,
        "level %d: %zu new vertices (%zu wanted triangles)", level, born, nwant);
  CHECK(confined == born, "level %d: %zu of %zu new vertices near the box", level,
        confined, born);
  CHECK(hanging == 0, "level %d: %zu hanging vertices", level, hanging);
  CHECK(away > 0 && still == away, "level %d: %zu of %zu vertices away kept", level,
        still, away);
  printf("level %d: %zu wanted triangles, %zu new vertices, %zu vertices away kept\n",
         level, nwant, born, still);
  ss_triedge_free(tn);
  free(tri);
  free(near);
  free(touched);
  ss_triedge_free(tc);
  ss_triedge_free(tf);
}

static int cmp_tri(const void *a, const void *b) {
  return memcmp(a, b, 3 * sizeof(ss_idx));
}

/* The triangles of cx as sorted triples, sorted; *n their count. */
static ss_idx *sorted_triangles(const ss_cx *cx, size_t *n) {
  *n = cx->nc[SS_TRIANGLE];
  ss_idx *t = malloc((3 * *n + 1) * sizeof *t);
  for (size_t i = 0; i < *n; i++) {
    ss_idx *v = t + 3 * i;
    memcpy(v, ss_cx_cell(cx, SS_TRIANGLE, i), 3 * sizeof *v);
    for (int a = 0; a < 3; a++)
      for (int b = a + 1; b < 3; b++)
        if (v[b] < v[a]) {
          const ss_idx x = v[a];
          v[a] = v[b];
          v[b] = x;
        }
  }
  qsort(t, *n, 3 * sizeof *t, cmp_tri);
  return t;
}

/* The triangles wanted on `old` and, unchanged, on `mid` (the next level:
 * smoothing moves them, so the box may let one go) that `now` still holds
 * (vertex numbers carry over: a coarse vertex keeps its number). */
static size_t left_behind(const ss_cx *old, const ss_cx *mid, const ss_cx *now,
                          const double *box) {
  size_t nn = 0, nm = 0, no = 0, left = 0;
  ss_idx *t = sorted_triangles(now, &nn), *o = sorted_triangles(old, &no);
  ss_idx *m = sorted_triangles(mid, &nm);
  for (size_t i = 0; i < no; i++) {
    const ss_idx *v = o + 3 * i;
    if (in_box(old, v, box) && in_box(mid, v, box) &&
        bsearch(v, m, nm, 3 * sizeof *m, cmp_tri) &&
        bsearch(v, t, nn, 3 * sizeof *t, cmp_tri))
      left++;
  }
  free(t);
  free(o);
  free(m);
  return left;
}

static void test_region(const ss_cx *cx) {
  ss_error err = {0};
  const ss_adapt a = {1, {0.45, -2, -2, 2, 2, 2}, 0.0, 0, 0.0};
  ss_scheme *s = NULL;
  ss_cx *lv[7] = {NULL};
  REQUIRE_OK_VOID(ss_scheme_new("quasi48", &s, &err), &err);
  REQUIRE_OK_VOID(ss_scheme_set_adapt(s, &a, &err), &err);
  REQUIRE_OK_VOID(ss_cx_copy(cx, &lv[0], &err), &err);
  size_t left = 0;
  for (int l = 1; l <= 6; l++) {
    gsl_spmatrix *R = NULL;
    ss_split *L = NULL;
    if (ss_scheme_refine_split(s, lv[l - 1], &lv[l], &R, &L, &err)) {
      CHECK(0, "level %d: %s", l, err.msg);
      break;
    }
    const size_t nt = lv[l - 1]->nc[SS_TRIANGLE];
    unsigned char *want = calloc(nt + 1, 1);
    for (size_t t = 0; t < nt; t++)
      want[t] =
          (unsigned char)in_box(lv[l - 1], ss_cx_cell(lv[l - 1], SS_TRIANGLE, t), a.box);
    check_level(lv[l - 1], lv[l], L, want, l);
    free(want);
    if (l >= 2) left += left_behind(lv[l - 2], lv[l - 1], lv[l], a.box);
    gsl_spmatrix_free(R);
    ss_split_free(L);
  }
  /* the closure's purpose: no wanted triangle waits more than two levels */
  CHECK(left == 0, "%zu wanted triangles left unrefined for two levels", left);
  for (int l = 0; l <= 6; l++)
    ss_cx_free(lv[l]);
  ss_scheme_free(s);
}

static double longest_edge(const ss_cx *cx) {
  double m = 0.0;
  for (size_t t = 0; t < cx->nc[SS_TRIANGLE]; t++) {
    const ss_idx *v = ss_cx_cell(cx, SS_TRIANGLE, t);
    for (int i = 0; i < 3; i++) {
      const double *p = cx->x + 3 * v[i], *q = cx->x + 3 * v[(i + 1) % 3];
      m = fmax(m, sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                       (p[2] - q[2]) * (p[2] - q[2])));
    }
  }
  return m;
}

/* Refine with an edge length h alone until a level adds no vertex (at most
 * 40 levels): then no edge may be longer than h. */
static void test_edge_length(const ss_cx *cx) {
  const double h0 = longest_edge(cx), h = 0.3 * h0;
  const ss_adapt a = {0, {0}, h, 0, 0.0};
  ss_cx *cur = refine_with("quasi48", NULL, cx, 0), *next = NULL;
  int l = 0;
  for (; cur && l < 40; l++) {
    if (!(next = refine_with("quasi48", &a, cur, 1))) break;
    const int same = next->nv == cur->nv;
    ss_cx_free(cur);
    cur = next;
    if (same) break;
  }
  if (cur) {
    const double got = longest_edge(cur);
    CHECK(l < 40 && got <= h, "edge length %.4g: after %d levels an edge of %.4g is left",
          h, l, got);
    printf("edge length %.4g (longest at first %.4g): %zu triangles after %d levels, "
           "longest %.4g\n",
           h, h0, cur->nc[SS_TRIANGLE], l, got);
  }
  ss_cx_free(cur);
}

/* The test's own reading of the curvature criterion: the angle between the
 * unit normals of t and a triangle sharing an edge with it exceeds T. */
static void bent(const ss_cx *cx, double T, unsigned char *want) {
  const size_t nt = cx->nc[SS_TRIANGLE];
  double *n = malloc((3 * nt + 1) * sizeof *n);
  for (size_t t = 0; t < nt; t++) {
    const ss_idx *v = ss_cx_cell(cx, SS_TRIANGLE, t);
    const double *p = cx->x + 3 * v[0], *q = cx->x + 3 * v[1], *r = cx->x + 3 * v[2];
    const double a[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double b[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    double *m = n + 3 * t;
    m[0] = a[1] * b[2] - a[2] * b[1];
    m[1] = a[2] * b[0] - a[0] * b[2];
    m[2] = a[0] * b[1] - a[1] * b[0];
    const double l = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    for (int i = 0; i < 3; i++)
      m[i] /= l;
  }
  for (size_t t = 0; t < nt; t++) {
    want[t] = 0;
    const ss_idx *v = ss_cx_cell(cx, SS_TRIANGLE, t);
    for (size_t u = 0; u < nt; u++) { /* u shares two corners with t */
      const ss_idx *w = ss_cx_cell(cx, SS_TRIANGLE, u);
      int common = 0;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
          common += v[i] == w[j];
      const double *a = n + 3 * t, *b = n + 3 * u;
      if (u != t && common == 2 &&
          acos(fmin(1.0, a[0] * b[0] + a[1] * b[1] + a[2] * b[2])) > T)
        want[t] = 1;
    }
  }
  free(n);
}

/* A dome: the sphere with z < 0 pressed onto z = 0 (a flat disc, angle 0
 * between its triangles, and a curved cap).  --adapt-curvature 5 degrees:
 * each of four levels conforming and confined to the bent triangles (the
 * test's own angles); no level adds a vertex inside the flat disc away from
 * its rim (radius below 0.55 of the disc's);
 * 170 degrees, above every angle, refines nothing. */
static void test_curvature(const ss_cx *sphere) {
  ss_error err = {0};
  ss_cx *dome = NULL;
  REQUIRE_OK_VOID(ss_cx_copy(sphere, &dome, &err), &err);
  double r2 = 0.0; /* the disc's radius, squared (Loop shrank the sphere) */
  for (size_t v = 0; v < dome->nv; v++) {
    const double *p = dome->x + 3 * v;
    r2 = fmax(r2, p[0] * p[0] + p[1] * p[1]);
    if (p[2] < 0.0) dome->x[3 * v + 2] = 0.0;
  }
  const double T = 5.0 * M_PI / 180.0;
  const ss_adapt a = {0, {0}, 0.0, 1, T};
  ss_scheme *s = NULL;
  ss_cx *lv[5] = {NULL};
  lv[0] = dome;
  REQUIRE_OK_VOID(ss_scheme_new("quasi48", &s, &err), &err);
  REQUIRE_OK_VOID(ss_scheme_set_adapt(s, &a, &err), &err);
  size_t inside = 0;
  for (int l = 1; l <= 4; l++) {
    ss_split *L = NULL;
    if (ss_scheme_refine_split(s, lv[l - 1], &lv[l], NULL, &L, &err)) {
      CHECK(0, "curvature level %d: %s", l, err.msg);
      break;
    }
    const size_t nt = lv[l - 1]->nc[SS_TRIANGLE];
    unsigned char *want = calloc(nt + 1, 1);
    bent(lv[l - 1], T, want);
    check_level(lv[l - 1], lv[l], L, want, l);
    for (size_t x = lv[l - 1]->nv; x < lv[l]->nv; x++) {
      const double *p = lv[l]->x + 3 * x;
      inside += p[2] == 0.0 && p[0] * p[0] + p[1] * p[1] < 0.3 * r2;
    }
    free(want);
    ss_split_free(L);
  }
  CHECK(inside == 0, "curvature: %zu new vertices inside the flat disc", inside);
  const ss_adapt none = {0, {0}, 0.0, 1, 170.0 * M_PI / 180.0};
  ss_cx *f = refine_with("quasi48", &none, dome, 3);
  CHECK(f && f->nv == dome->nv, "curvature above every angle: %zu vertices, not %zu",
        f ? f->nv : 0, dome->nv);
  ss_cx_free(f);
  for (int l = 0; l <= 4; l++)
    ss_cx_free(lv[l]);
  ss_scheme_free(s);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_quasi48_adapt DATA/MESHES\n");
    return 2;
  }
  ss_error err = {0};
  char path[4096];
  snprintf(path, sizeof path, "%s/icosahedron.obj", argv[1]);
  ss_cx *ico = NULL;
  REQUIRE_OK(ss_mesh_read(path, SS_MESH_AUTO, &ico, &err), &err);
  ss_cx *sphere = refine_with("loop", NULL, ico, 2);
  CHECK(sphere && sphere->nc[SS_TRIANGLE] == 320, "Loop^2 icosahedron");
  if (sphere) {
    test_uniform(sphere);
    test_region(sphere);
    test_edge_length(sphere);
    test_curvature(sphere);
  }
  ss_cx_free(sphere);
  ss_cx_free(ico);
  return ss_test_done("quasi48_adapt");
}
