/* ss_cli_report.c — `subspectra report`: tables (Markdown, CSV, LaTeX, JSON)
 * and a figure of the cases in a results store written by `subspectra sweep`.
 * Exit status 0 when every reported case passes both conditions, 1 when any
 * fails or is undecided, 2 on bad usage, a bad store or a bad --where. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_report_draw.h"
#include "ss_report_exhaustive.h"
#include "ss_report_plot.h"
#include "ss_report_table.h"
#include "ss_store.h"

static const char *const usage_text =
    "usage: subspectra report --db FILE [--format md|csv|tex|json]\n"
    "                         [--table cases|summary|both|exhaustive|not-passing]\n"
    "                         [--where EXPR]\n"
    "                         [--plot FILE.png|.svg|.pdf] [--size WxH] [--label NAME]\n"
    "\n"
    "Tables of the cases in a results store (written by `subspectra sweep`):\n"
    "  cases    one row per case: scheme, case, k (link vertices) or valence,\n"
    "           cells, canonical link (vertex cases), lambda1..lambda4 of the\n"
    "           two-ring matrix (a+bi when complex) and their multiplicities,\n"
    "           the eigenvalue condition and the regularity of the\n"
    "           characteristic map with their reasons, the minimum scaled\n"
    "           Jacobian, and improper pairs of major diagonals (boxspline);\n"
    "  summary  per scheme identity, case kind and k: cases, pass, fail,\n"
    "           undecided (pass = both conditions hold), the worst minimum\n"
    "           scaled Jacobian and the range of |lambda1|;\n"
    "  exhaustive  vertex one-rings per scheme identity and k: links, pass,\n"
    "           fail by the first condition that fails (eigenvalue condition,\n"
    "           regularity, injectivity only), undecided, passes with folds\n"
    "           around p only, points on an edge, and (--certify sweeps) how\n"
    "           many passes and failures are proven: the rows `reproduce`\n"
    "           writes for its tables over every link (md, csv or json);\n"
    "  not-passing  every vertex link that fails or is undecided, with that\n"
    "           class, whether it is proven and the three reasons (csv or\n"
    "           json).  reports/exhaustive.sh writes both for k <= 12.\n"
    "\n"
    "  --db FILE          the results store (SQLite)\n"
    "  --format F         md (GitHub Markdown, default), csv (RFC 4180, one table,\n"
    "                     numbers to 17 digits), tex (paste into a paper with\n"
    "                     \\usepackage{booktabs,longtable,array}: the cases in a\n"
    "                     longtable that runs over pages, the summary in a table\n"
    "                     float, both within \\linewidth), json ({\"cases\":\n"
    "                     [...], \"summary\": [...]}, numbers as numbers)\n"
    "  --label NAME       tex: the tables' labels tab:NAME-cases and\n"
    "                     tab:NAME-summary (default subspectra)\n"
    "  --table T          cases, summary, both (default both; csv: cases),\n"
    "                     exhaustive or not-passing\n"
    "  --where EXPR       an SQL expression over the columns of the view `cases`:\n"
    "                     scheme, identity, kind, k, link, cells, two_ring,\n"
    "                     one_ring, lambda1..lambda4 (moduli), eigen_condition,\n"
    "                     regularity, verdict ('pass', 'fail', 'undecided'),\n"
    "                     min_scaled_jacobian, tolerance, depth, improper_pairs,\n"
    "                     seconds.  E.g. --where \"kind = 'vertex' AND k <= 8\",\n"
    "                     --where \"verdict != 'pass'\"\n"
    "  --plot FILE        a figure against k: |lambda1..4| and the minimum scaled\n"
    "                     Jacobian (failing cases red), PNG, SVG or PDF by the\n"
    "                     extension; one scheme identity (the first selected).\n"
    "                     Alone (without --format or --table) no table is printed\n"
    "  --size WxH         the figure's size (default: 560 per case kind + 20, x 720)\n"
    "  --fail-on-fail     exit 1 when a reported case fails or is undecided (for\n"
    "                     CI; `subspectra check` is the gate for a stencil)\n"
    "  -h, --help         this text\n"
    "\n"
    "An empty selection prints empty tables (a note on stderr) and exits 0.\n"
    "Exit status: 0 when the tables (and figure) were written, whatever the\n"
    "verdicts; 1 only with --fail-on-fail when some reported case fails or is\n"
    "undecided; 2 bad usage, a bad store or a bad --where.\n";

/* Library failure: the message, and exit status 2 (bad store, bad --where,
 * unwritable output, no memory). */
