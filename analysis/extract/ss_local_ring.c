/* ss_local_ring.c — the ring Omega_w minus Omega_{w+1} on finer levels
 * (ss_local.h: the ring): its cells on each ring level and the rows that
 * push a net on the two-ring to their corners. */
#include <stdlib.h>
#include <string.h>

#include "ss_local_impl.h"

/* Whether the top cell v (nv corners) of a level has every corner marked. */
static int all_marked(const ss_idx *v, int nv, const unsigned char *mark) {
  for (int j = 0; j < nv; j++)
    if (!mark[v[j]]) return 0;
  return 1;
}

/* Ring level r on grid level l = w + 1 + r (ss_local.h): the top cells of
 * level l inside Omega_w (om marks) and not inside Omega_{w+1} (om1 marks;
 * NULL: no such exclusion, ss_local.whole);
 * counts them, or with M->ring[r] allocated, lists them with corners as
 * vertex indices of level l (renumbered by the caller). */
static size_t ring_cells(const ss_local_level *L, const unsigned char *om,
                         const unsigned char *om1, ss_local_ring *R) {
  const ss_cx *cx = L->cx;
  const int top = ss_cx_topdim(cx);
  size_t n = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (ss_cell_dim((ss_cell_type)t) != top) continue;
    const int nv = ss_cell_nverts((ss_cell_type)t);
    for (size_t i = 0; i < cx->nc[t]; i++) {
      const ss_idx *v = ss_cx_cell(cx, (ss_cell_type)t, i);
      if (!all_marked(v, nv, om) || (om1 && all_marked(v, nv, om1))) continue;
      if (R) {
        R->ctype[n] = (ss_cell_type)t;
        for (int j = 0; j < SS_MAXCELLVERTS; j++)
          R->corner[n * SS_MAXCELLVERTS + (size_t)j] = j < nv ? v[j] : SIZE_MAX;
      }
      n++;
    }
  }
  return n;
}

/* Ring level r's points (the needed vertices of level l = w + 1 + r,
 * numbered into idx[l]; idx[l - 1] numbered already) and their rows into
 * the previous ring level; the cells' corners renumbered to these points.
 * M->nring becomes r + 1.  SS_LOCAL_OK or SS_LOCAL_HARD (with err). */
static int ring_rows(const ss_local_levels *W, int w, int r, unsigned char *const *need,
                     size_t *const *idx, ss_local *M, ss_error *err) {
  const int l = w + 1 + r;
  const ss_local_level *C = W->lev + l - 1, *F = W->lev + l;
  ss_local_ring *R = M->ring + r;
  size_t nv = 0, nnz = 0;
  for (size_t f = 0; f < F->cx->nv; f++) {
    idx[l][f] = need[l][f] ? nv++ : SIZE_MAX;
    if (need[l][f]) nnz += (size_t)(C->R->p[f + 1] - C->R->p[f]);
  }
  R->nv = nv;
  R->nprev = r == 0 ? M->n2 : M->ring[r - 1].nv;
  R->ptr = malloc((nv + 1) * sizeof *R->ptr);
  R->col = malloc((nnz + 1) * sizeof *R->col);
  R->w = malloc((nnz + 1) * sizeof *R->w);
  R->coord = malloc((nv + 1) * sizeof *R->coord);
  if (!R->ptr || !R->col || !R->w || !R->coord) {
    ss_error_nomem(err, "ring rows");
    return SS_LOCAL_HARD;
  }
  size_t q = 0, i = 0;
  for (size_t f = 0; f < F->cx->nv; f++) {
    if (!need[l][f]) continue;
    R->coord[i] = F->rel[f];
    R->ptr[i++] = q;
    for (int e = C->R->p[f]; e < C->R->p[f + 1]; e++) {
      R->col[q] = idx[l - 1][C->R->i[e]];
      R->w[q++] = C->R->data[e];
    }
  }
  R->ptr[nv] = q;
  for (size_t k = 0; k < R->ncells * SS_MAXCELLVERTS; k++)
    if (R->corner[k] != SIZE_MAX) R->corner[k] = idx[l][R->corner[k]];
  M->nring = r + 1;
  return SS_LOCAL_OK;
}

/* Build M's ring levels 0 .. nring - 1 from the levels w .. w + nring of W
 * (which must exist).  SS_LOCAL_OK or SS_LOCAL_HARD (with err). */
