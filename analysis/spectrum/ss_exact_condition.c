/* ss_exact_condition.c — the certified order of the roots and the certified
 * eigenvalue condition: classes of proven-equal moduli, the order of
 * ss_exact_roots, the condition's checks (lambda0 = 1 simple and dominant,
 * lambda1..m real, positive, separated, non-defective), refining the factors
 * an open comparison depends on (ss_exact_impl.h). */
#include <stdarg.h>
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

void ss_exact_set_verdict(ss_exact *x, ss_verdict_kind v, int certified, const char *fmt,
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
    if (reach[b] && back[b]) len += ss_exact_block_rows(x, b, idx + len);
  const slong d = fmpz_poly_degree(x->fac[k].f);
  if (len > x->o.max_block) {
    ss_exact_set_verdict(
        x, SS_UNDECIDED, 0,
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
      ss_exact_set_verdict(
          x, SS_FAIL, 1,
          "defective: lambda%d = %s (multiplicity %d) has %ld independent "
          "eigenvectors (exact rank of f(S))",
          pos, root_text(x, x->fac[k].root0, buf), e, (long)(((slong)len - rank) / d));
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

/* lambda0: x - 1 divides (rows sum to 1), simple, every other root < 1.
 * *decided = 1 if a verdict is set (fail, or undecided with the classes to
 * refine flagged).  SS_EINTERNAL if 1 is no root. */
static ss_status assess_lambda0(ss_exact *x, arb_srcptr cmod, unsigned char *refine,
                                int *decided, ss_error *err) {
  const size_t nrt = x->nrt;
  const size_t *ord = x->order;
  char b1[64];
  long p;
  *decided = 1;
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
    ss_exact_set_verdict(x, SS_FAIL, 1,
                         "lambda0 = 1 is not simple (multiplicity %d, exact)", e1);
    return SS_OK;
  }
  const size_t c1 = x->rt[one].cls;
  for (size_t k = 0; k < nrt; k++)
    if (ord[k] != one && x->rt[ord[k]].cls == c1) {
      ss_exact_set_verdict(
          x, SS_FAIL, 1,
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
      ss_exact_set_verdict(x, SS_FAIL, 1, "the eigenvalue %s has modulus > 1 (proven)",
                           root_text(x, ord[k], b1));
      return SS_OK;
    }
    if (r == REL_UNKNOWN && !open++) {
      p = flag_class(x, c, refine);
      ss_exact_set_verdict(
          x, SS_UNDECIDED, 0,
          "not certified: the modulus of the eigenvalue %s and 1 not separated "
          "at %ld bits",
          root_text(x, ord[k], b1), p);
    } else if (r == REL_UNKNOWN) {
      flag_class(x, c, refine);
    }
  }
  *decided = open != 0;
  return SS_OK;
}

/* The positions of the roots in order (ord[0] is 1 now: every other class is
 * proven below 1): ord[*km] holds lambda_m, posk[k] is the first position of
 * ord[k], k <= km.  Returns 1 with the verdict set if S has fewer than m + 1
 * eigenvalues. */
static int assess_positions(ss_exact *x, size_t *km, int posk[8]) {
  const size_t nrt = x->nrt;
  const size_t *ord = x->order;
  const int m = x->m;
  size_t total = 0;
  for (size_t k = 0; k < nrt; k++)
    total += (size_t)x->fac[x->rt[ord[k]].factor].mult;
  if (total < (size_t)m + 1) {
    ss_exact_set_verdict(x, SS_FAIL, 1,
                         "S has %zu eigenvalues, fewer than lambda0..lambda%d", total, m);
    return 1;
  }
  int pos = 1;
  for (size_t k = 1; k < nrt; k++) {
    posk[k] = pos;
    pos += x->fac[x->rt[ord[k]].factor].mult;
    if (pos > m) {
      *km = k;
      break;
    }
  }
  return 0;
}

/* lambda1..lambda_m in order: each class among them proven above every later
 * class (its place is then proven), then its roots real, positive.  Returns 1
 * with the verdict set (fail, or undecided with the factors to refine
 * flagged), 0 if all are proven. */
static int assess_leading(ss_exact *x, arb_srcptr cmod, unsigned char *refine, size_t km,
                          const int posk[8]) {
  const size_t nrt = x->nrt;
  const size_t *ord = x->order;
  char b1[64];
  int open = 0;
  for (size_t k = 1; k <= km; k++) {
    const size_t c = x->rt[ord[k]].cls;
    if (k == 1 || c != x->rt[ord[k - 1]].cls) {
      int at = posk[k] + x->fac[x->rt[ord[k]].factor].mult;
      for (size_t j = k + 1; j < nrt; j++) {
        const size_t cj = x->rt[ord[j]].cls;
        if (cj != c && compare_classes(x, cmod, c, cj) != REL_GT) {
          long pa = flag_class(x, c, refine), pb = flag_class(x, cj, refine);
          if (!open++)
            ss_exact_set_verdict(
                x, SS_UNDECIDED, 0,
                "not certified: moduli of lambda%d and lambda%d not separated at "
                "%ld bits",
                posk[k], at, pa > pb ? pa : pb);
        }
        at += x->fac[x->rt[ord[j]].factor].mult;
      }
      if (open) return 1;
    }
    const ss_exact_rt *R = x->rt + ord[k];
    if (!R->real) {
      ss_exact_set_verdict(x, SS_FAIL, 1, "lambda%d = %s is not real (proven)", posk[k],
                           root_text(x, ord[k], b1));
      return 1;
    }
    const arb_struct *re = acb_realref(&R->z);
    if (arb_is_positive(re)) continue;
    if (arb_is_nonpositive(re)) {
      ss_exact_set_verdict(x, SS_FAIL, 1, "lambda%d = %s is not positive (proven)",
                           posk[k], root_text(x, ord[k], b1));
      return 1;
    }
    refine[R->factor] = 1;
    ss_exact_set_verdict(x, SS_UNDECIDED, 0,
                         "not certified: the sign of lambda%d not decided at %ld bits",
                         posk[k], x->fac[R->factor].prec);
    return 1;
  }
  return 0;
}

/* lambda_m > |lambda_m+1|: proven above unless its class goes on.  Returns 1
 * with the verdict set on an exact tie. */
static int assess_tie(ss_exact *x, size_t km, const int posk[8]) {
  const size_t nrt = x->nrt;
  const size_t *ord = x->order;
  const int m = x->m;
  char b1[64], b2[64];
  const size_t rm = ord[km], cm = x->rt[rm].cls;
  const int em = x->fac[x->rt[rm].factor].mult;
  if (posk[km] + em - 1 > m) {
    ss_exact_set_verdict(
        x, SS_FAIL, 1, "exact tie: lambda%d = lambda%d = %s (a root of multiplicity %d)",
        m, m + 1, root_text(x, rm, b1), em);
    return 1;
  }
  if (km + 1 < nrt && x->rt[ord[km + 1]].cls == cm) {
    ss_exact_set_verdict(
        x, SS_FAIL, 1, "exact tie: |lambda%d| = lambda%d = %s (lambda%d = %s, proven)",
        m + 1, m, root_text(x, rm, b1), m + 1, root_text(x, ord[km + 1], b2));
    return 1;
  }
  return 0;
}

/* The condition from the current enclosures (x->order sorted, classes made).
 * Sets x->cond and x->certified; factors whose refinement could decide an
 * open comparison get refine[k] = 1.  SS_ENOMEM, SS_EINTERNAL. */
static ss_status assess(ss_exact *x, arb_srcptr cmod, unsigned char *refine,
                        ss_error *err) {
  const size_t *ord = x->order;
  x->nlead = 0;
  int decided = 0;
  ss_status st = assess_lambda0(x, cmod, refine, &decided, err);
  if (st || decided) return st;
  size_t km = 0;     /* the root holding lambda_m is ord[km] */
  int posk[8] = {0}; /* first position of ord[k], k <= km (km <= m) */
  if (assess_positions(x, &km, posk)) return SS_OK;
  if (assess_leading(x, cmod, refine, km, posk)) return SS_OK;
  if (assess_tie(x, km, posk)) return SS_OK;
  /* non-defective */
  for (size_t k = 1; k <= km; k++) {
    const size_t f = x->rt[ord[k]].factor;
    const int e = x->fac[f].mult;
    int seen = 0, result = 0;
    for (size_t j = 1; j < k; j++)
      seen |= x->rt[ord[j]].factor == f;
    if (e < 2 || seen) continue;
    st = defect_check(x, f, e, posk[k], &result, err);
    if (st) return st;
    if (result) return SS_OK;
  }
  for (size_t k = 1; k <= km; k++)
    x->lead[x->nlead++] = ord[k];
  ss_exact_set_verdict(x, SS_PASS, 1, "%s", "");
  return SS_OK;
}

/* Classes, order and condition, refining the factors an open comparison
 * depends on (precision doubled, up to maxprec) until the condition is
 * decided or nothing can be refined.  SS_ENOMEM, SS_EINTERNAL. */
ss_status ss_exact_decide(ss_exact *x, ss_error *err) {
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
