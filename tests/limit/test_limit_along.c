/* test_limit_along.c — the derivative along an extraordinary edge, very near
 * it (issue 35 item 3), for MLCA (eq. (1)'s jump) and ccsolid (the
 * differences across the plane carried apart, ss_limit_along.c):
 *   - 5 wedges x 3 layers, straight along z with layers at z = 0..3, at
 *     (d, d, 1/2) and (d, 0, 1/2) of a middle-layer cell, d = 2^-k for k = 1
 *     .. 1074: the along row is (0, 0, 1) to 1e-14.  Why exactly: the mesh
 *     is its own mirror image in z = 3/2 (the point's plane), so x and y are
 *     even in w - 1/2 there and their derivatives 0; and the rules, symmetric
 *     above and below, map the layer function z = k to itself refined (a
 *     vertex of layer k to k, an edge point between layers to k + 1/2), so
 *     the limit's z is the B-spline of a linear function along w: w + 1.
 *     Before, the row read up to 1e27 at 1e-300;
 *   - the same ring jittered (no symmetry, an along row of its own): against
 *     the reference (repeated local subdivision, no eigenvectors) for k = 4 ..
 *     55, to 1e-12 of the row; and for k = 60 .. 1000 against the edge
 *     model's a' (the derivative along the edge on it, from the run's
 *     eigenvalue-1/2 part: ss_limit_edge.h), the limit the row tends to as
 *     mu^k (mu the across eigenvalue, the odd modes' largest decaying rate)
 *     -- below 1e-14 from k = 60 on; the reference and the model are
 *     computed without the carried differences;
 *   - on the mesh's bottom boundary (the plane w = 0 of a first-layer cell,
 *     no mirror image there): every answer finite; either the along row
 *     agrees with the one at 2^-40 (the row converges there as the interior
 *     one does) to 1e-8, or the point is refused (SS_ENUMERIC) -- and it is
 *     refused at 2^-1000, where the net's rounding grown by (2 mu)^1000 is
 *     all the row would hold. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ss_limit.h"
#include "ss_limit_edge.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testmesh.h"

static int all_finite(const ss_limit_point *p) {
  for (int d = 0; d < 3; d++) {
    if (!isfinite(p->p[d])) return 0;
    for (int i = 0; i < 3; i++)
      if (!isfinite(p->jac[i][d])) return 0;
  }
  return 1;
}

static double row_off(const double r[3], const double want[3]) {
  double m = 0.0;
  for (int d = 0; d < 3; d++)
    m = fmax(m, fabs(r[d] - want[d]));
  return m;
}

static double row_norm(const double r[3]) {
  return fmax(fabs(r[0]), fmax(fabs(r[1]), fabs(r[2])));
}

/* Straight ring: the along row (0, 0, 1) at (d, d, 1/2) and (d, 0, 1/2). */
static void test_straight(ss_scheme *s, const char *name) {
  ss_error err = {0};
  ss_cx *e = tm_edge_ring(5, 1, 3);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, e, &L, &err), &err);
  const double one[3] = {0, 0, 1};
  double worst = 0.0;
  int bad = 0;
  for (int k = 1; k <= 1074; k++) {
    const double d = ldexp(1.0, -k);
    for (int q = 0; q < 2; q++) {
      ss_limit_point p;
      if (ss_limit_eval(L, 5, d, q ? 0.0 : d, 0.5, 1, &p, &err)) {
        CHECK(0, "%s straight ring at d = 2^-%d: %s", name, k, err.msg);
        continue;
      }
      CHECK(all_finite(&p), "%s straight ring at d = 2^-%d: not finite", name, k);
      const double off = row_off(p.jac[2], one);
      worst = fmax(worst, off);
      if (!(off <= 1e-14) && bad++ < 5)
        CHECK(0, "%s straight ring at (2^-%d, %s, 1/2): along row (%.17g, %.17g, %.17g)",
              name, k, q ? "0" : "d", p.jac[2][0], p.jac[2][1], p.jac[2][2]);
    }
  }
  CHECK(bad == 0, "%s straight ring: the along row off (0, 0, 1) at %d points", name,
        bad);
  printf("%s straight ring: along row off (0, 0, 1) by at most %.2g (d = 2^-1 .. "
         "2^-1074)\n",
         name, worst);
  ss_limit_free(L);
  ss_cx_free(e);
}

