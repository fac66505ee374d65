/* ss_gsl.c — GSL's error handler at the library boundary (ss_gsl.h). */
#include "ss_gsl.h"

#include <gsl/gsl_errno.h>
#include <pthread.h>

static pthread_once_t ss_gsl_once = PTHREAD_ONCE_INIT;

static void ss_gsl_quiet(void) {
  /* GSL's default handler is NULL (abort); anything else was installed on
   * purpose and goes back */
  gsl_error_handler_t *prev = gsl_set_error_handler_off();
  if (prev) gsl_set_error_handler(prev);
}

void ss_gsl_init(void) {
  pthread_once(&ss_gsl_once, ss_gsl_quiet);
}

gsl_spmatrix *ss_gsl_csr_alloc(size_t nrows, size_t ncols, size_t nnz) {
  ss_gsl_init();
  return gsl_spmatrix_alloc_nzmax(nrows, ncols, nnz ? nnz : 1, GSL_SPMATRIX_CSR);
}
