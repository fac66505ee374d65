/* test_limit_tensor.c — limit evaluation near extraordinary edges under
 * ccsolid-tensor (issue 39): its vertex points on the edge are the tensor
 * product's, so the edge's stationary halves factor as A_b (x) T and the
 * evaluator takes the paper's eq. (1) (ss_limit_set_tensor): a bounded
 * number of matrix products per point however near the edge, where
 * Joy-MacCracken's ccsolid walks the point's binary digits (products growing
 * with -log2 of the distance).  On jittered rings of valence 3, 5 and 6, at
 * (2^-k 0.75, 2^-k 0.7, 0.3) of a cell at the edge, k = 1..52, and on it:
 *   - eq. (1) taken (ss_limit_stats.tensor >= 1) and at most 8 products per
 *     point (MLCA's bound in test_limit); ccsolid never factors;
 *   - eq. (1) on and off (the generic digit walk, no factoring used) agree
 *     to 1e-13 in the point and 1e-10 in the Jacobian;
 *   - against repeated local subdivision (the reference: no eigenvectors,
 *     no factoring) at k = 2, 5, 9 to 1e-12;
 *   - ccsolid needs more products than the variant at some k (the contrast
 *     bench_limit measures). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ss_limit.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testmesh.h"

#define KMAX 52

static double dist3(const double *a, const double *b) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

/* The point of depth k (k = 0: on the edge). */
static void point_at(int k, double x[3]) {
  x[0] = k ? ldexp(0.75, -k) : 0.0;
  x[1] = k ? ldexp(0.7, -k) : 0.0;
  x[2] = 0.3;
}

/* Products per point at depths 0..KMAX under scheme name (eq. (1) on) into
 * prod; the checks above for the variant.  Returns the largest. */
static int run(const char *name, int n, int *prod) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  REQUIRE_OK(ss_scheme_new(name, &s, &err), &err);
  ss_cx *e = tm_edge_ring(n, 3, 6);
  tm_jitter(e, 0.05, 3);
  const size_t cell = (size_t)((3 * n + 0) * 3 + 0) * 3 + 0; /* at the edge */
  ss_limit *A = NULL, *B = NULL;
  REQUIRE_OK(ss_limit_new(s, e, &A, &err), &err);
  REQUIRE_OK(ss_limit_new(s, e, &B, &err), &err);
  ss_limit_set_tensor(B, 0);
  const int tensor = !strcmp(name, "ccsolid-tensor");
  int most = 0;
  double dp = 0.0, dj = 0.0, dref = 0.0;
  for (int k = 0; k <= KMAX; k++) {
    double x[3];
    point_at(k, x);
    const int der = k > 0; /* on the edge: the point only */
    ss_limit_point a, b;
    REQUIRE_OK(ss_limit_eval(A, cell, x[0], x[1], x[2], der, &a, &err), &err);
    prod[k] = a.products;
    most = a.products > most ? a.products : most;
    if (!tensor) continue;
    REQUIRE_OK(ss_limit_eval(B, cell, x[0], x[1], x[2], der, &b, &err), &err);
    dp = fmax(dp, dist3(a.p, b.p));
    for (int i = 0; der && i < 3; i++)
      for (int d = 0; d < 3; d++)
        dj = fmax(dj, fabs(a.jac[i][d] - b.jac[i][d]) / fmax(1.0, fabs(b.jac[i][d])));
    if (k == 2 || k == 5 || k == 9) {
      REQUIRE_OK(ss_limit_eval_reference(B, cell, x[0], x[1], x[2], 0, 60, &b, &err),
                 &err);
      dref = fmax(dref, dist3(a.p, b.p));
    }
  }
  const ss_limit_stats st = ss_limit_get_stats(A);
  if (tensor) {
    CHECK(st.tensor >= 1 && most <= 8,
          "%s, edge %d: eq. (1) should apply in O(1): %zu factoring patches, at most %d "
          "products",
          name, n, st.tensor, most);
    CHECK(dp <= 1e-13 && dj <= 1e-10,
          "%s, edge %d: eq. (1) on and off differ by %g (point), %g (Jacobian)", name, n,
          dp, dj);
    CHECK(dref <= 1e-12, "%s, edge %d: eq. (1) and the reference differ by %g", name, n,
          dref);
    printf("%s, edge %d: eq. (1) %s; on/off %.1e (point) %.1e (Jacobian), "
           "reference %.1e\n",
           name, n, st.tensor ? "applies" : "does not apply", dp, dj, dref);
  } else {
    CHECK(st.tensor == 0, "%s, edge %d: a Joy-MacCracken edge factored", name, n);
  }
  ss_limit_free(A);
  ss_limit_free(B);
  ss_cx_free(e);
  ss_scheme_free(s);
  return most;
}

int main(void) {
  const int ns[3] = {3, 5, 6};
  for (int i = 0; i < 3; i++) {
    int pt[KMAX + 1], pc[KMAX + 1];
    const int mt = run("ccsolid-tensor", ns[i], pt);
    const int mc = run("ccsolid", ns[i], pc);
    CHECK(mc > mt, "edge %d: ccsolid needs no more products (%d) than the variant (%d)",
          ns[i], mc, mt);
    printf("edge %d: products per point at depth k = 0, 1, 10, 20, 30, 40, 52: "
           "ccsolid-tensor %d %d %d %d %d %d %d; ccsolid %d %d %d %d %d %d %d\n",
           ns[i], pt[0], pt[1], pt[10], pt[20], pt[30], pt[40], pt[52], pc[0], pc[1],
           pc[10], pc[20], pc[30], pc[40], pc[52]);
  }
  return ss_test_done("limit_tensor");
}
