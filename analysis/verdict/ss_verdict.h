/* ss_verdict.h — one verdict type for every test the workbench decides
 * (DESIGN sections 5 and 10): the eigenvalue condition, the regularity and
 * the injectivity of the characteristic map, the joint spectral radius test.
 *
 * A verdict says three things besides pass / fail / undecided and why:
 * whether it is proven (certified: exact or interval arithmetic that
 * accounts for every rounding), and what it is a statement about (judged
 * on): the spectrum of S, the control net of the characteristic map (its
 * multilinear interpolant on psi's ring, or its piecewise-linear image for
 * injectivity) — a proxy for psi itself —, psi itself, or the joint spectral
 * radius bound of the Levin–Levin reduction.  A case's three verdicts
 * travel together (ss_verdicts) and combine into one: pass when all pass,
 * fail when any fails, else undecided. */
#ifndef SS_VERDICT_H
#define SS_VERDICT_H

#include "ss_api.h"

SS_BEGIN_DECLS

typedef enum { SS_PASS = 0, SS_FAIL, SS_UNDECIDED } ss_verdict_kind;

/* What a verdict is a statement about. */
typedef enum {
  SS_ON_NOTHING = 0, /* not judged (no characteristic map to judge) */
  SS_ON_SPECTRUM,    /* the eigenvalues of S (LAPACK's, or the exact ones) */
  SS_ON_NET,         /* the characteristic map's control net: its
                        multilinear interpolant on the ring (regularity) or
                        its piecewise-linear image (injectivity) */
  SS_ON_PSI,         /* the characteristic map psi itself */
  SS_ON_JSR          /* the joint spectral radius bounds (Levin–Levin) */
} ss_judged_on;

/* A verdict and its reason. */
typedef struct {
  ss_verdict_kind verdict; /* pass, fail or undecided */
  char reason[512];        /* why (empty when passing) */
  int certified;           /* 1 if the verdict is proven; 0 otherwise (always 0
                              for undecided) */
  ss_judged_on on;         /* what it is a statement about */
} ss_verdict;

/* The three verdicts of one case. */
typedef struct {
  ss_verdict cond; /* the eigenvalue condition */
  ss_verdict reg;  /* regularity of the characteristic map */
  ss_verdict inj;  /* injectivity of the characteristic map */
} ss_verdicts;

/* "pass", "fail", "undecided". */
const char *ss_verdict_name(ss_verdict_kind v);

/* "nothing", "spectrum", "control-net", "psi", "jsr" (the names in JSON). */
const char *ss_judged_on_name(ss_judged_on on);

/* v becomes undecided, "not certified: why (double precision: v)", and not
 * certified; an undecided verdict keeps its reason (there is nothing to
 * prove). */
void ss_verdict_unproven(ss_verdict *v, const char *why);

/* The verdicts combined: pass if all three pass; fail if any fails; else
 * undecided. */
ss_verdict_kind ss_verdicts_combined(const ss_verdicts *v);

/* Whether the combined verdict is proven: a pass when the eigenvalue
 * condition and the regularity are (injectivity is checked with exact
 * predicates on the double-precision net, not proven), a failure when a
 * verdict that fails is; 0 for undecided. */
int ss_verdicts_certified(const ss_verdicts *v);

SS_END_DECLS

#endif
