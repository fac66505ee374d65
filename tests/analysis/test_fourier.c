/* test_fourier.c — the certified path for surface vertices and edges whose
 * local matrix is not rational (ss_fourier: Fourier blocks in ball arithmetic; ss_certify
 * takes it where ss_exact cannot read S).
 *
 * Known answers, computed independently of the program in arb at 200 bits
 * from Loop's closed forms (the one-ring of a valence-n vertex on Fourier
 * mode k: 3/8 + cos(2 pi k / n) / 4 for 0 < k < n; on mode 0, 1 and
 * 5/8 - n beta = (3/8 + cos(2 pi / n) / 4)^2):
 *   - Loop's surface vertices of valence 3..20: condition and regularity a
 *     certified pass (before: undecided at every valence but 3, 4, 6); where
 *     cos(2 pi / n) is irrational no exact spectrum is returned (the balls
 *     decided); lambda0 = 1 on mode 0; lambda1 = lambda2 = 3/8 + cos(2 pi /
 *     n) / 4, one real ball of multiplicity 2 on mode 1; every closed form
 *     above inside a ball of its mode; the multiplicities add up to S's size;
 *   - data/stencils/loop.ini (weights with cos(2*pi/n), which the exact path
 *     refuses) certified as the built-in at valences 3..12, its balls
 *     holding the same closed forms;
 *   - tet/oct edges of valence 3..7 from a stencil whose oct weight 3/8 is
 *     written 3/8 + cos(2*pi/n)/32 - cos(2*pi/n)/32 (so the exact path
 *     refuses it) proven passes as the built-in is by the exact path, each
 *     of the exact path's five leading roots inside the balls with its
 *     multiplicity (an independent computation: rational charpolys);
 *   - a hand-made rotation-invariant matrix (centre + a ring of 7, no outer
 *     points) whose mode-0 eigenvalue 0.7 lies above the mode-1 pair 0.5: a
 *     certified fail, "exact tie" lambda2 = lambda3; with the pair above it
 *     (mode-0 eigenvalue 0.2), a certified pass.
 * Mutations that must fail to prove (the tie is proven by the symmetry, so
 * breaking it must leave the condition undecided, never a pass):
 *   - one entry of Loop's S moved by 1e-9 (its row still summing to 1): S is
 *     no longer rotation-invariant, undecided, "not invariant";
 *   - the reflection replaced by the identity: refused (SS_EINPUT), it does
 *     not invert the rotation;
 *   - the hand-made matrix's tie broken by 1e-7 on one ring weight:
 *     undecided. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>
#include <flint/fmpq.h>

#include "arb.h"

#include "ss_certify.h"
#include "ss_fourier.h"
#include "ss_stencil.h"
#include "ss_test.h"
#include "ss_testcase.h"

static const char *dir; /* data/stencils */

/* A call's status checked: 1 if SS_OK, else a failed check with the message
 * (e is read after the call). */
static int try_ok(int st, const ss_error *e, const char *call) {
  CHECK(st == 0, "%s failed (status %d): %s\n", call, st, e->msg);
  return st == 0;
}
#define CHECK_OK(call, errp) try_ok((int)(call), (errp), #call)

/* x inside root r's ball (relative slack 1e-9 on the radius). */
static int holds(const ss_fourier_root *r, const arb_t x) {
  const double v = arf_get_d(arb_midref(x), ARF_RND_NEAR);
  return fabs(r->re - v) <= r->rad * (1 + 1e-9) + 1e-15 &&
         fabs(r->im) <= r->rad * (1 + 1e-9) + 1e-15;
}

/* Some root of mode k holds x. */
static int held_by_mode(const ss_fourier_root *r, size_t nr, int k, const arb_t x) {
  for (size_t i = 0; i < nr; i++)
    if (r[i].mode == k && holds(r + i, x)) return 1;
  return 0;
}

/* 3/8 + cos(2 pi k / n) / 4 at 200 bits. */
static void loop_mode(arb_t x, int k, int n) {
  fmpq_t q;
  fmpq_init(q);
  fmpq_set_si(q, 2 * k, (ulong)n);
  arb_cos_pi_fmpq(x, q, 200);
  arb_mul_2exp_si(x, x, -2);
  arb_t t;
  arb_init(t);
  arb_set_si(t, 3);
  arb_mul_2exp_si(t, t, -3);
  arb_add(x, x, t, 200);
  arb_clear(t);
  fmpq_clear(q);
}

/* The Fourier analysis of M under its star's rotation and reflection
 * (ss_charmap_sym_perm's candidates 0 and nc - 1, as ss_certify takes them);
 * refl_id: the identity instead of the reflection. */
