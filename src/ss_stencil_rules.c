/* ss_stencil_rules.c — the rule sections of stencil files: the points
 * family's [PLACE.POINT] and the neighbours family's [vertex], [edge],
 * [centre], [boundary.vertex], [boundary.edge] (ss_stencil.h), read into
 * valence tables and built into schemes (ss_scheme_points.c,
 * ss_scheme_boxspline.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_stencil_impl.h"

/* The points family: [PLACE.POINT], keys the averages up to the place's
 * dimension. */
static const char *const place_names[SS_PTS_PLACES] = {"volume", "surface", "crease"};
static const char *const dim_names[4] = {"vertex", "edge", "face", "cell"};
static const int place_top[SS_PTS_PLACES] = {3, 2, 1}; /* dimension averaged over */
/* [volume.axis]: a vertex on an extraordinary edge (ss_points.axis). */
static const char *const axis_keys[SS_AXIS_KEYS] = {"vertex", "along", "across",
                                                    "edge",   "face",  "cell"};

/* The neighbours family: sections 12.. and their keys. */
static const char *const nb_names[SS_NB_RULES] = {"vertex", "edge", "centre",
                                                  "boundary.vertex", "boundary.edge"};
static const char *const nb_keys[SS_NB_RULES][2] = {{"self", "rho"},
                                                    {"ends", "rho"},
                                                    {"diagonal", "equator"},
                                                    {"self", "ring"},
                                                    {"ends", "opposite"}};

/* Section i's name into buf and its keys (*nk of them) into keys. */
static void section_of(int i, char *buf, size_t cap, const char **keys, int *nk) {
  if (i == RSEC_AXIS) {
    snprintf(buf, cap, "volume.axis");
    *nk = SS_AXIS_KEYS;
    for (int k = 0; k < *nk; k++)
      keys[k] = axis_keys[k];
    return;
  }
  if (i < 12) {
    const int p = i / 4, d = i % 4;
    snprintf(buf, cap, "%s.%s", place_names[p], dim_names[d]);
    *nk = place_top[p] + 1;
    for (int k = 0; k < *nk; k++)
      keys[k] = dim_names[k];
    return;
  }
  snprintf(buf, cap, "%s", nb_names[i - 12]);
  *nk = 2;
  keys[0] = nb_keys[i - 12][0];
  keys[1] = nb_keys[i - 12][1];
}

/* The rule section named section: its index, -1 for none, -2 for a points
 * place with an unknown point (R->msg set). */
static int section_index(reader *R, const char *section) {
  for (int j = 0; j < SS_NB_RULES; j++)
    if (!strcmp(section, nb_names[j])) return 12 + j;
  if (!strcmp(section, "volume.axis")) return RSEC_AXIS;
  for (int p = 0; p < SS_PTS_PLACES; p++) {
    const size_t l = strlen(place_names[p]);
    if (strncmp(section, place_names[p], l) || section[l] != '.') continue;
    for (int d = 0; d <= place_top[p]; d++)
      if (!strcmp(section + l + 1, dim_names[d])) return p * 4 + d;
    snprintf(R->msg, sizeof R->msg,
             "[%.64s]: unknown point '%.32s' (known on a %s: vertex%s%s%s%s)", section,
             section + l + 1, place_names[p], place_top[p] > 0 ? ", edge" : "",
             place_top[p] > 1 ? ", face" : "", place_top[p] > 2 ? ", cell" : "",
             p == SS_PTS_VOLUME ? ", axis" : "");
    return -2;
  }
  return -1;
}

int ss_stencil_rule_key(reader *R, const char *section, const char *key,
                        const char *value) {
  const int i = section_index(R, section);
  if (i == -1) return -1;
  if (i == -2) return 0;
  if (!R->has_rs[i]++) R->rs_order[R->nrs++] = i;
  char name[32], base[64];
  const char *keys[RKEYS];
  int nk = 0, k = -1;
  long at = 0;
  section_of(i, name, sizeof name, keys, &nk);
  const int bad_at = ss_stencil_key_at(key, base, sizeof base, &at);
  for (int j = 0; j < nk && !bad_at; j++)
    if (!strcmp(base, keys[j])) k = j;
  if (k < 0 && i < 12 && (!strcmp(base, "along") || !strcmp(base, "across"))) {
    snprintf(R->msg, sizeof R->msg,
             "[%.64s]: average '%.64s' is defined only at a vertex on an extraordinary "
             "edge, in [volume.axis]",
             section, key);
    return 0;
  }
  if (k < 0) {
    char known[64] = "";
    for (int j = 0; j < nk; j++)
      snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", j ? ", " : "",
               keys[j]);
    snprintf(R->msg, sizeof R->msg, "[%.64s]: %s '%.64s' is unknown (known: %s)", section,
             i < 12 ? "average" : "key", key, known);
    return 0;
  }
  const int given = (int)(R->rgiven[i] >> k & 1u);
  if (!at && given) {
    snprintf(R->msg, sizeof R->msg, "[%.64s] %.64s is given twice", section, key);
    return 0;
  }
  slot *dst = ss_stencil_slot_for(R, &R->rs[i][k], given, at, section, key);
  if (!dst) return 0;
  const int ok = ss_stencil_weight_key(R, section, key, value, dst);
  if (ok && !at) R->rgiven[i] |= 1u << k;
  return ok;
}

