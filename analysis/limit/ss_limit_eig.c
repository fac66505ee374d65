/* ss_limit_eig.c — eigen-decomposition of a stationary run's matrix and its
 * powers: W^m = V diag(lambda^m) V^-1 (Stam's idea), checked for defects. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>

#include "ss_dense.h"
#include "ss_limit.h"
#include "ss_limit_impl.h"

void ss_lim_eig_free(ss_lim_eig *e) {
  if (!e) return;
  free(e->pw);
  free(e->V);
  free(e->Vinv);
  free(e->lam);
  free(e->pair);
  free(e);
}

/* The fallback for a defective W: W^(2^i), i = 0 .. SS_LIM_NPOW - 1, by repeated
 * squaring (products of averaging matrices: stable, whatever the Jordan
 * structure). */
static ss_status make_powers(const double *W, size_t K, ss_lim_eig *e, ss_error *err) {
  e->pw = malloc((SS_LIM_NPOW * K * K + 1) * sizeof *e->pw);
  if (!e->pw) return ss_error_nomem(err, "matrix powers");
  memcpy(e->pw, W, K * K * sizeof *W);
  for (int p = 1; p < SS_LIM_NPOW; p++) {
    const double *A = e->pw + (size_t)(p - 1) * K * K;
    double *B = e->pw + (size_t)p * K * K;
    memset(B, 0, K * K * sizeof *B);
    for (size_t i = 0; i < K; i++)
      for (size_t q = 0; q < K; q++) {
        double a = A[i * K + q];
        if (a == 0.0) continue;
        for (size_t j = 0; j < K; j++)
          B[i * K + j] += a * A[q * K + j];
      }
  }
  return SS_OK;
}

/* P <- A P (K x K times K x 3). */
static void matvec(const double *A, size_t K, double *P, double *tmp) {
  for (size_t i = 0; i < K; i++) {
    double acc[3] = {0, 0, 0};
    for (size_t j = 0; j < K; j++) {
      double a = A[i * K + j];
      if (a == 0.0) continue;
      for (int d = 0; d < 3; d++)
        acc[d] += a * P[j * 3 + (size_t)d];
    }
    memcpy(tmp + i * 3, acc, sizeof acc);
  }
  memcpy(P, tmp, K * 3 * sizeof *P);
}

