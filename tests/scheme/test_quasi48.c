/* test_quasi48.c — the quasi 4-8 scheme (Velho & Gomes) against closed forms
 * derived by hand, and its section 3.3 claims measured on real meshes.
 *
 * Regular planar 4-8 lattice (vertices Z^2, valence 8 on x+y even, every unit
 * square cut by the diagonal joining its even corners).  One level splits all
 * diagonals (the longest edges, length sqrt 2) and smooths:
 *   centre of a square   1/4 of its corners;
 *   old vertex           1/2 v + 1/8 sum of its 4 new neighbours
 *                        = 5/8 v + 1/16 (axis neighbours) + 1/32 (diagonal),
 * the same for both vertex classes.  With c1 = cos(w1/2), c2 = cos(w2/2) its
 * symbol is 1/2 + c1 c2 + 1/2 c1^2 c2^2 = 2 ((1 + c1 c2)/2)^2.  The second
 * level is the same on the lattice turned by 45 degrees (new points at
 * (1/2, 0) offsets), symbol 2 ((1 + (c1 + c2)/2)/2)^2.  The two-level
 * (dyadic) operator therefore has the normalized symbol
 *   M(w) = ((1 + c1 c2)/2)^2 ((1 + (c1 + c2)/2)/2)^2,
 * i.e. mask 4 (h1 * h1 * h2 * h2) on (Z/2)^2 with h1 = 1/2 at 0 and 1/8 at
 * (+-1/2, +-1/2), h2 = 1/2 at 0 and 1/8 at (+-1/2, 0), (0, +-1/2).  M vanishes
 * only at isolated points (c1 c2 = -1 or c1 = c2 = -1), while the subdivision
 * symbol of any box spline vanishes along whole lines: the scheme reproduces
 * no box spline.  Here the operator R that the library builds is compared with
 * that mask entry by entry (at both vertex classes), with the symmetries of
 * the lattice, and with linear precision. */
#include <stdint.h>
#include <string.h>

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>

#include "ss_mask48.h"
#include "ss_mesh.h"
#include "ss_optest.h"
#include "ss_split.h"
#include "ss_triedge.h"

#define HALF 6           /* the patch is [-HALF, HALF]^2 */
#define G    SS_MASK48_G /* mask grid: offsets -4..4 in steps of 1/2, index 2x + 8 */

/* The regular 4-8 patch [-HALF, HALF]^2; vertex (i, j) has index
 * (i + HALF) * (2 HALF + 1) + (j + HALF). */
static ss_cx *lattice48(void) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  const int n = 2 * HALF + 1;
  if (ss_cx_new(2, &cx, &err)) exit(1);
  for (int i = -HALF; i <= HALF; i++)
    for (int j = -HALF; j <= HALF; j++) {
      double x[2] = {i, j};
      if (ss_cx_add_vertex(cx, x, 0, &err)) exit(1);
    }
#define VID(i, j) ((ss_idx)(((i) + HALF) * n + ((j) + HALF)))
  for (int i = -HALF; i < HALF; i++)
    for (int j = -HALF; j < HALF; j++) {
      ss_idx a = VID(i, j), b = VID(i + 1, j), c = VID(i + 1, j + 1), d = VID(i, j + 1);
      /* the diagonal joins the even corners (valence 8) */
      int even = ((i + j) % 2 + 2) % 2 == 0;
      ss_idx t0[3] = {a, b, even ? c : d}, t1[3] = {even ? a : b, c, d};
      if (ss_cx_add_cell(cx, SS_TRIANGLE, t0, 0, &err) ||
          ss_cx_add_cell(cx, SS_TRIANGLE, t1, 0, &err))
        exit(1);
    }
#undef VID
  return cx;
}

/* Split level by level with the scheme, keeping the nominal position of each
 * vertex (a new vertex at the mean of its parents' nominal positions), so that
 * fine vertices can be named by lattice points independently of smoothing. */
static ss_cx *refine2(const ss_cx *c0, double **R, double **nominal) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *f1 = NULL, *f2 = NULL;
  gsl_spmatrix *R1 = NULL, *R2 = NULL;
  ss_split *L1 = NULL, *L2 = NULL;
  if (ss_scheme_new("quasi48", &s, &err) ||
      ss_scheme_refine_split(s, c0, &f1, &R1, &L1, &err) ||
      ss_scheme_refine_split(s, f1, &f2, &R2, &L2, &err)) {
    fprintf(stderr, "quasi48 refine: %s\n", err.msg);
    exit(1);
  }
  double *x1 = malloc(f1->nv * 2 * sizeof *x1), *x2 = malloc(f2->nv * 2 * sizeof *x2);
  for (size_t v = 0; v < f1->nv; v++)
    for (int r = 0; r < 2; r++) {
      double sum = 0;
      for (size_t q = L1->ptr[v]; q < L1->ptr[v + 1]; q++)
        sum += c0->x[2 * L1->parent[q] + (size_t)r];
      x1[2 * v + (size_t)r] = sum / (double)ss_split_npar(L1, v);
    }
  for (size_t v = 0; v < f2->nv; v++)
    for (int r = 0; r < 2; r++) {
      double sum = 0;
      for (size_t q = L2->ptr[v]; q < L2->ptr[v + 1]; q++)
        sum += x1[2 * L2->parent[q] + (size_t)r];
      x2[2 * v + (size_t)r] = sum / (double)ss_split_npar(L2, v);
    }
  /* R = R2 R1, dense (the patch is small) */
  double *P = calloc(R2->size1 * R1->size2, sizeof *P);
  for (size_t f = 0; f < R2->size1; f++)
    for (int q = R2->p[f]; q < R2->p[f + 1]; q++)
      for (int r = R1->p[R2->i[q]]; r < R1->p[R2->i[q] + 1]; r++)
        P[f * R1->size2 + (size_t)R1->i[r]] += R2->data[q] * R1->data[r];
  *R = P;
  *nominal = x2;
  gsl_spmatrix_free(R1);
  gsl_spmatrix_free(R2);
  ss_split_free(L1);
  ss_split_free(L2);
  ss_cx_free(f1);
  free(x1);
  ss_scheme_free(s);
  return f2;
}

