/* psi_case.h — what the psi tests share: a vertex case through the
 * pipeline's verdicts with psi judged, the two-ring's hexes as a limit
 * evaluator (another path to det Dpsi), a 3x3 determinant. */
#ifndef PSI_CASE_H
#define PSI_CASE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "ss_cx.h"
#include "ss_exact.h"
#include "ss_limit.h"
#include "ss_link.h"
#include "ss_pipeline.h"
#include "ss_scheme.h"

/* The pipeline of vertex case `link` under s through its verdicts with
 * options o; NULL (the reason printed) on failure. */
static inline ss_pipeline *psi_run_with(const ss_scheme *s, const char *link,
                                        const ss_pipeline_opts *o) {
  ss_link *l = NULL;
  ss_error err = {0};
  if (ss_link_named(link, &l, &err) && ss_link_parse(link, &l, &err)) {
    fprintf(stderr, "%s: %s\n", link, err.msg);
    return NULL;
  }
  const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  ss_pipeline *p = NULL;
  if (ss_pipeline_compute(s, &c, o, SS_PIPE_VERDICTS, NULL, &p, &err))
    fprintf(stderr, "%s: %s\n", link, err.msg);
  ss_link_free(l);
  return p;
}

/* The pipeline of vertex case `link` under s through its verdicts, psi
 * judged to box depth psi_depth, with the exact path if certify; NULL (the
 * reason printed) on failure. */
static inline ss_pipeline *psi_run(const ss_scheme *s, const char *link, int psi_depth,
                                   int certify) {
  ss_pipeline_opts o = ss_pipeline_defaults();
  o.psi_depth = psi_depth;
  o.certify = certify;
  return psi_run_with(s, link, &o);
}

/* The certified pipeline of vertex case `link`, psi judged to box depth 2,
 * its tubes proven if tubes (ss_pipeline_opts.psi_tubes); NULL (the reason
 * printed) on failure. */
static inline ss_pipeline *psi_run_tubes(const ss_scheme *s, const char *link,
                                         int tubes) {
  ss_pipeline_opts o = ss_pipeline_defaults();
  o.psi_depth = 2;
  o.certify = 1;
  o.psi_tubes = tubes;
  return psi_run_with(s, link, &o);
}

/* The two-ring's hexes of p's case with points x (n2 x 3) as a limit
 * evaluator under s; NULL (the reason printed) on failure. */
static inline ss_limit *psi_limit(const ss_scheme *s, const ss_pipeline *p,
                                  const double *x) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  ss_limit *L = NULL;
  if (ss_cx_new(3, &cx, &err)) return NULL;
  for (size_t i = 0; i < p->M->n2; i++)
    if (ss_cx_add_vertex(cx, x + 3 * i, 0, &err)) goto done;
  for (size_t c = 0; c < p->M->ncells; c++) {
    ss_idx v[8];
    for (int j = 0; j < 8; j++)
      v[j] = (ss_idx)p->M->corner[c * SS_MAXCELLVERTS + (size_t)j];
    if (ss_cx_add_cell(cx, SS_HEX, v, 0, &err)) goto done;
  }
  if (ss_limit_new(s, cx, &L, &err)) L = NULL;
done:
  if (!L) fprintf(stderr, "psi_limit: %s\n", err.msg);
  ss_cx_free(cx);
  return L;
}

static inline double psi_det3(double J[3][3]) {
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
         J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

/* The exact path's enclosure of p's basis, as rows (n2 x 3), column d times
 * g[d] (g NULL: 1; a diagonal basis change) and widened by delta, and its
 * midpoints. */
typedef struct {
  double *lo, *hi, *mid;
  size_t n;
} psi_encl;

/* 0, or -1 (the reason printed) if the basis is not enclosed. */
static inline int psi_encl_get(const ss_pipeline *p, double delta, const double *g,
                               psi_encl *e) {
  const size_t n = p->M->n2;
  double *bl = malloc(3 * n * sizeof *bl), *bh = malloc(3 * n * sizeof *bh);
  e->lo = malloc(3 * n * sizeof *e->lo);
  e->hi = malloc(3 * n * sizeof *e->hi);
  e->mid = malloc(3 * n * sizeof *e->mid);
  e->n = n;
  ss_error err = {0};
  int rc = ss_exact_basis(p->ex, bl, bh, &err) ? -1 : 0;
  for (size_t i = 0; i < n && !rc; i++)
    for (size_t d = 0; d < 3; d++) {
      const double f = g ? g[d] : 1.0, a = f * bl[d * n + i], b = f * bh[d * n + i];
      e->lo[3 * i + d] = (a < b ? a : b) - delta;
      e->hi[3 * i + d] = (a < b ? b : a) + delta;
      e->mid[3 * i + d] = 0.5 * e->lo[3 * i + d] + 0.5 * e->hi[3 * i + d];
    }
  free(bl);
  free(bh);
  if (rc) fprintf(stderr, "basis enclosure: %s\n", err.msg);
  return rc;
}

static inline void psi_encl_free(psi_encl *e) {
  free(e->lo);
  free(e->hi);
  free(e->mid);
}

/* Whether a box (depth, origin) of a cell around p, p at corner bits pbits,
 * lies in p's octant [0,1/2]^3: psi's ring leaves it out. */
static inline int psi_in_octant(unsigned pbits, int depth, const double o[3]) {
  if (depth < 1) return 0;
  const double h = ldexp(1.0, -depth);
  for (int a = 0; a < 3; a++) {
    const int hi = (int)((pbits >> a) & 1u);
    if (hi ? o[a] < 0.5 : o[a] + h > 0.5) return 0;
  }
  return 1;
}

/* The rule's weight as an exact rational, and enclosed (the exact path's
 * readers; arg: the long maxden). */
static inline int psi_exact_rat(double w, void *arg, long long *p, long long *q) {
  return ss_exact_rational(w, *(const long *)arg, p, q) ? 0 : -1;
}

static inline int psi_exact_weight(double w, void *arg, double *lo, double *hi) {
  return ss_exact_rational_enclose(w, *(const long *)arg, lo, hi) ? 0 : -1;
}

#endif
