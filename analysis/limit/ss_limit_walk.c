/* ss_limit_walk.c — limit evaluation at a point: the cached walk with
 * eigen-jumps over stationary runs and eq. (1) along extraordinary edges,
 * the Jacobian at a fixed point, and the reference by repeated local
 * subdivision (method in ss_limit.h). */
#include "ss_clock.h"
#include "ss_limit.h"

#include <complex.h>
#include <float.h>
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

/* out->jac <- the rows J (3 x D, current frame) through M (rows d/dx_a of
 * the caller's parameters). */
static void jac_through(const double *J, double M[3][3], ss_lim_res *out) {
  const size_t D = out->D;
  for (int i = 0; i < 3; i++)
    for (size_t d = 0; d < D; d++) {
      double acc = 0.0;
      for (int a = 0; a < 3; a++)
        acc += J[(size_t)a * D + d] * M[a][i];
      out->jac[(size_t)i * D + d] = acc;
    }
}

/* out->jerr <- the rounding error of out->jac read from the regular net P
 * (K x D) through M: the net's entries (relative to its first point) carry
 * an error of a few eps times their largest, and the B-spline's derivative
 * weights sum to at most 2 in modulus per axis, so row i's error is about
 * 8 eps max |P| sum_a |M[a][i]| over the axes a read from the net (rows
 * carried apart by A, ss_lim_along, are not).  An estimate, not a bound: the
 * walk's earlier steps rounded too, but their error is below the final
 * net's own once the net has shrunk by more than a few steps. */
static void jac_error(size_t K, const double *P, double M[3][3], const ss_lim_along *A,
                      ss_lim_res *out) {
  const size_t D = out->D;
  for (size_t d = 0; d < D; d++) {
    double mx = 0.0;
    for (size_t r = 0; r < K; r++)
      mx = fmax(mx, fabs(P[r * D + d]));
    for (int i = 0; i < 3; i++) {
      double g = 0.0;
      for (int a = 0; a < 3; a++) {
        int carried = 0;
        for (int j = 0; j < 3 && A; j++)
          carried |= A[j].on && A[j].axis == a;
        if (!carried) g += fabs(M[a][i]);
      }
      out->jerr[(size_t)i * D + d] = 8.0 * DBL_EPSILON * mx * g;
    }
  }
}

/* Point and Jacobian (3 x D, current frame: Jbuf) of the regular patch p's
 * points P (patch numbering) at pt, three columns at a time
 * (ss_limit_bspline); v NULL: the Jacobian only. */
static void regular_eval(const ss_lim_patch *p, const double *P, const ss_lim_pt *pt,
                         size_t D, double *v, double *Jbuf) {
  double net[64][3], J[3][3], x[3], val[3];
  pt_x(pt, x);
  for (size_t d0 = 0; d0 < D; d0 += 3) {
    const size_t nd = D - d0 < 3 ? D - d0 : 3;
    for (int i = 0; i < 64; i++)
      for (size_t d = 0; d < 3; d++)
        net[i][d] = d < nd ? P[(size_t)p->net[i] * D + d0 + d] : 0.0;
    ss_limit_bspline((const double(*)[3])net, x[0], x[1], x[2], val, J);
    for (size_t d = 0; d < nd; d++) {
      if (v) v[d0 + d] = val[d];
      for (int a = 0; a < 3; a++)
        Jbuf[(size_t)a * D + d0 + d] = J[a][d];
    }
  }
}

/* Point and Jacobian from a regular patch's points P (patch numbering); the
 * row along each A[j]'s axis from its differences while it carries them
 * (ss_lim_along; A may be NULL).  SS_ENOMEM. */
static ss_status finish_regular(const ss_lim_patch *p, const double *P,
                                const ss_lim_pt *pt, double M[3][3], int derivatives,
                                const ss_lim_along *A, ss_lim_res *out, ss_error *err) {
  const size_t D = out->D;
  double *Jbuf = malloc((6 * D + 1) * sizeof *Jbuf), *Q = NULL;
  if (!Jbuf) return ss_error_nomem(err, "limit Jacobian");
  regular_eval(p, P, pt, D, out->p, Jbuf);
  for (int j = 0; j < 3 && derivatives && A; j++) {
    if (!A[j].on) continue;
    ss_status st = ss_lim_along_net(&A[j], p, &Q, err);
    if (st) {
      free(Jbuf);
      return st;
    }
    const size_t ax = (size_t)A[j].axis;
    regular_eval(p, Q, pt, D, NULL, Jbuf + 3 * D);
    for (size_t d = 0; d < D; d++)
      Jbuf[ax * D + d] = ldexp(Jbuf[(3 + ax) * D + d], A[j].e);
    free(Q);
  }
  if (derivatives) jac_through(Jbuf, M, out);
  if (derivatives && out->jerr) jac_error(p->nv, P, M, A, out);
  free(Jbuf);
  return SS_OK;
}

