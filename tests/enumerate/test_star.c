/* test_star.c — stars built from links (hex and tet vertex stars), edge stars
 * and the face star: counts of vertices, edges, faces and cells, Euler
 * characteristic of a ball, orientation, centre valence, the local coordinates
 * (one chart, every cell an affine lattice cell, positions linear in the
 * coordinates, still integer and distinct after refinement), the octahedron's
 * hex star as the 3 x 3 x 3 grid, and bad input. */
#include "ss_star.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ss_enum.h"
#include "ss_split.h"
#include "ss_test.h"

#define PI 3.14159265358979323846

/* ---- cell complex counts ---- */

typedef struct {
  size_t nv, ne, nf, nc; /* vertices, edges, faces, cells */
  size_t centre_deg;     /* edges at vertex 0 */
} counts;

static int cmp_u32x4(const void *a, const void *b) {
  return memcmp(a, b, 4 * sizeof(uint32_t)) < 0   ? -1
         : memcmp(a, b, 4 * sizeof(uint32_t)) > 0 ? 1
                                                  : 0;
}

static int cmp_u32(const void *a, const void *b) {
  uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
  return (x > y) - (x < y);
}

/* Sort n rows of 4 and count distinct ones. */
static size_t distinct_rows(uint32_t *rows, size_t n) {
  if (!n) return 0;
  qsort(rows, n, 4 * sizeof *rows, cmp_u32x4);
  size_t d = 1;
  for (size_t i = 1; i < n; i++)
    d += memcmp(rows + 4 * i, rows + 4 * (i - 1), 4 * sizeof *rows) != 0;
  return d;
}

/* Local vertex lists of the faces of a cell type: hex faces are the cube faces
 * (bit i fixed to s), tet faces the four triples.  Returns the count. */
static int cell_faces(ss_cell_type t, int f[6][4], int *fn) {
  if (t == SS_TET) {
    for (int i = 0; i < 4; i++) {
      int m = 0;
      for (int j = 0; j < 4; j++)
        if (j != i) f[i][m++] = j;
      fn[i] = 3;
    }
    return 4;
  }
  int nf = 0;
  for (int i = 0; i < 3; i++)
    for (unsigned s = 0; s < 2; s++) {
      int m = 0;
      for (int j = 0; j < 8; j++)
        if (((ss_cube_corner_bits(3, j) >> i) & 1u) == s) f[nf][m++] = j;
      fn[nf++] = m;
    }
  return nf;
}

/* Edges and faces of a complex of hexes or tets, deduplicated by vertex set. */
static counts count_complex(const ss_cx *cx, ss_cell_type t) {
  counts c = {cx->nv, 0, 0, cx->nc[t], 0};
  const int ne = ss_cell_nedges(t);
  size_t nc = cx->nc[t];
  uint32_t *E = calloc(4 * (nc * (size_t)ne + 1), sizeof *E);
  uint32_t *F = calloc(4 * (nc * 6 + 1), sizeof *F);
  if (!E || !F) {
    fprintf(stderr, "out of memory\n");
    exit(99);
  }
  size_t nE = 0, nF = 0;
  int f[6][4], fn[6];
  int nfc = cell_faces(t, f, fn);
  for (size_t i = 0; i < nc; i++) {
    const ss_idx *v = ss_cx_cell(cx, t, i);
    for (int e = 0; e < ne; e++) {
      int a, b;
      ss_cell_edge(t, e, &a, &b);
      uint32_t *r = E + 4 * nE++;
      r[0] = v[a] < v[b] ? v[a] : v[b];
      r[1] = v[a] < v[b] ? v[b] : v[a];
      r[2] = r[3] = UINT32_MAX;
    }
    for (int k = 0; k < nfc; k++) {
      uint32_t *r = F + 4 * nF++;
      r[3] = UINT32_MAX;
      for (int j = 0; j < fn[k]; j++)
        r[j] = v[f[k][j]];
      qsort(r, (size_t)fn[k], sizeof *r, cmp_u32);
    }
  }
  c.ne = distinct_rows(E, nE);
  c.nf = distinct_rows(F, nF);
  for (size_t i = 0; i < nE; i++)
    if (E[4 * i] == 0 && (i == 0 || memcmp(E + 4 * i, E + 4 * (i - 1), 16)))
      c.centre_deg++;
  free(E);
  free(F);
  return c;
}

/* Number of cells of type t holding both vertices a and b. */
static size_t cells_holding(const ss_cx *cx, ss_cell_type t, ss_idx a, ss_idx b) {
  size_t n = 0;
  for (size_t i = 0; i < cx->nc[t]; i++) {
    const ss_idx *v = ss_cx_cell(cx, t, i);
    int ha = 0, hb = 0;
    for (int j = 0; j < ss_cell_nverts(t); j++)
      ha |= v[j] == a, hb |= v[j] == b;
    n += ha && hb;
  }
  return n;
}

/* ---- coordinates ---- */

