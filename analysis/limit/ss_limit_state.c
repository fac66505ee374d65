/* ss_limit_state.c — the limit evaluator's cache: the patch topologies met so
 * far (states, found by hash), each coarse cell's state, and the transitions
 * of a state into its children, computed on first use; coarse-only states'
 * transitions are kept for the most recent ones only. */
#include <complex.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"
#include "ss_limit_impl.h"

void ss_lim_tensor_free(ss_lim_tensor *t) {
  if (!t) return;
  free(t->layer);
  free(t->col);
  free(t->colpt);
  free(t);
}

static void drop_refined(ss_lim_state *s) {
  if (!s->rf) return;
  ss_lim_refined_free(s->rf);
  free(s->rf);
  s->rf = NULL;
}

static void drop_transitions(ss_lim_state *s) {
  drop_refined(s);
  for (int k = 0; k < 8; k++)
    if (s->tr[k]) {
      free(s->tr[k]->W);
      free(s->tr[k]->rp);
      free(s->tr[k]->ci);
      ss_lim_eig_free(s->tr[k]->eig);
      free(s->tr[k]->chi);
      free(s->tr[k]);
      s->tr[k] = NULL;
    }
}

void ss_lim_state_free(ss_lim_state *s) {
  if (!s) return;
  ss_lim_patch_free(&s->patch);
  ss_cx_free(s->cx);
  drop_transitions(s);
  ss_lim_tensor_free(s->ten);
  free(s);
}

static ss_status grow_table(ss_limit *L, ss_error *err) {
  size_t cap = L->captab * 2;
  size_t *t = calloc(cap, sizeof *t);
  if (!t) return ss_error_nomem(err, "state table");
  for (size_t i = 0; i < L->nst; i++) {
    size_t h = (size_t)L->st[i]->hash & (cap - 1);
    while (t[h])
      h = (h + 1) & (cap - 1);
    t[h] = i + 1;
  }
  free(L->tab);
  L->tab = t;
  L->captab = cap;
  return SS_OK;
}

/* The state of patch p (taken over: moved into a new state, or freed when its
 * key is known), with instance complex cx (likewise). */
static ss_status state_of(ss_limit *L, ss_lim_patch *p, ss_cx *cx, size_t *out,
                          ss_error *err) {
  ss_status st;
  uint64_t h = ss_lim_patch_hash(p);
  size_t i = (size_t)h & (L->captab - 1);
  while (L->tab[i]) {
    ss_lim_state *s = L->st[L->tab[i] - 1];
    if (s->hash == h && ss_lim_patch_same(&s->patch, p)) {
      *out = L->tab[i] - 1;
      ss_lim_patch_free(p);
      ss_cx_free(cx);
      return SS_OK;
    }
    i = (i + 1) & (L->captab - 1);
  }
  ss_lim_state *s = calloc(1, sizeof *s);
  if (!s) {
    st = ss_error_nomem(err, "state");
    goto fail;
  }
  if (L->nst == L->capst) {
    size_t cap = L->capst ? 2 * L->capst : 16;
    ss_lim_state **n = realloc(L->st, cap * sizeof *n);
    if (!n) {
      st = ss_error_nomem(err, "states");
      goto fail;
    }
    L->st = n;
    L->capst = cap;
  }
  s->patch = *p;
  s->cx = cx;
  s->hash = h;
  L->st[L->nst] = s;
  L->tab[i] = L->nst + 1;
  *out = L->nst++;
  L->stats.keys++;
  if (2 * L->nst > L->captab) return grow_table(L, err);
  return SS_OK;
fail:
  free(s);
  ss_lim_patch_free(p);
  ss_cx_free(cx);
  return st;
}

/* The state of coarse cell c (its patch in its canonical frame). */
ss_status ss_lim_cell_state(ss_limit *L, size_t c, ss_error *err) {
  if (L->cell[c].state != SIZE_MAX) return SS_OK;
  ss_status st;
  ss_lim_patch p;
  ss_cx *cx = NULL;
  /* a regular patch needs no canonical frame (every frame gives the same
   * grid walk up to the B-spline's symmetry, and it has no transitions):
   * most cells of a mesh are, and the 48 walks would dominate a first pass */
  L->cell[c].g = ss_lim_frame_id();
  if ((st = ss_lim_patch_build(&L->adj, c, &L->cell[c].g, L->loc, &p, err))) return st;
  if (!p.regular) {
    ss_lim_patch_free(&p);
    if ((st = ss_lim_patch_canonical(&L->adj, c, L->loc, &p, &L->cell[c].g, err)))
      return st;
  }
  ss_idx *src = malloc((p.nv + 1) * sizeof *src);
  if (!src) {
    ss_lim_patch_free(&p);
    return ss_error_nomem(err, "cell patch");
  }
  memcpy(src, p.src, p.nv * sizeof *src);
  if ((st = ss_lim_patch_complex(L->mesh, &p, &cx, err))) {
    free(src);
    ss_lim_patch_free(&p);
    return st;
  }
  size_t s, before = L->nst;
  if ((st = state_of(L, &p, cx, &s, err))) {
    free(src);
    return st;
  }
  if (L->nst > before) {
    /* a coarse-only patch keeps no instance until its transitions are
     * needed: one per irregular cell would grow with the mesh */
    L->st[s]->coarse_only = 1;
    L->st[s]->src_cell = c;
    ss_cx_free(L->st[s]->cx);
    L->st[s]->cx = NULL;
  }
  L->cell[c].src = src;
  L->cell[c].state = s;
  return SS_OK;
}

