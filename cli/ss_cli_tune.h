/* ss_cli_tune.h — `subspectra tune`: free parameters of a stencil file
 * chosen to make every case pass with the largest smallest margin
 * (ss_cli_tune.c: options, evaluation, rounding, the written file and its
 * certified check; ss_cli_tune_search.c: the NLopt search). */
#ifndef SS_CLI_TUNE_H
#define SS_CLI_TUNE_H

#include <stddef.h>

#include "ss_cli_check.h"
#include "ss_result.h"
#include "ss_stencil.h"

/* A tuning run: the file, its cases, and the best point seen. */
typedef struct {
  const char *text;               /* the stencil file's text */
  const char *where;              /* its path, for messages */
  ss_stencil_params params;       /* its parameters (the free ones searched) */
  int free[SS_STENCIL_MAXPARAMS]; /* indices into params of the free ones */
  int nfree;                      /* their number (the search's dimension) */
  double lo[SS_STENCIL_MAXPARAMS], hi[SS_STENCIL_MAXPARAMS]; /* their ranges */
  ss_check_run *run;                  /* the cases; their margins are the last point's */
  ss_result_opts ro;                  /* how a case is analysed (never certify here) */
  int jobs;                           /* cases analysed at once */
  int progress;                       /* print the best margin on stderr as it improves */
  const char *phase;                  /* "global", "local", "rounding": for progress */
  long evals;                         /* evaluations so far */
  double best;                        /* the best smallest margin seen (-inf before) */
  double bestx[SS_STENCIL_MAXPARAMS]; /* where (the free parameters) */
  double *margins;                    /* ncases: the margins of the last point */
} ss_tune;

/* The smallest margin over the cases at x (the free parameters, each
 * replaced by the nearest rational of denominator <= 99999 first), filling
 * t->margins and updating t->best and t->bestx; -10 when the file does not
 * read at x (e.g. a weight sum that is not 1 there). */
double ss_tune_eval(ss_tune *t, const double *x);

/* Search: NLopt's GN_DIRECT_L over the ranges (2/3 of budget evaluations),
 * then LN_COBYLA from its best point on the epigraph (maximise s subject to
 * s <= margin_i for every case i; the rest of the budget).  The best point
 * is in t->bestx.  0, or -1 with a message in msg (NLopt refused the
 * problem, out of memory). */
int ss_tune_search(ss_tune *t, long budget, char *msg, size_t msgsize);

/* Whether the search is available (the build found NLopt). */
int ss_tune_available(void);

#endif
