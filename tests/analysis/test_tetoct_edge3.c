/* test_tetoct_edge3.c — finding 9 (reports/README.md): the tet/oct edge of
 * valence 3, rebuilt without the program's scheme or extraction code.
 *
 * The refinement is written here from the tet/oct paper alone (section 2 and
 * figure 5): linear subdivision (a tet into 4 tets and an octahedron, an
 * octahedron into 6 octahedra and 8 tets around its centroid), then each
 * vertex the average over its cells of the cell's centroid mask (tet: -1/16
 * itself, 17/48 the others; octahedron: 3/8 itself, 1/12 the four
 * edge-adjacent, 7/24 the opposite one).  It runs on the star of three tets
 * around an edge AB (a convex bipyramid), vertices named by exact integer
 * positions of the linear split.  From level L to L + 1 it gives the rows of
 * the operator; the patch is the level-L segment [P, Q] of AB at its middle,
 * sigma_1 and sigma_2 the similarities x -> P + (x - P)/2 and
 * x -> (P + Q)/2 + (x - P)/2 onto the two halves, and the support the
 * smallest set U holding P and Q such that every row of a point of
 * sigma_i(U) reads only U (every such point strictly inside the bipyramid,
 * so its row is the infinite edge's).  S_i[a][b] is the weight of U[b] in
 * the row of sigma_i(U[a]).
 *
 * Checked, against properties and against the library:
 * - S_i square with unit row sums; S_1's leading eigenvalues 1, 1/2 and the
 *   double lambda1 = (63 + sqrt 801)/288 = 0.3170206..., i.e. 1/2 > lambda1
 *   (the order the paper's "1, lambda1, lambda1, 1/2" does not have), and the
 *   next one 0.2873777... (the largest root of
 *   186624 x^3 - 105408 x^2 + 17952 x - 883, a closed form of finding 9);
 * - the 4-dimensional leading invariant subspace of S_1 (ordered real Schur
 *   form) invariant under S_2; Y_i = Q2^T S_i Q2 on its orthogonal complement;
 * - the joint spectral radius of {Y_1, Y_2}: at least rho(Y_1) and at most
 *   max_{|w| = k} ||Y_w||_2^(1/k) for every k; the first k with that below
 *   lambda1 is found here (the paper's "rho^[k] < lambda3 for some k", in
 *   the 2-norm), so JSR < lambda1 = lambda3 without the program's bound;
 * - the library on the same case (ss_levin_new, ss_jsr_compute): the same
 *   support size, lambda1, threshold min(lambda1, 1/2), the same 2-norm
 *   profile rho_k (orthogonally invariant, so any orthonormal complement and
 *   any order of the support give it), and a proven upper bound between
 *   this rho(Y_1) and lambda1; ss_jsr_compute on the Y_i built here too.
 * - S_2 u = lambda1 u for S_1's lambda1-eigenvectors u (the across pair is
 *   not coupled to 1 or X);
 * - the rho-mode (eigenvalue 0.2873777...) not odd under the mirror through P:
 *   control values on P's cross-section not all zero.
 * A wrong weight, a wrong eigenvalue or a wrong reduction in the program
 * breaks the comparisons; a wrong key number of the finding breaks the
 * closed forms. */
#include <lapacke.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_jsr.h"
#include "ss_levin.h"
#include "ss_test.h"

/* ---- an independent tet/oct refinement on integer positions ---- */

typedef struct {
  int64_t (*p)[3]; /* positions, scaled so that every level's are integers */
  size_t n, cap;   /* vertices used and allocated */
  int64_t *hkey;   /* open-addressing hash: position -> id + 1 (0: empty) */
  size_t hcap;     /* slots of the hash (a power of two) */
  size_t *hval;    /* id + 1 per slot */
} vset;

typedef struct {
  int nv; /* 4 (tet) or 6 (octahedron: v[k] opposite v[k + 3]) */
  size_t v[6];
} cell;

typedef struct {
  cell *c;
  size_t n, cap;
} cells;

static uint64_t hpos(const int64_t *x) {
  uint64_t h = 1469598103934665603ull;
  for (int k = 0; k < 3; k++)
    h = (h ^ (uint64_t)x[k]) * 1099511628211ull;
  return h ^ (h >> 29);
}

