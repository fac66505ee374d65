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
#include <stdint.h>

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

/* Operator rows assembled as a rule emits them, for rules that send their
 * rows one after another in increasing row order (every emission for row r
 * before any for a later row; ss_scheme.rows_in_order): the current row's
 * entries are summed in place through a column -> slot map over the coarse
 * vertices and the row is closed, its columns sorted, when the next one
 * begins, so R is written in CSR form directly, with no triplet list to
 * bucket and merge.  Each entry is summed in the order the rule sends its
 * terms (the first term, then += each later one), which is how
 * ss_triplets_csr sums the same emissions: both give R bit for bit. */
typedef struct {
  size_t nrows, ncols; /* R's size: fine x coarse vertices */
  size_t row;          /* the row being summed; rows before it are closed */
  gsl_spmatrix *R;     /* the CSR matrix being written: R->p the closed rows'
                          starts, R->i and R->data their entries, then the
                          current row's; R->nzmax the room (it grows) */
  size_t nnz;          /* entries of the closed rows */
  size_t m;            /* entries of the current row, at R->i + nnz */
  uint32_t *slot;      /* ncols: 1 + position of the column in the current
                          row, 0 when absent (cleared as the row closes) */
  uint8_t *gslot;      /* ncols: 1 + position of the column in the sums of
                          one ss_sink_emit_many call, 0 when absent */
  double *tmp;         /* ncols: the current row's values while it is sorted */
} ss_rows;

/* Empty rows for an nrows x ncols operator, with room for about nnz entries
 * (a guess; they grow).  SS_ENOMEM (r cleared). */
ss_status ss_rows_init(ss_rows *r, size_t nrows, size_t ncols, size_t nnz, ss_error *err);
/* Close the last rows and hand the CSR matrix over (*out, caller frees with
 * gsl_spmatrix_free; its room may exceed its entries); r is cleared either
 * way.  SS_ENOMEM (r never initialised). */
ss_status ss_rows_finish(ss_rows *r, gsl_spmatrix **out, ss_error *err);
/* Free r's memory (a no-op on a cleared r). */
void ss_rows_clear(ss_rows *r);

typedef struct {
  const ss_split *L;  /* parents of the fine vertices */
  size_t dim;         /* coordinates per vertex (positions mode) */
  const double *xlin; /* positions mode: split positions, nfine*dim; else NULL */
  double *y;          /* positions mode: accumulated new positions, nfine*dim */
  ss_triplets *M;     /* operator mode, any row order: the entries of R; else NULL */
  ss_status st;       /* SS_OK; SS_ENOMEM once an insertion into M or rows
                         failed; SS_EINTERNAL once a row came out of order */
  ss_rows *rows;      /* operator mode, rows in order (instead of M); else NULL */
  const unsigned char *want; /* operator mode: emissions to row r are dropped
                                unless want[r]; NULL: every row is wanted */
} ss_sink;

/* Whether k takes emissions to row (a rule may skip a row's work if not). */
static inline int ss_sink_wants(const ss_sink *k, size_t row) {
  return !k->want || k->want[row];
}

/* Add x to entry (row, col) of the operator (rows in order or triplets), as
 * one parent's term of an emission would be: for operators that are not a
 * rule's (a product of two).  k->st as for emissions. */
void ss_sink_put(ss_sink *k, size_t row, ss_idx col, double x);

/* Operator-mode emission (out of line: it walks the parents). */
void ss_sink_emit_operator(ss_sink *k, size_t row, size_t src, double w);

/* Operator-mode ss_sink_emit_many: the sources' parents are merged into
 * distinct coarse columns before they are appended (a fine hex's 8 sources
 * have 27 parent slots but at most 8 distinct parents), which cuts the triplet
 * list, and with it the assembly of R, several-fold.  Each merged entry is
 * summed from 0.0 over the sources in turn; into rows, the merged entries are
 * then added to the row exactly as their triplets would be. */
void ss_sink_emit_many_operator(ss_sink *k, size_t row, int n, const ss_idx *src,
                                const double *w, double scale);

/* The cells of one type with each cell's sources' parents merged once
 * (operator mode), for a rule that sends a cell's weights row by row, so that
 * it visits the cell once per vertex: the search for a cell's distinct
 * parents, the costly part of ss_sink_emit_many_operator, is done once per
 * cell instead of once per visit. */
