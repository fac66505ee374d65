/* ss_psi_spoke.c — the spokes of a vertex case classified by the sign of
 * their coefficient det[a' | B] (method and classes: ss_psi_spoke.h). */
#include "ss_psi_spoke.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"
#include "ss_cx.h"
#include "ss_dense.h"
#include "ss_limit_edge.h"

const char *ss_psi_spoke_class_name(ss_psi_spoke_class c) {
  switch (c) {
  case SS_SPOKE_ONE_SIGN:
    return "one sign";
  case SS_SPOKE_SIGN_CHANGE:
    return "sign change";
  case SS_SPOKE_DEGENERATE:
    return "degenerate";
  }
  return "?";
}

void ss_psi_spokes_free(ss_psi_spokes *r) {
  if (!r) return;
  free(r->spoke);
  r->spoke = NULL;
  r->n = 0;
}

ss_status ss_psi_two_ring_limit(const ss_scheme *s, const ss_local *M, const double *x,
                                ss_limit **out, ss_error *err) {
  ss_cx *cx = NULL;
  ss_status st;
  *out = NULL;
  if ((st = ss_cx_new(3, &cx, err)) || (st = ss_cx_reserve_vertices(cx, M->n2, err)) ||
      (st = ss_cx_reserve_cells(cx, SS_HEX, M->ncells, err)))
    goto done;
  for (size_t i = 0; i < M->n2 && !st; i++)
    st = ss_cx_add_vertex(cx, x + 3 * i, 0, err);
  for (size_t c = 0; c < M->ncells && !st; c++) {
    ss_idx v[8];
    for (int j = 0; j < 8; j++)
      v[j] = (ss_idx)M->corner[c * SS_MAXCELLVERTS + (size_t)j];
    st = ss_cx_add_cell(cx, SS_HEX, v, 0, err);
  }
  if (!st) st = ss_limit_new(s, cx, out, err);
done:
  ss_cx_free(cx);
  return st;
}

/* p's corner (bits) in cell c, or -1 when p is not a corner. */
static int centre_bits(const ss_local *M, size_t c) {
  const int j = ss_local_centre_corner(M, c);
  return j < 0 ? -1 : (int)ss_cube_corner_bits(3, j);
}

/* The two-ring label at the far end of cell c's edge from p along axis a. */
static size_t far_end(const ss_local *M, size_t c, int pbits, int a) {
  const int j = ss_cube_corner_index(3, (unsigned)pbits ^ (1u << a));
  return M->corner[c * SS_MAXCELLVERTS + (size_t)j];
}

/* The link vertex of a spoke end's label (one coordinate), or -1. */
static int link_vertex(const ss_local *M, size_t q) {
  const ss_star_coord *l = &M->label[q];
  return l->n == 1 && l->val[0] > 0 ? (int)l->idx[0] : -1;
}

/* One sample: s at x0 on cell c's spoke along axis a, into sp. */
static ss_status sample(ss_limit *L, size_t c, int pbits, int a, double x0,
                        ss_psi_spoke *sp, ss_error *err) {
  double x[3], pr[3];
  const double h = ldexp(1.0, -SS_PSI_SPOKE_PROBE);
  for (int d = 0; d < 3; d++) {
    const int hi = (pbits >> d) & 1;
    x[d] = d == a ? (hi ? 1.0 - x0 : x0) : (double)hi;
    pr[d] = d == a ? x[d] : (hi ? 1.0 - h : h);
  }
  ss_limit_edge e;
  ss_limit_point lp;
  ss_status st;
  if ((st = ss_limit_edge_model(L, c, x, a, pr, &e, err)) ||
      (st = ss_limit_eval(L, c, pr[0], pr[1], pr[2], 1, &lp, err)))
    return st;
  ss_psi_spoke_sample smp;
  smp.cell = c;
  memcpy(smp.at, pr, sizeof smp.at);
  memcpy(smp.on, x, sizeof smp.on);
  smp.axis = a;
  smp.x0 = x0;
  smp.s = e.det;
  smp.rel = e.rel;
  smp.det_eval = ss_dense_det3(lp.jac[0], lp.jac[1], lp.jac[2]);
  const double mu = hypot(e.mu[0], e.mu[1]);
  sp->mu = mu;
  if (e.next / mu > sp->gap) sp->gap = e.next / mu;
  if (sp->nsamples == 0 || fabs(smp.s) < sp->smin) {
    sp->smin = fabs(smp.s);
    sp->min = smp;
  }
  if (fabs(smp.s) > sp->smax) sp->smax = fabs(smp.s);
  const double rd = fabs(smp.s - smp.det_eval) / fabs(smp.det_eval);
  if (!(rd <= sp->reldiff)) sp->reldiff = rd; /* NaN (det_eval 0) kept */
  if (sp->nsamples == 0 || smp.rel < sp->relmin) sp->relmin = smp.rel;
  sp->nsamples++;
  if (smp.rel < SS_PSI_SPOKE_DEGENERATE) {
    sp->ndegenerate++;
    return SS_OK;
  }
  if (smp.det_eval != 0.0 && (smp.s > 0.0) != (smp.det_eval > 0.0)) sp->ndisagree++;
  const int k = smp.s > 0.0 ? 0 : 1;
  if (!(sp->sign & (1 << k))) sp->w[k] = smp; /* sign: bits of the signs seen */
  sp->sign |= 1 << k;
  return SS_OK;
}

