/* ss_local_level.c — the levels of the refined star: each level refined
 * from the one before (peeled first), with its coordinates relative to p, its
 * lookup index and its boundary marks; the rows of the global rule computed
 * for the vertices that can be read; Omega_w's vertices on every level.
 *
 * test_marks (tests/analysis/meson.build) compiles its own copy of this file
 * with SS_CHECK_MARKS, which checks every derived level's boundary marks
 * against marks recomputed from the level's own facets (ss_local_add_level). */
#include <stdlib.h>
#include <string.h>

#include "ss_gsl.h"
#include "ss_local_impl.h"

#define MAXCELLS 6000000 /* refuse to refine a patch beyond this many cells */

/* Relative coordinates, lookup order and boundary marks of level l >= lc. */
ss_status ss_local_finish_level(ss_local_levels *W, int l, ss_error *err) {
  ss_local_level *L = W->lev + l;
  const size_t nv = L->cx->nv;
  size_t slots = 4;
  while (slots < 2 * nv)
    slots *= 2;
  L->rel = malloc((nv + 1) * sizeof *L->rel);
  L->index = malloc(slots * sizeof *L->index);
  if (!L->rel || !L->index) return ss_error_nomem(err, "local coordinates");
  L->mask = slots - 1;
  if (W->cp.n == 0) /* p is the chart's origin: relative = absolute */
    memcpy(L->rel, L->abs, nv * sizeof *L->rel);
  else {
    const ss_star_coord *c[2];
    const int mult[2] = {1, -(1 << (l - W->lc))};
    c[1] = &W->cp;
    for (size_t v = 0; v < nv; v++) {
      c[0] = L->abs + v;
      if (ss_local_lincomb(2, c, mult, 1, L->rel + v))
        return ss_error_set(err, SS_EINTERNAL,
                            "local coordinates of vertex %zu on level %d have too many "
                            "nonzero entries",
                            v, l);
    }
  }
  memset(L->index, 0xff, slots * sizeof *L->index); /* SS_IDX_NONE */
  for (size_t v = 0; v < nv; v++) {
    const size_t h = ss_local_slot(L, L->rel + v);
    if (L->index[h] != SS_IDX_NONE)
      return ss_error_set(err, SS_EINTERNAL, "two vertices of level %d share coordinates",
                          l);
    L->index[h] = (ss_idx)v;
  }
  return L->inner ? SS_OK : ss_local_inner_marks(L->cx, W->ws, &L->inner, err);
}

/* Peel level l (l > 0, p a vertex) before it is refined: with the distance
 * of a vertex from p counted in steps between vertices that share a cell (the
 * max-norm in grid units on a cube grid, whatever the chart), drop the cells
 * with a vertex at the largest distance r, if r >= PEEL_FROM.  Level l + 1
 * then reaches 2(r - 1) instead of 2r in that direction: the patch still
 * grows from level to level (so a boundary effect cannot repeat itself and
 * pass the stationarity check) but each level costs about ((r - 1) / r)^3 of
 * the unpeeled one (27/64 on level 2 of a vertex star).
 * The inner marks of level l stay as they are: they say which rows of the
 * operator into level l are complete, and that operator was built before the
 * peeling.  The vertices of dropped cells stay, in no cell; their children
 * on level l + 1 are in no cell either, hence not inner.  Too much peeling can
 * only cost room (a deeper level), never a wrong row: every row read belongs
 * to an inner vertex of the complex the operator was built from. */
#define PEEL_FROM 4
/* With `near` (marks of L's vertices) instead: drop every cell with a vertex
 * farther from p than margin plus the farthest marked vertex (the ring's
 * deeper levels need only a neighbourhood of Omega_w). */