static int report_fail(const ss_error *err) {
  fprintf(stderr, "subspectra report: %s\n",
          err->msg[0] ? err->msg : ss_status_name(err->status));
  return SS_EXIT_USAGE;
}

enum { O_DB = 256, O_FORMAT, O_TABLE, O_WHERE, O_PLOT, O_SIZE, O_FAILONFAIL, O_LABEL };

static const struct option report_options[] = {
    {"db", required_argument, NULL, O_DB},
    {"format", required_argument, NULL, O_FORMAT},
    {"table", required_argument, NULL, O_TABLE},
    {"where", required_argument, NULL, O_WHERE},
    {"plot", required_argument, NULL, O_PLOT},
    {"size", required_argument, NULL, O_SIZE},
    {"fail-on-fail", no_argument, NULL, O_FAILONFAIL},
    {"label", required_argument, NULL, O_LABEL},
    {"help", no_argument, NULL, 'h'},
    {NULL, 0, NULL, 0}};

/* The command line of report. */
typedef struct {
  const char *db;         /* --db */
  const char *where;      /* --where, or NULL */
  const char *plot;       /* --plot FILE, or NULL */
  const char *label;      /* --label, or NULL */
  ss_report_format fmt;   /* --format */
  int have_format;        /* --format was given */
  int fail_on_fail;       /* --fail-on-fail */
  unsigned tables;        /* --table cases, summary or both (ss_report_tables) */
  int exh;                /* --table exhaustive or not-passing:
                             ss_report_exh_table; else -1 */
  int print;              /* print tables (not --plot alone) */
  ss_report_plot_opts po; /* --size */
} report_args;

/* One option c (its argument in optarg) into a: -1 to go on, else the exit
 * status (0 after --help, 2 with the message printed). */
static int parse_option(int c, char **argv, report_args *a) {
  switch (c) {
  case O_DB:
    a->db = optarg;
    break;
  case O_FORMAT:
    if (ss_report_format_parse(optarg, &a->fmt))
      return ss_cli_usage_error("report", "--format '%s' is not md, csv, tex or json",
                                optarg);
    a->have_format = 1;
    break;
  case O_TABLE:
    a->exh = !strcmp(optarg, "exhaustive")    ? SS_REPORT_EXH_COUNTS
             : !strcmp(optarg, "not-passing") ? SS_REPORT_EXH_LINKS
                                              : -1;
    a->tables = 0;
    if (a->exh < 0 && ss_report_tables_parse(optarg, &a->tables))
      return ss_cli_usage_error(
          "report", "--table '%s' is not cases, summary, both, exhaustive or not-passing",
          optarg);
    break;
  case O_WHERE:
    a->where = optarg;
    break;
  case O_PLOT:
    a->plot = optarg;
    break;
  case O_SIZE: {
    int w = 0, h = 0;
    char tail;
    if (sscanf(optarg, "%dx%d%c", &w, &h, &tail) != 2 || w < 200 || h < 200 ||
        w > 10000 || h > 10000)
      return ss_cli_usage_error(
          "report", "--size '%s' is not WxH with 200 <= W, H <= 10000", optarg);
    a->po.width = w;
    a->po.height = h;
    break;
  }
  case O_FAILONFAIL:
    a->fail_on_fail = 1;
    break;
  case O_LABEL:
    if (!*optarg || strspn(optarg, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                   "0123456789-_:.") != strlen(optarg))
      return ss_cli_usage_error("report",
                                "--label '%s': use letters, digits, '-', '_', ':' "
                                "and '.' only",
                                optarg);
    a->label = optarg;
    break;
  case 'h':
    fputs(usage_text, stdout);
    return SS_EXIT_OK;
  default:
    return ss_cli_option_error("report", c, argv);
  }
  return -1;
}

/* argv into a, the options checked against each other and the default
 * tables chosen: -1 to go on, else the exit status (0 after --help, 2 with
 * the message printed). */
