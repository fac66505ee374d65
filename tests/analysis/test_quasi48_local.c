/* test_quasi48_local.c — local subdivision matrices of quasi 4-8 surfaces
 * (issue 19): the two-pass (dyadic) matrix at a vertex of a 4-8 mesh, derived
 * by ss_local from the global rule on the topological 4-8 refinement.
 *
 * Closed forms, derived here from the rules and not from the program:
 *  - On the regular 4-8 lattice one pass is, at an old vertex, 1/2 v + 1/8 of
 *    its 4 new neighbours, each 1/4 of its 4 neighbours (section 3.2), i.e.
 *    the mask 2 (h1 * h1) on the quincunx step, h1 = 1/2 at 0 and 1/8 at
 *    (+-1/2, +-1/2); the next pass is the same turned by 45 degrees, 2 (h2 *
 *    h2), h2 = 1/2 at 0 and 1/8 at (+-1/2, 0), (0, +-1/2).  The dyadic step is
 *    fine(x/2) = sum_k a(x/2 - k) coarse(k) with a = 4 h1 * h1 * h2 * h2.  The
 *    local matrix at a regular vertex must equal a on its labels, entry by
 *    entry, for both vertex classes.
 *  - Its leading eigenvalues: a satisfies the sum rules of order k + 1 (every
 *    coset of the fine lattice mod 2 reproduces the same moments up to order
 *    k), so the scheme generates polynomials of degree k and S has the
 *    eigenvalues 2^-j with multiplicity j + 1 for j = 0..k (the monomials of
 *    degree j).  The test finds k from a (3: the symbol's zeros at the other
 *    cosets are of order 4) and then requires exactly these (k + 1)(k + 2)/2
 *    eigenvalues above 2^-k - and nothing else as large.
 *  - Partition of unity: every row of S sums to 1.
 *  - A class-4 vertex of valence n is, one pass later, a class-8 vertex of
 *    valence 2n (its outer edges split, it gains n spokes): the two matrices
 *    are the same, bit for bit.
 *  - Symmetry: turning the chart by one ray or reflecting it maps the two-ring
 *    to itself and commutes with S.
 *  - Local against global: a 4-8 patch built here independently (a lattice per
 *    quadrant, vertices numbered in a scrambled order), refined once by the
 *    scheme's analysis step (two passes of the global rule, the same rule
 *    `subdivide` runs), gives the same rows as ss_local's S on the two-ring,
 *    and those rows put no weight outside it.
 *  - Local against the geometric scheme: the same patch embedded conformally
 *    (z -> z^(4/m) per quadrant), refined twice by quasi48 as `subdivide`
 *    runs it (longest-edge bisection on the positions, then smoothing), gives
 *    the same rows: on 4-8 meshes the criteria agree (section 2.3). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_eig.h"
#include "ss_local.h"
#include "ss_mask48.h"
#include "ss_scheme.h"
#include "ss_split.h"
#include "ss_star.h"
#include "ss_test.h"

#define PI 3.14159265358979323846
#define G  SS_MASK48_G

static ss_scheme *q48;

static ss_local *local(int n, int cls) {
  ss_error err = {0};
  ss_local *M = NULL;
  const ss_case c = {SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, cls};
  if (ss_local_new(q48, &c, &M, &err)) {
    CHECK(0, "quasi48 valence %d class %d: %s", n, cls, err.msg);
    return NULL;
  }
  return M;
}

/* The dyadic mask a = 4 h1 * h1 * h2 * h2 (above), a[(2x + 8) G + 2y + 8]. */
static void dyadic_mask(double *a) {
  double h1[G * G], h2[G * G], t[G * G], u[G * G], v[G * G];
  ss_mask48_halves(h1, h2);
  /* one pass at an old vertex: 2 h1 * h1 = 5/8 self, 1/16 axis, 1/32
   * diagonal (figure 6), which is 1/2 v + 1/8 sum of (1/4 of 4 neighbours) */
  ss_mask48_convolve(h1, h1, t);
  CHECK_CLOSE(2 * t[8 * G + 8], 0.5 + 4 * 0.125 * 0.25, 1e-16, "one pass: centre");
  CHECK_CLOSE(2 * t[10 * G + 8], 2 * 0.125 * 0.25, 1e-16, "one pass: axis neighbour");
  CHECK_CLOSE(2 * t[10 * G + 10], 0.125 * 0.25, 1e-16, "one pass: diagonal neighbour");
  ss_mask48_convolve(t, h2, u);
  ss_mask48_convolve(u, h2, v);
  for (int i = 0; i < G * G; i++)
    a[i] = 4 * v[i];
}

