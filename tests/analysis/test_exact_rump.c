/* test_exact_rump.c — Rump's enclosure of a simple real eigenpair in real
 * balls (ss_exact_rump_real, ss_exact_impl.h) against arb's complex one
 * (acb_mat_eig_enclosure_rump), another implementation of the method:
 *  - seeded random integer matrices of sizes 5, 20 and 60, every real
 *    eigenvalue LAPACK finds well separated from the others: the real
 *    enclosure succeeds (at least 90 % of them), its eigenvalue ball meets
 *    arb's, and its eigenvector, divided by its last entry, meets arb's
 *    likewise divided, entry by entry (the same direction whatever the
 *    normalisation); the vector's and the eigenvalue's balls tight (radius
 *    below 1e-30 of the entry: Newton's steps at 128 bits refine the pair
 *    before the inclusion; without them, one round from doubles gives
 *    1e-20 and 1e-11);
 *  - T = I - R M computed in doubles (ss_exact_rump_tmat) contains the
 *    product at 1024 bits, entry by entry, for M of rational balls, and its
 *    radii sum to no more than 1e4 times the midpoints' true errors (radii
 *    1e4 times smaller miss entries: checked by mutation); with balls of
 *    radius 1e-9 in M, T contains I - R M for the M in them that moves a
 *    row most (without the balls' part of the radius it does not);
 *  - a wrong guess (halfway between two real eigenvalues, a vector of ones):
 *    no enclosure, or one holding a true eigenvalue (LAPACK's, to 1e-8);
 *  - a double eigenvalue (two equal diagonal blocks): no enclosure is
 *    claimed — the method proves simple eigenpairs only;
 *  - an approximate vector whose frozen (last) entry is 0: no enclosure. */
#include <math.h>
#include <stdlib.h>

#include <lapacke.h>

#include "acb_mat.h"
#include "arb_mat.h"

#include "ss_exact_impl.h"
#include "ss_test.h"

#define PREC 128

/* a's n x n doubles into an arb_mat (exact) */
static void to_arb(arb_mat_t A, const double *a, slong n) {
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < n; j++)
      arb_set_d(arb_mat_entry(A, i, j), a[i * n + j]);
}

/* arb's complex enclosure of the eigenpair near (lam, x): 1 if proven. */
static int acb_pair(acb_t lz, acb_mat_t R, const arb_mat_t A, double lam, const double *x,
                    slong n) {
  acb_mat_t Ac, Ra;
  acb_t la;
  acb_mat_init(Ac, n, n), acb_mat_init(Ra, n, 1);
  acb_init(la);
  acb_mat_set_arb_mat(Ac, A);
  acb_set_d(la, lam);
  for (slong i = 0; i < n; i++)
    acb_set_d(acb_mat_entry(Ra, i, 0), x[i]);
  acb_mat_eig_enclosure_rump(lz, NULL, R, Ac, la, Ra, PREC);
  const int ok = acb_is_finite(lz) && acb_mat_is_finite(R);
  acb_mat_clear(Ac), acb_mat_clear(Ra);
  acb_clear(la);
  return ok;
}

/* Whether x / x_last meets y / y_last entry by entry (x real, y complex). */
static int same_direction(const arb_mat_t X, const acb_mat_t Y, slong n) {
  acb_t a, b, s, t;
  acb_init(a), acb_init(b), acb_init(s), acb_init(t);
  int ok = 1;
  acb_set_arb(s, arb_mat_entry(X, n - 1, 0));
  acb_set(t, acb_mat_entry(Y, n - 1, 0));
  for (slong i = 0; i < n && ok; i++) {
    acb_set_arb(a, arb_mat_entry(X, i, 0));
    acb_div(a, a, s, PREC);
    acb_div(b, acb_mat_entry(Y, i, 0), t, PREC);
    ok = acb_overlaps(a, b);
  }
  acb_clear(a), acb_clear(b), acb_clear(s), acb_clear(t);
  return ok;
}

/* The largest relative radius of X's entries (0 entries: absolute). */
static double rel_radius(const arb_mat_t X, slong n) {
  double r = 0.0;
  for (slong i = 0; i < n; i++) {
    const double m = fabs(arf_get_d(arb_midref(arb_mat_entry(X, i, 0)), ARF_RND_NEAR));
    const double d = mag_get_d(arb_radref(arb_mat_entry(X, i, 0)));
    r = fmax(r, m > 0.0 ? d / m : d);
  }
  return r;
}

