/* ss_cx.h — cell complexes: vertices with coordinates and cells of mixed type.
 *
 * A complex holds `nv` vertices with `dim` coordinates each (1 <= dim <=
 * SS_MAXDIM; a scheme acts on every coordinate alike, so dim = 1 carries a
 * scalar field, and coordinates past the third are fields, ss_mesh.h) and,
 * for every cell type, a flat array of cells.  Cells of different types and
 * dimensions may be mixed freely and need not form a manifold: lower-dimensional
 * cells act as creases (MLCA paper, section 3.2).
 *
 * Vertex order within a cell (the Medit/VTK conventions, so files map 1:1):
 *   segment   a b
 *   triangle  a b c, counter-clockwise seen from the side it faces
 *   quad      cyclic: 0 1 2 3
 *   tet       0 1 2 3, positive iff det(x1-x0, x2-x0, x3-x0) > 0
 *   hex       bottom face 0 1 2 3 cyclic, top face 4 5 6 7 with 4 above 0;
 *             positive iff det(x1-x0, x3-x0, x4-x0) > 0.  As a 3-cube, corner k
 *             has binary coordinates ss_cube_corner_bits(3, k).
 *   oct       opposite pairs (0,3), (1,4), (2,5); the octahedron with vertices
 *             +x +y +z -x -y -z in that order is positive, i.e. positive iff
 *             det(x0-x3, x1-x4, x2-x5) > 0.
 * Vertex cells (0-cubes) mark crease/corner vertices (Medit "Corners").
 *
 * Ownership: a complex owns all its arrays.  Functions taking `const ss_cx *`
 * never keep the pointer. */
#ifndef SS_CX_H
#define SS_CX_H

#include <stddef.h>
#include <stdint.h>

#include "ss_api.h"
#include "ss_error.h"

SS_BEGIN_DECLS

typedef uint32_t ss_idx; /* vertex index: complexes hold at most 2^32-2 vertices */
#define SS_IDX_NONE UINT32_MAX
#define SS_MAXDIM                                                                        \
  16 /* largest number of coordinates per vertex: 3 for the                              \
            position and 13 fields (ss_mesh.h) */

typedef enum {
  SS_VERTEX = 0, /* 0-cube: 1 vertex */
  SS_SEGMENT,    /* 1-cube: 2 vertices */
  SS_TRIANGLE,   /* 3 vertices */
  SS_QUAD,       /* 2-cube: 4 vertices */
  SS_TET,        /* 4 vertices */
  SS_HEX,        /* 3-cube: 8 vertices */
  SS_OCT,        /* 6 vertices */
  SS_NCELLTYPES  /* number of cell types; not a type */
} ss_cell_type;

#define SS_MAXCELLVERTS 8 /* most vertices of any cell type (hex) */

typedef struct {
  int dim;                      /* coordinates per vertex, 1..SS_MAXDIM */
  size_t nv;                    /* number of vertices */
  size_t nv_cap;                /* allocated vertex slots */
  double *x;                    /* nv*dim coordinates, vertex-major */
  int32_t *vref;                /* nv vertex references (Medit labels) */
  size_t nc[SS_NCELLTYPES];     /* number of cells of each type */
  size_t nc_cap[SS_NCELLTYPES]; /* allocated cell slots of each type */
  ss_idx *cells[SS_NCELLTYPES]; /* nc[t] * ss_cell_nverts(t) vertex indices */
  int32_t *cref[SS_NCELLTYPES]; /* nc[t] cell references (Medit labels) */
} ss_cx;

/* ---- cell types: constant tables ---- */

/* Number of vertices of a cell of type t (1, 2, 3, 4, 4, 8, 6). */
int ss_cell_nverts(ss_cell_type t);
/* Topological dimension of a cell of type t (0..3). */
int ss_cell_dim(ss_cell_type t);
/* English name ("hexahedron"; vertex cells are "corner", as in Medit); plural
 * form with ss_cell_plural. */
const char *ss_cell_name(ss_cell_type t);
const char *ss_cell_plural(ss_cell_type t);
/* Number of edges of a cell of type t, and the local vertex pair of edge e. */
int ss_cell_nedges(ss_cell_type t);
void ss_cell_edge(ss_cell_type t, int e, int *a, int *b);
/* Number of roles a vertex can have relative to another in a cell of type t
 * (segment 2, triangle 2, quad 3, tet 2, hex 4, oct 3, vertex 1). */
int ss_cell_nroles(ss_cell_type t);
/* Role of local vertex j relative to local vertex i: 0 = self, 1 = joined by an
 * edge; cubes: the dimension of the smallest face holding both (quad 2 =
 * opposite; hex 2 = same face, 3 = opposite); oct: 2 = opposite. */
int ss_cell_role(ss_cell_type t, int i, int j);
/* Binary coordinates of corner k of a d-cube (d = 1, 2, 3) in the order above:
 * bit i of the result is coordinate i.  ss_cube_corner_index is its inverse. */
