/* ss_psi.c — the characteristic map judged on its polynomial pieces on the
 * ring.  Method and verdicts: ss_psi.h. */
#include "ss_psi.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"
#include "ss_cx.h"
#include "ss_dense.h"
#include "ss_exact.h"
#include "ss_limit.h"
#include "ss_limit_pieces.h"
#include "ss_psi_bernstein.h"
#include "ss_psi_inject.h"
#include "ss_psi_spoke.h"
#include "ss_psi_tube.h"

ss_psi_opts ss_psi_defaults(void) {
  return (ss_psi_opts){SS_PSI_BOX_DEPTH, SS_PSI_PIECE_DEPTH, 0};
}

/* A box of a cell's parameters: side 2^-depth, corner origin. */
typedef struct {
  size_t cell;
  int depth;
  double origin[3];
} box_id;

/* What a traversal does at each piece: judge it in doubles, or prove (with
 * the enclosure) the corner values of the target pieces, the fold of the
 * target piece, or the sign of every piece. */
typedef enum { WALK_JUDGE, WALK_CORNERS, WALK_FOLD, WALK_ALL } walk_mode;

/* What the traversal of one case carries. */
typedef struct {
  const ss_psi_opts *o;
  unsigned pbits;     /* the centre's corner of the current cell, as bits */
  walk_mode mode;     /* what visit does */
  double vol[4];      /* parameter volume: positive, negative, doubtful,
                         uncovered */
  ss_psi_result *r;   /* counts and witnesses */
  int have[2];        /* a proven positive [0] / negative [1] point kept */
  ss_psi_point pt[2]; /* those points */
  int ptdepth[2];     /* the depth of their pieces (their corners t = 0) */
  int folded;         /* a folded piece's two witnesses are in r->witness */
  box_id fbox;        /* that piece */
  /* the proof passes */
  int ntarget;               /* WALK_CORNERS, WALK_FOLD: pieces to visit (else 0) */
  box_id target[2];          /* those pieces */
  int found[2];              /* a target was reached and its value enclosed */
  double encl[2][2];         /* WALK_CORNERS: det Dpsi at each target's corner */
  ss_psi_piece_result ps;    /* WALK_FOLD: the target's interval verdict */
  int need;                  /* WALK_ALL: the sign every piece must have (+-1);
                                0 once one does not */
  int tubes;                 /* WALK_ALL: prove the uncovered boxes' tubes too */
  long maxden;               /* the rule's rationals (with the enclosure) */
  ss_status st;              /* an error met in the callback */
  ss_error *err;             /* where it is described */
  ss_psi_tube_cache *tcache; /* WALK_ALL with tubes: the cross-sections met */
  ss_psi_inject *inj;        /* WALK_ALL: the star's boundary gathered */
  int tube_fold;             /* WALK_ALL: a tube proven folded (r->witness) */
} walk;

/* Whether a box of a cell around p lies in p's octant [0,1/2]^3 (in the
 * cell's parameters, p at corner bits pbits): psi's ring leaves it out. */
static int in_octant(const walk *w, int depth, const double origin[3]) {
  if (depth < 1) return 0;
  const double h = ldexp(1.0, -depth);
  for (int a = 0; a < 3; a++) {
    const int hi = (int)((w->pbits >> a) & 1u);
    if (hi ? origin[a] < 0.5 : origin[a] + h > 0.5) return 0;
  }
  return 1;
}

/* Whether box (cell, depth, origin) holds box b (or is it). */
static int holds(size_t cell, int depth, const double origin[3], const box_id *b) {
  if (cell != b->cell || depth > b->depth) return 0;
  const double h = ldexp(1.0, -depth);
  for (int a = 0; a < 3; a++)
    if (b->origin[a] < origin[a] || b->origin[a] >= origin[a] + h) return 0;
  return 1;
}

/* Boxes left out: p's octant, and in a pass with targets every box that
 * holds none of them. */
static int skip_box(size_t cell, int depth, const double origin[3], void *arg) {
  const walk *w = arg;
  if (in_octant(w, depth, origin)) return 1;
  if (!w->ntarget) return 0;
  for (int i = 0; i < w->ntarget; i++)
    if (holds(cell, depth, origin, &w->target[i])) return 0;
  return 1;
}

/* The cell's parameters of parameter t of the box (depth, origin). */
static void to_cell(int depth, const double origin[3], const double t[3], double x[3]) {
  const double h = ldexp(1.0, -depth);
  for (int a = 0; a < 3; a++)
    x[a] = origin[a] + h * t[a];
}