/* Dense copy of a sparse coordinate vector (d[0..ncoord)). */
static void dense(const ss_star_coord *c, int ncoord, long *d) {
  for (int i = 0; i < ncoord; i++)
    d[i] = 0;
  for (int i = 0; i < c->n; i++)
    d[c->idx[i]] = c->val[i];
}

/* A coordinate vector is canonical: ascending indices in range, nonzero
 * values, unused slots -1 / 0. */
static int canonical(const ss_star_coord *c, int ncoord) {
  if (c->n < 0 || c->n > SS_STAR_MAXSUPP) return 0;
  for (int i = 0; i < SS_STAR_MAXSUPP; i++) {
    if (i < c->n) {
      if (c->idx[i] < 0 || c->idx[i] >= ncoord || c->val[i] == 0) return 0;
      if (i && c->idx[i] <= c->idx[i - 1]) return 0;
    } else if (c->idx[i] != -1 || c->val[i] != 0) {
      return 0;
    }
  }
  return 1;
}

static int cmp_coord(const void *a, const void *b) {
  return ss_star_coord_cmp(a, b);
}

/* Positions, canonical form and distinctness of the coordinates of cx's
 * vertices on a level `scale` times finer than the star. */
static void check_coords(const ss_star *s, const ss_cx *cx, const ss_star_coord *co,
                         double scale, const char *what) {
  size_t bad_pos = 0, bad_form = 0;
  for (size_t v = 0; v < cx->nv; v++) {
    double x[3];
    ss_star_coord_position(s, co + v, scale, x);
    for (int r = 0; r < 3; r++)
      if (!(fabs(x[r] - cx->x[3 * v + (size_t)r]) <= 1e-12)) bad_pos++;
    bad_form += !canonical(co + v, s->ncoord);
  }
  CHECK(bad_pos == 0, "%s: %zu positions differ from sum_i coord_i axis_i", what,
        bad_pos);
  CHECK(bad_form == 0, "%s: %zu coordinate vectors not canonical", what, bad_form);
  /* distinct names: sort a copy by coordinates */
  ss_star_coord *sorted = malloc((cx->nv + 1) * sizeof *sorted);
  if (!sorted) exit(99);
  memcpy(sorted, co, cx->nv * sizeof *sorted);
  qsort(sorted, cx->nv, sizeof *sorted, cmp_coord);
  size_t dup = 0;
  for (size_t v = 1; v < cx->nv; v++)
    dup += ss_star_coord_cmp(sorted + v - 1, sorted + v) == 0;
  free(sorted);
  CHECK(dup == 0, "%s: %zu pairs of vertices share coordinates", what, dup);
}

/* Every cell is an affine image of its reference cell in the chart: hex corner
 * j = corner 0 + sum_i bit_i(j) (corner of axis i - corner 0), with axis
 * corners 1, 3, 4; tets need nothing beyond distinct corners (affine always).
 * Checks the base cells' frames against the layout of ss_star.h as well. */
static void check_cell_frames(const ss_star *s, const int *tri, const char *what) {
  const ss_cx *cx = s->cx;
  const int nc = s->ncoord;
  long *d = malloc((size_t)(9 * nc) * sizeof *d);
  if (!d) exit(99);
  size_t bad_affine = 0, bad_frame = 0;
  for (size_t i = 0; i < cx->nc[s->cell_type]; i++) {
    const ss_idx *v = ss_cx_cell(cx, s->cell_type, i);
    const int nvt = ss_cell_nverts(s->cell_type);
    for (int j = 0; j < nvt; j++)
      dense(s->coord + v[j], nc, d + (size_t)j * (size_t)nc);
    if (cx->cref[s->cell_type][i] != (int32_t)i) bad_frame++;
    /* expected corner coordinates */
    long *ex = d + 8 * nc;
    for (int j = 0; j < nvt; j++) {
      for (int r = 0; r < nc; r++)
        ex[r] = 0;
      if (s->centre_kind == SS_STAR_VERTEX) {
        const int *abc = tri + 3 * i;
        if (s->cell_type == SS_HEX) {
          unsigned b = ss_cube_corner_bits(3, j);
          for (int q = 0; q < 3; q++)
            ex[abc[q]] += (long)((b >> q) & 1u);
        } else if (j > 0) {
          ex[abc[j - 1]] = 1;
        }
      } else if (s->centre_kind == SS_STAR_EDGE) {
        const int n = s->n, a = (int)i, b = ((int)i + 1) % n;
        if (s->cell_type == SS_HEX) {
          unsigned bits = ss_cube_corner_bits(3, j);
          ex[a] += (long)(bits & 1u);
          ex[b] += (long)((bits >> 1) & 1u);
          ex[n] = ((bits >> 2) & 1u) ? 1 : -1;
        } else {
          const int who[4] = {-1, -2, a, b};
          if (who[j] == -1) ex[n] = -1;
          if (who[j] == -2) ex[n] = 1;
          if (who[j] >= 0) ex[who[j]] = 1;
        }
      } else {
        ex[v[j]] = 1; /* barycentric: vertex v is e_v */
      }
      if (memcmp(ex, d + (size_t)j * (size_t)nc, (size_t)nc * sizeof *ex)) bad_frame++;
    }
    if (s->cell_type == SS_HEX)
      for (int j = 0; j < 8; j++) {
        unsigned b = ss_cube_corner_bits(3, j);
        const int ax[3] = {1, 3, 4};
        for (int r = 0; r < nc; r++) {
          long want = d[r];
          for (int q = 0; q < 3; q++)
            if ((b >> q) & 1u) want += d[ax[q] * nc + r] - d[r];
          bad_affine += want != d[j * nc + r];
        }
      }
  }
  CHECK(bad_affine == 0, "%s: %zu hex corner coordinates not affine in the cube", what,
        bad_affine);
  CHECK(bad_frame == 0, "%s: %zu cell corners off the documented frame", what, bad_frame);
  free(d);
}

