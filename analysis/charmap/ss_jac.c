/* ss_jac.c — Jacobian sign of one cell's natural interpolant (Bernstein test
 * for hexes) and its scaled Jacobian.  Method: ss_jac.h.
 *
 * The sign machinery is written once, in ss_jac_impl.h, over a tiny number
 * interface (ss_jac_num.h, shared with analysis/psi/), and instantiated twice
 * below: for double (the hot path of the
 * sweeps, whose values of no sign are those below the flat threshold) and for
 * arb's di_t intervals with outward rounding (the certified path).  The scaled
 * Jacobian, a measure and not a proof, is computed in double only. */
#include "ss_jac.h"

#include <math.h>
#include <string.h>

#include "ss_jac_num.h"

enum { SS_JAC_STACK = 8 * 16 + 8 }; /* depth-first: at most 7 pending boxes per level */

/* The corners of a d-cube (ss_cx.h). */
typedef struct {
  unsigned bits[8]; /* bits[k]: the binary coordinates of corner k */
  int index[8];     /* index[b]: the corner with binary coordinates b */
} ss_jac_order;

/* The cube's corner order of ss_cx.h as constants: a quad's corners 0 1 2 3
 * cyclic (corner 2 at bits 11, corner 3 at bits 10), a hex's top face 4 5 6 7
 * the same above them.  The map is its own inverse.  Constants rather than
 * ss_cube_corner_bits calls so that the hex test's Lagrange weights below are
 * compile-time constants (its zero terms vanish from the code) and no cell
 * pays for looking the order up (16 calls per hex, twice); test_jac checks
 * that ss_cube_corner_bits and ss_cube_corner_index agree with it. */
#define QUAD_BITS(k) ((k) == 2 ? 3 : (k) == 3 ? 2 : (k))
#define HEX_BITS(k)  (QUAD_BITS((k)&3) | ((k)&4))
static const ss_jac_order quad_order = {
    {QUAD_BITS(0), QUAD_BITS(1), QUAD_BITS(2), QUAD_BITS(3)},
    {QUAD_BITS(0), QUAD_BITS(1), QUAD_BITS(2), QUAD_BITS(3)}};
static const ss_jac_order hex_order = {
    {HEX_BITS(0), HEX_BITS(1), HEX_BITS(2), HEX_BITS(3), HEX_BITS(4), HEX_BITS(5),
     HEX_BITS(6), HEX_BITS(7)},
    {HEX_BITS(0), HEX_BITS(1), HEX_BITS(2), HEX_BITS(3), HEX_BITS(4), HEX_BITS(5),
     HEX_BITS(6), HEX_BITS(7)}};

/* The weights of the trilinear map's derivatives at the 27 Lagrange points
 * (u, v, w) = (i, j, l) / 2 that start the hex test: d x / d t_a there is the
 * sum over corners k of LAG_W(i + 3 j + 9 l, k, a) times corner k, the weight
 * being the product over axes c of +-1 (c = a, by bit c of the corner's binary
 * coordinates b) or t_c, 1 - t_c (bit c set, clear).  Each is a product of 0,
 * +-1/2 and +-1, exact; written as the formula, not as numbers, so the weights
 * are those of hex_at (which computed them per point and per cell).  Constant
 * expressions: hex_lagrange (ss_jac_impl.h) is written out term by term with
 * them, so the compiler drops the 0 weights (more than half) and no table is
 * read or tested per cell (reading and testing the table was most of the
 * Jacobian test's time). */
#define LW_T(q, bit)                                                                     \
  ((q) == 0 ? ((bit) ? 0.0 : 1.0) : (q) == 1 ? 0.5 : ((bit) ? 1.0 : 0.0))
#define LW_Q(p, c) ((c) == 0 ? (p) % 3 : (c) == 1 ? ((p) / 3) % 3 : (p) / 9)
#define LW_F(p, b, a, c)                                                                 \
  ((a) == (c) ? ((((b) >> (c)) & 1) ? 1.0 : -1.0) : LW_T(LW_Q(p, c), ((b) >> (c)) & 1))
