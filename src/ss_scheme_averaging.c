/* ss_scheme_averaging.c — the averaging family: a linear split followed by
 * weighted-centroid averaging, one mask per cell type (DESIGN section 3).
 *
 * For each fine vertex v let dim[v] be the lowest dimension of a cell holding it
 * and val[v] the number of such cells (MLCA paper, section 3.2: lower-dimensional
 * cells are creases).  Then
 *     v' = (1 / val[v]) * sum over cells C of dimension dim[v] holding v of
 *          sum over u in C of mask_C[role(v, u)] * u,
 * with u at its split position.  A vertex in no cell keeps its position. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_scheme_impl.h"

/* The rule row by row: fine vertex v's cells of dimension dim[v] in the order
 * (type, index), so that a sink can write R's rows in order (ss_rows); row
 * v's terms come in the same order as a pass over the cells would send them,
 * so positions and R are the same to the bit either way. */
static ss_status averaging_rule(const ss_scheme *s, const ss_cx *coarse,
                                const ss_cx *fine, const ss_split *L, ss_sink *k,
                                ss_error *err) {
  (void)coarse; /* the split complex and L say all this rule needs */
  const size_t nv = fine->nv;
  unsigned char *dimv = malloc(nv + 1);
  size_t *ptr = calloc(nv + 2, sizeof *ptr); /* v's cells: inc[ptr[v] .. ptr[v + 1]) */
  uint64_t *inc = NULL; /* cell index << 8 | type << 4 | v's place in the cell */
  size_t ninc = 0;
  ss_sink_cells cells[SS_NCELLTYPES];
  memset(cells, 0, sizeof cells);
  ss_loop_surface *surf = NULL; /* Loop's rows on the triangles (tetoct) */
  ss_status st = SS_OK;
  if (!dimv || !ptr) goto nomem;
  if (s->loop_surfaces && fine->nc[SS_TRIANGLE] &&
      (st = ss_loop_surface_new(fine, L, s->loop_c, &surf, err)))
    goto done;
  for (size_t v = 0; v < nv; v++)
    dimv[v] = 0xff;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    const unsigned char D = (unsigned char)ss_cell_dim((ss_cell_type)t);
    const size_t n = fine->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t);
    for (size_t i = 0; i < n; i++) {
      const ss_idx v = fine->cells[t][i];
      if (D < dimv[v]) dimv[v] = D;
    }
  }
  /* counting sort of the (vertex, cell) pairs by vertex, cells in order */
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    const unsigned char D = (unsigned char)ss_cell_dim((ss_cell_type)t);
    const size_t n = fine->nc[t] * (size_t)ss_cell_nverts((ss_cell_type)t);
    for (size_t i = 0; i < n; i++)
      if (dimv[fine->cells[t][i]] == D) ptr[fine->cells[t][i] + 2]++;
  }
  for (size_t v = 0; v < nv; v++)
    ptr[v + 2] += ptr[v + 1];
  ninc = ptr[nv + 1];
  if (!(inc = malloc((ninc + 1) * sizeof *inc))) goto nomem;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    const unsigned char D = (unsigned char)ss_cell_dim((ss_cell_type)t);
    const int n = ss_cell_nverts((ss_cell_type)t);
    for (size_t c = 0; c < fine->nc[t]; c++)
      for (int i = 0; i < n; i++) {
        const ss_idx v = fine->cells[t][c * (size_t)n + (size_t)i];
        if (dimv[v] == D)
          inc[ptr[v + 1]++] = (uint64_t)c << 8 | (uint64_t)t << 4 | (uint64_t)i;
      }
  }
  /* the weight row of each place in a cell; places with equal rows (all of
   * them for MLCA's uniform masks) share one address, which lets the sink
   * reuse a cell's sums (ss_sink_emit_cell) */
  double w[SS_NCELLTYPES][SS_MAXCELLVERTS][SS_MAXCELLVERTS];
  const double *wrow[SS_NCELLTYPES][SS_MAXCELLVERTS];
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    const ss_cell_type type = (ss_cell_type)t;
    const int n = ss_cell_nverts(type);
    for (int i = 0; fine->nc[t] && i < n; i++) {
      for (int j = 0; j < n; j++)
        w[t][i][j] = s->avg.mask[t][ss_cell_role(type, i, j)];
      wrow[t][i] = w[t][i];
      for (int e = 0; e < i; e++)
        if (!memcmp(w[t][e], w[t][i], (size_t)n * sizeof w[t][i][0])) {
          wrow[t][i] = w[t][e];
          break;
        }
    }
  }
  for (int t = 0; t < SS_NCELLTYPES; t++) /* each cell's parents merged once */
    if ((st = ss_sink_cells_prepare(k, ss_cell_nverts((ss_cell_type)t), fine->nc[t],
                                    fine->cells[t], cells + t, err)))
      goto done;
  for (size_t v = 0; v < nv; v++) {
    if (!ss_sink_wants(k, v)) continue;
    if (dimv[v] == 0xff) {
      ss_sink_emit(k, v, v, 1.0);
      continue;
    }
    if (surf && dimv[v] == 2 && ss_loop_surface_emit(surf, L, v, k)) continue;
    /* val[v], the number of those cells */
    const size_t val = ptr[v + 1] - ptr[v];
    const double scale = 1.0 / (double)val;
    for (size_t q = ptr[v]; q < ptr[v + 1]; q++) {
      const int t = (int)(inc[q] >> 4 & 0xf), i = (int)(inc[q] & 0xf);
      const double *row = wrow[t][i];
      if (s->vrow[t]) { /* valence-dependent weights: the row at val */
        if (val > SS_AVG_NMAX) {
          st = ss_error_set(err, SS_EINPUT,
                            "scheme %s: fine vertex %zu lies in %zu cells, beyond the "
                            "valences its weights are given for (1..%d)",
                            s->name, v + 1, val, SS_AVG_NMAX);
          goto done;
        }
        row = s->vrow[t][val * (size_t)ss_cell_nverts((ss_cell_type)t) + (size_t)i];
      }
      ss_sink_emit_cell(k, cells + t, (size_t)(inc[q] >> 8), v, row, scale);
    }
  }
  goto done;
