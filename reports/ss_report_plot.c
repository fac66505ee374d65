/* ss_report_plot.c — the figure of a store's cases against k
 * (ss_report_plot.h). */
#include "ss_report_plot.h"
#include "ss_report_draw.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cairo.h>

#define NLAMBDA 4 /* |lambda1|..|lambda4| in the top panel */

/* A colour. */
typedef struct {
  double r, g, b; /* components in [0, 1] */
} rgb;

/* One colour and marker per eigenvalue index (1..4), none of them the
 * warning red of the Jacobian panel. */
static const rgb index_colour[NLAMBDA] = {
    {0.12, 0.47, 0.71}, {0.93, 0.49, 0.05}, {0.17, 0.60, 0.17}, {0.55, 0.35, 0.72}};
static const rgb pass_colour = {0.15, 0.35, 0.75};
static const rgb fail_colour = {0.85, 0.05, 0.05};
static const rgb undecided_colour = {1.0, 0.55, 0.0};

/* A plot area and the data range it shows. */
typedef struct {
  double x0, y0, w, h; /* the area in device units (top-left corner, size) */
  double xmin, xmax;   /* data range along x (k) */
  double ymin, ymax;   /* data range along y */
  double ystep;        /* tick spacing along y */
} frame;

static double X(const frame *f, double x) {
  return f->x0 + (x - f->xmin) / (f->xmax - f->xmin) * f->w;
}

static double Y(const frame *f, double y) {
  return f->y0 + f->h - (y - f->ymin) / (f->ymax - f->ymin) * f->h;
}

/* 1, 2 or 5 times a power of ten, at least x. */
static double nice_step(double x) {
  const double p = pow(10.0, floor(log10(x)));
  const double m = x / p;
  return (m <= 1.0 ? 1.0 : m <= 2.0 ? 2.0 : m <= 5.0 ? 5.0 : 10.0) * p;
}

/* A range with round ends around [lo, hi] and about five ticks. */
static void nice_range(double lo, double hi, frame *f) {
  if (!isfinite(lo) || !isfinite(hi)) lo = 0.0, hi = 1.0;
  if (hi - lo < 1e-9 * (fabs(lo) + fabs(hi)) || hi == lo) {
    const double d = fabs(lo) > 0.0 ? 0.05 * fabs(lo) : 0.5;
    lo -= d;
    hi += d;
  }
  f->ystep = nice_step((hi - lo) / 5.0);
  f->ymin = floor(lo / f->ystep + 1e-9) * f->ystep;
  f->ymax = ceil(hi / f->ystep - 1e-9) * f->ystep;
}

static void set(cairo_t *cr, rgb c, double alpha) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

/* Marker path of shape s (0 circle, 1 square, 2 triangle, 3 diamond) of
 * radius r at (x, y). */
static void marker(cairo_t *cr, int s, double x, double y, double r) {
  cairo_new_sub_path(cr);
  switch (s) {
  case 0:
    cairo_arc(cr, x, y, r, 0.0, 2.0 * M_PI);
    break;
  case 1:
    cairo_rectangle(cr, x - 0.85 * r, y - 0.85 * r, 1.7 * r, 1.7 * r);
    break;
  case 2:
    cairo_move_to(cr, x, y - 1.15 * r);
    cairo_line_to(cr, x + r, y + 0.75 * r);
    cairo_line_to(cr, x - r, y + 0.75 * r);
    cairo_close_path(cr);
    break;
  default:
    cairo_move_to(cr, x, y - 1.2 * r);
    cairo_line_to(cr, x + r, y);
    cairo_line_to(cr, x, y + 1.2 * r);
    cairo_line_to(cr, x - r, y);
    cairo_close_path(cr);
    break;
  }
}

static void cross(cairo_t *cr, double x, double y, double r) {
  cairo_move_to(cr, x - r, y - r);
  cairo_line_to(cr, x + r, y + r);
  cairo_move_to(cr, x + r, y - r);
  cairo_line_to(cr, x - r, y + r);
}

/* Text with its left (align 0), centre (0.5) or right (1) end at x and its
 * baseline at y; returns its width. */
static double text(cairo_t *cr, double x, double y, double align, const char *s) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s, &e);
  cairo_move_to(cr, x - align * e.x_advance, y);
  ss_report_text(cr, s);
  return e.x_advance;
}

