/* ss_cli_jsr.c — `subspectra jsr`: the Levin-Levin joint-spectral-radius
 * test across a tet/oct face or along an edge (ss_levin.h, ss_jsr.h). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <json-c/json.h>

#include "ss_cli.h"
#include "ss_diag.h"
#include "ss_jsr.h"
#include "ss_levin.h"

static void usage(FILE *f) {
  fprintf(
      f,
      "usage: subspectra jsr --scheme S (--face | --edge N) [--depth K] [--gap G]\n"
      "                      [--norm N] [--fit-words K] [--diagonals D]\n"
      "                      [--max-seconds T] [--format text|json] [--progress]\n\n"
      "The Levin-Levin smoothness test (tet/oct paper, appendix A).  From the scheme's\n"
      "global rule: the patch (face: the tet/tet + oct/oct pair of figure 10, a unit\n"
      "square of the face's grid; edge: a segment between two edge vertices), its\n"
      "support (the points whose basis functions do not vanish on it) and the maps\n"
      "S_i to the supports of its sub-patches after one step (4 for the face, 2 for\n"
      "an edge).  W = [V Q2] with V spanning the subspace the smoothness order needs\n"
      "(face: the quadratic polynomials, eigenvalues 1, 1/2 x3, 1/4 x6, or S_1's\n"
      "eigenvectors for those when the quadratics are not invariant; edge: S_1's\n"
      "eigenvectors for 1, lambda1, lambda1, 1/2), which must be invariant under\n"
      "every S_i, and Q2 an orthonormal complement; Y_i = Q2^T S_i Q2, the lower\n"
      "right block of W^-1 S_i W.  Another complement changes every Y_i by the same\n"
      "similarity, so the joint spectral radius does not depend on it.\n\n"
      "Printed: the sizes, rho_k = max ||Y_w||^(1/k) over the words of length k =\n"
      "1..K in the inf-norm and the 2-norm, lower and upper bounds on the joint\n"
      "spectral radius (ss_jsr: spectral radii of products; branch and bound), the\n"
      "threshold (face: 1/4, C^2 across the face; edge: lambda3, the third\n"
      "subdominant eigenvalue of S_1 = min(lambda1, 1/2)) and the verdict: pass if\n"
      "upper < threshold, fail if lower >= threshold, otherwise undecided.\n"
      "\"certified\": the bounds account for the rounding in the products of the\n"
      "computed Y_i (not for the rounding in forming Y_i from S_i).\n\n");
  fprintf(
      f,
      "  -s, --scheme S    a scheme with the tet/oct split: tetoct, boxspline or\n"
      "                    boxspline-avg\n"
      "  --face            the face shared by two tets\n"
      "  --edge N          an edge of valence N (3..64)\n"
      "  --depth K         word length of rho_k and the lower bound (1..12, default 8)\n"
      "  --gap G           relative gap of the branch and bound (default 1e-3)\n"
      "  --norm N          norm of the branch and bound: auto (default: the first\n"
      "                    pass runs in each of the others, the rest in the best;\n"
      "                    ellipsoid only for Y_i of order <= 64), inf, 2, or\n"
      "                    ellipsoid: sqrt(x^T P x), P = L L^T fitted to make\n"
      "                    max_i ||L^T Y_i L^-T||_2 small (a nearly extremal norm,\n"
      "                    so the bound converges at short words; the similar\n"
      "                    matrices are enclosed in ball arithmetic), or polytope:\n"
      "                    the invariant polytope (Guglielmi-Protasov) from the\n"
      "                    lower bound's word, slack gap/2, vertices added while\n"
      "                    images leave the hull (LPs by GLPK, the bound proven\n"
      "                    in ball arithmetic), at most 20000 vertices and half\n"
      "                    the time; if it does not close, auto's branch and\n"
      "                    bound goes on (auto never tries the polytope)\n"
      "  --fit-words K     fit the ellipsoid to the 4^K (face) or 2^K (edge)\n"
      "                    products of length K = 1..5 instead of the maps:\n"
      "                    max_w ||L^T Y_w L^-T||_2^(1/K) small (the fit on the\n"
      "                    maps first, then on the products); default 1; with\n"
      "                    --norm ellipsoid or auto only.  The\n"
      "                    bound stays proven for any K (tet/oct face, 60 s:\n"
      "                    see docs/methods.md, \"Joint spectral radius\")\n"
      "  --diagonals D     major diagonals of tet stars, for boxspline (the only rule\n"
      "                    that reads them; refused for the others): bfs (default),\n"
      "                    proper; skew and center for edges only\n"
      "  --max-seconds T   time limit (0 < T < 1e7, default 60) of everything after\n"
      "                    the maps are built (a fixed cost of 1-2 s): the\n"
      "                    products for rho_k from length 2 on (a length it cuts\n"
      "                    short is left out of rho_k and of the upper bound, and\n"
      "                    said so), the ellipsoid's fit (at most a quarter of\n"
      "                    it), the polytope and the branch and bound\n"
      "  --format F        text (default) or json (keys: lower, upper, threshold,\n"
      "                    rho_k, rho_k_2, verdict, certified, ...; when the time\n"
      "                    limit cut rho_k short also stopped_by, depth,\n"
      "                    depth_complete, cut_length, cut_words, cut_of; when the\n"
      "                    reduction does not apply applies = false, reason, the\n"
      "                    result keys null and verdict n/a)\n"
      "  --progress        the phases on stderr as they start (building the maps,\n"
      "                    the products, the norms' fit, each branch-and-bound\n"
      "                    word length; at most a line a second within one)\n\n"
      "Exit status: 0 pass, 1 fail or undecided (or the reduction does not apply:\n"
      "the spectrum of S_1 is not of the required form, the subspace is not\n"
      "invariant), 2 bad usage or bad input.  A time limit is not an error: the\n"
      "bounds found by then are proven, and the verdict is judged on them.\n");
}

enum {
  O_FACE = 256,
  O_EDGE,
  O_DEPTH,
  O_GAP,
  O_DIAG,
  O_SECONDS,
  O_FORMAT,
  O_NORM,
  O_FITWORDS,
  O_PROGRESS
};

static const char *const norm_names[] = {"inf", "2", "auto", "ellipsoid", "polytope"};

/* out->polytope: -1 not run, else ss_jsr_polytope_stop */
static const char *poly_name(int p) {
  static const char *const nm[] = {"closed", "vertex cap", "time limit", "LP failed",
                                   "rho = 0"};
  return p < 0 || p > 4 ? "not run" : nm[p];
}

