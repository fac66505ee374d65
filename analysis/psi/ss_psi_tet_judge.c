/* ss_psi_tet_judge.c — psi of a tet/oct vertex case judged by its spokes
 * where the control net leaves regularity undecided (ss_psi_tet.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_clock.h"
#include "ss_jac.h"
#include "ss_psi_mask.h"
#include "ss_psi_tet.h"

/* Whether a coordinate lies on a spoke (one nonzero entry). */
static int on_spoke(const ss_star_coord *c) {
  return c->n == 1 && c->val[0] > 0;
}

/* Whether cell c of ring level r lies in Omega_{w+1}: every corner's
 * coordinates sum to at most 2^r (Omega_w: 2^(r+1), conical coordinates in
 * the level's units). */
static int inner(const ss_local_ring *R, size_t c, int r) {
  const int nv = ss_cell_nverts(R->ctype[c]);
  for (int j = 0; j < nv; j++) {
    const ss_star_coord *q = R->coord + R->corner[c * SS_MAXCELLVERTS + (size_t)j];
    long sum = 0;
    for (int i = 0; i < q->n; i++)
      sum += q->val[i];
    if (sum > (1L << r)) return 0;
  }
  return 1;
}

/* The cells of ring level `last` of M (net x pushed there) not of the
 * ring's sign, into *bad, and how many of them have no corner on a spoke,
 * into *off.  0, or -1 out of memory. */
static int bad_cells(const ss_local *M, const double *x, int last, int sign, size_t *bad,
                     size_t *off) {
  *bad = *off = 0;
  const double *prev = x;
  double *net = NULL;
  for (int r = 0; r <= last; r++) {
    const ss_local_ring *R = M->ring + r;
    double *next = malloc((3 * R->nv + 1) * sizeof *next);
    if (!next) {
      free(net);
      return -1;
    }
    ss_local_ring_push(R, prev, 3, next);
    free(net);
    net = next;
    prev = net;
  }
  const ss_local_ring *R = M->ring + last;
  const ss_jac_sign want = sign > 0 ? SS_JAC_POSITIVE : SS_JAC_NEGATIVE;
  for (size_t c = 0; c < R->ncells; c++) {
    const int nv = ss_cell_nverts(R->ctype[c]);
    double y[3 * SS_MAXCELLVERTS];
    int touches = 0;
    for (int j = 0; j < nv; j++) {
      const size_t q = R->corner[c * SS_MAXCELLVERTS + (size_t)j];
      memcpy(y + 3 * j, net + 3 * q, 3 * sizeof *y);
      touches |= on_spoke(R->coord + q);
    }
    if (M->whole && inner(R, c, last)) continue; /* inside Omega_{w+1} */
    ss_jac_result jr;
    ss_jac_cell(R->ctype[c], y, 3, SS_JAC_DEPTH, &jr);
    if (jr.sign == want) continue;
    (*bad)++;
    *off += !touches;
  }
  free(net);
  return 0;
}

static ss_psi_point point_of(const ss_psi_spoke_sample *q) {
  ss_psi_point pt = {
      q->cell, {q->at[0], q->at[1], q->at[2]}, {q->s, q->s}, 0, {-1, -1, -1}, {0, 0, 0}};
  return pt;
}

/* Fail by spoke sp: its two points of opposite signs, or its point of
 * least |s| against ring, a point of a spoke of the ring's sign (NULL: none). */
static void fail_spoke(ss_psi_result *r, const ss_psi_spoke *sp,
                       const ss_psi_spoke_sample *ring) {
  char name[16];
  ss_psi_spoke_name(sp->vertex, name);
  r->spoke_vertex = sp->vertex;
  r->verdict.verdict = SS_FAIL;
  r->nwitness = ring || sp->cls == SS_SPOKE_SIGN_CHANGE ? 2 : 1;
  if (sp->cls == SS_SPOKE_SIGN_CHANGE) {
    r->witness[0] = point_of(&sp->w[0]);
    r->witness[1] = point_of(&sp->w[1]);
  } else {
    r->witness[0] = point_of(&sp->min);
    if (ring) r->witness[1] = point_of(ring);
  }
  snprintf(
      r->verdict.reason, sizeof r->verdict.reason,
      "psi folds %s spoke %s (valence %d): the spoke coefficient s = sigma "
      "det[a' | B] (the sign of det Dpsi in the tube) is %.6g at x0 = %.4g%s%.6g at "
      "x0 = %.4g%s (the edge case's modes on the ring's points; double precision, "
      "evidence, not proven)",
      sp->cls == SS_SPOKE_SIGN_CHANGE ? "across" : "in the tube round", name, sp->valence,
      r->witness[0].det[0], sp->cls == SS_SPOKE_SIGN_CHANGE ? sp->w[0].x0 : sp->min.x0,
      r->nwitness == 2 ? " and " : "", r->nwitness == 2 ? r->witness[1].det[0] : 0.0,
      r->nwitness == 2 ? (sp->cls == SS_SPOKE_SIGN_CHANGE ? sp->w[1].x0 : ring->x0) : 0.0,
      sp->cls == SS_SPOKE_SIGN_CHANGE ? "" : " on a spoke of the ring's sign");
}

