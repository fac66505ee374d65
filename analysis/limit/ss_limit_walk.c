/* ss_limit_walk.c — limit evaluation at a point: the cached walk with
 * eigen-jumps over stationary runs and eq. (1) along extraordinary edges,
 * the Jacobian at a fixed point, and the reference by repeated local
 * subdivision (method in ss_limit.h). */
#include "ss_limit.h"

#include <complex.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit_impl.h"

/* Runs shorter than this are walked step by step: a jump costs about two
 * plain steps (V^-1 P and V y, complex), so it pays from three steps on. */
#define JUMP_MIN 3

static ss_status check_args(const ss_limit *L, size_t cell, const double x[3],
                            ss_error *err) {
  if (cell >= L->mesh->nc[SS_HEX])
    return ss_error_set(err, SS_EINPUT,
                        "cell %zu does not exist (the mesh has %zu cells)", cell + 1,
                        L->mesh->nc[SS_HEX]);
  static const char *const name[3] = {"u", "v", "w"};
  for (int a = 0; a < 3; a++)
    if (!(x[a] >= 0.0 && x[a] <= 1.0))
      return ss_error_set(err, SS_EINPUT, "parameter %s = %.17g is outside [0, 1]",
                          name[a], x[a]);
  return SS_OK;
}

static void pt_normalize(ss_lim_pt *p) {
  for (int a = 0; a < 3; a++)
    if (p->d[a] > 0.5) {
      p->s[a] ^= 1;
      p->d[a] = 1.0 - p->d[a]; /* exact: Sterbenz */
    }
}

ss_lim_pt ss_lim_pt_make(const double x[3]) {
  ss_lim_pt p;
  for (int a = 0; a < 3; a++) {
    p.s[a] = 0;
    p.d[a] = x[a];
  }
  pt_normalize(&p);
  return p;
}

static void pt_x(const ss_lim_pt *p, double x[3]) {
  for (int a = 0; a < 3; a++)
    x[a] = p->s[a] ? 1.0 - p->d[a] : p->d[a];
}

/* The child holding the point: bit a set iff x_a >= 1/2. */
int ss_lim_child_of(const ss_lim_pt *p) {
  unsigned b = 0;
  for (int a = 0; a < 3; a++)
    if (p->s[a] || p->d[a] == 0.5) b |= 1u << a;
  return ss_cube_corner_index(3, b);
}

/* How many consecutive steps from p go into child bits b (-1: for ever);
 * exact, from the binary exponents of the distances to that corner. */
long ss_lim_run_length(const ss_lim_pt *p, unsigned b) {
  long m = -1;
  for (int a = 0; a < 3; a++) {
    int bit = (int)((b >> a) & 1u), e;
    double dist = p->s[a] == bit ? p->d[a] : 1.0 - p->d[a];
    if (dist == 0.0) continue;
    double f = frexp(dist, &e);
    long ma = bit && f == 0.5 ? 1L - e : -(long)e;
    if (m < 0 || ma < m) m = ma;
  }
  return m;
}

/* m steps into child bits b: the distance to that corner times 2^m. */
static void pt_jump(ss_lim_pt *p, unsigned b, long m) {
  for (int a = 0; a < 3; a++) {
    int bit = (int)((b >> a) & 1u);
    double dist = p->s[a] == bit ? p->d[a] : 1.0 - p->d[a];
    p->s[a] = bit;
    p->d[a] = ldexp(dist, (int)m);
  }
  pt_normalize(p);
}

/* One step into child k, then frame g; M <- G 2 M. */
void ss_lim_advance(ss_lim_pt *p, int k, const ss_lim_frame *g, double M[3][3]) {
  pt_jump(p, ss_cube_corner_bits(3, k), 1);
  ss_lim_pt q;
  double G[3][3], N[3][3];
  for (int a = 0; a < 3; a++) {
    q.s[a] = p->s[g->perm[a]] ^ g->flip[a];
    q.d[a] = p->d[g->perm[a]];
  }
  *p = q;
  double zero[3] = {0, 0, 0}, unused[3];
  ss_lim_frame_apply(g, zero, unused, G);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      N[i][j] = 0.0;
      for (int r = 0; r < 3; r++)
        N[i][j] += 2.0 * G[i][r] * M[r][j];
    }
  memcpy(M, N, sizeof N);
}

