/* ss_cli_check.h — `subspectra check`'s cases and their reports (text, JSON,
 * JUnit XML) and the comparison with a baseline run (ss_cli_check_out.c). */
#ifndef SS_CLI_CHECK_H
#define SS_CLI_CHECK_H

#include "ss_case.h"
#include "ss_link.h"

/* How one case ended. */
typedef enum {
  SS_CHECK_PASS,      /* every condition passes */
  SS_CHECK_FAIL,      /* some condition fails */
  SS_CHECK_UNDECIDED, /* none fails, some is undecided */
  SS_CHECK_ERROR      /* the analysis could not run (message in reason) */
} ss_check_outcome;

/* One case of a check run. */
typedef struct {
  char *name;               /* "vertex <link>", "edge N" or "face"; owned */
  ss_case c;                /* the case (c.link points at link) */
  ss_link *link;            /* the vertex case's link, owned; NULL otherwise */
  ss_check_outcome outcome; /* how it ended */
  const char *condition;    /* the first condition that does not pass (static
                               text), NULL when passing or on error */
  char reason[600];         /* the verdict's reason or the error message */
  int nomem;                /* an error out of memory or beyond the budget */
  double seconds;           /* wall time of the case */
  int regression;           /* passed in the baseline, does not pass now */
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
