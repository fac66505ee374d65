/* ss_scheme.h — subdivision schemes as global refinement operators.
 *
 * A scheme is a topological split (ss_split.h) followed by a rule that gives
 * every fine vertex as a linear combination of split positions.  Refining a
 * complex yields the fine complex and, on request, the sparse refinement
 * operator R (fine x coarse, fine = R * coarse), which is all the analysis ever
 * needs: local subdivision matrices are read from R, never typed in.
 *
 * Built-in schemes (each defined in its own file, the only place that knows its
 * weights):
 *   mlca           multilinear split + cell averaging, d = 1, 2, 3, with creases
 *                  by lower-dimensional cells (ss_scheme_mlca.c)
 *   tetoct         tet/oct split + weighted-centroid smoothing (ss_scheme_tetoct.c)
 *   catmull-clark  quad surfaces; boundaries and segments as B-spline creases
 *   loop           triangle surfaces; boundaries and segments as B-spline creases
 *   boxspline      box-spline solids over the tet/oct split (ss_scheme_boxspline.c)
 *   boxspline-avg  the same averaged over the three diagonal directions
 *   ccsolid        Catmull-Clark solids (Joy-MacCracken rules) on hex meshes;
 *                  boundaries as Catmull-Clark surfaces (ss_scheme_ccsolid.c)
 *   ccsolid-tensor the same with the tensor-product vertex rule on
 *                  extraordinary edges (curve x Catmull-Clark; ss_scheme_ccsolid.c)
 *   quasi48        quasi 4-8 surfaces: longest-edge bisection (a geometry-
 *                  sensitive split) + cascade convolution (ss_scheme_quasi48.c)
 * plus the `averaging` family (split + one mask per cell type) that stencil files
 * describe. */
#ifndef SS_SCHEME_H
#define SS_SCHEME_H

#include <stddef.h> /* gsl_spmatrix.h uses size_t without including it */

#include <gsl/gsl_spmatrix.h>

#include "ss_api.h"
#include "ss_cx.h"
#include "ss_split.h"

SS_BEGIN_DECLS

typedef struct ss_scheme ss_scheme; /* opaque; immutable once built, so threads
                                       may share one */

/* Weights of the averaging family: for a vertex v of dimension dim[v] (the
 * lowest dimension of a cell holding it), the new position is the mean over the
 * cells of that dimension holding v of sum_u mask[type][role(v,u)] * u
 * (ss_cell_role gives the roles).  Vertices in no cell keep their position. */
typedef struct {
  ss_split_kind split;           /* topological split */
  int accepts[SS_NCELLTYPES];    /* nonzero for each cell type the scheme takes */
  double mask[SS_NCELLTYPES][4]; /* weight of a cell vertex by its role */
} ss_averaging;

/* Largest valence n of the valence-dependent weights (ss_averaging_vary). */
#define SS_AVG_NMAX 256

/* Weights of the averaging family that depend on the valence n of the fine
 * vertex v moved: the number of cells of dimension dim[v] holding v (the
 * count the rule averages over: at a vertex born at a coarse vertex the
 * cells there, at one born on an edge of valence m a multiple of m). */
typedef struct {
  const double *w[SS_NCELLTYPES][4]; /* NULL: the mask's constant weight at every
                                        valence; else w[t][r][n] is the weight of
                                        role r at valence n = 1..SS_AVG_NMAX
                                        (w[t][r][0] unused); copied */
  int rational; /* 1: every weight is rational (the exact path may read them); 0:
                   some is not, and certified verdicts say so, proving nothing */
} ss_averaging_vary;

