/* test_random.c — random links from convex hulls of sphere points: every
 * sample is a valid link with k vertices, 2k - 4 triangles, 6k - 12
 * half-edges and degrees >= 3; a seed reproduces its links exactly and
 * different seeds give different links; the hull shim orients its triangles
 * outward, finds the octahedron, and rejects degenerate point sets (too few,
 * not finite, repeated, coplanar, collinear, a point inside, four points on a
 * facet) with SS_EINPUT; ss_link_random gives up with SS_ENUMERIC when every
 * draw is degenerate. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>

#include "ss_hull.h"
#include "ss_link.h"
#include "ss_link_random.h"
#include "ss_test.h"

static void check_link(const ss_link *l, int k, unsigned long seed) {
  ss_error err = {0};
  CHECK(ss_link_validate(l, &err) == SS_OK, "k=%d seed=%lu: %s", k, seed, err.msg);
  CHECK(l->k == k, "k=%d seed=%lu: %d vertices", k, seed, l->k);
  CHECK(l->off[l->k] == 6 * k - 12, "k=%d seed=%lu: %d half-edges, not %d", k, seed,
        l->off[l->k], 6 * k - 12);
  int mindeg = k;
  for (int v = 0; v < l->k; v++)
    if (ss_link_deg(l, v) < mindeg) mindeg = ss_link_deg(l, v);
  CHECK(mindeg >= 3, "k=%d seed=%lu: a vertex of degree %d", k, seed, mindeg);
  int *tri = NULL, ntri = 0;
  if (ss_link_triangles(l, &tri, &ntri, &err) == SS_OK)
    CHECK(ntri == 2 * k - 4, "k=%d seed=%lu: %d triangles, not %d", k, seed, ntri,
          2 * k - 4);
  else
    CHECK(0, "ss_link_triangles: %s", err.msg);
  free(tri);
}

/* A sample from a freshly seeded generator (the sample-th one); NULL after a
 * failed check. */
static ss_link *sample(int k, unsigned long seed, int nth) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  ss_link *l = NULL;
  ss_error err = {0};
  gsl_rng_set(r, seed);
  for (int i = 0; i <= nth; i++) {
    ss_link_free(l);
    l = NULL;
    ss_status st = ss_link_random(k, r, &l, &err);
    CHECK(st == SS_OK, "ss_link_random(%d, seed %lu): %s", k, seed, err.msg);
    if (st) break;
  }
  gsl_rng_free(r);
  return l;
}

static void test_random_links(void) {
  static const int ks[] = {4, 5, 6, 10, 50, 200};
  static const unsigned long seeds[] = {1, 2, 7, 12345, 4294967295UL};
  const int nk = (int)(sizeof ks / sizeof ks[0]),
            ns = (int)(sizeof seeds / sizeof seeds[0]);
  for (int a = 0; a < nk; a++) {
    int k = ks[a];
    ss_link *first[sizeof seeds / sizeof seeds[0]] = {NULL};
    for (int b = 0; b < ns; b++) {
      /* several samples from one stream: all valid */
      gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
      gsl_rng_set(r, seeds[b]);
      for (int i = 0; i < 5; i++) {
        ss_link *l = NULL;
        ss_error err = {0};
        ss_status st = ss_link_random(k, r, &l, &err);
        CHECK(st == SS_OK, "k=%d seed=%lu sample %d: %s", k, seeds[b], i, err.msg);
        if (st == SS_OK) check_link(l, k, seeds[b]);
        if (i == 0)
          first[b] = l;
        else
          ss_link_free(l);
      }
      gsl_rng_free(r);
      /* same seed, same links */
      ss_link *again = sample(k, seeds[b], 0), *third = sample(k, seeds[b], 2);
      CHECK(first[b] && again && ss_link_equal(first[b], again),
            "k=%d seed=%lu: not reproduced", k, seeds[b]);
      ss_link *third2 = sample(k, seeds[b], 2);
      CHECK(third && third2 && ss_link_equal(third, third2),
            "k=%d seed=%lu: third sample not reproduced", k, seeds[b]);
      ss_link_free(again);
      ss_link_free(third);
      ss_link_free(third2);
    }
    /* different seeds, different links (k >= 10: a coincidence has
     * probability far below 1e-6) */
    if (k >= 10)
      for (int b = 0; b < ns; b++)
        for (int b2 = b + 1; b2 < ns; b2++)
          CHECK(first[b] && first[b2] && !ss_link_equal(first[b], first[b2]),
                "k=%d: seeds %lu and %lu give the same link", k, seeds[b], seeds[b2]);
    for (int b = 0; b < ns; b++)
      ss_link_free(first[b]);
  }
  /* bad arguments */
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  ss_link *l = (ss_link *)&r; /* must be reset to NULL */
  ss_error err = {0};
  CHECK(ss_link_random(3, r, &l, &err) == SS_EINPUT && !l, "k = 3 accepted");
  CHECK(ss_link_random(SS_LINK_MAXK + 1, r, &l, &err) == SS_EINPUT && !l,
        "k too large accepted");
  CHECK(ss_link_random(10, NULL, &l, &err) == SS_EINPUT && !l, "no generator accepted");
  gsl_rng_free(r);
}

