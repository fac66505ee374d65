/* ss_exact_isolate.c — the roots of the exact spectrum's factors isolated in
 * ball arithmetic (ss_exact_impl.h), started from the block's eigenvalues.
 *
 * arb_fmpz_poly_complex_roots starts Durand-Kerner from generic points on a
 * spiral at 32 bits and doubles the precision until the roots are isolated
 * and accurate.  The one-ring block's characteristic polynomial has an
 * irreducible factor of degree 50-60 at k = 12 whose roots, clustered in
 * (-0.2, 0.7), are badly conditioned in the monomial basis (in doubles they
 * cannot even be approximated): its first isolation took most of a
 * certified case's time (bench_pipeline --phases --certify: 41 % at MLCA
 * k = 12, 0.15 s per factor).  The eigenproblem is well conditioned, so the
 * block's eigenvalues from LAPACK (in doubles, from the rational entries)
 * are accurate to about 1e-13: each is given to the factor of the block
 * with the smallest Newton step |g / g'| there, and a factor of
 * multiplicity 1 in the block that got exactly deg g of them starts
 * Durand-Kerner from them at twice the target precision.  The balls are
 * accepted only as arb accepts its own: every root isolated by the
 * inclusion test (acb_poly_find_roots), relatively accurate to the target
 * precision, the real ones proven real, no two balls meeting; so what is
 * proven does not depend on where the iteration started, only the balls'
 * last bits do.  A refinement to a higher precision starts from the balls
 * it has.  Anything else (no seeds, a first attempt that does not isolate)
 * is arb_fmpz_poly_complex_roots as before. */
#include <math.h>
#include <stdlib.h>

#include <lapacke.h>

#include "arb_fmpz_poly.h"
#include "arf.h"

#include "ss_clock.h"
#include "ss_exact_impl.h"

/* No two balls of the roots with nonnegative imaginary midpoints meet (the
 * others are their conjugates). */
static int isolated_balls(acb_srcptr z, slong d) {
  for (slong i = 0; i < d; i++) {
    if (arf_sgn(arb_midref(acb_imagref(z + i))) < 0) continue;
    for (slong j = i + 1; j < d; j++)
      if (arf_sgn(arb_midref(acb_imagref(z + j))) >= 0 && acb_overlaps(z + i, z + j))
        return 0;
  }
  return 1;
}

/* log2 |c| for a nonzero integer c, in doubles. */
static double log2_abs(const fmpz_t c) {
  slong e;
  const double m = fmpz_get_d_2exp(&e, c);
  return log2(fabs(m)) + (double)e;
}

static int accurate(acb_srcptr z, slong d, slong bits) {
  for (slong i = 0; i < d; i++)
    if (acb_rel_accuracy_bits(z + i) < bits) return 0;
  return 1;
}

/* Sorted as arb sorts them (_acb_vec_sort_pretty), then the complex ones
 * paired: each root of positive imaginary part followed by its conjugate.
 * tmp has room for d balls. */
static void arrange(acb_ptr z, slong d, acb_ptr tmp) {
  _acb_vec_sort_pretty(z, d);
  slong nreal = 0, m = 0;
  for (slong i = 0; i < d; i++)
    nreal += acb_is_real(z + i);
  if (nreal == d) return;
  for (slong i = nreal; i < d; i++)
    if (arb_is_positive(acb_imagref(z + i))) acb_swap(tmp + m++, z + i);
  for (slong i = 0; i < m; i++) {
    acb_swap(z + nreal + 2 * i, tmp + i);
    acb_conj(z + nreal + 2 * i + 1, z + nreal + 2 * i);
  }
}

/* The first precision of the seeded iteration: 2 times target, or target +
 * L + 32 rounded up to whole limbs (at most 8 times target), L the bits a root's ball
 * loses when its radius is validated (acb_poly_find_roots's inclusion radius d |f(z)| /
 * |f'(z)| with f(z) evaluated in balls, relative to |z|): L = max over the
 * seeds z_i of log2(d sum_k |c_k| |z_i|^k / (|c_d| prod_(j != i) |z_i - z_j|
 * |z_i|)), in doubles from the seeds (f'(z_i) = c_d prod (z_i - z_j) at the
 * roots).  MLCA k = 14's degree-68 factor loses 130-250 bits: at twice the
 * target (256) its roots were isolated but not accurate, and that attempt,
 * a third of its isolation, was wasted.  Only where to start: every attempt
 * is accepted by the same tests. */
