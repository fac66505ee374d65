/* ss_fourier.c — a surface vertex's eigenvalue condition from the Fourier
 * blocks of its local matrix in ball arithmetic (method: ss_fourier.h). */
#include "ss_fourier.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>

#include "acb_mat.h"
#include "arb.h"

enum {
  FR_PREC = 128, /* working precision, bits: the entries' balls (2^-40)
                    decide the width, not this */
  FR_WINDOW = 40 /* an entry s stands for s +- 2^-40 max(1, |s|) */
};

/* One Fourier block: S restricted to V_k. */
typedef struct {
  int k;       /* its mode, 0 <= k <= n / 2 */
  size_t b;    /* orbits in it (its size) */
  long *col;   /* norb entries: the orbit's column in the block, or -1 */
  size_t *orb; /* b orbits, in column order */
} fr_block;

/* One eigenvalue enclosure (internal). */
typedef struct {
  acb_struct z;   /* the ball */
  arb_struct mod; /* |z| enclosed */
  size_t blk;     /* its block */
  int isolated;   /* one eigenvalue of the block in z */
  int real;       /* 1 proven real, -1 proven not, 0 unknown */
  acb_ptr vec;    /* isolated: its eigenvector over the block's orbits, or NULL */
} fr_root;

struct ss_fourier {
  size_t n;             /* size of S */
  size_t n1;            /* its one-ring points, the first n1 */
  int order;            /* the rotation's order (the valence) */
  size_t norb;          /* orbits of the rotation */
  size_t *rep;          /* norb representatives */
  size_t *osize;        /* norb orbit sizes (each divides order) */
  size_t *orb_of;       /* n: each point's orbit */
  size_t *pos;          /* n: t with point = rot^t (its representative) */
  acb_ptr w;            /* order powers omega^t */
  size_t nblk;          /* blocks computed (k = 0..order / 2 with orbits) */
  fr_block *blk;        /* nblk blocks */
  size_t nrt;           /* eigenvalue enclosures */
  fr_root *rt;          /* nrt of them, by decreasing midpoint modulus */
  ss_fourier_root *pub; /* nrt public copies, same order */
  ss_verdict cond;      /* the condition */
  int certified;        /* 1 if cond is proven */
  size_t lead[2];       /* on a pass: lambda1 (and lambda2 unless pair) */
  int pair;             /* on a pass: 1 if lambda1 = lambda2 is one pair */
  double *lo, *hi;      /* on a pass: the basis enclosure (n x 2), or NULL */
  char bmsg[256];       /* why there is no basis on a pass */
};

static void set_verdict(ss_fourier *f, ss_verdict_kind v, int certified, const char *fmt,
                        ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static void set_verdict(ss_fourier *f, ss_verdict_kind v, int certified, const char *fmt,
                        ...) {
  va_list ap;
  va_start(ap, fmt);
  f->cond.verdict = v;
  vsnprintf(f->cond.reason, sizeof f->cond.reason, fmt, ap);
  va_end(ap);
  f->cond.certified = f->certified = certified;
  f->cond.on = SS_ON_SPECTRUM;
}

void ss_fourier_free(ss_fourier *f) {
  if (!f) return;
  for (size_t i = 0; i < f->nrt; i++) {
    acb_clear(&f->rt[i].z);
    arb_clear(&f->rt[i].mod);
    if (f->rt[i].vec) _acb_vec_clear(f->rt[i].vec, (slong)f->blk[f->rt[i].blk].b);
  }
  for (size_t b = 0; b < f->nblk; b++) {
    free(f->blk[b].col);
    free(f->blk[b].orb);
  }
  if (f->w) _acb_vec_clear(f->w, f->order);
  free(f->blk);
  free(f->rt);
  free(f->pub);
  free(f->rep);
  free(f->osize);
  free(f->orb_of);
  free(f->pos);
  free(f->lo);
  free(f->hi);
  free(f);
}

static double window(double s) {
  return ldexp(fmax(1.0, fabs(s)), -FR_WINDOW);
}

/* The ball an entry stands for: s +- 2^(e - 40) >= 2^-40 max(1, |s|); 0 for
 * an entry computed as 0 (no rule reads that point: the exact path's
 * reconstruction takes it for 0 too). */
static void entry_ball(arb_t b, double s) {
  int e = 0;
  if (s == 0.0) {
    arb_zero(b);
    return;
  }
  if (fabs(s) > 1.0) (void)frexp(s, &e); /* |s| < 2^e */
  arb_set_d(b, s);
  arb_add_error_2exp_si(b, (slong)e - FR_WINDOW);
}

static int is_perm(const size_t *p, size_t n, unsigned char *seen) {
  memset(seen, 0, n);
  for (size_t i = 0; i < n; i++) {
    if (p[i] >= n || seen[p[i]]) return 0;
    seen[p[i]] = 1;
  }
  return 1;
}

/* S[p i][p j] = S[i][j] within the windows: 1, or 0 with the entry. */
static int invariant(const double *S, size_t n, const size_t *p, size_t *bi, size_t *bj) {
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      const double a = S[i * n + j], b = S[p[i] * n + p[j]];
      if ((a == 0.0) != (b == 0.0) || !(fabs(a - b) <= window(a) + window(b))) {
        *bi = i;
        *bj = j;
        return 0;
      }
    }
  return 1;
}