/* det Dpsi at the piece's corner t = 0, from ss_limit_bspline's Jacobian (an
 * evaluation independent of the Bernstein form), in the cell's parameters. */
static double corner_det(const ss_limit_piece *pc) {
  double p[3], J[3][3];
  ss_limit_bspline(pc->net, 0.0, 0.0, 0.0, p, J);
  return ss_dense_det3(J[0], J[1], J[2]) *
         ldexp(1.0, 3 * pc->depth); /* d/dx = 2^depth d/dt, exactly */
}

/* WALK_JUDGE: the piece judged in doubles, counted, its witnesses kept. */
static int judge_piece(const ss_limit_piece *pc, walk *w) {
  ss_psi_result *r = w->r;
  /* a box of depth 0 is a whole cell around p: its ring part is 7/8 */
  const double vol = pc->depth ? ldexp(1.0, -3 * pc->depth) : 0.875;
  if (!pc->net) {
    r->nuncovered++;
    w->vol[3] += vol;
    return 0;
  }
  r->pieces++;
  ss_psi_piece_result ps;
  ss_psi_piece_sign(pc->net, w->o->piece_depth, &ps);
  if (ps.sign == SS_JAC_POSITIVE || ps.sign == SS_JAC_NEGATIVE) {
    const int k = ps.sign == SS_JAC_POSITIVE ? 0 : 1;
    if (k == 0)
      r->npositive++;
    else
      r->nnegative++;
    w->vol[k] += vol;
    /* the witness of each sign: the proven piece's corner with the largest
     * |det Dpsi|, far from rounding (on a mirror plane det Dpsi is 0) */
    const double d = corner_det(pc);
    if (!w->have[k] || fabs(d) > fabs(w->pt[k].det[0])) {
      w->pt[k].cell = pc->cell;
      memcpy(w->pt[k].at, pc->origin, sizeof w->pt[k].at); /* the corner t = 0 */
      w->pt[k].det[0] = w->pt[k].det[1] = d;
      w->ptdepth[k] = pc->depth;
      w->have[k] = 1;
    }
    return 0;
  }
  w->vol[2] += vol;
  if (ps.sign != SS_JAC_FOLDED) {
    r->nundecided++;
    return 0;
  }
  r->nfolded++;
  if (!w->folded) {
    const double sc = ldexp(1.0, 3 * pc->depth);
    for (int i = 0; i < 2; i++) {
      r->witness[i].cell = pc->cell;
      to_cell(pc->depth, pc->origin, ps.where[i], r->witness[i].at);
      r->witness[i].det[0] = ps.det[i][0] * sc;
      r->witness[i].det[1] = ps.det[i][1] * sc;
    }
    w->folded = 1;
    w->fbox =
        (box_id){pc->cell, pc->depth, {pc->origin[0], pc->origin[1], pc->origin[2]}};
  }
  return 0;
}

/* The index of the target that is piece pc (holds it at its own depth), or
 * -1. */
static int target_of(const walk *w, const ss_limit_piece *pc) {
  for (int i = 0; i < w->ntarget; i++)
    if (w->target[i].depth == pc->depth &&
        holds(pc->cell, pc->depth, pc->origin, &w->target[i]))
      return i;
  return -1;
}

/* WALK_ALL at an uncovered box: its tube's sign proven (ss_psi_tube.h), or
 * 0 with r->tube_why set. */
static int prove_tube(const ss_limit_piece *pc, walk *w) {
  ss_psi_result *r = w->r;
  ss_psi_tube_result tr = {0};
  if (!w->tubes || !pc->tube) {
    snprintf(tr.why, sizeof tr.why, "%s",
             w->tubes ? "not the layered structure of an extraordinary edge"
                      : "tubes not asked for");
  } else {
    w->st =
        ss_psi_tube_sign(pc->tube, w->maxden, w->o->piece_depth, w->tcache, &tr, w->err);
    if (w->st) return 0;
  }
  if (tr.sign) {
    r->ntubes++;
    if (tr.layers > r->tube_layers) r->tube_layers = tr.layers;
  } else if (tr.fold && !w->tube_fold) { /* psi folds in the tube: a proven failure */
    w->tube_fold = 1;
    r->tube_fold_layer = tr.fold_layer;
    for (int i = 0; i < 2; i++) {
      r->witness[i] =
          (ss_psi_point){pc->cell, {0, 0, 0}, {0, 0}, 0, {-1, -1, -1}, {0, 0, 0}};
      to_cell(pc->depth, pc->origin, tr.where[i], r->witness[i].at);
      for (int e = 0; e < 2; e++) /* d/dx = 2^depth d/dt, exactly */
        r->witness[i].det[e] = ldexp(tr.det[i][e], 3 * pc->depth);
    }
  }
  if (!tr.sign) {
    snprintf(r->tube_why, sizeof r->tube_why,
             "cell %zu box (%.6g, %.6g, %.6g) of side 2^-%d: %.150s", pc->cell + 1,
             pc->origin[0], pc->origin[1], pc->origin[2], pc->depth, tr.why);
  }
  return tr.sign;
}

