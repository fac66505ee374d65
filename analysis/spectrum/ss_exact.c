/* ss_exact.c — the exact spectrum's object: options, construction through
 * the stages (the rational matrix, ss_exact_rational.c; the factors and
 * roots by blocks, ss_exact_factor.c; the order and the condition,
 * ss_exact_condition.c; the subdominant basis, ss_exact_basis.c), and its
 * accessors.  Method: ss_exact.h. */
#include "ss_exact.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/nmod_poly.h>
#include <flint/ulong_extras.h>

#include "ss_clock.h"
#include "ss_exact_impl.h"

ss_exact_opts ss_exact_defaults(int dim) {
  ss_exact_opts o = {1L << 18, 128, 4096, dim, 400, 1, 0, NULL};
  return o;
}

void ss_exact_free(ss_exact *x) {
  if (!x) return;
  for (size_t i = 0; i < x->nrt; i++) {
    acb_clear(&x->rt[i].z);
    arb_clear(&x->rt[i].mod);
    fmpq_clear(&x->rt[i].nsq);
  }
  for (size_t k = 0; k < x->nfac; k++)
    fmpz_poly_clear(x->fac[k].f);
  fmpz_clear(&x->dA);
  if (x->qb) _arb_vec_clear(x->qb, (slong)x->A.ptr[x->n]); /* before A */
  ss_csr_free(&x->A);
  ss_scc_free(&x->K);
  free(x->q);
  free(x->bstart);
  free(x->bfac);
  free(x->bmult);
  free(x->brep);
  free(x->fac);
  free(x->rt);
  free(x->order);
  free(x->roots);
  free(x->lo);
  free(x->hi);
  free(x->bnum);
  free(x->bden);
  free(x->ev);
  free(x->evb);
  free(x->evf);
  free(x);
}

/* Whether a and b (integer polynomials of degree >= 1) have no common root:
 * their gcd modulo a prime dividing neither leading coefficient is 1 (a
 * common factor over Q would be one over Z, of positive degree modulo it),
 * else FLINT's exact gcd. */
static int coprime(const fmpz_poly_t a, const fmpz_poly_t b) {
  mp_limb_t p = UWORD(1) << 62;
  do
    p = n_nextprime(p, 1);
  while (!fmpz_fdiv_ui(fmpz_poly_lead(a), p) || !fmpz_fdiv_ui(fmpz_poly_lead(b), p));
  nmod_poly_t u, v, g;
  nmod_poly_init(u, p);
  nmod_poly_init(v, p);
  nmod_poly_init(g, p);
  fmpz_poly_get_nmod_poly(u, a);
  fmpz_poly_get_nmod_poly(v, b);
  nmod_poly_gcd(g, u, v);
  int yes = nmod_poly_degree(g) == 0;
  nmod_poly_clear(u);
  nmod_poly_clear(v);
  nmod_poly_clear(g);
  if (!yes) {
    fmpz_poly_t h;
    fmpz_poly_init(h);
    fmpz_poly_gcd(h, a, b);
    yes = fmpz_poly_degree(h) == 0;
    fmpz_poly_clear(h);
  }
  return yes;
}

/* ss_exact_opts.lazy: what the condition's steps assume of a factor that an
 * unproven one (squarefree, not proven irreducible) satisfies only when it
 * has multiplicity 1 in S and no root in common with any other factor
 * (distinct factors, distinct roots; its roots' multiplicity is then 1),
 * and x - 1 is a factor (assess_lambda0 looks for it).  1 when so. */
static int lazy_premises(const ss_exact *x) {
  int one = 0;
  for (size_t k = 0; k < x->nfac; k++) {
    const fmpz_poly_struct *f = x->fac[k].f;
    one |= fmpz_poly_degree(f) == 1 && fmpz_is_one(f->coeffs + 1) &&
           fmpz_equal_si(f->coeffs, -1);
  }
  if (!one || x->lazy_bad) return 0;
  for (size_t k = 0; k < x->nfac; k++) {
    if (!x->fac[k].unproven) continue;
    if (x->fac[k].mult != 1) return 0;
    for (size_t j = 0; j < x->nfac; j++)
      if (j != k && !coprime(x->fac[k].f, x->fac[j].f)) return 0;
  }
  return 1;
}

/* ss_exact_opts.lazy: whether x stands as computed.  What reads a factor's
 * irreducibility: the non-defectiveness of a root of multiplicity > 1 (none
 * is unproven: lazy_premises), the basis of lambda1..m (exact for a rational
 * root, Rump's method for an irrational one: an unproven factor's leading
 * root is proven irrational when dA times its ball holds no integer, the
 * roots of a monic integer polynomial being integers when rational) and the
 * exact moduli and reflections that prove ties (an unproven factor may hide
 * a reflection, and leave open what FLINT's factors would decide).  So: the
 * condition certified, each leading root of an unproven factor proven
 * irrational, and on a pass the basis as requested; otherwise the exact path
 * starts again with fmpz_poly_factor.  A certified failure stands: each of
 * its proofs (moduli of balls, realness and sign of isolated roots,
 * positions counted by multiplicities, exact ties by multiplicity or proven
 * equal moduli) holds for squarefree factors without common roots. */
