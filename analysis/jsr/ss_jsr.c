/* ss_jsr.c — bounds on the joint spectral radius: the norm profile rho_k by
 * brute force, the lower bound from spectral radii of products, and the
 * branch and bound (Gripenberg 1996) for the upper bound.  Method and
 * certification: ss_jsr.h. */
#include "ss_jsr.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>

#include "ss_clock.h"
#include "ss_jsr_cert.h"
#include "ss_jsr_ellipsoid.h"
#include "ss_jsr_polytope.h"

ss_jsr_opts ss_jsr_defaults(void) {
  ss_jsr_opts o = {8, 1e-3, SS_JSR_NORM_AUTO, 10000000, 0.0, 0, 1, 1};
  return o;
}

void ss_jsr_result_clear(ss_jsr_result *r) {
  if (!r) return;
  free(r->rho_inf);
  free(r->rho_2);
  free(r->lower_word);
  memset(r, 0, sizeof *r);
}

/* The depth-first walk over words.  Level k (0-based) of the stacks holds the
 * word's product of length k + 1, Y_{w_{k+1}} ... Y_{w_1}, formed as
 * Y_{w_{k+1}} times level k - 1: one n x n product per node.  All buffers are
 * allocated once (grown by ws_reserve when the branch and bound deepens). */
typedef struct {
  size_t m, n;            /* number and order of the matrices */
  const double *const *Y; /* the matrices in use: the (normalised) inputs or
                             their weighted copies in zbuf (not owned) */
  int cap;                /* levels the stacks hold */
  int *word;              /* cap: the current word, word[k] in 0..m-1 */
  double *prod;           /* cap * n * n: the computed products, row-major */
  double *err_inf;        /* cap: rigorous bound on ||exact - computed||_inf */
  double *nhat_inf;       /* cap: ||computed product||_inf (floating point) */
  double *nf_up;          /* cap: rigorous bound on ||computed product||_F */
  double *cap2;           /* cap: min(sqrt(||P^||_1 ||P^||_inf), ||P^||_F) >=
                             ||P^||_2 >= rho(P^) (floating point) */
  double *err_2;          /* cap: rigorous bound on ||exact - computed||_2 */
  double *qabs;           /* cap * n * n: products of |Y_i| along the word,
                             for the componentwise error bound (ws_push) */
  int *qvalid;            /* cap: 1 if that level of qabs is formed */
  double *bnd;            /* cap: the branch and bound's value of the prefix */
  double *a;              /* n * n: scratch copy for LAPACK (destroyed) */
  double *wr, *wi, *sv;   /* n each: eigenvalues and singular values */
  double *sb;             /* n: dgesvd's superdiagonal scratch, column sums */
  double *ynorm;          /* m: rigorous upper bounds of ||Y_i||_inf (of the
                             exact matrices the stored Y_i approximate) */
  double *delta;          /* m: rigorous bound on ||exact - stored Y_i||_inf:
                             0 for the inputs, rounding of the scaled copies */
  double *zbuf;           /* m * n * n: the diagonally scaled copies */
  const double **zptr;    /* m: pointers into zbuf */
  double *d;              /* 2 n: a candidate weighting and the sum of the
                             rotations' candidates (choose_scaling) */
  double *vl;             /* n * n: dgeev's eigenvectors */
  double *v, *t2;         /* n * n each: the 2-norm certificate's V and A V */
  double *y2, *yf;        /* m each: rigorous ||Y_i + Delta||_2 and ||Y_i||_F */
  double *ebuf;           /* m * n * n: the ellipsoidal copies L^T Y_i L^{-T}
                             (ss_jsr_ellipsoid.h), NULL until fitted */
  const double **eptr;    /* m: pointers into ebuf */
  double *edelta;         /* m: rigorous ||exact - stored||_inf of those */
  int ecw;                /* 1 if their entries are within 3u (componentwise) */
  int cw_ok;              /* 1 if the active copies are within 3u of the exact
                             matrices entrywise (ws_err_componentwise) */
  double gam;             /* gamma_n = n u / (1 - n u), u the unit roundoff */
  double tiny;            /* n^2 times the smallest subnormal: the absolute
                             rounding error of a row sum of a product
                             through underflow */
  double lower;           /* best rho(Y_w)^{1/|w|} found so far (floating point) */
  int lower_len;          /* its word's length */
  int *lower_word;        /* cap: its word */
  size_t nodes;           /* products formed */
  ss_status st;           /* first LAPACK failure, SS_OK if none */
} jsr_ws;

static const double U = DBL_EPSILON / 2;

/* AUTO tries the ellipsoidal norm up to this order (the tet/oct face is 30,
 * its edges 3..10 up to 50; the fit costs O(m n^3) per L-BFGS step). */
enum { ELL_AUTO_MAX_N = 64 };

/* The invariant polytope's vertex cap inside ss_jsr_compute (memory about
 * (12 m + 8 n) bytes per vertex plus GLPK's 2 n nonzeros per vertex). */
enum { POLY_CAP = 20000 };

/* x rounded away from 0 by a few units: covers the rounding of the handful of
 * floating-point operations on nonnegative numbers that produced x. */
static double up(double x) {
  return x * (1 + 8 * U);
}

/* A rigorous upper bound of x^{1/k} for x >= 0 from pow: glibc's pow is
 * within one ulp, and 1/k rounded perturbs the exponent by at most u/k, which
 * moves the result by the factor exp(u |ln x| / k). */
static double root_up(double x, int k) {
  if (x <= 0) return 0;
  double r = pow(x, 1.0 / k);
  return r * (1 + (8 + fabs(log(x))) * 2 * U);
}

static void ws_free(jsr_ws *w) {
  free(w->word);
  free(w->prod);
  free(w->err_inf);
  free(w->nhat_inf);
  free(w->bnd);
  free(w->a);
  free(w->wr);
  free(w->wi);
  free(w->sv);
  free(w->sb);
  free(w->ynorm);
  free(w->delta);
  free(w->zbuf);
  free(w->zptr);
  free(w->d);
  free(w->vl);
  free(w->v);
  free(w->t2);
  free(w->y2);
  free(w->yf);
  free(w->nf_up);
  free(w->cap2);
  free(w->qabs);
  free(w->qvalid);
  free(w->err_2);
  free(w->lower_word);
  free(w->ebuf);
  free(w->eptr);
  free(w->edelta);
}

