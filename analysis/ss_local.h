/* ss_local.h — local subdivision matrices, derived from a scheme's global rule
 * (DESIGN section 3).
 *
 * A case names a centre p and the star around it:
 *   vertex          a 3D vertex with a given link: the hex star for schemes with
 *                   the multilinear split, the tet star for the tet/oct split;
 *   edge            the midpoint of an edge of valence n (a vertex from level 1
 *                   on), in n hexes or n tets;
 *   face            tet/oct split only: a vertex inside the face shared by two
 *                   tets (from level 2 on, the vertex 1/4 (2, 1, 1) of the face;
 *                   every vertex inside that face sees the same infinite mesh,
 *                   two half tet/oct lattices meeting at a plane);
 *   surface vertex  a 2D vertex of valence n: n quads (multilinear split) or n
 *                   triangles (tet/oct split, which splits triangles like Loop).
 *
 * Extraction.  The star is refined with the scheme, keeping the refinement
 * operators R_l and the split's parent lists.  Every vertex carries exact
 * integer coordinates relative to p, in units of its level's grid
 * (ss_star.h).  The point with coordinates x on level l has coordinates 2x on
 * level l + 1, so level
 * l + 1 seen from p looks like level l, and a coordinate set names a set of
 * vertices on every level.  With N(X) the coordinates of the level-l vertices
 * that the rows of level-(l+1) vertices X touch:
 *   - Omega_w = the cells holding p on level w; a vertex of level w + m lies in
 *     Omega_w iff all its parents on level w + m - 1 do;
 *   - the two-ring T = vertices of level w whose basis function does not vanish
 *     on Omega_w: T = A_w with A_{w+d} = (vertices in Omega_w) and A_l =
 *     (vertices in Omega_w) u N(A_{l+1}); d = 1 and d = 2 must agree (fixed
 *     point), else the extraction fails;
 *   - the one-ring O = the closure of {p} under N (the smallest invariant set);
 *   - T and O must be invariant (N(T) in T, N(O) in O), every row read must
 *     belong to a vertex inside the patch (not on its boundary, where the rule
 *     is truncated), and S read at levels (w, w+1) must equal S read at
 *     (w+1, w+2) (the stationary regime).  If room runs out, w grows, up to a
 *     limit; any other failure is SS_EINTERNAL, never a wrong matrix.
 *
 * Cells: the cells of level w whose corners all lie in the two-ring (the
 * cells the characteristic map's regularity is judged on; 64 hexes for the
 * regular MLCA vertex), with corners named by their labels.  Their vertex order
 * comes from the split, which keeps every child positively oriented, so one
 * orientation holds for all of them.
 *
 * Ordering: labels (and rows and columns of S) list the one-ring first, then
 * the rest of the two-ring; within each part by the largest absolute
 * coordinate (so the centre comes first), then by ss_star_coord_cmp.  S is
 * therefore block lower triangular: S = [A 0; B C] with A the n1 x n1
 * one-ring block. */
#ifndef SS_LOCAL_H
#define SS_LOCAL_H

#include "ss_diag.h"
#include "ss_error.h"
#include "ss_link.h"
#include "ss_scheme.h"
#include "ss_star.h"

typedef enum {
  SS_CASE_VERTEX = 0,    /* a 3D vertex with a link */
  SS_CASE_EDGE,          /* a point on an edge of valence n */
  SS_CASE_FACE,          /* a point inside the face shared by two tets */
  SS_CASE_SURFACE_VERTEX /* a 2D vertex of valence n */
} ss_case_kind;

/* One case to analyse.  The link is borrowed, not copied. */
typedef struct {
  ss_case_kind kind;   /* which centre */
  const ss_link *link; /* vertex case: the link; otherwise NULL */
  int n;               /* edge and surface vertex cases: the valence */
  ss_diag_mode diag;   /* tet stars: major diagonals (ss_diag.h; bfs = 0 by
                          default, or proper; skew and center only for the
                          edge case, around the edge) */
} ss_case;

/* The local subdivision matrix of one case. */
typedef struct {
  size_t n2;            /* two-ring points (rows and columns of S) */
  size_t n1;            /* one-ring points: the first n1 rows and columns */
  double *S;            /* n2 x n2, row-major: S[i*n2 + j], fine i from coarse j */
  size_t nnz;           /* nonzero entries of S */
  ss_star_coord *label; /* n2 coordinates relative to p, the order of S */
  int ncoord;           /* dimension of the coordinate chart */
  int dim;              /* 3 for volume cases, 2 for surface vertices */
  int level;            /* the level w that S maps from */
  ss_cell_type cell;    /* the cell type of the star (hex, tet, quad, triangle) */
  size_t ncells;        /* cells of level w with every corner in the two-ring */
  ss_cell_type *ctype;  /* ncells cell types (hex; tet and oct; quad; triangle) */
  size_t *corner;       /* ncells * SS_MAXCELLVERTS corners, as indices into
                           label, in the vertex order of ss_cx.h; unused slots
                           SIZE_MAX */
} ss_local;

/* Name of a case kind as in the command line and JSON ("vertex", "edge",
 * "face", "surface-vertex"). */
const char *ss_case_name(ss_case_kind kind);

/* The star the scheme refines for case c (hex or tet stars by the scheme's
 * split; see above).  *out is owned by the caller.  SS_EINPUT if the scheme
 * does not support the case (it does not take the star's cell type, or the face
 * case with a multilinear split) or the valence is out of range. */
ss_status ss_local_star(const ss_scheme *s, const ss_case *c, ss_star **out,
                        ss_error *err);

/* Extract the local subdivision matrix of scheme s at case c (method above).
 * *out is owned by the caller (ss_local_free).  SS_EINPUT as ss_local_star;
 * SS_EINTERNAL if the two-ring or one-ring is not invariant, a row would be
 * read at the patch boundary even at the deepest level tried, or the matrix is
 * not stationary; SS_ENOMEM.  Cost: refining the star about w + 2 times, i.e.
 * O(cells of the star * 8^(w+2)). */
ss_status ss_local_new(const ss_scheme *s, const ss_case *c, ss_local **out,
                       ss_error *err);

/* Free; NULL is a no-op. */
void ss_local_free(ss_local *L);

/* Largest absolute coordinate of a label (its distance from p in the chart's
 * max-norm, in grid units). */
int ss_local_label_norm(const ss_star_coord *c);

#endif
