/* test_draw.c — pictures of characteristic maps: PNG of the requested size
 * whose warning colour appears exactly when a cell is not regular, SVG, VTK
 * whose cells and per-cell data match the map, and the errors for an unknown
 * format and an unwritable file. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cairo.h>

#include "ss_report_draw.h"
#include "ss_test.h"
#include "ss_testcase.h"

/* Whether the n bytes at b hold the string w. */
static int has(const char *b, size_t n, const char *w) {
  const size_t m = strlen(w);
  for (size_t i = 0; i + m <= n; i++)
    if (!memcmp(b + i, w, m)) return 1;
  return 0;
}

/* Pixels that are clearly the warning red: strong red, weak green and blue;
 * above the legend (in the drawing) or, legend != 0, in the legend's row
 * (its red swatch: 24 px above the caption's 70, from the bottom). */
static long red_in(const char *png, int *w, int *h, int legend) {
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
  const int y0 = legend ? *h - 94 : 0, y1 = legend ? *h - 70 : *h - 94;
  for (int y = y0; y < y1; y++)
    for (int x = 0; x < *w; x++) {
      const uint32_t p = *(const uint32_t *)(d + y * stride + 4 * x);
      const int R = (int)((p >> 16) & 255), G = (int)((p >> 8) & 255), B = (int)(p & 255);
      n += R > 180 && G < 90 && B < 90;
    }
  cairo_surface_destroy(s);
  return n;
}