/* P <- W P (Kc x K times K x D) into a new buffer. */
static ss_status apply(const double *W, size_t Kc, size_t K, size_t D, double **P,
                       ss_error *err) {
  double *Q = calloc(Kc * D + 1, sizeof *Q);
  if (!Q) return ss_error_nomem(err, "patch points");
  for (size_t i = 0; i < Kc; i++)
    for (size_t j = 0; j < K; j++) {
      double w = W[i * K + j];
      if (w == 0.0) continue;
      for (size_t d = 0; d < D; d++)
        Q[i * D + d] += w * (*P)[j * D + d];
    }
  free(*P);
  *P = Q;
  return SS_OK;
}

static ss_status not_reached(const ss_limit *L, size_t cell, int steps, ss_error *err) {
  return ss_error_set(
      err, SS_EINPUT,
      "cell %zu: no regular sub-cell after %d subdivision steps: the point "
      "lies on (or within about 2^-%d of) the mesh boundary or a crease, "
      "where the walk met no stationary run",
      cell + 1, steps, steps);
  (void)L;
}

/* Column groups of a net of D columns judged together: the 3 coordinates,
 * then each field alone (a field's size says nothing about a coordinate's). */
static size_t group_end(size_t g0, size_t D) {
  return g0 == 0 ? (D < 3 ? D : 3) : g0 + 1;
}

/* Whether the coefficients c (with c2 the second of a pair, or NULL) of one
 * eigencomponent are negligible in every column group: at most 1e-9 of the
 * group's spread scale[g0] (1-norm over the group's columns). */
static int negligible(const double *c, const double *c2, const double *scale, size_t D) {
  for (size_t g0 = 0; g0 < D; g0 = group_end(g0, D)) {
    double cn = 0.0;
    for (size_t d = g0; d < group_end(g0, D); d++)
      cn += fabs(c[d]);
    if (c2)
      for (size_t d = g0; d < group_end(g0, D); d++)
        cn += fabs(c2[d]);
    if (!(cn <= 1e-9 * scale[g0])) return 0;
  }
  return 1;
}

/* Q (K x D) <- the eigenvalue-1/2 part of P for a run that is not
 * defective, from its eigenvectors; SS_ENUMERIC if a component that is not
 * negligible has |lambda| >= 1/2 and is not 1/2 or 1. */
static ss_status half_part(const ss_lim_eig *e, size_t D, const double *P, double *Q,
                           size_t cell, ss_error *err) {
  const size_t K = e->K;
  double *C = malloc((K * D + D + 1) * sizeof *C), *scale = C + K * D;
  if (!C) return ss_error_nomem(err, "fixed-point Jacobian");
  for (size_t d = 0; d < D; d++)
    scale[d] = 0.0;
  for (size_t g0 = 0; g0 < D; g0 = group_end(g0, D))
    for (size_t r = 0; r < K; r++)
      for (size_t d = g0; d < group_end(g0, D); d++)
        if (fabs(P[r * D + d] - P[d]) > scale[g0]) scale[g0] = fabs(P[r * D + d] - P[d]);
  ss_lim_eig_coef(e, D, P, C);
  for (size_t i = 0; i < K; i++) {
    const double *c = C + i * D;
    const double al = cabs(e->lam[i]);
    if (i == e->one || negligible(c, e->pair[i] == 1 ? c + D : NULL, scale, D) ||
        al < 0.5 - 1e-8) {
      if (e->pair[i] == 1) i++;
      continue;
    }
    if (cabs(e->lam[i] - 0.5) <= 1e-8) {
      /* 1/2, real, or a pair 1/2 +- i eps (a double 1/2 split by rounding:
       * W is 1/2 on the span of its x and y, whose condition was checked) */
      for (size_t w = 0; w < (e->pair[i] == 1 ? 2u : 1u); w++)
        for (size_t r = 0; r < K; r++)
          for (size_t d = 0; d < D; d++)
            Q[r * D + d] += e->V[(i + w) * K + r] * c[w * D + d];
      if (e->pair[i] == 1) i++;
      continue;
    }
    free(C);
    return ss_error_set(err, SS_ENUMERIC,
                        "cell %zu: the parametric Jacobian is not defined at this point "
                        "(an extraordinary vertex or edge, or the boundary): the "
                        "eigenvalue %.6g%+.6gi of its run has modulus >= 1/2 and is not "
                        "1/2",
                        cell + 1, creal(e->lam[i]), cimag(e->lam[i]));
  }
  free(C);
  return SS_OK;
}

