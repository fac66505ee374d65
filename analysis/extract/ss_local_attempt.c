/* ss_local_attempt.c — one attempt at the local matrix with the two-ring on
 * level w (ss_local.h: extraction): the two-ring and one-ring as sets of
 * vertices, their labels, S read on two pairs of levels and compared, the
 * two-ring's cells. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_local_impl.h"

#define STAT_TOL 1e-12 /* S on consecutive levels must agree to this */

/* Add to mark_c (level l) every column of the rows of the marked vertices of
 * level l + 1.  A row of a boundary vertex means the patch is too small. */
static int influence(const ss_local_level *C, const ss_local_level *F,
                     const unsigned char *mark_f, unsigned char *mark_c) {
  for (size_t f = 0; f < F->cx->nv; f++) {
    if (!mark_f[f]) continue;
    if (!ss_local_row_complete(C, F, f)) return SS_LOCAL_ROOM;
    for (int q = C->R->p[f]; q < C->R->p[f + 1]; q++)
      mark_c[C->R->i[q]] = 1;
  }
  return SS_LOCAL_OK;
}

/* Read S (n2 x n2) between levels l and l + 1 for the labels; SS_LOCAL_ROOM
 * if a label is missing or a row lies on the boundary, SS_LOCAL_HARD (with
 * err) if a row leaves the set. */
static int read_matrix(const ss_local_levels *W, int l, const ss_local *M, double *S,
                       size_t *colmap, ss_error *err) {
  const ss_local_level *C = W->lev + l, *F = W->lev + l + 1;
  const size_t n = M->n2;
  for (size_t j = 0; j < C->cx->nv; j++)
    colmap[j] = SIZE_MAX;
  for (size_t j = 0; j < n; j++) {
    size_t v = ss_local_lookup(C, M->label + j);
    if (v == SIZE_MAX) return SS_LOCAL_ROOM;
    colmap[v] = j;
  }
  memset(S, 0, n * n * sizeof *S);
  for (size_t i = 0; i < n; i++) {
    size_t f = ss_local_lookup(F, M->label + i);
    if (f == SIZE_MAX || !ss_local_row_complete(C, F, f)) return SS_LOCAL_ROOM;
    for (int q = C->R->p[f]; q < C->R->p[f + 1]; q++) {
      size_t j = colmap[C->R->i[q]];
      if (j == SIZE_MAX) {
        ss_error_set(
            err, SS_EINTERNAL,
            "the two-ring is not invariant: a row of level %d reaches outside it", l + 1);
        return SS_LOCAL_HARD;
      }
      if (i < M->n1 && j >= M->n1) {
        ss_error_set(err, SS_EINTERNAL, "the one-ring is not invariant (level %d)",
                     l + 1);
        return SS_LOCAL_HARD;
      }
      S[i * n + j] += C->R->data[q];
    }
  }
  return SS_LOCAL_OK;
}

/* Make sure the rows of M's labels into level l are computed where they
 * are inner (ss_local_level.rows leaves out those outside Omega_w):
 * SS_LOCAL_OK or SS_LOCAL_HARD. */
static int label_rows(ss_local_levels *W, int l, const ss_local *M, ss_error *err) {
  const ss_local_level *F = W->lev + l;
  if (l >= W->nlev || !F->rows) return SS_LOCAL_OK;
  for (size_t i = 0; i < M->n2; i++) {
    const size_t f = ss_local_lookup(F, M->label + i);
    if (f != SIZE_MAX && F->inner[f] && !F->rows[f])
      return ss_local_complete_rows(W, l, err) ? SS_LOCAL_HARD : SS_LOCAL_OK;
  }
  return SS_LOCAL_OK;
}

/* The top cells of level w (L) with every corner in the two-ring (marks t2),
 * corners as label indices.  SS_LOCAL_OK or SS_LOCAL_HARD (with err). */
