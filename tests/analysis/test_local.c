/* test_local.c — local subdivision matrices and their spectra against closed
 * forms and structure that would break if the mathematics were wrong:
 * Catmull–Clark's subdominant eigenvalue (for catmull-clark and for 2D mlca),
 * MLCA's vertex-parameter eigenvalues 1/4 and 1/16, Loop's subdominant
 * eigenvalue, the tricubic spectrum at a regular hex vertex, the tensor
 * product structure along MLCA edges, the tet/oct face and edge spectra,
 * invariance under relabelling and mirroring of the link, a global-vs-local
 * cross-check on real refined patches, and the verdict logic with its
 * tolerance on matrices whose spectrum is known by construction; a ring
 * deepened on kept levels equals the ring extracted that deep from the
 * start, bit for bit. */
#define _DEFAULT_SOURCE /* wait4: the peak memory of a child process */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gsl/gsl_rng.h>

#include "ss_eig.h"
#include "ss_enum.h"
#include "ss_link_random.h"
#include "ss_local.h"
#include "ss_split.h"
#include "ss_test.h"
#include "ss_testlink.h"

#define PI 3.14159265358979323846

static ss_scheme *scheme(const char *name) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  if (ss_scheme_new(name, &s, &err)) fprintf(stderr, "%s\n", err.msg);
  return s;
}

/* Local matrix and eigenstructure of one case (NULLs on failure, reported). */
static int analyse(const ss_scheme *s, ss_case c, ss_local **M, ss_eig **e) {
  ss_error err = {0};
  *M = NULL;
  *e = NULL;
  if (ss_local_new(s, &c, M, &err)) {
    CHECK(0, "%s %s n=%d: %s", ss_scheme_name(s), ss_case_name(c.kind), c.n, err.msg);
    return -1;
  }
  ss_eig_opts o = ss_eig_defaults((*M)->dim);
  if (ss_eig_new((*M)->S, (*M)->n2, (*M)->n1, &o, e, &err)) {
    CHECK(0, "eig: %s", err.msg);
    ss_local_free(*M);
    *M = NULL;
    return -1;
  }
  return 0;
}

static int by_value(const void *pa, const void *pb) {
  const double *a = pa, *b = pb;
  if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
  return (a[1] > b[1]) - (a[1] < b[1]);
}

/* The multiset of eigenvalues as (re, im) pairs sorted by value. */
static double *values(const ss_eig *e) {
  double *v = malloc(2 * e->n * sizeof *v);
  for (size_t i = 0; i < e->n; i++)
    v[2 * i] = e->val[i].re, v[2 * i + 1] = e->val[i].im;
  qsort(v, e->n, 2 * sizeof *v, by_value);
  return v;
}

/* Number of pairs of two sorted multisets of size n that differ by more than
 * tol. */
static size_t mismatches(const double *a, const double *b, size_t n, double tol) {
  size_t bad = 0;
  for (size_t i = 0; i < n; i++)
    bad +=
        !(fabs(a[2 * i] - b[2 * i]) <= tol && fabs(a[2 * i + 1] - b[2 * i + 1]) <= tol);
  return bad;
}

/* Count of eigenvalues within tol of x (real). */
static int count_near(const ss_eig *e, double x, double tol) {
  int c = 0;
  for (size_t i = 0; i < e->n; i++)
    c += fabs(e->val[i].re - x) <= tol && fabs(e->val[i].im) <= tol;
  return c;
}

static const double curve[5] = {1.0, 0.5, 0.25, 0.125, 0.125}; /* cubic B-spline
                                                                  two-ring spectrum */

/* The subdominant basis X (n x m) spans an invariant subspace of S for
 * lambda1..m: S X = X C with C = (X^T X)^-1 X^T S X, and trace C is the sum of
 * those eigenvalues.  Checked for residual and trace.  Without the eigenvalue
 * condition there must be no basis. */
static void check_basis(const ss_local *M, const ss_eig *e, const char *what) {
  if (e->cond.verdict != SS_PASS) { /* no map without the eigenvalue condition */
    CHECK(e->basis == NULL, "%s: a basis although the condition fails", what);
    return;
  }
  CHECK(e->basis != NULL, "%s: no subdominant basis", what);
  if (!e->basis) return;
  const size_t n = M->n2;
  const int m = e->m;
  double *SX = calloc(n * (size_t)m, sizeof *SX), G[9] = {0}, H[9] = {0}, C[9] = {0};
  for (int c = 0; c < m; c++)
    for (size_t i = 0; i < n; i++)
      for (size_t j = 0; j < n; j++)
        SX[(size_t)c * n + i] += M->S[i * n + j] * e->basis[(size_t)c * n + j];
  for (int a = 0; a < m; a++)
    for (int b = 0; b < m; b++)
      for (size_t i = 0; i < n; i++) {
        G[a * m + b] += e->basis[(size_t)a * n + i] * e->basis[(size_t)b * n + i];
        H[a * m + b] += e->basis[(size_t)a * n + i] * SX[(size_t)b * n + i];
      }
  /* C = G^-1 H by Gauss-Jordan (G is m x m, m <= 3, positive definite) */
  for (int col = 0; col < m; col++) {
    for (int r = 0; r < m; r++)
      C[r * m + col] = H[r * m + col];
  }
  for (int p = 0; p < m; p++) {
    const double d = G[p * m + p];
    for (int c = 0; c < m; c++)
      G[p * m + c] /= d, C[p * m + c] /= d;
    for (int r = 0; r < m; r++) {
      if (r == p) continue;
      const double f = G[r * m + p];
      for (int c = 0; c < m; c++)
        G[r * m + c] -= f * G[p * m + c], C[r * m + c] -= f * C[p * m + c];
    }
  }
  double res = 0.0, scale = 0.0, trace = 0.0, want = 0.0;
  for (int c = 0; c < m; c++) {
    trace += C[c * m + c];
    want += e->val[c + 1].re;
    for (size_t i = 0; i < n; i++) {
      double y = SX[(size_t)c * n + i];
      for (int k = 0; k < m; k++)
        y -= e->basis[(size_t)k * n + i] * C[k * m + c];
      res = fmax(res, fabs(y));
      scale = fmax(scale, fabs(e->basis[(size_t)c * n + i]));
    }
  }
  CHECK(res <= 1e-10 * scale, "%s: S X - X C = %g (basis not invariant)", what, res);
  CHECK_CLOSE(trace, want, 1e-10, "%s: trace of S on the basis", what);
  free(SX);
}

