/* ss_scheme.c — the scheme registry and the refinement driver shared by all
 * schemes: split, run the rule into positions or into the operator. */
#include "ss_scheme.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_spblas.h>
#include <gsl/gsl_vector.h>

#include "ss_scheme_impl.h"

typedef struct {
  const char *name;
  ss_status (*make)(ss_scheme **, ss_error *);
} entry;

static const entry registry[] = {
    {"mlca", ss_scheme_mlca_new},
    {"tetoct", ss_scheme_tetoct_new},
    {"catmull-clark", ss_scheme_catmull_clark_new},
    {"loop", ss_scheme_loop_new},
    {"boxspline", ss_scheme_boxspline_new},
    {"boxspline-avg", ss_scheme_boxspline_avg_new},
};
#define NREG (sizeof registry / sizeof registry[0])

const char *const *ss_scheme_names(void) {
  static const char *const names[NREG + 1] = {
      "mlca", "tetoct", "catmull-clark", "loop", "boxspline", "boxspline-avg", NULL};
  return names;
}

ss_status ss_scheme_new(const char *name, ss_scheme **out, ss_error *err) {
  *out = NULL;
  for (size_t i = 0; i < NREG; i++)
    if (strcmp(name, registry[i].name) == 0) return registry[i].make(out, err);
  return ss_error_set(err, SS_EINPUT,
                      "unknown scheme '%s' (known: mlca, tetoct, catmull-clark, loop, "
                      "boxspline, boxspline-avg)",
                      name);
}

ss_status ss_scheme_alloc(const char *name, ss_split_kind split, unsigned accepts,
                          ss_rule_fn rule, ss_scheme **out, ss_error *err) {
  *out = NULL;
  ss_scheme *s = calloc(1, sizeof *s);
  if (!s) return ss_error_nomem(err, "scheme");
  snprintf(s->name, sizeof s->name, "%s", name);
  s->split = split;
  s->accepts = accepts;
  s->rule = rule;
  s->reach = 1;
  *out = s;
  return SS_OK;
}

void ss_scheme_free(ss_scheme *s) {
  free(s);
}

int ss_scheme_reach(const ss_scheme *s) {
  return s->reach;
}

int ss_scheme_reads_diagonals(const ss_scheme *s) {
  return s->diagonals;
}

const char *ss_scheme_name(const ss_scheme *s) {
  return s->name;
}

ss_split_kind ss_scheme_split_kind(const ss_scheme *s) {
  return s->split;
}

int ss_scheme_accepts(const ss_scheme *s, ss_cell_type t) {
  return (int)((s->accepts >> t) & 1u);
}

static ss_status check_types(const ss_scheme *s, const ss_cx *cx, ss_error *err) {
  char bad[200] = "", list[160] = "";
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    if (ss_scheme_accepts(s, (ss_cell_type)t)) {
      if (list[0]) strncat(list, ", ", sizeof list - strlen(list) - 1);
      strncat(list, ss_cell_plural((ss_cell_type)t), sizeof list - strlen(list) - 1);
    } else if (cx->nc[t]) {
      char one[64];
      snprintf(one, sizeof one, "%s%s (%zu)", bad[0] ? ", " : "",
               ss_cell_plural((ss_cell_type)t), cx->nc[t]);
      strncat(bad, one, sizeof bad - strlen(bad) - 1);
    }
  }
  if (bad[0])
    return ss_error_set(err, SS_EINPUT, "scheme %s does not take %s; it takes %s",
                        s->name, bad, list);
  return SS_OK;
}

/* Every row of a refinement operator is an affine combination. */
static ss_status check_rows(const ss_scheme *s, const gsl_spmatrix *R, ss_error *err) {
  for (size_t r = 0; r < R->size1; r++) {
    double sum = 0.0;
    for (int q = R->p[r]; q < R->p[r + 1]; q++)
      sum += R->data[q];
    if (!(fabs(sum - 1.0) <= 1e-12))
      return ss_error_set(err, SS_EINTERNAL,
                          "scheme %s: row %zu of the refinement operator sums to %.17g, "
                          "not 1",
                          s->name, r, sum);
  }
  return SS_OK;
}

