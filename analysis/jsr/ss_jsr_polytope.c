/* ss_jsr_polytope.c — the invariant polytope method (Guglielmi-Protasov):
 * vertices by breadth-first images, membership by GLPK, the bound proven in
 * ball arithmetic.  Method: ss_jsr_polytope.h. */
#include "ss_jsr_polytope.h"

#include <arb.h>
#include <glpk.h>
#include <lapacke.h>
#include <math.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"

/* pi, for the ellipse points (PI is not C11) */
#define PI 3.14159265358979323846

ss_jsr_polytope_opts ss_jsr_polytope_defaults(void) {
  ss_jsr_polytope_opts o = {5e-4, 20000, 60.0, 1e-4, 1e-9};
  return o;
}

/* An image counts as inside when its LP value is at most 1 + IN_TOL: the
 * certificate accounts for whatever the value is, so this only decides
 * which vertices are kept. */
#define IN_TOL 1e-10

/* The working state of one run. */
typedef struct {
  size_t m, n;            /* maps, order */
  const double *const *Y; /* the inputs */
  double s;               /* the normalisation lambda (1 + eps) */
  double *vert;           /* cap x n: the vertices, row k = v_k */
  size_t nv, cap;         /* vertices, their capacity */
  size_t *rec_off;        /* cap x m: offset of the coefficients of A_i v_j */
  int *rec_len;           /* cap x m: their number (-1: not tested) */
  int *gen;               /* cap: a vertex's generation (roots and ball 0, an
                             image of generation g: g + 1) */
  int depth;              /* largest generation so far */
  int *cidx;              /* coefficient store: vertex indices */
  double *cval;           /* coefficient store: values c_k */
  size_t nc, ccap;        /* used, capacity */
  glp_prob *lp;           /* rows = n coordinates, 2 columns per vertex */
  int *ind;               /* 1 + n: GLPK's 1-based row indices */
  double *col;            /* 1 + n: a column's values */
  char glpk_says[160];    /* GLPK's first line of terminal output (an error's
                             text: GLPK prints errors, whatever glp_term_out) */
} poly_ws;

/* Append vertex x (n values; the capacity is preallocated) as columns +x and
 * -x of the LP. */
static void add_vertex(poly_ws *p, const double *x) {
  const size_t n = p->n;
  memcpy(p->vert + p->nv * n, x, n * sizeof *x);
  for (size_t i = 0; i < p->m; i++)
    p->rec_len[p->nv * p->m + i] = -1;
  const int c0 = glp_add_cols(p->lp, 2);
  for (int sgn = 0; sgn < 2; sgn++) {
    for (size_t l = 0; l < n; l++)
      p->col[l + 1] = sgn ? -x[l] : x[l];
    glp_set_mat_col(p->lp, c0 + sgn, (int)n, p->ind, p->col);
    glp_set_col_bnds(p->lp, c0 + sgn, GLP_LO, 0.0, 0.0);
    glp_set_obj_coef(p->lp, c0 + sgn, 1.0);
  }
  p->nv++;
}

/* Record coefficients for the image (j, i): cnt pairs; 0 on no memory. */
static int record(poly_ws *p, size_t j, size_t i, const int *idx, const double *val,
                  int cnt) {
  if (p->nc + (size_t)cnt > p->ccap) {
    size_t nc = p->ccap ? 2 * p->ccap : 4096;
    while (nc < p->nc + (size_t)cnt)
      nc *= 2;
    int *ni = realloc(p->cidx, nc * sizeof *ni);
    if (!ni) return 0;
    p->cidx = ni;
    double *nvv = realloc(p->cval, nc * sizeof *nvv);
    if (!nvv) return 0;
    p->cval = nvv;
    p->ccap = nc;
  }
  memcpy(p->cidx + p->nc, idx, (size_t)cnt * sizeof *idx);
  memcpy(p->cval + p->nc, val, (size_t)cnt * sizeof *val);
  p->rec_off[j * p->m + i] = p->nc;
  p->rec_len[j * p->m + i] = cnt;
  p->nc += (size_t)cnt;
  return 1;
}

/* ||x||_P by the LP (x scaled to unit max-norm first, since GLPK's
 * tolerances are absolute); the nonzero coefficients go to idx/val (at most
 * nv of them), their count to *cnt.  Returns the value sum |c_k| (computed
 * from the coefficients, not GLPK's objective), or -1 if the LP failed. */