/* Frame, grid, ticks and labels of a panel; the panel title above it. */
static void axes(cairo_t *cr, const frame *f, ss_case_kind kind, const char *title,
                 const char *xlabel) {
  char buf[64];
  cairo_set_font_size(cr, 11.0);
  cairo_set_line_width(cr, 1.0);
  /* y grid and labels */
  for (double y = f->ymin; y <= f->ymax + 1e-9 * f->ystep; y += f->ystep) {
    const double py = Y(f, y);
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, f->x0, py);
    cairo_line_to(cr, f->x0 + f->w, py);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    snprintf(buf, sizeof buf, "%g", fabs(y) < 1e-9 * f->ystep ? 0.0 : y);
    text(cr, f->x0 - 6, py + 4, 1.0, buf);
  }
  /* x ticks: every integer, or a round step on wide ranges */
  const double span = f->xmax - f->xmin;
  const int step = span <= 26 ? 1 : (int)nice_step(span / 13.0);
  for (int k = (int)ceil(f->xmin); k <= (int)floor(f->xmax); k++) {
    if (k % step) continue;
    const double px = X(f, k);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_move_to(cr, px, f->y0 + f->h);
    cairo_line_to(cr, px, f->y0 + f->h + 4);
    cairo_stroke(cr);
    if (kind == SS_CASE_FACE)
      snprintf(buf, sizeof buf, "face");
    else
      snprintf(buf, sizeof buf, "%d", k);
    text(cr, px, f->y0 + f->h + 16, 0.5, buf);
  }
  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  cairo_rectangle(cr, f->x0, f->y0, f->w, f->h);
  cairo_stroke(cr);
  text(cr, f->x0 + f->w / 2, f->y0 + f->h + 32, 0.5, xlabel);
  cairo_set_font_size(cr, 13.0);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  text(cr, f->x0, f->y0 - 8, 0.0, title);
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Row pointers ordered by kind, k, then input order. */
static int cmp_kind_k(const void *a, const void *b) {
  const ss_report_row *x = *(const ss_report_row *const *)a;
  const ss_report_row *y = *(const ss_report_row *const *)b;
  if (x->r.kind != y->r.kind) return x->r.kind < y->r.kind ? -1 : 1;
  if (x->r.k != y->r.k) return x->r.k < y->r.k ? -1 : 1;
  return (x > y) - (x < y);
}

int ss_report_plot_x(const ss_result *r) {
  /* an edge point is stored with k = n + 2, the vertices of its link (the
   * bipyramid over n), as ss_store reads it back; its panel is the edge's */
  return r->kind == SS_CASE_EDGE_POINT ? r->k - 2 : r->k;
}

const char *ss_report_plot_xlabel(ss_case_kind kind) {
  return kind == SS_CASE_VERTEX ? "k (vertices of the link)"
         : kind == SS_CASE_FACE ? ""
         : kind == SS_CASE_EDGE_POINT
             ? "valence n of the edge (the link: the bipyramid over n)"
             : "valence n";
}

static double modulus(const ss_result *r, int i) {
  return i < r->neig ? hypot(r->eig[i].re, r->eig[i].im) : (double)NAN;
}

/* Horizontal place of index q (1..4) around k, in k units. */
static double offset(int q) {
  return ((double)q - 2.5) * 0.17;
}

/* The top panel: bars and markers of |lambda_q| per k. */
static void plot_lambda(cairo_t *cr, const frame *f, const ss_report_row **sel, size_t m,
                        double *v) {
  for (size_t i = 0, j; i < m; i = j) {
    const int k = ss_report_plot_x(&sel[i]->r);
    for (j = i; j < m && ss_report_plot_x(&sel[j]->r) == k; j++)
      ;
    for (int q = 1; q <= NLAMBDA; q++) {
      size_t c = 0;
      for (size_t t = i; t < j; t++) {
        const double x = modulus(&sel[t]->r, q);
        if (!isnan(x)) v[c++] = x;
      }
      if (!c) continue;
      qsort(v, c, sizeof *v, cmp_double);
      const double px = X(f, k + offset(q));
      set(cr, index_colour[q - 1], 0.9);
      cairo_set_line_width(cr, 1.5);
      cairo_move_to(cr, px, Y(f, v[0]));
      cairo_line_to(cr, px, Y(f, v[c - 1]));
      cairo_stroke(cr);
      double last = -1e300;
      for (size_t t = 0; t < c; t++) {
        const double py = Y(f, v[t]);
        if (fabs(py - last) < 1.0) continue;
        last = py;
        marker(cr, q - 1, px, py, 3.5);
      }
      set(cr, index_colour[q - 1], 0.75);
      cairo_fill_preserve(cr);
      cairo_set_source_rgba(cr, 0.1, 0.1, 0.1, 0.8);
      cairo_set_line_width(cr, 0.6);
      cairo_stroke(cr);
    }
  }
}

/* The bottom panel: the minimum scaled Jacobian of every case; pass, then
 * undecided, then fail, so that failures are drawn on top. */
