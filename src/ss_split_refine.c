/* ss_split_refine.c — the splits' registry: which cells each takes, their names,
 * the dispatch of ss_split_refine to the split files (ss_split_multilinear.c,
 * ss_split_tetoct.c, ss_split_bisect.c, ss_split_nvb.c, all built on
 * ss_split_builder.c below them), and the operator L as a sparse matrix. */
#include "ss_split.h"

#include "ss_gsl.h"
#include "ss_split_impl.h"

int ss_split_accepts(ss_split_kind kind, ss_cell_type t) {
  if (kind == SS_SPLIT_MULTILINEAR)
    return t == SS_VERTEX || t == SS_SEGMENT || t == SS_QUAD || t == SS_HEX;
  if (kind == SS_SPLIT_HEXIFY)
    return t == SS_VERTEX || t == SS_SEGMENT || t == SS_TRIANGLE || t == SS_QUAD ||
           t == SS_TET || t == SS_HEX;
  if (kind == SS_SPLIT_BISECT)
    return t == SS_VERTEX || t == SS_SEGMENT || t == SS_TRIANGLE;
  if (kind == SS_SPLIT_NVB) return t == SS_VERTEX || t == SS_TRIANGLE;
  return t == SS_VERTEX || t == SS_SEGMENT || t == SS_TRIANGLE || t == SS_TET ||
         t == SS_OCT;
}

const char *ss_split_name(ss_split_kind kind) {
  return kind == SS_SPLIT_MULTILINEAR ? "multilinear"
         : kind == SS_SPLIT_BISECT    ? "bisect"
         : kind == SS_SPLIT_NVB       ? "nvb"
         : kind == SS_SPLIT_HEXIFY    ? "hexify"
                                      : "tetoct";
}

ss_status ss_split_refine(ss_split_kind kind, const ss_cx *coarse, ss_cx **fine,
                          ss_split **L, ss_error *err) {
  return ss_split_refine_adapt(kind, coarse, NULL, fine, L, err);
}

ss_status ss_split_refine_adapt(ss_split_kind kind, const ss_cx *coarse,
                                const ss_adapt *adapt, ss_cx **fine, ss_split **L,
                                ss_error *err) {
  *fine = NULL;
  *L = NULL;
  if (adapt && kind != SS_SPLIT_BISECT)
    return ss_error_set(err, SS_EINPUT, "the %s split is not adaptive (bisect is)",
                        ss_split_name(kind));
  for (int t = 0; t < SS_NCELLTYPES; t++)
    if (coarse->nc[t] && !ss_split_accepts(kind, (ss_cell_type)t))
      return ss_error_set(
          err, SS_EINPUT, "the %s split does not take %s (the mesh has %zu)",
          ss_split_name(kind), ss_cell_plural((ss_cell_type)t), coarse->nc[t]);
  ss_status st = ss_cx_validate(coarse, err);
  if (st) return st;
  if (kind == SS_SPLIT_BISECT) return ss_split_bisect_adapt(coarse, adapt, fine, L, err);
  if (kind == SS_SPLIT_NVB) return ss_split_nvb(coarse, fine, L, err);
  if (kind == SS_SPLIT_HEXIFY) return ss_split_hexify(coarse, fine, L, err);
  return kind == SS_SPLIT_MULTILINEAR ? ss_split_multilinear(coarse, fine, L, err)
                                      : ss_split_tetoct(coarse, fine, L, err);
}

ss_status ss_split_matrix(const ss_split *L, gsl_spmatrix **out, ss_error *err) {
  *out = NULL;
  size_t nnz = L->ptr[L->nfine];
  gsl_spmatrix *M = ss_gsl_csr_alloc(L->nfine, L->ncoarse, nnz);
  if (!M) return ss_error_nomem(err, "split matrix");
  for (size_t f = 0; f <= L->nfine; f++)
    M->p[f] = (int)L->ptr[f];
  for (size_t f = 0; f < L->nfine; f++) {
    double w = 1.0 / (double)ss_split_npar(L, f);
    for (size_t k = L->ptr[f]; k < L->ptr[f + 1]; k++) {
      M->i[k] = (int)L->parent[k];
      M->data[k] = w;
    }
  }
  M->nz = nnz;
  *out = M;
  return SS_OK;
}