/* Orbits of rot, and the powers of omega.  SS_EINPUT when an orbit's size
 * does not divide the order. */
static ss_status orbits(ss_fourier *f, const size_t *rot, ss_error *err) {
  const size_t n = f->n;
  f->rep = malloc((n + 1) * sizeof *f->rep);
  f->osize = malloc((n + 1) * sizeof *f->osize);
  f->orb_of = malloc((n + 1) * sizeof *f->orb_of);
  f->pos = malloc((n + 1) * sizeof *f->pos);
  if (!f->rep || !f->osize || !f->orb_of || !f->pos)
    return ss_error_nomem(err, "Fourier blocks");
  for (size_t i = 0; i < n; i++)
    f->orb_of[i] = SIZE_MAX;
  for (size_t i = 0; i < n; i++) {
    if (f->orb_of[i] != SIZE_MAX) continue;
    size_t t = 0, j = i;
    do {
      f->orb_of[j] = f->norb;
      f->pos[j] = t++;
      j = rot[j];
    } while (j != i);
    if ((size_t)f->order % t)
      return ss_error_set(err, SS_EINPUT,
                          "Fourier blocks: an orbit of %zu points under a rotation of "
                          "order %d",
                          t, f->order);
    f->rep[f->norb] = i;
    f->osize[f->norb++] = t;
  }
  f->w = _acb_vec_init(f->order);
  fmpq_t q;
  fmpq_init(q);
  for (int t = 0; t < f->order; t++) {
    fmpq_set_si(q, 2 * t, (ulong)f->order);
    arb_sin_cos_pi_fmpq(acb_imagref(f->w + t), acb_realref(f->w + t), q, FR_PREC);
  }
  fmpq_clear(q);
  return SS_OK;
}

/* S_k in balls (block bl, its orbits set). */
static void block_matrix(const ss_fourier *f, const double *S, const fr_block *bl,
                         acb_mat_t B) {
  const size_t n = f->n;
  arb_t e;
  acb_t t;
  arb_init(e);
  acb_init(t);
  acb_mat_zero(B);
  for (size_t a = 0; a < bl->b; a++) {
    const size_t r = f->rep[bl->orb[a]];
    for (size_t j = 0; j < n; j++) {
      const long c = bl->col[f->orb_of[j]];
      if (c < 0) continue;
      entry_ball(e, S[r * n + j]);
      acb_mul_arb(t, f->w + ((size_t)bl->k * f->pos[j]) % (size_t)f->order, e, FR_PREC);
      acb_add(acb_mat_entry(B, (slong)a, c), acb_mat_entry(B, (slong)a, c), t, FR_PREC);
    }
  }
  acb_clear(t);
  arb_clear(e);
}

/* The eigenvalue enclosures of B (b x b) into E, with their eigenvectors in
 * R (may be NULL) when the balls isolate them: 1 isolating balls, 0 common
 * balls of clusters, -1 none. */