/* The proof passes: intervals from the enclosed net of the piece. */
static int prove_piece(const ss_limit_piece *pc, walk *w) {
  if (w->mode == WALK_ALL) {
    ss_psi_piece_result ps;
    if (pc->net) ss_psi_piece_sign_interval(pc->lo, pc->hi, w->o->piece_depth, &ps);
    const int sign = !pc->net                     ? prove_tube(pc, w)
                     : ps.sign == SS_JAC_POSITIVE ? 1
                     : ps.sign == SS_JAC_NEGATIVE ? -1
                                                  : 0;
    if (sign != w->need) w->need = 0;
    if (w->need && !w->st && w->inj)
      w->st = ss_psi_inject_box(w->inj, pc, w->pbits, w->err);
    return w->need == 0 || w->st; /* one piece not proven: stop */
  }
  const int i = target_of(w, pc);
  if (i < 0 || !pc->net) return 0;
  const int sc = 3 * pc->depth; /* d/dx = 2^depth d/dt, exactly */
  if (w->mode == WALK_CORNERS) {
    double clo[SS_PSI_NCOEF], chi[SS_PSI_NCOEF];
    ss_psi_bernstein_det_interval(pc->lo, pc->hi, clo, chi);
    w->encl[i][0] = ldexp(clo[0], sc); /* the corner t = 0's exact value */
    w->encl[i][1] = ldexp(chi[0], sc);
  } else {
    ss_psi_piece_sign_interval(pc->lo, pc->hi, w->o->piece_depth, &w->ps);
    for (int j = 0; j < 2; j++)
      for (int e = 0; e < 2; e++)
        w->ps.det[j][e] = ldexp(w->ps.det[j][e], sc);
  }
  w->found[i] = 1;
  return 0;
}

static int visit(const ss_limit_piece *pc, void *arg) {
  walk *w = arg;
  return w->mode == WALK_JUDGE ? judge_piece(pc, w) : prove_piece(pc, w);
}

/* The verdict from the counts (ss_psi.h); its reason is written later
 * (describe), once the proof passes have run. */
static void decide(walk *w, double ring) {
  ss_psi_result *r = w->r;
  const double pos = w->vol[0] / ring, neg = w->vol[1] / ring;
  r->sign = w->vol[0] > 0.0 || w->vol[1] > 0.0 ? (pos >= neg ? 1 : -1) : 0;
  r->covered = r->sign > 0 ? pos : r->sign < 0 ? neg : 0.0;
  r->opposite = r->sign > 0 ? neg : r->sign < 0 ? pos : 0.0;
  r->doubtful = w->vol[2] / ring;
  r->uncovered = w->vol[3] / ring;
  ss_verdict *v = &r->verdict;
  v->on = SS_ON_PSI;
  v->certified = 0;
  if (w->folded || (w->have[0] && w->have[1])) {
    if (w->have[0] && w->have[1]) { /* rather than a folded piece's corners */
      r->witness[0] = w->pt[0];
      r->witness[1] = w->pt[1];
    }
    r->nwitness = 2;
    v->verdict = SS_FAIL;
  } else if (r->nuncovered == 0 && r->nundecided == 0 && r->pieces > 0) {
    v->verdict = SS_PASS;
  } else {
    v->verdict = SS_UNDECIDED;
  }
}