static double lp_norm(poly_ws *p, const double *x, int *idx, double *val, int *cnt) {
  double sc = 0;
  for (size_t l = 0; l < p->n; l++)
    sc = fmax(sc, fabs(x[l]));
  *cnt = 0;
  if (sc == 0) return 0;
  for (size_t l = 0; l < p->n; l++)
    glp_set_row_bnds(p->lp, (int)l + 1, GLP_FX, x[l] / sc, x[l] / sc);
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.meth = GLP_DUALP; /* the last basis stays dual feasible: only b moved */
  if (glp_simplex(p->lp, &parm) != 0 || glp_get_status(p->lp) != GLP_OPT) {
    /* a stale basis can be singular after many added columns: retry once
     * from the standard basis */
    glp_std_basis(p->lp);
    if (glp_simplex(p->lp, &parm) != 0 || glp_get_status(p->lp) != GLP_OPT) return -1;
  }
  double sum = 0;
  for (size_t k = 0; k < p->nv; k++) {
    const double c =
        glp_get_col_prim(p->lp, 2 * (int)k + 1) - glp_get_col_prim(p->lp, 2 * (int)k + 2);
    if (c != 0) {
      idx[*cnt] = (int)k;
      val[(*cnt)++] = c * sc;
      sum += fabs(c * sc);
    }
  }
  return sum;
}

/* Stop codes besides ss_jsr_polytope_stop: out of memory; GLPK failed. */
#define STOP_NOMEM 100
#define STOP_GLPK  101

/* Test the images A_i v_j (i = 0..m-1) of vertex j: inside ones get their
 * coefficients recorded, the others become vertices.  Returns -1 to go on,
 * or a stop code (SS_POLY_CAP, SS_POLY_LP, STOP_NOMEM). */
static int test_images(poly_ws *p, size_t j, double *x, int *idx, double *val,
                       size_t *lps, double *max_out) {
  const size_t n = p->n;
  for (size_t i = 0; i < p->m; i++) {
    const double *y = p->Y[i], *vj = p->vert + j * n;
    for (size_t a = 0; a < n; a++) {
      double acc = 0;
      for (size_t c = 0; c < n; c++)
        acc += y[a * n + c] * vj[c];
      x[a] = acc / p->s;
    }
    int cnt;
    const double v = lp_norm(p, x, idx, val, &cnt);
    ++*lps;
    if (v < 0) return SS_POLY_LP;
    if (v <= 1 + IN_TOL) {
      if (!record(p, j, i, idx, val, cnt)) return STOP_NOMEM;
      continue;
    }
    if (p->nv == p->cap) return SS_POLY_CAP;
    *max_out = fmax(*max_out, v);
    const int k = (int)p->nv;
    const double one = 1;
    p->gen[k] = p->gen[j] + 1;
    if (p->gen[k] > p->depth) p->depth = p->gen[k];
    add_vertex(p, x);
    if (!record(p, j, i, &k, &one, 1)) return STOP_NOMEM;
  }
  return -1;
}

/* out = y q for n x n row-major matrices (out may not alias q): the next
 * letter of a word applied on the left. */
static void mul_left(size_t n, const double *y, const double *q, double *out) {
  for (size_t a = 0; a < n; a++)
    for (size_t b = 0; b < n; b++) {
      double acc = 0;
      for (size_t c = 0; c < n; c++)
        acc += y[a * n + c] * q[c * n + b];
      out[a * n + b] = acc;
    }
}

/* Two moduli at most this far apart (relative) are one leading eigenvalue:
 * a semisimple multiple one (the tet/oct face's Y_2..Y_4 each have a double
 * one) has an eigenplane, and a root from only one of its eigenvectors
 * leaves the other direction to be reached by images. */
#define LEAD_TOL 1e-9

/* A real leading eigenvector counts as a new direction when at least this
 * fraction of its norm lies outside the span of those already taken. */
#define INDEP_TOL 1e-6

