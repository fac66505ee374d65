/* ss_local.h — local subdivision matrices, derived from a scheme's global rule
 * (DESIGN section 3).
 *
 * A case (ss_case.h) names a centre p and the star around it.
 *
 * Extraction.  The star is refined with the scheme (ss_scheme_refine_step:
 * one level, or quasi48's two topological passes), keeping the refinement
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
 *     (vertices in Omega_w) u N(A_{l+1}); d = D and d = D + 1 must agree
 *     (fixed point), else the extraction fails; D = ss_scheme_ring_depth, 1
 *     for every scheme but quasi48 (3);
 *   - the one-ring O = the closure of {p} under N (the smallest invariant set);
 *   - T and O must be invariant (N(T) in T, N(O) in O), every row read must
 *     belong to a vertex inside the patch (not on its boundary, where the rule
 *     is truncated), and S read at levels (w, w+1) must equal S read at
 *     (w+1, w+2) (the stationary regime).  If room runs out, w grows, up to a
 *     limit (and a cap on the patch's cells: SS_ENOMEM); any other failure
 *     is SS_EINTERNAL, never a wrong matrix.
 *
 * Cells: the cells of level w whose corners all lie in the two-ring (the
 * cells the characteristic map's regularity is judged on; 64 hexes for the
 * regular MLCA vertex), with corners named by their labels.  Their vertex order
 * comes from the split, which keeps every child positively oriented, so one
 * orientation holds for all of them.
 *
 * The ring (DESIGN section 10).  The characteristic map psi is self-similar,
 * psi(lambda .) = Lambda psi on Omega_{w+1}, so it is regular iff it is
 * regular on the ring Omega_w \ Omega_{w+1}: the cells of level w + 1 inside
 * Omega_w that do not touch p, and, refined r more times, the cells of level
 * w + 1 + r inside Omega_w and outside Omega_{w+1} ("ring level r").  A cell
 * lies in Omega_w iff all its corners do (each cell is an affine image of a
 * lattice cell within one base cell, where Omega_w is convex).  The ring's
 * control points on level w + 1 + r are combinations of the two-ring's
 * (rows of the global rule, applied r + 1 times), so any net on the two-ring
 * (the characteristic map's, in doubles or intervals) can be pushed there:
 * ring level r's point i = sum_q w[q] * (previous level's point col[q]), the
 * previous level of ring level 0 being the two-ring (label indices).  Every
 * row is a complete row of the rule (as for S), and only the points the
 * ring's cells and the next level need are kept.  Levels w + 1 and w + 2 are
 * built for S anyway; deeper ring levels refine the patch further, peeled to
 * a neighbourhood of Omega_w.
 *
 * Ordering: labels (and rows and columns of S) list the one-ring first, then
 * the rest of the two-ring; within each part by the largest absolute
 * coordinate (so the centre comes first), then by ss_star_coord_cmp.  S is
 * therefore block lower triangular: S = [A 0; B C] with A the n1 x n1
 * one-ring block. */
#ifndef SS_LOCAL_H
#define SS_LOCAL_H

#include "ss_api.h"
#include "ss_case.h"
#include "ss_error.h"
#include "ss_local_cost.h"
#include "ss_progress.h"
#include "ss_scheme.h"
#include "ss_star.h"

SS_BEGIN_DECLS

#define SS_LOCAL_MAXRING 4 /* ring levels at most (ss_local_new_ring) */
#define SS_LOCAL_RING    2 /* ring levels of ss_local_new (no extra refinement) */

/* One level of the ring: points pushed from the previous level, and the ring's
 * cells on this level. */