static void test_lattice(void) {
  ss_cx *c0 = lattice48();
  gsl_spmatrix *R1 = NULL;
  double *R = NULL, *nom = NULL;
  /* one level: the figure 6 mask at a valence-8 vertex, by hand above */
  ss_cx *f1 = op_refine("quasi48", c0, &R1);
  const int n = 2 * HALF + 1;
  for (int cls = 0; cls < 2; cls++) {
    ss_idx v = (ss_idx)(HALF * n + HALF + cls); /* (0,0) even, (0,1) odd */
    double self = gsl_spmatrix_get(R1, v, v);
    double ax = gsl_spmatrix_get(R1, v, v + 1), dg = gsl_spmatrix_get(R1, v, v + 1 + n);
    CHECK_CLOSE(self, 5.0 / 8.0, 1e-15, "level 1, class %d: centre", cls);
    CHECK_CLOSE(ax, 1.0 / 16.0, 1e-15, "level 1, class %d: axis neighbour", cls);
    CHECK_CLOSE(dg, 1.0 / 32.0, 1e-15, "level 1, class %d: diagonal neighbour", cls);
  }
  check_row_sums(R1, "quasi48 level 1");
  ss_cx_free(f1);
  gsl_spmatrix_free(R1);

  ss_cx *f2 = refine2(c0, &R, &nom);
  const size_t nc0 = c0->nv;
  size_t rows_bad = 0;
  for (size_t f = 0; f < f2->nv; f++) {
    double sum = 0;
    for (size_t a = 0; a < nc0; a++)
      sum += R[f * nc0 + a];
    rows_bad += fabs(sum - 1) > 1e-14;
  }
  CHECK(rows_bad == 0, "%zu rows of the two-level operator do not sum to 1", rows_bad);
  /* the closed-form mask 4 (h1*h1*h2*h2) */
  static double h1[G * G], h2[G * G], t[G * G], u[G * G], mask[G * G];
  ss_mask48_halves(h1, h2);
  ss_mask48_convolve(h1, h1, t);
  ss_mask48_convolve(t, h2, u);
  ss_mask48_convolve(u, h2, mask);
  /* fine vertex by its nominal lattice point (2x, 2y integers) */
  const int m = 4 * HALF + 1;
  size_t *at = malloc((size_t)m * (size_t)m * sizeof *at);
  for (int k = 0; k < m * m; k++)
    at[k] = SIZE_MAX;
  int offgrid = 0;
  for (size_t v = 0; v < f2->nv; v++) {
    double X = 2 * nom[2 * v], Y = 2 * nom[2 * v + 1];
    long ix = lround(X), iy = lround(Y);
    if (fabs(X - (double)ix) > 1e-12 || fabs(Y - (double)iy) > 1e-12) offgrid++;
    at[(ix + 2 * HALF) * m + (iy + 2 * HALF)] = v;
  }
  CHECK(offgrid == 0 && f2->nv == (size_t)(m * m),
        "two levels of the regular patch give the half lattice: %zu vertices, %d off it",
        f2->nv, offgrid);
  /* interior coarse vertices of both classes: every fine row within reach */
  double worst = 0.0;
  int sym_bad = 0;
  for (int ci = -1; ci <= 1; ci++)
    for (int cj = -1; cj <= 1; cj++) {
      ss_idx a = (ss_idx)((ci + HALF) * n + (cj + HALF));
      for (int dx = -8; dx <= 8; dx++)
        for (int dy = -8; dy <= 8; dy++) {
          size_t f = at[(2 * ci + dx + 2 * HALF) * m + (2 * cj + dy + 2 * HALF)];
          double got = R[f * nc0 + a];
          double want = 4.0 * mask[(dx + 8) * G + (dy + 8)];
          if (fabs(got - want) > worst) worst = fabs(got - want);
          /* the 8 symmetries of the square lattice fix the mask */
          int img[8][2] = {{dx, dy}, {-dx, dy}, {dx, -dy}, {-dx, -dy},
                           {dy, dx}, {-dy, dx}, {dy, -dx}, {-dy, -dx}};
          for (int g = 0; g < 8; g++) {
            size_t fg =
                at[(2 * ci + img[g][0] + 2 * HALF) * m + (2 * cj + img[g][1] + 2 * HALF)];
            if (fabs(R[fg * nc0 + a] - got) > 1e-15) sym_bad++;
          }
        }
    }
  CHECK(worst <= 1e-15,
        "two-level operator differs from the closed-form symbol's mask by %g", worst);
  CHECK(sym_bad == 0, "%d mask entries break the square lattice's symmetry", sym_bad);
  /* the mask's centre and extent, from the convolution by hand: 4 (1/2)^4 ... */
  printf("two-level mask at a lattice vertex: centre %.17g, (1/2,0) %.17g, "
         "(1/2,1/2) %.17g, (1,0) %.17g\n",
         4 * mask[8 * G + 8], 4 * mask[9 * G + 8], 4 * mask[9 * G + 9],
         4 * mask[10 * G + 8]);
  /* The local subdivision matrix of two levels at a lattice vertex: the 9 x 9
   * block of lattice points around it maps onto the points at half their
   * coordinates (the mask reaches 2, so the block is closed).  Each of the
   * symbol M's other cosets ((2pi,0), (0,2pi), (2pi,2pi)) is a zero of order 4:
   * near (2pi,0), (1 + c1 c2)/2 ~ |e|^2/16 and is squared; near (2pi,2pi),
   * (1 + (c1 + c2)/2)/2 ~ |e|^2/32 and is squared.  So the scheme generates
   * cubics and S has the eigenvalues 2^-k with multiplicity k + 1, k = 0..3
   * (1, 1/2 twice, 1/4 three times, 1/8 four times). */
  {
    const int r = 4, w = 2 * r + 1, nn = w * w;
    gsl_matrix *S = gsl_matrix_alloc((size_t)nn, (size_t)nn);
    for (int i = 0; i < nn; i++) {
      int ax = i / w - r, ay = i % w - r; /* fine point (ax/2, ay/2) */
      size_t f = at[(ax + 2 * HALF) * m + (ay + 2 * HALF)];
      double sum = 0;
      for (int j = 0; j < nn; j++) {
        int bx = j / w - r, by = j % w - r;
        size_t a = (size_t)((bx + HALF) * n + (by + HALF));
        gsl_matrix_set(S, (size_t)i, (size_t)j, R[f * nc0 + a]);
        sum += R[f * nc0 + a];
      }
      CHECK_CLOSE(sum, 1.0, 1e-14, "local matrix row %d is not closed", i);
    }
    gsl_vector_complex *ev = gsl_vector_complex_alloc((size_t)nn);
    gsl_eigen_nonsymm_workspace *ws = gsl_eigen_nonsymm_alloc((size_t)nn);
    CHECK(gsl_eigen_nonsymm(S, ev, ws) == 0, "eigenvalues of the local matrix");
    double mags[81];
    for (int i = 0; i < nn; i++)
      mags[i] = gsl_complex_abs(gsl_vector_complex_get(ev, (size_t)i));
    for (int k = 0; k <= 3; k++) {
      int count = 0;
      for (int i = 0; i < nn; i++) {
        gsl_complex z = gsl_vector_complex_get(ev, (size_t)i);
        /* repeated eigenvalues of a non-normal matrix move by ~sqrt(eps) */
        count += fabs(GSL_REAL(z) - ldexp(1.0, -k)) < 1e-7 && fabs(GSL_IMAG(z)) < 1e-7;
      }
      CHECK(count == k + 1, "eigenvalue 2^-%d: multiplicity %d, expected %d", k, count,
            k + 1);
    }
    /* and nothing else as large as 1/8 (printed: the next one) */
    int above = 0;
    double next = 0;
    for (int i = 0; i < nn; i++) {
      above += mags[i] > 0.125 + 1e-7;
      if (mags[i] < 0.125 - 1e-7 && mags[i] > next) next = mags[i];
    }
    CHECK(above == 6, "%d eigenvalues above 1/8, expected 6 (1, 1/2, 1/2, 1/4 x3)",
          above);
    printf("two-level local matrix at a regular vertex (81 points): 1, 1/2 x2, "
           "1/4 x3, 1/8 x4 found; next |lambda| = %.6f\n",
           next);
    gsl_eigen_nonsymm_free(ws);
    gsl_vector_complex_free(ev);
    gsl_matrix_free(S);
  }
  /* linear precision: interior fine vertices of x and y stay on their points */
  double lin = 0.0;
  for (size_t v = 0; v < f2->nv; v++) {
    if (fabs(nom[2 * v]) > HALF - 3 || fabs(nom[2 * v + 1]) > HALF - 3) continue;
    for (int r = 0; r < 2; r++) {
      double e = fabs(f2->x[2 * v + (size_t)r] - nom[2 * v + (size_t)r]);
      if (e > lin) lin = e;
    }
  }
  CHECK(lin <= 1e-13, "linear functions are not reproduced: error %g", lin);
  free(at);
  free(nom);
  free(R);
  ss_cx_free(f2);
  ss_cx_free(c0);
}

