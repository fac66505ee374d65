/* ss_limit_pieces.c — the boxes where the limit is a tricubic B-spline
 * (ss_limit_pieces.h). */
#include "ss_limit_pieces.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "double_interval.h"
#include "ss_limit_impl.h"

/* The traversal's fixed arguments. */
typedef struct {
  ss_limit *L;
  size_t cell;
  int maxdepth;
  const ss_limit_enclosure *enc; /* NULL: doubles only */
  ss_limit_box_skip skip;
  ss_limit_piece_fn fn;
  void *arg;
  ss_limit_rational_fn rat; /* non-NULL: tubes for the uncovered boxes */
  void *rarg;               /* passed to rat */
  int stop;                 /* the callback asked to stop */
} trav;

/* An enclosure of a patch's points: lo[3 i + d] <= point i's coordinate d <=
 * hi[3 i + d], in the patch complex's vertex order. */
typedef struct {
  double *lo, *hi;
} box_enc;

static void enc_free(box_enc *e) {
  free(e->lo);
  free(e->hi);
  e->lo = e->hi = NULL;
}

static ss_status enc_alloc(box_enc *e, size_t nv, ss_error *err) {
  e->lo = malloc((3 * nv + 1) * sizeof *e->lo);
  e->hi = malloc((3 * nv + 1) * sizeof *e->hi);
  if (e->lo && e->hi) return SS_OK;
  enc_free(e);
  return ss_error_nomem(err, "limit pieces: enclosure");
}

/* The child's enclosure from the parent's through the rows W (nc x np) of
 * the refinement, each weight replaced by its enclosure (the caller's
 * weight function): interval arithmetic, outward rounding. */
static ss_status enc_step(const trav *t, const double *W, size_t nc, size_t np,
                          const box_enc *parent, box_enc *child, ss_error *err) {
  ss_status st = enc_alloc(child, nc, err);
  if (st) return st;
  for (size_t i = 0; i < nc; i++) {
    di_t s[3] = {di_interval(0, 0), di_interval(0, 0), di_interval(0, 0)};
    for (size_t j = 0; j < np; j++) {
      const double w = W[i * np + j];
      if (w == 0.0) continue;
      double wlo, whi;
      if (t->enc->weight(w, t->enc->arg, &wlo, &whi) || !(wlo <= whi)) {
        enc_free(child);
        return ss_error_set(err, SS_ENUMERIC,
                            "limit pieces: the rule's weight %.17g has no enclosure", w);
      }
      const di_t wi = di_interval(wlo, whi);
      for (int d = 0; d < 3; d++)
        s[d] = di_fast_add(s[d],
                           di_fast_mul(wi, di_interval(parent->lo[3 * j + (size_t)d],
                                                       parent->hi[3 * j + (size_t)d])));
    }
    for (int d = 0; d < 3; d++) {
      child->lo[3 * i + (size_t)d] = s[d].a;
      child->hi[3 * i + (size_t)d] = s[d].b;
    }
  }
  return SS_OK;
}

/* The piece's 64 points translated by -x0 (exactly representable doubles):
 * the net from the patch complex, its enclosure (e, if any) outward rounded. */
static void piece_net(const ss_lim_patch *p, const ss_cx *pcx, const box_enc *e,
                      double net[64][3], double lo[64][3], double hi[64][3]) {
  const double *x0 = pcx->x + 3 * (size_t)p->net[21]; /* grid position (0,0,0) */
  for (int q = 0; q < 64; q++)
    for (int d = 0; d < 3; d++) {
      const size_t k = 3 * (size_t)p->net[q] + (size_t)d;
      net[q][d] = pcx->x[k] - x0[d];
      if (!e->lo) continue;
      const di_t y = di_fast_sub_d(di_interval(e->lo[k], e->hi[k]), x0[d]);
      lo[q][d] = y.a;
      hi[q][d] = y.b;
    }
}

/* The box of patch p (complex pcx and enclosure e, owned here and freed) at
 * depth, origin. */
