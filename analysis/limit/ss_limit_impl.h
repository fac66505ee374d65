/* ss_limit_impl.h — internals of the limit evaluator shared by its files:
 * hex adjacency, framed patches and their canonical numbering, one step of
 * local refinement (ss_limit_patch.c), eigen-decomposition of stationary runs
 * (ss_limit_eig.c). */
#ifndef SS_LIMIT_IMPL_H
#define SS_LIMIT_IMPL_H

#include <complex.h>
#include <stddef.h>
#include <stdint.h>

#include "ss_cx.h"
#include "ss_error.h"
#include "ss_limit.h"
#include "ss_limit_tube.h"
#include "ss_scheme.h"

/* Vertex-to-cell incidence and face neighbours of the hexes of a complex, and
 * the crease cells (vertex cells, segments, quads: lower-dimensional cells,
 * which the schemes refine as creases and boundaries) at each vertex. */
typedef struct {
  const ss_cx *cx;      /* the complex (borrowed) */
  size_t nh;            /* hexes */
  size_t *vptr;         /* nv + 1 offsets into vcell */
  size_t *vcell;        /* hexes at each vertex */
  int64_t *nb;          /* nh * 6: neighbour across stored face 2 * axis + side, or -1 */
  size_t *cptr;         /* nv + 1 offsets into ccell */
  size_t *ccell;        /* crease cells at each vertex, as 4 * index + type
                           (SS_VERTEX, SS_SEGMENT or SS_QUAD) */
  unsigned char *cmark; /* scratch of a patch walk, nh entries, all 0 between
                           walks: 1 a cell of the patch (at a corner of the
                           target), 2 one already walked */
} ss_lim_adj;

/* Crease cell types a patch carries, and the words of one in a patch's
 * crease key: the type, then its vertices (SS_LIM_CREASE_W - 1 at most). */
#define SS_LIM_CREASE_W 5

/* A cube symmetry: framed axis a is stored axis perm[a], reversed if flip[a]. */
typedef struct {
  int perm[3]; /* stored axis of each framed axis */
  int flip[3]; /* 1 if the framed axis runs against the stored one */
} ss_lim_frame;

/* A patch: a target cell and every cell sharing a vertex with it, numbered by
 * the framed walk (ss_limit.h). */
typedef struct {
  size_t ncells;    /* cells */
  size_t nv;        /* vertices */
  uint32_t *key;    /* ncells * 8: framed cells as patch vertex numbers; cell 0
                       is the target in its frame */
  ss_idx *src;      /* nv vertex indices in the complex the patch was cut from */
  int (*pos)[3];    /* nv grid positions relative to the target cell (its
                       corners at 0 and 1), as the walk first met each vertex */
  unsigned posbad;  /* bit d set if some vertex was met at two different
                       positions along axis d (around an extraordinary edge
                       the positions across it disagree, along it they do not) */
  size_t ncrease;   /* crease cells holding a corner of the target */
  uint32_t *ckey;   /* ncrease * SS_LIM_CREASE_W: each crease cell's type, then
                       its vertices as patch numbers (a segment ascending, a
                       quad cyclic from its smallest towards the smaller
                       neighbour; unused words UINT32_MAX), the cells in
                       ascending order of these words */
  int regular;      /* 1 if the patch is the 3x3x3 block of a grid, no
                       crease cell holding a corner of the target */
  uint32_t net[64]; /* regular: patch vertex at grid position i + 4j + 16k,
                       position (i - 1, j - 1, k - 1) */
} ss_lim_patch;

/* The adjacency of cx's hexes and its crease cells' incidence.  SS_EINPUT for
 * a face in more than two hexes (non-manifold); SS_ENOMEM. */
ss_status ss_lim_adj_build(const ss_cx *cx, ss_lim_adj *a, ss_error *err);
void ss_lim_adj_free(ss_lim_adj *a);

/* The identity frame. */
ss_lim_frame ss_lim_frame_id(void);
/* Whether g is the identity. */
int ss_lim_frame_is_id(const ss_lim_frame *g);
/* Framed coordinates of a point with stored coordinates xs; G (may be NULL)
 * receives d framed / d stored. */
void ss_lim_frame_apply(const ss_lim_frame *g, const double xs[3], double xf[3],
                        double G[3][3]);

