/* test_jsr_cert.c — the certified lower bound of rho(Y_w)^(1/len) for one
 * word w of matrices (ss_jsr_cert_lower), against closed forms evaluated here
 * in arb at 256 bits.
 *
 * A certified lower bound must be rigorous (never above the true value,
 * checked with arb's certain comparisons, not in doubles) and tight (within
 * 1e-12 relative for simple dominant eigenvalues, 1e-6 for the identity's
 * multiple one, 10% for a Jordan block, whose one enclosure is wide: 1.905
 * for rho = 2).  Closed forms:
 *   - [[1, 1], [1, 0]]: rho = phi = (1 + sqrt 5) / 2; its powers A^3 (word
 *     0 0 0) give phi again (rho(A^k)^(1/k) = rho(A));
 *   - A = [[1, 1], [0, 1]], B = [[1, 0], [1, 1]]: B A = [[1, 1], [1, 2]] has
 *     rho = phi^2, so the word (A, B) gives phi; (B, A) the same
 *     (rho(AB) = rho(BA));
 *   - [[3/4, -1/2], [1/2, 3/4]]: a complex pair of modulus sqrt(13) / 4;
 *   - [[2, 1], [0, 2]] (a Jordan block) and the identity of order 3: rho 2
 *     and 1, multiple eigenvalues (Rump's cluster enclosure);
 *   - diag(1, -1): rho 1 with dominant eigenvalues cancelling in odd traces;
 *   - N = [[0, 1], [0, 0]]: rho(N) = rho(N N) = 0, so no positive lower bound
 *     may be claimed (return 0, lo = 0); but rho(N^T N) = 1 (word N, N^T);
 *   - [[2, 1], [1, 2]]: rho 3 exactly.
 * Random 4 x 4 matrices, words of length 1..4: lo <= ||Y_w||_inf^(1/len)
 * (every induced norm bounds rho), lo within 1e-9 of LAPACK's rho of the
 * product formed in doubles, lo invariant under a cyclic shift of the word,
 * and lo(2 Y) = 2 lo(Y) to 1e-12 (rho is homogeneous).
 * Mutations this catches (tried by hand: the report of issue 33):
 *   - the final bound rounded up to a double (ARF_RND_CEIL) instead of down:
 *     lo > phi and lo > sqrt(13) / 4, caught by the certain comparison (the
 *     upper end of the 256-bit ball instead of the lower is not a mutation
 *     doubles can see: the ball is far narrower than an ulp);
 *   - the product formed in the reverse order (Y_w[0] first on the left):
 *     not visible for two letters (rho(AB) = rho(BA)) but for the random
 *     words of three distinct letters (rho(CBA) != rho(ABC)). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <arb.h>
#include <flint/flint.h>
#include <gsl/gsl_rng.h>

#include "ss_eig.h"
#include "ss_jsr_cert.h"
#include "ss_test.h"

/* lo <= x certainly, x an arb ball (the comparison is rigorous). */
static int below(double lo, const arb_t x) {
  arb_t l;
  arb_init(l);
  arb_set_d(l, lo);
  const int ok = arb_le(l, x);
  arb_clear(l);
  return ok;
}

/* lo against the closed form x: lo <= x certainly and x - lo <= rel x. */
static void check_bound(size_t n, const double *const *Y, const int *w, int len,
                        const arb_t x, double rel, const char *what) {
  double lo = -1.0;
  const int ok = ss_jsr_cert_lower(n, Y, w, len, &lo);
  const double xd = arf_get_d(arb_midref(x), ARF_RND_NEAR);
  CHECK(ok == 1 && lo > 0.0, "%s: not certified (lo %g)", what, lo);
  CHECK(below(lo, x), "%s: lower bound %.17g above the true value %.17g", what, lo, xd);
  CHECK(lo >= xd * (1.0 - rel), "%s: lower bound %.17g far below %.17g (rel %g)", what,
        lo, xd, rel);
}