static int enclose_eigen(acb_ptr E, acb_mat_t R, const acb_mat_t B) {
  const slong b = acb_mat_nrows(B);
  acb_ptr E0 = _acb_vec_init(b);
  acb_mat_t R0;
  acb_mat_init(R0, b, b);
  acb_mat_approx_eig_qr(E0, NULL, R0, B, NULL, 0, FR_PREC);
  const int rc = acb_mat_eig_simple(E, NULL, R, B, E0, R0, FR_PREC) ? 1
                 : acb_mat_eig_multiple(E, B, E0, R0, FR_PREC)      ? 0
                                                                    : -1;
  acb_mat_clear(R0);
  _acb_vec_clear(E0, b);
  return rc;
}

/* When S_k's eigenvalues cluster: S_k = [A_k 0; B_k C_k] (the one-ring's
 * orbits, then the outer ones: S's one-ring rows read no outer point, and its
 * zeros are exact), so its spectrum is A_k's and C_k's, enclosed apart into
 * E with part[i] the sub-block and sim[i] 1 where the ball isolates its
 * eigenvalue there.  0, or -1 if a sub-block's are not enclosed. */
static int split_eigen(const ss_fourier *f, const fr_block *bl, const acb_mat_t B,
                       acb_ptr E, int *part, int *sim) {
  slong at = 0;
  for (int p = 0; p < 2; p++) {
    slong m = 0, *idx = malloc((bl->b + 1) * sizeof *idx);
    if (!idx) return -1;
    for (size_t a = 0; a < bl->b; a++)
      if ((f->rep[bl->orb[a]] < f->n1) == (p == 0)) idx[m++] = (slong)a;
    acb_mat_t D;
    acb_mat_init(D, m, m);
    for (slong x = 0; x < m; x++)
      for (slong y = 0; y < m; y++)
        acb_set(acb_mat_entry(D, x, y), acb_mat_entry(B, idx[x], idx[y]));
    const int rc = m ? enclose_eigen(E + at, NULL, D) : 1;
    for (slong x = 0; x < m; x++)
      part[at + x] = p, sim[at + x] = rc == 1;
    at += m;
    acb_mat_clear(D);
    free(idx);
    if (rc < 0) return -1;
  }
  return 0;
}

/* The eigenvalues of block bi into f->rt: 1, or 0 if arb encloses none. */
static int block_eigen(ss_fourier *f, size_t bi, const acb_mat_t B) {
  const slong b = acb_mat_nrows(B);
  acb_ptr E = _acb_vec_init(b);
  acb_mat_t R;
  acb_mat_init(R, b, b);
  int *part = calloc((size_t)b, sizeof *part), *sim = calloc((size_t)b, sizeof *sim);
  const int whole = part && sim && enclose_eigen(E, R, B) == 1;
  const int ok = part && sim && (whole || !split_eigen(f, f->blk + bi, B, E, part, sim));
  acb_t cz;
  acb_init(cz);
  for (slong i = 0; ok && i < b; i++) {
    fr_root *r = f->rt + f->nrt++;
    acb_init(&r->z);
    arb_init(&r->mod);
    acb_set(&r->z, E + i);
    acb_abs(&r->mod, &r->z, FR_PREC);
    r->blk = bi;
    r->isolated = whole || sim[i]; /* and apart from the other sub-block's */
    for (slong j = 0; !whole && j < b; j++)
      if (part[j] != part[i] && acb_overlaps(E + i, E + j)) r->isolated = 0;
    r->vec = NULL;
    acb_conj(cz, E + i);
    r->real = acb_overlaps(cz, E + i) ? 0 : -1;
    if (r->isolated && !r->real) {
      r->real = 1;
      for (slong j = 0; j < b; j++)
        if (j != i && acb_overlaps(cz, E + j)) r->real = 0;
    }
    if (whole) {
      r->vec = _acb_vec_init(b);
      for (slong j = 0; j < b; j++)
        acb_set(r->vec + j, acb_mat_entry(R, j, i));
    }
  }
  acb_clear(cz);
  free(part);
  free(sim);
  acb_mat_clear(R);
  _acb_vec_clear(E, b);
  return ok;
}

/* Every block k = 0..order/2 that has orbits, and its eigenvalues.  0, -1
 * out of memory, 1 when a block's eigenvalues are not enclosed (*bad = k). */
