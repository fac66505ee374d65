/* test_sink.c — the two assemblies of a refinement operator (ss_sink.h): a
 * triplet list merged by ss_triplets_csr, and rows written in order
 * (ss_rows), must give the same CSR matrix bit for bit from the same
 * emissions, since sweeps compare stores across versions bit for bit; and
 * both must equal the operator the emissions define, summed independently
 * here (a dense reference in long double).
 *  - random emissions (single sources, merged sources with zero weights,
 *    prepared cells, sources with more parents than merging holds, cells
 *    whose parents overflow the merge, empty rows), seeded;
 *  - the averaging schemes (MLCA on hex stars, tet/oct on tet stars, MLCA on
 *    a crease complex) refined both ways: the same R to the bit;
 *  - the rule's half of a step for some rows only (ss_scheme_step_rows):
 *    those rows the same bits, the others empty;
 *  - a rule that goes back to an earlier row is refused, not mis-assembled. */
#include <stdint.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "ss_optest.h"
#include "ss_scheme_impl.h"
#include "ss_sink.h"
#include "ss_testmesh.h"

enum { NC = 60, NF = 240, NCELL = 40 };

/* A split with NC coarse vertices and NF fine ones: fine f >= NC gets 1..12
 * distinct parents, a few 40 (more than the merge holds), ascending. */
static ss_split *random_split(gsl_rng *rng) {
  ss_split *L = calloc(1, sizeof *L);
  L->ncoarse = NC;
  L->nfine = NF;
  L->ptr = malloc((NF + 1) * sizeof *L->ptr);
  L->parent = malloc((size_t)NF * 40 * sizeof *L->parent);
  size_t q = 0;
  for (size_t f = 0; f < NF; f++) {
    L->ptr[f] = q;
    if (f < NC) {
      L->parent[q++] = (ss_idx)f;
      continue;
    }
    const size_t np = f % 29 == 0 ? 40 : 1 + gsl_rng_uniform_int(rng, 12);
    unsigned char used[NC] = {0};
    for (size_t k = 0; k < np; k++) {
      size_t c;
      do
        c = gsl_rng_uniform_int(rng, NC);
      while (used[c]);
      used[c] = 1;
    }
    for (size_t c = 0; c < NC; c++)
      if (used[c]) L->parent[q++] = (ss_idx)c;
  }
  L->ptr[NF] = q;
  return L;
}

/* One emission, recorded so that it can be replayed into any sink. */
typedef struct {
  int kind;         /* 0 single source, 1 merged sources, 2 prepared cell */
  size_t row, src;  /* row; kind 0: the source; kind 2: the cell */
  int n;            /* kind 1: sources */
  ss_idx many[8];   /* kind 1: the sources */
  double w[8];      /* weights (kind 0: w[0]; kind 2: a copy of *wp) */
  const double *wp; /* kind 2: a row of a shared pool (the sink reuses a
                       cell's sums for the same row address and scale) */
  double scale;     /* kinds 1, 2 */
} emission;

static void replay(ss_sink *k, const ss_sink_cells *cells, const emission *e, size_t ne) {
  for (size_t i = 0; i < ne; i++) {
    if (e[i].kind == 0)
      ss_sink_emit(k, e[i].row, e[i].src, e[i].w[0]);
    else if (e[i].kind == 1)
      ss_sink_emit_many(k, e[i].row, e[i].n, e[i].many, e[i].w, e[i].scale);
    else
      ss_sink_emit_cell(k, cells, e[i].src, e[i].row, e[i].wp, e[i].scale);
  }
}

/* The same matrix to the bit: shape, pattern and every value. */
static int same_bits(const gsl_spmatrix *A, const gsl_spmatrix *B) {
  if (A->size1 != B->size1 || A->size2 != B->size2 || A->nz != B->nz) return 0;
  if (memcmp(A->p, B->p, (A->size1 + 1) * sizeof *A->p)) return 0;
  if (memcmp(A->i, B->i, A->nz * sizeof *A->i)) return 0;
  return memcmp(A->data, B->data, A->nz * sizeof *A->data) == 0;
}

