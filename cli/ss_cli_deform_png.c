/* ss_cli_deform_png.c — `subspectra deform --format png`: the deformed
 * pattern drawn with cairo in a fixed oblique view (azimuth -60 degrees,
 * elevation 25 degrees, orthographic), over the moved control net's edges in
 * light grey.  Grid lines are coloured by their direction (x red, y green,
 * z blue); checker samples are drawn back to front as small squares, label 1
 * dark and label 0 light, so that the visible faces of the volume show the
 * checkerboard. */
#include <math.h>
#include <stdlib.h>

#include <cairo.h>

#include "ss_cli_deform.h"

#define IMG 900 /* picture size in pixels */

/* The fixed view: screen x, screen y (up) and depth (towards the viewer). */
static void project(const double p[3], double s[3]) {
  const double az = -60.0 * M_PI / 180.0, el = 25.0 * M_PI / 180.0;
  const double r[3] = {-sin(az), cos(az), 0.0};
  const double u[3] = {-sin(el) * cos(az), -sin(el) * sin(az), cos(el)};
  const double d[3] = {cos(el) * cos(az), cos(el) * sin(az), sin(el)};
  s[0] = r[0] * p[0] + r[1] * p[1] + r[2] * p[2];
  s[1] = u[0] * p[0] + u[1] * p[1] + u[2] * p[2];
  s[2] = d[0] * p[0] + d[1] * p[1] + d[2] * p[2];
}

/* The view box: projected extent of the points and the net. */
typedef struct {
  double lo[2], hi[2]; /* screen bounding box */
  double scale;        /* pixels per unit */
} view;

static void to_px(const view *v, const double p[3], double *x, double *y) {
  double s[3];
  project(p, s);
  *x = 40.0 + (s[0] - v->lo[0]) * v->scale;
  *y = IMG - 40.0 - (s[1] - v->lo[1]) * v->scale;
}

static void fit(const ss_deform_cli_out *o, view *v) {
  v->lo[0] = v->lo[1] = INFINITY;
  v->hi[0] = v->hi[1] = -INFINITY;
  double s[3];
  for (size_t i = 0; i < o->n + o->net->nv; i++) {
    const double *p = i < o->n ? o->pt[i].p : o->net->x + (i - o->n) * 3;
    if (i < o->n && o->pt[i].status != SS_DEFORM_CLI_OK) continue;
    project(p, s);
    for (int a = 0; a < 2; a++) {
      v->lo[a] = fmin(v->lo[a], s[a]);
      v->hi[a] = fmax(v->hi[a], s[a]);
    }
  }
  const double w = fmax(v->hi[0] - v->lo[0], v->hi[1] - v->lo[1]);
  v->scale = w > 0 ? (IMG - 80.0) / w : 1.0;
  /* centre the picture */
  for (int a = 0; a < 2; a++) {
    const double extra = (IMG - 80.0) / v->scale - (v->hi[a] - v->lo[a]);
    v->lo[a] -= extra / 2.0;
  }
}

/* The net's cell edges in light grey. */
static void draw_net(cairo_t *cr, const view *v, const ss_cx *net) {
  static const ss_cell_type kinds[3] = {SS_HEX, SS_TET, SS_OCT};
  cairo_set_source_rgba(cr, 0.55, 0.55, 0.55, 0.45);
  cairo_set_line_width(cr, 0.8);
  for (int ki = 0; ki < 3; ki++) {
    const ss_cell_type t = kinds[ki];
    for (size_t c = 0; c < net->nc[t]; c++) {
      const ss_idx *cv = ss_cx_cell(net, t, c);
      for (int e = 0; e < ss_cell_nedges(t); e++) {
        int a, b;
        double x, y;
        ss_cell_edge(t, e, &a, &b);
        to_px(v, net->x + (size_t)cv[a] * 3, &x, &y);
        cairo_move_to(cr, x, y);
        to_px(v, net->x + (size_t)cv[b] * 3, &x, &y);
        cairo_line_to(cr, x, y);
      }
    }
  }
  cairo_stroke(cr);
}