/* Cut the patch of hex t of a->cx in frame g, with the crease cells holding
 * a corner of t (the others do not reach the limit on t: the rule of every
 * fine vertex of a child's patch reads only cells holding a corner of t).
 * loc is scratch of a->cx->nv entries, all -1 on entry and on return.
 * SS_EINPUT when the cells around t are not face-connected (a non-manifold
 * vertex) or a crease cell at a corner of t leaves the patch (it lies on no
 * hex at that corner); SS_ENOMEM. */
ss_status ss_lim_patch_build(const ss_lim_adj *a, size_t t, const ss_lim_frame *g,
                             int64_t *loc, ss_lim_patch *out, ss_error *err);
/* As ss_lim_patch_build in the frame with the smallest key, then crease key
 * (the identity frame first among equals); *g receives it. */
ss_status ss_lim_patch_canonical(const ss_lim_adj *a, size_t t, int64_t *loc,
                                 ss_lim_patch *out, ss_lim_frame *g, ss_error *err);
void ss_lim_patch_free(ss_lim_patch *p);
/* Hash of a key and crease key. */
uint64_t ss_lim_patch_hash(const ss_lim_patch *p);
/* Whether two patches have the same key and crease key. */
int ss_lim_patch_same(const ss_lim_patch *p, const ss_lim_patch *q);

/* The patch as a complex: vertex i at cx's vertex p->src[i], the framed cells
 * in walk order (cell 0 the target, in its frame), then the crease cells in
 * the crease key's order.  SS_ENOMEM. */
ss_status ss_lim_patch_complex(const ss_cx *cx, const ss_lim_patch *p, ss_cx **out,
                               ss_error *err);

/* One step: refine the patch complex pcx (cell 0 the target) with s, cut the
 * patch of child k of cell 0 (canonical frame if `canonical`, else the
 * inherited one; *g receives it), give it as a complex (*ccx, positions of the
 * refined patch) and, if W is not NULL, the rows of the refinement operator
 * for its points (*W, nchild x pcx->nv row-major, caller frees).  *child
 * receives the child patch (its src are indices of the refined complex).
 * SS_EINTERNAL if the split does not put child k where ss_split.h says. */
ss_status ss_lim_step(const ss_scheme *s, const ss_cx *pcx, int k, int canonical,
                      ss_lim_patch *child, ss_lim_frame *g, ss_cx **ccx, double **W,
                      ss_error *err);

/* One refinement of a patch complex, from which any of its 8 children is cut
 * (ss_lim_cut): ss_lim_step refines the whole patch for one child, so a box
 * judged child by child would refine the same patch 8 times. */
typedef struct {
  const ss_cx *pcx; /* the parent patch complex (borrowed; cell 0 the target) */
  ss_cx *fine;      /* pcx refined by the scheme */
  void *R;          /* its refinement operator (a gsl_spmatrix, rows by fine
                       vertex), or NULL when no rows were asked for */
  ss_lim_adj fa;    /* fine's adjacency */
  int64_t *loc;     /* scratch, fine->nv entries, all -1 between calls */
} ss_lim_refined;

/* Refine pcx once (with_rows: keep the refinement operator for ss_lim_cut's
 * W).  *out is the caller's to free (ss_lim_refined_free, also after an
 * error).  The errors of ss_lim_step's refinement. */
ss_status ss_lim_refine(const ss_scheme *s, const ss_cx *pcx, int with_rows,
                        ss_lim_refined *out, ss_error *err);
/* Child k of r's cell 0, exactly as ss_lim_step(s, r->pcx, k, ...) gives it
 * (W only when r kept the rows). */
ss_status ss_lim_cut(const ss_lim_refined *r, int k, int canonical, ss_lim_patch *child,
                     ss_lim_frame *g, ss_cx **ccx, double **W, ss_error *err);
void ss_lim_refined_free(ss_lim_refined *r);

#define SS_LIM_NPOW                                                                      \
  12 /* powers W^(2^i) kept for a defective run: runs are at most                        \
        about 1075 steps (the binary exponents of doubles) */

/* Eigen-decomposition of a stationary run's matrix W (K x K, row-major):
 * W = V diag(lam) V^-1. */
