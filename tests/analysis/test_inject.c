/* test_inject.c — the injectivity test of a PL image (ss_inject):
 *  - one reference cell of every type winds once about an inner point, -1
 *    mirrored, 0 about an outer point, and is undecided for a point on it
 *    (this pins the facet orientations and the PL splitting);
 *  - the degree agrees with the solid-angle (2D: angle) sum of the boundary
 *    on random closed tet stars and triangle fans, flat facets included;
 *  - real characteristic maps (MLCA, tet/oct, Catmull–Clark, Loop, an MLCA
 *    edge) pass with degree equal to their cells' orientation and no
 *    overlaps, under similarities too, and with degree -1 mirrored;
 *  - a map that winds twice (Catmull–Clark valence 8 with its angles
 *    doubled; the MLCA hex star of bipyramid:8, whose characteristic map does
 *    not exist, with its azimuth doubled) fails with degree 2;
 *  - a cell moved onto a far cell is the one overlap found and reported, the
 *    same after a similarity; a folded lattice has degree 1, cells of both
 *    signs and flat cells, and its overlaps are found;
 *  - the cheap separating-facet / inner-point test asked before CGAL's
 *    do_intersect never contradicts it: pairs of random tets and triangles
 *    on a coarse integer grid (shared corners, touching facets and coplanar
 *    points are frequent there) and continuous ones; each answer it gives
 *    (apart, meet) and leaves open is seen;
 *  - bad input is SS_EINPUT with a message;
 *  - the time of the test on the MLCA k = 10 and k = 12 (icosahedron) maps
 *    is printed. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lapacke.h>

#include "ss_inject.h"
#include "ss_inject_cgal.h"
#include "ss_link.h"
#include "ss_test.h"
#include "ss_testcase.h"

#define PI 3.14159265358979323846

/* deterministic uniform numbers in [-1, 1) */
static double rnd(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}

/* ---- nets ---- */

/* A control net the test owns. */
typedef struct {
  int dim;             /* 2 or 3 */
  size_t n;            /* points */
  double *x;           /* n * dim coordinates */
  size_t ncells;       /* cells */
  ss_cell_type *ctype; /* ncells types */
  size_t *corner;      /* ncells * SS_MAXCELLVERTS corners */
} net;

static net net_alloc(int dim, size_t n, size_t ncells) {
  net m = {dim,
           n,
           calloc(n * (size_t)dim, sizeof(double)),
           ncells,
           calloc(ncells, sizeof(ss_cell_type)),
           malloc(ncells * SS_MAXCELLVERTS * sizeof(size_t))};
  if (!m.x || !m.ctype || !m.corner) {
    fprintf(stderr, "out of memory\n");
    exit(1);
  }
  for (size_t i = 0; i < ncells * SS_MAXCELLVERTS; i++)
    m.corner[i] = SIZE_MAX;
  return m;
}

static void net_free(net *m) {
  free(m->x);
  free(m->ctype);
  free(m->corner);
  memset(m, 0, sizeof *m);
}

static net net_copy(const double *x, int dim, size_t n, const ss_cell_type *ctype,
                    const size_t *corner, size_t ncells) {
  net m = net_alloc(dim, n, ncells);
  memcpy(m.x, x, n * (size_t)dim * sizeof *x);
  memcpy(m.ctype, ctype, ncells * sizeof *ctype);
  memcpy(m.corner, corner, ncells * SS_MAXCELLVERTS * sizeof *corner);
  return m;
}

static void set_cell(net *m, size_t c, ss_cell_type t, const size_t *v) {
  m->ctype[c] = t;
  for (int j = 0; j < ss_cell_nverts(t); j++)
    m->corner[c * SS_MAXCELLVERTS + (size_t)j] = v[j];
}

static ss_status inject(const net *m, size_t centre, ss_injectivity *r, ss_error *err) {
  return ss_inject_test(m->x, m->dim, m->n, m->ctype, m->corner, m->ncells, centre, r,
                        err);
}

/* x -> s R x + t with R a fixed rotation (det +1); mirror: then x0 -> -x0. */
static void similarity(net *m, double s, int mirror) {
  const double a = 0.7, b = -1.3, c = 2.1;
  double R[3][3];
  if (m->dim == 3) {
    /* Rz(a) Ry(b) Rx(c) */
    const double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cc = cos(c),
                 sc = sin(c);
    const double M[3][3] = {{ca * cb, ca * sb * sc - sa * cc, ca * sb * cc + sa * sc},
                            {sa * cb, sa * sb * sc + ca * cc, sa * sb * cc - ca * sc},
                            {-sb, cb * sc, cb * cc}};
    memcpy(R, M, sizeof R);
  } else {
    const double M[3][3] = {{cos(a), -sin(a), 0}, {sin(a), cos(a), 0}, {0, 0, 1}};
    memcpy(R, M, sizeof R);
  }
  const double t[3] = {10.25, -3.5, 7.0};
  const size_t D = (size_t)m->dim;
  for (size_t i = 0; i < m->n; i++) {
    double *p = m->x + D * i, y[3] = {0, 0, 0};
    for (size_t r = 0; r < D; r++)
      for (size_t k = 0; k < D; k++)
        y[r] += R[r][k] * p[k];
    for (size_t r = 0; r < D; r++)
      p[r] = s * y[r] + t[r];
    if (mirror) p[0] = -p[0];
  }
}

/* Map the net, relative to point `centre`, by C^(-1/2) with C the second
 * moments about it: a linear image of a configuration with a rotational
 * symmetry about an axis through the centre becomes, up to a rotation, one
 * with that symmetry and isotropic in the plane it rotates. */
