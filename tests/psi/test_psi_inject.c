/* test_psi_inject.c — ψ's winding number on the boundary of the star and
 * the injectivity proven from it (ss_psi_inject):
 *   - the icosahedron (MLCA): a certified pass with its tubes, ψ injective
 *     (proven), winding = the sign of det Dψ, on ncentre x 3 x 4^N squares
 *     (counted independently), and the injectivity verdict a certified pass
 *     judged on ψ;
 *   - the winding number recomputed by another path: ψ by ss_limit_eval (the
 *     runs' eigen-decompositions, not the pieces) at the same grid points,
 *     the surface built by this test's own loops, solid angles summed in
 *     doubles: the same integer;
 *   - a basis change X G with det G = -1: the sign and the winding both flip,
 *     still injective;
 *   - the rules of the proof, each on its edge: the enclosure widened by
 *     1e-9 still decides, widened by 0.5 cannot separate 0 from a hull (not
 *     decided); the wrong sign is not a proof; a cell left out (an open
 *     surface) and every box given twice (edges twice one way) are refused;
 *   - one of the MLCA links with k = 11 whose double net fails injectivity
 *     (overlapping ring cells, not proven): ψ injective, proven;
 *   - a k = 10 link whose tube boxes' patches do not separate 0: decided
 *     through the tubes' children, its winding recomputed by ss_limit_eval. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "psi_case.h"
#include "ss_exact.h"
#include "ss_limit_pieces.h"
#include "ss_psi.h"
#include "ss_psi_inject.h"
#include "ss_test.h"

/* A traversal feeding the boundary module. */
typedef struct {
  ss_psi_inject *b;
  unsigned pbits;
  int twice; /* give every box twice */
  ss_status st;
} trav;

static int skip_octant(size_t cell, int depth, const double o[3], void *arg) {
  const trav *t = arg;
  (void)cell;
  return psi_in_octant(t->pbits, depth, o);
}

static int visit(const ss_limit_piece *pc, void *arg) {
  trav *t = arg;
  ss_error err = {0};
  for (int k = 0; k <= t->twice && !t->st; k++)
    t->st = ss_psi_inject_box(t->b, pc, t->pbits, &err);
  return t->st != SS_OK;
}

/* The boundary decided for p's case with its enclosure widened by delta
 * (basis X diag(g)), skipping cell `leave` (SIZE_MAX: none), at box depth
 * N, judged against sign. */
static int decide(const ss_scheme *s, const ss_pipeline *p, const double *g, double delta,
                  size_t leave, int twice, int N, int sign, ss_psi_inject_result *out) {
  psi_encl e;
  if (psi_encl_get(p, delta, g, &e)) return -1;
  ss_limit *L = psi_limit(s, p, e.mid);
  long maxden = ss_exact_defaults(3).maxden;
  const ss_limit_enclosure en = {e.lo, e.hi, psi_exact_weight, &maxden};
  trav t = {ss_psi_inject_new(p->M, N), 0, twice, SS_OK};
  int rc = L && t.b ? 0 : -1;
  ss_error err = {0};
  for (size_t c = 0; c < p->M->ncells && !rc; c++) {
    const int j = ss_local_centre_corner(p->M, c);
    if (j < 0 || c == leave) continue;
    t.pbits = ss_cube_corner_bits(3, j);
    if (ss_limit_pieces_tubes(L, c, N, &en, psi_exact_rat, &maxden, skip_octant, visit,
                              &t, &err) ||
        t.st)
      rc = -1;
  }
  if (!rc && ss_psi_inject_degree(t.b, sign, out, &err)) rc = -1;
  ss_psi_inject_free(t.b);
  ss_limit_free(L);
  psi_encl_free(&e);
  return rc;
}