static int collect_cells(const ss_local_level *L, const unsigned char *t2, ss_local *M,
                         ss_error *err) {
  const ss_cx *cx = L->cx;
  const int top = ss_cx_topdim(cx);
  size_t n = 0;
  for (int pass = 0; pass < 2; pass++) {
    for (int t = 0; t < SS_NCELLTYPES; t++) {
      if (ss_cell_dim((ss_cell_type)t) != top) continue;
      const int nv = ss_cell_nverts((ss_cell_type)t);
      for (size_t i = 0; i < cx->nc[t]; i++) {
        const ss_idx *v = ss_cx_cell(cx, (ss_cell_type)t, i);
        int in = 1;
        for (int j = 0; j < nv && in; j++)
          in = t2[v[j]];
        if (!in) continue;
        if (pass == 0) {
          n++;
          continue;
        }
        M->ctype[M->ncells] = (ss_cell_type)t;
        size_t *c = M->corner + M->ncells * SS_MAXCELLVERTS;
        for (int j = 0; j < SS_MAXCELLVERTS; j++) {
          c[j] = SIZE_MAX;
          if (j >= nv) continue;
          c[j] = ss_local_label_index(M, L->rel + v[j]);
          if (c[j] == SIZE_MAX) {
            ss_error_set(err, SS_EINTERNAL, "a two-ring cell corner has no label");
            return SS_LOCAL_HARD;
          }
          M->ncentre += c[j] == 0; /* label 0 is the centre */
        }
        M->ncells++;
      }
    }
    if (pass == 0) {
      M->ctype = malloc((n + 1) * sizeof *M->ctype);
      M->corner = malloc((n * SS_MAXCELLVERTS + 1) * sizeof *M->corner);
      M->ncells = M->ncentre = 0;
      if (!M->ctype || !M->corner) {
        ss_error_nomem(err, "two-ring cells");
        return SS_LOCAL_HARD;
      }
    }
  }
  return SS_LOCAL_OK;
}

/* The two-ring estimate of depth d (ss_local.h): out (marks of level w) =
 * A_w with A_{w+d} = the vertices of level w + d in Omega_w (om[d]) and A_l =
 * (vertices of level l in Omega_w) u N(A_{l+1}).  scratch holds the vertex
 * count of every level w + 1 .. w + d.  SS_LOCAL_OK or SS_LOCAL_ROOM. */
static int ring_depth(const ss_local_levels *W, int w, int d, unsigned char *const *om,
                      unsigned char *const *scratch, unsigned char *out) {
  if (d == 1) {
    memcpy(out, om[0], W->lev[w].cx->nv);
    return influence(W->lev + w, W->lev + w + 1, om[1], out);
  }
  unsigned char *a = scratch[d - 1]; /* A_{w+d-1} */
  memcpy(a, om[d - 1], W->lev[w + d - 1].cx->nv);
  int rc = influence(W->lev + w + d - 1, W->lev + w + d, om[d], a);
  for (int l = w + d - 2; !rc && l >= w; l--) {
    unsigned char *to = l == w ? out : scratch[l - w];
    memcpy(to, om[l - w], W->lev[l].cx->nv);
    rc = influence(W->lev + l, W->lev + l + 1, scratch[l + 1 - w], to);
  }
  return rc;
}

/* The two-ring of level w (ss_local.h), p the centre: the estimate of depth
 * D, which must equal that of depth D + 1 (a fixed point).  Marks of level
 * w's vertices in the workspace, scratch until its next use: *t2 the
 * two-ring, *one zeroed for the one-ring.  SS_LOCAL_OK, SS_LOCAL_ROOM or
 * SS_LOCAL_HARD (with err). */