/* Random integer matrices of size n: every well separated real eigenvalue. */
static void random_case(slong n, unsigned seed, int *tried, int *proven) {
  double *a = malloc((size_t)(n * n) * sizeof *a),
         *w = malloc((size_t)(n * n) * sizeof *w);
  double *wr = malloc((size_t)n * sizeof *wr), *wi = malloc((size_t)n * sizeof *wi);
  double *vr = malloc((size_t)(n * n) * sizeof *vr);
  srand(seed);
  for (slong i = 0; i < n * n; i++)
    a[i] = (double)(rand() % 19 - 9);
  for (slong i = 0; i < n * n; i++)
    w[i] = a[i];
  CHECK(!LAPACKE_dgeev(LAPACK_ROW_MAJOR, 'N', 'V', (lapack_int)n, w, (lapack_int)n, wr,
                       wi, NULL, (lapack_int)n, vr, (lapack_int)n),
        "n = %ld: LAPACK eigenvalues", (long)n);
  arb_mat_t A, Xa, X;
  arb_t lam, lr;
  acb_t lz;
  acb_mat_t R;
  arb_mat_init(A, n, n), arb_mat_init(Xa, n, 1), arb_mat_init(X, n, 1);
  arb_init(lam), arb_init(lr);
  acb_init(lz);
  acb_mat_init(R, n, 1);
  to_arb(A, a, n);
  double *x = malloc((size_t)n * sizeof *x);
  for (slong k = 0; k < n; k++) {
    if (wi[k] != 0.0) continue;
    double gap = INFINITY;
    for (slong j = 0; j < n; j++)
      if (j != k) gap = fmin(gap, hypot(wr[j] - wr[k], wi[j]));
    double big = 0.0;
    for (slong i = 0; i < n; i++)
      big = fmax(big, fabs(x[i] = vr[i * n + k]));
    if (gap < 1e-3 * (1.0 + fabs(wr[k])) || fabs(x[n - 1]) < 1e-3 * big) continue;
    for (slong i = 0; i < n; i++)
      arb_set_d(arb_mat_entry(Xa, i, 0), x[i]);
    arb_set_d(lam, wr[k]);
    ++*tried;
    if (!ss_exact_rump_real(X, lr, A, lam, Xa, PREC)) continue;
    ++*proven;
    const int ref = acb_pair(lz, R, A, wr[k], x, n);
    CHECK(ref, "n = %ld, lambda %g: arb's complex enclosure", (long)n, wr[k]);
    if (!ref) continue;
    acb_t l2;
    acb_init(l2);
    acb_set_arb(l2, lr);
    CHECK(acb_overlaps(l2, lz) && same_direction(X, R, n),
          "n = %ld, lambda %g: eigenvalue and eigenvector meet arb's", (long)n, wr[k]);
    /* the eigenvector's ball is the refined approximation plus the
     * correction's ball; the eigenvalue gets the correction's whole
     * magnitude as radius: ~ the residual left by Newton's steps */
    CHECK(rel_radius(X, n) < 1e-30 &&
              mag_get_d(arb_radref(lr)) < 1e-30 * (1.0 + fabs(wr[k])),
          "n = %ld, lambda %g: tight (vector %g, eigenvalue %g)", (long)n, wr[k],
          rel_radius(X, n), mag_get_d(arb_radref(lr)));
    acb_clear(l2);
  }
  /* a wrong guess: halfway between two real eigenvalues, a vector of ones:
   * either no enclosure, or one whose eigenvalue ball holds a true one */
  for (slong k = 0; k + 1 < n; k++) {
    if (wi[k] != 0.0 || wi[k + 1] != 0.0) continue;
    for (slong i = 0; i < n; i++)
      arb_set_d(arb_mat_entry(Xa, i, 0), 1.0);
    arb_set_d(lam, 0.5 * (wr[k] + wr[k + 1]));
    if (!ss_exact_rump_real(X, lr, A, lam, Xa, PREC)) continue;
    int near = 0;
    for (slong j = 0; j < n; j++)
      near |= wi[j] == 0.0 && fabs(arf_get_d(arb_midref(lr), ARF_RND_NEAR) - wr[j]) <=
                                  1e-8 * (1.0 + fabs(wr[j])) + mag_get_d(arb_radref(lr));
    CHECK(near, "n = %ld: a guess halfway between %g and %g encloses a true eigenvalue",
          (long)n, wr[k], wr[k + 1]);
  }
  free(x);
  arb_mat_clear(A), arb_mat_clear(Xa), arb_mat_clear(X);
  arb_clear(lam), arb_clear(lr);
  acb_clear(lz);
  acb_mat_clear(R);
  free(a), free(w), free(wr), free(wi), free(vr);
}

/* diag(B, B): every eigenvalue double; diag(B, 10) with B's simple
 * eigenvalue 3 and its eigenvector (1, 1, -1, 0), frozen (last) entry 0. */
