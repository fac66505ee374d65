/* test_psi_bernstein.c — the sign of det Dψ on one tricubic B-spline piece
 * (ss_psi_bernstein):
 *  - the 729 Bernstein coefficients against an independent evaluation: at 200
 *    random points of random nets, their Bernstein sum (the basis written out
 *    here, binomials and powers) equals det of ss_limit_bspline's Jacobian
 *    (analysis/limit, another code path), and the corner coefficients are the
 *    corner values;
 *  - the regular grid under a random affine map A: every coefficient is det A,
 *    the sign proven in doubles and in intervals;
 *  - folds: (u, v, f(w)) with f' of both signs, one whose corners are all
 *    positive (found by subdivision), and a grid with one inner layer pushed
 *    through the next; the witnesses' det Dψ recomputed by ss_limit_bspline
 *    are of opposite signs; a positive piece that needs subdivision;
 *  - symmetries: a reflected net negates every coefficient exactly; relabelled
 *    grids (i <-> j, i -> j -> k, i -> 3 - i) permute them, times the
 *    relabelling's determinant;
 *  - the acceptance rules on their edges: the double path's flat threshold at
 *    half and twice a constant det, and the interval path's enclosures, which
 *    hold the coefficients of nets drawn in the boxes and, widened until one
 *    enclosure holds 0, must refuse although every midpoint is positive;
 *  - bad input; and the cost per piece in both paths (printed). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <flint/fmpq.h>

#include "ss_limit.h"
#include "ss_psi_bernstein.h"
#include "ss_test.h"

/* a net as the library takes it (C11 does not convert double (*)[3] to
 * const double (*)[3] by itself) */
#define CN(x) ((const double(*)[3])(x))

/* deterministic uniform numbers in [-1, 1) */
static double rnd(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}

static double det3(const double a[3], const double b[3], const double c[3]) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

/* det Dψ at (u, v, w) by ss_limit_bspline (rows d/du, d/dv, d/dw) */
static double det_ref(const double (*net)[3], double u, double v, double w) {
  double p[3], J[3][3];
  ss_limit_bspline(net, u, v, w, p, J);
  return det3(J[0], J[1], J[2]);
}

/* The Bernstein sum of coef at (u, v, w), written out: sum over (a, b, c) of
 * coef * C(8,a) u^a (1-u)^(8-a) * ... (not de Casteljau) */
static double bern_sum(const double *coef, double u, double v, double w) {
  static const double C8[9] = {1, 8, 28, 56, 70, 56, 28, 8, 1};
  double bu[9], bv[9], bw[9];
  for (int a = 0; a < 9; a++) {
    bu[a] = C8[a] * pow(u, a) * pow(1 - u, 8 - a);
    bv[a] = C8[a] * pow(v, a) * pow(1 - v, 8 - a);
    bw[a] = C8[a] * pow(w, a) * pow(1 - w, 8 - a);
  }
  double s = 0.0;
  for (int c = 0; c < 9; c++)
    for (int b = 0; b < 9; b++)
      for (int a = 0; a < 9; a++)
        s += coef[a + 9 * b + 81 * c] * bu[a] * bv[b] * bw[c];
  return s;
}

/* net = A (grid position) + t + noise (amplitude eta), A random with det > 0
 * (A = I + 0.4 random, rows swapped if needed); returns det A */
static double affine_net(uint64_t *s, double eta, double (*net)[3], double A[3][3]) {
  double t[3];
  for (int r = 0; r < 3; r++) {
    t[r] = 3.0 * rnd(s);
    for (int c = 0; c < 3; c++)
      A[r][c] = (r == c) + 0.4 * rnd(s);
  }
  double d = det3(A[0], A[1], A[2]);
  if (d < 0) {
    for (int c = 0; c < 3; c++) {
      const double x = A[0][c];
      A[0][c] = A[1][c], A[1][c] = x;
    }
    d = -d;
  }
  for (int q = 0; q < 64; q++) {
    const double g[3] = {q % 4 - 1, (q / 4) % 4 - 1, q / 16 - 1};
    for (int r = 0; r < 3; r++)
      net[q][r] = A[r][0] * g[0] + A[r][1] * g[1] + A[r][2] * g[2] + t[r] + eta * rnd(s);
  }
  return d;
}

/* the largest |coefficient| */
static double coef_scale(const double *c) {
  double m = 0.0;
  for (int q = 0; q < SS_PSI_NCOEF; q++)
    m = fmax(m, fabs(c[q]));
  return m;
}

