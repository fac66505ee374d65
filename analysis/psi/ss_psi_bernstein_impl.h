/* ss_psi_bernstein_impl.h — the machinery of ss_psi_bernstein.c (the
 * tricubic piece's Bezier net, the Bernstein coefficients of det Dψ, their de
 * Casteljau subdivision and the sign traversal), written once over a number
 * type and included by ss_psi_bernstein.c once per type, FLINT-template
 * style, as analysis/charmap/ss_jac_impl.h is by ss_jac.c.  Private to
 * ss_psi_bernstein.c: no include guard, on purpose.
 *
 * The includer defines
 *   NUM        the number type (double, or di_t for intervals)
 *   SUF        the suffix of every name defined here and of the operations
 *   PSI_FLAT   the verdict when all 729 coefficients have no sign
 *              (SS_JAC_DEGENERATE for doubles, SS_JAC_UNDECIDED for intervals)
 * and on NUM, named with the suffix: the operations of ss_jac_num.h (add,
 * sub, mul, scale, divd, zero, gt0, lt0) and
 *   enc(v, e)   e[0] <= v <= e[1] as doubles (doubles: e[0] = e[1] = v)
 *   mid(v)      a double in the enclosure (doubles: v)
 * and, shared by both, the constants psi_binom2, psi_binom3, psi_binom8 (the
 * binomial coefficients), PSI_SCALE (373248 = 72^3, see det_coef) and the
 * outcomes of judging one box, PSI_DECIDED, PSI_FOLD, PSI_DOUBT, PSI_SPLIT.
 * Everything here is defined as static PN(name), e.g. det_coef_d. */

#define PN_CAT2(a, b) a##_##b
#define PN_CAT(a, b)  PN_CAT2(a, b)
#define PN(name)      PN_CAT(name, SUF)

/* -1, 0 (no sign: zero to rounding, or an interval holding 0), +1 */
static inline int PN(sign)(NUM v, double thr) {
  return PN(gt0)(v, thr) ? 1 : PN(lt0)(v, thr) ? -1 : 0;
}

/* 6 times the cubic B-spline segment's Bezier points from its 4 control
 * points, in place, along the axis of stride s (in points) of the 4x4x4 net
 * P (3 coordinates per point), for each of its 16 lines along that axis */
static void PN(bezier_axis)(NUM (*P)[3], int s) {
  for (int u = 0; u < 16; u++) {
    /* the first point of the u-th line: the other two indices lo, hi */
    const int lo = u % 4, hi = u / 4;
    const int q = s == 1 ? 4 * lo + 16 * hi : s == 4 ? lo + 16 * hi : lo + 4 * hi;
    for (int r = 0; r < 3; r++) {
      const NUM p0 = P[q][r], p1 = P[q + s][r], p2 = P[q + 2 * s][r];
      const NUM p3 = P[q + 3 * s][r];
      const NUM f1 = PN(scale)(p1, 4.0), f2 = PN(scale)(p2, 4.0);
      P[q][r] = PN(add)(PN(add)(p0, f1), p2);
      P[q + s][r] = PN(add)(f1, PN(scale)(p2, 2.0));
      P[q + 2 * s][r] = PN(add)(PN(scale)(p1, 2.0), f2);
      P[q + 3 * s][r] = PN(add)(PN(add)(p1, f2), p3);
    }
  }
}

/* The tricubic Bezier net, times 216, from the B-spline net, in place */
static void PN(bezier)(NUM (*P)[3]) {
  PN(bezier_axis)(P, 1);
  PN(bezier_axis)(P, 4);
  PN(bezier_axis)(P, 16);
}

/* The differences of the Bezier net B along axis a (stride s = 1, 4, 16),
 * without the derivative's factor 3: D[i] for the multi-index (i0, i1, i2)
 * with i_a in 0..2 and the others in 0..3, at i0 + n0 (i1 + n1 i2) with n_a =
 * 3 and the others 4.  Bernstein coefficients of degree 2 along a and 3
 * across of B's partial derivative along a, divided by 3. */
