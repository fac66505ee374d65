/* test_jac.c — the Jacobian sign of one cell (ss_jac): ideal cells score 1,
 * orientation flips the sign, similarities keep the scaled Jacobian, and the
 * Bernstein test classifies hexes correctly, including one that folds inside
 * although its eight corner Jacobians are positive (the case corner checks
 * miss) and one that is positive but needs subdivision to show it.  Every
 * hex verdict is checked against dense sampling of det J.
 *
 * Values with no sign: flat cells (det J = 0 mathematically, computed as 0 or
 * as rounding noise) are DEGENERATE, a cell with one exact value zero is
 * UNDECIDED, not FOLDED, unless clear values prove a fold.
 *
 * The interval test (ss_jac_cell_interval) agrees with the double one for
 * tight boxes; its proofs hold for random nets drawn in the boxes (det J
 * sampled by a formula written independently here); widened boxes end in
 * UNDECIDED, never in a wrong proof.  The certified path's variant
 * (ss_jac_cell_interval_sign, a quicker first enclosure for hexes) never
 * contradicts it nor sampling. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_jac.h"
#include "ss_test.h"

/* deterministic uniform numbers in [-1, 1) */
static double rnd(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}

/* 64 deterministic random bits */
static uint64_t seed_bits(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return *s;
}

static void unit_cube(double *x) {
  for (int k = 0; k < 8; k++) {
    const unsigned b = ss_cube_corner_bits(3, k);
    for (int i = 0; i < 3; i++)
      x[3 * k + i] = (double)((b >> i) & 1u);
  }
}

/* min and max of det J over an (m+1)^3 grid; corner values separately */
static void sample(const double *x, int m, double *mn, double *mx, double *cmin) {
  *mn = INFINITY, *mx = -INFINITY, *cmin = INFINITY;
  for (int i = 0; i <= m; i++)
    for (int j = 0; j <= m; j++)
      for (int k = 0; k <= m; k++) {
        const double v = ss_jac_hex_at(x, (double)i / m, (double)j / m, (double)k / m);
        *mn = fmin(*mn, v), *mx = fmax(*mx, v);
        if ((i == 0 || i == m) && (j == 0 || j == m) && (k == 0 || k == m))
          *cmin = fmin(*cmin, v);
      }
}

/* x -> s R x + t with R a rotation (from a random unit quaternion) and
 * optionally a reflection of the first axis */
static void similarity(const double *x, int n, uint64_t *seed, int reflect, double *y) {
  double q[4], nq = 0;
  for (int i = 0; i < 4; i++)
    q[i] = rnd(seed), nq += q[i] * q[i];
  nq = sqrt(nq);
  for (int i = 0; i < 4; i++)
    q[i] /= nq;
  const double a = q[0], b = q[1], c = q[2], d = q[3];
  const double R[3][3] = {
      {a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
      {2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)},
      {2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d}};
  const double s = 0.3 + 2.0 * fabs(rnd(seed)), t[3] = {rnd(seed), rnd(seed), rnd(seed)};
  for (int p = 0; p < n; p++) {
    double v[3] = {x[3 * p], x[3 * p + 1], x[3 * p + 2]};
    if (reflect) v[0] = -v[0];
    for (int i = 0; i < 3; i++)
      y[3 * p + i] = s * (R[i][0] * v[0] + R[i][1] * v[1] + R[i][2] * v[2]) + t[i];
  }
}