static const struct option jsr_options[] = {
    {"scheme", required_argument, 0, 's'},
    {"face", no_argument, 0, O_FACE},
    {"edge", required_argument, 0, O_EDGE},
    {"depth", required_argument, 0, O_DEPTH},
    {"gap", required_argument, 0, O_GAP},
    {"norm", required_argument, 0, O_NORM},
    {"fit-words", required_argument, 0, O_FITWORDS},
    {"diagonals", required_argument, 0, O_DIAG},
    {"max-seconds", required_argument, 0, O_SECONDS},
    {"format", required_argument, 0, O_FORMAT},
    {"progress", no_argument, 0, O_PROGRESS},
    {"help", no_argument, 0, 'h'},
    {0, 0, 0, 0}};

/* The command line of jsr. */
typedef struct {
  const char *scheme_name; /* --scheme */
  ss_case c;               /* --face or --edge N, with --diagonals */
  int have_case;           /* --face or --edge was given */
  int diag_given;          /* --diagonals was given */
  int json;                /* --format json */
  int progress;            /* --progress: the phases on stderr */
  ss_jsr_opts o;           /* --depth, --gap, --norm, --fit-words, --max-seconds */
} jsr_args;

/* One option ch (its argument in optarg) into a: -1 to go on, else the exit
 * status (0 after --help, 2 with the message printed). */
