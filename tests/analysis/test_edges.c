/* test_edges.c — tests that sit on the edge of the proofs (issue 34, 6): a
 * slip that only weakens a proof (a rounding allowance or a margin dropped, a
 * sign turned in an acceptance rule) must fail here, not only slips that
 * change a value.
 *
 *  1. The inf-norm of a product, bounded from above (ss_jsr_ws_norm_inf_up),
 *     against the exact norm of the exact product of the same doubles in arb
 *     at 256 bits: the bound is certainly >= it and within a few units of
 *     roundoff of it (relative to prod ||Y_i||_inf).  Inputs built so that the
 *     floating-point value falls below the exact one: a row 1, 3u/4, 3u/4
 *     (exact sum 1 + 3u/2, summed in doubles to 1), so the bound without its
 *     relative allowance is wrong at level 0; a pair whose product is
 *     computed as 0 but is not (A's second row t times its first, rounded;
 *     B's rows (t, -1)), so the bound without the product's error bound is
 *     wrong; and seeded random words.  The 2-norm bound
 *     (ss_jsr_ws_norm_2_up) likewise on 2 x 2 words, against the closed form
 *     sigma_max^2 = (f + sqrt(f^2 - 4 det^2)) / 2, f = ||P||_F^2, in arb; the
 *     cancelling pair needs its error bound err_2.  The componentwise error
 *     bound of a product (formed where the normwise one exceeds 1e-12 of the
 *     norm: the cancelling pairs) is what these error bounds are on them.
 *  2. The k-th root bounded from above (ss_jsr_root_up) against arb's root of
 *     the same double: certainly >= it, within (8 + |ln x|) 2u + 2u of it, and
 *     pow alone below it on some of the inputs (1/3 rounded down makes
 *     x^(1/3) low for every x > 1; the test checks such inputs are present).
 *  3. The symmetry proof's margin (ss_charmap_cert_sym_margin): for
 *     s_min(Xm) = 1, gap g and ||P Xm - Xm|| = d the proof holds exactly for
 *     ||E|| < e* = (g / 2 - d) / (2 + g / 2); an enclosure 1% narrower than
 *     e* is accepted, one 1% wider refused (turning s_min - ||E|| into
 *     s_min + ||E|| moves the edge to (g / 2 - d) / (2 - g / 2) and accepts it).
 *  4. The fold-persistence rule on proven counts (ss_charmap_cert_persists):
 *     hand-made per-level counts a cell away from each side of every
 *     condition, the unknown cells included: the majority sign against the
 *     other sign plus the unknown cells (now and before), the bad share now
 *     against shrink times the bad share before with the unknown cells
 *     counted as bad, and nothing proven when no cell is proven bad now. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <arb.h>
#include <arb_mat.h>
#include <flint/flint.h>
#include <gsl/gsl_rng.h>

#include "ss_charmap_cert_impl.h"
#include "ss_jsr_ws.h"
#include "ss_test.h"

#define PREC 256

/* ge: 1 if the double x is certainly >= the ball v; !ge: certainly < v */
static int d_vs(double x, const arb_t v, int ge) {
  arb_t t;
  arb_init(t);
  arb_set_d(t, x);
  const int ok = ge ? arb_ge(t, v) : arb_lt(t, v);
  arb_clear(t);
  return ok;
}
#define d_ge(x, v) d_vs(x, v, 1)
#define d_lt(x, v) d_vs(x, v, 0)

/* 1 if x - v <= rel * s certainly (x a double, v a ball, s a double) */
static int d_within(double x, const arb_t v, double rel, double s) {
  arb_t t, b;
  arb_init(t);
  arb_init(b);
  arb_set_d(t, x);
  arb_sub(t, t, v, PREC);
  arb_set_d(b, rel * s); /* the tolerance: its rounding is irrelevant */
  const int ok = arb_le(t, b);
  arb_clear(b);
  arb_clear(t);
  return ok;
}

/* The workspace of the walks for the m n x n matrices Y, as ss_jsr.c sets it
 * up for its inputs (exact: delta 0, so the componentwise bound applies). */
