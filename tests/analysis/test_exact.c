/* test_exact.c — the exact spectrum and the certified eigenvalue condition:
 *  - known spectra: the regular MLCA vertex is the tensor cube of the cubic
 *    B-spline curve's spectrum (two-ring and one-ring, every multiplicity
 *    derived here from the curve's), the tet/oct face's leading 1, 1/2 x3,
 *    1/4 x6, Catmull–Clark's subdominant closed form (a root of the reported
 *    irreducible polynomial, whose degree follows from the field it lies in);
 *  - proofs that tolerances cannot give: two eigenvalues 1e-12 apart are
 *    certified distinct (checked against an independent arb isolation) while
 *    the double path groups them; exact ties from symmetry (the MLCA edge of
 *    valence 8), from -lambda, from equal exact moduli of a complex pair; a
 *    tie that cannot be proven stays "not certified"; Jordan blocks within
 *    one block and across coupled blocks are defective, uncoupled copies are
 *    not; an irrational entry (Loop) is refused, naming the entry;
 *  - the exact spectrum does not change when a link is relabelled or
 *    mirrored;
 *  - the time per MLCA vertex case at k = 8, 10, 12 (printed).
 * The basis enclosure and the sweeps over every small link (the double
 * path's verdicts and rounding error bounds): test_exact_links.c. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_rng.h>

#include <flint/flint.h>
#include <flint/fmpq.h>
#include <flint/fmpz_poly.h>
#include <flint/fmpz_poly_factor.h>

#include "arb.h"
#include "arb_fmpz_poly.h"

#include "ss_exact.h"
#include "ss_link_random.h"
#include "ss_local.h"
#include "ss_test.h"
#include "ss_testcase.h"
#include "ss_testexact.h"
#include "ss_testlink.h"

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- tensor spectra ---- */

/* count[e] = how many triples of the curve's eigenvalues 2^-a multiply to
 * 2^-e (the spectrum of a tensor cube of a dyadic curve spectrum). */
static void tensor_cube(const int *expo, int ne, int *count, int maxe) {
  memset(count, 0, (size_t)(maxe + 1) * sizeof *count);
  for (int a = 0; a < ne; a++)
    for (int b = 0; b < ne; b++)
      for (int c = 0; c < ne; c++)
        count[expo[a] + expo[b] + expo[c]]++;
}

/* The exact spectrum is exactly {2^-e with multiplicity count[e]}. */
static void check_dyadic(const ss_exact *x, const int *count, int maxe,
                         const char *what) {
  size_t nr;
  const ss_exact_root *r = ss_exact_roots(x, &nr);
  int distinct = 0;
  for (int e = 0; e <= maxe; e++)
    distinct += count[e] > 0;
  CHECK(nr == (size_t)distinct, "%s: %zu distinct eigenvalues, expected %d", what, nr,
        distinct);
  char buf[64], want[64];
  for (size_t k = 0; k < nr; k++) {
    int e = 0;
    while (e <= maxe && ldexp(1.0, -e) != r[k].re)
      e++;
    CHECK(e <= maxe && r[k].im == 0.0 && r[k].rad == 0.0 && r[k].real && r[k].degree == 1,
          "%s: eigenvalue %.17g%+gi (rad %g, degree %d) is not a power 2^-e, e <= %d",
          what, r[k].re, r[k].im, r[k].rad, r[k].degree, maxe);
    if (e > maxe) continue;
    CHECK(r[k].mult == count[e], "%s: 2^-%d has multiplicity %d, expected %d", what, e,
          r[k].mult, count[e]);
    snprintf(want, sizeof want, e ? "%ld*x - 1" : "x - 1", 1L << e);
    CHECK(!strcmp(ss_exact_minpoly(x, k, buf, sizeof buf), want),
          "%s: minimal polynomial of 2^-%d is \"%s\", expected \"%s\"", what, e, buf,
          want);
  }
}

