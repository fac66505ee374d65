/* stencil_case.h — checks shared by the stencil tests (test_stencil.c,
 * test_stencil_expr.c): two schemes' operators compared bit for bit, and a
 * bad stencil refused with a given message. */
#ifndef STENCIL_CASE_H
#define STENCIL_CASE_H

#include <string.h>

#include "ss_stencil.h"
#include "ss_test.h"

/* Refine cx once with both schemes; their operators must be identical, entry
 * for entry and bit for bit. */
static inline void same_operator(const ss_scheme *a, const ss_scheme *b, const ss_cx *cx,
                                 const char *what) {
  ss_error err = {0};
  ss_cx *fa = NULL, *fb = NULL;
  gsl_spmatrix *Ra = NULL, *Rb = NULL;
  if (ss_scheme_refine(a, cx, &fa, &Ra, &err) ||
      ss_scheme_refine(b, cx, &fb, &Rb, &err)) {
    CHECK(0, "%s: %s", what, err.msg);
  } else {
    int same = Ra->size1 == Rb->size1 && Ra->size2 == Rb->size2 && Ra->nz == Rb->nz;
    for (size_t r = 0; same && r <= Ra->size1; r++)
      same = Ra->p[r] == Rb->p[r];
    for (int q = 0; same && q < Ra->p[Ra->size1]; q++)
      same = Ra->i[q] == Rb->i[q] && !memcmp(&Ra->data[q], &Rb->data[q], sizeof(double));
    CHECK(same && Ra->nz > 0, "%s: the stencil's operator differs from the built-in one",
          what);
  }
  if (Ra) gsl_spmatrix_free(Ra);
  if (Rb) gsl_spmatrix_free(Rb);
  ss_cx_free(fa);
  ss_cx_free(fb);
}

/* A bad stencil: SS_EINPUT, no scheme, and a message containing want. */
static inline void bad(const char *text, const char *want) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  const ss_status st = ss_stencil_parse(text, "bad.ini", &s, &err);
  CHECK(st == SS_EINPUT && s == NULL && strstr(err.msg, want),
        "want '%s', got status %d: %s", want, (int)st, err.msg);
  ss_scheme_free(s);
}

#endif
