/* main.c — `subspectra`: one program, one subcommand per job. */
#include <errno.h>
#include <fcntl.h>
#include <malloc.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <flint/flint.h>
#include <gsl/gsl_errno.h>

#include "ss_cli.h"
#include "ss_outfile.h"
#include "ss_version.h"

typedef struct {
  const char *name;         /* subcommand */
  int (*run)(int, char **); /* its entry point */
  const char *summary;      /* one line for the overview */
} command;

static const command commands[] = {
    {"analyze", ss_cli_analyze,
     "local subdivision matrix, eigenstructure, verdicts of a case"},
    {"matrix", ss_cli_matrix, "the local subdivision matrix of a case (Matrix Market)"},
    {"draw", ss_cli_draw, "a picture of a case's characteristic map (PNG, SVG, VTK)"},
    {"enumerate", ss_cli_enumerate, "links (vertex one-rings): all, random, of a mesh"},
    {"subdivide", ss_cli_subdivide, "refine a mesh L times with a scheme"},
    {"limit", ss_cli_limit, "points and Jacobians of a hex mesh's limit volume"},
    {"deform", ss_cli_deform,
     "test patterns embedded in a mesh, deformed through the limit"},
    {"check", ss_cli_check, "the CI gate: every case of a stencil file must pass"},
    {"tune", ss_cli_tune, "choose a stencil's free parameters so that every case passes"},
    {"sweep", ss_cli_sweep, "analyse many cases into a resumable SQLite store"},
    {"merge", ss_cli_merge, "join the stores of sweep parts into one"},
    {"report", ss_cli_report, "tables (md, csv, tex, json) and plots of a store"},
    {"reproduce", ss_cli_reproduce, "the papers' tables beside the values they quote"},
    {"jsr", ss_cli_jsr, "Levin-Levin joint-spectral-radius test of a face or an edge"},
};

static void overview(FILE *f) {
  fprintf(f,
          "subspectra %s — spectral analysis and smoothness verification of subdivision "
          "schemes\n\n"
          "usage: subspectra COMMAND [OPTIONS] ...\n\ncommands:\n",
          SS_VERSION_STRING);
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    fprintf(f, "  %-12s %s\n", commands[i].name, commands[i].summary);
  fprintf(f, "\n'subspectra help COMMAND' (or 'subspectra COMMAND --help') describes a\n"
             "command; 'subspectra [COMMAND] --version' prints the version.\n"
             "Exit status: 0 ran and everything checked holds, 1 ran and something "
             "checked fails,\n2 bad usage or bad input.\n");
}

/* ---- standard output ----
 * Standard output is written through a buffer: a full disk, a file size limit
 * or a reader gone away may only show when it is flushed, and glibc forgets
 * why once the failed buffer is dropped.  So main puts its own stream in
 * stdout's place (ss_outfile_fdopen: the same buffering, but it remembers the
 * first failure's errno), and every command ends in finish(): flush, check the
 * error flag, close.  A failure turns the command's status rc into 2 with
 * "subspectra COMMAND: error writing standard output: REASON" (the output is lost,
 * whatever was computed).  EPIPE is the exception: the reader closed the pipe
 * early (`| head`), which is its choice, not an error of ours -- no message and
 * rc kept.  (With SIGPIPE at its default, as we leave it, the kernel ends the
 * process silently at that write anyway; EPIPE is seen only when the caller
 * ignores SIGPIPE.)  Streaming commands stop once ferror(stdout) is set. */

static int stdout_errno; /* why the first write to fd 1 failed; 0 while none has */

static void stdout_open(void) {
  /* a closed fd 1 (`>&-`) would be taken by the next file opened, and our
   * output written into it: hold it with /dev/null, and fail every write */
  if (fcntl(STDOUT_FILENO, F_GETFD) < 0 && errno == EBADF) {
    stdout_errno = EBADF;
    const int fd = open("/dev/null", O_WRONLY);
    if (fd >= 0 && fd != STDOUT_FILENO) close(fd);
  }
  FILE *f = ss_outfile_fdopen(STDOUT_FILENO, &stdout_errno);
  if (!f) return; /* the plain stream: only a failure's reason may get lost */
  if (isatty(STDOUT_FILENO)) setvbuf(f, NULL, _IOLBF, BUFSIZ);
  stdout = f; /* glibc's stdout is a variable for this purpose */
}

