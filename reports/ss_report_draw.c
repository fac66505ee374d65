/* ss_report_draw.c — pictures of a characteristic map (cairo) and its VTK
 * export.  What is drawn: ss_report_draw.h. */
#include "ss_report_draw.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

ss_report_draw_opts ss_report_draw_defaults(void) {
  ss_report_draw_opts o = {1200, 600, 30.0, 25.0, NULL};
  return o;
}

/* ---- colours ---- */

typedef struct {
  double r, g, b;
} rgb;

static const rgb col_cell = {0.55, 0.70, 0.90};   /* regular cells */
static const rgb col_ring = {0.20, 0.45, 0.85};   /* regular cells around p */
static const rgb col_bad = {0.90, 0.10, 0.10};    /* folded or wrongly oriented */
static const rgb col_doubt = {1.00, 0.55, 0.00};  /* undecided or flat */
static const rgb col_centre = {0.60, 0.45, 0.75}; /* a fold around p: it decides
                                                     nothing (ss_charmap.h) */

static int around_p(const ss_charmap *cm, size_t c) {
  const int nv = ss_cell_nverts(cm->ctype[c]);
  for (int j = 0; j < nv; j++)
    if (cm->corner[c * SS_MAXCELLVERTS + (size_t)j] == 0) return 1;
  return 0;
}

/* 1 when a ring cell is folded or of the minority sign, 2 when undecided or
 * flat, 3 when a cell around p is not of the ring's sign, else 0. */
static int cell_state(const ss_charmap *cm, const ss_regularity *r, size_t c) {
  const ss_jac_sign s = cm->jac[c].sign;
  int bad = s == SS_JAC_UNDECIDED || s == SS_JAC_DEGENERATE ? 2 : 0;
  if (s == SS_JAC_FOLDED ||
      (r->sign && (s == SS_JAC_POSITIVE || s == SS_JAC_NEGATIVE) && (int)s != r->sign))
    bad = 1;
  return bad && around_p(cm, c) ? 3 : bad;
}

static rgb cell_colour(const ss_charmap *cm, const ss_regularity *r, size_t c) {
  const int s = cell_state(cm, r, c);
  return s == 1            ? col_bad
         : s == 2          ? col_doubt
         : s == 3          ? col_centre
         : around_p(cm, c) ? col_ring
                           : col_cell;
}

/* ---- faces of the 3D cells ---- */

