/* ss_exact.c — the exact spectrum's object: options, construction through
 * the stages (the rational matrix, ss_exact_rational.c; the factors and
 * roots by blocks, ss_exact_factor.c; the order and the condition,
 * ss_exact_condition.c; the subdominant basis, ss_exact_basis.c), and its
 * accessors.  Method: ss_exact.h. */
#include "ss_exact.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"
#include "ss_exact_impl.h"

ss_exact_opts ss_exact_defaults(int dim) {
  ss_exact_opts o = {1L << 18, 128, 4096, dim, 400, 1, NULL};
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

ss_status ss_exact_new(const double *S, size_t n, size_t n1, const ss_exact_opts *o,
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
  if ((st = ss_exact_all_blocks(x, err))) goto done; /* times its own stages */
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
