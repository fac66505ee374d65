/* test_draw.c — pictures of characteristic maps: PNG of the requested size
 * whose warning colour appears exactly when a cell is not regular, SVG, VTK
 * whose cells and per-cell data match the map, and the errors for an unknown
 * format and an unwritable file. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cairo.h>

#include "ss_report_draw.h"
#include "ss_test.h"
#include "ss_testcase.h"

/* Pixels that are clearly the warning red: strong red, weak green and blue. */
static long red_pixels(const char *png, int *w, int *h) {
  cairo_surface_t *s = cairo_image_surface_create_from_png(png);
  if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(s);
    return -1;
  }
  *w = cairo_image_surface_get_width(s);
  *h = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char *d = cairo_image_surface_get_data(s);
  long n = 0;
  for (int y = 0; y < *h; y++)
    for (int x = 0; x < *w; x++) {
      const uint32_t p = *(const uint32_t *)(d + y * stride + 4 * x);
      const int R = (int)((p >> 16) & 255), G = (int)((p >> 8) & 255), B = (int)(p & 255);
      n += R > 180 && G < 90 && B < 90;
    }
  cairo_surface_destroy(s);
  return n;
}

static char *path(const char *dir, const char *name) {
  static char buf[4][512];
  static int k;
  char *p = buf[k++ % 4];
  snprintf(p, 512, "%s/%s", dir, name);
  return p;
}

static void test_png_svg(const char *dir) {
  ss_link *oct = NULL;
  ss_error err = {0};
  ss_testcase r;
  if (ss_link_parse("tetrahedron", &oct, &err) ||
      ss_testcase_run("mlca", (ss_case){SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS}, &r)) {
    ss_link_free(oct);
    return;
  }
  ss_report_draw_opts o = ss_report_draw_defaults();
  o.width = 640, o.height = 360, o.caption = "mlca, vertex tetrahedron";
  const char *png = path(dir, "a.png");
  CHECK(ss_report_draw(r.cm, &r.r, &o, png, &err) == SS_OK, "png: %s", err.msg);
  int w = 0, h = 0;
  long red = red_pixels(png, &w, &h);
  CHECK(w == 640 && h == 360, "png size %dx%d", w, h);
  CHECK(red == 0, "a regular map has %ld warning pixels", red);
  /* fold it over the plane z3 = 0: the lower half of the ring inverts */
  for (size_t i = 0; i < r.cm->n; i++)
    r.cm->x[3 * i + 2] = fabs(r.cm->x[3 * i + 2]);
  ss_regularity reg;
  const ss_charmap_opts co = ss_charmap_defaults();
  REQUIRE_OK_VOID(ss_charmap_regularity(r.cm, r.M, &co, &reg, &err), &err);
  CHECK(reg.verdict.verdict == SS_FAIL, "folded map: %s", reg.verdict.reason);
  CHECK(ss_report_draw(r.cm, &reg, &o, png, &err) == SS_OK, "png: %s", err.msg);
  red = red_pixels(png, &w, &h);
  CHECK(red > 200, "a folded map shows only %ld warning pixels", red);
  const char *svg = path(dir, "a.svg");
  CHECK(ss_report_draw(r.cm, &reg, &o, svg, &err) == SS_OK, "svg: %s", err.msg);
  FILE *f = fopen(svg, "r");
  char head[256] = {0};
  if (f) {
    size_t got = fread(head, 1, sizeof head - 1, f);
    head[got] = '\0';
    fclose(f);
  }
  CHECK(strstr(head, "<svg") != NULL, "svg header: %.60s", head);
  CHECK(ss_report_draw(r.cm, &reg, &o, path(dir, "a.jpg"), &err) == SS_EINPUT,
        "unknown format");
  CHECK(ss_report_draw(r.cm, &reg, &o, "/nonexistent/dir/x.png", &err) == SS_EIO,
        "unwritable png: %s", err.msg);
  CHECK(ss_report_draw(r.cm, &reg, &o, "/nonexistent/dir/x.vtk", &err) == SS_EIO,
        "unwritable vtk: %s", err.msg);
  o.width = 10;
  CHECK(ss_report_draw(r.cm, &reg, &o, png, &err) == SS_EINPUT, "tiny picture");
  unlink(png), unlink(svg);
  ss_testcase_free(&r);
  ss_link_free(oct);
  /* a surface case draws too */
  if (!ss_testcase_run("loop", (ss_case){SS_CASE_SURFACE_VERTEX, NULL, 5, SS_DIAG_BFS},
                       &r)) {
    o = ss_report_draw_defaults();
    CHECK(ss_report_draw(r.cm, &r.r, &o, png, &err) == SS_OK, "surface png: %s", err.msg);
    red = red_pixels(png, &w, &h);
    CHECK(red == 0 && w == 1200, "surface png: %ld warning pixels, width %d", red, w);
    unlink(png);
    ss_testcase_free(&r);
  }
}