/* Make the stacks hold `levels` levels; keeps their contents. */
static int ws_reserve(jsr_ws *w, int levels) {
  if (levels <= w->cap) return 1;
  const size_t L = (size_t)levels, nn = w->n * w->n;
  int *wd = realloc(w->word, L * sizeof *wd);
  if (wd) w->word = wd;
  double *p = realloc(w->prod, L * nn * sizeof *p);
  if (p) w->prod = p;
  double *e = realloc(w->err_inf, L * sizeof *e);
  if (e) w->err_inf = e;
  double *h = realloc(w->nhat_inf, L * sizeof *h);
  if (h) w->nhat_inf = h;
  double *f = realloc(w->nf_up, L * sizeof *f);
  if (f) w->nf_up = f;
  double *c2 = realloc(w->cap2, L * sizeof *c2);
  if (c2) w->cap2 = c2;
  double *e2 = realloc(w->err_2, L * sizeof *e2);
  if (e2) w->err_2 = e2;
  double *qa = realloc(w->qabs, L * nn * sizeof *qa);
  if (qa) w->qabs = qa;
  int *qv = realloc(w->qvalid, L * sizeof *qv);
  if (qv) w->qvalid = qv;
  double *b = realloc(w->bnd, L * sizeof *b);
  if (b) w->bnd = b;
  int *lw = realloc(w->lower_word, L * sizeof *lw);
  if (lw) w->lower_word = lw;
  if (!wd || !p || !e || !h || !f || !c2 || !e2 || !qa || !qv || !b || !lw) return 0;
  w->cap = levels;
  return 1;
}

/* Maximum absolute row sum of the n x n row-major matrix a (floating point). */
static double norm_inf(const double *a, size_t n) {
  double mx = 0;
  for (size_t r = 0; r < n; r++) {
    double s = 0;
    for (size_t c = 0; c < n; c++)
      s += fabs(a[r * n + c]);
    if (s > mx) mx = s;
  }
  return mx;
}

/* Maximum absolute column sum of the n x n row-major matrix a. */
static double norm_one(const double *a, size_t n, double *colsum) {
  for (size_t c = 0; c < n; c++)
    colsum[c] = 0;
  for (size_t r = 0; r < n; r++)
    for (size_t c = 0; c < n; c++)
      colsum[c] += fabs(a[r * n + c]);
  double mx = 0;
  for (size_t c = 0; c < n; c++)
    mx = fmax(mx, colsum[c]);
  return mx;
}

/* A rigorous upper bound of the Frobenius norm of the len entries a: the
 * computed sum of squares has relative error <= gamma_{len+1}. */
static double norm_f_up(const double *a, size_t len) {
  double s = 0;
  for (size_t e = 0; e < len; e++)
    s += a[e] * a[e];
  const double g = (double)(len + 2) * U / (1 - (double)(len + 2) * U);
  return up(sqrt(up(s * (1 + 2 * g))) + DBL_TRUE_MIN * (double)len);
}

/* c = a b for n x n row-major matrices, |a| instead of a when absa */
static void matmul(size_t n, const double *a, const double *b, double *c, int absa) {
  for (size_t r = 0; r < n; r++) {
    double *cr = c + r * n;
    for (size_t col = 0; col < n; col++)
      cr[col] = 0;
    for (size_t t = 0; t < n; t++) {
      const double art = absa ? fabs(a[r * n + t]) : a[r * n + t];
      if (art == 0) continue;
      const double *bt = b + t * n;
      for (size_t col = 0; col < n; col++)
        cr[col] += art * bt[col];
    }
  }
}

/* The componentwise error bound at level k (qabs formed up to k).  With
 * M_k = |Y_{w_k}| ... |Y_{w_1}| (exact) and g = gamma_n + 4u (the product's
 * rounding and the scaled copies' 3u),
 *   |E_k| <= (1 + g) |Y| |E_{k-1}| + g M_k  ==>  |E_k| <= ((1 + g)^k - 1) M_k
 * by induction, and the computed qabs (nonnegative sums) is at least
 * M_k (1 - gamma_n)^{k-1}.  Unlike the normwise recursion this does not grow
 * like prod ||Y_i|| when that is much larger than the products' norms. */
static void ws_err_componentwise(jsr_ws *w, int k) {
  const size_t n = w->n, nn = n * n;
  const double K1 = (double)(k + 1), g = w->gam + 4 * U;
  if (K1 * g >= 0.05 || !w->cw_ok) return;
  const double c = up(K1 * g * (1 + 2 * K1 * g) * (1 + 2 * K1 * w->gam));
  const double *q = w->qabs + (size_t)k * nn;
  const double ei = up(c * up(norm_inf(q, n) * (1 + 2 * w->gam))) + K1 * w->tiny;
  const double e2 = up(c * norm_f_up(q, nn)) + K1 * w->tiny;
  w->err_inf[k] = fmin(w->err_inf[k], ei);
  w->err_2[k] = fmin(w->err_2[k], e2);
}

/* Form the product at level k: Y_i, or Y_i times level k - 1, with its
 * rigorous error bound.  With Y the stored matrix, Y + Delta the exact one
 * (||Delta||_inf <= delta), fl(Y P^) = Y P^ + F, |F| <= gamma_n |Y| |P^|
 * (Higham, Accuracy and Stability, 3.5), so
 *   E_k = P_k - P^_k = (Y + Delta) E_{k-1} + Delta P^_{k-1} - F,
 *   ||E_k||_inf <= ||Y + Delta|| e_{k-1} + (delta + gamma_n ||Y||) ||P^_{k-1}||,
 * plus w->tiny for underflow, where the relative bound on F does not hold. */
