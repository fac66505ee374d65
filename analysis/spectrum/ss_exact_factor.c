/* ss_exact_factor.c — the exact spectrum by blocks: the characteristic
 * polynomial of each diagonal block of S factored over Q, the distinct
 * irreducible factors merged with their multiplicities, and their roots
 * isolated in ball arithmetic (ss_exact_impl.h). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_mat.h>
#include <flint/fmpz_poly_factor.h>
#include <flint/fmpz_vec.h>

#include "arb_fmpz_poly.h"
#include "arf.h"

#include "ss_clock.h"
#include "ss_exact_impl.h"

/* Index of the factor equal to g (normalised), or -1. */
static long find_factor(const ss_exact *x, const fmpz_poly_t g) {
  for (size_t k = 0; k < x->nfac; k++)
    if (fmpz_poly_equal(x->fac[k].f, g)) return (long)k;
  return -1;
}

/* Add multiplicity e of the normalised irreducible g to block b's list and to
 * the merged factors.  SS_ENOMEM. */
static ss_status add_factor(ss_exact *x, size_t b, const fmpz_poly_t g, int e,
                            int unproven, ss_error *err) {
  long k = find_factor(x, g);
  if (k >= 0 && (unproven || x->fac[k].unproven)) x->lazy_bad = 1;
  if (k < 0) {
    if (x->nfac == x->facalloc) {
      size_t na = x->facalloc ? 2 * x->facalloc : 16;
      ss_exact_factor *nf = realloc(x->fac, na * sizeof *nf);
      if (!nf) return ss_error_nomem(err, "factors");
      x->fac = nf;
      x->facalloc = na;
    }
    k = (long)x->nfac++;
    ss_exact_factor *F = x->fac + k;
    memset(F, 0, sizeof *F);
    fmpz_poly_init(F->f);
    fmpz_poly_set(F->f, g);
    F->refl = -1;
    F->unproven = unproven;
  }
  x->fac[k].mult += e;
  /* each block lists a factor once (distinct factors of one polynomial) */
  const size_t at = x->bstart[b + 1]++;
  x->bfac[at] = (size_t)k;
  x->bmult[at] = e;
  return SS_OK;
}

/* The number of block b's eigenvalues at the start of x->ev (b = 0, the
 * one-ring block, is computed first). */
static size_t eigen_count(const ss_exact *x, size_t b) {
  size_t ne = 0;
  while (ne < x->nev && x->evb[ne] == b)
    ne++;
  return ne;
}

/* The rows (= columns) of block b of S: the one-ring, or outer component
 * b - 1.  Returns their number; idx has room for the largest block. */
size_t ss_exact_block_rows(const ss_exact *x, size_t b, size_t *idx) {
  if (b == 0) {
    for (size_t i = 0; i < x->n1; i++)
      idx[i] = i;
    return x->n1;
  }
  const size_t s = x->K.start[b - 1], len = x->K.start[b] - s;
  for (size_t i = 0; i < len; i++)
    idx[i] = x->n1 + x->K.comp[s + i];
  return len;
}

/* The characteristic polynomial of block b (rows idx[0..len)), factored into
 * the merged list.  It is computed with each row scaled by its own
 * denominator (ss_exact_charpoly: P = (prod d_r) det(x - block)) and turned
 * into that of the block scaled by the lcm D of its denominators, the integer
 * matrix M = D block: det(y - M) = D^len det(y/D - block), whose coefficient
 * of y^j is D^(len-j) P_j / prod d_r; factored as before (the one-ring
 * block with ss_exact_opts.lazy: ss_exact_factor_lazy), each irreducible
 * factor g(y) of M's polynomial gives the factor g(D x) of the block's, made
 * primitive (a linear substitution keeps it irreducible).  SS_ENOMEM. */
