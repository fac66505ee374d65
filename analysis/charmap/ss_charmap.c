/* ss_charmap.c — the characteristic map's control net, normalised, and its
 * regularity judged on the ring.  Method and verdicts: ss_charmap.h. */
#include "ss_charmap.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>

#include "ss_clock.h"

ss_charmap_opts ss_charmap_defaults(void) {
  return (ss_charmap_opts){SS_JAC_DEPTH, 3, 0.5, NULL, 0, 0};
}

/* Forget the kept ring level (ss_charmap.h), freeing it. */
static void drop_ring(ss_charmap *cm) {
  free(cm->ring_x);
  free(cm->ring_ctype);
  free(cm->ring_corner);
  free(cm->ring_jac);
  cm->ring_x = NULL;
  cm->ring_ctype = NULL;
  cm->ring_corner = NULL;
  cm->ring_jac = NULL;
  cm->ring_n = cm->ring_ncells = 0;
  cm->ring_level = -1;
}

void ss_charmap_free(ss_charmap *cm) {
  if (!cm) return;
  free(cm->x);
  free(cm->ctype);
  free(cm->corner);
  free(cm->jac);
  drop_ring(cm);
  free(cm);
}

double ss_charmap_cell_measure(const ss_jac_result *j, int sign) {
  /* a cell of one strict sign opposite to the map's counts as minus its own
   * quality (the smallest |corner value|), so the measure stays in [-1, 1]
   * and a mirrored cell scores exactly the negative */
  if (j->sign == SS_JAC_DEGENERATE) return NAN; /* no sign, no margin */
  const int opposite = (sign > 0 && j->sign == SS_JAC_NEGATIVE) ||
                       (sign < 0 && j->sign == SS_JAC_POSITIVE);
  return opposite   ? (sign > 0 ? j->max_scaled : -j->min_scaled)
         : sign > 0 ? j->min_scaled
                    : -j->max_scaled;
}

/* Translate x (n points) to the centroid of the ring's points and map it by
 * C^(-1/2) (ss_charmap.h).  The ring's points: the corners of ring level 0's
 * cells, pushed from x; without a ring, the two-ring itself.  Returns 0, -1
 * out of memory, -2 if the points span less than dim dimensions. */
static int normalise(double *x, size_t n, int dim, const ss_local *M, double *centre) {
  double *pts = x;
  size_t np = n;
  unsigned char *use = NULL;
  double *net = NULL;
  int rc = -1;
  if (M->nring > 0) {
    const ss_local_ring *R = M->ring;
    net = malloc((R->nv * (size_t)dim + 1) * sizeof *net);
    use = calloc(R->nv + 1, 1);
    if (!net || !use) goto done;
    ss_local_ring_push(R, x, dim, net);
    for (size_t q = 0; q < R->ncells * SS_MAXCELLVERTS; q++)
      if (R->corner[q] != SIZE_MAX) use[R->corner[q]] = 1;
    pts = net;
    np = R->nv;
  }
  double mean[3] = {0, 0, 0}, C[9] = {0}, cnt = 0.0;
  for (size_t i = 0; i < np; i++) {
    if (use && !use[i]) continue;
    cnt += 1.0;
    for (int d = 0; d < dim; d++)
      mean[d] += pts[i * (size_t)dim + (size_t)d];
  }
  for (int d = 0; d < dim; d++)
    mean[d] /= cnt;
  for (size_t i = 0; i < np; i++) {
    if (use && !use[i]) continue;
    for (int a = 0; a < dim; a++)
      for (int b = 0; b < dim; b++)
        C[a * dim + b] += (pts[i * (size_t)dim + (size_t)a] - mean[a]) *
                          (pts[i * (size_t)dim + (size_t)b] - mean[b]) / cnt;
  }
  double mu[3];
  if (LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'V', 'U', dim, C, dim, mu)) goto done;
  if (!(mu[0] > 1e-14 * mu[dim - 1])) { /* ascending order */
    rc = -2;
    goto done;
  }
  double W[9]; /* V diag(mu^-1/2) V^T, symmetric */
  for (int a = 0; a < dim; a++)
    for (int b = 0; b < dim; b++) {
      double s = 0.0;
      for (int k = 0; k < dim; k++)
        s += C[a * dim + k] * C[b * dim + k] / sqrt(mu[k]);
      W[a * dim + b] = s;
    }
  for (int b = 0; b < dim; b++) {
    double c = 0.0;
    for (int a = 0; a < dim; a++)
      c -= mean[a] * W[a * dim + b];
    centre[b] = c;
  }
  for (size_t i = 0; i < n; i++) {
    double v[3];
    for (int d = 0; d < dim; d++)
      v[d] = x[i * (size_t)dim + (size_t)d] - mean[d];
    for (int b = 0; b < dim; b++) {
      double s = 0.0;
      for (int a = 0; a < dim; a++)
        s += v[a] * W[a * dim + b];
      x[i * (size_t)dim + (size_t)b] = s;
    }
  }
  rc = 0;
