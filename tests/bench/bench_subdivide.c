/* bench_subdivide.c — speed and memory of whole-mesh subdivision.
 *
 * Subdivides a >= 100k-hex grid with MLCA and a >= 100k-tet Kuhn grid with tet/oct
 * one level each and prints fine cells per second (target >= 1e6 on one core)
 * and peak resident memory per fine cell (target < 300 bytes).  Each case runs in
 * a fresh process (this program re-executes itself) so that the peak belongs to
 * that case alone; the peak covers the whole process: coarse mesh, fine mesh and
 * all scratch.  Run: build/tests/bench/bench_subdivide [--repeat N]. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>

#include "ss_scheme.h"
#include "ss_testmesh.h"

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* N^3 hexes of a jittered grid (not periodic: a real mesh with a boundary). */
static ss_cx *hex_grid(int N) {
  ss_cx *cx = NULL;
  ss_error err = {0};
  const int M = N + 1;
  ss_cx_new(3, &cx, &err);
  ss_cx_reserve_vertices(cx, (size_t)M * M * M, &err);
  ss_cx_reserve_cells(cx, SS_HEX, (size_t)N * N * N, &err);
  for (int v = 0; v < M * M * M; v++) {
    double x[3] = {(double)(v % M), (double)((v / M) % M), (double)(v / (M * M))};
    ss_cx_add_vertex(cx, x, 0, &err);
  }
  for (int c = 0; c < N * N * N; c++) {
    int i = c % N, j = (c / N) % N, k = c / (N * N);
    ss_idx h[8];
    for (int q = 0; q < 8; q++) {
      unsigned b = ss_cube_corner_bits(3, q);
      h[q] = (ss_idx)((i + (int)(b & 1u)) + M * (j + (int)((b >> 1) & 1u)) +
                      M * M * (k + (int)((b >> 2) & 1u)));
    }
    ss_cx_add_cell(cx, SS_HEX, h, 0, &err);
  }
  tm_jitter(cx, 0.2, 1);
  return cx;
}

/* Child: build the mesh, refine once `repeat` times, report on stdout. */
static int run_case(const char *which, int repeat) {
  gsl_set_error_handler_off();
  int hex = !strcmp(which, "mlca");
  ss_cx *cx = hex ? hex_grid(47) : tm_kuhn(26);
  if (!hex) tm_jitter(cx, 0.1, 2);
  ss_error err = {0};
  ss_scheme *s = NULL;
  if (ss_scheme_new(which, &s, &err)) return 1;
  double best = 1e300;
  size_t fine_cells = 0;
  for (int r = 0; r < repeat; r++) {
    ss_cx *f = NULL;
    double t0 = now();
    if (ss_scheme_refine(s, cx, &f, NULL, &err)) {
      fprintf(stderr, "%s\n", err.msg);
      return 1;
    }
    double dt = now() - t0;
    if (dt < best) best = dt;
    fine_cells = ss_cx_ncells(f);
    ss_cx_free(f);
  }
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  double peak = (double)ru.ru_maxrss * 1024.0;
  printf("%-7s %8zu coarse %-10s -> %8zu fine cells   %6.3f s   %7.2f M cells/s"
         "   peak %7.1f MB = %6.1f B/fine cell\n",
         which, ss_cx_ncells(cx), hex ? "hexahedra" : "tetrahedra", fine_cells, best,
         (double)fine_cells / best / 1e6, peak / 1e6, peak / (double)fine_cells);
  ss_cx_free(cx);
  ss_scheme_free(s);
  return 0;
}

int main(int argc, char **argv) {
  int repeat = 3;
  if (argc >= 3 && !strcmp(argv[1], "--case"))
    return run_case(argv[2], argc >= 4 ? atoi(argv[3]) : repeat);
  if (argc >= 3 && !strcmp(argv[1], "--repeat")) repeat = atoi(argv[2]);
  printf("one level of subdivision, one core, best of %d; targets: >= 1 M fine cells/s, "
         "< 300 B peak memory per fine cell\n",
         repeat);
  fflush(stdout);
  const char *cases[] = {"mlca", "tetoct"};
  int rc = 0;
  for (int i = 0; i < 2; i++) {
    pid_t pid = fork();
    if (pid == 0) {
      char rep[16];
      snprintf(rep, sizeof rep, "%d", repeat);
      execl("/proc/self/exe", argv[0], "--case", cases[i], rep, (char *)NULL);
      _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status)) rc = 1;
  }
  return rc;
}