/* The signed solid angle of (x, y, z) from 0, in doubles. */
static double solid_angle(const double *x, const double *y, const double *z) {
  const double num = x[0] * (y[1] * z[2] - y[2] * z[1]) -
                     x[1] * (y[0] * z[2] - y[2] * z[0]) +
                     x[2] * (y[0] * z[1] - y[1] * z[0]);
  const double nx = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]),
               ny = sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]),
               nz = sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
  const double xy = x[0] * y[0] + x[1] * y[1] + x[2] * y[2],
               xz = x[0] * z[0] + x[1] * z[1] + x[2] * z[2],
               yz = y[0] * z[0] + y[1] * z[1] + y[2] * z[2];
  return 2.0 * atan2(num, nx * ny * nz + xy * nz + xz * ny + yz * nx);
}

/* The winding number of psi on the faces opposite p, psi by ss_limit_eval
 * at the grid of side 2^-N, each face's squares outward (the face of axis a
 * at its far side: normal +e_a if that side is 1); *squares counted. */
static double winding_by_eval(const ss_scheme *s, const ss_pipeline *p, int N,
                              size_t *squares) {
  psi_encl e;
  *squares = 0;
  if (psi_encl_get(p, 0.0, NULL, &e)) return NAN;
  ss_limit *L = psi_limit(s, p, e.mid);
  double sum = 0.0;
  const int m = 1 << N;
  ss_error err = {0};
  double(*v)[3] = malloc((size_t)(m + 1) * (size_t)(m + 1) * sizeof *v);
  for (size_t c = 0; L && v && c < p->M->ncells; c++) {
    const int j = ss_local_centre_corner(p->M, c);
    if (j < 0) continue;
    const unsigned pb = ss_cube_corner_bits(3, j);
    for (int a = 0; a < 3; a++) {
      const int far = !((pb >> a) & 1u), e1 = (a + 1) % 3, e2 = (a + 2) % 3;
      for (int i = 0; i <= m; i++)
        for (int k = 0; k <= m; k++) {
          double t[3];
          t[a] = far, t[e1] = (double)i / m, t[e2] = (double)k / m;
          ss_limit_point q;
          if (ss_limit_eval(L, c, t[0], t[1], t[2], 0, &q, &err)) {
            sum = NAN;
            continue;
          }
          memcpy(v[i * (m + 1) + k], q.p, sizeof q.p);
        }
      for (int i = 0; i < m; i++)
        for (int k = 0; k < m; k++) {
          const double *c00 = v[i * (m + 1) + k], *c10 = v[(i + 1) * (m + 1) + k],
                       *c11 = v[(i + 1) * (m + 1) + k + 1], *c01 = v[i * (m + 1) + k + 1];
          const double w = solid_angle(c00, c10, c11) + solid_angle(c00, c11, c01);
          sum += far ? w : -w;
          ++*squares;
        }
    }
  }
  free(v);
  ss_limit_free(L);
  psi_encl_free(&e);
  return sum / (4.0 * M_PI);
}