/* ---- the Bernstein form against ss_limit_bspline ---- */

static void test_against_bspline(void) {
  uint64_t s = 12345;
  const double tol = 1e-12; /* relative to N_u N_v N_w (= flat / SS_PSI_FLAT) */
  double worst = 0.0, worst_eval = 0.0, worst_corner = 0.0;
  int npts = 0;
  for (int n = 0; n < 10; n++) {
    double net[64][3], A[3][3], coef[SS_PSI_NCOEF];
    /* half of them wild (noise as large as the grid), half near a grid */
    affine_net(&s, n % 2 ? 0.9 : 0.2, net, A);
    ss_psi_bernstein_det(CN(net), coef);
    const double N = ss_psi_bernstein_flat(CN(net)) / SS_PSI_FLAT;
    CHECK(N > 0 && isfinite(N), "net %d: N = %g", n, N);
    for (int p = 0; p < 20; p++, npts++) {
      const double u = 0.5 + 0.5 * rnd(&s), v = 0.5 + 0.5 * rnd(&s),
                   w = 0.5 + 0.5 * rnd(&s);
      const double ref = det_ref(CN(net), u, v, w), b = bern_sum(coef, u, v, w);
      const double e = ss_psi_bernstein_eval(coef, u, v, w);
      worst = fmax(worst, fabs(b - ref) / N);
      worst_eval = fmax(worst_eval, fabs(e - b) / N);
      CHECK(fabs(b - ref) <= tol * N, "net %d at (%g %g %g): Bernstein %.17g, det %.17g",
            n, u, v, w, b, ref);
      CHECK(fabs(e - b) <= tol * N, "net %d: de Casteljau %.17g, Bernstein sum %.17g", n,
            e, b);
    }
    for (int k = 0; k < 8; k++) {
      const int i = k & 1, j = (k >> 1) & 1, l = (k >> 2) & 1;
      const double ref = det_ref(CN(net), i, j, l), c = coef[8 * i + 72 * j + 648 * l];
      worst_corner = fmax(worst_corner, fabs(c - ref) / N);
      CHECK(fabs(c - ref) <= tol * N, "net %d corner %d: coefficient %.17g, det %.17g", n,
            k, c, ref);
    }
  }
  printf("Bernstein form vs ss_limit_bspline: %d points, largest |error| / (N_u N_v N_w) "
         "= %.2e (tolerance %.0e); de Casteljau vs the Bernstein sum %.2e; corners "
         "%.2e\n",
         npts, worst, tol, worst_eval, worst_corner);
}

/* ---- exact coefficients (FLINT rationals) ---- */

/* the double x as a rational, exactly */
static void fmpq_from_d(fmpq_t q, double x) {
  int e;
  const double m = frexp(x, &e); /* x = m 2^e, m 53 bits */
  fmpz_t z;
  fmpz_init(z);
  fmpz_set_d(z, ldexp(m, 53)); /* an integer, exact */
  fmpz_set(fmpq_numref(q), z);
  fmpz_one(fmpq_denref(q));
  if (e - 53 >= 0)
    fmpq_mul_2exp(q, q, (flint_bitcnt_t)(e - 53));
  else
    fmpq_div_2exp(q, q, (flint_bitcnt_t)(53 - e));
  fmpz_clear(z);
}

/* the 729 coefficients of det Dψ, exactly: the Bezier net by the B-spline
 * to Bezier matrix (1/6)[1 4 1 0; 0 4 2 0; 0 2 4 0; 0 1 4 1] per axis, the
 * derivatives 3 (b_{i+1} - b_i), and every triple (i, j, k) of their
 * coefficients adding det(du_i, dv_j, dw_k) times the product of its
 * binomials over C(8, i + j + k) to coefficient i + j + k */