/* The Jacobian at a fixed point: corner b (bits) of state s, whose run
 * matrix has eigen-decomposition e, patch points P (K x D).  With P = sum_i
 * v_i c_i^T and phi_i the limit of the net v_i, phi_i(b + (y - b)/2) =
 * lambda_i phi_i(y): a component with |lambda| < 1/2 has derivative 0 at b,
 * one with lambda = 1/2 (real, not defective) is homogeneous of degree 1
 * along rays, so its derivative along axis a is 2 phi_i(b moved 1/2 along
 * a), signed; any other component with |lambda| >= 1/2 makes the Jacobian
 * unbounded or direction-dependent, and is refused.  J (3 x D) receives rows
 * d/dx_a in the current frame. */
static ss_status fixed_jacobian(ss_limit *L, size_t s, const ss_lim_trans *t, unsigned b,
                                size_t D, const double *P, size_t cell, double *J,
                                ss_error *err) {
  ss_status st = SS_OK;
  const ss_lim_eig *e = t->eig;
  const size_t K = e->K;
  double *Q = calloc(K * D + 2 * D + 1, sizeof *Q), *oq = Q + K * D, *phip = oq + D;
  if (!Q) return ss_error_nomem(err, "fixed-point Jacobian");
  if (e->pw) {
    /* a defective run (a Jordan block, or a multiple eigenvalue LAPACK
     * returned with nearly parallel eigenvectors): only the eigenvalue-1/2
     * part matters, by its spectral projector */
    if ((st = ss_lim_eig_half_part(e, t->W, D, P, Q, err))) {
      free(Q);
      if (st != SS_ENUMERIC) return st;
      char why[sizeof err->msg];
      snprintf(why, sizeof why, "%s", err->msg);
      return ss_error_set(err, SS_ENUMERIC,
                          "cell %zu: the parametric Jacobian is not defined at this "
                          "point (an extraordinary vertex or edge, or the boundary): %s",
                          cell + 1, why);
    }
  } else if ((st = half_part(e, D, P, Q, cell, err)))
    goto done;
  for (int a = 0; a < 3; a++) {
    ss_lim_pt y;
    for (int d = 0; d < 3; d++) {
      y.s[d] = (int)((b >> d) & 1u);
      y.d[d] = d == a ? 0.5 : 0.0;
    }
    double *Qa = malloc((K * D + 1) * sizeof *Qa),
           I3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    if (!Qa) {
      st = ss_error_nomem(err, "fixed-point Jacobian");
      goto done;
    }
    memcpy(Qa, Q, K * D * sizeof *Qa);
    for (size_t d = 0; d < D; d++)
      oq[d] = 0.0;
    ss_lim_res phi = {D, phip, NULL, 0, 0, NULL};
    if ((st = ss_lim_walk(L, s, Qa, oq, 0, y, I3, 0, 1, cell, &phi, err))) goto done;
    const double sign = (b >> a) & 1u ? -2.0 : 2.0;
    for (size_t d = 0; d < D; d++)
      J[(size_t)a * D + d] = sign * phip[d];
  }
done:
  free(Q);
  return st;
}

/* Move the origin o to the first of K points P (D columns each) and make
 * P relative to it.  The rows of W sum to 1, so W (P - o) = W P - o: a shift
 * commutes with every step, and keeping the points relative to a point of
 * the current sub-cell keeps their differences -- of the order of the
 * sub-cell's size, 2^-m after m steps -- to full relative precision, which
 * absolute coordinates would lose (an error of eps |P| 2^m in the Jacobian). */
static void recentre(double *P, size_t K, size_t D, double *o, int sc) {
  for (size_t d = 0; d < D; d++) {
    const double c = P[d];
    for (size_t i = 0; i < K; i++)
      P[i * D + d] -= c;
    o[d] += ldexp(c, -sc);
  }
}

