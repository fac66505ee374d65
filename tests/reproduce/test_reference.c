/* test_reference.c — reference files of quoted values (ss_report_ref.h):
 * malformed lines are rejected with a message naming file and line, the
 * shipped files load, and the match rule (half a unit in the last quoted
 * digit; exact values; bounds; formulas in k) on small examples.
 * Usage: test_reference SRCDIR */
#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ss_report_ref.h"

static int failures = 0;

#define CHECK(cond, ...)                                                                 \
  do {                                                                                   \
    if (!(cond)) {                                                                       \
      failures++;                                                                        \
      fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);           \
      fprintf(stderr, __VA_ARGS__);                                                      \
      fputc('\n', stderr);                                                               \
    }                                                                                    \
  } while (0)

static const char good[] =
    "paper.txt\tsection 1\tmlca\tvertex\t4..8\t-\tverdict\tpass\tall pass\tread so\n";

/* Write text (a comment line, then good, then body) to a temporary file and
 * load it; returns the status and leaves the message in err. */
static ss_status load_text(const char *body, char *path, size_t n, ss_error *err,
                           size_t *rows) {
  snprintf(path, n, "/tmp/ss_test_refXXXXXX");
  int fd = mkstemp(path);
  if (fd < 0) return SS_EIO;
  FILE *f = fdopen(fd, "w");
  fprintf(f, "# header\n\n%s%s", good, body);
  fclose(f);
  ss_ref ref = {0};
  memset(err, 0, sizeof *err);
  ss_status st = ss_report_ref_load(path, &ref, err);
  *rows = ref.n;
  ss_report_ref_free(&ref);
  unlink(path);
  return st;
}

/* A malformed third line must be rejected as input, naming PATH:4 and want. */
static void bad(const char *body, const char *want) {
  char path[64], where[80];
  ss_error err;
  size_t rows;
  ss_status st = load_text(body, path, sizeof path, &err, &rows);
  snprintf(where, sizeof where, "%s:4:", path);
  CHECK(st == SS_EINPUT, "status %d for %s", (int)st, body);
  CHECK(strstr(err.msg, where) != NULL, "message '%s' does not name %s", err.msg, where);
  CHECK(strstr(err.msg, want) != NULL, "message '%s' does not say '%s'", err.msg, want);
}

static void malformed(void) {
  char path[64];
  ss_error err;
  size_t rows;
  CHECK(load_text("", path, sizeof path, &err, &rows) == SS_OK && rows == 1, "%s",
        err.msg);
  CHECK(load_text("p.txt\ts 2\ttetoct\tface\t-\t-\tlambda1\t1/2\tq\t\n", path,
                  sizeof path, &err, &rows) == SS_OK &&
            rows == 2,
        "empty note allowed: %s", err.msg);
  bad("p.txt\ts\tmlca\tvertex\t4..8\t-\tverdict\tpass\tq\n", "9 tab-separated fields");
  bad("p.txt\ts\tmlca\tvertex\t4..8\t-\tverdict\tpass\tq\tn\textra\n",
      "11 tab-separated fields");
  bad("p.txt\ts\tmlca\tcorner\t4..8\t-\tverdict\tpass\tq\tn\n", "case 'corner'");
  bad("p.txt\ts\tmlca\tvertex\t8..4\t-\tverdict\tpass\tq\tn\n", "range '8..4'");
  bad("p.txt\ts\tmlca\tvertex\t2\t-\tverdict\tpass\tq\tn\n", "range '2'");
  bad("p.txt\ts\tmlca\tvertex\t8:\t-\tverdict\tpass\tq\tn\n", "range '8:'");
  bad("p.txt\ts\tmlca\tvertex\t8(a)\t-\tverdict\tpass\tq\tn\n", "range '8(a)'");
  bad("p.txt\ts\tmlca\tvertex\t4..\t-\tverdict\tpass\tq\tn\n", "range '4..'");
  bad("p.txt\ts\tmlca\tface\t4\t-\tverdict\tpass\tq\tn\n", "a face case takes '-'");
  bad("p.txt\ts\tmlca\tvertex\t4\tdiagonal\tverdict\tpass\tq\tn\n",
      "diagonals 'diagonal'");
  bad("p.txt\ts\tmlca\tvertex\t4\t-\tlambda0\t1\tq\tn\n", "quantity 'lambda0'");
  bad("p.txt\ts\tmlca\tvertex\t4\t-\tlambda16\t1\tq\tn\n", "quantity 'lambda16'");
  bad("p.txt\ts\tmlca\tvertex\t4\t-\tlambda1\t0.5.1\tq\tn\n", "value '0.5.1'");
  bad("p.txt\ts\tmlca\tvertex\t4\t-\tlambda1\t1/0\tq\tn\n", "value '1/0'");
  bad("p.txt\ts\tmlca\tvertex\t4\t-\ttwo_ring\t5k-\tq\tn\n", "value '5k-'");
  bad("p.txt\ts\tmlca\tvertex\t4\t-\tlambda1\tpass\tq\tn\n", "takes a number");
  bad("p.txt\ts\tmlca\tvertex\t4\t-\tregularity\t0.5\tq\tn\n", "takes pass, fail");
  bad("p.txt\ts\tmlca\tvertex\t4\t-\tverdict\tpass\t\tn\n", "field 9 (quote) is empty");
  bad("\ts\tmlca\tvertex\t4\t-\tverdict\tpass\tq\tn\n", "field 1 (paper) is empty");
  bad("p.txt\ts\tMLCA\tvertex\t4\t-\tverdict\tpass\tq\tn\n", "scheme 'MLCA'");
  ss_ref ref = {0};
  memset(&err, 0, sizeof err);
  CHECK(ss_report_ref_load("/nonexistent/ref.tsv", &ref, &err) == SS_EIO &&
            strstr(err.msg, "/nonexistent/ref.tsv"),
        "missing file: %s", err.msg);
  ss_report_ref_free(&ref);
  ss_report_ref_free(NULL);
}

