/* ss_charmap.c — the characteristic map's control net and its regularity.
 * Method and verdicts: ss_charmap.h. */
#include "ss_charmap.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ss_charmap_free(ss_charmap *cm) {
  if (!cm) return;
  free(cm->x);
  free(cm->ctype);
  free(cm->corner);
  free(cm->jac);
  free(cm);
}

ss_status ss_charmap_new(const ss_local *M, const ss_eig *e, ss_charmap **out,
                         ss_error *err) {
  *out = NULL;
  if (!e->basis || e->n != M->n2 || e->m < 2 || e->m > 3)
    return ss_error_set(err, SS_EINPUT,
                        "no characteristic map: the eigenstructure has no subdominant "
                        "basis for this matrix");
  const int m = e->m;
  const size_t n = M->n2;
  ss_charmap *cm = calloc(1, sizeof *cm);
  if (!cm) return ss_error_nomem(err, "characteristic map");
  cm->dim = m;
  cm->n = n;
  cm->n1 = M->n1;
  cm->ncells = M->ncells;
  cm->x = malloc((n * (size_t)m + 1) * sizeof *cm->x);
  cm->ctype = malloc((M->ncells + 1) * sizeof *cm->ctype);
  cm->corner = malloc((M->ncells * SS_MAXCELLVERTS + 1) * sizeof *cm->corner);
  cm->jac = calloc(M->ncells + 1, sizeof *cm->jac);
  if (!cm->x || !cm->ctype || !cm->corner || !cm->jac) {
    ss_charmap_free(cm);
    return ss_error_nomem(err, "characteristic map");
  }
  /* scale: eigenvectors each to unit norm (each is unique up to scale and
   * sign); a Schur basis by one common factor, so that the map stays unique
   * up to a rotation (a different orthonormal basis of the same subspace) */
  const int eigvec = !strcmp(e->basis_kind, "eigenvectors");
  double norms[3], mean = 0.0;
  for (int j = 0; j < m; j++) {
    const double *col = e->basis + (size_t)j * n;
    norms[j] = 0.0;
    for (size_t i = 0; i < n; i++)
      norms[j] = hypot(norms[j], col[i]);
    if (!(norms[j] > 0.0)) {
      ss_charmap_free(cm);
      return ss_error_set(err, SS_ENUMERIC,
                          "no characteristic map: basis column %d vanishes", j + 1);
    }
    mean += norms[j] / m;
  }
  for (int j = 0; j < m; j++) {
    const double *col = e->basis + (size_t)j * n;
    const double scale = eigvec ? norms[j] : mean;
    for (size_t i = 0; i < n; i++)
      cm->x[i * (size_t)m + (size_t)j] = col[i] / scale;
    cm->lambda[j] = e->val[j + 1].re;
  }
  if (M->ncells) { /* a matrix given without its cells has none to copy */
    memcpy(cm->ctype, M->ctype, M->ncells * sizeof *cm->ctype);
    memcpy(cm->corner, M->corner, M->ncells * SS_MAXCELLVERTS * sizeof *cm->corner);
  }
  *out = cm;
  return SS_OK;
}

