/* test_marks.c — the boundary marks of refined levels (ss_local_marks.c).
 *
 * A refined level's inner/boundary marks are derived from the coarser
 * level's boundary facets through the split's parent lists (a fine facet is
 * a boundary facet iff its coarse one is), not recomputed by grouping the
 * fine level's facets.  This executable compiles its own copy of
 * ss_local_level.c with SS_CHECK_MARKS, which recomputes every derived
 * level's marks the independent way (ss_local_inner_marks on the fine
 * complex) and fails the
 * extraction with SS_EINTERNAL "derived boundary marks differ" if they are
 * not the same bytes.  The property is then: every case of every scheme
 * with a one-split step, vertex one-rings of random links k = 4..12 (with
 * the ring levels regularity needs, deeper ones included), edges and the
 * tet/oct face, Catmull-Clark and Loop surface vertices of valence 3..9, runs to a result
 * with no internal error.  Wrong derived marks would change which rows are emitted and
 * read, so they could otherwise surface only as a changed verdict somewhere in a sweep.
 */
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "ss_link_random.h"
#include "ss_result.h"
#include "ss_scheme.h"
#include "ss_test.h"

#ifndef SS_CHECK_MARKS
#error "test_marks must be compiled with SS_CHECK_MARKS (tests/analysis/meson.build)"
#endif

static int run(const ss_scheme *s, const ss_case *c, const char *what) {
  ss_result_opts ro = ss_result_defaults();
  ss_result r;
  ss_error err = {0};
  const ss_status st = ss_result_compute(s, c, &ro, &r, &err);
  /* bad input cannot occur here: anything but OK is the check or a defect */
  CHECK(st == SS_OK, "%s: %s", what, err.msg);
  const int deeper = st == SS_OK && r.ring_level >= 2;
  if (st == SS_OK) ss_result_clear(&r);
  return deeper;
}

int main(void) {
  static const char *const names[] = {"mlca", "tetoct", "boxspline", "ccsolid"};
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  if (!rng) return 1;
  gsl_rng_set(rng, 2026);
  int cases = 0, deeper = 0;
  for (int si = 0; si < 4; si++) {
    ss_scheme *s = NULL;
    ss_error err = {0};
    if (ss_scheme_new(names[si], &s, &err)) {
      CHECK(0, "scheme %s: %s", names[si], err.msg);
      continue;
    }
    char what[96];
    for (int k = 4; k <= 12; k++) {
      for (int rep = 0; rep < (k >= 9 ? 3 : 1); rep++) {
        ss_link *l = NULL;
        if (ss_link_random(k, rng, &l, &err)) {
          CHECK(0, "random link k = %d: %s", k, err.msg);
          continue;
        }
        const ss_case c = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
        snprintf(what, sizeof what, "%s vertex k = %d (%d)", names[si], k, rep);
        deeper += run(s, &c, what);
        cases++;
        ss_link_free(l);
      }
    }
    for (int n = 3; n <= 8; n++) {
      const ss_case c = {SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0};
      snprintf(what, sizeof what, "%s edge %d", names[si], n);
      run(s, &c, what);
      cases++;
    }
    if (si == 1) {
      const ss_case face = {SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0};
      run(s, &face, "tetoct face");
      cases++;
    }
    ss_scheme_free(s);
  }
  /* surfaces: boundary facets are edges (two corners) */
  static const char *const surf[] = {"catmull-clark", "loop"};
  for (int si = 0; si < 2; si++) {
    ss_scheme *s = NULL;
    ss_error err = {0};
    if (ss_scheme_new(surf[si], &s, &err)) {
      CHECK(0, "scheme %s: %s", surf[si], err.msg);
      continue;
    }
    for (int n = 3; n <= 9; n++) {
      char what[96];
      const ss_case c = {SS_CASE_SURFACE_VERTEX, NULL, n, SS_DIAG_BFS, 0};
      snprintf(what, sizeof what, "%s vertex %d", surf[si], n);
      run(s, &c, what);
      cases++;
    }
    ss_scheme_free(s);
  }
  /* the derivation must have been exercised on the deeper ring levels too */
  CHECK(deeper > 0, "no case needed a deeper ring level (%d cases)", cases);
  printf("%d cases, %d with a deeper ring level: derived marks = recomputed marks\n",
         cases, deeper);
  gsl_rng_free(rng);
  return ss_test_done("marks");
}