/* Fine coordinates: 2 * mean of the parents' (in units of the finer grid).
 * Returns the number of fine vertices whose coordinates are not integer or
 * have too large a support. */
static size_t refine_coords(const ss_split *L, const ss_star_coord *cc, int ncoord,
                            ss_star_coord *fc) {
  long *acc = calloc((size_t)ncoord, sizeof *acc);
  if (!acc) exit(99);
  size_t bad = 0;
  for (size_t f = 0; f < L->nfine; f++) {
    long np = (long)ss_split_npar(L, f);
    for (int i = 0; i < ncoord; i++)
      acc[i] = 0;
    for (size_t p = L->ptr[f]; p < L->ptr[f + 1]; p++) {
      const ss_star_coord *c = cc + L->parent[p];
      for (int i = 0; i < c->n; i++)
        acc[c->idx[i]] += 2 * (long)c->val[i];
    }
    int32_t idx[SS_STAR_MAXSUPP], val[SS_STAR_MAXSUPP];
    int m = 0, ok = 1;
    for (int i = 0; i < ncoord; i++) {
      if (!acc[i]) continue;
      if (acc[i] % np || m == SS_STAR_MAXSUPP) {
        ok = 0;
        break;
      }
      idx[m] = i;
      val[m++] = (int32_t)(acc[i] / np);
    }
    memset(fc + f, 0, sizeof *fc);
    fc[f].n = m;
    for (int i = 0; i < SS_STAR_MAXSUPP; i++) {
      fc[f].idx[i] = i < m ? idx[i] : -1;
      fc[f].val[i] = i < m ? val[i] : 0;
    }
    bad += !ok;
  }
  free(acc);
  return bad;
}

/* Refine the star `levels` times with its split and check the coordinates of
 * every level.  *fine_out (may be NULL) receives the last complex. */
static void check_refinement(const ss_star *s, int levels, const char *what,
                             ss_cx **fine_out, ss_star_coord **coord_out) {
  ss_error err = {0};
  ss_split_kind kind = s->cell_type == SS_HEX ? SS_SPLIT_MULTILINEAR : SS_SPLIT_TETOCT;
  ss_cx *cx = NULL;
  ss_star_coord *co = malloc(s->cx->nv * sizeof *co);
  if (!co) exit(99);
  memcpy(co, s->coord, s->cx->nv * sizeof *co);
  REQUIRE_OK_VOID(ss_cx_copy(s->cx, &cx, &err), &err);
  double scale = 1.0;
  for (int j = 1; j <= levels; j++) {
    ss_cx *fine = NULL;
    ss_split *L = NULL;
    REQUIRE_OK_VOID(ss_split_refine(kind, cx, &fine, &L, &err), &err);
    ss_star_coord *fc = malloc(fine->nv * sizeof *fc);
    if (!fc) exit(99);
    size_t bad = refine_coords(L, co, s->ncoord, fc);
    scale *= 2.0;
    char name[160];
    snprintf(name, sizeof name, "%s, level %d", what, j);
    CHECK(bad == 0, "%s: %zu fine vertices without integer coordinates", name, bad);
    check_coords(s, fine, fc, scale, name);
    /* face star: coordinates stay barycentric (they sum to 2^j) */
    if (s->centre_kind == SS_STAR_FACE) {
      size_t badsum = 0;
      for (size_t v = 0; v < fine->nv; v++) {
        long sum = 0;
        for (int i = 0; i < fc[v].n; i++)
          sum += fc[v].val[i];
        badsum += sum != (long)scale;
      }
      CHECK(badsum == 0, "%s: %zu coordinate sums differ from 2^j", name, badsum);
    }
    ss_split_free(L);
    ss_cx_free(cx);
    free(co);
    cx = fine;
    co = fc;
  }
  if (fine_out) {
    *fine_out = cx;
    *coord_out = co;
  } else {
    ss_cx_free(cx);
    free(co);
  }
}

/* ---- vertex stars ---- */

static long nlinks_tested;

/* 1 if the support of c is a vertex, edge or triangle of the link (or empty),
 * with all values positive. */
