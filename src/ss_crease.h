/* ss_crease.h — crease structure of a split surface complex, shared by the
 * Catmull-Clark and Loop rules (Hoppe et al. 1994 conventions).
 *
 * An edge is a crease if it lies in a segment cell or in a number of faces other
 * than two (a boundary or non-manifold edge).  A coarse vertex is
 *   corner  if it is a vertex cell, lies on no edge, has three or more crease
 *           edges, or has one crease edge that is not in exactly two faces;
 *   crease  if it has exactly two crease edges (B-spline rule 1/8, 3/4, 1/8);
 *   smooth  otherwise (the scheme's interior rule; a single sharp segment edge,
 *           a "dart", keeps the smooth rule).
 * Everything is read off the split complex: fine vertices with 2 parents are the
 * coarse edges. */
#ifndef SS_CREASE_H
#define SS_CREASE_H

#include <stdint.h>

#include "ss_split.h"

typedef enum { SS_SMOOTH = 0, SS_CREASE = 1, SS_CORNER = 2 } ss_vertex_kind;

typedef struct {
  uint32_t *nface;      /* per fine vertex: number of fine faces holding it */
  unsigned char *sharp; /* per fine vertex: 1 if it is the midpoint of a crease edge */
  uint32_t *nedge;      /* per coarse vertex: number of edges at it */
  unsigned char *kind;  /* per coarse vertex: an ss_vertex_kind */
} ss_crease;

/* Classify the split complex `fine` whose faces are of type `face` (SS_QUAD or
 * SS_TRIANGLE); `children_at_edge` is the number of fine faces one coarse face
 * puts at the midpoint of each of its edges (2 for quads, 3 for triangles).
 * *out is caller-owned (ss_crease_free).  SS_ENOMEM. */
ss_status ss_crease_classify(const ss_cx *fine, const ss_split *L, ss_cell_type face,
                             int children_at_edge, ss_crease **out, ss_error *err);
void ss_crease_free(ss_crease *c);

/* The coarse vertex of edge midpoint x (2 parents) other than a. */
static inline ss_idx ss_crease_other(const ss_split *L, size_t x, ss_idx a) {
  ss_idx p = L->parent[L->ptr[x]];
  return p == a ? L->parent[L->ptr[x] + 1] : p;
}

#endif