/* Add the terms of one emission to the dense reference (and |terms| to mag). */
static void reference_add(long double *ref, long double *mag, const ss_split *L,
                          const ss_sink_cells *cells, const emission *e) {
  const ss_idx *src = e->kind == 0   ? (const ss_idx[]){(ss_idx)e->src}
                      : e->kind == 1 ? e->many
                                     : cells->src + e->src * (size_t)cells->n;
  const int n = e->kind == 0 ? 1 : e->kind == 1 ? e->n : cells->n;
  const long double scale = e->kind == 0 ? 1.0L : e->scale;
  for (int j = 0; j < n; j++) {
    const size_t np = ss_split_npar(L, src[j]);
    for (size_t q = L->ptr[src[j]]; q < L->ptr[src[j] + 1]; q++) {
      const long double t = (long double)e->w[j] * scale / (long double)np;
      ref[e->row * NC + L->parent[q]] += t;
      mag[e->row * NC + L->parent[q]] += fabsl(t);
    }
  }
}

static void test_random(unsigned long seed) {
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, seed);
  ss_split *L = random_split(rng);
  /* cells of 8 fine vertices (distinct), some whose parents overflow */
  ss_idx cellv[NCELL * 8];
  for (size_t c = 0; c < NCELL; c++) {
    for (int j = 0; j < 8; j++) {
      ss_idx v;
      int again;
      do {
        v = (ss_idx)(c % 5 == 0 ? gsl_rng_uniform_int(rng, NF)
                                : gsl_rng_uniform_int(rng, NC + 20));
        again = 0;
        for (int i = 0; i < j; i++)
          again |= cellv[c * 8 + (size_t)i] == v;
      } while (again);
      cellv[c * 8 + (size_t)j] = v;
    }
  }
  /* a pool of weight rows for the cells: rows and scales repeat, so a
   * cell's kept sums are reused, and dropped when either changes */
  double pool[3][8];
  for (int r = 0; r < 3; r++)
    for (int j = 0; j < 8; j++)
      pool[r][j] = j == r ? 0.0 : gsl_rng_uniform(rng) - 0.2;
  /* emissions, rows ascending, some rows left empty */
  size_t ne = 0, cap = 8 * NF;
  emission *e = calloc(cap, sizeof *e);
  for (size_t row = 0; row < NF; row++) {
    if (row % 7 == 3) continue;
    const size_t m = 1 + gsl_rng_uniform_int(rng, 6);
    for (size_t i = 0; i < m && ne < cap; i++, ne++) {
      emission *x = e + ne;
      x->row = row;
      x->kind = (int)gsl_rng_uniform_int(rng, 3);
      x->scale = 1.0 / (double)(1 + gsl_rng_uniform_int(rng, 9));
      for (int j = 0; j < 8; j++) /* a quarter of the weights zero */
        x->w[j] = gsl_rng_uniform_int(rng, 4) == 0 ? 0.0 : gsl_rng_uniform(rng) - 0.3;
      if (x->kind == 0)
        x->src = gsl_rng_uniform_int(rng, NF);
      else if (x->kind == 1) {
        x->n = 1 + (int)gsl_rng_uniform_int(rng, 8);
        for (int j = 0; j < x->n; j++)
          x->many[j] = (ss_idx)gsl_rng_uniform_int(rng, NF);
      } else {
        x->src = gsl_rng_uniform_int(rng, NCELL / 4); /* cells met again */
        x->wp = pool[gsl_rng_uniform_int(rng, 3)];
        x->scale = gsl_rng_uniform_int(rng, 2) ? 0.125 : 0.25;
        memcpy(x->w, x->wp, sizeof x->w);
      }
    }
  }
  ss_error err = {0};
  /* triplets */
  ss_triplets t = {0, 0, NULL, NULL, NULL};
  ss_sink kt = {L, 0, NULL, NULL, &t, SS_OK, NULL, NULL};
  ss_sink_cells ct, cr;
  gsl_spmatrix *A = NULL, *B = NULL;
  REQUIRE_OK_VOID(ss_sink_cells_prepare(&kt, 8, NCELL, cellv, &ct, &err), &err);
  replay(&kt, &ct, e, ne);
  CHECK(kt.st == SS_OK, "seed %lu: triplet sink status %d", seed, (int)kt.st);
  REQUIRE_OK_VOID(ss_triplets_csr(&t, NF, NC, &A, &err), &err);
  /* rows */
  ss_rows rows;
  REQUIRE_OK_VOID(ss_rows_init(&rows, NF, NC, 16, &err), &err); /* must grow */
  ss_sink kr = {L, 0, NULL, NULL, NULL, SS_OK, &rows, NULL};
  REQUIRE_OK_VOID(ss_sink_cells_prepare(&kr, 8, NCELL, cellv, &cr, &err), &err);
  size_t unmerged = 0;
  for (size_t c = 0; c < NCELL; c++)
    unmerged += cr.np[c * 8] == 0;
  CHECK(unmerged > 0 && unmerged < NCELL, "seed %lu: %zu of %d cells not merged", seed,
        unmerged, NCELL);
  replay(&kr, &cr, e, ne);
  CHECK(kr.st == SS_OK, "seed %lu: row sink status %d", seed, (int)kr.st);
  REQUIRE_OK_VOID(ss_rows_finish(&rows, &B, &err), &err);
  CHECK(same_bits(A, B), "seed %lu: triplets and rows give different matrices", seed);
  /* the dense reference */
  long double *ref = calloc((size_t)NF * NC, sizeof *ref);
  long double *mag = calloc((size_t)NF * NC, sizeof *mag);
  for (size_t i = 0; i < ne; i++)
    reference_add(ref, mag, L, &cr, e + i);
  size_t bad = 0, nz = 0;
  for (size_t r = 0; r < NF; r++) {
    int last = -1;
    for (int q = B->p[r]; q < B->p[r + 1]; q++) {
      const size_t c = (size_t)B->i[q];
      bad += (int)c <= last; /* columns ascending within a row */
      last = (int)c;
      bad += !(fabsl((long double)B->data[q] - ref[r * NC + c]) <=
               1e-15L * 64 * mag[r * NC + c]);
      mag[r * NC + c] = -1.0L; /* seen */
    }
  }
  for (size_t i = 0; i < (size_t)NF * NC; i++)
    nz += mag[i] > 0.0L; /* a reached entry the matrix lacks */
  CHECK(bad == 0 && nz == 0, "seed %lu: %zu entries off the reference, %zu missing", seed,
        bad, nz);
  free(ref);
  free(mag);
  gsl_spmatrix_free(A);
  gsl_spmatrix_free(B);
  ss_sink_cells_clear(&ct);
  ss_sink_cells_clear(&cr);
  ss_triplets_clear(&t);
  free(e);
  ss_split_free(L);
  gsl_rng_free(rng);
}