static int all_blocks(ss_fourier *f, const double *S, int *bad) {
  const int half = f->order / 2;
  f->blk = calloc((size_t)half + 1, sizeof *f->blk);
  f->rt = calloc(f->norb * ((size_t)half + 1) + 1, sizeof *f->rt);
  if (!f->blk || !f->rt) return -1;
  for (int k = 0; k <= half; k++) {
    fr_block *bl = f->blk + f->nblk;
    bl->k = k;
    bl->col = malloc((f->norb + 1) * sizeof *bl->col);
    bl->orb = malloc((f->norb + 1) * sizeof *bl->orb);
    if (!bl->col || !bl->orb) {
      free(bl->col);
      free(bl->orb);
      return -1;
    }
    for (size_t o = 0; o < f->norb; o++) {
      bl->col[o] = ((size_t)k * f->osize[o]) % (size_t)f->order ? -1 : (long)bl->b;
      if (bl->col[o] >= 0) bl->orb[bl->b++] = o;
    }
    f->nblk++;
    if (!bl->b) continue;
    acb_mat_t B;
    acb_mat_init(B, (slong)bl->b, (slong)bl->b);
    block_matrix(f, S, bl, B);
    const int ok = block_eigen(f, f->nblk - 1, B);
    acb_mat_clear(B);
    if (!ok) {
      *bad = k;
      return 1;
    }
  }
  return 0;
}

static int mult_of(const ss_fourier *f, const fr_root *r) {
  const int k = f->blk[r->blk].k;
  return k > 0 && 2 * k < f->order ? 2 : 1;
}

static double mid_mod(const fr_root *r) {
  return arf_get_d(arb_midref(&r->mod), ARF_RND_NEAR);
}

static int by_modulus(const void *a, const void *b) {
  const double x = mid_mod(a), y = mid_mod(b);
  return x > y ? -1 : x < y;
}

/* "0.4226+0.0000i (Fourier mode 1)" */
static const char *root_text(const ss_fourier *f, size_t i, char *buf, size_t len) {
  const fr_root *r = f->rt + i;
  snprintf(buf, len, "%.10g%+.3gi (Fourier mode %d)",
           arf_get_d(arb_midref(acb_realref(&r->z)), ARF_RND_NEAR),
           arf_get_d(arb_midref(acb_imagref(&r->z)), ARF_RND_NEAR), f->blk[r->blk].k);
  return buf;
}

/* lambda0 = 1 simple and every other modulus below 1: 1 with the verdict set
 * otherwise; *one its index. */
static int assess_one(ss_fourier *f, size_t *one) {
  char b1[96];
  acb_t u;
  acb_init(u);
  acb_one(u);
  size_t ones = 0;
  for (size_t i = 0; i < f->nrt; i++)
    if (acb_contains(&f->rt[i].z, u)) ones++, *one = i;
  acb_clear(u);
  if (ones != 1 || f->blk[f->rt[*one].blk].k != 0 || !f->rt[*one].isolated) {
    set_verdict(f, SS_UNDECIDED, 0,
                "not certified: lambda0 = 1 not isolated by the Fourier blocks' balls "
                "(%zu contain 1)",
                ones);
    return 1;
  }
  arb_t t;
  arb_init(t);
  arb_one(t);
  int open = 0;
  for (size_t i = 0; i < f->nrt && !open; i++) {
    if (i == *one || arb_lt(&f->rt[i].mod, t)) continue;
    open = 1;
    if (arb_gt(&f->rt[i].mod, t))
      set_verdict(f, SS_FAIL, 1, "the eigenvalue %s has modulus > 1 (proven, balls)",
                  root_text(f, i, b1, sizeof b1));
    else
      set_verdict(f, SS_UNDECIDED, 0,
                  "not certified: the modulus of the eigenvalue %s and 1 not separated",
                  root_text(f, i, b1, sizeof b1));
  }
  arb_clear(t);
  return open;
}

/* Every root but one, a and b (SIZE_MAX: none) proven of modulus below x. */
static int all_below(const ss_fourier *f, size_t one, size_t a, size_t b, const arb_t x) {
  for (size_t i = 0; i < f->nrt; i++)
    if (i != one && i != a && i != b && !arb_lt(&f->rt[i].mod, x)) return 0;
  return 1;
}