/* The verdict's reason, with what it rests on. */
static void describe(ss_psi_result *r) {
  ss_verdict *v = &r->verdict;
  const char *how = v->certified  ? " (proven: interval arithmetic on the enclosed basis)"
                    : r->enclosed ? " (double precision; the enclosure did not prove it)"
                                  : " (double precision, not proven)";
  if (v->verdict == SS_FAIL) {
    snprintf(v->reason, sizeof v->reason,
             "psi folds: det Dpsi in [%.6g, %.6g] at cell %zu (%.6g, %.6g, %.6g) and in "
             "[%.6g, %.6g] at cell %zu (%.6g, %.6g, %.6g)%s",
             r->witness[0].det[0], r->witness[0].det[1], r->witness[0].cell,
             r->witness[0].at[0], r->witness[0].at[1], r->witness[0].at[2],
             r->witness[1].det[0], r->witness[1].det[1], r->witness[1].cell,
             r->witness[1].at[0], r->witness[1].at[1], r->witness[1].at[2], how);
    const size_t n = strlen(v->reason);
    if (r->tube_fold_layer >= 0)
      snprintf(v->reason + n, sizeof v->reason - n,
               "; both in the tube round a spoke, its layer %d", r->tube_fold_layer);
  } else if (v->verdict == SS_PASS && r->enclosed && r->ntubes)
    snprintf(
        v->reason, sizeof v->reason,
        "det Dpsi of one sign on all %zu pieces and in the tubes of all %zu boxes "
        "round its spokes (every layer to the spoke: the first %d directly, the rest "
        "by a bound on the edge's smaller modes)%s",
        r->pieces, r->ntubes, r->tube_layers, how);
  else if (v->verdict == SS_PASS && r->enclosed)
    snprintf(v->reason, sizeof v->reason, "det Dpsi of one sign on all %zu pieces%s",
             r->pieces, how);
  else if (v->verdict == SS_PASS)
    v->reason[0] = '\0';
  else
    snprintf(
        v->reason, sizeof v->reason,
        "psi of one sign on %.1f %% of its ring (%zu polynomial pieces); %.1f %% left "
        "uncovered round the spokes at box depth %d, %.1f %% in doubt%s%.240s",
        100.0 * r->covered, r->pieces, 100.0 * r->uncovered, r->maxdepth,
        100.0 * r->doubtful, r->tube_why[0] ? "; a tube not proven: " : "", r->tube_why);
}

/* The rule's weight as an exact rational (ss_exact_rational). */
static int exact_rational(double wt, void *arg, long long *p, long long *q) {
  return ss_exact_rational(wt, *(const long *)arg, p, q) ? 0 : -1;
}

/* Walk the ring of every cell around p (enc: the pieces' enclosures, or
 * NULL); the number of cells around p into *ncentre. */
static ss_status walk_cells(ss_limit *L, const ss_local *M, const ss_limit_enclosure *enc,
                            walk *w, size_t *ncentre, ss_error *err) {
  *ncentre = 0;
  for (size_t c = 0; c < M->ncells; c++) {
    const int j = ss_local_centre_corner(M, c);
    if (j < 0) continue;
    ++*ncentre;
    w->pbits = ss_cube_corner_bits(3, j);
    const ss_status st =
        ss_limit_pieces_tubes(L, c, w->o->maxdepth, enc, w->tubes ? exact_rational : NULL,
                              &w->maxden, skip_box, visit, w, err);
    if (st) return st;
    if (w->st) return w->st;
    if (w->mode == WALK_ALL && w->need == 0) break; /* a piece or tube not proven */
  }
  return SS_OK;
}

/* The rule's weight as the exact path reads it (ss_exact_rational). */
static int exact_weight(double wt, void *arg, double *lo, double *hi) {
  return ss_exact_rational_enclose(wt, *(const long *)arg, lo, hi) ? 0 : -1;
}

/* A failure proven: the double path's two witnesses (corners of pieces of
 * opposite signs) enclosed, else its folded piece's proven again. */
static ss_status prove_fail(ss_limit *L, const ss_local *M, const ss_limit_enclosure *enc,
                            walk *w, ss_error *err) {
  ss_psi_result *r = w->r;
  size_t n;
  ss_status st;
  if (w->have[0] && w->have[1]) {
    w->mode = WALK_CORNERS;
    w->ntarget = 2;
    for (int i = 0; i < 2; i++)
      w->target[i] = (box_id){
          w->pt[i].cell, w->ptdepth[i], {w->pt[i].at[0], w->pt[i].at[1], w->pt[i].at[2]}};
    if ((st = walk_cells(L, M, enc, w, &n, err))) return st;
    if (w->found[0] && w->found[1] && w->encl[0][0] > 0.0 && w->encl[1][1] < 0.0) {
      for (int i = 0; i < 2; i++)
        memcpy(r->witness[i].det, w->encl[i], sizeof w->encl[i]);
      r->verdict.certified = 1;
      return SS_OK;
    }
  }
  if (!w->folded) return SS_OK;
  w->mode = WALK_FOLD;
  w->ntarget = 1;
  w->target[0] = w->fbox;
  w->found[0] = 0;
  if ((st = walk_cells(L, M, enc, w, &n, err))) return st;
  if (!w->found[0] || w->ps.sign != SS_JAC_FOLDED) return SS_OK;
  for (int i = 0; i < 2; i++) {
    r->witness[i].cell = w->fbox.cell;
    to_cell(w->fbox.depth, w->fbox.origin, w->ps.where[i], r->witness[i].at);
    memcpy(r->witness[i].det, w->ps.det[i], sizeof w->ps.det[i]);
  }
  r->verdict.certified = 1;
  return SS_OK;
}

