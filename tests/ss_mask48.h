/* ss_mask48.h — the regular 4-8 lattice's dyadic mask, built by hand from the
 * quasi 4-8 rules (docs/schemes.md, "Quasi 4-8 surfaces"), for the tests of the scheme
 * (tests/scheme/test_quasi48.c) and of its local matrices
 * (tests/analysis/test_quasi48_local.c).
 *
 * Masks live on the half-integer grid of offsets -4..4: entry (x, y) at
 * index (2x + 8) SS_MASK48_G + (2y + 8).  One pass at an old vertex is
 * 2 (h1 * h1), h1 = 1/2 at 0 and 1/8 at (+-1/2, +-1/2); the next pass is the
 * same turned by 45 degrees, 2 (h2 * h2), h2 = 1/2 at 0 and 1/8 at (+-1/2, 0),
 * (0, +-1/2); two passes have the mask 4 (h1 * h1 * h2 * h2). */
#ifndef SS_MASK48_H
#define SS_MASK48_H

#include <string.h>

#define SS_MASK48_G 17 /* mask grid: offsets -4..4 in steps of 1/2 */

/* out = a * b on the half-integer grid (all SS_MASK48_G^2, centred; the
 * product is cut to the grid). */
static inline void ss_mask48_convolve(const double *a, const double *b, double *out) {
  enum { G = SS_MASK48_G };
  memset(out, 0, G * G * sizeof *out);
  for (int p = 0; p < G * G; p++)
    for (int q = 0; q < G * G; q++) {
      if (a[p] == 0 || b[q] == 0) continue;
      const int x = p / G + q / G - 8, y = p % G + q % G - 8;
      if (x >= 0 && x < G && y >= 0 && y < G) out[x * G + y] += a[p] * b[q];
    }
}

/* h1 and h2 above. */
static inline void ss_mask48_halves(double *h1, double *h2) {
  enum { G = SS_MASK48_G };
  memset(h1, 0, G * G * sizeof *h1);
  memset(h2, 0, G * G * sizeof *h2);
  h1[8 * G + 8] = h2[8 * G + 8] = 0.5;
  for (int s = -1; s <= 1; s += 2) {
    for (int r = -1; r <= 1; r += 2)
      h1[(8 + s) * G + 8 + r] = 0.125;
    h2[(8 + s) * G + 8] = 0.125;
    h2[8 * G + 8 + s] = 0.125;
  }
}

#endif