/* ---- section 3.3 claims on real meshes ---- */

static ss_triedge *edges_of(const ss_cx *cx) {
  ss_error err = {0};
  ss_triedge *te = NULL;
  if (ss_triedge_new(cx, &te, &err)) {
    fprintf(stderr, "edge table: %s\n", err.msg);
    exit(1);
  }
  return te;
}

static size_t valence(const ss_triedge *te, size_t v) {
  return te->vptr[v + 1] - te->vptr[v];
}

static int cmp_sz(const void *a, const void *b) {
  size_t x = *(const size_t *)a, y = *(const size_t *)b;
  return (x > y) - (x < y);
}

/* A fingerprint of the 2-ring structure of v: its valence, the sorted
 * valences of its 1-ring and those of the vertices at distance 2 (FNV-1a). */
static uint64_t ring2_signature(const ss_triedge *te, size_t v, size_t *mark,
                                size_t stamp) {
  size_t ring1[64], ring2[1024], n1 = 0, n2 = 0;
  mark[v] = stamp;
  for (size_t q = te->vptr[v]; q < te->vptr[v + 1] && n1 < 64; q++) {
    ring1[n1++] = te->vnbr[q];
    mark[te->vnbr[q]] = stamp;
  }
  for (size_t i = 0; i < n1; i++)
    for (size_t q = te->vptr[ring1[i]]; q < te->vptr[ring1[i] + 1]; q++) {
      size_t w = te->vnbr[q];
      if (mark[w] == stamp || n2 == 1024) continue;
      mark[w] = stamp;
      ring2[n2++] = valence(te, w);
    }
  for (size_t i = 0; i < n1; i++)
    ring1[i] = valence(te, ring1[i]);
  qsort(ring1, n1, sizeof *ring1, cmp_sz);
  qsort(ring2, n2, sizeof *ring2, cmp_sz);
  uint64_t h = 1469598103934665603ull;
#define MIX(x) (h = (h ^ (uint64_t)(x)) * 1099511628211ull)
  MIX(valence(te, v));
  MIX(1000 + n1);
  for (size_t i = 0; i < n1; i++)
    MIX(ring1[i]);
  MIX(2000 + n2);
  for (size_t i = 0; i < n2; i++)
    MIX(ring2[i]);
#undef MIX
  return h;
}