static int parse_option(int ch, char **argv, jsr_args *a) {
  const char *cmd = "jsr";
  char *end = NULL;
  long v;
  switch (ch) {
  case 'h':
    usage(stdout);
    return SS_EXIT_OK;
  case 's':
    a->scheme_name = optarg;
    break;
  case O_FACE:
    if (a->have_case) return ss_cli_usage_error(cmd, "give one of --face and --edge");
    a->c.kind = SS_CASE_FACE, a->have_case = 1;
    break;
  case O_EDGE:
    if (a->have_case) return ss_cli_usage_error(cmd, "give one of --face and --edge");
    if (ss_cli_parse_int(optarg, 3, 64, &v))
      return ss_cli_usage_error(cmd, "--edge: expected a valence 3..64, not '%s'",
                                optarg);
    a->c.kind = SS_CASE_EDGE, a->c.n = (int)v, a->have_case = 1;
    break;
  case O_DEPTH:
    if (ss_cli_parse_int(optarg, 1, 12, &v))
      return ss_cli_usage_error(cmd, "--depth: expected 1..12, not '%s'", optarg);
    a->o.depth = (int)v;
    break;
  case O_GAP:
    a->o.gap = strtod(optarg, &end);
    if (end == optarg || *end || !(a->o.gap > 0 && a->o.gap < 1))
      return ss_cli_usage_error(cmd, "--gap: expected a number in (0, 1), not '%s'",
                                optarg);
    break;
  case O_NORM: {
    int k = 0;
    while (k < 5 && strcmp(optarg, norm_names[k]))
      k++;
    if (k == 5)
      return ss_cli_usage_error(
          cmd, "--norm: expected auto, inf, 2, ellipsoid or polytope, not '%s'", optarg);
    a->o.norm = (ss_jsr_norm)k;
    break;
  }
  case O_FITWORDS:
    if (ss_cli_parse_int(optarg, 1, 5, &v))
      return ss_cli_usage_error(cmd, "--fit-words: expected 1..5, not '%s'", optarg);
    a->o.fit_words = (int)v;
    break;
  case O_SECONDS:
    a->o.max_seconds = strtod(optarg, &end);
    if (end == optarg || *end || !(a->o.max_seconds > 0 && a->o.max_seconds < 1e7))
      return ss_cli_usage_error(cmd,
                                "--max-seconds: expected a positive number of seconds "
                                "below 1e7 (the cap), not '%s'",
                                optarg);
    break;
  case O_DIAG:
    if (ss_diag_parse(optarg, &a->c.diag))
      return ss_cli_usage_error(
          cmd, "--diagonals: expected bfs, proper, skew or center, not '%s'", optarg);
    a->diag_given = 1;
    break;
  case O_FORMAT:
    if (ss_cli_format_option(cmd, optarg, &a->json)) return SS_EXIT_USAGE;
    break;
  case O_PROGRESS:
    a->progress = 1;
    break;
  default:
    return ss_cli_option_error(cmd, ch, argv);
  }
  return -1;
}

/* argv into a: -1 to go on, else the exit status (0 after --help, 2 with
 * the message printed). */
static int parse_args(int argc, char **argv, jsr_args *a) {
  const char *cmd = "jsr";
  *a = (jsr_args){.o = ss_jsr_defaults()};
  a->o.max_seconds = 60;
  optind = 1;
  opterr = 0;
  for (int ch; (ch = getopt_long(argc, argv, ":hs:", jsr_options, NULL)) != -1;) {
    const int rc = parse_option(ch, argv, a);
    if (rc >= 0) return rc;
  }
  if (optind < argc)
    return ss_cli_usage_error(cmd, "unexpected argument '%s'", argv[optind]);
  if (!a->scheme_name) return ss_cli_usage_error(cmd, "--scheme is required");
  if (!a->have_case) return ss_cli_usage_error(cmd, "give --face or --edge N");
  if (a->o.fit_words > 1 && a->o.norm != SS_JSR_NORM_AUTO &&
      a->o.norm != SS_JSR_NORM_ELLIPSOID)
    return ss_cli_usage_error(cmd,
                              "--fit-words fits the ellipsoidal norm: it needs --norm "
                              "ellipsoid or auto, not %s",
                              norm_names[a->o.norm]);
  return -1;
}

