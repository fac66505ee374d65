/* test_cx_orient.c — orientation, signed volume and flatness of cells, and
 * the inverted-cell check of a complex (ss_cx_orient.c), against symmetry
 * groups, affine maps and volumes computed here another way.
 *
 * Properties:
 *   - relabelling a cell's vertices by a symmetry of its type multiplies its
 *     orientation and signed volume by the symmetry's sign: the 24
 *     permutations of a tet (the parity), the 6 of a triangle, the 48
 *     signed axis permutations of a hex and of an octahedron and the 8 of a
 *     quad (the determinant of the signed permutation matrix, computed here
 *     from the cube's corner bits and the octahedron's axis pairs);
 *   - an affine map x -> A x + b multiplies every orientation by sign(det A)
 *     and every signed volume by det A (tets, octahedra, trilinear hexes,
 *     triangles, quads);
 *   - the volume of a non-affine (jittered) hex equals the integral of its
 *     trilinear Jacobian by a 3-point Gauss-Legendre rule per direction
 *     (exact for its degree) done here; an octahedron's equals the sum of
 *     the four tets around its diagonal (0, 3), formed here;
 *   - additivity: a hex grid and a Kuhn tet mesh of a box with jittered
 *     interior vertices have total signed volume the box's; the children of
 *     a jittered hex (multilinear split) and of a tet and an octahedron
 *     (tet/oct split) add up to their parent and keep its orientation;
 *   - scale: a cube of side 2^-1000 or 2^1000 is positive, a flat tet is
 *     flat at any scale, a needle (aspect 1e-7) is not flat;
 *   - ss_cx_cell_flat: collinear triangles and quads with a straight corner
 *     in 3D and 4D coordinates are flat, others not; vertex cells never;
 *   - ss_cx_check_orientation on a jittered hex grid with a random set of
 *     cells mirrored: passes with none, names an inverted cell that is one
 *     of the mirrored ones when they are fewer, one of the others when they
 *     are more; a relabelled copy (tm_permuted) passes; surfaces in 3D are
 *     judged for flatness only; tets with 2 coordinates are refused.
 * Mutations this catches (tried by hand: the report of issue 33):
 *   - the hex volume by the midpoint rule (Gauss points 0.5, 0.5): the
 *     Gauss-Legendre comparison and the jittered grid's total volume;
 *   - an octahedron's centroid tets all counted with one sign (the flip
 *     parity dropped): the octahedron's orientation under its symmetries. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_permutation.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "ss_cx.h"
#include "ss_split.h"
#include "ss_test.h"
#include "ss_testmesh.h"

/* A complex of one cell of type t on the points x (nv of them, dim each). */
static ss_cx *cell(ss_cell_type t, int dim, const double *x, int nv, const ss_idx *v) {
  ss_cx *cx = NULL;
  ss_error err = {0};
  ss_cx_new(dim, &cx, &err);
  for (int i = 0; i < nv; i++)
    ss_cx_add_vertex(cx, x + dim * i, 0, &err);
  ss_cx_add_cell(cx, t, v, 0, &err);
  return cx;
}

static const ss_idx ident[8] = {0, 1, 2, 3, 4, 5, 6, 7};

static int orient(ss_cell_type t, int dim, const double *x, int nv, const ss_idx *v,
                  double *vol) {
  ss_cx *cx = cell(t, dim, x, nv, v);
  const int o = ss_cx_cell_orientation(cx, t, 0, vol);
  ss_cx_free(cx);
  return o;
}

