/* ss_split_builder.h — the parent lists of a split under construction
 * (ss_split_builder.c), shared by the split files (private). */
#ifndef SS_SPLIT_BUILDER_H
#define SS_SPLIT_BUILDER_H

#include "ss_hash.h"
#include "ss_split.h"

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

/* End a split: on success hand fine and the parent lists to the caller; on
 * failure (st != SS_OK) free both and hand over NULLs.  Returns st. */
ss_status ss_split_builder_hand_over(ss_split_builder *b, ss_status st, ss_cx *fine,
                                     ss_cx **fine_out, ss_split **L_out);

#endif
