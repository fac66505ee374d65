/* ss_cli_check.c — `subspectra check STENCIL`: the CI gate for new stencils
 * (and, with --scheme, for a built-in scheme such as ccsolid, which no
 * stencil family describes).
 * Runs every case asked for (every link of the vertex range, every edge
 * valence, the face) through extraction, eigenstructure and the regularity
 * test, prints a summary and the cases that do not pass, and exits 0 when all
 * pass, 1 when any fails or is undecided, 2 on bad input. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_cli_check.h"
#include "ss_clock.h"
#include "ss_enum.h"
#include "ss_link.h"
#include "ss_jac.h"
#include "ss_result.h"
#include "ss_stencil.h"

static const char *const usage_text =
    "usage: subspectra check (STENCIL.ini | --scheme S) [--vertices A..B]\n"
    "                        [--edges A..B] [--face] [--surface-vertices A..B]\n"
    "                        [--links FILE] [--tol T] [--depth D]\n"
    "                        [--certify] [--max-memory SIZE] [--jobs N]\n"
    "                        [--format text|json|junit] [--baseline FILE]\n"
    "                        [--progress]\n"
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
    "  --links FILE      the vertex links in FILE, one a line (plantri ASCII or a\n"
    "                    name; '#' comments; '-' stdin), any number of vertices\n"
    "  --surface-vertices A..B\n"
    "                    every smooth surface vertex of valence A..B (3 <= A <=\n"
    "                    B <= 256): a triangle surface's (Loop-like rules) or a\n"
    "                    quad surface's\n"
    "  -s, --scheme S    a built-in scheme instead of a stencil file (mlca, tetoct,\n"
    "                    boxspline, boxspline-avg, ccsolid, ccsolid-tensor)\n"
    "  --certify         prove every verdict (exact spectrum, interval Jacobians);\n"
    "                    a verdict that cannot be proven counts as undecided\n"
    "  --max-memory SIZE memory budget of one case (K, M, G, T: powers of 1000;\n"
    "                    default half the physical memory, 3/4 of ulimit -v and\n"
    "                    -d when set): a case whose estimate exceeds it is not run\n"
    "                    but listed as an error with the estimate\n"
    "  -j, --jobs N      cases analysed at once, on N threads (default 1); the\n"
    "                    report is the same whatever N\n"
    "  --format F        text (default), json (every case with its outcome,\n"
    "                    condition and reason, and the counts) or junit (JUnit XML,\n"
    "                    one testcase per case; fail and undecided are failures\n"
    "                    with the verdict's reason): the document on stdout, the\n"
    "                    heading and the summary on stderr\n"
    "  --progress        a line on stderr as the cases finish (at most one a\n"
    "                    second, and the last): cases done of all, seconds\n"
    "  --baseline FILE   the JSON of an earlier run (--format json): list the\n"
    "                    regressions (cases that passed there and do not pass\n"
    "                    now) and exit 1 only if there is one\n"
    "  -h, --help        this text\n"
    "With no case option: --vertices 4..6 --edges 3..6 (and --face for tetoct).\n"
    "\n"
    "Exit status: 0 every case passes both conditions, 1 some case fails or is\n"
    "undecided, 2 bad usage, a bad stencil file (the message names file, line\n"
    "and key), or a case out of memory or beyond the memory budget.  With\n"
    "--baseline: 0 no regression, 1 some regression, 2 as above or an unreadable\n"
    "baseline.  In CI:  subspectra check data/stencils/mine.ini || exit 1\n";

typedef struct {
  ss_check_run *run; /* the cases, filled by visit */
  size_t cap;        /* room in run->cases */
  int failed;        /* out of memory while listing */
} gate;