/* ---- 2D ---- */

static void test_surfaces(void) {
  ss_scheme *ml = scheme("mlca"), *cc = scheme("catmull-clark"), *lp = scheme("loop");
  for (int n = 3; n <= 12; n++) {
    const double c2 = cos(2 * PI / n), c1 = cos(PI / n);
    const double lcc = (5 + c2 + c1 * sqrt(2 * (9 + c2))) / 16, lloop = 3.0 / 8 + c2 / 4;
    ss_local *Mm, *Mc, *Ml;
    ss_eig *em, *ec, *el;
    ss_case c = {SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0};
    if (analyse(ml, c, &Mm, &em) || analyse(cc, c, &Mc, &ec) || analyse(lp, c, &Ml, &el))
      continue;
    CHECK(Mm->n2 == (size_t)(6 * n + 1) && Mm->n1 == (size_t)(2 * n + 1),
          "mlca n=%d: two-ring %zu one-ring %zu", n, Mm->n2, Mm->n1);
    CHECK(Mc->n2 == (size_t)(6 * n + 1) && Mc->n1 == (size_t)(2 * n + 1),
          "catmull-clark n=%d: two-ring %zu one-ring %zu", n, Mc->n2, Mc->n1);
    CHECK(Ml->n2 == (size_t)(3 * n + 1) && Ml->n1 == (size_t)(n + 1),
          "loop n=%d: two-ring %zu one-ring %zu", n, Ml->n2, Ml->n1);
    for (int i = 1; i <= 2; i++) {
      CHECK_CLOSE(em->val[i].re, lcc, 1e-10, "mlca n=%d lambda%d", n, i);
      CHECK_CLOSE(ec->val[i].re, lcc, 1e-10, "catmull-clark n=%d lambda%d", n, i);
      CHECK_CLOSE(el->val[i].re, lloop, 1e-10, "loop n=%d lambda%d", n, i);
    }
    check_basis(Mm, em, "mlca surface");
    check_basis(Mc, ec, "catmull-clark surface");
    check_basis(Ml, el, "loop surface");
    CHECK(em->cond.verdict == SS_PASS && ec->cond.verdict == SS_PASS &&
              el->cond.verdict == SS_PASS,
          "n=%d: eigenvalue condition %s / %s / %s", n, em->cond.reason, ec->cond.reason,
          el->cond.reason);
    /* MLCA's vertex-parameter eigenvalues 1/4 and 1/16 (MLCA paper, eq. 6): take
     * them out; every other eigenvalue must match Catmull–Clark's, leaving
     * exactly two of Catmull–Clark's (its own vertex-parameter pair) over */
    double *vm = values(em), *vc = values(ec);
    size_t nm = em->n, nc = ec->n;
    const double drop[2] = {0.25, 0.0625};
    for (int d = 0; d < 2; d++) {
      size_t i = 0;
      while (i < nm && !(fabs(vm[2 * i] - drop[d]) <= 1e-9 && vm[2 * i + 1] == 0.0))
        i++;
      CHECK(i < nm, "mlca n=%d has no eigenvalue %g", n, drop[d]);
      if (i < nm) {
        memmove(vm + 2 * i, vm + 2 * i + 2, 2 * (nm - i - 1) * sizeof *vm);
        nm--;
      }
    }
    size_t unmatched = 0;
    unsigned char *used = calloc(nc, 1);
    for (size_t i = 0; i < nm; i++) {
      size_t j = 0;
      while (j < nc && (used[j] || !(fabs(vm[2 * i] - vc[2 * j]) <= 1e-8 &&
                                     fabs(vm[2 * i + 1] - vc[2 * j + 1]) <= 1e-8)))
        j++;
      if (j < nc)
        used[j] = 1;
      else
        unmatched++;
    }
    CHECK(unmatched == 0 && nc - nm == 2,
          "n=%d: %zu mlca eigenvalues not found in catmull-clark's", n, unmatched);
    free(used);
    free(vm);
    free(vc);
    ss_eig_free(em), ss_eig_free(ec), ss_eig_free(el);
    ss_local_free(Mm), ss_local_free(Mc), ss_local_free(Ml);
  }
  ss_scheme_free(ml), ss_scheme_free(cc), ss_scheme_free(lp);
}

/* ---- 3D MLCA ---- */