/* eval text for k and check whether computed value c matches. */
static int matches(const char *text, int k, double c) {
  ss_ref_value v;
  ss_error err = {0};
  if (ss_report_ref_eval(text, k, &v, &err)) {
    failures++;
    fprintf(stderr, "cannot evaluate '%s': %s\n", text, err.msg);
    return -1;
  }
  return ss_report_ref_match(&v, c);
}

static void match_rule(void) {
  /* half a unit in the last quoted digit */
  CHECK(matches("0.4101", 0, 0.410097050801) == 1, "0.4101 ~ 0.410097");
  CHECK(matches("0.4101", 0, 0.41015) == 1, "exactly half a unit matches");
  CHECK(matches("0.4101", 0, 0.41005) == 1, "exactly half a unit below matches");
  CHECK(matches("0.4101", 0, 0.4101501) == 0, "just over half a unit differs");
  CHECK(matches("0.4101", 0, 0.41004) == 0, "0.41004 is not 0.4101");
  CHECK(matches("0.41", 0, 0.415) == 1, "0.41 ~ 0.415");
  CHECK(matches("0.41", 0, 0.4151) == 0, "0.41 !~ 0.4151");
  CHECK(matches("0.410", 0, 0.4104) == 1, "a trailing zero is a digit");
  CHECK(matches("0.410", 0, 0.4106) == 0, "a trailing zero narrows the tolerance");
  CHECK(matches("-0.25", 0, -0.2549) == 1, "negative decimals");
  CHECK(matches("3", 0, 3.4) == 1 && matches("3", 0, 3.6) == 0, "integers: +-0.5");
  /* exact values */
  CHECK(matches("1/2", 0, 0.5 + 1e-12) == 1, "1/2 exact");
  CHECK(matches("1/2", 0, 0.5 + 1e-6) == 0, "1/2 is not 0.500001");
  CHECK(matches("1/4", 0, 0.25) == 1, "1/4");
  CHECK(matches("5k-5", 7, 30.0) == 1 && matches("5k-5", 7, 31.0) == 0, "5k-5 at 7");
  CHECK(matches("k+1", 22, 23.0) == 1, "k+1 at 22");
  CHECK(matches("4n+3", 9, 39.0) == 1 && matches("2n+3", 9, 21.0) == 1, "formulas in n");
  /* bounds */
  CHECK(matches(">1/4", 0, 0.25) == 0, "a bound is strict");
  CHECK(matches(">1/4", 0, 0.2500001) == 1, "above the bound");
  CHECK(matches("1/2", 0, NAN) == 0, "NaN never matches");
  ss_ref_value v;
  ss_error err = {0};
  CHECK(ss_report_ref_eval("undecided", 0, &v, &err) == SS_OK &&
            v.kind == SS_REF_VERDICT && !strcmp(v.verdict, "undecided"),
        "verdict");
  CHECK(ss_report_ref_eval("0.4101", 0, &v, &err) == SS_OK && !v.exact &&
            fabs(v.tol - 5e-5) < 1e-18,
        "tolerance of 0.4101 is 5e-5, not %g", v.tol);
  const char *badv[] = {"0.", ".5", "1/0",  "5k-",  "k5", "abc",
                        "",   ">",  "1e-3", "1/2x", NULL};
  for (int i = 0; badv[i]; i++)
    CHECK(ss_report_ref_eval(badv[i], 4, &v, &err) == SS_EINPUT, "'%s' accepted",
          badv[i]);
  int index;
  CHECK(ss_report_ref_quantity("lambda15", &index) && index == 15, "lambda15");
  CHECK(ss_report_ref_quantity("mult1", &index) && index == 1, "mult1");
  CHECK(!ss_report_ref_quantity("lambda", &index), "lambda alone");
  CHECK(!ss_report_ref_quantity("lambda01", &index), "lambda01");
  CHECK(ss_report_ref_quantity("jsr_rho9", &index) && index == 9, "jsr_rho9");
  CHECK(!ss_report_ref_quantity("jsr_rho", &index), "jsr_rho alone");
  CHECK(ss_report_ref_quantity("links", &index) && index == 0, "links");
}