static int ws_init(ss_jsr_ws *w, size_t m, size_t n, const double *const *Y, int levels) {
  memset(w, 0, sizeof *w);
  w->m = m, w->n = n, w->Y = Y;
  w->cw_ok = 1; /* the inputs are exact: the componentwise bound applies */
  w->gam = (double)n * U / (1 - (double)n * U);
  w->tiny = (double)n * (double)n * DBL_TRUE_MIN;
  w->ynorm = calloc(m, sizeof *w->ynorm);
  w->delta = calloc(m, sizeof *w->delta);
  w->y2 = calloc(m, sizeof *w->y2);
  w->yf = calloc(m, sizeof *w->yf);
  w->sb = calloc(n, sizeof *w->sb);
  w->a = calloc(n * n, sizeof *w->a);
  w->sv = calloc(n, sizeof *w->sv);
  w->vl = calloc(n * n, sizeof *w->vl);
  w->v = calloc(n * n, sizeof *w->v);
  w->t2 = calloc(n * n, sizeof *w->t2);
  if (!w->a || !w->sv || !w->vl || !w->v || !w->t2 || !w->sb || !w->ynorm || !w->delta ||
      !w->y2 || !w->yf || !ss_jsr_ws_reserve(w, levels))
    return 0;
  for (size_t i = 0; i < m; i++) {
    double mx = 0;
    for (size_t r = 0; r < n; r++) {
      double s = 0;
      for (size_t c = 0; c < n; c++)
        s += fabs(Y[i][r * n + c]);
      mx = fmax(mx, s);
    }
    w->ynorm[i] = ss_jsr_up(mx * (1 + 2 * w->gam));
    /* ||Y_i||_F from above, generously: bounds ||Y_i||_2 too */
    double f = 0;
    for (size_t e = 0; e < n * n; e++)
      f += Y[i][e] * Y[i][e];
    w->yf[i] = w->y2[i] = sqrt(f) * (1 + 1e-12) + 1e-300;
  }
  return 1;
}

/* ||Y_{w[len-1]} ... Y_{w[0]}||_inf of the exact product of the doubles, in
 * arb (exact: the balls stay points at PREC bits for these short words, and
 * a ball would do), and prod ||Y_i||_inf (doubles, for the tolerance) */
static void exact_norm(arb_t out, size_t n, const double *const *Y, const int *w, int len,
                       double *prodnorm) {
  arb_mat_t P, F, T;
  arb_mat_init(P, (slong)n, (slong)n);
  arb_mat_init(F, (slong)n, (slong)n);
  arb_mat_init(T, (slong)n, (slong)n);
  *prodnorm = 1;
  for (int k = 0; k < len; k++) {
    double mx = 0;
    for (size_t a = 0; a < n; a++) {
      double s = 0;
      for (size_t b = 0; b < n; b++) {
        arb_set_d(arb_mat_entry(F, (slong)a, (slong)b), Y[w[k]][a * n + b]);
        s += fabs(Y[w[k]][a * n + b]);
      }
      mx = fmax(mx, s);
    }
    *prodnorm *= mx;
    if (k == 0) {
      arb_mat_set(P, F);
    } else {
      arb_mat_mul(T, F, P, PREC);
      arb_mat_swap(T, P);
    }
  }
  arb_t s, a;
  arb_init(s);
  arb_init(a);
  arb_zero(out);
  for (size_t r = 0; r < n; r++) {
    arb_zero(s);
    for (size_t c = 0; c < n; c++) {
      arb_abs(a, arb_mat_entry(P, (slong)r, (slong)c));
      arb_add(s, s, a, PREC);
    }
    arb_max(out, out, s, PREC);
  }
  arb_clear(a);
  arb_clear(s);
  arb_mat_clear(T);
  arb_mat_clear(F);
  arb_mat_clear(P);
}

/* ||Y_{w[len-1]} ... Y_{w[0]}||_2 of the exact product of 2 x 2 doubles:
 * sigma_max^2 = (f + sqrt(f^2 - 4 det^2)) / 2, f = ||P||_F^2; and
 * prod ||Y_i||_F (doubles, for the tolerance) */
