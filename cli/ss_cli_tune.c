/* ss_cli_tune.c — `subspectra tune STENCIL`: choose a stencil file's free
 * parameters ([param] NAME = ?(LO, HI)) so that every case passes with the
 * largest smallest margin, write the file with exact rationals there and
 * check it with certified verdicts (ss_cli_tune.h). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_cli_tune.h"
#include "ss_jac.h"

static const char *const usage_text =
    "usage: subspectra tune STENCIL.ini [--vertices A..B] [--edges A..B] [--face]\n"
    "                       [--evals N] [--jobs N] [-o FILE] [--keep F]\n"
    "                       [--links FILE] [--tol T] [--depth D] [--progress]\n"
    "\n"
    "Choose the free parameters of a stencil file ([param] NAME = ?(LO, HI), used\n"
    "by name in the weights) so that every case passes, maximising the smallest\n"
    "margin over the cases: the spectral gap (lambda3 - |lambda4|) / lambda3 and\n"
    "the ring's minimum scaled Jacobian of the characteristic map, the smaller\n"
    "of the two; a case that does not pass has a margin below 0.  NLopt's\n"
    "DIRECT_L searches the ranges globally (2/3 of the evaluations), then COBYLA\n"
    "refines its best point (maximise s subject to s <= every case's margin).\n"
    "The optimum is rounded to the rationals of smallest denominators within\n"
    "(HI - LO) 10^-j of it, j = 2, 3, ... 9, the first whose margin keeps F of\n"
    "the best (default 0.9), written as `NAME = p/q` in place of the range, and\n"
    "the written file is read again and checked as `check --certify` does.\n"
    "\n"
    "  --vertices A..B   every vertex link with A..B vertices (4 <= A <= B <= 9)\n"
    "  --edges A..B      every edge valence A..B (3 <= A <= B <= 64)\n"
    "  --face            the face of two tets (split tetoct only)\n"
    "  --links FILE      the vertex links in FILE, one a line (plantri ASCII or a\n"
    "                    name; '#' comments; '-' stdin), any number of vertices\n"
    "  --evals N         evaluations of every case at one point (default 120,\n"
    "                    2..100000)\n"
    "  -j, --jobs N      cases analysed at once, on N threads (default 1)\n"
    "  -o, --output FILE the tuned stencil (default STENCIL-tuned.ini beside it)\n"
    "  --keep F          the share of the best margin a rounded point must keep\n"
    "                    (0 < F <= 1, default 0.9)\n"
    "  --tol T, --depth D  as for check (relative tolerance, hex depth)\n"
    "  --progress        the best margin on stderr whenever it improves\n"
    "  -h, --help        this text\n"
    "With no case option: --vertices 4..6 --edges 3..6 (and --face for tetoct).\n"
    "A rational point is needed for exact weights; during the search each\n"
    "parameter is replaced by its nearest rational of denominator <= 99999.\n"
    "\n"
    "Exit status: 0 the written file passes every case, certified; 1 the best\n"
    "point found does not make every case pass, or its certified check does not\n"
    "(the file is written all the same); 2 bad usage, a bad stencil file (no\n"
    "free parameter, or one no weight uses), a case out of memory, or a build\n"
    "without NLopt.\n";

/* The nearest rational to x of denominator <= maxden (continued fraction
 * convergents and the last semiconvergent). */
static void nearest_rational(double x, long long maxden, long long *p, long long *q) {
  long long h0 = 0, h1 = 1, k0 = 1, k1 = 0; /* convergents h/k */
  double r = x;
  for (int i = 0; i < 64; i++) {
    const double a = floor(r);
    if (fabs(a) > 1e15) break;
    const long long ai = (long long)a;
    if (k1 * ai + k0 > maxden) { /* the best semiconvergent, or h1/k1 */
      const long long m = k1 ? (maxden - k0) / k1 : 0;
      const long long hs = m * h1 + h0, ks = m * k1 + k0;
      if (ks > 0 && (k1 == 0 || fabs(x - (double)hs / ks) < fabs(x - (double)h1 / k1)))
        h1 = hs, k1 = ks;
      break;
    }
    const long long h2 = ai * h1 + h0, k2 = ai * k1 + k0;
    h0 = h1, k0 = k1, h1 = h2, k1 = k2;
    if (r == a) break;
    r = 1.0 / (r - a);
  }
  *p = h1, *q = k1 > 0 ? k1 : 1;
}