static int whiten(net *m, size_t centre) {
  const int D = m->dim;
  double C[9] = {0}, w[3];
  const double *p0 = m->x + (size_t)D * centre;
  double p[3] = {p0[0], p0[1], D == 3 ? p0[2] : 0.0};
  for (size_t i = 0; i < m->n; i++)
    for (int a = 0; a < D; a++)
      for (int b = 0; b < D; b++)
        C[a * D + b] += (m->x[(size_t)D * i + (size_t)a] - p[a]) *
                        (m->x[(size_t)D * i + (size_t)b] - p[b]);
  if (LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'V', 'U', D, C, D, w)) return -1;
  for (size_t i = 0; i < m->n; i++) {
    double *y = m->x + (size_t)D * i, z[3] = {0, 0, 0};
    for (int k = 0; k < D; k++) /* z_k = (v_k . (y - p)) / sqrt(w_k) */
      for (int a = 0; a < D; a++)
        z[k] += C[a * D + k] * (y[a] - p[a]) / sqrt(w[k]);
    for (int a = 0; a < D; a++) {
      y[a] = 0.0;
      for (int k = 0; k < D; k++)
        y[a] += C[a * D + k] * z[k];
    }
  }
  return 0;
}

/* ---- the pipeline ---- */

static int run_named(const char *scheme, const char *link, ss_testcase *out) {
  ss_link *l = NULL;
  ss_error err = {0};
  if (ss_link_named(link, &l, &err)) {
    CHECK(0, "%s: %s", link, err.msg);
    return -1;
  }
  const int st =
      ss_testcase_run(scheme, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, out);
  ss_link_free(l);
  return st;
}

static net charmap_net(const ss_charmap *cm) {
  return net_copy(cm->x, cm->dim, cm->n, cm->ctype, cm->corner, cm->ncells);
}

/* ---- one cell of each type ---- */