static int support_is_simplex(const ss_link *l, const int *tri, const ss_star_coord *c) {
  for (int i = 0; i < c->n; i++)
    if (c->val[i] <= 0) return 0;
  if (c->n <= 1) return 1;
  if (c->n == 2) {
    for (int j = l->off[c->idx[0]]; j < l->off[c->idx[0] + 1]; j++)
      if (l->nbr[j] == c->idx[1]) return 1;
    return 0;
  }
  if (c->n > 3) return 0;
  for (int t = 0; t < 2 * l->k - 4; t++) {
    int s[3] = {tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]};
    for (int i = 0; i < 3; i++)
      for (int j = i + 1; j < 3; j++)
        if (s[j] < s[i]) {
          int x = s[i];
          s[i] = s[j];
          s[j] = x;
        }
    if (s[0] == c->idx[0] && s[1] == c->idx[1] && s[2] == c->idx[2]) return 1;
  }
  return 0;
}

/* Embedding: unit vectors, positive triangles, solid angles summing to 4 pi. */
static void check_embedding(const ss_link *l, const int *tri, const char *name) {
  ss_error err = {0};
  double *x = malloc((size_t)l->k * 3 * sizeof *x);
  if (!x) exit(99);
  REQUIRE_OK_VOID(ss_star_link_embed(l, x, &err), &err);
  size_t bad_norm = 0, bad_sign = 0;
  for (int a = 0; a < l->k; a++) {
    const double *p = x + 3 * a;
    bad_norm += !(fabs(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 1.0) < 1e-12);
  }
  double omega = 0.0;
  for (int t = 0; t < 2 * l->k - 4; t++) {
    const double *a = x + 3 * tri[3 * t], *b = x + 3 * tri[3 * t + 1],
                 *c = x + 3 * tri[3 * t + 2];
    double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0]);
    double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2],
           bc = b[0] * c[0] + b[1] * c[1] + b[2] * c[2],
           ca = c[0] * a[0] + c[1] * a[1] + c[2] * a[2];
    bad_sign += !(det > 0.0);
    omega += 2.0 * atan2(det, 1.0 + ab + bc + ca); /* Van Oosterom-Strackee */
  }
  CHECK(bad_norm == 0, "%s: %zu link positions off the unit sphere", name, bad_norm);
  CHECK(bad_sign == 0, "%s: %zu link triangles not positive", name, bad_sign);
  CHECK_CLOSE(omega, 4.0 * PI, 1e-9, "%s: triangles must cover the sphere once", name);
  free(x);
}