unsigned ss_cube_corner_bits(int d, int k);
int ss_cube_corner_index(int d, unsigned bits);

/* If the cell with vertex indices v[0..nverts) is malformed for a complex of nv
 * vertices (an index >= nv, or a vertex repeated), return a constant phrase
 * naming the defect; otherwise NULL. */
const char *ss_cell_defect(ss_cell_type t, const ss_idx *v, size_t nv);

/* ---- complexes ---- */

/* Allocate an empty complex with dim coordinates per vertex.
 * SS_EINPUT if dim is outside 1..SS_MAXDIM; SS_ENOMEM. */
ss_status ss_cx_new(int dim, ss_cx **out, ss_error *err);
/* Free a complex; NULL is a no-op. */
void ss_cx_free(ss_cx *cx);

/* Make room for at least n vertices / n cells of type t in total (not in
 * addition), so that appending never reallocates.  SS_ENOMEM. */
ss_status ss_cx_reserve_vertices(ss_cx *cx, size_t n, ss_error *err);
ss_status ss_cx_reserve_cells(ss_cx *cx, ss_cell_type t, size_t n, ss_error *err);

/* Append a vertex with coordinates x[0..dim) and reference ref.  Its index is
 * the old cx->nv.  SS_EINPUT when the complex is full (2^32-1 vertices). */
ss_status ss_cx_add_vertex(ss_cx *cx, const double *x, int32_t ref, ss_error *err);
/* Append a cell of type t with vertex indices v[0..nverts) and reference ref.
 * Indices are not checked here (see ss_cell_defect / ss_cx_validate). */
ss_status ss_cx_add_cell(ss_cx *cx, ss_cell_type t, const ss_idx *v, int32_t ref,
                         ss_error *err);

/* Pointer to the vertex indices of cell i of type t (no bounds check). */
static inline ss_idx *ss_cx_cell(const ss_cx *cx, ss_cell_type t, size_t i) {
  return cx->cells[t] + i * (size_t)ss_cell_nverts(t);
}
/* Total number of cells of all types. */
size_t ss_cx_ncells(const ss_cx *cx);
/* Highest dimension of any cell, or -1 for a complex without cells. */
int ss_cx_topdim(const ss_cx *cx);

/* Deep copy.  SS_ENOMEM. */
ss_status ss_cx_copy(const ss_cx *cx, ss_cx **out, ss_error *err);

/* Check every cell with ss_cell_defect; on the first defect, SS_EINPUT with a
 * message naming the cell type, its index and the defect. */
ss_status ss_cx_validate(const ss_cx *cx, ss_error *err);

/* Values of a scaled Jacobian (a corner determinant divided by the lengths of
 * the edges it is formed from, in [-1, 1]) at most this far from 0 are zero up
 * to rounding: such a corner is flat and has no sign. */
#define SS_CX_FLAT_TOL 1e-12

/* Orientation of a volume cell (tet, hex, oct) in a complex with dim == 3, or
 * of a face (triangle, quad) with dim == 2: +1 if every corner (hex, quad), the
 * cell (tet, triangle) or every one of the eight centroid tets (oct) has
 * positive scaled Jacobian under the conventions above, -1 if all are
 * negative, 0 if they are mixed or one is within SS_CX_FLAT_TOL of 0 (a flat or
 * folded cell).  Scale-free: the cell's coordinates are rescaled by a power of
 * two first, so a cube of side 1e-300 or 1e300 is judged like the unit cube.
 * Cells of other dimensions return +1.  `vol` (may be NULL) receives the signed
 * volume (area), which may under- or overflow for extreme sizes. */
int ss_cx_cell_orientation(const ss_cx *cx, ss_cell_type t, size_t i, double *vol);

/* Whether the cell of type t with vertex indices v[0..nverts) (each < cx->nv)
 * is flat: a cell of dimension k (1..3) whose k edges at some corner (hex,
 * quad; for a simplex, at every corner; for an octahedron, in one of its
 * eight centroid tets) span a k-volume within SS_CX_FLAT_TOL of 0 relative to
 * the product of their lengths, in any number dim >= k of coordinates (a
 * zero-area triangle in 3D is flat).  Scale-free as ss_cx_cell_orientation.
 * Vertex cells and cells of more dimensions than coordinates return 0. */
int ss_cx_cell_flat(const ss_cx *cx, ss_cell_type t, const ss_idx *v);

/* Check the cells of the complex's top dimension (when it is 2 or 3):
 *  - top == dim: no cell is flat or folded (orientation 0) and all agree in
 *    orientation (an inverted cell is one whose orientation differs from the
 *    majority);
 *  - top < dim (surfaces in 3D, volumes in 4D): no cell is flat
 *    (ss_cx_cell_flat); without a normal there is no orientation to compare;
 *  - top > dim (e.g. tetrahedra with 2 coordinates): refused, every cell is
 *    flat.
 * SS_EINPUT naming the first bad cell (1-based, by type). */
ss_status ss_cx_check_orientation(const ss_cx *cx, ss_error *err);

SS_END_DECLS

#endif