static void ws_push(jsr_ws *w, int k, size_t i) {
  const size_t n = w->n, nn = n * n;
  double *p = w->prod + (size_t)k * nn;
  const double *y = w->Y[i];
  w->word[k] = (int)i;
  w->nodes++;
  if (k == 0) {
    memcpy(p, y, nn * sizeof *p);
    w->err_inf[0] = w->delta[i];
    w->err_2[0] = up(w->delta[i] * sqrt((double)n));
    w->qvalid[0] = 0;
  } else {
    matmul(n, y, p - nn, p, 0);
    w->err_inf[k] =
        up(up(up(w->ynorm[i] * w->err_inf[k - 1]) +
              up(up(w->delta[i] + w->gam * w->ynorm[i]) * w->nhat_inf[k - 1])) +
           w->tiny);
    /* the same in the 2-norm: ||Delta||_2 <= sqrt(n) delta, ||F||_2 <=
     * ||F||_F <= gamma_n ||Y||_F ||P^||_F */
    w->err_2[k] = up(
        up(up(w->y2[i] * w->err_2[k - 1]) +
           up(up(w->delta[i] * sqrt((double)n) + w->gam * w->yf[i]) * w->nf_up[k - 1])) +
        w->tiny);
  }
  w->nhat_inf[k] = norm_inf(p, n);
  w->nf_up[k] = norm_f_up(p, nn);
  w->cap2[k] = fmin(sqrt(norm_one(p, n, w->sb) * w->nhat_inf[k]), w->nf_up[k]);
  /* the normwise bound grows like prod ||Y_i||; where it starts to matter
   * (1e-12 of the norm) the products of |Y_i| are formed along the word, and
   * kept for the descendants, for the componentwise bound */
  if (k == 0) return;
  w->qvalid[k] = 0;
  if (!w->cw_ok) return; /* the copies' error is not componentwise: no use */
  if (!w->qvalid[k - 1]) {
    if (!(w->err_inf[k] > 1e-12 * w->nhat_inf[k])) return;
    for (int j = 0; j < k; j++) {
      double *qj = w->qabs + (size_t)j * nn;
      const double *yj = w->Y[w->word[j]];
      if (j == 0)
        for (size_t e = 0; e < nn; e++)
          qj[e] = fabs(yj[e]);
      else
        matmul(n, yj, qj - nn, qj, 1);
      w->qvalid[j] = 1;
    }
  }
  matmul(n, y, w->qabs + (size_t)(k - 1) * nn, w->qabs + (size_t)k * nn, 1);
  w->qvalid[k] = 1;
  ws_err_componentwise(w, k);
}

/* A rigorous upper bound of ||exact product at level k||_inf: the computed
 * norm (a sum of n nonnegative terms, relative error <= gamma_n) plus the
 * product's error bound. */
static double ws_norm_inf_up(const jsr_ws *w, int k) {
  return up(up(w->nhat_inf[k] * (1 + 2 * w->gam)) + w->err_inf[k]);
}

/* A rigorous upper bound of ||exact product at level k||_2.  With V the
 * (approximately orthogonal) right singular vectors of the computed A = P^
 * from LAPACK, x = V y gives ||A x|| / ||x|| <= ||A V||_2 / sigma_min(V), and
 *   ||A V||_2 <= ||W||_2 + gamma_n ||A||_F ||V||_F,  W = fl(A V),
 *   ||W||_2^2 = lambda_max(W^T W) <= Gershgorin(M) + gamma_n ||W||_F^2,
 *       M = fl(W^T W) made symmetric (its off-diagonal is O(u) ||A||^2),
 *   sigma_min(V)^2 >= 1 - ||V^T V - I||_2 >= 1 - (||fl(V^T V) - I||_F +
 *       gamma_n ||V||_F^2),
 * all rounded upwards (Higham 3.5 for each product); then the product's
 * error bound err_2 is added.  INFINITY if LAPACK fails or V is far from
 * orthogonal (never happens with a converged SVD). */
static double ws_norm_2_up(jsr_ws *w, int k) {
  const size_t n = w->n, nn = n * n;
  const double *A = w->prod + (size_t)k * nn;
  if (!isfinite(w->nhat_inf[k])) return INFINITY;
  double sv2;
  if (n == 1) {
    sv2 = fabs(A[0]);
  } else {
    memcpy(w->a, A, nn * sizeof *w->a);
    /* the buffer read column-major is A^T = U' S V'^T, so A's right
     * singular vectors are the columns of U': V[r][c] = u'[c n + r] */
    if (LAPACKE_dgesvd(LAPACK_COL_MAJOR, 'A', 'N', (lapack_int)n, (lapack_int)n, w->a,
                       (lapack_int)n, w->sv, w->vl, (lapack_int)n, NULL, 1, w->sb) != 0)
      return INFINITY;
    for (size_t r = 0; r < n; r++)
      for (size_t c = 0; c < n; c++)
        w->v[r * n + c] = w->vl[c * n + r];
    double *W = w->t2;
    for (size_t r = 0; r < n; r++)
      for (size_t c = 0; c < n; c++) {
        double acc = 0;
        for (size_t t = 0; t < n; t++)
          acc += A[r * n + t] * w->v[t * n + c];
        W[r * n + c] = acc;
      }
    const double vf = norm_f_up(w->v, nn), wf = norm_f_up(W, nn), af = w->nf_up[k];
    double gersh = 0, gi = 0;
    for (size_t i = 0; i < n; i++) {
      double row = 0;
      for (size_t j = 0; j < n; j++) {
        double mij = 0, gij = 0;
        const size_t a = i < j ? i : j, b = i < j ? j : i; /* symmetric order */
        for (size_t r = 0; r < n; r++) {
          mij += W[r * n + a] * W[r * n + b];
          gij += w->v[r * n + a] * w->v[r * n + b];
        }
        row += fabs(mij);
        if (i == j) gij -= 1; /* exact: gij is near 1 (Sterbenz) */
        gi += gij * gij;
      }
      gersh = fmax(gersh, row);
    }
    const double g = w->gam, gn2 = (double)(nn + 2) * U / (1 - (double)(nn + 2) * U);
    gersh = up(gersh * (1 + 2 * g));
    const double eps_v =
        up(up(sqrt(up(gi * (1 + 2 * gn2)))) + up(g * up(vf * vf))) + 4 * w->tiny;
    if (!(eps_v < 0.5)) return INFINITY;
    const double w2 = up(sqrt(up(gersh + up(g * up(wf * wf)) + w->tiny)));
    const double av = up(w2 + up(g * up(af * vf)) + w->tiny);
    const double lo = sqrt(1 - eps_v) * (1 - 4 * U); /* rounded down */
    sv2 = up(av / lo);
  }
  return up(sv2 + w->err_2[k]);
}

/* Largest singular value of the product at level k (LAPACK, floating point).
 * The row-major buffer read as column-major is the transpose, which has the
 * same singular values. */
