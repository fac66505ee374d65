/* ss_exact.c — the rational matrix, its exact spectrum by blocks, the
 * certified order of the roots and the certified eigenvalue condition.
 * Method: ss_exact.h; the subdominant basis is in ss_exact_basis.c. */
#include "ss_exact.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_mat.h>
#include <flint/fmpz_poly_factor.h>

#include "arb_fmpz_poly.h"
#include "arf.h"

#include "ss_exact_impl.h"

/* Largest denominator bound accepted, and largest |entry| reconstructed (so
 * that numerators fit in 64 bits with room to spare). */
#define MAXDEN_LIMIT (1L << 31)
#define MAXABS       1048576.0

ss_exact_opts ss_exact_defaults(int dim) {
  ss_exact_opts o = {1L << 18, 128, 4096, dim, 400, 1};
  return o;
}

/* ---- rational reconstruction ---- */

/* The rational nearest to v >= 0 among those of denominator <= maxden: v
 * itself if its denominator is small enough, else the last convergent or
 * semiconvergent of v's continued fraction within the bound, whichever is
 * nearer (the best approximation theorem; as Python's limit_denominator). */
static void nearest_rational(fmpq_t r, const fmpq_t v, long maxden) {
  if (fmpz_cmp_si(fmpq_denref(v), maxden) <= 0) {
    fmpq_set(r, v);
    return;
  }
  fmpz_t p0, q0, p1, q1, a, q2, nn, dd, t;
  fmpz_init_set_ui(p0, 0);
  fmpz_init_set_ui(q0, 1);
  fmpz_init_set_ui(p1, 1);
  fmpz_init_set_ui(q1, 0);
  fmpz_init(a);
  fmpz_init(q2);
  fmpz_init_set(nn, fmpq_numref(v));
  fmpz_init_set(dd, fmpq_denref(v));
  fmpz_init(t);
  while (!fmpz_is_zero(dd)) {
    fmpz_fdiv_q(a, nn, dd);
    fmpz_set(q2, q0);
    fmpz_addmul(q2, a, q1);
    if (fmpz_cmp_si(q2, maxden) > 0) break;
    fmpz_set(t, p0); /* (p0, p1) = (p1, p0 + a p1), (q0, q1) = (q1, q2) */
    fmpz_addmul(t, a, p1);
    fmpz_swap(p0, p1);
    fmpz_swap(p1, t);
    fmpz_swap(q0, q1);
    fmpz_swap(q1, q2);
    fmpz_submul(nn, a, dd); /* (nn, dd) = (dd, nn - a dd) */
    fmpz_swap(nn, dd);
  }
  /* the first step always fits (q = 1), so q1 >= 1 here */
  fmpz_set_si(t, maxden);
  fmpz_sub(t, t, q0);
  fmpz_fdiv_q(a, t, q1); /* the largest semiconvergent step */
  fmpq_t b1, d1, d2;
  fmpq_init(b1);
  fmpq_init(d1);
  fmpq_init(d2);
  fmpz_set(fmpq_numref(b1), p0);
  fmpz_addmul(fmpq_numref(b1), a, p1);
  fmpz_set(fmpq_denref(b1), q0);
  fmpz_addmul(fmpq_denref(b1), a, q1);
  fmpq_canonicalise(b1);
  fmpq_set_fmpz_frac(r, p1, q1);
  fmpq_sub(d1, b1, v);
  fmpq_abs(d1, d1);
  fmpq_sub(d2, r, v);
  fmpq_abs(d2, d2);
  if (fmpq_cmp(d2, d1) > 0) fmpq_set(r, b1);
  fmpq_clear(b1);
  fmpq_clear(d1);
  fmpq_clear(d2);
  fmpz_clear(p0);
  fmpz_clear(q0);
  fmpz_clear(p1);
  fmpz_clear(q1);
  fmpz_clear(a);
  fmpz_clear(q2);
  fmpz_clear(nn);
  fmpz_clear(dd);
  fmpz_clear(t);
}

int ss_exact_rational(double s, long maxden, long long *p, long long *q) {
  if (!isfinite(s) || maxden < 1 || maxden > MAXDEN_LIMIT || !(fabs(s) <= MAXABS))
    return 0;
  arf_t f;
  fmpq_t v, r, d, bound;
  arf_init(f);
  fmpq_init(v);
  fmpq_init(r);
  fmpq_init(d);
  fmpq_init(bound);
  arf_set_d(f, s); /* exact */
  arf_get_fmpq(v, f);
  const int neg = fmpq_sgn(v) < 0;
  fmpq_abs(v, v);
  nearest_rational(r, v, maxden);
  fmpq_sub(d, r, v);
  fmpq_abs(d, d);
  if (fmpq_cmp_ui(v, 1) > 0)
    fmpq_set(bound, v);
  else
    fmpq_one(bound);
  fmpq_div_2exp(bound, bound, 40);
  int ok = fmpq_cmp(d, bound) <= 0 && fmpz_fits_si(fmpq_numref(r)) &&
           fmpz_fits_si(fmpq_denref(r));
  if (ok) {
    if (neg) fmpq_neg(r, r);
    *p = fmpz_get_si(fmpq_numref(r));
    *q = fmpz_get_si(fmpq_denref(r));
  }
  arf_clear(f);
  fmpq_clear(v);
  fmpq_clear(r);
  fmpq_clear(d);
  fmpq_clear(bound);
  return ok;
}