/* VTK: the counts (two-ring and deciding ring level) and the per-cell
 * signs, in the map's orientation, read back. */
static void test_vtk(const char *dir) {
  ss_testcase r;
  if (ss_testcase_run("tetoct", (ss_case){SS_CASE_EDGE, NULL, 4, SS_DIAG_BFS}, &r))
    return;
  ss_error err = {0};
  ss_report_draw_opts o = ss_report_draw_defaults();
  const char *vtk = path(dir, "a.vtk");
  CHECK(ss_report_draw(r.cm, &r.r, &o, vtk, &err) == SS_OK, "vtk: %s", err.msg);
  size_t ntet = 0, noct = 0;
  for (size_t c = 0; c < r.cm->ncells; c++)
    ntet += r.cm->ctype[c] == SS_TET, noct += r.cm->ctype[c] == SS_OCT;
  CHECK(ntet > 0 && noct > 0, "tet/oct edge: %zu tets, %zu octahedra", ntet, noct);
  CHECK(r.cm->ring_x && r.cm->ring_ncells > 0 && r.cm->ring_level == r.r.ring_level,
        "the map keeps its deciding ring level %d (%d)", r.cm->ring_level,
        r.r.ring_level);
  for (size_t c = 0; c < r.cm->ring_ncells; c++)
    ntet += r.cm->ring_ctype[c] == SS_TET, noct += r.cm->ring_ctype[c] == SS_OCT;
  FILE *f = fopen(vtk, "r");
  char line[256];
  size_t npts = 0, ncells = 0, ntypes = 0, t10 = 0, t14 = 0, signs = 0, ones = 0;
  int section = 0;
  while (f && fgets(line, sizeof line, f)) {
    if (sscanf(line, "POINTS %zu", &npts) == 1) continue;
    if (sscanf(line, "CELLS %zu", &ncells) == 1) continue;
    if (sscanf(line, "CELL_TYPES %zu", &ntypes) == 1) {
      section = 1;
      continue;
    }
    if (!strncmp(line, "CELL_DATA", 9)) section = 0;
    if (!strncmp(line, "SCALARS jacobian_sign", 21)) {
      section = 2;
      continue;
    }
    if (!strncmp(line, "SCALARS min_scaled", 18)) section = 0;
    if (!strncmp(line, "LOOKUP_TABLE", 12)) continue;
    int v;
    if (section == 1 && sscanf(line, "%d", &v) == 1) t10 += v == 10, t14 += v == 14;
    if (section == 2 && sscanf(line, "%d", &v) == 1) signs++, ones += v == 1;
  }
  if (f) fclose(f);
  CHECK(npts == r.cm->n + r.cm->ring_n, "vtk points %zu, expected %zu + %zu", npts,
        r.cm->n, r.cm->ring_n);
  CHECK(ncells == ntet + 2 * noct && ntypes == ncells, "vtk cells %zu types %zu", ncells,
        ntypes);
  CHECK(t10 == ntet && t14 == 2 * noct, "vtk: %zu tets, %zu pyramids", t10, t14);
  CHECK(r.r.verdict.verdict == SS_PASS && signs == ncells && ones == ncells,
        "vtk signs: %zu of %zu of the map's orientation (+1)", ones, signs);
  unlink(vtk);
  ss_testcase_free(&r);
}

int main(void) {
  char dir[] = "/tmp/ss_test_draw_XXXXXX";
  if (!mkdtemp(dir)) {
    perror("mkdtemp");
    return 1;
  }
  test_png_svg(dir);
  test_vtk(dir);
  rmdir(dir);
  return ss_test_done("draw");
}
