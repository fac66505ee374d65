/* ss_scheme_loop.c — Loop subdivision of triangle surfaces (Loop 1987), the
 * triangular 2D baseline.
 *
 * On the 1-to-4 triangle split:
 *   edge point    3/8 of each end + 1/8 of each opposite vertex (in general
 *                 3/4 midpoint + 1/4 mean of the opposite vertices);
 *   vertex point  (1 - n b) v + b sum of its n neighbours, with Loop's
 *                 b = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n;
 * crease edges and vertices (boundaries, segment cells, non-manifold edges; see
 * ss_crease.h) follow the cubic B-spline: midpoints, and 1/8, 3/4, 1/8; corners
 * are interpolated. */
#include <math.h>
#include <stdlib.h>

#include "ss_crease.h"
#include "ss_scheme_impl.h"

/* The edge point: each end, and all opposite vertices together. */
static const double loop_edge_end = 3.0 / 8.0;
static const double loop_edge_opposite = 1.0 / 4.0;

static double loop_beta(size_t n) {
  const double t = 3.0 / 8.0 + cos(2.0 * M_PI / (double)n) / 4.0;
  return (5.0 / 8.0 - t * t) / (double)n;
}

/* A smooth surface vertex's weight c per neighbour at valence n >= 1: Loop's
 * beta, or the box-spline paper's other choice, 3/(8n) (figure 14(b)). */
static double vertex_weight(ss_loop_c c, size_t n) {
  return c == SS_LOOP_C_3_8K ? 3.0 / (8.0 * (double)n) : loop_beta(n);
}

/* The row of vertex x on a coarse surface: (1 - n c) x + c each of its n
 * neighbours nb (x alone if n = 0). */
static void vertex_emit(ss_sink *k, ss_idx x, const ss_idx *nb, size_t n, ss_loop_c c) {
  const double w = n ? vertex_weight(c, n) : 0.0;
  ss_sink_emit(k, x, x, 1.0 - (double)n * w);
  for (size_t q = 0; q < n; q++)
    ss_sink_emit(k, x, nb[q], w);
}

/* The coarse vertex two edge midpoints share (they are edges of one triangle). */
static ss_idx common_parent(const ss_split *L, ss_idx y, ss_idx z) {
  ss_idx y0 = L->parent[L->ptr[y]], y1 = L->parent[L->ptr[y] + 1];
  ss_idx z0 = L->parent[L->ptr[z]], z1 = L->parent[L->ptr[z] + 1];
  return (y0 == z0 || y0 == z1) ? y0 : y1;
}

static ss_status loop_rule(const ss_scheme *s, const ss_cx *coarse, const ss_cx *fine,
                           const ss_split *L, ss_sink *k, ss_error *err) {
  (void)coarse; /* the split complex and L say all this rule needs */
  (void)s;
  ss_crease *c = NULL;
  ss_status st = ss_crease_classify(fine, L, SS_TRIANGLE, 3, &c, err);
  if (st) return st;
  const size_t nc = L->ncoarse;
  for (size_t x = nc; x < fine->nv; x++)
    ss_sink_emit(k, x, x, c->sharp[x] ? 1.0 : 2.0 * loop_edge_end); /* x = (a + b) / 2 */
  /* the middle triangle of each coarse triangle holds its three edge midpoints */
  for (size_t t = 0; t < fine->nc[SS_TRIANGLE]; t++) {
    const ss_idx *v = ss_cx_cell(fine, SS_TRIANGLE, t);
    if (v[0] < nc || v[1] < nc || v[2] < nc) continue;
    for (int i = 0; i < 3; i++) {
      ss_idx x = v[i];
      if (c->sharp[x]) continue;
      ss_idx opp = common_parent(L, v[(i + 1) % 3], v[(i + 2) % 3]);
      double m = (double)c->nface[x] / 3.0; /* coarse triangles at this edge */
      ss_sink_emit(k, x, opp, loop_edge_opposite / m);
    }
  }
  for (size_t x = nc; x < fine->nv; x++) {
    for (size_t p = L->ptr[x]; p < L->ptr[x + 1]; p++) {
      ss_idx a = L->parent[p], b = ss_crease_other(L, x, a);
      if (c->kind[a] == SS_SMOOTH)
        ss_sink_emit(k, a, b, loop_beta(c->nedge[a]));
      else if (c->kind[a] == SS_CREASE && c->sharp[x])
        ss_sink_emit(k, a, b, 1.0 / 8.0);
    }
  }
  for (size_t v = 0; v < nc; v++) {
    const size_t n = c->nedge[v];
    double self = c->kind[v] == SS_SMOOTH   ? 1.0 - (double)n * loop_beta(n)
                  : c->kind[v] == SS_CREASE ? 3.0 / 4.0
                                            : 1.0;
    ss_sink_emit(k, v, v, self);
  }
  ss_crease_free(c);
  return SS_OK;
}

