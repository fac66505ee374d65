/* ss_split_tri.h — what the two triangle-bisection splits (bisect, nvb:
 * ss_split_bisect.c, ss_split_nvb.c) share (ss_split_tri.c; private). */
#ifndef SS_SPLIT_TRI_H
#define SS_SPLIT_TRI_H

#include "ss_cx.h"
#include "ss_triedge.h"

/* The edge table of coarse's triangles, refusing (SS_EINPUT) the first edge
 * held by more than two of them, by its vertices (1-based); SS_ENOMEM. */
ss_status ss_split_tri_edges(const ss_cx *coarse, ss_triedge **te, ss_error *err);
/* A new fine complex with coarse's vertex cells copied and room for twice its
 * triangles (on failure *fine may be set: the caller frees it).  SS_ENOMEM. */
ss_status ss_split_tri_fine(const ss_cx *coarse, ss_cx **fine, ss_error *err);

#endif