static void test_mlca_regular(void) {
  ss_scheme *s = scheme("mlca");
  ss_link *oct = NULL;
  ss_error err = {0};
  ss_link_named("octahedron", &oct, &err);
  ss_local *M;
  ss_eig *e;
  if (!analyse(s, (ss_case){SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0}, &M, &e)) {
    CHECK(M->n2 == 125 && M->n1 == 27, "regular hex vertex: two-ring %zu, one-ring %zu",
          M->n2, M->n1);
    /* the tensor cube of the curve's two-ring spectrum */
    double expect[2 * 125];
    size_t n = 0;
    for (int a = 0; a < 5; a++)
      for (int b = 0; b < 5; b++)
        for (int c = 0; c < 5; c++, n++)
          expect[2 * n] = curve[a] * curve[b] * curve[c], expect[2 * n + 1] = 0.0;
    qsort(expect, 125, 2 * sizeof *expect, by_value);
    double *got = values(e);
    if (e->n == 125)
      CHECK(mismatches(got, expect, 125, 1e-9) == 0, "regular spectrum is not tricubic");
    free(got);
    CHECK(count_near(e, 0.5, 1e-9) == 3 && count_near(e, 0.25, 1e-9) == 6 &&
              count_near(e, 0.125, 1e-9) == 13,
          "1/2, 1/4, 1/8 multiplicities %d %d %d", count_near(e, 0.5, 1e-9),
          count_near(e, 0.25, 1e-9), count_near(e, 0.125, 1e-9));
    CHECK(e->val[1].mult == 3 && e->val[4].mult == 6 && e->val[10].mult == 13,
          "grouped multiplicities %d %d %d", e->val[1].mult, e->val[4].mult,
          e->val[10].mult);
    /* the one-ring block alone: 1/8 seven times */
    ss_eig *e1 = NULL;
    double *A = malloc(27 * 27 * sizeof *A);
    for (int i = 0; i < 27; i++)
      for (int j = 0; j < 27; j++)
        A[i * 27 + j] = M->S[(size_t)i * M->n2 + (size_t)j];
    ss_eig_opts o = ss_eig_defaults(3);
    if (!ss_eig_new(A, 27, 27, &o, &e1, &err)) {
      CHECK(count_near(e1, 0.125, 1e-9) == 7, "one-ring block: 1/8 x %d",
            count_near(e1, 0.125, 1e-9));
      ss_eig_free(e1);
    }
    free(A);
    CHECK(e->cond.verdict == SS_PASS, "regular vertex: %s", e->cond.reason);
    check_basis(M, e, "regular vertex");
    /* outer blocks: a point of [-2,2]^3 outside [-1,1]^3 keeps its +-2
     * coordinates (their rows read only themselves there), the others range
     * over [-1,1]; so one block per pattern of +-2 entries: 6 of 9 points,
     * 12 of 3, 8 of 1 */
    CHECK(e->nblocks == 26 && e->largest_block == 9,
          "regular vertex: %zu outer blocks, "
          "largest %zu (expected 26, 9)",
          e->nblocks, e->largest_block);
    ss_eig_free(e);
    ss_local_free(M);
  }
  ss_link_free(oct);
  ss_scheme_free(s);
}

static void test_mlca_edges(void) {
  ss_scheme *s = scheme("mlca");
  for (int n = 3; n <= 8; n++) {
    ss_local *M2, *M3;
    ss_eig *e2, *e3;
    if (analyse(s, (ss_case){SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0}, &M2, &e2))
      continue;
    if (analyse(s, (ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0}, &M3, &e3)) continue;
    CHECK(M3->n2 == 5 * M2->n2 && M3->n1 == 3 * M2->n1,
          "edge n=%d: two-ring %zu one-ring %zu", n, M3->n2, M3->n1);
    const size_t N = e2->n * 5;
    double *expect = malloc(2 * N * sizeof *expect);
    for (size_t i = 0; i < e2->n; i++)
      for (int c = 0; c < 5; c++) {
        expect[2 * (5 * i + c)] = e2->val[i].re * curve[c];
        expect[2 * (5 * i + c) + 1] = e2->val[i].im * curve[c];
      }
    qsort(expect, N, 2 * sizeof *expect, by_value);
    double *got = values(e3);
    if (e3->n == N)
      CHECK(mismatches(got, expect, N, 1e-8) == 0,
            "edge n=%d: spectrum is not 2D x curve", n);
    free(got);
    free(expect);
    check_basis(M3, e3, "mlca edge");
    ss_eig_free(e2), ss_eig_free(e3);
    ss_local_free(M2), ss_local_free(M3);
  }
  ss_scheme_free(s);
}

/* ---- tet/oct ---- */