static const int hex_faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                    {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
static const int tet_faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

/* Face f of a cell of type t: its corner slots (returns how many, 0 if none). */
static int cell_face(ss_cell_type t, int f, int *slot) {
  if (t == SS_HEX && f < 6) {
    memcpy(slot, hex_faces[f], 4 * sizeof *slot);
    return 4;
  }
  if (t == SS_TET && f < 4) {
    memcpy(slot, tet_faces[f], 3 * sizeof *slot);
    return 3;
  }
  if (t == SS_OCT && f < 8) {
    slot[0] = f & 1 ? 3 : 0, slot[1] = f & 2 ? 4 : 1, slot[2] = f & 4 ? 5 : 2;
    return 3;
  }
  return 0;
}

/* One face to paint. */
typedef struct {
  size_t cell;         /* its cell */
  int n;               /* corners (3 or 4) */
  double sx[4], sy[4]; /* projected corners */
  double depth;        /* mean depth (larger = nearer the viewer) */
  double shade;        /* 0..1: how squarely it faces the viewer */
} face;

static int by_depth(const void *a, const void *b) {
  const double x = ((const face *)a)->depth, y = ((const face *)b)->depth;
  return (x > y) - (x < y); /* far first */
}

/* The viewing frame: right, up, toward the viewer. */
typedef struct {
  double r[3], u[3], f[3];
} view;

static view make_view(double az_deg, double el_deg) {
  const double az = az_deg * M_PI / 180.0, el = el_deg * M_PI / 180.0;
  view v = {{-sin(az), cos(az), 0.0},
            {-sin(el) * cos(az), -sin(el) * sin(az), cos(el)},
            {cos(el) * cos(az), cos(el) * sin(az), sin(el)}};
  return v;
}

static double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* A panel: the box it occupies and the map from data to it. */
typedef struct {
  double x0, y0, w, h;           /* box on the surface */
  double minx, maxx, miny, maxy; /* data bounds */
  double scale, cx, cy;          /* fitted transform */
} panel;

static void panel_fit(panel *p) {
  const double dx = fmax(p->maxx - p->minx, 1e-12), dy = fmax(p->maxy - p->miny, 1e-12);
  const double m = 0.08;
  p->scale = fmin(p->w * (1 - 2 * m) / dx, p->h * (1 - 2 * m) / dy);
  p->cx = 0.5 * (p->minx + p->maxx);
  p->cy = 0.5 * (p->miny + p->maxy);
}

static void panel_see(panel *p, double x, double y) {
  p->minx = fmin(p->minx, x), p->maxx = fmax(p->maxx, x);
  p->miny = fmin(p->miny, y), p->maxy = fmax(p->maxy, y);
}

static void to_surface(const panel *p, double x, double y, double *X, double *Y) {
  *X = p->x0 + 0.5 * p->w + p->scale * (x - p->cx);
  *Y = p->y0 + 0.5 * p->h - p->scale * (y - p->cy); /* y up */
}

static panel new_panel(double x0, double y0, double w, double h) {
  panel p = {x0, y0, w, h, INFINITY, -INFINITY, INFINITY, -INFINITY, 1.0, 0.0, 0.0};
  return p;
}

static void panel_title(cairo_t *cr, const panel *p, const char *t) {
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_set_font_size(cr, 13.0);
  cairo_move_to(cr, p->x0 + 10, p->y0 + 18);
  ss_report_text(cr, t);
}

static void mark_p(cairo_t *cr, const panel *p, double x, double y) {
  double X, Y;
  to_surface(p, x, y, &X, &Y);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_arc(cr, X, Y, 4.0, 0, 2 * M_PI);
  cairo_fill(cr);
}

static void panel_axes(cairo_t *cr, const panel *p, const char *xl, const char *yl);

/* ---- the 3D panel ---- */

static ss_status draw_3d(cairo_t *cr, const ss_charmap *cm, const ss_regularity *r,
                         const view *v, panel *p, ss_error *err) {
  size_t nf = 0;
  for (size_t c = 0; c < cm->ncells; c++)
    for (int f = 0, s[4]; cell_face(cm->ctype[c], f, s); f++)
      nf++;
  face *F = malloc((nf + 1) * sizeof *F);
  if (!F) return ss_error_nomem(err, "drawing");
  nf = 0;
  double dmin = INFINITY, dmax = -INFINITY;
  for (size_t c = 0; c < cm->ncells; c++) {
    int s[4];
    for (int f = 0, n; (n = cell_face(cm->ctype[c], f, s)) > 0; f++) {
      face *x = F + nf++;
      x->cell = c;
      x->n = n;
      x->depth = 0.0;
      double P[4][3];
      for (int j = 0; j < n; j++) {
        const double *q = cm->x + cm->corner[c * SS_MAXCELLVERTS + (size_t)s[j]] * 3;
        memcpy(P[j], q, sizeof P[j]);
        x->sx[j] = dot3(q, v->r);
        x->sy[j] = dot3(q, v->u);
        x->depth += dot3(q, v->f) / n;
        panel_see(p, x->sx[j], x->sy[j]);
      }
      /* normal from the diagonals (or two edges of a triangle) */
      double a[3], b[3], nrm[3];
      for (int i = 0; i < 3; i++) {
        a[i] = P[2][i] - P[0][i];
        b[i] = P[n == 4 ? 3 : 1][i] - P[n == 4 ? 1 : 0][i];
      }
      nrm[0] = a[1] * b[2] - a[2] * b[1];
      nrm[1] = a[2] * b[0] - a[0] * b[2];
      nrm[2] = a[0] * b[1] - a[1] * b[0];
      const double l = sqrt(dot3(nrm, nrm));
      x->shade = l > 0 ? fabs(dot3(nrm, v->f)) / l : 0.0;
      dmin = fmin(dmin, x->depth), dmax = fmax(dmax, x->depth);
    }
  }
  panel_fit(p);
  qsort(F, nf, sizeof *F, by_depth);
  const double span = dmax > dmin ? dmax - dmin : 1.0;
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (size_t i = 0; i < nf; i++) {
    const face *x = F + i;
    const double near = (x->depth - dmin) / span; /* 0 far .. 1 near */
    const rgb c = cell_colour(cm, r, x->cell);
    const int bad = cell_state(cm, r, x->cell) != 0;
    /* depth cue: far faces fade toward the background, shading by angle */
    const double fade = bad ? 0.15 : 0.55 * (1.0 - near);
    const double light = 0.65 + 0.35 * x->shade;
    cairo_new_path(cr);
    for (int j = 0; j < x->n; j++) {
      double X, Y;
      to_surface(p, x->sx[j], x->sy[j], &X, &Y);
      if (j == 0)
        cairo_move_to(cr, X, Y);
      else
        cairo_line_to(cr, X, Y);
    }
    cairo_close_path(cr);
    cairo_set_source_rgba(cr, (c.r * light) * (1 - fade) + fade,
                          (c.g * light) * (1 - fade) + fade,
                          (c.b * light) * (1 - fade) + fade, bad ? 0.85 : 0.45);
    cairo_fill_preserve(cr);
    const double g = 0.15 + 0.55 * (1.0 - near);
    cairo_set_source_rgba(cr, g, g, g + 0.05, 0.9);
    cairo_set_line_width(cr, bad ? 1.6 : 0.5 + 0.9 * near);
    cairo_stroke(cr);
  }
  free(F);
  mark_p(cr, p, 0.0, 0.0); /* psi(p), the frame's origin */
  return SS_OK;
}

/* ---- the cross-section z3 = 0 ---- */

static int by_angle_cmp(const void *a, const void *b) {
  const double x = ((const double *)a)[2], y = ((const double *)b)[2];
  return (x > y) - (x < y);
}

/* The polygon where the plane z3 = 0 cuts cell c (through its straight
 * edges): up to 12 points (x, y, angle), ordered by angle; returns the count. */
static int section(const ss_charmap *cm, size_t c, double pts[][3]) {
  const ss_cell_type t = cm->ctype[c];
  int n = 0;
  for (int e = 0; e < ss_cell_nedges(t); e++) {
    int a, b;
    ss_cell_edge(t, e, &a, &b);
    const double *A = cm->x + cm->corner[c * SS_MAXCELLVERTS + (size_t)a] * 3;
    const double *B = cm->x + cm->corner[c * SS_MAXCELLVERTS + (size_t)b] * 3;
    /* a point on the plane counts as above it (the plane z3 = +0), so a
     * face lying in the plane is drawn once, by the cell below it */
    if ((A[2] >= 0) == (B[2] >= 0)) continue;
    const double s = A[2] / (A[2] - B[2]);
    if (n < 12) {
      pts[n][0] = A[0] + s * (B[0] - A[0]);
      pts[n][1] = A[1] + s * (B[1] - A[1]);
      n++;
    }
  }
  if (n < 3) return 0;
  double mx = 0, my = 0;
  for (int i = 0; i < n; i++)
    mx += pts[i][0] / n, my += pts[i][1] / n;
  for (int i = 0; i < n; i++)
    pts[i][2] = atan2(pts[i][1] - my, pts[i][0] - mx);
  qsort(pts, (size_t)n, sizeof pts[0], by_angle_cmp);
  return n;
}

static void polygon(cairo_t *cr, const panel *p, int n, const double *xy, int stride,
                    rgb c, int bad) {
  cairo_new_path(cr);
  for (int j = 0; j < n; j++) {
    double X, Y;
    to_surface(p, xy[j * stride], xy[j * stride + 1], &X, &Y);
    if (j == 0)
      cairo_move_to(cr, X, Y);
    else
      cairo_line_to(cr, X, Y);
  }
  cairo_close_path(cr);
  cairo_set_source_rgba(cr, c.r, c.g, c.b, bad ? 0.85 : 0.5);
  cairo_fill_preserve(cr);
  cairo_set_source_rgba(cr, 0.15, 0.15, 0.2, 0.9);
  cairo_set_line_width(cr, bad ? 1.6 : 0.7);
  cairo_stroke(cr);
}

static void draw_section(cairo_t *cr, const ss_charmap *cm, const ss_regularity *r,
                         panel *p) {
  double pts[12][3];
  for (size_t c = 0; c < cm->ncells; c++) {
    int n = section(cm, c, pts);
    for (int i = 0; i < n; i++)
      panel_see(p, pts[i][0], pts[i][1]);
  }
  panel_see(p, 0.0, 0.0);
  panel_fit(p);
  for (int pass = 0; pass < 2; pass++) /* bad cells on top */
    for (size_t c = 0; c < cm->ncells; c++) {
      const int bad = cell_state(cm, r, c) != 0;
      if (bad != pass) continue;
      int n = section(cm, c, pts);
      if (n) polygon(cr, p, n, pts[0], 3, cell_colour(cm, r, c), bad);
    }
  panel_axes(cr, p, "z1", "z2"); /* on top: thin, and the numbers readable */
  mark_p(cr, p, 0.0, 0.0);       /* psi(p), the frame's origin */
}

/* ---- surfaces: the planar map ---- */

static void draw_flat(cairo_t *cr, const ss_charmap *cm, const ss_regularity *r,
                      panel *p) {
  for (size_t i = 0; i < cm->n; i++)
    panel_see(p, cm->x[2 * i], cm->x[2 * i + 1]);
  panel_fit(p);
  for (int pass = 0; pass < 2; pass++)
    for (size_t c = 0; c < cm->ncells; c++) {
      const int bad = cell_state(cm, r, c) != 0;
      if (bad != pass) continue;
      const int nv = ss_cell_nverts(cm->ctype[c]);
      double xy[8];
      for (int j = 0; j < nv && j < 4; j++) {
        const double *q = cm->x + cm->corner[c * SS_MAXCELLVERTS + (size_t)j] * 2;
        xy[2 * j] = q[0], xy[2 * j + 1] = q[1];
      }
      polygon(cr, p, nv < 4 ? nv : 4, xy, 2, cell_colour(cm, r, c), bad);
    }
  panel_axes(cr, p, "z1", "z2");
  mark_p(cr, p, 0.0, 0.0);
}

/* ---- the picture's frame (ss_report_draw.h) ---- */

void ss_report_draw_frame(const ss_charmap *cm, double *x) {
  const int d = cm->dim;
  double e[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, scale = 0.0;
  for (size_t i = 0; i < cm->n; i++)
    for (int k = 0; k < d; k++)
      scale = fmax(scale, fabs(cm->x[i * (size_t)d + (size_t)k] - cm->centre[k]));
  const double eps = 1e-9 * scale;
  int found = 0;
  for (size_t i = 0; i < cm->n && found < (d == 3 ? 2 : 1); i++) {
    double v[3] = {0, 0, 0};
    for (int k = 0; k < d; k++)
      v[k] = cm->x[i * (size_t)d + (size_t)k] - cm->centre[k];
    if (found == 1) { /* orthogonal to e1 */
      const double c = dot3(v, e[0]);
      for (int k = 0; k < 3; k++)
        v[k] -= c * e[0][k];
    }
    const double l = sqrt(dot3(v, v));
    if (!(l > eps)) continue;
    for (int k = 0; k < 3; k++)
      e[found][k] = v[k] / l;
    found++;
  }
  if (d == 2 && found == 1) { /* e2: e1 turned by +90 degrees */
    e[1][0] = -e[0][1], e[1][1] = e[0][0], e[1][2] = 0.0;
  } else if (d == 3 && found == 2) {
    e[2][0] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    e[2][1] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    e[2][2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
  } else { /* fewer directions than dimensions: the net as it is */
    memcpy(x, cm->x, cm->n * (size_t)d * sizeof *x);
    return;
  }
  for (size_t i = 0; i < cm->n; i++) {
    double v[3] = {0, 0, 0};
    for (int k = 0; k < d; k++)
      v[k] = cm->x[i * (size_t)d + (size_t)k] - cm->centre[k];
    /* rounding is snapped to 0: a face lying in the plane z3 = 0 then lies
     * in it exactly and the section draws it once (section()) */
    for (int k = 0; k < d; k++) {
      const double c = dot3(v, e[k]);
      x[i * (size_t)d + (size_t)k] = fabs(c) <= 1e-12 * scale ? 0.0 : c;
    }
  }
}

/* A tick step of about span / 5 from 1, 2, 5 x 10^k. */
static double tick_step(double span) {
  const double raw = span / 5.0, p = pow(10.0, floor(log10(raw))), f = raw / p;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * p;
}

/* Axes z1, z2 through the origin of a planar panel, with ticks and numbers. */
static void panel_axes(cairo_t *cr, const panel *p, const char *xl, const char *yl) {
  double X0, Y0, X1, Y1;
  const double lox = p->cx - 0.5 * p->w / p->scale, hix = p->cx + 0.5 * p->w / p->scale;
  const double loy = p->cy - 0.5 * p->h / p->scale, hiy = p->cy + 0.5 * p->h / p->scale;
  cairo_set_source_rgb(cr, 0.55, 0.55, 0.55);
  cairo_set_line_width(cr, 0.8);
  to_surface(p, lox, 0.0, &X0, &Y0);
  to_surface(p, hix, 0.0, &X1, &Y1);
  cairo_move_to(cr, X0 + 4, Y0);
  cairo_line_to(cr, X1 - 4, Y1);
  to_surface(p, 0.0, loy, &X0, &Y0);
  to_surface(p, 0.0, hiy, &X1, &Y1);
  cairo_move_to(cr, X0, Y0 - 4);
  cairo_line_to(cr, X1, Y1 + 30);
  cairo_stroke(cr);
  cairo_set_font_size(cr, 10.0);
  const double st = tick_step(fmax(hix - lox, hiy - loy) * 0.8);
  char t[32];
  for (int axis = 0; axis < 2; axis++) {
    const double lo = axis ? loy : lox, hi = axis ? hiy : hix;
    for (double v = ceil(lo / st) * st; v <= hi; v += st) {
      if (fabs(v) < 0.5 * st) continue;
      to_surface(p, axis ? 0.0 : v, axis ? v : 0.0, &X0, &Y0);
      if ((!axis && (X0 < p->x0 + 20 || X0 > p->x0 + p->w - 20)) ||
          (axis && (Y0 < p->y0 + 40 || Y0 > p->y0 + p->h - 10)))
        continue;
      cairo_move_to(cr, X0 - (axis ? 3 : 0), Y0 - (axis ? 0 : 3));
      cairo_line_to(cr, X0 + (axis ? 3 : 0), Y0 + (axis ? 0 : 3));
      cairo_stroke(cr);
      snprintf(t, sizeof t, "%g", v);
      cairo_move_to(cr, X0 + (axis ? 5 : -6), Y0 + (axis ? 3 : 13));
      ss_report_text(cr, t);
    }
  }
  to_surface(p, hix, 0.0, &X1, &Y1);
  cairo_set_font_size(cr, 12.0);
  cairo_move_to(cr, X1 - 22, Y1 - 6);
  ss_report_text(cr, xl);
  to_surface(p, 0.0, hiy, &X1, &Y1);
  cairo_move_to(cr, X1 + 6, Y1 + 42);
  ss_report_text(cr, yl);
}

/* The frame's axes as a triad in a corner of the 3D panel. */
static void axis_triad(cairo_t *cr, const panel *p, const view *v) {
  const double ox = p->x0 + 40, oy = p->y0 + p->h - 40, L = 26.0;
  const char *name[3] = {"z1", "z2", "z3"};
  cairo_set_line_width(cr, 1.2);
  cairo_set_font_size(cr, 11.0);
  for (int k = 0; k < 3; k++) {
    double e[3] = {0, 0, 0};
    e[k] = 1.0;
    const double X = ox + L * dot3(e, v->r), Y = oy - L * dot3(e, v->u);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    cairo_move_to(cr, ox, oy);
    cairo_line_to(cr, X, Y);
    cairo_stroke(cr);
    cairo_move_to(cr, X + 3, Y + 4);
    ss_report_text(cr, name[k]);
  }
}

/* The colour legend, one swatch per kind of cell, along the bottom of the
 * drawing area at height y. */
static void legend(cairo_t *cr, double y, double w) {
  static const struct {
    const rgb *c;
    const char *what;
  } key[] = {{&col_cell, "regular cell"},
             {&col_ring, "regular, one-ring"},
             {&col_bad, "folded or of the minority sign"},
             {&col_doubt, "undecided or flat"},
             {&col_centre, "fold at p (decides nothing)"}};
  cairo_set_font_size(cr, 11.0);
  double x = 12.0;
  for (size_t i = 0; i < sizeof key / sizeof key[0]; i++) {
    cairo_rectangle(cr, x, y - 9, 14, 10);
    cairo_set_source_rgb(cr, key[i].c->r, key[i].c->g, key[i].c->b);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    cairo_set_line_width(cr, 0.6);
    cairo_stroke(cr);
    cairo_move_to(cr, x + 19, y);
    ss_report_text(cr, key[i].what);
    cairo_text_extents_t te;
    cairo_text_extents(cr, key[i].what, &te);
    x += 19 + te.x_advance + 18;
    if (x > w - 60) break;
  }
}

/* ---- the picture ---- */

static void caption(cairo_t *cr, const ss_charmap *cm, const ss_regularity *r,
                    const ss_report_draw_opts *o, double y, double w) {
  char line[3][400];
  snprintf(line[0], sizeof line[0], "%s", o->caption ? o->caption : "");
  int n = snprintf(line[1], sizeof line[1], "lambda1..%d =", cm->dim);
  for (int i = 0; i < cm->dim && n > 0 && (size_t)n < sizeof line[1]; i++)
    n += snprintf(line[1] + n, sizeof line[1] - (size_t)n, " %.6f", cm->lambda[i]);
  snprintf(line[2], sizeof line[2], "regularity: %s, min scaled Jacobian %.4f%s%.200s",
           ss_verdict_name(r->verdict.verdict), r->min_scaled_jacobian,
           r->verdict.reason[0] ? ": " : "", r->verdict.reason);
  cairo_set_font_size(cr, 14.0);
  for (int i = 0; i < 3; i++) {
    if (i == 2 && r->verdict.verdict != SS_PASS)
      cairo_set_source_rgb(cr, 0.75, 0.0, 0.0);
    else
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_move_to(cr, 12, y + 18 + 18 * i);
    ss_report_text(cr, line[i]);
  }
  (void)w;
}

static ss_status paint(cairo_t *cr, const ss_charmap *cm, const ss_regularity *r,
                       const ss_report_draw_opts *o, ss_error *err) {
  const double W = o->width, H = o->height, cap = (o->caption ? 70.0 : 0.0) + 24.0;
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         CAIRO_FONT_WEIGHT_NORMAL);
  ss_status st = SS_OK;
  if (cm->dim == 3) {
    view v = make_view(o->azimuth, o->elevation);
    panel a = new_panel(0, 0, W / 2, H - cap), b = new_panel(W / 2, 0, W / 2, H - cap);
    if ((st = draw_3d(cr, cm, r, &v, &a, err))) return st;
    draw_section(cr, cm, r, &b);
    axis_triad(cr, &a, &v);
    char t[120];
    snprintf(t, sizeof t, "two-ring, %zu cells (view %.0f, %.0f)", cm->ncells, o->azimuth,
             o->elevation);
    panel_title(cr, &a, t);
    panel_title(cr, &b, "cross-section z3 = 0 through psi(p)");
    cairo_set_source_rgb(cr, 0.8, 0.8, 0.8);
    cairo_set_line_width(cr, 1.0);
    cairo_move_to(cr, W / 2, 10);
    cairo_line_to(cr, W / 2, H - cap);
    cairo_stroke(cr);
  } else {
    panel a = new_panel(0, 0, W, H - cap);
    draw_flat(cr, cm, r, &a);
    char t[120];
    snprintf(t, sizeof t, "planar characteristic map, %zu cells", cm->ncells);
    panel_title(cr, &a, t);
  }
  legend(cr, H - cap + 16, W);
  if (o->caption) caption(cr, cm, r, o, H - cap + 24, W);
  return st;
}

/* ---- VTK ---- */

static const int oct_pyramids[2][5] = {{1, 2, 4, 5, 0}, {1, 5, 4, 2, 3}};

/* VTK cell type and index count of a cell (octahedra: two pyramids). */
static int vtk_code(ss_cell_type t) {
  return t == SS_HEX        ? 12
         : t == SS_TET      ? 10
         : t == SS_QUAD     ? 9
         : t == SS_TRIANGLE ? 5
                            : 14; /* octahedron: two pyramids */
}

static void vtk_cell(FILE *f, ss_cell_type t, const size_t *v, size_t off) {
  if (t == SS_OCT) {
    for (int q = 0; q < 2; q++) {
      fprintf(f, "5");
      for (int j = 0; j < 5; j++)
        fprintf(f, " %zu", off + v[oct_pyramids[q][j]]);
      fputc('\n', f);
    }
    return;
  }
  fprintf(f, "%d", ss_cell_nverts(t));
  for (int j = 0; j < ss_cell_nverts(t); j++)
    fprintf(f, " %zu", off + v[j]);
  fputc('\n', f);
}

/* A cell's sign in the map's orientation: 1 of it, -1 inverted against it;
 * folded 0, undecided 2, degenerate 3 as ss_jac. */
static int oriented_sign(ss_jac_sign s, int sign) {
  return s == SS_JAC_POSITIVE || s == SS_JAC_NEGATIVE ? (int)s * sign : (int)s;
}

static ss_status write_vtk(const ss_charmap *cm, const ss_regularity *r, const char *path,
                           ss_error *err) {
  ss_outfile *out;
  ss_status st = ss_outfile_open(path, &out, err);
  if (st) return st;
  FILE *f = ss_outfile_file(out);
  /* the orientation analyze gives the map (+1 when it has none) */
  const int sign = r->sign < 0 ? -1 : 1;
  const size_t nring = cm->ring_x ? cm->ring_ncells : 0,
               npts = cm->n + (nring ? cm->ring_n : 0);
  size_t ncell = 0, nidx = 0;
  for (size_t c = 0; c < cm->ncells + nring; c++) {
    const ss_cell_type t = c < cm->ncells ? cm->ctype[c] : cm->ring_ctype[c - cm->ncells];
    ncell += t == SS_OCT ? 2 : 1;
    nidx += t == SS_OCT ? 12 : 1 + (size_t)ss_cell_nverts(t);
  }
  fprintf(f,
          "# vtk DataFile Version 3.0\nsubspectra characteristic map\nASCII\n"
          "DATASET UNSTRUCTURED_GRID\nFIELD FieldData 3\n"
          "min_scaled_jacobian 1 1 double\n%.17g\norientation 1 1 int\n%d\n"
          "ring_level 1 1 int\n%d\nPOINTS %zu double\n",
          isfinite(r->min_scaled_jacobian) ? r->min_scaled_jacobian : 0.0, r->sign,
          r->ring_level, npts);
  for (size_t i = 0; i < npts; i++) {
    const double *x = i < cm->n ? cm->x + i * (size_t)cm->dim
                                : cm->ring_x + (i - cm->n) * (size_t)cm->dim;
    fprintf(f, "%.17g %.17g %.17g\n", x[0], x[1], cm->dim == 3 ? x[2] : 0.0);
  }
  fprintf(f, "CELLS %zu %zu\n", ncell, nidx);
  for (size_t c = 0; c < cm->ncells; c++)
    vtk_cell(f, cm->ctype[c], cm->corner + c * SS_MAXCELLVERTS, 0);
  for (size_t c = 0; c < nring; c++)
    vtk_cell(f, cm->ring_ctype[c], cm->ring_corner + c * SS_MAXCELLVERTS, cm->n);
  fprintf(f, "CELL_TYPES %zu\n", ncell);
  for (size_t c = 0; c < cm->ncells + nring; c++) {
    const ss_cell_type t = c < cm->ncells ? cm->ctype[c] : cm->ring_ctype[c - cm->ncells];
    fprintf(f, t == SS_OCT ? "%d\n%d\n" : "%d\n", vtk_code(t), vtk_code(t));
  }
  fprintf(f, "CELL_DATA %zu\nSCALARS jacobian_sign int 1\nLOOKUP_TABLE default\n", ncell);
  for (size_t c = 0; c < cm->ncells + nring; c++) {
    const int two = c < cm->ncells;
    const ss_jac_result *j = two ? cm->jac + c : cm->ring_jac + (c - cm->ncells);
    const ss_cell_type t = two ? cm->ctype[c] : cm->ring_ctype[c - cm->ncells];
    for (int q = 0; q < (t == SS_OCT ? 2 : 1); q++)
      fprintf(f, "%d\n", oriented_sign(j->sign, sign));
  }
  fprintf(f, "SCALARS min_scaled_jacobian double 1\nLOOKUP_TABLE default\n");
  for (size_t c = 0; c < cm->ncells + nring; c++) {
    const int two = c < cm->ncells;
    const ss_jac_result *j = two ? cm->jac + c : cm->ring_jac + (c - cm->ncells);
    const ss_cell_type t = two ? cm->ctype[c] : cm->ring_ctype[c - cm->ncells];
    const double v = ss_charmap_cell_measure(j, sign);
    for (int q = 0; q < (t == SS_OCT ? 2 : 1); q++)
      fprintf(f, "%.17g\n", isfinite(v) ? v : 0.0); /* degenerate: no margin */
  }
  fprintf(f, "SCALARS part int 1\nLOOKUP_TABLE default\n");
  for (size_t c = 0; c < cm->ncells + nring; c++) {
    const int two = c < cm->ncells;
    const ss_cell_type t = two ? cm->ctype[c] : cm->ring_ctype[c - cm->ncells];
    const int part = two ? (around_p(cm, c) ? 0 : 1) : 2;
    for (int q = 0; q < (t == SS_OCT ? 2 : 1); q++)
      fprintf(f, "%d\n", part);
  }
  fprintf(f, "POINT_DATA %zu\nSCALARS one_ring int 1\nLOOKUP_TABLE default\n", npts);
  for (size_t i = 0; i < npts; i++)
    fprintf(f, "%d\n", i < cm->n1);
  return ss_outfile_commit(out, err); /* checks every write above */
}

/* ---- dispatch ---- */

int ss_report_has_ext(const char *path, const char *ext) {
  const size_t n = strlen(path), m = strlen(ext);
  if (n < m) return 0;
  for (size_t i = 0; i < m; i++)
    if (tolower((unsigned char)path[n - m + i]) != ext[i]) return 0;
  return 1;
}

/* Append n bytes to b; -1 if it cannot grow. */
static int bytes_add(ss_report_bytes *b, const void *p, size_t n) {
  if (b->n + n > b->cap) {
    size_t nc = b->cap ? b->cap : 1 << 16;
    while (nc < b->n + n)
      nc *= 2;
    char *ns = realloc(b->s, nc);
    if (!ns) return -1;
    b->s = ns;
    b->cap = nc;
  }
  if (n) memcpy(b->s + b->n, p, n);
  b->n += n;
  return 0;
}

/* the key under which a context knows its canvas (its address is the key) */
static const cairo_user_data_key_t canvas_key = {0};

void ss_report_text(cairo_t *cr, const char *s) {
  ss_report_canvas *c = cairo_get_user_data(cr, &canvas_key);
  if (!c || c->fmt != SS_PIC_SVG || !cairo_has_current_point(cr)) {
    cairo_show_text(cr, s);
    return;
  }
  double x, y, r = 0, g = 0, b = 0, a = 1;
  cairo_get_current_point(cr, &x, &y);
  cairo_user_to_device(cr, &x, &y);
  cairo_matrix_t fm;
  cairo_get_font_matrix(cr, &fm);
  cairo_pattern_get_rgba(cairo_get_source(cr), &r, &g, &b, &a);
  char head[256];
  int n = snprintf(head, sizeof head,
                   "<text x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" "
                   "font-size=\"%.2f\" fill=\"rgb(%d,%d,%d)\" fill-opacity=\"%.3g\">",
                   x, y, fm.xx, (int)lround(255 * r), (int)lround(255 * g),
                   (int)lround(255 * b), a);
  int bad = bytes_add(&c->text, head, (size_t)n);
  for (const char *p = s; *p; p++) {
    const char *e = *p == '&'   ? "&amp;"
                    : *p == '<' ? "&lt;"
                    : *p == '>' ? "&gt;"
                    : *p == '"' ? "&quot;"
                                : NULL;
    bad |= e ? bytes_add(&c->text, e, strlen(e)) : bytes_add(&c->text, p, 1);
  }
  bad |= bytes_add(&c->text, "</text>\n", 8);
  if (bad) c->nomem = 1;
  /* the current point moves on as after cairo_show_text */
  cairo_text_extents_t te;
  cairo_text_extents(cr, s, &te);
  cairo_rel_move_to(cr, te.x_advance, te.y_advance);
}

/* cairo's stream writer: into the canvas's file (SVG: its buffer), the first
 * errno kept. */
static cairo_status_t canvas_write(void *closure, const unsigned char *data,
                                   unsigned int len) {
  ss_report_canvas *c = closure;
  if (c->fmt == SS_PIC_SVG) {
    if (bytes_add(&c->svg, data, len)) {
      c->nomem = 1;
      return CAIRO_STATUS_NO_MEMORY;
    }
    return CAIRO_STATUS_SUCCESS;
  }
  FILE *f = ss_outfile_file(c->out);
  if (len && fwrite(data, 1, len, f) != len) {
    if (!c->werrno) c->werrno = errno ? errno : EIO;
    return CAIRO_STATUS_WRITE_ERROR;
  }
  return CAIRO_STATUS_SUCCESS;
}

int ss_report_pic_format(const char *path, ss_pic_format *fmt) {
  if (ss_report_has_ext(path, ".png"))
    *fmt = SS_PIC_PNG;
  else if (ss_report_has_ext(path, ".svg"))
    *fmt = SS_PIC_SVG;
  else if (ss_report_has_ext(path, ".pdf"))
    *fmt = SS_PIC_PDF;
  else
    return -1;
  return 0;
}

ss_status ss_report_cairo_open(const char *path, ss_pic_format fmt, int width, int height,
                               ss_report_canvas *c, ss_error *err) {
  *c = (ss_report_canvas){NULL, NULL, NULL, fmt, 0, 0, {NULL, 0, 0}, {NULL, 0, 0}};
  ss_status st = ss_outfile_open(path, &c->out, err);
  if (st) return st;
  c->s = fmt == SS_PIC_PNG
             ? cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height)
         : fmt == SS_PIC_SVG
             ? cairo_svg_surface_create_for_stream(canvas_write, c, width, height)
             : cairo_pdf_surface_create_for_stream(canvas_write, c, width, height);
  if (cairo_surface_status(c->s) != CAIRO_STATUS_SUCCESS) {
    st = ss_error_set(err, SS_EIO, "%s: %s", path,
                      cairo_status_to_string(cairo_surface_status(c->s)));
    cairo_surface_destroy(c->s);
    ss_outfile_abort(c->out);
    *c = (ss_report_canvas){NULL, NULL, NULL, fmt, 0, 0, {NULL, 0, 0}, {NULL, 0, 0}};
    return st;
  }
  c->cr = cairo_create(c->s);
  cairo_set_user_data(c->cr, &canvas_key, c, NULL);
  return SS_OK;
}

ss_status ss_report_draw(const ss_charmap *cm, const ss_regularity *r,
                         const ss_report_draw_opts *o, const char *path, ss_error *err) {
  if (o->width < 100 || o->height < 100 || o->width > 10000 || o->height > 10000)
    return ss_error_set(err, SS_EINPUT, "draw: picture size %dx%d out of range", o->width,
                        o->height);
  if (cm->dim != 2 && cm->dim != 3)
    return ss_error_set(err, SS_EINPUT, "draw: a map of dimension %d", cm->dim);
  if (ss_report_has_ext(path, ".vtk")) return write_vtk(cm, r, path, err);
  ss_pic_format fmt;
  if (ss_report_pic_format(path, &fmt))
    return ss_error_set(err, SS_EINPUT,
                        "%s: unknown picture format (use .png, .svg, .pdf or .vtk)",
                        path);
  /* the picture's own frame (see the header): a copy of the net */
  ss_charmap f = *cm;
  double *x = malloc((cm->n * (size_t)cm->dim + 1) * sizeof *x);
  if (!x) return ss_error_nomem(err, "drawing");
  ss_report_draw_frame(cm, x);
  f.x = x;
  memset(f.centre, 0, sizeof f.centre);
  ss_report_canvas c;
  ss_status st = ss_report_cairo_open(path, fmt, o->width, o->height, &c, err);
  if (!st) {
    st = paint(c.cr, &f, r, o, err);
    st = ss_report_cairo_close(&c, st, err);
  }
  free(x);
  return st;
}

ss_status ss_report_cairo_close(ss_report_canvas *c, ss_status st, ss_error *err) {
  const char *path = ss_outfile_path(c->out);
  if (!st && cairo_status(c->cr) != CAIRO_STATUS_SUCCESS)
    st = ss_error_set(err, SS_EIO, "%s: drawing failed: %s", path,
                      cairo_status_to_string(cairo_status(c->cr)));
  cairo_destroy(c->cr);
  cairo_status_t cs = CAIRO_STATUS_SUCCESS;
  if (!st && c->fmt == SS_PIC_PNG)
    cs = cairo_surface_write_to_png_stream(c->s, canvas_write, c);
  /* an SVG or PDF surface writes its end here */
  cairo_surface_finish(c->s);
  if (cs == CAIRO_STATUS_SUCCESS) cs = cairo_surface_status(c->s);
  cairo_surface_destroy(c->s);
  if (!st && c->nomem) st = ss_error_nomem(err, "picture");
  if (!st && cs == CAIRO_STATUS_SUCCESS && c->fmt == SS_PIC_SVG) {
    /* the document with the text before its end tag */
    const char *end = NULL;
    for (size_t i = c->svg.n; i-- > 0 && !end;)
      if (c->svg.n - i >= 6 && !memcmp(c->svg.s + i, "</svg>", 6)) end = c->svg.s + i;
    const size_t head = end ? (size_t)(end - c->svg.s) : c->svg.n;
    FILE *f = ss_outfile_file(c->out);
    if (fwrite(c->svg.s, 1, head, f) != head ||
        fwrite(c->text.s ? c->text.s : "", 1, c->text.n, f) != c->text.n ||
        fwrite(c->svg.s + head, 1, c->svg.n - head, f) != c->svg.n - head)
      c->werrno = errno ? errno : EIO;
  }
  free(c->svg.s);
  free(c->text.s);
  if (!st && c->werrno)
    st = ss_error_set(err, SS_EIO, "%s: cannot write: %s", path, strerror(c->werrno));
  else if (!st && cs != CAIRO_STATUS_SUCCESS)
    st = ss_error_set(err, SS_EIO, "%s: cannot write: %s", path,
                      cairo_status_to_string(cs));
  if (st)
    ss_outfile_abort(c->out);
  else
    st = ss_outfile_commit(c->out, err);
  *c = (ss_report_canvas){NULL, NULL, NULL, SS_PIC_PNG, 0, 0, {NULL, 0, 0}, {NULL, 0, 0}};
  return st;
}