/* The leading pair lambda1 = lambda2 = root a (a block 0 < k < n / 2). */
static void assess_pair(ss_fourier *f, size_t one, size_t a) {
  char b1[96];
  const fr_root *r = f->rt + a;
  const arb_struct *re = acb_realref(&r->z);
  if (!r->isolated) {
    set_verdict(f, SS_UNDECIDED, 0,
                "not certified: lambda1 = lambda2 = %s not isolated in its block",
                root_text(f, a, b1, sizeof b1));
  } else if (r->real == -1) {
    acb_t cz;
    acb_init(cz);
    acb_conj(cz, &r->z);
    int top = 1; /* every other root below it, or its conjugate */
    for (size_t i = 0; i < f->nrt; i++)
      if (i != one && i != a && !arb_lt(&f->rt[i].mod, &r->mod) &&
          !acb_overlaps(cz, &f->rt[i].z))
        top = 0;
    acb_clear(cz);
    if (top)
      set_verdict(f, SS_FAIL, 1, "lambda1 = %s is not real (proven, balls)",
                  root_text(f, a, b1, sizeof b1));
    else
      set_verdict(f, SS_UNDECIDED, 0,
                  "not certified: moduli of lambda1 and lambda3 not separated");
  } else if (r->real == 0) {
    set_verdict(f, SS_UNDECIDED, 0, "not certified: lambda1 = %s not proven real",
                root_text(f, a, b1, sizeof b1));
  } else if (!arb_is_positive(re)) {
    if (arb_is_nonpositive(re) && all_below(f, one, a, SIZE_MAX, &r->mod))
      set_verdict(f, SS_FAIL, 1, "lambda1 = lambda2 = %s is not positive (proven, balls)",
                  root_text(f, a, b1, sizeof b1));
    else
      set_verdict(f, SS_UNDECIDED, 0, "not certified: the sign of lambda1 not decided");
  } else if (!all_below(f, one, a, SIZE_MAX, re)) {
    set_verdict(f, SS_UNDECIDED, 0,
                "not certified: moduli of lambda2 and lambda3 not separated (balls)");
  } else {
    f->lead[0] = f->lead[1] = a;
    f->pair = 1;
    set_verdict(f, SS_PASS, 1, "%s", "");
  }
}

/* lambda1 = root a single (block 0 or n / 2), lambda2 root b. */
static void assess_single(ss_fourier *f, size_t one, size_t a, size_t b) {
  char b1[96], b2[96];
  const fr_root *ra = f->rt + a, *rb = f->rt + b;
  if (mult_of(f, rb) == 2) { /* lambda2 = lambda3: a tie if both are placed */
    if (arb_gt(&ra->mod, &rb->mod) && all_below(f, one, a, b, &rb->mod))
      set_verdict(f, SS_FAIL, 1,
                  "exact tie: lambda2 = lambda3 = %s (Fourier modes k and n - k, proven)",
                  root_text(f, b, b1, sizeof b1));
    else
      set_verdict(f, SS_UNDECIDED, 0,
                  "not certified: moduli of lambda1, lambda2 = lambda3 and lambda4 not "
                  "separated (balls)");
    return;
  }
  const arb_struct *ea = acb_realref(&ra->z), *eb = acb_realref(&rb->z);
  if (!ra->isolated || !rb->isolated || ra->real != 1 || rb->real != 1 ||
      !arb_is_positive(ea) || !arb_is_positive(eb)) {
    set_verdict(f, SS_UNDECIDED, 0,
                "not certified: lambda1 = %s and lambda2 = %s not proven real, positive "
                "and isolated",
                root_text(f, a, b1, sizeof b1), root_text(f, b, b2, sizeof b2));
  } else if (!all_below(f, one, a, b, ea) || !all_below(f, one, a, b, eb)) {
    set_verdict(f, SS_UNDECIDED, 0,
                "not certified: moduli of lambda2 and lambda3 not separated (balls)");
  } else {
    f->lead[0] = a;
    f->lead[1] = b;
    f->pair = 0;
    set_verdict(f, SS_PASS, 1, "%s", "");
  }
}

