/* test_stencil.c — stencil files (DESIGN section 3): the shipped mlca.ini and
 * tetoct.ini give operators identical, entry for entry, to the built-in
 * schemes on a hex star, a tet star with creases and a periodic grid; and
 * every kind of bad file is refused with SS_EINPUT and a message naming the
 * file, the line and the key or section. */
#include <stdlib.h>
#include <string.h>

#include "ss_stencil.h"
#include "ss_test.h"
#include "ss_testmesh.h"
#include "stencil_case.h"

static const char *dir; /* data/stencils */

static ss_scheme *load(const char *file) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", dir, file);
  ss_scheme *s = NULL;
  ss_error err = {0};
  uint64_t id = 0;
  CHECK(ss_stencil_load(path, &s, &id, &err) == SS_OK && id != 0, "%s: %s", path,
        err.msg);
  return s;
}

static void test_shipped(void) {
  ss_error err = {0};
  ss_scheme *mlca = NULL, *tetoct = NULL;
  ss_scheme_new("mlca", &mlca, &err);
  ss_scheme_new("tetoct", &tetoct, &err);
  ss_scheme *sm = load("mlca.ini"), *st = load("tetoct.ini"),
            *ns = load("no-smoothing.ini");
  if (!sm || !st || !ns) goto out;
  CHECK(!strcmp(ss_scheme_name(sm), "mlca-stencil") &&
            ss_scheme_split_kind(sm) == SS_SPLIT_MULTILINEAR &&
            ss_scheme_split_kind(st) == SS_SPLIT_TETOCT,
        "names and splits");
  tm_link *l = tm_link_named("bipyramid:5");
  ss_cx *hs = tm_hex_star(l), *ts = tm_tet_star(l), *grid = tm_torus(3, 4);
  tm_jitter(hs, 0.1, 3);
  tm_jitter(ts, 0.1, 4);
  same_operator(mlca, sm, hs, "mlca, hex star");
  same_operator(mlca, sm, grid, "mlca, periodic grid");
  same_operator(tetoct, st, ts, "tetoct, tet star");
  /* the no-smoothing stencil: every fine vertex where the split put it */
  ss_cx *f = NULL;
  gsl_spmatrix *R = NULL;
  if (!ss_scheme_refine(ns, grid, &f, &R, &err)) {
    int ok = 1;
    for (size_t r = 0; r < R->size1; r++) {
      const int m = R->p[r + 1] - R->p[r];
      for (int q = R->p[r]; q < R->p[r + 1]; q++)
        ok &= R->data[q] == 1.0 / m; /* a split point: the mean of its parents */
    }
    CHECK(ok, "no-smoothing: rows are not the split's means");
    gsl_spmatrix_free(R);
    ss_cx_free(f);
  }
  ss_cx_free(hs);
  ss_cx_free(ts);
  ss_cx_free(grid);
  tm_link_free(l);
out:
  ss_scheme_free(sm);
  ss_scheme_free(st);
  ss_scheme_free(ns);
  ss_scheme_free(mlca);
  ss_scheme_free(tetoct);
}

#define HEAD "[scheme]\nname = x\nfamily = averaging\nsplit = multilinear\n"

