/* ss_jac_impl.h — the sign machinery of ss_jac.c (the Bernstein coefficients
 * of a hex's det J, their de Casteljau subdivision, and the determinants that
 * decide quads, tets, triangles and octahedra), written once over a number
 * type and included by ss_jac.c once per type, FLINT-template style.  Private
 * to ss_jac.c: no include guard, on purpose.
 *
 * The includer defines
 *   NUM        the number type (double, or di_t for intervals)
 *   SUF        the suffix of every name defined here and of the operations
 *   JAC_FLAT   the verdict when every value that bounds det J has no sign
 *              (SS_JAC_DEGENERATE for doubles, SS_JAC_UNDECIDED for intervals)
 * and these operations on NUM, named with the suffix (add_d, add_di, ...):
 *   add(a, b), sub(a, b), mul(a, b)   a + b, a - b, a b (intervals: enclosures)
 *   scale(a, s), divd(a, s)           s a and a / s for a double s
 *   minus(a)                          -a
 *   zero()                            0
 *   gt0(v, thr), lt0(v, thr)          v certainly > 0, certainly < 0: for
 *                                     doubles v > thr and v < -thr (thr the
 *                                     flat threshold), for intervals the whole
 *                                     interval on that side of 0 (thr unused)
 * and, shared by both, ss_jac_order with its constants quad_order and
 * hex_order (a cube's corner order), SS_JAC_STACK (the hex box stack's size)
 * and LAG_W(p, k, a) (the Lagrange weights, constant expressions); JAC_HEX_AT
 * defined: hex_at too (det J at any point).
 * Everything here is defined as static JN(name), e.g. hex_sign_d. */

#define JN_CAT2(a, b) a##_##b
#define JN_CAT(a, b)  JN_CAT2(a, b)
#define JN(name)      JN_CAT(name, SUF)

/* -1, 0 (no sign: zero to rounding, or an interval holding 0), +1 */
static inline int JN(sign)(NUM v, double thr) {
  return JN(gt0)(v, thr) ? 1 : JN(lt0)(v, thr) ? -1 : 0;
}

static NUM JN(det3)(const NUM *a, const NUM *b, const NUM *c) {
  const NUM m0 = JN(sub)(JN(mul)(b[1], c[2]), JN(mul)(b[2], c[1]));
  const NUM m1 = JN(sub)(JN(mul)(b[0], c[2]), JN(mul)(b[2], c[0]));
  const NUM m2 = JN(sub)(JN(mul)(b[0], c[1]), JN(mul)(b[1], c[0]));
  return JN(add)(JN(sub)(JN(mul)(a[0], m0), JN(mul)(a[1], m1)), JN(mul)(a[2], m2));
}

static NUM JN(det2)(const NUM *a, const NUM *b) {
  return JN(sub)(JN(mul)(a[0], b[1]), JN(mul)(a[1], b[0]));
}

/* r = a - b, d coordinates */
static void JN(diff)(int d, const NUM *a, const NUM *b, NUM *r) {
  for (int i = 0; i < d; i++)
    r[i] = JN(sub)(a[i], b[i]);
}

/* Corner k of a d-cube (d = 2, 3; o its corner order): the edge vectors along
 * increasing parameters, e[i] = x(corner with bit i set) - x(corner with bit i
 * clear). */
static void JN(corner_frame)(const NUM *x, int d, const ss_jac_order *o, int k,
                             NUM e[3][3]) {
  const unsigned b = o->bits[k];
  for (int i = 0; i < d; i++) {
    const unsigned b1 = b | (1u << i), b0 = b & ~(1u << i);
    JN(diff)(d, x + d * o->index[b1], x + d * o->index[b0], e[i]);
  }
}

#ifdef JAC_HEX_AT
/* det J of the trilinear map of the hex x (8 x 3, corner order o) at (u, v, w) */
static NUM JN(hex_at)(const NUM *x, const ss_jac_order *o, double u, double v, double w) {
  const double t[3] = {u, v, w};
  NUM J[3][3]; /* J[i] = d x / d t_i */
  for (int i = 0; i < 3; i++)
    for (int r = 0; r < 3; r++)
      J[i][r] = JN(zero)();
  for (int k = 0; k < 8; k++) {
    const unsigned b = o->bits[k];
    for (int i = 0; i < 3; i++) {
      double wt = 1.0; /* exact: a product of +-1, t and 1 - t */
      for (int j = 0; j < 3; j++) {
        const int bj = (int)((b >> j) & 1u);
        wt *= j == i ? (bj ? 1.0 : -1.0) : (bj ? t[j] : 1.0 - t[j]);
      }
      if (wt == 0.0) continue; /* adds +-0: the same sums, fewer operations */
      for (int r = 0; r < 3; r++)
        J[i][r] = JN(add)(J[i][r], JN(scale)(x[3 * k + r], wt));
    }
  }
  return JN(det3)(J[0], J[1], J[2]);
}
#endif

