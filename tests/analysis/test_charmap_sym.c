/* test_charmap_sym.c — the symmetries of a case that its characteristic map
 * does not see, psi o sigma = psi (ss_charmap_symmetry, ss_charmap_sym_perm
 * in ss_charmap_sym.c).
 *
 * Properties:
 *   - every symmetry of a case's star commutes with S for schemes whose rule
 *     is combinatorial (MLCA, Catmull-Clark, Loop, tet/oct), so `tested` is
 *     the order of the star's symmetry group less the identity, a published
 *     value: the tetrahedron link's 24 (S4), the octahedron's 48, the
 *     icosahedron's 120, a bipyramid over n's 4n (D_nh, n != 4); an edge of
 *     valence n: 4n (the dihedral group of the faces around it, times the
 *     flip end for end); a surface vertex of valence n: 2n (D_n); the face
 *     of two tets: 4 (two swaps);
 *   - the maps of these passing cases have no such symmetry (found = 0);
 *   - constructed nets on the regular MLCA vertex and edge (the lattice
 *     coordinates z, through functions with known symmetry): z itself has
 *     none; (|z1|, z2, z3) only the reflection z1 -> -z1 (order 2,
 *     reversing; on the edge also z2 -> -z2, a plane through the edge, and
 *     z3 -> -z3, the flip end for end); (z1^2 - z2^2, 2 z1 z2, z3) only the
 *     half-turn about z3 (order 2, keeping the orientation); a net invariant
 *     under the cyclic permutation of the axes only (order 3, keeping it);
 *   - for every symmetry found, ss_charmap_sym_perm's P is a permutation of
 *     the two-ring with P S = S P exactly, X[P[i]] = X[i] for the net, as
 *     many moved points as `moved`, the lcm of its cycles equal to `order`,
 *     and it reverses orientation iff the linear map it induces on the
 *     lattice coordinates (read here off the images of the three axis
 *     points) has a negative determinant; gap = 2 sin(pi / order);
 *   - the MLCA k = 8 finding (reports/README.md finding 1): found, a
 *     reflection of order 2, for relabelled and mirrored copies of the link
 *     too (a reflection found ends the search: `tested` counts the
 *     symmetries tried until then);
 *   - refused: a case that does not match the map; sym_perm without a
 *     symmetry or with an index out of range.
 * Mutations this catches (tried by hand: the report of issue 33):
 *   - a link automorphism's orientation test inverted (== for !=): the
 *     constructed reflection and half-turn report the wrong `reverses`;
 *   - the order as the product of the cycle lengths instead of their lcm:
 *     the gap 2 sin(pi / order) collapses and nothing is found any more;
 *   - the edge's reflections built as rotations (j + s for s - j): the
 *     half-turn about the regular edge is then reported as a reflection
 *     (its induced map has det +1). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_charmap.h"
#include "ss_link.h"
#include "ss_test.h"
#include "ss_testcase.h"
#include "ss_testlink.h"

static const char *mlca_k8_exception = "8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb";

/* ---- the group orders ---- */

static void check_tested(const char *scheme, ss_case c, int order, const char *what) {
  ss_testcase t;
  if (ss_testcase_run(scheme, c, &t)) return;
  ss_charmap_sym y;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_charmap_symmetry(t.cm, t.M, &c, &y, &err), &err);
  CHECK(y.tested == order - 1, "%s %s: %d symmetries commute with S, the group has %d",
        scheme, what, y.tested, order);
  CHECK(!y.found, "%s %s: psi o sigma = psi found (%s)", scheme, what, y.what);
  ss_testcase_free(&t);
}

