/* ss_schur.c — a volume vertex's eigenvalue condition from ball enclosures
 * of its local matrix's eigenvalues and Schur's lemma under the link's
 * automorphisms (method: ss_schur.h). */
#include "ss_schur.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_ball.h"
#include "ss_schur_impl.h"

void ss_schur_free(ss_schur *s) {
  if (!s) return;
  for (size_t i = 0; i < s->nrt; i++) {
    acb_clear(&s->rt[i].ball.z);
    arb_clear(&s->rt[i].ball.mod);
    if (s->rt[i].has_x) arb_mat_clear(&s->rt[i].X);
    if (s->rt[i].has_xc) acb_mat_clear(&s->rt[i].Xc);
  }
  ss_csr_free(&s->csr);
  ss_scc_free(&s->scc);
  free(s->rt);
  free(s->pub);
  ss_ball_outcome_clear(&s->out);
  free(s);
}

/* ---- the group ---- */

static uint64_t perm_hash(const size_t *p, size_t n) {
  uint64_t h = 1469598103934665603u;
  for (size_t i = 0; i < n; i++)
    h = (h ^ (uint64_t)p[i]) * 1099511628211u;
  return h;
}

typedef struct {
  uint64_t h; /* perm_hash */
  size_t g;   /* the element */
} hashed;

static int by_hash(const void *a, const void *b) {
  const uint64_t x = ((const hashed *)a)->h, y = ((const hashed *)b)->h;
  return x < y ? -1 : x > y;
}

/* Whether q (n entries) is one of the elements (H sorted by hash). */
static int member(const hashed *H, size_t ng, const size_t *G, size_t n,
                  const size_t *q) {
  const uint64_t h = perm_hash(q, n);
  size_t a = 0, b = ng;
  while (a < b) { /* the first entry of hash >= h */
    const size_t c = a + (b - a) / 2;
    if (H[c].h < h)
      a = c + 1;
    else
      b = c;
  }
  for (; a < ng && H[a].h == h; a++)
    if (!memcmp(G + H[a].g * n, q, n * sizeof *q)) return 1;
  return 0;
}

/* SS_EINPUT unless every element is a permutation keeping the one-ring and
 * the elements form a group (the identity among them, closed under
 * composition: a finite set closed so is a group). */
static ss_status check_group(const size_t *G, size_t ng, size_t n, size_t n1,
                             ss_error *err) {
  ss_status st = SS_OK;
  unsigned char *seen = malloc(n + 1);
  hashed *H = malloc((ng + 1) * sizeof *H);
  size_t *q = malloc((n + 1) * sizeof *q);
  if (!seen || !H || !q) {
    st = ss_error_nomem(err, "symmetry group");
    goto done;
  }
  for (size_t g = 0; g < ng && !st; g++) {
    const size_t *p = G + g * n;
    memset(seen, 0, n);
    for (size_t i = 0; i < n && !st; i++) {
      if (p[i] >= n || seen[p[i]] || (p[i] < n1) != (i < n1))
        st = ss_error_set(err, SS_EINPUT,
                          "symmetry group: element %zu is not a permutation keeping the "
                          "one-ring (point %zu)",
                          g, i);
      else
        seen[p[i]] = 1;
    }
    H[g] = (hashed){perm_hash(p, n), g};
  }
  if (st) goto done;
  qsort(H, ng, sizeof *H, by_hash);
  for (size_t i = 0; i < n; i++)
    q[i] = i;
  if (!ng || !member(H, ng, G, n, q)) {
    st = ss_error_set(err, SS_EINPUT, "symmetry group: the identity is not an element");
    goto done;
  }
  for (size_t a = 0; a < ng && !st; a++)
    for (size_t b = 0; b < ng && !st; b++) {
      for (size_t i = 0; i < n; i++)
        q[i] = G[a * n + G[b * n + i]];
      if (!member(H, ng, G, n, q))
        st = ss_error_set(err, SS_EINPUT,
                          "symmetry group: elements %zu and %zu compose to no element: "
                          "not a group",
                          a, b);
    }
done:
  free(seen);
  free(H);
  free(q);
  return st;
}

/* ---- the enclosures ---- */

sc_root *ss_schur_root_new(ss_schur *s) {
  if (s->nrt == s->cap) {
    const size_t cap = 2 * s->cap + 8;
    sc_root *t = realloc(s->rt, cap * sizeof *t);
    if (!t) return NULL;
    s->rt = t;
    s->cap = cap;
  }
  sc_root *o = s->rt + s->nrt++;
  memset(o, 0, sizeof *o);
  acb_init(&o->ball.z);
  arb_init(&o->ball.mod);
  return o;
}

