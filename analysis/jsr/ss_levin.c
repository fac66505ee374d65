/* ss_levin.c — sub-patch subdivision matrices read from the global rule of a
 * refined face or edge star, and the Levin-Levin reduction.  The method and
 * its checks are in ss_levin.h. */
#include "ss_levin.h"

#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_eig.h"

#define MAXLEV 9 /* levels of the star refined at most */
#define PEEL                                                                             \
  12                     /* cells farther than this from the centre (grid                \
                            units, max-norm of the chart) are dropped before             \
                            each refinement from level 1 on */
#define STAT_TOL   1e-12 /* S_i on consecutive levels must agree to this */
#define ROWSUM_TOL 1e-12 /* rows of S_i must sum to 1 to this */

/* A vertex and its chart coordinates, for sorted lookup. */
typedef struct {
  ss_star_coord c; /* chart coordinates (level units) */
  size_t v;        /* vertex index */
} keyed;

/* One level of the refined star. */
typedef struct {
  ss_cx *cx;        /* complex (level 0: the star's) */
  ss_split *split;  /* parents of this level's vertices (NULL on level 0) */
  gsl_spmatrix *R;  /* operator to the next level (CSR), once built */
  ss_star_coord *x; /* chart coordinates, cx->nv */
  keyed *sorted;    /* vertices sorted by coordinates */
  double clean;     /* every cell of the unpeeled star whose corners lie
                       within this distance of the centre is present */
} level;

/* Workspace of one extraction. */
typedef struct {
  const ss_scheme *s; /* the scheme */
  ss_star *star;      /* the star, level 0 */
  ss_case_kind kind;  /* face or edge */
  int n;              /* edge valence (the chart's edge coordinate is n) */
  int nlev;           /* levels built */
  level L[MAXLEV];    /* levels */
} work;

static int by_coord(const void *a, const void *b) {
  return ss_star_coord_cmp(&((const keyed *)a)->c, &((const keyed *)b)->c);
}

/* Vertex of level L with coordinates c, or SIZE_MAX. */
static size_t find(const level *L, const ss_star_coord *c) {
  size_t lo = 0, hi = L->cx->nv;
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    const int r = ss_star_coord_cmp(&L->sorted[mid].c, c);
    if (r == 0) return L->sorted[mid].v;
    if (r < 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  return SIZE_MAX;
}

/* Dense value of coordinate k of c. */
static int32_t coord_at(const ss_star_coord *c, int k) {
  for (int i = 0; i < c->n; i++)
    if (c->idx[i] == k) return c->val[i];
  return 0;
}

/* a * x + b * y into *out; -1 if the result has too many nonzero entries. */
static int axpby(int a, const ss_star_coord *x, int b, const ss_star_coord *y,
                 ss_star_coord *out) {
  int32_t idx[2 * SS_STAR_MAXSUPP], val[2 * SS_STAR_MAXSUPP];
  int k = 0;
  for (int i = 0; i < x->n; i++) {
    idx[k] = x->idx[i];
    val[k++] = a * x->val[i] + b * coord_at(y, x->idx[i]);
  }
  for (int i = 0; i < y->n; i++)
    if (coord_at(x, y->idx[i]) == 0) {
      idx[k] = y->idx[i];
      val[k++] = b * y->val[i];
    }
  int m = 0;
  for (int i = 0; i < k; i++)
    if (val[i] != 0) {
      if (m == SS_STAR_MAXSUPP) return -1;
      idx[m] = idx[i];
      val[m++] = val[i];
    }
  *out = ss_star_coord_make(m, idx, val);
  return 0;
}

/* Max-norm distance of chart point c on level l from the centre: the face's
 * centroid 2^l (1, 1, 1, 0, 0) / 3, or the edge's midpoint 0. */
static double centre_dist(const work *W, const ss_star_coord *c, int l) {
  const double g = W->kind == SS_CASE_FACE ? ldexp(1.0, l) / 3.0 : 0.0;
  double d = 0;
  for (int k = 0; k < (W->kind == SS_CASE_FACE ? 3 : 0); k++)
    d = fmax(d, fabs(coord_at(c, k) - g));
  for (int i = 0; i < c->n; i++)
    if (W->kind != SS_CASE_FACE || c->idx[i] > 2) d = fmax(d, fabs((double)c->val[i]));
  return d;
}

/* Grid steps from chart point c on level l to the boundary of the refined
 * (peeled) star: the smallest barycentric coordinate of the star's outer
 * faces (face star: x_0, x_1, x_2; edge star: the weights of the edge's two
 * ends, (2^l - sum_{k<n} x_k -+ x_n) / 2), and the distance to the peeled
 * region. */
static double margin(const work *W, const ss_star_coord *c, int l) {
  double m;
  if (W->kind == SS_CASE_FACE) {
    m = fmin(coord_at(c, 0), fmin(coord_at(c, 1), coord_at(c, 2)));
  } else {
    double s = 0;
    for (int i = 0; i < c->n; i++)
      if (c->idx[i] < W->n) s += c->val[i];
    const double N = ldexp(1.0, l), xn = coord_at(c, W->n);
    m = fmin(N - s - xn, N - s + xn) / 2;
  }
  return fmin(m, W->L[l].clean - centre_dist(W, c, l));
}

/* Drop the cells of level l with a corner farther than PEEL from the centre
 * (their vertices stay, in no cell, and get the identity row; margin keeps
 * every row read away from them). */
static void peel(work *W, int l) {
  level *L = W->L + l;
  ss_cx *cx = L->cx;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    const int nv = ss_cell_nverts((ss_cell_type)t);
    size_t kept = 0;
    for (size_t i = 0; i < cx->nc[t]; i++) {
      const ss_idx *v = cx->cells[t] + i * (size_t)nv;
      int far = 0;
      for (int j = 0; j < nv && !far; j++)
        far = centre_dist(W, L->x + v[j], l) > PEEL;
      if (far) continue;
      memmove(cx->cells[t] + kept * (size_t)nv, v, (size_t)nv * sizeof *v);
      if (cx->cref[t]) cx->cref[t][kept] = cx->cref[t][i];
      kept++;
    }
    cx->nc[t] = kept;
  }
  L->clean = fmin(L->clean, PEEL);
}

