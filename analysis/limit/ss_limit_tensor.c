/* ss_limit_tensor.c — the layered structure of a patch around an
 * extraordinary edge (the paper's eq. (1)): whether both stationary halves
 * and the regular children factor as a B-spline along the edge times a
 * transversal part, so that the walk can jump along the edge at once. */
#include <complex.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit_impl.h"

static size_t uf_find(size_t *p, size_t i) {
  while (p[i] != i)
    i = p[i] = p[p[i]];
  return i;
}

/* Whether W (Kc child points x T's K parent points, row-major) is A_b (x) F
 * for some F: child point u in layer lc[u] of column cc[u] (ncc columns,
 * cpt[c][l] the point of column c in layer l), parent points as T says;
 * F (ncc x T->ncol) is scratch.  To 1e-12. */
static int factors(const double *W, size_t Kc, const int *lc, const size_t *cc,
                   size_t ncc, const size_t (*cpt)[4], const ss_lim_tensor *T, int b,
                   double *F) {
  const size_t K = T->ncol * 4, n = T->ncol;
  for (size_t p = 0; p < ncc; p++)
    for (size_t q = 0; q < n; q++)
      F[p * n + q] = W[cpt[p][1] * K + T->colpt[q][1]] / ss_lim_bspline_half[b][1][1];
  for (size_t u = 0; u < Kc; u++)
    for (size_t w = 0; w < K; w++) {
      double want = ss_lim_bspline_half[b][lc[u]][T->layer[w]] * F[cc[u] * n + T->col[w]];
      if (!(fabs(W[u * K + w] - want) <= 1e-12)) return 0;
    }
  return 1;
}

/* The axis of the extraordinary edge at state i's stationary child k: the
 * one a whose neighbour k ^ (1 << a) is a stationary run too (a vertex has
 * none, a boundary face two), with positions along it consistent; tr[b] the
 * run of the half b along it.  *axis = -1 if there is none. */
static ss_status tensor_axis(ss_limit *L, size_t i, int k, int *axis, ss_lim_trans *tr[2],
                             ss_error *err) {
  ss_status st;
  const unsigned bk = ss_cube_corner_bits(3, k);
  int ax = -1, runs = 0;
  *axis = -1;
  for (int a = 0; a < 3; a++) {
    ss_lim_trans *t;
    if ((st = ss_lim_transition(L, i, ss_cube_corner_index(3, bk ^ (1u << a)), &t, err)))
      return st;
    if (t->next == i && ss_lim_frame_is_id(&t->g)) {
      runs++;
      ax = a;
      tr[(bk >> a) & 1u ? 0 : 1] = t;
    }
  }
  const ss_lim_state *S = L->st[i];
  if (runs != 1 || (S->patch.posbad >> ax) & 1u) return SS_OK;
  tr[(bk >> ax) & 1u] = S->tr[k];
  *axis = ax;
  return SS_OK;
}

/* ss_limit_impl.h */
int ss_lim_tensor_columns(const ss_lim_patch *P, ss_lim_tensor *T, size_t *uf) {
  const size_t K = P->nv;
  const int axis = T->axis;
  for (size_t v = 0; v < K; v++) {
    int l = P->pos[v][axis] + 1;
    if (l < 0 || l > 3) return 0;
    T->layer[v] = l;
    uf[v] = v;
  }
  /* columns: the ends of every cell edge along the axis */
  for (size_t c = 0; c < P->ncells; c++)
    for (unsigned b = 0; b < 8; b++)
      if (!((b >> axis) & 1u)) {
        size_t u = P->key[c * 8 + (size_t)ss_cube_corner_index(3, b)];
        size_t w = P->key[c * 8 + (size_t)ss_cube_corner_index(3, b | (1u << axis))];
        uf[uf_find(uf, u)] = uf_find(uf, w);
      }
  for (size_t v = 0; v < K; v++)
    T->col[v] = SIZE_MAX;
  for (size_t v = 0; v < K; v++) {
    size_t r = uf_find(uf, v);
    if (T->col[r] == SIZE_MAX) {
      T->col[r] = T->ncol;
      for (int l = 0; l < 4; l++)
        T->colpt[T->ncol][l] = SIZE_MAX;
      T->ncol++;
    }
    T->col[v] = T->col[r];
  }
  for (size_t v = 0; v < K; v++) {
    size_t *slot = &T->colpt[T->col[v]][T->layer[v]];
    if (*slot != SIZE_MAX) return 0; /* two points of a column in one layer */
    *slot = v;
  }
  for (size_t c = 0; c < T->ncol; c++)
    for (int l = 0; l < 4; l++)
      if (T->colpt[c][l] == SIZE_MAX) return 0;
  return 1;
}

