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

/* Loop's rules (ss_scheme_loop.c), for schemes whose boundary surfaces refine
 * by Loop (the box-spline solids, figure 14).  ss_scheme_loop_beta: Loop's
 * vertex weight b = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n for a vertex of
 * valence n >= 1.  ss_scheme_loop_vertex_emit: the row of vertex x on a
 * coarse surface, (1 - n b) x + b sum of its n neighbours nb (x alone if
 * n = 0).  ss_scheme_loop_edge_emit: the edge point f of (a, b), 3/8 each end
 * and 1/4 shared by the m >= 1 vertices opposite the edge (Loop's 1/8 each
 * when m = 2). */
double ss_scheme_loop_beta(size_t n);
void ss_scheme_loop_vertex_emit(ss_sink *k, ss_idx x, const ss_idx *nb, size_t n);
void ss_scheme_loop_edge_emit(ss_sink *k, ss_idx f, ss_idx a, ss_idx b, const ss_idx *opp,
                              size_t m);

#endif