/* Append a case named name (copied) with link l (copied, may be NULL). */
static int add_case(gate *g, ss_case c, const ss_link *l, const char *name) {
  ss_check_run *r = g->run;
  if (r->ncases == g->cap) {
    const size_t cap = g->cap ? 2 * g->cap : 64;
    ss_check_case *k = realloc(r->cases, cap * sizeof *k);
    if (!k) return -1;
    r->cases = k;
    g->cap = cap;
  }
  ss_check_case *k = r->cases + r->ncases;
  memset(k, 0, sizeof *k);
  ss_error err = {0};
  if (!(k->name = strdup(name)) || (l && ss_link_copy(l, &k->link, &err))) {
    free(k->name);
    return -1;
  }
  k->c = c;
  k->c.link = k->link;
  r->ncases++;
  return 0;
}

double ss_check_margin(const ss_result *r) {
  const double fails = -0.01; /* below 0 however close to passing */
  double gap = -1.0;          /* (|lambda3| - |lambda4|) / |lambda3| */
  if (r->neig > 4) {
    const double l3 = hypot(r->eig[3].re, r->eig[3].im);
    const double l4 = hypot(r->eig[4].re, r->eig[4].im);
    if (l3 > 0) gap = (l3 - l4) / l3;
  }
  if (r->v.cond.verdict != SS_PASS) return fmin(gap, 0.0) + fails;
  double m = gap;
  if (r->v.reg.verdict != SS_PASS)
    m = fmin(m, (isnan(r->min_sj) ? 0.0 : fmin(r->min_sj, 0.0)) + fails);
  else if (!isnan(r->min_sj))
    m = fmin(m, r->min_sj);
  if (r->v.inj.verdict != SS_PASS) m = fmin(m, fails);
  return m;
}

/* Analyse one case into k (thread-safe: the scheme is shared read-only). */
static void run_case(const ss_scheme *s, const ss_result_opts *ro, ss_check_case *k) {
  static const char *const names[3] = {"eigenvalue condition", "regularity",
                                       "injectivity"};
  ss_error err = {0};
  ss_result r;
  const double t0 = ss_clock_wall();
  k->margin = -10.0;
  k->condition = NULL;
  k->reason[0] = '\0';
  if (ss_result_compute(s, &k->c, ro, &r, &err)) {
    k->outcome = SS_CHECK_ERROR;
    snprintf(k->reason, sizeof k->reason, "%s", err.msg);
    k->nomem = err.status == SS_ENOMEM;
    k->seconds = ss_clock_wall() - t0;
    return;
  }
  k->margin = ss_check_margin(&r);
  const ss_verdict_kind v = ss_result_verdict(&r);
  k->outcome = v == SS_PASS   ? SS_CHECK_PASS
               : v == SS_FAIL ? SS_CHECK_FAIL
                              : SS_CHECK_UNDECIDED;
  if (v != SS_PASS) { /* the first condition that does not pass */
    const int which = r.v.cond.verdict != SS_PASS  ? 0
                      : r.v.reg.verdict != SS_PASS ? 1
                                                   : 2;
    const ss_verdict *why = which == 0 ? &r.v.cond : which == 1 ? &r.v.reg : &r.v.inj;
    k->condition = names[which];
    snprintf(k->reason, sizeof k->reason, "%s", why->reason);
  }
  ss_result_clear(&r);
  k->seconds = ss_clock_wall() - t0;
}

static int visit(const ss_link *l, void *ctx) {
  gate *g = ctx;
  ss_error err = {0};
  char *text = NULL;
  if (ss_link_format(l, &text, &err)) {
    g->failed = 1;
    return 1;
  }
  char what[512];
  snprintf(what, sizeof what, "vertex %s", text);
  free(text);
  if (add_case(g, (ss_case){SS_CASE_VERTEX, NULL, 0, SS_DIAG_BFS, 0}, l, what)) {
    g->failed = 1;
    return 1;
  }
  return 0;
}

/* A vertex case of --links (ss_cli_read_links: l is ours). */
static int take_link(ss_link *l, void *ctx) {
  const int rc = visit(l, ctx);
  ss_link_free(l);
  return rc;
}

/* Run every case on `jobs` threads; in text format print each case that does
 * not pass as soon as it and every case before it are done (the order of the
 * list, whatever the threads); with progress a line on stderr at most once a
 * second as they are done, and after the last. */
