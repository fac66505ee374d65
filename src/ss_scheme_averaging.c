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
#include <stdlib.h>

#include "ss_scheme_impl.h"

static ss_status averaging_rule(const ss_scheme *s, const ss_cx *coarse,
                                const ss_cx *fine, const ss_split *L, ss_sink *k,
                                ss_error *err) {
  (void)coarse; /* the split complex and L say all this rule needs */
  (void)L;
  const size_t nv = fine->nv;
  unsigned char *dimv = malloc(nv + 1);
  uint32_t *val = calloc(nv + 1, sizeof *val);
  if (!dimv || !val) {
    free(dimv);
    free(val);
    return ss_error_nomem(err, "averaging valences");
  }
  for (size_t v = 0; v < nv; v++)
    dimv[v] = 0xff;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    const unsigned char D = (unsigned char)ss_cell_dim((ss_cell_type)t);
    const int n = ss_cell_nverts((ss_cell_type)t);
    const ss_idx *c = fine->cells[t];
    for (size_t i = 0; i < fine->nc[t] * (size_t)n; i++) {
      ss_idx v = c[i];
      if (D < dimv[v]) {
        dimv[v] = D;
        val[v] = 1;
      } else if (D == dimv[v]) {
        val[v]++;
      }
    }
  }
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (!fine->nc[t]) continue;
    const ss_cell_type type = (ss_cell_type)t;
    const unsigned char D = (unsigned char)ss_cell_dim(type);
    const int n = ss_cell_nverts(type);
    double w[SS_MAXCELLVERTS][SS_MAXCELLVERTS];
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++)
        w[i][j] = s->avg.mask[t][ss_cell_role(type, i, j)];
    for (size_t c = 0; c < fine->nc[t]; c++) {
      const ss_idx *cv = ss_cx_cell(fine, type, c);
      ss_sink_cell sc; /* the cell's parents merged once for its n rows */
      ss_sink_cell_prepare(k, n, cv, &sc);
      for (int i = 0; i < n; i++) {
        const ss_idx v = cv[i];
        if (dimv[v] != D) continue;
        ss_sink_emit_cell(k, &sc, v, w[i], 1.0 / (double)val[v]);
      }
    }
  }
  for (size_t v = 0; v < nv; v++)
    if (dimv[v] == 0xff) ss_sink_emit(k, v, v, 1.0);
  free(dimv);
  free(val);
  return SS_OK;
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
  *out = s;
  return SS_OK;
}
