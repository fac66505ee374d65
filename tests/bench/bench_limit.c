/* bench_limit.c — limit evaluation: per point, the cached walk with
 * eigen-jumps ("direct") against repeated local subdivision of the patch
 * (the reference, the paper's alternative [BHU10]) for targets needing 1..12
 * subdivision steps, as ratios measured in one run (best of several); and
 * points per second for 3x3x3 Gauss points on a mesh of 10 000 hexahedra.
 * The paper reports direct evaluation winning beyond 2 steps.  Then ccsolid
 * and ccsolid-tensor side by side near an extraordinary edge: products and
 * time per point (the variant takes eq. (1), ccsolid walks the digits). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "ss_limit.h"
#include "ss_scheme.h"
#include "ss_testmesh.h"

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void jitter(ss_cx *cx, double amp, unsigned seed) {
  srand(seed);
  for (size_t i = 0; i < cx->nv * 3; i++)
    cx->x[i] += amp * (2.0 * rand() / RAND_MAX - 1.0);
}

/* Best time of `reps` rounds of `inner` evaluations of one point. */
static double best_time(ss_limit *L, size_t cell, const double x[3], int reference,
                        int inner, int reps, ss_limit_point *p) {
  ss_error err = {0};
  double best = INFINITY;
  for (int r = 0; r < reps; r++) {
    double t0 = now();
    for (int i = 0; i < inner; i++) {
      ss_status st =
          reference ? ss_limit_eval_reference(L, cell, x[0], x[1], x[2], 0, 60, p, &err)
                    : ss_limit_eval(L, cell, x[0], x[1], x[2], 0, p, &err);
      if (st) {
        fprintf(stderr, "bench_limit: %s\n", err.msg);
        exit(1);
      }
    }
    double t = (now() - t0) / inner;
    if (t < best) best = t;
  }
  return best;
}

/* Targets approaching the centre of the cells (corner 0) geometrically: the
 * reference needs about n steps for the n-th. */
static void per_point(const ss_scheme *s, ss_cx *m, size_t cell, const double base[3],
                      int along_w, const char *what) {
  ss_error err = {0};
  ss_limit *L;
  if (ss_limit_new(s, m, &L, &err)) {
    fprintf(stderr, "bench_limit: %s\n", err.msg);
    exit(1);
  }
  printf("\n%s (cell %zu):\n  steps  direct products  direct us  reference us  "
         "reference/direct  |difference|\n",
         what, cell + 1);
  for (int n = 1; n <= 12; n++) {
    double x[3];
    for (int a = 0; a < 3; a++)
      x[a] = along_w && a == 2 ? base[a] : ldexp(base[a], 1 - n);
    ss_limit_point d, r;
    best_time(L, cell, x, 0, 1, 1, &d); /* fill the caches first */
    double td = best_time(L, cell, x, 0, 200, 5, &d);
    double tr = best_time(L, cell, x, 1, 3, 3, &r);
    double diff = sqrt((d.p[0] - r.p[0]) * (d.p[0] - r.p[0]) +
                       (d.p[1] - r.p[1]) * (d.p[1] - r.p[1]) +
                       (d.p[2] - r.p[2]) * (d.p[2] - r.p[2]));
    printf("  %5d  %15d  %9.2f  %12.1f  %16.1f  %.1e\n", r.steps, d.products, 1e6 * td,
           1e6 * tr, tr / td, diff);
  }
  ss_limit_stats st = ss_limit_get_stats(L);
  printf("  caches: %zu patch topologies, %zu transitions, %zu eigen-solves\n", st.keys,
         st.transitions, st.eigs);
  ss_limit_free(L);
}