/* Exponent-aware scaling: the walk keeps 2^sc times the points relative to
 * o, and M divided by 2^sc (the Jacobian, bilinear in the two, is the same).
 * After about 1000 steps the points' differences (|lambda|^m) would be
 * subnormal or 0 and M (2^m) infinite: when the largest |P| falls below
 * 2^-256, P is scaled up to [1/2, 1) and M down by the same power of 2.
 * Exact, and never done at ordinary depths (results there are unchanged to
 * the bit).  A's differences follow the net's scale. */
static void rescale(double *P, size_t K, size_t D, double M[3][3], int *sc,
                    ss_lim_along *A) {
  double mx = 0.0;
  for (size_t i = 0; i < K * D; i++)
    if (fabs(P[i]) > mx) mx = fabs(P[i]);
  if (!(mx > 0.0) || mx >= 0x1p-256) return;
  int k = -ilogb(mx) - 1;
  for (size_t i = 0; i < K * D; i++)
    P[i] = ldexp(P[i], k);
  for (int a = 0; a < 3; a++)
    for (int j = 0; j < 3; j++)
      M[a][j] = ldexp(M[a][j], -k);
  *sc += k;
  for (int j = 0; j < 3; j++)
    A[j].e += k; /* the differences carried apart are at the net's scale */
}

/* The point and Jacobian at pt of state s (whose child k is a stationary
 * run along a factoring edge, T) by the paper's eq. (1): the limit is
 * sum_(l,c) P[l,c] N_l(x_a) phi_c(y), so the net Q_c = sum_l N_l(x_a) P[l,c],
 * put in every layer, has the same limit at (0, y) -- a corner along the
 * edge, reached by one jump whatever x_a's digits; and the derivative along
 * the edge is the limit at (0, y) of the net with N_l'. */
static ss_status tensor_eval(ss_limit *L, size_t s, const ss_lim_tensor *T,
                             const double *P, const double *o, int sc, ss_lim_pt pt,
                             double M[3][3], int derivatives, size_t cell,
                             ss_lim_res *out, ss_error *err) {
  ss_status st = SS_OK;
  const size_t K = L->st[s]->patch.nv, D = out->D;
  const int a = T->axis;
  double x[3], bw[2][4];
  pt_x(&pt, x);
  ss_lim_basis(x[a], bw[0], bw[1]);
  ss_lim_pt p0 = pt;
  p0.s[a] = 0;
  p0.d[a] = 0.0;
  double *buf = malloc((2 * D + 1) * sizeof *buf), *oq = buf, *rp = buf + D;
  if (!buf) return ss_error_nomem(err, "layered net");
  for (int pass = 0; pass < (derivatives ? 2 : 1); pass++) {
    double *Q = malloc((K * D + 1) * sizeof *Q), M2[3][3];
    if (!Q) {
      st = ss_error_nomem(err, "layered net");
      break;
    }
    for (size_t v = 0; v < K; v++)
      for (size_t d = 0; d < D; d++) {
        double acc = 0.0;
        for (int l = 0; l < 4; l++)
          acc += bw[pass][l] * P[T->colpt[T->col[v]][l] * D + d];
        Q[v * D + d] = acc;
      }
    for (size_t d = 0; d < D; d++)
      oq[d] = pass == 0 ? o[d] : 0.0;
    memcpy(M2, M, sizeof M2);
    /* The first pass's net is the same in every layer, so its limit on the
     * cell, sum_c Q_c phi_c(y) sum_l N_l(x_a), does not depend on x_a (the
     * N_l sum to 1): its derivative along the edge is 0 exactly, and the
     * second pass gives that row alone.  The walk would form it from
     * differences of nets equal along the edge, and near the edge their
     * rounding (eps |Q| times the growth of the across parts, (2 mu)^m after
     * m steps) is all it would add; dropping its row of M (rows are only
     * permuted, signed and scaled by powers of 2 on the way) leaves it out
     * exactly. */
    if (pass == 0)
      for (int j = 0; j < 3; j++)
        M2[a][j] = 0.0;
    ss_lim_res r = {D, pass == 0 ? out->p : rp,     pass == 0 ? out->jac : NULL, 0,
                    0, pass == 0 ? out->jerr : NULL};
    if ((st = ss_lim_walk(L, s, Q, oq, pass == 0 ? sc : 0, p0, M2,
                          pass == 0 ? derivatives : 0, 1, cell, &r, err)))
      break;
    if (pass == 0) {
      out->steps = r.steps;
      out->products = r.products + 1;
    } else {
      out->products += r.products + 1;
      /* d/dx_a in the current frame, then through M like the other rows */
      for (int i = 0; i < 3; i++)
        for (size_t d = 0; d < D; d++)
          out->jac[(size_t)i * D + d] += rp[d] * M[a][i];
    }
  }
  free(buf);
  return st;
}

