/* ss_fourier.c — a surface vertex's eigenvalue condition from the Fourier
 * blocks of its local matrix in ball arithmetic (method: ss_fourier.h). */
#include "ss_fourier.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>

#include "acb_mat.h"
#include "arb.h"

#include "ss_ball.h"

enum {
  FR_PREC = 128 /* working precision, bits: the entries' balls (2^-40,
                   ss_ball_entry) decide the width, not this */
};

/* One Fourier block: S restricted to V_k. */
typedef struct {
  int k;            /* its mode, 0 <= k <= n / 2 */
  size_t b;         /* orbits in it (its size) */
  long *col;        /* norb entries: the orbit's column in the block, or -1 */
  size_t *orb;      /* b orbits, in column order */
  acb_mat_struct B; /* S_k in balls (b x b), kept for the basis */
  int has_b;        /* 1 once B is initialised */
} fr_block;

/* One eigenvalue enclosure (internal). */
typedef struct {
  ss_ball_root ball; /* the ball, |z|, counted (first: ss_ball_roots) */
  size_t blk;        /* its block */
  int isolated;      /* one eigenvalue of the block in z */
  int real;          /* 1 proven real, -1 proven not, 0 unknown */
  acb_ptr vec;       /* isolated: its eigenvector over the block's orbits, or NULL */
  int full;          /* 1: vec is S_k's eigenvector; 0: only its component's
                        (zero elsewhere), which extend() completes */
  size_t part;       /* its strongly connected component (a column of it) */
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
  ss_ball_outcome out;  /* the condition and on a pass the basis */
  int m;                /* subdominant eigenvalues: 2 surface, 3 volume */
  size_t lead[4];       /* on a pass: the roots of lambda1..m (a pair once) */
  int nlead;            /* ... how many */
};

void ss_fourier_free(ss_fourier *f) {
  if (!f) return;
  for (size_t i = 0; i < f->nrt; i++) {
    acb_clear(&f->rt[i].ball.z);
    arb_clear(&f->rt[i].ball.mod);
    if (f->rt[i].vec) _acb_vec_clear(f->rt[i].vec, (slong)f->blk[f->rt[i].blk].b);
  }
  for (size_t b = 0; b < f->nblk; b++) {
    free(f->blk[b].col);
    free(f->blk[b].orb);
    if (f->blk[b].has_b) acb_mat_clear(&f->blk[b].B);
  }
  if (f->w) _acb_vec_clear(f->w, f->order);
  free(f->blk);
  free(f->rt);
  free(f->pub);
  free(f->rep);
  free(f->osize);
  free(f->orb_of);
  free(f->pos);
  ss_ball_outcome_clear(&f->out);
  free(f);
}

static int is_perm(const size_t *p, size_t n, unsigned char *seen) {
  memset(seen, 0, n);
  for (size_t i = 0; i < n; i++) {
    if (p[i] >= n || seen[p[i]]) return 0;
    seen[p[i]] = 1;
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
      ss_ball_entry(e, S[r * n + j]);
      acb_mul_arb(t, f->w + ((size_t)bl->k * f->pos[j]) % (size_t)f->order, e, FR_PREC);
      acb_add(acb_mat_entry(B, (slong)a, c), acb_mat_entry(B, (slong)a, c), t, FR_PREC);
    }
  }
  acb_clear(t);
  arb_clear(e);
}

/* The closure of B's pattern (b x b): R[x b + y] = 1 when orbit x reads
 * orbit y through entries that are not exactly 0 (x reads itself), and
 * comp[x] the first column of x's strongly connected component.  NULL when
 * out of memory. */
