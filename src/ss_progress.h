/* ss_progress.h — progress of long computations, reported through a callback
 * the caller passes in its options (no global state: threads analysing
 * different cases each pass their own).  Library code never prints; the
 * command-line tool decides whether and where to show the steps. */
#ifndef SS_PROGRESS_H
#define SS_PROGRESS_H

#include <stddef.h>

#include "ss_api.h"

SS_BEGIN_DECLS

/* One step of a phase: `phase` names it ("refining the star", "eigen-solve
 * outer blocks", ...), done of total steps are finished (total 0: unknown).
 * Called from the computing thread; phase is a constant string. */
typedef void (*ss_progress_fn)(void *ctx, const char *phase, size_t done, size_t total);

/* A progress callback and its context; {NULL, NULL} reports nothing. */
typedef struct {
  ss_progress_fn fn; /* called at each step; NULL: silent */
  void *ctx;         /* passed to fn unchanged */
} ss_progress;

/* Report a step if p has a callback (p may be NULL). */
static inline void ss_progress_step(const ss_progress *p, const char *phase, size_t done,
                                    size_t total) {
  if (p && p->fn) p->fn(p->ctx, phase, done, total);
}

SS_END_DECLS

#endif
