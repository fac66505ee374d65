/* ss_scheme_points.c — the points family (ss_scheme.h, ss_points): new
 * points as weighted sums of named averages, for Catmull-Clark-solid-like
 * rules on hex meshes and Loop-like rules on triangle surfaces, with the
 * weights read from stencil files (ss_stencil.h, family = points).
 *
 * A fine vertex x stands for the coarse element X of its parents (itself
 * for an old vertex).  The elements incident to X are read off the fine
 * cells of the place's top dimension holding x: each corner y of such a
 * cell stands for the element of its parents, and the cell itself lies in
 * the coarse cell that is the union of its corners' parents (a triangle's
 * face has no split point; a hex's has, and the union is the same set).
 * Every coarse element incident to X (X in E or E in X) is found so: an
 * element E comparable with X has lattice digits within one of X's in some
 * coarse cell holding both, hence a fine cell holding both x and E's point
 * (or lying in E).  Elements are compared as sorted sets of coarse
 * vertices; each distinct one counts once, whatever number of fine cells
 * shows it.  The mean of centroids is emitted on the coarse vertices
 * themselves (weight / count / |E| each).  An old vertex on an extraordinary
 * edge (ss_points.axis) is recognised from the same elements — the valence
 * of an edge is the number of hexes among them holding it — and takes the
 * axis weights when the scheme has them.  So this rule shares nothing with
 * the built-in ccsolid and loop rules but the surface (ss_hex_surface_build)
 * and the crease classification (ss_crease.h): tests compare the two. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_crease.h"
#include "ss_scheme_impl.h"

#define NMAXV 8 /* vertices of an element at most (a hex) */

/* A coarse element: its vertices, ascending. */
typedef struct {
  int n;           /* number of vertices (1, 2, 3, 4 or 8) */
  ss_idx v[NMAXV]; /* the vertices */
} element;

/* Fine cells of one place: `nv` corners each, and the cells at each fine
 * vertex (CSR). */
typedef struct {
  int nv;          /* corners per cell: 8 hex, 4 quad, 3 triangle, 2 segment */
  size_t nc;       /* cells */
  const ss_idx *c; /* nc * nv corners */
  size_t *ptr;     /* per fine vertex: at[ptr[x] .. ptr[x + 1]) (owned) */
  size_t *at;      /* cell indices (owned) */
} place_cells;

static void place_clear(place_cells *P) {
  free(P->ptr);
  free(P->at);
}

static ss_status place_index(place_cells *P, size_t nf, ss_error *err) {
  P->ptr = calloc(nf + 2, sizeof *P->ptr);
  P->at = malloc((P->nc * (size_t)P->nv + 1) * sizeof *P->at);
  if (!P->ptr || !P->at) return ss_error_nomem(err, "points rule");
  for (size_t i = 0; i < P->nc * (size_t)P->nv; i++)
    P->ptr[P->c[i] + 2]++;
  for (size_t x = 0; x < nf; x++)
    P->ptr[x + 2] += P->ptr[x + 1];
  for (size_t i = 0; i < P->nc * (size_t)P->nv; i++)
    P->at[P->ptr[P->c[i] + 1]++] = i / (size_t)P->nv;
  return SS_OK;
}

/* The element of fine vertex y (its parents in L). */
static element element_of(const ss_split *L, ss_idx y) {
  element e = {0, {0}};
  for (size_t q = L->ptr[y]; q < L->ptr[y + 1] && e.n < NMAXV; q++)
    e.v[e.n++] = L->parent[q];
  return e;
}

static int cmp_idx(const void *a, const void *b) {
  const ss_idx x = *(const ss_idx *)a, y = *(const ss_idx *)b;
  return (x > y) - (x < y);
}

static int cmp_element(const void *a, const void *b) {
  const element *x = a, *y = b;
  if (x->n != y->n) return x->n - y->n;
  for (int i = 0; i < x->n; i++)
    if (x->v[i] != y->v[i]) return x->v[i] < y->v[i] ? -1 : 1;
  return 0;
}

