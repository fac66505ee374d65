/* ss_cli.h — the subcommands of the `subspectra` tool and what they share.
 * Exit statuses (DESIGN section 7): 0 ran and everything checked holds, 1 ran
 * and something checked fails, 2 bad usage or bad input. */
#ifndef SS_CLI_H
#define SS_CLI_H

#include <stdio.h>

#include "ss_error.h"
#include "ss_link.h"
#include "ss_scheme.h"

enum { SS_EXIT_OK = 0, SS_EXIT_FAIL = 1, SS_EXIT_USAGE = 2 };

/* The one setting every command writes JSON with (json-c's
 * json_object_to_json_string_ext): compact, and '/' not escaped — json-c
 * escapes it by default ("1\/2"), which JSON allows but which made the same
 * value read differently from command to command (issue 40).  Needs
 * <json-c/json.h>. */
#define SS_CLI_JSON_FLAGS (JSON_C_TO_STRING_PLAIN | JSON_C_TO_STRING_NOSLASHESCAPE)

/* Subcommands: argv[0] is the subcommand name. */
int ss_cli_subdivide(int argc, char **argv);
int ss_cli_limit(int argc, char **argv);
int ss_cli_deform(int argc, char **argv);
int ss_cli_enumerate(int argc, char **argv);
int ss_cli_analyze(int argc, char **argv);
int ss_cli_matrix(int argc, char **argv);
int ss_cli_draw(int argc, char **argv);
int ss_cli_check(int argc, char **argv);
int ss_cli_tune(int argc, char **argv);
int ss_cli_sweep(int argc, char **argv);
int ss_cli_merge(int argc, char **argv);
int ss_cli_report(int argc, char **argv);
int ss_cli_reproduce(int argc, char **argv);
int ss_cli_jsr(int argc, char **argv);
/* `enumerate` sub-subcommands (argv[0] = "links", "canonical", ...). */
int ss_cli_enumerate_links(int argc, char **argv);
int ss_cli_enumerate_canonical(int argc, char **argv);
int ss_cli_enumerate_random(int argc, char **argv);
int ss_cli_enumerate_mesh(int argc, char **argv);

/* Print "subspectra CMD: <msg>" to stderr and return the exit status for a
 * failed library call: 2 for bad input, i/o or memory, 1 for numerical or
 * internal failures (the run happened but a check did not hold). */
int ss_cli_fail(const char *cmd, const ss_error *err);
/* The exit status of a failed library call's status, as ss_cli_fail: 2 for
 * SS_EINPUT, SS_EIO and SS_ENOMEM (out of memory is never "a check fails"),
 * 1 for SS_ENUMERIC and SS_EINTERNAL. */
int ss_cli_exit_status(ss_status st);

/* For commands that read local subdivision matrices in bulk (check, sweep):
 * if scheme s is quasi48 (the geometry-sensitive bisect split, whose local
 * matrices exist for surface vertices only, through analyze and matrix),
 * print why on stderr, prefixed by "subspectra CMD: ", and return 1;
 * otherwise 0. */
int ss_cli_refuse_local(const char *cmd, const ss_scheme *s);
/* Parse a memory size: a positive number with an optional suffix K, M, G or T
 * (powers of 1000, as the messages print them; a trailing B is allowed:
 * "8G", "1.5GB", "500M").  0 on success, -1 otherwise. */
int ss_cli_parse_bytes(const char *s, double *out);
/* The memory budget of one analysis: --max-memory if given (> 0), else the
 * default (ss_local_memory_budget: half the physical memory, 3/4 of the
 * address space and data limits). */
double ss_cli_budget(double max_memory);
/* Progress lines on stderr ("subspectra CMD: [3.2 s] phase done/total"):
 * ss_cli_progress_fn is an ss_progress_fn whose ctx is an ss_cli_progress.
 * A line is printed when the phase changes, or at most once a second. */
