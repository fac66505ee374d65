/* ss_cli_check.h — `subspectra check`'s cases and their reports (text, JSON,
 * JUnit XML) and the comparison with a baseline run (ss_cli_check_out.c). */
#ifndef SS_CLI_CHECK_H
#define SS_CLI_CHECK_H

#include "ss_case.h"
#include "ss_link.h"
#include "ss_result.h"
#include "ss_scheme.h"

/* How one case ended. */
typedef enum {
  SS_CHECK_PASS,      /* every condition passes */
  SS_CHECK_FAIL,      /* some condition fails */
  SS_CHECK_UNDECIDED, /* none fails, some is undecided */
  SS_CHECK_ERROR      /* the analysis could not run (message in reason) */
} ss_check_outcome;

/* One case of a check run. */
typedef struct {
  char *name;               /* "vertex <link>", "edge N", "face" or
                               "surface-vertex N"; owned */
  ss_case c;                /* the case (c.link points at link) */
  ss_link *link;            /* the vertex case's link, owned; NULL otherwise */
  ss_check_outcome outcome; /* how it ended */
  const char *condition;    /* the first condition that does not pass (static
                               text), NULL when passing or on error */
  char reason[600];         /* the verdict's reason or the error message */
  int nomem;                /* an error out of memory or beyond the budget */
  double seconds;           /* wall time of the case */
  int regression;           /* passed in the baseline, does not pass now */
  double margin;            /* ss_check_margin of the result; -10 on error */
} ss_check_case;

/* A whole run. */
typedef struct {
  const char *stencil;  /* the stencil file, NULL with --scheme */
  const char *scheme;   /* the scheme's name */
  double tol;           /* relative tolerance */
  int depth;            /* hex depth */
  int certify;          /* certified verdicts */
  ss_check_case *cases; /* ncases cases in the order they are listed */
  size_t ncases;        /* number of cases */
  long count[4];        /* cases by outcome (ss_check_outcome) */
  long nomem;           /* errors out of memory or beyond the budget */
  long regressions;     /* cases marked regression */
} ss_check_run;

/* The cases asked for on the command line (check, tune). */
typedef struct {
  long va, vb;       /* vertex links with va..vb vertices; none when vb < va */
  long ea, eb;       /* edge valences ea..eb; none when eb < ea */
  int face;          /* the face of two tets */
  int any;           /* some case option was given */
  long sa, sb;       /* surface vertices of valences sa..sb; none when sb < sa */
  const char *links; /* --links FILE: vertex links one a line ('-' stdin); NULL none */
} ss_check_cases;

/* No case yet. */
#define SS_CHECK_CASES_NONE                                                              \
  { 0, -1, 0, -1, 0, 0, 0, -1, NULL }

/* Option c of getopt_long with its argument arg if it is a case option
 * ('v' --vertices A..B with 4 <= A <= B <= 9, 'e' --edges A..B with
 * 3 <= A <= B <= 64, 'f' --face, 'S' --surface-vertices A..B with
 * 3 <= A <= B <= 256, 'L' --links FILE): 0 taken into k, SS_EXIT_USAGE after a message
 * ("subspectra CMD: ..."), -1 not a case option. */
int ss_check_case_option(int c, const char *arg, const char *cmd, ss_check_cases *k);

/* After the options: --face refused unless tetoct (SS_EXIT_USAGE after a
 * message naming what, "scheme" or "stencil"); with no case option the
 * defaults --vertices 4..6 --edges 3..6, and --face for tetoct.  0 or 2. */
int ss_check_cases_default(ss_check_cases *k, const char *cmd, int tetoct,
                           const char *what);

/* List the cases k into r->cases (appended; --links' links after --vertices',
 * in the file's order, as given: no isomorphic repeats are dropped).  0, or an exit
 * status after a message on stderr ("subspectra CMD: ..."). */
int ss_check_list(ss_check_run *r, const char *cmd, const ss_check_cases *k);

/* Analyse every case of r under s (shared read-only) with ro on `jobs`
 * threads: each case's outcome, reason and margin, r->count and r->nomem
 * (reset first).  With text, print each case that does not pass as soon as
 * it and every case before it are done (the list's order, whatever the
 * threads); with progress, a line on stderr at most once a second (check's
 * --progress). */
void ss_check_analyse(ss_check_run *r, const ss_scheme *s, const ss_result_opts *ro,
                      int jobs, int text, int progress);

/* Free r's cases (names, links, the list). */
void ss_check_run_free(ss_check_run *r);

/* How far a case is from failing, the quantity `tune` maximises: the
 * spectral gap (|lambda3| - |lambda4|) / |lambda3| of the leading moduli,
 * and when the characteristic map is judged the smaller of it and the ring's
 * minimum scaled Jacobian.  Positive when every verdict passes (a passing
 * case has both positive); a case that does not pass gets min(gap or
 * Jacobian, 0) - 0.01, so that failing is always below passing and a
 * nearer failure above a farther one. */
double ss_check_margin(const ss_result *r);

/* The outcome's name: pass, fail, undecided, error. */
const char *ss_check_outcome_name(ss_check_outcome o);

/* The text line of a case that does not pass (nothing for a pass), as
 * `check` has always printed it. */
void ss_check_print_case(const ss_check_case *k);

/* The whole run as a JSON document or as JUnit XML (one testcase per case;
 * fail and undecided are <failure>s with the verdict's reason, errors
 * <error>s), on stdout.  0, or -1 out of memory. */
int ss_check_write_json(const ss_check_run *r);
int ss_check_write_junit(const ss_check_run *r);

/* Mark the regressions of r against the JSON of an earlier run at path
 * (cases that passed there and do not pass now; cases absent there are no
 * regressions) and count them.  0, or -1 with a message in msg (unreadable
 * or malformed file). */
int ss_check_baseline(ss_check_run *r, const char *path, char *msg, size_t msgsize);

#endif
