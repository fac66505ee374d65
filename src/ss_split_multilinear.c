/* ss_split_multilinear.c — the multilinear split of d-cubes (MLCA paper, 2.1),
 * and the hexify split of non-hexahedral input (section 3.3).
 *
 * A d-cube is refined on the lattice {0,1,2}^d of its half-integer points: a
 * lattice point with s coordinates equal to 1 is the centroid of the 2^s coarse
 * corners of a face of dimension s.  Edge midpoints (s = 1) and quad-face centres
 * (s = 2) are shared between cells through hash tables keyed by vertex sets, hex
 * centres (s = 3) belong to one cell.  Child octant o has corner k' at lattice
 * point o + bits(k').
 *
 * Hexify (section 3.3): a polyhedron whose vertices all have valence three
 * splits into one hexahedron per vertex — the vertex, the midpoints of its
 * three edges, the centres of its three faces and the centroid — and a
 * polygon into one quad per vertex likewise; on a d-cube this is the
 * multilinear split.  So triangles become 3 quads and tetrahedra 4 hexes, the
 * cubes split as above, and faces shared between cells share their centres
 * (a triangle's keyed by its sorted corners and a padding word, a quad's by
 * its sorted diagonals: keys of the two kinds never meet). */
#include <stdlib.h>

#include "ss_split_builder.h"
#include "ss_split_impl.h"

/* Lattice point t of a d-cube as the face it is born on: its parents are the
 * cube corners corner[0 .. 2^nfree) of the face in cyclic order over its free
 * dimensions (the same for every cube of a dimension: tabulated once a split). */
typedef struct {
  int nfree;     /* dimensions in which t is 1 (the face's dimension) */
  int corner[8]; /* the face's corners, as cube corner indices */
} lattice_face;

typedef struct {
  ss_split_builder b;      /* parent lists of fine vertices */
  ss_hash *edges;          /* sorted vertex pair -> fine index */
  ss_hash *faces;          /* the two sorted diagonals of a quad face -> fine index */
  lattice_face lat[3][27]; /* per d - 1: the faces of the lattice points */
  unsigned char child[3][8][8]; /* per d - 1: corner k of the child at corner kc
                                   is lattice point child[kc][k] */
} ml_state;

static void sort2(uint32_t *a, uint32_t *b) {
  if (*a > *b) {
    uint32_t t = *a;
    *a = *b;
    *b = t;
  }
}

/* The face of lattice point t (digits t[0..d)) of a d-cube. */
static lattice_face face_of(int d, const int *t) {
  lattice_face f = {0, {0}};
  int free_dims[3];
  unsigned fixed = 0;
  for (int i = 0; i < d; i++) {
    if (t[i] == 1)
      free_dims[f.nfree++] = i;
    else if (t[i] == 2)
      fixed |= 1u << i;
  }
  /* corners of the face in cyclic order over its free dimensions */
  for (int c = 0; c < 1 << f.nfree; c++) {
    unsigned bits = fixed;
    /* cyclic order 00 10 11 01 in the first two free dimensions */
    static const unsigned cyc[4] = {0u, 1u, 3u, 2u};
    unsigned local = f.nfree <= 2 ? cyc[c & 3] : (unsigned)c;
    for (int k = 0; k < f.nfree; k++)
      if ((local >> k) & 1u) bits |= 1u << free_dims[k];
    f.corner[c] = ss_cube_corner_index(d, bits);
  }
  return f;
}

/* Fine index of the lattice point with face f of the d-cube with corners v. */
static ss_status lattice_point(ml_state *s, const lattice_face *f, const ss_idx *v,
                               ss_idx *out, ss_error *err) {
  ss_idx par[8];
  for (int c = 0; c < 1 << f->nfree; c++)
    par[c] = v[f->corner[c]];
  if (f->nfree == 0) {
    *out = par[0];
    return SS_OK;
  }
  if (f->nfree == 1) {
    uint32_t key[2] = {par[0], par[1]};
    sort2(&key[0], &key[1]);
    return ss_split_shared(&s->b, s->edges, key, par, 2, out, err);
  }
  if (f->nfree == 2) {
    uint32_t a0 = par[0], a1 = par[2], b0 = par[1], b1 = par[3];
    sort2(&a0, &a1);
    sort2(&b0, &b1);
    const uint32_t key[4] = {b0 < a0 ? b0 : a0, b0 < a0 ? b1 : a1, b0 < a0 ? a0 : b0,
                             b0 < a0 ? a1 : b1};
    return ss_split_shared(&s->b, s->faces, key, par, 4, out, err);
  }
  return ss_split_builder_add(&s->b, par, 8, out, err);
}