ss_status ss_scheme_refine(const ss_scheme *s, const ss_cx *coarse, ss_cx **fine_out,
                           gsl_spmatrix **R_out, ss_error *err) {
  return ss_scheme_refine_split(s, coarse, fine_out, R_out, NULL, err);
}

ss_status ss_scheme_refine_split(const ss_scheme *s, const ss_cx *coarse,
                                 ss_cx **fine_out, gsl_spmatrix **R_out, ss_split **L_out,
                                 ss_error *err) {
  ss_cx *fine = NULL;
  ss_split *L = NULL;
  gsl_spmatrix *R = NULL;
  ss_triplets M = {0, 0, NULL, NULL, NULL};
  double *y = NULL;
  *fine_out = NULL;
  if (R_out) *R_out = NULL;
  if (L_out) *L_out = NULL;
  ss_status st = check_types(s, coarse, err);
  if (st) goto done;
  if (coarse->nv == 0) {
    st = ss_error_set(err, SS_EINPUT, "the mesh has no vertices");
    goto done;
  }
  if ((st = ss_split_refine(s->split, coarse, &fine, &L, err))) goto done;
  const size_t dim = (size_t)coarse->dim, nf = fine->nv;
  y = calloc(nf * dim + 1, sizeof *y);
  if (!y) {
    st = ss_error_nomem(err, "fine positions");
    goto done;
  }
  ss_sink k = {L, dim, fine->x, y, NULL, SS_OK};
  if (R_out) k.M = &M;
  if ((st = s->rule(s, coarse, fine, L, &k, err))) goto done;
  if (k.st) {
    st = ss_error_nomem(err, "refinement operator");
    goto done;
  }
  if (R_out) {
    if ((st = ss_triplets_csr(&M, nf, coarse->nv, &R, err))) goto done;
    ss_triplets_clear(&M);
    if ((st = check_rows(s, R, err))) goto done;
    for (size_t r = 0; r < dim; r++) {
      gsl_vector_const_view xv =
          gsl_vector_const_view_array_with_stride(coarse->x + r, dim, coarse->nv);
      gsl_vector_view yv = gsl_vector_view_array_with_stride(y + r, dim, nf);
      if (coarse->nv &&
          gsl_spblas_dgemv(CblasNoTrans, 1.0, R, &xv.vector, 0.0, &yv.vector) != 0) {
        st = ss_error_set(err, SS_ENUMERIC, "applying the refinement operator failed");
        goto done;
      }
    }
  }
  free(fine->x);
  fine->x = y;
  y = NULL;
done:
  free(y);
  ss_triplets_clear(&M);
  if (L_out && !st) {
    *L_out = L;
    L = NULL;
  }
  ss_split_free(L);
  if (st) {
    if (R) gsl_spmatrix_free(R);
    ss_cx_free(fine);
    R = NULL;
    fine = NULL;
  }
  if (R_out) *R_out = R;
  *fine_out = fine;
  return st;
}

ss_status ss_scheme_refine_levels(const ss_scheme *s, const ss_cx *coarse, int levels,
                                  ss_cx **fine_out, ss_error *err) {
  ss_cx *cur = NULL;
  *fine_out = NULL;
  if (levels < 0)
    return ss_error_set(err, SS_EINPUT, "number of levels %d is negative", levels);
  ss_status st = ss_cx_copy(coarse, &cur, err);
  for (int l = 0; l < levels && !st; l++) {
    ss_cx *next = NULL;
    st = ss_scheme_refine(s, cur, &next, NULL, err);
    ss_cx_free(cur);
    cur = next;
  }
  if (st) {
    ss_cx_free(cur);
    return st;
  }
  *fine_out = cur;
  return SS_OK;
}