static int claims(const double *a, const double *x, slong n, double l) {
  arb_mat_t A, Xa, X;
  arb_t lam, lr;
  arb_mat_init(A, n, n), arb_mat_init(Xa, n, 1), arb_mat_init(X, n, 1);
  arb_init(lam), arb_init(lr);
  to_arb(A, a, n);
  for (slong i = 0; i < n; i++)
    arb_set_d(arb_mat_entry(Xa, i, 0), x[i]);
  arb_set_d(lam, l);
  const int ok = ss_exact_rump_real(X, lr, A, lam, Xa, PREC);
  arb_mat_clear(A), arb_mat_clear(Xa), arb_mat_clear(X);
  arb_clear(lam), arb_clear(lr);
  return ok;
}

static void refusals(void) {
  const double b[9] = {2, 1, 0, 1, 3, 1, 0, 1, 4}; /* eigenvalues 3, 3 +- sqrt 3 */
  double a[36] = {0}, c[16] = {0};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      a[i * 6 + j] = a[(i + 3) * 6 + j + 3] = b[3 * i + j];
      c[i * 4 + j] = b[3 * i + j];
    }
  c[15] = 10.0;
  const double x[6] = {1, 1, -1, 1, 1, -1}, y[4] = {1, 1, -1, 0}, z[4] = {1, 1, -1, 1e-3};
  CHECK(!claims(a, x, 6, 3.0),
        "a double eigenvalue (diag(B, B), lambda 3): no enclosure");
  CHECK(!claims(c, y, 4, 3.0), "frozen (last) entry 0: no enclosure");
  /* diag(B, 10)'s eigenvector for 3 has last entry 0 exactly: no eigenvector
   * has the frozen entry 1e-3 */
  CHECK(!claims(c, z, 4, 3.0), "no eigenvector with that frozen entry: no enclosure");
}

/* T = I - R M in doubles against the same at 1024 bits: M = A - l I with its
 * last column -x, A of rationals p/q (balls at 128 bits), R a perturbed
 * inverse of M's doubles (any R: the bound must hold for each). */