static double ws_norm_2(jsr_ws *w, int k) {
  const size_t n = w->n, nn = n * n;
  if (!isfinite(w->nhat_inf[k])) return INFINITY; /* overflow */
  memcpy(w->a, w->prod + (size_t)k * nn, nn * sizeof *w->a);
  if (n == 1) return fabs(w->a[0]);
  lapack_int info =
      LAPACKE_dgesvd(LAPACK_COL_MAJOR, 'N', 'N', (lapack_int)n, (lapack_int)n, w->a,
                     (lapack_int)n, w->sv, NULL, 1, NULL, 1, w->sb);
  if (info != 0) {
    if (w->st == SS_OK) w->st = SS_ENUMERIC;
    return INFINITY;
  }
  return w->sv[0];
}

/* Spectral radius of the product at level k (LAPACK dgeev, floating point;
 * the transpose has the same eigenvalues). */
static double ws_specrad(jsr_ws *w, int k) {
  const size_t n = w->n, nn = n * n;
  memcpy(w->a, w->prod + (size_t)k * nn, nn * sizeof *w->a);
  if (n == 1) return fabs(w->a[0]);
  lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', (lapack_int)n, w->a,
                                  (lapack_int)n, w->wr, w->wi, NULL, 1, NULL, 1);
  if (info != 0) {
    if (w->st == SS_OK) w->st = SS_ENUMERIC;
    return 0;
  }
  double r = 0;
  for (size_t j = 0; j < n; j++)
    r = fmax(r, hypot(w->wr[j], w->wi[j]));
  return r;
}

/* 1 if the word w[0..len-1] is a Lyndon word (strictly smaller than all its
 * proper rotations; Duval's test).  Every word is a rotation of a power of a
 * Lyndon word, and rho(Y_w)^{1/|w|} is the same for rotations and powers,
 * so the lower bound needs the eigenvalues of Lyndon words only: about
 * 1/len of all words. */
static int is_lyndon(const int *w, int len) {
  int i = 0, j = 1;
  while (j < len && w[i] <= w[j]) {
    i = w[i] < w[j] ? 0 : i + 1;
    j++;
  }
  return i == 0 && j == len;
}

/* Offer the word at levels 0..k to the lower bound.  rho(P) <= ||P||_inf, so
 * the eigenvalue computation is skipped when the norm cannot beat the bound,
 * and for words that are not Lyndon words (is_lyndon). */
static void ws_offer_lower(jsr_ws *w, int k) {
  const double lim = pow(w->lower, (double)(k + 1));
  if (fmin(w->nhat_inf[k], w->cap2[k]) * (1 + 1e-12) <= lim || !isfinite(w->nhat_inf[k]))
    return;
  if (!is_lyndon(w->word, k + 1)) return;
  const double r = ws_specrad(w, k);
  if (r <= lim) return;
  const double v = pow(r, 1.0 / (k + 1));
  if (v > w->lower) {
    w->lower = v;
    w->lower_len = k + 1;
    memcpy(w->lower_word, w->word, (size_t)(k + 1) * sizeof *w->word);
  }
}

/* Use the exact similarity D^{-1} Y_i D, D = diag(d), for the words formed
 * from now on (d = NULL: the inputs; Y = w->eptr: the ellipsoidal copies,
 * with the bounds of their enclosure).  The scaled entries y_rc (d_c / d_r)
 * are rounded twice, so the stored copy differs from the exact one by at
 * most 2.0001 u |z| entrywise; delta bounds that in the inf-norm. */
static void ws_scale(jsr_ws *w, const double *const *Y, const double *d) {
  const size_t n = w->n, nn = n * n;
  w->cw_ok = 1;
  for (size_t i = 0; i < w->m; i++) {
    if (w->eptr && Y == w->eptr) { /* the ellipsoidal copies: as enclosed */
      w->zptr[i] = Y[i];
      w->delta[i] = w->edelta[i];
      w->cw_ok = w->ecw;
    } else if (!d) {
      w->zptr[i] = Y[i];
      w->delta[i] = 0;
    } else {
      double *z = w->zbuf + i * nn;
      for (size_t r = 0; r < n; r++)
        for (size_t c = 0; c < n; c++)
          z[r * n + c] = Y[i][r * n + c] * (d[c] / d[r]);
      w->zptr[i] = z;
      w->delta[i] = up(3 * U * up(norm_inf(z, n) * (1 + 2 * w->gam))) + w->tiny;
    }
    w->ynorm[i] = up(up(norm_inf(w->zptr[i], n) * (1 + 2 * w->gam)) + w->delta[i]);
    /* ||Y||_2 <= ||Y||_F; the 2-norm error recursion needs only a bound */
    w->yf[i] = norm_f_up(w->zptr[i], nn);
    w->y2[i] = up(w->yf[i] + up(w->delta[i] * sqrt((double)n)));
  }
  w->Y = (const double *const *)w->zptr;
}

/* Step the depth-first walk to the next sibling at level *k, backtracking
 * to lower levels when a level's m letters are used up; 0 when the walk is
 * over.  A caller descends by `w->word[++k] = -1`. */
static int ws_next(jsr_ws *w, int *k) {
  while (*k >= 0 && ++w->word[*k] >= (int)w->m)
    (*k)--;
  return *k >= 0;
}

/* Brute force over all m^K words of length <= K: rho_inf, rho_2 (floating
 * point), rigorous inf-norm profile rho_cert, and the lower bound. */
static void brute_force(jsr_ws *w, int K, double *rho_inf, double *rho_2,
                        double *rho_cert) {
  for (int k = 0; k < K; k++)
    rho_inf[k] = rho_2[k] = rho_cert[k] = 0;
  int k = 0;
  w->word[0] = -1;
  while (ws_next(w, &k)) {
    ws_push(w, k, (size_t)w->word[k]);
    const double p = 1.0 / (k + 1);
    rho_inf[k] = fmax(rho_inf[k], pow(w->nhat_inf[k], p));
    rho_cert[k] = fmax(rho_cert[k], ws_norm_inf_up(w, k));
    /* ||P||_2 <= min(sqrt(||P||_1 ||P||_inf), ||P||_F) skips the SVD when
     * it cannot raise the maximum */
    if (w->cap2[k] * (1 + 1e-12) > pow(rho_2[k], (double)(k + 1)))
      rho_2[k] = fmax(rho_2[k], pow(ws_norm_2(w, k), p));
    ws_offer_lower(w, k);
    if (k + 1 < K) w->word[++k] = -1;
  }
  for (k = 0; k < K; k++)
    rho_cert[k] = root_up(rho_cert[k], k + 1);
}