static void check_vertex_stars(const ss_link *l, const char *name, int refine) {
  ss_error err = {0};
  const int k = l->k;
  int *tri = NULL, ntri = 0;
  REQUIRE_OK_VOID(ss_link_triangles(l, &tri, &ntri, &err), &err);
  nlinks_tested++;
  check_embedding(l, tri, name);
  char what[200];

  /* hex star */
  ss_star *s = NULL;
  REQUIRE_OK_VOID(ss_star_hex_vertex(l, &s, &err), &err);
  snprintf(what, sizeof what, "hex star of %s", name);
  counts c = count_complex(s->cx, SS_HEX);
  CHECK(c.nv == (size_t)(6 * k - 9), "%s: %zu vertices, expected 6k-9", what, c.nv);
  CHECK(c.ne == (size_t)(13 * k - 24), "%s: %zu edges, expected 13k-24", what, c.ne);
  CHECK(c.nf == (size_t)(9 * k - 18), "%s: %zu faces, expected 9k-18", what, c.nf);
  CHECK(c.nc == (size_t)(2 * k - 4), "%s: %zu hexes, expected 2k-4", what, c.nc);
  CHECK(ss_cx_ncells(s->cx) == c.nc, "%s: only hexes expected", what);
  CHECK((long)c.nv - (long)c.ne + (long)c.nf - (long)c.nc == 1, "%s: Euler %ld, not 1",
        what, (long)c.nv - (long)c.ne + (long)c.nf - (long)c.nc);
  CHECK(c.centre_deg == (size_t)k, "%s: centre valence %zu, expected k = %d", what,
        c.centre_deg, k);
  CHECK(s->centre_kind == SS_STAR_VERTEX && s->cell_type == SS_HEX && s->n == k &&
            s->ncoord == k && s->ncentre == 1 && s->centre[0] == 0,
        "%s: header fields", what);
  CHECK(ss_cx_check_orientation(s->cx, &err) == SS_OK, "%s: %s", what, err.msg);
  size_t nonpos = 0;
  for (size_t i = 0; i < c.nc; i++)
    nonpos += ss_cx_cell_orientation(s->cx, SS_HEX, i, NULL) != 1;
  CHECK(nonpos == 0, "%s: %zu hexes not positive", what, nonpos);
  /* edge valences: the edge (centre, edge point of a) is in deg(a) hexes */
  size_t bad_val = 0;
  for (int a = 0; a < k; a++)
    bad_val +=
        cells_holding(s->cx, SS_HEX, 0, (ss_idx)(1 + a)) != (size_t)ss_link_deg(l, a);
  CHECK(bad_val == 0, "%s: %zu edges with the wrong valence", what, bad_val);
  /* coordinates: layout of the simplices and their supports */
  size_t bad_supp = 0, bad_layout = 0;
  for (size_t v = 0; v < c.nv; v++) {
    const ss_star_coord *co = s->coord + v;
    bad_supp += !support_is_simplex(l, tri, co);
    int want = v == 0 ? 0 : v <= (size_t)k ? 1 : v <= (size_t)(4 * k - 6) ? 2 : 3;
    bad_layout += co->n != want;
    for (int i = 0; i < co->n; i++)
      bad_layout += co->val[i] != 1;
  }
  CHECK(bad_supp == 0, "%s: %zu coordinate supports are not link simplices", what,
        bad_supp);
  CHECK(bad_layout == 0, "%s: %zu vertices out of the documented order", what,
        bad_layout);
  check_coords(s, s->cx, s->coord, 1.0, what);
  check_cell_frames(s, tri, what);
  if (refine) check_refinement(s, 2, what, NULL, NULL);
  ss_star_free(s);

  /* tet star */
  REQUIRE_OK_VOID(ss_star_tet_vertex(l, &s, &err), &err);
  snprintf(what, sizeof what, "tet star of %s", name);
  c = count_complex(s->cx, SS_TET);
  CHECK(c.nv == (size_t)(k + 1), "%s: %zu vertices, expected k+1", what, c.nv);
  CHECK(c.ne == (size_t)(4 * k - 6), "%s: %zu edges, expected 4k-6", what, c.ne);
  CHECK(c.nf == (size_t)(5 * k - 10), "%s: %zu faces, expected 5k-10", what, c.nf);
  CHECK(c.nc == (size_t)(2 * k - 4), "%s: %zu tets, expected 2k-4", what, c.nc);
  CHECK((long)c.nv - (long)c.ne + (long)c.nf - (long)c.nc == 1, "%s: Euler not 1", what);
  CHECK(c.centre_deg == (size_t)k, "%s: centre valence %zu", what, c.centre_deg);
  CHECK(ss_cx_check_orientation(s->cx, &err) == SS_OK, "%s: %s", what, err.msg);
  nonpos = 0;
  for (size_t i = 0; i < c.nc; i++)
    nonpos += ss_cx_cell_orientation(s->cx, SS_TET, i, NULL) != 1;
  CHECK(nonpos == 0, "%s: %zu tets not positive", what, nonpos);
  bad_val = 0;
  for (int a = 0; a < k; a++)
    bad_val +=
        cells_holding(s->cx, SS_TET, 0, (ss_idx)(1 + a)) != (size_t)ss_link_deg(l, a);
  CHECK(bad_val == 0, "%s: %zu edges with the wrong valence", what, bad_val);
  check_coords(s, s->cx, s->coord, 1.0, what);
  check_cell_frames(s, tri, what);
  if (refine) check_refinement(s, 2, what, NULL, NULL);
  ss_star_free(s);
  free(tri);
}

/* Links from the tetrahedron by inserting degree-3 vertices into faces,
 * deterministically, up to kmax vertices. */
static void check_stacked_links(int kmax) {
  ss_error err = {0};
  int ntri = 4, cap = 2 * kmax;
  int *t = malloc((size_t)cap * 3 * sizeof *t);
  if (!t) exit(99);
  const int tet[12] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
  memcpy(t, tet, sizeof tet);
  unsigned long r = 12345;
  for (int k = 5; k <= kmax; k++) {
    r = r * 6364136223846793005ul + 1442695040888963407ul;
    int f = (int)((r >> 33) % (unsigned long)ntri);
    int a = t[3 * f], b = t[3 * f + 1], c = t[3 * f + 2], x = k - 1;
    int nt[9] = {a, b, x, b, c, x, c, a, x};
    memcpy(t + 3 * f, nt, 3 * sizeof *t);
    memcpy(t + 3 * ntri, nt + 3, 6 * sizeof *t);
    ntri += 2;
    ss_link *l = NULL;
    REQUIRE_OK_VOID(ss_link_from_triangles(k, ntri, t, &l, &err), &err);
    char name[64];
    snprintf(name, sizeof name, "stacked link k=%d", k);
    check_vertex_stars(l, name, k <= 12);
    ss_link_free(l);
  }
  free(t);
}

static int visit_link(const ss_link *l, void *ctx) {
  long *i = ctx;
  char *code = NULL;
  ss_error err = {0};
  char name[160];
  if (ss_link_format(l, &code, &err) == SS_OK)
    snprintf(name, sizeof name, "link %s", code);
  else
    snprintf(name, sizeof name, "link #%ld", *i);
  free(code);
  check_vertex_stars(l, name, l->k <= 7);
  (*i)++;
  return 0;
}

