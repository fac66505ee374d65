/* ss_scheme_base.c — the scheme object: allocation with its parts, the
 * accessors, the dropping of cells it does not take, and the vertex lists of messages.
 * Below every scheme file (ss_scheme_<name>.c builds its scheme with ss_scheme_alloc) and
 * below the registry and driver in ss_scheme.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "ss_scheme_impl.h"

ss_status ss_scheme_alloc(const char *name, ss_split_kind split, unsigned accepts,
                          ss_rule_fn rule, ss_scheme **out, ss_error *err) {
  *out = NULL;
  ss_scheme *s = calloc(1, sizeof *s);
  if (!s) return ss_error_nomem(err, "scheme");
  snprintf(s->name, sizeof s->name, "%s", name);
  s->split = split;
  s->accepts = accepts;
  s->rule = rule;
  s->reach = 1;
  s->step_split = split;
  s->step_passes = 1;
  s->ring_depth = 1;
  *out = s;
  return SS_OK;
}

void ss_scheme_free(ss_scheme *s) {
  if (!s) return;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    free(s->vtab[t]);
    free(s->vrow[t]);
  }
  free(s->ptab);
  free(s->paxis);
  free(s);
}

int ss_scheme_weights_rational(const ss_scheme *s) {
  return !s->irrational;
}

ss_status ss_scheme_set_loop_c(ss_scheme *s, ss_loop_c c, ss_error *err) {
  if (!s->loop_c_choice)
    return ss_error_set(err, SS_EINPUT,
                        "scheme %s has no choice of Loop's vertex weight (boxspline and "
                        "boxspline-avg have, figure 14 of the box-spline paper)",
                        s->name);
  s->loop_c = c;
  return SS_OK;
}

ss_status ss_scheme_set_adapt(ss_scheme *s, const ss_adapt *a, ss_error *err) {
  if (s->split != SS_SPLIT_BISECT)
    return ss_error_set(err, SS_EINPUT,
                        "scheme %s does not refine adaptively (quasi48 does: its "
                        "bisection keeps the mesh conforming)",
                        s->name);
  if (!a) {
    s->adaptive = 0;
    return SS_OK;
  }
  for (int r = 0; a->use_box && r < 3; r++)
    if (!isfinite(a->box[r]) || !isfinite(a->box[r + 3]) || a->box[r] > a->box[r + 3])
      return ss_error_set(err, SS_EINPUT,
                          "adaptive box: coordinate %d runs from %g to %g (finite, lower "
                          "first)",
                          r + 1, a->box[r], a->box[r + 3]);
  if (a->use_angle && !(a->max_angle >= 0.0 && a->max_angle <= M_PI))
    return ss_error_set(err, SS_EINPUT,
                        "adaptive curvature angle %g rad: expected an angle in 0..pi",
                        a->max_angle);
  if (!(a->max_edge >= 0.0) || !isfinite(a->max_edge))
    return ss_error_set(err, SS_EINPUT,
                        "adaptive edge length %g: expected a finite length >= 0",
                        a->max_edge);
  s->adapt = *a;
  s->adaptive = 1;
  return SS_OK;
}

ss_status ss_scheme_set_boundary(ss_scheme *s, ss_boundary b, ss_error *err) {
  if (s->split != SS_SPLIT_BISECT)
    return ss_error_set(err, SS_EINPUT,
                        "scheme %s has no choice of boundary rule (quasi48 has: "
                        "normal, smooth or fixed)",
                        s->name);
  if (b != SS_BOUNDARY_NORMAL && b != SS_BOUNDARY_SMOOTH && b != SS_BOUNDARY_FIXED)
    return ss_error_set(err, SS_EINPUT,
                        "boundary rule %d: expected normal (0), smooth (1) or fixed (2)",
                        (int)b);
  s->boundary = b;
  return SS_OK;
}

int ss_scheme_volume_weights_rational(const ss_scheme *s) {
  return s->ptab ? !s->irrational_volume : !s->irrational;
}

int ss_scheme_reach(const ss_scheme *s) {
  return s->reach;
}

int ss_scheme_ring_depth(const ss_scheme *s) {
  return s->ring_depth;
}

int ss_scheme_reads_diagonals(const ss_scheme *s) {
  return s->diagonals;
}

const char *ss_scheme_name(const ss_scheme *s) {
  return s->name;
}

ss_split_kind ss_scheme_split_kind(const ss_scheme *s) {
  return s->split;
}

int ss_scheme_accepts(const ss_scheme *s, ss_cell_type t) {
  return (int)((s->accepts >> t) & 1u);
}

size_t ss_scheme_drop_lower(const ss_scheme *s, ss_cx *cx,
                            size_t dropped[SS_NCELLTYPES]) {
  const int top = ss_cx_topdim(cx);
  int keep = 0; /* a top cell the scheme refuses: nothing dropped */
  for (int t = 0; t < SS_NCELLTYPES; t++)
    keep |= cx->nc[t] && ss_cell_dim((ss_cell_type)t) == top &&
            !ss_scheme_accepts(s, (ss_cell_type)t);
  size_t total = 0;
  for (int t = 0; t < SS_NCELLTYPES; t++) {
    size_t n = 0;
    if (!keep && !ss_scheme_accepts(s, (ss_cell_type)t) &&
        ss_cell_dim((ss_cell_type)t) < top) {
      n = cx->nc[t];
      cx->nc[t] = 0; /* the slots stay allocated: ss_cx_free frees them */
    }
    if (dropped) dropped[t] = n;
    total += n;
  }
  return total;
}

void ss_scheme_list_vertices(const ss_idx *v, size_t n, char *buf, size_t cap) {
  size_t len = 0;
  buf[0] = '\0';
  for (size_t j = 0; j < n && len < cap; j++) {
    int w = snprintf(buf + len, cap - len, "%s%lu",
                     j == 0       ? ""
                     : j + 1 == n ? " and "
                                  : ", ",
                     (unsigned long)v[j] + 1);
    if (w < 0) break;
    len += (size_t)w;
  }
}