/* Planar position (in grid units of the label's level) of a label of the
 * 4-ray chart: ray j is (cos j pi/2, sin j pi/2). */
static void planar4(const ss_star_coord *c, int *x, int *y) {
  static const int ax[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  *x = *y = 0;
  for (int e = 0; e < c->n; e++) {
    *x += c->val[e] * ax[c->idx[e]][0];
    *y += c->val[e] * ax[c->idx[e]][1];
  }
}

/* The largest k such that a satisfies the sum rules of order k + 1: for every
 * monomial x^p y^q with p + q <= k, its moment over each coset of (Z/2)^2 in
 * the fine grid (indices 2x mod 2) is the same. */
static int sum_rule_order(const double *a) {
  int k = -1;
  for (int deg = 0; deg <= 6; deg++) {
    for (int p = 0; p <= deg; p++) {
      const int q = deg - p;
      double mom[4] = {0, 0, 0, 0};
      for (int i = 0; i < G; i++)
        for (int j = 0; j < G; j++) {
          const double w = a[i * G + j];
          if (w == 0) continue;
          const double x = (i - 8) / 2.0, y = (j - 8) / 2.0;
          mom[((i - 8) & 1) * 2 + ((j - 8) & 1)] += w * pow(x, p) * pow(y, q);
        }
      for (int c = 1; c < 4; c++)
        if (!(fabs(mom[c] - mom[0]) <= 1e-12)) return k;
    }
    k = deg;
  }
  return k;
}

static void test_regular(void) {
  double a[G * G];
  dyadic_mask(a);
  const int k = sum_rule_order(a);
  CHECK(k == 3, "the dyadic mask reproduces degree %d, expected 3 (zeros of order 4)", k);
  const int cls[2] = {4, 8}, val[2] = {4, 8};
  for (int t = 0; t < 2; t++) {
    ss_local *M = local(val[t], cls[t]);
    if (!M) continue;
    CHECK(M->ncoord == 4, "regular vertex: chart of %d rays, expected 4", M->ncoord);
    const size_t n = M->n2;
    double worst = 0, rowdev = 0;
    for (size_t i = 0; i < n; i++) {
      int xi, yi;
      planar4(M->label + i, &xi, &yi);
      double sum = 0;
      for (size_t j = 0; j < n; j++) {
        int xj, yj;
        planar4(M->label + j, &xj, &yj);
        /* fine point x_i / 2 from coarse x_j: offset x_i/2 - x_j, index 2 off + 8 */
        const int dx = xi - 2 * xj + 8, dy = yi - 2 * yj + 8;
        const double want = dx >= 0 && dx < G && dy >= 0 && dy < G ? a[dx * G + dy] : 0;
        worst = fmax(worst, fabs(M->S[i * n + j] - want));
        sum += M->S[i * n + j];
      }
      rowdev = fmax(rowdev, fabs(sum - 1));
    }
    CHECK(worst <= 1e-15, "class %d: S differs from the dyadic mask by %g", cls[t],
          worst);
    CHECK(rowdev <= 1e-14, "class %d: a row of S sums to 1 %+g", cls[t], rowdev);
    ss_eig *e = NULL;
    ss_error err = {0};
    ss_eig_opts eo = ss_eig_defaults(2);
    if (ss_eig_new(M->S, M->n2, M->n1, &eo, &e, &err)) {
      CHECK(0, "eigenvalues: %s", err.msg);
      ss_local_free(M);
      continue;
    }
    /* the leading (k + 1)(k + 2) / 2 are 2^-j, j + 1 times each */
    size_t i = 0;
    for (int j = 0; j <= k; j++)
      for (int r = 0; r <= j; r++, i++)
        CHECK(fabs(e->val[i].re - ldexp(1.0, -j)) <= 1e-9 && fabs(e->val[i].im) <= 1e-9,
              "class %d: eigenvalue %zu is %.12g%+.3gi, expected 2^-%d", cls[t], i,
              e->val[i].re, e->val[i].im, j);
    const double next = hypot(e->val[i].re, e->val[i].im);
    CHECK(next < ldexp(1.0, -k) * (1 - 1e-6),
          "class %d: eigenvalue %zu has modulus %.12g, not below 2^-%d", cls[t], i, next,
          k);
    printf("regular vertex, class %d: %zu points, mask matched to %.1e, 1, 1/2 x2, "
           "1/4 x3, 1/8 x4, then |lambda| = %.6f\n",
           cls[t], n, worst, next);
    ss_eig_free(e);
    ss_local_free(M);
  }
}

/* Class 4 with valence n is class 8 with valence 2n after one pass. */
static void test_classes(void) {
  for (int n = 3; n <= 8; n++) {
    ss_local *A = local(n, 4), *B = local(2 * n, 8);
    if (A && B) {
      int same = A->n2 == B->n2 && A->n1 == B->n1 && A->ncoord == B->ncoord;
      same = same && !memcmp(A->label, B->label, A->n2 * sizeof *A->label) &&
             !memcmp(A->S, B->S, A->n2 * A->n2 * sizeof *A->S);
      CHECK(same, "class 4 valence %d and class 8 valence %d differ", n, 2 * n);
      /* and the size formula of ss_local_estimate */
      CHECK(A->n2 == (size_t)(19 * n + 1) && A->n1 == (size_t)(11 * n + 1),
            "valence %d class 4: n2 %zu, n1 %zu", n, A->n2, A->n1);
      ss_local_cost k;
      ss_error err = {0};
      const ss_case c = {SS_CASE_SURFACE_VERTEX, NULL, 2 * n, SS_DIAG_BFS, 8};
      CHECK(!ss_local_estimate(q48, &c, &k, &err) && k.n2 == B->n2 && k.n1 == B->n1,
            "estimate for valence %d class 8: %zu, %zu rows", 2 * n, k.n2, k.n1);
    }
    ss_local_free(A);
    ss_local_free(B);
  }
}

/* The label of x with rays turned by s (and reflected, j -> -j, if refl). */
static ss_star_coord turn(const ss_star_coord *x, int m, int s, int refl) {
  int32_t idx[SS_STAR_MAXSUPP], v[SS_STAR_MAXSUPP];
  for (int e = 0; e < x->n; e++) {
    const int j = refl ? (m - x->idx[e]) % m : x->idx[e];
    idx[e] = (j + s) % m;
    v[e] = x->val[e];
  }
  return ss_star_coord_make(x->n, idx, v);
}

static void test_symmetry(void) {
  const int cases[][2] = {{3, 4}, {5, 4}, {7, 4}, {6, 8}, {10, 8}, {16, 8}};
  for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
    ss_local *M = local(cases[t][0], cases[t][1]);
    if (!M) continue;
    const size_t n = M->n2;
    const int m = M->ncoord;
    size_t *P = malloc(n * sizeof *P);
    int bad = 0, lost = 0;
    for (int g = 0; g < 2; g++) { /* turn by one ray; reflect */
      for (size_t i = 0; i < n; i++) {
        const ss_star_coord y = turn(M->label + i, m, g == 0, g == 1);
        P[i] = ss_local_label_index(M, &y);
        lost += P[i] == SIZE_MAX;
      }
      for (size_t i = 0; !lost && i < n; i++)
        for (size_t j = 0; j < n; j++)
          /* equal up to the order of summation in the rule: a few ulps */
          bad += !(fabs(M->S[P[i] * n + P[j]] - M->S[i * n + j]) <= 1e-15);
    }
    CHECK(!lost && !bad,
          "valence %d class %d: %d labels leave the two-ring, %d entries of S change "
          "(by more than 1e-15) under the chart's symmetries",
          cases[t][0], cases[t][1], lost, bad);
    free(P);
    ss_local_free(M);
  }
}