/* Jittered ring: against the reference, then against the edge model. */
static void test_jittered(ss_scheme *s, const char *name) {
  ss_error err = {0};
  ss_cx *e = tm_edge_ring(5, 1, 3);
  tm_jitter(e, 0.05, 7);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, e, &L, &err), &err);
  double worst = 0.0;
  for (int k = 4; k <= 55; k++) {
    const double d = ldexp(1.0, -k), w = 0.5 + ldexp(1.0, -3);
    for (int q = 0; q < 2; q++) {
      const double x[3] = {d, q ? 0.3 * d : d, q ? w : 0.5};
      ss_limit_point a, b;
      if (ss_limit_eval(L, 5, x[0], x[1], x[2], 1, &a, &err) ||
          ss_limit_eval_reference(L, 5, x[0], x[1], x[2], 1, 80, &b, &err)) {
        CHECK(0, "%s jittered ring at 2^-%d: %s", name, k, err.msg);
        continue;
      }
      const double rel = row_off(a.jac[2], b.jac[2]) / row_norm(b.jac[2]);
      worst = fmax(worst, rel);
      CHECK(rel <= 1e-12,
            "%s jittered ring at (%g, %g, %g): along row off the reference by %g of it "
            "(%.17g vs %.17g)",
            name, x[0], x[1], x[2], rel, a.jac[2][2], b.jac[2][2]);
    }
  }
  printf("%s jittered ring: along row against the reference, d = 2^-4 .. 2^-55: worst "
         "%.2g of the row\n",
         name, worst);
  ss_limit_edge m;
  const double on[3] = {0, 0, 0.5}, probe[3] = {0x1p-12, 0x1p-12, 0.5};
  REQUIRE_OK_VOID(ss_limit_edge_model(L, 5, on, 2, probe, &m, &err), &err);
  worst = 0.0;
  for (int k = 60; k <= 1000; k++) {
    const double d = ldexp(1.0, -k);
    for (int q = 0; q < 2; q++) {
      ss_limit_point a;
      if (ss_limit_eval(L, 5, d, q ? 0.0 : 0.7 * d, 0.5, 1, &a, &err)) {
        CHECK(0, "%s jittered ring at 2^-%d: %s", name, k, err.msg);
        continue;
      }
      CHECK(all_finite(&a), "%s jittered ring at 2^-%d: not finite", name, k);
      const double rel = row_off(a.jac[2], m.da) / row_norm(m.da);
      worst = fmax(worst, rel);
      CHECK(rel <= 1e-13,
            "%s jittered ring at 2^-%d: along row off the edge's a' by %g of it "
            "(%.17g vs %.17g)",
            name, k, rel, a.jac[2][2], m.da[2]);
    }
  }
  printf("%s jittered ring: along row against the edge's a', d = 2^-60 .. 2^-1000: "
         "worst %.2g of it\n",
         name, worst);
  ss_limit_free(L);
  ss_cx_free(e);
}

/* The bottom boundary: finite and right, or refused; refused at 2^-1000. */
static void test_boundary(ss_scheme *s, const char *name) {
  ss_error err = {0};
  ss_cx *e = tm_edge_ring(5, 1, 3);
  tm_jitter(e, 0.05, 7);
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, e, &L, &err), &err);
  ss_limit_point ref;
  REQUIRE_OK_VOID(ss_limit_eval(L, 0, 0x1p-40, 0x1p-40, 0.0, 1, &ref, &err), &err);
  int answered = 0, refused = 0;
  for (int k = 41; k <= 1000; k++) {
    const double d = ldexp(1.0, -k);
    ss_limit_point p;
    ss_status st = ss_limit_eval(L, 0, d, d, 0.0, 1, &p, &err);
    if (st) {
      CHECK(st == SS_ENUMERIC && strstr(err.msg, "cannot be trusted"),
            "%s boundary at 2^-%d: %s", name, k, err.msg);
      refused++;
      continue;
    }
    answered++;
    CHECK(all_finite(&p), "%s boundary at 2^-%d: not finite", name, k);
    const double off = row_off(p.jac[2], ref.jac[2]);
    CHECK(off <= 1e-8 * fmax(1.0, row_norm(ref.jac[2])),
          "%s boundary at 2^-%d: along row off the one at 2^-40 by %g", name, k, off);
    CHECK(k < 1000, "%s boundary at 2^-1000: answered, not refused", name);
  }
  printf("%s boundary: %d depths answered (the row right to 1e-8), %d refused\n", name,
         answered, refused);
  ss_limit_free(L);
  ss_cx_free(e);
}

int main(void) {
  const char *names[2] = {"mlca", "ccsolid"};
  for (int i = 0; i < 2; i++) {
    ss_error err = {0};
    ss_scheme *s;
    REQUIRE_OK(ss_scheme_new(names[i], &s, &err), &err);
    test_straight(s, names[i]);
    test_jittered(s, names[i]);
    test_boundary(s, names[i]);
    ss_scheme_free(s);
  }
  return ss_test_done("limit_along");
}