typedef struct {
  size_t K;                /* size */
  int ok;                  /* 1 if usable; 0: why says why */
  char why[256];           /* reason it is not */
  double cond;             /* ||V||_1 ||V^-1||_1 with unit columns */
  double *V;               /* K x K, column-major: column j the eigenvector of a
                              real lam[j]; for a pair a +- ib (pair 1, 2) the
                              real and imaginary parts x, y of x + iy, so that
                              W [x y] = [x y] [a b; -b a] */
  double *Vinv;            /* K x K, column-major: V^-1 */
  double complex *lam;     /* K eigenvalues */
  int *pair;               /* K: 0 real, 1 first of a complex pair, 2 second */
  size_t one;              /* index of the eigenvalue 1, or SIZE_MAX if not simple */
  double second;           /* largest |lambda| other than 1 */
  double *pw;              /* cond > SS_LIMIT_MAXCOND: W^(2^i), i < SS_LIM_NPOW, each
                              K x K row-major; else NULL */
  double *pd;              /* with pw: the powers D^(2^i) of the difference map D
                              ((K-1) x (K-1): (W P)_r - (W P)_0 from P_r - P_0,
                              r >= 1; eigenvalue 1 removed), each scaled by a
                              power of 2 to entries of at most 1 */
  long pdexp[SS_LIM_NPOW]; /* with pd: D^(2^i) = 2^pdexp[i] times the i-th */
} ss_lim_eig;

/* Decompose W (K x K row-major).  When V is singular or its condition
 * exceeds SS_LIMIT_MAXCOND (a Jordan block: W is defective) the powers
 * W^(2^i) and D^(2^i) are kept instead (why says so), and W^m costs
 * popcount(m) <= SS_LIM_NPOW products.  SS_ENOMEM; SS_ENUMERIC if LAPACK
 * fails outright. */
ss_status ss_lim_eig_new(const double *W, size_t K, ss_lim_eig **out, ss_error *err);
void ss_lim_eig_free(ss_lim_eig *e);
/* Nets: the functions below take K points of D columns each (K x D,
 * row-major): the 3 coordinates, then any fields (ss_limit.h); every
 * operation acts on each column alike, so a column's result does not depend
 * on the others (but for a common power-of-2 scale). */

/* C (K x D) = V^-1 P (P K x D): the coefficients of P's points on the
 * eigenvectors (real ones, and x, y of a pair). */
void ss_lim_eig_coef(const ss_lim_eig *e, size_t D, const double *P, double *C);
/* P (K x D) <- W^m P; m < 0 means the limit m -> infinity (the
 * projection on the eigenvalue 1, which must be simple and every other
 * |lambda| < 1).  With shift not NULL and m >= 0, a translation (the same for
 * every point) is left out of P and written to shift instead: W^m P = P' +
 * shift, row by row -- the eigenvalue-1 part, or for a defective run the
 * new first point (then P' is formed from the powers of the difference map,
 * so that differences of size |lambda_2|^m |P| keep their relative
 * precision instead of drowning in the rounding of the translation).  With
 * scale not NULL (and shift not NULL), P receives 2^*scale P' instead, *scale
 * chosen so that the dominant part does not underflow (0 whenever
 * |lambda_2|^m >= 2^-400 and the run is not defective: then P' is exactly the
 * unscaled result; a defective run's P' is normalised to entries below 1);
 * with scale NULL, P' itself (parts below DBL_MIN lost).
 * SS_ENUMERIC when the limit is not defined; SS_ENOMEM. */
ss_status ss_lim_eig_power(const ss_lim_eig *e, long m, size_t D, double *P,
                           double *shift, int *scale, ss_error *err);

/* Q (K x D) <- the eigenvalue-1/2 part of P (K x D) for a run W with the
 * decomposition e (used when e is defective: eigenvectors of the other
 * eigenvalues are not needed), by the spectral projector X (Y^T X)^-1 Y^T
 * from the null spaces of W - I/2 (SVD); Q = 0 when 1/2 is no eigenvalue.
 * SS_ENUMERIC (with the reason) when 1/2 has a Jordan block or another
 * eigenvalue but 1 has modulus >= 1/2: the parametric Jacobian at the run's
 * fixed point is then unbounded; SS_ENOMEM. */
ss_status ss_lim_eig_half_part(const ss_lim_eig *e, const double *W, size_t D,
                               const double *P, double *Q, ss_error *err);

/* ---- the evaluator's cache and object (ss_limit.c, ss_limit_state.c,
 * ss_limit_tensor.c, ss_limit_walk.c) ---- */

#define SS_LIM_RECENT  64 /* coarse-only states whose transitions are kept */
#define SS_LIM_REFINED 32 /* states whose refinement is kept (ss_lim_state.rf) */

/* A value of a stationary run's across pair chi (ss_limit_edge.c: the limit
 * of the net of its two eigenvectors) at one point of the run's sub-cell. */
typedef struct ss_lim_chi ss_lim_chi;