/* Sorted lookup table of level L. */
static ss_status sort_level(level *L, ss_error *err) {
  const size_t nv = L->cx->nv;
  L->sorted = malloc((nv + 1) * sizeof *L->sorted);
  if (!L->sorted) return ss_error_nomem(err, "sub-patch lookup");
  for (size_t v = 0; v < nv; v++) {
    L->sorted[v].c = L->x[v];
    L->sorted[v].v = v;
  }
  qsort(L->sorted, nv, sizeof *L->sorted, by_coord);
  for (size_t i = 1; i < nv; i++)
    if (!ss_star_coord_cmp(&L->sorted[i - 1].c, &L->sorted[i].c))
      return ss_error_set(err, SS_EINTERNAL, "two vertices share chart coordinates");
  return SS_OK;
}

/* Refine the last level once (peeled first from level 1 on). */
static ss_status add_level(work *W, ss_error *err) {
  if (W->nlev == MAXLEV)
    return ss_error_set(err, SS_EINTERNAL,
                        "no stationary sub-patch matrices within %d levels", MAXLEV - 2);
  level *C = W->L + W->nlev - 1, *F = W->L + W->nlev;
  if (W->nlev > 1) peel(W, W->nlev - 1);
  ss_status st = ss_scheme_refine_split(W->s, C->cx, &F->cx, &C->R, &F->split, err);
  if (st) return st;
  W->nlev++;
  /* a vertex within clean - 2 of the centre has all its cells (the corners of
   * a cell differ by at most 2 in a chart coordinate: 2 along an edge star's
   * edge, 1 otherwise), so every fine cell within 2 (clean - 2) lies in a
   * present coarse cell */
  F->clean = 2 * (C->clean - 2);
  const size_t nf = F->cx->nv;
  F->x = malloc((nf + 1) * sizeof *F->x);
  if (!F->x) return ss_error_nomem(err, "chart coordinates");
  for (size_t f = 0; f < nf; f++) {
    /* 2 * (mean of the parents) = (2 / np) * (sum of the parents) */
    const size_t np = ss_split_npar(F->split, f);
    ss_star_coord sum = ss_star_coord_make(0, NULL, NULL);
    for (size_t i = 0; i < np; i++) {
      const ss_star_coord *p = C->x + F->split->parent[F->split->ptr[f] + i];
      if (axpby(1, &sum, 1, p, &sum))
        return ss_error_set(err, SS_EINTERNAL, "parent sum of vertex %zu too wide", f);
    }
    int32_t val[SS_STAR_MAXSUPP];
    for (int i = 0; i < sum.n; i++) {
      if ((2 * sum.val[i]) % (int32_t)np)
        return ss_error_set(err, SS_EINTERNAL, "vertex %zu has no integer coordinates",
                            f);
      val[i] = 2 * sum.val[i] / (int32_t)np;
    }
    F->x[f] = ss_star_coord_make(sum.n, sum.idx, val);
  }
  return sort_level(F, err);
}

