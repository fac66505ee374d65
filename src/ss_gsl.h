/* ss_gsl.h — GSL at the library boundary.
 *
 * GSL's default error handler aborts the process, and GSL's allocation
 * functions call it when malloc fails: a library that never aborts cannot leave
 * that to its caller's main().  Every GSL allocation of the library goes
 * through the functions here, which make sure, once per process and
 * thread-safely, that GSL's handler does not abort: the default handler is
 * switched off (gsl_set_error_handler_off), so a failed allocation returns
 * NULL and becomes SS_ENOMEM; a handler the caller installed before is left
 * in place (it is the caller's choice what a GSL error does). */
#ifndef SS_GSL_H
#define SS_GSL_H

#include <stddef.h>

#include <gsl/gsl_spmatrix.h>

#include "ss_api.h"

SS_BEGIN_DECLS

/* Make GSL's error handler safe for the library as described above.
 * Idempotent and thread-safe; the allocation below calls it first. */
void ss_gsl_init(void);

/* gsl_spmatrix_alloc_nzmax(nrows, ncols, max(nnz, 1), GSL_SPMATRIX_CSR) after
 * ss_gsl_init (GSL wants room for one entry even in an empty matrix; nrows and
 * ncols must be at least 1): NULL when memory is short, never an abort. */
gsl_spmatrix *ss_gsl_csr_alloc(size_t nrows, size_t ncols, size_t nnz);

SS_END_DECLS

#endif