/* ---- local against global ---- */

#define RAD 8 /* the patch: 0 <= a, b <= RAD in every quadrant */

/* Chart coordinates a e_j + b e_j+1 of ray count m as a canonical label. */
static ss_star_coord qcoord(int m, int j, int a, int b) {
  int32_t idx[2], v[2];
  int k = 0;
  if (a) idx[k] = j, v[k++] = a;
  if (b) idx[k] = (j + 1) % m, v[k++] = b;
  return ss_star_coord_make(k, idx, v);
}

typedef struct {
  ss_star_coord *c; /* coordinates of each vertex */
  size_t n, cap;
} coords;

static int cmp_coord(const void *x, const void *y) {
  return ss_star_coord_cmp(x, y);
}

/* The 4-8 patch around a vertex of class cls with m rays: the lattice of
 * each quadrant, squares cut along the diagonal joining the class-8 corners
 * (a + b even for class 8, odd for class 4), right-angle corner first.
 * Vertices are numbered in a scrambled order (7919 i mod nv). */
static ss_cx *patch(int m, int cls, coords *C) {
  ss_error err = {0};
  /* distinct coordinates, sorted, then scrambled */
  C->cap = (size_t)m * (RAD + 1) * (RAD + 1) + 1;
  C->c = malloc(C->cap * sizeof *C->c);
  C->n = 0;
  for (int j = 0; j < m; j++)
    for (int a = 0; a <= RAD; a++)
      for (int b = 0; b <= RAD; b++)
        if (a > 0 || (b == 0 && j == 0)) /* ray j + 1 is quadrant j + 1's */
          C->c[C->n++] = qcoord(m, j, a, b);
  qsort(C->c, C->n, sizeof *C->c, cmp_coord);
  size_t *num = malloc(C->n * sizeof *num);
  ss_star_coord *sc = malloc(C->n * sizeof *sc);
  for (size_t i = 0; i < C->n; i++) {
    num[i] = (7919 * i) % C->n; /* 7919 is prime, C->n not a multiple */
    sc[num[i]] = C->c[i];
  }
  ss_cx *cx = NULL;
  if (ss_cx_new(2, &cx, &err)) exit(1);
  for (size_t v = 0; v < C->n; v++) {
    /* position: the quadrant's a + ib under z -> z^(4/m), turned to sector j
     * (conformal away from the centre, so the triangles stay close to right
     * isosceles and their hypotenuses are their longest edges) */
    int j = 0, qa = 0, qb = 0;
    if (sc[v].n == 1) j = sc[v].idx[0], qa = sc[v].val[0];
    if (sc[v].n == 2) {
      const int p0 = sc[v].idx[0], p1 = sc[v].idx[1];
      const int first = p1 == p0 + 1 ? 0 : 1; /* (0, m-1): quadrant m - 1 */
      j = sc[v].idx[first], qa = sc[v].val[first], qb = sc[v].val[1 - first];
    }
    const double rho = pow(hypot(qa, qb), 4.0 / m),
                 phi = 4.0 / m * atan2(qb, qa) + 2 * PI * j / m;
    const double x[2] = {rho * cos(phi), rho * sin(phi)};
    if (ss_cx_add_vertex(cx, x, 0, &err)) exit(1);
  }
  for (int j = 0; j < m; j++)
    for (int a = 0; a < RAD; a++)
      for (int b = 0; b < RAD; b++) {
        ss_idx p[2][2];
        for (int s = 0; s < 2; s++)
          for (int r = 0; r < 2; r++) {
            const ss_star_coord k = qcoord(m, j, a + s, b + r);
            const ss_star_coord *hit = bsearch(&k, C->c, C->n, sizeof *C->c, cmp_coord);
            p[s][r] = (ss_idx)num[hit - C->c];
          }
        const int even = ((a + b) % 2 == 0) == (cls == 8);
        ss_idx t0[3], t1[3];
        if (even) { /* diagonal p00-p11 */
          t0[0] = p[1][0], t0[1] = p[1][1], t0[2] = p[0][0];
          t1[0] = p[0][1], t1[1] = p[0][0], t1[2] = p[1][1];
        } else { /* diagonal p10-p01 */
          t0[0] = p[0][0], t0[1] = p[1][0], t0[2] = p[0][1];
          t1[0] = p[1][1], t1[1] = p[0][1], t1[2] = p[1][0];
        }
        if (ss_cx_add_cell(cx, SS_TRIANGLE, t0, 0, &err) ||
            ss_cx_add_cell(cx, SS_TRIANGLE, t1, 0, &err))
          exit(1);
      }
  /* C->c by vertex number from here on */
  memcpy(C->c, sc, C->n * sizeof *sc);
  free(sc);
  free(num);
  return cx;
}

