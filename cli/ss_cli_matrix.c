/* ss_cli_matrix.c — `subspectra matrix`'s Matrix Market output of one case,
 * and the eigenvectors analyze and matrix export (ss_cli_analyze.h).
 *
 * The program's one Matrix Market writer (NIST's exchange format: a banner,
 * '%' comment lines, a size line, the entries): S as "coordinate real" (its
 * nonzeros), eigenvectors as a dense "array real|complex", both with the
 * points named in comments.  Written here rather than by a library: Debian
 * has no C library for the format except SuiteSparse's CHOLMOD
 * (cholmod_write_sparse/_dense), which takes its comments only from a file
 * and would bring CHOLMOD for some twenty lines of fprintf; NIST's mmio.c is
 * not packaged.  The entries are %.17g, which reads back bit for bit. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_cli_analyze.h"
#include "ss_cli_eigvec.h"
#include "ss_eigvec.h"
#include "ss_outfile.h"

/* The banner: "coordinate" or "array" of "real" or "complex" entries. */
static void mtx_banner(FILE *f, int coordinate, int complex_entries) {
  fprintf(f, "%%%%MatrixMarket matrix %s %s general\n",
          coordinate ? "coordinate" : "array", complex_entries ? "complex" : "real");
}

/* One comment line per point of M (1..n), "% WORD<i> LABEL": each point
 * named by its exact coordinates relative to the centre. */
static void mtx_points(FILE *f, const ss_local *M, size_t n, const char *word) {
  char buf[256];
  for (size_t i = 0; i < n; i++) {
    ss_cli_label_text(M->label + i, buf, sizeof buf);
    fprintf(f, "%% %s%zu %s\n", word, i + 1, buf);
  }
}

/* The right or (left != 0) left eigenvectors of v as a dense n x k array,
 * with comments naming the eigenvalues, their normalisation and the points;
 * head is a comment line already formatted ("% subspectra ... case ..."). */
static void eigvec_mtx(FILE *f, const ss_eigvec *v, const ss_local *M, int left,
                       const char *head) {
  const double *re = left ? v->left_re : v->right_re,
               *im = left ? v->left_im : v->right_im;
  mtx_banner(f, 0, v->complex_any);
  fprintf(f, "%s\n", head);
  fprintf(f, "%% %s eigenvectors of the %d leading eigenvalues, one per column (%s)\n",
          left ? "left" : "right", v->k,
          left ? "row vectors l with l^T S = lambda l^T, no conjugation; L^T R = I "
                 "within each group of equal eigenvalues"
               : "S r = lambda r; maximum modulus 1, that entry real and positive");
  for (int j = 0; j < v->k; j++)
    fprintf(f, "%% eigenvalue %d: %.17g%+.17gi (group %d%s)\n", j + 1, v->re[j], v->im[j],
            v->group[j], v->biorth[j] ? "" : ", defective: not biorthonormal");
  mtx_points(f, M, v->n, "point ");
  fprintf(f, "%zu %d\n", v->n, v->k);
  for (int j = 0; j < v->k; j++)
    for (size_t i = 0; i < v->n; i++) {
      const size_t at = i + (size_t)j * v->n;
      if (v->complex_any)
        fprintf(f, "%.17g %.17g\n", re[at], im[at]);
      else
        fprintf(f, "%.17g\n", re[at]);
    }
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
  mtx_banner(f, 1, 0);
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
  mtx_points(f, M, n, "");
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
  eigvec_mtx(out ? ss_outfile_file(out) : stdout, v, M, o->left, head);
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