/* The proof passes of a decided double verdict, with the enclosure e. */
static ss_status prove(ss_limit *L, const ss_local *M, const ss_psi_enclosure *e, walk *w,
                       ss_error *err) {
  w->maxden = e->maxden;
  const ss_limit_enclosure enc = {e->lo, e->hi, exact_weight, &w->maxden};
  ss_psi_result *r = w->r;
  r->enclosed = 1;
  if (r->verdict.verdict == SS_FAIL) return prove_fail(L, M, &enc, w, err);
  /* undecided only for the tubes round the spokes: prove them too */
  const int tubes = w->o->tubes && r->verdict.verdict == SS_UNDECIDED &&
                    r->nuncovered > 0 && r->nundecided == 0 && r->nfolded == 0 &&
                    r->sign != 0 && r->opposite == 0.0 && r->pieces > 0;
  if (r->verdict.verdict != SS_PASS && !tubes) return SS_OK;
  w->mode = WALK_ALL;
  w->ntarget = 0;
  w->need = r->sign;
  w->tubes = tubes;
  r->tubes = tubes;
  w->err = err;
  size_t n;
  if (tubes && !(w->tcache = ss_psi_tube_cache_new()))
    return ss_error_nomem(err, "psi tubes");
  if (!(w->inj = ss_psi_inject_new(M, w->o->maxdepth))) {
    ss_psi_tube_cache_free(w->tcache);
    return ss_error_nomem(err, "psi boundary");
  }
  ss_status st = walk_cells(L, M, &enc, w, &n, err);
  ss_psi_tube_cache_free(w->tcache);
  w->tcache = NULL;
  if (!st && w->tube_fold) { /* two proven values of opposite signs in a tube */
    r->verdict.verdict = SS_FAIL;
    r->verdict.certified = 1;
    r->nwitness = 2;
  } else if (!st && w->need != 0) {
    r->verdict.verdict = SS_PASS;
    r->verdict.certified = 1;
    ss_psi_inject_result ir;
    st = ss_psi_inject_degree(w->inj, w->need, &ir, err);
    if (!st) {
      r->inject = ir.decided;
      r->degree = ir.degree;
      r->boundary_squares = ir.squares;
      snprintf(r->inject_why, sizeof r->inject_why, "%s", ir.why);
    }
  }
  ss_psi_inject_free(w->inj);
  w->inj = NULL;
  return st;
}

static ss_psi_point spoke_point(const ss_psi_spoke_sample *q) {
  ss_psi_point pt = {q->cell,
                     {q->at[0], q->at[1], q->at[2]},
                     {q->det_eval, q->det_eval},
                     0,
                     {-1, -1, -1},
                     {0, 0, 0}};
  return pt;
}

/* Fail by spoke sp: its two samples of opposite signs, or (ring's proven
 * point rp) its tube's sign opposite to the ring's. */
static void fail_spoke(ss_psi_result *r, const ss_psi_spoke *sp, const ss_psi_point *rp) {
  char name[16];
  ss_psi_spoke_name(sp->vertex, name);
  r->spoke_vertex = sp->vertex;
  r->verdict.verdict = SS_FAIL;
  r->nwitness = 2;
  if (sp->cls == SS_SPOKE_SIGN_CHANGE) {
    r->witness[0] = spoke_point(&sp->w[0]);
    r->witness[1] = spoke_point(&sp->w[1]);
  } else {
    r->witness[0] = *rp;
    r->witness[1] = spoke_point(&sp->min);
  }
  snprintf(r->verdict.reason, sizeof r->verdict.reason,
           "psi folds %s spoke %s (valence %d): det Dpsi %.6g at cell %zu (%.6g, %.6g, "
           "%.6g) and %.6g at cell %zu (%.6g, %.6g, %.6g) (double precision, evidence "
           "in the tube, not proven)",
           sp->cls == SS_SPOKE_SIGN_CHANGE ? "across" : "in the tube round", name,
           sp->valence, r->witness[0].det[0], r->witness[0].cell, r->witness[0].at[0],
           r->witness[0].at[1], r->witness[0].at[2], r->witness[1].det[0],
           r->witness[1].cell, r->witness[1].at[0], r->witness[1].at[1],
           r->witness[1].at[2]);
}

