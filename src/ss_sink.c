/* ss_sink.c — accumulating rule weights into the refinement operator. */
#include "ss_sink.h"

#include <stdlib.h>

void ss_sink_emit_operator(ss_sink *k, size_t row, size_t src, double w) {
  const ss_split *L = k->L;
  const double ws = w / (double)ss_split_npar(L, src);
  for (size_t q = L->ptr[src]; q < L->ptr[src + 1]; q++) {
    ss_triplets *t = k->M;
    if (t->n == t->cap) {
      size_t cap = t->cap ? 2 * t->cap : 1024;
      ss_idx *r = realloc(t->row, cap * sizeof *r);
      if (r) t->row = r;
      ss_idx *c = realloc(t->col, cap * sizeof *c);
      if (c) t->col = c;
      double *w2 = realloc(t->w, cap * sizeof *w2);
      if (w2) t->w = w2;
      if (!r || !c || !w2) {
        k->st = SS_ENOMEM;
        return;
      }
      t->cap = cap;
    }
    t->row[t->n] = (ss_idx)row;
    t->col[t->n] = L->parent[q];
    t->w[t->n++] = ws;
  }
}

void ss_triplets_clear(ss_triplets *t) {
  free(t->row);
  free(t->col);
  free(t->w);
  t->row = t->col = NULL;
  t->w = NULL;
  t->n = t->cap = 0;
}

ss_status ss_triplets_csr(const ss_triplets *t, size_t nrows, size_t ncols,
                          gsl_spmatrix **out, ss_error *err) {
  *out = NULL;
  size_t *ptr = calloc(nrows + 2, sizeof *ptr);
  ss_idx *col = malloc((t->n + 1) * sizeof *col);
  double *w = malloc((t->n + 1) * sizeof *w);
  if (!ptr || !col || !w) {
    free(ptr), free(col), free(w);
    return ss_error_nomem(err, "refinement operator");
  }
  /* bucket by row (counting sort), then sort each row by column and merge */
  for (size_t q = 0; q < t->n; q++)
    ptr[t->row[q] + 2]++;
  for (size_t r = 0; r < nrows; r++)
    ptr[r + 2] += ptr[r + 1];
  for (size_t q = 0; q < t->n; q++) {
    size_t at = ptr[t->row[q] + 1]++;
    col[at] = t->col[q];
    w[at] = t->w[q];
  }
  /* per row: merge repeated columns through a column -> slot map (rows carry
   * many repeats), then sort the few distinct columns */
  size_t *slot = malloc((ncols + 1) * sizeof *slot);
  if (!slot) {
    free(ptr), free(col), free(w);
    return ss_error_nomem(err, "refinement operator");
  }
  for (size_t c = 0; c < ncols; c++)
    slot[c] = SIZE_MAX;
  size_t nnz = 0;
  for (size_t r = 0; r < nrows; r++) {
    const size_t b = ptr[r], e = ptr[r + 1], start = nnz;
    for (size_t i = b; i < e; i++) {
      const ss_idx c = col[i];
      if (slot[c] != SIZE_MAX) {
        w[slot[c]] += w[i];
      } else {
        slot[c] = nnz;
        col[nnz] = c, w[nnz++] = w[i]; /* nnz <= i: compaction in place */
      }
    }
    for (size_t i = start; i < nnz; i++)
      slot[col[i]] = SIZE_MAX;
    for (size_t i = start + 1; i < nnz; i++) /* insertion sort: few distinct */
      for (size_t j = i; j > start && col[j - 1] > col[j]; j--) {
        ss_idx tc = col[j];
        double tw = w[j];
        col[j] = col[j - 1], w[j] = w[j - 1];
        col[j - 1] = tc, w[j - 1] = tw;
      }
    ptr[r] = start; /* bucket r is consumed; ptr[r] now starts CSR row r */
  }
  free(slot);
  gsl_spmatrix *R =
      gsl_spmatrix_alloc_nzmax(nrows, ncols ? ncols : 1, nnz ? nnz : 1, GSL_SPMATRIX_CSR);
  if (!R) {
    free(ptr), free(col), free(w);
    return ss_error_nomem(err, "refinement operator");
  }
  for (size_t r = 0; r < nrows; r++)
    R->p[r] = (int)ptr[r];
  R->p[nrows] = (int)nnz;
  for (size_t q = 0; q < nnz; q++) {
    R->i[q] = (int)col[q];
    R->data[q] = w[q];
  }
  R->nz = nnz;
  free(ptr), free(col), free(w);
  *out = R;
  return SS_OK;
}
