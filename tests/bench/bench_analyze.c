/* bench_analyze.c — eigenstructure of MLCA vertex cases over the links
 * k = 4..12 (DESIGN section 9, issue 4): one core, one run, ratios measured
 * side by side:
 *   (a) cases per second (eigenstructure alone, and with the extraction of the
 *       local matrix from the global rule);
 *   (b) our eigenstructure time (ss_eig_new: one-ring block by dgeevx, outer
 *       blocks by Tarjan's components, subdominant basis) over the time of one
 *       bare LAPACK dgeev (right vectors) on the same one-ring blocks — target
 *       <= 2;
 *   (c) a dense dgeev of each whole two-ring matrix over our time — target
 *       >= 10; and the largest difference between the two spectra (sorted by
 *       modulus), which must be at rounding level.
 * By default every link with k <= 11 and every 10th link with k = 12 (about
 * 4 minutes); `--all` takes all 9150 (about 25 minutes, most of it the dense
 * reference solves of the 305 x 305 two-rings); `--kmax K` stops at k = K. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ss_eig.h"
#include "ss_enum.h"
#include "ss_local.h"

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct {
  ss_scheme *s;
  int stride12;       /* take every stride12-th link with k = 12 */
  long seen12, cases; /* links with k = 12 seen; cases analysed */
  long failed;        /* extraction or LAPACK failures */
  double t_extract, t_ours, t_bare, t_dense;
  double worst_diff; /* our spectrum vs the dense one */
  long kcases[13];
  double kours[13];
} ctx;

static int cmp_mod(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x < y) - (x > y);
}

static int visit(const ss_link *l, void *vc) {
  ctx *c = vc;
  if (l->k == 12 && c->seen12++ % c->stride12 != 0) return 0;
  ss_error err = {0};
  ss_case cs = {SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0};
  ss_local *M = NULL;
  ss_eig *e = NULL;
  double t0 = now();
  if (ss_local_new(c->s, &cs, &M, &err)) {
    c->failed++;
    fprintf(stderr, "extraction failed: %s\n", err.msg);
    return 0;
  }
  double t1 = now();
  ss_eig_opts o = ss_eig_defaults(3);
  if (ss_eig_new(M->S, M->n2, M->n1, &o, &e, &err)) {
    c->failed++;
    ss_local_free(M);
    return 0;
  }
  double t2 = now();
  const size_t n1 = M->n1, n2 = M->n2;
  double *A = malloc(n1 * n1 * sizeof *A), *re = malloc(n2 * sizeof *re),
         *im = malloc(n2 * sizeof *im);
  for (size_t i = 0; i < n1; i++)
    memcpy(A + i * n1, M->S + i * n2, n1 * sizeof *A);
  double t3 = now();
  if (ss_eig_dense(A, n1, re, im, &err)) c->failed++;
  double t4 = now();
  if (ss_eig_dense(M->S, n2, re, im, &err)) c->failed++;
  double t5 = now();
  /* same numbers: moduli sorted, compared one by one */
  double *ours = malloc(n2 * sizeof *ours);
  for (size_t i = 0; i < n2; i++) {
    ours[i] = hypot(e->val[i].re, e->val[i].im);
    re[i] = hypot(re[i], im[i]);
  }
  qsort(ours, n2, sizeof *ours, cmp_mod);
  qsort(re, n2, sizeof *re, cmp_mod);
  for (size_t i = 0; i < n2; i++)
    c->worst_diff = fmax(c->worst_diff, fabs(ours[i] - re[i]));
  c->t_extract += t1 - t0;
  c->t_ours += t2 - t1;
  c->t_bare += t4 - t3;
  c->t_dense += t5 - t4;
  c->kcases[l->k]++;
  c->kours[l->k] += t2 - t1;
  c->cases++;
  free(A), free(re), free(im), free(ours);
  ss_eig_free(e);
  ss_local_free(M);
  if (c->cases % 500 == 0) fprintf(stderr, "  %ld cases...\n", c->cases);
  return 0;
}

int main(int argc, char **argv) {
  ctx c;
  memset(&c, 0, sizeof c);
  c.stride12 = 10;
  int kmax = 12;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--all")) c.stride12 = 1;
    if (!strcmp(argv[i], "--kmax") && i + 1 < argc) kmax = atoi(argv[++i]);
  }
  if (kmax < 4 || kmax > 12) kmax = 12;
  ss_error err = {0};
  if (ss_scheme_new("mlca", &c.s, &err)) return 1;
  ss_enum_opts o = {4, kmax, 0, 1};
  double t0 = now();
  if (ss_enum_links(&o, visit, &c, NULL, &err)) {
    fprintf(stderr, "%s\n", err.msg);
    return 1;
  }
  double wall = now() - t0;
  printf("MLCA vertex cases, links k = 4..%d (%s), one core\n", kmax,
         c.stride12 == 1 ? "all" : "every 10th with k = 12");
  printf("   k  cases  eigenstructure ms/case\n");
  for (int k = 4; k <= 12; k++)
    printf("  %2d  %5ld  %8.3f\n", k, c.kcases[k],
           c.kcases[k] ? 1e3 * c.kours[k] / c.kcases[k] : 0.0);
  printf("cases %ld (failures %ld) in %.1f s\n", c.cases, c.failed, wall);
  printf("(a) eigenstructure: %.0f cases/s; with extraction from the global rule: %.1f "
         "cases/s\n",
         c.cases / c.t_ours, c.cases / (c.t_ours + c.t_extract));
  printf("(b) ours / bare dgeev on the one-ring blocks: %.2f   (target <= 2)\n",
         c.t_ours / c.t_bare);
  printf("(c) dense dgeev of the whole two-ring / ours: %.1f   (target >= 10)\n",
         c.t_dense / c.t_ours);
  printf("    largest difference of the sorted moduli, ours vs dense: %.2e\n",
         c.worst_diff);
  ss_scheme_free(c.s);
  return c.failed ? 1 : 0;
}
