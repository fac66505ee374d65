/* test_limit_fuzz.c [SEED [POINTS]] — a seeded, bounded fuzzer of the limit
 * evaluator's parameters (issue 35): on the icosahedron star, an edge of
 * valence 5 and a jittered grid, for mlca and ccsolid, POINTS (default 3000)
 * points per mesh and scheme drawn from what breaks floating point -- 0, 1,
 * 1/2, the smallest subnormal, 2^-k for every k up to 1074, 1 - 2^-k,
 * random dyadics, random doubles, their neighbours -- and from what must be
 * refused: negative zero's neighbour below, 1 + ulp, NaN, infinities,
 * unknown cells.  Every evaluation, with and without derivatives, either
 * succeeds with every number finite, or fails with SS_EINPUT (parameter or
 * cell out of range: the CLI's exit 2) or SS_ENUMERIC (a fixed point whose
 * Jacobian is not defined) and a reason; never another status, never an
 * empty message.  Longer runs: `test_limit_fuzz SEED 100000`. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testmesh.h"

/* xorshift64*: the sequence depends on the seed only. */
static uint64_t next(uint64_t *s) {
  *s ^= *s >> 12;
  *s ^= *s << 25;
  *s ^= *s >> 27;
  return *s * 2685821657736338717ull;
}

static double uniform(uint64_t *s) {
  return (double)(next(s) >> 11) * 0x1p-53;
}

/* A hostile parameter; *bad set when it lies outside [0, 1] or is NaN. */
static double draw(uint64_t *s, int *bad) {
  unsigned kind = (unsigned)(next(s) % 16);
  int k = (int)(next(s) % 1075);
  double x;
  switch (kind) {
  case 0:
    x = 0.0;
    break;
  case 1:
    x = 1.0;
    break;
  case 2:
    x = 0.5;
    break;
  case 3:
    x = 0x1p-1074;
    break;
  case 4:
    x = ldexp(1.0, -k);
    break;
  case 5:
    x = 1.0 - ldexp(1.0, -(k % 54));
    break;
  case 6:
    x = ldexp(uniform(s), -k);
    break;
  case 7:
    x = ldexp((double)(next(s) % 64), -(int)(next(s) % 8));
    break;
  case 8:
    x = nextafter(ldexp(1.0, -(k % 8)), 0.0);
    break;
  case 9:
    x = nextafter(ldexp(1.0, -(k % 8)), 2.0);
    break;
  case 10: /* out of range, now and then */
    switch (next(s) % 5) {
    case 0:
      x = nextafter(1.0, 2.0);
      break;
    case 1:
      x = -0x1p-1074;
      break;
    case 2:
      x = NAN;
      break;
    case 3:
      x = INFINITY;
      break;
    default:
      x = -INFINITY;
      break;
    }
    break;
  case 11:
    x = -0.0;
    break;
  default:
    x = uniform(s);
    break;
  }
  *bad |= !(x >= 0.0 && x <= 1.0);
  return x;
}

static void fuzz(ss_scheme *s, const ss_cx *m, const char *what, uint64_t seed, long n) {
  ss_error err = {0};
  ss_limit *L;
  REQUIRE_OK_VOID(ss_limit_new(s, m, &L, &err), &err);
  const size_t nc = ss_limit_ncells(L);
  long ok = 0, input = 0, numeric = 0, wrong = 0;
  for (long i = 0; i < n; i++) {
    int bad = 0, bad_cell = next(&seed) % 50 == 0;
    size_t c = bad_cell ? nc + (size_t)(next(&seed) % 3) : (size_t)(next(&seed) % nc);
    double x[3];
    for (int a = 0; a < 3; a++)
      x[a] = draw(&seed, &bad);
    int derivs = (int)(next(&seed) & 1u);
    ss_limit_point p;
    err.msg[0] = '\0';
    ss_status st = ss_limit_eval(L, c, x[0], x[1], x[2], derivs, &p, &err);
    if (st == SS_OK) {
      int fin = 1;
      for (int d = 0; d < 3; d++) {
        fin &= isfinite(p.p[d]) != 0;
        for (int a = 0; a < 3 && derivs; a++)
          fin &= isfinite(p.jac[a][d]) != 0;
      }
      ok++;
      if (!fin || bad || bad_cell) {
        if (wrong++ < 5)
          CHECK(0, "%s: cell %zu at (%.17g %.17g %.17g)%s: %s", what, c + 1, x[0], x[1],
                x[2], derivs ? " with derivatives" : "",
                fin ? "accepted out of range" : "a non-finite number");
      }
    } else if (st == SS_EINPUT && (bad || bad_cell) && err.msg[0]) {
      input++;
    } else if (st == SS_ENUMERIC && !bad && !bad_cell && err.msg[0]) {
      numeric++;
    } else if (wrong++ < 5) {
      CHECK(0, "%s: cell %zu at (%.17g %.17g %.17g): status %d (%s)", what, c + 1, x[0],
            x[1], x[2], (int)st, err.msg);
    }
  }
  CHECK(wrong == 0, "%s: %ld points wrong", what, wrong);
  printf("%s: %ld points: %ld evaluated (all finite), %ld refused as input, %ld as "
         "undefined Jacobians\n",
         what, n, ok, input, numeric);
  ss_limit_free(L);
}

int main(int argc, char **argv) {
  uint64_t seed = argc > 1 ? strtoull(argv[1], NULL, 10) : 35;
  long n = argc > 2 ? strtol(argv[2], NULL, 10) : 3000;
  if (!seed) seed = 35;
  tm_link *l = tm_link_named("icosahedron");
  ss_cx *meshes[3] = {tm_hex_star(l), tm_edge_ring(5, 1, 3), tm_hex_grid(3, 3, 3)};
  tm_jitter(meshes[0], 0.05, 5);
  tm_jitter(meshes[2], 0.1, 7);
  const char *mname[3] = {"icosahedron star", "edge of valence 5", "grid"};
  const char *sname[2] = {"mlca", "ccsolid"};
  for (int i = 0; i < 2; i++) {
    ss_error err = {0};
    ss_scheme *s;
    REQUIRE_OK(ss_scheme_new(sname[i], &s, &err), &err);
    for (int k = 0; k < 3; k++) {
      char what[96];
      snprintf(what, sizeof what, "%s, %s (seed %llu)", sname[i], mname[k],
               (unsigned long long)seed);
      fuzz(s, meshes[k], what, seed + (uint64_t)(3 * i + k), n);
    }
    ss_scheme_free(s);
  }
  for (int k = 0; k < 3; k++)
    ss_cx_free(meshes[k]);
  tm_link_free(l);
  return ss_test_done("limit_fuzz");
}