/* A cached (key, child) transition. */
typedef struct {
  size_t next;     /* state of the child patch */
  ss_lim_frame g;  /* the child's canonical frame relative to the inherited one */
  double *W;       /* rows: child patch points from parent patch points */
  size_t *rp;      /* W's nonzeros row by row (a walk's step reads only
                      these): row i's are rp[i] .. rp[i + 1] - 1 of */
  size_t *ci;      /* their columns, ascending in each row */
  ss_lim_eig *eig; /* for a stationary run (next == self, g = id): lazily */
  ss_lim_chi *chi; /* a stationary run's chi at the points asked so far
                      (ss_limit_edge.c), each as its walk gave it */
  size_t nchi;     /* their number (room: the next power of 2) */
} ss_lim_trans;

/* P (K x D, taken over) <- W P (Kc x D) over t's nonzeros, in column order:
 * the same sums as the dense product that skips zero weights.  SS_ENOMEM
 * (ss_limit_state.c). */
ss_status ss_lim_trans_apply(const ss_lim_trans *t, size_t Kc, size_t K, size_t D,
                             double **P, ss_error *err);

/* The layered structure of a patch around an extraordinary edge (the
 * paper's eq. (1)): the patch points in 4 layers along the edge, columns
 * across them, and whether both stationary halves W_b factor as A_b (x) T,
 * A_b the cubic B-spline's 4 x 4 left/right matrices. */
typedef struct {
  int status;         /* 1 factors, -1 does not (or no edge here) */
  int axis;           /* the edge's axis in the patch's frame */
  int *layer;         /* K: 0..3, the B-spline index along the axis */
  size_t *col;        /* K: the column of each point */
  size_t ncol;        /* columns */
  size_t (*colpt)[4]; /* ncol x 4: the point of each column in each layer */
} ss_lim_tensor;

/* The layers (positions along T->axis + 1) and columns (the ends of every
 * cell edge along it, joined; uf: P->nv + 1 scratch) of patch P into T, whose
 * axis is set and layer, col, colpt have room for P->nv entries; T->ncol is
 * counted from 0.  Returns 0 unless the points form columns of exactly 4
 * layers. */
int ss_lim_tensor_columns(const ss_lim_patch *P, ss_lim_tensor *T, size_t *uf);

/* The exact layered structure of an uncovered box (ss_limit_tube.h). */
typedef struct ss_lim_tube ss_lim_tube;

/* The tube of the box with patch p (complex pcx, cell 0 the box; elo, ehi:
 * the enclosure of its points by patch vertex, 3 per vertex, or NULL), its
 * points translated by -x0, weights read by rat: *out NULL when the box has
 * no such structure (nothing claimed).  SS_ENOMEM; a refinement step's
 * errors. */
ss_status ss_lim_tube_build(const ss_scheme *s, const ss_lim_patch *p, const ss_cx *pcx,
                            const double *elo, const double *ehi, const double x0[3],
                            ss_limit_rational_fn rat, void *arg, ss_lim_tube **out,
                            ss_error *err);
void ss_lim_tube_free(ss_lim_tube *u);
/* The public view (valid while u lives); NULL for NULL. */
const ss_limit_tube *ss_lim_tube_view(const ss_lim_tube *u);

/* A patch topology met so far. */
typedef struct {
  ss_lim_patch patch;  /* key, regularity and net (src: of the instance below) */
  ss_cx *cx;           /* an instance of the patch as a complex (for refining) */
  uint64_t hash;       /* ss_lim_patch_hash */
  ss_lim_trans *tr[8]; /* per child, NULL until computed */
  int coarse_only;     /* 1 while only coarse cells have this patch (no transition
                          leads to it): its transitions may be evicted */
  int held;            /* 1 while its transitions are in the ring of recent ones */
  ss_lim_tensor *ten;  /* the layered structure, computed on first need */
  size_t src_cell;     /* coarse-only: a mesh cell with this patch, to rebuild the
                          instance cx from (it is dropped with the transitions) */
  ss_lim_refined *rf;  /* cx refined once for its transitions while some of the
                          8 are still to compute, else NULL (dropped with the
                          transitions) */
} ss_lim_state;

/* Per coarse cell: its patch's state and where its points come from. */
typedef struct {
  size_t state;   /* SIZE_MAX until first used */
  ss_idx *src;    /* the patch's mesh vertices, in the patch's numbering */
  ss_lim_frame g; /* the patch's canonical frame relative to the cell's stored
                  vertex order (isomorphic cells share their transitions) */
} ss_lim_cell;