ss_status ss_scheme_loop_new(ss_scheme **out, ss_error *err) {
  unsigned accepts = (1u << SS_VERTEX) | (1u << SS_SEGMENT) | (1u << SS_TRIANGLE);
  return ss_scheme_alloc("loop", SS_SPLIT_TETOCT, accepts, loop_rule, out, err);
}

/* The triangle surface inside a split complex, for rules that take Loop's
 * rows on it one fine vertex at a time (header: ss_scheme_impl.h). */
struct ss_loop_surface {
  ss_crease *c;          /* creases of the surface, on the split restricted to it */
  ss_loop_c cmode;       /* the smooth vertex weight: Loop's beta or 3/(8k) */
  size_t *nptr;          /* per coarse vertex: its surface neighbours nb[nptr[v]..) */
  ss_idx *nb;            /* the neighbours (coarse), with */
  unsigned char *nsharp; /* 1 where the edge to that neighbour is a crease */
  size_t *optr;          /* per fine vertex: the vertices opposite it opp[optr[x]..)
                            when x is an edge midpoint of the surface */
  ss_idx *opp;           /* those vertices (coarse) */
  unsigned char *on;     /* per fine vertex: on a fine triangle, segment or vertex
                            cell */
};

void ss_loop_surface_free(ss_loop_surface *S) {
  if (!S) return;
  ss_crease_free(S->c);
  free(S->nptr);
  free(S->nb);
  free(S->nsharp);
  free(S->optr);
  free(S->opp);
  free(S->on);
  free(S);
}

