/* ss_local.c — local subdivision matrices read from the global refinement
 * operator of a refined star: the entry points, which refine the star level
 * by level and make attempts until one succeeds, then build the ring.  The
 * method and the checks are in ss_local.h; the steps in ss_local_impl.h. */
#include <stdlib.h>
#include <string.h>

#include "ss_local_impl.h"

ss_local_opts ss_local_defaults(void) {
  return (ss_local_opts){SS_LOCAL_RING, 0.0, {NULL, NULL}, 0, NULL, 0};
}

ss_status ss_local_new(const ss_scheme *s, const ss_case *c, ss_local **out,
                       ss_error *err) {
  return ss_local_new_ring(s, c, SS_LOCAL_RING, out, err);
}

ss_status ss_local_new_ring(const ss_scheme *s, const ss_case *c, int nring,
                            ss_local **out, ss_error *err) {
  ss_local_opts o = ss_local_defaults();
  o.nring = nring;
  return ss_local_new_opts(s, c, &o, out, err);
}

ss_status ss_local_new_opts(const ss_scheme *s, const ss_case *c, const ss_local_opts *o,
                            ss_local **out, ss_error *err) {
  return ss_local_new_ws(s, c, o, NULL, out, err);
}

ss_status ss_local_new_ws(const ss_scheme *s, const ss_case *c, const ss_local_opts *o,
                          ss_local_workspace *wsp, ss_local **out, ss_error *err) {
  *out = NULL;
  const int nring = o->nring;
  if (nring < 1 || nring > SS_LOCAL_MAXRING)
    return ss_error_set(err, SS_EINPUT, "ring levels must be in 1..%d, not %d",
                        SS_LOCAL_MAXRING, nring);
  if (o->max_bytes > 0.0) { /* refuse what cannot fit before building anything */
    ss_local_cost k;
    ss_status st = ss_local_estimate(s, c, &k, err);
    if (!st) st = ss_local_check_budget(&k, o->max_bytes, err);
    if (st) return st;
  }
  ss_local_levels W;
  memset(&W, 0, sizeof W);
  /* without a caller's workspace, one for this case alone */
  ss_local_workspace own;
  memset(&own, 0, sizeof own);
  W.ws = wsp ? wsp : &own;
  W.scheme = s;
  W.prog = &o->progress;
  ss_progress_step(W.prog, "building the star", 0, 0);
  ss_status st = SS_OK;
  if (o->star) /* the caller's, only read: level 0's complex is never refined
                  in place (peeling and marks touch levels >= 1) */
    W.star = (ss_star *)o->star;
  else if ((st = ss_case_star(s, c, &W.star, err)))
    return st;
  W.star_owned = !o->star;
  ss_local *M = calloc(1, sizeof *M);
  if (!M) {
    if (W.star_owned) ss_star_free(W.star);
    return ss_error_nomem(err, "local matrix");
  }
  M->ncoord = W.star->ncoord;
  M->dim = c->kind == SS_CASE_SURFACE_VERTEX ? 2 : 3;
  M->cell = W.star->cell_type;
  /* p's chart coordinates on level lc: the origin, or (2, 1, 1) for the face
   * point */
  const int32_t idx[3] = {0, 1, 2}, val[3] = {2, 1, 1};
  W.lc = ss_case_centre_level(c->kind);
  W.cp = c->kind == SS_CASE_FACE ? ss_star_coord_make(3, idx, val)
                                 : ss_star_coord_make(0, NULL, NULL);
  W.lev[0].cx = W.star->cx;
  W.lev[0].abs = W.star->coord;
  W.nlev = 1;
  if (W.lc == 0) st = ss_local_finish_level(&W, 0, err);
  int w = W.lc + 1, rc = SS_LOCAL_ROOM;
  const int D = ss_scheme_ring_depth(s);
  while (!st && rc == SS_LOCAL_ROOM) {
    while (!st && W.nlev < w + D + 2)
      st = W.nlev + 1 == w + D + 2 ? ss_local_add_finest(&W, w, err)
                                   : ss_local_add_level(&W, NULL, 0, NULL, err);
    if (st) break;
    rc = ss_local_attempt(&W, w, M, err);
    if (rc == SS_LOCAL_HARD) st = err && err->status ? err->status : SS_EINTERNAL;
    w++;
  }
  w--;
  M->whole = o->whole != 0;
  if (!st) st = ss_local_rings_make(&W, w, nring, M, err);
  ss_local_ws_release(&own);
  W.ws = NULL; /* the caller's workspace is not the kept levels' */
  if (!st && o->keep_levels) {
    M->levels = malloc(sizeof *M->levels);
    if (M->levels) {
      *M->levels = W;         /* the levels move into M: freed by ss_local_free */
      M->levels->prog = NULL; /* the caller's options do not outlive the call */
    } else
      st = ss_error_nomem(err, "kept levels");
  }
  if (!M->levels) ss_local_levels_release(&W);
  if (st) {
    ss_local_free(M);
    return st;
  }
  *out = M;
  return SS_OK;
}

ss_status ss_local_ring_deepen(const ss_scheme *s, const ss_case *c, int nring,
                               ss_local *M, ss_error *err) {
  if (M->levels) {
    if (nring < 1 || nring > SS_LOCAL_MAXRING)
      return ss_error_set(err, SS_EINPUT, "ring levels must be in 1..%d, not %d",
                          SS_LOCAL_MAXRING, nring);
    ss_local_rings_free(M);
    ss_local_workspace own; /* the levels kept their refinement, not a workspace */
    memset(&own, 0, sizeof own);
    M->levels->ws = &own;
    const ss_status st = ss_local_rings_make(M->levels, M->level, nring, M, err);
    M->levels->ws = NULL;
    ss_local_ws_release(&own);
    return st;
  }
  ss_local *D = NULL;
  ss_status st = ss_local_new_ring(s, c, nring, &D, err);
  if (st) return st;
  if (D->n2 != M->n2 || D->n1 != M->n1 ||
      memcmp(D->S, M->S, M->n2 * M->n2 * sizeof *M->S) ||
      memcmp(D->label, M->label, M->n2 * sizeof *M->label)) {
    ss_local_free(D);
    return ss_error_set(err, SS_EINTERNAL,
                        "the deeper extraction gave another local matrix");
  }
  for (int r = 0; r < SS_LOCAL_MAXRING; r++) { /* swap the rings */
    const ss_local_ring t = M->ring[r];
    M->ring[r] = D->ring[r];
    D->ring[r] = t;
  }
  const int n = M->nring;
  M->nring = D->nring;
  D->nring = n;
  ss_local_free(D);
  return SS_OK;
}

void ss_local_free(ss_local *L) {
  if (!L) return;
  ss_local_rings_free(L);
  if (L->levels) {
    ss_local_levels_release(L->levels);
    free(L->levels);
  }
  free(L->S);
  free(L->label);
  free(L->ctype);
  free(L->corner);
  free(L);
}
