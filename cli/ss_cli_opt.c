/* ss_cli_opt.c — the options several commands share, each defined once: its
 * range, its meaning and its message, so `analyze`, `check` and `sweep` accept
 * the same values and say the same thing about a bad one. */
#include <stdlib.h>

#include "ss_cli.h"

int ss_cli_opt_tol(const char *cmd, const char *arg, double *out) {
  char *end;
  const double t = strtod(arg, &end);
  /* above 0.1 eigenvalues 10 % apart would count as equal: no longer a
   * tolerance of rounding but a different question */
  if (*arg == '\0' || *end != '\0' || !(t > 0.0 && t < SS_CLI_TOL_MAX))
    return ss_cli_usage_error(cmd, "--tol '%s' is not a number in (0, %g)", arg,
                              SS_CLI_TOL_MAX);
  *out = t;
  return 0;
}

int ss_cli_opt_depth(const char *cmd, const char *arg, long *out) {
  if (ss_cli_parse_int(arg, 0, SS_CLI_DEPTH_MAX, out))
    return ss_cli_usage_error(cmd, "--depth '%s' is not an integer in 0..%d", arg,
                              SS_CLI_DEPTH_MAX);
  return 0;
}

int ss_cli_opt_scheme_source(const char *cmd, const char *scheme, const char *stencil) {
  if (!scheme == !stencil)
    return ss_cli_usage_error(cmd, "give exactly one of --scheme and --stencil");
  return 0;
}