/* The points family (ss_scheme_points.c): every new point a weighted sum of
 * means of centroids of the coarse elements incident to its element (those
 * containing it or contained in it).  A fine vertex of a split stands for a
 * coarse element of dimension d (0 an old vertex, 1 an edge, 2 a face, 3 a
 * cell); its new position is
 *     sum over k of w[place][d][k](n) * (mean over the distinct coarse
 *     elements E of dimension k with E in X or X in E of centroid(E)),
 * X its element, n the number of elements of the place's top dimension at X,
 * and place 0 (volume: points of a hex mesh off its surface, averaged over
 * hexes), 1 (surface: the boundary faces and quad cells of a hex mesh as
 * ccsolid takes them, or a triangle surface; averaged over its faces), 2
 * (crease: crease edges and vertices after ss_crease.h, averaged over the
 * crease edges).  Corners are interpolated. */
enum { SS_PTS_VOLUME = 0, SS_PTS_SURFACE = 1, SS_PTS_CREASE = 2, SS_PTS_PLACES = 3 };

/* The averages of a vertex on an extraordinary edge (ss_points.axis): an old
 * vertex off the surface with n = 2m hexes and m + 2 edges, two of valence
 * m != 4 in no common hex (along: the extraordinary edge through it) and m of
 * valence 4 (across) — its link is the bipyramid over m.  ALONG and ACROSS
 * are the means of those edges' midpoints; VERTEX, EDGE, FACE, CELL as in the
 * volume.vertex rule. */
enum {
  SS_AXIS_VERTEX = 0,
  SS_AXIS_ALONG = 1,
  SS_AXIS_ACROSS = 2,
  SS_AXIS_EDGE = 3,
  SS_AXIS_FACE = 4,
  SS_AXIS_CELL = 5,
  SS_AXIS_KEYS = 6
};

typedef struct {
  ss_split_kind split;                  /* SS_SPLIT_MULTILINEAR (hexes, quads, segments,
                                           vertices) or SS_SPLIT_TETOCT (triangles, segments,
                                           vertices: Loop's 1-to-4 split) */
  const double *w[SS_PTS_PLACES][4][4]; /* w[place][d][k][n], n = 1..SS_AVG_NMAX
                                           (w[..][0] unused), copied; NULL: 0 at
                                           every n, and all NULL for (place, d):
                                           the centroid of X (k = 0 weight 1) */
  const double *axis[SS_AXIS_KEYS];     /* axis[k][n]: the rule of a vertex on an
                                           extraordinary edge (SS_AXIS_*), n = 2m
                                           its hexes, copied; NULL: 0 at every n,
                                           and all NULL: such vertices take
                                           w[SS_PTS_VOLUME][0] like any other */
  int rational;        /* 1: every weight is rational at every n (the exact
                          path may read them) */
  int rational_volume; /* 1: every weight of the volume place is */
} ss_points;

/* Build a points-family scheme (the weights copied).  For each (place, d)
 * given, the weights must sum to 1 within 1e-12 at every n (SS_EINPUT naming
 * them); SS_ENOMEM.  The rule refuses what ccsolid refuses (non-manifold hex
 * meshes) and a fine vertex whose n exceeds SS_AVG_NMAX (SS_EINPUT). */
ss_status ss_scheme_points_new(const char *name, const ss_points *p, ss_scheme **out,
                               ss_error *err);

/* The neighbours family (ss_scheme_boxspline.c): the box-spline paper's
 * rules (ss_scheme_boxspline.c's header) with weights given per valence, on
 * the tet/oct split of tets and octahedra with their major diagonals:
 *   vertex x, n = |rho(x)|: w[VERTEX][0](n) x + w[VERTEX][1](n) / n each
 *     rho neighbour (x stays when n = 0);
 *   edge point of (a, b), n = |rho(a) ∩ rho(b)|: w[EDGE][0](n) / 2 on each
 *     end + w[EDGE][1](n) / n on each common neighbour (the midpoint when
 *     n = 0);
 *   octahedron centre (n = 6): w[CENTRE][0] / 2 on each end of its major
 *     diagonal, w[CENTRE][1] / 4 on each of the other four corners;
 *   boundary vertex (on a face held by one cell), n boundary neighbours:
 *     w[BVERTEX][0](n) x + w[BVERTEX][1](n) / n each;
 *   boundary edge (in a boundary triangle), n vertices opposite it in
 *     boundary triangles: w[BEDGE][0](n) / 2 each end + w[BEDGE][1](n) / n
 *     each opposite vertex. */