/* Refine `levels` times and measure the claims of section 3.3 level by level:
 * (1) new interior vertices have valence 4 (checked: the construction
 * guarantees it); (2) old interior vertices of valence 4 become 8 and (3) of
 * valence 8 stay 8 (measured and printed: a failure is a finding); the share
 * of valence-4/8 vertices; and the share of vertices whose 2-ring structure
 * is the same two levels (one 4-8 cycle) later. */
static void claims(const char *name, const ss_cx *input, int levels) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  if (ss_scheme_new("quasi48", &s, &err)) exit(1);
  ss_cx *cur = NULL;
  if (ss_cx_copy(input, &cur, &err)) exit(1);
  ss_triedge *te = edges_of(cur);
  uint64_t *sig[64] = {NULL};
  size_t nvl[64] = {0};
  printf("%s: %zu vertices, %zu triangles\n", name, cur->nv, cur->nc[SS_TRIANGLE]);
  for (int l = 0; l <= levels; l++) {
    size_t *mark = calloc(cur->nv + 1, sizeof *mark);
    sig[l] = malloc((cur->nv + 1) * sizeof *sig[l]);
    nvl[l] = cur->nv;
    size_t n48 = 0;
    for (size_t v = 0; v < cur->nv; v++) {
      sig[l][v] = ring2_signature(te, v, mark, v + 1);
      n48 += valence(te, v) == 4 || valence(te, v) == 8;
    }
    free(mark);
    /* a vertex born at level l0 has valence 4 there and 8 from l0 + 1 on, so
     * compare over one 4-8 cycle (l - 2 to l) only vertices born by l - 3 */
    if (l >= 3) {
      size_t same = 0;
      for (size_t v = 0; v < nvl[l - 3]; v++)
        same += sig[l][v] == sig[l - 2][v];
      printf("  level %d: %zu vertices, %.4f of valence 4 or 8; of the %zu vertices "
             "born by level %d, %.4f have the same 2-ring at levels %d and %d\n",
             l, cur->nv, (double)n48 / (double)cur->nv, nvl[l - 3], l - 3,
             (double)same / (double)nvl[l - 3], l - 2, l);
    }
    if (l == levels) break;
    ss_cx *next = NULL;
    if (ss_scheme_refine(s, cur, &next, NULL, &err)) {
      fprintf(stderr, "%s level %d: %s\n", name, l + 1, err.msg);
      exit(1);
    }
    ss_triedge *tn = edges_of(next);
    size_t new_bad = 0, n4 = 0, n4to8 = 0, n8 = 0, n8kept = 0;
    for (size_t v = cur->nv; v < next->nv; v++)
      if (!tn->vbnd[v] && valence(tn, v) != 4) new_bad++;
    for (size_t v = 0; v < cur->nv; v++) {
      if (te->vbnd[v]) continue;
      if (valence(te, v) == 4) n4++, n4to8 += valence(tn, v) == 8;
      if (valence(te, v) == 8) n8++, n8kept += valence(tn, v) == 8;
    }
    CHECK(new_bad == 0, "%s level %d: %zu new interior vertices of valence != 4", name,
          l + 1, new_bad);
    printf("  step %d: %zu new vertices (all interior ones of valence 4: %s); "
           "valence 4 -> 8: %zu of %zu; valence 8 kept: %zu of %zu\n",
           l + 1, next->nv - cur->nv, new_bad ? "NO" : "yes", n4to8, n4, n8kept, n8);
    ss_triedge_free(te);
    te = tn;
    ss_cx_free(cur);
    cur = next;
  }
  for (int l = 0; l <= levels; l++)
    free(sig[l]);
  ss_triedge_free(te);
  ss_cx_free(cur);
  ss_scheme_free(s);
}