static void test_vertex_stars(void) {
  ss_error err = {0};
  const char *named[] = {"tetrahedron", "octahedron",  "icosahedron", "bipyramid:3",
                         "bipyramid:4", "bipyramid:5", "bipyramid:6", "bipyramid:7",
                         "bipyramid:8", "bipyramid:9", "bipyramid:10"};
  for (size_t i = 0; i < sizeof named / sizeof *named; i++) {
    ss_link *l = NULL;
    REQUIRE_OK_VOID(ss_link_named(named[i], &l, &err), &err);
    check_vertex_stars(l, named[i], 1);
    ss_link_free(l);
  }
  check_stacked_links(30);
  /* every link with k <= 9 (1 + 1 + 2 + 5 + 14 + 50 = 73 links) */
  long n = 0;
  uint64_t cnt[SS_ENUM_MAXK + 1];
  ss_enum_opts o = {4, 9, 0, 1};
  REQUIRE_OK_VOID(ss_enum_links(&o, visit_link, &n, cnt, &err), &err);
  CHECK(n == 73, "%ld links with 4..9 vertices, expected 73", n);
}

/* ---- the octahedron's hex star is the 3 x 3 x 3 grid ---- */

static void test_octahedron_grid(void) {
  ss_error err = {0};
  ss_link *l = NULL;
  ss_star *s = NULL;
  int *tri = NULL, ntri = 0;
  REQUIRE_OK_VOID(ss_link_named("octahedron", &l, &err), &err);
  REQUIRE_OK_VOID(ss_star_hex_vertex(l, &s, &err), &err);
  REQUIRE_OK_VOID(ss_link_triangles(l, &tri, &ntri, &err), &err);
  /* grid directions: antipodes are the non-neighbours */
  int g[6][3] = {{0}}, anti[6], done[6] = {0};
  for (int a = 0; a < 6; a++)
    for (int b = 0; b < 6; b++) {
      int adj = 0;
      for (int j = l->off[a]; j < l->off[a + 1]; j++)
        adj |= l->nbr[j] == b;
      if (b != a && !adj) anti[a] = b;
    }
  int axis = 0;
  for (int a = 0; a < 6 && axis < 3; a++)
    if (!done[a]) {
      g[a][axis] = 1;
      g[anti[a]][axis] = -1;
      done[a] = done[anti[a]] = 1;
      axis++;
    }
  /* orientation: link triangles must map to positive frames; else flip z */
  int t0[3] = {tri[0], tri[1], tri[2]};
  long det = (long)g[t0[0]][0] * (g[t0[1]][1] * g[t0[2]][2] - g[t0[1]][2] * g[t0[2]][1]) -
             (long)g[t0[0]][1] * (g[t0[1]][0] * g[t0[2]][2] - g[t0[1]][2] * g[t0[2]][0]) +
             (long)g[t0[0]][2] * (g[t0[1]][0] * g[t0[2]][1] - g[t0[1]][1] * g[t0[2]][0]);
  if (det < 0)
    for (int a = 0; a < 6; a++)
      g[a][2] = -g[a][2];
  /* grid point of every star vertex */
  int P[27][3], seen[27] = {0};
  size_t bad_pt = 0;
  CHECK(s->cx->nv == 27 && s->cx->nc[SS_HEX] == 8, "octahedron: %zu vertices, %zu hexes",
        s->cx->nv, s->cx->nc[SS_HEX]);
  for (size_t v = 0; v < s->cx->nv && v < 27; v++) {
    for (int r = 0; r < 3; r++)
      P[v][r] = 0;
    for (int i = 0; i < s->coord[v].n; i++)
      for (int r = 0; r < 3; r++)
        P[v][r] += s->coord[v].val[i] * g[s->coord[v].idx[i]][r];
    int ok = 1;
    for (int r = 0; r < 3; r++)
      ok &= P[v][r] >= -1 && P[v][r] <= 1;
    if (!ok) {
      bad_pt++;
      continue;
    }
    seen[(P[v][0] + 1) + 3 * (P[v][1] + 1) + 9 * (P[v][2] + 1)]++;
  }
  size_t missing = 0;
  for (int i = 0; i < 27; i++)
    missing += seen[i] != 1;
  CHECK(bad_pt == 0 && missing == 0,
        "octahedron: star vertices do not map one-to-one onto {-1,0,1}^3 (%zu, %zu)",
        bad_pt, missing);
  /* every hex is a positively oriented unit cube of the grid, corner j at
   * corner 0 + the bits of j along its three edges; all 8 octants used */
  size_t bad_cube = 0;
  int octant[8] = {0};
  for (size_t i = 0; i < s->cx->nc[SS_HEX] && i < 8; i++) {
    const ss_idx *h = ss_cx_cell(s->cx, SS_HEX, i);
    int e[3][3], lo[3];
    const int ax[3] = {1, 3, 4};
    for (int q = 0; q < 3; q++)
      for (int r = 0; r < 3; r++)
        e[q][r] = P[h[ax[q]]][r] - P[h[0]][r];
    for (int j = 0; j < 8; j++) {
      unsigned b = ss_cube_corner_bits(3, j);
      for (int r = 0; r < 3; r++) {
        int want = P[h[0]][r];
        for (int q = 0; q < 3; q++)
          want += (int)((b >> q) & 1u) * e[q][r];
        bad_cube += want != P[h[j]][r];
      }
    }
    long d = (long)e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
             (long)e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
             (long)e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    bad_cube += d != 1;
    for (int r = 0; r < 3; r++) {
      int m = P[h[0]][r];
      for (int q = 0; q < 3; q++)
        if (P[h[0]][r] + e[q][r] < m) m = P[h[0]][r] + e[q][r];
      lo[r] = m; /* -1 or 0 */
    }
    octant[(lo[0] + 1) + 2 * (lo[1] + 1) + 4 * (lo[2] + 1)]++;
  }
  for (int i = 0; i < 8; i++)
    bad_cube += octant[i] != 1;
  CHECK(bad_cube == 0, "octahedron: hexes are not the 8 unit cubes of the grid (%zu)",
        bad_cube);
  /* vertex degrees of the grid: 8 corners of degree 3, 12 edge midpoints 4, 6
   * face centres 5, the centre 6 */
  char adj[27][27] = {{0}};
  for (size_t i = 0; i < s->cx->nc[SS_HEX]; i++) {
    const ss_idx *h = ss_cx_cell(s->cx, SS_HEX, i);
    for (int e = 0; e < 12; e++) {
      int a, b;
      ss_cell_edge(SS_HEX, e, &a, &b);
      if (h[a] < 27 && h[b] < 27) adj[h[a]][h[b]] = adj[h[b]][h[a]] = 1;
    }
  }
  size_t deg[27] = {0};
  for (int v = 0; v < 27; v++)
    for (int w = 0; w < 27; w++)
      deg[v] += (size_t)adj[v][w];
  size_t hist[7] = {0};
  for (int v = 0; v < 27; v++)
    if (deg[v] <= 6) hist[deg[v]]++;
  CHECK(hist[3] == 8 && hist[4] == 12 && hist[5] == 6 && hist[6] == 1,
        "octahedron: degree histogram %zu %zu %zu %zu, expected 8 12 6 1", hist[3],
        hist[4], hist[5], hist[6]);
  CHECK(deg[0] == 6, "octahedron: the centre has degree %zu", deg[0]);
  free(tri);
  ss_star_free(s);
  ss_link_free(l);
}