/* Point and Jacobian from a regular patch's points P (patch numbering). */
static void finish_regular(const ss_lim_patch *p, const double *P, const ss_lim_pt *pt,
                           double M[3][3], int derivatives, ss_limit_point *out) {
  double net[64][3], J[3][3], x[3];
  pt_x(pt, x);
  for (int i = 0; i < 64; i++)
    memcpy(net[i], P + (size_t)p->net[i] * 3, sizeof net[i]);
  ss_limit_bspline((const double(*)[3])net, x[0], x[1], x[2], out->p, J);
  if (derivatives)
    for (int i = 0; i < 3; i++)
      for (int d = 0; d < 3; d++) {
        out->jac[i][d] = 0.0;
        for (int a = 0; a < 3; a++)
          out->jac[i][d] += J[a][d] * M[a][i];
      }
}

/* P <- W P (Kc x K times K x 3) into a new buffer. */
static ss_status apply(const double *W, size_t Kc, size_t K, double **P, ss_error *err) {
  double *Q = calloc(Kc * 3 + 1, sizeof *Q);
  if (!Q) return ss_error_nomem(err, "patch points");
  for (size_t i = 0; i < Kc; i++)
    for (size_t j = 0; j < K; j++) {
      double w = W[i * K + j];
      if (w == 0.0) continue;
      for (int d = 0; d < 3; d++)
        Q[i * 3 + (size_t)d] += w * (*P)[j * 3 + (size_t)d];
    }
  free(*P);
  *P = Q;
  return SS_OK;
}

static ss_status not_reached(const ss_limit *L, size_t cell, int steps, ss_error *err) {
  return ss_error_set(
      err, SS_EINPUT,
      "cell %zu: no regular sub-cell after %d subdivision steps: the point "
      "lies on (or within about 2^-%d of) the mesh boundary, and limit "
      "points of the boundary surface are not supported yet",
      cell + 1, steps, steps);
  (void)L;
}

/* The Jacobian at a fixed point: corner b (bits) of state s, whose run
 * matrix has eigen-decomposition e, patch points P.  With P = sum_i v_i c_i^T
 * and phi_i the limit of the net v_i, phi_i(b + (y - b)/2) = lambda_i
 * phi_i(y): a component with |lambda| < 1/2 has derivative 0 at b, one with
 * lambda = 1/2 (real, not defective) is homogeneous of degree 1 along rays,
 * so its derivative along axis a is 2 phi_i(b moved 1/2 along a), signed;
 * any other component with |lambda| >= 1/2 makes the Jacobian unbounded or
 * direction-dependent, and is refused.  J receives rows d/dx_a in the
 * current frame. */