/* a's vertices all in b's (both ascending). */
static int subset(const element *a, const element *b) {
  int j = 0;
  for (int i = 0; i < a->n; i++) {
    while (j < b->n && b->v[j] < a->v[i])
      j++;
    if (j == b->n || b->v[j] != a->v[i]) return 0;
  }
  return 1;
}

/* The dimension of an element of n vertices under the split. */
static int element_dim(ss_split_kind split, int n) {
  if (split == SS_SPLIT_MULTILINEAR) return n == 1 ? 0 : n == 2 ? 1 : n == 4 ? 2 : 3;
  return n - 1; /* vertex, edge, triangle */
}

/* The union of the parents of cell c's corners, as an element. */
static element cell_element(const ss_split *L, const place_cells *P, size_t c) {
  ss_idx all[4 * NMAXV];
  int m = 0;
  for (int i = 0; i < P->nv; i++) {
    const ss_idx y = P->c[c * (size_t)P->nv + (size_t)i];
    for (size_t q = L->ptr[y]; q < L->ptr[y + 1] && m < 4 * NMAXV; q++)
      all[m++] = L->parent[q];
  }
  qsort(all, (size_t)m, sizeof *all, cmp_idx);
  element e = {0, {0}};
  for (int i = 0; i < m && e.n < NMAXV; i++)
    if (i == 0 || all[i] != all[i - 1]) e.v[e.n++] = all[i];
  return e;
}

/* The hexes among the u elements e that hold element i. */
static size_t cells_holding(const element *e, size_t u, size_t i) {
  size_t c = 0;
  for (size_t j = 0; j < u; j++)
    c += e[j].n == 8 && subset(e + i, e + j);
  return c;
}

/* m if the old vertex whose u distinct incident elements are e (count[k] of
 * dimension k, multilinear) lies on an extraordinary edge (ss_points.axis:
 * 2m hexes, m + 2 edges, exactly two of valence m != 4 in no common hex,
 * the others of valence 4); 0 otherwise.  along[0..1]: those two. */
static size_t axis_valence(const element *e, size_t u, const size_t *count,
                           size_t *along) {
  size_t na = 0, m = 0;
  for (size_t i = 0; i < u; i++) {
    if (e[i].n != 2) continue;
    const size_t v = cells_holding(e, u, i);
    if (v == 4) continue;
    if (na == 2 || (na && v != m)) return 0;
    m = v;
    along[na++] = i;
  }
  if (na != 2 || m < 3 || count[3] != 2 * m || count[1] != m + 2) return 0;
  for (size_t j = 0; j < u; j++)
    if (e[j].n == 8 && subset(e + along[0], e + j) && subset(e + along[1], e + j))
      return 0;
  return m;
}

/* The row of an old vertex on an extraordinary edge of valence m (its u
 * elements e, count[k] of dimension k; along: the two edges along) by the
 * scheme's [volume.axis] weights at n = 2m. */
static void emit_axis(const ss_scheme *s, size_t x, const element *e, size_t u,
                      const size_t *count, size_t m, const size_t *along, ss_sink *k) {
  const size_t NN = SS_AVG_NMAX + 1, n = 2 * m;
  const double *w = s->paxis;
  for (size_t i = 0; i < u; i++) {
    const int kd = element_dim(SS_SPLIT_MULTILINEAR, e[i].n);
    static const int key[4] = {SS_AXIS_VERTEX, SS_AXIS_EDGE, SS_AXIS_FACE, SS_AXIS_CELL};
    double wk = w[(size_t)key[kd] * NN + n] / (double)count[kd];
    if (kd == 1)
      wk += i == along[0] || i == along[1]
                ? w[(size_t)SS_AXIS_ALONG * NN + n] / 2.0
                : w[(size_t)SS_AXIS_ACROSS * NN + n] / (double)m;
    if (wk == 0.0) continue;
    for (int j = 0; j < e[i].n; j++)
      ss_sink_emit(k, x, e[i].v[j], wk / (double)e[i].n);
  }
}