static void vset_init(vset *s, size_t hcap) {
  memset(s, 0, sizeof *s);
  s->hcap = hcap;
  s->hkey = calloc(3 * hcap, sizeof *s->hkey);
  s->hval = calloc(hcap, sizeof *s->hval);
}

static void vset_free(vset *s) {
  free(s->p), free(s->hkey), free(s->hval);
}

/* The id of the vertex at x; added when `add`, else SIZE_MAX if absent. */
static size_t vset_id(vset *s, const int64_t *x, int add) {
  size_t i = hpos(x) & (s->hcap - 1);
  while (s->hval[i]) {
    if (!memcmp(s->hkey + 3 * i, x, 3 * sizeof *x)) return s->hval[i] - 1;
    i = (i + 1) & (s->hcap - 1);
  }
  if (!add) return SIZE_MAX;
  if (s->n == s->cap) {
    s->cap = s->cap ? 2 * s->cap : 1024;
    s->p = realloc(s->p, s->cap * sizeof *s->p);
  }
  memcpy(s->p[s->n], x, sizeof s->p[0]);
  memcpy(s->hkey + 3 * i, x, 3 * sizeof *x);
  s->hval[i] = ++s->n;
  return s->n - 1;
}

static void cells_add(cells *c, int nv, const size_t *v) {
  if (c->n == c->cap) {
    c->cap = c->cap ? 2 * c->cap : 1024;
    c->c = realloc(c->c, c->cap * sizeof *c->c);
  }
  c->c[c->n].nv = nv;
  memcpy(c->c[c->n].v, v, (size_t)nv * sizeof *v);
  c->n++;
}

/* Linear-stage sources of a new vertex: 1 (an old vertex), 2 (an edge's
 * midpoint) or 6 (an octahedron's centroid) old vertices, equal weights. */
typedef struct {
  int ns;
  size_t src[6];
} lin;

typedef struct {
  vset V;  /* the new level's vertices */
  cells C; /* its cells */
  lin *L;  /* per new vertex */
  size_t nl;
} level;

static size_t mid(level *N, const vset *O, size_t a, size_t b) {
  int64_t x[3];
  for (int k = 0; k < 3; k++)
    x[k] = (O->p[a][k] + O->p[b][k]) / 2;
  size_t n0 = N->V.n, id = vset_id(&N->V, x, 1);
  if (id == n0) {
    N->L = realloc(N->L, N->V.cap * sizeof *N->L);
    N->L[id] = (lin){2, {a, b}};
  }
  return id;
}

/* One level of linear subdivision of (O, C): positions are the midpoints of
 * the old ones (the scale leaves them integers), the old vertices first. */
static void split(const vset *O, const cells *C, level *N) {
  memset(N, 0, sizeof *N);
  vset_init(&N->V, 1u << 18);
  N->L = malloc(sizeof *N->L);
  for (size_t i = 0; i < O->n; i++) {
    vset_id(&N->V, O->p[i], 1);
    N->L = realloc(N->L, N->V.cap * sizeof *N->L);
    N->L[i] = (lin){1, {i}};
  }
  for (size_t q = 0; q < C->n; q++) {
    const size_t *v = C->c[q].v;
    if (C->c[q].nv == 4) {
      size_t m[4][4];
      for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
          m[i][j] = m[j][i] = mid(N, O, v[i], v[j]);
      for (int i = 0; i < 4; i++) {
        size_t t[4] = {v[i], 0, 0, 0};
        for (int j = 0, k = 1; j < 4; j++)
          if (j != i) t[k++] = m[i][j];
        cells_add(&N->C, 4, t);
      }
      /* opposite pairs (01, 23), (02, 13), (03, 12) */
      size_t o[6] = {m[0][1], m[0][2], m[0][3], m[2][3], m[1][3], m[1][2]};
      cells_add(&N->C, 6, o);
    } else {
      int64_t x[3];
      for (int k = 0; k < 3; k++)
        x[k] = (O->p[v[0]][k] + O->p[v[3]][k]) / 2;
      size_t n0 = N->V.n, c = vset_id(&N->V, x, 1);
      if (c == n0) {
        N->L = realloc(N->L, N->V.cap * sizeof *N->L);
        N->L[c] = (lin){6, {v[0], v[1], v[2], v[3], v[4], v[5]}};
      }
      size_t m[6][6];
      for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++)
          if (i != j && (i + 3) % 6 != j) m[i][j] = mid(N, O, v[i], v[j]);
      for (int i = 0; i < 6; i++) { /* the octahedron at vertex i */
        int a = (i + 1) % 6, b = (i + 2) % 6;
        size_t t[6] = {v[i], m[i][a], m[i][b], c, m[i][(a + 3) % 6], m[i][(b + 3) % 6]};
        cells_add(&N->C, 6, t);
      }
      for (int f = 0; f < 8; f++) { /* the tet on each face */
        int a = (f & 1) ? 3 : 0, b = (f & 2) ? 4 : 1, d = (f & 4) ? 5 : 2;
        size_t t[4] = {m[a][b], m[b][d], m[a][d], c};
        cells_add(&N->C, 4, t);
      }
    }
  }
  N->nl = N->V.n;
}