static void test_closed_forms(void) {
  arb_t phi, x;
  arb_init(phi);
  arb_init(x);
  arb_sqrt_ui(phi, 5, 256);
  arb_add_ui(phi, phi, 1, 256);
  arb_mul_2exp_si(phi, phi, -1); /* (1 + sqrt 5) / 2 */
  const double F[4] = {1, 1, 1, 0};
  const double *one[1] = {F};
  const int w0[3] = {0, 0, 0};
  check_bound(2, one, w0, 1, phi, 1e-12, "Fibonacci matrix");
  check_bound(2, one, w0, 3, phi, 1e-12, "Fibonacci matrix cubed");
  const double A[4] = {1, 1, 0, 1}, B[4] = {1, 0, 1, 1};
  const double *ab[2] = {A, B};
  const int w01[2] = {0, 1}, w10[2] = {1, 0};
  check_bound(2, ab, w01, 2, phi, 1e-12, "golden pair (A, B)");
  check_bound(2, ab, w10, 2, phi, 1e-12, "golden pair (B, A)");
  const double R[4] = {0.75, -0.5, 0.5, 0.75};
  const double *rot[1] = {R};
  arb_sqrt_ui(x, 13, 256);
  arb_mul_2exp_si(x, x, -2);
  check_bound(2, rot, w0, 1, x, 1e-12, "scaled rotation");
  check_bound(2, rot, w0, 3, x, 1e-12, "scaled rotation cubed");
  const double J[4] = {2, 1, 0, 2};
  const double *jor[1] = {J};
  arb_set_ui(x, 2);
  /* a Jordan block's one enclosure is wide (1.905 for 2 at 128 bits): the
   * contract promises rigour, not tightness, so only 10% is asked */
  check_bound(2, jor, w0, 1, x, 0.1, "Jordan block");
  const double Id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double *id[1] = {Id};
  arb_set_ui(x, 1);
  check_bound(3, id, w0, 2, x, 1e-6, "identity");
  const double Dm[4] = {1, 0, 0, -1};
  const double *dm[1] = {Dm};
  check_bound(2, dm, w0, 3, x, 1e-12, "diag(1, -1) cubed");
  const double S3[4] = {2, 1, 1, 2};
  const double *s3[1] = {S3};
  arb_set_ui(x, 3);
  check_bound(2, s3, w0, 1, x, 1e-12, "[[2, 1], [1, 2]]");
  /* nilpotent: no positive bound may be certified */
  const double N[4] = {0, 1, 0, 0}, Nt[4] = {0, 0, 1, 0};
  const double *nn[2] = {N, Nt};
  double lo = -1.0;
  CHECK(ss_jsr_cert_lower(2, nn, w0, 1, &lo) == 0 && lo == 0.0,
        "nilpotent: certified lower bound %g of rho 0", lo);
  lo = -1.0;
  CHECK(ss_jsr_cert_lower(2, nn, w0, 2, &lo) == 0 && lo == 0.0,
        "N N = 0: certified lower bound %g", lo);
  arb_set_ui(x, 1);
  check_bound(2, nn, w01, 2, x, 1e-12, "N^T N");
  arb_clear(phi);
  arb_clear(x);
}

/* c = a b (n x n row-major; c does not alias). */
static void matmul(size_t n, const double *a, const double *b, double *c) {
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      double s = 0.0;
      for (size_t k = 0; k < n; k++)
        s += a[i * n + k] * b[k * n + j];
      c[i * n + j] = s;
    }
}

static void test_random(void) {
  enum { N = 4, NM = 3 };
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 2024);
  double M[NM][N * N], M2[NM][N * N];
  const double *Y[NM], *Y2[NM];
  for (int t = 0; t < 12; t++) {
    for (int k = 0; k < NM; k++) {
      for (int i = 0; i < N * N; i++) {
        M[k][i] = gsl_rng_uniform(r) - 0.3;
        M2[k][i] = 2.0 * M[k][i];
      }
      Y[k] = M[k];
      Y2[k] = M2[k];
    }
    const int len = 1 + t % 4;
    int w[4], ws[4];
    for (int i = 0; i < len; i++)
      w[i] = (int)gsl_rng_uniform_int(r, NM);
    if (len == 3) w[0] = 0, w[1] = 1, w[2] = 2; /* three distinct letters */
    for (int i = 0; i < len; i++)
      ws[i] = w[(i + 1) % len];
    /* the product Y_w[len-1] ... Y_w[0] in doubles */
    double P[N * N], T[N * N];
    memcpy(P, Y[w[0]], sizeof P);
    for (int i = 1; i < len; i++) {
      matmul(N, Y[w[i]], P, T);
      memcpy(P, T, sizeof P);
    }
    double norm = 0.0;
    for (int i = 0; i < N; i++) {
      double s = 0.0;
      for (int j = 0; j < N; j++)
        s += fabs(P[i * N + j]);
      norm = fmax(norm, s);
    }
    double re[N], im[N], rho = 0.0;
    ss_error err = {0};
    REQUIRE_OK_VOID(ss_eig_dense(P, N, re, im, &err), &err);
    for (int i = 0; i < N; i++)
      rho = fmax(rho, hypot(re[i], im[i]));
    rho = pow(rho, 1.0 / len);
    double lo = 0.0, los = 0.0, lo2 = 0.0;
    const int ok = ss_jsr_cert_lower(N, Y, w, len, &lo);
    CHECK(ok && lo <= pow(norm, 1.0 / len) * (1 + 1e-12),
          "random %d: lo %.17g above the norm bound %.17g", t, lo, pow(norm, 1.0 / len));
    CHECK(ok && fabs(lo - rho) <= 1e-9 * rho, "random %d (len %d): lo %.17g, rho %.17g",
          t, len, lo, rho);
    CHECK(ss_jsr_cert_lower(N, Y, ws, len, &los) && fabs(los - lo) <= 1e-12 * lo,
          "random %d: cyclic shift of the word: %.17g vs %.17g", t, los, lo);
    CHECK(ss_jsr_cert_lower(N, Y2, w, len, &lo2) && fabs(lo2 - 2.0 * lo) <= 1e-12 * lo,
          "random %d: scaled by 2: %.17g vs 2 x %.17g", t, lo2, lo);
  }
  gsl_rng_free(r);
}

int main(void) {
  test_closed_forms();
  test_random();
  flint_cleanup(); /* FLINT's caches, for the leak checker */
  return ss_test_done("jsr_cert");
}