static void assess(ss_fourier *f) {
  size_t one = 0;
  if (assess_one(f, &one)) return;
  size_t a = SIZE_MAX, b = SIZE_MAX; /* the two largest after lambda0 */
  for (size_t i = 0; i < f->nrt; i++)
    if (i != one && a == SIZE_MAX)
      a = i;
    else if (i != one && b == SIZE_MAX)
      b = i;
  if (a == SIZE_MAX || (mult_of(f, f->rt + a) == 1 && b == SIZE_MAX)) {
    set_verdict(f, SS_FAIL, 1, "S has fewer than 3 eigenvalues");
    return;
  }
  if (mult_of(f, f->rt + a) == 2)
    assess_pair(f, one, a);
  else
    assess_single(f, one, a, b);
}

/* Outward-rounded doubles around a ball. */
static void enclose(const arb_t x, double *lo, double *hi) {
  arf_t t;
  arf_init(t);
  arb_get_lbound_arf(t, x, 64);
  *lo = arf_get_d(t, ARF_RND_FLOOR);
  arb_get_ubound_arf(t, x, 64);
  *hi = arf_get_d(t, ARF_RND_CEIL);
  arf_clear(t);
}

/* Column c of the basis from root r (part 0: real, 1: imaginary). */
static int lift(ss_fourier *f, const fr_root *r, int part, double *lo, double *hi) {
  const fr_block *bl = f->blk + r->blk;
  if (!r->vec) return 0;
  size_t big = 0; /* the entry of largest midpoint, made 1 */
  double best = -1.0;
  for (size_t j = 0; j < bl->b; j++) {
    const double m = fabs(arf_get_d(arb_midref(acb_realref(r->vec + j)), ARF_RND_NEAR)) +
                     fabs(arf_get_d(arb_midref(acb_imagref(r->vec + j)), ARF_RND_NEAR));
    if (m > best) best = m, big = j;
  }
  acb_ptr a = _acb_vec_init((slong)bl->b);
  acb_t v;
  acb_init(v);
  int ok = 1;
  for (size_t j = 0; j < bl->b; j++)
    acb_div(a + j, r->vec + j, r->vec + big, FR_PREC);
  for (size_t i = 0; i < f->n && ok; i++) {
    const long c = bl->col[f->orb_of[i]];
    if (c < 0) {
      lo[i] = hi[i] = 0.0;
      continue;
    }
    acb_mul(v, a + c, f->w + ((size_t)bl->k * f->pos[i]) % (size_t)f->order, FR_PREC);
    enclose(part ? acb_imagref(v) : acb_realref(v), lo + i, hi + i);
    ok = isfinite(lo[i]) && isfinite(hi[i]);
  }
  acb_clear(v);
  _acb_vec_clear(a, (slong)bl->b);
  return ok;
}

static ss_status make_basis(ss_fourier *f, ss_error *err) {
  const size_t n = f->n;
  f->lo = malloc((2 * n + 1) * sizeof *f->lo);
  f->hi = malloc((2 * n + 1) * sizeof *f->hi);
  if (!f->lo || !f->hi) return ss_error_nomem(err, "Fourier basis");
  int ok = 1;
  for (int c = 0; c < 2 && ok; c++)
    ok = lift(f, f->rt + f->lead[f->pair ? 0 : c], f->pair ? c : 0, f->lo + (size_t)c * n,
              f->hi + (size_t)c * n);
  if (!ok) {
    free(f->lo);
    free(f->hi);
    f->lo = f->hi = NULL;
    snprintf(f->bmsg, sizeof f->bmsg, "%s",
             "an eigenvector of a Fourier block was not enclosed");
  }
  return SS_OK;
}

/* The permutations' checks: SS_EINPUT; *sym = 1 when S is invariant (else
 * the verdict says why not). */