static int two_ring(ss_local_levels *W, int w, size_t p, unsigned char **t2,
                    unsigned char **one, ss_error *err) {
  int rc = SS_LOCAL_OK;
  const int D = ss_scheme_ring_depth(W->scheme);
  unsigned char *om[SS_LOCAL_MAXLEVELS] = {NULL}, *sc[SS_LOCAL_MAXLEVELS] = {NULL},
                *t1 = NULL;
  const size_t nw = W->lev[w].cx->nv;
  ss_local_workspace *ws = W->ws;
  if (ss_local_omega_marks(W, w, p, om, err)) {
    rc = SS_LOCAL_HARD;
    goto done;
  }
  for (int d = 1; d <= D; d++)
    if (!(sc[d] = malloc(W->lev[w + d].cx->nv + 1))) {
      ss_error_nomem(err, "two-ring");
      rc = SS_LOCAL_HARD;
      goto done;
    }
  if (!(ws->mark = ss_local_ws_grow(ws->mark, &ws->nmark, 3 * nw, 1))) {
    ss_error_nomem(err, "two-ring");
    rc = SS_LOCAL_HARD;
    goto done;
  }
  t1 = ws->mark;
  *t2 = t1 + nw;
  *one = *t2 + nw;
  memset(ws->mark, 0, 3 * nw); /* as fresh memory would be read: never */
  /* depth D and depth D + 1 */
  if ((rc = ring_depth(W, w, D, om, sc, t1))) goto done;
  if ((rc = ring_depth(W, w, D + 1, om, sc, *t2))) goto done;
  if (memcmp(t1, *t2, nw) != 0) {
    ss_error_set(err, SS_EINTERNAL,
                 "the two-ring grows from depth %d to depth %d: no fixed point reached",
                 D, D + 1);
    rc = SS_LOCAL_HARD;
  }
done:
  for (int i = 0; i < SS_LOCAL_MAXLEVELS; i++) {
    free(om[i]);
    free(sc[i]);
  }
  return rc;
}

/* The one-ring of level w: the closure of {p} under the rows into level
 * w + 1, via coordinates, marked in one (zeroed).  SS_LOCAL_OK or
 * SS_LOCAL_ROOM. */
static int one_ring(const ss_local_levels *W, int w, size_t p, unsigned char *one) {
  const ss_local_level *Lw = W->lev + w;
  const size_t nw = Lw->cx->nv;
  one[p] = 1;
  for (int changed = 1; changed;) {
    changed = 0;
    for (size_t v = 0; v < nw; v++) {
      if (!one[v]) continue;
      size_t f = ss_local_lookup(W->lev + w + 1, Lw->rel + v);
      if (f == SIZE_MAX || !ss_local_row_complete(Lw, W->lev + w + 1, f))
        return SS_LOCAL_ROOM;
      for (int q = Lw->R->p[f]; q < Lw->R->p[f + 1]; q++) {
        size_t u = Lw->R->i[q];
        if (!one[u]) one[u] = 1, changed = 1;
      }
    }
  }
  return SS_LOCAL_OK;
}

/* M's sizes and labels from the marks t2 and one of level w: the one-ring's
 * labels first, then the rest of the two-ring's, each part in the labels'
 * order; M->S allocated, the workspace's second copy of S and column map
 * grown.  SS_LOCAL_OK or SS_LOCAL_HARD (with err). */
static int labels(ss_local_levels *W, int w, const unsigned char *t2,
                  const unsigned char *one, ss_local *M, ss_error *err) {
  const ss_local_level *Lw = W->lev + w;
  const size_t nw = Lw->cx->nv;
  ss_local_workspace *ws = W->ws;
  size_t n2 = 0, n1 = 0;
  for (size_t v = 0; v < nw; v++) {
    n2 += t2[v];
    n1 += one[v];
    if (one[v] && !t2[v]) {
      ss_error_set(err, SS_EINTERNAL, "the one-ring is not inside the two-ring");
      return SS_LOCAL_HARD;
    }
  }
  M->n2 = n2;
  M->n1 = n1;
  M->label = malloc((n2 + 1) * sizeof *M->label);
  M->S = malloc((n2 * n2 + 1) * sizeof *M->S);
  if (!M->label || !M->S ||
      !(ws->dense =
            ss_local_ws_grow(ws->dense, &ws->ndense, n2 * n2, sizeof *ws->dense)) ||
      !(ws->colmap = ss_local_ws_grow(ws->colmap, &ws->ncolmap, W->lev[w + 1].cx->nv,
                                      sizeof *ws->colmap))) {
    ss_error_nomem(err, "local matrix");
    return SS_LOCAL_HARD;
  }
  size_t i1 = 0, i2 = n1;
  for (size_t v = 0; v < nw; v++)
    if (one[v])
      M->label[i1++] = Lw->rel[v];
    else if (t2[v])
      M->label[i2++] = Lw->rel[v];
  qsort(M->label, n1, sizeof *M->label, ss_local_label_cmp);
  qsort(M->label + n1, n2 - n1, sizeof *M->label, ss_local_label_cmp);
  return SS_LOCAL_OK;
}

