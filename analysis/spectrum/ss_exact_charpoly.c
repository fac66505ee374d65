/* ss_exact_charpoly.c — the characteristic polynomial of a rational matrix,
 * multimodular, with each row scaled by its own denominator
 * (ss_exact_impl.h).
 *
 * FLINT's fmpz_mat_charpoly on the block scaled by the lcm D of all its
 * denominators (M = D B) needs primes for coefficients up to D^n det B: its
 * bound is n/2 (log2 n + 2 log2 max|M| + 1.67) bits, 1,000-1,800 at MLCA
 * k = 14 (n = 75, D up to 2^21), 21-29 primes of 0.85 ms each (Danilevsky
 * modulo p), most of the exact spectrum's characteristic polynomials.  The
 * rows have much smaller denominators d_r than D (one-ring rows: valences,
 * 2^k), and P(x) = det(x diag(d) - N), N = diag(d) B integer, is an integer
 * polynomial equal to (prod d_r) det(x - B): its coefficient of x^(n-k) is
 * (prod d_r) (-1)^k e_k(lambda(B)), and
 *   |e_k(lambda)| <= e_k(|lambda|) <= C(n,k) min(rho, sqrt(F2 / n))^k
 * with rho = max_r sum_c |b_rc| (every |lambda| <= rho) and F2 = sum |b_rc|^2
 * (Schur: sum |lambda|^2 <= F2; Maclaurin: e_k(y) / C(n,k) <= (mean y)^k <=
 * (mean y^2)^(k/2) for y >= 0).  So about log2 prod d_r + n bits: 440 at
 * MLCA k = 14 against FLINT's 1,000-1,800, 8 primes.  Modulo p (a prime
 * above 2^62, so no d_r vanishes: their prime factors are denominators'
 * factors, below 2^31) P = (prod d_r) charpoly(diag(d)^-1 N); the residues are
 * combined by the Chinese remainder theorem with signed representatives until
 * the modulus exceeds twice the bound. */
#include <math.h>

#include <flint/nmod_mat.h>
#include <flint/nmod_poly.h>

#include "ss_exact_impl.h"

/* log2 of a bound on max_k |coefficient of x^(n-k)| of P / prod d_r, from
 * rho and F2 / n as doubles (see the header comment). */
static double e_bound_bits(slong n, double rho, double f2n) {
  const double lr = log2(rho), lf = 0.5 * log2(f2n), l = lr < lf ? lr : lf;
  double best = 0.0, lbin = 0.0; /* log2 C(n, k), k = 0 */
  for (slong k = 0; k <= n; k++) {
    const double b = lbin + (double)k * l;
    if (b > best) best = b;
    lbin += log2((double)(n - k)) - log2((double)(k + 1));
  }
  return best;
}

void ss_exact_charpoly(fmpz_poly_t P, const fmpz_mat_t N, const fmpz *d) {
  const slong n = fmpz_mat_nrows(N);
  fmpz_t prod, m;
  fmpz_init_set_ui(prod, 1);
  fmpz_init_set_ui(m, 1);
  /* rho and F2 in doubles: entries below 2^53 d_r in size, so the relative
   * rounding of each sum is below 2^-45 here; the 4 bits added below cover
   * it many times over */
  double rho = 0.0, f2 = 0.0;
  for (slong r = 0; r < n; r++) {
    const double dr = fmpz_get_d(d + r);
    double row = 0.0;
    for (slong c = 0; c < n; c++) {
      const double v = fabs(fmpz_get_d(fmpz_mat_entry(N, r, c))) / dr;
      row += v;
      f2 += v * v;
    }
    if (row > rho) rho = row;
    fmpz_mul(prod, prod, d + r);
  }
  slong bound = 0;
  if (rho > 0.0) {
    const double e = e_bound_bits(n, rho, f2 / (double)n);
    bound = (slong)ceil(e) + (slong)fmpz_bits(prod) + 1 + 4; /* sign, margin */
  } else {
    bound = (slong)fmpz_bits(prod) + 1 + 4; /* B = 0: P = prod d_r x^n */
  }
  nmod_mat_t Bp;
  nmod_poly_t cp;
  fmpz_poly_zero(P);
  mp_limb_t p = UWORD(1) << 62;
  while ((slong)fmpz_bits(m) <= bound) {
    p = n_nextprime(p, 0);
    nmod_mat_init(Bp, n, n, p);
    nmod_poly_init(cp, p);
    for (slong r = 0; r < n; r++) {
      const mp_limb_t inv = n_invmod(fmpz_fdiv_ui(d + r, p), p);
      for (slong c = 0; c < n; c++)
        nmod_mat_entry(Bp, r, c) = n_mulmod2_preinv(
            fmpz_fdiv_ui(fmpz_mat_entry(N, r, c), p), inv, p, Bp->mod.ninv);
    }
    nmod_mat_charpoly(cp, Bp);
    nmod_poly_scalar_mul_nmod(cp, cp, fmpz_fdiv_ui(prod, p));
    fmpz_poly_CRT_ui(P, P, m, cp, 1);
    fmpz_mul_ui(m, m, p);
    nmod_mat_clear(Bp);
    nmod_poly_clear(cp);
  }
  fmpz_clear(prod);
  fmpz_clear(m);
}