static void level_free(level *N) {
  vset_free(&N->V), free(N->C.c), free(N->L);
}

/* The row of new vertex v over the old vertices (dense, length nold). */
static void row(const level *N, size_t v, size_t nold, double *r) {
  memset(r, 0, nold * sizeof *r);
  int ncell = 0;
  for (size_t q = 0; q < N->C.n; q++) {
    const cell *c = &N->C.c[q];
    int at = -1;
    for (int k = 0; k < c->nv; k++)
      if (c->v[k] == v) at = k;
    if (at < 0) continue;
    ncell++;
    for (int k = 0; k < c->nv; k++) {
      double w;
      if (c->nv == 4)
        w = k == at ? -1.0 / 16 : 17.0 / 48;
      else
        w = k == at ? 3.0 / 8 : (k == (at + 3) % 6 ? 7.0 / 24 : 1.0 / 12);
      const lin *l = &N->L[c->v[k]];
      for (int s = 0; s < l->ns; s++)
        r[l->src[s]] += w / l->ns;
    }
  }
  for (size_t i = 0; i < nold; i++)
    r[i] /= ncell;
}

/* ---- the star, the support, the maps ---- */

enum { LEV = 4, MAXU = 64 };
static const int64_t SC = 1 << (LEV + 1); /* positions scale: level LEV + 1 integer */

/* Strictly inside the bipyramid conv(A, B, C1, C2, C3)? */
static int inside(const int64_t *x, int64_t (*b)[3]) {
  static const int face[6][3] = {{0, 2, 3}, {0, 3, 4}, {0, 4, 2},
                                 {1, 3, 2}, {1, 4, 3}, {1, 2, 4}};
  for (int f = 0; f < 6; f++) {
    const int64_t *p = b[face[f][0]], *q = b[face[f][1]], *r = b[face[f][2]];
    int64_t u[3], w[3], d[3], o[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++)
      u[k] = q[k] - p[k], w[k] = r[k] - p[k];
    int64_t nn[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                     u[0] * w[1] - u[1] * w[0]};
    int64_t s0 = 0, s = 0;
    for (int k = 0; k < 3; k++)
      d[k] = x[k] - p[k], s += nn[k] * d[k];
    for (int k = 0; k < 3; k++)
      s0 += nn[k] * (o[k] - p[k]);
    if (s == 0 || (s > 0) != (s0 > 0)) return 0;
  }
  return 1;
}

typedef struct {
  size_t n;        /* support size */
  double *S[2];    /* n x n, row-major */
  int interior;    /* every point of sigma_i(U) strictly inside */
  int closed;      /* every such point exists in the refined mesh */
  int64_t z[MAXU]; /* each support point's height along the edge relative to P */
} maps;

