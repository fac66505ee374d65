/* ss_schur_rump.c — a diagonal block's eigenvalues by clusters, each cluster
 * enclosed with its invariant subspace by Rump's method, counted when the
 * balls are disjoint (ss_schur_block, ss_schur_impl.h).
 *
 * Why not acb_mat_eig_multiple: on blocks whose clusters are exact (the
 * symmetry's multiplicities: 1/2 three times, 1/4 six times on the regular
 * hex vertex's one-ring) it gives up, because acb_mat_eig_enclosure_rump
 * freezes the *last* k rows of the approximate basis for a cluster of k and
 * an arbitrary basis of the cluster's eigenvectors from the QR iteration
 * leaves those rows singular.  Here the k frozen rows are chosen by pivoting
 * on the approximate basis and the block permuted so that they come last. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_schur_impl.h"

static const double CLUSTER = 1e-6; /* approximations closer than this
                                       (relative, at least absolute) are
                                       one cluster */

static double mid(const arb_t x) {
  return arf_get_d(arb_midref(x), ARF_RND_NEAR);
}

/* k pivot rows of the approximate basis V (b x k, column-major complex
 * doubles; destroyed), flagged in piv (b bytes): 0, or 1 when V is singular. */
static int pivot_rows(double complex *V, size_t b, size_t k, unsigned char *piv) {
  for (size_t i = 0; i < b; i++)
    piv[i] = 0;
  for (size_t j = 0; j < k; j++) {
    size_t p = b;
    double best = 0.0;
    for (size_t i = 0; i < b; i++)
      if (!piv[i] && cabs(V[j * b + i]) > best) best = cabs(V[j * b + i]), p = i;
    if (p == b) return 1;
    piv[p] = 1;
    for (size_t q = j + 1; q < k; q++) { /* eliminate row p from later columns */
      const double complex f = V[q * b + p] / V[j * b + p];
      for (size_t i = 0; i < b; i++)
        V[q * b + i] -= f * V[j * b + i];
    }
  }
  return 0;
}

/* Rump's enclosure for the cluster with approximate eigenvalue lam0 and
 * basis Xap (b x k): lam holds the eigenvalues of J in B X = X J, X (b x k)
 * the basis, its frozen rows those of Xap.  1 on success. */
static int rump(const acb_mat_t B, const acb_t lam0, const acb_mat_t Xap, acb_t lam,
                acb_mat_t X) {
  const slong b = acb_mat_nrows(B), k = acb_mat_ncols(Xap);
  if (b < 1 || k < 1 || k > b) return 0;
  double complex *V = malloc(((size_t)(b * k) + 1) * sizeof *V);
  unsigned char *piv = malloc((size_t)b + 1);
  slong *perm = malloc(((size_t)b + 1) * sizeof *perm);
  int ok = V && piv && perm;
  for (slong j = 0; ok && j < k; j++)
    for (slong i = 0; i < b; i++) {
      const acb_struct *e = acb_mat_entry(Xap, i, j);
      V[j * b + i] = CMPLX(mid(acb_realref(e)), mid(acb_imagref(e)));
    }
  ok = ok && !pivot_rows(V, (size_t)b, (size_t)k, piv);
  if (ok) {
    slong q = 0; /* the frozen rows last, as arb freezes them */
    for (slong i = 0; i < b; i++)
      if (!piv[i]) perm[q++] = i;
    for (slong i = 0; i < b; i++)
      if (piv[i]) perm[q++] = i;
    acb_mat_t Bp, Xp, Xo;
    acb_mat_init(Bp, b, b);
    acb_mat_init(Xp, b, k);
    acb_mat_init(Xo, b, k);
    for (slong x = 0; x < b; x++) {
      for (slong y = 0; y < b; y++)
        acb_set(acb_mat_entry(Bp, x, y), acb_mat_entry(B, perm[x], perm[y]));
      for (slong j = 0; j < k; j++)
        acb_set(acb_mat_entry(Xp, x, j), acb_mat_entry(Xap, perm[x], j));
    }
    acb_mat_eig_enclosure_rump(lam, NULL, Xo, Bp, lam0, Xp, SC_PREC);
    ok = acb_is_finite(lam) && acb_mat_is_finite(Xo);
    acb_mat_t F, Fi; /* the frozen rows (exact) invertible: X has rank k */
    acb_mat_init(F, k, k);
    acb_mat_init(Fi, k, k);
    for (slong x = 0; x < k; x++)
      for (slong j = 0; j < k; j++)
        acb_set(acb_mat_entry(F, x, j), acb_mat_entry(Xp, b - k + x, j));
    ok = ok && acb_mat_inv(Fi, F, SC_PREC);
    acb_mat_clear(F);
    acb_mat_clear(Fi);
    for (slong x = 0; ok && x < b; x++)
      for (slong j = 0; j < k; j++)
        acb_set(acb_mat_entry(X, perm[x], j), acb_mat_entry(Xo, x, j));
    acb_mat_clear(Bp);
    acb_mat_clear(Xp);
    acb_mat_clear(Xo);
  }
  free(V);
  free(piv);
  free(perm);
  return ok;
}

