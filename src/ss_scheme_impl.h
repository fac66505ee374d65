/* ss_scheme_impl.h — what a scheme file provides (private). */
#ifndef SS_SCHEME_IMPL_H
#define SS_SCHEME_IMPL_H

#include "ss_scheme.h"
#include "ss_sink.h"

/* The rule of a scheme: given the coarse complex, the split complex `fine`
 * (topology, and positions at the split points) and L, emit every fine
 * vertex's weights into k. */
typedef ss_status (*ss_rule_fn)(const ss_scheme *s, const ss_cx *coarse,
                                const ss_cx *fine, const ss_split *L, ss_sink *k,
                                ss_error *err);

struct ss_scheme {
  char name[64];               /* scheme name, e.g. "mlca" */
  ss_split_kind split;         /* topological split */
  unsigned accepts;            /* bit t set: takes cells of type t */
  ss_rule_fn rule;             /* the smoothing rule */
  ss_averaging avg;            /* masks, for averaging-family schemes */
  int reach;                   /* 1: a fine vertex's rule reads only the coarse cells
                                  holding it; 2: it also reads the coarse
                                  neighbourhoods of the vertices it combines */
  int diagonals;               /* 1 if the rule reads major diagonals (ss_diag.h) */
  ss_split_kind step_split;    /* the split of one analysis step
                                  (ss_scheme_refine_step): `split` for every scheme
                                  but quasi48, whose is the topological nvb */
  int step_passes;             /* refinements in one analysis step: 1, or 2 for
                                  quasi48 (a full 4-8 cycle) */
  int ring_depth;              /* ss_scheme_ring_depth */
  int rows_in_order;           /* 1: the rule sends its rows one after another in
                                  increasing order, so R is written row by row
                                  (ss_rows); 0: in any order (ss_triplets) */
  double *vtab[SS_NCELLTYPES]; /* averaging with valence-dependent weights of type
                                  t: the weight rows by valence and place,
                                  vtab[t][(n * nv + i) * nv + j] for n <=
                                  SS_AVG_NMAX, nv = the type's vertices; NULL
                                  for constant masks */
  const double **vrow[SS_NCELLTYPES]; /* vrow[t][n * nv + i]: the row of place i
                                         at valence n, the first equal one's
                                         address (as wrow in the rule) */
  int irrational;                     /* some weight is not rational */
  int irrational_volume;              /* the points and neighbours families: some
                                         weight of a volume rule is not rational
                                         (ss_scheme_volume_weights_rational) */
  double *ptab;         /* the points family: w[place][d][k][n] of ss_points at
                           ptab[((place * 4 + d) * 4 + k) * (SS_AVG_NMAX + 1) + n]; NULL
                           for every other scheme */
  int loop_surfaces;    /* averaging: the vertices whose lowest cells are
                           triangles take Loop's rows on the triangle cells
                           (ss_loop_surface) instead of the triangle mask */
  int loop_c_choice;    /* 1: the boundary follows figure 14 of the
                           box-spline paper and takes ss_scheme_set_loop_c */
  ss_loop_c loop_c;     /* its smooth vertex weight (default Loop's beta) */
  int adaptive;         /* 1: refine with the adaptive bisect pass */
  ss_adapt adapt;       /* its criterion (ss_scheme_set_adapt) */
  ss_boundary boundary; /* quasi48's boundary rule (ss_scheme_set_boundary) */
  int tensor_axis;      /* ccsolid-tensor: a vertex on an extraordinary edge takes
                           the tensor-product rule (ss_scheme_ccsolid.c) */
  double *paxis;        /* the points family's [volume.axis] (a vertex on an
                           extraordinary edge): w[k][n] at paxis[k * (SS_AVG_NMAX
                           + 1) + n], k = SS_AXIS_*; NULL when not given */
};

/* Allocate a scheme with the given parts (ss_scheme_base.c, below every
 * scheme file). */
ss_status ss_scheme_alloc(const char *name, ss_split_kind split, unsigned accepts,
                          ss_rule_fn rule, ss_scheme **out, ss_error *err);

/* "a, b and c": the n vertices v, 1-based, into buf (cap bytes, truncated),
 * for messages. */