static void exact_coef(const double (*net)[3], fmpq *c) {
  static const int M[4][4] = {{1, 4, 1, 0}, {0, 4, 2, 0}, {0, 2, 4, 0}, {0, 1, 4, 1}};
  static const int C2[3] = {1, 2, 1}, C3[4] = {1, 3, 3, 1};
  static const int C8[9] = {1, 8, 28, 56, 70, 56, 28, 8, 1};
  fmpq *P = _fmpq_vec_init(192), *B = _fmpq_vec_init(192), *D = _fmpq_vec_init(3 * 192);
  fmpq_t t, x;
  fmpz_t six3;
  fmpq_init(t), fmpq_init(x);
  fmpz_init_set_ui(six3, 216);
  for (int q = 0; q < 64; q++)
    for (int r = 0; r < 3; r++)
      fmpq_from_d(P + 3 * q + r, net[q][r]);
  /* B[a,b,c] = sum M[a][i] M[b][j] M[c][k] P[i,j,k] / 216 */
  for (int q = 0; q < 64; q++)
    for (int r = 0; r < 3; r++) {
      fmpq_zero(B + 3 * q + r);
      for (int p = 0; p < 64; p++) {
        const int w = M[q % 4][p % 4] * M[(q / 4) % 4][(p / 4) % 4] * M[q / 16][p / 16];
        if (!w) continue;
        fmpq_mul_si(t, P + 3 * p + r, w);
        fmpq_add(B + 3 * q + r, B + 3 * q + r, t);
      }
      fmpq_div_fmpz(B + 3 * q + r, B + 3 * q + r, six3);
    }
  /* D[a][i + 4j + 16k] (index along a only up to 2), times the binomials of
   * the derivative's degrees */
  for (int a = 0; a < 3; a++)
    for (int q = 0; q < 64; q++) {
      const int id[3] = {q % 4, (q / 4) % 4, q / 16};
      if (id[a] == 3) continue;
      const int st = a == 0 ? 1 : a == 1 ? 4 : 16;
      int w = 3;
      for (int b = 0; b < 3; b++)
        w *= b == a ? C2[id[b]] : C3[id[b]];
      for (int r = 0; r < 3; r++) {
        fmpq_sub(t, B + 3 * (q + st) + r, B + 3 * q + r);
        fmpq_mul_si(D + 3 * (64 * a + q) + r, t, w);
      }
    }
  for (int q = 0; q < 729; q++)
    fmpq_zero(c + q);
  for (int i = 0; i < 64; i++) {
    if (i % 4 == 3) continue;
    for (int j = 0; j < 64; j++) {
      if ((j / 4) % 4 == 3) continue;
      for (int k = 0; k < 64; k++) {
        if (k / 16 == 3) continue;
        const fmpq *u = D + 3 * i, *v = D + 3 * (64 + j), *w = D + 3 * (128 + k);
        /* det(u, v, w) */
        fmpq_zero(x);
        for (int p = 0; p < 3; p++) {
          const int p1 = (p + 1) % 3, p2 = (p + 2) % 3;
          fmpq_mul(t, v + p1, w + p2);
          fmpq_submul(t, v + p2, w + p1);
          fmpq_addmul(x, u + p, t);
        }
        const int o = (i % 4 + j % 4 + k % 4) +
                      9 * ((i / 4) % 4 + (j / 4) % 4 + (k / 4) % 4) +
                      81 * (i / 16 + j / 16 + k / 16);
        fmpq_add(c + o, c + o, x);
      }
    }
  }
  for (int q = 0; q < 729; q++) {
    fmpz_t d;
    fmpz_init_set_ui(d, (ulong)C8[q % 9] * C8[(q / 9) % 9] * C8[q / 81]);
    fmpq_div_fmpz(c + q, c + q, d);
    fmpz_clear(d);
  }
  fmpq_clear(t), fmpq_clear(x);
  fmpz_clear(six3);
  _fmpq_vec_clear(P, 192), _fmpq_vec_clear(B, 192), _fmpq_vec_clear(D, 3 * 192);
}

/* the exact coefficients lie in the enclosures of the interval path, for
 * point boxes; and the double path's error against them, relative to N_u N_v
 * N_w, is far below the flat threshold's SS_PSI_FLAT */