static unsigned char *closure(const acb_mat_t B, size_t *comp) {
  const size_t b = (size_t)acb_mat_nrows(B);
  unsigned char *R = malloc(b * b + 1);
  if (!R) return NULL;
  for (size_t x = 0; x < b; x++)
    for (size_t y = 0; y < b; y++)
      R[x * b + y] = x == y || !acb_is_zero(acb_mat_entry(B, (slong)x, (slong)y));
  for (size_t k = 0; k < b; k++)
    for (size_t x = 0; x < b; x++)
      if (R[x * b + k])
        for (size_t y = 0; y < b; y++)
          R[x * b + y] |= R[k * b + y];
  for (size_t x = 0; x < b; x++) {
    comp[x] = x;
    for (size_t c = 0; c < x && comp[x] == x; c++)
      if (R[x * b + c] && R[c * b + x]) comp[x] = c;
  }
  return R;
}

/* S_k is block triangular over the strongly connected components of its
 * pattern (S's zeros are exact), so its spectrum is theirs: each
 * component's principal block enclosed apart into E, part[i] its component,
 * sim[i] 1 where the ball isolates its eigenvalue there, counted[i] 0 for
 * a ball that only bounds (ss_ball_eig's 2), vec[i] then its
 * eigenvector (zero off the component; else NULL).  0, or -1 if a
 * component's are not enclosed or out of memory. */
static int split_eigen(const acb_mat_t B, const size_t *comp, acb_ptr E, size_t *part,
                       int *sim, int *counted, acb_ptr *vec) {
  const slong b = acb_mat_nrows(B);
  slong at = 0, *idx = malloc(((size_t)b + 1) * sizeof *idx);
  if (!idx) return -1;
  int rc = 1;
  for (slong c = 0; c < b && rc >= 0; c++) {
    if (comp[c] != (size_t)c) continue;
    slong m = 0;
    for (slong a = 0; a < b; a++)
      if (comp[a] == (size_t)c) idx[m++] = a;
    acb_mat_t D, R;
    acb_mat_init(D, m, m);
    acb_mat_init(R, m, m);
    for (slong x = 0; x < m; x++)
      for (slong y = 0; y < m; y++)
        acb_set(acb_mat_entry(D, x, y), acb_mat_entry(B, idx[x], idx[y]));
    rc = ss_ball_eig(E + at, R, D, NULL, NULL, FR_PREC);
    for (slong x = 0; x < m && rc >= 0; x++, at++) {
      part[at] = (size_t)c, sim[at] = rc == 1, counted[at] = rc != 2;
      vec[at] = rc == 1 ? _acb_vec_init(b) : NULL;
      for (slong y = 0; rc == 1 && y < m; y++)
        acb_set(vec[at] + idx[y], acb_mat_entry(R, y, x));
    }
    acb_mat_clear(R);
    acb_mat_clear(D);
  }
  free(idx);
  return rc >= 0 ? 0 : -1;
}

/* The eigenvalues of block bi (S_k in bl->B) into f->rt: 1, or 0 if arb
 * encloses none (or out of memory). */
