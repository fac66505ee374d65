/* ss_limit_edge.c — the leading terms of the limit near a point on an
 * extraordinary edge, from the stationary run's eigenvectors (method:
 * ss_limit_edge.h). */
#include "ss_clock.h"
#include "ss_limit_edge.h"

#include <complex.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_dense.h"
#include "ss_limit_impl.h"

#define EDGE_MAXSTEPS 60 /* plain steps before x must be a corner */

/* Where the walk to x's stationary run ends. */
typedef struct {
  size_t s;        /* the state whose child k is the stationary run */
  ss_lim_trans *t; /* that run */
  unsigned b;      /* corner bits of x (the run's fixed point) */
  double *P;       /* the state's patch points, relative to o */
  double o[3];     /* their origin */
  double M[3][3];  /* current-frame derivatives -> the cell's */
  ss_lim_pt pr;    /* the probe in the current frame */
  int af;          /* the edge's axis in the current frame */
  int steps;       /* plain steps walked */
} fixed_pt;

static ss_status check(const ss_limit *L, size_t cell, const double x[3], int axis,
                       const double probe[3], ss_error *err) {
  if (cell >= ss_limit_ncells(L))
    return ss_error_set(err, SS_EINPUT, "cell %zu does not exist", cell + 1);
  if (axis < 0 || axis > 2) return ss_error_set(err, SS_EINPUT, "axis %d", axis);
  for (int a = 0; a < 3; a++)
    if (!(x[a] >= 0.0 && x[a] <= 1.0 && probe[a] >= 0.0 && probe[a] <= 1.0))
      return ss_error_set(err, SS_EINPUT, "edge point or probe outside [0, 1]^3");
  for (int a = 0; a < 3; a++)
    if (a != axis && x[a] != 0.0 && x[a] != 1.0)
      return ss_error_set(err, SS_EINPUT,
                          "(%g, %g, %g) is not on an edge of the cell along axis %d",
                          x[0], x[1], x[2], axis);
  int off = 0;
  for (int a = 0; a < 3; a++)
    if (a != axis && probe[a] != x[a]) off = 1;
  if (probe[axis] != x[axis] || !off)
    return ss_error_set(err, SS_EINPUT,
                        "the probe must share the edge point's along-parameter and lie "
                        "off the edge");
  return SS_OK;
}

/* x framed as ss_limit_eval frames it (the cell's canonical frame). */
static ss_lim_pt framed(const ss_lim_frame *g0, const double x[3]) {
  ss_lim_pt pt = ss_lim_pt_make(x), q;
  for (int a = 0; a < 3; a++) {
    q.s[a] = pt.s[g0->perm[a]] ^ g0->flip[a];
    q.d[a] = pt.d[g0->perm[a]];
  }
  return q;
}

/* P <- W P (Kc x K, t's rows), relative to o (recentred on the first
 * point).  Over W's nonzeros only: a zero weight adds a zero, which changes
 * no sum (the sums start at +0, and +0 + -0 is +0). */
static ss_status step_points(const ss_lim_trans *t, size_t Kc, size_t K, double **P,
                             double o[3], ss_error *err) {
  ss_status st = ss_lim_trans_apply(t, Kc, K, 3, P, err);
  if (st) return st;
  double *Q = *P;
  const double c[3] = {Q[0], Q[1], Q[2]};
  for (size_t i = 0; i < Kc; i++)
    for (int d = 0; d < 3; d++)
      Q[i * 3 + (size_t)d] -= c[d];
  for (int d = 0; d < 3; d++)
    o[d] += c[d];
  return SS_OK;
}

/* Walk x and the probe together until x's next step is a stationary run
 * for ever; f->P is the caller's to free. */
