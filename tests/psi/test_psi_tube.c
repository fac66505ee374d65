/* test_psi_tube.c — det Dψ's sign proven in the tubes round the spokes
 * (ss_psi_tube, ss_limit_tube, ss_psi_piece_sign_interval3):
 *   - the three-net Bernstein test with three equal nets is the one-net test
 *     (the same coefficients, the same verdicts);
 *   - the icosahedron (MLCA, 12 spokes of valence 5): every uncovered box of
 *     the ring at depth 2 has a tube, proven of the ring's sign; the proven
 *     sign agrees with det Dψ computed by the limit evaluator (ss_limit_eval:
 *     eigen-decomposition of the stationary runs, another path) at points
 *     2^-m off the spoke in each quadrant, m = 1..40;
 *   - a basis change X G with det G < 0: every tube proven of the other sign;
 *   - a tube built to fold (its spoke's curve turned back inside the box: the
 *     last layer replaced by the first, so a' changes sign): not proven, both
 *     signs found; a degenerate one (every layer the same points: a' = 0): not
 *     proven;
 *   - ss_psi_certify: the icosahedron's ψ a certified pass with its tubes;
 *     k = 10 links whose net is undecided: certified pass on ψ;
 *   - on the edge of the proof: the points' enclosure widened by 1e-9 of its
 *     spread, every tube still proven; by 10 %, none;
 *   - a k = 12 link whose tube folds at layer 1: a certified failure on ψ,
 *     its two witnesses (in one layer of the tube) of opposite signs, and
 *     det Dψ there recomputed by ss_limit_eval on the enclosure's midpoints
 *     inside their enclosures (to 1e-9 relative: another path, doubles);
 *   - a k = 12 link whose tail needed the powers of N / mu formed as
 *     products of two earlier ones (by steps of N / mu their balls grow
 *     wider than the powers near layer 75): a certified pass with its tubes;
 *   - refusals: a tube without an enclosure (SS_EINPUT). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "psi_case.h"
#include "ss_exact.h"
#include "ss_limit_pieces.h"
#include "ss_psi.h"
#include "ss_psi_bernstein.h"
#include "ss_psi_tube.h"
#include "ss_test.h"

/* What the traversal of the tubes found. */
typedef struct {
  ss_limit *L;    /* the two-ring's evaluator (midpoint net) */
  unsigned pbits; /* the centre's corner of the current cell */
  long maxden;
  size_t boxes;                  /* uncovered boxes */
  size_t tubes;                  /* with a tube */
  size_t proven[2];              /* proven positive, negative */
  size_t evals, agree;           /* ss_limit_eval's signs checked, agreeing */
  int mutate;                    /* 0 none, 1 fold (layer 3 := layer 0), 2 degenerate */
  size_t folded;                 /* mutated tubes: "both signs" reported */
  char why[200];                 /* the first unproven tube's reason */
  ss_psi_tube_cache *cache;      /* F's analyses, or NULL (each tube alone) */
  size_t hist[65];               /* proven tubes by the layers they judged directly */
  double mu_lo, mu_hi, ratio_hi; /* the range of mu and |next| / mu met */
} trav;

static int skip_octant(size_t cell, int depth, const double o[3], void *arg) {
  const trav *t = arg;
  (void)cell;
  return psi_in_octant(t->pbits, depth, o);
}

/* det Dψ by ss_limit_eval at points 2^-m off the spoke in each quadrant of
 * the box: each must have the proven sign s. */
static void check_eval(trav *t, const ss_limit_piece *pc, int s) {
  const ss_limit_tube *u = pc->tube;
  const double h = ldexp(1.0, -pc->depth);
  for (int c = 0; c < 3; c++)
    for (int m = 1; m <= 40; m += 3) {
      double x[3];
      x[u->axis] = pc->origin[u->axis] + h * 0.37;
      for (int k = 0; k < 2; k++) {
        const int a = u->across[k];
        const int at_hi = (int)((u->corner >> a) & 1u),
                  q_hi = (int)((u->quad[c] >> a) & 1u);
        /* inside quadrant c of the layer m: offset 2^-m (0.3 or 0.7) of the box
         * from the spoke's corner, towards the quadrant */
        const double f = ldexp(q_hi == at_hi ? 0.3 : 0.7, -m);
        x[a] = pc->origin[a] + h * (at_hi ? 1.0 - f : f);
      }
      ss_limit_point lp;
      ss_error err = {0};
      if (ss_limit_eval(t->L, pc->cell, x[0], x[1], x[2], 1, &lp, &err)) continue;
      double J[3][3];
      memcpy(J, lp.jac, sizeof J);
      const double d = psi_det3(J);
      t->evals++;
      t->agree += (d > 0.0 ? 1 : d < 0.0 ? -1 : 0) == s;
    }
}

