/* ss_local_label.c — exact coordinates relative to the centre: their
 * arithmetic from a level to the next, the vertices of a level looked up by
 * them, and the labels' order (ss_local.h: ordering). */
#include <stdlib.h>

#include "ss_local_impl.h"

/* ---- sparse coordinate arithmetic ---- */

/* sum_i mult[i] * c[i] / div, which must be an integer vector with at most
 * SS_STAR_MAXSUPP nonzeros.  Returns 0 on success, -1 otherwise. */
int ss_local_lincomb(int m, const ss_star_coord *const *c, const int *mult, int div,
                     ss_star_coord *out) {
  int32_t idx[8 * SS_STAR_MAXSUPP];
  long val[8 * SS_STAR_MAXSUPP];
  int n = 0;
  for (int i = 0; i < m; i++)
    for (int e = 0; e < c[i]->n; e++) {
      int j = 0;
      while (j < n && idx[j] != c[i]->idx[e])
        j++;
      if (j == n) {
        if (n == 8 * SS_STAR_MAXSUPP) return -1;
        idx[n] = c[i]->idx[e];
        val[n++] = 0;
      }
      val[j] += (long)mult[i] * c[i]->val[e];
    }
  int32_t oi[SS_STAR_MAXSUPP], ov[SS_STAR_MAXSUPP];
  int k = 0;
  for (int j = 0; j < n; j++) {
    if (val[j] == 0) continue;
    if (val[j] % div != 0 || k == SS_STAR_MAXSUPP) return -1;
    oi[k] = idx[j];
    ov[k++] = (int32_t)(val[j] / div);
  }
  *out = ss_star_coord_make(k, oi, ov);
  return 0;
}

/* 2 * (the mean of the np parents' coordinates), which must be an integer
 * vector with at most SS_STAR_MAXSUPP nonzeros: ss_local_lincomb(np, par,
 * {2, ..}, np, out) to the bit, the entries merged in index order as they
 * come (the parents' entries are few and each parent's ascending).  0 or
 * -1. */
int ss_local_child_coord(int np, const ss_star_coord *const *par, ss_star_coord *out) {
  if (np == 1) { /* a coarse vertex: its coordinates doubled */
    *out = *par[0];
    for (int e = 0; e < out->n; e++)
      out->val[e] = (int32_t)(2L * par[0]->val[e]);
    return 0;
  }
  int32_t idx[8 * SS_STAR_MAXSUPP];
  long val[8 * SS_STAR_MAXSUPP];
  int n = 0;
  for (int i = 0; i < np; i++)
    for (int e = 0; e < par[i]->n; e++) {
      const int32_t x = par[i]->idx[e];
      int j = n;
      while (j > 0 && idx[j - 1] > x)
        j--;
      if (j > 0 && idx[j - 1] == x) {
        val[j - 1] += 2L * par[i]->val[e];
        continue;
      }
      if (n == 8 * SS_STAR_MAXSUPP) return -1;
      for (int u = n; u > j; u--) { /* a loop: memmove would be a call */
        idx[u] = idx[u - 1];
        val[u] = val[u - 1];
      }
      idx[j] = x;
      val[j] = 2L * par[i]->val[e];
      n++;
    }
  ss_star_coord c;
  c.n = 0;
  for (int j = 0; j < n; j++) {
    if (val[j] == 0) continue;
    if (val[j] % np != 0 || c.n == SS_STAR_MAXSUPP) return -1;
    c.idx[c.n] = idx[j];
    c.val[c.n++] = (int32_t)(val[j] / np);
  }
  for (int i = c.n; i < SS_STAR_MAXSUPP; i++) { /* as ss_star_coord_make leaves them */
    c.idx[i] = -1;
    c.val[i] = 0;
  }
  *out = c;
  return 0;
}

/* ---- lookup by coordinates ---- */

/* A hash of a coordinate vector (of its nonzero entries: the unused slots
 * of equal vectors agree anyway). */
static size_t coord_hash(const ss_star_coord *c) {
  uint64_t h = (uint64_t)(c->n + 1) * 0x9e3779b97f4a7c15u;
  for (int i = 0; i < c->n; i++) {
    h ^= (uint64_t)(uint32_t)c->idx[i] << 32 | (uint32_t)c->val[i];
    h *= 0xff51afd7ed558ccdu;
    h ^= h >> 29;
  }
  return (size_t)h;
}

/* The slot of L's index holding the vertex with relative coordinates c, or
 * the empty slot where it would go. */
size_t ss_local_slot(const ss_local_level *L, const ss_star_coord *c) {
  size_t h = coord_hash(c) & L->mask;
  while (L->index[h] != SS_IDX_NONE && ss_star_coord_cmp(L->rel + L->index[h], c) != 0)
    h = (h + 1) & L->mask;
  return h;
}

/* Vertex with relative coordinates c on level l, or SIZE_MAX. */
size_t ss_local_lookup(const ss_local_level *L, const ss_star_coord *c) {
  const ss_idx v = L->index[ss_local_slot(L, c)];
  return v == SS_IDX_NONE ? SIZE_MAX : (size_t)v;
}

/* ---- labels ---- */

int ss_local_label_norm(const ss_star_coord *c) {
  int m = 0;
  for (int i = 0; i < c->n; i++)
    m = abs(c->val[i]) > m ? abs(c->val[i]) : m;
  return m;
}

int ss_local_label_cmp(const void *a, const void *b) {
  const ss_star_coord *x = a, *y = b;
  int nx = ss_local_label_norm(x), ny = ss_local_label_norm(y);
  if (nx != ny) return nx < ny ? -1 : 1;
  return ss_star_coord_cmp(x, y);
}

/* Index of the label x among M's labels (sorted within the one-ring and
 * within the rest), or SIZE_MAX. */
size_t ss_local_label_index(const ss_local *M, const ss_star_coord *x) {
  const ss_star_coord *hit =
      bsearch(x, M->label, M->n1, sizeof *M->label, ss_local_label_cmp);
  if (!hit)
    hit =
        bsearch(x, M->label + M->n1, M->n2 - M->n1, sizeof *M->label, ss_local_label_cmp);
  return hit ? (size_t)(hit - M->label) : SIZE_MAX;
}

int ss_local_centre_corner(const ss_local *M, size_t c) {
  for (int j = 0; j < SS_MAXCELLVERTS; j++)
    if (M->corner[c * SS_MAXCELLVERTS + (size_t)j] == 0) return j;
  return -1;
}