static ss_status to_fixed(ss_limit *L, size_t cell, const double x[3],
                          const double probe[3], int axis, fixed_pt *f, ss_error *err) {
  ss_status st;
  memset(f, 0, sizeof *f);
  if ((st = ss_lim_cell_state(L, cell, err))) return st;
  const ss_lim_frame *g0 = &L->cell[cell].g;
  ss_lim_pt pt = framed(g0, x);
  f->pr = framed(g0, probe);
  double unused[3], Md[3][3];
  ss_lim_frame_apply(g0, x, unused, f->M);
  size_t s = L->cell[cell].state;
  const size_t K0 = L->st[s]->patch.nv;
  f->P = malloc((K0 * 3 + 1) * sizeof *f->P);
  if (!f->P) return ss_error_nomem(err, "patch points");
  for (size_t i = 0; i < K0; i++)
    memcpy(f->P + i * 3, L->mesh->x + (size_t)L->cell[cell].src[i] * 3, 3 * sizeof *f->P);
  for (f->steps = 0; f->steps <= EDGE_MAXSTEPS; f->steps++) {
    if (L->st[s]->patch.regular)
      return ss_error_set(err, SS_EINPUT,
                          "cell %zu (%g, %g, %g): a regular sub-cell after %d steps: not "
                          "on an extraordinary edge",
                          cell + 1, x[0], x[1], x[2], f->steps);
    const int k = ss_lim_child_of(&pt);
    ss_lim_trans *t;
    if ((st = ss_lim_transition(L, s, k, &t, err))) return st;
    const unsigned bk = ss_cube_corner_bits(3, k);
    if (t->next == s && ss_lim_frame_is_id(&t->g) && ss_lim_run_length(&pt, bk) < 0) {
      f->s = s;
      f->t = t;
      f->b = bk;
      for (int a = 0; a < 3; a++)
        if (f->M[a][axis] != 0.0) f->af = a;
      return SS_OK;
    }
    if (ss_lim_child_of(&f->pr) != k)
      return ss_error_set(err, SS_EINPUT,
                          "the probe leaves the edge point's sub-cell after %d steps: "
                          "take it closer to the edge",
                          f->steps);
    if ((st = step_points(t, L->st[t->next]->patch.nv, L->st[s]->patch.nv, &f->P, f->o,
                          err)))
      return st;
    ss_lim_advance(&pt, k, &t->g, f->M);
    ss_lim_advance(&f->pr, k, &t->g, Md);
    s = t->next;
  }
  return ss_error_set(err, SS_EINPUT,
                      "cell %zu (%g, %g, %g): no stationary run within %d steps: not a "
                      "dyadic point of an extraordinary edge",
                      cell + 1, x[0], x[1], x[2], EDGE_MAXSTEPS);
}

/* Limit of the net Q (K x 3, taken over) from state s at point y, in the
 * current frame (no jump by eq. (1)). */
static ss_status eval_net(ss_limit *L, size_t s, double *Q, ss_lim_pt y, int derivatives,
                          size_t cell, ss_limit_point *out, ss_error *err) {
  double o[3] = {0, 0, 0}, I3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  memset(out, 0, sizeof *out);
  ss_lim_res r = {3, out->p, &out->jac[0][0], 0, 0, NULL};
  ss_status st = ss_lim_walk(L, s, Q, o, 0, y, I3, derivatives, 1, cell, &r, err);
  out->steps = r.steps;
  out->products = r.products;
  return st;
}

struct ss_lim_chi {
  ss_lim_pt at;     /* the point, in the run's frame */
  ss_limit_point v; /* chi there (p[0], p[1]) with its derivatives */
};

static int same_pt(const ss_lim_pt *a, const ss_lim_pt *b) {
  for (int d = 0; d < 3; d++)
    if (a->s[d] != b->s[d] || a->d[d] != b->d[d]) return 0;
  return 1;
}

/* chi (the run's across pair: eigenvectors i and j of e, the run f->t's) at
 * the probe f->pr with its derivatives, into pc.  Its walk depends on the
 * run, the pair and the point alone, so the spokes' samples that reach the
 * same run at the same point (a cell's points of one depth along the edge,
 * and the cells of one patch) share one walk: kept with the run, and
 * copied, the same bits. */
static ss_status across(ss_limit *L, const fixed_pt *f, const ss_lim_eig *e, size_t i,
                        size_t j, size_t cell, ss_limit_point *pc, ss_error *err) {
  const size_t K = e->K;
  const int k = ss_cube_corner_index(3, f->b);
  ss_lim_trans *t;
  ss_status st = ss_lim_transition(L, f->s, k, &t, err);
  if (st) return st;
  for (size_t q = 0; q < t->nchi; q++)
    if (same_pt(&t->chi[q].at, &f->pr)) {
      *pc = t->chi[q].v;
      return SS_OK;
    }
  double *Qc = calloc(K * 3 + 1, sizeof *Qc);
  if (!Qc) return ss_error_nomem(err, "edge modes");
  for (size_t r = 0; r < K; r++) {
    Qc[r * 3 + 0] = e->V[i * K + r];
    Qc[r * 3 + 1] = e->V[j * K + r];
  }
  /* the run again after the walk, which may have computed transitions (a
   * run's own state is a child's patch, whose transitions stay) */
  if ((st = eval_net(L, f->s, Qc, f->pr, 1, cell, pc, err)) ||
      (st = ss_lim_transition(L, f->s, k, &t, err)))
    return st;
  const size_t n = t->nchi;
  if ((n & (n - 1)) == 0) { /* full at powers of 2 (0 included) */
    ss_lim_chi *c = realloc(t->chi, (n ? 2 * n : 4) * sizeof *c);
    if (!c) return SS_OK; /* a cache only: the value stands */
    t->chi = c;
  }
  t->chi[n].at = f->pr;
  t->chi[n].v = *pc;
  t->nchi = n + 1;
  return SS_OK;
}

