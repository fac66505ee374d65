/* test_jac_num.c — the interval product of the Jacobian tests' number
 * interface (analysis/charmap/ss_jac_num.h): mul_di, di_fast_mul written
 * inline, gives arb's di_fast_mul's bits, so the certified verdicts that use
 * it are those arb's product gave. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "ss_jac_num.h"
#include "ss_test.h"

/* deterministic uniform numbers in [-1, 1) */
static double rnd(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}

/* 64 deterministic random bits */
static uint64_t seed_bits(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return *s;
}

/* mul_di (ss_jac_num.h), di_fast_mul inline, gives arb's bits: intervals
 * of every sign pattern, with zero, subnormal, huge and infinite ends. */
static void test_mul_inline(void) {
  uint64_t seed = 77;
  const double special[] = {0.0,   -0.0,   1e-310,   -1e-310,
                            1e300, -1e300, INFINITY, -INFINITY};
  int differ = 0, n = 0;
  for (int t = 0; t < 20000; t++) {
    double e[4];
    for (int i = 0; i < 4; i++) {
      const uint64_t k = seed_bits(&seed) % 16;
      e[i] = k < 8 ? special[k] : ldexp(rnd(&seed), (int)(seed_bits(&seed) % 200) - 100);
    }
    const di_t x = {fmin(e[0], e[1]), fmax(e[0], e[1])};
    const di_t y = {fmin(e[2], e[3]), fmax(e[2], e[3])};
    const di_t a = mul_di(x, y), b = di_fast_mul(x, y);
    differ += memcmp(&a, &b, sizeof a) != 0;
    n++;
  }
  CHECK(differ == 0, "mul_di differs from di_fast_mul in %d of %d products", differ, n);
}

int main(void) {
  test_mul_inline();
  return ss_test_done("jac_num");
}
