/* ss_scc.h — the sparsity of a local subdivision matrix S = [A 0; B C] and the
 * strongly connected components of its outer block C (internal to analysis/:
 * the double-precision path ss_eig and the exact path ss_exact share it).
 *
 * Ordered by its components, C is block lower triangular: the component
 * numbered c reads (has nonzero columns in) only components <= c and the
 * one-ring block, so block forward substitution works in that order, and the
 * spectrum of C is the union of its diagonal blocks' spectra. */
#ifndef SS_SCC_H
#define SS_SCC_H

#include <stddef.h>

#include "ss_error.h"

/* SS_EINPUT (naming the entry) unless 0 < n1 <= n and the leading n1 x n1
 * block of the row-major n x n matrix S is invariant: S[i][j] = 0 for
 * i < n1 <= j. */
ss_status ss_scc_check_form(const double *S, size_t n, size_t n1, ss_error *err);

/* S in compressed rows; in row r the columns < n1 (the part B of the outer
 * rows) come before mid[r], those >= n1 (C) from mid[r] on. */
typedef struct {
  size_t *ptr; /* n + 1 row starts */
  size_t *mid; /* n: first entry of a row with column >= n1 */
  size_t *col; /* nnz column indices, increasing within a row */
  double *val; /* nnz values */
} ss_csr;

/* The nonzero entries of the row-major n x n matrix S.  Returns 0, or -1 when
 * out of memory (then ss_csr_free frees what was allocated). */
int ss_csr_make(const double *S, size_t n, size_t n1, ss_csr *A);

/* Free the arrays (not A itself); the arrays may be NULL. */
void ss_csr_free(ss_csr *A);

/* The strongly connected components of the graph on the outer nodes 0..nc-1
 * (nc = n - n1; node i is row n1 + i of S) with an edge i -> j when
 * S[n1+i][n1+j] != 0. */
typedef struct {
  long n;         /* components */
  size_t *comp;   /* nc outer nodes, component by component */
  size_t *start;  /* n + 1 offsets into comp */
  size_t *cid;    /* nc: the component of each outer node */
  size_t *pos;    /* nc: the place of each outer node in its component */
  size_t largest; /* size of the largest component (0 if nc = 0) */
} ss_scc;

/* The components of A's outer block (Tarjan's algorithm, iterative, O(nnz)),
 * in an order in which block forward substitution works.  Returns 0, or -1
 * when out of memory (then ss_scc_free frees what was allocated). */
int ss_scc_make(const ss_csr *A, size_t n, size_t n1, ss_scc *K);

/* Free the arrays (not K itself); the arrays may be NULL. */
void ss_scc_free(ss_scc *K);

#endif