static void PN(diffs)(NUM (*B)[3], int a, NUM (*D)[3]) {
  const int n0 = a == 0 ? 3 : 4, n1 = a == 1 ? 3 : 4, n2 = a == 2 ? 3 : 4;
  const int s = a == 0 ? 1 : a == 1 ? 4 : 16;
  for (int i2 = 0; i2 < n2; i2++)
    for (int i1 = 0; i1 < n1; i1++)
      for (int i0 = 0; i0 < n0; i0++) {
        const int q = i0 + 4 * i1 + 16 * i2, t = i0 + n0 * (i1 + n1 * i2);
        for (int r = 0; r < 3; r++)
          D[t][r] = PN(sub)(B[q + s][r], B[q][r]);
      }
}

/* D (as diffs, axis a) times its binomial weights, in place: the scaled
 * coefficients that Bernstein multiplication convolves */
static void PN(binom_scale)(NUM (*D)[3], int a) {
  const int n0 = a == 0 ? 3 : 4, n1 = a == 1 ? 3 : 4, n2 = a == 2 ? 3 : 4;
  for (int i2 = 0; i2 < n2; i2++)
    for (int i1 = 0; i1 < n1; i1++)
      for (int i0 = 0; i0 < n0; i0++) {
        const double w = (n0 == 3 ? psi_binom2[i0] : psi_binom3[i0]) *
                         (n1 == 3 ? psi_binom2[i1] : psi_binom3[i1]) *
                         (n2 == 3 ? psi_binom2[i2] : psi_binom3[i2]); /* <= 18, exact */
        const int t = i0 + n0 * (i1 + n1 * i2);
        for (int r = 0; r < 3; r++)
          D[t][r] = PN(scale)(D[t][r], w);
      }
}

/* X += the scaled product dv x dw (degrees (3,2,3) and (3,3,2): dims 4x3x4
 * and 4x4x3), of degree (6,5,5): X[i0 + 7 i1 + 42 i2], 7x6x6 */
static void PN(cross)(NUM (*dv)[3], NUM (*dw)[3], NUM (*X)[3]) {
  for (int q = 0; q < 252; q++)
    X[q][0] = X[q][1] = X[q][2] = PN(zero)();
  for (int b2 = 0; b2 < 4; b2++)
    for (int b1 = 0; b1 < 3; b1++)
      for (int b0 = 0; b0 < 4; b0++) {
        const NUM *f = dv[b0 + 4 * (b1 + 3 * b2)];
        for (int c2 = 0; c2 < 3; c2++)
          for (int c1 = 0; c1 < 4; c1++)
            for (int c0 = 0; c0 < 4; c0++) {
              const NUM *g = dw[c0 + 4 * (c1 + 4 * c2)];
              NUM *x = X[(b0 + c0) + 7 * (b1 + c1) + 42 * (b2 + c2)];
              x[0] = PN(add)(x[0], PN(sub)(PN(mul)(f[1], g[2]), PN(mul)(f[2], g[1])));
              x[1] = PN(add)(x[1], PN(sub)(PN(mul)(f[2], g[0]), PN(mul)(f[0], g[2])));
              x[2] = PN(add)(x[2], PN(sub)(PN(mul)(f[0], g[1]), PN(mul)(f[1], g[0])));
            }
      }
}

/* The 729 Bernstein coefficients into c of det[∂_u ψ0 | ∂_v ψ1 | ∂_w ψ2],
 * ψa the tricubic of Bezier net Ba (times 216, as bezier); det Dψ when the
 * three nets are one.  Each difference of a net is 216 / 3 = 72 times the
 * derivative's coefficient, so the triple product of the scaled differences
 * is PSI_SCALE = 72^3 times C(8,a) C(8,b) C(8,c) times coefficient (a,b,c):
 * one division per coefficient by that exact integer (<= 1.3e11). */