static void test_exact(void) {
  uint64_t s = 8080;
  double worst = 0.0;
  for (int n = 0; n < 3; n++) {
    double net[64][3], A[3][3], c[SS_PSI_NCOEF], clo[SS_PSI_NCOEF], chi[SS_PSI_NCOEF];
    affine_net(&s, 0.6, net, A);
    ss_psi_bernstein_det(CN(net), c);
    ss_psi_bernstein_det_interval(CN(net), CN(net), clo, chi);
    const double N = ss_psi_bernstein_flat(CN(net)) / SS_PSI_FLAT;
    fmpq *e = _fmpq_vec_init(729);
    exact_coef(CN(net), e);
    int in = 1, point = 0;
    fmpq_t a, b;
    fmpq_init(a), fmpq_init(b);
    for (int q = 0; q < SS_PSI_NCOEF; q++) {
      fmpq_from_d(a, clo[q]);
      fmpq_from_d(b, chi[q]);
      in &= fmpq_cmp(a, e + q) <= 0 && fmpq_cmp(e + q, b) <= 0;
      point += clo[q] == chi[q];
      worst = fmax(worst, fabs(c[q] - fmpq_get_d(e + q)) / N);
    }
    CHECK(in, "net %d: an exact coefficient outside its enclosure", n);
    CHECK(point < SS_PSI_NCOEF / 2, "net %d: %d enclosures are points", n, point);
    fmpq_clear(a), fmpq_clear(b);
    _fmpq_vec_clear(e, 729);
  }
  CHECK(worst < 1e-2 * SS_PSI_FLAT, "double coefficients off by %g N", worst);
  printf("exact coefficients (FLINT rationals): inside every enclosure; double path's "
         "error %.2e N_u N_v N_w (flat threshold %.0e)\n",
         worst, SS_PSI_FLAT);
}

/* ---- the regular grid ---- */

static void test_affine_grid(void) {
  uint64_t s = 777;
  double worst = 0.0;
  for (int n = 0; n < 20; n++) {
    double net[64][3], A[3][3], coef[SS_PSI_NCOEF];
    double d = affine_net(&s, 0.0, net, A);
    const int flip = n % 2; /* odd n: mirrored, det A < 0 */
    if (flip) {
      for (int q = 0; q < 64; q++)
        net[q][2] = -net[q][2];
      d = -d;
    }
    ss_psi_bernstein_det(CN(net), coef);
    for (int q = 0; q < SS_PSI_NCOEF; q++)
      worst = fmax(worst, fabs(coef[q] - d) / fabs(d));
    int all = 1;
    for (int q = 0; q < SS_PSI_NCOEF; q++)
      all &= fabs(coef[q] - d) <= 1e-13 * fabs(d);
    CHECK(all, "affine grid %d: a coefficient differs from det A = %g", n, d);
    ss_psi_piece_result r, ri;
    ss_psi_piece_sign(CN(net), SS_PSI_DEPTH, &r);
    ss_psi_piece_sign_interval(CN(net), CN(net), SS_PSI_DEPTH, &ri);
    const ss_jac_sign want = d > 0 ? SS_JAC_POSITIVE : SS_JAC_NEGATIVE;
    CHECK(r.sign == want && r.depth == 0 && r.boxes == 1,
          "affine grid %d: sign %d depth %d boxes %ld", n, r.sign, r.depth, r.boxes);
    CHECK(ri.sign == want && ri.depth == 0, "affine grid %d, intervals: sign %d", n,
          ri.sign);
    CHECK(fabs(r.min_coef - d) <= 1e-13 * fabs(d) &&
              fabs(r.max_coef - d) <= 1e-13 * fabs(d),
          "affine grid %d: min %g max %g det %g", n, r.min_coef, r.max_coef, d);
  }
  printf("affine grids: every coefficient det A to %.2e relative\n", worst);
}

/* ---- folds ---- */

/* the net of (u, v, f(w)) with f(w) = w^3 + f2 w^2 + f1 w + f0, by the
 * cubic B-spline's blossoms at the knots (g-1, g, g+1) of grid position g:
 * w -> g, w^2 -> g^2 - 1/3, w^3 -> g^3 - g */
static void cubic_net(double f2, double f1, double f0, double (*net)[3]) {
  for (int q = 0; q < 64; q++) {
    const double g = q / 16 - 1;
    net[q][0] = q % 4 - 1;
    net[q][1] = (q / 4) % 4 - 1;
    net[q][2] = (g * g * g - g) + f2 * (g * g - 1.0 / 3.0) + f1 * g + f0;
  }
}

/* r is FOLDED with witnesses of opposite signs by ss_limit_bspline, and its
 * enclosures hold those values to tolerance */