static int visit(const ss_limit_piece *pc, void *arg) {
  trav *t = arg;
  if (pc->net) return 0;
  t->boxes++;
  if (!pc->tube) return 0;
  t->tubes++;
  ss_limit_tube u = *pc->tube;
  double *lo = NULL, *hi = NULL;
  if (t->mutate) {
    const size_t n = 3 * u.ncol;
    lo = malloc(4 * n * sizeof *lo), hi = malloc(4 * n * sizeof *hi);
    memcpy(lo, u.lo, 4 * n * sizeof *lo);
    memcpy(hi, u.hi, 4 * n * sizeof *hi);
    if (t->mutate <= 2) {
      for (int l = 1; l < 4; l++)
        if (t->mutate == 2 || l == 3) {
          memcpy(lo + (size_t)l * n, u.lo, n * sizeof *lo);
          memcpy(hi + (size_t)l * n, u.hi, n * sizeof *hi);
        }
    } else { /* widened by a share of the points' spread: 1e-9 (3), 0.1 (4) */
      double mn = INFINITY, mx = -INFINITY;
      for (size_t i = 0; i < 4 * n; i++)
        mn = fmin(mn, lo[i]), mx = fmax(mx, hi[i]);
      const double d = (t->mutate == 3 ? 1e-9 : 0.1) * (mx - mn);
      for (size_t i = 0; i < 4 * n; i++)
        lo[i] -= d, hi[i] += d;
    }
    u.lo = lo, u.hi = hi;
  }
  ss_psi_tube_result r;
  ss_error err = {0};
  if (ss_psi_tube_sign(&u, t->maxden, 4, t->cache, &r, &err)) {
    fprintf(stderr, "tube: %s\n", err.msg);
  } else if (r.sign) {
    t->proven[r.sign > 0 ? 0 : 1]++;
    t->hist[r.layers < 64 ? r.layers : 64]++;
    if (t->mu_lo == 0.0 || r.mu < t->mu_lo) t->mu_lo = r.mu;
    if (r.mu > t->mu_hi) t->mu_hi = r.mu;
    if (r.ratio > t->ratio_hi) t->ratio_hi = r.ratio;
    if (!t->mutate && t->L) check_eval(t, pc, r.sign);
  } else {
    if (!t->why[0]) snprintf(t->why, sizeof t->why, "%.190s", r.why);
    t->folded += strstr(r.why, "both signs") != NULL;
  }
  free(lo);
  free(hi);
  return 0;
}

/* Every uncovered box of the ring of `link` at depth 2, with the basis's
 * columns times g. */
static int tubes_of(const ss_scheme *s, const ss_pipeline *p, const double g[3],
                    int mutate, int eval, trav *t) {
  memset(t, 0, sizeof *t);
  psi_encl e;
  if (psi_encl_get(p, 0.0, g, &e)) return -1;
  t->maxden = ss_exact_defaults(3).maxden;
  t->mutate = mutate;
  t->cache = mutate == 2 ? NULL : ss_psi_tube_cache_new(); /* one run without */
  ss_limit *L = psi_limit(s, p, e.mid);
  if (eval) t->L = L;
  const ss_limit_enclosure en = {e.lo, e.hi, psi_exact_weight, &t->maxden};
  ss_error err = {0};
  int rc = L ? 0 : -1;
  for (size_t c = 0; c < p->M->ncells && !rc; c++) {
    const int j = ss_local_centre_corner(p->M, c);
    if (j < 0) continue;
    t->pbits = ss_cube_corner_bits(3, j);
    if (ss_limit_pieces_tubes(L, c, 2, &en, psi_exact_rat, &t->maxden, skip_octant, visit,
                              t, &err)) {
      fprintf(stderr, "pieces: %s\n", err.msg);
      rc = -1;
    }
  }
  ss_limit_free(L);
  ss_psi_tube_cache_free(t->cache);
  t->cache = NULL;
  psi_encl_free(&e);
  return rc;
}