static int lazy_accepted(const ss_exact *x) {
  if (x->lazy_bad || !x->certified) return 0;
  if (x->cond.verdict != SS_PASS) return 1;
  int ok = 1;
  arb_t y;
  arb_init(y);
  for (size_t j = 0; j < x->nlead && ok; j++) {
    const ss_exact_rt *R = x->rt + x->lead[j];
    if (!x->fac[R->factor].unproven) continue;
    arb_mul_fmpz(y, acb_realref(&R->z), &x->dA, x->fac[R->factor].prec + 64);
    ok = !arb_contains_int(y); /* irrational, as its minimal polynomial says */
  }
  arb_clear(y);
  return ok && (!x->o.basis || x->bstatus == SS_OK);
}

static ss_status exact_run(const double *S, size_t n, size_t n1, const ss_exact_opts *o,
                           ss_exact **out, ss_error *err);

ss_status ss_exact_new(const double *S, size_t n, size_t n1, const ss_exact_opts *o,
                       ss_exact **out, ss_error *err) {
  ss_status st = exact_run(S, n, n1, o, out, err);
  if (st || !o->lazy || lazy_accepted(*out)) return st;
  ss_exact_free(*out);
  ss_exact_opts full = *o;
  full.lazy = 0;
  return exact_run(S, n, n1, &full, out, err);
}

/* ss_exact_new with the options as given. */
static ss_status exact_run(const double *S, size_t n, size_t n1, const ss_exact_opts *o,
                           ss_exact **out, ss_error *err) {
  *out = NULL;
  ss_status st = ss_scc_check_form(S, n, n1, err);
  if (st) return st;
  if (!o) return ss_error_set(err, SS_EINPUT, "no options");
  if (o->maxden < 1 || o->maxden > SS_EXACT_MAXDEN_LIMIT || o->prec < 32 ||
      o->maxprec < o->prec || o->maxprec > (1L << 20) || (o->dim != 2 && o->dim != 3) ||
      o->max_block < 1)
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
  ss_exact_times *tm = o->times;
  double c1 = tm ? ss_clock_cpu() : 0.0;
  if (tm) tm->cases++;
  if ((st = ss_exact_reconstruct(x, S, err))) goto done;
  if (ss_scc_make(&x->A, n, n1, &x->K)) {
    st = ss_error_nomem(err, "outer blocks");
    goto done;
  }
  if (tm) ss_clock_lap(&tm->rational, &c1);
  x->nblk = 1 + (size_t)x->K.n;
  if (n1 > o->max_block || x->K.largest > o->max_block) {
    int inner = n1 > o->max_block;
    ss_exact_set_verdict(
        x, SS_UNDECIDED, 0,
        "not certified: %s block of %zu points exceeds the exact path's limit of "
        "%zu",
        inner ? "the one-ring" : "an outer", inner ? n1 : x->K.largest, o->max_block);
    goto done;
  }
  x->bstart = calloc(x->nblk + 1, sizeof *x->bstart);
  x->bfac = malloc((n + 1) * sizeof *x->bfac);
  x->bmult = malloc((n + 1) * sizeof *x->bmult);
  x->brep = malloc((x->nblk + 1) * sizeof *x->brep);
  if (!x->bstart || !x->bfac || !x->bmult || !x->brep) {
    st = ss_error_nomem(err, "blocks");
    goto done;
  }
  if (tm) c1 = ss_clock_cpu();
  if (ss_exact_eigen_values(x)) { /* seeds of the isolation, candidates of the
                                     factoring's linear factors */
    st = ss_error_nomem(err, "root seeds");
    goto done;
  }
  if (tm) ss_clock_lap(&tm->isolate, &c1);
  if ((st = ss_exact_all_blocks(x, err))) goto done; /* times its own stages */
  if (o->lazy && !lazy_premises(x)) {
    x->lazy_bad = 1; /* ss_exact_new starts again */
    goto done;
  }
  if (tm) c1 = ss_clock_cpu();
  if (ss_exact_eigen_seeds(x)) { /* the seeds are isolation's */
    st = ss_error_nomem(err, "root seeds");
    goto done;
  }
  if (tm) ss_clock_lap(&tm->isolate, &c1);
  if ((st = ss_exact_roots_init(x, err))) goto done; /* isolation only */
  if (tm) c1 = ss_clock_cpu();
  double iso = tm ? tm->isolate : 0.0; /* the refinements are isolation's */
  if ((st = ss_exact_decide(x, err))) goto done;
  if (tm) {
    ss_clock_lap(&tm->decide, &c1);
    tm->decide -= tm->isolate - iso;
    iso = tm->isolate;
  }
  if (o->basis && x->cond.verdict == SS_PASS && x->certified)
    st = ss_exact_basis_make(x, err);
  if (tm) {
    ss_clock_lap(&tm->basis, &c1);
    tm->basis -= tm->isolate - iso;
  }
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