typedef struct {
  size_t nv;            /* points of this level */
  size_t nprev;         /* points of the previous level (the two-ring for level 0) */
  size_t *ptr;          /* nv + 1 row starts into col and w */
  size_t *col;          /* previous-level point of each entry */
  double *w;            /* weight of each entry; every row sums to 1 */
  size_t ncells;        /* ring cells on this level */
  ss_cell_type *ctype;  /* ncells cell types */
  size_t *corner;       /* ncells * SS_MAXCELLVERTS corners, indices into this
                           level's points, vertex order of ss_cx.h; unused slots
                           SIZE_MAX */
  ss_star_coord *coord; /* nv coordinates of the points relative to p, in
                           units of this level's grid (level w + 1 + r for
                           ring level r; ss_star.h), so a point of ring level
                           r with coordinates x is the label x / 2^(r + 1)
                           when that is one */
} ss_local_ring;

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
  size_t ncentre;       /* of these cells, how many have the centre p (label 0)
                           as a corner: the cells around p, which the ring
                           does not contain */
  int nring;            /* ring levels built (see above) */
  int whole;            /* 1 if each ring level holds every cell of Omega_w on
                           its level, not only the ring's (ss_local_opts.whole) */
  ss_local_ring ring[SS_LOCAL_MAXRING]; /* ring levels 0 .. nring - 1 */
  struct ss_local_levels *levels;       /* the refined star's levels, kept
                                           for ss_local_ring_deepen when asked
                                           (ss_local_opts.keep_levels), else
                                           NULL; private to the extractor
                                           (ss_local_impl.h) */
} ss_local;

/* Extract the local subdivision matrix of scheme s at case c (method above).
 * *out is owned by the caller (ss_local_free).  SS_EINPUT as ss_case_star;
 * SS_EINTERNAL if the two-ring or one-ring is not invariant, a row would be
 * read at the patch boundary even at the deepest level tried, or the matrix is
 * not stationary; SS_ENOMEM when an allocation fails or the refined patch
 * would exceed its cap of 6e6 cells (a resource limit: quasi48 surface
 * vertices of valence above about 600, Catmull-Clark or Loop ones of valence
 * 100000).  Cost: refining the star about w + 2 times, i.e.
 * O(cells of the star * 8^(w+2)). */
ss_status ss_local_new(const ss_scheme *s, const ss_case *c, ss_local **out,
                       ss_error *err);

/* As ss_local_new, with nring ring levels (1 .. SS_LOCAL_MAXRING) instead of
 * SS_LOCAL_RING.  Levels beyond SS_LOCAL_RING cost one more refinement of the
 * patch each (peeled to the neighbourhood of the cells around p).  S and
 * everything else are the same as ss_local_new's, bit for bit. */
ss_status ss_local_new_ring(const ss_scheme *s, const ss_case *c, int nring,
                            ss_local **out, ss_error *err);

/* Replace M's ring by one of nring levels (M made by ss_local_new,
 * ss_local_new_ring or ss_local_new_opts for scheme s and case c).  With
 * M's levels kept (ss_local_opts.keep_levels) only the levels the deeper
 * ring needs are added to them: the same steps, on the same levels, as an
 * extraction with nring from the start, so the ring is the same bit for
 * bit.  Otherwise the case is extracted again with the deeper ring, and its
 * S and labels must equal M's bit for bit (SS_EINTERNAL otherwise).  Other
 * errors as ss_local_new_ring; on an error M's ring is left empty (nring 0)
 * when its levels were kept, unchanged otherwise. */
ss_status ss_local_ring_deepen(const ss_scheme *s, const ss_case *c, int nring,
                               ss_local *M, ss_error *err);

/* Free; NULL is a no-op. */
void ss_local_free(ss_local *L);

/* Push a net (dim coordinates per point, 1..3) through ring level R: out[i]
 * = sum over R's row i of w * prev[col] (prev: R->nprev points, out: R->nv). */
void ss_local_ring_push(const ss_local_ring *R, const double *prev, int dim, double *out);

/* The index of the label x among M's labels, or SIZE_MAX if x labels no
 * point of the two-ring.  Cost O(log n2). */
size_t ss_local_label_index(const ss_local *M, const ss_star_coord *x);

/* The corner (0 .. SS_MAXCELLVERTS - 1, ss_cx.h's vertex order) of cell c of
 * M that is the centre p (label 0), or -1 when p is not a corner of c. */
int ss_local_centre_corner(const ss_local *M, size_t c);

/* Largest absolute coordinate of a label (its distance from p in the chart's
 * max-norm, in grid units). */