static void free_work(work *W) {
  for (int l = 0; l < W->nlev; l++) {
    level *L = W->L + l;
    if (l > 0) {
      ss_cx_free(L->cx);
      free(L->x);
    }
    ss_split_free(L->split);
    if (L->R) gsl_spmatrix_free(L->R);
    free(L->sorted);
  }
  ss_star_free(W->star);
}

/* ---- the sub-patch matrices on levels (l, l + 1) ---- */

/* Corner of the patch on level l and the offsets of the sub-patches' corners
 * (level l + 1) from twice it; returns the number of sub-patches. */
static size_t patch_frame(const work *W, int l, ss_star_coord *corner,
                          ss_star_coord *shift) {
  if (W->kind == SS_CASE_FACE) {
    const int32_t N = (int32_t)1 << l, a = N / 3;
    const int32_t idx[3] = {0, 1, 2}, val[3] = {N - 2 * a, a, a};
    *corner = ss_star_coord_make(3, idx, val);
    for (int i = 0; i < 4; i++) {
      const int32_t s = i & 1, t = i >> 1, sv[3] = {-s - t, s, t};
      int32_t si[3], sw[3], k = 0;
      for (int q = 0; q < 3; q++)
        if (sv[q]) si[k] = q, sw[k++] = sv[q];
      shift[i] = ss_star_coord_make(k, si, sw);
    }
    return 4;
  }
  const int32_t e = W->n, two = 2;
  *corner = ss_star_coord_make(0, NULL, NULL);
  shift[0] = ss_star_coord_make(0, NULL, NULL);
  shift[1] = ss_star_coord_make(1, &e, &two);
  return 2;
}

/* The patch's corners relative to its own corner (the seed of the support). */
static size_t patch_seed(const work *W, ss_star_coord *seed) {
  if (W->kind == SS_CASE_FACE) {
    const int32_t i01[2] = {0, 1}, i02[2] = {0, 2}, i012[3] = {0, 1, 2};
    const int32_t v1[2] = {-1, 1}, v2[3] = {-2, 1, 1};
    seed[0] = ss_star_coord_make(0, NULL, NULL);
    seed[1] = ss_star_coord_make(2, i01, v1);
    seed[2] = ss_star_coord_make(2, i02, v1);
    seed[3] = ss_star_coord_make(3, i012, v2);
    return 4;
  }
  const int32_t e = W->n, two = 2;
  seed[0] = ss_star_coord_make(0, NULL, NULL);
  seed[1] = ss_star_coord_make(1, &e, &two);
  return 2;
}

/* Canonical order of support labels: by distance from the corner, then by
 * coordinates. */
static int label_order(const void *a, const void *b) {
  const ss_star_coord *x = a, *y = b;
  const int nx = ss_local_label_norm(x), ny = ss_local_label_norm(y);
  if (nx != ny) return nx < ny ? -1 : 1;
  return ss_star_coord_cmp(x, y);
}

static size_t label_find(const ss_star_coord *P, size_t n, const ss_star_coord *c) {
  for (size_t i = 0; i < n; i++)
    if (!ss_star_coord_cmp(P + i, c)) return i;
  return SIZE_MAX;
}

enum { OK = 0, ROOM = 1, HARD = 2 };

/* Read the support and the sub-patch matrices on levels (l, l + 1).  *P (n
 * labels) and S[i] (n x n) are new arrays.  ROOM if a row would be read too
 * near the star's boundary or a point is missing, HARD with err set. */
