/* ss_dense.h — small dense-matrix kernels written once for the library's
 * modules (internal, not installed).  static inline, so that each caller
 * compiles the same floating-point operations in the same order as the
 * private copies they replace: the results are the same bits.
 *
 * Kept apart on purpose (not the same bits, or not the same thing): the
 * Jacobian test's det3 over doubles and intervals (analysis/charmap/
 * ss_jac_impl.h, generic in its number type), its hypot-chained length
 * (ss_jac.c: exact to the last place where a sum of squares is not), the
 * JSR's rigorous upward-rounded norms (analysis/jsr/ss_jsr_products.c), the
 * ellipsoid fit's dot over n^2 entries against the drawings' dot3 (a sum
 * started at 0 turns a -0 product into +0), ss_cx_orient's Euclidean norm
 * (no other copy). */
#ifndef SS_DENSE_H
#define SS_DENSE_H

#include <math.h>
#include <stddef.h>

/* The determinant of the 3 x 3 matrix with rows a, b, c, expanded along a. */
static inline double ss_dense_det3(const double *a, const double *b, const double *c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

/* The largest absolute row sum of the n x n row-major matrix a: its
 * inf-norm (the 1-norm of the column-major matrix in the same buffer),
 * summed left to right. */
static inline double ss_dense_max_row_sum(const double *a, size_t n) {
  double mx = 0;
  for (size_t r = 0; r < n; r++) {
    double s = 0;
    for (size_t c = 0; c < n; c++)
      s += fabs(a[r * n + c]);
    if (s > mx) mx = s;
  }
  return mx;
}

#endif