static ss_status block_charpoly(ss_exact *x, size_t b, const size_t *idx, size_t len,
                                ss_error *err) {
  ss_status st = SS_OK;
  fmpz_poly_t g, cp;
  fmpz_poly_init(g);
  fmpz_poly_init(cp);
  if (len == 1) { /* den x - num */
    fmpq_t v;
    fmpq_init(v);
    ss_exact_get(x, idx[0], idx[0], v);
    fmpz_poly_set_coeff_fmpz(g, 1, fmpq_denref(v));
    fmpz_neg(fmpq_numref(v), fmpq_numref(v));
    fmpz_poly_set_coeff_fmpz(g, 0, fmpq_numref(v));
    fmpq_clear(v);
    st = add_factor(x, b, g, 1, 0, err);
    goto done;
  }
  fmpz_mat_t N;
  fmpz_t D, Dk, c, prod;
  fmpz_mat_init(N, (slong)len, (slong)len);
  fmpz *d = _fmpz_vec_init((slong)len);
  fmpz_init(D);
  fmpz_init(Dk);
  fmpz_init(c);
  fmpz_init(prod);
  fmpz_poly_factor_t fac;
  fmpz_poly_factor_init(fac);
  if (ss_exact_principal_rows(x, idx, len, d, N)) {
    st = ss_error_nomem(err, "characteristic polynomial");
  } else {
    ss_exact_times *tm = x->o.times;
    double c1 = tm ? ss_clock_cpu() : 0.0;
    ss_exact_charpoly(g, N, d);
    fmpz_one(D);
    fmpz_one(prod);
    for (size_t r = 0; r < len; r++) {
      fmpz_lcm(D, D, d + r);
      fmpz_mul(prod, prod, d + r);
    }
    fmpz_one(Dk); /* D^(len - j), j from len down */
    for (slong j = (slong)len; j >= 0; j--) {
      fmpz_poly_get_coeff_fmpz(c, g, j);
      fmpz_mul(c, c, Dk);
      fmpz_divexact(c, c, prod);
      fmpz_poly_set_coeff_fmpz(cp, j, c);
      fmpz_mul(Dk, Dk, D);
    }
    if (tm) ss_clock_lap(&tm->charpoly, &c1);
    slong kept = -1; /* the unproven factor (lazy, the one-ring block) */
    if (x->o.lazy && b == 0) fmpz_set(&x->dA, D);
    if (x->o.lazy && b == 0)
      kept = ss_exact_factor_lazy(fac, cp, D, x->ev, x->ev ? eigen_count(x, 0) : 0);
    else
      fmpz_poly_factor(fac, cp);
    if (tm) ss_clock_lap(&tm->factor, &c1);
    for (slong i = 0; i < fac->num && !st; i++) {
      const slong deg = fmpz_poly_degree(fac->p + i);
      fmpz_poly_zero(g);
      fmpz_one(Dk);
      for (slong j = 0; j <= deg; j++) {
        fmpz_poly_get_coeff_fmpz(c, fac->p + i, j);
        fmpz_mul(c, c, Dk);
        fmpz_poly_set_coeff_fmpz(g, j, c);
        fmpz_mul(Dk, Dk, D);
      }
      fmpz_poly_primitive_part(g, g); /* also makes the leading coefficient > 0 */
      st = add_factor(x, b, g, (int)fac->exp[i], i == kept, err);
    }
  }
  fmpz_poly_factor_clear(fac);
  fmpz_mat_clear(N);
  _fmpz_vec_clear(d, (slong)len);
  fmpz_clear(D);
  fmpz_clear(Dk);
  fmpz_clear(c);
  fmpz_clear(prod);
done:
  fmpz_poly_clear(g);
  fmpz_poly_clear(cp);
  return st;
}

/* Whether blocks a and b (rows ia, ib of equal length) have the same entries
 * in the same order: then they have the same characteristic polynomial. */
static int same_block(const ss_exact *x, const size_t *ia, const size_t *ib, size_t len,
                      fmpq_t u, fmpq_t v) {
  for (size_t r = 0; r < len; r++)
    for (size_t c = 0; c < len; c++) {
      ss_exact_get(x, ia[r], ia[c], u);
      ss_exact_get(x, ib[r], ib[c], v);
      if (!fmpq_equal(u, v)) return 0;
    }
  return 1;
}

/* The factors of every diagonal block.  Equal outer blocks (the lattice
 * repeats them) are factored once: a later copy takes the list of the first.
 * SS_ENOMEM. */