void ss_check_analyse(ss_check_run *r, const ss_scheme *s, const ss_result_opts *ro,
                      int jobs, int text, int progress) {
  const long n = (long)r->ncases;
  memset(r->count, 0, sizeof r->count);
  r->nomem = 0;
  const double t0 = ss_clock_wall();
  double last = t0;
#pragma omp parallel for schedule(dynamic, 1) ordered num_threads(jobs)
  for (long i = 0; i < n; i++) {
    run_case(s, ro, r->cases + i);
#pragma omp ordered
    {
      if (text) {
        ss_check_print_case(r->cases + i);
        fflush(stdout);
      }
      const double t = ss_clock_wall();
      if (progress && (t - last >= 1.0 || i == n - 1)) {
        fprintf(stderr, "subspectra check: [%.1f s] %ld/%ld cases done\n", t - t0, i + 1,
                n);
        last = t;
      }
    }
  }
  for (size_t i = 0; i < r->ncases; i++) {
    r->count[r->cases[i].outcome]++;
    r->nomem += r->cases[i].nomem;
  }
}

void ss_check_run_free(ss_check_run *r) {
  for (size_t i = 0; i < r->ncases; i++) {
    free(r->cases[i].name);
    ss_link_free(r->cases[i].link);
  }
  free(r->cases);
}

/* The options of a check run. */
typedef struct {
  ss_check_cases k; /* the cases */
  long depth, jobs;
  int certify, format; /* format: 0 text, 1 json, 2 junit */
  int progress;        /* --progress: lines on stderr */
  double tol, max_memory;
  const char *scheme, *baseline;
} check_opts;

/* Parse argv into o; -1 done (help printed), else the exit status of a usage
 * error or 0. */
static int parse_opts(int argc, char **argv, check_opts *o) {
  static const struct option opts[] = {{"vertices", required_argument, NULL, 'v'},
                                       {"edges", required_argument, NULL, 'e'},
                                       {"face", no_argument, NULL, 'f'},
                                       {"links", required_argument, NULL, 'L'},
                                       {"surface-vertices", required_argument, NULL, 'S'},
                                       {"tol", required_argument, NULL, 't'},
                                       {"depth", required_argument, NULL, 'd'},
                                       {"certify", no_argument, NULL, 'c'},
                                       {"max-memory", required_argument, NULL, 'm'},
                                       {"scheme", required_argument, NULL, 's'},
                                       {"format", required_argument, NULL, 'F'},
                                       {"jobs", required_argument, NULL, 'j'},
                                       {"baseline", required_argument, NULL, 'b'},
                                       {"progress", no_argument, NULL, 'P'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":hs:j:", opts, NULL)) != -1) {
    const int co = ss_check_case_option(c, optarg, "check", &o->k);
    if (co >= 0) {
      if (co) return co;
      continue;
    }
    switch (c) {
    case 't':
      if (ss_cli_opt_tol("check", optarg, &o->tol)) return SS_EXIT_USAGE;
      break;
    case 'd':
      if (ss_cli_opt_depth("check", optarg, &o->depth)) return SS_EXIT_USAGE;
      break;
    case 'c':
      o->certify = 1;
      break;
    case 's':
      o->scheme = optarg;
      break;
    case 'm':
      if (ss_cli_parse_bytes(optarg, &o->max_memory))
        return ss_cli_usage_error(
            "check", "--max-memory '%s' is not a size such as 8G, 500M or 2.5G", optarg);
      break;
    case 'F':
      if (!strcmp(optarg, "text") || !strcmp(optarg, "json") || !strcmp(optarg, "junit"))
        o->format = optarg[0] == 't' ? 0 : optarg[1] == 's' ? 1 : 2;
      else
        return ss_cli_usage_error(
            "check", "--format '%s' is not one of text, json, junit", optarg);
      break;
    case 'j':
      if (ss_cli_parse_int(optarg, 1, 1024, &o->jobs))
        return ss_cli_usage_error("check", "--jobs '%s' is not an integer in 1..1024",
                                  optarg);
      break;
    case 'b':
      o->baseline = optarg;
      break;
    case 'P':
      o->progress = 1;
      break;
    case 'h':
      fputs(usage_text, stdout);
      return -1;
    default:
      return ss_cli_option_error("check", c, argv);
    }
  }
  if (o->scheme && optind != argc)
    return ss_cli_usage_error("check", "a stencil file and --scheme: give one of them");
  if (!o->scheme && optind + 1 != argc)
    return ss_cli_usage_error("check", optind == argc ? "no stencil file given"
                                                      : "more than one stencil file");
  return 0;
}