/* The rational of smallest denominator in [a, b] (0 <= a <= b, doubles):
 * 0, or -1 past depth 40 (never for the intervals tune asks about). */
static int simplest_pos(double a, double b, int depth, long long *p, long long *q) {
  const double fa = floor(a);
  if (fa == a || fa + 1.0 <= b) {
    *p = (long long)(fa == a ? fa : fa + 1.0), *q = 1;
    return 0;
  }
  long long pp, qq;
  if (depth > 40 || simplest_pos(1.0 / (b - fa), 1.0 / (a - fa), depth + 1, &pp, &qq))
    return -1;
  *p = (long long)fa * pp + qq, *q = pp; /* fa + 1 / (pp / qq) */
  return 0;
}

static int simplest(double a, double b, long long *p, long long *q) {
  if (a <= 0.0 && b >= 0.0) return *p = 0, *q = 1, 0;
  if (b < 0.0) {
    const int r = simplest_pos(-b, -a, 0, p, q);
    *p = -*p;
    return r;
  }
  return simplest_pos(a, b, 0, p, q);
}

/* The parameter values at x (free ones from x as p/q). */
static void values_at(const ss_tune *t, const long long *num, const long long *den,
                      ss_stencil_params *v) {
  *v = t->params;
  for (int i = 0; i < t->nfree; i++) {
    ss_stencil_param *p = v->p + t->free[i];
    p->free = 0, p->num = num[i], p->den = den[i];
  }
}

/* The smallest margin at the rational point (num, den), filling t->margins. */
static double eval_rational(ss_tune *t, const long long *num, const long long *den) {
  ss_stencil_params v;
  values_at(t, num, den, &v);
  ss_scheme *s = NULL;
  ss_error err = {0};
  double m = -10.0;
  const size_t nc = t->run->ncases;
  if (!ss_stencil_parse_at(t->text, t->where, &v, &s, &err)) {
    ss_check_analyse(t->run, s, &t->ro, t->jobs, 0, 0);
    m = INFINITY;
    for (size_t i = 0; i < nc; i++)
      m = fmin(m, t->margins[i] = t->run->cases[i].margin);
  } else {
    for (size_t i = 0; i < nc; i++)
      t->margins[i] = -10.0;
  }
  ss_scheme_free(s);
  t->evals++;
  return m;
}

double ss_tune_eval(ss_tune *t, const double *x) {
  long long num[SS_STENCIL_MAXPARAMS], den[SS_STENCIL_MAXPARAMS];
  for (int i = 0; i < t->nfree; i++)
    nearest_rational(fmin(fmax(x[i], t->lo[i]), t->hi[i]), 99999, num + i, den + i);
  const double m = eval_rational(t, num, den);
  if (m > t->best) {
    t->best = m;
    memcpy(t->bestx, x, (size_t)t->nfree * sizeof *x);
    if (t->progress) {
      fprintf(stderr, "subspectra tune: [%s] evaluation %ld: best margin %.6g at",
              t->phase, t->evals, m);
      for (int i = 0; i < t->nfree; i++)
        fprintf(stderr, " %s = %.9g", t->params.p[t->free[i]].name, x[i]);
      fputc('\n', stderr);
    }
  }
  return m;
}

/* The rounded point: for j = 2..9 the simplest rationals within (hi - lo)
 * 10^-j of t->bestx, the first keeping `keep` of the best margin; else the
 * search's own rational point.  Into num, den; returns its margin. */
static double round_best(ss_tune *t, double keep, long long *num, long long *den) {
  const double best = t->best, want = best - (1.0 - keep) * fabs(best);
  t->phase = "rounding";
  for (int j = 2; j <= 9; j++) {
    int ok = 1;
    for (int i = 0; ok && i < t->nfree; i++) {
      const double d = (t->hi[i] - t->lo[i]) * pow(10.0, -j), x = t->bestx[i];
      ok = !simplest(fmax(x - d, t->lo[i]), fmin(x + d, t->hi[i]), num + i, den + i) &&
           llabs(num[i]) <= 999999 && den[i] <= 999999;
    }
    if (!ok) break;
    const double m = eval_rational(t, num, den);
    if (m >= want) return m;
  }
  for (int i = 0; i < t->nfree; i++)
    nearest_rational(fmin(fmax(t->bestx[i], t->lo[i]), t->hi[i]), 99999, num + i,
                     den + i);
  return eval_rational(t, num, den);
}