typedef struct {
  const char *cmd;   /* command name for the prefix */
  double t0;         /* start (ss_cli_now) */
  double last;       /* time of the last line */
  const char *phase; /* the phase of the last line */
  size_t done;       /* its step */
} ss_cli_progress;
void ss_cli_progress_fn(void *ctx, const char *phase, size_t done, size_t total);
/* Print "subspectra CMD: <message>" and a hint to use --help; returns 2. */
int ss_cli_usage_error(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* --format: set *json from "text" or "json"; otherwise print a usage error
 * for cmd and return 2 (0 on success). */
int ss_cli_format_option(const char *cmd, const char *arg, int *json);
/* The usage error for getopt_long's ':' (missing value) or '?' (unknown
 * option) result c; returns 2. */
int ss_cli_option_error(const char *cmd, int c, char **argv);
/* Parse a whole decimal integer in [lo, hi]; 0 on success, -1 otherwise. */
int ss_cli_parse_int(const char *s, long lo, long hi, long *out);

/* The shared options (ss_cli_opt.c), one definition each: 0 and *out set, or
 * the usage error's exit status (2) after the message.  --tol: a relative
 * tolerance in (0, SS_CLI_TOL_MAX); --depth: the hex depth limit
 * 0..SS_CLI_DEPTH_MAX; the scheme source: exactly one of --scheme and
 * --stencil (NULL when absent). */
#define SS_CLI_TOL_MAX   0.1
#define SS_CLI_DEPTH_MAX 12
int ss_cli_opt_tol(const char *cmd, const char *arg, double *out);
int ss_cli_opt_depth(const char *cmd, const char *arg, long *out);
int ss_cli_opt_scheme_source(const char *cmd, const char *scheme, const char *stencil);
/* Parse "A" or "A..B" (integers 0..1000000) into *a, *b; 0 or -1. */
int ss_cli_parse_range(const char *s, long *a, long *b);
/* Parse "I/N" (--part) with integers 0 <= I < N <= 10^9; 0 or -1. */
int ss_cli_parse_part(const char *s, long *part, long *nparts);
/* The next item of a line-oriented input (one link per line): reads lines
 * from f, drops '#' comments and surrounding white space, skips empty lines.
 * Returns the item, which lives in *line until the next call, or NULL at the
 * end of the input; *lineno counts every line read, for messages. */
char *ss_cli_next_item(FILE *f, char **line, size_t *cap, long *lineno);
/* The links of --links PATH (one a line as ss_cli_next_item reads them;
 * '-' stdin) for command cmd, each parsed and handed to take(l, ctx), which
 * owns l from then on and returns 0, or nonzero when out of memory.  0, or
 * SS_EXIT_USAGE after a message on stderr (PATH cannot be opened, a line is
 * not a link, take failed, no links at all). */
int ss_cli_read_links(const char *cmd, const char *path,
                      int (*take)(ss_link *l, void *ctx), void *ctx);
/* Monotonic wall-clock seconds (ss_clock_wall). */
double ss_cli_now(void);
#ifndef SS_DATADIR
/* where `meson install` puts data/ (stencils/, reference/, meshes/); meson
 * defines it from the prefix (cli/meson.build) */
#define SS_DATADIR "/usr/local/share/subspectra"
#endif
#ifndef SS_DATADIR_REL
/* the same, relative to the folder of the installed program ("" if none) */
#define SS_DATADIR_REL "../share/subspectra"
#endif
/* The default folder of the reference values for `reproduce`:
 * $SUBSPECTRA_DATADIR/reference when that variable is set; else
 * data/reference when it holds *.tsv files (run from the source tree); else
 * the installed data beside the program (SS_DATADIR_REL from its folder) when
 * it holds them; else SS_DATADIR/reference.  Written into buf (cap bytes);
 * returns buf, or NULL if it does not fit. */
char *ss_cli_refdir(char *buf, size_t cap);
/* The same data folder as ss_cli_refdir, with sub in place of "reference"
 * (reproduce's tables: "reproduce/tables.json"), so that both come from one
 * data set.  buf or NULL as ss_cli_refdir. */
char *ss_cli_datapath(const char *sub, char *buf, size_t cap);

#endif