/* Leading eigenpairs of Pi: roots written to `roots` (at most cap rows of
 * n): for every eigenvalue of modulus within LEAD_TOL of rho(Pi), its real
 * eigenvector, or for a complex pair the N ellipse points of the 2-plane
 * variant, each followed by its len - 1 cyclic images.  N is the least with
 * cos(pi / 2N) >= rho(Pi) / s^len, capped by (1 + eps)^{-len} (its value
 * for the candidate itself; a near-candidate, rho(Pi) < s^len / (1 + eps)^len,
 * needs fewer points).  Returns the number of rows, 0 if rho(Pi) = 0, -1 if
 * LAPACK failed, -2 on no memory, -3 if they exceed cap. */
static long make_roots(poly_ws *p, const int *w, int len, double eps, double *lambda,
                       int *cplx, double **roots_out) {
  const size_t n = p->n, nn = n * n;
  double *P = malloc(nn * sizeof *P), *T = malloc(nn * sizeof *T),
         *wr = malloc(n * sizeof *wr), *wi = malloc(n * sizeof *wi),
         *vr = malloc(nn * sizeof *vr);
  unsigned char *sel = malloc(n);
  double *roots = NULL;
  long nr = -2;
  if (!P || !T || !wr || !wi || !vr || !sel) goto out;
  /* P = Y_{w[len-1]} ... Y_{w[0]} */
  memcpy(P, p->Y[w[0]], nn * sizeof *P);
  for (int t = 1; t < len; t++) {
    mul_left(n, p->Y[w[t]], P, T);
    memcpy(P, T, nn * sizeof *P);
  }
  if (LAPACKE_dgeev(LAPACK_ROW_MAJOR, 'N', 'V', (lapack_int)n, P, (lapack_int)n, wr, wi,
                    NULL, 1, vr, (lapack_int)n) != 0) {
    nr = -1;
    goto out;
  }
  double mu = 0;
  for (size_t k = 0; k < n; k++)
    mu = fmax(mu, hypot(wr[k], wi[k]));
  if (!(mu > 0)) {
    nr = 0;
    goto out;
  }
  *lambda = pow(mu, 1.0 / len);
  /* points per complex pair: Pi / s^len has modulus c on the ellipse */
  const double c = fmin(mu / pow(p->s, len), pow(1 + eps, -(double)len));
  size_t npts = (size_t)ceil(PI / (2 * acos(c)));
  if (npts < 2) npts = 2;
  /* LAPACK stores a conjugate pair as columns k (real part) and k + 1
   * (imaginary part) for the eigenvalue with positive imaginary part: the
   * partner with negative imaginary part is skipped.  A real eigenvector
   * (nearly) in the span of those already taken is skipped too: a defective
   * eigenvalue gives (nearly) parallel columns, which would be the same root
   * twice.  P (spent by dgeev) holds their orthonormalised copies. */
  size_t rows = 0, taken = 0;
  *cplx = 0;
  for (size_t k = 0; k < n; k++) {
    sel[k] = hypot(wr[k], wi[k]) >= mu * (1 - LEAD_TOL) && wi[k] >= 0;
    if (sel[k] && wi[k] == 0) {
      double *g = P + taken * n, norm0 = 0, norm1 = 0;
      for (size_t l = 0; l < n; l++) {
        g[l] = vr[l * n + k];
        norm0 += g[l] * g[l];
      }
      for (size_t b = 0; b < taken; b++) {
        double d = 0;
        for (size_t l = 0; l < n; l++)
          d += P[b * n + l] * g[l];
        for (size_t l = 0; l < n; l++)
          g[l] -= d * P[b * n + l];
      }
      for (size_t l = 0; l < n; l++)
        norm1 += g[l] * g[l];
      sel[k] = norm1 > INDEP_TOL * INDEP_TOL * norm0;
      if (sel[k]) {
        for (size_t l = 0; l < n; l++)
          g[l] /= sqrt(norm1);
        taken++;
      }
    }
    if (sel[k]) {
      rows += (wi[k] > 0 ? npts : 1) * (size_t)len;
      *cplx |= wi[k] > 0;
    }
  }
  if (rows > p->cap) {
    nr = -3;
    goto out;
  }
  roots = malloc(rows * n * sizeof *roots);
  if (!roots) goto out;
  nr = 0;
  for (size_t ja = 0; ja < n; ja++) {
    if (!sel[ja]) continue;
    const int pair = wi[ja] > 0;
    double na = 0, nb = 0;
    for (size_t l = 0; l < n; l++) {
      na += vr[l * n + ja] * vr[l * n + ja];
      if (pair) nb += vr[l * n + ja + 1] * vr[l * n + ja + 1];
    }
    const double scale = 1 / sqrt(fmax(na, nb));
    for (size_t k = 0; k < (pair ? npts : 1); k++) {
      double *x = roots + (size_t)nr * n;
      const double th = PI * (double)k / (double)npts;
      for (size_t l = 0; l < n; l++)
        x[l] = scale *
               (cos(th) * vr[l * n + ja] - (pair ? sin(th) * vr[l * n + ja + 1] : 0));
      nr++;
      for (int t = 0; t + 1 < len; t++, nr++) {
        const double *y = p->Y[w[t]], *src = roots + (size_t)nr * n - n;
        double *dst = roots + (size_t)nr * n;
        for (size_t a = 0; a < n; a++) {
          double acc = 0;
          for (size_t q = 0; q < n; q++)
            acc += y[a * n + q] * src[q];
          dst[a] = acc / p->s;
        }
      }
    }
  }
  *roots_out = roots;
  roots = NULL;
out:
  free(roots);
  free(sel);
  free(vr);
  free(wi);
  free(wr);
  free(T);
  free(P);
  return nr;
}