static void exact_norm2(arb_t out, const double *const *Y, const int *w, int len,
                        double *prodnorm) {
  arb_mat_t P, F, T;
  arb_mat_init(P, 2, 2);
  arb_mat_init(F, 2, 2);
  arb_mat_init(T, 2, 2);
  *prodnorm = 1;
  for (int k = 0; k < len; k++) {
    double f = 0;
    for (slong e = 0; e < 4; e++) {
      arb_set_d(arb_mat_entry(F, e / 2, e % 2), Y[w[k]][e]);
      f += Y[w[k]][e] * Y[w[k]][e];
    }
    *prodnorm *= sqrt(f);
    if (k == 0) {
      arb_mat_set(P, F);
    } else {
      arb_mat_mul(T, F, P, PREC);
      arb_mat_swap(T, P);
    }
  }
  arb_t f, d, t;
  arb_init(f);
  arb_init(d);
  arb_init(t);
  arb_zero(f);
  for (slong e = 0; e < 4; e++)
    arb_addmul(f, arb_mat_entry(P, e / 2, e % 2), arb_mat_entry(P, e / 2, e % 2), PREC);
  arb_mat_det(d, P, PREC);
  arb_mul(t, f, f, PREC);
  arb_mul(d, d, d, PREC);
  arb_submul_ui(t, d, 4, PREC);
  arb_sqrtpos(t, t, PREC);
  arb_add(t, t, f, PREC);
  arb_mul_2exp_si(t, t, -1);
  arb_sqrtpos(out, t, PREC);
  arb_clear(t);
  arb_clear(d);
  arb_clear(f);
  arb_mat_clear(T);
  arb_mat_clear(F);
  arb_mat_clear(P);
}

/* The 2-norm bound at every level of the word w of 2 x 2 matrices (pushed
 * already) against the exact norm; returns how many levels had the bound
 * without the product's error bound err_2 below the exact norm. */
static int check_word2(ss_jsr_ws *ws, const int *w, int len, const char *what) {
  int below = 0;
  arb_t ex;
  arb_init(ex);
  for (int k = 0; k < len; k++) {
    double pn;
    exact_norm2(ex, ws->Y, w, k + 1, &pn);
    const double up = ss_jsr_ws_norm_2_up(ws, k);
    /* the certificate's own slack (Gershgorin of W^T W, sigma_min(V), the
     * gamma_n terms) reaches about 65u relative on these inputs */
    const double tol = (double)(k + 1) * 128 * U;
    CHECK(d_ge(up, ex), "%s, level %d: the 2-norm bound %.17g is below the exact norm",
          what, k, up);
    CHECK(d_within(up, ex, tol, pn),
          "%s, level %d: the 2-norm bound %.17g is more than %g of prod ||Y_i||_F = %g "
          "above the exact norm",
          what, k, up, tol, pn);
    below += d_lt(up - ws->err_2[k], ex);
  }
  arb_clear(ex);
  return below;
}

/* Push the word w (len letters) through the workspace and check the bound at
 * every level against the exact norm; returns how many levels had the
 * floating-point norm with the relative allowance alone (no error bound)
 * below the exact one, and in *bare how many had the bare floating-point
 * norm below it. */
static int check_word(ss_jsr_ws *ws, const int *w, int len, const char *what, int *bare) {
  const size_t n = ws->n;
  int below = 0;
  arb_t ex;
  arb_init(ex);
  for (int k = 0; k < len; k++) {
    ss_jsr_ws_push(ws, k, (size_t)w[k]);
    double pn;
    exact_norm(ex, n, ws->Y, w, k + 1, &pn);
    const double up = ss_jsr_ws_norm_inf_up(ws, k);
    /* the bound's relative allowance (1 + 2 gamma_n)(1 + 8u)^2 and the
     * product's error (a few gamma_n per level, relative to prod ||Y_i||) */
    const double tol = (double)(k + 1) * (4 * (double)n + 24) * U;
    CHECK(d_ge(up, ex), "%s, level %d: the bound %.17g is below the exact norm", what, k,
          up);
    CHECK(d_within(up, ex, tol, pn),
          "%s, level %d: the bound %.17g is more than %g of "
          "prod ||Y_i|| = %g above the exact norm",
          what, k, up, tol, pn);
    const double rel_only = ss_jsr_up(ss_jsr_up(ws->nhat_inf[k] * (1 + 2 * ws->gam)));
    below += d_lt(rel_only, ex);
    *bare += d_lt(ws->nhat_inf[k], ex);
  }
  arb_clear(ex);
  return below;
}