static slong first_prec(const fmpz_poly_t f, acb_srcptr seeds, slong d, slong target) {
  double *lc = malloc((size_t)(d + 1) * sizeof *lc), *zr = malloc((size_t)d * sizeof *zr),
         *zi = malloc((size_t)d * sizeof *zi);
  double L = 0.0;
  int ok = lc && zr && zi;
  for (slong k = 0; ok && k <= d; k++) /* log2 |c_k|, -inf for 0 */
    lc[k] = fmpz_is_zero(f->coeffs + k) ? -HUGE_VAL : log2_abs(f->coeffs + k);
  for (slong i = 0; ok && i < d; i++) {
    zr[i] = arf_get_d(arb_midref(acb_realref(seeds + i)), ARF_RND_NEAR);
    zi[i] = arf_get_d(arb_midref(acb_imagref(seeds + i)), ARF_RND_NEAR);
  }
  for (slong i = 0; ok && i < d; i++) {
    const double r = hypot(zr[i], zi[i]), lr = log2(r);
    if (!(r > 0.0) || !isfinite(lr)) {
      ok = 0;
      break;
    }
    double top = -HUGE_VAL; /* log2 sum_k |c_k| r^k */
    for (slong k = 0; k <= d; k++)
      top = fmax(top, lc[k] + (double)k * lr);
    double sum = 0.0;
    for (slong k = 0; k <= d; k++)
      if (lc[k] > -HUGE_VAL) sum += exp2(lc[k] + (double)k * lr - top);
    double li = log2((double)d) + top + log2(sum) - lc[d] - lr;
    for (slong j = 0; j < d; j++)
      if (j != i) li -= log2(hypot(zr[i] - zr[j], zi[i] - zi[j]));
    if (!isfinite(li)) {
      ok = 0;
      break;
    }
    L = fmax(L, li);
  }
  free(lc);
  free(zr);
  free(zi);
  if (!ok || (double)target + L + 32.0 <= 2.0 * (double)target) return 2 * target;
  if ((double)target + L + 32.0 >= 8.0 * (double)target) return 8 * target;
  return ((slong)ceil((double)target + L + 32.0) + 63) / 64 * 64; /* whole limbs */
}

void ss_exact_complex_roots(acb_ptr roots, const fmpz_poly_t f, acb_srcptr seeds,
                            slong target_prec) {
  const slong d = fmpz_poly_degree(f);
  if (!seeds || d < 2 || fmpz_is_zero(f->coeffs) || arb_fmpz_poly_deflation(f) != 1) {
    arb_fmpz_poly_complex_roots(roots, f, 0, target_prec);
    return;
  }
  acb_ptr tmp = _acb_vec_init(d), start = _acb_vec_init(d);
  acb_poly_t cp;
  acb_poly_init(cp);
  _acb_vec_set(start, seeds, d);
  int ok = 0;
  /* from the precision the seeds' condition numbers ask for (at least twice
   * the target: a badly conditioned factor, MLCA k = 14's degree 68-70 one,
   * needs more), doubled up to 8 times the target; each attempt starts from
   * the last one's midpoints */
  for (slong prec = first_prec(f, seeds, d, target_prec), last = 0; !ok && !last;
       prec = FLINT_MIN(2 * prec, 8 * target_prec)) {
    last = prec >= 8 * target_prec;
    acb_poly_set_fmpz_poly(cp, f, prec);
    const slong got =
        acb_poly_find_roots(roots, cp, start, FLINT_MIN(4 * d + 64, prec), prec);
    ok = got == d && accurate(roots, d, target_prec) &&
         acb_poly_validate_real_roots(roots, cp, prec);
    if (ok) {
      for (slong i = 0; i < d; i++)
        if (arb_contains_zero(acb_imagref(roots + i))) arb_zero(acb_imagref(roots + i));
      ok = isolated_balls(roots, d);
    }
    int finite = 1;
    for (slong i = 0; i < d; i++)
      finite &= acb_is_finite(roots + i);
    for (slong i = 0; !ok && finite && i < d; i++)
      acb_get_mid(start + i, roots + i);
  }
  if (ok)
    arrange(roots, d, tmp);
  else
    arb_fmpz_poly_complex_roots(roots, f, 0, target_prec);
  acb_poly_clear(cp);
  _acb_vec_clear(tmp, d);
  _acb_vec_clear(start, d);
}