/* A "generator" that always returns 1/4: every point it gives is the same,
 * so every hull is degenerate and ss_link_random must give up. */
static void const_set(void *state, unsigned long seed) {
  (void)state, (void)seed;
}
static unsigned long const_get(void *state) {
  (void)state;
  return 1UL << 30;
}
static double const_get_double(void *state) {
  (void)state;
  return 0.25;
}
static const gsl_rng_type const_type = {
    "constant", 1UL << 32, 0, sizeof(int), const_set, const_get, const_get_double};

static void test_give_up(void) {
  gsl_rng *r = gsl_rng_alloc(&const_type);
  ss_link *l = NULL;
  ss_error err = {0};
  ss_status st = ss_link_random(8, r, &l, &err);
  CHECK(st == SS_ENUMERIC && !l, "constant points: status %d (%s)", (int)st, err.msg);
  gsl_rng_free(r);
}

/* Every triangle of a hull of sphere points (containing the origin) runs
 * counterclockwise seen from outside: det(a, b, c) > 0. */
static void check_outward(int n, const double *p, const int *tri, int ntri) {
  int bad = 0;
  for (int t = 0; t < ntri; t++) {
    const double *a = p + 3 * tri[3 * t], *b = p + 3 * tri[3 * t + 1],
                 *c = p + 3 * tri[3 * t + 2];
    double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0]);
    if (!(det > 0)) bad++;
    if (!(tri[3 * t] < tri[3 * t + 1] && tri[3 * t] < tri[3 * t + 2])) bad++;
    if (t > 0) {
      const int *u = tri + 3 * (t - 1), *v = tri + 3 * t;
      if (!(u[0] < v[0] ||
            (u[0] == v[0] && (u[1] < v[1] || (u[1] == v[1] && u[2] < v[2])))))
        bad++;
    }
  }
  CHECK(bad == 0,
        "n=%d: %d triangles inward, not starting at their least index or "
        "out of order",
        n, bad);
}

static void test_hull(void) {
  ss_error err = {0};
  int *tri = NULL, ntri = 0;
  /* the octahedron */
  static const double oct[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  CHECK(ss_hull_sphere_triangles(6, oct, &tri, &ntri, &err) == SS_OK, "octahedron: %s",
        err.msg);
  CHECK(ntri == 8, "octahedron: %d triangles", ntri);
  if (tri && ntri == 8) {
    check_outward(6, oct, tri, ntri);
    ss_link *l = NULL, *o = NULL;
    if (ss_link_from_triangles(6, ntri, tri, &l, &err) == SS_OK &&
        ss_link_named("octahedron", &o, &err) == SS_OK)
      CHECK(ss_link_isomorphic(l, o) == 1, "octahedron hull is not the octahedron");
    else
      CHECK(0, "octahedron link: %s", err.msg);
    ss_link_free(l);
    ss_link_free(o);
  }
  free(tri);

  /* random points: outward and sorted */
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 3);
  enum { N = 300 };
  double *p = malloc(3 * N * sizeof *p);
  for (int i = 0; i < 3 * N; i++)
    p[i] = gsl_rng_uniform(r) - 0.5;
  for (int i = 0; i < N; i++) {
    double s = sqrt(p[3 * i] * p[3 * i] + p[3 * i + 1] * p[3 * i + 1] +
                    p[3 * i + 2] * p[3 * i + 2]);
    for (int j = 0; j < 3; j++)
      p[3 * i + j] /= s;
  }
  tri = NULL;
  CHECK(ss_hull_sphere_triangles(N, p, &tri, &ntri, &err) == SS_OK, "random: %s",
        err.msg);
  if (tri) check_outward(N, p, tri, ntri);
  free(tri);

  /* degenerate inputs: SS_EINPUT, *tri NULL, *ntri 0 */
  struct {
    const char *what;
    int n;
    double p[3 * 9];
  } bad[] = {
      {"three points", 3, {1, 0, 0, 0, 1, 0, 0, 0, 1}},
      {"coplanar", 5, {1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0, 0.5, 0.5, 0}},
      {"collinear", 4, {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3}},
      {"repeated point", 5, {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0}},
      {"point inside", 5, {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.1, 0.1}},
      {"point on an edge", 5, {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0.5, 0.5, 0}},
      {"four on a facet (cube)", 8, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0,
                                     0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1}},
      {"not finite", 4, {1, 0, 0, 0, 1, 0, 0, 0, 1, (double)NAN, 0, 0}},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    tri = (int *)&err; /* must be reset */
    ntri = -1;
    ss_error e = {0};
    ss_status st = ss_hull_sphere_triangles(bad[i].n, bad[i].p, &tri, &ntri, &e);
    CHECK(st == SS_EINPUT && !tri && ntri == 0 && e.msg[0], "%s: status %d (%s)",
          bad[i].what, (int)st, e.msg);
  }
  free(p);
  gsl_rng_free(r);
}

int main(void) {
  gsl_set_error_handler_off();
  test_hull();
  test_random_links();
  test_give_up();
  return ss_test_done("random");
}
