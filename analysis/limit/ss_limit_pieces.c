/* ss_limit_pieces.c — the boxes where the limit is a tricubic B-spline
 * (ss_limit_pieces.h). */
#include "ss_limit_pieces.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_limit_impl.h"

/* The traversal's fixed arguments. */
typedef struct {
  ss_limit *L;
  size_t cell;
  int maxdepth;
  ss_limit_box_skip skip;
  ss_limit_piece_fn fn;
  void *arg;
  int stop; /* the callback asked to stop */
} trav;

/* The box of patch p (complex pcx, owned here and freed) at depth, origin. */
static ss_status box(trav *t, ss_lim_patch *p, ss_cx *pcx, int depth,
                     const double origin[3], ss_error *err) {
  ss_status st = SS_OK;
  ss_limit_piece pc = {t->cell, depth, {origin[0], origin[1], origin[2]}, NULL};
  if (p->regular) {
    double net[64][3];
    const double *x0 = pcx->x + 3 * (size_t)p->net[21]; /* grid position (0,0,0) */
    for (int q = 0; q < 64; q++)
      for (int d = 0; d < 3; d++)
        net[q][d] = pcx->x[3 * (size_t)p->net[q] + (size_t)d] - x0[d];
    pc.net = (const double(*)[3])net;
    t->stop = t->fn(&pc, t->arg);
  } else if (depth >= t->maxdepth) {
    t->stop = t->fn(&pc, t->arg);
  } else {
    const double h = ldexp(1.0, -depth - 1);
    for (int k = 0; k < 8 && !st && !t->stop; k++) {
      const unsigned b = ss_cube_corner_bits(3, k);
      const double o[3] = {origin[0] + ((b & 1u) ? h : 0.0),
                           origin[1] + ((b & 2u) ? h : 0.0),
                           origin[2] + ((b & 4u) ? h : 0.0)};
      if (t->skip && t->skip(t->cell, depth + 1, o, t->arg)) continue;
      ss_lim_patch child;
      ss_lim_frame g;
      ss_cx *ccx = NULL;
      if ((st = ss_lim_step(t->L->s, pcx, k, 0, &child, &g, &ccx, NULL, err))) break;
      st = box(t, &child, ccx, depth + 1, o, err);
    }
  }
  ss_lim_patch_free(p);
  ss_cx_free(pcx);
  return st;
}

ss_status ss_limit_pieces(ss_limit *L, size_t cell, int maxdepth, ss_limit_box_skip skip,
                          ss_limit_piece_fn fn, void *arg, ss_error *err) {
  if (cell >= L->adj.nh || maxdepth < 0 || maxdepth > 10)
    return ss_error_set(err, SS_EINPUT, "limit pieces: cell %zu of %zu, depth %d (0..10)",
                        cell + 1, L->adj.nh, maxdepth);
  const double o[3] = {0.0, 0.0, 0.0};
  if (skip && skip(cell, 0, o, arg)) return SS_OK;
  trav t = {L, cell, maxdepth, skip, fn, arg, 0};
  ss_lim_frame g = ss_lim_frame_id();
  ss_lim_patch p;
  ss_cx *pcx = NULL;
  ss_status st = ss_lim_patch_build(&L->adj, cell, &g, L->loc, &p, err);
  if (st) return st;
  if ((st = ss_lim_patch_complex(L->mesh, &p, &pcx, err))) {
    ss_lim_patch_free(&p);
    return st;
  }
  return box(&t, &p, pcx, 0, o, err);
}
