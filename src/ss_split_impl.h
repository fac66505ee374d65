/* ss_split_impl.h — private helpers shared by the split implementations. */
#ifndef SS_SPLIT_IMPL_H
#define SS_SPLIT_IMPL_H

#include "ss_hash.h"
#include "ss_split.h"
#include "ss_triedge.h"

/* Parent lists under construction; new vertices are appended in order. */
typedef struct {
  ss_split *L; /* the operator being built (ptr/parent grow) */
  size_t vcap; /* capacity of L->ptr, in entries */
  size_t pcap; /* capacity of L->parent */
} ss_split_builder;

ss_status ss_split_builder_init(ss_split_builder *b, size_t ncoarse, size_t expect_new,
                                ss_error *err);
/* Append a new fine vertex with parents par[0..n) (any order); its index is
 * returned in *index.  SS_ENOMEM; SS_EINPUT when indices overflow. */
ss_status ss_split_builder_add(ss_split_builder *b, const ss_idx *par, int n,
                               ss_idx *index, ss_error *err);
/* Index of the shared vertex with the given parents, keyed in h by `key`
 * (width words); created on first use. */
ss_status ss_split_shared(ss_split_builder *b, ss_hash *h, const uint32_t *key,
                          const ss_idx *par, int n, ss_idx *index, ss_error *err);
/* Give the fine complex its vertices: coarse ones copied (with references), new
 * ones at the centroid of their parents.  Shrinks the builder's arrays. */
ss_status ss_split_builder_finish(ss_split_builder *b, const ss_cx *coarse, ss_cx *fine,
                                  ss_error *err);

/* For the two triangle-bisection splits (bisect, nvb; ss_split_bisect.c):
 * the edge table of coarse's triangles, refusing (SS_EINPUT) the first edge
 * held by more than two of them, by its vertices (1-based); and a new fine
 * complex with coarse's vertex cells copied and room for twice its
 * triangles (on failure *fine may be set: the caller frees it). */
ss_status ss_split_tri_edges(const ss_cx *coarse, ss_triedge **te, ss_error *err);
ss_status ss_split_tri_fine(const ss_cx *coarse, ss_cx **fine, ss_error *err);

ss_status ss_split_multilinear(const ss_cx *coarse, ss_cx **fine, ss_split **L,
                               ss_error *err);
ss_status ss_split_tetoct(const ss_cx *coarse, ss_cx **fine, ss_split **L, ss_error *err);
ss_status ss_split_bisect(const ss_cx *coarse, ss_cx **fine, ss_split **L, ss_error *err);
ss_status ss_split_nvb(const ss_cx *coarse, ss_cx **fine, ss_split **L, ss_error *err);

/* End a split: on success hand fine and the parent lists to the caller; on
 * failure (st != SS_OK) free both and hand over NULLs.  Returns st. */
ss_status ss_split_builder_hand_over(ss_split_builder *b, ss_status st, ss_cx *fine,
                                     ss_cx **fine_out, ss_split **L_out);

#endif