static int block_eigen(ss_fourier *f, size_t bi) {
  const acb_mat_struct *B = &f->blk[bi].B;
  const slong b = acb_mat_nrows(B);
  acb_ptr E = _acb_vec_init(b);
  acb_mat_t R;
  acb_mat_init(R, b, b);
  size_t *part = calloc((size_t)b + 1, sizeof *part);
  size_t *comp = malloc(((size_t)b + 1) * sizeof *comp);
  int *sim = calloc((size_t)b + 1, sizeof *sim);
  int *counted = calloc((size_t)b + 1, sizeof *counted);
  acb_ptr *vec = calloc((size_t)b + 1, sizeof *vec);
  unsigned char *reach = part && comp && sim && counted && vec ? closure(B, comp) : NULL;
  size_t ncomp = 0;
  for (slong a = 0; reach && a < b; a++)
    ncomp += comp[a] == (size_t)a;
  int ok = 0, whole = 0;
  if (reach && ncomp == 1) { /* one component: the block at once */
    const int rc = ss_ball_eig(E, R, B, NULL, NULL, FR_PREC);
    ok = rc >= 0, whole = rc == 1;
    for (slong i = 0; i < b; i++)
      counted[i] = rc != 2;
    for (slong i = 0; whole && i < b; i++) {
      sim[i] = 1;
      vec[i] = _acb_vec_init(b);
      for (slong j = 0; j < b; j++)
        acb_set(vec[i] + j, acb_mat_entry(R, j, i));
    }
  } else if (reach) {
    ok = !split_eigen(B, comp, E, part, sim, counted, vec);
  }
  acb_t cz;
  acb_init(cz);
  for (slong i = 0; ok && i < b; i++) {
    fr_root *r = f->rt + f->nrt++;
    acb_init(&r->ball.z);
    arb_init(&r->ball.mod);
    acb_set(&r->ball.z, E + i);
    acb_abs(&r->ball.mod, &r->ball.z, FR_PREC);
    r->blk = bi;
    r->part = part[i];
    r->full = whole;
    r->ball.counted = counted[i];
    r->isolated = sim[i]; /* and apart from the other components' */
    for (slong j = 0; j < b; j++)
      if (part[j] != part[i] && acb_overlaps(E + i, E + j)) r->isolated = 0;
    r->vec = vec[i];
    vec[i] = NULL;
    acb_conj(cz, E + i);
    r->real = acb_overlaps(cz, E + i) ? 0 : -1;
    if (r->isolated && !r->real) {
      r->real = 1;
      for (slong j = 0; j < b; j++)
        if (j != i && acb_overlaps(cz, E + j)) r->real = 0;
    }
  }
  acb_clear(cz);
  for (slong i = 0; vec && i < b; i++)
    if (vec[i]) _acb_vec_clear(vec[i], b);
  free(vec);
  free(reach);
  free(part);
  free(comp);
  free(sim);
  free(counted);
  acb_mat_clear(R);
  _acb_vec_clear(E, b);
  return ok;
}

/* Complete root r's eigenvector from its component C to S_k: x is 0 where
 * nothing reads C, and on the orbits Z that read C (through others) solves
 * (S_k[Z][Z] - lambda) x_Z = -S_k[Z][C] x_C, lambda r's ball, which is apart
 * from the other components' eigenvalues (r isolated).  1, or 0 when the
 * solve is not proven (or out of memory). */