/* Reference cells, positive under ss_cx.h: corners point by point. */
static const double tet_x[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double cube_x[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                                0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
/* a twisted hex: faces not planar */
static const double twisted_x[] = {0,   0, 0, 1, 0,    0.2, 1.1, 1, 0,   0, 1,   -0.1,
                                   0.1, 0, 1, 1, -0.1, 1,   1,   1, 1.2, 0, 1.2, 1};
static const double oct_x[] = {1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
static const double square_x[] = {0, 0, 1, 0, 1, 1, 0, 1};
static const double tri_x[] = {0, 0, 1, 0, 0, 1};

typedef struct {
  ss_cell_type t;
  int dim;
  const double *x;  /* corners */
  double inside[3]; /* a point inside */
  double on[3];     /* a point on the boundary (not a corner); NaN: the
                       centre of the first face (its corners 0 1 2 3) */
  size_t facets;    /* boundary facets */
} ref_cell;

static void test_single_cells(void) {
  const ref_cell cells[] = {
      {SS_TET, 3, tet_x, {0.1, 0.2, 0.3}, {0.25, 0.25, 0.5}, 4},
      {SS_HEX, 3, cube_x, {0.3, 0.4, 0.6}, {0.25, 0.5, 1.0}, 6},
      {SS_HEX, 3, twisted_x, {0.5, 0.5, 0.5}, {NAN, 0, 0}, 6},
      {SS_OCT, 3, oct_x, {0.1, -0.2, 0.15}, {-0.25, 0.25, -0.5}, 8},
      {SS_QUAD, 2, square_x, {0.3, 0.6}, {1.0, 0.375}, 4},
      {SS_TRIANGLE, 2, tri_x, {0.2, 0.3}, {0.5, 0.5}, 3},
  };
  for (size_t k = 0; k < sizeof cells / sizeof cells[0]; k++) {
    const ref_cell *rc = &cells[k];
    const int nv = ss_cell_nverts(rc->t), D = rc->dim;
    /* the face centre: the mean of corners 0..3 summed in that order, as
       ss_inject splits the face */
    double on[3];
    memcpy(on, rc->on, sizeof on);
    if (isnan(rc->on[0]))
      for (int i = 0; i < 3; i++)
        on[i] = (((rc->x[i] + rc->x[3 + i]) + rc->x[6 + i]) + rc->x[9 + i]) / 4;
    for (int mirror = 0; mirror < 2; mirror++)
      for (int where = 0; where < 4; where++) {
        /* centre: inside, outside, on the boundary, a corner */
        net m = net_alloc(D, (size_t)nv + 1, 1);
        size_t v[8];
        for (int j = 0; j < nv; j++) {
          v[j] = (size_t)j;
          memcpy(m.x + D * j, rc->x + D * j, (size_t)D * sizeof(double));
        }
        const double *c = where == 0 ? rc->inside : on;
        const double out_pt[3] = {1.5, 1.25, 2.0};
        if (where == 1) c = out_pt;
        if (where == 3) c = rc->x + D;
        memcpy(m.x + D * nv, c, (size_t)D * sizeof(double));
        set_cell(&m, 0, rc->t, v);
        if (mirror)
          for (size_t i = 0; i < m.n; i++)
            m.x[(size_t)D * i] = -m.x[(size_t)D * i];
        ss_injectivity r;
        ss_error err = {0};
        if (inject(&m, (size_t)nv, &r, &err) != SS_OK) {
          CHECK(0, "%s: %s", ss_cell_name(rc->t), err.msg);
          net_free(&m);
          continue;
        }
        const int want = where == 0 ? (mirror ? -1 : 1) : 0;
        const ss_verdict_kind vk = where == 0   ? SS_PASS
                                   : where == 1 ? SS_FAIL
                                                : SS_UNDECIDED;
        CHECK(r.verdict.verdict == vk && r.degree == want && r.boundary == rc->facets &&
                  r.overlaps == 0 && r.first[0] == SIZE_MAX,
              "%s %zu (mirror %d, centre %s): %s, degree %d (want %d), %zu facets, %zu "
              "overlaps: %s",
              ss_cell_name(rc->t), k, mirror,
              (const char *[]){"inside", "outside", "on a facet", "a corner"}[where],
              ss_verdict_name(r.verdict.verdict), r.degree, want, r.boundary, r.overlaps,
              r.verdict.reason);
        net_free(&m);
      }
  }
}

/* ---- the degree against the solid-angle sum, on random closed nets ---- */

/* Signed solid angle of triangle (a, b, c) seen from p (Van Oosterom and
 * Strackee); positive when a, b, c run counter-clockwise seen from p. */
static double solid_angle(const double *a, const double *b, const double *c,
                          const double *p) {
  double u[3], v[3], w[3];
  for (int i = 0; i < 3; i++)
    u[i] = a[i] - p[i], v[i] = b[i] - p[i], w[i] = c[i] - p[i];
  const double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const double lv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  const double lw = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  const double det = u[0] * (v[1] * w[2] - v[2] * w[1]) -
                     u[1] * (v[0] * w[2] - v[2] * w[0]) +
                     u[2] * (v[0] * w[1] - v[1] * w[0]);
  const double uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  const double uw = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
  const double vw = v[0] * w[0] + v[1] * w[1] + v[2] * w[2];
  return 2.0 * atan2(det, lu * lv * lw + uv * lw + uw * lv + vw * lu);
}

/* Distance from p to segment ab. */
static double seg_dist(const double *a, const double *b, const double *p, int D) {
  double ab[3] = {0}, ap[3] = {0}, t = 0, l2 = 0;
  for (int i = 0; i < D; i++)
    ab[i] = b[i] - a[i], ap[i] = p[i] - a[i], t += ab[i] * ap[i], l2 += ab[i] * ab[i];
  t = l2 > 0 ? fmin(1.0, fmax(0.0, t / l2)) : 0.0;
  double d2 = 0;
  for (int i = 0; i < D; i++)
    d2 += (ap[i] - t * ab[i]) * (ap[i] - t * ab[i]);
  return sqrt(d2);
}

static void test_random_degree(void) {
  ss_link *ico = NULL;
  ss_error err = {0};
  int *tri = NULL, ntri = 0;
  REQUIRE_OK_VOID(ss_link_named("icosahedron", &ico, &err), &err);
  REQUIRE_OK_VOID(ss_link_triangles(ico, &tri, &ntri, &err), &err);
  uint64_t s = 12345;
  int compared = 0, nonzero = 0, flat = 0;
  /* 3D: tets (o, a, b, c) over the icosahedron's triangles; the boundary is
   * the icosahedron with its 12 vertices placed at random; point 13 is p */
  for (int trial = 0; trial < 300; trial++) {
    net m = net_alloc(3, 14, (size_t)ntri);
    for (size_t i = 0; i < 14 * 3; i++) /* multiples of 2^-20: midpoints exact */
      m.x[i] = round(rnd(&s) * 1048576.0) / 1048576.0;
    if (trial % 3 == 1) { /* a flat boundary triangle: a vertex on an edge */
      const int *t = tri + 3 * (trial % ntri);
      for (int i = 0; i < 3; i++)
        m.x[3 * (1 + t[2]) + i] =
            0.5 * (m.x[3 * (1 + t[0]) + i] + m.x[3 * (1 + t[1]) + i]);
      flat++;
    } else if (trial % 3 == 2) { /* a flat one: two vertices on one point */
      const int *t = tri + 3 * (trial % ntri);
      memcpy(m.x + 3 * (1 + t[1]), m.x + 3 * (1 + t[0]), 3 * sizeof(double));
      flat++;
    }
    for (int t = 0; t < ntri; t++) {
      const size_t v[4] = {0, 1 + (size_t)tri[3 * t], 1 + (size_t)tri[3 * t + 1],
                           1 + (size_t)tri[3 * t + 2]};
      set_cell(&m, (size_t)t, SS_TET, v);
    }
    double omega = 0.0, dmin = INFINITY;
    const double *p = m.x + 3 * 13;
    for (int t = 0; t < ntri; t++) {
      const double *a = m.x + 3 * (1 + tri[3 * t]), *b = m.x + 3 * (1 + tri[3 * t + 1]),
                   *c = m.x + 3 * (1 + tri[3 * t + 2]);
      omega += solid_angle(a, b, c, p);
      dmin = fmin(dmin, fmin(seg_dist(a, b, p, 3),
                             fmin(seg_dist(b, c, p, 3), seg_dist(c, a, p, 3))));
    }
    const double w = omega / (4 * PI);
    ss_injectivity r;
    if (inject(&m, 13, &r, &err) != SS_OK) {
      CHECK(0, "random star %d: %s", trial, err.msg);
    } else if (dmin > 1e-6 && fabs(w - round(w)) < 1e-6) {
      CHECK(r.verdict.verdict != SS_UNDECIDED && r.degree == (int)round(w),
            "random star %d: degree %d (%s), solid angles give %.9f", trial, r.degree,
            ss_verdict_name(r.verdict.verdict), w);
      compared++;
      nonzero += r.degree != 0;
    }
    net_free(&m);
  }
  /* 2D: a fan of triangles (o, v_i, v_i+1) with random v_i; some edges of
   * zero length */
  for (int trial = 0; trial < 300; trial++) {
    const size_t k = 3 + (size_t)trial % 9;
    net m = net_alloc(2, k + 2, k);
    for (size_t i = 0; i < 2 * (k + 2); i++)
      m.x[i] = rnd(&s);
    if (trial % 4 == 3) {
      memcpy(m.x + 2 * 2, m.x + 2 * 1, 2 * sizeof(double));
      flat++;
    }
    double ang = 0.0, dmin = INFINITY;
    const double *p = m.x + 2 * (k + 1);
    for (size_t i = 0; i < k; i++) {
      const size_t v[3] = {0, 1 + i, 1 + (i + 1) % k};
      set_cell(&m, i, SS_TRIANGLE, v);
      const double *a = m.x + 2 * v[1], *b = m.x + 2 * v[2];
      ang += atan2((a[0] - p[0]) * (b[1] - p[1]) - (a[1] - p[1]) * (b[0] - p[0]),
                   (a[0] - p[0]) * (b[0] - p[0]) + (a[1] - p[1]) * (b[1] - p[1]));
      dmin = fmin(dmin, seg_dist(a, b, p, 2));
    }
    const double w = ang / (2 * PI);
    ss_injectivity r;
    if (inject(&m, k + 1, &r, &err) != SS_OK) {
      CHECK(0, "random fan %d: %s", trial, err.msg);
    } else if (dmin > 1e-6) {
      CHECK(r.verdict.verdict != SS_UNDECIDED && r.degree == (int)round(w),
            "random fan %d: degree %d (%s), angles give %.9f", trial, r.degree,
            ss_verdict_name(r.verdict.verdict), w);
      compared++;
      nonzero += r.degree != 0;
    }
    net_free(&m);
  }
  CHECK(compared > 400 && nonzero > 50 && flat > 200,
        "random nets: %d compared, %d of nonzero degree, %d with flat facets", compared,
        nonzero, flat);
  free(tri);
  ss_link_free(ico);
}

/* ---- real characteristic maps ---- */

/* The verdict on cm's net must be a pass with degree = the cells' sign, and
 * stay so under a similarity; mirrored, degree -sign. */
static void check_pass(const char *what, const ss_testcase *res) {
  const ss_charmap *cm = res->cm;
  ss_injectivity r;
  ss_error err = {0};
  if (ss_inject_test(cm->x, cm->dim, cm->n, cm->ctype, cm->corner, cm->ncells, 0, &r,
                     &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    return;
  }
  CHECK(r.verdict.verdict == SS_PASS && r.degree == res->r.sign && r.overlaps == 0 &&
            r.boundary > 0,
        "%s: %s (%s), degree %d, cells of sign %d, %zu overlaps, %zu boundary facets",
        what, ss_verdict_name(r.verdict.verdict), r.verdict.reason, r.degree, res->r.sign,
        r.overlaps, r.boundary);
  for (int mirror = 0; mirror < 2; mirror++) {
    net m = charmap_net(cm);
    similarity(&m, mirror ? 0.031 : 37.5, mirror);
    ss_injectivity r2;
    if (inject(&m, 0, &r2, &err)) {
      CHECK(0, "%s: %s", what, err.msg);
    } else {
      CHECK(r2.verdict.verdict == SS_PASS &&
                r2.degree == (mirror ? -r.degree : r.degree) && r2.overlaps == 0 &&
                r2.boundary == r.boundary,
            "%s under a similarity (mirror %d): %s (%s), degree %d", what, mirror,
            ss_verdict_name(r2.verdict.verdict), r2.verdict.reason, r2.degree);
    }
    net_free(&m);
  }
}

static void test_charmaps(void) {
  const char *links[] = {"octahedron", "bipyramid:3", "icosahedron", "tetrahedron"};
  char what[96];
  ss_testcase res;
  for (int i = 0; i < 3; i++) {
    if (run_named("mlca", links[i], &res)) continue;
    snprintf(what, sizeof what, "mlca vertex %s", links[i]);
    check_pass(what, &res);
    ss_testcase_free(&res);
  }
  for (int i = 0; i < 4; i++) {
    if (run_named("tetoct", links[i], &res)) continue;
    int tets = 0, octs = 0;
    for (size_t c = 0; c < res.cm->ncells; c++)
      tets += res.cm->ctype[c] == SS_TET, octs += res.cm->ctype[c] == SS_OCT;
    CHECK(tets > 0 && octs > 0, "tetoct %s: %d tets, %d octahedra", links[i], tets, octs);
    snprintf(what, sizeof what, "tetoct vertex %s", links[i]);
    check_pass(what, &res);
    ss_testcase_free(&res);
  }
  for (int n = 3; n <= 8; n++) {
    const char *schemes[2] = {"catmull-clark", "loop"};
    for (int s = 0; s < 2; s++) {
      if (ss_testcase_run(schemes[s],
                          (ss_case){SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0},
                          &res))
        continue;
      const ss_cell_type want = s == 0 ? SS_QUAD : SS_TRIANGLE;
      CHECK(res.cm->ctype[0] == want, "%s: cells are %s", schemes[s],
            ss_cell_plural(res.cm->ctype[0]));
      snprintf(what, sizeof what, "%s surface vertex n = %d", schemes[s], n);
      check_pass(what, &res);
      ss_testcase_free(&res);
    }
  }
  if (!ss_testcase_run("mlca", (ss_case){SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0}, &res)) {
    check_pass("mlca edge n = 5", &res);
    ss_testcase_free(&res);
  }
}

/* ---- maps of degree 2 ---- */

static void test_degree_two(void) {
  ss_testcase res;
  ss_error err = {0};
  ss_injectivity r;
  /* Catmull–Clark valence 8: each point's angle about the centre doubled */
  if (!ss_testcase_run("catmull-clark",
                       (ss_case){SS_CASE_SURFACE_VERTEX, NULL, 8, SS_DIAG_BFS, 0},
                       &res)) {
    net m = charmap_net(res.cm);
    CHECK(!whiten(&m, 0), "whiten");
    const double *p = m.x;
    const double px = p[0], py = p[1];
    for (size_t i = 0; i < m.n; i++) {
      double *y = m.x + 2 * i;
      const double dx = y[0] - px, dy = y[1] - py;
      const double rr = hypot(dx, dy), th = atan2(dy, dx);
      y[0] = px + rr * cos(2 * th), y[1] = py + rr * sin(2 * th);
    }
    /* the cells stay of one sign (a check on the construction) */
    int pos = 0, neg = 0;
    for (size_t c = 0; c < m.ncells; c++) {
      const size_t *v = m.corner + c * SS_MAXCELLVERTS;
      for (int j = 0; j < 4; j++) {
        const double *a = m.x + 2 * v[j], *b = m.x + 2 * v[(j + 1) % 4],
                     *d = m.x + 2 * v[(j + 3) % 4];
        const double det = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
        pos += det > 0, neg += det < 0;
      }
    }
    CHECK(pos == 0 || neg == 0, "CC 8 doubled: corners of both signs (%d, %d)", pos, neg);
    if (inject(&m, 0, &r, &err)) {
      CHECK(0, "CC 8 doubled: %s", err.msg);
    } else {
      CHECK(r.verdict.verdict == SS_FAIL && r.degree == 2 * res.r.sign,
            "CC 8 with doubled angles: %s (%s), degree %d, cells of sign %d",
            ss_verdict_name(r.verdict.verdict), r.verdict.reason, r.degree, res.r.sign);
      printf("CC 8 doubled: %s\n", r.verdict.reason);
    }
    net_free(&m);
    ss_testcase_free(&res);
  }
  /* The MLCA hex star of the bipyramid:8 link (its characteristic map does
   * not exist: the eigenvalue condition fails there), as ss_star embeds it:
   * symmetric about the axis through the centre (star vertex 0) and the
   * edge points of the poles, link vertices 8 and 9 (star vertex 1 + 8).  Its
   * azimuth about that axis doubled. */
  ss_scheme *mlca = NULL;
  ss_link *l = NULL;
  ss_star *st = NULL;
  if (ss_scheme_new("mlca", &mlca, &err) || ss_link_named("bipyramid:8", &l, &err) ||
      ss_case_star(mlca, &(ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, &st, &err)) {
    CHECK(0, "bipyramid:8 star: %s", err.msg);
  } else {
    const ss_cx *cx = st->cx;
    net m = net_alloc(3, cx->nv, cx->nc[SS_HEX]);
    memcpy(m.x, cx->x, 3 * cx->nv * sizeof(double));
    for (size_t c = 0; c < m.ncells; c++) {
      size_t v[8];
      for (int j = 0; j < 8; j++)
        v[j] = ss_cx_cell(cx, SS_HEX, c)[j];
      set_cell(&m, c, SS_HEX, v);
    }
    if (inject(&m, 0, &r, &err)) {
      CHECK(0, "bipyramid:8 star: %s", err.msg);
    } else {
      CHECK(r.verdict.verdict == SS_PASS && r.degree == 1,
            "MLCA bipyramid:8 star: %s (%s), degree %d",
            ss_verdict_name(r.verdict.verdict), r.verdict.reason, r.degree);
    }
    const double *p = m.x;
    double a[3], u[3], v[3], len = 0;
    for (int i = 0; i < 3; i++)
      a[i] = m.x[3 * 9 + (size_t)i] - p[i], len += a[i] * a[i];
    for (int i = 0; i < 3; i++)
      a[i] /= sqrt(len);
    /* u: the unit vector e_k least along a, less its component along a */
    const int k = fabs(a[0]) < fabs(a[1]) ? (fabs(a[0]) < fabs(a[2]) ? 0 : 2)
                                          : (fabs(a[1]) < fabs(a[2]) ? 1 : 2);
    double ul = 0;
    for (int i = 0; i < 3; i++)
      u[i] = (i == k) - a[k] * a[i], ul += u[i] * u[i];
    for (int i = 0; i < 3; i++)
      u[i] /= sqrt(ul);
    v[0] = a[1] * u[2] - a[2] * u[1], v[1] = a[2] * u[0] - a[0] * u[2],
    v[2] = a[0] * u[1] - a[1] * u[0];
    const double c0[3] = {p[0], p[1], p[2]};
    for (size_t i = 0; i < m.n; i++) {
      double *y = m.x + 3 * i, d[3], h = 0, s1 = 0, s2 = 0;
      for (int j = 0; j < 3; j++)
        d[j] = y[j] - c0[j], h += d[j] * a[j], s1 += d[j] * u[j], s2 += d[j] * v[j];
      const double rr = hypot(s1, s2), th = atan2(s2, s1);
      for (int j = 0; j < 3; j++)
        y[j] = c0[j] + h * a[j] + rr * (cos(2 * th) * u[j] + sin(2 * th) * v[j]);
    }
    if (inject(&m, 0, &r, &err)) {
      CHECK(0, "bipyramid:8 doubled: %s", err.msg);
    } else {
      CHECK(r.verdict.verdict == SS_FAIL && r.degree == 2,
            "MLCA bipyramid:8 star with doubled azimuth: %s (%s), degree %d",
            ss_verdict_name(r.verdict.verdict), r.verdict.reason, r.degree);
      printf("MLCA bipyramid:8 star doubled: %s\n", r.verdict.reason);
    }
    net_free(&m);
  }
  ss_star_free(st);
  ss_link_free(l);
  ss_scheme_free(mlca);
}

/* ---- overlaps ---- */

static int share_corner(const net *m, size_t a, size_t b) {
  for (int i = 0; i < SS_MAXCELLVERTS; i++)
    for (int j = 0; j < SS_MAXCELLVERTS; j++)
      if (m->corner[a * SS_MAXCELLVERTS + (size_t)i] != SIZE_MAX &&
          m->corner[a * SS_MAXCELLVERTS + (size_t)i] ==
              m->corner[b * SS_MAXCELLVERTS + (size_t)j])
        return 1;
  return 0;
}

/* Cell d is cut loose (given points of its own) and laid inside cell c, far
 * away: a copy of c shrunk by half about its centre.  Exactly the pair
 * (c, d) overlaps; the degree does not change. */
static void check_moved(const char *what, const ss_testcase *res) {
  const ss_charmap *cm = res->cm;
  const size_t D = (size_t)cm->dim;
  /* c: the cell holding the centre with the smallest index; d: the cell
   * farthest from it (by mean corner distance) sharing no corner */
  net base = charmap_net(cm);
  size_t c = SIZE_MAX, d = SIZE_MAX;
  for (size_t i = 0; i < cm->ncells && c == SIZE_MAX; i++)
    for (int j = 0; j < SS_MAXCELLVERTS; j++)
      if (cm->corner[i * SS_MAXCELLVERTS + (size_t)j] == 0) c = i;
  double far = -1;
  for (size_t i = 0; i < cm->ncells; i++) {
    if (share_corner(&base, i, c) || cm->ctype[i] != cm->ctype[c]) continue;
    double dist = 0;
    const int nv = ss_cell_nverts(cm->ctype[i]);
    for (int j = 0; j < nv; j++)
      for (size_t k = 0; k < D; k++) {
        const double t = cm->x[cm->corner[i * SS_MAXCELLVERTS + (size_t)j] * D + k];
        dist += t * t;
      }
    if (dist > far) far = dist, d = i;
  }
  net_free(&base);
  if (c == SIZE_MAX || d == SIZE_MAX) {
    CHECK(0, "%s: no cell pair to move", what);
    return;
  }
  const int nv = ss_cell_nverts(cm->ctype[c]);
  net m = net_alloc(cm->dim, cm->n + (size_t)nv, cm->ncells);
  memcpy(m.x, cm->x, cm->n * D * sizeof(double));
  memcpy(m.ctype, cm->ctype, cm->ncells * sizeof *m.ctype);
  memcpy(m.corner, cm->corner, cm->ncells * SS_MAXCELLVERTS * sizeof *m.corner);
  double g[3] = {0, 0, 0};
  for (int j = 0; j < nv; j++)
    for (size_t k = 0; k < D; k++)
      g[k] += cm->x[cm->corner[c * SS_MAXCELLVERTS + (size_t)j] * D + k] / nv;
  for (int j = 0; j < nv; j++) {
    const size_t q = cm->n + (size_t)j;
    for (size_t k = 0; k < D; k++)
      m.x[q * D + k] =
          g[k] +
          0.5 * (cm->x[cm->corner[c * SS_MAXCELLVERTS + (size_t)j] * D + k] - g[k]);
    m.corner[d * SS_MAXCELLVERTS + (size_t)j] = q;
  }
  ss_injectivity r;
  ss_error err = {0};
  const size_t lo = c < d ? c : d, hi = c < d ? d : c;
  for (int sim = 0; sim < 3; sim++) {
    if (sim) similarity(&m, sim == 1 ? 5.5 : 0.25, sim == 2);
    if (inject(&m, 0, &r, &err)) {
      CHECK(0, "%s: %s", what, err.msg);
      break;
    }
    const int deg = sim == 2 ? -res->r.sign : res->r.sign;
    CHECK(r.verdict.verdict == SS_FAIL && r.degree == deg && r.overlaps == 1 &&
              r.first[0] == lo && r.first[1] == hi,
          "%s, cell %zu moved into cell %zu (similarity %d): %s (%s), degree %d, %zu "
          "overlaps, first (%zu, %zu)",
          what, d, c, sim, ss_verdict_name(r.verdict.verdict), r.verdict.reason, r.degree,
          r.overlaps, r.first[0], r.first[1]);
    if (sim == 0) printf("%s: %s\n", what, r.verdict.reason);
  }
  net_free(&m);
}

static void test_moved(void) {
  ss_testcase res;
  if (!run_named("mlca", "icosahedron", &res)) {
    check_moved("mlca icosahedron", &res);
    ss_testcase_free(&res);
  }
  if (!run_named("tetoct", "octahedron", &res)) {
    check_moved("tetoct octahedron", &res);
    ss_testcase_free(&res);
  }
  if (!ss_testcase_run("catmull-clark",
                       (ss_case){SS_CASE_SURFACE_VERTEX, NULL, 5, SS_DIAG_BFS, 0},
                       &res)) {
    check_moved("catmull-clark n = 5", &res);
    ss_testcase_free(&res);
  }
  if (!ss_testcase_run("loop", (ss_case){SS_CASE_SURFACE_VERTEX, NULL, 7, SS_DIAG_BFS, 0},
                       &res)) {
    check_moved("loop n = 7", &res);
    ss_testcase_free(&res);
  }
}

/* Point index of lattice point (i, j, k) of a lattice with s points a side,
 * with the origin's index (o) and 0 swapped, so that the centre is point 0. */
static size_t lat_idx(int i, int j, int k, int s, size_t o) {
  const size_t q = (size_t)((k * s + j) * s + i);
  return q == o ? 0 : q == 0 ? o : q;
}

/* A lattice of (2h)^dim unit cubes (squares) on [-h, h]^dim, the origin
 * point 0. */
static net lattice(int dim, int h) {
  const int s = 2 * h + 1, nk = dim == 3 ? s : 1;
  const size_t np = (size_t)s * (size_t)s * (size_t)nk;
  const size_t nc = (size_t)(2 * h) * (size_t)(2 * h) * (size_t)(dim == 3 ? 2 * h : 1);
  net m = net_alloc(dim, np, nc);
  const size_t o = (size_t)(((dim == 3 ? h : 0) * s + h) * s + h);
  for (int k = 0; k < nk; k++)
    for (int j = 0; j < s; j++)
      for (int i = 0; i < s; i++) {
        const size_t q = lat_idx(i, j, k, s, o);
        m.x[q * (size_t)dim] = i - h, m.x[q * (size_t)dim + 1] = j - h;
        if (dim == 3) m.x[q * 3 + 2] = k - h;
      }
  size_t c = 0;
  for (int k = 0; k < (dim == 3 ? 2 * h : 1); k++)
    for (int j = 0; j < 2 * h; j++)
      for (int i = 0; i < 2 * h; i++, c++) {
        size_t v[8];
        for (int b = 0; b < (dim == 3 ? 8 : 4); b++) {
          const unsigned bits = ss_cube_corner_bits(dim, b);
          v[b] = lat_idx(i + (int)(bits & 1u), j + (int)((bits >> 1) & 1u),
                         k + (int)((bits >> 2) & 1u), s, o);
        }
        set_cell(&m, c, dim == 3 ? SS_HEX : SS_QUAD, v);
      }
  return m;
}

/* The lattice folded: x0 > f = 2.5 is reflected to 2 f - x0.  The cells
 * beyond x0 = 3 are inverted and land on cells in [1, 2] they share no corner
 * with; the cells across the fold are flat; the centre is not covered, so the
 * degree stays 1. */
static void test_folded(void) {
  for (int dim = 2; dim <= 3; dim++) {
    net m = lattice(dim, 4);
    ss_injectivity r;
    ss_error err = {0};
    if (inject(&m, 0, &r, &err)) {
      CHECK(0, "lattice %dD: %s", dim, err.msg);
    } else {
      CHECK(r.verdict.verdict == SS_PASS && r.degree == 1 && r.overlaps == 0,
            "lattice %dD: %s (%s), degree %d", dim, ss_verdict_name(r.verdict.verdict),
            r.verdict.reason, r.degree);
    }
    const double f = 2.5;
    for (size_t i = 0; i < m.n; i++)
      if (m.x[i * (size_t)dim] > f) m.x[i * (size_t)dim] = 2 * f - m.x[i * (size_t)dim];
    /* cells wholly beyond the fold (x0 in [3, 4]) land on cells in [1, 2] */
    const size_t folded = dim == 3 ? 8 * 8 : 8;
    if (inject(&m, 0, &r, &err)) {
      CHECK(0, "folded lattice %dD: %s", dim, err.msg);
    } else {
      CHECK(r.verdict.verdict == SS_FAIL && r.degree == 1 && r.overlaps >= folded &&
                r.first[0] != SIZE_MAX && !share_corner(&m, r.first[0], r.first[1]),
            "folded lattice %dD: %s (%s), degree %d, %zu overlaps (at least %zu)", dim,
            ss_verdict_name(r.verdict.verdict), r.verdict.reason, r.degree, r.overlaps,
            folded);
      printf("folded lattice %dD: %s\n", dim, r.verdict.reason);
    }
    net_free(&m);
  }
}

/* ---- bad input ---- */

static void expect_input_error(const char *what, const net *m, size_t centre,
                               const char *phrase) {
  ss_injectivity r;
  ss_error err = {0};
  const ss_status st = inject(m, centre, &r, &err);
  CHECK(st == SS_EINPUT && err.msg[0] && strstr(err.msg, phrase) &&
            r.verdict.verdict != SS_PASS,
        "%s: status %d, message '%s' (want '%s')", what, (int)st, err.msg, phrase);
}

/* The cheap test before do_intersect (ss_inject_cgal_meet): it may leave a
 * pair open, but what it answers must be do_intersect's answer.  On a grid of
 * 4 (3D) or 5 (2D) values per coordinate, closed simplices touch at corners,
 * edges and facets and points are coplanar (collinear) all the time: exactly
 * the ties a filter without exact predicates would get wrong. */
static void test_quick_meet(void) {
  uint64_t seed = 20;
  for (int dim = 2; dim <= 3; dim++)
    for (int grid = 0; grid < 2; grid++) {
      const int m = dim + 1;
      long asked = 0, apart = 0, meet = 0, open = 0, wrong = 0, touching = 0;
      for (int t = 0; t < 20000; t++) {
        double a[12], b[12];
        for (int j = 0; j < m * dim; j++) {
          const double u = rnd(&seed), v = rnd(&seed);
          a[j] = grid ? floor(2.5 * (u + 1.0)) : u;
          b[j] = grid ? floor(2.5 * (v + 1.0)) : v + 0.8;
        }
        ss_error err = {0};
        int quick, exact;
        if (ss_inject_cgal_meet(dim, a, b, &quick, &exact, &err)) {
          CHECK(0, "ss_inject_cgal_meet: %s", err.msg);
          return;
        }
        if (quick == -2) continue; /* a flat simplex: not asked */
        asked++;
        apart += quick == 0;
        meet += quick == 1;
        open += quick == -1;
        wrong += quick >= 0 && quick != exact;
        touching += grid && exact && quick == -1;
      }
      CHECK(wrong == 0,
            "%dD %s: the cheap test contradicts do_intersect on %ld of %ld pairs", dim,
            grid ? "grid" : "random", wrong, asked);
      CHECK(
          asked > 5000 && apart > 0 && meet > 0 && open > 0,
          "%dD %s: %ld pairs asked, %ld apart, %ld meet, %ld left open: a branch untried",
          dim, grid ? "grid" : "random", asked, apart, meet, open);
      if (grid)
        CHECK(touching > 0, "%dD grid: no pair left open that meets (touching)", dim);
    }
}

static void test_bad_input(void) {
  net m = lattice(3, 1); /* 8 hexes, 27 points */
  {
    ss_injectivity r;
    ss_error err = {0};
    CHECK(inject(&m, 0, &r, &err) == SS_OK && r.verdict.verdict == SS_PASS, "8 cubes: %s",
          err.msg);
  }
  m.corner[3 * SS_MAXCELLVERTS + 5] = 27;
  expect_input_error("corner out of range", &m, 0, "out of range");
  m.corner[3 * SS_MAXCELLVERTS + 5] = m.corner[3 * SS_MAXCELLVERTS + 4];
  expect_input_error("repeated corner", &m, 0, "both point");
  net_free(&m);
  m = lattice(3, 1);
  m.ctype[2] = SS_QUAD;
  expect_input_error("a quad among hexes", &m, 0, "mixed dimension");
  m.ctype[2] = SS_TET;
  expect_input_error("a tet among hexes", &m, 0, "mixed with");
  m.ctype[2] = SS_HEX;
  expect_input_error("centre out of range", &m, 27, "out of range");
  m.x[3 * 5 + 1] = NAN;
  expect_input_error("NaN", &m, 0, "not finite");
  m.x[3 * 5 + 1] = 0.0;
  /* one cell listed twice: its faces in two cells run the same way; thrice */
  for (size_t c = 1; c < 3; c++)
    memcpy(m.corner + c * SS_MAXCELLVERTS, m.corner, SS_MAXCELLVERTS * sizeof *m.corner);
  expect_input_error("a cell twice", &(net){3, 27, m.x, 2, m.ctype, m.corner}, 0,
                     "the same way");
  expect_input_error("a cell thrice", &(net){3, 27, m.x, 3, m.ctype, m.corner}, 0,
                     "belongs to 3 cells");
  net_free(&m);
  m = lattice(2, 1);
  expect_input_error("a 2D net read as 3D", &(net){3, 6, m.x, 4, m.ctype, m.corner}, 0,
                     "mixed dimension");
  expect_input_error("4 coordinates", &(net){4, 6, m.x, 4, m.ctype, m.corner}, 0,
                     "not 2 or 3");
  expect_input_error("no cells", &(net){2, 9, m.x, 0, m.ctype, m.corner}, 0, "no cells");
  /* a cell turned over: its edges run the same way as its neighbours' */
  size_t *v = m.corner + 1 * SS_MAXCELLVERTS, t = v[1];
  v[1] = v[3], v[3] = t;
  expect_input_error("a quad turned over", &m, 0, "not consistently ordered");
  net_free(&m);
}

/* ---- timing ---- */

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void time_case(const char *what, const ss_link *l) {
  ss_testcase res;
  if (ss_testcase_run("mlca", (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, &res))
    return;
  const ss_charmap *cm = res.cm;
  ss_injectivity r;
  ss_error err = {0};
  const int reps = 5;
  double best = INFINITY;
  for (int i = 0; i < reps; i++) {
    const double t0 = now();
    const ss_status st = ss_inject_test(cm->x, cm->dim, cm->n, cm->ctype, cm->corner,
                                        cm->ncells, 0, &r, &err);
    const double t = now() - t0;
    CHECK(st == SS_OK && r.verdict.verdict == SS_PASS, "%s: %s %s", what, err.msg,
          r.verdict.reason);
    best = fmin(best, t);
  }
  printf("time: %s: %zu hexes, %zu points, %zu boundary faces: %.1f ms (best of %d)\n",
         what, cm->ncells, cm->n, r.boundary, 1e3 * best, reps);
  ss_testcase_free(&res);
}

static void test_timing(void) {
  /* k = 10, icosahedron-like: the gyroelongated square bipyramid (poles 8,
   * 9 of degree 4, two squares 0..3 and 4..7 of degree 5) */
  int t[16 * 3], nt = 0;
  for (int i = 0; i < 4; i++) {
    const int u0 = i, u1 = (i + 1) % 4, l0 = 4 + i, l1 = 4 + (i + 1) % 4;
    const int f[4][3] = {{8, u0, u1}, {u0, l0, u1}, {u1, l0, l1}, {9, l1, l0}};
    memcpy(t + 3 * nt, f, sizeof f);
    nt += 4;
  }
  ss_link *l = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_link_from_triangles(10, nt, t, &l, &err), &err);
  time_case("mlca k = 10 (gyroelongated square bipyramid)", l);
  ss_link_free(l);
  REQUIRE_OK_VOID(ss_link_named("icosahedron", &l, &err), &err);
  time_case("mlca k = 12 (icosahedron)", l);
  ss_link_free(l);
}

int main(void) {
  test_single_cells();
  test_random_degree();
  test_charmaps();
  test_degree_two();
  test_moved();
  test_folded();
  test_quick_meet();
  test_bad_input();
  test_timing();
  return ss_test_done("inject");
}