static void test_mlca_regular(void) {
  ss_scheme *s = ss_testcase_scheme("mlca");
  ss_link *oct = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_link_named("octahedron", &oct, &err), &err);
  ss_local *M;
  ss_exact *x;
  if (!ss_testexact_run(s, (ss_case){SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0}, &M, &x)) {
    /* the cubic B-spline curve: two-ring {1, 1/2, 1/4, 1/8, 1/8}, one-ring
     * {1, 1/2, 1/4} */
    const int two[5] = {0, 1, 2, 3, 3}, one[3] = {0, 1, 2};
    int count[10];
    tensor_cube(two, 5, count, 9);
    CHECK(M->n2 == 125 && count[1] == 3 && count[2] == 6 && count[3] == 13,
          "regular MLCA: n = %zu, tensor cube 1/2 x%d, 1/4 x%d, 1/8 x%d", M->n2, count[1],
          count[2], count[3]);
    check_dyadic(x, count, 9, "regular MLCA two-ring");
    /* the rational matrix: within 2^-40 of S, rows summing to exactly 1 */
    int near = 1, sums = 1;
    fmpq_t sum, t;
    fmpq_init(sum);
    fmpq_init(t);
    for (size_t i = 0; i < M->n2; i++) {
      fmpq_zero(sum);
      for (size_t j = 0; j < M->n2; j++) {
        long long p, q;
        near &= ss_exact_entry(x, i, j, &p, &q) && q > 0 &&
                fabs((double)p / (double)q - M->S[i * M->n2 + j]) <= 0x1p-40;
        fmpq_set_si(t, p, (ulong)q);
        fmpq_add(sum, sum, t);
      }
      sums &= fmpq_is_one(sum);
    }
    long long p, q;
    CHECK(near && sums && !ss_exact_entry(x, M->n2, 0, &p, &q),
          "regular MLCA: rational entries near S %d, rows sum to 1 %d", near, sums);
    fmpq_clear(sum);
    fmpq_clear(t);
    CHECK(ss_testexact_verdict_is(x, SS_PASS, 1), "regular MLCA: %s",
          ss_testexact_reason(x).s);
    /* the one-ring block alone */
    const size_t n1 = M->n1;
    double *A = malloc(n1 * n1 * sizeof *A);
    for (size_t i = 0; i < n1; i++)
      for (size_t j = 0; j < n1; j++)
        A[i * n1 + j] = M->S[i * M->n2 + j];
    ss_exact *xa = NULL;
    ss_exact_opts o = ss_exact_defaults(3);
    if (!ss_exact_new(A, n1, n1, &o, &xa, &err)) {
      tensor_cube(one, 3, count, 6);
      CHECK(n1 == 27 && count[3] == 7, "one-ring: %zu points, 1/8 x%d", n1, count[3]);
      check_dyadic(xa, count, 6, "regular MLCA one-ring");
    } else {
      CHECK(0, "one-ring: %s", err.msg);
    }
    ss_exact_free(xa);
    free(A);
    ss_exact_free(x);
    ss_local_free(M);
  }
  ss_link_free(oct);
  ss_scheme_free(s);
}

