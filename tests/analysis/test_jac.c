/* test_jac.c — the Jacobian sign of one cell (ss_jac): ideal cells score 1,
 * orientation flips the sign, similarities keep the scaled Jacobian, and the
 * Bernstein test classifies hexes correctly, including one that folds inside
 * although its eight corner Jacobians are positive (the case corner checks
 * miss) and one that is positive but needs subdivision to show it.  Every
 * hex verdict is checked against dense sampling of det J. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "ss_jac.h"
#include "ss_test.h"

/* deterministic uniform numbers in [-1, 1) */
static double rnd(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
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
  const double flat[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  ss_jac_cell(SS_TET, flat, 3, 0, &r);
  CHECK(r.sign == SS_JAC_FOLDED, "flat tet: %d", r.sign);
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
  int counts[4] = {0, 0, 0, 0};
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
    counts[r.sign == SS_JAC_UNDECIDED ? 3 : r.sign + 1]++;
  }
  CHECK(counts[1] > 20 && counts[2] > 20, "random hexes: %d folded, %d positive",
        counts[1], counts[2]);
}

int main(void) {
  test_ideal_cells();
  test_similarity();
  test_bernstein();
  return ss_test_done("jac");
}