/* det J at the 27 Lagrange points (i, j, l) / 2 into v[i + 3 j + 9 l]: as
 * hex_at at each, the same operations in the same order (per derivative,
 * corners k = 0..7 in turn, 0 weights skipped), with the weights the constants
 * LAG_W (ss_jac.c) instead of computed.  Written out point by point and corner
 * by corner (the macros below, expanded 27 x 8 x 3 times) so that each weight
 * and its test against 0 are resolved by the compiler: the straight-line code
 * has only the nonzero terms (about 11 of 24 per point).  Only the order of
 * terms of different sums (different axes and coordinates) is interleaved
 * otherwise than in a loop; each sum is formed in the same order, so the
 * values are the same bits. */
#define JN_LTERM(p, k, a)                                                                \
  do {                                                                                   \
    const double wt_ = LAG_W(p, k, a);                                                   \
    if (wt_ != 0.0)                                                                      \
      for (int r_ = 0; r_ < 3; r_++)                                                     \
        J[a][r_] = JN(add)(J[a][r_], JN(scale)(x[3 * (k) + r_], wt_));                   \
  } while (0)
#define JN_LCORNER(p, k)                                                                 \
  JN_LTERM(p, k, 0);                                                                     \
  JN_LTERM(p, k, 1);                                                                     \
  JN_LTERM(p, k, 2)
#define JN_LPOINT(p)                                                                     \
  do {                                                                                   \
    NUM J[3][3];                                                                         \
    for (int i_ = 0; i_ < 3; i_++)                                                       \
      for (int r_ = 0; r_ < 3; r_++)                                                     \
        J[i_][r_] = JN(zero)();                                                          \
    JN_LCORNER(p, 0);                                                                    \
    JN_LCORNER(p, 1);                                                                    \
    JN_LCORNER(p, 2);                                                                    \
    JN_LCORNER(p, 3);                                                                    \
    JN_LCORNER(p, 4);                                                                    \
    JN_LCORNER(p, 5);                                                                    \
    JN_LCORNER(p, 6);                                                                    \
    JN_LCORNER(p, 7);                                                                    \
    v[p] = JN(det3)(J[0], J[1], J[2]);                                                   \
  } while (0)
static void JN(hex_lagrange)(const NUM *x, NUM *v) {
  JN_LPOINT(0);
  JN_LPOINT(1);
  JN_LPOINT(2);
  JN_LPOINT(3);
  JN_LPOINT(4);
  JN_LPOINT(5);
  JN_LPOINT(6);
  JN_LPOINT(7);
  JN_LPOINT(8);
  JN_LPOINT(9);
  JN_LPOINT(10);
  JN_LPOINT(11);
  JN_LPOINT(12);
  JN_LPOINT(13);
  JN_LPOINT(14);
  JN_LPOINT(15);
  JN_LPOINT(16);
  JN_LPOINT(17);
  JN_LPOINT(18);
  JN_LPOINT(19);
  JN_LPOINT(20);
  JN_LPOINT(21);
  JN_LPOINT(22);
  JN_LPOINT(23);
  JN_LPOINT(24);
  JN_LPOINT(25);
  JN_LPOINT(26);
}
#undef JN_LPOINT
#undef JN_LCORNER
#undef JN_LTERM

/* ---- hexes: Bernstein coefficients and adaptive subdivision ---- */

/* A box of the parameter cube with the 27 Bernstein coefficients of det J
 * on it, c[i + 3 j + 9 k] for the multi-index (i, j, k) in {0,1,2}^3. */
typedef struct {
  NUM c[27];    /* coefficients */
  double lo[3]; /* the box's low corner in [0,1]^3 */
  double size;  /* its edge length */
  int depth;    /* subdivision level */
} JN(box);

/* The first index of the u-th of the 9 lines of coefficients along axis a
 * (index 0 along a; u = the other two indices, the lower one first): the
 * lines without a division by the stride, which was a fifth of the hex
 * test's time. */
