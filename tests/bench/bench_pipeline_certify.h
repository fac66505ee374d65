/* bench_pipeline_certify.h — `bench_pipeline --phases --certify`
 * (bench_pipeline_certify.c): each certified stage's CPU per case beside the
 * double path's whole. */
#ifndef BENCH_PIPELINE_CERTIFY_H
#define BENCH_PIPELINE_CERTIFY_H

#include <stddef.h>

#include "ss_link.h"
#include "ss_scheme.h"

/* The n links l, each run three times certified and three times on the
 * double path with psi judged to psi_depth (0: not, as sweep runs); prints
 * the table.  exact_full: every factor proven irreducible
 * (ss_result_opts.exact_full).  0, or 1 on a failure. */
int bench_certify_phases(const ss_scheme *sc, ss_link *const *l, size_t n, int psi_depth,
                         int exact_full);

#endif