/* Several candidates (Guglielmi-Protasov): a product tied with Pi (two maps
 * of equal spectral radius, or a symmetric image of w) has an eigenvector
 * the hull from Pi's alone reaches only after about 1 / eps steps.  Words
 * searched: all of length <= T, the largest T <= TIE_MAXLEN with m + ... +
 * m^T <= TIE_BUDGET products (fewer for large n: 2e9 multiply-adds). */
enum { TIE_MAXLEN = 16, TIE_BUDGET = 1 << 16, TIE_MAX = 32 };

/* A tie: rho(Y_u)^{1/|u|} >= lambda (1 - o->near).  With the default near
 * (1e-9) that is equality up to rounding (a symmetry of the set, or maps of
 * equal spectral radius), and products merely near lambda are left to the
 * slack eps; a larger near also starts from the near-candidates'
 * eigenvectors (Mejstrik 2020), so that an orbit decaying like
 * (rho_u / s)^k need not be followed until it falls inside. */

/* 1 if u (length ul) repeated equals some rotation of w (length len) */
static int same_class(const int *u, int ul, const int *w, int len) {
  if (len % ul) return 0;
  for (int r = 0; r < len; r++) {
    int eq = 1;
    for (int t = 0; t < len && eq; t++)
      eq = w[(r + t) % len] == u[t % ul];
    if (eq) return 1;
  }
  return 0;
}

/* 1 if u[0..len-1] is a Lyndon word (smaller than its proper rotations) */
static int lyndon(const int *u, int len) {
  for (int r = 1; r < len; r++) {
    int c = 0;
    for (int t = 0; t < len && !c; t++)
      c = u[(r + t) % len] - u[t];
    if (c <= 0) return 0;
  }
  return 1;
}

/* The Lyndon words u of length <= T, not in w's class, with
 * rho(Y_u)^{1/|u|} >= floor_: at most TIE_MAX into ties (rows of
 * TIE_MAXLEN) and tlen.  Returns their number, -1 if LAPACK failed, -2 on
 * no memory.  Products by prefix, depth first. */