/* Check the sum of a section's weights at n: exactly when all are rational
 * there, else within 1e-12 (*all_q = 0 then). */
static ss_status rules_sum(const weight_values *w, unsigned given, long n, int varies,
                           const char *where, const char *sec, int line, int *all_q,
                           ss_error *err) {
  char at[48] = "";
  if (varies) snprintf(at, sizeof at, " at n = %ld", n);
  int exact = 1, overflow = 0;
  double d = 0.0;
  rational q = {0, 1};
  for (int k = 0; k < RKEYS; k++)
    if (given >> k & 1u) {
      exact &= w[k].exact[n];
      d += w[k].d[n];
      overflow |= w[k].exact[n] && ss_stencil_add_scaled(&q, 1, w[k].q[n]);
    }
  if (!exact) *all_q = 0;
  if (exact && overflow)
    return ss_error_set(err, SS_EINPUT,
                        "%s:%d: [%s]: weights too large to sum exactly in 64 bits%s",
                        where, line, sec, at);
  if (exact && q.num != q.den)
    return ss_error_set(err, SS_EINPUT,
                        "%s:%d: [%s]: the weights sum to %lld/%lld%s, not 1", where, line,
                        sec, q.num, q.den, at);
  if (!exact && !(fabs(d - 1.0) <= 1e-12))
    return ss_error_set(err, SS_EINPUT,
                        "%s:%d: [%s]: the weights sum to %.17g%s, not 1 (within 1e-12: "
                        "some weight is not rational)",
                        where, line, sec, d, at);
  return SS_OK;
}

/* Whether a file of family fam and split takes section i (1) and needs it
 * (2): points on hex meshes take every point up to the place's dimension
 * (the cell and the surface's face points are centroids unless given), on
 * triangle surfaces no volume and no face points (Loop's split makes none);
 * the neighbours family takes and needs its five sections. */
static int section_role(int fam, int hexes, int i) {
  if (i == RSEC_AXIS) return fam == FAM_POINTS && hexes;
  if (i >= 12) return fam == FAM_NEIGHBOURS ? 2 : 0;
  const int p = i / 4, d = i % 4;
  if (fam != FAM_POINTS || (!hexes && (p == SS_PTS_VOLUME || d == 2))) return 0;
  if (p == SS_PTS_VOLUME) return d <= 2 ? 2 : 1;
  if (p == SS_PTS_SURFACE) return d <= 1 ? 2 : 1;
  return d == 0 ? 2 : 1;
}

/* Section i's weights at every valence into tabs[k] (malloc'd, for the keys
 * given), the keys in the file's order, the sums checked. */
static ss_status section_tables(const reader *R, int i, const char *where,
                                const char *text, weight_values *w, double **tabs,
                                int *all_q, ss_error *err) {
  char sec[32];
  const char *keys[RKEYS];
  int nkeys = 0, varies = 0, ks[RKEYS], nk = 0;
  section_of(i, sec, sizeof sec, keys, &nkeys);
  const int line = ss_stencil_section_line(text, sec);
  for (int k = 0; k < RKEYS; k++) /* the keys in the file's order */
    if (R->rgiven[i] >> k & 1u) {
      int j = nk++;
      for (; j > 0 && R->rs[i][ks[j - 1]].keyline > R->rs[i][k].keyline; j--)
        ks[j] = ks[j - 1];
      ks[j] = k;
    }
  ss_status st = SS_OK;
  for (int j = 0; j < nk && !st; j++)
    st = ss_stencil_weight_at(&R->rs[i][ks[j]], keys[ks[j]], where, sec, w + ks[j],
                              &varies, err);
  for (long n = 1; !st && n <= (varies ? SS_AVG_NMAX : 1); n++)
    st = rules_sum(w, R->rgiven[i], n, varies, where, sec, line, all_q, err);
  for (int k = 0; k < RKEYS && !st; k++) {
    if (!(R->rgiven[i] >> k & 1u)) continue;
    if (!(tabs[k] = malloc(sizeof w[k].d))) return ss_error_nomem(err, "stencil weights");
    memcpy(tabs[k], w[k].d, sizeof w[k].d);
  }
  return st;
}

/* The sections seen that the family and split do not take, the masks of
 * a rule family, a neighbours file not on the tet/oct split. */
