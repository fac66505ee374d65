/* ss_cli_reproduce.c — `subspectra reproduce [--out DIR]`: regenerate every
 * table this project reproduces from the papers, each case beside the values
 * the papers quote (the TSV files of data/reference/, ss_report_ref.h) with the
 * difference and a match / differ / not quoted mark, the raw results as JSON
 * lines (DIR/data/), a TSV of the comparison per table, and the pictures of
 * characteristic maps (DIR/figures/).  Which tables and figures: the data
 * file data/reproduce/tables.json.
 *
 * This file is the command: options, loading, and the loop over the tables;
 * the other steps have a file each (ss_cli_reproduce.h lists them).  Every
 * case is judged by ss_result_compute, as `analyze`, `check` and `sweep`
 * judge it. */
#include <errno.h>
#include <getopt.h>
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ss_cli.h"
#include "ss_cli_reproduce.h"
#include "ss_cli_reproduce_jsr.h"

static const char cmd[] = "reproduce";

static const char usage[] =
    "usage: subspectra reproduce [--out DIR] [--reference DIR] [--tables FILE]\n"
    "                            [--certify]\n\n"
    "Regenerate every table this project reproduces from the papers, each case\n"
    "beside the values the papers quote, and the pictures of characteristic maps:\n"
    "  DIR/NAME.md          the table: cases, eigenvalues, both verdicts, and per\n"
    "                       row match / differ / not quoted; then every quoted\n"
    "                       value with the computed one, the difference, the\n"
    "                       tolerance and the source (paper, location, quote)\n"
    "  DIR/NAME.tsv         the comparison, machine-readable\n"
    "  DIR/data/NAME.jsonl  the results, one JSON object per case (keys as in\n"
    "                       `analyze --format json`)\n"
    "  DIR/figures/*.png    pictures (as `subspectra draw --no-caption`), their\n"
    "                       captions in DIR/figures/README.md\n"
    "Quoted values are read from the reference files (one TSV per paper; the\n"
    "columns are documented in their header).  A decimal matches when it is\n"
    "within half a unit in its last printed digit, an exact value (fraction,\n"
    "formula in k or n) within 1e-9, a verdict when equal.  One progress line\n"
    "per table on standard error.\n\n"
    "  -o, --output DIR     output folder, created if missing (default reports;\n"
    "                       --out DIR: the same)\n"
    "  -r, --reference DIR  reference files DIR/*.tsv; default:\n"
    "                       $SUBSPECTRA_DATADIR/reference when that is set, else\n"
    "                       data/reference when run from the source tree, else\n"
    "                       the installed data beside the program, or\n"
    "                       " SS_DATADIR "/reference\n"
    "  -t, --tables FILE    the tables and figures to make (JSON, described in\n"
    "                       reproduce/README.md beside it); default:\n"
    "                       reproduce/tables.json beside the reference folder\n"
    "                       (DIR/../reproduce/tables.json), else in the folder\n"
    "                       of the default reference folder (the same search)\n"
    "  --certify            prove every verdict (as `analyze --certify`): a proven\n"
    "                       verdict is marked ✓, one that cannot be proven becomes\n"
    "                       undecided; the exhaustive tables count both per k\n"
    "  -h, --help           this text\n\n"
    "Exit status: 0 when it ran, whatever the verdicts and comparisons; 1 when an\n"
    "analysis failed internally; 2 for bad usage, a malformed reference file or\n"
    "an output that cannot be written.\n";

/* mkdir -p; 0 or -1 with errno set. */
static int make_dirs(const char *path) {
  char *p = strdup(path);
  if (!p) return -1;
  int rc = 0;
  for (char *s = p + 1;; s++) {
    const char save = *s;
    if (save != '/' && save != '\0') continue;
    *s = '\0';
    struct stat sb;
    if (mkdir(p, 0777) != 0 &&
        !(errno == EEXIST && stat(p, &sb) == 0 && S_ISDIR(sb.st_mode))) {
      if (errno == EEXIST) errno = ENOTDIR;
      rc = -1;
      break;
    }
    *s = save;
    if (save == '\0') break;
  }
  free(p);
  return rc;
}