/* m^k, the number of words of length k over the maps of L. */
static double words_of(const ss_levin *L, int k) {
  return pow((double)L->m, k);
}

/* The result as one JSON object on standard output. */
static void print_json(const jsr_args *a, const ss_levin *L, const ss_jsr_result *r,
                       const char *verdict, const char *thr_name) {
  const ss_case c = a->c;
  json_object *j = json_object_new_object(), *rk = json_object_new_array(),
              *r2 = json_object_new_array(), *th = json_object_new_array(),
              *w = json_object_new_array();
  json_object_object_add(j, "scheme", json_object_new_string(a->scheme_name));
  json_object_object_add(j, "case", json_object_new_string(ss_case_name(c.kind)));
  if (c.kind == SS_CASE_EDGE) json_object_object_add(j, "n", json_object_new_int(c.n));
  json_object_object_add(j, "diagonals", json_object_new_string(ss_diag_name(c.diag)));
  json_object_object_add(j, "level", json_object_new_int(L->level));
  json_object_object_add(j, "maps", json_object_new_int64((int64_t)L->m));
  json_object_object_add(j, "support", json_object_new_int64((int64_t)L->n));
  json_object_object_add(j, "subspace", json_object_new_int64((int64_t)L->r));
  json_object_object_add(j, "subspace_basis", json_object_new_string(L->basis));
  json_object_object_add(j, "invariance_defect", json_object_new_double(L->defect));
  for (size_t i = 0; i < L->r; i++)
    json_object_array_add(th, json_object_new_double(L->theta[i]));
  json_object_object_add(j, "theta", th);
  if (c.kind == SS_CASE_EDGE)
    json_object_object_add(j, "lambda1", json_object_new_double(L->lambda1));
  for (int k = 0; k < r->depth; k++) {
    json_object_array_add(rk, json_object_new_double(r->rho_inf[k]));
    json_object_array_add(r2, json_object_new_double(r->rho_2[k]));
  }
  json_object_object_add(j, "rho_k", rk);
  json_object_object_add(j, "rho_k_2", r2);
  if (r->cut_len > 0) { /* only then: the bytes of complete runs are as before */
    json_object_object_add(j, "stopped_by", json_object_new_string("max-seconds"));
    json_object_object_add(j, "depth", json_object_new_int(a->o.depth));
    json_object_object_add(j, "depth_complete", json_object_new_int(r->depth));
    json_object_object_add(j, "cut_length", json_object_new_int(r->cut_len));
    json_object_object_add(j, "cut_words", json_object_new_int64((int64_t)r->cut_words));
    json_object_object_add(j, "cut_of",
                           json_object_new_int64((int64_t)words_of(L, r->cut_len)));
  }
  json_object_object_add(j, "lower", json_object_new_double(r->lower));
  for (int k = 0; k < r->lower_len; k++)
    json_object_array_add(w, json_object_new_int(r->lower_word[k] + 1));
  json_object_object_add(j, "lower_word", w);
  json_object_object_add(j, "upper", json_object_new_double(r->upper));
  json_object_object_add(j, "threshold", json_object_new_double(L->threshold));
  json_object_object_add(j, "threshold_name", json_object_new_string(thr_name));
  json_object_object_add(j, "verdict", json_object_new_string(verdict));
  json_object_object_add(j, "certified", json_object_new_boolean(r->certified));
  json_object_object_add(j, "converged", json_object_new_boolean(r->converged));
  json_object_object_add(j, "nodes", json_object_new_int64((int64_t)r->nodes));
  json_object_object_add(j, "norm", json_object_new_string(norm_names[r->norm]));
  json_object_object_add(j, "weighted", json_object_new_boolean(r->weighted));
  json_object_object_add(j, "fit_words", json_object_new_int(a->o.fit_words));
  json_object_object_add(j, "bnb_depth", json_object_new_int(r->bnb_depth));
  json_object_object_add(j, "polytope", json_object_new_string(poly_name(r->polytope)));
  json_object_object_add(j, "polytope_vertices",
                         json_object_new_int64((int64_t)r->poly_vertices));
  if (r->polytope == 0)
    json_object_object_add(j, "polytope_upper", json_object_new_double(r->poly_upper));
  printf("%s\n", json_object_to_json_string_ext(j, SS_CLI_JSON_FLAGS));
  json_object_put(j);
}

