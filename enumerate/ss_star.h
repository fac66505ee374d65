/* ss_star.h — stars: the small complexes around a centre that the schemes refine
 * to yield local subdivision matrices (DESIGN sections 1 and 3).
 *
 * Kinds (the centre is what the analysis studies; the cells are those holding it):
 *   vertex  the star of a vertex with a given link: one hex (or tet) per link
 *           triangle.  The centre is star vertex 0.
 *   edge    n cells (hexes or tets) around an edge of valence n, the edge running
 *           from star vertex 0 to star vertex 1.  The centre is the edge's
 *           midpoint: a vertex from the first refinement on, whose link is the
 *           bipyramid over n (so the stationary structure exists from level 1).
 *   face    two tets sharing the face (0, 1, 2).  The centre is the whole face:
 *           the tet/oct mesh is not uniform across it (tet/oct paper, appendix),
 *           and its analysis uses sub-patch maps rather than one centre point.
 *
 * Layouts (cells positive under the conventions of ss_cx.h; cell i has cell
 * reference i, which refinement passes on to its children, so every fine cell
 * knows its base cell):
 *   hex vertex star, link of k vertices: 6k - 9 vertices, 2k - 4 hexes
 *     0              the centre
 *     1 + a          edge point of link vertex a (k of them)
 *     1 + k + e      face point of link edge e (3k - 6); link edges {a < b} are
 *                    numbered in lexicographic order of (a, b)
 *     4k - 5 + t     cell point of link triangle t (2k - 4), in the order of
 *                    ss_link_triangles
 *     hex t of the triangle (a, b, c) = (0, a, ab, b, c, ca, abc, bc), naming each
 *     star vertex by its link simplex.
 *   tet vertex star: k + 1 vertices, 2k - 4 tets: 0 the centre, 1 + a the link
 *     vertex a; tet t of the triangle (a, b, c) = (0, 1 + a, 1 + b, 1 + c).
 *   hex edge star, valence n >= 3: 4n + 2 vertices, n hexes.  The n faces
 *     around the edge are numbered i = 0..n-1 in cyclic order; each layer
 *     (bottom s = 0, top s = 1) is a quad star of n quads:
 *     s              the end of the edge in layer s (0 bottom, 1 top)
 *     2 + s n + i    the edge point of face i in layer s
 *     2 + 2n + s n + i   the quad centre between faces i and i + 1 in layer s
 *     hex i = (0, e_i, f_i, e_i+1, 1, e'_i, f'_i, e'_i+1) (primes: top layer).
 *   tet edge star, valence n >= 3: n + 2 vertices, n tets: 0 and 1 the edge's
 *     ends, 2 + i the far vertex of face i; tet i = (0, 1, 2 + i, 2 + (i+1) % n).
 *   tet face star: 5 vertices, 2 tets: (0, 1, 2, 3) and (0, 2, 1, 4).
 *   surface vertex stars (2D baselines, kind vertex, in the plane z = 0), valence
 *     n: quad star 2n + 1 vertices (0 the centre, 1 + i the edge point of ray i,
 *     1 + n + i the far corner of quad i), quads (0, 1+i, 1+n+i, 1+(i+1)%n);
 *     triangle star n + 1 vertices, triangles (0, 1+i, 1+(i+1)%n).
 *
 * Local coordinates (DESIGN section 3, "exact, canonical local coordinates").
 * Every star vertex has a small integer vector in one chart shared by all cells
 * of the star, so a vertex has the same coordinates in every cell holding it (no
 * per-cell transformation), and each cell is an affine image of a lattice
 * cube or simplex in that chart.  Vectors are sparse (ss_star_coord): at most
 * SS_STAR_MAXSUPP nonzero entries.
 *   vertex stars: conical coordinates over the link.  Coordinate a belongs to
 *     link vertex a (ncoord = k); a point is sum_a x_a e_a with every x_a >= 0
 *     and support a link simplex (the smallest one whose cone holds the point).
 *     The centre is 0, the edge point of a is e_a, the face point of ab
 *     e_a + e_b, the cell point of abc e_a + e_b + e_c.  Hex t of the triangle
 *     (a, b, c) is the unit cube spanned by (e_a, e_b, e_c): corner j has
 *     coordinates u0 e_a + u1 e_b + u2 e_c with (u0, u1, u2) the bits of
 *     ss_cube_corner_bits(3, j); tet t is the simplex
 *     (0, e_a, e_b, e_c).
 *   edge stars: coordinates 0..n-1 belong to the faces around the edge, n to
 *     the edge itself (ncoord = n + 1); x_i >= 0 supported on two consecutive
 *     faces, x_n signed.  The ends of the edge are -e_n (vertex 0) and +e_n
 *     (vertex 1), so the centre, the midpoint, is 0.  Hex i is
 *     (u0 e_i + u1 e_i+1 + (2 u2 - 1) e_n) over its corners; tet i has corners
 *     -e_n, e_n, e_i, e_i+1.  These are the conical coordinates of the
 *     bipyramid link (ss_link_named "bipyramid:n": equator vertex i is face i,
 *     the two poles +-e_n), as seen at the midpoint.
 *   surface vertex stars: conical coordinates over the n rays (ncoord = n),
 *     supported on two consecutive rays; quad i is spanned by (e_i, e_i+1).
 *   face star: integer barycentric coordinates, coordinate v for star vertex v
 *     (ncoord = 5); vertex v is e_v, a point's coordinates sum to 1 and are
 *     supported on one tet.
 * Refinement: coordinates are in units of the current level's grid, so a point
 * with coordinates x on level j has coordinates 2x on level j + 1 (the centre,
 * 0, is fixed for vertex and edge stars).  Under the multilinear and tet/oct
 * splits a fine vertex gets 2 * (mean of its parents' coordinates), always an
 * integer vector.  Sorted sparse vectors are canonical names: distinct vertices
 * of a star, refined or not, have distinct coordinates (ss_star_coord_cmp).
 *
 * Positions are a linear image of the chart: x = sum_i coord_i axis_i (divided
 * by 2^j on level j), with axis_i the position of link vertex i (vertex stars),
 * unit vectors around and along the edge (edge stars) or the vertices of two
 * regular tets (face star).  Link vertices are placed on the unit sphere by
 * ss_star_link_embed, which guarantees det(x_a, x_b, x_c) > 0 for every link
 * triangle, so every hex is a parallelepiped and every tet positive.  The
 * positions serve for display and orientation checks; the analysis uses only
 * the combinatorics and the coordinates.
 *
 * Ownership: a star owns its complex and arrays; ss_star_free frees them all.
 * Functions taking `const ss_link *` never keep the pointer. */