nomem:
  st = ss_error_nomem(err, "averaging valences");
done:
  ss_loop_surface_free(surf);
  free(dimv);
  free(ptr);
  free(inc);
  for (int t = 0; t < SS_NCELLTYPES; t++)
    ss_sink_cells_clear(cells + t);
  return st;
}

/* Fill s's valence tables of type t from a and vary (vary->w[t] not all
 * NULL), checking each valence's sum: the rows of every place at every
 * valence, equal rows sharing the first one's address. */
static ss_status vary_tables(ss_scheme *s, ss_cell_type t, const ss_averaging *a,
                             const ss_averaging_vary *vary, ss_error *err) {
  const size_t nv = (size_t)ss_cell_nverts(t);
  double *tab = s->vtab[t] = malloc((SS_AVG_NMAX + 1) * nv * nv * sizeof *tab);
  const double **rows = s->vrow[t] = malloc((SS_AVG_NMAX + 1) * nv * sizeof *rows);
  if (!tab || !rows) return ss_error_nomem(err, "valence tables");
  for (size_t n = 0; n <= SS_AVG_NMAX; n++) {
    double sum = 0.0;
    for (size_t i = 0; i < nv; i++) {
      double *w = tab + (n * nv + i) * nv;
      for (size_t j = 0; j < nv; j++) {
        const int r = ss_cell_role(t, (int)i, (int)j);
        const double *vw = vary->w[t][r];
        w[j] = n == 0 ? 0.0 : vw ? vw[n] : a->mask[t][r];
        if (i == 0) sum += w[j];
      }
      rows[n * nv + i] = w;
      for (size_t e = 0; e < i; e++)
        if (!memcmp(rows[n * nv + e], w, nv * sizeof *w)) {
          rows[n * nv + i] = rows[n * nv + e];
          break;
        }
    }
    if (n > 0 && !(fabs(sum - 1.0) <= 1e-12))
      return ss_error_set(err, SS_EINPUT,
                          "scheme %s: the %s mask sums to %.17g over the cell's vertices "
                          "at valence n = %zu, not 1",
                          s->name, ss_cell_name(t), sum, n);
  }
  return SS_OK;
}

ss_status ss_scheme_averaging_vary_new(const char *name, const ss_averaging *a,
                                       const ss_averaging_vary *vary, ss_scheme **out,
                                       ss_error *err) {
  ss_status st = ss_scheme_averaging_new(name, a, out, err);
  if (st || !vary) return st;
  ss_scheme *s = *out;
  s->irrational = !vary->rational;
  for (int t = 0; t < SS_NCELLTYPES && !st; t++) {
    int varies = 0;
    for (int r = 0; r < 4; r++)
      varies |= vary->w[t][r] != NULL;
    if (varies && a->accepts[t]) st = vary_tables(s, (ss_cell_type)t, a, vary, err);
  }
  if (st) {
    ss_scheme_free(s);
    *out = NULL;
  }
  return st;
}

ss_status ss_scheme_averaging_new(const char *name, const ss_averaging *a,
                                  ss_scheme **out, ss_error *err) {
  *out = NULL;
  unsigned accepts = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (!a->accepts[t]) continue;
    const ss_cell_type type = (ss_cell_type)t;
    if (!ss_split_accepts(a->split, type))
      return ss_error_set(err, SS_EINPUT, "scheme %s: the %s split does not take %s",
                          name, ss_split_name(a->split), ss_cell_plural(type));
    double sum = 0.0;
    for (int j = 0; j < ss_cell_nverts(type); j++)
      sum += a->mask[t][ss_cell_role(type, 0, j)];
    if (!(fabs(sum - 1.0) <= 1e-12))
      return ss_error_set(
          err, SS_EINPUT,
          "scheme %s: the %s mask sums to %.17g over the cell's vertices, "
          "not 1",
          name, ss_cell_name(type), sum);
    accepts |= 1u << t;
  }
  ss_scheme *s = NULL;
  ss_status st = ss_scheme_alloc(name, a->split, accepts, averaging_rule, &s, err);
  if (st) return st;
  s->avg = *a;
  s->rows_in_order = 1;
  *out = s;
  return SS_OK;
}