static int exit_for(const ss_error *err) {
  return ss_cli_exit_status(err->status); /* out of memory: 2, never 1 */
}

/* Write NAME.md, NAME.tsv and data/NAME.jsonl for table t; vs (NULL unless
 * t->nvs) holds the other schemes' results on the same cases, in t->vs's
 * order; *ty counts the cases and comparisons. */
static ss_status write_table(const char *dir, const ss_reproduce_table *t,
                             const ss_reproduce_results *l,
                             const ss_reproduce_results *vs, const ss_ref *ref,
                             ss_reproduce_tally *ty, ss_error *err) {
  ss_strbuf md = {0}, tsv = {0}, js = {0};
  ss_reproduce_cmps cmp;
  char *path = NULL;
  ss_status st = ss_reproduce_compare(t, l, ref, &cmp, ty, err);
  if (st) goto done;
  ss_reproduce_md(&md, t, l, vs, &cmp, ty);
  ss_reproduce_tsv(&tsv, t, l, &cmp, ty);
  ss_reproduce_jsonl(&js, t, l);
  if (!md.s || !tsv.s || !js.s) {
    st = ss_error_nomem(err, "table text");
    goto done;
  }
  path = malloc(strlen(dir) + strlen(t->name) + 32);
  if (!path) {
    st = ss_error_nomem(err, "path");
    goto done;
  }
  sprintf(path, "%s/%s.md", dir, t->name);
  if ((st = ss_sb_write_file(path, &md, err))) goto done;
  sprintf(path, "%s/%s.tsv", dir, t->name);
  if ((st = ss_sb_write_file(path, &tsv, err))) goto done;
  sprintf(path, "%s/data/%s.jsonl", dir, t->name);
  st = ss_sb_write_file(path, &js, err);
done:
  free(path);
  free(md.s);
  free(tsv.s);
  free(js.s);
  ss_reproduce_cmps_free(&cmp);
  return st;
}

/* Compute table t (and the schemes beside it) and write it under out, with
 * its progress line on stderr; adds its quoted and matching values to
 * *quoted and *match.  The exit status: 0, or that of the failure, printed. */
static int run_table(const ss_reproduce_table *t, const char *out, const ss_ref *ref,
                     const ss_result_opts *ro, size_t *quoted, size_t *match) {
  const double t1 = ss_cli_now();
  ss_error err = {0};
  ss_scheme *s = NULL, *sv[SS_REPRODUCE_MAXVS] = {NULL};
  ss_reproduce_results l = {0}, lv[SS_REPRODUCE_MAXVS] = {{0}};
  int rc = SS_EXIT_OK;
  l.o = *ro;
  l.o.psi_depth = t->psi_depth;
  for (int k = 0; k < SS_REPRODUCE_MAXVS; k++)
    lv[k].o = l.o;
  ss_reproduce_tally ty;
  int bad = ss_scheme_new(t->scheme, &s, &err) || ss_reproduce_cases(t, s, &l, &err);
  for (int k = 0; k < t->nvs && !bad; k++)
    bad = ss_scheme_new(t->vs[k], &sv[k], &err) ||
          ss_reproduce_cases(t, sv[k], &lv[k], &err);
  if (bad || write_table(out, t, &l, t->nvs ? lv : NULL, ref, &ty, &err)) {
    fprintf(stderr, "subspectra %s: %s: %s\n", cmd, t->name, err.msg);
    rc = exit_for(&err);
  } else {
    char cbuf[64] = "";
    if (ro->certify)
      snprintf(cbuf, sizeof cbuf, " (%zu verdicts certified)", ty.certified);
    fprintf(stderr,
            "subspectra reproduce: %s: %zu of %zu cases pass%s; %zu quoted values: %zu "
            "match, "
            "%zu differ; %zu rows not quoted (%.1f s)\n",
            t->name, ty.pass, ty.cases, cbuf, ty.quoted, ty.match, ty.quoted - ty.match,
            ty.unquoted, ss_cli_now() - t1);
    *quoted += ty.quoted;
    *match += ty.match;
  }
  ss_reproduce_results_free(&l);
  ss_scheme_free(s);
  for (int k = 0; k < SS_REPRODUCE_MAXVS; k++) {
    ss_reproduce_results_free(&lv[k]);
    ss_scheme_free(sv[k]);
  }
  return rc;
}