static int read_maps(const work *W, int l, ss_star_coord **P_out, size_t *n_out,
                     double **S, ss_error *err) {
  const level *C = W->L + l, *F = W->L + l + 1;
  ss_star_coord corner, shift[SS_LEVIN_MAXMAPS], fc[SS_LEVIN_MAXMAPS];
  const size_t m = patch_frame(W, l, &corner, shift);
  const double need = 2.0 * ss_scheme_reach(W->s) + 2.0;
  size_t cap = 64, n;
  ss_star_coord *P = malloc(cap * sizeof *P);
  if (!P) return ss_error_nomem(err, "support"), HARD;
  n = patch_seed(W, P);
  for (size_t i = 0; i < m; i++)
    if (axpby(2, &corner, 1, shift + i, fc + i)) {
      free(P);
      return ss_error_set(err, SS_EINTERNAL, "sub-patch corner too wide"), HARD;
    }
  /* closure: every row of a point of a sub-patch's support reads the support */
  for (size_t done = 0; done < n;) {
    const size_t upto = n;
    for (size_t p = done; p < upto; p++)
      for (size_t i = 0; i < m; i++) {
        ss_star_coord a;
        if (axpby(1, fc + i, 1, P + p, &a)) goto room;
        const size_t f = find(F, &a);
        if (f == SIZE_MAX || margin(W, &a, l + 1) < need) goto room;
        for (int q = C->R->p[f]; q < C->R->p[f + 1]; q++) {
          if (C->R->data[q] == 0.0) continue;
          ss_star_coord rel;
          if (axpby(1, C->x + C->R->i[q], -1, &corner, &rel)) goto room;
          if (label_find(P, n, &rel) != SIZE_MAX) continue;
          if (n == cap) {
            ss_star_coord *t = realloc(P, 2 * cap * sizeof *P);
            if (!t) {
              free(P);
              return ss_error_nomem(err, "support"), HARD;
            }
            P = t, cap *= 2;
          }
          P[n++] = rel;
        }
      }
    done = upto;
  }
  qsort(P, n, sizeof *P, label_order);
  for (size_t i = 0; i < m; i++) {
    S[i] = calloc(n * n, sizeof **S);
    if (!S[i]) {
      for (size_t k = 0; k <= i; k++)
        free(S[k]), S[k] = NULL;
      free(P);
      return ss_error_nomem(err, "sub-patch matrices"), HARD;
    }
    for (size_t r = 0; r < n; r++) {
      ss_star_coord a;
      axpby(1, fc + i, 1, P + r, &a); /* succeeded in the closure */
      const size_t f = find(F, &a);
      double sum = 0;
      for (int q = C->R->p[f]; q < C->R->p[f + 1]; q++) {
        ss_star_coord rel;
        axpby(1, C->x + C->R->i[q], -1, &corner, &rel);
        const size_t c = label_find(P, n, &rel);
        if (c == SIZE_MAX) {
          if (C->R->data[q] == 0.0) continue;
          for (size_t k = 0; k <= i; k++)
            free(S[k]), S[k] = NULL;
          free(P);
          return ss_error_set(err, SS_EINTERNAL,
                              "S_%zu is not square: row %zu reads outside the support",
                              i + 1, r),
                 HARD;
        }
        S[i][r * n + c] += C->R->data[q];
        sum += C->R->data[q];
      }
      if (fabs(sum - 1) > ROWSUM_TOL) {
        for (size_t k = 0; k <= i; k++)
          free(S[k]), S[k] = NULL;
        free(P);
        return ss_error_set(err, SS_EINTERNAL, "row %zu of S_%zu sums to %.17g, not 1", r,
                            i + 1, sum),
               HARD;
      }
    }
  }
  *P_out = P;
  *n_out = n;
  return OK;
room:
  free(P);
  return ROOM;
}

/* ---- the reduction ---- */

