/* analyze_edge.c — libsubspectra from C: one edge case, start to finish.
 *
 * The smoothness of a scheme at a point on an edge of valence N: the scheme
 * (by name), the case, its local subdivision matrix S (derived by the library
 * from the scheme's global rule), the leading eigenvalues of S with their
 * multiplicities, the eigenvalue condition, and the regularity of the
 * characteristic map: two of the three verdicts of `subspectra analyze
 * --edge N` (the third, injectivity, is ss_charmap_injectivity; ss_result.h
 * runs the whole pipeline in one call).  The extraction and the eigen-solve
 * take their scratch memory from workspaces, as a loop over many cases would
 * (one workspace per thread, reused from case to case; ss_local_new and
 * ss_eig_new allocate their own).
 *
 * Build against an installed library:
 *   cc -std=c11 analyze_edge.c $(pkg-config --cflags --libs subspectra)
 * Run:
 *   ./a.out [SCHEME [N]]      (default: mlca 4)
 *
 * Output, one item per line (the install test reads it):
 *   case SCHEME edge N
 *   matrix TWO_RING ONE_RING NONZEROS
 *   lambda I RE IM MULT        (the 8 leading eigenvalues, by modulus)
 *   condition VERDICT [REASON]
 *   regularity VERDICT [REASON]
 *   verdict VERDICT
 * Exit status: 0 pass, 1 fail or undecided, 2 bad arguments or an error. */
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>

#include <subspectra/ss_charmap.h>
#include <subspectra/ss_eig.h>
#include <subspectra/ss_error.h>
#include <subspectra/ss_local.h>
#include <subspectra/ss_scheme.h>

int main(int argc, char **argv) {
  const char *name = argc > 1 ? argv[1] : "mlca";
  const int n = argc > 2 ? atoi(argv[2]) : 4;
  if (argc > 3 || n < 3) {
    fprintf(stderr, "usage: analyze_edge [SCHEME [N]]  (N >= 3)\n");
    return 2;
  }
  /* the library reports through ss_status: GSL must not abort the process */
  gsl_set_error_handler_off();

  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_local *M = NULL;
  ss_eig *e = NULL;
  ss_charmap *cm = NULL;
  ss_local_workspace *lw = ss_local_workspace_new();
  ss_eig_workspace *ew = ss_eig_workspace_new(0);
  int rc = 2;
  if (!lw || !ew) {
    ss_error_set(&err, SS_ENOMEM, "out of memory (workspaces)");
    goto done;
  }
  if (ss_scheme_new(name, &s, &err)) goto done;
  /* the case: a point on an edge of valence n (no link; default diagonals) */
  const ss_case c = {SS_CASE_EDGE, NULL, n, SS_DIAG_BFS, 0};
  const ss_local_opts lo = ss_local_defaults();
  if (ss_local_new_ws(s, &c, &lo, lw, &M, &err)) goto done;
  printf("case %s edge %d\n", ss_scheme_name(s), n);
  printf("matrix %zu %zu %zu\n", M->n2, M->n1, M->nnz);

  /* eigenvalues, the eigenvalue condition and the subdominant basis */
  const ss_eig_opts eo = ss_eig_defaults(M->dim);
  if (ss_eig_new_ws(M->S, M->n2, M->n1, &eo, ew, &e, &err)) goto done;
  for (size_t i = 0; i < e->n && i < 8; i++)
    printf("lambda %zu %.15g %.15g %d\n", i, e->val[i].re, e->val[i].im, e->val[i].mult);
  printf("condition %s %s\n", ss_verdict_name(e->cond.verdict), e->cond.reason);

  /* the characteristic map and its regularity (M's ring may be deepened) */
  const ss_charmap_opts co = ss_charmap_defaults();
  ss_regularity reg;
  if (ss_charmap_judge(s, &c, M, e, &co, &cm, &reg, &err)) goto done;
  printf("regularity %s %s\n", ss_verdict_name(reg.verdict.verdict), reg.verdict.reason);

  const int pass = e->cond.verdict == SS_PASS && reg.verdict.verdict == SS_PASS;
  printf("verdict %s\n", pass ? "pass" : "not pass");
  rc = pass ? 0 : 1;
done:
  if (rc == 2) fprintf(stderr, "analyze_edge: %s\n", err.msg);
  ss_charmap_free(cm);
  ss_eig_free(e);
  ss_local_free(M);
  ss_local_workspace_free(lw);
  ss_eig_workspace_free(ew);
  ss_scheme_free(s);
  return rc;
}