static void test_global(void) {
  const int cases[][2] = {{3, 4}, {4, 4}, {6, 8}, {8, 8}, {10, 8}, {14, 8}};
  for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
    const int n = cases[t][0], cls = cases[t][1], m = cls == 8 ? n / 2 : n;
    ss_local *M = local(n, cls);
    if (!M) continue;
    coords C;
    ss_cx *cx = patch(m, cls, &C), *f = NULL;
    gsl_spmatrix *R = NULL;
    ss_split *L = NULL;
    ss_error err = {0};
    if (ss_scheme_refine_step(q48, cx, &f, &R, &L, &err)) {
      CHECK(0, "refining the patch: %s", err.msg);
      ss_cx_free(cx);
      free(C.c);
      ss_local_free(M);
      continue;
    }
    /* fine coordinates (fine units): 2 * mean of the parents' */
    ss_star_coord *fc = malloc(f->nv * sizeof *fc);
    for (size_t v = 0; v < f->nv; v++) {
      int32_t idx[8], val[8];
      int k = 0;
      const size_t np = ss_split_npar(L, v);
      for (size_t q = L->ptr[v]; q < L->ptr[v + 1]; q++) {
        const ss_star_coord *p = C.c + L->parent[q];
        for (int e = 0; e < p->n; e++) {
          int h = 0;
          while (h < k && idx[h] != p->idx[e])
            h++;
          if (h == k) idx[k] = p->idx[e], val[k++] = 0;
          val[h] += 2 * p->val[e];
        }
      }
      int kk = 0;
      for (int h = 0; h < k; h++)
        if (val[h]) idx[kk] = idx[h], val[kk++] = val[h] / (int)np;
      fc[v] = ss_star_coord_make(kk, idx, val);
    }
    /* rows of the two-ring's labels */
    const size_t n2 = M->n2;
    double worst = 0, outside = 0;
    int missing = 0;
    for (size_t i = 0; i < n2; i++) {
      size_t row = SIZE_MAX;
      for (size_t v = 0; v < f->nv && row == SIZE_MAX; v++)
        if (!ss_star_coord_cmp(fc + v, M->label + i)) row = v;
      if (row == SIZE_MAX) {
        missing++;
        continue;
      }
      double in = 0;
      for (int q = R->p[row]; q < R->p[row + 1]; q++) {
        const size_t j = ss_local_label_index(M, C.c + R->i[q]);
        if (j == SIZE_MAX) {
          outside = fmax(outside, fabs(R->data[q]));
          continue;
        }
        in += R->data[q];
        worst = fmax(worst, fabs(R->data[q] - M->S[i * n2 + j]));
      }
      for (size_t j = 0; j < n2; j++) { /* entries S has but R not */
        const ss_star_coord *lj = M->label + j;
        int found = 0;
        for (int q = R->p[row]; q < R->p[row + 1] && !found; q++)
          found = !ss_star_coord_cmp(C.c + R->i[q], lj);
        if (!found) worst = fmax(worst, fabs(M->S[i * n2 + j]));
      }
      CHECK_CLOSE(in, 1.0, 1e-14, "global row %zu sums to 1 on the two-ring", i);
    }
    CHECK(!missing && worst <= 1e-15 && outside == 0,
          "valence %d class %d: local and global differ by %g (%d rows missing, weight "
          "%g outside the two-ring)",
          n, cls, worst, missing, outside);
    printf("valence %2d class %d: local S (%zu points) = the global rule on a scrambled "
           "patch of %zu vertices, to %.1e\n",
           n, cls, n2, cx->nv, worst);
    free(fc);
    ss_split_free(L);
    gsl_spmatrix_free(R);
    ss_cx_free(f);
    ss_cx_free(cx);
    free(C.c);
    ss_local_free(M);
  }
}