enum { SS_NB_VERTEX, SS_NB_EDGE, SS_NB_CENTRE, SS_NB_BVERTEX, SS_NB_BEDGE, SS_NB_RULES };

typedef struct {
  const double *w[SS_NB_RULES][2]; /* w[rule][key][n], n = 1..SS_AVG_NMAX, copied;
                                      NULL: 0 at every n */
  int rational;                    /* 1: every weight is rational at every n */
  int rational_volume; /* 1: every weight of the vertex, edge and centre rules */
} ss_neighbours;

/* Build a neighbours-family scheme (weights copied).  Each rule's two
 * weights must sum to 1 within 1e-12 at every n (SS_EINPUT); SS_ENOMEM. */
ss_status ss_scheme_neighbours_new(const char *name, const ss_neighbours *nb,
                                   ss_scheme **out, ss_error *err);

/* Names of the built-in schemes, NULL-terminated. */
const char *const *ss_scheme_names(void);

/* Build the scheme called `name` (one of ss_scheme_names()).  SS_EINPUT for an
 * unknown name (the message lists the known ones); SS_ENOMEM. */
ss_status ss_scheme_new(const char *name, ss_scheme **out, ss_error *err);

/* Build an averaging-family scheme from masks (copied).  Each accepted cell
 * type's mask must sum to 1 over the cell's vertices (within 1e-12) and the
 * split must take the type; otherwise SS_EINPUT naming the cell type. */
ss_status ss_scheme_averaging_new(const char *name, const ss_averaging *a,
                                  ss_scheme **out, ss_error *err);

/* ss_scheme_averaging_new with valence-dependent weights (vary may be NULL:
 * then as ss_scheme_averaging_new).  Each mask must sum to 1 within 1e-12 at
 * every valence n = 1..SS_AVG_NMAX (SS_EINPUT naming the type and n).  The
 * rule refuses a fine vertex whose valence exceeds SS_AVG_NMAX for a type with
 * varying weights (SS_EINPUT).  With every vary->w NULL and rational set, the
 * scheme is ss_scheme_averaging_new's, bit for bit. */
ss_status ss_scheme_averaging_vary_new(const char *name, const ss_averaging *a,
                                       const ss_averaging_vary *vary, ss_scheme **out,
                                       ss_error *err);

/* Whether the scheme's weights are all rational, so that the exact path's
 * rational reconstruction of a local matrix may stand for it: 0 only for an
 * averaging scheme built with a weight known not to be rational
 * (ss_averaging_vary.rational = 0); 1 for every built-in scheme (Loop's
 * cos(2 pi / n) is found irrational by the reconstruction itself). */
int ss_scheme_weights_rational(const ss_scheme *s);

/* Whether the weights the rule applies inside a volume are all rational:
 * those of the rows of a volume case's local matrix (3D vertex, edge and
 * face cases, whose stars hold cells of the top dimension only, their
 * boundary rows never read).  As ss_scheme_weights_rational, but a points
 * or neighbours stencil whose irrational weights are only on its surface
 * or creases (Loop's cos(2 pi / n) on a box-spline boundary) is rational
 * here; the averaging family answers as ss_scheme_weights_rational. */
int ss_scheme_volume_weights_rational(const ss_scheme *s);

/* Free; NULL is a no-op. */
void ss_scheme_free(ss_scheme *s);