static int find_ties(const poly_ws *p, const int *w, int len, double floor_, int *ties,
                     int *tlen) {
  const size_t n = p->n, nn = n * n, m = p->m;
  /* at most TIE_BUDGET products, and at most 2e9 multiply-adds */
  const double budget = fmin(TIE_BUDGET, 2e9 / ((double)n * (double)n * (double)n));
  int T = 0;
  for (double words = 0, pw = 1; T < TIE_MAXLEN; T++) {
    pw *= (double)m;
    if (words + pw > budget) break;
    words += pw;
  }
  if (T == 0) return 0;
  double *prod = malloc((size_t)T * nn * sizeof *prod), *a = malloc(nn * sizeof *a),
         *wr = malloc(n * sizeof *wr), *wi = malloc(n * sizeof *wi);
  int u[TIE_MAXLEN], k = 0, nt = 0;
  if (!prod || !a || !wr || !wi) {
    nt = -2;
    goto out;
  }
  u[0] = -1;
  while (k >= 0) {
    if (++u[k] == (int)m) {
      k--;
      continue;
    }
    double *P = prod + (size_t)k * nn;
    if (k == 0) {
      memcpy(P, p->Y[u[0]], nn * sizeof *P);
    } else {
      mul_left(n, p->Y[u[k]], P - nn, P);
    }
    if (nt < TIE_MAX && lyndon(u, k + 1) && !same_class(u, k + 1, w, len)) {
      memcpy(a, P, nn * sizeof *a);
      if (LAPACKE_dgeev(LAPACK_ROW_MAJOR, 'N', 'N', (lapack_int)n, a, (lapack_int)n, wr,
                        wi, NULL, 1, NULL, 1) != 0) {
        nt = -1;
        goto out;
      }
      double r = 0;
      for (size_t j = 0; j < n; j++)
        r = fmax(r, hypot(wr[j], wi[j]));
      if (r > 0 && pow(r, 1.0 / (k + 1)) >= floor_) {
        memcpy(ties + (size_t)nt * TIE_MAXLEN, u, (size_t)(k + 1) * sizeof *u);
        tlen[nt++] = k + 1;
      }
    }
    if (k + 1 < T) u[++k] = -1;
  }
out:
  free(wi);
  free(wr);
  free(a);
  free(prod);
  return nt;
}

/* The certificate: U = max over (j, i) of s sum |c_k| + ||r||_1 / delta,
 * r = Y_i v_j - s sum c_k v_k, in ball arithmetic; rounded up. */
static double certify(const poly_ws *p, double delta) {
  const slong n = (slong)p->n, prec = 128;
  arb_ptr y = _arb_vec_init(n), v = _arb_vec_init(n), row = _arb_vec_init(n);
  arb_t t, b, U, sv, dv;
  arf_t ub;
  arb_init(sv);
  arb_init(dv);
  arb_set_d(sv, p->s);
  arb_set_d(dv, delta);
  arb_init(t);
  arb_init(b);
  arb_init(U);
  arf_init(ub);
  arb_zero(U);
  int ok = 1;
  for (size_t j = 0; j < p->nv && ok; j++) {
    const double *vj = p->vert + j * p->n;
    for (slong l = 0; l < n; l++)
      arb_set_d(v + l, vj[l]);
    for (size_t i = 0; i < p->m && ok; i++) {
      const int cnt = p->rec_len[j * p->m + i];
      if (cnt < 0) {
        ok = 0;
        break;
      }
      const double *Yi = p->Y[i];
      for (slong a = 0; a < n; a++) {
        for (slong c = 0; c < n; c++)
          arb_set_d(row + c, Yi[a * n + c]);
        arb_dot(y + a, NULL, 0, row, 1, v, 1, n, prec);
      }
      arb_zero(b);
      const size_t off = p->rec_off[j * p->m + i];
      for (int q = 0; q < cnt; q++) {
        const double *vk = p->vert + (size_t)p->cidx[off + q] * p->n;
        arb_set_d(t, p->cval[off + q]);
        arb_mul(t, t, sv, prec); /* s c_k, exact in 128 bits */
        for (slong a = 0; a < n; a++) {
          arb_set_d(row, vk[a]);
          arb_submul(y + a, t, row, prec);
        }
        arb_abs(t, t);
        arb_add(b, b, t, prec);
      }
      /* b = s sum |c_k| + ||r||_1 / delta */
      arb_zero(t);
      for (slong a = 0; a < n; a++) {
        arb_abs(row, y + a);
        arb_add(t, t, row, prec);
      }
      arb_div(t, t, dv, prec);
      arb_add(b, b, t, prec);
      if (!arb_is_finite(b)) ok = 0;
      arb_max(U, U, b, prec);
    }
  }
  double out = INFINITY;
  if (ok) {
    arb_get_ubound_arf(ub, U, prec);
    out = arf_get_d(ub, ARF_RND_CEIL);
  }
  arf_clear(ub);
  arb_clear(U);
  arb_clear(b);
  arb_clear(t);
  arb_clear(dv);
  arb_clear(sv);
  _arb_vec_clear(row, n);
  _arb_vec_clear(v, n);
  _arb_vec_clear(y, n);
  return out;
}

static void ws_free(poly_ws *p) {
  if (p->lp) glp_delete_prob(p->lp);
  free(p->vert);
  free(p->rec_off);
  free(p->rec_len);
  free(p->gen);
  free(p->cidx);
  free(p->cval);
  free(p->ind);
  free(p->col);
}

