/* ss_local_impl.h — what the extractor's files share (not installed): the
 * refined star's levels, the patch boundary's facets, the outcome of an
 * attempt, and the steps each file offers the others.  The method is in
 * ss_local.h.  Files, each calling only those listed before it:
 *   ss_local_workspace.c  scratch memory kept between cases
 *   ss_local_label.c      exact coordinates relative to p, lookup by them,
 *                         the labels' order
 *   ss_local_marks.c      the patch boundary: facets and inner marks
 *   ss_local_level.c      the levels: refinement, peeling, rows of the rule,
 *                         Omega_w's vertices
 *   ss_local_attempt.c    one attempt at S with the two-ring on level w
 *   ss_local_ring.c       the ring on finer levels
 *   ss_local.c            the entry points (ss_local.h) */
#ifndef SS_LOCAL_IMPL_H
#define SS_LOCAL_IMPL_H

#include "ss_local.h"

#define SS_LOCAL_MAXLEVELS 8 /* levels of refinement tried at most */

/* One level of the refined star. */
typedef struct {
  ss_cx *cx;             /* the complex of this level */
  ss_split *split;       /* parents of this level's vertices (NULL on level 0) */
  gsl_spmatrix *R;       /* operator to the next level, CSR (NULL on the last) */
  ss_star_coord *abs;    /* chart coordinates, cx->nv */
  ss_star_coord *rel;    /* coordinates relative to p (levels >= lc), cx->nv */
  ss_idx *index;         /* the vertices hashed by rel, for lookup: open
                            addressing, mask + 1 slots, SS_IDX_NONE empty */
  size_t mask;           /* slots - 1 (a power of two minus one) */
  unsigned char *inner;  /* vertex not on the patch boundary */
  unsigned char *rows;   /* the finest level an attempt or a ring reads
                            (ss_local_add_level's keep): the vertices whose
                            rows into this level were computed, the inner
                            ones inside Omega_w (ss_local_complete_rows adds
                            the others when needed); NULL: every inner
                            vertex's */
  unsigned char *cinner; /* schemes reaching 2 rings: vertex not on the
                            boundary of the complex refined into the next
                            level (after peeling), else NULL */
} ss_local_level;

/* Extraction workspace (kept in ss_local.levels when asked). */
typedef struct ss_local_levels {
  const ss_scheme *scheme;                /* the scheme */
  ss_star *star;                          /* the star (level 0 is its complex) */
  int star_owned;                         /* 1 if star is freed with the levels;
                                             0 if the caller's (ss_local_opts.star) */
  int lc;                                 /* first level on which p is a vertex */
  ss_star_coord cp;                       /* p's chart coordinates on level lc */
  int nlev;                               /* levels built */
  ss_local_level lev[SS_LOCAL_MAXLEVELS]; /* levels 0 .. nlev-1 */
  const ss_progress *prog;                /* progress reports (may be NULL) */
  ss_local_workspace *ws;                 /* scratch memory (never NULL while a
                                             level is built or an attempt made;
                                             NULL in kept levels) */
} ss_local_levels;

/* A facet of a top cell: its vertices sorted ascending, padded with
 * SS_IDX_NONE (quads and triangles of hexes, tets and octahedra; segments of
 * quads and triangles). */
typedef struct {
  ss_idx v[4]; /* the vertices, ascending, then SS_IDX_NONE */
} ss_local_facet;

/* Why an attempt at level w failed: for lack of room (a deeper level may do)
 * or for good (status set in err). */
enum { SS_LOCAL_OK = 0, SS_LOCAL_ROOM = 1, SS_LOCAL_HARD = 2 };

/* ---- ss_local_workspace.c ---- */

/* Free w's buffers and empty it (w itself stays). */
void ss_local_ws_release(ss_local_workspace *w);

/* A block of at least n elements of size sz in place of p (capacity *cap);
 * NULL when out of memory (p freed, *cap 0). */
void *ss_local_ws_grow(void *p, size_t *cap, size_t n, size_t sz);

/* ---- ss_local_label.c ---- */

/* sum_i mult[i] * c[i] / div, an integer vector with at most
 * SS_STAR_MAXSUPP nonzeros, into out: 0, or -1 when it is not. */