/* A rule going back to a closed row is refused (status), not summed into a
 * wrong place. */
static void test_out_of_order(void) {
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  ss_split *L = random_split(rng);
  ss_error err = {0};
  ss_rows rows;
  REQUIRE_OK_VOID(ss_rows_init(&rows, NF, NC, 100, &err), &err);
  ss_sink k = {L, 0, NULL, NULL, NULL, SS_OK, &rows, NULL};
  ss_sink_emit(&k, 5, 70, 1.0);
  ss_sink_emit(&k, 9, 71, 1.0);
  CHECK(k.st == SS_OK, "rows in order refused");
  ss_sink_emit(&k, 5, 72, 1.0);
  CHECK(k.st == SS_EINTERNAL, "row 5 after row 9: status %d", (int)k.st);
  ss_rows_clear(&rows);
  ss_split_free(L);
  gsl_rng_free(rng);
}

/* R of an averaging scheme assembled both ways (the rule is the same; only
 * the scheme's rows_in_order differs): the same bits. */
static void check_scheme(const char *name, const ss_cx *cx, const char *what) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_cx *fa = NULL, *fb = NULL;
  gsl_spmatrix *A = NULL, *B = NULL;
  REQUIRE_OK_VOID(ss_scheme_new(name, &s, &err), &err);
  CHECK(s->rows_in_order, "%s: the averaging rule sends rows in order", name);
  REQUIRE_OK_VOID(ss_scheme_refine(s, cx, &fa, &A, &err), &err);
  s->rows_in_order = 0;
  REQUIRE_OK_VOID(ss_scheme_refine(s, cx, &fb, &B, &err), &err);
  CHECK(same_bits(A, B), "%s on %s: rows and triplets give different operators", name,
        what);
  CHECK(fa->nv == fb->nv &&
            !memcmp(fa->x, fb->x, fa->nv * (size_t)fa->dim * sizeof *fa->x),
        "%s on %s: different positions", name, what);
  check_row_sums(A, what);
  /* the rule's half of the step for some rows (every third vertex): those
   * rows the same bits, the others empty */
  ss_cx *fc = NULL;
  ss_split *L = NULL;
  gsl_spmatrix *C = NULL;
  s->rows_in_order = 1;
  CHECK(ss_scheme_step_is_one_split(s), "%s: one split per step", name);
  REQUIRE_OK_VOID(ss_split_refine(ss_scheme_split_kind(s), cx, &fc, &L, &err), &err);
  unsigned char *want = calloc(fc->nv, 1);
  for (size_t f = 0; f < fc->nv; f += 3)
    want[f] = 1;
  REQUIRE_OK_VOID(ss_scheme_step_rows(s, cx, fc, L, want, &C, &err), &err);
  size_t bad = 0;
  for (size_t f = 0; f < fc->nv && C->size1 == A->size1; f++) {
    const int n = C->p[f + 1] - C->p[f];
    if (!want[f]) {
      bad += n != 0;
      continue;
    }
    bad += n != A->p[f + 1] - A->p[f] ||
           memcmp(C->i + C->p[f], A->i + A->p[f], (size_t)n * sizeof *C->i) ||
           memcmp(C->data + C->p[f], A->data + A->p[f], (size_t)n * sizeof *C->data);
  }
  CHECK(C->size1 == A->size1 && bad == 0, "%s on %s: %zu rows differ from the step's",
        name, what, bad);
  free(want);
  gsl_spmatrix_free(C);
  ss_split_free(L);
  ss_cx_free(fc);
  gsl_spmatrix_free(A);
  gsl_spmatrix_free(B);
  ss_cx_free(fa);
  ss_cx_free(fb);
  ss_scheme_free(s);
}