#define LW(p, b, a)    (1.0 * LW_F(p, b, a, 0) * LW_F(p, b, a, 1) * LW_F(p, b, a, 2))
#define LAG_W(p, k, a) LW(p, HEX_BITS(k), a)

/* ---- the sign machinery over double (the number interface: ss_jac_num.h) ---- */

#define NUM        double
#define SUF        d
#define JAC_FLAT   SS_JAC_DEGENERATE
#define JAC_HEX_AT /* ss_jac_hex_at evaluates det J at any point */
#include "ss_jac_impl.h"
#undef NUM
#undef SUF
#undef JAC_FLAT
#undef JAC_HEX_AT

/* ---- the same over intervals (enclosures, outward rounding) ---- */

#define NUM      di_t
#define SUF      di
#define JAC_FLAT SS_JAC_UNDECIDED
#include "ss_jac_impl.h"
#undef NUM
#undef SUF
#undef JAC_FLAT
#undef LAG_W
#undef LW
#undef LW_F
#undef LW_Q
#undef LW_T

/* ---- the interval hex test's quick start ---- */

/* The 27 Lagrange values of det J of the hex x (intervals, hex_order) from
 * its 12 edge vectors (hex_derivs_di): 3 x 9 derivative vectors, each reused
 * at the three points that share it, instead of hex_lagrange_di's sums of
 * about 11 scaled corners per derivative and point.  Other roundings than
 * hex_lagrange_di's (an enclosure of the same values, other last bits). */
static void hex_lagrange_edges(const di_t *x, di_t *v) {
  di_t D[3][9][3];
  hex_derivs_di(x, D);
  for (int p = 0; p < 27; p++) {
    const int t[3] = {p % 3, (p / 3) % 3, p / 9};
    v[p] = det3_di(D[0][t[1] + 3 * t[2]], D[1][t[0] + 3 * t[2]], D[2][t[0] + 3 * t[1]]);
  }
}

/* +1 or -1 when the 27 Bernstein coefficients of the hex x, enclosed from its
 * edges, all have that sign (det J has it on the whole cell), else 0. */
static int hex_quick_sign(const di_t *x) {
  di_t c[27];
  hex_lagrange_edges(x, c);
  bernstein_di(c);
  int pos = 1, neg = 1;
  for (int q = 0; q < 27; q++) {
    pos &= gt0_di(c[q], 0.0);
    neg &= lt0_di(c[q], 0.0);
  }
  return pos ? 1 : neg ? -1 : 0;
}

/* ---- the interval hex test's first try: one evaluation at the midpoints ---- */

/* ss_jac.h.  Let u = 2^-53 and gamma_k = k u / (1 - k u) (rounding to
 * nearest; Higham, Accuracy and Stability, 3.1: a straight-line program of
 * sums and products whose paths hold at most k roundings errs by at most
 * gamma_k times the same program on the inputs' magnitudes with every sign
 * made +).
 *  1. Corners: m = the midpoints, R >= max |x - m| over coordinates and
 *     boxes (max(hi - m, m - lo), computed).
 *  2. Derivatives (hex_derivs_d at m): each exact D(x) combines corners with
 *     magnitudes summing to 2, so |D(x) - D(m)| <= 2 R; D~ = fl(D(m)) has
 *     one subtraction then at most two halved sums (the halving exact), so
 *     |D~ - D(m)| <= gamma_3 Dmax, Dmax the largest |D~| (an edge: the
 *     edges are among the D~, every D~ an average of them).  So every entry
 *     of D(x) is within e = 2 R + gamma_3 Dmax (1 + u) of D~.
 *  3. det J at point p: with a = the largest |D~| entry at p,
 *     |det D(x) - det D~| <= perm(|D~| + e) - perm(|D~|) <= 6((a + e)^3 - a^3)
 *     (det is multilinear; perm is increasing), and det3_d's rounding
 *     (5 per path, magnitudes perm(|D~|) <= 6 a^3) <= gamma_5 6 a^3: so
 *     |det J(x)(p) - v~_p| <= e_p = 6 e (3 a^2 + 3 a e + e^2) + 31 u a^3.
 *  4. Bernstein coefficients c = B v (bernstein_d: 2 roundings per axis):
 *     |c(x) - c~| <= |B| (e + gamma_6 |v~|) =: E, |B| the same transform
 *     with its -1/2 made +1/2.
 * Every bound above is a sum or product of nonnegative doubles whose own
 * rounding is below 40 u relatively: E is multiplied by 1 + 2^-20.
 * Underflow (absolute error <= 2^-1074 an operation, at most 2^101-fold
 * amplified below) is covered by adding 2^-900 to every e_p; entries above
 * 2^100 or a cell below 2^-300 (Dmax) are not tried. */