struct ss_limit {
  const ss_scheme *s; /* borrowed */
  ss_cx *mesh;        /* owned copy (3 coordinates) */
  size_t nf;          /* fields per vertex (ss_limit_new_fields) */
  double *fld;        /* mesh->nv * nf field values, vertex-major, or NULL */
  ss_lim_adj adj;     /* hex adjacency of the mesh */
  int64_t *loc;       /* scratch, mesh->nv entries, all -1 between calls */
  ss_lim_cell *cell;  /* per hex */
  ss_lim_state **st;  /* states */
  size_t nst, capst;  /* their number and room */
  size_t *tab;        /* hash table of states: index + 1, 0 empty */
  size_t captab;      /* its size, a power of 2 */
  /* Coarse-only states' transitions are kept for the SS_LIM_RECENT most recent
   * ones only: on an unstructured mesh nearly every irregular coarse cell has
   * a patch of its own, and keeping all their W (~80 KB each) would grow
   * with the mesh; points are usually asked cell by cell. */
  size_t recent[SS_LIM_RECENT]; /* ring of coarse-only states holding transitions */
  size_t nrecent;               /* entries ever pushed (the ring's head) */
  /* States holding a refinement (ss_lim_state.rf) are kept to the
   * SS_LIM_REFINED most recent: a refined patch with its rows is up to about
   * half a megabyte, and a state whose other children are never asked for
   * would keep it for good. */
  size_t refined[SS_LIM_REFINED]; /* ring of states holding a refinement */
  size_t nrefined;                /* entries ever pushed (the ring's head) */
  int tensor;                     /* use eq. (1) where an edge's runs factor (default
                                     1; ss_limit_set_tensor) */
  ss_limit_stats stats;
};

/* Cubic B-spline rows of the left (b = 0) and right (b = 1) halves: child
 * points at positions -1..2 of the half from the parent's at -1..2
 * (ss_limit_bspline.c). */
extern const double ss_lim_bspline_half[2][4][4];

/* Uniform cubic B-spline basis on [0,1] for the points at -1, 0, 1, 2, and
 * its derivative (ss_limit_bspline.c). */
void ss_lim_basis(double t, double b[4], double d[4]);

/* SS_OK if scheme s refines a regular hex grid by the tricubic B-spline's
 * rules, else SS_EINPUT saying by how much a weight is off
 * (ss_limit_bspline.c). */
ss_status ss_lim_check_bspline(const ss_scheme *s, ss_error *err);

/* Free a layered structure (NULL is fine; ss_limit_state.c). */
void ss_lim_tensor_free(ss_lim_tensor *t);

/* Free a state: its patch, instance, transitions and layered structure
 * (ss_limit_state.c). */
void ss_lim_state_free(ss_lim_state *s);

/* The state of coarse cell c (its patch in its canonical frame), found or
 * made (ss_limit_state.c). */
ss_status ss_lim_cell_state(ss_limit *L, size_t c, ss_error *err);

/* The transition of state i into child k, computed on first use; L->st may
 * move, the states do not (ss_limit_state.c). */
ss_status ss_lim_transition(ss_limit *L, size_t i, int k, ss_lim_trans **out,
                            ss_error *err);

/* The layered structure of state i, whose child k is a stationary run,
 * computed on first use: status 1 if it factors (ss_limit_tensor.c). */
ss_status ss_lim_tensor_of(ss_limit *L, size_t i, int k, ss_lim_tensor **out,
                           ss_error *err);

/* ---- the walk's point and steps, shared with ss_limit_edge.c
 * (ss_limit_walk.c) ---- */

/* A point in the current sub-cell, exactly: coordinate a is d[a] from the
 * corner side s[a] (x = s ? 1 - d : d), with d <= 1/2.  Doubling, picking a
 * child and turning the frame (a reflection only flips s) are then exact in
 * binary floating point, so a point 1e-300 from an extraordinary vertex stays
 * that far through any frame; x itself (with rounding) is formed only for the
 * B-spline of a regular sub-cell. */
typedef struct {
  int s[3];    /* the corner side each coordinate is measured from */
  double d[3]; /* the distance from it, in [0, 1/2] */
} ss_lim_pt;