/* A's differences through one plain step by t (parent patch pp, child cp),
 * pt already in the child's frame. */
static ss_status along_advance(ss_lim_along *A, const ss_lim_trans *t,
                               const ss_lim_patch *pp, const ss_lim_patch *cp,
                               const ss_lim_pt *pt, ss_error *err) {
  int ca = 0;
  while (t->g.perm[ca] != A->axis)
    ca++;
  return ss_lim_along_step(A, t->W, pp, cp, ca, pt->s[ca], 1, err);
}

/* A run of m steps by W from state S, the point pt on the plane x_a = 0 or 1
 * of the sub-cell for some axes a: the differences across each such plane
 * are carried apart from here on (ss_lim_along: the point stays on it), in
 * A[a]'s slot or another free one, and through the run. */
static ss_status along_jump(ss_lim_along A[3], const ss_lim_state *S, const ss_lim_pt *pt,
                            size_t D, const double *P, const double *W, long m,
                            ss_error *err) {
  ss_status st;
  for (int a = 0; a < 3; a++) {
    int have = 0, slot = -1;
    for (int j = 0; j < 3; j++) {
      have |= A[j].on && A[j].axis == a;
      if (!A[j].on && slot < 0) slot = j;
    }
    if (!have && slot >= 0 && pt->d[a] == 0.0)
      ss_lim_along_start(&A[slot], &S->patch, pt, a, D, P);
  }
  for (int j = 0; j < 3; j++)
    if (A[j].on && (st = ss_lim_along_step(&A[j], W, &S->patch, &S->patch, A[j].axis,
                                           A[j].side, m, err)))
      return st;
  return SS_OK;
}

/* The walk from state s with patch points P (taken over and freed), 2^sc
 * times their offsets from the origin o (recentred and rescaled on the way;
 * out->p is absolute). */
ss_status ss_lim_walk(ss_limit *L, size_t s, double *P, double *o, int sc, ss_lim_pt pt,
                      double M[3][3], int derivatives, int no_tensor, size_t cell,
                      ss_lim_res *out, ss_error *err) {
  ss_status st = SS_OK;
  const size_t D = out->D;
  double *P0 = NULL, *shift = NULL;
  int plain = 0;
  ss_lim_along A[3] = {{0}, {0}, {0}};
  recentre(P, L->st[s]->patch.nv, D, o, sc);
  rescale(P, L->st[s]->patch.nv, D, M, &sc, A);
  for (;;) {
    ss_lim_state *S = L->st[s];
    if (S->patch.regular) {
      if ((st = finish_regular(&S->patch, P, &pt, M, derivatives, A, out, err)))
        goto done;
      for (size_t d = 0; d < D; d++)
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
          double t0 = ss_clock_cpu();
          if ((st = ss_lim_eig_new(t->W, S->patch.nv, &t->eig, err))) goto done;
          ss_clock_lap(&L->stats.eig_s, &t0);
          L->stats.eigs++;
        }
        if (m < 0 && derivatives) {
          P0 = malloc((S->patch.nv * D + 1) * sizeof *P0);
          if (!P0) {
            st = ss_error_nomem(err, "patch points");
            goto done;
          }
          memcpy(P0, P, S->patch.nv * D * sizeof *P0);
        }
        if (!shift && !(shift = malloc((3 * D + 1) * sizeof *shift))) {
          st = ss_error_nomem(err, "patch points");
          goto done;
        }
        if (m > 0 && derivatives && (st = along_jump(A, S, &pt, D, P, t->W, m, err)))
          goto done;
        int js = 0;
        if ((st = ss_lim_eig_power(t->eig, m, D, P, shift, &js, err))) goto done;
        for (size_t d = 0; d < D; d++)
          o[d] += ldexp(shift[d], -sc);
        sc += js;
        for (int j = 0; j < 3; j++)
          A[j].e += js;
        out->products++;
        if (m < 0) {
          /* a fixed point: every patch point is its limit */
          for (size_t d = 0; d < D; d++)
            out->p[d] = o[d] + ldexp(P[d], -sc);
          if (derivatives) {
            double *J = shift; /* 3 x D, the shift no longer needed */
            if ((st = fixed_jacobian(L, s, t, ss_cube_corner_bits(3, k), D, P0, cell, J,
                                     err)))
              goto done;
            jac_through(J, M, out);
            if (out->jerr) jac_error(S->patch.nv, P0, M, NULL, out);
          }
          goto done;
        }
        pt_jump(&pt, ss_cube_corner_bits(3, k), m);
        for (int a = 0; a < 3; a++)
          for (int j = 0; j < 3; j++)
            M[a][j] = ldexp(M[a][j], (int)m - js);
        out->steps += (int)m;
        recentre(P, S->patch.nv, D, o, sc);
        rescale(P, S->patch.nv, D, M, &sc, A);
        continue;
      }
    }
    if ((st = ss_lim_trans_apply(t, L->st[t->next]->patch.nv, S->patch.nv, D, &P, err)))
      goto done;
    ss_lim_advance(&pt, k, &t->g, M);
    for (int j = 0; j < 3; j++)
      if (A[j].on &&
          (st = along_advance(&A[j], t, &S->patch, &L->st[t->next]->patch, &pt, err)))
        goto done;
    out->steps++;
    out->products++;
    s = t->next;
    recentre(P, L->st[s]->patch.nv, D, o, sc);
    rescale(P, L->st[s]->patch.nv, D, M, &sc, A);
    if (++plain > SS_LIMIT_MAXSTEPS) {
      st = not_reached(L, cell, plain, err);
      goto done;
    }
  }
