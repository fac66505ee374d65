/* ss_scheme_impl.h — what a scheme file provides (private). */
#ifndef SS_SCHEME_IMPL_H
#define SS_SCHEME_IMPL_H

#include "ss_scheme.h"
#include "ss_sink.h"

/* The rule of a scheme: given the coarse complex, the split complex `fine`
 * (topology, and positions at the split points) and L, emit every fine
 * vertex's weights into k. */
typedef ss_status (*ss_rule_fn)(const ss_scheme *s, const ss_cx *coarse,
                                const ss_cx *fine, const ss_split *L, ss_sink *k,
                                ss_error *err);

struct ss_scheme {
  char name[64];       /* scheme name, e.g. "mlca" */
  ss_split_kind split; /* topological split */
  unsigned accepts;    /* bit t set: takes cells of type t */
  ss_rule_fn rule;     /* the smoothing rule */
  ss_averaging avg;    /* masks, for averaging-family schemes */
  int reach;           /* 1: a fine vertex's rule reads only the coarse cells
                          holding it; 2: it also reads the coarse
                          neighbourhoods of the vertices it combines */
  int diagonals;       /* 1 if the rule reads major diagonals (ss_diag.h) */
};

/* Allocate a scheme with the given parts. */
ss_status ss_scheme_alloc(const char *name, ss_split_kind split, unsigned accepts,
                          ss_rule_fn rule, ss_scheme **out, ss_error *err);

/* Constructors of the built-in schemes, one per file. */
ss_status ss_scheme_mlca_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_tetoct_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_catmull_clark_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_loop_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_boxspline_new(ss_scheme **out, ss_error *err);
ss_status ss_scheme_boxspline_avg_new(ss_scheme **out, ss_error *err);

#endif
