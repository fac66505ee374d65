/* ss_cli_enumerate.c — `subspectra enumerate WHAT ...`: dispatch to the
 * link enumerators. */
#include <stdio.h>
#include <string.h>

#include "ss_cli.h"

static const struct {
  const char *name;
  int (*run)(int, char **);
  const char *what;
} subs[] = {
    {"links", ss_cli_enumerate_links, "every link with A..B vertices, once each"},
    {"canonical", ss_cli_enumerate_canonical, "canonical forms of links read on stdin"},
    {"random", ss_cli_enumerate_random,
     "random links from convex hulls of sphere points"},
    {"mesh", ss_cli_enumerate_mesh, "distinct vertex links and edge valences of a mesh"},
};

static void usage(FILE *f) {
  fprintf(f, "usage: subspectra enumerate WHAT [OPTIONS]\n\n"
             "Links are vertex one-rings: triangulations of the sphere, written in\n"
             "plantri's ASCII format (\"4 bcd,adc,abd,acb\"), one per line.\n\n");
  for (size_t i = 0; i < sizeof subs / sizeof subs[0]; i++)
    fprintf(f, "  %-10s %s\n", subs[i].name, subs[i].what);
  fprintf(f, "\n'subspectra enumerate WHAT --help' describes each.\n");
}

int ss_cli_enumerate(int argc, char **argv) {
  if (argc < 2) {
    usage(stderr);
    return SS_EXIT_USAGE;
  }
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    usage(stdout);
    return SS_EXIT_OK;
  }
  for (size_t i = 0; i < sizeof subs / sizeof subs[0]; i++)
    if (!strcmp(argv[1], subs[i].name)) return subs[i].run(argc - 1, argv + 1);
  return ss_cli_usage_error(
      "enumerate", "unknown 'enumerate %s' (links, canonical, random, mesh)", argv[1]);
}
