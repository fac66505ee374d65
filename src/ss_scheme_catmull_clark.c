/* ss_scheme_catmull_clark.c — Catmull-Clark subdivision of quad surfaces
 * (Catmull and Clark 1978), the 2D baseline.
 *
 * On the multilinear split:
 *   face point    the face centroid;
 *   edge point    1/2 edge midpoint + 1/2 mean of the adjacent face points
 *                 (3/8, 3/8, 1/16 x 4 for an interior edge);
 *   vertex point  ((n-2) v + (1/n) sum e_j + (1/n) sum f_j) / n for a smooth
 *                 vertex with n edges, e_j the edge neighbours and f_j the face
 *                 points — vertex parameter a = 1/(4 n^2) against MLCA's 1/(16 n);
 * crease edges and vertices (boundaries, segment cells, non-manifold edges; see
 * ss_crease.h) follow the cubic B-spline: midpoints, and 1/8, 3/4, 1/8; corners
 * are interpolated. */
#include "ss_crease.h"
#include "ss_scheme_impl.h"

ss_status ss_scheme_catmull_clark_emit(const ss_cx *surf, const ss_split *L,
                                       const unsigned char *on, ss_sink *k,
                                       ss_error *err) {
  ss_crease *c = NULL;
  ss_status st = ss_crease_classify(surf, L, SS_QUAD, 2, &c, err);
  if (st) return st;
  const size_t nc = L->ncoarse;
  for (size_t x = nc; x < surf->nv; x++) {
    if (on && !on[x]) continue;
    size_t np = ss_split_npar(L, x);
    if (np != 2 || c->sharp[x])
      ss_sink_emit(k, x, x, 1.0); /* face point or crease */
    else
      ss_sink_emit(k, x, x, 0.5);
  }
  for (size_t q = 0; q < surf->nc[SS_QUAD]; q++) {
    const ss_idx *v = ss_cx_cell(surf, SS_QUAD, q);
    ss_idx F = SS_IDX_NONE;
    for (int i = 0; i < 4; i++)
      if (ss_split_npar(L, v[i]) == 4) F = v[i];
    if (F == SS_IDX_NONE) continue; /* cannot happen for a multilinear split */
    for (int i = 0; i < 4; i++) {
      ss_idx x = v[i];
      if (x == F) continue;
      if (x < nc) {
        if (c->kind[x] == SS_SMOOTH) {
          double n = (double)c->nedge[x];
          ss_sink_emit(k, x, F, 1.0 / (n * n));
        }
      } else if (!c->sharp[x]) {
        ss_sink_emit(k, x, F, 0.5 / (double)c->nface[x]);
      }
    }
  }
  for (size_t x = nc; x < surf->nv; x++) {
    if (ss_split_npar(L, x) != 2 || (on && !on[x])) continue;
    for (size_t p = L->ptr[x]; p < L->ptr[x + 1]; p++) {
      ss_idx a = L->parent[p], b = ss_crease_other(L, x, a);
      if (c->kind[a] == SS_SMOOTH) {
        double n = (double)c->nedge[a];
        ss_sink_emit(k, a, b, 1.0 / (n * n));
      } else if (c->kind[a] == SS_CREASE && c->sharp[x]) {
        ss_sink_emit(k, a, b, 1.0 / 8.0);
      }
    }
  }
  for (size_t v = 0; v < nc; v++) {
    if (on && !on[v]) continue;
    double n = (double)c->nedge[v];
    double self = c->kind[v] == SS_SMOOTH   ? (n - 2.0) / n
                  : c->kind[v] == SS_CREASE ? 3.0 / 4.0
                                            : 1.0;
    ss_sink_emit(k, v, v, self);
  }
  ss_crease_free(c);
  return SS_OK;
}

static ss_status cc_rule(const ss_scheme *s, const ss_cx *coarse, const ss_cx *fine,
                         const ss_split *L, ss_sink *k, ss_error *err) {
  (void)coarse; /* the split complex and L say all this rule needs */
  (void)s;
  return ss_scheme_catmull_clark_emit(fine, L, NULL, k, err);
}

ss_status ss_scheme_catmull_clark_new(ss_scheme **out, ss_error *err) {
  unsigned accepts = (1u << SS_VERTEX) | (1u << SS_SEGMENT) | (1u << SS_QUAD);
  return ss_scheme_alloc("catmull-clark", SS_SPLIT_MULTILINEAR, accepts, cc_rule, out,
                         err);
}