/* The approximate basis of cluster members m[0..k-1] (columns of R0) into
 * Xap and their mean eigenvalue into lam0; a real cluster (every member
 * within CLUSTER of the real axis) gets a real orthonormal basis of the
 * members' real and imaginary parts (largest remaining first), so that the
 * enclosure's frozen rows are real.  0, or -1 out of memory. */
static int approx(acb_srcptr E0, const acb_mat_t R0, const slong *m, slong k,
                  acb_mat_t Xap, acb_t lam0) {
  const slong b = acb_mat_nrows(R0);
  double re = 0.0, im = 0.0;
  int real = 1;
  for (slong j = 0; j < k; j++) {
    const double x = mid(acb_realref(E0 + m[j])), y = mid(acb_imagref(E0 + m[j]));
    re += x, im += y;
    real &= fabs(y) <= CLUSTER * fmax(1.0, fabs(x));
  }
  if (!real) {
    acb_set_d_d(lam0, re / (double)k, im / (double)k);
    for (slong j = 0; j < k; j++)
      for (slong i = 0; i < b; i++)
        acb_get_mid(acb_mat_entry(Xap, i, j), acb_mat_entry(R0, i, m[j]));
    return 0;
  }
  acb_set_d(lam0, re / (double)k);
  double *V = malloc(((size_t)(2 * k * b) + 1) * sizeof *V);
  if (!V) return -1;
  const slong nv = 2 * k;
  for (slong j = 0; j < k; j++)
    for (slong i = 0; i < b; i++) {
      const acb_struct *e = acb_mat_entry(R0, i, m[j]);
      V[(2 * j) * b + i] = mid(acb_realref(e));
      V[(2 * j + 1) * b + i] = mid(acb_imagref(e));
    }
  for (slong j = 0; j < k; j++) {
    slong best = j;
    double bn = -1.0;
    for (slong q = j; q < nv; q++) {
      double t = 0.0;
      for (slong i = 0; i < b; i++)
        t += V[q * b + i] * V[q * b + i];
      if (t > bn) bn = t, best = q;
    }
    for (slong i = 0; i < b; i++) { /* best into place j, normalised */
      const double t = V[best * b + i];
      V[best * b + i] = V[j * b + i];
      V[j * b + i] = t / (bn > 0.0 ? sqrt(bn) : 1.0);
    }
    for (slong q = j + 1; q < nv; q++) {
      double d = 0.0;
      for (slong i = 0; i < b; i++)
        d += V[q * b + i] * V[j * b + i];
      for (slong i = 0; i < b; i++)
        V[q * b + i] -= d * V[j * b + i];
    }
    for (slong i = 0; i < b; i++)
      acb_set_d(acb_mat_entry(Xap, i, j), V[j * b + i]);
  }
  free(V);
  return 0;
}

/* Cluster ids (single linkage within CLUSTER) of the b approximations into
 * cl; returns the number of clusters. */
static slong clusters(acb_srcptr E0, slong b, slong *cl) {
  for (slong i = 0; i < b; i++)
    cl[i] = -1;
  slong nc = 0;
  for (slong i = 0; i < b; i++) {
    if (cl[i] >= 0) continue;
    cl[i] = nc;
    for (int grew = 1; grew;) {
      grew = 0;
      for (slong j = 0; j < b; j++) {
        if (cl[j] >= 0) continue;
        const double xj = mid(acb_realref(E0 + j)), yj = mid(acb_imagref(E0 + j));
        for (slong q = 0; q < b && cl[j] < 0; q++)
          if (cl[q] == nc &&
              hypot(xj - mid(acb_realref(E0 + q)), yj - mid(acb_imagref(E0 + q))) <=
                  CLUSTER * fmax(1.0, hypot(xj, yj)))
            cl[j] = nc, grew = 1;
      }
    }
    nc++;
  }
  return nc;
}