/* S read between levels w and w + 1 into M->S and between w + 1 and w + 2
 * into the workspace's second copy: the two must agree to STAT_TOL (the
 * stationary regime).  M->nnz counted.  SS_LOCAL_OK, SS_LOCAL_ROOM or
 * SS_LOCAL_HARD (with err). */
static int read_stationary(ss_local_levels *W, int w, ss_local *M, ss_error *err) {
  const size_t n2 = M->n2;
  double *S2 = W->ws->dense;
  size_t *colmap = W->ws->colmap;
  int rc;
  ss_progress_step(W->prog, "reading S, rows", n2, 0);
  if ((rc = label_rows(W, w + 1, M, err)) || (rc = label_rows(W, w + 2, M, err)))
    return rc;
  if ((rc = read_matrix(W, w, M, M->S, colmap, err))) return rc;
  if ((rc = read_matrix(W, w + 1, M, S2, colmap, err))) return rc;
  double diff = 0.0;
  M->nnz = 0;
  for (size_t k = 0; k < n2 * n2; k++) {
    diff = fmax(diff, fabs(M->S[k] - S2[k]));
    M->nnz += M->S[k] != 0.0;
  }
  if (!(diff <= STAT_TOL)) {
    ss_error_set(err, SS_EINTERNAL,
                 "not stationary: the local matrix on level %d differs from level %d by "
                 "%.3g",
                 w, w + 1, diff);
    return SS_LOCAL_HARD;
  }
  return SS_LOCAL_OK;
}

/* Every row of M's S sums to 1 (to 1e-12): SS_LOCAL_OK, else SS_LOCAL_HARD
 * (with err). */
static int check_row_sums(const ss_local *M, ss_error *err) {
  const size_t n2 = M->n2;
  for (size_t i = 0; i < n2; i++) {
    double sum = 0.0;
    for (size_t j = 0; j < n2; j++)
      sum += M->S[i * n2 + j];
    if (!(fabs(sum - 1.0) <= 1e-12)) {
      ss_error_set(err, SS_EINTERNAL, "row %zu of the local matrix sums to %.17g", i,
                   sum);
      return SS_LOCAL_HARD;
    }
  }
  return SS_LOCAL_OK;
}

/* One attempt with the two-ring on level w (levels up to w + D + 1 exist, D
 * the scheme's ring depth): the two-ring and the one-ring, their labels, S
 * read twice and checked, the two-ring's cells.  On failure M holds none of
 * them. */
int ss_local_attempt(ss_local_levels *W, int w, ss_local *M, ss_error *err) {
  const ss_local_level *Lw = W->lev + w;
  const ss_star_coord zero = ss_star_coord_make(0, NULL, NULL);
  size_t p = ss_local_lookup(Lw, &zero);
  if (p == SIZE_MAX) {
    ss_error_set(err, SS_EINTERNAL, "the centre is not a vertex of level %d", w);
    return SS_LOCAL_HARD;
  }
  unsigned char *t2 = NULL, *one = NULL;
  int rc = two_ring(W, w, p, &t2, &one, err);
  if (!rc) rc = one_ring(W, w, p, one);
  if (!rc) rc = labels(W, w, t2, one, M, err);
  if (!rc) rc = read_stationary(W, w, M, err);
  if (!rc) rc = check_row_sums(M, err);
  if (!rc) rc = collect_cells(Lw, t2, M, err);
  if (!rc) M->level = w;
  if (rc) {
    free(M->label);
    free(M->S);
    free(M->ctype);
    free(M->corner);
    M->label = NULL;
    M->S = NULL;
    M->ctype = NULL;
    M->corner = NULL;
    M->ncells = 0;
  }
  return rc;
}