static void test_tetoct_face(void) {
  ss_scheme *s = ss_testcase_scheme("tetoct");
  ss_local *M;
  ss_exact *x;
  if (!ss_testexact_run(s, (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, &M, &x)) {
    const double want[10] = {1, .5, .5, .5, .25, .25, .25, .25, .25, .25};
    for (int i = 0; i < 10; i++) {
      const ss_exact_root *r = ss_testexact_lambda(x, i);
      CHECK(r && r->re == want[i] && r->im == 0.0 && r->degree == 1 && r->rad == 0.0,
            "tet/oct face: lambda%d = %.17g, expected %g exactly", i,
            r ? r->re : (double)NAN, want[i]);
    }
    CHECK(ss_testexact_lambda(x, 10) && ss_testexact_lambda(x, 10)->re < 0.25,
          "tet/oct face: 1/4 more than x6");
    CHECK(ss_testexact_verdict_is(x, SS_PASS, 1), "tet/oct face: %s",
          ss_testexact_reason(x).s);
    ss_exact_free(x);
    ss_local_free(M);
  }
  ss_scheme_free(s);
}

/* ---- ties from symmetry ---- */

static void test_ties(void) {
  ss_scheme *mlca = ss_testcase_scheme("mlca"), *to = ss_testcase_scheme("tetoct");
  ss_local *M;
  ss_exact *x;
  /* finding 2: along an MLCA edge of valence 8, lambda3 = lambda4 = 1/2 */
  if (!ss_testexact_run(mlca, (ss_case){SS_CASE_EDGE, NULL, 8, SS_DIAG_BFS, 0}, &M, &x)) {
    CHECK(ss_testexact_verdict_is(x, SS_FAIL, 1) &&
              strstr(ss_testexact_reason(x).s, "exact tie"),
          "MLCA edge 8: expected a certified exact tie, got %s",
          ss_testexact_reason(x).s);
    const ss_exact_root *l3 = ss_testexact_lambda(x, 3), *l4 = ss_testexact_lambda(x, 4);
    CHECK(l3 == l4 && l3 && l3->re == 0.5 && l3->degree == 1 && l3->mult >= 2,
          "MLCA edge 8: lambda3 = %g is not lambda4 = 1/2 exactly",
          l3 ? l3->re : (double)NAN);
    CHECK(ss_testexact_lambda(x, 1) == ss_testexact_lambda(x, 2) &&
              ss_testexact_lambda(x, 1)->mult == 2,
          "MLCA edge 8: lambda1 = lambda2 should be one root of multiplicity 2");
    ss_exact_free(x);
    ss_local_free(M);
  }
  /* lambda1 = lambda2 (a double root of one factor), certified passes */
  struct {
    ss_scheme *s;
    ss_case c;
  } dbl[3] = {{mlca, {SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0}},
              {to, {SS_CASE_EDGE, NULL, 6, SS_DIAG_BFS, 0}},
              {to, {SS_CASE_EDGE, NULL, 8, SS_DIAG_BFS, 0}}};
  for (int i = 0; i < 3; i++) {
    if (ss_testexact_run(dbl[i].s, dbl[i].c, &M, &x)) continue;
    const ss_exact_root *l1 = ss_testexact_lambda(x, 1);
    CHECK(l1 == ss_testexact_lambda(x, 2) && l1->mult == 2 &&
              l1 != ss_testexact_lambda(x, 3),
          "%s edge %d: lambda1 = lambda2 of multiplicity %d", ss_scheme_name(dbl[i].s),
          dbl[i].c.n, l1->mult);
    CHECK(ss_testexact_verdict_is(x, SS_PASS, 1), "%s edge %d: %s",
          ss_scheme_name(dbl[i].s), dbl[i].c.n, ss_testexact_reason(x).s);
    ss_exact_free(x);
    ss_local_free(M);
  }
  ss_scheme_free(mlca);
  ss_scheme_free(to);
}

/* ---- Catmull–Clark: the subdominant closed form ---- */

/* Parse a polynomial as ss_exact_minpoly writes it ("8*x^2 - 6*x + 1").
 * Returns 0, or -1 if the text is not of that form. */
static int parse_poly(const char *s, fmpz_poly_t f) {
  fmpz_poly_zero(f);
  fmpz_t c, old;
  fmpz_init(c);
  fmpz_init(old);
  int sign = 1, rc = 0, terms = 0;
  char digits[400];
  while (*s && !rc) {
    if (*s == ' ') {
      s++;
      continue;
    }
    if (*s == '-' || *s == '+') {
      sign = *s++ == '-' ? -1 : 1;
      continue;
    }
    size_t nd = 0;
    while (isdigit((unsigned char)*s) && nd + 1 < sizeof digits)
      digits[nd++] = *s++;
    digits[nd] = '\0';
    if (nd) {
      fmpz_set_str(c, digits, 10);
      if (*s == '*') s++;
    } else {
      fmpz_one(c);
    }
    long k = 0;
    if (*s == 'x') {
      k = 1;
      if (*++s == '^') k = strtol(s + 1, (char **)&s, 10);
    } else if (!nd) {
      rc = -1;
    }
    if (sign < 0) fmpz_neg(c, c);
    fmpz_poly_get_coeff_fmpz(old, f, k);
    fmpz_add(c, c, old);
    fmpz_poly_set_coeff_fmpz(f, k, c);
    sign = 1;
    terms++;
  }
  fmpz_clear(c);
  fmpz_clear(old);
  return rc || !terms ? -1 : 0;
}

static void test_catmull_clark(void) {
  ss_scheme *cc = ss_testcase_scheme("catmull-clark");
  /* degree of (5 + cos(2 pi/n) + cos(pi/n) sqrt(2 (9 + cos(2 pi/n))))/16 over Q:
   * n = 4: 1/2; n = 3, 6: (9 + sqrt 17)/32, (11 + sqrt 57)/32; n = 5, 8: a
   * square root over Q(sqrt 5), Q(sqrt 2) (cos(pi/8) = sqrt(2 + sqrt 2)/2);
   * n = 7: a square root over the cubic field Q(cos(2 pi/7)) */
  const int degree[9] = {0, 0, 0, 2, 1, 4, 2, 6, 4};
  for (int n = 3; n <= 8; n++) {
    ss_local *M;
    ss_exact *x;
    if (ss_testexact_run(cc, (ss_case){SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0},
                         &M, &x))
      continue;
    CHECK(ss_testexact_verdict_is(x, SS_PASS, 1), "Catmull-Clark %d: %s", n,
          ss_testexact_reason(x).s);
    const ss_exact_root *l1 = ss_testexact_lambda(x, 1);
    CHECK(l1 == ss_testexact_lambda(x, 2) && l1->mult == 2 && l1->real,
          "Catmull-Clark %d: lambda1 = lambda2, multiplicity %d", n, l1->mult);
    /* the closed form, in balls */
    const long prec = 256;
    arb_t c2, c1, t, cf, v;
    arb_init(c2);
    arb_init(c1);
    arb_init(t);
    arb_init(cf);
    arb_init(v);
    fmpq_t q;
    fmpq_init(q);
    fmpq_set_si(q, 2, (ulong)n);
    arb_cos_pi_fmpq(c2, q, prec);
    fmpq_set_si(q, 1, (ulong)n);
    arb_cos_pi_fmpq(c1, q, prec);
    arb_add_ui(t, c2, 9, prec);
    arb_mul_ui(t, t, 2, prec);
    arb_sqrt(t, t, prec);
    arb_mul(t, t, c1, prec);
    arb_add(cf, t, c2, prec);
    arb_add_ui(cf, cf, 5, prec);
    arb_div_ui(cf, cf, 16, prec);
    /* the enclosure contains it */
    arb_set_d(v, l1->re);
    arb_add_error_2exp_si(v, -1074);
    mag_t rad;
    mag_init(rad);
    mag_set_d(rad, l1->rad);
    arb_add_error_mag(v, rad);
    mag_clear(rad);
    CHECK(arb_overlaps(v, cf),
          "Catmull-Clark %d: %.17g +- %g misses the closed form %.17g", n, l1->re,
          l1->rad, arf_get_d(arb_midref(cf), ARF_RND_NEAR));
    CHECK(l1->rad < 1e-15, "Catmull-Clark %d: radius %g", n, l1->rad);
    /* the closed form is a root of the reported polynomial, which is
     * irreducible of the expected degree: so it is its minimal polynomial */
    char buf[2048];
    fmpz_poly_t f;
    fmpz_poly_init(f);
    size_t nr;
    const ss_exact_root *r0 = ss_exact_roots(x, &nr);
    ss_exact_minpoly(x, (size_t)(l1 - r0), buf, sizeof buf);
    if (!parse_poly(buf, f)) {
      fmpz_poly_factor_t fac;
      fmpz_poly_factor_init(fac);
      fmpz_poly_factor(fac, f);
      CHECK(fac->num == 1 && fac->exp[0] == 1 && fmpz_poly_degree(f) == degree[n] &&
                l1->degree == degree[n],
            "Catmull-Clark %d: minimal polynomial %s (degree %d, reported %d), expected "
            "irreducible of degree %d",
            n, buf, (int)fmpz_poly_degree(f), l1->degree, degree[n]);
      fmpz_poly_factor_clear(fac);
      arb_fmpz_poly_evaluate_arb(v, f, cf, prec);
      CHECK(arb_contains_zero(v),
            "Catmull-Clark %d: %s does not vanish at the closed form", n, buf);
    } else {
      CHECK(0, "Catmull-Clark %d: cannot read the polynomial \"%s\"", n, buf);
    }
    fmpz_poly_clear(f);
    fmpq_clear(q);
    arb_clear(c2);
    arb_clear(c1);
    arb_clear(t);
    arb_clear(cf);
    arb_clear(v);
    ss_exact_free(x);
    ss_local_free(M);
  }
  ss_scheme_free(cc);
}

/* ---- built matrices ---- */

/* S (n x n, row-major) from the strictly given entries of rows 1..n-1 and
 * row 0 = e0; column 0 takes 1 - (the rest of the row), so rows sum to 1. */
static void fill_rows(double *S, size_t n) {
  S[0] = 1.0;
  for (size_t j = 1; j < n; j++)
    S[j] = 0.0;
  for (size_t i = 1; i < n; i++) {
    double s = 0.0;
    for (size_t j = 1; j < n; j++)
      s += S[i * n + j];
    S[i * n] = 1.0 - s;
  }
}

/* Two eigenvalues 2^-40 apart: outer nodes 1..5 a cycle of weight w = 2^-17
 * (row i reads node i + 1), diagonal 1/2 on nodes 1 and 2.  The outer block's
 * characteristic polynomial is (x - 1/2)^2 x^3 - w^5, with two roots
 * 1/2 +- 2^-41 (1 + O(2^-40)). */
static void near_tie_matrix(double *S) {
  const size_t n = 6;
  memset(S, 0, n * n * sizeof *S);
  for (size_t i = 1; i <= 5; i++)
    S[i * n + (i % 5) + 1] = ldexp(1.0, -17);
  S[1 * n + 1] = S[2 * n + 2] = 0.5;
  fill_rows(S, n);
}

static void test_near_tie(void) {
  const size_t n = 6;
  double S[36];
  near_tie_matrix(S);
  /* independently: 2^83 (2x - 1)^2 x^3 - 1, isolated by arb */
  fmpz_poly_t f, g;
  fmpz_poly_init(f);
  fmpz_poly_init(g);
  fmpz_poly_set_coeff_si(g, 1, 2);
  fmpz_poly_set_coeff_si(g, 0, -1);
  fmpz_poly_mul(f, g, g);
  fmpz_poly_shift_left(f, f, 3);
  fmpz_t c;
  fmpz_init(c);
  fmpz_one(c);
  fmpz_mul_2exp(c, c, 83);
  fmpz_poly_scalar_mul_fmpz(f, f, c);
  fmpz_poly_set_coeff_si(g, 1, 0);
  fmpz_poly_set_coeff_si(g, 0, 1);
  fmpz_poly_sub(f, f, g);
  fmpz_poly_derivative(g, f);
  fmpz_poly_gcd(g, f, g);
  CHECK(fmpz_poly_degree(g) == 0, "near tie: the test polynomial is not squarefree");
  acb_ptr z = _acb_vec_init(5);
  arb_fmpz_poly_complex_roots(z, f, 0, 256);
  /* the two largest real roots (real roots come first, ascending) */
  int nreal = 0;
  for (int i = 0; i < 5; i++)
    nreal += acb_is_real(z + i);
  arb_t gap;
  arb_init(gap);
  arb_sub(gap, acb_realref(z + nreal - 1), acb_realref(z + nreal - 2), 256);
  const double gapd = arf_get_d(arb_midref(gap), ARF_RND_NEAR);
  CHECK(nreal >= 2 && gapd > 8e-13 && gapd < 1e-12, "near tie: gap %g", gapd);
  for (int variant = 0; variant < 2; variant++) {
    /* in an outer block (n1 = 1) and in the one-ring block (n1 = n) */
    const size_t n1 = variant ? n : 1;
    ss_error err = {0};
    ss_exact *x = NULL;
    ss_exact_opts o = ss_exact_defaults(2);
    if (ss_exact_new(S, n, n1, &o, &x, &err)) {
      CHECK(0, "near tie: %s", err.msg);
      continue;
    }
    const ss_exact_root *l1 = ss_testexact_lambda(x, 1), *l2 = ss_testexact_lambda(x, 2);
    CHECK(
        l1 != l2 && l1->mult == 1 && l2->mult == 1 && l1->real && l2->real &&
            l1->re - l1->rad > l2->re + l2->rad,
        "near tie (n1 = %zu): lambda1 = %.17g +- %g, lambda2 = %.17g +- %g not separated",
        n1, l1->re, l1->rad, l2->re, l2->rad);
    arb_t b;
    arb_init(b);
    arb_set_d(b, l1->re);
    arb_add_error_2exp_si(b, -60);
    CHECK(arb_overlaps(b, acb_realref(z + nreal - 1)), "near tie: lambda1 misplaced");
    arb_set_d(b, l2->re);
    arb_add_error_2exp_si(b, -60);
    CHECK(arb_overlaps(b, acb_realref(z + nreal - 2)), "near tie: lambda2 misplaced");
    arb_clear(b);
    CHECK(ss_testexact_verdict_is(x, SS_PASS, 1), "near tie (n1 = %zu): %s", n1,
          ss_testexact_reason(x).s);
    double lo[12], hi[12];
    ss_status st = ss_exact_basis(x, lo, hi, &err);
    if (variant == 0) {
      CHECK(st == SS_ENUMERIC && strstr(err.msg, "outer block"),
            "near tie in an outer block: basis status %d (%s)", st, err.msg);
    } else {
      CHECK(st == SS_OK, "near tie in the one-ring: basis: %s", err.msg);
      /* S X = X diag(lambda1, lambda2) to rounding, X of full rank */
      double res = 0.0;
      for (int j = 0; j < 2 && !st; j++) {
        const double lj = j ? l2->re : l1->re;
        for (size_t i = 0; i < n; i++) {
          double s = -lj * 0.5 * (lo[j * 6 + i] + hi[j * 6 + i]);
          for (size_t k = 0; k < n; k++)
            s += S[i * n + k] * 0.5 * (lo[j * 6 + k] + hi[j * 6 + k]);
          res = fmax(res, fabs(s));
        }
      }
      CHECK(res < 1e-13, "near tie: |S X - X J| = %g", res);
    }
    ss_exact_free(x);
    /* the double path cannot tell them apart at its tolerance */
    ss_eig *e = NULL;
    ss_eig_opts eo = ss_eig_defaults(2);
    eo.basis = 0;
    if (!ss_eig_new(S, n, n1, &eo, &e, &err)) {
      CHECK(e->val[1].group == e->val[2].group && e->val[1].mult == 2,
            "near tie: ss_eig (tol %g) keeps %.17g and %.17g apart", eo.tol, e->val[1].re,
            e->val[2].re);
    } else {
      CHECK(0, "near tie: ss_eig: %s", err.msg);
    }
    ss_eig_free(e);
  }
  arb_clear(gap);
  _acb_vec_clear(z, 5);
  fmpz_clear(c);
  fmpz_poly_clear(f);
  fmpz_poly_clear(g);
}

/* Verdict of a built matrix (n x n, entries given in rows 1..n-1). */
static ss_exact *built(double *S, size_t n, size_t n1, int dim, long maxprec) {
  fill_rows(S, n);
  ss_exact_opts o = ss_exact_defaults(dim);
  if (maxprec) o.maxprec = maxprec;
  ss_exact *x = NULL;
  ss_error err = {0};
  if (ss_exact_new(S, n, n1, &o, &x, &err)) CHECK(0, "built matrix: %s", err.msg);
  return x;
}

static void test_jordan(void) {
  enum { n = 5 };
  double S[n * n];
  /* nodes 1, 2 of eigenvalue 1/2, node 3 of 1/3, node 4 of 1/8 */
  const double coupling[4][3] = {
      /* S[1][2], S[1][3], S[3][2] */
      {0.25, 0.0, 0.0},   /* direct Jordan chain: defective */
      {0.0, 0.25, 0.125}, /* a chain through node 3: defective */
      {0.0, 0.25, 0.0},   /* 1 reads 3, 3 does not read 2: not coupled */
      {0.0, 0.0, 0.0},    /* diagonal */
  };
  const int defective[4] = {1, 1, 0, 0};
  for (int v = 0; v < 4; v++)
    for (int n1 = 1; n1 <= n; n1 += n - 1) { /* 1x1 outer blocks, or one block */
      memset(S, 0, sizeof S);
      S[1 * n + 1] = S[2 * n + 2] = 0.5;
      S[3 * n + 3] = 1.0 / 3.0;
      S[4 * n + 4] = 0.125;
      S[1 * n + 2] = coupling[v][0];
      S[1 * n + 3] = coupling[v][1];
      S[3 * n + 2] = coupling[v][2];
      ss_exact *x = built(S, n, (size_t)n1, 3, 0);
      if (!x) continue;
      if (defective[v])
        CHECK(ss_testexact_verdict_is(x, SS_FAIL, 1) &&
                  strstr(ss_testexact_reason(x).s, "defective"),
              "Jordan case %d (n1 = %d): expected a certified defective fail, got %s", v,
              n1, ss_testexact_reason(x).s);
      else
        CHECK(ss_testexact_verdict_is(x, SS_PASS, 1),
              "diagonalisable case %d (n1 = %d): %s", v, n1, ss_testexact_reason(x).s);
      ss_exact_free(x);
    }
}

/* Exact ties and fails that only a proof can state, and one it cannot. */
static void test_built_ties(void) {
  double S[49];
  ss_exact *x;
  /* lambda2 = 1/2 and -1/2: |lambda3| = lambda2 */
  memset(S, 0, sizeof S);
  S[1 * 4 + 1] = 0.625, S[2 * 4 + 2] = 0.5, S[3 * 4 + 3] = -0.5;
  if ((x = built(S, 4, 1, 2, 0))) {
    CHECK(ss_testexact_verdict_is(x, SS_FAIL, 1) &&
              strstr(ss_testexact_reason(x).s, "exact tie"),
          "-lambda2: expected an exact tie, got %s", ss_testexact_reason(x).s);
    ss_exact_free(x);
  }
  /* +- sqrt(1/8) from [0 1/2; 1/4 0] (x^2 - 1/8, irrational): only the
   * reflection f(-x) = f(x) proves |lambda3| = lambda2 */
  memset(S, 0, sizeof S);
  S[1 * 4 + 1] = 0.625, S[2 * 4 + 3] = 0.5, S[3 * 4 + 2] = 0.25;
  if ((x = built(S, 4, 1, 2, 0))) {
    CHECK(ss_testexact_verdict_is(x, SS_FAIL, 1) &&
              strstr(ss_testexact_reason(x).s, "exact tie"),
          "+-sqrt(1/8): expected an exact tie, got %s", ss_testexact_reason(x).s);
    const ss_exact_root *l2 = ss_testexact_lambda(x, 2), *l3 = ss_testexact_lambda(x, 3);
    CHECK(l2 && l3 && l2->tied_next && l2->degree == 2 && l2->re > 0.0 && l3->re < 0.0,
          "+-sqrt(1/8): lambda2 = %g (tied %d), lambda3 = %g", l2 ? l2->re : 0.0,
          l2 ? l2->tied_next : -1, l3 ? l3->re : 0.0);
    ss_exact_free(x);
  }
  /* lambda2 = 1/2 and the complex pair (-1 +- i sqrt 3)/4 of x^3 = 1/8:
   * equal exact moduli (the pair's |z|^2 = 1/4) */
  memset(S, 0, sizeof S);
  S[1 * 5 + 1] = 0.625;
  S[2 * 5 + 3] = S[3 * 5 + 4] = 1.0, S[4 * 5 + 2] = 0.125;
  if ((x = built(S, 5, 1, 2, 0))) {
    CHECK(ss_testexact_verdict_is(x, SS_FAIL, 1) &&
              strstr(ss_testexact_reason(x).s, "exact tie"),
          "cube roots of 1/8: expected an exact tie, got %s", ss_testexact_reason(x).s);
    size_t nr;
    const ss_exact_root *r = ss_exact_roots(x, &nr);
    CHECK(nr == 5 && r[2].re == 0.5 && r[2].tied_next && r[3].tied_next &&
              !r[4].tied_next,
          "cube roots of 1/8: the three should be tied");
    ss_exact_free(x);
  }
  /* x^3 = 2/27: the real root and the complex pair have equal moduli, which
   * none of the proofs (conjugates, -z, exact |z|^2) shows: not certified */
  S[4 * 5 + 2] = 2.0 / 27.0;
  if ((x = built(S, 5, 1, 2, 512))) {
    CHECK(ss_testexact_verdict_is(x, SS_UNDECIDED, 0) &&
              !strncmp(ss_testexact_reason(x).s, "not certified: ", 15) &&
              strstr(ss_testexact_reason(x).s, "512 bits"),
          "cube roots of 2/27: expected not certified at 512 bits, got %s",
          ss_testexact_reason(x).s);
    size_t nr;
    const ss_exact_root *r = ss_exact_roots(x, &nr);
    CHECK(nr == 5 && r[2].degree == 3, "cube roots of 2/27: %zu roots", nr);
    /* the conjugate pair is proven tied, the real root to it is not */
    int pair = 0;
    for (size_t k = 0; k + 1 < nr; k++)
      pair += !r[k].real && !r[k + 1].real && r[k].tied_next && r[k].im > 0.0;
    CHECK(pair == 1 && !r[1].tied_next && r[2].degree == 3,
          "cube roots of 2/27: conjugates tied %d", pair);
    ss_exact_free(x);
  }
  /* an eigenvalue -1 or a primitive cube root of unity beside lambda0 */
  memset(S, 0, sizeof S);
  S[1 * 4 + 1] = -1.0;
  if ((x = built(S, 4, 1, 2, 0))) {
    CHECK(ss_testexact_verdict_is(x, SS_FAIL, 1) &&
              strstr(ss_testexact_reason(x).s, "modulus 1"),
          "-1: %s", ss_testexact_reason(x).s);
    ss_exact_free(x);
  }
  memset(S, 0, sizeof S); /* [0 1; -1 -1]: x^2 + x + 1 */
  S[1 * 5 + 2] = 1.0, S[2 * 5 + 1] = S[2 * 5 + 2] = -1.0, S[3 * 5 + 3] = 0.5;
  if ((x = built(S, 5, 1, 2, 0))) {
    CHECK(ss_testexact_verdict_is(x, SS_FAIL, 1) &&
              strstr(ss_testexact_reason(x).s, "modulus 1"),
          "unity: %s", ss_testexact_reason(x).s);
    ss_exact_free(x);
  }
  /* lambda0 = 1 twice */
  memset(S, 0, sizeof S);
  S[1 * 4 + 1] = 1.0, S[2 * 4 + 2] = 0.5, S[3 * 4 + 3] = 0.25;
  if ((x = built(S, 4, 1, 2, 0))) {
    CHECK(ss_testexact_verdict_is(x, SS_FAIL, 1) &&
              strstr(ss_testexact_reason(x).s, "not simple"),
          "1 twice: %s", ss_testexact_reason(x).s);
    ss_exact_free(x);
  }
}

/* ---- refused input ---- */

static void test_refused(void) {
  long long p, q;
  CHECK(ss_exact_rational(1.0 / 3.0, 1L << 18, &p, &q) && p == 1 && q == 3, "1/3");
  CHECK(ss_exact_rational(-0.1, 1L << 18, &p, &q) && p == -1 && q == 10, "-1/10");
  CHECK(ss_exact_rational(0.0, 1L << 18, &p, &q) && p == 0 && q == 1, "0");
  CHECK(!ss_exact_rational(3.14159265358979323846, 1L << 18, &p, &q),
        "pi accepted as %lld/%lld", p, q);
  CHECK(!ss_exact_rational(NAN, 1L << 18, &p, &q), "NaN accepted");
  CHECK(!ss_exact_rational(1.0 / 3.0 + 1e-11, 1L << 18, &p, &q), "1/3 + 1e-11 accepted");
  /* every p/q with q <= maxden comes back, however it was rounded */
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 7);
  int bad = 0;
  for (int t = 0; t < 2000; t++) {
    long long qq = 1 + (long long)gsl_rng_uniform_int(rng, 1UL << 18);
    long long pp = (long long)gsl_rng_uniform_int(rng, (unsigned long)(2 * qq)) - qq;
    double s = (double)pp / (double)qq;
    long long g = pp < 0 ? -pp : pp, h = qq;
    while (h) {
      long long r = g % h;
      g = h, h = r;
    }
    bad += !ss_exact_rational(s, 1L << 18, &p, &q) || p * g != pp || q * g != qq;
  }
  CHECK(bad == 0, "%d of 2000 random rationals not recovered", bad);
  gsl_rng_free(rng);
  /* Loop's weights are irrational: refused, naming the entry */
  ss_scheme *loop = ss_testcase_scheme("loop");
  ss_local *M = NULL;
  ss_error err = {0};
  ss_case c = {SS_CASE_SURFACE_VERTEX, NULL, 5, SS_DIAG_BFS, 0};
  if (!ss_local_new(loop, &c, &M, &err)) {
    ss_exact *x = NULL;
    ss_exact_opts o = ss_exact_defaults(2);
    ss_status st = ss_exact_new(M->S, M->n2, M->n1, &o, &x, &err);
    CHECK(st == SS_ENUMERIC && x == NULL && strstr(err.msg, "S[") &&
              strstr(err.msg, "not a rational"),
          "Loop 5: status %d (%s)", st, err.msg);
    ss_exact_free(x);
  } else {
    CHECK(0, "Loop 5: %s", err.msg);
  }
  ss_local_free(M);
  ss_scheme_free(loop);
  /* a row that does not sum to 1, a non-invariant one-ring, options */
  double S[9] = {1, 0, 0, 0.25, 0.5, 0.24, 0, 0, 1}; /* row 1: 99/100 */
  ss_exact *x = NULL;
  ss_exact_opts o = ss_exact_defaults(2);
  CHECK(ss_exact_new(S, 3, 1, &o, &x, &err) == SS_ENUMERIC && strstr(err.msg, "row 1"),
        "row sum: %s", err.msg);
  S[5] = 0.25;
  S[1] = 0.5, S[0] = 0.5;
  CHECK(ss_exact_new(S, 3, 1, &o, &x, &err) == SS_EINPUT, "not invariant: %s", err.msg);
  S[1] = 0.0, S[0] = 1.0;
  CHECK(ss_exact_new(S, 3, 0, &o, &x, &err) == SS_EINPUT, "n1 = 0");
  o.maxprec = 16;
  CHECK(ss_exact_new(S, 3, 1, &o, &x, &err) == SS_EINPUT, "maxprec < prec");
  /* a block beyond max_block: undecided, not a failure */
  o = ss_exact_defaults(2);
  o.max_block = 1;
  S[4] = 0.25, S[5] = 0.5; /* nodes 1, 2 one component */
  S[7] = 0.5, S[8] = 0.25, S[6] = 0.25;
  if (ss_exact_new(S, 3, 1, &o, &x, &err) == SS_OK) {
    CHECK(ss_testexact_verdict_is(x, SS_UNDECIDED, 0) &&
              strstr(ss_testexact_reason(x).s, "exceeds"),
          "max_block: %s", ss_testexact_reason(x).s);
    size_t nr;
    ss_exact_roots(x, &nr);
    CHECK(nr == 0, "max_block: %zu roots", nr);
    ss_exact_free(x);
  } else {
    CHECK(0, "max_block: %s", err.msg);
  }
}