/* How far the exploration got; the caller's, so that it is defined after
 * a jump out of GLPK. */
typedef struct {
  size_t next;   /* the next vertex whose images are tested */
  int ball_done; /* the ball vertices' images are tested */
} explore_pos;

/* Build the LP from the ball vertices delta e_l and the nr roots, then add
 * images breadth first until the hull is invariant, the cap or the
 * deadline; returns the stop code (ss_jsr_polytope_stop or STOP_NOMEM). */
static int explore(poly_ws *p, const double *roots, long nr, double delta,
                   double deadline, double *x, int *idx, double *val,
                   ss_jsr_polytope_result *out, explore_pos *pos) {
  const size_t n = p->n;
  p->lp = glp_create_prob();
  glp_set_obj_dir(p->lp, GLP_MIN);
  glp_add_rows(p->lp, (int)n);
  for (size_t l = 0; l < n; l++) {
    p->ind[l + 1] = (int)l + 1;
    glp_set_row_bnds(p->lp, (int)l + 1, GLP_FX, 0.0, 0.0);
  }
  /* the ball vertices delta e_l first (indices 0..n-1), then the roots */
  for (size_t l = 0; l < n; l++) {
    memset(x, 0, n * sizeof *x);
    x[l] = delta;
    add_vertex(p, x);
  }
  for (long r = 0; r < nr; r++)
    add_vertex(p, roots + (size_t)r * n);
  glp_std_basis(p->lp);

  /* breadth first over the vertices in the order they were added; the ball
   * vertices last (their images are small, and by then the hull is large) */
  int stop = -1;
  while (stop < 0) {
    if (pos->next < p->nv) {
      stop = test_images(p, pos->next++, x, idx, val, &out->lps, &out->max_out);
    } else if (!pos->ball_done) {
      pos->ball_done = 1;
      for (size_t b = 0; b < n && stop < 0; b++)
        stop = test_images(p, b, x, idx, val, &out->lps, &out->max_out);
    } else {
      stop = SS_POLY_CLOSED;
    }
    if (stop < 0 && deadline > 0 && ss_clock_wall() > deadline) stop = SS_POLY_TIME;
  }
  return stop;
}

/* GLPK has no error return for running out of memory (or for its internal
 * errors): it calls this hook, then aborts if the hook returns.  The hook
 * jumps back to explore_guarded instead (GLPK's documented way out). */
static void on_glpk_error(void *info) {
  longjmp(*(jmp_buf *)info, 1);
}

/* GLPK's terminal output: kept (the first line, for an error's message),
 * never printed. */
static int on_glpk_output(void *info, const char *text) {
  char *said = info;
  if (!*said) {
    snprintf(said, 160, "%s", text);
    said[strcspn(said, "\n")] = '\0';
  }
  return 1;
}

/* explore with GLPK's terminal output caught and its errors turned into
 * STOP_GLPK, so that the library neither prints nor aborts.  Nothing in this
 * frame changes after setjmp. */
static int explore_guarded(poly_ws *p, const double *roots, long nr, double delta,
                           double deadline, double *x, int *idx, double *val,
                           ss_jsr_polytope_result *out, explore_pos *pos) {
  jmp_buf jb;
  p->glpk_says[0] = '\0';
  glp_term_hook(on_glpk_output, p->glpk_says);
  if (setjmp(jb)) {
    /* GLPK's state is undefined after the jump: glp_free_env frees all of
     * this thread's GLPK memory, this problem's included (and the hooks) */
    glp_free_env();
    p->lp = NULL;
    return STOP_GLPK;
  }
  glp_error_hook(on_glpk_error, &jb);
  const int stop = explore(p, roots, nr, delta, deadline, x, idx, val, out, pos);
  glp_error_hook(NULL, NULL);
  glp_term_hook(NULL, NULL);
  return stop;
}

