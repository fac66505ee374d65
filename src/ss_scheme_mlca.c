/* ss_scheme_mlca.c — multi-linear cell averaging (Bajaj, Schaefer, Warren, Xu,
 * "A subdivision scheme for hexahedral meshes", section 2).
 *
 * Multilinear split of d-cubes (d = 1, 2, 3), then "reposition v at the centroid
 * of the centroids of the cells that contain v" — every mask is uniform, 1/2^d
 * per cell vertex.  Lower-dimensional cells (segments in a quad or hex mesh,
 * quads in a hex mesh, vertex cells anywhere) are creases (section 3.2): a vertex
 * is averaged over the cells of the lowest dimension holding it, so a vertex cell
 * is interpolated.  On regular grids this is the tensor-product cubic B-spline
 * rule; the composite rule is equation (2) of the paper. */
#include "ss_scheme_impl.h"

ss_status ss_scheme_mlca_new(ss_scheme **out, ss_error *err) {
  ss_averaging a = {.split = SS_SPLIT_MULTILINEAR};
  a.accepts[SS_VERTEX] = a.accepts[SS_SEGMENT] = a.accepts[SS_QUAD] = a.accepts[SS_HEX] =
      1;
  a.mask[SS_VERTEX][0] = 1.0;
  for (int r = 0; r < 2; r++)
    a.mask[SS_SEGMENT][r] = 1.0 / 2.0;
  for (int r = 0; r < 3; r++)
    a.mask[SS_QUAD][r] = 1.0 / 4.0;
  for (int r = 0; r < 4; r++)
    a.mask[SS_HEX][r] = 1.0 / 8.0;
  return ss_scheme_averaging_new("mlca", &a, out, err);
}
