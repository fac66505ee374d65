/* ss_cli_report.c — `subspectra report` (being written). */
#include <stdio.h>

#include "ss_cli.h"

int ss_cli_report(int argc, char **argv) {
  (void)argc;
  (void)argv;
  fputs("subspectra report: not yet implemented\n", stderr);
  return SS_EXIT_USAGE;
}