ss_status ss_levin_reduce(size_t m, size_t n, const double *const *S, const double *V,
                          size_t r, double tol, double **Y, double *defect,
                          ss_error *err) {
  for (size_t i = 0; i < m; i++)
    Y[i] = NULL;
  *defect = 0;
  if (r == 0 || r >= n)
    return ss_error_set(err, SS_EINPUT, "subspace of dimension %zu in %zu", r, n);
  ss_status st = SS_OK;
  const size_t c = n - r;
  double *Q = calloc(n * n, sizeof *Q), *tau = malloc(r * sizeof *tau);
  double *T = malloc(n * n * sizeof *T), *SV = malloc(n * r * sizeof *SV);
  if (!Q || !tau || !T || !SV) {
    st = ss_error_nomem(err, "Levin-Levin reduction");
    goto done;
  }
  /* V = Q [R; 0]: factor in the first r columns of Q, then form all of Q */
  for (size_t i = 0; i < n; i++)
    memcpy(Q + i * n, V + i * r, r * sizeof *Q);
  if (LAPACKE_dgeqrf(LAPACK_ROW_MAJOR, (lapack_int)n, (lapack_int)r, Q, (lapack_int)n,
                     tau)) {
    st = ss_error_set(err, SS_ENUMERIC, "QR factorisation of the subspace failed");
    goto done;
  }
  double rmax = 0;
  for (size_t k = 0; k < r; k++)
    rmax = fmax(rmax, fabs(Q[k * n + k]));
  for (size_t k = 0; k < r; k++)
    if (!(fabs(Q[k * n + k]) > 1e-10 * rmax)) {
      st = ss_error_set(err, SS_EINTERNAL,
                        "the subspace basis is rank deficient (column %zu of %zu)", k + 1,
                        r);
      goto done;
    }
  if (LAPACKE_dorgqr(LAPACK_ROW_MAJOR, (lapack_int)n, (lapack_int)n, (lapack_int)r, Q,
                     (lapack_int)n, tau)) {
    st = ss_error_set(err, SS_ENUMERIC, "forming the orthogonal complement failed");
    goto done;
  }
  /* Q_2 = columns r..n-1 of Q */
  for (size_t i = 0; i < m; i++) {
    /* T = S_i Q_2 (n x c), SV = S_i V (n x r) */
    double svmax = 0, dmax = 0;
    for (size_t a = 0; a < n; a++) {
      const double *s = S[i] + a * n;
      for (size_t b = 0; b < c; b++) {
        double t = 0;
        for (size_t k = 0; k < n; k++)
          t += s[k] * Q[k * n + r + b];
        T[a * c + b] = t;
      }
      for (size_t b = 0; b < r; b++) {
        double t = 0;
        for (size_t k = 0; k < n; k++)
          t += s[k] * V[k * r + b];
        SV[a * r + b] = t;
        svmax = fmax(svmax, fabs(t));
      }
    }
    /* the lower-left block Q_2^T S_i V must vanish */
    for (size_t a = 0; a < c; a++)
      for (size_t b = 0; b < r; b++) {
        double t = 0;
        for (size_t k = 0; k < n; k++)
          t += Q[k * n + r + a] * SV[k * r + b];
        dmax = fmax(dmax, fabs(t));
      }
    const double d = svmax > 0 ? dmax / svmax : dmax;
    *defect = fmax(*defect, d);
    if (!(d <= tol)) {
      st = ss_error_set(err, SS_EINTERNAL,
                        "the subspace is not invariant under S_%zu: relative defect %.3g "
                        "> %.3g",
                        i + 1, d, tol);
      goto done;
    }
    Y[i] = malloc(c * c * sizeof **Y);
    if (!Y[i]) {
      st = ss_error_nomem(err, "Levin-Levin blocks");
      goto done;
    }
    for (size_t a = 0; a < c; a++)
      for (size_t b = 0; b < c; b++) {
        double t = 0;
        for (size_t k = 0; k < n; k++)
          t += Q[k * n + r + a] * T[k * c + b];
        Y[i][a * c + b] = t;
      }
  }
done:
  if (st)
    for (size_t i = 0; i < m; i++)
      free(Y[i]), Y[i] = NULL;
  free(Q), free(tau), free(T), free(SV);
  return st;
}

/* ---- the subspace ---- */

/* Face: the 10 quadratic monomials in the positions (centred at the support's
 * mean, scaled to unit size for conditioning). */
