/* ss_split_impl.h — what a split file provides to the dispatch in ss_split_refine.c
 * (private): one entry point per split, each called with a validated complex
 * whose cell types the split accepts. */
#ifndef SS_SPLIT_IMPL_H
#define SS_SPLIT_IMPL_H

#include "ss_split.h"

ss_status ss_split_multilinear(const ss_cx *coarse, ss_cx **fine, ss_split **L,
                               ss_error *err);
ss_status ss_split_hexify(const ss_cx *coarse, ss_cx **fine, ss_split **L, ss_error *err);
ss_status ss_split_tetoct(const ss_cx *coarse, ss_cx **fine, ss_split **L, ss_error *err);
ss_status ss_split_bisect(const ss_cx *coarse, ss_cx **fine, ss_split **L, ss_error *err);
/* ss_split_bisect restricted by adapt (NULL: the whole pass). */
ss_status ss_split_bisect_adapt(const ss_cx *coarse, const ss_adapt *adapt, ss_cx **fine,
                                ss_split **L, ss_error *err);
ss_status ss_split_nvb(const ss_cx *coarse, ss_cx **fine, ss_split **L, ss_error *err);

#endif