/* ss_psi_piece_sign_interval3 with one net thrice is the one-net test; on
 * three affine maps det[∂_u N0 | ∂_v N1 | ∂_w N2] is det[A0 e_u | A1 e_v |
 * A2 e_w], a constant whose sign it must find. */
static void three_nets(void) {
  double net[64][3], lo[64][3], hi[64][3];
  unsigned seed = 7;
  for (int q = 0; q < 64; q++)
    for (int d = 0; d < 3; d++) {
      seed = seed * 1103515245u + 12345u;
      const double e = 0.2 * ((double)(seed >> 16 & 0x7fff) / 32767.0 - 0.5);
      const int ix[3] = {q % 4, (q / 4) % 4, q / 16};
      net[q][d] = ix[d] + e * (d == 0 ? 1.0 : 0.5);
      lo[q][d] = net[q][d] - 1e-12;
      hi[q][d] = net[q][d] + 1e-12;
    }
  typedef const double(*cnet)[3];
  const cnet cl = (cnet)lo, ch = (cnet)hi;
  const double(*l3[3])[3] = {cl, cl, cl}, (*h3[3])[3] = {ch, ch, ch};
  ss_psi_piece_result a, b;
  ss_psi_piece_sign_interval(cl, ch, 4, &a);
  ss_psi_piece_sign_interval3(l3, h3, 4, &b);
  CHECK(a.sign == b.sign && a.boxes == b.boxes && a.min_coef == b.min_coef &&
            a.max_coef == b.max_coef && a.sign == SS_JAC_POSITIVE,
        "three equal nets: the one-net verdict (%d/%d, %ld/%ld boxes)", (int)a.sign,
        (int)b.sign, a.boxes, b.boxes);
  /* three affine maps t -> A_k t: column k of the Jacobian is A_k e_k */
  static const double A[3][3][3] = {{{1, 0, 0}, {0.5, 2, 0}, {0, 0.3, 1}},
                                    {{0, 1, 0}, {0, 1, 0.2}, {1, 0, 0}},
                                    {{0.1, 0, 1}, {0, 0.4, -1}, {0.3, 0, 2}}};
  for (int flipz = 0; flipz < 2; flipz++) {
    double nl[3][64][3], nh[3][64][3];
    for (int k = 0; k < 3; k++)
      for (int q = 0; q < 64; q++) {
        const double t[3] = {q % 4 - 1.0, (q / 4) % 4 - 1.0, q / 16 - 1.0};
        for (int d = 0; d < 3; d++) {
          double v = 0.0;
          for (int j = 0; j < 3; j++)
            v += A[k][j][d] * t[j];
          if (flipz && d == 2) v = -v;
          nl[k][q][d] = v - 1e-13, nh[k][q][d] = v + 1e-13;
        }
      }
    double J[3][3];
    for (int k = 0; k < 3; k++)
      for (int d = 0; d < 3; d++)
        J[k][d] = A[k][k][d] * (flipz && d == 2 ? -1.0 : 1.0);
    const double det = psi_det3(J);
    const double(*L[3])[3] = {(cnet)nl[0], (cnet)nl[1], (cnet)nl[2]},
          (*H[3])[3] = {(cnet)nh[0], (cnet)nh[1], (cnet)nh[2]};
    ss_psi_piece_sign_interval3(L, H, 2, &b);
    CHECK(det != 0.0 && b.sign == (det > 0 ? SS_JAC_POSITIVE : SS_JAC_NEGATIVE) &&
              fabs(b.min_coef - det) <= 1e-9 * fabs(det),
          "three affine nets: sign of det %g found (coefficient %g)", det, b.min_coef);
  }
}

