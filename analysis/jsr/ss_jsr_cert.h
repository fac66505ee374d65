/* ss_jsr_cert.h — certified lower bound of the spectral radius of one matrix
 * product (ball arithmetic), for ss_jsr.  Internal to analysis/. */
#ifndef SS_JSR_CERT_H
#define SS_JSR_CERT_H

#include <stddef.h>

/* A rigorous lower bound *lo of rho(Y_w)^{1/len} for the word w (w[0] applied
 * first) of the n x n row-major matrices Y, the product formed exactly in
 * ball arithmetic from the double entries.  Returns 1 if certified, 0 if the
 * enclosure failed (then *lo = 0).  Never fails otherwise. */
int ss_jsr_cert_lower(size_t n, const double *const *Y, const int *w, int len,
                      double *lo);

#endif