static ss_status analyse(const ss_local *M, const ss_case *c, const double *S,
                         int refl_id, ss_fourier **f, ss_error *err) {
  size_t *rot = malloc(M->n2 * sizeof *rot), *refl = malloc(M->n2 * sizeof *refl);
  const int rays = c->kind == SS_CASE_EDGE ? c->n : M->ncoord;
  ss_charmap_sym y = {0};
  y.found = 1;
  ss_status st = ss_charmap_sym_perm(M, c, &y, rot, err);
  y.index = rays - 1;
  if (!st) st = ss_charmap_sym_perm(M, c, &y, refl, err);
  for (size_t i = 0; refl_id && i < M->n2; i++)
    refl[i] = i;
  if (!st) st = ss_fourier_new(S, M->n2, M->n1, rot, refl, rays, M->dim, f, err);
  free(rot);
  free(refl);
  return st;
}

/* Loop's closed forms inside f's balls at valence n. */
static void closed_forms(const ss_fourier *f, int n, size_t size, const char *what) {
  size_t nr = 0, total = 0;
  const ss_fourier_root *r = ss_fourier_roots(f, &nr);
  arb_t x, one;
  arb_init(x);
  arb_init(one);
  arb_one(one);
  for (size_t i = 0; i < nr; i++)
    total += (size_t)r[i].mult;
  CHECK(total == size, "%s: multiplicities add up to %zu, not %zu", what, total, size);
  CHECK(nr >= 2 && r[0].mode == 0 && holds(r, one), "%s: lambda0 = 1 not first", what);
  loop_mode(x, 1, n);
  CHECK(nr >= 2 && r[1].mode == 1 && r[1].mult == 2 && r[1].real == 1 && holds(r + 1, x),
        "%s: lambda1 = lambda2 = %.17g not the ball %.17g +- %.3g (mode %d, mult %d, "
        "real %d)",
        what, arf_get_d(arb_midref(x), ARF_RND_NEAR), nr > 1 ? r[1].re : 0.0,
        nr > 1 ? r[1].rad : 0.0, nr > 1 ? r[1].mode : -1, nr > 1 ? r[1].mult : 0,
        nr > 1 ? r[1].real : 0);
  for (int k = 1; 2 * k <= n; k++) {
    loop_mode(x, k, n);
    CHECK(held_by_mode(r, nr, k, x),
          "%s: 3/8 + cos(2 pi %d / n) / 4 in no ball of mode %d", what, k, k);
  }
  loop_mode(x, 1, n);
  arb_mul(x, x, x, 200);
  CHECK(held_by_mode(r, nr, 0, x), "%s: (3/8 + cos(2 pi / n) / 4)^2 in no ball of mode 0",
        what);
  arb_clear(x);
  arb_clear(one);
}

/* Certified verdicts of case c under s; the Fourier balls' closed forms. */
static void loop_case(const ss_scheme *s, int n, const char *name) {
  char what[64];
  snprintf(what, sizeof what, "%s %d", name, n);
  const ss_case c = {SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0};
  ss_local *M = NULL;
  ss_eig *e = NULL;
  ss_charmap *cm = NULL;
  ss_exact *x = NULL;
  ss_fourier *f = NULL;
  ss_error err = {0};
  ss_regularity reg;
  ss_charmap_inj inj;
  ss_certified out;
  REQUIRE_OK_VOID(ss_local_new(s, &c, &M, &err), &err);
  const ss_eig_opts eo = ss_eig_defaults(M->dim);
  const ss_charmap_opts o = ss_charmap_defaults();
  if (!CHECK_OK(ss_eig_new(M->S, M->n2, M->n1, &eo, &e, &err), &err) ||
      !CHECK_OK(ss_certify_verdicts(s, &c, M, e, &o, 1, &cm, &reg, &inj, &out, &x, &err),
                &err))
    goto done;
  const int rational_cos = n == 3 || n == 4 || n == 6;
  CHECK(out.cond.verdict == SS_PASS && out.cond.certified &&
            reg.verdict.verdict == SS_PASS && reg.verdict.certified,
        "%s: condition %s (%s), regularity %s (%s)", what,
        ss_verdict_name(out.cond.verdict), out.cond.reason,
        ss_verdict_name(reg.verdict.verdict), reg.verdict.reason);
  CHECK(x == NULL || (rational_cos && !strcmp(name, "loop")),
        "%s: an exact spectrum of irrational weights", what);
  if (CHECK_OK(analyse(M, &c, M->S, 0, &f, &err), &err)) {
    ss_verdict v;
    int cert = 0;
    ss_ball_outcome_condition(ss_fourier_outcome(f), &v, &cert);
    CHECK(v.verdict == SS_PASS && cert, "%s: the balls' condition %s (%s)", what,
          ss_verdict_name(v.verdict), v.reason);
    closed_forms(f, n, M->n2, what);
  }
  /* mutation: one entry moved, the row still summing to 1 */
  if (!strcmp(name, "loop") && n == 7) {
    double *S = malloc(M->n2 * M->n2 * sizeof *S);
    memcpy(S, M->S, M->n2 * M->n2 * sizeof *S);
    size_t i = M->n1 - 1, j = 0; /* a ring point's row: its weight on the centre */
    S[i * M->n2 + j] += 1e-9;
    S[i * M->n2 + i] -= 1e-9;
    ss_fourier *g = NULL;
    if (CHECK_OK(analyse(M, &c, S, 0, &g, &err), &err)) {
      ss_verdict v;
      int cert = 1;
      ss_ball_outcome_condition(ss_fourier_outcome(g), &v, &cert);
      CHECK(v.verdict == SS_UNDECIDED && !cert && strstr(v.reason, "not invariant"),
            "%s moved by 1e-9: %s (%s)", what, ss_verdict_name(v.verdict), v.reason);
    }
    ss_fourier_free(g);
    g = NULL;
    CHECK(analyse(M, &c, M->S, 1, &g, &err) == SS_EINPUT && !g,
          "%s: the identity accepted as the reflection", what);
    free(S);
  }
done:
  ss_fourier_free(f);
  ss_exact_free(x);
  ss_charmap_free(cm);
  ss_eig_free(e);
  ss_local_free(M);
}

