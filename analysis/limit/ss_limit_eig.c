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
  free(e->pd);
  free(e->V);
  free(e->Vinv);
  free(e->lam);
  free(e->pair);
  free(e);
}

/* c = a b (n x n, row-major; c aliases neither). */
static void square_into(const double *a, const double *b, size_t n, double *c) {
  memset(c, 0, n * n * sizeof *c);
  for (size_t i = 0; i < n; i++)
    for (size_t q = 0; q < n; q++) {
      double x = a[i * n + q];
      if (x == 0.0) continue;
      for (size_t j = 0; j < n; j++)
        c[i * n + j] += x * b[q * n + j];
    }
}

/* a (n entries) <- a 2^-k with the largest |entry| in [1/2, 1), *ex += k
 * (exact but for entries that become subnormal, negligible beside the
 * largest); all zeros are left alone. */
static void normalize(double *a, size_t n, long *ex) {
  double mx = 0.0;
  for (size_t i = 0; i < n; i++)
    if (fabs(a[i]) > mx) mx = fabs(a[i]);
  if (!(mx > 0.0) || !isfinite(mx)) return;
  int k = ilogb(mx) + 1;
  for (size_t i = 0; i < n; i++)
    a[i] = ldexp(a[i], -k);
  *ex += k;
}

/* The fallback for a defective W: W^(2^i), i = 0 .. SS_LIM_NPOW - 1, by repeated
 * squaring (products of averaging matrices: stable, whatever the Jordan
 * structure), and the same powers of the difference map D (scaled: they
 * shrink like |lambda_2|^(2^i), below DBL_MIN for i = 11). */
static ss_status make_powers(const double *W, size_t K, ss_lim_eig *e, ss_error *err) {
  const size_t n = K - 1;
  e->pw = malloc((SS_LIM_NPOW * K * K + 1) * sizeof *e->pw);
  e->pd = malloc((SS_LIM_NPOW * n * n + 1) * sizeof *e->pd);
  if (!e->pw || !e->pd) return ss_error_nomem(err, "matrix powers");
  memcpy(e->pw, W, K * K * sizeof *W);
  for (int p = 1; p < SS_LIM_NPOW; p++)
    square_into(e->pw + (size_t)(p - 1) * K * K, e->pw + (size_t)(p - 1) * K * K, K,
                e->pw + (size_t)p * K * K);
  for (size_t r = 1; r < K; r++)
    for (size_t j = 1; j < K; j++)
      e->pd[(r - 1) * n + (j - 1)] = W[r * K + j] - W[j];
  e->pdexp[0] = 0;
  normalize(e->pd, n * n, &e->pdexp[0]);
  for (int p = 1; p < SS_LIM_NPOW; p++) {
    double *B = e->pd + (size_t)p * n * n;
    square_into(e->pd + (size_t)(p - 1) * n * n, e->pd + (size_t)(p - 1) * n * n, n, B);
    e->pdexp[p] = 2 * e->pdexp[p - 1];
    normalize(B, n * n, &e->pdexp[p]);
  }
  return SS_OK;
}

/* x^m 2^s, formed with the exponent kept apart (binary powering on the
 * mantissa, about 2 log2(m) roundings), so that it neither underflows nor
 * overflows on the way when the result is a normal number. */
static double pow_scaled(double x, long m, long s) {
  if (m == 0) return ldexp(1.0, (int)s);
  if (x == 0.0) return 0.0;
  int t;
  double b = frexp(fabs(x), &t), r = 1.0;
  long eb = t, er = 0;
  for (long k = m; k > 0; k >>= 1) {
    if (k & 1) {
      r = frexp(r * b, &t);
      er += eb + t;
    }
    if (k > 1) {
      b = frexp(b * b, &t);
      eb = 2 * eb + t;
    }
  }
  er += s;
  double v = ldexp(r, (int)(er < -2200 ? -2200 : er > 2200 ? 2200 : er));
  return x < 0.0 && (m & 1) ? -v : v;
}