/* The arguments of ss_jsr_polytope checked; SS_EINPUT with the reason. */
static ss_status poly_validate(size_t m, size_t n, const double *const *Y, const int *w,
                               int len, const ss_jsr_polytope_opts *o, ss_error *err) {
  if (m < 1 || n < 1 || !Y)
    return ss_error_set(err, SS_EINPUT, "jsr polytope: no matrices (m = %zu, n = %zu)", m,
                        n);
  if (n > 4096)
    return ss_error_set(err, SS_EINPUT, "jsr polytope: order %zu above 4096", n);
  if (!w || len < 1)
    return ss_error_set(err, SS_EINPUT, "jsr polytope: no candidate word");
  for (int t = 0; t < len; t++)
    if (w[t] < 0 || (size_t)w[t] >= m)
      return ss_error_set(err, SS_EINPUT,
                          "jsr polytope: letter %d of the word is %d, not in 0..%zu",
                          t + 1, w[t], m - 1);
  for (size_t i = 0; i < m; i++)
    if (!Y[i])
      return ss_error_set(err, SS_EINPUT, "jsr polytope: matrix %zu missing", i + 1);
  if (!(o->near >= 0 && o->near < 1))
    return ss_error_set(err, SS_EINPUT, "jsr polytope: near %g not in [0, 1)", o->near);
  if (!(o->eps > 0) || !isfinite(o->eps) || !(o->delta > 0) || !isfinite(o->delta))
    return ss_error_set(err, SS_EINPUT,
                        "jsr polytope: eps %g and delta %g must be positive and finite",
                        o->eps, o->delta);
  if (o->max_vertices < n + 1 || o->max_vertices > (size_t)1 << 25)
    return ss_error_set(err, SS_EINPUT,
                        "jsr polytope: vertex cap %zu not in %zu..2^25 (the %zu ball "
                        "vertices and a root)",
                        o->max_vertices, n + 1, n);
  return SS_OK;
}

/* The tied candidates' roots (find_ties) appended to the nr roots in *roots,
 * as far as the vertex cap allows; out->ties counts them. */
static ss_status add_tie_roots(poly_ws *p, const int *w, int len,
                               const ss_jsr_polytope_opts *o, double lambda,
                               double **roots, long *nr, ss_jsr_polytope_result *out,
                               ss_error *err) {
  const size_t n = p->n;
  int ties[TIE_MAX * TIE_MAXLEN], tlen[TIE_MAX];
  const int nt = find_ties(p, w, len, lambda * (1 - o->near), ties, tlen);
  if (nt == -2) return ss_error_nomem(err, "jsr polytope ties");
  if (nt == -1)
    return ss_error_set(err, SS_ENUMERIC,
                        "jsr polytope: LAPACK eigenvalues of a candidate failed");
  for (int t = 0; t < nt; t++) {
    double *more = NULL, lt;
    int ct;
    const long nm =
        make_roots(p, ties + (size_t)t * TIE_MAXLEN, tlen[t], o->eps, &lt, &ct, &more);
    if (nm == -2) return ss_error_nomem(err, "jsr polytope roots");
    if (nm > 0 && (size_t)(*nr + nm) + n <= p->cap) {
      double *cat = realloc(*roots, (size_t)(*nr + nm) * n * sizeof *cat);
      if (!cat) {
        free(more);
        return ss_error_nomem(err, "jsr polytope roots");
      }
      *roots = cat;
      memcpy(*roots + (size_t)*nr * n, more, (size_t)nm * n * sizeof *more);
      *nr += nm;
      out->ties++;
    }
    free(more);
  }
  return SS_OK;
}

/* The polytope's roots: lambda and the scale s first (make_roots needs s for
 * the cyclic images), then the candidate's roots and its ties'.  *done = 1
 * when the run ends here (out->stop SS_POLY_ZERO or SS_POLY_CAP). */
static ss_status gather_roots(poly_ws *p, const int *w, int len,
                              const ss_jsr_polytope_opts *o, ss_jsr_polytope_result *out,
                              double **roots, long *nr, int *done, ss_error *err) {
  double lambda = 0;
  int cplx = 0;
  *done = 0;
  /* a throwaway s: make_roots recomputes the images after s is known */
  p->s = 1;
  long n0 = make_roots(p, w, len, o->eps, &lambda, &cplx, roots);
  free(*roots);
  *roots = NULL;
  if (n0 == -2) return ss_error_nomem(err, "jsr polytope roots");
  if (n0 == -1)
    return ss_error_set(err, SS_ENUMERIC,
                        "jsr polytope: LAPACK eigenvalues of the candidate failed");
  if (n0 == 0) {
    out->stop = SS_POLY_ZERO;
    *done = 1;
    return SS_OK;
  }
  p->s = lambda * (1 + o->eps);
  out->lambda = lambda, out->s = p->s, out->complex_leading = cplx;
  *nr = make_roots(p, w, len, o->eps, &lambda, &cplx, roots);
  if (*nr == -2) return ss_error_nomem(err, "jsr polytope roots");
  if (*nr == -3 || (size_t)*nr + p->n > p->cap) {
    out->stop = SS_POLY_CAP;
    *done = 1;
    return SS_OK;
  }
  const ss_status st = add_tie_roots(p, w, len, o, lambda, roots, nr, out, err);
  if (st != SS_OK) return st;
  out->roots = (size_t)*nr;
  return SS_OK;
}