done:
  for (int j = 0; j < 3; j++)
    ss_lim_along_free(&A[j]);
  free(shift);
  free(P0);
  free(P);
  return st;
}

/* No non-finite number leaves the evaluator as a value: a point, field or
 * Jacobian entry beyond DBL_MAX (the Jacobian grows like d^(-1 - log2
 * lambda) at distance d from a vertex whose subdominant eigenvalue lambda
 * exceeds 1/2) is refused with the reason. */
static ss_status check_finite(size_t cell, const double x[3], int derivatives,
                              const ss_lim_res *out, ss_error *err) {
  int ok = 1;
  for (size_t d = 0; d < out->D; d++) {
    ok &= isfinite(out->p[d]) != 0;
    for (size_t a = 0; a < 3 && derivatives; a++)
      ok &= isfinite(out->jac[a * out->D + d]) != 0;
  }
  if (ok) return SS_OK;
  return ss_error_set(
      err, SS_ENUMERIC,
      "cell %zu at (%.17g, %.17g, %.17g): the %s is not a finite double "
      "(beyond the range of doubles): refused",
      cell + 1, x[0], x[1], x[2],
      out->D > 3 ? (derivatives ? "limit point, a field or a derivative"
                                : "limit point or a field")
                 : (derivatives ? "limit point or its Jacobian" : "limit point"));
}

/* Nothing silently wrong: a Jacobian row (per column group) whose rounding
 * estimate r->jerr exceeds 1e-9 of its size -- or of the coarse net's spread
 * where the row is smaller (a derivative about 0, e.g. MLCA's normal one on
 * the boundary) -- is refused with the figures.  Near an extraordinary edge
 * on the mesh boundary the walk reads the along-edge row from a net whose
 * spread across the edge has shrunk like mu^m and whose along differences
 * like 2^-m: the row's error grows like eps (2 mu)^m, and without the mirror
 * symmetry that carries them apart (ss_lim_along) nothing recovers it. */
static ss_status check_rounding(size_t cell, const double x[3], const ss_lim_res *r,
                                const double *spread, ss_error *err) {
  static const char *const row[3] = {"U", "V", "W"};
  const size_t D = r->D;
  for (size_t g0 = 0; g0 < D; g0 = group_end(g0, D))
    for (size_t i = 0; i < 3; i++) {
      double e = 0.0, v = 0.0, sp = 0.0;
      for (size_t d = g0; d < group_end(g0, D); d++) {
        e = fmax(e, r->jerr[i * D + d]);
        v = fmax(v, fabs(r->jac[i * D + d]));
        sp = fmax(sp, spread[d]);
      }
      if (e <= 1e-9 * fmax(v, sp)) continue;
      return ss_error_set(err, SS_ENUMERIC,
                          "cell %zu at (%.17g, %.17g, %.17g): the derivative d/d%s%s "
                          "cannot be trusted: it is read from a net whose rounding, "
                          "grown by the depth, is about %.3g, over 1e-9 of %.3g (its "
                          "size, or the cell's if larger; near an extraordinary edge "
                          "on the boundary, or another run no exact structure "
                          "carries apart): refused",
                          cell + 1, x[0], x[1], x[2], row[i],
                          g0 == 0 ? "" : " of a field", e, fmax(v, sp));
    }
  return SS_OK;
}