int ss_local_lincomb(int m, const ss_star_coord *const *c, const int *mult, int div,
                     ss_star_coord *out);

/* 2 * (the mean of the np parents' coordinates) into out: 0, or -1 when it
 * is no integer vector with at most SS_STAR_MAXSUPP nonzeros. */
int ss_local_child_coord(int np, const ss_star_coord *const *par, ss_star_coord *out);

/* The slot of L's index holding the vertex with relative coordinates c, or
 * the empty slot where it would go. */
size_t ss_local_slot(const ss_local_level *L, const ss_star_coord *c);

/* The vertex of L with relative coordinates c, or SIZE_MAX. */
size_t ss_local_lookup(const ss_local_level *L, const ss_star_coord *c);

/* The labels' order (ss_local.h: ordering), for qsort and bsearch. */
int ss_local_label_cmp(const void *a, const void *b);

/* ---- ss_local_marks.c ---- */

/* The boundary facets of cx (the facets of its top cells that occur once)
 * in the workspace: *b and *nb, scratch until the workspace's next use. */
ss_status ss_local_boundary_facets(const ss_cx *cx, ss_local_workspace *ws,
                                   ss_local_facet **b, size_t *nb, ss_error *err);

/* *out (malloc'd, nv + 1 bytes): v lies in a top cell of cx and on none of
 * its nb boundary facets b. */
ss_status ss_local_boundary_marks(const ss_cx *cx, const ss_local_facet *b, size_t nb,
                                  unsigned char **out, ss_error *err);

/* ss_local_boundary_marks of cx's own boundary facets. */
ss_status ss_local_inner_marks(const ss_cx *cx, ss_local_workspace *ws,
                               unsigned char **out, ss_error *err);

/* The same marks for F = split(C), derived from C's nb boundary facets g
 * through the split's parent lists. */
ss_status ss_local_inner_marks_split(const ss_cx *C, const ss_local_facet *g, size_t nb,
                                     const ss_cx *F, const ss_split *sp,
                                     unsigned char **out, ss_error *err);

/* ---- ss_local_level.c ---- */

/* Relative coordinates, lookup index and boundary marks of level l >= lc. */
ss_status ss_local_finish_level(ss_local_levels *W, int l, ss_error *err);

/* Give level l every inner vertex's row into it (after a refinement that
 * computed only some, ss_local_level.rows). */
ss_status ss_local_complete_rows(ss_local_levels *W, int l, ss_error *err);

/* Refine the last level once more, peeled first (near, margin); with keep,
 * only the rows inside Omega_w. */
ss_status ss_local_add_level(ss_local_levels *W, const unsigned char *near, int margin,
                             const unsigned char *keep, ss_error *err);

/* Add level w + D + 1, the finest an attempt at level w reads. */
ss_status ss_local_add_finest(ss_local_levels *W, int w, ss_error *err);

/* out[l - w] (malloc'd, for l = w .. nlev - 1): the vertices of level l in
 * Omega_w, the cells around p (vertex p of level w). */
ss_status ss_local_omega_marks(const ss_local_levels *W, int w, size_t p,
                               unsigned char **out, ss_error *err);

/* Whether the row of fine vertex f (level F) in C's operator is complete. */
int ss_local_row_complete(const ss_local_level *C, const ss_local_level *F, size_t f);

/* Free W's levels and star (W itself stays). */
void ss_local_levels_release(ss_local_levels *W);

/* ---- ss_local_attempt.c ---- */

/* One attempt with the two-ring on level w (levels up to w + D + 1 exist):
 * M's matrix, labels and cells, or SS_LOCAL_ROOM / SS_LOCAL_HARD (err set)
 * with none of them. */
int ss_local_attempt(ss_local_levels *W, int w, ss_local *M, ss_error *err);

/* ---- ss_local_ring.c ---- */

/* M's ring of nring levels, S mapping from level w; the levels W lacks are
 * added. */
ss_status ss_local_rings_make(ss_local_levels *W, int w, int nring, ss_local *M,
                              ss_error *err);

/* Free M's ring levels and mark none built. */
void ss_local_rings_free(ss_local *M);

#endif
