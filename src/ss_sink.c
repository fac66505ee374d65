/* ss_sink.c — accumulating rule weights into the refinement operator. */
#include "ss_sink.h"

#include "ss_gsl.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

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

/* ---- rows in order (ss_rows) ---- */

ss_status ss_rows_init(ss_rows *r, size_t nrows, size_t ncols, size_t nnz,
                       ss_error *err) {
  memset(r, 0, sizeof *r);
  r->nrows = nrows;
  r->ncols = ncols;
  if (nnz > (size_t)INT_MAX - 64) nnz = (size_t)INT_MAX - 64;
  r->R = ss_gsl_csr_alloc(nrows ? nrows : 1, ncols ? ncols : 1, nnz + 64);
  r->slot = calloc(ncols + 1, sizeof *r->slot);
  r->gslot = calloc(ncols + 1, sizeof *r->gslot);
  r->tmp = malloc((ncols + 1) * sizeof *r->tmp);
  if (!r->R || !r->slot || !r->gslot || !r->tmp) {
    ss_rows_clear(r);
    return ss_error_nomem(err, "refinement operator");
  }
  r->R->p[0] = 0;
  return SS_OK;
}

void ss_rows_clear(ss_rows *r) {
  if (r->R) gsl_spmatrix_free(r->R);
  free(r->slot);
  free(r->gslot);
  free(r->tmp);
  memset(r, 0, sizeof *r);
}

/* Room for n more entries of the current row; 0, or -1 (k->st set). */
static int rows_room(ss_sink *k, size_t n) {
  ss_rows *r = k->rows;
  const size_t need = r->nnz + r->m + n;
  if (need <= r->R->nzmax) return 0;
  size_t cap = 2 * r->R->nzmax;
  if (cap < need) cap = need;
  if (cap > (size_t)INT_MAX) cap = (size_t)INT_MAX; /* GSL's CSR indices are int */
  if (need > cap || gsl_spmatrix_realloc(cap, r->R) != 0) {
    k->st = SS_ENOMEM;
    return -1;
  }
  return 0;
}

/* Add x to entry (current row, c): the row's first term for c is stored as
 * it is, later ones added, as ss_triplets_csr merges a row's triplets. */
static inline void row_add(ss_sink *k, ss_idx c, double x) {
  ss_rows *r = k->rows;
  const uint32_t s = r->slot[c];
  if (s) {
    r->R->data[r->nnz + s - 1] += x;
    return;
  }
  if (rows_room(k, 1)) return;
  r->R->i[r->nnz + r->m] = (int)c;
  r->R->data[r->nnz + r->m] = x;
  r->slot[c] = (uint32_t)++r->m;
}

/* Close the current row: columns ascending (the columns sorted alone, the
 * values then gathered through their slots), slots cleared. */
static void row_close(ss_rows *r) {
  int *col = r->R->i + r->nnz;
  double *w = r->R->data + r->nnz;
  const size_t m = r->m;
  for (size_t i = 0; i < m; i++)
    r->tmp[i] = w[i];
  for (size_t i = 1; i < m; i++) { /* insertion sort: a row has few columns */
    const int c = col[i];
    size_t j = i;
    for (; j > 0 && col[j - 1] > c; j--)
      col[j] = col[j - 1];
    col[j] = c;
  }
  for (size_t i = 0; i < m; i++) {
    w[i] = r->tmp[r->slot[col[i]] - 1];
    r->slot[col[i]] = 0;
  }
  r->nnz += m;
  r->m = 0;
  r->R->p[r->row + 1] = (int)r->nnz;
}

/* Make `row` the current row (closing the rows before it); 0, or -1 with
 * k->st set when the rule went back to a closed row or past the last. */
static int rows_goto(ss_sink *k, size_t row) {
  ss_rows *r = k->rows;
  if (row == r->row) return 0;
  if (row < r->row || row >= r->nrows) {
    k->st = SS_EINTERNAL;
    return -1;
  }
  row_close(r);
  for (size_t i = r->row + 2; i <= row; i++) /* rows the rule left empty */
    r->R->p[i] = (int)r->nnz;
  r->row = row;
  return 0;
}

ss_status ss_rows_finish(ss_rows *r, gsl_spmatrix **out, ss_error *err) {
  *out = NULL;
  if (!r->R) return ss_error_nomem(err, "refinement operator");
  if (r->nrows) {
    row_close(r);
    for (size_t i = r->row + 2; i <= r->nrows; i++)
      r->R->p[i] = (int)r->nnz;
  }
  r->R->nz = r->nnz;
  *out = r->R;
  r->R = NULL;
  ss_rows_clear(r);
  return SS_OK;
}