/* Scratch of one rule: the candidate elements of one fine vertex. */
typedef struct {
  element *e; /* cap of them */
  size_t cap;
} scratch;

/* Fine vertex x, of element dimension d, by the weights of (place, d): the
 * distinct elements incident to x's element in the cells of P at x, their
 * counts by dimension, and the row emitted.  SS_EINPUT when n (the top
 * elements) exceeds SS_AVG_NMAX; SS_ENOMEM. */
static ss_status emit_point(const ss_scheme *s, const ss_split *L, const place_cells *P,
                            int place, int top, size_t x, scratch *W, ss_sink *k,
                            ss_error *err) {
  const size_t ncell = P->ptr[x + 1] - P->ptr[x];
  const size_t need = ncell * (size_t)(P->nv + 1);
  if (need > W->cap) {
    element *e = realloc(W->e, need * sizeof *e);
    if (!e) return ss_error_nomem(err, "points rule");
    W->e = e, W->cap = need;
  }
  const element X = element_of(L, (ss_idx)x);
  size_t m = 0;
  for (size_t q = P->ptr[x]; q < P->ptr[x + 1]; q++) {
    const size_t c = P->at[q];
    for (int i = 0; i <= P->nv; i++) {
      const element E = i < P->nv ? element_of(L, P->c[c * (size_t)P->nv + (size_t)i])
                                  : cell_element(L, P, c);
      if (subset(&E, &X) || subset(&X, &E)) W->e[m++] = E;
    }
  }
  qsort(W->e, m, sizeof *W->e, cmp_element);
  size_t count[4] = {0};
  size_t u = 0;
  for (size_t i = 0; i < m; i++)
    if (i == 0 || cmp_element(W->e + i, W->e + u - 1)) {
      W->e[u++] = W->e[i];
      count[element_dim(s->split, W->e[i].n)]++;
    }
  const size_t n = count[top];
  const int d = element_dim(s->split, X.n);
  if (n > SS_AVG_NMAX)
    return ss_error_set(err, SS_EINPUT,
                        "scheme %s: fine vertex %zu has %zu cells at its element, beyond "
                        "the valences its weights are given for (1..%d)",
                        s->name, x + 1, n, SS_AVG_NMAX);
  size_t along[2], ma = 0;
  if (place == SS_PTS_VOLUME && d == 0 && s->paxis &&
      (ma = axis_valence(W->e, u, count, along))) {
    emit_axis(s, x, W->e, u, count, ma, along, k);
    return SS_OK;
  }
  const double *w = s->ptab + (size_t)(place * 4 + d) * 4 * (SS_AVG_NMAX + 1);
  for (size_t i = 0; i < u; i++) {
    const int kd = element_dim(s->split, W->e[i].n);
    const double wk = w[(size_t)kd * (SS_AVG_NMAX + 1) + n];
    if (wk == 0.0) continue;
    const double each = wk / (double)count[kd] / (double)W->e[i].n;
    for (int j = 0; j < W->e[i].n; j++)
      ss_sink_emit(k, x, W->e[i].v[j], each);
  }
  return SS_OK;
}

/* The crease edges of a classified surface as fine segments (a, x), (x, b)
 * for each sharp midpoint x of the surface (on[x]), into *segs (owned). */
static ss_status crease_segments(const ss_split *Ls, const ss_crease *c,
                                 const unsigned char *on, size_t nf, ss_idx **segs,
                                 size_t *nseg, ss_error *err) {
  *nseg = 0;
  if (!(*segs = malloc((4 * nf + 1) * sizeof **segs)))
    return ss_error_nomem(err, "points rule");
  for (size_t x = Ls->ncoarse; x < nf; x++) {
    if (!on[x] || ss_split_npar(Ls, x) != 2 || !c->sharp[x]) continue;
    for (size_t q = Ls->ptr[x]; q < Ls->ptr[x + 1]; q++) {
      (*segs)[2 * *nseg] = Ls->parent[q];
      (*segs)[2 * *nseg + 1] = (ss_idx)x;
      ++*nseg;
    }
  }
  return SS_OK;
}