static void check_witnesses(const char *what, const double (*net)[3],
                            const ss_psi_piece_result *r) {
  CHECK(r->sign == SS_JAC_FOLDED, "%s: sign %d", what, r->sign);
  if (r->sign != SS_JAC_FOLDED) return;
  const double N = ss_psi_bernstein_flat(CN(net)) / SS_PSI_FLAT;
  double d[2];
  for (int i = 0; i < 2; i++) {
    const double *p = r->where[i];
    CHECK(p[0] >= 0 && p[0] <= 1 && p[1] >= 0 && p[1] <= 1 && p[2] >= 0 && p[2] <= 1,
          "%s: witness %d outside the piece", what, i);
    d[i] = det_ref(CN(net), p[0], p[1], p[2]);
    CHECK(r->det[i][0] - 1e-12 * N <= d[i] && d[i] <= r->det[i][1] + 1e-12 * N,
          "%s: witness %d det %.17g, reported [%.17g, %.17g]", what, i, d[i],
          r->det[i][0], r->det[i][1]);
  }
  CHECK(d[0] * d[1] < 0, "%s: witnesses' det %g and %g", what, d[0], d[1]);
  printf(
      "%s: FOLDED at depth %d (%ld boxes), det %.4g at (%g %g %g), %.4g at (%g %g %g)\n",
      what, r->depth, r->boxes, d[0], r->where[0][0], r->where[0][1], r->where[0][2],
      d[1], r->where[1][0], r->where[1][1], r->where[1][2]);
}

static void test_folds(void) {
  double net[64][3];
  ss_psi_piece_result r, ri;
  /* f(w) = w^3 - 0.75 w: f' = 3 w^2 - 0.75 < 0 below w = 1/2: the corners
   * decide */
  cubic_net(0.0, -0.75, 0.0, net);
  ss_psi_piece_sign(CN(net), SS_PSI_DEPTH, &r);
  check_witnesses("w^3 - 0.75w", CN(net), &r);
  CHECK(r.depth == 0, "corners decide: depth %d", r.depth);
  ss_psi_piece_sign_interval(CN(net), CN(net), SS_PSI_DEPTH, &ri);
  check_witnesses("w^3 - 0.75w, intervals", CN(net), &ri);
  /* f(w) = (w - 1/2)^3 - e (w - 1/2): f' = 3 (w - 1/2)^2 - e, positive at
   * every corner, negative near w = 1/2: only a sub-box corner shows it */
  const double e = 0.05;
  cubic_net(-1.5, 0.75 - e, -0.125 + 0.5 * e, net);
  for (int k = 0; k < 8; k++)
    CHECK(det_ref(CN(net), k & 1, (k >> 1) & 1, (k >> 2) & 1) > 0,
          "corner %d not positive", k);
  ss_psi_piece_sign(CN(net), 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED, "inner fold at depth 0: sign %d", r.sign);
  ss_psi_piece_sign(CN(net), SS_PSI_DEPTH, &r);
  check_witnesses("inner fold", CN(net), &r);
  CHECK(r.depth >= 1, "inner fold needs subdivision: depth %d", r.depth);
  ss_psi_piece_sign_interval(CN(net), CN(net), SS_PSI_DEPTH, &ri);
  check_witnesses("inner fold, intervals", CN(net), &ri);
  /* + e instead: positive everywhere (min e at w = 1/2), but a negative
   * coefficient at depth 0 */
  cubic_net(-1.5, 0.75 + e, -0.125 - 0.5 * e, net);
  ss_psi_piece_sign(CN(net), 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && r.min_coef < 0, "positive, depth 0: sign %d min %g",
        r.sign, r.min_coef);
  ss_psi_piece_sign(CN(net), SS_PSI_DEPTH, &r);
  ss_psi_piece_sign_interval(CN(net), CN(net), SS_PSI_DEPTH, &ri);
  CHECK(r.sign == SS_JAC_POSITIVE && r.depth >= 1, "positive: sign %d depth %d", r.sign,
        r.depth);
  CHECK(ri.sign == SS_JAC_POSITIVE, "positive, intervals: sign %d", ri.sign);
  double mn = INFINITY;
  for (int i = 0; i <= 20; i++)
    for (int j = 0; j <= 4; j++)
      mn = fmin(mn, det_ref(CN(net), j / 4.0, j / 4.0, i / 20.0));
  CHECK(fabs(mn - e) < 1e-12, "positive: sampled min %.17g, expected %g", mn, e);
  printf("positive piece with a negative coefficient (%g): POSITIVE at depth %d "
         "(%ld boxes), sampled min det %.6g\n",
         r.min_coef, r.depth, r.boxes, mn);
  /* a grid whose inner layer k = 2 (w = 1) is pushed through layer k = 1 */
  uint64_t s = 99;
  double A[3][3];
  affine_net(&s, 0.0, net, A);
  for (int q = 32; q < 48; q++)
    for (int c = 0; c < 3; c++)
      net[q][c] -= 1.8 * A[c][2];
  ss_psi_piece_sign(CN(net), SS_PSI_DEPTH, &r);
  check_witnesses("pushed layer", CN(net), &r);
}