static void test_ideal_cells(void) {
  ss_jac_result r;
  double x[24];
  unit_cube(x);
  ss_jac_cell(SS_HEX, x, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_POSITIVE && r.depth == 0, "unit cube: sign %d depth %d", r.sign,
        r.depth);
  CHECK_CLOSE(r.min_scaled, 1.0, 1e-14, "unit cube");
  CHECK_CLOSE(r.max_scaled, 1.0, 1e-14, "unit cube");
  /* top and bottom faces swapped: the mirror image */
  double y[24];
  memcpy(y, x + 12, 12 * sizeof *y);
  memcpy(y + 12, x, 12 * sizeof *y);
  ss_jac_cell(SS_HEX, y, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_NEGATIVE, "mirrored cube: sign %d", r.sign);
  CHECK_CLOSE(r.max_scaled, -1.0, 1e-14, "mirrored cube");
  /* regular tet, triangle, octahedron, square */
  const double tet[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
  ss_jac_cell(SS_TET, tet, 3, 0, &r);
  CHECK(r.sign == SS_JAC_POSITIVE || r.sign == SS_JAC_NEGATIVE, "tet sign %d", r.sign);
  const double s0 = r.sign == SS_JAC_POSITIVE ? r.min_scaled : -r.max_scaled;
  CHECK_CLOSE(s0, 1.0, 1e-12, "regular tet");
  double tet2[12];
  memcpy(tet2, tet, sizeof tet2);
  memcpy(tet2 + 3, tet + 6, 3 * sizeof *tet2);
  memcpy(tet2 + 6, tet + 3, 3 * sizeof *tet2);
  ss_jac_result r2;
  ss_jac_cell(SS_TET, tet2, 3, 0, &r2);
  CHECK((int)r2.sign == -(int)r.sign, "swapped tet: %d vs %d", r2.sign, r.sign);
  /* det exactly 0: no sign, flat (it was FOLDED under the old rule) */
  const double flat[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  ss_jac_cell(SS_TET, flat, 3, 0, &r);
  CHECK(r.sign == SS_JAC_DEGENERATE, "flat tet: %d", r.sign);
  const double tri[6] = {0, 0, 1, 0, 0.5, sqrt(3.0) / 2};
  ss_jac_cell(SS_TRIANGLE, tri, 2, 0, &r);
  CHECK(r.sign == SS_JAC_POSITIVE, "triangle: %d", r.sign);
  CHECK_CLOSE(r.min_scaled, 1.0, 1e-12, "equilateral triangle");
  const double oct[18] = {1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
  ss_jac_cell(SS_OCT, oct, 3, 0, &r);
  CHECK(r.sign == SS_JAC_POSITIVE, "regular octahedron: %d", r.sign);
  CHECK_CLOSE(r.min_scaled, 1.0, 1e-12, "regular octahedron");
  double oct2[18];
  memcpy(oct2, oct, sizeof oct2);
  oct2[2 * 3 + 2] = -0.5; /* +z pushed below the centre: the upper octants flip */
  ss_jac_cell(SS_OCT, oct2, 3, 0, &r);
  CHECK(r.sign == SS_JAC_FOLDED, "squashed octahedron: %d", r.sign);
  const double sq[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  ss_jac_cell(SS_QUAD, sq, 2, 0, &r);
  CHECK(r.sign == SS_JAC_POSITIVE, "square: %d", r.sign);
  CHECK_CLOSE(r.min_scaled, 1.0, 1e-14, "square");
  const double bowtie[8] = {0, 0, 1, 0, 0, 1, 1, 1};
  ss_jac_cell(SS_QUAD, bowtie, 2, 0, &r);
  CHECK(r.sign == SS_JAC_FOLDED, "bow-tie quad: %d", r.sign);
  const double dart[8] = {0, 0, 2, 0, 0.5, 0.5, 0, 2}; /* reflex corner 2 */
  ss_jac_cell(SS_QUAD, dart, 2, 0, &r);
  CHECK(r.sign == SS_JAC_FOLDED && r.where[0] == 1.0 && r.where[1] == 1.0,
        "dart quad: %d at (%g, %g)", r.sign, r.where[0], r.where[1]);
  /* wrong dimension */
  ss_jac_cell(SS_HEX, x, 2, 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && isnan(r.min_scaled), "hex in 2D: %d", r.sign);
}

static void test_similarity(void) {
  uint64_t seed = 42;
  double cube[24];
  unit_cube(cube);
  const double oct[18] = {1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
  for (int t = 0; t < 50; t++) {
    double base[24], y[24];
    for (int i = 0; i < 24; i++)
      base[i] = cube[i] + 0.2 * rnd(&seed); /* a general, valid hex */
    ss_jac_result r0, r1;
    ss_jac_cell(SS_HEX, base, 3, SS_JAC_DEPTH, &r0);
    const int reflect = t & 1;
    similarity(base, 8, &seed, reflect, y);
    ss_jac_cell(SS_HEX, y, 3, SS_JAC_DEPTH, &r1);
    CHECK(r0.sign == SS_JAC_POSITIVE && (int)r1.sign == (reflect ? -1 : 1),
          "hex %d: sign %d -> %d (reflect %d)", t, r0.sign, r1.sign, reflect);
    const double m1 = reflect ? -r1.max_scaled : r1.min_scaled;
    CHECK_CLOSE(m1, r0.min_scaled, 1e-12, "hex %d: scaled Jacobian under a similarity",
                t);
    double o[18], oy[18];
    for (int i = 0; i < 18; i++)
      o[i] = oct[i] + 0.15 * rnd(&seed);
    ss_jac_cell(SS_OCT, o, 3, 0, &r0);
    similarity(o, 6, &seed, reflect, oy);
    ss_jac_cell(SS_OCT, oy, 3, 0, &r1);
    CHECK(r0.sign == SS_JAC_POSITIVE && (int)r1.sign == (reflect ? -1 : 1),
          "oct %d: sign %d -> %d", t, r0.sign, r1.sign);
    CHECK_CLOSE(reflect ? -r1.max_scaled : r1.min_scaled, r0.min_scaled, 1e-12,
                "oct %d: scaled Jacobian under a similarity", t);
  }
}

static void test_bernstein(void) {
  ss_jac_result r;
  double mn, mx, cmin;
  /* positive at all eight corners, negative inside (found by a random search,
   * coordinates in eighths) */
  const double fold[24] = {-0.625, -0.75,  -0.25, 1.75,  -0.25, 0,     0.25,  0.5,
                           -0.625, -0.125, 0.5,   -0.5,  -0.75, 0.375, 1,     0.375,
                           -0.25,  0.375,  0.25,  0.625, 1.75,  0,     1.375, 1.125};
  sample(fold, 40, &mn, &mx, &cmin);
  CHECK(cmin > 0.0 && mn < 0.0, "folding hex: corners min %g, interior min %g", cmin, mn);
  ss_jac_cell(SS_HEX, fold, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_FOLDED, "folding hex: sign %d", r.sign);
  CHECK(ss_jac_hex_at(fold, r.where[0], r.where[1], r.where[2]) <= 0.0,
        "folding hex: the reported point (%g %g %g) has det J %g", r.where[0], r.where[1],
        r.where[2], ss_jac_hex_at(fold, r.where[0], r.where[1], r.where[2]));
  ss_jac_cell(SS_HEX, fold, 3, 0, &r);
  CHECK(r.sign != SS_JAC_POSITIVE, "folding hex at depth 0: sign %d", r.sign);
  /* positive everywhere, but some of the 27 coefficients are negative */
  const double deep[24] = {0.625, 0.125, 0.25,  0.625, 0.25,   0.5,    1.25, 0.5,
                           0.25,  0.125, 0.875, 0.375, -0.625, -0.125, 1,    0.875,
                           0.5,   0.5,   0.625, 1,     0.75,   -0.125, 1.25, 0.625};
  sample(deep, 40, &mn, &mx, &cmin);
  CHECK(mn > 0.0, "deep hex: sampled min %g", mn);
  ss_jac_cell(SS_HEX, deep, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_POSITIVE && r.depth > 0, "deep hex: sign %d depth %d", r.sign,
        r.depth);
  ss_jac_cell(SS_HEX, deep, 3, 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED, "deep hex at depth 0: sign %d", r.sign);
  /* an inverted hex: one corner pushed through the opposite face */
  double inv[24];
  unit_cube(inv);
  inv[3 * 6 + 0] = inv[3 * 6 + 1] = inv[3 * 6 + 2] = -0.5; /* corner (1,1,1) */
  ss_jac_cell(SS_HEX, inv, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_FOLDED && r.min_scaled < 0.0, "inverted hex: sign %d, scaled %g",
        r.sign, r.min_scaled);
  /* many random hexes near degeneracy: the verdict never contradicts sampling */
  uint64_t seed = 7;
  int counts[5] = {0, 0, 0, 0, 0};
  for (int t = 0; t < 400; t++) {
    double x[24];
    unit_cube(x);
    for (int i = 0; i < 24; i++)
      x[i] += 0.55 * rnd(&seed);
    ss_jac_cell(SS_HEX, x, 3, SS_JAC_DEPTH, &r);
    sample(x, 16, &mn, &mx, &cmin);
    const double scale = fmax(fabs(mn), fabs(mx));
    if (r.sign == SS_JAC_POSITIVE)
      CHECK(mn > 0.0, "random hex %d: positive but sampled min %g", t, mn);
    else if (r.sign == SS_JAC_NEGATIVE)
      CHECK(mx < 0.0, "random hex %d: negative but sampled max %g", t, mx);
    else if (r.sign == SS_JAC_FOLDED)
      CHECK((mn <= 0.0 && mx >= 0.0) ||
                ss_jac_hex_at(x, r.where[0], r.where[1], r.where[2]) * mx <= 0.0,
            "random hex %d: folded but sampled in [%g, %g]", t, mn, mx);
    else
      CHECK(fmin(fabs(mn), fabs(mx)) < 1e-2 * scale || (mn < 0.0 && mx > 0.0),
            "random hex %d: undecided though far from 0: [%g, %g]", t, mn, mx);
    CHECK(r.sign != SS_JAC_DEGENERATE, "random hex %d: degenerate", t);
    counts[r.sign + 1]++;
  }
  CHECK(counts[1] > 20 && counts[2] > 20, "random hexes: %d folded, %d positive",
        counts[1], counts[2]);
}

/* ---- references written independently of ss_jac ---- */

/* the corner of a d-cube x with binary coordinates b (bit i: parameter i) */
static const double *cube_pt(const double *x, int d, unsigned b) {
  return x + d * ss_cube_corner_index(d, b);
}

static double sarrus(double J[3][3]) {
  return J[0][0] * J[1][1] * J[2][2] + J[0][1] * J[1][2] * J[2][0] +
         J[0][2] * J[1][0] * J[2][1] - J[0][2] * J[1][1] * J[2][0] -
         J[0][0] * J[1][2] * J[2][1] - J[0][1] * J[1][0] * J[2][2];
}

/* det J of the trilinear map at t: d x / d t_i as the bilinear blend of the
 * four edges along parameter i */
static double ref_hex(const double *x, const double *t) {
  double J[3][3];
  for (int i = 0; i < 3; i++) {
    const int j1 = (i + 1) % 3, j2 = (i + 2) % 3;
    for (int r = 0; r < 3; r++)
      J[i][r] = 0.0;
    for (unsigned a = 0; a < 2; a++)
      for (unsigned b = 0; b < 2; b++) {
        const double wt = (a ? t[j1] : 1.0 - t[j1]) * (b ? t[j2] : 1.0 - t[j2]);
        const unsigned base = (a << j1) | (b << j2);
        const double *p1 = cube_pt(x, 3, base | (1u << i)), *p0 = cube_pt(x, 3, base);
        for (int r = 0; r < 3; r++)
          J[i][r] += wt * (p1[r] - p0[r]);
      }
  }
  return sarrus(J);
}

/* det J of the bilinear map at (u, v) */
static double ref_quad(const double *x, double u, double v) {
  double du[2], dv[2];
  for (int r = 0; r < 2; r++) {
    du[r] = (1.0 - v) * (cube_pt(x, 2, 1)[r] - cube_pt(x, 2, 0)[r]) +
            v * (cube_pt(x, 2, 3)[r] - cube_pt(x, 2, 2)[r]);
    dv[r] = (1.0 - u) * (cube_pt(x, 2, 2)[r] - cube_pt(x, 2, 0)[r]) +
            u * (cube_pt(x, 2, 3)[r] - cube_pt(x, 2, 1)[r]);
  }
  return du[0] * dv[1] - du[1] * dv[0];
}

/* octant f's determinant (centroid, one vertex of each opposite pair),
 * oriented so that the octahedron +x +y +z -x -y -z scores +1 in all eight */
static double ref_octant(const double *x, int f) {
  double c[3] = {0, 0, 0}, J[3][3];
  for (int k = 0; k < 6; k++)
    for (int i = 0; i < 3; i++)
      c[i] += x[3 * k + i] / 6.0;
  for (int p = 0; p < 3; p++) {
    const int v = ((f >> p) & 1) ? p + 3 : p;
    for (int i = 0; i < 3; i++)
      J[p][i] = x[3 * v + i] - c[i];
  }
  const int odd = (f & 1) ^ ((f >> 1) & 1) ^ ((f >> 2) & 1);
  return odd ? -sarrus(J) : sarrus(J);
}

/* The range of det J's values: hex and quad on an (m+1)^d grid (which holds
 * the corners), tet and triangle their determinant, oct its eight octants. */
static void ref_range(ss_cell_type t, const double *x, int m, double *mn, double *mx) {
  *mn = INFINITY, *mx = -INFINITY;
  if (t == SS_HEX) {
    for (int i = 0; i <= m; i++)
      for (int j = 0; j <= m; j++)
        for (int k = 0; k <= m; k++) {
          const double p[3] = {(double)i / m, (double)j / m, (double)k / m};
          const double v = ref_hex(x, p);
          *mn = fmin(*mn, v), *mx = fmax(*mx, v);
        }
  } else if (t == SS_QUAD) {
    for (int i = 0; i <= m; i++)
      for (int j = 0; j <= m; j++) {
        const double v = ref_quad(x, (double)i / m, (double)j / m);
        *mn = fmin(*mn, v), *mx = fmax(*mx, v);
      }
  } else if (t == SS_TET) {
    double J[3][3];
    for (int p = 0; p < 3; p++)
      for (int i = 0; i < 3; i++)
        J[p][i] = x[3 * (p + 1) + i] - x[i];
    *mn = *mx = sarrus(J);
  } else if (t == SS_TRIANGLE) {
    *mn = *mx = (x[2] - x[0]) * (x[5] - x[1]) - (x[3] - x[1]) * (x[4] - x[0]);
  } else {
    for (int f = 0; f < 8; f++) {
      const double v = ref_octant(x, f);
      *mn = fmin(*mn, v), *mx = fmax(*mx, v);
    }
  }
}

/* det J at a FOLDED verdict's point (hex, quad) */
static double ref_at(ss_cell_type t, const double *x, const double *w) {
  return t == SS_HEX ? ref_hex(x, w) : ref_quad(x, w[0], w[1]);
}

static int nvals(ss_cell_type t) {
  return t == SS_HEX ? 24 : t == SS_OCT ? 18 : t == SS_TET ? 12 : t == SS_QUAD ? 8 : 6;
}

static int tdim(ss_cell_type t) {
  return t == SS_QUAD || t == SS_TRIANGLE ? 2 : 3;
}

/* the interval verdict for boxes of radius rad around x */
static void jac_box(ss_cell_type t, const double *x, double rad, int depth,
                    ss_jac_result *r) {
  double lo[24], hi[24];
  for (int i = 0; i < nvals(t); i++)
    lo[i] = x[i] - rad, hi[i] = x[i] + rad;
  ss_jac_cell_interval(t, lo, hi, tdim(t), depth, r);
}

/* the tight radius: 1e-14 relative to the largest coordinate */
static double tight(ss_cell_type t, const double *x) {
  double s = 0.0;
  for (int i = 0; i < nvals(t); i++)
    s = fmax(s, fabs(x[i]));
  return 1e-14 * s;
}

/* a random net in the boxes of radius rad around x: each coordinate at an end
 * of its interval or inside it */
static void net_in_box(ss_cell_type t, const double *x, double rad, uint64_t *seed,
                       double *y) {
  for (int i = 0; i < nvals(t); i++) {
    const double u = rnd(seed), lo = x[i] - rad, hi = x[i] + rad;
    y[i] = u < -0.5 ? lo : u > 0.5 ? hi : fmin(hi, fmax(lo, x[i] + 2.0 * u * rad));
  }
}

/* Whether the certified verdict r holds for the net y by sampling; 1 for
 * UNDECIDED.  FOLDED: det J at r->where has a sign opposite to one of the
 * cell's corner values (the proof's two exact values). */
static int holds(ss_cell_type t, const double *y, const ss_jac_result *r) {
  double mn, mx;
  ref_range(t, y, t == SS_HEX ? 12 : 16, &mn, &mx);
  switch (r->sign) {
  case SS_JAC_POSITIVE:
    return mn > 0.0;
  case SS_JAC_NEGATIVE:
    return mx < 0.0;
  case SS_JAC_FOLDED:
    if (t == SS_HEX || t == SS_QUAD) {
      const double v = ref_at(t, y, r->where);
      return v > 0.0 ? mn < 0.0 : v < 0.0 ? mx > 0.0 : 0;
    }
    return t == SS_OCT && mn < 0.0 && mx > 0.0;
  default:
    return r->sign == SS_JAC_UNDECIDED;
  }
}

/* the verdict of sampling alone: +-1 one sign, 0 both signs, 2 a zero */
static int sampled_sign(ss_cell_type t, const double *y) {
  double mn, mx;
  ref_range(t, y, t == SS_HEX ? 12 : 16, &mn, &mx);
  return mn > 0.0 ? 1 : mx < 0.0 ? -1 : mn < 0.0 && mx > 0.0 ? 0 : 2;
}

/* ---- the cells of the tests ---- */

static const double fold_hex[24] = {
    -0.625, -0.75, -0.25, 1.75,  -0.25, 0,     0.25, 0.5,   -0.625, -0.125, 0.5,   -0.5,
    -0.75,  0.375, 1,     0.375, -0.25, 0.375, 0.25, 0.625, 1.75,   0,      1.375, 1.125};
static const double deep_hex[24] = {
    0.625,  0.125,  0.25, 0.625, 0.25, 0.5, 1.25,  0.5, 0.25, 0.125,  0.875, 0.375,
    -0.625, -0.125, 1,    0.875, 0.5,  0.5, 0.625, 1,   0.75, -0.125, 1.25,  0.625};
static const double reg_tet[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
static const double reg_oct[18] = {1,  0, 0, 0, 1,  0, 0, 0, 1,
                                   -1, 0, 0, 0, -1, 0, 0, 0, -1};
static const double square[8] = {0, 0, 1, 0, 1, 1, 0, 1};
static const double eq_tri[6] = {0, 0, 1, 0, 0.5, 0.8660254037844386};

static void test_reference(void) {
  /* the test's own det J agrees with ss_jac_hex_at, and the Bernstein test's
   * hexes are what the comments say they are */
  uint64_t seed = 11;
  double worst = 0.0;
  for (int t = 0; t < 200; t++) {
    double x[24];
    unit_cube(x);
    for (int i = 0; i < 24; i++)
      x[i] += 0.5 * rnd(&seed);
    const double p[3] = {0.5 + 0.5 * rnd(&seed), 0.5 + 0.5 * rnd(&seed),
                         0.5 + 0.5 * rnd(&seed)};
    worst = fmax(worst, fabs(ss_jac_hex_at(x, p[0], p[1], p[2]) - ref_hex(x, p)));
  }
  CHECK(worst < 1e-13, "ss_jac_hex_at vs the bilinear blend of edges: %g", worst);
  double mn, mx;
  ref_range(SS_HEX, fold_hex, 40, &mn, &mx);
  CHECK(mn < 0.0 && mx > 0.0, "folding hex: [%g, %g]", mn, mx);
  ref_range(SS_HEX, deep_hex, 40, &mn, &mx);
  CHECK(mn > 0.0, "deep hex: min %g", mn);
  ref_range(SS_OCT, reg_oct, 0, &mn, &mx);
  CHECK(mn == 1.0 && mx == 1.0, "regular octahedron's octants: [%g, %g]", mn, mx);
}

/* The test's own scaled Jacobian of a tet or an octahedron (ss_jac.h): each
 * corner's (tet) or octant's (octahedron, at the centroid) determinant over
 * the product of its edges' lengths, the lengths as sqrt of a sum of squares
 * and each computed where it is used, not shared; extremes into *mn, *mx. */
static void ref_scaled(ss_cell_type t, const double *x, double *mn, double *mx) {
  *mn = INFINITY, *mx = -INFINITY;
  const int n = t == SS_TET ? 4 : 8;
  double c[3] = {0, 0, 0};
  for (int k = 0; t == SS_OCT && k < 6; k++)
    for (int i = 0; i < 3; i++)
      c[i] += x[3 * k + i] / 6.0;
  for (int f = 0; f < n; f++) {
    double e[3][3], s = 1.0, l = 1.0;
    if (t == SS_TET) { /* corner f: the edges to the other three, in order */
      for (int j = 0, m = 0; j < 4; j++)
        for (int i = 0; j != f && i < 3; i++)
          e[m][i] = x[3 * j + i] - x[3 * f + i], m += i == 2;
      s = (f & 1) ? -sqrt(2.0) : sqrt(2.0); /* odd corners list the others oddly */
    } else { /* octant f: one vertex of each opposite pair */
      const int v[3] = {(f & 1) ? 3 : 0, (f & 2) ? 4 : 1, (f & 4) ? 5 : 2};
      for (int m = 0; m < 3; m++)
        for (int i = 0; i < 3; i++)
          e[m][i] = x[3 * v[m] + i] - c[i];
      s = ((f & 1) + ((f >> 1) & 1) + ((f >> 2) & 1)) & 1 ? -1.0 : 1.0;
    }
    for (int m = 0; m < 3; m++)
      l *= sqrt(e[m][0] * e[m][0] + e[m][1] * e[m][1] + e[m][2] * e[m][2]);
    const double d = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                     e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                     e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    *mn = fmin(*mn, s * d / l);
    *mx = fmax(*mx, s * d / l);
  }
}

/* The scaled Jacobian of irregular tets and octahedra (a regular cell has all
 * its edges alike, so it cannot tell one edge's length from another's): the
 * extremes against ref_scaled, relative 1e-12. */
static void test_scaled_irregular(void) {
  uint64_t seed = 23;
  for (int n = 0; n < 200; n++) {
    const ss_cell_type t = n % 2 ? SS_OCT : SS_TET;
    const double *base = t == SS_OCT ? reg_oct : reg_tet;
    double x[18], mn, mx;
    for (int i = 0; i < nvals(t); i++)
      x[i] = base[i] + 0.4 * rnd(&seed);
    ss_jac_result r;
    ss_jac_cell(t, x, 3, 0, &r);
    ref_scaled(t, x, &mn, &mx);
    CHECK(fabs(r.min_scaled - mn) <= 1e-12 * fabs(mn) &&
              fabs(r.max_scaled - mx) <= 1e-12 * fabs(mx),
          "%s %d: scaled Jacobian [%.17g, %.17g], reference [%.17g, %.17g]",
          t == SS_OCT ? "octahedron" : "tet", n, r.min_scaled, r.max_scaled, mn, mx);
  }
}

/* The interval verdict for tight boxes against the double one: same sign,
 * same point, same depth. */
static void agree(ss_cell_type t, const double *x, int depth, const char *what, int n) {
  ss_jac_result a, b;
  ss_jac_cell(t, x, tdim(t), depth, &a);
  jac_box(t, x, tight(t, x), depth, &b);
  CHECK(a.sign == b.sign && a.depth == b.depth &&
            (a.sign != SS_JAC_FOLDED || memcmp(a.where, b.where, sizeof a.where) == 0),
        "%s %d: double %d (depth %d, at %g %g %g), interval %d (depth %d, at %g %g %g)",
        what, n, a.sign, a.depth, a.where[0], a.where[1], a.where[2], b.sign, b.depth,
        b.where[0], b.where[1], b.where[2]);
  CHECK(fabs(a.min_scaled - b.min_scaled) < 1e-12 &&
            fabs(a.max_scaled - b.max_scaled) < 1e-12,
        "%s %d: scaled Jacobian %g %g (double), %g %g (midpoints)", what, n, a.min_scaled,
        a.max_scaled, b.min_scaled, b.max_scaled);
}

static void test_interval_tight(void) {
  double cube[24], mirror[24];
  unit_cube(cube);
  memcpy(mirror, cube + 12, 12 * sizeof *mirror);
  memcpy(mirror + 12, cube, 12 * sizeof *mirror);
  agree(SS_HEX, cube, SS_JAC_DEPTH, "unit cube", 0);
  agree(SS_HEX, mirror, SS_JAC_DEPTH, "mirrored cube", 0);
  agree(SS_TET, reg_tet, 0, "regular tet", 0);
  agree(SS_TRIANGLE, eq_tri, 0, "triangle", 0);
  agree(SS_OCT, reg_oct, 0, "regular octahedron", 0);
  agree(SS_QUAD, square, 0, "square", 0);
  const double bowtie[8] = {0, 0, 1, 0, 0, 1, 1, 1};
  const double dart[8] = {0, 0, 2, 0, 0.5, 0.5, 0, 2};
  agree(SS_QUAD, bowtie, 0, "bow-tie", 0);
  agree(SS_QUAD, dart, 0, "dart", 0);
  double oct2[18];
  memcpy(oct2, reg_oct, sizeof oct2);
  oct2[2 * 3 + 2] = -0.5;
  agree(SS_OCT, oct2, 0, "squashed octahedron", 0);
  ss_jac_result r;
  jac_box(SS_HEX, fold_hex, tight(SS_HEX, fold_hex), SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_FOLDED && ref_hex(fold_hex, r.where) < 0.0,
        "folding hex, certified: %d at (%g %g %g)", r.sign, r.where[0], r.where[1],
        r.where[2]);
  agree(SS_HEX, fold_hex, SS_JAC_DEPTH, "folding hex", 0);
  jac_box(SS_HEX, deep_hex, tight(SS_HEX, deep_hex), SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_POSITIVE && r.depth > 0, "deep hex, certified: %d depth %d",
        r.sign, r.depth);
  agree(SS_HEX, deep_hex, SS_JAC_DEPTH, "deep hex", 0);
  jac_box(SS_HEX, deep_hex, tight(SS_HEX, deep_hex), 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED, "deep hex at depth 0, certified: %d", r.sign);
  /* similarities, random cells of every type, of both signs and folded */
  uint64_t seed = 42;
  int folded = 0;
  for (int t = 0; t < 400; t++) {
    double x[24], y[24];
    unit_cube(x);
    for (int i = 0; i < 24; i++)
      x[i] += (t < 100 ? 0.2 : 0.55) * rnd(&seed);
    similarity(x, 8, &seed, t & 1, y);
    agree(SS_HEX, y, SS_JAC_DEPTH, "random hex", t);
    ss_jac_cell(SS_HEX, y, 3, SS_JAC_DEPTH, &r);
    folded += r.sign == SS_JAC_FOLDED;
    double o[18], q[8], e[12], tr[6];
    for (int i = 0; i < 18; i++)
      o[i] = reg_oct[i] + (t < 100 ? 0.15 : 0.6) * rnd(&seed);
    agree(SS_OCT, o, 0, "random octahedron", t);
    for (int i = 0; i < 8; i++)
      q[i] = square[i] + 0.6 * rnd(&seed);
    agree(SS_QUAD, q, 0, "random quad", t);
    for (int i = 0; i < 12; i++)
      e[i] = rnd(&seed);
    agree(SS_TET, e, 0, "random tet", t);
    for (int i = 0; i < 6; i++)
      tr[i] = rnd(&seed);
    agree(SS_TRIANGLE, tr, 0, "random triangle", t);
  }
  CHECK(folded > 20, "random hexes: only %d folded", folded);
}

/* Boxes widened from tight to the cell's size: a certified verdict stays the
 * tight one and holds for random nets in the boxes, then turns UNDECIDED for
 * good; at the widest, UNDECIDED.  Returns the number of widths at which the
 * sampled nets disagreed among themselves (the sign was in doubt). */
static int widen(ss_cell_type t, const double *x, const char *what, uint64_t *seed) {
  ss_jac_result r0, r;
  double s = 0.0;
  for (int i = 0; i < nvals(t); i++)
    s = fmax(s, fabs(x[i]));
  jac_box(t, x, tight(t, x), SS_JAC_DEPTH, &r0);
  int was_undecided = 0, doubts = 0;
  for (double rad = tight(t, x); rad < 2.0 * s; rad *= 8.0) {
    jac_box(t, x, rad, SS_JAC_DEPTH, &r);
    CHECK(r.sign == r0.sign || r.sign == SS_JAC_UNDECIDED, "%s, radius %g: %d, tight %d",
          what, rad, r.sign, r0.sign);
    CHECK(!was_undecided || r.sign == SS_JAC_UNDECIDED,
          "%s, radius %g: %d after UNDECIDED at a smaller radius", what, rad, r.sign);
    was_undecided |= r.sign == SS_JAC_UNDECIDED;
    int bad = 0, seen[4] = {0, 0, 0, 0};
    for (int k = 0; k < 12; k++) {
      double y[24];
      net_in_box(t, x, rad, seed, y);
      bad += !holds(t, y, &r);
      seen[sampled_sign(t, y) + 1] = 1;
    }
    CHECK(bad == 0, "%s, radius %g: verdict %d fails for %d of 12 nets in the boxes",
          what, rad, r.sign, bad);
    if (seen[0] + seen[1] + seen[2] + seen[3] > 1) {
      doubts++;
      CHECK(r.sign == SS_JAC_UNDECIDED, "%s, radius %g: nets of different signs, %d",
            what, rad, r.sign);
    }
  }
  CHECK(r.sign == SS_JAC_UNDECIDED, "%s: %d at the widest boxes", what, r.sign);
  return doubts;
}

static void test_interval_proofs(void) {
  uint64_t seed = 2024;
  double cube[24];
  unit_cube(cube);
  int doubts = 0;
  doubts += widen(SS_HEX, cube, "unit cube", &seed);
  doubts += widen(SS_HEX, fold_hex, "folding hex", &seed);
  doubts += widen(SS_HEX, deep_hex, "deep hex", &seed);
  doubts += widen(SS_TET, reg_tet, "regular tet", &seed);
  doubts += widen(SS_TRIANGLE, eq_tri, "triangle", &seed);
  doubts += widen(SS_OCT, reg_oct, "regular octahedron", &seed);
  doubts += widen(SS_QUAD, square, "square", &seed);
  const double dart[8] = {0, 0, 2, 0, 0.5, 0.5, 0, 2};
  doubts += widen(SS_QUAD, dart, "dart", &seed);
  double oct2[18];
  memcpy(oct2, reg_oct, sizeof oct2);
  oct2[2 * 3 + 2] = -0.5;
  doubts += widen(SS_OCT, oct2, "squashed octahedron", &seed);
  for (int t = 0; t < 12; t++) {
    double x[24];
    unit_cube(x);
    for (int i = 0; i < 24; i++)
      x[i] += 0.5 * rnd(&seed);
    doubts += widen(SS_HEX, x, "random hex", &seed);
  }
  CHECK(doubts >= 10, "widening reached boxes of mixed signs only %d times", doubts);
  /* boxes a hundredth of the cell still prove the ideal cells */
  ss_jac_result r;
  jac_box(SS_HEX, cube, 0.01, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_POSITIVE, "unit cube, radius 0.01: %d", r.sign);
  jac_box(SS_HEX, fold_hex, 1e-4, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_FOLDED, "folding hex, radius 1e-4: %d", r.sign);
  jac_box(SS_OCT, reg_oct, 0.01, 0, &r);
  CHECK(r.sign == SS_JAC_POSITIVE, "regular octahedron, radius 0.01: %d", r.sign);
}

/* ss_jac_cell_interval_sign, the certified path's cell test, on the hex x
 * in boxes of radius rad: no measures; the verdict of ss_jac_cell_interval
 * wherever that one decides, else UNDECIDED or a sign; whatever it proves
 * holds for nets drawn in the boxes (det J sampled by ref_hex).  Returns
 * its verdict. */
static int sign_agrees(const double *x, double rad, const char *what, uint64_t *seed) {
  double lo[24], hi[24];
  for (int i = 0; i < 24; i++)
    lo[i] = x[i] - rad, hi[i] = x[i] + rad;
  ss_jac_result a, b;
  ss_jac_cell_interval(SS_HEX, lo, hi, 3, SS_JAC_DEPTH, &a);
  ss_jac_cell_interval_sign(SS_HEX, lo, hi, 3, SS_JAC_DEPTH, &b);
  CHECK(isnan(b.min_scaled) && isnan(b.max_scaled), "%s: measures %g %g", what,
        b.min_scaled, b.max_scaled);
  CHECK(a.sign == SS_JAC_UNDECIDED ? b.sign != SS_JAC_FOLDED : b.sign == a.sign,
        "%s, radius %g: %d, ss_jac_cell_interval %d", what, rad, b.sign, a.sign);
  for (int k = 0; k < 4; k++) {
    double y[24];
    net_in_box(SS_HEX, x, rad, seed, y);
    CHECK(holds(SS_HEX, y, &b), "%s, radius %g: verdict %d fails for a net in the boxes",
          what, rad, b.sign);
  }
  return b.sign;
}

/* The certified path's cell test (ss_jac_cell_interval_sign): its quick
 * start encloses the 27 Bernstein coefficients from the hex's edges, with
 * other roundings than the traversal's; on random hexes (half of them
 * strongly distorted, many folding), the hex that folds inside with positive
 * corners, the hex positive only after subdivision, and a mirrored unit cube,
 * it never contradicts ss_jac_cell_interval nor sampling. */
static void test_interval_sign(void) {
  uint64_t seed = 4242;
  double cube[24], mirror[24];
  unit_cube(cube);
  for (int k = 0; k < 8; k++)
    for (int i = 0; i < 3; i++)
      mirror[3 * k + i] = i == 1 ? -cube[3 * k + i] : cube[3 * k + i];
  const double *named[4] = {cube, mirror, fold_hex, deep_hex};
  const char *name[4] = {"unit cube", "mirrored cube", "folding hex", "deep hex"};
  for (int c = 0; c < 4; c++)
    for (double rad = tight(SS_HEX, named[c]); rad < 0.05; rad *= 64.0)
      sign_agrees(named[c], rad, name[c], &seed);
  ss_jac_result r;
  ss_jac_cell_interval_sign(SS_HEX, mirror, mirror, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_NEGATIVE && r.depth == 0, "mirrored cube: %d at depth %d",
        r.sign, r.depth);
  ss_jac_cell_interval_sign(SS_HEX, fold_hex, fold_hex, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_FOLDED, "folding hex, exact corners: %d", r.sign);
  /* det J > 0 at its 27 Lagrange points, not all its Bernstein coefficients:
   * no proof before subdividing (catches Lagrange values taken as
   * coefficients) */
  ss_jac_cell_interval_sign(SS_HEX, deep_hex, deep_hex, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_POSITIVE && r.depth > 0,
        "deep hex, exact corners: %d at depth %d", r.sign, r.depth);
  int count[4] = {0, 0, 0, 0}; /* folded, positive, negative, undecided */
  for (int t = 0; t < 150; t++) {
    double x[24];
    unit_cube(x);
    const double amp = t % 2 ? 0.25 : 0.6;
    for (int i = 0; i < 24; i++)
      x[i] += amp * rnd(&seed);
    for (double rad = tight(SS_HEX, x); rad < 0.05; rad *= 64.0) {
      const int v = sign_agrees(x, rad, "random hex", &seed);
      count[v == SS_JAC_NEGATIVE ? 2 : v == SS_JAC_UNDECIDED ? 3 : v]++;
    }
  }
  CHECK(count[0] > 20 && count[1] > 100 && count[3] > 0,
        "random hexes: %d folded, %d positive, %d undecided (too few to test)", count[0],
        count[1], count[3]);
}

/* A flat cell: DEGENERATE in double, UNDECIDED for tight boxes. */
static void flat_cell(ss_cell_type t, const double *x, const char *what) {
  ss_jac_result r;
  ss_jac_cell(t, x, tdim(t), SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_DEGENERATE, "%s: %d", what, r.sign);
  jac_box(t, x, tight(t, x), SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED, "%s, certified: %d", what, r.sign);
}

/* Vertex 2 (+z) of the octahedron x moved to the centroid of the other five,
 * hence to the centroid of all six: its four octants have det 0. */
static void apex_to_centroid(double *x) {
  for (int i = 0; i < 3; i++) {
    double m = 0.0;
    for (int k = 0; k < 6; k++)
      if (k != 2) m += x[3 * k + i] / 5.0;
    x[6 + i] = m;
  }
}

/* A cell with one exact value 0 (mathematically), and flat cells. */
static void test_no_sign(void) {
  uint64_t seed = 99;
  ss_jac_result r;
  double mn, mx;
  /* flat hex: the unit square and, above it, a smaller one in the same plane
   * z = 0 (det J = 0 exactly); then rotated, where det J is rounding noise of
   * either sign; then tiny, then far from the origin */
  double flat[24], y[24];
  unit_cube(flat);
  for (int k = 0; k < 8; k++) {
    if (k >= 4) flat[3 * k] = 0.25 + 0.5 * flat[3 * k] + 0.125;
    if (k >= 4) flat[3 * k + 1] = 0.25 + 0.5 * flat[3 * k + 1];
    flat[3 * k + 2] = 0.0;
  }
  flat_cell(SS_HEX, flat, "flat hex");
  jac_box(SS_HEX, flat, 0.0, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED, "flat hex, point intervals: %d", r.sign);
  double noise = 0.0;
  for (int t = 0; t < 50; t++) {
    similarity(flat, 8, &seed, t & 1, y);
    ref_range(SS_HEX, y, 4, &mn, &mx);
    noise = fmax(noise, fmax(fabs(mn), fabs(mx)));
    flat_cell(SS_HEX, y, "rotated flat hex");
  }
  CHECK(noise > 0.0 && noise < 1e-14, "rotated flat hexes: det J up to %g", noise);
  /* exactly flat with rounding in the arithmetic: coordinates of 51 bits on
   * the plane z = x + y (exact), so det J = 0 exactly while the sums and
   * products that compute it round.  Even boxes of radius 0 must not give the
   * enclosure a sign */
  int rounded = 0;
  for (int t = 0; t < 100; t++) {
    double e[24];
    for (int k = 0; k < 8; k++) {
      e[3 * k] = ldexp((double)(seed_bits(&seed) >> 13), -51);
      e[3 * k + 1] = ldexp((double)(seed_bits(&seed) >> 13), -51);
      e[3 * k + 2] = e[3 * k] + e[3 * k + 1];
    }
    ss_jac_cell(SS_TET, e, 3, 0, &r);
    CHECK(r.sign == SS_JAC_DEGENERATE, "flat 51-bit tet %d: %d", t, r.sign);
    jac_box(SS_TET, e, 0.0, 0, &r);
    CHECK(r.sign == SS_JAC_UNDECIDED, "flat 51-bit tet %d, point boxes: %d", t, r.sign);
    ref_range(SS_TET, e, 0, &mn, &mx);
    rounded += mn != 0.0;
    ss_jac_cell(SS_HEX, e, 3, SS_JAC_DEPTH, &r);
    CHECK(r.sign == SS_JAC_DEGENERATE, "flat 51-bit hex %d: %d", t, r.sign);
    jac_box(SS_HEX, e, 0.0, SS_JAC_DEPTH, &r);
    CHECK(r.sign == SS_JAC_UNDECIDED, "flat 51-bit hex %d, point boxes: %d", t, r.sign);
    ref_range(SS_HEX, e, 2, &mn, &mx);
    rounded += mn != 0.0 || mx != 0.0;
  }
  CHECK(rounded > 40, "flat 51-bit cells: only %d with a rounded det J", rounded);
  /* thin cells, relative height 1e-13 (flat) or 1e-10 (a sign): the same
   * verdict at every scale, the threshold being FLAT L^dim */
  for (double sc = 1e-4; sc < 2e4; sc *= 100.0)
    for (int th = 0; th < 2; th++) {
      const double h = th ? 1e-10 : 1e-13;
      const ss_jac_sign want = th ? SS_JAC_POSITIVE : SS_JAC_DEGENERATE;
      double thin[24];
      unit_cube(thin);
      for (int k = 0; k < 8; k++)
        thin[3 * k + 2] *= h;
      for (int i = 0; i < 24; i++)
        thin[i] *= sc;
      ss_jac_cell(SS_HEX, thin, 3, SS_JAC_DEPTH, &r);
      CHECK(r.sign == want, "hex of height %g at scale %g: %d", h, sc, r.sign);
      const double tt[12] = {0, 0, 0, sc, 0, 0, 0, sc, 0, 0, 0, h * sc};
      ss_jac_cell(SS_TET, tt, 3, 0, &r);
      CHECK(r.sign == want, "tet of height %g at scale %g: %d", h, sc, r.sign);
      const double tq[8] = {0, 0, sc, 0, sc, h * sc, 0, h * sc};
      ss_jac_cell(SS_QUAD, tq, 2, 0, &r);
      CHECK(r.sign == want, "quad of height %g at scale %g: %d", h, sc, r.sign);
      const double tr[6] = {0, 0, sc, 0, 0, h * sc};
      ss_jac_cell(SS_TRIANGLE, tr, 2, 0, &r);
      CHECK(r.sign == want, "triangle of height %g at scale %g: %d", h, sc, r.sign);
    }
  double tiny[24], cube[24];
  unit_cube(cube);
  for (int i = 0; i < 24; i++)
    tiny[i] = 1e-9 * cube[i] + 3e-9;
  ss_jac_cell(SS_HEX, tiny, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_POSITIVE, "a cube of edge 1e-9: %d (the threshold is relative)",
        r.sign);
  /* translated 500 times its size: rounding grows, the threshold covers it */
  for (int i = 0; i < 24; i++)
    tiny[i] = flat[i] + 500.0;
  ss_jac_cell(SS_HEX, tiny, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_DEGENERATE, "flat hex at 500: %d", r.sign);

  /* one corner value zero: corner (1,1,1) on the plane of its three
   * neighbours; det J >= 0 with its only zero there (sampled).  No sign: not
   * FOLDED (the old rule), not POSITIVE */
  double z[24];
  unit_cube(z);
  double *p = z + 3 * ss_cube_corner_index(3, 7);
  p[0] = 0.5, p[1] = 0.75, p[2] = 0.75;
  const double one[3] = {1, 1, 1};
  ref_range(SS_HEX, z, 16, &mn, &mx);
  CHECK(ref_hex(z, one) == 0.0 && mn == 0.0 && mx > 0.5, "zero-corner hex: [%g, %g]", mn,
        mx);
  ss_jac_cell(SS_HEX, z, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && memcmp(r.where, one, sizeof one) == 0,
        "zero-corner hex: %d at (%g %g %g)", r.sign, r.where[0], r.where[1], r.where[2]);
  jac_box(SS_HEX, z, tight(SS_HEX, z), SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && memcmp(r.where, one, sizeof one) == 0,
        "zero-corner hex, certified: %d at (%g %g %g)", r.sign, r.where[0], r.where[1],
        r.where[2]);
  for (int t = 0; t < 50; t++) {
    similarity(z, 8, &seed, 0, y);
    ss_jac_cell(SS_HEX, y, 3, SS_JAC_DEPTH, &r);
    CHECK(r.sign == SS_JAC_UNDECIDED, "rotated zero-corner hex %d: %d (corner value %g)",
          t, r.sign, ref_hex(y, one));
  }
  /* ... unless clear values prove a fold: two corner values exactly 0, one
   * clearly negative (found by a search in exact rationals) */
  const double zf[24] = {-0.375,    0.75,      0.125,     1.125,  0.25, -0.375,
                         0.875,     0.625,     0.5,       -0.375, 1.75, 0.125,
                         -0.25,     -0.75,     1,         1.25,   0.5,  0.375,
                         -65 / 64., 117 / 64., 131 / 64., -0.5,   1.5,  1.625};
  ss_jac_cell(SS_HEX, zf, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_FOLDED && ref_hex(zf, r.where) < -0.1,
        "zero-corner hex with a clear fold: %d at (%g %g %g)", r.sign, r.where[0],
        r.where[1], r.where[2]);

  /* quads: collinear (flat); corner (1,1) on the line of its neighbours; the
   * same with a clear fold */
  const double line[8] = {0, 0, 1, 1, 3, 3, 2, 2};
  flat_cell(SS_QUAD, line, "collinear quad");
  const double c = cos(0.3), sn = sin(0.3);
  double lq[8];
  for (int k = 0; k < 4; k++) /* 0.1 0.3 0.7 0.9 along a rotated line */
    lq[2 * k] = c * (0.1 + 0.2 * k), lq[2 * k + 1] = sn * (0.1 + 0.2 * k);
  flat_cell(SS_QUAD, lq, "collinear quad, rotated");
  const double kite[8] = {0, 0, 1, 0, 0.5, 0.5, 0, 1};
  ss_jac_cell(SS_QUAD, kite, 2, 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && r.where[0] == 1.0 && r.where[1] == 1.0,
        "quad with a zero corner: %d at (%g %g)", r.sign, r.where[0], r.where[1]);
  jac_box(SS_QUAD, kite, tight(SS_QUAD, kite), 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && r.where[0] == 1.0 && r.where[1] == 1.0,
        "quad with a zero corner, certified: %d at (%g %g)", r.sign, r.where[0],
        r.where[1]);
  const double qf[8] = {-0.125, 1.25, 1.125, -0.5, 0.8125, 2, 0.875, 1.5};
  CHECK(ref_quad(qf, 1, 1) == 0.0 && ref_quad(qf, 0, 1) < -0.5,
        "zero-corner quad with a fold: %g %g", ref_quad(qf, 1, 1), ref_quad(qf, 0, 1));
  ss_jac_cell(SS_QUAD, qf, 2, 0, &r);
  CHECK(r.sign == SS_JAC_FOLDED && r.where[0] == 0.0 && r.where[1] == 1.0,
        "zero-corner quad with a clear fold: %d at (%g %g)", r.sign, r.where[0],
        r.where[1]);

  /* tets and triangles: flat, rotated flat, thin but with a sign */
  const double ftet[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  double rtet[12];
  similarity(ftet, 4, &seed, 0, rtet);
  flat_cell(SS_TET, ftet, "flat tet");
  flat_cell(SS_TET, rtet, "flat tet, rotated");
  double thin[12];
  memcpy(thin, ftet, sizeof thin);
  thin[3 * 3 + 2] = 1e-6;
  ss_jac_cell(SS_TET, thin, 3, 0, &r);
  CHECK(r.sign == SS_JAC_POSITIVE, "thin tet: %d", r.sign);
  jac_box(SS_TET, thin, tight(SS_TET, thin), 0, &r);
  CHECK(r.sign == SS_JAC_POSITIVE, "thin tet, certified: %d", r.sign);
  const double ftri[6] = {0, 0, 2, 1, 1, 0.5};
  flat_cell(SS_TRIANGLE, ftri, "collinear triangle");
  const double rtri[6] = {0.1, 0.3, 0.1 + 2 * c, 0.3 + 2 * sn, 0.1 + c, 0.3 + sn};
  flat_cell(SS_TRIANGLE, rtri, "collinear triangle, rotated");

  /* octahedra: a flat hexagon; +z at the centroid of the other five (the four
   * upper octants have det 0 mathematically, rounding noise in double); the
   * same with -x pulled through so that clear octants of both signs prove
   * a fold */
  double hexagon[18];
  for (int k = 0; k < 6; k++) {
    hexagon[3 * k] = cos(k * 1.0471975511965976);
    hexagon[3 * k + 1] = sin(k * 1.0471975511965976);
    hexagon[3 * k + 2] = 0.0;
  }
  flat_cell(SS_OCT, hexagon, "flat octahedron");
  double oc[18];
  memcpy(oc, reg_oct, sizeof oc);
  apex_to_centroid(oc);
  ref_range(SS_OCT, oc, 0, &mn, &mx);
  ss_jac_cell(SS_OCT, oc, 3, 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED, "octahedron with flat octants: %d, [%g, %g]", r.sign,
        mn, mx);
  jac_box(SS_OCT, oc, tight(SS_OCT, oc), 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED, "octahedron with flat octants, certified: %d",
        r.sign);
  oc[3 * 3] = 0.5; /* -x now at +0.5: the lower octants at x0 and x3 differ */
  apex_to_centroid(oc);
  ref_range(SS_OCT, oc, 0, &mn, &mx);
  ss_jac_cell(SS_OCT, oc, 3, 0, &r);
  CHECK(r.sign == SS_JAC_FOLDED && mn < -0.1 && mx > 0.1,
        "octahedron with flat octants and a fold: %d, [%g, %g]", r.sign, mn, mx);
}

static void test_bad_input(void) {
  double cube[24], lo[24], hi[24];
  unit_cube(cube);
  ss_jac_result r;
  const double bad[3] = {NAN, INFINITY, -INFINITY};
  for (int b = 0; b < 3; b++) {
    memcpy(lo, cube, sizeof lo);
    memcpy(hi, cube, sizeof hi);
    lo[5] = bad[b];
    ss_jac_cell_interval(SS_HEX, lo, hi, 3, SS_JAC_DEPTH, &r);
    CHECK(r.sign == SS_JAC_UNDECIDED && isnan(r.min_scaled) && isnan(r.max_scaled),
          "interval, lo %g: %d, %g", bad[b], r.sign, r.min_scaled);
    ss_jac_cell_interval(SS_HEX, hi, lo, 3, SS_JAC_DEPTH, &r);
    CHECK(r.sign == SS_JAC_UNDECIDED && isnan(r.min_scaled), "interval, hi %g: %d, %g",
          bad[b], r.sign, r.min_scaled);
    ss_jac_cell(SS_HEX, lo, 3, SS_JAC_DEPTH, &r);
    CHECK(r.sign == SS_JAC_UNDECIDED && isnan(r.min_scaled), "double, %g: %d, %g", bad[b],
          r.sign, r.min_scaled);
  }
  memcpy(lo, cube, sizeof lo);
  memcpy(hi, cube, sizeof hi);
  lo[7] = hi[7] + 1e-3; /* unordered */
  ss_jac_cell_interval(SS_HEX, lo, hi, 3, SS_JAC_DEPTH, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && isnan(r.min_scaled), "lo > hi: %d", r.sign);
  ss_jac_cell_interval(SS_QUAD, square, square, 3, 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && isnan(r.min_scaled), "quad in 3D: %d", r.sign);
  ss_jac_cell_interval(SS_SEGMENT, square, square, 2, 0, &r);
  CHECK(r.sign == SS_JAC_UNDECIDED && isnan(r.min_scaled), "segment: %d", r.sign);
}

/* The cube corner order of ss_cx.h (quad corners 0 1 2 3 cyclic, hex top face
 * 4 5 6 7 above them), which ss_jac.c holds as constants (QUAD_BITS, HEX_BITS)
 * so that the hex test's Lagrange weights are compile-time constants: if the
 * order here changed, those would silently be another map's. */
static void test_corner_order(void) {
  static const unsigned quad[4] = {0u, 1u, 3u, 2u};
  static const unsigned hex[8] = {0u, 1u, 3u, 2u, 4u, 5u, 7u, 6u};
  for (int k = 0; k < 4; k++) {
    CHECK(ss_cube_corner_bits(2, k) == quad[k], "quad corner %d: bits %u", k,
          ss_cube_corner_bits(2, k));
    CHECK(ss_cube_corner_index(2, quad[k]) == k, "quad bits %u: corner %d", quad[k],
          ss_cube_corner_index(2, quad[k]));
  }
  for (int k = 0; k < 8; k++) {
    CHECK(ss_cube_corner_bits(3, k) == hex[k], "hex corner %d: bits %u", k,
          ss_cube_corner_bits(3, k));
    CHECK(ss_cube_corner_index(3, hex[k]) == k, "hex bits %u: corner %d", hex[k],
          ss_cube_corner_index(3, hex[k]));
  }
}

int main(void) {
  test_corner_order();
  test_ideal_cells();
  test_similarity();
  test_bernstein();
  test_reference();
  test_scaled_irregular();
  test_interval_tight();
  test_interval_proofs();
  test_interval_sign();
  test_no_sign();
  test_bad_input();
  return ss_test_done("jac");
}