static inline void PN(det_coef3)(NUM (*B0)[3], NUM (*B1)[3], NUM (*B2)[3], NUM *c) {
  NUM du[48][3], dv[48][3], dw[48][3], X[252][3];
  PN(diffs)(B0, 0, du);
  PN(diffs)(B1, 1, dv);
  PN(diffs)(B2, 2, dw);
  PN(binom_scale)(du, 0);
  PN(binom_scale)(dv, 1);
  PN(binom_scale)(dw, 2);
  PN(cross)(dv, dw, X);
  for (int q = 0; q < 729; q++)
    c[q] = PN(zero)();
  /* du: degree (2,3,3), dims 3x4x4; X: 7x6x6; c: 9x9x9 */
  for (int a2 = 0; a2 < 4; a2++)
    for (int a1 = 0; a1 < 4; a1++)
      for (int a0 = 0; a0 < 3; a0++) {
        const NUM *f = du[a0 + 3 * (a1 + 4 * a2)];
        for (int x2 = 0; x2 < 6; x2++)
          for (int x1 = 0; x1 < 6; x1++)
            for (int x0 = 0; x0 < 7; x0++) {
              const NUM *g = X[x0 + 7 * (x1 + 6 * x2)];
              NUM *t = c + (a0 + x0) + 9 * (a1 + x1) + 81 * (a2 + x2);
              const NUM dot = PN(add)(PN(add)(PN(mul)(f[0], g[0]), PN(mul)(f[1], g[1])),
                                      PN(mul)(f[2], g[2]));
              *t = PN(add)(*t, dot);
            }
      }
  for (int k = 0; k < 9; k++)
    for (int j = 0; j < 9; j++)
      for (int i = 0; i < 9; i++) {
        const double d = psi_binom8[i] * psi_binom8[j] * psi_binom8[k] * PSI_SCALE;
        c[i + 9 * j + 81 * k] = PN(divd)(c[i + 9 * j + 81 * k], d);
      }
}

/* The 729 Bernstein coefficients of det Dψ of the Bezier net B */
static inline void PN(det_coef)(NUM (*B)[3], NUM *c) {
  PN(det_coef3)(B, B, B, c);
}

/* ---- subdivision and the sign traversal ---- */

/* de Casteljau at 1/2 along axis a, in place, keeping the lower (upper = 0)
 * or the upper half of each of the 81 lines of 9 coefficients along a */
static void PN(half)(NUM *c, int a, int upper) {
  const int s = a == 0 ? 1 : a == 1 ? 9 : 81;
  for (int u = 0; u < 81; u++) {
    const int lo = u % 9, hi = u / 9;
    NUM *b = c + (a == 0 ? 9 * lo + 81 * hi : a == 1 ? lo + 81 * hi : lo + 9 * hi);
    for (int r = 1; r <= 8; r++)
      if (upper)
        for (int i = 0; i <= 8 - r; i++)
          b[i * s] = PN(scale)(PN(add)(b[i * s], b[(i + 1) * s]), 0.5);
      else
        for (int i = 8; i >= r; i--)
          b[i * s] = PN(scale)(PN(add)(b[(i - 1) * s], b[i * s]), 0.5);
  }
}

/* One box of the traversal: coefficients on [lo, lo + size]^3 */
typedef struct {
  NUM c[729];   /* the Bernstein coefficients of det Dψ on the box */
  double lo[3]; /* its low corner in [0,1]^3 */
  double size;  /* its edge length */
  int next;     /* the next of its 8 children to judge (bit 0: upper half in
                   u, bit 1 in v, bit 2 in w) */
} PN(box);

/* What the traversal has seen */
typedef struct {
  int seen;            /* sign of the first exact value met that has one */
  double seen_at[3];   /* its point */
  NUM seen_val;        /* its value */
  int nosign;          /* an exact value without a sign was met */
  double nosign_at[3]; /* the first such */
  NUM nosign_val;      /* its value */
  int doubt;           /* boxes left in doubt */
} PN(walk);

/* Judge box b at depth d: its 8 corner coefficients (exact values), then all
 * 729.  PSI_FOLD fills r's where and det. */
