/* ss_cli_util.c — error reporting and option parsing shared by subcommands. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <getopt.h>
#include <glob.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>
#include <unistd.h>

#include "ss_cli.h"
#include "ss_clock.h"
#include "ss_local.h"

int ss_cli_fail(const char *cmd, const ss_error *err) {
  fprintf(stderr, "subspectra %s: %s\n", cmd,
          err->msg[0] ? err->msg : ss_status_name(err->status));
  return ss_cli_exit_status(err->status);
}

int ss_cli_exit_status(ss_status st) {
  return st == SS_ENUMERIC || st == SS_EINTERNAL ? SS_EXIT_FAIL : SS_EXIT_USAGE;
}

int ss_cli_parse_bytes(const char *s, double *out) {
  if (!s || !*s) return -1;
  char *end = NULL;
  errno = 0;
  double v = strtod(s, &end);
  if (errno || end == s || !(v > 0.0) || !isfinite(v)) return -1;
  static const char suffix[] = "KMGT";
  const char *p = *end ? strchr(suffix, toupper((unsigned char)*end)) : NULL;
  if (*end && !p) return -1;
  if (p) {
    for (const char *q = suffix; q <= p; q++)
      v *= 1000.0;
    end++;
  }
  if (*end == 'B' || *end == 'b') end++;
  if (*end || !(v >= 1.0) || !isfinite(v)) return -1;
  *out = v;
  return 0;
}

double ss_cli_budget(double max_memory) {
  return max_memory > 0.0 ? max_memory : ss_local_memory_budget();
}

void ss_cli_progress_fn(void *ctx, const char *phase, size_t done, size_t total) {
  ss_cli_progress *p = ctx;
  const double t = ss_cli_now();
  /* a new phase, a new step of a phase without a total (a level), the last
   * step, or a second since the last line */
  if (phase == p->phase && (total || done == p->done) && t - p->last < 1.0 &&
      !(total && done == total))
    return;
  p->phase = phase;
  p->done = done;
  p->last = t;
  if (total)
    fprintf(stderr, "subspectra %s: [%.1f s] %s %zu/%zu\n", p->cmd, t - p->t0, phase,
            done, total);
  else if (done)
    fprintf(stderr, "subspectra %s: [%.1f s] %s %zu\n", p->cmd, t - p->t0, phase, done);
  else
    fprintf(stderr, "subspectra %s: [%.1f s] %s\n", p->cmd, t - p->t0, phase);
}

int ss_cli_usage_error(const char *cmd, const char *fmt, ...) {
  /* option values are the user's bytes: escaped like library messages */
  char raw[1024], msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(raw, sizeof raw, fmt, ap);
  va_end(ap);
  fprintf(stderr, "subspectra %s: %s\n(see 'subspectra %s --help')\n", cmd,
          ss_error_escape(msg, sizeof msg, raw), cmd);
  return SS_EXIT_USAGE;
}

int ss_cli_parse_int(const char *s, long lo, long hi, long *out) {
  if (!s || !*s) return -1;
  char *end = NULL;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (errno || *end || v < lo || v > hi) return -1;
  *out = v;
  return 0;
}

double ss_cli_now(void) {
  return ss_clock_wall();
}

int ss_cli_format_option(const char *cmd, const char *arg, int *json) {
  if (!strcmp(arg, "json")) {
    *json = 1;
  } else if (!strcmp(arg, "text")) {
    *json = 0;
  } else {
    return ss_cli_usage_error(cmd, "--format '%s' is not text or json", arg);
  }
  return 0;
}

int ss_cli_option_error(const char *cmd, int c, char **argv) {
  if (c == ':')
    return ss_cli_usage_error(cmd, "option %s needs a value", argv[optind - 1]);
  return ss_cli_usage_error(cmd, "unknown option '%s'", argv[optind - 1]);
}

char *ss_cli_next_item(FILE *f, char **line, size_t *cap, long *lineno) {
  while (getline(line, cap, f) >= 0) {
    ++*lineno;
    char *p = *line, *hash = strchr(p, '#');
    if (hash) *hash = '\0';
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
      p++;
    size_t len = strlen(p);
    while (len && (p[len - 1] == ' ' || p[len - 1] == '\t' || p[len - 1] == '\r' ||
                   p[len - 1] == '\n'))
      p[--len] = '\0';
    if (*p) return p;
  }
  return NULL;
}