ss_status ss_lim_eig_new(const double *W, size_t K, ss_lim_eig **out, ss_error *err) {
  ss_status st = SS_OK;
  ss_lim_eig *e = calloc(1, sizeof *e);
  double *a = malloc((K * K + 1) * sizeof *a), *wr = malloc((K + 1) * sizeof *wr);
  double *wi = malloc((K + 1) * sizeof *wi), *vr = malloc((K * K + 1) * sizeof *vr);
  lapack_int *ipiv = malloc((K + 1) * sizeof *ipiv);
  *out = NULL;
  if (e) e->why[0] = '\0';
  if (!e || !a || !wr || !wi || !vr || !ipiv) {
    st = ss_error_nomem(err, "eigen-decomposition");
    goto done;
  }
  e->K = K;
  e->one = SIZE_MAX;
  e->V = malloc((K * K + 1) * sizeof *e->V);
  e->Vinv = malloc((K * K + 1) * sizeof *e->Vinv);
  e->lam = malloc((K + 1) * sizeof *e->lam);
  e->pair = calloc(K + 1, sizeof *e->pair);
  if (!e->V || !e->Vinv || !e->lam || !e->pair) {
    st = ss_error_nomem(err, "eigen-decomposition");
    goto done;
  }
  memcpy(a, W, K * K * sizeof *a);
  lapack_int info = LAPACKE_dgeev(LAPACK_ROW_MAJOR, 'N', 'V', (lapack_int)K, a,
                                  (lapack_int)K, wr, wi, NULL, 1, vr, (lapack_int)K);
  if (info) {
    st =
        ss_error_set(err, SS_ENUMERIC, "dgeev failed (info %d) on a %zu x %zu run matrix",
                     (int)info, K, K);
    goto done;
  }
  /* V real (column-major): a real eigenvalue's eigenvector, or for a pair
   * a +- ib the real and imaginary parts x, y of x + iy (W [x y] = [x y]
   * [a b; -b a]), each column or pair scaled to unit norm */
  for (size_t j = 0; j < K; j++) {
    e->lam[j] = CMPLX(wr[j], wi[j]);
    int pair = wi[j] != 0.0 && j + 1 < K;
    size_t w = pair ? 2 : 1;
    double s = 0.0;
    for (size_t c = j; c < j + w; c++)
      for (size_t i = 0; i < K; i++)
        s += vr[i * K + c] * vr[i * K + c];
    s = s > 0.0 ? sqrt(s) : 1.0;
    for (size_t c = j; c < j + w; c++)
      for (size_t i = 0; i < K; i++)
        e->V[c * K + i] = vr[i * K + c] / s;
    if (pair) {
      e->lam[j + 1] = CMPLX(wr[j + 1], wi[j + 1]);
      e->pair[j] = 1;
      e->pair[j + 1] = 2;
      j++;
    }
  }
  memcpy(e->Vinv, e->V, K * K * sizeof *e->V);
  info = LAPACKE_dgetrf(LAPACK_COL_MAJOR, (lapack_int)K, (lapack_int)K, e->Vinv,
                        (lapack_int)K, ipiv);
  if (info == 0)
    info = LAPACKE_dgetri(LAPACK_COL_MAJOR, (lapack_int)K, e->Vinv, (lapack_int)K, ipiv);
  e->cond =
      info ? HUGE_VAL : ss_dense_max_row_sum(e->V, K) * ss_dense_max_row_sum(e->Vinv, K);
  if (!(e->cond <= SS_LIMIT_MAXCOND)) {
    snprintf(e->why, sizeof e->why,
             "the %zu x %zu matrix of a stationary run is defective or nearly so (a "
             "Jordan block): its eigenvector matrix has condition %.3g (limit %.0e)",
             K, K, e->cond, SS_LIMIT_MAXCOND);
    if ((st = make_powers(W, K, e, err))) goto done;
  }
  /* the eigenvalue 1: simple, every other eigenvalue inside the unit disc */
  size_t nones = 0;
  double rest = 0.0;
  for (size_t j = 0; j < K; j++) {
    if (cabs(e->lam[j] - 1.0) <= 1e-9) {
      nones++;
      e->one = j;
    } else if (cabs(e->lam[j]) > rest) {
      rest = cabs(e->lam[j]);
    }
  }
  if (nones != 1 || rest >= 1.0 - 1e-12) e->one = SIZE_MAX;
  e->second = rest;
  e->ok = 1;
done:
  free(a);
  free(wr);
  free(wi);
  free(vr);
  free(ipiv);
  if (st)
    ss_lim_eig_free(e);
  else
    *out = e;
  return st;
}

void ss_lim_eig_coef(const ss_lim_eig *e, const double *P, double *C) {
  const size_t K = e->K;
  memset(C, 0, K * 3 * sizeof *C);
  for (size_t j = 0; j < K; j++) {
    const double *col = e->Vinv + j * K, *p = P + j * 3;
    for (size_t i = 0; i < K; i++) {
      double v = col[i];
      C[i * 3] += v * p[0];
      C[i * 3 + 1] += v * p[1];
      C[i * 3 + 2] += v * p[2];
    }
  }
}