/* 1. the inf-norm of a product from above */
static void test_norm_inf_up(void) {
  const double q = 0.75 * U;
  /* level 0: the row 1, 3u/4, 3u/4 sums to 1 in doubles, 1 + 3u/2 exactly */
  const double A[9] = {1, q, q, 0.5, 0.25, 0, 0, 0, 0.5};
  const double *Y1[1] = {A};
  ss_jsr_ws ws;
  int bare = 0;
  CHECK(ws_init(&ws, 1, 3, Y1, 4), "workspace");
  const int w1[3] = {0, 0, 0};
  check_word(&ws, w1, 3, "row 1, 3u/4, 3u/4", &bare);
  CHECK(bare >= 1,
        "the inputs must put the bare floating-point norm below the exact "
        "one at least once (%d)",
        bare);
  ss_jsr_ws_free(&ws);

  /* a product that cancels: A = [[x, y], [fl(x t), fl(y t)]] and
   * B = [[t, -1], [t, -1]]; B A is computed as 0 exactly (fl(t x) - fl(x t)),
   * while the exact B A has the entries t x - fl(x t), t y - fl(y t): the
   * rounding errors.  Only the product's error bound covers them. */
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 34);
  int below = 0, below2 = 0, cw = 0;
  bare = 0;
  for (int t = 0; t < 20; t++) {
    const double x = gsl_rng_uniform(rng) + 0.5, y = gsl_rng_uniform(rng) - 0.5;
    const double s = gsl_rng_uniform(rng) * 3 + 0.1;
    const double A2[4] = {x, y, x * s, y * s}, B2[4] = {s, -1, s, -1};
    const double *Y2[2] = {A2, B2};
    const int w2[3] = {0, 1, 0};
    CHECK(ws_init(&ws, 2, 2, Y2, 3), "workspace");
    char what[64];
    snprintf(what, sizeof what, "cancelling pair %d", t);
    below += check_word(&ws, w2, 3, what, &bare);
    below2 += check_word2(&ws, w2, 3, what);
    cw += ws.qvalid[1] && ws.qvalid[2]; /* the componentwise bound was formed */
    ss_jsr_ws_free(&ws);
  }
  CHECK(cw == 20,
        "the componentwise error bound must be formed for every cancelling pair "
        "(%d of 20)",
        cw);
  CHECK(below2 >= 10,
        "the cancelling pairs must put the 2-norm bound without the product's error "
        "bound below the exact norm (%d of 20)",
        below2);
  /* seeded random words of two 2 x 2 matrices, in both norms */
  for (int t = 0; t < 50; t++) {
    double A2[4], B2[4];
    for (int e = 0; e < 4; e++) {
      A2[e] = gsl_rng_uniform(rng) - 0.5;
      B2[e] = gsl_rng_uniform(rng) - 0.5;
    }
    const double *Y2[2] = {A2, B2};
    int w2[5];
    for (int k = 0; k < 5; k++)
      w2[k] = (int)gsl_rng_uniform_int(rng, 2);
    CHECK(ws_init(&ws, 2, 2, Y2, 5), "workspace");
    char what[64];
    snprintf(what, sizeof what, "random 2 x 2 word %d", t);
    check_word(&ws, w2, 5, what, &bare);
    check_word2(&ws, w2, 5, what);
    ss_jsr_ws_free(&ws);
  }
  CHECK(below >= 10,
        "the cancelling pairs must put the norm with its relative allowance below the "
        "exact one (%d of 20)",
        below);
  /* seeded random words of three 4 x 4 matrices, lengths up to 4 */
  const size_t n = 4;
  double *M = malloc(3 * n * n * sizeof *M);
  const double *Y[3] = {M, M + n * n, M + 2 * n * n};
  for (int t = 0; t < 50; t++) {
    for (size_t e = 0; e < 3 * n * n; e++)
      M[e] = gsl_rng_uniform(rng) - 0.5;
    CHECK(ws_init(&ws, 3, n, Y, 4), "workspace");
    int w[4];
    for (int k = 0; k < 4; k++)
      w[k] = (int)gsl_rng_uniform_int(rng, 3);
    char what[64];
    snprintf(what, sizeof what, "random word %d", t);
    check_word(&ws, w, 4, what, &bare);
    ss_jsr_ws_free(&ws);
  }
  free(M);
  gsl_rng_free(rng);
}