/* ---- edge and face stars ---- */

static void check_edge_star(const ss_star *s, int n, const char *what) {
  ss_error err = {0};
  ss_cell_type t = s->cell_type;
  counts c = count_complex(s->cx, t);
  int hex = t == SS_HEX;
  size_t V = hex ? (size_t)(4 * n + 2) : (size_t)(n + 2),
         E = hex ? (size_t)(8 * n + 1) : (size_t)(3 * n + 1),
         F = hex ? (size_t)(5 * n) : (size_t)(3 * n);
  CHECK(c.nv == V, "%s: %zu vertices, expected %zu", what, c.nv, V);
  CHECK(c.ne == E, "%s: %zu edges, expected %zu", what, c.ne, E);
  CHECK(c.nf == F, "%s: %zu faces, expected %zu", what, c.nf, F);
  CHECK(c.nc == (size_t)n, "%s: %zu cells, expected %d", what, c.nc, n);
  CHECK(ss_cx_ncells(s->cx) == c.nc, "%s: one cell type only", what);
  CHECK((long)c.nv - (long)c.ne + (long)c.nf - (long)c.nc == 1, "%s: Euler not 1", what);
  CHECK(cells_holding(s->cx, t, 0, 1) == (size_t)n, "%s: the edge is in %zu cells", what,
        cells_holding(s->cx, t, 0, 1));
  CHECK(s->centre_kind == SS_STAR_EDGE && s->n == n && s->ncoord == n + 1 &&
            s->ncentre == 2 && s->centre[0] == 0 && s->centre[1] == 1 &&
            s->centre[2] == SS_IDX_NONE,
        "%s: header fields", what);
  CHECK(ss_cx_check_orientation(s->cx, &err) == SS_OK, "%s: %s", what, err.msg);
  size_t nonpos = 0;
  for (size_t i = 0; i < c.nc; i++)
    nonpos += ss_cx_cell_orientation(s->cx, t, i, NULL) != 1;
  CHECK(nonpos == 0, "%s: %zu cells not positive", what, nonpos);
  check_coords(s, s->cx, s->coord, 1.0, what);
  check_cell_frames(s, NULL, what);
  /* after one refinement the midpoint (coordinates 0) is a vertex whose star
   * is the vertex star of the bipyramid: 2n hexes, or 2n tets + n octahedra */
  ss_cx *fine = NULL;
  ss_star_coord *fc = NULL;
  check_refinement(s, 1, what, &fine, &fc);
  if (!fine) return;
  ss_idx mid = SS_IDX_NONE;
  for (size_t v = 0; v < fine->nv; v++)
    if (fc[v].n == 0) mid = (ss_idx)v;
  CHECK(mid != SS_IDX_NONE, "%s: no midpoint after refinement", what);
  if (mid != SS_IDX_NONE) {
    if (hex) {
      CHECK(cells_holding(fine, SS_HEX, mid, mid) == (size_t)(2 * n),
            "%s: %zu fine hexes at the midpoint", what,
            cells_holding(fine, SS_HEX, mid, mid));
    } else {
      CHECK(cells_holding(fine, SS_TET, mid, mid) == (size_t)(2 * n) &&
                cells_holding(fine, SS_OCT, mid, mid) == (size_t)n,
            "%s: %zu tets and %zu octahedra at the midpoint", what,
            cells_holding(fine, SS_TET, mid, mid), cells_holding(fine, SS_OCT, mid, mid));
    }
  }
  ss_cx_free(fine);
  free(fc);
  check_refinement(s, 2, what, NULL, NULL);
}

