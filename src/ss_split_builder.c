/* ss_split_builder.c — the parent lists of a split under construction, which
 * every split file (ss_split_multilinear.c, ss_split_tetoct.c,
 * ss_split_bisect.c, ss_split_nvb.c) builds its operator L with; and the
 * freeing of L.  Below every split and below the dispatch in ss_split_refine.c. */
#include "ss_split_builder.h"

#include <stdlib.h>
#include <string.h>

void ss_split_free(ss_split *L) {
  if (!L) return;
  free(L->ptr);
  free(L->parent);
  free(L);
}

ss_status ss_split_builder_init(ss_split_builder *b, size_t ncoarse, size_t expect_new,
                                ss_error *err) {
  memset(b, 0, sizeof *b);
  ss_split *L = calloc(1, sizeof *L);
  if (!L) return ss_error_nomem(err, "split");
  b->L = L;
  L->ncoarse = L->nfine = ncoarse;
  b->vcap = ncoarse + expect_new + 1;
  b->pcap = ncoarse + 2 * expect_new + 1;
  L->ptr = malloc(b->vcap * sizeof *L->ptr);
  L->parent = malloc(b->pcap * sizeof *L->parent);
  if (!L->ptr || !L->parent) {
    ss_split_free(L);
    b->L = NULL;
    return ss_error_nomem(err, "split parents");
  }
  for (size_t v = 0; v < ncoarse; v++) {
    L->ptr[v] = v;
    L->parent[v] = (ss_idx)v;
  }
  L->ptr[ncoarse] = ncoarse;
  return SS_OK;
}

ss_status ss_split_builder_add(ss_split_builder *b, const ss_idx *par, int n,
                               ss_idx *index, ss_error *err) {
  ss_split *L = b->L;
  if (L->nfine >= (size_t)SS_IDX_NONE - 1)
    return ss_error_set(err, SS_EINPUT, "refined complex would exceed %u vertices",
                        (unsigned)SS_IDX_NONE - 1);
  if (L->nfine + 2 > b->vcap) {
    size_t cap = 2 * b->vcap;
    size_t *p = realloc(L->ptr, cap * sizeof *p);
    if (!p) return ss_error_nomem(err, "split parents");
    L->ptr = p;
    b->vcap = cap;
  }
  size_t at = L->ptr[L->nfine];
  if (at + (size_t)n > b->pcap) {
    size_t cap = 2 * b->pcap + (size_t)n;
    ss_idx *p = realloc(L->parent, cap * sizeof *p);
    if (!p) return ss_error_nomem(err, "split parents");
    L->parent = p;
    b->pcap = cap;
  }
  ss_idx *q = L->parent + at;
  for (int i = 0; i < n; i++) { /* insertion sort: a vertex has few parents */
    int j = i;
    for (; j > 0 && q[j - 1] > par[i]; j--)
      q[j] = q[j - 1];
    q[j] = par[i];
  }
  *index = (ss_idx)L->nfine;
  L->nfine++;
  L->ptr[L->nfine] = at + (size_t)n;
  return SS_OK;
}

ss_status ss_split_shared(ss_split_builder *b, ss_hash *h, const uint32_t *key,
                          const ss_idx *par, int n, ss_idx *index, ss_error *err) {
  ss_idx next = (ss_idx)b->L->nfine;
  int inserted = 0;
  ss_status st = ss_hash_insert(h, key, next, index, &inserted, err);
  if (st || !inserted) return st;
  ss_idx got;
  st = ss_split_builder_add(b, par, n, &got, err);
  return st;
}

ss_status ss_split_builder_finish(ss_split_builder *b, const ss_cx *coarse, ss_cx *fine,
                                  ss_error *err) {
  ss_split *L = b->L;
  ss_status st = ss_cx_reserve_vertices(fine, L->nfine, err);
  if (st) return st;
  const size_t dim = (size_t)coarse->dim;
  memcpy(fine->x, coarse->x, coarse->nv * dim * sizeof *fine->x);
  memcpy(fine->vref, coarse->vref, coarse->nv * sizeof *fine->vref);
  for (size_t f = coarse->nv; f < L->nfine; f++) {
    double *y = fine->x + f * dim;
    for (size_t r = 0; r < dim; r++)
      y[r] = 0.0;
    const size_t n = ss_split_npar(L, f);
    for (size_t k = L->ptr[f]; k < L->ptr[f + 1]; k++) {
      const double *x = coarse->x + (size_t)L->parent[k] * dim;
      for (size_t r = 0; r < dim; r++)
        y[r] += x[r];
    }
    for (size_t r = 0; r < dim; r++)
      y[r] /= (double)n;
    fine->vref[f] = 0;
  }
  fine->nv = L->nfine;
  /* give back the slack of amortised growth (a failed shrink is harmless) */
  size_t *p = realloc(L->ptr, (L->nfine + 1) * sizeof *p);
  if (p) L->ptr = p;
  ss_idx *q = realloc(L->parent, L->ptr[L->nfine] * sizeof *q + 1);
  if (q) L->parent = q;
  return SS_OK;
}

ss_status ss_split_builder_hand_over(ss_split_builder *b, ss_status st, ss_cx *fine,
                                     ss_cx **fine_out, ss_split **L_out) {
  if (st) {
    ss_cx_free(fine);
    ss_split_free(b->L);
    fine = NULL;
    b->L = NULL;
  }
  *fine_out = fine;
  *L_out = b->L;
  return st;
}