/* t's nonzeros (rp, ci) from W (Kc x K).  SS_ENOMEM. */
static ss_status sparse_rows(ss_lim_trans *t, size_t Kc, size_t K, ss_error *err) {
  size_t nz = 0;
  for (size_t q = 0; q < Kc * K; q++)
    nz += t->W[q] != 0.0;
  t->rp = malloc((Kc + 1) * sizeof *t->rp);
  t->ci = malloc((nz + 1) * sizeof *t->ci);
  if (!t->rp || !t->ci) return ss_error_nomem(err, "transition rows");
  nz = 0;
  for (size_t i = 0; i < Kc; i++) {
    t->rp[i] = nz;
    for (size_t j = 0; j < K; j++)
      if (t->W[i * K + j] != 0.0) t->ci[nz++] = j;
  }
  t->rp[Kc] = nz;
  return SS_OK;
}

ss_status ss_lim_trans_apply(const ss_lim_trans *t, size_t Kc, size_t K, size_t D,
                             double **P, ss_error *err) {
  double *Q = calloc(Kc * D + 1, sizeof *Q);
  if (!Q) return ss_error_nomem(err, "patch points");
  if (D == 3) {
    /* the same sums, each row's three kept in registers */
    const double *X = *P;
    for (size_t i = 0; i < Kc; i++) {
      double a0 = 0.0, a1 = 0.0, a2 = 0.0;
      const double *w = t->W + i * K;
      for (size_t q = t->rp[i]; q < t->rp[i + 1]; q++) {
        const size_t j = t->ci[q];
        a0 += w[j] * X[j * 3];
        a1 += w[j] * X[j * 3 + 1];
        a2 += w[j] * X[j * 3 + 2];
      }
      Q[i * 3] = a0, Q[i * 3 + 1] = a1, Q[i * 3 + 2] = a2;
    }
    free(*P);
    *P = Q;
    return SS_OK;
  }
  for (size_t i = 0; i < Kc; i++)
    for (size_t q = t->rp[i]; q < t->rp[i + 1]; q++) {
      const size_t j = t->ci[q];
      const double w = t->W[i * K + j];
      for (size_t d = 0; d < D; d++)
        Q[i * D + d] += w * (*P)[j * D + d];
    }
  free(*P);
  *P = Q;
  return SS_OK;
}

/* The transition of state i into child k, computed on first use. */
ss_status ss_lim_transition(ss_limit *L, size_t i, int k, ss_lim_trans **out,
                            ss_error *err) {
  ss_status st;
  ss_lim_state *s = L->st[i];
  if (s->tr[k]) {
    *out = s->tr[k];
    return SS_OK;
  }
  if (!s->cx) {
    ss_lim_patch p;
    size_t c = s->src_cell;
    if ((st = ss_lim_patch_build(&L->adj, c, &L->cell[c].g, L->loc, &p, err))) return st;
    int same = ss_lim_patch_same(&p, &s->patch);
    st = same ? ss_lim_patch_complex(L->mesh, &p, &s->cx, err)
              : ss_error_set(err, SS_EINTERNAL, "limit: cell %zu's patch changed", c + 1);
    ss_lim_patch_free(&p);
    if (st) return st;
  }
  ss_lim_trans *t = calloc(1, sizeof *t);
  if (!t) return ss_error_nomem(err, "transition");
  ss_lim_patch child;
  ss_cx *ccx;
  double t0 = ss_clock_cpu();
  /* one refinement of the patch for all its children (the walks ask for them
   * one at a time: each used to refine the patch again) */
  if (!s->rf && !(s->rf = calloc(1, sizeof *s->rf))) {
    free(t);
    return ss_error_nomem(err, "refined patch");
  }
  if (!s->rf->fine) {
    if ((st = ss_lim_refine(L->s, s->cx, 1, s->rf, err))) {
      drop_refined(s);
      free(t);
      return st;
    }
    /* the oldest of the ring gives its refinement up (it may be gone already,
     * or this state itself: then nothing is dropped) */
    size_t slot = L->nrefined % SS_LIM_REFINED;
    if (L->nrefined >= SS_LIM_REFINED && L->refined[slot] != i)
      drop_refined(L->st[L->refined[slot]]);
    L->refined[slot] = i;
    L->nrefined++;
  }
  if ((st = ss_lim_cut(s->rf, k, 1, &child, &t->g, &ccx, &t->W, err))) {
    free(t);
    return st;
  }
  const size_t Kc = child.nv, K = s->patch.nv;
  if ((st = state_of(L, &child, ccx, &t->next, err)) ||
      (st = sparse_rows(t, Kc, K, err))) {
    free(t->W);
    free(t->rp);
    free(t->ci);
    free(t);
    return st;
  }
  ss_clock_lap(&L->stats.matrix_s, &t0);
  L->st[i]->tr[k] = t; /* L->st may have moved, the state has not */
  int all = 1;
  for (int j = 0; j < 8; j++)
    all &= s->tr[j] != NULL;
  if (all) drop_refined(s);
  L->stats.transitions++;
  L->st[t->next]->coarse_only = 0; /* a child's patch: keep its transitions */
  if (s->coarse_only && !s->held) {
    size_t slot = L->nrecent % SS_LIM_RECENT;
    if (L->nrecent >= SS_LIM_RECENT) {
      ss_lim_state *old = L->st[L->recent[slot]];
      if (old->coarse_only) {
        drop_transitions(old);
        ss_cx_free(old->cx);
        old->cx = NULL;
      }
      old->held = 0;
    }
    L->recent[slot] = i;
    L->nrecent++;
    s->held = 1;
  }
  *out = t;
  return SS_OK;
}