ss_status ss_lim_eig_power(const ss_lim_eig *e, long m, double *P, double shift[3],
                           ss_error *err) {
  const size_t K = e->K;
  if (!e->ok) return ss_error_set(err, SS_ENUMERIC, "%s", e->why);
  if (m < 0 && e->one == SIZE_MAX)
    return ss_error_set(
        err, SS_ENUMERIC,
        "the limit at a fixed point needs the eigenvalue 1 simple and all "
        "others inside the unit circle; this run's matrix has not");
  if (shift) shift[0] = shift[1] = shift[2] = 0.0;
  if (e->pw) {
    /* W^m by the binary digits of m; the limit as W^(2^(SS_LIM_NPOW-1)) applied
     * until |lambda_1|^(2^i) has vanished */
    double *tmp = malloc((K * 3 + 1) * sizeof *tmp);
    if (!tmp) return ss_error_nomem(err, "matrix powers");
    if (m < 0) {
      double l1 = e->second, r = l1;
      int reps = 0;
      for (int p = 0; p < SS_LIM_NPOW - 1; p++)
        r *= r;
      do {
        matvec(e->pw + (size_t)(SS_LIM_NPOW - 1) * K * K, K, P, tmp);
        reps++;
        l1 = reps == 1 ? r : l1 * r;
      } while (l1 > 1e-300 && reps < 64);
    } else {
      for (int p = 0; p < SS_LIM_NPOW && m > 0; p++, m >>= 1)
        if (m & 1) matvec(e->pw + (size_t)p * K * K, K, P, tmp);
      if (m > 0) {
        free(tmp);
        return ss_error_set(err, SS_EINTERNAL, "run too long for the matrix powers");
      }
    }
    free(tmp);
    return SS_OK;
  }
  /* C = V^-1 P, then diag-block(lambda)^m C, then P = V C; for finite m
   * the eigenvalue-1 part (a uniform translation: its eigenvector is
   * constant) goes to shift, not into P, so that its rounding (eps cond |P|,
   * which does not shrink with m) does not swamp the differences of the
   * result (|lambda_1|^m |P|) */
  double sh[3] = {0, 0, 0};
  double *C = malloc((K * 3 + 1) * sizeof *C);
  if (!C) return ss_error_nomem(err, "eigen power");
  ss_lim_eig_coef(e, P, C);
  for (size_t i = 0; i < K; i++) {
    double *c = C + i * 3;
    if (m < 0) {
      if (i != e->one) c[0] = c[1] = c[2] = 0.0;
      continue;
    }
    if (i == e->one && shift) {
      double vbar = 0.0;
      for (size_t r = 0; r < K; r++)
        vbar += e->V[i * K + r];
      vbar /= (double)K;
      for (int d = 0; d < 3; d++) {
        sh[d] = vbar * c[d];
        c[d] = 0.0;
      }
      continue;
    }
    if (e->pair[i] == 1) {
      /* [c_i; c_i+1] <- r^m [cos m t, sin m t; -sin m t, cos m t] [c_i; c_i+1] */
      double r = pow(cabs(e->lam[i]), (double)m), t = (double)m * carg(e->lam[i]);
      double cs = r * cos(t), sn = r * sin(t), *c2 = c + 3;
      for (int d = 0; d < 3; d++) {
        double x = c[d], y = c2[d];
        c[d] = cs * x + sn * y;
        c2[d] = -sn * x + cs * y;
      }
      i++;
      continue;
    }
    double f = pow(creal(e->lam[i]), (double)m);
    for (int d = 0; d < 3; d++)
      c[d] *= f;
  }
  memset(P, 0, K * 3 * sizeof *P);
  for (size_t i = 0; i < K; i++) {
    const double *col = e->V + i * K, *c = C + i * 3;
    if (c[0] == 0.0 && c[1] == 0.0 && c[2] == 0.0) continue;
    for (size_t r = 0; r < K; r++) {
      P[r * 3] += col[r] * c[0];
      P[r * 3 + 1] += col[r] * c[1];
      P[r * 3 + 2] += col[r] * c[2];
    }
  }
  free(C);
  if (shift) memcpy(shift, sh, sizeof sh);
  return SS_OK;
}