/* The place of fine vertex x and its element's dimension: 0 corner or in no
 * cell (x stays), else 1 with *place set. */
static int place_of(const ss_split *Ls, const ss_crease *c, const unsigned char *on,
                    const place_cells *vol, size_t x, int *place) {
  const size_t nc = Ls->ncoarse;
  if (!on[x]) {
    *place = SS_PTS_VOLUME;
    return vol->ptr && vol->ptr[x + 1] > vol->ptr[x];
  }
  if (x < nc) {
    if (c->kind[x] == SS_CORNER) return 0;
    *place = c->kind[x] == SS_CREASE ? SS_PTS_CREASE : SS_PTS_SURFACE;
    return 1;
  }
  *place = ss_split_npar(Ls, x) == 2 && c->sharp[x] ? SS_PTS_CREASE : SS_PTS_SURFACE;
  return 1;
}

static ss_status points_rule(const ss_scheme *s, const ss_cx *coarse, const ss_cx *fine,
                             const ss_split *L, ss_sink *k, ss_error *err) {
  (void)coarse; /* the split complex and L say all this rule needs */
  const size_t nf = fine->nv;
  const int hexes = s->split == SS_SPLIT_MULTILINEAR;
  ss_hex_surface hs = {0};
  ss_crease *c = NULL;
  place_cells P[SS_PTS_PLACES];
  memset(P, 0, sizeof P);
  ss_idx *segs = NULL;
  unsigned char *on = NULL;
  scratch W = {NULL, 0};
  ss_status st = SS_OK;
  const ss_cx *surf = fine;
  const ss_split *Ls = L;
  if (hexes) {
    if ((st = ss_hex_surface_build(fine, L, &hs, err))) goto done;
    surf = &hs.surf, Ls = &hs.Ls, on = hs.on;
  } else {
    if (!(on = calloc(nf + 1, 1))) goto nomem;
    for (int t = 0; t < SS_NCELLTYPES; t++)
      for (size_t i = 0; i < fine->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t); i++)
        on[fine->cells[t][i]] = 1;
  }
  const ss_cell_type face = hexes ? SS_QUAD : SS_TRIANGLE;
  if ((st = ss_crease_classify(surf, Ls, face, hexes ? 2 : 3, &c, err))) goto done;
  P[SS_PTS_VOLUME] = (place_cells){8, fine->nc[SS_HEX], fine->cells[SS_HEX], NULL, NULL};
  P[SS_PTS_SURFACE] =
      (place_cells){ss_cell_nverts(face), surf->nc[face], surf->cells[face], NULL, NULL};
  size_t nseg = 0;
  if ((st = crease_segments(Ls, c, on, nf, &segs, &nseg, err))) goto done;
  P[SS_PTS_CREASE] = (place_cells){2, nseg, segs, NULL, NULL};
  for (int p = 0; p < SS_PTS_PLACES; p++)
    if ((st = place_index(P + p, nf, err))) goto done;
  static const int top[SS_PTS_PLACES] = {3, 2, 1};
  for (size_t x = 0; x < nf && !st; x++) {
    if (!ss_sink_wants(k, x)) continue;
    int place = 0;
    if (!place_of(Ls, c, on, P + SS_PTS_VOLUME, x, &place))
      ss_sink_emit(k, x, x, 1.0);
    else
      st = emit_point(s, L, P + place, place, top[place], x, &W, k, err);
  }
  goto done;
nomem:
  st = ss_error_nomem(err, "points rule");
done:
  for (int p = 0; p < SS_PTS_PLACES; p++)
    place_clear(P + p);
  free(W.e);
  free(segs);
  ss_crease_free(c);
  if (hexes)
    ss_hex_surface_clear(&hs);
  else
    free(on);
  return st;
}