#ifndef SS_STAR_H
#define SS_STAR_H

#include <stdint.h>

#include "ss_api.h"
#include "ss_cx.h"
#include "ss_error.h"
#include "ss_link.h"

SS_BEGIN_DECLS

#define SS_STAR_MAXSUPP 4      /* most nonzero coordinates of a vertex (face star) */
#define SS_STAR_MAXN    100000 /* largest edge valence accepted (a sanity bound) */

typedef enum {
  SS_STAR_VERTEX = 0, /* star of a vertex (one cell per link triangle) */
  SS_STAR_EDGE,       /* n cells around an edge */
  SS_STAR_FACE        /* two tets sharing a face */
} ss_star_kind;

/* An exact local coordinate vector, sparse: entry idx[i] has value val[i]. */
typedef struct {
  int n;                        /* nonzero entries, 0..SS_STAR_MAXSUPP */
  int32_t idx[SS_STAR_MAXSUPP]; /* their coordinate indices, ascending; unused: -1 */
  int32_t val[SS_STAR_MAXSUPP]; /* their values, nonzero; unused slots: 0 */
} ss_star_coord;

typedef struct {
  ss_cx *cx;                /* the complex: dim 3, hexes or tets only, each
                               positive; cell i has reference i */
  ss_star_kind centre_kind; /* vertex, edge or face case */
  ss_cell_type cell_type;   /* SS_HEX or SS_TET */
  int n;                    /* vertex star: k, link vertices (= edges at the
                               centre); edge star: the valence n; face star: 2 */
  int ncentre;              /* vertices spanning the centre: 1, 2 or 3 */
  ss_idx centre[3];         /* those vertices (0; 0 1; 0 1 2), unused: SS_IDX_NONE */
  int ncoord;               /* dimension of the coordinate chart (k, n + 1, 5) */
  ss_star_coord *coord;     /* cx->nv local coordinates, one per vertex */
  double *axis;             /* ncoord * 3: position = sum_i coord_i axis[3i..3i+2] */
} ss_star;

/* Hex star of a vertex with link l (a valid link, as the ss_link constructors
 * return): one hex per link triangle, 6k - 9 vertices (layout above).  *out
 * is owned by the caller.  SS_ENUMERIC if the link could not be embedded with
 * positive triangles (ss_star_link_embed), SS_ENOMEM.  Cost: O(k log k) plus
 * the embedding. */
