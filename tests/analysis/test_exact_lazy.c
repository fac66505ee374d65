/* test_exact_lazy.c — lazy factoring (ss_exact_opts.lazy, ss_exact.h) gives
 * the verdicts of the full factorisation, and starts again with it where an
 * unproven factor would decide otherwise.  Each matrix is A = [1 0; v B]
 * (rows summing to 1: v = 1 - B 1; characteristic polynomial (x - 1) times
 * B's), B block lower triangular with companion blocks of chosen
 * polynomials, so that the one-ring block's simple part has degree >= 12 and
 * is kept whole by the lazy path.  Lazy and full runs are compared on the
 * condition (verdict, certified, reason), the roots, the basis enclosure and
 * the exact rational basis:
 *   - generic: lambda1..3 the roots of an irreducible cubic (irrational), the
 *     rest those of x^10 - 1/1000: the lazy result stands (lambda1's reported
 *     polynomial is the kept part of degree 13, not the cubic: the lazy path
 *     ran) and equals the full one;
 *   - a cyclotomic factor x^2 + 1 inside the kept part: the full path proves
 *     |i| = 1 exactly (a certified failure), the lazy one cannot separate
 *     the moduli and must start again;
 *   - lambda1..3 rational with denominators above the candidates' 4096,
 *     hidden in the kept part: the full path's basis is exact and rational,
 *     so the lazy one must see them rational (dA times the root an integer)
 *     and start again.
 * Mutations: ss_exact_new returning the lazy result without its check fails
 * the last two; without the integer test, the last. */
#include <stdlib.h>
#include <string.h>

#include "ss_exact.h"
#include "ss_test.h"

enum { NMAX = 32 };

/* Append the companion block of the monic polynomial x^d + c[d-1] x^(d-1) +
 * ... + c[0] to B (size *nb, NMAX wide) at rows and columns *nb.., coupled to
 * the previous block by 1/8 in its first row. */
static void companion(double *B, int *nb, const double *c, int d) {
  const int o = *nb;
  for (int i = 0; i + 1 < d; i++)
    B[(o + i) * NMAX + o + i + 1] = 1.0;
  for (int j = 0; j < d; j++)
    B[(o + d - 1) * NMAX + o + j] = -c[j];
  if (o > 0) B[o * NMAX + o - 1] = 0.125;
  *nb = o + d;
}

/* A = [1 0; v B] into S (n x n, n = nb + 1). */
static int assemble(const double *B, int nb, double *S) {
  const int n = nb + 1;
  memset(S, 0, (size_t)(n * n) * sizeof *S);
  S[0] = 1.0;
  for (int i = 0; i < nb; i++) {
    double sum = 0.0;
    for (int j = 0; j < nb; j++) {
      S[(i + 1) * n + j + 1] = B[i * NMAX + j];
      sum += B[i * NMAX + j];
    }
    S[(i + 1) * n] = 1.0 - sum;
  }
  return n;
}

/* The exact spectrum of S with lazy factoring or not (*x: caller frees). */
static ss_status run(const double *S, int n, int lazy, ss_exact **x) {
  ss_exact_opts o = ss_exact_defaults(3);
  o.lazy = lazy;
  ss_error err = {0};
  const ss_status st = ss_exact_new(S, (size_t)n, (size_t)n, &o, x, &err);
  CHECK(st == SS_OK, "ss_exact_new (lazy %d): %s", lazy, err.msg);
  return st;
}

/* Lazy and full agree on everything a verdict reads; returns lambda1's
 * reported polynomial degree under lazy (0 if none). */