static void test_edge_stars(void) {
  ss_error err = {0};
  for (int n = 3; n <= 12; n++) {
    char what[64];
    ss_star *s = NULL;
    REQUIRE_OK_VOID(ss_star_hex_edge(n, &s, &err), &err);
    snprintf(what, sizeof what, "hex edge star n=%d", n);
    CHECK(s->cell_type == SS_HEX, "%s: hexes", what);
    check_edge_star(s, n, what);
    ss_star_free(s);
    REQUIRE_OK_VOID(ss_star_tet_edge(n, &s, &err), &err);
    snprintf(what, sizeof what, "tet edge star n=%d", n);
    CHECK(s->cell_type == SS_TET, "%s: tets", what);
    check_edge_star(s, n, what);
    ss_star_free(s);
  }
  /* bad valences */
  const int bad[] = {-1, 0, 1, 2, SS_STAR_MAXN + 1};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    ss_star dummy, *s = &dummy; /* must be reset to NULL */
    ss_error e = {0};
    CHECK(ss_star_hex_edge(bad[i], &s, &e) == SS_EINPUT && s == NULL && e.msg[0],
          "hex edge star n=%d refused", bad[i]);
    s = &dummy;
    CHECK(ss_star_tet_edge(bad[i], &s, &e) == SS_EINPUT && s == NULL,
          "tet edge star n=%d refused", bad[i]);
  }
}

static void test_face_star(void) {
  ss_error err = {0};
  ss_star *s = NULL;
  REQUIRE_OK_VOID(ss_star_tet_face(&s, &err), &err);
  const char *what = "tet face star";
  counts c = count_complex(s->cx, SS_TET);
  CHECK(c.nv == 5 && c.ne == 9 && c.nf == 7 && c.nc == 2,
        "%s: %zu vertices, %zu edges, %zu faces, %zu tets (expected 5 9 7 2)", what, c.nv,
        c.ne, c.nf, c.nc);
  CHECK((long)c.nv - (long)c.ne + (long)c.nf - (long)c.nc == 1, "%s: Euler not 1", what);
  CHECK(s->centre_kind == SS_STAR_FACE && s->ncentre == 3 && s->ncoord == 5 &&
            s->centre[0] == 0 && s->centre[1] == 1 && s->centre[2] == 2,
        "%s: header fields", what);
  /* the face (0, 1, 2) is shared by both tets */
  size_t shared = 0;
  for (size_t i = 0; i < s->cx->nc[SS_TET]; i++) {
    const ss_idx *t = ss_cx_cell(s->cx, SS_TET, i);
    int h = 0;
    for (int j = 0; j < 4; j++)
      h += t[j] <= 2;
    shared += h == 3;
  }
  CHECK(shared == 2, "%s: the face is in %zu tets", what, shared);
  CHECK(ss_cx_check_orientation(s->cx, &err) == SS_OK, "%s: %s", what, err.msg);
  for (size_t i = 0; i < 2; i++)
    CHECK(ss_cx_cell_orientation(s->cx, SS_TET, i, NULL) == 1, "%s: tet %zu", what, i);
  check_coords(s, s->cx, s->coord, 1.0, what);
  check_cell_frames(s, NULL, what);
  check_refinement(s, 3, what, NULL, NULL);
  ss_star_free(s);
}

/* ---- small helpers ---- */

static void test_helpers(void) {
  ss_star_free(NULL);
  ss_star_coord z = {0, {-1, -1, -1, -1}, {0, 0, 0, 0}}, a = z, b;
  a.n = 1, a.idx[0] = 2, a.val[0] = 1;
  b = z;
  b.n = 1, b.idx[0] = 2, b.val[0] = 3;
  CHECK(ss_star_coord_cmp(&z, &z) == 0, "equal to itself");
  CHECK(ss_star_coord_cmp(&z, &a) < 0 && ss_star_coord_cmp(&a, &z) > 0,
        "by support size");
  CHECK(ss_star_coord_cmp(&a, &b) < 0 && ss_star_coord_cmp(&b, &a) > 0, "by value");
  b.val[0] = 1, b.idx[0] = 1;
  CHECK(ss_star_coord_cmp(&b, &a) < 0, "by index");
}

int main(void) {
  test_helpers();
  test_vertex_stars();
  test_octahedron_grid();
  test_edge_stars();
  test_face_star();
  printf("%ld links tested\n", nlinks_tested);
  return ss_test_done("star");
}
