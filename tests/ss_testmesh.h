/* ss_testmesh.h — complexes the tests build: periodic grids, polygons, stars of
 * link triangulations, tet meshes of cubes, surfaces of links, and random
 * relabellings.  Test-only code: it aborts on failure. */
#ifndef SS_TESTMESH_H
#define SS_TESTMESH_H

#include "ss_cx.h"
#include "ss_scheme.h"

/* A triangulated sphere with positions on the unit sphere. */
typedef struct {
  int k;          /* vertices */
  int ntri;       /* triangles = 2k - 4 */
  int (*tri)[3];  /* triangles, consistently oriented (outward normals) */
  double (*x)[3]; /* vertex positions */
} tm_link;

/* "tetrahedron", "octahedron", "icosahedron", "bipyramid:N" (N equator vertices). */
tm_link *tm_link_named(const char *name);
void tm_link_free(tm_link *l);

/* Periodic d-cube grid (d = 1, 2, 3) with N^d cells; vertex i + N j + N^2 k has
 * coordinates (i, j, k) (dim = d; positions do not wrap). */
ss_cx *tm_torus(int d, int N);
/* Periodic triangle grid N x N (each grid square split along its diagonal). */
ss_cx *tm_torus_triangles(int N);
/* Closed polygon with n segments on the unit circle (dim 2). */
ss_cx *tm_polygon(int n);
/* Hex star of a link: one hex per link triangle, 6k - 9 vertices, centre 0. */
ss_cx *tm_hex_star(const tm_link *l);
/* Tet star of a link: one tet per link triangle, k + 1 vertices, centre 0. */
ss_cx *tm_tet_star(const tm_link *l);
/* The link as a closed triangle surface (dim 3). */
ss_cx *tm_link_surface(const tm_link *l);
/* The link's triangles each split into 3 quads (a closed quad surface whose
 * link vertices keep their degree as valence). */
ss_cx *tm_link_quads(const tm_link *l);
/* N^3 unit cubes, each cut into 6 tets about its main diagonal (Kuhn). */
ss_cx *tm_kuhn(int N);
/* nx x ny x nz unit hexes; vertex i + (nx+1) (j + (ny+1) k) at (i, j, k), hex
 * i + nx (j + ny k) at (i, j, k). */
ss_cx *tm_hex_grid(int nx, int ny, int nz);
/* n sectors of R x R quads around the z axis (sector s between the unit rays
 * at angles 2 pi s / n and 2 pi (s + 1) / n), extruded into nz unit layers:
 * the z axis is an edge of valence n.  Hex ((k n + s) R + j) R + i is the
 * sector's quad (i, j) in layer k; i = j = 0 touches the axis, with its
 * corner 0 on it and w along it. */
ss_cx *tm_edge_ring(int n, int R, int nz);
/* The faces held by one tet or octahedron (the boundary of a solid), as
 * sorted vertex triples in ascending order, into *out (caller frees); their
 * count.  Written apart from the schemes': an octahedron's faces are the
 * triples of one vertex from each opposite pair. */
size_t tm_boundary_faces(const ss_cx *cx, ss_idx **out);
/* Of b's points not flagged in skip (nv flags), how many are also points of
 * a, bit for bit, in any order (*found), and how many were looked for
 * (*total). */
void tm_points_in(const ss_cx *a, const ss_cx *b, const unsigned char *skip,
                  size_t *total, size_t *found);
/* cx refined `levels` times by s (diagonals chosen by BFS first where s reads
 * them): a new complex, or NULL with err set (" level L: " says which). */
ss_cx *tm_refined(const ss_scheme *s, const ss_cx *cx, int levels, ss_error *err);
/* Move every vertex by a pseudo-random offset of size <= amp (seeded). */
void tm_jitter(ss_cx *cx, double amp, unsigned long seed);
/* A relabelled copy: vertices and cells permuted, each cell's vertex list turned
 * by a random orientation-preserving symmetry of its cell type (seeded). */
ss_cx *tm_permuted(const ss_cx *cx, unsigned long seed);
/* 0 if a and b are the same complex up to relabelling (positions within tol,
 * same cells as vertex sets); otherwise prints the first difference and
 * returns 1. */
int tm_same_geometry(const ss_cx *a, const ss_cx *b, double tol);

#endif