/* ---- symmetries ---- */

/* net' at (i, j, k) = net at perm(i, j, k): m maps the new indices to old */
static void relabel(const double (*net)[3], int m, double (*out)[3]) {
  for (int k = 0; k < 4; k++)
    for (int j = 0; j < 4; j++)
      for (int i = 0; i < 4; i++) {
        const int o = m == 0   ? j + 4 * i + 16 * k        /* swap i, j */
                      : m == 1 ? k + 4 * i + 16 * j        /* cyclic */
                               : (3 - i) + 4 * j + 16 * k; /* reverse i */
        memcpy(out[i + 4 * j + 16 * k], net[o], sizeof out[0]);
      }
}

/* the coefficient index that (a, b, c) of the relabelled net comes from, and
 * the relabelling's determinant */
static int relabel_index(int m, int a, int b, int c, int *sign) {
  *sign = m == 1 ? 1 : -1;
  return m == 0   ? b + 9 * a + 81 * c
         : m == 1 ? c + 9 * a + 81 * b
                  : (8 - a) + 9 * b + 81 * c;
}

static void test_symmetry(void) {
  uint64_t s = 4242;
  double worst = 0.0;
  int kinds[3] = {0, 0, 0};
  for (int n = 0; n < 6; n++) {
    double net[64][3], mir[64][3], A[3][3], c[SS_PSI_NCOEF], cm[SS_PSI_NCOEF];
    affine_net(&s, 0.3 + 0.3 * n, net, A); /* from nearly a grid to wild */
    ss_psi_bernstein_det(CN(net), c);
    memcpy(mir, net, sizeof mir);
    for (int q = 0; q < 64; q++)
      mir[q][n % 3] = -mir[q][n % 3];
    ss_psi_bernstein_det(CN(mir), cm);
    int exact = 1;
    for (int q = 0; q < SS_PSI_NCOEF; q++)
      exact &= cm[q] == -c[q];
    CHECK(exact, "net %d: reflecting coordinate %d does not negate every coefficient", n,
          n % 3);
    const double sc = coef_scale(c);
    for (int m = 0; m < 3; m++) {
      double rl[64][3], cr[SS_PSI_NCOEF];
      relabel(CN(net), m, rl);
      ss_psi_bernstein_det(CN(rl), cr);
      int ok = 1;
      for (int q = 0; q < SS_PSI_NCOEF; q++) {
        int sg;
        const int o = relabel_index(m, q % 9, (q / 9) % 9, q / 81, &sg);
        const double e = fabs(cr[q] - sg * c[o]) / sc;
        worst = fmax(worst, e);
        ok &= e <= 1e-13;
      }
      CHECK(ok, "net %d, relabelling %d: coefficients not permuted", n, m);
      /* the verdict: a proven sign times the relabelling's determinant */
      int sg;
      relabel_index(m, 0, 0, 0, &sg);
      ss_psi_piece_result r0, rr;
      ss_psi_piece_sign(CN(net), SS_PSI_DEPTH, &r0);
      ss_psi_piece_sign(CN(rl), SS_PSI_DEPTH, &rr);
      const ss_jac_sign want = r0.sign == SS_JAC_POSITIVE || r0.sign == SS_JAC_NEGATIVE
                                   ? (ss_jac_sign)(sg * (int)r0.sign)
                                   : r0.sign;
      CHECK(rr.sign == want, "net %d, relabelling %d: verdict %d, the net's %d", n, m,
            rr.sign, r0.sign);
      kinds[r0.sign == SS_JAC_FOLDED ? 0 : r0.sign == SS_JAC_UNDECIDED ? 2 : 1]++;
    }
  }
  CHECK(kinds[0] > 0 && kinds[1] > 0, "relabellings: no fold or no proof among the nets");
  printf("relabellings: coefficients permuted, times the determinant, to %.2e of the "
         "largest; verdicts kept (%d folded, %d proven, %d undecided)\n",
         worst, kinds[0], kinds[1], kinds[2]);
}

/* ---- the acceptance rules on their edges ---- */

/* the double path's flat threshold: psi = (u, v + w, eps w), det = eps, N_u
 * N_v N_w = sqrt(1 + eps^2) */