/* "p/q", or "p" when q = 1, into buf (48 bytes). */
static const char *fmt_rational(char *buf, long long num, long long den) {
  if (den == 1)
    snprintf(buf, 48, "%lld", num);
  else
    snprintf(buf, 48, "%lld/%lld", num, den);
  return buf;
}

/* t->text with each free parameter's line replaced by "NAME = p/q ; ...";
 * NULL out of memory. */
static char *tuned_text(const ss_tune *t, const long long *num, const long long *den,
                        double margin) {
  const size_t len = strlen(t->text);
  char *out = malloc(len + (size_t)t->nfree * 200 + 1), *o = out;
  if (!out) return NULL;
  int line = 1;
  for (const char *p = t->text; *p;) {
    const char *e = strchr(p, '\n');
    const size_t n = e ? (size_t)(e - p) + 1 : strlen(p);
    int k = -1;
    for (int i = 0; i < t->nfree; i++)
      if (t->params.p[t->free[i]].line == line) k = i;
    if (k < 0) {
      memcpy(o, p, n);
      o += n;
    } else {
      const ss_stencil_param *q = t->params.p + t->free[k];
      char v[48], lo[48], hi[48];
      o += sprintf(
          o, "%s = %s  ; tuned by subspectra tune in ?(%s, %s): smallest margin %.6g\n",
          q->name, fmt_rational(v, num[k], den[k]), fmt_rational(lo, q->lo[0], q->lo[1]),
          fmt_rational(hi, q->hi[0], q->hi[1]), margin);
    }
    p += n, line++;
  }
  *o = '\0';
  return out;
}

/* The options of a tune run. */
typedef struct {
  ss_check_cases k; /* the cases */
  long depth, jobs, evals;
  int progress;
  double tol, keep;
  const char *output;
} tune_opts;

/* Parse argv into o; -1 done (help printed), else the exit status of a usage
 * error or 0. */
