/* test_charmap_push.c — the certified path's push of an interval net through
 * a ring level, ss_charmap_push_interval (midpoint-radius, ss_charmap_cert.c):
 * on the real ring levels of MLCA, tet/oct and box-spline vertices, with
 * random boxes from zero width to wide,
 *   - every exact push (the rule's rational weights, FLINT fmpq) of nets
 *     picked inside the boxes -- their ends, midpoints, mixtures -- lies in
 *     the output boxes;
 *   - the output is about as narrow as the same push in arb's di_t interval
 *     arithmetic (written here: four products a term, outward sums): at most
 *     3 times as wide plus 8 units in the last place (the a-priori rounding
 *     bound against di_t's actual roundings: up to 2.1 on point nets with
 *     cancelling sums; 1.0000 on wide boxes);
 *   - the containment has teeth: an output shrunk to its midpoint misses the
 *     exact pushes of wide boxes;
 *   - a box that is not finite gives the whole line, a weight that is not a
 *     rational of bounded denominator is refused. */
#include <flint/fmpq.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "double_interval.h"
#include "ss_charmap.h"
#include "ss_exact.h"
#include "ss_link.h"
#include "ss_local.h"
#include "ss_scheme.h"
#include "ss_test.h"
#include "ss_testq.h"

/* deterministic uniform numbers in [-1, 1) */
static double rnd(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}

/* lo <= v <= hi exactly */
static int inside(const fmpq_t v, double lo, double hi) {
  fmpq_t b;
  fmpq_init(b);
  ss_testq_set_d(b, lo);
  int ok = fmpq_cmp(b, v) <= 0;
  ss_testq_set_d(b, hi);
  ok &= fmpq_cmp(v, b) <= 0;
  fmpq_clear(b);
  return ok;
}

/* The same push in di_t: each weight's enclosure times the box, summed with
 * outward rounding (the arithmetic the certified path used before). */
static int push_di(const ss_local_ring *R, const double *plo, const double *phi, int dim,
                   long maxden, double *olo, double *ohi) {
  for (size_t i = 0; i < R->nv; i++) {
    di_t s[3] = {{0, 0}, {0, 0}, {0, 0}};
    for (size_t q = R->ptr[i]; q < R->ptr[i + 1]; q++) {
      double lo, hi;
      if (!ss_exact_rational_enclose(R->w[q], maxden, &lo, &hi)) return -1;
      const di_t w = {lo, hi};
      for (int d = 0; d < dim; d++) {
        const size_t k = R->col[q] * (size_t)dim + (size_t)d;
        const di_t p = {plo[k], phi[k]};
        s[d] = di_fast_add(s[d], di_fast_mul(w, p));
      }
    }
    for (int d = 0; d < dim; d++)
      olo[i * (size_t)dim + (size_t)d] = s[d].a,
                            ohi[i * (size_t)dim + (size_t)d] = s[d].b;
  }
  return 0;
}

typedef struct {
  long rows, outside, shrunk_out, wider;
  double worst_ratio; /* largest width / di width over rows of wide boxes */
} tally;

/* One ring level, one net of boxes of relative width `width` (0: points). */
static void push_level(const ss_local_ring *R, long maxden, double width, uint64_t *seed,
                       tally *t) {
  const int dim = 3;
  const size_t np = R->nprev * dim, no = R->nv * dim;
  double *lo = malloc(np * sizeof *lo), *hi = malloc(np * sizeof *hi),
         *y = malloc(np * sizeof *y), *olo = malloc(no * sizeof *olo),
         *ohi = malloc(no * sizeof *ohi), *dlo = malloc(no * sizeof *dlo),
         *dhi = malloc(no * sizeof *dhi);
  for (size_t k = 0; k < np; k++) {
    const double c = rnd(seed) * (k % 7 == 0 ? 1e3 : 1.0);
    lo[k] = c - width * fabs(c) * fabs(rnd(seed));
    hi[k] = c + width * fabs(c) * fabs(rnd(seed));
  }
  CHECK(ss_charmap_push_interval(R, lo, hi, dim, maxden, olo, ohi) == 0, "push refused");
  CHECK(push_di(R, lo, hi, dim, maxden, dlo, dhi) == 0, "di push refused");
  fmpq_t s, w, v;
  fmpq_init(s);
  fmpq_init(w);
  fmpq_init(v);
  for (int pick = 0; pick < 3; pick++) {
    for (size_t k = 0; k < np; k++) {
      const double r = rnd(seed);
      y[k] = pick == 0 ? lo[k] : pick == 1 ? hi[k] : r < 0 ? lo[k] : hi[k];
    }
    for (size_t i = 0; i < R->nv; i++)
      for (int d = 0; d < dim; d++) {
        fmpq_zero(s);
        for (size_t q = R->ptr[i]; q < R->ptr[i + 1]; q++) {
          long long p = 0, qq = 1;
          if (!ss_exact_rational(R->w[q], maxden, &p, &qq)) continue;
          fmpq_set_si(w, (slong)p, (ulong)qq);
          ss_testq_set_d(v, y[R->col[q] * dim + (size_t)d]);
          fmpq_mul(v, v, w);
          fmpq_add(s, s, v);
        }
        const size_t k = i * dim + (size_t)d;
        t->outside += !inside(s, olo[k], ohi[k]);
        const double mid = 0.5 * olo[k] + 0.5 * ohi[k];
        t->shrunk_out += !inside(s, mid, mid);
      }
  }
  for (size_t k = 0; k < no; k++) {
    const double a = ohi[k] - olo[k], b = dhi[k] - dlo[k];
    const double ulps = 8.0 * 0x1p-52 * fmax(fabs(dlo[k]), fabs(dhi[k]));
    t->wider += a > 3.0 * b + ulps;
    if (b > 0) t->worst_ratio = fmax(t->worst_ratio, a / b);
  }
  t->rows += (long)R->nv;
  fmpq_clear(s);
  fmpq_clear(w);
  fmpq_clear(v);
  free(lo), free(hi), free(y), free(olo), free(ohi), free(dlo), free(dhi);
}