done:
  free(net);
  free(use);
  return rc;
}

ss_status ss_charmap_new(const ss_local *M, const ss_eig *e, ss_charmap **out,
                         ss_error *err) {
  *out = NULL;
  if (!e->basis || e->n != M->n2 || e->m < 2 || e->m > 3 || M->dim != e->m)
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
  cm->ring_level = -1;
  cm->ncells = M->ncells;
  cm->x = malloc((n * (size_t)m + 1) * sizeof *cm->x);
  cm->ctype = malloc((M->ncells + 1) * sizeof *cm->ctype);
  cm->corner = malloc((M->ncells * SS_MAXCELLVERTS + 1) * sizeof *cm->corner);
  cm->jac = calloc(M->ncells + 1, sizeof *cm->jac);
  if (!cm->x || !cm->ctype || !cm->corner || !cm->jac) {
    ss_charmap_free(cm);
    return ss_error_nomem(err, "characteristic map");
  }
  for (int j = 0; j < m; j++) {
    for (size_t i = 0; i < n; i++)
      cm->x[i * (size_t)m + (size_t)j] = e->basis[(size_t)j * n + i];
    cm->lambda[j] = e->val[j + 1].re;
  }
  const int rc = normalise(cm->x, n, m, M, cm->centre);
  if (rc) {
    ss_charmap_free(cm);
    return rc == -1 ? ss_error_nomem(err, "characteristic map")
                    : ss_error_set(err, SS_ENUMERIC,
                                   "no characteristic map: the subdominant basis spans "
                                   "less than %d dimensions on the ring",
                                   m);
  }
  if (M->ncells) { /* a matrix given without its cells has none to copy */
    memcpy(cm->ctype, M->ctype, M->ncells * sizeof *cm->ctype);
    memcpy(cm->corner, M->corner, M->ncells * SS_MAXCELLVERTS * sizeof *cm->corner);
  }
  *out = cm;
  return SS_OK;
}

/* Judge ncells cells of the net x (dim coordinates per point) into *L, each
 * cell's result into jac[c]. */
static void judge(size_t ncells, const ss_cell_type *ctype, const size_t *corner,
                  const double *x, int dim, int depth, ss_ring_level *L,
                  ss_jac_result *jac) {
  memset(L, 0, sizeof *L);
  L->cells = ncells;
  L->worst_cell = SIZE_MAX;
  L->min_scaled_jacobian = NAN;
  for (size_t c = 0; c < ncells; c++) {
    double y[SS_MAXCELLVERTS * 3];
    const int nv = ss_cell_nverts(ctype[c]);
    for (int j = 0; j < nv; j++)
      for (int d = 0; d < dim; d++)
        y[j * dim + d] =
            x[corner[c * SS_MAXCELLVERTS + (size_t)j] * (size_t)dim + (size_t)d];
    ss_jac_cell(ctype[c], y, dim, depth, jac + c);
    L->positive += jac[c].sign == SS_JAC_POSITIVE;
    L->negative += jac[c].sign == SS_JAC_NEGATIVE;
    L->folded += jac[c].sign == SS_JAC_FOLDED;
    L->undecided += jac[c].sign == SS_JAC_UNDECIDED;
    L->degenerate += jac[c].sign == SS_JAC_DEGENERATE;
  }
  L->sign = L->negative > L->positive ? -1 : 1;
  for (size_t c = 0; c < ncells; c++) {
    const ss_jac_result *j = jac + c;
    L->inverted += (L->sign > 0 && j->sign == SS_JAC_NEGATIVE) ||
                   (L->sign < 0 && j->sign == SS_JAC_POSITIVE);
    if (j->sign == SS_JAC_DEGENERATE) continue; /* no sign, no margin */
    const double s = ss_charmap_cell_measure(j, L->sign);
    if (L->worst_cell == SIZE_MAX || s < L->min_scaled_jacobian) {
      L->min_scaled_jacobian = s;
      L->worst_cell = c;
    }
  }
  L->bad_fraction = ncells ? (double)(L->folded + L->inverted) / (double)ncells : 0.0;
}

