/* ss_testexact.h — the exact path's tests' common steps (test_exact.c,
 * test_exact_links.c): one case's local matrix and exact spectrum, its
 * verdict and reason, lambda_i.  Header only, because it records failures
 * with CHECK, whose counters are each test executable's own (ss_test.h). */
#ifndef SS_TESTEXACT_H
#define SS_TESTEXACT_H

#include <stdio.h>

#include "ss_exact.h"
#include "ss_local.h"
#include "ss_test.h"

/* The local matrix of case c and its exact spectrum (default options of its
 * dimension); 0 on success. */
static inline int ss_testexact_run(const ss_scheme *s, ss_case c, ss_local **M,
                                   ss_exact **x) {
  ss_error err = {0};
  *M = NULL;
  *x = NULL;
  if (ss_local_new(s, &c, M, &err)) {
    CHECK(0, "%s: extraction: %s", ss_scheme_name(s), err.msg);
    return -1;
  }
  ss_exact_opts o = ss_exact_defaults((*M)->dim);
  if (ss_exact_new((*M)->S, (*M)->n2, (*M)->n1, &o, x, &err)) {
    CHECK(0, "%s %s: exact spectrum: %s", ss_scheme_name(s), ss_case_name(c.kind),
          err.msg);
    ss_local_free(*M);
    *M = NULL;
    return -1;
  }
  return 0;
}

static inline int ss_testexact_verdict_is(const ss_exact *x, ss_verdict_kind kind,
                                          int certified) {
  ss_verdict v;
  int c;
  ss_exact_condition(x, &v, &c);
  return v.verdict == kind && c == certified;
}

/* The verdict's reason, by value (ss_testexact_reason(x).s lives to the end of the
 * expression that uses it). */
typedef struct {
  char s[sizeof((ss_verdict *)0)->reason]; /* a verdict's reason */
} ss_testexact_why;

static inline ss_testexact_why ss_testexact_reason(const ss_exact *x) {
  ss_verdict v;
  int c;
  ss_exact_condition(x, &v, &c);
  ss_testexact_why w;
  snprintf(w.s, sizeof w.s, "%s", v.reason);
  return w;
}

/* lambda_i (i >= 0) in the multiset order: the root holding position i. */
static inline const ss_exact_root *ss_testexact_lambda(const ss_exact *x, int i) {
  size_t nr;
  const ss_exact_root *r = ss_exact_roots(x, &nr);
  for (size_t k = 0; k < nr; k++) {
    if (i < r[k].mult) return r + k;
    i -= r[k].mult;
  }
  return NULL;
}

#endif