int ss_jac_hex_midrad(const double *lo, const double *hi, double *c, double *E) {
  const double u = 0x1p-53, g3 = 3.0 * u / (1.0 - 3.0 * u),
               g6 = 6.0 * u / (1.0 - 6.0 * u);
  double m[24], R = 0.0;
  for (int i = 0; i < 24; i++) {
    if (!(isfinite(lo[i]) && isfinite(hi[i]) && lo[i] <= hi[i])) return 0;
    m[i] = 0.5 * lo[i] + 0.5 * hi[i];
    R = FLINT_MAX(R, FLINT_MAX(hi[i] - m[i], m[i] - lo[i]));
  }
  double D[3][9][3], dmax = 0.0;
  hex_derivs_d(m, D);
  for (int a = 0; a < 3; a++)
    for (int i = 0; i < 9; i++)
      for (int r = 0; r < 3; r++)
        dmax = FLINT_MAX(dmax, fabs(D[a][i][r]));
  if (!(dmax <= 0x1p100) || dmax < 0x1p-300 || !(R <= 0x1p100)) return 0;
  const double e = 2.0 * R + g3 * dmax * (1.0 + u);
  for (int p = 0; p < 27; p++) {
    const int t[3] = {p % 3, (p / 3) % 3, p / 9};
    const double *d0 = D[0][t[1] + 3 * t[2]], *d1 = D[1][t[0] + 3 * t[2]],
                 *d2 = D[2][t[0] + 3 * t[1]];
    double a = 0.0;
    for (int r = 0; r < 3; r++)
      a = FLINT_MAX(a, FLINT_MAX(fabs(d0[r]), FLINT_MAX(fabs(d1[r]), fabs(d2[r]))));
    c[p] = det3_d(d0, d1, d2);
    E[p] = 6.0 * e * (3.0 * a * a + 3.0 * a * e + e * e) + 31.0 * u * a * a * a +
           0x1p-900 + g6 * fabs(c[p]);
  }
  bernstein_d(c);
  for (int ax = 0, stride = 1; ax < 3; ax++, stride *= 3) /* |B| */
    for (int w = 0; w < 9; w++) {
      const int q = line_start_d(ax, w) + stride;
      E[q] = 2.0 * E[q] + 0.5 * (E[q - stride] + E[q + stride]);
    }
  int pos = 1, neg = 1;
  for (int q = 0; q < 27; q++) {
    E[q] *= 1.0 + 0x1p-20;
    pos &= c[q] > E[q];
    neg &= c[q] < -E[q];
  }
  return pos ? 1 : neg ? -1 : 0;
}

/* ---- the scaled Jacobian (double) ---- */

/* The length of a, as hypot folded over the coordinates from 0: the first
 * step hypot(0, a[0]) is |a[0]| exactly (a representable result, which a
 * faithful hypot returns), so it starts there and calls hypot d - 1 times,
 * with the same doubles as before. */
static double norm(const double *a, int d) {
  double s = fabs(a[0]);
  for (int i = 1; i < d; i++)
    s = hypot(s, a[i]);
  return s;
}

/* det/product of the lengths la, lb, lc of a, b, c; 0 when one is 0 */
static double scaled3_len(const double *a, const double *b, const double *c, double la,
                          double lb, double lc) {
  const double l = la * lb * lc;
  return l > 0.0 ? det3_d(a, b, c) / l : 0.0;
}

static void see_scaled(ss_jac_result *r, double s) {
  r->min_scaled = fmin(r->min_scaled, s);
  r->max_scaled = fmax(r->max_scaled, s);
}