static void quadratics(const ss_levin *L, double *V) {
  double c[3] = {0, 0, 0}, s = 0;
  for (size_t i = 0; i < L->n; i++)
    for (int k = 0; k < 3; k++)
      c[k] += L->pos[3 * i + k] / (double)L->n;
  for (size_t i = 0; i < L->n; i++)
    for (int k = 0; k < 3; k++)
      s = fmax(s, fabs(L->pos[3 * i + k] - c[k]));
  for (size_t i = 0; i < L->n; i++) {
    double x[3];
    for (int k = 0; k < 3; k++)
      x[k] = (L->pos[3 * i + k] - c[k]) / s;
    double *v = V + i * 10;
    v[0] = 1, v[1] = x[0], v[2] = x[1], v[3] = x[2];
    v[4] = x[0] * x[0], v[5] = x[0] * x[1], v[6] = x[0] * x[2];
    v[7] = x[1] * x[1], v[8] = x[1] * x[2], v[9] = x[2] * x[2];
  }
}

typedef struct {
  double re, im; /* eigenvalue */
  size_t k;      /* its index in dgeev's output */
} eigval;

static int by_modulus_desc(const void *a, const void *b) {
  const eigval *x = a, *y = b;
  const double mx = hypot(x->re, x->im), my = hypot(y->re, y->im);
  if (mx != my) return mx > my ? -1 : 1;
  return x->re > y->re ? -1 : (x->re < y->re);
}

/* The eigenvectors of S_1 for its r dominant eigenvalues, which must be
 * 1, lambda, lambda, 1/2 in some order after the 1 (edge, r = 4; sets lambda1
 * and the threshold lambda_3 = the smallest of the three subdominant ones)
 * or 1, 1/2 x3, 1/4 x6 (face, r = 10), all real, with |the next| below the
 * last (a gap, so the subspace is well defined). */
static ss_status dominant_subspace(ss_levin *L, double *V, ss_error *err) {
  const size_t n = L->n, r = L->r;
  ss_status st = SS_OK;
  double *A = malloc(n * n * sizeof *A), *wr = malloc(n * sizeof *wr);
  double *wi = malloc(n * sizeof *wi), *vr = malloc(n * n * sizeof *vr);
  eigval *ev = malloc(n * sizeof *ev);
  if (!A || !wr || !wi || !vr || !ev) {
    st = ss_error_nomem(err, "dominant eigenvectors");
    goto done;
  }
  memcpy(A, L->S[0], n * n * sizeof *A);
  if (LAPACKE_dgeev(LAPACK_ROW_MAJOR, 'N', 'V', (lapack_int)n, A, (lapack_int)n, wr, wi,
                    NULL, 1, vr, (lapack_int)n)) {
    st = ss_error_set(err, SS_ENUMERIC, "eigenvectors of S_1 failed (dgeev)");
    goto done;
  }
  for (size_t k = 0; k < n; k++)
    ev[k] = (eigval){wr[k], wi[k], k};
  qsort(ev, n, sizeof *ev, by_modulus_desc);
  const double tol = 1e-8;
  int ok = n > r && fabs(ev[0].re - 1) <= tol;
  for (size_t k = 0; k < r && ok; k++)
    ok = fabs(ev[k].im) <= tol;
  if (ok && L->kind == SS_CASE_FACE) {
    for (size_t k = 1; k < r && ok; k++)
      ok = fabs(ev[k].re - (k < 4 ? 0.5 : 0.25)) <= tol;
    ok = ok && hypot(ev[r].re, ev[r].im) < 0.25 - tol;
  } else if (ok) {
    int half = -1;
    for (int k = 1; k < 4; k++)
      if (fabs(ev[k].re - 0.5) <= tol && half < 0) half = k;
    double pair[2] = {0, 0};
    int np = 0;
    for (int k = 1; k < 4 && half > 0; k++)
      if (k != half) pair[np++] = ev[k].re;
    ok = half > 0 && fabs(pair[0] - pair[1]) <= tol * fmax(1, fabs(pair[0]));
    L->lambda1 = 0.5 * (pair[0] + pair[1]);
    L->threshold = fmin(L->lambda1, 0.5);
    ok = ok && hypot(ev[r].re, ev[r].im) < L->threshold - tol;
  }
  if (!ok) {
    char buf[512];
    size_t used = 0;
    for (size_t k = 0; k <= r && k < n && used < sizeof buf; k++)
      used += (size_t)snprintf(buf + used, sizeof buf - used, "%s%.6g%+.2gi",
                               k ? ", " : "", ev[k].re, ev[k].im);
    st = ss_error_set(err, SS_EINTERNAL,
                      "the %zu dominant eigenvalues of S_1 are not %s (then %s the "
                      "next): %s",
                      r,
                      L->kind == SS_CASE_FACE ? "1, 1/2 x3, 1/4 x6"
                                              : "1, lambda, lambda, 1/2 in some order",
                      "strictly above", buf);
    goto done;
  }
  for (size_t i = 0; i < n; i++)
    for (size_t k = 0; k < r; k++)
      V[i * r + k] = vr[i * n + ev[k].k];
done:
  free(A), free(wr), free(wi), free(vr), free(ev);
  return st;
}