/* |g(z) / g'(z)| into r, at a precision that resolves it (doubled from 128
 * bits until the quotient has 8 correct bits, at most 4096): the factors'
 * coefficients are large and z is near a root, so at a fixed 128 bits the
 * value of a degree 60-70 factor was noise and eigenvalues went to the
 * wrong factors (MLCA k = 14: 41 of 68 given to the right one). */
static void newton_step(arb_t r, const fmpz_poly_t g, const fmpz_poly_t dg, const acb_t z,
                        acb_t v, acb_t w) {
  for (slong p = 128;; p *= 2) {
    arb_fmpz_poly_evaluate_acb(v, g, z, p);
    arb_fmpz_poly_evaluate_acb(w, dg, z, p);
    acb_div(v, v, w, p);
    if (acb_rel_accuracy_bits(v) >= 8 || p >= 4096) break;
  }
  acb_abs(r, v, 128);
}

/* The blocks' eigenvalues (x->ev, x->evb: block b's) each given to the factor
 * of its own block with the smallest Newton step |g(z) / g'(z)| at it
 * (x->evf), in balls (the double is exact there).  Seeds only: nothing
 * proven depends on this. */
static void give_eigenvalues(ss_exact *x) {
  fmpz_poly_t dg;
  acb_t z, v, w;
  arb_t r, best;
  fmpz_poly_init(dg);
  acb_init(z);
  acb_init(v);
  acb_init(w);
  arb_init(r);
  arb_init(best);
  for (size_t i = 0; i < x->nev; i++) {
    const size_t blk = x->evb[i];
    x->evf[i] = -1;
    acb_set_d_d(z, x->ev[2 * i], x->ev[2 * i + 1]);
    for (size_t b = x->bstart[blk]; b < x->bstart[blk + 1]; b++) {
      const size_t k = x->bfac[b];
      fmpz_poly_derivative(dg, x->fac[k].f);
      newton_step(r, x->fac[k].f, dg, z, v, w);
      if (!arb_is_finite(r)) continue;
      if (x->evf[i] < 0 || arf_cmp(arb_midref(r), arb_midref(best)) < 0) {
        x->evf[i] = (long)k;
        arb_set(best, r);
      }
    }
  }
  fmpz_poly_clear(dg);
  acb_clear(z);
  acb_clear(v);
  acb_clear(w);
  arb_clear(r);
  arb_clear(best);
}

/* Block blk's matrix (0: the one-ring block A; 1 + c: outer component c) as
 * row-major doubles, the rationals rounded, into a (sz x sz). */
static void block_doubles(const ss_exact *x, size_t blk, double *a, size_t sz) {
  for (size_t i = 0; i < sz * sz; i++)
    a[i] = 0.0;
  for (size_t u = 0; u < sz; u++) {
    const size_t row = blk ? x->n1 + x->K.comp[x->K.start[blk - 1] + u] : u;
    for (size_t k = x->A.ptr[row]; k < x->A.ptr[row + 1]; k++) {
      const size_t j = x->A.col[k];
      const double q = (double)x->q[k].num / (double)x->q[k].den;
      if (!blk && j < x->n1)
        a[u * sz + j] = q;
      else if (blk && j >= x->n1 && x->K.cid[j - x->n1] == blk - 1)
        a[u * sz + x->K.pos[j - x->n1]] = q;
    }
  }
}

int ss_exact_eigen_seeds(ss_exact *x) {
  if (!x->ev && ss_exact_eigen_values(x)) return -1;
  give_eigenvalues(x);
  return 0;
}