/* The fan of n triangles about the origin with corners on the unit circle,
 * corners numbered in turn (the paper's section 3.3 example). */
static ss_cx *fan(int n) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  const double pi = 3.14159265358979323846;
  double o[2] = {0, 0};
  if (ss_cx_new(2, &cx, &err) || ss_cx_add_vertex(cx, o, 0, &err)) exit(1);
  for (int i = 0; i < n; i++) {
    double x[2] = {cos(2 * pi * i / n), sin(2 * pi * i / n)};
    if (ss_cx_add_vertex(cx, x, 0, &err)) exit(1);
  }
  for (int i = 0; i < n; i++) {
    ss_idx t[3] = {0, (ss_idx)(1 + i), (ss_idx)(1 + (i + 1) % n)};
    if (ss_cx_add_cell(cx, SS_TRIANGLE, t, 0, &err)) exit(1);
  }
  return cx;
}

/* Section 3.3: after one level the centre of a regular n-gon fan has valence
 * 2n for n < 6 (the boundary edges are longest), n for even n > 6 (every
 * other spoke splits) and n + 1 for odd n > 6 (one boundary edge too). */
static void test_fans(void) {
  const int ns[] = {3, 4, 5, 7, 8, 9, 11, 12, 16};
  for (size_t i = 0; i < sizeof ns / sizeof *ns; i++) {
    int n = ns[i];
    ss_cx *c = fan(n);
    gsl_spmatrix *R = NULL;
    ss_cx *f = op_refine("quasi48", c, &R);
    ss_triedge *te = edges_of(f);
    size_t want = n < 6 ? (size_t)(2 * n) : n % 2 == 0 ? (size_t)n : (size_t)n + 1;
    CHECK(valence(te, 0) == want,
          "fan n=%d: centre valence %zu after one level, the "
          "paper says %zu",
          n, valence(te, 0), want);
    /* and the boundary corners stayed where they were */
    double moved = 0;
    for (size_t v = 1; v <= (size_t)n; v++)
      for (int r = 0; r < 2; r++)
        moved = fmax(moved, fabs(f->x[2 * v + (size_t)r] - c->x[2 * v + (size_t)r]));
    CHECK(moved == 0.0, "fan n=%d: a boundary corner moved by %g", n, moved);
    ss_triedge_free(te);
    gsl_spmatrix_free(R);
    ss_cx_free(f);
    ss_cx_free(c);
  }
}

/* Figure 13: a triangulated cube after 4 levels, whose only extraordinary
 * vertices the paper says are the 8 corners.  Each quad of cube-surface.obj
 * is cut along its diagonal (0, 2).  Printed: how many vertices besides the
 * corners have a valence other than 4 or 8 (a finding if not 0). */
static ss_cx *cube_triangles(const ss_cx *quads) {
  ss_error err = {0};
  ss_cx *cx = NULL;
  if (ss_cx_new(quads->dim, &cx, &err)) exit(1);
  for (size_t v = 0; v < quads->nv; v++)
    if (ss_cx_add_vertex(cx, quads->x + v * (size_t)quads->dim, 0, &err)) exit(1);
  for (size_t q = 0; q < quads->nc[SS_QUAD]; q++) {
    const ss_idx *v = ss_cx_cell(quads, SS_QUAD, q);
    const ss_idx t0[3] = {v[0], v[1], v[2]}, t1[3] = {v[0], v[2], v[3]};
    if (ss_cx_add_cell(cx, SS_TRIANGLE, t0, 0, &err) ||
        ss_cx_add_cell(cx, SS_TRIANGLE, t1, 0, &err))
      exit(1);
  }
  return cx;
}

static void cube_claim(const ss_cx *cx) {
  ss_error err = {0};
  ss_cx *f = NULL;
  ss_scheme *s = NULL;
  if (ss_scheme_new("quasi48", &s, &err)) exit(1);
  if (ss_scheme_refine_levels(s, cx, 4, &f, &err)) {
    fprintf(stderr, "cube: %s\n", err.msg);
    exit(1);
  }
  ss_triedge *te = edges_of(f);
  size_t extra = 0, corners = 0;
  for (size_t v = 0; v < f->nv; v++) {
    size_t d = valence(te, v);
    if (d == 4 || d == 8) continue;
    if (v < cx->nv)
      corners++;
    else
      extra++;
  }
  printf("triangulated cube (figure 13), 4 levels: %zu vertices; extraordinary: %zu "
         "of the 8 corners, %zu others%s\n",
         f->nv, corners, extra, extra ? " (the paper says none)" : "");
  CHECK(f->nc[SS_TRIANGLE] > cx->nc[SS_TRIANGLE], "the cube was refined");
  ss_triedge_free(te);
  ss_cx_free(f);
  ss_scheme_free(s);
}