/* The verdict with the spokes classified (ss_psi.h, "The tubes"). */
int ss_psi_fail_degenerate(ss_psi_result *r, const ss_psi_spokes *sk, const char *points,
                           const char *source) {
  for (size_t i = 0; i < sk->n; i++) {
    const ss_psi_spoke *sp = &sk->spoke[i];
    if (sp->cls != SS_SPOKE_DEGENERATE) continue;
    char name[16];
    ss_psi_spoke_name(sp->vertex, name);
    r->spoke_vertex = sp->vertex;
    r->degenerate = 1;
    r->verdict.verdict = SS_FAIL;
    snprintf(r->verdict.reason, sizeof r->verdict.reason,
             "degenerate on spoke %s (valence %d): det[a' | B] = 0 along it (%zu of %zu "
             "%s below %.0e relative; %zu of %zu spokes degenerate; %sdouble "
             "precision, not proven)",
             name, sp->valence, sp->ndegenerate, sp->nsamples, points,
             SS_PSI_SPOKE_DEGENERATE, sk->ndegenerate, sk->n, source);
    return 1;
  }
  return 0;
}

static void decide_spokes(walk *w, const ss_psi_spokes *sk) {
  ss_psi_result *r = w->r;
  const ss_psi_spoke *bad = NULL;
  for (size_t i = 0; i < sk->n && !bad; i++)
    if (sk->spoke[i].cls == SS_SPOKE_SIGN_CHANGE) bad = &sk->spoke[i];
  for (size_t i = 0; i < sk->n && !bad && r->sign; i++)
    if (sk->spoke[i].cls == SS_SPOKE_ONE_SIGN && sk->spoke[i].sign != r->sign)
      bad = &sk->spoke[i];
  if (bad) {
    fail_spoke(r, bad, &w->pt[r->sign > 0 ? 0 : 1]);
    return;
  }
  if (ss_psi_fail_degenerate(r, sk, "samples", "")) return;
  char name[16];
  for (size_t i = 0; i < sk->n; i++) {
    const ss_psi_spoke *sp = &sk->spoke[i];
    if (sp->ndisagree == 0) continue;
    /* the leading term does not yet rule det Dpsi 2^-12 off the spoke: the
     * tube is not decided by it */
    ss_psi_spoke_name(sp->vertex, name);
    const size_t n = strlen(r->verdict.reason);
    snprintf(r->verdict.reason + n, sizeof r->verdict.reason - n,
             "; spoke %s: det Dpsi 2^-%d off it has the sign opposite to det[a' | B] "
             "det Dchi at %zu of %zu samples: its tube not decided",
             name, SS_PSI_SPOKE_PROBE, sp->ndisagree, sp->nsamples);
    return;
  }
  if (r->nundecided == 0 && r->pieces > 0 && r->sign != 0) {
    r->verdict.verdict = SS_PASS;
    snprintf(r->verdict.reason, sizeof r->verdict.reason,
             "psi's pieces of one sign on %.1f %% of its ring; the tubes round its %zu "
             "spokes (%.1f %%) by evidence: det[a' | B] of the ring's sign at every "
             "sample (double precision, not proven)",
             100.0 * r->covered, sk->n, 100.0 * r->uncovered);
    return;
  }
  const size_t n = strlen(r->verdict.reason);
  snprintf(r->verdict.reason + n, sizeof r->verdict.reason - n,
           "; its %zu spokes of the ring's sign (evidence)", sk->n);
}

/* Classify the spokes when tubes are left and no piece decided a fold. */
static ss_status spokes(ss_limit *L, const ss_local *M, walk *w, ss_error *err) {
  ss_psi_result *r = w->r;
  if (r->nuncovered == 0 || r->verdict.verdict != SS_UNDECIDED) return SS_OK;
  ss_psi_spokes sk;
  ss_error se = {0};
  const ss_status st = ss_psi_spokes_classify(L, M, &sk, &se);
  if (st == SS_ENOMEM) {
    *err = se;
    return st;
  }
  if (st) { /* a run refused (defective, modes not told apart): evidence missing */
    snprintf(r->spoke_why, sizeof r->spoke_why, "spokes not classified: %.170s", se.msg);
    return SS_OK;
  }
  r->spokes = 1;
  r->nspokes = sk.n;
  r->nspoke_one = sk.none;
  r->nspoke_change = sk.nchange;
  r->nspoke_deg = sk.ndegenerate;
  decide_spokes(w, &sk);
  ss_psi_spokes_free(&sk);
  return SS_OK;
}