/* The geometric scheme, as `subdivide --scheme quasi48` runs it (longest-edge
 * bisection reading the positions, two levels), on the conformally embedded
 * patch: where its two passes split what the topological ones split, its
 * rows must be S.  Fine vertices are named by coordinates carried through the
 * two splits (in units of the second level: twice the coarse ones, then the
 * mean of the parents at each pass). */
static void test_geometric(void) {
  const int cases[][2] = {{3, 4}, {5, 4}, {6, 8}, {8, 8}, {10, 8}, {12, 8}};
  for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
    const int n = cases[t][0], cls = cases[t][1], m = cls == 8 ? n / 2 : n;
    ss_local *M = local(n, cls);
    if (!M) continue;
    coords C;
    ss_cx *cx = patch(m, cls, &C), *f1 = NULL, *f2 = NULL;
    gsl_spmatrix *R1 = NULL, *R2 = NULL;
    ss_split *L1 = NULL, *L2 = NULL;
    ss_error err = {0};
    if (ss_scheme_refine_split(q48, cx, &f1, &R1, &L1, &err) ||
        ss_scheme_refine_split(q48, f1, &f2, &R2, &L2, &err)) {
      CHECK(0, "geometric refinement of the patch: %s", err.msg);
      goto next;
    }
    ss_star_coord *c1 = malloc(f1->nv * sizeof *c1), *c2 = malloc(f2->nv * sizeof *c2);
    int odd = 0;
    for (int pass = 0; pass < 2; pass++) {
      const ss_split *L = pass ? L2 : L1;
      const ss_star_coord *from = pass ? c1 : C.c;
      ss_star_coord *to = pass ? c2 : c1;
      for (size_t v = 0; v < L->nfine; v++) {
        int32_t idx[8], val[8];
        int k = 0;
        const int np = (int)ss_split_npar(L, v), mult = pass ? 1 : 2;
        for (size_t q = L->ptr[v]; q < L->ptr[v + 1]; q++) {
          const ss_star_coord *p = from + L->parent[q];
          for (int e = 0; e < p->n; e++) {
            int h = 0;
            while (h < k && idx[h] != p->idx[e])
              h++;
            if (h == k) idx[k] = p->idx[e], val[k++] = 0;
            val[h] += mult * p->val[e];
          }
        }
        int kk = 0;
        for (int h = 0; h < k; h++) {
          odd += val[h] % np != 0;
          if (val[h]) idx[kk] = idx[h], val[kk++] = val[h] / np;
        }
        to[v] = ss_star_coord_make(kk, idx, val);
      }
    }
    const size_t n2 = M->n2;
    double worst = 0;
    int missing = 0;
    for (size_t i = 0; i < n2; i++) {
      size_t row = SIZE_MAX;
      for (size_t v = 0; v < f2->nv && row == SIZE_MAX; v++)
        if (!ss_star_coord_cmp(c2 + v, M->label + i)) row = v;
      if (row == SIZE_MAX) {
        missing++;
        continue;
      }
      double *r = calloc(n2, sizeof *r), out = 0;
      for (int q = R2->p[row]; q < R2->p[row + 1]; q++)
        for (int u = R1->p[R2->i[q]]; u < R1->p[R2->i[q] + 1]; u++) {
          const size_t j = ss_local_label_index(M, C.c + R1->i[u]);
          if (j == SIZE_MAX)
            out += fabs(R2->data[q] * R1->data[u]);
          else
            r[j] += R2->data[q] * R1->data[u];
        }
      worst = fmax(worst, out);
      for (size_t j = 0; j < n2; j++)
        worst = fmax(worst, fabs(r[j] - M->S[i * n2 + j]));
      free(r);
    }
    CHECK(!odd && !missing && worst <= 1e-14,
          "valence %d class %d: the geometric scheme's two levels differ from S by %g "
          "(%d two-ring points not born, %d non-midpoints)",
          n, cls, worst, missing, odd);
    printf("valence %2d class %d: longest-edge quasi48 (subdivide's rule), two levels on "
           "a conformal 4-8 patch = S to %.1e\n",
           n, cls, worst);
    free(c1);
    free(c2);
  next:
    if (R1) gsl_spmatrix_free(R1);
    if (R2) gsl_spmatrix_free(R2);
    ss_split_free(L1);
    ss_split_free(L2);
    ss_cx_free(f1);
    ss_cx_free(f2);
    ss_cx_free(cx);
    free(C.c);
    ss_local_free(M);
  }
}