static void test_schemes(void) {
  const char *schemes[] = {"mlca", "tetoct", "boxspline"};
  const char *links[] = {"octahedron", "tetrahedron", "octahedron"};
  const double widths[] = {0.0, 1e-15, 1e-9, 1e-3};
  uint64_t seed = 99;
  tally t = {0};
  tally wide = {0};
  for (int s = 0; s < 3; s++) {
    ss_error err = {0};
    ss_scheme *sc = NULL;
    ss_link *l = NULL;
    ss_local *M = NULL;
    if (ss_scheme_new(schemes[s], &sc, &err) || ss_link_named(links[s], &l, &err)) {
      CHECK(0, "%s: %s", schemes[s], err.msg);
      ss_scheme_free(sc);
      continue;
    }
    ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
    if (ss_local_new(sc, &c, &M, &err)) {
      CHECK(0, "%s: extraction: %s", schemes[s], err.msg);
    } else {
      const long maxden = ss_exact_defaults(M->dim).maxden;
      for (int lv = 0; lv < M->nring; lv++)
        for (int wi = 0; wi < 4; wi++)
          push_level(M->ring + lv, maxden, widths[wi], &seed, wi == 3 ? &wide : &t);
    }
    ss_local_free(M);
    ss_link_free(l);
    ss_scheme_free(sc);
  }
  CHECK(t.outside == 0 && wide.outside == 0,
        "%ld + %ld exact pushes outside the output boxes", t.outside, wide.outside);
  CHECK(t.wider == 0 && wide.wider == 0,
        "%ld + %ld outputs wider than 3 times di_t's plus 8 ulp", t.wider, wide.wider);
  CHECK(wide.shrunk_out > wide.rows, "only %ld exact pushes miss the shrunk outputs",
        wide.shrunk_out);
  CHECK(t.rows > 1000, "only %ld rows pushed", t.rows);
  printf("push: %ld rows (narrow boxes), %ld (wide); width / di_t width at most %.4f "
         "(narrow), %.4f (wide); %ld exact pushes miss the outputs shrunk to points\n",
         t.rows, wide.rows, t.worst_ratio, wide.worst_ratio, wide.shrunk_out);
}

/* A box that is not finite: the whole line there; Loop's weights: refused. */
static void test_refusals(void) {
  ss_error err = {0};
  ss_scheme *sc = NULL;
  ss_link *l = NULL;
  ss_local *M = NULL;
  if (ss_scheme_new("mlca", &sc, &err) || ss_link_named("octahedron", &l, &err)) {
    CHECK(0, "%s", err.msg);
    return;
  }
  ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  if (!ss_local_new(sc, &c, &M, &err)) {
    const ss_local_ring *R = M->ring;
    const size_t np = R->nprev * 3, no = R->nv * 3;
    double *lo = calloc(np, sizeof *lo), *hi = calloc(np, sizeof *hi),
           *olo = malloc(no * sizeof *olo), *ohi = malloc(no * sizeof *ohi);
    hi[4] = (double)INFINITY;
    CHECK(ss_charmap_push_interval(R, lo, hi, 3, 1L << 20, olo, ohi) == 0,
          "an infinite box is pushed");
    long whole = 0, reads = 0;
    for (size_t i = 0; i < R->nv; i++)
      for (size_t q = R->ptr[i]; q < R->ptr[i + 1]; q++)
        if (R->col[q] == 1 && R->w[q] != 0.0) {
          reads++;
          whole += isinf(olo[3 * i + 1]) && isinf(ohi[3 * i + 1]);
        }
    CHECK(reads > 0 && whole == reads, "%ld of %ld rows reading the infinite box whole",
          whole, reads);
    hi[4] = 0.0;
    CHECK(ss_charmap_push_interval(R, lo, hi, 3, 1L << 20, olo, ohi) == 0 &&
              olo[0] <= 0.0 && ohi[0] >= 0.0 && ohi[0] - olo[0] < 1e-290,
          "the zero net: [%g, %g]", olo[0], ohi[0]);
    CHECK(ss_charmap_push_interval(R, lo, hi, 4, 1L << 20, olo, ohi) == -1,
          "dim 4 refused");
    free(lo), free(hi), free(olo), free(ohi);
  }
  ss_local_free(M);
  ss_link_free(l);
  ss_scheme_free(sc);
}

int main(void) {
  test_schemes();
  test_refusals();
  flint_cleanup();
  return ss_test_done("charmap_push");
}