/* The enclosures of A's and C's blocks' eigenvalues: 0, -1 out of memory, 1
 * a block not enclosed (*bad: -1 for A, else its component). */
static int all_roots(ss_schur *s, const double *S, long *bad) {
  const size_t n = s->n, n1 = s->n1;
  acb_mat_t A;
  acb_mat_init(A, (slong)n1, (slong)n1);
  for (size_t i = 0; i < n1; i++)
    for (size_t j = 0; j < n1; j++)
      ss_ball_entry(acb_realref(acb_mat_entry(A, i, j)), S[i * n + j]);
  int out = ss_schur_block(s, A, -1);
  acb_mat_clear(A);
  *bad = -1;
  if (out) return out;
  if (ss_csr_make(S, n, n1, &s->csr) || ss_scc_make(&s->csr, n, n1, &s->scc)) return -1;
  for (long c = 0; c < s->scc.n && !out; c++) {
    const size_t *nodes = s->scc.comp + s->scc.start[c];
    const slong b = (slong)(s->scc.start[c + 1] - s->scc.start[c]);
    acb_mat_t D;
    acb_mat_init(D, b, b);
    for (slong x = 0; x < b; x++)
      for (slong y = 0; y < b; y++)
        ss_ball_entry(acb_realref(acb_mat_entry(D, x, y)),
                      S[(n1 + nodes[x]) * n + n1 + nodes[y]]);
    out = ss_schur_block(s, D, c);
    *bad = c;
    acb_mat_clear(D);
  }
  return out;
}

/* Whether root a's ball meets no other root's. */
static int alone(const ss_schur *s, size_t a) {
  for (size_t i = 0; i < s->nrt; i++)
    if (i != a && acb_overlaps(&s->rt[i].ball.z, &s->rt[a].ball.z)) return 0;
  return 1;
}

/* The proven sign of Re of root r: 1 positive, -1 not positive, 0 unknown
 * (not inlined: as ss_ball_conj). */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static int
re_sign(const ss_schur *s, size_t r) {
  const arb_struct *re = acb_realref(&s->rt[r].ball.z);
  return arb_is_positive(re) ? 1 : arb_is_nonpositive(re) ? -1 : 0;
}

/* Whether root a is proven real: the conjugate of its ball meets no other
 * root (S is real, so the conjugate of its eigenvalue is an eigenvalue, in
 * some root: this one). */
static int proven_real(const ss_schur *s, size_t a) {
  acb_t cz;
  acb_init(cz);
  ss_ball_conj(cz, &s->rt[a].ball.z);
  int ok = acb_overlaps(cz, &s->rt[a].ball.z);
  for (size_t i = 0; i < s->nrt && ok; i++)
    if (i != a && acb_overlaps(cz, &s->rt[i].ball.z)) ok = 0;
  acb_clear(cz);
  return ok;
}

/* "0.4226+0i" */
static const char *root_text(const void *route, size_t i, char *buf, size_t len) {
  const ss_schur *s = route;
  double re = 0.0, im = 0.0;
  ss_ball_mid(&s->rt[i].ball, &re, &im, NULL);
  snprintf(buf, len, "%.10g%+.3gi", re, im);
  return buf;
}

/* s's roots for the steps ss_ball shares with ss_fourier. */
static ss_ball_roots roots_of(const ss_schur *s) {
  return (ss_ball_roots){s->rt, s->nrt, sizeof *s->rt, root_text, s};
}

/* lambda0 = 1 simple and every other modulus below 1: 1 with the verdict set
 * otherwise; *one its index. */
static int assess_one(ss_schur *s, size_t *one) {
  const ss_ball_roots R = roots_of(s);
  const size_t ones = ss_ball_ones(&R, one);
  const sc_root *o = s->rt + *one;
  if (ones != 1 || o->blk != -1 || o->count != 1 || !o->ball.counted || !alone(s, *one)) {
    ss_ball_verdict(
        &s->out, SS_UNDECIDED, 0,
        "not certified: lambda0 = 1 not isolated by the balls (%zu contain 1)", ones);
    return 1;
  }
  return ss_ball_below_one(&R, *one, &s->out);
}

/* Every root but one and the nl leading ones proven of modulus below x. */
static int rest_below(const ss_schur *s, size_t one, const size_t *lead, int nl,
                      const arb_t x) {
  const ss_ball_roots R = roots_of(s);
  return ss_ball_rest_below(&R, one, lead, nl, x, SIZE_MAX);
}