/* min_scaled and max_scaled of a cell whose type and dim were checked */
static void measures(ss_cell_type t, const double *x, ss_jac_result *r) {
  r->min_scaled = INFINITY;
  r->max_scaled = -INFINITY;
  if (t == SS_HEX) {
    const ss_jac_order *o = &hex_order;
    /* each of the 12 edges is in the frames of its two ends, as the same
     * difference: its length once (hypot was most of the measure's time),
     * len[i][b] for the edge along axis i from the corner of bits b */
    double len[3][8];
    for (int i = 0; i < 3; i++)
      for (unsigned b = 0; b < 8; b++)
        if (!(b & (1u << i))) {
          double a[3];
          diff_d(3, x + 3 * o->index[b | (1u << i)], x + 3 * o->index[b], a);
          len[i][b] = norm(a, 3);
        }
    for (int k = 0; k < 8; k++) {
      double e[3][3];
      corner_frame_d(x, 3, o, k, e);
      const unsigned b = o->bits[k];
      see_scaled(r, scaled3_len(e[0], e[1], e[2], len[0][b & ~1u], len[1][b & ~2u],
                                len[2][b & ~4u]));
    }
  } else if (t == SS_QUAD) {
    for (int k = 0; k < 4; k++) {
      double e[3][3];
      corner_frame_d(x, 2, &quad_order, k, e);
      const double d = det2_d(e[0], e[1]), l = norm(e[0], 2) * norm(e[1], 2);
      see_scaled(r, l > 0.0 ? d / l : 0.0);
    }
  } else if (t == SS_TET || t == SS_TRIANGLE) {
    /* the same determinant at every corner; normalised by that corner's edges,
     * times sqrt(2) (tet) or 2/sqrt(3) (triangle) */
    const int d = t == SS_TET ? 3 : 2, n = d + 1;
    double e[3][3];
    for (int i = 0; i < d; i++)
      diff_d(d, x + d * (i + 1), x, e[i]);
    const double det = d == 3 ? det3_d(e[0], e[1], e[2]) : det2_d(e[0], e[1]);
    const double f = d == 3 ? sqrt(2.0) : 2.0 / sqrt(3.0);
    /* each edge's length once, len[c][j] = len[j][c]: x_j - x_c and x_c - x_j
     * are the same difference negated (rounding to nearest is symmetric) and
     * the length takes |.| of each coordinate first, so both corners see the
     * same bits as when each computed its own (half the hypot calls) */
    double len[4][4];
    for (int c = 0; c < n; c++)
      for (int j = c + 1; j < n; j++) {
        double a[3];
        diff_d(d, x + d * j, x + d * c, a);
        len[c][j] = len[j][c] = norm(a, d);
      }
    for (int c = 0; c < n; c++) {
      double l = 1.0;
      for (int j = 0; j < n; j++)
        if (j != c) l *= len[c][j];
      see_scaled(r, l > 0.0 ? f * det / l : 0.0);
    }
  } else { /* SS_OCT */
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 6; k++)
      for (int i = 0; i < 3; i++)
        c[i] += x[3 * k + i] / 6.0;
    /* each vertex's vector from the centroid and its length once: every one
     * is in four of the eight octants (6 lengths instead of 24) */
    double v[6][3], len[6];
    for (int k = 0; k < 6; k++) {
      diff_d(3, x + 3 * k, c, v[k]);
      len[k] = norm(v[k], 3);
    }
    for (int f = 0; f < 8; f++) {
      const int s0 = (f & 1) ? 3 : 0, s1 = (f & 2) ? 4 : 1, s2 = (f & 4) ? 5 : 2;
      const int flips = (f & 1) + ((f >> 1) & 1) + ((f >> 2) & 1);
      const double s = scaled3_len(v[s0], v[s1], v[s2], len[s0], len[s1], len[s2]);
      see_scaled(r, (flips & 1) ? -s : s);
    }
  }
}

/* ---- the entry points ---- */

double ss_jac_hex_at(const double *x, double u, double v, double w) {
  return hex_at_d(x, &hex_order, u, v, w);
}

