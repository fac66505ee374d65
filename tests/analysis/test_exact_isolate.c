/* test_exact_isolate.c — the exact spectrum's factors and their roots on real
 * cases (MLCA k = 10 and 12, tet/oct and box-spline k = 12 vertex links):
 *  - the characteristic polynomial of the one-ring block A, as the product
 *    of the merged factors it lists with their multiplicities (each factor
 *    scaled back from the integer matrix D A), equals fmpq_mat_charpoly of
 *    the unscaled rational A exactly: the integer charpoly, its scaling and
 *    the factorisation checked against an independent computation;
 *  - every factor's roots as ss_exact isolated them (from the block's
 *    LAPACK eigenvalues where it could) are the roots arb_fmpz_poly_
 *    complex_roots isolates from scratch at the same precision: as many real
 *    ones, ball i meeting arb's ball i and no other, real flags equal;
 *  - the largest factor really is started from the eigenvalues (it got
 *    exactly its degree of them), and the seeded path (ss_exact_complex_
 *    roots with those seeds) and a refinement from the balls to 256 bits
 *    give arb's roots too; seeds that cannot converge (all equal) fall back
 *    to arb's own result, ball for ball;
 *  - ss_exact_rational reads dyadic rationals (the rules' weights) exactly
 *    when their denominator is within the bound, and otherwise by its rule. */
#include <math.h>

#include <flint/fmpq_mat.h>
#include <flint/fmpq_poly.h>

#include "arb_fmpz_poly.h"

#include "ss_exact.h"
#include "ss_exact_impl.h"
#include "ss_local.h"
#include "ss_test.h"

/* Balls a[0..d) and b[0..d) name the same roots in the same order: a_i meets
 * b_i and no other b_j, and the real flags agree. */
static int same_roots(acb_srcptr a, acb_srcptr b, slong d) {
  for (slong i = 0; i < d; i++) {
    if (!acb_overlaps(a + i, b + i) || acb_is_real(a + i) != acb_is_real(b + i)) return 0;
    for (slong j = 0; j < d; j++)
      if (j != i && acb_overlaps(a + i, b + j)) return 0;
  }
  return 1;
}

/* Block 0's polynomial from the listed factors equals fmpq_mat_charpoly of A
 * (the rationals ss_exact reconstructed). */
static void check_charpoly(const ss_exact *x, const char *what) {
  const slong n1 = (slong)x->n1;
  fmpq_mat_t A;
  fmpq_poly_t want, got, g;
  fmpq_mat_init(A, n1, n1);
  fmpq_poly_init(want);
  fmpq_poly_init(got);
  fmpq_poly_init(g);
  for (slong i = 0; i < n1; i++)
    for (slong j = 0; j < n1; j++)
      ss_exact_get(x, (size_t)i, (size_t)j, fmpq_mat_entry(A, i, j));
  fmpq_mat_charpoly(want, A);
  fmpq_poly_one(got);
  for (size_t b = x->bstart[0]; b < x->bstart[1]; b++) {
    fmpq_poly_set_fmpz_poly(g, x->fac[x->bfac[b]].f);
    fmpq_poly_make_monic(g, g);
    for (int e = 0; e < x->bmult[b]; e++)
      fmpq_poly_mul(got, got, g);
  }
  CHECK(fmpq_poly_degree(want) == n1 && fmpq_poly_equal(want, got),
        "%s: the factors' product is not fmpq_mat_charpoly(A) (degrees %ld, %ld)", what,
        (long)fmpq_poly_degree(want), (long)fmpq_poly_degree(got));
  fmpq_mat_clear(A);
  fmpq_poly_clear(want);
  fmpq_poly_clear(got);
  fmpq_poly_clear(g);
}

/* Every factor's roots against arb's own isolation at the factor's
 * precision; returns the factor of block 0 of the largest degree. */
static size_t check_roots(const ss_exact *x, const char *what) {
  size_t big = x->bfac[x->bstart[0]];
  for (size_t k = 0; k < x->nfac; k++) {
    const ss_exact_factor *F = x->fac + k;
    const slong d = fmpz_poly_degree(F->f);
    if (d < 2) continue;
    acb_ptr z = _acb_vec_init(d), r = _acb_vec_init(d);
    arb_fmpz_poly_complex_roots(z, F->f, 0, F->prec);
    for (slong i = 0; i < d; i++)
      acb_set(r + i, &x->rt[F->root0 + (size_t)i].z);
    CHECK(same_roots(r, z, d), "%s: factor %zu (degree %ld): roots differ from arb's",
          what, k, (long)d);
    _acb_vec_clear(z, d);
    _acb_vec_clear(r, d);
  }
  for (size_t b = x->bstart[0]; b < x->bstart[1]; b++)
    if (fmpz_poly_degree(x->fac[x->bfac[b]].f) > fmpz_poly_degree(x->fac[big].f))
      big = x->bfac[b];
  return big;
}

