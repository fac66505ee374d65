/* ss_star_edge.c — the edge stars (n hexes or n tets around an edge) and the
 * face star (two tets sharing a face).  Layouts and coordinates: ss_star.h. */
#include "ss_star_impl.h"

#include <math.h>

#define PI 3.14159265358979323846

static ss_status check_valence(int n, const char *what, ss_error *err) {
  if (n < 3 || n > SS_STAR_MAXN)
    return ss_error_set(err, SS_EINPUT, "%s: edge valence must be 3..%d, not %d", what,
                        SS_STAR_MAXN, n);
  return SS_OK;
}

/* Axes of the edge chart: face i at angle 2 pi i / n in the plane z = 0, the
 * edge along z. */
static void edge_axes(ss_star *s, int n) {
  for (int i = 0; i < n; i++) {
    s->axis[3 * i] = cos(2.0 * PI * i / n);
    s->axis[3 * i + 1] = sin(2.0 * PI * i / n);
    s->axis[3 * i + 2] = 0.0;
  }
  s->axis[3 * n + 2] = 1.0;
}

/* Coordinates with up to three entries: faces i (value 1) and j (value 1;
 * j < 0: none), and the edge coordinate z (0: none). */
static ss_star_coord edge_coord(int i, int j, int z, int n) {
  int32_t idx[3], val[3];
  int m = 0;
  if (i >= 0) {
    idx[m] = i;
    val[m++] = 1;
  }
  if (j >= 0) {
    idx[m] = j;
    val[m++] = 1;
  }
  if (z) {
    idx[m] = n;
    val[m++] = z;
  }
  return ss_star_coord_make(m, idx, val);
}

ss_status ss_star_hex_edge(int n, ss_star **out, ss_error *err) {
  *out = NULL;
  ss_status st = check_valence(n, "hex edge star", err);
  if (st) return st;
  ss_star *s = NULL;
  if ((st = ss_star_alloc(SS_STAR_EDGE, SS_HEX, n, n + 1, (size_t)(4 * n + 2), (size_t)n,
                          &s, err)))
    return st;
  edge_axes(s, n);
  /* the ends of the edge, then edge points and quad centres, bottom layer first */
  for (int layer = 0; layer < 2 && !st; layer++)
    st = ss_star_push_vertex(s, edge_coord(-1, -1, 2 * layer - 1, n), err);
  for (int layer = 0; layer < 2 && !st; layer++)
    for (int i = 0; i < n && !st; i++)
      st = ss_star_push_vertex(s, edge_coord(i, -1, 2 * layer - 1, n), err);
  for (int layer = 0; layer < 2 && !st; layer++)
    for (int i = 0; i < n && !st; i++)
      st = ss_star_push_vertex(s, edge_coord(i, (i + 1) % n, 2 * layer - 1, n), err);
  for (int i = 0; i < n && !st; i++) {
    const ss_idx un = (ss_idx)n, e0 = 2 + (ss_idx)i, e1 = 2 + (ss_idx)((i + 1) % n),
                 f = 2 + 2 * un + (ss_idx)i;
    ss_idx h[8] = {0, e0, f, e1, 1, e0 + un, f + un, e1 + un};
    st = ss_star_push_cell(s, h, err);
  }
  if (!st) st = ss_star_check_positive(s, err);
  if (st) {
    ss_star_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}

ss_status ss_star_tet_edge(int n, ss_star **out, ss_error *err) {
  *out = NULL;
  ss_status st = check_valence(n, "tet edge star", err);
  if (st) return st;
  ss_star *s = NULL;
  if ((st = ss_star_alloc(SS_STAR_EDGE, SS_TET, n, n + 1, (size_t)(n + 2), (size_t)n, &s,
                          err)))
    return st;
  edge_axes(s, n);
  for (int layer = 0; layer < 2 && !st; layer++)
    st = ss_star_push_vertex(s, edge_coord(-1, -1, 2 * layer - 1, n), err);
  for (int i = 0; i < n && !st; i++)
    st = ss_star_push_vertex(s, edge_coord(i, -1, 0, n), err);
  for (int i = 0; i < n && !st; i++) {
    ss_idx t[4] = {0, 1, 2 + (ss_idx)i, 2 + (ss_idx)((i + 1) % n)};
    st = ss_star_push_cell(s, t, err);
  }
  if (!st) st = ss_star_check_positive(s, err);
  if (st) {
    ss_star_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}

ss_status ss_star_tet_face(ss_star **out, ss_error *err) {
  *out = NULL;
  ss_star *s = NULL;
  ss_status st = ss_star_alloc(SS_STAR_FACE, SS_TET, 2, 5, 5, 2, &s, err);
  if (st) return st;
  /* two regular tets: the face (0, 1, 2) an equilateral triangle of
   * circumradius 1 in z = 0, counter-clockwise seen from above; apexes 3 above
   * and 4 below at the regular height sqrt(2) */
  for (int v = 0; v < 3; v++) {
    s->axis[3 * v] = cos(2.0 * PI * v / 3);
    s->axis[3 * v + 1] = sin(2.0 * PI * v / 3);
  }
  s->axis[3 * 3 + 2] = sqrt(2.0);
  s->axis[3 * 4 + 2] = -sqrt(2.0);
  for (int v = 0; v < 5 && !st; v++) {
    int32_t idx = v, one = 1;
    st = ss_star_push_vertex(s, ss_star_coord_make(1, &idx, &one), err);
  }
  const ss_idx t0[4] = {0, 1, 2, 3}, t1[4] = {0, 2, 1, 4};
  if (!st) st = ss_star_push_cell(s, t0, err);
  if (!st) st = ss_star_push_cell(s, t1, err);
  if (!st) st = ss_star_check_positive(s, err);
  if (st) {
    ss_star_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}