static int finish(int rc, const char *cmd) {
  errno = 0;
  int bad = fflush(stdout) != 0;
  int e = errno;
  if (ferror(stdout)) bad = 1;
  /* closes fd 1 too: errors that show only then (NFS) count */
  if (fclose(stdout) != 0 && !bad) bad = 1, e = errno;
  if (bad && stdout_errno) e = stdout_errno; /* a closed fd 1 counts only if used */
  if (!bad || e == EPIPE) return rc;
  fprintf(stderr, "subspectra%s%s: error writing standard output: %s\n", cmd ? " " : "",
          cmd ? cmd : "", strerror(e ? e : EIO));
  return SS_EXIT_USAGE;
}

static const command *find(const char *name) {
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (!strcmp(name, commands[i].name)) return &commands[i];
  return NULL;
}

/* `subspectra help [COMMAND [WHAT]]`: the overview, or exactly what
 * `subspectra COMMAND [WHAT] --help` prints (one text, one place); an unknown
 * command is a usage error. */
static int help(int argc, char **argv) {
  if (argc < 3 || !strcmp(argv[2], "--help") || !strcmp(argv[2], "-h")) {
    overview(stdout);
    return SS_EXIT_OK;
  }
  const command *c = find(argv[2]);
  char name[256];
  if (!c) {
    fprintf(stderr,
            "subspectra help: unknown command '%s' (the commands are listed by "
            "'subspectra help')\n",
            ss_error_escape(name, sizeof name, argv[2]));
    return SS_EXIT_USAGE;
  }
  if (argc > (strcmp(c->name, "enumerate") ? 3 : 4)) {
    fprintf(stderr,
            "subspectra help: too many arguments ('subspectra help %s%s' at "
            "most)\n",
            c->name, strcmp(c->name, "enumerate") ? "" : " WHAT");
    return SS_EXIT_USAGE;
  }
  /* COMMAND [WHAT] --help: enumerate's WHAT names its sub-command */
  char help_opt[] = "--help";
  char *args[4] = {argv[2], argc > 3 ? argv[3] : help_opt, help_opt, NULL};
  return c->run(argc > 3 ? 3 : 2, args);
}

static int run(int argc, char **argv) {
  /* library code reports through ss_status; GSL must not abort the process */
  gsl_set_error_handler_off();
  if (argc < 2) {
    overview(stderr);
    return SS_EXIT_USAGE;
  }
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    overview(stdout);
    return SS_EXIT_OK;
  }
  if (!strcmp(argv[1], "help")) return help(argc, argv);
  if (!strcmp(argv[1], "--version")) {
    printf("subspectra %s\n", SS_VERSION_STRING);
    return SS_EXIT_OK;
  }
  const command *c = find(argv[1]);
  if (c) {
    /* --version anywhere among a command's options, as every command's
     * --help says: one place instead of one option per command */
    for (int a = 2; a < argc && strcmp(argv[a], "--"); a++)
      if (!strcmp(argv[a], "--version")) {
        printf("subspectra %s\n", SS_VERSION_STRING);
        return SS_EXIT_OK;
      }
    const int rc = c->run(argc - 1, argv + 1);
    flint_cleanup_master(); /* FLINT's caches (the exact path, --certify) */
    return rc;
  }
  char name[256];
  fprintf(stderr, "subspectra: unknown command '%s' (see 'subspectra --help')\n",
          ss_error_escape(name, sizeof name, argv[1]));
  return SS_EXIT_USAGE;
}

/* Keep freed memory for reuse instead of returning it to the kernel at once.
 * A case builds and frees a few levels of several megabytes; with glibc's
 * defaults (blocks above a sliding threshold mapped and unmapped, the heap
 * trimmed above 128 KiB free) every case faulted its memory in afresh: 1300
 * page faults per k = 11 MLCA case, 14 % of its CPU time in the kernel, and
 * the unmapping serialises threads on the process's address-space lock.
 * With these limits a sweep faults 25 times fewer pages for the same peak
 * (issue 20).  Process-wide, hence here in the program, not the library. */
static void malloc_tune(void) {
#if defined(M_MMAP_THRESHOLD) && defined(M_TRIM_THRESHOLD)
  mallopt(M_MMAP_THRESHOLD, 32 << 20); /* glibc's largest: blocks below stay */
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
#endif
}

int main(int argc, char **argv) {
  malloc_tune();
  stdout_open();
  /* the command the messages name: a known one (or help), else none */
  const char *cmd =
      argc > 1 && (find(argv[1]) || !strcmp(argv[1], "help")) ? argv[1] : NULL;
  return finish(run(argc, argv), cmd);
}