static void test_group_orders(void) {
  const char *links[5] = {"tetrahedron", "octahedron", "icosahedron", "bipyramid:3",
                          "bipyramid:5"};
  const int orders[5] = {24, 48, 120, 12, 20};
  for (int i = 0; i < 5; i++) {
    ss_link *l = NULL;
    ss_error err = {0};
    REQUIRE_OK_VOID(ss_link_named(links[i], &l, &err), &err);
    const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
    check_tested("mlca", c, orders[i], links[i]);
    if (i < 2) check_tested("tetoct", c, orders[i], links[i]);
    ss_link_free(l);
  }
  for (int n = 3; n <= 5; n += 2) {
    char what[32];
    snprintf(what, sizeof what, "edge %d", n);
    check_tested("mlca", (ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0}, 4 * n, what);
    check_tested("tetoct", (ss_case){SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0}, 4 * n, what);
    snprintf(what, sizeof what, "surface vertex %d", n);
    check_tested("catmull-clark",
                 (ss_case){SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0}, 2 * n, what);
    check_tested("loop", (ss_case){SS_CASE_SURFACE_VERTEX, NULL, n + 2, SS_DIAG_BFS, 0},
                 2 * (n + 2), what);
  }
  check_tested("tetoct", (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, 4, "face");
}

/* ---- a symmetry found, checked through its permutation ---- */

/* The lattice coordinates of a regular case's labels: z_d = (g[axis[d]] -
 * g[anti[axis[d]]]) / unit[d] (anti -1: none), g the label's chart
 * coordinates.  The regular MLCA vertex (octahedron link): link vertex a and
 * its antipode a' (its one non-neighbour) span an axis (as in test_charmap);
 * the MLCA edge of valence 4: faces 0, 2 and 1, 3 are opposite, coordinate 4
 * the edge, whose chart steps by 2 per grid step (ss_star.h: the hexes span
 * -e_n..e_n along it). */
typedef struct {
  int axis[3], anti[6], unit[3];
} lattice;

static lattice lattice_of(const ss_link *oct) {
  lattice L = {{0, 0, 0}, {0}, {1, 1, 1}};
  int na = 0;
  for (int a = 0; a < 6; a++) {
    int adj[6] = {0};
    for (int q = oct->off[a]; q < oct->off[a + 1]; q++)
      adj[oct->nbr[q]] = 1;
    for (int b = 0; b < 6; b++)
      if (b != a && !adj[b]) L.anti[a] = b;
    if (L.anti[a] > a) L.axis[na++] = a;
  }
  return L;
}

static const lattice edge4 = {{0, 1, 4}, {2, 3, 0, 1, -1, -1}, {1, 1, 2}};

static void coords(const lattice *L, const ss_star_coord *l, double z[3]) {
  double g[6] = {0};
  for (int e = 0; e < l->n; e++)
    g[l->idx[e]] = l->val[e];
  for (int d = 0; d < 3; d++) {
    const int a = L->axis[d], b = L->anti[a];
    z[d] = (g[a] - (b >= 0 ? g[b] : 0.0)) / L->unit[d];
  }
}

/* The symmetry y found for t's net: its permutation against y's fields; for
 * a regular case (L not NULL) also the orientation through the induced map
 * on the lattice coordinates. */
static void check_found(const ss_testcase *t, const ss_case *c, const ss_charmap_sym *y,
                        const lattice *L, const char *what) {
  const size_t n = t->M->n2;
  size_t *P = malloc(n * sizeof *P);
  unsigned char *seen = calloc(n, 1);
  ss_error err = {0};
  if (ss_charmap_sym_perm(t->M, c, y, P, &err)) {
    CHECK(0, "%s: sym_perm: %s", what, err.msg);
    goto done;
  }
  int perm = 1;
  size_t moved = 0;
  for (size_t i = 0; i < n; i++) {
    perm &= P[i] < n && !seen[P[i]];
    if (P[i] < n) seen[P[i]] = 1;
    moved += P[i] != i;
  }
  CHECK(perm, "%s: P is not a permutation", what);
  if (!perm) goto done;
  size_t noncomm = 0;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      noncomm += t->M->S[P[i] * n + P[j]] != t->M->S[i * n + j];
  CHECK(noncomm == 0, "%s: P S != S P in %zu entries", what, noncomm);
  double off = 0.0;
  const int m = t->cm->dim;
  for (size_t i = 0; i < n; i++)
    for (int d = 0; d < m; d++)
      off = fmax(off, fabs(t->cm->x[P[i] * (size_t)m + (size_t)d] -
                           t->cm->x[i * (size_t)m + (size_t)d]));
  CHECK(off <= 1e-9, "%s: psi o sigma differs from psi by %g", what, off);
  CHECK(moved == y->moved, "%s: moves %zu points, y says %zu", what, moved, y->moved);
  /* the order: lcm of the cycle lengths */
  long order = 1;
  memset(seen, 0, n);
  for (size_t i = 0; i < n; i++) {
    long len = 0;
    for (size_t j = i; !seen[j]; j = P[j], len++)
      seen[j] = 1;
    if (!len) continue;
    long a = order, b = len;
    while (b) {
      const long r = a % b;
      a = b;
      b = r;
    }
    order = order / a * len;
  }
  CHECK(order == y->order, "%s: order %ld, y says %d", what, order, y->order);
  CHECK_CLOSE(y->gap, 2.0 * sin(M_PI / (double)order), 1e-15, "%s: gap", what);
  if (L) {
    /* the images of the three axis points z = e_d give the induced map's
     * columns */
    double Lm[9];
    for (int d = 0; d < 3; d++) {
      const int32_t idx[1] = {L->axis[d]}, val[1] = {L->unit[d]};
      const ss_star_coord e = ss_star_coord_make(1, idx, val);
      const size_t i = ss_local_label_index(t->M, &e);
      double z[3] = {0, 0, 0};
      if (i < n) coords(L, t->M->label + P[i], z);
      for (int r = 0; r < 3; r++)
        Lm[r * 3 + d] = z[r];
    }
    const double det = Lm[0] * (Lm[4] * Lm[8] - Lm[5] * Lm[7]) -
                       Lm[1] * (Lm[3] * Lm[8] - Lm[5] * Lm[6]) +
                       Lm[2] * (Lm[3] * Lm[7] - Lm[4] * Lm[6]);
    CHECK(fabs(fabs(det) - 1.0) <= 1e-12 && (det < 0) == (y->reverses != 0),
          "%s: induced map det %g, y says reverses %d", what, det, y->reverses);
  }
done:
  free(P);
  free(seen);
}

/* A regular case (its group of `group` symmetries) with its net replaced by
 * f(z), then the symmetry test; expectations: found, order, reverses. */
static void constructed(ss_testcase *t, const ss_case *c, const lattice *L, int group,
                        int which, int found, int order, int reverses, const char *what) {
  for (size_t i = 0; i < t->cm->n; i++) {
    double z[3], *x = t->cm->x + 3 * i;
    coords(L, t->M->label + i, z);
    /* a small generic linear map G keeps the nets from being special beyond
     * their symmetry (G commutes with nothing the functions respect) */
    const double G[9] = {1.0, 0.2, -0.1, 0.3, 0.9, 0.05, -0.2, 0.1, 1.1};
    double f[3];
    switch (which) {
    case 0: /* z: no symmetry */
      f[0] = z[0], f[1] = z[1], f[2] = z[2];
      break;
    case 1: /* the reflection z1 -> -z1 */
      f[0] = fabs(z[0]), f[1] = z[1], f[2] = z[2];
      break;
    case 4: /* the reflection z2 -> -z2 */
      f[0] = z[0], f[1] = fabs(z[1]), f[2] = z[2];
      break;
    case 5: /* the reflection z3 -> -z3 */
      f[0] = z[0], f[1] = z[1], f[2] = fabs(z[2]);
      break;
    case 2: /* the half-turn about z3 */
      f[0] = z[0] * z[0] - z[1] * z[1], f[1] = 2.0 * z[0] * z[1], f[2] = z[2];
      break;
    default: /* the cyclic permutation of the axes */
      f[0] = z[0] + z[1] + z[2];
      f[1] = z[0] * z[0] * z[1] + z[1] * z[1] * z[2] + z[2] * z[2] * z[0];
      f[2] = z[0] * z[1] * z[1] + z[1] * z[2] * z[2] + z[2] * z[0] * z[0] + 0.3 * f[0];
      break;
    }
    for (int r = 0; r < 3; r++)
      x[r] = G[r * 3] * f[0] + G[r * 3 + 1] * f[1] + G[r * 3 + 2] * f[2];
  }
  ss_charmap_sym y;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_charmap_symmetry(t->cm, t->M, c, &y, &err), &err);
  /* all are tested unless a reflection is found, which ends the search */
  CHECK(found && reverses ? y.tested >= 1 && y.tested <= group - 1
                          : y.tested == group - 1,
        "%s: %d symmetries tested", what, y.tested);
  CHECK(y.found == found && (!found || (y.order == order && y.reverses == reverses &&
                                        y.distance < 1e-9 && y.moved > 0)),
        "%s: found %d (want %d), order %d (%d), reverses %d (%d), distance %g (%s)", what,
        y.found, found, y.order, order, y.reverses, reverses, y.distance, y.what);
  if (y.found) check_found(t, c, &y, L, what);
}