/* The point at parameters x (in [0,1]^3), unframed. */
ss_lim_pt ss_lim_pt_make(const double x[3]);
/* The child holding the point: bit a set iff x_a >= 1/2. */
int ss_lim_child_of(const ss_lim_pt *p);
/* How many consecutive steps from p go into child bits b (-1: for ever). */
long ss_lim_run_length(const ss_lim_pt *p, unsigned b);
/* One step into child k, then frame g; M <- G 2 M. */
void ss_lim_advance(ss_lim_pt *p, int k, const ss_lim_frame *g, double M[3][3]);
/* A walk's result for a net of D columns per point (positions, then
 * fields); the caller provides the arrays.  With D = 3 they may point into an
 * ss_limit_point (p, and jac as 3 x 3 row-major). */
typedef struct {
  size_t D;     /* columns per point */
  double *p;    /* D: the limit */
  double *jac;  /* 3 x D row-major, with derivatives: row a = d/dx_a */
  int steps;    /* as ss_limit_point */
  int products; /* as ss_limit_point */
  double *jerr; /* NULL, or 3 x D: receives an estimate of jac's rounding
                   error (eps times the final net's spread times the
                   growth of the rows read from it; 0 for rows carried
                   apart, ss_lim_along, and at fixed points) */
} ss_lim_res;

/* The differences across the plane x_axis = side (a corner side of the
 * current sub-cell) carried apart from the net while the walk stays on it
 * (ss_limit_along.c).  Near an extraordinary edge the walk's last long run
 * keeps the point on such a plane through the edge's fixed point; the net's
 * spread across the edge then shrinks like mu^m (mu the run's across
 * eigenvalue, above 1/2) while its differences along the edge shrink like
 * 2^-m, so the derivative along the edge, read from the net, would carry the
 * net's rounding times (2 mu)^m (1e25 at 1e-300 from a valence-5 edge).
 * Where a step's rows give the child's differences P[side + 1] - P[side - 1]
 * (per column along the axis) from the parent's alone -- the other layers'
 * weights cancel, as the mirror symmetry of the rules about the plane makes
 * them do -- those differences are carried by that map instead, to their own
 * relative precision, and the derivative along the axis at the plane is read
 * from them (the B-spline's at a knot: 1/2 the difference, weighted across).
 * Where a step's rows do not, carrying stops (on = 0) and the net's row is
 * used as before. */
typedef struct {
  int on;             /* 1 while carried */
  int axis;           /* the plane's axis in the current frame */
  int side;           /* the plane: x_axis = side (0 or 1) */
  size_t D;           /* columns per point */
  size_t ncol;        /* columns of the current patch along axis */
  size_t (*colpt)[4]; /* ncol x 4: the point of each column at positions -1..2 */
  double *dl;         /* ncol x D: the differences, 2^-e times the net's scale */
  int e;              /* see dl */
} ss_lim_along;

/* Start carrying the differences of net P (patch p, D columns) across axis,
 * on which pt must lie on a corner side of the sub-cell; A->on = 0 if it
 * does not or p's points do not form columns along it (or memory is short:
 * carrying is an accuracy measure, never needed). */
void ss_lim_along_start(ss_lim_along *A, const ss_lim_patch *p, const ss_lim_pt *pt,
                        int axis, size_t D, const double *P);
/* m steps by W (child patch cp from parent patch pp; m > 1 only for a run,
 * cp = pp); in the child's frame the plane is x_caxis = cside.  Stops carrying
 * (A->on = 0) where W's rows do not give the child's differences from the
 * parent's alone.  SS_ENOMEM. */
ss_status ss_lim_along_step(ss_lim_along *A, const double *W, const ss_lim_patch *pp,
                            const ss_lim_patch *cp, int caxis, int cside, long m,
                            ss_error *err);
/* The net (p->nv x D, caller frees) with the differences at position side + 1
 * and 0 elsewhere: its B-spline derivative along the axis at the plane is
 * the net's, 2^-e times.  SS_ENOMEM. */
ss_status ss_lim_along_net(const ss_lim_along *A, const ss_lim_patch *p, double **Q,
                           ss_error *err);
void ss_lim_along_free(ss_lim_along *A);

/* The walk from state s with patch points P (K x out->D, taken over and
 * freed), 2^sc times their offsets from the origin o (out->D entries), at
 * pt; M maps the current frame's derivatives to the caller's (rows d/dx_a),
 * divided by 2^sc; no_tensor: never by eq. (1).  out->steps and
 * out->products are added to. */
ss_status ss_lim_walk(ss_limit *L, size_t s, double *P, double *o, int sc, ss_lim_pt pt,
                      double M[3][3], int derivatives, int no_tensor, size_t cell,
                      ss_lim_res *out, ss_error *err);

#endif
