/* ss_star_impl.h — private helpers shared by the star builders. */
#ifndef SS_STAR_IMPL_H
#define SS_STAR_IMPL_H

#include "ss_star.h"

/* Allocate a star of the given kind with room for nv vertices and ncells cells
 * of type t, an ncoord-dimensional chart (axis zeroed) and no vertices yet. The
 * centre fields are set from the kind (vertex 0; 0 1; 0 1 2).  SS_ENOMEM. */
ss_status ss_star_alloc(ss_star_kind kind, ss_cell_type t, int n, int ncoord, size_t nv,
                        size_t ncells, ss_star **out, ss_error *err);

/* Append a vertex with coordinates c; its position is computed from s->axis,
 * so the axes must be set first.  SS_ENOMEM. */
ss_status ss_star_push_vertex(ss_star *s, ss_star_coord c, ss_error *err);

/* Append cell number cx->nc[t] (reference = that number) with vertices v. */
ss_status ss_star_push_cell(ss_star *s, const ss_idx *v, ss_error *err);

/* Final check: every cell positive.  SS_ENUMERIC naming the first that is not. */
ss_status ss_star_check_positive(const ss_star *s, ss_error *err);

#endif