int ss_cli_read_links(const char *cmd, const char *path,
                      int (*take)(ss_link *l, void *ctx), void *ctx) {
  FILE *f = strcmp(path, "-") ? fopen(path, "r") : stdin;
  const char *name = f == stdin ? "stdin" : path;
  if (!f) {
    fprintf(stderr, "subspectra %s: --links %s: cannot open\n", cmd, path);
    return SS_EXIT_USAGE;
  }
  char *line = NULL, *p;
  size_t cap = 0, n = 0;
  long lineno = 0;
  int rc = SS_EXIT_OK;
  while (!rc && (p = ss_cli_next_item(f, &line, &cap, &lineno))) {
    ss_error err = {0};
    ss_link *l = NULL;
    if (ss_link_parse(p, &l, &err)) {
      fprintf(stderr, "subspectra %s: %s:%ld: %s\n", cmd, name, lineno, err.msg);
      rc = SS_EXIT_USAGE;
    } else if (take(l, ctx)) {
      fprintf(stderr, "subspectra %s: out of memory reading %s\n", cmd, name);
      rc = SS_EXIT_USAGE;
    } else {
      n++;
    }
  }
  free(line);
  if (f != stdin) fclose(f);
  if (!rc && !n) {
    fprintf(stderr, "subspectra %s: --links %s: no links read\n", cmd, name);
    rc = SS_EXIT_USAGE;
  }
  return rc;
}

int ss_cli_parse_range(const char *s, long *a, long *b) {
  const char *dots = strstr(s, "..");
  if (!dots) {
    if (ss_cli_parse_int(s, 0, 1000000, a)) return -1;
    *b = *a;
    return 0;
  }
  char first[32];
  size_t n = (size_t)(dots - s);
  if (n == 0 || n >= sizeof first) return -1;
  memcpy(first, s, n);
  first[n] = '\0';
  if (ss_cli_parse_int(first, 0, 1000000, a) || ss_cli_parse_int(dots + 2, 0, 1000000, b))
    return -1;
  return 0;
}

int ss_cli_parse_part(const char *s, long *part, long *nparts) {
  const char *slash = strchr(s, '/');
  char first[32];
  const size_t n = slash ? (size_t)(slash - s) : 0;
  if (!slash || n == 0 || n >= sizeof first) return -1;
  memcpy(first, s, n);
  first[n] = '\0';
  if (ss_cli_parse_int(slash + 1, 1, 1000000000, nparts) ||
      ss_cli_parse_int(first, 0, *nparts - 1, part))
    return -1;
  return 0;
}

int ss_cli_refuse_local(const char *cmd, const ss_scheme *s) {
  if (ss_scheme_split_kind(s) != SS_SPLIT_BISECT) return 0;
  /* its split depends on positions; the analysis refines 4-8 stars by the
   * topological refinement instead, for surface vertices only (ss_case.h) */
  fprintf(stderr,
          "subspectra %s: scheme %s: only its surface vertices are analysed (analyze "
          "--scheme %s --surface-vertex N --class 4|8); %s of its geometry-sensitive "
          "(bisection) split is not implemented\n",
          cmd, ss_scheme_name(s), ss_scheme_name(s), cmd);
  return 1;
}

/* Whether DIR/reference holds reference files (*.tsv). */
static int has_reference(const char *dir) {
  char pat[4200];
  if ((size_t)snprintf(pat, sizeof pat, "%s/reference/*.tsv", dir) >= sizeof pat)
    return 0;
  glob_t g;
  const int yes = glob(pat, 0, NULL, &g) == 0 && g.gl_pathc > 0;
  globfree(&g);
  return yes;
}

char *ss_cli_refdir(char *buf, size_t cap) {
  return ss_cli_datapath("reference", buf, cap);
}

char *ss_cli_datapath(const char *sub, char *buf, size_t cap) {
  const char *env = getenv("SUBSPECTRA_DATADIR");
  char dir[4096] = "";
  if (env && *env) {
    if (strlen(env) >= sizeof dir) return NULL;
    snprintf(dir, sizeof dir, "%s", env);
  } else if (has_reference("data"))
    /* the source tree first, as before an install existed: a developer's
     * edits to data/reference must be what reproduce reads */
    snprintf(dir, sizeof dir, "data");
  else {
    /* the installed data beside this program (PREFIX/bin/../share/subspectra),
     * which also holds in a moved or DESTDIR-staged tree; else the compiled-in
     * absolute path */
    char exe[4096];
    const ssize_t n =
        SS_DATADIR_REL[0] ? readlink("/proc/self/exe", exe, sizeof exe - 1) : -1;
    char *slash = n > 0 ? (exe[n] = '\0', strrchr(exe, '/')) : NULL;
    if (slash) *slash = '\0';
    if (!slash ||
        (size_t)snprintf(dir, sizeof dir, "%s/%s", exe, SS_DATADIR_REL) >= sizeof dir ||
        !has_reference(dir))
      snprintf(dir, sizeof dir, "%s", SS_DATADIR);
  }
  const int n = snprintf(buf, cap, "%s/%s", dir, sub);
  return n >= 0 && (size_t)n < cap ? buf : NULL;
}
