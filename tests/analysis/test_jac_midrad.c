/* test_jac_midrad.c — the interval hex test's first try, ss_jac_hex_midrad
 * (analysis/charmap/ss_jac.c): its bounds E hold the exact Bernstein
 * coefficients of det J of hexes anywhere in the boxes, computed here in
 * exact rational arithmetic (FLINT fmpq) by another route -- the trilinear
 * map's derivatives at the 27 Lagrange points from its corner weights, the
 * Bernstein form checked against det J at random rational points -- on
 * random hexes of every size, position and shape, with boxes from zero
 * width to wide; its signs never contradict the full interval test; and the
 * containment check would catch a bound without the boxes' widths. */
#include <flint/fmpq.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "ss_cx.h"
#include "ss_jac.h"
#include "ss_test.h"
#include "ss_testq.h"

/* deterministic uniform numbers in [-1, 1) */
static double rnd(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}

/* det of the 3 x 3 rational matrix with rows a, b, c into d */
static void det3_q(fmpq_t d, fmpq *const a, fmpq *const b, fmpq *const c) {
  fmpq_t t, s;
  fmpq_init(t);
  fmpq_init(s);
  fmpq_zero(d);
  static const int perm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                 {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  for (int k = 0; k < 6; k++) {
    fmpq_mul(t, a + perm[k][0], b + perm[k][1]);
    fmpq_mul(t, t, c + perm[k][2]);
    if (k < 3)
      fmpq_add(d, d, t);
    else
      fmpq_sub(d, d, t);
  }
  fmpq_clear(t);
  fmpq_clear(s);
}

/* det J of the trilinear hex x (8 corners, ss_cx.h's order, exact doubles)
 * at the rational point t[3], from the corner weights: d x / d t_a =
 * sum_k x_k (bit a of k ? 1 : -1) prod_{c != a} (bit c ? t_c : 1 - t_c) */
static void detj_q(fmpq_t d, const double *x, fmpq *const t) {
  fmpq J[3][3];
  fmpq_t w, f, xq;
  fmpq_init(w);
  fmpq_init(f);
  fmpq_init(xq);
  for (int a = 0; a < 3; a++)
    for (int r = 0; r < 3; r++)
      fmpq_init(&J[r][a]), fmpq_zero(&J[r][a]);
  for (int k = 0; k < 8; k++) {
    const unsigned b = ss_cube_corner_bits(3, k);
    for (int a = 0; a < 3; a++) {
      fmpq_set_si(w, (b >> a) & 1 ? 1 : -1, 1);
      for (int c = 0; c < 3; c++) {
        if (c == a) continue;
        if ((b >> c) & 1)
          fmpq_set(f, t + c);
        else
          fmpq_one(f), fmpq_sub(f, f, t + c);
        fmpq_mul(w, w, f);
      }
      for (int r = 0; r < 3; r++) {
        ss_testq_set_d(xq, x[3 * k + r]);
        fmpq_mul(f, w, xq);
        fmpq_add(&J[a][r], &J[a][r], f);
      }
    }
  }
  det3_q(d, J[0], J[1], J[2]);
  for (int a = 0; a < 3; a++)
    for (int r = 0; r < 3; r++)
      fmpq_clear(&J[a][r]);
  fmpq_clear(w);
  fmpq_clear(f);
  fmpq_clear(xq);
}

/* The exact Bernstein coefficients c[i + 3 j + 9 l] of det J of the hex x
 * (degree 2 in each parameter): the Lagrange values at (i, j, l) / 2, then
 * per axis the middle b1 = 2 f(1/2) - (f(0) + f(1)) / 2. */
static void bernstein_q(fmpq *c, const double *x) {
  fmpq t[3];
  fmpq_t h;
  for (int a = 0; a < 3; a++)
    fmpq_init(t + a);
  fmpq_init(h);
  for (int p = 0; p < 27; p++) {
    fmpq_set_si(t + 0, p % 3, 2);
    fmpq_set_si(t + 1, (p / 3) % 3, 2);
    fmpq_set_si(t + 2, p / 9, 2);
    detj_q(c + p, x, t);
  }
  for (int a = 0, stride = 1; a < 3; a++, stride *= 3)
    for (int p = 0; p < 27; p++) {
      if ((p / stride) % 3 != 1) continue;
      fmpq_add(h, c + p - stride, c + p + stride);
      fmpq_div_2exp(h, h, 1);
      fmpq_mul_2exp(c + p, c + p, 1);
      fmpq_sub(c + p, c + p, h);
    }
  for (int a = 0; a < 3; a++)
    fmpq_clear(t + a);
  fmpq_clear(h);
}

/* sum_q c_q B_q(t) at a rational t, B_q the tensor Bernstein basis of
 * degree 2 (the check that bernstein_q's c are det J's coefficients) */
static void bernstein_eval_q(fmpq_t s, const fmpq *c, fmpq *const t) {
  fmpq B[3][3];
  fmpq_t f, g;
  fmpq_init(f);
  fmpq_init(g);
  for (int a = 0; a < 3; a++) {
    for (int i = 0; i < 3; i++)
      fmpq_init(&B[a][i]);
    fmpq_one(g);
    fmpq_sub(g, g, t + a); /* 1 - t */
    fmpq_mul(&B[a][0], g, g);
    fmpq_mul(&B[a][1], g, t + a);
    fmpq_mul_2exp(&B[a][1], &B[a][1], 1);
    fmpq_mul(&B[a][2], t + a, t + a);
  }
  fmpq_zero(s);
  for (int q = 0; q < 27; q++) {
    fmpq_mul(f, &B[0][q % 3], &B[1][(q / 3) % 3]);
    fmpq_mul(f, f, &B[2][q / 9]);
    fmpq_mul(f, f, c + q);
    fmpq_add(s, s, f);
  }
  for (int a = 0; a < 3; a++)
    for (int i = 0; i < 3; i++)
      fmpq_clear(&B[a][i]);
  fmpq_clear(f);
  fmpq_clear(g);
}

/* |c_exact - cm| <= E, exactly (cm and E doubles, read as rationals) */
static int within(const fmpq_t ce, double cm, double E) {
  fmpq_t d, e;
  fmpq_init(d);
  fmpq_init(e);
  ss_testq_set_d(d, cm);
  fmpq_sub(d, ce, d);
  fmpq_abs(d, d);
  ss_testq_set_d(e, E);
  const int ok = fmpq_cmp(d, e) <= 0;
  fmpq_clear(d);
  fmpq_clear(e);
  return ok;
}

/* A random hex: the unit cube's corners moved by up to `jig`, through a
 * random linear map (some orientation reversing), scaled by 2^sc, moved by
 * `far` times its size in a random direction. */
static void random_hex(uint64_t *s, double jig, int sc, double far, double *x) {
  double A[9], o[3];
  for (int i = 0; i < 9; i++)
    A[i] = (i % 4 == 0 ? 1.0 : 0.0) + 0.4 * rnd(s);
  for (int r = 0; r < 3; r++)
    o[r] = far * rnd(s);
  for (int k = 0; k < 8; k++) {
    const unsigned b = ss_cube_corner_bits(3, k);
    double p[3];
    for (int a = 0; a < 3; a++)
      p[a] = (double)((b >> a) & 1) + jig * rnd(s);
    for (int r = 0; r < 3; r++)
      x[3 * k + r] =
          ldexp(A[3 * r] * p[0] + A[3 * r + 1] * p[1] + A[3 * r + 2] * p[2] + o[r], sc);
  }
}

/* The boxes' containment on random hexes: the exact coefficients of hexes at
 * the boxes' corners, midpoints and random points inside lie within E of c.
 * It also counts the boxes whose sign was decided. */
static void test_containment(void) {
  uint64_t seed = 2026;
  fmpq ce[27];
  fmpq_t v, w;
  fmpq t[3];
  for (int q = 0; q < 27; q++)
    fmpq_init(ce + q);
  fmpq_init(v);
  fmpq_init(w);
  for (int a = 0; a < 3; a++)
    fmpq_init(t + a);
  const double widths[] = {0.0, 1e-16, 1e-12, 1e-8, 1e-4, 1e-2};
  int cases = 0, outside = 0, bad_form = 0, decided = 0, contra = 0, mut_out = 0;
  int easy = 0, easy_decided = 0;
  double tight = 0.0;
  for (int n = 0; n < 1200; n++) {
    double x[24], lo[24], hi[24], y[24], c[27], E[27], c0[27], E0[27];
    const int sc = (int)(40.0 * rnd(&seed)), wi = n % 6;
    const double jig = n % 7 == 0 ? 0.45 : 0.15, far = n % 3 == 0 ? 1e6 : n % 3 ? 3.0 : 0;
    random_hex(&seed, jig, sc, far, x);
    double size = 0.0;
    for (int i = 0; i < 24; i++)
      size = fmax(size, fabs(x[i] - x[i % 3]));
    for (int i = 0; i < 24; i++) {
      const double h = widths[wi] * size;
      lo[i] = x[i] - h * fabs(rnd(&seed));
      hi[i] = x[i] + h * fabs(rnd(&seed));
    }
    const int s = ss_jac_hex_midrad(lo, hi, c, E);
    /* the same evaluation with the widths forgotten (mutation: no radius) */
    double m[24];
    for (int i = 0; i < 24; i++)
      m[i] = 0.5 * lo[i] + 0.5 * hi[i];
    ss_jac_hex_midrad(m, m, c0, E0);
    decided += s != 0;
    if (wi <= 3 && jig < 0.2) easy++, easy_decided += s != 0;
    for (int pt = 0; pt < 4; pt++) {
      for (int i = 0; i < 24; i++) {
        const double r = rnd(&seed);
        y[i] = pt == 0 ? lo[i] : pt == 1 ? hi[i] : pt == 2 ? m[i] : r < 0 ? lo[i] : hi[i];
        if (y[i] < lo[i] || y[i] > hi[i]) y[i] = m[i];
      }
      bernstein_q(ce, y);
      if (pt == 0) { /* the Bernstein form is det J's (at a random point) */
        for (int a = 0; a < 3; a++)
          fmpq_set_si(t + a, (slong)(seed % 1000), 1000), rnd(&seed);
        detj_q(v, y, t);
        bernstein_eval_q(w, ce, t);
        bad_form += !fmpq_equal(v, w);
      }
      for (int q = 0; q < 27; q++) {
        outside += !within(ce + q, c[q], E[q]);
        mut_out += wi >= 3 && !within(ce + q, c0[q], E0[q]);
        if (s) contra += fmpq_sgn(ce + q) != s;
        ss_testq_set_d(v, c[q]);
        fmpq_sub(v, ce + q, v);
        const double dev = fabs(fmpq_get_d(v));
        if (wi >= 4 && E[q] > 0) tight = fmax(tight, dev / E[q]);
      }
    }
    if (s) { /* the full interval test never says otherwise */
      ss_jac_result r;
      ss_jac_cell_interval(SS_HEX, lo, hi, 3, 4, &r);
      contra += r.sign == SS_JAC_FOLDED ||
                r.sign == (s > 0 ? SS_JAC_NEGATIVE : SS_JAC_POSITIVE);
    }
    cases++;
  }
  CHECK(bad_form == 0, "the exact Bernstein form differs from det J in %d hexes",
        bad_form);
  CHECK(outside == 0, "%d exact coefficients outside [c - E, c + E] (%d hexes x 4 x 27)",
        outside, cases);
  CHECK(contra == 0, "%d decided signs contradicted by exact values or the full test",
        contra);
  /* the containment check has teeth: without the widths, wide boxes escape */
  CHECK(mut_out > 100, "only %d exact coefficients escape a bound without the widths",
        mut_out);
  /* and the bound is not vacuous: some deviations reach 1/50 of it on wide
   * boxes, and it decides nearly every well-shaped hex in narrow boxes */
  CHECK(tight > 0.02, "largest deviation / bound on wide boxes %.3g", tight);
  CHECK(easy_decided >= easy * 0.95, "decided %d of %d well-shaped narrow hexes",
        easy_decided, easy);
  printf("midrad: %d hexes, %d decided (%d of %d well-shaped narrow), largest "
         "deviation / bound %.3f, %d escape the widthless bound\n",
         cases, decided, easy_decided, easy, tight, mut_out);
  for (int q = 0; q < 27; q++)
    fmpq_clear(ce + q);
  fmpq_clear(v);
  fmpq_clear(w);
  for (int a = 0; a < 3; a++)
    fmpq_clear(t + a);
}

/* Refusals: bad boxes, huge and tiny cells give 0. */
static void test_refusals(void) {
  double x[24], lo[24], hi[24], c[27], E[27];
  uint64_t seed = 5;
  random_hex(&seed, 0.1, 0, 0.0, x);
  memcpy(lo, x, sizeof lo);
  memcpy(hi, x, sizeof hi);
  CHECK(ss_jac_hex_midrad(lo, hi, c, E) != 0, "a plain hex is decided");
  hi[4] = lo[4] - 1.0;
  CHECK(ss_jac_hex_midrad(lo, hi, c, E) == 0, "lo > hi refused");
  hi[4] = INFINITY;
  CHECK(ss_jac_hex_midrad(lo, hi, c, E) == 0, "an infinite end refused");
  hi[4] = NAN;
  CHECK(ss_jac_hex_midrad(lo, hi, c, E) == 0, "a NaN end refused");
  for (int i = 0; i < 24; i++)
    lo[i] = hi[i] = ldexp(x[i], 200);
  CHECK(ss_jac_hex_midrad(lo, hi, c, E) == 0, "a hex of size 2^200 not tried");
  for (int i = 0; i < 24; i++)
    lo[i] = hi[i] = ldexp(x[i], -400);
  CHECK(ss_jac_hex_midrad(lo, hi, c, E) == 0, "a hex of size 2^-400 not tried");
}

int main(void) {
  test_containment();
  test_refusals();
  return ss_test_done("jac_midrad");
}
