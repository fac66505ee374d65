/* bench_enumerate.c — speed and memory of the link generator.
 *
 * Case "write": every link with 4..14 vertices formatted in plantri ASCII and
 * written to /dev/null, one core; prints links per second for each k (the
 * generator visits k = 4..14 in one pass, so each k's time is measured by a
 * separate pass with kmin = kmax = k) and the total time against the target
 * of 60 s.  Case "count": k = 15 counted (2,406,841 expected) in a fresh
 * process; prints the peak resident memory against the 200 MB target, which
 * shows that memory does not grow with the number of links. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "ss_enum.h"

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The published numbers of sphere triangulations (DESIGN section 6), to
 * compare with what the generator counts. */
static const unsigned long long published[] = {
    0, 0, 0, 0, 1, 1, 2, 5, 14, 50, 233, 1249, 7595, 49566, 339722, 2406841, 17490241};

static const char *verdict(int k, uint64_t n) {
  return k <= 16 && n == published[k] ? "= published"
                                      : "DIFFERS from the published count";
}

static int write_link(const ss_link *l, void *ctx) {
  char *s;
  if (ss_link_format(l, &s, NULL)) return 1;
  fputs(s, ctx);
  fputc('\n', ctx);
  free(s);
  return 0;
}

static int case_write(void) {
  FILE *null = fopen("/dev/null", "w");
  if (!null) return 1;
  ss_error err = {0};
  uint64_t c[SS_ENUM_MAXK + 1];
  double t0 = now();
  ss_enum_opts all = {4, 14, 0, 1};
  if (ss_enum_links(&all, write_link, null, c, &err)) return 1;
  double total = now() - t0;
  uint64_t n = 0;
  for (int k = 4; k <= 14; k++)
    n += c[k];
  printf("all links with k = 4..14 written to /dev/null: %llu links in %.2f s "
         "(%.0f links/s); target <= 60 s\n",
         (unsigned long long)n, total, (double)n / total);
  printf("  k   links      seconds   links/s   (each k alone, written)\n");
  int bad = 0;
  for (int k = 8; k <= 14; k++) {
    ss_enum_opts o = {k, k, 0, 1};
    double t = now();
    if (ss_enum_links(&o, write_link, null, c, &err)) return 1;
    t = now() - t;
    printf(" %2d  %8llu  %8.3f  %9.0f   %s\n", k, (unsigned long long)c[k], t,
           (double)c[k] / t, verdict(k, c[k]));
    bad |= c[k] != published[k];
  }
  fclose(null);
  return bad;
}

static int case_count(int k) {
  ss_error err = {0};
  uint64_t c[SS_ENUM_MAXK + 1];
  ss_enum_opts o = {k, k, 0, 1};
  double t = now();
  if (ss_enum_links(&o, NULL, NULL, c, &err)) return 1;
  t = now() - t;
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  printf("k = %d counted: %llu links (%s) in %.2f s (%.0f links/s), peak resident memory "
         "%.1f MB; target < 200 MB\n",
         k, (unsigned long long)c[k], verdict(k, c[k]), t, (double)c[k] / t,
         (double)ru.ru_maxrss / 1024.0);
  return k <= 16 && c[k] != published[k];
}

int main(int argc, char **argv) {
  if (argc >= 3 && !strcmp(argv[1], "--case"))
    return !strcmp(argv[2], "write") ? case_write()
                                     : case_count(argc >= 4 ? atoi(argv[3]) : 15);
  const char *cases[] = {"write", "count"};
  int rc = 0;
  fflush(stdout);
  for (int i = 0; i < 2; i++) {
    pid_t pid = fork();
    if (pid == 0) {
      execl("/proc/self/exe", argv[0], "--case", cases[i], "15", (char *)NULL);
      _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status)) rc = 1;
  }
  return rc;
}
