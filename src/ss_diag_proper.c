/* ss_diag_proper.c — counting improper pairs of major diagonals.  See
 * ss_diag.h for the reading of Definition 3.2 this implements. */
#include "ss_diag.h"

#include <stdlib.h>
#include <string.h>

/* A triangular face of a tet or octahedron: sorted corners, the cell. */
typedef struct {
  ss_idx v[3];
  int type; /* SS_TET or SS_OCT */
  size_t cell;
} cface;

static int cface_cmp(const void *a, const void *b) {
  const cface *x = a, *y = b;
  for (int i = 0; i < 3; i++)
    if (x->v[i] != y->v[i]) return x->v[i] < y->v[i] ? -1 : 1;
  if (x->type != y->type) return x->type < y->type ? -1 : 1;
  return (x->cell > y->cell) - (x->cell < y->cell);
}

/* An edge of an octahedron: sorted ends, the octahedron. */
typedef struct {
  ss_idx a, b;
  size_t oct;
} oedge;

static int oedge_cmp(const void *p, const void *q) {
  const oedge *x = p, *y = q;
  if (x->a != y->a) return x->a < y->a ? -1 : 1;
  if (x->b != y->b) return x->b < y->b ? -1 : 1;
  return (x->oct > y->oct) - (x->oct < y->oct);
}

static void sort3(ss_idx *v) {
  for (int i = 1; i < 3; i++)
    for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
      const ss_idx t = v[j];
      v[j] = v[j - 1];
      v[j - 1] = t;
    }
}

static int in_face(const ss_idx *f, ss_idx x) {
  return f[0] == x || f[1] == x || f[2] == x;
}

/* The diagonal's mark on a shared face: for a tet, the one edge of its pair
 * (0,1), (2,3) that lies in the face (as a key); for an octahedron, the one
 * end of its diagonal (0, 3) that does. */
static uint64_t mark(const ss_cx *cx, int type, size_t cell, const ss_idx *f) {
  const ss_idx *v = ss_cx_cell(cx, (ss_cell_type)type, cell);
  if (type == SS_OCT) return in_face(f, v[0]) ? v[0] : v[3];
  const ss_idx a = in_face(f, v[0]) && in_face(f, v[1]) ? v[0] : v[2];
  const ss_idx b = a == v[0] ? v[1] : v[3];
  return a < b ? ((uint64_t)a << 32) | b : ((uint64_t)b << 32) | a;
}

static int shared_vertices(const ss_idx *u, const ss_idx *w) {
  int n = 0;
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < 6; j++)
      n += u[i] == w[j];
  return n;
}

ss_status ss_diag_improper(const ss_cx *cx, size_t *pairs, size_t *improper,
                           ss_error *err) {
  const size_t nt = cx->nc[SS_TET], no = cx->nc[SS_OCT];
  size_t np = 0, nbad = 0;
  cface *F = malloc((4 * nt + 8 * no + 1) * sizeof *F);
  oedge *E = malloc((12 * no + 1) * sizeof *E);
  if (!F || !E) {
    free(F);
    free(E);
    return ss_error_nomem(err, "major-diagonal pairs");
  }
  size_t nf = 0;
  for (size_t t = 0; t < nt; t++) {
    const ss_idx *v = ss_cx_cell(cx, SS_TET, t);
    for (int k = 0; k < 4; k++) {
      cface *x = F + nf++;
      for (int i = 0; i < 3; i++)
        x->v[i] = v[(k + 1 + i) % 4];
      sort3(x->v);
      x->type = SS_TET;
      x->cell = t;
    }
  }
  size_t ne = 0;
  for (size_t o = 0; o < no; o++) {
    const ss_idx *v = ss_cx_cell(cx, SS_OCT, o);
    for (int k = 0; k < 8; k++) { /* one of each opposite pair per face */
      cface *x = F + nf++;
      x->v[0] = v[k & 1 ? 3 : 0];
      x->v[1] = v[k & 2 ? 4 : 1];
      x->v[2] = v[k & 4 ? 5 : 2];
      sort3(x->v);
      x->type = SS_OCT;
      x->cell = o;
    }
    for (int i = 0; i < 6; i++)
      for (int j = i + 1; j < 6; j++)
        if (j != i + 3) {
          const ss_idx a = v[i], b = v[j];
          E[ne].a = a < b ? a : b;
          E[ne].b = a < b ? b : a;
          E[ne++].oct = o;
        }
  }
  qsort(F, nf, sizeof *F, cface_cmp);
  for (size_t i = 0; i + 1 < nf; i++) {
    const cface *x = F + i, *y = F + i + 1;
    if (memcmp(x->v, y->v, sizeof x->v) || x->type != y->type) continue;
    /* two tets or two octahedra across a face: the face-to-face case */
    np++;
    nbad += mark(cx, x->type, x->cell, x->v) != mark(cx, y->type, y->cell, y->v);
  }
  qsort(E, ne, sizeof *E, oedge_cmp);
  for (size_t i = 0; i < ne;) {
    size_t j = i + 1;
    while (j < ne && E[j].a == E[i].a && E[j].b == E[i].b)
      j++;
    for (size_t p = i; p < j; p++)
      for (size_t q = p + 1; q < j; q++) {
        const ss_idx *u = ss_cx_cell(cx, SS_OCT, E[p].oct),
                     *w = ss_cx_cell(cx, SS_OCT, E[q].oct);
        if (shared_vertices(u, w) != 2) continue; /* face pairs are counted above */
        const ss_idx x = E[i].a, y = E[i].b;
        const int x1 = x == u[0] || x == u[3], y1 = y == u[0] || y == u[3];
        const int x2 = x == w[0] || x == w[3], y2 = y == w[0] || y == w[3];
        np++;
        nbad += !((x1 && y2) || (y1 && x2) || (!x1 && !y1 && !x2 && !y2));
      }
    i = j;
  }
  free(F);
  free(E);
  *pairs = np;
  *improper = nbad;
  return SS_OK;
}
