/* ss_sink.h — where a scheme's rule sends its weights.
 *
 * A rule says "fine vertex `row` receives weight w times the split position of
 * fine vertex `src`" (the split position is row src of L applied to the coarse
 * points).  The same rule code therefore serves two uses (DESIGN section 3):
 *  - positions: y[row] += w * xlin[src], for subdividing whole meshes fast;
 *  - operator:  R(row, p) += w / |parents(src)| for each parent p of src, giving
 *    the refinement operator R = (rule) * L from coarse to fine vertices, from
 *    which local subdivision matrices are read. */
#ifndef SS_SINK_H
#define SS_SINK_H

#include <stddef.h> /* gsl_spmatrix.h uses size_t without including it */

#include <gsl/gsl_spmatrix.h>

#include "ss_split.h"

/* Operator entries as an unsorted list of (row, column, weight) triplets;
 * repeated positions are summed when the list becomes a CSR matrix
 * (ss_triplets_csr).  Appending is O(1), which GSL's COO format with its
 * search tree per insertion is not. */
typedef struct {
  size_t n, cap; /* triplets held, allocated */
  ss_idx *row;   /* rows (fine vertices) */
  ss_idx *col;   /* columns (coarse vertices) */
  double *w;     /* weights */
} ss_triplets;

/* The nrows x ncols CSR matrix summing the triplets (*out, caller frees with
 * gsl_spmatrix_free).  SS_ENOMEM. */
ss_status ss_triplets_csr(const ss_triplets *t, size_t nrows, size_t ncols,
                          gsl_spmatrix **out, ss_error *err);
void ss_triplets_clear(ss_triplets *t);
/* Room for at least n triplets in t (an estimate made before a rule runs
 * saves the copies of growing by doubling).  SS_ENOMEM (t unchanged). */
ss_status ss_triplets_reserve(ss_triplets *t, size_t n, ss_error *err);

typedef struct {
  const ss_split *L;  /* parents of the fine vertices */
  size_t dim;         /* coordinates per vertex (positions mode) */
  const double *xlin; /* positions mode: split positions, nfine*dim; else NULL */
  double *y;          /* positions mode: accumulated new positions, nfine*dim */
  ss_triplets *M;     /* operator mode: the entries of R; else NULL */
  ss_status st;       /* SS_OK, or SS_ENOMEM once an insertion into M failed */
} ss_sink;

/* Operator-mode emission (out of line: it walks the parents). */
void ss_sink_emit_operator(ss_sink *k, size_t row, size_t src, double w);

/* Operator-mode ss_sink_emit_many: the sources' parents are merged into
 * distinct coarse columns before they are appended (a fine hex's 8 sources
 * have 27 parent slots but at most 8 distinct parents), which cuts the triplet
 * list, and with it the assembly of R, several-fold. */
void ss_sink_emit_many_operator(ss_sink *k, size_t row, int n, const ss_idx *src,
                                const double *w, double scale);

/* A cell's sources with their parents merged once (operator mode), for the
 * several rows a cell sends weights to over the same sources: the search for
 * distinct parents, the costly part of ss_sink_emit_many_operator, is then
 * done once per cell instead of once per row. */
enum { SS_SINK_CELLCAP = 4 * SS_MAXCELLVERTS }; /* parent slots merged at most */
typedef struct {
  int n;                          /* sources */
  const ss_idx *src;              /* the sources, n (not owned) */
  int m;                          /* distinct parents; -1: more than the caps, rows
                                     then go through ss_sink_emit_many_operator */
  ss_idx col[SS_SINK_CELLCAP];    /* the distinct parents, in order of first
                                     appearance over the sources' parent lists */
  unsigned from[SS_SINK_CELLCAP]; /* per distinct parent: bit j set when it is a
                                     parent of source j */
  int np[SS_MAXCELLVERTS];        /* parents of each source */
} ss_sink_cell;

/* Prepare c for rows over the n sources src (kept by pointer: it must
 * outlive c's use).  Only meaningful in operator mode; cheap otherwise. */
void ss_sink_cell_prepare(const ss_sink *k, int n, const ss_idx *src, ss_sink_cell *c);

/* Operator-mode ss_sink_emit_cell: the same triplets with the same values as
 * ss_sink_emit_many_operator over c's sources (each entry summed over the
 * sources in the same order; only the order of a row's distinct columns may
 * differ, which the CSR assembly does not see). */
void ss_sink_emit_cell_operator(ss_sink *k, const ss_sink_cell *c, size_t row,
                                const double *w, double scale);

/* Send weight w from split vertex src to fine vertex row. */
static inline void ss_sink_emit(ss_sink *k, size_t row, size_t src, double w) {
  if (k->M) {
    ss_sink_emit_operator(k, row, src, w);
    return;
  }
  double *y = k->y + row * k->dim;
  const double *x = k->xlin + src * k->dim;
  for (size_t r = 0; r < k->dim; r++)
    y[r] += w * x[r];
}

/* Send weights scale * w[j] from split vertices src[j] (j < n) to fine vertex
 * row: the same as n calls of ss_sink_emit, but in positions mode the sum is
 * formed locally and written once, which keeps a whole-mesh pass cache-bound
 * on the cell's few vertices instead of scattering n writes. */
static inline void ss_sink_emit_many(ss_sink *k, size_t row, int n, const ss_idx *src,
                                     const double *w, double scale) {
  if (k->M) {
    ss_sink_emit_many_operator(k, row, n, src, w, scale);
    return;
  }
  double acc[SS_MAXDIM] = {0.0};
  const size_t dim = k->dim;
  for (int j = 0; j < n; j++) {
    const double *x = k->xlin + (size_t)src[j] * dim;
    for (size_t r = 0; r < dim; r++)
      acc[r] += w[j] * x[r];
  }
  double *y = k->y + row * dim;
  for (size_t r = 0; r < dim; r++)
    y[r] += scale * acc[r];
}

/* ss_sink_emit_many over the sources of a prepared cell (ss_sink_cell_prepare). */
static inline void ss_sink_emit_cell(ss_sink *k, const ss_sink_cell *c, size_t row,
                                     const double *w, double scale) {
  if (k->M) {
    ss_sink_emit_cell_operator(k, c, row, w, scale);
    return;
  }
  ss_sink_emit_many(k, row, c->n, c->src, w, scale);
}

#endif