static int extend(const ss_fourier *f, fr_root *r) {
  const fr_block *bl = f->blk + r->blk;
  const slong b = (slong)bl->b;
  size_t *comp = malloc(((size_t)b + 1) * sizeof *comp);
  slong *z = malloc(((size_t)b + 1) * sizeof *z), nz = 0;
  unsigned char *reach = comp && z ? closure(&bl->B, comp) : NULL;
  for (slong a = 0; reach && a < b; a++)
    if (comp[a] != r->part && reach[(size_t)a * (size_t)b + r->part]) z[nz++] = a;
  int ok = reach != NULL;
  if (ok && nz) {
    acb_mat_t M, y, rhs;
    acb_mat_init(M, nz, nz);
    acb_mat_init(y, nz, 1);
    acb_mat_init(rhs, nz, 1);
    for (slong x = 0; x < nz; x++) {
      for (slong w = 0; w < nz; w++)
        acb_set(acb_mat_entry(M, x, w), acb_mat_entry(&bl->B, z[x], z[w]));
      acb_sub(acb_mat_entry(M, x, x), acb_mat_entry(M, x, x), &r->ball.z, FR_PREC);
      for (slong c = 0; c < b; c++)
        if (comp[c] == r->part)
          acb_submul(acb_mat_entry(rhs, x, 0), acb_mat_entry(&bl->B, z[x], c), r->vec + c,
                     FR_PREC);
    }
    ok = acb_mat_solve(y, M, rhs, FR_PREC);
    for (slong x = 0; ok && x < nz; x++)
      acb_set(r->vec + z[x], acb_mat_entry(y, x, 0));
    acb_mat_clear(rhs);
    acb_mat_clear(y);
    acb_mat_clear(M);
  }
  r->full = ok;
  free(reach);
  free(z);
  free(comp);
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
    acb_mat_init(&bl->B, (slong)bl->b, (slong)bl->b);
    bl->has_b = 1;
    block_matrix(f, S, bl, &bl->B);
    if (!block_eigen(f, f->nblk - 1)) {
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

/* "0.4226+0.0000i (Fourier mode 1)" */
static const char *root_text(const void *route, size_t i, char *buf, size_t len) {
  const ss_fourier *f = route;
  double re = 0.0, im = 0.0;
  ss_ball_mid(&f->rt[i].ball, &re, &im, NULL);
  snprintf(buf, len, "%.10g%+.3gi (Fourier mode %d)", re, im, f->blk[f->rt[i].blk].k);
  return buf;
}

/* f's roots for the steps ss_ball shares with ss_schur. */
static ss_ball_roots roots_of(const ss_fourier *f) {
  return (ss_ball_roots){f->rt, f->nrt, sizeof *f->rt, root_text, f};
}

/* lambda0 = 1 simple and every other modulus below 1: 1 with the verdict set
 * otherwise; *one its index. */
static int assess_one(ss_fourier *f, size_t *one) {
  const ss_ball_roots R = roots_of(f);
  const size_t ones = ss_ball_ones(&R, one);
  if (ones != 1 || f->blk[f->rt[*one].blk].k != 0 || !f->rt[*one].isolated) {
    ss_ball_verdict(
        &f->out, SS_UNDECIDED, 0,
        "not certified: lambda0 = 1 not isolated by the Fourier blocks' balls "
        "(%zu contain 1)",
        ones);
    return 1;
  }
  return ss_ball_below_one(&R, *one, &f->out);
}

/* Every root but one, the nl leading ones lead[] and skip (SIZE_MAX: none)
 * proven of modulus below x. */
static int rest_below(const ss_fourier *f, size_t one, const size_t *lead, int nl,
                      const arb_t x, size_t skip) {
  const ss_ball_roots R = roots_of(f);
  return ss_ball_rest_below(&R, one, lead, nl, x, skip);
}

/* The conjugate of root a (isolated): the one other ball of its block that
 * meets conj(a's ball) holds conj(a), since S_k's spectrum is closed under
 * conjugation; SIZE_MAX when that ball is not unique. */
static size_t partner(const ss_fourier *f, size_t a) {
  acb_t cz;
  acb_init(cz);
  ss_ball_conj(cz, &f->rt[a].ball.z);
  size_t p = SIZE_MAX, count = 0;
  for (size_t i = 0; i < f->nrt; i++)
    if (i != a && f->rt[i].blk == f->rt[a].blk && acb_overlaps(cz, &f->rt[i].ball.z))
      p = i, count++;
  acb_clear(cz);
  return count == 1 ? p : SIZE_MAX;
}

/* lambda_m = lambda_m+1: the last leading root, a pair, straddles m. */
static void assess_straddle(ss_fourier *f, size_t one, const size_t *lead, int nl) {
  char b1[96];
  const fr_root *r = f->rt + lead[nl - 1];
  int placed = r->isolated && rest_below(f, one, lead, nl, &r->ball.mod, SIZE_MAX);
  for (int j = 0; j + 1 < nl; j++)
    placed &= arb_gt(&f->rt[lead[j]].ball.mod, &r->ball.mod);
  if (placed)
    ss_ball_verdict(
        &f->out, SS_FAIL, 1,
        "exact tie: lambda%d = lambda%d = %s (Fourier modes k and n - k, proven)", f->m,
        f->m + 1, root_text(f, lead[nl - 1], b1, sizeof b1));
  else
    ss_ball_verdict(
        &f->out, SS_UNDECIDED, 0,
        "not certified: moduli of lambda%d and lambda%d not separated (balls)", f->m,
        f->m + 1);
}

/* Leading root j (lambda_pos): 0 if isolated, real and positive, else 1 with
 * the verdict set. */
static int assess_root(ss_fourier *f, size_t one, const size_t *lead, int nl, int j,
                       int pos) {
  char b1[96];
  const fr_root *r = f->rt + lead[j];
  const arb_struct *re = acb_realref(&r->ball.z);
  root_text(f, lead[j], b1, sizeof b1);
  if (!r->isolated) {
    ss_ball_verdict(&f->out, SS_UNDECIDED, 0,
                    "not certified: lambda%d = %s not isolated (balls)", pos, b1);
  } else if (r->real == -1) {
    /* every other root below |r| but r's conjugate: the moduli >= |r| fill
     * positions from at most pos on, and r, conj(r) share one, so a root that
     * is not real is among lambda1..m or |lambda_m| = |lambda_m+1| */
    const size_t p = partner(f, lead[j]);
    if (p != SIZE_MAX && rest_below(f, one, lead, nl, &r->ball.mod, p))
      ss_ball_verdict(&f->out, SS_FAIL, 1, "lambda%d = %s is not real (proven, balls)",
                      pos, b1);
    else
      ss_ball_verdict(&f->out, SS_UNDECIDED, 0,
                      "not certified: lambda%d = %s is not real but not placed (balls)",
                      pos, b1);
  } else if (r->real == 0) {
    ss_ball_verdict(&f->out, SS_UNDECIDED, 0,
                    "not certified: lambda%d = %s not proven real", pos, b1);
  } else if (!arb_is_positive(re)) {
    if (arb_is_nonpositive(re) && rest_below(f, one, lead, nl, &r->ball.mod, SIZE_MAX))
      ss_ball_verdict(&f->out, SS_FAIL, 1,
                      "lambda%d = %s is not positive (proven, balls)", pos, b1);
    else
      ss_ball_verdict(&f->out, SS_UNDECIDED, 0,
                      "not certified: the sign of lambda%d not decided", pos);
  } else {
    return 0;
  }
  return 1;
}

/* lambda1..lambda_m: the roots after lambda0, in order, until m copies are
 * counted (a pair of modes k, n - k counts twice); each isolated, real and
 * positive, and every later root proven below each of them. */
static void assess(ss_fourier *f) {
  size_t one = 0, lead[4];
  if (assess_one(f, &one)) return;
  int nl = 0, count = 0;
  for (size_t i = 0; i < f->nrt && count < f->m; i++)
    if (i != one) {
      lead[nl++] = i;
      count += mult_of(f, f->rt + i);
    }
  if (count < f->m) {
    ss_ball_verdict(&f->out, SS_FAIL, 1, "S has fewer than %d eigenvalues", f->m + 1);
    return;
  }
  if (count > f->m) {
    assess_straddle(f, one, lead, nl);
    return;
  }
  for (int j = 0, pos = 1; j < nl; pos += mult_of(f, f->rt + lead[j]), j++)
    if (assess_root(f, one, lead, nl, j, pos)) return;
  for (int j = 0; j < nl; j++)
    if (!rest_below(f, one, lead, nl, acb_realref(&f->rt[lead[j]].ball.z), SIZE_MAX)) {
      ss_ball_verdict(
          &f->out, SS_UNDECIDED, 0,
          "not certified: moduli of lambda%d and lambda%d not separated (balls)", f->m,
          f->m + 1);
      return;
    }
  memcpy(f->lead, lead, sizeof lead);
  f->nlead = nl;
  ss_ball_verdict(&f->out, SS_PASS, 1, "%s", "");
}

/* Column c of the basis from root r (part 0: real, 1: imaginary). */
static int lift(ss_fourier *f, fr_root *r, int part, double *lo, double *hi) {
  const fr_block *bl = f->blk + r->blk;
  if (!r->vec || (!r->full && !extend(f, r))) return 0;
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
    ss_ball_doubles(part ? acb_imagref(v) : acb_realref(v), lo + i, hi + i);
    ok = isfinite(lo[i]) && isfinite(hi[i]);
  }
  acb_clear(v);
  _acb_vec_clear(a, (slong)bl->b);
  return ok;
}

static ss_status make_basis(ss_fourier *f, ss_error *err) {
  const size_t n = f->n;
  f->out.lo = malloc(((size_t)f->m * n + 1) * sizeof *f->out.lo);
  f->out.hi = malloc(((size_t)f->m * n + 1) * sizeof *f->out.hi);
  if (!f->out.lo || !f->out.hi) return ss_error_nomem(err, "Fourier basis");
  int ok = 1;
  size_t c = 0; /* a pair gives two columns: Re x, Im x */
  for (int j = 0; j < f->nlead && ok; j++)
    for (int part = 0; part < mult_of(f, f->rt + f->lead[j]) && ok; part++, c++)
      ok = lift(f, f->rt + f->lead[j], part, f->out.lo + c * n, f->out.hi + c * n);
  if (!ok) {
    free(f->out.lo);
    free(f->out.hi);
    f->out.lo = f->out.hi = NULL;
    snprintf(f->out.bmsg, sizeof f->out.bmsg, "%s",
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
  *sym =
      ss_ball_invariant(S, n, rot, &bi, &bj) && ss_ball_invariant(S, n, refl, &bi, &bj);
  if (!*sym)
    ss_ball_verdict(&f->out, SS_UNDECIDED, 0,
                    "not certified: S is not invariant under the star's rotation and "
                    "reflection (entry %zu, %zu): the Fourier blocks do not apply",
                    bi, bj);
  return SS_OK;
}

ss_status ss_fourier_new(const double *S, size_t n, size_t n1, const size_t *rot,
                         const size_t *refl, int order, int m, ss_fourier **out,
                         ss_error *err) {
  *out = NULL;
  if (n1 < 1 || n1 > n || (m != 2 && m != 3))
    return ss_error_set(err, SS_EINPUT, "Fourier blocks: n1 %zu of %zu, m %d not 2 or 3",
                        n1, n, m);
  ss_fourier *f = calloc(1, sizeof *f);
  if (!f) return ss_error_nomem(err, "Fourier blocks");
  f->n = n;
  f->n1 = n1;
  f->m = m;
  f->order = order;
  ss_ball_outcome_init(&f->out, n, m);
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
    ss_ball_verdict(&f->out, SS_UNDECIDED, 0,
                    "not certified: the eigenvalues of Fourier block %d not enclosed",
                    bad);
    goto done;
  }
  /* by decreasing modulus: the vectors move with their roots */
  qsort(f->rt, f->nrt, sizeof *f->rt, ss_ball_by_modulus);
  f->pub = calloc(f->nrt + 1, sizeof *f->pub);
  if (!f->pub) {
    st = ss_error_nomem(err, "Fourier blocks");
    goto done;
  }
  for (size_t i = 0; i < f->nrt; i++) {
    const fr_root *r = f->rt + i;
    double re = 0.0, im = 0.0, rad = 0.0;
    ss_ball_mid(&r->ball, &re, &im, &rad);
    f->pub[i] = (ss_fourier_root){
        re, im, rad, mult_of(f, r), f->blk[r->blk].k, r->isolated, r->real};
  }
  assess(f);
  if (f->out.cond.verdict == SS_PASS) st = make_basis(f, err);
done:
  if (st) {
    ss_fourier_free(f);
    return st;
  }
  *out = f;
  return SS_OK;
}

const ss_ball_outcome *ss_fourier_outcome(const ss_fourier *f) {
  return &f->out;
}

const ss_fourier_root *ss_fourier_roots(const ss_fourier *f, size_t *nroots) {
  *nroots = f->pub ? f->nrt : 0;
  return f->pub;
}
