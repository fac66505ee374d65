/* ss_deform_eval.c — the deformed pattern: level by level through the
 * scheme's refinement, or exactly by the limit evaluator (ss_deform.h). */
#include <math.h>
#include <stdlib.h>

#include "ss_deform.h"
#include "ss_limit.h"

ss_status ss_deform_eval_levels(const ss_scheme *s, const ss_cx *mesh, int levels,
                                const ss_deform_loc *loc, size_t n, double (*val)[3],
                                ss_error *err) {
  const ss_split_kind kind = ss_scheme_split_kind(s);
  if (kind != SS_SPLIT_MULTILINEAR && kind != SS_SPLIT_TETOCT)
    return ss_error_set(err, SS_EINPUT,
                        "scheme %s splits by %s: deform follows points through the "
                        "multilinear and tet/oct splits only",
                        ss_scheme_name(s), ss_split_name(kind));
  if (levels < 1 || levels > 8)
    return ss_error_set(err, SS_EINPUT, "levels %d: expected 1..8", levels);
  for (size_t i = 0; i < n; i++)
    if (loc[i].cell >= mesh->nc[loc[i].type] ||
        (loc[i].type != SS_HEX && loc[i].type != SS_TET && loc[i].type != SS_OCT))
      return ss_error_set(err, SS_EINPUT, "point %zu names no volume cell of the mesh",
                          i + 1);
  ss_deform_loc *cur = malloc((n + 1) * sizeof *cur);
  ss_cx *coarse = NULL, *fine = NULL;
  ss_split *L = NULL;
  ss_status st = SS_OK;
  if (!cur) return ss_error_nomem(err, "tracked points");
  for (size_t i = 0; i < n; i++) {
    cur[i] = loc[i];
    ss_deform_interp(mesh, &cur[i], val[i]);
  }
  if ((st = ss_cx_copy(mesh, &coarse, err))) goto done;
  for (int l = 1; l <= levels; l++) {
    if ((st = ss_scheme_refine_split(s, coarse, &fine, NULL, &L, err))) goto done;
    for (size_t i = 0; i < n; i++) {
      if ((st = ss_deform_child(coarse, fine, L, &cur[i], &cur[i], err))) goto done;
      ss_deform_interp(fine, &cur[i], val[(size_t)l * n + i]);
    }
    ss_cx_free(coarse);
    ss_split_free(L);
    coarse = fine;
    fine = NULL;
    L = NULL;
  }
done:
  ss_cx_free(coarse);
  ss_cx_free(fine);
  ss_split_free(L);
  free(cur);
  return st;
}

ss_status ss_deform_eval_exact(const ss_scheme *s, const ss_cx *mesh,
                               const ss_deform_loc *loc, size_t n, double (*val)[3],
                               unsigned char *ok, ss_error *err) {
  for (size_t i = 0; i < n; i++)
    if (loc[i].type != SS_HEX)
      return ss_error_set(err, SS_EINPUT,
                          "point %zu is in a %s: the exact limit "
                          "evaluator takes hexahedra only",
                          i + 1, ss_cell_name(loc[i].type));
  ss_limit *Lm = NULL;
  ss_status st = ss_limit_new(s, mesh, &Lm, err);
  if (st) return st;
  int first = 1;
  for (size_t i = 0; i < n; i++) {
    ss_limit_point p;
    ss_error e1 = {0};
    ss_status si =
        ss_limit_eval(Lm, loc[i].cell, loc[i].r[0], loc[i].r[1], loc[i].r[2], 0, &p, &e1);
    if (si == SS_ENOMEM) {
      st = ss_error_nomem(err, "limit evaluation");
      break;
    }
    ok[i] = si == SS_OK;
    for (int a = 0; a < 3; a++)
      val[i][a] = si == SS_OK ? p.p[a] : (double)NAN;
    if (si != SS_OK && first && err) {
      *err = e1;
      first = 0;
    }
  }
  ss_limit_free(Lm);
  return st;
}

double ss_deform_estimate(const double (*q)[3], size_t stride, int levels, double *rate) {
  double g[2] = {0.0, 0.0};
  for (int j = 0; j < 2 && levels - j >= 1; j++) {
    const double *a = q[(size_t)(levels - j) * stride],
                 *b = q[(size_t)(levels - j - 1) * stride];
    g[j] = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
  }
  double lambda = 0.5;
  if (levels >= 2 && g[1] > 0.0) lambda = fmax(lambda, g[0] / g[1]);
  if (rate) *rate = lambda;
  if (lambda >= 1.0) return INFINITY;
  return g[0] * lambda / (1.0 - lambda);
}