static void tmat_case(slong n, unsigned seed, double wide) {
  srand(seed);
  arb_mat_t A, Xa, T, M, Rb, E;
  arb_t l, t;
  arb_mat_init(A, n, n), arb_mat_init(Xa, n, 1), arb_mat_init(T, n, n);
  arb_mat_init(M, n, n), arb_mat_init(Rb, n, n), arb_mat_init(E, n, n);
  arb_init(l), arb_init(t);
  double *r = malloc((size_t)(n * n) * sizeof *r);
  lapack_int *piv = malloc((size_t)n * sizeof *piv);
  for (slong i = 0; i < n; i++) {
    for (slong j = 0; j < n; j++) { /* (rand in -50..50) / (rand in 1..97) */
      arb_set_si(arb_mat_entry(A, i, j), rand() % 101 - 50);
      arb_div_ui(arb_mat_entry(A, i, j), arb_mat_entry(A, i, j),
                 (unsigned long)(rand() % 97 + 1), 128);
      arb_set_d(t, wide); /* a ball of radius wide round p/q */
      arb_add_error(arb_mat_entry(A, i, j), t);
    }
    arb_set_d(arb_mat_entry(Xa, i, 0), (double)(rand() % 2001 - 1000) / 997.0);
  }
  arb_set_d(l, 0.3183098861837907);
  for (slong i = 0; i < n; i++) /* M at 1024 bits from the same balls' midpoints */
    for (slong j = 0; j < n; j++) {
      if (j == n - 1)
        arb_neg(arb_mat_entry(M, i, j), arb_mat_entry(Xa, i, 0));
      else
        arb_get_mid_arb(arb_mat_entry(M, i, j), arb_mat_entry(A, i, j));
      if (i == j && j != n - 1)
        arb_sub(arb_mat_entry(M, i, j), arb_mat_entry(M, i, j), l, 1024);
      r[i * n + j] = arf_get_d(arb_midref(arb_mat_entry(M, i, j)), ARF_RND_NEAR);
    }
  int ok = !LAPACKE_dgetrf(LAPACK_ROW_MAJOR, (lapack_int)n, (lapack_int)n, r,
                           (lapack_int)n, piv) &&
           !LAPACKE_dgetri(LAPACK_ROW_MAJOR, (lapack_int)n, r, (lapack_int)n, piv);
  for (slong i = 0; i < n * n && ok; i++)
    r[i] *= 1.0 + 1e-6 * (double)(rand() % 3 - 1); /* not quite the inverse */
  CHECK(ok && !ss_exact_rump_tmat(T, r, A, l, Xa, 128), "tmat n = %ld: computed",
        (long)n);
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < n; j++)
      arb_set_d(arb_mat_entry(Rb, i, j), r[i * n + j]);
  arb_mat_mul(E, Rb, M, 1024); /* exact but for 1024-bit rounding */
  arb_mat_neg(E, E);
  for (slong i = 0; i < n; i++)
    arb_add_ui(arb_mat_entry(E, i, i), arb_mat_entry(E, i, i), 1, 1024);
  long miss = 0, zero_holds = 0;
  double srad = 0.0, serr = 0.0; /* sums of the radii and the true errors */
  for (slong i = 0; i < n; i++)
    for (slong j = 0; j < n; j++) {
      const arb_struct *te = arb_mat_entry(T, i, j), *ee = arb_mat_entry(E, i, j);
      miss += !arb_contains(te, ee);
      arb_set_arf(t, arb_midref(te));
      arb_sub(t, t, ee, 1024);
      const double err = fabs(arf_get_d(arb_midref(t), ARF_RND_NEAR));
      const double rad = mag_get_d(arb_radref(te));
      zero_holds += err == 0.0;
      srad += rad;
      serr += err;
    }
  /* with wide balls: for rows i, the M in the balls that moves (R M)_ij
   * most, delta_kj = rad * sign(R_ik), must be inside too */
  long wmiss = 0;
  for (slong i = 0; wide > 0.0 && i < n; i += 1 + n / 5) {
    arb_mat_t Mw, Ew;
    arb_mat_init(Mw, n, n), arb_mat_init(Ew, 1, n);
    for (slong k = 0; k < n; k++)
      for (slong j = 0; j < n; j++) {
        arb_set(arb_mat_entry(Mw, k, j), arb_mat_entry(M, k, j));
        if (j != n - 1) {
          arb_set_d(t, r[i * n + k] >= 0.0 ? wide : -wide);
          arb_add(arb_mat_entry(Mw, k, j), arb_mat_entry(Mw, k, j), t, 1024);
        }
      }
    for (slong j = 0; j < n; j++) {
      arb_zero(arb_mat_entry(Ew, 0, j));
      for (slong k = 0; k < n; k++)
        arb_addmul(arb_mat_entry(Ew, 0, j), arb_mat_entry(Rb, i, k),
                   arb_mat_entry(Mw, k, j), 1024);
      arb_neg(arb_mat_entry(Ew, 0, j), arb_mat_entry(Ew, 0, j));
      if (i == j) arb_add_ui(arb_mat_entry(Ew, 0, j), arb_mat_entry(Ew, 0, j), 1, 1024);
      wmiss += !arb_contains(arb_mat_entry(T, i, j), arb_mat_entry(Ew, 0, j));
    }
    arb_mat_clear(Mw), arb_mat_clear(Ew);
  }
  CHECK(wmiss == 0,
        "tmat n = %ld: T contains I - R M for the extreme M of balls of radius %g too "
        "(%ld missed)",
        (long)n, wide, wmiss);
  const double worst = srad / serr;
  printf("tmat n = %ld: %ld of %ld entries missed, radii %.0f times the midpoints' true "
         "errors (sums), %ld entries exact\n",
         (long)n, miss, (long)(n * n), worst, zero_holds);
  CHECK(miss == 0, "tmat n = %ld: T contains I - R M at 1024 bits (%ld missed)", (long)n,
        miss);
  CHECK((wide > 0.0 || worst < 1e4) && zero_holds < n * n / 2,
        "tmat n = %ld: the radius not absurd (%.3g times the error), the midpoint not "
        "exact",
        (long)n, worst);
  free(r), free(piv);
  arb_mat_clear(A), arb_mat_clear(Xa), arb_mat_clear(T);
  arb_mat_clear(M), arb_mat_clear(Rb), arb_mat_clear(E);
  arb_clear(l), arb_clear(t);
}

int main(void) {
  const slong sizes[3] = {5, 20, 60};
  for (int s = 0; s < 3; s++) {
    int tried = 0, proven = 0;
    for (unsigned seed = 1; seed <= 4; seed++)
      random_case(sizes[s], seed + 100u * (unsigned)s, &tried, &proven);
    printf("n = %ld: %d of %d real eigenpairs enclosed\n", (long)sizes[s], proven, tried);
    CHECK(tried > 0 && proven >= 0.9 * tried, "n = %ld: %d of %d enclosed",
          (long)sizes[s], proven, tried);
  }
  refusals();
  tmat_case(7, 11, 0.0);
  tmat_case(60, 12, 0.0);
  tmat_case(150, 13, 0.0);
  tmat_case(60, 14, 1e-9);
  flint_cleanup();
  return ss_test_done("exact_rump");
}
