/* ss_split_tetoct.c — the linear tet/oct split (tet/oct paper, section 2.1,
 * figure 3): corner chopping of tets and triangles, and octahedra into six
 * octahedra and eight tets about a new centroid.  Only edge midpoints are shared
 * between cells; each octahedron's centroid belongs to it alone. */
#include "ss_split_builder.h"
#include "ss_split_impl.h"

typedef struct {
  ss_split_builder b; /* parent lists of fine vertices */
  ss_hash *edges;     /* sorted vertex pair -> fine index of its midpoint */
} to_state;

static ss_status midpoint(to_state *s, ss_idx a, ss_idx b, ss_idx *out, ss_error *err) {
  uint32_t key[2] = {a < b ? a : b, a < b ? b : a};
  ss_idx par[2] = {a, b};
  return ss_split_shared(&s->b, s->edges, key, par, 2, out, err);
}

#define ADD(type, ...)                                                                   \
  do {                                                                                   \
    const ss_idx c_[] = {__VA_ARGS__};                                                   \
    if ((st = ss_cx_add_cell(fine, type, c_, ref, err))) return st;                      \
  } while (0)

static ss_status split_segment(to_state *s, const ss_idx *v, int32_t ref, ss_cx *fine,
                               ss_error *err) {
  ss_idx m;
  ss_status st = midpoint(s, v[0], v[1], &m, err);
  if (st) return st;
  ADD(SS_SEGMENT, v[0], m);
  ADD(SS_SEGMENT, m, v[1]);
  return SS_OK;
}

static ss_status split_triangle(to_state *s, const ss_idx *v, int32_t ref, ss_cx *fine,
                                ss_error *err) {
  ss_idx m01, m12, m20;
  ss_status st;
  if ((st = midpoint(s, v[0], v[1], &m01, err)) ||
      (st = midpoint(s, v[1], v[2], &m12, err)) ||
      (st = midpoint(s, v[2], v[0], &m20, err)))
    return st;
  ADD(SS_TRIANGLE, v[0], m01, m20);
  ADD(SS_TRIANGLE, m01, v[1], m12);
  ADD(SS_TRIANGLE, m20, m12, v[2]);
  /* the middle triangle is the parent turned by pi about its centroid */
  ADD(SS_TRIANGLE, m12, m20, m01);
  return SS_OK;
}

static ss_status split_tet(to_state *s, const ss_idx *v, int32_t ref, ss_cx *fine,
                           ss_error *err) {
  ss_idx m01, m02, m03, m12, m13, m23;
  ss_status st;
  if ((st = midpoint(s, v[0], v[1], &m01, err)) ||
      (st = midpoint(s, v[0], v[2], &m02, err)) ||
      (st = midpoint(s, v[0], v[3], &m03, err)) ||
      (st = midpoint(s, v[1], v[2], &m12, err)) ||
      (st = midpoint(s, v[1], v[3], &m13, err)) ||
      (st = midpoint(s, v[2], v[3], &m23, err)))
    return st;
  /* corner tets: the parent scaled by 1/2 about each corner */
  ADD(SS_TET, v[0], m01, m02, m03);
  ADD(SS_TET, m01, v[1], m12, m13);
  ADD(SS_TET, m02, m12, v[2], m23);
  ADD(SS_TET, m03, m13, m23, v[3]);
  /* opposite pairs are opposite tet edges; this order is positively oriented */
  ADD(SS_OCT, m01, m03, m02, m23, m12, m13);
  return SS_OK;
}