static void test_constructed(void) {
  ss_link *oct = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_link_named("octahedron", &oct, &err), &err);
  const ss_case c = {SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0};
  ss_testcase t;
  if (!ss_testcase_run("mlca", c, &t)) {
    const lattice L = lattice_of(oct);
    constructed(&t, &c, &L, 48, 0, 0, 0, 0, "vertex: the lattice net");
    constructed(&t, &c, &L, 48, 1, 1, 2, 1, "vertex: (|z1|, z2, z3)");
    constructed(&t, &c, &L, 48, 2, 1, 2, 0, "vertex: (z1^2 - z2^2, 2 z1 z2, z3)");
    constructed(&t, &c, &L, 48, 3, 1, 3, 0, "vertex: a net of cyclic symmetry");
    /* refused: the case does not match the map */
    ss_link *tet = NULL;
    ss_charmap_sym y;
    REQUIRE_OK_VOID(ss_link_named("tetrahedron", &tet, &err), &err);
    const ss_case wrong = {SS_CASE_VERTEX, tet, 0, SS_DIAG_BFS, 0};
    CHECK(ss_charmap_symmetry(t.cm, t.M, &wrong, &y, &err) == SS_EINPUT,
          "a tetrahedron case for the octahedron's map accepted");
    /* (an edge of valence 5 has the vertex's chart dimension, 6, and is
     * not told apart: the case must be the one M was made from) */
    const ss_case edge = {SS_CASE_EDGE, NULL, 3, SS_DIAG_BFS, 0};
    CHECK(ss_charmap_symmetry(t.cm, t.M, &edge, &y, &err) == SS_EINPUT,
          "an edge case for a vertex map accepted");
    size_t *P = malloc(t.M->n2 * sizeof *P);
    memset(&y, 0, sizeof y);
    CHECK(ss_charmap_sym_perm(t.M, &c, &y, P, &err) == SS_EINPUT,
          "sym_perm without a symmetry");
    y.found = 1, y.index = 47;
    CHECK(ss_charmap_sym_perm(t.M, &c, &y, P, &err) == SS_EINPUT,
          "sym_perm with index 47 of 47 symmetries");
    free(P);
    ss_link_free(tet);
    ss_testcase_free(&t);
  }
  ss_link_free(oct);
  /* the regular MLCA edge (valence 4): a reflection through a plane holding
   * the edge (faces 1 and 3 exchanged), the flip end for end, the half-turn
   * about the edge */
  const ss_case e4 = {SS_CASE_EDGE, NULL, 4, SS_DIAG_BFS, 0};
  if (!ss_testcase_run("mlca", e4, &t)) {
    constructed(&t, &e4, &edge4, 16, 0, 0, 0, 0, "edge: the lattice net");
    constructed(&t, &e4, &edge4, 16, 4, 1, 2, 1, "edge: (z1, |z2|, z3)");
    constructed(&t, &e4, &edge4, 16, 5, 1, 2, 1, "edge: (z1, z2, |z3|)");
    constructed(&t, &e4, &edge4, 16, 2, 1, 2, 0, "edge: (z1^2 - z2^2, 2 z1 z2, z3)");
    ss_testcase_free(&t);
  }
}