ss_status ss_star_hex_vertex(const ss_link *l, ss_star **out, ss_error *err);

/* Tet star of a vertex with link l: centre plus one vertex per link vertex
 * (k + 1), one tet per link triangle (2k - 4).  Status and cost as
 * ss_star_hex_vertex. */
ss_status ss_star_tet_vertex(const ss_link *l, ss_star **out, ss_error *err);

/* The n hexes around an edge of valence n (4n + 2 vertices: two quad stars of
 * 2n + 1 vertices stacked; layout above).  SS_EINPUT unless
 * 3 <= n <= SS_STAR_MAXN, SS_ENOMEM.  Cost O(n). */
ss_status ss_star_hex_edge(int n, ss_star **out, ss_error *err);

/* The n tets around an edge of valence n (n + 2 vertices).  SS_EINPUT unless
 * 3 <= n <= SS_STAR_MAXN, SS_ENOMEM.  Cost O(n). */
ss_status ss_star_tet_edge(int n, ss_star **out, ss_error *err);

/* Two tets sharing a face (5 vertices).  SS_ENOMEM. */
ss_status ss_star_tet_face(ss_star **out, ss_error *err);

/* The n quads (triangles) around a surface vertex of valence n, the stars of
 * the 2D baselines (layout above).  SS_EINPUT unless 3 <= n <= SS_STAR_MAXN,
 * SS_ENOMEM.  Cost O(n). */
ss_status ss_star_quad_vertex(int n, ss_star **out, ss_error *err);
ss_status ss_star_tri_vertex(int n, ss_star **out, ss_error *err);

/* The star of a vertex of valence n of a 4-8 mesh (quasi 4-8 surfaces, Velho &
 * Gomes section 2), tagged for newest-vertex bisection (ss_split.h "nvb":
 * corner 0 of each triangle is its right-angle corner, the edge opposite it
 * the next one split).  Class 4 (a vertex whose spokes are all legs: the next
 * binary step splits the outer edges): the triangle star above, n >= 3.
 * Class 8 (spokes alternate legs and hypotenuses; n = 2m even, m >= 3): 2m + 1
 * vertices, 0 the centre, 1 + j the class-4 neighbour A_j = e_j, 1 + m + j the
 * class-8 neighbour B_j = e_j + e_j+1, triangles (A_j, B_j, 0) and
 * (A_j+1, 0, B_j): the chart has m quadrants, quadrant j spanned by (e_j,
 * e_j+1), as Catmull-Clark's star of valence m (ncoord = m).  Regular: class 4
 * with n = 4, class 8 with n = 8.  SS_EINPUT for another class or an n out of
 * range (odd or below 6 for class 8), SS_ENOMEM.  Cost O(n). */
ss_status ss_star_tri48_vertex(int n, int cls, ss_star **out, ss_error *err);

/* Free a star and everything it owns; NULL is a no-op. */
void ss_star_free(ss_star *s);

/* Positions of the link's vertices on the unit sphere, x[3a .. 3a+2] for
 * a = 0..k-1, such that det(x_a, x_b, x_c) > 0 for every triangle (a, b, c)
 * that ss_link_triangles lists, and the triangles' cones cover space once (a
 * geodesic embedding of the link).  Method: Tutte's barycentric embedding of
 * the disk left by removing the lowest-numbered vertex w of maximum degree,
 * w's neighbours on a regular polygon (Floater 2003: one-to-one), centrally
 * projected onto the upper hemisphere, w at the south pole.  Deterministic.
 * x must hold 3k doubles.  SS_ENUMERIC if rounding left a triangle
 * non-positive, SS_ENOMEM.  Cost: a conjugate-gradient solve, O(k^2) worst. */
ss_status ss_star_link_embed(const ss_link *l, double *x, ss_error *err);

/* A coordinate vector from m (index, value) pairs with distinct indices and
 * nonzero values (m <= SS_STAR_MAXSUPP), sorted into canonical form. */
ss_star_coord ss_star_coord_make(int m, const int32_t *idx, const int32_t *val);

/* Total order on coordinate vectors (by support, then values): negative, 0 or
 * positive like strcmp.  Equal iff the vectors are equal. */
int ss_star_coord_cmp(const ss_star_coord *a, const ss_star_coord *b);

/* Position of the point with coordinates c on a level whose grid is `scale`
 * times finer than the star's (scale = 2^j on level j): sum_i c_i axis_i /
 * scale into x[0..2]. */
void ss_star_coord_position(const ss_star *s, const ss_star_coord *c, double scale,
                            double x[3]);

SS_END_DECLS

#endif