void ss_psi_spoke_classify(ss_psi_spoke *sp) {
  if (sp->nsamples == 0) {
    sp->cls = (ss_psi_spoke_class)-1;
    sp->sign = 0;
  } else if (sp->sign == 3) {
    sp->cls = SS_SPOKE_SIGN_CHANGE;
    sp->sign = 0;
  } else if (sp->ndegenerate > 0) {
    sp->cls = SS_SPOKE_DEGENERATE;
    sp->sign = 0;
  } else {
    sp->cls = SS_SPOKE_ONE_SIGN;
    sp->sign = sp->sign == 1 ? 1 : -1;
  }
}

/* The spokes' link vertices and valences: spoke[v] for link vertex v (the
 * cells round p holding its edge), into deg (k entries). */
static void valences(const ss_local *M, int k, int *deg) {
  memset(deg, 0, (size_t)k * sizeof *deg);
  for (size_t c = 0; c < M->ncells; c++) {
    const int pb = centre_bits(M, c);
    if (pb < 0) continue;
    for (int a = 0; a < 3; a++) {
      const int v = link_vertex(M, far_end(M, c, pb, a));
      if (v >= 0 && v < k) deg[v]++;
    }
  }
}

ss_status ss_psi_spokes_classify(ss_limit *L, const ss_local *M, ss_psi_spokes *out,
                                 ss_error *err) {
  memset(out, 0, sizeof *out);
  if (M->dim != 3 || M->cell != SS_HEX || M->ncoord < 1)
    return ss_error_set(err, SS_EINPUT, "spokes: not a hex vertex case");
  const double t0 = ss_clock_cpu();
  const int k = M->ncoord;
  int *deg = malloc((size_t)k * sizeof *deg);
  out->spoke = calloc((size_t)k + 1, sizeof *out->spoke);
  if (!deg || !out->spoke) {
    free(deg);
    ss_psi_spokes_free(out);
    return ss_error_nomem(err, "spokes");
  }
  valences(M, k, deg);
  ss_status st = SS_OK;
  for (int v = 0; v < k && !st; v++) {
    if (deg[v] == 0 || deg[v] == 4) continue;
    ss_psi_spoke *sp = &out->spoke[out->n++];
    sp->vertex = v;
    sp->valence = deg[v];
    for (size_t c = 0; c < M->ncells && !st; c++) {
      const int pb = centre_bits(M, c);
      for (int a = 0; pb >= 0 && a < 3 && !st; a++)
        if (link_vertex(M, far_end(M, c, pb, a)) == v)
          for (int i = 0; i < SS_PSI_SPOKE_SAMPLES && !st; i++)
            st = sample(L, c, pb, a, 0.5 + i / 16.0, sp, err);
    }
    if (st) break;
    ss_psi_spoke_classify(sp);
    out->none += sp->cls == SS_SPOKE_ONE_SIGN;
    out->nchange += sp->cls == SS_SPOKE_SIGN_CHANGE;
    out->ndegenerate += sp->cls == SS_SPOKE_DEGENERATE;
  }
  free(deg);
  if (st) ss_psi_spokes_free(out);
  out->seconds = ss_clock_cpu() - t0;
  return st;
}

ss_status ss_psi_spokes_of(const ss_scheme *s, const ss_local *M, const double *x,
                           ss_psi_spokes *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  if (M->dim != 3 || M->cell != SS_HEX)
    return ss_error_set(err, SS_EINPUT, "spokes: not a hex vertex case");
  ss_limit *L = NULL;
  ss_status st = ss_psi_two_ring_limit(s, M, x, &L, err);
  if (!st) st = ss_psi_spokes_classify(L, M, out, err);
  ss_limit_free(L);
  return st;
}

void ss_psi_spoke_name(int v, char name[16]) {
  if (v >= 0 && v < 26)
    snprintf(name, 16, "%c", 'a' + v);
  else
    snprintf(name, 16, "#%d", v + 1);
}
