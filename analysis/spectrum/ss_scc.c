/* ss_scc.c — compressed rows of S and the strongly connected components of its
 * outer block.  Method: ss_scc.h. */
#include "ss_scc.h"

#include <stdint.h>
#include <stdlib.h>

ss_status ss_scc_check_form(const double *S, size_t n, size_t n1, ss_error *err) {
  if (!S || n1 == 0 || n1 > n)
    return ss_error_set(err, SS_EINPUT,
                        "one-ring block of %zu rows in a %zu x %zu matrix", n1, n, n);
  for (size_t i = 0; i < n1; i++)
    for (size_t j = n1; j < n; j++)
      if (S[i * n + j] != 0.0)
        return ss_error_set(err, SS_EINPUT,
                            "the one-ring block is not invariant: S[%zu][%zu] = %g", i, j,
                            S[i * n + j]);
  return SS_OK;
}

void ss_csr_free(ss_csr *A) {
  free(A->ptr);
  free(A->mid);
  free(A->col);
  free(A->val);
  A->ptr = A->mid = A->col = NULL;
  A->val = NULL;
}

int ss_csr_make(const double *S, size_t n, size_t n1, ss_csr *A) {
  size_t nnz = 0;
  for (size_t k = 0; k < n * n; k++)
    nnz += S[k] != 0.0;
  A->ptr = malloc((n + 1) * sizeof *A->ptr);
  A->mid = malloc((n + 1) * sizeof *A->mid);
  A->col = malloc((nnz + 1) * sizeof *A->col);
  A->val = malloc((nnz + 1) * sizeof *A->val);
  if (!A->ptr || !A->mid || !A->col || !A->val) return -1;
  size_t q = 0;
  for (size_t i = 0; i < n; i++) {
    A->ptr[i] = q;
    A->mid[i] = SIZE_MAX;
    for (size_t j = 0; j < n; j++) {
      if (S[i * n + j] == 0.0) continue;
      if (j >= n1 && A->mid[i] == SIZE_MAX) A->mid[i] = q;
      A->col[q] = j;
      A->val[q++] = S[i * n + j];
    }
    if (A->mid[i] == SIZE_MAX) A->mid[i] = q;
  }
  A->ptr[n] = q;
  return 0;
}

/* Tarjan emits a component after every component it reaches, so its order is
 * one in which block forward substitution works.  Returns the number of
 * components, or -1 when out of memory. */
static long tarjan(const ss_csr *A, size_t n, size_t n1, size_t *comp, size_t *start) {
  const size_t nc = n - n1;
  size_t *index = malloc((nc + 1) * sizeof *index), *low = malloc((nc + 1) * sizeof *low),
         *stack = malloc((nc + 1) * sizeof *stack),
         *call = malloc((nc + 1) * sizeof *call), *next = malloc((nc + 1) * sizeof *next);
  unsigned char *on = calloc(nc + 1, 1);
  long ncomp = -1;
  if (!index || !low || !stack || !call || !next || !on) goto done;
  for (size_t i = 0; i < nc; i++)
    index[i] = SIZE_MAX;
  size_t counter = 0, sp = 0, emitted = 0;
  ncomp = 0;
  start[0] = 0;
  for (size_t root = 0; root < nc; root++) {
    if (index[root] != SIZE_MAX) continue;
    size_t depth = 0;
    call[depth++] = root;
    index[root] = low[root] = counter++;
    next[root] = A->mid[n1 + root];
    stack[sp++] = root;
    on[root] = 1;
    while (depth) {
      size_t v = call[depth - 1];
      int descended = 0;
      while (next[v] < A->ptr[n1 + v + 1]) {
        size_t w = A->col[next[v]++] - n1;
        if (w == v) continue;
        if (index[w] == SIZE_MAX) {
          index[w] = low[w] = counter++;
          next[w] = A->mid[n1 + w];
          stack[sp++] = w;
          on[w] = 1;
          call[depth++] = w;
          descended = 1;
          break;
        }
        if (on[w] && index[w] < low[v]) low[v] = index[w];
      }
      if (descended) continue;
      if (low[v] == index[v]) {
        size_t w;
        do {
          w = stack[--sp];
          on[w] = 0;
          comp[emitted++] = w;
        } while (w != v);
        start[++ncomp] = emitted;
      }
      depth--;
      if (depth) {
        size_t u = call[depth - 1];
        if (low[v] < low[u]) low[u] = low[v];
      }
    }
  }
done:
  free(index);
  free(low);
  free(stack);
  free(call);
  free(next);
  free(on);
  return ncomp;
}

void ss_scc_free(ss_scc *K) {
  free(K->comp);
  free(K->start);
  free(K->cid);
  free(K->pos);
  K->comp = K->start = K->cid = K->pos = NULL;
}

int ss_scc_make(const ss_csr *A, size_t n, size_t n1, ss_scc *K) {
  const size_t nc = n - n1;
  K->n = 0;
  K->largest = 0;
  K->comp = malloc((nc + 1) * sizeof *K->comp);
  K->start = malloc((nc + 2) * sizeof *K->start);
  K->cid = malloc((nc + 1) * sizeof *K->cid);
  K->pos = malloc((nc + 1) * sizeof *K->pos);
  if (!K->comp || !K->start || !K->cid || !K->pos) return -1;
  K->n = tarjan(A, n, n1, K->comp, K->start);
  if (K->n < 0) return -1;
  for (long c = 0; c < K->n; c++) {
    const size_t b = K->start[c], sz = K->start[c + 1] - b;
    if (sz > K->largest) K->largest = sz;
    for (size_t q = 0; q < sz; q++) {
      K->cid[K->comp[b + q]] = (size_t)c;
      K->pos[K->comp[b + q]] = q;
    }
  }
  return 0;
}