static inline int JN(line_start)(int a, int u) {
  const int lo = u % 3, hi = u / 3;
  return a == 0 ? 3 * lo + 9 * hi : a == 1 ? lo + 9 * hi : lo + 3 * hi;
}

/* de Casteljau at 1/2 along axis a: the coefficients of the lower and upper
 * halves. */
static void JN(split_axis)(const NUM *c, int a, NUM *lo, NUM *hi) {
  const int stride = a == 0 ? 1 : a == 1 ? 3 : 9;
  for (int u = 0; u < 9; u++) {
    const int q = JN(line_start)(a, u);
    const NUM b0 = c[q], b1 = c[q + stride], b2 = c[q + 2 * stride];
    const NUM m01 = JN(scale)(JN(add)(b0, b1), 0.5);
    const NUM m12 = JN(scale)(JN(add)(b1, b2), 0.5);
    const NUM m = JN(scale)(JN(add)(m01, m12), 0.5);
    lo[q] = b0, lo[q + stride] = m01, lo[q + 2 * stride] = m;
    hi[q] = m, hi[q + stride] = m12, hi[q + 2 * stride] = b2;
  }
}

/* The parameter point of multi-index (i, j, l) in {0,1,2}^3 of box b. */
static void JN(box_point)(const JN(box) * b, int i, int j, int l, double *p) {
  p[0] = b->lo[0] + b->size * 0.5 * i;
  p[1] = b->lo[1] + b->size * 0.5 * j;
  p[2] = b->lo[2] + b->size * 0.5 * l;
}

/* The derivatives of the trilinear map of the hex x (hex_order) at the 27
 * Lagrange points (i, j, l) / 2 from its 12 edge vectors: d x / d t_a there
 * is the bilinear interpolation, in the other two parameters, of the four
 * edges along axis a (x(b with bit a) - x(b)) at 0, 1/2, 1 -- an edge, the
 * half sum of two, or the half sum of two such -- so 3 x 9 vectors, each
 * shared by the three points on its line.  D[a][i1 + 3 i2]: axis a, indices
 * i1, i2 of the other two axes, the lower one first.  Each is a combination
 * of the corners whose coefficients' magnitudes sum to 2, formed by one
 * subtraction and at most two halved sums. */
static void JN(hex_derivs)(const NUM *x, NUM D[3][9][3]) {
  for (int a = 0; a < 3; a++) {
    const int c1 = a == 0 ? 1 : 0, c2 = a == 2 ? 1 : 2;
    NUM E[2][2][3]; /* the edge along a at bits (b1, b2) of axes c1, c2 */
    for (unsigned b1 = 0; b1 < 2; b1++)
      for (unsigned b2 = 0; b2 < 2; b2++) {
        const unsigned b = b1 << c1 | b2 << c2;
        JN(diff)
        (3, x + 3 * hex_order.index[b | 1u << a], x + 3 * hex_order.index[b], E[b1][b2]);
      }
    for (int r = 0; r < 3; r++) {
      NUM G[3][2]; /* along c1 at 0, 1/2, 1, for each bit of c2 */
      for (int b2 = 0; b2 < 2; b2++) {
        G[0][b2] = E[0][b2][r];
        G[2][b2] = E[1][b2][r];
        G[1][b2] = JN(scale)(JN(add)(E[0][b2][r], E[1][b2][r]), 0.5);
      }
      for (int i1 = 0; i1 < 3; i1++) {
        D[a][i1][r] = G[i1][0];
        D[a][i1 + 6][r] = G[i1][1];
        D[a][i1 + 3][r] = JN(scale)(JN(add)(G[i1][0], G[i1][1]), 0.5);
      }
    }
  }
}

/* The 27 Lagrange values on {0, 1/2, 1}^3 of a triquadratic into its
 * Bernstein coefficients, in place, axis by axis: the middle of each line
 * 2 c - (c_0 + c_2) / 2, its ends unchanged. */
static void JN(bernstein)(NUM *c) {
  for (int a = 0, stride = 1; a < 3; a++, stride *= 3)
    for (int u = 0; u < 9; u++) {
      const int q = JN(line_start)(a, u) + stride; /* the middle of the line */
      c[q] = JN(sub)(JN(scale)(c[q], 2.0),
                     JN(scale)(JN(add)(c[q - stride], c[q + stride]), 0.5));
    }
}

