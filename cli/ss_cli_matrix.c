/* ss_cli_matrix.c — `subspectra matrix`'s Matrix Market output of one case,
 * and the eigenvectors analyze and matrix export (ss_cli_analyze.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_cli_analyze.h"
#include "ss_cli_eigvec.h"
#include "ss_eigvec.h"
#include "ss_outfile.h"

static void print_label(FILE *f, const ss_star_coord *c) {
  char buf[256];
  ss_cli_label_text(c, buf, sizeof buf);
  fputs(buf, f);
}

int ss_cli_write_mtx(const ss_cli_analyze_opts *o, const ss_pipeline *p) {
  /* -o: a temporary file renamed over the target, written whole or not at all;
   * standard output is checked by main */
  const ss_local *M = p->M;
  ss_outfile *out = NULL;
  ss_error err = {0};
  if (o->out && ss_outfile_open(o->out, &out, &err)) return ss_cli_fail(o->cmd, &err);
  FILE *f = out ? ss_outfile_file(out) : stdout;
  const size_t n = o->ring == 1 ? M->n1 : M->n2;
  size_t nnz = 0;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      nnz += M->S[i * M->n2 + j] != 0.0;
  char buf[32];
  fprintf(f, "%%%%MatrixMarket matrix coordinate real general\n");
  fprintf(f, "%% subspectra local subdivision matrix: scheme %s, %s case %s\n",
          ss_scheme_name(p->scheme), ss_case_name(p->c.kind),
          ss_cli_case_param(o, p, buf, sizeof buf));
  if (p->has_diag)
    fprintf(f, "%% major diagonals: %s; %zu of %zu face-adjacent pairs improper\n",
            ss_diag_name(p->c.asked.diag), p->improper, p->pairs);
  fprintf(f,
          "%% %s: row i = point i on level j+1, column j = point j on level j (read on "
          "level %d)\n",
          o->ring == 1 ? "one-ring block A" : "whole two-ring S", M->level);
  fprintf(f,
          "%% points 1..%zu are the one-ring, %zu..%zu the rest of the two-ring; each\n"
          "%% point is named by its exact coordinates relative to the centre, as\n"
          "%% (chart-index:value ...) pairs in units of the level's grid\n",
          M->n1, M->n1 + 1, M->n2);
  for (size_t i = 0; i < n; i++) {
    fprintf(f, "%% %zu ", i + 1);
    print_label(f, M->label + i);
    fputc('\n', f);
  }
  fprintf(f, "%zu %zu %zu\n", n, n, nnz);
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++)
      if (M->S[i * M->n2 + j] != 0.0)
        fprintf(f, "%zu %zu %.17g\n", i + 1, j + 1, M->S[i * M->n2 + j]);
  if (ss_outfile_commit(out, &err)) return ss_cli_fail(o->cmd, &err);
  return SS_EXIT_OK;
}

/* The K leading eigenpairs of S, or of A with --ring 1 (ss_eigvec); NULL
 * after saying why. */
static ss_eigvec *eigvec_of(const ss_cli_analyze_opts *o, const ss_local *M, size_t n,
                            const char *where) {
  ss_error err = {0};
  ss_eigvec *v = NULL;
  double *A = NULL;
  if ((size_t)o->nvec > n) {
    fprintf(stderr, "subspectra %s: %s--eigenvectors %d: the matrix has only %zu rows\n",
            o->cmd, where, o->nvec, n);
    return NULL;
  }
  if (n != M->n2) { /* the one-ring block, contiguous */
    if (!(A = malloc(n * n * sizeof *A))) {
      fprintf(stderr, "subspectra %s: out of memory\n", o->cmd);
      return NULL;
    }
    for (size_t i = 0; i < n; i++)
      memcpy(A + i * n, M->S + i * M->n2, n * sizeof *A);
  }
  if (ss_eigvec_new(A ? A : M->S, n, o->nvec, o->tol, &v, &err))
    fprintf(stderr, "subspectra %s: %s%s\n", o->cmd, where, err.msg);
  free(A);
  return v;
}

int ss_cli_write_eigvec_mtx(const ss_cli_analyze_opts *o, const ss_pipeline *p) {
  const ss_local *M = p->M;
  const size_t n = o->ring == 1 ? M->n1 : M->n2;
  ss_eigvec *v = eigvec_of(o, M, n, "");
  if (!v) return SS_EXIT_USAGE;
  ss_outfile *out = NULL;
  ss_error err = {0};
  if (o->out && ss_outfile_open(o->out, &out, &err)) {
    ss_eigvec_free(v);
    return ss_cli_fail(o->cmd, &err);
  }
  char head[256], buf[32];
  snprintf(head, sizeof head,
           "%% subspectra local subdivision matrix: scheme %s, %s case %s, %s",
           ss_scheme_name(p->scheme), ss_case_name(p->c.kind),
           ss_cli_case_param(o, p, buf, sizeof buf),
           o->ring == 1 ? "one-ring block A" : "whole two-ring S");
  ss_cli_eigvec_mtx(out ? ss_outfile_file(out) : stdout, v, M, o->left, head);
  ss_eigvec_free(v);
  if (ss_outfile_commit(out, &err)) return ss_cli_fail(o->cmd, &err);
  return SS_EXIT_OK;
}

int ss_cli_eigvec_json_of(const ss_cli_analyze_opts *o, const ss_pipeline *p,
                          const char *where, json_object **out) {
  /* the limit masks need the eigenvalue condition as judged */
  const ss_local *M = p->M;
  ss_eigvec *v = eigvec_of(o, M, M->n2, where);
  if (!v) return SS_EXIT_USAGE;
  const int limit = ss_eigvec_has_limit(v, p->e->tol);
  const int ok = p->v.cond.verdict == SS_PASS && limit;
  *out = ss_cli_eigvec_json(v, M, M->dim, ok,
                            !limit ? "lambda0 = 1 is not simple with a constant "
                                     "eigenvector"
                                   : "the eigenvalue condition does not hold");
  ss_eigvec_free(v);
  if (!*out) {
    fprintf(stderr, "subspectra %s: out of memory\n", o->cmd);
    return SS_EXIT_USAGE;
  }
  return 0;
}