/* P <- A P (n x n times n x D); tmp holds n x D. */
static void matvec(const double *A, size_t n, size_t D, double *P, double *tmp) {
  for (size_t i = 0; i < n; i++) {
    double *acc = tmp + i * D;
    for (size_t d = 0; d < D; d++)
      acc[d] = 0.0;
    for (size_t j = 0; j < n; j++) {
      double a = A[i * n + j];
      if (a == 0.0) continue;
      for (size_t d = 0; d < D; d++)
        acc[d] += a * P[j * D + d];
    }
  }
  memcpy(P, tmp, n * D * sizeof *P);
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

/* Y[r][d] = sum_t A[j_t * K + r] X[j_t][d] (D = 3, A column-major K x K) for
 * rows r0 .. r0 + n - 1, n <= 4, over j_t = idx[t], t = 0 .. m - 1 (idx NULL:
 * j_t = t), each sum formed from +0 in the order of t: exactly the sums of
 * the plain loops (over j outside, each entry of Y updated in turn), with
 * the four rows' twelve partial sums kept in registers instead of in Y.
 * V^-1 P (every point) and V C (the components of nonzero coefficients). */
static void rows3(const double *A, size_t K, const double *X, const size_t *idx, size_t m,
                  size_t r0, size_t n, double *Y) {
  double y[4][3] = {{0}};
  for (size_t t = 0; t < m; t++) {
    const size_t j = idx ? idx[t] : t;
    const double *a = A + j * K + r0, *x = X + j * 3;
    if (n == 4) {
      for (int q = 0; q < 4; q++)
        for (int d = 0; d < 3; d++)
          y[q][d] += a[q] * x[d];
    } else {
      for (size_t q = 0; q < n; q++)
        for (int d = 0; d < 3; d++)
          y[q][d] += a[q] * x[d];
    }
  }
  for (size_t q = 0; q < n; q++)
    memcpy(Y + (r0 + q) * 3, y[q], sizeof y[q]);
}

void ss_lim_eig_coef(const ss_lim_eig *e, size_t D, const double *P, double *C) {
  const size_t K = e->K;
  if (D == 3) {
    for (size_t i0 = 0; i0 < K; i0 += 4)
      rows3(e->Vinv, K, P, NULL, K, i0, K - i0 < 4 ? K - i0 : 4, C);
    return;
  }
  memset(C, 0, K * D * sizeof *C);
  for (size_t j = 0; j < K; j++) {
    const double *col = e->Vinv + j * K, *p = P + j * D;
    for (size_t i = 0; i < K; i++) {
      double v = col[i];
      for (size_t d = 0; d < D; d++)
        C[i * D + d] += v * p[d];
    }
  }
}

/* A defective run: W^m P from the powers W^(2^i) (the limit for m < 0, as
 * W^(2^(SS_LIM_NPOW-1)) applied until |lambda_1|^(2^i) has vanished); with
 * shift, the first point of W^m P (row 0 of W^m, formed as a row vector) is
 * the shift and the differences come from the scaled powers of D. */
static ss_status power_defective(const ss_lim_eig *e, long m, size_t D, double *P,
                                 double *shift, int *scale, ss_error *err) {
  const size_t K = e->K, n = K - 1;
  double *tmp = malloc((K * D + K + 1) * sizeof *tmp), *row = tmp + K * D;
  if (!tmp) return ss_error_nomem(err, "matrix powers");
  if (m >= 0 && m >> SS_LIM_NPOW) {
    free(tmp);
    return ss_error_set(err, SS_EINTERNAL, "run too long for the matrix powers");
  }
  if (m < 0) {
    double l1 = e->second, r = l1;
    int reps = 0;
    for (int p = 0; p < SS_LIM_NPOW - 1; p++)
      r *= r;
    do {
      matvec(e->pw + (size_t)(SS_LIM_NPOW - 1) * K * K, K, D, P, tmp);
      reps++;
      l1 = reps == 1 ? r : l1 * r;
    } while (l1 > 1e-300 && reps < 64);
  } else if (!shift) {
    for (int p = 0; p < SS_LIM_NPOW && m >> p; p++)
      if ((m >> p) & 1) matvec(e->pw + (size_t)p * K * K, K, D, P, tmp);
  } else {
    /* row 0 of W^m: e_0^T times the powers (they commute) */
    memset(row, 0, K * sizeof *row);
    row[0] = 1.0;
    for (int p = 0; p < SS_LIM_NPOW && m >> p; p++) {
      if (!((m >> p) & 1)) continue;
      const double *A = e->pw + (size_t)p * K * K;
      for (size_t j = 0; j < K; j++) {
        double acc = 0.0;
        for (size_t q = 0; q < K; q++)
          acc += row[q] * A[q * K + j];
        tmp[j] = acc;
      }
      memcpy(row, tmp, K * sizeof *row);
    }
    for (size_t d = 0; d < D; d++) {
      double acc = 0.0;
      for (size_t q = 0; q < K; q++)
        acc += row[q] * P[q * D + d];
      shift[d] = acc;
    }
    /* the differences P_r - P_0 through D^m, scaled as they go */
    long ex = 0;
    double *y = P + D;
    for (size_t r = 0; r < n; r++)
      for (size_t d = 0; d < D; d++)
        y[r * D + d] -= P[d];
    for (size_t d = 0; d < D; d++)
      P[d] = 0.0;
    normalize(y, n * D, &ex);
    for (int p = 0; p < SS_LIM_NPOW && m >> p; p++) {
      if (!((m >> p) & 1)) continue;
      matvec(e->pd + (size_t)p * n * n, n, D, y, tmp);
      ex += e->pdexp[p];
      normalize(y, n * D, &ex);
    }
    if (scale) {
      *scale = (int)-ex;
    } else {
      for (size_t j = 0; j < n * D; j++)
        y[j] = ldexp(y[j], (int)ex);
    }
  }
  free(tmp);
  return SS_OK;
}

/* P (K x D) = V C over the components whose coefficients are not all 0 (a
 * component of zero coefficients adds nothing: the sums start at +0, and
 * +0 + -0 is +0), each entry summed in the order of the components.  nz:
 * scratch of K entries, or NULL (then the plain loop). */
static void combine(const ss_lim_eig *e, size_t D, const double *C, double *P,
                    size_t *nz) {
  const size_t K = e->K;
  size_t nn = 0;
  if (D == 3 && nz) {
    for (size_t i = 0; i < K; i++)
      if (C[i * 3] != 0.0 || C[i * 3 + 1] != 0.0 || C[i * 3 + 2] != 0.0) nz[nn++] = i;
    for (size_t r0 = 0; r0 < K; r0 += 4)
      rows3(e->V, K, C, nz, nn, r0, K - r0 < 4 ? K - r0 : 4, P);
    return;
  }
  memset(P, 0, K * D * sizeof *P);
  for (size_t i = 0; i < K; i++) {
    const double *col = e->V + i * K, *c = C + i * D;
    size_t z = 0;
    while (z < D && c[z] == 0.0)
      z++;
    if (z == D) continue;
    for (size_t r = 0; r < K; r++)
      for (size_t d = 0; d < D; d++)
        P[r * D + d] += col[r] * c[d];
  }
}

ss_status ss_lim_eig_power(const ss_lim_eig *e, long m, size_t D, double *P,
                           double *shift, int *scale, ss_error *err) {
  const size_t K = e->K;
  if (scale) *scale = 0;
  if (!e->ok) return ss_error_set(err, SS_ENUMERIC, "%s", e->why);
  if (m < 0 && e->one == SIZE_MAX)
    return ss_error_set(
        err, SS_ENUMERIC,
        "the limit at a fixed point needs the eigenvalue 1 simple and all "
        "others inside the unit circle; this run's matrix has not");
  if (shift)
    for (size_t d = 0; d < D; d++)
      shift[d] = 0.0;
  if (e->pw) return power_defective(e, m, D, P, shift, scale, err);
  /* C = V^-1 P, then diag-block(lambda)^m C, then P = V C; for finite m
   * the eigenvalue-1 part (a uniform translation: its eigenvector is
   * constant) goes to shift, not into P, so that its rounding (eps cond |P|,
   * which does not shrink with m) does not swamp the differences of the
   * result (|lambda_1|^m |P|).  When |lambda_1|^m would fall below 2^-400
   * the factors are lambda^m 2^s, s = -log2 |lambda_1|^m (rounded down),
   * formed without underflow. */
  long s = 0;
  if (scale && shift && m > 0 && e->second > 0.0 && (double)m * log2(e->second) < -400.0)
    s = (long)floor(-(double)m * log2(e->second));
  double *C = malloc((K * D + D + 1) * sizeof *C), *sh = C + K * D;
  if (!C) return ss_error_nomem(err, "eigen power");
  for (size_t d = 0; d < D; d++)
    sh[d] = 0.0;
  if (m < 0) {
    /* the limit: only the eigenvalue-1 coefficients survive, formed as
     * ss_lim_eig_coef forms them (from +0 in the order of the points) */
    memset(C, 0, K * D * sizeof *C);
    const double *vi = e->Vinv;
    for (size_t j = 0; j < K; j++)
      for (size_t d = 0; d < D; d++)
        C[e->one * D + d] += vi[j * K + e->one] * P[j * D + d];
  } else {
    ss_lim_eig_coef(e, D, P, C);
  }
  for (size_t i = 0; i < K && m >= 0; i++) {
    double *c = C + i * D;
    if (i == e->one && shift) {
      double vbar = 0.0;
      for (size_t r = 0; r < K; r++)
        vbar += e->V[i * K + r];
      vbar /= (double)K;
      for (size_t d = 0; d < D; d++) {
        sh[d] = vbar * c[d];
        c[d] = 0.0;
      }
      continue;
    }
    if (e->pair[i] == 1) {
      /* [c_i; c_i+1] <- r^m [cos m t, sin m t; -sin m t, cos m t] [c_i; c_i+1] */
      double r = s ? pow_scaled(cabs(e->lam[i]), m, s) : pow(cabs(e->lam[i]), (double)m);
      double t = (double)m * carg(e->lam[i]);
      double cs = r * cos(t), sn = r * sin(t), *c2 = c + D;
      for (size_t d = 0; d < D; d++) {
        double x = c[d], y = c2[d];
        c[d] = cs * x + sn * y;
        c2[d] = -sn * x + cs * y;
      }
      i++;
      continue;
    }
    double f = s ? pow_scaled(creal(e->lam[i]), m, s) : pow(creal(e->lam[i]), (double)m);
    for (size_t d = 0; d < D; d++)
      c[d] *= f;
  }
  size_t *nz = malloc((K + 1) * sizeof *nz); /* NULL: the plain loop, the same sums */
  combine(e, D, C, P, nz);
  free(nz);
  if (shift) memcpy(shift, sh, D * sizeof *sh);
  free(C);
  if (scale) *scale = (int)s;
  return SS_OK;
}

ss_status ss_lim_eig_half_part(const ss_lim_eig *e, const double *W, size_t D,
                               const double *P, double *Q, ss_error *err) {
  ss_status st = SS_OK;
  const size_t K = e->K;
  size_t k = 0;
  double bad = 0.0;
  for (size_t j = 0; j < K; j++) {
    if (cabs(e->lam[j] - 0.5) <= 1e-6)
      k++;
    else if (j != e->one && cabs(e->lam[j]) > 0.5 - 1e-8 && bad == 0.0)
      bad = cabs(e->lam[j]);
  }
  memset(Q, 0, K * D * sizeof *Q);
  if (bad > 0.0)
    return ss_error_set(err, SS_ENUMERIC,
                        "its run (a defective matrix) has an eigenvalue of modulus "
                        "%.6g, >= 1/2 and not 1/2",
                        bad);
  if (!k) return SS_OK; /* every component but the point has derivative 0 */
  double *A = malloc((3 * K * K + 2 * K + k * k + k * D + 1) * sizeof *A);
  lapack_int *ipiv = malloc((k + 1) * sizeof *ipiv);
  if (!A || !ipiv) {
    st = ss_error_nomem(err, "eigenvalue-1/2 projector");
    goto done;
  }
  double *U = A + K * K, *VT = U + K * K, *sv = VT + K * K, *work = sv + K, *G = work + K,
         *Z = G + k * k;
  for (size_t i = 0; i < K * K; i++)
    A[i] = W[i];
  for (size_t i = 0; i < K; i++)
    A[i * K + i] -= 0.5;
  lapack_int info =
      LAPACKE_dgesvd(LAPACK_ROW_MAJOR, 'A', 'A', (lapack_int)K, (lapack_int)K, A,
                     (lapack_int)K, sv, U, (lapack_int)K, VT, (lapack_int)K, work);
  if (info) {
    st = ss_error_set(err, SS_ENUMERIC, "dgesvd failed (info %d)", (int)info);
    goto done;
  }
  /* semisimple: exactly k singular values of W - I/2 vanish */
  if (!(sv[K - k] <= 1e-10) || (k < K && !(sv[K - k - 1] > 1e-7))) {
    st = ss_error_set(err, SS_ENUMERIC,
                      "the eigenvalue 1/2 (%zu-fold) of its run has a Jordan block "
                      "(singular values %.3g, %.3g of W - I/2): the Jacobian is "
                      "unbounded",
                      k, sv[K - k], k < K ? sv[K - k - 1] : 0.0);
    goto done;
  }
  /* right eigenvectors X = the last k rows of VT, left ones Y = the last k
   * columns of U; the projector X (Y^T X)^-1 Y^T */
  for (size_t a = 0; a < k; a++)
    for (size_t b = 0; b < k; b++) {
      double s = 0.0;
      for (size_t r = 0; r < K; r++)
        s += U[r * K + (K - k + a)] * VT[(K - k + b) * K + r];
      G[a * k + b] = s;
    }
  if (k > 64) { /* beyond any patch met (K ~ 100, 1/2 at most 3-fold) */
    st = ss_error_set(err, SS_ENUMERIC, "eigenvalue 1/2 of multiplicity %zu", k);
    goto done;
  }
  for (size_t a = 0; a < k; a++)
    for (size_t d = 0; d < D; d++) {
      double s = 0.0;
      for (size_t r = 0; r < K; r++)
        s += U[r * K + (K - k + a)] * P[r * D + d];
      Z[a * D + d] = s;
    }
  info = LAPACKE_dgesv(LAPACK_ROW_MAJOR, (lapack_int)k, (lapack_int)D, G, (lapack_int)k,
                       ipiv, Z, (lapack_int)D);
  if (info) {
    st = ss_error_set(err, SS_ENUMERIC,
                      "the eigenvalue 1/2 of a run: its left and right eigenvectors are "
                      "singular together (dgesv info %d)",
                      (int)info);
    goto done;
  }
  for (size_t r = 0; r < K; r++)
    for (size_t b = 0; b < k; b++)
      for (size_t d = 0; d < D; d++)
        Q[r * D + d] += VT[(K - k + b) * K + r] * Z[b * D + d];
done:
  free(A);
  free(ipiv);
  return st;
}