/* The hex test (ss_jac.h): exact values are the corner coefficients of the
 * cell and of its sub-boxes.  Depth first; a box with a corner of no sign is
 * left in doubt without splitting it (every sub-box at that corner would keep
 * it, and where det J vanishes on a face the split boxes would grow as 4^depth),
 * but the other boxes are still searched for a proof of a fold. */
static void JN(hex_sign)(const NUM *x, int maxdepth, double thr, ss_jac_result *r) {
  if (maxdepth > 15) maxdepth = 15;
  JN(box) stack[SS_JAC_STACK];
  int sp = 0;
  /* Lagrange values on {0, 1/2, 1}^3, converted axis by axis */
  JN(box) *b = stack + sp++;
  JN(hex_lagrange)(x, b->c);
  JN(bernstein)(b->c);
  int flat = 1;
  for (int q = 0; q < 27; q++)
    flat &= JN(sign)(b->c[q], thr) == 0;
  r->depth = 0;
  if (flat) {
    r->sign = JAC_FLAT;
    return;
  }
  b->lo[0] = b->lo[1] = b->lo[2] = 0.0;
  b->size = 1.0;
  b->depth = 0;
  int seen = 0;   /* sign of the first exact value met that has one */
  int nosign = 0; /* an exact value without a sign was met (where holds it) */
  int npos = 0, nneg = 0, doubt = 0;
  while (sp > 0) {
    JN(box) cur = stack[--sp];
    r->depth = cur.depth > r->depth ? cur.depth : r->depth;
    /* exact values: the 8 corner coefficients */
    int blind = 0;
    for (int k = 0; k < 8; k++) {
      const int i = (k & 1) * 2, j = ((k >> 1) & 1) * 2, l = ((k >> 2) & 1) * 2;
      const int s = JN(sign)(cur.c[i + 3 * j + 9 * l], thr);
      if (s == 0) {
        blind = 1;
        if (!nosign) JN(box_point)(&cur, i, j, l, r->where);
        nosign = 1;
        continue;
      }
      if (seen && s != seen) {
        JN(box_point)(&cur, i, j, l, r->where);
        r->sign = SS_JAC_FOLDED;
        return;
      }
      seen = s;
    }
    if (blind) {
      doubt++;
      continue;
    }
    int pos = 1, neg = 1;
    for (int q = 0; q < 27; q++) {
      pos &= JN(gt0)(cur.c[q], thr);
      neg &= JN(lt0)(cur.c[q], thr);
    }
    if (pos) {
      npos++;
      continue;
    }
    if (neg) {
      nneg++;
      continue;
    }
    if (cur.depth >= maxdepth || sp + 8 > SS_JAC_STACK) {
      doubt++;
      continue;
    }
    /* split into 8: along x, then y, then z */
    NUM h[2][27], q4[4][27], q8[8][27];
    JN(split_axis)(cur.c, 0, h[0], h[1]);
    for (int a = 0; a < 2; a++)
      JN(split_axis)(h[a], 1, q4[2 * a], q4[2 * a + 1]);
    for (int a = 0; a < 4; a++)
      JN(split_axis)(q4[a], 2, q8[2 * a], q8[2 * a + 1]);
    for (int a = 0; a < 8; a++) {
      /* q8 index: bit 2 = x half, bit 1 = y half, bit 0 = z half */
      JN(box) *nb = stack + sp++;
      memcpy(nb->c, q8[a], sizeof nb->c);
      nb->size = 0.5 * cur.size;
      nb->lo[0] = cur.lo[0] + ((a >> 2) & 1) * nb->size;
      nb->lo[1] = cur.lo[1] + ((a >> 1) & 1) * nb->size;
      nb->lo[2] = cur.lo[2] + (a & 1) * nb->size;
      nb->depth = cur.depth + 1;
    }
  }
  if (npos && nneg) {
    /* cannot happen without exact values of both signs, which return above */
    r->sign = SS_JAC_FOLDED;
    return;
  }
  if (doubt)
    r->sign = SS_JAC_UNDECIDED;
  else
    r->sign = seen > 0 ? SS_JAC_POSITIVE : SS_JAC_NEGATIVE;
}

/* ---- the other cell types ---- */

