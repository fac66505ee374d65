/* ss_exact_squarefree.c — the one-ring block's characteristic polynomial
 * factored only as far as the verdicts need (ss_exact_opts.lazy,
 * ss_exact_impl.h): its squarefree parts (FLINT's squarefree
 * decomposition), the linear factors of the simple part found from the
 * block's LAPACK eigenvalues and checked exactly, and the rest of that part
 * kept whole, its irreducibility not proven.
 *
 * Why.  At MLCA k = 14 the one-ring block's polynomial is four or five
 * linear factors times one irreducible factor of degree 68-70 (or, on a
 * symmetric link, a few factors of degree 12-40); fmpz_poly_factor proves
 * that factor irreducible by Hensel lifting to Mignotte's bound and
 * recombination, 6-12 ms of a certified case's 85, and nothing the verdicts
 * say about such a case reads that proof: its roots are simple eigenvalues
 * of S proven below lambda_m, and every step that does read a factor's
 * irreducibility (ss_exact.c, lazy_premises and lazy_accepted) makes the
 * exact path start again with fmpz_poly_factor.
 *
 * What the rest h is: squarefree (a part of the squarefree decomposition
 * with linear factors divided out), primitive, of multiplicity 1 in the
 * block.  Its roots are isolated as any factor's (arb's isolation needs a
 * squarefree polynomial only). */
#include <math.h>
#include <stdlib.h>

#include <flint/fmpq.h>
#include <flint/fmpz_poly_factor.h>

#include "ss_exact_impl.h"

enum {
  SQ_MIN_DEGREE = 12, /* a smaller simple part: FLINT's factors (fast there) */
  SQ_MAX_DEN = 4096   /* largest denominator of a candidate rational root
                         (ss_exact_rational_within) */
};

static const double SQ_TOL = 1e-10; /* a candidate's distance to the eigenvalue,
                                       relative to max(1, |eigenvalue|) */

/* Divide out of h (primitive, squarefree) each linear factor b y - a whose
 * root a / b = scale v is exact for a real candidate v among cand (re, im
 * interleaved, ncand of them), inserting it into fac with exponent e. */
static void split_linear(fmpz_poly_factor_t fac, fmpz_poly_t h, slong e,
                         const fmpz_t scale, const double *cand, size_t ncand) {
  fmpq_t r, val;
  fmpz_poly_t lin, q;
  fmpq_init(r);
  fmpq_init(val);
  fmpz_poly_init(lin);
  fmpz_poly_init(q);
  for (size_t i = 0; i < ncand && fmpz_poly_degree(h) > 1; i++) {
    const double re = cand[2 * i], im = cand[2 * i + 1];
    long long a = 0, b = 1; /* the nearest rational, as the exact path reads S */
    if (fabs(im) > SQ_TOL * fmax(1.0, fabs(re)) ||
        !ss_exact_rational_within(re, SQ_MAX_DEN, SQ_TOL, &a, &b) || !a)
      continue;
    fmpz_mul_si(fmpq_numref(r), scale, (slong)a);
    fmpz_set_si(fmpq_denref(r), (slong)b);
    fmpq_canonicalise(r);
    fmpz_poly_evaluate_fmpq(val, h, r);
    if (!fmpq_is_zero(val)) continue;
    fmpz_poly_zero(lin);
    fmpz_poly_set_coeff_fmpz(lin, 1, fmpq_denref(r));
    fmpz_neg(fmpq_numref(r), fmpq_numref(r));
    fmpz_poly_set_coeff_fmpz(lin, 0, fmpq_numref(r));
    if (!fmpz_poly_divides(q, h, lin)) continue; /* cannot happen: h(r) = 0 */
    fmpz_poly_swap(h, q);
    fmpz_poly_factor_insert(fac, lin, e);
  }
  fmpq_clear(r);
  fmpq_clear(val);
  fmpz_poly_clear(lin);
  fmpz_poly_clear(q);
}

/* FLINT's factors of the squarefree primitive h, inserted with exponent e
 * (t: scratch). */
static void flint_part(fmpz_poly_factor_t fac, const fmpz_poly_t h, slong e,
                       fmpz_poly_factor_t t) {
  fmpz_poly_factor(t, h);
  for (slong i = 0; i < t->num; i++)
    fmpz_poly_factor_insert(fac, t->p + i, e * t->exp[i]);
}

slong ss_exact_factor_lazy(fmpz_poly_factor_t fac, const fmpz_poly_t G,
                           const fmpz_t scale, const double *cand, size_t ncand) {
  fac->num = 0;
  fmpz_poly_t g, h;
  fmpz_poly_init(g);
  fmpz_poly_init(h);
  slong k = 0, kept = -1; /* as fmpz_poly_factor: the factor x^k first */
  while (fmpz_is_zero(G->coeffs + k))
    k++;
  if (k) {
    fmpz_poly_set_coeff_ui(h, 1, 1);
    fmpz_poly_factor_insert(fac, h, k);
  }
  fmpz_poly_shift_right(g, G, k);
  fmpz_poly_factor_t sq, t;
  fmpz_poly_factor_init(sq);
  fmpz_poly_factor_init(t);
  fmpz_poly_factor_squarefree(sq, g);
  fmpz_set(&fac->c, &sq->c);
  for (slong j = 0; j < sq->num; j++) {
    const slong e = sq->exp[j];
    fmpz_poly_primitive_part(h, sq->p + j);
    if (e == 1 && fmpz_poly_degree(h) >= SQ_MIN_DEGREE)
      split_linear(fac, h, e, scale, cand, ncand);
    const slong dh = fmpz_poly_degree(h);
    if (e == 1 && dh >= SQ_MIN_DEGREE) {
      kept = fac->num;
      fmpz_poly_factor_insert(fac, h, e);
    } else if (dh >= 1) {
      flint_part(fac, h, e, t);
    }
  }
  fmpz_poly_factor_clear(t);
  fmpz_poly_factor_clear(sq);
  fmpz_poly_clear(g);
  fmpz_poly_clear(h);
  return kept;
}