/* Reconstruct every entry and check the row sums.  SS_ENUMERIC naming the
 * entry or row, SS_ENOMEM. */
static ss_status reconstruct(ss_exact *x, const double *S, ss_error *err) {
  const size_t n = x->n;
  if (ss_csr_make(S, n, x->n1, &x->A)) return ss_error_nomem(err, "exact matrix");
  x->q = malloc((x->A.ptr[n] + 1) * sizeof *x->q);
  if (!x->q) return ss_error_nomem(err, "exact matrix");
  ss_status st = SS_OK;
  fmpq_t sum, t;
  fmpq_init(sum);
  fmpq_init(t);
  for (size_t i = 0; i < n && !st; i++) {
    fmpq_zero(sum);
    for (size_t k = x->A.ptr[i]; k < x->A.ptr[i + 1]; k++) {
      const double s = x->A.val[k];
      if (!ss_exact_rational(s, x->o.maxden, &x->q[k].num, &x->q[k].den)) {
        st = ss_error_set(err, SS_ENUMERIC,
                          "S[%zu][%zu] = %.17g is not a rational of denominator at most "
                          "%ld (within 2^-40): the exact path cannot certify this matrix",
                          i, x->A.col[k], s, x->o.maxden);
        break;
      }
      fmpq_set_si(t, x->q[k].num, (ulong)x->q[k].den);
      fmpq_add(sum, sum, t);
    }
    if (!st && !fmpq_is_one(sum)) {
      char *str = fmpq_get_str(NULL, 10, sum);
      st = ss_error_set(err, SS_ENUMERIC,
                        "row %zu of the rational matrix sums to %.60s, not exactly 1", i,
                        str ? str : "?");
      flint_free(str);
    }
  }
  fmpq_clear(sum);
  fmpq_clear(t);
  return st;
}

void ss_exact_get(const ss_exact *x, size_t i, size_t j, fmpq_t v) {
  size_t lo = x->A.ptr[i], hi = x->A.ptr[i + 1];
  while (lo < hi) { /* columns increase within a row */
    size_t mid = lo + (hi - lo) / 2;
    if (x->A.col[mid] < j)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo < x->A.ptr[i + 1] && x->A.col[lo] == j)
    fmpq_set_si(v, x->q[lo].num, (ulong)x->q[lo].den);
  else
    fmpq_zero(v);
}

int ss_exact_entry(const ss_exact *x, size_t i, size_t j, long long *p, long long *q) {
  if (!x || i >= x->n || j >= x->n) return 0;
  fmpq_t v;
  fmpq_init(v);
  ss_exact_get(x, i, j, v);
  *p = fmpz_get_si(fmpq_numref(v)); /* entries fit (ss_exact_rational) */
  *q = fmpz_get_si(fmpq_denref(v));
  fmpq_clear(v);
  return 1;
}

int ss_exact_principal(const ss_exact *x, const size_t *idx, size_t len, fmpz_t D,
                       fmpz_mat_t M) {
  size_t *at = malloc((x->n + 1) * sizeof *at); /* column -> place in idx */
  if (!at) return -1;
  for (size_t j = 0; j < x->n; j++)
    at[j] = SIZE_MAX;
  for (size_t c = 0; c < len; c++)
    at[idx[c]] = c;
  fmpz_one(D);
  for (size_t r = 0; r < len; r++)
    for (size_t k = x->A.ptr[idx[r]]; k < x->A.ptr[idx[r] + 1]; k++)
      if (at[x->A.col[k]] != SIZE_MAX) {
        fmpz_t d;
        fmpz_init_set_si(d, x->q[k].den);
        fmpz_lcm(D, D, d);
        fmpz_clear(d);
      }
  fmpz_mat_zero(M);
  fmpz_t t;
  fmpz_init(t);
  for (size_t r = 0; r < len; r++)
    for (size_t k = x->A.ptr[idx[r]]; k < x->A.ptr[idx[r] + 1]; k++) {
      const size_t c = at[x->A.col[k]];
      if (c == SIZE_MAX) continue;
      fmpz_divexact_si(t, D, x->q[k].den);
      fmpz_mul_si(fmpz_mat_entry(M, (slong)r, (slong)c), t, x->q[k].num);
    }
  fmpz_clear(t);
  free(at);
  return 0;
}

/* ---- factors ---- */

/* Index of the factor equal to g (normalised), or -1. */
static long find_factor(const ss_exact *x, const fmpz_poly_t g) {
  for (size_t k = 0; k < x->nfac; k++)
    if (fmpz_poly_equal(x->fac[k].f, g)) return (long)k;
  return -1;
}

/* Add multiplicity e of the normalised irreducible g to block b's list and to
 * the merged factors.  SS_ENOMEM. */
static ss_status add_factor(ss_exact *x, size_t b, const fmpz_poly_t g, int e,
                            ss_error *err) {
  long k = find_factor(x, g);
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
  }
  x->fac[k].mult += e;
  /* each block lists a factor once (distinct factors of one polynomial) */
  const size_t at = x->bstart[b + 1]++;
  x->bfac[at] = (size_t)k;
  x->bmult[at] = e;
  return SS_OK;
}

/* The rows (= columns) of block b of S: the one-ring, or outer component
 * b - 1.  Returns their number; idx has room for the largest block. */