void ss_scheme_list_vertices(const ss_idx *v, size_t n, char *buf, size_t cap);

/* Constructors of the built-in schemes, one per file. */
ss_status ss_scheme_mlca_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_tetoct_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_catmull_clark_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_loop_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_boxspline_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_boxspline_avg_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_ccsolid_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_ccsolid_tensor_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_quasi48_new(ss_scheme **out, ss_error *err);

/* The Catmull-Clark surface rule (ss_scheme_catmull_clark.c) on the quads,
 * segments and vertex cells of `surf`, a complex over the fine vertices of the
 * split L whose cells are split cells (a subset of the fine complex's, or the
 * fine boundary faces of a volume); creases by ss_crease.h, classified on
 * surf and L (a fine vertex that should not count as an edge of the surface
 * must have no parents in L).  Emits the rows of the fine vertices x with
 * on[x] != 0 (all when on is NULL) into k, whose own split gives the parents
 * of the sources.  SS_ENOMEM. */
ss_status ss_scheme_catmull_clark_emit(const ss_cx *surf, const ss_split *L,
                                       const unsigned char *on, ss_sink *k,
                                       ss_error *err);

/* The surface of a split hex mesh as Catmull-Clark solids take it
 * (ss_scheme_ccsolid.c, header comment "Boundaries and creases"): the fine
 * quads of the boundary faces and of the explicit quad cells, with the fine
 * segment and vertex cells; the vertices on them; and the split restricted
 * to those (a fine vertex off the surface has no parents).  Built after the
 * same manifold checks as the ccsolid rule (SS_EINPUT naming the vertices),
 * for rules that refine hex meshes as ccsolid does with other weights
 * (the points family, ss_scheme_points.c). */
typedef struct {
  ss_cx surf;        /* over fine's vertices: the surface quads (owned), fine's
                        segment and vertex cells (borrowed) */
  ss_split Ls;       /* the restricted split (ptr and parent owned) */
  unsigned char *on; /* per fine vertex: 1 on the surface (owned) */
} ss_hex_surface;

/* Build *out for the split `fine` (a multilinear split of hexes, quads,
 * segments and vertices) with L; clear it with ss_hex_surface_clear (also
 * after a failure).  SS_EINPUT (non-manifold), SS_ENOMEM. */
ss_status ss_hex_surface_build(const ss_cx *fine, const ss_split *L, ss_hex_surface *out,
                               ss_error *err);
void ss_hex_surface_clear(ss_hex_surface *h);

/* The triangle cells of a split complex as a Loop surface, for a rule that
 * sends its rows in order (ss_scheme_averaging.c, tetoct's crease surfaces).
 * The surface is the fine triangle, segment and vertex cells; its creases
 * follow ss_crease.h on the split restricted to it (a fine vertex on none of
 * those cells has no parents there, so an interior edge of a volume is no
 * edge of the surface).  ss_loop_surface_emit sends fine vertex x's row —
 * a coarse vertex: Loop's (1 - n b) x + b each of its n surface neighbours
 * when smooth, 3/4 x + 1/8 each crease neighbour on a crease, x at a corner;
 * an edge midpoint: 3/8 each end + 1/4 shared by the vertices opposite it,
 * or the midpoint on a crease edge — and returns 1, or 0 (nothing sent) when
 * x is on none of the surface's cells.  The same rows as ss_scheme_loop.c's
 * rule on a complex of those cells alone.  cmode picks the smooth vertex's
 * weight b: Loop's beta(n) (SS_LOOP_C_BETA, what tet/oct and the loop scheme
 * use) or 3/(8n) (SS_LOOP_C_3_8K, the box-spline paper's figure 14(b)). */
typedef struct ss_loop_surface ss_loop_surface;
ss_status ss_loop_surface_new(const ss_cx *fine, const ss_split *L, ss_loop_c cmode,
                              ss_loop_surface **out, ss_error *err);
int ss_loop_surface_emit(const ss_loop_surface *S, const ss_split *L, ss_idx x,
                         ss_sink *k);
void ss_loop_surface_free(ss_loop_surface *S);

#endif
