/* ss_verdict.c — verdicts, their names and their combination (ss_verdict.h). */
#include "ss_verdict.h"

#include <stdio.h>

const char *ss_verdict_name(ss_verdict_kind v) {
  return v == SS_PASS ? "pass" : v == SS_FAIL ? "fail" : "undecided";
}

const char *ss_judged_on_name(ss_judged_on on) {
  switch (on) {
  case SS_ON_SPECTRUM:
    return "spectrum";
  case SS_ON_NET:
    return "control-net";
  case SS_ON_PSI:
    return "psi";
  case SS_ON_JSR:
    return "jsr";
  default:
    return "nothing";
  }
}

void ss_verdict_unproven(ss_verdict *v, const char *why) {
  v->certified = 0;
  if (v->verdict == SS_UNDECIDED) return;
  char was[sizeof v->reason];
  snprintf(was, sizeof was, "%.9s%s%.300s", ss_verdict_name(v->verdict),
           v->reason[0] ? ": " : "", v->reason);
  v->verdict = SS_UNDECIDED;
  snprintf(v->reason, sizeof v->reason,
           "not certified: %.150s (double precision: %.300s)", why, was);
}

ss_verdict_kind ss_verdicts_combined(const ss_verdicts *v) {
  if (v->cond.verdict == SS_FAIL || v->reg.verdict == SS_FAIL ||
      v->inj.verdict == SS_FAIL)
    return SS_FAIL;
  if (v->cond.verdict == SS_PASS && v->reg.verdict == SS_PASS &&
      v->inj.verdict == SS_PASS)
    return SS_PASS;
  return SS_UNDECIDED;
}

int ss_verdicts_certified(const ss_verdicts *v) {
  switch (ss_verdicts_combined(v)) {
  case SS_PASS:
    return v->cond.certified && v->reg.certified;
  case SS_FAIL:
    return (v->cond.verdict == SS_FAIL && v->cond.certified) ||
           (v->reg.verdict == SS_FAIL && v->reg.certified) ||
           (v->inj.verdict == SS_FAIL && v->inj.certified);
  default:
    return 0;
  }
}
