/* ss_star_surface.c — the surface vertex stars, the 2D baselines: n quads or n
 * triangles around a vertex of valence n.  Layouts and coordinates: ss_star.h. */
#include "ss_star_impl.h"

#include <math.h>

#define PI 3.14159265358979323846

/* Chart of a surface vertex: ray i at angle 2 pi i / n in the plane z = 0. */
static void ray_axes(ss_star *s, int n) {
  for (int i = 0; i < n; i++) {
    s->axis[3 * i] = cos(2.0 * PI * i / n);
    s->axis[3 * i + 1] = sin(2.0 * PI * i / n);
  }
}

/* e_i, or e_i + e_j when j >= 0. */
static ss_star_coord ray_coord(int i, int j) {
  int32_t idx[2] = {i, j}, val[2] = {1, 1};
  return ss_star_coord_make(j >= 0 ? 2 : 1, idx, val);
}

static ss_status surface_star(ss_cell_type t, int n, ss_star **out, ss_error *err) {
  *out = NULL;
  if (n < 3 || n > SS_STAR_MAXN)
    return ss_error_set(err, SS_EINPUT,
                        "surface vertex star: valence must be 3..%d, not %d",
                        SS_STAR_MAXN, n);
  const size_t nv = t == SS_QUAD ? (size_t)(2 * n + 1) : (size_t)(n + 1);
  ss_star *s = NULL;
  ss_status st = ss_star_alloc(SS_STAR_VERTEX, t, n, n, nv, (size_t)n, &s, err);
  if (st) return st;
  ray_axes(s, n);
  st = ss_star_push_vertex(s, ss_star_coord_make(0, NULL, NULL), err);
  for (int i = 0; i < n && !st; i++)
    st = ss_star_push_vertex(s, ray_coord(i, -1), err);
  for (int i = 0; t == SS_QUAD && i < n && !st; i++)
    st = ss_star_push_vertex(s, ray_coord(i, (i + 1) % n), err);
  for (int i = 0; i < n && !st; i++) {
    const ss_idx a = 1 + (ss_idx)i, b = 1 + (ss_idx)((i + 1) % n);
    const ss_idx q[4] = {0, a, 1 + (ss_idx)n + (ss_idx)i, b}, tri[3] = {0, a, b};
    st = ss_star_push_cell(s, t == SS_QUAD ? q : tri, err);
  }
  if (st) {
    ss_star_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}

ss_status ss_star_quad_vertex(int n, ss_star **out, ss_error *err) {
  return surface_star(SS_QUAD, n, out, err);
}

ss_status ss_star_tri_vertex(int n, ss_star **out, ss_error *err) {
  return surface_star(SS_TRIANGLE, n, out, err);
}

ss_status ss_star_tri48_vertex(int n, int cls, ss_star **out, ss_error *err) {
  *out = NULL;
  if (cls == 4) return surface_star(SS_TRIANGLE, n, out, err);
  if (cls != 8)
    return ss_error_set(err, SS_EINPUT, "4-8 vertex class must be 4 or 8, not %d", cls);
  if (n < 6 || n % 2 || n > SS_STAR_MAXN)
    return ss_error_set(err, SS_EINPUT,
                        "a class-8 vertex of a 4-8 mesh has an even valence of at least "
                        "6 (its spokes alternate between class-4 and class-8 "
                        "neighbours, one pair per quadrant), not %d",
                        n);
  const int m = n / 2;
  ss_star *s = NULL;
  ss_status st = ss_star_alloc(SS_STAR_VERTEX, SS_TRIANGLE, n, m, (size_t)(2 * m + 1),
                               (size_t)n, &s, err);
  if (st) return st;
  ray_axes(s, m);
  st = ss_star_push_vertex(s, ss_star_coord_make(0, NULL, NULL), err);
  for (int j = 0; j < m && !st; j++) /* A_j: class 4, on ray j */
    st = ss_star_push_vertex(s, ray_coord(j, -1), err);
  for (int j = 0; j < m && !st; j++) /* B_j: class 8, the diagonal of quadrant j */
    st = ss_star_push_vertex(s, ray_coord(j, (j + 1) % m), err);
  for (int j = 0; j < m && !st; j++) {
    /* (o, A_j, B_j) and (o, B_j, A_j+1), each with its right-angle corner A
     * first: the hypotenuse o-B is the refinement edge */
    const ss_idx o = 0, a = 1 + (ss_idx)j, b = 1 + (ss_idx)(m + j),
                 a1 = 1 + (ss_idx)((j + 1) % m);
    const ss_idx t0[3] = {a, b, o}, t1[3] = {a1, o, b};
    st = ss_star_push_cell(s, t0, err);
    if (!st) st = ss_star_push_cell(s, t1, err);
  }
  if (st) {
    ss_star_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}