/* ss_sink_emit_operator into rows. */
static void rows_emit(ss_sink *k, size_t row, size_t src, double w) {
  if (rows_goto(k, row)) return;
  const ss_split *L = k->L;
  const double ws = w / (double)ss_split_npar(L, src);
  for (size_t q = L->ptr[src]; q < L->ptr[src + 1]; q++)
    row_add(k, L->parent[q], ws);
}

/* ss_sink_emit_many_operator into rows: the same merged sums (a column ->
 * slot map in place of the search), cut where that function cuts them, each
 * then added to the row as its triplet would be. */
static void rows_emit_many(ss_sink *k, size_t row, int n, const ss_idx *src,
                           const double *w, double scale) {
  enum { CAP = 4 * SS_MAXCELLVERTS };
  if (rows_goto(k, row)) return;
  ss_idx col[CAP];
  double acc[CAP];
  int m = 0;
  const ss_split *L = k->L;
  uint8_t *g = k->rows->gslot;
  for (int j = 0; j <= n; j++) {
    size_t np = 0;
    if (j < n) {
      if (w[j] == 0.0) continue;
      np = ss_split_npar(L, src[j]);
      if (np > CAP) {
        rows_emit(k, row, src[j], w[j] * scale);
        continue;
      }
    }
    if (j == n || m + np > CAP) { /* the merged sums go into the row */
      for (int i = 0; i < m; i++) {
        g[col[i]] = 0;
        row_add(k, col[i], acc[i]);
      }
      m = 0;
      if (j == n) break;
    }
    const double ws = w[j] * scale / (double)np;
    for (size_t q = L->ptr[src[j]]; q < L->ptr[src[j] + 1]; q++) {
      const ss_idx c = L->parent[q];
      if (!g[c]) {
        col[m] = c;
        acc[m] = 0.0;
        g[c] = (uint8_t)++m;
      }
      acc[g[c] - 1] += ws;
    }
  }
}

/* ---- triplets ---- */