/* The bisect split alone, on a closed surface: the fine triangles cover the
 * coarse ones (total area kept), each coarse triangle is halved at most once
 * (T + sum over split edges of their triangles fine triangles), and the
 * clusters are maximal: every edge that did not split shares a triangle with
 * one that did (Algorithm 1 splits every unmarked edge). */
static void test_split(const ss_cx *cx) {
  ss_error err = {0};
  ss_cx *f = NULL;
  ss_split *L = NULL;
  if (ss_split_refine(SS_SPLIT_BISECT, cx, &f, &L, &err)) {
    fprintf(stderr, "bisect split: %s\n", err.msg);
    exit(1);
  }
  ss_triedge *te = edges_of(cx);
  unsigned char *split = calloc(te->ne + 1, 1), *touched = calloc(te->ne + 1, 1);
  size_t want = cx->nc[SS_TRIANGLE];
  for (size_t x = L->ncoarse; x < L->nfine; x++) {
    ss_idx a = L->parent[L->ptr[x]], b = L->parent[L->ptr[x] + 1];
    size_t e = 0;
    while (e < te->ne && !(te->end[2 * e] == a && te->end[2 * e + 1] == b))
      e++;
    CHECK(e < te->ne && ss_split_npar(L, x) == 2, "new vertex %zu is no edge midpoint",
          x);
    if (e == te->ne) continue;
    split[e] = 1;
    want += te->nface[e];
  }
  for (size_t e = 0; e < te->ne; e++)
    if (split[e])
      for (size_t j = 0; j < te->nface[e]; j++)
        for (int k = 0; k < 3; k++)
          touched[te->tedge[3 * te->face[2 * e + j] + (size_t)k]] = 1;
  size_t lonely = 0;
  for (size_t e = 0; e < te->ne; e++)
    lonely += !touched[e];
  CHECK(f->nc[SS_TRIANGLE] == want, "%zu fine triangles, expected %zu",
        f->nc[SS_TRIANGLE], want);
  CHECK(lonely == 0, "%zu edges neither split nor next to a split edge", lonely);
  double area[2] = {0, 0};
  for (int lev = 0; lev < 2; lev++) {
    const ss_cx *c = lev ? f : cx;
    for (size_t t = 0; t < c->nc[SS_TRIANGLE]; t++) {
      const ss_idx *v = ss_cx_cell(c, SS_TRIANGLE, t);
      const double *p0 = c->x + 3 * v[0], *p1 = c->x + 3 * v[1], *p2 = c->x + 3 * v[2];
      double u[3], w[3];
      for (int r = 0; r < 3; r++)
        u[r] = p1[r] - p0[r], w[r] = p2[r] - p0[r];
      double cx_ = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2],
             cz = u[0] * w[1] - u[1] * w[0];
      area[lev] += 0.5 * sqrt(cx_ * cx_ + cy * cy + cz * cz);
    }
  }
  CHECK(fabs(area[1] - area[0]) <= 1e-12 * area[0], "area %g after the split, %g before",
        area[1], area[0]);
  free(split);
  free(touched);
  ss_triedge_free(te);
  ss_split_free(L);
  ss_cx_free(f);
}

/* Without ties (a jittered mesh) the refinement depends on the geometry only:
 * relabelling vertices and turning triangles changes nothing. */
static void test_relabel(const ss_cx *ico) {
  ss_error err = {0};
  ss_cx *j = NULL, *a = NULL, *b = NULL;
  ss_scheme *s = NULL;
  if (ss_cx_copy(ico, &j, &err) || ss_scheme_new("quasi48", &s, &err)) exit(1);
  tm_jitter(j, 0.05, 7);
  ss_cx *p = tm_permuted(j, 11);
  if (ss_scheme_refine_levels(s, j, 4, &a, &err) ||
      ss_scheme_refine_levels(s, p, 4, &b, &err)) {
    fprintf(stderr, "relabel: %s\n", err.msg);
    exit(1);
  }
  CHECK(tm_same_geometry(a, b, 1e-12) == 0,
        "4 levels of a jittered icosahedron depend on its labelling");
  ss_cx_free(a);
  ss_cx_free(b);
  ss_cx_free(p);
  ss_cx_free(j);
  ss_scheme_free(s);
}

/* The longest-edge order does not depend on units: the jittered icosahedron
 * scaled by 2^-565 (about 1e-170) and by 2^531 (about 1e160) refines to the
 * same triangles, each position the unit one times the factor exactly (issue
 * 35: both scales were refused, one as "coincide", one as "no finite
 * length"). */
