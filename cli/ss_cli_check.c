/* ss_cli_check.c — `subspectra check STENCIL`: the CI gate for new stencils
 * (and, with --scheme, for a built-in scheme such as ccsolid, which no
 * stencil family describes).
 * Runs every case asked for (every link of the vertex range, every edge
 * valence, the face) through extraction, eigenstructure and the regularity
 * test, prints a summary and the cases that do not pass, and exits 0 when all
 * pass, 1 when any fails or is undecided, 2 on bad input. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_enum.h"
#include "ss_link.h"
#include "ss_jac.h"
#include "ss_result.h"
#include "ss_stencil.h"

static const char *const usage_text =
    "usage: subspectra check (STENCIL.ini | --scheme S) [--vertices A..B]\n"
    "                        [--edges A..B] [--face] [--tol T] [--depth D]\n"
    "                        [--certify] [--max-memory SIZE]\n"
    "\n"
    "The CI gate for a new stencil: analyse every case and pass only if all pass.\n"
    "Each case: the local subdivision matrix from the stencil's global rule, its\n"
    "eigenvalue condition (relative tolerance T in (0, 0.1), default 1e-6) and the\n"
    "regularity of its characteristic map (hex subdivision depth D, default 6),\n"
    "exactly as `subspectra analyze` does.  Prints one line per case that fails\n"
    "or is undecided, then a summary.\n"
    "\n"
    "  --vertices A..B   every vertex link with A..B vertices (4 <= A <= B <= 9;\n"
    "                    hex stars for split multilinear, tet stars for tetoct)\n"
    "  --edges A..B      every edge valence A..B (3 <= A <= B <= 64)\n"
    "  --face            the face of two tets (split tetoct only)\n"
    "  --scheme S        a built-in scheme instead of a stencil file (mlca, tetoct,\n"
    "                    boxspline, boxspline-avg, ccsolid)\n"
    "  --certify         prove every verdict (exact spectrum, interval Jacobians);\n"
    "                    a verdict that cannot be proven counts as undecided\n"
    "  --max-memory SIZE memory budget of one case (K, M, G, T: powers of 1000;\n"
    "                    default half the physical memory, 3/4 of ulimit -v and\n"
    "                    -d when set): a case whose estimate exceeds it is not run\n"
    "                    but listed as an error with the estimate\n"
    "  -h, --help        this text\n"
    "With no case option: --vertices 4..6 --edges 3..6 (and --face for tetoct).\n"
    "\n"
    "Exit status: 0 every case passes both conditions, 1 some case fails or is\n"
    "undecided, 2 bad usage, a bad stencil file (the message names file, line\n"
    "and key), or a case out of memory or beyond the memory budget.  In CI:  subspectra "
    "check data/stencils/mine.ini || exit 1\n";

typedef struct {
  const ss_scheme *s;
  double tol;
  int depth;
  int certify;
  double max_bytes; /* memory budget of one case */
  long cases, pass, fail, undecided, errors;
  long nomem; /* of the errors, cases out of memory or beyond the budget */
} gate;

/* Analyse one case; print it unless it passes. */
static void run_case(gate *g, ss_case c, const char *what) {
  ss_error err = {0};
  ss_result r;
  ss_result_opts ro = ss_result_defaults();
  ro.tol = g->tol;
  ro.depth = g->depth;
  ro.certify = g->certify;
  ro.max_bytes = g->max_bytes;
  g->cases++;
  if (ss_result_compute(g->s, &c, &ro, &r, &err)) {
    printf("error      %s: %s\n", what, err.msg);
    g->errors++;
    g->nomem += err.status == SS_ENOMEM;
    return;
  }
  const ss_verdict_kind v = ss_result_verdict(&r);
  ++*(v == SS_PASS ? &g->pass : v == SS_FAIL ? &g->fail : &g->undecided);
  if (v != SS_PASS) { /* the first condition that does not pass */
    const int which = r.v.cond.verdict != SS_PASS  ? 0
                      : r.v.reg.verdict != SS_PASS ? 1
                                                   : 2;
    static const char *const names[3] = {"eigenvalue condition", "regularity",
                                         "injectivity"};
    const ss_verdict *why = which == 0 ? &r.v.cond : which == 1 ? &r.v.reg : &r.v.inj;
    printf("%-10s %s: %s: %s\n", v == SS_UNDECIDED ? "undecided" : "fail", what,
           names[which], why->reason);
  }
  ss_result_clear(&r);
}

static int visit(const ss_link *l, void *ctx) {
  gate *g = ctx;
  ss_error err = {0};
  char *text = NULL;
  if (ss_link_format(l, &text, &err)) {
    g->errors++;
    return 1;
  }
  char what[512];
  snprintf(what, sizeof what, "vertex %s", text);
  run_case(g, (ss_case){SS_CASE_VERTEX, l, 0, SS_DIAG_BFS, 0}, what);
  free(text);
  return 0;
}