static void build_maps(maps *M) {
  const int64_t base[5][3] = {{0, 0, -4}, {0, 0, 4}, {4, 0, 0}, {-2, 3, 0}, {-2, -3, 0}};
  int64_t bs[5][3];
  for (int i = 0; i < 5; i++)
    for (int k = 0; k < 3; k++)
      bs[i][k] = base[i][k] * SC * (1 << LEV);
  vset O;
  vset_init(&O, 1u << 18);
  for (int i = 0; i < 5; i++)
    vset_id(&O, bs[i], 1);
  cells C = {0};
  const size_t tets[3][4] = {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 2}};
  for (int t = 0; t < 3; t++)
    cells_add(&C, 4, tets[t]);
  level N = {0};
  for (int l = 0; l <= LEV; l++) { /* after the loop: N is level LEV + 1, O level LEV */
    if (l) {
      vset_free(&O), free(C.c);
      O = N.V, C = N.C, free(N.L);
    }
    split(&O, &C, &N);
  }
  /* P: the level-LEV vertex at the middle of AB; Q the next one up */
  const int64_t step = 8 * SC; /* |AB| = 8 * SC * 2^LEV over 2^LEV segments */
  int64_t P[3] = {0, 0, 0}, Q[3] = {0, 0, step}, Mid[3] = {0, 0, step / 2};
  size_t U[MAXU];
  size_t nu = 0;
  U[nu++] = vset_id(&O, P, 0), U[nu++] = vset_id(&O, Q, 0);
  double *r = malloc(O.n * sizeof *r);
  M->interior = M->closed = 1;
  for (size_t a = 0; a < nu; a++) /* nu grows while the closure adds points */
    for (int i = 0; i < 2; i++) {
      const int64_t *c = i ? Mid : P;
      int64_t y[3];
      for (int k = 0; k < 3; k++)
        y[k] = c[k] + (O.p[U[a]][k] - P[k]) / 2;
      size_t v = vset_id(&N.V, y, 0);
      if (v == SIZE_MAX) {
        M->closed = 0;
        continue;
      }
      M->interior &= inside(y, bs);
      row(&N, v, O.n, r);
      for (size_t b = 0; b < O.n; b++) {
        if (r[b] == 0) continue;
        size_t k = 0;
        while (k < nu && U[k] != b)
          k++;
        if (k == nu && nu < MAXU) U[nu++] = b;
      }
    }
  /* the loop's bound grows with U: each point is mapped once, after it is
   * added, so U ends closed */
  M->n = nu;
  for (size_t a = 0; a < nu; a++)
    M->z[a] = O.p[U[a]][2] - P[2];
  for (int i = 0; i < 2; i++) {
    M->S[i] = calloc(nu * nu, sizeof *M->S[i]);
    const int64_t *c = i ? Mid : P;
    for (size_t a = 0; a < nu; a++) {
      int64_t y[3];
      for (int k = 0; k < 3; k++)
        y[k] = c[k] + (O.p[U[a]][k] - P[k]) / 2;
      size_t v = vset_id(&N.V, y, 0);
      if (v == SIZE_MAX) continue;
      row(&N, v, O.n, r);
      double in = 0;
      for (size_t b = 0; b < nu; b++)
        M->S[i][a * nu + b] = r[U[b]], in += r[U[b]];
      if (fabs(in - 1) > 1e-12) M->closed = 0; /* a row reads outside U */
    }
  }
  free(r);
  vset_free(&O), free(C.c), level_free(&N);
}

/* ---- linear algebra ---- */

static double sel_lo; /* dgees selects eigenvalues with real part above this */
static lapack_logical sel(const double *re, const double *im) {
  (void)im;
  return *re > sel_lo;
}

/* max over the 2^k words of length k of ||Y_w||_2 (Y_w = Y_{w_k} ... Y_{w_1}). */
static double max_norm2(const double *const *Y, size_t n, int k) {
  double best = 0;
  double *P = malloc(n * n * sizeof *P), *T = malloc(n * n * sizeof *T),
         *s = malloc(n * sizeof *s), *sup = malloc(n * sizeof *sup);
  for (unsigned long w = 0; w < (1ul << k); w++) {
    memcpy(P, Y[w & 1], n * n * sizeof *P);
    for (int j = 1; j < k; j++) {
      const double *A = Y[(w >> j) & 1];
      for (size_t a = 0; a < n; a++)
        for (size_t b = 0; b < n; b++) {
          double x = 0;
          for (size_t c = 0; c < n; c++)
            x += A[a * n + c] * P[c * n + b];
          T[a * n + b] = x;
        }
      memcpy(P, T, n * n * sizeof *P);
    }
    LAPACKE_dgesvd(LAPACK_ROW_MAJOR, 'N', 'N', (lapack_int)n, (lapack_int)n, P,
                   (lapack_int)n, s, NULL, 1, NULL, 1, sup);
    if (s[0] > best) best = s[0];
  }
  free(P), free(T), free(s), free(sup);
  return best;
}

/* max over the words of length k of ||Y_w||_inf, for k = 1..K at once (rho[k - 1]
 * gets it), by depth-first products; stack holds K products. */
