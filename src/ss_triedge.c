/* ss_triedge.c — edge table of a triangle complex, by sorting the 3T
 * half-edges (no hashing: the sort also gives every edge a deterministic
 * index, ascending in its endpoints). */
#include "ss_triedge.h"

#include <stdint.h>
#include <stdlib.h>

typedef struct {
  ss_idx lo, hi; /* endpoints, lo < hi */
  size_t slot;   /* 3*t + k: triangle t, opposite corner k */
} half;

static int cmp_half(const void *a, const void *b) {
  const half *x = a, *y = b;
  if (x->lo != y->lo) return (x->lo > y->lo) - (x->lo < y->lo);
  if (x->hi != y->hi) return (x->hi > y->hi) - (x->hi < y->hi);
  return (x->slot > y->slot) - (x->slot < y->slot);
}

void ss_triedge_free(ss_triedge *te) {
  if (!te) return;
  free(te->end);
  free(te->nface);
  free(te->face);
  free(te->tedge);
  free(te->vptr);
  free(te->vnbr);
  free(te->vbnd);
  free(te);
}

ss_status ss_triedge_new(const ss_cx *cx, ss_triedge **out, ss_error *err) {
  *out = NULL;
  const size_t nt = cx->nc[SS_TRIANGLE], nh = 3 * nt, nv = cx->nv;
  ss_triedge *te = calloc(1, sizeof *te);
  half *h = malloc((nh + 1) * sizeof *h);
  if (!te || !h) {
    free(h);
    free(te);
    return ss_error_nomem(err, "edge table");
  }
  for (size_t t = 0; t < nt; t++) {
    const ss_idx *v = ss_cx_cell(cx, SS_TRIANGLE, t);
    for (int k = 0; k < 3; k++) {
      ss_idx a = v[(k + 1) % 3], b = v[(k + 2) % 3];
      if (a == b) {
        free(h);
        free(te);
        return ss_error_set(err, SS_EINPUT, "triangle %zu repeats vertex %lu", t + 1,
                            (unsigned long)a + 1);
      }
      h[3 * t + (size_t)k] = (half){a < b ? a : b, a < b ? b : a, 3 * t + (size_t)k};
    }
  }
  qsort(h, nh, sizeof *h, cmp_half);
  size_t ne = 0;
  for (size_t i = 0; i < nh; i++)
    if (i == 0 || h[i].lo != h[i - 1].lo || h[i].hi != h[i - 1].hi) ne++;
  te->ne = ne;
  te->nv = nv;
  te->end = malloc((2 * ne + 1) * sizeof *te->end);
  te->nface = calloc(ne + 1, sizeof *te->nface);
  te->face = malloc((2 * ne + 1) * sizeof *te->face);
  te->tedge = malloc((nh + 1) * sizeof *te->tedge);
  te->vptr = calloc(nv + 1, sizeof *te->vptr);
  te->vnbr = malloc((2 * ne + 1) * sizeof *te->vnbr);
  te->vbnd = calloc(nv + 1, 1);
  if (!te->end || !te->nface || !te->face || !te->tedge || !te->vptr || !te->vnbr ||
      !te->vbnd) {
    free(h);
    ss_triedge_free(te);
    return ss_error_nomem(err, "edge table");
  }
  size_t e = SIZE_MAX;
  for (size_t i = 0; i < nh; i++) {
    if (i == 0 || h[i].lo != h[i - 1].lo || h[i].hi != h[i - 1].hi) {
      e = e == SIZE_MAX ? 0 : e + 1;
      te->end[2 * e] = h[i].lo;
      te->end[2 * e + 1] = h[i].hi;
      te->face[2 * e] = te->face[2 * e + 1] = SIZE_MAX;
    }
    if (te->nface[e] < 2) te->face[2 * e + te->nface[e]] = h[i].slot / 3;
    te->nface[e]++;
    te->tedge[h[i].slot] = e;
  }
  free(h);
  /* adjacency in CSR form; edges are sorted, so each list comes out ascending
   * once both directions are merged by a counting pass per vertex */
  for (e = 0; e < ne; e++) {
    te->vptr[te->end[2 * e] + 1]++;
    te->vptr[te->end[2 * e + 1] + 1]++;
    if (te->nface[e] == 1) te->vbnd[te->end[2 * e]] = te->vbnd[te->end[2 * e + 1]] = 1;
  }
  for (size_t v = 0; v < nv; v++)
    te->vptr[v + 1] += te->vptr[v];
  size_t *fill = malloc((nv + 1) * sizeof *fill);
  if (!fill) {
    ss_triedge_free(te);
    return ss_error_nomem(err, "edge table");
  }
  for (size_t v = 0; v < nv; v++)
    fill[v] = te->vptr[v];
  /* the neighbours below v come from edges (u, v) with u < v, met in ascending u
   * before any edge (v, w) is met in ascending w: one pass in edge order keeps
   * every list ascending */
  for (e = 0; e < ne; e++) {
    ss_idx a = te->end[2 * e], b = te->end[2 * e + 1];
    te->vnbr[fill[a]++] = b;
    te->vnbr[fill[b]++] = a;
  }
  free(fill);
  *out = te;
  return SS_OK;
}

size_t ss_triedge_nonmanifold(const ss_triedge *te) {
  for (size_t e = 0; e < te->ne; e++)
    if (te->nface[e] > 2) return e;
  return SIZE_MAX;
}
