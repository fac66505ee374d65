/* ss_cli_enumerate_random.c — `enumerate random`: random links from convex
 * hulls of random points on the sphere (ss_link_random.h). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "ss_cli.h"
#include "ss_link.h"
#include "ss_link_random.h"

static const char random_usage[] =
    "usage: subspectra enumerate random --vertices K --samples M [--seed S]\n"
    "                                   [--format text|json]\n\n"
    "M random links on K vertices, one per line in plantri ASCII: each is the\n"
    "boundary of the convex hull of K points drawn uniformly on the unit sphere\n"
    "(GSL's MT19937 seeded with S, gsl_ran_dir_3d; hull by CGAL with exact\n"
    "predicates).  Vertex i is the i-th point.  The same K and S give the same\n"
    "links, byte for byte, and the first M samples do not depend on --samples.\n\n"
    "  -k, --vertices K   link vertices, 4..100000\n"
    "  -n, --samples M    number of links, >= 1\n"
    "      --seed S       seed, 0..4294967295 (default 1; GSL maps 0 to 4357);\n"
    "                     no -s: that is --scheme in the other commands\n"
    "      --format F     text (default) or json: one object per line\n"
    "                     {\"vertices\":K,\"seed\":S,\"sample\":i,\"link\":\"...\"},\n"
    "                     i = 0..M-1\n"
    "  -h, --help         this text\n";

int ss_cli_enumerate_random(int argc, char **argv) {
  static const char cmd[] = "enumerate random";
  static const struct option opts[] = {{"vertices", required_argument, NULL, 'k'},
                                       {"samples", required_argument, NULL, 'n'},
                                       {"seed", required_argument, NULL, 'S'},
                                       {"format", required_argument, NULL, 'F'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  long k = -1, samples = -1, seed = 1;
  int json = 0;
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":k:n:h", opts, NULL)) != -1) {
    switch (c) {
    case 'k':
      if (ss_cli_parse_int(optarg, 4, SS_LINK_MAXK, &k))
        return ss_cli_usage_error(cmd, "--vertices '%s' is not an integer in 4..%d",
                                  optarg, SS_LINK_MAXK);
      break;
    case 'n':
      if (ss_cli_parse_int(optarg, 1, 2000000000L, &samples))
        return ss_cli_usage_error(cmd, "--samples '%s' is not an integer >= 1", optarg);
      break;
    case 'S':
      if (ss_cli_parse_int(optarg, 0, 4294967295L, &seed))
        return ss_cli_usage_error(cmd, "--seed '%s' is not an integer in 0..4294967295",
                                  optarg);
      break;
    case 'F':
      if (ss_cli_format_option(cmd, optarg, &json)) return SS_EXIT_USAGE;
      break;
    case 'h':
      fputs(random_usage, stdout);
      return SS_EXIT_OK;
    default:
      /* -s was --seed here until the one convention made it --scheme
       * everywhere (issue 40): say so rather than "unknown option" */
      if (c == '?' && optopt == 's')
        return ss_cli_usage_error(cmd,
                                  "-s is no longer the seed (it means --scheme in the "
                                  "other commands, and enumerate random has no "
                                  "scheme): give --seed S");
      return ss_cli_option_error(cmd, c, argv);
    }
  }
  if (optind < argc)
    return ss_cli_usage_error(cmd, "unexpected argument '%s'", argv[optind]);
  if (k < 0) return ss_cli_usage_error(cmd, "--vertices is required");
  if (samples < 0) return ss_cli_usage_error(cmd, "--samples is required");

  ss_error err = {0};
  int rc = SS_EXIT_OK;
  ss_link *l = NULL;
  char *text = NULL;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  if (!r) {
    ss_error_nomem(&err, "random generator");
    rc = ss_cli_fail(cmd, &err);
    goto done;
  }
  gsl_rng_set(r, (unsigned long)seed);
  for (long i = 0; i < samples; i++) {
    if (ss_link_random((int)k, r, &l, &err) || ss_link_format(l, &text, &err)) {
      rc = ss_cli_fail(cmd, &err);
      goto done;
    }
    if (json)
      printf("{\"vertices\":%ld,\"seed\":%ld,\"sample\":%ld,\"link\":\"%s\"}\n", k, seed,
             i, text);
    else
      puts(text);
    free(text);
    text = NULL;
    ss_link_free(l);
    l = NULL;
    if (ferror(stdout)) break; /* output lost: main reports it */
  }
done:
  free(text);
  ss_link_free(l);
  gsl_rng_free(r);
  return rc;
}