static void plot_sj(cairo_t *cr, const frame *f, const ss_report_row **sel, size_t m) {
  if (f->ymin <= 0.0 && f->ymax >= 0.0) {
    const double dash[] = {5.0, 3.0};
    cairo_set_dash(cr, dash, 2, 0.0);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    cairo_set_line_width(cr, 1.2);
    cairo_move_to(cr, f->x0, Y(f, 0.0));
    cairo_line_to(cr, f->x0 + f->w, Y(f, 0.0));
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0.0);
  }
  static const ss_verdict_kind order[3] = {SS_PASS, SS_UNDECIDED, SS_FAIL};
  for (int pass = 0; pass < 3; pass++) {
    const rgb c = order[pass] == SS_PASS   ? pass_colour
                  : order[pass] == SS_FAIL ? fail_colour
                                           : undecided_colour;
    for (size_t i = 0, j; i < m; i = j) {
      const int k = ss_report_plot_x(&sel[i]->r);
      for (j = i; j < m && ss_report_plot_x(&sel[j]->r) == k; j++)
        ;
      for (size_t t = i; t < j; t++) {
        const ss_result *r = &sel[t]->r;
        if (ss_result_verdict(r) != order[pass]) continue;
        /* spread a k's cases evenly over +-0.3 (golden-ratio sequence) */
        const double u =
            j - i > 1 ? fmod((double)(t - i) * 0.6180339887498949, 1.0) : 0.5;
        const double px = X(f, k + 0.6 * (u - 0.5));
        set(cr, c, 0.85);
        if (isnan(r->min_sj)) {
          cairo_set_line_width(cr, 1.6);
          cross(cr, px, f->y0 + f->h - 6, 3.5);
          cairo_stroke(cr);
        } else {
          cairo_arc(cr, px, Y(f, r->min_sj), 3.2, 0.0, 2.0 * M_PI);
          cairo_fill(cr);
        }
      }
    }
  }
}

/* Legends right-aligned at (x, y); return their left end. */
static double legend_lambda(cairo_t *cr, double x, double y) {
  cairo_set_font_size(cr, 12.0);
  char s[16];
  for (int q = NLAMBDA; q >= 1; q--) {
    snprintf(s, sizeof s, "|λ%d|", q);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    x -= text(cr, x, y, 1.0, s) + 8;
    cairo_new_path(cr);
    marker(cr, q - 1, x, y - 4, 4.0);
    set(cr, index_colour[q - 1], 0.9);
    cairo_fill(cr);
    x -= 14;
  }
  return x;
}

static double legend_sj(cairo_t *cr, double x, double y) {
  cairo_set_font_size(cr, 12.0);
  static const char *const name[4] = {"no map", "undecided", "fail", "pass"};
  const rgb col[4] = {{0.3, 0.3, 0.3}, undecided_colour, fail_colour, pass_colour};
  for (int i = 0; i < 4; i++) {
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    x -= text(cr, x, y, 1.0, name[i]) + 8;
    cairo_new_path(cr);
    set(cr, col[i], 0.9);
    if (i == 0) {
      cairo_set_line_width(cr, 1.6);
      cross(cr, x, y - 4, 3.5);
      cairo_stroke(cr);
    } else {
      cairo_arc(cr, x, y - 4, 3.5, 0.0, 2.0 * M_PI);
      cairo_fill(cr);
    }
    x -= 14;
  }
  return x;
}

/* One column of panels in the box (x0, y0, w, h): the cases sel[0..m) of one
 * kind, ordered by k.  v: scratch for m values. */
static void column(cairo_t *cr, ss_case_kind kind, const ss_report_row **sel, size_t m,
                   double x0, double y0, double w, double h, double *v) {
  frame top, bot;
  const double left = 56, right = 14, tmargin = 28, bmargin = 44;
  top.x0 = bot.x0 = x0 + left;
  top.w = bot.w = w - left - right;
  top.h = bot.h = (h - 2 * (tmargin + bmargin)) / 2.0;
  top.y0 = y0 + tmargin;
  bot.y0 = top.y0 + top.h + bmargin + tmargin;
  top.xmin = bot.xmin = ss_report_plot_x(&sel[0]->r) - 0.6;
  top.xmax = bot.xmax = ss_report_plot_x(&sel[m - 1]->r) + 0.6;
  double lo = INFINITY, hi = -INFINITY, slo = 0.0, shi = 0.0;
  for (size_t i = 0; i < m; i++) {
    for (int q = 1; q <= NLAMBDA; q++) {
      const double x = modulus(&sel[i]->r, q);
      if (!isnan(x)) lo = fmin(lo, x), hi = fmax(hi, x);
    }
    if (!isnan(sel[i]->r.min_sj)) {
      slo = fmin(slo, sel[i]->r.min_sj);
      shi = fmax(shi, sel[i]->r.min_sj);
    }
  }
  nice_range(lo, hi, &top);
  /* the zero line inside the panel, with room below it for "no map" */
  nice_range(fmin(slo, -0.08 * shi), fmax(shi, -0.08 * slo), &bot);
  const char *kname = ss_case_name(kind);
  const char *xlabel = ss_report_plot_xlabel(kind);
  char title[96];
  snprintf(title, sizeof title, "%s: |λ1|..|λ4|", kname);
  axes(cr, &top, kind, title, xlabel);
  snprintf(title, sizeof title, "%s: minimum scaled Jacobian", kname);
  axes(cr, &bot, kind, title, xlabel);
  /* clip a marker's radius outside the frame: points on its edge stay whole */
  cairo_save(cr);
  cairo_rectangle(cr, top.x0 - 5, top.y0 - 5, top.w + 10, top.h + 10);
  cairo_clip(cr);
  plot_lambda(cr, &top, sel, m, v);
  cairo_restore(cr);
  cairo_save(cr);
  cairo_rectangle(cr, bot.x0 - 5, bot.y0 - 5, bot.w + 10, bot.h + 10);
  cairo_clip(cr);
  plot_sj(cr, &bot, sel, m);
  cairo_restore(cr);
}