/* Leading root r (lambda_pos..): 0 when it is one real positive eigenvalue
 * of A, not defective, counted, meeting no other root (a tie proven by
 * Schur's lemma); else 1 with the verdict set (undecided), -1 out of
 * memory. */
static int assess_root(ss_schur *s, size_t r, int pos, const size_t *G, size_t ng,
                       size_t one, const size_t *lead, int nl) {
  char b1[64], why[320] = "";
  sc_root *o = s->rt + r;
  root_text(s, r, b1, sizeof b1);
  if (o->blk >= 0)
    snprintf(why, sizeof why,
             "lambda%d = %s is an eigenvalue of the outer block (component %ld), where "
             "the symmetry route does not look",
             pos, b1, o->blk);
  else if (!o->ball.counted || !alone(s, r))
    snprintf(why, sizeof why, "lambda%d = %s not isolated (balls)", pos, b1);
  else if (!proven_real(s, r))
    snprintf(why, sizeof why, "lambda%d = %s not proven real", pos, b1);
  else if (re_sign(s, r) != 1) {
    if (re_sign(s, r) == -1 && rest_below(s, one, lead, nl, &o->ball.mod)) {
      ss_ball_verdict(&s->out, SS_FAIL, 1,
                      "lambda%d = %s is not positive (proven, balls)", pos, b1);
      return 1;
    }
    snprintf(why, sizeof why, "lambda%d = %s not proven positive", pos, b1);
  }
  if (*why) {
    ss_ball_verdict(&s->out, SS_UNDECIDED, 0, "not certified: %s", why);
    return 1;
  }
  if (o->count == 1) {
    o->scalar = 1;
    return 0;
  }
  if (ss_schur_subspace(s, r, why, sizeof why)) {
    ss_ball_verdict(&s->out, SS_UNDECIDED, 0, "not certified: lambda%d..%d = %s: %s", pos,
                    pos + o->count - 1, b1, why);
    return 1;
  }
  const int rc = ss_schur_character(s, r, G, ng, why, sizeof why);
  if (rc < 0) return -1;
  if (rc > 0 || !(o->scalar || o->split)) {
    if (rc == 0)
      snprintf(why, sizeof why,
               "<chi, chi> = [%.6g, %.6g] over the %zu symmetries is not proven 1 (nor "
               "2, 3 with real constituents): the cluster is not forced by the "
               "symmetry (balls too wide, or a constituent repeated)",
               o->nlo, o->nhi, ng);
    ss_ball_verdict(&s->out, SS_UNDECIDED, 0,
                    "not certified: %d eigenvalues in the ball of %s: %s", o->count, b1,
                    why);
    return 1;
  }
  return 0;
}

/* The condition (ss_schur.h).  0, or -1 out of memory. */
static int assess(ss_schur *s, const size_t *G, size_t ng) {
  size_t one = 0, lead[4];
  if (assess_one(s, &one)) return 0;
  int nl = 0, count = 0;
  for (size_t i = 0; i < s->nrt && count < s->m; i++)
    if (i != one) {
      lead[nl++] = i;
      s->rt[i].scalar = s->rt[i].split = 0;
      count += s->rt[i].count;
    }
  if (count < s->m) {
    ss_ball_verdict(&s->out, SS_UNDECIDED, 0,
                    "not certified: fewer than %d eigenvalues counted", s->m + 1);
    return 0;
  }
  for (int j = 0, pos = 1; j < nl; pos += s->rt[lead[j]].count, j++) {
    const int rc = assess_root(s, lead[j], pos, G, ng, one, lead, nl);
    if (rc) return rc < 0 ? -1 : 0;
  }
  for (int j = 0; j < nl; j++)
    if (!rest_below(s, one, lead, nl, acb_realref(&s->rt[lead[j]].ball.z))) {
      ss_ball_verdict(
          &s->out, SS_UNDECIDED, 0,
          "not certified: moduli of lambda%d and lambda%d not separated (balls)", s->m,
          s->m + 1);
      return 0;
    }
  if (count > s->m && !s->rt[lead[nl - 1]].scalar) {
    ss_ball_verdict(&s->out, SS_UNDECIDED, 0,
                    "not certified: lambda%d and lambda%d in one cluster of %d distinct "
                    "constituents: their order not decided",
                    s->m, s->m + 1, s->rt[lead[nl - 1]].split);
    return 0;
  }
  if (count > s->m) { /* the last root, one eigenvalue, straddles m */
    char b1[64];
    ss_ball_verdict(&s->out, SS_FAIL, 1,
                    "exact tie: lambda%d = lambda%d = %s (%d eigenvalues, one by Schur's "
                    "lemma, proven)",
                    s->m, s->m + 1, root_text(s, lead[nl - 1], b1, sizeof b1),
                    s->rt[lead[nl - 1]].count);
    return 0;
  }
  memcpy(s->lead, lead, sizeof lead);
  s->nlead = nl;
  ss_ball_verdict(&s->out, SS_PASS, 1, "%s", "");
  return 0;
}