/* ss_psi_judge, and with e the proof passes. */
static ss_status judge(const ss_scheme *s, const ss_local *M, const double *x,
                       const ss_psi_enclosure *e, const ss_psi_opts *o,
                       ss_psi_result *out, ss_error *err) {
  const double t0 = ss_clock_cpu();
  out->maxdepth = o->maxdepth;
  out->piece_depth = o->piece_depth;
  if (M->dim != 3 || M->cell != SS_HEX) {
    snprintf(out->why, sizeof out->why,
             "psi's pieces are tricubic: this case's cells are not hexahedra");
    return SS_OK;
  }
  ss_limit *L = NULL;
  ss_status st = SS_OK;
  walk w;
  memset(&w, 0, sizeof w);
  w.o = o;
  w.r = out;
  w.mode = WALK_JUDGE;
  ss_error le = {0};
  st = ss_psi_two_ring_limit(s, M, x, &L, &le);
  if (st == SS_EINPUT) { /* not a limit evaluator's scheme: no pieces */
    snprintf(out->why, sizeof out->why, "no polynomial pieces: %.130s", le.msg);
    st = SS_OK;
    goto done;
  }
  if (st) {
    *err = le;
    goto done;
  }
  size_t ncentre;
  if ((st = walk_cells(L, M, NULL, &w, &ncentre, err))) goto done;
  decide(&w, 0.875 * (double)(ncentre ? ncentre : 1));
  double c1 = ss_clock_cpu();
  if (e && (st = prove(L, M, e, &w, err))) goto done;
  ss_clock_lap(&out->prove_seconds, &c1);
  describe(out);
  if ((st = spokes(L, M, &w, err))) goto done; /* the tubes, by evidence */
  ss_clock_lap(&out->spoke_seconds, &c1);
  out->ran = 1;
done:
  ss_limit_free(L);
  out->seconds = ss_clock_cpu() - t0;
  return st;
}

/* The options' and inputs' check shared by both entries. */
static ss_status check(const ss_psi_opts *o, const void *net, ss_psi_result *out,
                       ss_error *err) {
  memset(out, 0, sizeof *out);
  out->verdict = (ss_verdict){SS_UNDECIDED, "", 0, SS_ON_NOTHING};
  out->spoke_vertex = -1;
  out->tube_fold_layer = -1;
  if (o->maxdepth < 1 || o->maxdepth > 8 || o->piece_depth < 0 || o->piece_depth > 8)
    return ss_error_set(err, SS_EINPUT,
                        "psi options out of range: box depth %d (1..8), piece depth %d "
                        "(0..8)",
                        o->maxdepth, o->piece_depth);
  if (!net) return ss_error_set(err, SS_EINPUT, "psi: no net");
  return SS_OK;
}

ss_status ss_psi_judge(const ss_scheme *s, const ss_local *M, const double *x,
                       const ss_psi_opts *o, ss_psi_result *out, ss_error *err) {
  const ss_status st = check(o, x, out, err);
  return st ? st : judge(s, M, x, NULL, o, out, err);
}

ss_status ss_psi_certify(const ss_scheme *s, const ss_local *M, const ss_psi_enclosure *e,
                         const ss_psi_opts *o, ss_psi_result *out, ss_error *err) {
  ss_status st = check(o, e && e->lo && e->hi ? e : NULL, out, err);
  if (st) return st;
  const size_t n = 3 * M->n2;
  for (size_t i = 0; i < n; i++)
    if (!(e->lo[i] <= e->hi[i]) || !isfinite(e->lo[i]) || !isfinite(e->hi[i]))
      return ss_error_set(err, SS_EINPUT,
                          "psi: point %zu's enclosure [%g, %g] is not an interval of "
                          "finite bounds",
                          i / 3 + 1, e->lo[i], e->hi[i]);
  double *x = malloc((n + 1) * sizeof *x);
  if (!x) return ss_error_nomem(err, "psi: net");
  for (size_t i = 0; i < n; i++)
    x[i] = 0.5 * e->lo[i] + 0.5 * e->hi[i]; /* inside: no overflow */
  st = judge(s, M, x, e, o, out, err);
  free(x);
  return st;
}

