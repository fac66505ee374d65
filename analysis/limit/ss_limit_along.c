/* ss_limit_along.c — the differences across a plane x_a = const carried
 * apart from the net while the walk stays on that plane (method:
 * ss_limit_impl.h, ss_lim_along). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit_impl.h"

/* A weight this close to its mirror image is its mirror image: the schemes'
 * stencils are symmetric, and the weights of W are formed in doubles (their
 * rounding is about 1e-16); an asymmetry of the rules themselves is a
 * rational number far above this. */
#define ALONG_TOL 1e-12

void ss_lim_along_free(ss_lim_along *A) {
  free(A->dl);
  free(A->colpt);
  memset(A, 0, sizeof *A);
}

/* The columns of patch p along axis into *colpt (ncol x 4: the point at
 * positions -1..2), allocated; 0 if p's points do not form such columns. */
static int columns(const ss_lim_patch *p, int axis, size_t (**colpt)[4], size_t *ncol) {
  const size_t K = p->nv;
  ss_lim_tensor T = {0};
  size_t *uf = malloc((K + 1) * sizeof *uf);
  T.axis = axis;
  T.layer = malloc((K + 1) * sizeof *T.layer);
  T.col = malloc((K + 1) * sizeof *T.col);
  T.colpt = malloc((K + 1) * sizeof *T.colpt);
  int ok = uf && T.layer && T.col && T.colpt && !((p->posbad >> axis) & 1u) &&
           ss_lim_tensor_columns(p, &T, uf);
  free(uf);
  free(T.layer);
  free(T.col);
  if (!ok) {
    free(T.colpt);
    return 0;
  }
  *colpt = T.colpt;
  *ncol = T.ncol;
  return 1;
}

/* Make dl's largest entry at least 2^-256 (or 0), e compensating. */
static void normalize(ss_lim_along *A) {
  double mx = 0.0;
  for (size_t i = 0; i < A->ncol * A->D; i++)
    mx = fmax(mx, fabs(A->dl[i]));
  if (!(mx > 0.0) || mx >= 0x1p-256) return;
  int k = -ilogb(mx) - 1;
  for (size_t i = 0; i < A->ncol * A->D; i++)
    A->dl[i] = ldexp(A->dl[i], k);
  A->e -= k;
}

void ss_lim_along_start(ss_lim_along *A, const ss_lim_patch *p, const ss_lim_pt *pt,
                        int axis, size_t D, const double *P) {
  memset(A, 0, sizeof *A);
  if (pt->d[axis] != 0.0 || !columns(p, axis, &A->colpt, &A->ncol)) return;
  A->dl = malloc((A->ncol * D + 1) * sizeof *A->dl);
  if (!A->dl) {
    ss_lim_along_free(A);
    return;
  }
  A->axis = axis;
  A->side = pt->s[axis];
  A->D = D;
  for (size_t c = 0; c < A->ncol; c++)
    for (size_t d = 0; d < D; d++)
      A->dl[c * D + d] =
          P[A->colpt[c][A->side + 2] * D + d] - P[A->colpt[c][A->side] * D + d];
  A->on = 1;
  normalize(A);
}

/* The map of the differences through W (child patch cp from parent points
 * in A's columns): child column c's difference is sum_q F[c][q] times
 * parent column q's, with F[c][q] = (W[c+] - W[c-])[q+]; 0 unless W's rows
 * give the child's differences from the parent's alone (the other layers'
 * weights cancel). */
static int diff_map(const ss_lim_along *A, const double *W, size_t K, size_t (*ccol)[4],
                    size_t nc, int cside, double *F) {
  const int ps = A->side, rest = ps == 0 ? 3 : 0;
  for (size_t c = 0; c < nc; c++) {
    const double *rp = W + ccol[c][cside + 2] * K, *rm = W + ccol[c][cside] * K;
    for (size_t q = 0; q < A->ncol; q++) {
      const size_t *qp = A->colpt[q];
      const double hi = rp[qp[ps + 2]] - rm[qp[ps + 2]];
      const double lo = rp[qp[ps]] - rm[qp[ps]];
      const double mid = rp[qp[ps + 1]] - rm[qp[ps + 1]];
      const double out = rp[qp[rest]] - rm[qp[rest]];
      if (!(fabs(hi + lo) <= ALONG_TOL && fabs(mid) <= ALONG_TOL &&
            fabs(out) <= ALONG_TOL))
        return 0;
      F[c * A->ncol + q] = hi;
    }
  }
  return 1;
}

ss_status ss_lim_along_step(ss_lim_along *A, const double *W, const ss_lim_patch *pp,
                            const ss_lim_patch *cp, int caxis, int cside, long m,
                            ss_error *err) {
  if (!A->on) return SS_OK;
  size_t(*ccol)[4] = NULL, nc = 0;
  const size_t D = A->D;
  if (!columns(cp, caxis, &ccol, &nc)) {
    ss_lim_along_free(A);
    return SS_OK;
  }
  double *F = malloc((nc * A->ncol + 1) * sizeof *F),
         *nd = malloc((nc * D + 1) * sizeof *nd);
  if (!F || !nd) {
    free(F), free(nd), free(ccol);
    return ss_error_nomem(err, "along-edge differences");
  }
  if (!diff_map(A, W, pp->nv, ccol, nc, cside, F) || (m > 1 && nc != A->ncol)) {
    free(F), free(nd), free(ccol);
    ss_lim_along_free(A);
    return SS_OK;
  }
  for (long it = 0; it < m; it++) {
    for (size_t c = 0; c < nc; c++)
      for (size_t d = 0; d < D; d++) {
        double acc = 0.0;
        for (size_t q = 0; q < A->ncol; q++)
          acc += F[c * A->ncol + q] * A->dl[q * D + d];
        nd[c * D + d] = acc;
      }
    double *t = A->dl;
    A->dl = nd;
    nd = t;
    A->ncol = nc;
    normalize(A);
  }
  free(F);
  free(nd);
  free(A->colpt);
  A->colpt = ccol;
  A->axis = caxis;
  A->side = cside;
  return SS_OK;
}

ss_status ss_lim_along_net(const ss_lim_along *A, const ss_lim_patch *p, double **Q,
                           ss_error *err) {
  const size_t D = A->D;
  *Q = calloc(p->nv * D + 1, sizeof **Q);
  if (!*Q) return ss_error_nomem(err, "along-edge differences");
  for (size_t c = 0; c < A->ncol; c++)
    memcpy(*Q + A->colpt[c][A->side + 2] * D, A->dl + c * D, D * sizeof **Q);
  return SS_OK;
}
