/* ss_limit_bspline.c — the tricubic B-spline: its basis, its evaluation on a
 * regular patch's 4x4x4 net, and the check that a scheme refines a regular
 * hex grid by its rules, which the evaluator assumes on regular cells. */
#include "ss_limit.h"

#include <complex.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit_impl.h"

/* Cubic B-spline rows of the left (b = 0) and right (b = 1) halves: child
 * points at positions -1..2 of the half from the parent's at -1..2. */
const double ss_lim_bspline_half[2][4][4] = {{{0.5, 0.5, 0, 0},
                                              {0.125, 0.75, 0.125, 0},
                                              {0, 0.5, 0.5, 0},
                                              {0, 0.125, 0.75, 0.125}},
                                             {{0.125, 0.75, 0.125, 0},
                                              {0, 0.5, 0.5, 0},
                                              {0, 0.125, 0.75, 0.125},
                                              {0, 0, 0.5, 0.5}}};

/* Regular patches are evaluated by the tricubic B-spline, which is right only
 * if the scheme's rule on a regular grid is the tricubic B-spline's: check it
 * on the 3x3x3 block, child by child (the 1D rows are the cubic B-spline's
 * midpoint 1/2 1/2 and vertex 1/8 3/4 1/8 rules; the 3D rows their tensor
 * product).  A stencil file with other hex weights is refused here instead
 * of evaluated wrongly. */
ss_status ss_lim_check_bspline(const ss_scheme *s, ss_error *err) {
  const double(*A)[4][4] = ss_lim_bspline_half;
  ss_status st;
  ss_cx *g = NULL, *pcx = NULL, *ccx = NULL;
  ss_lim_adj adj = {0};
  ss_lim_patch p = {0}, c = {0};
  double *W = NULL;
  int64_t loc[64];
  if ((st = ss_cx_new(3, &g, err))) return st;
  for (int k = 0; k < 4 && !st; k++)
    for (int j = 0; j < 4 && !st; j++)
      for (int i = 0; i < 4 && !st; i++) {
        double x[3] = {i, j, k};
        st = ss_cx_add_vertex(g, x, 0, err);
      }
  /* the centre cell first, so that it is hex 0 */
  for (int q = 0; q < 27 && !st; q++) {
    int r = (q + 13) % 27, i = r % 3, j = (r / 3) % 3, k = r / 9;
    ss_idx v[8];
    for (int b = 0; b < 8; b++) {
      unsigned bits = ss_cube_corner_bits(3, b);
      v[b] = (ss_idx)((i + (int)(bits & 1u)) + 4 * ((j + (int)((bits >> 1) & 1u)) +
                                                    4 * (k + (int)((bits >> 2) & 1u))));
    }
    st = ss_cx_add_cell(g, SS_HEX, v, 0, err);
  }
  for (int v = 0; v < 64; v++)
    loc[v] = -1;
  ss_lim_frame id = ss_lim_frame_id(), gk;
  if (st || (st = ss_lim_adj_build(g, &adj, err)) ||
      (st = ss_lim_patch_build(&adj, 0, &id, loc, &p, err)) ||
      (st = ss_lim_patch_complex(g, &p, &pcx, err)))
    goto done;
  double worst = 0.0;
  for (int k = 0; k < 8 && p.regular; k++) {
    if ((st = ss_lim_step(s, pcx, k, 0, &c, &gk, &ccx, &W, err))) goto done;
    unsigned b = ss_cube_corner_bits(3, k);
    for (int q = 0; q < 64 && c.regular; q++)
      for (int r = 0; r < 64; r++) {
        double want = A[b & 1u][q % 4][r % 4] *
                      A[(b >> 1) & 1u][(q / 4) % 4][(r / 4) % 4] *
                      A[(b >> 2) & 1u][q / 16][r / 16];
        double e = fabs(W[(size_t)c.net[q] * 64 + p.net[r]] - want);
        if (e > worst) worst = e;
      }
    if (!c.regular) worst = 1.0;
    ss_lim_patch_free(&c);
    ss_cx_free(ccx);
    ccx = NULL;
    free(W);
    W = NULL;
  }
  if (!p.regular || worst > 1e-12)
    st = ss_error_set(err, SS_EINPUT,
                      "scheme %s does not refine a regular hex grid by the tricubic "
                      "B-spline rules (a weight is off by %.3g), which limit evaluation "
                      "assumes on regular cells",
                      ss_scheme_name(s), worst);
done:
  free(W);
  ss_lim_patch_free(&c);
  ss_lim_patch_free(&p);
  ss_cx_free(ccx);
  ss_cx_free(pcx);
  ss_lim_adj_free(&adj);
  ss_cx_free(g);
  return st;
}

/* Uniform cubic B-spline basis on [0,1] for the points at -1, 0, 1, 2, and
 * its derivative. */
void ss_lim_basis(double t, double b[4], double d[4]) {
  const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
  b[0] = s * s * s / 6.0;
  b[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
  b[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
  b[3] = t3 / 6.0;
  d[0] = -s * s / 2.0;
  d[1] = (9.0 * t2 - 12.0 * t) / 6.0;
  d[2] = (-9.0 * t2 + 6.0 * t + 3.0) / 6.0;
  d[3] = t2 / 2.0;
}

void ss_limit_bspline(const double (*net)[3], double u, double v, double w, double p[3],
                      double jac[3][3]) {
  double bu[4], du[4], bv[4], dv[4], bw[4], dw[4];
  ss_lim_basis(u, bu, du);
  ss_lim_basis(v, bv, dv);
  ss_lim_basis(w, bw, dw);
  double r[4][3] = {{0}};
  for (int k = 0; k < 4; k++)
    for (int j = 0; j < 4; j++)
      for (int i = 0; i < 4; i++) {
        const double *q = net[i + 4 * j + 16 * k];
        const double c[4] = {bu[i] * bv[j] * bw[k], du[i] * bv[j] * bw[k],
                             bu[i] * dv[j] * bw[k], bu[i] * bv[j] * dw[k]};
        for (int e = 0; e < 4; e++)
          for (int d = 0; d < 3; d++)
            r[e][d] += c[e] * q[d];
      }
  for (int d = 0; d < 3; d++)
    p[d] = r[0][d];
  if (jac)
    for (int e = 0; e < 3; e++)
      for (int d = 0; d < 3; d++)
        jac[e][d] = r[e + 1][d];
}