/* The eigenvalues of S_1 on span(V): of M = V^+ S_1 V (least squares). */
static ss_status theta(ss_levin *L, ss_error *err) {
  const size_t n = L->n, r = L->r;
  ss_status st = SS_OK;
  double *A = malloc(n * r * sizeof *A), *B = malloc(n * r * sizeof *B);
  double *re = malloc(r * sizeof *re), *im = malloc(r * sizeof *im);
  if (!A || !B || !re || !im) {
    st = ss_error_nomem(err, "eigenvalues on the subspace");
    goto done;
  }
  memcpy(A, L->V, n * r * sizeof *A);
  for (size_t a = 0; a < n; a++)
    for (size_t b = 0; b < r; b++) {
      double t = 0;
      for (size_t k = 0; k < n; k++)
        t += L->S[0][a * n + k] * L->V[k * r + b];
      B[a * r + b] = t;
    }
  if (LAPACKE_dgels(LAPACK_ROW_MAJOR, 'N', (lapack_int)n, (lapack_int)r, (lapack_int)r, A,
                    (lapack_int)r, B, (lapack_int)r)) {
    st = ss_error_set(err, SS_ENUMERIC, "least squares on the subspace failed");
    goto done;
  }
  /* the first r rows of B hold M */
  st = ss_eig_dense(B, r, re, im, err);
  if (st) goto done;
  for (size_t i = 0; i < r; i++)
    L->theta[i] = re[i];
  for (size_t i = 1; i < r; i++)
    for (size_t j = i; j > 0 && L->theta[j] > L->theta[j - 1]; j--) {
      const double t = L->theta[j];
      L->theta[j] = L->theta[j - 1], L->theta[j - 1] = t;
    }
done:
  free(A), free(B), free(re), free(im);
  return st;
}

/* ---- the whole case ---- */

void ss_levin_free(ss_levin *L) {
  if (!L) return;
  for (int i = 0; i < SS_LEVIN_MAXMAPS; i++)
    free(L->S[i]), free(L->Y[i]);
  free(L->label), free(L->pos), free(L->V);
  free(L);
}

/* Whether the maps read on two consecutive level pairs agree. */
static int same_maps(size_t m, size_t n, const ss_star_coord *P, double *const *S,
                     size_t n2, const ss_star_coord *P2, double *const *S2) {
  if (n != n2) return 0;
  for (size_t i = 0; i < n; i++)
    if (ss_star_coord_cmp(P + i, P2 + i)) return 0;
  for (size_t i = 0; i < m; i++)
    for (size_t k = 0; k < n * n; k++)
      if (fabs(S[i][k] - S2[i][k]) > STAT_TOL) return 0;
  return 1;
}