ss_status ss_loop_surface_new(const ss_cx *fine, const ss_split *L, ss_loop_c cmode,
                              ss_loop_surface **out, ss_error *err) {
  *out = NULL;
  const size_t nf = fine->nv, nc = L->ncoarse;
  ss_loop_surface *S = calloc(1, sizeof *S);
  size_t *lptr = calloc(nf + 1, sizeof *lptr);
  ss_idx *par = malloc((L->ptr[nf] + 1) * sizeof *par);
  ss_status st = SS_OK;
  if (!S || !lptr || !par) goto nomem;
  S->cmode = cmode;
  S->on = calloc(nf + 1, 1);
  S->nptr = calloc(nc + 2, sizeof *S->nptr);
  S->optr = calloc(nf + 2, sizeof *S->optr);
  if (!S->on || !S->nptr || !S->optr) goto nomem;
  const ss_cell_type kept[3] = {SS_TRIANGLE, SS_SEGMENT, SS_VERTEX};
  for (int t = 0; t < 3; t++)
    for (size_t i = 0; i < fine->nc[kept[t]] * (size_t)ss_cell_nverts(kept[t]); i++)
      S->on[fine->cells[kept[t]][i]] = 1;
  /* a fine vertex off the surface is no edge of it: no parents (as ccsolid) */
  size_t m = 0;
  for (size_t x = 0; x < nf; x++) {
    if (S->on[x])
      for (size_t q = L->ptr[x]; q < L->ptr[x + 1]; q++)
        par[m++] = L->parent[q];
    lptr[x + 1] = m;
  }
  ss_split Ls = {nc, nf, lptr, par};
  ss_cx surf = {0};
  surf.dim = fine->dim;
  surf.nv = nf;
  for (int t = 0; t < 3; t++) {
    surf.nc[kept[t]] = fine->nc[kept[t]];
    surf.cells[kept[t]] = fine->cells[kept[t]];
  }
  if ((st = ss_crease_classify(&surf, &Ls, SS_TRIANGLE, 3, &S->c, err))) goto done;
  /* neighbours: the surface's edge midpoints, listed at both ends */
  for (int pass = 0; pass < 2; pass++) {
    for (size_t x = nc; x < nf; x++) {
      if (ss_split_npar(&Ls, x) != 2) continue;
      for (size_t q = Ls.ptr[x]; q < Ls.ptr[x + 1]; q++) {
        const ss_idx a = Ls.parent[q];
        if (pass == 0) {
          S->nptr[a + 2]++; /* counted, then placed (counting sort) */
          continue;
        }
        S->nb[S->nptr[a + 1]] = ss_crease_other(&Ls, x, a);
        S->nsharp[S->nptr[a + 1]++] = S->c->sharp[x];
      }
    }
    if (pass == 0) {
      for (size_t v = 0; v < nc; v++)
        S->nptr[v + 2] += S->nptr[v + 1];
      S->nb = malloc((S->nptr[nc + 1] + 1) * sizeof *S->nb);
      S->nsharp = malloc(S->nptr[nc + 1] + 1);
      if (!S->nb || !S->nsharp) goto nomem;
    }
  }
  /* opposite vertices: the middle triangle of a coarse triangle holds its
   * three edge midpoints, each opposite the coarse vertex the other two share */
  for (int pass = 0; pass < 2; pass++) {
    for (size_t t = 0; t < fine->nc[SS_TRIANGLE]; t++) {
      const ss_idx *v = ss_cx_cell(fine, SS_TRIANGLE, t);
      if (v[0] < nc || v[1] < nc || v[2] < nc) continue;
      for (int i = 0; i < 3; i++) {
        if (pass == 0) {
          S->optr[v[i] + 2]++;
          continue;
        }
        S->opp[S->optr[v[i] + 1]++] = common_parent(L, v[(i + 1) % 3], v[(i + 2) % 3]);
      }
    }
    if (pass == 0) {
      for (size_t x = 0; x < nf; x++)
        S->optr[x + 2] += S->optr[x + 1];
      if (!(S->opp = malloc((S->optr[nf + 1] + 1) * sizeof *S->opp))) goto nomem;
    }
  }
  goto done;
nomem:
  st = ss_error_nomem(err, "Loop surface");
done:
  free(lptr);
  free(par);
  if (st) {
    ss_loop_surface_free(S);
    S = NULL;
  }
  *out = S;
  return st;
}

int ss_loop_surface_emit(const ss_loop_surface *S, const ss_split *L, ss_idx x,
                         ss_sink *k) {
  if (!S->on[x]) return 0;
  const size_t nc = L->ncoarse;
  const ss_crease *c = S->c;
  if (x < nc) {
    const size_t n = S->nptr[x + 1] - S->nptr[x];
    const ss_idx *nb = S->nb + S->nptr[x];
    const unsigned char *sharp = S->nsharp + S->nptr[x];
    if (c->kind[x] == SS_SMOOTH) {
      vertex_emit(k, x, nb, n, S->cmode);
    } else if (c->kind[x] == SS_CREASE) {
      ss_sink_emit(k, x, x, 3.0 / 4.0);
      for (size_t q = 0; q < n; q++)
        if (sharp[q]) ss_sink_emit(k, x, nb[q], 1.0 / 8.0);
    } else {
      ss_sink_emit(k, x, x, 1.0);
    }
    return 1;
  }
  const size_t m = S->optr[x + 1] - S->optr[x];
  if (ss_split_npar(L, x) != 2 || c->sharp[x] || m == 0) {
    ss_sink_emit(k, x, x, 1.0); /* a crease edge's midpoint */
    return 1;
  }
  ss_sink_emit(k, x, x, 2.0 * loop_edge_end); /* x = (a + b) / 2 */
  for (size_t i = 0; i < m; i++)
    ss_sink_emit(k, x, S->opp[S->optr[x] + i], loop_edge_opposite / (double)m);
  return 1;
}