int ss_check_case_option(int c, const char *arg, const char *cmd, ss_check_cases *k) {
  if (c == 'v') {
    if (ss_cli_parse_range(arg, &k->va, &k->vb) || k->va < 4 || k->vb > 9 ||
        k->va > k->vb)
      return ss_cli_usage_error(cmd, "--vertices '%s' is not A..B with 4 <= A <= B <= 9",
                                arg);
  } else if (c == 'e') {
    if (ss_cli_parse_range(arg, &k->ea, &k->eb) || k->ea < 3 || k->eb > 64 ||
        k->ea > k->eb)
      return ss_cli_usage_error(cmd, "--edges '%s' is not A..B with 3 <= A <= B <= 64",
                                arg);
  } else if (c == 'f') {
    k->face = 1;
  } else if (c == 'L') {
    k->links = arg;
  } else if (c == 'S') {
    if (ss_cli_parse_range(arg, &k->sa, &k->sb) || k->sa < 3 || k->sb > 256 ||
        k->sa > k->sb)
      return ss_cli_usage_error(
          cmd, "--surface-vertices '%s' is not A..B with 3 <= A <= B <= 256", arg);
  } else {
    return -1;
  }
  k->any = 1;
  return 0;
}

int ss_check_cases_default(ss_check_cases *k, const char *cmd, int tetoct,
                           const char *what) {
  if (k->face && !tetoct)
    return ss_cli_usage_error(cmd, "--face: the %s's split is not tetoct", what);
  if (!k->any) k->va = 4, k->vb = 6, k->ea = 3, k->eb = 6, k->face = tetoct;
  return 0;
}

int ss_check_list(ss_check_run *r, const char *cmd, const ss_check_cases *k) {
  gate G = {r, 0, 0}, *g = &G;
  ss_error err = {0};
  const long va = k->va, vb = k->vb, ea = k->ea, eb = k->eb;
  const int face = k->face;
  if (vb >= va) {
    ss_enum_opts eo = {(int)va, (int)vb, 0, 1};
    if (ss_enum_links(&eo, visit, g, NULL, &err) || g->failed) {
      fprintf(stderr, "subspectra %s: %s\n", cmd, g->failed ? "out of memory" : err.msg);
      return g->failed ? SS_EXIT_USAGE : ss_cli_exit_status(err.status);
    }
  }
  if (k->links) {
    const int rc = ss_cli_read_links(cmd, k->links, take_link, g);
    if (rc) return rc;
  }
  for (long n = ea; n <= eb; n++) {
    char what[32];
    snprintf(what, sizeof what, "edge %ld", n);
    if (add_case(g, (ss_case){SS_CASE_EDGE, NULL, (int)n, SS_DIAG_BFS, 0}, NULL, what))
      goto nomem;
  }
  if (face && add_case(g, (ss_case){SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0}, NULL, "face"))
    goto nomem;
  for (long n = k->sa; n <= k->sb; n++) {
    char what[40];
    snprintf(what, sizeof what, "surface-vertex %ld", n);
    if (add_case(g, (ss_case){SS_CASE_SURFACE_VERTEX, NULL, (int)n, SS_DIAG_BFS, 0}, NULL,
                 what))
      goto nomem;
  }
  return 0;
nomem:
  fprintf(stderr, "subspectra %s: out of memory\n", cmd);
  return SS_EXIT_USAGE;
}

