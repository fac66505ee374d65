/* ss_exact.c — exact spectra (placeholder until the FLINT path lands). */
#include "ss_exact.h"

#include <stdlib.h>

#include <flint/fmpq_mat.h>
#include <flint/fmpz_poly_factor.h>

#include "acb_mat.h"
#include "arb_fmpz_poly.h"

struct ss_exact {
  int unused; /* placeholder */
};

ss_exact_opts ss_exact_defaults(int dim) {
  ss_exact_opts o = {1L << 18, 128, 4096, dim, 400, 1};
  return o;
}

ss_status ss_exact_new(const double *S, size_t n, size_t n1, const ss_exact_opts *o,
                       ss_exact **out, ss_error *err) {
  (void)S, (void)n, (void)n1, (void)o;
  *out = NULL;
  return ss_error_set(err, SS_EINPUT, "the exact path is not built yet");
}

void ss_exact_free(ss_exact *x) {
  free(x);
}