/* Drop the roots from index first on. */
static void drop_from(ss_schur *s, size_t first) {
  while (s->nrt > first) {
    sc_root *o = s->rt + --s->nrt;
    acb_clear(&o->ball.z);
    arb_clear(&o->ball.mod);
    if (o->has_xc) acb_mat_clear(&o->Xc);
  }
}

/* Each cluster of the block enclosed: 1 when all are and their balls are
 * pairwise disjoint, 0 when not (the roots appended are dropped again), -1
 * out of memory. */
static int by_clusters(ss_schur *s, const acb_mat_t B, long blk, acb_srcptr E0,
                       const acb_mat_t R0) {
  const slong b = acb_mat_nrows(B);
  const size_t first = s->nrt;
  slong *cl = malloc(((size_t)b + 1) * sizeof *cl),
        *m = malloc(((size_t)b + 1) * sizeof *m);
  if (!cl || !m) {
    free(cl);
    free(m);
    return -1;
  }
  const slong nc = clusters(E0, b, cl);
  int ok = 1;
  acb_t lam0;
  acb_init(lam0);
  for (slong c = 0; c < nc && ok == 1; c++) {
    slong k = 0;
    for (slong i = 0; i < b; i++)
      if (cl[i] == c) m[k++] = i;
    acb_mat_t Xap, X;
    acb_mat_init(Xap, b, k);
    acb_mat_init(X, b, k);
    sc_root *o = NULL;
    if (approx(E0, R0, m, k, Xap, lam0) || !(o = ss_schur_root_new(s))) ok = -1;
    if (o) {
      o->count = (int)k;
      o->blk = blk;
      ok = rump(B, lam0, Xap, &o->ball.z, X);
      acb_abs(&o->ball.mod, &o->ball.z, SC_PREC);
    }
    if (ok == 1 && blk < 0) { /* A's: the basis kept for the ties */
      acb_mat_init(&o->Xc, b, k);
      acb_mat_swap(&o->Xc, X);
      o->has_xc = 1;
    }
    acb_mat_clear(Xap);
    acb_mat_clear(X);
  }
  for (size_t i = first; i < s->nrt && ok == 1; i++)
    for (size_t j = first; j < i && ok == 1; j++)
      if (acb_overlaps(&s->rt[i].ball.z, &s->rt[j].ball.z)) ok = 0;
  for (size_t i = first; i < s->nrt && ok == 1; i++)
    s->rt[i].ball.counted = 1;
  if (ok != 1) drop_from(s, first);
  acb_clear(lam0);
  free(cl);
  free(m);
  return ok;
}

int ss_schur_block(ss_schur *s, const acb_mat_t B, long blk) {
  const slong b = acb_mat_nrows(B);
  if (b == 0) return 0;
  acb_ptr E0 = _acb_vec_init(b);
  acb_mat_t R0;
  acb_mat_init(R0, b, b);
  acb_mat_approx_eig_qr(E0, NULL, R0, B, NULL, 0, SC_PREC);
  int rc = by_clusters(s, B, blk, E0, R0);
  if (rc == 0) { /* bounds only: every eigenvalue within eps of an approximation */
    mag_t eps;
    mag_init(eps);
    acb_mat_eig_global_enclosure(eps, B, E0, R0, SC_PREC);
    rc = mag_is_finite(eps) ? 1 : 0;
    for (slong i = 0; i < b && rc == 1; i++) {
      sc_root *o = ss_schur_root_new(s);
      if (!o) {
        rc = -1;
        break;
      }
      acb_set(&o->ball.z, E0 + i);
      acb_add_error_mag(&o->ball.z, eps);
      acb_abs(&o->ball.mod, &o->ball.z, SC_PREC);
      o->count = 1;
      o->blk = blk;
    }
    mag_clear(eps);
  }
  acb_mat_clear(R0);
  _acb_vec_clear(E0, b);
  return rc < 0 ? -1 : rc == 1 ? 0 : 1;
}