int ss_exact_eigen_values(ss_exact *x) {
  const size_t n = x->n;
  x->ev = malloc((2 * n + 1) * sizeof *x->ev);
  x->evf = malloc((n + 1) * sizeof *x->evf);
  x->evb = malloc((n + 1) * sizeof *x->evb);
  size_t big = x->n1;
  for (long c = 0; c < x->K.n; c++)
    big = FLINT_MAX(big, x->K.start[c + 1] - x->K.start[c]);
  double *a = malloc((big * big + 1) * sizeof *a), *wr = malloc((big + 1) * sizeof *wr),
         *wi = malloc((big + 1) * sizeof *wi);
  int rc = -1;
  if (!a || !wr || !wi || !x->ev || !x->evf || !x->evb) goto done;
  x->nev = 0;
  for (size_t blk = 0; blk < x->nblk; blk++) {
    const size_t sz = blk ? x->K.start[blk] - x->K.start[blk - 1] : x->n1;
    if (sz < 2) continue; /* a linear factor needs no seed */
    block_doubles(x, blk, a, sz);
    if (LAPACKE_dgeev(LAPACK_ROW_MAJOR, 'N', 'N', (lapack_int)sz, a, (lapack_int)sz, wr,
                      wi, NULL, 1, NULL, 1))
      continue; /* no seeds for this block: arb's own start */
    for (size_t i = 0; i < sz; i++, x->nev++) {
      x->ev[2 * x->nev] = wr[i];
      x->ev[2 * x->nev + 1] = wi[i];
      x->evb[x->nev] = blk;
    }
  }
  rc = 0;
done:
  free(a);
  free(wr);
  free(wi);
  return rc;
}

/* Seeds for factor k from the eigenvalues given to it: a new vector of d
 * balls when it got exactly d = deg of them and divides exactly one block,
 * once, else NULL. */
static acb_ptr eigen_seeds(const ss_exact *x, size_t k, slong d) {
  if (!x->ev) return NULL;
  int once = 0, blocks = 0;
  for (size_t blk = 0; blk < x->nblk; blk++)
    for (size_t b = x->bstart[blk]; b < x->bstart[blk + 1]; b++)
      if (x->bfac[b] == k) {
        blocks++;
        once = x->bmult[b] == 1;
      }
  slong got = 0;
  for (size_t i = 0; i < x->nev; i++)
    got += x->evf[i] == (long)k;
  if (blocks != 1 || !once || got != d) return NULL;
  acb_ptr s = _acb_vec_init(d);
  got = 0;
  for (size_t i = 0; i < x->nev; i++)
    if (x->evf[i] == (long)k) acb_set_d_d(s + got++, x->ev[2 * i], x->ev[2 * i + 1]);
  return s;
}

void ss_exact_isolate(ss_exact *x, size_t k, long prec) {
  double c1 = x->o.times ? ss_clock_cpu() : 0.0;
  ss_exact_factor *F = x->fac + k;
  const slong d = fmpz_poly_degree(F->f);
  ss_exact_rt *R = x->rt + F->root0;
  if (d == 1) { /* -c0 / c1, exactly */
    fmpq_t r;
    fmpq_init(r);
    fmpz_neg(fmpq_numref(r), F->f->coeffs);
    fmpz_set(fmpq_denref(r), F->f->coeffs + 1);
    fmpq_canonicalise(r);
    arb_set_fmpq(acb_realref(&R->z), r, prec);
    arb_zero(acb_imagref(&R->z));
    R->real = 1;
    fmpq_clear(r);
  } else {
    acb_ptr z = _acb_vec_init(d), s = NULL;
    if (F->prec > 0) { /* a refinement: from the balls it has */
      s = _acb_vec_init(d);
      for (slong i = 0; i < d; i++)
        acb_set(s + i, &R[i].z);
    } else {
      s = eigen_seeds(x, k, d);
    }
    ss_exact_complex_roots(z, F->f, s, prec); /* F->f is squarefree */
    for (slong i = 0; i < d; i++) {
      acb_set(&R[i].z, z + i);
      R[i].real = acb_is_real(z + i);
    }
    _acb_vec_clear(z, d);
    if (s) _acb_vec_clear(s, d);
  }
  const long mp = x->o.maxprec + 64;
  for (slong i = 0; i < d; i++) {
    if (F->exact_nsq) {
      arb_t t;
      arb_init(t);
      arb_set_fmpq(t, &R[i].nsq, mp);
      arb_sqrt(&R[i].mod, t, mp);
      arb_clear(t);
    } else {
      acb_abs(&R[i].mod, &R[i].z, prec + 32);
    }
  }
  F->prec = prec;
  if (x->o.times) ss_clock_lap(&x->o.times->isolate, &c1);
}