static ss_status split_cube(ml_state *s, int d, ss_cell_type type, const ss_cx *coarse,
                            size_t c, ss_cx *fine, ss_error *err) {
  const ss_idx *v = ss_cx_cell(coarse, type, c);
  const int32_t ref = coarse->cref[type][c];
  ss_idx lat[27];
  int npts = d == 1 ? 3 : d == 2 ? 9 : 27;
  for (int p = 0; p < npts; p++) {
    ss_status st = lattice_point(s, &s->lat[d - 1][p], v, &lat[p], err);
    if (st) return st;
  }
  const int n = 1 << d;
  for (int kc = 0; kc < n; kc++) {
    ss_idx child[8];
    for (int k = 0; k < n; k++)
      child[k] = lat[s->child[d - 1][kc][k]];
    ss_status st = ss_cx_add_cell(fine, type, child, ref, err);
    if (st) return st;
  }
  return SS_OK;
}

/* Fine index of the centre of the simplex face with corners v[0..n): n = 1 the
 * corner, 2 an edge midpoint, 3 a triangle's centre (both shared). */
static ss_status simplex_point(ml_state *s, const ss_idx *v, int n, ss_idx *out,
                               ss_error *err) {
  if (n == 1) {
    *out = v[0];
    return SS_OK;
  }
  uint32_t key[4] = {v[0], v[1], n == 3 ? v[2] : 0, UINT32_MAX};
  for (int i = 1; i < n; i++) /* insertion sort of the n corners */
    for (int j = i; j > 0 && key[j - 1] > key[j]; j--) {
      const uint32_t t = key[j];
      key[j] = key[j - 1];
      key[j - 1] = t;
    }
  return n == 2 ? ss_split_shared(&s->b, s->edges, key, v, 2, out, err)
                : ss_split_shared(&s->b, s->faces, key, v, 3, out, err);
}

/* The corner split of a triangle (dim 2: 3 quads) or a tet (dim 3: 4 hexes).
 * The child at corner c has cube corner bits b: the centre of c and the
 * corners nb[c][i] with bit i set.  nb lists each corner's others in an
 * order of the cell's orientation (the triangle's cyclic order; for the tet
 * even permutations of 0 1 2 3), so children keep it: cube corner 1, 3, 4
 * are towards nb[c][0], nb[c][1], nb[c][2]. */