static int build_ring(const ss_local_levels *W, int w, int nring, ss_local *M,
                      ss_error *err) {
  const ss_star_coord zero = ss_star_coord_make(0, NULL, NULL);
  const size_t p0 = ss_local_lookup(W->lev + w, &zero),
               p1 = ss_local_lookup(W->lev + w + 1, &zero);
  unsigned char *om[SS_LOCAL_MAXLEVELS] = {NULL}, *om1[SS_LOCAL_MAXLEVELS] = {NULL},
                *need[SS_LOCAL_MAXLEVELS] = {NULL};
  size_t *idx[SS_LOCAL_MAXLEVELS] = {NULL};
  int rc = SS_LOCAL_OK;
  if (p0 == SIZE_MAX || p1 == SIZE_MAX || w + nring >= W->nlev) {
    ss_error_set(err, SS_EINTERNAL, "ring: levels %d..%d are missing", w, w + nring);
    rc = SS_LOCAL_HARD;
    goto done;
  }
  if (ss_local_omega_marks(W, w, p0, om, err) ||
      ss_local_omega_marks(W, w + 1, p1, om1, err)) {
    rc = SS_LOCAL_HARD;
    goto done;
  }
  for (int l = w; l <= w + nring; l++) {
    need[l] = calloc(W->lev[l].cx->nv + 1, 1);
    idx[l] = malloc((W->lev[l].cx->nv + 1) * sizeof *idx[l]);
    if (!need[l] || !idx[l]) {
      ss_error_nomem(err, "ring");
      rc = SS_LOCAL_HARD;
      goto done;
    }
  }
  /* the cells, then what their corners read, from the finest level down */
  for (int r = 0; r < nring; r++) {
    const int l = w + 1 + r;
    ss_local_ring *R = M->ring + r;
    const unsigned char *in1 = M->whole ? NULL : om1[l - w - 1];
    R->ncells = ring_cells(W->lev + l, om[l - w], in1, NULL);
    R->ctype = malloc((R->ncells + 1) * sizeof *R->ctype);
    R->corner = malloc((R->ncells * SS_MAXCELLVERTS + 1) * sizeof *R->corner);
    if (!R->ctype || !R->corner) {
      ss_error_nomem(err, "ring cells");
      rc = SS_LOCAL_HARD;
      goto done;
    }
    ring_cells(W->lev + l, om[l - w], in1, R);
    for (size_t q = 0; q < R->ncells * SS_MAXCELLVERTS; q++)
      if (R->corner[q] != SIZE_MAX) need[l][R->corner[q]] = 1;
  }
  for (int l = w + nring; l > w; l--) {
    const ss_local_level *C = W->lev + l - 1, *F = W->lev + l;
    for (size_t f = 0; f < F->cx->nv; f++) {
      if (!need[l][f]) continue;
      if (!ss_local_row_complete(C, F, f)) {
        ss_error_set(err, SS_EINTERNAL,
                     "ring level %d: the row of a point inside Omega_w is incomplete",
                     l - w - 1);
        rc = SS_LOCAL_HARD;
        goto done;
      }
      for (int q = C->R->p[f]; q < C->R->p[f + 1]; q++)
        need[l - 1][C->R->i[q]] = 1;
    }
  }
  /* number the kept points; level w's are the two-ring labels */
  for (size_t v = 0; v < W->lev[w].cx->nv; v++) {
    idx[w][v] = need[w][v] ? ss_local_label_index(M, W->lev[w].rel + v) : SIZE_MAX;
    if (need[w][v] && idx[w][v] == SIZE_MAX) {
      ss_error_set(err, SS_EINTERNAL, "the ring reads a point outside the two-ring");
      rc = SS_LOCAL_HARD;
      goto done;
    }
  }
  for (int r = 0; r < nring && !rc; r++)
    rc = ring_rows(W, w, r, need, idx, M, err);
done:
  for (int l = 0; l < SS_LOCAL_MAXLEVELS; l++) {
    free(om[l]);
    free(om1[l]);
    free(need[l]);
    free(idx[l]);
  }
  return rc;
}

/* M's ring of nring levels from the levels of W, S mapping from level w:
 * level w + 1 + r for ring level r; levels W lacks are added, each beyond
 * w + 2 refining a neighbourhood of Omega_w only (the rows read reach a few
 * cells out, the margin covers schemes of reach 2).  ss_local_ring_deepen
 * calls it again on kept levels: the levels added then are those an
 * extraction with the deeper ring from the start adds, in the same order. */
ss_status ss_local_rings_make(ss_local_levels *W, int w, int nring, ss_local *M,
                              ss_error *err) {
  ss_status st = SS_OK;
  while (!st && W->nlev < w + nring + 1) {
    const ss_star_coord zero = ss_star_coord_make(0, NULL, NULL);
    unsigned char *om[SS_LOCAL_MAXLEVELS] = {NULL};
    const size_t p = ss_local_lookup(W->lev + w, &zero);
    st = p == SIZE_MAX ? ss_error_set(err, SS_EINTERNAL, "the centre is lost")
                       : ss_local_omega_marks(W, w, p, om, err);
    if (!st)
      st = ss_local_add_level(W, om[W->nlev - 1 - w], ss_scheme_reach(W->scheme),
                              W->nlev + 1 == w + nring + 1 ? om[W->nlev - 1 - w] : NULL,
                              err);
    for (int l = 0; l < SS_LOCAL_MAXLEVELS; l++)
      free(om[l]);
  }
  if (!st && build_ring(W, w, nring, M, err) == SS_LOCAL_HARD)
    st = err && err->status ? err->status : SS_EINTERNAL;
  return st;
}

/* Free ring levels 0 .. SS_LOCAL_MAXRING - 1 of M and mark none built. */
void ss_local_rings_free(ss_local *M) {
  for (int r = 0; r < SS_LOCAL_MAXRING; r++) {
    free(M->ring[r].ptr);
    free(M->ring[r].col);
    free(M->ring[r].w);
    free(M->ring[r].ctype);
    free(M->ring[r].corner);
    free(M->ring[r].coord);
    memset(M->ring + r, 0, sizeof M->ring[r]);
  }
  M->nring = 0;
}

void ss_local_ring_push(const ss_local_ring *R, const double *prev, int dim,
                        double *out) {
  for (size_t i = 0; i < R->nv; i++) {
    double v[3] = {0.0, 0.0, 0.0};
    for (size_t q = R->ptr[i]; q < R->ptr[i + 1]; q++)
      for (int d = 0; d < dim; d++)
        v[d] += R->w[q] * prev[R->col[q] * (size_t)dim + (size_t)d];
    for (int d = 0; d < dim; d++)
      out[i * (size_t)dim + (size_t)d] = v[d];
  }
}