static ss_status fixed_jacobian(ss_limit *L, size_t s, const ss_lim_trans *t, unsigned b,
                                const double *P, size_t cell, double J[3][3],
                                ss_error *err) {
  ss_status st = SS_OK;
  const ss_lim_eig *e = t->eig;
  const size_t K = e->K;
  double *Q = NULL;
  Q = calloc(K * 3 + 1, sizeof *Q);
  if (!Q) return ss_error_nomem(err, "fixed-point Jacobian");
  if (e->pw) {
    /* a defective run (a Jordan block, or a multiple eigenvalue LAPACK
     * returned with nearly parallel eigenvectors): only the eigenvalue-1/2
     * part matters, by its spectral projector */
    if ((st = ss_lim_eig_half_part(e, t->W, P, Q, err))) {
      free(Q);
      if (st != SS_ENUMERIC) return st;
      char why[sizeof err->msg];
      snprintf(why, sizeof why, "%s", err->msg);
      return ss_error_set(err, SS_ENUMERIC,
                          "cell %zu: the parametric Jacobian is not defined at this "
                          "point (an extraordinary vertex or edge, or the boundary): %s",
                          cell + 1, why);
    }
    goto axes;
  }
  double scale = 0.0;
  for (size_t j = 0; j < K * 3; j++)
    if (fabs(P[j] - P[j % 3]) > scale) scale = fabs(P[j] - P[j % 3]);
  double *C = malloc((K * 3 + 1) * sizeof *C);
  if (!C) {
    free(Q);
    return ss_error_nomem(err, "fixed-point Jacobian");
  }
  ss_lim_eig_coef(e, P, C);
  for (size_t i = 0; i < K; i++) {
    const double *c = C + i * 3;
    double cn = fabs(c[0]) + fabs(c[1]) + fabs(c[2]), al = cabs(e->lam[i]);
    if (e->pair[i] == 1) cn += fabs(c[3]) + fabs(c[4]) + fabs(c[5]);
    if (i == e->one || cn <= 1e-9 * scale || al < 0.5 - 1e-8) {
      if (e->pair[i] == 1) i++;
      continue;
    }
    if (cabs(e->lam[i] - 0.5) <= 1e-8) {
      /* 1/2, real, or a pair 1/2 +- i eps (a double 1/2 split by rounding:
       * W is 1/2 on the span of its x and y, whose condition was checked) */
      for (size_t w = 0; w < (e->pair[i] == 1 ? 2u : 1u); w++)
        for (size_t r = 0; r < K; r++)
          for (int d = 0; d < 3; d++)
            Q[r * 3 + (size_t)d] += e->V[(i + w) * K + r] * c[w * 3 + (size_t)d];
      if (e->pair[i] == 1) i++;
      continue;
    }
    st =
        ss_error_set(err, SS_ENUMERIC,
                     "cell %zu: the parametric Jacobian is not defined at this point (an "
                     "extraordinary vertex or edge, or the boundary): the eigenvalue "
                     "%.6g%+.6gi of its run has modulus >= 1/2 and is not 1/2",
                     cell + 1, creal(e->lam[i]), cimag(e->lam[i]));
    free(C);
    goto done;
  }
  free(C);
axes:
  for (int a = 0; a < 3; a++) {
    ss_lim_pt y;
    for (int d = 0; d < 3; d++) {
      y.s[d] = (int)((b >> d) & 1u);
      y.d[d] = d == a ? 0.5 : 0.0;
    }
    double *Qa = malloc((K * 3 + 1) * sizeof *Qa),
           I3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    if (!Qa) {
      st = ss_error_nomem(err, "fixed-point Jacobian");
      goto done;
    }
    memcpy(Qa, Q, K * 3 * sizeof *Qa);
    ss_limit_point phi;
    double oq[3] = {0, 0, 0};
    memset(&phi, 0, sizeof phi);
    if ((st = ss_lim_walk(L, s, Qa, oq, 0, y, I3, 0, 1, cell, &phi, err))) goto done;
    const double sign = (b >> a) & 1u ? -2.0 : 2.0;
    for (int d = 0; d < 3; d++)
      J[a][d] = sign * phi.p[d];
  }
done:
  free(Q);
  return st;
}

/* Move the origin o to the first of K points P (3 coordinates each) and make
 * P relative to it.  The rows of W sum to 1, so W (P - o) = W P - o: a shift
 * commutes with every step, and keeping the points relative to a point of
 * the current sub-cell keeps their differences -- of the order of the
 * sub-cell's size, 2^-m after m steps -- to full relative precision, which
 * absolute coordinates would lose (an error of eps |P| 2^m in the Jacobian). */
static void recentre(double *P, size_t K, double o[3], int sc) {
  double c[3] = {P[0], P[1], P[2]};
  for (size_t i = 0; i < K; i++)
    for (int d = 0; d < 3; d++)
      P[i * 3 + (size_t)d] -= c[d];
  for (int d = 0; d < 3; d++)
    o[d] += ldexp(c[d], -sc);
}

/* Exponent-aware scaling: the walk keeps 2^sc times the points relative to
 * o, and M divided by 2^sc (the Jacobian, bilinear in the two, is the same).
 * After about 1000 steps the points' differences (|lambda|^m) would be
 * subnormal or 0 and M (2^m) infinite: when the largest |P| falls below
 * 2^-256, P is scaled up to [1/2, 1) and M down by the same power of 2.
 * Exact, and never done at ordinary depths (results there are unchanged to
 * the bit). */