static ss_status split_simplex(ml_state *s, int d, ss_cell_type type, const ss_cx *coarse,
                               size_t c, ss_cx *fine, ss_error *err) {
  static const int nb2[3][2] = {{1, 2}, {2, 0}, {0, 1}};
  static const int nb3[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  const ss_idx *v = ss_cx_cell(coarse, type, c);
  const int32_t ref = coarse->cref[type][c];
  ss_idx centroid = SS_IDX_NONE; /* a tet's own, in all four of its hexes */
  if (d == 3) {
    ss_status st = ss_split_builder_add(&s->b, v, 4, &centroid, err);
    if (st) return st;
  }
  for (int k = 0; k <= d; k++) {
    ss_idx child[8];
    for (int q = 0; q < 1 << d; q++) {
      const unsigned bits = ss_cube_corner_bits(d, q);
      ss_idx par[4] = {v[k]};
      int n = 1;
      for (int i = 0; i < d; i++)
        if (bits >> i & 1u) par[n++] = v[d == 2 ? nb2[k][i] : nb3[k][i]];
      if (n == 4) {
        child[q] = centroid;
        continue;
      }
      ss_status st = simplex_point(s, par, n, &child[q], err);
      if (st) return st;
    }
    ss_status st = ss_cx_add_cell(fine, d == 2 ? SS_QUAD : SS_HEX, child, ref, err);
    if (st) return st;
  }
  return SS_OK;
}

static ss_status split_cubes(const ss_cx *coarse, int simplices, ss_cx **fine_out,
                             ss_split **L_out, ss_error *err) {
  ml_state s = {{0}, NULL, NULL, {{{0, {0}}}}, {{{0}}}};
  for (int d = 1; d <= 3; d++)
    for (int p = 0; p < (d == 1 ? 3 : d == 2 ? 9 : 27); p++) {
      const int t[3] = {p % 3, (p / 3) % 3, p / 9};
      s.lat[d - 1][p] = face_of(d, t);
    }
  for (int d = 1; d <= 3; d++)
    for (int kc = 0; kc < 1 << d; kc++) {
      const unsigned o = ss_cube_corner_bits(d, kc);
      for (int k = 0; k < 1 << d; k++) {
        const unsigned bk = ss_cube_corner_bits(d, k);
        int p = 0, scale = 1;
        for (int i = 0; i < d; i++, scale *= 3)
          p += (int)((o >> i & 1u) + (bk >> i & 1u)) * scale;
        s.child[d - 1][kc][k] = (unsigned char)p;
      }
    }
  ss_cx *fine = NULL;
  const size_t nseg = coarse->nc[SS_SEGMENT], nquad = coarse->nc[SS_QUAD],
               nhex = coarse->nc[SS_HEX];
  /* in a conforming hex grid there are about 3 edges and 3 faces per hex */
  const size_t ntri = coarse->nc[SS_TRIANGLE], ntet = coarse->nc[SS_TET];
  size_t expect_e = nseg + 2 * nquad + 4 * nhex + 2 * ntri + 2 * ntet,
         expect_f = nquad + 4 * nhex + ntri + 2 * ntet;
  ss_status st =
      ss_split_builder_init(&s.b, coarse->nv, expect_e + expect_f + nhex + ntet, err);
  if (st) goto done;
  if ((st = ss_hash_new(2, expect_e, &s.edges, err))) goto done;
  if ((st = ss_hash_new(4, expect_f, &s.faces, err))) goto done;
  if ((st = ss_cx_new(coarse->dim, &fine, err))) goto done;
  if ((st = ss_cx_reserve_cells(fine, SS_SEGMENT, 2 * nseg, err)) ||
      (st = ss_cx_reserve_cells(fine, SS_QUAD, 4 * nquad + 3 * ntri, err)) ||
      (st = ss_cx_reserve_cells(fine, SS_HEX, 8 * nhex + 4 * ntet, err)) ||
      (st = ss_cx_reserve_cells(fine, SS_VERTEX, coarse->nc[SS_VERTEX], err)))
    goto done;

  for (size_t c = 0; c < coarse->nc[SS_VERTEX]; c++)
    if ((st = ss_cx_add_cell(fine, SS_VERTEX, ss_cx_cell(coarse, SS_VERTEX, c),
                             coarse->cref[SS_VERTEX][c], err)))
      goto done;
  for (size_t c = 0; c < nseg; c++)
    if ((st = split_cube(&s, 1, SS_SEGMENT, coarse, c, fine, err))) goto done;
  for (size_t c = 0; c < nquad; c++)
    if ((st = split_cube(&s, 2, SS_QUAD, coarse, c, fine, err))) goto done;
  for (size_t c = 0; c < nhex; c++)
    if ((st = split_cube(&s, 3, SS_HEX, coarse, c, fine, err))) goto done;
  for (size_t c = 0; simplices && c < ntri; c++)
    if ((st = split_simplex(&s, 2, SS_TRIANGLE, coarse, c, fine, err))) goto done;
  for (size_t c = 0; simplices && c < ntet; c++)
    if ((st = split_simplex(&s, 3, SS_TET, coarse, c, fine, err))) goto done;

  ss_hash_free(s.edges);
  ss_hash_free(s.faces);
  s.edges = s.faces = NULL;
  st = ss_split_builder_finish(&s.b, coarse, fine, err);
done:
  ss_hash_free(s.edges);
  ss_hash_free(s.faces);
  return ss_split_builder_hand_over(&s.b, st, fine, fine_out, L_out);
}

ss_status ss_split_multilinear(const ss_cx *coarse, ss_cx **fine_out, ss_split **L_out,
                               ss_error *err) {
  return split_cubes(coarse, 0, fine_out, L_out, err);
}

ss_status ss_split_hexify(const ss_cx *coarse, ss_cx **fine_out, ss_split **L_out,
                          ss_error *err) {
  return split_cubes(coarse, 1, fine_out, L_out, err);
}