void ss_charmap_regularity(ss_charmap *cm, int maxdepth, ss_regularity *r) {
  memset(r, 0, sizeof *r);
  r->depth = maxdepth;
  r->worst_cell = SIZE_MAX;
  r->min_scaled_jacobian = NAN;
  size_t first_folded = SIZE_MAX, first_undecided = SIZE_MAX, first_pos = SIZE_MAX,
         first_neg = SIZE_MAX;
  for (size_t c = 0; c < cm->ncells; c++) {
    double x[SS_MAXCELLVERTS * 3];
    const ss_cell_type t = cm->ctype[c];
    const int nv = ss_cell_nverts(t);
    for (int j = 0; j < nv; j++)
      for (int d = 0; d < cm->dim; d++)
        x[j * cm->dim + d] =
            cm->x[cm->corner[c * SS_MAXCELLVERTS + (size_t)j] * (size_t)cm->dim +
                  (size_t)d];
    ss_jac_cell(t, x, cm->dim, maxdepth, cm->jac + c);
    switch (cm->jac[c].sign) {
    case SS_JAC_POSITIVE:
      if (r->npositive++ == 0) first_pos = c;
      break;
    case SS_JAC_NEGATIVE:
      if (r->nnegative++ == 0) first_neg = c;
      break;
    case SS_JAC_FOLDED:
      if (r->nfolded++ == 0) first_folded = c;
      break;
    default:
      if (r->nundecided++ == 0) first_undecided = c;
      break;
    }
  }
  ss_verdict *v = &r->verdict;
  if (cm->ncells == 0) {
    v->verdict = SS_UNDECIDED;
    snprintf(v->reason, sizeof v->reason, "the two-ring has no cells");
    return;
  }
  r->sign = r->nnegative > r->npositive ? -1 : 1;
  for (size_t c = 0; c < cm->ncells; c++) {
    /* the margin, oriented by the common sign.  A cell of one strict sign
     * opposite to it counts as minus its own quality (the smallest |corner
     * value|), not as its most negative corner: corner values of a tet reach
     * sqrt(2) in size, the quality never exceeds 1, so the measure stays in
     * [-1, 1] and a mirrored cell scores exactly the negative. */
    const ss_jac_result *j = cm->jac + c;
    const int opposite = (r->sign > 0 && j->sign == SS_JAC_NEGATIVE) ||
                         (r->sign < 0 && j->sign == SS_JAC_POSITIVE);
    const double s = opposite      ? (r->sign > 0 ? j->max_scaled : -j->min_scaled)
                     : r->sign > 0 ? j->min_scaled
                                   : -j->max_scaled;
    if (r->worst_cell == SIZE_MAX || s < r->min_scaled_jacobian) {
      r->min_scaled_jacobian = s;
      r->worst_cell = c;
    }
  }
  const char *sname = r->sign > 0 ? "positive" : "negative";
  if (r->nfolded) {
    const size_t c = first_folded;
    const ss_jac_result *j = cm->jac + c;
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason,
             "%s %zu of %zu folds: its Jacobian determinant vanishes or changes sign "
             "(near parameter (%.3g, %.3g, %.3g)); %zu folded cells",
             ss_cell_name(cm->ctype[c]), c, cm->ncells, j->where[0], j->where[1],
             j->where[2], r->nfolded);
    r->worst_cell = c;
  } else if (r->npositive && r->nnegative) {
    const size_t c = r->sign > 0 ? first_neg : first_pos;
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason,
             "cells of both orientations: %zu positive, %zu negative (e.g. %s %zu is "
             "%s, most are %s)",
             r->npositive, r->nnegative, ss_cell_name(cm->ctype[c]), c,
             r->sign > 0 ? "negative" : "positive", sname);
    r->worst_cell = c;
  } else if (r->nundecided) {
    const size_t c = first_undecided;
    v->verdict = SS_UNDECIDED;
    snprintf(v->reason, sizeof v->reason,
             "%s %zu: the Bernstein test is still in doubt at subdivision depth %d (%zu "
             "such cells)",
             ss_cell_name(cm->ctype[c]), c, maxdepth, r->nundecided);
    r->worst_cell = c;
  } else {
    v->verdict = SS_PASS;
    v->reason[0] = '\0';
  }
}

/* Whether the condition failed because a subdominant eigenvalue is complex. */
static int complex_subdominant(const ss_eig *e) {
  for (int i = 1; i <= e->m && (size_t)i < e->n; i++)
    if (fabs(e->val[i].im) > e->tol * hypot(e->val[i].re, e->val[i].im)) return 1;
  return 0;
}

ss_status ss_charmap_analyze(const ss_local *M, const ss_eig *e, int maxdepth,
                             ss_charmap **cm, ss_regularity *r, ss_error *err) {
  *cm = NULL;
  memset(r, 0, sizeof *r);
  r->depth = maxdepth;
  r->worst_cell = SIZE_MAX;
  r->min_scaled_jacobian = NAN;
  ss_verdict *v = &r->verdict;
  if (e->cond.verdict != SS_PASS || !e->basis) {
    if (complex_subdominant(e)) {
      v->verdict = SS_FAIL;
      snprintf(v->reason, sizeof v->reason,
               "complex subdominant eigenvalues: no characteristic map");
    } else {
      v->verdict = SS_UNDECIDED;
      snprintf(v->reason, sizeof v->reason,
               "no characteristic map: the eigenvalue condition fails");
    }
    return SS_OK;
  }
  if (e->defective) {
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason,
             "defective subdominant eigenvalues (a Jordan block among lambda1..%d, "
             "tolerance %.1e): no characteristic map",
             e->m, e->tol);
    return SS_OK;
  }
  ss_status st = ss_charmap_new(M, e, cm, err);
  if (st == SS_ENOMEM) return st;
  if (st) {
    v->verdict = SS_UNDECIDED;
    size_t len = strnlen(err->msg, sizeof v->reason - 1);
    memcpy(v->reason, err->msg, len); /* a long message is cut to fit */
    v->reason[len] = '\0';
    return SS_OK;
  }
  ss_charmap_regularity(*cm, maxdepth, r);
  return SS_OK;
}