/* The polytope explored from the roots and, if it closed, its bound
 * certified. */
static ss_status explore_certify(poly_ws *p, const double *roots, long nr,
                                 const ss_jsr_polytope_opts *o, double deadline,
                                 ss_jsr_polytope_result *out, ss_error *err) {
  const size_t m = p->m, n = p->n;
  ss_status st = SS_OK;
  double *x = NULL, *val = NULL;
  int *idx = NULL;
  p->vert = malloc(p->cap * n * sizeof *p->vert);
  p->rec_off = malloc(p->cap * m * sizeof *p->rec_off);
  p->rec_len = malloc(p->cap * m * sizeof *p->rec_len);
  p->gen = calloc(p->cap, sizeof *p->gen);
  p->ind = malloc((n + 1) * sizeof *p->ind);
  p->col = malloc((n + 1) * sizeof *p->col);
  x = malloc(n * sizeof *x);
  idx = malloc(p->cap * sizeof *idx);
  val = malloc(p->cap * sizeof *val);
  if (!p->vert || !p->rec_off || !p->rec_len || !p->gen || !p->ind || !p->col || !x ||
      !idx || !val) {
    st = ss_error_nomem(err, "jsr polytope");
    goto done;
  }
  explore_pos pos = {n, 0};
  const int stop =
      explore_guarded(p, roots, nr, o->delta, deadline, x, idx, val, out, &pos);
  if (stop == STOP_GLPK) {
    st = ss_error_set(err, SS_ENOMEM, "jsr polytope: GLPK failed inside an LP: %s",
                      p->glpk_says[0] ? p->glpk_says : "no message");
    goto done;
  }
  if (stop == STOP_NOMEM) {
    st = ss_error_nomem(err, "jsr polytope coefficients");
    goto done;
  }
  out->stop = (ss_jsr_polytope_stop)stop;
  out->vertices = p->nv;
  out->depth = p->depth;
  out->pending = 0;
  if (stop != SS_POLY_CLOSED) {
    out->pending = (p->nv - pos.next) + (pos.ball_done ? 0 : n);
  } else {
    out->upper = certify(p, o->delta);
    if (!isfinite(out->upper)) out->stop = SS_POLY_LP;
  }
done:
  free(x);
  free(idx);
  free(val);
  return st;
}

ss_status ss_jsr_polytope(size_t m, size_t n, const double *const *Y, const int *w,
                          int len, const ss_jsr_polytope_opts *o,
                          ss_jsr_polytope_result *out, ss_error *err) {
  const double t0 = ss_clock_wall();
  ss_jsr_polytope_opts d = ss_jsr_polytope_defaults();
  if (!o) o = &d;
  if (!out) return ss_error_set(err, SS_EINPUT, "jsr polytope: no result given");
  memset(out, 0, sizeof *out);
  out->upper = INFINITY;
  ss_status st = poly_validate(m, n, Y, w, len, o, err);
  if (st != SS_OK) return st;
  const double deadline = o->max_seconds > 0 ? t0 + o->max_seconds : 0;

  poly_ws p;
  memset(&p, 0, sizeof p);
  p.m = m, p.n = n, p.Y = Y, p.cap = o->max_vertices;
  double *roots = NULL;
  long nr = 0;
  int done = 0;
  st = gather_roots(&p, w, len, o, out, &roots, &nr, &done, err);
  if (st == SS_OK && !done) st = explore_certify(&p, roots, nr, o, deadline, out, err);
  if (st == SS_OK) out->seconds = ss_clock_wall() - t0;
  ws_free(&p);
  free(roots);
  return st;
}