const char *ss_scheme_name(const ss_scheme *s);
ss_split_kind ss_scheme_split_kind(const ss_scheme *s);
/* Whether the scheme takes cells of type t. */
int ss_scheme_accepts(const ss_scheme *s, ss_cell_type t);
/* Remove from cx the cells of every type the scheme does not take whose
 * dimension is below cx's top dimension (TetGen's boundary faces beside its
 * tetrahedra, gmsh's geometry points and curves); cells of the top dimension
 * and all vertices stay.  Nothing is dropped when the scheme does not take
 * some cell of the top dimension (the mesh is refused anyway).  dropped[t] (may be NULL)
 * receives how many cells of type t went; returns their total. */
size_t ss_scheme_drop_lower(const ss_scheme *s, ss_cx *cx, size_t dropped[SS_NCELLTYPES]);

/* How far a fine vertex's rule reaches: 1 if it reads only the coarse cells
 * holding the fine vertex (the averaging family, Catmull–Clark, Loop,
 * Catmull–Clark solids), 2 if
 * it also reads the coarse neighbourhoods of the vertices it combines (the
 * box-spline rules: rho(e) needs all neighbours of both ends).  Local-matrix
 * extraction uses it to know which rows of a truncated patch are complete. */
int ss_scheme_reach(const ss_scheme *s);

/* Levels of influence after which the two-ring of a local subdivision matrix
 * (ss_local.h) is complete, D: the two-ring is found as the depth-D set and
 * must equal the depth-(D + 1) one.  With Omega of radius rho and rows of the
 * step reaching r coarse cells (in some norm), depth d reaches
 * rho + r (1 + 1/2 + ... + 2^(1-d)) < rho + 2r; D is where the lattice points
 * stop changing.  D = 1 serves every scheme but quasi48 (r = 1); quasi48's
 * analysis step (two passes) has rows reaching the octagon |x|, |y| <= 2,
 * |x| + |y| <= 3, and in the 1-norm (rho = 2, r = 3) depth 2 stops at 6.5,
 * depth 3 at 7.25 and the limit is 8: D = 3. */
int ss_scheme_ring_depth(const ss_scheme *s);

/* Whether the rule reads the major diagonals carried in the tets' and
 * octahedra's vertex order (ss_diag.h): 1 for boxspline, 0 otherwise. */
int ss_scheme_reads_diagonals(const ss_scheme *s);

/* The weight c of a smooth vertex of valence k on a Loop surface, (1 - k c) x
 * + c each neighbour: the box-spline paper's figure 14(b), "c can be chosen
 * as 3/(8k) or (1/k)(5/8 - (3/8 + 1/4 cos(2 pi / k))^2)"; both are 1/16 at
 * k = 6, the regular rule of its figure 14(a). */
typedef enum {
  SS_LOOP_C_BETA = 0, /* Loop's beta(k), the default */
  SS_LOOP_C_3_8K = 1  /* 3/(8k): the vertex keeps 5/8 at every valence */
} ss_loop_c;

/* Choose c for the boundary surface of a scheme that follows figure 14
 * (boxspline, boxspline-avg; their triangle cells too), before the scheme is
 * shared or used.  SS_EINPUT naming the scheme for any other scheme (tet/oct
 * and loop are Loop's by their papers). */
ss_status ss_scheme_set_loop_c(ss_scheme *s, ss_loop_c c, ss_error *err);

/* Make the scheme's refinement adaptive (quasi48 only: its bisect split;
 * ss_split_refine_adapt): each level refines the triangles `a` wants (copied)
 * and their closure, and the rule smooths as on any level (an old vertex with
 * no new neighbour keeps its place), so points away from the refined region
 * stay where they are.  A is NULL: uniform again.  The analysis step
 * (ss_scheme_refine_step) is never adaptive.  SS_EINPUT naming the scheme
 * for other schemes, for a box with a non-finite bound or a lower bound above
 * its upper one, and for a negative or non-finite edge length. */
ss_status ss_scheme_set_adapt(ss_scheme *s, const ss_adapt *a, ss_error *err);