ss_status ss_exact_all_blocks(ss_exact *x, ss_error *err) {
  const size_t big = x->K.largest > x->n1 ? x->K.largest : x->n1;
  size_t *idx = malloc((big + 1) * sizeof *idx), *jdx = malloc((big + 1) * sizeof *jdx);
  size_t *first = malloc((x->nblk + 1) * sizeof *first); /* distinct blocks > 1 x 1 */
  size_t nfirst = 0;
  ss_status st = SS_OK;
  fmpq_t u, v;
  fmpq_init(u);
  fmpq_init(v);
  if (!idx || !jdx || !first) {
    st = ss_error_nomem(err, "blocks");
    goto done;
  }
  x->bstart[0] = 0;
  for (size_t b = 0; b < x->nblk && !st; b++) {
    x->bstart[b + 1] = x->bstart[b];
    const size_t len = ss_exact_block_rows(x, b, idx);
    size_t hit = SIZE_MAX;
    for (size_t h = 0; b > 0 && len > 1 && h < nfirst && hit == SIZE_MAX; h++)
      if (ss_exact_block_rows(x, first[h], jdx) == len &&
          same_block(x, idx, jdx, len, u, v))
        hit = first[h];
    x->brep[b] = hit == SIZE_MAX ? b : hit;
    if (hit == SIZE_MAX) {
      st = block_charpoly(x, b, idx, len, err);
      if (len > 1 && b > 0) first[nfirst++] = b;
      continue;
    }
    for (size_t k = x->bstart[hit]; k < x->bstart[hit + 1]; k++) {
      const size_t at = x->bstart[b + 1]++;
      x->bfac[at] = x->bfac[k];
      x->bmult[at] = x->bmult[k];
      x->fac[x->bfac[k]].mult += x->bmult[k];
    }
  }
done:
  fmpq_clear(u);
  fmpq_clear(v);
  free(idx);
  free(jdx);
  free(first);
  return st;
}

/* The root count, reflections, exact moduli, and first isolation.
 * SS_ENOMEM. */
ss_status ss_exact_roots_init(ss_exact *x, ss_error *err) {
  size_t nrt = 0;
  for (size_t k = 0; k < x->nfac; k++) {
    x->fac[k].root0 = nrt;
    nrt += (size_t)fmpz_poly_degree(x->fac[k].f);
  }
  x->rt = calloc(nrt + 1, sizeof *x->rt);
  x->order = malloc((nrt + 1) * sizeof *x->order);
  x->roots = calloc(nrt + 1, sizeof *x->roots);
  if (!x->rt || !x->order || !x->roots) return ss_error_nomem(err, "roots");
  x->nrt = nrt;
  for (size_t i = 0; i < nrt; i++) {
    acb_init(&x->rt[i].z);
    arb_init(&x->rt[i].mod);
    fmpq_init(&x->rt[i].nsq);
  }
  fmpz_poly_t g;
  fmpz_poly_init(g);
  fmpq_t v;
  fmpq_init(v);
  for (size_t k = 0; k < x->nfac; k++) {
    ss_exact_factor *F = x->fac + k;
    const slong d = fmpz_poly_degree(F->f);
    /* f(-x): negate the odd coefficients */
    fmpz_poly_set(g, F->f);
    for (slong j = 1; j <= d; j += 2)
      fmpz_neg(g->coeffs + j, g->coeffs + j);
    fmpz_poly_primitive_part(g, g);
    F->refl = find_factor(x, g);
    /* exact |root|^2: (c0/c1)^2; c0/c2 for complex roots of a quadratic
     * (their product); 1 on cyclotomic factors */
    const fmpz *c = F->f->coeffs;
    F->exact_nsq = 1;
    if (d == 1) {
      fmpq_set_fmpz_frac(v, c, c + 1);
      fmpq_mul(v, v, v);
    } else if (d == 2) {
      fmpz_t disc; /* c1^2 - 4 c2 c0 */
      fmpz_init(disc);
      fmpz_mul(disc, c, c + 2);
      fmpz_mul_si(disc, disc, -4);
      fmpz_addmul(disc, c + 1, c + 1);
      F->exact_nsq = fmpz_sgn(disc) < 0;
      if (F->exact_nsq) fmpq_set_fmpz_frac(v, c, c + 2);
      fmpz_clear(disc);
    } else if (fmpz_poly_is_cyclotomic(F->f)) {
      fmpq_one(v);
    } else {
      F->exact_nsq = 0;
    }
    for (slong i = 0; F->exact_nsq && i < d; i++)
      fmpq_set(&x->rt[F->root0 + (size_t)i].nsq, v);
    for (slong i = 0; i < d; i++)
      x->rt[F->root0 + (size_t)i].factor = k;
    ss_exact_isolate(x, k, x->o.prec);
  }
  fmpq_clear(v);
  fmpz_poly_clear(g);
  return SS_OK;
}