static void test_flat_edge(void) {
  for (int t = 0; t < 2; t++) {
    const double eps = t ? 2.0 * SS_PSI_FLAT : 0.5 * SS_PSI_FLAT;
    double net[64][3];
    for (int q = 0; q < 64; q++) {
      const double g[3] = {q % 4 - 1, (q / 4) % 4 - 1, q / 16 - 1};
      net[q][0] = g[0], net[q][1] = g[1] + g[2], net[q][2] = eps * g[2];
    }
    ss_psi_piece_result r;
    ss_psi_piece_sign(CN(net), SS_PSI_DEPTH, &r);
    CHECK(fabs(r.flat - SS_PSI_FLAT) <= 1e-6 * SS_PSI_FLAT, "flat threshold %g", r.flat);
    CHECK(r.sign == (t ? SS_JAC_POSITIVE : SS_JAC_DEGENERATE),
          "det = %g x the threshold: sign %d", eps / r.flat, r.sign);
    ss_psi_piece_sign_interval(CN(net), CN(net), SS_PSI_DEPTH, &r);
    CHECK(r.sign == SS_JAC_POSITIVE, "det %g, intervals: sign %d", eps, r.sign);
  }
  double net[64][3];
  cubic_net(0.0, 0.0, 0.0, net);
  for (int q = 0; q < 64; q++)
    net[q][2] = 0.0; /* flat: psi = (u, v, 0) */
  ss_psi_piece_result r;
  ss_psi_piece_sign(CN(net), SS_PSI_DEPTH, &r);
  CHECK(r.sign == SS_JAC_DEGENERATE, "flat piece: sign %d", r.sign);
  ss_psi_piece_sign_interval(CN(net), CN(net), SS_PSI_DEPTH, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED, "flat piece, intervals: sign %d", r.sign);
}

/* net +- delta in every coordinate */
static void widen(const double (*net)[3], double delta, double (*lo)[3],
                  double (*hi)[3]) {
  for (int q = 0; q < 64; q++)
    for (int r = 0; r < 3; r++)
      lo[q][r] = net[q][r] - delta, hi[q][r] = net[q][r] + delta;
}

/* the smallest lower end of the 729 enclosures for boxes net +- delta */
static double min_lower(const double (*net)[3], double delta) {
  double lo[64][3], hi[64][3], clo[SS_PSI_NCOEF], chi[SS_PSI_NCOEF];
  widen(CN(net), delta, lo, hi);
  ss_psi_bernstein_det_interval(CN(lo), CN(hi), clo, chi);
  double m = INFINITY;
  for (int q = 0; q < SS_PSI_NCOEF; q++)
    m = fmin(m, clo[q]);
  return m;
}