/* min over k <= s of the rigorous max_{|w| = k} ||Y_w||_inf^{1/k} for the
 * current (scaled) matrices: an upper bound on rho(Y), used to rank the
 * scalings. */
static double scaling_score(jsr_ws *w, int s) {
  double best = INFINITY, mx[64] = {0};
  int k = 0;
  w->word[0] = -1;
  while (ws_next(w, &k)) {
    ws_push(w, k, (size_t)w->word[k]);
    mx[k] = fmax(mx[k], ws_norm_inf_up(w, k));
    if (k + 1 < s) w->word[++k] = -1;
  }
  for (k = 0; k < s; k++)
    best = fmin(best, root_up(mx[k], k + 1));
  return best;
}

/* d = |v| for v the eigenvector of the largest eigenvalue (in modulus) of the
 * product of the lower bound's word rotated to start at letter r, floored at
 * 1e-6 of its maximum; the inputs must be active (ws_scale(w, Y, NULL)).
 * Returns 0 if LAPACK fails.  The eigenvectors of P^T that dgeev returns as
 * left vectors for the row-major buffer are conjugates of P's right ones. */
static int perron_vector(jsr_ws *w, int r, double *d) {
  const int len = w->lower_len;
  const size_t n = w->n, nn = n * n;
  int *rot = w->word + len; /* scratch: the stack has room for 2 len */
  for (int k = 0; k < len; k++)
    rot[k] = w->lower_word[(r + k) % len];
  for (int k = 0; k < len; k++)
    ws_push(w, k, (size_t)rot[k]);
  memcpy(w->a, w->prod + (size_t)(len - 1) * nn, nn * sizeof *w->a);
  if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'V', 'N', (lapack_int)n, w->a, (lapack_int)n, w->wr,
                    w->wi, w->vl, (lapack_int)n, NULL, 1) != 0)
    return 0;
  size_t j = 0;
  for (size_t t = 1; t < n; t++)
    if (hypot(w->wr[t], w->wi[t]) > hypot(w->wr[j], w->wi[j])) j = t;
  if (w->wi[j] < 0) j--; /* the pair's second: its vector is re - i im */
  double mx = 0;
  for (size_t t = 0; t < n; t++) {
    const double re = w->vl[j * n + t], im = w->wi[j] != 0 ? w->vl[(j + 1) * n + t] : 0;
    d[t] = hypot(re, im);
    mx = fmax(mx, d[t]);
  }
  if (!(mx > 0) || !isfinite(mx)) return 0;
  for (size_t t = 0; t < n; t++)
    d[t] = fmax(d[t] / mx, 1e-6);
  return 1;
}

/* Choose the diagonal scaling of the inf-norm for the branch and bound: the
 * identity, or |eigenvector| of the products of the lower bound's word and
 * its rotations (for a nonnegative product P with Perron vector v,
 * ||D^{-1} P D||_inf = rho(P) with D = diag(v)), or their sum; the one with
 * the smallest scaling_score wins and stays active (ws_scale).  Any choice
 * is an exact similarity, so every choice gives valid bounds. */
static void choose_scaling(jsr_ws *w, const double *const *Y, int K, double *best_d,
                           int *have) {
  int s = 1;
  double cnt = (double)w->m;
  while (s < K && s < 3 && cnt * (double)w->m <= 4096)
    s++, cnt *= (double)w->m;
  ws_scale(w, Y, NULL);
  double best = scaling_score(w, s);
  *have = 0;
  const int len = w->lower_len, nrot = len < 8 ? len : 8;
  double *sum = w->d + w->n;
  for (size_t t = 0; t < w->n; t++)
    sum[t] = 0;
  for (int r = 0; r <= nrot && len > 0; r++) {
    ws_scale(w, Y, NULL);
    if (r < nrot) {
      if (!perron_vector(w, r, w->d)) continue;
      for (size_t t = 0; t < w->n; t++)
        sum[t] += w->d[t];
    } else {
      memcpy(w->d, sum, w->n * sizeof *w->d);
    }
    ws_scale(w, Y, w->d);
    const double sc = scaling_score(w, s);
    if (sc < best) {
      best = sc;
      memcpy(best_d, w->d, w->n * sizeof *best_d);
      *have = 1;
    }
  }
  ws_scale(w, Y, *have ? best_d : NULL);
}

/* Make candidate c of the branch and bound active (ss_jsr_compute: 0 the
 * inputs, 1 the weighted copies, 2 the inputs for the 2-norm, 3 the
 * ellipsoidal copies). */
static void ws_select(jsr_ws *w, const double *const *Y, int c, const double *best_d) {
  if (c == 3)
    ws_scale(w, (const double *const *)w->eptr, NULL);
  else
    ws_scale(w, Y, c == 1 ? best_d : NULL);
}

/* Fit the ellipsoidal norm to the inputs Y and enclose the similar copies
 * into w->ebuf (ss_jsr_ellipsoid.h).  Returns 1 if they are ready; 0 if the
 * fit or the enclosure failed (*st = SS_ENOMEM if memory ran out). */
static int ws_ellipsoid(jsr_ws *w, const double *const *Y, int words, double deadline,
                        ss_status *st) {
  const size_t m = w->m, n = w->n;
  double *L = malloc(n * n * sizeof *L);
  w->ebuf = malloc(m * n * n * sizeof *w->ebuf);
  w->eptr = malloc(m * sizeof *w->eptr);
  w->edelta = malloc(m * sizeof *w->edelta);
  int ok = 0;
  *st = SS_OK;
  if (!L || !w->ebuf || !w->eptr || !w->edelta) {
    *st = SS_ENOMEM;
    goto done;
  }
  *st = ss_jsr_ellipsoid_fit_words(m, n, Y, words, deadline, L);
  if (*st != SS_OK) goto done;
  ok = ss_jsr_ellipsoid_similar(m, n, Y, L, w->ebuf, w->edelta, &w->ecw);
  for (size_t i = 0; i < m; i++)
    w->eptr[i] = w->ebuf + i * n * n;
done:
  free(L);
  if (!ok) { /* not usable: ws_scale must not take it for the copies */
    free(w->eptr);
    w->eptr = NULL;
  }
  return ok;
}