static void icosahedron(const ss_scheme *s) {
  ss_pipeline *p = psi_run(s, "icosahedron", 2, 1);
  CHECK(p && p->ex, "icosahedron: certified pipeline");
  if (!p || !p->ex) return;
  trav t;
  const double id[3] = {1, 1, 1}, flip[3] = {1, -1, 1};
  CHECK(!tubes_of(s, p, id, 0, 1, &t), "icosahedron: tubes traversed");
  printf("icosahedron: %zu uncovered boxes, %zu tubes, proven %zu+ %zu-; det Dpsi by "
         "ss_limit_eval %zu of %zu of the proven sign\n",
         t.boxes, t.tubes, t.proven[0], t.proven[1], t.agree, t.evals);
  CHECK(t.boxes > 0 && t.tubes == t.boxes && t.proven[0] + t.proven[1] == t.tubes &&
            (t.proven[0] == 0 || t.proven[1] == 0),
        "icosahedron: every tube proven, of one sign (%s)", t.why);
  CHECK(t.evals > 1000 && t.agree == t.evals,
        "icosahedron: ss_limit_eval's det Dpsi 2^-1..2^-40 off the spokes has the proven "
        "sign (%zu of %zu)",
        t.agree, t.evals);
  const size_t neg = t.proven[1];
  CHECK(!tubes_of(s, p, flip, 0, 0, &t) && t.tubes > 0 &&
            t.proven[0] + t.proven[1] == t.tubes && t.proven[0] == neg,
        "basis X G (det G = -1): every tube proven, of the other sign (%zu+ %zu-)",
        t.proven[0], t.proven[1]);
  CHECK(!tubes_of(s, p, id, 1, 0, &t) && t.proven[0] + t.proven[1] == 0 && t.folded > 0,
        "tubes whose spoke curve turns back: none proven, %zu fold (%s)", t.folded,
        t.why);
  CHECK(!tubes_of(s, p, id, 2, 0, &t) && t.proven[0] + t.proven[1] == 0,
        "tubes with a' = 0 (degenerate): none proven (%s)", t.why);
  /* the proof on both sides of its edge: it uses the points' enclosure */
  CHECK(!tubes_of(s, p, id, 3, 0, &t) && t.proven[1] == t.tubes && t.tubes > 0,
        "enclosure widened by 1e-9 of its spread: every tube still proven (%zu of %zu)",
        t.proven[1], t.tubes);
  CHECK(!tubes_of(s, p, id, 4, 0, &t) && t.proven[0] + t.proven[1] == 0,
        "enclosure widened by 10 %% of its spread: no tube proven (%s)", t.why);
  ss_pipeline_free(p);
}

/* ss_psi_certify (through the pipeline): the verdict a proven pass on psi
 * with its tubes; the net had left k = 10's links undecided. */
static void certified(const ss_scheme *s, const char *link) {
  ss_pipeline *q = psi_run_tubes(s, link, 0);
  CHECK(q && q->psi.ran && !q->psi.verdict.certified && q->psi.ntubes == 0,
        "%s: without psi_tubes no proven verdict on psi (the tubes not proven)", link);
  ss_pipeline_free(q);
  ss_pipeline *p = psi_run_tubes(s, link, 1);
  CHECK(p && p->psi.ran && p->psi.enclosed, "%s: psi judged on an enclosure", link);
  if (p && p->psi.ran) {
    const ss_psi_result *r = &p->psi;
    ss_verdict reg = p->reg.verdict, inj = p->inj.verdict;
    ss_psi_apply(r, 1, &reg, &inj);
    CHECK(p->reg.verdict.verdict == SS_UNDECIDED && r->verdict.verdict == SS_PASS &&
              r->verdict.certified && r->ntubes > 0 && r->ntubes == r->nuncovered &&
              reg.verdict == SS_PASS && reg.certified && reg.on == SS_ON_PSI,
          "%s: the net undecided, psi a certified pass with %zu of %zu tubes (%s)", link,
          r->ntubes, r->nuncovered, r->verdict.reason);
  }
  ss_pipeline_free(p);
}

/* A link whose tube folds (MLCA k = 12, found by reports/tubes.sh): the
 * failure proven on psi, its witnesses checked by ss_limit_eval. */