static int run(const char *name) {
  ss_error err = {0};
  ss_scheme *s;
  if (ss_scheme_new(name, &s, &err)) {
    fprintf(stderr, "bench_limit: %s\n", err.msg);
    return 1;
  }
  printf("\n==== scheme %s; times per point, best of several rounds\n", name);

  /* an extraordinary vertex (icosahedron link: 12 edges of valence 5 at it) */
  tm_link *l = tm_link_named("icosahedron");
  ss_cx *h = tm_hex_star(l);
  jitter(h, 0.05, 5);
  const double ev[3] = {0.75, 0.7, 0.65};
  per_point(s, h, 0, ev, 0,
            "towards the icosahedron vertex (x = 2^(1-n) (0.75, 0.7, 0.65))");
  ss_cx_free(h);
  tm_link_free(l);

  /* an extraordinary edge of valence 5, from an interior cell along it */
  ss_cx *e = tm_edge_ring(5, 4, 8);
  jitter(e, 0.05, 3);
  const double ee[3] = {0.75, 0.7, 0.3};
  per_point(s, e, (size_t)((4 * 5 + 0) * 4 + 0) * 4 + 0, ee, 1,
            "towards an edge of valence 5 (x = (2^(1-n) 0.75, 2^(1-n) 0.7, 0.3))");
  ss_cx_free(e);

  /* Gauss points on 10 000 hexahedra around an edge of valence 5 */
  ss_cx *big = tm_edge_ring(5, 10, 20);
  jitter(big, 0.05, 11);
  ss_limit *L;
  if (ss_limit_new(s, big, &L, &err)) {
    fprintf(stderr, "bench_limit: %s\n", err.msg);
    return 1;
  }
  const double g[3] = {0.5 - 0.5 * sqrt(0.6), 0.5, 0.5 + 0.5 * sqrt(0.6)};
  size_t nc = ss_limit_ncells(L);
  printf("\nGauss 3x3x3 on %zu hexahedra (%zu points, Jacobians included):\n", nc,
         nc * 27);
  for (int pass = 0; pass < 2; pass++) {
    double t0 = now();
    for (size_t c = 0; c < nc; c++)
      for (int k = 0; k < 3; k++)
        for (int j = 0; j < 3; j++)
          for (int i = 0; i < 3; i++) {
            ss_limit_point p;
            if (ss_limit_eval(L, c, g[i], g[j], g[k], 1, &p, &err)) {
              fprintf(stderr, "bench_limit: %s\n", err.msg);
              return 1;
            }
          }
    double t = now() - t0;
    printf("  %s: %.2f s, %.0f points/s\n",
           pass ? "second pass (caches warm)" : "first pass (caches filled on the way)",
           t, (double)(nc * 27) / t);
  }
  ss_limit_stats st = ss_limit_get_stats(L);
  printf("  caches: %zu patch topologies, %zu transitions, %zu eigen-solves\n", st.keys,
         st.transitions, st.eigs);
  ss_limit_free(L);
  ss_cx_free(big);
  ss_scheme_free(s);
  return 0;
}

/* ccsolid against ccsolid-tensor near an edge of valence 5, side by side:
 * products and time per point at (2^-k 0.75, 2^-k 0.7, 0.3) of a cell at the
 * edge (ccsolid walks the digits; the variant's halves factor: eq. (1)). */
static int side_by_side(void) {
  const char *names[2] = {"ccsolid", "ccsolid-tensor"};
  ss_scheme *s[2] = {NULL, NULL};
  ss_limit *L[2] = {NULL, NULL};
  ss_error err = {0};
  ss_cx *e = tm_edge_ring(5, 4, 8);
  jitter(e, 0.05, 3);
  for (int i = 0; i < 2; i++)
    if (ss_scheme_new(names[i], &s[i], &err) || ss_limit_new(s[i], e, &L[i], &err)) {
      fprintf(stderr, "bench_limit: %s\n", err.msg);
      return 1;
    }
  const size_t cell = (size_t)((4 * 5 + 0) * 4 + 0) * 4 + 0;
  printf("\n==== near an edge of valence 5, side by side (points, no Jacobian)\n"
         "   k   ccsolid products  us   ccsolid-tensor products  us   time ratio\n");
  const int ks[] = {1, 2, 5, 10, 20, 30, 40, 52};
  for (size_t q = 0; q < sizeof ks / sizeof *ks; q++) {
    const double x[3] = {ldexp(0.75, -ks[q]), ldexp(0.7, -ks[q]), 0.3};
    ss_limit_point p[2];
    double t[2];
    for (int i = 0; i < 2; i++) {
      best_time(L[i], cell, x, 0, 1, 1, &p[i]);
      t[i] = best_time(L[i], cell, x, 0, 200, 5, &p[i]);
    }
    printf("  %2d   %16d  %5.1f  %23d  %5.1f   %5.1f\n", ks[q], p[0].products, 1e6 * t[0],
           p[1].products, 1e6 * t[1], t[0] / t[1]);
  }
  for (int i = 0; i < 2; i++) {
    ss_limit_free(L[i]);
    ss_scheme_free(s[i]);
  }
  ss_cx_free(e);
  return 0;
}

int main(void) {
  return run("mlca") || run("ccsolid") || run("ccsolid-tensor") || side_by_side();
}