/* Every child of state i but the two runs (bk the bits of child k): regular
 * (a tricubic B-spline, a tensor product) with its net factoring the same
 * way, its layers along the edge's axis; *ok = 1 if all do (F scratch). */
static ss_status tensor_children(ss_limit *L, size_t i, unsigned bk,
                                 const ss_lim_tensor *T, double *F, int *ok,
                                 ss_error *err) {
  ss_status st;
  const int axis = T->axis;
  *ok = 0;
  for (int kk = 0; kk < 8; kk++) {
    unsigned bb = ss_cube_corner_bits(3, kk);
    if (((bb ^ bk) & ~(1u << axis)) == 0) continue; /* the two runs */
    ss_lim_trans *t;
    if ((st = ss_lim_transition(L, i, kk, &t, err))) return st;
    const ss_lim_patch *cp = &L->st[t->next]->patch;
    if (!cp->regular) return SS_OK;
    int ca = 0; /* the child's framed axis along the edge */
    while (t->g.perm[ca] != axis)
      ca++;
    int lay[64];
    size_t col[64], colpt[16][4];
    for (int g = 0; g < 64; g++) {
      int ix[3] = {g % 4, (g / 4) % 4, g / 16};
      int o1 = (ca + 1) % 3, o2 = (ca + 2) % 3;
      int l = t->g.flip[ca] ? 3 - ix[ca] : ix[ca];
      size_t v = cp->net[g];
      lay[v] = l;
      col[v] = (size_t)(4 * ix[o1] + ix[o2]);
      colpt[col[v]][l] = v;
    }
    if (!factors(t->W, 64, lay, col, 16, (const size_t(*)[4])colpt, T,
                 (int)((bb >> axis) & 1u), F))
      return SS_OK;
  }
  *ok = 1;
  return SS_OK;
}

/* The layered structure of state i, whose child k is a stationary run: it
 * is an extraordinary edge's when exactly one neighbour k ^ (1 << a) of k is
 * a stationary run too (a vertex has none, a boundary face two), the
 * positions along a are consistent, the points form columns of 4 layers
 * across a, both runs' W factor as A_b (x) T to 1e-12, and every other child
 * is regular with its net factoring likewise -- then every basis function on
 * the cell is a product N_l(x_a) phi_c(y), which eq. (1) needs. */
ss_status ss_lim_tensor_of(ss_limit *L, size_t i, int k, ss_lim_tensor **out,
                           ss_error *err) {
  ss_status st = SS_OK;
  ss_lim_state *S = L->st[i];
  if (S->ten) {
    *out = S->ten;
    return SS_OK;
  }
  ss_lim_tensor *T = calloc(1, sizeof *T);
  size_t *uf = NULL;
  double *F = NULL;
  if (!T) return ss_error_nomem(err, "layers");
  T->status = -1;
  const size_t K = S->patch.nv;
  const unsigned bk = ss_cube_corner_bits(3, k);
  int axis = -1, ok = 0;
  ss_lim_trans *tr[2] = {NULL, NULL};
  if ((st = tensor_axis(L, i, k, &axis, tr, err)) || axis < 0) goto done;
  S = L->st[i];
  T->axis = axis;
  T->layer = malloc((K + 1) * sizeof *T->layer);
  T->col = malloc((K + 1) * sizeof *T->col);
  T->colpt = malloc((K + 1) * sizeof *T->colpt);
  uf = malloc((K + 1) * sizeof *uf);
  if (!T->layer || !T->col || !T->colpt || !uf) {
    st = ss_error_nomem(err, "layers");
    goto done;
  }
  if (!ss_lim_tensor_columns(&S->patch, T, uf)) goto done;
  /* both halves: W[u][w] = A_b[layer u][layer w] F[col u][col w] */
  F = malloc((T->ncol * T->ncol + 64 * T->ncol + 1) * sizeof *F);
  if (!F) {
    st = ss_error_nomem(err, "layers");
    goto done;
  }
  for (int b = 0; b < 2; b++)
    if (!factors(tr[b]->W, K, T->layer, T->col, T->ncol, (const size_t(*)[4])T->colpt, T,
                 b, F))
      goto done;
  if ((st = tensor_children(L, i, bk, T, F, &ok, err)) || !ok) goto done;
  T->status = 1;
  L->stats.tensor++;
done:
  free(uf);
  free(F);
  if (st) {
    ss_lim_tensor_free(T);
    return st;
  }
  L->st[i]->ten = T;
  *out = T;
  return SS_OK;
}