static long red_pixels(const char *png, int *w, int *h) {
  return red_in(png, w, h, 0);
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
      ss_testcase_run("mlca", (ss_case){SS_CASE_VERTEX, oct, 0, SS_DIAG_BFS, 0}, &r)) {
    ss_link_free(oct);
    return;
  }
  ss_report_draw_opts o = ss_report_draw_defaults();
  o.width = 640, o.height = 360, o.caption = "mlca, vertex tetrahedron";
  const char *png = path(dir, "a.png");
  CHECK(ss_report_draw(r.cm, &r.r, &o, png, &err) == SS_OK, "png: %s", err.msg);
  int w = 0, h = 0;
  long red = red_pixels(png, &w, &h);
  CHECK(red_in(png, &w, &h, 1) > 50, "no red swatch in the legend");
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
  /* SVG: text as text (<text> elements, no glyph outlines) */
  f = fopen(svg, "r");
  static char doc[1 << 21];
  size_t nd = f ? fread(doc, 1, sizeof doc - 1, f) : 0;
  if (f) fclose(f);
  doc[nd] = '\0';
  CHECK(strstr(doc, ">regular cell</text>") &&
            strstr(doc, ">mlca, vertex tetrahedron</text>") && !strstr(doc, "glyph") &&
            strstr(doc, "</text>\n</svg>"),
        "svg: the legend and caption as <text>, no glyph outlines");
  CHECK(ss_report_draw(r.cm, &reg, &o, path(dir, "a.jpg"), &err) == SS_EINPUT,
        "unknown format");
  CHECK(ss_report_draw(r.cm, &reg, &o, "/nonexistent/dir/x.png", &err) == SS_EIO,
        "unwritable png: %s", err.msg);
  CHECK(ss_report_draw(r.cm, &reg, &o, "/nonexistent/dir/x.vtk", &err) == SS_EIO,
        "unwritable vtk: %s", err.msg);
  o.width = 10;
  CHECK(ss_report_draw(r.cm, &reg, &o, png, &err) == SS_EINPUT, "tiny picture");
  /* PDF: text as text (a font resource, cairo's embedded subset) */
  o.width = 640;
  const char *pdf = path(dir, "a.pdf");
  CHECK(ss_report_draw(r.cm, &reg, &o, pdf, &err) == SS_OK, "pdf: %s", err.msg);
  f = fopen(pdf, "rb");
  static char body[1 << 20];
  size_t nb = f ? fread(body, 1, sizeof body - 1, f) : 0;
  if (f) fclose(f);
  body[nb] = '\0';
  CHECK(nb > 1000 && !memcmp(body, "%PDF-", 5), "pdf header");
  CHECK(has(body, nb, "/Font") && has(body, nb, "/ToUnicode"),
        "pdf: no font with a ToUnicode map (text drawn as outlines?)");
  unlink(png), unlink(svg), unlink(pdf);
  ss_testcase_free(&r);
  ss_link_free(oct);
  /* a surface case draws too */
  if (!ss_testcase_run("loop", (ss_case){SS_CASE_SURFACE_VERTEX, NULL, 5, SS_DIAG_BFS, 0},
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
  if (ss_testcase_run("tetoct", (ss_case){SS_CASE_EDGE, NULL, 4, SS_DIAG_BFS, 0}, &r))
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

/* The picture's frame does not depend on the basis: the net turned by an
 * orthogonal Q (rotation, then a reflection) gives the same coordinates (the
 * reflection: up to the sign of z3); psi(p) is the origin and e1 points to
 * the first point away from it. */
static void test_frame(void) {
  const char *sch[] = {"mlca", "tetoct", "loop"};
  const ss_case cs[] = {{SS_CASE_EDGE, NULL, 4, SS_DIAG_BFS, 0},
                        {SS_CASE_FACE, NULL, 0, SS_DIAG_BFS, 0},
                        {SS_CASE_SURFACE_VERTEX, NULL, 6, SS_DIAG_BFS, 0}};
  for (int t = 0; t < 3; t++) {
    ss_testcase r;
    if (ss_testcase_run(sch[t], cs[t], &r)) continue;
    const ss_charmap *cm = r.cm;
    const int d = cm->dim;
    const size_t N = cm->n * (size_t)d;
    double *a = malloc(N * sizeof *a), *b = malloc(N * sizeof *b),
           *q = malloc(N * sizeof *q);
    if (!a || !b || !q) {
      CHECK(0, "out of memory");
      free(a), free(b), free(q);
      ss_testcase_free(&r);
      return;
    }
    ss_report_draw_frame(cm, a);
    /* rotations about two axes by 0.7 and 1.9 radians, then z1 mirrored */
    const double c1 = cos(0.7), s1 = sin(0.7), c2 = cos(1.9), s2 = sin(1.9);
    const double R3[9] = {c1, -s1 * c2, s1 * s2, s1, c1 * c2, -c1 * s2, 0, s2, c2};
    const double R2[4] = {c1, -s1, s1, c1};
    const double *R = d == 3 ? R3 : R2;
    for (int mirror = 0; mirror < 2; mirror++) {
      ss_charmap turned = *cm;
      for (size_t i = 0; i < cm->n; i++)
        for (int k = 0; k < d; k++) {
          double v = 0.0;
          for (int j = 0; j < d; j++)
            v += R[k * d + j] * cm->x[i * (size_t)d + (size_t)j];
          q[i * (size_t)d + (size_t)k] = mirror && k == 0 ? -v : v;
        }
      for (int k = 0; k < d; k++) {
        double v = 0.0;
        for (int j = 0; j < d; j++)
          v += R[k * d + j] * cm->centre[j];
        turned.centre[k] = mirror && k == 0 ? -v : v;
      }
      turned.x = q;
      ss_report_draw_frame(&turned, b);
      double worst = 0.0, size = 0.0;
      for (size_t i = 0; i < cm->n; i++)
        for (int k = 0; k < d; k++) {
          const double s = mirror && (k == 2 || (d == 2 && k == 1)) ? -1.0 : 1.0;
          worst = fmax(worst, fabs(b[i * (size_t)d + (size_t)k] -
                                   s * a[i * (size_t)d + (size_t)k]));
          size = fmax(size, fabs(a[i * (size_t)d + (size_t)k]));
        }
      CHECK(worst <= 1e-12 * size, "%s %s: the frame moves by %.3g of %.3g (mirror %d)",
            sch[t], ss_case_name(cs[t].kind), worst, size, mirror);
    }
    /* e1 points to the first point away from psi(p) */
    size_t i = 0;
    while (i < cm->n && fabs(a[i * (size_t)d]) + fabs(a[i * (size_t)d + 1]) == 0.0)
      i++;
    CHECK(i < cm->n && a[i * (size_t)d] > 0 && a[i * (size_t)d + 1] == 0.0 &&
              (d == 2 || a[i * (size_t)d + 2] == 0.0),
          "%s: e1 along point %zu", sch[t], i);
    free(a), free(b), free(q);
    ss_testcase_free(&r);
  }
}

int main(void) {
  char dir[] = "/tmp/ss_test_draw_XXXXXX";
  if (!mkdtemp(dir)) {
    perror("mkdtemp");
    return 1;
  }
  test_png_svg(dir);
  test_vtk(dir);
  test_frame();
  rmdir(dir);
  return ss_test_done("draw");
}