/* The net of a patch (K x D, row-major) from the mesh vertices src: the
 * coordinates, then (D > 3) the fields.  SS_ENOMEM. */
static ss_status patch_net(const ss_limit *L, const ss_idx *src, size_t K, size_t D,
                           double **P, ss_error *err) {
  *P = malloc((K * D + 1) * sizeof **P);
  if (!*P) return ss_error_nomem(err, "patch points");
  for (size_t i = 0; i < K; i++) {
    memcpy(*P + i * D, L->mesh->x + (size_t)src[i] * 3, 3 * sizeof **P);
    if (D > 3)
      memcpy(*P + i * D + 3, L->fld + (size_t)src[i] * L->nf, L->nf * sizeof **P);
  }
  return SS_OK;
}

/* The walk for cell at x into r (r->D columns: 3, or 3 + L->nf). */
static ss_status eval_net(ss_limit *L, size_t cell, const double x0[3], int derivatives,
                          ss_lim_res *r, ss_error *err) {
  ss_status st;
  double x[3] = {x0[0], x0[1], x0[2]}, M[3][3], *P, *o;
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
  const size_t D = r->D, K = L->st[s]->patch.nv;
  /* o, then with derivatives the rounding estimate (3 x D) and the coarse
   * net's spread per column (D) */
  if (!(o = calloc(5 * D + 1, sizeof *o))) return ss_error_nomem(err, "patch points");
  double *spread = o + 4 * D;
  if (!(st = patch_net(L, L->cell[cell].src, K, D, &P, err))) {
    for (size_t i = 0; i < K * D; i++)
      spread[i % D] = fmax(spread[i % D], fabs(P[i] - P[i % D]));
    if (derivatives) r->jerr = o + D;
    st = ss_lim_walk(L, s, P, o, 0, q, M, derivatives, 0, cell, r, err);
  }
  if (!st) st = check_finite(cell, x0, derivatives, r, err);
  if (!st && derivatives) st = check_rounding(cell, x0, r, spread, err);
  r->jerr = NULL;
  free(o);
  return st;
}

/* Space for a result of D columns, or with fields NULL (D = 3) the arrays of
 * out itself.  SS_ENOMEM. */
static ss_status res_open(ss_limit_point *out, const double *fields, size_t nf,
                          ss_lim_res *r, ss_error *err) {
  memset(out, 0, sizeof *out);
  *r = (ss_lim_res){3, out->p, &out->jac[0][0], 0, 0, NULL};
  if (!fields) return SS_OK;
  r->D = 3 + nf;
  r->p = calloc(4 * r->D, sizeof *r->p);
  if (!r->p) return ss_error_nomem(err, "limit fields");
  r->jac = r->p + r->D;
  return SS_OK;
}

/* Copy r into out, f and df (when r is not out's own) and free its space. */
static void res_close(const ss_lim_res *r, ss_limit_point *out, double *f,
                      double (*df)[3]) {
  out->steps = r->steps;
  out->products = r->products;
  if (r->p == out->p) return;
  const size_t D = r->D;
  for (size_t d = 0; d < D; d++) {
    if (d < 3)
      out->p[d] = r->p[d];
    else
      f[d - 3] = r->p[d];
    for (size_t a = 0; a < 3; a++) {
      if (d < 3)
        out->jac[a][d] = r->jac[a * D + d];
      else if (df)
        df[d - 3][a] = r->jac[a * D + d];
    }
  }
  free(r->p);
}

ss_status ss_limit_eval_fields(ss_limit *L, size_t cell, double u, double v, double w,
                               int derivatives, ss_limit_point *out, double *f,
                               double (*df)[3], ss_error *err) {
  ss_lim_res r;
  const double x[3] = {u, v, w};
  ss_status st = res_open(out, f, L->nf, &r, err);
  if (st) return st;
  st = eval_net(L, cell, x, derivatives, &r, err);
  res_close(&r, out, f, derivatives ? df : NULL);
  return st;
}