/* The unit cell of type t in dim coordinates, jittered by amp. */
static int reference(ss_cell_type t, gsl_rng *r, double amp, double *x) {
  static const double tet[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const double oct[18] = {1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
  static const double tri[6] = {0, 0, 1, 0, 0, 1};
  const int n = ss_cell_nverts(t), dim = t == SS_TRIANGLE || t == SS_QUAD ? 2 : 3;
  for (int k = 0; k < n; k++)
    for (int d = 0; d < dim; d++) {
      double c;
      if (t == SS_HEX || t == SS_QUAD)
        c = (double)((ss_cube_corner_bits(dim, k) >> d) & 1u);
      else
        c = t == SS_TET ? tet[k * 3 + d] : t == SS_OCT ? oct[k * 3 + d] : tri[k * 2 + d];
      x[k * dim + d] = c + amp * (2.0 * gsl_rng_uniform(r) - 1.0);
    }
  return dim;
}

/* ---- symmetries ---- */

static int parity(const int *p, int n) {
  int s = 1;
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++)
      if (p[i] > p[j]) s = -s;
  return s;
}

/* Signed axis permutation number g (0 .. d! 2^d - 1) of d axes: axis i goes
 * to perm[i], flipped if flip[i]; returns its determinant. */
static int signed_perm(int d, int g, int *perm, int *flip) {
  static const int p3[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                               {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  static const int p2[2][3] = {{0, 1, 2}, {1, 0, 2}};
  const int nf = 1 << d, q = g / nf;
  int det = 1;
  for (int i = 0; i < d; i++) {
    perm[i] = d == 3 ? p3[q][i] : p2[q][i];
    flip[i] = (g >> i) & 1;
    if (flip[i]) det = -det;
  }
  return det * parity(perm, d);
}

static void test_symmetries(gsl_rng *r) {
  double x[24];
  /* simplices: every permutation */
  const ss_cell_type simp[2] = {SS_TET, SS_TRIANGLE};
  for (int s = 0; s < 2; s++) {
    const ss_cell_type t = simp[s];
    const int n = ss_cell_nverts(t), dim = reference(t, r, 0.2, x);
    double v0;
    const int o0 = orient(t, dim, x, n, ident, &v0);
    CHECK(o0 == 1, "%s: reference orientation %d", ss_cell_name(t), o0);
    int p[4] = {0, 1, 2, 3}, bad = 0;
    gsl_permutation *gp = gsl_permutation_calloc((size_t)n);
    do {
      ss_idx v[4];
      for (int i = 0; i < n; i++)
        v[i] = (ss_idx)(p[i] = (int)gsl_permutation_get(gp, (size_t)i));
      double vol;
      const int o = orient(t, dim, x, n, v, &vol), sg = parity(p, n);
      bad += o != sg * o0 || fabs(vol - sg * v0) > 1e-14;
    } while (gsl_permutation_next(gp) == GSL_SUCCESS);
    gsl_permutation_free(gp);
    CHECK(bad == 0, "%s: %d permutations with the wrong orientation or volume",
          ss_cell_name(t), bad);
  }
  /* cubes: corner k with bits b goes to the corner with bits b' where
   * b'[perm[i]] = b[i] ^ flip[i] */
  const ss_cell_type cube[2] = {SS_HEX, SS_QUAD};
  for (int s = 0; s < 2; s++) {
    const ss_cell_type t = cube[s];
    const int dim = reference(t, r, 0.15, x), n = 1 << dim;
    double v0;
    const int o0 = orient(t, dim, x, n, ident, &v0);
    int bad = 0, ng = (dim == 3 ? 6 : 2) << dim;
    for (int g = 0; g < ng; g++) {
      int perm[3], flip[3];
      const int det = signed_perm(dim, g, perm, flip);
      ss_idx v[8];
      for (int k = 0; k < n; k++) {
        const unsigned b = ss_cube_corner_bits(dim, k);
        unsigned b2 = 0;
        for (int i = 0; i < dim; i++)
          b2 |= (((b >> i) & 1u) ^ (unsigned)flip[i]) << perm[i];
        v[k] = (ss_idx)ss_cube_corner_index(dim, b2);
      }
      double vol;
      const int o = orient(t, dim, x, n, v, &vol);
      bad += o != det * o0 || fabs(vol - det * v0) > 1e-13;
    }
    CHECK(o0 == 1 && bad == 0, "%s: %d of %d symmetries with the wrong sign",
          ss_cell_name(t), bad, ng);
  }
  /* the octahedron: vertex a is axis a % 3, sign + for a < 3 */
  reference(SS_OCT, r, 0.15, x);
  double v0;
  const int o0 = orient(SS_OCT, 3, x, 6, ident, &v0);
  int bad = 0;
  for (int g = 0; g < 48; g++) {
    int perm[3], flip[3];
    const int det = signed_perm(3, g, perm, flip);
    ss_idx v[6];
    for (int a = 0; a < 6; a++) {
      const int axis = a % 3, neg = (a >= 3) ^ flip[axis];
      v[a] = (ss_idx)(perm[axis] + 3 * neg);
    }
    double vol;
    const int o = orient(SS_OCT, 3, x, 6, v, &vol);
    bad += o != det * o0 || fabs(vol - det * v0) > 1e-13;
  }
  CHECK(o0 == 1 && bad == 0, "octahedron: %d of 48 symmetries with the wrong sign", bad);
}

/* ---- affine maps and volumes ---- */

static double det3(const double *A) {
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
         A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* The volume of the trilinear hex x (8 corners) by Gauss-Legendre with 3
 * points per direction: det J has degree <= 2 in each variable. */
static double hex_volume_gauss3(const double *x) {
  const double g[3] = {0.5 - 0.5 * sqrt(0.6), 0.5, 0.5 + 0.5 * sqrt(0.6)};
  const double w[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  double V = 0.0;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      for (int c = 0; c < 3; c++) {
        const double u[3] = {g[a], g[b], g[c]};
        double J[9] = {0}; /* J[r * 3 + i] = d x_r / d u_i */
        for (int k = 0; k < 8; k++) {
          const unsigned bits = ss_cube_corner_bits(3, k);
          for (int i = 0; i < 3; i++) {
            double f = 1.0;
            for (int j = 0; j < 3; j++) {
              const int bj = (int)((bits >> j) & 1u);
              f *= j == i ? (bj ? 1.0 : -1.0) : (bj ? u[j] : 1.0 - u[j]);
            }
            for (int rr = 0; rr < 3; rr++)
              J[rr * 3 + i] += f * x[k * 3 + rr];
          }
        }
        V += w[a] * w[b] * w[c] * det3(J);
      }
  return V;
}

/* An octahedron's signed volume as the four tets (0, 3, s, s') around its
 * diagonal (0, 3), s s' = 1 2, 2 4, 4 5, 5 1 (the equator in order). */
static double oct_volume_diagonal(const double *x) {
  static const int eq[4] = {1, 2, 4, 5};
  double V = 0.0;
  for (int q = 0; q < 4; q++) {
    const int s = eq[q], t = eq[(q + 1) % 4];
    double A[9];
    for (int rr = 0; rr < 3; rr++) {
      A[rr * 3 + 0] = x[3 * 3 + rr] - x[rr];
      A[rr * 3 + 1] = x[s * 3 + rr] - x[rr];
      A[rr * 3 + 2] = x[t * 3 + rr] - x[rr];
    }
    V += det3(A) / 6.0;
  }
  /* (0, 3, 1, 2) is negative for the positive octahedron +x +y +z -x -y -z:
   * det(-2 e_x, e_y - e_x, e_z - e_x) = -2 */
  return -V;
}

static void test_affine(gsl_rng *r) {
  const ss_cell_type types[5] = {SS_TET, SS_OCT, SS_HEX, SS_TRIANGLE, SS_QUAD};
  for (int t = 0; t < 5; t++)
    for (int s = 0; s < 6; s++) {
      double x[24], y[24], A[9], b[3];
      const int dim = reference(types[t], r, 0.15, x), n = ss_cell_nverts(types[t]);
      for (int i = 0; i < 9; i++)
        A[i] = (i % 4 == 0 ? 1.0 : 0.0) + 0.4 * (2.0 * gsl_rng_uniform(r) - 1.0);
      if (dim == 2) A[2] = A[5] = A[6] = A[7] = 0.0, A[8] = 1.0;
      if (s & 1) /* a reflection: negate the first row */
        A[0] = -A[0], A[1] = -A[1], A[2] = -A[2];
      for (int i = 0; i < 3; i++)
        b[i] = 10.0 * gsl_rng_uniform(r);
      for (int k = 0; k < n; k++)
        for (int rr = 0; rr < dim; rr++) {
          double v = b[rr];
          for (int c = 0; c < dim; c++)
            v += A[rr * 3 + c] * x[k * dim + c];
          y[k * dim + rr] = v;
        }
      const double det = det3(A);
      double v0, v1;
      const int o0 = orient(types[t], dim, x, n, ident, &v0);
      const int o1 = orient(types[t], dim, y, n, ident, &v1);
      CHECK(o0 == 1 && o1 == (det > 0 ? 1 : -1),
            "%s, affine map %d (det %g): orientation %d -> %d", ss_cell_name(types[t]), s,
            det, o0, o1);
      CHECK_CLOSE(v1, det * v0, 1e-12, "%s, affine map %d: volume",
                  ss_cell_name(types[t]), s);
      if (types[t] == SS_HEX)
        CHECK_CLOSE(v0, hex_volume_gauss3(x), 1e-13, "jittered hex %d: volume", s);
      if (types[t] == SS_OCT)
        CHECK_CLOSE(v0, oct_volume_diagonal(x), 1e-13, "jittered octahedron %d: volume",
                    s);
    }
}

/* Total signed volume of the cells of type t. */
static double total_volume(const ss_cx *cx, ss_cell_type t, int *all_positive) {
  double V = 0.0;
  for (size_t i = 0; i < cx->nc[t]; i++) {
    double v;
    *all_positive &= ss_cx_cell_orientation(cx, t, i, &v) == 1;
    V += v;
  }
  return V;
}

/* Move the vertices strictly inside [0, n]^3 by up to amp. */
static void jitter_interior(ss_cx *cx, int n, double amp, gsl_rng *r) {
  for (size_t v = 0; v < cx->nv; v++) {
    int inside = 1;
    for (int d = 0; d < 3; d++)
      inside &= cx->x[v * 3 + (size_t)d] > 0.0 && cx->x[v * 3 + (size_t)d] < n;
    if (inside)
      for (int d = 0; d < 3; d++)
        cx->x[v * 3 + (size_t)d] += amp * (2.0 * gsl_rng_uniform(r) - 1.0);
  }
}

static void test_additive(gsl_rng *r) {
  enum { N = 4 };
  int pos = 1;
  ss_cx *g = tm_hex_grid(N, N, N);
  jitter_interior(g, N, 0.15, r);
  CHECK_CLOSE(total_volume(g, SS_HEX, &pos), N * N * N, 1e-12, "jittered hex grid");
  CHECK(pos, "jittered hex grid: a cell not positive");
  ss_cx *k = tm_kuhn(N);
  jitter_interior(k, N, 0.1, r);
  pos = 1;
  CHECK_CLOSE(total_volume(k, SS_TET, &pos), N * N * N, 1e-12, "jittered Kuhn mesh");
  /* children add up to the parent */
  double x[24];
  const ss_cell_type types[3] = {SS_HEX, SS_TET, SS_OCT};
  for (int t = 0; t < 3; t++) {
    reference(types[t], r, 0.1, x);
    ss_cx *c = cell(types[t], 3, x, ss_cell_nverts(types[t]), ident), *f = NULL;
    ss_split *L = NULL;
    ss_error err = {0};
    double v0;
    ss_cx_cell_orientation(c, types[t], 0, &v0);
    if (!ss_split_refine(types[t] == SS_HEX ? SS_SPLIT_MULTILINEAR : SS_SPLIT_TETOCT, c,
                         &f, &L, &err)) {
      pos = 1;
      const double V = total_volume(f, SS_HEX, &pos) + total_volume(f, SS_TET, &pos) +
                       total_volume(f, SS_OCT, &pos);
      CHECK_CLOSE(V, v0, 1e-13, "%s: children's volume", ss_cell_name(types[t]));
      CHECK(pos, "%s: a child not positive", ss_cell_name(types[t]));
    } else {
      CHECK(0, "%s: %s", ss_cell_name(types[t]), err.msg);
    }
    ss_split_free(L);
    ss_cx_free(f);
    ss_cx_free(c);
  }
  ss_cx_free(k);
  ss_cx_free(g);
}

/* ---- scale and flatness ---- */

static void test_scale_flat(void) {
  double x[24];
  for (int e = -1000; e <= 1000; e += 1000) {
    for (int k = 0; k < 8; k++)
      for (int d = 0; d < 3; d++)
        x[k * 3 + d] = ldexp((double)((ss_cube_corner_bits(3, k) >> d) & 1u), e);
    CHECK(orient(SS_HEX, 3, x, 8, ident, NULL) == 1, "cube of side 2^%d", e);
    /* a flat tet (four coplanar points) and a needle */
    const double flat[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, 0};
    const double needle[12] = {0, 0, 0, 1, 0, 0, 1, 1e-7, 0, 1, 0, 1e-7};
    double f[12], nd[12];
    for (int i = 0; i < 12; i++)
      f[i] = ldexp(flat[i], e), nd[i] = ldexp(needle[i], e);
    CHECK(orient(SS_TET, 3, f, 4, ident, NULL) == 0, "flat tet at 2^%d", e);
    CHECK(orient(SS_TET, 3, nd, 4, ident, NULL) != 0, "needle at 2^%d", e);
    ss_cx *c = cell(SS_TET, 3, f, 4, ident);
    CHECK(ss_cx_cell_flat(c, SS_TET, ident), "flat tet at 2^%d not flat", e);
    ss_cx_free(c);
  }
  /* faces with more coordinates than dimensions */
  for (int dim = 3; dim <= 4; dim++) {
    double t[12] = {0}, q[16] = {0};
    /* triangle (0,0,0) (1,1,1) (2,2,2): collinear; then lifted off the line */
    for (int k = 0; k < 3; k++)
      for (int d = 0; d < dim; d++)
        t[k * dim + d] = k;
    ss_cx *c = cell(SS_TRIANGLE, dim, t, 3, ident);
    CHECK(ss_cx_cell_flat(c, SS_TRIANGLE, ident), "collinear triangle in %dD", dim);
    c->x[2 * dim + dim - 1] += 1.0;
    CHECK(!ss_cx_cell_flat(c, SS_TRIANGLE, ident), "proper triangle in %dD flat", dim);
    ss_cx_free(c);
    /* a quad with a straight corner 1 (0, 1, 2 collinear) */
    const double sq[4][2] = {{0, 0}, {1, 0}, {2, 0}, {0, 1}};
    for (int k = 0; k < 4; k++)
      for (int d = 0; d < 2; d++)
        q[k * dim + d] = sq[k][d];
    c = cell(SS_QUAD, dim, q, 4, ident);
    CHECK(ss_cx_cell_flat(c, SS_QUAD, ident), "quad with a straight corner in %dD", dim);
    c->x[2 * dim + 1] = 1.0, c->x[3 * dim + 0] = 0.0; /* the unit square's (1, 1) */
    c->x[2 * dim + 0] = 1.0;
    CHECK(!ss_cx_cell_flat(c, SS_QUAD, ident), "square in %dD flat", dim);
    const ss_idx one[1] = {0};
    CHECK(!ss_cx_cell_flat(c, SS_VERTEX, one), "a vertex cell is flat");
    ss_cx_free(c);
  }
}

/* ---- the inverted-cell check ---- */

static void test_check(gsl_rng *r) {
  enum { N = 5, NC = N * N * N };
  ss_cx *g = tm_hex_grid(N, N, N);
  jitter_interior(g, N, 0.15, r);
  ss_error err = {0};
  CHECK(ss_cx_check_orientation(g, &err) == SS_OK, "jittered grid refused: %s", err.msg);
  ss_cx *p = tm_permuted(g, 5);
  CHECK(ss_cx_check_orientation(p, &err) == SS_OK, "relabelled grid refused: %s",
        err.msg);
  ss_cx_free(p);
  /* mirror a random set of m cells: bottom and top faces swapped */
  const size_t ms[3] = {1, 17, NC - 9};
  for (int t = 0; t < 3; t++) {
    ss_cx *c = NULL;
    ss_cx_copy(g, &c, &err);
    unsigned char flipped[NC] = {0};
    size_t idx[NC];
    for (size_t i = 0; i < NC; i++)
      idx[i] = i;
    gsl_ran_shuffle(r, idx, NC, sizeof *idx);
    for (size_t i = 0; i < ms[t]; i++) {
      ss_idx *h = ss_cx_cell(c, SS_HEX, idx[i]), tmp[4];
      memcpy(tmp, h, sizeof tmp);
      memmove(h, h + 4, sizeof tmp);
      memcpy(h + 4, tmp, sizeof tmp);
      flipped[idx[i]] = 1;
    }
    err.msg[0] = '\0';
    const ss_status st = ss_cx_check_orientation(c, &err);
    size_t named = 0;
    const char *at = strstr(err.msg, "hexahedron ");
    if (at) named = (size_t)strtoul(at + 11, NULL, 10);
    const int minority = ms[t] < NC / 2;
    CHECK(st == SS_EINPUT && strstr(err.msg, "inverted") && named >= 1 && named <= NC &&
              flipped[named - 1] == minority,
          "%zu of %d mirrored: %s", ms[t], NC, err.msg);
    ss_cx_free(c);
  }
  ss_cx_free(g);
  /* a surface in 3D: flatness only (two quads of opposite normals pass) */
  const double sx[6][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},
                           {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  ss_cx *s = NULL;
  ss_cx_new(3, &s, &err);
  for (int i = 0; i < 6; i++)
    ss_cx_add_vertex(s, sx[i], 0, &err);
  const ss_idx q0[4] = {0, 1, 2, 3}, q1[4] = {1, 2, 5, 4};
  ss_cx_add_cell(s, SS_QUAD, q0, 0, &err);
  ss_cx_add_cell(s, SS_QUAD, q1, 0, &err);
  CHECK(ss_cx_check_orientation(s, &err) == SS_OK, "surface in 3D refused: %s", err.msg);
  s->x[5 * 3 + 0] = 1.0, s->x[5 * 3 + 1] = 0.5; /* quad 2 folds flat at corner 5 */
  s->x[4 * 3 + 0] = 1.0, s->x[4 * 3 + 1] = 0.0;
  CHECK(ss_cx_check_orientation(s, &err) == SS_EINPUT && strstr(err.msg, "flat"),
        "a flat quad in 3D accepted: %s", err.msg);
  ss_cx_free(s);
  /* tets with 2 coordinates: every cell flat, refused */
  const double tx[8] = {0, 0, 1, 0, 0, 1, 1, 1};
  ss_cx *c2 = cell(SS_TET, 2, tx, 4, ident);
  CHECK(ss_cx_check_orientation(c2, &err) == SS_EINPUT && strstr(err.msg, "coordinate"),
        "tets in 2D accepted: %s", err.msg);
  ss_cx_free(c2);
}

int main(void) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 17);
  test_symmetries(r);
  test_affine(r);
  test_additive(r);
  test_scale_flat();
  test_check(r);
  gsl_rng_free(r);
  return ss_test_done("cx_orient");
}