static ss_status check_sections(const reader *R, const char *text, const char *where,
                                int sl, ss_error *err) {
  static const char *const fam[] = {"averaging", "points", "neighbours"};
  const int hexes = R->split == SS_SPLIT_MULTILINEAR;
  char sec[32];
  const char *keys[RKEYS];
  int nk;
  static const char *const mask[SS_NCELLTYPES] = {
      [SS_SEGMENT] = "segment", [SS_TRIANGLE] = "triangle", [SS_QUAD] = "quad",
      [SS_TET] = "tet",         [SS_HEX] = "hex",           [SS_OCT] = "oct"};
  for (int t = 0; t < SS_NCELLTYPES && R->family != FAM_AVERAGING; t++)
    if (R->has_mask[t] && mask[t]) {
      snprintf(sec, sizeof sec, "mask.%s", mask[t]);
      return ss_error_set(err, SS_EINPUT,
                          "%s:%d: [%s]: family %s takes no masks (its sections are "
                          "%s)",
                          where, ss_stencil_section_line(text, sec), sec, fam[R->family],
                          R->family == FAM_POINTS ? "[volume|surface|crease.POINT]"
                                                  : "[vertex], [edge], [centre], "
                                                    "[boundary.vertex|edge]");
    }
  if (R->family == FAM_NEIGHBOURS && hexes)
    return ss_error_set(err, SS_EINPUT,
                        "%s:%d: family neighbours takes split tetoct (the box-spline "
                        "rules' neighbourhoods)",
                        where, sl);
  for (int j = 0; j < R->nrs; j++) {
    const int i = R->rs_order[j];
    section_of(i, sec, sizeof sec, keys, &nk);
    if (section_role(R->family, hexes, i)) continue;
    const int other = i < 12 || i == RSEC_AXIS ? FAM_POINTS : FAM_NEIGHBOURS;
    if (R->family != other)
      return ss_error_set(err, SS_EINPUT, "%s:%d: [%s]: a section of family %s, not %s",
                          where, ss_stencil_section_line(text, sec), sec, fam[other],
                          fam[R->family]);
    return ss_error_set(err, SS_EINPUT, "%s:%d: [%s]: this split makes no such point",
                        where, ss_stencil_section_line(text, sec), sec);
  }
  return SS_OK;
}

ss_status ss_stencil_build_rules(const reader *R, const char *text, const char *where,
                                 int sl, ss_scheme **out, ss_error *err) {
  ss_status st = check_sections(R, text, where, sl, err);
  if (st) return st;
  const int hexes = R->split == SS_SPLIT_MULTILINEAR;
  weight_values *w = malloc(RKEYS * sizeof *w);
  double *tabs[NRSEC][RKEYS];
  memset(tabs, 0, sizeof tabs);
  int all_q = 1, vol_q = 1; /* every weight rational; every volume rule's */
  if (!w) st = ss_error_nomem(err, "stencil weights");
  for (int j = 0; j < R->nrs && !st; j++) { /* in the file's order */
    const int i = R->rs_order[j];
    int q = 1;
    st = section_tables(R, i, where, text, w, tabs[i], &q, err);
    all_q &= q;
    if (i < 4 || (i >= 12 && i < 12 + SS_NB_BVERTEX) || i == RSEC_AXIS) vol_q &= q;
  }
  char sec[32];
  const char *keys[RKEYS];
  int nk;
  for (int i = 0; i < NRSEC && !st; i++) /* after the file's own errors */
    if (!R->has_rs[i] && section_role(R->family, hexes, i) == 2) {
      section_of(i, sec, sizeof sec, keys, &nk);
      st = ss_error_set(err, SS_EINPUT,
                        "%s:%d: family %s with split %s needs a [%s] section", where, sl,
                        R->family == FAM_POINTS ? "points" : "neighbours",
                        hexes ? "multilinear" : "tetoct", sec);
    }
  if (!st && R->family == FAM_POINTS) {
    ss_points P;
    memset(&P, 0, sizeof P);
    P.split = R->split;
    P.rational = all_q;
    P.rational_volume = vol_q;
    for (int i = 0; i < 12; i++)
      for (int k = 0; k < 4; k++)
        P.w[i / 4][i % 4][k] = tabs[i][k];
    for (int k = 0; k < SS_AXIS_KEYS; k++)
      P.axis[k] = tabs[RSEC_AXIS][k];
    st = ss_scheme_points_new(R->name, &P, out, err);
  } else if (!st) {
    ss_neighbours N;
    memset(&N, 0, sizeof N);
    N.rational = all_q;
    N.rational_volume = vol_q;
    for (int j = 0; j < SS_NB_RULES; j++)
      for (int k = 0; k < 2; k++)
        N.w[j][k] = tabs[12 + j][k];
    st = ss_scheme_neighbours_new(R->name, &N, out, err);
  }
  free(w);
  for (int i = 0; i < NRSEC * RKEYS; i++)
    free(tabs[i / RKEYS][i % RKEYS]);
  return st;
}