/* ---- relabelling ---- */

/* The exact spectrum as text: minimal polynomial and multiplicity per root,
 * in order.  Caller frees. */
static char *spectrum_text(const ss_exact *x) {
  size_t nr, len = 1, cap = 4096;
  const ss_exact_root *r = ss_exact_roots(x, &nr);
  char *s = malloc(cap), buf[4096];
  s[0] = '\0';
  for (size_t k = 0; k < nr; k++) {
    int w =
        snprintf(buf, sizeof buf, "%s x%d%s; ", ss_exact_minpoly(x, k, buf + 2048, 2048),
                 r[k].mult, r[k].tied_next ? " =" : "");
    if (len + (size_t)w >= cap) s = realloc(s, cap = 2 * (cap + (size_t)w));
    strcat(s, buf);
    len += (size_t)w;
  }
  return s;
}

static void test_relabel(void) {
  ss_scheme *s = ss_testcase_scheme("mlca");
  ss_link *l = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(
      ss_link_parse("8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb", &l, &err), &err);
  ss_local *M;
  ss_exact *x;
  if (!ss_testexact_run(s, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, &M, &x)) {
    char *ref = spectrum_text(x), small[16];
    ss_exact_minpoly(x, 1, small, sizeof small); /* degree 10: does not fit */
    CHECK(strlen(small) == 15 && !strcmp(small + 12, "..."), "truncated minpoly \"%s\"",
          small);
    for (int t = 0; t < 4; t++) {
      ss_link *q = ss_testlink_scrambled(l, 11u + (unsigned)t, t & 1);
      ss_local *M2;
      ss_exact *x2;
      if (q && !ss_testexact_run(s, (ss_case){SS_CASE_VERTEX, q, 0, SS_DIAG_BFS, 0}, &M2,
                                 &x2)) {
        char *got = spectrum_text(x2);
        CHECK(!strcmp(ref, got),
              "relabelled (seed %d, mirror %d): spectrum differs:\n%s\n%s", 11 + t, t & 1,
              ref, got);
        CHECK(ss_testexact_verdict_is(x2, SS_PASS, 1), "relabelled: %s",
              ss_testexact_reason(x2).s);
        free(got);
        ss_exact_free(x2);
        ss_local_free(M2);
      }
      ss_link_free(q);
    }
    free(ref);
    ss_exact_free(x);
    ss_local_free(M);
  }
  ss_link_free(l);
  ss_scheme_free(s);
}