/* Centre + a ring of n = 7: centre row (1 - n b, b...), ring row i (p on the
 * centre, q on i, r on i +- 1).  Mode 0: 1 and q + 2 r - n b; mode k: q +
 * 2 r cos(2 pi k / n). */
static void hand_made(double lam0, double eps, ss_verdict_kind want, const char *why) {
  enum { N = 7, SZ = N + 1 };
  const double r = 0.1, q = 0.5 - 2 * r * cos(2 * acos(-1.0) / N), p = 1 - q - 2 * r;
  const double b = (q + 2 * r - lam0) / N;
  double S[SZ * SZ] = {0};
  size_t rot[SZ], refl[SZ];
  S[0] = 1 - N * b;
  rot[0] = refl[0] = 0;
  for (int i = 0; i < N; i++) {
    const int a = 1 + i;
    S[a] = b;
    S[a * SZ] = p;
    S[a * SZ + a] = q;
    S[a * SZ + 1 + (i + 1) % N] = r;
    S[a * SZ + 1 + (i + N - 1) % N] = r;
    rot[a] = 1 + (size_t)((i + 1) % N);
    refl[a] = 1 + (size_t)((N - i) % N);
  }
  S[1 * SZ + 1] += eps, S[1 * SZ + 2] -= eps; /* a mutation when eps != 0 */
  ss_fourier *f = NULL;
  ss_error err = {0};
  if (!CHECK_OK(ss_fourier_new(S, SZ, SZ, rot, refl, N, 2, &f, &err), &err)) return;
  ss_verdict v;
  int cert = 0;
  ss_ball_outcome_condition(ss_fourier_outcome(f), &v, &cert);
  CHECK(v.verdict == want && cert == (want != SS_UNDECIDED) && strstr(v.reason, why),
        "hand-made lam0 %g eps %g: %s (%s), want %s with '%s'", lam0, eps,
        ss_verdict_name(v.verdict), v.reason, ss_verdict_name(want), why);
  ss_fourier_free(f);
}

/* tet/oct edges of valence n under the built-in (exact path) and under a
 * stencil whose oct weight reads 3/8 as 3/8 + cos(2*pi/n)/32 -
 * cos(2*pi/n)/32 (not rational to the exact path: the balls): both proven
 * passes, and each of the exact path's leading roots inside a Fourier ball
 * of the stencil's matrix, multiplicities equal. */
