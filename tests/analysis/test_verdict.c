/* test_verdict.c — ss_verdict: the combination of a case's three verdicts,
 * its certified flag, unproven verdicts, what a verdict is judged on, and the
 * JSR test's verdict (ss_levin_verdict).
 *
 * The combination is checked against a second formulation, not against the
 * code's own: verdicts ordered fail < undecided < pass, the combination is
 * the minimum (the weakest link), for all 27 triples; a combination that
 * returned pass when one verdict is undecided, or undecided when one fails,
 * fails here.  The certified flag against its definition in words, on every
 * triple with every certified pattern (216 cases). */
#include <string.h>

#include "ss_levin.h"
#include "ss_test.h"
#include "ss_verdict.h"

static const ss_verdict_kind kinds[3] = {SS_PASS, SS_FAIL, SS_UNDECIDED};

/* fail < undecided < pass */
static int rank(ss_verdict_kind k) {
  return k == SS_FAIL ? 0 : k == SS_UNDECIDED ? 1 : 2;
}

static void combination(void) {
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      for (int c = 0; c < 3; c++)
        for (int cert = 0; cert < 8; cert++) {
          ss_verdicts v = {{kinds[a], "", cert & 1, SS_ON_SPECTRUM},
                           {kinds[b], "", (cert >> 1) & 1, SS_ON_NET},
                           {kinds[c], "", (cert >> 2) & 1, SS_ON_NET}};
          int lo = rank(kinds[a]);
          if (rank(kinds[b]) < lo) lo = rank(kinds[b]);
          if (rank(kinds[c]) < lo) lo = rank(kinds[c]);
          const ss_verdict_kind want = lo == 0   ? SS_FAIL
                                       : lo == 1 ? SS_UNDECIDED
                                                 : SS_PASS;
          const ss_verdict_kind got = ss_verdicts_combined(&v);
          CHECK(got == want, "combined(%s, %s, %s) = %s", ss_verdict_name(kinds[a]),
                ss_verdict_name(kinds[b]), ss_verdict_name(kinds[c]),
                ss_verdict_name(got));
          /* certified: a pass is proven when the condition and the regularity
           * are (injectivity is never required); a failure when at least one
           * failing verdict is proven; undecided never */
          int wantc = 0;
          if (want == SS_PASS) wantc = (cert & 1) && (cert & 2);
          if (want == SS_FAIL)
            wantc = (kinds[a] == SS_FAIL && (cert & 1)) ||
                    (kinds[b] == SS_FAIL && (cert & 2)) ||
                    (kinds[c] == SS_FAIL && (cert & 4));
          CHECK(ss_verdicts_certified(&v) == wantc,
                "certified(%s, %s, %s; pattern %d) = %d", ss_verdict_name(kinds[a]),
                ss_verdict_name(kinds[b]), ss_verdict_name(kinds[c]), cert,
                ss_verdicts_certified(&v));
        }
}

static void unproven(void) {
  ss_verdict v = {SS_PASS, "", 1, SS_ON_NET};
  ss_verdict_unproven(&v, "no enclosure");
  CHECK(v.verdict == SS_UNDECIDED && !v.certified && v.on == SS_ON_NET,
        "an unproven pass is undecided, not certified, still about the net");
  CHECK(!strcmp(v.reason, "not certified: no enclosure (double precision: pass)"), "%s",
        v.reason);
  ss_verdict f = {SS_FAIL, "folds", 1, SS_ON_NET};
  ss_verdict_unproven(&f, "why");
  CHECK(!strcmp(f.reason, "not certified: why (double precision: fail: folds)"), "%s",
        f.reason);
  ss_verdict u = {SS_UNDECIDED, "rounding", 0, SS_ON_SPECTRUM};
  ss_verdict_unproven(&u, "why");
  CHECK(u.verdict == SS_UNDECIDED && !strcmp(u.reason, "rounding"),
        "an undecided verdict keeps its reason: %s", u.reason);
}

static void names(void) {
  const ss_judged_on on[5] = {SS_ON_NOTHING, SS_ON_SPECTRUM, SS_ON_NET, SS_ON_PSI,
                              SS_ON_JSR};
  const char *want[5] = {"nothing", "spectrum", "control-net", "psi", "jsr"};
  for (int i = 0; i < 5; i++)
    CHECK(!strcmp(ss_judged_on_name(on[i]), want[i]), "%s", ss_judged_on_name(on[i]));
  CHECK(!strcmp(ss_verdict_name(SS_PASS), "pass") &&
            !strcmp(ss_verdict_name(SS_FAIL), "fail") &&
            !strcmp(ss_verdict_name(SS_UNDECIDED), "undecided"),
        "verdict names");
}

/* The JSR test: below the threshold passes, at or above fails, across it is
 * undecided; certified only when decided with rigorous bounds. */
static void jsr(void) {
  ss_levin L;
  memset(&L, 0, sizeof L);
  L.threshold = 0.25;
  struct {
    double lower, upper;
    int certified;
    ss_verdict_kind want;
    int wantc;
  } t[] = {
      {0.1, 0.2, 1, SS_PASS, 1},       {0.1, 0.2, 0, SS_PASS, 0},
      {0.25, 0.3, 1, SS_FAIL, 1},      {0.3, 0.4, 0, SS_FAIL, 0},
      {0.2, 0.25, 1, SS_UNDECIDED, 0}, /* upper = threshold: not below it */
      {0.2, 0.3, 1, SS_UNDECIDED, 0},
  };
  for (size_t i = 0; i < sizeof t / sizeof *t; i++) {
    ss_jsr_result r;
    memset(&r, 0, sizeof r);
    r.lower = t[i].lower;
    r.upper = t[i].upper;
    r.certified = t[i].certified;
    ss_verdict v;
    ss_levin_verdict(&L, &r, &v);
    CHECK(v.verdict == t[i].want && v.certified == t[i].wantc && v.on == SS_ON_JSR,
          "[%g, %g] against 1/4: %s certified %d", t[i].lower, t[i].upper,
          ss_verdict_name(v.verdict), v.certified);
    CHECK((v.verdict == SS_PASS) == (v.reason[0] == 0), "a reason unless passing: '%s'",
          v.reason);
  }
}

int main(void) {
  combination();
  unproven();
  names();
  jsr();
  return ss_test_done("verdict");
}