/* A label after the range binds a row to the case a table labels so: it
 * speaks of that case only, an unlabelled row of every case. */
static void labels(void) {
  char path[64] = "/tmp/ss_test_refXXXXXX";
  int fd = mkstemp(path);
  CHECK(fd >= 0, "temporary file");
  if (fd < 0) return;
  FILE *f = fdopen(fd, "w");
  fprintf(f, "%s",
          "p\ts\tboxspline\tvertex\t8:8(a)\t-\tlambda1\t0.480205\tq\tn\n"
          "p\ts\tboxspline\tvertex\t4..10:x\t-\tlambda1\t1/2\tq\tn\n"
          "p\ts\tboxspline\tvertex\t8\t-\tlambda1\t0.375\tq\tn\n");
  fclose(f);
  ss_ref ref = {0};
  ss_error err = {0};
  CHECK(ss_report_ref_load(path, &ref, &err) == SS_OK && ref.n == 3, "%s", err.msg);
  unlink(path);
  if (ref.n == 3) {
    const ss_ref_row *a = ref.row, *x = ref.row + 1, *plain = ref.row + 2;
    CHECK(a->lo == 8 && a->hi == 8 && a->label && !strcmp(a->label, "8(a)"), "8:8(a)");
    CHECK(x->lo == 4 && x->hi == 10 && x->label && !strcmp(x->label, "x"), "4..10:x");
    CHECK(!plain->label, "no label");
    const ss_case_kind V = SS_CASE_VERTEX;
    CHECK(ss_report_ref_applies_label(a, "boxspline", V, 8, "bfs", "8(a)"), "own label");
    CHECK(!ss_report_ref_applies_label(a, "boxspline", V, 8, "bfs", "8(b)"),
          "other label");
    CHECK(!ss_report_ref_applies_label(a, "boxspline", V, 8, "bfs", NULL), "no label");
    CHECK(!ss_report_ref_applies(a, "boxspline", V, 8, "bfs"), "unlabelled case");
    CHECK(!ss_report_ref_applies_label(a, "boxspline", V, 9, "bfs", "8(a)"), "k = 9");
    CHECK(ss_report_ref_applies_label(x, "boxspline", V, 10, NULL, "x"),
          "range and label");
    CHECK(ss_report_ref_applies_label(plain, "boxspline", V, 8, "bfs", "8(b)") &&
              ss_report_ref_applies(plain, "boxspline", V, 8, "bfs"),
          "an unlabelled row speaks of every case");
  }
  ss_report_ref_free(&ref);
}

/* The shipped reference files load, and rows apply as their ranges say. */
static void shipped(const char *src) {
  char pat[1024];
  snprintf(pat, sizeof pat, "%s/data/reference/*.tsv", src);
  glob_t g;
  CHECK(glob(pat, 0, NULL, &g) == 0 && g.gl_pathc >= 3, "reference files under %s", pat);
  ss_ref ref = {0};
  for (size_t i = 0; i < g.gl_pathc; i++) {
    ss_error err = {0};
    CHECK(ss_report_ref_load(g.gl_pathv[i], &ref, &err) == SS_OK, "%s", err.msg);
  }
  globfree(&g);
  CHECK(ref.n >= 30, "only %zu reference rows", ref.n);
  size_t mlca8 = 0;
  for (size_t i = 0; i < ref.n; i++)
    mlca8 += ss_report_ref_applies(ref.row + i, "mlca", SS_CASE_VERTEX, 8, NULL);
  CHECK(mlca8 == 2, "%zu rows for an MLCA vertex with k = 8 (want 2)", mlca8);
  size_t center9 = 0, skew9 = 0;
  for (size_t i = 0; i < ref.n; i++) {
    center9 += ss_report_ref_applies(ref.row + i, "boxspline", SS_CASE_EDGE, 9, "center");
    skew9 += ss_report_ref_applies(ref.row + i, "boxspline", SS_CASE_EDGE, 9, "skew");
  }
  CHECK(center9 == skew9 + 1, "center 9: %zu rows, skew 9: %zu", center9, skew9);
  ss_report_ref_free(&ref);
}

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: test_reference SRCDIR\n");
    return 2;
  }
  malformed();
  match_rule();
  labels();
  shipped(argv[1]);
  if (failures) fprintf(stderr, "%d checks failed\n", failures);
  return failures ? 1 : 0;
}
