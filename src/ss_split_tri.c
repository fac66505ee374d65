/* ss_split_tri.c — what the two triangle-bisection splits share
 * (ss_split_bisect.c, ss_split_nvb.c): the edge table of the coarse
 * triangles, refusing non-manifold edges, and the fine complex begun with the
 * coarse vertex cells. */
#include "ss_split_tri.h"

#include <stdint.h>

ss_status ss_split_tri_edges(const ss_cx *coarse, ss_triedge **te, ss_error *err) {
  ss_status st = ss_triedge_new(coarse, te, err);
  if (st) return st;
  const size_t bad = ss_triedge_nonmanifold(*te);
  if (bad == SIZE_MAX) return SS_OK;
  st = ss_error_set(err, SS_EINPUT,
                    "non-manifold edge: the edge between vertices %lu and %lu is held by "
                    "%zu triangles (at most 2 allowed)",
                    (unsigned long)(*te)->end[2 * bad] + 1,
                    (unsigned long)(*te)->end[2 * bad + 1] + 1, (*te)->nface[bad]);
  ss_triedge_free(*te);
  *te = NULL;
  return st;
}

ss_status ss_split_tri_fine(const ss_cx *coarse, ss_cx **fine, ss_error *err) {
  ss_status st = ss_cx_new(coarse->dim, fine, err);
  if (!st) st = ss_cx_reserve_cells(*fine, SS_VERTEX, coarse->nc[SS_VERTEX], err);
  if (!st) st = ss_cx_reserve_cells(*fine, SS_TRIANGLE, 2 * coarse->nc[SS_TRIANGLE], err);
  for (size_t c = 0; !st && c < coarse->nc[SS_VERTEX]; c++)
    st = ss_cx_add_cell(*fine, SS_VERTEX, ss_cx_cell(coarse, SS_VERTEX, c),
                        coarse->cref[SS_VERTEX][c], err);
  return st; /* on failure *fine is the caller's to free */
}
