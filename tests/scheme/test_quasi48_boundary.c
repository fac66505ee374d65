/* test_quasi48_boundary.c — quasi48's boundary (quasi 4-8 paper, section
 * 4.3; ss_boundary in ss_scheme.h), each property from the test's own
 * computation on the split the library made:
 *   - the curve rule, one level at a time on a 12-gon disc and an open square
 *     tube (figure 15's "box with two open sides"), whose boundary edges do
 *     not all split on one level: a new boundary vertex is the midpoint of
 *     its boundary neighbours, an old one with a split boundary edge is 3/4
 *     itself + 1/8 each coarse boundary neighbour, one without stays;
 *   - the normal boundary (the default): that displacement projected on the
 *     sum of the cross products of the coarse triangles at the vertex, so the
 *     displacement is parallel to that normal (cross product ~ 0 relative)
 *     and does move some vertex; a planar disc's boundary does not move at
 *     all; with an operator requested it is refused (not linear);
 *   - smooth boundary of a planar disc: it stays in its plane (z = 0 exactly)
 *     and tends to a smooth curve: the largest turning angle between
 *     boundary edges (30 degrees at the start) falls by a factor 0.7 every
 *     two levels, while the fixed boundary keeps its 30 degrees;
 *   - tags: a tube end whose boundary edges are segment cells and whose
 *     corners are vertex cells keeps every boundary point on the original
 *     square, the input ones bit for bit; the boundary end of a tagged
 *     longitudinal edge (figure 15(c), a corner of the square) stays bit for
 *     bit while the untagged corners of that end move;
 *   - a closed surface (the icosahedron): the three modes give the same
 *     result bit for bit. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_spmatrix.h>

#include "ss_mesh.h"
#include "ss_scheme.h"
#include "ss_split.h"
#include "ss_test.h"
#include "ss_triedge.h"

/* The regular n-gon in z = 0 fanned from its centre (vertex 0). */
static ss_cx *disc(int n) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  if (ss_cx_new(3, &cx, &err)) exit(1);
  const double o[3] = {0, 0, 0};
  if (ss_cx_add_vertex(cx, o, 0, &err)) exit(1);
  for (int i = 0; i < n; i++) {
    const double a = 2.0 * M_PI * i / n, p[3] = {cos(a), sin(a), 0.0};
    if (ss_cx_add_vertex(cx, p, 0, &err)) exit(1);
  }
  for (int i = 0; i < n; i++) {
    const ss_idx t[3] = {0, (ss_idx)(1 + i), (ss_idx)(1 + (i + 1) % n)};
    if (ss_cx_add_cell(cx, SS_TRIANGLE, t, 0, &err)) exit(1);
  }
  return cx;
}

#define RING 8 /* vertices round the tube: the square's corners and midpoints */

/* The square tube |x|, |y| <= 1, z in {0, 1, 2}, open at both ends; vertex
 * (ring j, place i) is j * RING + i, even places are corners. */
static ss_cx *tube(void) {
  static const double sq[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  ss_error err = {0};
  ss_cx *cx = NULL;
  if (ss_cx_new(3, &cx, &err)) exit(1);
  for (int j = 0; j < 3; j++)
    for (int i = 0; i < RING; i++) {
      const double *a = sq[i / 2], *b = sq[(i / 2 + 1) % 4], t = (i % 2) * 0.5;
      const double p[3] = {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, j};
      if (ss_cx_add_vertex(cx, p, 0, &err)) exit(1);
    }
  for (int j = 0; j < 2; j++)
    for (int i = 0; i < RING; i++) {
      const ss_idx a = (ss_idx)(j * RING + i), b = (ss_idx)(j * RING + (i + 1) % RING);
      const ss_idx t0[3] = {a, b, b + RING}, t1[3] = {a, b + RING, a + RING};
      if (ss_cx_add_cell(cx, SS_TRIANGLE, t0, 0, &err) ||
          ss_cx_add_cell(cx, SS_TRIANGLE, t1, 0, &err))
        exit(1);
    }
  return cx;
}

static ss_scheme *scheme(ss_boundary b) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  if (ss_scheme_new("quasi48", &s, &err) || ss_scheme_set_boundary(s, b, &err)) {
    fprintf(stderr, "%s\n", err.msg);
    exit(1);
  }
  return s;
}

/* Each vertex's boundary neighbours in cx (edges in one triangle): nb[v]
 * counts them, bn[2v..2v+1] the first two. */
