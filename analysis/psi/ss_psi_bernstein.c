/* ss_psi_bernstein.c — the sign of det Dψ on one tricubic B-spline piece.
 * Method: ss_psi_bernstein.h.
 *
 * The machinery is written once, in ss_psi_bernstein_impl.h, over the number
 * interface of the Jacobian tests (analysis/charmap/ss_jac_num.h), and
 * instantiated twice below: for double (values of no sign are those within
 * the flat threshold) and for arb's di_t intervals with outward rounding (the
 * proof).  The measures (min_coef, max_coef) and the evaluation of a
 * Bernstein polynomial are in double only. */
#include "ss_psi_bernstein.h"

#include <math.h>
#include <string.h>

#include "ss_jac_num.h"

/* binomial coefficients C(n, i) for n = 2, 3, 8 */
static const double psi_binom2[3] = {1, 2, 1};
static const double psi_binom3[4] = {1, 3, 3, 1};
static const double psi_binom8[9] = {1, 8, 28, 56, 70, 56, 28, 8, 1};

/* (216 / 3)^3: the Bezier net is kept times 6 per axis and the derivatives
 * without their factor 3 (ss_psi_bernstein_impl.h, det_coef) */
#define PSI_SCALE 373248.0

/* the outcomes of judging one box */
enum { PSI_DECIDED, PSI_FOLD, PSI_DOUBT, PSI_SPLIT };

/* ---- double ---- */

static inline void enc_d(double v, double e[2]) {
  e[0] = e[1] = v;
}
static inline double mid_d(double v) {
  return v;
}

#define NUM      double
#define SUF      d
#define PSI_FLAT SS_JAC_DEGENERATE
#include "ss_psi_bernstein_impl.h"
#undef NUM
#undef SUF
#undef PSI_FLAT

/* ---- intervals (enclosures, outward rounding) ---- */

static inline void enc_di(di_t v, double e[2]) {
  e[0] = v.a, e[1] = v.b;
}
/* the midpoint, rounded: a measure only */
static inline double mid_di(di_t v) {
  return 0.5 * v.a + 0.5 * v.b;
}

#define NUM      di_t
#define SUF      di
#define PSI_FLAT SS_JAC_UNDECIDED
#include "ss_psi_bernstein_impl.h"
#undef NUM
#undef SUF
#undef PSI_FLAT

/* ---- the entry points ---- */

/* every coordinate of the 64 points finite */
static int finite_net(const double (*net)[3]) {
  int ok = 1;
  for (int q = 0; q < 64; q++)
    for (int r = 0; r < 3; r++)
      ok &= isfinite(net[q][r]) != 0;
  return ok;
}

/* finite and ordered boxes (di_t needs a <= b) */
static int good_boxes(const double (*lo)[3], const double (*hi)[3]) {
  int ok = finite_net(lo) && finite_net(hi);
  for (int q = 0; q < 64 && ok; q++)
    for (int r = 0; r < 3; r++)
      ok &= lo[q][r] <= hi[q][r];
  return ok;
}

/* the Bezier net (times 216) of net in doubles, and in intervals */
static void bezier_net_d(const double (*net)[3], double (*B)[3]) {
  memcpy(B, net, 64 * sizeof *B);
  bezier_d(B);
}

static void bezier_net_di(const double (*lo)[3], const double (*hi)[3], di_t (*B)[3]) {
  for (int q = 0; q < 64; q++)
    for (int r = 0; r < 3; r++)
      B[q][r].a = lo[q][r], B[q][r].b = hi[q][r];
  bezier_di(B);
}

/* SS_PSI_FLAT N_u N_v N_w from the Bezier net B (times 216): N_a the largest
 * norm of a difference along a, over 72 (ss_psi_bernstein_impl.h) */
static double flat_of_bezier(double (*B)[3]) {
  double t = SS_PSI_FLAT;
  for (int a = 0; a < 3; a++) {
    double D[48][3], n2 = 0.0;
    diffs_d(B, a, D);
    for (int q = 0; q < 48; q++)
      n2 = fmax(n2, D[q][0] * D[q][0] + D[q][1] * D[q][1] + D[q][2] * D[q][2]);
    t *= sqrt(n2) / 72.0;
  }
  return t;
}

double ss_psi_bernstein_flat(const double (*net)[3]) {
  if (!finite_net(net)) return NAN;
  double B[64][3];
  bezier_net_d(net, B);
  return flat_of_bezier(B);
}