/* 2. the k-th root from above */
static void test_root_up(void) {
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 6);
  int low = 0;
  arb_t ex;
  arb_init(ex);
  for (int t = 0; t < 2000; t++) {
    const double x = exp(gsl_rng_uniform(rng) * 20 - 10);
    const int k = 1 + (int)gsl_rng_uniform_int(rng, 40);
    arb_set_d(ex, x);
    arb_root_ui(ex, ex, (ulong)k, PREC);
    const double up = ss_jsr_root_up(x, k);
    CHECK(d_ge(up, ex), "root_up(%.17g, %d) = %.17g below the exact root", x, k, up);
    const double r = pow(x, 1.0 / k);
    CHECK(d_within(up, ex, (8 + fabs(log(x))) * 2 * U + 4 * U, r),
          "root_up(%.17g, %d) = %.17g: more than its margin above the exact root", x, k,
          up);
    low += d_lt(r, ex);
  }
  arb_clear(ex);
  CHECK(low >= 100, "pow must fall below the exact root on some inputs (%d of 2000)",
        low);
  CHECK(ss_jsr_root_up(0, 3) == 0, "root of 0");
  gsl_rng_free(rng);
}

/* 3. the symmetry proof's margin: s_min 1 (mu0 = 1), gap g, distance d */
static void test_sym_margin(void) {
  const double gaps[3] = {2 * sin(3.14159265358979323846 / 2),
                          2 * sin(3.14159265358979323846 / 3),
                          2 * sin(3.14159265358979323846 / 8)};
  for (int i = 0; i < 3; i++) {
    const double g = gaps[i];
    for (int j = 0; j < 3; j++) {
      const double d = (double)j * 0.1 * g / 2; /* 0, 10%, 20% of the room */
      const double edge = (g / 2 - d) / (2 + g / 2);
      const double in = 0.99 * edge, out = 1.01 * edge;
      CHECK(ss_charmap_cert_sym_margin(d * d, in * in, 1.0, g),
            "gap %g, distance %g: an enclosure of %g (edge %g) must be accepted", g, d,
            in, edge);
      CHECK(!ss_charmap_cert_sym_margin(d * d, out * out, 1.0, g),
            "gap %g, distance %g: an enclosure of %g (edge %g) must be refused", g, d,
            out, edge);
      /* s_min scales the room: s_min 2 doubles the edge for d = 0 */
      if (j == 0)
        CHECK(ss_charmap_cert_sym_margin(0, 1.9 * edge * 1.9 * edge, 4.0, g) &&
                  !ss_charmap_cert_sym_margin(0, 2.1 * edge * 2.1 * edge, 4.0, g),
              "gap %g: s_min 2 must move the edge to twice %g", g, edge);
      /* a distance beyond the room is refused even with an exact basis */
      CHECK(!ss_charmap_cert_sym_margin(1.01 * g / 2 * 1.01 * g / 2, 0, 1.0, g),
            "gap %g: distance above g/2 must be refused", g);
    }
  }
  CHECK(!ss_charmap_cert_sym_margin(0, 0, -1e-30, 2), "a negative mu0: s_min 0, refused");
}