/* Whether a level's cells are all of one strict sign. */
static int clean(const ss_ring_level *L) {
  return L->cells > 0 && L->folded == 0 && L->inverted == 0 && L->undecided == 0 &&
         L->degenerate == 0;
}

/* Fill the summary fields of r from level l. */
static void take(ss_regularity *r, int l) {
  const ss_ring_level *L = r->level + l;
  r->ring_level = l;
  r->sign = L->sign;
  r->min_scaled_jacobian = L->min_scaled_jacobian;
  r->worst_cell = L->worst_cell;
  r->npositive = L->positive;
  r->nnegative = L->negative;
  r->nfolded = L->folded;
  r->nundecided = L->undecided;
  r->ndegenerate = L->degenerate;
  r->ninverted = L->inverted;
}

/* The verdict from the judged levels 0 .. r->nlevels - 1 (ss_charmap.h). */
static void decide(ss_regularity *r, int want) {
  ss_verdict *v = &r->verdict;
  v->reason[0] = '\0';
  for (int l = 0; l < r->nlevels; l++)
    if (clean(r->level + l)) {
      take(r, l);
      v->verdict = SS_PASS;
      return;
    }
  const int last = r->nlevels - 1;
  take(r, last);
  if (want > r->nlevels) r->want_levels = want;
  const ss_ring_level *L = r->level + last;
  if (L->folded + L->inverted == 0) {
    v->verdict = SS_UNDECIDED;
    if (L->undecided)
      snprintf(v->reason, sizeof v->reason,
               "ring level %d: %zu of %zu cells still in doubt at hex subdivision depth "
               "%d",
               last, L->undecided, L->cells, r->depth);
    else
      snprintf(v->reason, sizeof v->reason,
               "ring level %d: %zu of %zu cells flat to rounding (|det J| <= %.0e L^d): "
               "no sign in double precision",
               last, L->degenerate, L->cells, SS_JAC_FLAT);
    return;
  }
  char what[128];
  snprintf(what, sizeof what,
           "%zu of %zu cells folded, %zu inverted (min scaled Jacobian %.3g)", L->folded,
           L->cells, L->inverted, L->min_scaled_jacobian);
  if (last == 0) {
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason, "ring level 0: %s; one ring level judged",
             what);
    return;
  }
  const ss_ring_level *P = r->level + last - 1;
  const size_t was = P->folded + P->inverted;
  const double ratio =
      P->bad_fraction > 0.0 ? L->bad_fraction / P->bad_fraction : (double)INFINITY;
  v->verdict = ratio >= r->shrink ? SS_FAIL : SS_UNDECIDED;
  snprintf(v->reason, sizeof v->reason,
           "ring level %d: %s; %s under refinement (%zu bad cells on level %d: fraction "
           "ratio %.2f %s %.2f)%s",
           last, what, ratio >= r->shrink ? "the fold persists" : "shrinking", was,
           last - 1, ratio, ratio >= r->shrink ? ">=" : "<", r->shrink,
           ratio >= r->shrink ? "" : ": det J may vanish on a curve, not decided");
}