ss_report_plot_opts ss_report_plot_defaults(void) {
  return (ss_report_plot_opts){0, 0, NULL};
}

/* Paint the figure of the selected rows (sel[0..m), all of one identity). */
static void paint(cairo_t *cr, const ss_report_row **sel, size_t m, const char *identity,
                  int W, int H, double *v) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         CAIRO_FONT_WEIGHT_NORMAL);
  char title[400];
  snprintf(title, sizeof title, "%s — %zu case%s", identity ? identity : "no scheme", m,
           m == 1 ? "" : "s");
  cairo_set_font_size(cr, 16.0);
  cairo_set_source_rgb(cr, 0.05, 0.05, 0.05);
  text(cr, W / 2.0, 26, 0.5, title);
  /* legends: the eigenvalue indices, then the verdicts of the Jacobian panels */
  legend_lambda(cr, legend_sj(cr, W - 24.0, 50.0) - 40.0, 50.0);
  if (m == 0) {
    cairo_set_font_size(cr, 14.0);
    text(cr, W / 2.0, H / 2.0, 0.5, "no cases selected");
    return;
  }
  /* columns: one per kind present, in the order vertex, edge, face, surface,
   * edge point */
  qsort(sel, m, sizeof *sel, cmp_kind_k);
  int ncol = 0;
  for (size_t i = 0; i < m; i++)
    ncol += i == 0 || sel[i]->r.kind != sel[i - 1]->r.kind;
  const double cw = (W - 20.0) / ncol, top = 62.0;
  int col = 0;
  for (size_t i = 0, j; i < m; i = j) {
    for (j = i; j < m && sel[j]->r.kind == sel[i]->r.kind; j++)
      ;
    column(cr, sel[i]->r.kind, sel + i, j - i, 10.0 + col * cw, top, cw, H - top, v);
    col++;
  }
}

ss_status ss_report_plot(const ss_report_row *rows, size_t n,
                         const ss_report_plot_opts *o, const char *path, size_t *plotted,
                         ss_error *err) {
  if (plotted) *plotted = 0;
  ss_pic_format fmt;
  if (ss_report_pic_format(path, &fmt))
    return ss_error_set(err, SS_EINPUT,
                        "--plot %s: unknown picture format (use .png, .svg or .pdf)",
                        path);
  const char *identity = o->identity ? o->identity : n ? rows[0].identity : NULL;
  const ss_report_row **sel = malloc((n ? n : 1) * sizeof *sel);
  double *v = malloc((n ? n : 1) * sizeof *v);
  if (!sel || !v) {
    free(sel);
    free(v);
    return ss_error_nomem(err, "plot");
  }
  size_t m = 0;
  int kinds = 0;
  for (size_t i = 0; i < n; i++)
    if (!strcmp(rows[i].identity, identity)) {
      sel[m++] = &rows[i];
      kinds |= 1 << (int)rows[i].r.kind;
    }
  int ncol = 0;
  for (int k = 0; k < SS_NCASEKINDS; k++)
    ncol += (kinds >> k) & 1;
  const int W = o->width ? o->width : 20 + 560 * (ncol ? ncol : 1);
  const int H = o->height ? o->height : 720;
  ss_status st = SS_OK;
  if (W < 200 || H < 200 || W > 10000 || H > 10000) {
    st = ss_error_set(err, SS_EINPUT, "--plot: picture size %dx%d out of range", W, H);
    goto done;
  }
  ss_report_canvas c;
  if ((st = ss_report_cairo_open(path, fmt, W, H, &c, err))) goto done;
  paint(c.cr, sel, m, identity, W, H, v);
  st = ss_report_cairo_close(&c, SS_OK, err);
  if (!st && plotted) *plotted = m;
done:
  free(sel);
  free(v);
  return st;
}
