/* ss_scheme.c — the scheme registry (ss_scheme_new: a name to the
 * constructor of its scheme file, ss_scheme_<name>.c) and the refinement
 * driver shared by all schemes: split, run the rule into positions or into
 * the operator.  The scheme object the scheme files build (allocation,
 * accessors) lives below them, in ss_scheme_base.c. */
#include "ss_scheme.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
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
    {"ccsolid", ss_scheme_ccsolid_new},
    {"ccsolid-tensor", ss_scheme_ccsolid_tensor_new},
    {"quasi48", ss_scheme_quasi48_new},
};
#define NREG (sizeof registry / sizeof registry[0])

const char *const *ss_scheme_names(void) {
  static const char *const names[NREG + 1] = {
      "mlca",          "tetoct",  "catmull-clark",  "loop",    "boxspline",
      "boxspline-avg", "ccsolid", "ccsolid-tensor", "quasi48", NULL};
  return names;
}

ss_status ss_scheme_new(const char *name, ss_scheme **out, ss_error *err) {
  *out = NULL;
  for (size_t i = 0; i < NREG; i++)
    if (strcmp(name, registry[i].name) == 0) return registry[i].make(out, err);
  return ss_error_set(err, SS_EINPUT,
                      "unknown scheme '%s' (known: mlca, tetoct, catmull-clark, loop, "
                      "boxspline, boxspline-avg, ccsolid, ccsolid-tensor, quasi48)",
                      name);
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

/* Every row of a refinement operator is an affine combination (the rows r
 * with want[r]; want NULL: all): its sum is 1 to 1e-12, or, for a long row,
 * to the rounding bound of its sum, m eps sum|w| for m terms (a Catmull-Clark
 * vertex of valence 50000 has 100001 weights: its centre row sums to
 * 1 + 2.9e-12 in floating point). */
static ss_status check_rows(const ss_scheme *s, const gsl_spmatrix *R,
                            const unsigned char *want, ss_error *err) {
  for (size_t r = 0; r < R->size1; r++) {
    if (want && !want[r]) continue;
    double sum = 0.0, abs = 0.0;
    for (int q = R->p[r]; q < R->p[r + 1]; q++) {
      sum += R->data[q];
      abs += fabs(R->data[q]);
    }
    const double tol = fmax(1e-12, (double)(R->p[r + 1] - R->p[r]) * DBL_EPSILON * abs);
    if (!(fabs(sum - 1.0) <= tol))
      return ss_error_set(err, SS_EINTERNAL,
                          "scheme %s: row %zu of the refinement operator sums to %.17g, "
                          "not 1",
                          s->name, r, sum);
  }
  return SS_OK;
}

static int cmp_idx(const void *a, const void *b) {
  ss_idx x = *(const ss_idx *)a, y = *(const ss_idx *)b;
  return (x > y) - (x < y);
}

/* The first of nf vertices (dim coordinates each, in y) with a non-finite
 * coordinate, or nf if all are finite. */
static size_t first_nonfinite(const double *y, size_t nf, size_t dim) {
  for (size_t i = 0; i < nf * dim; i++)
    if (!isfinite(y[i])) return i / dim;
  return nf;
}

/* The first non-finite coordinate of vertex f. */
static double bad_value(const double *y, size_t f, size_t dim) {
  for (size_t r = 0; r < dim; r++)
    if (!isfinite(y[f * dim + r])) return y[f * dim + r];
  return 0.0;
}

static const char overflow_hint[] =
    "coordinates this close to DBL_MAX (1.8e+308) overflow when the scheme sums "
    "or averages them: scale the mesh down";

static ss_status refine(const ss_scheme *s, const ss_cx *coarse, ss_cx **fine_out,
                        gsl_spmatrix **R_out, ss_split **L_out, size_t *bad,
                        ss_error *err);

ss_status ss_scheme_refine(const ss_scheme *s, const ss_cx *coarse, ss_cx **fine_out,
                           gsl_spmatrix **R_out, ss_error *err) {
  return refine(s, coarse, fine_out, R_out, NULL, NULL, err);
}

ss_status ss_scheme_refine_split(const ss_scheme *s, const ss_cx *coarse,
                                 ss_cx **fine_out, gsl_spmatrix **R_out, ss_split **L_out,
                                 ss_error *err) {
  return refine(s, coarse, fine_out, R_out, L_out, NULL, err);
}

/* Parents of the composite of two splits, A (coarse -> mid) then B (mid ->
 * fine): a fine vertex keeps its parents in B when they are all coarse
 * vertices; a vertex of mid that is a coarse one is its own parent.  Every
 * vertex of fine must be the centroid of coarse vertices so: SS_EINTERNAL when
 * B names a vertex born in A as a parent (the composite would need weights). */
static ss_status compose_split(const ss_split *A, const ss_split *B, ss_split **out,
                               ss_error *err) {
  *out = NULL;
  ss_split *L = calloc(1, sizeof *L);
  if (!L) return ss_error_nomem(err, "composite split");
  L->ncoarse = A->ncoarse;
  L->nfine = B->nfine;
  L->ptr = malloc((B->nfine + 1) * sizeof *L->ptr);
  L->parent = malloc((B->ptr[B->nfine] + A->ptr[A->nfine] + 1) * sizeof *L->parent);
  if (!L->ptr || !L->parent) {
    ss_split_free(L);
    return ss_error_nomem(err, "composite split");
  }
  size_t q = 0;
  for (size_t f = 0; f < B->nfine; f++) {
    L->ptr[f] = q;
    if (f < A->nfine && f < B->ncoarse) { /* a vertex of mid: A's parents */
      for (size_t k = A->ptr[f]; k < A->ptr[f + 1]; k++)
        L->parent[q++] = A->parent[k];
      continue;
    }
    for (size_t k = B->ptr[f]; k < B->ptr[f + 1]; k++) {
      if (B->parent[k] >= A->ncoarse) {
        ss_split_free(L);
        return ss_error_set(err, SS_EINTERNAL,
                            "composite split: vertex %zu is born on an edge of a "
                            "vertex of the intermediate level",
                            f);
      }
      L->parent[q++] = B->parent[k];
    }
  }
  L->ptr[B->nfine] = q;
  *out = L;
  return SS_OK;
}

/* C = B A for CSR matrices (B: fine x mid, A: mid x coarse), row by row
 * (Gustavson, CSparse's cs_multiply): row f of C sums, for q in row f of B
 * and r in row q of A, B(f, q) A(q, r) in that order, written as it closes
 * (ss_rows).  SS_ENOMEM. */
static ss_status compose_operator(const gsl_spmatrix *B, const gsl_spmatrix *A,
                                  gsl_spmatrix **C, ss_error *err) {
  ss_rows rows;
  *C = NULL;
  ss_status st = ss_rows_init(&rows, B->size1, A->size2, B->p[B->size1], err);
  if (st) return st;
  ss_sink k = {NULL, 0, NULL, NULL, NULL, SS_OK, &rows, NULL};
  for (size_t f = 0; f < B->size1; f++)
    for (int q = B->p[f]; q < B->p[f + 1]; q++)
      for (int r = A->p[B->i[q]]; r < A->p[B->i[q] + 1]; r++)
        ss_sink_put(&k, f, (ss_idx)A->i[r], B->data[q] * A->data[r]);
  if (k.st) {
    ss_rows_clear(&rows);
    return ss_error_nomem(err, "composite operator");
  }
  return ss_rows_finish(&rows, C, err);
}

ss_status ss_scheme_refine_step(const ss_scheme *s, const ss_cx *coarse, ss_cx **fine_out,
                                gsl_spmatrix **R_out, ss_split **L_out, ss_error *err) {
  if (s->step_passes == 1 && s->step_split == s->split)
    return refine(s, coarse, fine_out, R_out, L_out, NULL, err);
  *fine_out = NULL;
  *R_out = NULL;
  *L_out = NULL;
  ss_scheme t = *s; /* the same rule on the step's (topological) split */
  t.split = s->step_split;
  t.adaptive = 0;                 /* a step is a whole 4-8 cycle */
  t.boundary = SS_BOUNDARY_FIXED; /* a patch's boundary is not the surface's */
  ss_cx *cx = NULL;
  gsl_spmatrix *R = NULL;
  ss_split *L = NULL;
  ss_status st = SS_OK;
  for (int pass = 0; pass < s->step_passes && !st; pass++) {
    ss_cx *f = NULL;
    gsl_spmatrix *Rp = NULL, *C = NULL;
    ss_split *Lp = NULL, *Lc = NULL;
    st = refine(&t, cx ? cx : coarse, &f, &Rp, &Lp, NULL, err);
    if (!st && R) { /* the step so far, then this pass */
      st = compose_operator(Rp, R, &C, err);
      if (!st) st = compose_split(L, Lp, &Lc, err);
      if (Rp) gsl_spmatrix_free(Rp);
      ss_split_free(Lp);
      Rp = C;
      Lp = Lc;
    }
    if (st) {
      ss_cx_free(f);
      if (Rp) gsl_spmatrix_free(Rp);
      ss_split_free(Lp);
      break;
    }
    if (R) gsl_spmatrix_free(R);
    ss_split_free(L);
    ss_cx_free(cx);
    R = Rp;
    L = Lp;
    cx = f;
  }
  if (st) {
    ss_cx_free(cx);
    if (R) gsl_spmatrix_free(R);
    ss_split_free(L);
    return st;
  }
  *fine_out = cx;
  *R_out = R;
  *L_out = L;
  return SS_OK;
}

ss_status ss_scheme_refine_at(const ss_scheme *s, const ss_cx *coarse, ss_cx **fine_out,
                              size_t *bad, ss_error *err) {
  return refine(s, coarse, fine_out, NULL, NULL, bad, err);
}

/* R from the rule over the split (fine, L) of coarse: rows f with want[f]
 * (want NULL: all) as the rule sends them, summed row by row (ss_rows) when
 * the rule sends its rows in order, else through triplets; the wanted rows
 * checked to sum to 1.  SS_ENOMEM, SS_EINTERNAL. */
static ss_status rule_operator(const ss_scheme *s, const ss_cx *coarse, const ss_cx *fine,
                               const ss_split *L, const unsigned char *want,
                               gsl_spmatrix **R_out, ss_error *err) {
  ss_triplets M = {0, 0, NULL, NULL, NULL};
  ss_rows rows;
  memset(&rows, 0, sizeof rows);
  gsl_spmatrix *R = NULL;
  const size_t nf = fine->nv;
  ss_status st = SS_OK;
  *R_out = NULL;
  ss_sink k = {L, (size_t)coarse->dim, NULL, NULL, NULL, SS_OK, NULL, want};
  if (s->rows_in_order) { /* up to 3^dim columns a row, fewer mostly */
    size_t est = nf * (size_t)(ss_cx_topdim(fine) == 3 ? 16 : 9);
    if ((st = ss_rows_init(&rows, nf, coarse->nv, est, err))) goto done;
    k.rows = &rows;
  } else { /* a cell sends about one entry per pair of its vertices */
    size_t est = nf;
    for (int t = 0; t < SS_NCELLTYPES; t++)
      est += fine->nc[t] *
             (size_t)(ss_cell_nverts((ss_cell_type)t) * ss_cell_nverts((ss_cell_type)t));
    if ((st = ss_triplets_reserve(&M, est, err))) goto done;
    k.M = &M;
  }
  if ((st = s->rule(s, coarse, fine, L, &k, err))) goto done;
  if (k.st == SS_EINTERNAL) {
    st = ss_error_set(err, SS_EINTERNAL,
                      "scheme %s: the rule sent a row of the refinement operator out of "
                      "order",
                      s->name);
    goto done;
  }
  if (k.st) {
    st = ss_error_nomem(err, "refinement operator");
    goto done;
  }
  if (k.rows)
    st = ss_rows_finish(&rows, &R, err);
  else
    st = ss_triplets_csr(&M, nf, coarse->nv, &R, err);
  if (!st) st = check_rows(s, R, want, err);
done:
  ss_triplets_clear(&M);
  ss_rows_clear(&rows);
  if (st && R) {
    gsl_spmatrix_free(R);
    R = NULL;
  }
  *R_out = R;
  return st;
}

int ss_scheme_step_is_one_split(const ss_scheme *s) {
  return s->step_passes == 1 && s->step_split == s->split;
}

ss_status ss_scheme_step_rows(const ss_scheme *s, const ss_cx *coarse, const ss_cx *fine,
                              const ss_split *L, const unsigned char *want,
                              gsl_spmatrix **R, ss_error *err) {
  *R = NULL;
  if (!ss_scheme_step_is_one_split(s))
    return ss_error_set(err, SS_EINTERNAL,
                        "scheme %s: its analysis step is not one split and the rule",
                        s->name);
  ss_status st = check_types(s, coarse, err);
  if (st) return st;
  return rule_operator(s, coarse, fine, L, want, R, err);
}

static ss_status refine(const ss_scheme *s, const ss_cx *coarse, ss_cx **fine_out,
                        gsl_spmatrix **R_out, ss_split **L_out, size_t *bad,
                        ss_error *err) {
  ss_cx *fine = NULL;
  ss_split *L = NULL;
  gsl_spmatrix *R = NULL;
  double *y = NULL;
  *fine_out = NULL;
  if (R_out) *R_out = NULL;
  if (L_out) *L_out = NULL;
  if (bad) *bad = SIZE_MAX;
  ss_status st = check_types(s, coarse, err);
  if (st) goto done;
  if (coarse->nv == 0) {
    st = ss_error_set(err, SS_EINPUT, "the mesh has no vertices");
    goto done;
  }
  if ((st = ss_split_refine_adapt(s->split, coarse, s->adaptive ? &s->adapt : NULL, &fine,
                                  &L, err)))
    goto done;
  const size_t dim = (size_t)coarse->dim, nf = fine->nv;
  y = calloc(nf * dim + 1, sizeof *y);
  if (!y) {
    st = ss_error_nomem(err, "fine positions");
    goto done;
  }
  if (R_out) {
    if ((st = rule_operator(s, coarse, fine, L, NULL, &R, err))) goto done;
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
  } else {
    ss_sink k = {L, dim, fine->x, y, NULL, SS_OK, NULL, NULL};
    if ((st = s->rule(s, coarse, fine, L, &k, err))) goto done;
  }
  /* Check results, not only input: finite coordinates can still overflow. */
  size_t f = first_nonfinite(y, nf, dim);
  if (f < nf) {
    /* in positions mode the rule read the split positions: an overflow there
     * (a centroid's sum) is where it began, and spread to f from it */
    size_t g = R_out ? nf : first_nonfinite(fine->x, nf, dim);
    if (g < nf) {
      f = g;
      memcpy(y + f * dim, fine->x + f * dim, dim * sizeof *y);
    }
    char par[128];
    ss_scheme_list_vertices(L->parent + L->ptr[f], ss_split_npar(L, f), par, sizeof par);
    st = ss_error_set(err, SS_EINPUT,
                      "refined vertex %zu has a non-finite coordinate (%g); it derives "
                      "from %s %s of the mesh refined; %s",
                      f + 1, bad_value(y, f, dim),
                      ss_split_npar(L, f) == 1 ? "vertex" : "vertices", par,
                      overflow_hint);
    if (bad) *bad = f;
    goto done;
  }
  free(fine->x);
  fine->x = y;
  y = NULL;
done:
  free(y);
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

ss_status ss_scheme_origin(const ss_scheme *s, const ss_cx *input, int levels, size_t f,
                           ss_idx *anc, size_t *n, ss_error *err) {
  ss_split **Ls = NULL;
  ss_cx *cur = NULL;
  ss_idx set[64], next[64];
  size_t ns = 0;
  int done_levels = 0;
  ss_status st = SS_OK;
  *n = 0;
  if (levels < 0)
    return ss_error_set(err, SS_EINPUT, "number of levels %d is negative", levels);
  Ls = calloc((size_t)levels + 1, sizeof *Ls);
  if (!Ls) return ss_error_nomem(err, "split history");
  const ss_cx *c = input;
  for (; done_levels < levels; done_levels++) {
    ss_cx *fine = NULL;
    if ((st = ss_split_refine(s->split, c, &fine, &Ls[done_levels], err))) goto done;
    ss_cx_free(cur);
    c = cur = fine;
  }
  if (f >= c->nv) {
    st = ss_error_set(err, SS_EINPUT, "vertex %zu is not in the refined complex (%zu)",
                      f + 1, c->nv);
    goto done;
  }
  set[ns++] = (ss_idx)f;
  for (int l = levels - 1; l >= 0; l--) {
    size_t nn = 0;
    const ss_split *L = Ls[l];
    for (size_t j = 0; j < ns; j++)
      for (size_t q = L->ptr[set[j]]; q < L->ptr[set[j] + 1]; q++) {
        size_t k = 0;
        while (k < nn && next[k] != L->parent[q])
          k++;
        if (k == nn && nn < sizeof next / sizeof next[0]) next[nn++] = L->parent[q];
      }
    memcpy(set, next, nn * sizeof *set);
    ns = nn;
  }
  qsort(set, ns, sizeof *set, cmp_idx);
  memcpy(anc, set, (ns < SS_MAXCELLVERTS ? ns : SS_MAXCELLVERTS) * sizeof *anc);
  *n = ns < SS_MAXCELLVERTS ? ns : SS_MAXCELLVERTS;
done:
  for (int l = 0; l < levels; l++)
    ss_split_free(Ls[l]);
  free(Ls);
  ss_cx_free(cur);
  return st;
}

ss_status ss_scheme_explain_nonfinite(const ss_scheme *s, const ss_cx *input, int level,
                                      size_t f, ss_error *err) {
  ss_idx anc[SS_MAXCELLVERTS];
  size_t n = 0;
  ss_error scratch = {0};
  if (ss_scheme_origin(s, input, level, f, anc, &n, &scratch) || n == 0)
    return ss_error_set(err, SS_EINPUT,
                        "level %d: refined vertex %zu has a non-finite coordinate; %s",
                        level, f + 1, overflow_hint);
  /* the input's largest coordinate, the likely cause */
  size_t big = 0;
  double bigx = 0.0;
  const size_t dim = (size_t)input->dim;
  for (size_t i = 0; i < input->nv * dim; i++)
    if (fabs(input->x[i]) > bigx) {
      bigx = fabs(input->x[i]);
      big = i / dim;
    }
  char list[128];
  ss_scheme_list_vertices(anc, n, list, sizeof list);
  return ss_error_set(err, SS_EINPUT,
                      "level %d: refined vertex %zu has a non-finite coordinate; it "
                      "derives from input %s %s (numbered as in the file); the "
                      "largest input coordinate is %.3g, at vertex %zu; %s",
                      level, f + 1, n == 1 ? "vertex" : "vertices", list, bigx, big + 1,
                      overflow_hint);
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
    size_t bad;
    st = ss_scheme_refine_at(s, cur, &next, &bad, err);
    ss_cx_free(cur);
    cur = next;
    if (st && bad != SIZE_MAX)
      st = ss_scheme_explain_nonfinite(s, coarse, l + 1, bad, err);
  }
  if (st) {
    ss_cx_free(cur);
    return st;
  }
  *fine_out = cur;
  return SS_OK;
}