static void no_map(ss_regularity *r, const ss_charmap_opts *o) {
  memset(r, 0, sizeof *r);
  r->depth = o->depth;
  r->shrink = o->shrink;
  r->worst_cell = SIZE_MAX;
  r->ring_level = -1;
  r->min_scaled_jacobian = NAN;
}

static ss_status judge_levels(ss_charmap *cm, const ss_local *M, const ss_charmap_opts *o,
                              int first, ss_regularity *r, ss_error *err);

ss_status ss_charmap_regularity(ss_charmap *cm, const ss_local *M,
                                const ss_charmap_opts *o, ss_regularity *r,
                                ss_error *err) {
  no_map(r, o);
  const int dim = cm->dim;
  const int nl = M->nring < o->ring_levels ? M->nring : o->ring_levels;
  /* the two-ring's own cells, for pictures and the centre's count */
  ss_ring_level two;
  judge(cm->ncells, cm->ctype, cm->corner, cm->x, dim, o->depth, &two, cm->jac);
  if (nl < 1) {
    drop_ring(cm); /* no ring level: none is kept (not an earlier test's) */
    r->verdict.verdict = SS_UNDECIDED;
    snprintf(r->verdict.reason, sizeof r->verdict.reason,
             "the local matrix carries no ring to judge the map on");
    return SS_OK;
  }
  return judge_levels(cm, M, o, 0, r, err);
}

/* Judge ring levels first .. (while none is clean) of M, levels
 * 0 .. first - 1 already judged in r (their nets are pushed again: a deeper
 * ring numbers their points otherwise, its cells are the same); then the
 * verdict, the deciding level kept in cm and the centre's corners counted
 * (from cm->jac, judged). */
static ss_status judge_levels(ss_charmap *cm, const ss_local *M, const ss_charmap_opts *o,
                              int first, ss_regularity *r, ss_error *err) {
  const int dim = cm->dim;
  const int nl = M->nring < o->ring_levels ? M->nring : o->ring_levels;
  double *prev = cm->x, *net = NULL;
  ss_jac_result *jac = NULL;
  for (int l = 0; l < nl; l++) {
    const ss_local_ring *R = M->ring + l;
    free(jac);
    net = malloc((R->nv * (size_t)dim + 1) * sizeof *net);
    jac = malloc((R->ncells + 1) * sizeof *jac);
    if (!net || !jac) {
      if (prev != cm->x) free(prev);
      free(net);
      free(jac);
      return ss_error_nomem(err, "ring net");
    }
    ss_local_ring_push(R, prev, dim, net);
    if (prev != cm->x) free(prev);
    prev = net;
    if (l < first) continue; /* judged before: the same cells, the same net */
    judge(R->ncells, R->ctype, R->corner, net, dim, o->depth, r->level + l, jac);
    r->nlevels = l + 1;
    if (clean(r->level + l)) break;
  }
  r->want_levels = 0;
  r->centre_corner_folds = 0;
  decide(r, o->ring_levels);
  /* keep the deciding level (the last judged: the loop stops at a clean one)
   * for pictures and files, replacing an earlier test's */
  const ss_local_ring *R = M->ring + r->nlevels - 1;
  drop_ring(cm);
  cm->ring_x = net;
  cm->ring_jac = jac;
  cm->ring_level = r->nlevels - 1;
  cm->ring_n = R->nv;
  cm->ring_ncells = R->ncells;
  cm->ring_ctype = malloc((R->ncells + 1) * sizeof *cm->ring_ctype);
  cm->ring_corner = malloc((R->ncells * SS_MAXCELLVERTS + 1) * sizeof *cm->ring_corner);
  if (!cm->ring_ctype || !cm->ring_corner) {
    drop_ring(cm);
    return ss_error_nomem(err, "ring cells");
  }
  if (R->ncells) {
    memcpy(cm->ring_ctype, R->ctype, R->ncells * sizeof *cm->ring_ctype);
    memcpy(cm->ring_corner, R->corner,
           R->ncells * SS_MAXCELLVERTS * sizeof *cm->ring_corner);
  }
  for (size_t c = 0; c < cm->ncells; c++) {
    int centre = 0;
    for (int j = 0; j < SS_MAXCELLVERTS && !centre; j++)
      centre = cm->corner[c * SS_MAXCELLVERTS + (size_t)j] == 0;
    const ss_jac_sign want = r->sign < 0 ? SS_JAC_NEGATIVE : SS_JAC_POSITIVE;
    r->centre_corner_folds += centre && cm->jac[c].sign != want;
  }
  return SS_OK;
}