static ss_status check_input(ss_fourier *f, const double *S, const size_t *rot,
                             const size_t *refl, int *sym, ss_error *err) {
  const size_t n = f->n;
  unsigned char *seen = malloc(n + 1);
  if (!seen) return ss_error_nomem(err, "Fourier blocks");
  const int perms = is_perm(rot, n, seen) && is_perm(refl, n, seen);
  free(seen);
  if (!perms || f->order < 3)
    return ss_error_set(err, SS_EINPUT,
                        "Fourier blocks: rotation or reflection not a permutation, or "
                        "order %d < 3",
                        f->order);
  for (size_t i = 0; i < n; i++) {
    if (rot[refl[rot[refl[i]]]] != i)
      return ss_error_set(err, SS_EINPUT,
                          "Fourier blocks: the reflection does not invert the rotation");
    if ((rot[i] < f->n1) != (i < f->n1) || (refl[i] < f->n1) != (i < f->n1))
      return ss_error_set(err, SS_EINPUT,
                          "Fourier blocks: the symmetries do not keep the one-ring");
  }
  size_t bi = 0, bj = 0;
  *sym = invariant(S, n, rot, &bi, &bj) && invariant(S, n, refl, &bi, &bj);
  if (!*sym)
    set_verdict(f, SS_UNDECIDED, 0,
                "not certified: S is not invariant under the star's rotation and "
                "reflection (entry %zu, %zu): the Fourier blocks do not apply",
                bi, bj);
  return SS_OK;
}

ss_status ss_fourier_new(const double *S, size_t n, size_t n1, const size_t *rot,
                         const size_t *refl, int order, ss_fourier **out, ss_error *err) {
  *out = NULL;
  if (n1 < 1 || n1 > n) return ss_error_set(err, SS_EINPUT, "Fourier blocks: n1 %zu", n1);
  ss_fourier *f = calloc(1, sizeof *f);
  if (!f) return ss_error_nomem(err, "Fourier blocks");
  f->n = n;
  f->n1 = n1;
  f->order = order;
  snprintf(f->bmsg, sizeof f->bmsg, "%s", "the condition is not a certified pass");
  set_verdict(f, SS_UNDECIDED, 0, "%s", "not certified: not assessed");
  int sym = 0;
  ss_status st = check_input(f, S, rot, refl, &sym, err);
  if (st || !sym) goto done; /* not invariant: the verdict says so */
  if ((st = orbits(f, rot, err))) goto done;
  int bad = 0;
  const int rc = all_blocks(f, S, &bad);
  if (rc < 0) {
    st = ss_error_nomem(err, "Fourier blocks");
    goto done;
  }
  if (rc > 0) {
    set_verdict(f, SS_UNDECIDED, 0,
                "not certified: the eigenvalues of Fourier block %d not enclosed", bad);
    goto done;
  }
  /* by decreasing modulus: the vectors move with their roots */
  qsort(f->rt, f->nrt, sizeof *f->rt, by_modulus);
  f->pub = calloc(f->nrt + 1, sizeof *f->pub);
  if (!f->pub) {
    st = ss_error_nomem(err, "Fourier blocks");
    goto done;
  }
  for (size_t i = 0; i < f->nrt; i++) {
    const fr_root *r = f->rt + i;
    mag_t m;
    mag_init(m);
    mag_hypot(m, arb_radref(acb_realref(&r->z)), arb_radref(acb_imagref(&r->z)));
    f->pub[i] = (ss_fourier_root){arf_get_d(arb_midref(acb_realref(&r->z)), ARF_RND_NEAR),
                                  arf_get_d(arb_midref(acb_imagref(&r->z)), ARF_RND_NEAR),
                                  mag_get_d(m),
                                  mult_of(f, r),
                                  f->blk[r->blk].k,
                                  r->isolated,
                                  r->real};
    mag_clear(m);
  }
  assess(f);
  if (f->cond.verdict == SS_PASS) st = make_basis(f, err);
done:
  if (st) {
    ss_fourier_free(f);
    return st;
  }
  *out = f;
  return SS_OK;
}

void ss_fourier_condition(const ss_fourier *f, ss_verdict *v, int *certified) {
  *v = f->cond;
  *certified = f->certified;
}

const ss_fourier_root *ss_fourier_roots(const ss_fourier *f, size_t *nroots) {
  *nroots = f->pub ? f->nrt : 0;
  return f->pub;
}

ss_status ss_fourier_basis(const ss_fourier *f, double *lo, double *hi, ss_error *err) {
  if (f->cond.verdict != SS_PASS || !f->certified)
    return ss_error_set(err, SS_EINPUT, "%s", f->bmsg);
  if (!f->lo) return ss_error_set(err, SS_ENUMERIC, "%s", f->bmsg);
  memcpy(lo, f->lo, 2 * f->n * sizeof *lo);
  memcpy(hi, f->hi, 2 * f->n * sizeof *hi);
  return SS_OK;
}