/* The result as text on standard output. */
static void print_text(const jsr_args *a, const ss_levin *L, const ss_jsr_result *r,
                       const char *verdict, const char *thr_name) {
  const ss_case c = a->c;
  printf("scheme %s, %s", a->scheme_name, ss_case_name(c.kind));
  if (c.kind == SS_CASE_EDGE) printf(" of valence %d", c.n);
  printf(" (diagonals %s)\n", ss_diag_name(c.diag));
  printf("maps S_1..S_%zu: %zu x %zu (support on level %d); subspace of dimension "
         "%zu (%s,\n  invariant under every S_i to %.2g); Y_i: %zu x %zu\n",
         L->m, L->n, L->n, L->level, L->r, L->basis, L->defect, L->n - L->r, L->n - L->r);
  printf("eigenvalues of S_1 on the subspace:");
  for (size_t i = 0; i < L->r; i++)
    printf(" %.6g", L->theta[i]);
  printf("\n%-4s %-12s %-12s\n", "k", "rho_k (inf)", "rho_k (2)");
  for (int k = 0; k < r->depth; k++)
    printf("%-4d %-12.6g %-12.6g\n", k + 1, r->rho_inf[k], r->rho_2[k]);
  if (r->cut_len > 0)
    printf("time limit (--max-seconds %g): rho_k for k = 1..%d of --depth %d; the "
           "words of length %d were cut short after %zu of %.0f (they count for the "
           "lower bound only)\n",
           a->o.max_seconds, r->depth, a->o.depth, r->cut_len, r->cut_words,
           words_of(L, r->cut_len));
  char fitted[48] = "";
  if (a->o.fit_words > 1 && r->norm == SS_JSR_NORM_ELLIPSOID)
    snprintf(fitted, sizeof fitted, " fitted to words of length %d", a->o.fit_words);
  printf("joint spectral radius in [%.6g, %.6g] (%s; %s, %zu products, %s-norm%s%s, "
         "words to length %d)\n",
         r->lower, r->upper, r->certified ? "certified" : "not certified",
         r->converged ? "gap reached" : "gap not reached", r->nodes, norm_names[r->norm],
         r->weighted ? " weighted" : "", fitted, r->bnb_depth);
  if (r->polytope >= 0) {
    printf("invariant polytope: %s, %zu vertices", poly_name(r->polytope),
           r->poly_vertices);
    if (r->polytope == 0) printf(", upper %.6g", r->poly_upper);
    printf("\n");
  }
  printf("threshold %.6g: %s\nverdict: %s\n", L->threshold, thr_name, verdict);
}

/* The reduction does not apply (ss_levin_new's SS_EINTERNAL, reason in
 * msg): with --format json the object with the case, the reason and a null
 * result, so that a reader of standard output gets one object per run. */