/* ---- the finding, and relabelling ---- */

static void test_finding(void) {
  ss_link *l = NULL;
  ss_error err = {0};
  REQUIRE_OK_VOID(ss_link_parse(mlca_k8_exception, &l, &err), &err);
  for (int q = 0; q < 4; q++) {
    ss_link *s = q ? ss_testlink_scrambled(l, (unsigned)(40 + q), q & 1) : NULL;
    const ss_link *use = q ? s : l;
    if (!use) continue;
    const ss_case c = {SS_CASE_VERTEX, use, 0, SS_DIAG_BFS, 0};
    ss_testcase t;
    if (ss_testcase_run("mlca", c, &t)) {
      ss_link_free(s);
      continue;
    }
    char what[64];
    snprintf(what, sizeof what, "k = 8 finding, copy %d", q);
    ss_charmap_sym y;
    REQUIRE_OK_VOID(ss_charmap_symmetry(t.cm, t.M, &c, &y, &err), &err);
    int naut = 0, *aut = NULL;
    REQUIRE_OK_VOID(ss_link_automorphisms(use, &aut, &naut, &err), &err);
    free(aut);
    /* a reflection ends the search: at most naut - 1 tested */
    CHECK(y.found && y.order == 2 && y.reverses && y.distance < 1e-10 && y.tested >= 1 &&
              y.tested <= naut - 1,
          "%s: found %d, order %d, reverses %d, distance %g, tested %d of %d", what,
          y.found, y.order, y.reverses, y.distance, y.tested, naut - 1);
    if (y.found) check_found(&t, &c, &y, NULL, what);
    ss_testcase_free(&t);
    ss_link_free(s);
  }
  ss_link_free(l);
}

int main(void) {
  test_group_orders();
  test_constructed();
  test_finding();
  return ss_test_done("charmap_sym");
}