ss_status ss_limit_eval(ss_limit *L, size_t cell, double u, double v, double w,
                        int derivatives, ss_limit_point *out, ss_error *err) {
  return ss_limit_eval_fields(L, cell, u, v, w, derivatives, out, NULL, NULL, err);
}

/* The reference's walk into r: the patch complex refined (its positions),
 * the fields (r->D > 3) carried by the rows of each step. */
static ss_status reference_net(ss_limit *L, size_t cell, const double x[3],
                               int derivatives, int max_depth, ss_lim_res *r,
                               ss_error *err) {
  ss_status st;
  double M[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const size_t D = r->D, nf = D - 3;
  ss_lim_pt pt = ss_lim_pt_make(x);
  ss_lim_patch p;
  ss_cx *pcx = NULL;
  double *P = NULL, *F = NULL, *W = NULL, *o = NULL;
  if ((st = check_args(L, cell, x, err))) return st;
  ss_lim_frame g = ss_lim_frame_id();
  if ((st = ss_lim_patch_build(&L->adj, cell, &g, L->loc, &p, err))) return st;
  if ((st = ss_lim_patch_complex(L->mesh, &p, &pcx, err))) goto done;
  if (!(o = calloc(D + 1, sizeof *o))) { /* the patch is kept relative to o */
    st = ss_error_nomem(err, "patch points");
    goto done;
  }
  if (nf) {
    if ((st = patch_net(L, p.src, p.nv, D, &F, err))) goto done;
    for (size_t i = 0; i < p.nv; i++) /* F: the fields only, K x nf */
      memmove(F + i * nf, F + i * D + 3, nf * sizeof *F);
  }
  for (int depth = 0;; depth++) {
    recentre(pcx->x, pcx->nv, 3, o, 0);
    if (nf) recentre(F, pcx->nv, nf, o + 3, 0);
    if (p.regular) {
      if (!(P = malloc((p.nv * D + 1) * sizeof *P))) {
        st = ss_error_nomem(err, "patch points");
        goto done;
      }
      for (size_t i = 0; i < p.nv; i++) {
        memcpy(P + i * D, pcx->x + i * 3, 3 * sizeof *P);
        if (nf) memcpy(P + i * D + 3, F + i * nf, nf * sizeof *P);
      }
      if ((st = finish_regular(&p, P, &pt, M, derivatives, NULL, r, err))) goto done;
      for (size_t d = 0; d < D; d++)
        r->p[d] += o[d];
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
    if ((st = ss_lim_step(L->s, pcx, k, 0, &child, &g, &ccx, nf ? &W : NULL, err)))
      goto done;
    if (nf && (st = apply(W, child.nv, p.nv, nf, &F, err))) {
      ss_lim_patch_free(&child);
      ss_cx_free(ccx);
      goto done;
    }
    free(W);
    W = NULL;
    ss_lim_patch_free(&p);
    ss_cx_free(pcx);
    p = child;
    pcx = ccx;
    ss_lim_advance(&pt, k, &g, M);
    r->steps++;
    r->products++;
  }
  st = check_finite(cell, x, derivatives, r, err);
done:
  free(P);
  free(F);
  free(W);
  free(o);
  ss_lim_patch_free(&p);
  ss_cx_free(pcx);
  return st;
}

ss_status ss_limit_eval_reference_fields(ss_limit *L, size_t cell, double u, double v,
                                         double w, int derivatives, int max_depth,
                                         ss_limit_point *out, double *f, double (*df)[3],
                                         ss_error *err) {
  ss_lim_res r;
  const double x[3] = {u, v, w};
  ss_status st = res_open(out, f, L->nf, &r, err);
  if (st) return st;
  st = reference_net(L, cell, x, derivatives, max_depth, &r, err);
  res_close(&r, out, f, derivatives ? df : NULL);
  return st;
}

ss_status ss_limit_eval_reference(ss_limit *L, size_t cell, double u, double v, double w,
                                  int derivatives, int max_depth, ss_limit_point *out,
                                  ss_error *err) {
  return ss_limit_eval_reference_fields(L, cell, u, v, w, derivatives, max_depth, out,
                                        NULL, NULL, err);
}
