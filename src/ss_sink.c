/* ss_sink.c — accumulating rule weights into the refinement operator. */
#include "ss_sink.h"

#include "ss_gsl.h"

#include <stdlib.h>

/* Room for m more triplets; 0, or -1 (and k->st set) without memory. */
static int reserve(ss_sink *k, size_t m) {
  ss_triplets *t = k->M;
  if (t->n + m <= t->cap) return 0;
  size_t cap = t->cap ? 2 * t->cap : 1024;
  while (cap < t->n + m)
    cap *= 2;
  ss_idx *r = realloc(t->row, cap * sizeof *r);
  if (r) t->row = r;
  ss_idx *c = realloc(t->col, cap * sizeof *c);
  if (c) t->col = c;
  double *w2 = realloc(t->w, cap * sizeof *w2);
  if (w2) t->w = w2;
  if (!r || !c || !w2) {
    k->st = SS_ENOMEM;
    return -1;
  }
  t->cap = cap;
  return 0;
}

void ss_sink_emit_operator(ss_sink *k, size_t row, size_t src, double w) {
  const ss_split *L = k->L;
  const size_t np = ss_split_npar(L, src);
  if (reserve(k, np)) return;
  ss_triplets *t = k->M;
  const double ws = w / (double)np;
  for (size_t q = L->ptr[src]; q < L->ptr[src + 1]; q++) {
    t->row[t->n] = (ss_idx)row;
    t->col[t->n] = L->parent[q];
    t->w[t->n++] = ws;
  }
}

/* Append the m merged entries of row. */
static void flush(ss_sink *k, size_t row, int m, const ss_idx *col, const double *acc) {
  if (reserve(k, (size_t)m)) return;
  ss_triplets *t = k->M;
  for (int i = 0; i < m; i++) {
    t->row[t->n] = (ss_idx)row;
    t->col[t->n] = col[i];
    t->w[t->n++] = acc[i];
  }
}

void ss_sink_emit_many_operator(ss_sink *k, size_t row, int n, const ss_idx *src,
                                const double *w, double scale) {
  enum { CAP = 4 * SS_MAXCELLVERTS };
  ss_idx col[CAP];
  double acc[CAP];
  int m = 0;
  const ss_split *L = k->L;
  for (int j = 0; j < n; j++) {
    if (w[j] == 0.0) continue;
    const size_t np = ss_split_npar(L, src[j]);
    if (np > CAP) {
      ss_sink_emit_operator(k, row, src[j], w[j] * scale);
      continue;
    }
    if (m + np > CAP) { /* more distinct parents than merging has room for */
      flush(k, row, m, col, acc);
      m = 0;
    }
    const double ws = w[j] * scale / (double)np;
    for (size_t q = L->ptr[src[j]]; q < L->ptr[src[j] + 1]; q++) {
      const ss_idx c = L->parent[q];
      int i = 0;
      while (i < m && col[i] != c)
        i++;
      if (i == m) {
        col[m] = c;
        acc[m++] = 0.0;
      }
      acc[i] += ws;
    }
  }
  flush(k, row, m, col, acc);
}

void ss_sink_cell_prepare(const ss_sink *k, int n, const ss_idx *src, ss_sink_cell *c) {
  c->n = n;
  c->src = src;
  c->m = -1;
  if (!k->M || n > SS_MAXCELLVERTS) return;
  const ss_split *L = k->L;
  int m = 0, s = 0;
  for (int j = 0; j < n; j++) {
    const size_t np = ss_split_npar(L, src[j]);
    if (np > (size_t)(SS_SINK_CELLCAP - s)) return; /* c->m stays -1 */
    s += (int)np;
    c->np[j] = (int)np;
    for (size_t q = L->ptr[src[j]]; q < L->ptr[src[j] + 1]; q++) {
      const ss_idx p = L->parent[q];
      int i = 0;
      while (i < m && c->col[i] != p)
        i++;
      if (i == m) {
        c->col[m] = p;
        c->from[m++] = 0;
      }
      c->from[i] |= 1u << j; /* a source's parents are distinct: once each */
    }
  }
  c->m = m;
}

void ss_sink_emit_cell_operator(ss_sink *k, const ss_sink_cell *c, size_t row,
                                const double *w, double scale) {
  if (c->m < 0) {
    ss_sink_emit_many_operator(k, row, c->n, c->src, w, scale);
    return;
  }
  /* ss_sink_emit_many_operator's sums, term by term in the same order (the
   * sources in turn, from 0.0); a column only zero weights reach is left out
   * there, so here too */
  double ws[SS_MAXCELLVERTS];
  unsigned nonzero = 0;
  for (int j = 0; j < c->n; j++) {
    if (w[j] == 0.0) continue;
    ws[j] = w[j] * scale / (double)c->np[j];
    nonzero |= 1u << j;
  }
  if (reserve(k, (size_t)c->m)) return;
  ss_triplets *t = k->M;
  for (int i = 0; i < c->m; i++) {
    unsigned b = c->from[i] & nonzero;
    if (!b) continue;
    double acc = 0.0;
    for (; b; b &= b - 1)
      acc += ws[__builtin_ctz(b)];
    t->row[t->n] = (ss_idx)row;
    t->col[t->n] = c->col[i];
    t->w[t->n++] = acc;
  }
}

ss_status ss_triplets_reserve(ss_triplets *t, size_t n, ss_error *err) {
  if (n <= t->cap) return SS_OK;
  ss_sink k = {NULL, 0, NULL, NULL, t, SS_OK};
  if (reserve(&k, n - t->n)) return ss_error_nomem(err, "refinement operator");
  return SS_OK;
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
  gsl_spmatrix *R = ss_gsl_csr_alloc(nrows, ncols ? ncols : 1, nnz);
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