static void rescale(double *P, size_t K, double M[3][3], int *sc) {
  double mx = 0.0;
  for (size_t i = 0; i < K * 3; i++)
    if (fabs(P[i]) > mx) mx = fabs(P[i]);
  if (!(mx > 0.0) || mx >= 0x1p-256) return;
  int k = -ilogb(mx) - 1;
  for (size_t i = 0; i < K * 3; i++)
    P[i] = ldexp(P[i], k);
  for (int a = 0; a < 3; a++)
    for (int j = 0; j < 3; j++)
      M[a][j] = ldexp(M[a][j], -k);
  *sc += k;
}

/* The point and Jacobian at pt of state s (whose child k is a stationary
 * run along a factoring edge, T) by the paper's eq. (1): the limit is
 * sum_(l,c) P[l,c] N_l(x_a) phi_c(y), so the net Q_c = sum_l N_l(x_a) P[l,c],
 * put in every layer, has the same limit at (0, y) -- a corner along the
 * edge, reached by one jump whatever x_a's digits; and the derivative along
 * the edge is the limit at (0, y) of the net with N_l'. */
static ss_status tensor_eval(ss_limit *L, size_t s, const ss_lim_tensor *T,
                             const double *P, const double o[3], int sc, ss_lim_pt pt,
                             double M[3][3], int derivatives, size_t cell,
                             ss_limit_point *out, ss_error *err) {
  ss_status st;
  const size_t K = L->st[s]->patch.nv;
  const int a = T->axis;
  double x[3], bw[2][4];
  pt_x(&pt, x);
  ss_lim_basis(x[a], bw[0], bw[1]);
  ss_lim_pt p0 = pt;
  p0.s[a] = 0;
  p0.d[a] = 0.0;
  for (int pass = 0; pass < (derivatives ? 2 : 1); pass++) {
    double *Q = malloc((K * 3 + 1) * sizeof *Q), oq[3] = {0, 0, 0}, M2[3][3];
    if (!Q) return ss_error_nomem(err, "layered net");
    for (size_t v = 0; v < K; v++)
      for (int d = 0; d < 3; d++) {
        double acc = 0.0;
        for (int l = 0; l < 4; l++)
          acc += bw[pass][l] * P[T->colpt[T->col[v]][l] * 3 + (size_t)d];
        Q[v * 3 + (size_t)d] = acc;
      }
    if (pass == 0)
      for (int d = 0; d < 3; d++)
        oq[d] = o[d];
    memcpy(M2, M, sizeof M2);
    ss_limit_point r;
    memset(&r, 0, sizeof r);
    if ((st = ss_lim_walk(L, s, Q, oq, pass == 0 ? sc : 0, p0, M2,
                          pass == 0 ? derivatives : 0, 1, cell, &r, err)))
      return st;
    if (pass == 0) {
      *out = r;
      out->products++;
    } else {
      out->products += r.products + 1;
      /* d/dx_a in the current frame, then through M like the other rows */
      for (int i = 0; i < 3; i++)
        for (int d = 0; d < 3; d++)
          out->jac[i][d] += r.p[d] * M[a][i];
    }
  }
  return SS_OK;
}

/* The walk from state s with patch points P (taken over and freed), 2^sc
 * times their offsets from the origin o (recentred and rescaled on the way;
 * out->p is absolute). */