static int parse_args(int argc, char **argv, report_args *a) {
  *a = (report_args){.fmt = SS_REPORT_MD, .exh = -1, .po = ss_report_plot_defaults()};
  optind = 1;
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, ":h", report_options, NULL)) != -1) {
    const int rc = parse_option(c, argv, a);
    if (rc >= 0) return rc;
  }
  if (optind < argc)
    return ss_cli_usage_error("report", "unexpected argument '%s'", argv[optind]);
  if (!a->db) return ss_cli_usage_error("report", "no results store given (--db FILE)");
  if (a->label && a->fmt != SS_REPORT_TEX)
    return ss_cli_usage_error("report", "--label is for --format tex");
  if ((a->po.width || a->po.height) && !a->plot)
    return ss_cli_usage_error("report", "--size needs --plot");
  if (a->exh >= 0 && a->plot)
    return ss_cli_usage_error("report",
                              "--plot goes with --table cases, summary or both");
  if (a->exh >= 0 && a->fmt == SS_REPORT_TEX)
    return ss_cli_usage_error("report", "--table %s: --format md, csv or json",
                              a->exh == SS_REPORT_EXH_COUNTS ? "exhaustive"
                                                             : "not-passing");
  if (a->exh == SS_REPORT_EXH_LINKS && a->fmt == SS_REPORT_MD)
    return ss_cli_usage_error("report", "--table not-passing: --format csv or json");
  /* --plot alone prints no table */
  a->print = a->have_format || a->tables || a->exh >= 0 || !a->plot;
  if (!a->tables && a->exh < 0)
    a->tables = a->fmt == SS_REPORT_CSV ? SS_REPORT_CASES : SS_REPORT_BOTH;
  if (a->fmt == SS_REPORT_CSV && a->tables == SS_REPORT_BOTH)
    return ss_cli_usage_error("report",
                              "--format csv holds one table: --table cases or summary");
  if (a->plot) {
    /* the format check before the (possibly long) read of the store */
    ss_pic_format pf;
    if (ss_report_pic_format(a->plot, &pf))
      return ss_cli_usage_error(
          "report", "--plot '%s' is not FILE.png, FILE.svg or FILE.pdf", a->plot);
  }
  return -1;
}

/* The figure of --plot: the first scheme identity of the rows, and a note
 * on stderr when there are others.  SS_OK, or the plot's error. */
static ss_status plot_rows(const report_args *a, const ss_report_rows *rows,
                           ss_error *err) {
  size_t nid = rows->n > 0;
  for (size_t i = 1; i < rows->n; i++)
    nid += strcmp(rows->row[i].identity, rows->row[i - 1].identity) != 0;
  size_t plotted = 0;
  const ss_status st = ss_report_plot(rows->row, rows->n, &a->po, a->plot, &plotted, err);
  if (st) return st;
  if (nid > 1)
    fprintf(stderr,
            "subspectra report: --plot: %zu scheme identities selected; %s shows the "
            "first, '%s' (%zu cases); choose another with --where \"identity = "
            "'...'\"\n",
            nid, a->plot, rows->row[0].identity, plotted);
  return SS_OK;
}

int ss_cli_report(int argc, char **argv) {
  report_args a;
  int rc = parse_args(argc, argv, &a);
  if (rc >= 0) return rc;
  ss_error err = {0};
  ss_store *st = NULL;
  ss_report_rows rows = {0};
  ss_report_summary *sum = NULL;
  size_t ns = 0;
  rc = SS_EXIT_OK;
  if (ss_store_open(a.db, SS_STORE_READ, &st, &err) ||
      ss_report_rows_load(st, a.where, &rows, &err) ||
      ss_report_summarize(rows.row, rows.n, &sum, &ns, &err)) {
    rc = report_fail(&err);
    goto done;
  }
  if (rows.n == 0)
    fprintf(stderr, "subspectra report: %s: no cases selected%s\n", a.db,
            a.where ? " by --where" : " (an empty store)");
  if (a.print &&
      (a.exh >= 0 ? ss_report_exh_write(stdout, a.fmt, (ss_report_exh_table)a.exh,
                                        rows.row, rows.n, &err)
                  : ss_report_table_write(stdout, a.fmt, a.tables, rows.row, rows.n, sum,
                                          ns, a.label, &err))) {
    /* standard output failed: main reports it, with the reason */
    if (!(err.status == SS_EIO && ferror(stdout))) rc = report_fail(&err);
    goto done;
  }
  if (a.plot && plot_rows(&a, &rows, &err)) {
    rc = report_fail(&err);
    goto done;
  }
  for (size_t i = 0; a.fail_on_fail && i < rows.n; i++)
    if (ss_result_verdict(&rows.row[i].r) != SS_PASS) rc = SS_EXIT_FAIL;
done:
  free(sum);
  ss_report_rows_clear(&rows);
  ss_store_close(st);
  return rc;
}