static ss_status peel(ss_local_level *L, const unsigned char *near, int margin,
                      ss_error *err) {
  ss_cx *cx = L->cx;
  const size_t nv = cx->nv;
  const ss_star_coord zero = ss_star_coord_make(0, NULL, NULL);
  const size_t p = ss_local_lookup(L, &zero);
  if (p == SIZE_MAX) return SS_OK; /* p is no vertex yet: nothing to measure from */
  /* vertex -> cells incidence, cells numbered across types */
  size_t base[SS_NCELLTYPES + 1] = {0};
  for (int t = 0; t < SS_NCELLTYPES; t++)
    base[t + 1] = base[t] + cx->nc[t];
  size_t *ptr = calloc(nv + 2, sizeof *ptr), *inc = NULL, *queue = NULL;
  int *dist = malloc((nv + 1) * sizeof *dist);
  size_t ninc = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++)
    ninc += cx->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t);
  inc = malloc((ninc + 1) * sizeof *inc);
  queue = malloc((nv + 1) * sizeof *queue);
  if (!ptr || !dist || !inc || !queue) {
    free(ptr), free(dist), free(inc), free(queue);
    return ss_error_nomem(err, "peeling");
  }
  for (int t = 0; t < SS_NCELLTYPES; t++)
    for (size_t i = 0; i < cx->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t); i++)
      ptr[cx->cells[t][i] + 2]++;
  for (size_t v = 0; v < nv; v++)
    ptr[v + 2] += ptr[v + 1];
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    const int n = ss_cell_nverts((ss_cell_type)t);
    for (size_t i = 0; i < cx->nc[t] * (size_t)n; i++)
      inc[ptr[cx->cells[t][i] + 1]++] = base[t] + i / (size_t)n;
  }
  /* breadth-first distances from p; ptr[v] .. ptr[v + 1] are v's cells */
  for (size_t v = 0; v < nv; v++)
    dist[v] = -1;
  size_t head = 0, tail = 0;
  dist[p] = 0;
  queue[tail++] = p;
  int r = 0;
  while (head < tail) {
    const size_t v = queue[head++];
    r = dist[v] > r ? dist[v] : r;
    for (size_t q = ptr[v]; q < ptr[v + 1]; q++) {
      int t = 0;
      while (inc[q] >= base[t + 1])
        t++;
      const int n = ss_cell_nverts((ss_cell_type)t);
      const ss_idx *c = cx->cells[t] + (inc[q] - base[t]) * (size_t)n;
      for (int j = 0; j < n; j++)
        if (dist[c[j]] < 0) {
          dist[c[j]] = dist[v] + 1;
          queue[tail++] = c[j];
        }
    }
  }
  free(ptr), free(inc), free(queue);
  int cut = r; /* cells reaching dist >= cut go */
  if (near) {
    int rho = 0;
    for (size_t v = 0; v < nv; v++)
      if (near[v] && dist[v] > rho) rho = dist[v];
    cut = rho + margin + 1;
  }
  if (near || r >= PEEL_FROM) {
    for (int t = 0; t < SS_NCELLTYPES; t++) {
      const int n = ss_cell_nverts((ss_cell_type)t);
      size_t kept = 0;
      for (size_t i = 0; i < cx->nc[t]; i++) {
        const ss_idx *v = cx->cells[t] + i * (size_t)n;
        int far = 0;
        for (int j = 0; j < n && !far; j++)
          far = dist[v[j]] < 0 || dist[v[j]] >= cut;
        if (far) continue;
        memmove(cx->cells[t] + kept * (size_t)n, v, (size_t)n * sizeof *v);
        if (cx->cref[t]) cx->cref[t][kept] = cx->cref[t][i];
        kept++;
      }
      cx->nc[t] = kept;
    }
  }
  free(dist);
  return SS_OK;
}

/* Give level l (computed with ss_local_level.rows) every inner vertex's row
 * into it: the rule once more for the rows left out, merged row by row into
 * the operator from level l - 1 (ss_scheme_step_rows: each row the same
 * bits whichever rows are asked with it).  Before level l - 1 ... l change:
 * C's complex must be the one F was split from (not peeled since). */
ss_status ss_local_complete_rows(ss_local_levels *W, int l, ss_error *err) {
  ss_local_level *C = W->lev + l - 1, *F = W->lev + l;
  if (!F->rows) return SS_OK;
  const size_t nf = F->cx->nv;
  unsigned char *rest = malloc(nf + 1);
  if (!rest) return ss_error_nomem(err, "refinement operator");
  size_t n = 0;
  for (size_t f = 0; f < nf; f++)
    n += rest[f] = (unsigned char)(F->inner[f] && !F->rows[f]);
  gsl_spmatrix *B = NULL, *A = C->R, *M = NULL;
  ss_status st = SS_OK;
  if (n &&
      !(st = ss_scheme_step_rows(W->scheme, C->cx, F->cx, F->split, rest, &B, err))) {
    size_t nnz = 0;
    for (size_t f = 0; f < nf; f++) {
      const gsl_spmatrix *X = rest[f] ? B : A;
      nnz += (size_t)(X->p[f + 1] - X->p[f]);
    }
    if (!(M = ss_gsl_csr_alloc(A->size1, A->size2, nnz)))
      st = ss_error_nomem(err, "refinement operator");
    else {
      size_t q = 0;
      M->p[0] = 0;
      for (size_t f = 0; f < nf; f++) {
        const gsl_spmatrix *X = rest[f] ? B : A;
        for (int e = X->p[f]; e < X->p[f + 1]; e++, q++) {
          M->i[q] = X->i[e];
          M->data[q] = X->data[e];
        }
        M->p[f + 1] = (int)q;
      }
      M->nz = nnz;
      gsl_spmatrix_free(C->R);
      C->R = M;
    }
  }
  if (B) gsl_spmatrix_free(B);
  free(rest);
  if (!st) {
    free(F->rows);
    F->rows = NULL;
  }
  return st;
}

