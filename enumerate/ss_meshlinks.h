/* ss_meshlinks.h — the distinct vertex links and the edge valences of a real
 * volume mesh (DESIGN sections 1 and 6: "the distinct vertex stars found in a
 * real mesh, with multiplicities"), and the valence statistics of the
 * box-spline paper's Table 1.
 *
 * The mesh is a complex of tetrahedra or of hexahedra (not both; octahedra are
 * not taken: their links are not simplicial).  Lower-dimensional cells
 * (boundary triangles, crease segments, corners) are ignored.
 *
 * The link of a vertex v has a vertex per edge at v and a triangle per cell at
 * v: for a tet (v, a, b, c) the opposite face (a, b, c); for a hex the three
 * hex-edge neighbours of v in that hex.  Vertices are classified by their link:
 *   interior      every link edge lies in exactly two link triangles and the
 *                 triangles form a simplicial sphere (ss_link_from_triangles);
 *   boundary      every link edge lies in one or two triangles, some in one;
 *   non-manifold  a link edge in three or more triangles, or a closed link
 *                 that is not a simplicial sphere (a pinch, a torus, a
 *                 repeated triangle, a link vertex of degree < 3, ...);
 *   unused        in no tet or hex.
 * The cells around an edge vw are the link triangles at w in the link of v;
 * each contributes a wedge joining its two other link vertices (its two faces
 * at the edge).  The edge is interior when the wedges form one closed cycle,
 * boundary when they form one open path, non-manifold otherwise; its valence
 * is the number of cells around it.
 *
 * Vertex valence = number of edges at an interior vertex (k of its link); edge
 * valence statistics are over interior edges.  These are the averages and
 * maxima of the box-spline paper's Table 1. */
#ifndef SS_MESHLINKS_H
#define SS_MESHLINKS_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_cx.h"
#include "ss_error.h"

SS_BEGIN_DECLS

/* One class of interior vertices with isomorphic (or mirrored) links. */
typedef struct {
  char *link;          /* canonical form in plantri ASCII (owned, NUL-terminated) */
  int k;               /* link vertices = edges at each such vertex (vertex valence) */
  size_t count;        /* number of interior vertices whose link is this one */
  size_t first_vertex; /* smallest (0-based) mesh vertex index with this link */
} ss_meshlink_class;

/* Everything ss_meshlinks_compute finds.  Owns its arrays. */
typedef struct {
  ss_cell_type cell_type; /* SS_TET or SS_HEX: the volume cells of the mesh */
  size_t nv;              /* vertices of the complex (all, used or not) */
  size_t ne;              /* distinct edges of the volume cells */
  size_t nc;              /* volume cells */

  size_t nv_interior;    /* vertices whose link is a simplicial sphere */
  size_t nv_boundary;    /* vertices whose link has a boundary (see above) */
  size_t nv_nonmanifold; /* vertices whose link is neither */
  size_t nv_unused;      /* vertices in no volume cell */
  size_t ne_interior;    /* edges whose cells form a closed cycle */
  size_t ne_boundary;    /* edges whose cells form an open path */
  size_t ne_nonmanifold; /* other edges */

  double vval_mean;  /* mean edges per interior vertex (0 if none) */
  int vval_max;      /* most edges at an interior vertex (0 if none) */
  double eval_mean;  /* mean cells per interior edge (0 if none) */
  int eval_max;      /* most cells around an interior edge (0 if none) */
  size_t *vval_hist; /* vval_max + 1 entries: [n] = interior vertices with n edges */
  size_t *eval_hist; /* eval_max + 1 entries: [n] = interior edges with n cells */

  size_t nlinks;            /* distinct interior links */
  ss_meshlink_class *links; /* nlinks classes, by count (descending), then k
                               (ascending), then the canonical text */
  size_t *nonmanifold;      /* nv_nonmanifold 0-based vertex indices, ascending */
} ss_meshlinks;

/* Compute the vertex links, edge valences and statistics of cx (any number of
 * coordinates; cells must be tets only or hexes only).  On success *out is a
 * new result owned by the caller (free with ss_meshlinks_free).  cx is not
 * kept.  SS_EINPUT for malformed cells (ss_cx_validate), a mesh with both
 * tets and hexes, with octahedra or with neither, or a vertex in more cells
 * than a link has triangles (2 SS_LINK_MAXK - 4); SS_ENOMEM.  Vertex numbers
 * in messages are 1-based, as in Medit files.
 * Cost: O(C log C) for the incidences plus one canonical form per interior
 * vertex (C = cell-vertex incidences); memory O(C) plus the distinct links. */
ss_status ss_meshlinks_compute(const ss_cx *cx, ss_meshlinks **out, ss_error *err);

/* Free a result; NULL is a no-op. */
void ss_meshlinks_free(ss_meshlinks *ml);

SS_END_DECLS

#endif