int ss_cli_check(int argc, char **argv) {
  static const struct option opts[] = {{"vertices", required_argument, NULL, 'v'},
                                       {"edges", required_argument, NULL, 'e'},
                                       {"face", no_argument, NULL, 'f'},
                                       {"tol", required_argument, NULL, 't'},
                                       {"depth", required_argument, NULL, 'd'},
                                       {"certify", no_argument, NULL, 'c'},
                                       {"max-memory", required_argument, NULL, 'm'},
                                       {"scheme", required_argument, NULL, 's'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  long va = 0, vb = -1, ea = 0, eb = -1, depth = SS_JAC_DEPTH;
  int face = 0, any = 0, certify = 0;
  double tol = 1e-6, max_memory = 0.0;
  const char *scheme = NULL;
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":h", opts, NULL)) != -1) {
    switch (c) {
    case 'v':
      if (ss_cli_parse_range(optarg, &va, &vb) || va < 4 || vb > 9 || va > vb)
        return ss_cli_usage_error(
            "check", "--vertices '%s' is not A..B with 4 <= A <= B <= 9", optarg);
      any = 1;
      break;
    case 'e':
      if (ss_cli_parse_range(optarg, &ea, &eb) || ea < 3 || eb > 64 || ea > eb)
        return ss_cli_usage_error(
            "check", "--edges '%s' is not A..B with 3 <= A <= B <= 64", optarg);
      any = 1;
      break;
    case 'f':
      face = any = 1;
      break;
    case 't':
      if (ss_cli_opt_tol("check", optarg, &tol)) return SS_EXIT_USAGE;
      break;
    case 'd':
      if (ss_cli_opt_depth("check", optarg, &depth)) return SS_EXIT_USAGE;
      break;
    case 'c':
      certify = 1;
      break;
    case 's':
      scheme = optarg;
      break;
    case 'm':
      if (ss_cli_parse_bytes(optarg, &max_memory))
        return ss_cli_usage_error(
            "check", "--max-memory '%s' is not a size such as 8G, 500M or 2.5G", optarg);
      break;
    case 'h':
      fputs(usage_text, stdout);
      return SS_EXIT_OK;
    default:
      return ss_cli_option_error("check", c, argv);
    }
  }
  if (scheme && optind != argc)
    return ss_cli_usage_error("check", "a stencil file and --scheme: give one of them");
  if (!scheme && optind + 1 != argc)
    return ss_cli_usage_error("check", optind == argc ? "no stencil file given"
                                                      : "more than one stencil file");
  const char *path = scheme ? "--scheme" : argv[optind];
  ss_error err = {0};
  ss_scheme *s = NULL;
  if (scheme ? ss_scheme_new(scheme, &s, &err) : ss_stencil_load(path, &s, NULL, &err)) {
    fprintf(stderr, "subspectra check: %s\n", err.msg);
    return SS_EXIT_USAGE; /* a bad stencil file, or out of memory */
  }
  if (ss_cli_refuse_local("check", s)) {
    ss_scheme_free(s);
    return SS_EXIT_USAGE;
  }
  const int tetoct = ss_scheme_split_kind(s) == SS_SPLIT_TETOCT;
  if (face && !tetoct) {
    ss_scheme_free(s);
    return ss_cli_usage_error("check", "--face: the %s's split is not tetoct",
                              scheme ? "scheme" : "stencil");
  }
  if (!any) va = 4, vb = 6, ea = 3, eb = 6, face = tetoct;
  gate g = {s, tol, (int)depth, certify, ss_cli_budget(max_memory), 0, 0, 0, 0, 0, 0};
  if (scheme)
    printf("check scheme %s: relative tolerance %g, hex depth %ld%s\n", ss_scheme_name(s),
           tol, depth, certify ? ", certified verdicts" : "");
  else
    printf("check %s (scheme %s): relative tolerance %g, hex depth %ld%s\n", path,
           ss_scheme_name(s), tol, depth, certify ? ", certified verdicts" : "");
  if (vb >= va) {
    ss_enum_opts eo = {(int)va, (int)vb, 0, 1};
    if (ss_enum_links(&eo, visit, &g, NULL, &err)) {
      fprintf(stderr, "subspectra check: %s\n", err.msg);
      ss_scheme_free(s);
      return ss_cli_exit_status(err.status);
    }
  }
  for (long n = ea; n <= eb; n++) {
    char what[32];
    snprintf(what, sizeof what, "edge %ld", n);
    run_case(&g, (ss_case){SS_CASE_EDGE, NULL, (int)n, SS_DIAG_BFS, 0}, what);
  }
  if (face) run_case(&g, (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, "face");
  printf("%ld cases: %ld pass, %ld fail, %ld undecided, %ld errors\n", g.cases, g.pass,
         g.fail, g.undecided, g.errors);
  ss_scheme_free(s);
  /* a case out of memory or beyond the budget: exit 2, never "a check fails" */
  return g.nomem ? SS_EXIT_USAGE : g.pass == g.cases ? SS_EXIT_OK : SS_EXIT_FAIL;
}