/* Append text to a verdict's reason, as room allows. */
static void append(ss_verdict *v, const char *text) {
  const size_t n = strlen(v->reason);
  snprintf(v->reason + n, sizeof v->reason - n, "%s%s", n ? "; " : "", text);
}

/* A decided verdict on psi that may decide (proven, or no proof asked for). */
static void apply_decided(const ss_psi_result *r, ss_verdict *reg, ss_verdict *inj) {
  const char *how = r->verdict.certified ? "proven" : "double precision";
  char text[200];
  if (r->verdict.verdict == SS_PASS) {
    *reg = r->verdict;
    if (r->inject) { /* the winding number on the boundary decided (proven) */
      snprintf(text, sizeof text, "the control net: %s%s%.150s",
               ss_verdict_name(inj->verdict), inj->reason[0] ? ": " : "", inj->reason);
      inj->verdict = r->inject > 0 ? SS_PASS : SS_FAIL;
      inj->on = SS_ON_PSI;
      inj->certified = 1;
      snprintf(inj->reason, sizeof inj->reason, "%s", r->inject_why);
      append(inj, text);
    }
    return;
  }
  if (reg->on == SS_ON_PSI && reg->verdict == SS_FAIL) {
    /* psi o sigma = psi failed it already, about psi (and perhaps proven):
     * that verdict stays, the witnesses added (and its proof, if it had none) */
    if (r->degenerate)
      snprintf(text, sizeof text, "psi %.190s", r->verdict.reason);
    else
      snprintf(text, sizeof text, "psi's %s agree: det Dpsi %.4g and %.4g (%s)",
               r->by_masks ? "regular vertices" : "pieces", r->witness[0].det[0],
               r->witness[1].det[0], how);
    append(reg, text);
    if (r->verdict.certified) {
      reg->certified = 1;
      if (inj->verdict == SS_FAIL) inj->certified = 1;
    }
    return;
  }
  if (r->degenerate) {
    /* not a fold: regularity fails (det Dpsi = 0 on the spoke), injectivity
     * is the net's */
    *reg = r->verdict;
    return;
  }
  /* what the net's verdict said, kept after psi's (an unproven failure of
   * the net is undecided by now, "not certified: ...") */
  char was[200];
  if (reg->verdict == SS_FAIL)
    was[0] = '\0';
  else
    snprintf(was, sizeof was, "the control net: %s%s%.150s",
             ss_verdict_name(reg->verdict), reg->reason[0] ? ": " : "", reg->reason);
  *reg = r->verdict;
  if (was[0]) append(reg, was);
  *inj = r->verdict;
  snprintf(inj->reason, sizeof inj->reason,
           "psi folds (det Dpsi takes both signs on its connected ring) (%s)", how);
}

void ss_psi_apply(const ss_psi_result *r, int certify, ss_verdict *reg, ss_verdict *inj) {
  if (!r->ran) return;
  const ss_verdict_kind k = r->verdict.verdict;
  if (k != SS_UNDECIDED && (r->verdict.certified || !certify)) {
    apply_decided(r, reg, inj);
    return;
  }
  /* psi undecided, or decided in doubles where a proof was asked for */
  if (reg->on == SS_ON_PSI) return; /* psi o sigma = psi: already about psi */
  if (reg->verdict == SS_PASS) return;
  char text[200];
  if (k == SS_FAIL && !r->degenerate)
    snprintf(text, sizeof text,
             "psi folds in double precision (det Dpsi %.4g and %.4g), not proven",
             r->witness[0].det[0], r->witness[1].det[0]);
  else if (k != SS_UNDECIDED)
    snprintf(text, sizeof text, "psi %s, not proven: %.150s", ss_verdict_name(k),
             r->verdict.reason);
  else if (r->by_spokes)
    snprintf(text, sizeof text, "psi by its spokes: %.180s", r->verdict.reason);
  else
    snprintf(text, sizeof text,
             "psi: of one sign on %.1f %% of its ring, no fold found on its pieces",
             100.0 * r->covered);
  if (reg->verdict == SS_FAIL) {
    /* a fold of the net that psi does not (provably) show */
    if (certify)
      ss_verdict_unproven(reg, text);
    else {
      reg->certified = 0;
      append(reg, text);
    }
  } else {
    append(reg, text);
  }
}