static ss_status split_oct(to_state *s, const ss_idx *v, int32_t ref, ss_cx *fine,
                           ss_error *err) {
  ss_idx mid[6][6], c;
  ss_status st;
  for (int e = 0; e < 12; e++) {
    int a, b;
    ss_cell_edge(SS_OCT, e, &a, &b);
    if ((st = midpoint(s, v[a], v[b], &mid[a][b], err))) return st;
    mid[b][a] = mid[a][b];
  }
  if ((st = ss_split_builder_add(&s->b, v, 6, &c, err))) return st;
  /* six octahedra: the parent scaled by 1/2 about corner i; the image of the
   * opposite corner is the centroid */
  for (int i = 0; i < 6; i++) {
    ss_idx child[6];
    for (int j = 0; j < 6; j++)
      child[j] = j == i ? v[i] : (j == (i + 3) % 6 ? c : mid[i][j]);
    if ((st = ss_cx_add_cell(fine, SS_OCT, child, ref, err))) return st;
  }
  /* eight tets, one per face (s0,s1,s2) with s_k in {k, k+3}: c and A =
   * m(s0,s1), B = m(s1,s2), C = m(s0,s2).  The edge pair (c,B), (A,C) comes
   * first: the octahedron it will bound joins their midpoints, along the
   * parent's axis s0 (its major diagonal (0,3), box-spline paper, Algorithm 1:
   * children inherit the parallel diagonal).  An odd number of choices k+3
   * reverses the face; (c, B, C, A) and (c, B, A, C) are then the positive
   * orders. */
  for (int f = 0; f < 8; f++) {
    int s0 = (f & 1) ? 3 : 0, s1 = (f & 2) ? 4 : 1, s2 = (f & 4) ? 5 : 2;
    int odd = ((f & 1) + ((f >> 1) & 1) + ((f >> 2) & 1)) & 1;
    ss_idx A = mid[s0][s1], B = mid[s1][s2], C = mid[s0][s2];
    if (odd)
      ADD(SS_TET, c, B, A, C);
    else
      ADD(SS_TET, c, B, C, A);
  }
  return SS_OK;
}

ss_status ss_split_tetoct(const ss_cx *coarse, ss_cx **fine_out, ss_split **L_out,
                          ss_error *err) {
  to_state s = {{0}, NULL};
  ss_cx *fine = NULL;
  const size_t ntet = coarse->nc[SS_TET], noct = coarse->nc[SS_OCT];
  /* a Delaunay-like tet mesh has about 1.2 edges per tet */
  size_t expect =
      coarse->nc[SS_SEGMENT] + 2 * coarse->nc[SS_TRIANGLE] + 2 * ntet + 6 * noct;
  ss_status st = ss_split_builder_init(&s.b, coarse->nv, expect + noct, err);
  if (st) goto done;
  if ((st = ss_hash_new(2, expect, &s.edges, err))) goto done;
  if ((st = ss_cx_new(coarse->dim, &fine, err))) goto done;
  if ((st = ss_cx_reserve_cells(fine, SS_VERTEX, coarse->nc[SS_VERTEX], err)) ||
      (st = ss_cx_reserve_cells(fine, SS_SEGMENT, 2 * coarse->nc[SS_SEGMENT], err)) ||
      (st = ss_cx_reserve_cells(fine, SS_TRIANGLE, 4 * coarse->nc[SS_TRIANGLE], err)) ||
      (st = ss_cx_reserve_cells(fine, SS_TET, 4 * ntet + 8 * noct, err)) ||
      (st = ss_cx_reserve_cells(fine, SS_OCT, ntet + 6 * noct, err)))
    goto done;

  for (size_t c = 0; c < coarse->nc[SS_VERTEX]; c++)
    if ((st = ss_cx_add_cell(fine, SS_VERTEX, ss_cx_cell(coarse, SS_VERTEX, c),
                             coarse->cref[SS_VERTEX][c], err)))
      goto done;
  for (size_t c = 0; c < coarse->nc[SS_SEGMENT]; c++)
    if ((st = split_segment(&s, ss_cx_cell(coarse, SS_SEGMENT, c),
                            coarse->cref[SS_SEGMENT][c], fine, err)))
      goto done;
  for (size_t c = 0; c < coarse->nc[SS_TRIANGLE]; c++)
    if ((st = split_triangle(&s, ss_cx_cell(coarse, SS_TRIANGLE, c),
                             coarse->cref[SS_TRIANGLE][c], fine, err)))
      goto done;
  for (size_t c = 0; c < ntet; c++)
    if ((st = split_tet(&s, ss_cx_cell(coarse, SS_TET, c), coarse->cref[SS_TET][c], fine,
                        err)))
      goto done;
  for (size_t c = 0; c < noct; c++)
    if ((st = split_oct(&s, ss_cx_cell(coarse, SS_OCT, c), coarse->cref[SS_OCT][c], fine,
                        err)))
      goto done;

  ss_hash_free(s.edges);
  s.edges = NULL;
  st = ss_split_builder_finish(&s.b, coarse, fine, err);
done:
  ss_hash_free(s.edges);
  return ss_split_builder_hand_over(&s.b, st, fine, fine_out, L_out);
}