static void tube_fold(const ss_scheme *s, const char *link) {
  ss_pipeline *p = psi_run_tubes(s, link, 1);
  CHECK(p && p->psi.ran && p->psi.enclosed, "%s: psi judged on an enclosure", link);
  if (!p || !p->psi.ran) {
    ss_pipeline_free(p);
    return;
  }
  const ss_psi_result *r = &p->psi;
  ss_verdict reg = p->reg.verdict, inj = p->inj.verdict;
  ss_psi_apply(r, 1, &reg, &inj);
  CHECK(r->verdict.verdict == SS_FAIL && r->verdict.certified && r->nwitness == 2 &&
            r->tube_fold_layer >= 0 && reg.verdict == SS_FAIL && reg.certified &&
            reg.on == SS_ON_PSI && inj.verdict == SS_FAIL && inj.on == SS_ON_PSI,
        "%s: psi folds in a tube, proven (%s)", link, r->verdict.reason);
  CHECK(!strncmp(r->verdict.reason, "psi folds: det Dpsi in [", 24) &&
            strstr(r->verdict.reason, "both in the tube round a spoke, its layer"),
        "%s: the reason names the witnesses and the tube: %s", link, r->verdict.reason);
  const ss_psi_point *w = r->witness;
  CHECK(
      w[0].det[0] <= w[0].det[1] && w[1].det[0] <= w[1].det[1] &&
          ((w[0].det[0] > 0 && w[1].det[1] < 0) || (w[0].det[1] < 0 && w[1].det[0] > 0)),
      "%s: witnesses [%g, %g] and [%g, %g] of opposite strict signs", link, w[0].det[0],
      w[0].det[1], w[1].det[0], w[1].det[1]);
  psi_encl e = {0}; /* psi in the certified basis: its enclosure's midpoints */
  ss_limit *L =
      r->nwitness == 2 && !psi_encl_get(p, 0.0, NULL, &e) ? psi_limit(s, p, e.mid) : NULL;
  CHECK(L != NULL, "%s: the enclosed basis as a limit evaluator", link);
  for (int i = 0; i < 2 && L; i++) {
    ss_limit_point pt;
    ss_error err = {0};
    const int ok =
        !ss_limit_eval(L, w[i].cell, w[i].at[0], w[i].at[1], w[i].at[2], 1, &pt, &err);
    const double d = ok ? psi_det3(pt.jac) : (double)NAN, tol = 1e-9 * fabs(w[i].det[0]);
    CHECK(ok && d >= w[i].det[0] - tol && d <= w[i].det[1] + tol,
          "%s: witness %d (cell %zu at %g, %g, %g): det Dpsi %.17g by ss_limit_eval in "
          "[%.17g, %.17g] (%s)",
          link, i, w[i].cell, w[i].at[0], w[i].at[1], w[i].at[2], d, w[i].det[0],
          w[i].det[1], err.msg);
  }
  ss_limit_free(L);
  psi_encl_free(&e);
  ss_pipeline_free(p);
}

static void refusals(void) {
  ss_limit_tube u;
  memset(&u, 0, sizeof u);
  ss_psi_tube_result r;
  ss_error err = {0};
  CHECK(ss_psi_tube_sign(&u, 1 << 18, 4, NULL, &r, &err) == SS_EINPUT && r.sign == 0,
        "a tube without an enclosure: SS_EINPUT (%s)", err.msg);
}

int main(int argc, char **argv) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  REQUIRE_OK(ss_scheme_new("mlca", &s, &err), &err);
  if (argc > 1) { /* a link's tubes, for a look */
    ss_pipeline *p = psi_run(s, argv[1], 2, 1);
    trav t;
    const double id[3] = {1, 1, 1};
    if (p && p->ex && !tubes_of(s, p, id, 0, 1, &t))
      printf("%zu uncovered boxes, %zu tubes, proven %zu+ %zu-; ss_limit_eval %zu of %zu "
             "agree; first not proven: %s\n",
             t.boxes, t.tubes, t.proven[0], t.proven[1], t.agree, t.evals, t.why);
    printf("mu in [%g, %g], |next| / mu <= %g; layers judged directly:", t.mu_lo, t.mu_hi,
           t.ratio_hi);
    for (int m = 0; m < 65; m++)
      if (t.hist[m]) printf(" %d: %zu", m, t.hist[m]);
    printf("\n");
    ss_pipeline_free(p);
  } else {
    three_nets();
    refusals();
    icosahedron(s);
    certified(s, "10 bcdefghi,aic,abid,acie,adihf,aehjg,afjh,agjfei,ahedcb,fhg");
    /* its tail holds from layer 47, not from 63: undecided while the
     * windows doubled to 32 and 63 */
    certified(s, "11 bcdefghijk,akc,abked,ace,adckgf,aeg,afekih,agi,ahgkj,aik,ajigecb");
    certified(
        s, "12 bcdefghij,ajc,abjd,acjfke,adkf,aekdjg,afjlh,aglji,ahj,aihlgfdcb,dfe,gjh");
    tube_fold(
        s, "12 bcdefghij,ajkc,abkd,acke,adkf,aekg,afkh,agkjli,ahlj,ailhkb,bjhgfedc,hji");
  }
  ss_scheme_free(s);
  return ss_test_done("psi_tube");
}