/* Report r as o asks; then the exit status. */
static int report(ss_check_run *r, const check_opts *o) {
  if (o->baseline) {
    char msg[1024];
    if (ss_check_baseline(r, o->baseline, msg, sizeof msg)) {
      fprintf(stderr, "subspectra check: %s\n", msg);
      return SS_EXIT_USAGE;
    }
  }
  FILE *info = o->format ? stderr : stdout; /* stdout is the document */
  if ((o->format == 1 && ss_check_write_json(r)) ||
      (o->format == 2 && ss_check_write_junit(r))) {
    fprintf(stderr, "subspectra check: out of memory writing the report\n");
    return SS_EXIT_USAGE;
  }
  fflush(stdout);
  fprintf(info, "%zu cases: %ld pass, %ld fail, %ld undecided, %ld errors\n", r->ncases,
          r->count[SS_CHECK_PASS], r->count[SS_CHECK_FAIL], r->count[SS_CHECK_UNDECIDED],
          r->count[SS_CHECK_ERROR]);
  if (o->baseline) {
    fprintf(info, "%ld regressions against %s\n", r->regressions, o->baseline);
    for (size_t i = 0; i < r->ncases; i++)
      if (r->cases[i].regression)
        fprintf(info, "regression %s: %s: %s\n", r->cases[i].name,
                r->cases[i].condition ? r->cases[i].condition : "error",
                r->cases[i].reason);
  }
  /* a case out of memory or beyond the budget: exit 2, never "a check fails" */
  if (r->nomem) return SS_EXIT_USAGE;
  if (o->baseline) return r->regressions ? SS_EXIT_FAIL : SS_EXIT_OK;
  return r->count[SS_CHECK_PASS] == (long)r->ncases ? SS_EXIT_OK : SS_EXIT_FAIL;
}

int ss_cli_check(int argc, char **argv) {
  check_opts o = {SS_CHECK_CASES_NONE, SS_JAC_DEPTH, 1, 0, 0, 0, 1e-6, 0.0, NULL, NULL};
  const int pr = parse_opts(argc, argv, &o);
  if (pr) return pr < 0 ? SS_EXIT_OK : pr;
  const char *path = o.scheme ? "--scheme" : argv[optind];
  ss_error err = {0};
  ss_scheme *s = NULL;
  if (o.scheme ? ss_scheme_new(o.scheme, &s, &err)
               : ss_stencil_load(path, &s, NULL, &err)) {
    fprintf(stderr, "subspectra check: %s\n", err.msg);
    return SS_EXIT_USAGE; /* a bad stencil file, or out of memory */
  }
  if (ss_cli_refuse_local("check", s)) {
    ss_scheme_free(s);
    return SS_EXIT_USAGE;
  }
  const int tetoct = ss_scheme_split_kind(s) == SS_SPLIT_TETOCT;
  const int bad =
      ss_check_cases_default(&o.k, "check", tetoct, o.scheme ? "scheme" : "stencil");
  if (bad) {
    ss_scheme_free(s);
    return bad;
  }
  ss_check_run run = {o.scheme ? NULL : path,
                      ss_scheme_name(s),
                      o.tol,
                      (int)o.depth,
                      o.certify,
                      NULL,
                      0,
                      {0, 0, 0, 0},
                      0,
                      -1};
  ss_result_opts ro = ss_result_defaults();
  ro.tol = o.tol;
  ro.depth = (int)o.depth;
  ro.certify = o.certify;
  ro.max_bytes = ss_cli_budget(o.max_memory) / (double)o.jobs;
  FILE *info = o.format ? stderr : stdout;
  if (o.scheme)
    fprintf(info, "check scheme %s: relative tolerance %g, hex depth %ld%s\n",
            ss_scheme_name(s), o.tol, o.depth, o.certify ? ", certified verdicts" : "");
  else
    fprintf(info, "check %s (scheme %s): relative tolerance %g, hex depth %ld%s\n", path,
            ss_scheme_name(s), o.tol, o.depth, o.certify ? ", certified verdicts" : "");
  int status = ss_check_list(&run, "check", &o.k);
  if (!status) {
    ss_check_analyse(&run, s, &ro, (int)o.jobs, o.format == 0, o.progress);
    status = report(&run, &o);
  }
  ss_check_run_free(&run);
  ss_scheme_free(s);
  return status;
}