/* The number of coordinates of a cell of type t in dim dimensions, 0 when the
 * pair is not one ss_jac handles. */
static int ncoords(ss_cell_type t, int dim) {
  const int need = t == SS_HEX || t == SS_TET || t == SS_OCT ? 3
                   : t == SS_QUAD || t == SS_TRIANGLE        ? 2
                                                             : 0;
  return need && dim == need ? need * ss_cell_nverts(t) : 0;
}

static void no_verdict(ss_jac_result *r) {
  r->sign = SS_JAC_UNDECIDED;
  r->min_scaled = r->max_scaled = NAN;
}

/* SS_JAC_FLAT L^dim, L the largest distance between two of the n corners */
static double flat_threshold(const double *x, int n, int dim) {
  double l2 = 0.0;
  for (int p = 0; p < n; p++)
    for (int q = p + 1; q < n; q++) {
      double s = 0.0;
      for (int i = 0; i < dim; i++) {
        const double d = x[dim * p + i] - x[dim * q + i];
        s += d * d;
      }
      l2 = s > l2 ? s : l2;
    }
  return SS_JAC_FLAT * (dim == 3 ? l2 * sqrt(l2) : l2);
}

void ss_jac_cell(ss_cell_type t, const double *x, int dim, int maxdepth,
                 ss_jac_result *r) {
  memset(r, 0, sizeof *r);
  const int n = ncoords(t, dim);
  int finite = n > 0;
  for (int i = 0; i < n; i++)
    finite &= isfinite(x[i]) != 0;
  if (!finite) {
    no_verdict(r);
    return;
  }
  measures(t, x, r);
  cell_sign_d(t, x, maxdepth, flat_threshold(x, n / dim, dim), r);
}

/* The corners' intervals of an interval cell into xi and their midpoints
 * into mid; 0 when a bound is not finite or lo[i] > hi[i] (r set to no
 * verdict), else the number of coordinates. */
static int interval_corners(ss_cell_type t, const double *lo, const double *hi, int dim,
                            di_t *xi, double *mid, ss_jac_result *r) {
  memset(r, 0, sizeof *r);
  const int n = ncoords(t, dim);
  int ok = n > 0;
  /* finite and ordered: di_t needs a <= b, and an infinite end proves nothing */
  for (int i = 0; i < n; i++)
    ok &= isfinite(lo[i]) && isfinite(hi[i]) && lo[i] <= hi[i];
  if (!ok) {
    no_verdict(r);
    return 0;
  }
  for (int i = 0; i < n; i++) {
    xi[i].a = lo[i];
    xi[i].b = hi[i];
    mid[i] = 0.5 * lo[i] + 0.5 * hi[i]; /* in [lo, hi], no overflow */
  }
  return n;
}

void ss_jac_cell_interval(ss_cell_type t, const double *lo, const double *hi, int dim,
                          int maxdepth, ss_jac_result *r) {
  di_t xi[SS_MAXCELLVERTS * 3];
  double mid[SS_MAXCELLVERTS * 3];
  if (!interval_corners(t, lo, hi, dim, xi, mid, r)) return;
  measures(t, mid, r);
  cell_sign_di(t, xi, maxdepth, 0.0, r);
}

void ss_jac_cell_interval_sign(ss_cell_type t, const double *lo, const double *hi,
                               int dim, int maxdepth, ss_jac_result *r) {
  di_t xi[SS_MAXCELLVERTS * 3];
  double mid[SS_MAXCELLVERTS * 3];
  if (!interval_corners(t, lo, hi, dim, xi, mid, r)) return;
  r->min_scaled = r->max_scaled = NAN;
  int s = 0;
  if (t == SS_HEX && dim == 3) {
    double c[27], E[27];
    s = ss_jac_hex_midrad(lo, hi, c, E);
    if (!s) s = hex_quick_sign(xi);
  }
  if (s) {
    r->sign = s > 0 ? SS_JAC_POSITIVE : SS_JAC_NEGATIVE;
    return;
  }
  cell_sign_di(t, xi, maxdepth, 0.0, r);
}