static void test_scale(const ss_cx *ico) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *j = NULL, *a = NULL;
  if (ss_cx_copy(ico, &j, &err) || ss_scheme_new("quasi48", &s, &err)) exit(1);
  tm_jitter(j, 0.05, 5);
  if (ss_scheme_refine_levels(s, j, 4, &a, &err)) exit(1);
  const int ex[2] = {-565, 531};
  for (int k = 0; k < 2; k++) {
    ss_cx *c = NULL, *b = NULL;
    if (ss_cx_copy(j, &c, &err)) exit(1);
    for (size_t i = 0; i < c->nv * (size_t)c->dim; i++)
      c->x[i] = ldexp(c->x[i], ex[k]);
    ss_status st = ss_scheme_refine_levels(s, c, 4, &b, &err);
    CHECK(st == SS_OK, "scale 2^%d: status %d, '%s'", ex[k], (int)st, err.msg);
    if (st == SS_OK) {
      size_t nt = a->nc[SS_TRIANGLE], bad = 0;
      CHECK(b->nv == a->nv && b->nc[SS_TRIANGLE] == nt, "scale 2^%d: other sizes", ex[k]);
      for (size_t i = 0; b->nv == a->nv && i < a->nv * (size_t)a->dim; i++)
        bad += b->x[i] != ldexp(a->x[i], ex[k]);
      for (size_t i = 0; b->nc[SS_TRIANGLE] == nt && i < 3 * nt; i++)
        bad += b->cells[SS_TRIANGLE][i] != a->cells[SS_TRIANGLE][i];
      CHECK(bad == 0, "scale 2^%d: %zu coordinates or corners differ", ex[k], bad);
    }
    ss_cx_free(b);
    ss_cx_free(c);
  }
  ss_cx_free(a);
  ss_cx_free(j);
  ss_scheme_free(s);
}

/* Non-manifold and zero-length edges and quadrilaterals are refused, each
 * with a message naming the problem. */
static void test_bad_input(void) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *cx = NULL, *f = NULL;
  if (ss_scheme_new("quasi48", &s, &err)) exit(1);
  const double x[5][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
  /* three triangles on the edge (1, 2) */
  if (ss_cx_new(3, &cx, &err)) exit(1);
  for (int i = 0; i < 4; i++)
    if (ss_cx_add_vertex(cx, x[i], 0, &err)) exit(1);
  double y[3] = {0, -1, 0};
  if (ss_cx_add_vertex(cx, y, 0, &err)) exit(1);
  const ss_idx t[3][3] = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  for (int i = 0; i < 3; i++)
    if (ss_cx_add_cell(cx, SS_TRIANGLE, t[i], 0, &err)) exit(1);
  ss_status st = ss_scheme_refine(s, cx, &f, NULL, &err);
  CHECK(st == SS_EINPUT && strstr(err.msg, "non-manifold edge") &&
            strstr(err.msg, "vertices 1 and 2"),
        "non-manifold edge: status %d, '%s'", (int)st, err.msg);
  CHECK(f == NULL, "no result on bad input");
  ss_cx_free(cx);
  /* vertex 5 sits on vertex 2: the edge (2, 5) has length zero */
  if (ss_cx_new(3, &cx, &err)) exit(1);
  for (int i = 0; i < 5; i++)
    if (ss_cx_add_vertex(cx, x[i], 0, &err)) exit(1);
  const ss_idx u[2][3] = {{0, 1, 2}, {1, 4, 3}};
  for (int i = 0; i < 2; i++)
    if (ss_cx_add_cell(cx, SS_TRIANGLE, u[i], 0, &err)) exit(1);
  st = ss_scheme_refine(s, cx, &f, NULL, &err);
  CHECK(st == SS_EINPUT && strstr(err.msg, "zero-length") &&
            strstr(err.msg, "vertices 2 and 5"),
        "zero-length edge: status %d, '%s'", (int)st, err.msg);
  ss_cx_free(cx);
  /* quadrilaterals */
  ss_cx *q = tm_torus(2, 3);
  st = ss_scheme_refine(s, q, &f, NULL, &err);
  CHECK(st == SS_EINPUT && strstr(err.msg, "does not take quadrilaterals"),
        "quads: status %d, '%s'", (int)st, err.msg);
  ss_cx_free(q);
  ss_scheme_free(s);
}

/* Tags (section 4.3): a tagged vertex or edge "is not affected by
 * smoothing".  On the icosahedron with vertex 4 a vertex cell and the five
 * edges at vertex 1 segment cells: vertex 4 stays put, bit for bit, for two
 * levels; every new vertex on a segment sits at the midpoint of its parents
 * (the split halves a segment with its edge, so the tag follows it); without
 * the tags both move. */
static int tagged_points_fixed(const ss_cx *coarse, const ss_cx *fine, const ss_split *L,
                               size_t *nmid) {
  int ok = 1;
  *nmid = 0;
  for (size_t i = 0; i < 2 * fine->nc[SS_SEGMENT]; i++) {
    const ss_idx x = fine->cells[SS_SEGMENT][i];
    if (x < coarse->nv) continue;
    ++*nmid;
    const ss_idx a = L->parent[L->ptr[x]], b = L->parent[L->ptr[x] + 1];
    for (int k = 0; k < 3; k++) {
      const double m =
          (coarse->x[3 * a + (size_t)k] + coarse->x[3 * b + (size_t)k]) / 2.0;
      ok &= fabs(fine->x[3 * x + (size_t)k] - m) <= 1e-15;
    }
  }
  return ok;
}