void ss_psi_bernstein_det(const double (*net)[3], double coef[SS_PSI_NCOEF]) {
  double B[64][3];
  bezier_net_d(net, B);
  det_coef_d(B, coef);
}

void ss_psi_bernstein_det_interval(const double (*lo)[3], const double (*hi)[3],
                                   double clo[SS_PSI_NCOEF], double chi[SS_PSI_NCOEF]) {
  if (!good_boxes(lo, hi)) {
    for (int q = 0; q < SS_PSI_NCOEF; q++)
      clo[q] = -INFINITY, chi[q] = INFINITY;
    return;
  }
  di_t B[64][3], c[SS_PSI_NCOEF];
  bezier_net_di(lo, hi, B);
  det_coef_di(B, c);
  for (int q = 0; q < SS_PSI_NCOEF; q++)
    clo[q] = c[q].a, chi[q] = c[q].b;
}

/* de Casteljau's value at t of the n + 1 coefficients b (overwritten) */
static double casteljau(double *b, int n, double t) {
  for (int r = 1; r <= n; r++)
    for (int i = 0; i <= n - r; i++)
      b[i] = (1.0 - t) * b[i] + t * b[i + 1];
  return b[0];
}

double ss_psi_bernstein_eval(const double coef[SS_PSI_NCOEF], double u, double v,
                             double w) {
  double cu[81], cv[9];
  for (int q = 0; q < 81; q++) {
    double b[9];
    memcpy(b, coef + 9 * q, sizeof b);
    cu[q] = casteljau(b, 8, u); /* cu[j + 9k] */
  }
  for (int k = 0; k < 9; k++) {
    double b[9];
    for (int j = 0; j < 9; j++)
      b[j] = cu[j + 9 * k];
    cv[k] = casteljau(b, 8, v);
  }
  return casteljau(cv, 8, w);
}

/* maxdepth in 0..SS_PSI_MAXDEPTH */
static int clamp_depth(int maxdepth) {
  return maxdepth < 0 ? 0 : maxdepth > SS_PSI_MAXDEPTH ? SS_PSI_MAXDEPTH : maxdepth;
}

static void no_verdict(ss_psi_piece_result *r) {
  r->sign = SS_JAC_UNDECIDED;
  r->min_coef = r->max_coef = r->flat = NAN;
}

void ss_psi_piece_sign(const double (*net)[3], int maxdepth, ss_psi_piece_result *r) {
  memset(r, 0, sizeof *r);
  if (!finite_net(net)) {
    no_verdict(r);
    return;
  }
  box_d lv[SS_PSI_MAXDEPTH + 1];
  double B[64][3];
  bezier_net_d(net, B);
  r->flat = flat_of_bezier(B);
  det_coef_d(B, lv[0].c);
  extremes_d(lv[0].c, r);
  piece_sign_d(lv, clamp_depth(maxdepth), r->flat, r);
}

void ss_psi_piece_sign_interval(const double (*lo)[3], const double (*hi)[3],
                                int maxdepth, ss_psi_piece_result *r) {
  memset(r, 0, sizeof *r);
  if (!good_boxes(lo, hi)) {
    no_verdict(r);
    return;
  }
  box_di lv[SS_PSI_MAXDEPTH + 1];
  di_t B[64][3];
  bezier_net_di(lo, hi, B);
  det_coef_di(B, lv[0].c);
  extremes_di(lv[0].c, r);
  piece_sign_di(lv, clamp_depth(maxdepth), 0.0, r);
}

void ss_psi_piece_sign_interval3(const double (*const lo[3])[3],
                                 const double (*const hi[3])[3], int maxdepth,
                                 ss_psi_piece_result *r) {
  memset(r, 0, sizeof *r);
  for (int a = 0; a < 3; a++)
    if (!good_boxes(lo[a], hi[a])) {
      no_verdict(r);
      return;
    }
  box_di lv[SS_PSI_MAXDEPTH + 1];
  di_t B[3][64][3];
  for (int a = 0; a < 3; a++)
    bezier_net_di(lo[a], hi[a], B[a]);
  det_coef3_di(B[0], B[1], B[2], lv[0].c);
  extremes_di(lv[0].c, r);
  piece_sign_di(lv, clamp_depth(maxdepth), 0.0, r);
}