static void icosahedron(const ss_scheme *s) {
  ss_pipeline *p = psi_run_tubes(s, "icosahedron", 1);
  CHECK(p && p->psi.ran && p->psi.verdict.certified,
        "icosahedron: a certified pass on psi");
  if (!p || !p->psi.ran) return;
  const ss_psi_result *r = &p->psi;
  const size_t want = p->M->ncentre * 3 * 16;
  CHECK(r->inject == 1 && r->degree == r->sign && r->boundary_squares == want,
        "icosahedron: psi injective, winding %d = sign %d, %zu squares (want %zu): %s",
        r->degree, r->sign, r->boundary_squares, want, r->inject_why);
  ss_verdict reg = p->reg.verdict, inj = p->inj.verdict;
  ss_psi_apply(r, 1, &reg, &inj);
  CHECK(inj.verdict == SS_PASS && inj.certified && inj.on == SS_ON_PSI,
        "icosahedron: injectivity a certified pass judged on psi (%s)", inj.reason);
  size_t nsq;
  const double w = winding_by_eval(s, p, 2, &nsq);
  CHECK(nsq == want && fabs(w - r->degree) < 1e-6,
        "icosahedron: ss_limit_eval's surface winds %.12g times (%zu squares), the proof "
        "%d",
        w, nsq, r->degree);
  ss_psi_inject_result a;
  const double flip[3] = {1, -1, 1};
  CHECK(!decide(s, p, flip, 0.0, SIZE_MAX, 0, 2, -r->sign, &a) && a.decided == 1 &&
            a.degree == -r->degree,
        "basis X G (det G = -1): winding %d (was %d), injective (%s)", a.degree,
        r->degree, a.why);
  CHECK(!decide(s, p, NULL, 1e-9, SIZE_MAX, 0, 2, r->sign, &a) && a.decided == 1,
        "enclosure widened by 1e-9: still injective (%s)", a.why);
  CHECK(!decide(s, p, NULL, 0.5, SIZE_MAX, 0, 2, r->sign, &a) && a.decided == 0 &&
            strstr(a.why, "not separated"),
        "enclosure widened by 0.5: 0 not separated, not decided (%s)", a.why);
  CHECK(!decide(s, p, NULL, 0.0, SIZE_MAX, 0, 2, -r->sign, &a) && a.decided == 0 &&
            a.degree == r->degree,
        "the other sign: winding %d is no proof (%s)", a.degree, a.why);
  size_t first = 0;
  while (first < p->M->ncells && ss_local_centre_corner(p->M, first) < 0)
    first++;
  CHECK(!decide(s, p, NULL, 0.0, first, 0, 2, r->sign, &a) && a.decided == 0 &&
            strstr(a.why, "not closed"),
        "a cell left out: an open surface, not decided (%s)", a.why);
  CHECK(!decide(s, p, NULL, 0.0, SIZE_MAX, 1, 2, r->sign, &a) && a.decided == 0 &&
            strstr(a.why, "not closed"),
        "every box twice: not a surface, not decided (%s)", a.why);
  ss_pipeline_free(p);
}

/* A k = 10 link whose boundary needs the tubes' children: at box depth 2 the
 * tube boxes' patches do not separate 0, the grid is refined into their
 * children ((A_b (x) F) P and (A_b (x) G_c) P, exact weights enclosed): psi
 * injective, on more squares than the box depth's, and its winding the one
 * ss_limit_eval's points give. */
static void tube_children(const ss_scheme *s) {
  const char *link = "10 bcdefghi,aic,abid,acie,adif,aeihjg,afjh,agjfi,ahfedcb,fhg";
  ss_pipeline *p = psi_run_tubes(s, link, 1);
  CHECK(p && p->psi.ran, "%s: psi judged", link);
  if (!p || !p->psi.ran) return;
  const ss_psi_result *r = &p->psi;
  CHECK(r->inject == 1 && r->boundary_squares > p->M->ncentre * 3 * 16,
        "%s: injective on %zu squares (the box depth's: %zu): %s", link,
        r->boundary_squares, p->M->ncentre * 3 * 16, r->inject_why);
  size_t nsq;
  const double w = winding_by_eval(s, p, 3, &nsq);
  CHECK(fabs(w - r->degree) < 1e-6,
        "%s: ss_limit_eval's surface winds %.12g, the proof %d", link, w, r->degree);
  ss_pipeline_free(p);
}

/* A k = 11 link whose ψ the tubes prove regular and whose double net's ring
 * cells overlap (injectivity fails on the net, not proven). */
static void net_overlaps(const ss_scheme *s) {
  const char *link =
      "11 bcdefgh,ahc,abhd,achie,adijgf,aeg,afejkih,agidcb,dhgkje,eikg,gji";
  ss_pipeline *p = psi_run_tubes(s, link, 1);
  CHECK(p && p->psi.ran, "%s: psi judged", link);
  if (!p || !p->psi.ran) return;
  CHECK(p->inj.verdict.verdict == SS_FAIL && p->psi.inject == 1,
        "the net's injectivity %s, psi's: %s", ss_verdict_name(p->inj.verdict.verdict),
        p->psi.inject_why);
  ss_pipeline_free(p);
}

int main(void) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  REQUIRE_OK(ss_scheme_new("mlca", &s, &err), &err);
  icosahedron(s);
  net_overlaps(s);
  tube_children(s);
  ss_scheme_free(s);
  return ss_test_done("test_psi_inject");
}