static void tetoct_edge(const ss_scheme *exact, const ss_scheme *balls, int n) {
  char what[64];
  snprintf(what, sizeof what, "tetoct edge %d", n);
  const ss_case c = {SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0};
  const ss_charmap_opts o = ss_charmap_defaults();
  ss_local *M[2] = {NULL, NULL};
  ss_eig *e[2] = {NULL, NULL};
  ss_charmap *cm[2] = {NULL, NULL};
  ss_exact *x[2] = {NULL, NULL};
  ss_fourier *f = NULL;
  ss_error err = {0};
  for (int q = 0; q < 2; q++) {
    ss_regularity reg;
    ss_charmap_inj inj;
    ss_certified out;
    const ss_scheme *s = q ? balls : exact;
    if (!CHECK_OK(ss_local_new(s, &c, &M[q], &err), &err)) goto done;
    const ss_eig_opts eo = ss_eig_defaults(M[q]->dim);
    if (!CHECK_OK(ss_eig_new(M[q]->S, M[q]->n2, M[q]->n1, &eo, &e[q], &err), &err) ||
        !CHECK_OK(ss_certify_verdicts(s, &c, M[q], e[q], &o, 1, &cm[q], &reg, &inj, &out,
                                      &x[q], &err),
                  &err))
      goto done;
    CHECK(out.cond.verdict == SS_PASS && out.cond.certified &&
              reg.verdict.verdict == SS_PASS && reg.verdict.certified &&
              (q ? x[q] == NULL : x[q] != NULL),
          "%s (%s): condition %s (%s), regularity %s (%s)", what, q ? "balls" : "exact",
          ss_verdict_name(out.cond.verdict), out.cond.reason,
          ss_verdict_name(reg.verdict.verdict), reg.verdict.reason);
  }
  if (!x[0] || !CHECK_OK(analyse(M[1], &c, M[1]->S, 0, &f, &err), &err)) goto done;
  size_t nx = 0, nf = 0;
  const ss_exact_root *rx = ss_exact_roots(x[0], &nx);
  const ss_fourier_root *rf = ss_fourier_roots(f, &nf);
  for (size_t i = 0; i < nx && i < 5; i++) {
    int in = 0; /* copies of this root among the balls that hold it */
    for (size_t j = 0; j < nf; j++)
      if (fabs(rf[j].re - rx[i].re) <= rf[j].rad + rx[i].rad + 1e-15 &&
          fabs(rf[j].im - rx[i].im) <= rf[j].rad + rx[i].rad + 1e-15)
        in += rf[j].mult;
    CHECK(in == rx[i].mult, "%s: exact root %.17g%+.3gi (mult %d) in balls of %d copies",
          what, rx[i].re, rx[i].im, rx[i].mult, in);
  }
done:
  ss_fourier_free(f);
  for (int q = 0; q < 2; q++) {
    ss_exact_free(x[q]);
    ss_charmap_free(cm[q]);
    ss_eig_free(e[q]);
    ss_local_free(M[q]);
  }
}

/* tetoct.ini with its oct weight self = 3/8 written with cos (its value
 * unchanged): the built-in's matrices, read as not rational. */
static ss_scheme *tetoct_cos(void) {
  char path[4096], *text = NULL;
  ss_scheme *s = NULL;
  ss_error err = {0};
  snprintf(path, sizeof path, "%s/tetoct.ini", dir);
  if (!CHECK_OK(ss_stencil_read(path, &text, NULL, &err), &err)) return NULL;
  char *at = strstr(text, "[mask.oct]");
  at = at ? strstr(at, "self = 3/8") : NULL;
  CHECK(at != NULL, "tetoct.ini: no oct self = 3/8");
  if (at) {
    const char *tail = at + strlen("self = 3/8");
    char *cos_text = malloc(strlen(text) + 64);
    memcpy(cos_text, text, (size_t)(at - text));
    sprintf(cos_text + (at - text), "self = 3/8 + cos(2*pi/n)/32 - cos(2*pi/n)/32%s",
            tail);
    if (CHECK_OK(ss_stencil_parse(cos_text, "tetoct-cos.ini", &s, &err), &err))
      CHECK(!ss_scheme_volume_weights_rational(s),
            "tetoct-cos: its cos read as rational");
    free(cos_text);
  }
  free(text);
  return s;
}

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: test_fourier DATA/stencils\n");
    return 2;
  }
  dir = argv[1];
  ss_scheme *loop = ss_testcase_scheme("loop");
  for (int n = 3; n <= 20 && loop; n++)
    loop_case(loop, n, "loop");
  ss_scheme_free(loop);
  char path[4096];
  snprintf(path, sizeof path, "%s/loop.ini", dir);
  ss_scheme *st = NULL;
  ss_error err = {0};
  if (CHECK_OK(ss_stencil_load(path, &st, NULL, &err), &err)) {
    CHECK(!ss_scheme_weights_rational(st), "loop.ini: its cos(2*pi/n) read as rational");
    for (int n = 3; n <= 12; n++)
      loop_case(st, n, "loop.ini");
  }
  ss_scheme_free(st);
  ss_scheme *tet = ss_testcase_scheme("tetoct"), *tcos = tetoct_cos();
  for (int n = 3; n <= 7 && tet && tcos; n++)
    tetoct_edge(tet, tcos, n);
  ss_scheme_free(tet);
  ss_scheme_free(tcos);
  hand_made(0.7, 0.0, SS_FAIL, "exact tie: lambda2 = lambda3");
  hand_made(0.2, 0.0, SS_PASS, "");
  hand_made(0.2, 1e-7, SS_UNDECIDED, "not invariant");
  flint_cleanup();
  return ss_test_done("fourier");
}