/* The largest factor's seeds, the seeded path, a refinement, a fallback. */
static void check_seeded(const ss_exact *x, size_t k, const char *what) {
  const ss_exact_factor *F = x->fac + k;
  const slong d = fmpz_poly_degree(F->f);
  slong given = 0;
  for (size_t i = 0; x->ev && i < x->n1; i++)
    given += x->evf[i] == (long)k;
  CHECK(d >= 2 && given == d, "%s: the largest factor (degree %ld) got %ld seeds", what,
        (long)d, (long)given);
  if (given != d) return;
  acb_ptr s = _acb_vec_init(d), z = _acb_vec_init(d), a = _acb_vec_init(d);
  given = 0;
  for (size_t i = 0; i < x->n1; i++)
    if (x->evf[i] == (long)k) acb_set_d_d(s + given++, x->ev[2 * i], x->ev[2 * i + 1]);
  ss_exact_complex_roots(z, F->f, s, 128);
  arb_fmpz_poly_complex_roots(a, F->f, 0, 128);
  CHECK(same_roots(z, a, d), "%s: seeded roots differ from arb's", what);
  ss_exact_complex_roots(s, F->f, z, 256); /* a refinement from the balls */
  arb_fmpz_poly_complex_roots(a, F->f, 0, 256);
  CHECK(same_roots(s, a, d), "%s: refined roots differ from arb's at 256 bits", what);
  int sharp = 1;
  for (slong i = 0; i < d; i++)
    sharp &= acb_rel_accuracy_bits(s + i) >= 256;
  CHECK(sharp, "%s: a refinement to 256 bits is not that accurate", what);
  for (slong i = 0; i < d; i++)
    acb_set_d(s + i, 0.5); /* Durand-Kerner cannot start from equal points */
  ss_exact_complex_roots(z, F->f, s, 128);
  arb_fmpz_poly_complex_roots(a, F->f, 0, 128);
  int equal = 1;
  for (slong i = 0; i < d; i++)
    equal &= acb_equal(z + i, a + i);
  CHECK(equal, "%s: the fallback is not arb's own isolation", what);
  _acb_vec_clear(s, d);
  _acb_vec_clear(z, d);
  _acb_vec_clear(a, d);
}

static void one(const char *scheme, const char *link) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_link *l = NULL;
  ss_local *M = NULL;
  ss_exact *x = NULL;
  char what[160];
  snprintf(what, sizeof what, "%s %.100s", scheme, link);
  if (ss_scheme_new(scheme, &s, &err) || ss_link_parse(link, &l, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    goto done;
  }
  const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  if (ss_local_new(s, &c, &M, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    goto done;
  }
  const ss_exact_opts o = ss_exact_defaults(M->dim);
  if (ss_exact_new(M->S, M->n2, M->n1, &o, &x, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    goto done;
  }
  CHECK(x->nrt > 0, "%s: no roots", what);
  if (x->nrt == 0) goto done;
  check_charpoly(x, what);
  check_seeded(x, check_roots(x, what), what);
done:
  ss_exact_free(x);
  ss_local_free(M);
  ss_link_free(l);
  ss_scheme_free(s);
}

/* ss_exact_rational on dyadic rationals M / 2^k (M odd; the rules' weights
 * are such): exactly (M, 2^k) when 2^k <= maxden, else within the rule's
 * window with a denominator <= maxden, or refused. */
static void check_dyadic(void) {
  const long maxden[] = {1000, 1L << 18, 1L << 31};
  int bad = 0, n = 0;
  for (int md = 0; md < 3; md++)
    for (int k = 0; k <= 34; k++)
      for (long long M = -999; M <= 999; M += 14) {
        const long long Mo = M % 2 ? M : M + 1;
        const double s = ldexp((double)Mo, -k);
        long long p = 0, q = 0;
        const int ok = ss_exact_rational(s, maxden[md], &p, &q);
        n++;
        if ((1LL << k) <= maxden[md])
          bad += !ok || p != Mo || q != (1LL << k);
        else if (ok)
          bad += q < 1 || q > maxden[md] ||
                 fabs((double)p / (double)q - s) > ldexp(fmax(1.0, fabs(s)), -39);
      }
  CHECK(bad == 0, "ss_exact_rational: %d of %d dyadic rationals read wrongly", bad, n);
  long long p, q;
  CHECK(ss_exact_rational(-1048576.0, 1L << 18, &p, &q) && p == -1048576 && q == 1,
        "-2^20");
  CHECK(!ss_exact_rational(ldexp(1.0, -19), 1L << 18, &p, &q), "2^-19 accepted");
  CHECK(ss_exact_rational(0.375, 8, &p, &q) && p == 3 && q == 8, "3/8");
  CHECK(!ss_exact_rational(0.375, 4, &p, &q), "3/8 with denominators <= 4");
}

int main(void) {
  check_dyadic();
  const char *k10 = "10 hgjecidf,hfdceg,aebdi,aicbf,ajgbc,adbh,ahbej,afbg,acd,age";
  const char *k12a =
      "12 bkigecdfhjl,aljhfdcegik,aebd,acbf,agbc,adbh,aibe,afbj,akbg,ahbl,abi,ajb";
  const char *k12b =
      "12 fhecgd,fdlkce,aebkdijg,agicklbf,ahfbc,adbeh,acjid,afe,cdgj,cig,bldc,bdk";
  one("mlca", k10);
  one("mlca", k12a);
  one("mlca", k12b);
  one("tetoct", k12b);
  one("boxspline", k12a);
  flint_cleanup();
  return ss_test_done("exact_isolate");
}