static int same(const char *name, const double *S, int n, ss_verdict_kind want,
                int *full_degree) {
  ss_exact *a = NULL, *b = NULL;
  int deg = 0;
  if (run(S, n, 1, &a) || run(S, n, 0, &b)) goto done;
  ss_verdict va, vb;
  int ca = 0, cb = 0;
  ss_exact_condition(a, &va, &ca);
  ss_exact_condition(b, &vb, &cb);
  CHECK(vb.verdict == want && cb, "%s: full path %s (%s), expected a certified %s", name,
        ss_verdict_name(vb.verdict), vb.reason, ss_verdict_name(want));
  CHECK(va.verdict == vb.verdict && ca == cb && !strcmp(va.reason, vb.reason),
        "%s: lazy %s certified %d (%s), full %s certified %d (%s)", name,
        ss_verdict_name(va.verdict), ca, va.reason, ss_verdict_name(vb.verdict), cb,
        vb.reason);
  size_t na = 0, nb = 0;
  const ss_exact_root *ra = ss_exact_roots(a, &na), *rb = ss_exact_roots(b, &nb);
  CHECK(na >= nb && nb >= 4, "%s: %zu lazy roots, %zu full", name, na, nb);
  for (size_t i = 0; i < 4 && i < nb && i < na; i++)
    CHECK(ra[i].re == rb[i].re && ra[i].im == rb[i].im && ra[i].mult == rb[i].mult,
          "%s: root %zu lazy %.17g%+.3gi x%d, full %.17g%+.3gi x%d", name, i, ra[i].re,
          ra[i].im, ra[i].mult, rb[i].re, rb[i].im, rb[i].mult);
  if (na > 1) deg = ra[1].degree;
  if (nb > 1) *full_degree = rb[1].degree;
  double la[NMAX * 3], ha[NMAX * 3], lb[NMAX * 3], hb[NMAX * 3];
  ss_error ea = {0}, eb = {0};
  const ss_status sa = ss_exact_basis(a, la, ha, &ea),
                  sb = ss_exact_basis(b, lb, hb, &eb);
  CHECK(sa == sb, "%s: basis lazy %d (%s), full %d (%s)", name, sa, ea.msg, sb, eb.msg);
  if (!sa && !sb)
    CHECK(!memcmp(la, lb, (size_t)(3 * n) * sizeof *la) &&
              !memcmp(ha, hb, (size_t)(3 * n) * sizeof *ha),
          "%s: the basis enclosures differ", name);
  long long qa[NMAX * 3], da[NMAX * 3], qb[NMAX * 3], db[NMAX * 3];
  const int xa = ss_exact_basis_rational(a, qa, da),
            xb = ss_exact_basis_rational(b, qb, db);
  CHECK(xa == xb, "%s: exact rational basis lazy %d, full %d", name, xa, xb);
  if (xa && xb)
    CHECK(!memcmp(qa, qb, (size_t)(3 * n) * sizeof *qa) &&
              !memcmp(da, db, (size_t)(3 * n) * sizeof *da),
          "%s: the rational bases differ", name);
done:
  ss_exact_free(a);
  ss_exact_free(b);
  return deg;
}

int main(void) {
  /* an irreducible cubic with roots near 0.9, 0.8, 0.7 (its constant
   * -0.5039 instead of -0.504: no rational root, still three real ones), and x^10 - 2^-18
   * (roots of modulus 0.287; (x^5 - 2^-9) (x^5 + 2^-9): a kept part with three
   * irreducible factors) */
  const double cubic[3] = {-0.5039, 1.91, -2.4}, tenth[10] = {-1.0 / 262144.0};
  const double circle[2] = {1.0, 0.0}; /* x^2 + 1: roots of modulus 1 */
  static double B[NMAX * NMAX], S[NMAX * NMAX];
  int nb = 0, full = 0;

  companion(B, &nb, cubic, 3);
  companion(B, &nb, tenth, 10);
  int n = assemble(B, nb, S);
  int lazy = same("generic", S, n, SS_PASS, &full);
  CHECK(full == 3 && lazy == 13,
        "generic: lambda1's polynomial of degree %d lazy (13: the kept part, so the "
        "lazy path ran), %d full (3)",
        lazy, full);

  memset(B, 0, sizeof B);
  nb = 0;
  companion(B, &nb, cubic, 3);
  companion(B, &nb, circle, 2);
  companion(B, &nb, tenth, 10);
  n = assemble(B, nb, S);
  same("x^2 + 1 inside the kept part", S, n, SS_FAIL, &full);

  /* lambda1..3 = 3000/4099, 2500/4111, 2000/4127 on the diagonal */
  memset(B, 0, sizeof B);
  B[0] = 3000.0 / 4099.0;
  B[NMAX + 1] = 2500.0 / 4111.0;
  B[2 * NMAX + 2] = 2000.0 / 4127.0;
  B[NMAX] = B[2 * NMAX + 1] = 0.25;
  nb = 3;
  companion(B, &nb, tenth, 10);
  n = assemble(B, nb, S);
  same("rational lambda1..3 with large denominators", S, n, SS_PASS, &full);
  CHECK(full == 1, "rational lambda1..3: full degree %d, expected 1", full);
  return ss_test_done("exact_lazy");
}