static ss_status box(trav *t, ss_lim_patch *p, ss_cx *pcx, box_enc *e, int depth,
                     const double origin[3], ss_error *err) {
  ss_status st = SS_OK;
  ss_limit_piece pc = {t->cell, depth, {origin[0], origin[1], origin[2]}, NULL, NULL,
                       NULL,    NULL,  {pcx->x[0], pcx->x[1], pcx->x[2]}};
  if (p->regular) {
    double net[64][3], lo[64][3], hi[64][3];
    piece_net(p, pcx, e, net, lo, hi);
    for (int d = 0; d < 3; d++) /* piece_net's x0 */
      pc.shift[d] = pcx->x[3 * (size_t)p->net[21] + (size_t)d];
    pc.net = (const double(*)[3])net;
    if (e->lo) {
      pc.lo = (const double(*)[3])lo;
      pc.hi = (const double(*)[3])hi;
    }
    t->stop = t->fn(&pc, t->arg);
  } else if (depth >= t->maxdepth) {
    ss_lim_tube *u = NULL;
    if (t->rat && (st = ss_lim_tube_build(t->L->s, p, pcx, e->lo, e->hi, pcx->x, t->rat,
                                          t->rarg, &u, err)))
      goto out;
    pc.tube = ss_lim_tube_view(u);
    t->stop = t->fn(&pc, t->arg);
    ss_lim_tube_free(u);
  } else {
    const double h = ldexp(1.0, -depth - 1);
    ss_lim_refined rf; /* the box's patch refined once for all its children */
    int refined = 0;
    for (int k = 0; k < 8 && !st && !t->stop; k++) {
      const unsigned b = ss_cube_corner_bits(3, k);
      const double o[3] = {origin[0] + ((b & 1u) ? h : 0.0),
                           origin[1] + ((b & 2u) ? h : 0.0),
                           origin[2] + ((b & 4u) ? h : 0.0)};
      if (t->skip && t->skip(t->cell, depth + 1, o, t->arg)) continue;
      if (!refined) {
        refined = 1;
        if ((st = ss_lim_refine(t->L->s, pcx, e->lo != NULL, &rf, err))) break;
      }
      ss_lim_patch child;
      ss_lim_frame g;
      ss_cx *ccx = NULL;
      double *W = NULL;
      box_enc ce = {NULL, NULL};
      if ((st = ss_lim_cut(&rf, k, 0, &child, &g, &ccx, e->lo ? &W : NULL, err))) break;
      if (e->lo && (st = enc_step(t, W, child.nv, pcx->nv, e, &ce, err))) {
        free(W);
        ss_lim_patch_free(&child);
        ss_cx_free(ccx);
        break;
      }
      free(W);
      st = box(t, &child, ccx, &ce, depth + 1, o, err);
    }
    if (refined) ss_lim_refined_free(&rf);
  }
out:
  ss_lim_patch_free(p);
  ss_cx_free(pcx);
  enc_free(e);
  return st;
}

/* The root box of the cell: its patch, and the enclosure of its points. */
static ss_status root(trav *t, ss_error *err) {
  const double o[3] = {0.0, 0.0, 0.0};
  if (t->skip && t->skip(t->cell, 0, o, t->arg)) return SS_OK;
  ss_lim_frame g = ss_lim_frame_id();
  ss_lim_patch p;
  ss_cx *pcx = NULL;
  box_enc e = {NULL, NULL};
  ss_status st = ss_lim_patch_build(&t->L->adj, t->cell, &g, t->L->loc, &p, err);
  if (st) return st;
  if ((st = ss_lim_patch_complex(t->L->mesh, &p, &pcx, err))) {
    ss_lim_patch_free(&p);
    return st;
  }
  if (t->enc && !(st = enc_alloc(&e, p.nv, err))) {
    for (size_t i = 0; i < p.nv; i++)
      for (int d = 0; d < 3; d++) {
        const size_t k = 3 * (size_t)p.src[i] + (size_t)d;
        e.lo[3 * i + (size_t)d] = t->enc->lo[k];
        e.hi[3 * i + (size_t)d] = t->enc->hi[k];
      }
  }
  if (st) {
    ss_lim_patch_free(&p);
    ss_cx_free(pcx);
    return st;
  }
  return box(t, &p, pcx, &e, 0, o, err);
}

static ss_status check(const ss_limit *L, size_t cell, int maxdepth,
                       const ss_limit_enclosure *enc, ss_error *err) {
  if (cell >= L->adj.nh || maxdepth < 0 || maxdepth > 10)
    return ss_error_set(err, SS_EINPUT, "limit pieces: cell %zu of %zu, depth %d (0..10)",
                        cell + 1, L->adj.nh, maxdepth);
  if (!enc) return SS_OK;
  if (!enc->lo || !enc->hi || !enc->weight)
    return ss_error_set(err, SS_EINPUT, "limit pieces: an enclosure without %s",
                        enc->weight ? "points" : "a weight function");
  const size_t n = 3 * L->mesh->nv;
  for (size_t i = 0; i < n; i++)
    if (!(enc->lo[i] <= enc->hi[i]) || !isfinite(enc->lo[i]) || !isfinite(enc->hi[i]))
      return ss_error_set(err, SS_EINPUT,
                          "limit pieces: point %zu's enclosure [%g, %g] is not an "
                          "interval of finite bounds",
                          i / 3 + 1, enc->lo[i], enc->hi[i]);
  return SS_OK;
}

ss_status ss_limit_pieces(ss_limit *L, size_t cell, int maxdepth, ss_limit_box_skip skip,
                          ss_limit_piece_fn fn, void *arg, ss_error *err) {
  return ss_limit_pieces_enclosed(L, cell, maxdepth, NULL, skip, fn, arg, err);
}

ss_status ss_limit_pieces_enclosed(ss_limit *L, size_t cell, int maxdepth,
                                   const ss_limit_enclosure *enc, ss_limit_box_skip skip,
                                   ss_limit_piece_fn fn, void *arg, ss_error *err) {
  return ss_limit_pieces_tubes(L, cell, maxdepth, enc, NULL, NULL, skip, fn, arg, err);
}

ss_status ss_limit_pieces_tubes(ss_limit *L, size_t cell, int maxdepth,
                                const ss_limit_enclosure *enc, ss_limit_rational_fn rat,
                                void *rarg, ss_limit_box_skip skip, ss_limit_piece_fn fn,
                                void *arg, ss_error *err) {
  const ss_status st = check(L, cell, maxdepth, enc, err);
  if (st) return st;
  trav t = {L, cell, maxdepth, enc, skip, fn, arg, rat, rarg, 0};
  return root(&t, err);
}