/* The point b + e_af / 2 of the fixed point's cell (on the edge). */
static ss_lim_pt along_point(const fixed_pt *f) {
  ss_lim_pt y;
  for (int d = 0; d < 3; d++) {
    y.s[d] = (int)((f->b >> d) & 1u);
    y.d[d] = d == f->af ? 0.5 : 0.0;
  }
  return y;
}

/* The modes: the real eigenvalue-1/2 ones (flag 1 in half: the mode along
 * the edge, and any real 1/2 mode of the cross-section, which vanishes on the
 * edge and adds nothing to a' there, so that LAPACK's basis of a multiple 1/2
 * need not be split), the across pair (i, j), and the next modulus (1/2
 * itself when a cross-section mode has it). */
static ss_status pick_modes(const ss_lim_eig *e, unsigned char *half, size_t *pi,
                            size_t *pj, double *next, ss_error *err) {
  const size_t K = e->K;
  size_t nh = 0, i = SIZE_MAX, j = SIZE_MAX;
  double best = -1.0;
  for (size_t q = 0; q < K; q++) {
    half[q] = q != e->one && e->pair[q] == 0 && fabs(creal(e->lam[q]) - 0.5) <= 1e-8 &&
              fabs(cimag(e->lam[q])) <= 1e-8;
    nh += half[q];
    if (q == e->one || half[q] || e->pair[q] == 2) continue;
    if (cabs(e->lam[q]) > best) best = cabs(e->lam[q]), i = q;
  }
  if (nh == 0 || (nh > 1 && best < 0.5 + 1e-6))
    return ss_error_set(err, SS_ENUMERIC,
                        "the run at this edge point has %zu real eigenvalue-1/2 modes "
                        "and the largest other one is %.9g: the mode along the edge "
                        "cannot be told from the cross-section's",
                        nh, best);
  if (i == SIZE_MAX)
    return ss_error_set(err, SS_ENUMERIC, "the run has no mode across the edge");
  if (e->pair[i] == 1) {
    j = i + 1;
  } else {
    double b2 = -1.0;
    for (size_t q = 0; q < K; q++)
      if (q != e->one && !half[q] && q != i && e->pair[q] == 0 && cabs(e->lam[q]) > b2)
        b2 = cabs(e->lam[q]), j = q;
    if (j == SIZE_MAX || fabs(b2 - best) > 1e-6 * best)
      return ss_error_set(err, SS_ENUMERIC,
                          "the largest eigenvalue across the edge, %.9g, is not a "
                          "pair (next %.9g)",
                          best, b2);
  }
  *next = nh > 1 ? 0.5 : 0.0;
  for (size_t q = 0; q < K; q++)
    if (q != e->one && !half[q] && q != i && q != j && cabs(e->lam[q]) > *next)
      *next = cabs(e->lam[q]);
  if (*next > best * (1.0 - 1e-6))
    return ss_error_set(err, SS_ENUMERIC,
                        "the across eigenvalue %.9g is not a single pair (next %.9g)",
                        best, *next);
  *pi = i;
  *pj = j;
  return SS_OK;
}