/* quasi48's boundary (quasi 4-8 paper, section 4.3: "boundary vertices are
 * constrained to move along the surface normal direction"; figure 15(c):
 * "boundary curves are smooth, except at the vertex shared with the tagged
 * edge").  A boundary vertex that is a vertex cell or ends a segment cell
 * (tagged), or where the boundary is not one curve (more than two boundary
 * edges), is kept in every mode.  The curve rule is the cascade of section
 * 3.2 along the boundary: a new boundary vertex stays at its edge's midpoint
 * (the average of its two boundary neighbours), an old one becomes 1/2 itself
 * + 1/(2k) the k new boundary neighbours (none: kept), the cubic B-spline
 * where every boundary edge splits. */
typedef enum {
  SS_BOUNDARY_NORMAL = 0, /* default: the curve rule's displacement of an old
                             boundary vertex projected on the line through it
                             along the surface normal there (the sum of the
                             cross products of its coarse triangles; none, a
                             zero normal or fewer than 3 coordinates: kept), in
                             the first three coordinates; coordinates past the
                             third (fields) take the curve rule.  A planar
                             surface's boundary therefore stays where it is
                             (section 4.1, "boundary vertices are not allowed to
                             move").  Not linear: ss_scheme_refine with R is
                             refused for a mesh whose boundary it moves */
  SS_BOUNDARY_SMOOTH = 1, /* the curve rule, unconstrained (linear) */
  SS_BOUNDARY_FIXED = 2   /* old boundary vertices kept, new ones at midpoints:
                             the boundary polygon never moves (linear) */
} ss_boundary;

/* Choose quasi48's boundary rule before the scheme is shared or used.  The
 * analysis step (ss_scheme_refine_step) always keeps the boundary (a
 * patch's boundary is not the surface's).  SS_EINPUT naming the scheme for
 * other schemes or a value not in the enum. */
ss_status ss_scheme_set_boundary(ss_scheme *s, ss_boundary b, ss_error *err);

/* Refine `coarse` once.  *fine receives the refined complex (caller owns).  If
 * R is not NULL, *R receives the refinement operator as a new CSR matrix of
 * size fine->nv x coarse->nv (caller frees), and the fine positions are R times
 * the coarse ones; every row of R is checked to sum to 1 (SS_EINTERNAL if not).
 * SS_EINPUT for cell types the scheme does not take or malformed cells, for R
 * requested where quasi48's normal boundary (ss_boundary) moves a vertex, and
 * for a fine position with a non-finite coordinate (the message names it and
 * the coarse vertices it derives from); SS_ENOMEM.  Cost: linear in the
 * complex; the operator adds a log factor. */
ss_status ss_scheme_refine(const ss_scheme *s, const ss_cx *coarse, ss_cx **fine,
                           gsl_spmatrix **R, ss_error *err);

/* As ss_scheme_refine, and if L is not NULL, *L receives the topological split
 * that the rule smoothed (its parent lists name where each fine vertex was
 * born; caller frees with ss_split_free).  The analysis uses it to carry exact
 * local coordinates from level to level. */
ss_status ss_scheme_refine_split(const ss_scheme *s, const ss_cx *coarse, ss_cx **fine,
                                 gsl_spmatrix **R, ss_split **L, ss_error *err);

/* One analysis step (DESIGN section 3): what ss_local refines a star with, so
 * that a point with local coordinates x becomes the point 2x.  For every
 * scheme but quasi48 this is ss_scheme_refine_split, bit for bit.  quasi48's
 * split depends on positions, which a star refined alone does not have as the
 * mesh has them; its step is two passes of the topological 4-8 refinement
 * (newest-vertex bisection, ss_split.h "nvb": the star carries its 4-8 tags
 * in the triangles' vertex order) with its own rule after each, a full 4-8
 * cycle (a dyadic step).  *R is then the product of the two passes' operators
 * and *L the composite split (every vertex born in the step is the midpoint of
 * two coarse vertices).  R and L must not be NULL.  Errors as
 * ss_scheme_refine_split (SS_EINPUT for non-conforming tags). */