static void test_bad(void) {
  bad(HEAD "[mask.hex]\nself = 1/8\nedge = 1/8\nface = 1/8\nopposite = 1/7\n",
      "bad.ini:5: [mask.hex]: the weights sum to 57/56 over the 8 vertices");
  bad(HEAD "[mask.hex]\nself = 1/8\nedge = 1/8\nface = 1/8\ncorner = 1/8\n",
      "bad.ini:9: [mask.hex]: role 'corner' is unknown (known: self, edge, face, "
      "opposite)");
  bad(HEAD "[mask.hex]\nself = 1/8\nedge = 1/x\n", "bad.ini:7: [mask.hex] edge = '1/x'");
  bad(HEAD "[mask.hex]\nself = 1/0\nedge = 0\nface = 0\nopposite = 0\n",
      "bad.ini:6: [mask.hex] self = '1/0'");
  bad(HEAD "[mask.hex]\nself = 0.125\n", "bad.ini:6: [mask.hex] self = '0.125'");
  /* beyond 64 bits: said so, not "not a rational"; leading zeros do not count */
  bad(HEAD "[mask.hex]\nself = 1/100000000000000000000\n",
      "bad.ini:6: [mask.hex] self = '1/100000000000000000000': a numerator or "
      "denominator has more than 17 digits");
  bad(HEAD "[mask.hex]\nself = 000000000000000000001/8\nedge = 1/8\nface = 1/8\n"
           "opposite = 1/7\n",
      "bad.ini:5: [mask.hex]: the weights sum to 57/56");
  bad(HEAD "[mask.hex]\nself = 1/8\nedge = 1/8\nface = 1/8\n",
      "bad.ini:5: [mask.hex] lacks the role 'opposite'");
  bad(HEAD "[mask.hex]\nself = 1/8\nself = 1/8\n",
      "bad.ini:7: [mask.hex] self is given twice");
  bad(HEAD "[mask.prism]\nself = 1\n",
      "bad.ini:6: [mask.prism]: unknown cell type 'prism'");
  bad(HEAD "[mask.tet]\nself = -1/16\nedge = 17/48\n",
      "bad.ini:5: [mask.tet]: split multilinear does not make tetrahedra");
  bad(HEAD, "bad.ini:1: no [mask.TYPE] section");
  bad("[mask.hex]\nself = 1/8\n",
      "[scheme] needs name, family and split (no [scheme] section)");
  bad("[scheme]\nname = x\nfamily = butterfly\n",
      "bad.ini:3: [scheme] family 'butterfly'");
  bad("[scheme]\nname = x\nsplit = sqrt3\n",
      "bad.ini:3: [scheme] split 'sqrt3' is unknown");
  bad("[scheme]\nname = x\nlevels = 3\n", "bad.ini:3: [scheme] key 'levels' is unknown");
  bad("[scheme]\nname = x\n[weights]\na = 1\n",
      "bad.ini:4: section [weights] is unknown");
  bad("[scheme]\nthis is no INI line\n", "bad.ini:2: not an INI line");
  bad("", "[scheme] needs name, family and split");
  /* two errors: the first one's line with the first one's message (the
   * message was the last error's, the line the first's) */
  bad(HEAD "[mask.hex]\nself = 1/x\nedge = 0\nface = 0\nopposite = 0\nfoo = 1\n",
      "bad.ini:6: [mask.hex] self = '1/x'");
  bad(HEAD "[mask.hex]\nfoo = 1\nedge = 0\nthis is no INI line\n",
      "bad.ini:6: [mask.hex]: role 'foo' is unknown");
  bad(HEAD "this is no INI line\n[mask.hex]\nfoo = 1\n", "bad.ini:5: not an INI line");
  /* a line longer than inih's buffer: named, and the lines after it keep
   * their numbers */
  {
    char text[2048];
    char longc[400];
    memset(longc, 'x', sizeof longc - 1);
    longc[sizeof longc - 1] = '\0';
    snprintf(text, sizeof text, HEAD "; %s\n[mask.hex]\nself = 1/8\nfoo = 1\n", longc);
    bad(text, "bad.ini:5: a line longer than 198 characters");
    snprintf(text, sizeof text, HEAD "[mask.hex]\nfoo = 1\n; %s\n", longc);
    bad(text, "bad.ini:6: [mask.hex]: role 'foo' is unknown");
  }
  /* the exact sum: 1/3 three times is 1, not 0.999... */
  ss_scheme *s = NULL;
  ss_error err = {0};
  CHECK(ss_stencil_parse("[scheme]\nname = t\nfamily = averaging\nsplit = tetoct\n"
                         "[mask.triangle]\nself = 1/3\nedge = 1/3\n",
                         "ok.ini", &s, &err) == SS_OK,
        "thirds: %s", err.msg);
  ss_scheme_free(s);
  CHECK(ss_stencil_load("/nonexistent/x.ini", &s, NULL, &err) == SS_EIO &&
            strstr(err.msg, "/nonexistent/x.ini"),
        "missing file: %s", err.msg);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_stencil DATA/stencils\n");
    return 1;
  }
  dir = argv[1];
  test_shipped();
  test_bad();
  return ss_test_done("stencil");
}