/* Quad: det J is affine, its four corner values decide. */
static void JN(quad_sign)(const NUM *x, double thr, ss_jac_result *r) {
  const ss_jac_order o = quad_order;
  int sg[4], flat = 1;
  for (int k = 0; k < 4; k++) {
    NUM e[3][3];
    JN(corner_frame)(x, 2, &o, k, e);
    sg[k] = JN(sign)(JN(det2)(e[0], e[1]), thr);
    flat &= sg[k] == 0;
  }
  if (flat) {
    r->sign = JAC_FLAT;
    return;
  }
  int first = 0, bad = -1, blind = -1;
  for (int k = 0; k < 4; k++) {
    if (sg[k] == 0) {
      if (blind < 0) blind = k;
    } else if (!first) {
      first = sg[k];
    } else if (bad < 0 && sg[k] != first) {
      bad = k;
    }
  }
  const int at = bad >= 0 ? bad : blind;
  if (at >= 0) {
    r->where[0] = (double)(o.bits[at] & 1u);
    r->where[1] = (double)((o.bits[at] >> 1) & 1u);
  }
  r->sign = bad >= 0     ? SS_JAC_FOLDED
            : blind >= 0 ? SS_JAC_UNDECIDED
            : first > 0  ? SS_JAC_POSITIVE
                         : SS_JAC_NEGATIVE;
}

/* Tet (d = 3) or triangle (d = 2): the determinant of the edges from vertex 0. */
static void JN(simplex_sign)(const NUM *x, int d, double thr, ss_jac_result *r) {
  NUM e[3][3];
  for (int i = 0; i < d; i++)
    JN(diff)(d, x + d * (i + 1), x, e[i]);
  const int s = JN(sign)(d == 3 ? JN(det3)(e[0], e[1], e[2]) : JN(det2)(e[0], e[1]), thr);
  r->sign = s > 0 ? SS_JAC_POSITIVE : s < 0 ? SS_JAC_NEGATIVE : JAC_FLAT;
}

/* Octahedron: the eight tets (centroid, one vertex of each opposite pair),
 * each oriented as the octant it fills. */
static void JN(oct_sign)(const NUM *x, double thr, ss_jac_result *r) {
  NUM c[3];
  for (int i = 0; i < 3; i++)
    c[i] = JN(zero)();
  for (int k = 0; k < 6; k++)
    for (int i = 0; i < 3; i++)
      c[i] = JN(add)(c[i], JN(divd)(x[3 * k + i], 6.0));
  int pos = 0, neg = 0, none = 0;
  for (int f = 0; f < 8; f++) {
    /* octant f: one vertex of each opposite pair; an odd number of
     * reflections reverses the orientation (as in ss_cx_orient.c) */
    const int s0 = (f & 1) ? 3 : 0, s1 = (f & 2) ? 4 : 1, s2 = (f & 4) ? 5 : 2;
    const int flips = (f & 1) + ((f >> 1) & 1) + ((f >> 2) & 1);
    NUM a[3], b[3], e[3];
    JN(diff)(3, x + 3 * s0, c, a);
    JN(diff)(3, x + 3 * s1, c, b);
    JN(diff)(3, x + 3 * s2, c, e);
    NUM d = JN(det3)(a, b, e);
    if (flips & 1) d = JN(minus)(d);
    const int s = JN(sign)(d, thr);
    pos += s > 0;
    neg += s < 0;
    none += s == 0;
  }
  r->sign = none == 8    ? JAC_FLAT
            : pos && neg ? SS_JAC_FOLDED
            : none       ? SS_JAC_UNDECIDED
            : pos        ? SS_JAC_POSITIVE
                         : SS_JAC_NEGATIVE;
}

/* The verdict, depth and where of a cell whose type and dim were checked. */
static void JN(cell_sign)(ss_cell_type t, const NUM *x, int maxdepth, double thr,
                          ss_jac_result *r) {
  switch (t) {
  case SS_HEX:
    JN(hex_sign)(x, maxdepth < 0 ? 0 : maxdepth, thr, r);
    break;
  case SS_QUAD:
    JN(quad_sign)(x, thr, r);
    break;
  case SS_TET:
    JN(simplex_sign)(x, 3, thr, r);
    break;
  case SS_TRIANGLE:
    JN(simplex_sign)(x, 2, thr, r);
    break;
  case SS_OCT:
    JN(oct_sign)(x, thr, r);
    break;
  default:
    r->sign = SS_JAC_UNDECIDED;
    break;
  }
}

#undef JN
#undef JN_CAT
#undef JN_CAT2