static void print_json_na(const jsr_args *a, const char *msg) {
  const ss_case c = a->c;
  json_object *j = json_object_new_object();
  json_object_object_add(j, "scheme", json_object_new_string(a->scheme_name));
  json_object_object_add(j, "case", json_object_new_string(ss_case_name(c.kind)));
  if (c.kind == SS_CASE_EDGE) json_object_object_add(j, "n", json_object_new_int(c.n));
  json_object_object_add(j, "diagonals", json_object_new_string(ss_diag_name(c.diag)));
  json_object_object_add(j, "applies", json_object_new_boolean(0));
  json_object_object_add(j, "reason", json_object_new_string(msg));
  static const char *const nulls[] = {"rho_k", "rho_k_2",   "lower",
                                      "upper", "threshold", "certified"};
  for (size_t k = 0; k < sizeof nulls / sizeof *nulls; k++)
    json_object_object_add(j, nulls[k], NULL);
  json_object_object_add(j, "verdict", json_object_new_string("n/a"));
  printf("%s\n", json_object_to_json_string_ext(j, SS_CLI_JSON_FLAGS));
  json_object_put(j);
}

/* The scheme and the Levin-Levin reduction of the case into *s and *L; -1 to
 * go on, else the exit status with the message printed (and with --format
 * json the object of print_json_na when the reduction does not apply). */
static int build_case(const jsr_args *a, ss_scheme **s, ss_levin **L) {
  ss_error err = {0};
  if (ss_scheme_new(a->scheme_name, s, &err)) return ss_cli_fail("jsr", &err);
  if (a->diag_given && !ss_scheme_reads_diagonals(*s))
    return ss_cli_usage_error("jsr",
                              "--diagonals: scheme %s reads no major diagonals (only "
                              "boxspline's rule does); leave the option out",
                              a->scheme_name);
  if (ss_levin_new(*s, &a->c, L, &err)) {
    if (err.status == SS_EINTERNAL && a->json) print_json_na(a, err.msg);
    return ss_cli_fail("jsr", &err);
  }
  return -1;
}

int ss_cli_jsr(int argc, char **argv) {
  jsr_args a;
  int rc = parse_args(argc, argv, &a);
  if (rc >= 0) return rc;
  const ss_case c = a.c;
  ss_error err = {0};
  ss_scheme *s = NULL;
  ss_levin *L = NULL;
  ss_jsr_result r;
  memset(&r, 0, sizeof r);
  ss_cli_progress pr = {"jsr", ss_cli_now(), 0, NULL, 0};
  if (a.progress) {
    a.o.progress = (ss_progress){ss_cli_progress_fn, &pr};
    ss_cli_progress_fn(&pr, "building the maps", 0, 0);
  }
  rc = build_case(&a, &s, &L);
  if (rc >= 0) goto done;
  rc = SS_EXIT_OK;
  if (ss_jsr_compute(L->m, L->n - L->r, (const double *const *)L->Y, &a.o, &r, &err)) {
    rc = ss_cli_fail("jsr", &err);
    goto done;
  }
  ss_verdict jv;
  ss_levin_verdict(L, &r, &jv);
  const char *verdict = ss_verdict_name(jv.verdict);
  rc = jv.verdict != SS_PASS ? SS_EXIT_FAIL : SS_EXIT_OK;
  const char *thr_name = c.kind == SS_CASE_FACE           ? "1/4 (C^2 across the face)"
                         : fabs(L->lambda1 - 0.5) <= 1e-8 ? "lambda3 = lambda1 = 1/2"
                         : L->lambda1 < 0.5               ? "lambda3 = lambda1 (< 1/2)"
                                                          : "lambda3 = 1/2 (< lambda1)";
  if (a.json)
    print_json(&a, L, &r, verdict, thr_name);
  else
    print_text(&a, L, &r, verdict, thr_name);
done:
  ss_jsr_result_clear(&r);
  ss_levin_free(L);
  ss_scheme_free(s);
  return rc;
}