static ss_charmap_proven pv(size_t pos, size_t neg, size_t folded, size_t unknown) {
  ss_charmap_proven p = {pos + neg + folded + unknown, pos, neg, folded, unknown};
  return p;
}

/* 4. the fold-persistence rule, counts a cell from each side of its edges */
static void test_persists(void) {
  /* shares on 64 cells, shrink 1/2: before, bad = folded + unknown +
   * minority; now, bad = folded + minority */
  ss_charmap_proven Q = pv(40, 4, 4, 16), L; /* before: 24 of 64 may be bad */
  L = pv(50, 6, 6, 2);                       /* now: 12 of 64 proven bad */
  CHECK(ss_charmap_cert_persists(&Q, &L, 0.5), "12/64 >= 1/2 * 24/64: persists");
  L = pv(51, 6, 5, 2); /* 11 of 64 */
  CHECK(!ss_charmap_cert_persists(&Q, &L, 0.5),
        "11/64 < 1/2 * 24/64: the unknown cells before count as bad");
  L = pv(51, 6, 5, 2);
  Q = pv(40, 4, 4, 14); /* 22 of 62 may have been bad: 11/64 >= 11/62? no */
  CHECK(!ss_charmap_cert_persists(&Q, &L, 0.5), "11/64 < 1/2 * 22/62");
  Q = pv(42, 4, 4, 14); /* 22 of 64: 11/64 >= 11/64 */
  CHECK(ss_charmap_cert_persists(&Q, &L, 0.5), "11/64 >= 1/2 * 22/64 (the edge itself)");
  /* the unknown cells now do not count as bad now */
  L = pv(45, 6, 5, 8);
  CHECK(ss_charmap_cert_persists(&Q, &L, 0.5), "unknown now: still 11 of 64 proven bad");
  /* the majority now must beat the other sign and the unknown cells */
  Q = pv(50, 2, 2, 2);   /* 6 of 56 may be bad */
  L = pv(30, 10, 4, 20); /* 30 > 10 + 20? no */
  CHECK(!ss_charmap_cert_persists(&Q, &L, 0.5), "majority now 30 against 10 + 20");
  L = pv(31, 10, 4, 19); /* 31 > 29 */
  CHECK(ss_charmap_cert_persists(&Q, &L, 0.5), "majority now 31 against 10 + 19");
  L = pv(10, 31, 4, 19); /* the negative majority likewise */
  CHECK(ss_charmap_cert_persists(&Q, &L, 0.5),
        "negative majority now 31 against 10 + 19");
  L = pv(10, 30, 4, 20);
  CHECK(!ss_charmap_cert_persists(&Q, &L, 0.5),
        "negative majority now 30 against 10 + 20");
  /* the majority before likewise */
  L = pv(40, 10, 14, 0); /* 24 of 64 proven bad now */
  Q = pv(30, 10, 4, 20); /* 30 > 30? no */
  CHECK(!ss_charmap_cert_persists(&Q, &L, 0.5), "majority before 30 against 10 + 20");
  Q = pv(31, 10, 4, 19);
  CHECK(ss_charmap_cert_persists(&Q, &L, 0.5), "majority before 31 against 10 + 19");
  Q = pv(10, 30, 4, 20);
  CHECK(!ss_charmap_cert_persists(&Q, &L, 0.5),
        "neg. majority before 30 against 10 + 20");
  Q = pv(10, 31, 4, 19);
  CHECK(ss_charmap_cert_persists(&Q, &L, 0.5), "neg. majority before 31 against 10 + 19");
  /* nothing proven bad now: no fold is proven, whatever before was */
  L = pv(60, 0, 0, 4);
  Q = pv(64, 0, 0, 0);
  CHECK(!ss_charmap_cert_persists(&Q, &L, 0.5), "no proven bad cell now");
  CHECK(!ss_charmap_cert_persists(&Q, &L, 0.0), "no proven bad cell now, shrink 0");
}

int main(void) {
  test_norm_inf_up();
  test_root_up();
  test_sym_margin();
  test_persists();
  flint_cleanup();
  return ss_test_done("edges");
}