/* One pass of the branch and bound to depth L.  The bound of a word w is
 *   b(w) = min over the prefixes u of w of N(u)^{1/|u|}
 * with N(u) the norm of Y_u (rigorous for the inf-norm).  The words not
 * extended (pruned, or of length L) form a complete set: every infinite word
 * has a prefix among them, so every long product factors into products of
 * these words and a bounded remainder, and submultiplicativity gives
 *   rho(Y) <= max over the leaves w of N(u_w)^{1/|u_w|},
 * u_w the prefix of w attaining b(w); that is, rho(Y) <= max_leaves b(w).
 * A word with b(w) <= target is not extended: its subtree can only lower its
 * bound, and it already cannot lift the maximum above the target.
 * Returns 1 and *upper if the pass completed, 0 if a limit stopped it. */
static int bnb_pass(jsr_ws *w, int L, ss_jsr_norm norm, double gap, size_t max_nodes,
                    double deadline, double *upper) {
  double mx = 0;
  int k = 0;
  w->word[0] = -1;
  while (ws_next(w, &k)) {
    if ((max_nodes && w->nodes >= max_nodes) ||
        (deadline > 0 && ss_clock_wall() > deadline))
      return 0;
    ws_push(w, k, (size_t)w->word[k]);
    ws_offer_lower(w, k);
    double b;
    if (norm == SS_JSR_NORM_INF) {
      b = root_up(ws_norm_inf_up(w, k), k + 1);
      if (k > 0) b = fmin(b, w->bnd[k - 1]);
    } else {
      /* the certified 2-norm costs an SVD with vectors and three products:
       * formed only where the floating-point value would lower the bound */
      b = k > 0 ? w->bnd[k - 1] : (double)INFINITY;
      if (pow(ws_norm_2(w, k), 1.0 / (k + 1)) * (1 - 1e-12) < b)
        b = fmin(b, root_up(ws_norm_2_up(w, k), k + 1));
    }
    w->bnd[k] = b;
    const double target = w->lower * (1 + gap);
    if (b <= target || k + 1 == L) {
      mx = fmax(mx, b);
      continue;
    }
    w->word[++k] = -1;
  }
  *upper = mx;
  return 1;
}

/* The invariant polytope (ss_jsr_polytope.h) from the current lower bound's
 * word, eps = gap / 2 (so that a closed polytope meets the gap), until the
 * wall-clock time `until` (0: no limit but the vertex cap).  Fills
 * out->polytope, poly_vertices, poly_upper.  Only running out of memory is
 * an error; anything else the method cannot do leaves the gap to the branch
 * and bound. */
static ss_status try_polytope(jsr_ws *w, const double *const *Y, double gap, double until,
                              ss_jsr_result *out, ss_error *err) {
  out->polytope = SS_POLY_LP;
  out->poly_upper = INFINITY;
  if (w->lower_len < 1 || w->n > 4096) return SS_OK;
  ss_jsr_polytope_opts po = ss_jsr_polytope_defaults();
  po.eps = gap > 0 ? fmin(gap / 2, 0.25) : 1e-9;
  po.max_vertices = POLY_CAP;
  po.max_seconds = until > 0 ? fmax(until - ss_clock_wall(), 1e-3) : 0;
  ss_jsr_polytope_result pr;
  ss_error e2 = {0};
  const ss_status st =
      ss_jsr_polytope(w->m, w->n, Y, w->lower_word, w->lower_len, &po, &pr, &e2);
  if (st == SS_ENOMEM) return ss_error_nomem(err, "jsr invariant polytope");
  if (st != SS_OK) return SS_OK;
  out->polytope = (int)pr.stop;
  out->poly_vertices = pr.vertices;
  if (pr.stop == SS_POLY_CLOSED) out->poly_upper = pr.upper;
  return SS_OK;
}