ss_status ss_scheme_refine_step(const ss_scheme *s, const ss_cx *coarse, ss_cx **fine,
                                gsl_spmatrix **R, ss_split **L, ss_error *err);

/* Whether ss_scheme_refine_step is one split (ss_split_refine with
 * ss_scheme_split_kind(s)) followed by the rule: 1 for every scheme but
 * quasi48, whose step is two passes.  Then ss_scheme_step_rows can take the
 * rule's half of the step. */
int ss_scheme_step_is_one_split(const ss_scheme *s);

/* The rule's half of ss_scheme_refine_step (schemes for which
 * ss_scheme_step_is_one_split holds; SS_EINTERNAL otherwise), for a caller
 * that split `coarse` itself (fine and L from ss_split_refine with
 * ss_scheme_split_kind(s)) and reads only some rows of R and no positions.
 * *R receives the fine->nv x coarse->nv operator (caller frees): row f equal
 * bit for bit to ss_scheme_refine_step's where want[f] is nonzero (want NULL:
 * every row), checked to sum to 1; the other rows are unspecified (a rule
 * that writes its rows in order leaves them empty) and must not be read.
 * fine's positions stay the split's (centroids of the parents), not R times
 * the coarse ones.  Skipping rows saves the rule's work on them: a patch's
 * boundary rows are incomplete, hence never read, and cost as much as the
 * rest.  SS_EINPUT for cell types the scheme does not take; SS_ENOMEM. */
ss_status ss_scheme_step_rows(const ss_scheme *s, const ss_cx *coarse, const ss_cx *fine,
                              const ss_split *L, const unsigned char *want,
                              gsl_spmatrix **R, ss_error *err);

/* As ss_scheme_refine without the operator, and when a fine position is not
 * finite (SS_EINPUT; coordinates near DBL_MAX overflow), *bad (may be NULL)
 * receives that fine vertex, 0-based; SIZE_MAX otherwise.  Every refinement
 * checks its results so: no caller ever receives a non-finite position. */
ss_status ss_scheme_refine_at(const ss_scheme *s, const ss_cx *coarse, ss_cx **fine,
                              size_t *bad, ss_error *err);

/* The vertices of `input` that vertex f (0-based) of `input` refined `levels`
 * times by the scheme's split derives from: its parents followed back level by
 * level (the corners of the smallest input cell or face holding it; a vertex of
 * the input is its own).  anc receives them ascending, 0-based, *n <=
 * SS_MAXCELLVERTS of them.  Repeats the splits (cost of `levels` splits; meant
 * for error messages).  SS_EINPUT if f is out of range; SS_ENOMEM. */
ss_status ss_scheme_origin(const ss_scheme *s, const ss_cx *input, int levels, size_t f,
                           ss_idx *anc, size_t *n, ss_error *err);

/* Record in err (SS_EINPUT, returned) that refining `input` found a non-finite
 * coordinate on fine vertex f (0-based) at level `level` (1-based), naming the
 * input vertices it derives from (ss_scheme_origin, 1-based as in a file) and
 * the likely cause: coordinates near DBL_MAX overflow when averaged. */
ss_status ss_scheme_explain_nonfinite(const ss_scheme *s, const ss_cx *input, int level,
                                      size_t f, ss_error *err);

/* Refine `levels` times (positions only).  *fine receives the result; levels = 0
 * gives a copy.  Errors as ss_scheme_refine; a non-finite position is
 * explained by ss_scheme_explain_nonfinite. */
ss_status ss_scheme_refine_levels(const ss_scheme *s, const ss_cx *coarse, int levels,
                                  ss_cx **fine, ss_error *err);

SS_END_DECLS

#endif