int ss_local_label_norm(const ss_star_coord *c);

/* Options of an extraction. */
typedef struct {
  int nring;            /* ring levels, 1..SS_LOCAL_MAXRING (default
                           SS_LOCAL_RING) */
  double max_bytes;     /* memory budget: refuse (SS_ENOMEM, before building
                           anything) a case whose estimate exceeds it
                           (ss_local_cost.h); <= 0: no budget (the default) */
  ss_progress progress; /* steps: "refining the star" level l of the levels
                           needed so far, "reading S" (default silent) */
  int keep_levels;      /* non-zero: keep the refined levels in the result
                           (ss_local.levels) so that ss_local_ring_deepen
                           refines only the levels it adds instead of the
                           whole case again; they hold about as much memory
                           as the extraction's peak, until ss_local_free
                           (default 0) */
  const ss_star *star;  /* the case's star as ss_case_star builds it, when the
                           caller has it already (ss_case_resolved_star):
                           borrowed and only read (level 0 is its complex),
                           it must outlive the result when keep_levels is
                           set; NULL (the default): built here */
  int whole;            /* non-zero: each ring level holds every cell of
                           Omega_w on its level (Omega_{w+1}'s too, the cells
                           at p included) and the points they need: psi's
                           points round the whole of each spoke, for
                           ss_psi_tet.h; not a ring to judge a map on
                           (default 0) */
} ss_local_opts;

/* nring SS_LOCAL_RING, no budget, no progress, levels not kept, the star
 * built here, not whole. */
ss_local_opts ss_local_defaults(void);

/* ss_local_new_ring with options o (budget and progress). */
ss_status ss_local_new_opts(const ss_scheme *s, const ss_case *c, const ss_local_opts *o,
                            ss_local **out, ss_error *err);

/* Scratch memory of ss_local_new_ws (GSL's _alloc discipline), kept between
 * extractions so that a sweep's thread extracts case after case in the same
 * memory: the per-case buffers that do not outlive the extraction.  One
 * workspace serves one call at a time (one per thread).  Every buffer is a
 * capacity that grows when a case needs more (to the largest case seen; it
 * never shrinks), so any workspace serves any case, and the result never
 * depends on its history: bit for bit ss_local_new_opts's.  Still allocated
 * per case: the refined levels (complexes, splits, refinement operators and
 * the triplets they are assembled from, coordinates, boundary marks: their
 * sizes and shapes differ from case to case, and the kept levels outlive the
 * call), the marks of Omega_w, the ring, and the result itself. */
typedef struct {
  double *dense;       /* S read a second time, one level deeper, to check
                          that S is stationary: n2^2 doubles */
  size_t ndense;       /* capacity of dense, doubles */
  size_t *colmap;      /* a level's points to S's columns while reading S */
  size_t ncolmap;      /* capacity of colmap, entries */
  unsigned char *mark; /* three marks per point of level w: the two-ring at
                          ring depths D and D + 1, the one-ring */
  size_t nmark;        /* capacity of mark, bytes */
  void *facet;         /* a level's cell facets and the same grouped (equal
                          facets adjacent), to find the patch boundary */
  size_t nfacet;       /* capacity of facet, bytes */
  size_t *bucket;      /* the grouping's counting sort: a bucket per point */
  size_t nbucket;      /* capacity of bucket, entries */
} ss_local_workspace;

/* An empty workspace (it grows at its first use); NULL when out of memory.
 * Free with ss_local_workspace_free. */
ss_local_workspace *ss_local_workspace_new(void);

/* Free; NULL is a no-op. */
void ss_local_workspace_free(ss_local_workspace *w);

/* ss_local_new_opts with the scratch memory taken from w (grown as the case
 * needs; SS_ENOMEM if it cannot grow, w then still valid).  The result is
 * the same as ss_local_new_opts's bit for bit, whatever w served before.  w
 * NULL: as ss_local_new_opts. */
ss_status ss_local_new_ws(const ss_scheme *s, const ss_case *c, const ss_local_opts *o,
                          ss_local_workspace *w, ss_local **out, ss_error *err);

SS_END_DECLS

#endif