/* The usable points of all spokes. */
static size_t points(const ss_psi_spokes *sk) {
  size_t n = 0;
  for (size_t i = 0; i < sk->n; i++)
    n += sk->spoke[i].nsamples;
  return n;
}

/* The verdict from the classified spokes sk (the ring's sign r->sign; off:
 * bad cells of the net away from every spoke; skipped: spoke points not
 * usable). */
static void decide(ss_psi_result *r, const ss_psi_spokes *sk, int level, size_t bad,
                   size_t off, size_t skipped) {
  const ss_psi_spoke *flip = NULL, *ring = NULL;
  size_t empty = 0;
  for (size_t i = 0; i < sk->n; i++) {
    const ss_psi_spoke *sp = &sk->spoke[i];
    if (sp->cls == SS_SPOKE_SIGN_CHANGE && !flip) flip = sp;
    if (sp->cls == SS_SPOKE_ONE_SIGN && sp->sign == r->sign && !ring) ring = sp;
    empty += (int)sp->cls < 0;
  }
  for (size_t i = 0; i < sk->n && !flip; i++)
    if (sk->spoke[i].cls == SS_SPOKE_ONE_SIGN && sk->spoke[i].sign != r->sign)
      flip = &sk->spoke[i];
  if (flip) {
    fail_spoke(r, flip, ring ? &ring->min : NULL);
    return;
  }
  if (ss_psi_fail_degenerate(r, sk, "points",
                             "the edge case's modes on the ring's points, "))
    return;
  if (empty || off) {
    snprintf(r->verdict.reason, sizeof r->verdict.reason,
             "the spokes do not decide: %zu of the net's %zu bad cells on ring level %d "
             "away from every spoke, %zu of %zu spokes without a usable point (%zu "
             "points skipped)",
             off, bad, level, empty, sk->n, skipped);
    return;
  }
  r->verdict.verdict = SS_PASS;
  snprintf(
      r->verdict.reason, sizeof r->verdict.reason,
      "by evidence on the spokes: the net's %zu bad cells on ring level %d all touch "
      "a spoke, and the spoke coefficient sigma det[a' | B] has the ring's sign at "
      "every usable point of its %zu spokes (%zu points; the edge case's modes on "
      "the ring's points; double precision, not proven)",
      bad, level, sk->n, points(sk));
}

/* Fail by the tangent masks' witnesses (ss_psi_mask.h), proven or not. */
static void fail_masks(ss_psi_result *r, const ss_local *M, const ss_psi_mask_result *m) {
  r->verdict.verdict = SS_FAIL;
  r->verdict.certified = m->proven;
  r->by_masks = 1;
  r->enclosed = m->enclosed;
  r->nregular = m->judged;
  r->nregular_pos = m->positive;
  r->nregular_neg = m->negative;
  r->nwitness = 2;
  r->witness[0] = ss_psi_mask_point_of(M, &m->wpos);
  r->witness[1] = ss_psi_mask_point_of(M, &m->wneg);
  if (m->proven)
    snprintf(r->verdict.reason, sizeof r->verdict.reason,
             "psi folds: det Dpsi at two regular vertices of the ring, read with the "
             "regular lattice's tangent masks, is in [%.6g, %.6g] and in [%.6g, %.6g] "
             "(of %zu regular vertices %zu positive, %zu negative; proven: exact masks, "
             "the exact basis's enclosure pushed through the ring in interval "
             "arithmetic)",
             m->wpos.lo, m->wpos.hi, m->wneg.lo, m->wneg.hi, m->judged, m->positive,
             m->negative);
  else
    snprintf(r->verdict.reason, sizeof r->verdict.reason,
             "psi folds: det Dpsi at two regular vertices of the ring, read with the "
             "regular lattice's tangent masks, is %.6g and %.6g (of %zu regular vertices "
             "%zu positive, %zu negative; double precision)",
             m->wpos.det, m->wneg.det, m->judged, m->positive, m->negative);
}

/* M again with every ring level whole (SS_LOCAL_MAXRING of them, every cell
 * of Omega_w: the spokes' points lie on levels 1..3, and round the whole
 * spoke): *deep, a new extraction whose S and labels must be M's (else
 * SS_EINTERNAL). */