static void draw_lines(cairo_t *cr, const view *v, const ss_deform_cli_out *o) {
  long nlines = 0;
  for (size_t i = 0; i < o->n; i++)
    if (o->pt[i].line + 1 > nlines) nlines = o->pt[i].line + 1;
  static const double col[3][3] = {
      {0.80, 0.15, 0.10}, {0.10, 0.55, 0.15}, {0.10, 0.25, 0.80}};
  cairo_set_line_width(cr, 1.6);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (size_t a = 0; a < o->n;) {
    size_t b = a;
    while (b < o->n && o->pt[b].line == o->pt[a].line &&
           o->pt[b].status == SS_DEFORM_CLI_OK)
      b++;
    if (b - a >= 2) {
      const int dir = (int)(o->pt[a].line * 3 / (nlines ? nlines : 1));
      cairo_set_source_rgb(cr, col[dir][0], col[dir][1], col[dir][2]);
      for (size_t i = a; i < b; i++) {
        double x, y;
        to_px(v, o->pt[i].p, &x, &y);
        if (i == a)
          cairo_move_to(cr, x, y);
        else
          cairo_line_to(cr, x, y);
      }
      cairo_stroke(cr);
    }
    a = b > a ? b : a + 1;
  }
}

/* Depth of each evaluated point, for sorting back to front. */
typedef struct {
  double depth; /* towards the viewer */
  size_t i;     /* the point */
} by_depth;

static int cmp_depth(const void *a, const void *b) {
  const double x = ((const by_depth *)a)->depth, y = ((const by_depth *)b)->depth;
  return (x > y) - (x < y);
}

static int draw_checker(cairo_t *cr, const view *v, const ss_deform_cli_out *o) {
  by_depth *d = malloc((o->n + 1) * sizeof *d);
  if (!d) return -1;
  size_t m = 0;
  for (size_t i = 0; i < o->n; i++)
    if (o->pt[i].status == SS_DEFORM_CLI_OK) {
      double s[3];
      project(o->pt[i].p, s);
      d[m].depth = s[2];
      d[m++].i = i;
    }
  qsort(d, m, sizeof *d, cmp_depth);
  /* squares about the sample spacing: the cube root of the count per axis */
  const double side = (IMG - 80.0) / (cbrt((double)(m ? m : 1)) * 1.15);
  for (size_t k = 0; k < m; k++) {
    const ss_deform_cli_point *p = &o->pt[d[k].i];
    double x, y;
    to_px(v, p->p, &x, &y);
    if (p->label)
      cairo_set_source_rgb(cr, 0.12, 0.20, 0.45);
    else
      cairo_set_source_rgb(cr, 0.93, 0.80, 0.45);
    cairo_rectangle(cr, x - side / 2, y - side / 2, side, side);
    cairo_fill(cr);
  }
  free(d);
  return 0;
}

static cairo_status_t to_file(void *closure, const unsigned char *data,
                              unsigned int len) {
  return fwrite(data, 1, len, (FILE *)closure) == len ? CAIRO_STATUS_SUCCESS
                                                      : CAIRO_STATUS_WRITE_ERROR;
}

ss_status ss_cli_deform_write_png(FILE *f, const ss_deform_cli_out *o, ss_error *err) {
  cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, IMG, IMG);
  cairo_t *cr = cairo_create(sf);
  ss_status st = SS_OK;
  view v;
  fit(o, &v);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  draw_net(cr, &v, o->net);
  int checker = o->n && o->pt[0].label >= 0;
  if (checker && draw_checker(cr, &v, o)) st = ss_error_nomem(err, "picture");
  if (!checker) draw_lines(cr, &v, o);
  if (!st && cairo_status(cr) != CAIRO_STATUS_SUCCESS)
    st = ss_error_set(err, SS_ENOMEM, "cairo: %s",
                      cairo_status_to_string(cairo_status(cr)));
  cairo_destroy(cr);
  if (!st && cairo_surface_write_to_png_stream(sf, to_file, f) != CAIRO_STATUS_SUCCESS)
    st = ss_error_set(err, SS_EIO, "cannot write the PNG picture");
  cairo_surface_destroy(sf);
  return st;
}