/* The joint-spectral-radius table i (ss_cli_reproduce_jsr.c), as run_table. */
static int run_jsr_table(size_t i, const char *out, const ss_ref *ref, size_t *quoted,
                         size_t *match) {
  const double t1 = ss_cli_now();
  ss_error err = {0};
  ss_jsr_tally ty;
  if (ss_reproduce_jsr_table(i, out, ref, &ty, &err)) {
    fprintf(stderr, "subspectra %s: %s: %s\n", cmd, ss_reproduce_jsr_name(i), err.msg);
    return exit_for(&err);
  }
  fprintf(stderr,
          "subspectra reproduce: %s: %zu of %zu cases pass the joint spectral radius "
          "test (the "
          "reduction applies to %zu); %zu quoted values: %zu match, %zu differ (%.1f "
          "s)\n",
          ss_reproduce_jsr_name(i), ty.pass, ty.cases, ty.reduced, ty.quoted, ty.match,
          ty.quoted - ty.match, ss_cli_now() - t1);
  *quoted += ty.quoted;
  *match += ty.match;
  return SS_EXIT_OK;
}

/* The default of --tables, into buf: reproduce/tables.json beside the
 * reference folder refdir (REFDIR/../reproduce/tables.json) when that file
 * exists, so that the tables and the values they are compared with come
 * from one data set, also with --reference; else the one of the default data
 * folder (ss_cli_datapath).  NULL when it does not fit. */
static const char *default_tables(const char *refdir, char *buf, size_t cap) {
  const int n = snprintf(buf, cap, "%s/../reproduce/tables.json", refdir);
  if (n < 0 || (size_t)n >= cap) return NULL;
  if (access(buf, F_OK) == 0) return buf;
  return ss_cli_datapath("reproduce/tables.json", buf, cap);
}

/* Every reference file DIR/NAME.tsv into *ref; the exit status (2 with a
 * message when there are none or one is malformed). */
static int load_reference(const char *refdir, ss_ref *ref) {
  ss_error err = {0};
  glob_t g;
  memset(&g, 0, sizeof g);
  int rc = SS_EXIT_OK;
  char *pat = malloc(strlen(refdir) + 16);
  if (!pat) {
    ss_error_nomem(&err, "path");
    return ss_cli_fail("reproduce", &err);
  }
  sprintf(pat, "%s/*.tsv", refdir);
  if (glob(pat, 0, NULL, &g) != 0 || g.gl_pathc == 0) {
    fprintf(stderr,
            "subspectra %s: %s: no reference files (*.tsv); run from the source tree, "
            "set SUBSPECTRA_DATADIR or give --reference DIR\n",
            cmd, refdir);
    rc = SS_EXIT_USAGE;
  }
  for (size_t i = 0; i < g.gl_pathc && rc == SS_EXIT_OK; i++)
    if (ss_report_ref_load(g.gl_pathv[i], ref, &err)) {
      fprintf(stderr, "subspectra %s: %s\n", cmd, err.msg);
      rc = SS_EXIT_USAGE; /* a bad reference file, or out of memory */
    }
  globfree(&g);
  free(pat);
  return rc;
}

/* DIR, DIR/data and DIR/figures, made if missing; the exit status. */
static int make_out_dirs(const char *out) {
  static const char *const sub[] = {"", "/data", "/figures"};
  char *path = malloc(strlen(out) + 16);
  int rc = SS_EXIT_OK;
  if (!path) {
    ss_error err = {0};
    ss_error_nomem(&err, "path");
    return ss_cli_fail("reproduce", &err);
  }
  for (int i = 0; i < 3 && rc == SS_EXIT_OK; i++) {
    sprintf(path, "%s%s", out, sub[i]);
    if (make_dirs(path)) {
      fprintf(stderr, "subspectra %s: --out %s: cannot create %s: %s\n", cmd, out, path,
              strerror(errno));
      rc = SS_EXIT_USAGE;
    }
  }
  free(path);
  return rc;
}