/* The model from the run's modes at the fixed point f (coefficients C). */
static ss_status model(ss_limit *L, const fixed_pt *f, const ss_lim_eig *e,
                       const double *C, int axis, size_t cell, ss_limit_edge *out,
                       ss_error *err) {
  ss_status st;
  const size_t K = e->K;
  unsigned char *half = calloc(K + 1, 1);
  double *Qh = calloc(K * 3 + 1, sizeof *Qh);
  if (!half || !Qh) {
    free(half), free(Qh);
    return ss_error_nomem(err, "edge modes");
  }
  size_t i = 0, j = 0;
  if ((st = pick_modes(e, half, &i, &j, &out->next, err))) {
    free(half), free(Qh);
    return st;
  }
  out->mu[0] = creal(e->lam[i]);
  out->mu[1] = cimag(e->lam[i]);
  for (size_t q = 0; q < K; q++)
    if (half[q])
      for (size_t r = 0; r < K; r++)
        for (int d = 0; d < 3; d++)
          Qh[r * 3 + (size_t)d] += e->V[q * K + r] * C[q * 3 + (size_t)d];
  for (int d = 0; d < 3; d++) {
    out->B[d][0] = C[i * 3 + (size_t)d];
    out->B[d][1] = C[j * 3 + (size_t)d];
    out->a[d] = f->o[d] + e->V[e->one * K] * C[e->one * 3 + (size_t)d];
  }
  free(half);
  /* a' along the edge: 2 phi_h(b + e_af / 2), signed (ss_limit_walk's
   * fixed-point Jacobian) */
  ss_limit_point ph, pc;
  if ((st = eval_net(L, f->s, Qh, along_point(f), 0, cell, &ph, err)) ||
      (st = across(L, f, e, i, j, cell, &pc, err)))
    return st;
  const double sg = (f->b >> f->af) & 1u ? -2.0 : 2.0;
  double J[3][3];
  for (int r = 0; r < 3; r++)
    for (int d = 0; d < 3; d++)
      J[r][d] = r == f->af ? sg * ph.p[d]
                           : pc.jac[r][0] * out->B[d][0] + pc.jac[r][1] * out->B[d][1];
  out->chi_at[0] = pc.p[0];
  out->chi_at[1] = pc.p[1];
  /* to the cell's parameters: rows d/du_i = sum_a J[a] M[a][i] */
  for (int r = 0; r < 3; r++)
    for (int d = 0; d < 3; d++) {
      out->jac[r][d] = 0.0;
      for (int a = 0; a < 3; a++)
        out->jac[r][d] += J[a][d] * f->M[a][r];
    }
  out->det = ss_dense_det3(out->jac[0], out->jac[1], out->jac[2]);
  double h = 1.0;
  for (int r = 0; r < 3; r++)
    h *= sqrt(out->jac[r][0] * out->jac[r][0] + out->jac[r][1] * out->jac[r][1] +
              out->jac[r][2] * out->jac[r][2]);
  out->hadamard = h > 0.0 ? fabs(out->det) / h : 0.0;
  memcpy(out->da, out->jac[axis], sizeof out->da);
  const double b0[3] = {out->B[0][0], out->B[1][0], out->B[2][0]},
               b1[3] = {out->B[0][1], out->B[1][1], out->B[2][1]};
  out->det_coef = ss_dense_det3(out->da, b0, b1);
  double S = 0.0;
  for (size_t r = 0; r < K; r++) {
    const double *q = f->P + 3 * r;
    const double dq =
        sqrt((q[0] - f->P[0]) * (q[0] - f->P[0]) + (q[1] - f->P[1]) * (q[1] - f->P[1]) +
             (q[2] - f->P[2]) * (q[2] - f->P[2]));
    if (dq > S) S = dq;
  }
  /* a' is a derivative in the cell's parameter: about S 2^steps */
  const double ref = S * S * S * ldexp(1.0, f->steps);
  out->rel = ref > 0.0 ? fabs(out->det_coef) / ref : 0.0;
  return SS_OK;
}

ss_status ss_limit_edge_model(ss_limit *L, size_t cell, const double x[3], int axis,
                              const double probe[3], ss_limit_edge *out, ss_error *err) {
  ss_status st;
  memset(out, 0, sizeof *out);
  if ((st = check(L, cell, x, axis, probe, err))) return st;
  fixed_pt f;
  if ((st = to_fixed(L, cell, x, probe, axis, &f, err))) goto done;
  out->axis = axis;
  out->steps = f.steps;
  if (!f.t->eig) {
    double t0 = ss_clock_cpu();
    if ((st = ss_lim_eig_new(f.t->W, L->st[f.s]->patch.nv, &f.t->eig, err))) goto done;
    ss_clock_lap(&L->stats.eig_s, &t0);
    L->stats.eigs++;
  }
  const ss_lim_eig *e = f.t->eig;
  if (e->pw || e->one == SIZE_MAX) {
    st = ss_error_set(err, SS_ENUMERIC,
                      "cell %zu: the run at this edge point has no usable "
                      "eigenvectors: %s",
                      cell + 1, e->pw ? e->why : "the eigenvalue 1 is not simple");
    goto done;
  }
  double *C = malloc((e->K * 3 + 1) * sizeof *C);
  if (!C) {
    st = ss_error_nomem(err, "edge modes");
    goto done;
  }
  ss_lim_eig_coef(e, 3, f.P, C);
  st = model(L, &f, e, C, axis, cell, out, err);
  free(C);
done:
  free(f.P);
  return st;
}
