/* ss_cli_enumerate_links.c — `enumerate links` (every link with A..B
 * vertices) and `enumerate canonical` (canonical forms of links on stdin). */
#include <getopt.h>
#include <json-c/json.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_enum.h"
#include "ss_link.h"

static const char links_usage[] =
    "usage: subspectra enumerate links --vertices A[..B] [--count] [--part I/N]\n"
    "                                  [--format text|json]\n\n"
    "Every link (triangulation of the sphere, mirror images identified) with A..B\n"
    "vertices, exactly once each, one per line in plantri ASCII; memory stays flat.\n"
    "Counts for k = 4..16: 1, 1, 2, 5, 14, 50, 233, 1249, 7595, 49566, 339722,\n"
    "2406841, 17490241.\n\n"
    "  -k, --vertices A[..B]  vertex counts, 4 <= A <= B <= 20\n"
    "  -c, --count            print only the number of links per vertex count (and\n"
    "                         the rate, on stderr)\n"
    "  -p, --part I/N         only part I of N (0 <= I < N): parts are disjoint, their\n"
    "                         union is everything, each is about 1/N of the work\n"
    "      --format F         text (default) or json: with --count one object, else\n"
    "                         one object per link {\"vertices\": k, \"link\": \"...\"}\n"
    "  -h, --help             this text\n";

static const char canonical_usage[] =
    "usage: subspectra enumerate canonical [--format text|json] < LINKS\n\n"
    "Read links on standard input, one per line (plantri ASCII or a name:\n"
    "tetrahedron, octahedron, icosahedron, bipyramid:N; '#' starts a comment), validate\n"
    "each and print its canonical form: equal for isomorphic or mirrored links,\n"
    "different otherwise.  A malformed line stops the run with exit status 2 and a\n"
    "message naming the line and the problem.\n\n"
    "      --format F   text (default) or json: one object per line with the\n"
    "                   canonical form, vertex count and automorphism count\n"
    "  -h, --help       this text\n";

typedef struct {
  int json;
  uint64_t written;
} out_ctx;

static int print_link(const ss_link *l, void *ctx) {
  out_ctx *o = ctx;
  char *text;
  if (ss_link_format(l, &text, NULL)) return 1;
  if (o->json)
    printf("{\"vertices\":%d,\"link\":\"%s\"}\n", l->k, text);
  else
    puts(text);
  free(text);
  o->written++;
  return ferror(stdout) ? 1 : 0;
}