static void max_norm_inf(const double *const *Y, size_t n, int K, int k, double *stack,
                         double *best) {
  const double *P = stack + (size_t)(k - 1) * n * n;
  double nrm = 0;
  for (size_t a = 0; a < n; a++) {
    double x = 0;
    for (size_t b = 0; b < n; b++)
      x += fabs(P[a * n + b]);
    nrm = fmax(nrm, x);
  }
  best[k - 1] = fmax(best[k - 1], nrm);
  if (k == K) return;
  double *N = stack + (size_t)k * n * n;
  for (int i = 0; i < 2; i++) {
    for (size_t a = 0; a < n; a++)
      for (size_t b = 0; b < n; b++) {
        double x = 0;
        for (size_t c = 0; c < n; c++)
          x += Y[i][a * n + c] * P[c * n + b];
        N[a * n + b] = x;
      }
    max_norm_inf(Y, n, K, k + 1, stack, best);
  }
}

int main(void) {
  maps M = {0};
  build_maps(&M);
  const size_t n = M.n;
  CHECK(M.closed, "every point of sigma_i(U) exists and reads only U");
  CHECK(M.interior, "the support's images lie strictly inside the star");
  for (int i = 0; i < 2; i++)
    for (size_t a = 0; a < n; a++) {
      double s = 0;
      for (size_t b = 0; b < n; b++)
        s += M.S[i][a * n + b];
      CHECK_CLOSE(s, 1.0, 1e-13, "S_%d row %zu sums to 1", i + 1, a);
    }

  /* the closed forms of finding 9 */
  const double lambda1 = (63 + sqrt(801.0)) / 288; /* root of 288x^2 - 126x + 11 */
  double rho4 = 0.2873777866, fx;                  /* Newton on the cubic */
  for (int it = 0; it < 50; it++) {
    fx = ((186624 * rho4 - 105408) * rho4 + 17952) * rho4 - 883;
    rho4 -= fx / ((3 * 186624 * rho4 - 2 * 105408) * rho4 + 17952);
  }
  CHECK(0.5 > lambda1 && lambda1 > rho4, "1/2 > lambda1 %.9f > rho4 %.9f", lambda1, rho4);

  /* ordered real Schur form of S_1: the eigenvalues above 0.30 first */
  double *T = malloc(n * n * sizeof *T), *Z = malloc(n * n * sizeof *Z);
  double *wr = malloc(n * sizeof *wr), *wi = malloc(n * sizeof *wi);
  memcpy(T, M.S[0], n * n * sizeof *T);
  lapack_int sdim = 0;
  sel_lo = 0.30;
  lapack_int info = LAPACKE_dgees(LAPACK_ROW_MAJOR, 'V', 'S', sel, (lapack_int)n, T,
                                  (lapack_int)n, &sdim, wr, wi, Z, (lapack_int)n);
  CHECK(info == 0 && sdim == 4, "dgees info %d, %d eigenvalues above 0.30", (int)info,
        (int)sdim);
  if (info || sdim != 4) return ss_test_done("tetoct_edge3");
  double lead[4];
  for (int k = 0; k < 4; k++) {
    CHECK(fabs(wi[k]) < 1e-12, "eigenvalue %d real", k);
    lead[k] = wr[k];
  }
  for (int a = 0; a < 4; a++) /* sort descending */
    for (int b = a + 1; b < 4; b++)
      if (lead[b] > lead[a]) fx = lead[a], lead[a] = lead[b], lead[b] = fx;
  CHECK_CLOSE(lead[0], 1.0, 1e-12, "lambda0");
  CHECK_CLOSE(lead[1], 0.5, 1e-12, "1/2 along the edge");
  CHECK_CLOSE(lead[2], lambda1, 1e-10, "lambda1 across");
  CHECK_CLOSE(lead[3], lambda1, 1e-10, "lambda1 across, twice");

  /* Y_i on the orthogonal complement Q2 = Z[:, 4:] of V = Z[:, :4] */
  const size_t m = n - 4;
  double *Y[2], *QSV = calloc(m * 4, sizeof *QSV);
  for (int i = 0; i < 2; i++) {
    Y[i] = calloc(m * m, sizeof *Y[i]);
    for (size_t a = 0; a < m; a++)
      for (size_t b = 0; b < n; b++) { /* (Q2^T S_i Z)[a][b] */
        double x = 0;
        for (size_t c = 0; c < n; c++)
          for (size_t d = 0; d < n; d++)
            x += Z[c * n + 4 + a] * M.S[i][c * n + d] * Z[d * n + b];
        if (b >= 4)
          Y[i][a * m + b - 4] = x;
        else if (i == 1)
          QSV[a * 4 + b] = x;
      }
  }
  double defect = 0;
  for (size_t k = 0; k < m * 4; k++)
    defect = fmax(defect, fabs(QSV[k]));
  CHECK(defect < 1e-12, "span(V) invariant under S_2: defect %.3g", defect);

  /* rho(Y_1): the next eigenvalue of S_1 */
  double rY1 = 0;
  for (size_t k = 4; k < n; k++)
    rY1 = fmax(rY1, hypot(wr[k], wi[k]));
  CHECK_CLOSE(rY1, rho4, 1e-10, "rho(Y_1) is the cubic's root");

  /* The rho-mode (S_1's eigenvector for rho4, by inverse iteration): its
   * control values on the cross-section through P (the support's points at
   * P's height, P left out) are not all zero, so the mode is not odd under the edge's
   * mirror through P (an odd one would vanish there exactly) -- the evidence
   * finding 9 gives for the exponent ln(rho)/ln(lambda1) - 1 being attained. */
  {
    double *A = malloc(n * n * sizeof *A), *x = malloc(n * sizeof *x);
    lapack_int *ipiv = malloc(n * sizeof *ipiv);
    memcpy(A, M.S[0], n * n * sizeof *A);
    for (size_t a = 0; a < n; a++)
      A[a * n + a] -= rho4 * (1 + 1e-7), x[a] = 1.0 + 0.1 * a;
    LAPACKE_dgetrf(LAPACK_ROW_MAJOR, (lapack_int)n, (lapack_int)n, A, (lapack_int)n,
                   ipiv);
    for (int it = 0; it < 6; it++) {
      LAPACKE_dgetrs(LAPACK_ROW_MAJOR, 'N', (lapack_int)n, 1, A, (lapack_int)n, ipiv, x,
                     1);
      double mx = 0;
      for (size_t a = 0; a < n; a++)
        mx = fmax(mx, fabs(x[a]));
      for (size_t a = 0; a < n; a++)
        x[a] /= mx;
    }
    double res = 0, mid0 = 0; /* residual of S_1 x = rho4 x; largest |x| at z = 0 */
    for (size_t a = 0; a < n; a++) {
      double y = -rho4 * x[a];
      for (size_t b = 0; b < n; b++)
        y += M.S[0][a * n + b] * x[b];
      res = fmax(res, fabs(y));
      if (a > 0 && M.z[a] == 0) mid0 = fmax(mid0, fabs(x[a])); /* U[0] is P */
    }
    CHECK(res < 1e-9, "rho-mode residual %.3g", res);
    CHECK(mid0 > 1e-3, "rho-mode on the cross-section through P: max |value| %.3g", mid0);
    printf(
        "independent: rho-mode's control values (max 1): at P %.4f, largest elsewhere on "
        "P's cross-section %.4f\n",
        x[0], mid0);
    free(A), free(x), free(ipiv);
  }

  /* 2-norm profile: the first k with rho_k < lambda1 */
  const double *Yc[2] = {Y[0], Y[1]};
  double rho2[12];
  int kpass = 0;
  for (int k = 1; k <= 12; k++) {
    rho2[k - 1] = pow(max_norm2(Yc, m, k), 1.0 / k);
    if (!kpass && rho2[k - 1] < lambda1 * (1 - 1e-9)) kpass = k;
  }
  CHECK(kpass > 0, "some rho_k (2-norm, k <= 12) below lambda1");
  if (kpass)
    printf("independent: rho_%d (2-norm) = %.6f < lambda1 = %.6f; rho(Y_1) = %.6f\n",
           kpass, rho2[kpass - 1], lambda1, rY1);

  /* the paper's own profile, the inf-norm, in this orthonormal complement
   * (basis-dependent: printed, not checked) */
  enum { KINF = 16 };
  double *stack = malloc(KINF * m * m * sizeof *stack), binf[KINF] = {0};
  for (int i = 0; i < 2; i++) {
    memcpy(stack, Y[i], m * m * sizeof *stack);
    max_norm_inf(Yc, m, KINF, 1, stack, binf);
  }
  free(stack);
  int kinf = 0;
  for (int k = 1; k <= KINF && !kinf; k++)
    if (pow(binf[k - 1], 1.0 / k) < lambda1) kinf = k;
  printf("independent: rho_k (inf-norm, this basis) k = 8, 12, 16: %.6f %.6f %.6f; first "
         "below lambda1 at k = %d (0: none up to %d)\n",
         pow(binf[7], 1.0 / 8), pow(binf[11], 1.0 / 12), pow(binf[15], 1.0 / 16), kinf,
         KINF);

  /* S_1's lambda1-eigenspace (the two smallest right singular vectors of
   * S_1 - lambda1 I) is mapped by S_2 to lambda1 times itself: no coupling
   * of the across pair to 1 or X, as the rotation about the edge forces. */
  {
    double *A = malloc(n * n * sizeof *A), *sv = malloc(n * sizeof *sv),
           *vt = malloc(n * n * sizeof *vt), *sup = malloc(n * sizeof *sup);
    memcpy(A, M.S[0], n * n * sizeof *A);
    for (size_t a = 0; a < n; a++)
      A[a * n + a] -= lambda1;
    LAPACKE_dgesvd(LAPACK_ROW_MAJOR, 'N', 'A', (lapack_int)n, (lapack_int)n, A,
                   (lapack_int)n, sv, NULL, 1, vt, (lapack_int)n, sup);
    CHECK(sv[n - 1] < 1e-12 && sv[n - 2] < 1e-12 && sv[n - 3] > 1e-6,
          "lambda1-eigenspace of S_1 of dimension 2: singular values %.3g %.3g %.3g",
          sv[n - 3], sv[n - 2], sv[n - 1]);
    double cpl = 0;
    for (size_t j = n - 2; j < n; j++)
      for (size_t a = 0; a < n; a++) {
        double y = -lambda1 * vt[j * n + a];
        for (size_t b = 0; b < n; b++)
          y += M.S[1][a * n + b] * vt[j * n + b];
        cpl = fmax(cpl, fabs(y));
      }
    CHECK(cpl < 1e-12, "S_2 u = lambda1 u on the pair: defect %.3g", cpl);
    free(A), free(sv), free(vt), free(sup);
  }

  /* the library on the same case */
  ss_error err = {0};
  ss_scheme *s = NULL;
  REQUIRE_OK(ss_scheme_new("tetoct", &s, &err), &err);
  ss_case c = {0};
  c.kind = SS_CASE_EDGE;
  c.n = 3;
  ss_levin *L = NULL;
  REQUIRE_OK(ss_levin_new(s, &c, &L, &err), &err);
  CHECK(L->n == n, "support size: library %zu, here %zu", L->n, n);
  CHECK_CLOSE(L->lambda1, lambda1, 1e-10, "library lambda1");
  CHECK_CLOSE(L->threshold, lambda1, 1e-10, "library threshold = lambda1 (< 1/2)");
  ss_jsr_opts o = ss_jsr_defaults();
  o.depth = 8;
  o.max_seconds = 30;
  ss_jsr_result r = {0};
  if (L->n == n) {
    REQUIRE_OK(ss_jsr_compute(2, m, (const double *const *)L->Y, &o, &r, &err), &err);
    for (int k = 0; k < 8; k++)
      CHECK_CLOSE(r.rho_2[k], rho2[k], 1e-9, "2-norm rho_%d: library against here",
                  k + 1);
    CHECK(r.lower <= rY1 * (1 + 1e-9) && r.lower >= rY1 * (1 - 1e-9),
          "library lower %.12g = rho(Y_1) %.12g", r.lower, rY1);
    CHECK(r.upper >= rY1 && r.upper < lambda1,
          "library upper %.9g in [rho(Y_1), lambda1)", r.upper);
    CHECK(r.certified, "library bound certified");
    ss_jsr_result_clear(&r);
  }
  /* the library's bound on the blocks built here */
  REQUIRE_OK(ss_jsr_compute(2, m, Yc, &o, &r, &err), &err);
  CHECK(r.upper >= rY1 && r.upper < lambda1, "bound on these Y_i %.9g in [%.9g, %.9g)",
        r.upper, rY1, lambda1);
  ss_jsr_result_clear(&r);

  ss_levin_free(L);
  ss_scheme_free(s);
  free(T), free(Z), free(wr), free(wi), free(QSV), free(Y[0]), free(Y[1]);
  free(M.S[0]), free(M.S[1]);
  return ss_test_done("tetoct_edge3");
}