static int parse_opts(int argc, char **argv, tune_opts *o) {
  static const struct option opts[] = {{"vertices", required_argument, NULL, 'v'},
                                       {"edges", required_argument, NULL, 'e'},
                                       {"face", no_argument, NULL, 'f'},
                                       {"links", required_argument, NULL, 'L'},
                                       {"tol", required_argument, NULL, 't'},
                                       {"depth", required_argument, NULL, 'd'},
                                       {"evals", required_argument, NULL, 'n'},
                                       {"jobs", required_argument, NULL, 'j'},
                                       {"output", required_argument, NULL, 'o'},
                                       {"keep", required_argument, NULL, 'k'},
                                       {"progress", no_argument, NULL, 'p'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  optind = 1;
  opterr = 0;
  int c;
  char *end;
  while ((c = getopt_long(argc, argv, ":ho:j:", opts, NULL)) != -1) {
    const int co = ss_check_case_option(c, optarg, "tune", &o->k);
    if (co >= 0) {
      if (co) return co;
      continue;
    }
    switch (c) {
    case 't':
      if (ss_cli_opt_tol("tune", optarg, &o->tol)) return SS_EXIT_USAGE;
      break;
    case 'd':
      if (ss_cli_opt_depth("tune", optarg, &o->depth)) return SS_EXIT_USAGE;
      break;
    case 'n':
      if (ss_cli_parse_int(optarg, 2, 100000, &o->evals))
        return ss_cli_usage_error("tune", "--evals '%s' is not an integer in 2..100000",
                                  optarg);
      break;
    case 'j':
      if (ss_cli_parse_int(optarg, 1, 1024, &o->jobs))
        return ss_cli_usage_error("tune", "--jobs '%s' is not an integer in 1..1024",
                                  optarg);
      break;
    case 'o':
      o->output = optarg;
      break;
    case 'k':
      o->keep = strtod(optarg, &end);
      if (end == optarg || *end || !(o->keep > 0.0 && o->keep <= 1.0))
        return ss_cli_usage_error("tune", "--keep '%s' is not a number in (0, 1]",
                                  optarg);
      break;
    case 'p':
      o->progress = 1;
      break;
    case 'h':
      fputs(usage_text, stdout);
      return -1;
    default:
      return ss_cli_option_error("tune", c, argv);
    }
  }
  if (optind + 1 != argc)
    return ss_cli_usage_error("tune", optind == argc ? "no stencil file given"
                                                     : "more than one stencil file");
  return 0;
}

/* The scheme at the middle of the ranges (rational), so that a file that
 * does not read is refused before any search.  0 or exit status 2. */
static int read_middle(ss_tune *t, ss_scheme **s) {
  long long num[SS_STENCIL_MAXPARAMS], den[SS_STENCIL_MAXPARAMS];
  for (int i = 0; i < t->nfree; i++)
    nearest_rational(0.5 * (t->lo[i] + t->hi[i]), 99999, num + i, den + i);
  ss_stencil_params v;
  values_at(t, num, den, &v);
  ss_error err = {0};
  if (ss_stencil_parse_at(t->text, t->where, &v, s, &err)) {
    fprintf(stderr, "subspectra tune: %s\n", err.msg);
    return SS_EXIT_USAGE;
  }
  return ss_cli_refuse_local("tune", *s) ? SS_EXIT_USAGE : 0;
}

/* The free parameters of t->params into t->free, t->lo, t->hi.  0 or 2. */
static int free_params(ss_tune *t) {
  for (int i = 0; i < t->params.n; i++) {
    const ss_stencil_param *p = t->params.p + i;
    if (!p->free) continue;
    t->lo[t->nfree] = (double)p->lo[0] / (double)p->lo[1];
    t->hi[t->nfree] = (double)p->hi[0] / (double)p->hi[1];
    t->free[t->nfree++] = i;
  }
  if (t->nfree) return 0;
  fprintf(stderr,
          "subspectra tune: %s: no free parameter (a [param] NAME = ?(LO, HI) that "
          "the weights use)\n",
          t->where);
  return SS_EXIT_USAGE;
}

/* Write text to path; 0 or exit status 2. */
static int write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  if (!f || fputs(text, f) < 0 || fclose(f)) {
    fprintf(stderr, "subspectra tune: %s: cannot write\n", path);
    return SS_EXIT_USAGE;
  }
  return 0;
}

/* Read the written file back and analyse every case with certified
 * verdicts, as `check --certify` does; print the summary.  Exit status. */
static int verify(ss_tune *t, const char *path, const char *text) {
  ss_scheme *s = NULL;
  ss_error err = {0};
  if (ss_stencil_parse(text, path, &s, &err)) {
    fprintf(stderr, "subspectra tune: the written file does not read: %s\n", err.msg);
    return SS_EXIT_USAGE;
  }
  ss_result_opts ro = t->ro;
  ro.certify = 1;
  ss_check_run *r = t->run;
  ss_check_analyse(r, s, &ro, t->jobs, 1, 0);
  ss_scheme_free(s);
  printf("check --certify %s: %zu cases: %ld pass, %ld fail, %ld undecided, %ld errors\n",
         path, r->ncases, r->count[SS_CHECK_PASS], r->count[SS_CHECK_FAIL],
         r->count[SS_CHECK_UNDECIDED], r->count[SS_CHECK_ERROR]);
  if (r->nomem) return SS_EXIT_USAGE;
  return r->count[SS_CHECK_PASS] == (long)r->ncases ? SS_EXIT_OK : SS_EXIT_FAIL;
}

/* Search, round, write and verify.  Exit status. */
static int tune(ss_tune *t, const tune_opts *o, const char *out) {
  char msg[256];
  if (ss_tune_search(t, o->evals, msg, sizeof msg)) {
    fprintf(stderr, "subspectra tune: %s\n", msg);
    return SS_EXIT_USAGE;
  }
  const double searched = t->best;
  const long nsearch = t->evals;
  long long num[SS_STENCIL_MAXPARAMS], den[SS_STENCIL_MAXPARAMS];
  char buf[48];
  const double m = round_best(t, o->keep, num, den);
  printf("search: %ld evaluations (DIRECT_L, then COBYLA): best smallest margin %.6g "
         "at",
         nsearch, searched);
  for (int i = 0; i < t->nfree; i++)
    printf(" %s = %.9g", t->params.p[t->free[i]].name, t->bestx[i]);
  printf("\nrounded:");
  for (int i = 0; i < t->nfree; i++)
    printf(" %s = %s", t->params.p[t->free[i]].name, fmt_rational(buf, num[i], den[i]));
  printf(": smallest margin %.6g (%ld evaluations in all)\n", m, t->evals);
  char *text = tuned_text(t, num, den, m);
  if (!text) {
    fprintf(stderr, "subspectra tune: out of memory\n");
    return SS_EXIT_USAGE;
  }
  int status = write_file(out, text);
  if (!status) {
    printf("written: %s\n", out);
    fflush(stdout);
    status = verify(t, out, text);
  }
  free(text);
  if (!status && m <= 0.0) status = SS_EXIT_FAIL; /* cannot happen: verified */
  return status;
}

int ss_cli_tune(int argc, char **argv) {
  tune_opts o = {SS_CHECK_CASES_NONE, SS_JAC_DEPTH, 1, 120, 0, 1e-6, 0.9, NULL};
  const int pr = parse_opts(argc, argv, &o);
  if (pr) return pr < 0 ? SS_EXIT_OK : pr;
  const char *path = argv[optind];
  if (!ss_tune_available()) {
    fprintf(stderr, "subspectra tune: this build has no NLopt (Debian libnlopt-dev; "
                    "meson option nlopt)\n");
    return SS_EXIT_USAGE;
  }
  ss_error err = {0};
  char *text = NULL;
  if (ss_stencil_read(path, &text, NULL, &err)) return ss_cli_fail("tune", &err);
  ss_check_run run = {path, NULL, o.tol, (int)o.depth, 0, NULL, 0, {0, 0, 0, 0}, 0, -1};
  ss_tune t = {.text = text,
               .where = path,
               .run = &run,
               .ro = ss_result_defaults(),
               .jobs = (int)o.jobs,
               .progress = o.progress,
               .phase = "global",
               .best = -INFINITY};
  t.ro.tol = o.tol;
  t.ro.depth = (int)o.depth;
  t.ro.max_bytes = ss_cli_budget(0.0) / (double)o.jobs;
  ss_scheme *s = NULL;
  char *out = NULL;
  int status = ss_stencil_read_params(text, path, &t.params, &err)
                   ? ss_cli_fail("tune", &err)
               : free_params(&t) ? SS_EXIT_USAGE
                                 : read_middle(&t, &s);
  if (!status) {
    const int tetoct = ss_scheme_split_kind(s) == SS_SPLIT_TETOCT;
    run.scheme = ss_scheme_name(s);
    status = ss_check_cases_default(&o.k, "tune", tetoct, "stencil");
  }
  if (!status) status = ss_check_list(&run, "tune", &o.k);
  const size_t len = strlen(path);
  if (!status && !(t.margins = calloc(run.ncases + 1, sizeof *t.margins))) {
    fprintf(stderr, "subspectra tune: out of memory\n");
    status = SS_EXIT_USAGE;
  }
  if (!status && !o.output && (out = malloc(len + 16))) {
    const int ini = len > 4 && !strcmp(path + len - 4, ".ini");
    sprintf(out, "%.*s-tuned.ini", (int)(ini ? len - 4 : len), path);
  }
  if (!status && !o.output && !out) {
    fprintf(stderr, "subspectra tune: out of memory\n");
    status = SS_EXIT_USAGE;
  }
  if (!status) {
    printf("tune %s (scheme %s): %d free parameter%s, %zu case%s, %ld evaluations\n",
           path, run.scheme, t.nfree, t.nfree == 1 ? "" : "s", run.ncases,
           run.ncases == 1 ? "" : "s", o.evals);
    fflush(stdout);
    status = tune(&t, &o, o.output ? o.output : out);
  }
  free(out);
  free(t.margins);
  ss_check_run_free(&run);
  ss_scheme_free(s);
  free(text);
  return status;
}