ss_status ss_lim_walk(ss_limit *L, size_t s, double *P, double o[3], int sc, ss_lim_pt pt,
                      double M[3][3], int derivatives, int no_tensor, size_t cell,
                      ss_limit_point *out, ss_error *err) {
  ss_status st = SS_OK;
  double *P0 = NULL;
  int plain = 0;
  recentre(P, L->st[s]->patch.nv, o, sc);
  rescale(P, L->st[s]->patch.nv, M, &sc);
  for (;;) {
    ss_lim_state *S = L->st[s];
    if (S->patch.regular) {
      finish_regular(&S->patch, P, &pt, M, derivatives, out);
      for (int d = 0; d < 3; d++)
        out->p[d] = ldexp(out->p[d], -sc) + o[d];
      break;
    }
    int k = ss_lim_child_of(&pt);
    ss_lim_trans *t = NULL;
    if ((st = ss_lim_transition(L, s, k, &t, err))) goto done;
    S = L->st[s];
    if (t->next == s && ss_lim_frame_is_id(&t->g)) {
      if (!no_tensor && L->tensor) {
        ss_lim_tensor *T = NULL;
        if ((st = ss_lim_tensor_of(L, s, k, &T, err))) goto done;
        if (T->status == 1) {
          int steps = out->steps, products = out->products;
          st = tensor_eval(L, s, T, P, o, sc, pt, M, derivatives, cell, out, err);
          out->steps += steps;
          out->products += products;
          goto done;
        }
      }
      long m = ss_lim_run_length(&pt, ss_cube_corner_bits(3, k));
      if (m < 0 || m >= JUMP_MIN) {
        if (!t->eig) {
          if ((st = ss_lim_eig_new(t->W, S->patch.nv, &t->eig, err))) goto done;
          L->stats.eigs++;
        }
        if (m < 0 && derivatives) {
          P0 = malloc((S->patch.nv * 3 + 1) * sizeof *P0);
          if (!P0) {
            st = ss_error_nomem(err, "patch points");
            goto done;
          }
          memcpy(P0, P, S->patch.nv * 3 * sizeof *P0);
        }
        double shift[3];
        int js = 0;
        if ((st = ss_lim_eig_power(t->eig, m, P, shift, &js, err))) goto done;
        for (int d = 0; d < 3; d++)
          o[d] += ldexp(shift[d], -sc);
        sc += js;
        out->products++;
        if (m < 0) {
          /* a fixed point: every patch point is its limit */
          for (int d = 0; d < 3; d++)
            out->p[d] = o[d] + ldexp(P[d], -sc);
          if (derivatives) {
            double J[3][3];
            if ((st = fixed_jacobian(L, s, t, ss_cube_corner_bits(3, k), P0, cell, J,
                                     err)))
              goto done;
            for (int i = 0; i < 3; i++)
              for (int d = 0; d < 3; d++) {
                out->jac[i][d] = 0.0;
                for (int a = 0; a < 3; a++)
                  out->jac[i][d] += J[a][d] * M[a][i];
              }
          }
          goto done;
        }
        pt_jump(&pt, ss_cube_corner_bits(3, k), m);
        for (int a = 0; a < 3; a++)
          for (int j = 0; j < 3; j++)
            M[a][j] = ldexp(M[a][j], (int)m - js);
        out->steps += (int)m;
        recentre(P, S->patch.nv, o, sc);
        rescale(P, S->patch.nv, M, &sc);
        continue;
      }
    }
    if ((st = apply(t->W, L->st[t->next]->patch.nv, S->patch.nv, &P, err))) goto done;
    ss_lim_advance(&pt, k, &t->g, M);
    out->steps++;
    out->products++;
    s = t->next;
    recentre(P, L->st[s]->patch.nv, o, sc);
    rescale(P, L->st[s]->patch.nv, M, &sc);
    if (++plain > SS_LIMIT_MAXSTEPS) {
      st = not_reached(L, cell, plain, err);
      goto done;
    }
  }
done:
  free(P0);
  free(P);
  return st;
}

/* No non-finite number leaves the evaluator as a value: a point or Jacobian
 * entry beyond DBL_MAX (the Jacobian grows like d^(-1 - log2 lambda) at
 * distance d from a vertex whose subdominant eigenvalue lambda exceeds 1/2)
 * is refused with the reason. */
static ss_status check_finite(size_t cell, const double x[3], int derivatives,
                              const ss_limit_point *out, ss_error *err) {
  int ok = 1;
  for (int d = 0; d < 3; d++) {
    ok &= isfinite(out->p[d]) != 0;
    for (int a = 0; a < 3 && derivatives; a++)
      ok &= isfinite(out->jac[a][d]) != 0;
  }
  if (ok) return SS_OK;
  return ss_error_set(err, SS_ENUMERIC,
                      "cell %zu at (%.17g, %.17g, %.17g): the %s is not a finite double "
                      "(beyond the range of doubles): refused",
                      cell + 1, x[0], x[1], x[2],
                      derivatives ? "limit point or its Jacobian" : "limit point");
}