static void test_tags(const ss_cx *ico) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  REQUIRE_OK_VOID(ss_scheme_new("quasi48", &s, &err), &err);
  ss_cx *tagged = NULL;
  REQUIRE_OK_VOID(ss_cx_copy(ico, &tagged, &err), &err);
  const ss_idx corner = 3;
  REQUIRE_OK_VOID(ss_cx_add_cell(tagged, SS_VERTEX, &corner, 0, &err), &err);
  size_t nseg = 0;
  for (size_t t = 0; t < ico->nc[SS_TRIANGLE]; t++) { /* the edges (0, b) */
    const ss_idx *v = ss_cx_cell(ico, SS_TRIANGLE, t);
    for (int i = 0; i < 3; i++)
      if (v[i] == 0 && v[(i + 1) % 3] != 0) {
        const ss_idx e[2] = {0, v[(i + 1) % 3]};
        REQUIRE_OK_VOID(ss_cx_add_cell(tagged, SS_SEGMENT, e, 0, &err), &err);
        nseg++;
      }
  }
  CHECK(nseg == 5, "icosahedron: %zu edges at vertex 1", nseg);
  ss_cx *c = tagged, *f = NULL;
  size_t split_total = 0;
  for (int level = 1; level <= 2; level++) {
    ss_split *L = NULL;
    REQUIRE_OK_VOID(ss_scheme_refine_split(s, c, &f, NULL, &L, &err), &err);
    size_t nmid;
    CHECK(tagged_points_fixed(c, f, L, &nmid), "level %d: a tagged edge's point moved",
          level);
    /* each halved segment's new point is in its two halves */
    CHECK(nmid % 2 == 0 && f->nc[SS_SEGMENT] == c->nc[SS_SEGMENT] + nmid / 2,
          "level %d: %zu segments from %zu with %zu points on halves", level,
          f->nc[SS_SEGMENT], c->nc[SS_SEGMENT], nmid);
    CHECK(!memcmp(f->x + 3 * corner, ico->x + 3 * corner, 3 * sizeof(double)),
          "level %d: the tagged vertex moved", level);
    split_total += nmid;
    ss_split_free(L);
    if (c != tagged) ss_cx_free(c);
    c = f;
  }
  CHECK(split_total > 0, "no tagged edge was split in two levels");
  /* without the tags the same points move */
  ss_cx *plain = NULL;
  ss_split *Lp = NULL;
  REQUIRE_OK_VOID(ss_scheme_refine_split(s, ico, &plain, NULL, &Lp, &err), &err);
  double moved = 0.0;
  for (int k = 0; k < 3; k++)
    moved = fmax(moved,
                 fabs(plain->x[3 * corner + (size_t)k] - ico->x[3 * corner + (size_t)k]));
  CHECK(moved > 1e-3, "untagged, vertex 4 moves only %.3g", moved);
  ss_split_free(Lp);
  ss_cx_free(plain);
  ss_cx_free(c);
  ss_cx_free(tagged);
  ss_scheme_free(s);
}

int main(int argc, char **argv) {
  test_lattice();
  test_fans();
  test_bad_input();
  if (argc < 2) {
    fprintf(stderr, "usage: test_quasi48 MESHDIR\n");
    return 1;
  }
  char path[4096];
  ss_error err = {0};
  ss_cx *ico = NULL, *big = NULL;
  snprintf(path, sizeof path, "%s/icosahedron.obj", argv[1]);
  REQUIRE_OK(ss_mesh_read(path, SS_MESH_AUTO, &ico, &err), &err);
  claims("icosahedron.obj", ico, 10);
  test_relabel(ico);
  test_scale(ico);
  test_tags(ico);
  ss_cx *cube = NULL;
  snprintf(path, sizeof path, "%s/cube-surface.obj", argv[1]);
  REQUIRE_OK(ss_mesh_read(path, SS_MESH_AUTO, &cube, &err), &err);
  ss_cx *tcube = cube_triangles(cube);
  cube_claim(tcube);
  claims("cube-surface.obj, quads cut along (0, 2)", tcube, 8);
  ss_cx_free(tcube);
  ss_cx_free(cube);
  /* a >= 5000-triangle surface: the icosahedron after 4 Loop levels (5120) */
  ss_scheme *loop = NULL;
  REQUIRE_OK(ss_scheme_new("loop", &loop, &err), &err);
  REQUIRE_OK(ss_scheme_refine_levels(loop, ico, 4, &big, &err), &err);
  CHECK(big->nc[SS_TRIANGLE] == 5120, "Loop^4 icosahedron: %zu triangles",
        big->nc[SS_TRIANGLE]);
  test_split(ico);
  test_split(big);
  claims("icosahedron after 4 Loop levels", big, 6);
  ss_scheme_free(loop);
  ss_cx_free(big);
  /* a surface meshed by gmsh (tests/scheme/torus.geo, made at build time) */
  if (argc > 2) {
    ss_cx *torus = NULL;
    REQUIRE_OK(ss_mesh_read(argv[2], SS_MESH_AUTO, &torus, &err), &err);
    CHECK(torus->nc[SS_TRIANGLE] >= 5000 && torus->nc[SS_TRIANGLE] == ss_cx_ncells(torus),
          "gmsh torus: %zu triangles, and nothing else", torus->nc[SS_TRIANGLE]);
    test_split(torus);
    claims("torus meshed by gmsh", torus, 6);
    ss_cx_free(torus);
  } else {
    printf("SKIPPED part: the gmsh-made torus (no gmsh program or reader in this "
           "build)\n");
  }
  ss_cx_free(ico);
  return ss_test_done("test_quasi48");
}
