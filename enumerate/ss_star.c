/* ss_star.c — star objects, coordinate helpers and the vertex stars (hex and
 * tet) built from a link. */
#include "ss_star_impl.h"

#include <stdlib.h>
#include <string.h>

/* ---- common ---- */

void ss_star_free(ss_star *s) {
  if (!s) return;
  ss_cx_free(s->cx);
  free(s->coord);
  free(s->axis);
  free(s);
}

ss_status ss_star_alloc(ss_star_kind kind, ss_cell_type t, int n, int ncoord, size_t nv,
                        size_t ncells, ss_star **out, ss_error *err) {
  *out = NULL;
  ss_star *s = calloc(1, sizeof *s);
  if (!s) return ss_error_nomem(err, "star");
  ss_status st = SS_OK;
  s->centre_kind = kind;
  s->cell_type = t;
  s->n = n;
  s->ncoord = ncoord;
  s->ncentre = kind == SS_STAR_VERTEX ? 1 : kind == SS_STAR_EDGE ? 2 : 3;
  for (int i = 0; i < 3; i++)
    s->centre[i] = i < s->ncentre ? (ss_idx)i : SS_IDX_NONE;
  s->coord = malloc((nv > 0 ? nv : 1) * sizeof *s->coord);
  s->axis = calloc((size_t)ncoord * 3, sizeof *s->axis);
  if (!s->coord || !s->axis) {
    st = ss_error_nomem(err, "star");
    goto done;
  }
  if ((st = ss_cx_new(3, &s->cx, err))) goto done;
  if ((st = ss_cx_reserve_vertices(s->cx, nv, err))) goto done;
  if ((st = ss_cx_reserve_cells(s->cx, t, ncells, err))) goto done;
done:
  if (st) {
    ss_star_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}

ss_star_coord ss_star_coord_make(int m, const int32_t *idx, const int32_t *val) {
  ss_star_coord c;
  c.n = m;
  for (int i = 0; i < SS_STAR_MAXSUPP; i++) {
    c.idx[i] = i < m ? idx[i] : -1;
    c.val[i] = i < m ? val[i] : 0;
  }
  /* insertion sort by index (m <= 4) */
  for (int i = 1; i < m; i++)
    for (int j = i; j > 0 && c.idx[j - 1] > c.idx[j]; j--) {
      int32_t ti = c.idx[j], tv = c.val[j];
      c.idx[j] = c.idx[j - 1];
      c.val[j] = c.val[j - 1];
      c.idx[j - 1] = ti;
      c.val[j - 1] = tv;
    }
  return c;
}

int ss_star_coord_cmp(const ss_star_coord *a, const ss_star_coord *b) {
  if (a->n != b->n) return a->n < b->n ? -1 : 1;
  for (int i = 0; i < a->n; i++)
    if (a->idx[i] != b->idx[i]) return a->idx[i] < b->idx[i] ? -1 : 1;
  for (int i = 0; i < a->n; i++)
    if (a->val[i] != b->val[i]) return a->val[i] < b->val[i] ? -1 : 1;
  return 0;
}

void ss_star_coord_position(const ss_star *s, const ss_star_coord *c, double scale,
                            double x[3]) {
  x[0] = x[1] = x[2] = 0.0;
  for (int i = 0; i < c->n; i++)
    for (int r = 0; r < 3; r++)
      x[r] += (double)c->val[i] * s->axis[3 * (size_t)c->idx[i] + (size_t)r];
  for (int r = 0; r < 3; r++)
    x[r] /= scale;
}

ss_status ss_star_push_vertex(ss_star *s, ss_star_coord c, ss_error *err) {
  double x[3];
  ss_star_coord_position(s, &c, 1.0, x);
  size_t v = s->cx->nv;
  ss_status st = ss_cx_add_vertex(s->cx, x, 0, err);
  if (st) return st;
  s->coord[v] = c;
  return SS_OK;
}

ss_status ss_star_push_cell(ss_star *s, const ss_idx *v, ss_error *err) {
  return ss_cx_add_cell(s->cx, s->cell_type, v, (int32_t)s->cx->nc[s->cell_type], err);
}

ss_status ss_star_check_positive(const ss_star *s, ss_error *err) {
  for (size_t i = 0; i < s->cx->nc[s->cell_type]; i++)
    if (ss_cx_cell_orientation(s->cx, s->cell_type, i, NULL) != 1)
      return ss_error_set(err, SS_ENUMERIC, "star: %s %zu is not positively oriented",
                          ss_cell_name(s->cell_type), i + 1);
  return SS_OK;
}

/* ---- vertex stars ---- */

/* Index of w in v's neighbour list (0-based position), or -1. */
static int nbr_pos(const ss_link *l, int v, int w) {
  for (int i = l->off[v]; i < l->off[v + 1]; i++)
    if (l->nbr[i] == w) return i - l->off[v];
  return -1;
}

/* Common part of both vertex stars: embed the link, list its triangles, and
 * allocate the star with the link positions as axes. */
static ss_status vertex_star_begin(const ss_link *l, ss_cell_type t, size_t nv, int **tri,
                                   int *ntri, ss_star **out, ss_error *err) {
  *tri = NULL;
  *out = NULL;
  const int k = l->k;
  ss_status st =
      ss_star_alloc(SS_STAR_VERTEX, t, k, k, nv, (size_t)(2 * k - 4), out, err);
  if (st) return st;
  if ((st = ss_star_link_embed(l, (*out)->axis, err))) goto done;
  if ((st = ss_link_triangles(l, tri, ntri, err))) goto done;
  if (*ntri != 2 * k - 4)
    st = ss_error_set(err, SS_EINPUT, "star: link has %d triangles, expected %d", *ntri,
                      2 * k - 4);
done:
  if (st) {
    free(*tri);
    *tri = NULL;
    ss_star_free(*out);
    *out = NULL;
  }
  return st;
}

/* A link edge {a < b} and the slot of b in a's neighbour list. */
typedef struct {
  int a, b, slot;
} link_edge;

static int cmp_edge(const void *x, const void *y) {
  const link_edge *p = x, *q = y;
  if (p->a != q->a) return p->a < q->a ? -1 : 1;
  return (p->b > q->b) - (p->b < q->b);
}

ss_status ss_star_hex_vertex(const ss_link *l, ss_star **out, ss_error *err) {
  *out = NULL;
  const int k = l->k, nedge = l->off[k] / 2;
  ss_star *s = NULL;
  int *tri = NULL, ntri = 0;
  int *eid = NULL; /* eid[off[a] + i]: link edge index of a and its i-th neighbour */
  link_edge *edges = NULL;
  ss_status st = vertex_star_begin(l, SS_HEX, (size_t)(1 + k + nedge + 2 * k - 4), &tri,
                                   &ntri, &s, err);
  if (st) return st;
  eid = malloc((size_t)l->off[k] * sizeof *eid);
  edges = malloc((size_t)nedge * sizeof *edges);
  if (!eid || !edges) {
    st = ss_error_nomem(err, "hex star");
    goto done;
  }
  /* centre, edge points */
  if ((st = ss_star_push_vertex(s, ss_star_coord_make(0, NULL, NULL), err))) goto done;
  for (int a = 0; a < k; a++) {
    int32_t ia = a, one = 1;
    if ((st = ss_star_push_vertex(s, ss_star_coord_make(1, &ia, &one), err))) goto done;
  }
  /* face points: link edges {a < b} sorted lexicographically */
  int e = 0;
  for (int a = 0; a < k; a++)
    for (int i = l->off[a]; i < l->off[a + 1]; i++)
      if (l->nbr[i] > a && e < nedge) {
        edges[e].a = a;
        edges[e].b = l->nbr[i];
        edges[e].slot = i;
        e++;
      }
  qsort(edges, (size_t)nedge, sizeof *edges, cmp_edge);
  for (e = 0; e < nedge; e++) {
    const int a = edges[e].a, b = edges[e].b;
    eid[edges[e].slot] = e;
    eid[l->off[b] + nbr_pos(l, b, a)] = e;
    int32_t idx[2] = {a, b}, val[2] = {1, 1};
    if ((st = ss_star_push_vertex(s, ss_star_coord_make(2, idx, val), err))) goto done;
  }
  /* cell points and hexes */
  const ss_idx fp0 = (ss_idx)(1 + k), cp0 = (ss_idx)(1 + k + nedge);
  for (int t = 0; t < ntri; t++) {
    const int a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
    int32_t idx[3] = {a, b, c}, val[3] = {1, 1, 1};
    if ((st = ss_star_push_vertex(s, ss_star_coord_make(3, idx, val), err))) goto done;
    ss_idx ab = fp0 + (ss_idx)eid[l->off[a] + nbr_pos(l, a, b)];
    ss_idx bc = fp0 + (ss_idx)eid[l->off[b] + nbr_pos(l, b, c)];
    ss_idx ca = fp0 + (ss_idx)eid[l->off[c] + nbr_pos(l, c, a)];
    /* cube corners in ss_cube_corner_bits order: 000 v, 100 a, 110 ab, 010 b,
     * 001 c, 101 ca, 111 abc, 011 bc */
    ss_idx h[8] = {0,  (ss_idx)(1 + a), ab, (ss_idx)(1 + b), (ss_idx)(1 + c),
                   ca, cp0 + (ss_idx)t, bc};
    if ((st = ss_star_push_cell(s, h, err))) goto done;
  }
  st = ss_star_check_positive(s, err);
done:
  free(edges);
  free(eid);
  free(tri);
  if (st) {
    ss_star_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}

ss_status ss_star_tet_vertex(const ss_link *l, ss_star **out, ss_error *err) {
  *out = NULL;
  const int k = l->k;
  ss_star *s = NULL;
  int *tri = NULL, ntri = 0;
  ss_status st = vertex_star_begin(l, SS_TET, (size_t)(k + 1), &tri, &ntri, &s, err);
  if (st) return st;
  if ((st = ss_star_push_vertex(s, ss_star_coord_make(0, NULL, NULL), err))) goto done;
  for (int a = 0; a < k; a++) {
    int32_t ia = a, one = 1;
    if ((st = ss_star_push_vertex(s, ss_star_coord_make(1, &ia, &one), err))) goto done;
  }
  for (int t = 0; t < ntri; t++) {
    ss_idx v[4] = {0, (ss_idx)(1 + tri[3 * t]), (ss_idx)(1 + tri[3 * t + 1]),
                   (ss_idx)(1 + tri[3 * t + 2])};
    if ((st = ss_star_push_cell(s, v, err))) goto done;
  }
  st = ss_star_check_positive(s, err);
done:
  free(tri);
  if (st) {
    ss_star_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}