static int PN(judge)(const PN(box) * b, int d, int maxdepth, double thr, PN(walk) * w,
                     ss_psi_piece_result *r) {
  r->boxes++;
  r->depth = d > r->depth ? d : r->depth;
  int blind = 0;
  for (int k = 0; k < 8; k++) {
    const int i = k & 1, j = (k >> 1) & 1, l = (k >> 2) & 1;
    const NUM v = b->c[8 * i + 72 * j + 648 * l];
    const double at[3] = {b->lo[0] + b->size * i, b->lo[1] + b->size * j,
                          b->lo[2] + b->size * l};
    const int s = PN(sign)(v, thr);
    if (s == 0) {
      if (!w->nosign) memcpy(w->nosign_at, at, sizeof at), w->nosign_val = v;
      w->nosign = blind = 1;
    } else if (!w->seen) {
      w->seen = s;
      memcpy(w->seen_at, at, sizeof at);
      w->seen_val = v;
    } else if (s != w->seen) {
      memcpy(r->where[0], w->seen_at, sizeof at);
      memcpy(r->where[1], at, sizeof at);
      PN(enc)(w->seen_val, r->det[0]);
      PN(enc)(v, r->det[1]);
      return PSI_FOLD;
    }
  }
  if (blind) return PSI_DOUBT;
  int pos = 1, neg = 1;
  for (int q = 0; q < 729 && (pos || neg); q++) {
    pos &= PN(gt0)(b->c[q], thr);
    neg &= PN(lt0)(b->c[q], thr);
  }
  if (pos || neg) return PSI_DECIDED;
  return d >= maxdepth ? PSI_DOUBT : PSI_SPLIT;
}

/* The sign traversal (ss_psi_bernstein.h) of the coefficients in lv[0].c;
 * lv has room for maxdepth + 1 boxes (maxdepth <= SS_PSI_MAXDEPTH).  Depth
 * first: each level holds one box and the index of its next child, which is
 * made from it by three halvings when its turn comes. */
static void PN(piece_sign)(PN(box) * lv, int maxdepth, double thr,
                           ss_psi_piece_result *r) {
  int flat = 1;
  for (int q = 0; q < 729 && flat; q++)
    flat = PN(sign)(lv[0].c[q], thr) == 0;
  if (flat) {
    r->sign = PSI_FLAT;
    r->boxes = 1;
    return;
  }
  PN(walk) w;
  memset(&w, 0, sizeof w);
  lv[0].lo[0] = lv[0].lo[1] = lv[0].lo[2] = 0.0;
  lv[0].size = 1.0;
  lv[0].next = 0;
  int st = PN(judge)(lv, 0, maxdepth, thr, &w, r), d = st == PSI_SPLIT ? 0 : -1;
  w.doubt += st == PSI_DOUBT;
  while (st != PSI_FOLD && d >= 0) {
    if (lv[d].next == 8) {
      d--;
      continue;
    }
    const int a = lv[d].next++;
    PN(box) *ch = lv + d + 1;
    memcpy(ch->c, lv[d].c, sizeof ch->c);
    ch->size = 0.5 * lv[d].size;
    for (int x = 0; x < 3; x++) {
      PN(half)(ch->c, x, (a >> x) & 1);
      ch->lo[x] = lv[d].lo[x] + ((a >> x) & 1) * ch->size;
    }
    ch->next = 0;
    st = PN(judge)(ch, d + 1, maxdepth, thr, &w, r);
    w.doubt += st == PSI_DOUBT;
    d += st == PSI_SPLIT;
  }
  if (st == PSI_FOLD) {
    r->sign = SS_JAC_FOLDED;
    return;
  }
  if (w.doubt) {
    r->sign = SS_JAC_UNDECIDED;
    if (w.nosign) {
      memcpy(r->where[0], w.nosign_at, sizeof w.nosign_at);
      PN(enc)(w.nosign_val, r->det[0]);
    }
    return;
  }
  /* every box decided, all corners of one sign: that sign everywhere */
  r->sign = w.seen > 0 ? SS_JAC_POSITIVE : SS_JAC_NEGATIVE;
}

/* min_coef and max_coef of the 729 coefficients c (their midpoints) */
static void PN(extremes)(const NUM *c, ss_psi_piece_result *r) {
  r->min_coef = INFINITY;
  r->max_coef = -INFINITY;
  for (int q = 0; q < 729; q++) {
    const double m = PN(mid)(c[q]);
    r->min_coef = fmin(r->min_coef, m);
    r->max_coef = fmax(r->max_coef, m);
  }
}

#undef PN
#undef PN_CAT
#undef PN_CAT2