static size_t block_rows(const ss_exact *x, size_t b, size_t *idx) {
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
 * the merged list: the block scaled by the lcm D of its denominators is an
 * integer matrix M, det(y - M) = D^len det(y/D - block), so each irreducible
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
    st = add_factor(x, b, g, 1, err);
    goto done;
  }
  fmpz_mat_t M;
  fmpz_t D, Dk, c;
  fmpz_mat_init(M, (slong)len, (slong)len);
  fmpz_init(D);
  fmpz_init(Dk);
  fmpz_init(c);
  fmpz_poly_factor_t fac;
  fmpz_poly_factor_init(fac);
  if (ss_exact_principal(x, idx, len, D, M)) {
    st = ss_error_nomem(err, "characteristic polynomial");
  } else {
    fmpz_mat_charpoly(cp, M);
    fmpz_poly_factor(fac, cp);
    for (slong i = 0; i < fac->num && !st; i++) {
      const slong d = fmpz_poly_degree(fac->p + i);
      fmpz_poly_zero(g);
      fmpz_one(Dk);
      for (slong j = 0; j <= d; j++) {
        fmpz_poly_get_coeff_fmpz(c, fac->p + i, j);
        fmpz_mul(c, c, Dk);
        fmpz_poly_set_coeff_fmpz(g, j, c);
        fmpz_mul(Dk, Dk, D);
      }
      fmpz_poly_primitive_part(g, g); /* also makes the leading coefficient > 0 */
      st = add_factor(x, b, g, (int)fac->exp[i], err);
    }
  }
  fmpz_poly_factor_clear(fac);
  fmpz_mat_clear(M);
  fmpz_clear(D);
  fmpz_clear(Dk);
  fmpz_clear(c);
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
static ss_status all_blocks(ss_exact *x, ss_error *err) {
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
    const size_t len = block_rows(x, b, idx);
    size_t hit = SIZE_MAX;
    for (size_t h = 0; b > 0 && len > 1 && h < nfirst && hit == SIZE_MAX; h++)
      if (block_rows(x, first[h], jdx) == len && same_block(x, idx, jdx, len, u, v))
        hit = first[h];
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

/* ---- roots ---- */

void ss_exact_isolate(ss_exact *x, size_t k, long prec) {
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
    acb_ptr z = _acb_vec_init(d);
    arb_fmpz_poly_complex_roots(z, F->f, 0, prec); /* F->f is irreducible */
    for (slong i = 0; i < d; i++) {
      acb_set(&R[i].z, z + i);
      R[i].real = acb_is_real(z + i);
    }
    _acb_vec_clear(z, d);
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
}

/* The root count, reflections, exact moduli, and first isolation.
 * SS_ENOMEM. */
static ss_status roots_init(ss_exact *x, ss_error *err) {
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

/* ---- classes of proven-equal moduli and the order ---- */

static size_t uf_find(size_t *par, size_t i) {
  while (par[i] != i)
    i = par[i] = par[par[i]];
  return i;
}

static void uf_union(size_t *par, size_t a, size_t b) {
  a = uf_find(par, a);
  b = uf_find(par, b);
  if (a < b)
    par[b] = a;
  else if (b < a)
    par[a] = b;
}

/* The one root of factor k whose ball overlaps w, or SIZE_MAX if not exactly
 * one does.  The balls of a factor's roots are disjoint and each holds one
 * root, so if w holds a root of that factor and overlaps one ball only, that
 * is its ball. */
static size_t overlapping_root(const ss_exact *x, size_t k, const acb_t w) {
  const ss_exact_factor *F = x->fac + k;
  const size_t d = (size_t)fmpz_poly_degree(F->f);
  size_t hit = SIZE_MAX, count = 0;
  for (size_t i = 0; i < d; i++)
    if (acb_overlaps(w, &x->rt[F->root0 + i].z)) hit = F->root0 + i, count++;
  return count == 1 ? hit : SIZE_MAX;
}

/* Group roots whose moduli are proven equal: equal exact |z|^2, complex
 * conjugates (the conjugate of a root is a root of the same factor), and z,
 * -z (-z is a root of the reflected factor).  cmod[c] receives the common
 * modulus of class c (the intersection of its members' enclosures) for each
 * class representative c.  SS_EINTERNAL if two members' enclosures are
 * disjoint (impossible unless a proof step is wrong). */
static ss_status make_classes(ss_exact *x, size_t *par, arb_ptr cmod, ss_error *err) {
  const size_t nrt = x->nrt;
  for (size_t i = 0; i < nrt; i++)
    par[i] = i;
  for (size_t i = 0; i < nrt; i++) {
    const ss_exact_rt *R = x->rt + i;
    const ss_exact_factor *F = x->fac + R->factor;
    if (F->exact_nsq)
      for (size_t j = i + 1; j < nrt; j++)
        if (x->fac[x->rt[j].factor].exact_nsq && fmpq_equal(&R->nsq, &x->rt[j].nsq))
          uf_union(par, i, j);
    acb_t w;
    acb_init(w);
    if (!R->real) {
      acb_conj(w, &R->z);
      size_t j = overlapping_root(x, R->factor, w);
      if (j != SIZE_MAX) uf_union(par, i, j);
    }
    if (F->refl >= 0) {
      acb_neg(w, &R->z);
      size_t j = overlapping_root(x, (size_t)F->refl, w);
      if (j != SIZE_MAX) uf_union(par, i, j);
    }
    acb_clear(w);
  }
  ss_status st = SS_OK;
  for (size_t i = 0; i < nrt; i++)
    x->rt[i].cls = uf_find(par, i);
  for (size_t i = 0; i < nrt; i++)
    if (x->rt[i].cls == i) arb_set(cmod + i, &x->rt[i].mod);
  for (size_t i = 0; i < nrt && !st; i++) {
    const size_t c = x->rt[i].cls;
    if (c != i && !arb_intersection(cmod + c, cmod + c, &x->rt[i].mod, x->o.maxprec + 64))
      st = ss_error_set(err, SS_EINTERNAL,
                        "roots proven of equal modulus have disjoint "
                        "modulus enclosures");
  }
  return st;
}

/* The order of ss_exact_roots: classes by decreasing midpoint of their
 * modulus; within a class real first, then larger real part, then larger
 * imaginary part.  Used only where the comparisons are proven (see
 * assess). */
static int root_before(const ss_exact *x, arb_srcptr cmod, size_t i, size_t j) {
  const size_t ci = x->rt[i].cls, cj = x->rt[j].cls;
  if (ci != cj) {
    int c = arf_cmp(arb_midref(cmod + ci), arb_midref(cmod + cj));
    if (c) return c > 0;
    return ci < cj;
  }
  const ss_exact_rt *a = x->rt + i, *b = x->rt + j;
  if (a->real != b->real) return a->real;
  int c = arf_cmp(arb_midref(acb_realref(&a->z)), arb_midref(acb_realref(&b->z)));
  if (c) return c > 0;
  c = arf_cmp(arb_midref(acb_imagref(&a->z)), arb_midref(acb_imagref(&b->z)));
  if (c) return c > 0;
  return i < j;
}

/* Stable merge sort of v[0..len) by root_before (tmp: len entries). */
static void sort_roots(const ss_exact *x, arb_srcptr cmod, size_t *v, size_t *tmp,
                       size_t len) {
  if (len < 2) return;
  const size_t h = len / 2;
  sort_roots(x, cmod, v, tmp, h);
  sort_roots(x, cmod, v + h, tmp, len - h);
  size_t i = 0, j = h, k = 0;
  while (i < h && j < len)
    tmp[k++] = root_before(x, cmod, v[j], v[i]) ? v[j++] : v[i++];
  while (i < h)
    tmp[k++] = v[i++];
  while (j < len)
    tmp[k++] = v[j++];
  memcpy(v, tmp, len * sizeof *v);
}

/* ---- the condition ---- */

typedef enum { REL_GT, REL_LT, REL_UNKNOWN } rel;

/* |class a| against |class b| (distinct classes, so never proven equal). */
static rel compare_classes(const ss_exact *x, arb_srcptr cmod, size_t a, size_t b) {
  if (x->fac[x->rt[a].factor].exact_nsq && x->fac[x->rt[b].factor].exact_nsq) {
    int c = fmpq_cmp(&x->rt[a].nsq, &x->rt[b].nsq);
    return c > 0 ? REL_GT : c < 0 ? REL_LT : REL_UNKNOWN;
  }
  if (arb_gt(cmod + a, cmod + b)) return REL_GT;
  if (arb_lt(cmod + a, cmod + b)) return REL_LT;
  return REL_UNKNOWN;
}

/* |class a| against 1. */
static rel compare_one(const ss_exact *x, arb_srcptr cmod, size_t a) {
  if (x->fac[x->rt[a].factor].exact_nsq) {
    int c = fmpq_cmp_ui(&x->rt[a].nsq, 1);
    return c > 0 ? REL_GT : c < 0 ? REL_LT : REL_UNKNOWN;
  }
  arb_t one;
  arb_init(one);
  arb_one(one);
  rel r = arb_gt(cmod + a, one) ? REL_GT : arb_lt(cmod + a, one) ? REL_LT : REL_UNKNOWN;
  arb_clear(one);
  return r;
}

/* A root as text, "0.5" or "0.3+0.2i", for reasons. */
static const char *root_text(const ss_exact *x, size_t r, char buf[64]) {
  const acb_struct *z = &x->rt[r].z;
  double re = arf_get_d(arb_midref(acb_realref(z)), ARF_RND_NEAR);
  double im = arf_get_d(arb_midref(acb_imagref(z)), ARF_RND_NEAR);
  if (x->rt[r].real)
    snprintf(buf, 64, "%.10g", re);
  else
    snprintf(buf, 64, "%.10g%+.10gi", re, im);
  return buf;
}

/* Mark the (inexact) factors of class c's members for refinement; returns the
 * largest precision among them. */
static long flag_class(const ss_exact *x, size_t c, unsigned char *refine) {
  long p = 0;
  for (size_t i = 0; i < x->nrt; i++) {
    if (x->rt[i].cls != c) continue;
    const size_t k = x->rt[i].factor;
    if (x->fac[k].exact_nsq) continue;
    refine[k] = 1;
    if (x->fac[k].prec > p) p = x->fac[k].prec;
  }
  return p;
}

static void set_verdict(ss_exact *x, ss_verdict_kind v, int certified, const char *fmt,
                        ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static void set_verdict(ss_exact *x, ss_verdict_kind v, int certified, const char *fmt,
                        ...) {
  va_list ap;
  va_start(ap, fmt);
  x->cond.verdict = v;
  vsnprintf(x->cond.reason, sizeof x->cond.reason, fmt, ap);
  va_end(ap);
  x->certified = certified;
}

/* Non-defectiveness of the roots of factor k (multiplicity e > 1 in S), shown
 * for lambda_pos.  The generalised eigenvectors of these roots live on the
 * blocks lying on paths between the blocks whose polynomial f divides: the
 * blocks reachable from them form an invariant subspace holding all of them,
 * and dividing out the invariant part not leading back to them loses none
 * (neither carries an eigenvalue of f), so the Jordan structure of f's roots
 * in S is that of the principal submatrix T on those blocks.  Every root of
 * f has as many eigenvectors as copies iff rank f(T) = |T| - e deg f,
 * computed exactly as rank of D^deg f f(T) (integer, D the lcm of T's
 * denominators).  *result: 0 non-defective, 1 defective (reason set), 2 not
 * decided (reason set).  SS_ENOMEM, SS_EINTERNAL. */
static ss_status defect_check(ss_exact *x, size_t k, int e, int pos, int *result,
                              ss_error *err) {
  const size_t nb = x->nblk, n1 = x->n1;
  unsigned char *inF = calloc(nb + 1, 1), *reach = calloc(nb + 1, 1),
                *back = calloc(nb + 1, 1);
  size_t *mark = malloc((nb + 1) * sizeof *mark),
         *rstart = calloc(nb + 2, sizeof *rstart);
  size_t *reads = malloc((x->A.ptr[x->n] + 1) * sizeof *reads);
  size_t *idx = malloc((x->n + 1) * sizeof *idx);
  ss_status st = SS_OK;
  char buf[64];
  if (!inF || !reach || !back || !mark || !rstart || !reads || !idx) {
    st = ss_error_nomem(err, "defectiveness");
    goto done;
  }
  for (size_t b = 0; b < nb; b++) {
    mark[b] = SIZE_MAX;
    for (size_t j = x->bstart[b]; j < x->bstart[b + 1]; j++)
      inF[b] |= x->bfac[j] == k;
  }
  /* reads[rstart[y]..rstart[y+1]): the blocks block y reads, all < y */
  size_t nr = 0;
  for (size_t y = 1; y < nb; y++) {
    rstart[y] = nr;
    const size_t s = x->K.start[y - 1], len = x->K.start[y] - s;
    for (size_t r = 0; r < len; r++) {
      const size_t i = n1 + x->K.comp[s + r];
      for (size_t q = x->A.ptr[i]; q < x->A.ptr[i + 1]; q++) {
        const size_t j = x->A.col[q], bj = j < n1 ? 0 : 1 + x->K.cid[j - n1];
        if (bj != y && mark[bj] != y) mark[bj] = y, reads[nr++] = bj;
      }
    }
  }
  rstart[nb] = nr;
  for (size_t y = 0; y < nb; y++) {
    reach[y] = inF[y];
    for (size_t q = rstart[y]; y > 0 && q < rstart[y + 1]; q++)
      reach[y] |= reach[reads[q]];
  }
  for (size_t y = nb; y-- > 0;) {
    back[y] |= inF[y];
    for (size_t q = rstart[y]; back[y] && y > 0 && q < rstart[y + 1]; q++)
      back[reads[q]] = 1;
  }
  size_t len = 0;
  for (size_t b = 0; b < nb; b++)
    if (reach[b] && back[b]) len += block_rows(x, b, idx + len);
  const slong d = fmpz_poly_degree(x->fac[k].f);
  if (len > x->o.max_block) {
    set_verdict(x, SS_UNDECIDED, 0,
                "not certified: non-defectiveness of lambda%d = %s needs an exact rank "
                "on %zu points (limit %zu)",
                pos, root_text(x, x->fac[k].root0, buf), len, x->o.max_block);
    *result = 2;
    goto done;
  }
  fmpz_mat_t M, R, T;
  fmpz_t D, Dk, c;
  fmpz_mat_init(M, (slong)len, (slong)len);
  fmpz_mat_init(R, (slong)len, (slong)len);
  fmpz_mat_init(T, (slong)len, (slong)len);
  fmpz_init(D);
  fmpz_init(Dk);
  fmpz_init(c);
  if (ss_exact_principal(x, idx, len, D, M)) {
    st = ss_error_nomem(err, "defectiveness");
  } else {
    /* Horner: R = sum_j c_j D^(d-j) M^j = D^d f(T) */
    fmpz_mat_zero(R);
    fmpz_one(Dk);
    for (slong j = d; j >= 0; j--) {
      if (j < d) {
        fmpz_mat_mul(T, R, M);
        fmpz_mat_swap(T, R);
      }
      fmpz_mul(c, x->fac[k].f->coeffs + j, Dk);
      for (size_t i = 0; i < len; i++)
        fmpz_add(fmpz_mat_entry(R, (slong)i, (slong)i),
                 fmpz_mat_entry(R, (slong)i, (slong)i), c);
      fmpz_mul(Dk, Dk, D);
    }
    const slong rank = fmpz_mat_rank(R), expected = (slong)len - (slong)e * d;
    if (rank < expected) {
      st = ss_error_set(err, SS_EINTERNAL,
                        "rank of f(S) below its bound: the factorisation is wrong");
    } else if (rank > expected) {
      set_verdict(x, SS_FAIL, 1,
                  "defective: lambda%d = %s (multiplicity %d) has %ld independent "
                  "eigenvectors (exact rank of f(S))",
                  pos, root_text(x, x->fac[k].root0, buf), e,
                  (long)(((slong)len - rank) / d));
      *result = 1;
    } else {
      *result = 0;
    }
  }
  fmpz_mat_clear(M);
  fmpz_mat_clear(R);
  fmpz_mat_clear(T);
  fmpz_clear(D);
  fmpz_clear(Dk);
  fmpz_clear(c);
done:
  free(inF);
  free(reach);
  free(back);
  free(mark);
  free(rstart);
  free(reads);
  free(idx);
  return st;
}

/* The condition from the current enclosures (x->order sorted, classes made).
 * Sets x->cond and x->certified; factors whose refinement could decide an
 * open comparison get refine[k] = 1.  SS_ENOMEM, SS_EINTERNAL. */
static ss_status assess(ss_exact *x, arb_srcptr cmod, unsigned char *refine,
                        ss_error *err) {
  const size_t nrt = x->nrt;
  const size_t *ord = x->order;
  const int m = x->m;
  char b1[64], b2[64];
  long p;
  x->nlead = 0;
  /* lambda0: x - 1 divides (rows sum to 1), simple, every other root < 1 */
  size_t one = SIZE_MAX;
  for (size_t i = 0; i < nrt && one == SIZE_MAX; i++) {
    const fmpz_poly_struct *f = x->fac[x->rt[i].factor].f;
    if (fmpz_poly_degree(f) == 1 && fmpz_is_one(f->coeffs + 1) &&
        fmpz_equal_si(f->coeffs, -1))
      one = i;
  }
  if (one == SIZE_MAX)
    return ss_error_set(err, SS_EINTERNAL,
                        "1 is not an eigenvalue of a rational matrix "
                        "whose rows sum to 1");
  const int e1 = x->fac[x->rt[one].factor].mult;
  if (e1 > 1) {
    set_verdict(x, SS_FAIL, 1, "lambda0 = 1 is not simple (multiplicity %d, exact)", e1);
    return SS_OK;
  }
  const size_t c1 = x->rt[one].cls;
  for (size_t k = 0; k < nrt; k++)
    if (ord[k] != one && x->rt[ord[k]].cls == c1) {
      set_verdict(x, SS_FAIL, 1,
                  "the eigenvalue %s has modulus 1 like lambda0 = 1 (proven exactly)",
                  root_text(x, ord[k], b1));
      return SS_OK;
    }
  int open = 0;
  for (size_t k = 0; k < nrt; k++) {
    const size_t c = x->rt[ord[k]].cls;
    if (c != ord[k] || c == c1) continue; /* one look per class */
    rel r = compare_one(x, cmod, c);
    if (r == REL_GT) {
      set_verdict(x, SS_FAIL, 1, "the eigenvalue %s has modulus > 1 (proven)",
                  root_text(x, ord[k], b1));
      return SS_OK;
    }
    if (r == REL_UNKNOWN && !open++) {
      p = flag_class(x, c, refine);
      set_verdict(x, SS_UNDECIDED, 0,
                  "not certified: the modulus of the eigenvalue %s and 1 not separated "
                  "at %ld bits",
                  root_text(x, ord[k], b1), p);
    } else if (r == REL_UNKNOWN) {
      flag_class(x, c, refine);
    }
  }
  if (open) return SS_OK;
  /* ord[0] is 1 now (every other class is proven below 1); positions */
  size_t total = 0;
  for (size_t k = 0; k < nrt; k++)
    total += (size_t)x->fac[x->rt[ord[k]].factor].mult;
  if (total < (size_t)m + 1) {
    set_verdict(x, SS_FAIL, 1, "S has %zu eigenvalues, fewer than lambda0..lambda%d",
                total, m);
    return SS_OK;
  }
  size_t km = 0;     /* the root holding lambda_m is ord[km] */
  int posk[8] = {0}; /* first position of ord[k], k <= km (km <= m) */
  int pos = 1;
  for (size_t k = 1; k < nrt; k++) {
    posk[k] = pos;
    pos += x->fac[x->rt[ord[k]].factor].mult;
    if (pos > m) {
      km = k;
      break;
    }
  }
  /* lambda1..lambda_m in order: each class among them proven above every
   * later class (its place is then proven), then its roots real, positive */
  for (size_t k = 1; k <= km; k++) {
    const size_t c = x->rt[ord[k]].cls;
    if (k == 1 || c != x->rt[ord[k - 1]].cls) {
      int at = posk[k] + x->fac[x->rt[ord[k]].factor].mult;
      for (size_t j = k + 1; j < nrt; j++) {
        const size_t cj = x->rt[ord[j]].cls;
        if (cj != c && compare_classes(x, cmod, c, cj) != REL_GT) {
          long pa = flag_class(x, c, refine), pb = flag_class(x, cj, refine);
          if (!open++)
            set_verdict(x, SS_UNDECIDED, 0,
                        "not certified: moduli of lambda%d and lambda%d not separated at "
                        "%ld bits",
                        posk[k], at, pa > pb ? pa : pb);
        }
        at += x->fac[x->rt[ord[j]].factor].mult;
      }
      if (open) return SS_OK;
    }
    const ss_exact_rt *R = x->rt + ord[k];
    if (!R->real) {
      set_verdict(x, SS_FAIL, 1, "lambda%d = %s is not real (proven)", posk[k],
                  root_text(x, ord[k], b1));
      return SS_OK;
    }
    const arb_struct *re = acb_realref(&R->z);
    if (arb_is_positive(re)) continue;
    if (arb_is_nonpositive(re)) {
      set_verdict(x, SS_FAIL, 1, "lambda%d = %s is not positive (proven)", posk[k],
                  root_text(x, ord[k], b1));
      return SS_OK;
    }
    refine[R->factor] = 1;
    set_verdict(x, SS_UNDECIDED, 0,
                "not certified: the sign of lambda%d not decided at %ld bits", posk[k],
                x->fac[R->factor].prec);
    return SS_OK;
  }
  /* lambda_m > |lambda_m+1|: proven above unless its class goes on */
  const size_t rm = ord[km], cm = x->rt[rm].cls;
  const int em = x->fac[x->rt[rm].factor].mult;
  if (posk[km] + em - 1 > m) {
    set_verdict(x, SS_FAIL, 1,
                "exact tie: lambda%d = lambda%d = %s (a root of multiplicity %d)", m,
                m + 1, root_text(x, rm, b1), em);
    return SS_OK;
  }
  if (km + 1 < nrt && x->rt[ord[km + 1]].cls == cm) {
    set_verdict(x, SS_FAIL, 1,
                "exact tie: |lambda%d| = lambda%d = %s (lambda%d = %s, proven)", m + 1, m,
                root_text(x, rm, b1), m + 1, root_text(x, ord[km + 1], b2));
    return SS_OK;
  }
  /* non-defective */
  for (size_t k = 1; k <= km; k++) {
    const size_t f = x->rt[ord[k]].factor;
    const int e = x->fac[f].mult;
    int seen = 0, result = 0;
    for (size_t j = 1; j < k; j++)
      seen |= x->rt[ord[j]].factor == f;
    if (e < 2 || seen) continue;
    ss_status st = defect_check(x, f, e, posk[k], &result, err);
    if (st) return st;
    if (result) return SS_OK;
  }
  for (size_t k = 1; k <= km; k++)
    x->lead[x->nlead++] = ord[k];
  set_verdict(x, SS_PASS, 1, "%s", "");
  return SS_OK;
}

/* Classes, order and condition, refining the factors an open comparison
 * depends on (precision doubled, up to maxprec) until the condition is
 * decided or nothing can be refined.  SS_ENOMEM, SS_EINTERNAL. */
static ss_status decide(ss_exact *x, ss_error *err) {
  const size_t nrt = x->nrt;
  size_t *par = malloc((nrt + 1) * sizeof *par), *tmp = malloc((nrt + 1) * sizeof *tmp);
  unsigned char *refine = malloc(x->nfac + 1);
  arb_ptr cmod = _arb_vec_init((slong)nrt + 1);
  ss_status st = SS_OK;
  if (!par || !tmp || !refine) {
    st = ss_error_nomem(err, "root order");
    goto done;
  }
  for (;;) {
    if ((st = make_classes(x, par, cmod, err))) goto done;
    for (size_t i = 0; i < nrt; i++)
      x->order[i] = i;
    sort_roots(x, cmod, x->order, tmp, nrt);
    memset(refine, 0, x->nfac + 1);
    if ((st = assess(x, cmod, refine, err))) goto done;
    if (x->cond.verdict != SS_UNDECIDED) break;
    int more = 0;
    for (size_t k = 0; k < x->nfac; k++)
      if (refine[k] && x->fac[k].prec < x->o.maxprec) {
        long p = 2 * x->fac[k].prec;
        ss_exact_isolate(x, k, p < x->o.maxprec ? p : x->o.maxprec);
        more = 1;
      }
    if (!more) break;
  }
  /* the public roots */
  for (size_t k = 0; k < nrt; k++) {
    const ss_exact_rt *R = x->rt + x->order[k];
    ss_exact_root *P = x->roots + k;
    const arb_struct *re = acb_realref(&R->z), *im = acb_imagref(&R->z);
    P->re = arf_get_d(arb_midref(re), ARF_RND_NEAR);
    P->im = arf_get_d(arb_midref(im), ARF_RND_NEAR);
    arb_t d;
    mag_t a, b;
    arb_init(d);
    mag_init(a);
    mag_init(b);
    arb_set_d(d, P->re); /* |true - (re + i im)| <= hypot(|z.re - re|, |z.im - im|) */
    arb_sub(d, re, d, 2 * x->o.maxprec);
    arb_get_mag(a, d);
    arb_set_d(d, P->im);
    arb_sub(d, im, d, 2 * x->o.maxprec);
    arb_get_mag(b, d);
    mag_hypot(a, a, b);
    P->rad = mag_get_d(a);
    arb_clear(d);
    mag_clear(a);
    mag_clear(b);
    P->mult = x->fac[R->factor].mult;
    P->degree = (int)fmpz_poly_degree(x->fac[R->factor].f);
    P->factor = (int)R->factor;
    P->real = R->real;
    P->tied_next = k + 1 < nrt && x->rt[x->order[k + 1]].cls == R->cls;
  }
done:
  free(par);
  free(tmp);
  free(refine);
  _arb_vec_clear(cmod, (slong)nrt + 1);
  return st;
}

/* ---- the object ---- */

void ss_exact_free(ss_exact *x) {
  if (!x) return;
  for (size_t i = 0; i < x->nrt; i++) {
    acb_clear(&x->rt[i].z);
    arb_clear(&x->rt[i].mod);
    fmpq_clear(&x->rt[i].nsq);
  }
  for (size_t k = 0; k < x->nfac; k++)
    fmpz_poly_clear(x->fac[k].f);
  ss_csr_free(&x->A);
  ss_scc_free(&x->K);
  free(x->q);
  free(x->bstart);
  free(x->bfac);
  free(x->bmult);
  free(x->fac);
  free(x->rt);
  free(x->order);
  free(x->roots);
  free(x->lo);
  free(x->hi);
  free(x->bnum);
  free(x->bden);
  free(x);
}

ss_status ss_exact_new(const double *S, size_t n, size_t n1, const ss_exact_opts *o,
                       ss_exact **out, ss_error *err) {
  *out = NULL;
  ss_status st = ss_scc_check_form(S, n, n1, err);
  if (st) return st;
  if (!o) return ss_error_set(err, SS_EINPUT, "no options");
  if (o->maxden < 1 || o->maxden > MAXDEN_LIMIT || o->prec < 32 || o->maxprec < o->prec ||
      o->maxprec > (1L << 20) || (o->dim != 2 && o->dim != 3) || o->max_block < 1)
    return ss_error_set(
        err, SS_EINPUT,
        "exact options out of range (maxden %ld in [1, 2^31], prec %ld >= "
        "32, maxprec %ld in [prec, 2^20], dim %d in {2, 3}, max_block %zu "
        ">= 1)",
        o->maxden, o->prec, o->maxprec, o->dim, o->max_block);
  ss_exact *x = calloc(1, sizeof *x);
  if (!x) return ss_error_nomem(err, "exact spectrum");
  x->n = n;
  x->n1 = n1;
  x->o = *o;
  x->m = o->dim;
  x->bstatus = SS_EINPUT;
  snprintf(x->bmsg, sizeof x->bmsg, "%s", "the subdominant basis was not requested");
  if ((st = reconstruct(x, S, err))) goto done;
  if (ss_scc_make(&x->A, n, n1, &x->K)) {
    st = ss_error_nomem(err, "outer blocks");
    goto done;
  }
  x->nblk = 1 + (size_t)x->K.n;
  if (n1 > o->max_block || x->K.largest > o->max_block) {
    int inner = n1 > o->max_block;
    set_verdict(x, SS_UNDECIDED, 0,
                "not certified: %s block of %zu points exceeds the exact path's limit of "
                "%zu",
                inner ? "the one-ring" : "an outer", inner ? n1 : x->K.largest,
                o->max_block);
    goto done;
  }
  x->bstart = calloc(x->nblk + 1, sizeof *x->bstart);
  x->bfac = malloc((n + 1) * sizeof *x->bfac);
  x->bmult = malloc((n + 1) * sizeof *x->bmult);
  if (!x->bstart || !x->bfac || !x->bmult) {
    st = ss_error_nomem(err, "blocks");
    goto done;
  }
  if ((st = all_blocks(x, err))) goto done;
  if ((st = roots_init(x, err))) goto done;
  if ((st = decide(x, err))) goto done;
  if (o->basis && x->cond.verdict == SS_PASS && x->certified)
    st = ss_exact_basis_make(x, err);
done:
  if (st) {
    ss_exact_free(x);
    return st;
  }
  *out = x;
  return SS_OK;
}

void ss_exact_condition(const ss_exact *x, ss_verdict *v, int *certified) {
  *v = x->cond;
  *certified = x->certified;
}

const ss_exact_root *ss_exact_roots(const ss_exact *x, size_t *nroots) {
  *nroots = x->nrt;
  return x->roots;
}

char *ss_exact_minpoly(const ss_exact *x, size_t r, char *buf, size_t len) {
  if (!len) return buf;
  buf[0] = '\0';
  if (r >= x->nrt) return buf;
  const fmpz_poly_struct *f = x->fac[x->roots[r].factor].f;
  size_t used = 0;
  int first = 1, cut = 0;
  fmpz_t c;
  fmpz_init(c);
  for (slong j = fmpz_poly_degree(f); j >= 0 && !cut; j--) {
    fmpz_poly_get_coeff_fmpz(c, f, j);
    if (fmpz_is_zero(c)) continue;
    const char *sign = fmpz_sgn(c) < 0 ? (first ? "-" : " - ") : (first ? "" : " + ");
    fmpz_abs(c, c);
    char *digits = fmpz_get_str(NULL, 10, c);
    const int unit = fmpz_is_one(c) && j > 0;
    char power[32] = "";
    if (j == 1)
      snprintf(power, sizeof power, "%sx", unit ? "" : "*");
    else if (j > 1)
      snprintf(power, sizeof power, "%sx^%ld", unit ? "" : "*", (long)j);
    int w = snprintf(buf + used, len - used, "%s%s%s", sign, unit ? "" : digits, power);
    flint_free(digits);
    if (w < 0 || (size_t)w >= len - used)
      cut = 1;
    else
      used += (size_t)w;
    first = 0;
  }
  fmpz_clear(c);
  if (cut && len >= 4) memcpy(buf + len - 4, "...", 4);
  return buf;
}