int main(void) {
  gsl_set_error_handler_off();
  for (unsigned long seed = 1; seed <= 20; seed++)
    test_random(seed);
  test_out_of_order();
  const char *links[] = {"octahedron", "icosahedron", "bipyramid:5"};
  for (size_t i = 0; i < sizeof links / sizeof *links; i++) {
    tm_link *l = tm_link_named(links[i]);
    ss_cx *hex = tm_hex_star(l), *tet = tm_tet_star(l);
    ss_cx *hex2 = NULL, *tet2 = NULL;
    gsl_spmatrix *R = NULL;
    hex2 = op_refine("mlca", hex, &R); /* a bigger, less regular complex */
    gsl_spmatrix_free(R);
    tet2 = op_refine("tetoct", tet, &R);
    gsl_spmatrix_free(R);
    check_scheme("mlca", hex, links[i]);
    check_scheme("mlca", hex2, links[i]);
    check_scheme("tetoct", tet, links[i]);
    check_scheme("tetoct", tet2, links[i]);
    ss_cx_free(hex);
    ss_cx_free(tet);
    ss_cx_free(hex2);
    ss_cx_free(tet2);
    tm_link_free(l);
  }
  ss_cx *grid = tm_hex_grid(3, 3, 2); /* with a crease quad, segment and vertex */
  ss_error err = {0};
  const ss_idx quad[4] = {5, 6, 10, 9}, seg[2] = {6, 7}, vtx[1] = {1};
  REQUIRE_OK(ss_cx_add_cell(grid, SS_QUAD, quad, 0, &err), &err);
  REQUIRE_OK(ss_cx_add_cell(grid, SS_SEGMENT, seg, 0, &err), &err);
  REQUIRE_OK(ss_cx_add_cell(grid, SS_VERTEX, vtx, 0, &err), &err);
  check_scheme("mlca", grid, "a hex grid with creases");
  ss_cx_free(grid);
  return ss_test_done("sink");
}