static void boundary_nbrs(const ss_cx *cx, unsigned char *nb, ss_idx *bn) {
  ss_error err = {0};
  ss_triedge *te = NULL;
  if (ss_triedge_new(cx, &te, &err)) exit(1);
  memset(nb, 0, cx->nv);
  for (size_t e = 0; e < te->ne; e++)
    for (int j = 0; j < 2 && te->nface[e] == 1; j++) {
      const ss_idx v = te->end[2 * e + j];
      if (nb[v] < 2) bn[2 * (size_t)v + nb[v]] = te->end[2 * e + 1 - j];
      nb[v]++;
    }
  ss_triedge_free(te);
}

/* The sum of the cross products of cx's triangles at v. */
static void normal_at(const ss_cx *cx, size_t v, double n[3]) {
  n[0] = n[1] = n[2] = 0.0;
  for (size_t t = 0; t < cx->nc[SS_TRIANGLE]; t++) {
    const ss_idx *c = ss_cx_cell(cx, SS_TRIANGLE, t);
    if (c[0] != v && c[1] != v && c[2] != v) continue;
    const double *p = cx->x + 3 * c[0], *q = cx->x + 3 * c[1], *r = cx->x + 3 * c[2];
    const double a[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double b[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    n[0] += a[1] * b[2] - a[2] * b[1];
    n[1] += a[2] * b[0] - a[0] * b[2];
    n[2] += a[0] * b[1] - a[1] * b[0];
  }
}

static double norm3(const double *a) {
  return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

/* One level of scheme s on c checked against the curve rule (smooth) or its
 * projection (normal); returns the largest boundary displacement. */
static double check_level(const ss_scheme *s, ss_boundary mode, const ss_cx *c,
                          ss_cx **next, const char *what, int level) {
  ss_error err = {0};
  ss_cx *f = NULL;
  ss_split *L = NULL;
  *next = NULL;
  if (ss_scheme_refine_split(s, c, &f, NULL, &L, &err)) {
    CHECK(0, "%s level %d: %s", what, level, err.msg);
    return 0.0;
  }
  const size_t nc = c->nv;
  unsigned char *nb = malloc(f->nv + 1);
  ss_idx *bn = malloc(2 * f->nv * sizeof *bn + 1);
  boundary_nbrs(f, nb, bn);
  size_t bad = 0, nonpar = 0;
  double moved = 0.0;
  for (size_t v = 0; v < f->nv; v++) {
    if (nb[v] != 2) continue;
    const double *y = f->x + 3 * v;
    double want[3];
    if (v >= nc) { /* a new boundary vertex: the midpoint */
      for (int i = 0; i < 3; i++)
        want[i] = 0.5 * (c->x[3 * bn[2 * v] + i] + c->x[3 * bn[2 * v + 1] + i]);
    } else {
      const double *p = c->x + 3 * v;
      int split = 0;
      ss_idx w[2];
      for (int j = 0; j < 2; j++) {
        w[j] = bn[2 * v + j];
        if (w[j] >= nc) { /* the midpoint's other boundary neighbour */
          split = 1;
          w[j] =
              bn[2 * (size_t)w[j]] == v ? bn[2 * (size_t)w[j] + 1] : bn[2 * (size_t)w[j]];
        }
      }
      for (int i = 0; i < 3; i++)
        want[i] = split ? 0.75 * p[i] + 0.125 * (c->x[3 * w[0] + i] + c->x[3 * w[1] + i])
                        : p[i];
      if (mode == SS_BOUNDARY_NORMAL) {
        double n[3], t = 0.0;
        normal_at(c, v, n);
        for (int i = 0; i < 3; i++)
          t += n[i] * (want[i] - p[i]);
        t /= n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        for (int i = 0; i < 3; i++)
          want[i] = p[i] + t * n[i];
        const double d[3] = {y[0] - p[0], y[1] - p[1], y[2] - p[2]};
        const double x[3] = {d[1] * n[2] - d[2] * n[1], d[2] * n[0] - d[0] * n[2],
                             d[0] * n[1] - d[1] * n[0]};
        nonpar += norm3(x) > 1e-12 * norm3(d) * norm3(n);
      }
      const double d[3] = {y[0] - p[0], y[1] - p[1], y[2] - p[2]};
      moved = fmax(moved, norm3(d));
    }
    const double e[3] = {y[0] - want[0], y[1] - want[1], y[2] - want[2]};
    bad += !(norm3(e) <= 1e-14 * (1.0 + norm3(want)));
  }
  CHECK(bad == 0, "%s level %d: %zu boundary vertices off the rule", what, level, bad);
  CHECK(nonpar == 0, "%s level %d: %zu displacements not along the normal", what, level,
        nonpar);
  free(nb);
  free(bn);
  ss_split_free(L);
  *next = f;
  return moved;
}

/* Levels of one mode on cx, each checked; the largest displacement seen. */
static double run_checked(ss_boundary mode, const ss_cx *cx, int levels,
                          const char *what) {
  ss_error err = {0};
  ss_scheme *s = scheme(mode);
  ss_cx *cur = NULL;
  double moved = 0.0;
  if (ss_cx_copy(cx, &cur, &err)) exit(1);
  for (int l = 1; l <= levels && cur; l++) {
    ss_cx *next = NULL;
    moved = fmax(moved, check_level(s, mode, cur, &next, what, l));
    ss_cx_free(cur);
    cur = next;
  }
  ss_cx_free(cur);
  ss_scheme_free(s);
  return moved;
}

static ss_cx *refined(ss_boundary mode, const ss_cx *cx, int levels) {
  ss_error err = {0};
  ss_scheme *s = scheme(mode);
  ss_cx *f = NULL;
  if (ss_scheme_refine_levels(s, cx, levels, &f, &err)) CHECK(0, "%s", err.msg);
  ss_scheme_free(s);
  return f;
}

/* The largest turning angle (degrees) between consecutive boundary edges, and
 * the largest |z| of a boundary vertex. */
static double max_turn(const ss_cx *cx, double *zmax) {
  unsigned char *nb = malloc(cx->nv + 1);
  ss_idx *bn = malloc(2 * cx->nv * sizeof *bn + 1);
  boundary_nbrs(cx, nb, bn);
  double turn = 0.0;
  *zmax = 0.0;
  for (size_t v = 0; v < cx->nv; v++) {
    if (nb[v] != 2) continue;
    const double *a = cx->x + 3 * bn[2 * v], *p = cx->x + 3 * v,
                 *b = cx->x + 3 * bn[2 * v + 1];
    const double u[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const double w[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
    const double c = (u[0] * w[0] + u[1] * w[1] + u[2] * w[2]) / (norm3(u) * norm3(w));
    turn = fmax(turn, acos(fmin(1.0, fmax(-1.0, c))) * 180.0 / M_PI);
    *zmax = fmax(*zmax, fabs(p[2]));
  }
  free(nb);
  free(bn);
  return turn;
}

static void test_disc(void) {
  ss_cx *d = disc(12);
  const double ms = run_checked(SS_BOUNDARY_SMOOTH, d, 8, "disc smooth");
  const double mn = run_checked(SS_BOUNDARY_NORMAL, d, 8, "disc normal");
  CHECK(ms > 1e-3, "disc smooth: the boundary moved by %g", ms);
  CHECK(mn == 0.0, "disc normal: a planar boundary moved by %g", mn);
  double prev = 0.0, z = 0.0;
  for (int l = 0; l <= 10; l += 2) {
    ss_cx *f = refined(SS_BOUNDARY_SMOOTH, d, l), *g = refined(SS_BOUNDARY_FIXED, d, l);
    double zg = 0.0;
    const double t = max_turn(f, &z), tg = max_turn(g, &zg);
    CHECK(z == 0.0, "disc smooth level %d: a boundary vertex at z = %g", l, z);
    CHECK(l == 0 || t < 0.7 * prev,
          "disc smooth level %d: largest turn %.3g, %.3g before", l, t, prev);
    CHECK(fabs(tg - 30.0) < 1e-9, "disc fixed level %d: largest turn %.3g", l, tg);
    printf("disc level %2d: largest boundary turn %.3g deg (smooth), %.3g (fixed)\n", l,
           t, tg);
    prev = t;
    ss_cx_free(f);
    ss_cx_free(g);
  }
  ss_cx_free(d);
}

static void test_tube(const ss_cx *t) {
  const double mn = run_checked(SS_BOUNDARY_NORMAL, t, 8, "tube normal");
  const double ms = run_checked(SS_BOUNDARY_SMOOTH, t, 8, "tube smooth");
  CHECK(mn > 1e-2 && ms > 1e-2, "tube: boundary moved by %g (normal), %g (smooth)", mn,
        ms);
  printf("tube: largest boundary move %.4g (normal), %.4g (smooth)\n", mn, ms);
  /* no operator for the normal boundary; the smooth one has one */
  ss_error err = {0};
  ss_scheme *sn = scheme(SS_BOUNDARY_NORMAL), *ss = scheme(SS_BOUNDARY_SMOOTH);
  ss_cx *f = NULL,
        *t1 = refined(SS_BOUNDARY_SMOOTH, t, 1); /* boundary edges split next */
  gsl_spmatrix *R = NULL;
  const ss_status st = t1 ? ss_scheme_refine(sn, t1, &f, &R, &err) : SS_EINPUT;
  CHECK(st == SS_EINPUT && strstr(err.msg, "normal"), "normal with an operator: %d %s",
        (int)st, err.msg);
  CHECK(t1 && ss_scheme_refine(ss, t1, &f, &R, &err) == SS_OK,
        "smooth with an operator: %s", err.msg);
  ss_cx_free(t1);
  if (R) gsl_spmatrix_free(R);
  ss_cx_free(f);
  ss_scheme_free(sn);
  ss_scheme_free(ss);
}

/* Figure 15: the z = 0 end tagged (its edges segment cells, its corners
 * vertex cells), and figure 15(c): one longitudinal edge tagged. */
static void test_tags(const ss_cx *t) {
  ss_error err = {0};
  ss_cx *a = NULL, *b = NULL;
  if (ss_cx_copy(t, &a, &err) || ss_cx_copy(t, &b, &err)) exit(1);
  for (ss_idx i = 0; i < RING; i++) {
    const ss_idx s[2] = {i, (ss_idx)((i + 1) % RING)};
    if (ss_cx_add_cell(a, SS_SEGMENT, s, 0, &err) ||
        (i % 2 == 0 && ss_cx_add_cell(a, SS_VERTEX, &i, 0, &err)))
      exit(1);
  }
  const ss_idx lon[2] = {2, 2 + RING}; /* from the corner (-1, 1, 0) up */
  if (ss_cx_add_cell(b, SS_SEGMENT, lon, 0, &err)) exit(1);
  ss_cx *fa = refined(SS_BOUNDARY_NORMAL, a, 6), *fb = refined(SS_BOUNDARY_NORMAL, b, 6);
  if (!fa || !fb) return;
  size_t kept = 0, onsq = 0, at0 = 0, moved_far = 0;
  for (size_t v = 0; v < RING; v++)
    kept += !memcmp(fa->x + 3 * v, t->x + 3 * v, 3 * sizeof *t->x);
  unsigned char *nb = malloc(fa->nv + 1);
  ss_idx *bn = malloc(2 * fa->nv * sizeof *bn + 1);
  boundary_nbrs(fa, nb, bn);
  for (size_t v = 0; v < fa->nv; v++) {
    const double *p = fa->x + 3 * v;
    if (nb[v] != 2) continue;
    if (p[2] < 1.0) {
      at0++;
      onsq += p[2] == 0.0 &&
              (fabs(fabs(p[0]) - 1.0) < 1e-15 || fabs(fabs(p[1]) - 1.0) < 1e-15) &&
              fabs(p[0]) <= 1.0 && fabs(p[1]) <= 1.0;
    } else if (v < t->nv && memcmp(p, t->x + 3 * v, 3 * sizeof *p)) {
      moved_far++;
    }
  }
  CHECK(kept == RING, "tagged end: %zu of %d input vertices kept", kept, RING);
  CHECK(at0 > RING && onsq == at0, "tagged end: %zu of %zu boundary points on the square",
        onsq, at0);
  CHECK(moved_far > 0, "untagged end: nothing moved");
  CHECK(!memcmp(fb->x + 3 * 2, t->x + 3 * 2, 3 * sizeof *t->x),
        "the boundary end of the tagged edge moved");
  CHECK(memcmp(fb->x, t->x, 3 * sizeof *t->x) &&
            memcmp(fb->x + 3 * 4, t->x + 3 * 4, 3 * sizeof *t->x),
        "the untagged corners of that end did not move");
  free(nb);
  free(bn);
  ss_cx_free(fa);
  ss_cx_free(fb);
  ss_cx_free(a);
  ss_cx_free(b);
}

static void test_closed(const char *dir) {
  ss_error err = {0};
  char path[4096];
  snprintf(path, sizeof path, "%s/icosahedron.obj", dir);
  ss_cx *ico = NULL;
  REQUIRE_OK_VOID(ss_mesh_read(path, SS_MESH_AUTO, &ico, &err), &err);
  ss_cx *f[3];
  for (int m = 0; m < 3; m++)
    f[m] = refined((ss_boundary)m, ico, 5);
  for (int m = 1; m < 3; m++)
    CHECK(f[0] && f[m] && f[0]->nv == f[m]->nv &&
              !memcmp(f[0]->x, f[m]->x, 3 * f[0]->nv * sizeof *f[0]->x),
          "closed surface: boundary mode %d differs from normal", m);
  for (int m = 0; m < 3; m++)
    ss_cx_free(f[m]);
  ss_cx_free(ico);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_quasi48_boundary DATA/MESHES\n");
    return 2;
  }
  test_disc();
  ss_cx *t = tube();
  test_tube(t);
  test_tags(t);
  ss_cx_free(t);
  test_closed(argv[1]);
  ss_error err = {0};
  ss_scheme *s = NULL;
  CHECK(!ss_scheme_new("loop", &s, &err) &&
            ss_scheme_set_boundary(s, SS_BOUNDARY_SMOOTH, &err) == SS_EINPUT,
        "loop took a boundary rule");
  ss_scheme_free(s);
  return ss_test_done("quasi48_boundary");
}