/* ---- timing ---- */

static void test_timing(void) {
  ss_scheme *s = ss_testcase_scheme("mlca");
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 1);
  for (int k = 8; k <= 12; k += 2) {
    ss_link *l = NULL;
    ss_error err = {0};
    if (ss_link_random(k, rng, &l, &err)) {
      CHECK(0, "random link k = %d: %s", k, err.msg);
      continue;
    }
    ss_local *M = NULL;
    ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
    if (!ss_local_new(s, &c, &M, &err)) {
      ss_exact_opts o = ss_exact_defaults(3);
      ss_exact *x = NULL;
      double t0 = now();
      ss_status st = ss_exact_new(M->S, M->n2, M->n1, &o, &x, &err);
      double t1 = now();
      CHECK(st == SS_OK, "k = %d: %s", k, err.msg);
      if (!st) {
        ss_verdict v;
        int cert;
        ss_exact_condition(x, &v, &cert);
        size_t nr;
        ss_exact_roots(x, &nr);
        printf("exact: MLCA vertex k = %d (random link, n = %zu, n1 = %zu): %.3f s, %zu "
               "distinct eigenvalues, %s%s%s\n",
               k, M->n2, M->n1, t1 - t0, nr, ss_verdict_name(v.verdict),
               cert ? " (certified)" : "", v.reason);
      }
      ss_exact_free(x);
    }
    ss_local_free(M);
    ss_link_free(l);
  }
  gsl_rng_free(rng);
  ss_scheme_free(s);
}

int main(void) {
  test_refused();
  test_mlca_regular();
  test_tetoct_face();
  test_ties();
  test_catmull_clark();
  test_near_tie();
  test_jordan();
  test_built_ties();
  test_relabel();
  test_timing();
  flint_cleanup();
  return ss_test_done("exact");
}
