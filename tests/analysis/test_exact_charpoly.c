/* test_exact_charpoly.c — the characteristic polynomial with each row scaled
 * by its own denominator (ss_exact_charpoly, ss_exact_impl.h) against
 * FLINT's rational one (fmpq_mat_charpoly, fraction-free over Q: another
 * algorithm), times prod d_r, coefficient for coefficient:
 *  - seeded random matrices of sizes 2..40 whose rows have denominators from
 *    1 to 2^31 - 1 (mixed: small rows beside huge ones, the case where the
 *    per-row scaling gains most), entries of both signs and row sums up to
 *    40 (spectral radii above 1, so the bound's rho term matters);
 *  - stochastic rows (the subdivision matrices' shape) of size 60;
 *  - a zero matrix and a single row of zeros (the bound's degenerate cases).
 * A bound 60 bits too small (one prime fewer) fails the large cases: checked
 * by mutation. */
#include <stdlib.h>

#include <flint/fmpq_mat.h>
#include <flint/fmpq_poly.h>
#include <flint/fmpz_vec.h>

#include "ss_exact_impl.h"
#include "ss_test.h"

/* N and d from a random rational matrix of size n, each row's entries
 * num / d_r with |num| <= maxnum; 1 if P equals prod d_r times FLINT's
 * rational characteristic polynomial. */
static int agrees(const fmpz_mat_t N, const fmpz *d) {
  const slong n = fmpz_mat_nrows(N);
  fmpq_mat_t B;
  fmpq_poly_t ref;
  fmpz_poly_t P, want;
  fmpz_t prod;
  fmpq_mat_init(B, n, n);
  fmpq_poly_init(ref);
  fmpz_poly_init(P);
  fmpz_poly_init(want);
  fmpz_init_set_ui(prod, 1);
  for (slong r = 0; r < n; r++) {
    fmpz_mul(prod, prod, d + r);
    for (slong c = 0; c < n; c++)
      fmpq_set_fmpz_frac(fmpq_mat_entry(B, r, c), fmpz_mat_entry(N, r, c), d + r);
  }
  fmpq_mat_charpoly(ref, B);
  fmpq_poly_scalar_mul_fmpz(ref, ref, prod);
  fmpq_poly_get_numerator(want, ref);
  int ok = fmpz_is_one(fmpq_poly_denref(ref));
  ss_exact_charpoly(P, N, d);
  ok = ok && fmpz_poly_equal(P, want);
  fmpq_mat_clear(B);
  fmpq_poly_clear(ref);
  fmpz_poly_clear(P);
  fmpz_poly_clear(want);
  fmpz_clear(prod);
  return ok;
}

static long rnd(long lo, long hi) { /* uniform-ish in [lo, hi] */
  return lo + (long)(((unsigned long)rand() << 16 ^ (unsigned long)rand()) %
                     (unsigned long)(hi - lo + 1));
}

/* A random case of size n: row r's denominator from [1, dmax] (every third
 * row 1..8 only), numerators in [-span d_r, span d_r] on about half the
 * entries; stochastic rows when stoch (nonnegative, summing to d_r). */
static int random_case(slong n, long dmax, long span, int stoch) {
  fmpz_mat_t N;
  fmpz *d = _fmpz_vec_init(n);
  fmpz_mat_init(N, n, n);
  for (slong r = 0; r < n; r++) {
    const long dr = r % 3 == 0 ? rnd(1, 8) : rnd(1, dmax);
    fmpz_set_si(d + r, dr);
    long left = dr;
    for (slong c = 0; c < n; c++) {
      if (stoch) {
        const long v = c == n - 1 ? left : rnd(0, (left + 1) / 4);
        fmpz_set_si(fmpz_mat_entry(N, r, c), v);
        left -= v;
      } else if (rnd(0, 1)) {
        const long m = dr > (1L << 20) ? dr : span * dr / (long)n + 1;
        fmpz_set_si(fmpz_mat_entry(N, r, c), rnd(-m, m));
      }
    }
  }
  const int ok = agrees(N, d);
  fmpz_mat_clear(N);
  _fmpz_vec_clear(d, n);
  return ok;
}

int main(void) {
  srand(37);
  for (slong n = 2; n <= 40; n += 3)
    for (int t = 0; t < 3; t++) {
      const long dmax = t == 0 ? 64 : t == 1 ? 100000 : 2147483647L;
      CHECK(random_case(n, dmax, 40, 0), "random rows, n %ld, denominators up to %ld",
            (long)n, dmax);
    }
  for (int t = 0; t < 3; t++)
    CHECK(random_case(60, t ? 1L << 21 : 1000, 1, 1), "stochastic rows, n 60, case %d",
          t);
  fmpz_mat_t Z;
  fmpz *d = _fmpz_vec_init(5);
  fmpz_mat_init(Z, 5, 5);
  for (slong r = 0; r < 5; r++)
    fmpz_set_si(d + r, 3 + r);
  CHECK(agrees(Z, d), "zero matrix");
  for (slong c = 0; c < 5; c++)
    for (slong r = 1; r < 5; r++)
      fmpz_set_si(fmpz_mat_entry(Z, r, c), r - 2 * c);
  CHECK(agrees(Z, d), "first row zero");
  fmpz_mat_clear(Z);
  _fmpz_vec_clear(d, 5);
  return ss_test_done("exact_charpoly");
}