/* Refine the last level once more, peeled first (peel's near and margin).
 * With keep (marks of the last level's vertices in Omega_w), the new level
 * is the finest one an attempt or the ring reads, only inside Omega_w
 * (ss_local.h): the rule runs only for the inner vertices there
 * (ss_local_level.rows; a vertex of the finer level lies in Omega_w iff all its
 * parents do, as ss_local_omega_marks says), the other rows are added
 * (ss_local_complete_rows) when a read needs them or a level is added below. */
ss_status ss_local_add_level(ss_local_levels *W, const unsigned char *near, int margin,
                             const unsigned char *keep, ss_error *err) {
  if (W->nlev == SS_LOCAL_MAXLEVELS)
    return ss_error_set(err, SS_EINTERNAL, "no stationary neighbourhood within %d levels",
                        SS_LOCAL_MAXLEVELS);
  ss_local_level *C = W->lev + W->nlev - 1, *F = W->lev + W->nlev;
  if (W->nlev >= 2) { /* C becomes an inner level: every inner row into it */
    ss_status st = ss_local_complete_rows(W, W->nlev - 1, err);
    if (st) return st;
  }
  if (W->nlev - 1 > 0 && W->nlev - 1 >= W->lc) {
    ss_status st = peel(C, near, margin, err);
    if (st) return st;
  }
  /* C's boundary facets, once for both of their uses: the marks of C's
   * complex as refined (schemes reaching 2 rings) and F's derived marks */
  const int one_split = ss_scheme_step_is_one_split(W->scheme),
            derive = one_split && W->nlev >= W->lc; /* F will be level >= lc */
  ss_local_facet *cb = NULL;
  size_t ncb = 0;
  if (ss_scheme_reach(W->scheme) > 1 || derive) {
    ss_status st = ss_local_boundary_facets(C->cx, W->ws, &cb, &ncb, err);
    if (st) return st;
  }
  if (ss_scheme_reach(W->scheme) > 1) {
    free(C->cinner);
    ss_status st = ss_local_boundary_marks(C->cx, cb, ncb, &C->cinner, err);
    if (st) return st;
  }
  if (8 * ss_cx_ncells(C->cx) > MAXCELLS)
    return ss_error_set(err, SS_ENOMEM,
                        "too large a case: the refined patch would exceed the cap of %d "
                        "cells before a stationary neighbourhood is found (a resource "
                        "limit, not a failed check)",
                        MAXCELLS);
  ss_progress_step(W->prog, "refining the star to level", (size_t)W->nlev, 0);
  ss_status st;
  if (one_split) {
    /* split, then the rule only for the rows that can be read: those of
     * inner vertices (ss_local_row_complete), where a level has its
     * boundary marks */
    st = ss_split_refine(ss_scheme_split_kind(W->scheme), C->cx, &F->cx, &F->split, err);
    if (st) return st;
    W->nlev++;
    if (derive && (st = ss_local_inner_marks_split(C->cx, cb, ncb, F->cx, F->split,
                                                   &F->inner, err)))
      return st;
#ifdef SS_CHECK_MARKS
    if (derive) {
      unsigned char *chk = NULL;
      if ((st = ss_local_inner_marks(F->cx, W->ws, &chk, err))) return st;
      const int same = !memcmp(chk, F->inner, F->cx->nv);
      free(chk);
      if (!same) return ss_error_set(err, SS_EINTERNAL, "derived boundary marks differ");
    }
#endif
    if (keep && F->inner) { /* only the rows inside Omega_w */
      if (!(F->rows = malloc(F->cx->nv + 1))) return ss_error_nomem(err, "ring rows");
      for (size_t f = 0; f < F->cx->nv; f++) {
        int in = F->inner[f];
        for (size_t q = F->split->ptr[f]; in && q < F->split->ptr[f + 1]; q++)
          in = keep[F->split->parent[q]];
        F->rows[f] = (unsigned char)in;
      }
    }
    st = ss_scheme_step_rows(W->scheme, C->cx, F->cx, F->split,
                             F->rows ? F->rows : F->inner, &C->R, err);
    if (st) return st;
  } else {
    st = ss_scheme_refine_step(W->scheme, C->cx, &F->cx, &C->R, &F->split, err);
    if (st) return st;
    W->nlev++;
  }
  const size_t nf = F->cx->nv;
  F->abs = malloc((nf + 1) * sizeof *F->abs);
  if (!F->abs) return ss_error_nomem(err, "local coordinates");
  for (size_t f = 0; f < nf; f++) {
    const ss_star_coord *par[8];
    const size_t np = ss_split_npar(F->split, f);
    if (np > 8) return ss_error_set(err, SS_EINTERNAL, "vertex with %zu parents", np);
    for (size_t i = 0; i < np; i++)
      par[i] = C->abs + F->split->parent[F->split->ptr[f] + i];
    if (ss_local_child_coord((int)np, par, F->abs + f))
      return ss_error_set(err, SS_EINTERNAL,
                          "fine vertex %zu on level %d has no integer coordinates", f,
                          W->nlev - 1);
  }
  if (W->nlev - 1 >= W->lc) return ss_local_finish_level(W, W->nlev - 1, err);
  return SS_OK;
}

