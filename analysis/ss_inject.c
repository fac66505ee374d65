/* ss_inject.c — injectivity of a PL image (placeholder). */
#include "ss_inject.h"

#include <string.h>

ss_status ss_inject_test(const double *x, int dim, size_t n, const ss_cell_type *ctype,
                         const size_t *corner, size_t ncells, size_t centre,
                         ss_injectivity *out, ss_error *err) {
  (void)x, (void)dim, (void)n, (void)ctype, (void)corner, (void)ncells, (void)centre;
  memset(out, 0, sizeof *out);
  return ss_error_set(err, SS_EINPUT, "the injectivity test is not built yet");
}