ss_status ss_levin_new(const ss_scheme *s, const ss_case *c, ss_levin **out,
                       ss_error *err) {
  *out = NULL;
  if (c->kind != SS_CASE_FACE && c->kind != SS_CASE_EDGE)
    return ss_error_set(err, SS_EINPUT,
                        "the Levin-Levin reduction is built for the face and edge "
                        "cases only, not %s",
                        ss_case_name(c->kind));
  work W;
  memset(&W, 0, sizeof W);
  W.s = s;
  W.kind = c->kind;
  W.n = c->n;
  ss_levin *L = calloc(1, sizeof *L);
  ss_star_coord *P2 = NULL;
  double *S2[SS_LEVIN_MAXMAPS] = {NULL};
  size_t n2 = 0;
  ss_status st = L ? SS_OK : ss_error_nomem(err, "Levin-Levin case");
  if (!st) st = ss_case_star(s, c, &W.star, err);
  if (st) goto done;
  if (ss_cx_ncells(W.star->cx) && W.star->cell_type != SS_TET) {
    st = ss_error_set(err, SS_EINPUT,
                      "scheme %s: the sub-patch maps are built for tet stars only "
                      "(schemes with the tet/oct split)",
                      ss_scheme_name(s));
    goto done;
  }
  W.L[0].cx = W.star->cx;
  W.L[0].x = W.star->coord;
  W.L[0].clean = 1e9;
  W.nlev = 1;
  if ((st = sort_level(W.L, err))) goto done;
  L->kind = c->kind;
  for (int j = c->kind == SS_CASE_FACE ? 2 : 1;; j++) {
    while (W.nlev < j + 3)
      if ((st = add_level(&W, err))) goto done;
    for (size_t i = 0; i < SS_LEVIN_MAXMAPS; i++) {
      free(L->S[i]), free(S2[i]);
      L->S[i] = S2[i] = NULL;
    }
    free(L->label), free(P2);
    L->label = P2 = NULL;
    int a = read_maps(&W, j, &L->label, &L->n, L->S, err);
    if (a == HARD) {
      st = err ? err->status : SS_EINTERNAL;
      goto done;
    }
    if (a == ROOM) continue;
    a = read_maps(&W, j + 1, &P2, &n2, S2, err);
    if (a == HARD) {
      st = err ? err->status : SS_EINTERNAL;
      goto done;
    }
    if (a == ROOM) continue;
    L->m = c->kind == SS_CASE_FACE ? 4 : 2;
    if (!same_maps(L->m, L->n, L->label, L->S, n2, P2, S2)) continue;
    L->level = j;
    break;
  }
  L->pos = malloc(3 * L->n * sizeof *L->pos);
  L->r = c->kind == SS_CASE_FACE ? 10 : 4;
  L->V = malloc(L->n * L->r * sizeof *L->V);
  if (!L->pos || !L->V) {
    st = ss_error_nomem(err, "Levin-Levin subspace");
    goto done;
  }
  for (size_t i = 0; i < L->n; i++)
    ss_star_coord_position(W.star, L->label + i, 1.0, L->pos + 3 * i);
  /* face: the quadratic polynomials, if the scheme keeps them; otherwise (and
   * for edges) the dominant eigenvectors of S_1, as the paper builds W */
  L->basis = "eigenvectors";
  if (c->kind == SS_CASE_FACE) {
    L->threshold = 0.25;
    L->lambda1 = 0.5;
    quadratics(L, L->V);
    ss_error e2 = {0};
    if (!ss_levin_reduce(L->m, L->n, (const double *const *)L->S, L->V, L->r,
                         SS_LEVIN_TOL, L->Y, &L->defect, &e2)) {
      L->basis = "quadratics";
      st = theta(L, err);
      goto done;
    }
  }
  if ((st = dominant_subspace(L, L->V, err))) goto done;
  if ((st = ss_levin_reduce(L->m, L->n, (const double *const *)L->S, L->V, L->r,
                            SS_LEVIN_TOL, L->Y, &L->defect, err)))
    goto done;
  st = theta(L, err);
done:
  for (size_t i = 0; i < SS_LEVIN_MAXMAPS; i++)
    free(S2[i]);
  free(P2);
  W.L[0].x = NULL; /* the star's */
  free_work(&W);
  if (st) {
    ss_levin_free(L);
    L = NULL;
  }
  *out = L;
  return st;
}

void ss_levin_verdict(const ss_levin *L, const ss_jsr_result *r, ss_verdict *v) {
  *v = (ss_verdict){.verdict = SS_UNDECIDED, .on = SS_ON_JSR};
  if (r->upper < L->threshold) {
    v->verdict = SS_PASS;
  } else if (r->lower >= L->threshold) {
    v->verdict = SS_FAIL;
    snprintf(v->reason, sizeof v->reason,
             "the joint spectral radius is at least %.6g, not below the threshold %.6g",
             r->lower, L->threshold);
  } else {
    snprintf(v->reason, sizeof v->reason,
             "the bounds [%.6g, %.6g] on the joint spectral radius contain the "
             "threshold %.6g",
             r->lower, r->upper, L->threshold);
  }
  v->certified = v->verdict != SS_UNDECIDED && r->certified;
}
