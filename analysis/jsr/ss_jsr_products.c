/* ss_jsr_products.c — the products along a word of the JSR's walks and their
 * norms: the workspace's stacks, the product at each level with its rigorous
 * error bound (normwise and componentwise), the certified inf- and 2-norms,
 * the floating-point 2-norm and spectral radius, and the similarity that
 * weights the inputs (ss_jsr_ws.h). */
#include <lapacke.h>
#include <stdlib.h>
#include <string.h>

#include "ss_jsr_ws.h"

/* Free the workspace's buffers. */
void ss_jsr_ws_free(ss_jsr_ws *w) {
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
int ss_jsr_ws_reserve(ss_jsr_ws *w, int levels) {
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
  return ss_jsr_up(sqrt(ss_jsr_up(s * (1 + 2 * g))) + DBL_TRUE_MIN * (double)len);
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
static void ws_err_componentwise(ss_jsr_ws *w, int k) {
  const size_t n = w->n, nn = n * n;
  const double K1 = (double)(k + 1), g = w->gam + 4 * U;
  if (K1 * g >= 0.05 || !w->cw_ok) return;
  const double c = ss_jsr_up(K1 * g * (1 + 2 * K1 * g) * (1 + 2 * K1 * w->gam));
  const double *q = w->qabs + (size_t)k * nn;
  const double ei =
      ss_jsr_up(c * ss_jsr_up(ss_dense_max_row_sum(q, n) * (1 + 2 * w->gam))) +
      K1 * w->tiny;
  const double e2 = ss_jsr_up(c * norm_f_up(q, nn)) + K1 * w->tiny;
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
void ss_jsr_ws_push(ss_jsr_ws *w, int k, size_t i) {
  const size_t n = w->n, nn = n * n;
  double *p = w->prod + (size_t)k * nn;
  const double *y = w->Y[i];
  w->word[k] = (int)i;
  w->nodes++;
  if (k == 0) {
    memcpy(p, y, nn * sizeof *p);
    w->err_inf[0] = w->delta[i];
    w->err_2[0] = ss_jsr_up(w->delta[i] * sqrt((double)n));
    w->qvalid[0] = 0;
  } else {
    matmul(n, y, p - nn, p, 0);
    w->err_inf[k] =
        ss_jsr_up(ss_jsr_up(ss_jsr_up(w->ynorm[i] * w->err_inf[k - 1]) +
                            ss_jsr_up(ss_jsr_up(w->delta[i] + w->gam * w->ynorm[i]) *
                                      w->nhat_inf[k - 1])) +
                  w->tiny);
    /* the same in the 2-norm: ||Delta||_2 <= sqrt(n) delta, ||F||_2 <=
     * ||F||_F <= gamma_n ||Y||_F ||P^||_F */
    w->err_2[k] = ss_jsr_up(
        ss_jsr_up(ss_jsr_up(w->y2[i] * w->err_2[k - 1]) +
                  ss_jsr_up(ss_jsr_up(w->delta[i] * sqrt((double)n) + w->gam * w->yf[i]) *
                            w->nf_up[k - 1])) +
        w->tiny);
  }
  w->nhat_inf[k] = ss_dense_max_row_sum(p, n);
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
double ss_jsr_ws_norm_inf_up(const ss_jsr_ws *w, int k) {
  return ss_jsr_up(ss_jsr_up(w->nhat_inf[k] * (1 + 2 * w->gam)) + w->err_inf[k]);
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
double ss_jsr_ws_norm_2_up(ss_jsr_ws *w, int k) {
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
    gersh = ss_jsr_up(gersh * (1 + 2 * g));
    const double eps_v = ss_jsr_up(ss_jsr_up(sqrt(ss_jsr_up(gi * (1 + 2 * gn2)))) +
                                   ss_jsr_up(g * ss_jsr_up(vf * vf))) +
                         4 * w->tiny;
    if (!(eps_v < 0.5)) return INFINITY;
    const double w2 =
        ss_jsr_up(sqrt(ss_jsr_up(gersh + ss_jsr_up(g * ss_jsr_up(wf * wf)) + w->tiny)));
    const double av = ss_jsr_up(w2 + ss_jsr_up(g * ss_jsr_up(af * vf)) + w->tiny);
    const double lo = sqrt(1 - eps_v) * (1 - 4 * U); /* rounded down */
    sv2 = ss_jsr_up(av / lo);
  }
  return ss_jsr_up(sv2 + w->err_2[k]);
}

/* Largest singular value of the product at level k (LAPACK, floating point).
 * The row-major buffer read as column-major is the transpose, which has the
 * same singular values. */
double ss_jsr_ws_norm_2(ss_jsr_ws *w, int k) {
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
double ss_jsr_ws_specrad(ss_jsr_ws *w, int k) {
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

/* Use the exact similarity D^{-1} Y_i D, D = diag(d), for the words formed
 * from now on (d = NULL: the inputs; Y = w->eptr: the ellipsoidal copies,
 * with the bounds of their enclosure).  The scaled entries y_rc (d_c / d_r)
 * are rounded twice, so the stored copy differs from the exact one by at
 * most 2.0001 u |z| entrywise; delta bounds that in the inf-norm. */
void ss_jsr_ws_scale(ss_jsr_ws *w, const double *const *Y, const double *d) {
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
      w->delta[i] =
          ss_jsr_up(3 * U * ss_jsr_up(ss_dense_max_row_sum(z, n) * (1 + 2 * w->gam))) +
          w->tiny;
    }
    w->ynorm[i] = ss_jsr_up(
        ss_jsr_up(ss_dense_max_row_sum(w->zptr[i], n) * (1 + 2 * w->gam)) + w->delta[i]);
    /* ||Y||_2 <= ||Y||_F; the 2-norm error recursion needs only a bound */
    w->yf[i] = norm_f_up(w->zptr[i], nn);
    w->y2[i] = ss_jsr_up(w->yf[i] + ss_jsr_up(w->delta[i] * sqrt((double)n)));
  }
  w->Y = (const double *const *)w->zptr;
}
