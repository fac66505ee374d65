/* main.c — `subspectra`: one program, one subcommand per job. */
#include <stdio.h>
#include <string.h>

#include <flint/flint.h>
#include <gsl/gsl_errno.h>

#include "ss_cli.h"

#ifndef SS_VERSION
#define SS_VERSION "0.1.0"
#endif

typedef struct {
  const char *name;         /* subcommand */
  int (*run)(int, char **); /* its entry point */
  const char *summary;      /* one line for the overview */
} command;

static const command commands[] = {
    {"analyze", ss_cli_analyze,
     "local subdivision matrix, eigenstructure, verdicts of a case"},
    {"matrix", ss_cli_matrix, "the local subdivision matrix of a case (Matrix Market)"},
    {"draw", ss_cli_draw, "a picture of a case's characteristic map (PNG, SVG, VTK)"},
    {"enumerate", ss_cli_enumerate, "links (vertex one-rings): all, random, of a mesh"},
    {"subdivide", ss_cli_subdivide, "refine a mesh L times with a scheme"},
    {"check", ss_cli_check, "the CI gate: every case of a stencil file must pass"},
    {"sweep", ss_cli_sweep, "analyse many cases into a resumable SQLite store"},
    {"merge", ss_cli_merge, "join the stores of sweep parts into one"},
    {"report", ss_cli_report, "tables (md, csv, tex, json) and plots of a store"},
    {"reproduce", ss_cli_reproduce, "the papers' tables beside the values they quote"},
};

static void overview(FILE *f) {
  fprintf(f,
          "subspectra %s — spectral analysis and smoothness verification of subdivision "
          "schemes\n\n"
          "usage: subspectra COMMAND [OPTIONS] ...\n\ncommands:\n",
          SS_VERSION);
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    fprintf(f, "  %-12s %s\n", commands[i].name, commands[i].summary);
  fprintf(f, "\n'subspectra COMMAND --help' describes a command.\n"
             "Exit status: 0 ran and everything checked holds, 1 ran and something "
             "checked fails,\n2 bad usage or bad input.\n");
}

int main(int argc, char **argv) {
  /* library code reports through ss_status; GSL must not abort the process */
  gsl_set_error_handler_off();
  if (argc < 2) {
    overview(stderr);
    return SS_EXIT_USAGE;
  }
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
    overview(stdout);
    return SS_EXIT_OK;
  }
  if (!strcmp(argv[1], "--version")) {
    printf("subspectra %s\n", SS_VERSION);
    return SS_EXIT_OK;
  }
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (!strcmp(argv[1], commands[i].name)) {
      const int rc = commands[i].run(argc - 1, argv + 1);
      flint_cleanup_master(); /* FLINT's caches (the exact path, --certify) */
      return rc;
    }
  char name[256];
  fprintf(stderr, "subspectra: unknown command '%s' (see 'subspectra --help')\n",
          ss_error_escape(name, sizeof name, argv[1]));
  return SS_EXIT_USAGE;
}