static void test_interval_edge(void) {
  uint64_t s = 31337;
  double net[64][3], A[3][3], c[SS_PSI_NCOEF];
  affine_net(&s, 0.15, net, A);
  ss_psi_bernstein_det(CN(net), c);
  /* tight boxes enclose the double coefficients, and they are narrow */
  double lo[64][3], hi[64][3], clo[SS_PSI_NCOEF], chi[SS_PSI_NCOEF];
  ss_psi_bernstein_det_interval(CN(net), CN(net), clo, chi);
  int in = 1;
  double width = 0.0;
  for (int q = 0; q < SS_PSI_NCOEF; q++) {
    in &= clo[q] <= c[q] && c[q] <= chi[q];
    width = fmax(width, (chi[q] - clo[q]) / coef_scale(c));
  }
  CHECK(in, "point boxes do not enclose the double coefficients");
  CHECK(width < 1e-12, "point boxes: relative width %g", width);
  /* boxes of 0.02: the enclosures hold the coefficients of nets drawn in them */
  widen(CN(net), 0.02, lo, hi);
  ss_psi_bernstein_det_interval(CN(lo), CN(hi), clo, chi);
  int held = 1;
  for (int t = 0; t < 20; t++) {
    double x[64][3], cx[SS_PSI_NCOEF];
    for (int q = 0; q < 64; q++)
      for (int r = 0; r < 3; r++)
        x[q][r] = t == 0 ? lo[q][r] : t == 1 ? hi[q][r] : net[q][r] + 0.02 * rnd(&s);
    ss_psi_bernstein_det(CN(x), cx);
    for (int q = 0; q < SS_PSI_NCOEF; q++)
      held &= clo[q] <= cx[q] && cx[q] <= chi[q];
  }
  CHECK(held, "an enclosure misses a coefficient of a net in the boxes");
  /* the edge: bisect the box size delta until the smallest lower end of the
   * enclosures crosses 0 (an enclosure starts to hold 0) */
  ss_psi_piece_result r;
  ss_psi_piece_sign_interval(CN(net), CN(net), 0, &r);
  CHECK(r.sign == SS_JAC_POSITIVE && r.min_coef > 0, "the net: sign %d, min %g", r.sign,
        r.min_coef);
  double a = 0.0, b = 1.0;
  CHECK(min_lower(CN(net), b) < 0, "delta = 1 does not straddle");
  for (int it = 0; it < 60; it++) {
    const double m = 0.5 * (a + b);
    if (min_lower(CN(net), m) > 0)
      a = m;
    else
      b = m;
  }
  ss_psi_piece_result ra, rb;
  widen(CN(net), a, lo, hi);
  ss_psi_piece_sign_interval(CN(lo), CN(hi), 0, &ra);
  widen(CN(net), b, lo, hi);
  ss_psi_piece_sign_interval(CN(lo), CN(hi), 0, &rb);
  CHECK(ra.sign == SS_JAC_POSITIVE, "just inside (delta %.17g): sign %d", a, ra.sign);
  CHECK(rb.sign == SS_JAC_UNDECIDED, "just outside (delta %.17g): sign %d", b, rb.sign);
  /* refused on the enclosures, although every midpoint is still positive */
  CHECK(rb.min_coef > 0, "just outside: the smallest midpoint %g", rb.min_coef);
  printf("interval edge: boxes +-%.6g prove POSITIVE, +-%.6g (an enclosure holds 0; "
         "smallest midpoint %.4g) refuse\n",
         a, b, rb.min_coef);
}

/* ---- bad input, cost ---- */

static void test_bad_input(void) {
  double net[64][3], A[3][3];
  uint64_t s = 5;
  affine_net(&s, 0.1, net, A);
  net[17][1] = NAN;
  ss_psi_piece_result r;
  ss_psi_piece_sign(CN(net), 3, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && isnan(r.min_coef), "NaN net: sign %d", r.sign);
  CHECK(isnan(ss_psi_bernstein_flat(CN(net))), "NaN net: a flat threshold");
  affine_net(&s, 0.1, net, A);
  double hi[64][3];
  memcpy(hi, net, sizeof hi);
  hi[5][0] -= 1.0; /* lo > hi */
  ss_psi_piece_sign_interval(CN(net), CN(hi), 3, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && isnan(r.min_coef), "lo > hi: sign %d", r.sign);
  /* a huge maxdepth is clamped: the inner fold still found */
  cubic_net(-1.5, 0.7, -0.1, net);
  ss_psi_piece_sign(CN(net), 1000, &r);
  CHECK(r.sign == SS_JAC_FOLDED && r.depth <= SS_PSI_MAXDEPTH,
        "clamped: sign %d depth %d", r.sign, r.depth);
}

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void cost(void) {
  uint64_t s = 2024;
  enum { N = 200 };
  static double nets[N][64][3];
  double A[3][3];
  for (int n = 0; n < N; n++)
    affine_net(&s, 0.1, nets[n], A);
  ss_psi_piece_result r;
  int npos = 0;
  double t0 = now();
  for (int n = 0; n < N; n++) {
    ss_psi_piece_sign(CN(nets[n]), SS_PSI_DEPTH, &r);
    npos += r.sign == SS_JAC_POSITIVE;
  }
  double t1 = now();
  int nposi = 0;
  for (int n = 0; n < N; n++) {
    ss_psi_piece_sign_interval(CN(nets[n]), CN(nets[n]), SS_PSI_DEPTH, &r);
    nposi += r.sign == SS_JAC_POSITIVE;
  }
  double t2 = now();
  CHECK(npos == N && nposi == N, "near-grid nets: %d and %d of %d proven positive", npos,
        nposi, N);
  printf("cost per piece (near-grid nets, depth 0 decides): double %.1f us, interval "
         "%.1f us\n",
         1e6 * (t1 - t0) / N, 1e6 * (t2 - t1) / N);
}

int main(void) {
  test_against_bspline();
  test_exact();
  test_affine_grid();
  test_folds();
  test_symmetry();
  test_flat_edge();
  test_interval_edge();
  test_bad_input();
  cost();
  return ss_test_done("psi_bernstein");
}
