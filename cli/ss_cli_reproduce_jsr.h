/* ss_cli_reproduce_jsr.h — the joint-spectral-radius tables of `subspectra
 * reproduce` (the Levin-Levin test, ss_levin.h, ss_jsr.h; issue 18). */
#ifndef SS_CLI_REPRODUCE_JSR_H
#define SS_CLI_REPRODUCE_JSR_H

#include <stddef.h>

#include "ss_error.h"
#include "ss_report_ref.h"

/* Counts of one JSR table, for the progress line. */
typedef struct {
  size_t cases;   /* rows */
  size_t pass;    /* verdict pass (upper < threshold) */
  size_t quoted;  /* quoted values compared (jsr_* rows of the reference) */
  size_t match;   /* of those, matching */
  size_t reduced; /* rows where the reduction applied (the others: a reason) */
} ss_jsr_tally;

/* Number of JSR tables. */
size_t ss_reproduce_jsr_count(void);

/* File stem of table i (0 <= i < ss_reproduce_jsr_count()). */
const char *ss_reproduce_jsr_name(size_t i);

/* Compute table i and write DIR/NAME.md, DIR/NAME.tsv and DIR/data/NAME.jsonl
 * (each whole or not at all), comparing each row with the reference rows of
 * quantity jsr_threshold and jsr_verdict that speak of it.  Deterministic:
 * the branch and bound runs under a fixed node budget, no time limit.  A case
 * the reduction does not apply to (SS_EINTERNAL from ss_levin_new: the
 * spectrum of S_1 is not of the required form) is a row with its reason;
 * other failures are returned (SS_EIO, SS_ENOMEM, SS_ENUMERIC, ...). */
ss_status ss_reproduce_jsr_table(size_t i, const char *dir, const ss_ref *ref,
                                 ss_jsr_tally *ty, ss_error *err);

#endif
