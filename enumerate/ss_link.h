/* ss_link.h — links: simplicial triangulations of the 2-sphere.
 *
 * The link of a vertex v of a volume mesh has a vertex per edge at v, an edge
 * per face at v and a triangle per cell at v (DESIGN section 1).  A link is
 * stored as a rotation system: for every vertex its neighbours in cyclic
 * order, all vertices turning the same way, so that for consecutive neighbours
 * w, w' of v the triangle (v, w, w') is a face.  Valid links are simple (no
 * loops or multi-edges), every vertex has degree >= 3, the rotation system is
 * consistent (w follows w' around v iff ... the faces close up) and the
 * surface it spans is a sphere (V - E + F = 2, connected); such graphs are
 * exactly the 3-connected planar triangulations.
 *
 * Text form: plantri's ASCII format, one link per line:
 *     4 bcd,adc,abd,acb
 * the vertex count, then for each vertex (a, b, c, ...) its neighbours in
 * cyclic order.  Names run a..z then A..Z (52 vertices); larger links use 1-based
 * decimal numbers separated by spaces inside each list ("60 2 3 4,1 4 3,...").
 * The names "tetrahedron", "octahedron", "icosahedron" and "bipyramid:N"
 * (N >= 3 equator vertices) are accepted wherever a link is read.
 *
 * Mirror images are identified: a link and its reflection are isomorphic. */
#ifndef SS_LINK_H
#define SS_LINK_H

#include <stdint.h>

#include "ss_api.h"
#include "ss_error.h"

SS_BEGIN_DECLS

#define SS_LINK_MAXK 100000 /* largest link read (a sanity bound, not a design limit) */

typedef struct {
  int k;    /* number of vertices (edges at the centre vertex) */
  int *off; /* k + 1 offsets: the neighbours of v are nbr[off[v] .. off[v+1]) */
  int *nbr; /* 2E = 6k - 12 neighbour indices, each vertex's in cyclic order */
} ss_link;

/* Degree of vertex v (the valence of the corresponding mesh edge). */
static inline int ss_link_deg(const ss_link *l, int v) {
  return l->off[v + 1] - l->off[v];
}

/* Build a link from degrees deg[0..k) and the concatenated cyclic neighbour
 * lists nbr, copying them, and validate it (ss_link_validate).  SS_EINPUT with
 * a message naming the problem; SS_ENOMEM. */
ss_status ss_link_new(int k, const int *deg, const int *nbr, ss_link **out,
                      ss_error *err);
/* Free a link; NULL is a no-op. */
void ss_link_free(ss_link *l);
/* Deep copy.  SS_ENOMEM. */
ss_status ss_link_copy(const ss_link *l, ss_link **out, ss_error *err);

/* Check that l is a simplicial triangulation of the sphere: k >= 4, indices in
 * range, no loops or repeated neighbours, degree >= 3, symmetric adjacency,
 * consistent rotations (every directed triangle closes), V - E + F = 2 and
 * connected.  SS_EINPUT naming the first problem. */
ss_status ss_link_validate(const ss_link *l, ss_error *err);

/* Build a link from ntri triangles tri[3 t + 0..2] on vertices 0..k-1,
 * orienting them consistently first (the input orientation may be arbitrary),
 * and validate it.  SS_EINPUT if the triangles do not form a simplicial sphere
 * (a vertex in no triangle, an edge not in exactly two triangles, a vertex
 * whose triangles do not form one cycle, not orientable, wrong Euler
 * characteristic).  SS_ENOMEM. */
ss_status ss_link_from_triangles(int k, int ntri, const int *tri, ss_link **out,
                                 ss_error *err);

/* Parse one link: plantri ASCII or a name.  Messages carry no file or line;
 * callers prefix them.  SS_EINPUT, SS_ENOMEM. */
ss_status ss_link_parse(const char *text, ss_link **out, ss_error *err);
/* The named links: "tetrahedron", "octahedron", "icosahedron", "bipyramid:N".
 * SS_EINPUT for an unknown name or N < 3. */
ss_status ss_link_named(const char *name, ss_link **out, ss_error *err);
/* Write l in plantri ASCII into a new string (*out, free() it).  SS_ENOMEM. */
ss_status ss_link_format(const ss_link *l, char **out, ss_error *err);

/* The oriented triangles of l, each once: (*tri)[3 t + 0..2], counter to the
 * rotation (for consecutive neighbours w, w' of v: (v, w, w')), 2k - 4 of them,
 * listed by their smallest vertex.  *tri is malloc'd.  SS_ENOMEM. */
ss_status ss_link_triangles(const ss_link *l, int **tri, int *ntri, ss_error *err);

/* ---- canonical form (ss_link_canon.c) ---- */

/* Canonical form: a relabelled copy of l, equal (as arrays) for isomorphic or
 * mirrored links and different otherwise.  perm (may be NULL) receives k
 * entries: perm[old vertex] = canonical vertex.  SS_ENOMEM. */
ss_status ss_link_canonical(const ss_link *l, ss_link **out, int *perm, ss_error *err);
/* 1 if a and b are isomorphic (mirror images included), else 0; -1 on
 * allocation failure. */
int ss_link_isomorphic(const ss_link *a, const ss_link *b);
/* The automorphisms of l (orientation-reversing ones included): *naut maps,
 * (*aut)[i * k + v] = image of v under automorphism i; the identity is first.
 * *aut is malloc'd.  SS_ENOMEM. */
ss_status ss_link_automorphisms(const ss_link *l, int **aut, int *naut, ss_error *err);

/* 1 if the two links are equal as rotation systems (same k, same lists). */
int ss_link_equal(const ss_link *a, const ss_link *b);

SS_END_DECLS

#endif