static ss_status deepest(const ss_scheme *s, const ss_case *c, const ss_local *M,
                         ss_local **deep, ss_error *err) {
  ss_local_opts o = ss_local_defaults();
  o.nring = SS_LOCAL_MAXRING;
  o.whole = 1;
  ss_status st = ss_local_new_opts(s, c, &o, deep, err);
  if (!st && ((*deep)->n2 != M->n2 ||
              memcmp((*deep)->label, M->label, M->n2 * sizeof *M->label))) {
    ss_local_free(*deep);
    *deep = NULL;
    st = ss_error_set(err, SS_EINTERNAL, "tet spokes: the deeper ring's labels differ");
  }
  return st;
}

ss_status ss_psi_tet_judge(const ss_scheme *s, const ss_case *c, const ss_local *M,
                           const double *x, const ss_psi_enclosure *e,
                           const ss_regularity *reg, ss_psi_result *out, ss_error *err) {
  const double t0 = ss_clock_cpu();
  memset(out, 0, sizeof *out);
  out->verdict = (ss_verdict){SS_UNDECIDED, "", 0, SS_ON_PSI};
  out->spoke_vertex = -1;
  if (c->kind != SS_CASE_VERTEX || M->cell != SS_TET || M->dim != 3) {
    snprintf(out->why, sizeof out->why, "not a tet vertex case");
    return SS_OK;
  }
  if (reg->verdict.verdict == SS_PASS) {
    snprintf(out->why, sizeof out->why, "the control net passes: psi is not needed");
    return SS_OK;
  }
  ss_local *deep = NULL;
  ss_status st = deepest(s, c, M, &deep, err);
  if (st) return st;
  M = deep;
  /* the regular vertices first: a fold of psi there decides (proven with e) */
  ss_psi_mask_result mr;
  st = e ? ss_psi_mask_certify(M, e, &mr, err) : ss_psi_mask_judge(M, x, M->n2, &mr, err);
  if (st) {
    ss_local_free(deep);
    return st;
  }
  if (mr.wpos.level >= 0 && mr.wneg.level >= 0 && (!e || mr.proven)) {
    out->ran = 1;
    out->sign = reg->sign;
    fail_masks(out, M, &mr);
    ss_local_free(deep);
    out->seconds = ss_clock_cpu() - t0;
    return SS_OK;
  }
  if (strcmp(ss_scheme_name(s), "tetoct") != 0) {
    /* boxspline reads major diagonals (round a spoke the vertex star's need
     * not be the edge case's); boxspline-avg's split adds octahedron centres
     * and is not checked against its edge cases (tests/psi/test_psi_spoke_tet.c
     * checks tetoct's label map).  The regular vertices above need no edge
     * case: their masks are read from the ring's own rows. */
    ss_local_free(deep);
    snprintf(out->why, sizeof out->why,
             "the regular vertices show no fold of psi, and the spokes are matched to "
             "the edge cases for tetoct only, not %s",
             ss_scheme_name(s));
    return SS_OK;
  }
  if (reg->verdict.verdict != SS_UNDECIDED || reg->sign == 0 || reg->nlevels < 1 ||
      reg->nlevels > M->nring) {
    ss_local_free(deep);
    snprintf(out->why, sizeof out->why,
             "the control net decides (or has no ring sign), and the regular vertices "
             "show no fold of psi: the spokes are not needed");
    return SS_OK;
  }
  const int level = M->nring - 1;
  size_t bad, off, skipped = 0;
  if (bad_cells(M, x, level, reg->sign, &bad, &off)) {
    ss_local_free(deep);
    return ss_error_nomem(err, "tet spokes: the net's cells");
  }
  ss_psi_spokes sk;
  ss_error se = {0};
  st = ss_psi_tet_spokes_classify(s, M, c->link, x, &sk, &skipped, &se);
  ss_local_free(deep);
  if (st == SS_ENOMEM) {
    *err = se;
    return st;
  }
  out->ran = 1;
  out->by_spokes = 1;
  out->sign = reg->sign;
  if (st) {
    snprintf(out->spoke_why, sizeof out->spoke_why, "spokes not classified: %.170s",
             se.msg);
    snprintf(out->verdict.reason, sizeof out->verdict.reason, "%s", out->spoke_why);
  } else {
    out->spokes = 1;
    out->nspokes = sk.n;
    out->nspoke_one = sk.none;
    out->nspoke_change = sk.nchange;
    out->nspoke_deg = sk.ndegenerate;
    decide(out, &sk, level, bad, off, skipped);
    ss_psi_spokes_free(&sk);
  }
  out->seconds = ss_clock_cpu() - t0;
  return SS_OK;
}