/* Whether the condition failed because a subdominant eigenvalue is complex. */
static int complex_subdominant(const ss_eig *e) {
  for (int i = 1; i <= e->m && (size_t)i < e->n; i++)
    if (fabs(e->val[i].im) > e->tol * hypot(e->val[i].re, e->val[i].im)) return 1;
  return 0;
}

ss_status ss_charmap_analyze(const ss_local *M, const ss_eig *e, const ss_charmap_opts *o,
                             ss_charmap **cm, ss_regularity *r, ss_error *err) {
  *cm = NULL;
  no_map(r, o);
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
  double t0 = o->times ? ss_clock_cpu() : 0.0;
  ss_status st = ss_charmap_new(M, e, cm, err);
  if (o->times) ss_clock_lap(&o->times->map, &t0);
  if (st == SS_ENOMEM) return st;
  if (st) {
    v->verdict = SS_UNDECIDED;
    size_t len = strnlen(err->msg, sizeof v->reason - 1);
    memcpy(v->reason, err->msg, len); /* a long message is cut to fit */
    v->reason[len] = '\0';
    return SS_OK;
  }
  st = ss_charmap_regularity(*cm, M, o, r, err);
  if (o->times) ss_clock_lap(&o->times->jacobian, &t0);
  return st;
}

ss_status ss_charmap_judge(const ss_scheme *s, const ss_case *c, ss_local *M,
                           const ss_eig *e, const ss_charmap_opts *o, ss_charmap **cm,
                           ss_regularity *r, ss_error *err) {
  ss_status st = ss_charmap_analyze(M, e, o, cm, r, err);
  if (st || !*cm) return st;
  if (r->want_levels > M->nring) {
    /* the levels judged stay as they were (the deeper ring's first levels
     * hold the same cells, ss_local_ring_deepen): judge only the new ones */
    int more = r->nlevels >= 1;
    double t0 = o->times ? ss_clock_cpu() : 0.0;
    if (o->times) o->times->deep++;
    if ((st = ss_local_ring_deepen(s, c, r->want_levels, M, err))) return st;
    if (o->times) ss_clock_lap(&o->times->deepen, &t0);
    more = more && (M->nring < o->ring_levels ? M->nring : o->ring_levels) > r->nlevels;
    st = more ? judge_levels(*cm, M, o, r->nlevels, r, err)
              : ss_charmap_regularity(*cm, M, o, r, err);
    if (o->times) ss_clock_lap(&o->times->deep_jac, &t0);
    if (st) return st;
  }
  double t1 = o->times ? ss_clock_cpu() : 0.0;
  st = ss_charmap_symmetry(*cm, M, c, &r->sym, err);
  if (o->times) ss_clock_lap(&o->times->symmetry, &t1);
  if (st) return st;
  if (r->sym.found) {
    char ring[sizeof r->verdict.reason];
    snprintf(ring, sizeof ring, "%s%s%.400s", ss_verdict_name(r->verdict.verdict),
             r->verdict.reason[0] ? ": " : "", r->verdict.reason);
    r->verdict.verdict = SS_FAIL;
    snprintf(r->verdict.reason, sizeof r->verdict.reason,
             "psi o sigma = psi for %s, of order %d (||M_sigma - I|| = %.1e, gap %.2f): "
             "det Dpsi %s; the ring alone: %.200s",
             r->sym.what, r->sym.order, r->sym.distance, r->sym.gap,
             r->sym.reverses ? "changes sign under sigma"
                             : "vanishes on sigma's fixed rays",
             ring);
  }
  return SS_OK;
}