int ss_cli_enumerate_links(int argc, char **argv) {
  static const struct option opts[] = {{"vertices", required_argument, NULL, 'k'},
                                       {"count", no_argument, NULL, 'c'},
                                       {"part", required_argument, NULL, 'p'},
                                       {"format", required_argument, NULL, 'F'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  long a = -1, b = -1, part = 0, nparts = 1;
  int count = 0, json = 0;
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":k:cp:h", opts, NULL)) != -1) {
    switch (c) {
    case 'k':
      if (ss_cli_parse_range(optarg, &a, &b) || a < 4 || b > SS_ENUM_MAXK || a > b)
        return ss_cli_usage_error(
            "enumerate links", "--vertices '%s' is not A or A..B with 4 <= A <= B <= %d",
            optarg, SS_ENUM_MAXK);
      break;
    case 'c':
      count = 1;
      break;
    case 'p':
      if (ss_cli_parse_part(optarg, &part, &nparts))
        return ss_cli_usage_error("enumerate links",
                                  "--part '%s': need integers 0 <= I < N", optarg);
      break;
    case 'F':
      if (ss_cli_format_option("enumerate links", optarg, &json)) return SS_EXIT_USAGE;
      break;
    case 'h':
      fputs(links_usage, stdout);
      return SS_EXIT_OK;
    default:
      return ss_cli_option_error("enumerate links", c, argv);
    }
  }
  if (optind < argc)
    return ss_cli_usage_error("enumerate links", "unexpected argument '%s'",
                              argv[optind]);
  if (a < 0) return ss_cli_usage_error("enumerate links", "--vertices is required");
  ss_enum_opts o = {(int)a, (int)b, (int)part, (int)nparts};
  out_ctx ctx = {json, 0};
  uint64_t counts[SS_ENUM_MAXK + 1];
  ss_error err = {0};
  double t0 = ss_cli_now();
  if (ss_enum_links(&o, count ? NULL : print_link, &ctx, counts, &err))
    return ss_cli_fail("enumerate links", &err);
  double dt = ss_cli_now() - t0;
  /* the links could not be written (print_link stopped): main reports why */
  if (!count && ferror(stdout)) return SS_EXIT_OK;
  if (count) {
    if (json) {
      json_object *r = json_object_new_object(), *v = json_object_new_object();
      for (long k = a; k <= b; k++) {
        char key[8];
        snprintf(key, sizeof key, "%ld", k);
        json_object_object_add(v, key, json_object_new_int64((int64_t)counts[k]));
      }
      json_object_object_add(r, "counts", v);
      json_object_object_add(r, "part", json_object_new_int64(part));
      json_object_object_add(r, "parts", json_object_new_int64(nparts));
      json_object_object_add(r, "seconds", json_object_new_double(dt));
      printf("%s\n", json_object_to_json_string_ext(r, SS_CLI_JSON_FLAGS));
      json_object_put(r);
    } else {
      printf("# vertices\tlinks%s\n", nparts > 1 ? "\t(this part)" : "");
      for (long k = a; k <= b; k++)
        printf("%ld\t%llu\n", k, (unsigned long long)counts[k]);
    }
  }
  uint64_t total = 0;
  for (long k = a; k <= b; k++)
    total += counts[k];
  fprintf(stderr,
          "subspectra enumerate links: %llu links with %ld..%ld vertices%s in %.2f s "
          "(%.0f links/s)\n",
          (unsigned long long)total, a, b, nparts > 1 ? " (this part)" : "", dt,
          dt > 0 ? (double)total / dt : 0.0);
  return SS_EXIT_OK;
}

int ss_cli_enumerate_canonical(int argc, char **argv) {
  static const struct option opts[] = {{"format", required_argument, NULL, 'F'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  int json = 0;
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":h", opts, NULL)) != -1) {
    switch (c) {
    case 'F':
      if (ss_cli_format_option("enumerate canonical", optarg, &json))
        return SS_EXIT_USAGE;
      break;
    case 'h':
      fputs(canonical_usage, stdout);
      return SS_EXIT_OK;
    default:
      return ss_cli_option_error("enumerate canonical", c, argv);
    }
  }
  if (optind < argc)
    return ss_cli_usage_error(
        "enumerate canonical",
        "unexpected argument '%s' (links are read on standard input)", argv[optind]);
  char *line = NULL;
  size_t cap = 0;
  long lineno = 0, nread = 0;
  int rc = SS_EXIT_OK;
  char *p;
  while ((p = ss_cli_next_item(stdin, &line, &cap, &lineno))) {
    ss_error err = {0};
    ss_link *l = NULL, *cl = NULL;
    int *aut = NULL, naut = 0;
    char *text = NULL;
    if (ss_link_parse(p, &l, &err) || ss_link_canonical(l, &cl, NULL, &err) ||
        ss_link_automorphisms(l, &aut, &naut, &err) || ss_link_format(cl, &text, &err)) {
      fprintf(stderr, "subspectra enumerate canonical: stdin:%ld: %s\n", lineno, err.msg);
      rc = SS_EXIT_USAGE; /* a bad link, or out of memory */
    } else if (json) {
      printf("{\"line\":%ld,\"vertices\":%d,\"automorphisms\":%d,\"canonical\":\"%s\"}\n",
             lineno, cl->k, naut, text);
    } else {
      puts(text);
    }
    nread++;
    free(text);
    free(aut);
    ss_link_free(l);
    ss_link_free(cl);
    if (rc || ferror(stdout)) break; /* output lost: main reports it */
  }
  free(line);
  if (rc == SS_EXIT_OK && nread == 0) {
    fprintf(stderr, "subspectra enumerate canonical: stdin: no links read\n");
    rc = SS_EXIT_USAGE;
  }
  return rc;
}