ss_status ss_limit_eval(ss_limit *L, size_t cell, double u, double v, double w,
                        int derivatives, ss_limit_point *out, ss_error *err) {
  ss_status st;
  double x[3] = {u, v, w}, M[3][3];
  memset(out, 0, sizeof *out);
  if ((st = check_args(L, cell, x, err)) || (st = ss_lim_cell_state(L, cell, err)))
    return st;
  /* the cell's canonical frame: turned, not recomputed (exact) */
  const ss_lim_frame *g0 = &L->cell[cell].g;
  ss_lim_pt pt = ss_lim_pt_make(x), q;
  for (int a = 0; a < 3; a++) {
    q.s[a] = pt.s[g0->perm[a]] ^ g0->flip[a];
    q.d[a] = pt.d[g0->perm[a]];
  }
  ss_lim_frame_apply(g0, x, x, M);
  size_t s = L->cell[cell].state;
  const size_t K0 = L->st[s]->patch.nv;
  double *P = malloc((K0 * 3 + 1) * sizeof *P);
  if (!P) return ss_error_nomem(err, "patch points");
  for (size_t i = 0; i < K0; i++)
    memcpy(P + i * 3, L->mesh->x + (size_t)L->cell[cell].src[i] * 3, 3 * sizeof *P);
  double o[3] = {0, 0, 0}, x0[3] = {u, v, w};
  if ((st = ss_lim_walk(L, s, P, o, 0, q, M, derivatives, 0, cell, out, err))) return st;
  return check_finite(cell, x0, derivatives, out, err);
}

ss_status ss_limit_eval_reference(ss_limit *L, size_t cell, double u, double v, double w,
                                  int derivatives, int max_depth, ss_limit_point *out,
                                  ss_error *err) {
  ss_status st;
  double x[3] = {u, v, w}, M[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  ss_lim_pt pt = ss_lim_pt_make(x);
  ss_lim_patch p;
  ss_cx *pcx = NULL;
  double *P = NULL;
  memset(out, 0, sizeof *out);
  if ((st = check_args(L, cell, x, err))) return st;
  ss_lim_frame g = ss_lim_frame_id();
  if ((st = ss_lim_patch_build(&L->adj, cell, &g, L->loc, &p, err))) return st;
  if ((st = ss_lim_patch_complex(L->mesh, &p, &pcx, err))) goto done;
  double o[3] = {0, 0, 0}; /* the patch is kept relative to o (recentre) */
  for (int depth = 0;; depth++) {
    recentre(pcx->x, pcx->nv, o, 0);
    if (p.regular) {
      P = malloc((p.nv * 3 + 1) * sizeof *P);
      if (!P) {
        st = ss_error_nomem(err, "patch points");
        goto done;
      }
      memcpy(P, pcx->x, p.nv * 3 * sizeof *P);
      finish_regular(&p, P, &pt, M, derivatives, out);
      for (int d = 0; d < 3; d++)
        out->p[d] += o[d];
      break;
    }
    if (depth >= max_depth) {
      st = ss_error_set(
          err, SS_ENUMERIC,
          "cell %zu: the reference evaluator found no regular sub-cell in %d "
          "steps (the point lies on or within 2^-%d of an extraordinary "
          "vertex or edge, or the boundary)",
          cell + 1, max_depth, max_depth);
      goto done;
    }
    int k = ss_lim_child_of(&pt);
    ss_lim_patch child;
    ss_cx *ccx;
    if ((st = ss_lim_step(L->s, pcx, k, 0, &child, &g, &ccx, NULL, err))) goto done;
    ss_lim_patch_free(&p);
    ss_cx_free(pcx);
    p = child;
    pcx = ccx;
    ss_lim_advance(&pt, k, &g, M);
    out->steps++;
    out->products++;
  }
  if (!st) st = check_finite(cell, (const double[3]){u, v, w}, derivatives, out, err);
done:
  free(P);
  ss_lim_patch_free(&p);
  ss_cx_free(pcx);
  return st;
}
