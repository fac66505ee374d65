/* ss_split_multilinear.c — the multilinear split of d-cubes (MLCA paper, 2.1).
 *
 * A d-cube is refined on the lattice {0,1,2}^d of its half-integer points: a
 * lattice point with s coordinates equal to 1 is the centroid of the 2^s coarse
 * corners of a face of dimension s.  Edge midpoints (s = 1) and quad-face centres
 * (s = 2) are shared between cells through hash tables keyed by vertex sets, hex
 * centres (s = 3) belong to one cell.  Child octant o has corner k' at lattice
 * point o + bits(k'). */
#include <stdlib.h>

#include "ss_split_impl.h"

typedef struct {
  ss_split_builder b; /* parent lists of fine vertices */
  ss_hash *edges;     /* sorted vertex pair -> fine index */
  ss_hash *faces;     /* the two sorted diagonals of a quad face -> fine index */
} ml_state;

static void sort2(uint32_t *a, uint32_t *b) {
  if (*a > *b) {
    uint32_t t = *a;
    *a = *b;
    *b = t;
  }
}

/* Fine index of lattice point t (digits t[0..d)) of the d-cube with corners v. */
static ss_status lattice_point(ml_state *s, int d, const ss_idx *v, const int *t,
                               ss_idx *out, ss_error *err) {
  int free_dims[3], nfree = 0;
  unsigned fixed = 0;
  for (int i = 0; i < d; i++) {
    if (t[i] == 1)
      free_dims[nfree++] = i;
    else if (t[i] == 2)
      fixed |= 1u << i;
  }
  /* corners of the face in cyclic order over its free dimensions */
  ss_idx par[8];
  int npar = 1 << nfree;
  for (int c = 0; c < npar; c++) {
    unsigned bits = fixed;
    /* cyclic order 00 10 11 01 in the first two free dimensions */
    static const unsigned cyc[4] = {0u, 1u, 3u, 2u};
    unsigned local = nfree <= 2 ? cyc[c & 3] : (unsigned)c;
    for (int k = 0; k < nfree; k++)
      if ((local >> k) & 1u) bits |= 1u << free_dims[k];
    par[c] = v[ss_cube_corner_index(d, bits)];
  }
  if (nfree == 0) {
    *out = par[0];
    return SS_OK;
  }
  if (nfree == 1) {
    uint32_t key[2] = {par[0], par[1]};
    sort2(&key[0], &key[1]);
    return ss_split_shared(&s->b, s->edges, key, par, 2, out, err);
  }
  if (nfree == 2) {
    uint32_t key[4] = {par[0], par[2], par[1], par[3]};
    sort2(&key[0], &key[1]);
    sort2(&key[2], &key[3]);
    if (key[2] < key[0]) {
      uint32_t a = key[0], b = key[1];
      key[0] = key[2];
      key[1] = key[3];
      key[2] = a;
      key[3] = b;
    }
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
    int t[3] = {p % 3, (p / 3) % 3, p / 9};
    ss_status st = lattice_point(s, d, v, t, &lat[p], err);
    if (st) return st;
  }
  const int n = 1 << d;
  for (int kc = 0; kc < n; kc++) {
    const unsigned o = ss_cube_corner_bits(d, kc); /* child kc sits at corner kc */
    ss_idx child[8];
    for (int k = 0; k < n; k++) {
      unsigned bk = ss_cube_corner_bits(d, k);
      int p = 0, scale = 1;
      for (int i = 0; i < d; i++, scale *= 3)
        p += (int)((o >> i & 1u) + (bk >> i & 1u)) * scale;
      child[k] = lat[p];
    }
    ss_status st = ss_cx_add_cell(fine, type, child, ref, err);
    if (st) return st;
  }
  return SS_OK;
}

ss_status ss_split_multilinear(const ss_cx *coarse, ss_cx **fine_out, ss_split **L_out,
                               ss_error *err) {
  ml_state s = {{0}, NULL, NULL};
  ss_cx *fine = NULL;
  const size_t nseg = coarse->nc[SS_SEGMENT], nquad = coarse->nc[SS_QUAD],
               nhex = coarse->nc[SS_HEX];
  /* in a conforming hex grid there are about 3 edges and 3 faces per hex */
  size_t expect_e = nseg + 2 * nquad + 4 * nhex, expect_f = nquad + 4 * nhex;
  ss_status st = ss_split_builder_init(&s.b, coarse->nv, expect_e + expect_f + nhex, err);
  if (st) goto done;
  if ((st = ss_hash_new(2, expect_e, &s.edges, err))) goto done;
  if ((st = ss_hash_new(4, expect_f, &s.faces, err))) goto done;
  if ((st = ss_cx_new(coarse->dim, &fine, err))) goto done;
  static const int factor[SS_NCELLTYPES] = {1, 2, 0, 4, 0, 8, 0};
  for (int t = 0; t < SS_NCELLTYPES; t++)
    if (coarse->nc[t] &&
        (st = ss_cx_reserve_cells(fine, (ss_cell_type)t,
                                  (size_t)factor[t] * coarse->nc[t], err)))
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

  ss_hash_free(s.edges);
  ss_hash_free(s.faces);
  s.edges = s.faces = NULL;
  st = ss_split_builder_finish(&s.b, coarse, fine, err);
done:
  ss_hash_free(s.edges);
  ss_hash_free(s.faces);
  return ss_split_builder_hand_over(&s.b, st, fine, fine_out, L_out);
}
