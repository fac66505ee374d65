/* ss_triedge.h — the edges of a triangle complex: each unordered vertex pair
 * that bounds a triangle once, with the triangles holding it.  The bisection
 * split (ss_split_bisect.c) reads lengths and clusters from it, the quasi 4-8
 * rule (ss_scheme_quasi48.c) 1-rings and boundaries. */
#ifndef SS_TRIEDGE_H
#define SS_TRIEDGE_H

#include "ss_cx.h"

typedef struct {
  size_t ne;           /* number of distinct edges */
  ss_idx *end;         /* 2*ne endpoints, end[2e] < end[2e+1]; edges sorted by them */
  size_t *nface;       /* ne: triangles holding edge e */
  size_t *face;        /* 2*ne: the first two triangles holding e (SIZE_MAX if none) */
  size_t *tedge;       /* 3*ntri: edge of triangle t opposite its corner k is
                          tedge[3t+k] (between corners k+1 and k+2) */
  size_t nv;           /* vertices of the complex */
  size_t *vptr;        /* nv+1 offsets into vnbr */
  ss_idx *vnbr;        /* neighbours of each vertex along edges, ascending */
  unsigned char *vbnd; /* nv: 1 if the vertex ends an edge held by one triangle */
} ss_triedge;

/* Build the edge table of the triangles of cx (other cells are ignored).
 * *out is owned by the caller (ss_triedge_free).  SS_EINPUT for a triangle
 * with a repeated vertex; SS_ENOMEM.  Cost: O(T log T) for T triangles. */
ss_status ss_triedge_new(const ss_cx *cx, ss_triedge **out, ss_error *err);

/* Free; NULL is a no-op. */
void ss_triedge_free(ss_triedge *te);

/* The first edge holding more than two triangles, or SIZE_MAX. */
size_t ss_triedge_nonmanifold(const ss_triedge *te);

#endif
