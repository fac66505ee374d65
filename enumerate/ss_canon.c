/* ss_canon.c — least breadth-first codes of rotation systems (see ss_canon.h). */
#include "ss_canon.h"

#include <stdlib.h>
#include <string.h>

ss_canon_ws *ss_canon_ws_new(int maxk, int maxcode, int maxbest) {
  ss_canon_ws *w = calloc(1, sizeof *w);
  if (!w) return NULL;
  w->maxk = maxk;
  w->maxcode = maxcode;
  w->maxbest = maxbest;
  w->code = malloc((size_t)maxcode * sizeof *w->code);
  w->best = malloc((size_t)maxcode * sizeof *w->best);
  w->label = malloc((size_t)maxk * sizeof *w->label);
  w->order = malloc((size_t)maxk * sizeof *w->order);
  w->entry = malloc((size_t)maxk * sizeof *w->entry);
  w->best_order = malloc((size_t)maxk * sizeof *w->best_order);
  w->labels = malloc((size_t)maxk * (size_t)maxbest * sizeof *w->labels);
  if (!w->code || !w->best || !w->label || !w->order || !w->entry || !w->best_order ||
      !w->labels) {
    ss_canon_ws_free(w);
    return NULL;
  }
  return w;
}

void ss_canon_ws_free(ss_canon_ws *w) {
  if (!w) return;
  free(w->code);
  free(w->best);
  free(w->label);
  free(w->order);
  free(w->entry);
  free(w->best_order);
  free(w->labels);
  free(w);
}

void ss_canon_inverse(int k, const int *off, const int *deg, const int *nbr, int *inv) {
  for (int v = 0; v < k; v++)
    for (int i = 0; i < deg[v]; i++) {
      int w = nbr[off[v] + i];
      for (int j = 0; j < deg[w]; j++)
        if (nbr[off[w] + j] == v) {
          inv[off[v] + i] = off[w] + j;
          break;
        }
    }
}

/* One start.  Returns -1 if its code is less than w->best (then w->code holds
 * it, unless `quit_below`: then it returns at the first lower entry), 0 if
 * equal, +1 if greater (abandoned early).  `first`: no best yet. */
static int one_start(const ss_cgraph *g, int v0, int p0, int dir, ss_canon_ws *w,
                     int first, int quit_below) {
  const int k = g->k;
  int *label = w->label, *order = w->order, *code = w->code;
  int *ent = w->entry;
  for (int v = 0; v < k; v++)
    label[v] = -1;
  int cmp = first ? -1 : 0, n = 0, nl = 1;
  label[v0] = 0;
  order[0] = v0;
  ent[v0] = p0;
  const int *best = w->best;
  for (int i = 0; i < k; i++) {
    const int x = order[i], d = g->deg[x], base = g->off[x];
    const int *row = g->nbr + base;
    int p = ent[x];
    for (int j = 0; j < d; j++) {
      const int y = row[p];
      int c = label[y];
      if (c < 0) {
        c = label[y] = nl;
        order[nl++] = y;
        if (g->inv) {
          ent[y] = g->inv[base + p] - g->off[y];
        } else {
          const int *ly = g->nbr + g->off[y];
          int q = 0;
          while (ly[q] != x)
            q++;
          ent[y] = q;
        }
      }
      if (cmp == 0) {
        if (c > best[n]) return 1;
        if (c < best[n]) {
          if (quit_below) return -1;
          cmp = -1;
        }
      }
      code[n++] = c;
      p += dir;
      if ((unsigned)p >= (unsigned)d) p -= dir * d; /* wrapped: d -> 0, -1 -> d - 1 */
    }
    if (cmp == 0) {
      if (k > best[n]) return 1;
      if (k < best[n]) {
        if (quit_below) return -1;
        cmp = -1;
      }
    }
    code[n++] = k;
  }
  w->ncode = cmp < 0 ? n : w->ncode;
  return cmp;
}

int ss_canon_run(const ss_cgraph *g, const int *starts, int nstarts, int nfirst,
                 ss_canon_ws *w) {
  const int k = g->k;
  w->nbest = 0;
  int first = 1;
  for (int s = 0; s < nstarts; s++) {
    const int *st = starts + 3 * s;
    int r = one_start(g, st[0], st[1], st[2], w, first, s >= nfirst);
    if (r > 0) continue;
    if (r < 0 && s >= nfirst) return 1;
    if (r < 0) {
      memcpy(w->best, w->code, (size_t)w->ncode * sizeof *w->best);
      memcpy(w->best_order, w->order, (size_t)k * sizeof *w->order);
      w->nbest = 0;
      first = 0;
    }
    if (w->nbest < w->maxbest)
      memcpy(w->labels + (size_t)w->nbest * (size_t)k, w->label,
             (size_t)k * sizeof *w->label);
    w->nbest++;
  }
  return 0;
}