/* Bad cases: SS_EINPUT with a message, never a matrix. */
static void test_bad(void) {
  const int bad[][2] = {{7, 8}, {4, 8}, {2, 4}, {6, 5}};
  for (size_t t = 0; t < sizeof bad / sizeof bad[0]; t++) {
    ss_error err = {0};
    ss_local *M = NULL;
    const ss_case c = {SS_CASE_SURFACE_VERTEX, NULL, bad[t][0], SS_DIAG_BFS, bad[t][1]};
    const ss_status st = ss_local_new(q48, &c, &M, &err);
    CHECK(st == SS_EINPUT && !M && err.msg[0], "valence %d class %d: status %d",
          bad[t][0], bad[t][1], (int)st);
    ss_local_free(M);
  }
  /* non-conforming tags: two triangles on an edge, only one refining it */
  ss_error err = {0};
  ss_cx *cx = NULL, *f = NULL;
  ss_split *L = NULL;
  const double x[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  if (ss_cx_new(2, &cx, &err)) exit(1);
  for (int v = 0; v < 4; v++)
    if (ss_cx_add_vertex(cx, x[v], 0, &err)) exit(1);
  const ss_idx t0[3] = {1, 2, 0}, t1[3] = {0, 2, 3}; /* edge 0-2 refines in t0 only */
  if (ss_cx_add_cell(cx, SS_TRIANGLE, t0, 0, &err) ||
      ss_cx_add_cell(cx, SS_TRIANGLE, t1, 0, &err))
    exit(1);
  CHECK(ss_split_refine(SS_SPLIT_NVB, cx, &f, &L, &err) == SS_EINPUT &&
            strstr(err.msg, "non-conforming"),
        "non-conforming tags: %s", err.msg);
  ss_cx_free(f);
  ss_split_free(L);
  /* conforming: both refine 0-2; one pass halves both, two make 8 triangles */
  ss_cx_free(cx);
  if (ss_cx_new(2, &cx, &err)) exit(1);
  for (int v = 0; v < 4; v++)
    if (ss_cx_add_vertex(cx, x[v], 0, &err)) exit(1);
  const ss_idx u0[3] = {1, 2, 0}, u1[3] = {3, 0, 2};
  if (ss_cx_add_cell(cx, SS_TRIANGLE, u0, 0, &err) ||
      ss_cx_add_cell(cx, SS_TRIANGLE, u1, 0, &err))
    exit(1);
  gsl_spmatrix *R = NULL;
  CHECK(!ss_scheme_refine_step(q48, cx, &f, &R, &L, &err) && f->nc[SS_TRIANGLE] == 8 &&
            f->nv == 9,
        "a square, one 4-8 cycle: %zu triangles, %zu vertices (%s)",
        f ? f->nc[SS_TRIANGLE] : 0, f ? f->nv : 0, err.msg);
  if (R) gsl_spmatrix_free(R);
  ss_cx_free(f);
  ss_split_free(L);
  ss_cx_free(cx);
}

int main(void) {
  ss_error err = {0};
  if (ss_scheme_new("quasi48", &q48, &err)) {
    fprintf(stderr, "%s\n", err.msg);
    return 1;
  }
  test_regular();
  test_classes();
  test_symmetry();
  test_global();
  test_geometric();
  test_bad();
  ss_scheme_free(q48);
  return ss_test_done("quasi48_local");
}