/* The public copies of the roots. */
static int publish(ss_schur *s) {
  s->pub = calloc(s->nrt + 1, sizeof *s->pub);
  if (!s->pub) return -1;
  for (size_t i = 0; i < s->nrt; i++) {
    const sc_root *r = s->rt + i;
    double re = 0.0, im = 0.0, rad = 0.0;
    ss_ball_mid(&r->ball, &re, &im, &rad);
    int lead = 0;
    for (int j = 0; j < s->nlead; j++)
      lead |= s->lead[j] == i;
    s->pub[i] = (ss_schur_root){re,
                                im,
                                rad,
                                r->ball.counted ? r->count : 0,
                                r->blk < 0 ? 0 : (int)r->blk + 1,
                                lead ? 2 : 0,
                                r->nlo,
                                r->nhi,
                                r->scalar && r->count > 1 ? 1 : r->split};
  }
  return 0;
}

/* The enclosures, the condition and on a pass the basis. */
static ss_status analyse(ss_schur *s, const double *S, const size_t *G, size_t ng,
                         ss_error *err) {
  long bad = 0;
  int rc = all_roots(s, S, &bad);
  if (rc < 0) return ss_error_nomem(err, "Schur route");
  if (rc > 0) {
    if (bad < 0)
      ss_ball_verdict(
          &s->out, SS_UNDECIDED, 0,
          "not certified: the eigenvalues of the one-ring block not enclosed");
    else
      ss_ball_verdict(
          &s->out, SS_UNDECIDED, 0,
          "not certified: the eigenvalues of the outer block's component %ld not "
          "enclosed",
          bad);
    return SS_OK;
  }
  qsort(s->rt, s->nrt, sizeof *s->rt, ss_ball_by_modulus);
  if (assess(s, G, ng) < 0) return ss_error_nomem(err, "Schur route");
  if (s->out.cond.verdict == SS_PASS) {
    for (int j = 0; j < s->nlead && !rc; j++)
      if (!s->rt[s->lead[j]].has_x)
        rc = ss_schur_subspace(s, s->lead[j], s->out.bmsg, sizeof s->out.bmsg);
    if (!rc) rc = ss_schur_complete(s, S, s->out.bmsg, sizeof s->out.bmsg);
    if (rc < 0) return ss_error_nomem(err, "Schur basis");
  }
  if (publish(s)) return ss_error_nomem(err, "Schur route");
  return SS_OK;
}

ss_status ss_schur_new(const double *S, size_t n, size_t n1, const size_t *group,
                       size_t ng, int m, ss_schur **out, ss_error *err) {
  *out = NULL;
  if (n1 < 1 || n1 > n || (m != 2 && m != 3))
    return ss_error_set(err, SS_EINPUT, "Schur route: n1 %zu of %zu, m %d not 2 or 3", n1,
                        n, m);
  ss_status st = ss_scc_check_form(S, n, n1, err);
  if (st) return st;
  if ((st = check_group(group, ng, n, n1, err))) return st;
  ss_schur *s = calloc(1, sizeof *s);
  if (!s) return ss_error_nomem(err, "Schur route");
  s->n = n;
  s->n1 = n1;
  s->m = m;
  ss_ball_outcome_init(&s->out, n, m);
  size_t bi = 0, bj = 0, g = 0;
  while (g < ng && ss_ball_invariant(S, n, group + g * n, &bi, &bj))
    g++;
  if (g < ng)
    ss_ball_verdict(
        &s->out, SS_UNDECIDED, 0,
        "not certified: S is not invariant under symmetry %zu of %zu (entry %zu, "
        "%zu): Schur's lemma does not apply",
        g, ng, bi, bj);
  else
    st = analyse(s, S, group, ng, err);
  if (st) {
    ss_schur_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}

const ss_ball_outcome *ss_schur_outcome(const ss_schur *s) {
  return &s->out;
}

const ss_schur_root *ss_schur_roots(const ss_schur *s, size_t *nroots) {
  *nroots = s->pub ? s->nrt : 0;
  return s->pub;
}