static void test_tetoct(void) {
  ss_scheme *s = scheme("tetoct");
  ss_local *M;
  ss_eig *e;
  if (!analyse(s, (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, &M, &e)) {
    CHECK_CLOSE(e->val[0].re, 1.0, 1e-10, "face lambda0");
    for (int i = 1; i <= 3; i++)
      CHECK_CLOSE(e->val[i].re, 0.5, 1e-10, "face lambda%d", i);
    for (int i = 4; i <= 9; i++)
      CHECK_CLOSE(e->val[i].re, 0.25, 1e-10, "face lambda%d", i);
    CHECK(hypot(e->val[10].re, e->val[10].im) < 0.25 - 1e-3, "face: |lambda10| = %g",
          hypot(e->val[10].re, e->val[10].im));
    check_basis(M, e, "tetoct face");
    ss_eig_free(e);
    ss_local_free(M);
  }
  for (int n = 3; n <= 10; n++) {
    if (analyse(s, (ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0}, &M, &e)) continue;
    /* leading four: {1, l, l, 1/2} as a multiset, l real and not 1/2 */
    int half = -1;
    for (int i = 1; i <= 3; i++)
      if (fabs(e->val[i].re - 0.5) <= 1e-10) half = i;
    CHECK(half > 0, "edge n=%d: 1/2 not among the leading eigenvalues", n);
    double l[2];
    int m = 0;
    for (int i = 1; i <= 3 && half > 0; i++)
      if (i != half) l[m++] = e->val[i].re;
    CHECK(m == 2 && fabs(l[0] - l[1]) <= 1e-10 && fabs(l[0] - 0.5) > 1e-3 &&
              e->val[1].im == 0.0 && e->val[2].im == 0.0 && e->val[3].im == 0.0,
          "edge n=%d: leading eigenvalues are not 1, l, l, 1/2", n);
    CHECK(e->val[1].mult + e->val[2].mult + e->val[3].mult == 5,
          "edge n=%d: multiplicities %d %d %d", n, e->val[1].mult, e->val[2].mult,
          e->val[3].mult);
    check_basis(M, e, "tetoct edge");
    ss_eig_free(e);
    ss_local_free(M);
  }
  ss_scheme_free(s);
}

/* ---- sizes and invariance over many links ---- */

typedef struct {
  ss_scheme *mlca, *tetoct;
  int count;
} links_ctx;

static int visit(const ss_link *l, void *vctx) {
  links_ctx *ctx = vctx;
  const int k = l->k;
  ss_scheme *ss[2] = {ctx->mlca, ctx->tetoct};
  for (int si = 0; si < 2; si++) {
    ss_local *M;
    ss_eig *e;
    if (analyse(ss[si], (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, &M, &e))
      continue;
    if (si == 0)
      CHECK(M->n2 == (size_t)(30 * k - 55) && M->n1 == (size_t)(6 * k - 9),
            "mlca k=%d: two-ring %zu one-ring %zu", k, M->n2, M->n1);
    else
      CHECK(M->n2 == (size_t)(5 * k - 5) && M->n1 == (size_t)(k + 1),
            "tetoct k=%d: two-ring %zu one-ring %zu", k, M->n2, M->n1);
    check_basis(M, e, ss_scheme_name(ss[si]));
    double *ref = values(e);
    for (int mirror = 0; mirror < 2; mirror++) {
      ss_link *r = ss_testlink_scrambled(l, (unsigned)(ctx->count * 7 + mirror), mirror);
      ss_local *M2;
      ss_eig *e2;
      if (r &&
          !analyse(ss[si], (ss_case){SS_CASE_VERTEX, r, 0, SS_DIAG_BFS, 0}, &M2, &e2)) {
        double *v = values(e2);
        CHECK(M2->n2 == M->n2 && M2->n1 == M->n1 && mismatches(v, ref, e->n, 1e-9) == 0,
              "%s k=%d link %d: spectrum changes under relabelling (mirror %d)",
              ss_scheme_name(ss[si]), k, ctx->count, mirror);
        free(v);
        ss_eig_free(e2);
        ss_local_free(M2);
      }
      ss_link_free(r);
    }
    free(ref);
    ss_eig_free(e);
    ss_local_free(M);
  }
  ctx->count++;
  return 0;
}

static void test_links(void) {
  links_ctx ctx = {scheme("mlca"), scheme("tetoct"), 0};
  ss_enum_opts o = {4, 8, 0, 1};
  ss_error err = {0};
  CHECK(ss_enum_links(&o, visit, &ctx, NULL, &err) == SS_OK, "%s", err.msg);
  CHECK(ctx.count == 1 + 1 + 2 + 5 + 14, "visited %d links", ctx.count);
  ss_scheme_free(ctx.mlca);
  ss_scheme_free(ctx.tetoct);
}

/* ---- global vs local ---- */

/* Fine coordinates: 2 * mean of the split parents' (dense, nc per vertex). */
static long *fine_coords(const ss_split *L, const long *co, int nc) {
  long *fc = calloc(L->nfine * (size_t)nc + 1, sizeof *fc);
  for (size_t v = 0; v < L->nfine; v++) {
    const long np = (long)ss_split_npar(L, v);
    for (size_t q = L->ptr[v]; q < L->ptr[v + 1]; q++)
      for (int i = 0; i < nc; i++)
        fc[v * (size_t)nc + (size_t)i] += 2 * co[L->parent[q] * (size_t)nc + (size_t)i];
    for (int i = 0; i < nc; i++)
      fc[v * (size_t)nc + (size_t)i] /= np;
  }
  return fc;
}

/* Refine the star of case c with scheme s to level w + 1, tracking exact
 * coordinates independently of ss_local (2 * mean of the split parents), give
 * the level-w vertices random positions, refine once more as a whole mesh, and
 * compare the fine two-ring with S times the coarse two-ring. */
static void cross_check(const ss_scheme *s, ss_case c, const char *what) {
  ss_error err = {0};
  ss_local *M = NULL;
  ss_star *star = NULL;
  if (ss_local_new(s, &c, &M, &err) || ss_case_star(s, &c, &star, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
    ss_local_free(M);
    return;
  }
  ss_cx *cx = NULL;
  ss_cx_copy(star->cx, &cx, &err);
  const int nc = star->ncoord;
  long *co = malloc(cx->nv * (size_t)nc * sizeof *co);
  memset(co, 0, cx->nv * (size_t)nc * sizeof *co);
  for (size_t v = 0; v < cx->nv; v++)
    for (int i = 0; i < star->coord[v].n; i++)
      co[v * (size_t)nc + (size_t)star->coord[v].idx[i]] = star->coord[v].val[i];
  for (int l = 0; l < M->level; l++) {
    ss_cx *f = NULL;
    ss_split *L = NULL;
    if (ss_scheme_refine_split(s, cx, &f, NULL, &L, &err)) {
      CHECK(0, "%s: %s", what, err.msg);
      break;
    }
    long *fc = fine_coords(L, co, nc);
    free(co);
    co = fc;
    ss_split_free(L);
    ss_cx_free(cx);
    cx = f;
  }
  /* the centre's coordinates on level w (the face case's centre is 1/4 (2,1,1)
   * of the face on level 2) */
  long *cp = calloc((size_t)nc, sizeof *cp);
  if (c.kind == SS_CASE_FACE) {
    const long sc = 1L << (M->level - 2);
    cp[0] = 2 * sc, cp[1] = sc, cp[2] = sc;
  }
  /* random positions on level w */
  srand(12345);
  for (size_t i = 0; i < cx->nv * (size_t)cx->dim; i++)
    cx->x[i] = (double)rand() / RAND_MAX - 0.5;
  ss_cx *f = NULL;
  ss_split *L = NULL;
  ss_scheme_refine_split(s, cx, &f, NULL, &L, &err);
  /* find the label's vertex on a level by brute force over dense coordinates */
  size_t *cidx = malloc(M->n2 * sizeof *cidx), *fidx = malloc(M->n2 * sizeof *fidx);
  long *want = malloc((size_t)nc * sizeof *want);
  size_t missing = 0;
  long *fco = fine_coords(L, co, nc);
  for (size_t j = 0; j < M->n2; j++) {
    for (int pass = 0; pass < 2; pass++) {
      const long scale = pass ? 2 : 1;
      for (int i = 0; i < nc; i++)
        want[i] = scale * cp[i];
      for (int e = 0; e < M->label[j].n; e++)
        want[M->label[j].idx[e]] += M->label[j].val[e];
      const ss_cx *X = pass ? f : cx;
      size_t found = SIZE_MAX;
      const long *cc = pass ? fco : co;
      for (size_t v = 0; v < X->nv && found == SIZE_MAX; v++)
        if (!memcmp(cc + v * (size_t)nc, want, (size_t)nc * sizeof *want)) found = v;
      if (found == SIZE_MAX) missing++;
      (pass ? fidx : cidx)[j] = found;
    }
  }
  CHECK(missing == 0, "%s: %zu labels not found in the refined patch", what, missing);
  double worst = 0.0;
  for (size_t i = 0; missing == 0 && i < M->n2; i++)
    for (int d = 0; d < cx->dim; d++) {
      double y = 0.0;
      for (size_t j = 0; j < M->n2; j++)
        y += M->S[i * M->n2 + j] * cx->x[cidx[j] * (size_t)cx->dim + (size_t)d];
      worst = fmax(worst, fabs(y - f->x[fidx[i] * (size_t)f->dim + (size_t)d]));
    }
  CHECK(worst <= 1e-12, "%s: global and local subdivision differ by %g", what, worst);
  free(cidx), free(fidx), free(want), free(cp), free(co), free(fco);
  ss_split_free(L);
  ss_cx_free(f);
  ss_cx_free(cx);
  ss_star_free(star);
  ss_local_free(M);
}

static void test_cross(void) {
  ss_scheme *ml = scheme("mlca"), *to = scheme("tetoct"), *cc = scheme("catmull-clark"),
            *lp = scheme("loop");
  /* the k = 8 link is the one whose MLCA characteristic map fails
   * (test_charmap.c): its matrix must be right */
  const char *links[] = {"tetrahedron", "bipyramid:5",
                         "7 bcdef,afgc,abgd,acge,adgf,aegb,bfedc", "icosahedron",
                         "8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb"};
  for (int i = 0; i < 5; i++) {
    ss_link *l = NULL;
    ss_error err = {0};
    if (ss_link_parse(links[i], &l, &err)) {
      CHECK(0, "%s: %s", links[i], err.msg);
      continue;
    }
    cross_check(ml, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, links[i]);
    cross_check(to, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, links[i]);
    ss_link_free(l);
  }
  {
    /* box-spline solids: vertex, edge and face cases */
    ss_scheme *bx = scheme("boxspline");
    ss_link *l = NULL;
    ss_error err = {0};
    if (!ss_link_parse("bipyramid:5", &l, &err))
      cross_check(bx, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0},
                  "boxspline bipyramid:5");
    cross_check(bx, (ss_case){SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0}, "boxspline edge 5");
    cross_check(bx, (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, "boxspline face");
    cross_check(bx, (ss_case){SS_CASE_EDGE, NULL, 6, SS_DIAG_SKEW, 0},
                "boxspline edge 6 skew");
    cross_check(bx, (ss_case){SS_CASE_EDGE, NULL, 6, SS_DIAG_CENTER, 0},
                "boxspline edge 6 center");
    ss_scheme *av = scheme("boxspline-avg");
    if (l)
      cross_check(av, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0},
                  "boxspline-avg bipyramid:5");
    cross_check(av, (ss_case){SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0},
                "boxspline-avg edge 5");
    cross_check(av, (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0},
                "boxspline-avg face");
    ss_link_free(l);
    ss_scheme_free(av);
    ss_scheme_free(bx);
  }
  cross_check(ml, (ss_case){SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0}, "mlca edge 5");
  cross_check(to, (ss_case){SS_CASE_EDGE, NULL, 7, SS_DIAG_BFS, 0}, "tetoct edge 7");
  cross_check(to, (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, "tetoct face");
  cross_check(cc, (ss_case){SS_CASE_SURFACE_VERTEX, NULL, 5, SS_DIAG_BFS, 0},
              "catmull-clark 5");
  cross_check(lp, (ss_case){SS_CASE_SURFACE_VERTEX, NULL, 7, SS_DIAG_BFS, 0}, "loop 7");
  ss_scheme_free(ml), ss_scheme_free(to), ss_scheme_free(cc), ss_scheme_free(lp);
}

/* ---- the verdict on matrices of known spectrum ---- */

/* Verdict for the upper triangular matrix with diagonal d (n <= 8) plus an
 * optional 2 x 2 rotation block at rows 1, 2 (complex pair). */
static ss_verdict_kind verdict_of(const double *d, int n, int dim, int rot, double tol,
                                  int *mult1) {
  double S[64] = {0};
  for (int i = 0; i < n; i++)
    S[i * n + i] = d[i];
  for (int i = 0; i + 1 < n; i++)
    S[i * n + i + 1] = 0.01; /* not symmetric, still triangular */
  if (rot) {
    S[1 * n + 1] = S[2 * n + 2] = 0.4;
    S[1 * n + 2] = 0.3, S[2 * n + 1] = -0.3;
  }
  ss_eig_opts o = ss_eig_defaults(dim);
  o.tol = tol;
  o.basis = 0;
  ss_eig *e = NULL;
  ss_error err = {0};
  if (ss_eig_new(S, (size_t)n, (size_t)n, &o, &e, &err)) {
    CHECK(0, "%s", err.msg);
    return SS_UNDECIDED;
  }
  ss_verdict_kind v = e->cond.verdict;
  if (mult1) *mult1 = e->val[1].mult;
  ss_eig_free(e);
  return v;
}

static void test_verdicts(void) {
  const double ok[6] = {1, 0.5, 0.4, 0.3, 0.2, 0.1};
  const double tie34[6] = {1, 0.5, 0.4, 0.3, 0.3, 0.1};
  const double near34[6] = {1,  0.5, 0.4, 0.3, 0.3 * (1 - 1e-3),
                            0.1}; /* a genuine near-tie */
  const double split[6] = {1, 0.5, 0.5 * (1 + 1e-9), 0.5 * (1 - 1e-9), 0.2, 0.1};
  const double double1[6] = {1, 1, 0.4, 0.3, 0.2, 0.1};
  const double negative[6] = {1, 0.5, 0.4, -0.3, 0.2, 0.1};
  const double neg4[6] = {1, 0.5, 0.4, 0.3, -0.3, 0.1};
  int m = 0;
  CHECK(verdict_of(ok, 6, 3, 0, 1e-6, NULL) == SS_PASS, "distinct spectrum");
  CHECK(verdict_of(tie34, 6, 3, 0, 1e-6, NULL) == SS_FAIL, "lambda3 = lambda4");
  CHECK(verdict_of(neg4, 6, 3, 0, 1e-6, NULL) == SS_FAIL, "lambda3 = |lambda4|");
  CHECK(verdict_of(near34, 6, 3, 0, 1e-6, NULL) == SS_PASS, "near-tie 1e-3 kept apart");
  CHECK(verdict_of(near34, 6, 3, 0, 1e-2, NULL) == SS_FAIL, "near-tie within tol 1e-2");
  CHECK(verdict_of(split, 6, 3, 0, 1e-6, &m) == SS_PASS && m == 3,
        "a tie split by rounding is one group (mult %d)", m);
  CHECK(verdict_of(double1, 6, 3, 0, 1e-6, NULL) == SS_FAIL, "eigenvalue 1 twice");
  CHECK(verdict_of(negative, 6, 3, 0, 1e-6, NULL) == SS_FAIL, "negative lambda3");
  CHECK(verdict_of(ok, 6, 3, 1, 1e-6, NULL) == SS_FAIL, "complex lambda1");
  CHECK(verdict_of(tie34, 6, 2, 0, 1e-6, NULL) == SS_PASS, "2D: lambda2 > |lambda3|");
  /* below the rounding floor (ss_eig.h): the tolerance is raised, an exact tie
   * still fails, a distinct spectrum still passes, and a gap that only the
   * requested tolerance would resolve (1e-11 relative, coupled by 0.01: far
   * below the cluster's rounding) is undecided, not a pass */
  const double near11[6] = {1, 0.5, 0.4, 0.3, 0.3 * (1 - 1e-11), 0.1};
  CHECK(verdict_of(ok, 6, 3, 0, 1e-15, NULL) == SS_PASS, "distinct spectrum at 1e-15");
  CHECK(verdict_of(tie34, 6, 3, 0, 1e-15, NULL) == SS_FAIL, "lambda3 = lambda4 at 1e-15");
  CHECK(verdict_of(double1, 6, 3, 0, 1e-15, NULL) == SS_FAIL, "1 twice at 1e-15");
  CHECK(verdict_of(split, 6, 3, 0, 1e-15, &m) == SS_PASS && m == 3,
        "a tie split by rounding at 1e-15 (mult %d)", m);
  CHECK(verdict_of(near11, 6, 3, 0, 1e-15, NULL) == SS_UNDECIDED,
        "near-tie 1e-11 at 1e-15: rounding decides");
  CHECK(verdict_of(near11, 6, 3, 0, 1e-6, NULL) == SS_FAIL, "near-tie 1e-11 at 1e-6");
  /* condition numbers: a symmetric matrix (Q diag(1, 1/2, 1/4) Q^T, Q a
   * rotation) has perfectly conditioned eigenvalues, rcond = 1 */
  const double c = cos(0.3), sn = sin(0.3), d[3] = {1.0, 0.5, 0.25};
  const double Q[9] = {c, -sn, 0, sn * c, c * c, -sn, sn * sn, sn * c, c};
  double A[9] = {0};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      for (int k = 0; k < 3; k++)
        A[i * 3 + j] += Q[i * 3 + k] * d[k] * Q[j * 3 + k];
  ss_eig_opts o = ss_eig_defaults(2);
  o.basis = 0;
  ss_eig *e = NULL;
  ss_error err = {0};
  if (!ss_eig_new(A, 3, 3, &o, &e, &err)) {
    for (int i = 0; i < 3; i++) {
      CHECK_CLOSE(e->val[i].re, d[i], 1e-12, "symmetric: eigenvalue %d", i);
      CHECK_CLOSE(e->val[i].rcond, 1.0, 1e-12, "symmetric: rcond of eigenvalue %d", i);
    }
    ss_eig_free(e);
  } else {
    CHECK(0, "%s", err.msg);
  }
}
/* A vertex whose link is the bipyramid over n is a point on an edge of
 * valence n (ss_case_edge_point): in a hex mesh its star is the edge
 * midpoint's, so the vertex and the edge case must give one local matrix (the
 * same sizes and spectrum), and only hex schemes call it an edge point. */
static void test_edge_points(void) {
  ss_scheme *mlca = scheme("mlca"), *tetoct = scheme("tetoct");
  ss_error err = {0};
  for (int n = 3; n <= 9; n++) {
    char name[32];
    snprintf(name, sizeof name, "bipyramid:%d", n);
    ss_link *l = NULL;
    if (ss_link_named(name, &l, &err)) {
      CHECK(0, "%s: %s", name, err.msg);
      continue;
    }
    CHECK(ss_case_edge_point(mlca, l) == (n == 4 ? 0 : n), "%s: edge point %d", name,
          ss_case_edge_point(mlca, l));
    CHECK(ss_case_edge_point(tetoct, l) == 0, "%s: tet stars have no edge points", name);
    /* a relabelled copy is recognised too; a link that is no bipyramid is not */
    ss_link *q = ss_testlink_scrambled(l, (unsigned)n, n & 1);
    CHECK(q && ss_case_edge_point(mlca, q) == (n == 4 ? 0 : n), "%s relabelled", name);
    ss_link_free(q);
    ss_local *Mv = NULL, *Me = NULL;
    ss_eig *ev = NULL, *ee = NULL;
    if (!analyse(mlca, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, &Mv, &ev) &&
        !analyse(mlca, (ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0}, &Me, &ee)) {
      CHECK(Mv->n2 == Me->n2 && Mv->n1 == Me->n1,
            "%s: vertex two-ring %zu / one-ring %zu, edge %zu / %zu", name, Mv->n2,
            Mv->n1, Me->n2, Me->n1);
      if (Mv->n2 == Me->n2) {
        double *a = values(ev), *b = values(ee);
        CHECK(mismatches(a, b, Mv->n2, 1e-10) == 0, "%s: vertex and edge spectra differ",
              name);
        free(a);
        free(b);
      }
    }
    ss_eig_free(ev);
    ss_eig_free(ee);
    ss_local_free(Mv);
    ss_local_free(Me);
    ss_link_free(l);
  }
  ss_link *ico = NULL;
  if (!ss_link_named("icosahedron", &ico, &err))
    CHECK(ss_case_edge_point(mlca, ico) == 0, "the icosahedron is no edge point");
  ss_link_free(ico);
  ss_scheme_free(mlca);
  ss_scheme_free(tetoct);
}

/* ---- the cost estimate (ss_local_estimate) ---- */

/* Rows of S estimated exactly, for every built-in scheme and case kind:
 * named links, random links (conical counts depend on k only), edges with
 * every diagonal choice, the face, surfaces. */
static void estimate_rows(const ss_scheme *s, ss_case c, const char *what) {
  ss_error err = {0};
  ss_local_cost k;
  ss_local *M = NULL;
  if (ss_local_estimate(s, &c, &k, &err) || ss_local_new(s, &c, &M, &err)) {
    CHECK(0, "%s %s: %s", ss_scheme_name(s), what, err.msg);
    return;
  }
  CHECK(k.n2 == M->n2 && k.n1 == M->n1,
        "%s %s: estimated %zu / %zu rows, extracted %zu / %zu", ss_scheme_name(s), what,
        k.n2, k.n1, M->n2, M->n1);
  CHECK(k.block <= k.n2 - k.n1 && k.star_cells > 0 && k.bytes >= 2 * k.dense_bytes &&
            k.dense_bytes == 8.0 * (double)k.n2 * (double)k.n2 && k.seconds > 0.0,
        "%s %s: inconsistent estimate", ss_scheme_name(s), what);
  ss_local_free(M);
}

#if !defined(__SANITIZE_ADDRESS__)
/* Peak resident memory (bytes) of extracting and solving case c, measured in
 * a child process (wait4's ru_maxrss), or -1. */
static double peak_bytes(const ss_scheme *s, ss_case c) {
  fflush(NULL);
  const pid_t pid = fork();
  if (pid < 0) return -1.0;
  if (pid == 0) {
    ss_local *M = NULL;
    ss_eig *e = NULL;
    int ok = analyse(s, c, &M, &e) == 0;
    ss_eig_free(e);
    ss_local_free(M);
    _exit(ok ? 0 : 1);
  }
  int status = 0;
  struct rusage ru;
  if (wait4(pid, &status, 0, &ru) != pid || !WIFEXITED(status) || WEXITSTATUS(status))
    return -1.0;
  return 1024.0 * (double)ru.ru_maxrss;
}
#endif

static void test_estimate(void) {
  static const char *const names[] = {
      "mlca", "tetoct", "boxspline", "boxspline-avg", "catmull-clark", "loop", "ccsolid"};
  static const char *const links[] = {"tetrahedron", "octahedron", "icosahedron",
                                      "bipyramid:5"};
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 16);
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
    ss_scheme *s = scheme(names[i]);
    const int vol = ss_scheme_accepts(s, SS_HEX) || ss_scheme_accepts(s, SS_TET);
    ss_error err = {0};
    char what[64];
    for (size_t j = 0; vol && j < sizeof links / sizeof links[0] + 2; j++) {
      ss_link *l = NULL;
      const ss_status st = j < 4 ? ss_link_named(links[j], &l, &err)
                                 : ss_link_random(j == 4 ? 9 : 17, rng, &l, &err);
      if (st) {
        CHECK(0, "link %zu: %s", j, err.msg);
        continue;
      }
      snprintf(what, sizeof what, "vertex k = %d", l->k);
      estimate_rows(s, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, what);
      ss_link_free(l);
    }
    const int box = ss_scheme_reads_diagonals(s);
    for (int n = 3; vol && n <= 9; n += 1 + (n > 5)) {
      for (int d = 0; d < (box ? 3 : 1); d++) {
        const ss_diag_mode m = d == 0   ? SS_DIAG_BFS
                               : d == 1 ? SS_DIAG_SKEW
                                        : SS_DIAG_CENTER;
        snprintf(what, sizeof what, "edge %d, diagonals %s", n, ss_diag_name(m));
        estimate_rows(s, (ss_case){SS_CASE_EDGE, NULL, n, m, 0}, what);
      }
    }
    if (ss_scheme_split_kind(s) == SS_SPLIT_TETOCT && vol)
      estimate_rows(s, (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, "face");
    for (int n = 3; n <= 8; n += 1 + (n > 4))
      if (ss_scheme_accepts(s, SS_QUAD) || ss_scheme_accepts(s, SS_TRIANGLE)) {
        snprintf(what, sizeof what, "surface vertex %d", n);
        estimate_rows(s, (ss_case){SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0},
                      what);
      }
    ss_scheme_free(s);
  }
  gsl_rng_free(rng);
  /* the budget refuses before building anything, with the estimate */
  ss_scheme *mlca = scheme("mlca"), *tetoct = scheme("tetoct");
  ss_error err = {0};
  ss_local_opts o = ss_local_defaults();
  o.max_bytes = 1e9;
  ss_local *M = NULL;
  const ss_case big = {SS_CASE_EDGE, NULL, 1000, SS_DIAG_BFS, 0};
  CHECK(ss_local_new_opts(mlca, &big, &o, &M, &err) == SS_ENOMEM && !M &&
            strstr(err.msg, "needs about 30005 rows of S") &&
            strstr(err.msg, "budget of 1.0 GB"),
        "edge 1000 under a 1 GB budget: %s", err.msg);
  CHECK(ss_local_memory_budget() > 0.0, "no default budget");
  /* memory within a factor 2 of the measured peak, for cases of 50..300 MB
   * (not under AddressSanitizer, whose shadow memory inflates the peak) */
#if !defined(__SANITIZE_ADDRESS__)
  const struct {
    const ss_scheme *s;
    ss_case c;
  } mem[] = {{mlca, {SS_CASE_EDGE, NULL, 40, SS_DIAG_BFS, 0}},
             {tetoct, {SS_CASE_EDGE, NULL, 60, SS_DIAG_BFS, 0}},
             {mlca, {SS_CASE_SURFACE_VERTEX, NULL, 400, SS_DIAG_BFS, 0}}};
  for (size_t i = 0; i < sizeof mem / sizeof mem[0]; i++) {
    ss_local_cost k;
    if (ss_local_estimate(mem[i].s, &mem[i].c, &k, &err)) {
      CHECK(0, "%s", err.msg);
      continue;
    }
    const double peak = peak_bytes(mem[i].s, mem[i].c);
    CHECK(peak > 0 && k.bytes <= 2.0 * peak && peak <= 2.0 * k.bytes,
          "%s %s %d: estimated %.0f MB, measured %.0f MB", ss_scheme_name(mem[i].s),
          ss_case_name(mem[i].c.kind), mem[i].c.n, k.bytes / 1e6, peak / 1e6);
    fprintf(stderr, "memory %s %s %d: estimated %.0f MB, measured %.0f MB\n",
            ss_scheme_name(mem[i].s), ss_case_name(mem[i].c.kind), mem[i].c.n,
            k.bytes / 1e6, peak / 1e6);
  }
#endif
  ss_scheme_free(mlca);
  ss_scheme_free(tetoct);
}

/* Whether rings a and b are equal bit for bit (points, rows, cells,
 * coordinates). */
static int same_ring(const ss_local_ring *a, const ss_local_ring *b) {
  if (a->nv != b->nv || a->nprev != b->nprev || a->ncells != b->ncells) return 0;
  for (size_t i = 0; i < a->nv; i++)
    if (ss_star_coord_cmp(a->coord + i, b->coord + i)) return 0;
  const size_t nnz = a->ptr[a->nv];
  return nnz == b->ptr[b->nv] && !memcmp(a->ptr, b->ptr, (a->nv + 1) * sizeof *a->ptr) &&
         !memcmp(a->col, b->col, nnz * sizeof *a->col) &&
         !memcmp(a->w, b->w, nnz * sizeof *a->w) &&
         !memcmp(a->ctype, b->ctype, a->ncells * sizeof *a->ctype) &&
         !memcmp(a->corner, b->corner, a->ncells * SS_MAXCELLVERTS * sizeof *a->corner);
}

/* ss_local_ring_deepen on kept levels (ss_local_opts.keep_levels) adds only
 * the levels it lacks; its ring must be the ring of an extraction with that
 * many levels from the start: MLCA (reach 1) and tet/oct vertices, an MLCA
 * edge, deepened 2 -> 3 -> 4 and 2 -> 4, and S untouched. */
static void test_deepen(void) {
  const char *names[2] = {"mlca", "tetoct"};
  ss_link *l = NULL;
  ss_error err = {0};
  if (ss_link_named("icosahedron", &l, &err)) {
    CHECK(0, "icosahedron: %s", err.msg);
    return;
  }
  for (int q = 0; q < 3; q++) {
    ss_scheme *s = scheme(names[q == 1]);
    const ss_case c = q < 2 ? (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}
                            : (ss_case){SS_CASE_EDGE, NULL, 5, SS_DIAG_BFS, 0};
    for (int steps = 1; steps <= 2 && s; steps++) {
      ss_local_opts o = ss_local_defaults();
      o.keep_levels = 1;
      ss_local *K = NULL, *F[SS_LOCAL_MAXRING + 1] = {NULL};
      ss_status st = ss_local_new_opts(s, &c, &o, &K, &err);
      for (int n = SS_LOCAL_RING; !st && n <= SS_LOCAL_MAXRING; n++)
        st = ss_local_new_ring(s, &c, n, &F[n], &err);
      const double *S0 = K ? K->S : NULL;
      for (int n = SS_LOCAL_RING + (steps == 1 ? 1 : 2); !st && n <= SS_LOCAL_MAXRING;
           n += steps) {
        st = ss_local_ring_deepen(s, &c, n, K, &err);
        if (st) break;
        int same = K->nring == n && F[n]->nring == n && K->S == S0 &&
                   !memcmp(K->S, F[n]->S, K->n2 * K->n2 * sizeof *K->S);
        for (int r = 0; r < n && same; r++)
          same = same_ring(K->ring + r, F[n]->ring + r);
        CHECK(same,
              "%s %s: the ring deepened on kept levels to %d differs from the "
              "ring extracted with %d levels",
              names[q == 1], q < 2 ? "icosahedron vertex" : "edge 5", n, n);
      }
      CHECK(!st, "%s: %s", names[q == 1], err.msg);
      ss_local_free(K);
      for (int n = 0; n <= SS_LOCAL_MAXRING; n++)
        ss_local_free(F[n]);
    }
    ss_scheme_free(s);
  }
  ss_link_free(l);
}

int main(void) {
  test_verdicts();
  test_surfaces();
  test_mlca_regular();
  test_mlca_edges();
  test_tetoct();
  test_links();
  test_cross();
  test_edge_points();
  test_estimate();
  test_deepen();
  return ss_test_done("local");
}