void ss_sink_emit_operator(ss_sink *k, size_t row, size_t src, double w) {
  if (!ss_sink_wants(k, row)) return;
  if (k->rows) {
    rows_emit(k, row, src, w);
    return;
  }
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
  if (!ss_sink_wants(k, row)) return;
  if (k->rows) {
    rows_emit_many(k, row, n, src, w, scale);
    return;
  }
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

/* Append entry (row, c) = x: into the current row, or as a triplet. */
static inline void put(ss_sink *k, size_t row, ss_idx c, double x) {
  if (k->rows) {
    row_add(k, c, x);
    return;
  }
  ss_triplets *t = k->M;
  t->row[t->n] = (ss_idx)row;
  t->col[t->n] = c;
  t->w[t->n++] = x;
}

void ss_sink_put(ss_sink *k, size_t row, ss_idx col, double x) {
  if (!ss_sink_wants(k, row)) return;
  if (k->rows) {
    if (!rows_goto(k, row)) row_add(k, col, x);
    return;
  }
  if (!reserve(k, 1)) put(k, row, col, x);
}

void ss_sink_cells_clear(ss_sink_cells *c) {
  free(c->off);
  free(c->col);
  free(c->from);
  free(c->np);
  free(c->g);
  free(c->gw);
  free(c->gscale);
  free(c->gmask);
  free(c->glast);
  memset(c, 0, sizeof *c);
}

ss_status ss_sink_cells_prepare(const ss_sink *k, int n, size_t ncells, const ss_idx *src,
                                ss_sink_cells *c, ss_error *err) {
  memset(c, 0, sizeof *c);
  c->n = n;
  c->src = src;
  if (!(k->M || k->rows) || !ncells) return SS_OK;
  const ss_split *L = k->L;
  /* room: each cell's parent slots, at most SS_SINK_CELLCAP merged */
  size_t room = 0;
  for (size_t i = 0; i < ncells * (size_t)n; i++)
    room += ss_split_npar(L, src[i]);
  uint8_t *map = calloc(L->ncoarse + 1, 1); /* parent -> 1 + its place, 0: none */
  c->off = malloc((ncells + 1) * sizeof *c->off);
  c->col = malloc((room + 1) * sizeof *c->col);
  c->from = malloc(room + 1);
  c->np = malloc(ncells * (size_t)n + 1);
  c->g = malloc((2 * room + 1) * sizeof *c->g);
  c->gw = calloc(2 * ncells, sizeof *c->gw);
  c->gscale = malloc(2 * ncells * sizeof *c->gscale);
  c->gmask = malloc(2 * ncells * sizeof *c->gmask);
  c->glast = calloc(ncells, 1);
  if (!map || !c->off || !c->col || !c->from || !c->np || !c->g || !c->gw || !c->gscale ||
      !c->gmask || !c->glast) {
    free(map);
    ss_sink_cells_clear(c);
    return ss_error_nomem(err, "refinement operator");
  }
  size_t at = 0;
  for (size_t i = 0; i < ncells; i++) {
    const ss_idx *s = src + i * (size_t)n;
    uint8_t *np = c->np + i * (size_t)n;
    ss_idx *col = c->col + at;
    uint8_t *from = c->from + at;
    c->off[i] = at;
    int m = 0, slots = 0, merged = n <= 8, wanted = !k->want;
    for (int j = 0; j < n && !wanted; j++)
      wanted = k->want[s[j]];
    if (!wanted) { /* no row of the cell is emitted (ss_sink_emit_cell_operator
                      is called for its corners' rows only): nothing to merge */
      np[0] = 0;
      continue;
    }
    for (int j = 0; j < n && merged; j++) {
      const size_t p = ss_split_npar(L, s[j]);
      if (p > (size_t)(SS_SINK_CELLCAP - slots)) {
        merged = 0;
        break;
      }
      slots += (int)p;
      np[j] = (uint8_t)p;
      for (size_t q = L->ptr[s[j]]; q < L->ptr[s[j] + 1]; q++) {
        const ss_idx v = L->parent[q];
        if (!map[v]) {
          col[m] = v;
          from[m] = 0;
          map[v] = (uint8_t)++m;
        }
        from[map[v] - 1] |= (uint8_t)(1u << j); /* a source's parents are
                                                   distinct: once each */
      }
    }
    for (int u = 0; u < m; u++)
      map[col[u]] = 0;
    if (merged)
      at += (size_t)m;
    else
      np[0] = 0;
  }
  c->off[ncells] = at;
  free(map);
  return SS_OK;
}

void ss_sink_emit_cell_operator(ss_sink *k, const ss_sink_cells *c, size_t i, size_t row,
                                const double *w, double scale) {
  if (!ss_sink_wants(k, row)) return;
  const int n = c->n;
  const uint8_t *np = c->np + i * (size_t)n;
  if (!np[0]) {
    ss_sink_emit_many_operator(k, row, n, c->src + i * (size_t)n, w, scale);
    return;
  }
  if (k->rows && rows_goto(k, row)) return;
  const size_t b = c->off[i], e = c->off[i + 1];
  if (!k->rows && reserve(k, e - b)) return;
  /* the kept sums of this weight row and scale, if either slot has them */
  int slot = 0;
  while (slot < 2 &&
         (c->gw[2 * i + (size_t)slot] != w || c->gscale[2 * i + (size_t)slot] != scale))
    slot++;
  if (slot == 2) { /* the slot not used last */
    slot = !c->glast[i];
    /* ss_sink_emit_many_operator's sums, term by term in the same order (the
     * sources in turn, from 0.0); a column only zero weights reach is left
     * out there, so here too */
    double ws[8];
    unsigned nonzero = 0;
    for (int j = 0; j < n; j++) {
      if (w[j] == 0.0) continue;
      ws[j] = w[j] * scale / (double)np[j];
      nonzero |= 1u << j;
    }
    double *g = c->g + 2 * b + (size_t)slot * (e - b);
    uint32_t mask = 0;
    for (size_t q = b; q < e; q++) {
      unsigned f = c->from[q] & nonzero;
      if (!f) continue;
      double acc = 0.0;
      for (; f; f &= f - 1)
        acc += ws[__builtin_ctz(f)];
      g[q - b] = acc;
      mask |= 1u << (q - b);
    }
    c->gw[2 * i + (size_t)slot] = w;
    c->gscale[2 * i + (size_t)slot] = scale;
    c->gmask[2 * i + (size_t)slot] = mask;
  }
  c->glast[i] = (uint8_t)slot;
  const double *g = c->g + 2 * b + (size_t)slot * (e - b);
  const uint32_t mask = c->gmask[2 * i + (size_t)slot];
  if (!k->rows) {
    for (uint32_t f = mask; f; f &= f - 1) {
      const size_t u = (size_t)__builtin_ctz(f);
      put(k, row, c->col[b + u], g[u]);
    }
    return;
  }
  /* into the row: row_add's steps with the room made once */
  if (rows_room(k, e - b)) return;
  ss_rows *r = k->rows;
  uint32_t *slotof = r->slot;
  int *rc = r->R->i + r->nnz;
  double *rw = r->R->data + r->nnz;
  size_t m = r->m;
  for (size_t u = 0; u < e - b; u++) {
    if (!(mask >> u & 1u)) continue;
    const ss_idx col = c->col[b + u];
    const uint32_t sl = slotof[col];
    if (sl)
      rw[sl - 1] += g[u];
    else {
      rc[m] = (int)col;
      rw[m] = g[u];
      slotof[col] = (uint32_t)++m;
    }
  }
  r->m = m;
}

ss_status ss_triplets_reserve(ss_triplets *t, size_t n, ss_error *err) {
  if (n <= t->cap) return SS_OK;
  ss_sink k = {NULL, 0, NULL, NULL, t, SS_OK, NULL, NULL};
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