enum { SS_SINK_CELLCAP = 4 * SS_MAXCELLVERTS }; /* parent slots merged at most */
typedef struct {
  int n;             /* sources per cell (its vertices) */
  const ss_idx *src; /* ncells * n sources (not owned: must outlive the use) */
  size_t *off;       /* ncells + 1: cell c's distinct parents are col[off[c] ..
                        off[c + 1]); NULL outside operator mode */
  ss_idx *col;       /* the distinct parents, in order of first appearance */
  uint8_t *from;     /* per distinct parent: bit j set when it is a parent of
                        source j */
  uint8_t *np;       /* ncells * n: parents of each source; 0 in a cell's first
                        slot: more parent slots than SS_SINK_CELLCAP, the cell's
                        rows then go through ss_sink_emit_many_operator */
  /* The sums of a cell's last two rows of different weights are kept with
   * what they depend on (the weight row, by address, and the scale): a
   * later row of the cell with the same two (MLCA's uniform masks at
   * vertices of equal valence) takes them as they are, the same bits
   * without summing again. */
  double *g;         /* per cell: two slots of sums, one per distinct parent
                        (slot s of cell i at 2 off[i] + s (off[i + 1] - off[i])) */
  const double **gw; /* per cell and slot: the weight row of the sums; NULL:
                        none yet */
  double *gscale;    /* per cell and slot: their scale */
  uint32_t *gmask;   /* per cell and slot: bit u set when distinct parent u
                        has a sum (a parent only zero weights reach has none) */
  uint8_t *glast;    /* per cell: the slot used last (the other is replaced) */
} ss_sink_cells;

/* Prepare c for the ncells cells whose vertices are src (n each, kept by
 * pointer).  Only operator mode merges; otherwise c just holds src.  A cell
 * none of whose vertices' rows the sink wants is not merged (its rows are
 * dropped anyway): emit a cell only into one of its own vertices' rows.
 * SS_ENOMEM (c cleared). */
ss_status ss_sink_cells_prepare(const ss_sink *k, int n, size_t ncells, const ss_idx *src,
                                ss_sink_cells *c, ss_error *err);
/* Free c's memory (the sources are not c's). */
void ss_sink_cells_clear(ss_sink_cells *c);

/* Operator-mode ss_sink_emit_cell: the same entries with the same values as
 * ss_sink_emit_many_operator over cell i's sources (each entry summed over
 * the sources in the same order; only the order of a row's distinct columns
 * may differ, which the CSR assembly does not see).  Rows of a cell that
 * share a weight row should pass the same address w (the kept sums are
 * found by it). */
void ss_sink_emit_cell_operator(ss_sink *k, const ss_sink_cells *c, size_t i, size_t row,
                                const double *w, double scale);

/* Send weight w from split vertex src to fine vertex row. */
static inline void ss_sink_emit(ss_sink *k, size_t row, size_t src, double w) {
  if (k->M || k->rows) {
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
  if (k->M || k->rows) {
    ss_sink_emit_many_operator(k, row, n, src, w, scale);
    return;
  }
  double acc[SS_MAXDIM];
  const size_t dim = k->dim;
  for (size_t r = 0; r < dim; r++)
    acc[r] = 0.0;
  for (int j = 0; j < n; j++) {
    const double *x = k->xlin + (size_t)src[j] * dim;
    for (size_t r = 0; r < dim; r++)
      acc[r] += w[j] * x[r];
  }
  double *y = k->y + row * dim;
  for (size_t r = 0; r < dim; r++)
    y[r] += scale * acc[r];
}

/* ss_sink_emit_many over the sources of cell i of a prepared table
 * (ss_sink_cells_prepare). */
static inline void ss_sink_emit_cell(ss_sink *k, const ss_sink_cells *c, size_t i,
                                     size_t row, const double *w, double scale) {
  if (k->M || k->rows) {
    ss_sink_emit_cell_operator(k, c, i, row, w, scale);
    return;
  }
  ss_sink_emit_many(k, row, c->n, c->src + i * (size_t)c->n, w, scale);
}

#endif