int ss_cli_reproduce(int argc, char **argv) {
  static const struct option opts[] = {{"out", required_argument, NULL, 'o'},
                                       {"output", required_argument, NULL, 'o'},
                                       {"reference", required_argument, NULL, 'r'},
                                       {"tables", required_argument, NULL, 't'},
                                       {"certify", no_argument, NULL, 'c'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  const char *out = "reports", *refdir = NULL, *tables = NULL;
  char refbuf[4096], tabbuf[4096];
  ss_result_opts ro = ss_result_defaults();
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":o:r:t:h", opts, NULL)) != -1) {
    switch (c) {
    case 'o':
      out = optarg;
      break;
    case 'r':
      refdir = optarg;
      break;
    case 't':
      tables = optarg;
      break;
    case 'c':
      ro.certify = 1;
      break;
    case 'h':
      fputs(usage, stdout);
      return SS_EXIT_OK;
    default:
      return ss_cli_option_error(cmd, c, argv);
    }
  }
  if (optind < argc)
    return ss_cli_usage_error(cmd, "unexpected argument '%s'", argv[optind]);
  if (!*out) return ss_cli_usage_error(cmd, "--out: empty folder name");
  if (!refdir && !(refdir = ss_cli_refdir(refbuf, sizeof refbuf)))
    return ss_cli_usage_error(cmd, "SUBSPECTRA_DATADIR: path too long");
  if (!tables && !(tables = default_tables(refdir, tabbuf, sizeof tabbuf)))
    return ss_cli_usage_error(cmd, "--reference or SUBSPECTRA_DATADIR: path too long");

  ss_error err = {0};
  ss_ref ref = {0};
  ss_reproduce_spec spec = {0};
  int rc = load_reference(refdir, &ref);
  if (rc != SS_EXIT_OK) goto done;
  if (ss_reproduce_spec_load(tables, &spec, &err)) {
    fprintf(stderr, "subspectra %s: %s%s\n", cmd, err.msg,
            err.status == SS_EIO ? " (the tables to make); run from the source tree, set "
                                   "SUBSPECTRA_DATADIR or give --tables FILE"
                                 : "");
    rc = SS_EXIT_USAGE;
    goto done;
  }
  if ((rc = make_out_dirs(out)) != SS_EXIT_OK) goto done;
  const double t0 = ss_cli_now();
  size_t quoted = 0, match = 0;
  for (size_t i = 0; i < spec.ntables && rc == SS_EXIT_OK; i++)
    rc = run_table(spec.table + i, out, &ref, &ro, &quoted, &match);
  for (size_t i = 0; i < ss_reproduce_jsr_count() && rc == SS_EXIT_OK; i++)
    rc = run_jsr_table(i, out, &ref, &quoted, &match);
  if (rc != SS_EXIT_OK) goto done;
  const double t2 = ss_cli_now();
  if (ss_reproduce_figures(&spec, out, &err)) {
    fprintf(stderr, "subspectra %s: %s\n", cmd, err.msg);
    rc = exit_for(&err);
    goto done;
  }
  fprintf(
      stderr,
      "subspectra reproduce: figures: %zu pictures in %s/figures (%.1f s)\n"
      "subspectra reproduce: wrote %zu tables to %s (%zu quoted values: %zu match, %zu "
      "differ; %.1f s in all)\n",
      spec.nfigures, out, ss_cli_now() - t2, spec.ntables + ss_reproduce_jsr_count(), out,
      quoted, match, quoted - match, ss_cli_now() - t0);
done:
  ss_reproduce_spec_free(&spec);
  ss_report_ref_free(&ref);
  return rc;
}
