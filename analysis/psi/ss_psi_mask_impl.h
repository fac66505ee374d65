/* ss_psi_mask_impl.h — what ss_psi_mask.c and ss_psi_mask_cert.c share:
 * the ring levels' lookups, a vertex's one-ring and its matrix (private to
 * the psi room). */
#ifndef SS_PSI_MASK_IMPL_H
#define SS_PSI_MASK_IMPL_H

#include <stddef.h>

#include "ss_local.h"
#include "ss_psi_mask.h"

/* A point's chart coordinates on its cone: the cone's link vertices
 * (ascending) and the values on them, all positive. */
typedef struct {
  int cone[3];
  int v[3];
} ss_psi_mask_cpt;

/* A point's coordinates and index, sorted for lookup. */
typedef struct {
  ss_star_coord c;
  size_t i;
} keyed;

/* One ring level's points sorted by coordinates. */
typedef struct {
  const ss_local_ring *R;
  keyed *ord; /* R->nv points, ascending by ss_star_coord_cmp */
} level_ix;

/* A distinct neighbourhood: offsets, matrix and (if solved) masks. */
typedef struct {
  size_t n;       /* offsets */
  int (*o)[3];    /* n offsets, ascending (lexicographic) */
  double *A;      /* n x n, row-major */
  double *L;      /* dim x n masks, row-major; NULL if there are none */
  int tried;      /* masks solved (L may still be NULL) */
  int stationary; /* 1 seen equal on two consecutive levels, -1 seen
                     different (not used), 0 not checked */
} ss_psi_mask_nbhd;

typedef struct {
  const ss_local *M;
  int dim;
  level_ix *lev;        /* M->nring levels */
  double **net;         /* M->nring pushed nets */
  ss_psi_mask_nbhd *nb; /* distinct neighbourhoods */
  size_t nnb, cap;
  int (*orient)[4]; /* cones met: 3 link vertices and the sign (+-1) */
  size_t norient, capo;
} ss_psi_mask_ctx;

/* The support of c as a cone (its size must be dim, its values positive)
 * into *p: 0, else -1. */
int ss_psi_mask_cone_of(const ss_star_coord *c, int dim, ss_psi_mask_cpt *p);

/* The one-ring O(q) of point q (coordinates, cone) of ring level r, its
 * matrix A (rows of level r + 1) and the level-r points of q + O (in O's
 * sorted order) into nb (allocated) and *pidx (allocated).  0, 1 if O is
 * not whole inside q's cone on these levels (or too large), -1 out of
 * memory. */
int ss_psi_mask_closure(const ss_psi_mask_ctx *t, int r, const ss_psi_mask_cpt *q,
                        ss_psi_mask_nbhd *nb, size_t **pidx);

/* The lookups of M's ring levels, the nets pushed from x (n2 x dim) and the
 * cones' orientations into t (t->M and t->dim set, the rest zero): 0, 1 if
 * two cells of one cone disagree on its orientation, -1 out of memory. */
int ss_psi_mask_ctx_build(ss_psi_mask_ctx *t, const double *x);
void ss_psi_mask_ctx_free(ss_psi_mask_ctx *t);

/* The orientation (+-1) of the chart on cone (3 link vertices, -1 unused),
 * as read from the ring's cells (0: no cell of it seen). */
int ss_psi_mask_orient_of(const ss_psi_mask_ctx *t, const int *cone);

void ss_psi_mask_nbhd_free(ss_psi_mask_nbhd *nb);

#endif
