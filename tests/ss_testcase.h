/* ss_testcase.h — one case through the whole pipeline for the tests: local
 * matrix, eigenstructure, characteristic map and its regularity.  Header
 * only, because it records failures with CHECK, whose counters are each test
 * executable's own (ss_test.h). */
#ifndef SS_TESTCASE_H
#define SS_TESTCASE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_charmap.h"
#include "ss_scheme.h"
#include "ss_test.h"

/* The stages of one case, each owned (ss_testcase_free). */
typedef struct {
  ss_local *M;     /* the local subdivision matrix */
  ss_eig *e;       /* its eigenstructure */
  ss_charmap *cm;  /* the characteristic map */
  ss_regularity r; /* its regularity verdict */
} ss_testcase;

static inline void ss_testcase_free(ss_testcase *t) {
  ss_charmap_free(t->cm);
  ss_eig_free(t->e);
  ss_local_free(t->M);
  memset(t, 0, sizeof *t);
}

/* The built-in scheme called name; a test cannot go on without it, so a
 * failure ends the test executable (exit status 1). */
static inline ss_scheme *ss_testcase_scheme(const char *name) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  if (ss_scheme_new(name, &s, &err)) {
    fprintf(stderr, "scheme %s: %s\n", name, err.msg);
    exit(1);
  }
  return s;
}

/* Case c of the scheme named `scheme`, analysed with the defaults (ss_eig
 * and ss_charmap options; the ring deepened as the verdict wants).  0 when
 * there is a characteristic map; otherwise -1, with the failure recorded as a
 * failed CHECK and *out freed. */
static inline int ss_testcase_run(const char *scheme, ss_case c, ss_testcase *out) {
  ss_error err = {0};
  ss_scheme *s = NULL;
  memset(out, 0, sizeof *out);
  int ok = !ss_scheme_new(scheme, &s, &err) && !ss_local_new(s, &c, &out->M, &err);
  if (ok) {
    ss_eig_opts o = ss_eig_defaults(out->M->dim);
    const ss_charmap_opts co = ss_charmap_defaults();
    ok = !ss_eig_new(out->M->S, out->M->n2, out->M->n1, &o, &out->e, &err) &&
         !ss_charmap_judge(s, &c, out->M, out->e, &co, &out->cm, &out->r, &err);
  }
  ss_scheme_free(s);
  if (ok && !out->cm)
    snprintf(err.msg, sizeof err.msg, "no characteristic map (%.400s)",
             out->r.verdict.reason);
  if (!ok || !out->cm) {
    CHECK(0, "%s %s: %s", scheme, ss_case_name(c.kind), err.msg);
    ss_testcase_free(out);
    return -1;
  }
  return 0;
}

#endif
