/* ss_cli_reproduce.c — `subspectra reproduce` (being written). */
#include <stdio.h>

#include "ss_cli.h"

int ss_cli_reproduce(int argc, char **argv) {
  (void)argc;
  (void)argv;
  fputs("subspectra reproduce: not yet implemented\n", stderr);
  return SS_EXIT_USAGE;
}