/* p's axis weights as a table (*tab, NULL when none is given), their sums
 * checked at every n.  SS_EINPUT, SS_ENOMEM. */
static ss_status axis_table(const char *name, const ss_points *p, double **tab,
                            ss_error *err) {
  const size_t NN = SS_AVG_NMAX + 1;
  int given = 0;
  for (int k = 0; k < SS_AXIS_KEYS; k++)
    given |= p->axis[k] != NULL;
  *tab = NULL;
  if (!given) return SS_OK;
  if (p->split != SS_SPLIT_MULTILINEAR)
    return ss_error_set(err, SS_EINPUT,
                        "scheme %s: axis weights (a vertex on an extraordinary edge) "
                        "need the multilinear split",
                        name);
  if (!(*tab = calloc(SS_AXIS_KEYS * NN, sizeof **tab)))
    return ss_error_nomem(err, "points weights");
  for (size_t n = 1; n < NN; n++) {
    double sum = 0.0;
    for (int k = 0; k < SS_AXIS_KEYS; k++)
      sum += (*tab)[(size_t)k * NN + n] = p->axis[k] ? p->axis[k][n] : 0.0;
    if (!(fabs(sum - 1.0) <= 1e-12)) {
      free(*tab);
      *tab = NULL;
      return ss_error_set(err, SS_EINPUT,
                          "scheme %s: the volume axis weights sum to %.17g at n = %zu, "
                          "not 1",
                          name, sum, n);
    }
  }
  return SS_OK;
}

ss_status ss_scheme_points_new(const char *name, const ss_points *p, ss_scheme **out,
                               ss_error *err) {
  *out = NULL;
  const int hexes = p->split == SS_SPLIT_MULTILINEAR;
  if (!hexes && p->split != SS_SPLIT_TETOCT)
    return ss_error_set(err, SS_EINPUT,
                        "scheme %s: the points family takes the multilinear or the "
                        "tetoct split, not %s",
                        name, ss_split_name(p->split));
  const size_t NN = SS_AVG_NMAX + 1;
  double *tab = calloc(SS_PTS_PLACES * 16 * NN, sizeof *tab);
  if (!tab) return ss_error_nomem(err, "points weights");
  static const char *const places[] = {"volume", "surface", "crease"};
  static const char *const dims[] = {"vertex", "edge", "face", "cell"};
  for (int pl = 0; pl < SS_PTS_PLACES; pl++)
    for (int d = 0; d < 4; d++) {
      double *w = tab + (size_t)(pl * 4 + d) * 4 * NN;
      int given = 0;
      for (int kd = 0; kd < 4; kd++)
        given |= p->w[pl][d][kd] != NULL;
      for (size_t n = 1; n < NN; n++) {
        double sum = 0.0;
        for (int kd = 0; kd < 4; kd++) {
          const double v = given ? (p->w[pl][d][kd] ? p->w[pl][d][kd][n] : 0.0)
                                 : (kd == 0 ? 1.0 : 0.0);
          w[(size_t)kd * NN + n] = v;
          sum += v;
        }
        if (!(fabs(sum - 1.0) <= 1e-12)) {
          free(tab);
          return ss_error_set(err, SS_EINPUT,
                              "scheme %s: the %s %s weights sum to %.17g at n = %zu, "
                              "not 1",
                              name, places[pl], dims[d], sum, n);
        }
      }
    }
  double *axis = NULL;
  ss_status st = axis_table(name, p, &axis, err);
  unsigned accepts = (1u << SS_VERTEX) | (1u << SS_SEGMENT) |
                     (hexes ? (1u << SS_QUAD) | (1u << SS_HEX) : (1u << SS_TRIANGLE));
  if (!st) st = ss_scheme_alloc(name, p->split, accepts, points_rule, out, err);
  if (st) {
    free(tab);
    free(axis);
    return st;
  }
  (*out)->ptab = tab;
  (*out)->paxis = axis;
  (*out)->irrational = !p->rational;
  (*out)->irrational_volume = !p->rational_volume;
  return SS_OK;
}
