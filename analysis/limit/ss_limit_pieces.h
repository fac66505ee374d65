/* ss_limit_pieces.h — where the limit is a polynomial: the boxes of a cell's
 * parameters on which the limit of a hex mesh (ss_limit.h) is exactly the
 * tricubic B-spline of 64 points, found by refining the cell's patch.
 *
 * From the cell's box (depth 0): a box whose patch is the 3x3x3 block of a
 * grid is one piece; otherwise its 8 children (child k the octant at corner
 * k, its patch cut from one refinement of the box's patch, ss_lim_refine and
 * ss_lim_cut, the same patch the reference evaluator ss_limit_eval_reference
 * reaches by ss_lim_step), down to maxdepth, where a box
 * still irregular is left uncovered (round an extraordinary vertex or edge
 * boxes never become regular).  Every patch is cut in the frame inherited
 * from the cell's vertex order, so a piece's own parameters are the box's,
 * axis for axis: t in [0,1]^3 is the cell's origin + 2^-depth t, and det
 * D_x(limit) = 2^(3 depth) det D_t(piece).  Nothing is cached across boxes:
 * each box that is split costs one refinement of its patch (about a
 * millisecond), shared by its children (until 2026-12-06 each child refined
 * the parent again: 7-8 refinements per box).
 *
 * Points.  A piece's net is the refined patch's (rows of the scheme applied
 * in doubles).  With an enclosure of the mesh's points (ss_limit_pieces_
 * enclosed), each patch also carries intervals holding its true points: the
 * rows of each step (ss_lim_cut's W) applied in interval arithmetic with
 * outward rounding, every nonzero weight replaced by the caller's enclosure
 * of the rule's true weight (e.g. the rational ss_exact_rational
 * reconstructs), so a piece's intervals hold the net of the exact rule
 * applied to any points inside the mesh's enclosure.  Each step then also
 * costs a dense product (child x parent points). */
#ifndef SS_LIMIT_PIECES_H
#define SS_LIMIT_PIECES_H

#include <stddef.h>

#include "ss_api.h"
#include "ss_error.h"
#include "ss_limit.h"
#include "ss_limit_tube.h"

SS_BEGIN_DECLS

/* One box: a polynomial piece of the limit, or a box left uncovered. */
typedef struct {
  size_t cell;            /* the mesh cell (0-based, as ss_limit_eval) */
  int depth;              /* the box has side 2^-depth in the cell's parameters */
  double origin[3];       /* its corner of smallest (u, v, w) */
  const double (*net)[3]; /* a piece: its 64 points in ss_limit_bspline's
                             layout (valid during the callback; translated by
                             a common vector, which changes no derivative);
                             NULL for a box left uncovered */
  const double (*lo)[3];  /* with an enclosure: lo[q] <= true point q - the
                             same vector <= hi[q] (valid during the
                             callback); NULL without one or without a piece */
  const double (*hi)[3];
  const ss_limit_tube *tube; /* an uncovered box's exact layered structure
                                round an extraordinary edge (valid during the
                                callback), with ss_limit_pieces_tubes; else
                                NULL */
  double shift[3];           /* the common vector net, lo, hi and the tube's
                                points are translated by: a true point is
                                shift + its translated one (an exactly
                                representable double point of the patch) */
} ss_limit_piece;

/* An enclosure of the rule's weight w (as the scheme computes it in
 * doubles): 0 with wlo <= true weight <= whi, nonzero if w is not known
 * exactly (the traversal then fails with SS_ENUMERIC). */
typedef int (*ss_limit_weight_fn)(double w, void *arg, double *wlo, double *whi);

/* What the true points of the mesh are known to be. */
typedef struct {
  const double *lo;          /* mesh->nv x 3, row by row: lo <= true point */
  const double *hi;          /* likewise, true point <= hi */
  ss_limit_weight_fn weight; /* the rule's true weights */
  void *arg;                 /* passed to weight */
} ss_limit_enclosure;

/* Called for each piece and each box left uncovered; nonzero stops the
 * traversal (ss_limit_pieces then returns SS_OK). */
typedef int (*ss_limit_piece_fn)(const ss_limit_piece *pc, void *arg);

/* Whether to leave out a box and everything in it (1) — e.g. the octant of
 * an extraordinary vertex; NULL keeps every box. */
typedef int (*ss_limit_box_skip)(size_t cell, int depth, const double origin[3],
                                 void *arg);

/* Visit the pieces of cell `cell` of L's mesh down to maxdepth (0..10).
 * SS_EINPUT for an unknown cell or depth out of range; SS_ENOMEM; the errors
 * of a refinement step. */
ss_status ss_limit_pieces(ss_limit *L, size_t cell, int maxdepth, ss_limit_box_skip skip,
                          ss_limit_piece_fn fn, void *arg, ss_error *err);

/* As ss_limit_pieces, each piece with the enclosure of its points from enc
 * (above).  SS_EINPUT also for an enclosure with a bound that is not finite
 * or lo > hi; SS_ENUMERIC for a weight without enclosure. */
ss_status ss_limit_pieces_enclosed(ss_limit *L, size_t cell, int maxdepth,
                                   const ss_limit_enclosure *enc, ss_limit_box_skip skip,
                                   ss_limit_piece_fn fn, void *arg, ss_error *err);

/* As ss_limit_pieces_enclosed (enc may be NULL), and each box left uncovered
 * at maxdepth with its tube (ss_limit_tube.h) where it has one, its weights
 * read by rat (rarg passed to it). */
ss_status ss_limit_pieces_tubes(ss_limit *L, size_t cell, int maxdepth,
                                const ss_limit_enclosure *enc, ss_limit_rational_fn rat,
                                void *rarg, ss_limit_box_skip skip, ss_limit_piece_fn fn,
                                void *arg, ss_error *err);

SS_END_DECLS

#endif