ss_status ss_jsr_compute(size_t m, size_t n, const double *const *Y, const ss_jsr_opts *o,
                         ss_jsr_result *out, ss_error *err) {
  const double t0 = ss_clock_wall();
  ss_jsr_opts d = ss_jsr_defaults();
  if (!o) o = &d;
  if (!out) return ss_error_set(err, SS_EINPUT, "jsr: no result given");
  memset(out, 0, sizeof *out);
  out->polytope = -1;
  out->poly_upper = INFINITY;
  if (m < 1) return ss_error_set(err, SS_EINPUT, "jsr: no matrices (m = 0)");
  if (n < 1) return ss_error_set(err, SS_EINPUT, "jsr: matrices of order n = 0");
  if (!Y) return ss_error_set(err, SS_EINPUT, "jsr: no matrices given");
  if (n > 100000 || m > 1000000)
    return ss_error_set(err, SS_EINPUT, "jsr: %zu matrices of order %zu: too large", m,
                        n);
  if (o->depth < 1 || o->depth > 64)
    return ss_error_set(err, SS_EINPUT, "jsr: depth %d not in 1..64", o->depth);
  {
    /* brute force forms every word of length <= depth: refuse what could
     * not finish rather than run for years */
    double words = 0, p = 1;
    for (int k = 1; k <= o->depth && words <= 1e10; k++)
      words += (p *= (double)m);
    if (words > 1e10)
      return ss_error_set(err, SS_EINPUT,
                          "jsr: depth %d with %zu matrices means more than 10^10 "
                          "products of brute force; lower the depth",
                          o->depth, m);
  }
  if (!(o->gap >= 0) || !isfinite(o->gap))
    return ss_error_set(err, SS_EINPUT, "jsr: gap %g is not a finite number >= 0",
                        o->gap);
  if (o->norm != SS_JSR_NORM_INF && o->norm != SS_JSR_NORM_2 &&
      o->norm != SS_JSR_NORM_AUTO && o->norm != SS_JSR_NORM_ELLIPSOID &&
      o->norm != SS_JSR_NORM_POLYTOPE)
    return ss_error_set(err, SS_EINPUT, "jsr: unknown norm %d", (int)o->norm);
  if (isnan(o->max_seconds))
    return ss_error_set(err, SS_EINPUT, "jsr: max_seconds is NaN");
  if (o->max_depth < 0)
    return ss_error_set(err, SS_EINPUT, "jsr: max_depth %d < 0", o->max_depth);
  if (o->fit_words < 1 || o->fit_words > 5)
    return ss_error_set(err, SS_EINPUT, "jsr: fit_words %d not in 1..5", o->fit_words);
  {
    double prods = 1; /* the ellipsoid's fit holds all m^K products */
    for (int k = 0; k < o->fit_words; k++)
      prods *= (double)m;
    if (prods > 4096)
      return ss_error_set(err, SS_EINPUT,
                          "jsr: fit_words %d with %zu matrices means %.0f products "
                          "(at most 4096); lower fit_words",
                          o->fit_words, m, prods);
  }
  for (size_t i = 0; i < m; i++) {
    if (!Y[i]) return ss_error_set(err, SS_EINPUT, "jsr: matrix %zu is missing", i + 1);
    for (size_t e = 0; e < n * n; e++)
      if (!isfinite(Y[i][e]))
        return ss_error_set(err, SS_EINPUT,
                            "jsr: matrix %zu, entry (%zu, %zu) is not finite (%g)", i + 1,
                            e / n + 1, e % n + 1, Y[i][e]);
  }
  if (n * U * 4 >= 1) return ss_error_set(err, SS_EINPUT, "jsr: order %zu too large", n);

  ss_status st = SS_OK;
  const int K = o->depth;
  /* POLYTOPE runs the polytope first, then the branch and bound as AUTO */
  const int auto_ = o->norm == SS_JSR_NORM_AUTO || o->norm == SS_JSR_NORM_POLYTOPE;
  double *rho_cert = NULL, *best_d = NULL, *ybuf = NULL;
  const double **yn = NULL;
  jsr_ws w;
  memset(&w, 0, sizeof w);
  w.m = m, w.n = n, w.Y = Y;
  w.gam = (double)n * U / (1 - (double)n * U);
  w.tiny = (double)n * (double)n * DBL_TRUE_MIN;
  w.a = malloc(n * n * sizeof *w.a);
  w.wr = malloc(n * sizeof *w.wr);
  w.wi = malloc(n * sizeof *w.wi);
  w.sv = malloc(n * sizeof *w.sv);
  w.sb = malloc(n * sizeof *w.sb);
  w.ynorm = malloc(m * sizeof *w.ynorm);
  w.delta = malloc(m * sizeof *w.delta);
  w.zbuf = malloc(m * n * n * sizeof *w.zbuf);
  w.zptr = malloc(m * sizeof *w.zptr);
  w.d = malloc(2 * n * sizeof *w.d);
  w.vl = malloc(n * n * sizeof *w.vl);
  w.v = malloc(n * n * sizeof *w.v);
  w.t2 = malloc(n * n * sizeof *w.t2);
  w.y2 = malloc(m * sizeof *w.y2);
  w.yf = malloc(m * sizeof *w.yf);
  best_d = malloc(n * sizeof *best_d);
  out->rho_inf = calloc((size_t)K, sizeof *out->rho_inf);
  out->rho_2 = calloc((size_t)K, sizeof *out->rho_2);
  rho_cert = calloc((size_t)K, sizeof *rho_cert);
  if (!w.a || !w.wr || !w.wi || !w.sv || !w.sb || !w.ynorm || !w.delta || !w.zbuf ||
      !w.zptr || !w.d || !w.vl || !w.v || !w.t2 || !w.y2 || !w.yf || !best_d ||
      !out->rho_inf || !out->rho_2 || !rho_cert || !ws_reserve(&w, K)) {
    st = ss_error_nomem(err, "jsr workspace");
    goto done;
  }
  /* JSR(2^e Y) = 2^e JSR(Y): the inputs are scaled by the power of two that
   * brings the largest norm near 1 (exactly, or not at all), so that long
   * products neither overflow nor underflow for inputs of any size; the
   * results are scaled back exactly at the end */
  int ex = 0;
  {
    double mx = 0;
    for (size_t i = 0; i < m; i++)
      mx = fmax(mx, norm_inf(Y[i], n));
    if (mx > 0 && isfinite(mx)) ex = -ilogb(mx);
    if (ex != 0) {
      ybuf = malloc(m * n * n * sizeof *ybuf);
      yn = malloc(m * sizeof *yn);
      if (!ybuf || !yn) {
        st = ss_error_nomem(err, "jsr scaled inputs");
        goto done;
      }
      for (size_t i = 0; i < m && ex != 0; i++) {
        for (size_t e = 0; e < n * n && ex != 0; e++) {
          const double z = ldexp(Y[i][e], ex);
          if (ldexp(z, -ex) != Y[i][e]) ex = 0; /* underflow: not exact */
          ybuf[i * n * n + e] = z;
        }
        yn[i] = ybuf + i * n * n;
      }
    }
    if (ex != 0) Y = (const double *const *)yn;
  }
  w.Y = Y;
  ws_scale(&w, Y, NULL);
  out->depth = K;

  brute_force(&w, K, out->rho_inf, out->rho_2, rho_cert);
  if (w.st != SS_OK) goto lapack_failed;
  /* min_k rho_k bounds rho(Y); the rigorous inf-norm profile is used (the
   * branch and bound's first pass, at depth K, is at least as good in its
   * own norm: max over words of the min over prefixes <= min_k rho_k) */
  double upper = INFINITY;
  for (int k = 0; k < K; k++)
    if (rho_cert[k] < upper) upper = rho_cert[k];
  const size_t brute_nodes = w.nodes;
  /* the inf-norm branch and bound may run in a diagonally weighted inf-norm
   * (an exact similarity; the profile rho_inf stays the plain inf-norm) */
  int have = 0;
  if (o->weighted && (o->norm == SS_JSR_NORM_INF || auto_) &&
      upper > w.lower * (1 + o->gap)) {
    if (!ws_reserve(&w, 2 * w.lower_len)) {
      st = ss_error_nomem(err, "jsr scaling");
      goto done;
    }
    choose_scaling(&w, Y, K, best_d, &have);
    if (w.st != SS_OK) goto lapack_failed;
  }
  const double deadline = o->max_seconds > 0 ? t0 + o->max_seconds : 0;
  /* the ellipsoidal norm (ss_jsr_ellipsoid.h): fitted, then the similar
   * copies enclosed; AUTO tries it for orders up to ELL_AUTO_MAX_N (the fit
   * costs O(m n^3) per step), with at most a quarter of the time limit */
  int have_ell = 0;
  if ((o->norm == SS_JSR_NORM_ELLIPSOID || (auto_ && n <= ELL_AUTO_MAX_N)) &&
      upper > w.lower * (1 + o->gap)) {
    have_ell = ws_ellipsoid(&w, Y, o->fit_words,
                            deadline > 0 ? t0 + o->max_seconds / 4 : 0, &st);
    if (st == SS_ENOMEM) {
      st = ss_error_nomem(err, "jsr ellipsoidal norm");
      goto done;
    }
    st = SS_OK;
    if (!have_ell && o->norm == SS_JSR_NORM_ELLIPSOID) {
      st = ss_error_set(err, SS_ENUMERIC,
                        "jsr: the ellipsoidal norm could not be fitted or its "
                        "similarity not enclosed (ill-conditioned)");
      goto done;
    }
  }

  /* branch and bound by iterative deepening: each pass's leaves give a valid
   * bound, deeper passes refine it; recomputing the shallow levels costs a
   * factor of about m / (m - 1) at most.  The candidates: the plain
   * inf-norm, the weighted inf-norm, the 2-norm and the ellipsoidal norm
   * (the 2-norm of the similar copies), those that o->norm allows; with
   * more than one the first pass runs each and the rest keep the one with
   * the lowest bound: every candidate's bound is valid */
  enum { C_INF, C_WINF, C_2, C_ELL, NCAND };
  const ss_jsr_norm cn[NCAND] = {SS_JSR_NORM_INF, SS_JSR_NORM_INF, SS_JSR_NORM_2,
                                 SS_JSR_NORM_2};
  const int use[NCAND] = {o->norm == SS_JSR_NORM_INF || auto_, have,
                          o->norm == SS_JSR_NORM_2 || auto_, have_ell};
  int ncand = 0, active = C_INF;
  for (int c = NCAND - 1; c >= 0; c--)
    if (use[c]) ncand++, active = c;
  ws_select(&w, Y, active, best_d);
  const size_t max_nodes = o->max_nodes ? brute_nodes + o->max_nodes : 0;
  if (o->norm == SS_JSR_NORM_POLYTOPE && upper > w.lower * (1 + o->gap)) {
    const double now = ss_clock_wall();
    st = try_polytope(&w, Y, o->gap, deadline > 0 ? now + (deadline - now) / 2 : 0, out,
                      err);
    if (st != SS_OK) goto done;
    if (out->poly_upper < upper) upper = out->poly_upper;
  }
  for (int L = K; upper > w.lower * (1 + o->gap); L++) {
    if (o->max_depth && L > o->max_depth) break;
    if (!ws_reserve(&w, L)) {
      st = ss_error_nomem(err, "jsr branch and bound stack");
      goto done;
    }
    double u;
    int stop = 0;
    if (L == K && ncand > 1) {
      int best = -1;
      u = INFINITY;
      /* the ellipsoid first: usually the best, and a limit that stops the
       * pass early should not cut it off */
      static const int order[NCAND] = {C_ELL, C_WINF, C_INF, C_2};
      for (int oc = 0; oc < NCAND && !stop; oc++) {
        const int c = order[oc];
        if (!use[c]) continue;
        double uc;
        ws_select(&w, Y, c, best_d);
        if (!bnb_pass(&w, L, cn[c], o->gap, max_nodes, deadline, &uc)) {
          stop = 1;
          break;
        }
        if (w.st != SS_OK) goto lapack_failed;
        if (uc < u) u = uc, best = c;
      }
      if (best < 0) break;
      active = best;
      ws_select(&w, Y, active, best_d);
    } else if (!bnb_pass(&w, L, cn[active], o->gap, max_nodes, deadline, &u)) {
      break;
    }
    if (w.st != SS_OK) goto lapack_failed;
    out->bnb_depth = L;
    if (u < upper) upper = u;
    if (stop) break;
    /* AUTO does not try the invariant polytope: on the cases it exists
     * for (tet/oct face and edges) the polytope does not close within
     * thousands of vertices (README, "Joint spectral radius"), so its time
     * would be taken from the branch and bound; --norm polytope asks for it */
  }
  out->weighted = active == C_WINF;
  out->norm = upper >= out->poly_upper ? SS_JSR_NORM_POLYTOPE
              : active == C_ELL        ? SS_JSR_NORM_ELLIPSOID
                                       : cn[active];
  if (w.st != SS_OK) goto lapack_failed;
  out->nodes = w.nodes - brute_nodes;

  out->lower_word = malloc((size_t)(w.lower_len > 0 ? w.lower_len : 1) * sizeof(int));
  if (!out->lower_word) {
    st = ss_error_nomem(err, "jsr lower word");
    goto done;
  }
  out->lower_len = w.lower_len;
  memcpy(out->lower_word, w.lower_word, (size_t)w.lower_len * sizeof(int));
  /* the floating-point lower bound is replaced by a certified one for the
   * same word when the ball-arithmetic enclosure succeeds */
  double lower_cert = 0;
  int lower_rigorous = 0;
  if (w.lower_len == 0)
    lower_rigorous = 1; /* no product has a nonzero spectral radius: 0 */
  else
    lower_rigorous = ss_jsr_cert_lower(n, Y, w.lower_word, w.lower_len, &lower_cert);
  /* the bounds are of the scaled inputs; scaling back by 2^-ex is exact
   * unless the result is subnormal, where one rounding is undone by a step
   * outwards */
  out->lower = ldexp(lower_rigorous ? lower_cert : w.lower, -ex);
  out->upper = ldexp(upper, -ex);
  out->poly_upper = ldexp(out->poly_upper, -ex);
  if (out->poly_upper > 0 && out->poly_upper < DBL_MIN)
    out->poly_upper = nextafter(out->poly_upper, INFINITY);
  if (out->lower > 0 && out->lower < DBL_MIN) out->lower = nextafter(out->lower, 0.0);
  if (out->upper > 0 && out->upper < DBL_MIN)
    out->upper = nextafter(out->upper, INFINITY);
  for (int k = 0; k < K; k++) {
    out->rho_inf[k] = ldexp(out->rho_inf[k], -ex);
    out->rho_2[k] = ldexp(out->rho_2[k], -ex);
  }
  /* every upper bound above is rigorous (rounding carried in both norms) */
  out->certified = lower_rigorous;
  out->converged = out->upper <= out->lower * (1 + o->gap);
  out->seconds = ss_clock_wall() - t0;
  goto done;

lapack_failed:
  st = w.st == SS_ENOMEM ? ss_error_nomem(err, "jsr LAPACK scratch")
                         : ss_error_set(err, SS_ENUMERIC,
                                        "jsr: LAPACK eigenvalue or singular value "
                                        "computation did not converge");
done:
  ws_free(&w);
  free(rho_cert);
  free(best_d);
  free(ybuf);
  free(yn);
  if (st != SS_OK) ss_jsr_result_clear(out);
  return st;
}
