/* ss_sink.c — accumulating rule weights into the refinement operator. */
#include "ss_sink.h"

void ss_sink_emit_operator(ss_sink *k, size_t row, size_t src, double w) {
  const ss_split *L = k->L;
  const double ws = w / (double)ss_split_npar(L, src);
  for (size_t q = L->ptr[src]; q < L->ptr[src + 1]; q++) {
    size_t col = L->parent[q];
    double *p = gsl_spmatrix_ptr(k->M, row, col);
    if (p)
      *p += ws;
    else if (gsl_spmatrix_set(k->M, row, col, ws) != 0)
      k->st = SS_ENOMEM;
  }
}