/* Vertices of level l lying in Omega_w (the cells around p on level w). */
ss_status ss_local_omega_marks(const ss_local_levels *W, int w, size_t p,
                               unsigned char **out, ss_error *err) {
  for (int l = w; l < W->nlev; l++) {
    out[l - w] = calloc(W->lev[l].cx->nv + 1, 1);
    if (!out[l - w]) return ss_error_nomem(err, "two-ring");
  }
  const ss_cx *cx = W->lev[w].cx;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (ss_cell_dim((ss_cell_type)t) != ss_cx_topdim(cx)) continue;
    const int nv = ss_cell_nverts((ss_cell_type)t);
    for (size_t i = 0; i < cx->nc[t]; i++) {
      const ss_idx *v = ss_cx_cell(cx, (ss_cell_type)t, i);
      int has = 0;
      for (int j = 0; j < nv; j++)
        has |= v[j] == p;
      for (int j = 0; has && j < nv; j++)
        out[0][v[j]] = 1;
    }
  }
  for (int l = w + 1; l < W->nlev; l++) {
    const ss_split *sp = W->lev[l].split;
    for (size_t f = 0; f < sp->nfine; f++) {
      int all = 1;
      for (size_t q = sp->ptr[f]; q < sp->ptr[f + 1]; q++)
        all &= out[l - 1 - w][sp->parent[q]];
      out[l - w][f] = (unsigned char)all;
    }
  }
  return SS_OK;
}

/* Add level w + D + 1, the finest an attempt at level w reads (rows of
 * Omega_w's vertices and of the labels, ss_local.h), computing only the rows
 * inside Omega_w (ss_local_add_level's keep); the labels' rows, if any lies
 * outside, are added before S is read there (ss_local_attempt). */
ss_status ss_local_add_finest(ss_local_levels *W, int w, ss_error *err) {
  const ss_star_coord zero = ss_star_coord_make(0, NULL, NULL);
  const size_t p =
      w >= W->lc && w < W->nlev ? ss_local_lookup(W->lev + w, &zero) : SIZE_MAX;
  if (p == SIZE_MAX || !ss_scheme_step_is_one_split(W->scheme))
    return ss_local_add_level(W, NULL, 0, NULL, err);
  unsigned char *om[SS_LOCAL_MAXLEVELS] = {NULL};
  ss_status st = ss_local_omega_marks(W, w, p, om, err);
  if (!st) st = ss_local_add_level(W, NULL, 0, om[W->nlev - 1 - w], err);
  for (int l = 0; l < SS_LOCAL_MAXLEVELS; l++)
    free(om[l]);
  return st;
}

/* Whether the row of fine vertex f (level F) in C's operator is complete: f
 * is not on the boundary of F; and for schemes whose rule reads the coarse
 * neighbourhoods of the vertices it combines (reach 2, ss_scheme.h), none of
 * the row's coarse vertices is on the boundary of the complex C refined. */
int ss_local_row_complete(const ss_local_level *C, const ss_local_level *F, size_t f) {
  if (!(F->rows ? F->rows : F->inner)[f]) return 0;
  if (C->cinner)
    for (int q = C->R->p[f]; q < C->R->p[f + 1]; q++)
      if (!C->cinner[C->R->i[q]]) return 0;
  return 1;
}

void ss_local_levels_release(ss_local_levels *W) {
  for (int l = 0; l < W->nlev; l++) {
    ss_local_level *L = W->lev + l;
    if (l > 0) ss_cx_free(L->cx); /* level 0 belongs to the star */
    ss_split_free(L->split);
    if (L->R) gsl_spmatrix_free(L->R);
    if (l > 0) free(L->abs);
    free(L->rel);
    free(L->index);
    free(L->inner);
    free(L->rows);
    free(L->cinner);
  }
  if (W->star_owned) ss_star_free(W->star);
}
